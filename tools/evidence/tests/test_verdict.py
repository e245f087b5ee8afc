"""Tests of tools/evidence/verdict.py: the verdict of a requirement from the results of the
run (run: python3 -m pytest tools/evidence/tests).

Each test makes up a matrix record (as tools/evidence/trace.py writes it) and the results
(JUnit files in a temporary directory, WP and CBMC rows with the state of their inputs stamp,
bench rows, scenarios) and checks the statuses and the verdict.  The requirements are those of
specs/requirements/evidence.md.
"""
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent.parent  # tools/evidence
sys.path.insert(0, str(HERE))

import verdict as vd  # noqa: E402

# Requirement IDs of the made-up records, written so that the trace gate does not read them
# as IDs named by this file.
X1, X2 = "REQ-" + "X-001", "REQ-" + "X-002"

JUNIT = """<?xml version="1.0" encoding="UTF-8"?>
<testsuites>
  <testsuite name="test_x" tests="3" failures="1" errors="0" skipped="1">
    <testcase classname="test_x" name="test_x_ok"/>
    <testcase classname="test_x" name="test_x_bad"><failure message="failed">1 != 2</failure></testcase>
    <testcase classname="test_x" name="test_x_skipped"><skipped/></testcase>
  </testsuite>
</testsuites>
"""

JUNIT_PYTEST = """<?xml version="1.0" encoding="utf-8"?>
<testsuites><testsuite name="pytest" tests="3" failures="0" errors="0" skipped="0">
  <testcase classname="tools.tune.tests.test_t" name="test_p[a]"/>
  <testcase classname="tools.tune.tests.test_t" name="test_p[b]"/>
  <testcase classname="tools.tune.tests.test_t.TestK" name="test_m"/>
</testsuite></testsuites>
"""

JUNIT_TARGET = """<?xml version="1.0" encoding="UTF-8"?>
<testsuites><testsuite name="target_equivalence" tests="1" failures="0" errors="0">
  <testcase classname="target_equivalence" name="sincos"/>
</testsuite></testsuites>
"""

JUNIT_CHECKS = """<?xml version="1.0" encoding="UTF-8"?>
<testsuites><testsuite name="target_checks" tests="1" failures="0" errors="0">
  <testcase classname="target_checks" name="target_test.sh"/>
</testsuite></testsuites>
"""

WP_ROWS = [{"unit": "qfoc_x", "function": "qfoc_x_step", "goals": 10, "proved": 10},
           {"unit": "qfoc_x", "function": "x_helper", "goals": 4, "proved": 4},
           {"unit": "qfoc_x", "function": "qfoc_x_init", "goals": 5, "proved": 4},
           {"unit": "lemmas_unit", "function": "lemmas", "goals": 3, "proved": 3}]
CBMC_ROWS = [{"harness": "x_step", "result": "PASS", "properties": 50, "failed": 0},
             {"harness": "x_init", "result": "FAIL", "properties": 20, "failed": 1}]
BENCH_ROWS = [{"item": "`qfoc_x_step`, loop A", "max": 100, "limit": 200, "result": "OK",
               "requirement": X1},
              {"item": "`qfoc_x_step`, loop B", "max": 150, "limit": 200, "result": "OK",
               "requirement": X1},
              {"item": "RAM", "max": 900, "limit": 512, "result": "OVER", "requirement": X2}]


def results(tmp_path, wp_state="current", cbmc_state="current", bench_state="current"):
    """Results of a run: every JUnit file above, WP, CBMC and bench rows, two scenarios of
    the demonstration (one failed) and a robustness campaign."""
    paths = []
    for name, text in (("test_x", JUNIT), ("pytest", JUNIT_PYTEST), ("target_equivalence", JUNIT_TARGET),
                       ("target_checks", JUNIT_CHECKS)):
        p = tmp_path / f"{name}.xml"
        p.write_text(text, encoding="utf-8")
        paths.append(str(p))
    return {"junit": vd.junit_cases(paths),
            "wp": {"state": wp_state, "rows": WP_ROWS},
            "cbmc": {"state": cbmc_state, "rows": CBMC_ROWS},
            "bench": {"state": bench_state, "rows": BENCH_ROWS},
            "demo": {"cold_start": True, "fault_oc": False},
            "robustness": {"count": 24, "successes": 24}}


def rec(**kw):
    base = {"id": X1, "wp": {"functions": [], "helpers": []}, "cbmc": [], "tests": [], "scenarios": []}
    base.update(kw)
    return base


def test_verified_when_every_proof_proved_and_every_test_passed(tmp_path):
    """REQ-EVD-027: every kind of test (CMocka, parametrised pytest and a method, target group
    and checking program, bench rows named from the run, a scenario, the robustness campaign)
    passed and every proof (WP function, its static helper, lemma, CBMC harness) proved:
    verified.

    Methods: 1b every kind of test (CMocka, parametrised pytest and a method, target group and
    checking program, bench rows, a scenario, the campaign) and every kind of proof (WP
    function, static helper, lemma, CBMC harness)
    """
    r = rec(wp={"functions": [{"unit": "qfoc_x", "function": "qfoc_x_step", "goals": 10, "proved": 10},
                              {"unit": "lemmas_unit", "function": "lemma L", "goals": 1, "proved": 1}],
                "helpers": [{"unit": "qfoc_x", "function": "x_helper", "goals": 4, "proved": 4,
                             "via": ["qfoc_x_step"]}]},
            cbmc=[{"harness": "x_step", "file": "proofs/cbmc/x_step/harness.c"}],
            tests=[{"kind": "cmocka", "file": "tests/test_x.c", "name": "test_x_ok"},
                   {"kind": "pytest", "file": "tools/tune/tests/test_t.py", "name": "test_p"},
                   {"kind": "pytest", "file": "tools/tune/tests/test_t.py", "name": "test_m"},
                   {"kind": "target", "file": "tools/target_test/tt_groups.c", "name": "group sincos"},
                   {"kind": "target", "file": "tools/target_test/target_test.sh", "name": "target_test.sh"},
                   {"kind": "bench", "file": "build/bench/bench.json", "name": "row `qfoc_x_step`, loop A"}],
            scenarios=[{"name": "cold_start"}, {"name": "scn_run_start"}])
    v = vd.requirement_verdict(X1, r, results(tmp_path))
    assert v["verdict"] == vd.VERIFIED, v
    assert [p["status"] for p in v["proofs"]] == ["proved"] * 4
    assert [p["kind"] for p in v["proofs"]] == ["WP", "WP", "WP helper", "CBMC"]
    assert [t["status"] for t in v["tests"]] == ["passed"] * 6
    assert [s["status"] for s in v["scenarios"]] == ["passed", "passed"]


def test_test_not_run_is_not_run_never_verified(tmp_path):
    """REQ-EVD-027: a test that names the requirement but is in no result (or was skipped),
    a target group or bench of a run that did not happen: 'not run', and the verdict is
    'not run', although every proof holds.

    Methods: 1b a test in no result, a skipped one, a target group and a bench of a run that did
    not happen; 1d tests that did not run while every proof holds
    """
    res = results(tmp_path)
    for t in ({"kind": "cmocka", "file": "tests/test_x.c", "name": "test_x_missing"},
              {"kind": "cmocka", "file": "tests/test_x.c", "name": "test_x_skipped"},
              {"kind": "cmocka", "file": "tests/test_other.c", "name": "test_x_ok"},
              {"kind": "target", "file": "tools/target_test/tt_groups.c", "name": "group park"},
              {"kind": "pytest", "file": "tools/evidence/tests/test_e.py", "name": "test_p"}):
        v = vd.requirement_verdict(X1, rec(cbmc=["x_step"], tests=[t]), res)
        assert v["tests"][0]["status"] == vd.NOT_RUN, t
        assert v["verdict"] == vd.NOT_RUN, t
    # no bench run at all, no demonstration
    res["bench"], res["demo"] = None, None
    v = vd.requirement_verdict(X1, rec(tests=[{"kind": "bench", "file": "tools/bench/count.py",
                                               "name": "row `qfoc_x_step`, [title]"}],
                                       scenarios=[{"name": "cold_start"}]), res)
    assert [t["status"] for t in v["tests"] + v["scenarios"]] == [vd.NOT_RUN, vd.NOT_RUN]
    assert v["verdict"] == vd.NOT_RUN


def test_failed_test_or_proof_is_failed(tmp_path):
    """REQ-EVD-027: a failed CMocka test, a scenario whose targets are not met, a bench row
    over its limit, a WP function with a goal not proved or a failing CBMC harness make the
    verdict 'failed', which wins over 'not run'.

    Methods: 1b each kind of failure alone and together with a test not run; 1d a failed test,
    unmet scenario targets, a bench row over its limit, a goal not proved, a failing harness
    """
    res = results(tmp_path)
    cases = [rec(tests=[{"kind": "cmocka", "file": "tests/test_x.c", "name": "test_x_bad"},
                        {"kind": "cmocka", "file": "tests/test_x.c", "name": "test_x_missing"}]),
             rec(scenarios=[{"name": "fault_oc"}]),
             rec(tests=[{"kind": "bench", "file": "tools/bench/count.py", "name": "row RAM"}]),
             rec(wp={"functions": [{"unit": "qfoc_x", "function": "qfoc_x_init"}], "helpers": []}),
             rec(cbmc=[{"harness": "x_init"}])]
    for i, r in enumerate(cases):
        rid = X2 if i == 2 else X1
        v = vd.requirement_verdict(rid, r, res)
        assert v["verdict"] == vd.FAILED, (i, v)
    v = vd.requirement_verdict(X1, cases[0], res)
    assert [t["status"] for t in v["tests"]] == [vd.FAILED, vd.NOT_RUN]
    v = vd.requirement_verdict(X1, cases[3], res)
    assert v["proofs"][0]["detail"] == "4/5 goals"


def test_stale_results_are_stale_not_proved(tmp_path):
    """REQ-EVD-027, REQ-EVD-028: WP or CBMC rows that all hold, but from results whose inputs
    stamp is not current (inputs changed, or no stamp at all), are 'stale', and so is the
    verdict; bench rows of a stale bench result too.  A failure still wins.

    Methods: 1b inputs changed, no stamp at all, a stale bench, a failure beside them; 1d
    results whose inputs stamp is not current
    """
    r = rec(wp={"functions": [{"unit": "qfoc_x", "function": "qfoc_x_step"}], "helpers": []},
            cbmc=[{"harness": "x_step"}], tests=[{"kind": "cmocka", "file": "tests/test_x.c", "name": "test_x_ok"}])
    for wp_state, cbmc_state in (("stale", "current"), ("current", "unstamped"), ("stale", "stale")):
        v = vd.requirement_verdict(X1, r, results(tmp_path, wp_state=wp_state, cbmc_state=cbmc_state))
        assert v["verdict"] == vd.STALE, (wp_state, cbmc_state)
        assert {p["kind"]: p["status"] for p in v["proofs"]} == {
            "WP": vd.STALE if wp_state != "current" else vd.PROVED,
            "CBMC": vd.STALE if cbmc_state != "current" else vd.PROVED}
    v = vd.requirement_verdict(X1, rec(tests=[{"kind": "bench", "file": "build/bench/bench.json",
                                               "name": "row `qfoc_x_step`, loop A"}]),
                               results(tmp_path, bench_state="stale"))
    assert v["tests"][0]["status"] == vd.STALE and v["verdict"] == vd.STALE
    bad = dict(r, tests=[{"kind": "cmocka", "file": "tests/test_x.c", "name": "test_x_bad"}])
    assert vd.requirement_verdict(X1, bad, results(tmp_path, wp_state="stale"))["verdict"] == vd.FAILED


def test_no_result_and_no_evidence(tmp_path):
    """REQ-EVD-027: a function or harness without a row, or no WP result at all, is 'no
    result' (verdict 'not run'); a requirement that names nothing has 'no evidence'.

    Methods: 1d a function or harness without a row, no WP result at all, a requirement that
    names nothing
    """
    res = results(tmp_path)
    v = vd.requirement_verdict(X1, rec(wp={"functions": [{"unit": "qfoc_x", "function": "qfoc_x_gone"}]},
                                       cbmc=["x_gone"]), res)
    assert [p["status"] for p in v["proofs"]] == [vd.NO_RESULT, vd.NO_RESULT]
    assert v["verdict"] == vd.NOT_RUN
    res["wp"] = {"state": "absent", "rows": []}
    v = vd.requirement_verdict(X1, rec(wp={"functions": [{"unit": "qfoc_x", "function": "qfoc_x_step"}]}), res)
    assert v["proofs"][0]["status"] == vd.NO_RESULT
    assert vd.requirement_verdict(X1, rec(), res)["verdict"] == vd.NO_EVIDENCE


def test_bench_rows_named_from_the_source(tmp_path):
    """REQ-EVD-027: a bench row the matrix named from tools/bench/count.py (the bench had not
    run when the matrix was made) takes the rows of the run that name the requirement.

    Methods: 1a a bench row named from tools/bench/count.py takes the run's rows that name the
    requirement
    """
    res = results(tmp_path)
    t = {"kind": "bench", "file": "tools/bench/count.py", "name": "row `qfoc_x_step`, [title]"}
    assert vd.requirement_verdict(X1, rec(tests=[t]), res)["verdict"] == vd.VERIFIED
    assert vd.requirement_verdict(X2, rec(id=X2, tests=[t]), res)["verdict"] == vd.FAILED


def test_bench_rows_static_bound(tmp_path):
    """REQ-EVD-027: a bench row with a static bound (REQ-BENCH-008): a reported row without a
    limit passes when it carries a measured max or a static bound and is not run when it has
    neither; a measured count above its bound (UNSOUND) fails.

    Methods: 1b a row with a static bound only, with neither figure, and an UNSOUND row
    """
    assert vd.bench_row_status({"item": "load", "max": None, "static": 69.8, "limit": None,
                                "result": "-"}) == vd.PASSED
    assert vd.bench_row_status({"item": "load", "max": None, "static": None, "limit": None,
                                "result": "-"}) == vd.NOT_RUN
    assert vd.bench_row_status({"item": "f", "max": 50, "static": 47, "limit": 60,
                                "result": "UNSOUND"}) == vd.FAILED
    assert vd.bench_row_status({"item": "f", "max": 50, "static": 47, "limit": None,
                                "result": "UNSOUND"}) == vd.FAILED


def test_loose_records_and_counts(tmp_path):
    """REQ-EVD-027: records in the loose forms of a hand-written matrix (function and harness
    names as strings, tests as 'file: name') are read; the count line of the matrix cell.

    Methods: 1b the loose forms of a hand-written matrix (names as strings, tests as 'file:
    name') beside the full records
    """
    res = results(tmp_path)
    v = vd.requirement_verdict(X1, {"wp": {"functions": ["qfoc_x_step"], "goals": 10, "proved": 10},
                                    "cbmc": ["x_step"], "tests": ["test_x.c: test_x_ok", "test_nowhere"]}, res)
    assert [x["status"] for x in v["proofs"] + v["tests"]] == [vd.PROVED, vd.PROVED, vd.PASSED, vd.NOT_RUN]
    assert vd.counts(v["proofs"] + v["tests"]) == "2 proved, 1 passed, 1 not run"
