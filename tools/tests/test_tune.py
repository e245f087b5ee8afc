"""Tests of tools/qfoc_tune.py (run: python3 -m pytest tools/tests).

The hand computations below are written out so that a reader can check every expected
number with a pocket calculator.
"""
import math
import sys
import zlib
from pathlib import Path

import pytest

TOOLS = Path(__file__).resolve().parent.parent
REPO = TOOLS.parent
sys.path.insert(0, str(TOOLS))

import qfoc_tune as qt  # noqa: E402

REFERENCE = REPO / "specs" / "motors" / "reference.toml"
SECOND = REPO / "specs" / "motors" / "traction350.toml"

SIMPLE_MOTOR = """
[motor]
name = "simple test motor"
pole_pairs = 2
rs_ohm = 1.0
ld_h = 1.0e-3
lq_h = 1.0e-3
psi_f_wb = 0.05
j_kgm2 = 1.0e-3
b_nms = 1.0e-3
rated_speed_rpm = 1000
max_speed_rpm = 1200
rated_current_a = 5.0
nominal_torque_nm = 0.5

[inverter]
vdc_nominal_v = 48.0
vdc_min_v = 40.0
vdc_max_v = 56.0
f_pwm_hz = 10000.0
f_timer_hz = 80.0e6
dead_time_s = 1.0e-6

[sensing]
i_full_scale_a = 10.0
vdc_full_scale_v = 100.0
adc_bits = 12

[scaling]
f_base_hz = 100.0
"""


def run(tmp_path, motor, *extra):
    """Run the tool in-process into tmp_path; return the exit code."""
    return qt.main([str(motor), "--out-dir", str(tmp_path / "out"),
                    "--table-dir", str(tmp_path / "tables"), "--no-plots", *extra])


def simple_design(tmp_path):
    """Design of the simple motor."""
    path = tmp_path / "simple.toml"
    path.write_text(SIMPLE_MOTOR)
    cfg = qt.load_config(path, [])
    b = qt.make_bases(cfg)
    return qt.design_loops(cfg, b), path


# REQ-TUNE-006: the table CRC is CRC-32/ISO-HDLC (check value, zlib agreement).
def test_crc_check_value():
    assert qt.crc32_iso_hdlc(b"123456789") == 0xCBF43926
    data = bytes(range(256)) * 3
    assert qt.crc32_iso_hdlc(data) == zlib.crc32(data)
    assert qt.crc32_iso_hdlc(b"") == 0


# REQ-TUNE-003: gains in the pi.h representation (Q15 mantissa, left shift).
def test_mantissa_left_corners():
    assert qt.mant_left(0.0) == (0, 0)
    assert qt.mant_left(32767 / 32768) == (32767, 0)      # largest gain with shift 0
    assert qt.mant_left(1.0) == (16384, 1)                 # 32768 does not fit: shift 1
    assert qt.mant_left(2.5) == (20480, 2)                 # the example of pi.h
    assert qt.mant_left(32767.0) == (32767, 15)            # largest representable gain
    assert qt.mant_left(1.0e6) == (32767, 15)              # saturates (caught by range checks)
    assert qt.mant_left(1.0 / 32768) == (1, 0)             # one LSB
    assert qt.mant_left(0.4 / 32768) == (0, 0)             # below half an LSB


# REQ-TUNE-002, REQ-TUNE-003: flux.h right-shift mantissa, Q15 and Qn rounding corners.
def test_mantissa_right_and_q15_corners():
    # flux.h example: g = 3141.593 / 8000 -> 25736 with gain_shift 1
    assert qt.mant_right(2 * math.pi * 500 / 8000) == (25736, 1)
    assert qt.mant_right(0.9) == (29491, 0)                # 0.9 x 65536 > 32767: no shift
    assert qt.mant_right(1e-9)[1] == 15                    # smallest values: largest shift
    assert qt.q15(1.0) == 32767 and qt.q15(-1.0) == -32767  # symmetric range
    assert qt.q15(0.5 / 32768) == 1                         # ties round up
    assert qt.q15(-0.5 / 32768) == 0                        # floor(x + 0.5), as est_q15
    assert qt.qn(8.0, 12) == 32767                          # Q12 saturates at 8 pu


# REQ-TUNE-002, REQ-TUNE-003: bases and every chapter 2 gain against a hand computation.
def test_simple_motor_gains_by_hand(tmp_path):
    ds, _ = simple_design(tmp_path)
    g = ds.gains
    # Bases: w_base = 2 pi 100 = 628.3185 rad/s, T_s = 1 / 10 kHz = 100 us.
    # T_sigma = T_s / 2 (PWM) + T_s (computation) + 0 (filter) = 150 us.
    assert ds.t_sigma == pytest.approx(150e-6)
    # Current loop: k_cp = L / (2 T_sigma) = 1e-3 / 3e-4 = 3.3333 ohm;
    # kp_pu = k_cp I_base / V_base = 3.3333 x 10 / 100 = 0.33333 -> 0.33333 x 32768 = 10922.7
    assert g["pi_id.kp"].real == pytest.approx(1.0 / 3.0)
    assert (g["pi_id.kp"].raw, g["pi_id.kp"].shift) == (10923, 0)
    # k_ci = R / (2 T_sigma) = 1 / 3e-4 = 3333.3 ohm/s; ki T = 0.33333 ohm;
    # per unit 0.033333 -> 0.033333 x 32768 = 1092.3
    assert g["pi_iq.ki"].real == pytest.approx(1.0 / 30.0)
    assert (g["pi_iq.ki"].raw, g["pi_iq.ki"].shift) == (1092, 0)
    # Output limits: V_dc,max / sqrt 3 / V_base = 56 / 1.73205 / 100 = 0.323316 -> 10594.4
    assert g["pi_id.out"].raw == math.floor(56 / math.sqrt(3) / 100 * 32768 + 0.5) == 10594
    # Speed loop, sampled every T_sam = 1 ms (the drive's tick):
    # T_ssigma = 2 T_sigma + 1 / (2 pi 20 Hz) + T_sam = 0.3 ms + 7.9577 ms + 1 ms
    t_ss = 2 * 150e-6 + 1 / (2 * math.pi * 20) + 1e-3
    assert ds.t_ssigma == pytest.approx(t_ss)
    # K_t = 1.5 x 2 x 0.05 = 0.15 N m/A, b = 1 / J = 1000: ksp = 1 / (2 T_ssigma K_t b)
    ksp = 1 / (2 * t_ss * 0.15 * 1000)                     # = 0.39883 A s/rad (mechanical)
    assert ds.phys["ksp"] == pytest.approx(ksp)
    # electrical speed in pu of w_base: kp_pu = ksp / n_p x w_base / I_base = 11.311
    kp = ksp / 2 * 2 * math.pi * 100 / 10
    assert g["pi_speed.kp"].real == pytest.approx(kp)
    assert g["pi_speed.kp"].shift == 4                      # 11.31 / 16 = 0.707 < 1
    assert g["pi_speed.kp"].raw == math.floor(kp / 16 * 32768 + 0.5)
    # tau_s = J / B = 1 s: ki T = kp T_sam / tau_s
    assert g["pi_speed.ki"].real == pytest.approx(kp * 1e-3 / 1.0)
    # PLL: w_n = 2 pi 100 = 628.32; kp = 2 x 0.9 x 628.32 / 628.32 = 1.8 -> shift 1,
    # 0.9 x 32768 = 29491.2; ki T = w_n^2 T / w_base = 628.32 x 1e-4 = 0.062832 -> 2058.9
    assert (g["pll.kp"].raw, g["pll.kp"].shift) == (29491, 1)
    assert (g["pll.ki"].raw, g["pll.ki"].shift) == (2059, 0)
    # k_theta = 100 / 10000 x 131072 = 1310.72 -> 1311
    assert g["pll.k_theta"].raw == 1311
    # Flux: g = T w_base = 0.0628319; right shift 3: 0.0628319 x 2^18 = 16470.97 -> 16471
    assert (g["flux.gain"].raw, g["flux.gain"].shift) == (16471, 3)
    # r = R / Z_base = 1 / 10 = 0.1 -> 3276.8 -> 3277; L_base = 10 / 628.32 = 15.915 mH,
    # l = 1e-3 / 15.915e-3 = 0.062832 -> Q12 257.36 -> 257; kg = 100 / 628.32 -> 5215.2
    assert g["flux.r"].raw == 3277
    assert g["flux.l"].raw == 257
    assert g["flux.kg"].raw == 5215
    # Low-pass: alpha = 2 pi 20 / 10000 = 0.012566 -> 411.77 -> 412
    assert g["pll.speed_alpha"].raw == 412
    # Field weakening: G_fw = w_max L_d I_base / (V_dc,min / sqrt 3)
    # = (1200 x 2 x 2 pi / 60) x 1e-3 x 10 / (40 / sqrt 3) = 251.33 x 0.01 / 23.094 = 0.10883
    g_fw = 1200 * 2 * 2 * math.pi / 60 * 1e-3 * 10 / (40 / math.sqrt(3))
    w_fw = 0.1 / (2 * 150e-6)                               # 333.3 rad/s
    assert g["pi_fw.ki"].real == pytest.approx(w_fw / g_fw * 100e-6)
    assert g["pi_fw.kp"].real == pytest.approx(1 / (4 * g_fw))


# REQ-TUNE-006: the serialisation length of params.h and the generated initialiser.
def test_simple_motor_passes_and_table_compiles_layout(tmp_path):
    ds, path = simple_design(tmp_path)
    items = qt.build_table(ds.cfg, ds)
    # params.h serialisation: 4+2+2+4+4+4 + svpwm 8 + 4 PI x 10 + flux 9 + pll 18 + 10 x 2
    assert len(qt.serialise(items)) == 115
    assert run(tmp_path, path) == 0
    text = (tmp_path / "tables" / "simple_params.c").read_text()
    assert "const qfoc_param_table_t qfoc_params_simple = {" in text
    assert ".out_min = (int16_t)-10594," in text


# REQ-TUNE-004: a scaling made too tight is rejected, naming the bound and the input.
def test_too_tight_scaling_rejected(tmp_path, capsys):
    rc = run(tmp_path, REFERENCE, "--set", "sensing.i_full_scale_a=15")
    err = capsys.readouterr().err
    assert rc == 1
    assert "bound violated: Clarke (2-5, 2-6" in err
    assert "> 32767 for i_trip = 30 A" in err
    assert not (tmp_path / "tables").exists()                # no table on failure
    assert "Status: **FAILED**" in (tmp_path / "out" / "report.md").read_text()


# REQ-TUNE-001: malformed motor data are rejected with exit code 2 and the field named.
@pytest.mark.parametrize("override, message", [
    ("motor.rs_ohm=-1", "must be > 0"),
    ("motor.pole_pairs=2.5", "expected an integer"),
    ("motor.ld_h=\"abc\"", "expected a number"),
    ("design.no_such_key=1", "unknown key"),
    ("nosection.key=1", "unknown section"),
])
def test_bad_input_exit_2(tmp_path, capsys, override, message):
    assert run(tmp_path, REFERENCE, "--set", override) == 2
    assert message in capsys.readouterr().err


# REQ-TUNE-001: a missing field is rejected with exit code 2.
def test_missing_field_exit_2(tmp_path, capsys):
    path = tmp_path / "broken.toml"
    path.write_text(SIMPLE_MOTOR.replace("rs_ohm = 1.0\n", ""))
    assert run(tmp_path, path) == 2
    assert "missing [motor] rs_ohm" in capsys.readouterr().err


# REQ-TUNE-004, REQ-TUNE-005, REQ-TUNE-006: both motors pass every bound and loop check;
# the committed tables regenerate byte for byte.
@pytest.mark.parametrize("motor", [REFERENCE, SECOND])
def test_motor_passes_and_table_reproducible(tmp_path, motor):
    assert run(tmp_path, motor) == 0
    for ext in ("c", "h"):
        name = f"{motor.stem}_params.{ext}"
        assert (tmp_path / "tables" / name).read_bytes() == (REPO / "tables" / name).read_bytes()


# REQ-TUNE-007: the report and its Bode / step plots.
def test_report_with_plots(tmp_path):
    rc = qt.main([str(REFERENCE), "--out-dir", str(tmp_path), "--table-dir", str(tmp_path)])
    assert rc == 0
    report = (tmp_path / "report.md").read_text()
    assert "Status: **PASSED**" in report
    for loop in ("current_d", "current_q", "speed", "field_weakening", "PLL"):
        assert (tmp_path / f"loop_{loop}.png").stat().st_size > 1000
        assert f"loop_{loop}.png" in report


# REQ-TUNE-005: the document's current-loop design gives PM 65.5 deg; every discrete loop >= 45 deg.
def test_loop_margins_reference():
    cfg = qt.load_config(REFERENCE, [])
    ds = qt.design_loops(cfg, qt.make_bases(cfg))
    res = qt.run_analysis(cfg, ds)
    rc, rd = res["current q"]
    # K T = 0.5 on 1 / (s (T s + 1)): crossover w T = 0.4551, PM = 90 - atan(0.4551) = 65.5 deg
    assert rc.pm_deg == pytest.approx(65.53, abs=0.1)
    for _name, (_c, d) in res.items():
        assert d.stable and d.pm_deg >= 45.0
