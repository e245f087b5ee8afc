#!/usr/bin/env python3
"""Plan the Frama-C WP jobs of `make prove`: one line per job, longest first.

usage: wp_jobs.py OUTDIR [UNIT.c ...]

A unit (src/*.c, the Q15 header unit, the lemma unit) is proved by one or more
jobs; a job is one Frama-C run over a set of the unit's functions with one prover
order.  proofs/wp/provers.txt sets, from the results of earlier runs:

    <unit> <provers>              the unit's prover order (z3,cvc4 when not listed)
    <unit>:<function> <provers>   the order for one function of the unit (for the
                                  lemma unit: one lemma, by its name)
    split <unit> <n>              the unit's functions of its own order in n jobs

WP tries the provers of a goal one after the other and the timeout is the same for
every prover, so a goal whose first prover cannot prove it waits for that prover's
timeout: a function whose goals one prover proves and the other does not is given
the order that starts with the one that proves them.  A unit whose single job would
set the length of the whole run is split so that both job slots are kept busy; its
functions are spread over the jobs by their weight in the last results
(proofs/wp/results.md: solver time plus a fixed cost per goal).  Splitting changes
nothing in what is proved: every job proves its functions against the contracts of
the functions it calls, exactly as the whole unit does.

Each output line: JOB UNIT_PATH PROVERS SELECT, where SELECT is the comma-separated
function list, '@lemma' (with ',-Name' for each lemma proved in a job of its own) or
'prop:Name,...' for the lemma unit, or '-' for a unit without functions.
Jobs are ordered by the wall times of the last full run (proofs/wp/times.txt), the
longest first, a job not listed there first of all.
"""
import os
import re
import subprocess
import sys

PROVERS = "proofs/wp/provers.txt"
TIMES = "proofs/wp/times.txt"
RESULTS = "proofs/wp/results.md"
DEFAULT_ORDER = "z3,cvc4"
# fixed cost of one goal on top of its solver time (process start, Qed, why3), ms
GOAL_COST_MS = 400.0


def functions_of(path):
    src = "include/qfoc/q15.h" if path.endswith("proofs/wp/q15_unit.c") else path
    out = subprocess.run([sys.executable, "tools/gates/c_functions.py", src], check=True,
                         capture_output=True, text=True).stdout.strip()
    return [f for f in out.split(",") if f]


def read_config():
    unit_order, fn_order, split = {}, {}, {}
    if not os.path.exists(PROVERS):
        return unit_order, fn_order, split
    with open(PROVERS, encoding="utf-8") as f:
        for n, line in enumerate(f, 1):
            line = line.split("#", 1)[0].strip()
            if not line:
                continue
            words = line.split()
            if words[0] == "split" and len(words) == 3 and words[2].isdigit():
                split[words[1]] = max(1, int(words[2]))
            elif len(words) == 2 and re.fullmatch(r"[a-z0-9]+(,[a-z0-9]+)*", words[1]):
                if ":" in words[0]:
                    unit, fn = words[0].split(":", 1)
                    fn_order[(unit, fn)] = words[1]
                else:
                    unit_order[words[0]] = words[1]
            else:
                sys.exit(f"wp_jobs: {PROVERS}:{n}: cannot read '{line}'")
    return unit_order, fn_order, split


def read_weights():
    weights = {}
    if not os.path.exists(RESULTS):
        return weights
    row = re.compile(r"^\| (\S+) \| (\S+) \| (\d+) \| \d+ \| \S+ \| (\d+) \|$")
    with open(RESULTS, encoding="utf-8") as f:
        for line in f:
            m = row.match(line.strip())
            if m:
                weights[(m.group(1), m.group(2))] = int(m.group(4)) + GOAL_COST_MS * int(m.group(3))
    return weights


def read_times():
    times = {}
    if os.path.exists(TIMES):
        with open(TIMES, encoding="utf-8") as f:
            for line in f:
                words = line.split()
                if len(words) == 2 and words[1].isdigit():
                    times[words[0]] = int(words[1])
    return times


def spread(fns, n, weight):
    """Greedy longest-first partition of fns into n lists of close total weight."""
    bins = [[0.0, []] for _ in range(n)]
    for fn in sorted(fns, key=lambda f: (-weight(f), f)):
        b = min(bins, key=lambda x: x[0])
        b[0] += weight(fn)
        b[1].append(fn)
    return [sorted(b[1]) for b in bins if b[1]]


def main():
    outdir = sys.argv[1]
    units = sys.argv[2:] or (sorted(f"src/{f}" for f in os.listdir("src") if f.endswith(".c"))
                             + [os.path.join(outdir, "lemmas_unit.c"), "proofs/wp/q15_unit.c"])
    unit_order, fn_order, split = read_config()
    weights = read_weights()
    times = read_times()
    jobs = []
    for path in units:
        unit = os.path.basename(path)[:-2]
        order = unit_order.get(unit, DEFAULT_ORDER)
        if unit == "lemmas_unit":
            # lemmas by name: the ones with an order of their own in one job each order,
            # every other lemma in the unit's job
            named = {}
            for (u, lemma), prov in sorted(fn_order.items()):
                if u == unit:
                    named.setdefault(prov, []).append(lemma)
            rest = "".join(f",-{lemma}" for prov in named for lemma in named[prov])
            parts = [(order, "@lemma" + rest)]
            parts += [(prov, "prop:" + ",".join(names)) for prov, names in sorted(named.items())]
            for k, (prov, sel) in enumerate(parts, 1):
                jobs.append((unit if len(parts) == 1 else f"{unit}@{k}", path, prov, sel))
            continue
        fns = functions_of(path)
        if not fns:
            jobs.append((unit, path, order, "-"))
            continue
        groups = {}
        for fn in fns:
            groups.setdefault(fn_order.get((unit, fn), order), []).append(fn)
        parts = []
        for prov, members in sorted(groups.items(), key=lambda g: (g[0] != order, g[0])):
            n = split.get(unit, 1) if prov == order else 1
            for chunk in spread(members, min(n, len(members)),
                                lambda f: weights.get((unit, f), GOAL_COST_MS * 20)):
                parts.append((prov, chunk))
        for k, (prov, chunk) in enumerate(parts, 1):
            name = unit if len(parts) == 1 else f"{unit}@{k}"
            jobs.append((name, path, prov, ",".join(chunk)))
    jobs.sort(key=lambda j: (-times.get(j[0], 999999), j[0]))
    for job in jobs:
        print(" ".join(job))
    return 0


if __name__ == "__main__":
    sys.exit(main())
