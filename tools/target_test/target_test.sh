#!/bin/sh
# target_test.sh OUT -- run the golden-vector test (make target-test builds what it needs).
#
#   1. host runner: every group identical to the generator's digests; the same with the
#      library under UndefinedBehaviorSanitizer (no vector reaches undefined behaviour);
#   2. host runner, self-test: for every group, one expected digest corrupted must be
#      reported as exactly that group and vector; one flipped input bit (an angle of
#      qfoc_sincos, a phase-current sample of the drive) must be reported at its vector;
#   3. target runner on QEMU mps2-an386 (Cortex-M4F, semihosting): every group identical,
#      exit status 0;
#   4. target runner, self-test: a corrupted digest and a flipped input are reported and
#      the exit status is 1 (the failure path works on the target too).
# Exit status 0 only when all four hold.  Requirements: REQ-TGT-002, REQ-TGT-004, REQ-TGT-005
# (specs/requirements/target.md).  Outputs: OUT/host.txt, OUT/target.txt,
# OUT/target_selftest.txt; the JUnit files build/junit/target_equivalence.xml (one test
# case per group of the target run) and build/junit/target_checks.xml (one per checking
# program, target_test.sh, tt_gen.c and tt_runner.c: OK when all four hold, FAILED with
# the reason otherwise), which tools/evidence/evidence.py reads for the verdicts.
set -u
OUT=${1:?usage: target_test.sh BUILD_DIR}
QEMU=${QEMU:-qemu-system-arm -M mps2-an386 -nographic -monitor none -serial none}
SEMI="-semihosting-config enable=on,target=native"
HOST="$OUT/tt_runner_host"
ELF="$OUT/tt_runner.elf"
T0=$(date +%s)
# the JUnit files of this run (those of an earlier run are removed first: a run that stops
# early must not leave them to be read as its own)
JDIR="$(dirname "$OUT")/junit"
rm -f "$JDIR/target_equivalence.xml" "$JDIR/target_checks.xml"

# checks_junit STATUS [MESSAGE]: the result of the checking programs as JUnit
# (tools/gates/junit.py checks:), one test case per program, all with the run's result
checks_junit() {
    mkdir -p "$JDIR"
    msg=$(printf '%s' "${2:-}" | tr '\n' ' ')
    for c in target_test.sh tt_gen.c tt_runner.c; do
        echo "$c: $1${msg:+: $msg}"
    done > "$OUT/checks.txt"
    /usr/bin/python3 "$(dirname "$0")/../gates/junit.py" "$JDIR" target_checks=checks:"$OUT/checks.txt" >/dev/null ||
        echo "target-test: could not write $JDIR/target_checks.xml"
}

fail() {
    echo "target-test: FAILED: $*"
    checks_junit FAILED "$*"
    exit 1
}

# ---------------------------------------------------------------- 1. host
"$HOST" > "$OUT/host.txt"
rc=$?
if [ $rc -ne 0 ]; then
    grep -v ', identical$' "$OUT/host.txt"
    fail "the host runner differs from the generator (exit status $rc, $OUT/host.txt)"
fi
"$OUT/tt_runner_ubsan" > "$OUT/host_ubsan.txt" 2>&1
rc=$?
if [ $rc -ne 0 ]; then
    grep -v ', identical$' "$OUT/host_ubsan.txt"
    fail "the host runner under UndefinedBehaviorSanitizer failed (exit status $rc, $OUT/host_ubsan.txt)"
fi
"$HOST" --list > "$OUT/groups.txt" || fail "cannot list the groups"
NG=$(wc -l < "$OUT/groups.txt")
NV=$(awk '{ s += $2 } END { print s }' "$OUT/groups.txt")

# ---------------------------------------------------------------- 2. host self-test
nexp=0
while read -r name n; do
    idx=$(( (n * 7) / 11 ))
    out=$("$HOST" --only "$name" --corrupt-expected "$name" "$idx")
    rc=$?
    [ $rc -eq 1 ] || fail "self-test: a corrupted digest of $name (vector $idx) gave exit status $rc"
    echo "$out" | grep -q "^$name: DIFFERENT: 1 of $n vectors differ, first at vector $idx:" ||
        fail "self-test: a corrupted digest of $name (vector $idx) was not reported as such: $out"
    nexp=$((nexp + 1))
done < "$OUT/groups.txt"
for case in "sincos 12345" "drive_fast 20000"; do
    set -- $case
    out=$("$HOST" --only "$1" --corrupt-input "$1" "$2")
    rc=$?
    [ $rc -eq 1 ] || fail "self-test: a flipped input bit of $1 (vector $2) gave exit status $rc"
    echo "$out" | grep -q "^$1: DIFFERENT: .* first at vector $2:" ||
        fail "self-test: a flipped input bit of $1 (vector $2) was not reported at its vector: $out"
done

# ---------------------------------------------------------------- 3. target
timeout 120 $QEMU $SEMI,arg=tt_runner -kernel "$ELF" > "$OUT/target.txt" 2>&1
rc=$?
cat "$OUT/target.txt"
# JUnit XML of the run, one test case per group, beside the unit tests' (build/junit/)
/usr/bin/python3 "$(dirname "$0")/../gates/junit.py" "$JDIR" target_equivalence=vectors:"$OUT/target.txt" >/dev/null ||
    fail "could not write the JUnit file of the run"
[ $rc -eq 0 ] || fail "the Cortex-M4F runner exited with status $rc (1: a difference, 3: a fault, 124: timeout)"
nid=$(grep -c ', identical$' "$OUT/target.txt")
[ "$nid" -eq "$NG" ] || fail "$nid of $NG groups reported identical on the target"
grep -q "^result: $NG groups, $NV vectors, all identical" "$OUT/target.txt" ||
    fail "the target's summary is not '$NG groups, $NV vectors, all identical'"

# ---------------------------------------------------------------- 4. target self-test
timeout 120 $QEMU $SEMI,arg=tt_runner,arg=--only,arg=sincos,arg=--only,arg=drive_fast,arg=--corrupt-expected,arg=sincos,arg=40000,arg=--corrupt-input,arg=drive_fast,arg=20000 \
    -kernel "$ELF" > "$OUT/target_selftest.txt" 2>&1
rc=$?
[ $rc -eq 1 ] || fail "target self-test: exit status $rc instead of 1 ($OUT/target_selftest.txt)"
grep -q "^sincos: DIFFERENT: 1 of 65536 vectors differ, first at vector 40000:" "$OUT/target_selftest.txt" &&
    grep -q "^drive_fast: DIFFERENT: .* first at vector 20000:" "$OUT/target_selftest.txt" ||
    fail "target self-test: the corruptions were not reported ($OUT/target_selftest.txt)"

T1=$(date +%s)
checks_junit OK
echo "target-test: host: identical, also under UndefinedBehaviorSanitizer; self-test: $nexp corrupted" \
     "digests (one per group) and 2 flipped input bits reported on the host, 2 on the target" \
     "(exit status 1); $((T1 - T0)) s"
echo "target-test: $NG groups, $NV vectors, all bit-identical on Cortex-M4F (QEMU mps2-an386)"
