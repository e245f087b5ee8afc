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
def test_named_failures_are_open():
    d = campaign()
    fr.apply_findings(d, FINDINGS)
    assert [c["verdict"] for c in d["classes"]] == ["OPEN", "OPEN"]
    assert all(fr.verdict_ok(c) for c in d["classes"]) and d["stale_findings"] == []
    assert d["injections"][0]["finding"] == "FND-7"


# REQ-FINJ-007
def test_unnamed_failure_fails():
    d = campaign(flip_fail=("s.speed_ref", 13))
    fr.apply_findings(d, FINDINGS)
    assert d["classes"][1]["verdict"] == "FAIL" and not fr.verdict_ok(d["classes"][1])


# REQ-FINJ-007
def test_without_findings_every_failure_fails():
    d = campaign()
    fr.apply_findings(d, [])
    assert [c["verdict"] for c in d["classes"]] == ["FAIL", "FAIL"]


# REQ-FINJ-007
def test_finding_that_passes_is_stale():
    d = campaign(stuck_pass=True, flip_fail=None)
    fr.apply_findings(d, FINDINGS)
    assert len(d["stale_findings"]) == 1 and "FND-7" in d["stale_findings"][0]
    # a flip's finding is not stale when the flip did not fail (random instants)
    assert all("FND-10" not in m for m in d["stale_findings"])


# REQ-FINJ-007
def test_malformed_finding_refused(tmp_path, capsys):
    p = tmp_path / "f.toml"
    p.write_text('[[finding]]\nid = "FND-1"\nclass = "adc_stuck"\n')
    with pytest.raises(SystemExit) as e:
        fr.load_findings(str(p))
    assert e.value.code == 2 and "either what or field" in capsys.readouterr().err


# REQ-FINJ-007
def test_repository_findings_load():
    """The committed list loads entry for entry, and each entry names a finding of the
    safety analysis that is not marked closed there."""
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
