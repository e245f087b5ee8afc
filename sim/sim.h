/**
 * @file sim.h
 * @brief Double-precision plant for closed-loop tests of qfoc (host only).
 *
 * Not part of the library: plain C99 with double arithmetic, used by the tests,
 * the estimator report and the demonstration to put the Q15 library in a loop
 * with a model of the compressor drive.
 *
 * Models (specs/reference-motor.md gives the equations and their sources):
 *  - motor file: a TOML subset (sections, `key = number`, `key = "text"`,
 *    comments), one file per motor under specs/motors/;
 *  - salient-pole PMSM in the rotor (dq) frame, document chapter 1, integrated
 *    with classical RK4 at a fixed number of sub-steps per PWM period;
 *  - mechanics J dw/dt = T_e - T_L - B w, or a locked (imposed) speed; an optional
 *    breakaway torque (static friction) holds the rotor at standstill while
 *    |T_e - T_L| does not exceed it;
 *  - compressor load T_L = T_mean + T_1 sin(theta_m + phi_1) + T_2 sin(2 theta_m + phi_2);
 *  - two-level inverter on a centre-aligned up-down PWM counter, with dead time:
 *    the pole voltage follows the current sign while both switches are off;
 *  - sensing: phase currents u, v and the DC bus through 12-bit ADCs, sampled
 *    at the start of each PWM period (counter zero, zero vector on the low side),
 *    with optional Gaussian noise; compare values written during period k take
 *    effect at the start of period k + 1 (one period of computation delay);
 *  - single-shunt sensing (optional): the DC-link current, the sum of the phase
 *    currents of the poles that are high (through the switch or, in the dead time,
 *    the diode), with a ringing after every pole transition, sampled by the ADC's
 *    sample-and-hold at two counter values of the up-counting half that the drive
 *    chose, with asymmetric compare values (an up- and a down-counting edge per phase).
 *
 * Requirements: REQ-SIM-001 .. REQ-SIM-006 (specs/requirements/sim.md), verified
 * against closed-form solutions by tests/test_sim_plant.c.
 */
#ifndef QFOC_SIM_H
#define QFOC_SIM_H

#include <stdbool.h>
#include <stdint.h>

/** pi in double precision (M_PI is not C99). */
#define SIM_PI 3.14159265358979323846

/* ------------------------------------------------------------------ motor file */

/** Motor, inverter and sensing data of one motor file (SI units). */
typedef struct {
    char name[96];
    double pole_pairs;
    double rs_ohm;
    double ld_h;
    double lq_h;
    double psi_f_wb;
    double j_kgm2;
    double b_nms;
    double rated_speed_rpm;
    double max_speed_rpm;
    double rated_current_a;
    double nominal_torque_nm;
    double vdc_nominal_v;
    double vdc_min_v;
    double vdc_max_v;
    double f_pwm_hz;
    double f_timer_hz;
    double dead_time_s;
    double i_full_scale_a;
    double vdc_full_scale_v;
    double adc_bits;
    double f_base_hz;
} sim_motor_t;

/**
 * @brief Read a motor file.
 * @return 0 on success; -1 when the file cannot be read, a line is malformed or a
 *         required key is missing or not positive (the message names it on stderr).
 */
int sim_motor_load(const char *path, sim_motor_t *m);

/**
 * @brief Apply one override "section.key=number" (the tuning tool's --set syntax).
 * @return 0, or -1 for an unknown key or a malformed value (message on stderr).
 */
int sim_motor_set(sim_motor_t *m, const char *assignment);

/** Per-unit bases of a motor file (specs/scaling.md section 2). */
typedef struct {
    double v_base;    /**< V: DC-bus sensing full scale */
    double i_base;    /**< A: phase-current sensing full scale */
    double f_base;    /**< Hz: electrical frequency of speed 1.0 */
    double w_base;    /**< rad/s electrical */
    double psi_base;  /**< Wb = V_base / w_base */
    double z_base;    /**< ohm = V_base / I_base */
    double l_base;    /**< H = Z_base / w_base */
    double t_s;       /**< s: PWM (and control) period */
    uint16_t period;  /**< PWM counter top, f_timer / (2 f_pwm) */
} sim_bases_t;

void sim_bases(const sim_motor_t *m, sim_bases_t *b);

/* ------------------------------------------------------------------ plant */

/** Compressor load torque (N m) as a function of the mechanical angle. */
typedef struct {
    double t_mean;  /**< mean load torque */
    double t_1x;    /**< amplitude of the pulsation at 1x the mechanical frequency */
    double phi_1x;  /**< its phase (rad) */
    double t_2x;    /**< amplitude at 2x */
    double phi_2x;  /**< its phase (rad) */
    double knee_rpm;/**< 0: the torque above at any speed (an active load, as on a
                         dynamometer); > 0: a passive load (a compressor): it opposes the
                         motion and fades in linearly over +-knee_rpm, so it never drives
                         the rotor backwards at standstill */
    double t_break; /**< breakaway torque (static friction), N m, >= 0 (0: none): at
                         standstill the rotor is held while |T_e - T_L| <= t_break (T_L at
                         zero speed) and starts at the first sub-step where it is exceeded;
                         once turning there is no friction torque beyond B w; when the
                         speed passes through zero the rotor is held again (the release is
                         then checked at the next sub-step) */
} sim_load_t;

/**
 * Single-shunt sensing (REQ-SIM-007; the measurement on it: REQ-SHUNT-005, the cold start on
 * it: REQ-SCN-016, the pulsating load and the stop: REQ-SCN-017).  The DC-link current
 * i_dc(t) = sum over the poles that are high of their phase current (a pole is high while
 * its high-side switch is on, and in the dead time before a rising or after a falling gate
 * edge while its current is negative: the high-side diode conducts).  Every pole transition within the
 * period, at t_e with a step D of i_dc, adds the ringing
 *     r(t) = ring_gain D exp(-3 (t - t_e) / t_ring) cos(2 pi f_ring (t - t_e))
 * for t_e <= t < t_e + t_ring, and nothing after: a sample that overlaps [t_e, t_e +
 * t_ring) is wrong, one after it is exact.  A sample is the mean of i_dc + r over the
 * sample-and-hold aperture [t_j, t_j + t_sh] (16 points), the phase currents taken at
 * t_j (the integration is split there), converted like a phase-current channel (2048 =
 * 0 A, 2048 counts per full scale, the ADC offset error and the current noise of the
 * configuration).
 */
typedef struct {
    bool active;       /**< the two DC-link samples are taken (sim_set_triggers) */
    double t_ring_s;   /**< length of the ringing after a pole transition, s (0: none) */
    double ring_gain;  /**< its initial amplitude relative to the step of i_dc */
    double f_ring_hz;  /**< its frequency, Hz */
    double t_sh_s;     /**< the ADC's sample-and-hold aperture, s (0: a point sample) */
} sim_shunt_cfg_t;

/** Scenario settings of a plant instance. */
typedef struct {
    sim_motor_t motor;        /**< the motor actually simulated (parameter errors are
                                   applied to the controller's copy, not here) */
    double vdc_v;             /**< DC-bus voltage */
    double dead_time_s;       /**< inverter dead time (0 = ideal switches) */
    double noise_i_rms_a;     /**< Gaussian noise on each current sample, A rms */
    double noise_vdc_rms_v;   /**< Gaussian noise on the DC-bus sample, V rms */
    double adc_offset_counts; /**< current-ADC offset error, counts */
    uint32_t seed;            /**< noise generator seed */
    bool speed_locked;        /**< true: speed imposed, mechanics not integrated */
    double locked_speed_e;    /**< imposed electrical speed, rad/s (speed_locked) */
    sim_load_t load;
    int substeps;             /**< RK4 steps per PWM period (>= 1, e.g. 20) */
    sim_shunt_cfg_t shunt;    /**< single-shunt sensing (inactive when all zero) */
} sim_cfg_t;

/** ADC samples of one PWM period. */
typedef struct {
    uint16_t iu;   /**< phase u current, 0..4095, 2048 = 0 A */
    uint16_t iv;   /**< phase v current */
    uint16_t vdc;  /**< DC bus, 0..4095 */
} sim_adc_t;

/**
 * Faults of the sensing chain and of the windings, for the fault-injection campaign
 * (sim/apps/faults.c, specs/fault-campaign.md; REQ-FINJ-001 .. REQ-FINJ-008).  sim_init()
 * makes every one inactive, and the plant is then exactly the model above.
 *  - sensing: each current channel's sample is gain x the true current plus an offset in
 *    counts before the 12-bit conversion, the DC-bus sample vdc_gain x the true bus; any
 *    channel can be stuck at a code;
 *  - open phases: an open phase carries no current.  With one phase open (a broken wire or
 *    a failed connection on the motor side, star point not connected) the current of the
 *    two others is i and -i: the stator current vector is confined to the axis at right
 *    angles to the open phase's, e = (cos phi, sin phi) with phi = axis + 90 deg, and the
 *    flux linkage along it, psi_e = L_e(theta) i + psi_f cos(theta - phi) with
 *    L_e = L_d cos^2(theta - phi) + L_q sin^2(theta - phi), obeys d psi_e / dt = e . v - R_s i
 *    (the alpha-beta model is exact for it: the zero-sequence current is still zero); the
 *    open phase's pole voltage has no effect.  With two or three phases open no current
 *    flows at all (no motor).  The phase opens at the next sub-step: the current along the
 *    open phase's axis is cut.
 */
typedef struct {
    bool sense;          /**< the sensing faults below are applied */
    double gain[2];      /**< current channels u, v: sensed = gain x true (1 = exact) */
    double offset[2];    /**< current channels u, v: offset added, counts */
    double vdc_gain;     /**< DC-bus channel: sensed = vdc_gain x true (1 = exact) */
    int stuck[3];        /**< iu, iv, vdc: the code returned, or -1 (not stuck) */
    unsigned open;       /**< open phases: bit 0 u, bit 1 v, bit 2 w (0 = none) */
    bool shunt_open;     /**< single shunt: the amplifier's sense connection open, both
                              samples read its zero (2048 plus the offsets below) */
    double shunt_offset; /**< single shunt: offset added to both samples, counts */
} sim_inj_t;

/**
 * Recording of the true phase currents at sub-step resolution (REQ-SCN-018, with the
 * analysis of the records, sim_harmonics()).  Off unless sim_record() gives a buffer:
 * nothing of the plant's behaviour or outputs depends on it.  While on, every period
 * appends cfg.substeps samples, one at the end of each uniform sub-step (instants
 * t + (k + 1) T / substeps, k = 0 .. substeps - 1, of the period starting at t; the splits
 * at the single-shunt sampling instants add none): the electrical angle unwrapped from the
 * first sample on (rad) and the phase currents u, v, w (A), four doubles per sample in
 * buf[4 n .. 4 n + 3].  Once cap samples are recorded the rest are counted in dropped.
 */
typedef struct {
    double *buf;       /**< 4 x cap doubles: theta_e (unwrapped), i_u, i_v, i_w */
    long cap;          /**< samples the buffer holds */
    long n;            /**< samples recorded */
    long dropped;      /**< samples not recorded for want of room */
    double th_last;    /**< the last sample's wrapped angle, for the unwrapping */
    double th_turns;   /**< 2 pi x the turns unwrapped so far */
} sim_rec_t;

/** Plant state (read the fields; change them only through the functions). */
typedef struct {
    sim_cfg_t cfg;
    sim_bases_t bases;
    double t;          /**< time, s (start of the current PWM period) */
    double id, iq;     /**< rotor-frame currents, A */
    double w_m;        /**< mechanical speed, rad/s */
    double theta_m;    /**< mechanical angle, rad, in [0, 2 pi) */
    uint16_t cmp_active[3];   /**< compare values of the current period */
    uint16_t cmp_pending[3];  /**< written this period, active from the next */
    bool asym_active;         /**< the period's compare values are asymmetric (up, down) */
    bool asym_pending;
    uint16_t up_active[3];    /**< asymmetric: up-counting-half compare values */
    uint16_t down_active[3];  /**< asymmetric: down-counting-half compare values */
    uint16_t up_pending[3];
    uint16_t down_pending[3];
    bool trig_active;         /**< single shunt: samples are taken this period */
    bool trig_pending;
    uint16_t trig_active_v[2];   /**< counter values of the up half of the two samples */
    uint16_t trig_pending_v[2];
    bool shunt_taken;         /**< the last period took the two samples below */
    uint16_t shunt_code[2];   /**< DC-link ADC codes of the last period's two samples */
    double shunt_true[2];     /**< i_dc at each sample's start without ringing or noise, A */
    double shunt_iph[2][3];   /**< the phase currents u, v, w at each sample's start, A */
    double v_ab_avg[2];       /**< average alpha/beta phase voltage of the last period */
    double torque_avg;        /**< average electromagnetic torque of the last period */
    bool en_active;           /**< inverter switching in the current period */
    bool en_pending;          /**< written this period, active from the next */
    bool extinct;             /**< switching off and the currents have died out */
    bool held;                /**< rotor held at standstill by load.t_break */
    uint32_t rng;
    sim_inj_t inj;            /**< injected faults (none after sim_init) */
    sim_rec_t *rec;           /**< sub-step recording (NULL after sim_init: off) */
} sim_t;

/** Initialise at standstill, zero currents, theta_m = 0, compare = period / 2. */
void sim_init(sim_t *s, const sim_cfg_t *cfg);

/** Set the state: electrical angle and speed (rad, rad/s) and dq currents (A). */
void sim_set_state(sim_t *s, double theta_e, double w_e, double id, double iq);

/** Impose the stator current vector (alpha, beta, A) at the present angle: a
    short-circuit current surge in the windings (fault injection). */
void sim_set_current_ab(sim_t *s, const double i_ab[2]);

/** ADC samples at the current instant (start of the period). */
void sim_sample(sim_t *s, sim_adc_t *adc);

/** Write compare values (0..period); they take effect at the next period start. */
void sim_set_compare(sim_t *s, const uint16_t cmp[3]);

/**
 * Write asymmetric compare values (each clamped to 0..period), effective at the next
 * period start like sim_set_compare(), which makes them symmetric again: phase k's
 * high side is on from counter value period - up[k] in the up-counting half (the first
 * half of the period) to period - down[k] in the down-counting half, so its on-time is
 * (up[k] + down[k]) / (2 period) of the period.
 */
void sim_set_compare2(sim_t *s, const uint16_t up[3], const uint16_t down[3]);

/**
 * Single shunt: the counter values of the up-counting half (each clamped to 0..period)
 * at which the next period's two DC-link samples start, or none (on false).  Effective
 * at the next period start; the samples are read after it with sim_sample_shunt().
 */
void sim_set_triggers(sim_t *s, const uint16_t trig[2], bool on);

/**
 * Single shunt: the two DC-link ADC codes the last sim_step_period() took.
 * @return false (codes 2048) when that period took no samples (triggers off, or shunt
 *         sensing inactive).
 */
bool sim_sample_shunt(const sim_t *s, uint16_t code[2]);

/**
 * Record the true phase currents at every sub-step from the next period on into rec
 * (its n and dropped reset to 0), or stop recording (rec NULL).  See sim_rec_t.
 */
void sim_record(sim_t *s, sim_rec_t *rec);

/** Integrate one PWM period; then the pending compare values become active. */
void sim_step_period(sim_t *s);

/**
 * The ADC codes (as sim_sample()) at the instant tau s after the start of the current PWM
 * period: a copy of the plant integrated from the period's start to tau with the period's
 * active compare values and enable, in the uniform sub-steps of sim_step_period() (the last
 * one cut at tau), then sampled; s itself is not changed.  tau = 0 gives sim_sample() of
 * s; tau = T gives the codes of s after sim_step_period() with the same settings.  For
 * symmetric compare values only: with asymmetric ones or single-shunt triggers active the
 * codes of the period's start are returned.  (The processor-in-the-loop run converts the
 * plant at each conversion's start: port_s32k/pil/.)
 */
void sim_sample_at(const sim_t *s, double tau, sim_adc_t *adc);

/**
 * Inverter enable for the next period (like the compare values).  Disabled: all six
 * switches off; each pole follows its current through the freewheeling diodes
 * (low for a positive current, high for a negative one), so the currents decay
 * against the DC bus; once the current vector is below 0.3 A it is taken as zero
 * (no conduction while the line-to-line back-EMF stays below V_dc).
 */
void sim_set_enable(sim_t *s, bool enable);

/* truth, for references and reports */
double sim_theta_e(const sim_t *s);          /**< electrical angle, rad, [0, 2 pi) */
double sim_w_e(const sim_t *s);              /**< electrical speed, rad/s */
void sim_i_ab(const sim_t *s, double i_ab[2]);   /**< stationary-frame current, A */
double sim_torque(const sim_t *s);           /**< electromagnetic torque now, N m */
double sim_load_torque(const sim_t *s);      /**< load torque now, N m */

/* ------------------------------------------------------------------ helpers */

/** Phase-current ADC code to Q15 of I_base: (code - 2048) x 16. */
int16_t sim_adc_current_q15(uint16_t code);
/** DC-bus ADC code to Q15 of V_base: code x 8. */
int16_t sim_adc_vdc_q15(uint16_t code);
/** Wrap an angle to [-pi, pi). */
double sim_wrap_pi(double x);

/* ------------------------------------------------------------------ harmonic analysis */

/** Highest harmonic order sim_harmonics() reports one by one. */
#define SIM_HARM_MAX 64

/** Harmonic content of a signal over a whole number of periods of its fundamental. */
typedef struct {
    double dc;            /**< mean */
    double fund_rms;      /**< RMS of the fundamental */
    double fund_phase;    /**< its phase, rad: x_1(k) = sqrt 2 fund_rms cos(w k + fund_phase) */
    double h_rms[SIM_HARM_MAX + 1]; /**< RMS of harmonic h = 0 .. h_max (h_rms[1] = fund_rms,
                                         h_rms[0] = |dc|); 0 above h_max */
    double harm_rms;      /**< RMS of harmonics 2 .. h_max together */
    double thd;           /**< harm_rms / fund_rms */
    double dist_rms;      /**< RMS of x minus its fundamental, in the time domain: every other
                               component (DC, harmonics of any order, the PWM ripple) */
    double tdd;           /**< dist_rms / fund_rms: the total distortion */
} sim_harm_t;

/**
 * @brief The harmonic content of n samples x[0], x[stride], ... taken uniformly over exactly
 *        `cycles` periods of the fundamental (REQ-SCN-018): the discrete Fourier transform's
 *        bins h x cycles, h = 0 .. h_max, each evaluated directly in double precision (the
 *        angle of sample k reduced exactly, (h cycles k) mod n, before the cosine), and the
 *        time-domain RMS of x less its fundamental.
 * @return 0; -1 when cycles < 1, h_max is not 2 .. SIM_HARM_MAX, the samples are too few for
 *         the highest bin (n <= 2 h_max cycles) or the fundamental is zero (out zeroed).
 */
int sim_harmonics(const double *x, long stride, long n, int cycles, int h_max, sim_harm_t *out);

/* ------------------------------------------------------------------ ideal controller */

/**
 * Double-precision current controller on the TRUE rotor angle (the "ideal"
 * controller the estimators are validated under): PI in dq with decoupling,
 * pole-zero cancellation at bandwidth bw_hz, angle advanced by 1.5 periods for the
 * computation and PWM delay, voltage limited to the inscribed circle, and the
 * library's SVPWM (qfoc_svpwm_step) with dead-time compensation producing the
 * compare values.  Reference currents from a torque command with a voltage-limit
 * (field-weakening) rule for i_d.
 */
typedef struct {
    sim_motor_t m;        /**< controller's motor data */
    sim_bases_t b;
    double bw_hz;         /**< current-loop bandwidth */
    double u_margin;      /**< usable fraction of Vdc / sqrt(3) for the i_d rule */
    double int_d, int_q;  /**< integrators, V */
    double id_ref, iq_ref;
    double v_ab_q15[2];   /**< last command, Q15 of V_base (as sent to SVPWM) */
    int16_t v_cmd[2];     /**< last command as Q15 integers */
    double dt_comp_s;     /**< dead-time compensation, s */
} sim_ctrl_t;

void sim_ctrl_init(sim_ctrl_t *c, const sim_motor_t *m, double bw_hz);

/** Reference currents for a torque at an electrical speed and bus voltage. */
void sim_ctrl_torque_ref(sim_ctrl_t *c, double torque_nm, double w_e, double vdc);

/**
 * One control period: measured ADC samples, true angle and speed at the sample;
 * writes the compare values and returns the voltage command (Q15) in v_cmd.
 */
void sim_ctrl_step(sim_ctrl_t *c, const sim_adc_t *adc, double theta_e, double w_e,
                   uint16_t cmp[3]);

#endif /* QFOC_SIM_H */
