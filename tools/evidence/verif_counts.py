#!/usr/bin/env python3
"""Counts of the unit verification cases of qfoc, per suite and per test-design method, for
specs/verification-spec.md.

  python3 tools/evidence/verif_counts.py            rewrite the generated section
  python3 tools/evidence/verif_counts.py --check    exit 1 when a case has no valid method
                                                    tag or the committed section differs
  python3 tools/evidence/verif_counts.py --list     print every case with its methods and
                                                    their reasons
  options: --root DIR (the repository root; default: two levels above this file),
           --spec PATH (default: specs/verification-spec.md under the root)

Suites and their cases (paths relative to the root; a suite whose files are absent is left
out):
  CMocka     each tests/test_*.c; a case is each function registered with cmocka_unit_test*()
             (a file without registrations: each 'void test_*(void **state)' function);
  pytest     each test_*.py under tools/ (any depth) and port_s32k/pil/tests/; a case is each function 'def test_*'
             (a parametrised function is one case), named by the file's base name (its path
             relative to the root when two files share a base name);
  CBMC       proofs/cbmc: a case is each folder holding a harness.c;
  target     the golden-vector groups of tools/**/tt_groups.c (the names of its suite table
             tt_suites[], "drive_fast" and "drive_tick" included); their inputs are made by
             tt_gen.c;
  robustness the campaign of sim/apps/robust.c: ROBUST_COUNT cold starts (the default of the
             Makefile or mk/*.mk), each drawn by the same code, so each carries the same tag.
The targets of specs/scenarios.toml (sections, min_/max_ keys) are counted apart: the
scenarios themselves are the cases of tests/test_scenarios.c.

Methods.  The methods of ISO 26262-6:2018 Table 8 (derivation of test cases: 1a analysis
of requirements, 1b equivalence classes, 1c boundary values, 1d error guessing) and two of
Table 7 (1l fault injection test, 1n back-to-back comparison test) that derived a case are
stated by its author in the case's specification text, in a method tag:

  Methods: 1b <the classes>; 1c <the boundaries>; 1d <the error guessed>

a line starting with 'Methods:' (after the comment's leader '/*', '*', '//' or '#'), in
  CMocka   the comment block right above the test function;
  pytest   the comment lines right above the function (above its decorators) or its
           docstring;
  CBMC     the header comment of harness.c (its first /* */ block);
  target   the comment right above the group's entry in the suite table of tt_groups.c
           (the entry of "drive_fast" and "drive_tick" gives both groups);
  campaign the header comment of sim/apps/robust.c.
The tag runs on over the following lines up to a blank line or the end of the comment.  Its
entries are separated by ';'; each is a method code (1a, 1b, 1c, 1d, 1l, 1n) and the reason
that makes the method true of the case: which classes, which boundaries, which error, which
fault, against what.  A case has exactly one tag, each code at most once, every code with a
reason; a tag with a Table 7 code on a CBMC harness is an error (formal verification,
Table 7 1e: the test columns do not apply, '-').  1b .. 1n are counted from the tags alone.

1a is counted from the requirements a case traces, as make trace reads them: a
requirement ID REQ-<MOD>-NNN in the case's text (its comment, docstring, body; for a target
group also the comment above the suite table, which names the requirements of every group;
for a harness or the campaign its file) or a name test_<mod>_NNN_..., test_req_<mod>_NNN_...
or test_<mod>_reqNNN_... of a defined requirement.  A tag may list 1a too, with the analysis
(which statement, which formula); it must then name a requirement, and a case derived from
its requirement alone has the tag 'Methods: 1a <reason>'.

Errors (exit status 1, each named with file:line and the case, before any figure): a case
without a tag, two tags, a line that looks like a tag but is not one ('methods:', 'Method:'),
an empty tag or entry, an unknown method code, a code twice, a code without a reason, 1a
on a case that names no requirement, 1l or 1n on a CBMC harness.

The generated section lies between the markers BEGIN and END below; the rest of the spec is
left as it is.  --check parses the figures of the committed section and names each suite and
figure that differs from what the tool would write.  parse_tag() and case_tags() are the one
reader of the tags: a tool that needs a case's methods imports them.

Requirement: REQ-EVD-007 (the tests reported with the evidence).
"""
import argparse
import ast
import glob
import os
import re
import sys

BEGIN = "<!-- BEGIN GENERATED: counts -->"
END = "<!-- END GENERATED: counts -->"

# Columns of the generated tables: key, heading.
COLUMNS = (
    ("cases", "cases"),
    ("1a", "T8 1a requirements"),
    ("1b", "T8 1b equivalence classes"),
    ("1c", "T8 1c boundary values"),
    ("1d", "T8 1d error guessing"),
    ("1l", "T7 1l fault injection"),
    ("1n", "T7 1n back-to-back"),
)
METHODS = tuple(k for k, _ in COLUMNS if k != "cases")
T7 = ("1l", "1n")
# The method codes of a tag and what each states.
CODES = {
    "1a": "analysis of requirements (Table 8)",
    "1b": "generation and analysis of equivalence classes (Table 8)",
    "1c": "analysis of boundary values (Table 8)",
    "1d": "error guessing based on knowledge or experience (Table 8)",
    "1l": "fault injection test (Table 7)",
    "1n": "back-to-back comparison test (Table 7)",
}

REQ_ID = re.compile(r"\bREQ-([A-Z0-9]+)-(\d{3})\b")
# test_<mod>_NNN..., test_req_<mod>_NNN..., test_<mod>_reqNNN...: the requirement REQ-<MOD>-NNN
NAME_REQ = re.compile(r"^test_(?:req_)?([a-z0-9]+?)_(?:req)?(\d{3})(?:_|$)")

TAG = "Methods:"
# A line that looks like a tag: 'methods:', 'Method :', ...
TAG_LIKE = re.compile(r"^methods?\s*:", re.I)
ENTRY = re.compile(r"^(\S+)(?:\s+(.*))?$", re.S)


# ------------------------------------------------------------------ the method tag

def strip_leader(line):
    """A line of a comment or docstring without its comment leader and the comment's ends
    ('/*', '/**', '*', '//', '#', '*/')."""
    s = line.strip()
    if s.endswith("*/"):
        s = s[:-2].rstrip()
    if s.startswith("/*"):
        s = s[2:]
        s = s.lstrip("*")
    elif s.startswith("//"):
        s = s.lstrip("/")
    elif s.startswith("#"):
        s = s.lstrip("#")
    elif s.startswith("*"):
        s = s[1:]
    return s.strip()


def parse_tag(text, first_line=1):
    """The method tag of a specification text (a comment or a docstring whose first line is
    line first_line of its file).

    Returns (tag, errors): tag is None when the text has no tag, else a dict with 'line'
    (the tag's line) and 'methods' ({code: reason}, in the order written); errors is a list
    of (line, message)."""
    lines = [strip_leader(ln) for ln in text.split("\n")]
    errors = []
    starts = []
    for k, s in enumerate(lines):
        if s.startswith(TAG):
            starts.append(k)
        elif TAG_LIKE.match(s):
            errors.append((first_line + k, f"malformed tag {s.split(':')[0]!r}: write "
                                            f"'{TAG}'"))
    if not starts:
        return None, errors
    if len(starts) > 1:
        errors.append((first_line + starts[1], f"a second tag (the first on line "
                                               f"{first_line + starts[0]})"))
    k0 = starts[0]
    parts = [lines[k0][len(TAG):].strip()]
    k = k0 + 1
    while k < len(lines) and lines[k] and not lines[k].startswith(TAG):
        parts.append(lines[k])
        k += 1
    body = " ".join(p for p in parts if p).strip()
    line = first_line + k0
    methods = {}
    if not body:
        errors.append((line, "empty tag: name at least one method with its reason"))
    entries = [e.strip() for e in body.split(";")]
    if entries and entries[-1] == "" and len(entries) > 1:
        entries.pop()          # a ';' closing the last entry
    for e in entries if body else []:
        m = ENTRY.match(e)
        if not e or not m:
            errors.append((line, "empty entry between ';'"))
            continue
        code, reason = m.group(1).rstrip(":,."), (m.group(2) or "").strip()
        if code not in CODES:
            errors.append((line, f"unknown method code {code!r} (known: {', '.join(CODES)})"))
            continue
        if code in methods:
            errors.append((line, f"method {code} twice"))
            continue
        if not reason.strip(" .,:"):
            errors.append((line, f"method {code} without a reason"))
            continue
        methods[code] = reason.rstrip()
    return {"line": line, "methods": methods}, errors


def case_tags(places):
    """The tag of a case from its specification texts, places = [(text, first line)]:
    (tag or None, errors) as parse_tag(); two tags among the places are an error."""
    found, errors = [], []
    for text, first in places:
        tag, errs = parse_tag(text, first)
        errors += errs
        if tag is not None:
            found.append(tag)
    if len(found) > 1:
        errors.append((found[1]["line"], f"a second tag (the first on line "
                                         f"{found[0]['line']})"))
    return (found[0] if found else None), errors


# ------------------------------------------------------------------ C text

def c_split(text):
    """(code, comments) of a C text: comments replaced by a space in the code; string and
    character literals kept in the code."""
    code, comments = [], []
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            comments.append(text[i:j])
            code.append(" ")
            i = j
        elif text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            comments.append(text[i:j])
            code.append(" ")
            i = j
        elif c in "\"'":
            j = i + 1
            while j < n and text[j] != c:
                j += 2 if text[j] == "\\" else 1
            code.append(text[i:j + 1])
            i = j + 1
        else:
            code.append(c)
            i += 1
    return "".join(code), "\n".join(comments)


def c_block_end(text, open_idx):
    """Index just after the brace that closes the one at open_idx (comments and literals
    skipped)."""
    depth, i, n = 0, open_idx, len(text)
    while i < n:
        if text.startswith("/*", i):
            j = text.find("*/", i + 2)
            i = n if j < 0 else j + 2
            continue
        if text.startswith("//", i):
            j = text.find("\n", i)
            i = n if j < 0 else j
            continue
        c = text[i]
        if c in "\"'":
            j = i + 1
            while j < n and text[j] != c:
                j += 2 if text[j] == "\\" else 1
            i = j + 1
            continue
        if c == "{":
            depth += 1
        elif c == "}":
            depth -= 1
            if depth == 0:
                return i + 1
        i += 1
    return n


def line_of(text, pos):
    """The 1-based line of position pos."""
    return text.count("\n", 0, pos) + 1


def comment_above(text, start):
    """(comment, first line) of the comment right above the line that starts at position
    start: a /* */ block or // lines, no blank line between them and that line; first line
    is 1-based (the line of start when there is no comment)."""
    lines = text[:start].split("\n")
    if lines and lines[-1].strip() == "":
        lines = lines[:-1]
    out = []
    k = len(lines) - 1
    if k >= 0 and lines[k].rstrip().endswith("*/"):
        while k >= 0:
            out.insert(0, lines[k])
            if "/*" in lines[k]:
                break
            k -= 1
        return "\n".join(out), k + 1
    while k >= 0 and lines[k].lstrip().startswith("//"):
        out.insert(0, lines[k])
        k -= 1
    return "\n".join(out), k + 2


C_DEF = re.compile(
    r"^(?:static\s+)?(?:inline\s+)?(?:const\s+)?[A-Za-z_]\w*[\s\*]+(\w+)\s*\(([^;{}()]*)\)\s*\{",
    re.MULTILINE)


def c_functions(text):
    """name -> (comment above, its first line, body, line of the definition) of each
    function defined at the start of a line."""
    out = {}
    for m in C_DEF.finditer(text):
        name = m.group(1)
        if name in ("if", "for", "while", "switch", "return", "sizeof"):
            continue
        open_idx = m.end() - 1
        end = c_block_end(text, open_idx)
        above, first = comment_above(text, m.start())
        out.setdefault(name, (above, first, text[open_idx:end], line_of(text, m.start())))
    return out


def header_comment(text):
    """(the first /* */ block of a file, its first line)."""
    m = re.match(r"\s*(/\*.*?\*/)", text, re.S)
    return (m.group(1), line_of(text, m.start(1))) if m else ("", 1)


# ------------------------------------------------------------------ cases

class Case:
    """One verification case: its name, where it is defined, the texts its requirements
    are read from, the places its method tag may be, and (after read_tags) its tag."""

    def __init__(self, name, path, line, description, code, places, module=""):
        self.name = name
        self.path = path          # relative to the root
        self.line = line          # of its definition (or entry)
        self.description = description
        self.code = code
        self.places = places      # [(text, first line)]
        self.module = module
        self.tag = None
        self.tags = set()
        self.why = {}
        self.errors = []          # [(line, message)]


class Suite:
    """A suite: its name, kind, cases."""

    def __init__(self, name, kind, cases, no_t7=False, repeat=1):
        self.name = name
        self.kind = kind
        self.cases = cases
        self.no_t7 = no_t7
        self.repeat = repeat     # the robustness campaign: one drawing code, N runs


def read(path):
    with open(path, encoding="utf-8", errors="replace") as f:
        return f.read()


def rel(root, path):
    return os.path.relpath(path, root).replace(os.sep, "/")


def defined_requirements(root):
    ids = set()
    for path in glob.glob(os.path.join(root, "specs", "requirements", "*.md")):
        for m in re.finditer(r"^###\s+(REQ-[A-Z0-9]+-\d{3})\b", read(path), re.M):
            ids.add(m.group(1))
    return ids


def cmocka_suites(root):
    suites = []
    for path in sorted(glob.glob(os.path.join(root, "tests", "test_*.c"))):
        text = read(path)
        funcs = c_functions(text)
        names = []
        for n in re.findall(r"cmocka_unit_test\w*\(\s*(\w+)", text):
            if n not in names:
                names.append(n)
        if not names:
            names = re.findall(r"^(?:static\s+)?void\s+(test_\w+)\s*\(\s*void\s*\*\*", text,
                               re.M)
        module = os.path.basename(path)[len("test_"):-len(".c")]
        cases = []
        for name in names:
            above, first, body, line = funcs.get(name, ("", 1, "", 1))
            code, comments = c_split(body)
            cases.append(Case(name, rel(root, path), line,
                              "\n".join((name, above, comments)), code, [(above, first)],
                              module))
        suites.append(Suite(rel(root, path), "CMocka", cases))
    return suites


def py_cases(root, path):
    text = read(path)
    lines = text.split("\n")
    tree = ast.parse(text)
    module = os.path.basename(path)[len("test_"):-len(".py")]
    cases = []
    nodes = []
    for node in tree.body:
        if isinstance(node, ast.ClassDef):
            nodes.extend(n for n in node.body if isinstance(n, ast.FunctionDef))
        elif isinstance(node, ast.FunctionDef):
            nodes.append(node)
    for node in nodes:
        if not node.name.startswith("test_"):
            continue
        first = min([node.lineno] + [d.lineno for d in node.decorator_list]) - 1
        above = []
        k = first - 1
        while k >= 0 and lines[k].lstrip().startswith("#"):
            above.insert(0, lines[k])
            k -= 1
        places = [("\n".join(above), k + 2)]
        first_stmt = node.body[0]
        if (isinstance(first_stmt, ast.Expr) and isinstance(first_stmt.value, ast.Constant)
                and isinstance(first_stmt.value.value, str)):
            # the docstring as written (not cleaned), so that its lines are the file's
            places.append((first_stmt.value.value, first_stmt.lineno))
        seg = "\n".join(lines[first:node.end_lineno])
        description = "\n".join((node.name, "\n".join(above), seg))
        cases.append(Case(node.name, rel(root, path), node.lineno, description, "", places,
                          module))
    return cases


def pytest_suites(root):
    paths = sorted(glob.glob(os.path.join(root, "tools", "**", "test_*.py"), recursive=True)
                   + glob.glob(os.path.join(root, "port_s32k", "pil", "tests", "test_*.py")))
    base = [os.path.basename(p) for p in paths]
    suites = []
    for path, b in zip(paths, base):
        name = b if base.count(b) == 1 else rel(root, path)
        suites.append(Suite(name, "pytest", py_cases(root, path)))
    return sorted(suites, key=lambda s: s.name)


def cbmc_suite(root):
    cases = []
    for path in sorted(glob.glob(os.path.join(root, "proofs", "cbmc", "*", "harness.c"))):
        name = os.path.basename(os.path.dirname(path))
        text = read(path)
        head, first = header_comment(text)
        cases.append(Case(name, rel(root, path), 1, text, "", [(head, first)]))
    if not cases:
        return []
    return [Suite("proofs/cbmc", "CBMC", cases, no_t7=True)]


def target_suite(root):
    found = sorted(glob.glob(os.path.join(root, "tools", "**", "tt_groups.c"), recursive=True))
    if not found:
        return []
    text = read(found[0])
    funcs = c_functions(text)
    table_at = text.find("tt_suites[")
    if table_at < 0:
        return []
    table_line = text.rfind("\n", 0, table_at) + 1
    # the comment above the suite table names the requirements of every group (1a)
    suite_comment, _ = comment_above(text, table_line)
    table_end = c_block_end(text, text.find("{", table_at))
    cases = []
    for m in re.finditer(r'\{\s*\{\s*"(\w+)"\s*,\s*(?:"(\w+)"|NULL)\s*\}\s*,\s*\w+\s*,'
                         r'\s*(\w+)\s*\}', text[table_at:table_end]):
        at = table_at + m.start()
        first = text.rfind("\n", 0, at) + 1
        entry = text[first:text.find("\n", at)]
        above, above_first = comment_above(text, first)
        replay = funcs.get(m.group(3), ("", 1, "", 1))
        description = "\n".join((above, entry, replay[0], replay[2], suite_comment))
        for name in (m.group(1), m.group(2)):
            if name:
                cases.append(Case(name, rel(root, found[0]), line_of(text, at), description,
                                  "", [(above, above_first)]))
    return [Suite("target_test", "target", cases)]


def robust_count(root):
    for path in [os.path.join(root, "Makefile")] + sorted(glob.glob(os.path.join(root, "mk",
                                                                             "*.mk"))):
        if os.path.exists(path):
            m = re.search(r"^ROBUST_COUNT\s*\??=\s*(\d+)\s*$", read(path), re.M)
            if m:
                return int(m.group(1))
    return 0


def robust_suite(root):
    path = os.path.join(root, "sim", "apps", "robust.c")
    if not os.path.exists(path):
        return []
    text = read(path)
    head, first = header_comment(text)
    case = Case("cold start (seeded draw)", rel(root, path), first, text, "", [(head, first)])
    return [Suite("robustness", "campaign", [case], repeat=robust_count(root))]


def scenario_targets(root):
    """(sections, targets) of specs/scenarios.toml, or None."""
    path = os.path.join(root, "specs", "scenarios.toml")
    if not os.path.exists(path):
        return None
    text = read(path)
    sections = re.findall(r"^\[([^\]]+)\]", text, re.M)
    targets = re.findall(r"^(?:min|max)_\w+\s*=", text, re.M)
    return len(sections), len(targets)


# ------------------------------------------------------------------ methods of a case

def requirement_of(case, defined):
    """The first requirement the case names (for 1a), or None."""
    ids = sorted({m.group(0) for m in REQ_ID.finditer(case.description + "\n" + case.code)})
    if ids:
        return ids[0]
    m = NAME_REQ.match(case.name)
    if m and f"REQ-{m.group(1).upper()}-{m.group(2)}" in defined:
        return f"name: REQ-{m.group(1).upper()}-{m.group(2)}"
    return None


def read_tags(suite, defined):
    """Read the tag of every case of the suite: case.tag, case.tags (the methods counted),
    case.why (code -> reason) and case.errors."""
    for c in suite.cases:
        c.tag, c.errors = case_tags(c.places)
        methods = dict(c.tag["methods"]) if c.tag else {}
        line = c.tag["line"] if c.tag else c.line
        if c.tag is None and not c.errors:
            c.errors.append((c.line, f"no '{TAG}' tag ({where(suite.kind)})"))
        req = requirement_of(c, defined)
        if "1a" in methods and req is None:
            c.errors.append((line, "1a in the tag, but the case names no requirement"))
        if suite.no_t7:
            for k in T7:
                if k in methods:
                    c.errors.append((line, f"{k} in the tag of a CBMC harness (formal "
                                           f"verification; the Table 7 test methods do "
                                           f"not apply)"))
        c.why = {k: methods[k] for k in METHODS if k in methods and k != "1a"}
        if req is not None:
            c.why["1a"] = req if "1a" not in methods else f"{req}: {methods['1a']}"
        c.tags = set(c.why)


def where(kind):
    return {"CMocka": "in the comment right above the test function",
            "pytest": "in the comment right above the function or in its docstring",
            "CBMC": "in the header comment of harness.c",
            "target": "in the comment right above the group's entry in tt_suites[]",
            "campaign": "in the header comment of robust.c"}.get(kind, "")


def tag_errors(suites):
    """'file:line: suite case: message' of every case whose tag is missing or invalid."""
    out = []
    for s in suites:
        for c in s.cases:
            for line, msg in c.errors:
                out.append(f"{c.path}:{line}: {c.name}: {msg}")
    return out


def figures(suites, defined):
    """suite name -> (kind, {column: number or None}), in the order of the suites."""
    out = {}
    for s in suites:
        read_tags(s, defined)
        row = {"cases": len(s.cases) * s.repeat}
        for k in METHODS:
            if s.no_t7 and k in T7:
                row[k] = None
            else:
                row[k] = sum(1 for c in s.cases if k in c.tags) * s.repeat
        out[s.name] = (s.kind, row)
    return out


def all_suites(root):
    return (cmocka_suites(root) + pytest_suites(root) + cbmc_suite(root) + target_suite(root)
            + robust_suite(root))


# ------------------------------------------------------------------ the section

def fmt(v):
    return "-" if v is None else str(v)


def table(row):
    head = "| " + " | ".join(h for _, h in COLUMNS) + " |"
    rule = "|" + "|".join("---:" for _ in COLUMNS) + "|"
    data = "| " + " | ".join(fmt(row[k]) for k, _ in COLUMNS) + " |"
    return [head, rule, data]


def section(figs, scn):
    lines = [BEGIN,
             "",
             "Written by `python3 tools/evidence/verif_counts.py` from the sources; "
             "`--check` compares it with them.  Do not edit by hand.",
             ""]
    totals = {}
    for kind in ("CMocka", "pytest", "CBMC", "target", "campaign"):
        names = [n for n, (k, _) in figs.items() if k == kind]
        if not names:
            continue
        tot = {}
        for key, _ in COLUMNS:
            vals = [figs[n][1][key] for n in names]
            tot[key] = None if all(v is None for v in vals) else sum(v for v in vals if v)
        totals[kind] = (len(names), tot)
    lines += ["#### How a case is counted", "",
              "| column | a case is counted when ... |",
              "|---|---|",
              "| T8 1a requirements | it names a requirement: an ID REQ-<MOD>-NNN in its text, "
              "or a name test_<mod>_NNN_..., test_req_<mod>_NNN_... or test_<mod>_reqNNN_... "
              "where REQ-<MOD>-NNN is defined in specs/requirements/ |"]
    for key, head in COLUMNS[2:]:
        lines.append(f"| {head} | its method tag lists {key} |")
    lines += ["| suites | a robustness campaign's tag counts once per start; the CBMC "
              "harnesses are formal verification (T7 1e), their T7 test columns are '-' |",
              ""]
    lines += ["#### Totals", "",
              "| kind | suites | " + " | ".join(h for _, h in COLUMNS) + " |",
              "|---|---:|" + "|".join("---:" for _ in COLUMNS) + "|"]
    for kind, (n, tot) in totals.items():
        lines.append(f"| {kind} | {n} | " + " | ".join(fmt(tot[k]) for k, _ in COLUMNS) + " |")
    lines.append("")
    for name, (kind, row) in figs.items():
        lines += [f"#### {name} ({kind})", ""] + table(row) + [""]
    if scn is not None:
        lines += ["#### specs/scenarios.toml (targets)", "",
                  "| sections | min_ / max_ targets |", "|---:|---:|",
                  f"| {scn[0]} | {scn[1]} |", ""]
    lines.append(END)
    return "\n".join(lines)


def parse_section(text):
    """suite heading -> {column: figure text} of a generated section."""
    out = {}
    lines = text.split("\n")
    k = 0
    while k < len(lines):
        m = re.match(r"^#### (.+)$", lines[k])
        if m:
            name = m.group(1)
            rows = []
            j = k + 1
            while j < len(lines) and not lines[j].startswith("####"):
                if lines[j].startswith("|"):
                    rows.append([c.strip() for c in lines[j].strip().strip("|").split("|")])
                j += 1
            if len(rows) >= 3:
                head = rows[0]
                for data in rows[2:]:
                    key = name if len(rows) == 3 else f"{name} {data[0]}"
                    out[key] = dict(zip(head, data))
            k = j
        else:
            k += 1
    return out


def extract(spec_text):
    b = spec_text.find(BEGIN)
    e = spec_text.find(END)
    if b < 0 or e < 0 or e < b:
        return None
    return spec_text[b:e + len(END)]


def compare(committed, generated):
    """The differing figures, as messages."""
    old, new = parse_section(committed), parse_section(generated)
    msgs = []
    for name in new:
        if name not in old:
            msgs.append(f"{name}: missing from the committed section")
            continue
        for col, v in new[name].items():
            if old[name].get(col) != v:
                msgs.append(f"{name}: {col}: committed {old[name].get(col)}, sources give {v}")
    for name in old:
        if name not in new:
            msgs.append(f"{name}: in the committed section, no longer in the sources")
    if not msgs and committed != generated:
        msgs.append("the section's text differs from the generated one (figures equal)")
    return msgs


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--root", default=os.path.dirname(os.path.dirname(os.path.dirname(
        os.path.abspath(__file__)))))
    ap.add_argument("--spec", default=None)
    ap.add_argument("--check", action="store_true")
    ap.add_argument("--list", action="store_true")
    a = ap.parse_args(argv)
    root = a.root
    spec = a.spec or os.path.join(root, "specs", "verification-spec.md")
    suites = all_suites(root)
    figs = figures(suites, defined_requirements(root))
    errors = tag_errors(suites)
    if a.list:
        for s in suites:
            for c in s.cases:
                line = c.tag["line"] if c.tag else c.line
                tags = "; ".join(f"{k} {c.why[k]}" for k in METHODS if k in c.why)
                print(f"{s.name}\t{c.name}\t{c.path}:{line}\t{tags}")
    for msg in errors:
        print(f"verif_counts: {msg}", file=sys.stderr)
    if errors:
        print(f"verif_counts: {len(errors)} method tag error(s); each case states the methods "
              f"that derived it in a line '{TAG} 1b <classes>; 1c <boundaries>; ...' "
              f"(tools/evidence/verif_counts.py)", file=sys.stderr)
        return 1
    if a.list:
        return 0
    generated = section(figs, scenario_targets(root))
    if not os.path.exists(spec):
        print(f"verif_counts: {spec} not found", file=sys.stderr)
        return 2
    text = read(spec)
    committed = extract(text)
    if committed is None:
        print(f"verif_counts: {spec} has no section {BEGIN} .. {END}", file=sys.stderr)
        return 2
    if a.check:
        msgs = compare(committed, generated)
        for msg in msgs:
            print(f"verif_counts: {msg}", file=sys.stderr)
        if msgs:
            print("verif_counts: stale; run python3 tools/evidence/verif_counts.py",
                  file=sys.stderr)
            return 1
        print(f"verif_counts: {os.path.relpath(spec, root)} up to date "
              f"({sum(r['cases'] for _, r in figs.values())} cases in {len(figs)} suites, "
              f"every case tagged)")
        return 0
    new_text = text.replace(committed, generated)
    if new_text != text:
        with open(spec, "w", encoding="utf-8") as f:
            f.write(new_text)
    print(f"verif_counts: wrote {os.path.relpath(spec, root)} "
          f"({sum(r['cases'] for _, r in figs.values())} cases in {len(figs)} suites)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
