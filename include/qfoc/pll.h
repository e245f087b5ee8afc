/**
 * @file pll.h
 * @brief Phase-locked loop on the estimated rotor flux (E2-27, E2-28, formerly
 *        PhaseLockedLoop) and angle-tracking observer on the back-EMF.
 *
 * Equation tags E2-n, E3-n: specs/equations.md (sections 5 to 7).
 *
 * @par What it does
 * The PLL turns the stationary-frame rotor flux estimated by the flux observer
 * (psi_alpha, psi_beta; include/qfoc/flux.h) into the electrical rotor angle
 * theta and speed omega.  It is a type-2 loop (specs/equations.md section 5):
 *
 *     Delta theta = psi_beta cos(theta) - psi_alpha sin(theta)
 *                 = |psi| sin(theta_r - theta)                     (E2-28a)
 *     omega       = Delta theta (kp + ki / s)                       (E2-27)
 *     theta       = theta + omega / f_pwm                           (E2-28)
 *     omega_f     = low-pass of omega, y(k+1) = y(k) + alpha (omega - y(k))  (E2-34)
 *
 * discretised with the forward difference (E2-16, E2-35)
 * (omega_2(k) = omega_2(k-1) + Delta theta(k) ki T, theta(k+1) = theta(k) +
 * omega(k) T).  qfoc_pi_step() (pi.h) is the PI, qfoc_lpf_step() (filter.h) the
 * speed low-pass, qfoc_sincos() (trig.h) the sine and cosine of the estimate and
 * qfoc_vec_mag() (vector.h) the input magnitude.
 *
 * @par Normalisation by the flux magnitude (why)
 * The phase detector E2-28a has the gain |psi|: its loop gain, hence the
 * natural frequency (proportional to sqrt |psi|) and the damping, would change
 * with the magnet temperature, with the load (active flux
 * psi_f + (L_d - L_q) i_d), with the high-pass attenuation of the flux
 * observer at low speed and with the choice of the flux base; for the EMF
 * input of the angle-tracking observer the gain is omega |psi| and would change
 * by a factor 10 over the speed range.  qfoc divides the detector output by the
 * input magnitude:
 *
 *     error = round(32768 (psi_beta cos - psi_alpha sin) / |psi|)
 *           = 32768 sin(theta_r - theta)  ~  32768 (theta_r - theta) [rad]
 *
 * so the loop gain is exactly 1 per radian whatever the amplitude: the PI gains
 * below give the designed natural frequency and damping at every speed and
 * load, the lock time does not depend on |psi| (tested for |psi| = 2000 and
 * 20000), and err_clamp is an angle (the earlier clamp 5000 of E2-28a acts on an
 * unnormalised product and so depends on its flux scaling).
 *
 * @par Parameters from base values and f_pwm (reference numbers)
 * Bases as in specs/scaling.md: w_base = 2 pi f_base, speed in Q15 of w_base;
 * reference: f_base = 500 Hz (w_base = 3141.593 rad/s), f_pwm = 8000 Hz
 * (T = 125 us).
 *  - k_theta = round(f_base / f_pwm x 131072): angle increment in 2^-32 turns
 *    per speed LSB per sample (speed raw s stands for s / 32768 x f_base Hz, so
 *    one sample turns s / 32768 x f_base / f_pwm x 2^32 = s x f_base / f_pwm x
 *    131072 accumulator counts).  Reference: 500 / 8000 x 131072 = 8192 (exact).
 *    Admissible 1..32767, i.e. f_base < f_pwm / 4.  The increment speed x k_theta
 *    is exact, so the speed estimate carries no bias from the conversion other
 *    than the rounding of k_theta itself (<= 0.5 / k_theta relative, 0 for the
 *    reference); the earlier 16-bit u16_theta += 600 x 2 w / f_pwm (E2-28)
 *    truncates the increment every sample instead.
 *  - PI gains (E3-8) from a natural frequency w_n (rad/s) and a damping ratio zeta:
 *    with the normalised detector (gain 1 per rad) the loop is
 *    s^2 + kp_c s + ki_c = s^2 + 2 zeta w_n s + w_n^2, and the speed is in pu of
 *    w_base, hence
 *
 *        kp_real  = 2 zeta w_n / w_base,     kiT_real = w_n^2 T / w_base
 *
 *    written in the qfoc_pi mantissa/shift form (kp_real = kp / 32768 x
 *    2^kp_shift, kiT_real = ki / 32768 x 2^ki_shift, smallest shift that brings
 *    the mantissa below 32768).  Reference, w_n = 2 pi 50 Hz = 314.159 rad/s:
 *      - zeta = 1.0: kp_real = 0.2000 -> kp = 6553.6 -> 6554, kp_shift = 0;
 *      - zeta = 0.8: kp_real = 0.1600 -> kp = 5242.9 -> 5243, kp_shift = 0;
 *      - kiT_real = 314.159^2 x 125e-6 / 3141.593 = 0.0039270
 *        -> ki = 128.68 -> 129, ki_shift = 0 (realised w_n = 314.55 rad/s);
 *      - out_min / out_max: the speed range, e.g. -32767 / 32767 (+-1 pu = 500 Hz
 *        electrical); the PI clamps its integrator to it (anti-windup).
 *    A small-signal step of the angle settles (2 %) in about 4 / (zeta w_n),
 *    12.7 ms for the reference; the discrete loop is close to the continuous
 *    one while w_n T << 1 (reference: 0.039).  A constant speed is tracked
 *    without steady-state angle error (two integrators in the loop); a constant
 *    acceleration a (rad/s^2) leaves an angle error a / w_n^2 rad.
 *  - err_clamp (Q15 1..32767): clamp of the normalised error, i.e. of
 *    sin(theta_r - theta).  The earlier code used 5000 (= 0.153, 8.8 deg).  It bounds
 *    the speed correction per sample: |P| <= kp_real x err_clamp / 32768 pu
 *    (reference, zeta = 1: 0.031 pu) and the integrator slope
 *    <= w_n^2 x err_clamp / 32768 rad/s^2 (reference: 15061 rad/s^2 = 4.8 pu/s),
 *    which is also the largest acceleration the loop follows.  With a large
 *    angle error at a known speed the loop pulls in at a limited rate:
 *    reference (zeta = 1), lock (error < 1 deg) from a 90 deg error in 24.75 ms
 *    at every speed and amplitude.  Frequency acquisition from standstill is
 *    slow with the clamp: 0.06 pu in 25 ms, 0.3 pu in 0.33 s, 0.6 pu in 1.3 s,
 *    0.8 pu in 2.4 s (without the clamp, err_clamp = 32767: 0.6 pu in 61 ms);
 *    so preset the speed with qfoc_pll_reset() when the observer takes over
 *    from an open-loop start-up (tests/test_pll.c).  A noisy estimate cannot
 *    kick the speed by more than the clamp allows.
 *  - mag_min (Q15 1..32767): smallest input magnitude that is trusted.  Below it
 *    the error is forced to 0 and the loop coasts (see "Coasting").  E.g. 10 %
 *    of the rated flux: psi_f = 0.40841 pu = 13383 -> mag_min = 1338; for EMF
 *    inputs the magnitude is w psi_f, e.g. 400 (coasting below about 0.03 pu).
 *  - speed_alpha (Q15 1..32767): E2-34 low-pass of the speed,
 *    alpha = 2 pi f_c / f_pwm x 32768, e.g. f_c = 50 Hz: 1286.8 -> 1287.
 *
 * @par Coasting (mag_min rule)
 * When |psi| < mag_min (start-up, very low speed, a flux or EMF estimate that is
 * switched off or faulty) the error is 0: the proportional term is 0 and the
 * integrator holds, so the speed equals the last integrator value and the angle
 * keeps advancing with it (extrapolation).  out->mag tells the caller that the
 * PLL is coasting (out->mag < mag_min); a drive switches to its open-loop or
 * I/f start-up below the magnitude it trusts.  Nothing is divided by a small
 * magnitude, and a zero input never produces a spurious error.  The decision is
 * exact on the squares (x^2 + y^2 < mag_min^2, contract behaviours coast/track).
 *
 * @par Flux magnitudes of 1 pu and more
 * qfoc_vec_mag() saturates at 32767, so a vector longer than 1 pu (possible only
 * when both components are large, up to sqrt(2) pu) is normalised by 32767:
 * the detector gain is then |psi| / 32767 <= 1.414 instead of 1 (still clamped).
 * Choose psi_base so that the flux stays below 1 pu (reference: 0.408 pu).
 *
 * @par Angle accumulator (wraps modulo 2^32 by design)
 * The angle is a uint32 accumulator theta_acc, 2^32 counts per electrical turn.
 * theta_acc(k+1) = (theta_acc(k) + speed x k_theta) mod 2^32: the wrap-around
 * from one turn to the next is the intended modulo arithmetic of an angle (it is
 * formed in 64-bit signed arithmetic and reduced explicitly, so no C
 * expression wraps; the contract states the modulo result, `acc`, `acc_mod`).
 * The output angles are the accumulator rounded to the qfoc_angle_t resolution,
 * theta = round(theta_acc / 65536) mod 2^16 (error <= 0.5 count = 0.0027 deg).
 *
 * @par Which angle to use when
 * A call at sample k receives the flux estimated for sample k (from the current
 * sampled at k).
 *  - out->theta: the estimate at sample k, the angle the error was computed with.
 *    Use it (and out->sc = sin/cos of it) for the Park transform of the currents
 *    sampled at k.  From a flux observer with a high-pass (flux.h), subtract its
 *    phase lead qfoc_flux_lead(flux, out->speed_f) first.
 *  - out->theta_next: the prediction for sample k+1 (= theta + speed x k_theta).
 *    The voltage computed at k is applied during [k, k+1], while the rotor turns
 *    from theta to theta_next: its mean angle is the midpoint
 *    theta + d / 2, d = (theta_next - theta) taken as a signed 16-bit difference
 *    (|d| < 16384 counts).  Using theta for the inverse Park lets the applied
 *    voltage lag by d / 2 (at 0.8 pu and 8 kHz: 9 electrical degrees), using
 *    theta_next lets it lead by the same amount.  Where the PWM loads the new
 *    compare values one period later, add one more d.
 *
 * @par Angle-tracking observer on the back-EMF (qfoc_pll_step_emf)
 * The EMF estimators of include/qfoc/emf.h give e = w psi (-sin theta_r,
 * cos theta_r) (active flux, steady state).  qfoc_pll_step_emf() turns it into
 * the flux direction, (e_beta, -e_alpha) while the PLL's speed integrator is
 * >= 0 and (-e_beta, e_alpha) while it is negative, and runs the same loop;
 * thanks to the normalisation the loop gain does not grow with the speed.  It
 * is the alternative to the open-loop atan2 angle of those estimators (no
 * derivative of an angle, a filtered speed and a prediction for free).  Near
 * zero speed the EMF vanishes (coasting below mag_min) and its direction is
 * undefined; starting with the wrong speed sign the loop first tracks the
 * opposite direction until the integrator changes sign, then locks (tested).
 *
 * @par Bias from mismatched flux components (E2-29 .. E2-32)
 * Let the estimated components carry amplitude and phase errors
 * psi_alpha = psi1 cos(theta_r + phi_a), psi_beta = psi2 sin(theta_r + phi_b)
 * (E2-29, E2-30) and write theta = theta_r + b.  With cos phi ~ 1, sin phi ~ phi
 * (E2-32) and theta ~ theta_r in the small terms,
 *
 *     psi_beta cos(theta) - psi_alpha sin(theta)
 *       = psi2 sin(theta_r) cos(theta) - psi1 cos(theta_r) sin(theta)
 *         + psi2 phi_b cos^2(theta_r) + psi1 phi_a sin^2(theta_r)
 *       = -(psi1 + psi2)/2 sin(b) + (psi2 - psi1)/2 sin(2 theta_r + b)
 *         + (psi1 phi_a + psi2 phi_b)/2 + (psi2 phi_b - psi1 phi_a)/2 cos(2 theta_r)
 *
 * (using psi2 sin x cos y - psi1 cos x sin y = S sin(x - y) + D sin(x + y),
 * S = (psi1 + psi2)/2, D = (psi2 - psi1)/2).  The loop drives this to zero, so
 * the angle error settles to
 *
 *     b = (psi1 phi_a + psi2 phi_b) / (psi1 + psi2)                      (mean)
 *       + (psi2 - psi1) / (psi1 + psi2) sin(2 theta_r)                    (ripple)
 *       + (psi2 phi_b - psi1 phi_a) / (psi1 + psi2) cos(2 theta_r)
 *
 * The mean bias is the amplitude-weighted mean phase error,
 * ~ (phi_a + phi_b) / 2; it does not depend on the speed, the gains or the
 * normalisation (the loop's DC gain is 1), and a lead common to both components
 * (the flux observer's high-pass) appears in full (compensate it with
 * qfoc_flux_lead()).  The ripple at twice the electrical frequency has the
 * amplitude ~ |psi2 - psi1| / (psi1 + psi2) rad when the loop is fast enough to
 * follow it; the PLL's closed-loop response T(z) filters it, so the angle ripple
 * is |T(e^(j 2 W))| times that amplitude, W = speed x k_theta x 2 pi / 2^32 rad
 * per sample.  Both are first order in the mismatch: tests/test_pll.c measures
 * the mean within 0.0003 deg of the formula and the ripple within 1 % for
 * |psi2 - psi1| / (psi1 + psi2) = 0.08 (psi1 < psi2 and psi1 > psi2); at 0.23
 * the neglected second-order terms reach 0.4 deg and 25 %.
 * Note on an earlier statement of E2-31: its first case (psi1 <= psi2) is the
 * unnormalised error above at b = 0; its second case (psi1 > psi2) does not
 * follow from its own previous line: psi2 sin(th_r) cos(th) - psi1 cos(th_r)
 * sin(th) = psi2 sin(th_r - th) + (psi2 - psi1) cos(th_r) sin(th) (that statement
 * writes +(psi1 - psi2)), and with th_r = th the term (psi1 - psi2) cos(th)
 * sin(th) is (psi1 - psi2) sin(2 th) / 2, of zero mean, not
 * (psi1 - psi2)(1 + cos(2 th)) / 2.  The constant (psi2 - psi1)/2 of that case is
 * therefore spurious: one formula holds for both cases, with the mean bias
 * above and the detector gain (psi1 + psi2)/2 (neither psi1 nor psi2 alone).
 *
 * @par Bad input
 * Every int16 input value is accepted (-32768 is saturated to -32767 first).
 * Parameters are checked once by qfoc_pll_init() (rejected: status -1 and a safe
 * state, see there); the step functions require a valid instance
 * (qfoc_pll_is_valid(), ACSL PllValid), which init, reset and every step
 * establish.
 *
 * Requirements: REQ-PLL-001 .. REQ-PLL-012 (specs/requirements/pll.md).
 *
 * Validation of the whole estimation chain on the plant model (flux observer +
 * PLL, back-EMF and disturbance observers, angle-tracking observer; reference
 * motor, quantised ADC samples, tests/test_estimation.c and `make
 * estimator-report`), specs/requirements/estimation.md: REQ-EST-001 (angle
 * accuracy), REQ-EST-002 (speed accuracy), REQ-EST-003 (convergence from a
 * 90-degree error), REQ-EST-004 (bias against E2-31),
 * REQ-EST-005 (noise and parameter robustness).
 */
#ifndef QFOC_PLL_H
#define QFOC_PLL_H

#include "qfoc/types.h"
#include "qfoc/pi.h"
#include "qfoc/filter.h"
#include "qfoc/vector.h"

#ifdef __cplusplus
extern "C" {
#endif

/** qfoc_pll_init() status: parameters accepted. */
#define QFOC_PLL_OK ((int32_t)0)
/** qfoc_pll_init() status: parameters rejected, instance set to the safe state. */
#define QFOC_PLL_ERR_PARAM ((int32_t)-1)
/** Largest admissible k_theta: f_base / f_pwm < 1/4 (32767 / 131072 = 0.24999). */
#define QFOC_PLL_K_THETA_MAX ((uint16_t)32767u)

/** PLL parameters (see the file description for their derivation). */
typedef struct {
    qfoc_pi_params_t pi;     /**< error -> speed: kp = 2 zeta w_n / w_base,
                                  ki T = w_n^2 T / w_base; out_min / out_max =
                                  speed limits, Q15 of w_base */
    qfoc_q15_t err_clamp;    /**< clamp of the normalised error, Q15, 1..32767
                                  (formerly PhaseLockedLoop: 5000 = 0.153,
                                  8.8 deg) */
    qfoc_q15_t mag_min;      /**< smallest trusted input magnitude, Q15, 1..32767 */
    uint16_t k_theta;        /**< round(f_base / f_pwm x 131072), 1..32767
                                  (2^-32 turn per speed LSB per sample) */
    qfoc_q15_t speed_alpha;  /**< speed low-pass 2 pi f_c / f_pwm, Q15, 1..32767 */
} qfoc_pll_params_t;

/** PLL instance. */
typedef struct {
    qfoc_pi_t pi;            /**< PI of E2-27, integrator = speed without the P term */
    qfoc_lpf_t speed_lpf;    /**< E2-34 low-pass of the speed */
    uint32_t theta_acc;      /**< angle, 2^32 counts per electrical turn (mod 2^32) */
    qfoc_q15_t speed;        /**< last speed output, Q15 of w_base */
    qfoc_q15_t err_clamp;    /**< copy of the parameter */
    qfoc_q15_t mag_min;      /**< copy of the parameter */
    uint16_t k_theta;        /**< copy of the parameter */
} qfoc_pll_t;

/** Result of one PLL step. */
typedef struct {
    qfoc_angle_t theta;      /**< estimate at this sample: the angle the error was
                                  computed with (Park of the currents sampled now) */
    qfoc_angle_t theta_next; /**< prediction for the next sample */
    qfoc_sincos_t sc;        /**< qfoc_sincos(theta) */
    qfoc_q15_t speed;        /**< electrical speed, Q15 of w_base (PI output) */
    qfoc_q15_t speed_f;      /**< speed after the E2-34 low-pass */
    qfoc_q15_t error;        /**< normalised, clamped error ~ sin(theta_r - theta) */
    qfoc_q15_t mag;          /**< input magnitude |psi| (floor, saturated at 32767);
                                  the PLL coasts while mag < mag_min */
} qfoc_pll_out_t;

#ifdef __FRAMAC__
/* ACSL predicates over the types above, read by Frama-C only (DEV-001). */
/* cppcheck-suppress misra-c2012-20.1 ; DEV-001 */
#include "pll.acsl"
#endif

/**
 * @brief Check a PLL parameter set.
 * @param[in] p parameters (read only)
 * @return true when the PI parameters are valid (qfoc_pi_params_is_valid()),
 *         err_clamp >= 1, mag_min >= 1, 1 <= k_theta <= 32767 and
 *         speed_alpha >= 1.
 *
 * Scaling and overflow: compares only.
 *
 * Requirements: REQ-PLL-001.
 */
/*@
  requires valid_p: \valid_read(p);
  assigns \nothing;
  ensures result: \result <==> PllParamsValid(p);
*/
bool qfoc_pll_params_is_valid(const qfoc_pll_params_t *p);

/**
 * @brief Check a PLL instance (the run-time twin of the ACSL predicate PllValid).
 * @param[in] pll instance (read only)
 * @return true when its parameters are valid, the PI instance and the speed
 *         low-pass are valid (qfoc_pi_is_valid(), qfoc_lpf_is_valid()) and the
 *         stored speed lies within the PI output limits.  Every theta_acc is
 *         valid.
 *
 * Scaling and overflow: compares only.
 *
 * Requirements: REQ-PLL-002.
 */
/*@
  requires valid_pll: \valid_read(pll);
  assigns \nothing;
  ensures result: \result <==> PllValid(pll);
*/
bool qfoc_pll_is_valid(const qfoc_pll_t *pll);

/**
 * @brief Initialise a PLL: store the parameters, angle 0, speed 0.
 * @param[out] pll instance
 * @param[in]  p   parameters (copied; not referenced afterwards)
 * @return QFOC_PLL_OK (0) when qfoc_pll_params_is_valid(p), else
 *         QFOC_PLL_ERR_PARAM (-1).
 *
 * After init the instance is as after qfoc_pll_reset(pll, 0, 0): theta_acc = 0,
 * speed = integrator = low-pass output = the point of [out_min, out_max]
 * nearest to 0.
 *
 * Bad input: rejected parameters are not stored; the safe state is set instead:
 * PI with kp = ki = 0 and limits [0, 0], err_clamp = 1, mag_min = 32767,
 * k_theta = 1, speed_alpha = 32767.  It is a valid instance whose speed is 0
 * and whose angle stays 0 for every input; the caller must treat the status -1
 * as a configuration error.
 *
 * Scaling and overflow: copies only.
 *
 * Requirements: REQ-PLL-001, REQ-PLL-009.
 */
/*@
  requires valid_pll: \valid(pll);
  requires valid_p: \valid_read(p);
  requires sep: \separated(pll, p);
  assigns *pll;
  ensures valid: PllValid(pll);
  ensures acc: pll->theta_acc == 0;
  ensures speed: pll->speed == QfocClamp(0, pll->pi.params.out_min, pll->pi.params.out_max);
  ensures integ: pll->pi.integ == pll->speed * 65536;
  ensures lpf: pll->speed_lpf.state == pll->speed * 65536;
  behavior accepted:
    assumes PllParamsValid(p);
    ensures result: \result == 0;
    ensures pi: pll->pi.params.kp == p->pi.kp && pll->pi.params.kp_shift == p->pi.kp_shift &&
                pll->pi.params.ki == p->pi.ki && pll->pi.params.ki_shift == p->pi.ki_shift &&
                pll->pi.params.out_min == p->pi.out_min &&
                pll->pi.params.out_max == p->pi.out_max;
    ensures params: pll->err_clamp == p->err_clamp && pll->mag_min == p->mag_min &&
                    pll->k_theta == p->k_theta && pll->speed_lpf.alpha == p->speed_alpha;
  behavior rejected:
    assumes !PllParamsValid(p);
    ensures result: \result == -1;
    ensures safe_pi: pll->pi.params.kp == 0 && pll->pi.params.ki == 0 &&
                     pll->pi.params.out_min == 0 && pll->pi.params.out_max == 0;
    ensures safe_params: pll->err_clamp == 1 && pll->mag_min == 32767 &&
                         pll->k_theta == 1 && pll->speed_lpf.alpha == 32767;
  complete behaviors;
  disjoint behaviors;
*/
int32_t qfoc_pll_init(qfoc_pll_t *pll, const qfoc_pll_params_t *p);

/**
 * @brief Set the angle and the speed (e.g. when the observer takes over from an
 *        open-loop start-up, or after a fault).
 * @param[in,out] pll   instance with valid parameters (as after qfoc_pll_init())
 * @param[in]     theta angle, any value (65536 counts per turn)
 * @param[in]     speed speed, Q15 of w_base, any int16_t
 *
 * theta_acc = theta x 65536; the speed clamped to [out_min, out_max] is loaded
 * into the PI integrator (qfoc_pi_reset(), bumpless: the next output for a zero
 * error is that speed), into the speed low-pass and into the stored speed.
 *
 * Bad input: a speed outside the limits (-32768 included) is clamped.
 *
 * Scaling and overflow: theta x 65536 <= 65535 x 65536 < 2^32 in uint32; the
 * clamped speed x 65536 fits int32 (Q15 -> Q31).
 *
 * Requirements: REQ-PLL-009.
 */
/*@
  requires valid_pll: \valid(pll);
  requires config_valid: PllConfigValid(pll);
  assigns pll->theta_acc, pll->speed, pll->pi.integ, pll->pi.limited,
          pll->speed_lpf.state;
  ensures valid: PllValid(pll);
  ensures acc: pll->theta_acc == theta * 65536;
  ensures speed: pll->speed == QfocClamp(speed, pll->pi.params.out_min, pll->pi.params.out_max);
  ensures integ: pll->pi.integ == pll->speed * 65536;
  ensures lpf: pll->speed_lpf.state == pll->speed * 65536;
*/
void qfoc_pll_reset(qfoc_pll_t *pll, qfoc_angle_t theta, qfoc_q15_t speed);

/**
 * @brief One PLL sample on a stationary-frame flux vector (E2-27, E2-28, E2-34).
 * @param[in,out] pll valid instance (qfoc_pll_is_valid())
 * @param[in]     psi rotor flux (psi_alpha, psi_beta) at this sample, Q15 of
 *                    psi_base, any int16_t values (-32768 saturated to -32767)
 * @param[out]    out results (see qfoc_pll_out_t)
 *
 * Algorithm (x, y = psi saturated to [-32767, 32767]):
 *   1. theta = round(theta_acc / 65536) mod 2^16, sc = qfoc_sincos(theta);
 *   2. e30 = y cos - x sin (Q30), mag = qfoc_vec_mag(x, y);
 *   3. error = 0 if mag < mag_min (coast), else
 *      clamp(round(e30 / mag), -err_clamp, err_clamp) (nearest, ties away from
 *      zero): 32768 sin(theta_r - theta);
 *   4. speed = qfoc_pi_step(pi, error)                                  (E2-27);
 *   5. theta_acc = (theta_acc + speed x k_theta) mod 2^32                (E2-28);
 *      theta_next = round(theta_acc / 65536) mod 2^16;
 *   6. speed_f = qfoc_lpf_step(speed_lpf, speed)                         (E2-34).
 * The angle and error of the step are exact integer functions of the inputs
 * (contract).  Against the real-valued detector 32768 sin(theta_r - theta)
 * the error differs by at most 3 + 32768 / mag LSB while mag < 32767 (sine and
 * cosine <= 1 LSB each, the floor of the magnitude a relative 1 / mag, the
 * final rounding 0.5 LSB); measured maximum 16.2 LSB for |psi| >= 1000
 * (tests/test_pll.c, which re-computes every output exactly).
 *
 * Bad input: none possible beyond the preconditions; a magnitude below mag_min
 * (zero vector included) gives error 0 (coasting), never a division by a
 * small number.
 *
 * Scaling and overflow: x, y, sin, cos in [-32767, 32767]: each product
 * <= 32767^2 and e30 <= 2 x 32767^2 = 2147352578 < 2^31 in int32 (Q30).
 * mag >= mag_min >= 1 when dividing; e30 +- mag / 2 stays below 2^31; the
 * quotient (Q30 / Q15 = Q15) is clamped to +-err_clamp, so it fits int16.
 * speed x k_theta <= 32767 x 32767 < 2^30 in int32; theta_acc + increment is
 * formed in int64 and brought into [0, 2^32) by adding or subtracting 2^32
 * once (the modulo), then stored as uint32: no C type ever wraps.  The angle
 * rounding uses the uint32 quotient and remainder by 65536 (the quotient + 1
 * <= 65536, then % 65536).
 *
 * Requirements: REQ-PLL-003, REQ-PLL-004, REQ-PLL-005, REQ-PLL-006,
 * REQ-PLL-007, REQ-PLL-010, REQ-PLL-011, REQ-PLL-012.
 */
/*@
  requires valid_pll: \valid(pll);
  requires valid_psi: \valid_read(psi);
  requires valid_out: \valid(out);
  requires sep: \separated(pll, psi, out);
  requires pll_valid: PllValid(pll);
  assigns pll->pi.integ, pll->pi.limited, pll->speed_lpf.state, pll->theta_acc,
          pll->speed, *out;
  ensures still_valid: PllValid(pll);
  ensures config: pll->mag_min == \old(pll->mag_min) &&
                  pll->err_clamp == \old(pll->err_clamp) &&
                  pll->k_theta == \old(pll->k_theta);
  ensures theta: out->theta == PllAngle(\old(pll->theta_acc));
  ensures sincos_range: QfocQ15Sym(out->sc.sine) && QfocQ15Sym(out->sc.cosine);
  ensures mag: PllMag(out->mag, QfocSat15(\old(psi->alpha)), QfocSat15(\old(psi->beta)));
  ensures error: out->error ==
    PllErr(PllE30(QfocSat15(\old(psi->alpha)), QfocSat15(\old(psi->beta)),
                  out->sc.sine, out->sc.cosine),
           out->mag, \old(pll->mag_min), \old(pll->err_clamp));
  ensures error_range: -\old(pll->err_clamp) <= out->error <= \old(pll->err_clamp);
  ensures speed: out->speed == PllPiOut{Pre}(&pll->pi, out->error);
  ensures speed_range: pll->pi.params.out_min <= out->speed <= pll->pi.params.out_max;
  ensures speed_state: pll->speed == out->speed;
  ensures integ: pll->pi.integ == PiNextInteg{Pre}(&pll->pi, out->error);
  ensures acc: pll->theta_acc ==
    PllAccNext(\old(pll->theta_acc), out->speed * \old(pll->k_theta));
  ensures acc_mod:
    (pll->theta_acc - (\old(pll->theta_acc) + out->speed * \old(pll->k_theta)))
      % 4294967296 == 0;
  ensures theta_next: out->theta_next == PllAngle(pll->theta_acc);
  ensures speed_lpf: pll->speed_lpf.state ==
    LpfNext(\old(pll->speed_lpf.state), out->speed, \old(pll->speed_lpf.alpha));
  ensures speed_f: out->speed_f == QfocSat15(QfocRoundDiv(pll->speed_lpf.state, 65536));
  behavior coast:
    assumes PllCoast(QfocSat15(psi->alpha), QfocSat15(psi->beta), pll->mag_min);
    ensures below: out->mag < \old(pll->mag_min);
    ensures zero_error: out->error == 0;
  behavior track:
    assumes !PllCoast(QfocSat15(psi->alpha), QfocSat15(psi->beta), pll->mag_min);
    ensures above: out->mag >= \old(pll->mag_min);
    ensures normalised: out->error ==
      QfocClamp(QfocRoundDiv(PllE30(QfocSat15(\old(psi->alpha)), QfocSat15(\old(psi->beta)),
                                    out->sc.sine, out->sc.cosine), out->mag),
                -\old(pll->err_clamp), \old(pll->err_clamp));
  complete behaviors;
  disjoint behaviors;
*/
void qfoc_pll_step(qfoc_pll_t *pll, const qfoc_ab_t *psi, qfoc_pll_out_t *out);

/**
 * @brief One angle-tracking-observer sample on a back-EMF vector.
 * @param[in,out] pll valid instance (qfoc_pll_is_valid())
 * @param[in]     emf back-EMF (e_alpha, e_beta) = w psi (-sin theta_r,
 *                    cos theta_r), Q15 of V_base, any int16_t values
 *                    (-32768 saturated to -32767); e.g. the output of
 *                    qfoc_emf_step() or qfoc_dob_step() (emf.h)
 * @param[out]    out results as for qfoc_pll_step(); out->mag is |e|
 *
 * The flux direction is (e_beta, -e_alpha) while the PI integrator (the speed
 * without its proportional part) is >= 0, (-e_beta, e_alpha) while it is < 0;
 * that vector goes through the steps of qfoc_pll_step().  mag_min applies to
 * |e| = |w| psi: choose it for the lowest speed at which the EMF is trusted.
 *
 * Bad input: as qfoc_pll_step().
 *
 * Scaling and overflow: the components are saturated to [-32767, 32767]
 * before the negation, so the negation is exact; then as qfoc_pll_step().
 *
 * Requirements: REQ-PLL-008, REQ-PLL-010.
 */
/*@
  requires valid_pll: \valid(pll);
  requires valid_emf: \valid_read(emf);
  requires valid_out: \valid(out);
  requires sep: \separated(pll, emf, out);
  requires pll_valid: PllValid(pll);
  assigns pll->pi.integ, pll->pi.limited, pll->speed_lpf.state, pll->theta_acc,
          pll->speed, *out;
  ensures still_valid: PllValid(pll);
  ensures config: pll->mag_min == \old(pll->mag_min) &&
                  pll->err_clamp == \old(pll->err_clamp) &&
                  pll->k_theta == \old(pll->k_theta);
  ensures theta: out->theta == PllAngle(\old(pll->theta_acc));
  ensures sincos_range: QfocQ15Sym(out->sc.sine) && QfocQ15Sym(out->sc.cosine);
  ensures mag: PllMag(out->mag, PllAtoX(\old(pll->pi.integ), \old(emf->beta)),
                      PllAtoY(\old(pll->pi.integ), \old(emf->alpha)));
  ensures error: out->error ==
    PllErr(PllE30(PllAtoX(\old(pll->pi.integ), \old(emf->beta)),
                  PllAtoY(\old(pll->pi.integ), \old(emf->alpha)),
                  out->sc.sine, out->sc.cosine),
           out->mag, \old(pll->mag_min), \old(pll->err_clamp));
  ensures error_range: -\old(pll->err_clamp) <= out->error <= \old(pll->err_clamp);
  ensures speed: out->speed == PllPiOut{Pre}(&pll->pi, out->error);
  ensures speed_range: pll->pi.params.out_min <= out->speed <= pll->pi.params.out_max;
  ensures speed_state: pll->speed == out->speed;
  ensures integ: pll->pi.integ == PiNextInteg{Pre}(&pll->pi, out->error);
  ensures acc: pll->theta_acc ==
    PllAccNext(\old(pll->theta_acc), out->speed * \old(pll->k_theta));
  ensures acc_mod:
    (pll->theta_acc - (\old(pll->theta_acc) + out->speed * \old(pll->k_theta)))
      % 4294967296 == 0;
  ensures theta_next: out->theta_next == PllAngle(pll->theta_acc);
  ensures speed_lpf: pll->speed_lpf.state ==
    LpfNext(\old(pll->speed_lpf.state), out->speed, \old(pll->speed_lpf.alpha));
  ensures speed_f: out->speed_f == QfocSat15(QfocRoundDiv(pll->speed_lpf.state, 65536));
  behavior coast:
    assumes PllCoast(QfocSat15(emf->alpha), QfocSat15(emf->beta), pll->mag_min);
    ensures below: out->mag < \old(pll->mag_min);
    ensures zero_error: out->error == 0;
  behavior track:
    assumes !PllCoast(QfocSat15(emf->alpha), QfocSat15(emf->beta), pll->mag_min);
    ensures above: out->mag >= \old(pll->mag_min);
  complete behaviors;
  disjoint behaviors;
*/
void qfoc_pll_step_emf(qfoc_pll_t *pll, const qfoc_ab_t *emf, qfoc_pll_out_t *out);

#ifdef __cplusplus
}
#endif

#endif /* QFOC_PLL_H */
