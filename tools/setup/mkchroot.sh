#!/bin/sh
# tools/setup/mkchroot.sh -- the Debian trixie chroot that runs gcc 14 for MC/DC coverage.
#
#   sh tools/setup/mkchroot.sh [DIR]      (as root; default build/trixie-chroot)
#
# Debian bookworm ships gcc 12; condition coverage (-fcondition-coverage, gcov
# --conditions) arrived in gcc 14.  This script builds a minimal trixie root with
# debootstrap (variant minbase) and installs gcc-14, libc6-dev and libcmocka-dev in it.
# It needs network access to the mirror (MIRROR, default http://deb.debian.org/debian)
# and the host packages debootstrap and debian-archive-keyring.
#
# Idempotent: when the chroot is complete it prints the tool versions and returns at
# once.  An interrupted first stage is started again from scratch in a temporary
# directory, which is renamed only when debootstrap succeeded, so a half-made root is
# never taken for a complete one.  The chroot holds no mounts when this script ends.
set -eu

TOP=$(cd "$(dirname "$0")/../.." && pwd)
T=${1:-$TOP/build/trixie-chroot}
MIRROR=${MIRROR:-http://deb.debian.org/debian}
SUITE=trixie
PKGS="gcc-14 libc6-dev libcmocka-dev"
STAMP=.qfoc-chroot

say() { echo "mkchroot: $*"; }

if [ "$(id -u)" != 0 ]; then
    echo "mkchroot: debootstrap and chroot need root; run: sudo sh tools/setup/mkchroot.sh" >&2
    exit 1
fi

case $T in /*) ;; *) T=$(pwd)/$T ;; esac

# Every mount point below $1 (deepest first), from the kernel's table.
mounts_below() {
    awk -v p="$1" '$2 == p || index($2, p "/") == 1 { print $2 }' /proc/self/mounts | sort -r
}

# Unmount whatever is left below $1 (an interrupted debootstrap leaves /proc and /sys).
release_mounts() {
    for m in $(mounts_below "$1"); do
        say "umount $m"
        umount "$m" || umount -l "$m"
    done
}

# The chroot is complete when the compiler, gcov and the CMocka header are in it.
chroot_ready() {
    [ -x "$1/usr/bin/gcc-14" ] && [ -x "$1/usr/bin/gcov-14" ] && [ -f "$1/usr/include/cmocka.h" ] \
        && [ -f "$1/$STAMP" ]
}

# shellcheck disable=SC2016
versions() {
    chroot "$1" /usr/bin/env -i PATH=/usr/bin:/bin \
        dpkg-query -W -f='${Package} ${Version}\n' gcc-14 libc6-dev libcmocka-dev | sed 's/^/  /'
}

if chroot_ready "$T"; then
    say "$T ready"
    versions "$T"
    exit 0
fi

if ! command -v debootstrap >/dev/null 2>&1 || [ ! -f /usr/share/keyrings/debian-archive-keyring.gpg ]; then
    say "apt-get install debootstrap debian-archive-keyring"
    DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends \
        debootstrap debian-archive-keyring
fi

t0=$(date +%s)
# Stage 1: the base system.  Done when apt-get exists in the root.
if [ ! -x "$T/usr/bin/apt-get" ]; then
    tmp=$T.partial
    release_mounts "$tmp"
    if [ -e "$tmp" ]; then
        say "removing the interrupted attempt $tmp"
        [ -z "$(mounts_below "$tmp")" ] || { echo "mkchroot: $tmp still has mounts" >&2; exit 1; }
        rm -rf "$tmp"
    fi
    if [ -e "$T" ]; then
        # Not made by this script (it renames only a finished root): leave it alone.
        echo "mkchroot: $T exists but holds no Debian root; move it away first" >&2
        exit 1
    fi
    mkdir -p "$(dirname "$T")"
    say "debootstrap --variant=minbase $SUITE $tmp $MIRROR"
    debootstrap --variant=minbase "$SUITE" "$tmp" "$MIRROR" > "$(dirname "$T")/trixie-debootstrap.log" 2>&1 || {
        tail -n 20 "$(dirname "$T")/trixie-debootstrap.log"
        release_mounts "$tmp"
        echo "mkchroot: debootstrap failed (log: $(dirname "$T")/trixie-debootstrap.log)" >&2
        exit 1
    }
    release_mounts "$tmp"
    mv "$tmp" "$T"
    say "base system in $(( $(date +%s) - t0 )) s"
fi

# Stage 2: the compiler and CMocka.
say "apt-get install $PKGS (in the chroot)"
cp /etc/resolv.conf "$T/etc/resolv.conf" 2>/dev/null || true
chroot "$T" /usr/bin/env -i PATH=/usr/sbin:/usr/bin:/sbin:/bin DEBIAN_FRONTEND=noninteractive \
    LANG=C.UTF-8 sh -c "apt-get update -q && apt-get install -y -q --no-install-recommends $PKGS \
    && apt-get clean" > "$(dirname "$T")/trixie-apt.log" 2>&1 || {
    tail -n 20 "$(dirname "$T")/trixie-apt.log"
    release_mounts "$T"
    echo "mkchroot: package installation failed (log: $(dirname "$T")/trixie-apt.log)" >&2
    exit 1
}
release_mounts "$T"
date -u '+%Y-%m-%dT%H:%M:%SZ' > "$T/$STAMP"
chroot_ready "$T" || { echo "mkchroot: $T is still incomplete" >&2; exit 1; }
say "$T ready in $(( $(date +%s) - t0 )) s, $(du -sh "$T" | cut -f1)"
versions "$T"
