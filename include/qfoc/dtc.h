/**
 * @file dtc.h
 * @brief The inverter's residual voltage error, learnt at ALIGN and taken out of the
 *        flux observer's voltage.
 *
 * The dead-time compensation of the table (svpwm.h) adds dt_comp ticks in the direction
 * of each phase current.  A real inverter's dead time, switching delays and device drops
 * differ from it: the voltage that reaches the motor is the command less a residual
 * error of the same shape,
 *
 *     v_x = v_x,cmd - dV f(i_x),   f(i) = clamp(i / i_db, -1, 1)   (f = sign(i) for i_db = 0)
 *
 * with f the same fade the compensation uses inside its current dead band i_db.  The
 * current loops reject dV (it is a disturbance to them), but the voltage-model flux
 * observer integrates it: at the low speed of the start-up hand-over, dV / w is an angle
 * error of tens of degrees on a low-flux motor (specs/equations.md section 10).
 *
 * ALIGN holds the rotor with the d current i_hi on the alpha axis (i_u = i_hi, i_v = i_w =
 * -i_hi / 2) and then, for its last quarter, with i_lo = i_hi / 2; at w = 0, with the
 * current settled, the d current PI's output is the whole voltage:
 * u = R' i + dV s_d(i), s_d(i) = (2/3)(f(i) - f(-i / 2)) the projection of the error's
 * shape on the d axis and R' the motor's real resistance.  qfoc_dtc_learn() solves the two
 * alignments for dV, free of the resistance (of the table's and of the motor's, which
 * differ by up to 30 % with the temperature): an error learnt against the table's R would
 * carry (R' - R) i_hi in the shape of the dead time, which inside the dead band acts as a
 * resistance error i_hi / i_db times larger at light load.  qfoc_dtc_error() forms the
 * error vector dV Clarke(f(i_u), f(i_v), f(i_w)) that the drive subtracts from the
 * observer's voltage in every later period of the run.
 *
 * Scaling (specs/scaling.md): voltages Q15 of V_base, currents Q15 of I_base.
 *
 * Every function is total on every value of its argument types and has no state.
 *
 * Requirements: REQ-DTC-001 .. REQ-DTC-004 (specs/requirements/dtc.md).
 */
#ifndef QFOC_DTC_H
#define QFOC_DTC_H

#include "qfoc/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/** The smallest |s_d(i_hi) - 2 s_d(i_lo)| (Q15) for which qfoc_dtc_learn() solves for dV:
    1/2.  Below it the alignment currents lie inside the dead band, where the error's shape
    is linear in the current like the resistance and cannot be told from it; the result is
    then 0 (no correction). */
#define QFOC_DTC_DEN_MIN ((int32_t)16384)

/**
 * @brief The fade of the compensation for one phase current: f(i) = clamp(i / i_db, -1, 1)
 *        in Q15.
 * @param[in] i    phase current, Q15 (any value)
 * @param[in] i_db dead band, Q15 (any value; a value <= 0 gives the sign of i)
 * @return 32767 sign(i) when |i| >= i_db (or i_db <= 0, and 0 for i = 0), else
 *         i x 32767 / i_db truncated towards zero: in [-32767, 32767], with the sign of i.
 * Scaling and overflow: |i| < i_db <= 32767 inside the band, |i| x 32767 < 2^30.
 * Requirements: REQ-DTC-001.
 */
/*@
  assigns \nothing;
  ensures range: -32767 <= \result <= 32767;
  ensures sign: (i > 0 ==> \result >= 0) && (i < 0 ==> \result <= 0) && (i == 0 ==> \result == 0);
  ensures full: (i_db <= 0 || i >= i_db) && i > 0 ==> \result == 32767;
  ensures full_neg: (i_db <= 0 || i <= -i_db) && i < 0 ==> \result == -32767;
  ensures band: 0 < i_db && -i_db < i < i_db ==> \result == (i * 32767) / i_db;
*/
qfoc_q15_t qfoc_dtc_fade(qfoc_q15_t i, qfoc_q15_t i_db);

/** The two settled alignments of ALIGN and what the table says of the motor and inverter. */
typedef struct {
    qfoc_q15_t u_hi;   /**< the d voltage the current loop holds at the d current i_hi, Q15 */
    qfoc_q15_t u_hi0;  /**< the same an eighth of ALIGN earlier, Q15 */
    qfoc_q15_t u_lo;   /**< the d voltage at i_lo = trunc(i_hi / 2), Q15 */
    qfoc_q15_t u_lo0;  /**< the same an eighth of ALIGN earlier, Q15 */
    qfoc_q15_t i_hi;   /**< the larger alignment current on the alpha axis, Q15 */
    qfoc_q15_t i_db;   /**< the compensation's dead band, Q15 (svpwm.h) */
    qfoc_q15_t v_max;  /**< the largest |dV| accepted, Q15: the table's dead-time voltage
                            error bound (a value <= 0 reads as 0: no correction) */
    qfoc_q15_t r;      /**< the table's stator resistance R / Z_base, Q15 */
    qfoc_q15_t r_err;  /**< the relative resistance error the table allows, Q15 (a value < 0
                            reads as 0) */
} qfoc_dtc_align_t;

/** The quantisation allowance of the resistance check of qfoc_dtc_learn(), Q15 counts of
    voltage: u_lo and dV s_lo, from voltages held to 1 LSB. */
#define QFOC_DTC_R_TOL ((int32_t)4)
/** The quantisation part of the settling check of qfoc_dtc_learn(), Q15 counts: a hold is
    settled when its d voltage moved by at most m / 4 + QFOC_DTC_SETTLE_TOL over the last
    eighth of ALIGN (m the accepted bound of dV). */
#define QFOC_DTC_SETTLE_TOL ((int32_t)4)

/**
 * @brief The residual voltage error dV from the d voltages of two settled alignments.
 * @param[in] a the alignments and the table's values (any values)
 * @return with s(i) = trunc(2 (f(i) - f(-trunc(i / 2))) / 3), den = s(i_hi) - 2 s(i_lo) and
 *         n = u_hi - 2 u_lo clamped to [-65535, 65535]:
 *         - 0 when |u_hi - u_hi0| or |u_lo - u_lo0| exceeds trunc(m / 4) +
 *           QFOC_DTC_SETTLE_TOL, m = max(v_max, 0) (a hold that has not settled: a rotor
 *           still moving, a current still changing); a pair within it moves the learnt
 *           error by at most 3 (m / 4 + 4) / |den|, under 0.57 m + 9 counts outside the
 *           band (a rotor that a breakaway torque releases late in the hold);
 *         - 0 when |den| < QFOC_DTC_DEN_MIN (the dead band hides the error's shape);
 *         - else with v = trunc(n x 32768 / den) clamped to [-49151, 49151], the resistance
 *           drop it implies, u_lo - trunc(v s(i_lo) / 32768), must lie within
 *           trunc(r' |R i_lo| / 32768) + QFOC_DTC_R_TOL of the table's
 *           R i_lo = trunc(r i_lo / 32768), r' = max(r_err, 0): 0 when it does not (a rotor
 *           still moving, a table whose R is wrong: a measurement the error model does not
 *           explain), v clamped to [-m, m] when it does.
 *         For i_hi = 2 i_lo the resistance drops out of v: u_hi - 2 u_lo = dV den (E10-4);
 *         an odd i_hi leaves R' / 32768 of a count.
 * Scaling and overflow: |n| <= 65535, 65535 x 32768 < 2^31; |den| <= 131070;
 * |v s| <= 49151 x 43690 < 2^31; |r i| <= 2^30.  The clamps of n and v change nothing for
 * v_max < 16384 (a larger |n| gives |v| > 16384).
 * Requirements: REQ-DTC-002.
 */
/*@
  requires valid: \valid_read(a);
  assigns \nothing;
  ensures range: -((a->v_max > 0) ? a->v_max : 0) <= \result <= ((a->v_max > 0) ? a->v_max : 0);
  ensures off: a->v_max <= 0 ==> \result == 0;
*/
qfoc_q15_t qfoc_dtc_learn(const qfoc_dtc_align_t *a);

/**
 * @brief The learnt error as the observer uses it at the speed w: whole up to w_full,
 *        fading linearly to 0 at 2 w_full (E10-5).
 * The observer's angle error from an uncorrected residual falls as 1 / w (E10-3): it
 * matters at the start-up's hand-over and below; at speed the residual is small against
 * the back-EMF, while an error learnt off the true one (a rotor that still moved when ALIGN
 * ended, an inverter whose low-current behaviour differs from the fade) would act at light
 * load, inside the dead band, as a resistance error i_hi / i_db times its own size.
 * @param[in] dv     the learnt error, Q15 (any value)
 * @param[in] w      the estimated speed, Q15 (any value; |w| is used, |-32768| = 32768)
 * @param[in] w_full the speed up to which dv is whole, Q15 (a value <= 0 reads as 0: dv is
 *                   used at standstill only)
 * @return dv for |w| <= w_full; else 0 for |w| >= 2 w_full; else
 *         trunc(dv (2 w_full - |w|) / w_full), between 0 and dv.
 * Scaling and overflow: |dv| <= 32768 and 0 < 2 w_full - |w| < w_full <= 32767: the product
 * < 2^30.
 * Requirements: REQ-DTC-004.
 */
/*@
  assigns \nothing;
  ensures between: (dv >= 0 ==> 0 <= \result <= dv) && (dv < 0 ==> dv <= \result <= 0);
  ensures whole: ((w >= 0) ? w : -w) <= w_full ==> \result == dv;
  ensures none: ((w >= 0) ? w : -w) > ((w_full > 0) ? w_full : 0) &&
                ((w >= 0) ? w : -w) >= 2 * ((w_full > 0) ? w_full : 0) ==> \result == 0;
*/
qfoc_q15_t qfoc_dtc_speed_fade(qfoc_q15_t dv, qfoc_q15_t w, qfoc_q15_t w_full);

/**
 * @brief The error vector dV Clarke(f(i_u), f(i_v), f(i_w)) of the phase currents.
 * @param[in]  dv   the residual error, Q15 (any value)
 * @param[in]  i    the phase currents, Q15 (any values)
 * @param[in]  i_db the dead band, Q15 (any value)
 * @param[out] e    alpha = dv (2 f_u - f_v - f_w) / 3, beta = dv (f_v - f_w) / sqrt 3:
 *                  each factor in Q15 (truncated), the products / 32768 (truncated) and
 *                  saturated to [-32767, 32767]
 * Scaling and overflow: |2 f_u - f_v - f_w| / 3 <= 43689, |f_v - f_w| x 18919 / 32768
 * <= 37836; times |dv| <= 32768: < 2^31.
 * Requirements: REQ-DTC-003.
 */
/*@
  requires valid: \valid_read(i) && \valid(e);
  requires sep: \separated(i, e);
  assigns *e;
  ensures range: QfocQ15Sym(e->alpha) && QfocQ15Sym(e->beta);
  ensures zero: dv == 0 ==> e->alpha == 0 && e->beta == 0;
*/
void qfoc_dtc_error(qfoc_q15_t dv, const qfoc_abc_t *i, qfoc_q15_t i_db, qfoc_ab_t *e);

#ifdef __cplusplus
}
#endif

#endif /* QFOC_DTC_H */
