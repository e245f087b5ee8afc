/**
 * @file filter.h
 * @brief First-order filters: low-pass (E2-33/E2-34) and leaky
 *        (high-pass-filtered) integrator (E2-14 .. E2-18).
 *
 * Equation tags E2-n: specs/equations.md (sections 4 and 6).
 *
 * Both blocks keep their state in Q31 so that small coefficients do not lose the
 * signal in the rounding of a 16-bit state, and return a Q15 output rounded to
 * nearest (ties away from zero).
 *
 * Requirements: REQ-FLT-001 .. REQ-FLT-008 (specs/requirements/filter.md).
 *
 * @par Low-pass filter (E2-33, E2-34)
 * G(s) = 1 / (tau s + 1), discretised with the forward difference s = (z - 1) / T:
 *
 *     y(k+1) = alpha u(k) + (1 - alpha) y(k) = y(k) + alpha (u(k) - y(k))
 *     alpha  = omega_c / f = 2 pi fc / fs          (fc cut-off, fs sample rate)
 *
 * Q15 coefficient: alpha_raw = round(2 pi fc / fs x 32768), e.g. fc = 50 Hz,
 * fs = 10 kHz: 2 pi 50 / 10000 x 32768 = 1029.4 -> 1029.  The forward
 * difference is stable and free of overshoot only for alpha in [0, 1]
 * (E2-34: alpha in [0, 1]), i.e. fc <= fs / (2 pi); the library admits
 * alpha_raw in [1, 32767].  The discrete pole is 1 - alpha: after n samples a
 * step has reached 1 - (1 - alpha)^n, 63 % after about 1 / alpha samples
 * (exactly ln(0.37) / ln(1 - alpha)).  DC gain is 1.
 *
 * @par Leaky integrator (E2-14 .. E2-18)
 * An integrator followed by a high-pass filter, (1/s) (tau s / (1 + tau s)) =
 * tau / (1 + tau s), used by the flux observer on each axis (x = u - R i).
 * Forward difference gives (E2-17):
 *
 *     y(k+1) = y(k) + T x(k) - (T / tau) y(k)
 *
 * Fixed point: gain = T x (input base / output base) as a Q15 mantissa with a
 * right shift, leak = T / tau in Q15:
 *
 *     g = gain / 32768 x 2^-gain_shift     (gain 0..32767, gain_shift 0..15:
 *                                           a larger shift makes the step SMALLER)
 *     l = leak / 32768                     (leak 0..32767; 0 = pure integrator)
 *
 * e.g. fs = 10 kHz (T = 100 us), voltage base 24 V, flux base 0.05 Wb:
 * T x 24 / 0.05 = 0.048 -> choose gain_shift = 4: 0.048 x 16 x 32768 = 25165.8
 * -> gain = 25166; tau = 20 ms: leak = 1e-4 / 0.02 x 32768 = 163.84 -> 164.
 *
 * Steady state (discrete transfer function H(z) = g / (z - (1 - l))):
 *  - DC: y = x g / l (= x tau (input base / output base)); this is the form of
 *    the flux bounds E2-25/E2-26, psi = (1 / k_g)(V_max u - R i / 64),
 *    with 1/k_g = g / l.
 *  - sine input x(k) = A sin(W k), W = 2 pi f_in / fs (rad per sample):
 *        y(k) = A |H| sin(W k + phi)
 *        |H|  = g / sqrt(1 - 2 (1 - l) cos W + (1 - l)^2)
 *        phi  = -atan2(sin W, cos W - (1 - l))
 *    For l << W << 1 (f_in well above 1 / (2 pi tau), well below fs)
 *    |H| ~ g / W = (input base / output base) / omega_in with
 *    omega_in = 2 pi f_in: the amplitude of the ideal integral A / omega_in, and
 *    phi ~ -90 deg - W/2 + l / W (forward-difference delay of half a sample,
 *    high-pass phase lead that removes the integrator drift).
 *  - Bound: for any |x| <= X, a state that starts within X g / l stays within
 *    X g / l (geometric sum), so g <= l (tau x input base / output base <= 1)
 *    guarantees that the state never saturates for a full-scale input;
 *    otherwise the state saturates at the symmetric Q31 limits.
 *  - Accuracy: two roundings of at most 1/2 Q31 LSB per sample, decaying with
 *    (1 - l): after k samples the state is within min(k, 32768 / leak) Q31 LSB
 *    of the real-valued recursion (e.g. leak = 164: 200 Q31 LSB = 0.003 Q15 LSB).
 */
#ifndef QFOC_FILTER_H
#define QFOC_FILTER_H

#include "qfoc/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Filter init status: coefficients accepted. */
#define QFOC_FILTER_OK ((int32_t)0)
/** Filter init status: coefficients rejected, instance set to the safe state. */
#define QFOC_FILTER_ERR_PARAM ((int32_t)-1)
/** Largest admissible leaky-integrator gain_shift (gain factor 2^-15). */
#define QFOC_LEAKY_SHIFT_MAX ((uint8_t)15u)

/** First-order low-pass filter (E2-34). */
typedef struct {
    qfoc_q15_t alpha;   /**< omega_c / f, Q15, 1..32767 */
    qfoc_q31_t state;   /**< y(k), Q31, symmetric Q31 range; within
                             [-32767, 32767] x 65536 after init/reset/step */
} qfoc_lpf_t;

/** Leaky (high-pass-filtered) integrator (E2-17). */
typedef struct {
    qfoc_q15_t gain;     /**< T x (input base / output base) mantissa, Q15, >= 0 */
    uint8_t gain_shift;  /**< g = gain / 32768 / 2^gain_shift, 0..15 */
    qfoc_q15_t leak;     /**< T / tau, Q15, 0..32767 */
    qfoc_q31_t state;    /**< y(k), Q31, symmetric Q31 range */
} qfoc_leaky_int_t;

#ifdef __FRAMAC__
/* ACSL predicates over the types above, read by Frama-C only (DEV-001). */
/* cppcheck-suppress misra-c2012-20.1 ; DEV-001 */
#include "filter.acsl"
#endif

/**
 * @brief Check a low-pass instance (run-time twin of LpfValid).
 * @param[in] f instance (read only)
 * @return true when 0 < alpha and the state is in the symmetric Q31 range
 *         (-2^31 excluded).  The state stays within the narrower range
 *         [-32767, 32767] x 65536 once it has been set by qfoc_lpf_init(),
 *         qfoc_lpf_reset() or a step (contract of qfoc_lpf_step, `q15_range`).
 *
 * Scaling and overflow: compares only.
 *
 * Requirements: REQ-FLT-001.
 */
/*@
  requires valid_f: \valid_read(f);
  assigns \nothing;
  ensures result: \result <==> LpfValid(f);
*/
bool qfoc_lpf_is_valid(const qfoc_lpf_t *f);

/**
 * @brief Initialise a low-pass filter with coefficient alpha; the state is 0.
 * @param[out] f     instance
 * @param[in]  alpha omega_c / f in Q15, valid range 1..32767
 * @return QFOC_FILTER_OK (0), or QFOC_FILTER_ERR_PARAM (-1) when alpha <= 0.
 *
 * Bad input: alpha <= 0 is rejected and alpha = 32767 is stored instead (safe
 * state: the filter passes its input on with one sample delay and an error of at
 * most 1 LSB, so a signal chain stays alive and bounded); the state is 0.
 *
 * Scaling and overflow: copies only.
 *
 * Requirements: REQ-FLT-001.
 */
/*@
  requires valid_f: \valid(f);
  assigns *f;
  ensures valid: LpfValid(f);
  ensures state: f->state == 0;
  behavior accepted:
    assumes alpha > 0;
    ensures result: \result == 0;
    ensures alpha: f->alpha == alpha;
  behavior rejected:
    assumes alpha <= 0;
    ensures result: \result == -1;
    ensures alpha: f->alpha == 32767;
  complete behaviors;
  disjoint behaviors;
*/
int32_t qfoc_lpf_init(qfoc_lpf_t *f, qfoc_q15_t alpha);

/**
 * @brief Set the low-pass output (state) to a value.
 * @param[in,out] f     instance with 0 < alpha
 * @param[in]     value new output, Q15, any int16_t (-32768 is saturated to -32767)
 *
 * Scaling and overflow: Q15 -> Q31 by x 65536, exact after saturation.
 *
 * Requirements: REQ-FLT-001.
 */
/*@
  requires valid_f: \valid(f);
  requires alpha_valid: 0 < f->alpha;
  assigns f->state;
  ensures valid: LpfValid(f);
  ensures q15_range: FilterQ15InQ31(f->state);
  ensures state: f->state == QfocSat15(value) * 65536;
*/
void qfoc_lpf_reset(qfoc_lpf_t *f, qfoc_q15_t value);

/**
 * @brief One low-pass sample (E2-34): y(k+1) = y(k) + alpha (u(k) - y(k)).
 * @param[in,out] f valid instance (qfoc_lpf_is_valid())
 * @param[in]     u input u(k), Q15, any int16_t (-32768 is saturated to -32767)
 * @return the new output y(k+1), Q15 (state rounded to nearest).
 *
 * The new state is a convex combination of the input and the old state: it lies
 * between them (inclusive) exactly in Q31, and the Q15 output lies between the
 * input and the previous output.  Hence the filter never overshoots and never
 * overflows, and a state within [-32767, 32767] x 65536 stays there.
 *
 * Scaling and overflow: u (1.15) x 65536 -> 1.31; the distance |u - y| < 2^32 is
 * formed unsigned on the side given by the compare of u and y; (alpha x 2^17) x
 * |u - y| + 2^31 (< 2^64, one unsigned 32 x 32 -> 64 bit multiply-accumulate) has
 * the rounded increment magnitude round(alpha |u - y| / 32768) as its high
 * word, which is at most |u - y| because alpha < 32768, so y +- that magnitude
 * stays between y and u and fits 32 bits.  Output: Q31 -> Q15 rounded (error
 * <= 1/2 LSB), saturated to [-32767, 32767] (only a state set beyond the Q15
 * range by the caller reaches the saturation).  The increment's
 * rounding (<= 1/2 Q31 LSB) makes the state settle within 16384 / alpha Q31 LSB
 * (<= 1/4 Q15 LSB) of a constant input, so the Q15 DC gain is exactly 1.
 * Error against the real-valued recursion (E2-34): the increment roundings
 * accumulate to at most 1/2 Q31 LSB / (alpha / 32768) = 1/4 Q15 LSB / alpha_raw
 * in the state (<= 0.25 LSB), hence <= 0.75 LSB at the Q15 output.
 *
 * Requirements: REQ-FLT-002, REQ-FLT-003, REQ-FLT-004.
 */
/*@
  requires valid_f: \valid(f);
  requires f_valid: LpfValid(f);
  assigns f->state;
  ensures still_valid: LpfValid(f);
  ensures state: f->state == LpfNext(\old(f->state), u, f->alpha);
  ensures q15_range: FilterQ15InQ31(\old(f->state)) ==> FilterQ15InQ31(f->state);
  ensures result: \result == QfocSat15(QfocRoundDiv(f->state, 65536));
  ensures range: QfocQ15Sym(\result);
  behavior rising:
    assumes LpfInput(u) >= f->state;
    ensures between: \old(f->state) <= f->state <= LpfInput(u);
    ensures out_between: QfocRoundDiv(\old(f->state), 65536) <= \result <= QfocSat15(u);
  behavior falling:
    assumes LpfInput(u) < f->state;
    ensures between: LpfInput(u) <= f->state <= \old(f->state);
    ensures out_between: QfocSat15(u) <= \result <= QfocRoundDiv(\old(f->state), 65536);
  complete behaviors;
  disjoint behaviors;
*/
qfoc_q15_t qfoc_lpf_step(qfoc_lpf_t *f, qfoc_q15_t u);

/**
 * @brief Check a leaky-integrator instance (run-time twin of LeakyValid).
 * @param[in] f instance (read only)
 * @return true when gain >= 0, gain_shift <= 15, leak >= 0 and the state is in
 *         the symmetric Q31 range.
 *
 * Scaling and overflow: compares only.
 *
 * Requirements: REQ-FLT-005.
 */
/*@
  requires valid_f: \valid_read(f);
  assigns \nothing;
  ensures result: \result <==> LeakyValid(f);
*/
bool qfoc_leaky_is_valid(const qfoc_leaky_int_t *f);

/**
 * @brief Initialise a leaky integrator; the state is 0.
 * @param[out] f          instance
 * @param[in]  gain       T x (input base / output base) mantissa, Q15, 0..32767
 * @param[in]  gain_shift right shift of the gain, 0..15 (g = gain / 2^(15 + gain_shift))
 * @param[in]  leak       T / tau, Q15, 0..32767
 * @return QFOC_FILTER_OK (0), or QFOC_FILTER_ERR_PARAM (-1) when gain < 0,
 *         gain_shift > 15 or leak < 0.
 *
 * Bad input: the coefficients are not stored; the safe state gain = 0,
 * gain_shift = 0, leak = 32767, state = 0 is set instead (output stays 0).
 *
 * Scaling and overflow: copies only.
 *
 * Requirements: REQ-FLT-005.
 */
/*@
  requires valid_f: \valid(f);
  assigns *f;
  ensures valid: LeakyValid(f);
  ensures state: f->state == 0;
  behavior accepted:
    assumes 0 <= gain && gain_shift <= 15 && 0 <= leak;
    ensures result: \result == 0;
    ensures coeffs: f->gain == gain && f->gain_shift == gain_shift && f->leak == leak;
  behavior rejected:
    assumes gain < 0 || gain_shift > 15 || leak < 0;
    ensures result: \result == -1;
    ensures coeffs: f->gain == 0 && f->gain_shift == 0 && f->leak == 32767;
  complete behaviors;
  disjoint behaviors;
*/
int32_t qfoc_leaky_init(qfoc_leaky_int_t *f, qfoc_q15_t gain, uint8_t gain_shift,
                        qfoc_q15_t leak);

/**
 * @brief Set the leaky-integrator output (state) to a value.
 * @param[in,out] f     instance
 * @param[in]     value new output, Q15, any int16_t (-32768 is saturated to -32767)
 *
 * Scaling and overflow: Q15 -> Q31 by x 65536, exact after saturation.
 *
 * Requirements: REQ-FLT-005.
 */
/*@
  requires valid_f: \valid(f);
  requires coeffs_valid: 0 <= f->gain && f->gain_shift <= 15 && 0 <= f->leak;
  assigns f->state;
  ensures valid: LeakyValid(f);
  ensures state: f->state == QfocSat15(value) * 65536;
*/
void qfoc_leaky_reset(qfoc_leaky_int_t *f, qfoc_q15_t value);

/**
 * @brief One leaky-integrator sample (E2-17): y(k+1) = y(k) + T x(k) - (T/tau) y(k).
 * @param[in,out] f valid instance (qfoc_leaky_is_valid())
 * @param[in]     x input x(k), Q15, any int16_t (-32768 included, used as -1.0)
 * @return the new output y(k+1), Q15 (state rounded to nearest, saturated to
 *         [-32767, 32767]).
 *
 * Scaling and overflow: x (1.15) x gain (1.15) = 2.30, |x gain| < 2^30, exact in
 * 32 bits; x 2 -> 1.31 and / 2^gain_shift rounded to nearest gives the Q31
 * integration step (|.| <= 2^31, formed in 64 bits).  leak (1.15) x y (1.31) =
 * 2.46 in 64 bits (|.| < 2^46), / 32768 rounded gives the Q31 leak term, at most
 * |y| in magnitude.  y + step - leak term is formed in 64 bits (|.| < 2^33) and
 * saturated to the symmetric Q31 range, which is the invariant.  Rounding error
 * per sample <= 1 Q31 LSB (two roundings of 1/2 LSB).
 *
 * Requirements: REQ-FLT-006, REQ-FLT-007, REQ-FLT-008.
 */
/*@
  requires valid_f: \valid(f);
  requires f_valid: LeakyValid(f);
  assigns f->state;
  ensures still_valid: LeakyValid(f);
  ensures result: \result == QfocSat15(QfocRoundDiv(f->state, 65536));
  ensures range: QfocQ15Sym(\result);
  behavior exact:
    assumes QfocQ31Sym(LeakySum(f, x));
    ensures state: f->state == \old(LeakySum(f, x));
  behavior upper:
    assumes LeakySum(f, x) > 2147483647;
    ensures state: f->state == 2147483647;
  behavior lower:
    assumes LeakySum(f, x) < -2147483647;
    ensures state: f->state == -2147483647;
  complete behaviors;
  disjoint behaviors;
*/
qfoc_q15_t qfoc_leaky_step(qfoc_leaky_int_t *f, qfoc_q15_t x);

#ifdef __cplusplus
}
#endif

#endif /* QFOC_FILTER_H */
