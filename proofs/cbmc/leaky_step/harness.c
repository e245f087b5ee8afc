/*
 * CBMC harness: qfoc_leaky_step() on any valid instance and any input.
 *
 * Properties checked for every int16_t input (-32768 included) and every
 * instance accepted by qfoc_leaky_is_valid() (REQ-FLT-005, REQ-FLT-006, REQ-FLT-007,
 * REQ-FLT-008):
 *  - no undefined behaviour: signed/unsigned overflow, conversion, shift, bounds,
 *    pointer and division checks of the command line;
 *  - the instance is still valid afterwards (state in the symmetric Q31 range)
 *    and the coefficients are unchanged;
 *  - the output is the new state rounded to Q15 (nearest, ties away from zero),
 *    saturated to [-32767, 32767];
 *  - with leak = 0 (pure integrator) the state moves in the direction of the
 *    input, and stays unchanged for x = 0 or gain = 0.
 * The exact update sat31(y + round(2 x gain / 2^gain_shift)
 * - round(leak y / 32768)) (2-17) is proved by Frama-C WP (contract of
 * qfoc_leaky_step: behaviours exact/upper/lower) and tested against a double
 * reference (tests/test_filter.c): bit-level reasoning through the multipliers
 * does not finish within the time budget.
 *
 * Methods: 1b every int16 input and every valid instance; 1c -32768 inputs, the state
 * at the ends of the symmetric Q31 range, leak = 0, x = 0 and gain = 0
 */
#include <stdint.h>
#include <stdbool.h>
#include "qfoc/filter.h"
#include "../harness_util.h"


int main(void)
{
    qfoc_leaky_int_t f;
    qfoc_leaky_int_t old;
    qfoc_q15_t x = nondet_int16();
    qfoc_q15_t out;

    f.gain = nondet_int16();
    f.gain_shift = nondet_uint8();
    f.leak = nondet_int16();
    f.state = nondet_int32();
    __CPROVER_assume(qfoc_leaky_is_valid(&f));
    old = f;

    out = qfoc_leaky_step(&f, x);

    __CPROVER_assert(qfoc_leaky_is_valid(&f), "still valid (state in symmetric Q31)");
    __CPROVER_assert((f.gain == old.gain) && (f.gain_shift == old.gain_shift)
                     && (f.leak == old.leak), "coefficients unchanged");
    __CPROVER_assert((out >= -32767) && (out <= 32767), "output in symmetric Q15");
    __CPROVER_assert(is_rounded_sat((int64_t)out, (int64_t)f.state),
                     "output is the rounded, saturated state");
    if ((old.leak == 0) && (x > 0)) {
        __CPROVER_assert(f.state >= old.state, "pure integrator, positive input: state does not fall");
    }
    if ((old.leak == 0) && (x < 0)) {
        __CPROVER_assert(f.state <= old.state, "pure integrator, negative input: state does not rise");
    }
    if ((old.leak == 0) && ((x == 0) || (old.gain == 0))) {
        __CPROVER_assert(f.state == old.state, "no input, no leak: state unchanged");
    }
    return 0;
}
