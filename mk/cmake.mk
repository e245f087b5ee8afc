# mk/cmake.mk -- the CMake build (CMakeLists.txt, cmake/) checked against this Makefile.
#
#   make cmake-check       host and Cortex-M4F libraries built by CMake, a consumer project
#                          through add_subdirectory and through the installed package
#                          (find_package), compile flags compared with CFLAGS / ARM_CFLAGS,
#                          the Cortex-M4F objects compared with the Makefile's
#                          (tools/gates/cmake_check.sh)
#   make print-cflags      the host library's compile flags (CFLAGS)
#   make print-arm-cflags  the Cortex-M4F library's compile flags (ARM_CFLAGS)

.PHONY: cmake-check print-cflags print-arm-cflags

## cmake-check: the CMake build (host, Cortex-M4F, add_subdirectory, find_package) against the Makefile's flags
cmake-check: deps $(BUILD)/target/libqfoc.a
	@MAKE_CFLAGS="$(CFLAGS)" MAKE_ARM_CFLAGS="$(ARM_CFLAGS)" MAKE_ARM_LIB=$(BUILD)/target/libqfoc.a \
	    CMAKE_OUT=$(BUILD)/cmake \
	    sh tools/gates/cmake_check.sh

print-cflags:
	@echo $(CFLAGS)

print-arm-cflags:
	@echo $(ARM_CFLAGS)

# make clean also removes the CMake build trees
clean: cmake-clean
.PHONY: cmake-clean
cmake-clean:
	rm -rf $(BUILD)/cmake-host $(BUILD)/cmake-consumer $(BUILD)/cmake-stage $(BUILD)/cmake-consumer-pkg \
	    $(BUILD)/cmake-arm
