#!/bin/sh
# tools/gates/smoke.sh -- Frama-C WP smoke tests, unit by unit (make smoke).
#
# Each unit given (default: every src/*.c) is run through WP with the options of the prove
# gate (tools/gates/prove.sh: -wp-rte, the four -warn-* checks, -wp-fct restricted to the
# functions the unit defines, provers cvc4 then z3, timeout WP_TIMEOUT, default 60 s, one
# prover process) and -wp-smoke-tests.  WP then adds smoke goals: for every precondition
# (and every behaviour's assumes) that it is satisfiable, for every statement and call that
# it is reachable, for every loop that its invariant can hold (-wp-smoke-timeout, 2 s).
# A smoke goal that is PROVED is a finding: the hypotheses before the point are
# contradictory (a dead branch, or a precondition or assumes no caller can meet); a smoke
# goal that is not proved ("Passed") is unreachable code not found, as expected.  WP's
# other goals are proved as in make prove; their count is reported beside.
#
# A unit not done within SMOKE_UNIT_LIMIT seconds (default 300) is stopped and reported.
# Writes build/smoke/UNIT.log and build/smoke/results.md (per unit: smoke goals, all
# passed yes/no, the findings, the time); exits non-zero on a finding or a failed run.
# Usage: smoke.sh [UNIT.c ...]; smoke.sh --report [UNIT.c ...] writes results.md again from
# the logs of the last run, and lists the units given that it did not run.
set -u
PY=/usr/bin/python3
[ -x "$PY" ] || PY=python3
TOP=$(cd "$(dirname "$0")/../.." && pwd)
cd "$TOP"
OUT=${SMOKE_OUT:-build/smoke}
TIMEOUT=${WP_TIMEOUT:-60}
# a unit not done within this time is stopped and reported as not finished
LIMIT=${SMOKE_UNIT_LIMIT:-300}
mkdir -p "$OUT"
REPORT_ONLY=0
if [ "${1:-}" = "--report" ]; then
    # the results file again from the logs of earlier runs (build/smoke/units.txt)
    REPORT_ONLY=1
    shift
fi
[ $# -gt 0 ] || set -- src/*.c
[ "$REPORT_ONLY" = 1 ] || : > "$OUT/units.txt"
[ "$REPORT_ONLY" = 1 ] || echo "smoke: Frama-C WP smoke tests (cvc4,z3, timeout ${TIMEOUT} s) over $# units"
for unit in "$@"; do
    [ "$REPORT_ONLY" = 0 ] || break
    name=$(basename "$unit" .c)
    fcts=$("$PY" tools/gates/c_functions.py "$unit")
    if [ -z "$fcts" ]; then
        echo "$name $unit - 0 0" >> "$OUT/units.txt"
        echo "  $name: data only, no function"
        continue
    fi
    start=$(date +%s)
    timeout "$LIMIT" frama-c -cpp-extra-args="-Iinclude -Ispecs" "$unit" \
        -wp -wp-rte -wp-fct "$fcts" \
        -warn-signed-overflow -warn-signed-downcast \
        -warn-unsigned-overflow -warn-unsigned-downcast \
        -wp-prover cvc4,z3 -wp-timeout "$TIMEOUT" -wp-par 1 \
        -wp-smoke-tests > "$OUT/$name.log" 2>&1
    rc=$?
    secs=$(($(date +%s) - start))
    echo "$name $unit $rc $secs 1" >> "$OUT/units.txt"
    echo "  $name: $(sed -n 's/.*Smoke-test //p' "$OUT/$name.log" | sort -u | wc -l) smoke goals," \
         "$(sed -n 's/.*\[Failed\] Smoke-test //p' "$OUT/$name.log" | sort -u | wc -l) proved (findings)" \
         "($secs s, frama-c exit $rc)"
done
"$PY" - "$OUT" "$TIMEOUT" "$LIMIT" "$@" <<'PY'
import datetime, re, subprocess, sys
out, timeout, limit = sys.argv[1], sys.argv[2], sys.argv[3]
rows, bad = [], 0
for line in open(f"{out}/units.txt", encoding="utf-8"):
    name, unit, rc, secs, ran = line.split()
    if ran == "0":
        rows.append(f"| {unit} | 0 | yes | data only, no function | - | 0 |")
        continue
    text = open(f"{out}/{name}.log", encoding="utf-8", errors="replace").read()
    smoke, where = {}, {}
    lines = text.splitlines()
    for i, l in enumerate(lines):
        m = re.match(r"^\[wp\] \[([^\]]+)\] Smoke-test (\S+)", l)
        if m:
            smoke[m.group(2)] = m.group(1)
            for k in lines[i + 1:i + 4]:
                w = re.match(r"^\[wp\] (\S+:\d+): Warning: Failed smoke-test", k)
                if w:
                    where[m.group(2)] = w.group(1)
                    break
    found = [f"{g} ({st}{', ' + where[g] if g in where else ''})"
             for g, st in sorted(smoke.items()) if st != "Passed"]
    m = re.search(r"Proved goals:\s*(\d+) / (\d+)", text)
    goals = f"{m.group(1)} / {m.group(2)}" if m else "no result"
    if rc == "124":
        bad += 1
        rows.append(f"| {unit} | {len(smoke)} done | {'no' if found else 'none proved so far'} | "
                    f"not finished within {limit} s (stopped){': ' + '; '.join(found) if found else ''} "
                    f"| - | {secs} |")
        continue
    ok = rc == "0" and m is not None and not found
    bad += not ok
    what = "; ".join(found) if found else ("none" if rc == "0" and m else f"frama-c exit {rc}")
    rows.append(f"| {unit} | {len(smoke)} | {'yes' if not found else 'no'} | {what} | {goals} | {secs} |")
ran = {l.split()[1] for l in open(f"{out}/units.txt", encoding="utf-8") if l.strip()}
for unit in sys.argv[4:]:
    if unit not in ran:
        bad += 1
        rows.append(f"| {unit} | - | - | not run | - | - |")
ver = subprocess.run(["frama-c", "-version"], capture_output=True, text=True).stdout.strip()
md = ["# Frama-C WP smoke tests", "",
      f"Run: {datetime.datetime.utcnow().strftime('%Y-%m-%d %H:%M')} UTC; Frama-C {ver}; "
      f"`tools/gates/smoke.sh` (make smoke): the options of `make prove` (-wp-rte, the -warn-* "
      f"checks, the unit's own functions, cvc4 then z3, timeout {timeout} s) and "
      "-wp-smoke-tests (smoke timeout 2 s).", "",
      "A smoke goal proved is a finding (dead code, or a precondition or assumes that cannot "
      "hold); \"unreachable as expected\" = every smoke goal of the unit was not proved.  "
      "\"WP goals\" counts every goal of the run, smoke goals included (a smoke goal not "
      "proved counts as passed).", "",
      "| unit | smoke goals | all unreachable as expected | findings | WP goals proved | time (s) |",
      "|---|---:|---|---|---:|---:|"] + rows
open(f"{out}/results.md", "w").write("\n".join(md) + "\n")
print(f"smoke: {len(rows)} units, {bad} with a finding or a failed run; {out}/results.md")
sys.exit(1 if bad else 0)
PY
