#!/bin/sh
# tools/release/release_check.sh -- check a release package as an integrator receives it
# (make release-check).
#
#   sh tools/release/release_check.sh dist/qfoc-<version>.tar.gz
#
# Environment (set by mk/release.mk): CC, CFLAGS (the host library's flags), ARM_CC,
# ARM_CFLAGS (the Cortex-M4F flags), EXAMPLE (the program built against the package when
# the package has no examples/host_minimal.c).
#
# In an empty temporary directory: unpacks the tarball; checks SHA256SUMS (sha256sum -c)
# and that it lists every file of the package; checks that lib/cortex-m4f/libqfoc.a is the
# one BUILDINFO.txt records; builds the host library from the package's src/ with $CC
# $CFLAGS, builds the example (examples/host_minimal.c of the package, else $EXAMPLE) with
# the package's tables/reference_params.c against it and runs it; compiles the example
# with $ARM_CC $ARM_CFLAGS and links it with the package's Cortex-M4F libqfoc.a into an ELF
# whose entry points are checked with nm; configures, builds and installs the library with
# the package's CMakeLists.txt.  Exit 1 on the first failure.
set -eu
TOP=$(cd "$(dirname "$0")/../.." && pwd)
TAR=${1:?usage: release_check.sh TARBALL}
case "$TAR" in /*) ;; *) TAR=$(pwd)/$TAR ;; esac
CC=${CC:-gcc}
CFLAGS=${CFLAGS:--std=c99 -Wall -Wextra -Werror -O2 -Iinclude}
ARM_CC=${ARM_CC:-arm-none-eabi-gcc}
ARM_CFLAGS=${ARM_CFLAGS:?ARM_CFLAGS not set (run make release-check)}
EXAMPLE=${EXAMPLE:-$TOP/tools/release/release_example.c}
case "$EXAMPLE" in /*) ;; *) EXAMPLE=$TOP/$EXAMPLE ;; esac
[ -f "$TAR" ] || { echo "release-check: $TAR missing (run make release)"; exit 1; }

NAME=$(basename "$TAR" .tar.gz)
TMP=$(mktemp -d "${TMPDIR:-/tmp}/qfoc-release-check.XXXXXX")
trap 'rm -rf "$TMP"' EXIT INT TERM
fail() { echo "release-check: $*"; exit 1; }

tar -xzf "$TAR" -C "$TMP"
PKG=$TMP/$NAME
[ -d "$PKG" ] || fail "the tarball has no top directory $NAME/"
[ "$(ls -A "$TMP")" = "$NAME" ] || fail "the tarball holds more than $NAME/"
cd "$PKG"

# 1. the sums: every listed file intact, every file listed
sha256sum --quiet --strict -c SHA256SUMS || fail "SHA256SUMS does not match the files"
find . -type f ! -name SHA256SUMS | sed 's|^\./||' | LC_ALL=C sort > "$TMP/files.txt"
sed 's/^[0-9a-f]\{64\}  //' SHA256SUMS | LC_ALL=C sort > "$TMP/listed.txt"
cmp -s "$TMP/files.txt" "$TMP/listed.txt" || {
    diff "$TMP/listed.txt" "$TMP/files.txt" || true
    fail "SHA256SUMS does not list exactly the package's files"
}
nfiles=$(wc -l < "$TMP/files.txt")
version=$(sed -n 's/^#define QFOC_VERSION_STRING "\(.*\)".*/\1/p' include/qfoc/version.h)
[ "qfoc-$version" = "$NAME" ] || fail "version.h says $version, the package is $NAME"
lib_sha=$(sha256sum lib/cortex-m4f/libqfoc.a | cut -d' ' -f1)
grep -qx "sha256: $lib_sha" lib/cortex-m4f/BUILDINFO.txt || fail "libqfoc.a differs from BUILDINFO.txt"
echo "release-check: $NAME: SHA256SUMS verified ($nfiles files), libqfoc.a sha256 $lib_sha"

# 2. the host library from the package's sources, the example against it, run
if [ -f examples/host_minimal.c ]; then
    example=examples/host_minimal.c
else
    example=$EXAMPLE
fi
mkdir -p "$TMP/host/obj"
for c in src/*.c; do
    # shellcheck disable=SC2086
    $CC $CFLAGS -Iinclude -c "$c" -o "$TMP/host/obj/$(basename "$c" .c).o"
done
ar rcs "$TMP/host/libqfoc.a" "$TMP"/host/obj/*.o
# shellcheck disable=SC2086
$CC -std=c99 -Wall -Wextra -Werror -O2 -Iinclude -Itables "$example" tables/reference_params.c \
    "$TMP/host/libqfoc.a" -lm -o "$TMP/host/example"
"$TMP/host/example" > "$TMP/host/example.out" 2>&1 || {
    rc=$?; cat "$TMP/host/example.out"; fail "host example ($example) exited with $rc"; }
sed 's/^/  | /' "$TMP/host/example.out"
echo "release-check: host: library from $(ls src/*.c | wc -l) sources ($CC), $(basename "$example") built and run: pass"

# 3. the Cortex-M4F: the example compiled with the package's flags, linked with its libqfoc.a
mkdir -p "$TMP/arm"
arm_ex=$EXAMPLE
# shellcheck disable=SC2086
$ARM_CC $ARM_CFLAGS -Iinclude -Itables -c "$arm_ex" -o "$TMP/arm/example.o"
# shellcheck disable=SC2086
$ARM_CC $ARM_CFLAGS -Iinclude -Itables -c tables/reference_params.c -o "$TMP/arm/reference_params.o"
cpu_flags=$(for f in $ARM_CFLAGS; do case "$f" in -mcpu=*|-mthumb|-mfloat-abi=*|-mfpu=*) printf '%s ' "$f" ;; esac; done)
# shellcheck disable=SC2086
$ARM_CC $cpu_flags -nostartfiles --specs=nosys.specs -Wl,-e,main -Wl,--gc-sections \
    "$TMP/arm/example.o" "$TMP/arm/reference_params.o" lib/cortex-m4f/libqfoc.a \
    -o "$TMP/arm/example.elf"
for s in main qfoc_version qfoc_drive_init qfoc_drive_fast_step qfoc_drive_tick; do
    arm-none-eabi-nm "$TMP/arm/example.elf" | grep -q " T $s\$" || fail "Cortex-M4F ELF: $s not linked"
done
arm-none-eabi-readelf -A "$TMP/arm/example.elf" | grep -q 'Tag_ABI_VFP_args: VFP registers' || \
    fail "Cortex-M4F ELF: not the hard-float ABI"
text=$(arm-none-eabi-size "$TMP/arm/example.elf" | awk 'NR == 2 {print $1}')
echo "release-check: Cortex-M4F: $(basename "$arm_ex") linked with lib/cortex-m4f/libqfoc.a ($ARM_CC, hard float): text $text B"
# 4. the package's own CMake build: the library configured, built and installed from the
#    unpacked tree (the CMake files refer only to what the package holds)
if command -v cmake > /dev/null 2>&1; then
    ( unset CFLAGS CC CMAKE_PREFIX_PATH CMAKE_GENERATOR CMAKE_BUILD_TYPE
      cmake -S . -B "$TMP/cmake" > "$TMP/cmake.log" 2>&1 &&
      cmake --build "$TMP/cmake" -j 2 >> "$TMP/cmake.log" 2>&1 &&
      cmake --install "$TMP/cmake" --prefix "$TMP/cmake-prefix" >> "$TMP/cmake.log" 2>&1 ) || {
        cat "$TMP/cmake.log"; fail "the package's CMake build failed"; }
    [ -f "$TMP/cmake-prefix/lib/cmake/qfoc/qfocConfigVersion.cmake" ] || fail "CMake install without qfocConfigVersion.cmake"
    echo "release-check: CMake: the package's CMakeLists.txt builds and installs qfoc $version"
else
    fail "cmake missing (make deps installs it)"
fi
echo "release-check: $NAME passes"
