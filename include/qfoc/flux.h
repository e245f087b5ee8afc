/**
 * @file flux.h
 * @brief Rotor (active) flux observer: voltage-model integrator with a
 *        high-pass correction (E2-13 .. E2-26), per stationary axis.
 *
 * Equation tags E1-n, E2-n: specs/equations.md (sections 2 and 4).
 *
 * The observer estimates the rotor flux vector psi_r = psi_s - L i in the
 * stationary frame from the applied voltage and the measured current; its angle
 * is the rotor angle (up to the high-pass phase lead, qfoc_flux_lead()), which a
 * PLL (include/qfoc/pll.h) turns into angle and speed.
 *
 * Requirements: REQ-FLUX-001 .. REQ-FLUX-008 (specs/requirements/flux.md):
 * REQ-FLUX-001, REQ-FLUX-002, REQ-FLUX-003, REQ-FLUX-004, REQ-FLUX-005,
 * REQ-FLUX-006, REQ-FLUX-007, REQ-FLUX-008.
 *
 * @par Equations (specs/equations.md section 4)
 * Continuous model (E2-13, E2-14): d psi_s = u - R i, integrated through
 * (1/s)(tau s / (1 + tau s)), i.e. an integrator whose drift is removed by a
 * high-pass filter.  Discretised with s = (z - 1)/T (E2-16, E2-17) and applied per
 * axis with the inductance term (E2-19 .. E2-24, in their integer units):
 *
 *     psi_temp(k+1) = psi_temp(k) + (V_max u(k) - R_s i(k)/64 - K_gain psi(k)) / f_pwm
 *     psi(k+1)      = psi_temp(k+1) - i(k) (L_D + L_Q) / 8192
 *
 * Substituting psi_temp(k) = psi(k) + L i(k-1) gives the equivalent recursion on
 * the ROTOR flux, which qfoc implements with the rotor flux as its (wide) state:
 *
 *     psi(k) = psi(k-1) + g (u(k) - R i(k) - kg psi(k-1)) - L (i(k) - i(k-1))
 *
 *     g  = T w_base / 2^s      integration gain per sample (T = 1 / f_pwm)
 *     kg = 2^s K_gain / w_base high-pass corner, 2^s times its per-unit value
 *
 * with s the table's flux base (drive_cfg.h psi_shift: psi_base = 2^s V_base / w_base;
 * s = 0 for the reference motor, so g = T w_base and kg = K_gain / w_base there).  The
 * decay per sample g kg, and so the high-pass corner K_gain, do not depend on s; the
 * corner in per unit of w_base that qfoc_flux_lead() reads is kg / 2^s (the drive
 * passes it so).
 *
 * How the constants of E2-19 .. E2-24 map onto the parameters:
 *  - 630 = V_max: the integration scale V_base / psi_base = w_base of the
 *    bases of E2-19 (630 rad/s, close to 2 pi 100 Hz); divided by f_pwm it is
 *    the gain g = w_base T (gain, gain_shift);
 *  - R_s / 64: the resistance stored with 6 extra fraction bits so that the term
 *    has the units of 630 u; qfoc stores r = R / Z_base in Q15 and applies the
 *    common factor w_base T once, through g;
 *  - K_gain psi / f_pwm = (K_gain / w_base) (w_base T) psi = kg g psi: qfoc's kg
 *    is K_gain in per unit of w_base;
 *  - (L_D + L_Q) / 8192 = ((L_D + L_Q) / 2) / 4096: the mean inductance with the
 *    inductances stored in Q12 (raw / 4096 pu).  qfoc's l is also Q12, but holds
 *    L_q, not the mean (next paragraph).
 *
 * @par Salient machines: L = L_q (active flux)
 * With L = L_q, psi_s - L_q i = (psi_f + (L_d - L_q) i_d) e^{j theta}: the
 * "active flux" is exactly aligned with the rotor d axis for every load, so the
 * estimated angle is the rotor angle; only its magnitude changes with i_d.  The
 * mean (L_d + L_q)/2 of E2-24 is exact only for L_d = L_q: on the reference
 * motor (L_d = 2.6 mH, L_q = 4.2 mH) it puts the angle 14 degrees off at
 * i_q = 20 A.  Equivalently u - R i - L_q di/dt = d/dt(active flux) =
 * w psi_a (-sin theta, cos theta) in steady state: the extended back-EMF
 * (E1-8, E1-9) with the saliency term absorbed (E1-10).
 *
 * @par Step semantics
 * A call at sample k receives u = the stationary-frame voltage APPLIED DURING THE
 * LAST PWM PERIOD [k-1, k] (with compare registers that take effect one period
 * after they are written, the command computed two calls earlier) and i = the
 * current SAMPLED NOW, at k.  The observer remembers i(k-1) itself.  Every input
 * may be any int16_t value; -32768 is saturated to -32767 first.
 *
 * @par Per-unit scaling of the parameters (from the bases and f_pwm)
 * Bases (specs/scaling.md): V_base, I_base, w_base = 2 pi f_base,
 * psi_base = 2^s V_base / w_base, Z_base = V_base / I_base, L_base = psi_base / I_base.
 *
 *     g     = T w_base / 2^s                        gain = round(g 2^(15 + gain_shift))
 *     r     = R / Z_base                  Q15       r    = round(32768 R / Z_base)
 *     l     = L_q / L_base                Q12       l    = round(4096 L_q / L_base)
 *     kg    = 2^s K_gain / w_base         Q15       kg   = round(32768 kg)
 *
 * Reference motor (s = 0; V_base = 500 V, I_base = 40 A, f_base = 500 Hz, f_pwm = 8 kHz;
 * w_base = 3141.593 rad/s, psi_base = 0.159155 Wb, Z_base = 12.5 ohm,
 * L_base = 3.97887 mH; R = 0.35 ohm, L_d = 2.6 mH, L_q = 4.2 mH,
 * psi_f = 0.065 Wb = 0.40841 pu):
 *
 *     g  = 3141.593 / 8000 = 0.392699   -> gain = 12868, gain_shift = 0
 *                                          (or 25736 with gain_shift = 1: finer)
 *     r  = 0.35 / 12.5 = 0.028          -> 0.028 x 32768 = 917.5 -> 918
 *     l  = 4.2 / 3.97887 = 1.05558      -> 1.05558 x 4096 = 4323.6 -> 4324
 *     kg = 100 rad/s / 3141.593 = 0.031831 -> 0.031831 x 32768 = 1043.0 -> 1043
 *          (K_gain = 100 rad/s: high-pass corner 15.9 Hz electrical)
 *
 * Choose K_gain well below the lowest electrical speed at which the estimate is
 * used (the lead is atan(K_gain / w)) and well above the rate at which offsets
 * drift (the decay time constant of an offset is 1 / K_gain = 10 ms here).
 *
 * @par High-pass response and qfoc_flux_lead()
 * At a steady electrical speed w (pu of w_base) the estimate is the true rotor
 * flux times the discrete transfer function
 *
 *     H = (z - 1) / (z - 1 + g kg),  z = e^{jW},  W = w g (rad per sample)
 *       ~ j w / (j w + kg):   |H| ~ |w| / sqrt(w^2 + kg^2),  arg H ~ atan(kg / |w|)
 *
 * i.e. the estimate LEADS the rotor flux by atan(kg / |w|) in the direction of
 * rotation and is smaller by |H|.  qfoc_flux_lead() returns this lead as an
 * angle (negative, modulo 2^16, for w < 0); the caller subtracts it from the
 * PLL angle.  Reference motor, kg = 1043: w = 0.1 pu: lead 17.66 deg, |H| 0.953;
 * w = 0.6 pu: lead 3.04 deg, |H| 0.9986.  The exact discrete lead differs from
 * atan(kg / |w|) by at most 0.11 deg for |w| >= 0.1 pu (0.005 deg at 0.6 pu).
 *
 * R i term: the recursion E2-23 uses R i(k) (sampled at the end of the
 * period) where the period average of R i belongs; this shifts the estimate by
 * about -g R I / 2 (I the current vector), an angle error of about
 * g R i_q / (2 |psi_a|) rad: 0.19 deg at i = (-0.1, 0.25) pu on the reference
 * motor, 0.39 deg at i_q = 0.5 pu.  Both effects are checked against the exact
 * discrete steady state in tests/test_flux.c.
 *
 * @par Steady-state bound (E2-25, E2-26) and saturation
 * For a constant input (i = i_prev) the state settles at (E2-26)
 * psi = (u - R i) / kg, and psi_temp = psi + L i (E2-25).  In
 * general the state obeys a one-step invariance (lemma FluxBoundInvariant in
 * specs/flux.acsl, proved; it is stated on FluxRaw, the unsaturated new state
 * that the contract of qfoc_flux_step() names in `state_alpha` / `state_beta`
 * through FluxSum): for a bound B (Q27, 0 <= B <= 32767 x 4096), if
 * |psi(k-1)| <= B and the drive of the step satisfies
 *
 *     |g (u - R i) - L (i - i_prev)| + 1/2 + gain / 2^(19 + gain_shift) <= g kg B
 *
 * (Q27 units; the last two terms are the rounding slack, < 0.57 LSB; in integers,
 * predicate FluxDriveBounded: 4096 |gain x30 - 2^(18+s) l di|
 * + 2048 (gain + 2^(18+s)) <= gain kg B), then |psi(k)| <= B, so the state is not
 * saturated, and the Q15 output is the exact rounded state (`out_exact_alpha`,
 * lemma FluxOutExact).
 * Hence an input whose drive stays below g kg B keeps the estimate within B for
 * ever; for i = i_prev this is E2-26: |u - R i| <= kg B.  A real machine's drive
 * is the flux change per sample (about W |psi_a|), which the invariance bounds
 * only for W <= g kg; at speed the estimate's magnitude is |H| |psi_a|
 * (|H| <= 1.006 for the reference values), so the output saturates only when
 * the active flux exceeds about 0.99 pu.
 *
 * Bad input and saturation: the state is held in Q4.27 (raw / 2^27 pu,
 * +-16 pu) and saturates symmetrically at +-(2^31 - 1); the output saturates at
 * +-32767 (+-1 pu) while the state keeps its value, so the estimate recovers
 * without windup as soon as the flux returns below 1 pu.  Parameters outside
 * their ranges are rejected by qfoc_flux_init() (safe state: output 0).
 *
 * @par Accuracy
 * Per sample the two roundings add at most 1/2 + gain / 2^(19 + gain_shift)
 * < 0.5625 Q27 LSB; they decay with (1 - g kg), so the state stays within
 * 0.5625 / (g kg) Q27 LSB of the real-valued recursion (45 Q27 LSB = 0.011 Q15
 * LSB for the reference values); the output adds 1/2 LSB of rounding.
 */
#ifndef QFOC_FLUX_H
#define QFOC_FLUX_H

#include "qfoc/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/** qfoc_flux_init() status: parameters accepted. */
#define QFOC_FLUX_OK ((int32_t)0)
/** qfoc_flux_init() status: parameters rejected, instance set to the safe state. */
#define QFOC_FLUX_ERR_PARAM ((int32_t)-1)
/** Largest admissible gain_shift (g = gain / 2^30 at most). */
#define QFOC_FLUX_SHIFT_MAX ((uint8_t)15u)
/** Q27 state per Q15 output LSB: 2^27 / 2^15 = 4096 (also the Q12 scale of l). */
#define QFOC_FLUX_Q27_PER_Q15 ((int32_t)4096)

/** Flux observer parameters (E2-19 .. E2-24; see the file comment). */
typedef struct {
    qfoc_q15_t gain;     /**< g = T w_base mantissa: g = gain / 2^(15 + gain_shift),
                              0..32767 */
    uint8_t gain_shift;  /**< 0..15 (a larger shift makes g SMALLER) */
    qfoc_q15_t r;        /**< R / Z_base, Q15, 0..32767 */
    int16_t l;           /**< L_q / L_base in Q12 (raw / 4096 pu), 0..32767 (< 8 pu) */
    qfoc_q15_t kg;       /**< K_gain / w_base (high-pass corner), Q15, 0..32767;
                              0 = pure integrator */
} qfoc_flux_params_t;

/** Flux observer instance. */
typedef struct {
    qfoc_flux_params_t params;  /**< parameters */
    int32_t psi_alpha;  /**< rotor flux alpha, Q4.27 (raw / 2^27 pu), symmetric Q31 range */
    int32_t psi_beta;   /**< rotor flux beta, Q4.27, symmetric Q31 range */
    qfoc_ab_t i_prev;   /**< current of the previous call, Q15, symmetric range */
} qfoc_flux_t;

#ifdef __FRAMAC__
/* ACSL predicates over the types above, read by Frama-C only (DEV-001). */
/* cppcheck-suppress misra-c2012-20.1 ; DEV-001 */
#include "flux.acsl"
#endif

/**
 * @brief Check a flux observer parameter set.
 * @param[in] p parameters (read only)
 * @return true when gain >= 0, gain_shift <= 15, r >= 0, l >= 0 and kg >= 0.
 *
 * Scaling and overflow: compares only.
 *
 * Requirements: REQ-FLUX-001.
 */
/*@
  requires valid_p: \valid_read(p);
  assigns \nothing;
  ensures result: \result <==> FluxParamsValid(p);
*/
bool qfoc_flux_params_is_valid(const qfoc_flux_params_t *p);

/**
 * @brief Check a flux observer instance (run-time twin of the ACSL predicate
 *        FluxValid).
 * @param[in] o instance (read only)
 * @return true when the parameters are valid, both flux states are in the
 *         symmetric Q31 range (-2^31 excluded) and both previous currents are in
 *         the symmetric Q15 range (-32768 excluded).
 *
 * Scaling and overflow: compares only.
 *
 * Requirements: REQ-FLUX-001.
 */
/*@
  requires valid_o: \valid_read(o);
  assigns \nothing;
  ensures result: \result <==> FluxValid(o);
*/
bool qfoc_flux_is_valid(const qfoc_flux_t *o);

/**
 * @brief Initialise a flux observer: store the parameters, clear the state.
 * @param[out] o instance to initialise
 * @param[in]  p parameters (copied; not referenced afterwards)
 * @return QFOC_FLUX_OK (0) when qfoc_flux_params_is_valid(p);
 *         QFOC_FLUX_ERR_PARAM (-1) otherwise.
 *
 * Bad input: invalid parameters are not stored; the safe state gain = 0,
 * gain_shift = 0, r = 0, l = 0, kg = 0 is set instead.  It is valid, and every
 * later step returns a zero flux, which a PLL reads as "no signal" (it coasts).
 * In both cases the flux state and the previous current are 0.
 *
 * Scaling and overflow: copies only.
 *
 * Requirements: REQ-FLUX-001.
 */
/*@
  requires valid_o: \valid(o);
  requires valid_p: \valid_read(p);
  requires sep: \separated(o, p);
  assigns *o;
  ensures valid: FluxValid(o);
  ensures state: o->psi_alpha == 0 && o->psi_beta == 0;
  ensures i_prev: o->i_prev.alpha == 0 && o->i_prev.beta == 0;
  behavior accepted:
    assumes FluxParamsValid(p);
    ensures result: \result == 0;
    ensures params: o->params.gain == p->gain && o->params.gain_shift == p->gain_shift
                    && o->params.r == p->r && o->params.l == p->l
                    && o->params.kg == p->kg;
  behavior rejected:
    assumes !FluxParamsValid(p);
    ensures result: \result == -1;
    ensures safe: o->params.gain == 0 && o->params.gain_shift == 0
                  && o->params.r == 0 && o->params.l == 0 && o->params.kg == 0;
  complete behaviors;
  disjoint behaviors;
*/
int32_t qfoc_flux_init(qfoc_flux_t *o, const qfoc_flux_params_t *p);

/**
 * @brief Set the flux estimate and the remembered current (e.g. at a restart
 *        from a known rotor position, or 0 / 0 after a fault).
 * @param[in,out] o    instance with valid parameters
 * @param[in]     psi0 rotor flux to start from, Q15 (pu of psi_base), any int16_t
 * @param[in]     i0   present current (the i(k-1) of the next step), Q15, any
 *                     int16_t
 *
 * Bad input: -32768 in either input is saturated to -32767.
 *
 * Scaling and overflow: psi0 Q15 -> Q27 by x 4096, exact in 32 bits after the
 * saturation (|value| <= 32767 x 4096 = 134213632).
 *
 * Requirements: REQ-FLUX-002.
 */
/*@
  requires valid_o: \valid(o);
  requires valid_psi0: \valid_read(psi0);
  requires valid_i0: \valid_read(i0);
  requires sep: \separated(o, psi0) && \separated(o, i0);
  requires params_valid: FluxParamsValid(&o->params);
  assigns o->psi_alpha, o->psi_beta, o->i_prev;
  ensures valid: FluxValid(o);
  ensures state: o->psi_alpha == QfocSat15(psi0->alpha) * 4096
                 && o->psi_beta == QfocSat15(psi0->beta) * 4096;
  ensures i_prev: o->i_prev.alpha == QfocSat15(i0->alpha)
                  && o->i_prev.beta == QfocSat15(i0->beta);
*/
void qfoc_flux_reset(qfoc_flux_t *o, const qfoc_ab_t *psi0, const qfoc_ab_t *i0);

/**
 * @brief One observer sample (E2-19 .. E2-24 as a rotor-flux recursion):
 *        psi(k) = psi(k-1) + g (u - R i - kg psi(k-1)) - L (i(k) - i(k-1)).
 * @param[in,out] o     valid instance (qfoc_flux_is_valid())
 * @param[in]     u     voltage applied during the last PWM period [k-1, k],
 *                      stationary frame, Q15 of V_base, any int16_t
 * @param[in]     i     current sampled now (k), stationary frame, Q15 of I_base,
 *                      any int16_t
 * @param[out]    psi_r estimated rotor (active) flux at k, Q15 of psi_base:
 *                      the state rounded to nearest, saturated to +-32767
 *
 * Per axis (u, i saturated to [-32767, 32767] first; p = the parameters):
 *
 *     x30  = u 32768 - r i                                  u - R i, Q30, exact
 *     leak = RoundDiv(kg psi, 4096)                         kg psi, Q42 -> Q30
 *     inc  = RoundDiv((x30 - leak) gain, 2^(18 + gain_shift))   Q45 -> Q27
 *     psi' = Sat31(psi + inc - l (i - i_prev))              l di: Q12 x Q15 = Q27
 *     out  = Sat15(RoundDiv(psi', 4096))                    Q27 -> Q15
 *     i_prev = i
 *
 * Scaling and overflow: |x30| <= 32767 x 65535 < 2^31.  kg psi (< 2^46) is
 * not formed: the state is split as psi = 4096 ph + pl, 0 <= pl < 4096 (floor
 * division of psi + 2^31 in unsigned 32-bit arithmetic), so that
 * leak = kg ph + lr with lr = floor((kg pl + 2048 - [psi < 0]) / 4096) in
 * [0, 32760] (kg pl < 2^27, 32 bits), and
 * (x30 - leak) gain = (x30 - lr) gain - (kg gain) ph: one 32 x 32 -> 64-bit
 * product and one 64-bit multiply-accumulate, |.| <= 633280043253767 < 2^50
 * (the identity with RoundDiv(kg psi, 4096) is proved, assert leak_split).  The
 * division by 2^(18 + gain_shift) is done on the magnitude plus the rounding
 * offset 2^(17 + gain_shift) as a 64-bit division by the constant 2^18 (the
 * quotient is below 2^32) followed by a 32-bit unsigned division by
 * 2^gain_shift.  Two floor divisions equal one floor division by
 * 2^(18 + gain_shift), so inc is a single rounding to nearest, ties away from
 * zero, |inc| <= 2415788033; the contract states the two-step form
 * (FluxScaleDiv in specs/flux.acsl), its rounding error
 * |2^(18 + s) inc - x| <= 2^(17 + s) is proved (lemma FluxScaleDivErr), and the
 * tests compare it bit-exactly with a single-rounding reference.
 * |l di| <= 32767 x 65534 < 2^31; the sum is formed in 64 bits and saturated to
 * the symmetric Q31 range.  No 64-bit division by a variable, no shift of a
 * negative value.
 *
 * Flux bound (E2-25, E2-26): if |psi(k-1)| <= B <= 32767 x 4096 and the drive
 * meets FluxDriveBounded (file comment), lemma FluxBoundInvariant applied to
 * `state_alpha` gives |psi(k)| <= B (behaviour `alpha_exact`), and
 * `out_exact_alpha` makes the output the exact rounded state; the same per beta.
 *
 * Bad input: none; every input value is accepted.  A state beyond +-16 pu is
 * held at +-(2^31 - 1) (behaviours upper / lower), an output beyond +-1 pu at
 * +-32767.
 *
 * Requirements: REQ-FLUX-003, REQ-FLUX-004, REQ-FLUX-005, REQ-FLUX-006.
 */
/*@
  requires valid_o: \valid(o);
  requires valid_u: \valid_read(u);
  requires valid_i: \valid_read(i);
  requires valid_out: \valid(psi_r);
  requires sep_u: \separated(o, u, psi_r);
  requires sep_i: \separated(o, i, psi_r);
  requires o_valid: FluxValid(o);
  assigns o->psi_alpha, o->psi_beta, o->i_prev, *psi_r;
  ensures still_valid: FluxValid(o);
  ensures i_prev: o->i_prev.alpha == QfocSat15(\old(i->alpha))
                  && o->i_prev.beta == QfocSat15(\old(i->beta));
  ensures state_alpha: o->psi_alpha ==
    QfocSat31(\old(FluxSum(&o->params, o->psi_alpha, u->alpha, i->alpha,
                           o->i_prev.alpha)));
  ensures state_beta: o->psi_beta ==
    QfocSat31(\old(FluxSum(&o->params, o->psi_beta, u->beta, i->beta,
                           o->i_prev.beta)));
  ensures out_alpha: psi_r->alpha == FluxOut(o->psi_alpha);
  ensures out_beta: psi_r->beta == FluxOut(o->psi_beta);
  ensures out_range: QfocQ15Sym(psi_r->alpha) && QfocQ15Sym(psi_r->beta);
  ensures out_exact_alpha: -134213632 <= o->psi_alpha <= 134213632 ==>
    psi_r->alpha == QfocRoundDiv(o->psi_alpha, 4096);
  ensures out_exact_beta: -134213632 <= o->psi_beta <= 134213632 ==>
    psi_r->beta == QfocRoundDiv(o->psi_beta, 4096);
  behavior alpha_exact:
    assumes QfocQ31Sym(FluxSum(&o->params, o->psi_alpha, u->alpha, i->alpha,
                               o->i_prev.alpha));
    ensures state: o->psi_alpha == \old(FluxSum(&o->params, o->psi_alpha, u->alpha,
                                                 i->alpha, o->i_prev.alpha));
  behavior alpha_upper:
    assumes FluxSum(&o->params, o->psi_alpha, u->alpha, i->alpha, o->i_prev.alpha)
            > 2147483647;
    ensures state: o->psi_alpha == 2147483647;
  behavior alpha_lower:
    assumes FluxSum(&o->params, o->psi_alpha, u->alpha, i->alpha, o->i_prev.alpha)
            < -2147483647;
    ensures state: o->psi_alpha == -2147483647;
  behavior beta_exact:
    assumes QfocQ31Sym(FluxSum(&o->params, o->psi_beta, u->beta, i->beta,
                               o->i_prev.beta));
    ensures state: o->psi_beta == \old(FluxSum(&o->params, o->psi_beta, u->beta,
                                                i->beta, o->i_prev.beta));
  behavior beta_upper:
    assumes FluxSum(&o->params, o->psi_beta, u->beta, i->beta, o->i_prev.beta)
            > 2147483647;
    ensures state: o->psi_beta == 2147483647;
  behavior beta_lower:
    assumes FluxSum(&o->params, o->psi_beta, u->beta, i->beta, o->i_prev.beta)
            < -2147483647;
    ensures state: o->psi_beta == -2147483647;
  complete behaviors alpha_exact, alpha_upper, alpha_lower;
  disjoint behaviors alpha_exact, alpha_upper, alpha_lower;
  complete behaviors beta_exact, beta_upper, beta_lower;
  disjoint behaviors beta_exact, beta_upper, beta_lower;
*/
void qfoc_flux_step(qfoc_flux_t *o, const qfoc_ab_t *u, const qfoc_ab_t *i,
                    qfoc_ab_t *psi_r);

/**
 * @brief Phase lead of the flux estimate over the true rotor flux, caused by the
 *        high-pass correction, at electrical speed w.
 * @param[in] o valid instance (only kg is read)
 * @param[in] w electrical speed, Q15 of w_base, signed (the PLL speed), any
 *              int16_t (-32768 is saturated to -32767)
 * @return the lead in angle counts (65536 per turn): atan2(kg, |w|) for w >= 0
 *         and its negation modulo 2^16 for w < 0.  Subtract it from the angle of
 *         the estimate (the PLL angle) to obtain the rotor angle.
 *
 * The estimate is the rotor flux times j w / (j w + kg) (continuous
 * approximation of the discrete high-pass, see the file comment): it leads by
 * atan(kg / |w|) in the direction of rotation.  At w = 0 the lead is 90 degrees
 * (16384 counts), the true limit for w -> 0+; with kg = 0 (pure integrator) the
 * lead is 0.  Accuracy: qfoc_atan2() error (<= 1 count = 0.0055 deg) plus the
 * difference between the discrete and the continuous high-pass (<= 0.11 deg for
 * |w| >= 0.1 pu on the reference values, smaller at higher speed).
 *
 * Bad input: none; every w is accepted.
 *
 * Scaling and overflow: |w| saturated to [0, 32767]; the negation of a lead
 * a in [1, 65535] is formed as 65536 - a in 32 bits (in [1, 65535]; a lead of
 * 0 stays 0), no wrap-around in a C type.
 *
 * Requirements: REQ-FLUX-007.
 */
/*@
  requires valid_o: \valid_read(o);
  requires o_valid: FluxValid(o);
  assigns \nothing;
  ensures range: 0 <= \result <= 65535;
  behavior no_highpass:
    assumes o->params.kg == 0;
    ensures zero: \result == 0;
  behavior standstill:
    assumes o->params.kg > 0 && w == 0;
    ensures quarter_turn: \result == 16384;
  behavior forward:
    assumes o->params.kg > 0 && w > 0;
  behavior reverse:
    assumes o->params.kg > 0 && w < 0;
  complete behaviors;
  disjoint behaviors;
*/
qfoc_angle_t qfoc_flux_lead(const qfoc_flux_t *o, qfoc_q15_t w);

#ifdef __cplusplus
}
#endif

#endif /* QFOC_FLUX_H */
