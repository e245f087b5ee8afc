#!/bin/sh
# tools/release/release.sh -- the release package dist/qfoc-<version>.tar.gz (make release).
#
#   sh tools/release/release.sh ARM_LIB EVIDENCE_DIR
#
# ARM_LIB is the Cortex-M4F libqfoc.a built by the Makefile with its ARM_CFLAGS, EVIDENCE_DIR
# the bundle of `make evidence`.  The environment passes the Makefile's flags (WARN, CFLAGS,
# ARM_CFLAGS), which the package's own Makefile and BUILDINFO.txt record.  The version is
# QFOC_VERSION_STRING of include/qfoc/version.h.
#
# Refusal first (tools/release/release_ready.py tree): nothing is packaged, exit 1, every
# reason printed, unless the working tree is a clean git checkout (git status empty, untracked
# files included; build/ and dist/ set aside) and the evidence bundle is of HEAD, made in a
# clean tree, every summary row green (no result missing, failed or STALE), its stamped
# results still current, its MANIFEST.sha256 intact.
#
# Package layout (qfoc-<version>/):
#   README.md Makefile                      the package's own (tools/release/pkg/): what is
#                                           inside, what it needs, how to build it; the
#                                           Makefile builds the host and Cortex-M4F libraries,
#                                           the example and the S32K144 image from this tree
#   RELEASE.txt                             version, commit, commit date, the evidence's summary
#   CHANGELOG.md LICENSE NOTICE             the project's documents
#   CMakeLists.txt cmake/                   the CMake build and its Cortex-M4F toolchain file
#   include/ src/ specs/                    headers with contracts, sources, requirements and
#                                           specifications (the safety manual is
#                                           specs/safety-manual.md)
#   tables/                                 the generated parameter tables and their manifest
#   tools/tune/qfoc_tune.py                 the tuning tool (Python 3 with numpy and scipy,
#                                           matplotlib for the plots; it imports nothing of
#                                           its own)
#   docs/                                   the porting guide, the motor-file format
#   docs/api/                               the API reference (make docs: doxygen HTML of
#                                           include/qfoc/, 0 warnings)
#   port_s32k/ misra/                       the S32K144 reference port; the MISRA records
#   examples/host_minimal.c                 the integration example the package builds
#   lib/cortex-m4f/libqfoc.a                the library for Cortex-M4F, and BUILDINFO.txt with
#                                           its compiler, flags and SHA-256 (checked against
#                                           build/repro/repro.json when make repro has run)
#   evidence/                               the verification evidence bundle of the commit
#   SHA256SUMS                              sha256sum of every other file of the package
#
# Only the files git tracks are packaged (no build product, no editor file).  The tarball is
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

# the refusal: a clean checkout of HEAD and green evidence of it, or nothing
"$PY" tools/release/release_ready.py tree --root "$TOP" --evidence "$EVIDENCE" || exit 1

VERSION=$(sed -n 's/^#define QFOC_VERSION_STRING "\([0-9]*\.[0-9]*\.[0-9]*\)".*/\1/p' include/qfoc/version.h)
[ -n "$VERSION" ] || { echo "release: no QFOC_VERSION_STRING in include/qfoc/version.h"; exit 1; }
NAME=qfoc-$VERSION
[ -f "$ARM_LIB" ] || { echo "release: $ARM_LIB missing"; exit 1; }
[ -f "$EVIDENCE/index.html" ] || { echo "release: no index.html in the evidence bundle $EVIDENCE"; exit 1; }
: "${ARM_CFLAGS:?release: ARM_CFLAGS not set (run make release)}"
: "${CFLAGS:?release: CFLAGS not set (run make release)}"
: "${WARN:?release: WARN not set (run make release)}"

COMMIT=$(git rev-parse HEAD)
if [ -n "${SOURCE_DATE_EPOCH:-}" ]; then
    EPOCH=$SOURCE_DATE_EPOCH
elif [ -n "$(git log -1 --format=%ct -- include/qfoc/version.h)" ]; then
    EPOCH=$(git log -1 --format=%ct -- include/qfoc/version.h)
else
    EPOCH=0
fi

PKG=$STAGE_ROOT/$NAME
rm -rf "$STAGE_ROOT"
mkdir -p "$PKG" "$DIST"

# copy_files PATH...: the tracked files under each path into the package, same paths
copy_files() {
    for d in "$@"; do
        [ -e "$d" ] || continue
        git ls-files -- "$d"
    done | LC_ALL=C sort -u | while IFS= read -r f; do
        [ -f "$f" ] || continue
        mkdir -p "$PKG/$(dirname "$f")"
        cp "$f" "$PKG/$f"
    done
}

copy_files CHANGELOG.md LICENSE NOTICE CMakeLists.txt cmake include src specs tables \
           tools/tune/qfoc_tune.py docs examples/host_minimal.c port_s32k misra
for f in CHANGELOG.md LICENSE NOTICE CMakeLists.txt include/qfoc/version.h \
         specs/safety-manual.md tools/tune/qfoc_tune.py tables/reference_params.c \
         tables/manifest.txt examples/host_minimal.c port_s32k/README.md port_s32k/s32k144.ld \
         misra/deviations.md docs/porting.md; do
    [ -f "$PKG/$f" ] || { echo "release: $f is not in the package (not tracked by git?)"; exit 1; }
done

# the API reference, as make docs built it from these headers
DOCS_HTML=${DOCS_HTML:-build/docs/html}
[ -f "$DOCS_HTML/index.html" ] || { echo "release: no API reference in $DOCS_HTML (make docs)"; exit 1; }
mkdir -p "$PKG/docs/api"
cp -R "$DOCS_HTML/." "$PKG/docs/api/"

# the package's own README and Makefile, with the version and the Makefile's flags
# subst TEMPLATE OUT: @VERSION@, @VERSION_MM@, @WARN@, @CFLAGS@, @ARM_CFLAGS@ replaced
subst() {
    VERSION=$VERSION WARN=$WARN CFLAGS=$CFLAGS ARM_CFLAGS=$ARM_CFLAGS "$PY" -c '
import os, re, sys
text = open(sys.argv[1], encoding="utf-8").read()
v = os.environ["VERSION"]
for key, val in (("@VERSION_MM@", ".".join(v.split(".")[:2])), ("@VERSION@", v),
                 ("@WARN@", os.environ["WARN"]), ("@CFLAGS@", os.environ["CFLAGS"]),
                 ("@ARM_CFLAGS@", os.environ["ARM_CFLAGS"])):
    text = text.replace(key, " ".join(val.split()))
left = re.findall(r"@[A-Z_]+@", text)
if left:
    sys.exit("release: placeholders left in " + sys.argv[1] + ": " + " ".join(left))
open(sys.argv[2], "w", encoding="utf-8").write(text)' "$1" "$2"
}
subst tools/release/pkg/README.md "$PKG/README.md"
subst tools/release/pkg/Makefile "$PKG/Makefile"

# the Cortex-M4F library with its build record
mkdir -p "$PKG/lib/cortex-m4f"
cp "$ARM_LIB" "$PKG/lib/cortex-m4f/libqfoc.a"
LIB_SHA=$(sha256sum "$PKG/lib/cortex-m4f/libqfoc.a" | cut -d' ' -f1)
{
    echo "qfoc $VERSION: lib/cortex-m4f/libqfoc.a"
    echo "sha256: $LIB_SHA"
    echo "commit: $COMMIT"
    echo "compiler: $(arm-none-eabi-gcc --version | head -n 1)"
    # shellcheck disable=SC2086
    echo "flags:" $ARM_CFLAGS
    echo "built from: src/*.c of this package, one object per source, arm-none-eabi-ar rcs (make target)"
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

# the evidence bundle, as make evidence wrote it (green: release_ready.py checked it)
mkdir -p "$PKG/evidence"
cp -R "$EVIDENCE/." "$PKG/evidence/"
rows=$("$PY" -c 'import json, sys
d = json.load(open(sys.argv[1]))
print("%s of %s summary rows green, made %s" % (d["green"], len(d["summary"]), d["date"]))' "$EVIDENCE/evidence.json")

# the provenance of the prover verdicts the proofs replayed (REQ-EVD-032): a production
# release needs the store of a full run over these sources (release_ready.py refused the
# tree otherwise); a candidate (QFOC_RELEASE_CANDIDATE=1) says that it is one
full_run=$(sed -n 's/^# last full run (make prove-full, no entry read): \(.*\)$/\1/p' proofs/wp/cache.txt)
if "$PY" tools/gates/wp_cache.py full-check proofs/wp/cache.txt > "$STAGE_ROOT/wp-store.txt" 2>&1; then
    proofs="proofs: every WP prover verdict replayed comes from the full run of ${full_run:-?} over these sources and tools (proofs/wp/cache.txt)"
elif [ "${QFOC_RELEASE_CANDIDATE:-0}" = 1 ]; then
    n=$(grep -c '^  ' "$STAGE_ROOT/wp-store.txt" || true)
    proofs="status: CANDIDATE, not for production: the WP prover results replayed (proofs/wp/cache.txt) were last proved in full on ${full_run:-no record} over other sources or tools ($n difference(s)); a release needs make prove-full first"
else
    cat "$STAGE_ROOT/wp-store.txt"
    echo "release: the WP prover results are not those of a full run over these sources: make prove-full"
    exit 1
fi
rm -f "$STAGE_ROOT/wp-store.txt"

# what the release is
{
    echo "qfoc $VERSION"
    echo "commit: $COMMIT"
    echo "commit date: $(git log -1 --format=%cI "$COMMIT")"
    echo "subject: $(git log -1 --format=%s "$COMMIT")"
    echo "evidence: evidence/index.html, of commit $COMMIT in a clean tree: $rows"
    echo "library: lib/cortex-m4f/libqfoc.a sha256 $LIB_SHA"
    echo "$proofs"
} > "$PKG/RELEASE.txt"

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
