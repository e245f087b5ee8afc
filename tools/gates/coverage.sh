#!/bin/sh
# tools/gates/coverage.sh "COV_OBJS" TEST_SOURCES... -- statement and branch coverage gate.
#
# Links every test against the --coverage library objects, runs them, then
# gcovr reports src/ and the inline code of include/qfoc/ (HTML under
# build/coverage/, Cobertura XML beside it) and fails below 100 % lines or branches.
# coverage.xml and summary.txt are stamped with the run's UTC time and the SHA-256 of their
# inputs (tools/evidence/inputs.py coverage; the list in build/coverage/inputs-coverage.sha256).
set -eu
objs=$1
shift
OUT=build/cov
STARTED=$(date +%s)
mkdir -p "$OUT/tests" "$OUT/sim" build/coverage
find "$OUT" -name '*.gcda' -delete
# The plant model (sim/) is test equipment and the generated parameter tables
# (tables/) are constant data, not library code: built without coverage
# instrumentation and outside the gate.
sim_objs=
for s in sim/*.c tables/*.c; do
    [ -f "$s" ] || continue
    o="$OUT/sim/$(basename "$(dirname "$s")")_$(basename "$s" .c).o"
    gcc -std=c99 -O1 -g -Iinclude -Isim -Itables -c "$s" -o "$o"
    sim_objs="$sim_objs $o"
done
for t in "$@"; do
    n=$(basename "$t" .c)
    # shellcheck disable=SC2086
    gcc -std=c99 -O0 -g --coverage -Iinclude -Isim -Itables -c "$t" -o "$OUT/tests/$n.o"
    # shellcheck disable=SC2086
    gcc --coverage "$OUT/tests/$n.o" $sim_objs $objs -lcmocka -lm -o "$OUT/tests/$n"
    "$OUT/tests/$n" > "$OUT/tests/$n.out" 2>&1 || { cat "$OUT/tests/$n.out"; echo "coverage: $n failed"; exit 1; }
done
# Exclude the test programs themselves; keep the library sources and headers.
# COV_FILTER (gcovr regular expressions, space-separated) narrows the report: the tool
# validation (tools/validation/run.py) gives one unit's source, e.g. 'src/qfoc_ramp\.c$'.
filters=
for f in ${COV_FILTER:-src/ include/}; do filters="$filters --filter $f"; done
# shellcheck disable=SC2086
gcovr --root . --object-directory "$OUT" $filters \
    --print-summary \
    --html-details build/coverage/index.html --cobertura build/coverage/coverage.xml \
    --txt build/coverage/coverage.txt \
    --fail-under-line 100 --fail-under-branch 100 > build/coverage/summary.txt 2>&1 && rc=0 || rc=$?
cat build/coverage/summary.txt
for f in build/coverage/coverage.xml build/coverage/summary.txt; do
    [ -f "$f" ] || continue
    /usr/bin/python3 tools/evidence/inputs.py --stamp "$f" coverage --started "$STARTED" > /dev/null ||
        { echo "coverage: could not stamp $f with its inputs"; exit 1; }
done
if [ "$rc" != 0 ]; then
    echo "coverage: below 100 % (gcovr exit $rc); uncovered:"
    # shellcheck disable=SC2086
    gcovr --root . --object-directory "$OUT" $filters --branches \
        | grep -E '^(src|include)/' | grep -v ' 100% ' || true
    grep -E '^(src|include)/' build/coverage/coverage.txt | grep -v ' 100% ' || true
    exit 1
fi
echo "coverage: report build/coverage/index.html"
