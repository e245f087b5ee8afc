#!/bin/sh
# tools/gates/cbmc.sh [HARNESS_DIR...] -- run every CBMC harness under proofs/cbmc/.
#
# A harness folder holds harness.c and config.mk, which sets
#   SRCS   = library sources the harness links (paths from the repository root)
#   UNWIND = loop unwinding bound (checked: --unwinding-assertions)
#   CBMC_EXTRA = optional further flags
#   SAT    = optional: minisat for CBMC's built-in MiniSat 2 instead of CaDiCaL (below),
#            for a harness that the built-in solver decides faster
#   GOTO_INSTRUMENT = optional goto-instrument flags applied first (the harness and
#                sources are then compiled with goto-cc), e.g. --remove-function-body F
# Every harness runs with the full set of runtime checks below; the run fails unless
# every property of every harness holds.  Results: build/cbmc/*.log and
# proofs/cbmc/results.md (property count, result, unwinding bound, time), stamped with the
# run's UTC time and the SHA-256 of its inputs (tools/evidence/inputs.py cbmc), with the list
# of those inputs beside it (proofs/cbmc/inputs-cbmc.sha256, committed with the results).
set -eu
TOP=$(cd "$(dirname "$0")/../.." && pwd)
cd "$TOP"
. tools/gates/jobs.sh
CBMC=${CBMC:-build/tools/cbmc/bin/cbmc}
OUT=build/cbmc
JOBS=${JOBS:-2}
STARTED=$(date +%s)
mkdir -p "$OUT"
rm -f "$OUT"/*.log "$OUT"/*.res "$OUT"/*.backend

CHECKS="--bounds-check --pointer-check --div-by-zero-check --signed-overflow-check \
--unsigned-overflow-check --pointer-overflow-check --conversion-check --undefined-shift-check \
--float-overflow-check --nan-check --pointer-primitive-check --unwinding-assertions"

# The SAT back end: CaDiCaL (Debian bookworm's cadical, installed by make deps) through
# CBMC's DIMACS interface, 3 to 6 times faster than the built-in MiniSat 2 on the
# arithmetic harnesses.  CBMC reads the solver's verdict and, for a failed property, its
# model (the counterexample), exactly as with a built-in solver.  CBMC_SAT= (empty) runs
# the built-in MiniSat 2 instead.
CADICAL=${CADICAL:-$(command -v cadical || true)}
CBMC_SAT=${CBMC_SAT-${CADICAL:+--external-sat-solver $CADICAL}}

# longest first, by the times of the committed results (new harnesses first of all),
# so that the two job slots finish close together
order_by_time() {
    for d in $(ls -d proofs/cbmc/*/ 2>/dev/null | sed 's#/$##'); do
        t=$(sed -n "s/^| $(basename "$d") | [A-Z]* | [0-9]* | [0-9]* | [0-9]* | \([0-9]*\) |$/\1/p" \
            proofs/cbmc/results.md 2>/dev/null)
        echo "${t:-999999} $d"
    done | sort -rn | cut -d' ' -f2
}
dirs=${*:-$(order_by_time)}

mkval() {  # mkval FILE VAR: value of 'VAR = ...' in a config.mk
    sed -n "s/^$2[[:space:]]*[:?]*=[[:space:]]*//p" "$1" | tail -n 1
}

run_one() {
    d=$1
    name=$(basename "$d")
    srcs=$(mkval "$d/config.mk" SRCS)
    unwind=$(mkval "$d/config.mk" UNWIND)
    extra=$(mkval "$d/config.mk" CBMC_EXTRA)
    [ -n "$unwind" ] || unwind=1
    sat=$CBMC_SAT
    # a harness on an SMT back end (CBMC_EXTRA --z3 ...), or one that asks for MiniSat
    case " $extra $(mkval "$d/config.mk" SAT) " in
        *" --z3 "*|*" --cvc4 "*|*" --cvc5 "*|*" --smt2 "*|*" minisat "*) sat="" ;;
    esac
    if [ -z "$sat" ]; then
        case " $extra " in
            *" --z3 "*|*" --cvc4 "*|*" --cvc5 "*|*" --smt2 "*) echo "$name (SMT: $extra)" ;;
            *) echo "$name (MiniSat 2)" ;;
        esac > "$OUT/$name.backend"
    fi
    gi=$(mkval "$d/config.mk" GOTO_INSTRUMENT)
    start=$(date +%s)
    input="$d/harness.c $srcs"
    if [ -n "$gi" ]; then
        # the program is compiled with goto-cc and transformed by goto-instrument
        # first (e.g. --remove-function-body F: F returns any value of its type)
        # shellcheck disable=SC2086
        { "$(dirname "$CBMC")/goto-cc" $input -Iinclude -DQFOC_CBMC -o "$OUT/$name.gb" &&
          "$(dirname "$CBMC")/goto-instrument" $gi "$OUT/$name.gb" "$OUT/$name.gi.gb"; } \
            > "$OUT/$name.gi.log" 2>&1 || echo "goto-instrument failed: $OUT/$name.gi.log" >> "$OUT/$name.gi.log"
        input="$OUT/$name.gi.gb"
    fi
    # shellcheck disable=SC2086
    if "$CBMC" $input -Iinclude -DQFOC_CBMC $CHECKS --unwind "$unwind" $extra $sat \
        > "$OUT/$name.log" 2>&1; then
        res=PASS
    else
        res=FAIL
    fi
    end=$(date +%s)
    props=$(grep -c ': SUCCESS$' "$OUT/$name.log" || true)
    failed=$(grep -c ': FAILURE$' "$OUT/$name.log" || true)
    grep -q 'VERIFICATION SUCCESSFUL' "$OUT/$name.log" || res=FAIL
    echo "$name|$res|$props|$failed|$unwind|$((end - start))" > "$OUT/$name.res"
    echo "  $name: $res ($props properties hold, $failed fail, unwind $unwind, $((end - start)) s)"
}

# The back end's own check first (proofs/cbmc-selftest/planted.c): one planted overflow
# must be reported as failed and the other three properties as holding.
# shellcheck disable=SC2086
"$CBMC" proofs/cbmc-selftest/planted.c $CHECKS $CBMC_SAT > "$OUT/selftest.log" 2>&1 || true
if grep -q '^\[main\.overflow\.1\] .*: FAILURE$' "$OUT/selftest.log" &&
   [ "$(grep -c ': FAILURE$' "$OUT/selftest.log")" = 1 ] &&
   [ "$(grep -c ': SUCCESS$' "$OUT/selftest.log")" = 3 ] &&
   grep -q '^VERIFICATION FAILED$' "$OUT/selftest.log"; then
    echo "cbmc: self-test of the SAT back end: the planted overflow found, 3 properties hold"
else
    echo "cbmc: self-test of the SAT back end FAILED ($OUT/selftest.log)"
    exit 1
fi

echo "cbmc: $("$CBMC" --version) on $(echo $dirs | wc -w) harnesses"
pids=""
for d in $dirs; do
    run_one "$d" &
    pids="$pids $!"
    throttle
done
wait

{
    echo "# CBMC results, per harness"
    echo
    echo "Generated by \`make cbmc\` (tools/gates/cbmc.sh) with CBMC $("$CBMC" --version): every harness"
    echo "runs with $CHECKS."
    echo
    if [ -n "$CBMC_SAT" ]; then
        echo "SAT back end: CaDiCaL $("$CADICAL" --version) (--external-sat-solver), except:" \
            "$(cat "$OUT"/*.backend 2>/dev/null | sort | paste -sd, - | sed 's/,/, /g')."
    else
        echo "SAT back end: MiniSat 2 (built into CBMC)."
    fi
    echo
    echo "| harness | result | properties proved | failed | unwind | time (s) |"
    echo "|---|---|---:|---:|---:|---:|"
    cat "$OUT"/*.res 2>/dev/null | sort | awk -F'|' '{printf "| %s | %s | %s | %s | %s | %s |\n", $1, $2, $3, $4, $5, $6}'
} > proofs/cbmc/results.md
stamped=1
/usr/bin/python3 tools/evidence/inputs.py --stamp proofs/cbmc/results.md cbmc --started "$STARTED" > /dev/null ||
    { echo "cbmc: could not stamp proofs/cbmc/results.md with its inputs"; stamped=0; }
n=$(cat "$OUT"/*.res 2>/dev/null | wc -l)
bad=$(cat "$OUT"/*.res 2>/dev/null | grep -c '|FAIL|' || true)
props=$(cat "$OUT"/*.res 2>/dev/null | awk -F'|' '{s += $3} END {print s + 0}')
echo "cbmc: $((n - bad)) / $n harnesses pass, $props properties hold"
[ "$n" -gt 0 ] && [ "$bad" = 0 ] && [ "$stamped" = 1 ]
