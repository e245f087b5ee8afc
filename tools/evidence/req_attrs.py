#!/usr/bin/env python3
"""Requirement attributes and the clause-level trace of the safety requirements.

The syntax is given in specs/requirements/README.md.  Each requirement heading
'### REQ-<MOD>-NNN title' is followed, on the very next line, by

  Attributes: ASIL <QM|A|B|C|D> · kind <safety|functional|tool|simulation> · verification <m>[, <m>...][ · ASR <ASR-id>[, <ASR-id>...]]

with the methods <m> out of proof, analysis, test, review (in that order, each once), and,
on the line after it when present (required for every requirement above QM and every
requirement of kind safety),

  Clauses: <ref>[, <ref>...]

where a <ref> is one of
  <function>:<label>   a behaviour or a named ensures / requires / assigns clause of the
                       ACSL contract of <function> (include/qfoc/*.h or src/*.c); the label
                       'assigns' is the function's unnamed assigns clause, the label 'rte'
                       its runtime-error goals (-wp-rte) with those of the static functions
                       of its unit that it calls
  lemma <name>         a lemma of specs/*.acsl
  cbmc <harness>       a CBMC harness proofs/cbmc/<harness>/harness.c naming the requirement
  test <name>          a CMocka or pytest test naming the requirement
  target <name>        a target-equivalence group (tools/target_test/tt_groups.c) or checking
                       program (tt_gen.c, tt_runner.c, target_test.sh) naming the requirement
  bench <name>         a limit constant or a function of the bench (tools/bench/*.py) whose
                       rows name the requirement

Used by tools/evidence/trace.py (the gates and the matrix), tools/evidence/gen_manual.py
(the ASR table of specs/safety-manual.md) and tools/evidence/figures.py.  Requirements:
REQ-EVD-015 .. REQ-EVD-018 (specs/requirements/evidence.md).
"""
import glob
import json
import os
import re
import xml.etree.ElementTree as ET

try:  # Python 3.11
    import tomllib
except ImportError:  # pragma: no cover
    tomllib = None

ASILS = ("QM", "A", "B", "C", "D")
KINDS = ("safety", "functional", "tool", "simulation")
METHODS = ("proof", "analysis", "test", "review")
SEP = " \u00b7 "
HEAD = re.compile(r"^###\s+(REQ-[A-Z0-9]+-\d{3})\s+(.*)$")
ASR_ID = re.compile(r"^ASR-(?:\d{2}|P\d+)$")
IDENT = r"[A-Za-z_]\w*"
REF_FUNC = re.compile(rf"^({IDENT}):({IDENT})$")
REF_KIND = re.compile(r"^(lemma|cbmc|test|target|bench) ([A-Za-z_][\w.]*)$")
ASR_FILE = "specs/asr.toml"
WP_DIR = "build/wp"
JUNIT_DIR = "build/junit"


def _read(path):
    with open(path, encoding="utf-8") as f:
        return f.read()


# ------------------------------------------------------------------ the ASR list

def load_asrs(root="."):
    """specs/asr.toml: ID -> dict(id, asil, scope, statement, evidence), in file order, and
    the errors found in it."""
    path = os.path.join(root, ASR_FILE)
    if not os.path.exists(path):
        return {}, [f"{ASR_FILE} is missing"]
    with open(path, "rb") as f:
        data = tomllib.load(f)
    out, errors = {}, []
    for i, a in enumerate(data.get("asr", [])):
        aid = a.get("id", "")
        if not ASR_ID.match(aid):
            errors.append(f"{ASR_FILE}: entry {i + 1}: id '{aid}' is not ASR-NN or ASR-Pn")
            continue
        if a.get("asil") not in ASILS:
            errors.append(f"{ASR_FILE}: {aid}: asil '{a.get('asil')}' is not one of {', '.join(ASILS)}")
        for key in ("statement", "scope"):
            if not str(a.get(key, "")).strip():
                errors.append(f"{ASR_FILE}: {aid}: no {key}")
        if aid in out:
            errors.append(f"{ASR_FILE}: {aid} is defined twice")
        out[aid] = dict(a)
    return out, errors


# ------------------------------------------------------------------ parsing the attribute lines

def parse_attributes(line):
    """The attributes of an 'Attributes:' line: (dict(asil, kind, verification, asr), None)
    or (None, the reason it is not valid)."""
    if not line.startswith("Attributes: "):
        return None, "no 'Attributes:' line right after the heading"
    fields = line[len("Attributes: "):].split(SEP)
    if len(fields) not in (3, 4):
        return None, (f"'{line}': expected 'ASIL x{SEP}kind y{SEP}verification m, ...' "
                      f"and optionally '{SEP}ASR ASR-nn', separated by '{SEP.strip()}'")
    words = [f.split(" ", 1) for f in fields]
    names = ["ASIL", "kind", "verification", "ASR"][:len(fields)]
    for (w, _rest), want in zip(words, names):
        if w != want:
            return None, f"'{line}': field '{w}' where '{want}' is expected"
    if any(len(w) != 2 or w[1] != w[1].strip() or not w[1] for w in words):
        return None, f"'{line}': a field without its value, or with extra spaces"
    asil, kind, ver = words[0][1], words[1][1], words[2][1]
    if asil not in ASILS:
        return None, f"invalid ASIL '{asil}' (one of {', '.join(ASILS)})"
    if kind not in KINDS:
        return None, f"invalid kind '{kind}' (one of {', '.join(KINDS)})"
    methods = ver.split(", ")
    for m in methods:
        if m not in METHODS:
            return None, f"invalid verification method '{m}' (out of {', '.join(METHODS)}, ', '-separated)"
    if len(set(methods)) != len(methods) or methods != sorted(methods, key=METHODS.index):
        return None, (f"verification '{ver}': each method once, in the order "
                      f"{', '.join(METHODS)}")
    asr = []
    if len(fields) == 4:
        asr = words[3][1].split(", ")
        for a in asr:
            if not ASR_ID.match(a):
                return None, f"invalid ASR '{a}' (ASR-NN or ASR-Pn, ', '-separated)"
        if len(set(asr)) != len(asr) or asr != sorted(asr, key=asr_key):
            return None, f"ASR '{words[3][1]}': each once, in order"
    return {"asil": asil, "kind": kind, "verification": methods, "asr": asr}, None


def asr_key(aid):
    m = re.match(r"ASR-(P?)(\d+)$", aid)
    return (1 if m and m.group(1) else 0, int(m.group(2)) if m else 0, aid)


def parse_clauses(line):
    """The references of a 'Clauses:' line: (list of dict(ref, kind, name, label), errors)."""
    refs, errors = [], []
    body = line[len("Clauses: "):]
    if not body.strip():
        return [], ["'Clauses:' line without a reference"]
    for ref in body.split(", "):
        m = REF_FUNC.match(ref)
        if m:
            refs.append({"ref": ref, "kind": "acsl", "name": m.group(1), "label": m.group(2)})
            continue
        m = REF_KIND.match(ref)
        if m:
            refs.append({"ref": ref, "kind": m.group(1), "name": m.group(2), "label": None})
            continue
        errors.append(f"clause reference '{ref}' is not '<function>:<label>', 'lemma <name>', "
                      f"'cbmc <harness>', 'test <name>', 'target <name>' or 'bench <name>'")
    if len({r["ref"] for r in refs}) != len(refs):
        errors.append("a clause reference is given twice")
    return refs, errors


def load_attributes(root="."):
    """ID -> dict(file, line, attrs, clauses, errors) for every requirement heading of
    specs/requirements/*.md.  The 'Attributes:' line must be the line right after the
    heading, the 'Clauses:' line (if any) the one after it; neither may appear anywhere
    else."""
    out = {}
    for path in sorted(glob.glob(os.path.join(root, "specs/requirements/*.md"))):
        rel = os.path.relpath(path, root)
        lines = _read(path).splitlines()
        owner = {}
        for i, ln in enumerate(lines):
            m = HEAD.match(ln.strip())
            if not m:
                continue
            rid = m.group(1)
            rec = {"file": rel, "line": i + 1, "attrs": None, "clauses": None, "errors": []}
            out[rid] = rec
            nxt = lines[i + 1] if i + 1 < len(lines) else ""
            attrs, err = parse_attributes(nxt)
            if err:
                rec["errors"].append(err)
            else:
                rec["attrs"] = attrs
                owner[i + 1] = rid
                if i + 2 < len(lines) and lines[i + 2].startswith("Clauses:"):
                    refs, errs = parse_clauses(lines[i + 2])
                    rec["clauses"] = refs
                    rec["errors"] += errs
                    owner[i + 2] = rid
        for i, ln in enumerate(lines):
            if (ln.startswith("Attributes:") or ln.startswith("Clauses:")) and i not in owner:
                out.setdefault("?", {"file": rel, "line": i + 1, "attrs": None, "clauses": None,
                                     "errors": []})["errors"].append(
                    f"{rel}:{i + 1}: '{ln.split(':')[0]}:' line not right after a requirement heading")
    return out


def check_attributes(attrs, asrs):
    """Gate failures of the attribute lines themselves and of their consistency with the ASR
    list: a requirement of kind safety names at least one ASR, and only such a requirement
    does; its ASIL is the highest ASIL assumed for its ASRs (QM when none); a requirement
    above QM, and every requirement of kind safety, has a 'Clauses:' line."""
    failures = []
    for rid, rec in sorted(attrs.items()):
        where = f"{rid} ({rec['file']}:{rec['line']})" if rid != "?" else rec["file"]
        for e in rec["errors"]:
            failures.append(f"{where}: {e}")
        a = rec["attrs"]
        if a is None:
            continue
        if a["kind"] == "safety" and not a["asr"]:
            failures.append(f"{where}: kind safety without an ASR it implements (field 'ASR')")
        if a["asr"] and a["kind"] != "safety":
            failures.append(f"{where}: implements {', '.join(a['asr'])} but its kind is {a['kind']}, not safety")
        for aid in a["asr"]:
            if aid not in asrs:
                failures.append(f"{where}: names {aid}, which {ASR_FILE} does not define")
        assumed = [asrs[x]["asil"] for x in a["asr"] if x in asrs and asrs[x].get("asil") in ASILS]
        want = max(assumed, key=ASILS.index) if assumed else "QM"
        if a["asil"] != want:
            failures.append(f"{where}: ASIL {a['asil']}, but the highest ASIL assumed for its ASRs "
                            f"({', '.join(a['asr']) or 'none'}) is {want} ({ASR_FILE})")
        if (a["asil"] != "QM" or a["kind"] == "safety") and not rec["clauses"]:
            failures.append(f"{where}: ASIL {a['asil']}, kind {a['kind']}, without a 'Clauses:' line "
                            f"naming the contract clauses, lemmas, CBMC harnesses or tests that state it")
    return failures


# ------------------------------------------------------------------ ACSL contracts

ACSL_BLOCK = re.compile(r"/\*@(.*?)\*/", re.S)
LABEL = re.compile(r"\b(behavior|ensures|requires|assigns|assumes)\s+([A-Za-z_]\w*)\s*:")
CONTRACT_WORD = re.compile(r"(?<!loop )\b(requires|ensures|assigns|behavior)\b")
DECL_AFTER = re.compile(r"\s*((?:(?:static|inline|extern|const|unsigned|signed|struct)\s+)*"
                        r"[A-Za-z_]\w*[\s\*]+)([A-Za-z_]\w*)\s*\(")
C_KEYWORDS = {"if", "for", "while", "switch", "return", "sizeof", "do", "else"}


def acsl_index(root="."):
    """Function -> dict(file, behaviors, ensures, requires, assigns) of every ACSL function
    contract in include/qfoc/*.h and src/*.c, and the set of functions defined (with a body)
    there, as (unit, name) -> file."""
    index, defined = {}, {}
    files = sorted(glob.glob(os.path.join(root, "include/qfoc/*.h"))) + sorted(
        glob.glob(os.path.join(root, "src/*.c")))
    for path in files:
        rel = os.path.relpath(path, root)
        text = _read(path)
        for m in ACSL_BLOCK.finditer(text):
            body = m.group(1)
            if not CONTRACT_WORD.search(body):
                continue
            d = DECL_AFTER.match(text, m.end())
            if not d or d.group(2) in C_KEYWORDS or d.group(1).strip() in C_KEYWORDS:
                continue
            name = d.group(2)
            rec = index.setdefault(name, {"file": rel, "behaviors": set(), "ensures": set(),
                                          "requires": set(), "assigns": False})
            for lm in LABEL.finditer(body):
                kind = lm.group(1)
                if kind == "behavior":
                    rec["behaviors"].add(lm.group(2))
                elif kind in ("ensures", "requires"):
                    rec[kind].add(lm.group(2))
            if re.search(r"(?<!loop )\bassigns\b", body):
                rec["assigns"] = True
        unit = os.path.splitext(os.path.basename(path))[0]
        for fm in re.finditer(r"^[ \t]*(?:static[ \t]+)?(?:inline[ \t]+)?[A-Za-z_][\w \t\*]*?\b"
                              r"([A-Za-z_]\w*)[ \t]*\([^;{}]*\)[ \t\n]*\{", text, re.M):
            if fm.group(1) not in C_KEYWORDS:
                defined.setdefault((unit, fm.group(1)), rel)
    return index, defined


def clause_exists(ref, index, defined):
    """None when the <function>:<label> reference names a clause of that function's contract,
    else the reason."""
    fn, label = ref["name"], ref["label"]
    if label == "rte":
        if any(n == fn for (_u, n) in defined):
            return None
        return f"{fn} is not a function defined in src/*.c or include/qfoc/*.h"
    c = index.get(fn)
    if c is None:
        return f"{fn} has no ACSL contract in include/qfoc/*.h or src/*.c"
    if label == "assigns":
        return None if c["assigns"] else f"the contract of {fn} has no assigns clause"
    if label in c["behaviors"] or label in c["ensures"] or label in c["requires"]:
        return None
    known = sorted(c["behaviors"] | c["ensures"] | c["requires"])
    return (f"the contract of {fn} ({c['file']}) has no behaviour or ensures / requires clause "
            f"named '{label}' (it has: {', '.join(known) or 'no named clause'})")


# ------------------------------------------------------------------ WP results (-wp-report-json)

def load_wp_json(root=".", wp_dir=WP_DIR):
    """The per-property goals of the -wp-report-json files make prove wrote (one per job,
    <unit>[@k].json; wp-summary.json is not one): dict(files, functions: (unit, fn) ->
    {property: (total, valid)}, lemmas: {lemma_<name>: (total, valid)}), or None when there
    is none."""
    files = sorted(p for p in glob.glob(os.path.join(root, wp_dir, "*.json"))
                   if os.path.basename(p) != "wp-summary.json")
    if not files:
        return None
    out = {"files": [os.path.relpath(p, root) for p in files], "functions": {}, "lemmas": {},
           "unreadable": []}
    for p in files:
        try:
            rep = json.loads(_read(p))
        except (OSError, ValueError):
            out["unreadable"].append(os.path.relpath(p, root))
            continue
        if not isinstance(rep, dict) or not ("wp:functions" in rep or "wp:axiomatics" in rep):
            out["unreadable"].append(os.path.relpath(p, root))
            continue
        unit = os.path.basename(p)[:-5].split("@")[0]
        for fn, props in (rep.get("wp:functions") or {}).items():
            sec = out["functions"].setdefault((unit, fn), {})
            for prop, res in props.items():
                if prop == "wp:section":
                    continue
                main = (res or {}).get("wp:main", {})
                t, v = sec.get(prop, (0, 0))
                sec[prop] = (t + int(main.get("total", 0)), v + int(main.get("valid", 0)))
        for _ax, props in (rep.get("wp:axiomatics") or {}).items():
            for prop, res in props.items():
                if prop == "wp:section":
                    continue
                main = (res or {}).get("wp:main", {})
                t, v = out["lemmas"].get(prop, (0, 0))
                out["lemmas"][prop] = (t + int(main.get("total", 0)), v + int(main.get("valid", 0)))
    return out


CLAUSE_KINDS = r"(?:ensures|assigns|requires|exits|breaks|continues|returns|allocates|frees|terminates|decreases)"


def wp_goals(ref, index, wp, helpers):
    """(total, valid, sections found) of the WP goals of one <function>:<label> reference.
    helpers: (unit, public function) -> static functions it calls."""
    fn, label = ref["name"], ref["label"]
    c = index.get(fn, {"behaviors": set(), "ensures": set(), "requires": set()})
    f = re.escape(fn)
    behaviours = "|".join(re.escape(b) for b in sorted(c["behaviors"]))
    bpre = f"(?:(?:{behaviours})_)?" if behaviours else ""
    if label == "rte":
        pats, scope = [re.compile(rf"^{f}_assert_rte_")], "own"
    elif label == "assigns":
        pats, scope = [re.compile(rf"^{f}_assigns(?:_|$)")], "own"
    elif label in c["behaviors"]:
        pats, scope = [re.compile(rf"^{f}_{re.escape(label)}_{CLAUSE_KINDS}(?:_|$)")], "own"
    elif label in c["requires"] and label not in c["ensures"]:
        pats, scope = [re.compile(rf"^{f}_{bpre}requires_{re.escape(label)}(?:_\d+)?$")], "callers"
    else:
        pats, scope = [re.compile(rf"^{f}_{bpre}ensures_{re.escape(label)}(?:_\d+)?$")], "own"
    total = valid = 0
    sections = 0
    for (unit, name), props in wp["functions"].items():
        if scope == "own":
            mine = name == fn or (label == "rte" and name in helpers.get((unit, fn), ()))
            if not mine:
                continue
            pats_here = pats if name == fn else [re.compile(rf"^{re.escape(name)}_assert_rte_")]
        else:
            pats_here = pats
        if name == fn:
            sections += 1
        for prop, (t, v) in props.items():
            if any(p.match(prop) for p in pats_here):
                total += t
                valid += v
    return total, valid, sections


def junit_results(root=".", junit_dir=JUNIT_DIR):
    """Test name -> 'passed' / 'failed' / 'skipped' from build/junit/*.xml, or None when
    there is no JUnit file."""
    files = sorted(glob.glob(os.path.join(root, junit_dir, "*.xml")))
    if not files:
        return None
    out = {}
    for p in files:
        try:
            tree = ET.parse(p)
        except (ET.ParseError, OSError):
            continue
        for tc in tree.iter("testcase"):
            name = (tc.get("name") or "").split("[")[0]
            if tc.find("failure") is not None or tc.find("error") is not None:
                st = "failed"
            elif tc.find("skipped") is not None:
                st = "skipped"
            else:
                st = "passed"
            if out.get(name) != "failed":
                out[name] = st if out.get(name) in (None, "skipped", st) else out[name]
    return out


def resolve_clauses(rid, refs, ctx):
    """The clause entries of a requirement (ref, kind, status, goals, proved, ok) and the gate
    failures.  ctx: dict(index, defined, wp, helpers, lemmas, harness_ids, cbmc_res,
    test_ids, junit).  ok is True (held), False (failed) or None (no result here: never
    green)."""
    out, failures = [], []
    for ref in refs:
        e = {"ref": ref["ref"], "kind": ref["kind"], "status": "", "goals": None, "proved": None,
             "ok": None}
        if ref["kind"] == "acsl":
            why = clause_exists(ref, ctx["index"], ctx["defined"])
            if why:
                failures.append(f"{rid}: unknown clause '{ref['ref']}': {why}")
                e["status"], e["ok"] = "unknown clause", False
            elif ctx["wp"] is None:
                e["status"] = "no WP result"
            else:
                t, v, sections = wp_goals(ref, ctx["index"], ctx["wp"], ctx["helpers"])
                e["goals"], e["proved"] = t, v
                if ref["label"] in ctx["index"].get(ref["name"], {}).get("requires", ()) and \
                        ref["label"] not in ctx["index"][ref["name"]]["ensures"]:
                    if t == 0:
                        e["status"] = "precondition: no call site proved here (the caller's obligation)"
                    else:
                        e["status"] = f"precondition: {v}/{t} goals at the call sites"
                        e["ok"] = v == t
                elif sections == 0:
                    e["status"] = f"no WP result for {ref['name']} (not in {WP_DIR})"
                elif t == 0:
                    e["status"], e["ok"] = "no WP goal", False
                else:
                    e["ok"] = v == t
                    e["status"] = f"proved {v}/{t}" if v == t else f"NOT PROVED {v}/{t}"
                if e["ok"] is False:
                    failures.append(f"{rid}: clause '{ref['ref']}' does not hold in the WP report "
                                    f"({WP_DIR}/*.json): {e['status']}")
        elif ref["kind"] == "lemma":
            if ref["name"] not in ctx["lemmas"]:
                failures.append(f"{rid}: unknown clause '{ref['ref']}': no lemma {ref['name']} in specs/*.acsl")
                e["status"], e["ok"] = "unknown lemma", False
            elif ctx["wp"] is None:
                e["status"] = "no WP result"
            else:
                t, v = ctx["wp"]["lemmas"].get("lemma_" + ref["name"], (0, 0))
                e["goals"], e["proved"] = t, v
                if t == 0:
                    e["status"] = "no WP result for the lemma"
                else:
                    e["ok"] = v == t
                    e["status"] = f"proved {v}/{t}" if v == t else f"NOT PROVED {v}/{t}"
                    if v != t:
                        failures.append(f"{rid}: lemma {ref['name']} is not proved ({v}/{t})")
        elif ref["kind"] == "cbmc":
            ids = ctx["harness_ids"].get(ref["name"])
            if ids is None:
                failures.append(f"{rid}: unknown clause '{ref['ref']}': no harness proofs/cbmc/{ref['name']}/harness.c")
                e["status"], e["ok"] = "unknown harness", False
            elif rid not in ids:
                failures.append(f"{rid}: clause '{ref['ref']}': the harness does not name {rid}")
                e["status"], e["ok"] = "harness does not name the requirement", False
            else:
                res = ctx["cbmc_res"].get(ref["name"])
                if res is None:
                    e["status"] = "no CBMC result"
                else:
                    e["goals"] = res["properties"]
                    e["proved"] = res["properties"] - res["failed"]
                    e["ok"] = res["result"] == "PASS"
                    e["status"] = f"{res['result']} ({res['properties']} properties, proofs/cbmc/results.md)"
        elif ref["kind"] == "target":
            ids = ctx["target_ids"].get(ref["name"])
            if ids is None:
                failures.append(f"{rid}: unknown clause '{ref['ref']}': no target-equivalence group or "
                                f"checking program {ref['name']}")
                e["status"], e["ok"] = "unknown target test", False
            elif rid not in ids:
                failures.append(f"{rid}: clause '{ref['ref']}': it does not name {rid}")
                e["status"], e["ok"] = "does not name the requirement", False
            else:
                st = (ctx.get("target_results") or {}).get(ref["name"])
                if st is None:
                    e["status"] = "no target-test result (build/target_test/target.txt)"
                else:
                    e["status"], e["ok"] = st, st == "identical"
        elif ref["kind"] == "bench":
            if ref["name"] not in ctx["bench_names"]:
                failures.append(f"{rid}: unknown clause '{ref['ref']}': no limit or function {ref['name']} "
                                f"in tools/bench/*.py")
                e["status"], e["ok"] = "unknown bench name", False
            else:
                rows = [r for r in (ctx.get("bench_rows") or []) if rid in str(r.get("requirement", ""))]
                if ctx.get("bench_rows") is None or not rows:
                    e["status"] = "no bench result (build/bench/bench.json)"
                else:
                    over = [r for r in rows if r.get("result") in ("OVER", "UNSOUND")]
                    e["ok"] = not over
                    e["status"] = (f"{len(rows)} bench rows within their limits" if not over
                                   else f"{len(over)} of {len(rows)} bench rows OVER their limits")
        else:  # test
            ids = ctx["test_ids"].get(ref["name"])
            if ids is None:
                failures.append(f"{rid}: unknown clause '{ref['ref']}': no CMocka or pytest test {ref['name']}")
                e["status"], e["ok"] = "unknown test", False
            elif rid not in ids:
                failures.append(f"{rid}: clause '{ref['ref']}': the test does not name {rid}")
                e["status"], e["ok"] = "test does not name the requirement", False
            elif ctx["junit"] is None or ref["name"] not in ctx["junit"]:
                e["status"] = "no test result (build/junit)"
            else:
                st = ctx["junit"][ref["name"]]
                e["status"], e["ok"] = st, st == "passed"
        out.append(e)
    return out, failures


def bench_names(root="."):
    """The module-level names (constants and functions) of tools/bench/*.py."""
    names = set()
    for p in sorted(glob.glob(os.path.join(root, "tools/bench/*.py"))):
        text = _read(p)
        names.update(re.findall(r"^def ([A-Za-z_]\w*)\s*\(", text, re.M))
        names.update(re.findall(r"^([A-Z_][A-Z0-9_]*)(?:\s*,\s*[A-Z_][A-Z0-9_]*)*\s*=", text, re.M))
        for m in re.finditer(r"^((?:[A-Z_][A-Z0-9_]*\s*,\s*)+[A-Z_][A-Z0-9_]*)\s*=", text, re.M):
            names.update(n.strip() for n in m.group(1).split(","))
    return names


def bench_rows(root="."):
    """The rows of build/bench/bench.json, or None when the bench has not run."""
    try:
        with open(os.path.join(root, "build/bench/bench.json"), encoding="utf-8") as f:
            table = json.load(f).get("table")
        return table if isinstance(table, list) else None
    except (OSError, ValueError, AttributeError):
        return None


def target_results(root="."):
    """Group -> 'identical' / 'DIFFERENT' from build/target_test/target.txt, or None."""
    path = os.path.join(root, "build/target_test/target.txt")
    if not os.path.exists(path):
        return None
    out = {}
    for ln in _read(path).splitlines():
        m = re.match(r"^([\w.]+): (?:\d+ vectors, (identical)|(DIFFERENT))", ln)
        if m:
            out[m.group(1)] = m.group(2) or m.group(3)
    return out


def make_context(root, callees, harness_list, test_list, target_list, cbmc_res, acsl_decls):
    """The context resolve_clauses needs, from what trace.py has read."""
    index, defined = acsl_index(root)
    helpers = {}
    for (unit, pub), fns in callees.items():
        helpers[(unit, pub)] = set(fns)
    test_ids = {}
    for kind, _f, name, i, _tg in test_list:
        if kind in ("cmocka", "pytest"):
            test_ids.setdefault(name, set()).update(i)
    target_ids = {}
    for _f, name, i in target_list:
        target_ids.setdefault(name[len("group "):] if name.startswith("group ") else name, set()).update(i)
    return {"index": index, "defined": defined, "wp": load_wp_json(root), "helpers": helpers,
            "lemmas": {d["name"] for d in acsl_decls if d["kind"] == "lemma"},
            "harness_ids": {h: set(i) for h, _p, i in harness_list}, "cbmc_res": cbmc_res,
            "test_ids": test_ids, "junit": junit_results(root), "target_ids": target_ids,
            "target_results": target_results(root), "bench_names": bench_names(root),
            "bench_rows": bench_rows(root)}


# ------------------------------------------------------------------ verification methods

def found_methods(entry):
    """The methods the trace finds for a matrix entry: proof (WP goals of a contract or a
    lemma, or a CBMC harness that passes), analysis (a bench row naming the requirement),
    test (a CMocka, pytest or target-equivalence test, or a scenario), review (none: the
    repository holds no review record)."""
    found = set()
    if entry.get("proof"):
        found.add("proof")
    kinds = {t["kind"] for t in entry.get("tests", [])}
    if "bench" in kinds:
        found.add("analysis")
    if kinds - {"bench"} or entry.get("scenarios"):
        found.add("test")
    return found


def derive_methods(verified_by):
    """The methods a 'Verified by:' text lists (the rule of specs/requirements/README.md)."""
    t = verified_by
    out = []
    if re.search(r"(?i)contract|ensures|behaviou?r|\bWP\b|lemma|CBMC|harness|-wp-rte", t):
        out.append("proof")
    if re.search(r"(?i)make bench|bench row|\bEVA\b|MISRA|static analysis", t):
        out.append("analysis")
    if re.search(r"(?i)\btest|pytest|CMocka|tt_gen|tt_runner|target_test|boot_check|check_image|"
                 r"demo page|arch_check", t):
        out.append("test")
    if re.search(r"(?i)\breview", t):
        out.append("review")
    return out


# ------------------------------------------------------------------ the trace's hook

def apply_to_matrix(matrix, ctx, root="."):
    """Add 'attributes' and 'clauses' to every matrix entry of trace.py and return the gate
    failures: attribute lines, the ASR list, claimed verification methods the trace does
    not find, and clause references."""
    attrs = load_attributes(root)
    asrs, failures = load_asrs(root)
    failures = list(failures) + check_attributes(attrs, asrs)
    for e in matrix:
        rec = attrs.get(e["id"])
        a = rec["attrs"] if rec else None
        e["attributes"] = a
        e["clauses"] = []
        if a is None:
            continue
        found = found_methods(e)
        for m in a["verification"]:
            if m not in found:
                what = {"proof": "a contract with WP goals, a lemma or a passing CBMC harness",
                        "analysis": "a bench row", "test": "a test or a scenario",
                        "review": "a review record"}[m]
                failures.append(f"{e['id']} ({e['file']}) claims verification '{m}', but the trace "
                                f"finds no {what} for it")
        if rec["clauses"]:
            e["clauses"], f = resolve_clauses(e["id"], rec["clauses"], ctx)
            failures += f
    return failures


def attribute_totals(matrix):
    """Counts per ASIL, per kind and per verification method."""
    t = {"asil": {a: 0 for a in reversed(ASILS)}, "kind": {k: 0 for k in KINDS},
         "verification": {m: 0 for m in METHODS}, "without_attributes": 0,
         "clauses": 0, "clauses_held": 0, "clauses_no_result": 0}
    for e in matrix:
        a = e.get("attributes")
        if not a:
            t["without_attributes"] += 1
            continue
        t["asil"][a["asil"]] += 1
        t["kind"][a["kind"]] += 1
        for m in a["verification"]:
            t["verification"][m] += 1
        for c in e.get("clauses", []):
            t["clauses"] += 1
            t["clauses_held"] += c["ok"] is True
            t["clauses_no_result"] += c["ok"] is None
    return t
