#!/bin/sh
# tools/release/check_gate.sh -- the release gate of make check (tools/gates/check.sh runs it
# after the evidence gate; make release-gate).
#
# 1. make release's refusals, seeded (tools/release/tests/release_test.sh).
# 2. The release of this checkout, without weakening make release's refusal:
#    - the gates of make check rewrite result files that are committed with the sources:
#      make prove writes proofs/wp/results.md (a new "Run:" line), proofs/wp/times.txt (the
#      wall times of its jobs) and proofs/wp/inputs-wp.sha256, make cbmc proofs/cbmc/results.md
#      and proofs/cbmc/inputs-cbmc.sha256.  After a full run the working tree is therefore
#      never clean, even on a clean clone, and make evidence records it as "working tree
#      modified": make release refuses both;
#    - when git status lists nothing: make release and make release-check here;
#    - when it lists anything besides those result files (a source, a test, an untracked
#      file): the gate runs make release, which refuses and says why, and fails;
#    - when it lists those result files only: the gate does what a maintainer does after a
#      clean-clone run.  In a clone of HEAD in a temporary directory (build/ a link to this
#      checkout's build/, so the gates' results are the ones of this run), the rewritten
#      results are committed on top of HEAD; make evidence (strict) writes the bundle of that
#      commit to build/release-gate/evidence; make release (which refuses as ever, and here
#      finds a clean tree and green evidence of its HEAD) and make release-check run there;
#      the package is copied to dist/.  Its RELEASE.txt names that commit and its subject
#      names HEAD: the package is HEAD's sources with the results of this run.
# Exit status 0 when the package was made and passed release-check.
set -u
TOP=$(cd "$(dirname "$0")/../.." && pwd)
cd "$TOP" || exit 1
RESULTS="proofs/wp/results.md proofs/wp/times.txt proofs/wp/inputs-wp.sha256 proofs/cbmc/results.md proofs/cbmc/inputs-cbmc.sha256"
MK="make --no-print-directory"

sh tools/release/tests/release_test.sh || { echo "release-gate: the refusal tests failed"; exit 1; }

# 3. The store of WP's prover results (REQ-EVD-032): make release wants the one a full run
#    (make prove-full) wrote over these very sources.  A commit that changed a proof source
#    since is not releasable until then; the gate still checks its packaging, as a candidate
#    (QFOC_RELEASE_CANDIDATE=1: its RELEASE.txt says "CANDIDATE, not for production"), and
#    says so.
mkdir -p build
if /usr/bin/python3 tools/gates/wp_cache.py full-check proofs/wp/cache.txt > build/release-gate-wpstore.txt 2>&1; then
    echo "release-gate: $(tail -n 1 build/release-gate-wpstore.txt | sed 's/^wp_cache: //')"
else
    sed 's/^wp_cache: /release-gate: /' build/release-gate-wpstore.txt | head -n 12
    echo "release-gate: HEAD can be released only as a candidate until make prove-full re-proves the store; its packaging is checked as one"
    QFOC_RELEASE_CANDIDATE=1
    export QFOC_RELEASE_CANDIDATE
fi

changes=$(git status --porcelain=v1 --untracked-files=all -- . ':(top,exclude)build' ':(top,exclude)dist')
if [ -z "$changes" ]; then
    echo "release-gate: the working tree is clean: make release here"
    $MK release && $MK release-check
    exit $?
fi

results=""
others=""
nl='
'
IFS_SAVE=$IFS
IFS=$nl
set -f
for line in $changes; do
    code=$(printf '%s' "$line" | cut -c1-2)
    path=$(printf '%s' "$line" | cut -c4-)
    case " $RESULTS " in
        *" $path "*)
            if [ "$code" = " M" ]; then results="$results $path"; else others="$others$nl$line"; fi ;;
        *) others="$others$nl$line" ;;
    esac
done
set +f
IFS=$IFS_SAVE

if [ -n "$others" ]; then
    echo "release-gate: the working tree has changes besides the results the gates rewrote ($RESULTS):"
    printf '%s\n' "$others" | sed '/^$/d; s/^/  /'
    echo "release-gate: no release can be made from it; make release says:"
    $MK release
    echo "release-gate: FAILED (commit or remove those changes, then make check again)"
    exit 1
fi

head=$(git rev-parse HEAD)
short=$(git rev-parse --short HEAD)
echo "release-gate: the gates rewrote$results; the tree is otherwise HEAD ($short)"
echo "release-gate: releasing HEAD with these results committed on top, in a clone of HEAD"
WORK=$(mktemp -d "${TMPDIR:-/tmp}/qfoc-release-gate.XXXXXX")
trap 'rm -rf "$WORK"' EXIT INT TERM
CLONE=$WORK/qfoc
git clone --quiet --shared --no-checkout "$TOP" "$CLONE" || { echo "release-gate: git clone failed"; exit 1; }
git -C "$CLONE" checkout --quiet --detach "$head" || { echo "release-gate: checkout of $head failed"; exit 1; }
for f in $results; do
    cp "$f" "$CLONE/$f"
done
# shellcheck disable=SC2086
git -C "$CLONE" add -- $results
git -C "$CLONE" -c user.name="qfoc make check" -c user.email="make-check@localhost" \
    -c commit.gpgsign=false commit --quiet \
    -m "The results make check wrote on $short ($(echo "$results" | sed 's/^ //; s/ /, /g'))" \
    -m "On top of $head: the same sources, the proof results of the run that checked them." ||
    { echo "release-gate: commit in the clone failed"; exit 1; }
ln -s "$TOP/build" "$CLONE/build"
EVD=build/release-gate/evidence
rm -rf "${TOP:?}/$EVD"
( cd "$CLONE" &&
  $MK evidence EVIDENCE_DIR=$EVD EVIDENCE_STRICT=1 > "$TOP/build/release-gate-evidence.log" 2>&1 ||
      { cat "$TOP/build/release-gate-evidence.log"; echo "release-gate: the evidence of the results commit is not green"; exit 1; }
  tail -n 1 "$TOP/build/release-gate-evidence.log"
  $MK release EVIDENCE_DIR=$EVD && $MK release-check ) || exit 1
mkdir -p dist
cp "$CLONE"/dist/qfoc-*.tar.gz "$CLONE"/dist/qfoc-*.tar.gz.sha256 dist/
echo "release-gate: $(ls dist/qfoc-*.tar.gz) = HEAD $short + the results of this run (commit $(git -C "$CLONE" rev-parse --short HEAD) in the package's RELEASE.txt); evidence in $EVD"
