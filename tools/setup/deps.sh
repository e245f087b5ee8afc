#!/bin/sh
# tools/setup/deps.sh -- install everything qfoc needs on Debian bookworm.
#
#   sh tools/setup/deps.sh            install (as root) or print the sudo command (not root)
#   sh tools/setup/deps.sh --check    exit 0 when everything is already there, 1 otherwise
#   sh tools/setup/deps.sh --tune     only what the tuning tool needs (make tune, make tune-check):
#                                     make and Debian's python3 with numpy, scipy, matplotlib, pytest
#   sh tools/setup/deps.sh --tune --check   the same, check only
#   sh tools/setup/deps.sh --a2l      only what the calibration description needs (make a2l,
#                                     make a2l-check): make, the ARM tool chain and Debian's
#                                     python3 with numpy, pyelftools, pytest
#   sh tools/setup/deps.sh --a2l --check    the same, check only
#   sh tools/setup/deps.sh --docs     only what the API reference needs (make docs): make and doxygen
#   sh tools/setup/deps.sh --docs --check   the same, check only
#   sh tools/setup/deps.sh --demo     only what make demo needs: make, gcc and Debian's python3
#                                     with numpy and matplotlib
#   sh tools/setup/deps.sh --release  only what make release needs: make, git, gcc, the ARM
#                                     tool chain, doxygen (the API reference it carries), python3
#
# Idempotent: when every tool is present it returns within a second.
# CBMC 6.x is not in bookworm; tools/setup/install-cbmc.sh puts trixie's build into
# build/tools/cbmc (project-local, the system is left alone).
set -eu

TOP=$(cd "$(dirname "$0")/../.." && pwd)
CBMC_PREFIX=${CBMC_PREFIX:-$TOP/build/tools/cbmc}
# Debian's interpreter, which sees the python3-* packages (a PATH python may not)
PY=/usr/bin/python3
[ -x "$PY" ] || PY=python3

PKGS="make gcc frama-c-base why3 z3 cvc4 cppcheck lcov gcovr libcmocka-dev \
gcc-arm-none-eabi libnewlib-arm-none-eabi binutils-arm-none-eabi \
python3 python3-matplotlib python3-numpy python3-scipy python3-pytest \
qemu-system-arm python3-unicorn python3-pyelftools python3-capstone clang-tidy debootstrap \
debian-archive-keyring dpkg-dev cmake cadical clang g++ doxygen"

# have_cmds CMD...: every command is on the PATH (else "missing: CMD", status 1)
have_cmds() {
    for c in "$@"; do
        command -v "$c" >/dev/null 2>&1 || { echo "missing: $c"; return 1; }
    done
    return 0
}

# have_py "MODULES" "PACKAGES": $PY imports the modules (else "missing: PACKAGES", status 1)
have_py() {
    "$PY" -c "import $1" >/dev/null 2>&1 || { echo "missing: $2"; return 1; }
}

# command that must exist for each tool (same order is not required)
need_cmds() {
    have_cmds gcc make frama-c why3 z3 cvc4 cppcheck lcov gcovr arm-none-eabi-gcc python3 dpkg-deb \
              qemu-system-arm clang-tidy debootstrap cmake cadical clang g++ doxygen || return 1
    [ -f /usr/include/cmocka.h ] || { echo "missing: libcmocka-dev"; return 1; }
    need_a2l >/dev/null || { need_a2l; return 1; }
    have_py "matplotlib, numpy" "python3-matplotlib" || return 1
    have_py "scipy.signal, pytest" "python3-scipy or python3-pytest" || return 1
    have_py "unicorn, elftools, capstone" "python3-unicorn, python3-pyelftools or python3-capstone" || return 1
    [ -f /usr/share/keyrings/debian-archive-keyring.gpg ] || { echo "missing: debian-archive-keyring"; return 1; }
    [ -x "$CBMC_PREFIX/bin/cbmc" ] || { echo "missing: cbmc ($CBMC_PREFIX)"; return 1; }
    [ -f "$HOME/.why3.conf" ] || { echo "missing: why3 prover configuration"; return 1; }
    return 0
}

# The tuning tool alone (tools/tune/qfoc_tune.py and its pytest suite).
TUNE_PKGS="make python3 python3-numpy python3-scipy python3-matplotlib python3-pytest"

need_tune() {
    have_cmds make &&
        have_py "numpy, scipy.signal, matplotlib, pytest" \
            "python3-numpy, python3-scipy, python3-matplotlib or python3-pytest"
}

# One light target (--tune, --a2l, --docs): its packages only.
#   light_target ARG1 ARG2 FLAG CHECK_FN PKGS WHAT
# ARG1 and ARG2 are the script's own arguments; returns when ARG1 is not FLAG.
light_target() {
    _a1=$1; _a2=$2
    shift 2
    [ "$_a1" = "$1" ] || return 0
    if [ "$_a2" = "--check" ]; then
        "$2" >/dev/null
        exit $?
    fi
    if "$2" >/dev/null 2>&1; then
        echo "deps: $4 packages present"
        exit 0
    fi
    if [ "$(id -u)" != 0 ]; then
        echo "deps: $("$2") and this is not root. Run:" >&2
        echo "  sudo apt-get update && sudo apt-get install -y --no-install-recommends $3" >&2
        exit 1
    fi
    export DEBIAN_FRONTEND=noninteractive
    apt-get update -q
    # shellcheck disable=SC2086
    apt-get install -y -q --no-install-recommends $3
    "$2"
    exit $?
}

# The calibration description alone (tools/a2l/qfoc_a2l.py, its tests, and the firmware image
# it describes: the ARM tool chain with newlib's nano.specs).
A2L_PKGS="make gcc-arm-none-eabi libnewlib-arm-none-eabi binutils-arm-none-eabi \
python3 python3-numpy python3-pyelftools python3-pytest"

need_a2l() {
    have_cmds make arm-none-eabi-gcc arm-none-eabi-objcopy || return 1
    [ -f /usr/lib/arm-none-eabi/newlib/nano.specs ] || { echo "missing: libnewlib-arm-none-eabi"; return 1; }
    have_py "numpy, elftools, pytest" "python3-numpy, python3-pyelftools or python3-pytest"
}

light_target "${1:-}" "${2:-}" --a2l need_a2l "$A2L_PKGS" "calibration description's"

# The API reference alone (Doxyfile, mk/docs.mk): no compiler, no verification chain.
DOCS_PKGS="make doxygen"

need_docs() {
    have_cmds make doxygen
}

light_target "${1:-}" "${2:-}" --docs need_docs "$DOCS_PKGS" "API reference's"

# The demo alone (sim/, the host library, tools/demo/demo_report.py).
DEMO_PKGS="make gcc libc6-dev python3 python3-numpy python3-matplotlib"

need_demo() {
    have_cmds make gcc && have_py "numpy, matplotlib" "python3-numpy or python3-matplotlib"
}

light_target "${1:-}" "${2:-}" --demo need_demo "$DEMO_PKGS" "demo's"

# The release package alone (tools/release/release.sh): the Cortex-M4F library, the API
# reference, the package's checks.
RELEASE_PKGS="make git gcc libc6-dev gcc-arm-none-eabi libnewlib-arm-none-eabi \
binutils-arm-none-eabi doxygen python3"

need_release() {
    have_cmds make git gcc arm-none-eabi-gcc doxygen
}

light_target "${1:-}" "${2:-}" --release need_release "$RELEASE_PKGS" "release's"

light_target "${1:-}" "${2:-}" --tune need_tune "$TUNE_PKGS" "tuning tool's"

if [ "${1:-}" = "--check" ]; then
    need_cmds >/dev/null
    exit $?
fi

if need_cmds >/dev/null 2>&1; then
    echo "deps: all tools present"
    exit 0
fi

if [ "$(id -u)" != 0 ]; then
    echo "deps: some tools are missing and this is not root. Run:" >&2
    echo "  sudo apt-get update && sudo apt-get install -y --no-install-recommends $PKGS" >&2
    echo "  then: make deps" >&2
    exit 1
fi

missing_pkgs=""
for p in $PKGS; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing_pkgs="$missing_pkgs $p"
done
if [ -n "$missing_pkgs" ]; then
    echo "deps: apt-get install$missing_pkgs"
    export DEBIAN_FRONTEND=noninteractive
    apt-get update -q
    # shellcheck disable=SC2086
    apt-get install -y -q --no-install-recommends $missing_pkgs
fi

# why3 must know z3 and cvc4 (bookworm has no Alt-Ergo).
if [ ! -f "$HOME/.why3.conf" ] || ! grep -q 'name = "Z3"' "$HOME/.why3.conf" 2>/dev/null; then
    why3 config detect >/dev/null 2>&1 || why3 config --detect >/dev/null
fi

sh "$TOP/tools/setup/install-cbmc.sh" "$CBMC_PREFIX"
echo "deps: done"
