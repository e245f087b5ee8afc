#!/usr/bin/env python3
"""MISRA gate report: cppcheck XML findings and inline suppressions vs deviation records.

usage: misra_report.py CPPCHECK_XML DEVIATIONS_MD REPORT_MD SRC_DIR...
- every finding left in the XML is unrecorded: the gate fails;
- every 'cppcheck-suppress misra-c2012-R.N' comment in the sources must carry a
  deviation ID (DEV-nnn) that misra/deviations.md defines for the same rule.
Prints 'misra: N findings, M suppressions (all recorded)' and exits 1 on a gap.
"""
import os
import re
import sys
import xml.etree.ElementTree as ET

SUPP = re.compile(r"cppcheck-suppress\s+(misra-c2012-[0-9.]+)(.*)$")
DEV_ID = re.compile(r"\bDEV-\d{3}\b")
DEV_HEAD = re.compile(r"^##+\s*(DEV-\d{3})\b.*$")
DEV_RULE = re.compile(r"Rule\s*[:|]?\s*\**\s*([0-9]+\.[0-9]+)")


def deviations(path):
    devs = {}
    if not os.path.exists(path):
        return devs
    cur = None
    with open(path, encoding="utf-8") as f:
        for line in f:
            m = DEV_HEAD.match(line)
            if m:
                cur = m.group(1)
                devs[cur] = set()
                continue
            if cur:
                for r in DEV_RULE.findall(line):
                    devs[cur].add(r)
    return devs


def main() -> int:
    xml_path, dev_path, report, *dirs = sys.argv[1:]
    findings = []
    root = ET.parse(xml_path).getroot()
    for e in root.iter("error"):
        loc = e.find("location")
        where = f"{loc.get('file')}:{loc.get('line')}" if loc is not None else "?"
        findings.append((e.get("id"), where, e.get("msg")))
    devs = deviations(dev_path)
    supps, gaps = [], []
    for d in dirs:
        for dirpath, _dirs, files in os.walk(d):
            for fn in sorted(files):
                if not fn.endswith((".c", ".h")):
                    continue
                p = os.path.join(dirpath, fn)
                with open(p, encoding="utf-8") as f:
                    for no, line in enumerate(f, 1):
                        m = SUPP.search(line)
                        if not m:
                            continue
                        rule = m.group(1).replace("misra-c2012-", "")
                        ids = DEV_ID.findall(m.group(2))
                        ok = any(i in devs and rule in devs[i] for i in ids)
                        supps.append((p, no, rule, ",".join(ids) or "-", ok))
                        if not ok:
                            gaps.append(f"{p}:{no}: suppression of Rule {rule} without a matching "
                                        f"deviation record in {dev_path}")
    with open(report, "w", encoding="utf-8") as f:
        f.write("# MISRA C:2012 check (cppcheck addon)\n\n")
        f.write(f"Unrecorded findings: {len(findings)}\n\n")
        for rid, where, msg in findings:
            f.write(f"- {where}: {rid}: {msg}\n")
        f.write(f"\nSuppressed findings with deviation records: {sum(1 for s in supps if s[4])}\n\n")
        f.write("| file | line | rule | deviation | recorded |\n|---|---:|---|---|---|\n")
        for p, no, rule, ids, ok in supps:
            f.write(f"| {p} | {no} | {rule} | {ids} | {'yes' if ok else 'NO'} |\n")
    for rid, where, msg in findings:
        print(f"{where}: {rid}: {msg}")
    for g in gaps:
        print(g)
    print(f"misra: {len(findings)} unrecorded findings, {len(supps)} suppressions "
          f"({len(supps) - len(gaps)} with deviation records)")
    return 0 if not findings and not gaps else 1


if __name__ == "__main__":
    sys.exit(main())
