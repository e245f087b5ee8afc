/*
 * CBMC harness: qfoc_lpf_step() on any valid instance and any input.
 *
 * Properties checked for every int16_t input (-32768 included) and every
 * instance accepted by qfoc_lpf_is_valid() (REQ-FLT-001, REQ-FLT-002,
 * REQ-FLT-003):
 *  - no undefined behaviour: signed/unsigned overflow, conversion, shift, bounds,
 *    pointer and division checks of the command line;
 *  - the instance is still valid afterwards and alpha is unchanged;
 *  - the output is the new state rounded to Q15 (nearest, ties away from zero),
 *    saturated to [-32767, 32767];
 *  - the state moves towards the (saturated) input, never away from it;
 *  - product-free exactness: an input equal to the state leaves the state
 *    unchanged (fixed point of 2-34).
 * The other half of the convex-combination property (no overshoot past the
 * input) and
 * the exact update y + round(alpha (u - y) / 32768) are nonlinear; they are
 * proved by Frama-C WP (contract of qfoc_lpf_step: state, rising/falling,
 * q15_range) and tested (tests/test_filter.c): bit-level reasoning through the
 * 64-bit multiplier does not finish within the time budget.
 *
 * Methods: 1b every int16 input and every valid instance; 1c -32768 inputs, the output
 * saturated to +-32767, an input equal to the state (the fixed point)
 */
#include <stdint.h>
#include <stdbool.h>
#include "qfoc/filter.h"
#include "../harness_util.h"


int main(void)
{
    qfoc_lpf_t f;
    qfoc_q15_t u = nondet_int16();
    qfoc_q15_t out;
    qfoc_q15_t alpha_old;
    int32_t y_old;

    f.alpha = nondet_int16();
    f.state = nondet_int32();
    __CPROVER_assume(qfoc_lpf_is_valid(&f));
    alpha_old = f.alpha;
    y_old = f.state;

    out = qfoc_lpf_step(&f, u);

    __CPROVER_assert(qfoc_lpf_is_valid(&f), "still valid");
    __CPROVER_assert(f.alpha == alpha_old, "coefficient unchanged");
    __CPROVER_assert((out >= -32767) && (out <= 32767), "output in symmetric Q15");
    __CPROVER_assert(is_rounded_sat((int64_t)out, (int64_t)f.state),
                     "output is the rounded state");
    if ((int64_t)y_old <= ((int64_t)((u < -32767) ? -32767 : u) * 65536)) {
        __CPROVER_assert(f.state >= y_old, "rising input: state does not fall");
    } else {
        __CPROVER_assert(f.state <= y_old, "falling input: state does not rise");
    }
    if ((u > -32768) && (y_old == ((int32_t)u * 65536))) {
        __CPROVER_assert(f.state == y_old, "input equal to state: state unchanged");
    }
    return 0;
}
