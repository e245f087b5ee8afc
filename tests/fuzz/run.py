#!/usr/bin/env python3
# The runner of the fuzz campaign (make fuzz) and of its short pass (make fuzz-check).
# Requirements: REQ-FUZZ-007.
"""Run the libFuzzer harnesses of tests/fuzz/ and write their results (REQ-FUZZ-007).

  run.py --mode full  --time T [--workers W] [--parallel P] TARGET...
  run.py --mode check --time T [--workers W] [--parallel P] TARGET...
  options: --build DIR (default build/fuzz; the harness of TARGET is DIR/fuzz_TARGET),
           --corpus DIR (default tests/fuzz/corpus; the committed corpus of TARGET is
           DIR/TARGET), --flags TEXT (the compile flags, recorded in the results)

full   each target is fuzzed for T seconds by W processes (libFuzzer, sharing the working
       corpus DIR/TARGET/corpus, seeded from the committed corpus, which is only read);
       then the working corpus and the committed one are replayed once (-runs=0) for the
       coverage the whole corpus reaches.  The working corpus is kept between runs.
check  each target replays its committed corpus (-runs=0), then is fuzzed for T seconds
       from it (a fresh working corpus under DIR/check/TARGET).
P targets run at the same time (default 1).

A finding is any abnormal end of a libFuzzer process: a crash, a broken guarantee
(abort() in a harness), a sanitizer report (AddressSanitizer, UndefinedBehaviorSanitizer,
LeakSanitizer), a timeout or an out-of-memory; libFuzzer writes the input that caused it to
DIR/TARGET/artifacts/.  Writes DIR/results.json and DIR/results.md (per target:
executions (those of the replay of the committed corpus included in check mode), exec/s of
the fuzzing (all its processes together), cov and ft of libFuzzer's status line after the
replay of the whole corpus, files and bytes of the whole corpus (working and committed),
findings, time) and exits 1 on any
finding.
"""
import argparse
import json
import os
import platform
import re
import shutil
import subprocess
import sys
import time
from concurrent.futures import ThreadPoolExecutor

# libFuzzer options per target: the longest input (the harness reads no further)
MAX_LEN = {
    "link_decode": 258,
    "link_service": 1024,
    "drive_tick": 2048,
    "drive_fast_step": 4096,
    "drive_command": 2048,
    "params_check": 1024,
}
TIMEOUT_S = 25          # one input longer than this is a finding (timeout)
RSS_LIMIT_MB = 2048     # a process above this is a finding (out of memory)

FINDING_RE = re.compile(r"==\d+==ERROR: |runtime error: |qfoc-fuzz: guarantee broken|"
                        r"ERROR: libFuzzer: |SUMMARY: (Address|Undefined|Leak)Sanitizer")
STATUS_RE = re.compile(r"^#(\d+)\s+(INITED|DONE|NEW|REDUCE|pulse|RELOAD)\s+cov: (\d+) ft: (\d+)"
                       r"(?: corp: (\d+)/(\d+)(b|Kb|Mb))?", re.M)


def sh(cmd, log, cwd=None):
    with open(log, "w", encoding="utf-8") as f:
        f.write("$ " + " ".join(cmd) + "\n")
        f.flush()
        return subprocess.call(cmd, stdout=f, stderr=subprocess.STDOUT, cwd=cwd)


def read(path):
    with open(path, encoding="utf-8", errors="replace") as f:
        return f.read()


def stat(text, key):
    m = re.search(r"^stat::" + key + r":\s+(\d+)", text, re.M)
    return int(m.group(1)) if m else None


def last_status(text):
    rows = STATUS_RE.findall(text)
    if not rows:
        return None
    n, _kind, cov, ft = rows[-1][:4]
    return {"units": int(n), "cov": int(cov), "ft": int(ft)}


def findings_of(text, rc):
    lines = [ln for ln in text.splitlines() if FINDING_RE.search(ln)]
    return lines, (rc != 0 or bool(lines))


def corpus_size(*dirs):
    """Files and bytes of the union of corpus folders (libFuzzer names an input by its
    SHA-1, so a name present in two folders is one input)."""
    seen = {}
    for d in dirs:
        if not os.path.isdir(d):
            continue
        for f in os.listdir(d):
            p = os.path.join(d, f)
            if os.path.isfile(p) and f not in seen:
                seen[f] = os.path.getsize(p)
    return len(seen), sum(seen.values())


def base_opts(target, art):
    return [f"-max_len={MAX_LEN.get(target, 4096)}", f"-timeout={TIMEOUT_S}",
            f"-rss_limit_mb={RSS_LIMIT_MB}", "-print_final_stats=1",
            f"-artifact_prefix={art}/"]


def run_target(target, args):
    exe = os.path.abspath(os.path.join(args.build, "fuzz_" + target))
    seed = os.path.join(args.corpus, target)
    os.makedirs(seed, exist_ok=True)
    if args.mode == "full":
        tdir = os.path.join(args.build, target)
    else:
        tdir = os.path.join(args.build, "check", target)
        shutil.rmtree(tdir, ignore_errors=True)
    work = os.path.join(tdir, "corpus")
    art = os.path.join(tdir, "artifacts")
    logs = os.path.join(tdir, "logs")
    shutil.rmtree(art, ignore_errors=True)
    shutil.rmtree(logs, ignore_errors=True)
    for d in (work, art, logs):
        os.makedirs(d, exist_ok=True)
    opts = base_opts(target, art)
    res = {"target": target, "mode": args.mode, "workers": args.workers,
           "fuzz_time_s": args.time, "findings": 0, "finding_lines": [], "artifacts": []}
    t0 = time.time()
    execs = 0

    if args.mode == "check":
        # the committed corpus, every input once
        log = os.path.join(logs, "replay.log")
        rc = sh([exe, "-runs=0"] + opts + [seed], log)
        text = read(log)
        st = last_status(text)
        lines, bad = findings_of(text, rc)
        res["replay_inputs"] = corpus_size(seed)[0]
        res["replay_cov"] = st["cov"] if st else None
        res["replay_ft"] = st["ft"] if st else None
        res["replay_executions"] = stat(text, "number_of_executed_units") or 0
        execs += res["replay_executions"]
        if bad:
            res["findings"] += 1
            res["finding_lines"] += lines[:5] or [f"replay exited with status {rc}"]

    # W processes fuzzing for T seconds
    t_fuzz = time.time()
    fuzz_execs = 0
    procs = []
    for k in range(args.workers):
        log = os.path.join(logs, f"worker{k}.log")
        f = open(log, "w", encoding="utf-8")
        cmd = [exe, f"-max_total_time={args.time}"] + opts + [work, seed]
        f.write("$ " + " ".join(cmd) + "\n")
        f.flush()
        procs.append((subprocess.Popen(cmd, stdout=f, stderr=subprocess.STDOUT), f, log))
    for p, f, log in procs:
        rc = p.wait()
        f.close()
        text = read(log)
        n = stat(text, "number_of_executed_units")
        if n is None:
            st = last_status(text)
            n = st["units"] if st else 0
        fuzz_execs += n
        lines, bad = findings_of(text, rc)
        if bad:
            res["findings"] += 1
            res["finding_lines"] += lines[:5] or [f"{os.path.basename(log)} exited with status {rc}"]
    fuzz_s = time.time() - t_fuzz

    # coverage of the corpus: the working corpus and the committed one replayed once
    log = os.path.join(logs, "coverage.log")
    rc = sh([exe, "-runs=0"] + opts + [work, seed], log)
    text = read(log)
    st = last_status(text)
    lines, bad = findings_of(text, rc)
    if bad:
        res["findings"] += 1
        res["finding_lines"] += lines[:5] or [f"corpus replay exited with status {rc}"]
    res["cov"] = st["cov"] if st else None
    res["ft"] = st["ft"] if st else None

    res["artifacts"] = sorted(os.listdir(art))
    res["findings"] = max(res["findings"], len(res["artifacts"]))
    execs += fuzz_execs
    res["executions"] = execs
    res["fuzz_executions"] = fuzz_execs
    res["fuzz_wall_s"] = round(fuzz_s, 1)
    res["exec_per_s"] = int(round(fuzz_execs / fuzz_s)) if fuzz_s > 0 else 0
    nf, nb = corpus_size(work, seed)
    res["corpus_files"], res["corpus_bytes"] = nf, nb
    sf, sb = corpus_size(seed)
    res["committed_corpus_files"], res["committed_corpus_bytes"] = sf, sb
    res["time_s"] = round(time.time() - t0, 1)
    print(f"fuzz {args.mode}: {target}: {execs} executions ({res['exec_per_s']}/s, "
          f"{args.workers} process{'es' if args.workers > 1 else ''}, {res['fuzz_wall_s']} s), "
          f"cov {res['cov']} ft {res['ft']}, corpus {nf} files {nb} B, "
          f"findings {res['findings']}", flush=True)
    for ln in res["finding_lines"]:
        print(f"fuzz {args.mode}: {target}:   {ln}", flush=True)
    return res


def machine():
    cpu = platform.processor() or ""
    try:
        for ln in read("/proc/cpuinfo").splitlines():
            if ln.startswith("model name"):
                cpu = ln.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    try:
        load = read("/proc/loadavg").split()[:3]
    except OSError:
        load = []
    return {"host": platform.node(), "cpu": cpu, "cpus": os.cpu_count(), "loadavg": load}


def write(args, results, wall):
    total = sum(r["executions"] for r in results)
    findings = sum(r["findings"] for r in results)
    doc = {
        "generated_by": "tests/fuzz/run.py",
        "mode": args.mode,
        "date": time.strftime("%Y-%m-%d %H:%M:%S %Z"),
        "machine": machine(),
        "fuzz_time_s": args.time,
        "workers": args.workers,
        "parallel": args.parallel,
        "flags": args.flags,
        "wall_s": round(wall, 1),
        "total_executions": total,
        "total_findings": findings,
        "targets": results,
    }
    os.makedirs(args.build, exist_ok=True)
    with open(os.path.join(args.build, "results.json"), "w", encoding="utf-8") as f:
        json.dump(doc, f, indent=1)
        f.write("\n")
    m = doc["machine"]
    with open(os.path.join(args.build, "results.md"), "w", encoding="utf-8") as f:
        f.write(f"# Fuzzing results ({args.mode})\n\n")
        f.write(f"Generated by `tests/fuzz/run.py` ({'make fuzz' if args.mode == 'full' else 'make fuzz-check'}) "
                f"on {doc['date']}, host {m['host']} ({m['cpu']}, {m['cpus']} CPUs, load average "
                f"{' '.join(m['loadavg'])} at the end).\n\n")
        f.write(f"- mode: {args.mode}; fuzzing time per target: {args.time} s; processes per target: "
                f"{args.workers}; targets at a time: {args.parallel}; wall time: {doc['wall_s']} s\n")
        f.write(f"- flags: `{args.flags}`\n")
        f.write(f"- executions in all: {total}; findings: {findings}\n\n")
        f.write("| target | executions | exec/s | cov | ft | corpus files | corpus bytes | findings | time s |\n")
        f.write("|---|---:|---:|---:|---:|---:|---:|---:|---:|\n")
        for r in results:
            f.write(f"| {r['target']} | {r['executions']} | {r['exec_per_s']} | {r['cov']} | {r['ft']} | "
                    f"{r['corpus_files']} | {r['corpus_bytes']} | {r['findings']} | {r['time_s']} |\n")
        bad = [r for r in results if r["findings"]]
        if bad:
            f.write("\n## Findings\n\n")
            for r in bad:
                f.write(f"- {r['target']}: artefacts {', '.join(r['artifacts']) or '-'} in "
                        f"`{args.build}/{'check/' if args.mode == 'check' else ''}{r['target']}/artifacts/`\n")
                for ln in r["finding_lines"]:
                    f.write(f"  - `{ln.strip()}`\n")
    return total, findings


def write_junit(path, args, results, wall):
    """JUnit XML of the run: a test case per harness, named by its source file
    (fuzz_TARGET.c), failed when it has findings or did not run, and `run.py` for the whole;
    make evidence reads the verdicts of REQ-FUZZ-* from it."""
    import xml.etree.ElementTree as ET
    cases = []
    for r in results:
        ok = r["findings"] == 0 and r["executions"] > 0
        msg = (f"{r['findings']} findings: " + "; ".join(ln.strip() for ln in r["finding_lines"][:5])
               if r["findings"] else "no execution")
        cases.append((f"fuzz_{r['target']}.c", ok, msg, r["time_s"]))
    cases.append(("run.py", all(ok for _n, ok, _m, _t in cases),
                  "failing harnesses: " + ", ".join(n for n, ok, _m, _t in cases if not ok), wall))
    suite = ET.Element("testsuite", name="fuzz", tests=str(len(cases)),
                       failures=str(sum(1 for _n, ok, _m, _t in cases if not ok)), errors="0",
                       time=f"{wall:.1f}",
                       timestamp=time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime()))
    props = ET.SubElement(suite, "properties")
    ET.SubElement(props, "property", name="mode", value=args.mode)
    for name, ok, msg, t in cases:
        tc = ET.SubElement(suite, "testcase", classname="fuzz", name=name, time=f"{float(t or 0):.1f}")
        if not ok:
            ET.SubElement(tc, "failure", message=msg[:2000])
    os.makedirs(os.path.dirname(path) or ".", exist_ok=True)
    ET.ElementTree(suite).write(path, encoding="utf-8", xml_declaration=True)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--mode", choices=("full", "check"), required=True)
    ap.add_argument("--time", type=int, required=True)
    ap.add_argument("--workers", type=int, default=1)
    ap.add_argument("--parallel", type=int, default=1)
    ap.add_argument("--build", default="build/fuzz")
    ap.add_argument("--corpus", default="tests/fuzz/corpus")
    ap.add_argument("--flags", default="")
    ap.add_argument("--junit", default="build/junit/fuzz.xml", help="JUnit XML of the run")
    ap.add_argument("targets", nargs="+")
    args = ap.parse_args()
    t0 = time.time()
    with ThreadPoolExecutor(max_workers=max(1, args.parallel)) as ex:
        results = list(ex.map(lambda t: run_target(t, args), args.targets))
    wall = time.time() - t0
    total, findings = write(args, results, wall)
    write_junit(args.junit, args, results, wall)
    print(f"fuzz {args.mode}: {len(results)} targets, {total} executions, {findings} findings, "
          f"{wall:.0f} s (build/fuzz/results.md)")
    return 1 if findings else 0


if __name__ == "__main__":
    sys.exit(main())
