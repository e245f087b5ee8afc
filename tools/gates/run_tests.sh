#!/bin/sh
# tools/gates/run_tests.sh TEST_BIN... -- run CMocka test executables, print each one's
# report, and close with the totals line 'N passed, N failed'.  Exit 1 on any failure.
# Each executable's output is kept in build/junit/raw/ and converted to JUnit XML in
# build/junit/ (tools/gates/junit.py).
set -u
# Debian's interpreter (a python3 earlier on PATH may lack the packages)
PY=/usr/bin/python3
[ -x "$PY" ] || PY=python3
JDIR=build/junit
mkdir -p "$JDIR/raw"
jargs=
passed=0
failed=0
crashed=0
for t in "$@"; do
    out=$("$t" 2>&1)
    rc=$?
    printf '%s\n' "$out"
    n=$(basename "$t")
    printf '%s\n' "$out" > "$JDIR/raw/$n.txt"
    jargs="$jargs $n=$JDIR/raw/$n.txt"
    p=$(printf '%s\n' "$out" | sed -n 's/^\[  PASSED  \] \([0-9]*\) test(s)\./\1/p' | tail -n 1)
    f=$(printf '%s\n' "$out" | sed -n 's/^\[  FAILED  \] \([0-9]*\) test(s), listed below:/\1/p' | tail -n 1)
    passed=$((passed + ${p:-0}))
    failed=$((failed + ${f:-0}))
    if [ "$rc" != 0 ] && [ "${f:-0}" = 0 ]; then
        echo "test: $t exited with status $rc"
        crashed=$((crashed + 1))
    fi
done
"$PY" tools/gates/junit.py "$JDIR" $jargs || echo "test: JUnit XML not written"
echo "tests: $# executables"
echo "$passed passed, $((failed + crashed)) failed"
[ "$failed" = 0 ] && [ "$crashed" = 0 ] && [ "$passed" -gt 0 ]
