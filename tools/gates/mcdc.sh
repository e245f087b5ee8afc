#!/bin/sh
# tools/gates/mcdc.sh [REPORT OPTIONS] -- MC/DC coverage of the library by its unit tests.
#
#   sh tools/setup/mkchroot.sh && sh tools/gates/mcdc.sh --min 95      (as root)
#
# Modified condition/decision coverage (ISO 26262-6, table 9) with gcc 14's
# -fcondition-coverage, run in the Debian trixie chroot of tools/setup/mkchroot.sh
# (build/trixie-chroot, or MCDC_CHROOT):
#   1. the sources (src, include, tests, sim, tables, specs, port_s32k) are copied to
#      /qfoc inside the chroot; nothing of the repository is mounted into it;
#   2. every src/*.c is compiled on its own (-c) with -O0 -fcondition-coverage --coverage
#      and the warning flags of the project (MCDC_WARN, default below, -Werror included);
#   3. every tests/test_*.c is compiled with the same instrumentation (so that the inline
#      functions of include/qfoc/ it calls are measured too) and linked with the plant
#      model sim/*.c and the parameter tables tables/*.c, which are test equipment,
#      built without instrumentation; each test runs from the copy's root (the tests
#      read specs/ by relative path), one after the other;
#   4. gcov-14 --conditions --json-format writes one record per object; the records, the
#      test logs and the tool versions are copied to build/mcdc/;
#   5. tools/gates/mcdc_report.py (on the host) keeps src/ and include/qfoc/, lists every
#      condition outcome not covered, marks those justified in
#      specs/mcdc-justifications.md and writes build/mcdc/mcdc.{json,md}; the options of
#      this script are passed to it (--min PERCENT sets the gate).
# MCDC_TESTS="tests/test_pi.c ..." runs only those tests (a partial measurement).
# Exit status: non-zero when a test fails or the report's gate fails.
set -eu

TOP=$(cd "$(dirname "$0")/../.." && pwd)
cd "$TOP"
T=${MCDC_CHROOT:-$TOP/build/trixie-chroot}
case $T in /*) ;; *) T=$TOP/$T ;; esac
OUT=$TOP/build/mcdc
PY=${PYTHON:-/usr/bin/python3}
[ -x "$PY" ] || PY=python3
MCDC_WARN=${MCDC_WARN:--std=c99 -Wall -Wextra -Wconversion -Wsign-conversion -Wshadow \
-Wstrict-prototypes -Wmissing-prototypes -Wundef -Wcast-qual -Werror}
W=/qfoc                         # the copy, as seen from inside the chroot

if [ "$(id -u)" != 0 ]; then
    echo "mcdc: chroot needs root; run: sudo sh tools/gates/mcdc.sh $*" >&2
    exit 1
fi
if [ ! -x "$T/usr/bin/gcc-14" ] || [ ! -f "$T/usr/include/cmocka.h" ]; then
    echo "mcdc: no gcc-14 chroot at $T; run: sh tools/setup/mkchroot.sh" >&2
    exit 1
fi
# The copy must hold no mount point before it is removed.
if awk -v p="$T$W" '$2 == p || index($2, p "/") == 1 { f = 1 } END { exit !f }' /proc/self/mounts; then
    echo "mcdc: something is mounted below $T$W; unmount it first" >&2
    exit 1
fi

t0=$(date +%s)
echo "mcdc: copying the sources to $T$W"
rm -rf "$T$W" "$OUT"
mkdir -p "$T$W/build" "$OUT/gcov" "$OUT/tests"
tar -cf - src include tests sim tables specs port_s32k | tar -xf - -C "$T$W"

echo "mcdc: building and running in the chroot (gcc-14 -O0 -fcondition-coverage --coverage)"
rc=0
chroot "$T" /usr/bin/env -i PATH=/usr/bin:/bin HOME=/root LANG=C.UTF-8 \
    MCDC_WARN="$MCDC_WARN" MCDC_TESTS="${MCDC_TESTS:-}" W="$W" sh -s <<'EOF' || rc=$?
set -eu
cd "$W"
M=build/mcdc
mkdir -p $M/obj $M/equip $M/tests $M/gcov
gcc-14 --version | head -n 1 > $M/toolchain.txt
gcov-14 --version | head -n 1 >> $M/toolchain.txt
dpkg-query -W -f='${Package} ${Version}\n' gcc-14 libc6-dev libcmocka-dev >> $M/toolchain.txt
lib=
for s in src/*.c; do
    o=$M/obj/$(basename "$s" .c).o
    # shellcheck disable=SC2086
    gcc-14 $MCDC_WARN -O0 -g -fcondition-coverage --coverage -Iinclude -c "$s" -o "$o"
    lib="$lib $o"
done
echo "mcdc: library: $(ls src/*.c | wc -l) units"
# Test equipment: the plant model and the parameter tables, not measured.
equip=
for s in sim/*.c tables/*.c; do
    o=$M/equip/$(basename "$(dirname "$s")")_$(basename "$s" .c).o
    gcc-14 -std=c99 -O1 -g -Iinclude -Isim -Itables -c "$s" -o "$o"
    equip="$equip $o"
done
fail=0
: > $M/tests/times.txt
for t in ${MCDC_TESTS:-tests/test_*.c}; do
    n=$(basename "$t" .c)
    gcc-14 -std=c99 -O0 -g -fcondition-coverage --coverage -Iinclude -Isim -Itables \
        -c "$t" -o "$M/tests/$n.o"
    # shellcheck disable=SC2086
    gcc-14 --coverage "$M/tests/$n.o" $equip $lib -lcmocka -lm -o "$M/tests/$n"
    s0=$(date +%s)
    if "$M/tests/$n" < /dev/null > "$M/tests/$n.out" 2>&1; then st=ok; else st=FAILED; fail=1; fi
    s1=$(date +%s)
    printf '%-24s %-6s %4s s\n' "$n" "$st" "$((s1 - s0))" | tee -a $M/tests/times.txt
    [ "$st" = ok ] || tail -n 30 "$M/tests/$n.out"
done
# One JSON record per object: the library units and the test units (for the inline
# code of the headers).  The report keeps src/ and include/qfoc/ only.
cd $M/gcov
for d in ../obj/*.gcda ../tests/*.gcda; do
    gcov-14 --conditions --json-format "$d" > /dev/null
    b=$(basename "$d" .gcda)
    case $d in ../obj/*) k=lib ;; *) k=test ;; esac
    mv "$b.gcov.json.gz" "$k-$b.gcov.json.gz"
done
exit $fail
EOF
cp "$T$W/build/mcdc/toolchain.txt" "$OUT/"
cp "$T$W"/build/mcdc/gcov/*.json.gz "$OUT/gcov/" 2>/dev/null || true
cp "$T$W"/build/mcdc/tests/*.out "$T$W/build/mcdc/tests/times.txt" "$OUT/tests/" 2>/dev/null || true
t1=$(date +%s)
echo "mcdc: build and test run $((t1 - t0)) s"
echo "build and test run: $((t1 - t0)) s" >> "$OUT/toolchain.txt"
if [ "$rc" != 0 ]; then
    echo "mcdc: a test failed or the build broke (logs in $OUT/tests/)" >&2
fi
rrc=0
"$PY" tools/gates/mcdc_report.py --gcov-dir "$OUT/gcov" --out "$OUT" \
    --justifications specs/mcdc-justifications.md "$@" || rrc=$?
[ "$rc" = 0 ] || exit 1
exit "$rrc"
