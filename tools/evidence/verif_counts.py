#!/usr/bin/env python3
"""Counts of the unit verification cases of qfoc, per suite, for specs/verification-spec.md.

  python3 tools/evidence/verif_counts.py            rewrite the generated section
  python3 tools/evidence/verif_counts.py --check    exit 1 when the committed section differs
  python3 tools/evidence/verif_counts.py --list     print every case with its tags
  options: --root DIR (the repository root; default: two levels above this file),
           --spec PATH (default: specs/verification-spec.md under the root)

Suites and their cases (paths relative to the root; a suite whose files are absent is left
out):
  CMocka     each tests/test_*.c; a case is each function registered with cmocka_unit_test*()
             (a file without registrations: each 'void test_*(void **state)' function);
  pytest     each test_*.py under tools/ (any depth); a case is each function 'def test_*'
             (a parametrised function is one case), named by the file's base name (its path
             relative to the root when two files share a base name);
  CBMC       proofs/cbmc: a case is each folder holding a harness.c;
  target     the golden-vector groups of tools/**/tt_groups.c (the names of its suite table,
             "drive_fast" and "drive_tick" included); their inputs are made by tt_gen.c;
  robustness the campaign of sim/apps/robust.c: ROBUST_COUNT cold starts (the default of the
             Makefile or mk/*.mk), each drawn by the same code, so each carries the same tags.
The targets of specs/scenarios.toml (sections, min_/max_ keys) are counted apart: the
scenarios themselves are the cases of tests/test_scenarios.c.

Tags.  Each case gets the methods of ISO 26262-6:2018 Table 8 (derivation of test cases:
1a analysis of requirements, 1b equivalence classes, 1c boundary values, 1d error guessing)
and two of Table 7 (1l fault injection test, 1n back-to-back comparison test) by the rules
of RULES below, which the generated section prints.  A case has three texts:
  head   its name and the comment block right above its definition (for pytest also the
         decorators and the docstring); for a CBMC harness or a target group its name;
  inner  the comments inside its body; for a CBMC harness all comments of harness.c; for a
         target group the comments of its generator function in tt_gen.c, of the tt_gen.c
         functions that one calls, of its entry line and of its replay function in
         tt_groups.c (the drive's groups: the generator's header and record_drive()); for
         the robustness campaign all comments of robust.c;
  code   the rest, without comments (and, for a target group, the comment above the suite
         table, which names the requirements of every group).
The description (head and inner) is lower-cased and split into words at every character
that is not a letter or a digit ('test_lpf_corners' gives 'test', 'lpf', 'corners'); the
runs of MERGE are joined first ('round trip' -> 'roundtrip'); the words that follow a
negation (NEGATION, articles skipped) are dropped ('no fault present'); and the module prefix
of a CMocka or pytest case's name (the 'fault' of 'test_fault_bits' in test_fault.c) is not a
word.  A rule's 'words' and 'desc_re' match anywhere in the description, its 'head' words
and 'head_phrases' only in the head, its 'code_re' in the code of the suite kinds it names;
1a also takes a requirement ID from any text.  Suite rules: every target group is 1n (it
compares the target build's outputs with the host build's); the CBMC harnesses are formal
verification (Table 7, 1e), and the Table 7 test columns do not apply to them ('-').

The generated section lies between the markers BEGIN and END below; the rest of the spec is
left as it is.  --check parses the figures of the committed section and names each suite and
figure that differs from what the tool would write.

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

REQ_ID = re.compile(r"\bREQ-([A-Z0-9]+)-(\d{3})\b")
# test_<mod>_NNN..., test_req_<mod>_NNN..., test_<mod>_reqNNN...: the requirement REQ-<MOD>-NNN
NAME_REQ = re.compile(r"^test_(?:req_)?([a-z0-9]+?)_(?:req)?(\d{3})(?:_|$)")

# The rule set ('doc' is printed in the generated section).  'words': any of these words
# of the description (a trailing '*' matches every word that starts so); 'head': words that
# count only in the case's head (words that also name a module or a field); 'phrases' and
# 'head_phrases': runs of words, likewise; 'desc_re': a regular expression on the
# description's text; 'code_re': one on the code, for the suite kinds of 'code_kinds'.
RULES = {
    "1a": {
        "doc": "names a requirement: an ID REQ-<MOD>-NNN in its description or code, or a "
               "name test_<mod>_NNN_..., test_req_<mod>_NNN_... or test_<mod>_reqNNN_... "
               "where REQ-<MOD>-NNN is defined in specs/requirements/",
    },
    "1b": {
        "doc": "samples or partitions the input domain: random*, exhaustive*, every, each, "
               "all, any, grid, class, classes, accepts, both, sign, signs, forward, reverse, "
               "positive, negative, sector*, quadrant*, octant*, sweep*, speeds, periods, "
               "tables, lengths, mixed; or draws its values in code (a call of rand_range, "
               "lcg*, rnd or rand, lcg_state, random.*, rng)",
        "words": ("random*", "exhaustive*", "every", "each", "all", "any", "grid", "class",
                  "classes", "accepts", "both", "sign", "signs", "forward", "reverse",
                  "positive", "negative", "sector*", "quadrant*", "octant*", "sweep*",
                  "speeds", "periods", "tables", "lengths", "mixed"),
        "code_re": r"\b(?:rand_range|lcg\w*|rnd|rand)\s*\(|\blcg_state\b|\brandom\.\w+|\brng\b",
        "code_kinds": ("CMocka", "pytest", "CBMC", "target", "campaign"),
    },
    "1c": {
        "doc": "aims at the edges of a range: boundar*, corner*, limit*, edge*, extreme*, "
               "saturat*, clamp*, span, overflow*, wrap*, axis, axes, diagonals, nodes, "
               "threshold*, window, bound, bounds, bounded, above, below, max, min, range, "
               "or the value -32768 (INT16_MIN); or uses the limits of the C types in code "
               "(-32768, INT8/16/32_MIN and _MAX, UINT8/16/32_MAX, 0x7FFF, 0x8000, 0xFFFF, "
               "65535)",
        "words": ("boundar*", "corner*", "limit*", "edge*", "extreme*", "saturat*",
                  "clamp*", "span", "overflow*", "wrap*", "axis", "axes", "diagonals",
                  "nodes", "threshold*", "window", "bound", "bounds", "bounded", "above",
                  "below", "max", "min", "range"),
        "desc_re": r"-32768\b|\bINT16_MIN\b",
        "code_re": r"-\s*32768\b|\b(?:U?INT(?:8|16|32)_(?:MIN|MAX)|0x7[fF]{3}|0x8000"
                   r"|0x[fF]{4}(?:[fF]{4})?|65535)[uUlL]*\b",
        "code_kinds": ("CMocka", "pytest", "CBMC", "target", "campaign"),
    },
    "1d": {
        "doc": "anticipates a failure: invalid, reject*, refuse*, flip*, corrupt*, "
               "malformed, wrong, bad, loss, lost, timeout*, stall*, overcurrent, "
               "overvoltage, noise, mismatch*, unbound, missing, broken, defect*, fail*, "
               "locked, garbage; fault, faults, trip, trips, tripped in the name or the "
               "comment above only (they also name modules and fields: fault.h, i_trip)",
        "words": ("invalid", "reject*", "refuse*", "flip*", "corrupt*", "malformed", "wrong",
                  "bad", "loss", "lost", "timeout*", "stall*", "overcurrent", "overvoltage",
                  "noise", "mismatch*", "unbound", "missing", "broken", "defect*", "fail*",
                  "locked", "garbage"),
        "head": ("fault", "faults", "trip", "trips", "tripped"),
    },
    "1l": {
        "doc": "injects a fault into the inputs or the data: flip*, corrupt*, malformed, "
               "inject*, overcurrent, overvoltage, loss, lost, stall*, timeout*, mismatch*, "
               "defect*, broken, locked, garbage, recheck; in the name or the comment above, "
               "trip, trips, tripped, or fault followed by its kind (fault oc, fault ov, "
               "fault ot, fault stall, fault link, fault reaction, fault to)",
        "words": ("flip*", "corrupt*", "malformed", "inject*", "overcurrent", "overvoltage",
                  "loss", "lost", "stall*", "timeout*", "mismatch*", "defect*", "broken",
                  "locked", "garbage", "recheck"),
        "head": ("trip", "trips", "tripped"),
        "head_phrases": ("fault oc", "fault ov", "fault ot", "fault stall", "fault link",
                         "fault reaction", "fault to"),
    },
    "1n": {
        "doc": "compares with an independent model or a twin: vs, twin, twins, equivalent, "
               "matches, double (a double-precision reference), against a/an/the model, "
               "reference or double, real recursion, real valued, reference recursion, "
               "like frame, bit exact, same as; or, in a CMocka case, computes in double "
               "precision in its code (the type double: a reference model of the "
               "equations)",
        "words": ("vs", "twin", "twins", "equivalent", "matches", "double"),
        "code_re": r"\bdouble\b",
        "code_kinds": ("CMocka",),
        "phrases": ("against a model", "against the model", "against a reference",
                    "against the reference", "against an independent", "against a double",
                    "against the double", "real recursion", "real valued",
                    "reference recursion", "like frame", "bit exact", "same as"),
    },
}
# Runs of words read as one word before the rules apply.
MERGE = (("round trip", "roundtrip"), ("over current", "overcurrent"),
         ("over voltage", "overvoltage"))
# The NEGATED words after one of these (articles skipped) are negated and do not count.
NEGATION = ("no", "not", "without", "never", "nor")
ARTICLES = ("a", "an", "the", "any")
NEGATED = 2   # words negated after the articles

WORD = re.compile(r"[a-z0-9]+")


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


def comment_above(text, start):
    """The comment lines right above position start (a /* */ block or // lines; no blank
    line between them and the definition)."""
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
        return "\n".join(out)
    while k >= 0 and lines[k].lstrip().startswith("//"):
        out.insert(0, lines[k])
        k -= 1
    return "\n".join(out)


C_DEF = re.compile(
    r"^(?:static\s+)?(?:inline\s+)?(?:const\s+)?[A-Za-z_]\w*[\s\*]+(\w+)\s*\(([^;{}()]*)\)\s*\{",
    re.MULTILINE)


def c_functions(text):
    """name -> (comment above, body) of each function defined at the start of a line."""
    out = {}
    for m in C_DEF.finditer(text):
        name = m.group(1)
        if name in ("if", "for", "while", "switch", "return", "sizeof"):
            continue
        open_idx = m.end() - 1
        end = c_block_end(text, open_idx)
        out.setdefault(name, (comment_above(text, m.start()), text[open_idx:end]))
    return out


def header_comment(text):
    """The first /* */ block of a file."""
    m = re.match(r"\s*(/\*.*?\*/)", text, re.S)
    return m.group(1) if m else ""


# ------------------------------------------------------------------ cases

class Case:
    """One verification case: its name, its description and code texts, and its tags."""

    def __init__(self, name, head, inner, code, module=""):
        self.name = name
        self.head = head          # name, comment above, docstring, decorators
        self.inner = inner        # comments inside the body
        self.description = head + "\n" + inner
        self.code = code
        self.module = module
        self.kind = ""
        self.tags = set()
        self.why = {}


class Suite:
    """A suite: its name, kind, cases and suite rules."""

    def __init__(self, name, kind, cases, all_tags=(), no_t7=False, repeat=1):
        self.name = name
        self.kind = kind
        self.cases = cases
        self.all_tags = set(all_tags)
        self.no_t7 = no_t7
        self.repeat = repeat     # the robustness campaign: one drawing code, N runs


def read(path):
    with open(path, encoding="utf-8", errors="replace") as f:
        return f.read()


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
        names = re.findall(r"cmocka_unit_test\w*\(\s*(\w+)", text)
        if not names:
            names = re.findall(r"^(?:static\s+)?void\s+(test_\w+)\s*\(\s*void\s*\*\*", text,
                               re.M)
        module = os.path.basename(path)[len("test_"):-len(".c")]
        cases = []
        for name in names:
            above, body = funcs.get(name, ("", ""))
            code, comments = c_split(body)
            cases.append(Case(name, name + "\n" + above, comments, code, module))
        suites.append(Suite(os.path.relpath(path, root).replace(os.sep, "/"), "CMocka",
                            cases))
    return suites


def py_cases(path):
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
        seg = "\n".join(lines[first:node.end_lineno])
        comments = "\n".join(ln for ln in seg.split("\n") if ln.lstrip().startswith("#"))
        doc = ast.get_docstring(node) or ""
        decorators = "\n".join(lines[first:node.lineno - 1])
        head = "\n".join((node.name, "\n".join(above), decorators, doc))
        code = "\n".join(ln for ln in seg.split("\n") if not ln.lstrip().startswith("#"))
        cases.append(Case(node.name, head, comments, code, module))
    return cases


def pytest_suites(root):
    paths = sorted(glob.glob(os.path.join(root, "tools", "**", "test_*.py"), recursive=True))
    base = [os.path.basename(p) for p in paths]
    suites = []
    for path, b in zip(paths, base):
        name = b if base.count(b) == 1 else os.path.relpath(path, root).replace(os.sep, "/")
        suites.append(Suite(name, "pytest", py_cases(path)))
    return sorted(suites, key=lambda s: s.name)


def cbmc_suite(root):
    cases = []
    for path in sorted(glob.glob(os.path.join(root, "proofs", "cbmc", "*", "harness.c"))):
        name = os.path.basename(os.path.dirname(path))
        code, comments = c_split(read(path))
        cases.append(Case(name, name, comments, code))
    if not cases:
        return []
    return [Suite("proofs/cbmc", "CBMC", cases, no_t7=True)]


def target_suite(root):
    found = sorted(glob.glob(os.path.join(root, "tools", "**", "tt_groups.c"), recursive=True))
    if not found:
        return []
    groups_text = read(found[0])
    gen_path = os.path.join(os.path.dirname(found[0]), "tt_gen.c")
    gen_text = read(gen_path) if os.path.exists(gen_path) else ""
    funcs = c_functions(gen_text)
    gen_of = dict(re.findall(r'\{\s*"(\w+)"\s*,\s*\w+\s*,\s*\w+\s*,\s*(\w+)\s*\}', gen_text))
    replay_funcs = c_functions(groups_text)
    table_at = groups_text.find("tt_suites[")
    suite_comment = comment_above(groups_text, groups_text.rfind("\n", 0, table_at) + 1)
    names = []
    for m in re.finditer(r'\{\s*\{\s*"(\w+)"\s*,\s*(?:"(\w+)"|NULL)\s*\}\s*,\s*\w+\s*,'
                         r'\s*(\w+)\s*\}', groups_text):
        first = groups_text.rfind("\n", 0, m.start()) + 1
        line = groups_text[first:groups_text.find("\n", m.end())]
        replay = "\n".join(replay_funcs.get(m.group(3), ("", "")))
        names.extend((n, "\n".join((line, replay))) for n in (m.group(1), m.group(2)) if n)
    cases = []
    for name, replay_text in names:
        fn = gen_of.get(name)
        if fn is None:
            # the drive's groups: recorded in the closed-loop run of the generator
            fn = "record_drive"
            texts = [header_comment(gen_text)]
        else:
            texts = []
        above, body = funcs.get(fn, ("", ""))
        texts += [above, body]
        for callee in sorted(set(re.findall(r"\b(\w+)\s*\(", c_split(body)[0]))):
            if callee in funcs and callee != fn:
                texts += list(funcs[callee])
        code, comments = c_split("\n".join(texts + [replay_text]))
        # the comment above the suite table names the requirements of every group (1a)
        cases.append(Case(name, name, comments, code + "\n" + suite_comment))
    return [Suite("target_test", "target", cases, all_tags=("1n",))]


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
    code, comments = c_split(read(path))
    case = Case("cold start (seeded draw)", "robustness campaign", comments, code)
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


# ------------------------------------------------------------------ tags

def words_of(case, text):
    """The words of a text of the case: lower case, runs of MERGE joined, negated words
    and (for a CMocka or pytest case) the module prefix of the name left out."""
    low = " " + " ".join(WORD.findall(text.lower())) + " "
    for run, word in MERGE:
        low = low.replace(f" {run} ", f" {word} ")
    words = low.split()
    prefix = ["test"] + WORD.findall(case.module.lower())
    if case.module and words[:len(prefix)] == prefix:
        words = ["test"] + words[len(prefix):]
    out, k = [], 0
    while k < len(words):
        if words[k] in NEGATION:
            k += 1
            while k < len(words) and words[k] in ARTICLES:
                k += 1
            k += NEGATED
            continue
        out.append(words[k])
        k += 1
    return out


def word_match(words, patterns):
    """The first word that a pattern matches, or None."""
    for p in patterns:
        for w in words:
            if (p.endswith("*") and w.startswith(p[:-1])) or w == p:
                return w
    return None


def phrase_match(words, phrases):
    joined = " " + " ".join(words) + " "
    return next((p for p in phrases if f" {p} " in joined), None)


def tag(case, defined):
    """The methods of a case; case.why gets the word, phrase or literal that gave each."""
    head = words_of(case, case.head)
    words = head + ["."] + words_of(case, case.inner)
    why = {}
    ids = sorted({m.group(0) for m in REQ_ID.finditer(case.description + "\n" + case.code)})
    m = NAME_REQ.match(case.name)
    if ids:
        why["1a"] = ids[0]
    elif m and f"REQ-{m.group(1).upper()}-{m.group(2)}" in defined:
        why["1a"] = f"name: REQ-{m.group(1).upper()}-{m.group(2)}"
    for key in ("1b", "1c", "1d", "1l", "1n"):
        rule = RULES[key]
        code_re = rule.get("code_re")
        if code_re and case.kind in rule.get("code_kinds", ()):
            m_code = re.search(code_re, case.code)
        else:
            m_code = None
        desc_re = rule.get("desc_re")
        m_desc = re.search(desc_re, case.description) if desc_re else None
        hit = (word_match(words, rule.get("words", ()))
               or (m_desc.group(0) if m_desc else None)
               or word_match(head, rule.get("head", ()))
               or phrase_match(words, rule.get("phrases", ()))
               or phrase_match(head, rule.get("head_phrases", ()))
               or (f"code: {m_code.group(0).strip()}" if m_code else None))
        if hit:
            why[key] = hit
    case.why = why
    return set(why)


def figures(suites, defined):
    """suite name -> {column: number or None}, in the order of the suites."""
    out = {}
    for s in suites:
        row = {"cases": len(s.cases) * s.repeat}
        for c in s.cases:
            c.kind = s.kind
            c.tags = tag(c, defined) | s.all_tags
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
    lines += ["#### Rules", "",
              "| method | a case is tagged when its description (code for the literals) ... |",
              "|---|---|"]
    for key, head in COLUMNS[1:]:
        lines.append(f"| {head} | {RULES[key]['doc']} |")
    lines += ["| suite rules | every target_test group is T7 1n; the CBMC harnesses are formal "
              "verification (T7 1e), their T7 test columns are '-' |", ""]
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
    if a.list:
        for s in suites:
            for c in s.cases:
                tags = " ".join(f"{k}({c.why[k]})" if k in c.why else k for k in sorted(c.tags))
                print(f"{s.name}\t{c.name}\t{tags}")
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
              f"({sum(r['cases'] for _, r in figs.values())} cases in {len(figs)} suites)")
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
