#!/bin/sh
# tools/evidence/tool_versions.sh -- the version of every tool qfoc's build and verification use.
#
#   sh tools/evidence/tool_versions.sh
#
# Prints one line per tool, `name: version`, in a fixed order (the tools of
# specs/tool-confidence.md, then the project's own scripts with their SHA-256).  A tool
# that is not there prints `name: not installed`; a tool that is there but does not
# answer prints `name: unknown (...)`.  The exit status is 0 in every case: the lines are
# a record, the gates are elsewhere.  Nothing is installed or changed.
#
# Where the tools are looked for:
#   CBMC_PREFIX   CBMC from Debian trixie (tools/setup/install-cbmc.sh), default build/tools/cbmc
#   MCDC_CHROOT   the trixie chroot with gcc 14 (tools/setup/mkchroot.sh), default build/trixie-chroot;
#                 gcc-14 is asked through chroot when run as root, else its version is read
#                 from the chroot's package database (dpkg-query --admindir)
#   PY            the Debian interpreter the Makefile uses as PYTHON, default /usr/bin/python3
set -u
TOP=$(cd "$(dirname "$0")/../.." && pwd)
cd "$TOP" || exit 0
CBMC_PREFIX=${CBMC_PREFIX:-$TOP/build/tools/cbmc}
CHROOT=${MCDC_CHROOT:-$TOP/build/trixie-chroot}
PY=${PY:-/usr/bin/python3}
[ -x "$PY" ] || PY=$(command -v python3 2>/dev/null || echo python3)

if command -v timeout >/dev/null 2>&1; then TMO="timeout 30"; else TMO=""; fi

# first non-empty line of a text, trimmed
first() {
    tr -d '\r' | sed -e 's/^[[:space:]]*//' -e 's/[[:space:]]*$//' | grep -v '^$' | head -n 1
}

# line NAME CMD [ARGS...]: NAME: the first line CMD ARGS prints (stdout and stderr)
line() {
    name=$1
    shift
    if ! command -v "$1" >/dev/null 2>&1 && [ ! -x "$1" ]; then
        echo "$name: not installed"
        return 0
    fi
    # shellcheck disable=SC2086
    out=$($TMO "$@" 2>&1 | first)
    out=${out#"$name: "}
    if [ -n "$out" ]; then
        echo "$name: $out"
    else
        echo "$name: unknown (no output)"
    fi
}

# pkg NAME PACKAGE: NAME: the installed Debian package's version
pkg() {
    v=$(dpkg-query -W -f='${Status} ${Version}\n' "$2" 2>/dev/null |
        sed -n 's/^install ok installed //p' | head -n 1)
    if [ -n "$v" ]; then echo "$1: $2 $v (Debian package)"; else echo "$1: not installed"; fi
}

# pymod NAME MODULE: NAME: MODULE.__version__ as seen by the Debian interpreter
pymod() {
    v=$($TMO "$PY" -c "import $2; print(getattr($2, '__version__', 'unknown'))" 2>/dev/null | first)
    if [ -n "$v" ]; then echo "$1: $v ($PY)"; else echo "$1: not installed"; fi
}

# sha NAME FILE: NAME: sha256 of a file of the repository
sha() {
    if [ -f "$2" ]; then
        echo "$1: sha256 $(sha256sum "$2" | cut -d' ' -f1)"
    else
        echo "$1: not installed"
    fi
}

# ---------------------------------------------------------------- host compiler and coverage
line gcc gcc --version
line g++ g++ --version
line gcov gcov --version
line lcov lcov --version
line gcovr gcovr --version
line make make --version
line cmake cmake --version

# ---------------------------------------------------------------- Cortex-M4F toolchain
line arm-none-eabi-gcc arm-none-eabi-gcc --version
line arm-none-eabi-binutils arm-none-eabi-objdump --version
pkg newlib-arm-none-eabi libnewlib-arm-none-eabi

# ---------------------------------------------------------------- Frama-C and its provers
line frama-c frama-c -version
pkg frama-c-package frama-c-base
line why3 why3 --version
line z3 z3 --version
line cvc4 cvc4 --version

# ---------------------------------------------------------------- CBMC (Debian trixie build)
if [ -x "$CBMC_PREFIX/bin/cbmc" ]; then
    line cbmc "$CBMC_PREFIX/bin/cbmc" --version
    line goto-instrument "$CBMC_PREFIX/bin/goto-instrument" --version
    for p in cbmc minisat; do
        for deb in "$CBMC_PREFIX"/apt/debs/"$p"_*.deb; do
            [ -f "$deb" ] && echo "$p-package: $(basename "$deb") (Debian trixie)"
            break
        done
    done
else
    line cbmc cbmc --version
    line goto-instrument goto-instrument --version
fi

# CBMC's SAT back end (tools/gates/cbmc.sh: --external-sat-solver)
line cadical cadical --version
pkg cadical-package cadical

# ---------------------------------------------------------------- MISRA and static analysis
line cppcheck cppcheck --version
addon=$(dpkg -L cppcheck 2>/dev/null | grep '/addons/misra\.py$' | head -n 1)
if [ -n "$addon" ] && [ -f "$addon" ]; then
    echo "cppcheck-misra-addon: $addon sha256 $(sha256sum "$addon" | cut -d' ' -f1)"
else
    echo "cppcheck-misra-addon: not installed"
fi
line clang-tidy clang-tidy --version

# ---------------------------------------------------------------- test framework
pkg cmocka libcmocka-dev

# ---------------------------------------------------------------- MC/DC: gcc 14 in the trixie chroot
if [ -x "$CHROOT/usr/bin/gcc-14" ]; then
    if [ "$(id -u)" = 0 ] && command -v chroot >/dev/null 2>&1; then
        v=$($TMO chroot "$CHROOT" /usr/bin/env -i PATH=/usr/bin:/bin gcc-14 --version 2>&1 | first)
        echo "gcc-14: ${v:-unknown} (chroot $CHROOT)"
        v=$($TMO chroot "$CHROOT" /usr/bin/env -i PATH=/usr/bin:/bin gcov-14 --version 2>&1 | first)
        echo "gcov-14: ${v:-unknown} (chroot $CHROOT)"
    else
        v=$(dpkg-query --admindir="$CHROOT/var/lib/dpkg" -W -f='${Version}' gcc-14 2>/dev/null)
        echo "gcc-14: gcc-14 ${v:-unknown} (Debian package in $CHROOT)"
    fi
    v=$(dpkg-query --admindir="$CHROOT/var/lib/dpkg" -W -f='${Version}' libcmocka-dev 2>/dev/null)
    if [ -n "$v" ]; then echo "cmocka-chroot: libcmocka-dev $v (Debian package in $CHROOT)"; fi
else
    echo "gcc-14: not installed"
fi
line debootstrap debootstrap --version

# ---------------------------------------------------------------- emulators
line qemu-system-arm qemu-system-arm --version
pymod unicorn unicorn
pymod pyelftools elftools

# ---------------------------------------------------------------- API reference
line doxygen doxygen --version

# ---------------------------------------------------------------- Python
line python3-debian "$PY" --version
if command -v python3 >/dev/null 2>&1 && [ "$(command -v python3)" != "$PY" ]; then
    v=$($TMO python3 --version 2>&1 | first)
    echo "python3-path: ${v:-unknown} ($(command -v python3))"
fi
pymod matplotlib matplotlib
pymod numpy numpy
pymod scipy scipy
pymod pytest pytest

# ---------------------------------------------------------------- the project's own scripts
if command -v git >/dev/null 2>&1 && git rev-parse --git-dir >/dev/null 2>&1; then
    c=$(git rev-parse HEAD 2>/dev/null)
    if [ -n "$(git status --porcelain 2>/dev/null)" ]; then c="$c (working tree modified)"; fi
    echo "qfoc: git $c"
else
    echo "qfoc: not a git checkout"
fi
for f in tools/*/*.py tools/*/*.sh port_s32k/*.py; do
    [ -f "$f" ] || continue
    sha "$f" "$f"
done
exit 0
