/**
 * @file trqcomp.h
 * @brief Torque compensation of the compressor's pulsating load (formerly
 *        TrqComp(), specs/equations.md section 8.4): a feed-forward q-current at
 *        1x and 2x the mechanical frequency, learned online from the speed
 *        ripple, and the mechanical-angle tracker it is synchronised with.
 *
 * A rotary compressor's load torque pulsates once (and, with its harmonics,
 * twice) per mechanical revolution.  The speed loop alone cannot follow it: its
 * bandwidth (about 8.5 Hz on the reference motor) is below the mechanical
 * frequency (25 Hz at 1500 rpm), so the load pulsation shows as a speed ripple
 * (about +-450 rpm at 1500 rpm with the reference motor's 4.5 N m x (1 +
 * 0.5 sin) load).  This module learns, per mechanical angle, the q-current that
 * cancels the pulsation and feeds it forward:
 *
 *     i_ff(theta_m) = sum over h = 1, 2 of  a_h cos(h theta_m) + b_h sin(h theta_m)
 *
 * (Q15 of I_base), added by the drive to the speed PI's i_q reference.
 *
 * ## Mechanical angle (qfoc_mech_t)
 * The observer gives the electrical angle theta_e; the load is synchronous with
 * the mechanical angle theta_m = theta_e / n_p (+ k turn / n_p).  The tracker
 * counts the electrical revolutions modulo n_p from the change of theta_e at each
 * fast step and returns
 *
 *     theta_m = floor((turn x 65536 + theta_e) / n_p)       (65536 per mechanical turn)
 *
 * Assumption: theta_e changes by less than half an electrical turn per call
 * (a step of d counts with |d| < 32768 is taken as the short way round).  At
 * 8 kHz and 8000 rpm x 3 pole pairs the step is 400 Hz / 8 kHz = 0.05 turn; the
 * assumption holds up to 10 x that speed.  The mechanical zero is arbitrary: it is
 * the position at qfoc_mech_init() (turn 0).  The learned coefficients are
 * therefore relative to this counted zero, and the drive must reset them
 * (qfoc_trqcomp_reset()) at every start, when it re-initialises the tracker.
 * qfoc_trqcomp_phase1() returns the angle of the learned 1x component (the
 * position of the compressor's peak load relative to the counted zero); a drive
 * that needs the true mechanical zero (e.g. to keep coefficients across starts)
 * finds it from this phase and a stored reference phase of the compressor.
 *
 * ## Learning law (derivation)
 * Mechanics (mechanical rad/s, ripple parts only, speed reference constant):
 *
 *     J dw/dt + B w = K_t (i_pi + i_ff) - T_L,     i_pi = -(k_p + k_i / s) w
 *
 * so the speed ripple is w(s) = G(s) [K_t i_ff(s) - T_L(s)] with
 *
 *     G(s) = 1 / (J s + B + K_t k_p + K_t k_i / s).
 *
 * At the harmonic w_h = h W (W the mechanical speed) write G(j w_h) = |G| e^(j psi_h),
 * psi_h = -atan((J w_h - K_t k_i / w_h) / (B + K_t k_p)): the pure inertia gives
 * -90 degrees, the proportional term of the speed PI reduces the lag.  The speed
 * error e = w_ref - w = -w is the mean over the last 1 ms, i.e. delayed by
 * 0.5 ms (a further -w_h x 0.5 ms).  With i_ff,h = a cos(h theta) + b sin(h theta)
 * in steady state
 *
 *     e = -K_t |G| [a cos(h theta + psi) + b sin(h theta + psi)] + (load part),
 *     de/da = -K_t |G| cos(h theta + psi),   de/db = -K_t |G| sin(h theta + psi).
 *
 * The steepest descent of e^2 / 2 is a += mu e cos(h theta + psi),
 * b += mu e sin(h theta + psi) (K_t |G| absorbed in mu): the error must be
 * correlated with the regressors shifted by the phase psi of the torque-to-speed
 * path.  With the model value psi = -90 degrees (inertia):
 *
 *     a_h += mu e sin(h theta_m),     b_h -= mu e cos(h theta_m)        (W > 0)
 *
 * and, for reverse rotation (W < 0, the harmonic's time frequency is negative,
 * G(-jw) = conj G(jw), psi = +90 degrees), a_h -= mu e sin, b_h += mu e cos.
 * Convergence: averaged over a revolution (mu small), the coefficient error
 * c = (a - a*, b - b*) obeys c(k+1) = (I - mu' R(delta)) c(k) with
 * mu' = mu |G_pu| / 2, R(delta) the rotation by the phase error
 * delta = psi_true - psi_model; the eigenvalues 1 - mu' e^(+-j delta) lie inside
 * the unit circle iff cos(delta) > 0 and mu' < 2 cos(delta), and the time constant
 * is 1 / (mu' cos(delta)) ticks.  For the reference motor |delta| <= 44 degrees
 * from 600 to 6000 rpm for both harmonics (specs/requirements/trqcomp.md, table),
 * so the fixed -90 degrees model converges over the whole default window.
 * Here mu = gain / 32768 (pu current per pu speed error per 1 ms tick).
 *
 * Coefficients are held in Q31 (Q15 x 65536) so that the small per-tick updates
 * accumulate; each is clamped to +-amp_max (Q15, x 65536 in Q31), so the amplitude
 * of each harmonic is at most sqrt(2) amp_max and |i_ff| <= 4 amp_max (2 sqrt 2
 * amp_max in fact).  Learning (qfoc_trqcomp_learn) and output
 * (qfoc_trqcomp_output) act only while speed_min <= |speed| <= speed_max;
 * outside that window the output is 0 and the coefficients are held (so a brief
 * excursion does not lose what was learned; the drive resets them at each start).
 *
 * All functions are total for every value of their input types (int16 -32768
 * included).  Parameters are checked by the _init functions; the others require
 * a valid instance (qfoc_mech_is_valid(), qfoc_trqcomp_is_valid()).
 *
 * Requirements: REQ-TC-001 .. REQ-TC-010 (specs/requirements/trqcomp.md).
 */
#ifndef QFOC_TRQCOMP_H
#define QFOC_TRQCOMP_H

#include "qfoc/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Status: parameters accepted. */
#define QFOC_TRQCOMP_OK ((int32_t)0)
/** Status: parameters rejected, instance set to the safe state. */
#define QFOC_TRQCOMP_ERR_PARAM ((int32_t)-1)
/** Largest pole-pair count of the mechanical-angle tracker. */
#define QFOC_MECH_PP_MAX ((uint8_t)16u)
/** Number of learned harmonics (1x and 2x the mechanical frequency). */
#define QFOC_TRQCOMP_HARMONICS (2u)

/** Torque-compensation parameters (drive configuration: tc_gain, tc_amp_max, ...). */
typedef struct {
    qfoc_q15_t gain;       /**< learning gain mu, Q15 (pu current per pu speed error per tick), 0..32767 */
    qfoc_q15_t amp_max;    /**< limit of each coefficient, Q15 of I_base, 0..32767 */
    qfoc_q15_t speed_min;  /**< learning and output only while speed_min <= |speed| <= speed_max */
    qfoc_q15_t speed_max;  /**< (electrical speed, Q15), 0 <= speed_min <= speed_max */
    uint8_t pole_pairs;    /**< 1..16, for the drive's qfoc_mech_init() */
} qfoc_trqcomp_params_t;

/** Mechanical-angle tracker. */
typedef struct {
    uint8_t pole_pairs;    /**< 1..16 */
    uint8_t turn;          /**< electrical revolutions counted modulo pole_pairs, 0..pole_pairs-1 */
    qfoc_angle_t theta_e;  /**< electrical angle of the last call */
    uint32_t recip;        /**< ceil(2^28 / pole_pairs): the division as a multiplication */
} qfoc_mech_t;

/** Torque-compensation instance. */
typedef struct {
    qfoc_trqcomp_params_t params;         /**< gains, limits, speed window */
    qfoc_q31_t a[QFOC_TRQCOMP_HARMONICS]; /**< cosine coefficients a_1, a_2, Q31 of I_base, |.| <= amp_max x 65536 */
    qfoc_q31_t b[QFOC_TRQCOMP_HARMONICS]; /**< sine coefficients b_1, b_2, Q31 of I_base, |.| <= amp_max x 65536 */
} qfoc_trqcomp_t;

#ifdef __FRAMAC__
/* ACSL predicates over the types above, read by Frama-C only (DEV-001). */
/* cppcheck-suppress misra-c2012-20.1 ; DEV-001 */
#include "trqcomp.acsl"
#endif

/**
 * @brief Check a mechanical-angle tracker (run-time twin of MechValid).
 * @param[in] m tracker (read only)
 * @return true when 1 <= pole_pairs <= 16, turn < pole_pairs and
 *         recip == ceil(2^28 / pole_pairs).
 *
 * Scaling and overflow: compares and one 32-bit division of constants' size
 * (2^28 + 15 < 2^32).
 *
 * Requirements: REQ-TC-001.
 */
/*@
  requires valid_m: \valid_read(m);
  assigns \nothing;
  ensures result: \result <==> MechValid(m);
*/
bool qfoc_mech_is_valid(const qfoc_mech_t *m);

/**
 * @brief Initialise the tracker: the present position becomes the mechanical zero
 *        of the count (turn 0).
 * @param[out] m          tracker
 * @param[in]  pole_pairs 1..16
 * @param[in]  theta_e    present electrical angle, any value
 * @return QFOC_TRQCOMP_OK (0); QFOC_TRQCOMP_ERR_PARAM (-1) when pole_pairs is
 *         outside 1..16, in which case 1 pole pair is used (valid state).
 *
 * Scaling and overflow: recip = (2^28 + pp - 1) / pp in uint32 (one division, at
 * initialisation only).
 *
 * Requirements: REQ-TC-001.
 */
/*@
  requires valid_m: \valid(m);
  assigns *m;
  ensures valid: MechValid(m);
  ensures turn: m->turn == 0;
  ensures theta: m->theta_e == theta_e;
  behavior accepted:
    assumes 1 <= pole_pairs <= 16;
    ensures result: \result == 0;
    ensures pp: m->pole_pairs == pole_pairs;
  behavior rejected:
    assumes pole_pairs < 1 || pole_pairs > 16;
    ensures result: \result == -1;
    ensures pp: m->pole_pairs == 1;
  complete behaviors;
  disjoint behaviors;
*/
int32_t qfoc_mech_init(qfoc_mech_t *m, uint8_t pole_pairs, qfoc_angle_t theta_e);

/**
 * @brief Fast step: count electrical revolutions and return the mechanical angle.
 * @param[in,out] m       valid tracker (qfoc_mech_is_valid())
 * @param[in]     theta_e electrical angle of this step, any value
 * @return theta_m = floor((turn x 65536 + theta_e) / pole_pairs), 65536 counts per
 *         mechanical turn, exact (no rounding error beyond the floor: the result is
 *         within 1 count below the real value (turn x 65536 + theta_e) / pole_pairs).
 *
 * Counting: d = theta_e - theta_e(previous) as an integer in [-65535, 65535];
 * d < -32768 is a forward wrap (turn + 1 mod pole_pairs), d > 32767 a reverse wrap
 * (turn - 1 mod pole_pairs); otherwise the turn is kept.  This reads every step of
 * less than half an electrical turn correctly in both directions (see the file
 * comment for the speed bound).
 *
 * Scaling and overflow: n = turn x 65536 + theta_e < 16 x 65536 = 2^20 in uint32;
 * n x recip < 2^20 x 2^28 = 2^48 in uint64; / 2^28 (a shift) gives
 * floor(n / pole_pairs) exactly: with recip = ceil(2^28 / pp) = (2^28 + e) / pp,
 * e < pp, n = q pp + r, n recip = q 2^28 + q e + r recip and q e + r recip
 * < 2^20 x 16 / pp + (pp - 1) (2^28 + pp) / pp < 2^28 (lemmas MechExact1..16, one
 * per pole-pair count); the quotient is < 65536 because n < pp x 65536.
 *
 * Requirements: REQ-TC-002.
 */
/*@
  requires valid_m: \valid(m);
  requires m_valid: MechValid(m);
  assigns m->turn, m->theta_e;
  ensures valid: MechValid(m);
  ensures theta: m->theta_e == theta_e;
  ensures turn: m->turn == MechNextTurn(\old(m->turn), m->pole_pairs, \old(m->theta_e), theta_e);
  ensures result: \result == MechCount(m->turn, theta_e) / m->pole_pairs;
  behavior forward_wrap:
    assumes theta_e - m->theta_e < -32768;
    ensures turn_up: m->turn == ((\old(m->turn) + 1 == m->pole_pairs) ? 0 : \old(m->turn) + 1);
  behavior reverse_wrap:
    assumes theta_e - m->theta_e > 32767;
    ensures turn_down: m->turn == ((\old(m->turn) == 0) ? m->pole_pairs - 1 : \old(m->turn) - 1);
  behavior same_turn:
    assumes -32768 <= theta_e - m->theta_e <= 32767;
    ensures turn_kept: m->turn == \old(m->turn);
  complete behaviors;
  disjoint behaviors;
*/
qfoc_angle_t qfoc_mech_update(qfoc_mech_t *m, qfoc_angle_t theta_e);

/**
 * @brief Check a torque-compensation parameter set.
 * @param[in] p parameters (read only)
 * @return true when gain >= 0, amp_max >= 0, 0 <= speed_min <= speed_max and
 *         1 <= pole_pairs <= 16.
 *
 * Scaling and overflow: compares only.
 *
 * Requirements: REQ-TC-003.
 */
/*@
  requires valid_p: \valid_read(p);
  assigns \nothing;
  ensures result: \result <==> TcParamsValid(p);
*/
bool qfoc_trqcomp_params_is_valid(const qfoc_trqcomp_params_t *p);

/**
 * @brief Check a torque-compensation instance (run-time twin of TcValid).
 * @param[in] tc instance (read only)
 * @return true when the parameters are valid and every coefficient lies in
 *         [-amp_max x 65536, amp_max x 65536].
 *
 * Scaling and overflow: amp_max x 65536 <= 32767 x 65536 < 2^31 fits int32.
 *
 * Requirements: REQ-TC-004.
 */
/*@
  requires valid_tc: \valid_read(tc);
  assigns \nothing;
  ensures result: \result <==> TcValid(tc);
*/
bool qfoc_trqcomp_is_valid(const qfoc_trqcomp_t *tc);

/**
 * @brief Initialise: store the parameters and clear the coefficients.
 * @param[out] tc instance
 * @param[in]  p  parameters (copied)
 * @return QFOC_TRQCOMP_OK (0) for valid parameters; QFOC_TRQCOMP_ERR_PARAM (-1)
 *         otherwise, and the instance is set to the safe state gain 0,
 *         amp_max 0, speed window [0, 0], 1 pole pair: valid, never learns, its
 *         output is always 0.
 *
 * Scaling and overflow: copies only.
 *
 * Requirements: REQ-TC-003, REQ-TC-004.
 */
/*@
  requires valid_tc: \valid(tc);
  requires valid_p: \valid_read(p);
  requires sep: \separated(tc, p);
  assigns *tc;
  ensures valid: TcValid(tc);
  ensures zero: tc->a[0] == 0 && tc->b[0] == 0 && tc->a[1] == 0 && tc->b[1] == 0;
  behavior accepted:
    assumes TcParamsValid(p);
    ensures result: \result == 0;
    ensures params: tc->params.gain == p->gain && tc->params.amp_max == p->amp_max &&
                    tc->params.speed_min == p->speed_min &&
                    tc->params.speed_max == p->speed_max &&
                    tc->params.pole_pairs == p->pole_pairs;
  behavior rejected:
    assumes !TcParamsValid(p);
    ensures result: \result == -1;
    ensures safe: tc->params.gain == 0 && tc->params.amp_max == 0 &&
                  tc->params.speed_min == 0 && tc->params.speed_max == 0 &&
                  tc->params.pole_pairs == 1;
  complete behaviors;
  disjoint behaviors;
*/
int32_t qfoc_trqcomp_init(qfoc_trqcomp_t *tc, const qfoc_trqcomp_params_t *p);

/**
 * @brief Clear the learned coefficients (drive start; the mechanical zero of a new
 *        qfoc_mech_init() differs from the previous one).
 * @param[in,out] tc instance with valid parameters
 *
 * Scaling and overflow: stores only.
 *
 * Requirements: REQ-TC-004.
 */
/*@
  requires valid_tc: \valid(tc);
  requires params_valid: TcParamsValid(&tc->params);
  assigns tc->a[0 .. 1], tc->b[0 .. 1];
  ensures valid: TcValid(tc);
  ensures zero: tc->a[0] == 0 && tc->b[0] == 0 && tc->a[1] == 0 && tc->b[1] == 0;
*/
void qfoc_trqcomp_reset(qfoc_trqcomp_t *tc);

/**
 * @brief 1 ms tick: one gradient step of the four coefficients from the speed error.
 * @param[in,out] tc        valid instance (qfoc_trqcomp_is_valid())
 * @param[in]     theta_m   mechanical angle at the tick (qfoc_mech_update()), any value
 * @param[in]     speed_err speed reference - speed estimate (the speed PI's error),
 *                          Q15 of w_base, any int16_t (-32768 included)
 * @param[in]     speed     electrical speed estimate, Q15, any int16_t; its sign
 *                          selects the direction of the regressor shift
 *
 * Law (see the file comment): with s_1, c_1 = qfoc_sincos(theta_m), the second
 * harmonic from the double-angle identities s_2 = 2 s_1 c_1, c_2 = c_1^2 - s_1^2 (each
 * rounded to Q15, within 2.5 LSB of 32767 sin / cos of 2 theta_m) and sigma = +1 for
 * speed >= 0, -1 otherwise:
 *
 *     a_h = clamp(a_h + 2 gain round(e x sigma s_h / 32768), +-amp_max x 65536)
 *     b_h = clamp(b_h + 2 gain round(e x (-sigma c_h) / 32768), +-amp_max x 65536)
 *
 * only while speed_min <= |speed| <= speed_max; outside, nothing changes.  The second
 * harmonic (h = 2) learns only while also 2 |speed| <= speed_max: every learned
 * frequency is then at most the first harmonic's at speed_max, the frequency up to
 * which the table's window keeps the law's phase error small (the tool derives
 * speed_max from it); above, a_2 and b_2 are held (and still output).
 *
 * Integration rule: the drive skips this call in a tick in which the i_q
 * reference (speed PI output + qfoc_trqcomp_output()) was clamped to +-i_max in
 * any fast step: the gradient assumes that the current follows the feed-forward.
 * Without this hold a load whose peak needs more than i_max winds the
 * coefficients up to amp_max (closed-loop test with a 4.5 N m x (1 + 0.5 sin)
 * load whose peak needs 23 A > i_max = 20 A: the speed fell from 1500 to 784 rpm;
 * with the hold it stays at 1499 rpm and the peak-to-peak ripple falls by 76 %).
 *
 * Bad input: none; every int16 value is accepted (the regressors are in
 * [-32767, 32767], so the rounded product never saturates).
 *
 * Scaling and overflow: e (Q15) x regressor (Q15) = Q30, |.| <= 32768 x 32767
 * < 2^30, rounded to Q15 (qfoc_q15_mul, |p| <= 32767); x gain (Q15) x 2 =
 * increment in Q31 (|.| <= 2 x 32767^2 < 2^31, exact in int32), i.e. a real step
 * gain/32768 x e/32768 x r/32768 pu; added to the Q31 coefficient in int64 and
 * clamped to +-amp_max x 65536 (< 2^31).
 *
 * Requirements: REQ-TC-005, REQ-TC-006, REQ-TC-007, REQ-TC-010.
 */
/*@
  requires valid_tc: \valid(tc);
  requires tc_valid: TcValid(tc);
  assigns tc->a[0 .. 1], tc->b[0 .. 1];
  ensures valid: TcValid(tc);
  behavior hold:
    assumes !TcInWindow(tc, speed) || speed_err == 0 || tc->params.gain == 0;
    ensures held: tc->a[0] == \old(tc->a[0]) && tc->b[0] == \old(tc->b[0]) &&
                  tc->a[1] == \old(tc->a[1]) && tc->b[1] == \old(tc->b[1]);
  behavior learn:
    assumes TcInWindow(tc, speed) && speed_err != 0 && tc->params.gain != 0;
    ensures step_a0: \abs(tc->a[0] - \old(tc->a[0])) <= 2 * 32767 * tc->params.gain;
    ensures step_b0: \abs(tc->b[0] - \old(tc->b[0])) <= 2 * 32767 * tc->params.gain;
    ensures step_a1: \abs(tc->a[1] - \old(tc->a[1])) <= 2 * 32767 * tc->params.gain;
    ensures step_b1: \abs(tc->b[1] - \old(tc->b[1])) <= 2 * 32767 * tc->params.gain;
    ensures held_2x: 2 * TcAbs(speed) > tc->params.speed_max ==>
                     tc->a[1] == \old(tc->a[1]) && tc->b[1] == \old(tc->b[1]);
  complete behaviors;
  disjoint behaviors;
*/
void qfoc_trqcomp_learn(qfoc_trqcomp_t *tc, qfoc_angle_t theta_m, qfoc_q15_t speed_err,
                        qfoc_q15_t speed);

/**
 * @brief Fast step: the feed-forward q-current at the present mechanical angle.
 * @param[in] tc      valid instance (read only)
 * @param[in] theta_m mechanical angle (qfoc_mech_update()), any value
 * @param[in] speed   electrical speed estimate, Q15, any int16_t
 * @return i_ff = round(sum_h a_h cos(h theta_m) + b_h sin(h theta_m)), Q15 of
 *         I_base, saturated to [-32767, 32767]; 0 when |speed| is outside
 *         [speed_min, speed_max].
 *
 * The first harmonic's sine and cosine come from qfoc_sincos(theta_m), the
 * second's from them by the double-angle identities (2 s c, c^2 - s^2, rounded to
 * Q15): one table look-up a period instead of two.
 *
 * Accuracy against the real-valued sum with the stored coefficients:
 * |error| <= 0.5 + ((|a_1| + |b_1|) x 2 + (|a_2| + |b_2|) x 5) / 32768 LSB
 * (coefficients in Q15 LSB; qfoc_sin is within 1 LSB of 32767 sin, the doubled
 * harmonic within 2.5 LSB, and 32767 / 32768 scales by at most 1 LSB more):
 * <= 2.5 LSB for amp_max <= 8192 (measured 1.97).
 *
 * Bad input: none; every int16 speed and every angle is accepted.
 *
 * Scaling and overflow: coefficient (Q31, |.| <= 32767 x 65536) x cos / sin
 * (Q15, |.| <= 32767) = Q46, |.| < 2^46, four terms summed in int64 (< 2^48),
 * rounded to Q15 (/ 2^31, nearest, ties away from zero) and saturated:
 * |i_ff| <= 4 amp_max.
 *
 * Requirements: REQ-TC-005, REQ-TC-008.
 */
/*@
  requires valid_tc: \valid_read(tc);
  requires tc_valid: TcValid(tc);
  assigns \nothing;
  ensures range: QfocQ15Sym(\result);
  behavior off:
    assumes !TcInWindow(tc, speed);
    ensures zero: \result == 0;
  behavior on:
    assumes TcInWindow(tc, speed);
    ensures bound: -4 * tc->params.amp_max <= \result <= 4 * tc->params.amp_max;
    ensures zero_coef: (tc->a[0] == 0 && tc->b[0] == 0 && tc->a[1] == 0 && tc->b[1] == 0)
                       ==> \result == 0;
  complete behaviors;
  disjoint behaviors;
*/
qfoc_q15_t qfoc_trqcomp_output(const qfoc_trqcomp_t *tc, qfoc_angle_t theta_m, qfoc_q15_t speed);

/**
 * @brief Angle of the learned 1x component: where, relative to the counted
 *        mechanical zero, the feed-forward (i.e. the compressor's load) peaks.
 * @param[in] tc valid instance (read only)
 * @return phi_1 = atan2(b_1, a_1) (qfoc_atan2 of the coefficients rounded to Q15),
 *         65536 per mechanical turn: a_1 cos(theta) + b_1 sin(theta) =
 *         A cos(theta - phi_1) is largest at theta_m = phi_1.  0 when both are 0.
 *
 * Use: the mechanical zero of qfoc_mech_init() is arbitrary (a multiple of
 * 1 / pole_pairs turn away from the compressor's own zero).  Comparing phi_1 with
 * the compressor's known peak-load angle gives that offset, e.g. to restore
 * coefficients learned in an earlier run.
 *
 * Scaling and overflow: Q31 -> Q15 rounding (qfoc_q15_from_q31), then qfoc_atan2
 * (within 1 count of the true angle of the rounded vector).
 *
 * Requirements: REQ-TC-009.
 */
/*@
  requires valid_tc: \valid_read(tc);
  requires tc_valid: TcValid(tc);
  assigns \nothing;
  ensures range: 0 <= \result <= 65535;
*/
qfoc_angle_t qfoc_trqcomp_phase1(const qfoc_trqcomp_t *tc);

#ifdef __cplusplus
}
#endif

#endif /* QFOC_TRQCOMP_H */
