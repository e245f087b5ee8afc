/*
 * CBMC harness: qfoc_ramp_toward() for every value, target and step.
 *
 * Properties checked for all 2^48 argument triples (-32768 included)
 * (REQ-RAMP-001, REQ-RAMP-002, REQ-RAMP-003, REQ-RAMP-004):
 *  - no undefined behaviour: signed/unsigned overflow, conversion, shift, bounds,
 *    pointer and division checks of the command line;
 *  - the result is in the symmetric Q15 range;
 *  - exactness: |t - v| <= |step| gives exactly t (REQ-RAMP-002);
 *  - otherwise the result is strictly between v and t for a non-zero step, on the
 *    target's side, and the distance to t is reduced by exactly |step|
 *    (REQ-RAMP-003);
 *  - step 0 holds the (saturated) value; the sign of the step does not matter
 *    (REQ-RAMP-001); the result never passes the target (REQ-RAMP-004).
 * v, t and |step| are recomputed here from their definitions (sat15, |.|).
 *
 * Methods: 1b all 2^48 (value, target, step) triples; 1c -32768, step 0, |t - v| equal
 * to |step|, the sign of the step
 */
#include <stdint.h>
#include <stdbool.h>
#include "qfoc/ramp.h"
#include "../harness_util.h"

int main(void)
{
    const int16_t value = nondet_int16();
    const int16_t target = nondet_int16();
    const int16_t step = nondet_int16();
    const int32_t v = sat15((int32_t)value);
    const int32_t t = sat15((int32_t)target);
    const int32_t s = (step == (int16_t)-32768) ? 32767 : ((step < 0) ? -(int32_t)step : (int32_t)step);
    const int32_t r = (int32_t)qfoc_ramp_toward(value, target, step);
    const int32_t dist_old = (t >= v) ? (t - v) : (v - t);
    const int32_t dist_new = (t >= r) ? (t - r) : (r - t);

    __CPROVER_assert((r >= -32767) && (r <= 32767), "result in the symmetric Q15 range");
    if (dist_old <= s) {
        __CPROVER_assert(r == t, "within one step: exactly the target");
    } else {
        __CPROVER_assert(dist_new == (dist_old - s), "distance reduced by exactly |step|");
        if (s > 0) {
            __CPROVER_assert(((v < r) && (r < t)) || ((t < r) && (r < v)),
                             "strictly between value and target");
        }
    }
    __CPROVER_assert(((v <= t) && (v <= r) && (r <= t)) || ((v >= t) && (t <= r) && (r <= v)),
                     "no overshoot");
    if (step == 0) {
        __CPROVER_assert((r == v) || (r == t), "step 0 holds the value (or it is the target)");
        __CPROVER_assert((v == t) || (r == v), "step 0 with v != t holds the value");
    }
    if (step != (int16_t)-32768) {
        __CPROVER_assert(r == (int32_t)qfoc_ramp_toward(value, target, (int16_t)(-step)),
                         "sign of the step does not matter");
    }
    return 0;
}
