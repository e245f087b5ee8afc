#!/bin/sh
# tools/setup/install-cbmc.sh PREFIX -- CBMC 6.x from Debian trixie on a bookworm host.
#
# bookworm ships no CBMC 6. trixie's cbmc needs trixie's libc and libstdc++, so the
# packages are fetched with a private apt state (the host's apt configuration and
# installed packages are not touched), unpacked into PREFIX/root, and each tool is
# started through trixie's own dynamic loader with --library-path.  LD_LIBRARY_PATH
# is deliberately not used: it would leak into the host gcc that cbmc runs as its
# preprocessor.  Idempotent; FORCE=1 downloads again.
set -eu

PREFIX=${1:?usage: install-cbmc.sh PREFIX}
SUITE=trixie
MIRROR=${MIRROR:-http://deb.debian.org/debian}
KEYRING=/usr/share/keyrings/debian-archive-keyring.gpg
PKGS="cbmc libc6 libstdc++6 libgcc-s1 minisat"
TOOLS="cbmc goto-cc goto-instrument goto-analyzer"
MA=x86_64-linux-gnu

mkdir -p "$PREFIX"
PREFIX=$(cd "$PREFIX" && pwd)
APTD=$PREFIX/apt
ROOT=$PREFIX/root
BIN=$PREFIX/bin
[ "${FORCE:-0}" = 1 ] && rm -rf "$APTD" "$ROOT" "$BIN"
mkdir -p "$APTD/lists/partial" "$APTD/cache/archives/partial" "$APTD/debs" "$BIN"
: > "$APTD/status"
printf 'Types: deb\nURIs: %s\nSuites: %s\nComponents: main\nSigned-By: %s\n' \
    "$MIRROR" "$SUITE" "$KEYRING" > "$APTD/$SUITE.sources"

apt_private() {
    apt-get -q -o Dir::Etc::SourceList="$APTD/$SUITE.sources" -o Dir::Etc::SourceParts=/dev/null \
        -o Dir::Etc::Preferences=/dev/null -o Dir::Etc::PreferencesParts=/dev/null \
        -o Dir::State::Lists="$APTD/lists" -o Dir::State::status="$APTD/status" \
        -o Dir::Cache="$APTD/cache" -o APT::Sandbox::User=root -o Acquire::Languages=none \
        -o Acquire::IndexTargets::deb::DEP-11::DefaultEnabled=false "$@"
}

have_debs=1
for p in $PKGS; do ls "$APTD/debs/${p}_"*.deb >/dev/null 2>&1 || have_debs=0; done
if [ "$have_debs" = 0 ]; then
    echo "cbmc: fetching $PKGS from $SUITE"
    apt_private update
    (cd "$APTD/debs" && apt_private download $PKGS)
fi

want=$(cd "$APTD/debs" && ls ./*.deb | sort | tr '\n' ' ')
if [ ! -f "$ROOT/.extracted" ] || [ "$(cat "$ROOT/.extracted")" != "$want" ]; then
    rm -rf "$ROOT"; mkdir -p "$ROOT"
    for d in "$APTD"/debs/*.deb; do dpkg-deb -x "$d" "$ROOT"; done
    printf '%s' "$want" > "$ROOT/.extracted"
fi

LDSO=$ROOT/usr/lib/$MA/ld-linux-x86-64.so.2
[ -e "$LDSO" ] || LDSO=$ROOT/lib/$MA/ld-linux-x86-64.so.2
[ -e "$LDSO" ] || { echo "cbmc: trixie loader not found under $ROOT" >&2; exit 1; }
LIBPATH=$ROOT/usr/lib/$MA:$ROOT/lib/$MA:$ROOT/usr/lib:/usr/lib/$MA:/lib/$MA
for t in $TOOLS; do
    [ -x "$ROOT/usr/bin/$t" ] || continue
    printf '#!/bin/sh\nexec "%s" --library-path "%s" --argv0 "$0" "%s" "$@"\n' \
        "$LDSO" "$LIBPATH" "$ROOT/usr/bin/$t" > "$BIN/$t.tmp"
    chmod 755 "$BIN/$t.tmp"
    mv -f "$BIN/$t.tmp" "$BIN/$t"
done
"$BIN/cbmc" --version >/dev/null
echo "cbmc: $("$BIN/cbmc" --version) in $BIN"
