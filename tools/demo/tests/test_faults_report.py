"""Tests of the open-finding rule of tools/demo/faults_report.py (REQ-FINJ-007): a failure
named by a finding is reported OPEN, any other fails the gate, and a finding whose
injection passes is stale and fails it."""
import os
import re
import sys

import pytest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
import faults_report as fr  # noqa: E402


def campaign(stuck_pass=False, flip_fail=("s.speed_ref", 14)):
    inj = [{"class": "adc_stuck", "what": "iu stuck at 2048", "pass": stuck_pass},
           {"class": "adc_stuck", "what": "iu stuck at 0", "pass": True}]
    fails = [] if flip_fail is None else [
        {"field": flip_fail[0], "bit": flip_fail[1], "record": {"what": "drive bit 1"}}]
    classes = [{"class": "adc_stuck", "verdict": "PASS" if stuck_pass else "FAIL"},
               {"class": "drive_flip", "verdict": "FAIL" if fails else "PASS"}]
    return {"injections": inj, "flips": {"drive_flip": {"failures": fails}}, "classes": classes}


FINDINGS = [{"id": "FND-7", "class": "adc_stuck", "what": "iu stuck at 2048"},
            {"id": "FND-10", "class": "drive_flip", "field": "s.speed_ref", "bit": 14}]


# REQ-FINJ-007
# Methods: 1a failures of the campaign that a finding names read OPEN, the finding linked to its
# injection
def test_named_failures_are_open():
    d = campaign()
    fr.apply_findings(d, FINDINGS)
    assert [c["verdict"] for c in d["classes"]] == ["OPEN", "OPEN"]
    assert all(fr.verdict_ok(c) for c in d["classes"]) and d["stale_findings"] == []
    assert d["injections"][0]["finding"] == "FND-7"


# REQ-FINJ-007
# Methods: 1d a failed flip that no finding names (s.speed_ref bit 13): FAIL
def test_unnamed_failure_fails():
    d = campaign(flip_fail=("s.speed_ref", 13))
    fr.apply_findings(d, FINDINGS)
    assert d["classes"][1]["verdict"] == "FAIL" and not fr.verdict_ok(d["classes"][1])


# REQ-FINJ-007
# Methods: 1d an empty list of findings: every failure FAIL
def test_without_findings_every_failure_fails():
    d = campaign()
    fr.apply_findings(d, [])
    assert [c["verdict"] for c in d["classes"]] == ["FAIL", "FAIL"]


# REQ-FINJ-007
# Methods: 1d a finding whose injection now passes (stale), and a flip's finding whose flip did
# not fail at its random instant (not stale)
def test_finding_that_passes_is_stale():
    d = campaign(stuck_pass=True, flip_fail=None)
    fr.apply_findings(d, FINDINGS)
    assert len(d["stale_findings"]) == 1 and "FND-7" in d["stale_findings"][0]
    # a flip's finding is not stale when the flip did not fail (random instants)
    assert all("FND-10" not in m for m in d["stale_findings"])


# REQ-FINJ-007
# Methods: 1d a finding with neither 'what' nor 'field': refused with exit code 2
def test_malformed_finding_refused(tmp_path, capsys):
    p = tmp_path / "f.toml"
    p.write_text('[[finding]]\nid = "FND-1"\nclass = "adc_stuck"\n')
    with pytest.raises(SystemExit) as e:
        fr.load_findings(str(p))
    assert e.value.code == 2 and "either what or field" in capsys.readouterr().err


# REQ-FINJ-007
def test_repository_findings_load():
    """The committed list loads entry for entry, and each entry names a finding of the
    safety analysis that is not marked closed there.

    Methods: 1a the committed list loads entry for entry, each entry a finding of the safety
    analysis that is not closed
    """
    root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..")
    path = os.path.join(root, "specs", "fault-findings.toml")
    items = fr.load_findings(path)
    with open(path, encoding="utf-8") as f:
        entries = sum(1 for line in f if line.strip() == "[[finding]]")
    assert len(items) == entries
    with open(os.path.join(root, "specs", "safety-analysis.md"), encoding="utf-8") as f:
        analysis = f.read()
    for it in items:
        head = re.search(r"^\*\*" + re.escape(it["id"]) + r" .*$", analysis, re.M)
        assert head is not None and "Closed by" not in head.group(0)


def ftti_campaign(spec_oc=0.125):
    """Two mechanisms with their item FTTIs; OC judged by three injections, LINK by one."""
    mech = [{"mechanism": "none (within limits)", "key": "", "assumption": "", "spec_ms": None,
             "budget_ms": None, "ftti_ms": None, "adequate": True},
            {"mechanism": "OC", "key": "oc", "assumption": "IA-01", "spec_ms": spec_oc,
             "budget_ms": 1.5 * spec_oc, "ftti_ms": 0.33, "adequate": spec_oc <= 0.33},
            {"mechanism": "LINK", "key": "link", "assumption": "IA-08", "spec_ms": 2795.0,
             "budget_ms": 4192.5, "ftti_ms": 5000.0, "adequate": True}]
    inj = [{"class": "oc_surge", "mechanism": "OC", "faults": ["OC"], "t_react_ms": 0.1,
            "in_time": True, "pass": True},
           {"class": "oc_surge", "mechanism": "OC", "faults": ["OC"], "t_react_ms": 0.125,
            "in_time": True, "pass": True},
           {"class": "oc_surge", "mechanism": "OC", "faults": [], "t_react_ms": None,
            "in_time": False, "pass": True},
           {"class": "link_loss", "mechanism": "LINK", "faults": ["LINK"], "t_react_ms": 5200.0,
            "in_time": False, "pass": False}]
    classes = [{"class": "oc_surge", "verdict": "PASS"}, {"class": "link_loss", "verdict": "FAIL"}]
    # 40 drive-object flips judged against OC's FTTI, 30 detected, 29 in time
    classes.append({"class": "drive_flip", "verdict": "PASS", "mechanism": "OC", "injected": 40,
                    "detected": 30, "in_time": 29, "t_react_ms": [0.125, 0.25]})
    return {"mechanisms": mech, "injections": inj, "classes": classes,
            "flips": {"drive_flip": {"failures": []}}}


ASSUMED = {"oc": {"hazard": "h", "assumption": "a", "derivation": "d"}}


# REQ-FINJ-008
# Methods: 1b a mechanism within its FTTI and one detected after it; 1a the judged, detected and
# within counts and the worst time per mechanism
def test_ftti_rows_judge_each_mechanism_against_its_assumption():
    d = ftti_campaign()
    rows = fr.ftti_rows(d, ASSUMED)
    assert [r["id"] for r in rows] == ["IA-01", "IA-08"]
    oc, link = rows
    assert (oc["judged"], oc["detected"], oc["within"], oc["worst_ms"]) == (43, 32, 31, 0.25)
    assert oc["hazard"] == "h" and oc["verdict"] == "PASS"
    # LINK: detected after its FTTI and failed
    assert (link["within"], link["failed"], link["verdict"]) == (0, 1, "FAIL")


# REQ-FINJ-007, REQ-FINJ-008
# Methods: 1d an injection detected after its mechanism's FTTI that an open finding names: the
# mechanism's row OPEN, not FAIL, and its JUnit case passes (the class is OPEN too), and the
# same injection unnamed FAIL in the row and in the JUnit file
def test_ftti_row_open_when_its_failures_are_named(tmp_path):
    for named in (True, False):
        d = ftti_campaign()
        d.update({"wall_s": 1.0, "mode": "check", "model_checks": []})
        for c in d["classes"]:
            c.setdefault("injected", 1)
            c.setdefault("failed", 0)
        d["injections"][3]["what"] = "master stops at 3000 rpm"
        d["injections"][3].update({"t_det_ms": 5200.0, "first": ["LINK"], "ftti_ms": 5000.0,
                                   "i_peak_a": 10.0, "rpm_peak": 3000.0, "harmless": False,
                                   "oc_missed": False, "over_full_scale": False,
                                   "state_bad": False, "pwm_outside_run": False,
                                   "cmd_changed": False})
        findings = [{"id": "FND-99", "class": "link_loss", "what": "master stops at 3000 rpm"}]
        fr.apply_findings(d, findings if named else [])
        rows = fr.ftti_rows(d, ASSUMED)
        link = rows[1]
        assert link["verdict"] == ("OPEN" if named else "FAIL")
        assert (link["failed"], link["open"]) == ((0, 1) if named else (1, 0))
        path = tmp_path / f"j{named}.xml"
        fr.write_junit(d, str(path), rows)
        text = path.read_text()
        assert ('name="ftti_IA-08_LINK"><failure' in text) == (not named)
        assert ('failures="0"' in text) == named


# REQ-FINJ-008
# Methods: 1c a specified reaction above the FTTI (0.5 ms) and the campaign otherwise passing;
# 1d a mechanism slower than its FTTI
def test_mechanism_slower_than_its_ftti_fails_the_campaign():
    d = ftti_campaign(spec_oc=0.5)
    d["classes"][1]["verdict"] = "PASS"
    rows = fr.ftti_rows(d, ASSUMED)
    assert rows[0]["verdict"] == "FAIL" and not fr.campaign_ok(d, rows)
    d = ftti_campaign()
    d["classes"][1]["verdict"] = "PASS"
    assert fr.campaign_ok(d, fr.ftti_rows(d, ASSUMED))


def _ms(text):
    """The last 'number unit' of a derivation, in ms."""
    m = re.findall(r"([0-9]+(?:\.[0-9]+)?) (ms|s)\b", text)
    v, unit = m[-1]
    return float(v) * (1.0 if unit == "ms" else 1000.0)


# REQ-FINJ-008
def test_repository_assumptions_cover_every_mechanism():
    """specs/item-assumptions.toml has a section for every mechanism of sim/apps/faults.c, each
    with its id, hazard, assumption, derivation and a positive FTTI equal to the figure its
    derivation ends with.

    Methods: 1b every one of the 13 mechanisms of sim/apps/faults.c; 1a each with its id,
    hazard, assumption, derivation and an FTTI equal to the figure its derivation ends with
    """
    import tomllib
    root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..")
    with open(os.path.join(root, "specs", "item-assumptions.toml"), "rb") as f:
        items = tomllib.load(f)
    with open(os.path.join(root, "sim", "apps", "faults.c"), encoding="utf-8") as f:
        src = f.read()
    keys = re.findall(r'"([a-z_]+)"', src[src.index("mech_key[M_N] = {"):].split("};")[0])
    assert len(keys) == 13 and set(items) == set(keys)
    for k, v in items.items():
        assert re.fullmatch(r"IA-[0-9]{2}", v["id"]), k
        assert all(v[f].strip() for f in ("hazard", "assumption", "derivation")), k
        assert v["ftti_ms"] > 0 and abs(_ms(v["derivation"]) - v["ftti_ms"]) < 1e-6 * v["ftti_ms"] + 1e-3, k
