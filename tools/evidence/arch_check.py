#!/usr/bin/env python3
"""Keep the software architecture description (specs/architecture.md) true to the sources
(REQ-EVD-014).

Usage: python3 tools/evidence/arch_check.py [--root DIR]

The document is read for the names it gives in code (inline code spans and fenced blocks)
and for the requirement IDs it cites anywhere:

  functions     every `qfoc_...` name that is not a type (a name ending in `_t`) or a file
                (a name followed by an extension, as `qfoc_fast.h`), with or without `()`,
                and every other name written as a call, `name()`; each must be declared in
                include/qfoc/*.h or defined in src/*.c (or src/*.h); the port's own
                functions may also be declared or defined in port_s32k/*.c, *.h (a
                constant table declared there, as the trig tables, counts as present but
                not as a function in the summary);
  files         every `src/...`, `include/...`, `specs/...`, `port_s32k/...` or
                `proofs/...` path must exist (the module files `src/qfoc_*.c`,
                `include/qfoc/*.h` are the ones counted in the summary);
  requirements  every REQ-<MOD>-NNN must be a '### REQ-<MOD>-NNN' heading of
                specs/requirements/*.md.

And the document must keep up with the sources:

  - every public function declared in include/qfoc/*.h is named in the section whose
    level-2 heading contains "Interfaces";
  - every src/*.c module is named in the section whose level-2 heading contains
    "Static architecture", outside its dependency table;
  - the dependency table (the level-3 heading containing "Dependency table" inside that
    section) has one row per src/*.c, src/*.h and include/qfoc/*.h file: column 2 lists
    the file's #include names (the .acsl includes left out), column 3 (modules only) the
    other modules whose functions the file calls (`qfoc_x.c`, or `q15.h` for the inline
    primitives); both must equal what the sources give.

Exit 0 prints one line:
  arch-check: N functions, M modules, K requirements named, all present
Exit 1 lists each problem with where the document mentions the name, then a count.
"""
import argparse
import glob
import os
import re
import sys

DOC = "specs/architecture.md"

SPAN = re.compile(r"`([^`\n]+)`")
FENCE = re.compile(r"^\s*(```|~~~)")
QFOC_NAME = re.compile(r"(?<![A-Za-z0-9_])(qfoc_[a-z0-9_]*[a-z0-9])(?![A-Za-z0-9_])(?!\.[A-Za-z])")
CALL_NAME = re.compile(r"(?<![A-Za-z0-9_.>])([A-Za-z_][A-Za-z0-9_]*)\(\)")
PATH = re.compile(r"(?<![A-Za-z0-9_./-])((?:src|include|specs|port_s32k|proofs)/[A-Za-z0-9_./-]*[A-Za-z0-9_])")
MODULE_FILE = re.compile(r"^(?:src/qfoc_\w+\.[ch]|include/qfoc/\w+\.h)$")
REQ = re.compile(r"\bREQ-[A-Z0-9]+-\d+\b")
REQ_HEAD = re.compile(r"^###\s+(REQ-[A-Z0-9]+-\d+)\b", re.M)
# a declaration or definition at column 0: the first identifier followed by ( or [
DECL = re.compile(r"^[A-Za-z_][^;{}()=\n]*?\b([A-Za-z_]\w*)\s*([(\[])", re.M)
INCLUDE = re.compile(r'^\s*#\s*include\s*[<"]([^>"]+)[>"]', re.M)
CALL = re.compile(r"(?<![A-Za-z0-9_])(qfoc_\w+)\s*\(")
COMMENT_OR_STRING = re.compile(r'/\*.*?\*/|//[^\n]*|"(?:\\.|[^"\\\n])*"|\'(?:\\.|[^\'\\\n])*\'',
                               re.S)


def read(path):
    with open(path, encoding="utf-8") as f:
        return f.read()


def strip_c(text, strings=True):
    """C text without comments (ACSL included) and, when strings is true, with empty string
    and character literals."""
    def repl(m):
        s = m.group(0)
        if s.startswith(('"', "'")):
            if not strings:
                return s
            return '""' if s.startswith('"') else "' '"
        return " " + "\n" * s.count("\n") if s.startswith("/*") else " "
    return COMMENT_OR_STRING.sub(repl, text)


def rel(root, path):
    return os.path.relpath(path, root).replace(os.sep, "/")


def files(root, pattern):
    return sorted(rel(root, p) for p in glob.glob(os.path.join(root, pattern)))


# ------------------------------------------------------------------ the sources

class Sources:
    def __init__(self, root):
        self.root = root
        self.headers = files(root, "include/qfoc/*.h")
        self.src_c = files(root, "src/*.c")
        self.src_h = files(root, "src/*.h")
        self.port = files(root, "port_s32k/*.c") + files(root, "port_s32k/*.h")
        raw = {p: read(os.path.join(root, p))
               for p in self.headers + self.src_c + self.src_h + self.port}
        self.text = {p: strip_c(t) for p, t in raw.items()}
        self.with_strings = {p: strip_c(t, strings=False) for p, t in raw.items()}
        self.public = {}      # name -> header declaring it (functions of include/qfoc/*.h)
        self.library = set()  # names declared in include/qfoc/*.h or defined in src/
        self.port_names = set()
        self.objects = set()  # names declared with [ : constant tables, not functions
        for p in self.headers:
            for name, bracket in DECL.findall(self.text[p]):
                self.library.add(name)
                if bracket == "[":
                    self.objects.add(name)
                if bracket == "(" and name.startswith("qfoc_"):
                    self.public.setdefault(name, p)
        for p in self.src_c + self.src_h:
            self.library.update(name for name, _ in DECL.findall(self.text[p]))
        for p in self.port:
            self.port_names.update(name for name, _ in DECL.findall(self.text[p]))
        # who defines a function, for the "calls into" column
        self.definers = {}
        for p in self.src_c:
            for name, bracket in DECL.findall(self.text[p]):
                if bracket == "(":
                    self.definers.setdefault(name, set()).add(os.path.basename(p))
        q15 = "include/qfoc/q15.h"
        if q15 in self.text:
            for name, bracket in DECL.findall(self.text[q15]):
                if bracket == "(":
                    self.definers.setdefault(name, set()).add("q15.h")

    def exists(self, name):
        return name in self.library or name in self.port_names

    def includes(self, path):
        return {i for i in INCLUDE.findall(self.with_strings[path]) if not i.endswith(".acsl")}

    def calls(self, path):
        own = os.path.basename(path)
        out = set()
        for name in CALL.findall(self.text[path]):
            targets = self.definers.get(name, set())
            if own in targets:
                continue
            out.update(targets)
        return out


def requirement_ids(root):
    ids = set()
    for p in glob.glob(os.path.join(root, "specs/requirements/*.md")):
        ids.update(REQ_HEAD.findall(read(p)))
    return ids


# ------------------------------------------------------------------ the document

class Doc:
    def __init__(self, text):
        self.lines = text.splitlines()
        self.heading = []  # per line: (level-2 heading, level-3 heading)
        h2 = h3 = ""
        fenced = False
        self.code = []     # per line: list of code texts (spans, or the line when fenced)
        for ln in self.lines:
            if FENCE.match(ln):
                fenced = not fenced
                self.code.append([])
            elif fenced:
                self.code.append([ln])
            else:
                if ln.startswith("## "):
                    h2, h3 = ln[3:].strip(), ""
                elif ln.startswith("### "):
                    h3 = ln[4:].strip()
                self.code.append(SPAN.findall(ln))
            self.heading.append((h2, h3))

    def where(self, lines):
        nums = sorted(set(lines))
        shown = ", ".join(str(n) for n in nums[:8]) + (", ..." if len(nums) > 8 else "")
        return f"{DOC} line{'s' if len(nums) > 1 else ''} {shown}"

    def section_lines(self, word, level3=None):
        """Line indexes of the level-2 section whose heading contains word (and of its
        level-3 subsection containing level3, when given)."""
        out = []
        for i, (h2, h3) in enumerate(self.heading):
            if word.lower() in h2.lower():
                if level3 is None or level3.lower() in h3.lower():
                    out.append(i)
        return out

    def names(self, regex, indexes=None):
        found = {}
        for i in (range(len(self.lines)) if indexes is None else indexes):
            for code in self.code[i]:
                for m in regex.finditer(code):
                    found.setdefault(m.group(1), []).append(i + 1)
        return found


def function_names(doc, indexes=None):
    names = {}
    for name, lines in doc.names(QFOC_NAME, indexes).items():
        if not name.endswith("_t"):
            names.setdefault(name, []).extend(lines)
    for name, lines in doc.names(CALL_NAME, indexes).items():
        names.setdefault(name, []).extend(lines)
    return names


def cells(line):
    """The cells of a Markdown table row (an escaped \\| stays in its cell)."""
    body = line.strip()
    body = body[1:] if body.startswith("|") else body
    body = body[:-1] if body.endswith("|") and not body.endswith("\\|") else body
    return [c.strip() for c in re.split(r"(?<!\\)\|", body)]


def span_set(cell):
    return {s.strip() for s in SPAN.findall(cell)}


# ------------------------------------------------------------------ the check

def check(root):
    problems = []
    doc_path = os.path.join(root, DOC)
    if not os.path.exists(doc_path):
        return [f"{DOC} does not exist"], None
    doc = Doc(read(doc_path))
    src = Sources(root)
    reqs = requirement_ids(root)

    # functions named
    funcs = function_names(doc)
    for name in sorted(funcs):
        if not src.exists(name):
            problems.append(f"function {name} ({doc.where(funcs[name])}) is neither declared in "
                            "include/qfoc/*.h nor defined in src/ or port_s32k/")

    # files named
    paths = doc.names(PATH)
    modules = set()
    for path in sorted(paths):
        if not os.path.exists(os.path.join(root, path)):
            problems.append(f"file {path} ({doc.where(paths[path])}) does not exist")
        elif MODULE_FILE.match(path):
            modules.add(path)

    # requirement IDs cited
    cited = {}
    for i, ln in enumerate(doc.lines):
        for rid in REQ.findall(ln):
            cited.setdefault(rid, []).append(i + 1)
    for rid in sorted(cited):
        if rid not in reqs:
            problems.append(f"requirement {rid} ({doc.where(cited[rid])}) has no '### {rid}' "
                            "heading in specs/requirements/*.md")

    # the interface section names every public function
    iface = doc.section_lines("Interfaces")
    if not iface:
        problems.append(f"{DOC} has no level-2 section 'Interfaces'")
    else:
        named = set(function_names(doc, iface))
        for name in sorted(src.public):
            if name not in named:
                problems.append(f"public function {name} ({src.public[name]}) is not named in the "
                                f"interface section '{doc.heading[iface[0]][0]}' of {DOC}")

    # the static architecture describes every module, and its dependency table is true
    static = doc.section_lines("Static architecture")
    deps = doc.section_lines("Static architecture", "Dependency table")
    if not static:
        problems.append(f"{DOC} has no level-2 section 'Static architecture'")
    else:
        described = set(doc.names(PATH, [i for i in static if i not in set(deps)]))
        for path in src.src_c:
            if path not in described:
                problems.append(f"module {path} is not described in the section "
                                f"'{doc.heading[static[0]][0]}' of {DOC}")
    if static and not deps:
        problems.append(f"{DOC} has no 'Dependency table' subsection in 'Static architecture'")
    elif deps:
        rows = {}
        for i in deps:
            ln = doc.lines[i]
            if not ln.lstrip().startswith("|"):
                continue
            row = cells(ln)
            first = span_set(row[0]) if row else set()
            if len(first) != 1:
                continue
            path = next(iter(first))
            if path in rows:
                problems.append(f"dependency table: {path} has two rows ({DOC} lines "
                                f"{rows[path][0]}, {i + 1})")
            rows[path] = (i + 1, row)
        for path in src.src_c + src.src_h + src.headers:
            if path not in rows:
                problems.append(f"dependency table: no row for {path}")
                continue
            line, row = rows[path]
            want = src.includes(path)
            have = span_set(row[1]) if len(row) > 1 else set()
            if want != have:
                problems.append(dep_problem(path, line, "includes", want, have))
            if path.endswith(".c"):
                want = src.calls(path)
                have = span_set(row[2]) if len(row) > 2 else set()
                if want != have:
                    problems.append(dep_problem(path, line, "calls into", want, have))
        for path in sorted(set(rows) - set(src.src_c + src.src_h + src.headers)):
            if os.path.exists(os.path.join(root, path)):
                problems.append(f"dependency table: {path} ({DOC} line {rows[path][0]}) is not a "
                                "file of src/ or include/qfoc/")

    summary = (len([n for n in funcs if n not in src.objects]), len(modules), len(cited))
    return problems, summary


def dep_problem(path, line, column, want, have):
    parts = []
    if want - have:
        parts.append("missing " + ", ".join(sorted(want - have)))
    if have - want:
        parts.append("not in the sources " + ", ".join(sorted(have - want)))
    return (f"dependency table: {path} ({DOC} line {line}), column '{column}': "
            + "; ".join(parts))


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--root", default=os.path.dirname(os.path.dirname(os.path.dirname(
        os.path.abspath(__file__)))), help="repository root (default: this file's)")
    args = ap.parse_args(argv)
    root = os.path.abspath(args.root)
    problems, summary = check(root)
    if problems:
        for p in problems:
            print(f"arch-check: {p}")
        print(f"arch-check: {len(problems)} problem{'s' if len(problems) != 1 else ''}")
        return 1
    n, m, k = summary
    print(f"arch-check: {n} functions, {m} modules, {k} requirements named, all present")
    return 0


if __name__ == "__main__":
    sys.exit(main())
