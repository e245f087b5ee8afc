/**
 * @file ramp.h
 * @brief Rate limiter: move a Q15 value toward a target by at most one step.
 *
 * Used by the drive for every ramped quantity (speed reference in closed loop,
 * the I/f start-up speed and current, the ALIGN current): the caller keeps the
 * present value and calls qfoc_ramp_toward() once per tick with the step per
 * tick, e.g. a speed slope of 1000 rpm/s on the reference motor (1 rpm = 3.2768
 * Q15 LSB) at the 1 ms tick is a step of 1000 x 3.2768 / 1000 = 3.3 -> 3 LSB.
 *
 * The function is pure and total: every int16_t value of every argument is
 * accepted (-32768 included).
 *
 * Requirements: REQ-RAMP-001 .. REQ-RAMP-004 (specs/requirements/ramp.md).
 */
#ifndef QFOC_RAMP_H
#define QFOC_RAMP_H

#include "qfoc/types.h"

#ifdef __cplusplus
extern "C" {
#endif

#ifdef __FRAMAC__
/* ACSL logic of this module, read by Frama-C only (DEV-001). */
/* cppcheck-suppress misra-c2012-20.1 ; DEV-001 */
#include "ramp.acsl"
#endif

/**
 * @brief Move `value` toward `target` by at most |step|, never past the target.
 * @param[in] value  present value, Q15, any int16_t (-32768 is first saturated
 *                   to -32767)
 * @param[in] target value to reach, Q15, any int16_t (-32768 is first saturated
 *                   to -32767)
 * @param[in] step   largest change per call, Q15; its magnitude is used (a
 *                   negative step acts as |step|, -32768 as 32767); 0 holds the
 *                   value (the saturated value is returned)
 * @return with v = sat(value), t = sat(target), s = |step| (saturated):
 *         t when |t - v| <= s (the target is reached exactly);
 *         v + s when t - v > s; v - s when t - v < -s.  In the last two cases the
 *         result lies strictly between v and t when s > 0, and its distance to the
 *         target is exactly |t - v| - s (monotone approach, no overshoot).
 *
 * Bad input: none; -32768 (outside the symmetric Q15 range) is saturated, a
 * negative step is read as its magnitude.
 *
 * Scaling and overflow: all three arguments are in the same Q15 scaling (the
 * step is a change of the value per call).  v, t in [-32767, 32767] and
 * s in [0, 32767]; the distance t - v is formed in 32 bits (|t - v| <= 65534).
 * v + s is only formed when v + s < t <= 32767, and v - s only when
 * v - s > t >= -32767, so the result is always in [-32767, 32767] without any
 * saturation.  No rounding: the result is exact.
 *
 * Requirements: REQ-RAMP-001, REQ-RAMP-002, REQ-RAMP-003, REQ-RAMP-004.
 */
/*@
  assigns \nothing;
  ensures range: QfocQ15Sym(\result);
  ensures value: \result == RampMove(QfocSat15(value), QfocSat15(target), RampStep(step));
  ensures no_overshoot: QfocSat15(value) <= QfocSat15(target) ==>
                          QfocSat15(value) <= \result <= QfocSat15(target);
  ensures no_undershoot: QfocSat15(value) >= QfocSat15(target) ==>
                          QfocSat15(target) <= \result <= QfocSat15(value);
  behavior reach:
    assumes -RampStep(step) <= QfocSat15(target) - QfocSat15(value) <= RampStep(step);
    ensures result: \result == QfocSat15(target);
  behavior rise:
    assumes QfocSat15(target) - QfocSat15(value) > RampStep(step);
    ensures result: \result == QfocSat15(value) + RampStep(step);
    ensures distance: QfocSat15(target) - \result == QfocSat15(target) - QfocSat15(value) - RampStep(step);
  behavior fall:
    assumes QfocSat15(target) - QfocSat15(value) < -RampStep(step);
    ensures result: \result == QfocSat15(value) - RampStep(step);
    ensures distance: \result - QfocSat15(target) == QfocSat15(value) - QfocSat15(target) - RampStep(step);
  complete behaviors;
  disjoint behaviors;
*/
qfoc_q15_t qfoc_ramp_toward(qfoc_q15_t value, qfoc_q15_t target, qfoc_q15_t step);

#ifdef __cplusplus
}
#endif

#endif /* QFOC_RAMP_H */
