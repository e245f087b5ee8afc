/**
 * @file qfoc_ramp.c
 * @brief Rate limiter (see include/qfoc/ramp.h).
 *
 * Requirements: REQ-RAMP-001 .. REQ-RAMP-004 (specs/requirements/ramp.md).
 */
#include "qfoc/ramp.h"
#include "qfoc/q15.h"

qfoc_q15_t qfoc_ramp_toward(qfoc_q15_t value, qfoc_q15_t target, qfoc_q15_t step)
{
    /* v, t in [-32767, 32767]; s = |step| in [0, 32767] (|-32768| saturated) */
    const int32_t v = (int32_t)qfoc_q15_sat((int32_t)value);
    const int32_t t = (int32_t)qfoc_q15_sat((int32_t)target);
    const int32_t s = (int32_t)qfoc_q15_abs(step);
    /* distance to go, |d| <= 65534 */
    const int32_t d = t - v;
    int32_t r;

    if (d > s) {
        /* v + s < t <= 32767 */
        r = v + s;
    } else if (d < -s) {
        /* v - s > t >= -32767 */
        r = v - s;
    } else {
        /* within one step: land exactly on the target */
        r = t;
    }
    /* r lies between v and t, both in [-32767, 32767] */
    return (qfoc_q15_t)r;
}
