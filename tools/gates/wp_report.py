#!/usr/bin/env python3
"""Summarise Frama-C WP runs: per-function goals, proved, provers and time.

usage: wp_report.py OUTDIR RESULTS_MD [--cache replay|full]
Reads OUTDIR/<job>.json (-wp-report-json) and OUTDIR/<job>.log of every job
(a unit, or a part UNIT@K of one: tools/gates/wp_jobs.py), writes
RESULTS_MD (committed under proofs/wp/) and OUTDIR/wp-summary.json, prints
'proved N / M goals' and exits 1 unless N == M and every unit ran cleanly.
"""
import json
import os
import re
import sys

GOAL = re.compile(r"^\[wp\] \[([^\]]+)\] Goal (typed_\S+) : (\w+)(.*)$")
TIME = re.compile(r"\((\d+(?:\.\d+)?)(ms|s)\)")


def goal_time_ms(rest: str) -> float:
    """Largest time figure on a goal line, in ms (prover time, or Qed time)."""
    best = 0.0
    for value, unit in TIME.findall(rest):
        t = float(value) * (1000.0 if unit == "s" else 1.0)
        best = max(best, t)
    return best


def print_second_prover(outdir: str) -> None:
    """Name the functions with goals that their job's first prover did not prove: each
    of them waited for that prover to fail (a time-out for Z3), and is a candidate for
    a line of proofs/wp/provers.txt."""
    jobs = os.path.join(outdir, "jobs.txt")
    if not os.path.exists(jobs):
        return
    with open(jobs, encoding="utf-8") as f:
        first = {w[0]: w[2].split(",")[0] for w in (line.split() for line in f) if len(w) == 4}
    for job, prover in sorted(first.items()):
        log = os.path.join(outdir, job + ".log")
        if not os.path.exists(log):
            continue
        late = {}
        with open(log, encoding="utf-8") as f:
            for line in f:
                m = GOAL.match(line.strip())
                if m and m.group(3) == "Valid":
                    who = m.group(1).split()[0].lower()
                    if who not in ("qed", prover):
                        fn = m.group(2)[len("typed_"):]
                        late[fn] = late.get(fn, 0) + 1
        if late:
            print(f"prove: {job}: {sum(late.values())} goal(s) proved only after {prover} "
                  f"(see proofs/wp/provers.txt): " + ", ".join(sorted(late)))


def provenance(outdir: str, mode: str) -> dict:
    """How the goals of this run were proved: by Qed, by a prover in this run, or by the
    verdict that proofs/wp/cache.txt records for the same goal text (tools/gates/wp_cache.py)."""
    cached = fresh = qed = 0
    for name in sorted(os.listdir(outdir)):
        if not name.endswith(".log"):
            continue
        with open(os.path.join(outdir, name), encoding="utf-8") as f:
            for line in f:
                m = GOAL.match(line.strip())
                if not m or m.group(3) != "Valid":
                    continue
                if m.group(1) == "Qed":
                    qed += 1
                elif line.rstrip().endswith("(cached)"):
                    cached += 1
                else:
                    fresh += 1
    fresh_jobs = []
    if os.path.exists(os.path.join(outdir, "fresh.txt")):
        with open(os.path.join(outdir, "fresh.txt"), encoding="utf-8") as f:
            fresh_jobs = f.read().split()
    return {"mode": mode, "qed": qed, "prover": fresh, "store": cached, "fresh_jobs": fresh_jobs}


def main() -> int:
    outdir, results_md = sys.argv[1], sys.argv[2]
    mode = sys.argv[4] if len(sys.argv) == 5 and sys.argv[3] == "--cache" else "full"
    prov = provenance(outdir, mode)
    rows = []
    total = valid = 0
    clean = True
    logs = sorted(f[:-4] for f in os.listdir(outdir) if f.endswith(".log"))
    units = [u for u in logs if os.path.exists(os.path.join(outdir, u + ".json"))]
    for missing in sorted(set(logs) - set(units)):
        print(f"prove: unit {missing} produced no report (see {outdir}/{missing}.log)")
        clean = False
    if os.path.exists(os.path.join(outdir, "failed")):
        clean = False
    for unit in units:
        with open(os.path.join(outdir, unit + ".json"), encoding="utf-8") as f:
            rep = json.load(f)
        goals = []  # (name, prover, status, ms)
        with open(os.path.join(outdir, unit + ".log"), encoding="utf-8") as f:
            for line in f:
                m = GOAL.match(line.strip())
                if m:
                    goals.append((m.group(2), m.group(1), m.group(3), goal_time_ms(m.group(4))))
        sections = []
        for fn, props in rep.get("wp:functions", {}).items():
            sections.append((fn, props))
        for axiomatic, props in rep.get("wp:axiomatics", {}).items():
            lemmas = {k: v for k, v in props.items() if k != "wp:section"}
            sections.append(("lemmas" + (" " + axiomatic if axiomatic else ""), lemmas))
        for fn, props in sections:
            t = v = 0
            for _prop, res in props.items():
                if _prop == "wp:section":
                    continue
                main_res = res.get("wp:main", {})
                t += main_res.get("total", 0)
                v += main_res.get("valid", 0)
            if fn.startswith("lemmas"):
                names = ["typed_" + p for p in props]
                mine = [g for g in goals if g[0] in names]
            else:
                mine = [g for g in goals if g[0].startswith("typed_" + fn + "_")]
            provers = sorted({g[1].split()[0] for g in mine if g[2] == "Valid"})
            ms = sum(g[3] for g in mine)
            # a unit proved in several jobs (tools/gates/wp_jobs.py) logs as UNIT@K
            rows.append((unit.split("@")[0], fn, t, v, "+".join(provers) or "-", ms))
            total += t
            valid += v
    rows.sort(key=lambda r: (r[0], r[1]))
    with open(results_md, "w", encoding="utf-8") as f:
        f.write("# Frama-C WP results, per function\n\n")
        f.write("Generated by `make prove` (tools/gates/prove.sh, tools/gates/wp_report.py): Frama-C 25 WP "
                "with -wp-rte, signed/unsigned overflow and downcast checks, provers z3 and cvc4. "
                "Time is the sum of the goals' solver times (ms); Qed means the goal was "
                "discharged by WP's own simplifier.\n\n")
        f.write(f"**proved {valid} / {total} goals**\n\n")
        if mode == "full":
            f.write(f"Proved in this run (make prove-full, no recorded result read): "
                    f"{prov['qed']} by Qed, {prov['prover']} by a prover.\n\n")
        else:
            jobs = ", ".join(prov["fresh_jobs"]) or "none"
            f.write(f"Proved in this run: {prov['qed']} by Qed, {prov['prover']} by a prover "
                    f"(the jobs proved without any recorded result: {jobs}); {prov['store']} by "
                    "the verdict recorded in proofs/wp/cache.txt for the same goal, digest for "
                    "digest as sent to the prover (tools/gates/wp_cache.py; make prove-full "
                    "proves every goal anew).\n\n")
        f.write("| unit | function | goals | proved | provers | time (ms) |\n")
        f.write("|---|---|---:|---:|---|---:|\n")
        for unit, fn, t, v, provers, ms in rows:
            f.write(f"| {unit} | {fn} | {t} | {v} | {provers} | {ms:.0f} |\n")
    with open(os.path.join(outdir, "wp-summary.json"), "w", encoding="utf-8") as f:
        json.dump({"proved": valid, "total": total, "clean": clean, "provenance": prov,
                   "functions": [dict(zip(("unit", "function", "goals", "proved", "provers",
                                           "time_ms"), r)) for r in rows]}, f, indent=1)
    print_second_prover(outdir)
    for unit, fn, t, v, _p, _ms in rows:
        if v != t:
            print(f"prove: {unit}: {fn}: {t - v} goal(s) not proved")
    print(f"proved {valid} / {total} goals")
    return 0 if (clean and valid == total and total > 0) else 1


if __name__ == "__main__":
    sys.exit(main())
