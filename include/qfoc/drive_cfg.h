/**
 * @file drive_cfg.h
 * @brief Drive configuration: the start-up sequence, protection, command-link and
 *        feature settings of the drive layer, stored in the parameter table (params.h,
 *        field `drive`, layout version 4: version 2, the seven fields from mtpa_speed
 *        on (version 3) and the flux base psi_shift (version 4)).
 *
 * Every number is an integer the tuning tool (tools/tune/qfoc_tune.py) derives from the
 * motor file (section [drive] overrides the documented defaults).  Unless a field says
 * otherwise the scalings are those of specs/scaling.md: currents Q15 of I_base, speeds
 * Q15 of the electrical base speed w_base = 2 pi f_base, fluxes Q15 of
 * psi_base = 2^psi_shift V_base / w_base, inductances Q12 of L_base = psi_base / I_base,
 * angles 65536 counts per electrical turn, times in milliseconds of the 1 ms tick, temperatures in 0.1 degC.
 *
 * qfoc_drive_cfg_is_valid() checks every field against the range its comment gives
 * (the ranges are what the drive's proofs assume: no zero debounce, no zero filter
 * coefficient, ordered pairs).  The conditions that tie a field to the rest of the
 * table (currents within i_max, speeds within speed_max) are checked by
 * qfoc_params_is_valid() (params.h).
 *
 * Requirements: REQ-DCFG-001 .. REQ-DCFG-005 (specs/requirements/drive_cfg.md).
 */
#ifndef QFOC_DRIVE_CFG_H
#define QFOC_DRIVE_CFG_H

#include "qfoc/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Largest number of pole pairs. */
#define QFOC_DRIVE_POLE_PAIRS_MAX ((uint8_t)16u)
/** Largest time setting in milliseconds (one minute). */
#define QFOC_DRIVE_MS_MAX ((uint16_t)60000u)
/** Offset calibration: at least 2^4 current samples averaged. */
#define QFOC_DRIVE_OFFSET_SHIFT_MIN ((uint8_t)4u)
/** Offset calibration: at most 2^10 current samples averaged. */
#define QFOC_DRIVE_OFFSET_SHIFT_MAX ((uint8_t)10u)
/** Largest offset window: |offset - 2048| of a 12-bit converter, 2^11 - 1 counts. */
#define QFOC_DRIVE_OFFSET_WINDOW_MAX ((uint16_t)2047u)
/** Largest handover angle: a quarter turn, 16384 / 65536 = 90 degrees electrical. */
#define QFOC_DRIVE_HO_ANGLE_MAX ((uint16_t)16384u)
/** Lowest temperature threshold, 0.1 degC: -40.0 degC. */
#define QFOC_DRIVE_TEMP_MIN ((int16_t)-400)
/** Highest temperature threshold, 0.1 degC: 200.0 degC. */
#define QFOC_DRIVE_TEMP_MAX ((int16_t)2000)
/** Largest DC-bus and temperature debounce, ms (1 ms tick). */
#define QFOC_DRIVE_DEBOUNCE_MAX ((uint16_t)10u)
/** Largest LIN frame identifier carrying signals: 0x3B (59); 0x3C .. 0x3F are reserved. */
#define QFOC_DRIVE_LIN_ID_MAX ((uint8_t)0x3Bu)
/** Largest 11-bit CAN identifier: 0x7FF (2047). */
#define QFOC_DRIVE_CAN_ID_MAX ((uint16_t)0x7FFu)
/** Largest flux-base shift: psi_base = 2^psi_shift V_base / w_base, at most 16 V_base / w_base. */
#define QFOC_DRIVE_PSI_SHIFT_MAX ((uint8_t)4u)
/** Largest number of start retries after an open loop without a handover. */
#define QFOC_DRIVE_HO_RETRIES_MAX ((uint8_t)3u)
/** Current sensing (version 5): two phase-current sensors, qfoc_drive_fast_step() */
#define QFOC_SENSING_PHASES ((uint8_t)0u)
/** Current sensing (version 5): one DC-link shunt, qfoc_drive_shunt_measure() (drive_shunt.h) */
#define QFOC_SENSING_SHUNT ((uint8_t)1u)
/** Largest shunt_hold: periods the last reconstructed currents may stand in */
#define QFOC_DRIVE_SHUNT_HOLD_MAX ((uint16_t)16u)

/** The drive configuration (params.h field `drive`). */
typedef struct {
    /** Pole pairs n_p, 1 .. 16: mechanical angle and speed from the electrical ones. */
    uint8_t pole_pairs;
    /** Q15 electrical speed per mechanical rpm, Q12: n_p 32768 / (60 f_base) x 4096,
        1 .. 65535; a target in rpm becomes (rpm k_rpm + 2048) >> 12 Q15 counts. */
    uint16_t k_rpm;
    /** Mechanical rpm per Q15 speed count, Q15: 60 f_base / (n_p 32768) x 32768,
        1 .. 65535; a speed of s Q15 counts is s x k_speed_rpm / 32768 rpm. */
    uint16_t k_speed_rpm;
    /** Smallest running target, rpm mechanical, 1 .. rpm_max: a non-zero target below it
        is raised to it (the compressor's lowest speed). */
    uint16_t rpm_min;
    /** Largest target, rpm mechanical, rpm_min .. 65535; in the table additionally
        (rpm_max k_rpm + 2048) >> 12 <= speed_max (params.h). */
    uint16_t rpm_max;
    /** Closed-loop speed-reference ramp, Q15 of w_base per ms, 1 .. 32767. */
    qfoc_q15_t speed_ramp;
    /** Pre-charge: DC bus above vdc_uv this long before the offset calibration starts,
        ms, 1 .. 60000. */
    uint16_t precharge_ms;
    /** Current-sensor offset calibration averages 2^offset_shift samples per phase,
        4 .. 10. */
    uint8_t offset_shift;
    /** Largest accepted |offset - 2048|, 12-bit ADC counts, 0 .. 2047; outside it the
        offset fault is raised. */
    uint16_t offset_window;
    /** ALIGN: d-axis current, Q15 of I_base, 1 .. 32767; in the table <= i_max. */
    qfoc_q15_t i_align;
    /** ALIGN time, ms, 2 .. 60000: ramp of i_align over the first half, hold over the
        second. */
    uint16_t align_ms;
    /** OPEN_LOOP (I/f) current amplitude, Q15 of I_base, 1 .. 32767; in the table <= i_max. */
    qfoc_q15_t i_start;
    /** OPEN_LOOP speed ramp, Q15 of w_base per ms, 1 .. 32767. */
    qfoc_q15_t of_accel;
    /** OPEN_LOOP end speed, Q15 of w_base, 1 .. 32767; in the table <= speed_max. */
    qfoc_q15_t of_speed;
    /** Handover to closed loop when |theta_est - theta_ol| is below this, 65536 counts per
        electrical turn, 1 .. 16384 ... */
    uint16_t ho_angle;
    /** ... for this long, ms, 1 .. 60000. */
    uint16_t ho_dwell_ms;
    /** No handover within this time after OPEN_LOOP reached of_speed: stall fault, ms,
        1 .. 60000. */
    uint16_t ol_timeout_ms;
    /** The speed reference is not ramped to the target before this long after RUN entry
        (2 s, specs/equations.md section 8.3), ms, 0 .. 60000. */
    uint16_t cl_hold_ms;
    /** IPM over-temperature threshold, 0.1 degC, -400 .. 2000. */
    int16_t t_ipm_max;
    /** PCB over-temperature threshold, 0.1 degC, -400 .. 2000. */
    int16_t t_pcb_max;
    /** DC-bus over/under-voltage debounce, ms, 1 .. 10. */
    uint16_t vdc_ms;
    /** Over-temperature debounce, ms, 1 .. 10. */
    uint16_t temp_ms;
    /** Stall: |speed reference - estimate| above this, Q15 of w_base, 1 .. 32767 ... */
    qfoc_q15_t stall_err;
    /** ... or | |psi_est| - psi_expected | above this, Q15 of psi_base, 1 .. 32767 ... */
    qfoc_q15_t flux_tol;
    /** ... for this long, ms, 1 .. 60000. */
    uint16_t stall_ms;
    /** Phase-loss monitor low-pass 2 pi f_c / f_pwm, Q15, 1 .. 32767. */
    qfoc_q15_t phase_alpha;
    /** Phase loss is checked while the largest filtered |i| is above this, Q15 of I_base,
        1 .. 32767. */
    qfoc_q15_t phase_i_min;
    /** Phase loss when smallest / largest filtered |i| is below this, Q15, 0 .. 32767 ... */
    qfoc_q15_t phase_ratio;
    /** ... for this long, ms, 1 .. 60000. */
    uint16_t phase_ms;
    /** Command link lost after this long without a valid command, ms, 1 .. 60000. */
    uint16_t link_timeout_ms;
    /** A fault clear is accepted only after the drive has been stopped this long (the
        5 s of specs/equations.md section 8.3), ms, 1 .. 60000. */
    uint16_t clear_ms;
    /** Field weakening: utilisation target FWK_LVL, Q15, 1 .. 32767. */
    qfoc_q15_t fw_level;
    /** Field weakening: utilisation low-pass 2 pi f_c / f_pwm, Q15, 1 .. 32767. */
    qfoc_q15_t fw_alpha;
    /** Torque compensation: learning gain, Q15, 0 .. 32767 (0 = no learning). */
    qfoc_q15_t tc_gain;
    /** Torque compensation: amplitude limit of each harmonic's i_q, Q15 of I_base,
        0 .. 32767; in the table <= i_max. */
    qfoc_q15_t tc_amp_max;
    /** Torque compensation active from this electrical speed, Q15 of w_base,
        0 .. tc_speed_max ... */
    qfoc_q15_t tc_speed_min;
    /** ... up to this one, Q15 of w_base, 0 .. 32767. */
    qfoc_q15_t tc_speed_max;
    /** motorParaChange: above this electrical speed the high-speed inductances are used,
        Q15 of w_base, 1 .. 32767. */
    qfoc_q15_t para_speed;
    /** High-speed L_d / L_base, Q12, 0 .. 32767. */
    int16_t ld_hs;
    /** High-speed L_q / L_base, Q12, 0 .. 32767. */
    int16_t lq_hs;
    /** LIN identifier of the command frame, 0 .. 0x3B. */
    uint8_t lin_id_cmd;
    /** LIN identifier of the status frame, 0 .. 0x3B, != lin_id_cmd. */
    uint8_t lin_id_status;
    /** CAN identifier of the status frame, even frames, 11 bits: 0 .. 0x7FF. */
    uint16_t can_id_a;
    /** CAN identifier of the status frame, odd frames, 11 bits: 0 .. 0x7FF. */
    uint16_t can_id_b;
    /** MTPA (iref.h) acts while |filtered speed estimate| exceeds this, Q15 of w_base,
        0 .. 32767 (version 3); the tool's default is of_speed (the estimate's angle is
        trusted above the handover); a value at or above speed_max turns MTPA off
        (i_d = 0 below field weakening). */
    qfoc_q15_t mtpa_speed;
    /** Derating (version 3): above this IPM temperature the speed limit falls linearly from
        rpm_max to rpm_derate at t_ipm_max, 0.1 degC, -400 .. 2000, below t_ipm_max. */
    int16_t t_ipm_derate;
    /** ... and above this PCB temperature to rpm_derate at t_pcb_max, 0.1 degC,
        -400 .. 2000, below t_pcb_max; the lower of the two limits applies. */
    int16_t t_pcb_derate;
    /** ... the speed limit at the trip temperature, rpm mechanical, rpm_min .. rpm_max. */
    uint16_t rpm_derate;
    /** Fast flux check (version 3): the band's part proportional to the expected flux,
        Q15 fraction, 1 .. 32767 (magnet temperature and inductance errors) ... */
    qfoc_q15_t flux_band;
    /** ... plus the estimator's voltage error divided by the speed: the voltage error bound
        (the dead-time voltage the compensation may miss, sensing), Q15 of V_base,
        0 .. 32767 ... */
    qfoc_q15_t flux_v_err;
    /** ... and the resistance error, a Q15 fraction of R, 0 .. 32767, times R |i|. */
    qfoc_q15_t flux_r_err;
    /** The flux base (version 4): psi_base = 2^psi_shift V_base / w_base and
        L_base = psi_base / I_base, 0 .. QFOC_DRIVE_PSI_SHIFT_MAX (specs/scaling.md
        section 2).  Every flux and inductance of the table (psi_f, ld, lq, ld_hs, lq_hs,
        flux_tol, pll.mag_min, flux.l) is in this base; a speed times a flux is a voltage
        of 2^psi_shift V_base.  The tool chooses the smallest shift that holds the
        machine's active flux below 1 pu, so that the DC-bus scale V_base can be the bus
        sensor's own full scale (650 .. 900 V buses). */
    uint8_t psi_shift;
    /** Start retries (version 4): an OPEN_LOOP that has not handed over after
        ol_timeout_ms goes back through CATCH and ALIGN to a new I/f start, with the start
        current raised by a quarter of i_start per retry (at most i_max), this many times
        before STALL (sm.h, REQ-SM-011), 0 .. QFOC_DRIVE_HO_RETRIES_MAX. */
    uint8_t ho_retries;
    /** Current sensing (version 5): QFOC_SENSING_PHASES (two phase-current sensors) or
        QFOC_SENSING_SHUNT (one shunt in the DC link, two samples per period inside the
        active vectors, specs/equations.md section 13). */
    uint8_t sensing;
    /** Single shunt: PWM-timer ticks from a gate edge to a settled DC-link current (the
        dead time plus the ringing), 0 .. ; with shunt_sample at most a quarter of the
        PWM counter's period (4 (shunt_settle + shunt_sample) <= svpwm.period, checked in
        both modes so that switching a table's mode keeps it valid). */
    uint16_t shunt_settle;
    /** Single shunt: ticks of the ADC's sample-and-hold, >= 1. */
    uint16_t shunt_sample;
    /** Single shunt: periods the last reconstructed currents may stand in for a missed
        measurement before the sensing is lost, 1 .. QFOC_DRIVE_SHUNT_HOLD_MAX. */
    uint16_t shunt_hold;
} qfoc_drive_cfg_t;

#ifdef __FRAMAC__
/* ACSL predicates over the type above, read by Frama-C only (DEV-001). */
/* cppcheck-suppress misra-c2012-20.1 ; DEV-001 */
#include "drive_cfg.acsl"
#endif

/**
 * @brief Range check of a drive configuration (the logic twin of DriveCfgValid).
 * @param[in] c configuration (any bit pattern)
 * @return true exactly when every field is in the range its comment gives:
 *         speed group: 1 <= pole_pairs <= 16; k_rpm, k_speed_rpm >= 1;
 *         1 <= rpm_min <= rpm_max; speed_ramp >= 1;
 *         start group: precharge_ms, ho_dwell_ms, ol_timeout_ms in 1 .. 60000;
 *         offset_shift in 4 .. 10; offset_window <= 2047; i_align, i_start, of_accel,
 *         of_speed >= 1; align_ms in 2 .. 60000; ho_angle in 1 .. 16384;
 *         cl_hold_ms <= 60000;
 *         protection group: t_ipm_max, t_pcb_max in -400 .. 2000; vdc_ms, temp_ms in
 *         1 .. 10; stall_err, flux_tol, phase_alpha, phase_i_min >= 1;
 *         phase_ratio >= 0; stall_ms, phase_ms, link_timeout_ms, clear_ms in 1 .. 60000;
 *         feature group: fw_level, fw_alpha, para_speed >= 1; tc_gain, tc_amp_max,
 *         ld_hs, lq_hs >= 0; 0 <= tc_speed_min <= tc_speed_max;
 *         lin_id_cmd, lin_id_status <= 0x3B and different; can_id_a, can_id_b <= 0x7FF;
 *         derating and estimator group: mtpa_speed, flux_v_err, flux_r_err >= 0;
 *         flux_band >= 1; t_ipm_derate, t_pcb_derate in -400 .. 2000 and below t_ipm_max,
 *         t_pcb_max (a derating window ending above its trip is refused);
 *         rpm_min <= rpm_derate <= rpm_max;
 *         sensing group: sensing QFOC_SENSING_PHASES or QFOC_SENSING_SHUNT;
 *         shunt_sample >= 1; shunt_hold in 1 .. QFOC_DRIVE_SHUNT_HOLD_MAX (the window's
 *         fit in the PWM period is a table check, params.h).
 *         A field of type qfoc_q15_t / int16_t "<= 32767" and uint16_t "<= 65535" bound
 *         only by the type is not compared.
 *
 * Scaling and overflow: comparisons of each field, widened to its own essential type;
 * no arithmetic.
 *
 * Requirements: REQ-DCFG-001, REQ-DCFG-002, REQ-DCFG-003, REQ-DCFG-004, REQ-DCFG-005,
 * REQ-DCFG-006.
 */
/*@
  requires valid_c: \valid_read(c);
  assigns \nothing;
  ensures result: \result <==> DriveCfgValid(c);
*/
bool qfoc_drive_cfg_is_valid(const qfoc_drive_cfg_t *c);

#ifdef __cplusplus
}
#endif

#endif /* QFOC_DRIVE_CFG_H */
