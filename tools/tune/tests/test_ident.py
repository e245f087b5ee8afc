"""Tests of tools/tune/qfoc_ident.py: an identification record and a ratings file to a motor
file and its table (REQ-TUNE-008; run: python3 -m pytest tools/tune/tests).

The reference is the committed table of the reference motor: a record carrying the motor
file's own values must give the same table, byte for byte but for the line naming the motor
file.  Every refusal checks the exit code, a message naming what was typed, and that nothing
was written.
"""
import json
import re
import sys
from pathlib import Path

import pytest

TUNE = Path(__file__).resolve().parent.parent  # tools/tune
REPO = TUNE.parent.parent
sys.path.insert(0, str(TUNE))

import qfoc_ident as qi  # noqa: E402

REFERENCE = REPO / "specs" / "motors" / "reference.toml"
TABLE = REPO / "tables" / "reference_params.c"
# the reference motor file's values of the measured keys
VALUES = {"rs_ohm": 0.35, "ld_h": 2.6e-3, "lq_h": 4.2e-3, "psi_f_wb": 0.065}


def record(tmp_path, values=None, quality=(0.3, 0.5), edit=None):
    """A record file with the values (default the reference motor's) and quality figures."""
    rec = {"format": "qfoc-ident/1", "source": "plant, reference table",
           "conditions": {"vdc_v": 320.0, "winding_temp_degc": 25.0},
           "results": {k: {"value": v, "repeat_pct": quality[0], "residual_pct": quality[1]}
                       for k, v in (values or VALUES).items()}}
    if edit:
        edit(rec)
    p = tmp_path / "record.json"
    p.write_text(json.dumps(rec), encoding="utf-8")
    return p


def ratings(tmp_path, keep=()):
    """The reference motor file without the measured keys (but those named in keep)."""
    lines = [ln for ln in REFERENCE.read_text().splitlines()
             if not re.match(r"^(rs_ohm|ld_h|lq_h|psi_f_wb)\s*=", ln)
             or ln.split("=")[0].strip() in keep]
    p = tmp_path / "ratings.toml"
    p.write_text("\n".join(lines) + "\n", encoding="utf-8")
    return p


def run(tmp_path, rec, rat, *extra, out=None):
    out = out or tmp_path / "motors" / "reference.toml"
    return qi.main([str(rec), str(rat), "--motor-out", str(out), "--table-dir",
                    str(tmp_path / "tables"), "--out-dir", str(tmp_path / "report"),
                    "--no-plots", *extra]), out


def table_body(path):
    """A table's text without the lines that name the motor file it was generated from."""
    return [ln for ln in Path(path).read_text().splitlines() if ".toml" not in ln]


# REQ-TUNE-008: the record's values go into [motor], marked with their quality, and the
# table is the one of a typed motor file with the same values.
# Methods: 1a the reference motor's values through the record against the committed table
# (independent reference: the table generated from the typed file); 1b quality at its limits
def test_ident_round_trip_gives_the_typed_files_table(tmp_path, capsys):
    lim = qi.QUALITY_LIMIT_PCT
    rc, out = run(tmp_path, record(tmp_path, quality=(0.0, min(lim.values()))), ratings(tmp_path))
    assert rc == 0, capsys.readouterr().err
    text = out.read_text()
    for key, v in VALUES.items():
        assert re.search(rf"^{key} = {v:.6g} +# identified: repeat 0 %, residual 2\.5 %$", text,
                         re.M), key
    assert "record.json: plant, reference table" in text
    assert table_body(tmp_path / "tables" / "reference_params.c") == table_body(TABLE)
    crc = re.search(r"0x[0-9A-F]{8}", capsys.readouterr().out).group(0)
    assert crc in TABLE.read_text()


# REQ-TUNE-008: a measured value outside the motor file's plausible range is refused by the
# tuning tool's check, with the unit-slip hint; no motor file and no table are written.
# Methods: 1c a resistance typed in mOhm (350 for 0.35 ohm) and an inductance in H x 1e3;
# 1d values a motor file would refuse
@pytest.mark.parametrize("key, value, text", [
    ("rs_ohm", 350.0, "did you mean motor.rs_ohm = 0.35 ohm"),
    ("ld_h", 2.6, "did you mean motor.ld_h = 0.0026 H"),
])
def test_ident_out_of_range_refused(tmp_path, capsys, key, value, text):
    vals = dict(VALUES, **{key: value})
    rc, out = run(tmp_path, record(tmp_path, values=vals), ratings(tmp_path))
    err = capsys.readouterr().err
    assert rc == 1, err
    assert text in err
    assert "no motor file and no table written" in err
    assert not out.exists()
    assert not (tmp_path / "tables").exists()


# REQ-TUNE-008: a value that is not positive, or a quality figure beyond half the accuracy
# target, is refused naming the record's field, its value and the limit.
# Methods: 1c each quality figure just above its limit (R 2.5 %, L 5 %, psi 2.5 %), a
# negative figure, a zero and a negative value; 1d a measurement that did not repeat
@pytest.mark.parametrize("key, field, value, text", [
    ("rs_ohm", "repeat_pct", 2.51, "results.rs_ohm.repeat_pct = 2.51 %: outside 0 .. 2.5 %"),
    ("lq_h", "residual_pct", 5.01, "results.lq_h.residual_pct = 5.01 %: outside 0 .. 5 %"),
    ("ld_h", "repeat_pct", -0.1, "results.ld_h.repeat_pct = -0.1 %: outside 0 .. 5 %"),
    ("psi_f_wb", "residual_pct", 2.6, "results.psi_f_wb.residual_pct = 2.6 %: outside 0 .. 2.5 %"),
    ("psi_f_wb", "value", 0.0, "results.psi_f_wb.value = 0 Wb: must be > 0"),
    ("rs_ohm", "value", -0.35, "results.rs_ohm.value = -0.35 ohm: must be > 0"),
])
def test_ident_quality_refused(tmp_path, capsys, key, field, value, text):
    def edit(rec):
        rec["results"][key][field] = value
    rc, out = run(tmp_path, record(tmp_path, edit=edit), ratings(tmp_path))
    err = capsys.readouterr().err
    assert rc == 1, err
    assert text in err
    assert not out.exists() and not (tmp_path / "tables").exists()


# REQ-TUNE-008: a malformed record or ratings file is an input error (exit 2) naming the file
# and the field.
# Methods: 1d not JSON, a wrong format, a missing result, a text for a number, an unknown
# result, NaN, a line break in a text the motor file copies, a list for a condition
@pytest.mark.parametrize("mutate, text", [
    (lambda p: p.write_text("{not json"), "not JSON"),
    (lambda p: p.write_text(json.dumps({"format": "qfoc-ident/0", "results": {}})),
     'format = "qfoc-ident/0": expected "qfoc-ident/1"'),
    (lambda p: p.write_text(p.read_text().replace('"lq_h"', '"lq_mh"')),
     "results.lq_mh: not a measured key"),
    (lambda p: p.write_text(p.read_text().replace('"value": 0.065', '"value": "0.065"')),
     'results.psi_f_wb.value = "0.065": not a number'),
    (lambda p: p.write_text(p.read_text().replace('"value": 0.35', '"value": NaN')),
     "results.rs_ohm.value = NaN: not a finite number"),
    (lambda p: p.write_text(p.read_text().replace(', "residual_pct": 0.5}}}', "}}}")),
     "results.psi_f_wb.residual_pct: missing"),
    # text copied into the motor file's comments: a line break would start a key of its own
    (lambda p: p.write_text(p.read_text().replace('"plant, reference table"',
                                                  '"bench\\nrs_ohm = 9"')),
     'source = "bench\\nrs_ohm = 9": a control character'),
    (lambda p: p.write_text(p.read_text().replace('"winding_temp_degc": 25.0',
                                                  '"winding_temp_degc": [25]')),
     "conditions.winding_temp_degc = [25]: not a number or a text"),
])
def test_ident_malformed_record(tmp_path, capsys, mutate, text):
    rec = record(tmp_path)
    mutate(rec)
    rc, out = run(tmp_path, rec, ratings(tmp_path))
    err = capsys.readouterr().err
    assert rc == 2, err
    assert text in err and "record.json" in err
    assert not out.exists()


# REQ-TUNE-008: a ratings file without its [motor] section is an input error.
# Methods: 1d a ratings file of the inverter alone
def test_ident_ratings_without_motor_section(tmp_path, capsys):
    rat = tmp_path / "ratings.toml"
    rat.write_text("[inverter]\nvdc_nominal_v = 320.0\n")
    rc, out = run(tmp_path, record(tmp_path), rat)
    err = capsys.readouterr().err
    assert rc == 2 and "no [motor] section" in err
    assert not out.exists()


# REQ-TUNE-008: a measured key typed in the ratings file is refused (the measurement would
# silently override it, or the typed value the measurement).
# Methods: 1d the ratings file of a motor whose resistance was typed
def test_ident_typed_measured_key_refused(tmp_path, capsys):
    rc, out = run(tmp_path, record(tmp_path), ratings(tmp_path, keep=("rs_ohm",)))
    err = capsys.readouterr().err
    assert rc == 1, err
    assert re.search(r"ratings\.toml:\d+: motor\.rs_ohm is typed \(rs_ohm = 0\.35", err)
    assert not out.exists()


# REQ-TUNE-008: an existing motor file is replaced only with --force, and is left as it was
# when the tuning tool refuses the result.
# Methods: 1d an existing output without --force, and a refusal after the file was written
def test_ident_existing_output(tmp_path, capsys):
    out = tmp_path / "motors" / "reference.toml"
    out.parent.mkdir()
    out.write_text("# the integrator's file\n")
    rc, _ = run(tmp_path, record(tmp_path), ratings(tmp_path), out=out)
    assert rc == 1 and "exists; --force replaces it" in capsys.readouterr().err
    assert out.read_text() == "# the integrator's file\n"
    # with --force, a value the tuning tool refuses: the old file is back, no table
    vals = dict(VALUES, rs_ohm=350.0)
    rc, _ = run(tmp_path, record(tmp_path, values=vals), ratings(tmp_path), "--force", out=out)
    assert rc == 1
    assert out.read_text() == "# the integrator's file\n"
    assert not (tmp_path / "tables").exists()
    rc, _ = run(tmp_path, record(tmp_path), ratings(tmp_path), "--force", out=out)
    assert rc == 0 and "# identified" in out.read_text()
