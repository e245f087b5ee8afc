/**
 * @file catch.h
 * @brief Flying start: the verdict on a rotor that may still be turning when the drive
 *        is asked to run (a short stop, or pressure equalising through the compressor,
 *        in either direction).
 *
 * The drive enters RUN in the sub-state CATCH (sm.h).  There it runs the current loops
 * with zero references in the frame of the flux observer (zero-current control): the
 * loops' voltage command then equals the rotor's back-EMF, e = w psi_f, and no torque
 * acts on the rotor.  The voltage-model observer works in the stationary frame, so it
 * converges on a coasting rotor from its reset state whatever the control frame, and its
 * PLL measures the speed.  Until the PLL has locked (a few milliseconds) the loops run in
 * a frame that does not yet turn with the rotor: the back-EMF drives a transient current
 * that grows with the speed (on the reference motor about 35 % of i_max from 3000 rpm,
 * 80 % from the rated 6000 rpm, 130 % from speed_max, below the over-current trip), then
 * the phase currents fall to the measurement noise.  Zero-current control rather than
 * short zero-vector pulses: a pulse's short-circuit current grows with the speed too, up
 * to psi_f / L_d, and needs a pulse width tuned to each motor, and the pulses leave the
 * observer without a voltage to integrate; zero-current control needs no tuning of its
 * own, and the observer the drive already has measures the speed (specs/equations.md
 * section 11).
 *
 * qfoc_catch_verdict() classifies one tick's measurement:
 *  - LOCK: the observer's speed lies in [w_min, w_max], its flux magnitude within the
 *    table's band psi_f +- psi_tol, and the voltage command agrees with the back-EMF the
 *    speed implies, | |u| - w psi_f | <= v_err + w psi_f / 4 (two independent measures of
 *    the speed, the PLL's frequency and the voltage's magnitude);
 *  - STILL: otherwise, when |u| <= v_still = max(2 v_err, w_min psi_f / 4): the voltage is
 *    below twice the error the inverter can make (v_err, the table's dead-time
 *    voltage-error bound) or below the back-EMF of a quarter of the handover speed, so a
 *    standing rotor is always classed STILL (also on a table with v_err = 0, whatever the
 *    loops' voltage noise below w_min psi_f / 4), and a rotor classed STILL turns slower
 *    than max(3 v_err / psi_f, w_min / 4 + v_err / psi_f): ALIGN's current stops it;
 *  - WAIT: a rotor that turns but cannot be caught: backwards, slower than w_min (where
 *    the observer is not trusted), faster than w_max, or with the two speeds disagreeing.
 *    The drive keeps zero current (no torque: the compressor's load slows the rotor down)
 *    until the verdict is STILL or LOCK.
 * qfoc_catch_step() is the tick's whole CATCH logic: it low-passes |u| over 8 ticks
 * (each step an eighth of the difference rounded away from zero, so that the filter
 * reaches a constant input exactly), starting from full scale at CATCH entry
 * (qfoc_catch_reset()), so that STILL cannot come before the filter has seen the loops'
 * voltage for about ln(32767 / v_still) / ln(8 / 7) ticks (30 on the reference table),
 * whatever the dwell; it then debounces LOCK and STILL over
 * the dwell (the drive's ho_dwell_ms, drive_cfg.h) before the drive acts on them.
 *
 * Scaling (specs/scaling.md): speeds Q15 of w_base, fluxes Q15 of psi_base =
 * 2^s V_base / w_base (s = psi_shift, the table's flux base drive.psi_shift), voltages Q15
 * of V_base: w psi in Q15 of V_base is (w psi 2^s) / 32768, formed as
 * (w psi) / (32768 / 2^s) (|w psi| <= 2^30, so the quotient is exact in 32 bits).
 *
 * Both functions are total on every value of their argument types.
 *
 * Requirements: REQ-CATCH-001 .. REQ-CATCH-003 (specs/requirements/catch.md).
 */
#ifndef QFOC_CATCH_H
#define QFOC_CATCH_H

#include "qfoc/types.h"
#include "qfoc/fault.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Verdicts of qfoc_catch_verdict(). */
#define QFOC_CATCH_WAIT  ((uint8_t)0u)  /**< turning, not catchable: keep zero current */
#define QFOC_CATCH_STILL ((uint8_t)1u)  /**< standing: the normal start (ALIGN) */
#define QFOC_CATCH_LOCK  ((uint8_t)2u)  /**< caught: closed loop at the measured speed */

/** One tick's measurement in CATCH. */
typedef struct {
    qfoc_q15_t speed;    /**< the observer's filtered electrical speed, Q15 of w_base */
    qfoc_q15_t psi_mag;  /**< the observer's flux magnitude, Q15 of psi_base */
    qfoc_q15_t u_mag;    /**< the magnitude of the voltage command (filtered), Q15 of V_base */
} qfoc_catch_meas_t;

/** What the table says (each read as its magnitude). */
typedef struct {
    qfoc_q15_t psi_f;    /**< the magnet flux, Q15 of psi_base */
    qfoc_q15_t psi_tol;  /**< the flux band (drive.flux_tol), Q15 of psi_base */
    qfoc_q15_t v_err;    /**< the inverter's voltage-error bound (drive.flux_v_err), Q15 of V_base */
    qfoc_q15_t w_min;    /**< the lowest speed caught (drive.of_speed), Q15 of w_base */
    qfoc_q15_t w_max;    /**< the highest speed caught (speed_max), Q15 of w_base */
    uint8_t psi_shift;   /**< the flux base (drive.psi_shift): w psi is a voltage of
                              2^psi_shift V_base; a value above 4 reads as 4 */
} qfoc_catch_cfg_t;

/*@
  logic integer CatchAbs(integer x) = (x < 0) ? -x : x;
  // 32768 / 2^s: the divisor of w psi in the flux base 2^s V_base / w_base (s <= 4)
  logic integer CatchDiv(integer s) =
    (s == 0) ? 32768 : (s == 1) ? 16384 : (s == 2) ? 8192 : (s == 3) ? 4096 : 2048;
  // the back-EMF the speed implies, Q15 of V_base
  logic integer CatchEmf(integer w, integer psi, integer s) =
    (w * CatchAbs(psi)) / CatchDiv(s);
  predicate CatchLock(qfoc_catch_meas_t *m, qfoc_catch_cfg_t *c) =
    CatchAbs(c->w_min) <= m->speed <= CatchAbs(c->w_max) &&
    CatchAbs(m->psi_mag - CatchAbs(c->psi_f)) <= CatchAbs(c->psi_tol) &&
    CatchAbs(CatchAbs(m->u_mag) - CatchEmf(m->speed, c->psi_f, c->psi_shift)) <=
      CatchAbs(c->v_err) + CatchEmf(m->speed, c->psi_f, c->psi_shift) / 4;
  // the STILL threshold: twice the inverter's error, at least a quarter of the back-EMF
  // at the handover speed
  logic integer CatchVStill(qfoc_catch_cfg_t *c) =
    (2 * CatchAbs(c->v_err) >= CatchEmf(CatchAbs(c->w_min), c->psi_f, c->psi_shift) / 4) ?
      2 * CatchAbs(c->v_err) : CatchEmf(CatchAbs(c->w_min), c->psi_f, c->psi_shift) / 4;
  predicate CatchStill(qfoc_catch_meas_t *m, qfoc_catch_cfg_t *c) =
    CatchAbs(m->u_mag) <= CatchVStill(c);
  // one filter step: an eighth of the difference, rounded away from zero
  logic integer CatchStep(integer d) = (d >= 0) ? (d + 7) / 8 : -((7 - d) / 8);
  // at most 32767 (the step from 32767 towards |u| = 32768)
  logic integer CatchSat(integer x) = (x > 32767) ? 32767 : x;
*/

/**
 * @brief The verdict on one tick's measurement in CATCH (rules in the file comment).
 * @param[in] m the measurement (any values)
 * @param[in] c the table's values (any values; each read as its magnitude)
 * @return QFOC_CATCH_LOCK, QFOC_CATCH_STILL or QFOC_CATCH_WAIT
 * Scaling and overflow: every quantity is formed in 32 bits; |w psi| <= 2^30 and the
 * back-EMF |w psi| / (32768 / 2^s) <= 2^19.
 * Requirements: REQ-CATCH-001, REQ-CATCH-002.
 */
/*@
  requires valid: \valid_read(m) && \valid_read(c);
  assigns \nothing;
  ensures lock: \result == QFOC_CATCH_LOCK <==> CatchLock(m, c);
  ensures still: \result == QFOC_CATCH_STILL <==> !CatchLock(m, c) && CatchStill(m, c);
  ensures wait: \result == QFOC_CATCH_WAIT <==> !CatchLock(m, c) && !CatchStill(m, c);
*/
uint8_t qfoc_catch_verdict(const qfoc_catch_meas_t *m, const qfoc_catch_cfg_t *c);

/** The tick's CATCH state (qfoc_catch_step()). */
typedef struct {
    qfoc_q15_t u_f;            /**< |u| low-passed over 8 ticks, Q15 of V_base */
    qfoc_debounce_t db_lock;   /**< ticks in a row with the verdict LOCK */
    qfoc_debounce_t db_still;  /**< ticks in a row with the verdict STILL */
} qfoc_catch_t;

/**
 * @brief The state at CATCH entry: the filter at full scale, both counts 0.
 * @param[out] k state
 * Requirements: REQ-CATCH-003.
 */
/*@
  requires valid: \valid(k);
  assigns *k;
  ensures u_f: k->u_f == 32767;
  ensures counts: k->db_lock.count == 0 && k->db_still.count == 0;
*/
void qfoc_catch_reset(qfoc_catch_t *k);

/**
 * @brief One tick in CATCH: the filter, the verdict on the filtered magnitude, and its
 *        debounce.
 * @param[in,out] k     state (any values)
 * @param[in]     u     the magnitude of the last voltage command, Q15 (read as |u|)
 * @param[in]     speed the observer's filtered speed, Q15
 * @param[in]     psi   the observer's flux magnitude, Q15
 * @param[in]     c     the table's values
 * @param[in]     dwell ticks a verdict must hold (0 reads as 1)
 * @return QFOC_CATCH_LOCK once the verdict LOCK has held for dwell ticks in a row, else
 *         QFOC_CATCH_STILL once STILL has, else QFOC_CATCH_WAIT.
 * Scaling and overflow: u_f + CatchStep(|u| - u_f) lies between u_f and |u| (at most
 * 32768, for u = -32768 from 32767: saturated to 32767).
 * Requirements: REQ-CATCH-003.
 */
/*@
  requires valid: \valid(k) && \valid_read(c);
  requires sep: \separated(k, c);
  assigns *k;
  ensures filter: k->u_f == CatchSat(\old(k->u_f) + CatchStep(CatchAbs(u) - \old(k->u_f)));
  ensures result: \result == QFOC_CATCH_LOCK || \result == QFOC_CATCH_STILL ||
                  \result == QFOC_CATCH_WAIT;
  ensures lock: \result == QFOC_CATCH_LOCK ==> k->db_lock.count >= 1;
  ensures still: \result == QFOC_CATCH_STILL ==> k->db_still.count >= 1;
*/
uint8_t qfoc_catch_step(qfoc_catch_t *k, qfoc_q15_t u, qfoc_q15_t speed, qfoc_q15_t psi,
                        const qfoc_catch_cfg_t *c, uint16_t dwell);

#ifdef __cplusplus
}
#endif

#endif /* QFOC_CATCH_H */
