/**
 * @file pi.h
 * @brief Discrete PI controller with clamping anti-windup, Q15 in and out.
 *
 * One block serves the current loops (d and q), the speed loop, the
 * field-weakening loop and the PLL of the position observer.  It implements the
 * discrete PI of specs/equations.md E2-35 (speed loop E2-36, current loops E2-37):
 *
 *     u(k) = kp e(k) + I(k)
 *     I(k) = I(k-1) + ki T e(k)
 *
 * with e the control error, kp the proportional gain and ki T the integral
 * gain per sample (ki in 1/s times the sample time T in s).
 *
 * Gains: both gains are a Q15 mantissa and a left shift, so that gains above 1
 * are representable:
 *
 *     kp_real = kp / 32768 * 2^kp_shift        (kp in [0, 32767], kp_shift 0..15)
 *     kiT_real = ki / 32768 * 2^ki_shift       (ki in [0, 32767], ki_shift 0..15)
 *
 * (largest gain 32767/32768 * 2^15 = 32767).  Choose the smallest shift that
 * brings the mantissa below 32768, e.g. kp_real = 2.5 -> kp_shift = 2,
 * kp = 2.5 / 4 * 32768 = 20480.
 *
 * Anti-windup: clamping (conditional integration by saturating the integrator).
 * After every update the integrator is clamped to [out_min, out_max] (scaled to
 * Q31), and the output P + I is clamped to the same interval.  Reasons: (1) the
 * integrator can never hold more than the actuator can deliver, so after a long
 * saturation the output leaves the limit in the very sample in which the error
 * changes sign (no unwinding delay, no overshoot from stored windup); (2) it
 * needs no extra tuning parameter (a back-calculation gain would); (3) the
 * invariant "integrator inside the limits" is a simple interval that the proofs
 * and the CBMC harness carry from one sample to the next.
 *
 * The instance records whether the last output was clamped (`limited`, the
 * "limit reached" flag), which an outer loop can use, e.g. to stop a speed ramp.
 *
 * All functions are total on every value of their input types (e = -32768 is
 * accepted).  Parameters are checked by qfoc_pi_init(); the other functions
 * require a valid instance (qfoc_pi_is_valid(), ACSL predicate PiValid).
 *
 * Requirements: REQ-PI-001 .. REQ-PI-008 (specs/requirements/pi.md).
 */
#ifndef QFOC_PI_H
#define QFOC_PI_H

#include "qfoc/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/** qfoc_pi_init() status: parameters accepted. */
#define QFOC_PI_OK ((int32_t)0)
/** qfoc_pi_init() status: parameters rejected, instance set to the safe state. */
#define QFOC_PI_ERR_PARAM ((int32_t)-1)
/** Largest admissible kp_shift / ki_shift (gain factor 2^15 = 32768). */
#define QFOC_PI_SHIFT_MAX ((uint8_t)15u)

/** PI parameters (specs/equations.md E2-35: kp, ki T, output limits). */
typedef struct {
    qfoc_q15_t kp;       /**< proportional gain mantissa, Q15, >= 0 */
    uint8_t kp_shift;    /**< kp_real = kp / 32768 * 2^kp_shift, 0..15 */
    qfoc_q15_t ki;       /**< integral gain per sample (ki T) mantissa, Q15, >= 0 */
    uint8_t ki_shift;    /**< kiT_real = ki / 32768 * 2^ki_shift, 0..15 */
    qfoc_q15_t out_min;  /**< lower output limit, Q15, in [-32767, out_max] */
    qfoc_q15_t out_max;  /**< upper output limit, Q15, in [out_min, 32767] */
} qfoc_pi_params_t;

/** PI controller instance. */
typedef struct {
    qfoc_pi_params_t params;  /**< gains and limits */
    qfoc_q31_t integ;         /**< integrator I(k), Q31, in [out_min, out_max] x 65536 */
    bool limited;             /**< true when the last output was clamped to a limit */
} qfoc_pi_t;

#ifdef __FRAMAC__
/* ACSL predicates over the types above, read by Frama-C only (DEV-001). */
/* cppcheck-suppress misra-c2012-20.1 ; DEV-001 */
#include "pi.acsl"
#endif

/**
 * @brief Check a PI parameter set.
 * @param[in] p parameters (read only)
 * @return true when 0 <= kp, 0 <= ki, kp_shift <= 15, ki_shift <= 15 and
 *         -32767 <= out_min <= out_max <= 32767.
 *
 * Scaling and overflow: compares only.
 *
 * Requirements: REQ-PI-001.
 */
/*@
  requires valid_p: \valid_read(p);
  assigns \nothing;
  ensures result: \result <==> PiParamsValid(p);
*/
bool qfoc_pi_params_is_valid(const qfoc_pi_params_t *p);

/**
 * @brief Check a PI instance (the run-time twin of the ACSL predicate PiValid).
 * @param[in] pi instance (read only)
 * @return true when the parameters are valid and
 *         out_min x 65536 <= integ <= out_max x 65536.
 *
 * Scaling and overflow: the limits are widened Q15 -> Q31 (x 65536, exact in
 * 32 bits because |limit| <= 32767) before the compare.
 *
 * Requirements: REQ-PI-002.
 */
/*@
  requires valid_pi: \valid_read(pi);
  assigns \nothing;
  ensures result: \result <==> PiValid(pi);
*/
bool qfoc_pi_is_valid(const qfoc_pi_t *pi);

/**
 * @brief Initialise a PI instance: store the parameters and clear the state.
 * @param[out] pi instance to initialise
 * @param[in]  p  parameters (copied; not referenced afterwards)
 * @return QFOC_PI_OK (0) when the parameters are valid (qfoc_pi_params_is_valid());
 *         QFOC_PI_ERR_PARAM (-1) otherwise.
 *
 * Bad input: invalid parameters are not stored.  The instance is then set to the
 * safe state kp = ki = 0, both shifts 0, limits [0, 0]: it is valid, and every
 * later qfoc_pi_step() returns 0.  In both cases the integrator is set to the
 * value of [out_min, out_max] nearest to 0 (0 when the limits include 0) and
 * `limited` is false.
 *
 * Scaling and overflow: copies only.
 *
 * Requirements: REQ-PI-001, REQ-PI-003.
 */
/*@
  requires valid_pi: \valid(pi);
  requires valid_p: \valid_read(p);
  requires sep: \separated(pi, p);
  assigns *pi;
  ensures valid: PiValid(pi);
  ensures integ: pi->integ == QfocClamp(0, pi->params.out_min, pi->params.out_max) * 65536;
  ensures flag: pi->limited == \false;
  behavior accepted:
    assumes PiParamsValid(p);
    ensures result: \result == 0;
    ensures kp: pi->params.kp == p->kp && pi->params.kp_shift == p->kp_shift;
    ensures ki: pi->params.ki == p->ki && pi->params.ki_shift == p->ki_shift;
    ensures limits: pi->params.out_min == p->out_min && pi->params.out_max == p->out_max;
  behavior rejected:
    assumes !PiParamsValid(p);
    ensures result: \result == -1;
    ensures safe_gains: pi->params.kp == 0 && pi->params.ki == 0 &&
                        pi->params.kp_shift == 0 && pi->params.ki_shift == 0;
    ensures safe_limits: pi->params.out_min == 0 && pi->params.out_max == 0;
  complete behaviors;
  disjoint behaviors;
*/
int32_t qfoc_pi_init(qfoc_pi_t *pi, const qfoc_pi_params_t *p);

/**
 * @brief Bumpless preset: load the integrator so that the next output for a zero
 *        error equals `preset` (clamped to the limits).
 * @param[in,out] pi     instance with valid parameters
 * @param[in]     preset output value to start from, Q15, any int16_t
 *
 * Used when a loop is switched in (e.g. the speed loop takes over from an
 * open-loop start-up with the present current reference).  `limited` is cleared.
 *
 * Bad input: a preset outside [out_min, out_max] (-32768 included) is clamped.
 *
 * Scaling and overflow: Q15 -> Q31 by x 65536, exact in 32 bits after the clamp
 * (|value| <= 32767).
 *
 * Requirements: REQ-PI-006.
 */
/*@
  requires valid_pi: \valid(pi);
  requires params_valid: PiParamsValid(&pi->params);
  assigns pi->integ, pi->limited;
  ensures valid: PiValid(pi);
  ensures flag: pi->limited == \false;
  behavior upper:
    assumes preset > pi->params.out_max;
    ensures integ: pi->integ == pi->params.out_max * 65536;
  behavior between:
    assumes pi->params.out_min <= preset <= pi->params.out_max;
    ensures integ: pi->integ == preset * 65536;
  behavior lower:
    assumes preset < pi->params.out_min;
    ensures integ: pi->integ == pi->params.out_min * 65536;
  complete behaviors;
  disjoint behaviors;
*/
void qfoc_pi_reset(qfoc_pi_t *pi, qfoc_q15_t preset);

/**
 * @brief Set symmetric output limits [-lim, lim] on a running controller (a limit that
 *        moves with the operating point: the speed loop's q current under the
 *        current-vector limit, iref.h).
 * @param[in,out] pi  valid instance (qfoc_pi_is_valid())
 * @param[in]     lim the new limit, Q15, any int16_t: clamped to [0, 32767]
 *
 * The integrator is clamped into the new limits (it holds the output the controller
 * would give with a zero error, so a limit that falls takes it down with it: no windup);
 * the gains and the limit flag are unchanged.
 *
 * Scaling and overflow: the limit in Q15, x 65536 exact in 32 bits (|lim| <= 32767).
 *
 * Requirements: REQ-PI-009.
 */
/*@
  requires valid_pi: \valid(pi);
  requires pi_valid: PiValid(pi);
  assigns pi->params.out_min, pi->params.out_max, pi->integ;
  ensures valid: PiValid(pi);
  ensures limits: pi->params.out_max == QfocClamp(lim, 0, 32767) &&
                  pi->params.out_min == -pi->params.out_max;
  ensures integ: pi->integ == QfocClamp(\old(pi->integ), pi->params.out_min * 65536,
                                        pi->params.out_max * 65536);
*/
void qfoc_pi_set_limit(qfoc_pi_t *pi, qfoc_q15_t lim);

/**
 * @brief One PI sample: integrate the error, return the limited output.
 * @param[in,out] pi    valid instance (qfoc_pi_is_valid())
 * @param[in]     error control error e(k) = reference - feedback, Q15, any
 *                      int16_t (-32768 included)
 * @return u(k) = clamp(round(P + I(k)), out_min, out_max), Q15.
 *
 * Algorithm:
 *   1. P     = e kp 2^kp_shift                                 (Q31)
 *   2. I(k)  = clamp(I(k-1) + e ki 2^ki_shift, out_min, out_max) (Q31)
 *   3. u(k)  = clamp(P + I(k), out_min, out_max), rounded to Q15 (nearest,
 *              ties away from zero); limited = (the clamp in 3 was active).
 * The output equals the rounded P + I(k) exactly whenever P + I(k) lies within
 * the limits (contract behaviour `exact`).
 *
 * Scaling and overflow: e (1.15) x kp (1.15) = 2.30, |e kp| <= 32768 x 32767
 * < 2^30, exact in 32 bits; x 2^(kp_shift + 1) (2.30 -> 1.31, <= 2^16) in one
 * 32 x 32 -> 64 bit product gives |P| < 2^46, no overflow.  The increment
 * e ki 2^ki_shift x 2 is formed the same way (|.| < 2^46).  P and the increment
 * both have the sign of e (kp, ki >= 0), so only the limit on that side can be
 * reached: its distance from I(k-1), in [0, 2^32), is compared with the
 * increment's magnitude (anti-windup), and the distance left with |P| (output
 * clamp), so I(k) and the unclamped P + I(k) are formed exactly in 32 bits.  The
 * Q31 -> Q15 conversion rounds to nearest (error <= 1/2 LSB) and, because the
 * limits are multiples of 65536, stays inside the limits; a clamped output is
 * the limit itself.
 *
 * Requirements: REQ-PI-004, REQ-PI-005, REQ-PI-007, REQ-PI-008.
 */
/*@
  requires valid_pi: \valid(pi);
  requires pi_valid: PiValid(pi);
  assigns pi->integ, pi->limited;
  ensures still_valid: PiValid(pi);
  ensures range: pi->params.out_min <= \result <= pi->params.out_max;
  ensures integ: pi->integ == \old(PiNextInteg(pi, error));
  behavior exact:
    assumes pi->params.out_min * 65536 <= PiNextSum(pi, error) <= pi->params.out_max * 65536;
    ensures result: \result == QfocRoundDiv(\old(PiNextSum(pi, error)), 65536);
    ensures flag: pi->limited == \false;
  behavior upper:
    assumes PiNextSum(pi, error) > pi->params.out_max * 65536;
    ensures result: \result == pi->params.out_max;
    ensures flag: pi->limited == \true;
  behavior lower:
    assumes PiNextSum(pi, error) < pi->params.out_min * 65536;
    ensures result: \result == pi->params.out_min;
    ensures flag: pi->limited == \true;
  complete behaviors;
  disjoint behaviors;
*/
qfoc_q15_t qfoc_pi_step(qfoc_pi_t *pi, qfoc_q15_t error);

#ifdef __cplusplus
}
#endif

#endif /* QFOC_PI_H */
