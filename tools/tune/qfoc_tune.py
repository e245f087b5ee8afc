#!/usr/bin/env python3
"""qfoc tuning and scaling tool: motor TOML -> parameter table, bound checks, loop analysis.

Usage:
    python3 tools/tune/qfoc_tune.py MOTOR.toml [--out-dir DIR] [--table-dir DIR]
                                    [--set section.key=value ...] [--no-plots]
    python3 tools/tune/qfoc_tune.py --motor-file-doc      (prints docs/motor-file.md)

What it does (every equation number is the source document's, chapter 2 unless named):

1. Reads the motor-and-inverter file (sections [motor], [inverter], [sensing],
   [scaling]; optional [design], [limits], [drive] and [demo]; SCHEMA lists every key
   with its unit, range, default and rule, docs/motor-file.md is generated from it) and
   validates presence, type, sign and range of every key; refuses unknown keys, and the
   files that break a rule between keys (check_rules(): the f_base rule of
   specs/scaling.md section 2, protection thresholds their sensors cannot read, [drive]
   speeds and currents outside the motor's range), naming the key as section.key;
   refuses the values of the physical keys outside their plausible ranges (PLAUSIBLE: a
   unit slip such as mH typed as H), with the value x 1e-3 or x 1e3 inside the range as
   "did you mean"; warns when L_q < L_d (an IPM motor has L_q > L_d).
2. Derives the per-unit bases and every scale factor of specs/scaling.md, with the flux
   base psi_base = 2^s V_base / w_base, L_base = psi_base / I_base (table layout 4,
   drive.psi_shift): s = scaling.psi_shift, or the smallest s in 0 .. 4 for which every
   flux-unit bound holds (derive_psi_shift()); a speed (pu) times a flux (pu) is then a
   voltage of 2^s V_base, and the flux observer's g = T w_base / 2^s, kg = K_gain 2^s / w_base.
3. Designs the loops:
   - current loops d and q (pole cancellation tau_c = L / R, K T = 0.5, so
     k_cp = L / (2 T_sigma), k_ci = R / (2 T_sigma), "Current Loop"),
   - speed loop from a bandwidth target: crossover w_sc = the smaller of
     design.speed_crossover_ratio x 1 / (2 T_sigma) and 1 / (2 T_ssigma), T_ssigma =
     2 T_sigma + T_filter + T_sam ("Speed Loop"); ksp = w_sc / (K_t b) (= K / (2 K_t b), K =
     1 / T_ssigma, at the default); PI zero design.speed_zero_ratio below the crossover,
     tau_s = ratio / w_sc (formerly J / B, seconds on a compressor),
   - field-weakening PI (integral-dominant, crossover a decade below the current loop),
   - PLL (2-27, 2-28) and flux observer (2-19 .. 2-24) exactly as sim/estim.c est_tune(),
   - low-pass coefficients alpha = omega_c / f (2-33, 2-34),
   and converts every gain to the library representation (pi.h: Q15 mantissa with a
   LEFT shift; flux.h: Q15 mantissa with a RIGHT shift), reporting the rounding error.
4. Checks the fixed-point bounds of chapter 2 for this scaling: Clarke (2-5, 2-6),
   Park with exact angle (2-9, 2-10) and with angle error (2-11, 2-12), the flux
   observer's steady state (2-25, 2-26), the fluxes and inductances in the flux base
   (flux_unit_bounds()), the inverse transforms with harmonics.
5. Analyses the loops (chapter 4) with scipy.signal: continuous models as the
   document writes them and discrete models (ZOH at T_s plus one sample of
   computation delay z^-1) with the quantised gains; phase and gain margins,
   closed-loop -3 dB bandwidth, step responses; Bode/step PNGs.  The speed-loop check
   (speed_check()) simulates the ramp from the hand-over speed with a load step and the
   stored speed PI; more than 1 % speed error 1 s after the ramp's end fails the design.
6. Derives the drive configuration (include/qfoc/drive_cfg.h, table layout version 2:
   start-up, protection, link and feature settings) from [drive] and its defaults
   (drive_fields()), checks every field's range and the cross-field conditions of
   params.h (range_checks()).
7. Writes <table-dir>/<name>_params.c/.h (qfoc_param_table_t of include/qfoc/params.h,
   CRC-32/ISO-HDLC over the little-endian serialisation) and <out-dir>/report.md.

Exit codes: 0 = table and report written; 1 = refused: the input breaks a range or rule of
the schema or has an unknown key (nothing is written), or a bound or a loop check failed
(the report is written and marked FAILED, no table is written); 2 = malformed input (file
unreadable, TOML syntax, missing key, wrong type or sign).

Requirements: REQ-TUNE-001 (input), REQ-TUNE-002 (bases and scale factors),
REQ-TUNE-003 (gains), REQ-TUNE-004 (bound check), REQ-TUNE-005 (loop analysis),
REQ-TUNE-006 (table and CRC), REQ-TUNE-007 (report) in specs/requirements/tune.md.
"""
from __future__ import annotations

import argparse
import difflib
import math
import os
import sys
import tomllib
import warnings
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

REPO_ROOT = Path(__file__).resolve().parents[2]
TOOL_PATH = "tools/tune/qfoc_tune.py"
Q15_MAX = 32767
PARAMS_MAGIC = 0x434F4651          # "QFOC" little-endian (params.h QFOC_PARAMS_MAGIC)
PARAMS_VERSION = 5                 # params.h QFOC_PARAMS_VERSION (3: MTPA speed, derating,
                                   # the flux check's error model; 4: the flux base
                                   # drive.psi_shift; 5: the current sensing mode and the
                                   # single shunt's sampling)
SENSING_MODES = {"phases": 0, "shunt": 1}  # drive_cfg.h QFOC_SENSING_PHASES, _SHUNT
SHUNT_HOLD_MAX = 16                # drive_cfg.h QFOC_DRIVE_SHUNT_HOLD_MAX
PSI_SHIFT_MAX = 4                  # drive_cfg.h QFOC_DRIVE_PSI_SHIFT_MAX: psi_base at most
                                   # 2^4 V_base / w_base
FLUX_STATE_MAX_Q15 = 524287        # (2^31 - 1) / 4096: flux state Q4.27 range in Q15 counts
PM_MIN_DEG = 45.0                  # required phase margin of every discrete loop
COARSE_GAIN_PCT = 1.0              # rounding errors above this are listed as warnings
SPEED_ZERO_RATIO = 5.0             # default design.speed_zero_ratio
SPEED_CHECK_ERR_PCT = 1.0          # the speed-loop check: largest |speed error|, % of target,
SPEED_CHECK_AFTER_S = 1.0          # from this long after the ramp's end,
SPEED_CHECK_SPAN_S = 1.0           # over this long
SQRT3 = math.sqrt(3.0)
# The drive's tick period (qfoc_drive_tick, 1 kHz): field weakening and the speed loop run in it.
T_TICK_S = 1e-3
# The largest field-weakening crossover in units of 1 / T_tick (0.2: 200 rad/s, 32 Hz).
FW_TICK_WT = 0.2


class InputError(Exception):
    """Malformed input: unreadable file, syntax, missing key, wrong type or sign (exit code 2)."""


# --------------------------------------------------------------------------------------
# Input schema
# --------------------------------------------------------------------------------------

class Refusal(InputError):
    """Input the tool refuses: it would make an unsafe or wrong table (exit code 1)."""


class _Required:
    """Marker of a key without a default."""

    def __repr__(self) -> str:
        return "required"


REQUIRED = _Required()
# The library reads 12-bit ADC codes (include/qfoc/drive.h; src/qfoc_drive.c drv_adc12
# saturates larger codes to 4095; 4096 codes = V_base, 2048 codes = I_base).
ADC_BITS = 12
ADC_CODES = 1 << ADC_BITS
# Ranges: (low, high, ends); None = unbounded; ends "[]", "(]", "[)" or "()" say which ends
# are included.
POS = (0, None, "(]")
NONNEG = (0, None, "[]")
ANY = (None, None, "[]")


@dataclass(frozen=True)
class Key:
    """One key of the motor file: the single description the validation, the defaults,
    the report and docs/motor-file.md (--motor-file-doc) are made from."""
    section: str
    key: str
    kind: str           # "str" | "int" | "num"
    unit: str
    rng: tuple          # (low, high, ends), see POS
    default: object     # REQUIRED, a value, or a str: the text of a derived default
    desc: str
    rule: str           # where the value goes, and the rule that checks it

    @property
    def name(self) -> str:
        """section.key, as the messages name it."""
        return f"{self.section}.{self.key}"

    @property
    def value_default(self) -> object:
        """The default value; None when derived (resolve_defaults) or required."""
        return None if self.default is REQUIRED or isinstance(self.default, str) else self.default


def _k(section: str, key: str, kind: str, unit: str, rng: tuple, default: object, desc: str,
       rule: str) -> Key:
    return Key(section, key, kind, unit, rng, default, desc, rule)


RULE_FBASE = ("specs/scaling.md section 2: f_base >= 1.25 x the highest electrical frequency "
              "(field weakening included)")
RULE_DERATE = ("'derating': the derating window of each temperature starts below its trip "
               "(drive.t_ipm_derate_degc < drive.t_ipm_max_degc, drive.t_pcb_derate_degc < "
               "drive.t_pcb_max_degc) and the derated speed lies in drive.rpm_min .. "
               "drive.rpm_max")
RULE_VDC_READ = (f"a DC-bus threshold must lie within what the bus sensor reads: at least one "
                 f"code and below the largest reading, {ADC_CODES - 1} codes of the "
                 f"{ADC_BITS}-bit ADC with V_base = {ADC_CODES} codes (the Q15 reading is "
                 f"code x 8, at most {(ADC_CODES - 1) * 8}; over-voltage trips when the reading "
                 f"is above vdc_ov, under-voltage when it is below vdc_uv)")
RULE_I_READ = (f"the over-current trip must be below the current sensor's largest reading on "
               f"both sides of the offset: (2047 - drive.offset_window_counts) codes of the "
               f"{ADC_BITS}-bit ADC with I_base = 2048 codes (the offset is calibrated within "
               f"2048 +- offset_window; the trip fires when |i| is above i_trip)")
RULE_SPEED = "every [drive] speed lies within 0 .. the motor's largest speed"
RULE_VDC_OPERATING = ("the DC-bus protection thresholds lie outside the operating bus: "
                      "limits.vdc_uv_v <= inverter.vdc_min_v and limits.vdc_ov_v >= "
                      "inverter.vdc_max_v, else the drive trips in normal operation")
RULE_CURRENT = "params.h: drive.i_align, i_start, tc_amp_max <= i_max"
RULE_SHUNT = ("'shunt window': a single-shunt measurement window, sensing.shunt_settle_ns + "
              "sensing.shunt_sample_ns in PWM-timer ticks (each rounded up: ceil(ns f_timer / "
              "1e9)), fits four times in the PWM counter's period (params.h 4 (shunt_settle + "
              "shunt_sample) <= svpwm.period, checked in both modes), and shunt_settle_ns is at "
              "least inverter.dead_time_s (a sample in the dead time reads the wrong phase)")
RULE_PSI = (f"the flux base psi_base = 2^s V_base / w_base (s = scaling.psi_shift, an integer "
            f"0 .. {PSI_SHIFT_MAX}, drive_cfg.h QFOC_DRIVE_PSI_SHIFT_MAX; L_base = psi_base / "
            "I_base) holds every flux and inductance of the table: the flux-estimate bounds "
            "2-25, 2-26 (the active flux psi_f + |L_d - L_q| i_max), psi_f, pll.mag_min and "
            "drive.flux_tol below 1 pu (Q15), ld, lq, flux.l, drive.ld_hs and drive.lq_hs below "
            "8 pu (Q12), and flux.kg = K_gain 2^s / w_base below 1 pu (Q15)")

SCHEMA: tuple = (
    # [motor]
    _k("motor", "name", "str", "", ANY, REQUIRED, "motor name",
       "table comments and report title"),
    _k("motor", "pole_pairs", "int", "", (1, 16, "[]"), REQUIRED, "pole pairs n_p",
       "drive_cfg.h pole_pairs 1 .. 16; rpm to electrical speed (n_p / 60); rule 'f_base'"),
    _k("motor", "rs_ohm", "num", "ohm", POS, REQUIRED, "stator resistance per phase",
       "current-loop zero tau_c = L / R; flux.r = R / Z_base"),
    _k("motor", "ld_h", "num", "H", POS, REQUIRED, "d-axis inductance",
       "d current loop k_cp = L_d / (2 T_sigma); ld; field-weakening plant gain"),
    _k("motor", "lq_h", "num", "H", POS, REQUIRED, "q-axis inductance",
       "q current loop k_cp = L_q / (2 T_sigma); lq; flux.l"),
    _k("motor", "psi_f_wb", "num", "Wb", POS, REQUIRED, "magnet flux linkage (peak)",
       "K_t = 3/2 n_p psi_f (speed loop); psi_f; flux bounds 2-25, 2-26"),
    _k("motor", "j_kgm2", "num", "kg m^2", POS, REQUIRED, "inertia (rotor and load)",
       "speed loop b = 1 / J, pi_speed.kp = w_sc J / K_t; the speed-loop check"),
    _k("motor", "b_nms", "num", "N m s", POS, REQUIRED, "viscous friction",
       "speed loop a = B / J; the speed-loop check"),
    _k("motor", "rated_speed_rpm", "num", "rpm", POS, REQUIRED, "rated speed (mechanical)",
       "<= motor.max_speed_rpm; defaults of drive.tc_speed_max_rpm, drive.stall_err_rpm, "
       "design.observer_min_speed_rpm"),
    _k("motor", "max_speed_rpm", "num", "rpm", POS, REQUIRED,
       "maximum speed (mechanical), field weakening included",
       "rule 'f_base'; defaults of limits.speed_max_rpm, drive.rpm_max, drive.para_speed_rpm"),
    _k("motor", "rated_current_a", "num", "A", POS, REQUIRED, "rated phase current (peak)",
       "defaults of limits.i_max_a and the [drive] currents"),
    _k("motor", "nominal_torque_nm", "num", "N m", NONNEG, REQUIRED, "nominal load torque",
       "the simulator's load (sim/motor.c); default of demo.start_load_nm; not in the table"),
    _k("motor", "ld_hs_h", "num", "H", POS, "motor.ld_h",
       "d-axis inductance at high speed (formerly motorParaChange, specs/equations.md section 8)",
       "drive.ld_hs, used above drive.para_speed_rpm"),
    _k("motor", "lq_hs_h", "num", "H", POS, "motor.lq_h",
       "q-axis inductance at high speed (formerly motorParaChange, specs/equations.md section 8)",
       "drive.lq_hs, used above drive.para_speed_rpm"),
    # [inverter]
    _k("inverter", "vdc_nominal_v", "num", "V", POS, REQUIRED, "nominal DC bus",
       "inverter.vdc_min_v <= vdc_nominal_v <= inverter.vdc_max_v"),
    _k("inverter", "vdc_min_v", "num", "V", POS, REQUIRED, "lowest DC bus",
       "field-weakening plant gain; defaults of limits.vdc_uv_v, limits.vdc_svpwm_min_v"),
    _k("inverter", "vdc_max_v", "num", "V", POS, REQUIRED, "highest DC bus",
       "current-PI output limit V_dc,max / sqrt 3; inverse-transform bounds; default of "
       "limits.vdc_ov_v"),
    _k("inverter", "f_pwm_hz", "num", "Hz", (1000, 40000, "[]"), REQUIRED,
       "PWM and control frequency (an integer)",
       "params.h f_pwm_hz 1000 .. 40000; T_s = 1 / f_pwm"),
    _k("inverter", "f_timer_hz", "num", "Hz", POS, REQUIRED, "PWM counter clock",
       "svpwm.period = f_timer / (2 f_pwm), params.h 100 .. 32767"),
    _k("inverter", "dead_time_s", "num", "s", NONNEG, REQUIRED, "dead time",
       "svpwm.dt_comp = t_d f_timer / 2, params.h <= period / 4"),
    # [sensing]
    _k("sensing", "i_full_scale_a", "num", "A", POS, REQUIRED,
       "phase-current sensing full scale = I_base (2048 ADC codes from the offset)",
       "specs/scaling.md section 2 (I_base); rule 'over-current trip'"),
    _k("sensing", "vdc_full_scale_v", "num", "V", POS, REQUIRED,
       "DC-bus sensing full scale = V_base (4096 ADC codes)",
       "specs/scaling.md section 2 (V_base); rule 'DC-bus thresholds'"),
    _k("sensing", "adc_bits", "int", "bits", (ADC_BITS, ADC_BITS, "[]"), REQUIRED,
       "ADC resolution",
       f"the library reads {ADC_BITS}-bit codes (include/qfoc/drive.h, src/qfoc_drive.c "
       f"drv_adc12): only {ADC_BITS} is accepted; a wider converter's result is shifted to "
       f"{ADC_BITS} bits by the port"),
    _k("sensing", "mode", "str", "", ANY, "phases",
       "current sensing: \"phases\" (two phase-current sensors) or \"shunt\" (one shunt in "
       "the DC link, two samples per period, specs/equations.md section 13)",
       "drive.sensing; the drive's fast step for the mode (drive.h, drive_shunt.h)"),
    _k("sensing", "shunt_settle_ns", "num", "ns", NONNEG,
       "inverter.dead_time_s + 1000 ns (a ringing allowance)",
       "single shunt: from a gate edge to a settled DC-link current (dead time plus ringing)",
       "drive.shunt_settle in PWM-timer ticks, rounded up; rule 'shunt window'"),
    _k("sensing", "shunt_sample_ns", "num", "ns", POS, 500.0,
       "single shunt: the ADC's sample-and-hold time",
       "drive.shunt_sample in PWM-timer ticks, rounded up; rule 'shunt window'"),
    _k("sensing", "shunt_hold", "int", "periods", (1, SHUNT_HOLD_MAX, "[]"), 4,
       "single shunt: periods the last reconstructed currents may stand in for a missed "
       "measurement before the sensing is declared lost (the drive trips)",
       "drive.shunt_hold"),
    # [scaling]
    _k("scaling", "f_base_hz", "num", "Hz", POS, REQUIRED, "electrical frequency of speed 1.0",
       "specs/scaling.md section 2 (f_base); rule 'f_base'"),
    _k("scaling", "psi_shift", "int", "", (0, PSI_SHIFT_MAX, "[]"),
       f"the smallest shift in 0 .. {PSI_SHIFT_MAX} whose flux base holds the machine "
       "(rule 'flux base')",
       "flux base: psi_base = 2^psi_shift V_base / w_base, L_base = psi_base / I_base",
       "drive.psi_shift; every flux (Q15 of psi_base) and inductance (Q12 of L_base) of the "
       "table; a speed times a flux is a voltage of 2^psi_shift V_base (specs/scaling.md "
       "section 2); rule 'flux base'"),
    # [design]: loop-design choices
    _k("design", "t_filter_current_s", "num", "s", NONNEG, 0.0,
       "current-sensing filter time constant T_filter of T_sigma", "current and speed loops"),
    _k("design", "speed_crossover_ratio", "num", "", POS, 0.1,
       "largest speed-loop crossover / current-loop crossover 1 / (2 T_sigma) (cascade "
       "separation)", "default of design.speed_crossover_hz"),
    _k("design", "speed_crossover_hz", "num", "Hz", POS,
       "the smaller of design.speed_crossover_ratio x 1 / (2 pi 2 T_sigma) (the current-loop "
       "crossover) and 1 / (2 pi 2 T_ssigma) (K T = 0.5 on the speed path's lag T_ssigma)",
       "speed-loop crossover (bandwidth target) w_sc = 2 pi f",
       "pi_speed.kp = w_sc J / K_t; default of design.speed_tau_s"),
    _k("design", "speed_zero_ratio", "num", "", POS, SPEED_ZERO_RATIO,
       "speed-loop crossover / speed PI zero: the zero 1 / tau_s lies this factor below the "
       "crossover (symmetric optimum: 2 .. 4 on a pure lag; 5 leaves a discrete phase margin "
       "of about 49 deg with the speed filter's lag and the tick's delay, 4 about 46 deg)",
       "default of design.speed_tau_s"),
    _k("design", "speed_tau_s", "num", "s", POS,
       "design.speed_zero_ratio / (2 pi design.speed_crossover_hz)",
       "speed PI integral time tau_s = kp / ki (the PI zero at 1 / tau_s); formerly "
       "J / B", "pi_speed.ki = kp T_sam / tau_s; the speed-loop check"),
    _k("design", "speed_check_rpm", "num", "rpm", POS, "0.5 x motor.rated_speed_rpm",
       "speed-loop check: target of the ramp from drive.of_speed_rpm (the hand-over)",
       f"the speed-loop check: |speed error| <= {SPEED_CHECK_ERR_PCT:g} % of the target from "
       f"{SPEED_CHECK_AFTER_S:g} s after the ramp's end"),
    _k("design", "speed_check_load_nm", "num", "N m", NONNEG, "motor.nominal_torque_nm",
       "speed-loop check: load torque, a step when the ramp starts (the loop holds the "
       "start speed unloaded before)", "the speed-loop check"),
    _k("design", "speed_t_sam_s", "num", "s", POS, 1.0e-3,
       "speed-loop sample time T_sam (the speed PI runs in the drive's 1 ms tick)",
       "speed loop T_ssigma and pi_speed.ki"),
    _k("design", "pll_wn_hz", "num", "Hz", POS, 100.0, "PLL natural frequency",
       "pll.pi (2-27, 2-28; est_design_default)"),
    _k("design", "pll_zeta", "num", "", POS, 0.9, "PLL damping", "pll.pi.kp"),
    _k("design", "pll_clamp", "num", "", (0, 1, "(]"), 0.75, "PLL normalised-error clamp",
       "pll.err_clamp (Q15)"),
    _k("design", "pll_mag_min", "num", "", POS, 0.05,
       "PLL coasting threshold, fraction of psi_f", "pll.mag_min"),
    _k("design", "speed_fc_hz", "num", "Hz", POS, 20.0,
       "PLL speed low-pass corner", "pll.speed_alpha (2-34); speed-loop T_filter"),
    _k("design", "kg_rad_s", "num", "rad/s", POS, 100.0,
       "flux observer high-pass corner K_gain", "flux.kg; flux bounds 2-25, 2-26"),
    _k("design", "vdc_fc_hz", "num", "Hz", POS, 100.0, "DC-bus low-pass corner",
       "alpha_vdc (2-34)"),
    _k("design", "fw_v_max", "num", "", (0, 1, "(]"), 0.92,
       "field-weakening reference: |v| / (V_dc / sqrt 3)", "v_max; default of drive.fw_level"),
    _k("design", "fw_crossover_ratio", "num", "", POS, 0.1,
       "FW crossover / current-loop crossover", "pi_fw"),
    _k("design", "fw_zero_ratio", "num", "", POS, 4.0,
       "FW PI zero / FW crossover (integral-dominant)", "pi_fw.kp"),
    _k("design", "deadband_a", "num", "A", NONNEG, "sensing.i_full_scale_a / 80",
       "dead-time compensation current dead band", "svpwm.i_deadband"),
    _k("design", "clarke_phase_dev_deg", "num", "deg", NONNEG, 10.0,
       "Clarke bound: phase of i_v within 120 deg +- this", "bounds 2-5 .. 2-12"),
    _k("design", "park_angle_err_deg", "num", "deg", NONNEG, 180.0,
       "Park bound: largest angle error considered", "bounds 2-11, 2-12"),
    _k("design", "v_harmonic_fraction", "num", "", NONNEG, 0.10,
       "inverse Park bound: A_d = A_q = fraction x |v|", "inverse-transform bounds"),
    _k("design", "i_offset_a", "num", "A", NONNEG, "sensing.i_full_scale_a / 100",
       "flux bound: DC current offset", "flux bound 2-26"),
    _k("design", "observer_min_speed_rpm", "num", "rpm", POS, "0.1 x motor.rated_speed_rpm",
       "flux bound: lowest observer speed", "flux bounds 2-25, 2-26"),
    # [limits]: protection limits
    _k("limits", "i_max_a", "num", "A", POS, "motor.rated_current_a", "current-vector limit",
       "i_max; speed-PI and FW-PI output limits; rules 'currents', 'over-current trip'"),
    _k("limits", "i_trip_a", "num", "A", POS, "1.5 x limits.i_max_a", "phase over-current trip",
       "i_trip; Clarke and Park bounds; rule 'over-current trip'"),
    _k("limits", "speed_max_rpm", "num", "rpm", POS, "motor.max_speed_rpm",
       "largest speed (mechanical)", "speed_max; rules 'f_base', 'speeds'"),
    _k("limits", "vdc_uv_v", "num", "V", POS, "0.9 x inverter.vdc_min_v", "DC-bus under-voltage",
       "vdc_uv; rule 'DC-bus thresholds'"),
    _k("limits", "vdc_ov_v", "num", "V", POS, "1.05 x inverter.vdc_max_v", "DC-bus over-voltage",
       "vdc_ov; rule 'DC-bus thresholds'"),
    _k("limits", "vdc_svpwm_min_v", "num", "V", POS, "0.4 x inverter.vdc_min_v",
       "smallest DC bus used by SVPWM", "svpwm.vdc_min; rule 'DC-bus thresholds'"),
    # [drive]: drive configuration (include/qfoc/drive_cfg.h); speeds mechanical
    _k("drive", "rpm_min", "num", "rpm", POS, 1000.0, "smallest running target",
       "drive.rpm_min; rule 'speeds'"),
    _k("drive", "rpm_max", "num", "rpm", (1, 65535, "[]"),
       "motor.max_speed_rpm, lowered to the largest rpm whose Q15 speed (rpm k_rpm + 2048) "
       ">> 12 is within speed_max", "largest target",
       "drive.rpm_max; rule 'speeds'; params.h (rpm_max k_rpm + 2048) >> 12 <= "
       "speed_max"),
    _k("drive", "accel_rpm_s", "num", "rpm/s", POS, 3000.0, "closed-loop speed ramp",
       "drive.speed_ramp"),
    _k("drive", "precharge_ms", "int", "ms", (1, 60000, "[]"), 200,
       "DC bus above vdc_uv this long before offset calibration", "drive.precharge_ms"),
    _k("drive", "offset_shift", "int", "", (4, 10, "[]"), 6,
       "2^offset_shift current samples averaged per offset", "drive.offset_shift"),
    _k("drive", "offset_window_counts", "int", "ADC codes", (0, 2047, "[]"), 100,
       "largest |offset - 2048| (100 = 4.9 % of the 2048-code half scale)",
       "drive.offset_window; rule 'over-current trip'"),
    _k("drive", "i_align_a", "num", "A", POS, "0.5 x motor.rated_current_a",
       "ALIGN d current", "drive.i_align; rule 'currents'"),
    _k("drive", "align_ms", "int", "ms", (2, 60000, "[]"), 300,
       "ALIGN time (ramp over the first half, hold to 3/4, half the current for the last "
       "quarter: the inverter's error learnt from the two holds)", "drive.align_ms"),
    _k("drive", "i_start_a", "num", "A", POS, "motor.rated_current_a",
       "OPEN_LOOP (I/f) current amplitude", "drive.i_start; rule 'currents'"),
    _k("drive", "of_accel_rpm_s", "num", "rpm/s", POS, 1000.0, "OPEN_LOOP speed ramp",
       "drive.of_accel"),
    _k("drive", "of_speed_rpm", "num", "rpm", POS, 1000.0, "OPEN_LOOP end speed",
       "drive.of_speed; rule 'speeds'"),
    _k("drive", "ho_angle_deg", "num", "deg", (0, 90, "(]"), 15.0,
       "handover: |theta_est - theta_ol| below this, electrical", "drive.ho_angle"),
    _k("drive", "ho_dwell_ms", "int", "ms", (1, 60000, "[]"), 50,
       "handover: angle condition held this long", "drive.ho_dwell_ms"),
    _k("drive", "ol_timeout_ms", "int", "ms", (1, 60000, "[]"), 4000,
       "no handover this long after OPEN_LOOP entry: stall (the handover waits for cl_hold_ms "
       "after the ALIGN entry)", "drive.ol_timeout_ms"),
    _k("drive", "ho_retries", "int", "", (0, 3, "[]"), 2,
       "start retries: an OPEN_LOOP without a handover after ol_timeout_ms goes back "
       "through CATCH and ALIGN to a new I/f start with the start current raised by a "
       "quarter per retry (at most i_max), this many times before STALL",
       "drive.ho_retries"),
    _k("drive", "cl_hold_ms", "int", "ms", (0, 60000, "[]"), 2000,
       "no handover and no ramp to the target before this long after the ALIGN entry; the "
       "handover comes at convergence (the I/f ramp at of_speed and the estimator locked "
       "for ho_dwell_ms) once this time has passed; 0: at convergence alone (2 s: "
       "specs/equations.md section 8.3)",
       "drive.cl_hold_ms"),
    _k("drive", "t_ipm_max_degc", "num", "degC", (-40, 200, "[)"), 110.0,
       "IPM over-temperature",
       "drive.t_ipm_max; the temperature input reads -40.0 .. 200.0 degC (drive_cfg.h; the "
       "reference port saturates its NTC there): a threshold of 200 degC or more never trips"),
    _k("drive", "t_pcb_max_degc", "num", "degC", (-40, 200, "[)"), 100.0,
       "PCB over-temperature",
       "drive.t_pcb_max; the temperature input reads -40.0 .. 200.0 degC (drive_cfg.h; the "
       "reference port saturates its NTC there): a threshold of 200 degC or more never trips"),
    _k("drive", "vdc_ms", "int", "ms", (1, 10, "[]"), 2, "DC-bus OV/UV debounce",
       "drive.vdc_ms"),
    _k("drive", "temp_ms", "int", "ms", (1, 10, "[]"), 10, "over-temperature debounce",
       "drive.temp_ms"),
    _k("drive", "stall_err_rpm", "num", "rpm", POS, "0.3 x motor.rated_speed_rpm",
       "stall: |speed ref - estimate| above this", "drive.stall_err; rule 'speeds'"),
    _k("drive", "flux_tol_frac", "num", "", POS, 0.5,
       "stall: flux-magnitude error above this fraction of psi_f", "drive.flux_tol"),
    _k("drive", "stall_ms", "int", "ms", (1, 60000, "[]"), 500, "stall condition held this long",
       "drive.stall_ms"),
    _k("drive", "phase_fc_hz", "num", "Hz", POS, 5.0, "phase-loss monitor low-pass corner",
       "drive.phase_alpha (2-34)"),
    _k("drive", "phase_i_min_a", "num", "A", POS, "0.1 x motor.rated_current_a",
       "phase loss checked above this filtered |i|", "drive.phase_i_min; rule 'currents'"),
    _k("drive", "phase_ratio", "num", "", (0, 1, "[]"), 0.25,
       "phase loss: smallest / largest filtered |i| below this", "drive.phase_ratio"),
    _k("drive", "phase_ms", "int", "ms", (1, 60000, "[]"), 100,
       "phase-loss condition held this long", "drive.phase_ms"),
    _k("drive", "link_timeout_ms", "int", "ms", (1, 60000, "[]"), 500,
       "command link lost after this long without a valid command", "drive.link_timeout_ms"),
    _k("drive", "clear_ms", "int", "ms", (1, 60000, "[]"), 5000,
       "stopped this long before a fault clear is accepted", "drive.clear_ms"),
    _k("drive", "fw_level", "num", "", (0, 1, "(]"), "design.fw_v_max",
       "field-weakening utilisation target FWK_LVL", "drive.fw_level"),
    _k("drive", "fw_fc_hz", "num", "Hz", POS, 50.0,
       "field-weakening utilisation low-pass corner", "drive.fw_alpha (2-34)"),
    _k("drive", "tc_gain_q15", "int", "Q15 counts", (0, 32767, "[]"), 492,
       "torque-compensation learning gain mu; 492 = 0.015, learning time constant 0.6 s at "
       "1x, 1500 rpm (specs/requirements/trqcomp.md)", "drive.tc_gain"),
    _k("drive", "tc_amp_max_a", "num", "A", NONNEG, "0.5 x motor.rated_current_a",
       "torque-compensation amplitude limit per coefficient", "drive.tc_amp_max; rule 'currents'"),
    _k("drive", "tc_speed_min_rpm", "num", "rpm", NONNEG, 600.0,
       "torque compensation from this speed (the learning law's phase error stays below "
       "44 deg above it)", "drive.tc_speed_min; rule 'speeds'"),
    _k("drive", "tc_speed_max_rpm", "num", "rpm", NONNEG,
       "the highest speed <= motor.rated_speed_rpm with the phase error <= 50 deg",
       "torque compensation up to this speed (the second harmonic learns up to half of it): "
       "its learning law converges while the phase of the current loop, the speed-PI-closed "
       "mechanics, the PLL's speed estimate and the tick's half sample stays within 90 deg "
       "of the model's -90 deg; the default keeps 50 deg, and a window with 90 deg or more "
       "anywhere is refused", "drive.tc_speed_max; rule 'speeds'"),
    _k("drive", "para_speed_rpm", "num", "rpm", POS, "0.7 x motor.max_speed_rpm",
       "high-speed inductances (motor.ld_hs_h, lq_hs_h) above this speed",
       "drive.para_speed; rule 'speeds'"),
    _k("drive", "lin_id_cmd", "int", "", (0, 0x3B, "[]"), 0x10,
       "LIN identifier of the command frame", "drive.lin_id_cmd"),
    _k("drive", "lin_id_status", "int", "", (0, 0x3B, "[]"), 0x11,
       "LIN identifier of the status frame", "drive.lin_id_status, != drive.lin_id_cmd"),
    _k("drive", "can_id_a", "int", "", (0, 0x7FF, "[]"), 0x310,
       "CAN status identifier, even frames", "drive.can_id_a"),
    _k("drive", "can_id_b", "int", "", (0, 0x7FF, "[]"), 0x311,
       "CAN status identifier, odd frames", "drive.can_id_b"),
    _k("drive", "mtpa_speed_rpm", "num", "rpm", NONNEG, "drive.of_speed_rpm",
       "MTPA (maximum torque per ampere, salient motors) above this speed; at or above "
       "limits.speed_max_rpm MTPA is off (i_d = 0 below field weakening)", "drive.mtpa_speed"),
    _k("drive", "t_ipm_derate_degc", "num", "degC", (-40, 200, "[)"),
       "drive.t_ipm_max_degc - 10",
       "derating: above this IPM temperature the speed limit falls linearly to "
       "drive.derate_rpm at drive.t_ipm_max_degc", "drive.t_ipm_derate; rule 'derating'"),
    _k("drive", "t_pcb_derate_degc", "num", "degC", (-40, 200, "[)"),
       "drive.t_pcb_max_degc - 10",
       "derating: the same for the PCB temperature, to drive.t_pcb_max_degc",
       "drive.t_pcb_derate; rule 'derating'"),
    _k("drive", "derate_rpm", "num", "rpm", POS, "drive.rpm_min",
       "derating: the speed limit at the over-temperature trip",
       "drive.rpm_derate; rule 'derating'"),
    _k("drive", "flux_band", "num", "", (0, 1, "(]"), 0.3,
       "fast flux check: the band's fraction of the expected flux (magnet temperature, "
       "inductance errors)", "drive.flux_band"),
    _k("drive", "flux_v_err_v", "num", "V", NONNEG,
       "4 / pi x inverter.dead_time_s x inverter.f_pwm_hz x inverter.vdc_max_v",
       "fast flux check: the estimator's voltage error bound, divided by the speed in the band "
       "(default: the fundamental of a dead-time voltage error as large as the compensated dead "
       "time, so a real dead time from 0 to twice the compensation)", "drive.flux_v_err"),
    _k("drive", "flux_r_err", "num", "", (0, 1, "[)"), 0.3,
       "fast flux check: the resistance error bound, a fraction of motor.rs_ohm (winding "
       "temperature); times R |i| divided by the speed in the band", "drive.flux_r_err"),
    # [demo]: read by the simulator only (sim/scenario.c scn_start_point)
    _k("demo", "start_rpm", "num", "rpm", POS, "motor.rated_speed_rpm / 2, rounded to 10 rpm",
       "target speed of the demonstration's cold start",
       "sim/scenario.c (make demo); not in the table"),
    _k("demo", "start_load_nm", "num", "N m", NONNEG, "motor.nominal_torque_nm",
       "load torque of the demonstration's cold start",
       "sim/scenario.c (make demo); not in the table"),
)

# Plausible ranges of the physical keys (load_config() refuses a value outside, with the value
# x 1e-3 or x 1e3 that falls inside as "did you mean"): each range holds every real
# compressor and traction PMSM and its inverter from 100 W (a 12 V pump or fan motor) to
# 400 kW (a heavy-duty traction machine), and is at most about four decades wide, so that
# a value typed in the wrong unit (mH as H, mOhm as ohm, mWb as Wb, ms as s: a factor 1000)
# falls outside it for most machines.  A range of 1 uH .. 1 H, for instance, would accept a
# compressor's 4.2 mH typed as 4.2 mH = 0.0042 and as 4.2 H alike.  name: (low, high,
# reason); a key whose range is ">= 0" accepts 0 as well.
PLAUSIBLE = {
    "motor.rs_ohm": (0.5e-3, 2.0,
                     "phase resistance: about 1 .. 10 mOhm for 100 .. 400 kW traction machines, "
                     "20 .. 200 mOhm for 12 V motors of 100 W, 0.2 .. 1 ohm for high-voltage "
                     "compressors; a value in mOhm typed as ohm (35 for 0.035) is above 2 ohm"),
    "motor.ld_h": (5e-6, 50e-3,
                   "inductance: about 50 uH .. 3 mH for traction machines, 20 .. 200 uH for "
                   "12 V motors, 1 .. 30 mH for high-voltage compressors; a value in mH "
                   "typed as H (2.6 for 2.6e-3) is above 50 mH"),
    "motor.psi_f_wb": (1e-3, 1.0,
                       "magnet flux linkage: about 3 .. 10 mWb for 12 V motors of 100 W, "
                       "0.03 .. 0.2 Wb for compressors, 0.05 .. 0.3 Wb for traction machines; "
                       "a value in mWb typed as Wb (65 for 0.065) is above 1 Wb"),
    "motor.j_kgm2": (1e-6, 10.0,
                     "inertia of rotor and load: about 1e-6 .. 1e-5 kg m^2 for a 100 W rotor, "
                     "0.01 .. 0.3 kg m^2 for a traction rotor, a few kg m^2 with a reflected "
                     "load"),
    "motor.b_nms": (1e-7, 1.0,
                    "viscous friction: the torque B w at top speed is a small fraction of the "
                    "rated torque (about 1e-7 N m s for a 100 W motor, 0.01 .. 0.1 N m s for a "
                    "traction machine)"),
    "motor.rated_speed_rpm": (100.0, 100000.0,
                              "mechanical speeds of compressors and traction machines: "
                              "1000 .. 20000 rpm; a speed in krpm (6 for 6000) is below "
                              "100 rpm"),
    "motor.rated_current_a": (0.5, 3000.0,
                              "peak phase current: about 5 .. 20 A for 100 W at 12 V or 1 kW "
                              "at 400 V, up to 1500 A for 400 kW; a current in mA is above "
                              "3000 A"),
    "inverter.vdc_nominal_v": (6.0, 1500.0,
                               "DC bus: 12 V, 48 V, 400 V and 800 V classes; a bus in kV "
                               "(0.65 for 650) is below 6 V"),
    "inverter.f_timer_hz": (1e6, 1e9,
                            "PWM counter clock of a microcontroller timer: about 8 MHz .. "
                            "300 MHz"),
    "inverter.dead_time_s": (10e-9, 10e-6,
                             "dead time: about 100 ns (GaN, SiC) .. 5 us (IGBT); a time in us "
                             "typed as s (1 for 1e-6) is above 10 us"),
    "design.t_filter_current_s": (100e-9, 1e-3,
                                  "current-sensing filter: a few us, far below the current "
                                  "loop's T_sigma; a time in us or ms typed as s is above 1 ms"),
    "design.speed_t_sam_s": (20e-6, 20e-3,
                             "speed-loop sample time: one PWM period (25 us at 40 kHz) .. a "
                             "few ms (the drive's tick is 1 ms); a time in ms typed as s (1 "
                             "for 0.001) is above 20 ms"),
    "design.speed_tau_s": (1e-3, 10.0,
                           "speed PI integral time: tens to hundreds of ms; a time in ms typed "
                           "as s (80 for 0.08) is above 10 s"),
}
for _n, _o in (("motor.lq_h", "motor.ld_h"), ("motor.ld_hs_h", "motor.ld_h"),
               ("motor.lq_hs_h", "motor.ld_h"), ("inverter.vdc_min_v", "inverter.vdc_nominal_v"),
               ("inverter.vdc_max_v", "inverter.vdc_nominal_v"),
               ("motor.max_speed_rpm", "motor.rated_speed_rpm")):
    PLAUSIBLE[_n] = PLAUSIBLE[_o]
del _n, _o
# The unit slips the "did you mean" names: factor from the typed to the meant value.
UNIT_SLIPS = {"ohm": {1e-3: "mOhm typed as ohm", 1e3: "kOhm typed as ohm"},
              "H": {1e-3: "mH typed as H", 1e-6: "uH typed as H", 1e3: "H typed as mH"},
              "Wb": {1e-3: "mWb typed as Wb", 1e3: "Wb typed as mWb"},
              "kg m^2": {1e-3: "g m^2 typed as kg m^2", 1e-4: "kg cm^2 typed as kg m^2"},
              "N m s": {1e-3: "mN m s typed as N m s", 1e3: "N m s typed as mN m s"},
              "rpm": {1e3: "krpm typed as rpm"},
              "A": {1e-3: "mA typed as A", 1e3: "kA typed as A"},
              "V": {1e-3: "mV typed as V", 1e3: "kV typed as V"},
              "Hz": {1e3: "kHz typed as Hz", 1e6: "MHz typed as Hz"},
              "s": {1e-3: "ms typed as s", 1e-6: "us typed as s", 1e-9: "ns typed as s"}}


def plausibility_error(k: "Key", value: float) -> str | None:
    """The refusal text of a value outside the plausible range of its key, or None."""
    if k.name not in PLAUSIBLE or (value == 0 and k.rng[0] == 0 and k.rng[2][0] == "["):
        return None
    lo, hi, why = PLAUSIBLE[k.name]
    if lo <= value <= hi:
        return None
    u = unit_text(k)
    text = (f"{k.name} = {fmt(value)}{u}: outside the plausible range {fmt(lo)} .. {fmt(hi)}{u} "
            "of a compressor or traction PMSM drive")
    why = f" (plausible range: {why})"
    slips = UNIT_SLIPS.get(k.unit, {})
    # x 1e-3 or x 1e3 first (the unit slips of the SI prefixes), then the key's other slips
    factors = [1e-3, 1e3] + \
        sorted((f for f in slips if f not in (1e-3, 1e3)), key=lambda f: abs(math.log10(f)))
    for f in factors:
        cand = float(f"{value * f:.12g}")
        if lo <= cand <= hi:
            slip = slips.get(f, f"the value x {fmt(f)}")
            return text + f"; did you mean {k.name} = {fmt(cand)}{u} ({slip})?" + why
    return text + why


SECTIONS = ("motor", "inverter", "sensing", "scaling", "design", "limits", "drive", "demo")
SECTION_TEXT = {
    "motor": "the machine (required)",
    "inverter": "the power stage (required)",
    "sensing": "the current and DC-bus measurement: the per-unit bases (required)",
    "scaling": "the frequency base (required) and the flux base (optional)",
    "design": "loop-design choices (optional, every key has a default)",
    "limits": "protection limits (optional, every key has a default)",
    "drive": "drive configuration, include/qfoc/drive_cfg.h (optional, every key has a default)",
    "demo": "the demonstration's cold start, read by the simulator only (optional)",
}
SCHEMA_BY_NAME = {k.name: k for k in SCHEMA}


def _constraint(rng: tuple) -> str | None:
    """The sign part of a range as check_value() knows it: "pos", "nonneg" or None."""
    if rng[0] == 0:
        return "pos" if rng[2][0] == "(" else "nonneg"
    return None


# Views of SCHEMA in the form the design code reads them.
# (section, key): (kind, constraint, description) of the required keys.
REQUIRED_KEYS = {(k.section, k.key): (k.kind, _constraint(k.rng), k.desc)
                 for k in SCHEMA if k.default is REQUIRED}
# key: (default, constraint, description); default None = derived (resolve_defaults()).
DESIGN_KEYS = {k.key: (k.value_default, _constraint(k.rng), k.desc)
               for k in SCHEMA if k.section == "design"}
LIMIT_KEYS = {k.key: (k.value_default, _constraint(k.rng), k.desc)
              for k in SCHEMA if k.section == "limits"}
DRIVE_KEYS = {k.key: (k.value_default, _constraint(k.rng), k.desc)
              for k in SCHEMA if k.section == "drive"}
DEMO_KEYS = {k.key: (k.value_default, _constraint(k.rng), k.desc)
             for k in SCHEMA if k.section == "demo"}
# Optional [motor] keys: the inductances used above drive.para_speed (motorParaChange).
OPTIONAL_MOTOR_KEYS = {k.key: (_constraint(k.rng), k.desc) for k in SCHEMA
                       if k.section == "motor" and k.default is not REQUIRED}
# [drive] keys that must be integers (times, counts, identifiers, the gain in counts).
DRIVE_INT_KEYS = {k.key for k in SCHEMA if k.section == "drive" and k.kind == "int"}

OPTIONAL_SECTIONS = {"design": DESIGN_KEYS, "limits": LIMIT_KEYS, "drive": DRIVE_KEYS}


def range_text(rng: tuple) -> str:
    """A range as the messages and docs/motor-file.md write it."""
    lo, hi, ends = rng
    if lo is None and hi is None:
        return "any"
    if hi is None:
        return ("> " if ends[0] == "(" else ">= ") + fmt(lo)
    if lo == hi:
        return f"= {fmt(lo)}"
    if ends == "[]":
        return f"{fmt(lo)} .. {fmt(hi)}"
    return (f"{fmt(lo)} {'<' if ends[0] == '(' else '<='} x "
            f"{'<' if ends[1] == ')' else '<='} {fmt(hi)}")


def in_range(value: float, rng: tuple) -> bool:
    """True when value lies within rng."""
    lo, hi, ends = rng
    if lo is not None and (value < lo or (ends[0] == "(" and value == lo)):
        return False
    if hi is not None and (value > hi or (ends[1] == ")" and value == hi)):
        return False
    return True


def suggest(word: str, choices) -> str:
    """' (did you mean X?)' for the closest known name, or ''."""
    close = difflib.get_close_matches(word, sorted(choices), n=1, cutoff=0.6)
    return f" (did you mean {close[0]}?)" if close else ""


def known_keys(section: str) -> set:
    """The keys of one section of the motor file."""
    return {k.key for k in SCHEMA if k.section == section}


def unknown_key_error(where: str, section: str, key: str) -> Refusal:
    """The refusal of a key or section the tool does not use, with a close match."""
    if section not in SECTIONS:
        hint = suggest(section, SECTIONS)
        hint = hint.replace("mean ", "mean [").replace("?)", "]?)") if hint else ""
        return Refusal(f"{where}unknown section [{section}]{hint}: the "
                       f"motor file has the sections {', '.join(f'[{s}]' for s in SECTIONS)} "
                       "(docs/motor-file.md)")
    hint = suggest(key, known_keys(section)).replace("mean ", f"mean {section}.")
    return Refusal(f"{where}unknown key {section}.{key}{hint}: "
                   f"not a key of [{section}] (docs/motor-file.md lists every key); a key the "
                   "tool does not use would be silently ignored")


def parse_override(text: str) -> tuple[str, str, object]:
    """Parse one --set argument 'section.key=value' (value in TOML syntax, or a bare string)."""
    if "=" not in text or "." not in text.split("=", 1)[0]:
        raise InputError(f"--set {text!r}: expected section.key=value")
    lhs, rhs = text.split("=", 1)
    section, key = lhs.strip().split(".", 1)
    try:
        value = tomllib.loads(f"v = {rhs.strip()}")["v"]
    except tomllib.TOMLDecodeError:
        value = rhs.strip()
    if section not in SECTIONS or key not in known_keys(section):
        raise unknown_key_error(f"--set {text!r}: ", section, key)
    return section, key, value


def check_value(where: str, value: object, kind: str, constraint: str | None) -> object:
    """Check one value's type and sign; return it (numbers as float, ints as int)."""
    if kind == "str":
        if not isinstance(value, str) or not value:
            raise InputError(f"{where}: expected a non-empty string, got {value!r}")
        return value
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise InputError(f"{where}: expected a number, got {value!r}")
    if kind == "int" and not (isinstance(value, int) or float(value).is_integer()):
        raise InputError(f"{where}: expected an integer, got {value!r}")
    if not math.isfinite(float(value)):
        raise InputError(f"{where}: not finite: {value!r}")
    if constraint == "pos" and not value > 0:
        raise InputError(f"{where}: must be > 0, got {value!r}")
    if constraint == "nonneg" and not value >= 0:
        raise InputError(f"{where}: must be >= 0, got {value!r}")
    return int(value) if kind == "int" else float(value)


def load_config(path: Path, overrides: list[str]) -> dict:
    """Read and validate the motor file with its --set overrides; return section dicts.

    Raises InputError (exit code 2) for a file that cannot be read as a motor file
    (syntax, missing key, type, sign) and Refusal (exit code 1) for one the tool will not
    make a table of (unknown key, a range or rule of the schema broken)."""
    try:
        with open(path, "rb") as fh:
            raw = tomllib.load(fh)
    except OSError as exc:
        raise InputError(f"{path}: cannot read: {exc.strerror}") from exc
    except tomllib.TOMLDecodeError as exc:
        raise InputError(f"{path}: TOML syntax error: {exc}") from exc
    for text in overrides:
        section, key, value = parse_override(text)
        sec = raw.setdefault(section, {})
        if not isinstance(sec, dict):
            raise InputError(f"{path}: [{section}] must be a table")
        sec[key] = value
    for section, sec in raw.items():
        if section not in SECTIONS and not isinstance(sec, dict):
            raise Refusal(f"{path}: unknown key {section} outside any section: every key "
                          "belongs to a section (docs/motor-file.md)")
        if section not in SECTIONS:
            raise unknown_key_error(f"{path}: ", section, "")
        if not isinstance(sec, dict):
            raise InputError(f"{path}: [{section}] must be a table")
        for key in sec:
            if key not in known_keys(section):
                raise unknown_key_error(f"{path}: ", section, key)
    cfg: dict = {s: {} for s in SECTIONS}
    implausible: list[str] = []
    for k in SCHEMA:
        sec = raw.get(k.section, {})
        if k.key not in sec:
            if k.default is REQUIRED:
                if k.section not in raw:
                    raise InputError(f"{path}: missing section [{k.section}]")
                raise InputError(f"{path}: missing [{k.section}] {k.key} ({k.desc})")
            cfg[k.section][k.key] = k.value_default
            continue
        if k.name == "scaling.psi_shift":
            cfg[k.section][k.key] = psi_shift_value(path, sec[k.key])
            continue
        val = check_value(f"{path}: {k.name}", sec[k.key], k.kind, _constraint(k.rng))
        if k.kind != "str" and not in_range(val, k.rng):
            want = f"must be {fmt(k.rng[0])}" if k.rng[0] == k.rng[1] else \
                f"outside {range_text(k.rng)}"
            rule = k.rule if k.section != "drive" else "include/qfoc/drive_cfg.h " + k.rule
            rule = rule.replace("rule '", "docs/motor-file.md rule '")
            raise Refusal(f"{path}: {k.name} = {fmt(val)}{unit_text(k)}: {want} (rule: {rule})")
        cfg[k.section][k.key] = val
        if k.kind == "num":
            bad = plausibility_error(k, val)
            if bad:
                implausible.append(f"{path}: {bad}")
    if implausible:
        raise Refusal("\n".join(implausible))
    resolve_defaults(cfg)
    cfg["warnings"] = input_warnings(cfg)
    refusals = check_rules(cfg)
    if refusals:
        raise Refusal("\n".join(f"{path}: {r}" for r in refusals))
    return cfg


def psi_shift_value(path: Path, value: object) -> int:
    """scaling.psi_shift as typed: an integer 0 .. PSI_SHIFT_MAX, else refused (exit code 1,
    whatever the type: the flux base of a table is not guessed from a malformed value)."""
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        typed_text, why = repr(value) if isinstance(value, str) else str(value).lower(), \
            "not a number"
    elif not math.isfinite(float(value)) or not float(value).is_integer():
        typed_text, why = fmt(float(value)), "not an integer"
    elif not 0 <= int(value) <= PSI_SHIFT_MAX:
        typed_text, why = str(int(value)), f"outside 0 .. {PSI_SHIFT_MAX}"
    else:
        return int(value)
    raise Refusal(f"{path}: scaling.psi_shift = {typed_text}: {why}; the flux-base shift is an "
                  f"integer 0 .. {PSI_SHIFT_MAX} (rule: docs/motor-file.md rule 'flux base': "
                  f"{RULE_PSI}); leave the key out to have the tool derive it")


# The L_q error the hand-over window should cover: the spread of the robustness campaign
# (REQ-SCN-011, L_d and L_q +-20 %).
HO_LQ_TOL = 0.20


def handover_lq_cover(cfg: dict) -> tuple[float, float]:
    """(r, e): r = L_q i_start / psi_f; an L_q error e turns the flux estimate in OPEN_LOOP by
    about atan(r e) (the voltage model's L_q i_q term against the magnet's flux), so the
    hand-over window ho_angle covers an L_q error down to -e = -tan(ho_angle) / r."""
    m, dr = cfg["motor"], cfg["drive"]
    r = m["lq_h"] * abs(dr["i_start_a"]) / m["psi_f_wb"]
    return r, math.tan(math.radians(dr["ho_angle_deg"])) / r if r > 0 else math.inf


def input_warnings(cfg: dict) -> list[str]:
    """Values the tool accepts but that look wrong: an interior-magnet motor has L_q > L_d;
    a hand-over window that covers less L_q error than HO_LQ_TOL."""
    m = cfg["motor"]
    pairs = [("lq_h", "ld_h", m["lq_h"], m["ld_h"])]
    if m["lq_hs_h"] is not None or m["ld_hs_h"] is not None:
        pairs.append(("lq_hs_h", "ld_hs_h",
                      m["lq_hs_h"] if m["lq_hs_h"] is not None else m["lq_h"],
                      m["ld_hs_h"] if m["ld_hs_h"] is not None else m["ld_h"]))
    out = [f"motor.{q} = {fmt(lq)} H is below motor.{d} = {fmt(ld)} H: an interior-magnet "
           "(IPM) motor has L_q > L_d (L_q = L_d for a surface-magnet motor); are the two "
           "values swapped? The table is made with the values as given"
           for q, d, lq, ld in pairs if lq < ld]
    r, e = handover_lq_cover(cfg)
    if e < HO_LQ_TOL:
        out.append(f"the hand-over window drive.ho_angle_deg = {fmt(cfg['drive']['ho_angle_deg'])} deg "
                   f"covers an L_q error down to -{e * 100:.1f} % only: L_q i_start / psi_f = "
                   f"{r:.2f} (motor.lq_h x drive.i_start_a / motor.psi_f_wb), and an L_q error e "
                   f"turns the flux estimate by about atan({r:.2f} e); a motor whose L_q is further "
                   "below the table's does not hand over and stops in STALL after its retries. "
                   f"Measure L_q at the start current within {e * 100:.0f} %, or lower "
                   "drive.i_start_a (specs/safety-manual.md section 4.2)")
    return out


def unit_text(k: Key) -> str:
    """' V', ' rpm', ... after a value; '' for a quantity without a unit."""
    return f" {k.unit}" if k.unit and k.unit not in ("bits", "ADC codes", "Q15 counts") else ""


def loop_lags(cfg: dict) -> tuple[float, float]:
    """(T_sigma, T_ssigma) of the current and speed loops (design_loops())."""
    d = cfg["design"]
    t_s = 1.0 / cfg["inverter"]["f_pwm_hz"]
    t_sigma = 0.5 * t_s + t_s + d["t_filter_current_s"]
    return t_sigma, 2.0 * t_sigma + 1.0 / (2.0 * math.pi * d["speed_fc_hz"]) + d["speed_t_sam_s"]


def resolve_defaults(cfg: dict) -> None:
    """Fill the derived defaults of [design], [limits] and [drive] (the str defaults of SCHEMA)."""
    m, inv, d, lim = cfg["motor"], cfg["inverter"], cfg["design"], cfg["limits"]
    i_base = cfg["sensing"]["i_full_scale_a"]
    cfg["defaulted"] = {f"design.{k}" for k, v in d.items() if v is None}
    cfg["defaulted"] |= {f"limits.{k}" for k, v in lim.items() if v is None}
    cfg["defaulted"] |= {f"design.{k}" for k, (dflt, _c, _s) in DESIGN_KEYS.items()
                         if dflt is not None and d[k] == dflt}
    dr = cfg["drive"]
    cfg["defaulted"] |= {f"drive.{k}" for k, (dflt, _c, _s) in DRIVE_KEYS.items()
                         if dr[k] is None or dr[k] == dflt}
    sen = cfg["sensing"]
    if sen["shunt_settle_ns"] is None:
        sen["shunt_settle_ns"] = inv["dead_time_s"] * 1e9 + 1000.0
        cfg["defaulted"].add("sensing.shunt_settle_ns")
    if sen["mode"] is None:
        sen["mode"] = "phases"
    cfg["defaulted"] |= {k.name for k in SCHEMA if k.section == "sensing" and k.key != "mode"
                         and k.value_default is not None and sen[k.key] == k.value_default}
    if sen["mode"] == "phases":
        cfg["defaulted"].add("sensing.mode")
    t_sigma, t_ssigma = loop_lags(cfg)
    if d["speed_crossover_hz"] is None:
        d["speed_crossover_hz"] = min(d["speed_crossover_ratio"] / (2.0 * t_sigma),
                                      1.0 / (2.0 * t_ssigma)) / (2.0 * math.pi)
    if d["speed_tau_s"] is None:
        d["speed_tau_s"] = d["speed_zero_ratio"] / (2.0 * math.pi * d["speed_crossover_hz"])
    if d["speed_check_rpm"] is None:
        d["speed_check_rpm"] = 0.5 * m["rated_speed_rpm"]
    if d["speed_check_load_nm"] is None:
        d["speed_check_load_nm"] = m["nominal_torque_nm"]
    if d["deadband_a"] is None:
        d["deadband_a"] = i_base / 80.0
    if d["i_offset_a"] is None:
        d["i_offset_a"] = i_base / 100.0
    if d["observer_min_speed_rpm"] is None:
        d["observer_min_speed_rpm"] = 0.1 * m["rated_speed_rpm"]
    if lim["i_max_a"] is None:
        lim["i_max_a"] = m["rated_current_a"]
    if lim["i_trip_a"] is None:
        lim["i_trip_a"] = 1.5 * lim["i_max_a"]
    if lim["speed_max_rpm"] is None:
        lim["speed_max_rpm"] = m["max_speed_rpm"]
    if lim["vdc_uv_v"] is None:
        lim["vdc_uv_v"] = 0.9 * inv["vdc_min_v"]
    if lim["vdc_ov_v"] is None:
        lim["vdc_ov_v"] = 1.05 * inv["vdc_max_v"]
    if lim["vdc_svpwm_min_v"] is None:
        lim["vdc_svpwm_min_v"] = 0.4 * inv["vdc_min_v"]
    # [drive]: rpm_max is resolved in drive_fields() (it needs the quantised k_rpm and
    # speed_max); the others here.
    if dr["i_align_a"] is None:
        dr["i_align_a"] = 0.5 * m["rated_current_a"]
    if dr["i_start_a"] is None:
        dr["i_start_a"] = m["rated_current_a"]
    if dr["stall_err_rpm"] is None:
        dr["stall_err_rpm"] = 0.3 * m["rated_speed_rpm"]
    if dr["phase_i_min_a"] is None:
        dr["phase_i_min_a"] = 0.1 * m["rated_current_a"]
    if dr["fw_level"] is None:
        dr["fw_level"] = d["fw_v_max"]
    if dr["tc_amp_max_a"] is None:
        dr["tc_amp_max_a"] = 0.5 * m["rated_current_a"]
    if dr["tc_speed_max_rpm"] is None:
        dr["tc_speed_max_rpm"] = m["rated_speed_rpm"]
    if dr["para_speed_rpm"] is None:
        dr["para_speed_rpm"] = 0.7 * m["max_speed_rpm"]
    if dr["mtpa_speed_rpm"] is None:
        dr["mtpa_speed_rpm"] = dr["of_speed_rpm"]
    if dr["t_ipm_derate_degc"] is None:
        dr["t_ipm_derate_degc"] = dr["t_ipm_max_degc"] - 10.0
    if dr["t_pcb_derate_degc"] is None:
        dr["t_pcb_derate_degc"] = dr["t_pcb_max_degc"] - 10.0
    if dr["derate_rpm"] is None:
        dr["derate_rpm"] = dr["rpm_min"]
    if dr["flux_v_err_v"] is None:
        dr["flux_v_err_v"] = 4.0 / math.pi * inv["dead_time_s"] * inv["f_pwm_hz"] * inv["vdc_max_v"]


def typed(cfg: dict, name: str) -> str:
    """'section.key = value unit', with the default's derivation when the file did not set it."""
    k = SCHEMA_BY_NAME[name]
    section, key = name.split(".")
    if cfg[section][key] is None:
        return f"{name} (not set: {k.default})"
    if isinstance(cfg[section][key], str):
        text = f"{name} = {cfg[section][key]!r}"
        return text + (" (default)" if name in cfg["defaulted"] else "")
    text = f"{name} = {fmt(cfg[section][key])}{unit_text(k)}"
    if name in cfg["defaulted"]:
        text += " (default" + (f" {k.default}" if isinstance(k.default, str) else "") + ")"
    return text


# The motor-file keys a table field is computed from (the [drive] fields: from the rule text
# of SCHEMA, which starts with the field's name), for the messages of range_checks().
FIELD_KEYS = {
    "f_pwm_hz": ("inverter.f_pwm_hz",),
    "svpwm.period": ("inverter.f_timer_hz", "inverter.f_pwm_hz"),
    "svpwm.dt_comp": ("inverter.dead_time_s", "inverter.f_timer_hz"),
    "svpwm.i_deadband": ("design.deadband_a", "sensing.i_full_scale_a"),
    "svpwm.vdc_min": ("limits.vdc_svpwm_min_v", "sensing.vdc_full_scale_v"),
    "i_max": ("limits.i_max_a", "sensing.i_full_scale_a"),
    "i_trip": ("limits.i_trip_a", "sensing.i_full_scale_a"),
    "speed_max": ("limits.speed_max_rpm", "motor.pole_pairs", "scaling.f_base_hz"),
    "vdc_uv": ("limits.vdc_uv_v", "sensing.vdc_full_scale_v"),
    "vdc_ov": ("limits.vdc_ov_v", "sensing.vdc_full_scale_v"),
    "v_max": ("design.fw_v_max",),
    "pll.err_clamp": ("design.pll_clamp",),
    "pll.mag_min": ("design.pll_mag_min", "motor.psi_f_wb", "scaling.psi_shift"),
    "pll.k_theta": ("scaling.f_base_hz", "inverter.f_pwm_hz"),
    "pll.speed_alpha": ("design.speed_fc_hz", "inverter.f_pwm_hz"),
    "alpha_vdc": ("design.vdc_fc_hz", "inverter.f_pwm_hz"),
    "flux.r": ("motor.rs_ohm", "sensing.vdc_full_scale_v", "sensing.i_full_scale_a"),
    "flux.gain": ("inverter.f_pwm_hz", "scaling.f_base_hz", "scaling.psi_shift"),
    "flux.l": ("motor.lq_h", "scaling.f_base_hz", "scaling.psi_shift"),
    "flux.kg": ("design.kg_rad_s", "scaling.f_base_hz", "scaling.psi_shift"),
    "ld": ("motor.ld_h", "scaling.f_base_hz", "scaling.psi_shift"),
    "lq": ("motor.lq_h", "scaling.f_base_hz", "scaling.psi_shift"),
    "psi_f": ("motor.psi_f_wb", "sensing.vdc_full_scale_v", "scaling.f_base_hz",
              "scaling.psi_shift"),
    "drive.pole_pairs": ("motor.pole_pairs",),
    "drive.k_rpm": ("motor.pole_pairs", "scaling.f_base_hz"),
    "drive.k_speed_rpm": ("motor.pole_pairs", "scaling.f_base_hz"),
    "drive.rpm_max": ("drive.rpm_max", "motor.max_speed_rpm", "limits.speed_max_rpm"),
    "drive.ld_hs": ("motor.ld_hs_h", "motor.ld_h", "scaling.f_base_hz", "scaling.psi_shift"),
    "drive.lq_hs": ("motor.lq_hs_h", "motor.lq_h", "scaling.f_base_hz", "scaling.psi_shift"),
    "drive.psi_shift": ("scaling.psi_shift", "motor.psi_f_wb", "sensing.vdc_full_scale_v",
                        "scaling.f_base_hz"),
    "drive.sensing": ("sensing.mode",),
    "drive.shunt_settle": ("sensing.shunt_settle_ns", "inverter.f_timer_hz"),
    "drive.shunt_sample": ("sensing.shunt_sample_ns", "inverter.f_timer_hz"),
    "drive.shunt_hold": ("sensing.shunt_hold",),
}
for _k_ in SCHEMA:
    if _k_.section == "drive" and _k_.key != "rpm_max":
        FIELD_KEYS.setdefault(_k_.rule.replace(",", " ").replace(";", " ").split()[0],
                              (_k_.name,))
del _k_


def field_source(cfg: dict, name: str) -> str:
    """' (from key = value, ...)' for a table field, or ''."""
    keys = FIELD_KEYS.get(name)
    if keys is None:
        for pi in ("pi_id", "pi_iq", "pi_speed", "pi_fw", "pll.pi"):
            if name.startswith(pi + "."):
                return " (from the loop design: motor, inverter, scaling and [design] keys)"
        return ""
    return " (from " + ", ".join(typed(cfg, k) for k in keys) + ")"


def check_rules(cfg: dict) -> list[str]:
    """The rules between keys (and against the sensors) that the per-key ranges cannot
    see; every message names the key of the motor file, its value and the rule."""
    m, inv, lim, dr = cfg["motor"], cfg["inverter"], cfg["limits"], cfg["drive"]
    sen = cfg["sensing"]
    out: list[str] = []
    if not inv["vdc_min_v"] <= inv["vdc_nominal_v"] <= inv["vdc_max_v"]:
        out.append(f"{typed(cfg, 'inverter.vdc_nominal_v')}: outside inverter.vdc_min_v .. "
                   f"inverter.vdc_max_v = {fmt(inv['vdc_min_v'])} .. {fmt(inv['vdc_max_v'])} V "
                   "(rule: vdc_min_v <= vdc_nominal_v <= vdc_max_v)")
    if m["max_speed_rpm"] < m["rated_speed_rpm"]:
        out.append(f"{typed(cfg, 'motor.max_speed_rpm')} is below "
                   f"{typed(cfg, 'motor.rated_speed_rpm')} (rule: max_speed_rpm >= "
                   "rated_speed_rpm)")
    if not float(inv["f_pwm_hz"]).is_integer():
        out.append(f"{typed(cfg, 'inverter.f_pwm_hz')}: not an integer (params.h f_pwm_hz is "
                   "an integer number of Hz)")

    # f_base (specs/scaling.md section 2): the highest electrical frequency is that of the
    # largest speed the table allows, motor.max_speed_rpm or limits.speed_max_rpm.
    n_p, f_base = m["pole_pairs"], cfg["scaling"]["f_base_hz"]
    top_key = "limits.speed_max_rpm" if lim["speed_max_rpm"] > m["max_speed_rpm"] \
        else "motor.max_speed_rpm"
    top_rpm = max(lim["speed_max_rpm"], m["max_speed_rpm"])
    f_e = top_rpm * n_p / 60.0
    if f_base < 1.25 * f_e * (1.0 - 1e-12):
        out.append(f"{typed(cfg, 'scaling.f_base_hz')} breaks the rule of {RULE_FBASE}: "
                   f"{top_key} {fmt(top_rpm)} rpm x motor.pole_pairs {n_p} / 60 = {fmt(f_e)} Hz, "
                   f"so this motor needs scaling.f_base_hz >= 1.25 x {fmt(f_e)} = "
                   f"{fmt(1.25 * f_e)} Hz")

    # The rpm conversions of the drive (drive_cfg.h k_rpm, k_speed_rpm: 1 .. 65535).
    k_rpm = n_p * 32768.0 / (60.0 * f_base) * 4096.0
    if k_rpm >= 65536.0:
        out.append(f"{typed(cfg, 'scaling.f_base_hz')} is too low for motor.pole_pairs {n_p}: "
                   f"the drive's rpm conversion k_rpm = n_p 32768 x 4096 / (60 f_base) = "
                   f"{fmt(k_rpm)} exceeds 65535 (rule: drive_cfg.h k_rpm 1 .. 65535); this "
                   "motor needs scaling.f_base_hz >= "
                   f"{fmt(n_p * 32768.0 * 4096.0 / (60.0 * 65535.0))} Hz")
    if 60.0 * f_base / n_p >= 65535.5:
        out.append(f"{typed(cfg, 'scaling.f_base_hz')} is too high for motor.pole_pairs {n_p}: "
                   f"k_speed_rpm = 60 f_base / n_p = {fmt(60.0 * f_base / n_p)} exceeds 65535 "
                   f"(rule: drive_cfg.h k_speed_rpm 1 .. 65535)")

    # Protection thresholds against their sensors.
    v_base, i_base = sen["vdc_full_scale_v"], sen["i_full_scale_a"]
    code_v = v_base / ADC_CODES
    for key, what, off in (("vdc_ov_v", "over-voltage", "never trips: over-voltage protection "
                            "disabled"),
                           ("vdc_uv_v", "under-voltage", "trips at every reading: the drive "
                            "never runs")):
        raw = q15(lim[key] / v_base)
        if raw >= (ADC_CODES - 1) * 8:
            out.append(f"{typed(cfg, 'limits.' + key)}: the DC-bus sensor cannot read this "
                       f"{what} threshold: it is not below the largest reading "
                       f"{ADC_CODES - 1} codes x sensing.vdc_full_scale_v {fmt(v_base)} V / "
                       f"{ADC_CODES} = {fmt((ADC_CODES - 1) * code_v)} V (rule: {RULE_VDC_READ}); "
                       f"the table value would be {raw}, which the reading (at most "
                       f"{(ADC_CODES - 1) * 8}) never exceeds: the {what} check {off}")
        elif raw < 8:
            out.append(f"{typed(cfg, 'limits.' + key)}: below one code of the DC-bus sensor, "
                       f"sensing.vdc_full_scale_v {fmt(v_base)} V / {ADC_CODES} = "
                       f"{fmt(code_v)} V (rule: {RULE_VDC_READ})")
    if not lim["vdc_ov_v"] > lim["vdc_uv_v"]:
        out.append(f"{typed(cfg, 'limits.vdc_ov_v')} is not above "
                   f"{typed(cfg, 'limits.vdc_uv_v')} (rule: vdc_ov > vdc_uv)")
    if lim["vdc_ov_v"] < inv["vdc_max_v"]:
        out.append(f"{typed(cfg, 'limits.vdc_ov_v')} is below {typed(cfg, 'inverter.vdc_max_v')} "
                   f"(rule: {RULE_VDC_OPERATING})")
    if lim["vdc_uv_v"] > inv["vdc_min_v"]:
        out.append(f"{typed(cfg, 'limits.vdc_uv_v')} is above {typed(cfg, 'inverter.vdc_min_v')} "
                   f"(rule: {RULE_VDC_OPERATING})")
    if lim["vdc_svpwm_min_v"] > inv["vdc_min_v"]:
        out.append(f"{typed(cfg, 'limits.vdc_svpwm_min_v')} is above "
                   f"{typed(cfg, 'inverter.vdc_min_v')} (rule: the SVPWM uses the measured bus "
                   "down to this floor, svpwm.h; a floor above the lowest bus would compute the "
                   "phase times from a wrong bus voltage in operation)")
    side = 2047 - dr["offset_window_counts"]
    i_read = side * i_base / 2048.0
    if q15(lim["i_trip_a"] / i_base) >= side * 16:
        out.append(f"{typed(cfg, 'limits.i_trip_a')}: the current sensor cannot read this "
                   f"over-current trip: it is not below the largest reading (2047 - "
                   f"drive.offset_window_counts {dr['offset_window_counts']}) codes x "
                   f"sensing.i_full_scale_a {fmt(i_base)} A / 2048 = {fmt(i_read)} A "
                   f"(rule: {RULE_I_READ})")
    if lim["i_trip_a"] < lim["i_max_a"]:
        out.append(f"{typed(cfg, 'limits.i_trip_a')} is below {typed(cfg, 'limits.i_max_a')} "
                   "(rule: i_trip >= i_max)")
    for key in ("i_align_a", "i_start_a", "tc_amp_max_a"):
        if dr[key] > lim["i_max_a"]:
            out.append(f"{typed(cfg, 'drive.' + key)} is above {typed(cfg, 'limits.i_max_a')} "
                       f"(rule: {RULE_CURRENT})")
    if dr["phase_i_min_a"] >= lim["i_max_a"]:
        out.append(f"{typed(cfg, 'drive.phase_i_min_a')} is not below "
                   f"{typed(cfg, 'limits.i_max_a')} (rule: the phase-loss monitor works above "
                   "phase_i_min; at or above i_max it never checks)")

    # Speeds of [drive] within the motor's speed range.
    rpm_max = dr["rpm_max"] if dr["rpm_max"] is not None else \
        min(m["max_speed_rpm"], lim["speed_max_rpm"])
    rpm_src = "drive.rpm_max" if dr["rpm_max"] is not None else \
        ("motor.max_speed_rpm" if m["max_speed_rpm"] <= lim["speed_max_rpm"]
         else "limits.speed_max_rpm")
    if dr["rpm_max"] is not None and dr["rpm_max"] > lim["speed_max_rpm"]:
        out.append(f"{typed(cfg, 'drive.rpm_max')} is above {typed(cfg, 'limits.speed_max_rpm')} "
                   "(rule: the largest target is within the speed limit)")
    for key, top, src in (("rpm_min", rpm_max, rpm_src),
                          ("tc_speed_max_rpm", rpm_max, rpm_src),
                          ("of_speed_rpm", lim["speed_max_rpm"], "limits.speed_max_rpm"),
                          ("stall_err_rpm", lim["speed_max_rpm"], "limits.speed_max_rpm"),
                          ("para_speed_rpm", lim["speed_max_rpm"], "limits.speed_max_rpm")):
        if dr[key] > top:
            out.append(f"{typed(cfg, 'drive.' + key)}: outside the motor's speed range 0 .. "
                       f"{fmt(top)} rpm ({src}) (rule: {RULE_SPEED})")
    if dr["tc_speed_min_rpm"] > dr["tc_speed_max_rpm"]:
        out.append(f"{typed(cfg, 'drive.tc_speed_min_rpm')} is above "
                   f"{typed(cfg, 'drive.tc_speed_max_rpm')} (rule: tc_speed_min <= tc_speed_max)")
    if dr["lin_id_status"] == dr["lin_id_cmd"]:
        out.append(f"{typed(cfg, 'drive.lin_id_status')} equals "
                   f"{typed(cfg, 'drive.lin_id_cmd')} (rule: the two LIN frames need different "
                   "identifiers)")
    for start, trip in (("t_ipm_derate_degc", "t_ipm_max_degc"),
                        ("t_pcb_derate_degc", "t_pcb_max_degc")):
        if not round(dr[start] * 10.0) < round(dr[trip] * 10.0):
            out.append(f"{typed(cfg, 'drive.' + start)} is not below "
                       f"{typed(cfg, 'drive.' + trip)} (rule: {RULE_DERATE}: a window that "
                       "starts at or above the trip never derates)")
    if not dr["rpm_min"] <= dr["derate_rpm"] <= rpm_max:
        out.append(f"{typed(cfg, 'drive.derate_rpm')}: outside drive.rpm_min .. drive.rpm_max "
                   f"{fmt(dr['rpm_min'])} .. {fmt(rpm_max)} rpm (rule: {RULE_DERATE})")
    out += shunt_rules(cfg)
    return out


def shunt_rules(cfg: dict) -> list[str]:
    """[sensing]: the mode's name, and rule 'shunt window' (checked in both modes)."""
    sen, inv = cfg["sensing"], cfg["inverter"]
    out: list[str] = []
    if sen["mode"] not in SENSING_MODES:
        out.append(f"{typed(cfg, 'sensing.mode')}: not a sensing mode; use "
                   + " or ".join(f'"{m}"' for m in SENSING_MODES)
                   + suggest(str(sen["mode"]), SENSING_MODES))
    period = int(round(inv["f_timer_hz"] / (2.0 * inv["f_pwm_hz"])))
    settle = shunt_ticks(sen["shunt_settle_ns"], inv["f_timer_hz"])
    sample = shunt_ticks(sen["shunt_sample_ns"], inv["f_timer_hz"])
    if 4 * (settle + sample) > period:
        out.append(f"{typed(cfg, 'sensing.shunt_settle_ns')} and "
                   f"{typed(cfg, 'sensing.shunt_sample_ns')}: the window {settle} + {sample} "
                   f"ticks does not fit four times in the PWM counter's period {period} ticks "
                   f"(rule: {RULE_SHUNT})")
    if sen["shunt_settle_ns"] < inv["dead_time_s"] * 1e9 * (1.0 - 1e-12):
        out.append(f"{typed(cfg, 'sensing.shunt_settle_ns')} is below "
                   f"{typed(cfg, 'inverter.dead_time_s')} = {fmt(inv['dead_time_s'] * 1e9)} ns "
                   f"(rule: {RULE_SHUNT})")
    return out


def motor_file_doc() -> str:
    """docs/motor-file.md: every section and key of SCHEMA with unit, range, default and rule."""
    lines = [
        "# The motor file",
        "",
        "Generated by `python3 tools/tune/qfoc_tune.py --motor-file-doc` from the tool's schema "
        "(`SCHEMA` in tools/tune/qfoc_tune.py); do not edit: a pytest test compares this file with "
        "the tool's output.",
        "",
        "One TOML file per motor and inverter (`specs/motors/*.toml`) is the input of "
        "`tools/tune/qfoc_tune.py` (the parameter table), of the simulator (`sim/motor.c`) and of "
        "the demonstration (`sim/scenario.c`, section [demo]).  Units are SI; speeds are "
        "mechanical rpm, currents peak phase amperes, angles electrical unless named.  "
        "`--set section.key=value` overrides one key on the command line.",
        "",
        "The tool refuses (exit code 1, no table written) a key it does not know, a value "
        "outside its range or its plausible range (below), and a file that breaks one of the "
        "rules below; a file it cannot "
        "read as a motor file (TOML syntax, a missing required key, a wrong type or sign) "
        "ends with exit code 2.  Every message names the key as `section.key`, its value "
        "and the rule.",
        "",
        "`specs/motors/reference.toml` is a complete example.",
        "",
        "Rules between keys (the column \"used by / rule\" of the tables refers to them):",
        "",
        f"- 'f_base': {RULE_FBASE}: scaling.f_base_hz >= 1.25 x max(motor.max_speed_rpm, "
        "limits.speed_max_rpm) x motor.pole_pairs / 60; and the drive's rpm conversions "
        "k_rpm = n_p 32768 x 4096 / (60 f_base) and k_speed_rpm = 60 f_base / n_p within "
        "1 .. 65535 (drive_cfg.h).",
        f"- 'DC-bus thresholds' (limits.vdc_ov_v, limits.vdc_uv_v): {RULE_VDC_READ}; and "
        f"vdc_ov_v > vdc_uv_v; {RULE_VDC_OPERATING}; limits.vdc_svpwm_min_v <= "
        "inverter.vdc_min_v.",
        f"- 'over-current trip' (limits.i_trip_a): {RULE_I_READ}; and i_trip_a >= i_max_a.",
        f"- 'currents': {RULE_CURRENT} (limits.i_max_a); drive.phase_i_min_a < limits.i_max_a.",
        f"- 'speeds': {RULE_SPEED}: drive.rpm_min and drive.tc_speed_max_rpm <= drive.rpm_max "
        "(or the smaller of motor.max_speed_rpm and limits.speed_max_rpm when drive.rpm_max is "
        "not set); drive.rpm_max, drive.of_speed_rpm, drive.stall_err_rpm and drive.para_speed_rpm <= "
        "limits.speed_max_rpm; drive.tc_speed_min_rpm <= drive.tc_speed_max_rpm.",
        f"- 'flux base' (scaling.psi_shift): {RULE_PSI}.  Without the key the tool takes the "
        "smallest shift that holds them (so a motor whose flux fits V_base / w_base keeps "
        "s = 0); a shift too small for the machine fails the bound it breaks (report marked "
        "FAILED); any value but an integer 0 .. 4 is refused with exit code 1 (whatever its "
        "type), and so is a machine whose flux does not fit even s = 4, with its active flux "
        "and the largest flux base 16 V_base / w_base.",
        "- inverter.vdc_min_v <= inverter.vdc_nominal_v <= inverter.vdc_max_v; "
        "motor.max_speed_rpm >= motor.rated_speed_rpm; drive.lin_id_status != drive.lin_id_cmd.",
        "- Then the table itself: the fixed-point bounds of chapter 2, the loop margins of "
        "chapter 4, the speed-loop check (the stored speed PI, the current loop as a lag, the "
        "mechanics J, B and the speed filter simulated in double precision: from drive.of_speed_rpm "
        "the drive's ramp to design.speed_check_rpm with the load step design.speed_check_load_nm; "
        f"|speed error| <= {SPEED_CHECK_ERR_PCT:g} % of the target from {SPEED_CHECK_AFTER_S:g} s "
        "after the ramp's end) and the field ranges of params.h and drive_cfg.h (exit code 1, report "
        "marked FAILED).",
        "",
        "## Plausible values and warnings",
        "",
        "The physical keys below must also lie within a plausible range: every real compressor "
        "and traction PMSM and its inverter from 100 W (a 12 V pump or fan motor) to 400 kW "
        "(a heavy-duty traction machine) lies inside it, and each range is at most about four "
        "decades wide, so that a value typed in the wrong unit (mH as H, mOhm as ohm, mWb as "
        "Wb, ms or us as s: a factor of 1000) falls outside it; a range of 1 uH .. 1 H would "
        "accept a compressor's 4.2 mH typed as 4.2 as well.  The tool refuses a value outside "
        "(exit code 1, no table written) and names the key, the value typed, the plausible "
        "range and, as \"did you mean\", the value x 1e-3 or x 1e3 (or the key's other unit "
        "slip) that lies inside it.  A key whose range is \">= 0\" accepts 0 as well.",
        "",
        "It warns (and makes the table) when motor.lq_h < motor.ld_h (or motor.lq_hs_h < "
        "motor.ld_hs_h): an interior-magnet (IPM) motor has L_q > L_d, a surface-magnet "
        "motor L_q = L_d; the two values may be swapped.  It warns as well when the hand-over "
        "window drive.ho_angle_deg covers an L_q error of less than "
        f"{HO_LQ_TOL * 100:.0f} %: an L_q error e turns the open-loop flux estimate by about "
        "atan(e L_q i_start / psi_f), and a start whose estimate lies beyond the window does "
        "not hand over.",
        "",
    ]
    prow = []
    for k in SCHEMA:
        if k.name in PLAUSIBLE:
            lo, hi, why = PLAUSIBLE[k.name]
            prow.append([f"`{k.name}`", f"{fmt(lo)} .. {fmt(hi)}", k.unit, why])
    lines += md_table(["key", "plausible range", "unit", "reasoning"], prow) + [""]
    for section in SECTIONS:
        lines += [f"## [{section}]", "", f"{SECTION_TEXT[section][0].upper()}"
                  f"{SECTION_TEXT[section][1:]}.", ""]
        rows = []
        for k in SCHEMA:
            if k.section != section:
                continue
            if k.default is REQUIRED:
                dflt = "required"
            elif isinstance(k.default, str):
                dflt = k.default
            elif k.kind == "int" and k.key.startswith(("lin_id", "can_id")):
                dflt = f"0x{k.default:X}"
            else:
                dflt = fmt(k.default)
            kind = {"str": "string", "int": "integer", "num": "number"}[k.kind]
            rows.append([f"`{k.key}`", kind, k.unit, range_text(k.rng) if k.kind != "str"
                         else "non-empty", dflt, k.desc, k.rule])
        lines += md_table(["key", "type", "unit", "range", "default", "meaning", "used by / rule"],
                          rows)
        lines.append("")
    return "\n".join(lines)


# --------------------------------------------------------------------------------------
# Number formats (identical to sim/estim.c est_q15 / est_qn / est_mant_left / est_mant_right)
# --------------------------------------------------------------------------------------

def q15(x: float) -> int:
    """round(x * 32768), nearest with ties up, clamped to [-32767, 32767] (est_q15)."""
    r = math.floor(x * 32768.0 + 0.5)
    return int(max(-Q15_MAX, min(Q15_MAX, r)))


def qn(x: float, frac_bits: int) -> int:
    """round(x * 2^frac_bits), clamped to [0, 32767] (est_qn)."""
    r = math.floor(math.ldexp(x, frac_bits) + 0.5)
    return int(max(0, min(Q15_MAX, r)))


def mant_left(x: float) -> tuple[int, int]:
    """pi.h gain: x = mant / 32768 * 2^shift, smallest shift 0..15 (est_mant_left)."""
    s = 0
    while s < 15 and math.ldexp(x, 15 - s) > 32767.0:
        s += 1
    return qn(x, 15 - s), s


def mant_right(x: float) -> tuple[int, int]:
    """flux.h gain: x = mant / 2^(15 + shift), largest shift 0..15 (est_mant_right)."""
    s = 0
    while s < 15 and math.ldexp(x, 16 + s) < 32767.0:
        s += 1
    return qn(x, 15 + s), s


def crc32_iso_hdlc(data: bytes) -> int:
    """CRC-32/ISO-HDLC: poly 0x04C11DB7 reflected (0xEDB88320), init and xorout 0xFFFFFFFF."""
    crc = 0xFFFFFFFF
    for byte in data:
        crc ^= byte
        for _ in range(8):
            crc = (crc >> 1) ^ (0xEDB88320 if crc & 1 else 0)
    return crc ^ 0xFFFFFFFF


def fmt(x: float, digits: int = 6) -> str:
    """Compact, reproducible number format."""
    if x == 0:
        return "0"
    if math.isinf(x):
        return "inf" if x > 0 else "-inf"
    return f"{x:.{digits}g}"


# --------------------------------------------------------------------------------------
# Bases and scale factors (specs/scaling.md sections 2 and 3)
# --------------------------------------------------------------------------------------

@dataclass
class Bases:
    """Per-unit bases (sim/motor.c sim_bases(), with the flux base of table layout 4)."""
    v_base: float
    i_base: float
    f_base: float
    w_base: float
    psi_base: float
    z_base: float
    l_base: float
    t_base: float
    f_pwm: float
    t_s: float
    period: int
    psi_shift: int = 0        # s of psi_base = 2^s V_base / w_base (drive.psi_shift)
    shift_src: str = ""       # how s was chosen (the table comment and the report)

    @property
    def k_psi(self) -> int:
        """2^s: a speed (pu of w_base) times a flux (pu of psi_base) is a voltage of
        2^s V_base."""
        return 1 << self.psi_shift


def make_bases(cfg: dict, psi_shift: int | None = None) -> Bases:
    """Derive the bases of specs/scaling.md section 2 with the flux base 2^s V_base / w_base:
    s = psi_shift when given, else scaling.psi_shift when the motor file sets it, else the
    smallest shift that holds the machine (derive_psi_shift(); Refusal when none does)."""
    if psi_shift is None:
        typed_s = cfg["scaling"].get("psi_shift")
        if typed_s is not None:
            b = make_bases(cfg, typed_s)
            b.shift_src = f"scaling.psi_shift = {typed_s}"
            return b
        return derive_psi_shift(cfg)
    v_base = cfg["sensing"]["vdc_full_scale_v"]
    i_base = cfg["sensing"]["i_full_scale_a"]
    f_base = cfg["scaling"]["f_base_hz"]
    w_base = 2.0 * math.pi * f_base
    f_pwm = cfg["inverter"]["f_pwm_hz"]
    # 2^s applied with ldexp (exact): with s = 0 every base is bit for bit that of layout 3
    psi_base = math.ldexp(v_base / w_base, psi_shift)
    return Bases(v_base=v_base, i_base=i_base, f_base=f_base, w_base=w_base,
                 psi_base=psi_base, z_base=v_base / i_base,
                 l_base=math.ldexp(v_base / i_base / w_base, psi_shift),
                 t_base=1.5 * cfg["motor"]["pole_pairs"] * psi_base * i_base,
                 f_pwm=f_pwm, t_s=1.0 / f_pwm,
                 period=int(round(cfg["inverter"]["f_timer_hz"] / (2.0 * f_pwm))),
                 psi_shift=psi_shift)


def active_flux_wb(cfg: dict) -> float:
    """The largest active flux the observer sees: psi_f + |L_d - L_q| i_max (Wb)."""
    m = cfg["motor"]
    return m["psi_f_wb"] + abs(m["ld_h"] - m["lq_h"]) * cfg["limits"]["i_max_a"]


def derive_psi_shift(cfg: dict) -> Bases:
    """The bases with the smallest flux-base shift s in 0 .. PSI_SHIFT_MAX for which every
    flux-unit bound holds (flux_bounds(), flux_unit_bounds(): the flux-estimate bounds 2-25,
    2-26, the fluxes below 1 pu, the inductances below 8 pu, kg below 1 pu).  Every bound but
    kg's relaxes as s grows (kg = K_gain 2^s / w_base grows with it).  Refusal when no shift
    holds the machine, naming the active flux and the largest flux base."""
    first_fit = None
    for s in range(PSI_SHIFT_MAX + 1):
        b = make_bases(cfg, s)
        ds = design_loops(cfg, b)
        rows = flux_bounds(cfg, ds) + flux_unit_bounds(cfg, ds)
        bad = [r for r in rows if not r.ok]
        if not bad:
            b.shift_src = (f"derived: the smallest shift 0 .. {PSI_SHIFT_MAX} that holds "
                           "every flux-unit bound")
            return b
        if first_fit is None and all(r.name == "flux base: flux.kg" for r in bad):
            first_fit = (s, bad)
    b = make_bases(cfg, PSI_SHIFT_MAX)
    if first_fit is not None:
        s, bad = first_fit
        raise Refusal(
            f"no flux base holds this machine: the flux needs scaling.psi_shift >= {s}, and "
            f"from there the flux observer's high-pass gain flux.kg = K_gain 2^s / w_base = "
            f"{typed(cfg, 'design.kg_rad_s')} x 2^{s} / {fmt(b.w_base)} rad/s = "
            f"{fmt(bad[0].value / 32768.0)} pu is not below 1 pu (Q15) (rule: docs/motor-file.md "
            f"rule 'flux base': {RULE_PSI}); kg = K_gain psi_base / V_base: lower "
            "design.kg_rad_s or raise sensing.vdc_full_scale_v")
    ds = design_loops(cfg, b)
    bad = [r for r in flux_bounds(cfg, ds) + flux_unit_bounds(cfg, ds) if not r.ok]
    m = cfg["motor"]
    raise Refusal(
        f"the machine's flux does not fit even the largest flux base: the active flux psi_f + "
        f"|L_d - L_q| i_max = {fmt(m['psi_f_wb'])} + |{fmt(m['ld_h'])} - {fmt(m['lq_h'])}| x "
        f"{fmt(cfg['limits']['i_max_a'])} = {fmt(active_flux_wb(cfg))} Wb against psi_shift "
        f"{PSI_SHIFT_MAX}: psi_base = 2^{PSI_SHIFT_MAX} V_base / w_base = {1 << PSI_SHIFT_MAX} x "
        f"{fmt(b.v_base)} / {fmt(b.w_base)} = {fmt(b.psi_base)} Wb, where "
        + "; ".join(f"{r.name} ({r.equation}): {fmt(r.value)} > {fmt(r.limit)} for "
                    f"{r.worst_input}" for r in bad)
        + f" (rule: docs/motor-file.md rule 'flux base': {RULE_PSI}); the machine needs a "
        "larger sensing.vdc_full_scale_v or a lower scaling.f_base_hz (within the rule "
        "'f_base')")


def base_rows(cfg: dict, b: Bases) -> list[tuple[str, str, str]]:
    """(symbol, derivation with numbers, value) rows of the bases."""
    n_p = cfg["motor"]["pole_pairs"]
    return [
        ("V_base", f"sensing.vdc_full_scale_v = {fmt(b.v_base)} V", f"{fmt(b.v_base)} V"),
        ("I_base", f"sensing.i_full_scale_a = {fmt(b.i_base)} A", f"{fmt(b.i_base)} A"),
        ("f_base", f"scaling.f_base_hz = {fmt(b.f_base)} Hz", f"{fmt(b.f_base)} Hz"),
        ("w_base", f"2 pi f_base = 2 pi x {fmt(b.f_base)}", f"{fmt(b.w_base)} rad/s"),
        ("psi_shift", f"s, {b.shift_src}: active flux psi_f + |L_d - L_q| i_max = "
                      f"{fmt(active_flux_wb(cfg))} Wb = {fmt(active_flux_wb(cfg) / b.psi_base, 4)} "
                      "psi_base", str(b.psi_shift)),
        ("psi_base", f"2^s V_base / w_base = {b.k_psi} x {fmt(b.v_base)} / {fmt(b.w_base)}",
         f"{fmt(b.psi_base)} Wb"),
        ("Z_base", f"V_base / I_base = {fmt(b.v_base)} / {fmt(b.i_base)}", f"{fmt(b.z_base)} ohm"),
        ("L_base", f"psi_base / I_base = 2^s Z_base / w_base = {b.k_psi} x {fmt(b.z_base)} / "
                   f"{fmt(b.w_base)}", f"{fmt(b.l_base * 1e3)} mH"),
        ("T_base", f"3/2 n_p psi_base I_base = 1.5 x {n_p} x {fmt(b.psi_base)} x {fmt(b.i_base)}",
         f"{fmt(b.t_base)} N m"),
        ("T_s", f"1 / f_pwm = 1 / {fmt(b.f_pwm)}", f"{fmt(b.t_s * 1e6)} us"),
        ("period", f"round(f_timer / (2 f_pwm)) = round({fmt(cfg['inverter']['f_timer_hz'])} / "
                   f"(2 x {fmt(b.f_pwm)}))", f"{b.period} ticks"),
    ]


# --------------------------------------------------------------------------------------
# Gains
# --------------------------------------------------------------------------------------

@dataclass
class Gain:
    """One quantised quantity: real value, raw integer(s), representation, error."""
    name: str
    real: float
    raw: int
    shift: int | None
    kind: str           # "left" (pi.h), "right" (flux.h), "q15", "q12", "int"
    derivation: str

    @property
    def quantised(self) -> float:
        """The real value that the raw integer represents."""
        if self.kind == "left":
            return self.raw / 32768.0 * 2.0 ** self.shift
        if self.kind == "right":
            return self.raw / 2.0 ** (15 + self.shift)
        if self.kind == "q15":
            return self.raw / 32768.0
        if self.kind == "q12":
            return self.raw / 4096.0
        return float(self.raw)

    @property
    def rel_err(self) -> float:
        """Relative rounding error (quantised - real) / real."""
        return 0.0 if self.real == 0 else (self.quantised - self.real) / self.real

    def repr_text(self) -> str:
        """Human-readable representation, e.g. '14680 / 32768 x 2^0'."""
        if self.kind == "left":
            return f"{self.raw} / 32768 x 2^{self.shift}"
        if self.kind == "right":
            return f"{self.raw} / 2^(15+{self.shift})"
        if self.kind == "q15":
            return f"{self.raw} / 32768"
        if self.kind == "q12":
            return f"{self.raw} / 4096"
        return str(self.raw)


def g_left(name: str, x: float, derivation: str) -> Gain:
    """A pi.h gain (mantissa, left shift)."""
    mant, shift = mant_left(x)
    return Gain(name, x, mant, shift, "left", derivation)


def g_right(name: str, x: float, derivation: str) -> Gain:
    """A flux.h gain (mantissa, right shift)."""
    mant, shift = mant_right(x)
    return Gain(name, x, mant, shift, "right", derivation)


def g_q15(name: str, x: float, derivation: str) -> Gain:
    """A Q15 value."""
    return Gain(name, x, q15(x), None, "q15", derivation)


@dataclass
class Design:
    """Everything derived from the motor file: real design values and quantised gains."""
    cfg: dict
    b: Bases
    t_sigma: float = 0.0
    t_ssigma: float = 0.0
    k_t: float = 0.0
    gains: dict = field(default_factory=dict)
    phys: dict = field(default_factory=dict)   # physical design values for the report/analysis


# Torque compensation (include/qfoc/trqcomp.h): the learning law correlates the speed
# error with regressors shifted by the model phase -90 degrees; it converges while the
# true phase of the path from the feed-forward current to the learner's speed error stays
# within 90 degrees of it (cos delta > 0).  That path is the current loop (closed loop
# 1 / (1 + 2 T_sigma s) by the design rule of design_loops()), the mechanics closed by the
# speed PI (on the filtered estimate), the PLL's speed estimate and the tick's half-sample
# delay.  The library learns the first harmonic over [speed_min, speed_max] and the second
# up to speed_max / 2, so the highest learned frequency is the first harmonic's at
# speed_max.  TC_DELTA_MAX_DEG leaves 40 degrees for what the model leaves out (the
# plant's spread of inertia and friction, the estimator's dynamics under parameter error).
TC_DELTA_MAX_DEG = 50.0


def tc_phase_error_deg(cfg: dict, ds: "Design", rpm: float, h: int) -> float:
    """delta = psi_true - psi_model (degrees) of harmonic h at rpm (positive rotation)."""
    m, d = cfg["motor"], cfg["design"]
    w = h * rpm * 2.0 * math.pi / 60.0      # the harmonic's time frequency, rad/s
    s = 1j * w
    ph = ds.phys
    kp = ph["ksp"]                          # A s/rad (mechanical)
    ki = kp / ph["tau_s"]
    f_speed = 1.0 / (1.0 + s / (2.0 * math.pi * d["speed_fc_hz"]))
    g = 1.0 / (m["j_kgm2"] * s + m["b_nms"] + ds.k_t * (kp + ki / s) * f_speed)
    wn = 2.0 * math.pi * d["pll_wn_hz"]
    zeta = d["pll_zeta"]
    pll = (2.0 * zeta * wn * s + wn * wn) / (s * s + 2.0 * zeta * wn * s + wn * wn)
    cur = 1.0 / (1.0 + 2.0 * ds.t_sigma * s)
    phase = math.degrees(float(np.angle(cur * g * pll))) - math.degrees(w * 0.5e-3)
    delta = phase + 90.0
    return (delta + 180.0) % 360.0 - 180.0


def tc_worst_phase(cfg: dict, ds: "Design", lo: float, hi: float) -> tuple:
    """The largest |delta| of the learned harmonics over the window [lo, hi] (the first
    over [lo, hi], the second over [lo, hi / 2]), in 10 rpm steps: (deg, rpm, h)."""
    worst = (0.0, lo, 1)
    for h, top in ((1, hi), (2, hi / 2.0)):
        rpm = lo
        while rpm <= top + 1e-9:
            dv = abs(tc_phase_error_deg(cfg, ds, rpm, h))
            if dv > worst[0]:
                worst = (dv, rpm, h)
            rpm += 10.0
    return worst


def tc_speed_limit_rpm(cfg: dict, ds: "Design", lo: float, hi: float) -> float:
    """The highest top <= hi (10 rpm steps from lo) up to which the first harmonic and the
    second at half the speed keep |delta| <= TC_DELTA_MAX_DEG (or <= the first harmonic's at
    lo, where that is larger: the window's lower end is the user's)."""
    bound = max(TC_DELTA_MAX_DEG, abs(tc_phase_error_deg(cfg, ds, lo, 1)))
    top = lo
    rpm = lo
    while rpm <= hi + 1e-9:
        if abs(tc_phase_error_deg(cfg, ds, rpm, 1)) > bound or \
                (rpm / 2.0 >= lo and abs(tc_phase_error_deg(cfg, ds, rpm / 2.0, 2)) > bound):
            break
        top = rpm
        rpm += 10.0
    return min(top, hi)


def design_loops(cfg: dict, b: Bases) -> Design:
    """Design every loop and quantise every gain (the rules of specs/equations.md section 7)."""
    m, inv, d, lim = cfg["motor"], cfg["inverter"], cfg["design"], cfg["limits"]
    ds = Design(cfg, b)
    g, ph = ds.gains, ds.phys
    n_p, R = m["pole_pairs"], m["rs_ohm"]
    t_s = b.t_s
    vb_ib = f"I_base / V_base = {fmt(b.i_base)} / {fmt(b.v_base)}"

    # Current loops ("Current Loop"): T_sigma = T_pwm + T_sam + T_filter, with the PWM
    # (zero-order hold) delay T_s / 2 and one sample of computation delay T_s: the
    # voltage computed from the sample at t_k is applied during [t_k+1, t_k+2].
    ds.t_sigma = loop_lags(cfg)[0]
    ph["T_sigma"] = ds.t_sigma
    v_lim = inv["vdc_max_v"] / SQRT3
    ph["v_lim"] = v_lim
    for axis, l_h in (("d", m["ld_h"]), ("q", m["lq_h"])):
        k_cp = l_h / (2.0 * ds.t_sigma)            # tau_c = L/R, k_cp = T_s/(2 T_sigma K_s)
        k_ci = R / (2.0 * ds.t_sigma)              # k_ci = k_cp / tau_c
        ph[f"k_cp_{axis}"], ph[f"k_ci_{axis}"] = k_cp, k_ci
        g[f"pi_i{axis}.kp"] = g_left(
            f"pi_i{axis}.kp", k_cp * b.i_base / b.v_base,
            f"k_cp = L_{axis} / (2 T_sigma) = {fmt(l_h)} / (2 x {fmt(ds.t_sigma)}) = "
            f"{fmt(k_cp)} ohm; x {vb_ib}")
        g[f"pi_i{axis}.ki"] = g_left(
            f"pi_i{axis}.ki", k_ci * t_s * b.i_base / b.v_base,
            f"k_ci T = R / (2 T_sigma) T = {fmt(R)} / (2 x {fmt(ds.t_sigma)}) x {fmt(t_s)} = "
            f"{fmt(k_ci * t_s)} ohm; x {vb_ib}")
        g[f"pi_i{axis}.out"] = g_q15(
            f"pi_i{axis}.out_max", v_lim / b.v_base,
            f"V_dc,max / sqrt 3 / V_base = {fmt(inv['vdc_max_v'])} / sqrt 3 / {fmt(b.v_base)}")

    # Speed loop ("Speed Loop"): T_ssigma = 2 T_sigma + T_filter + T_sam; tau_s = 1/a;
    # ksp = K / (2 K_t b) with K = 1 / T_ssigma (K T = 0.5 as in the current loop).
    t_filter_speed = 1.0 / (2.0 * math.pi * d["speed_fc_hz"])
    ds.t_ssigma = 2.0 * ds.t_sigma + t_filter_speed + d["speed_t_sam_s"]
    ds.k_t = 1.5 * n_p * m["psi_f_wb"]
    b_mech = 1.0 / m["j_kgm2"]
    a_mech = m["b_nms"] / m["j_kgm2"]
    # Crossover w_sc (design.speed_crossover_hz): |kp K_t b / s| = 1 there, kp = w_sc / (K_t b);
    # the default w_sc = 1 / (2 T_ssigma) is the document's ksp = K / (2 K_t b), K = 1 / T_ssigma.
    w_sc = 2.0 * math.pi * d["speed_crossover_hz"]
    ksp = w_sc / (ds.k_t * b_mech)                              # A per rad/s (mechanical)
    tau_s = d["speed_tau_s"]
    ph.update(T_ssigma=ds.t_ssigma, T_filter_speed=t_filter_speed, K_t=ds.k_t, b=b_mech,
              a=a_mech, ksp=ksp, tau_s=tau_s, w_sc=w_sc)
    kp_speed = ksp / n_p * b.w_base / b.i_base
    g["pi_speed.kp"] = g_left(
        "pi_speed.kp", kp_speed,
        f"ksp = w_sc / (K_t b) = 2 pi x {fmt(d['speed_crossover_hz'])} / ({fmt(ds.k_t)} x "
        f"{fmt(b_mech)}) = {fmt(ksp)} A s/rad (mech); / n_p x w_base / I_base")
    g["pi_speed.ki"] = g_left(
        "pi_speed.ki", kp_speed * d["speed_t_sam_s"] / tau_s,
        f"kp T_sam / tau_s = {fmt(kp_speed)} x {fmt(d['speed_t_sam_s'])} / {fmt(tau_s)}")
    g["i_max"] = g_q15("i_max", lim["i_max_a"] / b.i_base,
                       f"i_max / I_base = {fmt(lim['i_max_a'])} / {fmt(b.i_base)}")

    # Field weakening: e = v_max - utilisation -> i_d reference in [-i_max, 0].  Plant gain
    # d(utilisation)/d(i_d) <= w_max L_d / (V_dc,min / sqrt 3) (largest at top speed and
    # lowest bus); crossover w_fw = ratio x 1/(2 T_sigma) (current-loop crossover), PI zero at
    # zero_ratio x w_fw (integral-dominant): ki = w_fw / G, kp = ki / (zero_ratio w_fw).
    # The loop runs in the drive's 1 ms tick (REQ-DRV-006): its integral gain per sample is
    # ki T_tick, and its crossover is at most FW_TICK_WT / T_tick, where the tick's hold and
    # its one-tick delay (1.5 T_tick) cost at most 1.5 FW_TICK_WT rad = 17 degrees of phase.
    w_max_e = lim["speed_max_rpm"] * n_p * 2.0 * math.pi / 60.0
    g_fw = w_max_e * m["ld_h"] / (inv["vdc_min_v"] / SQRT3) * b.i_base
    w_ci = 1.0 / (2.0 * ds.t_sigma)
    w_fw = min(d["fw_crossover_ratio"] * w_ci, FW_TICK_WT / T_TICK_S)
    ki_fw = w_fw / g_fw
    kp_fw = ki_fw / (d["fw_zero_ratio"] * w_fw)
    ph.update(G_fw=g_fw, w_fw=w_fw, w_ci=w_ci, ki_fw=ki_fw, kp_fw=kp_fw, w_max_e=w_max_e)
    g["pi_fw.kp"] = g_left("pi_fw.kp", kp_fw,
                           f"1 / (zero_ratio G_fw) = 1 / ({fmt(d['fw_zero_ratio'])} x {fmt(g_fw)})")
    g["pi_fw.ki"] = g_left("pi_fw.ki", ki_fw * T_TICK_S,
                           f"w_fw / G_fw T_tick = {fmt(w_fw)} / {fmt(g_fw)} x {fmt(T_TICK_S)}")
    g["v_max"] = g_q15("v_max", d["fw_v_max"], "design.fw_v_max")

    # PLL (2-27, 2-28) exactly as est_tune(): kp = 2 zeta wn / w_base, ki T = wn^2 T / w_base.
    wn = 2.0 * math.pi * d["pll_wn_hz"]
    g["pll.kp"] = g_left("pll.pi.kp", 2.0 * d["pll_zeta"] * wn / b.w_base,
                         f"2 zeta w_n / w_base = 2 x {fmt(d['pll_zeta'])} x {fmt(wn)} / "
                         f"{fmt(b.w_base)}")
    g["pll.ki"] = g_left("pll.pi.ki", wn * wn * t_s / b.w_base,
                         f"w_n^2 T / w_base = {fmt(wn)}^2 x {fmt(t_s)} / {fmt(b.w_base)}")
    g["pll.err_clamp"] = g_q15("pll.err_clamp", d["pll_clamp"], "design.pll_clamp")
    g["pll.mag_min"] = g_q15("pll.mag_min", d["pll_mag_min"] * m["psi_f_wb"] / b.psi_base,
                             f"{fmt(d['pll_mag_min'])} psi_f / psi_base")
    k_theta = b.f_base / b.f_pwm * 131072.0
    g["pll.k_theta"] = Gain("pll.k_theta", k_theta, int(math.floor(k_theta + 0.5)), None, "int",
                            f"round(f_base / f_pwm x 131072) = round({fmt(b.f_base)} / "
                            f"{fmt(b.f_pwm)} x 131072)")
    g["pll.speed_alpha"] = g_q15("pll.speed_alpha", 2.0 * math.pi * d["speed_fc_hz"] * t_s,
                                 f"2 pi f_c / f_pwm = 2 pi x {fmt(d['speed_fc_hz'])} / "
                                 f"{fmt(b.f_pwm)} (2-34)")
    g["alpha_vdc"] = g_q15("alpha_vdc", 2.0 * math.pi * d["vdc_fc_hz"] * t_s,
                           f"2 pi f_c / f_pwm = 2 pi x {fmt(d['vdc_fc_hz'])} / {fmt(b.f_pwm)} (2-34)")

    # Flux observer (2-19 .. 2-24) as est_tune(), in the flux unit psi_base = 2^s V_base /
    # w_base (flux.h: psi(k) = psi(k-1) + g (u - R i - kg psi(k-1)) - L (i(k) - i(k-1)), psi in
    # psi_base, u and R i in V_base): g = T V_base / psi_base = T w_base / 2^s, r = R / Z_base,
    # l = L_q / L_base in Q12, kg = K_gain psi_base / V_base = K_gain 2^s / w_base (g kg =
    # T K_gain whatever s).  With s = 0 these are est_tune()'s, texts included.
    gval = math.ldexp(t_s * b.w_base, -b.psi_shift)
    g["flux.gain"] = g_right("flux.gain", gval,
                             f"T w_base = {fmt(b.w_base)} / {fmt(b.f_pwm)}" if b.psi_shift == 0
                             else f"T w_base / 2^s = {fmt(b.w_base)} / {fmt(b.f_pwm)} / "
                                  f"{b.k_psi}")
    g["flux.r"] = g_q15("flux.r", R / b.z_base, f"R / Z_base = {fmt(R)} / {fmt(b.z_base)}")
    g["flux.l"] = Gain("flux.l", m["lq_h"] / b.l_base, qn(m["lq_h"] / b.l_base, 12), None, "q12",
                       f"L_q / L_base = {fmt(m['lq_h'])} / {fmt(b.l_base)} (Q12)")
    g["flux.kg"] = g_q15("flux.kg", math.ldexp(d["kg_rad_s"] / b.w_base, b.psi_shift),
                         f"K_gain / w_base = {fmt(d['kg_rad_s'])} / {fmt(b.w_base)}"
                         if b.psi_shift == 0 else
                         f"K_gain 2^s / w_base = {fmt(d['kg_rad_s'])} x {b.k_psi} / "
                         f"{fmt(b.w_base)}")

    # Machine constants and limits.
    g["ld"] = Gain("ld", m["ld_h"] / b.l_base, qn(m["ld_h"] / b.l_base, 12), None, "q12",
                   f"L_d / L_base = {fmt(m['ld_h'])} / {fmt(b.l_base)} (Q12)")
    g["lq"] = Gain("lq", m["lq_h"] / b.l_base, qn(m["lq_h"] / b.l_base, 12), None, "q12",
                   f"L_q / L_base = {fmt(m['lq_h'])} / {fmt(b.l_base)} (Q12)")
    g["psi_f"] = g_q15("psi_f", m["psi_f_wb"] / b.psi_base,
                       f"psi_f / psi_base = {fmt(m['psi_f_wb'])} / {fmt(b.psi_base)}")
    g["i_trip"] = g_q15("i_trip", lim["i_trip_a"] / b.i_base,
                        f"i_trip / I_base = {fmt(lim['i_trip_a'])} / {fmt(b.i_base)}")
    sp = lim["speed_max_rpm"] * n_p / 60.0 / b.f_base
    g["speed_max"] = g_q15("speed_max", sp, f"speed_max n_p / 60 / f_base = "
                           f"{fmt(lim['speed_max_rpm'])} x {n_p} / 60 / {fmt(b.f_base)}")
    for key in ("vdc_uv", "vdc_ov"):
        g[key] = g_q15(key, lim[f"{key}_v"] / b.v_base,
                       f"{fmt(lim[f'{key}_v'])} V / V_base")
    g["svpwm.vdc_min"] = g_q15("svpwm.vdc_min", lim["vdc_svpwm_min_v"] / b.v_base,
                               f"{fmt(lim['vdc_svpwm_min_v'])} V / V_base")
    g["svpwm.i_deadband"] = g_q15("svpwm.i_deadband", d["deadband_a"] / b.i_base,
                                  f"{fmt(d['deadband_a'])} A / I_base")
    dt = inv["dead_time_s"] * inv["f_timer_hz"] / 2.0
    g["svpwm.dt_comp"] = Gain("svpwm.dt_comp", dt, int(math.floor(dt + 0.5)), None, "int",
                              f"t_d f_timer / 2 = {fmt(inv['dead_time_s'])} x "
                              f"{fmt(inv['f_timer_hz'])} / 2 (one compare count = 2 ticks "
                              f"of high time)")
    # the torque compensation's window: by default up to the speed where the learning law's
    # phase model holds with margin (tc_speed_limit_rpm; the same value on every call)
    if "drive.tc_speed_max_rpm" in cfg["defaulted"]:
        dr_tc = cfg["drive"]
        dr_tc["tc_speed_max_rpm"] = tc_speed_limit_rpm(cfg, ds, dr_tc["tc_speed_min_rpm"],
                                                       dr_tc["tc_speed_max_rpm"])
    return ds


def scale_factor_rows(cfg: dict, ds: Design) -> list[tuple[str, str, str]]:
    """(factor, derivation with numbers, value) rows of specs/scaling.md section 3."""
    b, g = ds.b, ds.gains
    lq = cfg["motor"]["lq_h"]
    # back-EMF estimator (Q10, in V_base): L_q di/dt / V_base = L_q / (Z_base T) di_pu, and
    # L_q / (Z_base T) = (L_q / L_base) 2^s / (T w_base) with the flux base of 2^s
    emf_l = math.ldexp(lq / b.l_base / (b.t_s * b.w_base), b.psi_shift)
    emf_text = (f"L_q / (L_base T w_base) = {fmt(lq)} / ({fmt(b.l_base)} x "
                f"{fmt(b.t_s * b.w_base)})" if b.psi_shift == 0 else
                f"L_q 2^s / (L_base T w_base) = L_q / (Z_base T) = {fmt(lq)} x {b.k_psi} / "
                f"({fmt(b.l_base)} x {fmt(b.t_s * b.w_base)})")
    return [
        ("1/sqrt(3) (Clarke)", "round(32768 / sqrt 3) = round(18918.6)", "18919 / 32768"),
        ("sqrt(3)/2 (inverse Clarke)", "round(32768 sqrt 3 / 2) = round(28377.9)", "28378 / 32768"),
        ("k_theta (2-28)", g["pll.k_theta"].derivation, str(g["pll.k_theta"].raw)),
        ("flux gain g (2-19)", g["flux.gain"].derivation, g["flux.gain"].repr_text()),
        ("r = R_pu", g["flux.r"].derivation, g["flux.r"].repr_text()),
        ("l = L_q / L_base (flux, Q12)", g["flux.l"].derivation, g["flux.l"].repr_text()),
        ("l (back-EMF, Q10)", emf_text, f"{qn(emf_l, 10)} / 1024"),
        ("speed low-pass alpha (2-34)", g["pll.speed_alpha"].derivation,
         g["pll.speed_alpha"].repr_text()),
        ("DC-bus low-pass alpha (2-34)", g["alpha_vdc"].derivation, g["alpha_vdc"].repr_text()),
        ("PWM period", f"f_timer / (2 f_pwm)", f"{b.period} ticks"),
        ("phase time", "T_x = U_x / V_dc x period", f"{b.period} ticks per V_dc"),
        ("dead-time compensation", g["svpwm.dt_comp"].derivation, f"{g['svpwm.dt_comp'].raw} counts"),
    ]


# --------------------------------------------------------------------------------------
# Bound checks (chapter 2, "the discrete system computation")
# --------------------------------------------------------------------------------------

@dataclass
class Bound:
    """One fixed-point bound: value against its limit, with the input that reaches it."""
    name: str
    equation: str
    value: float
    limit: float
    worst_input: str
    note: str
    violated: bool = False    # set for a range check failed at its lower end

    @property
    def ok(self) -> bool:
        """True when the bound holds."""
        return not self.violated and self.value <= self.limit

    @property
    def margin_pct(self) -> float:
        """(limit - value) / limit in percent (negative when violated)."""
        if self.limit == 0:
            return 0.0 if self.ok else -100.0
        return (self.limit - self.value) / self.limit * 100.0


def park_peak(a_alpha: float, a_beta: float, phi1: float, delta: float) -> float:
    """Largest |i_d|, |i_q| of Park (2-7, 2-8) applied with angle error delta to
    i_alpha = a_alpha sin x, i_beta = a_beta sin(x - phi1).

    Closed form of specs/equations.md E2-9 .. E2-12, evaluated without the small-angle
    approximation: the 2 w t term has amplitude A1 |sin(pi/4 - phi1/2)| and the DC terms
    are P = A1 (sin d + cos(d - phi1)) / 2, Q = A1 (sin(d - phi1) - cos d) / 2, with
    A1 = max(a_alpha, a_beta); the sampled sup over one period with the exact amplitudes
    is taken as well and the larger value is returned.
    """
    a1 = max(a_alpha, a_beta)
    ac = abs(math.sin(math.pi / 4.0 - phi1 / 2.0))
    p = 0.5 * (math.sin(delta) + math.cos(delta - phi1))
    q = 0.5 * (math.sin(delta - phi1) - math.cos(delta))
    closed = a1 * (ac + max(abs(p), abs(q)))
    x = np.linspace(0.0, 2.0 * math.pi, 721)
    ia, ib = a_alpha * np.sin(x), a_beta * np.sin(x - phi1)
    th = x - delta
    i_d = ia * np.cos(th) + ib * np.sin(th)
    i_q = -ia * np.sin(th) + ib * np.cos(th)
    return max(closed, float(np.max(np.abs(i_d))), float(np.max(np.abs(i_q))))


def flux_bounds(cfg: dict, ds: Design) -> list[Bound]:
    """The flux observer's steady state (2-25, 2-26) in the flux unit psi_base = 2^s V_base /
    w_base, with the quantised g and kg: at speed w (pu of w_base) the estimate is
    |H| |psi_a|, H = (z - 1) / (z - 1 + g kg), z = exp(j w w_base T) = exp(j w g 2^s)
    (flux.h; g = T w_base / 2^s); |psi_a| <= psi_f + |L_d - L_q| i_max (active flux, i_d down
    to -i_max); a DC current offset i_off adds R i_off / kg (2-26 with u = 0).  psi_temp =
    psi + L_q i (2-25) against the Q4.27 state range."""
    b, g, m, d, lim = ds.b, ds.gains, cfg["motor"], cfg["design"], cfg["limits"]
    bounds: list[Bound] = []
    gq = g["flux.gain"].quantised
    kgq = g["flux.kg"].quantised
    psi_a = active_flux_wb(cfg) / b.psi_base
    offset = g["flux.r"].quantised * (d["i_offset_a"] / b.i_base) / kgq if kgq > 0 else math.inf
    li = g["flux.l"].quantised * lim["i_max_a"] / b.i_base
    w_low = d["observer_min_speed_rpm"] * m["pole_pairs"] / 60.0 / b.f_base
    w_top = g["speed_max"].real
    for label, w in (("lowest observer speed", w_low), ("highest speed", w_top)):
        wt = w * gq * b.k_psi                   # rad per sample: w w_base T
        z = complex(math.cos(wt), math.sin(wt))
        h = abs((z - 1.0) / (z - 1.0 + gq * kgq))
        psi = (h * psi_a + offset) * 32768.0
        where = (f"w = {fmt(w, 4)} pu ({fmt(w * b.f_base, 4)} Hz), |H| = {fmt(h, 5)}, "
                 f"|psi_a| = {fmt(psi_a, 4)} pu, offset {fmt(d['i_offset_a'])} A")
        if b.psi_shift:
            where += f", psi_base = {fmt(b.psi_base)} Wb (psi_shift {b.psi_shift})"
        bounds.append(Bound(f"flux estimate at {label}", "2-26 (psi = (u - R i) / kg)", psi,
                            Q15_MAX, where, "output range +-1 pu"))
        bounds.append(Bound(f"flux psi_temp at {label}", "2-25 (psi_temp = psi + L i)",
                            psi + li * 32768.0, FLUX_STATE_MAX_Q15,
                            where + f", L_q i_max = {fmt(li, 4)} pu", "state range Q4.27, 16 pu"))
    return bounds


def flux_unit_bounds(cfg: dict, ds: Design) -> list[Bound]:
    """The table's fluxes and inductances in the flux base (rule 'flux base'): the fluxes
    (psi_f, pll.mag_min, drive.flux_tol) below 1 pu in Q15, the inductances (ld, lq, flux.l,
    drive.ld_hs, drive.lq_hs) below 8 pu in Q12 (no saturation), and the observer's
    high-pass gain flux.kg = K_gain 2^s / w_base below 1 pu in Q15."""
    b, g, m, d, dr = ds.b, ds.gains, cfg["motor"], cfg["design"], cfg["drive"]
    base = (f"psi_base = 2^{b.psi_shift} V_base / w_base = {fmt(b.psi_base)} Wb, L_base = "
            f"psi_base / I_base = {fmt(b.l_base * 1e3)} mH")
    out = []

    def row(name: str, eq: str, x: float, scale: float, what: str) -> None:
        out.append(Bound(f"flux base: {name}", eq, x * scale, float(Q15_MAX),
                         f"{what}, {base}", "Q15 below 1 pu" if scale == 32768.0
                         else "Q12 below 8 pu"))

    psi_f = m["psi_f_wb"]
    row("psi_f", "psi_f / psi_base < 1 (Q15)", psi_f / b.psi_base, 32768.0,
        f"psi_f = {fmt(psi_f)} Wb")
    row("pll.mag_min", "pll_mag_min psi_f / psi_base < 1 (Q15)",
        d["pll_mag_min"] * psi_f / b.psi_base, 32768.0,
        f"{fmt(d['pll_mag_min'])} x psi_f = {fmt(d['pll_mag_min'] * psi_f)} Wb")
    row("drive.flux_tol", "flux_tol_frac psi_f / psi_base < 1 (Q15)",
        dr["flux_tol_frac"] * psi_f / b.psi_base, 32768.0,
        f"{fmt(dr['flux_tol_frac'])} x psi_f = {fmt(dr['flux_tol_frac'] * psi_f)} Wb")
    ld_hs = m["ld_hs_h"] if m["ld_hs_h"] is not None else m["ld_h"]
    lq_hs = m["lq_hs_h"] if m["lq_hs_h"] is not None else m["lq_h"]
    for name, key, l_h in (("ld", "motor.ld_h", m["ld_h"]), ("lq", "motor.lq_h", m["lq_h"]),
                           ("flux.l", "motor.lq_h", m["lq_h"]),
                           ("drive.ld_hs", "motor.ld_hs_h", ld_hs),
                           ("drive.lq_hs", "motor.lq_hs_h", lq_hs)):
        row(name, "L / L_base < 8 (Q12)", l_h / b.l_base, 4096.0, f"{key} = {fmt(l_h)} H")
    row("flux.kg", "K_gain 2^s / w_base < 1 (Q15)", g["flux.kg"].real, 32768.0,
        f"design.kg_rad_s = {fmt(d['kg_rad_s'])} rad/s, w_base = {fmt(b.w_base)} rad/s")
    return out


def check_bounds(cfg: dict, ds: Design) -> list[Bound]:
    """Every fixed-point bound of chapter 2 for this scaling."""
    b, d, lim = ds.b, cfg["design"], cfg["limits"]
    bounds: list[Bound] = []
    i_trip = lim["i_trip_a"]
    amp = i_trip / b.i_base * 32768.0            # A of (2-1), Q15 counts
    dev = math.radians(d["clarke_phase_dev_deg"])
    phis = np.linspace(2.0 * math.pi / 3.0 - dev, 2.0 * math.pi / 3.0 + dev, 41)

    # Clarke (2-5, 2-6): i_alpha = A sin wt; i_beta = A sqrt(m^2 + n^2) / sqrt 3 sin(wt - phi1),
    # m = 1 + 2 cos phi, n = 2 sin phi.
    worst, worst_phi = -1.0, 0.0
    for phi in phis:
        mn = math.hypot(1.0 + 2.0 * math.cos(phi), 2.0 * math.sin(phi))
        val = amp * max(1.0, mn / SQRT3)
        if val > worst:
            worst, worst_phi = val, phi
    bounds.append(Bound("Clarke", "2-5, 2-6 (A sqrt(m^2+n^2)/sqrt 3)", worst, Q15_MAX,
                        f"i_trip = {fmt(i_trip)} A (A = {fmt(amp)}), phi = "
                        f"{fmt(math.degrees(worst_phi), 4)} deg",
                        f"phase of i_v within 120 +- {fmt(d['clarke_phase_dev_deg'])} deg"))

    # Park with the exact angle (2-9, 2-10) and with an angle error (2-11, 2-12).
    deltas = np.radians(np.linspace(-d["park_angle_err_deg"], d["park_angle_err_deg"], 73))
    for label, eq, dset in (("Park, exact angle", "2-9, 2-10 (A1 (sqrt(m1^2+n1^2) + |P|))", [0.0]),
                            ("Park, angle error", "2-11, 2-12 (A1 (sqrt(m2^2+n2^2) + |P1|))",
                             deltas)):
        worst, arg = -1.0, (0.0, 0.0)
        for phi in phis:
            mm, nn = 1.0 + 2.0 * math.cos(phi), 2.0 * math.sin(phi)
            a_beta = amp * math.hypot(mm, nn) / SQRT3
            phi1 = math.atan2(nn, mm)
            for delta in dset:
                val = park_peak(amp, a_beta, phi1, float(delta))
                if val > worst:
                    worst, arg = val, (phi, float(delta))
        bounds.append(Bound(label, eq, worst, Q15_MAX,
                            f"i_trip = {fmt(i_trip)} A, phi = {fmt(math.degrees(arg[0]), 4)} deg, "
                            f"angle error {fmt(math.degrees(arg[1]), 4)} deg",
                            "angle error up to +-" + fmt(d["park_angle_err_deg"]) + " deg"
                            if dset is not None and len(dset) > 1 else "exact angle"))

    bounds += flux_bounds(cfg, ds) + flux_unit_bounds(cfg, ds)

    # Inverse Park with harmonics: U_d = M + A_d sin(wt + phi_d), U_q = N + A_q sin(wt + phi_q),
    # |(M, N)| = Z = V_dc,max / sqrt 3 (largest vector of the linear SVPWM range),
    # A_d = A_q = h Z; |U_alpha| <= Z + A_dq1 + C1, |U_beta| <= Z + A_dq2 + C2 (document),
    # maximised over phi_d, phi_q.
    zv = cfg["inverter"]["vdc_max_v"] / SQRT3 / b.v_base * 32768.0
    ad = aq = d["v_harmonic_fraction"] * zv
    pd, pq = np.meshgrid(np.linspace(0, 2 * math.pi, 73), np.linspace(0, 2 * math.pi, 73))
    s1 = ad * np.cos(pd) - aq * np.sin(pq)
    s2 = ad * np.sin(pd) + aq * np.cos(pq)
    a_dq = 0.5 * np.hypot(s1, s2)
    c1 = 0.5 * np.abs(ad * np.sin(pd) - aq * np.cos(pq))
    c2 = 0.5 * np.abs(ad * np.cos(pd) + aq * np.sin(pq))
    ip = float(np.max(zv + a_dq + np.maximum(c1, c2)))
    hin = (f"|v| = V_dc,max / sqrt 3 = {fmt(cfg['inverter']['vdc_max_v'] / SQRT3)} V "
           f"(Z = {fmt(zv)}), A_d = A_q = {fmt(100 * d['v_harmonic_fraction'])} % of Z")
    bounds.append(Bound("inverse Park with harmonics", "Z + A_dq + C", ip, Q15_MAX, hin,
                        "worst phases of the harmonics"))
    # Inverse Clarke: every phase voltage is a projection of the alpha-beta vector, whose
    # magnitude equals |U_dq| <= Z + sqrt(A_d^2 + A_q^2).
    bounds.append(Bound("inverse Clarke with harmonics", "|U_x| <= Z + sqrt(A_d^2 + A_q^2)",
                        zv + math.hypot(ad, aq), Q15_MAX, hin, "amplitude-invariant inverse"))
    return bounds


# --------------------------------------------------------------------------------------
# Parameter table (include/qfoc/params.h)
# --------------------------------------------------------------------------------------

CTYPES = {"u8": (1, False), "u16": (2, False), "i16": (2, True), "u32": (4, False)}


@dataclass(frozen=True)
class Phys:
    """The physical meaning of a table field's integer: physical value = raw x factor, in
    unit (the motor file's unit of key when the field holds a motor-file value).  The
    calibration description (tools/a2l/qfoc_a2l.py) takes its conversions from here."""
    factor: float             # the physical value of one LSB
    unit: str                 # "-": a ratio or a plain integer
    real: float               # the physical value the integer represents before rounding
    rep: str                  # the representation: Q format and base, e.g. "Q15 of I_base"
    key: str | None = None    # the motor-file key (section.key) whose value real is
    lsb: float = 0.5          # the rounding bound in LSB: 0.5 rounded, 1 rounded down
    fixed: bool = False       # part of the identity or of the representation of other
                              # fields (a base, a shift, the rate they are per): not
                              # changed alone


def q_phys(frac_bits: int, base: float, base_name: str, unit: str, real: float,
           key: str | None = None) -> Phys:
    """A Q15 (or Q12) value of a base: raw / 2^frac_bits x base (a ratio: base_name "")."""
    return Phys(base / float(1 << frac_bits), unit, real,
                f"Q{frac_bits}" + (f" of {base_name}" if base_name else ""), key)


def int_phys(value: float, unit: str = "-", key: str | None = None, rep: str = "integer",
             factor: float = 1.0, lsb: float = 0.5, fixed: bool = False) -> Phys:
    """A plain integer in a unit (ms, rpm, 0.1 degC, counts)."""
    return Phys(factor, unit, value, rep, key, lsb, fixed)


def gain_phys(gn: "Gain", scale: float, unit: str, base: str) -> Phys:
    """A pi.h (left shift) or flux.h (right shift) mantissa with the table's shift: the
    physical gain is the per-unit gain times scale."""
    lsb = math.ldexp(1.0, gn.shift - 15) if gn.kind == "left" else math.ldexp(1.0, -15 - gn.shift)
    rep = (f"mantissa / 32768 x 2^{gn.shift}" if gn.kind == "left"
           else f"mantissa / 2^(15+{gn.shift})") + f" x {base}"
    return Phys(lsb * scale, unit, gn.real * scale, rep)


@dataclass
class Field:
    """One integer field of qfoc_param_table_t."""
    name: str
    ctype: str
    value: int
    comment: str
    phys: Phys | None = None  # its physical meaning (every field of the table has one)


@dataclass
class Group:
    """A sub-structure of qfoc_param_table_t, fields in declaration order."""
    name: str
    items: list


# drive_cfg.h ranges of the fields whose bounds are constants: (low, high).
DRIVE_RANGES = {
    "pole_pairs": (1, 16), "k_rpm": (1, 65535), "k_speed_rpm": (1, 65535),
    "speed_ramp": (1, Q15_MAX), "precharge_ms": (1, 60000), "offset_shift": (4, 10),
    "offset_window": (0, 2047), "i_align": (1, Q15_MAX), "align_ms": (2, 60000),
    "i_start": (1, Q15_MAX), "of_accel": (1, Q15_MAX), "of_speed": (1, Q15_MAX),
    "ho_angle": (1, 16384), "ho_dwell_ms": (1, 60000), "ol_timeout_ms": (1, 60000),
    "cl_hold_ms": (0, 60000), "t_ipm_max": (-400, 2000), "t_pcb_max": (-400, 2000),
    "vdc_ms": (1, 10), "temp_ms": (1, 10), "stall_err": (1, Q15_MAX), "flux_tol": (1, Q15_MAX),
    "stall_ms": (1, 60000), "phase_alpha": (1, Q15_MAX), "phase_i_min": (1, Q15_MAX),
    "phase_ratio": (0, Q15_MAX), "phase_ms": (1, 60000), "link_timeout_ms": (1, 60000),
    "clear_ms": (1, 60000), "fw_level": (1, Q15_MAX), "fw_alpha": (1, Q15_MAX),
    "tc_gain": (0, Q15_MAX), "tc_amp_max": (0, Q15_MAX), "tc_speed_max": (0, Q15_MAX),
    "para_speed": (1, Q15_MAX), "ld_hs": (0, Q15_MAX), "lq_hs": (0, Q15_MAX),
    "lin_id_cmd": (0, 0x3B), "lin_id_status": (0, 0x3B), "can_id_a": (0, 0x7FF),
    "can_id_b": (0, 0x7FF), "mtpa_speed": (0, Q15_MAX), "t_ipm_derate": (-400, 2000),
    "t_pcb_derate": (-400, 2000), "flux_band": (1, Q15_MAX), "flux_v_err": (0, Q15_MAX),
    "flux_r_err": (0, Q15_MAX), "psi_shift": (0, PSI_SHIFT_MAX), "ho_retries": (0, 3),
    "sensing": (0, 1), "shunt_settle": (0, 65535), "shunt_sample": (1, 65535),
    "shunt_hold": (1, SHUNT_HOLD_MAX),
}


def rpm_to_q15(rpm: int, k_rpm: int) -> int:
    """The drive's conversion of a target in rpm to Q15 speed: (rpm k_rpm + 2048) >> 12."""
    return (rpm * k_rpm + 2048) >> 12


def drive_range_text(name: str, flat: dict) -> str:
    """The admissible range of drive.<name> as the report lists it (with the table's limits)."""
    cross = {"i_align": "i_max", "i_start": "i_max", "tc_amp_max": "i_max",
             "of_speed": "speed_max"}
    if name == "rpm_min":
        return "1 .. rpm_max"
    if name == "rpm_max":
        return "rpm_min .. 65535, (rpm_max k_rpm + 2048) >> 12 <= speed_max"
    if name == "tc_speed_min":
        return "0 .. tc_speed_max"
    if name == "rpm_derate":
        return "rpm_min .. rpm_max"
    if name in ("t_ipm_derate", "t_pcb_derate"):
        return f"-400 .. {name.replace('derate', 'max')} - 1"
    lo, hi = DRIVE_RANGES[name]
    text = f"{lo} .. {hi}"
    if name in cross:
        text += f", <= {cross[name]} = {flat[cross[name]]}"
    if name == "lin_id_status":
        text += ", != lin_id_cmd"
    return text


def range_checks(table: list, ranges: dict | None = None) -> list[Bound]:
    """Field ranges documented in params.h, pi.h, svpwm.h, flux.h, pll.h and drive_cfg.h,
    and the cross-field conditions of params.h between the drive configuration and the
    table's limits.  ranges, when given, receives the range (low, high) of every field
    checked (field_ranges())."""
    flat = {name: f.value for name, f in flatten(table)}
    out = []

    def need(name: str, lo: int, hi: int, eq: str = "params.h range") -> None:
        if ranges is not None:
            lo0, hi0 = ranges.get(name, (lo, hi))
            ranges[name] = (max(lo, lo0), min(hi, hi0))
        v = flat[name]
        if not lo <= v <= hi:
            out.append(Bound(f"table field {name}", eq, float(v), float(hi),
                             f"{name} = {v}, allowed {lo} .. {hi}", "representation",
                             violated=True))

    need("f_pwm_hz", 1000, 40000)
    for key in ("v_base_mv", "i_base_ma", "f_base_mhz"):
        need(key, 1, 0xFFFFFFFF)
    need("svpwm.period", 100, 32767)
    need("svpwm.dt_comp", 0, flat["svpwm.period"] // 4)
    need("svpwm.i_deadband", 0, Q15_MAX)
    need("svpwm.vdc_min", 1, Q15_MAX)
    for pi in ("pi_id", "pi_iq", "pi_speed", "pi_fw", "pll.pi"):
        for k in ("kp", "ki"):
            need(f"{pi}.{k}", 0, Q15_MAX)
            need(f"{pi}.{k}_shift", 0, 15)
        need(f"{pi}.out_min", -Q15_MAX, flat[f"{pi}.out_max"])
        need(f"{pi}.out_max", flat[f"{pi}.out_min"], Q15_MAX)
    for k in ("flux.gain", "flux.r", "flux.l", "flux.kg", "ld", "lq", "psi_f"):
        need(k, 0, Q15_MAX)
    need("flux.gain_shift", 0, 15)
    for k in ("pll.err_clamp", "pll.mag_min", "pll.k_theta", "pll.speed_alpha", "alpha_vdc",
              "i_max", "speed_max", "vdc_uv", "v_max"):
        need(k, 1, Q15_MAX)
    need("i_trip", flat["i_max"], Q15_MAX)
    need("vdc_ov", flat["vdc_uv"] + 1, (ADC_CODES - 1) * 8 - 1,
         "params.h vdc_uv < vdc_ov < QFOC_PARAMS_VDC_READ_MAX")
    # drive_cfg.h ranges, then the cross-field conditions of params.h
    for key, (lo, hi) in DRIVE_RANGES.items():
        need(f"drive.{key}", lo, hi, "drive_cfg.h range")
    need("drive.rpm_max", 1, 65535, "drive_cfg.h range")
    need("drive.rpm_min", 1, flat["drive.rpm_max"], "drive_cfg.h range")
    need("drive.tc_speed_min", 0, flat["drive.tc_speed_max"], "drive_cfg.h range")
    need("drive.t_ipm_derate", -400, flat["drive.t_ipm_max"] - 1, "drive_cfg.h range")
    need("drive.t_pcb_derate", -400, flat["drive.t_pcb_max"] - 1, "drive_cfg.h range")
    need("drive.rpm_derate", flat["drive.rpm_min"], flat["drive.rpm_max"], "drive_cfg.h range")
    if flat["drive.lin_id_status"] == flat["drive.lin_id_cmd"]:
        out.append(Bound("table field drive.lin_id_status", "drive_cfg.h lin_id_status != "
                         "lin_id_cmd", 2.0, 1.0, f"lin_id_status = lin_id_cmd = "
                         f"{flat['drive.lin_id_cmd']}: the two frames need different "
                         "identifiers (value: frames per identifier)", "representation"))
    for key in ("drive.i_align", "drive.i_start", "drive.tc_amp_max"):
        need(key, 0, flat["i_max"], "params.h drive current <= i_max")
    need("drive.of_speed", 0, flat["speed_max"], "params.h drive.of_speed <= speed_max")
    window = flat["drive.shunt_settle"] + flat["drive.shunt_sample"]
    if 4 * window > flat["svpwm.period"]:
        out.append(Bound("table field drive.shunt_settle", "params.h 4 (shunt_settle + "
                         "shunt_sample) <= svpwm.period", float(4 * window),
                         float(flat["svpwm.period"]),
                         f"shunt_settle = {flat['drive.shunt_settle']}, shunt_sample = "
                         f"{flat['drive.shunt_sample']} ticks: 4 x {window} > period = "
                         f"{flat['svpwm.period']}", "representation", violated=True))
    top = rpm_to_q15(flat["drive.rpm_max"], flat["drive.k_rpm"])
    if top > flat["speed_max"]:
        out.append(Bound("table field drive.rpm_max", "params.h (rpm_max k_rpm + 2048) >> 12 "
                         "<= speed_max", float(top), float(flat["speed_max"]),
                         f"rpm_max = {flat['drive.rpm_max']}, k_rpm = {flat['drive.k_rpm']}: "
                         f"{top} > speed_max = {flat['speed_max']}", "representation"))
    return out


def field_ranges(table: list) -> dict[str, tuple[int, int]]:
    """The admissible integer range (low, high) of every field of the table, as
    range_checks() checks it (the library's range check: params.h, the modules' headers,
    drive_cfg.h); a bound that is another field of the table is taken at its value in this
    table.  The identity at its one value, crc over its type."""
    ranges = {"magic": (PARAMS_MAGIC, PARAMS_MAGIC),
              "version": (PARAMS_VERSION, PARAMS_VERSION), "crc": (0, 0xFFFFFFFF)}
    range_checks(table, ranges)
    return ranges


def drive_fields(cfg: dict, ds: Design) -> tuple[list[Field], list[str]]:
    """The qfoc_drive_cfg_t content (drive_cfg.h order) with the derivation of every value,
    and the notes the report lists (defaults that had to be adjusted)."""
    b, g, m, dr = ds.b, ds.gains, cfg["motor"], cfg["drive"]
    n_p = m["pole_pairs"]
    notes: list[str] = []
    rpm_q15 = f"n_p / 60 / f_base = {n_p} / 60 / {fmt(b.f_base)}"

    def rnd(x: float) -> int:
        return int(math.floor(x + 0.5))

    def amps(a: float) -> str:
        return f"{fmt(a)} A / I_base = {fmt(a)} / {fmt(b.i_base)}"

    def q15_field(name: str, x: float, text: str, phys: Phys) -> Field:
        raw = q15(x)
        if x != 0 and abs(raw / 32768.0 - x) > COARSE_GAIN_PCT / 100.0 * abs(x):
            notes.append(f"drive.{name}: rounding error {(raw / 32768.0 - x) / x * 100:+.2f} % "
                         f"(raw {raw}): the value is close to the Q15 resolution")
        err = "" if x == 0 else f"; stored {fmt(raw / 32768.0)}, error " \
                                f"{(raw / 32768.0 - x) / x * 100:+.2f} %"
        return Field(name, "i16", raw, f"{fmt(x)} = {text}{err}", phys)

    def src(key: str) -> str:
        return f"drive.{key}" + (", default" if f"drive.{key}" in cfg["defaulted"] else "")

    def ms_field(name: str, key: str) -> Field:
        return Field(name, "u16", int(dr[key]), f"{int(dr[key])} ms ({src(key)})",
                     int_phys(dr[key], "ms", f"drive.{key}"))

    # The physical meaning of the fields (Phys): speeds Q15 of w_base in mechanical rpm,
    # currents Q15 of I_base, low-pass coefficients 2 pi f_c / f_s as their corner frequency.
    rpm_pu = b.f_base * 60.0 / n_p          # mechanical rpm of 1 pu (w_base electrical)
    rpm_base = "w_base (60 f_base / n_p rpm)"

    def rpm_phys(key: str) -> Phys:
        return q_phys(15, rpm_pu, rpm_base, "rpm", dr[key], f"drive.{key}")

    def ramp_phys(key: str) -> Phys:
        return q_phys(15, rpm_pu * 1e3, rpm_base + " per ms", "rpm/s", dr[key], f"drive.{key}")

    def amp_phys(key: str) -> Phys:
        return q_phys(15, b.i_base, "I_base", "A", dr[key], f"drive.{key}")

    def ratio_phys(key: str) -> Phys:
        return q_phys(15, 1.0, "", "-", dr[key], f"drive.{key}")

    def fc_phys(key: str, f_s: float, s_name: str) -> Phys:
        return Phys(f_s / (2.0 * math.pi) / 32768.0, "Hz", dr[key],
                    f"Q15 of 2 pi f_c / {s_name} (low-pass corner f_c)", f"drive.{key}")

    def degc_phys(key: str) -> Phys:
        return int_phys(dr[key], "degC", f"drive.{key}", "0.1 degC", 0.1)

    k_rpm_real = n_p * 32768.0 / (60.0 * b.f_base) * 4096.0
    # rounded down (at most 1 / 4096 of a speed LSB per rpm low), so that the motor's
    # maximum speed in rpm converts to at most speed_max
    k_rpm = int(math.floor(k_rpm_real))
    k_speed_real = 60.0 * b.f_base / (n_p * 32768.0) * 32768.0
    k_speed = rnd(k_speed_real)
    speed_max = g["speed_max"].raw
    if dr["rpm_max"] is None:
        want = int(math.floor(m["max_speed_rpm"]))
        fit = ((speed_max + 1) * 4096 - 2049) // k_rpm if k_rpm > 0 else want
        rpm_max = max(0, min(want, fit))
        if rpm_max < want:
            why = (f"{rpm_max} rpm: motor.max_speed_rpm {want} lowered to the largest rpm with "
                   f"(rpm k_rpm + 2048) >> 12 <= speed_max = {speed_max} ({want} rpm -> "
                   f"{rpm_to_q15(want, k_rpm)}: k_rpm and speed_max rounded)")
            notes.append(f"drive.rpm_max = {why}; set drive.rpm_max or limits.speed_max_rpm "
                         "to choose otherwise")
        else:
            why = f"{rpm_max} rpm = motor.max_speed_rpm"
    else:
        rpm_max = int(math.floor(dr["rpm_max"]))
        why = f"{rpm_max} rpm (drive.rpm_max)"
    ds.phys["drive.rpm_max"] = rpm_max
    ds.phys["drive_notes"] = notes
    if dr["rpm_max"] is not None:
        rpm_max_phys = int_phys(dr["rpm_max"], "rpm", "drive.rpm_max", lsb=1.0)
    elif rpm_max == int(math.floor(m["max_speed_rpm"])):
        rpm_max_phys = int_phys(m["max_speed_rpm"], "rpm", "motor.max_speed_rpm", lsb=1.0)
    else:
        rpm_max_phys = int_phys(rpm_max, "rpm")
    mtpa_x = dr["mtpa_speed_rpm"] * n_p / 60.0 / b.f_base * 32768.0
    mtpa_phys = q_phys(15, rpm_pu, rpm_base, "rpm", dr["mtpa_speed_rpm"], "drive.mtpa_speed_rpm") \
        if rnd(mtpa_x) <= Q15_MAX else q_phys(15, rpm_pu, rpm_base, "rpm", Q15_MAX / 32768.0 * rpm_pu)
    rpm_min = int(math.floor(dr["rpm_min"]))
    ld_hs_h = m["ld_hs_h"] if m["ld_hs_h"] is not None else m["ld_h"]
    lq_hs_h = m["lq_hs_h"] if m["lq_hs_h"] is not None else m["lq_h"]
    ld_src = "motor.ld_hs_h" if m["ld_hs_h"] is not None else "motor.ld_h (no ld_hs_h)"
    lq_src = "motor.lq_hs_h" if m["lq_hs_h"] is not None else "motor.lq_h (no lq_hs_h)"
    rated_e = m["rated_speed_rpm"] * n_p / 60.0 / b.f_base
    fields = [
        Field("pole_pairs", "u8", n_p, "motor.pole_pairs",
              int_phys(n_p, "-", "motor.pole_pairs", fixed=True)),
        Field("k_rpm", "u16", k_rpm, f"{fmt(k_rpm_real)} = n_p 32768 / (60 f_base) x 4096 = "
              f"{n_p} x 32768 / (60 x {fmt(b.f_base)}) x 4096 (Q12)",
              Phys(1.0 / 4096.0, "-", k_rpm_real / 4096.0,
                   "Q12: Q15 speed counts per rpm, n_p 32768 / (60 f_base)", lsb=1.0, fixed=True)),
        Field("k_speed_rpm", "u16", k_speed, f"{fmt(k_speed_real)} = 60 f_base / (n_p 32768) x "
              f"32768 = 60 x {fmt(b.f_base)} / {n_p} (Q15)",
              Phys(1.0 / 32768.0, "rpm", k_speed_real / 32768.0,
                   "Q15: rpm per Q15 speed count, 60 f_base / (n_p 32768)", fixed=True)),
        Field("rpm_min", "u16", rpm_min, f"{rpm_min} rpm ({src('rpm_min')})",
              int_phys(dr["rpm_min"], "rpm", "drive.rpm_min", lsb=1.0)),
        Field("rpm_max", "u16", rpm_max, why, rpm_max_phys),
        q15_field("speed_ramp", dr["accel_rpm_s"] * 1e-3 * n_p / 60.0 / b.f_base,
                  f"{fmt(dr['accel_rpm_s'])} rpm/s x 1 ms x {rpm_q15} (per ms)",
                  ramp_phys("accel_rpm_s")),
        ms_field("precharge_ms", "precharge_ms"),
        Field("offset_shift", "u8", int(dr["offset_shift"]),
              f"2^{int(dr['offset_shift'])} = {2 ** int(dr['offset_shift'])} samples per offset",
              int_phys(dr["offset_shift"], "-", "drive.offset_shift", "log2 of the samples")),
        Field("offset_window", "u16", int(dr["offset_window_counts"]),
              f"{int(dr['offset_window_counts'])} counts = "
              f"{fmt(dr['offset_window_counts'] / 2048.0 * 100.0, 3)} % of 2048 = "
              f"{fmt(dr['offset_window_counts'] / 2048.0 * b.i_base, 4)} A",
              int_phys(dr["offset_window_counts"], "ADC codes", "drive.offset_window_counts")),
        q15_field("i_align", dr["i_align_a"] / b.i_base, amps(dr["i_align_a"]),
                  amp_phys("i_align_a")),
        ms_field("align_ms", "align_ms"),
        q15_field("i_start", dr["i_start_a"] / b.i_base, amps(dr["i_start_a"]),
                  amp_phys("i_start_a")),
        q15_field("of_accel", dr["of_accel_rpm_s"] * 1e-3 * n_p / 60.0 / b.f_base,
                  f"{fmt(dr['of_accel_rpm_s'])} rpm/s x 1 ms x {rpm_q15} (per ms)",
                  ramp_phys("of_accel_rpm_s")),
        q15_field("of_speed", dr["of_speed_rpm"] * n_p / 60.0 / b.f_base,
                  f"{fmt(dr['of_speed_rpm'])} rpm x {rpm_q15}", rpm_phys("of_speed_rpm")),
        Field("ho_angle", "u16", rnd(dr["ho_angle_deg"] / 360.0 * 65536.0),
              f"{fmt(dr['ho_angle_deg'] / 360.0 * 65536.0)} = {fmt(dr['ho_angle_deg'])} deg / "
              f"360 x 65536",
              Phys(360.0 / 65536.0, "deg", dr["ho_angle_deg"], "65536 counts per electrical turn",
                   "drive.ho_angle_deg")),
        ms_field("ho_dwell_ms", "ho_dwell_ms"),
        ms_field("ol_timeout_ms", "ol_timeout_ms"),
        ms_field("cl_hold_ms", "cl_hold_ms"),
        Field("t_ipm_max", "i16", rnd(dr["t_ipm_max_degc"] * 10.0),
              f"{fmt(dr['t_ipm_max_degc'])} degC x 10", degc_phys("t_ipm_max_degc")),
        Field("t_pcb_max", "i16", rnd(dr["t_pcb_max_degc"] * 10.0),
              f"{fmt(dr['t_pcb_max_degc'])} degC x 10", degc_phys("t_pcb_max_degc")),
        ms_field("vdc_ms", "vdc_ms"),
        ms_field("temp_ms", "temp_ms"),
        q15_field("stall_err", dr["stall_err_rpm"] * n_p / 60.0 / b.f_base,
                  f"{fmt(dr['stall_err_rpm'])} rpm x {rpm_q15}"
                  + (f" (0.3 x rated {fmt(rated_e, 4)} pu)" if "drive.stall_err_rpm"
                     in cfg["defaulted"] else ""), rpm_phys("stall_err_rpm")),
        q15_field("flux_tol", dr["flux_tol_frac"] * m["psi_f_wb"] / b.psi_base,
                  f"{fmt(dr['flux_tol_frac'])} psi_f / psi_base = {fmt(dr['flux_tol_frac'])} x "
                  f"{fmt(m['psi_f_wb'])} / {fmt(b.psi_base)}",
                  q_phys(15, b.psi_base, "psi_base", "Wb", dr["flux_tol_frac"] * m["psi_f_wb"])),
        ms_field("stall_ms", "stall_ms"),
        q15_field("phase_alpha", 2.0 * math.pi * dr["phase_fc_hz"] / b.f_pwm,
                  f"2 pi f_c / f_pwm = 2 pi x {fmt(dr['phase_fc_hz'])} / {fmt(b.f_pwm)} (2-34)",
                  fc_phys("phase_fc_hz", b.f_pwm, "f_pwm")),
        q15_field("phase_i_min", dr["phase_i_min_a"] / b.i_base,
                  amps(dr["phase_i_min_a"]), amp_phys("phase_i_min_a")),
        q15_field("phase_ratio", dr["phase_ratio"], src("phase_ratio"), ratio_phys("phase_ratio")),
        ms_field("phase_ms", "phase_ms"),
        ms_field("link_timeout_ms", "link_timeout_ms"),
        ms_field("clear_ms", "clear_ms"),
        q15_field("fw_level", dr["fw_level"], "FWK_LVL, " + (
            "design.fw_v_max (default)" if "drive.fw_level" in cfg["defaulted"] else
            "drive.fw_level"), ratio_phys("fw_level")),
        q15_field("fw_alpha", 2.0 * math.pi * dr["fw_fc_hz"] * T_TICK_S,
                  f"2 pi f_c T_tick = 2 pi x {fmt(dr['fw_fc_hz'])} x {fmt(T_TICK_S)} (2-34; the "
                  "1 ms tick)", fc_phys("fw_fc_hz", 1.0 / T_TICK_S, "f_tick")),
        Field("tc_gain", "i16", int(dr["tc_gain_q15"]),
              f"{fmt(dr['tc_gain_q15'] / 32768.0)} = drive.tc_gain_q15 / 32768 (trqcomp.md)",
              Phys(1.0 / 32768.0, "-", dr["tc_gain_q15"] / 32768.0, "Q15")),
        q15_field("tc_amp_max", dr["tc_amp_max_a"] / b.i_base,
                  amps(dr["tc_amp_max_a"]), amp_phys("tc_amp_max_a")),
        q15_field("tc_speed_min", dr["tc_speed_min_rpm"] * n_p / 60.0 / b.f_base,
                  f"{fmt(dr['tc_speed_min_rpm'])} rpm x {rpm_q15}", rpm_phys("tc_speed_min_rpm")),
        q15_field("tc_speed_max", dr["tc_speed_max_rpm"] * n_p / 60.0 / b.f_base,
                  f"{fmt(dr['tc_speed_max_rpm'])} rpm x {rpm_q15}", rpm_phys("tc_speed_max_rpm")),
        q15_field("para_speed", dr["para_speed_rpm"] * n_p / 60.0 / b.f_base,
                  f"{fmt(dr['para_speed_rpm'])} rpm x {rpm_q15}", rpm_phys("para_speed_rpm")),
        Field("ld_hs", "i16", qn(ld_hs_h / b.l_base, 12),
              f"{fmt(ld_hs_h / b.l_base)} = {ld_src} / L_base = {fmt(ld_hs_h)} / "
              f"{fmt(b.l_base)} (Q12)",
              q_phys(12, b.l_base, "L_base", "H", ld_hs_h,
                     "motor.ld_hs_h" if m["ld_hs_h"] is not None else "motor.ld_h")),
        Field("lq_hs", "i16", qn(lq_hs_h / b.l_base, 12),
              f"{fmt(lq_hs_h / b.l_base)} = {lq_src} / L_base = {fmt(lq_hs_h)} / "
              f"{fmt(b.l_base)} (Q12)",
              q_phys(12, b.l_base, "L_base", "H", lq_hs_h,
                     "motor.lq_hs_h" if m["lq_hs_h"] is not None else "motor.lq_h")),
        Field("lin_id_cmd", "u8", int(dr["lin_id_cmd"]), f"LIN command frame ({src('lin_id_cmd')})",
              int_phys(dr["lin_id_cmd"], "-", "drive.lin_id_cmd", "LIN frame identifier")),
        Field("lin_id_status", "u8", int(dr["lin_id_status"]),
              f"LIN status frame ({src('lin_id_status')})",
              int_phys(dr["lin_id_status"], "-", "drive.lin_id_status", "LIN frame identifier")),
        Field("can_id_a", "u16", int(dr["can_id_a"]), f"CAN status, even frames ({src('can_id_a')})",
              int_phys(dr["can_id_a"], "-", "drive.can_id_a", "CAN identifier (11 bits)")),
        Field("can_id_b", "u16", int(dr["can_id_b"]), f"CAN status, odd frames ({src('can_id_b')})",
              int_phys(dr["can_id_b"], "-", "drive.can_id_b", "CAN identifier (11 bits)")),
        Field("mtpa_speed", "i16", min(rnd(dr["mtpa_speed_rpm"] * n_p / 60.0 / b.f_base * 32768.0),
                                       Q15_MAX),
              f"{fmt(dr['mtpa_speed_rpm'])} rpm x {rpm_q15} x 32768, at most 32767 "
              f"({src('mtpa_speed_rpm')})", mtpa_phys),
        Field("t_ipm_derate", "i16", rnd(dr["t_ipm_derate_degc"] * 10.0),
              f"{fmt(dr['t_ipm_derate_degc'])} degC x 10 ({src('t_ipm_derate_degc')})",
              degc_phys("t_ipm_derate_degc")),
        Field("t_pcb_derate", "i16", rnd(dr["t_pcb_derate_degc"] * 10.0),
              f"{fmt(dr['t_pcb_derate_degc'])} degC x 10 ({src('t_pcb_derate_degc')})",
              degc_phys("t_pcb_derate_degc")),
        Field("rpm_derate", "u16", int(math.floor(dr["derate_rpm"])),
              f"{int(math.floor(dr['derate_rpm']))} rpm ({src('derate_rpm')})",
              int_phys(dr["derate_rpm"], "rpm", "drive.derate_rpm", lsb=1.0)),
        q15_field("flux_band", dr["flux_band"], f"{fmt(dr['flux_band'])} ({src('flux_band')})",
                  ratio_phys("flux_band")),
        q15_field("flux_v_err", dr["flux_v_err_v"] / b.v_base,
                  f"{fmt(dr['flux_v_err_v'])} V / V_base {fmt(b.v_base)} V "
                  f"({src('flux_v_err_v')})",
                  q_phys(15, b.v_base, "V_base", "V", dr["flux_v_err_v"], "drive.flux_v_err_v")),
        q15_field("flux_r_err", dr["flux_r_err"], f"{fmt(dr['flux_r_err'])} of R "
                  f"({src('flux_r_err')})", ratio_phys("flux_r_err")),
        Field("psi_shift", "u8", b.psi_shift,
              f"flux base psi_base = 2^{b.psi_shift} V_base / w_base = {fmt(b.psi_base)} Wb, "
              f"L_base = psi_base / I_base = {fmt(b.l_base * 1e3)} mH ({b.shift_src}: active "
              f"flux {fmt(active_flux_wb(cfg))} Wb = "
              f"{fmt(active_flux_wb(cfg) / b.psi_base, 4)} pu)",
              int_phys(b.psi_shift, "-", "scaling.psi_shift" if cfg["scaling"].get("psi_shift")
                       is not None else None, "s of psi_base = 2^s V_base / w_base", fixed=True)),
        Field("ho_retries", "u8", int(dr["ho_retries"]),
              f"{int(dr['ho_retries'])} start retries ({src('ho_retries')})",
              int_phys(dr["ho_retries"], "-", "drive.ho_retries")),
    ] + sensing_fields(cfg)
    return fields, notes


def shunt_ticks(ns: float, f_timer: float) -> int:
    """A single-shunt time in PWM-timer ticks, rounded up (E13-7): never shorter than the
    motor file's time."""
    return int(math.ceil(ns * f_timer / 1e9 - 1e-9))


def sensing_fields(cfg: dict) -> list[Field]:
    """drive.sensing .. drive.shunt_hold (layout version 5), from [sensing]."""
    sen, f_timer = cfg["sensing"], cfg["inverter"]["f_timer_hz"]
    ns_tick = 1e9 / f_timer

    def src(key: str) -> str:
        return f"sensing.{key}" + (", default" if f"sensing.{key}" in cfg["defaulted"] else "")

    def ticks(name: str, key: str) -> Field:
        raw = shunt_ticks(sen[key], f_timer)
        return Field(name, "u16", raw,
                     f"{fmt(sen[key])} ns x f_timer {fmt(f_timer)} Hz / 1e9, rounded up: {raw} "
                     f"ticks ({src(key)})",
                     int_phys(sen[key], "ns", f"sensing.{key}", "PWM-timer ticks",
                              factor=ns_tick, lsb=1.0))
    mode = SENSING_MODES[sen["mode"]]
    return [
        Field("sensing", "u8", mode, f"{sen['mode']} ({src('mode')}): "
              + ("QFOC_SENSING_SHUNT" if mode else "QFOC_SENSING_PHASES"),
              int_phys(mode, "-", None, "0 two phase-current sensors, 1 one DC-link shunt",
                       fixed=True)),
        ticks("shunt_settle", "shunt_settle_ns"),
        ticks("shunt_sample", "shunt_sample_ns"),
        Field("shunt_hold", "u16", int(sen["shunt_hold"]),
              f"{int(sen['shunt_hold'])} periods ({src('shunt_hold')})",
              int_phys(sen["shunt_hold"], "periods", "sensing.shunt_hold")),
    ]


def gain_fields(prefix: str, kp: Gain, ki: Gain, out_min: int, out_max: int,
                limit_note: str, units: tuple) -> list[Field]:
    """The six fields of a qfoc_pi_params_t.  units: the physical meaning, ((scale, unit,
    base) of kp, the same of ki T, Phys of out_min, Phys of out_max): the physical gain is
    the per-unit gain times scale."""
    def note(gn: Gain) -> str:
        return (f"{fmt(gn.real)} = {gn.derivation}; stored {fmt(gn.quantised)}, "
                f"error {gn.rel_err * 100:+.3f} %")
    (kp_s, ki_s, out_lo, out_hi) = units
    return [
        Field("kp", "i16", kp.raw, f"kp {note(kp)}", gain_phys(kp, *kp_s)),
        Field("kp_shift", "u8", kp.shift, f"kp_real = kp / 32768 x 2^{kp.shift}",
              int_phys(kp.shift, rep="left shift of kp", fixed=True)),
        Field("ki", "i16", ki.raw, f"ki T {note(ki)}", gain_phys(ki, *ki_s)),
        Field("ki_shift", "u8", ki.shift, f"kiT_real = ki / 32768 x 2^{ki.shift}",
              int_phys(ki.shift, rep="left shift of ki", fixed=True)),
        Field("out_min", "i16", out_min, f"{fmt(out_min / 32768.0)} pu: {limit_note}", out_lo),
        Field("out_max", "i16", out_max, f"{fmt(out_max / 32768.0)} pu: {limit_note}", out_hi),
    ]


def qnote(gn: Gain) -> str:
    """Comment text for a quantised value."""
    return f"{fmt(gn.real)} = {gn.derivation}"


def build_table(cfg: dict, ds: Design) -> list:
    """The qfoc_param_table_t content in declaration order (crc excluded)."""
    b, g = ds.b, ds.gains
    m, inv, d, lim = cfg["motor"], cfg["inverter"], cfg["design"], cfg["limits"]
    v_out = g["pi_id.out"].raw
    i_max = g["i_max"].raw
    # The physical meaning of every field (Phys): currents Q15 of I_base, voltages of V_base,
    # speeds of w_base in mechanical rpm, fluxes of psi_base, inductances Q12 of L_base,
    # gains in SI units with the table's shifts, low-pass coefficients as corner frequencies.
    n_p, f_timer = m["pole_pairs"], inv["f_timer_hz"]
    rpm_pu = b.f_base * 60.0 / n_p
    rpm_base = "w_base (60 f_base / n_p rpm)"
    v_lim = g["pi_id.out"].real * b.v_base

    def volts(real: float, key: str | None = None) -> Phys:
        return q_phys(15, b.v_base, "V_base", "V", real, key)

    def amps(real: float, key: str | None = None) -> Phys:
        return q_phys(15, b.i_base, "I_base", "A", real, key)

    def ratio(real: float, key: str | None = None) -> Phys:
        return q_phys(15, 1.0, "", "-", real, key)

    def corner(key: str) -> Phys:
        return Phys(b.f_pwm / (2.0 * math.pi) / 32768.0, "Hz", d[key],
                    "Q15 of 2 pi f_c / f_pwm (low-pass corner f_c)", f"design.{key}")

    speed_units = ((b.i_base * n_p / b.w_base, "A s/rad", "I_base n_p / w_base"),
                   (b.i_base * n_p / b.w_base / d["speed_t_sam_s"], "A/rad",
                    "I_base n_p / w_base / T_sam"),
                   amps(-lim["i_max_a"]), amps(lim["i_max_a"], "limits.i_max_a"))
    cur_units = ((b.v_base / b.i_base, "ohm", "V_base / I_base"),
                 (b.v_base / b.i_base * b.f_pwm, "ohm/s", "V_base / I_base / T_s"),
                 volts(-v_lim), volts(v_lim))
    fw_units = ((b.i_base, "A", "I_base (per unit of voltage utilisation)"),
                (b.i_base / T_TICK_S, "A/s", "I_base / T_tick (per unit of voltage utilisation)"),
                amps(-lim["i_max_a"]), amps(0.0))
    pll_units = ((b.w_base, "1/s", "w_base (rad/s per rad of angle error)"),
                 (b.w_base * b.f_pwm, "1/s^2", "w_base / T_s (rad/s^2 per rad of angle error)"),
                 q_phys(15, rpm_pu, rpm_base, "rpm", -Q15_MAX / 32768.0 * rpm_pu),
                 q_phys(15, rpm_pu, rpm_base, "rpm", Q15_MAX / 32768.0 * rpm_pu))
    return [
        Field("magic", "u32", PARAMS_MAGIC, "QFOC_PARAMS_MAGIC, ASCII \"QFOC\" little-endian",
              int_phys(PARAMS_MAGIC, rep="QFOC_PARAMS_MAGIC", fixed=True)),
        Field("version", "u16", PARAMS_VERSION, "QFOC_PARAMS_VERSION",
              int_phys(PARAMS_VERSION, rep="QFOC_PARAMS_VERSION", fixed=True)),
        Field("f_pwm_hz", "u16", int(b.f_pwm), f"f_pwm = {fmt(b.f_pwm)} Hz, T_s = "
              f"{fmt(b.t_s * 1e6)} us", int_phys(b.f_pwm, "Hz", "inverter.f_pwm_hz", fixed=True)),
        Field("v_base_mv", "u32", int(round(b.v_base * 1000)), f"V_base = {fmt(b.v_base)} V",
              int_phys(b.v_base, "V", "sensing.vdc_full_scale_v", "mV", 1e-3, fixed=True)),
        Field("i_base_ma", "u32", int(round(b.i_base * 1000)), f"I_base = {fmt(b.i_base)} A",
              int_phys(b.i_base, "A", "sensing.i_full_scale_a", "mA", 1e-3, fixed=True)),
        Field("f_base_mhz", "u32", int(round(b.f_base * 1000)),
              f"f_base = {fmt(b.f_base)} Hz, w_base = {fmt(b.w_base)} rad/s",
              int_phys(b.f_base, "Hz", "scaling.f_base_hz", "mHz", 1e-3, fixed=True)),
        Group("svpwm", [
            Field("period", "u16", b.period, f"f_timer / (2 f_pwm) = "
                  f"{fmt(cfg['inverter']['f_timer_hz'])} / (2 x {fmt(b.f_pwm)}) ticks",
                  int_phys(f_timer / (2.0 * b.f_pwm), "ticks", rep="timer ticks, f_timer / "
                           "(2 f_pwm)", fixed=True)),
            Field("dt_comp", "u16", g["svpwm.dt_comp"].raw, qnote(g["svpwm.dt_comp"]),
                  Phys(2.0 / f_timer, "s", inv["dead_time_s"], "compare counts of 2 / f_timer",
                       "inverter.dead_time_s")),
            Field("i_deadband", "i16", g["svpwm.i_deadband"].raw, qnote(g["svpwm.i_deadband"]),
                  amps(d["deadband_a"], "design.deadband_a")),
            Field("vdc_min", "i16", g["svpwm.vdc_min"].raw, qnote(g["svpwm.vdc_min"]),
                  volts(lim["vdc_svpwm_min_v"], "limits.vdc_svpwm_min_v")),
        ]),
        Group("pi_id", gain_fields("pi_id", g["pi_id.kp"], g["pi_id.ki"], -v_out, v_out,
                                   g["pi_id.out"].derivation, cur_units)),
        Group("pi_iq", gain_fields("pi_iq", g["pi_iq.kp"], g["pi_iq.ki"], -v_out, v_out,
                                   g["pi_iq.out"].derivation, cur_units)),
        Group("pi_speed", gain_fields("pi_speed", g["pi_speed.kp"], g["pi_speed.ki"], -i_max,
                                      i_max, "+-i_max (i_q reference)", speed_units)),
        Group("pi_fw", gain_fields("pi_fw", g["pi_fw.kp"], g["pi_fw.ki"], -i_max, 0,
                                   "i_d reference in [-i_max, 0]", fw_units)),
        Group("flux", [
            Field("gain", "i16", g["flux.gain"].raw,
                  f"g {qnote(g['flux.gain'])} = gain / 2^(15+{g['flux.gain'].shift})",
                  gain_phys(g["flux.gain"], math.ldexp(1.0 / b.w_base, b.psi_shift), "s",
                            "2^s / w_base (the sample time T)")),
            Field("gain_shift", "u8", g["flux.gain"].shift, "right shift: g = gain / 2^(15+shift)",
                  int_phys(g["flux.gain"].shift, rep="right shift of gain", fixed=True)),
            Field("r", "i16", g["flux.r"].raw, qnote(g["flux.r"]),
                  q_phys(15, b.z_base, "Z_base", "ohm", m["rs_ohm"], "motor.rs_ohm")),
            Field("l", "i16", g["flux.l"].raw, qnote(g["flux.l"]),
                  q_phys(12, b.l_base, "L_base", "H", m["lq_h"], "motor.lq_h")),
            Field("kg", "i16", g["flux.kg"].raw, qnote(g["flux.kg"]),
                  q_phys(15, math.ldexp(b.w_base, -b.psi_shift), "w_base / 2^s", "rad/s",
                         d["kg_rad_s"], "design.kg_rad_s")),
        ]),
        Group("pll", [
            Group("pi", gain_fields("pll.pi", g["pll.kp"], g["pll.ki"], -Q15_MAX, Q15_MAX,
                                    "speed range (est_tune)", pll_units)),
            Field("err_clamp", "i16", g["pll.err_clamp"].raw, qnote(g["pll.err_clamp"]),
                  ratio(d["pll_clamp"], "design.pll_clamp")),
            Field("mag_min", "i16", g["pll.mag_min"].raw, qnote(g["pll.mag_min"]),
                  q_phys(15, b.psi_base, "psi_base", "Wb", d["pll_mag_min"] * m["psi_f_wb"])),
            Field("k_theta", "u16", g["pll.k_theta"].raw, qnote(g["pll.k_theta"]),
                  int_phys(g["pll.k_theta"].real, rep="f_base / f_pwm x 131072", fixed=True)),
            Field("speed_alpha", "i16", g["pll.speed_alpha"].raw, qnote(g["pll.speed_alpha"]),
                  corner("speed_fc_hz")),
        ]),
        Field("alpha_vdc", "i16", g["alpha_vdc"].raw, qnote(g["alpha_vdc"]), corner("vdc_fc_hz")),
        Field("ld", "i16", g["ld"].raw, qnote(g["ld"]),
              q_phys(12, b.l_base, "L_base", "H", m["ld_h"], "motor.ld_h")),
        Field("lq", "i16", g["lq"].raw, qnote(g["lq"]),
              q_phys(12, b.l_base, "L_base", "H", m["lq_h"], "motor.lq_h")),
        Field("psi_f", "i16", g["psi_f"].raw, qnote(g["psi_f"]),
              q_phys(15, b.psi_base, "psi_base", "Wb", m["psi_f_wb"], "motor.psi_f_wb")),
        Field("i_max", "i16", g["i_max"].raw, qnote(g["i_max"]),
              amps(lim["i_max_a"], "limits.i_max_a")),
        Field("i_trip", "i16", g["i_trip"].raw, qnote(g["i_trip"]),
              amps(lim["i_trip_a"], "limits.i_trip_a")),
        Field("speed_max", "i16", g["speed_max"].raw, qnote(g["speed_max"]),
              q_phys(15, rpm_pu, rpm_base, "rpm", lim["speed_max_rpm"], "limits.speed_max_rpm")),
        Field("vdc_uv", "i16", g["vdc_uv"].raw, qnote(g["vdc_uv"]),
              volts(lim["vdc_uv_v"], "limits.vdc_uv_v")),
        Field("vdc_ov", "i16", g["vdc_ov"].raw, qnote(g["vdc_ov"]),
              volts(lim["vdc_ov_v"], "limits.vdc_ov_v")),
        Field("v_max", "i16", g["v_max"].raw, qnote(g["v_max"]),
              ratio(d["fw_v_max"], "design.fw_v_max")),
        Group("drive", drive_fields(cfg, ds)[0]),
    ]


def crc_field(crc: int) -> Field:
    """The table's last field, the CRC of every field before it."""
    return Field("crc", "u32", crc, "CRC-32/ISO-HDLC of every field above",
                 int_phys(crc, rep="CRC-32/ISO-HDLC of every field before it", fixed=True))


def flatten(items: list, prefix: str = "") -> list[tuple[str, Field]]:
    """(dotted name, field) pairs in declaration order."""
    out = []
    for it in items:
        if isinstance(it, Group):
            out += flatten(it.items, f"{prefix}{it.name}.")
        else:
            out.append((prefix + it.name, it))
    return out


def serialise(items: list) -> bytes:
    """params.h serialisation: every field in order, little-endian in its own width."""
    data = bytearray()
    for _name, f in flatten(items):
        width, signed = CTYPES[f.ctype]
        data += int(f.value).to_bytes(width, "little", signed=signed)
    return bytes(data)


def c_literal(f: Field) -> str:
    """MISRA-friendly integer literal of a field."""
    if f.ctype == "u32":
        return f"0x{f.value:08X}u" if f.name in ("magic", "crc") else f"{f.value}u"
    if f.name in ("lin_id_cmd", "lin_id_status"):
        return f"0x{f.value:02X}u"
    if f.name in ("can_id_a", "can_id_b"):
        return f"0x{f.value:03X}u"
    if f.ctype in ("u8", "u16"):
        return f"{f.value}u"
    return f"(int16_t){f.value}" if f.value < 0 else str(f.value)


def c_comment(text: str) -> str:
    """A C comment body without comment terminators."""
    return text.replace("*/", "* /").replace("/*", "/ *")


def emit_items(items: list, indent: int) -> list[str]:
    """Designated-initialiser lines of a structure body."""
    pad = " " * indent
    lines = []
    for i, it in enumerate(items):
        comma = "," if i < len(items) - 1 else ""
        if isinstance(it, Group):
            lines.append(f"{pad}.{it.name} = {{")
            lines += emit_items(it.items, indent + 4)
            lines.append(f"{pad}}}{comma}")
        else:
            lines.append(f"{pad}.{it.name} = {c_literal(it)}{comma}"
                         f" /* {c_comment(it.comment)} */")
    return lines


def c_sources(name: str, toml_rel: str, overrides: list[str], cfg: dict,
              items: list, crc: int) -> tuple[str, str]:
    """Text of <name>_params.c and <name>_params.h (byte-for-byte reproducible)."""
    head = [
        "/**",
        f" * @file {name}_params.{{EXT}}",
        f" * @brief qfoc parameter table of \"{c_comment(cfg['motor']['name'])}\".",
        " *",
        f" * Generated by {TOOL_PATH} from {toml_rel}; do not edit: change the motor",
        " * file and run the tool again.  Layout, scalings and CRC: include/qfoc/params.h.",
    ]
    if overrides:
        head.append(" * Overrides: " + c_comment(" ".join(sorted(overrides))) + ".")
    head.append(" */")
    guard = f"QFOC_PARAMS_{name.upper()}_H"
    h = [ln.replace("{EXT}", "h") for ln in head] + [
        f"#ifndef {guard}", f"#define {guard}", "", "#include \"qfoc/params.h\"", "",
        f"/** Parameter table of {c_comment(cfg['motor']['name'])} (CRC 0x{crc:08X}). */",
        f"extern const qfoc_param_table_t qfoc_params_{name};", "", f"#endif /* {guard} */", ""]
    c = [ln.replace("{EXT}", "c") for ln in head] + [
        "#include \"qfoc/params.h\"", f"#include \"{name}_params.h\"", "",
        f"const qfoc_param_table_t qfoc_params_{name} = {{"]
    body = items + [crc_field(crc)]
    c += emit_items(body, 4)
    c += ["};", ""]
    return "\n".join(c), "\n".join(h)


# --------------------------------------------------------------------------------------
# Loop analysis (chapter 4)
# --------------------------------------------------------------------------------------

def pmul(*polys) -> np.ndarray:
    """Product of polynomials (highest power first)."""
    out = np.array([1.0])
    for p in polys:
        out = np.polymul(out, np.asarray(p, dtype=float))
    return out


def zoh(num, den, t_s: float) -> tuple[np.ndarray, np.ndarray]:
    """Zero-order-hold discretisation of num/den at T_s."""
    from scipy.signal import cont2discrete
    nd, dd, _ = cont2discrete((num, den), t_s, method="zoh")
    nd = np.trim_zeros(np.atleast_1d(np.squeeze(nd)), "f")
    return (nd if nd.size else np.array([0.0])), np.asarray(dd, dtype=float)


@dataclass
class LoopModel:
    """A feedback loop: forward path F = fn/fd, feedback path H = hn/hd; dt None = continuous."""
    fn: np.ndarray
    fd: np.ndarray
    hn: np.ndarray
    hd: np.ndarray
    dt: float | None

    def open_loop(self) -> tuple[np.ndarray, np.ndarray]:
        """L = F H."""
        return pmul(self.fn, self.hn), pmul(self.fd, self.hd)

    def closed_loop(self) -> tuple[np.ndarray, np.ndarray]:
        """T = F / (1 + F H)."""
        num = pmul(self.fn, self.hd)
        den = np.polyadd(pmul(self.fd, self.hd), pmul(self.fn, self.hn))
        return num, den

    def freq(self, num, den, w: np.ndarray) -> np.ndarray:
        """Frequency response at w (rad/s)."""
        x = np.exp(1j * w * self.dt) if self.dt else 1j * w
        return np.polyval(num, x) / np.polyval(den, x)

    def stable(self) -> bool:
        """Closed-loop poles in the left half plane / inside the unit circle."""
        poles = np.roots(self.closed_loop()[1])
        if self.dt:
            return bool(np.all(np.abs(poles) < 1.0))
        return bool(np.all(poles.real < 0.0))


@dataclass
class LoopResult:
    """Margins and bandwidth of one model."""
    pm_deg: float
    gm_db: float
    w_c: float
    bw_hz: float
    stable: bool
    overshoot_pct: float
    w: np.ndarray
    l_resp: np.ndarray
    t: np.ndarray
    y: np.ndarray


def analyse(model: LoopModel, w_top: float) -> LoopResult:
    """Phase margin, gain margin, crossover, -3 dB bandwidth and step response of a loop."""
    from scipy import signal
    w_hi = (math.pi / model.dt) if model.dt else w_top
    w = np.logspace(-2, math.log10(w_hi), 20000)
    if model.dt:
        w[-1] = math.pi / model.dt          # the Nyquist point itself (phase crossovers there)
    ln, ld = model.open_loop()
    lr = model.freq(ln, ld, w)
    mag = np.abs(lr)
    ph = np.degrees(np.unwrap(np.angle(lr)))
    if ph[0] > 0:
        ph -= 360.0
    pm, wc = math.inf, math.nan
    idx = np.nonzero((mag[:-1] >= 1.0) & (mag[1:] < 1.0))[0]
    for i in idx:
        f = (math.log(mag[i])) / (math.log(mag[i]) - math.log(mag[i + 1]))
        phc = ph[i] + f * (ph[i + 1] - ph[i])
        wci = w[i] * (w[i + 1] / w[i]) ** f
        pmi = (phc + 180.0 + 180.0) % 360.0 - 180.0
        if pmi < pm:
            pm, wc = pmi, wci
    gm = math.inf
    for k in range(-3, 1):
        line = -180.0 + 360.0 * k
        idx = np.nonzero((ph[:-1] > line) & (ph[1:] <= line + 1e-6))[0]
        for i in idx:
            if not (mag[i] > 0.0 and mag[i + 1] > 0.0):
                continue                    # |L| = 0 there: no gain-margin limit
            f = min(1.0, (ph[i] - line) / (ph[i] - ph[i + 1]))
            mg = math.exp(math.log(mag[i]) + f * (math.log(mag[i + 1]) - math.log(mag[i])))
            gm = min(gm, -20.0 * math.log10(mg))
    cn, cd = model.closed_loop()
    tr = np.abs(model.freq(cn, cd, w))
    dc_num = abs(np.polyval(cn, 1.0 if model.dt else 0.0))
    dc_den = abs(np.polyval(cd, 1.0 if model.dt else 0.0))
    # a closed loop with a pole at DC (dc_den = 0) has no finite DC gain: no -3 dB point
    below = np.nonzero(tr < dc_num / dc_den / math.sqrt(2.0))[0] if dc_den > 0 \
        else np.array([], dtype=int)
    bw = w[below[0]] / (2.0 * math.pi) if below.size else math.inf
    stable = model.stable()
    t_end = min(20.0 / max(wc if math.isfinite(wc) else 1.0, 1e-3), 2.0)
    if model.dt:
        n = int(min(max(t_end / model.dt, 50), 40000))
        t, yy = signal.dstep(signal.dlti(cn, cd, dt=model.dt), n=n)
        y = np.squeeze(yy[0])
    else:
        t = np.linspace(0.0, t_end, 2000)
        t, y = signal.step(signal.lti(cn, cd), T=t)
    final = y[-1] if abs(y[-1]) > 1e-12 else 1.0
    overshoot = max(0.0, (float(np.max(y)) - final) / final * 100.0) if stable else math.inf
    return LoopResult(pm, gm, wc, bw, stable, overshoot, w, lr, np.asarray(t), np.asarray(y))


def build_loops(cfg: dict, ds: Design) -> dict[str, tuple[LoopModel, LoopModel]]:
    """(continuous, discrete) models of the current loops, speed loop, FW loop and PLL.

    Continuous: the models of specs/equations.md section 7 with the quantised gains (delays lumped in
    1 / (T_sigma s + 1), 1 / (T_ssigma s + 1)).  Discrete at T_s: PI as implemented by
    qfoc_pi_step (u = kp e + I, I(k) = I(k-1) + ki T e(k): kp + kiT z / (z - 1)), one
    sample of computation delay z^-1, zero-order hold of the plant.
    """
    m, b, g, ph = cfg["motor"], ds.b, ds.gains, ds.phys
    t = b.t_s
    one = np.array([1.0])
    delay = (one, np.array([1.0, 0.0]))
    loops: dict = {}

    def pi_z(kp: float, kit: float) -> tuple[np.ndarray, np.ndarray]:
        return np.array([kp + kit, -kp]), np.array([1.0, -1.0])

    current_cl = {}
    for axis, l_h in (("d", m["ld_h"]), ("q", m["lq_h"])):
        k_cp = g[f"pi_i{axis}.kp"].quantised * b.v_base / b.i_base
        k_cit = g[f"pi_i{axis}.ki"].quantised * b.v_base / b.i_base
        k_ci = k_cit / t
        tf = cfg["design"]["t_filter_current_s"]
        cont = LoopModel(pmul([k_cp, k_ci]), pmul([1.0, 0.0], [ds.t_sigma, 1.0], [l_h, m["rs_ohm"]]),
                         one, one, None)
        pn, pd = zoh([1.0], [l_h, m["rs_ohm"]], t)
        cn, cd = pi_z(k_cp, k_cit)
        hn, hd = (zoh([1.0], [tf, 1.0], t) if tf > 0 else (one, one))
        disc = LoopModel(pmul(cn, delay[0], pn), pmul(cd, delay[1], pd), hn, hd, t)
        loops[f"current {axis}"] = (cont, disc)
        current_cl[axis] = disc.closed_loop()

    # Speed loop: i_q reference -> (current loop) -> K_t -> b / (s + a) -> w_m.
    kp_s = g["pi_speed.kp"].quantised * b.i_base / b.w_base * m["pole_pairs"]
    kit_s = g["pi_speed.ki"].quantised * b.i_base / b.w_base * m["pole_pairs"]
    t_sam = cfg["design"]["speed_t_sam_s"]
    ki_s = kit_s / t_sam
    cont = LoopModel(pmul([kp_s, ki_s], [ds.k_t * ph["b"]]),
                     pmul([1.0, 0.0], [ds.t_ssigma, 1.0], [1.0, ph["a"]]), one, one, None)
    # Discrete at the speed loop's own sample time T_sam (the 1 ms tick): zero-order hold
    # of the closed current loop and the mechanics, one T_sam of computation delay, the PI
    # as qfoc_pi_step at T_sam, and the speed low-pass (which runs at the PWM rate)
    # as its continuous equivalent 1 / (T_f s + 1), held at T_sam.
    if abs(t_sam - t) <= 1e-12:
        pn, pd = zoh([ds.k_t * ph["b"]], pmul([2.0 * ds.t_sigma, 1.0], [1.0, ph["a"]]), t)
        alpha = g["pll.speed_alpha"].quantised
        hn, hd = np.array([alpha, 0.0]), np.array([1.0, alpha - 1.0])
    else:
        pn, pd = zoh([ds.k_t * ph["b"]], pmul([2.0 * ds.t_sigma, 1.0], [1.0, ph["a"]]), t_sam)
        hn, hd = zoh([1.0], [ph["T_filter_speed"], 1.0], t_sam)
    cn, cd = pi_z(kp_s, kit_s)
    disc = LoopModel(pmul(cn, delay[0], pn), pmul(cd, delay[1], pd), hn, hd, t_sam)
    loops["speed"] = (cont, disc)

    # Field weakening: e = v_max - utilisation -> i_d reference -> d current loop -> G_fw.
    kp_f = g["pi_fw.kp"].quantised
    kit_f = g["pi_fw.ki"].quantised
    gfw = ph["G_fw"]
    # Discrete at the tick (T_tick): the PI as qfoc_pi_step at T_tick, one tick of delay (the
    # utilisation of the last command, computed at the end of the tick before), the closed d
    # current loop as its continuous equivalent 1 / (2 T_sigma s + 1) held at T_tick.
    cont = LoopModel(pmul([kp_f, kit_f / T_TICK_S], [gfw]),
                     pmul([1.0, 0.0], [2.0 * ds.t_sigma, 1.0]), one, one, None)
    cn, cd = pi_z(kp_f, kit_f)
    fn, fd = zoh([gfw], [2.0 * ds.t_sigma, 1.0], T_TICK_S)
    disc = LoopModel(pmul(cn, [1.0], fn), pmul(cd, [1.0, 0.0], fd), one, one, T_TICK_S)
    loops["field weakening"] = (cont, disc)

    # PLL (2-27, 2-28): error ~ theta_r - theta (rad), speed (pu) -> theta += speed w_base T.
    kp_p, kit_p = g["pll.kp"].quantised, g["pll.ki"].quantised
    cont = LoopModel(pmul([kp_p, kit_p / t], [b.w_base]), np.array([1.0, 0.0, 0.0]), one, one,
                     None)
    cn, cd = pi_z(kp_p, kit_p)
    disc = LoopModel(pmul(cn, [b.w_base * t]), pmul(cd, [1.0, -1.0]), one, one, t)
    loops["PLL"] = (cont, disc)
    return loops


# The motor-file keys the loop models are made from (the [design] keys as well).
LOOP_KEYS = ("motor.rs_ohm", "motor.ld_h", "motor.lq_h", "motor.psi_f_wb", "motor.j_kgm2",
             "motor.b_nms", "motor.pole_pairs", "inverter.f_pwm_hz", "scaling.f_base_hz")


def run_analysis(cfg: dict, ds: Design) -> dict[str, tuple[LoopResult, LoopResult]]:
    """Analyse every loop, continuous and discrete."""
    w_top = 10.0 * math.pi / ds.b.t_s
    return {name: (analyse(c, w_top), analyse(dm, w_top))
            for name, (c, dm) in build_loops(cfg, ds).items()}


@dataclass
class SpeedCheck:
    """The speed-loop check: the ramp response simulated with the stored speed PI."""
    start_rpm: float
    target_rpm: float
    load_nm: float
    ramp_rpm_s: float
    t_ramp_end: float
    err_end_pct: float          # speed error at the ramp's end, % of the target
    overshoot_pct: float        # largest speed above the target after the ramp's end
    err_pct: float              # largest |error| over the check window
    iq_load_a: float            # i_q that holds the load at the target
    i_max_a: float
    t: np.ndarray
    rpm: np.ndarray
    failure: str | None


def speed_check(cfg: dict, ds: Design) -> SpeedCheck:
    """Simulate, in double precision, the speed loop's response to the drive's speed ramp.

    From steady state at drive.of_speed_rpm (the hand-over: the loop carries the load) the
    reference ramps at the stored drive.speed_ramp to design.speed_check_rpm against the
    constant load design.speed_check_load_nm.  The speed PI is qfoc_pi_step with the stored
    gains and limits (+-i_max, clamping anti-windup) at T_sam, its output applied one T_sam
    later; the closed current loop is the lag 1 / (2 T_sigma s + 1); the mechanics
    J dw/dt = K_t i_q - B w - T_load; the fed-back speed passes the speed low-pass
    1 / (T_filter s + 1).  The continuous part is integrated exactly over each T_sam (matrix
    exponential).  The check fails when the speed error exceeds SPEED_CHECK_ERR_PCT % of the
    target anywhere from SPEED_CHECK_AFTER_S after the ramp's end over SPEED_CHECK_SPAN_S.
    """
    from scipy.linalg import expm
    m, d, dr = cfg["motor"], cfg["design"], cfg["drive"]
    b, g, ph = ds.b, ds.gains, ds.phys
    n_p = m["pole_pairs"]
    rpm = 2.0 * math.pi / 60.0                          # rad/s (mechanical) per rpm
    pu = b.i_base / b.w_base * n_p                     # A per rad/s mech of a speed-PI gain
    kp, kit = g["pi_speed.kp"].quantised * pu, g["pi_speed.ki"].quantised * pu
    i_lim = g["i_max"].quantised * b.i_base
    t_sam = d["speed_t_sam_s"]
    # the drive's ramp: drive.speed_ramp Q15 of w_base (electrical) per 1 ms tick
    ramp_raw = max(1, q15(dr["accel_rpm_s"] * 1e-3 * n_p / 60.0 / b.f_base))
    ramp = ramp_raw / 32768.0 * b.w_base / n_p / 1e-3    # rad/s^2 (mechanical)
    w0, w1 = dr["of_speed_rpm"] * rpm, d["speed_check_rpm"] * rpm
    load, j, bb, kt = d["speed_check_load_nm"], m["j_kgm2"], m["b_nms"], ds.k_t
    t_i, t_f = 2.0 * ds.t_sigma, ph["T_filter_speed"]
    a = np.array([[-1.0 / t_i, 0.0, 0.0], [kt / j, -bb / j, 0.0], [0.0, 1.0 / t_f, -1.0 / t_f]])
    bm = np.array([[1.0 / t_i, 0.0], [0.0, -1.0 / j], [0.0, 0.0]])
    big = np.zeros((5, 5))
    big[:3, :3], big[:3, 3:] = a, bm
    e = expm(big * t_sam)
    ad, bd = e[:3, :3], e[:3, 3:]
    iq0 = bb * w0 / kt                                  # unloaded until the ramp starts
    x = np.array([iq0, w0, w0])
    integ = min(max(iq0, -i_lim), i_lim)
    u_prev = integ
    t_ramp = abs(w1 - w0) / ramp
    n = int(math.ceil((t_ramp + SPEED_CHECK_AFTER_S + SPEED_CHECK_SPAN_S) / t_sam)) + 2
    ref = w0
    ws = np.empty(n + 1)
    ws[0] = w0
    k_end = 0 if w1 == w0 else None
    for k in range(n):
        step = ramp * t_sam
        ref = min(ref + step, w1) if w1 >= ref else max(ref - step, w1)
        if k_end is None and ref == w1:
            k_end = k + 1
        err = ref - x[2]
        integ = min(max(integ + kit * err, -i_lim), i_lim)
        u = min(max(kp * err + integ, -i_lim), i_lim)
        x = ad @ x + bd @ np.array([u_prev, load])
        u_prev = u
        ws[k + 1] = x[1]
    t = np.arange(n + 1) * t_sam
    t_end = (k_end if k_end is not None else n) * t_sam
    e_pct = (ws - w1) / w1 * 100.0
    after = t >= t_end - 1e-12
    win = (t >= t_end + SPEED_CHECK_AFTER_S - 1e-12) &         (t <= t_end + SPEED_CHECK_AFTER_S + SPEED_CHECK_SPAN_S + 1e-12)
    err_pct = float(np.max(np.abs(e_pct[win])))
    k0 = int(round(t_end / t_sam))
    iq_load = (load + bb * w1) / kt
    res = SpeedCheck(dr["of_speed_rpm"], d["speed_check_rpm"], load, ramp * 60.0 / (2 * math.pi),
                     t_end, float(e_pct[k0]), max(0.0, float(np.max(e_pct[after]))), err_pct,
                     iq_load, i_lim, t, ws / rpm, None)
    if iq_load > i_lim or iq0 > i_lim:
        res.failure = (f"speed-loop check failed: the load {typed(cfg, 'design.speed_check_load_nm')} "
                       f"needs i_q = {fmt(max(iq_load, iq0), 4)} A, above i_max = "
                       f"{fmt(i_lim, 4)} A")
    elif not err_pct <= SPEED_CHECK_ERR_PCT:
        res.failure = (
            f"speed-loop check failed: the speed error {fmt(err_pct, 3)} % of the target is above "
            f"{fmt(SPEED_CHECK_ERR_PCT)} % {fmt(SPEED_CHECK_AFTER_S)} s after the ramp's end "
            f"(ramp {fmt(res.start_rpm)} -> {fmt(res.target_rpm)} rpm at "
            f"{fmt(res.ramp_rpm_s, 4)} rpm/s, ends at {fmt(t_end, 3)} s; load "
            f"{fmt(load)} N m; error at the ramp's end {fmt(res.err_end_pct, 3)} %, overshoot "
            f"{fmt(res.overshoot_pct, 3)} %): the speed PI's integral time "
            f"{typed(cfg, 'design.speed_tau_s')} is too long for its crossover "
            f"design.speed_crossover_hz = {fmt(d['speed_crossover_hz'])} Hz (tau_s w_sc = "
            f"{fmt(d['speed_tau_s'] * ph['w_sc'], 3)}; design.speed_zero_ratio, default "
            f"{fmt(SPEED_ZERO_RATIO)}); the integral action needs seconds to remove the error")
    return res


def plot_loops(results: dict, out_dir: Path) -> list[str]:
    """One PNG per loop: open-loop Bode (continuous and discrete) and closed-loop step."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    names = []
    for name, (rc, rd) in results.items():
        fig, axes = plt.subplots(3, 1, figsize=(7.5, 9.0))
        for r, label, style in ((rc, "continuous", "-"), (rd, "discrete", "--")):
            axes[0].semilogx(r.w / (2 * math.pi), 20 * np.log10(np.abs(r.l_resp)), style, label=label)
            ph = np.degrees(np.unwrap(np.angle(r.l_resp)))
            if ph[0] > 0:
                ph = ph - 360.0
            axes[1].semilogx(r.w / (2 * math.pi), ph, style, label=label)
            axes[2].plot(r.t * 1e3, r.y, style, label=label)
        axes[0].axhline(0.0, color="grey", lw=0.5)
        axes[1].axhline(-180.0, color="grey", lw=0.5)
        axes[0].set_ylabel("|L| (dB)")
        axes[1].set_ylabel("arg L (deg)")
        axes[1].set_xlabel("frequency (Hz)")
        axes[2].set_xlabel("time (ms)")
        axes[2].set_ylabel("closed-loop step")
        axes[0].set_title(f"{name} loop: PM {rc.pm_deg:.1f} / {rd.pm_deg:.1f} deg "
                          "(continuous / discrete)")
        for ax in axes:
            ax.grid(True, which="both", lw=0.3)
            ax.legend(loc="best", fontsize=8)
        fig.tight_layout()
        fname = "loop_" + name.replace(" ", "_") + ".png"
        fig.savefig(out_dir / fname, dpi=90, metadata={"Software": None})
        plt.close(fig)
        names.append(fname)
    return names


# --------------------------------------------------------------------------------------
# Report
# --------------------------------------------------------------------------------------

def md_table(header: list[str], rows: list[list[str]]) -> list[str]:
    """A Markdown table."""
    out = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    out += ["| " + " | ".join(str(c).replace("|", "\\|") for c in r) + " |" for r in rows]
    return out


def gain_rows(ds: Design) -> list[list[str]]:
    """Rows of the gains table."""
    keys = ["pi_id.kp", "pi_id.ki", "pi_iq.kp", "pi_iq.ki", "pi_id.out", "pi_speed.kp",
            "pi_speed.ki", "pi_fw.kp", "pi_fw.ki", "v_max", "pll.kp", "pll.ki", "pll.err_clamp",
            "pll.mag_min", "pll.k_theta", "pll.speed_alpha", "alpha_vdc", "flux.gain", "flux.r",
            "flux.l", "flux.kg", "ld", "lq", "psi_f", "i_max", "i_trip", "speed_max", "vdc_uv",
            "vdc_ov", "svpwm.vdc_min", "svpwm.i_deadband", "svpwm.dt_comp"]
    rows = []
    for k in keys:
        gn = ds.gains[k]
        rows.append([gn.name, fmt(gn.real), str(gn.raw), "" if gn.shift is None else
                     f"{gn.shift} ({gn.kind})", fmt(gn.quantised), f"{gn.rel_err * 100:+.4f} %",
                     gn.derivation])
    return rows


def drive_rows(cfg: dict, ds: Design) -> list[list[str]]:
    """Rows of the drive-configuration table: field, value, derivation, range."""
    flat = {"i_max": ds.gains["i_max"].raw, "speed_max": ds.gains["speed_max"].raw}
    return [[f"drive.{f.name}", c_literal(f), f.comment, drive_range_text(f.name, flat)]
            for f in drive_fields(cfg, ds)[0]]


def write_report(path: Path, cfg: dict, toml_rel: str, overrides: list[str], ds: Design,
                 bounds: list[Bound], results: dict | None, pngs: list[str],
                 failures: list[str], crc: int | None, sc: SpeedCheck | None = None) -> None:
    """Write report.md."""
    b, ph = ds.b, ds.phys
    status = "FAILED" if failures else "PASSED"
    lines = [f"# qfoc tuning report: {cfg['motor']['name']}", "",
             f"Status: **{status}**", "",
             f"Motor file: `{toml_rel}`" + (f", overrides: `{' '.join(overrides)}`"
                                            if overrides else ""),
             f"Generated by `{TOOL_PATH}`." + (f" Table CRC-32: `0x{crc:08X}`." if crc is not None
                                              else " No table written."), ""]
    if failures:
        lines += ["## Failures", ""] + [f"- {f}" for f in failures] + [""]
    coarse = [gn for gn in ds.gains.values() if abs(gn.rel_err) > COARSE_GAIN_PCT / 100.0]
    if coarse or cfg.get("warnings"):
        lines += ["## Warnings", ""]
        lines += [f"- {w}" for w in cfg.get("warnings", [])]
        lines += [f"- {gn.name}: rounding error {gn.rel_err * 100:+.2f} % (raw {gn.raw}): the "
                  "value is close to the resolution of its representation" for gn in coarse]
        lines.append("")
    notes = drive_fields(cfg, ds)[1]
    if notes:
        lines += ["## Notes", ""] + [f"- {n}" for n in notes] + [""]
    lines += ["## 1. Design choices ([design], [limits], [drive])", ""]
    rows = []
    for sec, keys in OPTIONAL_SECTIONS.items():
        for k, (_d, _c, desc) in keys.items():
            src = "default" if f"{sec}.{k}" in cfg["defaulted"] else "motor file / --set"
            val = cfg[sec][k] if cfg[sec][k] is not None else ds.phys[f"{sec}.{k}"]
            rows.append([f"{sec}.{k}", fmt(val), src, desc])
    lines += md_table(["key", "value", "source", "meaning"], rows) + [""]
    lines += ["## 2. Bases (specs/scaling.md section 2)", ""]
    lines += md_table(["symbol", "derivation", "value"], [list(r) for r in base_rows(cfg, b)])
    lines += ["", "## 3. Scale factors (specs/scaling.md section 3)", ""]
    lines += md_table(["factor", "derivation", "value"],
                      [list(r) for r in scale_factor_rows(cfg, ds)])
    lines += ["", "## 4. Loop design and gains", "",
              f"- Current loops (chapter 2, \"Current Loop\"): T_sigma = T_pwm + T_sam + T_filter "
              f"= T_s/2 + T_s + {fmt(cfg['design']['t_filter_current_s'])} = "
              f"{fmt(ph['T_sigma'] * 1e6)} us; tau_c = L/R; K T = 0.5: k_cp = L / (2 T_sigma) = "
              f"{fmt(ph['k_cp_d'])} / {fmt(ph['k_cp_q'])} ohm (d / q), k_ci = R / (2 T_sigma) = "
              f"{fmt(ph['k_ci_d'])} ohm/s; per unit kp = k_cp I_base / V_base, "
              f"ki T = k_ci T_s I_base / V_base; limits +-V_dc,max / sqrt 3 = {fmt(ph['v_lim'])} V.",
              f"- Speed loop (\"Speed Loop\"): T_ssigma = 2 T_sigma + T_filter + T_sam = "
              f"{fmt(ph['T_ssigma'] * 1e3)} ms (T_filter = 1 / (2 pi f_c) of the PLL speed filter = "
              f"{fmt(ph['T_filter_speed'] * 1e3)} ms); K_t = 3/2 n_p psi_f = {fmt(ph['K_t'])} N m/A; "
              f"b = 1/J = {fmt(ph['b'])}, a = B/J = {fmt(ph['a'])}; tau_s = {fmt(ph['tau_s'])} s; "
              f"ksp = K / (2 K_t b), K = 1 / T_ssigma: {fmt(ph['ksp'])} A s/rad (mechanical); "
              f"input speed error in Q15 of w_base (electrical), output i_q in Q15 of I_base.",
              f"- Field weakening: error v_max - utilisation -> i_d reference in [-i_max, 0]; plant "
              f"gain G_fw = w_max L_d I_base / (V_dc,min / sqrt 3) = {fmt(ph['G_fw'])} pu/pu "
              f"(largest: top speed, lowest bus); crossover w_fw = "
              f"{fmt(cfg['design']['fw_crossover_ratio'])} x 1/(2 T_sigma) = {fmt(ph['w_fw'])} rad/s "
              f"(a decade below the current loop); integral-dominant: ki = w_fw / G_fw = "
              f"{fmt(ph['ki_fw'])} 1/s, kp = ki / ({fmt(cfg['design']['fw_zero_ratio'])} w_fw) = "
              f"{fmt(ph['kp_fw'])}.",
              "- PLL (2-27, 2-28) and flux observer (2-19 .. 2-24): as sim/estim.c est_tune() "
              f"in the flux base psi_base = 2^s V_base / w_base, s = {b.psi_shift} "
              "(g = T w_base / 2^s, kg = K_gain 2^s / w_base, l = L_q / L_base; with s = 0 "
              "exactly est_tune()'s).", "",
              "Gains: `left` = pi.h (real = raw / 32768 x 2^shift, smallest shift), `right` = "
              "flux.h (real = raw / 2^(15 + shift), largest shift).", ""]
    lines += md_table(["quantity", "real value", "raw", "shift", "stored value", "rounding error",
                       "derivation"], gain_rows(ds))
    lines += ["", "## 5. Drive configuration (include/qfoc/drive_cfg.h, table field drive)", "",
              "Defaults and overrides: section 1, keys drive.*.  Speeds are electrical Q15 of "
              "w_base converted from mechanical rpm with n_p / 60 / f_base; currents Q15 of "
              "I_base; times in ms of the 1 ms tick.  The range column is what "
              "qfoc_drive_cfg_is_valid() and qfoc_params_is_valid() accept.", ""]
    lines += md_table(["field", "value", "derivation", "range"], drive_rows(cfg, ds))
    lines += ["", "## 6. Fixed-point bounds (chapter 2)", "",
              "Margin = (limit - value) / limit.  Assumptions: Clarke and Park at the trip current "
              "with the phase of i_v within 120 deg +- design.clarke_phase_dev_deg; Park angle "
              "error up to design.park_angle_err_deg; flux at the lowest observer speed and the "
              "highest speed with |psi_a| = psi_f + |L_d - L_q| i_max and a DC current offset "
              "design.i_offset_a, in the flux base (the rows 'flux base: ...' hold the table's "
              "fluxes below 1 pu, its inductances below 8 pu and kg below 1 pu); inverse transforms at V_dc,max / sqrt 3 with harmonics "
              "A_d = A_q = design.v_harmonic_fraction x |v|.", ""]
    lines += md_table(["bound", "equation", "value", "limit", "margin", "worst input"],
                      [[bd.name, bd.equation, fmt(bd.value), fmt(bd.limit),
                        f"{bd.margin_pct:.1f} %" + ("" if bd.ok else " VIOLATED"), bd.worst_input]
                       for bd in bounds])
    if results:
        lines += ["", "## 7. Loop analysis (chapter 4)", "",
                  "Continuous: the models of specs/equations.md section 7 with the stored gains.  Discrete: T_s = "
                  f"{fmt(b.t_s * 1e6)} us, zero-order hold of the plant, z^-1 computation delay, "
                  "PI as qfoc_pi_step (kp + kiT z/(z-1)); speed loop with the speed low-pass "
                  "alpha z/(z-1+alpha) in the feedback; FW loop through the discrete closed d "
                  "current loop; PLL linearised (error = angle error in rad).  Required: discrete "
                  f"loop stable with PM >= {fmt(PM_MIN_DEG)} deg.  The discrete current loops "
                  "show a wider bandwidth than the continuous ones: the continuous model lumps the "
                  "1.5 T_s delay into 1 / (T_sigma s + 1), which has the delay's phase but not its "
                  "unit magnitude, so its closed loop rolls off earlier; a continuous model with the "
                  "exact delay exp(-1.5 T_s s) agrees with the discrete one (on the reference motor "
                  "955 Hz against 1001 Hz), and the phase margins of both models agree.", ""]
        rows = []
        for name, (rc, rd) in results.items():
            rows.append([name,
                         f"{rc.pm_deg:.1f} / {rd.pm_deg:.1f}",
                         f"{fmt(rc.gm_db, 4)} / {fmt(rd.gm_db, 4)}",
                         f"{fmt(rc.w_c / (2 * math.pi), 4)} / {fmt(rd.w_c / (2 * math.pi), 4)}",
                         f"{fmt(rc.bw_hz, 4)} / {fmt(rd.bw_hz, 4)}",
                         f"{rc.overshoot_pct:.1f} / {rd.overshoot_pct:.1f}",
                         "yes" if rd.stable else "NO"])
        lines += md_table(["loop", "PM deg (cont / disc)", "GM dB (cont / disc)",
                           "crossover Hz (cont / disc)", "bandwidth -3 dB Hz (cont / disc)",
                           "step overshoot % (cont / disc)", "discrete stable"], rows)
    if sc is not None:
        lines += ["", "Speed-loop check (double precision: the stored speed PI at T_sam with its "
                  "limits, one T_sam of delay, the current loop as 1 / (2 T_sigma s + 1), the "
                  "mechanics J, B, the speed low-pass in the feedback): from steady state at "
                  f"drive.of_speed_rpm = {fmt(sc.start_rpm)} rpm the drive's ramp "
                  f"({fmt(sc.ramp_rpm_s, 4)} rpm/s as stored) to design.speed_check_rpm = "
                  f"{fmt(sc.target_rpm)} rpm against design.speed_check_load_nm = "
                  f"{fmt(sc.load_nm)} N m; the ramp ends at {fmt(sc.t_ramp_end, 4)} s.  Error at "
                  f"the ramp's end {sc.err_end_pct:+.3f} % of the target, overshoot "
                  f"{sc.overshoot_pct:.3f} %, largest |error| from {fmt(SPEED_CHECK_AFTER_S)} s to "
                  f"{fmt(SPEED_CHECK_AFTER_S + SPEED_CHECK_SPAN_S)} s after the ramp's end "
                  f"{sc.err_pct:.3f} % (required <= {fmt(SPEED_CHECK_ERR_PCT)} %): "
                  + ("FAILED." if sc.failure else "met.")]
    if pngs:
        lines += ["", "## 8. Figures", ""]
        lines += [f"![{p}]({p})" for p in pngs]
    lines.append("")
    path.write_text("\n".join(lines), encoding="utf-8")


# --------------------------------------------------------------------------------------
# Main
# --------------------------------------------------------------------------------------

def rel_to_repo(path: Path) -> str:
    """The path relative to the repository root when inside it, else as given."""
    try:
        return Path(os.path.relpath(path.resolve(), REPO_ROOT)).as_posix() \
            if path.resolve().is_relative_to(REPO_ROOT) else path.as_posix()
    except ValueError:
        return path.as_posix()


def c_name(stem: str) -> str:
    """A C identifier from the TOML file stem."""
    name = "".join(ch if ch.isalnum() else "_" for ch in stem.lower())
    return name if name and not name[0].isdigit() else "m_" + name


NOTHING_WRITTEN = "no table written (docs/motor-file.md)"


def exit_on(exc: InputError, tool: str, nothing: str) -> int:
    """Report a refusal (a line 'refused: ...' per reason, then what was not written; exit code
    1) or malformed input (a line 'error: ...'; exit code 2) on stderr; return the code."""
    if isinstance(exc, Refusal):
        for line in str(exc).split("\n"):
            print(f"refused: {line}", file=sys.stderr)
        print(f"{tool}: refused, {nothing}", file=sys.stderr)
        return 1
    print(f"error: {exc}", file=sys.stderr)
    return 2


def main(argv: list[str] | None = None) -> int:
    """Command-line entry point; returns the exit code."""
    ap = argparse.ArgumentParser(
        prog="qfoc_tune.py",
        description="qfoc tuning and scaling tool: reads a motor TOML, derives bases and Q15 "
                    "scale factors, designs the current, speed, field-weakening and PLL loops "
                    "(document chapter 2), checks the fixed-point bounds (2-5 .. 2-12, 2-25, "
                    "2-26, inverse transforms), analyses the loops (chapter 4) and writes the "
                    "parameter table (include/qfoc/params.h) and a report.",
        epilog="The motor file's sections and keys, with units, ranges, defaults and the rules "
               "the tool checks: docs/motor-file.md (--motor-file-doc prints it).  Exit codes: "
               "0 ok; 1 refused (a key the tool does not know, a value outside its range or a "
               "broken rule: no file written; or a bound or loop check failed: report marked "
               "FAILED, no table written); 2 malformed input (syntax, missing key, type, sign).")
    ap.add_argument("motor", type=Path, nargs="?",
                    help="motor and inverter file, e.g. specs/motors/reference.toml "
                         "(format: docs/motor-file.md)")
    ap.add_argument("--motor-file-doc", action="store_true",
                    help="print docs/motor-file.md (the motor-file format, from the tool's "
                         "schema) and exit")
    ap.add_argument("--out-dir", type=Path, help="report directory (default build/tune/<name>/)")
    ap.add_argument("--table-dir", type=Path, default=Path("tables"),
                    help="directory of <name>_params.c/.h (default tables/)")
    ap.add_argument("--set", dest="overrides", action="append", default=[],
                    metavar="SECTION.KEY=VALUE", help="override a motor-file value (repeatable)")
    ap.add_argument("--no-plots", action="store_true", help="skip the PNG figures")
    ap.add_argument("--name", help="table name: tables/<name>_params.c, symbol qfoc_params_<name> "
                                   "(default: from the motor file's name)")
    args = ap.parse_args(argv)
    if args.motor_file_doc:
        sys.stdout.write(motor_file_doc())
        return 0
    if args.motor is None:
        ap.error("the motor file is required")

    try:
        cfg = load_config(args.motor, args.overrides)
        # the flux base: scaling.psi_shift, or the smallest shift that holds the machine
        try:
            b = make_bases(cfg)
        except Refusal as exc:
            raise Refusal(f"{args.motor}: {exc}") from exc
    except InputError as exc:
        return exit_on(exc, "qfoc_tune", NOTHING_WRITTEN)
    for w in cfg["warnings"]:
        print(f"warning: {w}", file=sys.stderr)
    name = c_name(args.name if args.name else args.motor.stem)
    toml_rel = rel_to_repo(args.motor)
    out_dir = args.out_dir if args.out_dir else Path("build") / "tune" / name

    ds = design_loops(cfg, b)
    # the torque compensation's window: by default up to the speed where the learning law's
    # phase model holds with margin (tc_speed_limit_rpm); a window with a phase error of 90
    # degrees or more anywhere (the learning would diverge) is refused
    dr = cfg["drive"]
    worst, at_rpm, harm = tc_worst_phase(cfg, ds, dr["tc_speed_min_rpm"], dr["tc_speed_max_rpm"])
    if worst >= 90.0:
        top = tc_speed_limit_rpm(cfg, ds, dr["tc_speed_min_rpm"], dr["tc_speed_max_rpm"])
        return exit_on(Refusal(
            f"{typed(cfg, 'drive.tc_speed_min_rpm')} .. "
            f"{typed(cfg, 'drive.tc_speed_max_rpm')}: the torque compensation's "
            f"{'first' if harm == 1 else 'second'} harmonic at {fmt(at_rpm)} rpm has a phase "
            f"error of {fmt(worst)} deg (90 deg or more: its learning diverges, "
            f"include/qfoc/trqcomp.h); with this lower end the window may reach "
            f"{fmt(top)} rpm"), "qfoc_tune", NOTHING_WRITTEN)
    items = build_table(cfg, ds)
    bounds = check_bounds(cfg, ds) + range_checks(items)
    failures = []
    for bd in bounds:
        src = field_source(cfg, bd.name[len("table field "):]) \
            if bd.name.startswith("table field ") else ""
        if bd.violated:
            failures.append(f"bound violated: {bd.name} ({bd.equation}): {bd.worst_input}{src}")
        elif not bd.ok:
            failures.append(f"bound violated: {bd.name} ({bd.equation}): {fmt(bd.value)} > "
                            f"{fmt(bd.limit)} for {bd.worst_input}{src}")
    # The loop models of extreme (if in-range) values can leave the floating-point range
    # (a plant pole far beyond the sample rate, a gain that rounds to zero): such a design
    # fails the loop check, named with the keys the loops are designed from, instead of a
    # numpy or scipy warning.
    try:
        with np.errstate(divide="raise", over="raise", invalid="raise"), \
                warnings.catch_warnings():
            warnings.simplefilter("error")
            results = run_analysis(cfg, ds)
    except (ArithmeticError, ValueError, Warning, np.linalg.LinAlgError) as exc:
        results = {}
        failures.append("loop check failed: the loop models leave the floating-point range "
                        f"({type(exc).__name__}: {exc}) for " + ", ".join(
                            typed(cfg, k) for k in LOOP_KEYS))
    sc = None
    try:
        with np.errstate(divide="raise", over="raise", invalid="raise"), \
                warnings.catch_warnings():
            warnings.simplefilter("error")
            sc = speed_check(cfg, ds)
    except (ArithmeticError, ValueError, Warning, np.linalg.LinAlgError) as exc:
        failures.append("speed-loop check failed: the simulation leaves the floating-point range "
                        f"({type(exc).__name__}: {exc})")
    if sc is not None and sc.failure:
        failures.append(sc.failure)
    for lname, (_rc, rd) in results.items():
        if not rd.stable:
            failures.append(f"loop check failed: {lname} loop: discrete closed loop unstable")
        elif not rd.pm_deg >= PM_MIN_DEG:
            failures.append(f"loop check failed: {lname} loop: discrete phase margin "
                            f"{rd.pm_deg:.1f} deg < {fmt(PM_MIN_DEG)} deg")

    print(f"qfoc_tune: {cfg['motor']['name']} ({toml_rel})")
    print("bases:")
    for sym, der, val in base_rows(cfg, b):
        print(f"  {sym:9s} = {val:16s} {der}")
    print("scale factors:")
    for sym, der, val in scale_factor_rows(cfg, ds):
        print(f"  {sym:30s} = {val:18s} {der}")
    print("gains (real, raw, shift, rounding error):")
    for row in gain_rows(ds):
        print(f"  {row[0]:18s} {row[1]:>12s} {row[2]:>7s} {row[3]:>10s} {row[5]:>11s}")
    print("drive configuration (drive_cfg.h):")
    for row in drive_rows(cfg, ds):
        print(f"  {row[0]:22s} {row[1]:>8s}  {row[2]}")
    for note in drive_fields(cfg, ds)[1]:
        print(f"note: {note}", file=sys.stderr)
    print("bounds (value, limit, margin):")
    for bd in bounds:
        print(f"  {bd.name:36s} {bd.equation:38s} {fmt(bd.value):>10s} {fmt(bd.limit):>8s} "
              f"{bd.margin_pct:6.1f} %")
    print("loops (PM deg cont/disc, GM dB cont/disc, bandwidth Hz cont/disc):")
    for lname, (rc, rd) in results.items():
        print(f"  {lname:16s} {rc.pm_deg:6.1f} / {rd.pm_deg:6.1f}   {fmt(rc.gm_db, 4):>6s} / "
              f"{fmt(rd.gm_db, 4):>6s}   {fmt(rc.bw_hz, 4):>7s} / {fmt(rd.bw_hz, 4):>7s}")

    if sc is not None:
        print(f"speed-loop check (ramp {fmt(sc.start_rpm)} -> {fmt(sc.target_rpm)} rpm at "
              f"{fmt(sc.ramp_rpm_s, 4)} rpm/s, load {fmt(sc.load_nm)} N m): error at the ramp's "
              f"end {sc.err_end_pct:+.3f} %, overshoot {sc.overshoot_pct:.3f} %, largest |error| "
              f"{fmt(SPEED_CHECK_AFTER_S)} .. {fmt(SPEED_CHECK_AFTER_S + SPEED_CHECK_SPAN_S)} s "
              f"after the ramp {sc.err_pct:.3f} % (limit {fmt(SPEED_CHECK_ERR_PCT)} %)")

    out_dir.mkdir(parents=True, exist_ok=True)
    pngs = [] if args.no_plots else plot_loops(results, out_dir)
    crc = None
    if not failures:
        crc = crc32_iso_hdlc(serialise(items))
        c_text, h_text = c_sources(name, toml_rel, args.overrides, cfg, items, crc)
        args.table_dir.mkdir(parents=True, exist_ok=True)
        # each file appears whole or not at all (written aside, then renamed)
        for ext, text in (("c", c_text), ("h", h_text)):
            tmp = args.table_dir / f".{name}_params.{ext}.tmp"
            tmp.write_text(text, encoding="utf-8")
            os.replace(tmp, args.table_dir / f"{name}_params.{ext}")
    write_report(out_dir / "report.md", cfg, toml_rel, args.overrides, ds, bounds,
                 results, pngs, failures, crc, sc)
    for gn in ds.gains.values():
        if abs(gn.rel_err) > COARSE_GAIN_PCT / 100.0:
            print(f"warning: {gn.name}: rounding error {gn.rel_err * 100:+.2f} % (raw {gn.raw})",
                  file=sys.stderr)
    for f in failures:
        print(f, file=sys.stderr)
    if failures:
        print(f"FAILED: report {out_dir / 'report.md'}, no table written", file=sys.stderr)
        return 1
    print(f"wrote {args.table_dir / (name + '_params.c')}, {args.table_dir / (name + '_params.h')}, "
          f"{out_dir / 'report.md'} (CRC 0x{crc:08X})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
