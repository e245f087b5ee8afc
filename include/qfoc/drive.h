/**
 * @file drive.h
 * @brief The compressor drive: one motor object, two entry points.
 *
 * This is the header an ECU integrator reads.  The drive is specs/equations.md section 8's
 * application and interface layers turned into a library: it owns the motor's
 * controllers, estimator, state machine, fault detection and command link, and is
 * called from exactly two places:
 *
 *   qfoc_drive_fast_step()  once per PWM period, from the ADC-complete interrupt:
 *                           raw ADC samples in, three compare values and the PWM
 *                           enable out (formerly adc1isr / ftmTimerISR);
 *   qfoc_drive_tick()       every 1 ms, from a lower-priority interrupt or task:
 *                           temperatures and a received command frame in, a status
 *                           frame and the 100 ms CAN frame out (formerly
 *                           Ms_1_job, Ms_100_job, Communication_service).
 *
 * There are no globals: one qfoc_drive_t per motor (two compressors, or a test, run
 * side by side).  The library never touches a register; the port (port_s32k/) moves
 * ADC results, compare values, UART bytes and CAN frames.
 *
 * Units at the interface:
 *   - current and DC-bus ADC samples: 12-bit codes 0..4095 (larger codes are
 *     saturated to 4095); phase current = (code - offset) x I_base / 2048 with the
 *     offset calibrated in PRECHARGE (nominal 2048); DC bus = code x V_base / 4096;
 *   - temperatures: 0.1 degC, converted from the NTC by the port;
 *   - compare values: 0..period timer ticks of the centre-aligned PWM (svpwm.h), high
 *     side on for cmp ticks of each half period; PWM disabled = all six switches off;
 *   - speed on the command link: mechanical rpm; internally Q15 of w_base electrical.
 *
 * Behaviour (the state machine is sm.h; thresholds and times are the parameter
 * table's drive section, drive_cfg.h; every rule has an ID in specs/requirements/):
 *   - PRECHARGE: PWM off; the DC bus must stay above vdc_uv for precharge_ms; then
 *     2^offset_shift samples of each current channel are averaged (one per tick) and
 *     each offset must lie within offset_window of 2048, else fault OFFSET.
 *   - STOP: PWM off; a run request (power-on bit, target rpm_min..rpm_max, link alive)
 *     starts the motor.
 *   - RUN / CATCH (flying start, catch.h, REQ-DRV-027): zero-current control in the
 *     observer's frame; a coasting rotor between of_speed and speed_max is caught
 *     (CLOSED_LOOP at its measured speed, no cl_hold_ms hold), a standing one goes to
 *     ALIGN (estimator and current loops restarted), any other waits with zero current.
 *   - RUN / ALIGN: d-current ramp to i_align at angle 0 over align_ms / 2, then held to
 *     3/4 align_ms and half of it for the last quarter; the two d voltages give the
 *     inverter's residual voltage error (dtc.h, REQ-DRV-026).
 *   - RUN / OPEN_LOOP (I/f): current i_start on the q axis of an imposed frame whose
 *     speed ramps at of_accel to of_speed (the q current ramping in from 0 and ALIGN's d
 *     current out, each by ceil(i_max / 16) per tick); the estimator (flux observer + PLL) runs
 *     throughout.
 *   - handover to CLOSED_LOOP when, for ho_dwell_ms, the open-loop speed has reached
 *     of_speed (the minimum speed), the filtered estimated speed is
 *     within 1/4 of the open-loop speed, the observer's flux magnitude is at least the
 *     PLL's mag_min, and the angle delta = theta_ol - theta_est between the open-loop
 *     frame and the estimated rotor lies in (-(90 deg + ho_angle), ho_angle): a rotor
 *     following the frame settles at K i cos(delta) = T_load with delta in [-90, 0] deg,
 *     a slipping one sweeps through +180 deg; and not before cl_hold_ms after the ALIGN
 *     entry (2 s in the generated tables, specs/equations.md section 8.3; 0: at convergence).  The speed PI is preset to the q current that gives, with
 *     i_d = 0, the torque the rotor carries, for a bumpless transfer.
 *   - CLOSED_LOOP: speed reference ramps at speed_ramp to the target; speed PI every
 *     1 ms on the filtered estimate; the tick turns its q current into the current
 *     references (iref.h): the MTPA d current of a salient motor above of_speed, plus
 *     field weakening (fw.h, in the tick), which drives i_d negative when the voltage
 *     utilisation exceeds fw_level, and the q limit sqrt(i_max^2 - i_d^2) of the current
 *     vector; torque compensation (trqcomp.h) adds its feed-forward q current within that
 *     limit; current PIs with decoupling feed-forward, voltage circle limit
 *     V_dc / sqrt 3, SVPWM with dead-time compensation.
 *   - power-off in CLOSED_LOOP: STOPPING ramps the speed reference down to of_speed,
 *     then PWM off and STOP.  Power-off in ALIGN or OPEN_LOOP: PWM off at once.
 *   - ERROR: PWM off at once; the fault word and the first-fault record latch; left
 *     to STOP only after clear_ms (5 s) in ERROR on a fault-clear request with no
 *     fault present and the table intact (formerly Faultclear).
 *
 * Faults and reaction times (fault.h bits; specs/requirements/drive.md):
 *   OC     |i_u|, |i_v| or |i_w| > i_trip: PWM off in the SAME fast step, ERROR at the
 *          next tick (latched by the fast step until the fault is cleared);
 *   OV, UV filtered DC bus above vdc_ov (any state) / below vdc_uv (RUN) for vdc_ms;
 *   OT_IPM, OT_PCB  temperature above its limit for temp_ms;
 *   STALL  in CLOSED_LOOP, |speed ref - estimate| > stall_err or the observer's flux
 *          magnitude off its expected value by more than flux_tol, for stall_ms; or
 *          no handover within ol_timeout_ms of OPEN_LOOP; and the fast flux check
 *          (REQ-DRV-023): in CLOSED_LOOP from 100 ms after its entry, above 1.5 of_speed,
 *          the flux magnitude off its expected value psi_f + (L_d - L_q) i_d by more than
 *          3/10 of it in 2 ticks in a row (a current-sensor offset or gain, a DC-bus
 *          reading off the true bus, an open phase: the observer integrates the measured
 *          voltage and current; the table's psi_f, L_d and L_q must hold within that band
 *          over the magnet's temperature range, safety manual AoU-15); and the lost
 *          rotor (REQ-DRV-023): in CLOSED_LOOP from 100 ms after its entry, 4 |estimate|
 *          below both of_speed and the speed reference in 2 ticks in a row;
 *   PHASE  in OPEN_LOOP, CLOSED_LOOP and STOPPING, the smallest filtered |phase
 *          current| below phase_ratio x the largest, the largest above phase_i_min, for
 *          phase_ms; in ALIGN from align_ms / 2 on, the same with phase_ratio / 2; and
 *          in ALIGN (from align_ms / 2) and OPEN_LOOP, no current: 4 x the largest
 *          filtered |phase current| below |i_align| / |i_start| (no motor, an open phase,
 *          stuck current sensors), for phase_ms: ERROR align_ms / 2 + phase_ms after
 *          the start, before the motor is accelerated (REQ-DRV-018);
 *   OFFSET offset calibration out of its window (PRECHARGE); and, in CLOSED_LOOP and
 *          STOPPING while the stall condition is false and the current is one a healthy
 *          phase cannot hold on a code for 2 ms (REQ-DRV-020): one current code
 *          unchanged for 2 ms of fast steps while the other channel's code moved (a
 *          stuck sample or a sensor stuck at any value: where a healthy phase current is
 *          slowest, at its peak, the other phase's is near its steepest; a rotor at
 *          standstill, whose DC currents hold both codes, is STALL's);
 *   TIMING in RUN, fewer than floor(f_pwm / 1000) - 2 or more than ceil(f_pwm / 1000) + 2
 *          fast steps since the previous tick (a lost or repeated PWM interrupt,
 *          REQ-DRV-021); the tick that sees it sets out.pwm_off, so the port turns the
 *          inverter off although the fast step does not run;
 *   LINK   no valid command frame for link_timeout_ms while running: the command
 *          becomes power-off (controlled ramp-down), then ERROR;
 *   PARAM  the parameter table fails its identity, CRC or range check, at
 *          initialisation or at its 100 ms re-check: ERROR, not clearable.
 *   The tick reacts within 1 ms of a debounce completing, so every reaction time is
 *   its debounce time + 1 ms (OV/UV/OT within 10 ms with the default tables).
 *
 * Concurrency: the fast step may pre-empt the tick at any point.  Every field of
 * qfoc_drive_t is written by one context only: qfoc_drive_fast_t by the fast step,
 * qfoc_drive_slow_t by the tick; each reads the other's fields (single 8-, 16- or
 * 32-bit reads, atomic on the Cortex-M4).  The over-current latch is a counter the
 * fast step increments and a clear counter the tick increments, so neither context
 * writes the other's data.  Initialisation runs before the interrupts are enabled.
 *
 * Resources on the Cortex-M4F (arm-none-eabi-gcc -O2, measured by make bench into
 * build/bench/bench.md): no recursion, no dynamic memory, no library data or bss.  The
 * size of one qfoc_drive_t (REQ-BENCH-005), the worst-case stack of the fast step and of
 * the tick (REQ-BENCH-006), the instructions of the fast step's longest path in closed
 * loop with field weakening and torque compensation (REQ-BENCH-001, REQ-BENCH-002; the
 * core functions against published figures: REQ-BENCH-003), those of the tick with the
 * 100 ms table re-check, and the code a drive firmware links (REQ-BENCH-004) are each
 * gated by a limit in specs/requirements/bench.md: make bench fails when a measured
 * figure exceeds it.  The figure to plan the CPU with is the static bound of
 * qfoc_drive_fast_step() and of qfoc_drive_tick(): the longest path of the linked image
 * over every input and every state, in instructions and estimated cycles, which no
 * measured count exceeds (REQ-BENCH-008, tools/bench/wcet.py).  The target build gives
 * the host build's outputs bit for bit (REQ-BENCH-007; make target-test replays golden
 * vectors of every function group and of the whole drive under QEMU: REQ-TGT-001 ..
 * REQ-TGT-005 in specs/requirements/target.md, named in tools/target_test/tt.h).
 *
 * Requirements (specs/requirements/drive.md): REQ-DRV-001 motor object and table,
 * REQ-DRV-002 PWM only in RUN, REQ-DRV-003 over-current, REQ-DRV-004 measurement,
 * REQ-DRV-005 one writer per field, REQ-DRV-006 start-up and control, REQ-DRV-007
 * offsets, REQ-DRV-008 faults, REQ-DRV-009 commands, REQ-DRV-010 table re-check,
 * REQ-DRV-011 status and CAN, REQ-DRV-012 motorParaChange, REQ-DRV-013 field weakening
 * and torque compensation, REQ-DRV-014 start on the plant, REQ-DRV-015 malformed frames,
 * REQ-DRV-016 command without frames, REQ-DRV-017 status readers, REQ-DRV-018 current
 * response in ALIGN and OPEN_LOOP, REQ-DRV-019 RAM check, REQ-DRV-020 stuck sample,
 * REQ-DRV-021 fast steps per tick, REQ-DRV-022 reference guard, REQ-DRV-023 fast flux
 * plausibility.
 *
 * Behaviour on the plant, end to end (specs/requirements/scenarios.md, targets in
 * specs/scenarios.toml, shown by make demo): REQ-SCN-001 cold start, REQ-SCN-002 speed
 * steps and field weakening, REQ-SCN-003 pulsating load, REQ-SCN-004 load step,
 * REQ-SCN-005 DC-bus sag, REQ-SCN-006 over-current, REQ-SCN-007 over-voltage,
 * REQ-SCN-008 over-temperature, REQ-SCN-009 locked rotor, REQ-SCN-010 link loss (each
 * with its recovery), REQ-SCN-011 robust start, REQ-SCN-012 other tables, REQ-SCN-013
 * MTPA against i_d = 0, REQ-SCN-014 thermal derating, REQ-SCN-015 flying start.
 */
#ifndef QFOC_DRIVE_H
#define QFOC_DRIVE_H

#include "qfoc/types.h"
#include "qfoc/params.h"
#include "qfoc/filter.h"
#include "qfoc/pi.h"
#include "qfoc/flux.h"
#include "qfoc/pll.h"
#include "qfoc/svpwm.h"
#include "qfoc/fw.h"
#include "qfoc/fault.h"
#include "qfoc/trqcomp.h"
#include "qfoc/link.h"
#include "qfoc/sm.h"
#include "qfoc/catch.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Largest ADC code (12 bits). */
#define QFOC_ADC_MAX ((uint16_t)4095u)
/** ADC code of zero current (mid-scale). */
#define QFOC_ADC_MID ((uint16_t)2048u)

/** Raw samples of one PWM period (formerly adcRawValue_n). */
typedef struct {
    uint16_t iu;   /**< phase u current, 0..4095 (2048 nominal zero) */
    uint16_t iv;   /**< phase v current, 0..4095 */
    uint16_t vdc;  /**< DC-bus voltage, 0..4095 */
} qfoc_adc_t;

/* Output of one PWM period: qfoc_pwm_t (types.h). */

/** Inputs of one tick. */
typedef struct {
    int16_t t_ipm;          /**< IPM temperature, 0.1 degC */
    int16_t t_pcb;          /**< PCB temperature, 0.1 degC */
    const uint8_t *rx;      /**< frame received since the last tick (may be NULL when rx_len is 0) */
    uint8_t rx_len;         /**< its length in bytes, 0 = none */
} qfoc_tick_in_t;

/** Outputs of one tick. */
typedef struct {
    uint8_t tx[QFOC_LIN_FRAME_MAX];  /**< status frame to send on the UART */
    uint8_t tx_len;                  /**< its length, 0 = nothing to send */
    qfoc_can_frame_t can;            /**< CAN status frame */
    bool can_send;                   /**< true on the 100 ms job's tick */
    bool pwm_off;                    /**< true when the drive is not in RUN after this tick: the
                                          port turns the inverter off at once, without waiting
                                          for the fast step (REQ-DRV-021) */
} qfoc_tick_out_t;

/** Data written by the fast step only. */
typedef struct {
    qfoc_flux_t flux;         /**< flux observer (specs/equations.md E2-19 .. E2-24) */
    qfoc_pll_t pll;           /**< PLL (specs/equations.md E2-27, E2-28, E2-34) */
    qfoc_pi_t pi_id;          /**< d-current PI */
    qfoc_pi_t pi_iq;          /**< q-current PI */
    qfoc_lpf_t vdc_lpf;       /**< DC-bus low-pass */
    qfoc_phase_mon_t phase;   /**< phase-loss monitor */
    qfoc_mech_t mech;         /**< mechanical angle */
    qfoc_ab_t u_last;         /**< voltage command of this period (applied next period) */
    qfoc_ab_t u_applied;      /**< voltage applied during the period just sampled */
    uint32_t theta_ol;        /**< open-loop angle, 2^32 per turn */
    qfoc_dq_t i_dq;           /**< measured currents in the control frame */
    qfoc_q15_t vdc;           /**< filtered DC bus */
    uint16_t adc_iu;          /**< last raw sample of i_u, ADC code (offset calibration) */
    uint16_t adc_iv;          /**< last raw sample of i_v, ADC code (offset calibration) */
    qfoc_angle_t theta_est;   /**< estimated rotor angle (lead-corrected) */
    qfoc_angle_t theta_m;     /**< mechanical angle (torque compensation) */
    qfoc_q15_t speed;         /**< PLL speed, unfiltered */
    qfoc_q15_t speed_f;       /**< PLL speed after the low-pass (specs/equations.md E2-34) */
    qfoc_q15_t psi_mag;       /**< observer flux magnitude */
    uint8_t trip_count;       /**< over-current events (mod 256) */
    uint8_t clamp_count;      /**< periods with the q reference clamped to +-iq_lim (mod 256) */
    uint8_t clear_ack;        /**< last clear_seq acknowledged */
    bool trip;                /**< over-current latch: PWM held off */
    bool active;              /**< the control ran in the last period */
    bool hs;                  /**< high-speed inductances in use (motorParaChange) */
    uint8_t phase_k;          /**< phase the monitor filters in this period (0, 1, 2) */
    uint8_t sub_last;         /**< the sub-state of the last controlled period */
    qfoc_abc_t i_abc;         /**< this period's phase currents, offset-corrected, Q15 */
    qfoc_pwm_t out;           /**< this period's output (returned by the fast step) */
    uint16_t same_u;          /**< consecutive samples with the i_u code unchanged (capped at
                                   65535; REQ-DRV-020) */
    uint16_t same_v;          /**< the same for i_v */
    uint16_t n_fast;          /**< fast steps so far, mod 65536 (REQ-DRV-021) */
} qfoc_drive_fast_t;

/** Data written by the tick only. */
typedef struct {
    qfoc_sm_t sm;             /**< state machine */
    qfoc_pi_t pi_speed;       /**< speed PI (1 ms); its limits follow iq_lim (REQ-IREF-002) */
    qfoc_fw_t fw;             /**< field weakening (1 ms, REQ-DRV-006) */
    qfoc_trqcomp_t tc;        /**< torque compensation */
    qfoc_link_t link;         /**< command link */
    qfoc_debounce_t db_ov;    /**< debounce of OV (each tick-evaluated fault has its own) */
    qfoc_debounce_t db_uv;    /**< debounce of UV */
    qfoc_debounce_t db_ot_ipm; /**< debounce of OT_IPM */
    qfoc_debounce_t db_ot_pcb; /**< debounce of OT_PCB */
    qfoc_debounce_t db_stall; /**< debounce of STALL (speed or flux error) */
    qfoc_debounce_t db_flux;  /**< the fast flux plausibility check (REQ-DRV-023) */
    qfoc_debounce_t db_phase; /**< debounce of PHASE */
    qfoc_debounce_t db_align; /**< ALIGN without current (REQ-DRV-025) */
    qfoc_debounce_t db_ho;    /**< handover condition dwell */
    qfoc_catch_t catch_st;    /**< flying start: CATCH's filter and dwells (catch.h) */
    uint32_t off_sum_u;       /**< offset calibration: sum of the i_u samples */
    uint32_t off_sum_v;       /**< offset calibration: sum of the i_v samples */
    uint16_t off_n;           /**< samples summed */
    uint16_t offset_u;        /**< calibrated offset of i_u, ADC code */
    uint16_t offset_v;        /**< calibrated offset of i_v, ADC code */
    qfoc_q15_t speed_target;  /**< commanded speed, Q15 electrical */
    qfoc_q15_t speed_ref;     /**< ramped speed reference */
    qfoc_q15_t ol_speed;      /**< open-loop frame speed */
    qfoc_q15_t id_ref;        /**< d-current reference: ALIGN's ramp, 0 in OPEN_LOOP, MTPA plus
                                   field weakening in CLOSED_LOOP and STOPPING (iref.h) */
    qfoc_q15_t iq_ref;        /**< q-current reference (speed PI, or i_start in OPEN_LOOP) */
    qfoc_q15_t iq_lim;        /**< q-current limit of the closed loop, sqrt(i_max^2 - id_ref^2)
                                   (iref.h); 0 outside CLOSED_LOOP and STOPPING */
    qfoc_q15_t dt_dv;         /**< the inverter's residual voltage error the observer uses:
                                   dt_learn faded out with the speed (dtc.h, REQ-DRV-026) */
    qfoc_q15_t dt_learn;      /**< the residual learnt at the end of ALIGN, 0 until then in
                                   each run and outside RUN */
    qfoc_q15_t dt_u;          /**< the d voltage at the end of ALIGN's full-current hold */
    qfoc_q15_t dt_u0;         /**< the d voltage at 5/8 of ALIGN (the full-current hold) */
    qfoc_q15_t dt_u1;         /**< the d voltage at 7/8 of ALIGN (the half-current hold) */
    qfoc_angle_t lead;        /**< observer phase lead at the filtered speed (qfoc_flux_lead) */
    qfoc_q15_t util;          /**< voltage utilisation of the last command, |v| / (V_dc / sqrt 3) */
    uint8_t trip_seen;        /**< trip_count already reported */
    uint8_t clamp_seen;       /**< clamp_count at the last tick */
    uint8_t clear_seq;        /**< incremented when a fault clear is accepted */
    uint8_t ms100;            /**< ticks of the current 100 ms period, 0..99 */
    uint16_t fast_seen;       /**< n_fast at the last tick (REQ-DRV-021) */
    bool table_ok;            /**< result of the last table check */
    uint32_t scan_crc;        /**< CRC register of the table check in progress */
    bool calib_done;          /**< offsets calibrated in range */
    bool hs;                  /**< request: high-speed inductances (motorParaChange) */
    bool derated;             /**< a temperature holds the speed limit below rpm_max
                                   (REQ-DRV-024) */
    bool caught;              /**< this run's CLOSED_LOOP was entered from CATCH: no
                                   cl_hold_ms hold (REQ-DRV-027) */
    uint16_t ref_guard;       /**< guard word of speed_target .. dt_dv (REQ-DRV-022) */
    uint32_t run_ms;          /**< time in RUN, ms, saturating (Motor_Run_Time) */
    qfoc_status_t status;     /**< last status (LIN and CAN) */
    qfoc_cmd_t cmd;           /**< effective command of this tick (after the link rules) */
    qfoc_sm_cfg_t sm_cfg;     /**< state-machine times, from the table at initialisation */
    qfoc_sm_in_t sm_in;       /**< state-machine inputs of this tick */
    qfoc_tick_out_t out;      /**< this tick's output (returned by the tick) */
} qfoc_drive_slow_t;

/** One motor. */
typedef struct {
    const qfoc_param_table_t *p;  /**< the parameter table (flash), checked */
    qfoc_drive_fast_t f;          /**< written by the fast step */
    qfoc_drive_slow_t s;          /**< written by the tick */
} qfoc_drive_t;

#ifdef __FRAMAC__
/* ACSL predicates over the types above, read by Frama-C only (DEV-001). */
/* cppcheck-suppress misra-c2012-20.1 ; DEV-001 */
#include "drive.acsl"
#endif

/**
 * @brief Check the drive invariant (the logic twin of DriveValid): the table passes
 *        its range check, every controller, filter and estimator satisfies its own
 *        invariant, the state machine is valid, and the offsets are ADC codes.
 * @param[in] d drive
 * @return true when the drive may be stepped.
 * Requirements: REQ-DRV-001.
 */
/*@
  requires valid_d: \valid_read(d) && \valid_read(d->p) && \separated(d, d->p);
  assigns \nothing;
  ensures result: \result <==> DriveValid(d);
*/
bool qfoc_drive_is_valid(const qfoc_drive_t *d);

/**
 * @brief Initialise one motor from its parameter table.
 * @param[out] d     the motor object
 * @param[in]  table the generated parameter table (any bit pattern)
 * @return QFOC_PARAMS_OK, or the table's failure status (params.h); on failure the
 *         drive is in ERROR with fault PARAM (not clearable) and its PWM stays off,
 *         using a built-in safe configuration for its own state.
 * Call before the interrupts are enabled.  Requirements: REQ-DRV-001, REQ-DRV-010.
 */
/*@
  requires valid_d: \valid(d);
  requires valid_table: \valid_read(table);
  requires sep: \separated(d, table);
  assigns *d;
  ensures table: d->p == table;
  ensures valid: DRV_VALID(d);
  ensures status: \result == QFOC_PARAMS_OK || \result == QFOC_PARAMS_ERR_ID ||
                  \result == QFOC_PARAMS_ERR_CRC || \result == QFOC_PARAMS_ERR_RANGE;
  ensures refused: \result != QFOC_PARAMS_OK ==>
      d->s.sm.state == QFOC_STATE_ERROR && !d->s.table_ok;
  ensures accepted: \result == QFOC_PARAMS_OK ==>
      d->s.sm.state == QFOC_STATE_PRECHARGE && d->s.table_ok;
  ensures guard: DRV_GUARD_OK(d);
*/
int32_t qfoc_drive_init(qfoc_drive_t *d, const qfoc_param_table_t *table);

/**
 * @brief One PWM period (ADC-complete interrupt).
 * @param[in,out] d   the motor object (valid)
 * @param[in]     adc raw samples of this period (any values)
 * @return compare values and enable for the next period: a copy of d->f.out, which
 *         the guarantees below describe
 * Guarantees: cmp[k] <= period always; enable only in RUN without an over-current
 * latch; an over-current in these samples gives enable false in this same call.
 * Writes only d->f (the tick's half d->s and the table are read only).
 * The flux observer integrates the voltage applied in the last period less the inverter's
 * residual error the tick learnt when ALIGN ended (dtc.h, REQ-DRV-026).
 * Requirements: REQ-DRV-002, REQ-DRV-003, REQ-DRV-004, REQ-DRV-026.
 */
/*@
  requires valid: \valid(d) && \valid_read(adc);
  requires sep: \separated(d, adc);
  requires inv: DRV_VALID(d);
  assigns d->f;
  ensures inv: DRV_VALID(d);
  ensures table: d->p == \old(d->p);
  ensures kept: \result == d->f.out;
  ensures cmp: d->f.out.cmp[0] <= d->p->svpwm.period && d->f.out.cmp[1] <= d->p->svpwm.period &&
               d->f.out.cmp[2] <= d->p->svpwm.period;
  ensures pwm_only_in_run: d->f.out.enable ==> d->s.sm.state == QFOC_STATE_RUN && !d->f.trip;
  ensures over_current: DriveOverCurrent{Pre}(d, adc) ==> !d->f.out.enable && d->f.trip;
*/
qfoc_pwm_t qfoc_drive_fast_step(qfoc_drive_t *d, const qfoc_adc_t *adc);

/**
 * @brief The 1 ms tick (and, every 100th call, the 100 ms job).
 * @param[in,out] d   the motor object (valid)
 * @param[in]     in  temperatures and the received frame (any values)
 * @return the status frame and the CAN frame to send: a copy of d->s.out
 * Writes only d->s (the fast step's half d->f and the table are read only).
 * RAM check: each call first checks a quarter of the drive object against its invariant
 * (the checks of qfoc_drive_is_valid, the offsets within their window, the PLL's angle
 * gain against the table), the whole in 4 calls; a violation (a flipped bit, a stray
 * write) raises PARAM and ERROR in that call, the PWM goes off in the next period, and
 * the drive stays in ERROR until qfoc_drive_init() is called again (REQ-DRV-019).
 * Reference guard: each call also first compares the guard word of the seven references
 * (speed_target, speed_ref, ol_speed, id_ref, iq_ref, iq_lim, dt_dv) with their values; only the
 * init and the tick write them and both leave the guard matching (ensures guard), so a flipped bit
 * that leaves a reference admissible is PARAM in the same way, before it is used
 * (REQ-DRV-022).
 * Sensor and timing monitors: the current-sensor and fast-step checks of OFFSET and
 * TIMING above (REQ-DRV-020, REQ-DRV-021).  out.pwm_off is true whenever the state after
 * the call is not RUN: the port turns the inverter off at once (a second path to the safe
 * state beside the fast step's PWM off, for a fast step that no longer runs).
 * Requirements: REQ-DRV-005 .. REQ-DRV-012, REQ-DRV-019 .. REQ-DRV-022, REQ-DRV-026.
 */
/*@
  requires valid: \valid(d) && \valid_read(in);
  requires rx: in->rx_len > 0 ==> \valid_read(in->rx + (0 .. in->rx_len - 1));
  requires sep: \separated(d, in) &&
                (in->rx_len > 0 ==> \separated(d, in->rx + (0 .. in->rx_len - 1)));
  requires inv: DRV_VALID(d);
  assigns d->s;
  ensures inv: DRV_VALID(d);
  ensures kept: \result == d->s.out;
  ensures tx: d->s.out.tx_len == 0 || d->s.out.tx_len == QFOC_LIN_STATUS_LEN;
  ensures pwm_off: d->s.out.pwm_off == \true <==> d->s.sm.state != QFOC_STATE_RUN;
  ensures guard: DRV_GUARD_OK(d);
  ensures error_exit: \old(d->s.sm.state) == QFOC_STATE_ERROR &&
      d->s.sm.state != QFOC_STATE_ERROR ==> d->s.sm.state == QFOC_STATE_STOP;
  ensures run_entry: \old(d->s.sm.state) != QFOC_STATE_RUN && d->s.sm.state == QFOC_STATE_RUN ==>
      \old(d->s.sm.state) == QFOC_STATE_STOP && d->s.sm.sub == QFOC_SUB_CATCH;
*/
qfoc_tick_out_t qfoc_drive_tick(qfoc_drive_t *d, const qfoc_tick_in_t *in);

/* ---------------------------------------------------------- command and status
 *
 * Commands and status without the LIN frames, for an ECU commanded over CAN, AUTOSAR
 * COM or its own logic.  Call every function below from the tick's context (the task
 * or interrupt that calls qfoc_drive_tick(), between two ticks), never from the fast
 * step's interrupt: the command writes the tick's half of the drive, and the readers
 * read values the tick writes.
 *
 * When status goes out on its own: the tick fills qfoc_tick_out_t.tx (tx_len 11) only in
 * a tick whose received frame was an accepted command frame (the answer of a LIN slave;
 * a command given through qfoc_drive_command() is not answered on LIN), and the CAN
 * frame (can_send true) on every 100th tick.  The status the readers return is updated
 * by every tick.
 *
 * Typical use (1 ms task):
 *
 *     qfoc_cmd_t cmd = { .power_on = true, .fault_clear = false, .target_rpm = 3000u };
 *     (void)qfoc_drive_command(&drive, &cmd);      repeat within timeout_ms
 *     out = qfoc_drive_tick(&drive, &in);
 *     if (qfoc_drive_state(&drive) == QFOC_STATE_ERROR) { report qfoc_drive_faults() }
 */

/**
 * @brief Give the drive a decoded command: run (power_on), target speed in mechanical
 *        rpm, fault clear, and the identification request (identify).
 * @param[in,out] d   the motor object (valid)
 * @param[in]     cmd the command (any field values)
 * @return QFOC_LINK_OK: taken, it acts from the next tick on; QFOC_LINK_ERR_RANGE:
 *         target_rpm above the table's rpm_max, refused, nothing changes but the link's
 *         n_range counter (as for a command frame out of range).
 * A taken command is the link's command exactly as a valid LIN command frame would be:
 * it restarts the link timeout (the command must be repeated within timeout_ms ticks,
 * else the link is lost: the drive ramps down, then reports LINK), and it replaces the
 * last frame's command.  power_on starts the motor only with target_rpm >= rpm_min;
 * fault_clear acts as described for ERROR above.  identify is the one way to request
 * the identification (commission.h): it runs only while this request stands (repeated
 * within timeout_ms, power_on clear, the drive in STOP); a command frame received
 * later replaces the command with identify false, and a lost link clears it, which
 * ends a running identification.
 * Requirements: REQ-DRV-016, REQ-IDENT-007.
 */
/*@
  requires valid: \valid(d) && \valid_read(cmd);
  requires sep: \separated(d, cmd);
  requires inv: DRV_VALID(d);
  assigns d->s.link.cmd, d->s.link.seen, d->s.link.silent_ms, d->s.link.lost, d->s.link.n_ok,
          d->s.link.n_range;
  ensures inv: DRV_VALID(d);
  behavior taken:
    assumes cmd->target_rpm <= d->s.link.cfg.rpm_max;
    ensures result: \result == QFOC_LINK_OK;
    ensures cmd: d->s.link.cmd.power_on == cmd->power_on &&
                 d->s.link.cmd.fault_clear == cmd->fault_clear &&
                 d->s.link.cmd.target_rpm == cmd->target_rpm &&
                 d->s.link.cmd.identify == cmd->identify;
    ensures timer: d->s.link.seen == \true && d->s.link.silent_ms == 0;
  behavior refused:
    assumes cmd->target_rpm > d->s.link.cfg.rpm_max;
    ensures result: \result == QFOC_LINK_ERR_RANGE;
    ensures unchanged: LinCmdSame{Pre, Post}(&d->s.link.cmd) &&
                       d->s.link.seen == \old(d->s.link.seen) &&
                       d->s.link.silent_ms == \old(d->s.link.silent_ms) &&
                       d->s.link.lost == \old(d->s.link.lost);
    ensures count: d->s.link.n_range == LinSatInc(\old(d->s.link.n_range));
  complete behaviors;
  disjoint behaviors;
*/
int32_t qfoc_drive_command(qfoc_drive_t *d, const qfoc_cmd_t *cmd);

/**
 * @brief State of the state machine: QFOC_STATE_PRECHARGE .. QFOC_STATE_ERROR (sm.h).
 * @param[in] d the motor object
 * @return the state, one of the QFOC_STATE_* codes
 * Requirements: REQ-DRV-017.
 */
/*@
  requires valid: \valid_read(d);
  assigns \nothing;
  ensures result: \result == d->s.sm.state;
*/
uint8_t qfoc_drive_state(const qfoc_drive_t *d);

/**
 * @brief Sub-state (sm.h): QFOC_SUB_ALIGN, QFOC_SUB_OPEN_LOOP, QFOC_SUB_CLOSED_LOOP or
 *        QFOC_SUB_STOPPING in RUN; QFOC_SUB_CALIB in PRECHARGE's calibration.
 * @param[in] d the motor object
 * @return the sub-state, one of the QFOC_SUB_* codes
 * Requirements: REQ-DRV-017.
 */
/*@
  requires valid: \valid_read(d);
  assigns \nothing;
  ensures result: \result == d->s.sm.sub;
*/
uint8_t qfoc_drive_substate(const qfoc_drive_t *d);

/**
 * @brief Fault word: the QFOC_FAULT_* bits (fault.h) of the tick that entered ERROR,
 *        latched until the fault clear (0 outside ERROR).
 * @param[in] d the motor object
 * @return the fault word (qfoc_fault_name() names a single bit)
 * Requirements: REQ-DRV-017.
 */
/*@
  requires valid: \valid_read(d);
  assigns \nothing;
  ensures result: \result == d->s.sm.faults;
*/
uint16_t qfoc_drive_faults(const qfoc_drive_t *d);

/**
 * @brief First fault: the QFOC_FAULT_* bits of the tick that entered ERROR (0 outside
 *        ERROR), for the diagnostic record of the root cause.  The fault word latches at
 *        the same value when ERROR is entered (a later fault changes neither), so the two
 *        are equal in this release; read this one for the root cause.
 * @param[in] d the motor object
 * @return the first-fault word (qfoc_fault_name() names a single bit)
 * Requirements: REQ-DRV-017.
 */
/*@
  requires valid: \valid_read(d);
  assigns \nothing;
  ensures result: \result == d->s.sm.first_fault;
*/
uint16_t qfoc_drive_first_fault(const qfoc_drive_t *d);

/**
 * @brief Status in physical units, as the last tick computed it (the values of the LIN
 *        status frame and of the CAN frame, before their coarser encoding): state,
 *        sub-state, fault word, |estimated speed| in mechanical rpm (0 while the PWM is
 *        off), DC bus in 0.1 V,
 *        current-vector amplitude in 0.01 A, the hotter of IPM and PCB in 0.1 degC.
 * @param[in]  d  the motor object
 * @param[out] st the copy
 * Requirements: REQ-DRV-017.
 */
/*@
  requires valid: \valid_read(d) && \valid(st);
  requires sep: \separated(d, st);
  assigns *st;
  ensures copy: st->state == d->s.status.state && st->substate == d->s.status.substate &&
                st->faults == d->s.status.faults && st->speed_rpm == d->s.status.speed_rpm &&
                st->vdc_dv == d->s.status.vdc_dv && st->current_ca == d->s.status.current_ca &&
                st->temp_dc == d->s.status.temp_dc;
*/
void qfoc_drive_status(const qfoc_drive_t *d, qfoc_status_t *st);

/**
 * @brief |Estimated speed|, mechanical rpm (the filtered estimate, as of the last tick;
 *        0 while the PWM is off, when the estimator has no input).
 * @param[in] d the motor object
 * @return the speed magnitude, mechanical rpm
 * Requirements: REQ-DRV-017.
 */
/*@
  requires valid: \valid_read(d);
  assigns \nothing;
  ensures result: \result == d->s.status.speed_rpm;
*/
uint16_t qfoc_drive_speed_rpm(const qfoc_drive_t *d);

/**
 * @brief Commanded speed in effect, mechanical rpm: the target of the last command
 *        taken (frame or qfoc_drive_command()), 0 before the first.
 * @param[in] d the motor object
 * @return the commanded speed, mechanical rpm
 * Requirements: REQ-DRV-017.
 */
/*@
  requires valid: \valid_read(d);
  assigns \nothing;
  ensures result: \result == d->s.cmd.target_rpm;
*/
uint16_t qfoc_drive_target_rpm(const qfoc_drive_t *d);

/**
 * @brief Run request in effect: the last command's power_on while the link is alive
 *        (false before the first command and while the link is lost).
 * @param[in] d the motor object
 * @return true when a run is requested
 * Requirements: REQ-DRV-017.
 */
/*@
  requires valid: \valid_read(d);
  assigns \nothing;
  ensures result: \result == d->s.cmd.power_on;
*/
bool qfoc_drive_run_requested(const qfoc_drive_t *d);

/**
 * @brief Identification request in effect: the identify of the last command taken while
 *        the link is alive (false before the first command, while the link is lost, and
 *        after a command frame, which never carries it); commission.h starts the
 *        identification only while it is true.
 * @param[in] d the motor object
 * @return true when the identification is requested
 * Requirements: REQ-DRV-017, REQ-IDENT-007.
 */
/*@
  requires valid: \valid_read(d);
  assigns \nothing;
  ensures result: \result == d->s.cmd.identify;
*/
bool qfoc_drive_identify_requested(const qfoc_drive_t *d);

/**
 * @brief Thermal derating in effect: after the last tick, the IPM or the PCB temperature
 *        held the speed limit below rpm_max (it falls linearly from rpm_max at the
 *        derating temperature to rpm_derate at the trip; false before the first tick).
 * @param[in] d the motor object
 * @return true when the speed limit is derated
 * Requirements: REQ-DRV-024.
 */
/*@
  requires valid: \valid_read(d);
  assigns \nothing;
  ensures result: \result == d->s.derated;
*/
bool qfoc_drive_derated(const qfoc_drive_t *d);

/**
 * @brief Estimated electrical rotor angle, 65536 per electrical turn (the fast step's
 *        last estimate; 0 = the d axis on phase u).
 * @param[in] d the motor object
 * @return the estimated angle, 65536 counts per electrical turn
 * Requirements: REQ-DRV-017.
 */
/*@
  requires valid: \valid_read(d);
  assigns \nothing;
  ensures result: \result == d->f.theta_est;
*/
qfoc_angle_t qfoc_drive_angle_est(const qfoc_drive_t *d);

/**
 * @brief Measured d and q currents of the last controlled period, Q15 of I_base
 *        (the table's i_base_ma: 32767 = I_base); 0 while the PWM is off.  The two
 *        values are read one after the other and may come from consecutive periods.
 * @param[in]  d    the motor object
 * @param[out] i_dq the currents
 * Requirements: REQ-DRV-017.
 */
/*@
  requires valid: \valid_read(d) && \valid(i_dq);
  requires sep: \separated(d, i_dq);
  assigns *i_dq;
  ensures copy: i_dq->d == d->f.i_dq.d && i_dq->q == d->f.i_dq.q;
*/
void qfoc_drive_currents_q15(const qfoc_drive_t *d, qfoc_dq_t *i_dq);

/**
 * @brief Filtered DC-bus voltage, Q15 of V_base (the table's v_base_mv: 32767 = V_base);
 *        qfoc_drive_status() gives it in 0.1 V.
 * @param[in] d the motor object
 * @return the filtered DC-bus voltage, Q15 of V_base
 * Requirements: REQ-DRV-017.
 */
/*@
  requires valid: \valid_read(d);
  assigns \nothing;
  ensures result: \result == d->f.vdc;
*/
qfoc_q15_t qfoc_drive_vdc_q15(const qfoc_drive_t *d);

#ifdef __cplusplus
}
#endif

#endif /* QFOC_DRIVE_H */
