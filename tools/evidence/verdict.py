"""Requirement verdicts from the results of the run (used by tools/evidence/evidence.py).

The traceability matrix of `make trace` (build/trace/trace.json) says which proofs and
tests each requirement names; it reads the sources only.  Whether the requirement is
verified is decided here, from the results (specs/requirements/evidence.md, REQ-EVD-027):

  proof  a WP function (its own goals, and those of the static functions it calls), a
         lemma, or a CBMC harness:
           proved     every goal proved (every property holds) in results tied to the
                      current sources (their inputs stamp is current: tools/evidence/inputs.py)
           failed     a goal not proved, a property that fails
           stale      the results are not tied to the current sources (inputs changed
                      since the run, or no inputs stamp)
           no result  no result for it
  test   a CMocka or pytest test, a target-equivalence group or checking program, a bench
         row, a scenario of the demonstration or the robustness campaign:
           passed     it ran and passed in this run's results (build/junit/*.xml; the
                      bench's build/bench/bench.json; build/demo/<scenario>/metrics.json;
                      build/robustness/campaign.json)
           failed     it ran and failed (a failure or an error)
           not run    it is not in the results (or was skipped)
           stale      a bench row of a bench result whose inputs changed

A requirement is verified only when it names at least one proof or test and every proof it
names is proved and every test it names passed.  Otherwise its verdict is, in this order:
failed (something failed), stale, not run (something has no result), no evidence (it
names nothing).  Several requirements together (the requirements a row of the software FMEA
names, REQ-EVD-031) are verified only when each one is (`combine`).
"""
import os
import re
import xml.etree.ElementTree as ET

PROVED, FAILED, STALE, NO_RESULT = "proved", "failed", "stale", "no result"
PASSED, NOT_RUN = "passed", "not run"
VERIFIED, NO_EVIDENCE = "verified", "no evidence"
OK_STATUSES = (PROVED, PASSED)

REQ_ID = re.compile(r"\bREQ-[A-Z0-9]+-\d{3}\b")


# ----------------------------------------------------------------------------- JUnit

def junit_cases(paths):
    """(classname, name) -> list of case statuses ('passed', 'failed', 'skipped') of the
    JUnit files; unreadable files are left out."""
    cases = {}
    for p in paths:
        try:
            root = ET.parse(p).getroot()
        except (ET.ParseError, OSError):
            continue
        for c in root.iter("testcase"):
            if c.find("failure") is not None or c.find("error") is not None:
                st = FAILED
            elif c.find("skipped") is not None:
                st = "skipped"
            else:
                st = PASSED
            cases.setdefault((c.get("classname") or "", c.get("name") or ""), []).append(st)
    return cases


def aggregate(statuses):
    """One status of several results of the same test: failed wins, then passed."""
    if any(s == FAILED for s in statuses):
        return FAILED
    if any(s == PASSED for s in statuses):
        return PASSED
    return NOT_RUN


def _cases_where(cases, cls_ok, name_ok):
    out = []
    for (cls, name), sts in cases.items():
        if cls_ok(cls) and name_ok(name):
            out += sts
    return out


# ----------------------------------------------------------------------------- tests

def _kind_of(t):
    kind = t.get("kind")
    if kind:
        return kind
    f = str(t.get("file", ""))
    if f.endswith(".py"):
        return "pytest"
    if f.endswith(".c") and os.path.basename(os.path.dirname(f)) == "tests":
        return "cmocka"
    return "other"


def bench_row_status(r):
    res = str(r.get("result", "")).strip().upper()
    if res in ("OK", "PASS", "PASSED"):
        return PASSED
    if res in ("", "-", "NONE"):
        # a row without a limit: reported (its measured max or its static bound present)
        return PASSED if (r.get("max") is not None or r.get("static") is not None) else NOT_RUN
    return FAILED


def status_of_test(t, rid, results):
    """(status, where) of one test record of the matrix."""
    if isinstance(t, str):
        t = {"name": t.split(": ", 1)[-1], "file": t.split(": ", 1)[0] if ": " in t else ""}
    kind = _kind_of(t)
    name = str(t.get("name", ""))
    f = str(t.get("file", ""))
    cases = results.get("junit") or {}
    if kind == "cmocka":
        suite = os.path.basename(f)[:-2] if f.endswith(".c") else os.path.basename(f)
        sts = cases.get((suite, name), [])
        return (aggregate(sts) if sts else NOT_RUN), f"JUnit {suite}.{name}"
    if kind == "pytest":
        mod = f[:-3].replace("/", ".") if f.endswith(".py") else f
        base = os.path.basename(f)[:-3] if f.endswith(".py") else f

        def cls_ok(c):
            return (c == mod or c.startswith(mod + ".") or c == base or c.startswith(base + ".")
                    or c.endswith("." + base) or ("." + base + ".") in c)

        sts = _cases_where(cases, cls_ok, lambda n: n == name or n.startswith(name + "["))
        return (aggregate(sts) if sts else NOT_RUN), f"JUnit {mod}.{name}"
    if kind == "target":
        if name.startswith("group "):
            key = ("target_equivalence", name[len("group "):])
        else:
            key = ("target_checks", os.path.basename(f) or name)
        sts = cases.get(key, [])
        return (aggregate(sts) if sts else NOT_RUN), f"JUnit {key[0]}.{key[1]}"
    if kind == "bench":
        bench = results.get("bench")
        if not bench or not bench.get("rows"):
            return NOT_RUN, "build/bench/bench.json"
        if bench.get("state") not in (None, "current"):
            return STALE, "build/bench/bench.json (" + str(bench.get("state")) + ")"
        label = re.sub(r"\s+", " ", name[len("row "):] if name.startswith("row ") else name).strip()
        rows = [r for r in bench["rows"] if re.sub(r"\s+", " ", str(r.get("item", ""))).strip() == label]
        if not rows:
            # a row named from the bench's source (the bench had not run when the matrix was
            # made): the rows of the run that name the requirement
            rows = [r for r in bench["rows"] if rid in REQ_ID.findall(str(r.get("requirement", "")))]
        if not rows:
            return NOT_RUN, "build/bench/bench.json"
        return aggregate([bench_row_status(r) for r in rows]), "build/bench/bench.json"
    # anything else: a JUnit case of that name in any suite
    sts = _cases_where(cases, lambda c: True, lambda n: n == name)
    return (aggregate(sts) if sts else NOT_RUN), "JUnit"


def scenario_status(s, results):
    name = s.get("name") if isinstance(s, dict) else str(s)
    name = str(name)
    if name.startswith("scn_run_"):
        camp = results.get("robustness")
        if not isinstance(camp, dict):
            return NOT_RUN, "build/robustness/campaign.json"
        count, ok = camp.get("count"), camp.get("successes")
        if isinstance(count, int) and count > 0 and ok == count:
            return PASSED, "build/robustness/campaign.json"
        return FAILED, "build/robustness/campaign.json"
    demo = results.get("demo")
    where = f"build/demo/{name}/metrics.json"
    if not isinstance(demo, dict) or name not in demo:
        return NOT_RUN, where
    p = demo[name]
    return (PASSED if p is True else FAILED if p is False else NOT_RUN), where


# ----------------------------------------------------------------------------- proofs

def _wp_index(rows):
    by_key, by_fn = {}, {}
    for r in rows or []:
        k = (str(r.get("unit", "")), str(r.get("function", "")))
        g, p = by_key.get(k, (0, 0))
        by_key[k] = (g + int(r.get("goals") or 0), p + int(r.get("proved") or 0))
        by_fn.setdefault(k[1], set()).add(k[0])
    return by_key, by_fn


def wp_status(item, wp, index):
    """(status, detail) of one WP function (or lemma) record of the matrix."""
    if isinstance(item, str):
        item = {"function": item}
    fn, unit = str(item.get("function", "")), item.get("unit")
    if not wp or wp.get("state") in (None, "absent", "missing"):
        return NO_RESULT, "no WP result"
    if wp.get("state") != "current":
        return STALE, f"WP results {wp.get('state')}"
    by_key, by_fn = index
    if fn.startswith("lemma "):
        # a lemma is one goal of its section's row; the matrix carries its result
        have = any(k[1].startswith("lemmas") and (unit is None or k[0] == unit) for k in by_key)
        if not have:
            return NO_RESULT, "no lemma rows"
        g, p = int(item.get("goals") or 0), int(item.get("proved") or 0)
        return (PROVED if g and p == g else FAILED), f"{p}/{g}"
    keys = [(unit, fn)] if unit is not None else [(u, fn) for u in sorted(by_fn.get(fn, ()))]
    found = [by_key[k] for k in keys if k in by_key]
    if not found:
        return NO_RESULT, "no row in the WP results"
    g = sum(x[0] for x in found)
    p = sum(x[1] for x in found)
    return (PROVED if p == g else FAILED), f"{p}/{g} goals"


def cbmc_status(item, cbmc, index):
    h = item.get("harness") if isinstance(item, dict) else str(item)
    if not cbmc or cbmc.get("state") in (None, "absent", "missing"):
        return NO_RESULT, "no CBMC result"
    if cbmc.get("state") != "current":
        return STALE, f"CBMC results {cbmc.get('state')}"
    r = index.get(h)
    if r is None:
        return NO_RESULT, "no row in the CBMC results"
    ok = str(r.get("result", "")).upper() == "PASS" and not int(r.get("failed") or 0)
    return (PROVED if ok else FAILED), f"{r.get('result')}, {r.get('properties')} properties"


# ----------------------------------------------------------------------------- verdicts

def _as_list(v):
    if v is None or v == "" or v == "-":
        return []
    return v if isinstance(v, list) else [v]


def verdict_of(statuses):
    if not statuses:
        return NO_EVIDENCE
    if any(s == FAILED for s in statuses):
        return FAILED
    if any(s == STALE for s in statuses):
        return STALE
    if any(s not in OK_STATUSES for s in statuses):
        return NOT_RUN
    return VERIFIED


def combine(req_verdicts):
    """One verdict of several requirements (the requirements an FMEA row names: REQ-EVD-031):
    verified only when every one is verified and there is at least one; otherwise failed,
    stale, not run, no evidence, in this order."""
    if not req_verdicts:
        return NO_EVIDENCE
    for v in (FAILED, STALE, NOT_RUN, NO_EVIDENCE):
        if any(x == v for x in req_verdicts):
            return v
    return VERIFIED if all(x == VERIFIED for x in req_verdicts) else NOT_RUN


def requirement_verdict(rid, rec, results, wp_index=None, cbmc_index=None):
    """The verdict of one requirement record of trace.json:
    dict(verdict, proofs: [dict(kind, name, status, detail)], tests: [...], scenarios: [...])."""
    wp_index = wp_index or _wp_index((results.get("wp") or {}).get("rows"))
    if cbmc_index is None:
        cbmc_index = {str(r.get("harness")): r for r in (results.get("cbmc") or {}).get("rows") or []}
    proofs = []
    wp = rec.get("wp")
    if isinstance(wp, dict):
        seen = set()
        for kind, lst in (("WP", wp.get("functions")), ("WP helper", wp.get("helpers"))):
            for item in _as_list(lst):
                it = item if isinstance(item, dict) else {"function": str(item)}
                key = (kind, it.get("unit"), it.get("function"))
                if key in seen:
                    continue
                seen.add(key)
                st, detail = wp_status(it, results.get("wp"), wp_index)
                label = str(it.get("function")) + (f" ({it['unit']})" if it.get("unit") else "")
                if kind == "WP helper" and it.get("via"):
                    label += " via " + ", ".join(it["via"])
                proofs.append({"kind": kind, "name": label, "status": st, "detail": detail})
    elif isinstance(wp, list):
        for item in wp:
            st, detail = wp_status(item, results.get("wp"), wp_index)
            proofs.append({"kind": "WP", "name": str(item.get("function") if isinstance(item, dict) else item),
                           "status": st, "detail": detail})
    for item in _as_list(rec.get("cbmc")):
        st, detail = cbmc_status(item, results.get("cbmc"), cbmc_index)
        name = item.get("harness") if isinstance(item, dict) else str(item)
        proofs.append({"kind": "CBMC", "name": str(name), "status": st, "detail": detail,
                       "file": item.get("file") if isinstance(item, dict) else None})
    tests = []
    for t in _as_list(rec.get("tests", rec.get("test"))):
        st, where = status_of_test(t, rid, results)
        if isinstance(t, dict):
            tests.append({"kind": _kind_of(t), "name": str(t.get("name", "")), "file": t.get("file"),
                          "status": st, "detail": where})
        else:
            tests.append({"kind": "other", "name": str(t), "file": None, "status": st, "detail": where})
    scen = []
    for s in _as_list(rec.get("scenarios")):
        st, where = scenario_status(s, results)
        scen.append({"kind": "scenario", "name": str(s.get("name") if isinstance(s, dict) else s),
                     "file": s.get("file") if isinstance(s, dict) else None, "status": st,
                     "detail": where})
    statuses = [x["status"] for x in proofs + tests + scen]
    return {"verdict": verdict_of(statuses), "proofs": proofs, "tests": tests, "scenarios": scen}


def verdicts(records, results):
    """rid -> verdict of every requirement record (trace.json's 'requirements')."""
    wp_index = _wp_index((results.get("wp") or {}).get("rows"))
    cbmc_index = {str(r.get("harness")): r for r in (results.get("cbmc") or {}).get("rows") or []}
    return {rid: requirement_verdict(rid, rec, results, wp_index, cbmc_index)
            for rid, rec in records.items()}


def counts(items):
    """'3 passed, 1 not run' of a list of verdict items."""
    out = {}
    for x in items:
        out[x["status"]] = out.get(x["status"], 0) + 1
    order = (PROVED, PASSED, FAILED, STALE, NOT_RUN, NO_RESULT)
    return ", ".join(f"{out[k]} {k}" for k in order if k in out)
