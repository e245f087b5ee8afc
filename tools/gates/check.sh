#!/bin/sh
# tools/gates/check.sh -- every qfoc gate, then a summary.
# All gates run even when one fails, so one run shows every shortfall; the exit
# status is non-zero when any gate failed.  The gates run one after the other, except
# two that use one processor for minutes and share no file with the gates beside them:
# MC/DC (in its own chroot) runs beside the tests, EVA beside the gates after CBMC (the
# summary lists the gates in the order they ended).  Coverage uses one processor: it runs
# first among the gates beside EVA (before trace, which reads its result), in time EVA
# takes anyway.
set -u
TOP=$(cd "$(dirname "$0")/../.." && pwd)
cd "$TOP"
mkdir -p build
summary=build/check-summary.txt
: > "$summary"
status=0
start_all=$(date +%s)

gate() {  # gate NAME COMMAND...
    name=$1
    shift
    echo
    echo "==================== $name"
    t0=$(date +%s)
    log=build/check-$name.log
    "$@" > "$log" 2>&1
    rc=$?
    t1=$(date +%s)
    cat "$log"
    last=$(grep -v '^[[:space:]]*$' "$log" | tail -n 1)
    if [ "$rc" = 0 ]; then res=PASS; else res=FAIL; status=1; fi
    printf '%-9s %s  %4ss  %s\n' "$name" "$res" "$((t1 - t0))" "$last" >> "$summary"
}

# gate_bg NAME COMMAND...: the gate in the background, its output kept until gate_wait NAME
gate_bg() {
    ( gate "$@" ) > "build/check-$1.out" 2>&1 &
    eval "bg_$(echo "$1" | tr -c 'a-z0-9\n' _)=$!"
}

gate_wait() {  # gate_wait NAME
    eval "wait \"\$bg_$(echo "$1" | tr -c 'a-z0-9\n' _)\"" || true
    cat "build/check-$1.out"
    grep -q "^$1  *FAIL " "$summary" && status=1
    return 0
}

gate_bg mcdc  make --no-print-directory mcdc
gate test     make --no-print-directory test
gate_wait mcdc
gate prove    make --no-print-directory prove
gate cbmc     make --no-print-directory cbmc
gate_bg eva   make --no-print-directory eva
gate coverage make --no-print-directory coverage
gate misra    make --no-print-directory misra
gate misra-cs make --no-print-directory misra-summary
gate static   make --no-print-directory static
gate target   make --no-print-directory target
gate tgt-test make --no-print-directory target-test
gate pil      make --no-print-directory pil-check
gate bench    make --no-print-directory bench
gate trace    make --no-print-directory trace
gate docs     make --no-print-directory docs
gate report   make --no-print-directory estimator-report
gate tune     make --no-print-directory tune-check
gate a2l      make --no-print-directory a2l-check
gate demo     make --no-print-directory quickstart
gate robust   make --no-print-directory robustness ROBUST_COUNT=24
gate identify make --no-print-directory identify
gate repro    make --no-print-directory repro
gate cmake    make --no-print-directory cmake-check
gate fuzz     make --no-print-directory fuzz-check
gate faults   make --no-print-directory faults-check
gate_wait eva

# The evidence bundle last: it collects what the gates above wrote, and fails when one of
# its summary rows is red (a gate's result missing or failed).
gate evidence make --no-print-directory evidence EVIDENCE_STRICT=1
# The release package after it (tools/release/check_gate.sh): make release's refusals tested,
# then the package of this commit with the results the gates above rewrote in proofs/,
# packed with a bundle of that state, unpacked and checked (make release-check).
gate release  make --no-print-directory release-gate

echo
echo "==================== summary ($(( $(date +%s) - start_all )) s)"
cat "$summary"
if [ "$status" = 0 ]; then echo "check: all gates pass"; else echo "check: FAILED"; fi
exit "$status"
