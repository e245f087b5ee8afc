#!/usr/bin/env python3
"""The ISO 26262 evidence bundle of qfoc: what the gates produced, in one place.

usage: evidence.py [--root DIR] [--build DIR] [--out DIR] [--strict]

Reads the results the gates wrote (build/ and the committed results under proofs/, misra/
and specs/; it runs no gate itself) and writes into OUT (default build/evidence/):

  index.html      one self-contained page (inline CSS, no script, no external resource):
                  the one-screen summary, then one section per kind of evidence
  evidence.json   the summary rows and every section's figures, machine-readable
  artefacts/      a copy of every underlying file, under its path in the repository
                  (artefacts/proofs/wp/results.md, artefacts/build/eva/eva-all.json, ...);
                  the page links them relatively, so OUT can be archived and handed over
  tool-versions.txt  the output of `sh tools/evidence/tool_versions.sh` for this run
  MANIFEST.sha256 the SHA-256 of every other file of OUT (sha256sum format)

artefacts/ also holds what an assessor needs to read what was verified: the requirements
(specs/requirements/*.md), the contracts (include/qfoc/*.h), the sources, specs/*.acsl and
specs/*.md, the tests (tests/*.c, tools/*/tests/*.py), the proofs and their results, the
MISRA records (misra/), and every input file of every stamped result.

Every summary row is green or red with its figure; an input that is missing makes its
row red with "not run", never green.  A result whose inputs stamp (tools/evidence/inputs.py)
differs from the inputs now is stale: red.  A requirement is verified only when every proof
it names is proved in results tied to the current sources and every test it names passed
in this run's results (tools/evidence/verdict.py); a test that did not run is "not run".
Prints the summary as plain text, one line per row, and
'evidence: OUT/index.html (N green, M red)'.  Exit status 0 when the page was written; with
--strict, 1 when a summary row is red.  The review records (the MISRA review records of
misra/reviews.md, in section 3, and the rows of the software FMEA of specs/safety-analysis.md,
section 14) are current or stale against the files they reviewed
(tools/evidence/review_stamp.py): a stale or unstamped record makes its summary row red, and
an FMEA row is green only when every requirement it names is verified.  The requirements are
specs/requirements/evidence.md (REQ-EVD-001 .. REQ-EVD-032; REQ-EVD-030 the tool validation of
section 13, REQ-EVD-031 the review records, REQ-EVD-032 the store of WP's prover results).
"""
import argparse
import datetime
import glob
import hashlib
import html
import json
import os
import re
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import inputs as inp  # noqa: E402  (tools/evidence/inputs.py: the gates' inputs and stamps)
import verdict as vd  # noqa: E402  (tools/evidence/verdict.py: the requirement verdicts)
import review_stamp as rs  # noqa: E402  (tools/evidence/review_stamp.py: review records and their files)

# --------------------------------------------------------------------------- helpers


def esc(value) -> str:
    return html.escape("" if value is None else str(value), quote=True)


def read_text(path):
    try:
        with open(path, encoding="utf-8", errors="replace") as f:
            return f.read()
    except OSError:
        return None


def read_json(path):
    """The parsed JSON of a file, or None when it is missing or malformed."""
    text = read_text(path)
    if text is None:
        return None
    try:
        return json.loads(text)
    except ValueError:
        return None


def as_int(value, default=0):
    try:
        return int(value)
    except (TypeError, ValueError):
        try:
            return int(float(value))
        except (TypeError, ValueError):
            return default


def as_float(value, default=None):
    try:
        return float(value)
    except (TypeError, ValueError):
        return default


def pct(num, den):
    return 100.0 * num / den if den else None


def fmt_pct(value, digits=1):
    return "-" if value is None else f"{value:.{digits}f} %"


def as_list(value):
    """A list of the value (None: empty; a string or number: one element; a dict: its items)."""
    if value is None or value == "" or value == "-":
        return []
    if isinstance(value, list):
        return value
    if isinstance(value, dict):
        return [value]
    if isinstance(value, str) and "<br>" in value:
        return [v.strip() for v in value.split("<br>") if v.strip()]
    return [value]


def truthy(value):
    if isinstance(value, bool):
        return value
    if isinstance(value, (int, float)):
        return value != 0
    if isinstance(value, str):
        return value.strip().lower() in ("yes", "true", "pass", "passed", "ok", "verified", "1")
    return False


def split_md_row(line):
    """The cells of a markdown table row ('\\|' is a literal bar)."""
    s = line.strip()
    if s.startswith("|"):
        s = s[1:]
    if s.endswith("|") and not s.endswith("\\|"):
        s = s[:-1]
    return [c.strip().replace("\\|", "|") for c in re.split(r"(?<!\\)\|", s)]


def md_tables(text):
    """Every markdown table of a text: a list of (header cells, list of row cells)."""
    tables = []
    lines = (text or "").splitlines()
    i = 0
    while i < len(lines) - 1:
        if lines[i].strip().startswith("|") and re.match(r"^\s*\|?\s*:?-{2,}", lines[i + 1]):
            head = split_md_row(lines[i])
            rows = []
            i += 2
            while i < len(lines) and lines[i].strip().startswith("|"):
                rows.append(split_md_row(lines[i]))
                i += 1
            tables.append((head, rows))
        else:
            i += 1
    return tables


def table_with(text, *columns):
    """The first markdown table whose header has all the columns, as a list of dicts."""
    for head, rows in md_tables(text):
        low = [h.lower() for h in head]
        if all(c in low for c in columns):
            return [dict(zip(low, r)) for r in rows]
    return None


# --------------------------------------------------------------------------- markdown


LIST_RE = re.compile(r"^(\s*)([-*+]|\d+[.)])\s+")


def md_inline(text):
    """Inline markdown (code spans, bold, emphasis, links) of one line, escaped."""
    parts = re.split(r"(`+[^`]*?`+)", text)
    out = []
    for part in parts:
        if part.startswith("`") and part.endswith("`") and len(part) >= 2:
            out.append("<code>" + esc(part.strip("`")) + "</code>")
            continue
        s = esc(part)
        s = re.sub(r"\*\*(.+?)\*\*", r"<strong>\1</strong>", s)
        s = re.sub(r"(?<![\w*])\*(?![\s*])(.+?)(?<![\s*])\*(?![\w*])", r"<em>\1</em>", s)

        def link(m):
            label, url = m.group(1), m.group(2)
            if re.match(r"^https?://", html.unescape(url)):
                return f'<a href="{url}">{label}</a>'
            return f"{label} (<code>{url}</code>)"

        s = re.sub(r"\[([^\]]+)\]\(([^)\s]+)\)", link, s)
        out.append(s)
    return "".join(out)


def md_list(block):
    """A (possibly nested) markdown list from its lines."""
    base = len(LIST_RE.match(block[0]).group(1))
    ordered = LIST_RE.match(block[0]).group(2)[0].isdigit()
    items = []
    for line in block:
        m = LIST_RE.match(line)
        if m and len(m.group(1)) <= base:
            items.append([line[m.end():]])
        elif items:
            items[-1].append(line)
    out = ["<ol>" if ordered else "<ul>"]
    for item in items:
        text, j = [item[0]], 1
        while j < len(item) and not LIST_RE.match(item[j]):
            if item[j].strip():
                text.append(item[j].strip())
            j += 1
        body = md_inline(" ".join(t.strip() for t in text))
        nested, para = [], []
        for ln in item[j:] + [None]:
            if ln is not None and not ln.strip():
                continue
            indent = None if ln is None else len(ln) - len(ln.lstrip())
            if ln is not None and (LIST_RE.match(ln) or (nested and indent > len(LIST_RE.match(nested[0]).group(1)))):
                if para:
                    body += "<p>" + md_inline(" ".join(para)) + "</p>"
                    para = []
                nested.append(ln)
                continue
            if nested:
                body += md_list(nested)
                nested = []
            if ln is not None:
                para.append(ln.strip())
        if para:
            body += "<p>" + md_inline(" ".join(para)) + "</p>"
        out.append(f"<li>{body}</li>")
    out.append("</ol>" if ordered else "</ul>")
    return "".join(out)


def md_to_html(text, shift=2):
    """Markdown of the project's documents to HTML: headings (shifted down by SHIFT levels),
    paragraphs, lists, tables, fenced and indented code, inline code, bold, emphasis."""
    lines = (text or "").splitlines()
    out, para = [], []

    def flush():
        if para:
            out.append("<p>" + md_inline(" ".join(p.strip() for p in para)) + "</p>")
            para.clear()

    i, n = 0, len(lines)
    while i < n:
        line = lines[i]
        if line.strip().startswith("```"):
            flush()
            j = i + 1
            while j < n and not lines[j].strip().startswith("```"):
                j += 1
            out.append("<pre>" + esc("\n".join(lines[i + 1:j])) + "</pre>")
            i = j + 1
            continue
        if line.strip().startswith("<!--") and line.strip().endswith("-->"):
            flush()  # a marker of a generated block (tools/evidence/gen_manual.py): not shown
            i += 1
            continue
        m = re.match(r"^(#{1,6})\s+(.*)$", line)
        if m:
            flush()
            level = min(6, len(m.group(1)) + shift)
            out.append(f"<h{level}>{md_inline(m.group(2).strip())}</h{level}>")
            i += 1
            continue
        if line.strip().startswith("|") and i + 1 < n and re.match(r"^\s*\|?\s*:?-{2,}", lines[i + 1]):
            flush()
            head = split_md_row(line)
            rows = []
            i += 2
            while i < n and lines[i].strip().startswith("|"):
                rows.append(split_md_row(lines[i]))
                i += 1
            out.append("<table><tr>" + "".join(f"<th>{md_inline(h)}</th>" for h in head) + "</tr>")
            for r in rows:
                out.append("<tr>" + "".join(f"<td>{md_inline(c)}</td>" for c in r) + "</tr>")
            out.append("</table>")
            continue
        if LIST_RE.match(line) and (not para or not line.startswith(" ")):
            flush()
            block = []
            while i < n:
                cur = lines[i]
                if not cur.strip():
                    k = i + 1
                    while k < n and not lines[k].strip():
                        k += 1
                    if k < n and (LIST_RE.match(lines[k]) or lines[k].startswith("  ")):
                        i = k
                        continue
                    break
                if block and not LIST_RE.match(cur) and not cur.startswith(" "):
                    break
                block.append(cur)
                i += 1
            out.append(md_list(block))
            continue
        if line.startswith("    ") and not para:
            j = i
            code = []
            while j < n and (lines[j].startswith("    ") or not lines[j].strip()):
                code.append(lines[j][4:])
                j += 1
            while code and not code[-1].strip():
                code.pop()
            out.append("<pre>" + esc("\n".join(code)) + "</pre>")
            i = j
            continue
        if not line.strip():
            flush()
        else:
            para.append(line)
        i += 1
    flush()
    return "\n".join(out)


# --------------------------------------------------------------------------- the bundle


class Bundle:
    """Paths of one run and the artefacts copied so far."""

    def __init__(self, root, build, out):
        self.root = os.path.abspath(root)
        self.build = build if os.path.isabs(build) else os.path.join(self.root, build)
        self.out = out if os.path.isabs(out) else os.path.join(self.root, out)
        self.copied = {}

    def path(self, rel):
        return rel if os.path.isabs(rel) else os.path.join(self.root, rel)

    def rel(self, path):
        """A path relative to the repository root (for display and for the artefacts tree)."""
        p = os.path.abspath(self.path(path))
        r = os.path.relpath(p, self.root)
        return p if r.startswith("..") else r

    def b(self, *parts):
        """A path under the build directory, relative to the root when it can be."""
        return self.rel(os.path.join(self.build, *parts))

    def exists(self, rel):
        return os.path.exists(self.path(rel))

    def art(self, rel):
        """Copy a file or directory into artefacts/ (once); its link relative to OUT, or None."""
        src = self.path(rel)
        if not os.path.exists(src):
            return None
        r = self.rel(rel)
        if os.path.isabs(r):
            r = os.path.join("external", os.path.basename(r))
        if r in self.copied:
            return self.copied[r]
        dst = os.path.join(self.out, "artefacts", r)
        os.makedirs(os.path.dirname(dst), exist_ok=True)
        if os.path.isdir(src):
            shutil.copytree(src, dst, dirs_exist_ok=True)
            link = "artefacts/" + r.replace(os.sep, "/") + "/"
            if os.path.exists(os.path.join(src, "index.html")):
                link += "index.html"
        else:
            shutil.copy2(src, dst)
            link = "artefacts/" + r.replace(os.sep, "/")
        self.copied[r] = link
        return link

    def inputs(self, *rels):
        """The record of the inputs of a section: path, present, run (the UTC time of the run
        that wrote it, from its stamp or JUnit timestamp; never the file's mtime), link; copies
        them."""
        recs = []
        for rel in rels:
            present = self.exists(rel)
            recs.append({"path": self.rel(rel), "present": present,
                         "run": inp.run_date(self.path(rel)) if present else None,
                         "link": self.art(rel) if present else None})
        return recs


def row(key, label, ok, figure, section, missing=False, note=""):
    return {"key": key, "label": label, "status": "PASS" if ok and not missing else "FAIL",
            "figure": "not run" if missing and not figure else figure,
            "missing": missing, "section": section, "note": note}


def missing_row(key, label, section, what, bundle=None):
    """The red row of a result that is not there ("not run"), or there but unreadable."""
    if bundle is not None and bundle.exists(what):
        return row(key, label, False, f"unreadable: {what}", section, missing=True,
                   note=f"{what} is not in the expected form")
    return row(key, label, False, "not run", section, missing=True, note=f"{what} not found")


# --------------------------------------------------------------------------- 1 traceability


def module_of(rid):
    m = re.match(r"^REQ-([A-Z0-9]+)-\d+", rid or "")
    return m.group(1) if m else "?"


def names(values, key_order=("name", "id", "harness", "function", "file", "scenario", "title")):
    """Display names of a list of strings or records."""
    out = []
    for v in as_list(values):
        if isinstance(v, dict):
            for k in key_order:
                if v.get(k):
                    name = str(v[k])
                    if k == "name" and v.get("file"):
                        name += f" ({v['file']})"
                    out.append(name)
                    break
            else:
                out.append(json.dumps(v, sort_keys=True))
        else:
            out.append(str(v))
    return out


def wp_cell(value):
    """The WP figure of a requirement, whatever the form trace.json gives it."""
    if value is None or value == "" or value == []:
        return "-", []
    if isinstance(value, dict):
        total = value.get("goals", value.get("total"))
        proved = value.get("proved", value.get("valid"))
        fns = names(value.get("functions") or value.get("contracts") or [])
        if total is not None and proved is not None:
            if not as_int(total) and not fns:
                return "-", []
            return f"{proved}/{total}", fns
        return (", ".join(fns) or json.dumps(value, sort_keys=True)), fns
    if isinstance(value, (int, float)):
        return str(value), []
    items = names(value)
    return (str(len(items)) if len(items) > 1 else (items[0] if items else "-")), items


def normalise_requirement(rid, rec):
    rec = rec if isinstance(rec, dict) else {}
    rid = rid or rec.get("id") or rec.get("requirement") or "?"
    contracts = names(rec.get("contracts", rec.get("contract", rec.get("header"))))
    named_in = [os.path.basename(n) for n in names(rec.get("named_in"))]
    cbmc = names(rec.get("cbmc"))
    tests = names(rec.get("tests", rec.get("test")))
    scenarios = names(rec.get("scenarios", rec.get("scenario")))
    wp_text, wp_items = wp_cell(rec.get("wp"))
    if "verified" in rec:
        verified = truthy(rec.get("verified"))
    else:
        verified = bool(contracts) and bool(tests or cbmc or wp_items)
    return {"raw": rec, "req_file": rec.get("file"),
            "id": rid, "title": str(rec.get("title", "")), "module": rec.get("module") or module_of(rid),
            "contracts": contracts, "named_in": named_in, "wp": wp_text, "wp_items": wp_items, "cbmc": cbmc,
            "tests": tests, "scenarios": scenarios, "verified": verified}


def demo_scenarios(bundle):
    """Requirement ID -> scenarios of the demonstration that name it (with their result)."""
    found = {}
    for mpath in sorted(glob.glob(os.path.join(bundle.build, "demo", "*", "metrics.json"))):
        m = read_json(mpath)
        if not isinstance(m, dict):
            continue
        name = m.get("scenario") or os.path.basename(os.path.dirname(mpath))
        label = name + ("" if m.get("pass") is None else (" (pass)" if m.get("pass") else " (FAIL)"))
        for rid in as_list(m.get("requirements")):
            found.setdefault(str(rid), []).append(label)
    return found


def collect_trace(bundle):
    sec = {"title": "Requirements and traceability", "rows": []}
    jpath, mpath = bundle.b("trace", "trace.json"), bundle.b("trace", "trace.md")
    data = read_json(bundle.path(jpath))
    reqs = []
    if data is not None:
        sec["inputs"] = bundle.inputs(jpath, mpath) if bundle.exists(mpath) else bundle.inputs(jpath)
        sec["source"] = jpath
        body = data.get("requirements", data) if isinstance(data, dict) else data
        if isinstance(data, dict):
            sec["totals"] = data.get("totals") if isinstance(data.get("totals"), dict) else {}
            sec["gate_failures"] = [str(g) for g in as_list(data.get("gate_failures"))]
        if isinstance(body, dict):
            for rid, rec in body.items():
                if isinstance(rec, dict) and re.match(r"^REQ-", str(rid)):
                    reqs.append(normalise_requirement(rid, rec))
        elif isinstance(body, list):
            for rec in body:
                if isinstance(rec, dict):
                    reqs.append(normalise_requirement(None, rec))
    elif bundle.exists(mpath):
        sec["inputs"] = bundle.inputs(mpath)
        sec["source"] = mpath
        rows = table_with(read_text(bundle.path(mpath)), "requirement") or []
        for r in rows:
            rec = {"title": r.get("title", ""),
                   "contracts": as_list(r.get("header", r.get("contract"))),
                   "cbmc": as_list(r.get("cbmc")), "tests": as_list(r.get("tests"))}
            if "wp" in r:
                rec["wp"] = as_list(r.get("wp"))
            if "scenarios" in r:
                rec["scenarios"] = as_list(r.get("scenarios"))
            if "verified" in r:
                rec["verified"] = r["verified"]
            reqs.append(normalise_requirement(r.get("requirement"), rec))
    else:
        sec["inputs"] = bundle.inputs(jpath)
        sec["present"] = False
        sec["summary"] = [missing_row("requirements", "requirements verified", "sec1",
                                      f"{jpath} and {mpath}")]
        return sec
    demo = demo_scenarios(bundle)
    for r in reqs:
        if not r["scenarios"] and r["id"] in demo:
            r["scenarios"] = demo[r["id"]]
            r["scenarios_from"] = "demo"
    reqs.sort(key=lambda r: r["id"])
    n = len(reqs)
    v = sum(1 for r in reqs if r["verified"])
    sec.update({"present": True, "requirements": reqs, "total": n, "verified": v,
                "with_tests": sum(1 for r in reqs if r["tests"]),
                "with_cbmc": sum(1 for r in reqs if r["cbmc"]),
                "with_scenarios": sum(1 for r in reqs if r["scenarios"])})
    failures = sec.get("gate_failures") or []
    if n == 0:
        sec["summary"] = [row("requirements", "requirements verified", False, "0 requirements found", "sec1")]
    else:
        fig = f"{v}/{n} verified"
        if failures:
            fig += f"; {len(failures)} trace gate failures"
        sec["summary"] = [row("requirements", "requirements verified", v == n and not failures, fig, "sec1")]
    return sec


# --------------------------------------------------------------------------- 1.1 attributes
# The requirement attributes and clauses of the matrix (tools/evidence/req_attrs.py,
# specs/requirements/README.md; REQ-EVD-020).

ATTR_ASILS = ("D", "C", "B", "A", "QM")
ATTR_KINDS = ("safety", "functional", "tool", "simulation")
ATTR_METHODS = ("proof", "analysis", "test", "review")


def collect_attrs(bundle):
    """The requirements of build/trace/trace.json by ASIL, kind and verification method."""
    data = read_json(bundle.path(bundle.b("trace", "trace.json")))
    reqs = data.get("requirements") if isinstance(data, dict) else None
    if not isinstance(reqs, list) or not any(isinstance(r, dict) and "attributes" in r for r in reqs):
        return {"present": False}
    by_asil = {a: [] for a in ATTR_ASILS}
    kinds = {k: [] for k in ATTR_KINDS}
    methods = {m: [] for m in ATTR_METHODS}
    missing, clause_failed, clause_open, clause_held = [], 0, 0, 0
    for r in reqs:
        if not isinstance(r, dict):
            continue
        a = r.get("attributes")
        if not isinstance(a, dict):
            missing.append(str(r.get("id")))
            continue
        rec = {"id": str(r.get("id")), "title": str(r.get("title", "")), "asil": a.get("asil"),
               "kind": a.get("kind"), "verification": as_list(a.get("verification")),
               "asr": as_list(a.get("asr")), "clauses": []}
        for c in as_list(r.get("clauses")):
            if isinstance(c, dict):
                rec["clauses"].append({"ref": str(c.get("ref")), "status": str(c.get("status", "")),
                                       "ok": c.get("ok")})
                clause_held += c.get("ok") is True
                clause_failed += c.get("ok") is False
                clause_open += c.get("ok") is None
        by_asil.setdefault(rec["asil"], []).append(rec)
        kinds.setdefault(rec["kind"], []).append(rec["id"])
        for m in rec["verification"]:
            methods.setdefault(m, []).append(rec["id"])
    return {"present": True, "by_asil": by_asil, "kinds": kinds, "methods": methods, "missing": missing,
            "clauses": {"held": clause_held, "failed": clause_failed, "no_result": clause_open}}


def attrs_counts_text(sec):
    """'ASIL D 73, QM 168; kind safety 81, ...; verification proof 146, ...' (non-zero only)."""
    if not sec or not sec.get("present"):
        return "requirement attributes: not run (no attributes in build/trace/trace.json; make trace)"
    asil = ", ".join(f"{a} {len(v)}" for a, v in sec["by_asil"].items() if v)
    kind = ", ".join(f"{k} {len(v)}" for k, v in sec["kinds"].items() if v)
    meth = ", ".join(f"{m} {len(v)}" for m, v in sec["methods"].items() if v)
    text = f"requirements per ASIL: {asil}; per kind: {kind}; per verification method: {meth}"
    if sec["missing"]:
        text += f"; {len(sec['missing'])} without attributes"
    return text


def html_attrs(sec):
    out = ["<h3 id=attrs>1.1 Requirements by ASIL, kind and verification method</h3>"]
    if not sec.get("present"):
        return out[0] + '<p class=missing>Not run: no requirement attributes in build/trace/trace.json (make trace).</p>'
    c = sec["clauses"]
    out.append(f"<p>{esc(attrs_counts_text(sec))}.  Clauses named by the requirements: {c['held']} hold, "
               f"{c['failed']} failed, {c['no_result']} without a result here (a WP clause needs the report "
               "of <code>make prove</code>, <code>build/wp/*.json</code>; without it the clause reads \"no WP "
               "result\", never a pass).  Attributes and clauses: <code>specs/requirements/README.md</code>.</p>")
    if sec["missing"]:
        out.append(f"<p class=missing>Without attributes: {esc(', '.join(sec['missing']))}</p>")
    out.append("<table>" + th("ASIL", "requirements", "safety", "functional", "tool", "simulation"))
    for a, reqs in sec["by_asil"].items():
        if reqs:
            out.append("<tr>" + td(a) + td(len(reqs), True)
                       + "".join(td(sum(1 for r in reqs if r["kind"] == k), True) for k in ATTR_KINDS) + "</tr>")
    out.append("</table>")
    for a, reqs in sec["by_asil"].items():
        if not reqs:
            continue
        bad = any(cl["ok"] is False for r in reqs for cl in r["clauses"])
        opened = " open" if a != "QM" or bad else ""
        out.append(f"<details{opened}><summary><b>ASIL {esc(a)}</b>: {len(reqs)} requirements</summary>")
        out.append("<table>" + th("ID", "title", "kind", "verification", "ASR", "clauses (status)"))
        for r in reqs:
            cl = "<br>".join(
                f'<span{"" if x["ok"] is None else " class=" + cls(x["ok"])}>{esc(x["ref"])}: {esc(x["status"])}</span>'
                for x in r["clauses"]) or "-"
            out.append("<tr>" + td(r["id"]) + td(r["title"]) + td(r["kind"]) + td(", ".join(r["verification"]))
                       + td(", ".join(r["asr"]) or "-") + f"<td class=small>{cl}</td></tr>")
        out.append("</table></details>")
    for label, groups in (("kind", sec["kinds"]), ("verification method", sec["methods"])):
        for k, ids in groups.items():
            if ids:
                out.append(f"<details><summary>{esc(label)} <b>{esc(k)}</b>: {len(ids)} requirements</summary>"
                           f"<p class=small>{esc(', '.join(ids))}</p></details>")
    return "\n".join(out)


# --------------------------------------------------------------------------- 2 formal


def wp_rows_from_md(text):
    rows = table_with(text, "unit", "function", "goals", "proved") or []
    out = []
    for r in rows:
        out.append({"unit": r.get("unit", ""), "function": r.get("function", ""),
                    "goals": as_int(r.get("goals")), "proved": as_int(r.get("proved")),
                    "provers": r.get("provers", ""), "time_ms": as_float(r.get("time (ms)"), None)})
    return out


def defined_functions(bundle, unit):
    """Functions a WP unit defines (tools/gates/c_functions.py), or None when unknown."""
    if unit == "lemmas_unit" or unit.startswith("lemmas"):
        return None
    src = "include/qfoc/q15.h" if unit == "q15_unit" else f"src/{unit}.c"
    script = bundle.path("tools/gates/c_functions.py")
    if not bundle.exists(src) or not os.path.exists(script):
        return None
    try:
        res = subprocess.run([sys.executable, script, bundle.path(src)], capture_output=True,
                             text=True, timeout=30, check=False)
    except (OSError, subprocess.SubprocessError):
        return None
    return [f for f in res.stdout.strip().split(",") if f] if res.returncode == 0 else None


def collect_wp(bundle):
    sec = {"title": "Frama-C WP"}
    jpath = bundle.b("wp", "wp-summary.json")
    mpath = "proofs/wp/results.md"
    data = read_json(bundle.path(jpath))
    use_json = False
    if isinstance(data, dict) and isinstance(data.get("functions"), list):
        jm = os.path.getmtime(bundle.path(jpath))
        mm = os.path.getmtime(bundle.path(mpath)) if bundle.exists(mpath) else 0
        use_json = jm + 5 >= mm
    clean = None
    if use_json:
        sec["source"] = jpath
        sec["inputs"] = bundle.inputs(jpath, mpath)
        rows = [{"unit": f.get("unit", ""), "function": f.get("function", ""),
                 "goals": as_int(f.get("goals")), "proved": as_int(f.get("proved")),
                 "provers": f.get("provers", ""), "time_ms": as_float(f.get("time_ms"))}
                for f in data["functions"] if isinstance(f, dict)]
        clean = data.get("clean")
    elif bundle.exists(mpath):
        sec["source"] = mpath
        sec["inputs"] = bundle.inputs(mpath)
        rows = wp_rows_from_md(read_text(bundle.path(mpath)))
    else:
        sec["inputs"] = bundle.inputs(mpath)
        sec["present"] = False
        sec["summary"] = [missing_row("wp", "WP goals proved", "sec2", f"{jpath} and {mpath}")]
        return sec
    # a prove run newer than the results it fell back to (interrupted, or running)
    logs = sorted(glob.glob(os.path.join(bundle.build, "wp", "*.log")))
    if not use_json and logs and bundle.exists(mpath):
        newest = max(os.path.getmtime(p) for p in logs)
        if newest > os.path.getmtime(bundle.path(mpath)) + 5:
            sec["note"] = (f"{bundle.b('wp')} holds the logs of a later, incomplete `make prove` run "
                           f"({len(logs)} units, no wp-summary.json); the committed {mpath} is shown.")
    total = sum(r["goals"] for r in rows)
    proved = sum(r["proved"] for r in rows)
    units = sorted({r["unit"] for r in rows})
    missing_fns = []
    for unit in units:
        fns = defined_functions(bundle, unit)
        if fns is None:
            continue
        have = {r["function"] for r in rows if r["unit"] == unit}
        missing_fns += [f"{unit}:{f}" for f in fns if f not in have]
    expected_units = [os.path.basename(p)[:-2] for p in sorted(glob.glob(bundle.path("src/*.c")))]
    missing_units = [u for u in expected_units if u not in units and defined_functions(bundle, u)]
    sec.update({"present": True, "functions": rows, "goals": total, "proved": proved,
                "units": units, "clean": clean, "functions_without_result": missing_fns,
                "units_without_result": missing_units})
    ok = total > 0 and proved == total and clean is not False and not missing_fns and not missing_units
    fig = f"{proved}/{total} goals, {len(rows)} functions"
    if missing_units or missing_fns:
        fig += f"; {len(missing_units)} units, {len(missing_fns)} functions without a result"
    sec["summary"] = [row("wp", "WP goals proved", ok, fig, "sec2")]
    return sec


def collect_cbmc(bundle):
    sec = {"title": "CBMC"}
    mpath = "proofs/cbmc/results.md"
    dirs = sorted(os.path.basename(os.path.dirname(p))
                  for p in glob.glob(bundle.path("proofs/cbmc/*/harness.c")))
    res_files = sorted(glob.glob(os.path.join(bundle.build, "cbmc", "*.res")))
    res_rows = []
    for p in res_files:
        parts = (read_text(p) or "").strip().split("|")
        if len(parts) >= 6:
            res_rows.append({"harness": parts[0], "result": parts[1], "properties": as_int(parts[2]),
                             "failed": as_int(parts[3]), "unwind": parts[4], "time_s": as_int(parts[5])})
    md_rows = None
    if bundle.exists(mpath):
        t = table_with(read_text(bundle.path(mpath)), "harness", "result") or []
        md_rows = [{"harness": r.get("harness", ""), "result": r.get("result", ""),
                    "properties": as_int(r.get("properties proved", r.get("properties"))),
                    "failed": as_int(r.get("failed")), "unwind": r.get("unwind", ""),
                    "time_s": as_int(r.get("time (s)"))} for r in t]
    use_res = bool(res_rows) and (not dirs or {r["harness"] for r in res_rows} >= set(dirs)) and \
        (md_rows is None or max(os.path.getmtime(p) for p in res_files) > os.path.getmtime(bundle.path(mpath)))
    if use_res:
        rows, sec["source"] = res_rows, bundle.b("cbmc")
        sec["inputs"] = bundle.inputs(mpath) if md_rows is not None else []
    elif md_rows is not None:
        rows, sec["source"] = md_rows, mpath
        sec["inputs"] = bundle.inputs(mpath)
    else:
        sec["inputs"] = bundle.inputs(mpath)
        sec["present"] = False
        sec["summary"] = [missing_row("cbmc", "CBMC properties", "sec2", mpath)]
        return sec
    rows.sort(key=lambda r: r["harness"])
    have = {r["harness"] for r in rows}
    missing = [d for d in dirs if d not in have]
    failed_h = [r["harness"] for r in rows if r["result"].upper() != "PASS" or r["failed"]]
    props = sum(r["properties"] for r in rows)
    failed = sum(r["failed"] for r in rows)
    sec.update({"present": True, "harnesses": rows, "count": len(rows), "properties": props,
                "failed_properties": failed, "failed_harnesses": failed_h,
                "harnesses_without_result": missing})
    ok = bool(rows) and not failed_h and not missing
    fig = f"{len(rows)} harnesses, {props} properties, {failed} failed"
    if failed_h:
        fig += f" ({len(failed_h)} harnesses fail)"
    if missing:
        fig += f"; {len(missing)} harnesses without a result"
    sec["summary"] = [row("cbmc", "CBMC properties", ok, fig, "sec2")]
    return sec


def _eva_result(data):
    alarms = [a for a in as_list(data.get("rte_alarms")) if isinstance(a, dict)]
    return {"alarms": alarms, "frama_c_exit": data.get("frama_c_exit"), "seconds": data.get("seconds"),
            "unknown_properties": data.get("unknown_properties")}


def _eva_figure(res):
    n = len(res["alarms"])
    fig = f"{n} alarm{'s' if n != 1 else ''}"
    if res["frama_c_exit"] not in (0, None):
        fig += f", Frama-C exit {res['frama_c_exit']}"
    return fig


def collect_eva(bundle):
    """make eva's analysis over every table the drive accepts (build/eva/eva-all.json) is the
    result; the analysis of the reference table alone (build/eva/eva.json, make eva-reference,
    not part of make check) is shown beside it when it is there, and an alarm of it is red too."""
    sec = {"title": "Frama-C EVA"}
    jpath = bundle.b("eva", "eva-all.json")
    rpath = bundle.b("eva", "eva.json")
    data = read_json(bundle.path(jpath))
    sec["inputs"] = bundle.inputs(*[p for p in (jpath, bundle.b("eva", "eva-all.md"), bundle.b("eva", "eva-all.log"))
                                   if bundle.exists(p)] or [jpath])
    if not isinstance(data, dict):
        sec["present"] = False
        sec["summary"] = [missing_row("eva", "EVA runtime-error alarms", "sec2", jpath, bundle)]
        return sec
    res = _eva_result(data)
    sec.update({"present": True, **res})
    ok = len(res["alarms"]) == 0 and res["frama_c_exit"] in (0, None)
    fig = _eva_figure(res) + " (target 0) over every accepted table"
    if res["seconds"] is not None:
        fig += f", {res['seconds']} s"
    rdata = read_json(bundle.path(rpath)) if bundle.exists(rpath) else None
    if isinstance(rdata, dict) and inp.check(bundle.path(rpath), "eva", root=bundle.root)["state"] != inp.CURRENT:
        # an earlier make eva-reference over other sources: shown as such, not counted
        sec["reference_stale"] = True
        fig += "; reference table: result of other sources, not counted (make eva-reference)"
    elif isinstance(rdata, dict):
        ref = _eva_result(rdata)
        sec["reference"] = ref
        ok = ok and len(ref["alarms"]) == 0 and ref["frama_c_exit"] in (0, None)
        fig += "; reference table: " + _eva_figure(ref)
        sec["inputs"] = sec["inputs"] + bundle.inputs(rpath)
    elif bundle.exists(rpath):
        ok = False
        fig += f"; reference table: unreadable: {rpath}"
    sec["summary"] = [row("eva", "EVA runtime-error alarms", ok, fig, "sec2")]
    return sec


# --------------------------------------------------------------------------- 3 MISRA


def collect_misra(bundle):
    sec = {"title": "MISRA Compliance:2020"}
    jpath = bundle.b("misra", "compliance-summary.json")
    others = [bundle.b("misra", "compliance-summary.md"), bundle.b("misra", "report.md"),
              "misra/enforcement-plan.csv", "misra/deviations.md", "misra/reviews.md"]
    sec["inputs"] = bundle.inputs(jpath, *[p for p in others if bundle.exists(p)])
    sec["deviations_md"] = read_text(bundle.path("misra/deviations.md"))
    report = read_text(bundle.path(bundle.b("misra", "report.md")))
    if report:
        m = re.search(r"Unrecorded findings:\s*(\d+)", report)
        sec["cppcheck_unrecorded"] = as_int(m.group(1)) if m else None
        m = re.search(r"Suppressed findings with deviation records:\s*(\d+)", report)
        sec["cppcheck_suppressed"] = as_int(m.group(1)) if m else None
    data = read_json(bundle.path(jpath))
    if not isinstance(data, dict):
        sec["present"] = False
        sec["summary"] = [missing_row("misra", "MISRA C:2012", "sec3", jpath, bundle)]
        return sec
    counts = data.get("counts") or {}
    status = [g for g in as_list(data.get("guideline_status")) if isinstance(g, dict)]
    if not counts and status:
        for g in status:
            k = str(g.get("status", "")).lower()
            counts[k] = counts.get(k, 0) + 1
    violations = as_int(counts.get("violations"))
    deviations = as_int(counts.get("deviations"))
    disapplied = as_int(counts.get("disapplied"))
    records = [d for d in as_list(data.get("deviation_records")) if isinstance(d, dict)]
    plan_errors = as_list(data.get("plan_errors"))
    unattributed = as_list(data.get("unattributed_findings"))
    sec.update({"present": True, "counts": counts, "guidelines": status,
                "deviation_records": records, "recategorisation": as_list(data.get("recategorisation_plan")),
                "tools": data.get("tools") or {}, "framework": data.get("framework"),
                "guideline_set": data.get("guidelines"), "scope": data.get("scope"),
                "plan_errors": plan_errors, "unattributed_findings": unattributed,
                "per_method": data.get("per_method") or {}, "compliant": data.get("compliant")})
    sites = sum(as_int(d.get("sites")) for d in records)
    ok = violations == 0 and not plan_errors and not unattributed and data.get("compliant") is not False
    fig = (f"{violations} violations, {len(records)} deviation records ({sites} sites, "
           f"{deviations} guidelines), {disapplied} disapplied; {as_int(counts.get('guidelines'), len(status))} guidelines")
    if plan_errors:
        fig += f"; {len(plan_errors)} plan errors"
    if unattributed:
        fig += f"; {len(unattributed)} unattributed findings"
    sec["summary"] = [row("misra", "MISRA C:2012", ok, fig, "sec3")]
    return sec


# --------------------------------------------------------------------------- 4 coverage


def cobertura(path):
    """Per-file lines and branches of a Cobertura file: {file: {...}} and the totals."""
    try:
        tree = ET.parse(path)
    except (ET.ParseError, OSError):
        return None, None
    root = tree.getroot()
    files = {}
    for cls in root.iter("class"):
        fname = cls.get("filename") or cls.get("name") or "?"
        f = files.setdefault(fname, {"lines": 0, "lines_covered": 0, "branches": 0, "branches_covered": 0})
        for line in cls.iter("line"):
            f["lines"] += 1
            if as_int(line.get("hits")) > 0:
                f["lines_covered"] += 1
            if line.get("branch") == "true":
                m = re.search(r"\((\d+)/(\d+)\)", line.get("condition-coverage", ""))
                if m:
                    f["branches_covered"] += as_int(m.group(1))
                    f["branches"] += as_int(m.group(2))
    total = {"lines": as_int(root.get("lines-valid"), sum(f["lines"] for f in files.values())),
             "lines_covered": as_int(root.get("lines-covered"), sum(f["lines_covered"] for f in files.values())),
             "branches": as_int(root.get("branches-valid"), sum(f["branches"] for f in files.values())),
             "branches_covered": as_int(root.get("branches-covered"),
                                        sum(f["branches_covered"] for f in files.values()))}
    if root.get("lines-valid") is None:
        total = {k: sum(f[k] for f in files.values()) for k in total}
    return files, total


def collect_coverage(bundle):
    sec = {"title": "Statement and branch coverage"}
    xml_path = bundle.b("coverage", "coverage.xml")
    summ = bundle.b("coverage", "summary.txt")
    txt = bundle.b("coverage", "coverage.txt")
    sec["inputs"] = bundle.inputs(*[p for p in (xml_path, summ, txt) if bundle.exists(p)] or [xml_path])
    if bundle.exists(bundle.b("coverage", "index.html")):
        sec["html"] = bundle.art(bundle.b("coverage"))
    files, total = (None, None)
    if bundle.exists(xml_path):
        files, total = cobertura(bundle.path(xml_path))
    if total is None and bundle.exists(summ):
        text = read_text(bundle.path(summ)) or ""
        lm = re.search(r"lines:\s*[\d.]+%\s*\((\d+) out of (\d+)\)", text)
        bm = re.search(r"branches:\s*[\d.]+%\s*\((\d+) out of (\d+)\)", text)
        if lm and bm:
            total = {"lines_covered": as_int(lm.group(1)), "lines": as_int(lm.group(2)),
                     "branches_covered": as_int(bm.group(1)), "branches": as_int(bm.group(2))}
            files = {}
    if total is None:
        sec["present"] = False
        sec["summary"] = [missing_row("statement", "statement coverage", "sec4", xml_path, bundle),
                          missing_row("branch", "branch coverage", "sec4", xml_path, bundle)]
        return sec
    lp = pct(total["lines_covered"], total["lines"])
    bp = pct(total["branches_covered"], total["branches"])
    sec.update({"present": True, "files": files, "total": total, "statement_percent": lp,
                "branch_percent": bp, "target_percent": 100.0})
    sec["summary"] = [
        row("statement", "statement coverage", total["lines"] > 0 and total["lines_covered"] == total["lines"],
            f"{fmt_pct(lp)} ({total['lines_covered']}/{total['lines']} lines, target 100 %)", "sec4"),
        row("branch", "branch coverage", total["branches"] > 0 and total["branches_covered"] == total["branches"],
            f"{fmt_pct(bp)} ({total['branches_covered']}/{total['branches']} branches, target 100 %)", "sec4")]
    return sec


def collect_mcdc(bundle):
    sec = {"title": "MC/DC"}
    jpath = bundle.b("mcdc", "mcdc.json")
    justif = "specs/mcdc-justifications.md"
    sec["inputs"] = bundle.inputs(*[p for p in (jpath, bundle.b("mcdc", "mcdc.md"), bundle.b("mcdc", "toolchain.txt"),
                                                justif) if bundle.exists(p)] or [jpath])
    data = read_json(bundle.path(jpath))
    if not isinstance(data, dict):
        sec["present"] = False
        sec["summary"] = [missing_row("mcdc", "MC/DC coverage", "sec4", jpath, bundle)]
        return sec
    s = data.get("summary") or {}
    scopes = {k: s.get(k) for k in ("src", "include") if isinstance(s.get(k), dict)}
    outcomes = sum(as_int(v.get("outcomes")) for v in scopes.values())
    covered = sum(as_int(v.get("covered")) for v in scopes.values())
    justified = sum(as_int(v.get("justified")) for v in scopes.values())
    files = data.get("files") if isinstance(data.get("files"), dict) else {}
    if not scopes and files:
        outcomes = sum(as_int(f.get("outcomes")) for f in files.values())
        covered = sum(as_int(f.get("covered")) for f in files.values())
        justified = sum(as_int(f.get("justified")) for f in files.values())
    uncovered = []
    for d in as_list(data.get("decisions")):
        if not isinstance(d, dict):
            continue
        for o in as_list(d.get("outcomes")):
            if isinstance(o, dict) and not o.get("covered"):
                uncovered.append({"file": d.get("file"), "line": d.get("line"), "function": d.get("function"),
                                  "decision": d.get("decision"), "condition": o.get("text"),
                                  "outcome": o.get("outcome"), "justification": o.get("justification")})
    unjustified = as_int(s.get("unjustified"), sum(1 for u in uncovered if not u["justification"]))
    unused = as_list(s.get("unused_justifications"))
    p = pct(covered, outcomes)
    sec.update({"present": True, "scopes": scopes, "outcomes": outcomes, "covered": covered,
                "justified": justified, "percent": p, "percent_with_justified": pct(covered + justified, outcomes),
                "files": files, "uncovered": uncovered, "unjustified": unjustified,
                "unused_justifications": unused, "not_instrumented": as_list(data.get("not_instrumented")),
                "tool": s.get("tool"), "criterion": s.get("criterion"), "min_percent": s.get("min_percent")})
    ok = outcomes > 0 and covered + justified == outcomes and unjustified == 0 and not unused
    fig = f"{fmt_pct(p, 2)} ({covered}/{outcomes} condition outcomes, target 100 %), {justified} justified exclusions"
    if unjustified:
        fig += f", {unjustified} not justified"
    if unused:
        fig += f", {len(unused)} stale justifications"
    sec["summary"] = [row("mcdc", "MC/DC coverage", ok, fig, "sec4")]
    return sec


# --------------------------------------------------------------------------- 5 tests


def junit_file(path):
    """Counts and test records of one JUnit XML file (any of the usual dialects)."""
    try:
        root = ET.parse(path).getroot()
    except (ET.ParseError, OSError) as e:
        return {"error": f"unreadable: {e}"}
    suites = [root] if root.tag == "testsuite" else list(root.iter("testsuite"))
    rec = {"suites": [], "tests": 0, "failures": 0, "errors": 0, "skipped": 0, "time": None,
           "failed_tests": [], "test_names": []}
    for s in suites:
        cases = [c for c in s if c.tag == "testcase"]
        c_fail = c_err = c_skip = 0
        t_sum = None
        for c in cases:
            name = (c.get("classname") + "." if c.get("classname") else "") + (c.get("name") or "?")
            rec["test_names"].append(name)
            if c.find("failure") is not None:
                c_fail += 1
                rec["failed_tests"].append(name)
            elif c.find("error") is not None:
                c_err += 1
                rec["failed_tests"].append(name + " (error)")
            elif c.find("skipped") is not None:
                c_skip += 1
            if c.get("time") is not None:
                t_sum = (t_sum or 0.0) + (as_float(c.get("time"), 0.0) or 0.0)
        tests = max(as_int(s.get("tests"), len(cases)), len(cases))
        fails = max(as_int(s.get("failures")), c_fail)
        errs = max(as_int(s.get("errors")), c_err)
        skips = max(as_int(s.get("skipped", s.get("skip"))), c_skip)
        t = as_float(s.get("time"), t_sum)
        rec["suites"].append(s.get("name") or "?")
        rec["tests"] += tests
        rec["failures"] += fails
        rec["errors"] += errs
        rec["skipped"] += skips
        if t is not None:
            rec["time"] = (rec["time"] or 0.0) + t
    if not suites and root.tag == "testsuites":
        rec["tests"] = as_int(root.get("tests"))
        rec["failures"] = as_int(root.get("failures"))
        rec["errors"] = as_int(root.get("errors"))
    return rec


def collect_tests(bundle):
    sec = {"title": "Tests"}
    jdir = os.path.join(bundle.build, "junit")
    paths = sorted(glob.glob(os.path.join(jdir, "**", "*.xml"), recursive=True))
    files = []
    for p in paths:
        rec = junit_file(p)
        rec["file"] = bundle.rel(p)
        rec["link"] = bundle.art(p)
        files.append(rec)
    runs = sorted(d for d in (inp.run_date(p) for p in paths) if d)
    sec["inputs"] = [{"path": bundle.b("junit") + "/**/*.xml", "present": bool(paths),
                      "run": (runs[0] if runs[0] == runs[-1] else f"{runs[0]} .. {runs[-1]}")
                      if runs else None, "link": None}]
    sec["files"] = files
    # the demonstration (build/demo): linked, with each scenario's result
    demo_index = bundle.b("demo", "index.html")
    if bundle.exists(demo_index):
        sec["demo_link"] = bundle.art(bundle.b("demo"))
        scen = []
        order = (read_json(bundle.path(bundle.b("demo", "summary.json"))) or {}).get("scenarios") or []
        for mpath in sorted(glob.glob(os.path.join(bundle.build, "demo", "*", "metrics.json"))):
            m = read_json(mpath) or {}
            scen.append({"scenario": m.get("scenario") or os.path.basename(os.path.dirname(mpath)),
                         "title": m.get("title", ""), "pass": m.get("pass"),
                         "requirements": as_list(m.get("requirements"))})
        scen.sort(key=lambda s: order.index(s["scenario"]) if s["scenario"] in order else len(order))
        sec["demo"] = scen
    camp = read_json(bundle.path(bundle.b("robustness", "campaign.json")))
    if isinstance(camp, dict) and bundle.exists(bundle.b("robustness", "index.html")):
        sec["robustness"] = {k: camp.get(k) for k in ("count", "successes", "rate_pct", "table", "criteria")}
        sec["robustness_link"] = bundle.art(bundle.b("robustness"))
    if not paths:
        sec["present"] = False
        sec["summary"] = [missing_row("tests", "tests passed", "sec5", f"{bundle.b('junit')}/*.xml")]
        return sec
    total = sum(f.get("tests", 0) for f in files)
    fails = sum(f.get("failures", 0) for f in files)
    errs = sum(f.get("errors", 0) for f in files)
    skips = sum(f.get("skipped", 0) for f in files)
    bad_files = [f["file"] for f in files if f.get("error")]
    passed = total - fails - errs - skips
    sec.update({"present": True, "tests": total, "passed": passed, "failures": fails, "errors": errs,
                "skipped": skips, "unreadable": bad_files})
    ok = total > 0 and fails == 0 and errs == 0 and not bad_files
    fig = f"{passed}/{total} passed, {fails} failures, {errs} errors"
    if skips:
        fig += f", {skips} skipped"
    fig += f" ({len(files)} JUnit files)"
    if bad_files:
        fig += f"; {len(bad_files)} unreadable"
    sec["summary"] = [row("tests", "tests passed", ok, fig, "sec5")]
    return sec


def collect_target_test(bundle):
    sec = {"title": "Target equivalence"}
    tpath = bundle.b("target_test", "target.txt")
    extra = [bundle.b("target_test", n) for n in ("host.txt", "host_ubsan.txt", "vectors.txt", "target_selftest.txt")]
    sec["inputs"] = bundle.inputs(tpath, *[p for p in extra if bundle.exists(p)])
    text = read_text(bundle.path(tpath))
    if text is None:
        sec["present"] = False
        sec["summary"] = [missing_row("target_equivalence", "target equivalence", "sec5", tpath, bundle)]
        return sec
    groups = []
    for line in text.splitlines():
        m = re.match(r"^(\w+): (\d+) vectors, (identical)$", line.strip())
        if m:
            groups.append({"group": m.group(1), "vectors": as_int(m.group(2)), "result": "identical"})
            continue
        m = re.match(r"^(\w+): DIFFERENT: (.*)$", line.strip())
        if m and m.group(1) != "result":
            groups.append({"group": m.group(1), "vectors": None, "result": "DIFFERENT: " + m.group(2)})
    result = next((ln for ln in text.splitlines() if ln.startswith("result:")), "")
    header = text.splitlines()[0] if text.strip() else ""
    same = [g for g in groups if g["result"] == "identical"]
    vectors = sum(g["vectors"] or 0 for g in same)
    sec.update({"present": True, "groups": groups, "result": result, "header": header})
    ok = bool(groups) and len(same) == len(groups) and "all identical" in result
    sec["summary"] = [row("target_equivalence", "target equivalence", ok,
                          f"{len(same)}/{len(groups)} groups, {vectors} vectors bit-identical on the Cortex-M4F",
                          "sec5")]
    return sec


# --------------------------------------------------------------------------- 6 bench


def collect_bench(bundle):
    sec = {"title": "Resource usage"}
    jpath = bundle.b("bench", "bench.json")
    sec["inputs"] = bundle.inputs(*[p for p in (jpath, bundle.b("bench", "bench.md")) if bundle.exists(p)] or [jpath])
    data = read_json(bundle.path(jpath))
    if not isinstance(data, dict):
        sec["present"] = False
        sec["summary"] = [missing_row("bench", "resource usage (bench)", "sec6", jpath, bundle)]
        return sec
    table = [r for r in as_list(data.get("table")) if isinstance(r, dict)]
    limited = [r for r in table if r.get("limit") is not None]
    met = [r for r in limited if str(r.get("result", "")).upper() in ("OK", "PASS")]

    def rows_max(pred, unit=None):
        vals = [as_int(r.get("max"), None) for r in table if pred(str(r.get("item", "")))
                and (unit is None or r.get("unit") == unit)]
        vals = [v for v in vals if v is not None]
        return max(vals) if vals else None

    sizes = data.get("sizes") if isinstance(data.get("sizes"), dict) else {}
    stack = data.get("stack") if isinstance(data.get("stack"), dict) else {}
    fast = rows_max(lambda s: "qfoc_drive_fast_step" in s and not s.startswith("stack"), "instructions")
    flash = sizes.get("lib_text_rodata", rows_max(lambda s: s.startswith("library flash, all")))
    flash_linked = sizes.get("drive_linked")
    ram = sizes.get("sizeof_drive", rows_max(lambda s: s.startswith("RAM per motor")))
    st = (stack.get("qfoc_drive_fast_step") or {}).get("bytes") if isinstance(stack.get("qfoc_drive_fast_step"), dict) \
        else rows_max(lambda s: s.startswith("stack, `qfoc_drive_fast_step`"))
    goals = [r for r in table if r.get("goal") is not None]
    goals_met = [r for r in goals if str(r.get("goal_result", "")).upper() in ("OK", "PASS", "MET")]
    sec.update({"present": True, "table": table, "limits": len(limited), "limits_met": len(met),
                "goals": len(goals), "goals_met": len(goals_met),
                "over": [r.get("item") for r in limited if r not in met],
                "fast_step_instructions": fast, "flash_bytes": flash, "flash_linked_bytes": flash_linked,
                "ram_per_motor_bytes": ram, "fast_step_stack_bytes": st, "compiler": data.get("cc"),
                "has_goal": any("goal" in r for r in table)})
    ok = len(limited) > 0 and len(met) == len(limited)

    def val(v, unit):
        return "-" if v is None else f"{v} {unit}"

    fig = (f"limits met {len(met)}/{len(limited)}"
           + (f" (goals met {len(goals_met)}/{len(goals)}, reported only)" if goals else "")
           + f"; fast step {val(fast, 'instructions')}, "
           f"flash {val(flash, 'B')}, RAM {val(ram, 'B')} per motor, stack {val(st, 'B')}")
    sec["summary"] = [row("bench", "resource usage (bench)", ok, fig, "sec6")]
    return sec


# --------------------------------------------------------------------------- 7 static


def accepted_reason(result):
    for s in as_list(result.get("suppressions")):
        if isinstance(s, dict) and s.get("status", "accepted") == "accepted" and s.get("kind") != "inSource":
            just = str(s.get("justification", ""))
            m = re.match(r"^[^,]*,\s*(.*?):\s", just)
            return (m.group(1) if m else just[:120]) or "accepted", just
    return None, None


def collect_static(bundle):
    sec = {"title": "Static analysis"}
    spath = bundle.b("static", "qfoc.sarif")
    extra = [bundle.b("static", "static.md"), "specs/static-accepted.md"]
    sec["inputs"] = bundle.inputs(spath, *[p for p in extra if bundle.exists(p)])
    data = read_json(bundle.path(spath))
    if not isinstance(data, dict) or not isinstance(data.get("runs"), list):
        sec["present"] = False
        sec["summary"] = [missing_row("static", "static analysis", "sec7", spath, bundle)]
        return sec
    tools, rules, unaccepted = [], {}, []
    for run in data["runs"]:
        drv = ((run.get("tool") or {}).get("driver") or {})
        name = drv.get("name", "?")
        invs = as_list(run.get("invocations"))
        ran = all(truthy(i.get("executionSuccessful", True)) for i in invs if isinstance(i, dict)) if invs else None
        results = [r for r in as_list(run.get("results")) if isinstance(r, dict)]
        acc = 0
        for r in results:
            rid = r.get("ruleId", "?")
            reason, just = accepted_reason(r)
            key = (name, rid)
            rr = rules.setdefault(key, {"tool": name, "rule": rid, "findings": 0, "accepted": 0, "reasons": {}})
            rr["findings"] += 1
            if reason:
                acc += 1
                rr["accepted"] += 1
                rr["reasons"][reason] = just
            else:
                loc = ((as_list(r.get("locations")) or [{}])[0].get("physicalLocation") or {})
                uri = (loc.get("artifactLocation") or {}).get("uri", "?")
                line = (loc.get("region") or {}).get("startLine", "")
                unaccepted.append({"tool": name, "rule": rid, "where": f"{uri}:{line}",
                                   "message": (r.get("message") or {}).get("text", "")})
        tools.append({"tool": name, "version": drv.get("version", ""), "ran": ran,
                      "findings": len(results), "accepted": acc, "unaccepted": len(results) - acc})
    total = sum(t["findings"] for t in tools)
    acc = sum(t["accepted"] for t in tools)
    not_ran = [t["tool"] for t in tools if t["ran"] is False]
    rule_list = []
    for (_tool, _rid), r in sorted(rules.items()):
        r = dict(r)
        r["reasons"] = [{"reason": k, "justification": v} for k, v in r["reasons"].items()]
        rule_list.append(r)
    sec.update({"present": True, "tools": tools, "rules": rule_list, "findings": total, "accepted": acc,
                "unaccepted": unaccepted, "tools_failed": not_ran})
    ok = bool(tools) and not unaccepted and not not_ran
    per_tool = ", ".join("%s %d" % (t["tool"], t["findings"]) for t in tools)
    fig = f"{total} findings ({per_tool}), {acc} accepted, {len(unaccepted)} unaccepted"
    if not_ran:
        fig += f"; did not run: {', '.join(not_ran)}"
    sec["summary"] = [row("static", "static analysis", ok, fig, "sec7")]
    return sec


# --------------------------------------------------------------------------- 8 .. 11


def collect_tools(bundle):
    sec = {"title": "Tool confidence"}
    jpath, mpath = "specs/tool-confidence.json", "specs/tool-confidence.md"
    sec["inputs"] = bundle.inputs(*[p for p in (jpath, mpath) if bundle.exists(p)] or [jpath])
    data = read_json(bundle.path(jpath))
    if isinstance(data, dict):
        data = data.get("tools", [])
    sec["tools"] = [t for t in as_list(data) if isinstance(t, dict)]
    sec["present"] = bool(sec["tools"])
    script = bundle.path("tools/evidence/tool_versions.sh")
    sec["versions"] = None
    if os.path.exists(script):
        try:
            res = subprocess.run(["sh", script], cwd=bundle.root, capture_output=True, text=True,
                                 timeout=300, check=False)
            sec["versions"] = res.stdout
            sec["versions_exit"] = res.returncode
        except (OSError, subprocess.SubprocessError) as e:
            sec["versions_error"] = str(e)
    if sec["versions"] is not None:
        os.makedirs(bundle.out, exist_ok=True)
        with open(os.path.join(bundle.out, "tool-versions.txt"), "w", encoding="utf-8") as f:
            f.write(sec["versions"])
        sec["versions_link"] = "tool-versions.txt"
    return sec


def collect_manual(bundle):
    path = "specs/safety-manual.md"
    sec = {"title": "Safety manual", "inputs": bundle.inputs(path)}
    sec["text"] = read_text(bundle.path(path))
    sec["present"] = sec["text"] is not None
    return sec


def collect_repro(bundle):
    sec = {"title": "Reproducibility"}
    jpath = bundle.b("repro", "repro.json")
    sec["inputs"] = bundle.inputs(*[p for p in (jpath, bundle.b("repro", "a.log"), bundle.b("repro", "b.log"))
                                   if bundle.exists(p)] or [jpath])
    data = read_json(bundle.path(jpath))
    if not isinstance(data, dict):
        sec["present"] = False
        sec["summary"] = [missing_row("repro", "reproducible build", "sec10", jpath, bundle)]
        return sec
    arts = [a for a in as_list(data.get("artefacts")) if isinstance(a, dict)]
    same = all(truthy(a.get("identical")) for a in arts) and bool(arts)
    for a in arts:
        # the artefact of the main build tree, for comparison (not part of the verdict)
        cur = os.path.join(bundle.build, str(a.get("file", "")))
        a["build_file"] = bundle.rel(cur)
        a["build_sha256"] = sha256_file(cur)
    sec.update({"present": True, "compiler": data.get("compiler"), "artefacts": arts, "identical": same})
    shas = ", ".join(f"{os.path.basename(str(a.get('file')))} {str(a.get('sha256', ''))[:12]}" for a in arts)
    fig = f"identical: {'yes' if same else 'no'} ({len(arts)} artefacts; {shas})"
    moved = [os.path.basename(str(a.get("file"))) for a in arts
             if a.get("build_sha256") and a.get("build_sha256") != a.get("sha256")]
    if moved:
        fig += f"; {bundle.b()} now differs: {', '.join(moved)}"
    sec["summary"] = [row("repro", "reproducible build", same, fig, "sec10")]
    return sec


def sha256_file(path):
    try:
        h = hashlib.sha256()
        with open(path, "rb") as f:
            for chunk in iter(lambda: f.read(1 << 16), b""):
                h.update(chunk)
        return h.hexdigest()
    except OSError:
        return None


def collect_gates(bundle):
    sec = {"title": "Gate log (make check)"}
    spath = bundle.b("check-summary.txt")
    sec["inputs"] = bundle.inputs(spath)
    text = read_text(bundle.path(spath))
    if text is None:
        sec["present"] = False
        return sec
    gates = []
    for line in text.splitlines():
        m = re.match(r"^(\S+)\s+(PASS|FAIL)\s+(\d+)s\s*(.*)$", line)
        if m:
            log = bundle.b(f"check-{m.group(1)}.log")
            gates.append({"gate": m.group(1), "result": m.group(2), "seconds": as_int(m.group(3)),
                          "last_line": m.group(4), "log": bundle.art(log) if bundle.exists(log) else None})
    sec.update({"present": True, "gates": gates, "failed": [g["gate"] for g in gates if g["result"] != "PASS"]})
    return sec


def git_info(root):
    def git(*args):
        try:
            r = subprocess.run(["git", "-C", root, *args], capture_output=True, text=True, timeout=30,
                               check=False)
        except (OSError, subprocess.SubprocessError):
            return None
        return r.stdout.strip() if r.returncode == 0 else None

    head = git("rev-parse", "HEAD")
    status = git("status", "--porcelain", "--untracked-files=no") if head else None
    return {"commit": head or "unknown (not a git checkout)",
            "dirty": None if status is None else bool(status),
            "branch": git("rev-parse", "--abbrev-ref", "HEAD") if head else None}


# --------------------------------------------------------------------------- review records


def review_figure(res, noun):
    """'41 records, every one current' or '41 records: 3 stale (Dir 4.1: ...), ...'."""
    n = len(res["records"])
    noun = noun if n != 1 else noun[:-1]
    bad = [r for r in res["records"] if r["state"] != rs.CURRENT]
    if not bad and not res["errors"]:
        return f"{n} {noun}, every one tied to the files it reviewed"
    by = {}
    for r in bad:
        by.setdefault(r["state"], []).append(r)
    parts = []
    for st in (rs.STALE, rs.UNSTAMPED, rs.INVALID):
        if st in by:
            ids = ", ".join(r["id"] for r in by[st][:6]) + (", ..." if len(by[st]) > 6 else "")
            parts.append(f"{len(by[st])} {st} ({ids})")
    fig = f"{n} {noun}: {n - len(bad)} current, " + ", ".join(parts) if parts else f"{n} {noun}"
    if res["errors"]:
        fig += "; " + "; ".join(res["errors"])
    return fig


def review_check(res):
    """The check of a document without the per-file digests (they are in its manifest)."""
    for r in res["records"]:
        r.pop("hashes", None)
    return res


def collect_reviews(bundle):
    """The MISRA review records of misra/reviews.md, each current or stale against the files
    it reviewed (tools/evidence/review_stamp.py, REQ-EVD-031)."""
    sec = {"title": "MISRA review records"}
    res = rs.check("misra", bundle.root)
    sec["inputs"] = bundle.inputs(*[p for p in (res["path"], res["manifest"]) if bundle.exists(p)]
                                  or [res["path"]])
    if not res["present"]:
        sec["present"] = False
        sec["summary"] = [missing_row("reviews", "MISRA review records", "sec3", res["path"])]
        return sec
    sec.update({"present": True, "check": review_check(res)})
    fig = review_figure(res, "records")
    first = next((r for r in res["records"] if r["state"] != rs.CURRENT), None)
    if first is not None:
        why = f"{first['id']}: " + "; ".join(first["reasons"])
        fig += "; STALE: " + (why if len(why) <= 160 else why[:157] + "...")
    sec["summary"] = [row("reviews", "MISRA review records", rs.ok(res), fig, "sec3")]
    return sec


def collect_fmea(bundle):
    """The rows of the software FMEA (specs/safety-analysis.md, section 2), each current or
    stale against its code and requirement files (tools/evidence/review_stamp.py); the
    verdicts of the requirements each row names are added by apply_fmea_verdicts."""
    sec = {"title": "Software FMEA"}
    res = rs.check("fmea", bundle.root)
    sec["inputs"] = bundle.inputs(*[p for p in (res["path"], res["manifest"]) if bundle.exists(p)]
                                  or [res["path"]])
    if not res["present"]:
        sec["present"] = False
        sec["summary"] = [missing_row("fmea", "software FMEA rows", "sec14", res["path"])]
        return sec
    sec.update({"present": True, "check": review_check(res)})
    return sec


def apply_fmea_verdicts(bundle, secs):
    """Each FMEA row with the verdicts of the requirements it names (those of the matrix,
    tools/evidence/verdict.py; 'not run' without a matrix) and the row's own verdict: green
    only when the row is current and every one of its requirements verified."""
    sec = secs.get("fmea") or {}
    if not sec.get("present"):
        return
    tr = secs.get("trace") or {}
    by_id = {r["id"]: r.get("verdict") or (vd.VERIFIED if r.get("verified") else vd.NOT_RUN)
             for r in tr.get("requirements") or []} if tr.get("present") else None
    links = {r["id"]: r.get("req_link") for r in tr.get("requirements") or []} if tr.get("present") else {}
    rows = []
    for r in sec["check"]["records"]:
        reqs = []
        for rid in r["reqs"]:
            if by_id is None:
                v = vd.NOT_RUN
            else:
                v = by_id.get(rid, vd.NO_EVIDENCE)
            reqs.append({"id": rid, "verdict": v, "link": links.get(rid)})
        verdict = vd.combine([x["verdict"] for x in reqs])
        rows.append(dict(r, req_verdicts=reqs, verdict=verdict,
                         ok=r["state"] == rs.CURRENT and verdict == vd.VERIFIED))
    sec["rows"] = rows
    res = sec["check"]
    fig = review_figure(res, "rows")
    unverified = [r for r in rows if r["verdict"] != vd.VERIFIED]
    if unverified:
        ids = ", ".join(f"{r['id']} {r['verdict']}" for r in unverified[:6]) + (", ..." if len(unverified) > 6 else "")
        fig += f"; {len(unverified)} with a requirement not verified ({ids})"
    else:
        fig += "; every requirement they name verified"
    if by_id is None:
        fig += " (no traceability matrix: build/trace/trace.json)"
    sec["verified_rows"] = len(rows) - len(unverified)
    sec["summary"] = [row("fmea", "software FMEA rows", rs.ok(res) and not unverified, fig, "sec14")]


# --------------------------------------------------------------------------- results tied to sources


# (section, gate of tools/evidence/inputs.py): the sections whose result files the gates stamp
# with the SHA-256 of their inputs (REQ-EVD-028)
STAMPED = (("wp", "wp"), ("cbmc", "cbmc"), ("eva", "eva"), ("misra", "misra"), ("coverage", "coverage"),
           ("bench", "bench"))


def stamped_file(bundle, key, sec):
    """The result file whose stamp ties a section to its inputs (None: rows from files that
    carry no stamp, the per-harness files of an unfinished CBMC run)."""
    if key == "wp":
        return sec.get("source") or "proofs/wp/results.md"
    if key == "cbmc":
        src = sec.get("source") or ""
        return src if src.endswith(".md") else None
    if key == "coverage":
        x = bundle.b("coverage", "coverage.xml")
        return x if bundle.exists(x) else bundle.b("coverage", "summary.txt")
    return {"eva": bundle.b("eva", "eva-all.json"), "misra": bundle.b("misra", "compliance-summary.json"),
            "bench": bundle.b("bench", "bench.json")}[key]


def stale_reason(st):
    if st["state"] == inp.UNSTAMPED:
        return "no inputs stamp, not tied to the sources it was computed from"
    text = "; ".join(st.get("reasons") or ["inputs changed since the run"])
    return text if len(text) <= 160 else text[:157] + "..."


def apply_staleness(bundle, secs):
    """Compare each stamped result with its inputs now (tools/evidence/inputs.py): a result
    whose inputs changed since its run, or that carries no stamp, is STALE and its summary
    rows are red, whatever its figures."""
    for key, gate in STAMPED:
        sec = secs.get(key) or {}
        if not sec.get("present"):
            continue
        path = stamped_file(bundle, key, sec)
        if path is None:
            st = {"state": inp.UNSTAMPED, "gate": gate, "run": None, "recorded": None, "now": None,
                  "reasons": [f"rows from the per-harness files of {bundle.b('cbmc')}, which carry no "
                              "inputs stamp"]}
        else:
            st = inp.check(bundle.path(path), gate, root=bundle.root)
            man = inp.manifest_path(bundle.path(path), gate)
            if os.path.exists(man):
                st["manifest"] = bundle.art(man)
        st["file"] = path
        sec["stamp"] = st
        if st["state"] == inp.CURRENT:
            continue
        for r in sec.get("summary", []):
            r["status"] = "FAIL"
            r["stale"] = True
            r["figure"] = f"{r['figure']}; STALE: {stale_reason(st)}"


def stamp_html(sec):
    st = sec.get("stamp")
    if not st:
        return ""
    where = f"<code>{esc(st.get('file'))}</code>"
    man = f" (inputs: {link(st['manifest'], 'list')})" if st.get("manifest") else ""
    if st["state"] == inp.CURRENT:
        return (f"<p class=small><span class=st-ok>tied to the current sources</span>: {where} was computed "
                f"{esc(st.get('run'))} from inputs sha256 <code>{esc(st.get('now'))}</code>{man}, the same as "
                f"now (<code>python3 tools/evidence/inputs.py --check {esc(st.get('file'))}</code>).</p>")
    reasons = "".join(f"<li>{esc(x)}</li>" for x in st.get("reasons") or [])
    run = f" run {esc(st['run'])}" if st.get("run") else ""
    return (f"<div class=small><p class=missing>STALE: {where}{run} is not tied to the current sources; "
            f"its figures are shown, never green.{man}</p><ul>{reasons}</ul></div>")


# --------------------------------------------------------------------------- requirement verdicts


def verdict_results(bundle, secs):
    """What the verdicts read: this run's JUnit cases, the WP and CBMC rows with the state of
    their stamp, the bench rows, the demonstration's scenarios, the robustness campaign."""
    paths = sorted(glob.glob(os.path.join(bundle.build, "junit", "**", "*.xml"), recursive=True))

    def proof(key, rows_key):
        sec = secs.get(key) or {}
        if not sec.get("present"):
            return {"state": "absent", "rows": []}
        return {"state": (sec.get("stamp") or {}).get("state", inp.UNSTAMPED), "rows": sec.get(rows_key) or []}

    bench = secs.get("bench") or {}
    tests = secs.get("tests") or {}
    return {
        "junit": vd.junit_cases(paths),
        "wp": proof("wp", "functions"), "cbmc": proof("cbmc", "harnesses"),
        "bench": {"state": (bench.get("stamp") or {}).get("state", inp.UNSTAMPED),
                  "rows": bench.get("table") or []} if bench.get("present") else None,
        "demo": {d["scenario"]: d.get("pass") for d in tests["demo"]} if "demo" in tests else None,
        "robustness": tests.get("robustness"),
    }


def apply_verdicts(bundle, secs):
    """The verdict of every requirement from the results (tools/evidence/verdict.py), and the
    requirements summary row: green only when every requirement is verified."""
    sec = secs.get("trace") or {}
    sec["strict"] = bool(getattr(bundle, "strict", False))
    if not sec.get("present"):
        return
    results = verdict_results(bundle, secs)
    by = {}
    for r in sec["requirements"]:
        raw = r.pop("raw", None) or {}
        v = vd.requirement_verdict(r["id"], raw, results)
        r.update({"verdict": v["verdict"], "verified": v["verdict"] == vd.VERIFIED,
                  "proof_items": v["proofs"], "test_items": v["tests"], "scenario_items": v["scenarios"]})
        r["req_link"] = bundle.art(r["req_file"]) if r.get("req_file") and bundle.exists(r["req_file"]) else None
        for x in v["proofs"] + v["tests"] + v["scenarios"]:
            f = x.get("file")
            if x["kind"] in ("WP", "WP helper"):
                f = (secs.get("wp") or {}).get("source")
            elif x["kind"] == "scenario" and x["status"] != vd.NOT_RUN and x["detail"].endswith(".json"):
                f = x["detail"]
            x["link"] = bundle.art(f) if f and bundle.exists(f) else None
        by[v["verdict"]] = by.get(v["verdict"], 0) + 1
    n = len(sec["requirements"])
    v = by.get(vd.VERIFIED, 0)
    sec["verified"] = v
    sec["verdicts"] = by
    failures = sec.get("gate_failures") or []
    if n:
        fig = f"{v}/{n} verified"
        rest = [f"{by[k]} {k}" for k in (vd.FAILED, vd.STALE, vd.NOT_RUN, vd.NO_EVIDENCE) if by.get(k)]
        if rest:
            fig += "; " + ", ".join(rest)
        if failures:
            fig += f"; {len(failures)} trace gate failures"
        sec["summary"] = [row("requirements", "requirements verified", v == n and not failures, fig, "sec1")]


def status_class(status, strict=False):
    if status in vd.OK_STATUSES or status == vd.VERIFIED:
        return "st-ok"
    if status in (vd.NOT_RUN, vd.NO_RESULT) and not strict:
        return "st-nr"
    return "st-bad"


def items_html(items, strict=False):
    """The proofs or tests of a requirement, each with its status, under a count line."""
    if not items:
        return "-"
    worst = vd.verdict_of([x["status"] for x in items])
    lines = [f"<span class={status_class(x['status'], strict)}>{esc(x['status'])}</span> "
             + (f"{esc(x['kind'])} " if x["kind"] in ("WP", "WP helper", "CBMC") else "")
             + link(x.get("link"), x["name"]) + f" <span class=meta>({esc(x.get('detail'))})</span>"
             for x in items]
    return (f"<details{' open' if worst != vd.VERIFIED and len(items) <= 3 else ''}><summary "
            f"class={status_class(worst, strict)}>{esc(vd.counts(items))}</summary>"
            + "<br>".join(lines) + "</details>")


def matrix_row_html(r, strict=False):
    """One requirement of the matrix: its proofs, tests and scenarios with their status, and
    its verdict (not run: amber, red under --strict)."""
    v = r.get("verdict") or (vd.VERIFIED if r.get("verified") else vd.NOT_RUN)
    c = "pass" if v == vd.VERIFIED else ("notrun" if v == vd.NOT_RUN and not strict else "fail")
    contracts = (f"<td>{details_list(r['contracts'])}</td>" if r["contracts"] else
                 f"<td class=meta>{('named in ' + esc(', '.join(r['named_in']))) if r['named_in'] else '-'}</td>")
    if r.get("scenario_items"):
        scen = items_html(r["scenario_items"], strict)
    elif r.get("scenarios"):
        scen = details_list(r["scenarios"]) + " <span class=meta>(from the demonstration; not in the verdict)</span>"
    else:
        scen = "-"
    return (f"<tr class={c}><td>{link(r.get('req_link'), r['id'])}</td>" + td(r["title"]) + contracts
            + f"<td>{items_html(r.get('proof_items'), strict)}</td>"
            + f"<td>{items_html(r.get('test_items'), strict)}</td><td>{scen}</td>"
            + f"<td class='s {c}'>{esc(v)}</td></tr>")


def verdict_rule_html(sec):
    by = sec.get("verdicts") or {}
    counts = ", ".join(f"{by[k]} {k}" for k in (vd.VERIFIED, vd.FAILED, vd.STALE, vd.NOT_RUN, vd.NO_EVIDENCE)
                       if by.get(k))
    return ("<p class=small>Verdict (<code>tools/evidence/verdict.py</code>): a requirement is <b>verified</b> "
            "only when every proof it names is <i>proved</i> in results tied to the current sources (their "
            "inputs stamp is current) and every test it names <i>passed</i> in this run's results "
            "(<code>build/junit/*.xml</code>, <code>build/bench/bench.json</code>, the demonstration's and the "
            "robustness campaign's results). Otherwise: <b>failed</b> (a proof or test failed), <b>stale</b> "
            "(a result not tied to the current sources), <b>not run</b> (a test or proof without a result; "
            + ("red: <code>--strict</code>" if sec.get("strict") else "amber here, red under "
               "<code>EVIDENCE_STRICT=1</code>")
            + "), <b>no evidence</b> (it names no proof and no test). " + (f"Here: {esc(counts)}." if counts else "")
            + "</p>")


# --------------------------------------------------------------------------- the archive


MANIFEST = "MANIFEST.sha256"

# What the bundle holds besides the results, so that an assessor who receives the folder can
# read what was verified (REQ-EVD-029): (group, patterns relative to the root)
ARCHIVE = (
    ("requirements", ("specs/requirements/*.md",)),
    ("contracts: the public headers", ("include/qfoc/*.h",)),
    ("library sources", ("src/*.c",)),
    ("ACSL specifications", ("specs/*.acsl",)),
    ("work products: specifications, safety manual, tool confidence, architecture",
     ("specs/*.md", "specs/*.json", "specs/*.toml", "specs/*.sha256", "specs/motors/*.toml")),
    ("unit tests (CMocka)", ("tests/*.c", "tests/*.h")),
    ("pytest tests", ("tools/*/tests/*.py",)),
    ("proofs: WP units, CBMC harnesses and configurations, EVA driver, committed results",
     ("proofs/**/*",)),
    ("MISRA: guideline lists, enforcement plan, deviation and review records", ("misra/*",)),
    ("parameter tables", ("tables/*",)),
    ("plant model and scenarios", ("sim/*.c", "sim/*.h", "sim/apps/*.c", "sim/apps/*.h")),
    ("target-equivalence test and bench", ("tools/target_test/*", "tools/bench/*")),
    ("gate and evidence scripts, make files", ("tools/gates/*", "tools/evidence/*.py", "tools/evidence/*.sh",
                                               "Makefile", "mk/*.mk")),
    ("read-me, change log, documents", ("README.md", "CHANGELOG.md", "docs/*.md")),
)


def archive_sources(bundle):
    """Copy the documents, sources, tests and proof inputs into artefacts/ (with the input files
    of every stamped result, so that its digest can be recomputed from the bundle)."""
    groups, done = [], set()

    def add(name, rels):
        links = []
        for rel in sorted(set(rels)):
            if rel in done or not os.path.isfile(bundle.path(rel)) or "__pycache__" in rel:
                continue
            done.add(rel)
            lk = bundle.art(rel)
            if lk:
                links.append({"path": rel, "link": lk})
        if links:
            groups.append({"group": name, "files": links})

    for name, pats in ARCHIVE:
        rels = []
        for pat in pats:
            rels += [os.path.relpath(p, bundle.root).replace(os.sep, "/")
                     for p in glob.glob(bundle.path(pat), recursive=True)]
        add(name, rels)
    extra = []
    for _key, gate in STAMPED:
        extra += inp.files(gate, bundle.root)
    add("other inputs of the stamped results (tools/evidence/inputs.py)", extra)
    return {"groups": groups, "count": sum(len(g["files"]) for g in groups)}


def write_manifest(out):
    """OUT/MANIFEST.sha256: the SHA-256 of every other file of the bundle (sha256sum format,
    paths relative to OUT); returns the number of files."""
    rows = []
    for root, dirs, fnames in os.walk(out):
        dirs.sort()
        for f in fnames:
            p = os.path.join(root, f)
            rel = os.path.relpath(p, out).replace(os.sep, "/")
            if rel != MANIFEST:
                rows.append((rel, sha256_file(p)))
    rows.sort()
    with open(os.path.join(out, MANIFEST), "w", encoding="utf-8") as f:
        for rel, h in rows:
            f.write(f"{h}  {rel}\n")
    return len(rows)


def html_sec12(sec):
    out = [f"<p>This folder can be archived and handed over as it is. <a href=\"{MANIFEST}\">{MANIFEST}</a> "
           "holds the SHA-256 of every other file of it (<code>sha256sum -c " + MANIFEST + "</code> in the folder "
           f"checks them). Besides the results linked above, <code>artefacts/</code> holds {esc(sec.get('count', 0))} "
           "files of the repository at their paths: what was verified and how.</p>"]
    if sec.get("groups"):
        out.append("<table>" + th("group", "files"))
        for g in sec["groups"]:
            items = "<br>".join(link(x["link"], x["path"]) for x in g["files"])
            out.append("<tr>" + td(g["group"]) + f"<td><details><summary>{len(g['files'])} files</summary>"
                       f"{items}</details></td></tr>")
        out.append("</table>")
    return "\n".join(out)


# --------------------------------------------------------------------------- HTML

CSS = """
body{font-family:sans-serif;font-size:14px;margin:1.5em auto;max-width:1200px;padding:0 1em;color:#111}
h1{font-size:1.6em;margin-bottom:.2em}h2{border-bottom:2px solid #444;margin-top:2em}
table{border-collapse:collapse;margin:.5em 0}th,td{border:1px solid #bbb;padding:2px 6px;vertical-align:top;text-align:left}
th{background:#eee}td.n{text-align:right}tr.pass td.s,td.pass{background:#c8f0c8}tr.fail td.s,td.fail{background:#f6c4c4}
tr.pass td{background:#eefaee}tr.fail td{background:#fdeeee}
table.summary td{font-size:1.05em}table.summary td.s{font-weight:bold;text-align:center}
code{background:#f3f3f3;padding:0 2px}pre{background:#f6f6f6;padding:.5em;overflow-x:auto;font-size:12px}
details{margin:.3em 0}summary{cursor:pointer}.meta{color:#555}.small{font-size:12px}
.missing{color:#a00;font-weight:bold}nav a{margin-right:.8em}span.fail{color:#a00;font-weight:bold}
tr.notrun td{background:#fff6dd}td.notrun,tr.notrun td.s{background:#fde3a7}
.st-ok{color:#075e07;font-weight:bold}.st-bad{color:#a00;font-weight:bold}.st-nr{color:#8a5a00;font-weight:bold}
"""


def cls(ok):
    return "pass" if ok else "fail"


def th(*cols):
    return "<tr>" + "".join(f"<th>{esc(c)}</th>" for c in cols) + "</tr>"


def td(value, num=False, extra=""):
    return f'<td{" class=n" if num else ""}{extra}>{esc(value)}</td>'


def link(href, text=None):
    if not href:
        return esc(text or "")
    return f'<a href="{esc(href)}">{esc(text or href)}</a>'


def inputs_html(sec):
    parts = []
    for i in sec.get("inputs") or []:
        if i["present"]:
            parts.append(f"{link(i.get('link'), i['path'])}"
                         + (f" <span class=meta>(run {esc(i['run'])})</span>" if i.get("run") else ""))
        else:
            parts.append(f'<code>{esc(i["path"])}</code> <span class=missing>not found</span>')
    return ("<p class=small>Inputs: " + "; ".join(parts) + "</p>" if parts else "") + stamp_html(sec)


def not_run(sec, what):
    return f'<p class=missing>Not run: {esc(what)} not found.</p>' + inputs_html(sec)


def details_list(items, label=None):
    items = [str(i) for i in items]
    if not items:
        return "-"
    if len(items) == 1 and label is None:
        return esc(items[0])
    head = label or f"{len(items)}"
    return (f"<details><summary title=\"{esc(', '.join(items))}\">{esc(head)}</summary>"
            + "<br>".join(esc(i) for i in items) + "</details>")


def html_sec1(sec):
    out = [inputs_html(sec)]
    if not sec.get("present"):
        return not_run(sec, "the traceability matrix (build/trace/trace.json or trace.md; make trace)")
    out.append(f"<p>{sec['total']} requirements, {sec['verified']} verified; {sec['with_tests']} with tests, "
               f"{sec['with_cbmc']} with CBMC harnesses, {sec['with_scenarios']} with demonstration scenarios. "
               f"Source: <code>{esc(sec['source'])}</code>.")
    if any(r.get("scenarios_from") == "demo" for r in sec["requirements"]):
        out.append(" Scenarios from the demonstration's <code>metrics.json</code> files where the matrix gives none.")
    out.append(" One block per module; a module with a requirement not verified is open.</p>")
    out.append(verdict_rule_html(sec))
    if sec.get("gate_failures"):
        out.append(f"<details open><summary class=missing>{len(sec['gate_failures'])} trace gate failures</summary>"
                   "<ul>" + "".join(f"<li>{esc(g)}</li>" for g in sec["gate_failures"]) + "</ul></details>")
    if sec.get("totals"):
        out.append("<details><summary>Totals of the matrix</summary><table>" + th("figure", "value")
                   + "".join("<tr>" + td(k.replace("_", " ")) + td(v, True) + "</tr>"
                             for k, v in sec["totals"].items()) + "</table></details>")
    mods = {}
    for r in sec["requirements"]:
        mods.setdefault(r["module"], []).append(r)
    for mod, reqs in sorted(mods.items()):
        v = sum(1 for r in reqs if r["verified"])
        opened = " open" if v != len(reqs) else ""
        out.append(f"<details{opened}><summary><b>{esc(mod)}</b>: {len(reqs)} requirements, {v} verified</summary>")
        out.append("<table>" + th("ID", "title", "contracts", "proofs (WP, CBMC)", "tests", "scenarios",
                                  "verdict"))
        for r in reqs:
            out.append(matrix_row_html(r, sec.get("strict")))
        out.append("</table></details>")
    return "\n".join(out)


def html_sec2(wp, cbmc, eva):
    out = ["<h3>2.1 Frama-C WP, per function</h3>", inputs_html(wp)]
    if wp.get("present"):
        out.append(f"<p><b>proved {wp['proved']} / {wp['goals']} goals</b> in {len(wp['functions'])} functions "
                   f"of {len(wp['units'])} units (source <code>{esc(wp['source'])}</code>).</p>")
        if wp.get("note"):
            out.append(f"<p class=meta>{esc(wp['note'])}</p>")
        if wp["units_without_result"] or wp["functions_without_result"]:
            out.append("<p class=missing>Without a WP result: "
                       + esc(", ".join(wp["units_without_result"] + wp["functions_without_result"])) + "</p>")
        units = {}
        for r in wp["functions"]:
            units.setdefault(r["unit"], []).append(r)
        for unit, rows in sorted(units.items()):
            g = sum(r["goals"] for r in rows)
            p = sum(r["proved"] for r in rows)
            t = sum(r["time_ms"] or 0 for r in rows)
            opened = " open" if p != g else ""
            out.append(f"<details{opened}><summary><b>{esc(unit)}</b>: {len(rows)} functions, "
                       f"{p}/{g} goals, {t / 1000:.1f} s solver time</summary><table>"
                       + th("function", "goals", "proved", "provers", "time (ms)"))
            for r in rows:
                ok = r["goals"] == r["proved"]
                out.append(f"<tr class={cls(ok)}>" + td(r["function"]) + td(r["goals"], True)
                           + td(r["proved"], True) + td(r["provers"])
                           + td("-" if r["time_ms"] is None else f"{r['time_ms']:.0f}", True) + "</tr>")
            out.append("</table></details>")
    else:
        out.append(not_run(wp, "WP results (build/wp/wp-summary.json or proofs/wp/results.md; make prove)"))
    out += ["<h3>2.2 CBMC, per harness</h3>", inputs_html(cbmc)]
    if cbmc.get("present"):
        out.append(f"<p><b>{cbmc['count']} harnesses, {cbmc['properties']} properties, "
                   f"{cbmc['failed_properties']} failed</b> (source <code>{esc(cbmc['source'])}</code>).</p>")
        if cbmc["harnesses_without_result"]:
            out.append("<p class=missing>Harnesses without a result: "
                       + esc(", ".join(cbmc["harnesses_without_result"])) + "</p>")
        out.append("<table>" + th("harness", "result", "properties", "failed", "unwind", "time (s)"))
        for r in cbmc["harnesses"]:
            ok = r["result"].upper() == "PASS" and not r["failed"]
            out.append(f"<tr class={cls(ok)}>" + td(r["harness"]) + td(r["result"]) + td(r["properties"], True)
                       + td(r["failed"], True) + td(r["unwind"], True) + td(r["time_s"], True) + "</tr>")
        out.append("</table>")
    else:
        out.append(not_run(cbmc, "CBMC results (proofs/cbmc/results.md; make cbmc)"))
    out += ["<h3>2.3 Frama-C EVA over the whole drive</h3>", inputs_html(eva)]
    if eva.get("present"):
        out.append(f"<p>Every table the drive accepts (<code>proofs/eva/eva_all_tables.c</code>, "
                   f"<code>make eva</code>): <b>{len(eva['alarms'])} runtime-error alarms</b> (target 0); "
                   f"ACSL properties EVA leaves unknown (proved by WP): {esc(eva.get('unknown_properties'))}; "
                   f"Frama-C exit {esc(eva.get('frama_c_exit'))}; {esc(eva.get('seconds'))} s.</p>")
        ref = eva.get("reference")
        if ref is not None:
            out.append(f"<p>The reference table alone (<code>proofs/eva/eva_main.c</code>, "
                       f"<code>make eva-reference</code>): <b>{len(ref['alarms'])} runtime-error alarms</b> "
                       f"(target 0); properties left to WP: {esc(ref.get('unknown_properties'))}; Frama-C exit "
                       f"{esc(ref.get('frama_c_exit'))}; {esc(ref.get('seconds'))} s.</p>")
        elif eva.get("reference_stale"):
            out.append("<p>The reference table alone (<code>make eva-reference</code>): its result is of other "
                       "sources (stale), not counted.</p>")
        else:
            out.append("<p>The reference table alone (<code>make eva-reference</code>): not run; the table is "
                       "one of the accepted tables above.</p>")
        alarms = [("every accepted table", a) for a in eva["alarms"]]
        alarms += [("reference table", a) for a in (ref or {}).get("alarms", [])]
        if alarms:
            out.append("<table>" + th("analysis", "file", "line", "alarm"))
            for which, a in alarms:
                out.append("<tr class=fail>" + td(which) + td(a.get("file")) + td(a.get("line"), True)
                           + td(a.get("message")) + "</tr>")
            out.append("</table>")
    else:
        out.append(not_run(eva, "build/eva/eva-all.json (make eva)"))
    return "\n".join(out)


def html_sec3(sec):
    out = [inputs_html(sec)]
    if sec.get("cppcheck_unrecorded") is not None:
        out.append(f"<p>cppcheck MISRA addon (<code>make misra</code>): {sec['cppcheck_unrecorded']} unrecorded "
                   f"findings, {esc(sec.get('cppcheck_suppressed'))} suppressed under deviation records.</p>")
    if not sec.get("present"):
        out.append(not_run(sec, "build/misra/compliance-summary.json (make misra-summary)"))
    else:
        c = sec["counts"]
        out.append(f"<p>{esc(sec.get('framework'))}; {esc(sec.get('guideline_set'))}; code: "
                   f"{esc(sec.get('scope'))}.</p>")
        out.append("<table>" + th("guidelines", "compliant", "with deviations", "disapplied", "violations")
                   + "<tr>" + "".join(td(c.get(k, 0), True) for k in
                                      ("guidelines", "compliant", "deviations", "disapplied")) +
                   td(c.get("violations", 0), True, f" class='n {cls(not as_int(c.get('violations')))}'") +
                   "</tr></table>")
        for what, items in (("Plan errors", sec["plan_errors"]), ("Unattributed findings", sec["unattributed_findings"])):
            if items:
                out.append(f"<p class=missing>{what}: " + esc("; ".join(json.dumps(i) if not isinstance(i, str)
                                                                         else i for i in items)) + "</p>")
        bad = [g for g in sec["guidelines"] if str(g.get("status")) != "Compliant"]
        out.append("<h4>Guidelines not simply compliant</h4><table>"
                   + th("guideline", "category", "status", "detail", "methods"))
        for g in bad:
            st = str(g.get("status"))
            detail = "; ".join([str(v) for v in as_list(g.get("violations"))]
                               + [f"{d.get('id')} ({d.get('sites')} sites)" for d in as_list(g.get("deviations"))
                                  if isinstance(d, dict)] + ([str(g.get("reason"))] if g.get("reason") else []))
            out.append(f"<tr class={cls(st != 'Violations')}>" + td(g.get("id")) + td(g.get("category"))
                       + td(st) + td(detail) + td(", ".join(as_list(g.get("methods")))) + "</tr>")
        out.append("</table>")
        out.append(f"<details><summary>Guideline compliance summary: all {len(sec['guidelines'])} guidelines"
                   "</summary><table>" + th("guideline", "category", "edition", "status", "methods", "evidence"))
        for g in sec["guidelines"]:
            st = str(g.get("status"))
            out.append(f"<tr class={cls(st != 'Violations')}>" + td(g.get("id")) + td(g.get("category"))
                       + td(g.get("edition")) + td(st) + td(", ".join(as_list(g.get("methods"))))
                       + td(g.get("evidence")) + "</tr>")
        out.append("</table></details>")
        if sec["recategorisation"]:
            out.append("<h4>Re-categorisation plan</h4><table>" + th("guideline", "category", "re-categorised", "reason"))
            for r in sec["recategorisation"]:
                if isinstance(r, dict):
                    out.append("<tr>" + td(r.get("id")) + td(r.get("category")) + td(r.get("recategorised"))
                               + td(r.get("reason")) + "</tr>")
            out.append("</table>")
        out.append("<h4>Deviation records</h4><table>" + th("record", "guidelines", "sites", "title"))
        for d in sec["deviation_records"]:
            out.append("<tr>" + td(d.get("id")) + td(", ".join(as_list(d.get("guidelines"))))
                       + td(d.get("sites"), True) + td(d.get("title")) + "</tr>")
        out.append("</table>")
        if sec["tools"]:
            out.append("<details><summary>Tools of the MISRA analysis</summary><table>" + th("tool", "version")
                       + "".join("<tr>" + td(k) + td(v) + "</tr>" for k, v in sec["tools"].items())
                       + "</table></details>")
    if sec.get("deviations_md"):
        out.append("<details><summary>misra/deviations.md (rendered)</summary>"
                   + md_to_html(sec["deviations_md"], shift=3) + "</details>")
    links = {i["path"]: i.get("link") for i in sec.get("inputs") or []}
    out.append("<p>Enforcement plan: " + link(links.get("misra/enforcement-plan.csv"), "misra/enforcement-plan.csv")
               + "; review records: " + link(links.get("misra/reviews.md"), "misra/reviews.md") + ".</p>")
    return "\n".join(out)


def html_sec4(cov, mcdc):
    out = ["<h3>4.1 Statement and branch coverage (gcovr, Cobertura)</h3>", inputs_html(cov)]
    if cov.get("present"):
        t = cov["total"]
        out.append(f"<p><b>statements {fmt_pct(cov['statement_percent'])} ({t['lines_covered']}/{t['lines']}), "
                   f"branches {fmt_pct(cov['branch_percent'])} ({t['branches_covered']}/{t['branches']})</b>; "
                   f"target 100 %. " + (f"HTML report: {link(cov.get('html'), 'gcovr')}." if cov.get("html") else "")
                   + "</p>")
        if cov["files"]:
            out.append("<table>" + th("file", "lines", "covered", "%", "branches", "covered", "%"))
            for f, v in sorted(cov["files"].items()):
                ok = v["lines_covered"] == v["lines"] and v["branches_covered"] == v["branches"]
                out.append(f"<tr class={cls(ok)}>" + td(f) + td(v["lines"], True) + td(v["lines_covered"], True)
                           + td(fmt_pct(pct(v["lines_covered"], v["lines"])), True) + td(v["branches"], True)
                           + td(v["branches_covered"], True)
                           + td(fmt_pct(pct(v["branches_covered"], v["branches"])), True) + "</tr>")
            out.append("</table>")
    else:
        out.append(not_run(cov, "build/coverage/coverage.xml (make coverage)"))
    out += ["<h3>4.2 MC/DC (gcc 14 -fcondition-coverage)</h3>", inputs_html(mcdc)]
    if mcdc.get("present"):
        out.append(f"<p><b>{fmt_pct(mcdc['percent'], 2)} of {mcdc['outcomes']} condition outcomes covered</b>, "
                   f"{mcdc['justified']} justified exclusions, {mcdc['unjustified']} not covered without a "
                   f"justification; target 100 %. Criterion: {esc(mcdc.get('criterion'))}; tool: "
                   f"{esc(mcdc.get('tool'))}.</p>")
        if mcdc["scopes"]:
            out.append("<table>" + th("scope", "outcomes", "covered", "%", "justified"))
            for k, v in mcdc["scopes"].items():
                ok = as_int(v.get("covered")) + as_int(v.get("justified")) == as_int(v.get("outcomes"))
                out.append(f"<tr class={cls(ok)}>" + td("src/" if k == "src" else "include/qfoc/ (inline)")
                           + td(v.get("outcomes"), True) + td(v.get("covered"), True)
                           + td(fmt_pct(as_float(v.get("percent")), 2), True) + td(v.get("justified"), True) + "</tr>")
            out.append("</table>")
        if mcdc["files"]:
            out.append("<table>" + th("file", "outcomes", "covered", "%", "justified"))
            for f, v in sorted(mcdc["files"].items()):
                o, c, j = as_int(v.get("outcomes")), as_int(v.get("covered")), as_int(v.get("justified"))
                out.append(f"<tr class={cls(c + j == o)}>" + td(f) + td(o, True) + td(c, True)
                           + td(fmt_pct(pct(c, o), 2), True) + td(j, True) + "</tr>")
            out.append("</table>")
        out.append("<h4>Condition outcomes not covered</h4>")
        if mcdc["uncovered"]:
            out.append("<table>" + th("location", "function", "condition", "outcome", "justification"))
            for u in mcdc["uncovered"]:
                out.append(f"<tr class={cls(bool(u['justification']))}>" + td(f"{u['file']}:{u['line']}")
                           + td(u["function"]) + td(u["condition"]) + td(u["outcome"])
                           + td(u["justification"] or "NOT JUSTIFIED") + "</tr>")
            out.append("</table>")
        else:
            out.append("<p>None: every condition outcome is covered; no exclusion is used.</p>")
        if mcdc["unused_justifications"]:
            out.append("<p class=missing>Justifications matching nothing: "
                       + esc(json.dumps(mcdc["unused_justifications"])) + "</p>")
        if mcdc["not_instrumented"]:
            out.append(f"<details><summary>{len(mcdc['not_instrumented'])} decisions without conditions in the "
                       "object code (branch-free MIN/MAX/ABS)</summary><table>" + th("location", "kind", "decision"))
            for d in mcdc["not_instrumented"]:
                if isinstance(d, dict):
                    out.append("<tr>" + td(f"{d.get('file')}:{d.get('line')}") + td(d.get("kind"))
                               + td(d.get("decision")) + "</tr>")
            out.append("</table></details>")
    else:
        out.append(not_run(mcdc, "build/mcdc/mcdc.json (make mcdc)"))
    return "\n".join(out)


def html_sec5(tests, tt):
    out = ["<h3>5.1 JUnit results</h3>", inputs_html(tests)]
    if tests.get("present"):
        out.append(f"<p><b>{tests['passed']} of {tests['tests']} tests passed</b>, {tests['failures']} failures, "
                   f"{tests['errors']} errors, {tests['skipped']} skipped, in {len(tests['files'])} JUnit files.</p>")
        out.append("<table>" + th("file", "suites", "tests", "failures", "errors", "skipped", "time (s)", "failed"))
        for f in tests["files"]:
            if f.get("error"):
                out.append("<tr class=fail>" + td(f["file"]) + f"<td colspan=7>{esc(f['error'])}</td></tr>")
                continue
            ok = not f["failures"] and not f["errors"] and f["tests"] > 0
            tn = f["test_names"]
            out.append(f"<tr class={cls(ok)}><td>{link(f.get('link'), f['file'])}</td>"
                       + td(", ".join(f["suites"]))
                       + f"<td class=n>{details_list(tn, str(f['tests'])) if tn else esc(f['tests'])}</td>"
                       + td(f["failures"], True) + td(f["errors"], True) + td(f["skipped"], True)
                       + td("-" if f["time"] is None else f"{f['time']:.2f}", True)
                       + f"<td>{details_list(f['failed_tests'])}</td></tr>")
        out.append("</table>")
    else:
        out.append(not_run(tests, "build/junit/*.xml (make test)"))
    out += ["<h3>5.2 Target equivalence (golden vectors on the Cortex-M4F under QEMU)</h3>", inputs_html(tt)]
    if tt.get("present"):
        out.append(f"<p>{esc(tt['header'])}<br><b>{esc(tt['result'])}</b></p>")
        out.append(f"<details><summary>{len(tt['groups'])} groups</summary><table>"
                   + th("group", "vectors", "result"))
        for g in tt["groups"]:
            out.append(f"<tr class={cls(g['result'] == 'identical')}>" + td(g["group"])
                       + td(g["vectors"], True) + td(g["result"]) + "</tr>")
        out.append("</table></details>")
    else:
        out.append(not_run(tt, "build/target_test/target.txt (make target-test)"))
    out.append("<h3>5.3 Demonstration (simulation with the library in the loop)</h3>")
    if tests.get("demo_link"):
        out.append(f"<p>Report: {link(tests['demo_link'], 'build/demo/index.html')}.</p>")
        if tests.get("demo"):
            out.append("<table>" + th("scenario", "title", "requirements", "targets met"))
            for s in tests["demo"]:
                ok = s["pass"] is not False
                out.append(f"<tr class={cls(ok)}>" + td(s["scenario"]) + td(s["title"])
                           + td(", ".join(str(r) for r in s["requirements"]))
                           + td("-" if s["pass"] is None else ("yes" if s["pass"] else "NO")) + "</tr>")
            out.append("</table>")
    else:
        out.append('<p class=missing>Not run: build/demo/index.html not found (make demo).</p>')
    if tests.get("robustness"):
        r = tests["robustness"]
        out.append(f"<p>Robustness campaign ({link(tests.get('robustness_link'), 'build/robustness/index.html')}): "
                   f"<b>{esc(r.get('successes'))} of {esc(r.get('count'))} cold starts succeed</b> "
                   f"({esc(r.get('rate_pct'))} %, table {esc(r.get('table'))}); {esc(r.get('criteria'))}.</p>")
    return "\n".join(out)


def html_sec6(sec):
    out = [inputs_html(sec)]
    if not sec.get("present"):
        return not_run(sec, "build/bench/bench.json (make bench)")
    out.append(f"<p><b>limits met {sec['limits_met']} / {sec['limits']}</b>"
               + (f"; goals met {sec['goals_met']} / {sec['goals']} (goals are reported, not enforced)"
                  if sec.get("goals") else "") + f". Compiler: {esc(sec.get('compiler'))}."
               + (f" Over the limit: {esc('; '.join(str(o) for o in sec['over']))}." if sec["over"] else "") + "</p>")
    goal = sec.get("has_goal")
    out.append("<table>" + th("item", "min", "max", "limit", "result", *(["goal", "goal result"] if goal else []),
                              "unit", "requirement"))
    for r in sec["table"]:
        res = str(r.get("result", ""))
        c = "" if r.get("limit") is None else f" class={cls(res.upper() in ('OK', 'PASS'))}"
        out.append(f"<tr{c}><td>{md_inline(str(r.get('item', '')))}</td>"
                   + td("-" if r.get("min") is None else r.get("min"), True)
                   + td("-" if r.get("max") is None else r.get("max"), True)
                   + td("-" if r.get("limit") is None else r.get("limit"), True)
                   + td(res)
                   + (td("-" if r.get("goal") is None else r.get("goal"), True) + td(r.get("goal_result", "-"))
                      if goal else "")
                   + td(r.get("unit")) + td(r.get("requirement")) + "</tr>")
    out.append("</table>")
    return "\n".join(out)


def html_sec7(sec):
    out = [inputs_html(sec)]
    if not sec.get("present"):
        return not_run(sec, "build/static/qfoc.sarif (make static)")
    out.append("<table>" + th("tool", "version", "ran", "findings", "accepted", "unaccepted"))
    for t in sec["tools"]:
        ok = not t["unaccepted"] and t["ran"] is not False
        out.append(f"<tr class={cls(ok)}>" + td(t["tool"]) + td(t["version"])
                   + td({True: "yes", False: "NO", None: "-"}[t["ran"]]) + td(t["findings"], True)
                   + td(t["accepted"], True) + td(t["unaccepted"], True) + "</tr>")
    out.append("</table><h4>Findings per rule</h4><table>" + th("tool", "rule", "findings", "accepted", "reason"))
    for r in sec["rules"]:
        reasons = "<br>".join(f'<span title="{esc(x["justification"])}">{esc(x["reason"])}</span>'
                              for x in r["reasons"])
        out.append(f"<tr class={cls(r['accepted'] == r['findings'])}>" + td(r["tool"]) + td(r["rule"])
                   + td(r["findings"], True) + td(r["accepted"], True) + f"<td>{reasons or '-'}</td></tr>")
    out.append("</table>")
    if sec["unaccepted"]:
        out.append("<h4>Unaccepted findings</h4><table>" + th("tool", "rule", "where", "message"))
        for u in sec["unaccepted"]:
            out.append("<tr class=fail>" + td(u["tool"]) + td(u["rule"]) + td(u["where"]) + td(u["message"]) + "</tr>")
        out.append("</table>")
    return "\n".join(out)


def html_sec8(sec):
    out = [inputs_html(sec)]
    if sec.get("tools"):
        out.append("<table>" + th("tool", "version (recorded)", "use cases", "TI", "TD", "TCL", "mitigation"))
        for t in sec["tools"]:
            uses = "<ul>" + "".join(f"<li>{esc(u)}</li>" for u in as_list(t.get("use_cases"))) + "</ul>"
            out.append("<tr>" + td(t.get("tool")) + td(t.get("version")) + f"<td>{uses}</td>"
                       + f'<td title="{esc(t.get("impact_reason"))}">{esc(t.get("impact"))}</td>'
                       + f'<td title="{esc(t.get("detection_reason"))}">{esc(t.get("detection"))}</td>'
                       + td(t.get("tcl")) + td(t.get("mitigation")) + "</tr>")
        out.append("</table>")
    else:
        out.append('<p class=missing>Not found: specs/tool-confidence.json.</p>')
    out.append("<h4>Tool versions of this run (<code>sh tools/evidence/tool_versions.sh</code>)</h4>")
    if sec.get("versions") is not None:
        out.append(f"<p>{link(sec.get('versions_link'), 'tool-versions.txt')}"
                   + (f" (exit status {sec['versions_exit']})" if sec.get("versions_exit") else "") + "</p>")
        out.append("<pre>" + esc(sec["versions"]) + "</pre>")
    else:
        out.append('<p class=missing>Not run: tools/evidence/tool_versions.sh not found or failed.</p>')
    return "\n".join(out)


def html_sec9(sec):
    out = [inputs_html(sec)]
    if not sec.get("present"):
        return '<p class=missing>Not found: specs/safety-manual.md.</p>'
    out.append("<details open><summary>specs/safety-manual.md, rendered</summary>"
               + md_to_html(sec["text"], shift=2) + "</details>")
    return "\n".join(out)


def html_sec10(sec):
    out = [inputs_html(sec)]
    if not sec.get("present"):
        return not_run(sec, "build/repro/repro.json (make repro)")
    out.append(f"<p>Two builds from the same sources in separate build trees: <b>"
               f"{'identical' if sec['identical'] else 'DIFFERENT'}</b>. Compiler: {esc(sec.get('compiler'))}.</p>")
    out.append("<table>" + th("artefact", "SHA-256 (first build)", "SHA-256 (second build)", "identical"))
    for a in sec["artefacts"]:
        ok = truthy(a.get("identical"))
        out.append(f"<tr class={cls(ok)}>" + td(a.get("file")) + f"<td><code>{esc(a.get('sha256'))}</code></td>"
                   + f"<td><code>{esc(a.get('sha256_second'))}</code></td>" + td("yes" if ok else "NO") + "</tr>")
    out.append("</table>")
    out.append("<p>The same artefacts in the main build tree now (for reference; built by <code>make target</code> "
               "and <code>make firmware</code>, possibly from another state of the sources):</p><table>"
               + th("file", "SHA-256", "same as the reproducibility builds"))
    for a in sec["artefacts"]:
        h = a.get("build_sha256")
        same = "-" if h is None else ("yes" if h == a.get("sha256") else "no")
        out.append("<tr>" + td(a.get("build_file")) + f"<td><code>{esc(h or 'not built')}</code></td>"
                   + td(same) + "</tr>")
    out.append("</table>")
    return "\n".join(out)


def html_sec11(sec):
    out = [inputs_html(sec)]
    if not sec.get("present"):
        return ('<p class=missing>Not run: build/check-summary.txt not found (<code>make check</code> writes it).'
                '</p>' + inputs_html(sec))
    out.append("<table>" + th("gate", "result", "time (s)", "last line of its log"))
    for g in sec["gates"]:
        out.append(f"<tr class={cls(g['result'] == 'PASS')}><td>{link(g.get('log'), g['gate'])}</td>"
                   + td(g["result"]) + td(g["seconds"], True) + td(g["last_line"]) + "</tr>")
    out.append("</table>")
    return "\n".join(out)


def review_state_html(r):
    """A record's state: current (green) or stale, unstamped, invalid (red) with the reasons."""
    if r["state"] == rs.CURRENT:
        return (f"<span class=st-ok>current</span> <span class=meta>({len(r['files'])} files, sha256 "
                f"<code>{esc(r['now'][:16])}</code>...)</span>")
    return (f"<span class=st-bad>{esc(r['state'].upper())}</span>: "
            + esc("; ".join(r["reasons"])))


def review_rule_html(res):
    return ("<p class=small>Each record carries the SHA-256 of the files it reviewed "
            f"(<code>tools/evidence/review_stamp.py</code>, manifest <code>{esc(res['manifest'])}</code>): "
            "<b>current</b> when the files are unchanged since the review; <b>stale</b> (red) when one of "
            "them changed, appeared or disappeared, named; <b>unstamped</b> (red) without a digest or "
            "without the date and reviewer of its review. <code>python3 tools/evidence/review_stamp.py "
            "--check</code> gives the same.</p>")


def html_reviews(sec):
    out = ["<h3>Review records (misra/reviews.md)</h3>", inputs_html(sec)]
    if not sec.get("present"):
        out.append('<p class=missing>Not found: misra/reviews.md.</p>')
        return "\n".join(out)
    res = sec["check"]
    out.append(review_rule_html(res))
    for e in res["errors"]:
        out.append(f"<p class=missing>{esc(e)}</p>")
    out.append("<table>" + th("guideline", "result", "reviewed", "files reviewed", "state"))
    for r in res["records"]:
        rv = r.get("reviewed") or (None, None)
        files = details_list(r["files"], f"{len(r['files'])} files")
        out.append(f"<tr class={cls(r['state'] == rs.CURRENT)}>" + td(f"{r['id']} {r['title']}")
                   + td(r.get("result")) + td(" ".join(x for x in rv if x) or "-")
                   + f"<td>{files}</td><td class=small>{review_state_html(r)}</td></tr>")
    out.append("</table>")
    return "\n".join(out)


def html_fmea(sec, trace_sec):
    out = [inputs_html(sec)]
    if not sec.get("present"):
        return out[0] + '<p class=missing>Not found: specs/safety-analysis.md.</p>'
    res = sec["check"]
    strict = bool((trace_sec or {}).get("strict"))
    rv = res.get("reviewed") or (None, None)
    out.append(f"<p>The rows of the software FMEA (<code>specs/safety-analysis.md</code>, section 2): "
               f"{len(sec.get('rows') or [])} rows, {sec.get('verified_rows', 0)} with every requirement they "
               f"name verified. Reviewed: {esc(' '.join(x for x in rv if x) or 'no Reviewed: line')}.</p>")
    out.append(review_rule_html(res))
    out.append("<p class=small>A row is green only when it is current and every requirement its evidence "
               "names is verified (section 1; <code>tools/evidence/verdict.py</code>): the row follows the "
               "mechanisms it relies on.</p>")
    for e in res["errors"]:
        out.append(f"<p class=missing>{esc(e)}</p>")
    out.append("<table>" + th("ID", "block", "failure mode", "requirements (verdict)", "files reviewed", "state",
                              "row"))
    for r in sec.get("rows") or []:
        c = "pass" if r["ok"] else ("notrun" if r["verdict"] == vd.NOT_RUN and r["state"] == rs.CURRENT
                                    and not strict else "fail")
        reqs = "<br>".join(f"<span class={status_class(x['verdict'], strict)}>{esc(x['verdict'])}</span> "
                           + link(x.get("link"), x["id"]) for x in r["req_verdicts"]) or "-"
        files = details_list(r["files"], f"{len(r['files'])} files")
        out.append(f"<tr class={c}>" + td(r["id"]) + f"<td>{md_inline(r['title'])}</td>" + td(r.get("failure"))
                   + f"<td class=small>{reqs}</td><td>{files}</td><td class=small>{review_state_html(r)}</td>"
                   + f"<td class='s {c}'>{esc(r['verdict'] if r['state'] == rs.CURRENT else r['state'])}</td></tr>")
    out.append("</table>")
    return "\n".join(out)


# --------------------------------------------------------------------------- 12 tool validation


TOOLVAL_GATES = (("wp", "WP"), ("cbmc", "CBMC"), ("eva", "EVA"), ("misra", "MISRA"), ("tests", "tests"),
                 ("coverage", "coverage"))


def collect_tool_validation(bundle):
    """Tool validation by seeded defects (REQ-EVD-030): build/validation/results.json of
    `make tool-validation` (tools/validation/run.py).  Its row is green when every expected
    catch happened and the control (the unmodified copy through the same gates) passed.
    `make check` does not run the campaign: without the file the section shows a red "not
    run" row and the one-screen summary has no row for it (so --strict does not fail)."""
    sec = {"title": "Tool validation by seeded defects"}
    jpath, mpath = bundle.b("validation", "results.json"), bundle.b("validation", "results.md")
    sec["inputs"] = bundle.inputs(*[p for p in (jpath, mpath) if bundle.exists(p)] or [jpath])
    data = read_json(bundle.path(jpath))
    summ = data.get("summary") if isinstance(data, dict) else None
    if not isinstance(summ, dict) or not isinstance(data.get("defects"), list):
        sec["present"] = False
        sec["summary"] = []
        sec["status"] = missing_row("toolval", "tool validation (seeded defects)", "sec13", jpath, bundle)
        return sec
    defects = [d for d in data["defects"] if isinstance(d, dict)]
    control = [c for c in as_list(data.get("control")) if isinstance(c, dict)]
    expected = sum(len(as_list(d.get("expected"))) for d in defects)
    caught = sum(1 for d in defects for g in as_list(d.get("expected"))
                 if isinstance(d.get("gates"), dict) and (d["gates"].get(g) or {}).get("status") == "caught")
    control_ok = bool(control) and all(truthy(c.get("ok")) for c in control)
    partial = summ.get("partial") or ""
    ok = expected > 0 and caught == expected and control_ok and not partial
    sec.update({"present": True, "defects": defects, "control": control, "expected": expected,
                "caught": caught, "control_ok": control_ok, "date": data.get("date"),
                "commit": data.get("commit"), "wall_seconds": summ.get("wall_seconds"),
                "cpu_seconds": summ.get("cpu_seconds")})
    fig = (f"{caught} / {expected} expected catches in {len(defects)} seeded defects; control "
           f"{'passes' if control_ok else 'FAILS'} ({len(control)} runs)" + (f"; partial run ({partial})" if partial else ""))
    sec["status"] = row("toolval", "tool validation (seeded defects)", ok, fig, "sec13")
    sec["summary"] = [sec["status"]]
    return sec


def html_tool_validation(sec):
    st = sec["status"]
    out = [f"<table class=summary><tr class={cls(st['status'] == 'PASS')}>{td(st['label'])}{td(st['figure'])}"
           f"<td class=s>{esc(st['status'])}</td></tr></table>"]
    if not sec.get("present"):
        return out[0] + not_run(sec, "build/validation/results.json (make tool-validation, not part of make check)")
    out.append(inputs_html(sec))
    out.append(f"<p>Defects seeded into copies of the library, each run through the gates expected to catch "
               f"it, scoped to the unit it touches (<code>make tool-validation</code>, catalogue "
               f"<code>tools/validation/defects.toml</code>): <b>{sec['caught']} / {sec['expected']}</b> expected "
               f"catches; the unmodified copy through the same gates: <b>{'passes' if sec['control_ok'] else 'FAILS'}"
               f"</b>. Run {esc(sec.get('date'))}, commit <code>{esc(sec.get('commit'))}</code>, "
               f"{esc(sec.get('wall_seconds'))} s wall, {esc(sec.get('cpu_seconds'))} s CPU.</p>")
    out.append("<table>" + th("defect", "class", "file", *[n for _g, n in TOOLVAL_GATES]))
    for d in sec["defects"]:
        gates = d.get("gates") if isinstance(d.get("gates"), dict) else {}
        good = all((gates.get(g) or {}).get("status") == "caught" for g in as_list(d.get("expected")))
        cells = []
        for g, _n in TOOLVAL_GATES:
            st = (gates.get(g) or {}).get("status", "not expected")
            cells.append(td("-" if st == "not expected" else st,
                            extra=f' title="{esc((gates.get(g) or {}).get("detail", ""))}"'))
        out.append(f"<tr class={cls(good)}>" + td(f"{d.get('id')} {d.get('title', '')}") + td(d.get("class"))
                   + td(d.get("file")) + "".join(cells) + "</tr>")
    out.append("</table>")
    out.append("<details><summary>Control runs (the unmodified copy)</summary><table>"
               + th("scope", "gate", "result", "figure"))
    for c in sec["control"]:
        out.append(f"<tr class={cls(truthy(c.get('ok')))}>" + td(c.get("scope")) + td(c.get("gate"))
                   + td(c.get("outcome")) + td(c.get("detail")) + "</tr>")
    out.append("</table></details>")
    return "\n".join(out)


SECTIONS = [("sec1", "1 Requirements and traceability"), ("sec2", "2 Formal verification"),
            ("sec3", "3 MISRA Compliance:2020"), ("sec4", "4 Structural coverage"), ("sec5", "5 Tests"),
            ("sec6", "6 Resource usage"), ("sec7", "7 Static analysis"), ("sec8", "8 Tool confidence"),
            ("sec9", "9 Safety manual"), ("sec10", "10 Reproducibility"), ("sec11", "11 Gate log"),
            ("sec12", "12 Archive"), ("sec13", "13 Tool validation"), ("sec14", "14 Software FMEA")]


def write_html(path, model, secs):
    g, date = model["commit"], model["date"]
    dirty = {True: " (working tree modified)", False: " (clean)", None: ""}[g["dirty"]]
    green = sum(1 for r in model["summary"] if r["status"] == "PASS")
    red = len(model["summary"]) - green
    out = ["<!DOCTYPE html>", "<html lang=en><head><meta charset=utf-8>",
           "<title>qfoc evidence</title>", f"<style>{CSS}</style></head><body>",
           "<h1>qfoc: ISO 26262 verification evidence</h1>",
           f"<p class=meta>Commit <code>{esc(g['commit'])}</code>{esc(dirty)}"
           + (f", branch {esc(g['branch'])}" if g.get("branch") else "")
           + f"; generated {esc(date)} by <code>make evidence</code> (tools/evidence/evidence.py) from the results the "
           "gates wrote; it runs no gate. Machine-readable: <a href=\"evidence.json\">evidence.json</a>.</p>",
           "<nav>" + "".join(f'<a href="#{k}">{esc(t)}</a>' for k, t in SECTIONS) + "</nav>",
           f"<h2 id=summary>Summary: {green} green, {red} red</h2>",
           "<table class=summary>" + th("evidence", "figure", "status")]
    for r in model["summary"]:
        out.append(f"<tr class={cls(r['status'] == 'PASS')}><td><a href=\"#{r['section']}\">{esc(r['label'])}</a>"
                   f"</td>{td(r['figure'])}<td class=s>{'PASS' if r['status'] == 'PASS' else 'FAIL'}</td></tr>")
    out.append("</table><p class=small>A row is green only when its input exists and meets its target; a "
               "missing input is red with \"not run\"; a result whose inputs changed since its run (or that "
               "carries no inputs stamp) is red with \"STALE\". Dates are those of the runs, from the "
               "result files' stamps.</p>")
    out.append(f'<p><a href="#attrs">{esc(attrs_counts_text(secs["attrs"]))}</a></p>')
    bodies = {"sec1": html_sec1(secs["trace"]) + "\n" + html_attrs(secs["attrs"]), "sec2": html_sec2(secs["wp"], secs["cbmc"], secs["eva"]),
              "sec3": html_sec3(secs["misra"]) + "\n" + html_reviews(secs["reviews"]), "sec4": html_sec4(secs["coverage"], secs["mcdc"]),
              "sec5": html_sec5(secs["tests"], secs["target_test"]), "sec6": html_sec6(secs["bench"]),
              "sec7": html_sec7(secs["static"]), "sec8": html_sec8(secs["tools"]),
              "sec9": html_sec9(secs["manual"]), "sec10": html_sec10(secs["repro"]),
              "sec11": html_sec11(secs["gates"]), "sec12": html_sec12(secs.get("archive") or {}),
              "sec13": html_tool_validation(secs["toolval"]), "sec14": html_fmea(secs["fmea"], secs["trace"])}
    for key, title in SECTIONS:
        out.append(f"<h2 id={key}>{esc(title)}</h2>")
        out.append(bodies[key])
    out.append("</body></html>")
    with open(path, "w", encoding="utf-8") as f:
        f.write("\n".join(out) + "\n")


# --------------------------------------------------------------------------- main


def build_model(bundle):
    secs = {
        "trace": collect_trace(bundle), "wp": collect_wp(bundle), "eva": collect_eva(bundle),
        "cbmc": collect_cbmc(bundle), "misra": collect_misra(bundle), "coverage": collect_coverage(bundle),
        "mcdc": collect_mcdc(bundle), "tests": collect_tests(bundle), "target_test": collect_target_test(bundle),
        "static": collect_static(bundle), "bench": collect_bench(bundle), "repro": collect_repro(bundle),
        "tools": collect_tools(bundle), "manual": collect_manual(bundle), "gates": collect_gates(bundle),
        "attrs": collect_attrs(bundle),
        "toolval": collect_tool_validation(bundle),
        "reviews": collect_reviews(bundle), "fmea": collect_fmea(bundle),
    }
    apply_staleness(bundle, secs)
    apply_verdicts(bundle, secs)
    apply_fmea_verdicts(bundle, secs)
    secs["archive"] = archive_sources(bundle)
    order = ["trace", "wp", "eva", "cbmc", "misra", "reviews", "coverage", "mcdc", "tests", "target_test",
             "static", "bench", "repro", "fmea", "toolval"]
    summary = [r for k in order for r in secs[k].get("summary", [])]
    model = {"generated_by": "tools/evidence/evidence.py (make evidence)",
             "date": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M:%S UTC"),
             "commit": git_info(bundle.root), "summary": summary,
             "green": sum(1 for r in summary if r["status"] == "PASS"),
             "red": sum(1 for r in summary if r["status"] != "PASS")}
    return model, secs


def json_sections(secs):
    """The sections for evidence.json (the rendered texts left out: they are files of their own)."""
    out = {}
    for k, s in secs.items():
        d = {kk: vv for kk, vv in s.items() if kk not in ("summary", "text", "deviations_md", "versions")}
        if k == "tools":
            d["versions"] = s.get("versions")
        out[k] = d
    return out


def main(argv=None) -> int:
    here = os.path.dirname(os.path.abspath(__file__))
    ap = argparse.ArgumentParser(description="Collect the gates' results into build/evidence/.")
    ap.add_argument("--root", default=os.path.dirname(os.path.dirname(here)),
                    help="repository root (default: this checkout)")
    ap.add_argument("--build", default="build", help="build directory, relative to the root (default build)")
    ap.add_argument("--out", default=None, help="output directory (default BUILD/evidence)")
    ap.add_argument("--strict", action="store_true", help="exit 1 when a summary row is red")
    args = ap.parse_args(argv)
    out = args.out or os.path.join(args.build, "evidence")
    bundle = Bundle(args.root, args.build, out)
    bundle.strict = args.strict
    os.makedirs(bundle.out, exist_ok=True)
    shutil.rmtree(os.path.join(bundle.out, "artefacts"), ignore_errors=True)
    for stale in ("tool-versions.txt", MANIFEST):
        if os.path.exists(os.path.join(bundle.out, stale)):
            os.remove(os.path.join(bundle.out, stale))
    model, secs = build_model(bundle)
    model["sections"] = json_sections(secs)
    model["artefacts"] = sorted(bundle.copied.values())
    index = os.path.join(bundle.out, "index.html")
    write_html(index, model, secs)
    with open(os.path.join(bundle.out, "evidence.json"), "w", encoding="utf-8") as f:
        json.dump(model, f, indent=1, sort_keys=False, default=str)
        f.write("\n")
    n_manifest = write_manifest(bundle.out)
    width = max(len(r["label"]) for r in model["summary"]) + 2
    g = model["commit"]
    print(f"evidence: commit {g['commit']}" + {True: " (working tree modified)", False: "", None: ""}[g["dirty"]])
    for r in model["summary"]:
        print(f"{r['label']:<{width}}{r['figure']}   {r['status']}")
    print(f"evidence: {bundle.rel(os.path.join(bundle.out, MANIFEST))} ({n_manifest} files)")
    print(attrs_counts_text(secs["attrs"]))
    print(f"evidence: {bundle.rel(index)} ({model['green']} green, {model['red']} red)")
    if args.strict and model["red"]:
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
