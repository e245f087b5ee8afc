#!/usr/bin/env python3
"""Requirement traceability gate.

Requirements are the '### REQ-<MOD>-NNN title' headings of specs/requirements/*.md.
For each one, this finds where its ID is named:
  contract  - include/qfoc/*.h (doxygen of the function whose contract states it),
              tools/qfoc_tune.py (the tuning tool's interface, for REQ-TUNE), the
              target-equivalence vector format tools/target_test/tt.h (REQ-TGT) and the
              bench's interface tools/bench/*.h (REQ-BENCH)
  wp        - specs/*.acsl and include/qfoc/*.h contracts (proved by make prove)
  cbmc      - proofs/cbmc/*/harness.c
  test      - tests/*.c (CMocka), tools/tests/*.py (pytest, the tuning tool), the
              target-equivalence runner tools/target_test/*.c, *.sh (under QEMU) and
              the bench tools/bench/*.py
The gate fails when a requirement is named by no test and no proof artefact, or when
a source names an ID that no requirement defines.  Writes build/trace/trace.md and
prints 'trace: N requirements, N with tests, N with CBMC harnesses'.
"""
import glob
import os
import re
import sys

REQ = re.compile(r"\bREQ-[A-Z0-9]+-\d{3}\b")
HEAD = re.compile(r"^###\s+(REQ-[A-Z0-9]+-\d{3})\s+(.*)$")


def ids_in(paths):
    found = {}
    for p in paths:
        with open(p, encoding="utf-8") as f:
            for m in REQ.finditer(f.read()):
                found.setdefault(m.group(0), set()).add(p)
    return found


def main() -> int:
    reqs = {}
    for p in sorted(glob.glob("specs/requirements/*.md")):
        with open(p, encoding="utf-8") as f:
            for line in f:
                m = HEAD.match(line.strip())
                if m:
                    reqs[m.group(1)] = (m.group(2), p)
    kinds = {
        "contract": ids_in(sorted(glob.glob("include/qfoc/*.h")) + ["tools/qfoc_tune.py"]
                           + sorted(glob.glob("tools/target_test/tt.h"))
                           + sorted(glob.glob("tools/bench/*.h"))),
        "cbmc": ids_in(sorted(glob.glob("proofs/cbmc/*/harness.c"))),
        "test": ids_in(sorted(glob.glob("tests/*.c")) + sorted(glob.glob("tools/tests/*.py"))
                       + sorted(glob.glob("tools/target_test/*.c"))
                       + sorted(glob.glob("tools/target_test/*.sh"))
                       + sorted(glob.glob("tools/bench/*.py"))),
    }
    ok = True
    rows = []
    for rid, (title, src) in sorted(reqs.items()):
        where = {k: sorted(v.get(rid, ())) for k, v in kinds.items()}
        if not where["test"] and not where["cbmc"]:
            print(f"trace: {rid} ({src}) is exercised by no test and no CBMC harness")
            ok = False
        if not where["contract"]:
            print(f"trace: {rid} ({src}) is named by no public header")
            ok = False
        rows.append((rid, title, where))
    for k, found in kinds.items():
        for rid in sorted(set(found) - set(reqs)):
            print(f"trace: {rid} named in {', '.join(sorted(found[rid]))} is not a defined requirement")
            ok = False
    os.makedirs("build/trace", exist_ok=True)
    with open("build/trace/trace.md", "w", encoding="utf-8") as f:
        f.write("# Requirement traceability\n\n| requirement | title | header | CBMC | tests |\n"
                "|---|---|---|---|---|\n")
        for rid, title, where in rows:
            cell = {k: "<br>".join(os.path.basename(os.path.dirname(p)) if k == "cbmc"
                                   else os.path.basename(p) for p in v) or "-"
                    for k, v in where.items()}
            f.write(f"| {rid} | {title} | {cell['contract']} | {cell['cbmc']} | {cell['test']} |\n")
    n = len(rows)
    print(f"trace: {n} requirements, {sum(1 for r in rows if r[2]['test'])} with tests, "
          f"{sum(1 for r in rows if r[2]['cbmc'])} with CBMC harnesses, "
          f"{sum(1 for r in rows if r[2]['contract'])} named in headers")
    return 0 if ok and n > 0 else 1


if __name__ == "__main__":
    sys.exit(main())
