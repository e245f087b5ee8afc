#!/bin/sh
# tools/setup/deps.sh -- install everything qfoc needs on Debian bookworm.
#
#   sh tools/setup/deps.sh            install (as root) or print the sudo command (not root)
#   sh tools/setup/deps.sh --check    exit 0 when everything is already there, 1 otherwise
#   sh tools/setup/deps.sh --tune     only what the tuning tool needs (make tune, make tune-check):
#                                     make and Debian's python3 with numpy, scipy, matplotlib, pytest
#   sh tools/setup/deps.sh --tune --check   the same, check only
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
qemu-system-arm python3-unicorn python3-pyelftools clang-tidy debootstrap \
debian-archive-keyring dpkg-dev cmake cadical clang"

# command that must exist for each tool (same order is not required)
need_cmds() {
    for c in gcc make frama-c why3 z3 cvc4 cppcheck lcov gcovr arm-none-eabi-gcc python3 dpkg-deb \
             qemu-system-arm clang-tidy debootstrap cmake cadical clang; do
        command -v "$c" >/dev/null 2>&1 || { echo "missing: $c"; return 1; }
    done
    [ -f /usr/include/cmocka.h ] || { echo "missing: libcmocka-dev"; return 1; }
    "$PY" -c "import matplotlib, numpy" >/dev/null 2>&1 || { echo "missing: python3-matplotlib"; return 1; }
    "$PY" -c "import scipy.signal, pytest" >/dev/null 2>&1 || { echo "missing: python3-scipy or python3-pytest"; return 1; }
    "$PY" -c "import unicorn, elftools" >/dev/null 2>&1 || { echo "missing: python3-unicorn or python3-pyelftools"; return 1; }
    [ -f /usr/share/keyrings/debian-archive-keyring.gpg ] || { echo "missing: debian-archive-keyring"; return 1; }
    [ -x "$CBMC_PREFIX/bin/cbmc" ] || { echo "missing: cbmc ($CBMC_PREFIX)"; return 1; }
    [ -f "$HOME/.why3.conf" ] || { echo "missing: why3 prover configuration"; return 1; }
    return 0
}

# The tuning tool alone (tools/tune/qfoc_tune.py and its pytest suite).
TUNE_PKGS="make python3 python3-numpy python3-scipy python3-matplotlib python3-pytest"

need_tune() {
    command -v make >/dev/null 2>&1 || { echo "missing: make"; return 1; }
    "$PY" -c "import numpy, scipy.signal, matplotlib, pytest" >/dev/null 2>&1 ||
        { echo "missing: python3-numpy, python3-scipy, python3-matplotlib or python3-pytest"; return 1; }
    return 0
}

if [ "${1:-}" = "--tune" ]; then
    if [ "${2:-}" = "--check" ]; then
        need_tune >/dev/null
        exit $?
    fi
    if need_tune >/dev/null 2>&1; then
        echo "deps: tuning tool's packages present"
        exit 0
    fi
    if [ "$(id -u)" != 0 ]; then
        echo "deps: $(need_tune) and this is not root. Run:" >&2
        echo "  sudo apt-get update && sudo apt-get install -y --no-install-recommends $TUNE_PKGS" >&2
        exit 1
    fi
    export DEBIAN_FRONTEND=noninteractive
    apt-get update -q
    # shellcheck disable=SC2086
    apt-get install -y -q --no-install-recommends $TUNE_PKGS
    need_tune
    exit $?
fi

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
