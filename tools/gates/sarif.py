#!/usr/bin/env python3
"""Static-analysis results as SARIF 2.1.0, the report and the gate (make static).

usage: sarif.py --out build/static --accepted specs/static-accepted.md

Reads the raw outputs tools/gates/static.sh leaves in OUT:
  cppcheck      cppcheck.xml (XML version 2), cppcheck-errorlist.xml (the rule texts)
  gcc-analyzer  gcc-analyzer/<unit>.json (gcc 12 -fdiagnostics-format=json, one per unit),
                gcc-analyzer-options.txt (gcc --help=warnings: the rule texts)
  clang-tidy    clang-tidy.txt (the diagnostics as text), clang-tidy-checks.txt (the
                enabled checks), clang-tidy-all.txt (every bugprone-* and cert-* check:
                counts for the disabled ones), clang-tidy-disabled.txt (check | reason)
and for each tool <tool>.version, <tool>.cmd and <tool>.rc.

Writes OUT/<tool>.sarif (one run each), OUT/qfoc.sarif (the three runs), both checked
for the structure SARIF 2.1.0 requires, and OUT/static.md: the findings per tool and
rule with file:line, function and message, and whether each is accepted.

A finding's key is tool:rule:file:function (function '-' at file scope).  It is
accepted when specs/static-accepted.md lists the key under a section that gives a
justification; the SARIF result then carries the justification as an external,
accepted suppression.  Prints
  static: N findings (cppcheck a, gcc-analyzer b, clang-tidy c), K accepted, U unaccepted
and exits 1 on an unaccepted finding, on an accepted key that matches no finding, on
an accepted section without a justification, on an analyser that failed, or on a SARIF
file that breaks the structure.
"""
import argparse
import glob
import hashlib
import json
import os
import re
import sys
import xml.etree.ElementTree as ET

TOP = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
SCHEMA = "https://docs.oasis-open.org/sarif/sarif/v2.1.0/errata01/os/schemas/sarif-schema-2.1.0.json"
TOOLS = ("cppcheck", "gcc-analyzer", "clang-tidy")
LEVELS = ("none", "note", "warning", "error")
CT_DOC = "https://releases.llvm.org/{major}.0.0/tools/clang/tools/extra/docs/clang-tidy/checks/{check}.html"


# ------------------------------------------------------------------ source helpers
def rel_path(path):
    """Path relative to the repository root when it lies inside it, else absolute."""
    p = path if os.path.isabs(path) else os.path.join(TOP, path)
    p = os.path.normpath(p)
    if p == TOP or p.startswith(TOP + os.sep):
        return os.path.relpath(p, TOP).replace(os.sep, "/")
    return p


def _blank_comments_and_literals(text):
    """The text with comments, string and character literals turned into spaces
    (newlines kept), so that braces and parentheses can be counted."""
    out = list(text)
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
        elif text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
        elif c in "\"'":
            j = i + 1
            while j < n and text[j] != c and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            j = min(j + 1, n)
        elif c == "#" and (i == 0 or text[i - 1] == "\n"):
            # a preprocessor line, continuations included
            j = i
            while j < n and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
        else:
            i += 1
            continue
        for k in range(i, j):
            if out[k] != "\n":
                out[k] = " "
        i = j
    return "".join(out)


_IDENT_END = re.compile(r"([A-Za-z_][A-Za-z0-9_]*)\s*$")
_functions_cache = {}


def functions(path):
    """[(name, first line, last line)] of the function definitions of a C file."""
    if path in _functions_cache:
        return _functions_cache[path]
    result = []
    full = os.path.join(TOP, path) if not os.path.isabs(path) else path
    try:
        with open(full, encoding="utf-8", errors="replace") as f:
            text = _blank_comments_and_literals(f.read())
    except OSError:
        _functions_cache[path] = result
        return result
    depth = 0
    start = None
    for i, c in enumerate(text):
        if c == "{":
            if depth == 0:
                start = None
                head = text[:i].rstrip()
                # skip attributes after the parameter list: f(void) __attribute__((x)) {
                while head.endswith(")"):
                    k, level = len(head) - 1, 0
                    while k >= 0:
                        if head[k] == ")":
                            level += 1
                        elif head[k] == "(":
                            level -= 1
                            if level == 0:
                                break
                        k -= 1
                    m = _IDENT_END.search(head[:k])
                    if m is None:
                        break
                    if m.group(1) in ("__attribute__", "__attribute", "__declspec"):
                        head = head[:m.start()].rstrip()
                        continue
                    if m.group(1) not in ("if", "while", "for", "switch", "sizeof", "return"):
                        start = (m.group(1), text.count("\n", 0, m.start()) + 1)
                    break
            depth += 1
        elif c == "}":
            depth = max(depth - 1, 0)
            if depth == 0 and start is not None:
                result.append((start[0], start[1], text.count("\n", 0, i) + 1))
                start = None
    _functions_cache[path] = result
    return result


def function_at(path, line):
    if os.path.isabs(path) or not line:
        return "-"
    for name, first, last in functions(path):
        if first <= line <= last:
            return name
    return "-"


# ------------------------------------------------------------------ findings
def finding(tool, rule, level, message, path, line, col, aliases=(), related=(), flow=(),
            props=None):
    path = rel_path(path) if path else ""
    line = int(line) if line else 0
    col = int(col) if col else 0
    return {
        "tool": tool, "rule": rule, "aliases": [a for a in aliases if a != rule],
        "level": level if level in LEVELS else "warning", "message": message.strip(),
        "file": path, "line": line, "col": col, "function": function_at(path, line),
        "related": list(related), "flow": list(flow), "props": props or {},
    }


def key_of(f, rule=None):
    return "%s:%s:%s:%s" % (f["tool"], rule or f["rule"], f["file"] or "-", f["function"])


def _read(path, default=""):
    try:
        with open(path, encoding="utf-8", errors="replace") as fh:
            return fh.read()
    except OSError:
        return default


def _rc(out, tool):
    t = _read(os.path.join(out, tool + ".rc")).strip()
    return int(t) if t.lstrip("-").isdigit() else None


# cppcheck ----------------------------------------------------------------------
CPPCHECK_LEVEL = {"error": "error", "warning": "warning", "performance": "warning",
                  "portability": "warning", "style": "note", "information": "note"}
CPPCHECK_ENABLED = ("error", "warning", "style", "performance", "portability")


def read_cppcheck(out):
    path = os.path.join(out, "cppcheck.xml")
    root = ET.parse(path).getroot()
    ver = root.find("cppcheck")
    version = ver.get("version") if ver is not None else _read(os.path.join(out, "cppcheck.version")).split()[-1]
    results = []
    for e in root.iter("error"):
        locs = e.findall("location")
        first = locs[0] if locs else None
        related = [(rel_path(l.get("file")), int(l.get("line", 0)), int(l.get("column", 0)),
                    l.get("info") or "") for l in locs[1:]]
        props = {"severity": e.get("severity")}
        if e.get("cwe"):
            props["cwe"] = int(e.get("cwe"))
        sym = e.find("symbol")
        if sym is not None and sym.text:
            props["symbol"] = sym.text
        results.append(finding(
            "cppcheck", e.get("id"), CPPCHECK_LEVEL.get(e.get("severity"), "warning"),
            e.get("msg", ""),
            first.get("file") if first is not None else e.get("file0", ""),
            first.get("line") if first is not None else 0,
            first.get("column") if first is not None else 0,
            related=related, props=props))
    rules = {}
    el = os.path.join(out, "cppcheck-errorlist.xml")
    if os.path.exists(el):
        for e in ET.parse(el).getroot().iter("error"):
            if e.get("severity") in CPPCHECK_ENABLED:
                rules[e.get("id")] = {"text": e.get("msg", e.get("id")), "level":
                                      CPPCHECK_LEVEL.get(e.get("severity"), "warning"),
                                      "cwe": e.get("cwe")}
    for f in results:
        if f["rule"] not in rules:
            rules[f["rule"]] = {"text": f["message"], "level": f["level"],
                                "cwe": f["props"].get("cwe")}
        elif f["props"].get("cwe"):
            rules[f["rule"]]["cwe"] = f["props"]["cwe"]
    return {
        "tool": "cppcheck", "version": version, "fullName": "Cppcheck " + version,
        "informationUri": "https://cppcheck.sourceforge.io/", "rules": rules,
        "results": results, "ok": _rc(out, "cppcheck") == 0,
        "rc": _rc(out, "cppcheck"), "cmd": _read(os.path.join(out, "cppcheck.cmd")).strip(),
        "units": None, "props": {},
    }


# gcc -fanalyzer ----------------------------------------------------------------
def _gcc_rules(text):
    """-Wanalyzer-* options and their help texts from gcc --help=warnings."""
    rules, cur = {}, None
    for line in text.splitlines():
        m = re.match(r"^  (-Wanalyzer-[a-z0-9-]+)\s*(.*)$", line)
        if m:
            cur = m.group(1)[2:]
            rules[cur] = m.group(2).strip()
        elif cur and line.startswith("      ") and line.strip():
            rules[cur] = (rules[cur] + " " + line.strip()).strip()
        else:
            cur = None
    return rules


def _gcc_loc(loc):
    c = loc.get("caret", loc)
    return c.get("file", ""), c.get("line", 0), c.get("display-column", c.get("column", 0))


def read_gcc(out):
    results, units, failed = [], 0, []
    for path in sorted(glob.glob(os.path.join(out, "gcc-analyzer", "*.json"))):
        units += 1
        text = _read(path).strip()
        try:
            diags = json.loads(text) if text else None
        except ValueError:
            diags = None
        if not isinstance(diags, list):
            failed.append(os.path.basename(path))
            continue
        for d in diags:
            option = d.get("option") or ""
            rule = option[2:] if option.startswith("-W") else (option or "gcc-" + d.get("kind", "error"))
            locs = d.get("locations") or [{}]
            fpath, line, col = _gcc_loc(locs[0])
            related = []
            for ch in d.get("children") or []:
                cl = (ch.get("locations") or [{}])[0]
                p, ln, cc = _gcc_loc(cl)
                related.append((rel_path(p) if p else "", ln, cc, ch.get("message", "")))
            flow = []
            for ev in d.get("path") or []:
                p, ln, cc = _gcc_loc(ev.get("location") or {})
                flow.append((rel_path(p) if p else "", ln, cc, ev.get("description", ""),
                             ev.get("function", "")))
            props = {"kind": d.get("kind")}
            if (d.get("metadata") or {}).get("cwe"):
                props["cwe"] = d["metadata"]["cwe"]
            if d.get("option_url"):
                props["helpUri"] = d["option_url"]
            level = {"error": "error", "fatal error": "error", "warning": "warning",
                     "note": "note"}.get(d.get("kind"), "warning")
            results.append(finding("gcc-analyzer", rule, level, d.get("message", ""), fpath,
                                   line, col, related=related, flow=flow, props=props))
    rules = {r: {"text": t, "level": "warning"} for r, t in
             _gcc_rules(_read(os.path.join(out, "gcc-analyzer-options.txt"))).items()}
    for f in results:
        rules.setdefault(f["rule"], {"text": f["message"], "level": f["level"]})
        if f["props"].get("cwe"):
            rules[f["rule"]]["cwe"] = f["props"]["cwe"]
        if f["props"].get("helpUri"):
            rules[f["rule"]]["helpUri"] = f["props"]["helpUri"]
    version = _read(os.path.join(out, "gcc-analyzer.version")).strip() or "unknown"
    return {
        "tool": "gcc-analyzer", "version": version,
        "fullName": "GCC %s static analyzer (-fanalyzer)" % version,
        "informationUri": "https://gcc.gnu.org/onlinedocs/gcc/Static-Analyzer-Options.html",
        "rules": rules, "results": results,
        "ok": _rc(out, "gcc-analyzer") == 0 and not failed and units > 0,
        "rc": _rc(out, "gcc-analyzer"), "cmd": _read(os.path.join(out, "gcc-analyzer.cmd")).strip(),
        "units": units, "props": {"unitsWithoutOutput": failed},
    }


# clang-tidy --------------------------------------------------------------------
CT_LINE = re.compile(r"^(.+?):(\d+):(\d+): (warning|error|note|fatal error): (.*?)(?: \[([^\]\s]+)\])?$")


def parse_clang_tidy(text):
    results, cur = [], None
    for line in text.splitlines():
        m = CT_LINE.match(line)
        if not m:
            continue
        path, ln, col, kind, msg, checks = m.groups()
        if kind == "note":
            if cur is not None:
                cur["related"].append((rel_path(path), int(ln), int(col), msg))
            continue
        names = (checks or "clang-diagnostic-error").split(",")
        cur = finding("clang-tidy", names[0], "error" if kind != "warning" else "warning",
                      msg, path, ln, col, aliases=names[1:])
        results.append(cur)
    return results


def read_clang_tidy(out):
    results = parse_clang_tidy(_read(os.path.join(out, "clang-tidy.txt")))
    enabled = [l.strip() for l in _read(os.path.join(out, "clang-tidy-checks.txt")).splitlines()
               if l.startswith("    ") and l.strip()]
    vtext = _read(os.path.join(out, "clang-tidy.version"))
    m = re.search(r"version\s+([0-9][0-9.]*)", vtext)
    version = m.group(1) if m else "unknown"
    major = version.split(".")[0]
    rules = {}
    for c in enabled:
        rules[c] = {"text": "clang-tidy check " + c, "level": "warning",
                    "helpUri": CT_DOC.format(major=major, check=c)}
    for f in results:
        rules.setdefault(f["rule"], {"text": "clang-tidy check " + f["rule"], "level": f["level"]})
    disabled = []
    all_results = parse_clang_tidy(_read(os.path.join(out, "clang-tidy-all.txt")))
    for line in _read(os.path.join(out, "clang-tidy-disabled.txt")).splitlines():
        if "|" in line:
            check, reason = (s.strip() for s in line.split("|", 1))
            n = sum(1 for f in all_results if check in [f["rule"]] + f["aliases"])
            disabled.append({"check": check, "reason": reason, "findingsWhenEnabled": n})
    return {
        "tool": "clang-tidy", "version": version, "fullName": "clang-tidy " + version,
        "informationUri": "https://clang.llvm.org/extra/clang-tidy/", "rules": rules,
        "results": results, "ok": _rc(out, "clang-tidy") == 0, "rc": _rc(out, "clang-tidy"),
        "cmd": _read(os.path.join(out, "clang-tidy.cmd")).strip(),
        "units": None, "props": {"enabledChecks": enabled, "disabledChecks": disabled,
                                 "findingsWithEveryCheck": len(all_results)},
    }


def dedupe(run):
    """A finding in a header comes once per unit that includes it: keep one."""
    seen, uniq = set(), []
    for f in run["results"]:
        k = (f["rule"], f["file"], f["line"], f["col"], f["message"])
        if k not in seen:
            seen.add(k)
            uniq.append(f)
    run["results"] = uniq
    return run


# ------------------------------------------------------------------ accepted findings
KEY = re.compile(r"^\s*[-*]\s+`([^`]+)`\s*(.*)$")


def read_accepted(path):
    """{key: {"section", "justification", "note"}}, [errors]"""
    acc, errors = {}, []
    if not os.path.exists(path):
        return acc, errors
    sections, cur = [], None
    with open(path, encoding="utf-8") as fh:
        for no, line in enumerate(fh, 1):
            if line.startswith("## "):
                cur = {"title": line[3:].strip(), "line": no, "keys": [], "text": []}
                sections.append(cur)
            elif line.startswith("#"):
                cur = None
            elif cur is not None:
                m = KEY.match(line)
                if m:
                    cur["keys"].append((m.group(1).strip(), m.group(2).strip(" -\u2014:"), no))
                elif line.strip():
                    cur["text"].append(line.strip())
    for s in sections:
        just = " ".join(s["text"]).strip()
        if s["keys"] and len(just) < 20:
            errors.append("%s:%d: section '%s' accepts findings without a justification"
                          % (path, s["line"], s["title"]))
            continue
        for k, note, no in s["keys"]:
            parts = k.split(":")
            if len(parts) != 4 or parts[0] not in TOOLS or not all(parts):
                errors.append("%s:%d: '%s' is not tool:rule:file:function (tool one of %s)"
                              % (path, no, k, ", ".join(TOOLS)))
                continue
            if k in acc:
                errors.append("%s:%d: '%s' is listed twice" % (path, no, k))
                continue
            acc[k] = {"section": s["title"], "justification": just, "note": note, "line": no}
    return acc, errors


def apply_accepted(runs, acc):
    used = set()
    for run in runs:
        for f in run["results"]:
            f["accepted"] = None
            for r in [f["rule"]] + f["aliases"]:
                k = key_of(f, r)
                if k in acc:
                    f["accepted"] = dict(acc[k], key=k)
                    used.add(k)
                    break
    return [k for k in acc if k not in used]


# ------------------------------------------------------------------ SARIF
def _phys(path, line, col):
    loc = {"artifactLocation": {"uri": path}}
    if path and not os.path.isabs(path):
        loc["artifactLocation"]["uriBaseId"] = "SRCROOT"
    elif path:
        loc["artifactLocation"]["uri"] = "file://" + path
    region = {}
    if line and line > 0:
        region["startLine"] = int(line)
        if col and col > 0:
            region["startColumn"] = int(col)
    if region:
        loc["region"] = region
    return loc


def sarif_run(run):
    rule_ids = sorted(run["rules"])
    index = {r: i for i, r in enumerate(rule_ids)}
    rules = []
    for r in rule_ids:
        info = run["rules"][r]
        d = {"id": r, "name": r, "shortDescription": {"text": info["text"] or r},
             "defaultConfiguration": {"level": info.get("level", "warning")}}
        if info.get("helpUri"):
            d["helpUri"] = info["helpUri"]
        if info.get("cwe"):
            d["properties"] = {"tags": ["external/cwe/cwe-%s" % info["cwe"]]}
        rules.append(d)
    results = []
    seen = {}
    for f in sorted(run["results"], key=lambda f: (f["file"], f["line"], f["col"], f["rule"],
                                                  f["message"])):
        # fingerprint: key, message and the finding's rank among equal ones (no line
        # number, so that it survives edits elsewhere in the file)
        fp = key_of(f) + "\n" + f["message"]
        seen[fp] = seen.get(fp, 0) + 1
        fp = hashlib.sha256(("%s\n%d" % (fp, seen[fp])).encode("utf-8")).hexdigest()[:32]
        loc = {"physicalLocation": _phys(f["file"], f["line"], f["col"])}
        if f["function"] != "-":
            loc["logicalLocations"] = [{"name": f["function"], "fullyQualifiedName": f["function"],
                                        "kind": "function"}]
        res = {"ruleId": f["rule"], "ruleIndex": index[f["rule"]], "level": f["level"],
               "message": {"text": f["message"] or f["rule"]}, "locations": [loc],
               "partialFingerprints": {"qfocFinding/v1": fp}}
        if f["related"]:
            res["relatedLocations"] = []
            for i, (p, ln, cc, msg) in enumerate(f["related"], 1):
                rl = {"id": i, "physicalLocation": _phys(p, ln, cc)}
                if msg:
                    rl["message"] = {"text": msg}
                res["relatedLocations"].append(rl)
        if f["flow"]:
            tfl = []
            for p, ln, cc, desc, fn in f["flow"]:
                loc2 = {"physicalLocation": _phys(p, ln, cc), "message": {"text": desc or "-"}}
                if fn:
                    loc2["logicalLocations"] = [{"name": fn, "kind": "function"}]
                tfl.append({"location": loc2})
            res["codeFlows"] = [{"threadFlows": [{"locations": tfl}]}]
        props = dict(f["props"])
        props["qfocKey"] = key_of(f)
        if f["aliases"]:
            props["aliases"] = f["aliases"]
        props.pop("helpUri", None)
        res["properties"] = props
        if f.get("accepted"):
            a = f["accepted"]
            just = a["justification"] + ((" " + a["note"]) if a["note"] else "")
            res["suppressions"] = [{"kind": "external", "status": "accepted",
                                    "justification": "specs/static-accepted.md, %s: %s"
                                                     % (a["section"], just)}]
        results.append(res)
    inv = {"executionSuccessful": bool(run["ok"]), "commandLine": run["cmd"] or run["tool"]}
    if run["rc"] is not None:
        inv["exitCode"] = run["rc"]
    out = {
        "tool": {"driver": {"name": run["tool"], "fullName": run["fullName"],
                            "version": run["version"], "informationUri": run["informationUri"],
                            "rules": rules}},
        "automationDetails": {"id": "qfoc-static/%s/" % run["tool"]},
        "originalUriBaseIds": {"SRCROOT": {"description": {"text": "the root of the qfoc repository"}}},
        "columnKind": "unicodeCodePoints",
        "invocations": [inv],
        "results": results,
    }
    if run["props"]:
        out["properties"] = run["props"]
    return out


def sarif_log(runs):
    return {"$schema": SCHEMA, "version": "2.1.0", "runs": runs}


def validate(log, name):
    """The structure SARIF 2.1.0 requires of what this converter writes."""
    err = []

    def need(cond, what):
        if not cond:
            err.append("%s: %s" % (name, what))

    need(isinstance(log, dict), "top level is not an object")
    if not isinstance(log, dict):
        return err
    need(log.get("version") == "2.1.0", "version is not 2.1.0")
    need(isinstance(log.get("$schema", ""), str), "$schema is not a string")
    runs = log.get("runs")
    need(isinstance(runs, list), "runs is not an array")
    for ri, run in enumerate(runs or []):
        where = "runs[%d]" % ri
        drv = ((run.get("tool") or {}).get("driver")) or {}
        need(isinstance(drv.get("name"), str) and drv.get("name"), where + ".tool.driver.name missing")
        rules = drv.get("rules", [])
        need(isinstance(rules, list), where + ".tool.driver.rules is not an array")
        ids = [r.get("id") for r in rules]
        need(all(isinstance(i, str) and i for i in ids), where + ": a rule without id")
        need(len(set(ids)) == len(ids), where + ": duplicate rule ids")
        for r in rules:
            lvl = (r.get("defaultConfiguration") or {}).get("level", "warning")
            need(lvl in LEVELS, where + ": rule %s has level %r" % (r.get("id"), lvl))
            if "shortDescription" in r:
                need(isinstance(r["shortDescription"].get("text"), str),
                     where + ": rule %s shortDescription.text" % r.get("id"))
        for inv in run.get("invocations", []):
            need(isinstance(inv.get("executionSuccessful"), bool),
                 where + ": invocation without executionSuccessful")
        need(run.get("columnKind", "unicodeCodePoints") in ("utf16CodeUnits", "unicodeCodePoints"),
             where + ": columnKind")
        bases = run.get("originalUriBaseIds", {})
        results = run.get("results")
        need(isinstance(results, list), where + ".results is not an array")

        def check_loc(loc, w):
            pl = loc.get("physicalLocation")
            if pl is None:
                return
            al = pl.get("artifactLocation") or {}
            need(isinstance(al.get("uri"), str), w + ": artifactLocation.uri")
            if "uriBaseId" in al:
                need(al["uriBaseId"] in bases, w + ": uriBaseId %r not in originalUriBaseIds" % al["uriBaseId"])
            reg = pl.get("region")
            if reg is not None:
                need(isinstance(reg.get("startLine"), int) and reg["startLine"] >= 1, w + ": region.startLine")
                if "startColumn" in reg:
                    need(isinstance(reg["startColumn"], int) and reg["startColumn"] >= 1,
                         w + ": region.startColumn")
            for ll in loc.get("logicalLocations", []):
                need(isinstance(ll.get("name", ""), str), w + ": logicalLocation.name")

        for i, res in enumerate(results or []):
            w = "%s.results[%d]" % (where, i)
            msg = res.get("message") or {}
            need(isinstance(msg.get("text"), str) or isinstance(msg.get("id"), str), w + ": message.text")
            need(res.get("level", "warning") in LEVELS, w + ": level %r" % res.get("level"))
            if "ruleIndex" in res:
                ri2 = res["ruleIndex"]
                need(isinstance(ri2, int) and 0 <= ri2 < len(rules)
                     and rules[ri2].get("id") == res.get("ruleId"), w + ": ruleIndex / ruleId")
            need(isinstance(res.get("ruleId"), str), w + ": ruleId")
            for loc in res.get("locations", []):
                check_loc(loc, w)
            for loc in res.get("relatedLocations", []):
                check_loc(loc, w + ".relatedLocations")
            for cf in res.get("codeFlows", []):
                need(isinstance(cf.get("threadFlows"), list) and cf["threadFlows"], w + ": codeFlow.threadFlows")
                for tf in cf.get("threadFlows", []):
                    need(isinstance(tf.get("locations"), list), w + ": threadFlow.locations")
                    for tl in tf.get("locations", []):
                        check_loc(tl.get("location") or {}, w + ".codeFlows")
            for s in res.get("suppressions", []):
                need(s.get("kind") in ("inSource", "external"), w + ": suppression.kind")
                need(s.get("status", "accepted") in ("accepted", "underReview", "rejected"),
                     w + ": suppression.status")
    return err


# ------------------------------------------------------------------ report
def md_escape(s):
    return s.replace("|", "\\|").replace("\n", " ")


def write_report(path, runs, acc, stale, acc_errors, failed, counts):
    total, n_acc, n_un = counts
    L = ["# Static analysis beyond MISRA", "",
         "`make static` (tools/gates/static.sh, tools/gates/sarif.py): cppcheck's warning, style, performance "
         "and portability checks, gcc's static analyser (-fanalyzer) and clang-tidy's bugprone "
         "and cert checks.  SARIF 2.1.0: `build/static/qfoc.sarif` (one run per tool; "
         "`cppcheck.sarif`, `gcc-analyzer.sarif`, `clang-tidy.sarif` alone).  A finding passes "
         "only when `specs/static-accepted.md` accepts its key `tool:rule:file:function` with a "
         "justification; the SARIF result then carries it as an accepted suppression.", "",
         "**static: %d findings (%s), %d accepted, %d unaccepted**" % (
             total, ", ".join("%s %d" % (r["tool"], len(r["results"])) for r in runs), n_acc, n_un),
         "", "| tool | version | analysed | ran | findings | accepted | unaccepted |",
         "|---|---|---|---|---:|---:|---:|"]
    scope = {"cppcheck": "src/*.c, port_s32k/*.c", "gcc-analyzer": "src/*.c",
             "clang-tidy": "src/*.c, port_s32k/*.c and the project's headers"}
    for r in runs:
        a = sum(1 for f in r["results"] if f.get("accepted"))
        L.append("| %s | %s | %s | %s | %d | %d | %d |" % (
            r["tool"], r["version"], scope[r["tool"]], "yes" if r["ok"] else "**FAILED** (exit %s)" % r["rc"],
            len(r["results"]), a, len(r["results"]) - a))
    L += ["", "## Commands", ""]
    for r in runs:
        L.append("- %s: `%s`" % (r["tool"], r["cmd"]))
    ct = next(r for r in runs if r["tool"] == "clang-tidy")
    L += ["", "## Check selection", "",
          "- cppcheck: `--enable=warning,style,performance,portability` (%d message ids of these "
          "severities and of `error` in cppcheck's list); no inline suppressions are honoured." % sum(
              1 for _ in next(r for r in runs if r["tool"] == "cppcheck")["rules"]),
          "- gcc-analyzer: every `-Wanalyzer-*` warning of gcc %s (%d) plus `-Wanalyzer-too-complex`, "
          "so that an analysis cut short by the analyser's limits is a finding; %d units." % (
              next(r for r in runs if r["tool"] == "gcc-analyzer")["version"],
              len(next(r for r in runs if r["tool"] == "gcc-analyzer")["rules"]),
              next(r for r in runs if r["tool"] == "gcc-analyzer")["units"]),
          "- clang-tidy: %d checks enabled (`bugprone-*`, `cert-*`); with every check of both groups "
          "the run gives %d findings.  Disabled:" % (len(ct["props"]["enabledChecks"]),
                                                  ct["props"]["findingsWithEveryCheck"]), ""]
    if ct["props"]["disabledChecks"]:
        L += ["| disabled check | findings when enabled | reason |", "|---|---:|---|"]
        for d in ct["props"]["disabledChecks"]:
            L.append("| `%s` | %d | %s |" % (d["check"], d["findingsWhenEnabled"], md_escape(d["reason"])))
    else:
        L.append("(none)")
    L += ["", "## Findings per tool and rule", ""]
    for r in runs:
        L.append("### %s" % r["tool"])
        L.append("")
        if not r["results"]:
            L += ["No findings.", ""]
            continue
        by_rule = {}
        for f in r["results"]:
            by_rule.setdefault(f["rule"], []).append(f)
        for rule in sorted(by_rule):
            fs = sorted(by_rule[rule], key=lambda f: (f["file"], f["line"], f["col"]))
            L.append("#### `%s` (%d)" % (rule, len(fs)))
            L.append("")
            L += ["| where | function | message | status |", "|---|---|---|---|"]
            for f in fs:
                st = ("accepted: %s" % md_escape(f["accepted"]["section"])) if f.get("accepted") \
                    else "**not accepted**"
                L.append("| `%s:%d` | `%s` | %s | %s |" % (f["file"], f["line"], f["function"],
                                                           md_escape(f["message"]), st))
            L.append("")
    L += ["## Accepted findings", "",
          "From `specs/static-accepted.md` (the justification applies to every key of its section).", ""]
    sections = {}
    for k, a in acc.items():
        sections.setdefault(a["section"], {"just": a["justification"], "keys": []})["keys"].append(k)
    for title, s in sections.items():
        L += ["### %s" % title, "", s["just"], ""]
        for k in s["keys"]:
            n = sum(1 for r in runs for f in r["results"] if (f.get("accepted") or {}).get("key") == k)
            note = acc[k]["note"]
            L.append("- `%s`: %d finding%s%s" % (k, n, "" if n == 1 else "s",
                                                 (" (" + note + ")") if note else ""))
        L.append("")
    if stale or acc_errors or failed:
        L += ["## Gate problems", ""]
        L += ["- accepted key matches no finding: `%s`" % k for k in stale]
        L += ["- %s" % e for e in acc_errors]
        L += ["- %s" % e for e in failed]
        L.append("")
    with open(path, "w", encoding="utf-8") as fh:
        fh.write("\n".join(L).rstrip() + "\n")


# ------------------------------------------------------------------ main
def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--out", default=os.path.join(TOP, "build", "static"))
    ap.add_argument("--accepted", default=os.path.join(TOP, "specs", "static-accepted.md"))
    args = ap.parse_args()
    out = args.out

    runs = [dedupe(read_cppcheck(out)), dedupe(read_gcc(out)), dedupe(read_clang_tidy(out))]
    acc, acc_errors = read_accepted(args.accepted)
    stale = apply_accepted(runs, acc)

    problems = []
    logs = {}
    for r in runs:
        log = sarif_log([sarif_run(r)])
        problems += validate(log, r["tool"] + ".sarif")
        logs[r["tool"]] = log
        with open(os.path.join(out, r["tool"] + ".sarif"), "w", encoding="utf-8") as fh:
            json.dump(log, fh, indent=1, sort_keys=False)
            fh.write("\n")
    merged = sarif_log([logs[t]["runs"][0] for t in TOOLS])
    problems += validate(merged, "qfoc.sarif")
    with open(os.path.join(out, "qfoc.sarif"), "w", encoding="utf-8") as fh:
        json.dump(merged, fh, indent=1)
        fh.write("\n")

    failed = []
    for r in runs:
        if not r["ok"]:
            bad = r["props"].get("unitsWithoutOutput")
            failed.append("%s did not run to completion (exit %s%s)" % (
                r["tool"], r["rc"], "; no diagnostics output for " + ", ".join(bad) if bad else ""))
    failed += ["SARIF structure: " + p for p in problems]
    total = sum(len(r["results"]) for r in runs)
    n_acc = sum(1 for r in runs for f in r["results"] if f.get("accepted"))
    n_un = total - n_acc
    write_report(os.path.join(out, "static.md"), runs, acc, stale, acc_errors, failed,
                 (total, n_acc, n_un))

    for r in runs:
        for f in r["results"]:
            if not f.get("accepted"):
                print("%s:%d:%d: %s [%s] not accepted: %s (key %s)" % (
                    f["file"], f["line"], f["col"], r["tool"], f["rule"], f["message"], key_of(f)))
    for k in stale:
        print("static: %s accepts %s, which matches no finding: remove it"
              % (rel_path(args.accepted), k))
    for e in acc_errors + failed:
        print("static: " + e)
    print("static: %d findings (%s), %d accepted, %d unaccepted" % (
        total, ", ".join("%s %d" % (r["tool"], len(r["results"])) for r in runs), n_acc, n_un))
    return 1 if (n_un or stale or acc_errors or failed) else 0


if __name__ == "__main__":
    sys.exit(main())
