#!/usr/bin/env python3
"""Review records tied to the files they reviewed (REQ-EVD-031).

Two documents hold records of a manual review:

  misra   misra/reviews.md: one record per MISRA C:2012 guideline reviewed by hand (a
          '## Rule N.M ...' or '## Dir N.M ...' section with '- Field:' lines).  The files a
          record covers are the glob patterns written in backticks on its 'Scope:' line
          (every backticked token there is a pattern relative to the repository root and
          must match at least one file).
  fmea    specs/safety-analysis.md, section 2: one record per row of the software FMEA
          (ID I-nn, F-nn, T-nn, A-nn, M-nn, O-nn).  The files a row covers are derived from the
          row: the files of the code that define (a .c file: a function or a file-scope
          object) or declare (a header) each identifier written in backticks in its block
          column (src/*.c, src/*.h, include/qfoc/*.h, tables/*.c, tables/*.h; a backticked
          expression such as `d->p` names nothing), and the requirement files
          (specs/requirements/*.md) that define the REQ IDs of its evidence column (a range
          'REQ-<MOD>-001 .. REQ-<MOD>-004' names every ID in it).

Each record carries the SHA-256 of its files as they were when it was reviewed, computed as
tools/evidence/inputs.py computes a gate's digest (`digest_of`: the SHA-256 of every file,
sorted by repository-relative path, then the SHA-256 of that list, with the gate name
`review`, no flags and no tools), so that it depends on file contents and paths only:

  misra   the record's lines '- Reviewed: <YYYY-MM-DD>, <who>' (the reviewer's role) and
          '- Files: sha256 <hex> over N files (tools/evidence/review_stamp.py)'
  fmea    one 'Reviewed: <YYYY-MM-DD>, <who>' line for the analysis (section 2) and, per
          row, its files and their digest in the generated table of section 2.7 (between
          '<!-- BEGIN GENERATED: fmea-stamps' and '<!-- END GENERATED: fmea-stamps -->')

and beside the document a manifest (misra/reviews.sha256, specs/safety-analysis.sha256:
sha256sum format, one '# stamp <hex>' section per digest recorded) keeps the SHA-256 of each
file as it was reviewed, so that a stale record names the files that changed.  A record is

  current    its digest equals the digest of its files now;
  stale      a file changed, appeared or disappeared since it was stamped (the files are
             named), or the files its scope derives now are not those recorded;
  unstamped  it carries no digest or no 'Reviewed:' line with a date and a reviewer:
             refused, never current;
  invalid    its scope names no file (a pattern that matches nothing, a row whose block
             names nothing of the code).

No record names a commit: the commit that records a review is made after the review, and a
commit identifier does not survive a rebase, whereas the digest identifies the reviewed
content in any clone.  `make evidence` (tools/evidence/evidence.py) shows every record
current or stale (red) and each FMEA row with the verdicts of its requirements.

usage:
  review_stamp.py --check [DOC ...]        per record: 'current' or 'stale: <files>', ...;
                                           exit 1 when one is not current (DOC: misra, fmea;
                                           default both)
  review_stamp.py --stamp DOC [ID ...] [--date YYYY-MM-DD] [--reviewer TEXT]
                                           after a review: write the digests of the records
                                           named (every record of DOC without an ID), the
                                           review date (default today, UTC) and the manifest
  review_stamp.py --files DOC ID           the files of one record, with their SHA-256 now
Options: --root DIR (default: this checkout).
"""
import argparse
import datetime
import os
import re
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)

import inputs as inp  # noqa: E402  (the digest of a set of files)
import trace  # noqa: E402  (REQ IDs and their ranges)

ROOT = inp.ROOT
SELF = "tools/evidence/review_stamp.py"
GATE = "review"
CURRENT, STALE, UNSTAMPED = inp.CURRENT, inp.STALE, inp.UNSTAMPED
INVALID = "invalid"
ROLE = "the qfoc maintainers, independent of the author of the change"

DOCS = {
    "misra": {"path": "misra/reviews.md", "manifest": "misra/reviews.sha256",
              "what": "MISRA C:2012 review records"},
    "fmea": {"path": "specs/safety-analysis.md", "manifest": "specs/safety-analysis.sha256",
             "what": "software FMEA rows"},
}

CODE = ("src/*.c", "src/*.h", "include/qfoc/*.h", "tables/*.c", "tables/*.h")
REQUIREMENTS = "specs/requirements/*.md"

FILES_RE = re.compile(r"^sha256 ([0-9a-f]{64}) over (\d+) files? \(tools/evidence/review_stamp\.py\)\s*$")
REVIEWED_RE = re.compile(r"^(\d{4}-\d\d-\d\d)\b[,;:]?\s*(.*)$")
REV_HEAD = re.compile(r"^##\s+((?:Rule|Dir)\s+[0-9]+\.[0-9]+)\b\s*(.*)$")
FIELD = re.compile(r"^-\s*([A-Z][A-Za-z ]*?)\s*:\s*(.*)$")
TICKS = re.compile(r"`([^`]+)`")
ROW_ID = re.compile(r"^[A-Z]-\d\d$")
BEGIN = ("<!-- BEGIN GENERATED: fmea-stamps (tools/evidence/review_stamp.py --stamp fmea: "
         "the files of each row and their SHA-256 when the row was reviewed; do not edit) -->")
BEGIN_RE = re.compile(r"^<!-- BEGIN GENERATED: fmea-stamps\b.*-->$")
END = "<!-- END GENERATED: fmea-stamps -->"
STAMPS_HEAD = "| row | files reviewed | sha256 of the files |\n|---|---|---|"


def today():
    return datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d")


def read(root, rel):
    try:
        with open(os.path.join(root, rel), encoding="utf-8") as f:
            return f.read()
    except OSError:
        return None


def digest(paths, root):
    """(digest, {path: sha256}) of a set of repository-relative paths."""
    hashes = inp.hashes_of(sorted(paths), root)
    return inp.digest_of(GATE, "", [], hashes), hashes


def files_line(hexdigest, n):
    return f"sha256 {hexdigest} over {n} file{'s' if n != 1 else ''} ({SELF})"


# ----------------------------------------------------------------------------- the manifest

def read_manifest(path):
    """{digest: {path: sha256}} of a manifest (empty when it is missing)."""
    out, cur = {}, None
    try:
        with open(path, encoding="utf-8") as f:
            for line in f:
                m = re.match(r"^# stamp ([0-9a-f]{64})\b", line)
                if m:
                    cur = out.setdefault(m.group(1), {})
                    continue
                m = re.match(r"^([0-9a-f]{64})  (.+)$", line.rstrip("\n"))
                if m and cur is not None:
                    cur[m.group(2)] = m.group(1)
    except OSError:
        pass
    return out


def write_manifest(path, doc, sections):
    """sections: {digest: ({path: sha256}, [record IDs])}."""
    with open(path, "w", encoding="utf-8") as f:
        f.write(f"# {SELF}: the files of the records of {DOCS[doc]['path']} as they were when each "
                "was reviewed ('sha256sum -c' checks the files)\n")
        for d in sorted(sections):
            hashes, ids = sections[d]
            f.write(f"# stamp {d} ({len(hashes)} file{'s' if len(hashes) != 1 else ''}): {', '.join(ids)}\n")
            for p in sorted(hashes):
                f.write(f"{hashes[p]}  {p}\n")


def differences(recorded, hashes):
    """Why the files now differ from those of the manifest section."""
    changed = sorted(p for p in hashes if p in recorded and recorded[p] != hashes[p])
    added = sorted(p for p in hashes if p not in recorded)
    removed = sorted(p for p in recorded if p not in hashes)
    out = []
    for what, lst in (("changed", changed), ("new", added), ("removed", removed)):
        if lst:
            out.append(f"{len(lst)} file{'s' if len(lst) != 1 else ''} {what} since the review: "
                       + ", ".join(lst[:8]) + (", ..." if len(lst) > 8 else ""))
    return out


# ----------------------------------------------------------------------------- MISRA records

def parse_misra(text):
    """The records of misra/reviews.md: list of dict(id, title, line, fields {name: value},
    spans {name: (first, last) line index}, end (index of the record's last field line))."""
    recs = []
    lines = text.splitlines()
    cur, last = None, None
    for i, line in enumerate(lines):
        m = REV_HEAD.match(line)
        if m:
            cur = {"id": m.group(1), "title": m.group(2).strip(), "line": i + 1, "fields": {},
                   "spans": {}, "end": i}
            recs.append(cur)
            last = None
            continue
        if line.startswith("#"):
            cur, last = None, None
            continue
        if cur is None:
            continue
        m = FIELD.match(line)
        if m:
            last = m.group(1)
            cur["fields"][last] = m.group(2).strip()
            cur["spans"][last] = (i, i)
            cur["end"] = i
        elif line.startswith("  ") and last is not None:
            cur["fields"][last] += " " + line.strip()
            cur["spans"][last] = (cur["spans"][last][0], i)
            cur["end"] = i
        else:
            last = None
    return recs


def misra_scope(rec, root):
    """(patterns, sorted files, errors) of a record's Scope line."""
    pats = TICKS.findall(rec["fields"].get("Scope", ""))
    errors, found = [], set()
    if not pats:
        errors.append("its Scope names no file pattern in backticks")
    for p in pats:
        got = inp.glob_files([p], root)
        if not got:
            errors.append(f"the Scope pattern `{p}` matches no file")
        found |= got
    return pats, sorted(found), errors


# ----------------------------------------------------------------------------- FMEA rows

def blank_c(text):
    """C text with comments and string and character literals blanked (newlines kept)."""
    out, i, n = [], 0, len(text)
    while i < n:
        j = trace.c_skip(text, i)
        if j != i:
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        else:
            out.append(text[i])
            i += 1
    return "".join(out)


FUNC_DEF = re.compile(
    r"^(?:static\s+)?(?:inline\s+)?(?:const\s+)?[A-Za-z_][A-Za-z0-9_]*\s*\**\s*"
    r"([A-Za-z_][A-Za-z0-9_]*)\s*\(([^;{}]*)\)\s*\n\{", re.M)
OBJ_DEF = re.compile(
    r"^(?:static\s+)?(?:const\s+)?(?:[A-Za-z_][A-Za-z0-9_]*\s+)+(?:const\s+)?\**\s*"
    r"([A-Za-z_][A-Za-z0-9_]*)\s*(?:\[[^\]\n]*\]\s*)*(?:=|;)", re.M)


class CodeIndex:
    """Where the identifiers of the code are defined (a .c file: its functions and file-scope
    objects) or declared (a header: every identifier of its code)."""

    def __init__(self, root):
        self.where = {}
        for rel in sorted(inp.glob_files(CODE, root)):
            code = blank_c(read(root, rel) or "")
            if rel.endswith(".c"):
                names = {m.group(1) for m in FUNC_DEF.finditer(code)}
                names |= {m.group(1) for m in OBJ_DEF.finditer(code)}
            else:
                names = set(re.findall(r"\b[A-Za-z_][A-Za-z0-9_]*\b", code))
            for name in names:
                self.where.setdefault(name, set()).add(rel)

    def files(self, name):
        return self.where.get(name, set())


def requirement_files(root):
    """{REQ ID: its requirement file}."""
    out = {}
    for rel in sorted(inp.glob_files([REQUIREMENTS], root)):
        for line in (read(root, rel) or "").splitlines():
            m = trace.HEAD.match(line.strip())
            if m:
                out[m.group(1)] = rel
    return out


def md_cells(line):
    """The cells of a markdown table row ('\\|' is a literal bar)."""
    s = line.strip()
    if s.startswith("|"):
        s = s[1:]
    if s.endswith("|") and not s.endswith("\\|"):
        s = s[:-1]
    return [c.strip().replace("\\|", "|") for c in re.split(r"(?<!\\)\|", s)]


def fmea_section(text):
    """(first, end) line indices of section 2 (the software FMEA), or None."""
    lines = text.splitlines()
    first = next((i for i, ln in enumerate(lines) if re.match(r"^##\s+2\.\s", ln)), None)
    if first is None:
        return None
    end = next((i for i in range(first + 1, len(lines)) if re.match(r"^##\s+\S", lines[i])), len(lines))
    return first, end


def parse_fmea(text):
    """dict(rows: [dict(id, block, evidence, line, cells)], reviewed: (date, who) or None,
    reviewed_line: index, stamps: {id: (files, digest)}, stamps_span: (begin, end) or None)."""
    lines = text.splitlines()
    sec = fmea_section(text)
    out = {"rows": [], "reviewed": None, "reviewed_line": None, "stamps": {}, "stamps_span": None,
           "section": sec, "malformed": []}
    if sec is None:
        return out
    head = None
    in_stamps = False
    for i in range(sec[0], sec[1]):
        ln = lines[i]
        if BEGIN_RE.match(ln.strip()):
            in_stamps, begin = True, i
            continue
        if ln.strip() == END:
            in_stamps = False
            out["stamps_span"] = (begin, i)
            continue
        if in_stamps:
            c = md_cells(ln) if ln.strip().startswith("|") else []
            if len(c) >= 3 and ROW_ID.match(c[0]):
                m = re.search(r"[0-9a-f]{64}", c[2])
                out["stamps"][c[0]] = (sorted(TICKS.findall(c[1])), m.group(0) if m else None)
            continue
        m = re.match(r"^Reviewed:\s*(.*)$", ln)
        if m and out["reviewed_line"] is None:
            out["reviewed_line"] = i
            r = REVIEWED_RE.match(m.group(1).strip())
            out["reviewed"] = ((r.group(1), r.group(2).strip().rstrip(".;,")) if r
                               else (None, m.group(1).strip()))
            continue
        if not ln.strip().startswith("|"):
            head = None
            continue
        cells = md_cells(ln)
        if cells and cells[0] == "ID":
            head = [c.lower() for c in cells]
            continue
        if head and cells and ROW_ID.match(cells[0]) and len(cells) != len(head):
            out["malformed"].append(f"row {cells[0]} (line {i + 1}) has {len(cells)} cells, its table "
                                    f"{len(head)} (a '|' inside a cell must be written '\\|')")
        elif head and cells and ROW_ID.match(cells[0]):
            row = dict(zip(head, cells))
            out["rows"].append({"id": cells[0], "block": row.get("block", ""),
                                "evidence": row.get("evidence", ""), "line": i + 1,
                                "failure": row.get("failure mode", ""),
                                "detection": row.get("detection / mitigation", "")})
    return out


def fmea_scope(row, root, index, reqs):
    """(files, requirement IDs, errors, notes) of one FMEA row."""
    code, unknown = set(), []
    for name in TICKS.findall(row["block"]):
        if not re.fullmatch(r"[A-Za-z_][A-Za-z0-9_]*", name):
            continue  # an expression (`d->p`, `i_w = ...`): its identifiers are named apart
        got = index.files(name)
        if got:
            code |= got
        elif name not in unknown:
            unknown.append(name)
    rids = sorted(trace.ids(row["evidence"], set(reqs)))
    errors = []
    if not code:
        errors.append("its block names no function, type or object of the code in backticks")
    undefined = [r for r in rids if r not in reqs]
    if undefined:
        errors.append("its evidence names undefined requirements: " + ", ".join(undefined))
    files = code | {reqs[r] for r in rids if r in reqs}
    notes = [f"not found in the code: {', '.join(unknown)}"] if unknown else []
    return sorted(files), rids, errors, notes


# ----------------------------------------------------------------------------- checking

def _state(files, errors, recorded, recorded_files, reviewed, manifest, root):
    """dict(state, reasons, now, hashes) of one record."""
    if errors:
        return {"state": INVALID, "reasons": errors, "now": None, "hashes": {}}
    now, hashes = digest(files, root)
    res = {"state": CURRENT, "reasons": [], "now": now, "hashes": hashes}
    if recorded is None:
        res.update(state=UNSTAMPED, reasons=["no digest of its files: not tied to the files it reviewed"])
        return res
    if not reviewed or not reviewed[0] or not reviewed[1]:
        res.update(state=UNSTAMPED, reasons=["no 'Reviewed:' line with the date and the reviewer"])
        return res
    if recorded == now and (recorded_files is None or recorded_files == files):
        return res
    res["state"] = STALE
    reasons = []
    if recorded_files is not None and recorded_files != files:
        new = [p for p in files if p not in recorded_files]
        gone = [p for p in recorded_files if p not in files]
        reasons.append("its files are not those reviewed"
                       + (f": now also {', '.join(new)}" if new else "")
                       + (f"{';' if new else ':'} no longer {', '.join(gone)}" if gone else ""))
    sec = manifest.get(recorded)
    if sec is not None:
        reasons += differences(sec, hashes)
    elif not reasons:
        reasons.append("its files differ from those reviewed (no manifest section for that "
                       "digest to tell which)")
    res["reasons"] = reasons or ["its files differ from those reviewed"]
    return res


def check(doc, root=ROOT):
    """dict(doc, path, what, present, reviewed, records: [dict(id, title, state, reasons,
    files, recorded, now, reviewed, line, result | reqs, notes)], counts, errors)."""
    spec = DOCS[doc]
    text = read(root, spec["path"])
    out = {"doc": doc, "path": spec["path"], "manifest": spec["manifest"], "what": spec["what"],
           "present": text is not None, "records": [], "errors": [], "reviewed": None}
    if text is None:
        return out
    manifest = read_manifest(os.path.join(root, spec["manifest"]))
    if doc == "misra":
        for rec in parse_misra(text):
            _pats, files, errors = misra_scope(rec, root)
            m = FILES_RE.match(rec["fields"].get("Files", ""))
            rv = REVIEWED_RE.match(rec["fields"].get("Reviewed", ""))
            reviewed = (rv.group(1), rv.group(2).strip()) if rv else None
            if m and int(m.group(2)) != len(files) and not errors:
                recorded_n = int(m.group(2))
            else:
                recorded_n = None
            st = _state(files, errors, m.group(1) if m else None, None, reviewed, manifest, root)
            if recorded_n is not None and st["state"] == STALE:
                st["reasons"].insert(0, f"{recorded_n} files reviewed, {len(files)} now")
            out["records"].append({"id": rec["id"], "title": rec["title"], "line": rec["line"],
                                   "result": rec["fields"].get("Result", ""), "files": files,
                                   "recorded": m.group(1) if m else None, "reviewed": reviewed,
                                   "notes": [], **st})
        if not out["records"]:
            out["errors"].append(f"{spec['path']}: no review record")
    else:
        fm = parse_fmea(text)
        if fm["section"] is None:
            out["errors"].append(f"{spec['path']}: no section '## 2. ...' (the software FMEA)")
            return out
        out["reviewed"] = fm["reviewed"]
        out["errors"] += [f"{spec['path']}: {m}" for m in fm["malformed"]]
        if fm["stamps_span"] is None:
            out["errors"].append(f"{spec['path']}: no generated table of the rows' stamps")
        index, reqs = CodeIndex(root), requirement_files(root)
        for row in fm["rows"]:
            files, rids, errors, notes = fmea_scope(row, root, index, reqs)
            rec_files, rec_digest = fm["stamps"].get(row["id"], (None, None))
            st = _state(files, errors, rec_digest, rec_files, fm["reviewed"], manifest, root)
            out["records"].append({"id": row["id"], "title": row["block"], "line": row["line"],
                                   "reqs": rids, "files": files, "recorded": rec_digest,
                                   "reviewed": fm["reviewed"], "notes": notes,
                                   "failure": row["failure"], **st})
        extra = sorted(set(fm["stamps"]) - {r["id"] for r in fm["rows"]})
        if extra:
            out["errors"].append(f"{spec['path']}: stamps of rows that are not in the analysis: "
                                 + ", ".join(extra))
        if not out["records"]:
            out["errors"].append(f"{spec['path']}: no FMEA row")
    counts = {}
    for r in out["records"]:
        counts[r["state"]] = counts.get(r["state"], 0) + 1
    out["counts"] = counts
    return out


def ok(result):
    return (result["present"] and not result["errors"] and bool(result["records"])
            and all(r["state"] == CURRENT for r in result["records"]))


# ----------------------------------------------------------------------------- stamping

def _select(records, ids):
    known = {r["id"] for r in records}
    bad = [i for i in ids if i not in known]
    if bad:
        raise ValueError("no record " + ", ".join(repr(b) for b in bad))
    return set(ids) if ids else known


def stamp(doc, root=ROOT, ids=(), date=None, reviewer=None):
    """Write the digests of the records IDS (every record without IDs) of DOC, the review
    date and the manifest; returns the records' new check results."""
    spec = DOCS[doc]
    path = os.path.join(root, spec["path"])
    text = read(root, spec["path"])
    if text is None:
        raise ValueError(f"{spec['path']} not found")
    date = date or today()
    if not re.fullmatch(r"\d{4}-\d\d-\d\d", date):
        raise ValueError(f"not a date: {date!r}")
    before = check(doc, root)
    chosen = _select(before["records"], list(ids))
    bad = [r for r in before["records"] if r["id"] in chosen and r["state"] == INVALID]
    if bad:
        raise ValueError("; ".join(f"{r['id']}: {'; '.join(r['reasons'])}" for r in bad))
    lines = text.splitlines()
    if doc == "misra":
        recs = parse_misra(text)
        # from the last record up, so that the indices above stay valid
        for rec in reversed(recs):
            if rec["id"] not in chosen:
                continue
            now = next(r for r in before["records"] if r["id"] == rec["id"])
            who = reviewer
            if who is None:
                rv = REVIEWED_RE.match(rec["fields"].get("Reviewed", ""))
                who = rv.group(2).strip() if rv and rv.group(2).strip() else "by " + ROLE
            new = [f"- Reviewed: {date}, {who}", f"- Files: {files_line(now['now'], len(now['files']))}"]
            drop = set()
            for name in ("Reviewed", "Files"):
                if name in rec["spans"]:
                    a, b = rec["spans"][name]
                    drop.update(range(a, b + 1))
            end = rec["end"]
            keep = [k for k in range(rec["line"], end + 1) if k not in drop]
            block = [lines[k] for k in keep] + new
            lines[rec["line"]:end + 1] = block
    else:
        fm = parse_fmea(text)
        stamps = dict(fm["stamps"])
        for r in before["records"]:
            if r["id"] in chosen:
                stamps[r["id"]] = (r["files"], r["now"])
        order = [r["id"] for r in before["records"]]
        table = [BEGIN, STAMPS_HEAD]
        for rid in order:
            if rid in stamps:
                fl, d = stamps[rid]
                table.append(f"| {rid} | " + ", ".join(f"`{p}`" for p in fl) + f" | `{d or '-'}` |")
        table.append(END)
        if fm["stamps_span"] is not None:
            a, b = fm["stamps_span"]
            lines[a:b + 1] = table
        else:
            stop = end = fm["section"][1]
            add = ["### 2.6 Review stamps of the rows", "",
                   "Generated by `tools/evidence/review_stamp.py --stamp fmea` after a review of the",
                   "rows: the files of each row and their SHA-256.", ""] + table
            while end > 0 and not lines[end - 1].strip():
                end -= 1
            lines[end:stop] = [""] + add + ([""] if stop < len(lines) else [])
        who = reviewer
        if who is None:
            who = fm["reviewed"][1] if fm["reviewed"] and fm["reviewed"][1] else "by " + ROLE
        rline = f"Reviewed: {date}, {who}"
        if fm["reviewed_line"] is not None:
            lines[fm["reviewed_line"]] = rline
        else:
            first = fm["section"][0]
            lines[first + 1:first + 1] = ["", rline]
    with open(path, "w", encoding="utf-8") as f:
        f.write("\n".join(lines) + "\n")
    after = check(doc, root)
    sections = {}
    old = read_manifest(os.path.join(root, spec["manifest"]))
    for r in after["records"]:
        d = r["recorded"]
        if not d:
            continue
        if r["id"] in chosen or d not in old:
            hashes = r["hashes"] if r["state"] == CURRENT else old.get(d)
        else:
            hashes = old[d]
        if hashes is None:
            continue
        sections.setdefault(d, (hashes, []))[1].append(r["id"])
    write_manifest(os.path.join(root, spec["manifest"]), doc, sections)
    return after


# ----------------------------------------------------------------------------- command line

def describe(r):
    if r["state"] == CURRENT:
        return f"current ({len(r['files'])} files, sha256 {r['now'][:16]}..., reviewed {r['reviewed'][0]})"
    return f"{r['state']}: " + "; ".join(r["reasons"])


def main(argv=None):
    ap = argparse.ArgumentParser(description="Review records tied to the files they reviewed.")
    ap.add_argument("--root", default=ROOT)
    g = ap.add_mutually_exclusive_group(required=True)
    g.add_argument("--check", nargs="*", metavar="DOC")
    g.add_argument("--stamp", nargs="+", metavar=("DOC", "ID"))
    g.add_argument("--files", nargs=2, metavar=("DOC", "ID"))
    ap.add_argument("--date", default=None, help="the review's date (YYYY-MM-DD; default today, UTC)")
    ap.add_argument("--reviewer", default=None,
                    help="who reviewed (a role; default: the record's, else '" + "by " + ROLE + "')")
    a = ap.parse_args(argv)
    root = os.path.abspath(a.root)
    docs = a.check if a.check is not None else [(a.stamp or a.files)[0]]
    docs = docs or list(DOCS)
    for d in docs:
        if d not in DOCS:
            print(f"review_stamp: unknown document {d!r} (documents: {', '.join(DOCS)})", file=sys.stderr)
            return 2
    if a.files:
        res = check(a.files[0], root)
        rec = next((r for r in res["records"] if r["id"] == a.files[1]), None)
        if rec is None:
            print(f"review_stamp: no record {a.files[1]!r} in {res['path']}", file=sys.stderr)
            return 2
        for p in rec["files"]:
            print(f"{inp.sha256_file(os.path.join(root, p))}  {p}")
        print(f"# {describe(rec)}")
        return 0
    if a.stamp:
        try:
            res = stamp(a.stamp[0], root, a.stamp[1:], a.date, a.reviewer)
        except ValueError as e:
            print(f"review_stamp: {e}", file=sys.stderr)
            return 1
        n = len(a.stamp[1:]) or len(res["records"])
        print(f"review_stamp: {res['path']}: {n} record{'s' if n != 1 else ''} stamped; "
              + ", ".join(f"{v} {k}" for k, v in sorted(res["counts"].items())))
        return 0
    rc = 0
    for d in docs:
        res = check(d, root)
        if not res["present"]:
            print(f"{res['path']}: not found")
            rc = 1
            continue
        for e in res["errors"]:
            print(f"{e}")
        for r in res["records"]:
            print(f"{res['path']}:{r['line']}: {r['id']}: {describe(r)}")
        print(f"review_stamp: {res['path']}: {len(res['records'])} {res['what']}: "
              + ", ".join(f"{v} {k}" for k, v in sorted(res["counts"].items())))
        if not ok(res):
            rc = 1
    return rc


if __name__ == "__main__":
    sys.exit(main())
