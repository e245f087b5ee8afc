"""Tests of the motor-file input of tools/tune/qfoc_tune.py: the refusals, the schema and its
documentation docs/motor-file.md (run: python3 -m pytest tools/tune/tests).

Every refusal test checks the exit code 1, a message naming the key as the motor file
writes it (section.key) with its value and the rule, and that nothing was written.
"""
import math
import subprocess
import sys
from pathlib import Path

import pytest

TUNE = Path(__file__).resolve().parent.parent  # tools/tune
REPO = TUNE.parent.parent
sys.path.insert(0, str(TUNE))

import qfoc_tune as qt  # noqa: E402

REFERENCE = REPO / "specs" / "motors" / "reference.toml"
SECOND = REPO / "specs" / "motors" / "traction350.toml"
ECOMP = REPO / "specs" / "motors" / "ecomp800.toml"
DOC = REPO / "docs" / "motor-file.md"


def refused(tmp_path, capsys, motor, *extra):
    """Run the tool in-process; assert exit code 1 and no file written; return stderr."""
    rc = qt.main([str(motor), "--out-dir", str(tmp_path / "out"),
                  "--table-dir", str(tmp_path / "tables"), "--no-plots", *extra])
    err = capsys.readouterr().err
    assert rc == 1, err
    assert "refused, no table written" in err
    assert not (tmp_path / "tables").exists()
    assert not (tmp_path / "out").exists()
    return err


def with_text(tmp_path, motor, old, new):
    """A copy of a motor file with one text replaced."""
    text = motor.read_text()
    assert old in text
    path = tmp_path / motor.name
    path.write_text(text.replace(old, new))
    return path


# REQ-TUNE-001: a protection threshold its sensor cannot read is refused.  The bus reading
# is code x 8 (12-bit code 0 .. 4095, 4096 codes = V_base), at most 32760; the current
# reading is (code - offset) x 16 with the offset within 2048 +- offset_window; the
# temperature input reads -40.0 .. 200.0 degC.
# Methods: 1b each sensor's rule broken, one case per parameter (bus, current, temperature); 1c
# thresholds just beyond what the sensor reads (493.5 V against a 480 V full scale: 32767 >
# 32760); 1d thresholds the sensor cannot read
@pytest.mark.parametrize("overrides, message", [
    # bus max 470 V, full scale 480 V: default OV 1.05 x 470 = 493.5 V -> 32767 > 32760
    (("sensing.vdc_full_scale_v=480", "inverter.vdc_max_v=470"),
     "limits.vdc_ov_v = 493.5 V (default 1.05 x inverter.vdc_max_v): the DC-bus sensor "
     "cannot read this over-voltage threshold: it is not below the largest reading 4095 codes "
     "x sensing.vdc_full_scale_v 480 V / 4096 = 479.883 V"),
    # 499.9 / 500 x 32768 = 32761.4 -> 32761 >= 32760
    (("limits.vdc_ov_v=499.9",), "limits.vdc_ov_v = 499.9 V: the DC-bus sensor cannot read"),
    # 499.95 V -> 32765: the bus always reads under it
    (("limits.vdc_uv_v=499.95", "limits.vdc_ov_v=499.99"),
     "limits.vdc_uv_v = 499.95 V: the DC-bus sensor cannot read this under-voltage threshold"),
    # one code = 500 / 4096 = 0.122 V
    (("limits.vdc_uv_v=0.1",), "limits.vdc_uv_v = 0.1 V: below one code of the DC-bus "
                               "sensor, sensing.vdc_full_scale_v 500 V / 4096 = 0.12207 V"),
    # (2047 - 100) x 40 / 2048 = 38.027 A
    (("limits.i_trip_a=39",), "limits.i_trip_a = 39 A: the current sensor cannot read this "
                              "over-current trip: it is not below the largest reading (2047 - "
                              "drive.offset_window_counts 100) codes x sensing.i_full_scale_a "
                              "40 A / 2048 = 38.0273 A"),
    # a wide offset window: (2047 - 600) x 40 / 2048 = 28.26 A < the default trip 30 A
    (("drive.offset_window_counts=600",), "limits.i_trip_a = 30 A (default 1.5 x "
                                          "limits.i_max_a): the current sensor cannot read"),
    (("drive.t_ipm_max_degc=200",), "drive.t_ipm_max_degc = 200 degC: outside -40 <= x < 200"),
    (("drive.t_pcb_max_degc=-41",), "drive.t_pcb_max_degc = -41 degC: outside -40 <= x < 200"),
])
def test_refused_threshold_sensor_cannot_read(tmp_path, capsys, overrides, message):
    args = [a for o in overrides for a in ("--set", o)]
    err = refused(tmp_path, capsys, REFERENCE, *args)
    assert f"refused: {REFERENCE}: {message}" in err


# REQ-TUNE-001: a threshold or setting inside the operating range, which would trip or
# mislead the drive in normal operation (or never act), is refused.
# Methods: 1b each threshold or setting inside the operating range, one per parameter; 1c the
# over-voltage below vdc_max, the under-voltage above vdc_min, phase_i_min equal to i_max; 1d
# settings that would trip or never act in normal operation
@pytest.mark.parametrize("override, message", [
    ("limits.vdc_ov_v=400", "limits.vdc_ov_v = 400 V is below inverter.vdc_max_v = 420 V "
                            "(rule: the DC-bus protection thresholds lie outside the operating "
                            "bus"),
    ("limits.vdc_uv_v=260", "limits.vdc_uv_v = 260 V is above inverter.vdc_min_v = 250 V"),
    ("limits.vdc_svpwm_min_v=300", "limits.vdc_svpwm_min_v = 300 V is above "
                                   "inverter.vdc_min_v = 250 V"),
    ("drive.stall_err_rpm=9000", "drive.stall_err_rpm = 9000 rpm: outside the motor's speed "
                                 "range 0 .. 8000 rpm (limits.speed_max_rpm)"),
    ("drive.phase_i_min_a=20", "drive.phase_i_min_a = 20 A is not below limits.i_max_a = 20 A "
                               "(default motor.rated_current_a)"),
])
def test_refused_operating_range(tmp_path, capsys, override, message):
    err = refused(tmp_path, capsys, REFERENCE, "--set", override)
    assert f"refused: {REFERENCE}: {message}" in err


# REQ-TUNE-001: the rule of specs/scaling.md section 2 is enforced, naming scaling.f_base_hz,
# the speed that needs more and the f_base the motor needs.
# Methods: 1c f_base 499.9 Hz just below the least 500 Hz, k_rpm 67108.9 above 65535; 1d more
# pole pairs or a higher speed than the base frequency allows; 1a the needed f_base computed by
# hand (1.25 x 666.667 = 833.333 Hz)
@pytest.mark.parametrize("overrides, message", [
    # 8000 rpm x 5 / 60 = 666.667 Hz; 1.25 x 666.667 = 833.333 Hz > 500 Hz
    (("motor.pole_pairs=5",),
     "scaling.f_base_hz = 500 Hz breaks the rule of specs/scaling.md section 2: f_base >= "
     "1.25 x the highest electrical frequency (field weakening included): "
     "motor.max_speed_rpm 8000 rpm x motor.pole_pairs 5 / 60 = 666.667 Hz, so this motor "
     "needs scaling.f_base_hz >= 1.25 x 666.667 = 833.333 Hz"),
    # 9000 rpm x 3 / 60 = 450 Hz; 1.25 x 450 = 562.5 Hz
    (("limits.speed_max_rpm=9000",),
     "limits.speed_max_rpm 9000 rpm x motor.pole_pairs 3 / 60 = 450 Hz, so this motor needs "
     "scaling.f_base_hz >= 1.25 x 450 = 562.5 Hz"),
    # 1.25 x 400 Hz = 500 Hz is the least f_base; k_rpm = 3 x 32768 x 4096 / (60 x 499.9)
    (("scaling.f_base_hz=499.9",), "scaling.f_base_hz = 499.9 Hz breaks the rule"),
    # slow motor: 3 x 32768 x 4096 / (60 x 1000 / ... ): at 1500 rpm max, f_base 100 Hz
    # meets 1.25 x 75 Hz but k_rpm = 3 x 32768 x 4096 / 6000 = 67109 > 65535
    (("motor.rated_speed_rpm=1000", "motor.max_speed_rpm=1500", "scaling.f_base_hz=100",
      "drive.rpm_min=500", "drive.of_speed_rpm=300", "drive.tc_speed_min_rpm=100"),
     "scaling.f_base_hz = 100 Hz is too low for motor.pole_pairs 3: the drive's rpm conversion "
     "k_rpm = n_p 32768 x 4096 / (60 f_base) = 67108.9 exceeds 65535"),
])
def test_refused_f_base_rule(tmp_path, capsys, overrides, message):
    args = [a for o in overrides for a in ("--set", o)]
    err = refused(tmp_path, capsys, REFERENCE, *args)
    assert message in err


# REQ-TUNE-001: the library reads 12-bit ADC codes (drive.h, drv_adc12): adc_bits other
# than 12 is refused rather than ignored.
# Methods: 1b 10 and 16 bits, either side of the 12 the library reads; 1d an ADC resolution the
# library would misread
@pytest.mark.parametrize("bits", [10, 16])
def test_refused_adc_bits(tmp_path, capsys, bits):
    err = refused(tmp_path, capsys, REFERENCE, "--set", f"sensing.adc_bits={bits}")
    assert (f"sensing.adc_bits = {bits}: must be 12 (rule: the library reads 12-bit codes "
            "(include/qfoc/drive.h, src/qfoc_drive.c drv_adc12)") in err


# REQ-TUNE-001: a key or section the tool does not use is refused, named, with the close
# match; in the file as on the command line.
# Methods: 1d a misspelt key and section in the file, named with the close match
@pytest.mark.parametrize("old, new, message", [
    ("pole_pairs = 3\n", "pole_pairs = 3\npole_pair = 3\n",
     "unknown key motor.pole_pair (did you mean motor.pole_pairs?)"),
    ("[scaling]", "[limits]\nvdc_ov = 450\n\n[scaling]",
     "unknown key limits.vdc_ov (did you mean limits.vdc_ov_v?)"),
    ("[scaling]", "[limit]\nvdc_ov_v = 450\n\n[scaling]",
     "unknown section [limit] (did you mean [limits]?)"),
    ("adc_bits = 12", "adc_bits = 12\nadc_ref_v = 3.3", "unknown key sensing.adc_ref_v"),
])
def test_refused_unknown_key(tmp_path, capsys, old, new, message):
    path = with_text(tmp_path, REFERENCE, old, new)
    err = refused(tmp_path, capsys, path)
    assert f"refused: {path}: {message}" in err


# REQ-TUNE-001: the same refusal for a key given with --set.
# Methods: 1d a misspelt or unknown key and an unknown section given with --set
@pytest.mark.parametrize("override, message", [
    ("design.no_such_key=1", "unknown key design.no_such_key"),
    ("drive.tc_speed_max=7000", "unknown key drive.tc_speed_max (did you mean "
                                "drive.tc_speed_max_rpm?)"),
    ("nosection.key=1", "unknown section [nosection]"),
])
def test_refused_unknown_key_set(tmp_path, capsys, override, message):
    err = refused(tmp_path, capsys, REFERENCE, "--set", override)
    assert message in err


# REQ-TUNE-001: the [demo] keys of the simulator (sim/scenario.c) are known keys.
# Methods: 1a the simulator's [demo] keys accepted, the table written
def test_demo_keys_accepted(tmp_path):
    rc = qt.main([str(REFERENCE), "--out-dir", str(tmp_path / "out"), "--table-dir",
                  str(tmp_path / "tables"), "--no-plots", "--set", "demo.start_rpm=3000",
                  "--set", "demo.start_load_nm=2.5"])
    assert rc == 0
    assert (tmp_path / "tables" / "reference_params.c").exists()


def _tc_delta_ref(cfg, ds, rpm, h):
    """The torque compensation's phase error from the transfer functions' polynomials
    (scipy.signal.freqs), independent of the tool's complex arithmetic: current loop
    1 / (2 T_sigma s + 1), mechanics s / (J s^2 + (B + K_t kp F) s + K_t ki F) with the speed
    filter F = w_f / (s + w_f) multiplied out, PLL (2 zeta wn s + wn^2) / (s^2 + 2 zeta wn s
    + wn^2), the half-tick delay; delta = phase + 90 deg, wrapped to +-180."""
    import numpy as np
    from scipy import signal
    m, d, ph = cfg["motor"], cfg["design"], ds.phys
    w = h * rpm * 2.0 * math.pi / 60.0
    wf = 2.0 * math.pi * d["speed_fc_hz"]
    kp, ki, kt = ph["ksp"], ph["ksp"] / ph["tau_s"], ds.k_t
    # G = s (s + wf) / [(J s^2 + B s)(s + wf) + K_t wf (kp s + ki)]
    num_g = np.polymul([1.0, 0.0], [1.0, wf])
    den_g = np.polyadd(np.polymul([m["j_kgm2"], m["b_nms"], 0.0], [1.0, wf]),
                       [kt * wf * kp, kt * wf * ki])
    wn, z = 2.0 * math.pi * d["pll_wn_hz"], d["pll_zeta"]
    parts = [([1.0], [2.0 * ds.t_sigma, 1.0]), (num_g, den_g),
             ([2.0 * z * wn, wn * wn], [1.0, 2.0 * z * wn, wn * wn])]
    phase = 0.0
    for num, den in parts:
        _, hw = signal.freqs(num, den, worN=[w])
        phase += math.degrees(float(np.angle(hw[0])))
    delta = phase - math.degrees(w * 0.5e-3) + 90.0
    return (delta + 180.0) % 360.0 - 180.0


# REQ-TUNE-001: the default of drive.tc_speed_max_rpm is the highest speed up to the rated
# one where the torque compensation's learning law keeps its phase error within
# TC_DELTA_MAX_DEG (the first harmonic up to the top, the second up to half of it); a window
# where it reaches 90 deg (divergence) is refused with the key named; an explicit value above
# the largest target is refused.
# Methods: 1c the derived top: its phase error within TC_DELTA_MAX_DEG, 10 rpm above it beyond,
# a rated speed below it, 8001 rpm above the speed range; 1d a slow PLL whose learning diverges
# inside a typed window; 1n the phase error of the learning law recomputed in the test
def test_tc_speed_max_default_derived(tmp_path, capsys):
    cfg = qt.load_config(REFERENCE, [])
    ds = qt.design_loops(cfg, qt.make_bases(cfg))
    for rpm in (600.0, 1500.0, 3000.0, 6000.0):
        for h in (1, 2):
            assert abs(qt.tc_phase_error_deg(cfg, ds, rpm, h) -
                       _tc_delta_ref(cfg, ds, rpm, h)) < 1e-6
    top = qt.tc_speed_limit_rpm(cfg, ds, 600.0, 6000.0)
    assert 600.0 < top < 6000.0
    assert abs(_tc_delta_ref(cfg, ds, top, 1)) <= qt.TC_DELTA_MAX_DEG
    assert abs(_tc_delta_ref(cfg, ds, top / 2.0, 2)) <= qt.TC_DELTA_MAX_DEG
    assert abs(_tc_delta_ref(cfg, ds, top + 10.0, 1)) > qt.TC_DELTA_MAX_DEG
    # the table carries the derived top
    rc = qt.main([str(REFERENCE), "--out-dir", str(tmp_path / "o"), "--table-dir",
                  str(tmp_path / "t"), "--no-plots"])
    assert rc == 0
    text = (tmp_path / "t" / "reference_params.c").read_text()
    raw = math.floor(top * 3 / 60 / 500 * 32768 + 0.5)
    assert f".tc_speed_max = {raw}," in text
    # a rated speed below the derived top bounds it
    path = with_text(tmp_path, REFERENCE, "rated_speed_rpm = 6000", "rated_speed_rpm = 4000")
    cfg = qt.load_config(path, [])
    ds = qt.design_loops(cfg, qt.make_bases(cfg))
    assert qt.tc_speed_limit_rpm(cfg, ds, 600.0, cfg["drive"]["tc_speed_max_rpm"]) == 4000.0
    # a slow PLL (5 Hz) puts the phase error beyond 90 deg inside a typed window: refused
    err = refused(tmp_path, capsys, REFERENCE, "--set", "design.pll_wn_hz=5",
                  "--set", "drive.tc_speed_max_rpm=6000")
    assert "drive.tc_speed_max_rpm = 6000 rpm" in err and "learning diverges" in err
    err = refused(tmp_path, capsys, REFERENCE, "--set", "drive.tc_speed_max_rpm=8001")
    assert ("drive.tc_speed_max_rpm = 8001 rpm: outside the motor's speed range 0 .. 8000 rpm "
            "(motor.max_speed_rpm)") in err


# REQ-TUNE-001: no Python warning or traceback reaches the terminal: a value the per-key range
# refuses (pole_pairs 1 .. 16, drive_cfg.h) is named as typed before any computation; loop
# models that leave the floating-point range (a plant pole far beyond the sample rate, a
# vanishing inertia) fail the loop check, naming the keys the loops are made from.
# Methods: 1c pole_pairs 500 (outside 1 .. 16), R_s 1e6 ohm, J 1e-12 kg m^2; 1d values that
# would drive the loop models out of the floating-point range
@pytest.mark.parametrize("override, message", [
    ("motor.pole_pairs=500", "refused: " + str(REFERENCE) + ": motor.pole_pairs = 500: "
                             "outside 1 .. 16"),
    ("motor.rs_ohm=1e6", "motor.rs_ohm = 1e+06 ohm: outside the plausible range"),
    ("motor.j_kgm2=1e-12", "motor.j_kgm2 = 1e-12 kg m^2"),
])
def test_no_python_warning(tmp_path, override, message):
    proc = subprocess.run([sys.executable, str(TUNE / "qfoc_tune.py"), str(REFERENCE),
                           "--no-plots", "--out-dir", str(tmp_path / "out"), "--table-dir",
                           str(tmp_path / "tables"), "--set", override],
                          capture_output=True, text=True, cwd=REPO, check=False)
    assert proc.returncode == 1
    assert message in proc.stderr
    assert "Warning" not in proc.stderr and "Traceback" not in proc.stderr
    assert not (tmp_path / "tables").exists()


# REQ-TUNE-001: values beyond the plausible ranges (PLAUSIBLE) reach the loop models only when
# the ranges are lifted; the models then leave the floating-point range, and the loop check
# fails naming the keys the loops are made from, without a Python warning.
# Methods: 1d a resistance beyond the plausible range with the ranges lifted: the loop check
# fails naming the keys, no Python warning
def test_loop_models_float_range(tmp_path, capsys, monkeypatch):
    monkeypatch.setattr(qt, "PLAUSIBLE", {})
    rc = qt.main([str(REFERENCE), "--out-dir", str(tmp_path / "out"), "--table-dir",
                  str(tmp_path / "tables"), "--no-plots", "--set", "motor.rs_ohm=1e6"])
    err = capsys.readouterr().err
    assert rc == 1
    assert "loop check failed: the loop models leave the floating-point range" in err
    assert "motor.rs_ohm = 1e+06 ohm" in err
    assert not (tmp_path / "tables").exists()


# REQ-TUNE-001: a value implausible by orders of magnitude (a unit slip: mH typed as H, mOhm
# as ohm, mWb as Wb, ms or us as s, krpm as rpm) is refused with the key, the value typed, the
# plausible range and the value x 1e-3 or x 1e3 inside the range as "did you mean".
# Methods: 1b one unit slip per parameter (mH as H, mOhm as ohm, mWb as Wb, ms or us as s, krpm
# as rpm); 1c values outside the plausible range by a factor 1000; 1d unit slips, with the
# corrected value as 'did you mean'
@pytest.mark.parametrize("override, message", [
    ("motor.ld_h=2.6", "motor.ld_h = 2.6 H: outside the plausible range 5e-06 .. 0.05 H of a "
                       "compressor or traction PMSM drive; did you mean motor.ld_h = 0.0026 H "
                       "(mH typed as H)?"),
    ("motor.lq_h=4.2", "motor.lq_h = 4.2 H: outside the plausible range 5e-06 .. 0.05 H"),
    ("motor.rs_ohm=35", "motor.rs_ohm = 35 ohm: outside the plausible range 0.0005 .. 2 ohm of "
                        "a compressor or traction PMSM drive; did you mean motor.rs_ohm = "
                        "0.035 ohm (mOhm typed as ohm)?"),
    ("motor.psi_f_wb=65", "motor.psi_f_wb = 65 Wb: outside the plausible range 0.001 .. 1 Wb of "
                          "a compressor or traction PMSM drive; did you mean motor.psi_f_wb = "
                          "0.065 Wb (mWb typed as Wb)?"),
    ("design.speed_t_sam_s=1", "design.speed_t_sam_s = 1 s: outside the plausible range 2e-05 .. "
                               "0.02 s of a compressor or traction PMSM drive; did you mean "
                               "design.speed_t_sam_s = 0.001 s (ms typed as s)?"),
    ("design.speed_tau_s=80", "did you mean design.speed_tau_s = 0.08 s (ms typed as s)?"),
    ("inverter.dead_time_s=1", "inverter.dead_time_s = 1 s: outside the plausible range 1e-08 .. "
                               "1e-05 s"),
    ("motor.rated_speed_rpm=6", "did you mean motor.rated_speed_rpm = 6000 rpm (krpm typed as "
                                "rpm)?"),
    ("inverter.vdc_max_v=0.42", "did you mean inverter.vdc_max_v = 420 V (kV typed as V)?"),
    ("motor.rated_current_a=20000", "did you mean motor.rated_current_a = 20 A (mA typed as A)?"),
])
def test_refused_implausible(tmp_path, capsys, override, message):
    err = refused(tmp_path, capsys, REFERENCE, "--set", override)
    key, value = override.split("=")
    assert f"refused: {REFERENCE}: {key} = " in err
    assert message in err
    assert "outside the plausible range" in err and "(plausible range: " in err


# REQ-TUNE-001: the same in a motor file, every implausible value named at once; a value
# without a factor-1000 neighbour inside the range has no "did you mean".
# Methods: 1d three implausible values in one motor file, named at once, one without a
# factor-1000 neighbour in the range
def test_refused_implausible_in_file(tmp_path, capsys):
    path = with_text(tmp_path, REFERENCE, "ld_h = 2.6e-3", "ld_h = 2.6")
    path.write_text(path.read_text().replace("rs_ohm = 0.35 ", "rs_ohm = 350 "))
    path.write_text(path.read_text().replace("j_kgm2 = 3.0e-4", "j_kgm2 = 1e-12"))
    err = refused(tmp_path, capsys, path)
    assert "motor.ld_h = 2.6 H: outside the plausible range" in err
    assert "did you mean motor.ld_h = 0.0026 H (mH typed as H)?" in err
    assert "did you mean motor.rs_ohm = 0.35 ohm (mOhm typed as ohm)?" in err
    line = next(ln for ln in err.splitlines() if "motor.j_kgm2 = 1e-12" in ln)
    assert "outside the plausible range 1e-06 .. 10 kg m^2" in line and "did you mean" not in line


# REQ-TUNE-001: every plausible range belongs to a number key of the schema and holds the
# values of both committed motor files (and their defaults); 0 stays accepted where the key
# allows it (no dead time, no current filter).
# Methods: 1b the three committed motor files, one per parameter; 1c 0 accepted where the key
# allows it (no dead time, no current filter)
@pytest.mark.parametrize("motor", [REFERENCE, SECOND, ECOMP])
def test_plausible_ranges_accept_committed_motors(tmp_path, motor):
    for name in qt.PLAUSIBLE:
        assert qt.SCHEMA_BY_NAME[name].kind == "num"
    cfg = qt.load_config(motor, [])
    for name, (lo, hi, _why) in qt.PLAUSIBLE.items():
        section, key = name.split(".")
        if cfg[section][key] is not None and cfg[section][key] != 0:
            assert lo <= cfg[section][key] <= hi, name
    assert qt.load_config(motor, ["inverter.dead_time_s=0", "design.t_filter_current_s=0"])
    # the hand-over window of the 800 V motor covers only -10 % of L_q error (L_q i_start /
    # psi_f = 2.65), that of the traction motor -8 % (3.30): both are warned about; the
    # reference motor has no warning
    assert [w[:45] for w in cfg["warnings"]] == (
        ["the hand-over window drive.ho_angle_deg = 15 "] if motor in (ECOMP, SECOND) else [])


# REQ-TUNE-001: the hand-over window's cover of an L_q error, against its formula in double
# precision: tan(ho_angle) / (L_q i_start / psi_f); warned below 20 %, named with the figures.
# Methods: 1c the cover of an L_q error below and above 20 %; 1n tan(ho_angle) / (L_q i_start /
# psi_f) in double precision
def test_warns_handover_window_narrow_for_lq():
    import math
    cfg = qt.load_config(ECOMP, [])
    r, e = qt.handover_lq_cover(cfg)
    assert r == pytest.approx(6.5e-3 * 40.0 / 0.098, rel=1e-9)
    assert e == pytest.approx(math.tan(math.radians(15.0)) / r, rel=1e-9)
    assert 0.10 < e < 0.102
    w = cfg["warnings"][-1]
    assert "covers an L_q error down to -10.1 % only" in w and "= 2.65" in w
    # a wider window or a lower start current covers 20 %: no warning
    assert qt.load_config(ECOMP, ["drive.ho_angle_deg=30"])["warnings"] == []
    assert qt.load_config(ECOMP, ["drive.i_start_a=19"])["warnings"] == []
    # the reference motor: r = 1.29, the window covers 20.8 %
    r, e = qt.handover_lq_cover(qt.load_config(REFERENCE, []))
    assert r == pytest.approx(4.2e-3 * 20.0 / 0.065) and e > 0.20


# REQ-TUNE-001: L_q < L_d is warned about (an IPM motor has L_q > L_d), naming both keys and
# values; the table is made all the same.
# Methods: 1d L_d and L_q swapped (L_q < L_d): warned, named, the table made all the same
def test_warns_lq_below_ld(tmp_path, capsys):
    rc = qt.main([str(REFERENCE), "--out-dir", str(tmp_path / "out"), "--table-dir",
                  str(tmp_path / "tables"), "--no-plots", "--set", "motor.ld_h=4.2e-3",
                  "--set", "motor.lq_h=2.6e-3"])
    err = capsys.readouterr().err
    assert rc == 0, err
    text = ("motor.lq_h = 0.0026 H is below motor.ld_h = 0.0042 H: an interior-magnet (IPM) "
            "motor has L_q > L_d")
    assert "warning: " + text in err
    assert "refused" not in err
    assert (tmp_path / "tables" / "reference_params.c").exists()
    assert "- " + text in (tmp_path / "out" / "report.md").read_text()


# REQ-TUNE-001: the high-speed inductances are checked the same way; L_q = L_d (a surface
# magnet motor) is no warning.
# Methods: 1c L_q = L_d (a surface magnet motor: no warning); 1d the high-speed inductances
# swapped
def test_warns_lq_hs_below_ld_hs(tmp_path):
    cfg = qt.load_config(REFERENCE, ["motor.ld_hs_h=3e-3", "motor.lq_hs_h=2e-3"])
    assert cfg["warnings"] == [
        "motor.lq_hs_h = 0.002 H is below motor.ld_hs_h = 0.003 H: an interior-magnet (IPM) "
        "motor has L_q > L_d (L_q = L_d for a surface-magnet motor); are the two values "
        "swapped? The table is made with the values as given"]
    assert qt.load_config(REFERENCE, ["motor.lq_h=2.6e-3"])["warnings"] == []


# REQ-TUNE-001: docs/motor-file.md is the tool's schema (--motor-file-doc), every section and
# key with its unit, range, default and rule; --help points to it.
# Methods: 1a docs/motor-file.md is the tool's schema, every section and key with its unit,
# range, default and rule
def test_motor_file_doc_matches_schema(capsys):
    assert qt.main(["--motor-file-doc"]) == 0
    out = capsys.readouterr().out
    assert out == qt.motor_file_doc()
    assert DOC.read_text(encoding="utf-8") == out, \
        "docs/motor-file.md differs from the tool's schema: python3 tools/tune/qfoc_tune.py " \
        "--motor-file-doc > docs/motor-file.md"
    for section in qt.SECTIONS:
        assert f"## [{section}]" in out
    for k in qt.SCHEMA:
        row = next(ln for ln in out.splitlines() if ln.startswith(f"| `{k.key}` |")
                   and k.desc.replace("|", "\\|") in ln)
        assert k.rule.replace("|", "\\|") in row
        assert qt.range_text(k.rng) in row or k.kind == "str"
    assert "| `vdc_ov_v` | number | V | > 0 | 1.05 x inverter.vdc_max_v |" in out
    assert "| `adc_bits` | integer | bits | = 12 | required |" in out
    assert "| `start_load_nm` | number | N m | >= 0 | motor.nominal_torque_nm |" in out


# REQ-TUNE-001: --help points to the motor-file format.
# Methods: 1a --help names docs/motor-file.md
def test_help_points_to_motor_file_doc(capsys):
    with pytest.raises(SystemExit):
        qt.main(["--help"])
    assert "docs/motor-file.md" in capsys.readouterr().out


# REQ-TUNE-001: every key of the committed motor files is a key of the schema.
# Methods: 1b the three committed motor files, one per parameter, every key in the schema
@pytest.mark.parametrize("motor", [REFERENCE, SECOND, ECOMP])
def test_committed_motor_keys_in_schema(motor):
    import tomllib
    raw = tomllib.loads(motor.read_text())
    for section, keys in raw.items():
        for key in keys:
            assert f"{section}.{key}" in qt.SCHEMA_BY_NAME


# REQ-TUNE-001: the simulator reads the same motor files (sim/motor.c sim_keys): every key it
# requires is in each committed motor file, as a number.
# Methods: 1b the three committed motor files, one per parameter; 1a every key the simulator
# requires present as a number
@pytest.mark.parametrize("motor", [REFERENCE, SECOND, ECOMP])
def test_committed_motor_has_sim_keys(motor):
    import re
    import tomllib
    keys = re.findall(r'SIM_KEY\("([a-z_]+\.[a-z_0-9]+)"', (REPO / "sim" / "motor.c").read_text())
    assert len(keys) >= 20
    raw = tomllib.loads(motor.read_text())
    for key in keys:
        section, name = key.split(".")
        assert isinstance(raw[section][name], (int, float)), key


# REQ-TUNE-001: scaling.psi_shift is an integer 0 .. 4 (drive_cfg.h
# QFOC_DRIVE_PSI_SHIFT_MAX); any other value, whatever its type, is refused with exit code 1,
# naming the key and the value as typed.
# Methods: 1b a value of each wrong kind, one per parameter: negative, too large, not an
# integer, not a number; 1c -1 and 5 either side of 0 .. 4
@pytest.mark.parametrize("value, shown, why", [
    ("-1", "-1", "outside 0 .. 4"),
    ("5", "5", "outside 0 .. 4"),
    ("1.5", "1.5", "not an integer"),
    ("x", "'x'", "not a number"),
    ('"2"', "'2'", "not a number"),
    ("true", "true", "not a number"),
])
def test_refused_psi_shift(tmp_path, capsys, value, shown, why):
    err = refused(tmp_path, capsys, REFERENCE, "--set", f"scaling.psi_shift={value}")
    assert (f"refused: {REFERENCE}: scaling.psi_shift = {shown}: {why}; the flux-base shift is "
            "an integer 0 .. 4 (rule: docs/motor-file.md rule 'flux base'") in err


# REQ-TUNE-001: the same in a motor file.
# Methods: 1c psi_shift 7, beyond 0 .. 4, in a motor file
def test_refused_psi_shift_in_file(tmp_path, capsys):
    path = with_text(tmp_path, REFERENCE, "[scaling]\n", "[scaling]\npsi_shift = 7\n")
    err = refused(tmp_path, capsys, path)
    assert f"refused: {path}: scaling.psi_shift = 7: outside 0 .. 4" in err


# REQ-TUNE-001: real DC-bus sensor full scales of 650 .. 900 V buses (1000 .. 1100 V) are
# accepted; an over-voltage threshold the sensor cannot read stays refused: 1100 V full scale
# reads at most 4095 / 4096 x 1100 = 1099.73 V.
# Methods: 1c full scales 1000, 1050 and 1100 V accepted, an over-voltage threshold of 1099.9 V
# above the largest readable 1099.73 V refused
def test_bus_sensor_full_scale_800v(tmp_path, capsys):
    for v in (1000, 1050, 1100):
        cfg = qt.load_config(ECOMP, [f"sensing.vdc_full_scale_v={v}"])
        assert cfg["sensing"]["vdc_full_scale_v"] == v
    err = refused(tmp_path, capsys, ECOMP, "--set", "limits.vdc_ov_v=1099.9")
    assert (f"refused: {ECOMP}: limits.vdc_ov_v = 1099.9 V: the DC-bus sensor cannot read this "
            "over-voltage threshold: it is not below the largest reading 4095 codes x "
            "sensing.vdc_full_scale_v 1100 V / 4096 = 1099.73 V") in err
