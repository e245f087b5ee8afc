/**
 * @file emf.h
 * @brief Back-EMF estimator (open loop) and disturbance observer (closed loop):
 *        rotor angle of a PMSM from the stationary-frame voltage and current.
 *
 * Two blocks, one method family, the model-based estimators of specs/equations.md
 * section 2 (equation tags E1-n, E2-n of that file):
 *  - qfoc_emf_*: the open-loop back-EMF method (E1-11): the EMF is computed
 *    from the voltage equation and low-pass filtered (E2-33, E2-34);
 *  - qfoc_dob_*: the closed-loop disturbance observer (E1-13, E1-14): a current
 *    model driven by the voltage, whose current error is turned into the EMF
 *    estimate.
 * Both give the EMF vector and its angle theta = atan2(-e_alpha, e_beta); the
 * angle lags the rotor by a known amount that qfoc_emf_lag() / qfoc_dob_lag()
 * return for compensation.  Instead of the arctangent, the EMF can drive the
 * angle-tracking observer qfoc_pll_step_emf() of pll.h (speed and angle from a
 * PLL, less noise, no division), the alternative to the arctangent named with
 * E1-15.
 *
 * Requirements: REQ-EMF-001 .. REQ-EMF-014 (specs/requirements/emf.md); each
 * function below names the ones it meets.
 *
 * @par Machine model (E1-6 .. E1-10) and the choice L = L_q
 * Stationary frame, per unit, p = d/dt:
 *
 *     u = R i + p psi_s,   psi_s = rotor-frame (L_d i_d + psi_f, L_q i_q) rotated by theta
 *
 * The extended-EMF form of the salient machine (E1-9) is
 * u = R i + L_d p i + (cross term) + E (-sin theta, cos theta) with the extended EMF
 * E = omega ((L_d - L_q) i_d + psi_f) - (L_d - L_q) p i_q.  qfoc uses L = L_q
 * instead ("active flux"): the active flux
 *
 *     psi_a = psi_s - L_q i = (psi_f + (L_d - L_q) i_d) (cos theta, sin theta)
 *
 * lies exactly on the rotor d axis for ANY load, so
 *
 *     e = u - R i - L_q p i = p psi_a
 *       = omega |psi_a| (-sin theta, cos theta) + (p |psi_a|) (cos theta, sin theta)
 *
 * In steady state (|psi_a| constant) e points exactly along
 * (-sin theta, cos theta), so atan2(-e_alpha, e_beta) = theta for omega > 0,
 * for salient and non-salient machines alike: this is the extended EMF of E1-9
 * with the saliency term (L_d - L_q) i_d absorbed into |psi_a| and no
 * speed-dependent cross term (E1-10).  The mean inductance (L_d + L_q)/2 is
 * exact only for L_d = L_q (on the reference motor below, with i_q = 20 A it
 * puts the angle 14 degrees off).  For omega < 0, e points along
 * (sin theta, -cos theta): the arctangent gives theta + 180 degrees, which the
 * caller corrects by adding 0x8000 (the angle-tracking observer of pll.h does
 * it with the sign of its speed).
 *
 * @par Discrete form: what one call sees
 * A call at sample k receives u = the stationary-frame voltage APPLIED during
 * the last PWM period [k-1, k] (its period average; with compare registers that
 * take effect one period after they are written, this is the command computed
 * two calls earlier) and i = the current sampled now at k.  Integrating the
 * model over the period exactly:
 *
 *     u = R i_mean + L_q (i(k) - i(k-1)) / T + (psi_a(k) - psi_a(k-1)) / T
 *
 * With i_mean = (i(k) + i(k-1)) / 2 (trapezoid), both blocks measure
 *
 *     e_raw(k) = u - R (i(k) + i(k-1)) / 2 - L_q (i(k) - i(k-1)) / T
 *              = (psi_a(k) - psi_a(k-1)) / T
 *
 * a difference quotient centred half a sample back.  For a flux rotating at
 * omega (W = omega T rad per sample) this is
 * omega |psi_a| sinc(W/2) (-sin, cos)(theta(k) - W/2): the angle lags by
 * exactly W/2 and the magnitude is omega |psi_a| sin(W/2)/(W/2).  (Taking
 * R i(k) instead of the mean, as a plain forward difference would, adds an
 * angle error of R |i| W/2 / (omega |psi_a|) = R |i| T w_base / (2 |psi_a|),
 * independent of speed: 0.39 degrees at 20 A on the reference motor.)
 *
 * @par Back-EMF block
 *
 *     e_raw(k) = u - R (i(k) + i(k-1))/2 - l (i(k) - i(k-1)),   l = L_q / (T w_base)
 *     e(k)     = e(k-1) + alpha (e_raw(k) - e(k-1))              (E2-34, qfoc_lpf_step)
 *     theta    = atan2(-e_alpha, e_beta)
 *
 * @par Disturbance observer (E1-13, E1-14, with the sign of the resistive term)
 * An earlier statement of the current model, d i/dt = +(R/L) i + (u - e)/L, and of
 * the observer, d i_hat/dt = +(R/L) i + (u - e_hat)/L, d e_hat/dt = G d(i_hat - i)/dt,
 * had the resistive term with the wrong sign: from u = R i + L di/dt + e,
 * d i/dt = -(R/L) i + (u - e)/L (E1-13).  qfoc implements the corrected observer
 *
 *     d i_hat/dt = -(R/L) i + (u - e_hat)/L,     e_hat = G (i_hat - i)
 *
 * (the second equation integrated with zero initial error), L = L_q, per call:
 *
 *     i_hat(k) = i_hat(k-1) + k_i (u - R (i(k) + i(k-1))/2 - e_hat(k-1))   current model
 *     e_hat(k) = G (i_hat(k) - i(k))                                       EMF from the error
 *
 * with k_i = T w_base / L_q_pu (the current change per sample per unit of
 * voltage).  The resistive drop is the period mean like in the back-EMF block
 * (the measured i(k) is known when the model is advanced).  Subtracting the
 * exact period model of the motor, i(k) = i(k-1) + k_i (u - R i_mean - e_raw(k)),
 * and multiplying by G gives
 *
 *     e_hat(k) = e_hat(k-1) + lambda (e_raw(k) - e_hat(k-1)),   lambda = k_i G
 *
 * the same first-order low-pass of the same e_raw as the back-EMF block with
 * alpha = lambda: stable for 0 < lambda < 2, monotone for lambda <= 1
 * (qfoc_dob_init() accepts 0 < lambda <= 1), lambda = 1 gives e_hat = e_raw.
 * The observer never forms the difference quotient; its state is the predicted
 * current, kept in Q4.27 (+-16 pu) because i_hat = i + e_hat / G exceeds 1 pu
 * when G < 1 (reference tuning: e_hat / G up to 0.49 pu at 0.8 pu speed).
 *
 * @par Lag of the estimates and its compensation
 * For a rotor turning at w (Q15 of w_base), W = w T w_base rad per sample, the
 * estimated angle lags the true rotor angle at the sample instant by
 *
 *     lag(W) = W/2 + atan2((1 - a) sin W, 1 - (1 - a) cos W)
 *
 * W/2 from the difference quotient, the second term the phase of the low-pass
 * y(k) = y(k-1) + a (x(k) - y(k-1)) (a = alpha, or lambda for the observer), and
 * the magnitude is w |psi_a| sinc(W/2) |H(W)| with
 * |H| = a / sqrt(1 - 2 (1 - a) cos W + (1 - a)^2).  qfoc_emf_lag() and
 * qfoc_dob_lag() return lag(W) in angle counts (negative, i.e. modulo 2^16, for
 * w < 0); the rotor angle is theta + lag (plus 0x8000 for w < 0, see above):
 *
 *     rotor = (theta + qfoc_emf_lag(&emf, w) + (w < 0 ? 0x8000 : 0)) mod 2^16
 *
 * Reference motor (8 kHz, f_base 500 Hz, alpha = lambda = 0.25): lag = 7.8,
 * 22.4, 39.6, 48.0 degrees and |H| sinc = 0.991, 0.925, 0.774, 0.675 at
 * w = 0.1, 0.3, 0.6, 0.8 pu.  With the compensation the angle error measured on
 * the reference motor (rotating active flux 0.408 pu, current 0.5 pu) is below
 * 0.05 degree at 0.1 .. 0.8 pu for both blocks, the requirement being 0.5 degree
 * (tests/test_emf.c, REQ-EMF-013).
 *
 * @par Parameters from base values (specs/scaling.md)
 * w_base = 2 pi f_base, Z_base = V_base / I_base, L_base = Z_base / w_base,
 * g = T w_base = w_base / f_pwm.
 *  - r = R / Z_base in Q15 (both blocks);
 *  - l = L_q / L_base / g = L_q f_pwm I_base / V_base in Q10 (raw / 1024, up to
 *    32 pu), back-EMF block;
 *  - alpha = 2 pi f_c / f_pwm in Q15 (cut-off f_c of the EMF low-pass), back-EMF
 *    block;
 *  - k_i = g / (L_q / L_base) as a Q15 mantissa ki and a shift:
 *    k_i = ki / 2^(15 + ki_shift); choose the largest ki_shift that keeps
 *    ki <= 32767 (k_i < 1 always: full voltage over one PWM period moves the
 *    current by less than I_base for any sensible base choice);
 *  - G in Q12 (raw / 4096), chosen for the observer bandwidth lambda = k_i G:
 *    G = lambda / k_i;
 *  - k_theta = round(f_base / f_pwm x 131072) (as the PLL): angle increment in
 *    2^-32 turns per speed LSB per sample, used only for the lag.
 * Reference motor (V_base 500 V, I_base 40 A, f_base 500 Hz, f_pwm 8 kHz,
 * R = 0.35 ohm, L_q = 4.2 mH): Z_base = 12.5 ohm, L_base = 3.97887 mH,
 * g = 0.392699, R_pu = 0.028 -> r = 918 (917.5), L_q_pu = 1.05558 ->
 * l = 1.05558 / 0.392699 = 2.68802 -> 2753; k_i = 0.392699 / 1.05558 =
 * 0.372020 -> ki_shift = 1, ki = 0.372020 x 65536 = 24380.8 -> 24381;
 * lambda = 0.25 -> G = 0.25 / (24381 / 65536) = 0.671999 -> 2752.5 -> g = 2753
 * (lambda = 24381 x 2753 / 2^28 = 0.25005); alpha = 0.25 -> 8192
 * (f_c = 318 Hz); k_theta = 500 / 8000 x 131072 = 8192.
 *
 * @par Bad input
 * Every input value of every type is accepted: voltages and currents are
 * saturated to [-32767, 32767] first (-32768 is read as -32767), the speed of
 * the lag functions likewise.  Parameters are checked by qfoc_emf_init() /
 * qfoc_dob_init(); rejected parameters leave the instance in a safe state
 * whose outputs are EMF 0 and angle 0 (an angle-tracking observer with a
 * magnitude threshold then coasts) and whose lag is 0.  The step, reset and lag
 * functions require a valid instance (qfoc_emf_is_valid(), qfoc_dob_is_valid():
 * the run-time twins of the ACSL predicates EmfValid, DobValid).  Estimates are
 * meaningful only above a minimum speed (the EMF is proportional to speed; at
 * standstill it is 0 and the angle is undefined): start the drive in open loop.
 */
#ifndef QFOC_EMF_H
#define QFOC_EMF_H

#include "qfoc/types.h"
#include "qfoc/filter.h"

#ifdef __cplusplus
extern "C" {
#endif

/** qfoc_emf_init() / qfoc_dob_init() status: parameters accepted. */
#define QFOC_EMF_OK ((int32_t)0)
/** qfoc_emf_init() / qfoc_dob_init() status: parameters rejected, safe state set. */
#define QFOC_EMF_ERR_PARAM ((int32_t)-1)
/** Largest admissible k_theta (f_base / f_pwm < 1/4). */
#define QFOC_EMF_KTHETA_MAX ((uint16_t)32767u)
/** Largest admissible observer gain shift ki_shift (k_i factor 2^-15). */
#define QFOC_DOB_SHIFT_MAX ((uint8_t)15u)

/** Back-EMF estimator parameters. */
typedef struct {
    qfoc_q15_t r;      /**< R / Z_base, Q15, >= 0 */
    qfoc_q15_t l;      /**< L_q / L_base / (T w_base) = L_q f_pwm I_base / V_base,
                            Q10 (raw / 1024), >= 0 */
    qfoc_q15_t alpha;  /**< EMF low-pass coefficient 2 pi f_c / f_pwm, Q15, 1..32767 */
    uint16_t k_theta;  /**< round(f_base / f_pwm x 131072), 1..32767 (lag only) */
} qfoc_emf_params_t;

/** Output of one estimator step (both blocks). */
typedef struct {
    qfoc_ab_t emf;       /**< EMF estimate, Q15 of V_base, symmetric range */
    qfoc_angle_t theta;  /**< atan2(-emf.alpha, emf.beta): rotor angle minus the lag
                              (plus 180 degrees for negative speed) */
} qfoc_emf_out_t;

/** Back-EMF estimator instance. */
typedef struct {
    qfoc_emf_params_t params;  /**< parameters (copied by qfoc_emf_init()) */
    qfoc_ab_t i_prev;          /**< current of the previous call, Q15, symmetric */
    qfoc_lpf_t lpf_alpha;      /**< EMF low-pass, alpha axis (E2-34) */
    qfoc_lpf_t lpf_beta;       /**< EMF low-pass, beta axis (E2-34) */
    bool active;               /**< false after a rejected init: output held at 0 */
} qfoc_emf_t;

/** Disturbance-observer parameters. */
typedef struct {
    qfoc_q15_t ki;     /**< k_i = T w_base / L_q_pu mantissa, Q15, 1..32767 */
    uint8_t ki_shift;  /**< k_i = ki / 2^(15 + ki_shift), 0..15 */
    qfoc_q15_t r;      /**< R / Z_base, Q15, >= 0 */
    qfoc_q15_t g;      /**< observer gain G, Q12 (raw / 4096), > 0, with
                            lambda = k_i G <= 1 */
    uint16_t k_theta;  /**< round(f_base / f_pwm x 131072), 1..32767 (lag only) */
} qfoc_dob_params_t;

/** Disturbance-observer instance. */
typedef struct {
    qfoc_dob_params_t params;  /**< parameters (copied by qfoc_dob_init()) */
    int32_t ih_alpha;          /**< predicted current i_hat, alpha, Q4.27
                                    (raw / 2^27 of I_base, +-16 pu), symmetric */
    int32_t ih_beta;           /**< predicted current i_hat, beta, Q4.27 */
    qfoc_ab_t i_prev;          /**< current of the previous call, Q15, symmetric */
    qfoc_ab_t e_prev;          /**< EMF estimate of the previous call, Q15, symmetric */
} qfoc_dob_t;

#ifdef __FRAMAC__
/* ACSL predicates over the types above, read by Frama-C only (DEV-001). */
/* cppcheck-suppress misra-c2012-20.1 ; DEV-001 */
#include "emf.acsl"
#endif

/**
 * @brief Check a back-EMF parameter set (run-time twin of EmfParamsValid).
 * @param[in] p parameters (read only)
 * @return true when r >= 0, l >= 0, alpha >= 1 and 1 <= k_theta <= 32767.
 *
 * Scaling and overflow: compares only.
 *
 * Requirements: REQ-EMF-001.
 */
/*@
  requires valid_p: \valid_read(p);
  assigns \nothing;
  ensures result: \result <==> EmfParamsValid(p);
*/
bool qfoc_emf_params_is_valid(const qfoc_emf_params_t *p);

/**
 * @brief Check a back-EMF instance (run-time twin of EmfValid).
 * @param[in] e instance (read only)
 * @return true when r >= 0, l >= 0, alpha >= 1, k_theta <= 32767, both filters
 *         are valid (qfoc_lpf_is_valid()) with the coefficient alpha, the
 *         previous current is in the symmetric Q15 range, and an inactive
 *         instance has both filter states at 0.
 *
 * Scaling and overflow: compares only.
 *
 * Requirements: REQ-EMF-001.
 */
/*@
  requires valid_e: \valid_read(e);
  assigns \nothing;
  ensures result: \result <==> EmfValid(e);
*/
bool qfoc_emf_is_valid(const qfoc_emf_t *e);

/**
 * @brief Initialise a back-EMF estimator: store the parameters, clear the state.
 * @param[out] e instance
 * @param[in]  p parameters (copied; not referenced afterwards)
 * @return QFOC_EMF_OK (0) when qfoc_emf_params_is_valid(p), else
 *         QFOC_EMF_ERR_PARAM (-1).
 *
 * Accepted: both low-pass filters get alpha, their states and i_prev are 0, the
 * instance is active.  Call qfoc_emf_reset() with the present current before
 * the first step (otherwise the first difference quotient sees the jump from 0).
 *
 * Bad input: rejected parameters are not stored; the safe state r = 0, l = 0,
 * alpha = 32767, k_theta = 0, all states 0 and active = false is set instead:
 * it is valid, every later qfoc_emf_step() outputs EMF 0 and angle 0, and
 * qfoc_emf_lag() returns 0.
 *
 * Scaling and overflow: copies only.
 *
 * Requirements: REQ-EMF-001.
 */
/*@
  requires valid_e: \valid(e);
  requires valid_p: \valid_read(p);
  requires sep: \separated(e, p);
  assigns *e;
  ensures valid: EmfValid(e);
  ensures state: e->lpf_alpha.state == 0 && e->lpf_beta.state == 0;
  ensures i_prev: e->i_prev.alpha == 0 && e->i_prev.beta == 0;
  behavior accepted:
    assumes EmfParamsValid(p);
    ensures result: \result == 0;
    ensures active: e->active == 1;
    ensures params: e->params.r == p->r && e->params.l == p->l &&
                    e->params.alpha == p->alpha && e->params.k_theta == p->k_theta;
  behavior rejected:
    assumes !EmfParamsValid(p);
    ensures result: \result == -1;
    ensures inactive: e->active == 0;
    ensures safe: e->params.r == 0 && e->params.l == 0 &&
                  e->params.alpha == 32767 && e->params.k_theta == 0;
  complete behaviors;
  disjoint behaviors;
*/
int32_t qfoc_emf_init(qfoc_emf_t *e, const qfoc_emf_params_t *p);

/**
 * @brief Restart a back-EMF estimator from the present current.
 * @param[in,out] e  valid instance
 * @param[in]     i0 present stationary-frame current, Q15, any value
 *                   (saturated to the symmetric range)
 *
 * The EMF estimate restarts from 0 (it converges within a few multiples of
 * 1 / alpha samples, 63 % after 1 / alpha); i_prev = i0, so the first
 * difference quotient is i(k) - i0.  Use it when the estimator is switched in
 * (e.g. at the end of the open-loop start-up).  Parameters and the active flag
 * are kept.
 *
 * Scaling and overflow: saturation only.
 *
 * Requirements: REQ-EMF-002.
 */
/*@
  requires valid_e: \valid(e);
  requires valid_i0: \valid_read(i0);
  requires sep: \separated(e, i0);
  requires e_valid: EmfValid(e);
  assigns e->i_prev, e->lpf_alpha.state, e->lpf_beta.state;
  ensures valid: EmfValid(e);
  ensures state: e->lpf_alpha.state == 0 && e->lpf_beta.state == 0;
  ensures i_prev: e->i_prev.alpha == QfocSat15(i0->alpha) &&
                  e->i_prev.beta == QfocSat15(i0->beta);
*/
void qfoc_emf_reset(qfoc_emf_t *e, const qfoc_ab_t *i0);

/**
 * @brief One back-EMF sample: EMF from the voltage equation, low-pass, angle.
 * @param[in,out] e   valid instance (qfoc_emf_is_valid())
 * @param[in]     u   voltage applied during the last PWM period [k-1, k],
 *                    stationary frame, Q15 of V_base, any value
 * @param[in]     i   current sampled now (k), stationary frame, Q15 of I_base,
 *                    any value
 * @param[out]    out out->emf = filtered EMF (Q15 of V_base),
 *                    out->theta = atan2(-emf.alpha, emf.beta)
 *
 * Per axis: e_raw = sat(round((65536 u - r (i + i_prev) - 64 l (i - i_prev))
 * / 65536)), emf = qfoc_lpf_step(e_raw) (coefficient lpf_*.alpha = alpha),
 * i_prev = i; an inactive instance (rejected init) uses e_raw = 0, so its
 * output stays EMF 0, angle 0.
 * theta = rotor angle - qfoc_emf_lag() (+ 180 degrees for negative speed).
 *
 * Accuracy: e_raw is the exact Q31 value rounded once (<= 1/2 LSB) unless it
 * saturates; the output is within 1.25 LSB of the real-valued recursion
 * (rounding 1/2 LSB filtered, low-pass 0.75 LSB, filter.h).  The angle carries
 * qfoc_atan2's <= 1 count plus the EMF's relative error.
 *
 * Bad input: any u, i (saturated first).  The difference quotient amplifies
 * current noise by l (2.7 on the reference motor): filter with alpha.
 *
 * Scaling and overflow: u, i saturated to [-32767, 32767].
 * 65536 u: Q15 -> Q31 (|.| <= 2147418112).  r (Q15) x (i + i_prev)
 * (|.| <= 65534) = Q30 of the sum = Q31 of the mean, |.| <= 2147352578 < 2^31:
 * exact in 32 bits.  l (Q10) x (i - i_prev) = Q25, |.| <= 2147352578, exact in
 * 32 bits; x 64 -> Q31 in 64 bits (< 2^37).  The sum (< 2^38, 64 bits) is
 * divided by 65536 with rounding to nearest, ties away from zero (division by
 * a constant power of two) and saturated to Q15.  Low-pass: Q31 state
 * (qfoc_lpf_step).  Angle: the output is in the symmetric range, so -emf.alpha
 * is exact.
 *
 * Requirements: REQ-EMF-003, REQ-EMF-004, REQ-EMF-005, REQ-EMF-006.
 */
/*@
  requires valid_e: \valid(e);
  requires valid_u: \valid_read(u);
  requires valid_i: \valid_read(i);
  requires valid_out: \valid(out);
  requires sep: \separated(e, u, i, out);
  requires e_valid: EmfValid(e);
  assigns e->i_prev, e->lpf_alpha.state, e->lpf_beta.state, *out;
  ensures still_valid: EmfValid(e);
  ensures i_prev: e->i_prev.alpha == QfocSat15(\old(i->alpha)) &&
                  e->i_prev.beta == QfocSat15(\old(i->beta));
  ensures out_alpha: out->emf.alpha == QfocSat15(QfocRoundDiv(e->lpf_alpha.state, 65536));
  ensures out_beta: out->emf.beta == QfocSat15(QfocRoundDiv(e->lpf_beta.state, 65536));
  ensures range: QfocQ15Sym(out->emf.alpha) && QfocQ15Sym(out->emf.beta);
  behavior active:
    assumes e->active != 0;
    ensures state_alpha: e->lpf_alpha.state ==
      LpfNext(\old(e->lpf_alpha.state),
              EmfRaw(\old(u->alpha), \old(i->alpha), \old(e->i_prev.alpha),
                     \old(e->params.r), \old(e->params.l)),
              \old(e->lpf_alpha.alpha));
    ensures state_beta: e->lpf_beta.state ==
      LpfNext(\old(e->lpf_beta.state),
              EmfRaw(\old(u->beta), \old(i->beta), \old(e->i_prev.beta),
                     \old(e->params.r), \old(e->params.l)),
              \old(e->lpf_beta.alpha));
  behavior inactive:
    assumes e->active == 0;
    ensures zero: out->emf.alpha == 0 && out->emf.beta == 0 && out->theta == 0;
  complete behaviors;
  disjoint behaviors;
*/
void qfoc_emf_step(qfoc_emf_t *e, const qfoc_ab_t *u, const qfoc_ab_t *i,
                   qfoc_emf_out_t *out);

/**
 * @brief Lag of the back-EMF angle behind the rotor at speed w.
 * @param[in] e valid instance
 * @param[in] w electrical speed, Q15 of w_base, any value (saturated)
 * @return lag(W) = W/2 + atan2((1 - a) sin W, 1 - (1 - a) cos W) in angle
 *         counts modulo 2^16 (a = alpha / 32768, W = w k_theta / 65536 counts
 *         per sample): in [0, 0x6000] (0 .. 135 degrees) for w > 0, the exact
 *         negation modulo 2^16 for w < 0, and 0 for w = 0 or k_theta = 0.
 *
 * The rotor angle at the sample instant is theta + lag (+ 0x8000 for w < 0).
 * W/2 = round(w k_theta / 131072) counts.  The filter phase is evaluated with
 * the half-angle form 1 - (1 - a) cos W = a + 2 (1 - a) sin^2(W/2),
 * sin W = 2 sin(W/2) cos(W/2) from qfoc_sincos at W/2 (W = round(w k_theta /
 * 65536) counts; an odd W uses the mean of the two neighbouring half angles),
 * so that a small a and a small W lose no precision.
 *
 * Accuracy: within 1.5 + 0.65 (1 - a)/a counts of the double-precision formula
 * with the same (rounded) W, e.g. 3.5 counts (0.02 degree) for a = 0.25,
 * 65.8 counts (0.36 degree) for a = 0.01 (tested for every speed, 7 alphas,
 * 3 k_theta).  The term in (1 - a)/a is the Q15 sine quantisation (<= 1 LSB)
 * of sin(W/2) amplified by the filter phase slope (1 - a)/a at small W; the
 * rounding of W to whole counts adds at most 0.5 count x (1 - a)/a.
 *
 * Bad input: any w (saturated); an inactive instance has k_theta = 0: lag 0.
 *
 * Scaling and overflow: w k_theta <= 32767^2 in 32 bits; W/2 in [-8192, 8192],
 * |W| <= 16383.  s2 = sin + sin and c2 = cos + cos of the half angles
 * (0 .. 65534, Q16-like); b = 32768 - alpha (Q15); b s2 <= 2147352578 in 32
 * bits; Y = 2 b s2 c2 and X = alpha 2^32 + 2 b s2 s2 are (1 - a) sin W and
 * 1 - (1 - a) cos W scaled by 2^47, < 2^49 in 64 bits, X > 0; both are halved
 * together until they fit Q15 (at most 34 halvings, the ratio kept to
 * < 1/16384), then qfoc_atan2.  The final sum is formed as a non-negative int32
 * and reduced with & 0xFFFF.
 *
 * Requirements: REQ-EMF-007, REQ-EMF-013.
 */
/*@
  requires valid_e: \valid_read(e);
  requires e_valid: EmfValid(e);
  assigns \nothing;
  ensures zero_speed: (QfocSat15(w) == 0 || e->params.k_theta == 0) ==> \result == 0;
*/
qfoc_angle_t qfoc_emf_lag(const qfoc_emf_t *e, qfoc_q15_t w);

/**
 * @brief Check a disturbance-observer parameter set (twin of DobParamsValid).
 * @param[in] p parameters (read only)
 * @return true when ki >= 1, ki_shift <= 15, r >= 0, g >= 1,
 *         1 <= k_theta <= 32767 and lambda = k_i G <= 1
 *         (ki g <= 2^(27 + ki_shift)).
 *
 * Scaling and overflow: ki g <= 32767^2 in 32 bits; 2^27 x 2^ki_shift <= 2^42
 * compared in 64 bits.
 *
 * Requirements: REQ-EMF-008.
 */
/*@
  requires valid_p: \valid_read(p);
  assigns \nothing;
  ensures result: \result <==> DobParamsValid(p);
*/
bool qfoc_dob_params_is_valid(const qfoc_dob_params_t *p);

/**
 * @brief Check a disturbance-observer instance (run-time twin of DobValid).
 * @param[in] d instance (read only)
 * @return true when ki >= 0, ki_shift <= 15, r >= 0, g >= 0, k_theta <= 32767,
 *         both predicted currents are in the symmetric 32-bit range and i_prev,
 *         e_prev are in the symmetric Q15 range.
 *
 * Scaling and overflow: compares only.
 *
 * Requirements: REQ-EMF-008.
 */
/*@
  requires valid_d: \valid_read(d);
  assigns \nothing;
  ensures result: \result <==> DobValid(d);
*/
bool qfoc_dob_is_valid(const qfoc_dob_t *d);

/**
 * @brief Initialise a disturbance observer: store the parameters, clear the state.
 * @param[out] d instance
 * @param[in]  p parameters (copied; not referenced afterwards)
 * @return QFOC_EMF_OK (0) when qfoc_dob_params_is_valid(p), else
 *         QFOC_EMF_ERR_PARAM (-1).
 *
 * The predicted current, i_prev and e_prev are 0.  Call qfoc_dob_reset() with
 * the present current before the first step.
 *
 * Bad input: rejected parameters are not stored; the safe state ki = 0,
 * ki_shift = 0, r = 0, g = 0, k_theta = 0 (state 0) is set instead: it is
 * valid, every later step outputs EMF 0 (G = 0) and angle 0, and
 * qfoc_dob_lag() returns 0.
 *
 * Scaling and overflow: copies only.
 *
 * Requirements: REQ-EMF-008.
 */
/*@
  requires valid_d: \valid(d);
  requires valid_p: \valid_read(p);
  requires sep: \separated(d, p);
  assigns *d;
  ensures valid: DobValid(d);
  ensures state: d->ih_alpha == 0 && d->ih_beta == 0 &&
                 d->i_prev.alpha == 0 && d->i_prev.beta == 0 &&
                 d->e_prev.alpha == 0 && d->e_prev.beta == 0;
  behavior accepted:
    assumes DobParamsValid(p);
    ensures result: \result == 0;
    ensures params: d->params.ki == p->ki && d->params.ki_shift == p->ki_shift &&
                    d->params.r == p->r && d->params.g == p->g &&
                    d->params.k_theta == p->k_theta;
  behavior rejected:
    assumes !DobParamsValid(p);
    ensures result: \result == -1;
    ensures safe: d->params.ki == 0 && d->params.ki_shift == 0 && d->params.r == 0 &&
                  d->params.g == 0 && d->params.k_theta == 0;
  complete behaviors;
  disjoint behaviors;
*/
int32_t qfoc_dob_init(qfoc_dob_t *d, const qfoc_dob_params_t *p);

/**
 * @brief Restart a disturbance observer from the present current.
 * @param[in,out] d  valid instance
 * @param[in]     i0 present stationary-frame current, Q15, any value (saturated)
 *
 * i_hat = i_prev = i0 and e_prev = 0: the EMF estimate restarts from 0 and
 * converges with lambda (63 % after about 1 / lambda samples).  Parameters are
 * kept.
 *
 * Scaling and overflow: Q15 -> Q4.27 by x 4096, exact (|.| <= 134213632).
 *
 * Requirements: REQ-EMF-009.
 */
/*@
  requires valid_d: \valid(d);
  requires valid_i0: \valid_read(i0);
  requires sep: \separated(d, i0);
  requires d_valid: DobValid(d);
  assigns d->ih_alpha, d->ih_beta, d->i_prev, d->e_prev;
  ensures valid: DobValid(d);
  ensures i_prev: d->i_prev.alpha == QfocSat15(i0->alpha) &&
                  d->i_prev.beta == QfocSat15(i0->beta);
  ensures ih: d->ih_alpha == 4096 * QfocSat15(i0->alpha) &&
              d->ih_beta == 4096 * QfocSat15(i0->beta);
  ensures e_prev: d->e_prev.alpha == 0 && d->e_prev.beta == 0;
*/
void qfoc_dob_reset(qfoc_dob_t *d, const qfoc_ab_t *i0);

/**
 * @brief One disturbance-observer sample: advance the current model, EMF from
 *        the current error, angle.
 * @param[in,out] d   valid instance (qfoc_dob_is_valid())
 * @param[in]     u   voltage applied during the last PWM period [k-1, k],
 *                    stationary frame, Q15 of V_base, any value
 * @param[in]     i   current sampled now (k), stationary frame, Q15 of I_base,
 *                    any value
 * @param[out]    out out->emf = e_hat(k) (Q15 of V_base),
 *                    out->theta = atan2(-e_hat_alpha, e_hat_beta)
 *
 * Per axis: x = u - R (i + i_prev)/2 - e_prev; i_hat = sat(i_hat + k_i x);
 * e_hat = sat(G (i_hat - i)); i_prev = i, e_prev = e_hat.
 * Equivalent to a first-order low-pass with alpha = lambda = k_i G of the
 * back-EMF sample e_raw (see the file comment); theta = rotor angle -
 * qfoc_dob_lag() (+ 180 degrees for negative speed).
 *
 * Accuracy: the increment is the exact product rounded once to Q4.27
 * (<= 2^-28 pu), e_hat is rounded once to Q15 (<= 1/2 LSB) unless it
 * saturates; e_hat is within 1 LSB + 0.001 LSB / lambda of the real-valued
 * low-pass with alpha = lambda (1/2 LSB output rounding, 1/2 LSB of the rounded
 * e_hat fed back into the model).  i_hat stays unsaturated while |i| + |e_hat| / G < 16 pu (for
 * G >= 1/15, Q12 >= 274, for every Q15 current and EMF).
 *
 * Bad input: any u, i (saturated first).  The safe state (G = 0) outputs 0.
 *
 * Scaling and overflow: u, i saturated to [-32767, 32767].
 * x = 65536 u - r (i + i_prev) - 65536 e_prev in Q31 of V_base (r (i + i_prev)
 * is Q30 of the sum = Q31 of the mean), |x| <= 6442188802 < 2^33 in 64 bits.
 * k_i x: x ki (Q31 x Q15, |.| < 2^48) x 2^(15 - ki_shift) (|.| < 2^63, 64 bits)
 * / 2^34 rounded = x k_i in Q27 (division by a constant power of two; the
 * variable shift enters as the factor 2^(15 - ki_shift)).  i_hat + k_i x
 * saturated to the symmetric 32-bit range (Q4.27, +-16 pu).  i_hat - 4096 i in
 * Q27 (|.| < 2^32, 64 bits); x G (Q12) = Q39 (|.| < 2^47); / 2^24 rounded ->
 * Q15, saturated.
 *
 * Requirements: REQ-EMF-010, REQ-EMF-011, REQ-EMF-005, REQ-EMF-014.
 */
/*@
  requires valid_d: \valid(d);
  requires valid_u: \valid_read(u);
  requires valid_i: \valid_read(i);
  requires valid_out: \valid(out);
  requires sep: \separated(d, u, i, out);
  requires d_valid: DobValid(d);
  assigns d->ih_alpha, d->ih_beta, d->i_prev, d->e_prev, *out;
  ensures still_valid: DobValid(d);
  ensures ih_alpha: d->ih_alpha ==
    DobNext(\old(d->ih_alpha),
            DobSum(\old(u->alpha), \old(i->alpha), \old(d->i_prev.alpha),
                   \old(d->e_prev.alpha), \old(d->params.r)),
            \old(d->params.ki), \old(d->params.ki_shift));
  ensures ih_beta: d->ih_beta ==
    DobNext(\old(d->ih_beta),
            DobSum(\old(u->beta), \old(i->beta), \old(d->i_prev.beta),
                   \old(d->e_prev.beta), \old(d->params.r)),
            \old(d->params.ki), \old(d->params.ki_shift));
  ensures e_alpha: d->e_prev.alpha == DobEmf(d->ih_alpha, \old(i->alpha), \old(d->params.g));
  ensures e_beta: d->e_prev.beta == DobEmf(d->ih_beta, \old(i->beta), \old(d->params.g));
  ensures i_prev: d->i_prev.alpha == QfocSat15(\old(i->alpha)) &&
                  d->i_prev.beta == QfocSat15(\old(i->beta));
  ensures out: out->emf.alpha == d->e_prev.alpha && out->emf.beta == d->e_prev.beta;
  ensures range: QfocQ15Sym(out->emf.alpha) && QfocQ15Sym(out->emf.beta);
  behavior observing:
    assumes d->params.g != 0;
  behavior safe:
    assumes d->params.g == 0;
    ensures zero: out->emf.alpha == 0 && out->emf.beta == 0 && out->theta == 0;
  complete behaviors;
  disjoint behaviors;
*/
void qfoc_dob_step(qfoc_dob_t *d, const qfoc_ab_t *u, const qfoc_ab_t *i,
                   qfoc_emf_out_t *out);

/**
 * @brief Lag of the disturbance-observer angle behind the rotor at speed w.
 * @param[in] d valid instance
 * @param[in] w electrical speed, Q15 of w_base, any value (saturated)
 * @return lag(W) as qfoc_emf_lag() with a = lambda = k_i G
 *         (= round(ki g / 2^(12 + ki_shift)) in Q15, clamped to [1, 32767]).
 *
 * Accuracy: as qfoc_emf_lag(); lambda is rounded to Q15 (<= 1/2 LSB).
 *
 * Bad input: any w (saturated); the safe state (k_theta = 0) gives 0.
 *
 * Scaling and overflow: ki g <= 32767^2 in 32 bits, divided by
 * 4096 x 2^ki_shift (<= 2^27) with rounding in 32 bits; then as qfoc_emf_lag().
 *
 * Requirements: REQ-EMF-012, REQ-EMF-013.
 */
/*@
  requires valid_d: \valid_read(d);
  requires d_valid: DobValid(d);
  assigns \nothing;
  ensures zero_speed: (QfocSat15(w) == 0 || d->params.k_theta == 0) ==> \result == 0;
*/
qfoc_angle_t qfoc_dob_lag(const qfoc_dob_t *d, qfoc_q15_t w);

#ifdef __cplusplus
}
#endif

#endif /* QFOC_EMF_H */
