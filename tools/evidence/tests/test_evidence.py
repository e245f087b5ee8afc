"""Tests of tools/evidence/evidence.py (run: python3 -m pytest tools/evidence/tests).

Each test makes up the gates' results in a temporary repository root (a few lines of
JUnit, results.md, JSON), stamps them with their inputs as the gates do
(tools/evidence/inputs.py, with fixed tool versions), runs the tool on it and reads the
summary rows of evidence.json.  The requirements are those of specs/requirements/evidence.md.
"""
import json
import os
import sys
from pathlib import Path

import pytest

HERE = Path(__file__).resolve().parent.parent  # tools/evidence
GATES = HERE.parent / "gates"
sys.path.insert(0, str(HERE))

import evidence as ev  # noqa: E402
import inputs  # noqa: E402
import review_stamp  # noqa: E402


@pytest.fixture(autouse=True)
def fixed_tools(monkeypatch):
    """The tools' version lines of the inputs stamps, fixed (no tool is run)."""
    monkeypatch.setattr(inputs, "tool_line", lambda name, argv: name + " 1.0")
    for var in ("WP_TIMEOUT", "CBMC_SAT", "EVA_EXTRA", "EVA_ALL_EXTRA", "EVA_PRECISION",
                "EVA_MAX_ALARMS", "EVA_RUN"):
        monkeypatch.delenv(var, raising=False)

# Requirement IDs of the made-up matrix, written so that the trace gate does not read them
# as IDs named by this file.
X1, X2, Y1 = "REQ-" + "X-001", "REQ-" + "X-002", "REQ-" + "Y-001"

JUNIT_OK = """<?xml version="1.0" encoding="UTF-8"?>
<testsuites tests="2" failures="0" errors="0">
  <testsuite name="test_a" tests="2" failures="0" errors="0" skipped="0">
    <testcase classname="test_a" name="test_one"/>
    <testcase classname="test_a" name="test_two"/>
  </testsuite>
</testsuites>
"""

JUNIT_FAIL = """<?xml version="1.0" encoding="UTF-8"?>
<testsuites tests="2" failures="1" errors="0">
  <testsuite name="test_b" tests="2" failures="1" errors="0" skipped="0">
    <testcase classname="test_b" name="test_good"/>
    <testcase classname="test_b" name="test_bad"><failure message="failed">x != y</failure></testcase>
  </testsuite>
</testsuites>
"""

# pytest's own dialect: <testsuite> at the root, time attributes, a skipped test
JUNIT_PYTEST = """<?xml version="1.0" encoding="utf-8"?>
<testsuite name="pytest" errors="0" failures="0" skipped="1" tests="3" time="0.50">
  <testcase classname="tools.tests.test_x" name="test_p" time="0.1"/>
  <testcase classname="tools.tests.test_x" name="test_q" time="0.2"/>
  <testcase classname="tools.tests.test_x" name="test_r" time="0.0"><skipped message="no"/></testcase>
</testsuite>
"""


def wp_results(proved, total):
    return ("# Frama-C WP results, per function\n\n"
            f"**proved {proved} / {total} goals**\n\n"
            "| unit | function | goals | proved | provers | time (ms) |\n"
            "|---|---|---:|---:|---|---:|\n"
            f"| qfoc_x | qfoc_x_step | {total - 3} | {proved - 3} | Qed+Z3 | 120 |\n"
            "| qfoc_x | qfoc_x_init | 3 | 3 | Qed | 2 |\n")


CBMC_RESULTS = ("# CBMC results, per harness\n\n"
                "| harness | result | properties proved | failed | unwind | time (s) |\n"
                "|---|---|---:|---:|---:|---:|\n"
                "| x_step | PASS | 120 | 0 | 2 | 3 |\n"
                "| x_init | PASS | 30 | 0 | 1 | 0 |\n")

TRACE = {"requirements": [
    {"id": X1, "title": "Step", "contracts": ["qfoc_x_step"],
     "wp": {"functions": ["qfoc_x_step"], "goals": 10, "proved": 10}, "cbmc": ["x_step"],
     "tests": [{"kind": "cmocka", "file": "tests/test_a.c", "name": "test_one"}],
     "scenarios": [], "verified": True, "file": "specs/requirements/x.md"},
    {"id": Y1, "title": "Init", "contracts": ["qfoc_y_init"], "wp": {"goals": 0, "proved": 0},
     "cbmc": [], "tests": [{"name": "test_two", "file": "tests/test_a.c"}], "verified": True}],
    "gate_failures": []}

# The result files the gates stamp, with their gate (tools/evidence/inputs.py)
STAMPED = (("proofs/wp/results.md", "wp"), ("build/wp/wp-summary.json", "wp"),
           ("proofs/cbmc/results.md", "cbmc"), ("build/eva/eva.json", "eva"),
           ("build/eva/eva-all.json", "eva"),
           ("build/misra/compliance-summary.json", "misra"), ("build/coverage/coverage.xml", "coverage"),
           ("build/bench/bench.json", "bench"))


def stamp(root, now=None):
    """Stamp every result file there is with its inputs, as the gates do."""
    for rel, gate in STAMPED:
        if (root / rel).exists():
            inputs.stamp(str(root / rel), gate, str(root), now=now)


# build/validation/results.json of make tool-validation (tools/validation/run.py): two
# defects, every expected catch made, the control passing
TOOLVAL = {"date": "2025-01-01 00:00:00 UTC", "commit": "abc",
           "summary": {"ok": True, "caught": 3, "expected_catches": 3, "control_ok": True,
                       "wall_seconds": 100.0, "cpu_seconds": 150.0},
           "defects": [{"id": "TV-01", "class": "overflow", "title": "t", "file": "src/x.c",
                        "expected": ["wp", "cbmc"],
                        "gates": {"wp": {"status": "caught", "detail": "proved 1 / 2 goals"},
                                  "cbmc": {"status": "caught"}, "tests": {"status": "not expected"}}},
                       {"id": "TV-02", "class": "MISRA violation", "title": "u", "file": "src/x.c",
                        "expected": ["misra"], "gates": {"misra": {"status": "caught"}}}],
           "control": [{"scope": "x", "gate": "wp", "outcome": "pass", "ok": True, "detail": "proved 2 / 2"},
                       {"scope": "x", "gate": "misra", "outcome": "pass", "ok": True, "detail": "0"}]}


# The review records of the made-up tree: one MISRA review record over src/*.c, and an FMEA
# row naming the function of src/qfoc_x.c and the requirement X1 (tools/evidence/review_stamp.py)
REVIEWS = ("# MISRA C:2012 manual review records\n\n## Rule 17.2 No recursion\n"
           "- Guideline: Rule 17.2 (required)\n- Scope: `src/*.c`\n- Method: the call graph.\n"
           "- Checked: no cycle.\n- Result: compliant\n- Reviewed: 2025-01-01, by the maintainers\n")
ANALYSIS = ("# Safety analysis\n\n## 2. Software FMEA\n\nReviewed: 2025-01-01, by the maintainers\n\n"
            "| ID | block | failure mode | evidence |\n|---|---|---|---|\n"
            f"| F-01 | `qfoc_x_step` | value wrong | {X1}; test `test_one` |\n"
            f"| F-02 | `qfoc_x_step` | omitted | {X1}, {Y1} |\n\n## 3. Dependent failures\n")


def review(root):
    """Stamp the review records as a review does (before the gates: misra/ is an input of MISRA)."""
    review_stamp.stamp("misra", str(root), date="2025-01-02")
    review_stamp.stamp("fmea", str(root), date="2025-01-02")


def write(root, rel, text):
    p = root / rel
    p.parent.mkdir(parents=True, exist_ok=True)
    p.write_text(text if isinstance(text, str) else json.dumps(text), encoding="utf-8")
    return p


def full_inputs(root):
    """Every input of a passing run."""
    write(root, "build/junit/test_a.xml", JUNIT_OK)
    write(root, "proofs/wp/results.md", wp_results(13, 13))
    write(root, "proofs/cbmc/results.md", CBMC_RESULTS)
    write(root, "build/eva/eva.json", {"frama_c_exit": 0, "seconds": 9, "rte_alarms": [],
                                       "unknown_properties": 4})
    write(root, "build/eva/eva-all.json", {"frama_c_exit": 0, "seconds": 20, "rte_alarms": [],
                                           "unknown_properties": 7})
    write(root, "build/trace/trace.json", TRACE)
    write(root, "build/misra/compliance-summary.json",
          {"framework": "MISRA Compliance:2020",
           "counts": {"guidelines": 3, "compliant": 2, "deviations": 1, "disapplied": 0, "violations": 0},
           "guideline_status": [{"id": "Rule 8.7", "category": "advisory", "status": "Deviations",
                                 "deviations": [{"id": "DEV-002", "sites": 2}], "methods": ["cppcheck"]}],
           "deviation_records": [{"id": "DEV-002", "title": "t", "guidelines": ["Rule 8.7"], "sites": 2}],
           "plan_errors": [], "unattributed_findings": [], "compliant": True})
    write(root, "misra/deviations.md", "# MISRA C:2012 deviation records\n\n## DEV-002 t\n\nRule: 8.7.\n")
    write(root, "misra/enforcement-plan.csv", "id,kind\nRule 8.7,rule\n")
    write(root, "build/coverage/coverage.xml",
          '<?xml version="1.0"?><coverage lines-valid="3" lines-covered="3" branches-valid="2" '
          'branches-covered="2"><packages><package><classes><class filename="src/x.c"><lines>'
          '<line number="1" hits="4" branch="false"/><line number="2" hits="1" branch="true" '
          'condition-coverage="100% (2/2)"/><line number="3" hits="2" branch="false"/></lines>'
          '</class></classes></package></packages></coverage>')
    write(root, "build/mcdc/mcdc.json",
          {"summary": {"src": {"outcomes": 4, "covered": 3, "justified": 1, "percent": 75.0},
                       "include": {"outcomes": 2, "covered": 2, "justified": 0, "percent": 100.0},
                       "unjustified": 0, "unused_justifications": []},
           "files": {"src/x.c": {"outcomes": 4, "covered": 3, "justified": 1, "percent": 75.0}},
           "decisions": [{"file": "src/x.c", "line": 7, "function": "qfoc_x_step", "decision": "a && b",
                          "outcomes": [{"text": "b", "outcome": "false", "covered": False,
                                        "justification": "b is always true by XValid"}]}]})
    write(root, "build/bench/bench.json",
          {"table": [{"item": "`qfoc_drive_fast_step`, closed loop", "min": 10, "max": 20, "limit": 30,
                      "result": "OK", "unit": "instructions", "requirement": "REQ-BENCH-002", "goal": 5,
                      "goal_result": "OVER"},
                     {"item": "RAM per motor", "min": None, "max": 400, "limit": 512, "result": "OK",
                      "unit": "bytes", "requirement": "REQ-BENCH-005"}],
           "sizes": {"lib_text_rodata": 1000, "sizeof_drive": 400},
           "stack": {"qfoc_drive_fast_step": {"bytes": 100}}})
    write(root, "build/static/qfoc.sarif",
          {"version": "2.1.0", "runs": [
              {"tool": {"driver": {"name": "cppcheck", "version": "2.10"}},
               "invocations": [{"executionSuccessful": True}],
               "results": [{"ruleId": "variableScope", "message": {"text": "m"},
                            "suppressions": [{"kind": "external", "status": "accepted",
                                              "justification": "specs/static-accepted.md, Locals: why"}]}]}]})
    write(root, "build/repro/repro.json",
          {"compiler": "arm-none-eabi-gcc 12", "artefacts": [
              {"file": "target/libqfoc.a", "sha256": "ab" * 32, "sha256_second": "ab" * 32, "identical": True}]})
    write(root, "build/target_test/target.txt",
          "qfoc golden vectors: 2 groups\nq15_sat: 10 vectors, identical\nsin: 5 vectors, identical\n"
          "result: 2 groups, 15 vectors, all identical (0.1 s)\n")
    write(root, "specs/tool-confidence.json",
          [{"tool": "gcc", "version": "12", "use_cases": ["builds"], "impact": "TI2", "detection": "TD1",
            "tcl": "TCL1", "mitigation": "none"}])
    write(root, "specs/safety-manual.md", "# Manual\n\n- **one**\n  - nested `x`\n\n| a | b |\n|---|---|\n| 1 | 2 |\n")
    write(root, "build/check-summary.txt", "test      PASS     3s  2 passed, 0 failed\n"
                                           "prove     FAIL    40s  proved 12 / 13 goals\n")
    write(root, "build/check-test.log", "2 passed, 0 failed\n")
    write(root, "src/qfoc_x.c", "#include \"qfoc/x.h\"\nint qfoc_x_step(int a)\n{\n    return a;\n}\n")
    write(root, "include/qfoc/x.h", "int qfoc_x_step(int a);\n")
    write(root, "specs/requirements/x.md", f"# X\n\n### {X1} Step\n\n### {Y1} Init\n")
    write(root, "misra/reviews.md", REVIEWS)
    write(root, "specs/safety-analysis.md", ANALYSIS)
    review(root)
    stamp(root)
    write(root, "build/validation/results.json", TOOLVAL)


def run(root, *extra):
    """Run the tool on ROOT; (exit status, evidence.json, summary rows by key)."""
    rc = ev.main(["--root", str(root), *extra])
    data = json.loads((root / "build" / "evidence" / "evidence.json").read_text(encoding="utf-8"))
    return rc, data, {r["key"]: r for r in data["summary"]}


def test_all_inputs_green_and_bundle_written(tmp_path, capsys):
    """REQ-EVD-001, REQ-EVD-002: every row green on a passing run; the page, the JSON and
    the copied artefacts are written, the page is self-contained and its links resolve.

    Methods: 1a every row green on a passing run, the page, the JSON and the copied artefacts
    written, the page self-contained with every link resolving
    """
    full_inputs(tmp_path)
    rc, data, rows = run(tmp_path, "--strict")
    assert rc == 0
    assert all(r["status"] == "PASS" for r in data["summary"]), [r for r in data["summary"]
                                                                   if r["status"] != "PASS"]
    assert data["red"] == 0 and data["green"] == len(data["summary"]) == 16
    out = tmp_path / "build" / "evidence"
    page = (out / "index.html").read_text(encoding="utf-8")
    assert "<script" not in page and "http://" not in page.replace("http://cobertura", "")
    assert (out / "artefacts" / "proofs" / "wp" / "results.md").exists()
    assert (out / "artefacts" / "build" / "junit" / "test_a.xml").exists()
    for href in __import__("re").findall(r'href="([^"#][^"]*)"', page):
        assert (out / href).exists(), href
    text = capsys.readouterr().out
    assert text.strip().splitlines()[-1].endswith("(16 green, 0 red)")
    assert "tests passed" in text and "PASS" in text


def test_failed_test_turns_tests_row_red(tmp_path):
    """REQ-EVD-007, REQ-EVD-002: one failed JUnit test makes the tests row red, with the
    totals over every JUnit file (both dialects), and --strict exits 1.

    Methods: 1b JUnit files of both dialects (CMocka and pytest); 1d one failed test: the tests
    row red, --strict exits 1; 1l the failure written into a made-up JUnit file
    """
    full_inputs(tmp_path)
    write(tmp_path, "build/junit/test_b.xml", JUNIT_FAIL)
    write(tmp_path, "build/junit/pytest/pytest.xml", JUNIT_PYTEST)
    rc, data, rows = run(tmp_path)
    assert rc == 0
    assert rows["tests"]["status"] == "FAIL"
    assert rows["tests"]["figure"].startswith("5/7 passed, 1 failures, 0 errors, 1 skipped")
    tests = data["sections"]["tests"]
    assert tests["failures"] == 1 and tests["tests"] == 7
    assert any("test_b.test_bad" in f["failed_tests"] for f in tests["files"])
    rc, _data, _rows = run(tmp_path, "--strict")
    assert rc == 1


def test_missing_inputs_are_red_not_run(tmp_path, capsys):
    """REQ-EVD-002: with no result at all every summary row is red 'not run', the page is
    still written and the exit status is 0 (1 with --strict).

    Methods: 1c no result at all (every row 'not run'); 1d every input missing, the page still
    written
    """
    rc, data, rows = run(tmp_path)
    assert rc == 0
    assert data["green"] == 0 and data["red"] == len(data["summary"]) == 15
    for r in data["summary"]:
        assert r["status"] == "FAIL" and r["figure"] == "not run" and r["missing"], r
    assert (tmp_path / "build" / "evidence" / "index.html").exists()
    assert "(0 green, 15 red)" in capsys.readouterr().out
    assert run(tmp_path, "--strict")[0] == 1


def test_one_missing_input_only_its_row_red(tmp_path):
    """REQ-EVD-002, REQ-EVD-004: without build/eva/eva-all.json (make eva's result) only the EVA
    row turns red.

    Methods: 1d one input missing and one truncated (unreadable JSON); 1l the file removed and
    truncated among made-up inputs
    """
    full_inputs(tmp_path)
    os.remove(tmp_path / "build" / "eva" / "eva-all.json")
    _rc, _data, rows = run(tmp_path)
    assert rows["eva"]["status"] == "FAIL" and rows["eva"]["figure"] == "not run"
    assert [k for k, r in rows.items() if r["status"] == "FAIL"] == ["eva"]
    write(tmp_path, "build/eva/eva-all.json", "{ truncated")
    _rc, _data, rows = run(tmp_path)
    assert rows["eva"]["status"] == "FAIL" and rows["eva"]["figure"] == "unreadable: build/eva/eva-all.json"


# REQ-EVD-030
def test_tool_validation_row_and_section(tmp_path):
    """REQ-EVD-030: the tool-validation row is green when every expected catch happened and
    the control passed; a missed catch or a failed control turns it red; the section lists
    every defect with its gates; without results.json (make check does not run the campaign)
    the section shows a red 'not run' row and the one-screen summary has no row for it.

    Methods: 1b every catch and the control passing, a missed catch, a failed control, no
    results file; 1d a missed catch and a false alarm; 1l each written into made-up campaign
    results
    """
    full_inputs(tmp_path)
    _rc, data, rows = run(tmp_path)
    assert rows["toolval"]["status"] == "PASS"
    assert rows["toolval"]["figure"].startswith("3 / 3 expected catches in 2 seeded defects; control passes")
    page = (tmp_path / "build" / "evidence" / "index.html").read_text(encoding="utf-8")
    assert "13 Tool validation" in page and "TV-02 u" in page
    assert (tmp_path / "build" / "evidence" / "artefacts" / "build" / "validation" / "results.json").exists()
    missed = json.loads(json.dumps(TOOLVAL))
    missed["defects"][0]["gates"]["cbmc"]["status"] = "MISSED"
    write(tmp_path, "build/validation/results.json", missed)
    _rc, _data, rows = run(tmp_path)
    assert rows["toolval"]["status"] == "FAIL" and rows["toolval"]["figure"].startswith("2 / 3")
    assert [k for k, r in rows.items() if r["status"] == "FAIL"] == ["toolval"]
    false_alarm = json.loads(json.dumps(TOOLVAL))
    false_alarm["control"][0].update(ok=False, outcome="FALSE ALARM")
    write(tmp_path, "build/validation/results.json", false_alarm)
    _rc, _data, rows = run(tmp_path)
    assert rows["toolval"]["status"] == "FAIL" and "control FAILS" in rows["toolval"]["figure"]
    os.remove(tmp_path / "build" / "validation" / "results.json")
    rc, data, rows = run(tmp_path, "--strict")
    assert "toolval" not in rows and rc == 0
    assert data["sections"]["toolval"]["status"]["figure"] == "not run"
    page = (tmp_path / "build" / "evidence" / "index.html").read_text(encoding="utf-8")
    assert "Not run: build/validation/results.json" in page


def test_wp_not_all_proved_is_red(tmp_path):
    """REQ-EVD-004: WP with proved < total is red, with the figure proved/total.

    Methods: 1c 12 of 13 goals, one short of all; 1d a goal not proved
    """
    full_inputs(tmp_path)
    write(tmp_path, "proofs/wp/results.md", wp_results(12, 13))
    _rc, data, rows = run(tmp_path)
    assert rows["wp"]["status"] == "FAIL"
    assert rows["wp"]["figure"].startswith("12/13 goals")
    assert data["sections"]["wp"]["source"] == "proofs/wp/results.md"


def test_wp_prefers_fresh_build_results(tmp_path):
    """REQ-EVD-004: build/wp/wp-summary.json written after the committed results wins.

    Methods: 1b committed and built WP results, the built one newer
    """
    full_inputs(tmp_path)
    write(tmp_path, "build/wp/wp-summary.json",
          {"proved": 20, "total": 20, "clean": True,
           "functions": [{"unit": "qfoc_x", "function": "qfoc_x_step", "goals": 20, "proved": 20,
                          "provers": "Z3", "time_ms": 5}]})
    stamp(tmp_path)
    later = os.path.getmtime(tmp_path / "proofs" / "wp" / "results.md") + 60
    os.utime(tmp_path / "build" / "wp" / "wp-summary.json", (later, later))
    _rc, data, rows = run(tmp_path)
    assert data["sections"]["wp"]["source"] == "build/wp/wp-summary.json"
    assert rows["wp"]["status"] == "PASS" and rows["wp"]["figure"].startswith("20/20 goals")


def test_wp_function_without_result_is_red(tmp_path):
    """REQ-EVD-004: a function that src/ defines but the WP results do not list is red.

    Methods: 1d a static function and a whole unit that the WP results do not list
    """
    full_inputs(tmp_path)
    gates = tmp_path / "tools" / "gates"
    gates.mkdir(parents=True)
    (gates / "c_functions.py").write_bytes((GATES / "c_functions.py").read_bytes())
    write(tmp_path, "src/qfoc_x.c", "void qfoc_x_init(void)\n{\n}\n\nvoid qfoc_x_step(void)\n{\n}\n\n"
                                    "static void qfoc_x_extra(void)\n{\n}\n")
    write(tmp_path, "src/qfoc_z.c", "int qfoc_z_get(void)\n{\n    return 0;\n}\n")
    _rc, data, rows = run(tmp_path)
    assert rows["wp"]["status"] == "FAIL"
    assert data["sections"]["wp"]["functions_without_result"] == ["qfoc_x:qfoc_x_extra"]
    assert data["sections"]["wp"]["units_without_result"] == ["qfoc_z"]


def test_eva_reference_table_optional_but_counted(tmp_path):
    """REQ-EVD-004: make eva's result is the analysis over every accepted table; the reference
    table's analysis (make eva-reference, outside make check) may be missing, but when it is
    there and current an alarm of it is red, and when it is of other sources it is not counted.

    Methods: 1b both analyses clean, the reference analysis missing, one alarm in it, the
    reference analysis stale; 1d an alarm of the optional analysis; 1l made-up results
    """
    full_inputs(tmp_path)
    _rc, _data, rows = run(tmp_path)
    assert rows["eva"]["status"] == "PASS"
    assert rows["eva"]["figure"] == "0 alarms (target 0) over every accepted table, 20 s; reference table: 0 alarms"
    os.remove(tmp_path / "build" / "eva" / "eva.json")
    _rc, _data, rows = run(tmp_path)
    assert rows["eva"]["status"] == "PASS" and "reference" not in rows["eva"]["figure"]
    write(tmp_path, "build/eva/eva.json", {"frama_c_exit": 0, "seconds": 9, "rte_alarms": [
        {"file": "src/x.c", "line": 3, "message": "signed overflow. assert a + b <= 32767;"}],
        "unknown_properties": 4})
    stamp(tmp_path)
    _rc, _data, rows = run(tmp_path)
    assert rows["eva"]["status"] == "FAIL" and rows["eva"]["figure"].endswith("reference table: 1 alarm")
    # the sources change after the reference run: make check reruns eva-all only
    (tmp_path / "src" / "qfoc_x.c").write_text("/* changed */\n", encoding="utf-8")
    inputs.stamp(str(tmp_path / "build/eva/eva-all.json"), "eva", str(tmp_path))
    _rc, _data, rows = run(tmp_path)
    assert rows["eva"]["status"] == "PASS"
    assert rows["eva"]["figure"].endswith("reference table: result of other sources, not counted "
                                          "(make eva-reference)")


def test_eva_alarm_and_cbmc_failure_are_red(tmp_path):
    """REQ-EVD-004: an EVA runtime-error alarm, or a CBMC harness that fails, is red.

    Methods: 1d an EVA runtime-error alarm and a failing CBMC harness; 1l both written into
    made-up results
    """
    full_inputs(tmp_path)
    write(tmp_path, "build/eva/eva-all.json", {"frama_c_exit": 0, "seconds": 9, "rte_alarms": [
        {"file": "src/x.c", "line": 3, "message": "signed overflow. assert a + b <= 32767;"}]})
    write(tmp_path, "proofs/cbmc/results.md", CBMC_RESULTS.replace("| x_init | PASS | 30 | 0 |",
                                                                    "| x_init | FAIL | 29 | 1 |"))
    _rc, _data, rows = run(tmp_path)
    assert rows["eva"]["status"] == "FAIL" and rows["eva"]["figure"].startswith("1 alarm (target 0)")
    assert rows["cbmc"]["status"] == "FAIL" and "1 failed" in rows["cbmc"]["figure"]


def test_cbmc_harness_without_result_is_red(tmp_path):
    """REQ-EVD-004: a harness folder of proofs/cbmc/ missing from the results is red.

    Methods: 1d a harness folder missing from the results
    """
    full_inputs(tmp_path)
    write(tmp_path, "proofs/cbmc/x_new/harness.c", "void harness(void) {}\n")
    write(tmp_path, "proofs/cbmc/x_step/harness.c", "void harness(void) {}\n")
    _rc, data, rows = run(tmp_path)
    assert rows["cbmc"]["status"] == "FAIL"
    assert data["sections"]["cbmc"]["harnesses_without_result"] == ["x_new"]


def test_trace_from_markdown_and_gate_failures(tmp_path):
    """REQ-EVD-003: without trace.json the matrix comes from trace.md; a requirement
    without test or harness is not verified; trace gate failures turn the row red.

    Methods: 1b the matrix from trace.md and from trace.json; 1d a requirement without test or
    harness, a trace gate failure
    """
    full_inputs(tmp_path)
    os.remove(tmp_path / "build" / "trace" / "trace.json")
    write(tmp_path, "build/trace/trace.md",
          "# Requirement traceability\n\n| requirement | title | header | CBMC | tests |\n"
          f"|---|---|---|---|---|\n| {X1} | Step | x.h | x_step | test_a.c: test_one<br>test_a.c: test_two |\n"
          f"| {X2} | Init | x.h | - | - |\n")
    _rc, data, rows = run(tmp_path)
    assert rows["requirements"]["status"] == "FAIL"
    assert rows["requirements"]["figure"] == "1/2 verified; 1 no evidence"
    reqs = {r["id"]: r for r in data["sections"]["trace"]["requirements"]}
    assert reqs[X1]["tests"] == ["test_a.c: test_one", "test_a.c: test_two"] and reqs[X1]["module"] == "X"
    assert reqs[X1]["verdict"] == "verified" and reqs[X2]["verdict"] == "no evidence"
    trace = dict(TRACE, gate_failures=["tests/test_x.c: cmocka test t names no requirement"])
    write(tmp_path, "build/trace/trace.json", trace)
    _rc, _data, rows = run(tmp_path)
    assert rows["requirements"]["status"] == "FAIL"
    assert rows["requirements"]["figure"] == "2/2 verified; 1 trace gate failures"


def test_misra_violation_coverage_gap_bench_over_static_unaccepted(tmp_path):
    """REQ-EVD-005, REQ-EVD-006, REQ-EVD-008, REQ-EVD-009, REQ-EVD-012: a MISRA violation,
    a branch not covered, an MC/DC outcome without justification, a limit exceeded, an
    unaccepted finding and two different builds each turn their row red.

    Methods: 1b each of six rows turned red by its own defect; 1c a branch coverage of 1 / 2, a
    bench figure over its limit; 1d a MISRA violation, an unjustified MC/DC outcome, an
    unaccepted finding, two different builds; 1l each defect written into made-up results
    """
    full_inputs(tmp_path)
    misra = json.loads((tmp_path / "build/misra/compliance-summary.json").read_text())
    misra["counts"]["violations"] = 1
    write(tmp_path, "build/misra/compliance-summary.json", misra)
    cov = (tmp_path / "build/coverage/coverage.xml").read_text()
    write(tmp_path, "build/coverage/coverage.xml",
          cov.replace('branches-covered="2"', 'branches-covered="1"').replace("100% (2/2)", "50% (1/2)"))
    write(tmp_path, "build/mcdc/mcdc.json",
          {"summary": {"src": {"outcomes": 4, "covered": 3, "justified": 0}, "unjustified": 1},
           "decisions": [{"file": "src/x.c", "line": 7, "function": "f", "decision": "a && b",
                          "outcomes": [{"text": "b", "outcome": "false", "covered": False}]}]})
    bench = json.loads((tmp_path / "build/bench/bench.json").read_text())
    bench["table"][1].update({"max": 600, "result": "OVER"})
    write(tmp_path, "build/bench/bench.json", bench)
    sarif = json.loads((tmp_path / "build/static/qfoc.sarif").read_text())
    sarif["runs"][0]["results"].append({"ruleId": "nullPointer", "message": {"text": "n"}})
    write(tmp_path, "build/static/qfoc.sarif", sarif)
    write(tmp_path, "build/repro/repro.json", {"artefacts": [
        {"file": "target/libqfoc.a", "sha256": "ab" * 32, "sha256_second": "cd" * 32, "identical": False}]})
    stamp(tmp_path)
    _rc, data, rows = run(tmp_path)
    red = {k for k, r in rows.items() if r["status"] == "FAIL"}
    assert red == {"misra", "branch", "mcdc", "bench", "static", "repro"}
    assert rows["statement"]["status"] == "PASS"
    assert rows["branch"]["figure"].startswith("50.0 % (1/2 branches")
    assert rows["bench"]["figure"].startswith("limits met 1/2")
    assert rows["static"]["figure"].endswith("1 accepted, 1 unaccepted")
    assert data["sections"]["mcdc"]["uncovered"][0]["justification"] is None


def test_mcdc_justified_exclusion_listed(tmp_path):
    """REQ-EVD-006: an outcome not covered but justified keeps MC/DC green and is listed
    with its justification.

    Methods: 1a an outcome not covered but justified keeps MC/DC green and is listed with its
    justification
    """
    full_inputs(tmp_path)
    _rc, data, rows = run(tmp_path)
    assert rows["mcdc"]["status"] == "PASS"
    assert "1 justified exclusions" in rows["mcdc"]["figure"]
    page = (tmp_path / "build/evidence/index.html").read_text(encoding="utf-8")
    assert "b is always true by XValid" in page


def test_sections_tools_manual_gates(tmp_path):
    """REQ-EVD-010, REQ-EVD-011, REQ-EVD-013: the tool classification, the rendered safety
    manual and the gate log with its links are in the page and in the JSON.

    Methods: 1a the tool classification, the rendered safety manual and the gate log with its
    links in the page and in the JSON
    """
    full_inputs(tmp_path)
    _rc, data, _rows = run(tmp_path)
    page = (tmp_path / "build/evidence/index.html").read_text(encoding="utf-8")
    assert "<td>TCL1</td>" in page
    assert "<li><strong>one</strong><ul><li>nested <code>x</code></li></ul></li>" in page
    assert "<td>1</td><td>2</td>" in page
    gates = data["sections"]["gates"]["gates"]
    assert [(g["gate"], g["result"], g["seconds"]) for g in gates] == [("test", "PASS", 3), ("prove", "FAIL", 40)]
    assert gates[0]["log"] == "artefacts/build/check-test.log"
    assert data["sections"]["gates"]["failed"] == ["prove"]


@pytest.mark.parametrize("text, html", [
    ("a `x*y*z` **b** *c*", "a <code>x*y*z</code> <strong>b</strong> <em>c</em>"),
    ("see [doc](specs/x.md)", "see doc (<code>specs/x.md</code>)"),
    ("a < b & c", "a &lt; b &amp; c"),
])
def test_markdown_inline(text, html):
    """REQ-EVD-011: the inline markdown of the rendered documents.

    Methods: 1b code, emphasis, links and characters to escape, one case per parameter
    """
    assert ev.md_inline(text) == html


def test_stale_results_are_red_and_their_proofs_stale(tmp_path):
    """REQ-EVD-028, REQ-EVD-027: a source changed after the runs makes every result computed
    from it stale: its row red with STALE and the file named, its figures kept, and a
    requirement whose WP and CBMC rows all hold gets the verdict 'stale'.  A committed result
    without a stamp is stale too.

    Methods: 1d a source changed after the runs, a committed result without a stamp; 1l the
    source change written into the made-up tree
    """
    full_inputs(tmp_path)
    _rc, data, rows = run(tmp_path, "--strict")
    assert data["red"] == 0
    write(tmp_path, "src/qfoc_x.c", "int qfoc_x_step(void) { return 1; }\n")
    rc, data, rows = run(tmp_path, "--strict")
    assert rc == 1
    for key in ("wp", "cbmc", "eva", "misra", "statement", "branch", "bench"):
        assert rows[key]["status"] == "FAIL" and "; STALE: " in rows[key]["figure"], rows[key]
    assert rows["wp"]["figure"].startswith("13/13 goals")
    assert "src/qfoc_x.c" in rows["wp"]["figure"]
    reqs = {r["id"]: r for r in data["sections"]["trace"]["requirements"]}
    assert reqs[X1]["verdict"] == "stale"
    assert {p["kind"]: p["status"] for p in reqs[X1]["proof_items"]} == {"WP": "stale", "CBMC": "stale"}
    assert reqs[Y1]["verdict"] == "verified"
    assert rows["requirements"]["figure"] == "1/2 verified; 1 stale"
    page = (tmp_path / "build/evidence/index.html").read_text(encoding="utf-8")
    assert "STALE: <code>proofs/wp/results.md</code>" in page
    assert rows["reviews"]["status"] == "FAIL" and "src/qfoc_x.c" in rows["reviews"]["figure"]
    # the code reviewed and the gates run again: current again
    review(tmp_path)
    stamp(tmp_path)
    _rc, data, rows = run(tmp_path)
    assert data["red"] == 0
    # a committed result without a stamp, all PASS: stale
    write(tmp_path, "proofs/cbmc/results.md", CBMC_RESULTS)
    _rc, data, rows = run(tmp_path)
    assert rows["cbmc"]["status"] == "FAIL"
    assert rows["cbmc"]["figure"] == ("2 harnesses, 150 properties, 0 failed; STALE: no inputs stamp, not tied "
                                      "to the sources it was computed from")
    assert data["sections"]["cbmc"]["stamp"]["state"] == "unstamped"


def test_verdict_needs_every_named_test_passed(tmp_path):
    """REQ-EVD-027, REQ-EVD-003: a test the matrix names but the JUnit files do not hold is
    'not run' (amber, red under --strict), a failed one 'failed'; the requirements row counts
    them and is red; the page shows each test's status.

    Methods: 1b a test named and passed, not run, failed; 1d a named test missing from the JUnit
    files and a failed one
    """
    full_inputs(tmp_path)
    write(tmp_path, "build/junit/test_a.xml", JUNIT_OK.replace('    <testcase classname="test_a" name="test_two"/>\n', ""))
    _rc, data, rows = run(tmp_path)
    reqs = {r["id"]: r for r in data["sections"]["trace"]["requirements"]}
    assert reqs[Y1]["verdict"] == "not run" and reqs[Y1]["test_items"][0]["status"] == "not run"
    assert reqs[X1]["verdict"] == "verified"
    assert rows["requirements"]["status"] == "FAIL" and rows["requirements"]["figure"] == "1/2 verified; 1 not run"
    page = (tmp_path / "build/evidence/index.html").read_text(encoding="utf-8")
    assert "<td class='s notrun'>not run</td>" in page and "<span class=st-nr>not run</span>" in page
    assert run(tmp_path, "--strict")[0] == 1
    page = (tmp_path / "build/evidence/index.html").read_text(encoding="utf-8")
    assert "<td class='s fail'>not run</td>" in page and "red: <code>--strict</code>" in page
    write(tmp_path, "build/junit/test_a.xml", JUNIT_OK.replace(
        '<testcase classname="test_a" name="test_one"/>',
        '<testcase classname="test_a" name="test_one"><failure message="f">no</failure></testcase>'))
    _rc, data, rows = run(tmp_path)
    reqs = {r["id"]: r for r in data["sections"]["trace"]["requirements"]}
    assert reqs[X1]["verdict"] == "failed" and reqs[Y1]["verdict"] == "verified"
    assert rows["requirements"]["figure"] == "1/2 verified; 1 failed"


def test_archive_holds_what_was_verified_with_manifest(tmp_path):
    """REQ-EVD-029, REQ-EVD-001: artefacts/ holds the requirements, the contracts, the sources,
    the ACSL files, the specs' work products, the tests (C and Python), the proofs and the MISRA
    records; MANIFEST.sha256 lists every other file of the bundle with its SHA-256; every
    relative link of the page resolves to a file of the bundle; a requirement links its file.

    Methods: 1a the archive's content, MANIFEST.sha256 of every other file with its SHA-256,
    every relative link resolving
    """
    full_inputs(tmp_path)
    sources = {"specs/requirements/x.md": f"### {X1} Step\nStatement: steps.\n",
               "include/qfoc/x.h": "int qfoc_x_step(void);\n", "src/qfoc_x.c": "int qfoc_x_step(void) { return 0; }\n",
               "specs/x.acsl": "/*@ predicate P = \\true; */\n", "specs/architecture.md": "# Architecture\n",
               "specs/tool-confidence.md": "# Tools\n", "tests/test_a.c": "/* tests */\n",
               "tools/tune/tests/test_t.py": "def test_t():\n    pass\n",
               "proofs/cbmc/x_step/harness.c": "void harness(void) {}\n", "proofs/wp/q15_unit.c": "\n",
               "misra/reviews.md": "# Reviews\n"}
    for rel, text in sources.items():
        write(tmp_path, rel, text)
    stamp(tmp_path)
    _rc, data, _rows = run(tmp_path)
    out = tmp_path / "build" / "evidence"
    for rel in list(sources) + ["specs/safety-manual.md", "misra/deviations.md", "proofs/wp/results.md",
                                "proofs/wp/inputs-wp.sha256", "build/eva/inputs-eva.sha256"]:
        assert (out / "artefacts" / rel).read_bytes() == (tmp_path / rel).read_bytes(), rel
    listed = {}
    for line in (out / "MANIFEST.sha256").read_text(encoding="utf-8").splitlines():
        h, rel = line.split("  ", 1)
        listed[rel] = h
    on_disk = sorted(str(p.relative_to(out)).replace(os.sep, "/") for p in out.rglob("*") if p.is_file())
    assert sorted(listed) == [p for p in on_disk if p != "MANIFEST.sha256"]
    for rel, h in listed.items():
        assert ev.sha256_file(str(out / rel)) == h, rel
    page = (out / "index.html").read_text(encoding="utf-8")
    hrefs = __import__("re").findall(r'href="([^"#][^"]*)"', page)
    assert 'href="MANIFEST.sha256"' in page and 'href="artefacts/specs/requirements/x.md"' in page
    for href in hrefs:
        assert (out / __import__("html").unescape(href)).is_file(), href
    assert data["sections"]["archive"]["count"] >= len(sources)


def test_dates_are_those_of_the_runs(tmp_path):
    """REQ-EVD-001, REQ-EVD-028: the date shown for a result is the run's, from its stamp or
    its JUnit timestamp, not the file's modification time.

    Methods: 1d a file whose modification time is not its run's; 1a the date from the stamp or
    the JUnit timestamp
    """
    full_inputs(tmp_path)
    stamp(tmp_path, now=1_000_000_000)
    write(tmp_path, "build/junit/test_a.xml", JUNIT_OK.replace(
        '<testsuite name="test_a"', '<testsuite timestamp="2002-02-02T02:02:02Z" name="test_a"'))
    _rc, data, _rows = run(tmp_path)
    page = (tmp_path / "build/evidence/index.html").read_text(encoding="utf-8")
    assert "proofs/wp/results.md</a> <span class=meta>(run 2001-09-09 01:46:40 UTC)</span>" in page
    assert "(run 2002-02-02 02:02:02 UTC)" in page
    assert data["sections"]["wp"]["stamp"]["run"] == "2001-09-09 01:46:40 UTC"


def test_fmea_row_follows_the_verdicts_of_its_requirements(tmp_path):
    """REQ-EVD-031, REQ-EVD-027: an FMEA row is green only when it is current and every
    requirement it names is verified: a failed test of one of them makes the row (and the
    FMEA summary row) red 'failed', a test that did not run 'not run'; the page shows each
    requirement's verdict beside the row.
    Methods: 1b requirement verdicts passed, failed and not run; 1d a failed test behind a row."""
    full_inputs(tmp_path)
    _rc, data, rows = run(tmp_path, "--strict")
    assert rows["fmea"]["status"] == "PASS"
    assert rows["fmea"]["figure"] == ("2 rows, every one tied to the files it reviewed; every requirement "
                                      "they name verified")
    fm = {r["id"]: r for r in data["sections"]["fmea"]["rows"]}
    assert fm["F-02"]["req_verdicts"] == [{"id": X1, "verdict": "verified", "link": fm["F-02"]["req_verdicts"][0]["link"]},
                                         {"id": Y1, "verdict": "verified", "link": None}]
    write(tmp_path, "build/junit/test_a.xml", JUNIT_OK.replace(
        '<testcase classname="test_a" name="test_two"/>',
        '<testcase classname="test_a" name="test_two"><failure message="f">x</failure></testcase>'))
    rc, data, rows = run(tmp_path, "--strict")
    assert rc == 1 and rows["fmea"]["status"] == "FAIL"
    assert rows["fmea"]["figure"].endswith("; 1 with a requirement not verified (F-02 failed)")
    fm = {r["id"]: r for r in data["sections"]["fmea"]["rows"]}
    assert fm["F-01"]["ok"] and not fm["F-02"]["ok"] and fm["F-02"]["verdict"] == "failed"
    os.remove(tmp_path / "build/junit/test_a.xml")
    _rc, data, rows = run(tmp_path)
    assert rows["fmea"]["status"] == "FAIL"
    assert "2 with a requirement not verified (F-01 not run, F-02 not run)" in rows["fmea"]["figure"]
    page = (tmp_path / "build/evidence/index.html").read_text(encoding="utf-8")
    assert "14 Software FMEA" in page and "<span class=st-nr>not run</span>" in page
    os.remove(tmp_path / "build/trace/trace.json")
    _rc, data, rows = run(tmp_path)
    assert rows["fmea"]["status"] == "FAIL" and rows["fmea"]["figure"].endswith(
        "(no traceability matrix: build/trace/trace.json)")


def test_review_records_stale_or_unstamped_are_red(tmp_path):
    """REQ-EVD-031: a MISRA review record whose files changed since its review is stale: the
    review records row is red with STALE and the changed file named, and the section shows the
    record red; a record without its digest is red 'unstamped'.
    Methods: 1d a review record whose file changed, a record without its digest."""
    full_inputs(tmp_path)
    _rc, data, rows = run(tmp_path)
    assert rows["reviews"]["status"] == "PASS"
    assert rows["reviews"]["figure"] == "1 record, every one tied to the files it reviewed"
    write(tmp_path, "src/qfoc_y.c", "int qfoc_y;\n")
    rc, data, rows = run(tmp_path, "--strict")
    assert rc == 1 and rows["reviews"]["status"] == "FAIL"
    assert rows["reviews"]["figure"].startswith("1 record: 0 current, 1 stale (Rule 17.2); STALE: Rule 17.2: ")
    assert "1 file new since the review: src/qfoc_y.c" in rows["reviews"]["figure"]
    page = (tmp_path / "build/evidence/index.html").read_text(encoding="utf-8")
    assert "Review records (misra/reviews.md)" in page and "<span class=st-bad>STALE</span>" in page
    os.remove(tmp_path / "src/qfoc_y.c")
    text = (tmp_path / "misra/reviews.md").read_text(encoding="utf-8")
    write(tmp_path, "misra/reviews.md", "\n".join(ln for ln in text.splitlines() if not ln.startswith("- Files:")))
    _rc, data, rows = run(tmp_path)
    assert rows["reviews"]["status"] == "FAIL" and "1 unstamped (Rule 17.2)" in rows["reviews"]["figure"]
    os.remove(tmp_path / "misra/reviews.md")
    _rc, data, rows = run(tmp_path)
    assert rows["reviews"]["figure"] == "not run"
