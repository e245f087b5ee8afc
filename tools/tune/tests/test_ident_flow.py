"""Tests of tools/tune/ident_flow.py: the commissioning flow from identification records to
motor files and tables (REQ-TUNE-009; run: python3 -m pytest tools/tune/tests).

Reference: the typed motor files of specs/motors/ and the tables the tuning tool makes from
them (tables/); a record that carries a typed file's own values must give that file's table.
"""
import json
import re
import sys
from pathlib import Path

TUNE = Path(__file__).resolve().parent.parent  # tools/tune
REPO = TUNE.parent.parent
sys.path.insert(0, str(TUNE))

import ident_flow as flow  # noqa: E402

REFERENCE = REPO / "specs" / "motors" / "reference.toml"
VALUES = {"rs_ohm": 0.35, "ld_h": 2.6e-3, "lq_h": 4.2e-3, "psi_f_wb": 0.065}


def record(path, values=VALUES, repeat=0.5):
    rec = {"format": "qfoc-ident/1", "source": "test", "conditions": {"vdc_v": 320.0},
           "results": {k: {"value": v, "repeat_pct": repeat, "residual_pct": 0.5}
                       for k, v in values.items()}}
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(rec), encoding="utf-8")


def body(path):
    """A table's text without the lines that name the files it was generated from."""
    return [ln for ln in Path(path).read_text().splitlines()
            if ".toml" not in ln and "_params" not in ln and "qfoc_params_" not in ln]


# REQ-TUNE-009: the ratings file is the motor file without the four measured keys of its
# [motor] section, every other line kept (a key of the same name in another section too).
# Methods: 1a the reference motor file; 1c a measured key's name outside [motor]
def test_tune_009_ratings_strip_only_the_measured_keys(tmp_path):
    text = REFERENCE.read_text()
    out = flow.ratings_text(REFERENCE)
    removed = [ln for ln in text.splitlines() if ln not in out.splitlines()]
    assert sorted(re.match(r"\s*(\w+)", ln).group(1) for ln in removed) == \
        sorted(VALUES)
    m = tmp_path / "m.toml"
    m.write_text("[demo]\nrs_ohm = 1.0\n[motor]\nrs_ohm = 2.0\npole_pairs = 3\n")
    assert flow.ratings_text(m) == "[demo]\nrs_ohm = 1.0\n[motor]\npole_pairs = 3\n"


# REQ-TUNE-009: a record with the typed file's own values gives the typed table (the
# manifest's overrides passed on: the 16 kHz variant), the flow's manifest pairs the table
# with the true motor file; a motor without a record, or whose record is refused, has no
# table and fails the flow unless named --known; a --known that is not a table is malformed.
# Methods: 1a back-to-back against tables/reference_params.c and reference16k_params.c;
# 1b a table made, a record missing, a record refused (repeatability 3 % > 2.5 %)
def test_tune_009_flow(tmp_path, capsys):
    man = tmp_path / "manifest.txt"
    man.write_text("# test\nreference specs/motors/reference.toml\n"
                   "reference16k specs/motors/reference.toml inverter.f_pwm_hz=16000\n"
                   "lowflux specs/motors/lowflux.toml\n"
                   "ecomp800 specs/motors/ecomp800.toml\n")
    rec = tmp_path / "rec"
    record(rec / "reference.json")
    record(rec / "reference16k.json")
    record(rec / "ecomp800.json", {"rs_ohm": 0.2, "ld_h": 2.5e-3, "lq_h": 6.5e-3,
                                   "psi_f_wb": 0.098}, repeat=3.0)
    out = tmp_path / "flow"
    import os
    cwd = os.getcwd()
    os.chdir(REPO)
    try:
        rc = flow.main([str(rec), "--out", str(out), "--manifest", str(man)])
        log = capsys.readouterr().out
        assert rc == 1
        assert "lowflux: no record" in log
        assert "ecomp800: refused" in log and "repeat_pct" in log
        made = [ln for ln in (out / "manifest.txt").read_text().splitlines()
                if not ln.startswith("#")]
        assert made == ["reference_id specs/motors/reference.toml",
                        "reference16k_id specs/motors/reference.toml inverter.f_pwm_hz=16000"]
        for name in ("reference", "reference16k"):
            assert body(out / "tables" / f"{name}_id_params.c") == \
                body(REPO / "tables" / f"{name}_params.c"), name
        assert not (out / "tables" / "ecomp800_id_params.c").exists()
        assert flow.main([str(rec), "--out", str(out), "--manifest", str(man),
                          "--known", "lowflux", "--known", "ecomp800"]) == 0
        assert "ecomp800: no table: a known shortfall" in capsys.readouterr().out
        assert flow.main([str(rec), "--out", str(out), "--manifest", str(man),
                          "--known", "nosuch"]) == 2
        assert "--known 'nosuch'" in capsys.readouterr().err
    finally:
        os.chdir(cwd)
