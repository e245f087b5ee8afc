#!/usr/bin/env python3
"""Requirement traceability: the matrix and its gates.

Requirements are the '### REQ-<MOD>-NNN title' headings of specs/requirements/*.md.
Everything else is read from the sources, from the IDs they name (tags in comments, test
names, contract documentation) and from the committed proof results:

  contracts  the public functions of include/qfoc/*.h whose doxygen names the ID (a range
             'REQ-<MOD>-001 .. REQ-<MOD>-005' names every ID in it), with the named ACSL
             behaviours of their contract; a header that ties contract clauses to IDs, in
             the doxygen ('name, name (REQ-...)') or in an ACSL comment, gives those
             clauses (and only those behaviours) for the ID
  acsl       the predicates, logic functions, lemmas and axiomatic blocks of specs/*.acsl
             under a comment naming the ID (a '// ---- title (REQ-...) ----' line names
             every declaration up to the next such line)
  wp         the goals of those functions in proofs/wp/results.md (every row of the
             function), plus one goal per lemma named (each lemma is a goal of its own; an
             axiomatic block named as a whole brings its row); apart, as helpers, the rows
             of the static functions of src/<unit>.c the public functions call
  cbmc       proofs/cbmc/<harness>/harness.c naming the ID anywhere, with the harness's row
             of proofs/cbmc/results.md
  tests      CMocka tests (the functions registered with cmocka_unit_test*() in tests/*.c)
             and pytest tests (test_* in tools/*/tests/*.py and port_s32k/pil/tests/*.py)
             naming the ID in their body or in
             the comment block right above their definition (decorators skipped), or in
             their name (test_<mod>_NNN_...: REQ-<MOD>-NNN, when defined); the
             target-equivalence groups of tools/target_test/tt_groups.c (the IDs of the
             comment above the suite table, of the group's entry line and of its replay
             function) and the checking programs target_test.sh, tt_gen.c, tt_runner.c
             (their header); the rows of the bench report (tools/bench/count.py, row());
             the libFuzzer harnesses tests/fuzz/fuzz_*.c and their runner tests/fuzz/run.py
             (their header; fuzz_tests()); the fault-injection campaign sim/apps/faults.c
             (its header; campaign_tests(); its result is the JUnit case faults.c)
  scenarios  the scenarios of sim/scenario.c (the IDs each one records), and those a
             test of tests/test_scenarios.c runs while naming the ID
  named_in   the headers naming the ID anywhere: include/qfoc/*.h, the tuning tool's
             interface tools/tune/qfoc_tune.py and its identification import
             tools/tune/qfoc_ident.py, the calibration description's
             tools/a2l/qfoc_a2l.py, the evidence generator's
             tools/evidence/evidence.py, the architecture check tools/evidence/arch_check.py,
             the vector format tools/target_test/tt.h, the
             bench's tools/bench/*.h, the fuzz harnesses' tests/fuzz/fuzz.h and the
             processor-in-the-loop modules port_s32k/pil/{core,periph,twin,scenarios,defects}.py

Gates (exit status 1, every offender listed):
  (a) a requirement with no proof (a contract with WP goals, an ACSL lemma, or a CBMC
      harness) and no test;
  (b) a source naming an ID that no requirement defines;
  (c) a CMocka or pytest test, a target-equivalence group or checker, or a CBMC harness
      that names no requirement (a test's name does not count here: the ID must be
      written in its body or in the comment above it);
  also a requirement named by no header, and a requirement traced to a proof result
  that is not a success;
  (d) the attribute and clause lines of the requirements (tools/evidence/req_attrs.py,
      specs/requirements/README.md): a missing or invalid attribute line, a verification
      method claimed that the trace does not find, an ASIL other than the one
      specs/asr.toml assumes for the requirement's ASRs, a safety requirement without
      clauses, a clause, lemma, harness or test that does not exist or does not name the
      requirement, a clause that the WP report of make prove (build/wp/*.json) does not
      prove.
Warnings (no gate): a requirement's text names a test or harness (`test_...`,
"CBMC harness `name`") that does not name the requirement.

Writes build/trace/trace.json and build/trace/trace.md, and prints
'trace: N requirements, ...'.  Output is sorted and carries no time stamp: the same
sources give the same files.
"""
import ast
import glob
import json
import os
import re
import sys

import req_attrs

REQ = re.compile(r"\bREQ-([A-Z0-9]+)-(\d{3})\b")
RANGE = re.compile(r"\bREQ-([A-Z0-9]+)-(\d{3})\s*(?:\.\.|\u2026|--)\s*REQ-([A-Z0-9]+)-(\d{3})\b")
HEAD = re.compile(r"^###\s+(REQ-[A-Z0-9]+-\d{3})\s+(.*)$")
OUT = "build/trace"

# The processor-in-the-loop tests (port_s32k/pil/, specs/requirements/pil.md): pytest too,
# and the modules of port_s32k/pil/ whose docstrings name its requirements.
PIL_TESTS = "port_s32k/pil/tests/test_*.py"
PIL_INTERFACES = ("port_s32k/pil/core.py", "port_s32k/pil/periph.py", "port_s32k/pil/twin.py",
                  "port_s32k/pil/scenarios.py", "port_s32k/pil/defects.py")

# Checking programs of the target-equivalence test: each is one test, traced by its header.
TT_CHECKERS = ("tools/target_test/target_test.sh", "tools/target_test/tt_gen.c",
               "tools/target_test/tt_runner.c")
# The fuzz harnesses' runner, traced like a harness, and their shared header (an interface).
FUZZ_RUNNER = ("tests/fuzz/run.py",)
FUZZ_INTERFACE = "tests/fuzz/fuzz.h"
# The fault-injection campaign (make faults): one test, traced by its header.
CAMPAIGNS = ("sim/apps/faults.c",)
# Files read for gate (b) besides the ones traced (text files of these trees).
SCAN_TREES = ("include", "src", "specs", "tests", "tools", "proofs", "sim", "port_s32k",
              "misra", "tables", "mk")
SCAN_EXT = (".c", ".h", ".md", ".py", ".sh", ".acsl", ".mk", ".toml", ".json", ".ld", ".txt")


def read(path):
    with open(path, encoding="utf-8") as f:
        return f.read()


def ids(text, defined=None):
    """The IDs a text names; a range 'REQ-<MOD>-001 .. REQ-<MOD>-004' names the IDs between
    (those defined, when the set of defined IDs is given)."""
    found = {m.group(0) for m in REQ.finditer(text)}
    for m in RANGE.finditer(text):
        if m.group(1) != m.group(3):
            continue
        for n in range(int(m.group(2)), int(m.group(4)) + 1):
            rid = f"REQ-{m.group(1)}-{n:03d}"
            if defined is None or rid in defined:
                found.add(rid)
    return found


def line_of(text, pos):
    return text.count("\n", 0, pos) + 1


# ------------------------------------------------------------------ C text helpers

def c_skip(text, i):
    """If a comment, string or character literal starts at i, the index after it."""
    if text.startswith("/*", i):
        j = text.find("*/", i + 2)
        return len(text) if j < 0 else j + 2
    if text.startswith("//", i):
        j = text.find("\n", i)
        return len(text) if j < 0 else j
    if text[i] in "\"'":
        q = text[i]
        j = i + 1
        while j < len(text) and text[j] != q:
            j += 2 if text[j] == "\\" else 1
        return j + 1
    return i


def c_block_end(text, open_idx):
    """Index after the brace matching text[open_idx] == '{'."""
    depth = 0
    i = open_idx
    while i < len(text):
        j = c_skip(text, i)
        if j != i:
            i = j
            continue
        if text[i] == "{":
            depth += 1
        elif text[i] == "}":
            depth -= 1
            if depth == 0:
                return i + 1
        i += 1
    return len(text)


def comment_above(lines, first, python=False):
    """The comment block ending on the line right above lines[first] (0-based), without
    blank lines in between: stacked '/* */' blocks and '//' lines in C, '#' lines in
    Python."""
    out = []
    k = first - 1
    while k >= 0:
        s = lines[k].strip()
        if python:
            if not s.startswith("#"):
                break
            out.insert(0, lines[k])
            k -= 1
        elif s.endswith("*/"):
            j = k
            while j >= 0 and "/*" not in lines[j]:
                j -= 1
            if j < 0:
                break
            out[:0] = lines[j:k + 1]
            k = j - 1
        elif s.startswith("//"):
            out.insert(0, lines[k])
            k -= 1
        else:
            break
    return "\n".join(out)


def c_functions(text):
    """Function definitions of a C file: name -> (first line 0-based, body text)."""
    funcs = {}
    pat = re.compile(r"^[ \t]*(?:static[ \t]+)?(?:inline[ \t]+)?[A-Za-z_][\w \t\*]*?\b([A-Za-z_]\w*)"
                     r"[ \t]*\(((?:[^;{}()/]|\([^;{}()]*\))*)\)[ \t\n]*\{", re.M)
    for m in pat.finditer(text):
        name = m.group(1)
        if name in ("if", "for", "while", "switch", "return", "sizeof"):
            continue
        open_idx = m.end() - 1
        end = c_block_end(text, open_idx)
        funcs.setdefault(name, (line_of(text, m.start()) - 1, text[m.start():end]))
    return funcs


# ------------------------------------------------------------------ requirements

def load_requirements():
    """ID -> dict(title, file, text): the text is the requirement's section."""
    reqs = {}
    for p in sorted(glob.glob("specs/requirements/*.md")):
        cur = None
        for line in read(p).splitlines():
            m = HEAD.match(line.strip())
            if m:
                cur = m.group(1)
                reqs[cur] = {"title": m.group(2).strip(), "file": p, "text": ""}
            elif line.startswith("#"):
                cur = None
            elif cur:
                reqs[cur]["text"] += line + "\n"
    return reqs


def text_claims(reqs, test_ids, harness_ids):
    """Warnings (no gate): a requirement's text names a test (`test_...`) or a CBMC harness
    as verifying it, and that test or harness does not name the requirement (or does not
    exist).  test_ids: name -> set of IDs; harness_ids: harness -> set of IDs."""
    out = []
    for rid, r in sorted(reqs.items()):
        text = re.sub(r"\s+", " ", r["text"])
        for name in sorted(set(re.findall(r"`(test_\w+)`", text))):
            if name not in test_ids:
                out.append(f"{rid}: its text names test {name}, which does not exist")
            elif rid not in test_ids[name]:
                out.append(f"{rid}: its text names test {name}, which does not name {rid}")
        named = set()
        for m in re.finditer(r"CBMC(?: harness(?:es)?)? ((?:`[\w/]+`(?:, | and )?)+)", text):
            named.update(n.split("/")[-1] for n in re.findall(r"`([\w/]+)`", m.group(1)))
        for h in sorted(named):
            if h not in harness_ids:
                out.append(f"{rid}: its text names CBMC harness {h}, which does not exist")
            elif rid not in harness_ids[h]:
                out.append(f"{rid}: its text names CBMC harness {h}, which does not name {rid}")
    return out


# ------------------------------------------------------------------ contracts (headers)

ACSL_NAMED = re.compile(r"\b(behavior|ensures|requires|assigns|assumes)\s+([A-Za-z_]\w*)\s*:")
CLAUSE_MAP = re.compile(r"([A-Za-z_][\w, \t\n*]*?)\s*\(((?:REQ-[A-Z0-9]+-\d{3}[,\s]*(?:and\s+)?)+)\)")


def contract_names(acsl):
    """Named behaviours and named clauses (labels of ensures, requires, assigns) of an
    ACSL contract, in their order."""
    behaviors, clauses = [], []
    for m in ACSL_NAMED.finditer(acsl):
        (behaviors if m.group(1) == "behavior" else clauses).append(m.group(2))
    return behaviors, clauses


def acsl_tagged(acsl, defined):
    """IDs named inside an ACSL contract, each with the behaviour or clause it sits in
    (a comment line applies to the clause that follows it)."""
    tagged = {}
    lines = acsl.splitlines()
    pending = set()
    current = None
    for ln in lines:
        s = ln.strip()
        m = ACSL_NAMED.search(s)
        found = ids(s, defined)
        if s.startswith("//"):
            pending |= found
            continue
        if m:
            current = m.group(2)
            for rid in pending | found:
                tagged.setdefault(rid, set()).add(current)
            pending = set()
        elif found and current:
            for rid in found:
                tagged.setdefault(rid, set()).add(current)
    return tagged


def doxygen_clause_map(dox, names, defined):
    """'name, name (REQ-...)' in a doxygen block, for names of the contract."""
    out = {}
    flat = re.sub(r"\n\s*\*\s?", " ", dox)
    for m in CLAUSE_MAP.finditer(flat):
        words = [w.strip(" *") for w in re.split(r"[,;]|\band\b", m.group(1))]
        picked = [w.split()[-1] for w in words if w.split() and w.split()[-1] in names]
        if not picked:
            continue
        for rid in ids(m.group(2), defined):
            out.setdefault(rid, set()).update(picked)
    return out


def load_contracts(defined):
    """Public functions of include/qfoc/*.h: name -> dict(header, ids, behaviors,
    clauses, tagged, acsl)."""
    funcs = {}
    decl = re.compile(r"\s*(/\*@.*?\*/)?\s*([^;{#/]*?\b([A-Za-z_]\w*)\s*\([^;{]*?\))\s*[;{]", re.S)
    for path in sorted(glob.glob("include/qfoc/*.h")):
        text = read(path)
        for m in re.finditer(r"/\*\*(?!\*)(.*?)\*/", text, re.S):
            dox = m.group(1)
            if "@file" in dox:
                continue
            d = decl.match(text, m.end())
            if not d or "typedef" in d.group(2) or "struct" in d.group(2).split("(")[0]:
                continue
            name = d.group(3)
            acsl = d.group(1) or ""
            behaviors, clauses = contract_names(acsl)
            tagged = acsl_tagged(acsl, defined)
            for rid, names in doxygen_clause_map(dox, set(behaviors + clauses), defined).items():
                tagged.setdefault(rid, set()).update(names)
            funcs[name] = {
                "header": path, "ids": ids(dox, defined) | ids(acsl, defined),
                "behaviors": behaviors, "clauses": clauses, "tagged": tagged,
                "acsl": bool(acsl),
            }
    return funcs


def contract_entry(name, c, rid):
    tagged = c["tagged"]
    if tagged:
        mine = tagged.get(rid, set())
        behaviors = [b for b in c["behaviors"] if b in mine]
        clauses = [b for b in c["clauses"] if b in mine]
    else:
        behaviors = list(c["behaviors"])
        clauses = []
    return {"function": name, "header": c["header"], "behaviors": behaviors,
            "clauses": clauses, "acsl": c["acsl"]}


# ------------------------------------------------------------------ specs/*.acsl

ACSL_DECL = re.compile(r"^\s*(predicate|logic\s+[\w<>\s\*]+?|lemma|axiomatic|inductive|type)\s+"
                       r"([A-Za-z_]\w*)")


def load_acsl(defined):
    """Declarations of specs/*.acsl under a comment naming IDs:
    list of dict(file, kind, name, ids, axiomatic)."""
    decls = []
    for path in sorted(glob.glob("specs/*.acsl")):
        lines = read(path).splitlines()
        section = set()
        block = set()
        axiomatic = None
        depth = 0
        for ln in lines:
            s = ln.strip()
            if s.startswith("//"):
                if re.match(r"//\s*-{3,}", s):
                    section = ids(s, defined)
                    block = set()
                else:
                    block |= ids(s, defined)
                continue
            m = ACSL_DECL.match(ln)
            if m:
                kind = m.group(1).split()[0]
                names = block | section
                decls.append({"file": path, "kind": kind, "name": m.group(2), "ids": names,
                              "axiomatic": axiomatic if kind != "axiomatic" else None})
                if kind == "axiomatic":
                    axiomatic = m.group(2)
                    depth = 0
            if axiomatic is not None:
                depth += ln.count("{") - ln.count("}")
                if depth <= 0 and "}" in ln:
                    axiomatic = None
            if s:
                block = set()
    return decls


# ------------------------------------------------------------------ committed proof results

def md_rows(path, ncols):
    rows = []
    if not os.path.exists(path):
        return rows
    for line in read(path).splitlines():
        if not line.startswith("|") or line.startswith("|---"):
            continue
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) == ncols and cells[0] not in ("unit", "harness"):
            rows.append(cells)
    return rows


def load_wp():
    """proofs/wp/results.md: function -> list of dict(unit, function, goals, proved, provers,
    time_ms)."""
    out = {}
    for unit, fn, goals, proved, provers, ms in md_rows("proofs/wp/results.md", 6):
        out.setdefault(fn, []).append({"unit": unit, "function": fn, "goals": int(goals),
                                       "proved": int(proved), "provers": provers,
                                       "time_ms": int(ms)})
    return out


def load_callees(contracts):
    """(unit, public function) -> the static functions of src/<unit>.c it calls, directly
    or through each other (their contracts are what its proof uses; their goals are
    proved in the same unit)."""
    out = {}
    for path in sorted(glob.glob("src/*.c")):
        unit = os.path.basename(path)[:-2]
        funcs = c_functions(read(path))
        calls = {f: set(re.findall(r"\b([A-Za-z_]\w*)\s*\(", body.split("{", 1)[1])) & set(funcs)
                 for f, (_l, body) in funcs.items()}
        for pub in funcs:
            if pub not in contracts:
                continue
            seen, stack = set(), [pub]
            while stack:
                for g in calls.get(stack.pop(), ()):
                    if g not in seen and g not in contracts:
                        seen.add(g)
                        stack.append(g)
            out[(unit, pub)] = seen
    return out


def load_cbmc_results():
    """proofs/cbmc/results.md: harness -> dict(result, properties, failed, unwind)."""
    out = {}
    for h, result, proved, failed, unwind, _t in md_rows("proofs/cbmc/results.md", 6):
        out[h] = {"result": result, "properties": int(proved) + int(failed),
                  "failed": int(failed), "unwind": int(unwind)}
    return out


# ------------------------------------------------------------------ tests

NAME_TAG = re.compile(r"^test_(?:req_)?([a-z0-9]+)((?:_(?:req)?\d{3})+)(?:_|$)")


def name_ids(name, defined):
    """IDs a test's name encodes: test_<mod>_NNN[_NNN...]_..., e.g. test_sm_002_x ->
    REQ-SM-002 (only IDs that are defined)."""
    m = NAME_TAG.match(name)
    if not m:
        return set()
    found = {f"REQ-{m.group(1).upper()}-{n}" for n in re.findall(r"\d{3}", m.group(2))}
    return found & defined


def cmocka_tests(defined):
    """(file, name, ids) of every registered CMocka test, and registrations without a
    definition."""
    tests, missing = [], []
    for path in sorted(glob.glob("tests/*.c")):
        text = read(path)
        lines = text.splitlines()
        funcs = c_functions(text)
        names = []
        for m in re.finditer(r"\bcmocka_unit_test\w*\s*\(\s*([A-Za-z_]\w*)", text):
            if m.group(1) not in names:
                names.append(m.group(1))
        for name in names:
            if name not in funcs:
                missing.append((path, name))
                continue
            first, body = funcs[name]
            tests.append((path, name, ids(comment_above(lines, first) + "\n" + body, defined)))
    return tests, missing


def with_names(tests, defined):
    """Add the IDs the test names encode (gate (c) looks at the tags only)."""
    return [(f, n, i | name_ids(n, defined), i) for f, n, i in tests]


def pytest_tests(defined):
    tests = []
    for path in sorted(glob.glob("tools/*/tests/*.py") + glob.glob(PIL_TESTS)):
        text = read(path)
        lines = text.splitlines()
        tree = ast.parse(text, path)
        for node in ast.walk(tree):
            if (isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef))
                    and node.name.startswith("test_")):
                first = min([node.lineno] + [d.lineno for d in node.decorator_list]) - 1
                head = "\n".join(lines[first:node.lineno - 1])  # decorators and comments among them
                body = "\n".join(lines[node.lineno - 1:node.end_lineno])
                tests.append((path, node.name, ids(comment_above(lines, first, python=True) + "\n"
                                                   + head + "\n" + body, defined)))
    return sorted(tests)


def header_comment(text):
    """The leading comment of a file (C block or '#' lines)."""
    m = re.match(r"\s*/\*.*?\*/", text, re.S)
    if m:
        return m.group(0)
    out = []
    for ln in text.splitlines():
        if ln.startswith("#"):
            out.append(ln)
        elif out:
            break
    return "\n".join(out)


def target_tests(defined):
    """Target-equivalence groups and checking programs: (file, name, ids)."""
    tests = []
    path = "tools/target_test/tt_groups.c"
    if os.path.exists(path):
        text = read(path)
        lines = text.splitlines()
        funcs = c_functions(text)
        t = re.search(r"^const\s+tt_suite_t\s+tt_suites\s*\[[^\]]*\]\s*=\s*\{", text, re.M)
        if t:
            common = ids(comment_above(lines, line_of(text, t.start()) - 1), defined)
            body = text[t.end() - 1:c_block_end(text, t.end() - 1)]
            for ln in body.splitlines():
                e = re.search(r"\{\s*\{\s*(\"[^\"]*\"|NULL)\s*,\s*(\"[^\"]*\"|NULL)\s*\}\s*,"
                              r"\s*\w+\s*,\s*([A-Za-z_]\w*)\s*\}", ln)
                if not e:
                    continue
                fn = e.group(3)
                own = set()
                if fn in funcs:
                    first, fbody = funcs[fn]
                    own = ids(comment_above(lines, first) + "\n" + fbody, defined)
                for g in (e.group(1), e.group(2)):
                    if g != "NULL":
                        tests.append((path, "group " + g.strip('"'), common | own | ids(ln, defined)))
    for path in TT_CHECKERS:
        if os.path.exists(path):
            tests.append((path, os.path.basename(path), ids(header_comment(read(path)), defined)))
    return tests


def header_tests(paths, defined):
    """Programs that are one test each, traced by the IDs of their header comment;
    (file, name, ids)."""
    return [(p, os.path.basename(p), ids(header_comment(read(p)), defined)) for p in paths]


def fuzz_tests(defined):
    """The libFuzzer harnesses (tests/fuzz/fuzz_*.c) and their runner (tests/fuzz/run.py).
    FUZZ_INTERFACE, the header they share, names their requirements."""
    paths = sorted(glob.glob("tests/fuzz/fuzz_*.c")) + [p for p in FUZZ_RUNNER if os.path.exists(p)]
    return header_tests(paths, defined)


def campaign_tests(defined):
    """The fault-injection campaign (CAMPAIGNS); sim/sim.h names its requirements."""
    return header_tests([p for p in CAMPAIGNS if os.path.exists(p)], defined)


def bench_rows(defined):
    """Rows of the bench report: the rows of build/bench/bench.json (item, requirement)
    when the bench has run, else the row(<REQ id or a choice of two>, <label>, ...) calls
    of its source."""
    rows = []
    try:
        with open("build/bench/bench.json", encoding="utf-8") as f:
            table = json.load(f).get("table") or []
        for r in table:
            found = ids(str(r.get("requirement", "")), defined)
            if found:
                rows.append(("build/bench/bench.json", "row " + re.sub(r"\s+", " ", str(r["item"])),
                             found))
    except (OSError, ValueError, KeyError, AttributeError):
        rows = []
    if rows:
        return rows
    tests = []
    for path in sorted(glob.glob("tools/bench/*.py")):
        text = read(path)
        for node in ast.walk(ast.parse(text, path)):
            if (isinstance(node, ast.Call) and isinstance(node.func, ast.Name)
                    and node.func.id == "row" and len(node.args) >= 2):
                found = ids(ast.get_source_segment(text, node.args[0]) or "", defined)
                if not found:
                    continue
                label = label_text(node.args[1])
                if not isinstance(node.args[1], (ast.Constant, ast.JoinedStr, ast.BinOp)):
                    label += " (a row per item)"
                tests.append((node.lineno, path, "row " + re.sub(r"\s+", " ", label), found))
    return [t[1:] for t in sorted(tests)]


def label_text(node):
    """A readable form of a label expression: the string as written, [name] for a value
    formatted into it (the key or name it is read from: never the Python source of a
    template), the first branch of a conditional part."""
    if isinstance(node, ast.Constant):
        return str(node.value)
    if isinstance(node, ast.JoinedStr):
        return "".join(str(v.value) if isinstance(v, ast.Constant)
                       else "[" + placeholder(v.value) + "]" for v in node.values)
    if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Add):
        return label_text(node.left) + label_text(node.right)
    if isinstance(node, ast.IfExp):
        return label_text(node.body)
    return "[" + placeholder(node) + "]"


def placeholder(expr):
    """The name of what a value formatted into a label stands for: d['title'] -> title."""
    if isinstance(expr, ast.Subscript) and isinstance(expr.slice, ast.Constant):
        return str(expr.slice.value)
    if isinstance(expr, ast.Attribute):
        return expr.attr
    if isinstance(expr, ast.Name):
        return expr.id
    if isinstance(expr, ast.Call):
        return placeholder(expr.func)
    return "value"


def harnesses(defined):
    out = []
    for path in sorted(glob.glob("proofs/cbmc/*/harness.c")):
        out.append((os.path.basename(os.path.dirname(path)), path, ids(read(path), defined)))
    return out


# ------------------------------------------------------------------ scenarios

def scenarios(defined, cm_tests):
    """Scenario name -> dict(file, ids, tests); and test (file, name) -> scenario names."""
    path = "sim/scenario.c"
    out = {}
    if not os.path.exists(path):
        return out
    text = read(path)
    funcs = c_functions(text)
    names = []
    m = re.search(r"scn_names\[\]\s*=\s*\{(.*?)\};", text, re.S)
    if m:
        names = re.findall(r"\"([^\"]+)\"", m.group(1))
    run = funcs.get("scn_run", (0, ""))[1]
    for name in names:
        d = re.search(r"strcmp\(\s*\w+\s*,\s*\"" + re.escape(name) + r"\"\s*\)\s*==\s*0\s*\)\s*\{"
                      r"\s*\w+\s*=\s*([A-Za-z_]\w*)\s*\(([^;]*)\)\s*;", run)
        found = set()
        if d and d.group(1) in funcs:
            body = funcs[d.group(1)][1]
            kind = re.search(r"\b(SCN_[A-Z0-9_]+)\s*$", d.group(2).strip())
            if kind:
                cases = re.split(r"\n\s*(?=case\s+\w+\s*:|default\s*:)", body)
                mine = [c for c in cases if re.match(r"\s*case\s+" + kind.group(1) + r"\s*:", c)]
                if not mine:
                    mine = [c for c in cases if re.match(r"\s*default\s*:", c)]
                body = "\n".join(mine)
            found = ids(" ".join(re.findall(r"\"([^\"]*)\"", body)), defined)
        out[name] = {"file": path, "ids": found, "tests": [], "title": scenario_title(body if d else "")}
    # entry points other than scn_run that record requirements (the robustness start)
    for fn, (_first, body) in sorted(funcs.items()):
        if fn.startswith("scn_run_") and "requirements" in body:
            out[fn] = {"file": path, "ids": ids(" ".join(re.findall(r"\"([^\"]*)\"", body)), defined),
                       "tests": [], "title": scenario_title(body)}
    # the scenario tests: the scenarios a test runs (a scenario name as a string literal,
    # or a call of the entry point)
    for tpath, name, tids in cm_tests:
        if os.path.basename(tpath) != "test_scenarios.c":
            continue
        body = c_functions(read(tpath)).get(name, (0, ""))[1]
        runs = (set(re.findall(r"\"([a-z_0-9]+)\"", body))
                | set(re.findall(r"\b(scn_run_\w+)\s*\(", body)))
        for key in sorted(runs):
            if key in out:
                out[key]["tests"].append({"file": tpath, "name": name, "ids": sorted(tids)})
    return out


def scenario_title(body):
    """The title a scenario script records: scn_describe(r, "title", ...) or the format of
    snprintf(...->title, ..., "title", ...)."""
    m = re.search(r"scn_describe\(\s*[^,]+,\s*\"([^\"]*)\"", body)
    if not m:
        m = re.search(r"snprintf\([^,]*->title\s*,[^,]*,\s*\"([^\"]*)\"", body)
    return m.group(1) if m else ""


# ------------------------------------------------------------------ gate (b)

def all_sources():
    files = set()
    for tree in SCAN_TREES:
        for root, dirs, fnames in os.walk(tree):
            dirs[:] = [d for d in dirs if not d.startswith(".") and d != "__pycache__"]
            for f in fnames:
                if f.endswith(SCAN_EXT):
                    files.add(os.path.join(root, f))
    files.update(p for p in glob.glob("*.md"))
    files.update(p for p in ("Makefile",) if os.path.exists(p))
    return sorted(files)


# ------------------------------------------------------------------ main

def esc(text):
    return str(text).replace("|", "\\|")


def cell(items):
    return "<br>".join(esc(x) for x in items) if items else "-"


def main() -> int:
    reqs = load_requirements()
    defined = set(reqs)
    failures = []

    contracts = load_contracts(defined)
    acsl_decls = load_acsl(defined)
    wp = load_wp()
    cbmc_res = load_cbmc_results()
    callees = load_callees(contracts)
    cm, cm_missing = cmocka_tests(defined)
    py = pytest_tests(defined)
    tt = target_tests(defined)
    bench = bench_rows(defined)
    hs = harnesses(defined)
    scn = scenarios(defined, cm)

    interfaces = (sorted(glob.glob("include/qfoc/*.h"))
                  + ["tools/tune/qfoc_tune.py", "tools/tune/qfoc_ident.py", "tools/a2l/qfoc_a2l.py",
                     "tools/evidence/evidence.py",
                     "tools/evidence/arch_check.py", "tools/target_test/tt.h",
                     "sim/sim.h"]
                  + sorted(glob.glob("tools/bench/*.h")) + [FUZZ_INTERFACE] + list(PIL_INTERFACES))
    named_in = {}
    for p in interfaces:
        if os.path.exists(p):
            for rid in ids(read(p), defined):
                named_in.setdefault(rid, set()).add(p)

    all_tests = ([("cmocka",) + t for t in with_names(cm, defined)]
                 + [("pytest",) + t for t in with_names(py, defined)]
                 + [("target", f, n, i, i) for f, n, i in tt]
                 + [("bench", f, n, i, i) for f, n, i in bench]
                 + [("fuzz", f, n, i, i) for f, n, i in fuzz_tests(defined)]
                 + [("campaign", f, n, i, i) for f, n, i in campaign_tests(defined)])

    lemma_rows = {}
    for fn, rows in wp.items():
        if fn == "lemmas" or fn.startswith("lemmas "):
            lemma_rows[fn] = rows

    matrix = []
    for rid in sorted(reqs):
        r = reqs[rid]
        cons = [contract_entry(n, c, rid) for n, c in sorted(contracts.items()) if rid in c["ids"]]
        decls = [d for d in acsl_decls if rid in d["ids"]]
        wp_funcs = []
        for c in cons:
            for row in wp.get(c["function"], []):
                wp_funcs.append(dict(row))
        lemmas = [d for d in decls if d["kind"] == "lemma"]
        axioms = {d["name"] for d in decls if d["kind"] == "axiomatic"}
        for ax in sorted(axioms):
            for row in lemma_rows.get("lemmas " + ax, []):
                wp_funcs.append(dict(row))
        for lem in lemmas:
            if lem["axiomatic"] in axioms:
                continue
            key = "lemmas " + lem["axiomatic"] if lem["axiomatic"] else "lemmas"
            for row in lemma_rows.get(key, []):
                ok = row["proved"] == row["goals"]
                wp_funcs.append({"unit": row["unit"], "function": "lemma " + lem["name"],
                                 "goals": 1, "proved": 1 if ok else 0, "provers": row["provers"],
                                 "time_ms": None})
        goals = sum(w["goals"] for w in wp_funcs)
        proved = sum(w["proved"] for w in wp_funcs)
        helpers = {}
        for c in cons:
            for (unit, pub), callee in callees.items():
                if pub != c["function"]:
                    continue
                for g in sorted(callee):
                    for row in wp.get(g, []):
                        if row["unit"] == unit:
                            h = helpers.setdefault((unit, g), dict(row, via=[]))
                            h["via"].append(pub)
        helper_rows = [helpers[k] for k in sorted(helpers)]
        cb = []
        for h, path, hids in hs:
            if rid in hids:
                res = cbmc_res.get(h)
                cb.append({"harness": h, "file": path,
                           "properties": res["properties"] if res else None,
                           "failed": res["failed"] if res else None,
                           "result": res["result"] if res else "no result",
                           "unwind": res["unwind"] if res else None})
        tests = [{"kind": k, "file": f, "name": n} for k, f, n, i, _t in all_tests if rid in i]
        sc = []
        for name, s in sorted(scn.items()):
            via = [t["name"] for t in s["tests"] if rid in t["ids"]]
            if rid in s["ids"] or via:
                sc.append({"name": name, "title": s["title"], "file": s["file"],
                           "tests": sorted({t["name"] for t in s["tests"]}
                                           if rid in s["ids"] else via)})
        proof = goals > 0 or any(c["result"] == "PASS" for c in cb)
        bad = [f"WP {w['function']} ({w['proved']}/{w['goals']})" for w in wp_funcs + helper_rows
               if w["proved"] != w["goals"]]
        bad += [f"CBMC {c['harness']} ({c['result']})" for c in cb if c["result"] != "PASS"]
        verified = (proof or bool(tests)) and not bad
        entry = {
            "id": rid, "title": r["title"], "file": r["file"],
            "named_in": sorted(named_in.get(rid, ())),
            "contracts": cons,
            "acsl": [{"file": d["file"], "kind": d["kind"], "name": d["name"]} for d in decls],
            "wp": {"functions": wp_funcs, "goals": goals, "proved": proved,
                   "helpers": helper_rows,
                   "helper_goals": sum(h["goals"] for h in helper_rows),
                   "helper_proved": sum(h["proved"] for h in helper_rows)},
            "cbmc": cb, "tests": tests, "scenarios": sc,
            "proof": proof, "verified": verified,
        }
        matrix.append(entry)
        if not proof and not tests:
            failures.append(f"{rid} ({r['file']}) has no proof (contract with WP goals, lemma, "
                            f"CBMC harness) and no test")
        if not entry["named_in"]:
            failures.append(f"{rid} ({r['file']}) is named by no public header")
        for b in bad:
            failures.append(f"{rid} ({r['file']}) is traced to a proof that does not hold: {b}")

    failures += attribute_gate(matrix, callees, hs, all_tests, tt, cbmc_res, acsl_decls)

    # (b) IDs named anywhere that no requirement defines
    undefined = {}
    for p in all_sources():
        try:
            text = read(p)
        except (UnicodeDecodeError, OSError):
            continue
        for rid in {m.group(0) for m in REQ.finditer(text)} - defined:
            undefined.setdefault(rid, set()).add(p)
    for rid in sorted(undefined):
        failures.append(f"{rid} named in {', '.join(sorted(undefined[rid]))} "
                        f"is not a defined requirement")

    # (c) every test and every harness names a requirement
    for path, name in cm_missing:
        failures.append(f"{path}: registered test {name} has no definition in the file")
    for k, f, n, _i, tagged in all_tests:
        if not tagged:
            failures.append(f"{f}: {k} test {n} names no requirement (in its body or the "
                            f"comment right above it)")
    for h, path, hids in hs:
        if not hids:
            failures.append(f"{path}: CBMC harness {h} names no requirement")
    for h, path, _ in hs:
        if h not in cbmc_res:
            failures.append(f"{path}: CBMC harness {h} has no row in proofs/cbmc/results.md")

    test_ids = {}
    for _k, _f, nm, i, _tg in all_tests:
        test_ids.setdefault(nm, set()).update(i)
    warnings = text_claims(reqs, test_ids, {h: i for h, _p, i in hs})

    n = len(matrix)
    n_unit = len(cm) + len(py)
    n_unit_tagged = sum(1 for k, f, nm, i, tg in all_tests if tg and k in ("cmocka", "pytest"))
    totals = {
        "requirements": n,
        "traced": sum(1 for e in matrix if e["proof"] or e["tests"]),
        "verified": sum(1 for e in matrix if e["verified"]),
        "with_tests": sum(1 for e in matrix if e["tests"]),
        "with_cbmc": sum(1 for e in matrix if e["cbmc"]),
        "with_contracts": sum(1 for e in matrix if e["contracts"]),
        "with_wp": sum(1 for e in matrix if e["wp"]["goals"]),
        "with_scenarios": sum(1 for e in matrix if e["scenarios"]),
        "named_in_headers": sum(1 for e in matrix if e["named_in"]),
        "cmocka_tests": len(cm), "pytest_tests": len(py),
        "unit_tests": n_unit, "unit_tests_naming_a_requirement": n_unit_tagged,
        "target_tests": len(tt), "bench_rows": len(bench),
        "harnesses": len(hs), "harnesses_naming_a_requirement": sum(1 for h in hs if h[2]),
        "gate_failures": len(failures),
        "warnings": len(warnings),
    }
    # goals of the distinct rows (a function traced by several requirements counts once;
    # a lemma is one goal of its section's row)
    seen = {}
    for e in matrix:
        for w in e["wp"]["functions"]:
            seen[(w["unit"], w["function"])] = w["goals"]
    totals["wp_goals_attributed"] = sum(seen.values())
    for e in matrix:
        for w in e["wp"]["helpers"]:
            seen[(w["unit"], w["function"])] = w["goals"]
    totals["wp_goals_attributed_with_helpers"] = sum(seen.values())
    named_ax = {d["name"] for d in acsl_decls if d["kind"] == "axiomatic" and d["ids"]}
    unattributed = sorted(f"{r['unit']} {fn} ({r['goals']} goals)" for fn, rows in wp.items()
                          for r in rows if (r["unit"], r["function"]) not in seen
                          and not (fn == "lemmas" or fn.startswith("lemmas ")))
    unattributed += [f"lemma {d['name']} ({d['file']})" for d in acsl_decls
                     if d["kind"] == "lemma" and not d["ids"] and d["axiomatic"] not in named_ax]
    totals["wp_goals_total"] = sum(r["goals"] for rows in wp.values() for r in rows)

    tests_index = [{"kind": k, "file": f, "name": nm, "requirements": sorted(i),
                    "tagged": bool(tg)} for k, f, nm, i, tg in all_tests]
    harness_index = []
    for h, path, hids in hs:
        res = cbmc_res.get(h, {})
        harness_index.append({"harness": h, "file": path, "requirements": sorted(hids),
                              "properties": res.get("properties"),
                              "result": res.get("result", "no result"),
                              "unwind": res.get("unwind")})
    doc = {
        "generated_by": "tools/evidence/trace.py",
        "sources": {
            "requirements": "specs/requirements/*.md", "contracts": "include/qfoc/*.h",
            "acsl": "specs/*.acsl", "wp": "proofs/wp/results.md",
            "cbmc": "proofs/cbmc/*/harness.c, proofs/cbmc/results.md",
            "tests": "tests/*.c, tools/*/tests/*.py, tools/target_test/, tools/bench/*.py, tests/fuzz/, sim/apps/faults.c",
            "scenarios": "sim/scenario.c, tests/test_scenarios.c",
        },
        "totals": totals,
        "gate_failures": failures,
        "warnings": warnings,
        "wp_unattributed": unattributed,
        "requirements": matrix,
        "tests": tests_index,
        "harnesses": harness_index,
    }
    doc["attributes"] = req_attrs.attribute_totals(matrix)
    os.makedirs(OUT, exist_ok=True)
    with open(os.path.join(OUT, "trace.json"), "w", encoding="utf-8") as f:
        json.dump(doc, f, indent=1, sort_keys=False)
        f.write("\n")
    write_md(os.path.join(OUT, "trace.md"), doc)

    for msg in failures:
        print(f"trace: {msg}")
    print(f"trace: {n} requirements, {totals['traced']} traced to a proof or a test, "
          f"{totals['with_tests']} with tests, {totals['with_cbmc']} with CBMC harnesses, "
          f"{totals['named_in_headers']} named in headers, "
          f"{totals['wp_goals_attributed']} of {totals['wp_goals_total']} WP goals attributed "
          f"({totals['wp_goals_attributed_with_helpers']} with the static functions they call); "
          f"{n_unit_tagged} of {n_unit} tests naming a requirement, "
          f"{totals['harnesses_naming_a_requirement']} of {len(hs)} harnesses naming a requirement")
    print_attributes(doc["attributes"])
    if warnings:
        print(f"trace: {len(warnings)} warning(s): requirement texts naming a test or harness that "
              f"does not name them (listed in {OUT}/trace.md)")
    if failures:
        print(f"trace: FAILED: {len(failures)} gate failure(s) listed above "
              f"(matrix in {OUT}/trace.md, {OUT}/trace.json)")
    return 0 if not failures and n > 0 else 1


def write_md(path, doc):
    t = doc["totals"]
    with open(path, "w", encoding="utf-8") as f:
        f.write("# Requirement traceability\n\n")
        f.write("Generated by `make trace` (`tools/evidence/trace.py`) from the requirement headings of "
                "`specs/requirements/*.md` and the IDs the sources name: contract documentation "
                "in `include/qfoc/*.h`, comments of `specs/*.acsl`, CBMC harnesses, test "
                "functions and their comments, scenario scripts; goal and property counts from "
                "the committed `proofs/wp/results.md` and `proofs/cbmc/results.md`.\n\n")
        f.write(f"- requirements: {t['requirements']}; traced to a proof or a test: {t['traced']}; "
                f"traced with no committed proof failing: {t['verified']} (whether they are verified, "
                f"from the results of a run: `make evidence`)\n")
        f.write(f"- with contracts: {t['with_contracts']}, with WP goals: {t['with_wp']} "
                f"({t['wp_goals_attributed']} of the {t['wp_goals_total']} goals of proofs/wp/results.md "
                f"attributed: the public functions' own goals and the lemmas named; "
                f"{t['wp_goals_attributed_with_helpers']} with the static functions they call), "
                f"with CBMC harnesses: "
                f"{t['with_cbmc']}, with tests: {t['with_tests']}, with scenarios: "
                f"{t['with_scenarios']}\n")
        f.write(f"- tests: {t['cmocka_tests']} CMocka, {t['pytest_tests']} pytest "
                f"({t['unit_tests_naming_a_requirement']} of {t['unit_tests']} name a requirement), "
                f"{t['target_tests']} target-equivalence groups and checks, {t['bench_rows']} bench rows; "
                f"harnesses: {t['harnesses_naming_a_requirement']} of {t['harnesses']} name a requirement\n")
        f.write(f"- gate failures: {t['gate_failures']}; warnings: {t['warnings']}\n\n")
        if doc["gate_failures"]:
            f.write("## Gate failures\n\n")
            for msg in doc["gate_failures"]:
                f.write(f"- {msg}\n")
            f.write("\n")
        if doc["warnings"]:
            f.write("## Requirement texts against the tags (warnings)\n\n"
                    "The \"Verified by\" text of a requirement names a test or harness that does "
                    "not name the requirement; the matrix follows the tags.\n\n")
            for msg in doc["warnings"]:
                f.write(f"- {msg}\n")
            f.write("\n")
        f.write("## Matrix\n\n")
        f.write("| requirement | title | contract (behaviours) | ACSL | WP goals | CBMC (properties, "
                "result, unwind) | tests | scenarios | traced |\n|---|---|---|---|---:|---|---|---|---|\n")
        for e in doc["requirements"]:
            cons = []
            for c in e["contracts"]:
                extra = c["behaviors"] + [f"ensures {x}" for x in c["clauses"]]
                cons.append(f"`{c['function']}`" + (f" ({', '.join(extra)})" if extra else "")
                            + ("" if c["acsl"] else " (no ACSL)"))
            acsl = [f"{d['kind']} {d['name']}" for d in e["acsl"]]
            wpc = f"{e['wp']['proved']}/{e['wp']['goals']}" if e["wp"]["goals"] else "-"
            cb = [f"{c['harness']} ({c['properties']}, {c['result']}, {c['unwind']})" for c in e["cbmc"]]
            tests = [x["name"] if x["name"] == os.path.basename(x["file"])
                     else f"{os.path.basename(x['file'])}: {x['name']}" for x in e["tests"]]
            sc = [s["name"] for s in e["scenarios"]]
            f.write(f"| {e['id']} | {esc(e['title'])} | {cell(cons)} | {cell(acsl)} | {wpc} | {cell(cb)} | "
                    f"{cell(tests)} | {cell(sc)} | {'yes' if e['verified'] else 'NO'} |\n")
        f.write("\n## Tests and the requirements they name\n\n| kind | file | test | requirements |\n"
                "|---|---|---|---|\n")
        for x in doc["tests"]:
            named = ", ".join(x["requirements"]) or "**none**"
            f.write(f"| {x['kind']} | {x['file']} | {esc(x['name'])} | {named} |\n")
        if doc["wp_unattributed"]:
            f.write("\n## WP goals no requirement names\n\n"
                    "Rows of `proofs/wp/results.md` (and lemmas of `specs/*.acsl`, one goal each) "
                    "that are neither a public function's, nor a static function a public "
                    "function calls, nor a lemma or axiomatic block a requirement names:\n\n")
            for x in doc["wp_unattributed"]:
                f.write(f"- {x}\n")
        f.write("\n## CBMC harnesses\n\n| harness | properties | result | unwind | requirements |\n"
                "|---|---:|---|---:|---|\n")
        for h in doc["harnesses"]:
            f.write(f"| {h['harness']} | {h['properties']} | {h['result']} | {h['unwind']} | "
                    f"{', '.join(h['requirements']) or '**none**'} |\n")
        write_md_attributes(f, doc)


# ------------------------------------------------------------------ attributes and clauses
# The attribute and clause lines of the requirements (tools/evidence/req_attrs.py,
# specs/requirements/README.md; REQ-EVD-015 .. REQ-EVD-017).

def attribute_gate(matrix, callees, hs, all_tests, tt, cbmc_res, acsl_decls):
    """Adds 'attributes' and 'clauses' to every matrix entry; the gate failures of the
    attribute lines, of the verification methods they claim and of the clauses named."""
    ctx = req_attrs.make_context(".", callees, hs, all_tests, tt, cbmc_res, acsl_decls)
    return req_attrs.apply_to_matrix(matrix, ctx, ".")


def print_attributes(t):
    asil = ", ".join(f"{a} {n}" for a, n in t["asil"].items() if n)
    kind = ", ".join(f"{k} {n}" for k, n in t["kind"].items() if n)
    print(f"trace: attributes: ASIL {asil}; kind {kind}; {t['clauses']} clauses named "
          f"({t['clauses_held']} held, {t['clauses_no_result']} without a result here)")


def write_md_attributes(f, doc):
    """The attributes of every requirement and the clause-level trace of those with clauses."""
    t = doc["attributes"]
    f.write("\n## Attributes\n\n"
            "From the `Attributes:` and `Clauses:` lines of `specs/requirements/*.md` "
            "(`specs/requirements/README.md`).  A clause's status comes from the WP report of "
            "`make prove` (`build/wp/*.json`), `proofs/cbmc/results.md`, `build/junit/`, "
            "`build/target_test/target.txt` or `build/bench/bench.json`; without that result it "
            "reads \"no ... result\", which is not a pass.\n\n")
    f.write("| ASIL | " + " | ".join(t["asil"]) + " |\n|---|" + "---:|" * len(t["asil"]) + "\n")
    f.write("| requirements | " + " | ".join(str(n) for n in t["asil"].values()) + " |\n\n")
    f.write("| kind | " + " | ".join(t["kind"]) + " |\n|---|" + "---:|" * len(t["kind"]) + "\n")
    f.write("| requirements | " + " | ".join(str(n) for n in t["kind"].values()) + " |\n\n")
    f.write("| requirement | ASIL | kind | verification | ASR | clauses (status) |\n"
            "|---|---|---|---|---|---|\n")
    for e in doc["requirements"]:
        a = e.get("attributes")
        if not a:
            f.write(f"| {e['id']} | **none** | | | | |\n")
            continue
        cl = [f"{c['ref']} ({c['status']})" for c in e.get("clauses", [])]
        f.write(f"| {e['id']} | {a['asil']} | {a['kind']} | {', '.join(a['verification'])} | "
                f"{', '.join(a['asr']) or '-'} | {cell(cl)} |\n")


if __name__ == "__main__":
    sys.exit(main())
