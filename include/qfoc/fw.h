/**
 * @file fw.h
 * @brief Field weakening: voltage-utilisation loop producing a negative d-axis
 *        current reference (specs/equations.md E2-46; formerly
 *        FireldWeakeningControl, Init_MtrFwc).
 *
 * When the back-EMF approaches the largest voltage the inverter can apply, the
 * current loops lose their margin.  The loop measures the SVPWM voltage
 * utilisation (qfoc_svpwm_out_t.utilisation = |v| / (V_dc / sqrt 3), t_all of
 * E2-45), low-passes it, and drives i_d negative until the filtered
 * utilisation equals the level FWK_LVL:
 *
 *     util_f(k) = util_f(k-1) + alpha (utilisation(k) - util_f(k-1))   (lpf, E2-34)
 *     e(k)      = FWK_LVL - util_f(k)
 *     i_d_ref(k) = PI(e(k)),  limited to [out_min, 0]                   (qfoc_pi)
 *
 * The earlier code added the PI output to the previous i_d reference (incremental
 * form); here the PI integrator is that accumulated reference and the
 * proportional part acts on top of it, with the clamping anti-windup of
 * qfoc_pi.  Above the level (e < 0) the reference falls toward out_min (the
 * largest field-weakening current, FWK_MAX of Init_MtrFwc); below it (e > 0) it
 * rises back to 0 and stays there: the loop never produces a positive i_d.
 * Disabling the loop is the release of E2-46: i_d reference 0, filter output 0,
 * integrator 0.  (The earlier start-up counter, which let the filter run
 * only after 1000 calls, belongs to the caller: the drive enables the loop only
 * in closed-loop operation.)
 *
 * Tuning (reference motor, specs/reference-motor.md, f_pwm = 8 kHz):
 *  - alpha = 2 pi f_c / f_pwm: f_c = 50 Hz gives 2 pi 50 / 8000 x 32768 = 1286.8 -> 1287;
 *  - level: e.g. 0.95 (31130) keeps 5 % voltage margin for the current loops;
 *  - out_min: -(largest field-weakening current), e.g. -15 A / 40 A = -0.375
 *    -> -12288;
 *  - plant gain d(utilisation)/d(i_d) = w L_d / (V_dc / sqrt 3) x (u_q / |v|)
 *    in per unit (at 8000 rpm, 320 V: 0.8 x 0.6535 / 0.3695 = 1.41 x u_q / |v|);
 *    an integral gain ki T ~ 1 / (gain x N) settles in about N samples, e.g.
 *    N = 400 (50 ms): ki T = 1 / (1.41 x 400) = 0.00177 -> ki = 58, ki_shift = 0;
 *    kp small (e.g. 0.1 -> 3277) since the utilisation is already filtered.
 *
 * All functions are total on every value of their input types; the instance
 * must satisfy qfoc_fw_is_valid() (ACSL FwValid), which qfoc_fw_init()
 * establishes and every function preserves.
 *
 * Requirements: REQ-FW-001 .. REQ-FW-006 (specs/requirements/fw.md).
 */
#ifndef QFOC_FW_H
#define QFOC_FW_H

#include "qfoc/types.h"
#include "qfoc/pi.h"
#include "qfoc/filter.h"

#ifdef __cplusplus
extern "C" {
#endif

/** qfoc_fw_init() status: parameters accepted. */
#define QFOC_FW_OK ((int32_t)0)
/** qfoc_fw_init() status: parameters rejected, instance set to the safe state. */
#define QFOC_FW_ERR_PARAM ((int32_t)-1)

/** Field-weakening parameters (Init_MtrFwc). */
typedef struct {
    qfoc_pi_params_t pi;  /**< error (level - utilisation_f) -> i_d reference; out_max
                               must be 0, out_min = -(largest field-weakening
                               current) <= 0, Q15 of I_base */
    qfoc_q15_t level;     /**< FWK_LVL: utilisation target, Q15, 1..32767 */
    qfoc_q15_t alpha;     /**< utilisation low-pass 2 pi f_c / f_pwm, Q15, 1..32767 */
} qfoc_fw_params_t;

/** Field-weakening instance. */
typedef struct {
    qfoc_pi_t pi;          /**< PI, limits [out_min, 0]; its integrator is the
                                accumulated i_d reference */
    qfoc_lpf_t util_lpf;   /**< low-pass of the utilisation, state in [0, 32767] x 65536 */
    qfoc_q15_t level;      /**< FWK_LVL, Q15, 1..32767 */
    qfoc_q15_t id_ref;     /**< last i_d reference, Q15 of I_base, in [out_min, 0] */
} qfoc_fw_t;

#ifdef __FRAMAC__
/* ACSL predicates over the types above, read by Frama-C only (DEV-001). */
/* cppcheck-suppress misra-c2012-20.1 ; DEV-001 */
#include "fw.acsl"
#endif

/**
 * @brief Check a field-weakening parameter set.
 * @param[in] p parameters (read only)
 * @return true when the PI parameters are valid (qfoc_pi_params_is_valid()),
 *         pi.out_max == 0 (hence out_min <= 0), level >= 1 and alpha >= 1.
 *
 * Scaling and overflow: compares only.
 *
 * Requirements: REQ-FW-001.
 */
/*@
  requires valid_p: \valid_read(p);
  assigns \nothing;
  ensures result: \result != 0 <==> FwParamsValid(p);
*/
bool qfoc_fw_params_is_valid(const qfoc_fw_params_t *p);

/**
 * @brief Check a field-weakening instance (run-time twin of FwValid).
 * @param[in] fw instance (read only)
 * @return true when the PI instance is valid with out_max == 0, the filter is
 *         valid with its state in [0, 32767 x 65536], level >= 1 and
 *         out_min <= id_ref <= 0.
 *
 * Scaling and overflow: compares only (the PI check widens its limits to Q31).
 *
 * Requirements: REQ-FW-002.
 */
/*@
  requires valid_fw: \valid_read(fw);
  assigns \nothing;
  ensures result: \result != 0 <==> FwValid(fw);
*/
bool qfoc_fw_is_valid(const qfoc_fw_t *fw);

/**
 * @brief Initialise the field-weakening loop: store the parameters, clear the
 *        state (i_d reference 0, filter 0, integrator 0).
 * @param[out] fw instance
 * @param[in]  p  parameters (copied; not referenced afterwards)
 * @return QFOC_FW_OK (0) when qfoc_fw_params_is_valid(p), QFOC_FW_ERR_PARAM (-1)
 *         otherwise.
 *
 * Bad input: invalid parameters are not stored; the instance is set to the safe
 * state kp = ki = 0, limits [0, 0], alpha = 32767, level = 32767, which is valid
 * and makes every later qfoc_fw_step() return 0 (no field weakening).
 *
 * Scaling and overflow: copies only.
 *
 * Requirements: REQ-FW-001, REQ-FW-002.
 */
/*@
  requires valid_fw: \valid(fw);
  requires valid_p: \valid_read(p);
  requires sep: \separated(fw, p);
  assigns *fw;
  ensures valid: FwValid(fw);
  ensures cleared: fw->id_ref == 0 && fw->pi.integ == 0 && fw->util_lpf.state == 0 &&
                   fw->pi.limited == \false;
  behavior accepted:
    assumes FwParamsValid(p);
    ensures result: \result == 0;
    ensures gains: fw->pi.params.kp == p->pi.kp && fw->pi.params.kp_shift == p->pi.kp_shift &&
                   fw->pi.params.ki == p->pi.ki && fw->pi.params.ki_shift == p->pi.ki_shift;
    ensures limits: fw->pi.params.out_min == p->pi.out_min && fw->pi.params.out_max == 0;
    ensures level: fw->level == p->level && fw->util_lpf.alpha == p->alpha;
  behavior rejected:
    assumes !FwParamsValid(p);
    ensures result: \result == -1;
    ensures safe: fw->pi.params.kp == 0 && fw->pi.params.ki == 0 &&
                  fw->pi.params.out_min == 0 && fw->pi.params.out_max == 0;
    ensures safe_filter: fw->level == 32767 && fw->util_lpf.alpha == 32767;
  complete behaviors;
  disjoint behaviors;
*/
int32_t qfoc_fw_init(qfoc_fw_t *fw, const qfoc_fw_params_t *p);

/**
 * @brief Release: i_d reference 0, filtered utilisation 0, integrator 0
 *        (parameters kept).
 * @param[in,out] fw valid instance
 *
 * Scaling and overflow: stores only.
 *
 * Requirements: REQ-FW-005.
 */
/*@
  requires valid_fw: \valid(fw);
  requires fw_valid: FwValid(fw);
  assigns fw->pi.integ, fw->pi.limited, fw->util_lpf.state, fw->id_ref;
  ensures valid: FwValid(fw);
  ensures cleared: fw->id_ref == 0 && fw->pi.integ == 0 && fw->util_lpf.state == 0 &&
                   fw->pi.limited == \false;
*/
void qfoc_fw_reset(qfoc_fw_t *fw);

/**
 * @brief One fast-step sample of the field-weakening loop.
 * @param[in,out] fw          valid instance (qfoc_fw_is_valid())
 * @param[in]     utilisation SVPWM utilisation |v| / (V_dc / sqrt 3), Q15,
 *                            0..32767 (qfoc_svpwm_out_t.utilisation); a negative
 *                            value (impossible) is read as 0
 * @param[in]     enable      false: release (qfoc_fw_reset()), returns 0
 * @return the i_d reference, Q15 of I_base, always in [pi.out_min, 0]; also
 *         stored in fw->id_ref.
 *
 * enable true:
 *   1. util_f = qfoc_lpf_step(utilisation)       (the filter's Q15 output)
 *   2. e = level - util_f                        (Q15, exact: both in [0, 32767])
 *   3. i_d_ref = qfoc_pi_step(e), limits [out_min, 0]
 *
 * Scaling and overflow: utilisation and level share the Q15 scaling of the
 * voltage utilisation (1.0 = the linear SVPWM limit); the filter state stays in
 * [0, 32767 x 65536] (convex combination of non-negative values), so util_f is in
 * [0, 32767] and level - util_f in [-32766, 32767] needs no saturation (the
 * saturating subtraction is kept for totality).  The error times the PI gains
 * gives a current in Q15 of I_base: the PI gains carry the unit change
 * (current per utilisation); all PI arithmetic is exact in 64 bits (pi.h) and
 * its output is clamped to [out_min, 0].
 *
 * Requirements: REQ-FW-003, REQ-FW-004, REQ-FW-005, REQ-FW-006.
 */
/*@
  requires valid_fw: \valid(fw);
  requires fw_valid: FwValid(fw);
  assigns fw->pi.integ, fw->pi.limited, fw->util_lpf.state, fw->id_ref;
  ensures still_valid: FwValid(fw);
  ensures range: fw->pi.params.out_min <= \result <= 0;
  ensures stored: \result == fw->id_ref;
  behavior active:
    assumes enable != 0;
    ensures util: fw->util_lpf.state ==
                  LpfNext(\old(fw->util_lpf.state), FwUtilIn(utilisation), fw->util_lpf.alpha);
    ensures integ: \let e = FwError(fw->level, fw->util_lpf.state);
                   fw->pi.integ == \old(PiNextInteg(&fw->pi, e));
    ensures result: \let e = FwError(fw->level, fw->util_lpf.state);
                    \result == FwPiOut(\old(PiNextSum(&fw->pi, e)), fw->pi.params.out_min, 0);
  behavior released:
    assumes enable == 0;
    ensures result: \result == 0;
    ensures cleared: fw->pi.integ == 0 && fw->util_lpf.state == 0 && fw->pi.limited == \false;
  complete behaviors;
  disjoint behaviors;
*/
qfoc_q15_t qfoc_fw_step(qfoc_fw_t *fw, qfoc_q15_t utilisation, bool enable);

#ifdef __cplusplus
}
#endif

#endif /* QFOC_FW_H */
