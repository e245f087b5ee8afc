#!/usr/bin/env python3
"""MC/DC report from gcov-14 --conditions --json-format records (tools/gates/mcdc.sh).

For every decision that gcc 14's -fcondition-coverage instrumented in src/*.c and in
the inline code of include/qfoc/*.h, the report counts the condition outcomes (two per
condition: true and false) that the tests covered in the MC/DC sense gcc measures
(masking MC/DC: an outcome counts when the condition, with that value, was shown to
decide the decision's result).  A header's inline function is compiled into several
units (library units and tests): its outcomes are merged over all of them, decision by
decision.

It writes build/mcdc/mcdc.json (every decision with its conditions and outcomes) and
build/mcdc/mcdc.md (per file and function: conditions, outcomes covered, percentage;
every outcome not covered with file:line, function, decision and condition text, and
whether specs/mcdc-justifications.md justifies it), and prints

    mcdc: N / M condition outcomes covered (P %) in src/

as its last line.  Exit status 1 when src/ or the inline header code is below --min
PERCENT, or (with --strict) when an outcome not covered has no justification or a
justification matches nothing; 2 on unusable input.

Justifications (specs/mcdc-justifications.md) are list items of the form

    - `FILE:FUNCTION:CONDITION` (OUTCOME): reason

with OUTCOME `true`, `false` or `true, false`, and CONDITION the condition's text as this
report prints it (white space is not significant).
"""

import argparse
import glob
import gzip
import json
import math
import os
import re
import sys

KEEP = ("src/", "include/qfoc/")

# ---------------------------------------------------------------- source parsing
# Enough of C to find the boolean decisions of a file and split them into conditions
# the way gcc numbers them (left to right, through parentheses, not into calls).

TOKEN_RE = re.compile(
    r"[A-Za-z_]\w*|\.?\d[\w.]*(?:[eEpP][-+]\d+)?|&&|\|\||<<=|>>=|->|\+\+|--|<<|>>"
    r"|[-+*/%&|^!=<>]=|[(){}\[\];,?:~!<>=+\-*/%&|^.]")
ASSIGN = {"=", "+=", "-=", "*=", "/=", "%=", "&=", "|=", "^=", "<<=", ">>="}
BOUNDARY = ASSIGN | {";", ",", "?", ":", "return", "case", "default", "else", "do",
                     "goto", "break", "continue"}


def blank_comments(text):
    """Comments, string and character literals and preprocessor lines replaced by
    spaces (newlines kept, so offsets and line numbers stay)."""
    out = list(text)
    i, n = 0, len(text)
    line_start = True
    while i < n:
        c = text[i]
        if line_start and c == "#":
            # preprocessor directive with its continuation lines
            j = i
            while j < n and text[j] != "\n":
                if text[j] == "\\" and j + 1 < n and text[j + 1] == "\n":
                    j += 2
                    continue
                # comments inside a directive end with it
                j += 1
            for k in range(i, j):
                if out[k] != "\n":
                    out[k] = " "
            i = j
            continue
        if c == "\n":
            line_start = True
            i += 1
            continue
        if not c.isspace():
            line_start = False
        if text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            for k in range(i, j):
                if out[k] != "\n":
                    out[k] = " "
            i = j
        elif text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            for k in range(i, j):
                out[k] = " "
            i = j
        elif c in "\"'":
            j = i + 1
            while j < n and text[j] != c and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            for k in range(i + 1, min(j, n)):
                out[k] = " "
            i = j + 1
        else:
            i += 1
    return "".join(out)


class Group:
    """A bracketed group: kind is '(', '[' or '{'; items are tokens and groups."""

    def __init__(self, kind, open_tok):
        self.kind = kind
        self.open = open_tok
        self.close = open_tok
        self.items = []


def tokenize(code):
    line_starts = [0]
    for m in re.finditer("\n", code):
        line_starts.append(m.end())
    toks = []
    li = 0
    for m in TOKEN_RE.finditer(code):
        while li + 1 < len(line_starts) and line_starts[li + 1] <= m.start():
            li += 1
        toks.append((m.group(), m.start(), m.end(), li + 1))
    return toks


def build_tree(toks):
    root = Group("", None)
    stack = [root]
    pairs = {")": "(", "]": "[", "}": "{"}
    for t in toks:
        v = t[0]
        if v in "([{":
            g = Group(v, t)
            stack[-1].items.append(g)
            stack.append(g)
        elif v in pairs:
            if len(stack) > 1 and stack[-1].kind == pairs[v]:
                stack[-1].close = t
                stack.pop()
            # an unbalanced closer is ignored
        else:
            stack[-1].items.append(t)
    return root


def is_tok(x, v=None):
    return isinstance(x, tuple) and (v is None or x[0] == v)


def first_tok(x):
    return x.open if isinstance(x, Group) else x


def last_tok(x):
    return x.close if isinstance(x, Group) else x


def split_on(items, values):
    parts, cur = [], []
    for x in items:
        if is_tok(x) and x[0] in values:
            parts.append(cur)
            cur = []
        else:
            cur.append(x)
    parts.append(cur)
    return parts


def unwrap(seg):
    """seg without leading '!' when the rest is one parenthesised group: its content."""
    k = 0
    while k < len(seg) and is_tok(seg[k], "!"):
        k += 1
    if len(seg) == k + 1 and isinstance(seg[k], Group) and seg[k].kind == "(":
        return seg[k].items
    return None


def is_chain(seg):
    if any(is_tok(x) and x[0] in ("&&", "||") for x in seg):
        return True
    inner = unwrap(seg)
    return inner is not None and is_chain(inner)


def flatten(seg):
    """Conditions of a decision expression, left to right."""
    if not any(is_tok(x) and x[0] in ("&&", "||") for x in seg):
        inner = unwrap(seg)
        if inner is not None and is_chain(inner):
            return flatten(inner)
        return [seg]
    atoms = []
    for part in split_on(seg, ("&&", "||")):
        inner = unwrap(part)
        if inner is not None and is_chain(inner):
            atoms.extend(flatten(inner))
        else:
            atoms.append(part)
    return atoms


class Decision:
    """A decision: the expression seg, its conditions atoms (lists of items)."""

    def __init__(self, seg, kind):
        self.atoms = flatten(seg)
        self.kind = kind
        self.line = first_tok(self.atoms[0][0])[3]
        self.first = first_tok(seg[0])[1]
        self.last = last_tok(seg[-1])[2]


def scan(items, out):
    """Append every decision found in items (and below) to out."""
    i, n = 0, len(items)
    seg = []

    def flush(following):
        if seg:
            if is_chain(seg):
                d = Decision(seg[:], "expression")
                out.append(d)
                for a in d.atoms:
                    scan_groups(a, out)
            elif following == "?":
                d = Decision(seg[:], "ternary")
                out.append(d)
                scan_groups(seg, out)
            else:
                scan_groups(seg, out)
        seg.clear()

    while i < n:
        x = items[i]
        if is_tok(x) and x[0] in ("if", "while", "switch", "for") and i + 1 < n \
                and isinstance(items[i + 1], Group) and items[i + 1].kind == "(":
            flush(None)
            g = items[i + 1]
            if x[0] in ("if", "while"):
                if g.items:
                    d = Decision(g.items, x[0])
                    out.append(d)
                    for a in d.atoms:
                        scan_groups(a, out)
            elif x[0] == "for":
                parts = split_on(g.items, (";",))
                for k, p in enumerate(parts):
                    if k == 1 and p:
                        d = Decision(p, "for")
                        out.append(d)
                        for a in d.atoms:
                            scan_groups(a, out)
                    else:
                        scan(p, out)
            else:
                scan(g.items, out)
            i += 2
            continue
        if isinstance(x, Group) and x.kind == "{":
            flush(None)
            scan(x.items, out)
        elif is_tok(x) and x[0] in BOUNDARY:
            flush(x[0])
        else:
            seg.append(x)
        i += 1
    flush(None)


def scan_groups(seg, out):
    for x in seg:
        if isinstance(x, Group):
            scan(x.items, out)


class Source:
    def __init__(self, path):
        with open(path, encoding="utf-8", errors="replace") as f:
            self.text = f.read()
        code = blank_comments(self.text)
        self.code = code
        self.lines = self.text.split("\n")
        decisions = []
        toks = tokenize(code)
        scan(build_tree(toks).items, decisions)
        # gcc places a decision on the line of its first condition, or (for one written
        # over several lines, or inside a call) on a later line of its statement: keep
        # the line of the ';' or '{' that ends the statement too.
        ends = [(t[1], t[3]) for t in toks if t[0] in (";", "{")]
        self.decisions = decisions
        self.by_line = {}
        for d in decisions:
            d.end_line = d.line
            for off, line in ends:
                if off >= d.last:
                    d.end_line = line
                    break
            self.by_line.setdefault(d.line, []).append(d)

    def span_text(self, first, last):
        return " ".join(self.code[first:last].split())

    def atom_text(self, atom):
        inner = atom
        # a condition written in parentheses is shown without them
        while len(inner) == 1 and isinstance(inner[0], Group) and inner[0].kind == "(":
            inner = inner[0].items
        if not inner:
            inner = atom
        return self.span_text(first_tok(inner[0])[1], last_tok(inner[-1])[2])

    def line_text(self, line):
        if 1 <= line <= len(self.lines):
            return " ".join(self.lines[line - 1].split())
        return ""

    def match(self, line, nconds, used, exact):
        """The decision with nconds conditions, not used yet, that starts at line
        (exact) or, failing that, whose statement spans line (the nearest before)."""
        if exact:
            cands = self.by_line.get(line, [])
        else:
            cands = sorted((d for d in self.decisions if d.line <= line <= d.end_line),
                           key=lambda d: -d.line)
        for d in cands:
            if len(d.atoms) == nconds and id(d) not in used:
                used.add(id(d))
                return d
        return None


# ---------------------------------------------------------------- gcov records

def norm_path(path, cwd):
    p = path
    if not os.path.isabs(p):
        p = os.path.normpath(os.path.join(cwd, p))
    # the chroot's copy lives at /qfoc (tools/gates/mcdc.sh); keep the path inside the tree
    for root in ("/qfoc/",):
        if p.startswith(root):
            return p[len(root):]
    return os.path.normpath(path)


def load_records(gcov_dir):
    """{(file, line, index): {...}} merged over every record."""
    decisions = {}
    units = []
    for rec in sorted(glob.glob(os.path.join(gcov_dir, "*.gcov.json.gz"))):
        with gzip.open(rec, "rt", encoding="utf-8") as f:
            data = json.load(f)
        units.append(os.path.basename(rec))
        cwd = data.get("current_working_directory", "/")
        for fe in data.get("files", []):
            path = norm_path(fe["file"], cwd)
            if not path.startswith(KEEP):
                continue
            for ln in fe.get("lines", []):
                for k, c in enumerate(ln.get("conditions", [])):
                    ncond = c["count"] // 2
                    covered = set()
                    for i in range(ncond):
                        if i not in c.get("not_covered_true", []):
                            covered.add((i, True))
                        if i not in c.get("not_covered_false", []):
                            covered.add((i, False))
                    if len(covered) != c["covered"]:
                        print("mcdc_report: %s:%d: gcov counts %d covered, lists %d"
                              % (path, ln["line_number"], c["covered"], len(covered)),
                              file=sys.stderr)
                    key = (path, ln["line_number"], k)
                    d = decisions.get(key)
                    if d is None:
                        decisions[key] = {"file": path, "line": ln["line_number"], "index": k,
                                          "function": ln.get("function_name", "?"),
                                          "conditions": ncond, "covered": covered,
                                          "units": {os.path.basename(rec)}}
                    elif d["conditions"] != ncond:
                        print("mcdc_report: %s:%d: decision %d has %d conditions in one unit, "
                              "%d in another" % (path, ln["line_number"], k, d["conditions"], ncond),
                              file=sys.stderr)
                        sys.exit(2)
                    else:
                        d["covered"] |= covered
                        d["units"].add(os.path.basename(rec))
    return decisions, units


# ---------------------------------------------------------------- justifications

JUST_RE = re.compile(r"^[-*]\s+`(?P<key>[^`]+)`\s*\((?P<out>[^)]*)\)\s*:\s*(?P<why>.+?)\s*$")


def norm_cond(text):
    return " ".join(text.split())


def load_justifications(path):
    items = []
    if not path or not os.path.exists(path):
        return items
    with open(path, encoding="utf-8") as f:
        lines = f.read().split("\n")
    # entries are the unindented list items of the section '## Entries' (of the whole
    # file when it has no such section)
    sectioned = any(x.strip().lower() == "## entries" for x in lines)
    in_entries = not sectioned
    for no, line in enumerate(lines, 1):
        if line.startswith("## ") and sectioned:
            in_entries = line.strip().lower() == "## entries"
            continue
        if in_entries:
            m = JUST_RE.match(line)
            if not m:
                continue
            parts = m.group("key").split(":", 2)
            if len(parts) != 3:
                print("mcdc_report: %s:%d: key is not FILE:FUNCTION:CONDITION" % (path, no),
                      file=sys.stderr)
                continue
            outs = set()
            for w in re.split(r"[,\s]+", m.group("out").strip().lower()):
                if w in ("true", "false"):
                    outs.add(w == "true")
                elif w in ("both",):
                    outs |= {True, False}
                elif w:
                    print("mcdc_report: %s:%d: outcome '%s' is not true or false" % (path, no, w),
                          file=sys.stderr)
            items.append({"file": parts[0].strip(), "function": parts[1].strip(),
                          "condition": norm_cond(parts[2]), "outcomes": outs,
                          "reason": m.group("why"), "line": no, "used": False})
    return items


# ---------------------------------------------------------------- report

def pct(n, m):
    """Percentage rounded down to two decimals (never shows 100 when short of it)."""
    if m == 0:
        return 100.0
    return math.floor(10000.0 * n / m) / 100.0


def fmt_pct(n, m):
    return "%.2f" % pct(n, m) if m else "-"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--gcov-dir", default="build/mcdc/gcov")
    ap.add_argument("--out", default="build/mcdc")
    ap.add_argument("--root", default=".", help="repository root (the sources are read here)")
    ap.add_argument("--justifications", default="specs/mcdc-justifications.md")
    ap.add_argument("--min", type=float, default=None, metavar="PERCENT",
                    help="fail when src/ or the inline header code is below PERCENT")
    ap.add_argument("--strict", action="store_true",
                    help="also fail on an unjustified outcome or an unused justification")
    args = ap.parse_args()

    os.chdir(args.root)
    decisions, units = load_records(args.gcov_dir)
    if not units:
        print("mcdc_report: no gcov records in %s" % args.gcov_dir, file=sys.stderr)
        return 2
    justs = load_justifications(args.justifications)

    sources = {}
    for d in decisions.values():
        if d["file"] not in sources:
            sources[d["file"]] = Source(d["file"]) if os.path.exists(d["file"]) else None
    # each gcov decision to its source text: first those that start on their line
    used = {}
    found = {}
    for exact in (True, False):
        for key in sorted(decisions):
            d = decisions[key]
            src = sources[d["file"]]
            if key not in found and src is not None:
                m = src.match(d["line"], d["conditions"], used.setdefault(d["file"], set()), exact)
                if m is not None:
                    found[key] = m
    # decisions of the source that gcc did not instrument: a conditional expression it
    # folds into a branch-free MIN, MAX or ABS (e.g. (x < 0) ? -x : x) has no condition
    matched = {id(m) for m in found.values()}
    folded = []
    for path in sorted(set(list(sources) + sorted(glob.glob("src/*.c")))):
        if path not in sources:
            sources[path] = Source(path) if os.path.exists(path) else None
        src = sources[path]
        if src is None:
            continue
        for m in src.decisions:
            if id(m) not in matched:
                folded.append({"file": path, "line": m.line, "kind": m.kind,
                               "conditions": len(m.atoms),
                               "decision": src.span_text(m.first, m.last)})
    unmatched = 0
    rows = []
    for key in sorted(decisions):
        d = decisions[key]
        path = d["file"]
        src = sources[path]
        dec = found.get(key)
        if dec is not None:
            conds = [src.atom_text(a) for a in dec.atoms]
            text = src.span_text(dec.first, dec.last)
        else:
            unmatched += 1
            line = src.line_text(d["line"]) if src else ""
            conds = ["condition %d of: %s" % (i, line) for i in range(d["conditions"])]
            text = line
        outcomes = []
        for i in range(d["conditions"]):
            for val in (True, False):
                cov = (i, val) in d["covered"]
                o = {"condition": i, "text": conds[i], "outcome": "true" if val else "false",
                     "covered": cov}
                if not cov:
                    for j in justs:
                        if j["file"] == path and j["function"] == d["function"] \
                                and j["condition"] == norm_cond(conds[i]) and val in j["outcomes"]:
                            o["justification"] = j["reason"]
                            j["used"] = True
                            break
                outcomes.append(o)
        rows.append({"file": path, "line": d["line"], "function": d["function"],
                     "decision": text, "conditions": d["conditions"],
                     "outcomes_total": 2 * d["conditions"],
                     "outcomes_covered": len(d["covered"]),
                     "units": sorted(d["units"]), "outcomes": outcomes,
                     "text_from_source": dec is not None})

    # every library unit appears, also one without decisions (or without code)
    files = {}
    for s in sorted(glob.glob("src/*.c")):
        files[s] = {"total": 0, "covered": 0, "justified": 0, "functions": {}}
    for r in rows:
        f = files.setdefault(r["file"], {"total": 0, "covered": 0, "justified": 0, "functions": {}})
        fn = f["functions"].setdefault(r["function"], {"decisions": 0, "conditions": 0, "total": 0,
                                                       "covered": 0, "justified": 0})
        just = sum(1 for o in r["outcomes"] if not o["covered"] and "justification" in o)
        fn["decisions"] += 1
        fn["conditions"] += r["conditions"]
        fn["total"] += r["outcomes_total"]
        fn["covered"] += r["outcomes_covered"]
        fn["justified"] += just
        f["total"] += r["outcomes_total"]
        f["covered"] += r["outcomes_covered"]
        f["justified"] += just

    def area(prefix):
        t = sum(f["total"] for p, f in files.items() if p.startswith(prefix))
        c = sum(f["covered"] for p, f in files.items() if p.startswith(prefix))
        j = sum(f["justified"] for p, f in files.items() if p.startswith(prefix))
        return t, c, j

    s_t, s_c, s_j = area("src/")
    h_t, h_c, h_j = area("include/")
    uncovered = [(r, o) for r in rows for o in r["outcomes"] if not o["covered"]]
    unjustified = [(r, o) for r, o in uncovered if "justification" not in o]
    stale = [j for j in justs if not j["used"]]

    summary = {
        "tool": "gcc 14 -fcondition-coverage, gcov --conditions --json-format",
        "criterion": "MC/DC (masking), ISO 26262-6 table 9; two outcomes per condition",
        "records": units,
        "src": {"outcomes": s_t, "covered": s_c, "justified": s_j, "percent": pct(s_c, s_t)},
        "include": {"outcomes": h_t, "covered": h_c, "justified": h_j, "percent": pct(h_c, h_t)},
        "uncovered": len(uncovered), "unjustified": len(unjustified),
        "unused_justifications": [{"line": j["line"], "key": "%s:%s:%s" % (j["file"], j["function"],
                                                                         j["condition"])}
                                  for j in stale],
        "decisions_without_source_text": unmatched,
        "decisions_not_instrumented": len(folded),
        "min_percent": args.min,
    }
    os.makedirs(args.out, exist_ok=True)
    jfiles = {}
    for p, f in sorted(files.items()):
        jfiles[p] = {"outcomes": f["total"], "covered": f["covered"], "justified": f["justified"],
                     "percent": pct(f["covered"], f["total"]),
                     "functions": {n: dict(v, percent=pct(v["covered"], v["total"]))
                                   for n, v in sorted(f["functions"].items())}}
    with open(os.path.join(args.out, "mcdc.json"), "w", encoding="utf-8") as f:
        json.dump({"summary": summary, "files": jfiles, "decisions": rows,
                   "not_instrumented": folded}, f, indent=1)
        f.write("\n")

    md = []
    md.append("# MC/DC coverage of the library")
    md.append("")
    md.append("Modified condition/decision coverage (ISO 26262-6, table 9) measured with gcc 14's "
              "`-fcondition-coverage` (masking MC/DC: an outcome of a condition counts when the "
              "condition, with that value, was shown to decide its decision) while the unit tests "
              "`tests/test_*.c` ran; `sim/` and `tables/` are test equipment and not measured.  "
              "Two outcomes (true, false) per condition.  Inline functions of `include/qfoc/` are "
              "merged over every unit that compiles them.  Produced by `make mcdc` "
              "(`tools/gates/mcdc.sh`, `tools/gates/mcdc_report.py`); justifications from "
              "`specs/mcdc-justifications.md`.")
    md.append("")
    md.append("| scope | condition outcomes | covered | % | not covered | justified |")
    md.append("|---|---:|---:|---:|---:|---:|")
    md.append("| `src/` | %d | %d | %s | %d | %d |" % (s_t, s_c, fmt_pct(s_c, s_t), s_t - s_c, s_j))
    md.append("| `include/qfoc/` (inline) | %d | %d | %s | %d | %d |"
              % (h_t, h_c, fmt_pct(h_c, h_t), h_t - h_c, h_j))
    if args.min is not None:
        md.append("")
        md.append("Gate: at least %g %% in each scope." % args.min)
    md.append("")
    md.append("## Outcomes not covered")
    md.append("")
    if not uncovered:
        md.append("None: every condition outcome of every decision is covered.")
    else:
        md.append("| location | function | condition | outcome | justification |")
        md.append("|---|---|---|---|---|")
        for r, o in uncovered:
            where = "" if r["conditions"] == 1 else " (condition %d of `%s`)" % (
                o["condition"], r["decision"].replace("|", "\\|"))
            md.append("| `%s:%d` | `%s` | `%s`%s | %s | %s |" % (
                r["file"], r["line"], r["function"], o["text"].replace("|", "\\|"),
                where, o["outcome"],
                ("justified: " + o["justification"].replace("|", "\\|"))
                if "justification" in o else "**not justified**"))
    if stale:
        md.append("")
        md.append("Justifications that match no outcome not covered (out of date):")
        md.append("")
        for j in stale:
            md.append("- line %d: `%s:%s:%s`" % (j["line"], j["file"], j["function"], j["condition"]))
    md.append("")
    md.append("## Per file")
    md.append("")
    md.append("| file | decisions | conditions | outcomes | covered | % | justified |")
    md.append("|---|---:|---:|---:|---:|---:|---:|")
    for p, f in sorted(files.items()):
        nd = sum(v["decisions"] for v in f["functions"].values())
        nc = sum(v["conditions"] for v in f["functions"].values())
        md.append("| `%s` | %d | %d | %d | %d | %s | %d |" % (
            p, nd, nc, f["total"], f["covered"], fmt_pct(f["covered"], f["total"]), f["justified"]))
    md.append("")
    md.append("## Per function")
    md.append("")
    md.append("| file | function | decisions | conditions | outcomes | covered | % | justified |")
    md.append("|---|---|---:|---:|---:|---:|---:|---:|")
    for p, f in sorted(files.items()):
        for n, v in sorted(f["functions"].items()):
            md.append("| `%s` | `%s` | %d | %d | %d | %d | %s | %d |" % (
                p, n, v["decisions"], v["conditions"], v["total"], v["covered"],
                fmt_pct(v["covered"], v["total"]), v["justified"]))
    empty = [p for p, f in sorted(files.items()) if f["total"] == 0]
    if empty:
        md.append("")
        md.append("Units without a decision: " + ", ".join("`%s`" % p for p in empty) + ".")
    if unmatched:
        md.append("")
        md.append("%d decisions could not be matched to their text in the source; they are "
                  "shown by line." % unmatched)
    if folded:
        md.append("")
        md.append("## Decisions without conditions in the object code")
        md.append("")
        md.append("Found in the source, but gcc compiled them without a branch (a conditional "
                  "expression folded into MIN, MAX or ABS), so `-fcondition-coverage` measures "
                  "no condition for them and they are not counted above:")
        md.append("")
        md.append("| location | kind | decision |")
        md.append("|---|---|---|")
        for x in folded:
            md.append("| `%s:%d` | %s | `%s` |" % (x["file"], x["line"], x["kind"],
                                                  x["decision"].replace("|", "\\|")))
    md.append("")
    md.append("Every decision with its conditions: `mcdc.json` (`decisions`; the ones above "
              "in `not_instrumented`).")
    with open(os.path.join(args.out, "mcdc.md"), "w", encoding="utf-8") as f:
        f.write("\n".join(md) + "\n")

    # terminal
    shown = 40
    for r, o in uncovered[:shown]:
        print("mcdc: not covered: %s:%d %s: %s (%s)%s" % (
            r["file"], r["line"], r["function"], o["text"], o["outcome"],
            " -- justified" if "justification" in o else ""))
    if len(uncovered) > shown:
        print("mcdc: ... %d more outcomes not covered in the report" % (len(uncovered) - shown))
    for j in stale:
        print("mcdc: %s:%d: justification matches nothing: %s:%s:%s" % (
            args.justifications, j["line"], j["file"], j["function"], j["condition"]))
    if unmatched:
        print("mcdc: %d decisions shown by line (text not found)" % unmatched)
    if folded:
        print("mcdc: %d decisions of the source have no branch in the object code "
              "(MIN/MAX/ABS), not measured: listed in the report" % len(folded))
    print("mcdc: report %s, %s" % (os.path.join(args.out, "mcdc.md"),
                                   os.path.join(args.out, "mcdc.json")))
    print("mcdc: %d of %d outcomes not covered are justified" % (len(uncovered) - len(unjustified),
                                                                 len(uncovered)))
    print("mcdc: %d / %d condition outcomes covered (%s %%) in include/qfoc/ (inline)"
          % (h_c, h_t, fmt_pct(h_c, h_t)))
    status = 0
    if args.min is not None:
        for name, c, t in (("src/", s_c, s_t), ("include/qfoc/", h_c, h_t)):
            if t and 100.0 * c < args.min * t:
                print("mcdc: %s below %g %%" % (name, args.min))
                status = 1
    if args.strict and (unjustified or stale):
        print("mcdc: --strict: %d outcomes not justified, %d justifications unused"
              % (len(unjustified), len(stale)))
        status = 1
    print("mcdc: %d / %d condition outcomes covered (%s %%) in src/" % (s_c, s_t, fmt_pct(s_c, s_t)))
    return status


if __name__ == "__main__":
    sys.exit(main())
