/**
 * @file faults.c
 * @brief The fault-injection campaign (make faults, make faults-check): faults injected into
 *        the plant, its sensing, the DC bus, the temperatures, the command link, the calls of
 *        the two entry points, the RAM copy of the parameter table and the drive object, with
 *        the drive of include/qfoc/drive.h in the loop (drive_sim.h) on the reference motor
 *        and its table.  specs/fault-campaign.md gives the classes, the fault tolerant time
 *        intervals (FTTI) and the verdict rule.
 *
 * Method: the drive runs on a RAM copy of the reference table that this program owns
 * (qfoc_drive_init(&drv, &ram_table)).  Five states are made once and saved whole (the
 * dsim_t with plant, drive, master and noise generator, and the RAM table): power-up (COLD),
 * calibrated in STOP (STOP) and 3000 rpm at the nominal load in CLOSED_LOOP, steady (RUN);
 * and STOP and RUN again on the single-shunt table of the reference motor, behind the
 * drive's single-shunt front end (drive_shunt.h).
 * Every injection restores its state, injects at t0 and runs its window, period by period,
 * watching the true plant and the drive:
 *   detected   the fault word is not 0; detection time: the first tick with it, from t0;
 *   reaction   the time from t0 to the start of the first PWM period from which the inverter
 *              stays off to the end of the window (0 when it is off from t0 on);
 *   harmless   every sample with a true phase current above the table's i_trip made the
 *              fast step of that period switch off (the drive's own OC trip), no true current
 *              above the sensing full scale, the true speed at most 5 % above the motor's
 *              maximum (the overshoot the scenario targets accept at that speed), the
 *              state and sub-state codes in range and, for the faults that do not corrupt
 *              RAM, qfoc_drive_is_valid() at the end, and no PWM switching commanded outside
 *              RUN (and, for link garbage, the command kept).
 * Verdict: a fault passes when it is detected with its reaction within the item's FTTI of
 * its mechanism (specs/item-assumptions.toml) and within the library's own budget (1.5 x the
 * specified reaction time), or is harmless over its window; a disturbance within the
 * specified limits (and a fault-free run) passes only when it raises no fault and is
 * harmless.  A mechanism whose specified reaction exceeds the item's FTTI fails the campaign.
 *
 * usage: qfoc_faults [--mode full|check] [--flips N] [--table-step S] [--seed S] [--jobs J]
 *                    [--out DIR] [--assumptions TOML]
 *   full: N = 10000 random single-bit flips of the drive object, every bit of the table;
 *   check: N = 400 and one bit of each byte of the table (S = 8), every class still present.
 * Writes DIR/results.json (the FTTIs, the classes with their figures, every injection but
 * the flips, the flips by field and every flip that failed) and DIR/flips.csv (one row per
 * flip); tools/demo/faults_report.py makes results.md, index.html and the JUnit file.
 * Exit: 0 when every injection passes and every mechanism is within its FTTI, 1 otherwise,
 * 2 on an error (the assumptions file refused among them, the message naming the line).
 *
 * Requirements: REQ-FINJ-001 .. REQ-FINJ-006, REQ-FINJ-008 (specs/requirements/faults.md).
 */
#define _POSIX_C_SOURCE 200809L  /* clock_gettime, fork, mkdir */

#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "scenario.h"
#include "tables_registry.h"

#define RPM_OP 3000u          /* the operating point of the RUN state */
#define T_RUN_S 6.0           /* from the run command to the RUN state */
#define MARGIN 1.5            /* the library's budget: MARGIN x the specified reaction time */
#define FLIP_DELAY_MAX 800    /* a flip lands 0 .. 799 periods (100 ms) after RUN */
#define FLIP_WINDOW_S 0.3     /* observation after a drive-object flip */
/* Over-speed: above the motor's maximum speed by more than the overshoot the scenario targets
   accept for a step to it (specs/scenarios.toml, [speed_steps] max_overshoot_8000_pct). */
#define OVERSPEED 1.05
/* The fault.h bits (QFOC_FAULT_ALL) and the stuck-sample time of REQ-DRV-020 (drive.h). */
#define N_BITS 11
#define DRV_STUCK_MS_SIM 2u

/* ------------------------------------------------------------------ classes */

/* The mechanism whose reaction time gives a budget (budget_ms[]) and whose hazard gives the
   item's FTTI (ftti_ms[]). */
enum { M_NONE, M_FIRST, M_OC, M_VDC, M_OT, M_STALL, M_STALL_OL, M_PHASE, M_PHASE_START, M_OFFSET,
       M_LINK, M_PARAM_TABLE, M_PARAM_OBJ, M_SENSOR, M_TIMING, M_N };

/* The section of each mechanism in the item's assumptions (specs/item-assumptions.toml). */
static const char *const mech_key[M_N] = {
    NULL, NULL, "oc", "vdc", "ot", "stall", "stall_ol", "phase", "phase_start", "offset", "link",
    "param_table", "param_obj", "sensor", "timing"
};

static const char *const mech_name[M_N] = {
    "none (within limits)", "that of the first fault raised", "OC", "OV / UV", "OT", "STALL",
    "STALL (no handover)", "PHASE", "PHASE (ALIGN)", "OFFSET", "LINK", "PARAM (table re-check)",
    "PARAM (object check)", "OFFSET (running: stuck sample)", "TIMING"
};

/* Where an injection starts; S_RUN_SH, S_STOP_SH: S_RUN and S_STOP on the single-shunt
   inverter. */
enum { S_RUN, S_STOP, S_COLD, S_RUN_SH, S_STOP_SH, S_N };

/* What is injected. */
enum { K_NONE, K_SPEEDS, K_GARBAGE, K_SURGE, K_BUS, K_T_IPM, K_T_PCB, K_SEIZE, K_LOCK, K_STUCK,
       K_OPEN, K_OFFSET, K_GAIN, K_VDC_GAIN, K_LINK_STOP, K_LINK_BAD, K_SKIP_FAST, K_SKIP_TICK, K_FLIP_TABLE,
       K_FLIP_DRIVE, K_RING, K_SHUNT_OPEN, K_SHUNT_OFFSET };

typedef struct {
    const char *id;
    const char *title;   /* what is injected and how */
    int mech;            /* M_*: its FTTI; M_NONE: a disturbance within limits */
    uint16_t bit;        /* the fault.h bit the class provokes (0: none in particular) */
    bool ram;            /* deliberate RAM corruption: no invariant check at the end */
} cls_t;

enum { C_CONTROL, C_GARBAGE, C_OC, C_OV, C_UV, C_BUS_IN, C_OT_IPM, C_OT_PCB, C_TEMP_IN, C_STALL,
       C_LOCKED, C_NO_CURRENT, C_OPEN_RUN, C_OPEN_START, C_OFFSET, C_OFFSET_IN, C_LINK, C_STUCK,
       C_DRIFT, C_GAIN, C_VDC_GAIN, C_SKIP_FAST, C_SKIP_TICK, C_SH_CONTROL, C_SH_RING, C_SH_OPEN,
       C_SH_OFFSET, C_FLIP_TABLE, C_FLIP_DRIVE, C_N };

static const cls_t cls[C_N] = {
    { "control", "fault-free runs: the cold start to 3000 rpm, 2 s steady at 3000 rpm, speed "
      "changes 3000 -> 6000 -> 8000 -> 1500 rpm", M_NONE, 0u, false },
    { "link_garbage", "a frame of random bytes (half behind a valid sync byte and command "
      "identifier, never a valid checksum) on every tick between the master's command frames, "
      "2 s at 3000 rpm", M_NONE, 0u, false },
    { "oc_surge", "short-circuit current surge: the stator current set to +-32, 36, 39 A along "
      "each phase's axis (that phase carries it), and 60 A beyond the sensing full scale, at "
      "3000 rpm", M_OC, QFOC_FAULT_OC, false },
    { "ov_step", "DC bus stepped from 320 V to 460, 480 and 520 V (the sensing clips at 500 V), "
      "at 3000 rpm", M_VDC, QFOC_FAULT_OV, false },
    { "uv_step", "DC bus stepped from 320 V down to 210, 180 and 120 V in RUN, at 3000 rpm", M_VDC,
      QFOC_FAULT_UV, false },
    { "bus_step_within", "DC bus stepped from 320 V to 250, 280, 360 and 420 V (within the "
      "motor file's range), at 3000 rpm", M_NONE, 0u, false },
    { "ot_ipm", "IPM temperature stepped from 40 degC to 110.1, 115 and 150 degC (limit 110 degC), "
      "at 3000 rpm", M_OT, QFOC_FAULT_OT_IPM, false },
    { "ot_pcb", "PCB temperature stepped from 35 degC to 100.1, 105 and 130 degC (limit 100 degC), "
      "at 3000 rpm", M_OT, QFOC_FAULT_OT_PCB, false },
    { "temp_within", "IPM temperature stepped to 105 and 110 degC, PCB temperature to 95 and "
      "100 degC (at the limits), at 3000 rpm", M_NONE, 0u, false },
    { "stall_seizure", "compressor seizure at 3000 rpm: load torque stepped to 2, 3 and 5 times "
      "the nominal 4.5 N m (above what the current limit gives)", M_STALL, QFOC_FAULT_STALL,
      false },
    { "stall_locked_start", "locked rotor: the rotor held at standstill (at 0, 100 and 220 deg "
      "electrical) from the run command", M_STALL_OL, QFOC_FAULT_STALL, false },
    { "phase_no_current", "no current from the run command: both current ADCs stuck at mid-scale "
      "(2048); motor disconnected (three phases open); phases u and v open", M_PHASE_START,
      QFOC_FAULT_PHASE, false },
    { "open_phase_run", "one motor phase open (u, v, w) at 3000 rpm: its current and its sensor "
      "reading are 0, the current of the two others is confined to one axis (sim.h)", M_PHASE,
      QFOC_FAULT_PHASE, false },
    { "open_phase_start", "one motor phase open (u, v, w) from the run command (ALIGN)",
      M_PHASE_START, QFOC_FAULT_PHASE, false },
    { "offset_calib", "current-sensor offset at power-up, during the calibration: +-120, +-300, "
      "+-600 counts on iu and on iv (window 100 counts)", M_OFFSET, QFOC_FAULT_OFFSET, false },
    { "offset_calib_within", "current-sensor offset at power-up within the window: +-50 and "
      "+-90 counts on iu and on iv; then the cold start to 3000 rpm", M_NONE, 0u, false },
    { "link_loss", "the master stops at 3000 rpm; it sends only frames with a wrong checksum at "
      "3000 rpm; it stops 1 s after the run command (OPEN_LOOP)", M_LINK, QFOC_FAULT_LINK, false },
    { "adc_stuck", "one ADC channel (iu, iv, vdc) stuck at 0, 4095 and 2048, at 3000 rpm",
      M_FIRST, 0u, false },
    { "offset_drift", "current-sensor offset drift after the calibration: +-50, +-200, +-600 "
      "counts on iu and on iv, at 3000 rpm", M_FIRST, 0u, false },
    { "gain_error", "current-sensor gain error: 0.5, 0.8, 1.25 and 2.0 on iu and on iv, at "
      "3000 rpm", M_FIRST, 0u, false },
    { "vdc_gain", "DC-bus sensor gain error: the reading 0.75, 0.8, 1.25 and 1.35 times the "
      "true 320 V bus (inside the UV and OV thresholds), at 3000 rpm", M_FIRST, 0u, false },
    { "missed_fast_steps", "the fast step not called for 1, 2, 3, 8, 16, 40 and 80 periods "
      "while the inverter goes on with its last compare values and enable, at 3000 rpm",
      M_FIRST, 0u, false },
    { "stalled_tick", "no tick for 2, 10, 50, 200 and 1000 ms while the fast step runs (the "
      "master's frames of that time are lost), at 3000 rpm", M_FIRST, 0u, false },
    { "shunt_control", "single-shunt inverter, fault-free: 2 s steady at 3000 rpm, speed "
      "changes 3000 -> 6000 -> 8000 -> 1500 rpm", M_NONE, 0u, false },
    { "shunt_ringing", "single-shunt inverter: the DC-link current rings for 1.5, 2 and 3 times "
      "the table's settle time after each edge (samples taken in the ringing), at half and full "
      "step amplitude, at 3000 rpm", M_FIRST, 0u, false },
    { "shunt_open", "single-shunt inverter: the amplifier's sense connection open (both samples "
      "read zero current), at 3000 rpm and from the run command", M_FIRST, 0u, false },
    { "shunt_offset", "single-shunt inverter: an offset of +-50, +-200, +-600 counts on the "
      "shunt amplifier after the calibration, at 3000 rpm", M_FIRST, 0u, false },
    { "table_flip", "single-bit flip of the RAM copy of the parameter table at 3000 rpm, "
      "0 .. 99 ms after the RUN state (every phase of the 100 ms re-check)", M_PARAM_TABLE,
      QFOC_FAULT_PARAM, true },
    { "drive_flip", "single-bit flip of the drive object (qfoc_drive_fast_t and "
      "qfoc_drive_slow_t, byte and bit uniform, fixed seed) at 3000 rpm, 0 .. 99 ms after the "
      "RUN state", M_PARAM_OBJ, QFOC_FAULT_PARAM, true },
};

/* ------------------------------------------------------------------ fields */

typedef struct {
    const char *name;
    size_t off;
    size_t size;
} fld_t;

#define F(T, m) { #m, offsetof(T, m), sizeof(((T *)0)->m) }
#define F_PIP(T, b) F(T, b.kp), F(T, b.kp_shift), F(T, b.ki), F(T, b.ki_shift), F(T, b.out_min), \
    F(T, b.out_max)
#define F_PI(T, b) F_PIP(T, b.params), F(T, b.integ), F(T, b.limited)
#define F_LPF(T, b) F(T, b.alpha), F(T, b.state)
#define F_AB(T, b) F(T, b.alpha), F(T, b.beta)
#define D(m) F(qfoc_drive_t, m)
#define P(m) F(qfoc_param_table_t, m)

/* Every field of the drive's two halves (drive.h), in order. */
static const fld_t drive_fields[] = {
    D(f.flux.params.gain), D(f.flux.params.gain_shift), D(f.flux.params.r), D(f.flux.params.l),
    D(f.flux.params.kg), D(f.flux.psi_alpha), D(f.flux.psi_beta), F_AB(qfoc_drive_t, f.flux.i_prev),
    F_PI(qfoc_drive_t, f.pll.pi), F_LPF(qfoc_drive_t, f.pll.speed_lpf), D(f.pll.theta_acc),
    D(f.pll.speed), D(f.pll.err_clamp), D(f.pll.mag_min), D(f.pll.k_theta),
    F_PI(qfoc_drive_t, f.pi_id), F_PI(qfoc_drive_t, f.pi_iq),
    F_LPF(qfoc_drive_t, f.vdc_lpf), F_LPF(qfoc_drive_t, f.phase.abs_lpf[0]),
    F_LPF(qfoc_drive_t, f.phase.abs_lpf[1]), F_LPF(qfoc_drive_t, f.phase.abs_lpf[2]),
    D(f.mech.pole_pairs), D(f.mech.turn), D(f.mech.theta_e), D(f.mech.recip),
    F_AB(qfoc_drive_t, f.u_last), F_AB(qfoc_drive_t, f.u_applied), D(f.theta_ol), D(f.i_dq.d),
    D(f.i_dq.q), D(f.vdc), D(f.adc_iu), D(f.adc_iv), D(f.theta_est), D(f.theta_m), D(f.speed),
    D(f.speed_f), D(f.psi_mag), D(f.trip_count), D(f.clamp_count), D(f.clear_ack),
    D(f.trip), D(f.active), D(f.hs), D(f.phase_k), D(f.i_abc.u), D(f.i_abc.v), D(f.i_abc.w),
    D(f.out.cmp), D(f.out.enable), D(f.same_u), D(f.same_v), D(f.n_fast),
    D(s.sm.state), D(s.sm.sub), D(s.sm.faults), D(s.sm.first_fault), D(s.sm.t_state),
    D(s.sm.t_sub), D(s.sm.retry), F_PI(qfoc_drive_t, s.pi_speed),
    F_PI(qfoc_drive_t, s.fw.pi), F_LPF(qfoc_drive_t, s.fw.util_lpf), D(s.fw.level), D(s.fw.id_ref), D(s.tc.params.gain), D(s.tc.params.amp_max),
    D(s.tc.params.speed_min), D(s.tc.params.speed_max), D(s.tc.params.pole_pairs), D(s.tc.a),
    D(s.tc.b), D(s.link.cfg.id_cmd), D(s.link.cfg.id_status), D(s.link.cfg.rpm_max),
    D(s.link.cfg.timeout_ms), D(s.link.cfg.can_id_a), D(s.link.cfg.can_id_b),
    D(s.link.cmd.power_on), D(s.link.cmd.fault_clear), D(s.link.cmd.target_rpm),
    D(s.link.silent_ms), D(s.link.cfg_ok), D(s.link.seen), D(s.link.lost), D(s.link.can_b),
    D(s.link.n_ok), D(s.link.n_len), D(s.link.n_sync), D(s.link.n_id), D(s.link.n_checksum),
    D(s.link.n_reserved), D(s.link.n_range), D(s.db_ov.count), D(s.db_uv.count),
    D(s.db_ot_ipm.count), D(s.db_ot_pcb.count), D(s.db_stall.count), D(s.db_flux.count), D(s.db_phase.count), D(s.db_align.count),
    D(s.db_ho.count), D(s.off_sum_u), D(s.off_sum_v), D(s.off_n), D(s.offset_u), D(s.offset_v),
    D(s.speed_target), D(s.speed_ref), D(s.ol_speed), D(s.id_ref), D(s.iq_ref), D(s.iq_lim), D(s.lead),
    D(s.util), D(s.trip_seen), D(s.clamp_seen), D(s.clear_seq), D(s.ms100), D(s.fast_seen), D(s.table_ok),
    D(s.ref_guard), D(s.scan_crc), D(s.calib_done), D(s.hs), D(s.derated), D(s.run_ms), D(s.status.state),
    D(s.status.substate), D(s.status.faults), D(s.status.speed_rpm), D(s.status.vdc_dv),
    D(s.status.current_ca), D(s.status.temp_dc), D(s.cmd.power_on), D(s.cmd.fault_clear),
    D(s.cmd.target_rpm), D(s.sm_cfg.precharge_ms), D(s.sm_cfg.align_ms), D(s.sm_cfg.ol_timeout_ms),
    D(s.sm_cfg.cl_hold_ms), D(s.sm_cfg.clear_ms), D(s.sm_cfg.retries), D(s.sm_in.faults),
    D(s.sm_in.bus_ok),
    D(s.sm_in.calib_done), D(s.sm_in.run_request), D(s.sm_in.link_lost), D(s.sm_in.fault_clear),
    D(s.sm_in.table_ok), D(s.sm_in.converged), D(s.sm_in.stop_reached), D(s.out.tx),
    D(s.out.tx_len), D(s.out.can.id), D(s.out.can.dlc), D(s.out.can.data), D(s.out.can_send),
    D(s.out.pwm_off),
};

/* Every field of the parameter table (params.h), in order. */
static const fld_t table_fields[] = {
    P(magic), P(version), P(f_pwm_hz), P(v_base_mv), P(i_base_ma), P(f_base_mhz), P(svpwm.period),
    P(svpwm.dt_comp), P(svpwm.i_deadband), P(svpwm.vdc_min),
    F_PIP(qfoc_param_table_t, pi_id), F_PIP(qfoc_param_table_t, pi_iq),
    F_PIP(qfoc_param_table_t, pi_speed), F_PIP(qfoc_param_table_t, pi_fw), P(flux.gain),
    P(flux.gain_shift), P(flux.r), P(flux.l), P(flux.kg), F_PIP(qfoc_param_table_t, pll.pi),
    P(pll.err_clamp), P(pll.mag_min), P(pll.k_theta), P(pll.speed_alpha), P(alpha_vdc), P(ld),
    P(lq), P(psi_f), P(i_max), P(i_trip), P(speed_max), P(vdc_uv), P(vdc_ov), P(v_max),
    P(drive.pole_pairs), P(drive.k_rpm), P(drive.k_speed_rpm), P(drive.rpm_min), P(drive.rpm_max),
    P(drive.speed_ramp), P(drive.precharge_ms), P(drive.offset_shift), P(drive.offset_window),
    P(drive.i_align), P(drive.align_ms), P(drive.i_start), P(drive.of_accel), P(drive.of_speed),
    P(drive.ho_angle), P(drive.ho_dwell_ms), P(drive.ol_timeout_ms), P(drive.cl_hold_ms),
    P(drive.t_ipm_max), P(drive.t_pcb_max), P(drive.vdc_ms), P(drive.temp_ms), P(drive.stall_err),
    P(drive.flux_tol), P(drive.stall_ms), P(drive.phase_alpha), P(drive.phase_i_min),
    P(drive.phase_ratio), P(drive.phase_ms), P(drive.link_timeout_ms), P(drive.clear_ms),
    P(drive.fw_level), P(drive.fw_alpha), P(drive.tc_gain), P(drive.tc_amp_max),
    P(drive.tc_speed_min), P(drive.tc_speed_max), P(drive.para_speed), P(drive.ld_hs),
    P(drive.lq_hs), P(drive.lin_id_cmd), P(drive.lin_id_status), P(drive.can_id_a),
    P(drive.can_id_b), P(crc),
};

#define N_DRIVE_FIELDS ((int)(sizeof drive_fields / sizeof drive_fields[0]))
#define N_TABLE_FIELDS ((int)(sizeof table_fields / sizeof table_fields[0]))

/* The field holding byte off: its index, or -1 for padding (no field). */
static int field_at(const fld_t *f, int n, size_t off)
{
    int k;
    for (k = 0; k < n; k++) {
        if (off >= f[k].off && off < f[k].off + f[k].size) {
            return k;
        }
    }
    return -1;
}

/* The drive's two halves, the flip domain: [f, end of s). */
#define DRV_LO offsetof(qfoc_drive_t, f)
#define DRV_HI (offsetof(qfoc_drive_t, s) + sizeof(qfoc_drive_slow_t))

/* ------------------------------------------------------------------ injections */

typedef struct {
    int cls;
    int start;           /* S_* */
    int kind;            /* K_* */
    int ch;              /* channel, phase mask, or bit number of a flip */
    double a;            /* magnitude */
    long delay;          /* periods between the start state and t0 */
    long window;         /* periods observed from t0 */
    char what[64];
} inj_t;

typedef struct {
    uint16_t faults;     /* every fault bit seen in the window */
    uint16_t first;      /* the fault word of the first tick with one */
    double t_det;        /* s from t0 to the first tick with a fault (NAN: none) */
    double t_react;      /* s from t0 until the inverter is off for good (NAN: never) */
    double i_peak;       /* largest true |phase current| at the samples, A */
    double rpm_peak;     /* largest true |speed|, rpm */
    bool oc_missed;      /* a sample above i_trip and the inverter left switching */
    bool over_fs;        /* a true current above the sensing full scale */
    bool state_bad;      /* a state or sub-state code out of range, or an invalid object */
    bool pwm_off_run;    /* switching commanded outside RUN */
    bool cmd_changed;    /* the link's command changed (link garbage) */
    long rejected;       /* frames the link rejected in the window */
    double ftti;         /* s, the item's FTTI the verdict used (NAN: none) */
    double budget;       /* s, the library's budget the verdict used (NAN: none) */
    int mech;            /* M_*: the mechanism whose FTTI and budget the verdict used */
    bool harmless;
    bool in_time;
    bool pass;
} res_t;

static const scn_table_t *tabr;        /* the reference table of the registry */
static const scn_table_t *tabs;        /* its single-shunt table (sensing.mode = shunt) */
static qfoc_drive_shunt_t shunt_run;   /* the single-shunt front end of snap[S_RUN_SH] */
static qfoc_drive_shunt_t shunt_stop;  /* ... and of snap[S_STOP_SH] */
static qfoc_param_table_t ram_table;   /* the RAM copy the drive runs on */
static qfoc_param_table_t ram_intact;
static sim_motor_t motor;
static dsim_t snap[S_N];
static double ftti_ms[M_N];    /* the item's FTTI (specs/item-assumptions.toml) */
static char ftti_id[M_N][16];   /* its assumption */
static const char *assumptions_file = "specs/item-assumptions.toml";
static double budget_ms[M_N];  /* the library's budget: MARGIN x the specified reaction */
static double spec_ms[M_N];
static char spec_text[M_N][200];
static double i_trip_a;

/* splitmix64 */
static uint64_t mix(uint64_t *s)
{
    uint64_t z = (*s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

/* ------------------------------------------------------------------ FTTIs */

/* The specified reaction times of specs/safety-manual.md section 2.2 from the table's values
   (drive.h: every tick-decided fault reacts within its debounce + 1 ms), and the FTTIs. */
static void fttis(const qfoc_param_table_t *p)
{
    const qfoc_drive_cfg_t *c = &p->drive;
    const double t = 1000.0 / (double)p->f_pwm_hz;
    const double tau_vdc = t * 32768.0 / (double)p->alpha_vdc;
    const double tau_ph = t * 32768.0 / (double)c->phase_alpha;
    const double rpm_of = (double)c->of_speed * (double)c->k_speed_rpm / 32768.0;
    const double ramp = (double)c->speed_ramp * (double)c->k_speed_rpm / 32768.0;
    int k;
    spec_ms[M_OC] = t;
    snprintf(spec_text[M_OC], sizeof spec_text[0], "PWM off in the fast step of the sample: "
             "switches off at the next period start, T = %.3f ms", t);
    spec_ms[M_VDC] = (double)c->vdc_ms + 1.0 + tau_vdc * log(10.0);
    snprintf(spec_text[M_VDC], sizeof spec_text[0], "vdc_ms %u + 1 ms tick + the bus filter's "
             "lag to 90 %% of a step (tau %.2f ms x ln 10)", (unsigned)c->vdc_ms, tau_vdc);
    spec_ms[M_OT] = (double)c->temp_ms + 1.0;
    snprintf(spec_text[M_OT], sizeof spec_text[0], "temp_ms %u + 1 ms tick", (unsigned)c->temp_ms);
    spec_ms[M_STALL] = (double)c->stall_ms + 1.0;
    snprintf(spec_text[M_STALL], sizeof spec_text[0], "stall_ms %u + 1 ms tick",
             (unsigned)c->stall_ms);
    /* each start: CATCH on the standing rotor (the filter's fall from full scale, at most
       80 ticks, and the dwell), ALIGN and the open loop; 1 + ho_retries starts (REQ-SM-011) */
    spec_ms[M_STALL_OL] = (1.0 + (double)c->ho_retries) *
                          (80.0 + (double)c->ho_dwell_ms + (double)c->align_ms +
                           (double)c->ol_timeout_ms) + 1.0;
    snprintf(spec_text[M_STALL_OL], sizeof spec_text[0], "(1 + ho_retries %u) x (CATCH 80 + "
             "ho_dwell_ms %u + align_ms %u + ol_timeout_ms %u) + 1 ms tick, from the run command",
             (unsigned)c->ho_retries, (unsigned)c->ho_dwell_ms, (unsigned)c->align_ms,
             (unsigned)c->ol_timeout_ms);
    spec_ms[M_PHASE] = (double)c->phase_ms + 1.0 + tau_ph * log(32768.0 / (double)c->phase_ratio);
    snprintf(spec_text[M_PHASE], sizeof spec_text[0], "phase_ms %u + 1 ms tick + the monitor's "
             "decay to phase_ratio (tau %.1f ms x ln(1 / %.2f))", (unsigned)c->phase_ms, tau_ph,
             (double)c->phase_ratio / 32768.0);
    spec_ms[M_PHASE_START] = (double)(c->align_ms / 2u) + (double)c->phase_ms + 1.0;
    snprintf(spec_text[M_PHASE_START], sizeof spec_text[0], "align_ms / 2 %u + phase_ms %u + 1 ms "
             "tick, from the run command (REQ-DRV-018)", (unsigned)(c->align_ms / 2u),
             (unsigned)c->phase_ms);
    spec_ms[M_OFFSET] = (double)c->precharge_ms + (double)(1u << c->offset_shift) + 1.0;
    snprintf(spec_text[M_OFFSET], sizeof spec_text[0], "precharge_ms %u + 2^%u calibration ticks "
             "+ 1 ms, from power-up (PWM off throughout)", (unsigned)c->precharge_ms,
             (unsigned)c->offset_shift);
    spec_ms[M_LINK] = (double)c->link_timeout_ms + ((double)c->rpm_max - rpm_of) / ramp + 1.0;
    snprintf(spec_text[M_LINK], sizeof spec_text[0], "link_timeout_ms %u + the ramp from rpm_max "
             "%u to %.0f rpm at %.3f rpm/ms + 1 ms", (unsigned)c->link_timeout_ms,
             (unsigned)c->rpm_max, rpm_of, ramp);
    spec_ms[M_PARAM_TABLE] = 100.0 + (double)QFOC_PARAMS_SCAN_STEPS + t;
    snprintf(spec_text[M_PARAM_TABLE], sizeof spec_text[0], "100 ms re-check + its %u steps "
             "(REQ-DRV-010: within 105 ms) + 1 period to PWM off", (unsigned)QFOC_PARAMS_SCAN_STEPS);
    spec_ms[M_PARAM_OBJ] = 4.0 + t;
    snprintf(spec_text[M_PARAM_OBJ], sizeof spec_text[0], "the object check, a quarter a tick "
             "(REQ-DRV-019: within 4 ms) + 1 period to PWM off");
    spec_ms[M_SENSOR] = (double)DRV_STUCK_MS_SIM + 1.0;
    snprintf(spec_text[M_SENSOR], sizeof spec_text[0], "in CLOSED_LOOP: a current code unchanged "
             "for %u ms while the other moves + 1 ms tick (REQ-DRV-020)", (unsigned)DRV_STUCK_MS_SIM);
    spec_ms[M_TIMING] = 1.0 + 4.0 * t;
    snprintf(spec_text[M_TIMING], sizeof spec_text[0], "in RUN: the tick that ends the first tick "
             "interval short of 3 fast steps, within 1 ms + 3 periods of the first missed one, "
             "+ 1 period for the port's PWM off (REQ-DRV-021)");
    for (k = 0; k < M_N; k++) {
        budget_ms[k] = (k == M_NONE || k == M_FIRST) ? NAN : MARGIN * spec_ms[k];
    }
    spec_ms[M_NONE] = spec_ms[M_FIRST] = NAN;
}

/* One "key = value" of the assumptions file: a number, or a string on one line. */
static char *trim(char *s)
{
    char *e;
    while (*s == ' ' || *s == '\t') {
        s++;
    }
    e = s + strlen(s);
    while (e > s && (e[-1] == ' ' || e[-1] == '\t' || e[-1] == '\n' || e[-1] == '\r')) {
        *--e = '\0';
    }
    return s;
}

/* A table value an assumption's arithmetic uses must be the table's (within 0.5 %). */
static int table_value_ok(const char *path, int lineno, const char *key, double v, double table)
{
    if (fabs(v - table) > 0.005 * fabs(table)) {
        fprintf(stderr, "%s:%d: %s = %g is not the table's %g: derive the FTTI again\n", path,
                lineno, key, v, table);
        return -1;
    }
    return 0;
}

/* The item's FTTIs: each mechanism's section of the assumptions file (its id and ftti_ms;
   hazard, assumption and derivation are for the report).  Refused (-1, the message names the
   line): a section that is no mechanism's, a mechanism without an FTTI, a value that is not
   a positive number, a table value that is not the table's. */
static int load_fttis(const char *path, const qfoc_param_table_t *p)
{
    const double i_trip = (double)p->i_trip / 32768.0 * (double)p->i_base_ma * 1e-3;
    const double vdc_ov = (double)p->vdc_ov / 32768.0 * (double)p->v_base_mv * 1e-3;
    FILE *f = fopen(path, "r");
    char line[1024];
    int m = -1;
    int lineno = 0;
    int k;
    if (f == NULL) {
        fprintf(stderr, "%s: cannot open (the item's FTTIs)\n", path);
        return -1;
    }
    for (k = 0; k < M_N; k++) {
        ftti_ms[k] = NAN;
        ftti_id[k][0] = '\0';
    }
    while (fgets(line, (int)sizeof line, f) != NULL) {
        char *s = trim(line);
        char *eq;
        char *key;
        char *val;
        char *end;
        double v;
        lineno++;
        if (*s == '#' || *s == '\0') {
            continue;
        }
        if (*s == '[') {
            char *close = strchr(s, ']');
            m = -1;
            if (close != NULL) {
                *close = '\0';
                for (k = 0; k < M_N; k++) {
                    m = (mech_key[k] != NULL && strcmp(mech_key[k], s + 1) == 0) ? k : m;
                }
            }
            if (m < 0) {
                fprintf(stderr, "%s:%d: [%s] is no mechanism of the campaign\n", path, lineno, s + 1);
                fclose(f);
                return -1;
            }
            continue;
        }
        eq = strchr(s, '=');
        if (eq == NULL || m < 0) {
            fprintf(stderr, "%s:%d: expected key = value in a mechanism's section\n", path, lineno);
            fclose(f);
            return -1;
        }
        *eq = '\0';
        key = trim(s);
        val = trim(eq + 1);
        if (*val == '"') {
            if (strcmp(key, "id") == 0) {
                snprintf(ftti_id[m], sizeof ftti_id[m], "%.*s", (int)strcspn(val + 1, "\""), val + 1);
            }
            continue;
        }
        v = strtod(val, &end);
        if (end == val || *trim(end) != '\0' || !(v > 0.0)) {
            fprintf(stderr, "%s:%d: %s = %s: expected a positive number\n", path, lineno, key, val);
            fclose(f);
            return -1;
        }
        if (strcmp(key, "ftti_ms") == 0) {
            ftti_ms[m] = v;
        } else if ((strcmp(key, "table_i_trip_a") == 0 &&
                    table_value_ok(path, lineno, key, v, i_trip) != 0) ||
                   (strcmp(key, "table_vdc_ov_v") == 0 &&
                    table_value_ok(path, lineno, key, v, vdc_ov) != 0) ||
                   (strcmp(key, "table_t_ipm_max_degc") == 0 &&
                    table_value_ok(path, lineno, key, v, (double)p->drive.t_ipm_max / 10.0) != 0)) {
            fclose(f);
            return -1;
        }
    }
    fclose(f);
    for (k = 0; k < M_N; k++) {
        if (mech_key[k] != NULL && (isnan(ftti_ms[k]) || ftti_id[k][0] == '\0')) {
            fprintf(stderr, "%s: [%s] (%s) needs an id and an ftti_ms\n", path, mech_key[k],
                    mech_name[k]);
            return -1;
        }
    }
    return 0;
}

/* The mechanism of a fault word (its lowest bit), for a class without a mechanism of its
   own; OFFSET raised while running is the running sensor monitor's (REQ-DRV-020); M_NONE for
   no fault. */
static int mech_of_word(uint16_t w, bool running)
{
    static const int mech_of_bit[N_BITS] = { M_OC, M_VDC, M_VDC, M_OT, M_OT, M_STALL, M_PHASE,
                                             M_OFFSET, M_LINK, M_PARAM_OBJ, M_TIMING };
    int b;
    for (b = 0; b < N_BITS; b++) {
        if ((w & (1u << b)) != 0u) {
            return (running && mech_of_bit[b] == M_OFFSET) ? M_SENSOR : mech_of_bit[b];
        }
    }
    return M_NONE;
}

/* ------------------------------------------------------------------ states */

static double nominal_nm(void)
{
    return motor.nominal_torque_nm;
}

/* The STOP and RUN states on the single-shunt inverter: the same plant and operating point,
   the drive on the ROM single-shunt table behind its front end (latency 2, as in
   drive_sim.h), the plant's single-shunt sensing as the scenarios rig it
   (scn_shunt_plant). */
static int make_shunt_state(const sim_cfg_t *base)
{
    const qfoc_param_table_t *p = tabs->table;
    sim_cfg_t cfg = *base;
    dsim_t *ds = &snap[S_RUN_SH];
    long k;
    scn_shunt_plant(&cfg, p, &motor);
    if (dsim_init(ds, &cfg, p) != QFOC_PARAMS_OK ||
        qfoc_drive_shunt_init(&shunt_run, &ds->drv, 2u) != QFOC_SHUNT_OK) {
        fprintf(stderr, "qfoc_faults: %s: the single-shunt drive is refused\n", tabs->name);
        return -1;
    }
    ds->shunt = &shunt_run;
    ds->target_rpm = RPM_OP;
    ds->t_pcb = 350;
    for (k = 0; k < 8000 && ds->drv.s.sm.state != QFOC_STATE_STOP; k++) {
        dsim_period(ds);
    }
    snap[S_STOP_SH] = *ds;
    shunt_stop = shunt_run;
    ds->power_on = true;
    dsim_run(ds, T_RUN_S);
    if (snap[S_STOP_SH].drv.s.sm.state != QFOC_STATE_STOP ||
        ds->drv.s.sm.sub != QFOC_SUB_CLOSED_LOOP || ds->drv.s.sm.faults != 0u ||
        fabs(dsim_rpm(ds) - (double)RPM_OP) > 0.02 * RPM_OP) {
        fprintf(stderr, "qfoc_faults: %s: the operating point was not reached\n", tabs->name);
        return -1;
    }
    /* shunt_run is now the front end of this state: run() starts from a copy of it */
    return 0;
}

static int make_states(void)
{
    sim_cfg_t cfg;
    dsim_t *ds = &snap[S_COLD];
    long k;
    memset(&cfg, 0, sizeof cfg);
    cfg.motor = motor;
    cfg.vdc_v = motor.vdc_nominal_v;
    cfg.dead_time_s = motor.dead_time_s;
    cfg.substeps = 20;
    cfg.noise_i_rms_a = 0.05;
    cfg.seed = 7u;
    cfg.load.t_mean = nominal_nm();
    cfg.load.knee_rpm = 30.0;
    if (qfoc_params_load(&ram_table, tabr->table) != QFOC_PARAMS_OK) {
        return -1;
    }
    ram_intact = ram_table;
    /* the master and the plant on the ROM table, the drive on the RAM copy */
    if (dsim_init(ds, &cfg, tabr->table) != QFOC_PARAMS_OK ||
        qfoc_drive_init(&ds->drv, &ram_table) != QFOC_PARAMS_OK) {
        return -1;
    }
    ds->target_rpm = RPM_OP;
    ds->t_pcb = 350;
    snap[S_STOP] = *ds;
    for (k = 0; k < 8000 && snap[S_STOP].drv.s.sm.state != QFOC_STATE_STOP; k++) {
        dsim_period(&snap[S_STOP]);
    }
    snap[S_RUN] = snap[S_STOP];
    snap[S_RUN].power_on = true;
    dsim_run(&snap[S_RUN], T_RUN_S);
    if (snap[S_STOP].drv.s.sm.state != QFOC_STATE_STOP ||
        snap[S_RUN].drv.s.sm.sub != QFOC_SUB_CLOSED_LOOP || snap[S_RUN].drv.s.sm.faults != 0u ||
        fabs(dsim_rpm(&snap[S_RUN]) - (double)RPM_OP) > 0.02 * RPM_OP) {
        fprintf(stderr, "qfoc_faults: the operating points were not reached\n");
        return -1;
    }
    return make_shunt_state(&cfg);
}

/* ------------------------------------------------------------------ model checks */

typedef struct {
    char what[96];
    double value;
    bool ok;
} chk_t;

#define N_CHECKS 5
static chk_t checks[N_CHECKS];

/* Largest |current| of phase j (0 u, 1 v, 2 w) over n periods of the RUN state with the
   phases of mask open, the drive in the loop. */
static double open_current(unsigned mask, int j, long n)
{
    dsim_t *ds = malloc(sizeof *ds);
    double pk = 0.0;
    long k;
    if (ds == NULL) {
        return INFINITY;
    }
    *ds = snap[S_RUN];
    ds->plant.inj.open = mask;
    for (k = 0; k < n; k++) {
        double ab[2];
        double i[3];
        dsim_period(ds);
        sim_i_ab(&ds->plant, ab);
        i[0] = ab[0];
        i[1] = -0.5 * ab[0] + 0.5 * sqrt(3.0) * ab[1];
        i[2] = -i[0] - i[1];
        pk = fmax(pk, (j < 3) ? fabs(i[j]) : hypot(ab[0], ab[1]));
    }
    free(ds);
    return pk;
}

/* The ADC code of channel ch of a noise-free copy of the RUN state with one sensing fault. */
static int sensed(int ch, double gain, int stuck)
{
    sim_t p = snap[S_RUN].plant;
    sim_adc_t a;
    p.cfg.noise_i_rms_a = 0.0;
    p.inj.sense = true;
    p.inj.gain[ch < 2 ? ch : 0] = gain;
    p.inj.stuck[ch] = stuck;
    sim_sample(&p, &a);
    return (ch == 0) ? a.iu : ((ch == 1) ? a.iv : a.vdc);
}

/* The fault models of sim.h do what they are meant to. */
static int check_models(void)
{
    const long n = lround(0.02 / snap[S_RUN].plant.bases.t_s);
    const int c1 = sensed(0, 1.0, -1);
    const int c2 = sensed(0, 2.0, -1);
    int k;
    int bad = 0;
    checks[0].value = open_current(1u, 0, n);
    snprintf(checks[0].what, sizeof checks[0].what, "phase u open at 3000 rpm: max |i_u| over 20 ms, A");
    checks[0].ok = checks[0].value < 1e-9;
    checks[1].value = open_current(4u, 2, n);
    snprintf(checks[1].what, sizeof checks[1].what, "phase w open at 3000 rpm: max |i_w| over 20 ms, A");
    checks[1].ok = checks[1].value < 1e-9;
    checks[2].value = open_current(3u, 3, n);
    snprintf(checks[2].what, sizeof checks[2].what, "phases u and v open: max |i| over 20 ms, A");
    checks[2].ok = checks[2].value < 1e-9;
    checks[3].value = (double)sensed(2, 1.0, 4095);
    snprintf(checks[3].what, sizeof checks[3].what, "vdc stuck at 4095: the code sampled");
    checks[3].ok = checks[3].value == 4095.0;
    checks[4].value = (double)(c2 - 2048) / (double)(c1 - 2048);
    snprintf(checks[4].what, sizeof checks[4].what, "iu gain 2: sensed / exact current (codes from "
             "mid-scale, %d and %d)", c2 - 2048, c1 - 2048);
    /* each code is rounded: round(2 x) - 2 round(x) is -1, 0 or 1 (compared in integers, not
       through the quotient's floating-point rounding) */
    checks[4].ok = abs((c2 - 2048) - (2 * (c1 - 2048))) <= 1;
    for (k = 0; k < N_CHECKS; k++) {
        if (!checks[k].ok) {
            fprintf(stderr, "qfoc_faults: model check failed: %s = %g\n", checks[k].what,
                    checks[k].value);
            bad = 1;
        }
    }
    return bad ? -1 : 0;
}

/* ------------------------------------------------------------------ one injection */

static void flip(void *base, int bit)
{
    uint8_t *b = (uint8_t *)base;
    b[bit / 8] = (uint8_t)(b[bit / 8] ^ (1u << (bit % 8)));
}

/* The injection at t0. */
static void inject(dsim_t *ds, const inj_t *in)
{
    sim_inj_t *f = &ds->plant.inj;
    switch (in->kind) {
    case K_SURGE: {
        const double phi = (double)in->ch * 2.0 * SIM_PI / 3.0;
        const double i_ab[2] = { in->a * cos(phi), in->a * sin(phi) };
        sim_set_current_ab(&ds->plant, i_ab);
        break;
    }
    case K_BUS: ds->plant.cfg.vdc_v = in->a; break;
    case K_T_IPM: ds->t_ipm = (int16_t)lround(in->a * 10.0); break;
    case K_T_PCB: ds->t_pcb = (int16_t)lround(in->a * 10.0); break;
    case K_SEIZE: ds->plant.cfg.load.t_mean = in->a * nominal_nm(); break;
    case K_LOCK:
        ds->plant.cfg.speed_locked = true;
        ds->plant.cfg.locked_speed_e = 0.0;
        sim_set_state(&ds->plant, in->a * SIM_PI / 180.0, 0.0, 0.0, 0.0);
        break;
    case K_STUCK:
        f->sense = true;
        f->stuck[0] = ((in->ch & 1) != 0) ? (int)in->a : -1;
        f->stuck[1] = ((in->ch & 2) != 0) ? (int)in->a : -1;
        f->stuck[2] = ((in->ch & 4) != 0) ? (int)in->a : -1;
        break;
    case K_OPEN: f->open = (unsigned)in->ch; break;
    case K_OFFSET: f->sense = true; f->offset[in->ch] = in->a; break;
    case K_GAIN: f->sense = true; f->gain[in->ch] = in->a; break;
    case K_VDC_GAIN: f->sense = true; f->vdc_gain = in->a; break;
    case K_LINK_STOP: ds->link_alive = false; break;
    case K_GARBAGE: ds->garbage = (uint32_t)in->a; break;
    case K_SKIP_FAST: ds->skip_fast = (int)in->a; break;
    case K_SKIP_TICK: ds->skip_tick = (int)in->a; break;
    case K_FLIP_TABLE: flip(&ram_table, in->ch); break;
    case K_FLIP_DRIVE: flip(&ds->drv, in->ch); break;
    case K_RING:
        /* ringing over a times the table's settle time, at half (ch 0) or full (ch 1) step */
        ds->plant.cfg.shunt.t_ring_s = in->a * (double)tabs->table->drive.shunt_settle /
                                       motor.f_timer_hz;
        ds->plant.cfg.shunt.ring_gain = (in->ch == 0) ? 0.5 : 1.0;
        break;
    case K_SHUNT_OPEN: f->shunt_open = true; break;
    case K_SHUNT_OFFSET: f->shunt_offset = in->a; break;
    default: break;
    }
}

/* What goes on through the window, before period k of it. */
static void keep(dsim_t *ds, const inj_t *in, long k)
{
    const long per_s = (long)lround(1.0 / ds->plant.bases.t_s);
    if (in->kind == K_LINK_BAD) {
        ds->corrupt_next = true;
    } else if (in->kind == K_SPEEDS) {
        ds->target_rpm = (k < 2 * per_s) ? 6000u : ((k < 9 * per_s / 2) ? 8000u : 1500u);
    }
}

static double phase_peak(const sim_t *p)
{
    double ab[2];
    double iv;
    sim_i_ab(p, ab);
    iv = -0.5 * ab[0] + 0.5 * sqrt(3.0) * ab[1];
    return fmax(fabs(ab[0]), fmax(fabs(iv), fabs(ab[0] + iv)));
}

static void verdict(const inj_t *in, res_t *r)
{
    const cls_t *c = &cls[in->cls];
    const int m = (c->mech == M_FIRST) ? mech_of_word(r->first, in->start == S_RUN) : c->mech;
    r->harmless = !r->oc_missed && !r->over_fs && r->rpm_peak <= OVERSPEED * motor.max_speed_rpm &&
                  !r->state_bad && !r->pwm_off_run && !r->cmd_changed;
    r->mech = m;
    r->ftti = ftti_ms[m] * 1e-3;
    r->budget = budget_ms[m] * 1e-3;
    /* in time: within the item's FTTI and within the library's own budget */
    r->in_time = r->faults != 0u && !isnan(r->t_react) && !isnan(r->ftti) &&
                 r->t_react <= r->ftti + 1e-9 && r->t_react <= r->budget + 1e-9;
    r->pass = (c->mech == M_NONE) ? (r->harmless && r->faults == 0u) : (r->in_time || r->harmless);
}

/* Frames the link has rejected, for any cause. */
static long rejected(const qfoc_link_t *l)
{
    return (long)l->n_len + (long)l->n_sync + (long)l->n_id + (long)l->n_checksum +
           (long)l->n_reserved + (long)l->n_range;
}

static void run(const inj_t *in, res_t *r)
{
    dsim_t *ds = malloc(sizeof *ds);
    qfoc_drive_shunt_t sh;   /* the front end of an injection on the single-shunt inverter */
    const double t = snap[S_RUN].plant.bases.t_s;
    long off_from = 0;   /* the inverter is off from this period of the window on */
    long k;
    memset(r, 0, sizeof *r);
    r->t_det = r->t_react = NAN;
    if (ds == NULL) {
        r->state_bad = true;
        return;
    }
    *ds = snap[in->start];
    if (in->start == S_RUN_SH || in->start == S_STOP_SH) {
        sh = (in->start == S_RUN_SH) ? shunt_run : shunt_stop;
        ds->shunt = &sh;
    }
    ram_table = ram_intact;
    ds->power_on = true;
    r->rejected = -rejected(&ds->drv.s.link);
    for (k = -in->delay; k < in->window; k++) {
        const long ms = ds->ms;
        double i_pk;
        if (k < 0) {
            dsim_period(ds);
            continue;
        }
        if (k == 0) {
            inject(ds, in);
            off_from = ds->plant.en_active ? 1 : 0;
        }
        keep(ds, in, k);
        i_pk = phase_peak(&ds->plant);
        dsim_period(ds);
        r->i_peak = fmax(r->i_peak, i_pk);
        r->oc_missed = r->oc_missed || (i_pk > i_trip_a && ds->plant.en_pending);
        r->over_fs = r->over_fs || i_pk > motor.i_full_scale_a;
        r->rpm_peak = fmax(r->rpm_peak, fabs(dsim_rpm(ds)));
        r->pwm_off_run = r->pwm_off_run ||
                         (ds->fast_ran && ds->pwm.enable && ds->fast_state != QFOC_STATE_RUN);
        if (ds->plant.en_pending) {
            off_from = k + 2;   /* switching in period k + 1 */
        }
        if (ds->ms != ms) {
            const qfoc_sm_t *sm = &ds->drv.s.sm;
            r->faults = (uint16_t)(r->faults | sm->faults);
            if (isnan(r->t_det) && sm->faults != 0u) {
                r->t_det = (double)(k + 1) * t;
                r->first = sm->faults;
            }
            r->state_bad = r->state_bad || sm->state > QFOC_STATE_ERROR || sm->sub > QFOC_SUB_CATCH;
            r->cmd_changed = r->cmd_changed ||
                             (in->kind == K_GARBAGE && (ds->drv.s.link.cmd.target_rpm != RPM_OP ||
                                                        !ds->drv.s.link.cmd.power_on));
        }
        /* a flip detected: the drive stays in ERROR with the PWM off (no clear is sent) */
        if (cls[in->cls].ram && !isnan(r->t_det) && ds->drv.s.sm.state == QFOC_STATE_ERROR &&
            !ds->plant.en_pending && k > off_from + 8) {
            break;
        }
    }
    r->t_react = ds->plant.en_pending ? NAN : (double)off_from * t;
    r->rejected += rejected(&ds->drv.s.link);
    if (!cls[in->cls].ram && !qfoc_drive_is_valid(&ds->drv)) {
        r->state_bad = true;
    }
    verdict(in, r);
    free(ds);
}

/* ------------------------------------------------------------------ the list */

typedef struct {
    inj_t *v;
    int n;
    int cap;
    double per_s;        /* PWM periods per second */
} list_t;

static inj_t *add(list_t *l, int c, int start, int kind, int ch, double a, double window_s,
                  const char *what)
{
    inj_t *in;
    if (l->n == l->cap) {
        inj_t *v = realloc(l->v, (size_t)(l->cap * 2 + 64) * sizeof *v);
        if (v == NULL) {
            return NULL;
        }
        l->v = v;
        l->cap = l->cap * 2 + 64;
    }
    in = &l->v[l->n++];
    memset(in, 0, sizeof *in);
    in->cls = c;
    in->start = start;
    in->kind = kind;
    in->ch = ch;
    in->a = a;
    in->window = lround(window_s * l->per_s);
    snprintf(in->what, sizeof in->what, "%s", what);
    return in;
}

/* A class's injections: each value, on each channel when the class names channels. */
typedef struct {
    int cls;
    int start;
    int kind;
    int names;           /* 0: no channel; 1: the sensing channels iu, iv (, vdc); 2: phases */
    int n_ch;            /* channels to go through (ch = j, or 1 << j for K_STUCK, K_OPEN) */
    double window_s;
    double per_value_s;  /* added to the window per unit of the value */
    const char *fmt;     /* the channel's name (when names != 0), then the value (may be unused) */
    int n;
    double v[7];
} sweep_t;

static const sweep_t sweeps[] = {
    { C_OC, S_RUN, K_SURGE, 2, 3, 0.02, 0.0, "phase %s: %+.0f A", 6,
      { 32.0, -32.0, 36.0, -36.0, 39.0, -39.0 } },
    { C_OV, S_RUN, K_BUS, 0, 0, 0.1, 0.0, "bus 320 -> %.0f V", 3, { 460.0, 480.0, 520.0 } },
    { C_UV, S_RUN, K_BUS, 0, 0, 0.1, 0.0, "bus 320 -> %.0f V", 3, { 210.0, 180.0, 120.0 } },
    { C_BUS_IN, S_RUN, K_BUS, 0, 0, 1.0, 0.0, "bus 320 -> %.0f V", 4, { 250.0, 280.0, 360.0, 420.0 } },
    { C_OT_IPM, S_RUN, K_T_IPM, 0, 0, 0.1, 0.0, "IPM 40 -> %.1f degC", 3, { 110.1, 115.0, 150.0 } },
    { C_OT_PCB, S_RUN, K_T_PCB, 0, 0, 0.1, 0.0, "PCB 35 -> %.1f degC", 3, { 100.1, 105.0, 130.0 } },
    { C_TEMP_IN, S_RUN, K_T_IPM, 0, 0, 0.5, 0.0, "IPM 40 -> %.0f degC (limit 110)", 2, { 105.0, 110.0 } },
    { C_TEMP_IN, S_RUN, K_T_PCB, 0, 0, 0.5, 0.0, "PCB 35 -> %.0f degC (limit 100)", 2, { 95.0, 100.0 } },
    { C_STALL, S_RUN, K_SEIZE, 0, 0, 1.0, 0.0, "load %.0f x nominal", 3, { 2.0, 3.0, 5.0 } },
    /* the three starts of a locked rotor (ho_retries 2): STALL after about 13.3 s */
    { C_LOCKED, S_STOP, K_LOCK, 0, 0, 21.0, 0.0, "rotor locked at %.0f deg", 3, { 0.0, 100.0, 220.0 } },
    { C_OPEN_RUN, S_RUN, K_OPEN, 2, 3, 0.5, 0.0, "phase %s open at 3000 rpm", 1, { 0.0 } },
    { C_OPEN_START, S_STOP, K_OPEN, 2, 3, 0.6, 0.0, "phase %s open from the run command", 1, { 0.0 } },
    { C_OFFSET, S_COLD, K_OFFSET, 1, 2, 0.6, 0.0, "%s offset %+.0f counts at power-up", 6,
      { 120.0, -120.0, 300.0, -300.0, 600.0, -600.0 } },
    { C_OFFSET_IN, S_COLD, K_OFFSET, 1, 2, T_RUN_S + 0.4, 0.0, "%s offset %+.0f counts at power-up",
      4, { 50.0, -50.0, 90.0, -90.0 } },
    { C_STUCK, S_RUN, K_STUCK, 1, 3, 1.0, 0.0, "%s stuck at %.0f", 3, { 0.0, 4095.0, 2048.0 } },
    { C_DRIFT, S_RUN, K_OFFSET, 1, 2, 1.0, 0.0, "%s offset drift %+.0f counts", 6,
      { 50.0, -50.0, 200.0, -200.0, 600.0, -600.0 } },
    { C_GAIN, S_RUN, K_GAIN, 1, 2, 1.0, 0.0, "%s gain %.2f", 4, { 0.5, 0.8, 1.25, 2.0 } },
    { C_VDC_GAIN, S_RUN, K_VDC_GAIN, 0, 0, 1.0, 0.0, "vdc gain %.2f", 4, { 0.75, 0.8, 1.25, 1.35 } },
    { C_SKIP_FAST, S_RUN, K_SKIP_FAST, 0, 0, 0.5, 1.25e-4, "%.0f fast steps missed", 7,
      { 1.0, 2.0, 3.0, 8.0, 16.0, 40.0, 80.0 } },
    { C_SKIP_TICK, S_RUN, K_SKIP_TICK, 0, 0, 0.5, 1e-3, "no tick for %.0f ms", 5,
      { 2.0, 10.0, 50.0, 200.0, 1000.0 } },
};

static int add_sweep(list_t *l, const sweep_t *w)
{
    static const char *const names[3][3] = { { "", "", "" }, { "iu", "iv", "vdc" }, { "u", "v", "w" } };
    const bool mask = (w->kind == K_STUCK || w->kind == K_OPEN);
    char what[64];
    int j;
    int i;
    for (j = 0; j < ((w->n_ch > 0) ? w->n_ch : 1); j++) {
        for (i = 0; i < w->n; i++) {
            if (w->names != 0) {
                snprintf(what, sizeof what, w->fmt, names[w->names][j], w->v[i]);
            } else {
                snprintf(what, sizeof what, w->fmt, w->v[i]);
            }
            if (add(l, w->cls, w->start, w->kind, mask ? (1 << j) : j, w->v[i],
                    w->window_s + w->per_value_s * w->v[i], what) == NULL) {
                return -1;
            }
        }
    }
    return 0;
}

static int build(list_t *l, long n_flips, int table_step, uint64_t seed)
{
    const size_t n_bytes = DRV_HI - DRV_LO;
    uint64_t s = seed;
    inj_t *in;
    char w[64];
    long k;
    int j;

    add(l, C_CONTROL, S_COLD, K_NONE, 0, 0.0, T_RUN_S + 0.4, "cold start to 3000 rpm");
    add(l, C_CONTROL, S_RUN, K_NONE, 0, 0.0, 2.0, "2 s steady at 3000 rpm");
    add(l, C_CONTROL, S_RUN, K_SPEEDS, 0, 0.0, 7.0, "3000 -> 6000 -> 8000 -> 1500 rpm");
    for (j = 0; j < 3; j++) {
        snprintf(w, sizeof w, "garbage frames, seed %d", j + 1);
        add(l, C_GARBAGE, S_RUN, K_GARBAGE, 0, (double)(0x2545F491u * (unsigned)(j + 1)), 2.0, w);
    }
    add(l, C_OC, S_RUN, K_SURGE, 0, 60.0, 0.02, "phase u: +60 A (beyond full scale)");
    add(l, C_OC, S_RUN, K_SURGE, 1, -60.0, 0.02, "phase v: -60 A (beyond full scale)");
    add(l, C_NO_CURRENT, S_STOP, K_STUCK, 3, 2048.0, 0.6, "iu and iv stuck at 2048");
    add(l, C_NO_CURRENT, S_STOP, K_OPEN, 7, 0.0, 0.6, "motor disconnected (u, v, w open)");
    add(l, C_NO_CURRENT, S_STOP, K_OPEN, 3, 0.0, 0.6, "phases u and v open");
    add(l, C_LINK, S_RUN, K_LINK_STOP, 0, 0.0, 4.5, "master stops at 3000 rpm");
    add(l, C_LINK, S_RUN, K_LINK_BAD, 0, 0.0, 4.5, "only frames with a wrong checksum");
    in = add(l, C_LINK, S_STOP, K_LINK_STOP, 0, 0.0, 4.5, "master stops in OPEN_LOOP");
    if (in == NULL) {
        return -1;
    }
    in->delay = lround(l->per_s);   /* 1 s after the run command */
    add(l, C_SH_CONTROL, S_RUN_SH, K_NONE, 0, 0.0, 2.0, "2 s steady at 3000 rpm");
    add(l, C_SH_CONTROL, S_RUN_SH, K_SPEEDS, 0, 0.0, 7.0, "3000 -> 6000 -> 8000 -> 1500 rpm");
    for (j = 0; j < 6; j++) {
        static const double ring[3] = { 1.5, 2.0, 3.0 };
        snprintf(w, sizeof w, "ringing %.1f x the settle time, %s step", ring[j % 3],
                 (j < 3) ? "half" : "full");
        add(l, C_SH_RING, S_RUN_SH, K_RING, j / 3, ring[j % 3], 1.0, w);
    }
    add(l, C_SH_OPEN, S_RUN_SH, K_SHUNT_OPEN, 0, 0.0, 0.5, "sense connection open at 3000 rpm");
    add(l, C_SH_OPEN, S_STOP_SH, K_SHUNT_OPEN, 0, 0.0, 0.6,
        "sense connection open from the run command");
    for (j = 0; j < 6; j++) {
        static const double offs[6] = { 50.0, -50.0, 200.0, -200.0, 600.0, -600.0 };
        snprintf(w, sizeof w, "shunt offset drift %+.0f counts", offs[j]);
        add(l, C_SH_OFFSET, S_RUN_SH, K_SHUNT_OFFSET, 0, offs[j], 1.0, w);
    }
    for (j = 0; j < (int)(sizeof sweeps / sizeof sweeps[0]); j++) {
        if (add_sweep(l, &sweeps[j]) != 0) {
            return -1;
        }
    }
    for (k = 0; k < (long)(8 * sizeof(qfoc_param_table_t)); k += table_step) {
        /* with a step, the bit within the step turns, so every bit position is hit */
        const int bit = (int)(k + (k / table_step) % table_step);
        if (bit >= (int)(8 * sizeof(qfoc_param_table_t))) {
            break;
        }
        snprintf(w, sizeof w, "table bit %d", bit);
        in = add(l, C_FLIP_TABLE, S_RUN, K_FLIP_TABLE, bit, 0.0, budget_ms[M_PARAM_TABLE] * 1e-3 + 0.02, w);
        if (in == NULL) {
            return -1;
        }
        in->delay = (long)(mix(&s) % FLIP_DELAY_MAX);
    }
    for (k = 0; k < n_flips; k++) {
        const size_t byte = DRV_LO + (size_t)(mix(&s) % n_bytes);
        const int bit = (int)(byte * 8u) + (int)(mix(&s) % 8u);
        snprintf(w, sizeof w, "drive bit %d", bit);
        in = add(l, C_FLIP_DRIVE, S_RUN, K_FLIP_DRIVE, bit, 0.0, FLIP_WINDOW_S, w);
        if (in == NULL) {
            return -1;
        }
        in->delay = (long)(mix(&s) % FLIP_DELAY_MAX);
    }
    return 0;
}

/* ------------------------------------------------------------------ results */

typedef struct {
    long n;
    long detected;
    long in_time;
    long harmless;
    long pass;
    uint16_t bits;
    long per_bit[N_BITS];
    double det_min, det_max, react_min, react_max;
    double i_peak;
    double rpm_peak;
} agg_t;

/* What a flip did, for the breakdown by field. */
enum { O_PARAM, O_OTHER, O_MASKED, O_LATE, O_FAIL, O_N };
static const char *const outcome_name[O_N] = { "param", "other_fault", "masked", "late_harmless",
                                               "fail" };

static int outcome(const res_t *r)
{
    if (!r->pass) {
        return O_FAIL;
    }
    if (r->in_time) {
        return ((r->first & QFOC_FAULT_PARAM) != 0u) ? O_PARAM : O_OTHER;
    }
    return (r->faults == 0u) ? O_MASKED : O_LATE;
}

static void aggregate(const inj_t *v, const res_t *r, int n, agg_t *a)
{
    int k;
    int b;
    memset(a, 0, C_N * sizeof *a);
    for (k = 0; k < C_N; k++) {
        a[k].det_min = a[k].react_min = INFINITY;
        a[k].det_max = a[k].react_max = -INFINITY;
    }
    for (k = 0; k < n; k++) {
        agg_t *g = &a[v[k].cls];
        g->n++;
        g->detected += (r[k].faults != 0u);
        g->in_time += r[k].in_time;
        g->harmless += r[k].harmless;
        g->pass += r[k].pass;
        g->bits = (uint16_t)(g->bits | r[k].faults);
        for (b = 0; b < N_BITS; b++) {
            g->per_bit[b] += ((r[k].faults >> b) & 1u);
        }
        if (!isnan(r[k].t_det)) {
            g->det_min = fmin(g->det_min, r[k].t_det);
            g->det_max = fmax(g->det_max, r[k].t_det);
        }
        if (!isnan(r[k].t_react) && r[k].faults != 0u) {
            g->react_min = fmin(g->react_min, r[k].t_react);
            g->react_max = fmax(g->react_max, r[k].t_react);
        }
        g->i_peak = fmax(g->i_peak, r[k].i_peak);
        g->rpm_peak = fmax(g->rpm_peak, r[k].rpm_peak);
    }
}

static void jnum(FILE *f, double v, double scale)
{
    if (isnan(v) || isinf(v)) {
        fputs("null", f);
    } else {
        fprintf(f, "%.6g", v * scale);
    }
}

/* , "key": value x scale */
static void jfield(FILE *f, const char *key, double v, double scale)
{
    fprintf(f, ", \"%s\": ", key);
    jnum(f, v, scale);
}

/* , "key": [lo, hi] x scale */
static void jrange(FILE *f, const char *key, double lo, double hi, double scale)
{
    fprintf(f, ", \"%s\": [", key);
    jnum(f, lo, scale);
    fputs(", ", f);
    jnum(f, hi, scale);
    fputc(']', f);
}

static const char *const fault_names[N_BITS] = { "OC", "OV", "UV", "OT_IPM", "OT_PCB", "STALL",
                                                 "PHASE", "OFFSET", "LINK", "PARAM", "TIMING" };

static void jbits(FILE *f, uint16_t w)
{
    int b;
    int first = 1;
    fputc('[', f);
    for (b = 0; b < N_BITS; b++) {
        if ((w & (1u << b)) != 0u) {
            fprintf(f, "%s\"%s\"", first ? "" : ", ", fault_names[b]);
            first = 0;
        }
    }
    fputc(']', f);
}

/* One injection's record (times in ms). */
static void jrec(FILE *f, const inj_t *in, const res_t *r)
{
    fprintf(f, "{\"class\": \"%s\", \"what\": \"%s\", \"faults\": ", cls[in->cls].id, in->what);
    jbits(f, r->faults);
    fputs(", \"first\": ", f);
    jbits(f, r->first);
    jfield(f, "t_det_ms", r->t_det, 1e3);
    jfield(f, "t_react_ms", r->t_react, 1e3);
    jfield(f, "ftti_ms", r->ftti, 1e3);
    jfield(f, "budget_ms", r->budget, 1e3);
    fprintf(f, ", \"mechanism\": \"%s\"", mech_name[r->mech]);
    fprintf(f, ", \"i_peak_a\": %.2f, \"rpm_peak\": %.0f, \"oc_missed\": %s, \"over_full_scale\": %s, "
               "\"state_bad\": %s, \"pwm_outside_run\": %s, \"cmd_changed\": %s, "
               "\"frames_rejected\": %ld, \"harmless\": %s, \"in_time\": %s, \"pass\": %s}",
            r->i_peak, r->rpm_peak, r->oc_missed ? "true" : "false", r->over_fs ? "true" : "false",
            r->state_bad ? "true" : "false", r->pwm_off_run ? "true" : "false",
            r->cmd_changed ? "true" : "false", r->rejected,
            r->harmless ? "true" : "false", r->in_time ? "true" : "false", r->pass ? "true" : "false");
}

/* The flips of one class by field: counts per outcome, then every failure. */
static void jflips(FILE *f, int c, const fld_t *fl, int nf, size_t base, size_t size,
                   const inj_t *v, const res_t *r, int n)
{
    long (*cnt)[O_N] = calloc((size_t)nf + 1u, sizeof *cnt);
    long tot[O_N] = { 0 };
    size_t pad = 0u;
    size_t b;
    int k;
    int o;
    int first = 1;
    if (cnt == NULL) {
        return;
    }
    for (b = base; b < base + size; b++) {
        pad += (field_at(fl, nf, b) < 0) ? 1u : 0u;
    }
    for (k = 0; k < n; k++) {
        if (v[k].cls == c) {
            const int fi = field_at(fl, nf, (size_t)(v[k].ch / 8));
            o = outcome(&r[k]);
            cnt[(fi < 0) ? nf : fi][o]++;
            tot[o]++;
        }
    }
    fprintf(f, "    \"%s\": {\"bytes\": %zu, \"padding_bytes\": %zu, \"fields_named\": %d, "
               "\"totals\": {", cls[c].id, size, pad, nf);
    for (o = 0; o < O_N; o++) {
        fprintf(f, "%s\"%s\": %ld", o ? ", " : "", outcome_name[o], tot[o]);
    }
    fputs("},\n      \"fields\": [", f);
    for (k = 0; k <= nf; k++) {
        const size_t bytes = (k < nf) ? fl[k].size : pad;
        fprintf(f, "%s\n        {\"field\": \"%s\", \"offset\": %zu, \"bytes\": %zu", k ? "," : "",
                (k < nf) ? fl[k].name : "(padding)", (k < nf) ? fl[k].off : 0u, bytes);
        for (o = 0; o < O_N; o++) {
            fprintf(f, ", \"%s\": %ld", outcome_name[o], cnt[k][o]);
        }
        fputc('}', f);
    }
    fputs("],\n      \"failures\": [", f);
    for (k = 0; k < n; k++) {
        if (v[k].cls == c && !r[k].pass) {
            const size_t byte = (size_t)(v[k].ch / 8);
            const int fi = field_at(fl, nf, byte);
            fprintf(f, "%s\n        {\"field\": \"%s\", \"bit\": %d, \"delay_ms\": %.3f, \"record\": ",
                    first ? "" : ",", (fi < 0) ? "(padding)" : fl[fi].name,
                    (fi < 0) ? v[k].ch % 8 : (int)((byte - fl[fi].off) * 8u) + v[k].ch % 8,
                    (double)v[k].delay * snap[S_RUN].plant.bases.t_s * 1e3);
            jrec(f, &v[k], &r[k]);
            fputc('}', f);
            first = 0;
        }
    }
    fputs("]}", f);
    free(cnt);
}

static int write_results(const char *out, const inj_t *v, const res_t *r, int n, const char *mode,
                         long n_flips, int table_step, unsigned long seed, double wall)
{
    char path[700];
    agg_t a[C_N];
    FILE *f;
    int k;
    int first;
    aggregate(v, r, n, a);
    snprintf(path, sizeof path, "%s/flips.csv", out);
    f = fopen(path, "w");
    if (f == NULL) {
        return -1;
    }
    fputs("class,bit,field,bit_in_field,delay_ms,faults,t_det_ms,t_react_ms,i_peak_a,rpm_peak,"
          "outcome\n", f);
    for (k = 0; k < n; k++) {
        if (v[k].kind == K_FLIP_TABLE || v[k].kind == K_FLIP_DRIVE) {
            const bool tb = v[k].kind == K_FLIP_TABLE;
            const fld_t *fl = tb ? table_fields : drive_fields;
            const size_t byte = (size_t)(v[k].ch / 8);
            const int fi = field_at(fl, tb ? N_TABLE_FIELDS : N_DRIVE_FIELDS, byte);
            fprintf(f, "%s,%d,%s,%d,%.3f,%u,%.4g,%.4g,%.2f,%.0f,%s\n", cls[v[k].cls].id, v[k].ch,
                    (fi < 0) ? "(padding)" : fl[fi].name,
                    (fi < 0) ? v[k].ch % 8 : (int)((byte - fl[fi].off) * 8u) + v[k].ch % 8,
                    (double)v[k].delay * snap[S_RUN].plant.bases.t_s * 1e3, (unsigned)r[k].faults,
                    r[k].t_det * 1e3, r[k].t_react * 1e3, r[k].i_peak, r[k].rpm_peak,
                    outcome_name[outcome(&r[k])]);
        }
    }
    fclose(f);
    snprintf(path, sizeof path, "%s/results.json", out);
    f = fopen(path, "w");
    if (f == NULL) {
        return -1;
    }
    fprintf(f, "{\n  \"mode\": \"%s\", \"seed\": %lu, \"drive_flips\": %ld, \"table_step\": %d,\n"
               "  \"wall_s\": %.1f, \"table\": \"%s\", \"motor\": \"%s\", \"f_pwm_hz\": %.0f,\n"
               "  \"operating_point\": {\"rpm\": %u, \"load_nm\": %.3g, \"vdc_v\": %.0f},\n"
               "  \"limits\": {\"i_trip_a\": %.3f, \"i_full_scale_a\": %.1f, \"max_speed_rpm\": %.0f},\n"
               "  \"margin\": %.2f, \"assumptions\": \"%s\",\n  \"mechanisms\": [",
            mode, seed, n_flips, table_step, wall, tabr->name, motor.name, motor.f_pwm_hz,
            (unsigned)RPM_OP, nominal_nm(), motor.vdc_nominal_v, i_trip_a, motor.i_full_scale_a,
            motor.max_speed_rpm, MARGIN, assumptions_file);
    for (k = 0; k < M_N; k++) {
        fprintf(f, "%s\n    {\"mechanism\": \"%s\"", k ? "," : "", mech_name[k]);
        jfield(f, "spec_ms", spec_ms[k], 1.0);
        jfield(f, "budget_ms", budget_ms[k], 1.0);
        jfield(f, "ftti_ms", ftti_ms[k], 1.0);
        fprintf(f, ", \"key\": \"%s\", \"assumption\": \"%s\", \"adequate\": %s",
                (mech_key[k] != NULL) ? mech_key[k] : "", ftti_id[k],
                (mech_key[k] == NULL || spec_ms[k] <= ftti_ms[k]) ? "true" : "false");
        fprintf(f, ", \"source\": \"%s\"}", spec_text[k]);
    }
    fputs("\n  ],\n  \"model_checks\": [", f);
    for (k = 0; k < N_CHECKS; k++) {
        fprintf(f, "%s\n    {\"check\": \"%s\", \"value\": %.6g, \"ok\": %s}", k ? "," : "",
                checks[k].what, checks[k].value, checks[k].ok ? "true" : "false");
    }
    fputs("\n  ],\n  \"classes\": [", f);
    for (k = 0; k < C_N; k++) {
        const agg_t *g = &a[k];
        int b;
        fprintf(f, "%s\n    {\"class\": \"%s\", \"title\": \"%s\", \"mechanism\": \"%s\"",
                k ? "," : "", cls[k].id, cls[k].title, mech_name[cls[k].mech]);
        jfield(f, "ftti_ms", ftti_ms[cls[k].mech], 1.0);
        jfield(f, "budget_ms", budget_ms[cls[k].mech], 1.0);
        fputs(", \"expected_bit\": ", f);
        jbits(f, cls[k].bit);
        fprintf(f, ", \"expected_bit_raised\": %s, \"within_limits\": %s, \"injected\": %ld, "
                   "\"detected\": %ld, \"in_time\": %ld, \"harmless\": %ld, \"passed\": %ld, "
                   "\"failed\": %ld, \"bits\": ",
                (cls[k].bit == 0u) ? "null" : ((g->bits & cls[k].bit) != 0u ? "true" : "false"),
                (cls[k].mech == M_NONE) ? "true" : "false", g->n, g->detected, g->in_time,
                g->harmless, g->pass, g->n - g->pass);
        jbits(f, g->bits);
        fputs(", \"per_bit\": {", f);
        for (b = 0, first = 1; b < N_BITS; b++) {
            if (g->per_bit[b] > 0) {
                fprintf(f, "%s\"%s\": %ld", first ? "" : ", ", fault_names[b], g->per_bit[b]);
                first = 0;
            }
        }
        fputc('}', f);
        jrange(f, "t_det_ms", g->det_min, g->det_max, 1e3);
        jrange(f, "t_react_ms", g->react_min, g->react_max, 1e3);
        fprintf(f, ", \"i_peak_a\": %.2f, \"rpm_peak\": %.0f, \"verdict\": \"%s\"}", g->i_peak,
                g->rpm_peak, (g->n > 0 && g->pass == g->n) ? "PASS" : "FAIL");
    }
    fputs("\n  ],\n  \"injections\": [", f);
    for (k = 0, first = 1; k < n; k++) {
        if (!cls[v[k].cls].ram) {
            fputs(first ? "\n    " : ",\n    ", f);
            jrec(f, &v[k], &r[k]);
            first = 0;
        }
    }
    fputs("\n  ],\n  \"flips\": {\n", f);
    jflips(f, C_FLIP_TABLE, table_fields, N_TABLE_FIELDS, 0u, sizeof(qfoc_param_table_t), v, r, n);
    fputs(",\n", f);
    jflips(f, C_FLIP_DRIVE, drive_fields, N_DRIVE_FIELDS, DRV_LO, DRV_HI - DRV_LO, v, r, n);
    fputs("\n  }\n}\n", f);
    return (fclose(f) == 0) ? 0 : -1;
}

/* ------------------------------------------------------------------ main */

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* The injection a worker runs, in DIR/.curJ, so that a worker that dies (a crash in the
   drive or the plant) is reported with the injection that killed it. */
static void cur_write(const char *out, int j, int k)
{
    char path[700];
    FILE *f;
    snprintf(path, sizeof path, "%s/.cur%d", out, j);
    f = fopen(path, "w");
    if (f != NULL) {
        fprintf(f, "%d\n", k);
        (void)fclose(f);
    }
}

static long cur_read(const char *out, int j)
{
    char path[700];
    long k = -1;
    FILE *f;
    snprintf(path, sizeof path, "%s/.cur%d", out, j);
    f = fopen(path, "r");
    if (f != NULL) {
        if (fscanf(f, "%ld", &k) != 1) {
            k = -1;
        }
        (void)fclose(f);
    }
    return k;
}

/* jobs processes, injection k in process k % jobs; each writes its results to a file */
static int run_all(const char *out, const inj_t *v, res_t *r, int n, int jobs)
{
    char path[700];
    int j;
    int k;
    for (j = 0; j < jobs; j++) {
        const pid_t pid = fork();
        if (pid == 0) {
            FILE *f;
            snprintf(path, sizeof path, "%s/.part%d", out, j);
            f = fopen(path, "wb");
            for (k = j; k < n && f != NULL; k += jobs) {
                res_t x;
                cur_write(out, j, k);
                run(&v[k], &x);
                fwrite(&x, sizeof x, 1, f);
                if (j == 0 && (k / jobs) % 50 == 0) {
                    fprintf(stderr, "\rfaults: %d of %d injections", k + 1, n);
                    fflush(stderr);
                }
            }
            _exit((f != NULL && fclose(f) == 0) ? 0 : 2);
        } else if (pid < 0) {
            return -1;
        }
    }
    for (j = 0; j < jobs; j++) {
        int st;
        const pid_t pid = wait(&st);
        if (pid < 0 || !WIFEXITED(st) || WEXITSTATUS(st) != 0) {
            int w;
            fprintf(stderr, "\nqfoc_faults: a worker failed%s%s\n",
                    (pid >= 0 && WIFSIGNALED(st)) ? " on signal " : "",
                    (pid >= 0 && WIFSIGNALED(st)) ? strsignal(WTERMSIG(st)) : "");
            for (w = 0; w < jobs; w++) {
                const long c = cur_read(out, w);
                if (c >= 0 && c < n) {
                    fprintf(stderr, "qfoc_faults: worker %d was running injection %ld: %s, %s "
                            "(bit %d)\n", w, c, cls[v[c].cls].id, v[c].what, v[c].ch);
                }
            }
            return -1;
        }
    }
    fprintf(stderr, "\rfaults: %d of %d injections\n", n, n);
    for (j = 0; j < jobs; j++) {
        FILE *f;
        snprintf(path, sizeof path, "%s/.part%d", out, j);
        f = fopen(path, "rb");
        for (k = j; k < n && f != NULL; k += jobs) {
            if (fread(&r[k], sizeof r[k], 1, f) != 1) {
                fclose(f);
                return -1;
            }
        }
        if (f == NULL) {
            return -1;
        }
        fclose(f);
        remove(path);
        snprintf(path, sizeof path, "%s/.cur%d", out, j);
        remove(path);
    }
    return 0;
}

int main(int argc, char **argv)
{
    const char *out = "build/faults";
    const char *mode = "full";
    long n_flips = -1;
    int table_step = -1;
    unsigned long seed = 1;
    int jobs = 1;
    list_t l;
    res_t *r;
    agg_t a[C_N];
    double t0;
    int a_i;
    int k;
    int fails = 0;

    for (a_i = 1; a_i < argc; a_i++) {
        if (strcmp(argv[a_i], "--mode") == 0 && a_i + 1 < argc) {
            mode = argv[++a_i];
        } else if (strcmp(argv[a_i], "--flips") == 0 && a_i + 1 < argc) {
            n_flips = strtol(argv[++a_i], NULL, 10);
        } else if (strcmp(argv[a_i], "--table-step") == 0 && a_i + 1 < argc) {
            table_step = (int)strtol(argv[++a_i], NULL, 10);
        } else if (strcmp(argv[a_i], "--seed") == 0 && a_i + 1 < argc) {
            seed = strtoul(argv[++a_i], NULL, 10);
        } else if (strcmp(argv[a_i], "--jobs") == 0 && a_i + 1 < argc) {
            jobs = (int)strtol(argv[++a_i], NULL, 10);
        } else if (strcmp(argv[a_i], "--out") == 0 && a_i + 1 < argc) {
            out = argv[++a_i];
        } else if (strcmp(argv[a_i], "--assumptions") == 0 && a_i + 1 < argc) {
            assumptions_file = argv[++a_i];
        } else {
            fprintf(stderr, "usage: qfoc_faults [--mode full|check] [--flips N] [--table-step S] "
                            "[--seed S] [--jobs J] [--out DIR] [--assumptions TOML]\n");
            return 2;
        }
    }
    if (strcmp(mode, "full") != 0 && strcmp(mode, "check") != 0) {
        fprintf(stderr, "qfoc_faults: --mode full or check\n");
        return 2;
    }
    n_flips = (n_flips >= 0) ? n_flips : ((strcmp(mode, "full") == 0) ? 10000 : 400);
    table_step = (table_step >= 1) ? table_step : ((strcmp(mode, "full") == 0) ? 1 : 8);
    tabr = &scn_tables[0];
    tabs = NULL;
    for (k = 0; k < scn_n_tables; k++) {
        if (tabs == NULL && scn_tables[k].table->drive.sensing == QFOC_SENSING_SHUNT &&
            strcmp(scn_tables[k].motor_file, tabr->motor_file) == 0) {
            tabs = &scn_tables[k];
        }
    }
    if (tabs == NULL) {
        fprintf(stderr, "qfoc_faults: tables/manifest.txt has no single-shunt table of the "
                        "reference motor (%s)\n", tabr->motor_file);
        return 2;
    }
    if (jobs < 1 || jobs > 16 || sim_motor_load(tabr->motor_file, &motor) != 0) {
        fprintf(stderr, "qfoc_faults: bad arguments or motor file\n");
        return 2;
    }
    mkdir(out, 0777);
    t0 = now_s();
    fttis(tabr->table);
    if (load_fttis(assumptions_file, tabr->table) != 0) {
        return 2;
    }
    for (k = 0; k < M_N; k++) {
        if (mech_key[k] != NULL && spec_ms[k] > ftti_ms[k]) {
            printf("faults: %s: the library's specified reaction %.4g ms exceeds the item's FTTI "
                   "%.4g ms (%s): the hazard needs a mechanism outside the library\n",
                   mech_name[k], spec_ms[k], ftti_ms[k], ftti_id[k]);
            fails++;
        }
    }
    fflush(stdout);
    if (make_states() != 0 || check_models() != 0) {
        return 2;
    }
    i_trip_a = (double)ram_intact.i_trip / 32768.0 * snap[S_RUN].plant.bases.i_base;
    memset(&l, 0, sizeof l);
    l.per_s = 1.0 / snap[S_RUN].plant.bases.t_s;
    if (build(&l, n_flips, table_step, (uint64_t)seed) != 0) {
        return 2;
    }
    r = calloc((size_t)l.n, sizeof *r);
    if (r == NULL || run_all(out, l.v, r, l.n, jobs) != 0) {
        return 2;
    }
    if (write_results(out, l.v, r, l.n, mode, n_flips, table_step, seed, now_s() - t0) != 0) {
        fprintf(stderr, "qfoc_faults: cannot write %s\n", out);
        return 2;
    }
    aggregate(l.v, r, l.n, a);
    printf("%-20s %7s %8s %15s %15s %10s %10s %s\n", "class", "injected", "detected", "t_det ms",
           "t_react ms", "budget ms", "FTTI ms", "verdict");
    for (k = 0; k < C_N; k++) {
        const agg_t *g = &a[k];
        printf("%-20s %7ld %8ld %7.4g..%-7.4g %7.4g..%-7.4g %10.5g %10.5g %s (%ld failed)\n",
               cls[k].id, g->n, g->detected, g->det_min * 1e3, g->det_max * 1e3,
               g->react_min * 1e3, g->react_max * 1e3, budget_ms[cls[k].mech],
               ftti_ms[cls[k].mech], (g->n > 0 && g->pass == g->n) ? "PASS" : "FAIL",
               g->n - g->pass);
        fails += (g->n > 0 && g->pass == g->n) ? 0 : 1;
    }
    printf("faults: %d injections in %.1f s, %d class(es) failing\n", l.n, now_s() - t0, fails);
    free(r);
    free(l.v);
    return (fails == 0) ? 0 : 1;
}
