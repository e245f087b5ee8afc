"""Tests of tools/validation/run.py (run: python3 -m pytest tools/validation/tests).

No gate runs here: the catalogue is parsed from made-up TOML, the substitution is applied
to made-up text and to a made-up repository in a temporary directory, and the verdicts are
taken from gate outputs written here in the form the gate scripts print them.  One test
reads the committed catalogue and checks its substitutions against the working tree (text
only).  The requirement is REQ-EVD-030 (specs/requirements/evidence.md).
"""
import os
import sys
import tomllib
from pathlib import Path

import pytest

HERE = Path(__file__).resolve().parent.parent  # tools/validation
sys.path.insert(0, str(HERE))

import run as tv  # noqa: E402

CATALOGUE = """
[scope.ramp]
wp = ["src/qfoc_ramp.c"]
cbmc = ["ramp_toward"]
tests = ["test_ramp"]
cover = "src/qfoc_ramp.c"

[scope.lib]

[[defect]]
id = "TV-01"
class = "overflow"
title = "t"
why = "w"
file = "src/x.c"
scope = "ramp"
gates = ["wp", "cbmc", "tests", "coverage"]
old = '''a = b;'''
new = '''a = c;'''

[[defect]]
id = "TV-02"
class = "MISRA violation"
title = "t"
why = "w"
file = "src/y.c"
scope = "lib"
gates = ["misra", "eva"]
old = '''x'''
new = ''
"""


def parsed(text=CATALOGUE):
    return tv.parse_catalogue(tomllib.loads(text))


def step(label, rc, output):
    return {"label": label, "rc": rc, "output": output}


# REQ-EVD-030
# Methods: 1a the made-up catalogue's scopes and defects read back field by field
def test_catalogue_parses():
    scopes, defects = parsed()
    assert [d["id"] for d in defects] == ["TV-01", "TV-02"]
    assert scopes["ramp"]["cbmc"] == ["ramp_toward"]
    assert defects[1]["new"] == "" and defects[0]["gates"] == ["wp", "cbmc", "tests", "coverage"]


# REQ-EVD-030
# Methods: 1b thirteen catalogue errors, one rule broken per parameter; 1d a duplicate or
# malformed id, unknown or repeated gates, an unknown scope, a gate without what it needs, 'new'
# equal to 'old', a missing class, a cover file outside src/, an unknown key, a time-out that is
# not a number
@pytest.mark.parametrize("change, message", [
    (('id = "TV-02"', 'id = "TV-01"'), "used twice"),
    (('id = "TV-02"', 'id = "T2"'), "TV-nn"),
    (('gates = ["misra", "eva"]', 'gates = ["misra", "lint"]'), "unknown gate 'lint'"),
    (('gates = ["misra", "eva"]', 'gates = []'), "'gates' must list"),
    (('gates = ["misra", "eva"]', 'gates = ["misra", "misra"]'), "listed twice"),
    (('scope = "lib"', 'scope = "nowhere"'), "unknown scope 'nowhere'"),
    (('gates = ["misra", "eva"]', 'gates = ["wp"]'), "gate wp needs 'wp' in scope lib"),
    (('gates = ["misra", "eva"]', 'gates = ["coverage"]'), "gate coverage needs 'cover'"),
    (("new = '''a = c;'''", "new = '''a = b;'''"), "'new' equals 'old'"),
    (("class = \"overflow\"\n", ""), "'class' is missing"),
    (('cover = "src/qfoc_ramp.c"', 'cover = "tests/test_ramp.c"'), "'cover' must be a src/*.c file"),
    (('[scope.lib]', '[scope.lib]\nunits = ["a"]'), "unknown key 'units'"),
    (('[scope.lib]', '[scope.lib]\nwp_timeout = 0'), "'wp_timeout' must be a number of seconds"),
])
def test_catalogue_errors(change, message):
    old, new = change
    assert old in CATALOGUE
    with pytest.raises(tv.CatalogueError, match=message.replace("(", r"\(").replace("*", r"\*")):
        parsed(CATALOGUE.replace(old, new, 1))


# REQ-EVD-030
# Methods: 1c the old text occurring 0, 1 and 2 times; 1d an empty old text
def test_substitution_exactly_once():
    assert tv.substitute("int a;\nx = 1;\n", "x = 1;", "x = 2;") == "int a;\nx = 2;\n"
    with pytest.raises(tv.CatalogueError, match="occurs 0 times"):
        tv.substitute("x = 1;\n", "x = 3;", "x = 2;", "TV-09 (src/x.c)")
    with pytest.raises(tv.CatalogueError, match="occurs 2 times"):
        tv.substitute("x = 1;\nx = 1;\n", "x = 1;", "x = 2;")
    with pytest.raises(tv.CatalogueError, match="empty"):
        tv.substitute("x", "", "y")


# REQ-EVD-030
def test_check_sources_and_copy(tmp_path, monkeypatch):
    """The catalogue fails loudly when the text moved; the copy carries the defect, the
    original file does not change.

    Methods: 1d text moved in the source (the substitution occurs twice), scope files missing
    from the tree; 1a the copy carries the defect and the original stays unchanged
    """
    (tmp_path / "src").mkdir()
    (tmp_path / "src" / "x.c").write_text("int f(void)\n{\n    a = b;\n}\n", encoding="utf-8")
    (tmp_path / "src" / "y.c").write_text("x\n", encoding="utf-8")
    (tmp_path / "Makefile").write_text("all:\n", encoding="utf-8")
    scopes, defects = parsed()
    with pytest.raises(tv.CatalogueError) as err:
        tv.check_sources(str(tmp_path), scopes, defects)
    # the scope's files do not exist in the made-up tree; the substitutions do match
    assert "WP unit src/qfoc_ramp.c not found" in str(err.value)
    assert "occurs" not in str(err.value)
    (tmp_path / "src" / "x.c").write_text("a = b;\na = b;\n", encoding="utf-8")
    with pytest.raises(tv.CatalogueError, match=r"TV-01 \(src/x.c\): the old text occurs 2 times"):
        tv.check_sources(str(tmp_path), scopes, defects)
    (tmp_path / "src" / "x.c").write_text("a = b;\n", encoding="utf-8")
    monkeypatch.setattr(tv, "ROOT", str(tmp_path))
    dst = tmp_path / "copy"
    tv.copy_tree(str(dst), defects[0])
    assert (dst / "src" / "x.c").read_text(encoding="utf-8") == "a = c;\n"
    assert (dst / "Makefile").exists()
    assert (tmp_path / "src" / "x.c").read_text(encoding="utf-8") == "a = b;\n"
    tv.copy_tree(str(dst), None)
    assert (dst / "src" / "x.c").read_text(encoding="utf-8") == "a = b;\n"


# REQ-EVD-030
def test_committed_catalogue_matches_the_tree():
    """The committed catalogue: every substitution matches its file exactly once, every
    scope names files that exist, every gate catches at least one defect, at least 8
    defects (text checks only: no gate runs).

    Methods: 1a the committed catalogue: every substitution matches its file exactly once, every
    scope's files exist, every gate catches at least one defect, at least 8 defects
    """
    scopes, defects = tv.load_catalogue(tv.CATALOGUE)
    tv.check_sources(tv.ROOT, scopes, defects)
    assert len(defects) >= 8
    for g in tv.GATES:
        assert any(g in d["gates"] for d in defects), g


# REQ-EVD-030
# Methods: 1b a clean run, goals not proved, and three kinds of error; 1d a unit that did not
# run cleanly, Frama-C that cannot parse, 0 / 0 goals, no exit status: errors, not catches
def test_classify_wp():
    ok = "prove: Frama-C WP ...\n  qfoc_ramp: 31 / 31 (7 s, z3,cvc4, frama-c exit 0)\nproved 31 / 31 goals\n"
    assert tv.classify("wp", [step("prove", 0, ok)]) == ("pass", "proved 31 / 31 goals")
    bad = ("prove: qfoc_ramp: qfoc_ramp_toward: 7 goal(s) not proved\nproved 22 / 29 goals\n"
           "[wp] [Failed] Goal typed_qfoc_ramp_toward_ensures_range : Unknown\n")
    verdict, detail = tv.classify("wp", [step("prove", 1, bad)])
    assert verdict == "fail" and detail.startswith("proved 22 / 29 goals; prove: qfoc_ramp")
    # every goal proved but a unit did not run cleanly: not a catch
    assert tv.classify("wp", [step("prove", 1, "proved 31 / 31 goals\n")])[0] == "error"
    assert tv.classify("wp", [step("prove", 2, "Frama-C cannot parse it\n")])[0] == "error"
    assert tv.classify("wp", [step("prove", 0, "proved 0 / 0 goals\n")])[0] == "error"
    assert tv.classify("wp", [step("prove", None, "")])[0] == "error"


# REQ-EVD-030
# Methods: 1b a pass, failed properties, a harness that did not build, a failed SAT self-test;
# 1d a build failure and a broken SAT back end: errors, not catches
def test_classify_cbmc():
    head = "cbmc: self-test of the SAT back end: the planted overflow found, 3 properties hold\n"
    ok = head + "  ramp_toward: PASS (23 properties hold, 0 fail, unwind 1, 3 s)\n"
    assert tv.classify("cbmc", [step("cbmc", 0, ok)])[0] == "pass"
    bad = head + ("  ramp_toward: FAIL (16 properties hold, 7 fail, unwind 1, 3 s)\n"
                  "[main.assertion.1] line 34 result in the symmetric Q15 range: FAILURE\n")
    verdict, detail = tv.classify("cbmc", [step("cbmc", 1, bad)])
    assert verdict == "fail" and detail.startswith("ramp_toward: 7 of 23 properties fail")
    # a harness that did not build: FAIL with no failed property is not a catch
    assert tv.classify("cbmc", [step("cbmc", 1, head + "  x: FAIL (0 properties hold, 0 fail, unwind 1, 0 s)\n")])[0] \
        == "error"
    assert tv.classify("cbmc", [step("cbmc", 1, "cbmc: self-test of the SAT back end FAILED (x)\n")])[0] == "error"


# REQ-EVD-030
# Methods: 1b a pass, failed tests, a crash, a -Werror stop, a syntax error, a run without
# summary; 1d a crash and a build stopped by -Werror (catches), a syntax error and no summary
# (errors)
def test_classify_tests():
    built = step("build", 0, "")
    ok = step("run", 0, "[  PASSED  ] 3 test(s).\ntests: 1 executables\n3 passed, 0 failed\n")
    assert tv.classify("tests", [built, ok]) == ("pass", "3 passed, 0 failed")
    bad = step("run", 1, "[  FAILED  ] test_ramp_corners\ntests: 1 executables\n1 passed, 2 failed\n")
    verdict, detail = tv.classify("tests", [built, bad])
    assert verdict == "fail" and "1 passed, 2 failed" in detail and "test_ramp_corners" in detail
    crash = step("run", 1, "test: build/host/tests/test_trig exited with status 136\n12 passed, 1 failed\n")
    assert tv.classify("tests", [built, crash])[0] == "fail"
    werror = step("build", 2, "src/qfoc_ramp.c:31:12: error: 'r' may be used uninitialized "
                              "[-Werror=maybe-uninitialized]\n")
    verdict, detail = tv.classify("tests", [werror])
    assert verdict == "fail" and detail.startswith("build stopped by -Werror")
    syntax = step("build", 2, "src/qfoc_ramp.c:3:1: error: expected ';' before '}' token\n")
    assert tv.classify("tests", [syntax])[0] == "error"
    assert tv.classify("tests", [built, step("run", 1, "no summary\n")])[0] == "error"


# REQ-EVD-030
# Methods: 1b full coverage, a gap, a test failing under coverage, a build error; 1d a test that
# fails under coverage is no coverage finding
def test_classify_coverage():
    built = step("build", 0, "")
    ok = step("coverage", 0, "lines: 100.0% (11 out of 11)\nfunctions: 100.0% (1 out of 1)\n"
                             "branches: 100.0% (4 out of 4)\ncoverage: report build/coverage/index.html\n")
    assert tv.classify("coverage", [built, ok])[0] == "pass"
    gap = step("coverage", 1, "lines: 92.3% (12 out of 13)\nbranches: 83.3% (5 out of 6)\n"
                              "coverage: below 100 % (gcovr exit 6); uncovered:\n"
                              "src/qfoc_ramp.c                                6       5    83%   23\n")
    verdict, detail = tv.classify("coverage", [built, gap])
    assert verdict == "fail" and detail.startswith("lines: 92.3% (12 out of 13); branches: 83.3%")
    # a test that fails under coverage is not a coverage finding
    assert tv.classify("coverage", [built, step("coverage", 1, "coverage: test_ramp failed\n")])[0] == "error"
    assert tv.classify("coverage", [step("build", 2, "make: *** error\n")])[0] == "error"


# REQ-EVD-030
# Methods: 1b a clean run, a finding, a suppression without a record, a tool error, for MISRA,
# and clean, alarm and error for EVA; 1d cppcheck failing, Frama-C stopping without an alarm
def test_classify_misra_and_eva():
    ok = "misra: 0 unrecorded findings, 35 suppressions (35 with deviation records)\n"
    assert tv.classify("misra", [step("misra", 0, ok)])[0] == "pass"
    finding = ("src/qfoc_ramp.c:26: misra-c2012-15.6: Bodies ...\n"
               "misra: 1 unrecorded findings, 35 suppressions (35 with deviation records)\n")
    verdict, detail = tv.classify("misra", [step("misra", 1, finding)])
    assert verdict == "fail" and "misra-c2012-15.6" in detail
    gap = ("src/qfoc_fw.c:75: suppression of Rule 8.7 without a matching deviation record in misra/deviations.md\n"
           "misra: 0 unrecorded findings, 35 suppressions (34 with deviation records)\n")
    verdict, detail = tv.classify("misra", [step("misra", 1, gap)])
    assert verdict == "fail" and "1 suppressions without a matching record" in detail
    assert tv.classify("misra", [step("misra", 1, "cppcheck: error\n")])[0] == "error"
    assert tv.classify("eva", [step("eva", 0, "eva: 0 runtime-error alarms (limit 0), 555 ACSL ...\n")])[0] \
        == "pass"
    alarm = ("eva: 2 runtime-error alarms (limit 0), 555 ACSL properties\n"
             "ALARM src/qfoc_ramp.c:31: accessing uninitialized left-value. assert \\initialized(&r);\n")
    verdict, detail = tv.classify("eva", [step("eva", 1, alarm)])
    assert verdict == "fail" and "src/qfoc_ramp.c:31" in detail
    # Frama-C stopped without an alarm: an error, not a catch
    assert tv.classify("eva", [step("eva", 1, "eva: 0 runtime-error alarms (limit 0)\n")])[0] == "error"


# REQ-EVD-030
# Methods: 1b each outcome of a defect and of the control (caught, MISSED, pass, FALSE ALARM,
# ERROR); 1d a missed catch, a failed control, no control at all
def test_outcomes_and_summary():
    assert tv.outcome("defect", "fail") == "caught" and tv.outcome("defect", "pass") == "MISSED"
    assert tv.outcome("control", "pass") == "pass" and tv.outcome("control", "fail") == "FALSE ALARM"
    assert tv.outcome("defect", "error") == tv.outcome("control", "error") == "ERROR"
    assert tv.job_ok("defect", "fail") and not tv.job_ok("defect", "pass") and not tv.job_ok("defect", "error")
    assert tv.job_ok("control", "pass") and not tv.job_ok("control", "fail")
    _scopes, defects = parsed()

    def res(kind, name, gate, verdict):
        return {"kind": kind, "name": name, "scope": "ramp", "gate": gate, "verdict": verdict,
                "outcome": tv.outcome(kind, verdict), "ok": tv.job_ok(kind, verdict), "detail": "d",
                "seconds": 1.0, "cpu_seconds": 0.5, "log": "x"}
    runs = [res("defect", d["id"], g, "fail") for d in defects for g in d["gates"]]
    control = [res("control", "control", g, "pass") for g in ("wp", "misra")]
    s = tv.summarise(defects, runs + control, 10.0, len(runs) + 2)
    assert s["summary"]["ok"] and s["summary"]["caught"] == s["summary"]["expected_catches"] == 6
    assert s["defects"][0]["gates"]["eva"]["status"] == "not expected"
    assert s["summary"]["catches_per_gate"]["misra"] == 1
    runs[1] = res("defect", "TV-01", "cbmc", "pass")
    s = tv.summarise(defects, runs + control, 10.0, 0)
    assert not s["summary"]["ok"] and s["summary"]["missed"] == 1
    assert s["defects"][0]["gates"]["cbmc"]["status"] == "MISSED" and not s["defects"][0]["ok"]
    runs[1] = res("defect", "TV-01", "cbmc", "fail")
    control[0] = res("control", "control", "wp", "fail")
    s = tv.summarise(defects, runs + control, 10.0, 0)
    assert not s["summary"]["ok"] and not s["summary"]["control_ok"]
    assert not tv.summarise(defects, runs, 10.0, 0)["summary"]["ok"]     # no control at all


# REQ-EVD-030
# Methods: 1a one control job per scope and gate however many defects share them, one directory
# per job
def test_jobs_control_once_per_scope_and_gate(tmp_path):
    scopes, defects = parsed()
    twin = dict(defects[0], id="TV-03")
    jobs = tv.make_jobs(scopes, defects + [twin], str(tmp_path))
    control = sorted((j["scope"], j["gate"]) for j in jobs if j["kind"] == "control")
    assert control == sorted([("ramp", "wp"), ("ramp", "cbmc"), ("ramp", "tests"), ("ramp", "coverage"),
                              ("lib", "misra"), ("lib", "eva")])
    assert len([j for j in jobs if j["kind"] == "defect"]) == 10
    dirs = [j["dir"] for j in jobs]
    assert len(set(dirs)) == len(dirs)
    assert os.path.join(str(tmp_path), "control", "misra") in dirs
    assert os.path.join(str(tmp_path), "TV-01", "wp") in dirs


# REQ-EVD-030
def test_gate_commands_are_scoped():
    """Each gate's command names only the scope's unit, harnesses and tests; WP takes the
    scope's prover time-out, or none (prove.sh's own) when the scope sets none.

    Methods: 1b every gate's command (WP with and without the scope's time-out, CBMC, tests,
    coverage, MISRA); 1a each names only the scope's unit, harnesses and tests
    """
    scopes, _defects = parsed(CATALOGUE.replace("[scope.ramp]\n", "[scope.ramp]\nwp_timeout = 10\n"))
    job = {"scope": "ramp", "gate": "wp"}
    (label, argv, env), = tv.gate_steps(job, scopes, "/x/cbmc")
    assert argv == ["sh", "tools/gates/prove.sh", "src/qfoc_ramp.c"] and env["WP_TIMEOUT"] == "10"
    assert env["WP_JOBS"] == "1"
    scopes["ramp"].pop("wp_timeout")
    assert tv.gate_steps(job, scopes, "/x/cbmc")[0][2]["WP_TIMEOUT"] is None
    (_l, argv, env), = tv.gate_steps(dict(job, gate="cbmc"), scopes, "/x/cbmc")
    assert argv == ["sh", "tools/gates/cbmc.sh", "proofs/cbmc/ramp_toward"] and env["CBMC"] == "/x/cbmc"
    build, runs = tv.gate_steps(dict(job, gate="tests"), scopes, "")
    assert build[1] == ["make", "-s", "build/host/tests/test_ramp"]
    assert runs[1] == ["sh", "tools/gates/run_tests.sh", "build/host/tests/test_ramp"]
    build, cov = tv.gate_steps(dict(job, gate="coverage"), scopes, "")
    objs = cov[1][2].split()
    assert objs[0] == "build/cov/obj/qfoc_ramp.o" and "build/host/obj/qfoc_ramp.o" not in objs
    assert all(o.startswith("build/host/obj/") for o in objs[1:]) and build[1][2:] == objs
    assert cov[1][3:] == ["tests/test_ramp.c"] and cov[2]["COV_FILTER"] == r"src/qfoc_ramp\.c$"
    assert tv.gate_steps(dict(job, gate="misra"), scopes, "")[0][1] == ["sh", "tools/gates/misra.sh"]


# REQ-EVD-030
def test_report_table(tmp_path):
    """results.md: one row per defect with caught / MISSED / - per gate, the scoping table,
    the control, and the partial-run note.

    Methods: 1a results.md: one row per defect with caught, MISSED or '-' per gate, the scoping
    table, the control and the partial-run note
    """
    scopes, defects = parsed()

    def res(kind, name, gate, verdict):
        return {"kind": kind, "name": name, "scope": "ramp", "gate": gate, "verdict": verdict,
                "outcome": tv.outcome(kind, verdict), "ok": tv.job_ok(kind, verdict), "detail": "fig",
                "seconds": 2.0, "cpu_seconds": 1.0, "log": "x"}
    runs = [res("defect", d["id"], g, "fail") for d in defects for g in d["gates"]]
    runs[0] = res("defect", "TV-01", "wp", "pass")
    runs.append(res("control", "control", "wp", "pass"))
    s = tv.summarise(defects, runs, 12.0, len(runs), "--only TV-01,TV-02", scopes, [1.0, 2.0])
    tv.write_md(str(tmp_path / "r.md"), s)
    text = (tmp_path / "r.md").read_text(encoding="utf-8")
    assert "**FAIL: 5 of 6 expected catches in 2 seeded defects; control passes" in text
    assert "| TV-01 | overflow | `src/x.c` | **MISSED** | caught | - | - | caught | caught | 8 |" in text
    assert "| TV-02 | MISRA violation | `src/y.c` | - | - | caught | caught | - | - | 4 |" in text
    assert "| ramp | `src/qfoc_ramp.c` (60 s) | ramp_toward | test_ramp | `src/qfoc_ramp.c` |" in text
    assert "Partial run (--only TV-01,TV-02)" in text and "| ramp | WP | pass |" in text
