#!/usr/bin/env python3
"""MISRA Compliance:2020 guideline compliance summary of qfoc.

usage: misra_summary.py [--root DIR] [--out DIR]

Reads, relative to the repository root:
  misra/enforcement-plan.csv   the guideline enforcement plan: one row per guideline
                               (id, kind, category, edition, decidability, analysis,
                               summary, methods, evidence, plan, reason)
  misra/guidelines.txt         qfoc's rule list, misra/directives.txt its directive list:
                               every guideline listed there must be in the plan, with the
                               same category
  build/misra/cppcheck.xml     the findings of `make misra` (cppcheck MISRA addon and the
                               core checks of error severity); every finding is unrecorded
  misra/deviations.md          the deviation records (DEV-nnn, each naming its rules)
  misra/reviews.md             the manual review records (one per guideline reviewed), each
                               tied to the files it reviewed (tools/evidence/review_stamp.py,
                               REQ-EVD-031): a record whose files changed since its review
                               is noted "review record stale" with the files (not a
                               violation: the evidence page shows it red)
  src/ include/ tables/ port_s32k/  the inline suppressions (`cppcheck-suppress
                               misra-c2012-R.N ; DEV-nnn`), counted per record

For every guideline of the baseline (MISRA C:2012 with Amendments 1 and 2) the status is
  Compliant    no finding, no deviation;
  Deviations   every non-compliant site is covered by a deviation record for that guideline
               (the records and the number of sites are listed);
  Disapplied   advisory guidelines the plan disapplies (with the reason);
  Violations   a cppcheck finding, a suppression without a matching record, a review that
               found a violation, or a review record the plan asks for and that is missing.
Guidelines added by Amendments 3 and 4 are listed apart (outside the claimed baseline).

Writes OUT/compliance-summary.md and OUT/compliance-summary.json (OUT defaults to
build/misra) with the MISRA Compliance:2020 header data: the guideline re-categorisation
plan, the tool versions, the deviation records.  Prints
  misra-summary: N guidelines: a compliant, b with deviations, c disapplied, d violations
and exits 1 on a violation, on a guideline missing from the plan, or on an inconsistent
plan.
"""
import argparse
import csv
import glob
import json
import os
import re
import subprocess
import sys
import xml.etree.ElementTree as ET

from misra_rule_texts import read_guidelines

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "evidence"))
import review_stamp  # noqa: E402  (tools/evidence/review_stamp.py: review records and their files)

BASELINE = "MISRA C:2012 (third edition) with Amendment 1 (2016) and Amendment 2 (2020)"
FRAMEWORK = "MISRA Compliance:2020"
CATEGORIES = ("mandatory", "required", "advisory")
CAT_LETTER = {"M": "mandatory", "R": "required", "A": "advisory"}
METHODS = ("cppcheck", "cppcheck-core", "compiler", "proof", "cbmc", "coverage", "trace",
           "review", "not-applicable", "none")
PLANS = ("apply", "disapplied", "outside-baseline")
SOURCE_DIRS = ("src", "include", "tables", "port_s32k")

SUPP = re.compile(r"cppcheck-suppress\s+misra-c2012-([0-9]+\.[0-9]+)(.*)$")
DEV_ID = re.compile(r"\bDEV-\d{3}\b")
DEV_HEAD = re.compile(r"^##+\s*(DEV-\d{3})\b\s*(.*)$")
DEV_RULE = re.compile(r"^\s*[-*]?\s*(Rule|Directive|Dir)\s*[:|]?\s*\**\s*([0-9]+\.[0-9]+)")
REV_HEAD = re.compile(r"^##\s+((?:Rule|Dir)\s+[0-9]+\.[0-9]+)\b\s*(.*)$")
REV_FIELD = re.compile(r"^-\s*(Result|Sites)\s*:\s*(.*)$")
SITE = re.compile(r"\b[\w./-]+\.[ch]:\d+(?:-\d+)?(?:(?:,| and) \d+(?:-\d+)?)*")

# cppcheck core checks (error severity, run by `make misra`) and the guideline whose
# concern they detect; any other finding is counted against the gate unattributed.
CORE = {
    "uninitvar": "Rule 9.1", "uninitdata": "Rule 9.1", "uninitStructMember": "Rule 9.1",
    "legacyUninitvar": "Rule 9.1",
    "unknownEvaluationOrder": "Rule 13.2",
    "missingReturn": "Rule 17.4",
    "arrayIndexOutOfBounds": "Rule 18.1", "arrayIndexOutOfBoundsCond": "Rule 18.1",
    "bufferAccessOutOfBounds": "Rule 18.1", "pointerOutOfBounds": "Rule 18.1",
    "negativeIndex": "Rule 18.1", "objectIndex": "Rule 18.1", "outOfBounds": "Rule 18.1",
    "danglingLifetime": "Rule 18.6", "returnDanglingLifetime": "Rule 18.6",
    "invalidLifetime": "Rule 18.6", "danglingTemporaryLifetime": "Rule 18.6",
    "overlappingWriteFunction": "Rule 19.1", "overlappingWriteUnion": "Rule 19.1",
    "memleak": "Rule 22.1", "resourceLeak": "Rule 22.1",
    "mismatchAllocDealloc": "Rule 22.2", "deallocuse": "Rule 22.2", "doubleFree": "Rule 22.2",
    "shiftTooManyBits": "Rule 12.2", "shiftTooManyBitsSigned": "Rule 12.2",
    "shiftNegative": "Rule 12.2",
    "zerodiv": "Rule 1.3", "zerodivcond": "Rule 1.3", "integerOverflow": "Rule 1.3",
    "nullPointer": "Rule 1.3",
}

ADDON_CANDIDATES = ("/usr/lib/x86_64-linux-gnu/cppcheck/addons/misra.py",
                    "/usr/lib/aarch64-linux-gnu/cppcheck/addons/misra.py",
                    "/usr/share/cppcheck/addons/misra.py",
                    "/usr/lib/cppcheck/addons/misra.py")


def gid_key(gid):
    kind, num = gid.split()
    a, b = num.split(".")
    return (0 if kind == "Dir" else 1, int(a), int(b))


def read_list(path, prefix):
    """qfoc's guideline list: 'N.M C|summary' lines -> {id: (category, summary)}."""
    return {f"{prefix} {num}": (CAT_LETTER[cat], text)
            for num, cat, text in read_guidelines(path)}


def read_plan(path, errors):
    rows = {}
    with open(path, encoding="utf-8", newline="") as f:
        for line_no, row in enumerate(csv.DictReader(f), 2):
            gid = row["id"].strip()
            if gid in rows:
                errors.append(f"{path}:{line_no}: {gid} listed twice")
            row["methods_list"] = [m.strip() for m in row["methods"].split(";") if m.strip()]
            for m in row["methods_list"]:
                if m not in METHODS:
                    errors.append(f"{path}:{line_no}: {gid}: unknown method '{m}'")
            if not row["methods_list"]:
                errors.append(f"{path}:{line_no}: {gid}: no verification method")
            if row["plan"] not in PLANS:
                errors.append(f"{path}:{line_no}: {gid}: unknown plan '{row['plan']}'")
            if row["category"] not in CATEGORIES:
                errors.append(f"{path}:{line_no}: {gid}: unknown category '{row['category']}'")
            if row["plan"] == "disapplied" and row["category"] != "advisory":
                errors.append(f"{path}:{line_no}: {gid}: only advisory guidelines may be "
                              f"disapplied ({row['category']})")
            if row["plan"] in ("disapplied", "outside-baseline") and not row["reason"].strip():
                errors.append(f"{path}:{line_no}: {gid}: {row['plan']} without a reason")
            if "not-applicable" in row["methods_list"] and not row["reason"].strip():
                errors.append(f"{path}:{line_no}: {gid}: not applicable without a reason")
            rows[gid] = row
    return rows


def read_deviations(path):
    """{DEV-nnn: {'title': str, 'guidelines': set of 'Rule N.M' / 'Dir N.M'}}"""
    devs = {}
    cur = None
    if not os.path.exists(path):
        return devs
    with open(path, encoding="utf-8") as f:
        for line in f:
            m = DEV_HEAD.match(line)
            if m:
                cur = m.group(1)
                devs[cur] = {"title": m.group(2).strip(), "guidelines": set()}
                continue
            if cur:
                m = DEV_RULE.match(line)
                if m:
                    kind = "Rule" if m.group(1) == "Rule" else "Dir"
                    devs[cur]["guidelines"].add(f"{kind} {m.group(2)}")
    return devs


def read_reviews(path):
    """{guideline: {'title', 'result', 'sites', 'line'}}; a field continues on the indented
    lines below it."""
    revs = {}
    cur = None
    last = None
    if not os.path.exists(path):
        return revs
    with open(path, encoding="utf-8") as f:
        for no, line in enumerate(f, 1):
            m = REV_HEAD.match(line)
            if m:
                cur = m.group(1)
                revs[cur] = {"title": m.group(2).strip(), "result": "", "sites": "",
                             "line": no}
                last = None
                continue
            if not cur:
                continue
            m = REV_FIELD.match(line)
            if m:
                last = m.group(1).lower()
                revs[cur][last] = m.group(2).strip()
            elif line.startswith("  ") and last is not None:
                revs[cur][last] += " " + line.strip()
            else:
                last = None
    return revs


def count_sites(text):
    """Number of file:line references (a range or a list of lines counts each entry)."""
    n = 0
    for m in SITE.finditer(text):
        n += len(re.split(r",| and ", m.group(0)))
    return n


def read_findings(path):
    root = ET.parse(path).getroot()
    version = ""
    c = root.find("cppcheck")
    if c is not None:
        version = c.get("version", "")
    out = []
    for e in root.iter("error"):
        loc = e.find("location")
        where = f"{loc.get('file')}:{loc.get('line')}" if loc is not None else "?"
        out.append({"id": e.get("id", ""), "where": where, "msg": e.get("msg", "")})
    return version, out


def read_suppressions(root_dir):
    out = []
    for d in SOURCE_DIRS:
        for dirpath, _dirs, files in os.walk(os.path.join(root_dir, d)):
            for fn in sorted(files):
                if not fn.endswith((".c", ".h")):
                    continue
                p = os.path.join(dirpath, fn)
                with open(p, encoding="utf-8") as f:
                    for no, line in enumerate(f, 1):
                        m = SUPP.search(line)
                        if m:
                            out.append({"rule": "Rule " + m.group(1),
                                        "where": f"{os.path.relpath(p, root_dir)}:{no}",
                                        "devs": DEV_ID.findall(m.group(2))})
    return out


def addon_rules():
    """Rules the installed cppcheck MISRA addon implements, as 'Rule N.M' (None if absent)."""
    paths = list(ADDON_CANDIDATES) + glob.glob("/usr/lib/*/cppcheck/addons/misra.py")
    for p in paths:
        if os.path.exists(p):
            with open(p, encoding="utf-8") as f:
                nums = set(int(n) for n in re.findall(r"executeCheck\((\d+),", f.read()))
            return p, {f"Rule {n // 100}.{n % 100}" for n in nums}
    return None, None


def tool_version(cmd):
    try:
        r = subprocess.run(cmd, capture_output=True, text=True, timeout=30, check=False)
    except (OSError, subprocess.TimeoutExpired):
        return "not found"
    text = (r.stdout or r.stderr).strip().splitlines()
    return text[0].strip() if text else "not found"


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--root", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
    ap.add_argument("--out", default=None)
    args = ap.parse_args()
    root = os.path.abspath(args.root)
    out_dir = args.out or os.path.join(root, "build", "misra")
    os.makedirs(out_dir, exist_ok=True)

    def rp(*p):
        return os.path.join(root, *p)

    errors = []
    plan = read_plan(rp("misra", "enforcement-plan.csv"), errors)
    listed = read_list(rp("misra", "guidelines.txt"), "Rule")
    listed.update(read_list(rp("misra", "directives.txt"), "Dir"))
    devs = read_deviations(rp("misra", "deviations.md"))
    revs = read_reviews(rp("misra", "reviews.md"))
    xml_path = rp("build", "misra", "cppcheck.xml")
    if not os.path.exists(xml_path):
        print(f"misra-summary: {xml_path} missing: run `make misra` first", file=sys.stderr)
        return 1
    cppcheck_xml_version, findings = read_findings(xml_path)
    supps = read_suppressions(root)
    addon_path, implemented = addon_rules()

    # ---- the plan against qfoc's guideline lists
    missing = sorted((g for g in listed if g not in plan), key=gid_key)
    for g in missing:
        errors.append(f"{g}: missing from misra/enforcement-plan.csv")
    for g, row in plan.items():
        if row["plan"] == "outside-baseline":
            continue
        if g not in listed:
            errors.append(f"{g}: in the plan as baseline, but not in misra/guidelines.txt or "
                          f"misra/directives.txt")
        elif listed[g][0] != row["category"]:
            errors.append(f"{g}: category {row['category']} in the plan, {listed[g][0]} in the "
                          f"guideline list")
        if implemented is not None and g.startswith("Rule") and "cppcheck" in row["methods_list"] \
                and g not in implemented:
            errors.append(f"{g}: the plan names cppcheck, but {addon_path} has no check for it")
    for g in revs:
        if g not in plan or "review" not in plan[g]["methods_list"]:
            errors.append(f"misra/reviews.md: record for {g}, whose plan has no review")

    # ---- evidence per guideline
    per = {g: {"violations": [], "deviations": {}, "notes": []} for g in plan}
    unattributed = []
    for fnd in findings:
        fid = fnd["id"]
        if fid.startswith("misra-c2012-"):
            g = "Rule " + fid[len("misra-c2012-"):]
        else:
            g = CORE.get(fid)
        entry = f"{fnd['where']}: {fid}: {fnd['msg']}"
        if g in per:
            per[g]["violations"].append(entry)
        else:
            unattributed.append(entry)
    for s in supps:
        g = s["rule"]
        ok = [d for d in s["devs"] if d in devs and g in devs[d]["guidelines"]]
        if g not in per:
            unattributed.append(f"{s['where']}: suppression of {g}, which is not in the plan")
        elif ok:
            for d in ok:
                per[g]["deviations"][d] = per[g]["deviations"].get(d, 0) + 1
        else:
            per[g]["violations"].append(
                f"{s['where']}: suppression without a deviation record for {g} "
                f"({', '.join(s['devs']) or 'no DEV id'})")
    for g, row in plan.items():
        if row["plan"] == "outside-baseline" or "review" not in row["methods_list"]:
            continue
        r = revs.get(g)
        if r is None:
            per[g]["violations"].append("no review record in misra/reviews.md")
            continue
        result = r["result"].lower()
        if result.startswith("compliant"):
            pass
        elif result.startswith("deviation"):
            ids = DEV_ID.findall(r["result"])
            bad = [d for d in ids if d not in devs or g not in devs[d]["guidelines"]]
            if not ids or bad:
                per[g]["violations"].append(
                    f"review (misra/reviews.md:{r['line']}) names "
                    f"{', '.join(bad) or 'no record'}: no deviation record for {g}")
            else:
                n = count_sites(r["sites"])
                for d in ids:
                    per[g]["deviations"][d] = per[g]["deviations"].get(d, 0) + (n if d == ids[0] else 0)
        elif result.startswith("violation"):
            per[g]["violations"].append(
                f"review (misra/reviews.md:{r['line']}): {r['sites'] or 'see the record'}")
        else:
            per[g]["violations"].append(
                f"review (misra/reviews.md:{r['line']}): no recognised result '{r['result']}'")
    stamps = review_stamp.check("misra", root)
    review_states = {}
    for r in stamps["records"]:
        review_states[r["state"]] = review_states.get(r["state"], 0) + 1
        if r["id"] in per and r["state"] != review_stamp.CURRENT:
            per[r["id"]]["notes"].append(f"review record {r['state']} ({'; '.join(r['reasons'])})")
    for d, rec in devs.items():
        for g in rec["guidelines"]:
            if g in per and d not in per[g]["deviations"]:
                per[g]["notes"].append(f"{d} recorded, no site found")
                per[g]["deviations"].setdefault(d, 0)
            elif g not in per:
                errors.append(f"misra/deviations.md: {d} names {g}, which is not in the plan")
            if g in plan and plan[g]["category"] == "mandatory":
                errors.append(f"misra/deviations.md: {d} deviates mandatory {g}")

    # ---- statuses
    guidelines = []
    outside = []
    counts = {"compliant": 0, "deviations": 0, "disapplied": 0, "violations": 0}
    for g in sorted(plan, key=gid_key):
        row = plan[g]
        ev = per[g]
        item = {"id": g, "kind": row["kind"], "category": row["category"],
                "edition": row["edition"], "decidability": row["decidability"],
                "analysis": row["analysis"], "summary": row["summary"],
                "methods": row["methods_list"], "evidence": row["evidence"],
                "reason": row["reason"]}
        if row["plan"] == "outside-baseline":
            item["status"] = "Outside baseline"
            outside.append(item)
            continue
        if ev["violations"]:
            status = "Violations"
        elif row["plan"] == "disapplied":
            status = "Disapplied"
        elif any(n > 0 for n in ev["deviations"].values()):
            status = "Deviations"
        else:
            status = "Compliant"
        item["status"] = status
        item["violations"] = ev["violations"]
        item["deviations"] = [{"id": d, "sites": n} for d, n in sorted(ev["deviations"].items())]
        item["notes"] = ev["notes"]
        counts[{"Compliant": "compliant", "Deviations": "deviations", "Disapplied": "disapplied",
                "Violations": "violations"}[status]] += 1
        guidelines.append(item)

    by_cat = {}
    by_method = {}
    for it in guidelines:
        k = f"{it['kind']}s"
        by_cat.setdefault(k, {c: 0 for c in CATEGORIES})[it["category"]] += 1
        for m in it["methods"]:
            by_method[m] = by_method.get(m, 0) + 1

    tools = {
        "cppcheck": tool_version(["cppcheck", "--version"]),
        "cppcheck MISRA addon": addon_path or "not found",
        "gcc": tool_version(["gcc", "--version"]),
        "arm-none-eabi-gcc": tool_version(["arm-none-eabi-gcc", "--version"]),
        "frama-c": tool_version(["frama-c", "-version"]),
        "cbmc": tool_version([rp("build", "tools", "cbmc", "bin", "cbmc"), "--version"]),
        "python": sys.version.split()[0],
    }
    grp = [{"id": it["id"], "category": it["category"], "recategorised": "disapplied",
            "reason": it["reason"]} for it in guidelines if it["status"] == "Disapplied"]
    dev_list = []
    for d, rec in sorted(devs.items()):
        sites = sum(per[g]["deviations"].get(d, 0) for g in rec["guidelines"] if g in per)
        dev_list.append({"id": d, "title": rec["title"], "guidelines": sorted(rec["guidelines"], key=gid_key),
                         "sites": sites})

    total = len(guidelines)
    viol_total = counts["violations"] + (1 if unattributed else 0)
    summary = {
        "framework": FRAMEWORK,
        "guidelines": BASELINE,
        "scope": "src/*.c, include/qfoc/*.h, tables/*.[ch], port_s32k/*.[ch]",
        "tools": tools,
        "cppcheck_result_version": cppcheck_xml_version,
        "recategorisation_plan": grp,
        "deviation_records": dev_list,
        "counts": dict(counts, guidelines=total),
        "per_category": by_cat,
        "per_method": dict(sorted(by_method.items())),
        "unattributed_findings": unattributed,
        "review_records": review_states,
        "plan_errors": errors,
        "compliant": viol_total == 0 and not errors,
        "guideline_status": guidelines,
        "outside_baseline": outside,
    }
    with open(os.path.join(out_dir, "compliance-summary.json"), "w", encoding="utf-8") as f:
        json.dump(summary, f, indent=1)
        f.write("\n")
    write_md(os.path.join(out_dir, "compliance-summary.md"), summary)

    for e in errors:
        print(f"misra-summary: {e}")
    for it in guidelines:
        for v in it["violations"]:
            print(f"misra-summary: {it['id']}: {v}")
    for u in unattributed:
        print(f"misra-summary: unattributed finding: {u}")
    print("misra-summary: review records (misra/reviews.md): "
          + (", ".join(f"{v} {k}" for k, v in sorted(review_states.items())) or "none"))
    print(f"misra-summary: {total} guidelines: {counts['compliant']} compliant, "
          f"{counts['deviations']} with deviations, {counts['disapplied']} disapplied, "
          f"{viol_total} violations")
    return 0 if viol_total == 0 and not errors else 1


def write_md(path, s):
    c = s["counts"]
    L = []
    L.append("# MISRA C:2012 Guideline Compliance Summary (qfoc)\n")
    L.append(f"Framework: {s['framework']}.  Guidelines: {s['guidelines']}.  "
             f"Code: {s['scope']}.\n")
    verdict = "compliant" if s["compliant"] else "NOT compliant (violations or plan errors below)"
    L.append(f"**{c['guidelines']} guidelines: {c['compliant']} compliant, {c['deviations']} with "
             f"deviations, {c['disapplied']} disapplied, {c['violations']} with violations: "
             f"{verdict}.**\n")
    L.append("## Tools\n")
    L.append("| tool | version |\n|---|---|")
    for k, v in s["tools"].items():
        L.append(f"| {k} | {v} |")
    L.append("")
    L.append("## Guideline re-categorisation plan\n")
    L.append("Mandatory and required guidelines keep their categories; no advisory guideline is "
             "raised.  Advisory guidelines disapplied:\n")
    if s["recategorisation_plan"]:
        L.append("| guideline | category | re-categorised | reason |\n|---|---|---|---|")
        for r in s["recategorisation_plan"]:
            L.append(f"| {r['id']} | {r['category']} | {r['recategorised']} | {r['reason']} |")
    else:
        L.append("none.")
    L.append("")
    L.append("## Deviation records (misra/deviations.md)\n")
    L.append("| record | guidelines | sites | title |\n|---|---|---:|---|")
    for d in s["deviation_records"]:
        L.append(f"| {d['id']} | {', '.join(d['guidelines'])} | {d['sites']} | {d['title']} |")
    L.append("")
    L.append("## Guidelines per category and per verification method\n")
    L.append("| kind | mandatory | required | advisory |\n|---|---:|---:|---:|")
    for k, v in sorted(s["per_category"].items()):
        L.append(f"| {k} | {v['mandatory']} | {v['required']} | {v['advisory']} |")
    L.append("")
    L.append("| method | guidelines |\n|---|---:|")
    for k, v in s["per_method"].items():
        L.append(f"| {k} | {v} |")
    L.append("")
    if s["plan_errors"] or s["unattributed_findings"]:
        L.append("## Plan errors and unattributed findings\n")
        for e in s["plan_errors"] + s["unattributed_findings"]:
            L.append(f"- {e}")
        L.append("")
    L.append("## Guideline compliance\n")
    L.append("Methods: `cppcheck` the MISRA addon of `make misra`; `cppcheck-core` cppcheck's "
             "core checks of error severity in the same run; `compiler` a warning of the "
             "project's `WARN` flags with `-Werror`; `proof` Frama-C WP with `-wp-rte` "
             "(`make prove`, src/); `cbmc` `make cbmc`; `coverage` `make coverage` (100 % lines "
             "and branches, src/); `trace` `make trace`; `review` a record of "
             "misra/reviews.md; `not-applicable` the construct does not occur (reason given).\n")
    L.append("| guideline | category | edition | decidability | status | detail | methods |\n"
             "|---|---|---|---|---|---|---|")
    for it in s["guideline_status"]:
        detail = []
        if it["status"] == "Deviations":
            detail.append(", ".join(f"{d['id']} ({d['sites']} sites)" for d in it["deviations"]
                                    if d["sites"] > 0))
        if it["status"] == "Disapplied":
            detail.append(it["reason"])
        if it["violations"]:
            detail.append("; ".join(it["violations"]))
        if "not-applicable" in it["methods"] and it["status"] == "Compliant":
            detail.append("not applicable: " + it["reason"])
        detail += it["notes"]
        L.append(f"| {it['id']} | {it['category']} | {it['edition']} | {it['decidability'] or '-'} | "
                 f"{it['status']} | {' '.join(detail).replace('|', '/')} | "
                 f"{', '.join(it['methods'])} |")
    L.append("")
    L.append("## Outside the claimed baseline: MISRA C:2012 Amendments 3 and 4\n")
    L.append("The guidelines these amendments add (C11/C18 features) are not part of the "
             "compliance claim; qfoc is C99 (`-std=c99`).  None of their constructs occurs.\n")
    L.append("| guideline | category | edition | reason |\n|---|---|---|---|")
    for it in s["outside_baseline"]:
        L.append(f"| {it['id']} | {it['category']} | {it['edition']} | {it['reason']} |")
    L.append("")
    with open(path, "w", encoding="utf-8") as f:
        f.write("\n".join(L))


if __name__ == "__main__":
    sys.exit(main())
