#!/bin/sh
# tools/release/release.sh -- the release package dist/qfoc-<version>.tar.gz (make release).
#
#   sh tools/release/release.sh ARM_LIB EVIDENCE_DIR
#
# ARM_LIB is the Cortex-M4F libqfoc.a built by the Makefile with its ARM_CFLAGS (passed in
# the environment as ARM_CFLAGS, recorded in the package), EVIDENCE_DIR the bundle of
# `make evidence`.  The version is QFOC_VERSION_STRING of include/qfoc/version.h.
#
# Package layout (qfoc-<version>/):
#   README.md CHANGELOG.md LICENSE NOTICE   the project's documents
#   CMakeLists.txt cmake/                   the CMake build and its Cortex-M4F toolchain file
#   include/ src/ specs/                    headers with contracts, sources, requirements and
#                                           specifications (the safety manual is
#                                           specs/safety-manual.md)
#   tables/                                 the generated parameter tables and their manifest
#   tools/tune/qfoc_tune.py                 the tuning tool (Python 3 with numpy, scipy and
#                                           matplotlib; it imports nothing of its own)
#   lib/cortex-m4f/libqfoc.a                the library for Cortex-M4F, and BUILDINFO.txt with
#                                           its compiler, flags and SHA-256 (checked against
#                                           build/repro/repro.json when make repro has run)
#   evidence/                               the verification evidence bundle
#   docs/ examples/                         when the repository has them
#   SHA256SUMS                              sha256sum of every other file of the package
#
# Only the files git tracks are packaged from the source trees (no build product, no
# editor file); outside a git work tree every file of those trees is.  The tarball is
# deterministic: names sorted, every mtime the commit time of the version (the last commit
# that changed include/qfoc/version.h; SOURCE_DATE_EPOCH overrides it), owner and group 0,
# modes 0644 / 0755, gzip without name or time stamp: two runs over the same inputs give
# the same bytes.  Prints the package's name, size, SHA-256 and file count.
set -eu
TOP=$(cd "$(dirname "$0")/../.." && pwd)
cd "$TOP"
ARM_LIB=${1:?usage: release.sh ARM_LIB EVIDENCE_DIR}
EVIDENCE=${2:?usage: release.sh ARM_LIB EVIDENCE_DIR}
DIST=${DIST:-dist}
STAGE_ROOT=${RELEASE_STAGE:-build/release}
PY=/usr/bin/python3
[ -x "$PY" ] || PY=python3

VERSION=$(sed -n 's/^#define QFOC_VERSION_STRING "\([0-9]*\.[0-9]*\.[0-9]*\)".*/\1/p' include/qfoc/version.h)
[ -n "$VERSION" ] || { echo "release: no QFOC_VERSION_STRING in include/qfoc/version.h"; exit 1; }
NAME=qfoc-$VERSION
[ -f "$ARM_LIB" ] || { echo "release: $ARM_LIB missing"; exit 1; }
[ -f "$EVIDENCE/index.html" ] && [ -f "$EVIDENCE/evidence.json" ] || {
    echo "release: no evidence bundle in $EVIDENCE (run make evidence after the gates)"; exit 1; }

if git rev-parse --is-inside-work-tree > /dev/null 2>&1; then
    in_git=1
else
    in_git=0
fi
if [ -n "${SOURCE_DATE_EPOCH:-}" ]; then
    EPOCH=$SOURCE_DATE_EPOCH
elif [ "$in_git" = 1 ] && [ -n "$(git log -1 --format=%ct -- include/qfoc/version.h)" ]; then
    EPOCH=$(git log -1 --format=%ct -- include/qfoc/version.h)
else
    EPOCH=0
fi

PKG=$STAGE_ROOT/$NAME
rm -rf "$STAGE_ROOT"
mkdir -p "$PKG" "$DIST"

# list_files PATH...: the tracked files under each path (every file outside git), sorted
list_files() {
    for d in "$@"; do
        [ -e "$d" ] || continue
        if [ "$in_git" = 1 ]; then
            git ls-files -- "$d"
        else
            find "$d" -type f
        fi
    done | LC_ALL=C sort -u
}

# copy_files PATH...: those files into the package, under the same paths
copy_files() {
    list_files "$@" | while IFS= read -r f; do
        [ -f "$f" ] || continue
        mkdir -p "$PKG/$(dirname "$f")"
        cp "$f" "$PKG/$f"
    done
}

copy_files README.md CHANGELOG.md LICENSE NOTICE CMakeLists.txt cmake include src specs tables \
           tools/tune/qfoc_tune.py docs examples
for f in README.md CHANGELOG.md LICENSE NOTICE CMakeLists.txt include/qfoc/version.h \
         specs/safety-manual.md tools/tune/qfoc_tune.py tables/reference_params.c; do
    [ -f "$PKG/$f" ] || { echo "release: $f is not in the package (not tracked by git?)"; exit 1; }
done

# the Cortex-M4F library with its build record
mkdir -p "$PKG/lib/cortex-m4f"
cp "$ARM_LIB" "$PKG/lib/cortex-m4f/libqfoc.a"
LIB_SHA=$(sha256sum "$PKG/lib/cortex-m4f/libqfoc.a" | cut -d' ' -f1)
{
    echo "qfoc $VERSION: lib/cortex-m4f/libqfoc.a"
    echo "sha256: $LIB_SHA"
    echo "compiler: $(arm-none-eabi-gcc --version | head -n 1)"
    echo "flags: ${ARM_CFLAGS:-}"
    echo "built from: src/*.c of this package, one object per source, arm-none-eabi-ar rcs"
    echo "reproducible: make repro builds it twice from the same sources and compares the bytes"
} > "$PKG/lib/cortex-m4f/BUILDINFO.txt"

# the same bytes as both builds of make repro (when it ran: make check runs it first)
REPRO_JSON=${REPRO_JSON:-build/repro/repro.json}
repro_note="make repro not run"
if [ -f "$REPRO_JSON" ]; then
    repro_sha=$("$PY" -c 'import json, sys
d = json.load(open(sys.argv[1]))
print(next((a["sha256"] for a in d["artefacts"] if a["file"] == "target/libqfoc.a" and a["identical"]), ""))' "$REPRO_JSON")
    if [ "$repro_sha" = "$LIB_SHA" ]; then
        repro_note="identical to both builds of make repro"
        echo "make repro: $repro_note ($REPRO_JSON)" >> "$PKG/lib/cortex-m4f/BUILDINFO.txt"
    else
        echo "release: libqfoc.a sha256 $LIB_SHA is not the one make repro built twice (${repro_sha:-none}): rebuild or run make repro again"
        exit 1
    fi
fi

# the evidence bundle, as make evidence wrote it (its red rows said here, packaged as they are)
red=$("$PY" -c 'import json, sys
print(json.load(open(sys.argv[1])).get("red", "?"))' "$EVIDENCE/evidence.json" 2>/dev/null || echo "?")
[ "$red" = 0 ] || echo "release: warning: the evidence bundle has $red red summary rows (run the gates, then make evidence)"
mkdir -p "$PKG/evidence"
cp -R "$EVIDENCE/." "$PKG/evidence/"

# normalised modes: directories and scripts 0755, other files 0644
find "$PKG" -type d -exec chmod 0755 {} +
find "$PKG" -type f -exec chmod 0644 {} +
find "$PKG" -type f \( -name '*.sh' -o -name '*.py' \) -exec chmod 0755 {} +

# SHA256SUMS over every other file, sorted by path
( cd "$PKG" && find . -type f ! -name SHA256SUMS | sed 's|^\./||' | LC_ALL=C sort | \
      while IFS= read -r f; do sha256sum "$f"; done > SHA256SUMS )
chmod 0644 "$PKG/SHA256SUMS"

TAR=$DIST/$NAME.tar.gz
find "$PKG" -exec touch -h -d "@$EPOCH" {} +
tar --sort=name --format=gnu --owner=0 --group=0 --numeric-owner --mtime="@$EPOCH" \
    -C "$STAGE_ROOT" -cf - "$NAME" | gzip -n -9 > "$TAR.tmp"
mv "$TAR.tmp" "$TAR"
sha256sum "$TAR" | sed 's|  .*/|  |' > "$TAR.sha256"
files=$(wc -l < "$PKG/SHA256SUMS")
size=$(wc -c < "$TAR")
echo "release: $TAR ($size B, $((files + 1)) files, version $VERSION, mtime $(date -u -d "@$EPOCH" '+%Y-%m-%d %H:%M:%S UTC'))"
echo "release: sha256 $(cut -d' ' -f1 "$TAR.sha256"); libqfoc.a (Cortex-M4F) sha256 $LIB_SHA ($repro_note)"
