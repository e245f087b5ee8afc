#!/bin/sh
# tools/gates/quickstart.sh -- the quick start of README.md on a fresh clone (make quickstart;
# the demo gate of make check).
#
# A new user clones the repository and types the commands at the top of README.md.  This
# test does the same, in a clone of HEAD in a temporary directory (the committed state: what
# a user gets), and checks what each command must leave behind:
#   make demo                   exit 0; build/demo/index.html with every scenario's page
#                               and no target missed (demo_report.py's verdict is its exit);
#   make lib                    build/host/libqfoc.a;
#   make tune MOTOR=specs/motors/reference.toml
#                               exit 0; the table it writes is the committed one, byte for
#                               byte (the clone stays clean: git status lists nothing);
# and that these light targets stay light: none of them made the verification chain's
# targets (deps, deps-trixie: Frama-C, CBMC, cppcheck, the trixie chroot), as `make --trace`
# shows the targets make updated.  The demo's pages and results are copied to build/demo/,
# where make demo writes them (the evidence bundle reads the scenarios' results there).
#
# Exit status 0 when every check passed; 1 otherwise, each failure named.
set -u
TOP=$(cd "$(dirname "$0")/../.." && pwd)
cd "$TOP" || exit 1
OUT=build/quickstart
rm -rf "$OUT"
mkdir -p "$OUT"
tmp=$(mktemp -d "${TMPDIR:-/tmp}/qfoc-quickstart.XXXXXX") || exit 1
trap 'rm -rf "$tmp"' EXIT
fail=0
bad() { echo "quickstart: FAIL: $*"; fail=1; }

head=$(git rev-parse --short HEAD) || exit 1
git clone -q --no-local "$TOP" "$tmp/qfoc" || { echo "quickstart: cannot clone $TOP"; exit 1; }
git -C "$tmp/qfoc" checkout -q "$(git rev-parse HEAD)" || exit 1
echo "quickstart: a fresh clone of $head in $tmp/qfoc"

# step NAME COMMAND...: run it in the clone with make's trace, its log in $OUT/NAME.log
step() {
    name=$1
    shift
    t0=$(date +%s)
    (cd "$tmp/qfoc" && "$@") > "$OUT/$name.log" 2>&1
    rc=$?
    echo "quickstart: $* -> exit $rc ($(( $(date +%s) - t0 )) s)"
    [ "$rc" = 0 ] || { bad "'$*' exited $rc (log $OUT/$name.log):"; tail -n 15 "$OUT/$name.log"; }
    # the verification chain's installers must not have run
    if grep -E "update target '(deps|deps-trixie)'|target '(deps|deps-trixie)' does not exist" \
            "$OUT/$name.log" > /dev/null; then
        bad "'$*' made the verification chain's installer (deps): a light target must not"
    fi
}

step demo make --no-print-directory --trace demo
for f in index.html cold_start/index.html; do
    [ -s "$tmp/qfoc/build/demo/$f" ] || bad "make demo wrote no build/demo/$f"
done
# the demo's results are the demo gate's, where make demo writes them (the evidence reads
# build/demo/<scenario>/metrics.json): the clone is HEAD, the tree make check verifies
if [ -d "$tmp/qfoc/build/demo" ]; then
    rm -rf build/demo
    cp -r "$tmp/qfoc/build/demo" build/demo
fi

step lib make --no-print-directory --trace lib
[ -s "$tmp/qfoc/build/host/libqfoc.a" ] || bad "make lib wrote no build/host/libqfoc.a"

step tune make --no-print-directory --trace tune MOTOR=specs/motors/reference.toml
dirty=$(git -C "$tmp/qfoc" status --porcelain --untracked-files=all -- . ':!build' ':!dist')
if [ -n "$dirty" ]; then
    bad "the quick start left the clone modified (the regenerated table is not the committed one?):"
    echo "$dirty"
fi

if [ "$fail" = 0 ]; then
    echo "quickstart: make demo, make lib and make tune pass on a fresh clone of $head, without the verification chain"
fi
exit "$fail"
