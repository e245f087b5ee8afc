#!/bin/sh
# tools/gates/cmake_check.sh -- the CMake build of qfoc checked against the Makefile (make cmake-check).
#
# Environment (set by mk/cmake.mk): MAKE_CFLAGS, MAKE_ARM_CFLAGS (the Makefile's CFLAGS and
# ARM_CFLAGS), MAKE_ARM_LIB (the Makefile's Cortex-M4F libqfoc.a, optional), CMAKE_OUT (the
# build directory's prefix, default build/cmake).
#
#   1. the host library configured and built by CMake (CMAKE_OUT-host); the consumer project
#      tests/cmake/consumer built through add_subdirectory and run; the host compile flags
#      equal the Makefile's CFLAGS;
#   2. cmake --install to a staging prefix (CMAKE_OUT-stage); the consumer built through
#      find_package(qfoc 0.2 CONFIG REQUIRED) against that prefix alone and run;
#   3. the Cortex-M4F library configured with cmake/arm-none-eabi-cortex-m4f.cmake and built;
#      its compile flags (compile_commands.json) equal the Makefile's ARM_CFLAGS, and each of
#      its objects has the same sections, byte for byte, as the Makefile's build.
# Exit 1 on the first failure.
set -eu
TOP=$(cd "$(dirname "$0")/../.." && pwd)
cd "$TOP"
PY=/usr/bin/python3
[ -x "$PY" ] || PY=python3
OUT=${CMAKE_OUT:-build/cmake}
MAKE_CFLAGS=${MAKE_CFLAGS:?MAKE_CFLAGS not set (run make cmake-check)}
MAKE_ARM_CFLAGS=${MAKE_ARM_CFLAGS:?MAKE_ARM_CFLAGS not set (run make cmake-check)}
# the flags come from the project files alone, not from the caller's environment
unset CFLAGS CC LDFLAGS CMAKE_PREFIX_PATH CMAKE_GENERATOR CMAKE_BUILD_TYPE 2>/dev/null || true
JOBS=2
version=$(sed -n 's/^#define QFOC_VERSION_STRING "\(.*\)".*/\1/p' include/qfoc/version.h)
start=$(date +%s)

run() {  # run LOG COMMAND...: the command's output in LOG, shown when it fails
    log=$1
    shift
    if ! "$@" > "$log" 2>&1; then
        cat "$log"
        echo "cmake-check: failed: $*"
        exit 1
    fi
}

rm -rf "$OUT-host" "$OUT-consumer" "$OUT-stage" "$OUT-consumer-pkg" "$OUT-arm"
mkdir -p "$OUT-host"

# 1. host library, and the consumer through add_subdirectory
run "$OUT-host/configure.log" cmake -S . -B "$OUT-host" -DCMAKE_EXPORT_COMPILE_COMMANDS=ON
run "$OUT-host/build.log" cmake --build "$OUT-host" -j "$JOBS"
[ -f "$OUT-host/libqfoc.a" ] || { echo "cmake-check: no $OUT-host/libqfoc.a"; exit 1; }
"$PY" tools/gates/cmake_flags.py "$OUT-host/compile_commands.json" . "host (gcc)" "$MAKE_CFLAGS"
mkdir -p "$OUT-consumer"
run "$OUT-consumer/configure.log" cmake -S tests/cmake/consumer -B "$OUT-consumer" \
    -DQFOC_CONSUMER_MODE=subdirectory -DQFOC_SOURCE_DIR="$TOP"
run "$OUT-consumer/build.log" cmake --build "$OUT-consumer" -j "$JOBS"
printf 'cmake-check: add_subdirectory: '
"$OUT-consumer/consumer"

# 2. installed package, and the consumer through find_package
run "$OUT-host/install.log" cmake --install "$OUT-host" --prefix "$TOP/$OUT-stage"
for f in include/qfoc/version.h include/qfoc/drive.h lib/libqfoc.a lib/cmake/qfoc/qfocConfig.cmake \
         lib/cmake/qfoc/qfocConfigVersion.cmake lib/cmake/qfoc/qfocTargets.cmake; do
    [ -f "$OUT-stage/$f" ] || { echo "cmake-check: the install lacks $f"; exit 1; }
done
mkdir -p "$OUT-consumer-pkg"
run "$OUT-consumer-pkg/configure.log" cmake -S tests/cmake/consumer -B "$OUT-consumer-pkg" \
    -DQFOC_CONSUMER_MODE=package -DQFOC_SOURCE_DIR="$TOP" -DCMAKE_PREFIX_PATH="$TOP/$OUT-stage" \
    -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF -DCMAKE_FIND_USE_SYSTEM_PACKAGE_REGISTRY=OFF
grep -q "qfoc $version found in $TOP/$OUT-stage/lib/cmake/qfoc" "$OUT-consumer-pkg/configure.log" || {
    cat "$OUT-consumer-pkg/configure.log"; echo "cmake-check: find_package did not take the staged qfoc $version"; exit 1; }
run "$OUT-consumer-pkg/build.log" cmake --build "$OUT-consumer-pkg" -j "$JOBS"
printf 'cmake-check: find_package(qfoc 0.2 CONFIG) from %s: ' "$OUT-stage"
"$OUT-consumer-pkg/consumer"
# a request for another minor release must be refused while the major number is 0
mkdir -p "$OUT-consumer-pkg/v"
cat > "$OUT-consumer-pkg/v/CMakeLists.txt" <<'CMK'
cmake_minimum_required(VERSION 3.16)
project(qfoc_version_probe LANGUAGES NONE)
find_package(qfoc 0.1 CONFIG QUIET)
if(qfoc_FOUND)
  message(FATAL_ERROR "find_package(qfoc 0.1) accepted qfoc ${qfoc_VERSION}")
endif()
CMK
run "$OUT-consumer-pkg/v/configure.log" cmake -S "$OUT-consumer-pkg/v" -B "$OUT-consumer-pkg/v/build" \
    -DCMAKE_PREFIX_PATH="$TOP/$OUT-stage"
echo "cmake-check: find_package(qfoc 0.1) refuses qfoc $version (same minor version while the major is 0)"

# 3. the Cortex-M4F library with the toolchain file, flags against ARM_CFLAGS
mkdir -p "$OUT-arm"
run "$OUT-arm/configure.log" cmake -S . -B "$OUT-arm" -DCMAKE_EXPORT_COMPILE_COMMANDS=ON \
    -DCMAKE_TOOLCHAIN_FILE="$TOP/cmake/arm-none-eabi-cortex-m4f.cmake"
run "$OUT-arm/build.log" cmake --build "$OUT-arm" -j "$JOBS"
[ -f "$OUT-arm/libqfoc.a" ] || { echo "cmake-check: no $OUT-arm/libqfoc.a"; exit 1; }
arm-none-eabi-readelf -A "$OUT-arm/libqfoc.a" | grep -q 'Tag_ABI_VFP_args: VFP registers' || {
    echo "cmake-check: $OUT-arm/libqfoc.a is not built for the hard-float ABI"; exit 1; }
"$PY" tools/gates/cmake_flags.py "$OUT-arm/compile_commands.json" . "Cortex-M4F (arm-none-eabi-gcc)" \
    "$MAKE_ARM_CFLAGS"
# ... and the same code: every object's sections (contents and disassembly) equal those of
# the Makefile's Cortex-M4F build, when it is given
if [ -n "${MAKE_ARM_LIB:-}" ]; then
    [ -f "$MAKE_ARM_LIB" ] || { echo "cmake-check: $MAKE_ARM_LIB missing"; exit 1; }
    mkdir -p "$OUT-arm/cmp/make" "$OUT-arm/cmp/cmake"
    ( cd "$OUT-arm/cmp/make" && arm-none-eabi-ar x "$TOP/$MAKE_ARM_LIB" )
    ( cd "$OUT-arm/cmp/cmake" && arm-none-eabi-ar x "$TOP/$OUT-arm/libqfoc.a" )
    n=0
    for c in src/*.c; do
        u=$(basename "$c" .c)
        a=$OUT-arm/cmp/make/$u.o
        b=$OUT-arm/cmp/cmake/$u.c.obj
        [ -f "$a" ] && [ -f "$b" ] || { echo "cmake-check: no object of $c in one of the two libraries"; exit 1; }
        # the dumps without their first lines (the file name)
        arm-none-eabi-objdump -s -d "$a" | tail -n +3 > "$a.dump"
        arm-none-eabi-objdump -s -d "$b" | tail -n +3 > "$b.dump"
        cmp -s "$a.dump" "$b.dump" || {
            diff "$a.dump" "$b.dump" | head -n 20
            echo "cmake-check: $c: the CMake object differs from the Makefile's"; exit 1; }
        n=$((n + 1))
    done
    echo "cmake-check: Cortex-M4F: the $n objects of the CMake build have the sections of the Makefile's build ($MAKE_ARM_LIB), byte for byte"
fi
echo "cmake-check: qfoc $version: host and Cortex-M4F libraries, add_subdirectory and find_package consumers pass ($(( $(date +%s) - start )) s)"
