#!/bin/sh
# tools/gates/eva.sh -- Frama-C EVA over the whole drive (proofs/eva/eva_main.c): the reference
# table, then any number of fast steps and ticks with every input over its full range.
# Counts the runtime-error alarms (the '... assert ...' alarms of the -warn-* checks and
# of memory accesses) apart from the ACSL properties EVA leaves unknown (those are proved
# by WP, make prove), writes build/eva/eva.log, eva.md and eva.json, and exits non-zero
# when a runtime-error alarm remains and EVA_MAX_ALARMS (default 0) is exceeded.
#
# Domains: octagons and equalities beside the default intervals, so that relations
# between two variables (a clamp and its bound) are kept.  One function is analysed by
# its contract instead of its code (-eva-use-spec): qfoc_isqrt32, whose Newton steps and loop
# the intervals cannot follow (the remainder and the root are bounded only together);
# its contract (include/qfoc/vector.h: the result is the floor of the square root, at
# most 65535) is proved by WP with every runtime-error check (make prove), and its code
# has no memory access beyond its locals, so the two analyses together cover it.
# EVA_EXTRA replaces these options, EVA_PRECISION (default 4) sets -eva-precision.
# eva.json and eva.md are stamped with the run's UTC time and the SHA-256 of their inputs
# (tools/evidence/inputs.py eva; the list of the inputs in build/eva/inputs-eva.sha256).
set -u
TOP=$(cd "$(dirname "$0")/../.." && pwd)
cd "$TOP"
OUT=build/eva
mkdir -p "$OUT"
max=${EVA_MAX_ALARMS:-0}
t0=$(date +%s)
frama-c -cpp-extra-args="-Iinclude -Ispecs -Itables" src/*.c tables/reference_params.c \
    proofs/eva/eva_main.c -eva -eva-precision "${EVA_PRECISION:-4}" ${EVA_EXTRA:--eva-domains octagon,equality -eva-use-spec qfoc_isqrt32} \
    -warn-signed-overflow -warn-signed-downcast -warn-unsigned-overflow -warn-unsigned-downcast \
    -eva-no-show-progress > "$OUT/eva.log" 2>&1
rc=$?
t1=$(date +%s)
/usr/bin/python3 - "$OUT" "$rc" "$((t1 - t0))" "$max" <<'PY'
import json, re, sys
out, rc, secs, mx = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), int(sys.argv[4])
lines = open(f"{out}/eva.log", encoding="utf-8", errors="replace").read().splitlines()
rte, props = [], []
for i, l in enumerate(lines):
    m = re.match(r"^\[eva:alarm\] (\S+):(\d+): Warning: ?(.*)$", l)
    if not m:
        continue
    msg = m.group(3).strip() or (lines[i + 1].strip() if i + 1 < len(lines) else "")
    rec = {"file": m.group(1), "line": int(m.group(2)), "message": msg}
    (rte if ". assert " in " " + msg else props).append(rec)
with open(f"{out}/eva.json", "w") as f:
    json.dump({"frama_c_exit": rc, "seconds": secs, "rte_alarms": rte,
               "unknown_properties": len(props)}, f, indent=1)
md = ["# Frama-C EVA over the whole drive", "",
      f"Runtime-error alarms: **{len(rte)}**; ACSL properties EVA leaves unknown (proved by WP): "
      f"{len(props)}; {secs} s.", "", "| file | line | alarm |", "|---|---:|---|"]
md += [f"| {a['file']} | {a['line']} | {a['message']} |" for a in rte]
open(f"{out}/eva.md", "w").write("\n".join(md) + "\n")
print(f"eva: {len(rte)} runtime-error alarms (limit {mx}), {len(props)} ACSL properties left "
      f"to WP, {secs} s; build/eva/eva.md")
sys.exit(0 if rc == 0 and len(rte) <= mx else 1)
PY
rc=$?
for f in "$OUT/eva.json" "$OUT/eva.md"; do
    /usr/bin/python3 tools/evidence/inputs.py --stamp "$f" eva --started "$t0" > /dev/null ||
        { echo "eva: could not stamp $f with its inputs"; rc=1; }
done
exit "$rc"
