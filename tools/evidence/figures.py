#!/usr/bin/env python3
"""The figures quoted in the documents come from the results (REQ-EVD-019).

usage: figures.py [--root DIR] [--write]

Every count quoted in specs/safety-manual.md, specs/tool-confidence.md,
specs/tool-confidence.json, specs/asr.toml, README.md, port_s32k/README.md and the current
section of CHANGELOG.md (its [Unreleased] section, or the newest release's; WP goals, CBMC harnesses and
properties, requirements, tests, target-equivalence groups and vectors, MISRA deviations,
limitations, ...) is registered below (FIGURES: file and template) and compared with the
figure computed from its source:

  committed   proofs/wp/results.md, proofs/cbmc/results.md, misra/deviations.md,
              specs/requirements/*.md, specs/asr.toml, specs/scenarios.toml, the sources of
              the tests (tests/*.c, tools/*/tests/*.py, tools/target_test/tt_groups.c), src/,
              the Makefile and tools/gates/check.sh, the safety manual's own limitation table
  built       build/trace/trace.json (make trace writes it before this check runs),
              build/target_test/target.txt, build/junit/*.xml, build/coverage/summary.txt,
              build/bench/bench.json, build/robustness/campaign.json,
              build/s32k144/firmware.json (make firmware): checked only when
              present (the output says which were not); the occurrences of such a figure
              must still agree with each other in every document

It fails (exit status 1, each offender named with its file, line, the figure written and
the figure computed) when a registered figure differs, when a template no longer matches
its document, or when a document quotes a count that no template covers (a hand-typed
figure nobody checks).  --write replaces every registered figure whose source is present
with the computed one.  Run by `make trace`; figures filled in by gen_manual.py (the ASR
table) come from values().
"""
import argparse
import glob
import json
import os
import re
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)

import req_attrs  # noqa: E402

MANUAL = "specs/safety-manual.md"
TCM = "specs/tool-confidence.md"
TCJ = "specs/tool-confidence.json"
ASR = "specs/asr.toml"
README = "README.md"
PORT = "port_s32k/README.md"
CHANGELOG = "CHANGELOG.md"

# (file, template): {name} is a figure of values(); spaces match any white space (line
# breaks of the markdown).  Every match of the template in the file is checked.
FIGURES = [
    (MANUAL, "{wp.proved} / {wp.goals} goals proved"),
    (MANUAL, "{cbmc.harnesses} harnesses, {cbmc.properties} properties, {cbmc.failed} failed"),
    (MANUAL, "{req.count} requirements, each named in a public header"),
    (MANUAL, "{misra.sites} tagged sites under {misra.devs}"),
    (MANUAL, "deviations {misra.devs}"),
    (MANUAL, "{tests.cmocka_files} executables, {tests.cmocka} tests, {junit.failed} failed"),
    (MANUAL, "{trace.with_tests} of {req.count} requirements named by tests"),
    (MANUAL, "{tests.pytest} pytest test functions"),
    (MANUAL, "{tt.vectors} vectors identical"),
    (MANUAL, "{bench.periods} periods identical"),
    (MANUAL, "lines {cov.lines_covered} / {cov.lines}, branches {cov.branches_covered} / {cov.branches}"),
    (README, "100 % lines ({cov.lines_covered}/{cov.lines}), 100 % branches ({cov.branches_covered}/"
             "{cov.branches})"),
    (MANUAL, "{scenarios.count} scenarios against"),
    (MANUAL, "{robust.count} random cold starts"),
    (MANUAL, "{robust.successes} of {robust.count} starts"),
    (MANUAL, "{robust.successes} of {robust.count} cold starts"),
    (MANUAL, "limitations L1 .. {limits.last}"),
    (MANUAL, "ASR-01 to {asr.lib_last} apply"),
    (MANUAL, "ASR-P1 to {asr.port_last} apply"),
    (MANUAL, "requirements ASR-01 .. {asr.lib_last}"),
    (MANUAL, "Compare ASR-01 .. {asr.lib_last} (and ASR-P1 .. {asr.port_last}"),
    (MANUAL, "{tt.groups} groups, {tt.vectors} vectors"),
    (MANUAL, "{wp.proved} of {wp.goals} goals proved"),
    (MANUAL, "each of the {src.loops} `for` and `while` loops"),
    (MANUAL, "{bench.periods} PWM periods identical"),
    (MANUAL, "a bound no input can exceed, {bench.fast_static} instructions (limit {bench.limit_fast_static}; "
             "goal {bench.goal_fast} of REQ-BENCH-008), ~{bench.fast_static_cyc} cycles"),
    (MANUAL, "the tick's {bench.tick_static} (~{bench.tick_static_cyc} cycles) take {bench.load_eight_khz} % of the CPU at "
             "8 kHz and {bench.load_sixteen_khz} % at 16 kHz"),
    (MANUAL, "| fast step, static bound (every input, every state) | up to {bench.fast_static} | "
             "~{bench.fast_static_cyc} |"),
    (MANUAL, "| tick, static bound (every input, every state, every kind of tick) | up to {bench.tick_static} | "
             "~{bench.tick_static_cyc} |"),
    (MANUAL, "(static bounds {bench.static_clarke} / {bench.static_park} / {bench.static_inv_clarke} / "
             "{bench.static_svpwm_chain} against {bench.goal_clarke} / {bench.goal_park} / {bench.goal_inv_clarke} / "
             "{bench.goal_svpwm_chain}; limits {bench.limit_clarke} / {bench.limit_park} / {bench.limit_inv_clarke} / "
             "{bench.limit_svpwm_chain}"),
    (MANUAL, "fast step {bench.fast_static} instructions (goal {bench.goal_fast}), tick {bench.tick_static} (goal "
             "{bench.goal_tick}), {bench.load_sixteen_khz} % of an 80 MHz CPU at 16 kHz (goal {bench.goal_load_pct} %)"),
    (MANUAL, "At 8 kHz the two bounds take {bench.load_eight_khz} % of the CPU"),
    (MANUAL, "(the fast step executes up to {bench.fast_measured} instructions on its longest measured path)"),
    (MANUAL, "against the goal of {bench.goal_flash_kib} KiB (limit {bench.limit_flash_kib} KiB)"),
    (MANUAL, "(goal {bench.goal_flash_drive_kib} KiB)"),
    (MANUAL, "REQ-BENCH-008 (fast step {bench.goal_fast} instructions on its static bound)"),
    (MANUAL, "all of `src/` takes {bench.flash_lib} B"),
    (MANUAL, "a drive links {bench.flash_drive} B of it"),
    (MANUAL, "Code: {bench.flash_lib} B for all of `src/`, of which a drive firmware links {bench.flash_drive} B"),
    (MANUAL, "`qfoc_drive_t` of {bench.ram_motor} B in RAM and one parameter table of {bench.table_bytes} B"),
    (MANUAL, "`sizeof` {bench.table_bytes} bytes on the Cortex-M4F"),
    (MANUAL, "fast step: {bench.stack_fast} B;"),
    (MANUAL, "tick: {bench.stack_tick} B;"),
    (MANUAL, "init: {bench.stack_init} B."),
    (MANUAL, "(longest path) | up to {bench.fast_max} |"),
    (MANUAL, "the 100 ms job's CAN frame) | up to {bench.tick_max} |"),
    (MANUAL, "tick interrupt: 104 B + {bench.stack_tick} B"),
    (MANUAL, "ADC interrupt: 32 B + {bench.stack_fast} B"),
    (README, "fast step {bench.fast_static} instructions (limit {bench.limit_fast_static}; the goal of "
             "{bench.goal_fast} is not met), tick {bench.tick_static} ({bench.limit_tick_static}; goal "
             "{bench.goal_tick} not met), CPU load at 16 kHz and 80 MHz {bench.load_sixteen_khz} %"),
    (README, "measured fast step {bench.fast_measured} instructions (limit {bench.limit_fast}), tick "
             "{bench.tick_max} ({bench.limit_tick})"),
    (README, "{bench.limits_met} of {bench.limits} limits met"),
    (README, "| fast step | {bench.fast_static} instructions, ~{bench.fast_static_cyc} cycles at most | "
             "{bench.fast_max} in closed loop with field weakening and torque compensation, {bench.fast_measured} "
             "at a RUN entry | {bench.goal_fast} |"),
    (README, "command answered) | {bench.tick_static} instructions, ~{bench.tick_static_cyc} cycles at most | "
             "{bench.tick_max} | {bench.goal_tick} |"),
    (README, "| CPU load at 80 MHz, fast step and tick at their cycle bounds | {bench.load_eight_khz} % at 8 kHz, "
             "{bench.load_sixteen_khz} % at 16 kHz | - | {bench.goal_load_pct} % at 16 kHz |"),
    (README, "| {bench.ram_motor} B | - | {bench.limit_ram_motor} B (limit) |"),
    (README, "| {bench.stack_fast} B / {bench.stack_tick} B | - | {bench.limit_stack_fast} B (limit) |"),
    (README, "flash {bench.flash_lib} B ({bench.limit_flash_kib} KiB; goal {bench.goal_flash_kib} KiB) and "
             "{bench.flash_drive} B linked by a drive ({bench.limit_flash_drive} B; goal "
             "{bench.goal_flash_drive_kib} KiB), RAM per motor {bench.ram_motor} B ({bench.limit_ram_motor}), "
             "fast-step stack {bench.stack_fast} B ({bench.limit_stack_fast})"),
    (README, "| {bench.flash_lib} B; {bench.flash_drive} B | - | {bench.goal_flash_kib} KiB; "
             "{bench.goal_flash_drive_kib} KiB |"),
    (ASR, "{tt.groups} groups, {tt.vectors} vectors"),
    (ASR, "{bench.periods} PWM periods identical"),
    (TCM, "{tt.vectors} vectors in {tt.groups} groups"),
    (TCM, "{bench.periods} PWM periods"),
    (TCM, "bench replays {bench.periods} closed-loop periods"),
    (TCM, "host build on {tt.vectors} vectors"),
    (TCM, "reports {wp.proved} of {wp.goals} goals proved"),
    (TCM, "({cbmc.harnesses} harnesses)"),
    (TCM, "{cbmc.harnesses} harnesses under"),
    (TCM, "reports {cbmc.properties} properties and {cbmc.failed} failed"),
    (TCM, "{misra.sites} tagged sites under {misra.devs}"),
    (TCJ, "{misra.sites} tagged sites under {misra.devs_short}"),
    (TCM, "{tests.cmocka_files} executables and {tests.cmocka} tests, {junit.failed} failed"),
    (TCM, "{tests.pytest_tune} pytest test functions of `tools/tune/tests/`"),
    (TCM, "reports {req.count} requirements: {trace.with_tests} with tests and {trace.with_cbmc} with CBMC harnesses"),
    (TCJ, "{tt.vectors} vectors of {tt.groups} groups"),
    (TCJ, "{bench.periods} PWM periods"),
    (TCJ, "host build on {tt.vectors} vectors"),
    (TCJ, "replays {bench.periods} closed-loop"),
    (TCJ, "proofs/wp/results.md: {wp.proved} / {wp.goals} goals"),
    (TCJ, "({cbmc.harnesses} harnesses)"),
    (TCJ, "UBSan build replays {tt.vectors} vectors"),
    (TCJ, "\"{cbmc.harnesses} harnesses under"),
    (TCJ, "proofs/cbmc/results.md: {cbmc.properties} properties, {cbmc.failed} failed"),
    (TCJ, "{tests.cmocka_files} executables, {tests.cmocka} tests in build/junit/"),
    (TCJ, "pytest ({tests.pytest_tune} test functions)"),
    (TCJ, "build/trace/trace.md: {req.count} requirements, {trace.with_tests} with tests, "
          "{trace.with_cbmc} with CBMC harnesses"),
    (README, "**{robust.successes} of {robust.count} starts succeed**"),
    (README, "all {wp.drive_goals} goals of `src/qfoc_drive.c`, `src/qfoc_drive_mon.c` and `src/qfoc_drive_start.c`"),
    (README, "`tests/test_port.c` ({tests.port} tests)"),
    (README, "({tt.groups} groups, {tt.vectors} vectors:"),
    (README, "{tests.cmocka} passed, {junit.failed} failed ({tests.cmocka_files} CMocka executables"),
    (README, "evidence generator: {tests.pytest} pytest test functions"),
    (README, "proved {wp.proved} / {wp.goals} goals ({wp.units} units, lemmas included; the drive alone "
             "{wp.drive_goals})"),
    (README, "{cbmc.harnesses} harnesses, {cbmc.properties} properties, all hold"),
    (README, "In `make check` {wp.qed} goals are closed by Qed"),
    (README, "clang-tidy bugprone and cert: {static.findings} findings, all accepted"),
    (README, "`make pil-check`: {tests.pil} tests of the emulator"),
    (README, "{misra.guidelines} guidelines, {misra.compliant} compliant, {misra.deviated} with deviations "
             "({misra.devs_short}, {misra.sites} tagged sites), {misra.disapplied} disapplied"),
    (README, "{req.count} requirements, each named by its interface"),
    (README, "({trace.with_tests} with tests, {trace.with_cbmc} with CBMC harnesses); {trace.tests_naming} of "
             "{trace.tests} tests and {trace.harnesses_naming} of {cbmc.harnesses} harnesses name"),
    (README, "{tt.groups} groups, {tt.vectors} golden vectors"),
    (README, "the {scenarios.count} scenarios of `make demo`"),
    (README, "`robustness` ({robust.check} starts)"),
    (README, "`build/s32k144/qfoc_compressor.elf` (+ `.map`, `.bin`): {fw.flash} B of flash, {fw.ram} B of RAM"),
    (MANUAL, "The reference image uses {fw.flash} B of flash and {fw.ram} B of RAM"),
    (MANUAL, "*derived*: {fw.isr_adc} for the whole interrupt in PRECHARGE"),
    (PORT, "| {fw.flash} B of 512 KiB"),
    (PORT, "| {fw.ram} B of 32 KiB |"),
    (CHANGELOG, "proved ({wp.iref_goals} goals)"),
    (CHANGELOG, "{robust.total} starts with per-axis success"),
    (CHANGELOG, "library flash limit is {bench.limit_flash_kib} KiB (was 21 KiB)"),
    (CHANGELOG, "the tick's limit 1665 -> {bench.limit_tick} instructions and the drive's linked flash "
                "16452 -> {bench.limit_flash_drive} B"),
    (CHANGELOG, "fast step {bench.fast_max} instructions (limit {bench.limit_fast}), tick "
                "{bench.tick_max} (limit {bench.limit_tick}), RAM per motor {bench.ram_motor} B "
                "(limit {bench.limit_ram_motor})"),
    (PORT, "loop in {fw.boot} instructions; in PRECHARGE the ADC-complete interrupt executes {fw.isr_adc} "
           "instructions, the FTM3 period interrupt {fw.isr_ftm} and the 1 ms tick {fw.isr_tick}"),
]

# Counts the scan below finds that are not figures of a result (file, text, reason).
NOT_FIGURES = [
    (README, "| 1 requirements |", "the number of a section of the evidence page"),
    (README, "| 5 tests |", "the number of a section of the evidence page"),
    (PORT, "at\n0 starts both PDBs", "the counter value at which the trigger fires"),
]

# A count in a document: a number (or 'N of M', 'N / M') before a counted noun, possibly
# with one word between; ranges of IDs.
NOUNS = (r"goals|requirements|tests|harnesses|properties|vectors|groups|executables|pytest|CMocka|"
         r"deviations|limitations|scenarios|starts|loops|periods|sites|guidelines|limits")
COUNT = re.compile(r"(?<![\w.-])\d+(?:,\d{3})*(?:\s+(?:of|/)\s+\d+(?:,\d{3})*)?\s+(?:[A-Za-z-]+\s+)?(?:" + NOUNS + r")\b")
RANGES = re.compile(r"\bDEV-\d{3}\s*(?:\.\.|to)\s*DEV-\d{3}\b|\bDEV-\d{3}\.\.\d{3}\b|\bL1\s*(?:\.\.|to)\s*L\d+\b|"
                    r"\bASR-(?:01|P1)\s*(?:\.\.|to)\s*ASR-(?:\d{2}|P\d+)\b")

# The form of a figure in the text (default: a number).
FORMS = {"bench.load_eight_khz": r"\d+\.\d", "bench.load_sixteen_khz": r"\d+\.\d",
         "misra.devs": r"DEV-\d{3}\s+\.\.\s+DEV-\d{3}", "misra.devs_short": r"DEV-\d{3}\.\.\d{3}",
         "limits.last": r"L\d+",
         "asr.lib_last": r"ASR-\d{2}", "asr.port_last": r"ASR-P\d+"}


def _read(root, rel):
    try:
        with open(os.path.join(root, rel), encoding="utf-8") as f:
            return f.read()
    except OSError:
        return None


def _md_rows(text, ncols):
    rows = []
    for line in (text or "").splitlines():
        if not line.startswith("|") or line.startswith("|---"):
            continue
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) == ncols and cells[0] not in ("unit", "harness"):
            rows.append(cells)
    return rows


def _trace_module():
    """tools/evidence/trace.py (loaded by path: the standard library has a module 'trace')."""
    import importlib.util
    spec = importlib.util.spec_from_file_location("qfoc_trace", os.path.join(HERE, "trace.py"))
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def bench_budgets(root="."):
    """The limits and goals of tools/bench/count.py: bench.limit_<x>, bench.goal_<x> (KiB
    for the flash figures)."""
    import ast
    out = {}
    text = _read(root, "tools/bench/count.py")
    if text is None:
        return out
    consts = {}
    for node in ast.parse(text).body:
        if isinstance(node, ast.Assign) and len(node.targets) == 1 and isinstance(node.targets[0], ast.Name):
            try:
                consts[node.targets[0].id] = ast.literal_eval(node.value)
            except ValueError:
                try:
                    consts[node.targets[0].id] = eval(compile(ast.Expression(node.value), "count.py", "eval"),
                                                      {"__builtins__": {}}, {})
                except Exception:  # noqa: BLE001 - an expression of other names: not a figure
                    pass
    for key, name in (("GOAL_FAST_STEP", "goal_fast"), ("LIMIT_FAST_STEP", "limit_fast"),
                      ("STATIC_LIMIT_FAST_STEP", "limit_fast_static"),
                      ("STATIC_LIMIT_TICK", "limit_tick_static"), ("GOAL_LOAD_PCT", "goal_load_pct"),
                      ("LIMIT_SVPWM_CHAIN", "limit_svpwm_chain"), ("GOAL_SVPWM_CHAIN", "goal_svpwm_chain"),
                      ("GOAL_TICK", "goal_tick"), ("LIMIT_TICK", "limit_tick"),
                      ("LIMIT_RAM_MOTOR", "limit_ram_motor"), ("LIMIT_STACK_FAST", "limit_stack_fast"),
                      ("LIMIT_FLASH_DRIVE", "limit_flash_drive")):
        if isinstance(consts.get(key), int):
            out[f"bench.{name}"] = consts[key]
    for key, name in (("GOAL_FLASH", "goal_flash_kib"), ("LIMIT_FLASH", "limit_flash_kib"),
                      ("GOAL_FLASH_DRIVE", "goal_flash_drive_kib")):
        if isinstance(consts.get(key), int) and consts[key] % 1024 == 0:
            out[f"bench.{name}"] = consts[key] // 1024
    for fn, (limit, goal) in (consts.get("FUNC_BUDGET") or {}).items():
        out[f"bench.limit_{fn}"] = limit
        if goal is not None:
            out[f"bench.goal_{fn}"] = goal
    return out


def values(root="."):
    """Figure name -> (value or None, source)."""
    v = {}

    def put(name, value, source):
        v[name] = (value, source)

    wp = _md_rows(_read(root, "proofs/wp/results.md"), 6)
    src = "proofs/wp/results.md"
    put("wp.goals", sum(int(r[2]) for r in wp) if wp else None, src)
    put("wp.proved", sum(int(r[3]) for r in wp) if wp else None, src)
    put("wp.units", len({r[0] for r in wp}) if wp else None, src)
    qed = re.search(r"^Proved in this run[^:]*: (\d+) by Qed", _read(root, src) or "", re.M)
    put("wp.qed", int(qed.group(1)) if qed else None, src)
    put("wp.iref_goals", sum(int(r[2]) for r in wp if r[0] == "qfoc_iref") if wp else None, src)
    put("wp.drive_goals", sum(int(r[2]) for r in wp if r[0] in ("qfoc_drive", "qfoc_drive_mon", "qfoc_drive_start"))
        if wp else None, src)
    cb = _md_rows(_read(root, "proofs/cbmc/results.md"), 6)
    src = "proofs/cbmc/results.md"
    put("cbmc.harnesses", len(cb) if cb else None, src)
    put("cbmc.properties", sum(int(r[2]) + int(r[3]) for r in cb) if cb else None, src)
    put("cbmc.failed", sum(int(r[3]) for r in cb) if cb else None, src)
    devs = sorted(set(re.findall(r"^## (DEV-\d{3})\b", _read(root, "misra/deviations.md") or "", re.M)))
    put("misra.devs", f"{devs[0]} .. {devs[-1]}" if devs else None, "misra/deviations.md (## DEV-nnn)")
    attrs = req_attrs.load_attributes(root)
    attrs.pop("?", None)
    put("req.count", len(attrs) or None, "specs/requirements/*.md (### REQ-...)")
    asrs, _errors = req_attrs.load_asrs(root)
    lib = [a for a in asrs if re.match(r"ASR-\d{2}$", a)]
    port = [a for a in asrs if a.startswith("ASR-P")]
    put("asr.lib_last", max(lib, key=req_attrs.asr_key) if lib else None, req_attrs.ASR_FILE)
    put("asr.port_last", max(port, key=req_attrs.asr_key) if port else None, req_attrs.ASR_FILE)
    lims = re.findall(r"^\| L(\d+) \|", _read(root, MANUAL) or "", re.M)
    put("limits.last", f"L{max(int(n) for n in lims)}" if lims else None, f"{MANUAL} (section 5 table)")
    scn = re.findall(r"^\[[A-Za-z_0-9]+\]", _read(root, "specs/scenarios.toml") or "", re.M)
    put("scenarios.count", len(scn) or None, "specs/scenarios.toml (sections)")
    mk = re.search(r"^ROBUST_COUNT \?= (\d+)", _read(root, "Makefile") or "", re.M)
    put("robust.count", int(mk.group(1)) if mk else None, "Makefile (ROBUST_COUNT)")
    ax = re.search(r"^ROBUST_AXIS_COUNT \?= .*,(\d+)\)\s*$", _read(root, "Makefile") or "", re.M)
    rob = _read(root, "sim/apps/robust.c") or ""
    axes = re.findall(r'^\s+\{ "([a-z_0-9]+)",', rob[rob.find("axes[] = {"):rob.find("#define N_AXES")], re.M)
    put("robust.total", int(mk.group(1)) + (len(axes) - 1) * int(ax.group(1)) if mk and ax and axes else None,
        "Makefile (ROBUST_COUNT, ROBUST_AXIS_COUNT) and sim/apps/robust.c (axes[])")
    ck = re.search(r"robustness ROBUST_COUNT=(\d+)", _read(root, "tools/gates/check.sh") or "")
    put("robust.check", int(ck.group(1)) if ck else None, "tools/gates/check.sh")
    # tests, counted as the trace counts them
    cwd = os.getcwd()
    try:
        os.chdir(root)
        tr = _trace_module()
        defined = set(attrs)
        cm, _missing = tr.cmocka_tests(defined)
        py = tr.pytest_tests(defined)
        groups = [n for _f, n, _i in tr.target_tests(defined) if n.startswith("group ")]
    finally:
        os.chdir(cwd)
    put("tests.cmocka", len(cm), "tests/*.c (cmocka_unit_test registrations)")
    put("tests.port", sum(1 for f, _n, _i in cm if os.path.basename(f) == "test_port.c"),
        "tests/test_port.c")
    put("tests.cmocka_files", len({f for f, _n, _i in cm}), "tests/*.c with registered tests")
    put("tests.pytest", sum(1 for f, _n, _i in py if f.startswith("tools/")),
        "tools/*/tests/*.py (test_ functions)")
    put("tests.pytest_tune", sum(1 for f, _n, _i in py if f.startswith("tools/tune/")),
        "tools/tune/tests/*.py (test_ functions)")
    put("tests.pil", sum(1 for f, _n, _i in py if f.startswith("port_s32k/pil/")),
        "port_s32k/pil/tests/*.py (test_ functions)")
    put("tt.groups", len(groups) or None, "tools/target_test/tt_groups.c")
    loops = variants = 0
    for p in sorted(glob.glob(os.path.join(root, "src/*.c"))):
        text = _read(root, os.path.relpath(p, root))
        loops += len(re.findall(r"^\s*(?:for|while)\s*\(|^\s*do\s*\{?\s*$", text, re.M))
        variants += len(re.findall(r"\bloop\s+variant\b", text))
    put("src.loops", loops if loops == variants else None,
        "src/*.c (loops; each must carry a loop variant" + ("" if loops == variants else
                                                             f": {loops} loops, {variants} variants") + ")")
    # the bench's limits and goals (tools/bench/count.py)
    for name, value in bench_budgets(root).items():
        put(name, value, "tools/bench/count.py")
    # built results
    tj = _read(root, "build/trace/trace.json")
    t = json.loads(tj).get("totals", {}) if tj else {}
    src = "build/trace/trace.json"
    for name, key in (("trace.with_tests", "with_tests"), ("trace.with_cbmc", "with_cbmc"),
                      ("trace.tests_naming", "unit_tests_naming_a_requirement"),
                      ("trace.tests", "unit_tests"), ("trace.harnesses_naming", "harnesses_naming_a_requirement")):
        put(name, t.get(key), src)
    tt = re.search(r"^result: (\d+) groups, (\d+) vectors", _read(root, "build/target_test/target.txt") or "", re.M)
    put("tt.vectors", int(tt.group(2)) if tt else None, "build/target_test/target.txt")
    junit = sorted(glob.glob(os.path.join(root, "build/junit/test_*.xml")))
    fails = None
    if junit:
        import xml.etree.ElementTree as ET
        fails = 0
        for p in junit:
            try:
                for tc in ET.parse(p).iter("testcase"):
                    fails += tc.find("failure") is not None or tc.find("error") is not None
            except (ET.ParseError, OSError):
                fails = None
                break
    put("junit.executables", len(junit) or None, "build/junit/test_*.xml")
    put("junit.failed", fails, "build/junit/test_*.xml")
    st = re.search(r"\*\*static: (\d+) findings", _read(root, "build/static/static.md") or "")
    put("static.findings", int(st.group(1)) if st else None, "build/static/static.md")
    bench = _read(root, "build/bench/bench.json")
    periods = None
    if bench:
        for row in (json.loads(bench).get("table") or []):
            m = re.search(r"\((\d+) compared\)", str(row.get("item", "")))
            if m:
                periods = int(m.group(1))
    put("bench.periods", periods, "build/bench/bench.json")
    rows = (json.loads(bench).get("table") or []) if bench else []

    def bmax(pred):
        hits = [r.get("max") for r in rows if pred(str(r.get("item", ""))) and r.get("max") is not None]
        return max(hits) if hits else None
    for name, pred in (
            ("bench.fast_max", lambda i: i.startswith("`qfoc_drive_fast_step`, CLOSED_LOOP")),
            ("bench.fast_measured", lambda i: i.startswith("`qfoc_drive_fast_step`") and "static" not in i),
            ("bench.tick_max", lambda i: i.startswith("`qfoc_drive_tick`") and "static" not in i),
            ("bench.flash_lib", lambda i: i.startswith("library flash, all of")),
            ("bench.flash_drive", lambda i: i.startswith("library flash a drive links")),
            ("bench.ram_motor", lambda i: i.startswith("RAM per motor")),
            ("bench.table_bytes", lambda i: i.startswith("parameter table, `sizeof")),
            ("bench.stack_fast", lambda i: i.startswith("stack, `qfoc_drive_fast_step`")),
            ("bench.stack_tick", lambda i: i.startswith("stack, `qfoc_drive_tick`")),
            ("bench.stack_init", lambda i: i.startswith("stack, `qfoc_drive_init`"))):
        put(name, bmax(pred), "build/bench/bench.json")
    sb = (json.loads(bench).get("static") or {}) if bench else {}
    bfn = (json.loads(bench).get("functions") or {}) if bench else {}
    for key in ("clarke", "park", "inv_clarke"):
        put(f"bench.static_{key}", (bfn.get(key) or {}).get("static"), "build/bench/bench.json (functions)")
    put("bench.static_svpwm_chain",
        sum(sb[n]["instructions"] for n in ("qfoc_circle_limit", "qfoc_svpwm_step_lin"))
        if all(n in sb for n in ("qfoc_circle_limit", "qfoc_svpwm_step_lin")) else None,
        "build/bench/bench.json (static)")
    for name, fn, key in (("bench.fast_static", "qfoc_drive_fast_step", "instructions"),
                          ("bench.tick_static", "qfoc_drive_tick", "instructions"),
                          ("bench.fast_static_cyc", "qfoc_drive_fast_step", "cycles"),
                          ("bench.tick_static_cyc", "qfoc_drive_tick", "cycles")):
        put(name, (sb.get(fn) or {}).get(key), "build/bench/bench.json (static)")
    for f_khz in (8, 16):
        fs, tk = (sb.get("qfoc_drive_fast_step") or {}), (sb.get("qfoc_drive_tick") or {})
        load = (round(100.0 * (fs["cycles"] * f_khz * 1000.0 + tk["cycles"] * 1000.0) / 80e6, 1)
                if "cycles" in fs and "cycles" in tk else None)
        put("bench.load_eight_khz" if f_khz == 8 else "bench.load_sixteen_khz", load, "build/bench/bench.json (static)")
    limited = [r for r in rows if r.get("limit") is not None]
    put("bench.limits", len(limited) if rows else None, "build/bench/bench.json")
    put("bench.limits_met", sum(1 for r in limited if r.get("result") == "OK") if rows else None,
        "build/bench/bench.json")
    fw = _read(root, "build/s32k144/firmware.json")
    fwj = json.loads(fw) if fw else {}
    for name, key in (("fw.flash", "flash_bytes"), ("fw.ram", "ram_bytes"),
                      ("fw.boot", "boot_instructions"), ("fw.isr_adc", "isr_adc_instructions"),
                      ("fw.isr_ftm", "isr_ftm3_instructions"), ("fw.isr_tick", "isr_tick_instructions")):
        put(name, fwj.get(key), "build/s32k144/firmware.json (make firmware)")
    cov = _read(root, "build/coverage/summary.txt") or ""
    for kind in ("lines", "branches", "functions"):
        m = re.search(rf"^{kind}: [\d.]+% \((\d+) out of (\d+)\)", cov, re.M)
        put(f"cov.{kind}_covered", int(m.group(1)) if m else None, "build/coverage/summary.txt")
        put(f"cov.{kind}", int(m.group(2)) if m else None, "build/coverage/summary.txt")
    put("misra.devs_short", f"{devs[0]}..{devs[-1][4:]}" if devs else None, "misra/deviations.md (## DEV-nnn)")
    ms = _read(root, "build/misra/compliance-summary.json")
    try:
        ms = json.loads(ms) if ms else None
    except ValueError:
        ms = None
    counts = (ms or {}).get("counts") or {}
    src = "build/misra/compliance-summary.json"
    for name, key in (("misra.guidelines", "guidelines"), ("misra.compliant", "compliant"),
                      ("misra.deviated", "deviations"), ("misra.disapplied", "disapplied")):
        put(name, counts.get(key), src)
    put("misra.sites", sum(int(d.get("sites", 0)) for d in ms.get("deviation_records", []))
        if ms else None, src)
    camp = _read(root, "build/robustness/campaign.json")
    succ = None
    if camp:
        try:
            c = json.loads(camp)
            if int(c.get("count", -1)) == v["robust.count"][0]:
                succ = int(c.get("successes"))
        except (ValueError, TypeError):
            succ = None
    put("robust.successes", succ, "build/robustness/campaign.json (a full campaign)")
    return v


def template_regex(template):
    """The regex of a template and the figure names of its groups, in order."""
    names, parts, pos = [], [], 0
    for m in re.finditer(r"\{([a-z_.]+)\}", template):
        parts.append(re.escape(template[pos:m.start()]).replace(r"\ ", r"\s+"))
        names.append(m.group(1))
        parts.append("(" + FORMS.get(m.group(1), r"\d+(?:,\d{3})*") + ")")
        pos = m.end()
    parts.append(re.escape(template[pos:]).replace(r"\ ", r"\s+"))
    return re.compile("".join(parts)), names


def current_section(text):
    """(start, end) of the changelog's current section: from its first '## [' heading to the
    next (the older releases' figures are history)."""
    heads = [m.start() for m in re.finditer(r"^## \[", text, re.M)]
    if not heads:
        return 0, len(text)
    return heads[0], heads[1] if len(heads) > 1 else len(text)


def _norm(text):
    return text.replace(",", "") if re.fullmatch(r"\d+(?:,\d{3})*", text) else re.sub(r"\s+", " ", text)


def check(root=".", write=False, registry=None):
    """(failures, notes): every registered figure (FIGURES, or the registry given) against
    its source; the counts no template covers in those files; the figures without a source
    here, and whether they agree across documents."""
    vals = values(root)
    failures, notes = [], []
    covered = {}
    seen = {}  # figure -> set of values written (for the built ones)
    texts = {}
    for rel, template in (FIGURES if registry is None else registry):
        if rel not in texts:
            texts[rel] = _read(root, rel)
        text = texts[rel]
        if text is None:
            failures.append(f"{rel}: missing (figure template '{template}')")
            continue
        rx, names = template_regex(template)
        matches = list(rx.finditer(text))
        if not matches:
            failures.append(f"{rel}: the figure '{template}' is no longer in the text (update "
                            f"FIGURES in tools/evidence/figures.py with the text)")
            continue
        for m in matches:
            covered.setdefault(rel, []).append((m.start(), m.end()))
            line = text.count("\n", 0, m.start()) + 1
            for k, name in enumerate(names):
                if name not in vals:
                    failures.append(f"{rel}:{line}: unknown figure {{{name}}} in FIGURES")
                    continue
                written = _norm(m.group(k + 1))
                value, source = vals[name]
                seen.setdefault(name, {}).setdefault(written, []).append(f"{rel}:{line}")
                if value is None:
                    continue
                if written != str(value):
                    quoted = re.sub(r"\s+", " ", m.group(0))
                    failures.append(f"{rel}:{line}: figure {name} is {written}, the source says {value} "
                                    f"({source}): '{quoted}'")
        if write:
            def repl(m):
                out, last = [], m.start()
                for k, name in enumerate(names):
                    value = vals.get(name, (None, ""))[0]
                    out.append(m.string[last:m.start(k + 1)])
                    out.append(str(value) if value is not None else m.group(k + 1))
                    last = m.end(k + 1)
                out.append(m.string[last:m.end()])
                return "".join(out)
            texts[rel] = rx.sub(repl, text)
    for rel, text in texts.items():
        if text is None:
            continue
        spans = covered.get(rel, [])
        lo, hi = current_section(text) if rel == CHANGELOG else (0, len(text))
        for m in list(COUNT.finditer(text)) + list(RANGES.finditer(text)):
            if m.start() < lo or m.end() > hi:
                continue
            if any(s <= m.start() and m.end() <= e for s, e in spans):
                continue
            around = text[max(0, m.start() - 2):m.end() + 2]
            if any(r == rel and (t in around or around.strip() in t) for r, t, _w in NOT_FIGURES):
                continue
            line = text.count("\n", 0, m.start()) + 1
            quoted = re.sub(r"\s+", " ", m.group(0))
            failures.append(f"{rel}:{line}: hand-typed figure '{quoted}' that no "
                            f"template of tools/evidence/figures.py checks")
    for name, written in sorted(seen.items()):
        value, source = vals[name]
        if value is None:
            where = sorted(w for ws in written.values() for w in ws)
            notes.append(f"{name}: not checked, {source} not present here ({len(where)} occurrence(s))")
            if len(written) > 1:
                failures.append(f"figure {name} differs between documents: " + "; ".join(
                    f"{w} in {', '.join(ws)}" for w, ws in sorted(written.items())))
    if write:
        for rel, text in texts.items():
            if text is not None and text != _read(root, rel):
                with open(os.path.join(root, rel), "w", encoding="utf-8") as f:
                    f.write(text)
    return failures, notes


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--root", default=".")
    ap.add_argument("--write", action="store_true", help="replace the figures by the computed ones")
    args = ap.parse_args(argv)
    failures, notes = check(args.root, write=args.write)
    if args.write:
        failures, notes = check(args.root)
    for n in notes:
        print(f"figures: {n}")
    for f in failures:
        print(f"figures: {f}")
    n = sum(1 for _ in FIGURES)
    if failures:
        print(f"figures: FAILED: {len(failures)} figure(s) differ from their source or are not checked "
              f"(tools/evidence/figures.py --write replaces the registered ones)")
        return 1
    print(f"figures: {n} figure templates checked against their sources, "
          f"{len(notes)} built figure(s) not present here")
    return 0


if __name__ == "__main__":
    sys.exit(main())
