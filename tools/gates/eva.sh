#!/bin/sh
# tools/gates/eva.sh -- Frama-C EVA over the whole drive, two analyses:
#
#   eva-all  proofs/eva/eva_all_tables.c: every table the drive accepts (every field any
#            value of its type, kept where ParamsIdOk and ParamsValid hold), then any number
#            of fast steps and ticks with every input over its full range (make eva, and
#            so make check);
#   eva      proofs/eva/eva_main.c: the reference table (tables/reference_params.c) alone,
#            then the same fast steps and ticks (make eva-reference).  The reference table
#            is one of the tables eva-all covers, so this analysis adds no case to it: it
#            analyses the bodies of the functions eva-all takes by their contracts below,
#            with the reference table's values, and is a check of the same property by
#            another route (some minutes of one processor, outside make check).
#
# Each analysis counts its runtime-error alarms (the '... assert ...' alarms of the -warn-*
# checks and of memory accesses) apart from the ACSL properties EVA leaves unknown (those
# are proved by WP, make prove), writes build/eva/NAME.log, NAME.md and NAME.json, and the
# script exits non-zero when a runtime-error alarm of either analysis remains and
# EVA_MAX_ALARMS (default 0) is exceeded.
#
# Domains: octagons and equalities beside the default intervals, so that relations
# between two variables (a clamp and its bound) are kept.  Functions analysed by their
# contract instead of their code (-eva-use-spec), each contract proved by WP with every
# runtime-error check (make prove), so the two analyses together cover the code:
#   qfoc_isqrt32 (both analyses), whose Newton steps and loop the intervals cannot follow
#     (the remainder and the root are bounded only together); its contract
#     (include/qfoc/vector.h: the result is the floor of the square root, at most 65535);
#     no memory access beyond its locals;
#   qfoc_mech_scale (src/qfoc_trqcomp.c, eva-all only): the mechanical angle
#     (turn x 65536 + theta_e) / pole_pairs through the reciprocal ceil(2^28 / pole_pairs);
#     the quotient is below 65536 because turn < pole_pairs, a relation between the count
#     and the reciprocal that intervals lose when pole_pairs ranges over 1 .. 16 (with the
#     reference table's single pole-pair count they keep it); its contract (the exact
#     quotient MechCount / pole_pairs) is proved by WP; it reads *m and writes nothing;
#   qfoc_iref_q_limit and qfoc_iref_derate (src/qfoc_iref.c, both analyses): the square
#     root of i_max^2 - min(|i_d|, i_max)^2, and hi less a drop at most hi - lo: the clamp's
#     bound enters a product or a quotient, a relation neither octagons nor equalities keep
#     when i_max, the temperatures and the window range over every accepted table; their
#     contracts (include/qfoc/iref.h: the floor root in [0, max(i_max, 0)], the result in
#     [min(lo, hi), hi]) are proved by WP; no memory access beyond their locals;
#   qfoc_dtc_fade and qfoc_dtc_speed_fade (src/qfoc_dtc.c, eva-all only): i x 32767 / i_db
#     inside the dead band |i| < i_db, and dv (2 w_full - |w|) / w_full for
#     w_full < |w| < 2 w_full: the quotient is bounded by the relation between the
#     numerator's factor and the divisor, which intervals lose when the dead band and the
#     hand-over speed range over every accepted table (with the reference table's values the
#     analysis over the whole drive keeps it: 0 alarms); their contracts (include/qfoc/dtc.h:
#     the fade in [-32767, 32767] with the sign of i, the faded value between 0 and dv) are
#     proved by WP; no memory access beyond their locals.
#
# eva-all keeps the table where it is accepted by a filter in the harness, eva_table_ok():
# the identity (ParamsIdOk) and the groups of ParamsValid, one function per group, each
# condition tested on its own, so that EVA reduces the table's fields on the path where
# the table is accepted (-eva-split-return-function keeps the accepted and the refused
# states of each filter function apart at its return, a slevel of 50 keeps the paths
# apart inside it).  The filter leaves out no accepted table: the contract of each of its
# functions states that it is exactly its predicate (eva_table_ok: \result != 0 <==>
# ParamsIdOk(t) && ParamsValid(t)), proved by WP here first (build/eva/eva-all-filter.log;
# without -wp-rte: the runtime errors of the harness are EVA's alarms); the analysis is
# not run, and the gate fails, unless every goal is proved.  Only the intervals of the
# fields are kept: relations between fields (i_max <= i_trip, out_min <= out_max, ...)
# are not, which over-approximates the accepted tables.
#
# EVA_EXTRA (eva) and EVA_ALL_EXTRA (eva-all) replace these options, EVA_PRECISION (default
# 4) sets -eva-precision of both; EVA_RUN (default "eva-all"; "eva eva-all" for both)
# selects the analyses.
# Every .json and .md is stamped with the run's UTC time and the SHA-256 of the inputs
# (tools/evidence/inputs.py eva; the list of the inputs in build/eva/inputs-eva.sha256).
set -u
TOP=$(cd "$(dirname "$0")/../.." && pwd)
cd "$TOP"
OUT=build/eva
mkdir -p "$OUT"
max=${EVA_MAX_ALARMS:-0}
precision=${EVA_PRECISION:-4}
WARN="-warn-signed-overflow -warn-signed-downcast -warn-unsigned-overflow -warn-unsigned-downcast"
FILTER="eva_table_ok,eva_scaling_ok,eva_svpwm_ok,eva_pi_ok,eva_flux_ok,eva_pll_ok,eva_limits_ok,eva_cfg_speed_ok,eva_cfg_start_ok,eva_cfg_prot_ok,eva_cfg_feat_ok,eva_cfg_derate_ok,eva_cross_ok"
# the default options of eva-all: every filter function split at its return, with a slevel
ALL_DEFAULT="-eva-domains octagon,equality \
-eva-use-spec qfoc_isqrt32,qfoc_mech_scale,qfoc_iref_q_limit,qfoc_iref_derate,qfoc_dtc_fade,qfoc_dtc_speed_fade \
-eva-split-return-function $(echo "$FILTER" | sed 's/,/:0,/g'):0 \
-eva-slevel-function $(echo "$FILTER" | sed 's/,/:50,/g'):50"
t0=$(date +%s)

report() {  # report NAME TITLE FRAMA_C_EXIT SECONDS: NAME.json and NAME.md from NAME.log
    /usr/bin/python3 - "$OUT" "$1" "$2" "$3" "$4" "$max" <<'PY'
import json, re, sys
out, name, title = sys.argv[1], sys.argv[2], sys.argv[3]
rc, secs, mx = int(sys.argv[4]), int(sys.argv[5]), int(sys.argv[6])
lines = open(f"{out}/{name}.log", encoding="utf-8", errors="replace").read().splitlines()
rte, props = [], []
for i, l in enumerate(lines):
    m = re.match(r"^\[eva:alarm\] (\S+):(\d+): Warning: ?(.*)$", l)
    if not m:
        continue
    msg = m.group(3).strip() or (lines[i + 1].strip() if i + 1 < len(lines) else "")
    rec = {"file": m.group(1), "line": int(m.group(2)), "message": msg}
    (rte if ". assert " in " " + msg else props).append(rec)
with open(f"{out}/{name}.json", "w") as f:
    json.dump({"frama_c_exit": rc, "seconds": secs, "rte_alarms": rte,
               "unknown_properties": len(props)}, f, indent=1)
md = [f"# {title}", "",
      f"Runtime-error alarms: **{len(rte)}**; ACSL properties EVA leaves unknown (proved by WP): "
      f"{len(props)}; {secs} s.", "", "| file | line | alarm |", "|---|---:|---|"]
md += [f"| {a['file']} | {a['line']} | {a['message']} |" for a in rte]
open(f"{out}/{name}.md", "w").write("\n".join(md) + "\n")
print(f"{name}: {len(rte)} runtime-error alarms (limit {mx}), {len(props)} ACSL properties left "
      f"to WP, {secs} s; {out}/{name}.md")
sys.exit(0 if rc == 0 and len(rte) <= mx else 1)
PY
}

failed() {  # failed NAME TITLE REASON: a result that says the analysis did not run
    /usr/bin/python3 - "$OUT" "$1" "$2" "$3" <<'PY'
import json, sys
out, name, title, why = sys.argv[1:5]
with open(f"{out}/{name}.json", "w") as f:
    json.dump({"frama_c_exit": -1, "seconds": 0, "rte_alarms": [], "unknown_properties": 0,
               "not_run": why}, f, indent=1)
open(f"{out}/{name}.md", "w").write(f"# {title}\n\nNot run: {why}.\n")
print(f"{name}: not run: {why}")
PY
}

stamp() {  # stamp NAME
    for f in "$OUT/$1.json" "$OUT/$1.md"; do
        /usr/bin/python3 tools/evidence/inputs.py --stamp "$f" eva --started "$t0" > /dev/null ||
            { echo "eva: could not stamp $f with its inputs"; return 1; }
    done
}

run_one() {  # run_one NAME: one analysis, its report and its stamp; non-zero on failure
    name=$1
    rc=0
    s0=$(date +%s)
    case "$name" in
    eva)
        title="Frama-C EVA over the whole drive"
        # shellcheck disable=SC2086
        frama-c -cpp-extra-args="-Iinclude -Ispecs -Itables" src/*.c tables/reference_params.c \
            proofs/eva/eva_main.c -eva -eva-precision "$precision" \
            ${EVA_EXTRA:--eva-domains octagon,equality -eva-use-spec qfoc_isqrt32,qfoc_iref_q_limit,qfoc_iref_derate} \
            $WARN -eva-no-show-progress > "$OUT/eva.log" 2>&1
        r=$?
        report eva "$title" "$r" "$(($(date +%s) - s0))" || rc=1
        ;;
    eva-all)
        title="Frama-C EVA over the whole drive, every accepted parameter table"
        # the filter of the harness: exactly the accepted tables (WP, every goal proved)
        # shellcheck disable=SC2086
        frama-c -cpp-extra-args="-Iinclude -Ispecs" proofs/eva/eva_all_tables.c \
            -wp -wp-fct "$FILTER" -wp-prover cvc4,z3 \
            -wp-timeout "${WP_TIMEOUT:-60}" -wp-par 1 > "$OUT/eva-all-filter.log" 2>&1
        r=$?
        goals=$(sed -n 's/.*Proved goals: *//p' "$OUT/eva-all-filter.log")
        p=${goals%% /*}
        n=${goals##*/ }
        if [ "$r" != 0 ] || [ -z "$goals" ] || [ "$p" != "$n" ]; then
            failed eva-all "$title" "the filter eva_table_ok of proofs/eva/eva_all_tables.c is not proved (WP: ${goals:-no result}; $OUT/eva-all-filter.log)"
            rc=1
        else
            echo "eva-all: filter eva_table_ok proved by WP ($goals goals)"
            # shellcheck disable=SC2086
            frama-c -cpp-extra-args="-Iinclude -Ispecs" src/*.c proofs/eva/eva_all_tables.c \
                -eva -eva-precision "$precision" \
                ${EVA_ALL_EXTRA:-$ALL_DEFAULT} \
                $WARN -eva-no-show-progress > "$OUT/eva-all.log" 2>&1
            r=$?
            report eva-all "$title" "$r" "$(($(date +%s) - s0))" || rc=1
        fi
        ;;
    *)
        echo "eva: no analysis '$name' (EVA_RUN: eva, eva-all)"
        return 1
        ;;
    esac
    return "$rc"
}

# the analyses in parallel (each is one single-threaded Frama-C process); their messages in
# the order of EVA_RUN once all have finished, then their stamps
for name in ${EVA_RUN:-eva-all}; do
    ( run_one "$name"; echo $? > "$OUT/$name.rc" ) > "$OUT/$name.out" 2>&1 &
done
wait
rc=0
for name in ${EVA_RUN:-eva-all}; do
    cat "$OUT/$name.out"
    [ "$(cat "$OUT/$name.rc" 2>/dev/null)" = 0 ] || rc=1
    rm -f "$OUT/$name.out" "$OUT/$name.rc"
    case "$name" in
    eva | eva-all) stamp "$name" || rc=1 ;;  # one at a time: the stamps share the input list
    *) ;;
    esac
done
exit "$rc"
