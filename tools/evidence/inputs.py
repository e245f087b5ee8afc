#!/usr/bin/env python3
"""The inputs of every gate's result, in one place, and the stamp that ties a result to them.

A gate's result file (proofs/wp/results.md, proofs/cbmc/results.md, build/eva/eva-all.json,
build/misra/compliance-summary.json, build/coverage/coverage.xml, build/bench/bench.json,
...) carries the SHA-256 of the inputs it was computed from, written into it by the gate
when it ends (the "stamp"), with the run's UTC time.  `make evidence` computes the digest
again from the checkout: a result whose inputs changed since its run is stale (red), never
green (specs/requirements/evidence.md, REQ-EVD-028).

The input set of each gate is defined here and nowhere else (GATES below): the sorted input
files (sources, headers, specs/*.acsl, tables, harnesses and their configurations, the gate's
own scripts), the flag string (the options the gate runs its tool with, and the environment
variables that change them), and the tools' version lines (the first line each tool prints
for its version, as tools/evidence/tool_versions.sh shows them).  The digest is the SHA-256 of

    qfoc-inputs 1
    gate <GATE>
    flags <flag string>
    tool <name>: <version line>          one per tool, in the gate's order
    file <sha256 of the content>  <path> one per file, sorted by its path in the repository

so it depends on file contents, repository-relative paths, flags and tool version strings
only: not on the machine, absolute paths, modification times or the time of the checkout.
A result produced on another machine and committed (WP, CBMC) is current here exactly when
the same files and the same tool versions are here.

usage:
  inputs.py --gates                        the gates, one per line
  inputs.py --list GATE                    the input files, one per line, then '# flags ...'
                                           and '# tool ...' lines
  inputs.py --digest GATE                  'Inputs: sha256 <hex> (N files; tools/evidence/inputs.py GATE)'
  inputs.py --stamp FILE GATE [--started EPOCH]
                                           stamp FILE: markdown or text gets the lines 'Run: ...',
                                           'Inputs: sha256 ...' and 'Tools: ...' under its title
                                           (at its top without one), JSON the keys "run_utc" and
                                           "inputs", XML the same lines as comments after its
                                           declaration; an earlier stamp is replaced.  Writes the
                                           manifest inputs-GATE.sha256 beside FILE (sha256sum
                                           format, the flags and tools as '#' lines): it names the
                                           files that changed when the stamp is stale
  inputs.py --check FILE [GATE]            'current' or 'stale: <reasons>' (or 'unstamped');
                                           exit 0 only when current
Options: --root DIR (default: this checkout).
"""
import argparse
import datetime
import glob
import hashlib
import json
import os
import re
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
SELF = "tools/evidence/inputs.py"
PYTHON = "/usr/bin/python3" if os.path.exists("/usr/bin/python3") else sys.executable

CURRENT, STALE, UNSTAMPED, MISSING = "current", "stale", "unstamped", "missing"

# ----------------------------------------------------------------------------- the gates

HEADERS = ["include/qfoc/*.h"]
SOURCES = ["src/*.c", "src/*.h"]
ACSL = ["specs/*.acsl"]
TABLES = ["tables/*.c", "tables/*.h"]
SIM = ["sim/*.c", "sim/*.h"]


def _wp_flags(env):
    return ("frama-c -cpp-extra-args=-Iinclude -Ispecs -wp -wp-rte -warn-signed-overflow "
            "-warn-signed-downcast -warn-unsigned-overflow -warn-unsigned-downcast "
            f"-wp-timeout {env.get('WP_TIMEOUT') or 120} -wp-par 1; provers z3,cvc4 in the order "
            "of proofs/wp/provers.txt; lemmas -wp-prop=@lemma in a unit of every public header; "
            "prover results recorded in proofs/wp/cache.txt (-wp-cache update, make prove-full: rebuild)")


CBMC_CHECKS = ("--bounds-check --pointer-check --div-by-zero-check --signed-overflow-check "
               "--unsigned-overflow-check --pointer-overflow-check --conversion-check "
               "--undefined-shift-check --float-overflow-check --nan-check "
               "--pointer-primitive-check --unwinding-assertions")


def _cbmc_flags(env):
    sat = env.get("CBMC_SAT")
    if sat is None:
        sat = "default (CaDiCaL through --external-sat-solver when installed, else MiniSat 2)"
    else:
        sat = "CBMC_SAT=" + " ".join(os.path.basename(w) for w in sat.split())
    return (f"cbmc -Iinclude -DQFOC_CBMC {CBMC_CHECKS} --unwind UNWIND CBMC_EXTRA "
            f"(proofs/cbmc/*/config.mk); SAT back end: {sat}")


# the analyses' default options, as tools/gates/eva.sh sets them
EVA_FILTER = ("eva_table_ok,eva_scaling_ok,eva_svpwm_ok,eva_pi_ok,eva_flux_ok,eva_pll_ok,eva_limits_ok,"
              "eva_cfg_speed_ok,eva_cfg_start_ok,eva_cfg_prot_ok,eva_cfg_feat_ok,eva_cfg_derate_ok,eva_cross_ok")


def _eva_flags(env):
    extra = env.get("EVA_EXTRA") or (
        "-eva-domains octagon,equality -eva-use-spec qfoc_isqrt32,qfoc_iref_q_limit,qfoc_iref_derate")
    extra_all = env.get("EVA_ALL_EXTRA") or (
        "-eva-domains octagon,equality -eva-use-spec qfoc_isqrt32,qfoc_mech_scale,qfoc_iref_q_limit,"
        "qfoc_iref_derate,qfoc_dtc_fade,qfoc_dtc_speed_fade "
        "-eva-split-return-function " + ",".join(f + ":0" for f in EVA_FILTER.split(",")) + " "
        "-eva-slevel-function " + ",".join(f + ":50" for f in EVA_FILTER.split(",")))
    precision = env.get("EVA_PRECISION") or 4
    warn = ("-warn-signed-overflow -warn-signed-downcast -warn-unsigned-overflow "
            "-warn-unsigned-downcast")
    return ("frama-c -cpp-extra-args=-Iinclude -Ispecs -Itables src/*.c tables/reference_params.c "
            f"proofs/eva/eva_main.c -eva -eva-precision {precision} {extra} {warn}; "
            "frama-c -cpp-extra-args=-Iinclude -Ispecs proofs/eva/eva_all_tables.c -wp "
            f"-wp-fct {EVA_FILTER} -wp-prover cvc4,z3 "
            f"-wp-timeout {env.get('WP_TIMEOUT') or 60} -wp-par 1; "
            "frama-c -cpp-extra-args=-Iinclude -Ispecs src/*.c proofs/eva/eva_all_tables.c -eva "
            f"-eva-precision {precision} {extra_all} {warn}; "
            f"EVA_MAX_ALARMS={env.get('EVA_MAX_ALARMS') or 0}")


def _misra_flags(env):
    return ("cppcheck --addon=misra (rule texts from misra/guidelines.txt) --std=c99 "
            "--platform=arm32-wchar_t4 --inline-suppr -Iinclude -Itables -Iport_s32k "
            "--suppress=missingIncludeSystem src/*.c tables/*.c port_s32k/*.c")


def _coverage_flags(env):
    return ("library: gcc $(WARN) -O0 -g --coverage -Iinclude (Makefile); tests: gcc -std=c99 -O0 -g "
            "--coverage -Iinclude -Isim -Itables; gcovr --filter src/ --filter include/ "
            "--fail-under-line 100 --fail-under-branch 100")


def _bench_flags(env):
    return ("arm-none-eabi-gcc $(ARM_CFLAGS) -fcallgraph-info=su (Makefile, mk/bench.mk); "
            "recordings fwtc and fw8000 of mk/bench.mk on specs/motors/reference.toml; "
            "instructions counted in Unicorn (tools/bench/count.py)")


def _cbmc_extra_files(root):
    """Library files the harnesses' config.mk SRCS name outside src/ (the tables)."""
    out = set()
    for cfg in glob.glob(os.path.join(root, "proofs", "cbmc", "*", "config.mk")):
        with open(cfg, encoding="utf-8", errors="replace") as f:
            for line in f:
                m = re.match(r"^\s*SRCS\s*[:?]?=\s*(.*)$", line)
                if m:
                    out.update(w for w in m.group(1).split() if not w.startswith("$"))
    return sorted(out)


def _cbmc_tool(env, root):
    return env.get("CBMC") or os.path.join(root, "build", "tools", "cbmc", "bin", "cbmc")


# gate -> files (glob patterns relative to the root), flags(env), tools [(name, argv(env, root))],
# extra files(root).  The result files themselves are never inputs.
GATES = {
    "wp": {
        "what": "Frama-C WP (make prove: tools/gates/prove.sh, wp_report.py)",
        "files": HEADERS + SOURCES + ACSL + [
            "proofs/wp/q15_unit.c", "proofs/wp/provers.txt", "proofs/wp/cache.txt",
            "tools/gates/prove.sh", "tools/gates/wp_jobs.py", "tools/gates/wp_report.py",
            "tools/gates/wp_cache.py", "tools/gates/c_functions.py",
            "tools/gates/jobs.sh"],
        "flags": _wp_flags,
        "tools": [("frama-c", lambda env, root: ["frama-c", "-version"]),
                  ("why3", lambda env, root: ["why3", "--version"]),
                  ("z3", lambda env, root: ["z3", "--version"]),
                  ("cvc4", lambda env, root: ["cvc4", "--version"])],
    },
    "cbmc": {
        "what": "CBMC (make cbmc: tools/gates/cbmc.sh)",
        "files": HEADERS + SOURCES + [
            "proofs/cbmc/*.h", "proofs/cbmc/*/*", "proofs/cbmc-selftest/*",
            "tools/gates/cbmc.sh", "tools/gates/jobs.sh"],
        "extra": _cbmc_extra_files,
        "flags": _cbmc_flags,
        "tools": [("cbmc", lambda env, root: [_cbmc_tool(env, root), "--version"]),
                  ("cadical", lambda env, root: [env.get("CADICAL") or "cadical", "--version"])],
    },
    "eva": {
        "what": "Frama-C EVA (make eva: tools/gates/eva.sh)",
        "files": HEADERS + SOURCES + ACSL + [
            "tables/reference_params.c", "tables/*.h", "proofs/eva/eva_main.c",
            "proofs/eva/eva_all_tables.c", "proofs/eva/*", "tools/gates/eva.sh"],
        "flags": _eva_flags,
        "tools": [("frama-c", lambda env, root: ["frama-c", "-version"])],
    },
    "misra": {
        "what": "MISRA (make misra, make misra-summary: tools/gates/misra.sh, misra_summary.py)",
        "files": HEADERS + SOURCES + TABLES + [
            "port_s32k/*.c", "port_s32k/*.h", "misra/*", "tools/gates/misra.sh",
            "tools/gates/misra_report.py", "tools/gates/misra_rule_texts.py",
            "tools/gates/misra_summary.py", "tools/evidence/review_stamp.py", "mk/misra_summary.mk"],
        "flags": _misra_flags,
        "tools": [("cppcheck", lambda env, root: ["cppcheck", "--version"])],
    },
    "coverage": {
        "what": "statement and branch coverage (make coverage: tools/gates/coverage.sh)",
        "files": HEADERS + SOURCES + TABLES + SIM + [
            "tests/*.c", "tests/*.h", "tools/gates/coverage.sh", "Makefile"],
        "flags": _coverage_flags,
        "tools": [("gcc", lambda env, root: ["gcc", "--version"]),
                  ("gcov", lambda env, root: ["gcov", "--version"]),
                  ("gcovr", lambda env, root: ["gcovr", "--version"])],
    },
    "bench": {
        "what": "the bench (make bench: mk/bench.mk, tools/bench/count.py)",
        "files": HEADERS + SOURCES + TABLES + SIM + [
            "tools/bench/*", "tools/bench/tests/*.py", "specs/motors/reference.toml",
            "mk/bench.mk", "Makefile"],
        "flags": _bench_flags,
        "tools": [("arm-none-eabi-gcc", lambda env, root: ["arm-none-eabi-gcc", "--version"]),
                  ("unicorn", lambda env, root: [PYTHON, "-c",
                                                 "import unicorn; print(unicorn.__version__)"]),
                  ("capstone", lambda env, root: [PYTHON, "-c",
                                                  "import capstone; print(capstone.__version__)"])],
    },
}


# ----------------------------------------------------------------------------- the digest

def sha256_file(path):
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for chunk in iter(lambda: f.read(1 << 16), b""):
            h.update(chunk)
    return h.hexdigest()


def glob_files(patterns, root=ROOT):
    """The set of repository-relative paths of the files the glob patterns (relative to the
    root) match."""
    found = set()
    for pat in patterns:
        for p in glob.glob(os.path.join(root, pat)):
            if os.path.isfile(p) and "__pycache__" not in p:
                found.add(os.path.relpath(p, root).replace(os.sep, "/"))
    return found


def hashes_of(paths, root=ROOT):
    """{path: sha256 of its content} of repository-relative paths."""
    return {p: sha256_file(os.path.join(root, p)) for p in paths}


def files(gate, root=ROOT):
    """The sorted repository-relative paths of GATE's input files that exist."""
    spec = GATES[gate]
    found = glob_files(spec["files"], root)
    if spec.get("extra"):
        found.update(p for p in spec["extra"](root) if os.path.isfile(os.path.join(root, p)))
    return sorted(found)


_TOOL_CACHE = {}


def tool_line(name, argv):
    """The first non-empty line a tool prints for its version (stdout and stderr), trimmed;
    'not installed' or 'unknown (...)'.  Cached for the process."""
    key = (name, tuple(argv))
    if key in _TOOL_CACHE:
        return _TOOL_CACHE[key]
    try:
        r = subprocess.run(argv, capture_output=True, text=True, timeout=60, check=False)
        text = (r.stdout or "") + "\n" + (r.stderr or "")
        lines = [ln.strip() for ln in text.replace("\r", "").splitlines() if ln.strip()]
        line = lines[0] if lines else "unknown (no output)"
        if line.startswith(name + ": "):
            line = line[len(name) + 2:]
    except FileNotFoundError:
        line = "not installed"
    except PermissionError:
        line = "not installed"
    except (OSError, subprocess.SubprocessError) as e:
        line = f"unknown ({type(e).__name__})"
    _TOOL_CACHE[key] = line
    return line


def tools(gate, root=ROOT, env=None):
    env = os.environ if env is None else env
    return [f"{name}: {tool_line(name, argv(env, root))}" for name, argv in GATES[gate]["tools"]]


def flags(gate, env=None):
    return GATES[gate]["flags"](os.environ if env is None else env)


def inputs(gate, root=ROOT, env=None):
    """(files, flags, tool lines, {path: sha256}) of GATE."""
    fl = files(gate, root)
    return fl, flags(gate, env), tools(gate, root, env), hashes_of(fl, root)


def digest_of(gate, flag_text, tool_lines, hashes):
    h = hashlib.sha256()
    h.update(f"qfoc-inputs 1\ngate {gate}\nflags {flag_text}\n".encode("utf-8"))
    for t in tool_lines:
        h.update(f"tool {t}\n".encode("utf-8"))
    for p in sorted(hashes):
        h.update(f"file {hashes[p]}  {p}\n".encode("utf-8"))
    return h.hexdigest()


def digest(gate, root=ROOT, env=None):
    """The SHA-256 of GATE's inputs as they are now."""
    _fl, flag_text, tool_lines, hashes = inputs(gate, root, env)
    return digest_of(gate, flag_text, tool_lines, hashes)


def stamp_line(gate, hexdigest, n):
    return f"Inputs: sha256 {hexdigest} ({n} files; {SELF} {gate})"


# ----------------------------------------------------------------------------- stamping

STAMP_RE = re.compile(r"Inputs: sha256 ([0-9a-f]{64}) \((\d+) files; tools/evidence/inputs\.py ([\w-]+)\)")
RUN_RE = re.compile(r"^(?:<!-- )?Run: (\d{4}-\d\d-\d\d \d\d:\d\d(?::\d\d)? UTC)(.*?)(?: -->)?$", re.M)
TOOLS_RE = re.compile(r"^(?:<!-- )?Tools: (.*?)(?: -->)?$", re.M)
STAMP_LINE = re.compile(r"^(?:<!-- )?(?:Run: \d{4}-|Inputs: sha256 [0-9a-f]{64} |Tools: ).*$")


def utc(epoch=None):
    t = datetime.datetime.now(datetime.timezone.utc) if epoch is None else \
        datetime.datetime.fromtimestamp(epoch, datetime.timezone.utc)
    return t.strftime("%Y-%m-%d %H:%M:%S UTC")


def manifest_path(path, gate):
    return os.path.join(os.path.dirname(path) or ".", f"inputs-{gate}.sha256")


def write_manifest(path, gate, hexdigest, flag_text, tool_lines, hashes):
    with open(path, "w", encoding="utf-8") as f:
        f.write(f"# {SELF} {gate}: the inputs of the results beside this file; "
                f"'sha256sum -c' checks the files\n")
        f.write(f"# {stamp_line(gate, hexdigest, len(hashes))}\n")
        f.write(f"# flags {flag_text}\n")
        for t in tool_lines:
            f.write(f"# tool {t}\n")
        for p in sorted(hashes):
            f.write(f"{hashes[p]}  {p}\n")


def read_manifest(path):
    """(digest, flags, tool lines, {path: sha256}) of a manifest, or None."""
    try:
        with open(path, encoding="utf-8") as f:
            text = f.read()
    except OSError:
        return None
    m = STAMP_RE.search(text)
    fl = re.search(r"^# flags (.*)$", text, re.M)
    tl = re.findall(r"^# tool (.*)$", text, re.M)
    hashes = dict((p, h) for h, p in re.findall(r"^([0-9a-f]{64})  (.+)$", text, re.M))
    return (m.group(1) if m else None, fl.group(1) if fl else None, tl, hashes)


def stamp_text(text, lines, xml=False):
    """TEXT with its earlier stamp lines removed and LINES put under its title (markdown),
    after its declaration (XML, as comments) or at its top."""
    body = [ln for ln in text.splitlines() if not STAMP_LINE.match(ln.strip())]
    # drop the blank lines an earlier stamp left doubled
    clean = []
    for ln in body:
        if not ln.strip() and clean and not clean[-1].strip():
            continue
        clean.append(ln)
    if xml:
        add = ["<!-- " + ln.replace("--", "- -") + " -->" for ln in lines]
        if clean and clean[0].startswith("<?xml") and "?>" in clean[0]:
            end = clean[0].index("?>") + 2
            head, tail = clean[0][:end], clean[0][end:]
            out = [head] + add + ([tail] if tail.strip() else []) + clean[1:]
        else:
            out = add + clean
    elif clean and clean[0].startswith("# "):
        rest = clean[1:]
        while rest and not rest[0].strip():
            rest = rest[1:]
        out = [clean[0], ""]
        for ln in lines:
            out += [ln, ""]
        out += rest
    else:
        out = lines + [""] + clean
    return "\n".join(out) + "\n"


def stamp(path, gate, root=ROOT, env=None, started=None, now=None):
    """Stamp the result file PATH with the run's UTC time and GATE's inputs digest; write the
    manifest beside it.  Returns the stamp line."""
    _fl, flag_text, tool_lines, hashes = inputs(gate, root, env)
    hexd = digest_of(gate, flag_text, tool_lines, hashes)
    line = stamp_line(gate, hexd, len(hashes))
    run = utc(now) + (f" (started {utc(started)})" if started else "")
    with open(path, encoding="utf-8") as f:
        text = f.read()
    if path.endswith(".json"):
        data = json.loads(text)
        data["run_utc"] = run
        data["inputs"] = {"sha256": hexd, "files": len(hashes), "gate": gate, "stamp": line,
                          "flags": flag_text, "tools": tool_lines}
        out = json.dumps(data, indent=1) + "\n"
    else:
        lines = [f"Run: {run}", line, "Tools: " + "; ".join(tool_lines)]
        out = stamp_text(text, lines, xml=path.endswith(".xml"))
    with open(path, "w", encoding="utf-8") as f:
        f.write(out)
    write_manifest(manifest_path(path, gate), gate, hexd, flag_text, tool_lines, hashes)
    return line


def read_stamp(path):
    """The stamp of a result file: dict(sha256, files, gate, run, tools) or None."""
    try:
        with open(path, encoding="utf-8", errors="replace") as f:
            text = f.read()
    except OSError:
        return None
    if path.endswith(".json"):
        try:
            data = json.loads(text)
        except ValueError:
            return None
        inp = data.get("inputs") if isinstance(data, dict) else None
        if not isinstance(inp, dict) or not re.fullmatch(r"[0-9a-f]{64}", str(inp.get("sha256", ""))):
            return None
        return {"sha256": inp["sha256"], "files": inp.get("files"), "gate": inp.get("gate"),
                "run": data.get("run_utc"), "tools": inp.get("tools") or []}
    m = STAMP_RE.search(text)
    if not m:
        return None
    r = RUN_RE.search(text)
    t = TOOLS_RE.search(text)
    return {"sha256": m.group(1), "files": int(m.group(2)), "gate": m.group(3),
            "run": (r.group(1) + r.group(2)).strip() if r else None,
            "tools": [x.strip() for x in t.group(1).split(";")] if t else []}


def run_date(path):
    """The UTC time of the run that wrote a result file: its stamp's, a JUnit file's
    timestamp, or None."""
    s = read_stamp(path)
    if s and s.get("run"):
        return s["run"]
    if path.endswith(".xml"):
        try:
            with open(path, encoding="utf-8", errors="replace") as f:
                head = f.read(4096)
        except OSError:
            return None
        m = re.search(r"<testsuite\b[^>]*\btimestamp=\"([^\"]+)\"", head)
        if m:
            return m.group(1).replace("T", " ").replace("Z", " UTC")
    return None


def check(path, gate=None, root=ROOT, env=None):
    """Whether the result file PATH is tied to the inputs as they are now:
    dict(state: current | stale | unstamped | missing, gate, run, recorded, now, reasons)."""
    if not os.path.exists(path):
        return {"state": MISSING, "gate": gate, "run": None, "recorded": None, "now": None,
                "reasons": [f"{path} not found"]}
    s = read_stamp(path)
    if s is None:
        return {"state": UNSTAMPED, "gate": gate, "run": None, "recorded": None, "now": None,
                "reasons": ["no inputs stamp: not tied to the sources it was computed from"]}
    g = gate or s["gate"]
    if g not in GATES:
        return {"state": STALE, "gate": g, "run": s["run"], "recorded": s["sha256"], "now": None,
                "reasons": [f"unknown gate {g!r}"]}
    if gate and s["gate"] != gate:
        return {"state": STALE, "gate": gate, "run": s["run"], "recorded": s["sha256"], "now": None,
                "reasons": [f"stamped for gate {s['gate']}, not {gate}"]}
    _fl, flag_text, tool_lines, hashes = inputs(g, root, env)
    now = digest_of(g, flag_text, tool_lines, hashes)
    res = {"state": CURRENT if now == s["sha256"] else STALE, "gate": g, "run": s["run"],
           "recorded": s["sha256"], "now": now, "reasons": []}
    if res["state"] == STALE:
        res["reasons"] = differences(manifest_path(path, g), s, flag_text, tool_lines, hashes)
    return res


def differences(mpath, s, flag_text, tool_lines, hashes):
    """Why the recorded inputs differ from those now, from the manifest beside the result."""
    man = read_manifest(mpath)
    reasons = []
    if man is None or man[0] != s["sha256"]:
        rec_tools = s.get("tools") or []
        if rec_tools and rec_tools != tool_lines:
            reasons.append("tool versions differ: " + "; ".join(
                f"{a} (run) / {b} (now)" for a, b in zip(rec_tools, tool_lines) if a != b))
        reasons.append("the inputs differ from those of the run (no manifest "
                       f"{os.path.basename(mpath)} of that run to tell which files)")
        return reasons
    _d, rec_flags, rec_tools, rec_hashes = man
    changed = sorted(p for p in hashes if p in rec_hashes and rec_hashes[p] != hashes[p])
    added = sorted(p for p in hashes if p not in rec_hashes)
    removed = sorted(p for p in rec_hashes if p not in hashes)
    for what, lst in (("changed", changed), ("new", added), ("removed", removed)):
        if lst:
            reasons.append(f"{len(lst)} input file(s) {what} since the run: " + ", ".join(lst[:8])
                           + (", ..." if len(lst) > 8 else ""))
    if rec_flags != flag_text:
        reasons.append(f"flags differ: '{rec_flags}' (run) / '{flag_text}' (now)")
    if rec_tools != tool_lines:
        diff = [f"{a} (run) / {b} (now)" for a, b in zip(rec_tools, tool_lines) if a != b]
        reasons.append("tool versions differ: " + ("; ".join(diff) or "the list of tools"))
    return reasons or ["the inputs differ from those of the run"]


# ----------------------------------------------------------------------------- command line

def main(argv=None):
    ap = argparse.ArgumentParser(description="The inputs of every gate's result and their stamp.")
    ap.add_argument("--root", default=ROOT)
    g = ap.add_mutually_exclusive_group(required=True)
    g.add_argument("--gates", action="store_true")
    g.add_argument("--list", metavar="GATE")
    g.add_argument("--digest", metavar="GATE")
    g.add_argument("--stamp", nargs=2, metavar=("FILE", "GATE"))
    g.add_argument("--check", nargs="+", metavar=("FILE", "GATE"))
    ap.add_argument("--started", type=float, default=None, help="the run's start (seconds since the epoch)")
    a = ap.parse_args(argv)
    root = os.path.abspath(a.root)
    gate = a.list or a.digest or (a.stamp[1] if a.stamp else None) or \
        (a.check[1] if a.check and len(a.check) > 1 else None)
    if gate is not None and gate not in GATES:
        print(f"inputs: unknown gate {gate!r} (gates: {', '.join(GATES)})", file=sys.stderr)
        return 2
    if a.gates:
        for k, v in GATES.items():
            print(f"{k}\t{v['what']}")
        return 0
    if a.list:
        fl, flag_text, tool_lines, _h = inputs(a.list, root)
        for p in fl:
            print(p)
        print(f"# flags {flag_text}")
        for t in tool_lines:
            print(f"# tool {t}")
        return 0
    if a.digest:
        fl, flag_text, tool_lines, hashes = inputs(a.digest, root)
        print(stamp_line(a.digest, digest_of(a.digest, flag_text, tool_lines, hashes), len(fl)))
        return 0
    if a.stamp:
        path = a.stamp[0]
        if not os.path.exists(path):
            print(f"inputs: {path} not found", file=sys.stderr)
            return 1
        print(f"{path}: {stamp(path, a.stamp[1], root, started=a.started)}")
        return 0
    res = check(a.check[0], gate, root)
    if res["state"] == CURRENT:
        print(f"{a.check[0]}: current (run {res['run']}; inputs sha256 {res['now']})")
        return 0
    print(f"{a.check[0]}: {res['state']}: " + "; ".join(res["reasons"]))
    return 1


if __name__ == "__main__":
    sys.exit(main())
