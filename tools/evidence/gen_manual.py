#!/usr/bin/env python3
"""The table of assumed safety requirements of specs/safety-manual.md, generated
(REQ-EVD-018).

usage: gen_manual.py [--root DIR] [--check]

Writes the table of section 2.1 of specs/safety-manual.md between the lines
'<!-- BEGIN GENERATED: asr ... -->' and '<!-- END GENERATED: asr -->' from

  specs/asr.toml               each ASR's ID, assumed ASIL, statement and note (human-written;
                               the figures {wp.proved}, ... of the note filled in from the
                               committed results by tools/evidence/figures.py)
  specs/requirements/*.md      the requirements whose 'Attributes:' line names the ASR
                               ('ASR ASR-nn'): the column "stated by"; and the references of
                               their 'Clauses:' lines: the evidence column, before the note

With --check it writes nothing and exits 1 when the committed table differs from the one
it would write (each differing row named), when an ASR has no requirement, or when a
requirement names an ASR that specs/asr.toml does not define.  `make trace` runs it with
--check.
"""
import argparse
import os
import re
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)

import figures  # noqa: E402
import req_attrs  # noqa: E402

MANUAL = "specs/safety-manual.md"
BEGIN = ("<!-- BEGIN GENERATED: asr (tools/evidence/gen_manual.py from specs/asr.toml and the "
         "Attributes: and Clauses: lines of specs/requirements/*.md; do not edit) -->")
BEGIN_RE = re.compile(r"^<!-- BEGIN GENERATED: asr\b.*-->$", re.M)
END = "<!-- END GENERATED: asr -->"
HEADER = ("| ID | assumed safety requirement | ASIL assumed | stated by | evidence: the clauses, "
          "lemmas, harnesses and tests of those requirements; more evidence |\n|---|---|---|---|---|")


def id_ranges(ids):
    """Consecutive IDs (three or more: 001, 002, 003 of one module) -> "first .. last"."""
    out, run = [], []

    def flush():
        if len(run) >= 3:
            out.append(f"{run[0]} .. {run[-1]}")
        else:
            out.extend(run)
        run.clear()
    for rid in ids:
        if run:
            pm, pn = run[-1].rsplit("-", 1)
            m, n = rid.rsplit("-", 1)
            if not (m == pm and int(n) == int(pn) + 1):
                flush()
        run.append(rid)
    flush()
    return ", ".join(out)


def evidence_of(refs):
    """The evidence text of the clause references of a set of requirements (in order, each
    once)."""
    wp, lemmas, groups = {}, [], {"cbmc": [], "test": [], "target": [], "bench": []}
    for r in refs:
        if r["kind"] == "acsl":
            label = "no runtime error" if r["label"] == "rte" else f"`{r['label']}`"
            lst = wp.setdefault(r["name"], [])
            if label not in lst:
                lst.append(label)
        elif r["kind"] == "lemma":
            if r["name"] not in lemmas:
                lemmas.append(r["name"])
        elif r["name"] not in groups[r["kind"]]:
            groups[r["kind"]].append(r["name"])
    parts = []
    if wp:
        parts.append("WP: " + "; ".join(f"`{fn}` {', '.join(labels)}" for fn, labels in wp.items()))
    if lemmas:
        parts.append("lemma" + ("s " if len(lemmas) > 1 else " ") + ", ".join(f"`{x}`" for x in lemmas))
    names = {"cbmc": ("CBMC", "CBMC"), "test": ("test", "tests"), "target": ("target test", "target tests"),
             "bench": ("bench", "bench")}
    for k in ("cbmc", "test", "target", "bench"):
        if groups[k]:
            one, many = names[k]
            parts.append((many if len(groups[k]) > 1 else one) + " " + ", ".join(f"`{x}`" for x in groups[k]))
    return "; ".join(parts)


def fill(note, vals):
    """The note with its {figure} placeholders replaced; raises KeyError on an unknown or
    unavailable figure."""
    def repl(m):
        value = vals.get(m.group(1), (None, ""))[0]
        if value is None:
            raise KeyError(m.group(1))
        return str(value)
    return re.sub(r"\{([a-z_.]+)\}", repl, note)


def generate(root="."):
    """(the table text between the markers, errors)."""
    asrs, errors = req_attrs.load_asrs(root)
    attrs = req_attrs.load_attributes(root)
    vals = figures.values(root)
    stated = {a: [] for a in asrs}
    for rid, rec in sorted(attrs.items()):
        if rid == "?" or not rec["attrs"]:
            continue
        for a in rec["attrs"]["asr"]:
            if a not in stated:
                errors.append(f"{rid} names {a}, which {req_attrs.ASR_FILE} does not define")
                continue
            stated[a].append(rid)
    rows = []
    for aid, a in asrs.items():
        reqs = stated[aid]
        if not reqs:
            errors.append(f"{aid}: no requirement names it (field 'ASR' of the Attributes: lines)")
        refs = [r for rid in reqs for r in (attrs[rid]["clauses"] or [])]
        ev = evidence_of(refs)
        try:
            note = fill(str(a.get("note", "")).strip(), vals)
        except KeyError as e:
            errors.append(f"{aid}: the note's figure {{{e.args[0]}}} is unknown or has no source here")
            note = str(a.get("note", ""))
        cell = "; ".join(x for x in (ev, note) if x) or "-"
        asil = a.get("asil", "?") + ("" if a.get("scope") == "library" else " (none assumed: reference port)")
        rows.append(f"| {aid} | {a['statement'].strip()} | {asil} | {id_ranges(reqs) or '-'} | {cell} |")
    return "\n".join([BEGIN, HEADER] + rows + [END]), errors


def current(text):
    """(start, end) of the generated block in the manual's text, or None."""
    b = BEGIN_RE.search(text)
    e = text.find(END)
    if not b or e < b.start():
        return None
    return b.start(), e + len(END)


def main(argv=None):
    ap = argparse.ArgumentParser(description="The ASR table of specs/safety-manual.md.")
    ap.add_argument("--root", default=".")
    ap.add_argument("--check", action="store_true", help="fail when the committed table differs")
    args = ap.parse_args(argv)
    path = os.path.join(args.root, MANUAL)
    with open(path, encoding="utf-8") as f:
        text = f.read()
    table, errors = generate(args.root)
    span = current(text)
    if span is None:
        errors.append(f"{MANUAL}: no '<!-- BEGIN GENERATED: asr -->' ... '{END}' block")
    for e in errors:
        print(f"gen-manual: {e}")
    if errors:
        return 1
    old = text[span[0]:span[1]]
    if args.check:
        if old == table:
            print(f"gen-manual: the ASR table of {MANUAL} is up to date "
                  f"({len(table.splitlines()) - 4} ASRs)")
            return 0
        old_rows = {r.split(" | ")[0]: r for r in old.splitlines() if r.startswith("| ASR-")}
        new_rows = {r.split(" | ")[0]: r for r in table.splitlines() if r.startswith("| ASR-")}
        for k in sorted(set(old_rows) | set(new_rows), key=lambda x: req_attrs.asr_key(x[2:])):
            if old_rows.get(k) != new_rows.get(k):
                print(f"gen-manual: {MANUAL}: the row {k[2:]} of the ASR table is stale")
        if old.splitlines()[:2] != table.splitlines()[:2]:
            print(f"gen-manual: {MANUAL}: the ASR table's markers or header differ")
        print(f"gen-manual: FAILED: the ASR table of {MANUAL} differs from its sources; "
              f"run tools/evidence/gen_manual.py")
        return 1
    if old != table:
        with open(path, "w", encoding="utf-8") as f:
            f.write(text[:span[0]] + table + text[span[1]:])
        print(f"gen-manual: {MANUAL}: ASR table written")
    else:
        print(f"gen-manual: {MANUAL}: ASR table unchanged")
    return 0


if __name__ == "__main__":
    sys.exit(main())
