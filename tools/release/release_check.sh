#!/bin/sh
# tools/release/release_check.sh -- check a release package as an integrator receives it
# (make release-check).
#
#   sh tools/release/release_check.sh dist/qfoc-<version>.tar.gz
#
# Environment (set by mk/release.mk): ARM_CC, ARM_CFLAGS (the Cortex-M4F flags, for the
# example linked against the shipped library), EXAMPLE (that freestanding example,
# tools/release/release_example.c).
#
# In an empty temporary directory: unpacks the tarball, then, exit 1 on the first failure:
#   1. SHA256SUMS verified (sha256sum -c) and listing every file; the version of the name
#      is version.h's; the package's own README.md, Makefile and RELEASE.txt, and port_s32k/
#      and misra/, at its top level;
#   2. the evidence (tools/release/release_ready.py package): evidence/evidence.json of the
#      commit RELEASE.txt records, made in a clean tree, every summary row green (none
#      missing, failed or STALE), evidence/MANIFEST.sha256 intact; lib/cortex-m4f/libqfoc.a
#      the one BUILDINFO.txt records, of the same commit;
#   3. the package's own Makefile, in the unpacked tree, nothing from outside it: the host
#      and the Cortex-M4F libraries built from src/, the Cortex-M4F one byte for byte the
#      shipped lib/cortex-m4f/libqfoc.a (make target-compare), the example built and run
#      (make example), the S32K144 image built and checked (make firmware) and run from
#      reset in the emulator (make boot-check);
#   4. a freestanding example compiled with ARM_CFLAGS and linked with the shipped
#      lib/cortex-m4f/libqfoc.a into an ELF: entry points present, hard-float ABI;
#   5. the package's CMakeLists.txt: the host library configured, built and installed, and
#      the Cortex-M4F library with cmake/arm-none-eabi-cortex-m4f.cmake;
#   6. the tuning tool of the package (tools/tune/qfoc_tune.py, Debian's python3) on every
#      line of tables/manifest.txt into a temporary directory: each table byte for byte the
#      package's.
set -eu
TOP=$(cd "$(dirname "$0")/../.." && pwd)
TAR=${1:?usage: release_check.sh TARBALL}
case "$TAR" in /*) ;; *) TAR=$(pwd)/$TAR ;; esac
ARM_CC=${ARM_CC:-arm-none-eabi-gcc}
ARM_CFLAGS=${ARM_CFLAGS:?ARM_CFLAGS not set (run make release-check)}
EXAMPLE=${EXAMPLE:-$TOP/tools/release/release_example.c}
case "$EXAMPLE" in /*) ;; *) EXAMPLE=$TOP/$EXAMPLE ;; esac
PY=/usr/bin/python3
[ -x "$PY" ] || PY=python3
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

# 1. the sums, the version, the layout
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
for f in README.md Makefile RELEASE.txt CMakeLists.txt port_s32k/README.md port_s32k/s32k144.ld \
         misra/deviations.md docs/porting.md docs/api/index.html specs/safety-manual.md tools/tune/qfoc_tune.py \
         examples/host_minimal.c; do
    [ -f "$f" ] || fail "$f is not in the package"
done
head -n 1 README.md | grep -q "^# qfoc $version .*release package" ||
    fail "README.md is not the package's own (its first line: $(head -n 1 README.md))"
{ grep -q '^lib:' Makefile && grep -q '^target:' Makefile; } || fail "Makefile is not the package's own"
echo "release-check: $NAME: SHA256SUMS verified ($nfiles files); README.md, Makefile, RELEASE.txt, port_s32k/, misra/ at the top"

# 2. the evidence of the package's commit, the library's record
"$PY" "$TOP/tools/release/release_ready.py" package "$PKG" || fail "the package's evidence is refused"
commit=$(sed -n 's/^commit: \([0-9a-f]*\).*/\1/p' RELEASE.txt)
lib_sha=$(sha256sum lib/cortex-m4f/libqfoc.a | cut -d' ' -f1)
grep -qx "sha256: $lib_sha" lib/cortex-m4f/BUILDINFO.txt || fail "libqfoc.a differs from BUILDINFO.txt"
grep -qx "commit: $commit" lib/cortex-m4f/BUILDINFO.txt || fail "BUILDINFO.txt is not of the commit $commit"
echo "release-check: lib/cortex-m4f/libqfoc.a sha256 $lib_sha, commit $commit"

# 3. the package's own Makefile (the environment's compiler flags kept out of it)
pmake() {
    env -u CC -u CFLAGS -u ARM_CFLAGS -u MAKEFLAGS -u MFLAGS -u BUILD make --no-print-directory "$@"
}
pmake -j2 lib target > "$TMP/make.log" 2>&1 || { cat "$TMP/make.log"; fail "make lib target failed in the package"; }
n_src=$(find src -maxdepth 1 -name "*.c" | wc -l)
[ "$(ar t build/host/libqfoc.a | wc -l)" = "$n_src" ] || fail "build/host/libqfoc.a does not hold one object per source"
pmake target-compare || fail "the package's Makefile does not rebuild the shipped Cortex-M4F library"
pmake example > "$TMP/example.log" 2>&1 || { cat "$TMP/example.log"; fail "make example failed in the package"; }
grep '^host_minimal:' "$TMP/example.log" | sed 's/^/  | /'
pmake firmware > "$TMP/firmware.log" 2>&1 || { cat "$TMP/firmware.log"; fail "make firmware failed in the package"; }
pmake boot-check > "$TMP/boot.log" 2>&1 || { cat "$TMP/boot.log"; fail "make boot-check failed in the package"; }
tail -n 1 "$TMP/boot.log" | sed 's/^/  | /'
echo "release-check: the package's Makefile: host library ($n_src sources), Cortex-M4F library identical to the shipped one, example run, S32K144 image built, checked and booted in the emulator"

# 4. the Cortex-M4F: a freestanding example compiled with the flags, linked with the shipped library
mkdir -p "$TMP/arm"
# shellcheck disable=SC2086
$ARM_CC $ARM_CFLAGS -Iinclude -Itables -c "$EXAMPLE" -o "$TMP/arm/example.o"
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
echo "release-check: Cortex-M4F: $(basename "$EXAMPLE") linked with lib/cortex-m4f/libqfoc.a ($ARM_CC, hard float): text $text B"

# 5. the package's own CMake build: host (configured, built, installed) and Cortex-M4F
command -v cmake > /dev/null 2>&1 || fail "cmake missing (make deps installs it)"
( unset CFLAGS CC CMAKE_PREFIX_PATH CMAKE_GENERATOR CMAKE_BUILD_TYPE
  cmake -S . -B "$TMP/cmake" > "$TMP/cmake.log" 2>&1 &&
  cmake --build "$TMP/cmake" -j 2 >> "$TMP/cmake.log" 2>&1 &&
  cmake --install "$TMP/cmake" --prefix "$TMP/cmake-prefix" >> "$TMP/cmake.log" 2>&1 &&
  cmake -S . -B "$TMP/cmake-arm" -DCMAKE_TOOLCHAIN_FILE=cmake/arm-none-eabi-cortex-m4f.cmake \
      >> "$TMP/cmake.log" 2>&1 &&
  cmake --build "$TMP/cmake-arm" -j 2 >> "$TMP/cmake.log" 2>&1 ) || {
    cat "$TMP/cmake.log"; fail "the package's CMake build failed"; }
[ -f "$TMP/cmake-prefix/lib/cmake/qfoc/qfocConfigVersion.cmake" ] || fail "CMake install without qfocConfigVersion.cmake"
[ -f "$TMP/cmake-arm/libqfoc.a" ] || fail "the CMake Cortex-M4F build made no libqfoc.a"
echo "release-check: CMake: the package's CMakeLists.txt builds and installs qfoc $version (host), and builds it for the Cortex-M4F"

# 6. the tuning tool of the package regenerates the package's tables
"$PY" -c 'import numpy, scipy.signal' 2> /dev/null || fail "$PY without numpy or scipy (Debian: python3-numpy python3-scipy)"
mkdir -p "$TMP/tune"
ntab=0
grep -v '^[[:space:]]*#' tables/manifest.txt | while read -r name motor rest; do
    [ -n "$name" ] || continue
    set --
    for o in $rest; do set -- "$@" --set "$o"; done
    "$PY" tools/tune/qfoc_tune.py "$motor" --name "$name" --no-plots --out-dir "$TMP/tune/report-$name" \
        --table-dir "$TMP/tune" "$@" > "$TMP/tune/$name.log" 2>&1 || {
        cat "$TMP/tune/$name.log"; echo "release-check: the package's tool refused $motor ($name)"; exit 1; }
    for ext in c h; do
        cmp -s "$TMP/tune/${name}_params.$ext" "tables/${name}_params.$ext" ||
            { echo "release-check: tables/${name}_params.$ext is not what the package's tool makes of $motor"; exit 1; }
    done
done || exit 1
ntab=$(grep -v '^[[:space:]]*#' tables/manifest.txt | grep -c '[^[:space:]]')
echo "release-check: the package's tuning tool regenerates its $ntab tables of tables/manifest.txt byte for byte"
echo "release-check: $NAME passes"
