/**
 * @file ident.h
 * @brief Commissioning a new motor: the measurements from which the host computes the
 *        stator resistance R_s, the inductances L_d and L_q, the magnet flux psi_f and the
 *        inverter's voltage error (specs/equations.md section 12).
 *
 * The mode runs on the inverter and the motor it will drive, once per PWM period, in
 * place of the drive's control (the integrator calls qfoc_ident_step() from the
 * ADC-complete interrupt while the drive is stopped, with PWM off; safety manual AoU-26).
 * The first step aligns the rotor's d axis with the alpha axis (phase u), so that alpha is
 * the rotor's d axis and beta its q axis for the standstill steps after it.  Two PI
 * controllers (pi.h, the table's current-loop gains) hold the current of the control
 * frame's first axis at the step's level and that of its second axis at zero; the control
 * frame is the stationary one (alpha, beta) in ALIGN .. L_Q and the frame that turns with
 * PSI's current in PSI.  The voltage vector is modulated by qfoc_svpwm_step() without
 * dead-time compensation, so the inverter's own voltage error is in what the motor
 * receives and is measured, not guessed.
 *
 * Steps (each n_settle periods to settle, then a window of 2^win_shift periods, in two
 * halves whose sums are kept apart; ALIGN settles for n_align periods, PSI for n_ramp +
 * n_settle):
 *   ALIGN  alpha current i_hi: the rotor turns to the alpha axis and stays there;
 *   R_LO   alpha current i_lo;
 *   R_HI   alpha current i_hi: R_s = (V_hi - V_lo) / (I_hi - I_lo), the inverter's
 *          voltage error V_lo - R_s I_lo (both levels positive and above its transition,
 *          so the error is the same in both and cancels in the difference);
 *   L_D    alpha current i_hi (the rotor held) plus a voltage A cos(2 pi k / 16) on
 *          alpha: injection at f_pwm / 16;
 *   L_Q    the same with the injection on beta;
 *   PSI    the current i_hi turning at an angle step that ramps from 0 to w_psi per period
 *          over n_ramp periods, then holds w_psi: the rotor turns with it (I/f), and the
 *          voltage it takes gives psi_f (E12-3).
 * The injection amplitude A starts at v_inj in L_D and in L_Q and is found on the motor
 * over the first half of their settling: at the end of each injection period (16 PWM
 * periods) that follows one without a change, it doubles (at most v_inj_max) when the
 * injected axis's peak-to-peak current was below i_inj and halves (at least 1) when it was
 * above 4 i_inj; it is held over the window.  The reference on the control frame's first
 * axis moves towards each step's level by at most i_ramp per period (no current step, no
 * overshoot of the PI).  The voltage the motor receives is taken from the compare values
 * written (the inverter's duty cycles times the measured DC bus): the window sums hold the
 * alpha counts 2 cmp_u - cmp_v - cmp_w and the beta counts cmp_v - cmp_w, from which the
 * host forms u_alpha = counts V_dc / (3 P) and u_beta = counts V_dc / (sqrt 3 P).  The
 * compare values written in period k act in period k + 1: the host's models (E12-2,
 * E12-3) account for it.
 *
 * Bounds (each checked in the period it is seen; PWM off in that period and after):
 *   - current: |i_alpha| or |i_beta| above i_lim: QFOC_IDENT_ERR_OC (a shorted phase or
 *     a winding far below any plausible resistance; the drive's over-current trip on
 *     the phase currents stays the integrator's second barrier);
 *   - DC bus below vdc_min or above vdc_max: QFOC_IDENT_ERR_BUS (the drive's own
 *     bus monitors do not run while the mode has the PWM, commission.h);
 *   - at each window's end, the mean current of the control frame's first axis off the
 *     step's level by more than a quarter of it, or that of its second axis more than
 *     that from zero: QFOC_IDENT_ERR_NO_CURRENT (an open phase, no motor, a bus too low
 *     for the test current: the PI's voltage is at its limit and the current is not
 *     reached);
 *   - at the end of R_LO, R_HI, L_D and L_Q, the mean beta voltage command above
 *     v_move: QFOC_IDENT_ERR_MOVED (a rotor that creeps induces w psi_f on the q axis,
 *     which the beta loop must cancel; a rotor that turns through whole turns within a
 *     window averages this out and is seen by the current bounds or by the host's
 *     quality figures);
 *   - the whole mode lasts n_align + 5 n_settle + n_ramp + 6 2^win_shift periods at most.
 * qfoc_ident_abort() ends it at once (QFOC_IDENT_ERR_ABORT).
 *
 * Scaling (specs/scaling.md): currents Q15 of I_base, voltages and the DC bus Q15 of
 * V_base, compare values in timer ticks (svpwm.h), angles in 65536 counts a turn.  A half
 * window has at most 2^13 periods: every 32-bit sum stays within 2^13 x 65534 < 2^30,
 * every 64-bit product sum within 2^13 x 65534 x 32767 < 2^45; the sums are nevertheless
 * saturating (no input can overflow them).
 *
 * Every function is total: a configuration that fails qfoc_ident_cfg_is_valid() is
 * refused by qfoc_ident_start() (QFOC_IDENT_ERR_CFG, PWM off, nothing run).
 *
 * Requirements: REQ-IDENT-001 .. REQ-IDENT-007 (specs/requirements/ident.md).
 */
#ifndef QFOC_IDENT_H
#define QFOC_IDENT_H

#include "qfoc/types.h"
#include "qfoc/pi.h"
#include "qfoc/svpwm.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Results (qfoc_ident_result()). */
#define QFOC_IDENT_IDLE           ((uint8_t)0u)  /**< not started */
#define QFOC_IDENT_RUNNING        ((uint8_t)1u)  /**< measuring: PWM on */
#define QFOC_IDENT_DONE           ((uint8_t)2u)  /**< every step measured: the record is complete */
#define QFOC_IDENT_ERR_CFG        ((uint8_t)3u)  /**< configuration refused: nothing ran */
#define QFOC_IDENT_ERR_BUS        ((uint8_t)4u)  /**< DC bus below vdc_min or above vdc_max */
#define QFOC_IDENT_ERR_OC         ((uint8_t)5u)  /**< a current above i_lim */
#define QFOC_IDENT_ERR_NO_CURRENT ((uint8_t)6u)  /**< the step's current not reached */
#define QFOC_IDENT_ERR_MOVED      ((uint8_t)7u)  /**< the rotor turned */
#define QFOC_IDENT_ERR_ABORT      ((uint8_t)8u)  /**< ended by qfoc_ident_abort() */
#define QFOC_IDENT_ERR_DRIVE      ((uint8_t)9u)  /**< not started: the drive is not stopped, or
                                                      the bounds exceed its protections
                                                      (commission.h) */

/* Steps (qfoc_ident_step_now()); the record has one entry per step. */
#define QFOC_IDENT_ALIGN  ((uint8_t)0u)  /**< aligning the rotor */
#define QFOC_IDENT_R_LO   ((uint8_t)1u)  /**< the first resistance level */
#define QFOC_IDENT_R_HI   ((uint8_t)2u)  /**< the second resistance level */
#define QFOC_IDENT_L_D    ((uint8_t)3u)  /**< injection on the d (alpha) axis */
#define QFOC_IDENT_L_Q    ((uint8_t)4u)  /**< injection on the q (beta) axis */
#define QFOC_IDENT_PSI    ((uint8_t)5u)  /**< the rotor turned by a rotating current (I/f) */
#define QFOC_IDENT_STEPS  (6u)           /**< number of steps */

/** Smallest and largest window: 2^5 .. 2^14 periods (halves of 16 .. 8192). */
#define QFOC_IDENT_WIN_MIN ((uint8_t)5u)
#define QFOC_IDENT_WIN_MAX ((uint8_t)14u)  /**< largest window shift */

/** Largest angle step of PSI's rotating current, counts per period (f_pwm / 16). */
#define QFOC_IDENT_W_MAX ((uint16_t)4096u)

/** The saturation bound of the 32-bit window sums. */
#define QFOC_IDENT_SUM32_MAX ((int32_t)2147483647)
/** The saturation bound of the 64-bit window sums, 2^62. */
#define QFOC_IDENT_SUM64_MAX (4611686018427387904LL)

/** Configuration: what the host tool derives from the motor's ratings and the table. */
typedef struct {
    qfoc_q15_t i_lo;       /**< first resistance level, Q15 of I_base, > 0 */
    qfoc_q15_t i_hi;       /**< second level, alignment and bias current, > i_lo */
    qfoc_q15_t i_lim;      /**< the mode's current bound, > i_hi */
    qfoc_q15_t i_ramp;     /**< largest change of the reference per period, > 0 */
    qfoc_q15_t v_inj;      /**< first injection amplitude of L_D and L_Q, Q15 of V_base, > 0 */
    qfoc_q15_t v_inj_max;  /**< largest injection amplitude, Q15 of V_base, >= v_inj */
    qfoc_q15_t i_inj;      /**< injected current amplitude aimed at, Q15 of I_base, > 0 */
    qfoc_q15_t v_move;     /**< mean beta voltage of a turning rotor, Q15 of V_base, > 0 */
    qfoc_q15_t vdc_min;    /**< lowest DC bus the test runs on, Q15 of V_base, > 0 */
    qfoc_q15_t vdc_max;    /**< highest DC bus the test runs on, Q15 of V_base, > vdc_min */
    uint16_t n_align;      /**< periods of ALIGN before its window, > 0 */
    uint16_t n_settle;     /**< periods of the other steps before their window, > 0 */
    uint8_t win_shift;     /**< window of 2^win_shift periods, WIN_MIN .. WIN_MAX */
    uint16_t w_psi;        /**< PSI's angle step per period at its test speed, 1 .. W_MAX */
    uint16_t n_ramp;       /**< periods of PSI's speed ramp from standstill to w_psi, > 0 */
    qfoc_pi_params_t pi;   /**< current PI of both axes (pi.h; valid, out_min < 0 < out_max) */
    qfoc_svpwm_cfg_t pwm;  /**< modulation (svpwm.h; valid, dt_comp = 0) */
} qfoc_ident_cfg_t;

/** The sums of one half window.  The control frame is the stationary frame (alpha,
    beta) in ALIGN .. L_Q and the frame of the rotating current in PSI (d along the
    current); the reference angle of the demodulated sums is 2 pi k / 16 in ALIGN .. L_Q
    (the injection's) and the rotating current's angle in PSI. */
typedef struct {
    int32_t n;        /**< periods summed */
    int32_t i_a;      /**< sum of the current on the control frame's first axis, Q15 */
    int32_t i_b;      /**< sum of the current on its second axis, Q15 */
    int32_t u_a;      /**< sum of the alpha counts 2 cmp_u - cmp_v - cmp_w, ticks */
    int32_t u_b;      /**< sum of the beta counts cmp_v - cmp_w, ticks */
    int32_t vdc;      /**< sum of the DC bus, Q15 */
    int32_t vb_cmd;   /**< sum of the second axis's voltage command, Q15 */
    int64_t u_c;      /**< sum of the alpha counts times the reference cosine (Q15) */
    int64_t u_s;      /**< sum of the alpha counts times the reference sine */
    int64_t v_c;      /**< sum of the beta counts times the reference cosine */
    int64_t v_s;      /**< sum of the beta counts times the reference sine */
    int64_t i_c;      /**< sum of i_alpha times the reference cosine */
    int64_t i_s;      /**< sum of i_alpha times the reference sine */
    int64_t j_c;      /**< sum of i_beta times the reference cosine */
    int64_t j_s;      /**< sum of i_beta times the reference sine */
} qfoc_ident_sums_t;

/** The record: each step's two half windows. */
typedef struct {
    qfoc_ident_sums_t s[QFOC_IDENT_STEPS][2];  /**< [step][half] */
} qfoc_ident_record_t;

/** The mode's state (one per motor; written by the fast step's context only). */
typedef struct {
    qfoc_ident_cfg_t cfg;   /**< configuration taken at the start */
    qfoc_pi_t pi_a;         /**< current loop of the control frame's first axis */
    qfoc_pi_t pi_b;         /**< current loop of its second axis */
    qfoc_q15_t ref;         /**< the first axis's current reference now, Q15 */
    uint32_t n;             /**< periods spent in this step (at most 2 x 65535 + 2^14) */
    qfoc_angle_t theta;     /**< angle of PSI's rotating current */
    qfoc_q15_t inj;         /**< injection amplitude now, Q15 of V_base */
    qfoc_q15_t pk_max;      /**< largest injected-axis current of this injection period */
    qfoc_q15_t pk_min;      /**< smallest injected-axis current of this injection period */
    bool inj_hold;          /**< true: this injection period is not judged (the first one
                                 after an amplitude change or a step's start) */
    uint8_t step;           /**< QFOC_IDENT_ALIGN .. QFOC_IDENT_PSI */
    uint8_t result;         /**< QFOC_IDENT_IDLE .. QFOC_IDENT_ERR_DRIVE */
    uint8_t k;              /**< injection phase, 0 .. 15 */
    qfoc_ident_record_t rec;  /**< the record */
} qfoc_ident_t;

#ifdef __FRAMAC__
/* ACSL logic over the types above, read by Frama-C only (DEV-001). */
/* cppcheck-suppress misra-c2012-20.1 ; DEV-001 */
#include "ident.acsl"
#endif

/**
 * @brief Check a configuration (IDENT_CFG_VALID of specs/ident.acsl).
 * @param[in] c the configuration (any values)
 * @return true iff 0 < i_lo < i_hi < i_lim, i_ramp, v_inj, i_inj, v_move, vdc_min,
 *         n_align, n_settle and n_ramp are positive, v_inj <= v_inj_max, vdc_min < vdc_max,
 *         0 < w_psi <= QFOC_IDENT_W_MAX, QFOC_IDENT_WIN_MIN <= win_shift <=
 *         QFOC_IDENT_WIN_MAX, the PI parameters are valid with out_min < 0 < out_max, and
 *         the modulation is valid without dead-time compensation.
 * Requirements: REQ-IDENT-001.
 */
/*@
  requires valid: \valid_read(c);
  assigns \nothing;
  ensures result: \result <==> IDENT_CFG_VALID(c);
*/
bool qfoc_ident_cfg_is_valid(const qfoc_ident_cfg_t *c);

/**
 * @brief The idle state: PWM off, result QFOC_IDENT_IDLE, an empty record.
 * @param[out] id the state
 * Requirements: REQ-IDENT-001.
 */
/*@
  requires valid: \valid(id);
  assigns *id;
  ensures inv: IDENT_VALID(id);
  ensures idle: id->result == QFOC_IDENT_IDLE && id->step == QFOC_IDENT_ALIGN &&
                id->n == 0 && id->ref == 0;
*/
void qfoc_ident_init(qfoc_ident_t *id);

/**
 * @brief Start the mode with a configuration (copied), from any state.
 * @param[in,out] id the state (valid)
 * @param[in]     c  the configuration (any values)
 * @return QFOC_IDENT_RUNNING: started at ALIGN with an empty record and zero current;
 *         QFOC_IDENT_ERR_CFG: refused (the state is the idle state with that result,
 *         the PWM stays off).
 * Requirements: REQ-IDENT-001.
 */
/*@
  requires valid: \valid(id) && \valid_read(c);
  requires sep: \separated(id, c);
  assigns *id;
  ensures inv: IDENT_VALID(id);
  ensures step: id->step == QFOC_IDENT_ALIGN && id->n == 0 && id->ref == 0;
  behavior taken:
    assumes IDENT_CFG_VALID(c);
    ensures result: \result == QFOC_IDENT_RUNNING && id->result == QFOC_IDENT_RUNNING;
  behavior refused:
    assumes !IDENT_CFG_VALID(c);
    ensures result: \result == QFOC_IDENT_ERR_CFG && id->result == QFOC_IDENT_ERR_CFG;
  complete behaviors;
  disjoint behaviors;
*/
uint8_t qfoc_ident_start(qfoc_ident_t *id, const qfoc_ident_cfg_t *c);

/**
 * @brief End a running mode at once (QFOC_IDENT_ERR_ABORT); any other state is kept.
 * @param[in,out] id the state (valid)
 * Requirements: REQ-IDENT-003.
 */
/*@
  requires valid: \valid(id);
  requires inv: IDENT_VALID(id);
  assigns id->result;
  ensures inv: IDENT_VALID(id);
  ensures result: \old(id->result) == QFOC_IDENT_RUNNING ?
                    id->result == QFOC_IDENT_ERR_ABORT : id->result == \old(id->result);
*/
void qfoc_ident_abort(qfoc_ident_t *id);

/**
 * @brief The idle state of a start refused because the drive is not stopped
 *        (qfoc_commission_start()): PWM off in every following period, an empty record,
 *        result QFOC_IDENT_ERR_DRIVE.
 * @param[out] id the state (any contents)
 * Requirements: REQ-IDENT-007.
 */
/*@
  requires valid: \valid(id);
  assigns *id;
  ensures inv: IDENT_VALID(id);
  ensures refused: id->result == QFOC_IDENT_ERR_DRIVE && id->step == QFOC_IDENT_ALIGN &&
                   id->n == 0 && id->ref == 0;
*/
void qfoc_ident_refuse(qfoc_ident_t *id);

/**
 * @brief One PWM period of the mode (the file comment's steps and bounds).
 * @param[in,out] id  the state (valid)
 * @param[in]     i   this period's stator current, alpha and beta, Q15 of I_base
 * @param[in]     vdc this period's DC bus, Q15 of V_base
 * @return the compare values and the enable: enabled only while the mode runs and no
 *         bound is broken in this period; disabled, with every compare value at half the
 *         period (0 for an invalid modulation configuration), otherwise.
 * Requirements: REQ-IDENT-002, REQ-IDENT-003, REQ-IDENT-004.
 */
/*@
  requires valid: \valid(id) && \valid_read(i);
  requires sep: \separated(id, i);
  requires inv: IDENT_VALID(id);
  assigns *id;
  ensures inv: IDENT_VALID(id);
  ensures only_running: \result.enable ==> \old(id->result) == QFOC_IDENT_RUNNING &&
                                            id->result != QFOC_IDENT_ERR_OC &&
                                            id->result != QFOC_IDENT_ERR_BUS;
  ensures off_after_end: \old(id->result) != QFOC_IDENT_RUNNING ==>
                           !\result.enable && id->result == \old(id->result);
  ensures over_current: \old(id->result) == QFOC_IDENT_RUNNING &&
                        (IdentAbs(i->alpha) > \old(id->cfg.i_lim) ||
                         IdentAbs(i->beta) > \old(id->cfg.i_lim)) ==>
                          !\result.enable && id->result == QFOC_IDENT_ERR_OC;
  ensures bus: \old(id->result) == QFOC_IDENT_RUNNING &&
               IdentAbs(i->alpha) <= \old(id->cfg.i_lim) &&
               IdentAbs(i->beta) <= \old(id->cfg.i_lim) &&
               (vdc < \old(id->cfg.vdc_min) || vdc > \old(id->cfg.vdc_max)) ==>
                 !\result.enable && id->result == QFOC_IDENT_ERR_BUS;
  ensures cmp: \result.enable ==> \result.cmp[0] <= id->cfg.pwm.period &&
                                  \result.cmp[1] <= id->cfg.pwm.period &&
                                  \result.cmp[2] <= id->cfg.pwm.period;
  ensures mid: !\result.enable ==> \result.cmp[0] == id->cfg.pwm.period / 2 &&
                                   \result.cmp[1] == id->cfg.pwm.period / 2 &&
                                   \result.cmp[2] == id->cfg.pwm.period / 2;
  ensures ref: \result.enable ==> 0 <= id->ref <= id->cfg.i_hi;
*/
qfoc_pwm_t qfoc_ident_step(qfoc_ident_t *id, const qfoc_ab_t *i, qfoc_q15_t vdc);

/**
 * @brief The mode's result: QFOC_IDENT_IDLE .. QFOC_IDENT_ERR_DRIVE.
 * @param[in] id the state
 * @return the result
 * Requirements: REQ-IDENT-005.
 */
/*@
  requires valid: \valid_read(id);
  assigns \nothing;
  ensures result: \result == id->result;
*/
uint8_t qfoc_ident_result(const qfoc_ident_t *id);

/**
 * @brief The step the mode is in (or ended in): QFOC_IDENT_ALIGN .. QFOC_IDENT_PSI.
 * @param[in] id the state
 * @return the step
 * Requirements: REQ-IDENT-005.
 */
/*@
  requires valid: \valid_read(id);
  assigns \nothing;
  ensures result: \result == id->step;
*/
uint8_t qfoc_ident_step_now(const qfoc_ident_t *id);

/**
 * @brief Copy one half window's sums out of the record.
 * @param[in]  id   the state
 * @param[in]  step QFOC_IDENT_ALIGN .. QFOC_IDENT_PSI (any value)
 * @param[in]  half 0 or 1 (any value)
 * @param[out] out  the copy (all zero when step or half is out of range)
 * @return true when step and half are in range
 * Requirements: REQ-IDENT-005.
 */
/*@
  requires valid: \valid_read(id) && \valid(out);
  requires sep: \separated(id, out);
  assigns *out;
  behavior in_range:
    assumes step < QFOC_IDENT_STEPS && half < 2;
    ensures result: \result == \true;
    ensures copy: *out == id->rec.s[step][half];
  behavior out_of_range:
    assumes step >= QFOC_IDENT_STEPS || half >= 2;
    ensures result: \result == \false;
    ensures zero: out->n == 0 && out->i_a == 0 && out->u_a == 0 && out->i_c == 0;
  complete behaviors;
  disjoint behaviors;
*/
bool qfoc_ident_sums(const qfoc_ident_t *id, uint8_t step, uint8_t half,
                     qfoc_ident_sums_t *out);

/** Frames of the record: one header, then one per sum field. */
#define QFOC_IDENT_FIELDS  (15u)  /**< fields of qfoc_ident_sums_t, in declaration order */
#define QFOC_IDENT_FRAMES  ((uint16_t)181u)  /**< 1 + QFOC_IDENT_STEPS x 2 x QFOC_IDENT_FIELDS */

/**
 * @brief Frame k of the record, 8 bytes for a CAN, LIN or UART transport.
 *        Frame 0: byte 0 = 0xA5, byte 1 = result, byte 2 = step, byte 3 = win_shift,
 *        bytes 4..5 = the PWM period (little endian), bytes 6..7 = QFOC_IDENT_FRAMES.
 *        Frame k >= 1: with j = k - 1, step = j / 30, half = (j / 15) % 2 and field =
 *        j % 15 (qfoc_ident_sums_t's order): byte 0 = k (mod 256), byte 1 = 32 step +
 *        16 half + field, bytes 2..7 = the field's value as a 48-bit two's complement
 *        number, little endian (every sum fits: |sum| < 2^45; a 64-bit sum beyond 48
 *        bits, which only a saturated sum could be, is sent as +-(2^47 - 1)).
 * @param[in]  id  the state
 * @param[in]  k   0 .. QFOC_IDENT_FRAMES - 1 (any value)
 * @param[out] buf 8 bytes (all zero for k out of range)
 * @return true for k in range
 * Requirements: REQ-IDENT-005.
 */
/*@
  requires valid: \valid_read(id) && \valid(buf + (0 .. 7));
  requires sep: \separated(id, buf + (0 .. 7));
  assigns buf[0 .. 7];
  ensures result: \result <==> k < QFOC_IDENT_FRAMES;
*/
bool qfoc_ident_frame(const qfoc_ident_t *id, uint16_t k, uint8_t buf[8]);

#ifdef __cplusplus
}
#endif

#endif /* QFOC_IDENT_H */
