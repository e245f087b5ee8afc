#!/bin/sh
# tools/release/tests/release_test.sh -- make release's refusals, each seeded in a temporary
# repository (make release-test; the first step of make check's release gate).
#
# The repository under test is this checkout's files as they are (tracked and untracked,
# not ignored), committed into a fresh git repository in a temporary directory; each case
# clones it, seeds one defect and runs `make release` (or tools/release/release_ready.py
# for the cases where make release would go on to build): the exit status and the reason
# printed are checked against what the case expects, and a refused make release must have
# built and packaged nothing (no build/target/, no dist/).
#
# Evidence bundles: "real" ones are written by tools/evidence/evidence.py in the case's
# repository, which has run no gate (every result "not run"; a committed proof result made
# stale by a source change); "green" ones are written here (evidence.json with every summary
# row PASS, of the commit and tree state the case names, index.html, MANIFEST.sha256), since
# a green bundle needs every gate of make check to have run.
#
# Prints one line per case (ok / FAIL) and "release-test: N passed, M failed"; exit 1 when a
# case fails.
set -u
TOP=$(cd "$(dirname "$0")/../../.." && pwd)
PY=/usr/bin/python3
[ -x "$PY" ] || PY=python3
T=$(mktemp -d "${TMPDIR:-/tmp}/qfoc-release-test.XXXXXX")
trap 'rm -rf "$T"' EXIT INT TERM
MK="make --no-print-directory"
GIT="git -c user.name=release-test -c user.email=release-test@localhost -c commit.gpgsign=false"
passed=0
failed=0

# the base repository: the checkout's files, one commit
BASE=$T/base
mkdir -p "$BASE"
( cd "$TOP" && git ls-files -z --cached --others --exclude-standard ) |
    ( cd "$TOP" && tar --null --ignore-failed-read -T - -cf - 2> /dev/null ) | tar -xf - -C "$BASE"
rm -rf "$BASE/build" "$BASE/dist"
# its store of WP prover results as a full run over its sources would have left it (the
# cases below that need another store seed it)
( cd "$BASE" && { grep '^#' proofs/wp/cache.txt | grep -v '^# full run over: \|^# last full run\|^# updated by'
                  echo "# last full run (make prove-full, no entry read): release-test, 0 prover calls"
                  "$PY" tools/gates/wp_cache.py sources | sed 's/^/# full run over: /'
                  grep -v '^#' proofs/wp/cache.txt; } > cache.tmp && mv cache.tmp proofs/wp/cache.txt ) ||
    { echo "release-test: cannot record a full run in the base repository"; exit 1; }
( cd "$BASE" && git init --quiet && $GIT add -A && $GIT commit --quiet -m "the tree under test" ) ||
    { echo "release-test: cannot make the base repository"; exit 1; }

# case NAME: a fresh clone of the base in $R
case_repo() {
    R=$T/$1
    git clone --quiet --shared "$BASE" "$R" || { echo "release-test: clone failed"; exit 1; }
}

# green_bundle DIR COMMIT DIRTY(true|false|null) [SECTIONS_JSON]: a bundle with every summary
# row green (and those sections in evidence.json)
green_bundle() {
    "$PY" - "$@" <<'EOF'
import hashlib, json, os, sys
out, commit, dirty = sys.argv[1], sys.argv[2], {"true": True, "false": False, "null": None}[sys.argv[3]]
os.makedirs(out, exist_ok=True)
rows = [{"key": k, "label": k, "status": "PASS", "figure": "seeded"} for k in ("wp", "cbmc", "tests")]
data = {"generated_by": "release_test.sh", "date": "2026-01-01 00:00:00 UTC",
        "commit": {"commit": commit, "dirty": dirty, "branch": None},
        "summary": rows, "green": len(rows), "red": 0, "sections": {}}
if len(sys.argv) > 4:
    data["sections"] = json.loads(sys.argv[4])
with open(os.path.join(out, "evidence.json"), "w") as f:
    json.dump(data, f, indent=1)
with open(os.path.join(out, "index.html"), "w") as f:
    f.write("<p>seeded</p>\n")
rows = []
for root, dirs, files in os.walk(out):
    for fn in files:
        rel = os.path.relpath(os.path.join(root, fn), out)
        if rel != "MANIFEST.sha256":
            rows.append((rel, hashlib.sha256(open(os.path.join(root, fn), "rb").read()).hexdigest()))
with open(os.path.join(out, "MANIFEST.sha256"), "w") as f:
    for rel, h in sorted(rows):
        f.write(f"{h}  {rel}\n")
EOF
}

# expect NAME STATUS OUTPUT_FILE PATTERN...: the status and every (grep -E) pattern in the
# output; STATUS "refused" is a refused make release: make's 2 and the recipe's "Error 1"
expect() {
    name=$1; want=$2; got=$3; out=$4; shift 4
    ok=1
    if [ "$want" = refused ]; then
        want=2
        set -- "$@" "release: nothing packaged" "\] Error 1\$"
    fi
    [ "$got" = "$want" ] || { ok=0; echo "  $name: exit status $got, expected $want"; }
    for p in "$@"; do
        grep -Eq -- "$p" "$out" || { ok=0; echo "  $name: no line matching: $p"; }
    done
    if [ "$ok" = 1 ]; then
        passed=$((passed + 1)); echo "ok    $name"
    else
        failed=$((failed + 1)); echo "FAIL  $name"; sed 's/^/  | /' "$out" | head -n 40
    fi
}

# nothing_built NAME: a refused make release built and packaged nothing
nothing_built() {
    if [ -e "$R/build/target" ] || [ -e "$R/dist" ] || [ -e "$R/build/release" ]; then
        failed=$((failed + 1)); echo "FAIL  $1: make release built or packaged something although it refused"
    else
        passed=$((passed + 1)); echo "ok    $1"
    fi
}

# release OUT: make release in $R, status in $rc; make's own status for a failed recipe is 2,
# and it names the recipe's status: "Error 1" is the refusal of release_ready.py.  (Should a
# refusal be missed, deps finds the tool chain of this checkout instead of installing one.)
release() {
    ( cd "$R" && CBMC_PREFIX=${CBMC_PREFIX:-$TOP/build/tools/cbmc} $MK release > "$1" 2>&1 ); rc=$?
}

# 1. a tracked source modified (evidence green and of HEAD: the tree alone is the reason)
case_repo modified
green_bundle "$R/build/evidence" "$(git -C "$R" rev-parse HEAD)" false
echo "/* an edit not committed */" >> "$R/src/qfoc_version.c"
release "$T/modified.out"
expect "modified tracked file refused" refused "$rc" "$T/modified.out" \
    "release: refused: the working tree is not clean" "modified: src/qfoc_version.c" \
    "release: nothing packaged"
if grep -q "not green" "$T/modified.out"; then
    failed=$((failed + 1)); echo "FAIL  modified tracked file: a green bundle called red"
fi
nothing_built "modified tracked file: nothing built"

# 2. an untracked file under a tracked directory (src/*.c is taken by wildcard)
case_repo untracked
green_bundle "$R/build/evidence" "$(git -C "$R" rev-parse HEAD)" false
echo "int qfoc_extra;" > "$R/src/qfoc_extra.c"
release "$T/untracked.out"
expect "untracked file under src/ refused" refused "$rc" "$T/untracked.out" \
    "release: refused: the working tree is not clean" "untracked: src/qfoc_extra.c"
nothing_built "untracked file: nothing built"

# 3. a file added to the index but not committed, and a tracked file deleted
case_repo staged
green_bundle "$R/build/evidence" "$(git -C "$R" rev-parse HEAD)" false
echo "note" > "$R/docs/note.md" && git -C "$R" add docs/note.md && rm "$R/NOTICE"
release "$T/staged.out"
expect "staged and deleted files refused" refused "$rc" "$T/staged.out" \
    "added, not committed: docs/note.md" "deleted: NOTICE" "2 paths"

# 4. build/ and dist/ are set aside: files there do not make the tree modified
case_repo aside
green_bundle "$R/build/evidence" "$(git -C "$R" rev-parse HEAD)" false
mkdir -p "$R/build/x" "$R/dist" && echo x > "$R/build/x/y.o" && echo x > "$R/dist/old.tar.gz"
( cd "$R" && "$PY" tools/release/release_ready.py tree > "$T/aside.out" 2>&1 ); rc=$?
expect "build/ and dist/ set aside, green evidence of HEAD accepted" 0 "$rc" "$T/aside.out" \
    "release: tree clean at [0-9a-f]{40}; evidence build/evidence: commit [0-9a-f]{40}, 3 of 3 summary rows green"

# 4a. the WP store of no full run (REQ-EVD-032): refused, every other reason absent
case_repo nofull
sed -i '/^# full run over: /d' "$R/proofs/wp/cache.txt" && ( cd "$R" && $GIT commit --quiet -am "store without its record" )
green_bundle "$R/build/evidence" "$(git -C "$R" rev-parse HEAD)" false
( cd "$R" && "$PY" tools/release/release_ready.py tree > "$T/nofull.out" 2>&1 ); rc=$?
expect "WP store without a full run refused" 1 "$rc" "$T/nofull.out" \
    "release: refused: the WP prover results of proofs/wp/cache.txt were not all proved by one full run" \
    "records no full run over named sources"

# 4b. a proof source changed (and committed) since the store's full run: refused, the file
#     named; as a candidate (QFOC_RELEASE_CANDIDATE=1) accepted, and said to be one
case_repo srcchanged
echo "/* a comment committed after the full run */" >> "$R/include/qfoc/version.h"
( cd "$R" && $GIT commit --quiet -am "a header changed" )
green_bundle "$R/build/evidence" "$(git -C "$R" rev-parse HEAD)" false
( cd "$R" && "$PY" tools/release/release_ready.py tree > "$T/srcchanged.out" 2>&1 ); rc=$?
expect "proof source changed since the full run refused" 1 "$rc" "$T/srcchanged.out" \
    "were not all proved by one full run over this tree's proof sources and tools \(1 difference\)" \
    "include/qfoc/version.h: changed since the last full run"
( cd "$R" && QFOC_RELEASE_CANDIDATE=1 "$PY" tools/release/release_ready.py tree > "$T/candidate.out" 2>&1 ); rc=$?
expect "the same tree as a candidate accepted, and said to be one" 0 "$rc" "$T/candidate.out" \
    "release: candidate \(QFOC_RELEASE_CANDIDATE=1\), not for production" \
    "include/qfoc/version.h: changed since the last full run" "release: tree clean at [0-9a-f]{40}"

# 5. no evidence bundle
case_repo none
release "$T/none.out"
expect "no evidence bundle refused" refused "$rc" "$T/none.out" \
    "release: refused: no evidence bundle in build/evidence"
nothing_built "no evidence bundle: nothing built"

# 6. a real bundle of a repository where no gate ran: red rows ("not run")
case_repo red
( cd "$R" && $MK evidence > "$T/red-evidence.out" 2>&1 )
release "$T/red.out"
expect "red evidence (gates not run) refused" refused "$rc" "$T/red.out" \
    "release: refused: the evidence bundle build/evidence is not green: [0-9]+ of [0-9]+ summary rows red" \
    "FAIL +EVA runtime-error alarms: not run" "FAIL +tests passed: not run"
if grep -q "working tree is not clean" "$T/red.out"; then
    failed=$((failed + 1)); echo "FAIL  red evidence: the clean tree called modified"
fi
nothing_built "red evidence: nothing built"

# 7. a real stale bundle: a WP input changed and committed after the committed proof results
case_repo stale
echo "/* changed after the proofs ran */" >> "$R/src/qfoc_version.c"
$GIT -C "$R" commit --quiet -am "a source changed after the proofs"
( cd "$R" && $MK evidence > "$T/stale-evidence.out" 2>&1 )
release "$T/stale.out"
expect "stale evidence refused" refused "$rc" "$T/stale.out" \
    "STALE +WP goals proved: .*STALE" "STALE +CBMC properties: .*STALE"

# 8. a green bundle of another commit
case_repo other
green_bundle "$R/build/evidence" "$(git -C "$R" rev-parse HEAD)" false
echo "/* next commit */" >> "$R/src/qfoc_version.c"
$GIT -C "$R" commit --quiet -am "a commit after the evidence"
release "$T/other.out"
expect "evidence of another commit refused" refused "$rc" "$T/other.out" \
    "the evidence bundle build/evidence is of commit [0-9a-f]{40}, not [0-9a-f]{40}"

# 9. a green bundle made in a modified working tree
case_repo dirty
green_bundle "$R/build/evidence" "$(git -C "$R" rev-parse HEAD)" true
release "$T/dirty.out"
expect "evidence of a modified tree refused" refused "$rc" "$T/dirty.out" \
    "was made in a modified working tree \(evidence.json: working tree modified\)"

# 10. a green bundle edited after it was written
case_repo edited
green_bundle "$R/build/evidence" "$(git -C "$R" rev-parse HEAD)" false
echo "<p>edited</p>" >> "$R/build/evidence/index.html"
release "$T/edited.out"
expect "evidence edited after MANIFEST.sha256 refused" refused "$rc" "$T/edited.out" \
    "does not match its MANIFEST.sha256" "changed since MANIFEST.sha256 was written: index.html"

# 11. a green bundle that took a result as current which is stale now
case_repo stalenow
echo "/* changed after the proofs ran */" >> "$R/src/qfoc_version.c"
$GIT -C "$R" commit --quiet -am "a source changed after the proofs"
green_bundle "$R/build/evidence" "$(git -C "$R" rev-parse HEAD)" false \
    '{"wp": {"stamp": {"state": "current", "gate": "wp", "file": "proofs/wp/results.md"}}}'
release "$T/stalenow.out"
expect "a result stale now refused" refused "$rc" "$T/stalenow.out" \
    "stale now" "STALE wp: proofs/wp/results.md is stale now"

# 12. not a git work tree
mkdir -p "$T/nogit"
( cd "$BASE" && git ls-files -z | tar --null -T - -cf - ) | tar -xf - -C "$T/nogit"
green_bundle "$T/nogit/build/evidence" 0000000000000000000000000000000000000000 false
( cd "$T/nogit" && GIT_CEILING_DIRECTORIES=$T $MK release > "$T/nogit.out" 2>&1 ); rc=$?
expect "not a git work tree refused" refused "$rc" "$T/nogit.out" "is not a git work tree with a commit"

# 13 .. 16. an unpacked package: its evidence against the commit of its RELEASE.txt
P=$T/pkg/qfoc-0.0.0
mkdir -p "$P"
printf 'qfoc 0.0.0\ncommit: %s\n' 1111111111111111111111111111111111111111 > "$P/RELEASE.txt"
green_bundle "$P/evidence" 1111111111111111111111111111111111111111 false
"$PY" "$TOP/tools/release/release_ready.py" package "$P" > "$T/pkg-ok.out" 2>&1; rc=$?
expect "package: green evidence of its commit accepted" 0 "$rc" "$T/pkg-ok.out" \
    "release-check: evidence/ of commit 1111111111111111111111111111111111111111"
printf 'qfoc 0.0.0\ncommit: %s\n' 2222222222222222222222222222222222222222 > "$P/RELEASE.txt"
"$PY" "$TOP/tools/release/release_ready.py" package "$P" > "$T/pkg-other.out" 2>&1; rc=$?
expect "package: evidence of another commit refused" 1 "$rc" "$T/pkg-other.out" \
    "release-check: refused: the evidence bundle evidence is of commit 1111111111111111111111111111111111111111, not 2222222222222222222222222222222222222222"
rm "$P/RELEASE.txt"
"$PY" "$TOP/tools/release/release_ready.py" package "$P" > "$T/pkg-norel.out" 2>&1; rc=$?
expect "package: no RELEASE.txt refused" 1 "$rc" "$T/pkg-norel.out" "RELEASE.txt missing"
printf 'qfoc 0.0.0\ncommit: %s\n' 1111111111111111111111111111111111111111 > "$P/RELEASE.txt"
"$PY" - "$P/evidence/evidence.json" <<'EOF'
import json, sys
d = json.load(open(sys.argv[1]))
d["summary"][1].update(status="FAIL", stale=True, figure="44 harnesses; STALE: inputs changed")
d["green"], d["red"] = 2, 1
json.dump(d, open(sys.argv[1], "w"), indent=1)
EOF
"$PY" "$TOP/tools/release/release_ready.py" package "$P" > "$T/pkg-red.out" 2>&1; rc=$?
expect "package: a stale row refused (and the bundle no longer its MANIFEST)" 1 "$rc" "$T/pkg-red.out" \
    "is not green: 1 of 3 summary rows red" "STALE cbmc: 44 harnesses; STALE: inputs changed" \
    "changed since MANIFEST.sha256 was written: evidence.json"

echo "release-test: $passed passed, $failed failed"
[ "$failed" = 0 ]
