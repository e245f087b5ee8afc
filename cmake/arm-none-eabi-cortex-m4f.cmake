# cmake/arm-none-eabi-cortex-m4f.cmake -- CMake toolchain file for the Cortex-M4F build
# of qfoc with the GNU Arm Embedded toolchain (Debian: gcc-arm-none-eabi).
#
#   cmake -S . -B build/cmake-arm -DCMAKE_TOOLCHAIN_FILE=cmake/arm-none-eabi-cortex-m4f.cmake
#
# The compile flags of the library equal the Makefile's ARM_CFLAGS: the machine and
# code-generation flags below (CMAKE_C_FLAGS), the warning set of CMakeLists.txt, and -O2
# (QFOC_DEFAULT_OPT_FLAGS) when no CMAKE_BUILD_TYPE is given.  make cmake-check compares
# them.
set(CMAKE_SYSTEM_NAME Generic)
set(CMAKE_SYSTEM_PROCESSOR arm)

set(CMAKE_C_COMPILER arm-none-eabi-gcc)
set(CMAKE_AR arm-none-eabi-ar CACHE FILEPATH "archiver")
set(CMAKE_RANLIB arm-none-eabi-ranlib CACHE FILEPATH "archive indexer")
# no start-up code or linker script here: the compiler check builds a static library
set(CMAKE_TRY_COMPILE_TARGET_TYPE STATIC_LIBRARY)

# Cortex-M4 with its single-precision FPU, hard-float ABI; one section per function and
# object (a firmware links with --gc-sections); freestanding; per-function stack use.
set(CMAKE_C_FLAGS_INIT
    "-mcpu=cortex-m4 -mthumb -mfloat-abi=hard -mfpu=fpv4-sp-d16 -ffunction-sections -fdata-sections -ffreestanding -fstack-usage")
set(QFOC_DEFAULT_OPT_FLAGS -O2)

set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)
