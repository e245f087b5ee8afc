#!/usr/bin/env python3
"""Tool validation by seeded defects (REQ-EVD-030; ISO 26262-8 11.4.9, method 1c).

usage: run.py [--catalogue FILE] [--out DIR] [--jobs N] [--only TV-01,TV-02] [--check]

Each defect of the catalogue (tools/validation/defects.toml) is seeded into a copy of the
repository (the parts the gates read: Makefile, mk/, src/, include/, specs/, proofs/,
tests/, tools/, sim/, tables/, misra/, port_s32k/, copied from the working tree) by an
exact text substitution, and each gate expected to catch it runs on that copy, scoped to
the unit the defect touches:

  wp        tools/gates/prove.sh UNIT...        (WP_JOBS=1; WP_TIMEOUT: the scope's
            wp_timeout, prove.sh's 120 s without it); caught: a goal not proved
  cbmc      tools/gates/cbmc.sh HARNESS...      (JOBS=1);    caught: a property fails
  tests     make build/host/tests/TEST..., tools/gates/run_tests.sh; caught: a test fails,
            or the build stops on a -Werror diagnostic (the test gate builds with -Werror)
  coverage  the unit's object built --coverage, the rest of the library without, the
            unit's tests, tools/gates/coverage.sh with COV_FILTER = the unit's source;
            caught: below 100 % of lines or branches
  misra     tools/gates/misra.sh over the whole library: its cross-unit rules (2.3, 2.4
            unused declarations, 8.7, ...) give false findings on one unit alone, and the
            whole run takes about 15 s; caught: an unrecorded finding or a suppression
            without a matching deviation record
  eva       tools/gates/eva.sh over the whole drive (it has no per-unit mode; about two
            minutes of CPU): used for one defect only; caught: a runtime-error alarm

Each (defect, gate) runs alone in its own copy (build/validation/TV-nn/GATE/), at most
--jobs (2) at a time.  The control: the unmodified copy through every (scope, gate) that
some defect uses (build/validation/control/), each of which must pass: a gate that always
fails would validate nothing.  A defect whose substitution does not match its file exactly
once stops the run before any gate runs.

Writes build/validation/results.json and results.md (per defect and gate: caught, MISSED,
ERROR or not expected, with the gate's own figure and the time; the control; the wall and
CPU time), prints one line per job, and exits 1 when an expected catch is missed, a gate
ends in an error, or the control does not pass.  --check only reads the catalogue and
checks the substitutions against the working tree.
"""
import argparse
import concurrent.futures
import datetime
import json
import os
import re
import shutil
import signal
import subprocess
import sys
import threading
import time
import tomllib

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
CATALOGUE = os.path.join(HERE, "defects.toml")
GATES = ("wp", "cbmc", "eva", "misra", "tests", "coverage")
LIBRARY_GATES = ("misra", "eva")       # run over the whole library, not per unit
COPY = ("Makefile", "mk", "src", "include", "specs", "proofs", "tests", "tools", "sim",
        "tables", "misra", "port_s32k")
ID = re.compile(r"^TV-\d\d$")
STEP_TIMEOUT = 3600                     # seconds: a hung gate is killed and is an error
# rough cost of a gate run in CPU seconds, for the order only (longest first)
COST = {"eva": 110, "misra": 15, "tests": 10, "coverage": 10}


class CatalogueError(Exception):
    """The catalogue cannot be used as it is (the message says where)."""


# --------------------------------------------------------------------------- catalogue


def substitute(text, old, new, where="the file"):
    """text with old replaced by new; old must occur exactly once."""
    if not old:
        raise CatalogueError(f"{where}: the old text is empty")
    n = text.count(old)
    if n != 1:
        raise CatalogueError(f"{where}: the old text occurs {n} times (exactly once needed): "
                             f"{old.splitlines()[0].strip() if old.strip() else repr(old)!r}")
    return text.replace(old, new, 1)


def parse_catalogue(data):
    """(scopes, defects) from the parsed TOML; CatalogueError on any inconsistency."""
    if not isinstance(data, dict):
        raise CatalogueError("the catalogue is not a table")
    scopes = data.get("scope", {})
    defects = data.get("defect", [])
    if not isinstance(scopes, dict) or not isinstance(defects, list) or not defects:
        raise CatalogueError("the catalogue needs [scope.NAME] tables and [[defect]] entries")
    for name, sc in scopes.items():
        for key in sc:
            if key not in ("wp", "wp_timeout", "cbmc", "tests", "cover"):
                raise CatalogueError(f"scope {name}: unknown key '{key}'")
        for key in ("wp", "cbmc", "tests"):
            v = sc.get(key, [])
            if not isinstance(v, list) or not all(isinstance(x, str) and x for x in v):
                raise CatalogueError(f"scope {name}: '{key}' must be a list of names")
        if "wp_timeout" in sc and not (isinstance(sc["wp_timeout"], int) and 1 <= sc["wp_timeout"] <= 600):
            raise CatalogueError(f"scope {name}: 'wp_timeout' must be a number of seconds, 1 .. 600")
        if "cover" in sc and not (isinstance(sc["cover"], str) and sc["cover"].startswith("src/")
                                  and sc["cover"].endswith(".c")):
            raise CatalogueError(f"scope {name}: 'cover' must be a src/*.c file")
    seen = set()
    for d in defects:
        did = d.get("id", "?")
        if not ID.match(str(did)):
            raise CatalogueError(f"defect '{did}': the id must be TV-nn")
        if did in seen:
            raise CatalogueError(f"defect {did}: the id is used twice")
        seen.add(did)
        for key in ("class", "title", "why", "file", "scope", "old"):
            if not isinstance(d.get(key), str) or not d[key]:
                raise CatalogueError(f"defect {did}: '{key}' is missing or empty")
        if not isinstance(d.get("new"), str):
            raise CatalogueError(f"defect {did}: 'new' is missing")
        if d["old"] == d["new"]:
            raise CatalogueError(f"defect {did}: 'new' equals 'old' (nothing is seeded)")
        gates = d.get("gates")
        if not isinstance(gates, list) or not gates:
            raise CatalogueError(f"defect {did}: 'gates' must list the gates expected to catch it")
        for g in gates:
            if g not in GATES:
                raise CatalogueError(f"defect {did}: unknown gate '{g}' (known: {', '.join(GATES)})")
        if len(set(gates)) != len(gates):
            raise CatalogueError(f"defect {did}: a gate is listed twice")
        sc = scopes.get(d["scope"])
        if sc is None:
            raise CatalogueError(f"defect {did}: unknown scope '{d['scope']}'")
        need = {"wp": ("wp",), "cbmc": ("cbmc",), "tests": ("tests",), "coverage": ("cover", "tests")}
        for g in gates:
            for key in need.get(g, ()):
                if not sc.get(key):
                    raise CatalogueError(f"defect {did}: gate {g} needs '{key}' in scope {d['scope']}")
    return scopes, defects


def load_catalogue(path):
    try:
        with open(path, "rb") as f:
            data = tomllib.load(f)
    except (OSError, tomllib.TOMLDecodeError) as e:
        raise CatalogueError(f"{path}: {e}") from e
    return parse_catalogue(data)


def check_sources(root, scopes, defects):
    """Every substitution matches its file exactly once, every scope names what exists."""
    problems = []
    for d in defects:
        path = os.path.join(root, d["file"])
        try:
            with open(path, encoding="utf-8") as f:
                substitute(f.read(), d["old"], d["new"], f"{d['id']} ({d['file']})")
        except OSError:
            problems.append(f"{d['id']}: {d['file']} not found")
        except CatalogueError as e:
            problems.append(str(e))
    for name, sc in scopes.items():
        for u in sc.get("wp", []):
            if not os.path.isfile(os.path.join(root, u)):
                problems.append(f"scope {name}: WP unit {u} not found")
        for h in sc.get("cbmc", []):
            if not os.path.isfile(os.path.join(root, "proofs", "cbmc", h, "harness.c")):
                problems.append(f"scope {name}: CBMC harness proofs/cbmc/{h} not found")
        for t in sc.get("tests", []):
            if not os.path.isfile(os.path.join(root, "tests", t + ".c")):
                problems.append(f"scope {name}: test tests/{t}.c not found")
        if sc.get("cover") and not os.path.isfile(os.path.join(root, sc["cover"])):
            problems.append(f"scope {name}: {sc['cover']} not found")
    if problems:
        raise CatalogueError("\n".join(problems))


# --------------------------------------------------------------------------- classification


def _last(pattern, text):
    found = re.findall(pattern, text, re.M)
    return found[-1] if found else None


def _lines(pattern, text, limit=6):
    out = [ln.strip() for ln in text.splitlines() if re.search(pattern, ln)]
    more = len(out) - limit
    return out[:limit] + ([f"... {more} more"] if more > 0 else [])


def classify(gate, steps):
    """The verdict of one gate run: ('pass' | 'fail' | 'error', detail).

    steps: the commands run in order, each {'label', 'rc', 'output'}; the run stops at the
    first command that fails.  'fail' means the gate reported a finding of its own kind
    (the signature below); a failure without it (a tool that did not run, a parse error)
    is an 'error', never a catch."""
    if not steps:
        return "error", "nothing ran"
    last = steps[-1]
    rc, out, label = last["rc"], last["output"], last["label"]
    if rc is None:
        return "error", f"{label}: killed after {STEP_TIMEOUT} s"
    if gate == "wp":
        m = _last(r"^proved (\d+) / (\d+) goals$", out)
        if not m:
            return "error", "no 'proved N / M goals' line"
        proved, total = int(m[0]), int(m[1])
        limit = _last(r"^prove: Frama-C WP \(.*timeout (\d+) s\)", out)
        fig = f"proved {proved} / {total} goals" + (f" (prover time-out {limit} s)" if limit else "")
        if rc == 0 and proved == total and total > 0:
            return "pass", fig
        if rc != 0 and proved < total:
            return "fail", "; ".join([fig] + _lines(r"^prove: .*goal\(s\) not proved", out, 3)
                                     + _lines(r"^\[wp\] \[[^\]]+\] Goal \S+ : (?!Valid)", out, 3))
        return "error", f"{fig}, exit status {rc} (a unit did not run cleanly)"
    if gate == "cbmc":
        if "self-test of the SAT back end FAILED" in out:
            return "error", "CBMC's self-test failed"
        rows = re.findall(r"^  (\S+): (PASS|FAIL) \((\d+) properties hold, (\d+) fail", out, re.M)
        if not rows:
            return "error", "no harness result"
        failed = [r for r in rows if r[1] == "FAIL" and int(r[3]) > 0]
        if rc == 0 and all(r[1] == "PASS" for r in rows):
            return "pass", "; ".join(f"{r[0]}: {r[2]} properties hold" for r in rows)
        if rc != 0 and failed:
            return "fail", "; ".join([f"{r[0]}: {r[3]} of {int(r[2]) + int(r[3])} properties fail"
                                      for r in failed] + _lines(r": FAILURE$", out, 4))
        return "error", "; ".join(f"{r[0]}: {r[1]} with {r[3]} failed properties" for r in rows)
    if gate == "tests":
        if label == "build":
            if rc == 0:
                return "error", "the run step is missing"
            werr = _lines(r"error: .*\[-Werror", out, 2)
            if werr:
                return "fail", "build stopped by -Werror: " + "; ".join(werr)
            return "error", "build failed: " + "; ".join(_lines(r"error", out, 2))
        m = _last(r"^(\d+) passed, (\d+) failed$", out)
        if not m:
            return "error", "no 'N passed, M failed' line"
        passed, failed = int(m[0]), int(m[1])
        fig = f"{passed} passed, {failed} failed"
        if rc == 0 and failed == 0 and passed > 0:
            return "pass", fig
        if rc != 0 and failed > 0:
            return "fail", "; ".join([fig] + _lines(r"^\[  FAILED  \] test_|exited with status", out, 3))
        return "error", f"{fig}, exit status {rc}"
    if gate == "coverage":
        if label != "coverage":
            return "error", f"{label} failed: " + "; ".join(_lines(r"error", out, 2))
        figs = _lines(r"^(lines|branches): ", out, 2)
        if rc == 0 and len(figs) == 2 and all("100.0%" in f for f in figs):
            return "pass", "; ".join(figs)
        if rc != 0 and "coverage: below 100 %" in out:
            return "fail", "; ".join(figs + _lines(r"^src/\S+\s+\d+\s+\d+\s+\d+%", out, 2))
        return "error", "; ".join(_lines(r"^coverage: ", out, 2) or [f"exit status {rc}"])
    if gate == "misra":
        m = _last(r"^misra: (\d+) unrecorded findings, (\d+) suppressions \((\d+) with deviation records\)$",
                  out)
        if not m:
            return "error", "no 'misra: N unrecorded findings' line"
        findings, supps, recorded = int(m[0]), int(m[1]), int(m[2])
        fig = f"{findings} unrecorded findings, {supps - recorded} suppressions without a matching record"
        if rc == 0 and findings == 0 and supps == recorded:
            return "pass", fig
        if rc != 0 and (findings > 0 or supps > recorded):
            return "fail", "; ".join([fig] + _lines(r": misra-c2012-|without a matching deviation record",
                                                    out, 3))
        return "error", f"{fig}, exit status {rc}"
    if gate == "eva":
        m = _last(r"^eva: (\d+) runtime-error alarms", out)
        if not m:
            return "error", "no 'eva: N runtime-error alarms' line"
        n = int(m)
        if rc == 0 and n == 0:
            return "pass", "0 runtime-error alarms"
        if rc != 0 and n > 0:
            return "fail", "; ".join([f"{n} runtime-error alarms"] + _lines(r"^ALARM ", out, 4))
        return "error", f"{n} runtime-error alarms, exit status {rc}"
    return "error", f"unknown gate {gate}"


def outcome(kind, verdict):
    """The cell of the report: a defect's gate is caught / MISSED, the control's passes /
    FALSE ALARM; an error is an ERROR either way."""
    if verdict == "error":
        return "ERROR"
    if kind == "defect":
        return "caught" if verdict == "fail" else "MISSED"
    return "pass" if verdict == "pass" else "FALSE ALARM"


def job_ok(kind, verdict):
    return (kind == "defect" and verdict == "fail") or (kind == "control" and verdict == "pass")


# --------------------------------------------------------------------------- jobs


def wp_cost(units):
    cost = 0
    try:
        with open(os.path.join(ROOT, "proofs", "wp", "times.txt"), encoding="utf-8") as f:
            times = [ln.split() for ln in f if len(ln.split()) == 2]
    except OSError:
        times = []
    for u in units:
        name = os.path.basename(u)[:-2]
        cost += sum(int(t) for j, t in times if j.split("@")[0] == name and t.isdigit()) or 60
    return cost


def cbmc_cost(harnesses):
    cost = 0
    try:
        with open(os.path.join(ROOT, "proofs", "cbmc", "results.md"), encoding="utf-8") as f:
            text = f.read()
    except OSError:
        text = ""
    for h in harnesses:
        m = re.search(r"^\| " + re.escape(h) + r" \| \w+ \| \d+ \| \d+ \| \d+ \| (\d+) \|$", text, re.M)
        cost += int(m.group(1)) if m else 60
    return cost


def make_jobs(scopes, defects, out, control=True):
    jobs = []

    def add(kind, name, scope, gate, defect):
        if gate in LIBRARY_GATES:
            sub = gate
        else:
            sub = f"{scope}-{gate}" if kind == "control" else gate
        sc = scopes[scope]
        cost = {"wp": lambda: wp_cost(sc.get("wp", [])),
                "cbmc": lambda: cbmc_cost(sc.get("cbmc", []))}.get(gate, lambda: COST[gate])()
        jobs.append({"kind": kind, "name": name, "scope": scope, "gate": gate, "defect": defect,
                     "dir": os.path.join(out, name, sub), "cost": cost * (2 if kind == "defect" else 1)})

    pairs = []
    for d in defects:
        for g in d["gates"]:
            add("defect", d["id"], d["scope"], g, d)
            key = ("library", g) if g in LIBRARY_GATES else (d["scope"], g)
            if key not in [p[0] for p in pairs]:
                pairs.append((key, d["scope"]))
    if control:
        for (_key, g), scope in pairs:
            add("control", "control", scope, g, None)
    jobs.sort(key=lambda j: -j["cost"])
    return jobs


def copy_tree(dst, defect=None):
    if os.path.exists(dst):
        shutil.rmtree(dst)
    os.makedirs(dst)
    ignore = shutil.ignore_patterns("__pycache__", ".pytest_cache", "*.gcda", "*.gcno")
    for name in COPY:
        src = os.path.join(ROOT, name)
        if os.path.isdir(src):
            shutil.copytree(src, os.path.join(dst, name), ignore=ignore, symlinks=True)
        elif os.path.exists(src):
            shutil.copy2(src, os.path.join(dst, name))
    if defect is not None:
        path = os.path.join(dst, defect["file"])
        with open(path, encoding="utf-8") as f:
            text = substitute(f.read(), defect["old"], defect["new"], f"{defect['id']} ({defect['file']})")
        with open(path, "w", encoding="utf-8") as f:
            f.write(text)
        os.utime(path)   # newer than anything built before


def gate_steps(job, scopes, cbmc):
    sc = scopes[job["scope"]]
    gate = job["gate"]
    if gate == "wp":
        # the prover time-out of the scope, or prove.sh's own (120 s) when the scope sets none
        return [("prove", ["sh", "tools/gates/prove.sh", *sc["wp"]],
                 {"WP_JOBS": "1", "WP_TIMEOUT": str(sc["wp_timeout"]) if "wp_timeout" in sc else None})]
    if gate == "cbmc":
        return [("cbmc", ["sh", "tools/gates/cbmc.sh", *[f"proofs/cbmc/{h}" for h in sc["cbmc"]]],
                 {"JOBS": "1", "CBMC": cbmc})]
    if gate == "tests":
        bins = [f"build/host/tests/{t}" for t in sc["tests"]]
        return [("build", ["make", "-s", *bins], {}),
                ("run", ["sh", "tools/gates/run_tests.sh", *bins], {})]
    if gate == "coverage":
        unit = os.path.basename(sc["cover"])[:-2]
        others = sorted(f[:-2] for f in os.listdir(os.path.join(ROOT, "src"))
                        if f.endswith(".c") and f[:-2] != unit)
        objs = [f"build/cov/obj/{unit}.o"] + [f"build/host/obj/{u}.o" for u in others]
        return [("build", ["make", "-s", *objs], {}),
                ("coverage", ["sh", "tools/gates/coverage.sh", " ".join(objs),
                              *[f"tests/{t}.c" for t in sc["tests"]]],
                 {"COV_FILTER": re.escape(sc["cover"]) + "$"})]
    if gate == "misra":
        return [("misra", ["sh", "tools/gates/misra.sh"], {})]
    if gate == "eva":
        # both analyses: the reference table's follows the bodies eva-all takes by contract
        return [("eva", ["sh", "tools/gates/eva.sh"], {"EVA_RUN": "eva eva-all"})]
    raise ValueError(gate)


def evidence_lines(job):
    """The gate's own findings from the files it wrote, appended to its output."""
    d, gate, out = job["dir"], job["gate"], []
    try:
        if gate == "wp":
            for f in sorted(os.listdir(os.path.join(d, "build", "wp"))):
                if f.endswith(".log"):
                    with open(os.path.join(d, "build", "wp", f), encoding="utf-8", errors="replace") as fh:
                        out += [ln.rstrip() for ln in fh if re.match(r"^\[wp\] \[[^\]]+\] Goal \S+ : (?!Valid)", ln)]
        elif gate == "cbmc":
            for f in sorted(os.listdir(os.path.join(d, "build", "cbmc"))):
                if f.endswith(".log") and f != "selftest.log":
                    with open(os.path.join(d, "build", "cbmc", f), encoding="utf-8", errors="replace") as fh:
                        out += [ln.rstrip() for ln in fh if ln.rstrip().endswith(": FAILURE")]
        elif gate == "eva":
            with open(os.path.join(d, "build", "eva", "eva.json"), encoding="utf-8") as fh:
                data = json.load(fh)
            out += [f"ALARM {a['file']}:{a['line']}: {a['message']}" for a in data.get("rte_alarms", [])]
    except (OSError, ValueError, KeyError):
        pass
    return out


def run_step(argv, cwd, env, log):
    """Run one command; (exit status or None when killed, wall s, CPU s of the whole tree)."""
    t0 = time.monotonic()
    with open(log, "ab") as lf:
        lf.write(("$ " + " ".join(argv) + "\n").encode())
        lf.flush()
        p = subprocess.Popen(argv, cwd=cwd, env=env, stdout=lf, stderr=subprocess.STDOUT,
                             stdin=subprocess.DEVNULL, start_new_session=True)
        killed = []

        def kill():
            killed.append(True)
            try:
                os.killpg(p.pid, signal.SIGKILL)
            except OSError:
                pass
        timer = threading.Timer(STEP_TIMEOUT, kill)
        timer.start()
        _pid, status, usage = os.wait4(p.pid, 0)
        timer.cancel()
        p.returncode = os.waitstatus_to_exitcode(status)
    rc = None if killed else p.returncode
    return rc, time.monotonic() - t0, usage.ru_utime + usage.ru_stime


def run_job(job, scopes, cbmc):
    t0 = time.monotonic()
    copy_tree(job["dir"], job["defect"])
    log = os.path.join(job["dir"], "gate.log")
    env = dict(os.environ)
    steps, cpu = [], 0.0
    for label, argv, extra in gate_steps(job, scopes, cbmc):
        env_step = {k: v for k, v in dict(env, **extra).items() if v is not None}
        start = os.path.getsize(log) if os.path.exists(log) else 0
        rc, _wall, c = run_step(argv, job["dir"], env_step, log)
        cpu += c
        with open(log, encoding="utf-8", errors="replace") as f:
            f.seek(start)
            output = f.read()
        steps.append({"label": label, "rc": rc, "output": output})
        if rc != 0:
            break
    extra_lines = evidence_lines(job)
    if extra_lines:
        steps[-1]["output"] += "\n" + "\n".join(extra_lines) + "\n"
    verdict, detail = classify(job["gate"], steps)
    return {"kind": job["kind"], "name": job["name"], "scope": job["scope"], "gate": job["gate"],
            "verdict": verdict, "outcome": outcome(job["kind"], verdict), "ok": job_ok(job["kind"], verdict),
            "detail": detail, "seconds": round(time.monotonic() - t0, 1), "cpu_seconds": round(cpu, 1),
            "log": os.path.relpath(log, ROOT)}


# --------------------------------------------------------------------------- report


def summarise(defects, results, wall, jobs_n, partial="", scopes=None, load=None):
    by = {(r["name"], r["gate"]): r for r in results if r["kind"] == "defect"}
    rows = []
    for d in defects:
        gates = {}
        for g in GATES:
            r = by.get((d["id"], g))
            if g not in d["gates"]:
                gates[g] = {"status": "not expected"}
            elif r is None:
                gates[g] = {"status": "NOT RUN"}
            else:
                gates[g] = {"status": r["outcome"], "detail": r["detail"], "seconds": r["seconds"],
                            "cpu_seconds": r["cpu_seconds"], "log": r["log"]}
        caught = [g for g in d["gates"] if gates[g]["status"] == "caught"]
        rows.append({"id": d["id"], "class": d["class"], "title": d["title"], "why": d["why"],
                     "file": d["file"], "scope": d["scope"], "expected": list(d["gates"]),
                     "caught": caught, "ok": len(caught) == len(d["gates"]), "gates": gates,
                     "seconds": round(sum(gates[g].get("seconds", 0) for g in d["gates"]), 1)})
    control = [r for r in results if r["kind"] == "control"]
    expected = sum(len(d["gates"]) for d in defects)
    caught = sum(len(r["caught"]) for r in rows)
    control_ok = all(r["ok"] for r in control)
    per_gate = {g: sum(1 for r in rows if g in r["caught"]) for g in GATES}
    return {
        "requirement": "REQ-EVD-030",
        "generated_by": "tools/validation/run.py (make tool-validation)",
        "date": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M:%S UTC"),
        "commit": git_commit(),
        "summary": {"defects": len(rows), "expected_catches": expected, "caught": caught,
                    "missed": sum(1 for r in rows for g in r["expected"] if r["gates"][g]["status"] == "MISSED"),
                    "errors": sum(1 for r in rows for g in r["expected"] if r["gates"][g]["status"] == "ERROR"),
                    "catches_per_gate": per_gate,
                    "control_runs": len(control), "control_ok": control_ok,
                    "ok": caught == expected and control_ok and bool(control),
                    "partial": partial, "jobs": jobs_n, "wall_seconds": round(wall, 1),
                    "cpu_seconds": round(sum(r["cpu_seconds"] for r in results), 1)},
        "scopes": scopes or {},
        "load_average": load or [],
        "defects": rows,
        "control": [{k: r[k] for k in ("scope", "gate", "outcome", "ok", "detail", "seconds", "cpu_seconds", "log")}
                    for r in control],
    }


def git_commit():
    try:
        c = subprocess.run(["git", "-C", ROOT, "rev-parse", "HEAD"], capture_output=True, text=True,
                           check=True).stdout.strip()
        dirty = subprocess.run(["git", "-C", ROOT, "status", "--porcelain"], capture_output=True,
                               text=True, check=True).stdout.strip() != ""
        return c + (" (working tree modified)" if dirty else "")
    except (OSError, subprocess.CalledProcessError):
        return "unknown"


def md_cell(text):
    return str(text).replace("|", "\\|").replace("\n", " ")


def write_md(path, res):
    s = res["summary"]
    names = {"wp": "WP", "cbmc": "CBMC", "eva": "EVA", "misra": "MISRA", "tests": "tests", "coverage": "coverage"}
    cell = {"caught": "caught", "not expected": "-"}
    out = ["# Tool validation by seeded defects", "",
           f"Generated by `make tool-validation` (tools/validation/run.py, REQ-EVD-030) on {res['date']}, "
           f"commit {res['commit']}; catalogue tools/validation/defects.toml.", "",
           f"**{'PASS' if s['ok'] else 'FAIL'}: {s['caught']} of {s['expected_catches']} expected catches "
           f"in {s['defects']} seeded defects; control {'passes' if s['control_ok'] else 'FAILS'} "
           f"({s['control_runs']} gate runs on the unmodified copy).**", ""]
    if s.get("partial"):
        out += [f"Partial run ({s['partial']}): not the whole catalogue.", ""]
    out += [
           f"{s['jobs']} gate runs, {s['wall_seconds']:.0f} s wall, {s['cpu_seconds']:.0f} s CPU "
           f"(user + system of every gate's processes; on two idle processors the run cannot take less "
           f"than half the CPU time, {s['cpu_seconds'] / 2:.0f} s)."
           + (f"  Load average (1 min) of the machine at the start and the end: "
              f"{', '.join(f'{x:.1f}' for x in res['load_average'])}." if res.get("load_average") else ""), "",
           "Catches per gate: " + ", ".join(f"{names[g]} {s['catches_per_gate'][g]}" for g in GATES) + ".", "",
           "| defect | class | file | " + " | ".join(names[g] for g in GATES) + " | time (s) |",
           "|---|---|---|" + "---|" * len(GATES) + "---:|"]
    for r in res["defects"]:
        out.append(f"| {r['id']} | {md_cell(r['class'])} | `{r['file']}` | "
                   + " | ".join(cell.get(r["gates"][g]["status"], f"**{r['gates'][g]['status']}**")
                                for g in GATES) + f" | {r['seconds']:.0f} |")
    out += ["", "`-`: not expected to catch this defect, not run.  Each gate runs alone on its own copy "
            "(build/validation/TV-nn/GATE/ and build/validation/control/), scoped as below.", "",
            "## How each gate is scoped", "",
            "| scope | WP units (prover time-out) | CBMC harnesses | tests | coverage of |", "|---|---|---|---|---|"]
    for name, sc in res.get("scopes", {}).items():
        if not any(sc.get(k) for k in ("wp", "cbmc", "tests", "cover")):
            continue
        wp = ", ".join(f"`{u}`" for u in sc.get("wp", []))
        if wp:
            wp += f" ({sc.get('wp_timeout', 60)} s)"
        out.append(f"| {name} | {wp or '-'} | {', '.join(sc.get('cbmc', [])) or '-'} | "
                   f"{', '.join(sc.get('tests', [])) or '-'} | {('`' + sc['cover'] + '`') if sc.get('cover') else '-'} |")
    out += ["", "MISRA (`tools/gates/misra.sh`) runs over the whole library as the gate does: its cross-unit "
            "rules report false findings on one unit alone.  EVA (`tools/gates/eva.sh`) runs over the whole "
            "drive: it has no per-unit mode.  Tests: the Makefile's rule builds each test program (library "
            "with -Werror), `tools/gates/run_tests.sh` runs it.  Coverage: the unit's object built with "
            "--coverage, the rest of the library without, `tools/gates/coverage.sh` with COV_FILTER set to "
            "the unit's source.  WP and CBMC run one job at a time (WP_JOBS=1, JOBS=1), two gate runs at a "
            "time.", "",
            "## The defects and what each gate reported", ""]
    for r in res["defects"]:
        out.append(f"### {r['id']} {r['title']}")
        out.append("")
        out.append(f"Class: {r['class']}; file `{r['file']}`; scope `{r['scope']}`.  Expected: {r['why']}.")
        out.append("")
        for g in r["expected"]:
            gr = r["gates"][g]
            out.append(f"- {names[g]}: **{gr['status']}** ({gr.get('seconds', 0):.0f} s, "
                       f"CPU {gr.get('cpu_seconds', 0):.0f} s): {md_cell(gr.get('detail', ''))}")
        out.append("")
    out += ["## Control: the unmodified copy through the same scoped gates", "",
            "| scope | gate | result | time (s) | CPU (s) | figure |", "|---|---|---|---:|---:|---|"]
    for c in res["control"]:
        scope = "library" if c["gate"] in LIBRARY_GATES else c["scope"]
        out.append(f"| {scope} | {names[c['gate']]} | {c['outcome'] if c['ok'] else '**' + c['outcome'] + '**'} "
                   f"| {c['seconds']:.0f} | {c['cpu_seconds']:.0f} | {md_cell(c['detail'])} |")
    with open(path, "w", encoding="utf-8") as f:
        f.write("\n".join(out) + "\n")


# --------------------------------------------------------------------------- main


def main(argv=None):
    ap = argparse.ArgumentParser(description="Seeded-defect validation of the gates (REQ-EVD-030).")
    ap.add_argument("--catalogue", default=CATALOGUE)
    ap.add_argument("--out", default=os.path.join(ROOT, "build", "validation"))
    ap.add_argument("--jobs", type=int, default=2, help="gate runs at a time (default 2)")
    ap.add_argument("--only", default="", help="comma-separated defect IDs (the control is limited to their scopes)")
    ap.add_argument("--gates", default="", help="comma-separated gates: run only these (a partial run)")
    ap.add_argument("--check", action="store_true", help="check the catalogue and the substitutions only")
    args = ap.parse_args(argv)
    try:
        scopes, defects = load_catalogue(args.catalogue)
        if args.only:
            want = {x.strip() for x in args.only.split(",") if x.strip()}
            unknown = want - {d["id"] for d in defects}
            if unknown:
                raise CatalogueError(f"--only: unknown defect(s) {', '.join(sorted(unknown))}")
            defects = [d for d in defects if d["id"] in want]
        if args.gates:
            keep = {x.strip() for x in args.gates.split(",") if x.strip()}
            if keep - set(GATES):
                raise CatalogueError(f"--gates: unknown gate(s) {', '.join(sorted(keep - set(GATES)))}")
            defects = [dict(d, gates=[g for g in d["gates"] if g in keep]) for d in defects]
            defects = [d for d in defects if d["gates"]]
        check_sources(ROOT, scopes, defects)
    except CatalogueError as e:
        print(f"tool-validation: catalogue error:\n{e}", file=sys.stderr)
        return 2
    gates_used = sorted({g for d in defects for g in d["gates"]}, key=GATES.index)
    print(f"tool-validation: {len(defects)} defects, every substitution matches once; gates "
          + ", ".join(f"{g} ({sum(1 for d in defects if g in d['gates'])})" for g in gates_used))
    if args.check:
        return 0
    cbmc = os.environ.get("CBMC") or os.path.join(ROOT, "build", "tools", "cbmc", "bin", "cbmc")
    if "cbmc" in gates_used and not os.access(cbmc, os.X_OK):
        print(f"tool-validation: {cbmc} not found (make deps installs it)", file=sys.stderr)
        return 2
    out = os.path.abspath(args.out)
    for name in os.listdir(out) if os.path.isdir(out) else []:
        p = os.path.join(out, name)
        if name == "control" or ID.match(name):
            shutil.rmtree(p)
        elif name in ("results.json", "results.md"):
            os.remove(p)
    os.makedirs(out, exist_ok=True)
    jobs = make_jobs(scopes, defects, out)
    print(f"tool-validation: {len(jobs)} gate runs, {args.jobs} at a time, in {os.path.relpath(out, ROOT)}/")
    t0 = time.monotonic()
    load0 = os.getloadavg()[0]
    results = []
    lock = threading.Lock()

    def one(job):
        try:
            r = run_job(job, scopes, cbmc)
        except Exception as e:  # noqa: BLE001 -- a runner failure is an error of that job
            r = {"kind": job["kind"], "name": job["name"], "scope": job["scope"], "gate": job["gate"],
                 "verdict": "error", "outcome": "ERROR", "ok": False, "detail": f"runner: {e}",
                 "seconds": 0.0, "cpu_seconds": 0.0, "log": ""}
        with lock:
            results.append(r)
            print(f"  [{len(results)}/{len(jobs)}] {r['name']} {r['scope']} {r['gate']}: {r['outcome']} "
                  f"({r['seconds']:.0f} s, CPU {r['cpu_seconds']:.0f} s) {r['detail'][:150]}", flush=True)
        return r

    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, args.jobs)) as pool:
        list(pool.map(one, jobs))
    partial = " ".join(f"--{k} {v}" for k, v in (("only", args.only), ("gates", args.gates)) if v)
    load = [load0, os.getloadavg()[0]]
    res = summarise(defects, results, time.monotonic() - t0, len(jobs), partial, scopes, load)
    with open(os.path.join(out, "results.json"), "w", encoding="utf-8") as f:
        json.dump(res, f, indent=1)
        f.write("\n")
    write_md(os.path.join(out, "results.md"), res)
    s = res["summary"]
    print(f"tool-validation: {s['caught']} / {s['expected_catches']} expected catches, "
          f"{s['missed']} missed, {s['errors']} errors; control "
          f"{'passes' if s['control_ok'] else 'FAILS'} ({s['control_runs']} runs); "
          f"{s['wall_seconds']:.0f} s wall, {s['cpu_seconds']:.0f} s CPU; "
          f"{os.path.relpath(os.path.join(out, 'results.md'), ROOT)}")
    return 0 if s["ok"] else 1


if __name__ == "__main__":
    sys.exit(main())
