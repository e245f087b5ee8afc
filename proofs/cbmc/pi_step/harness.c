/*
 * CBMC harness: qfoc_pi_step() on any valid instance and any error value.
 *
 * Properties checked for every int16_t error (-32768 included) and every instance
 * accepted by qfoc_pi_is_valid() (REQ-PI-002, REQ-PI-004, REQ-PI-005, REQ-PI-007,
 * REQ-PI-008):
 *  - no undefined behaviour: signed/unsigned overflow, conversion, shift, bounds,
 *    pointer and division checks of the command line;
 *  - the instance is still valid afterwards (integrator inside the limits);
 *  - the output lies in [out_min, out_max];
 *  - a set limit flag means the output sits on a limit;
 *  - product-free exactness: for e = 0 the integrator is unchanged and the output
 *    is the rounded integrator, unlimited; for kp = 0 the output is the rounded new
 *    integrator, unlimited; for ki = 0 the integrator is unchanged; the
 *    integrator moves in the direction of the error (ki >= 0).
 * The exactness of the product terms (P = e kp 2^kp_shift, increment
 * e ki 2^ki_shift) is proved by Frama-C WP (contract of qfoc_pi_step, behaviours
 * exact/upper/lower) and tested against a double reference (tests/test_pi.c):
 * a bit-level miter of two multipliers does not finish within the time budget.
 *
 * Methods: 1b every int16 error and every valid instance; 1c -32768, the output on its
 * limits, e = 0, kp = 0, ki = 0 (product-free special cases)
 */
#include <stdint.h>
#include <stdbool.h>
#include "qfoc/pi.h"

int16_t nondet_int16(void);
int32_t nondet_int32(void);
uint8_t nondet_uint8(void);
bool nondet_bool(void);

/* u is x / 65536 rounded to nearest, ties away from zero (checked by
   multiplication with a constant, without a divider) */
static bool is_rounded(int64_t u, int64_t x)
{
    bool ok;
    if (x >= 0) {
        ok = (((u * 65536) - 32768) <= x) && (x < ((u * 65536) + 32768));
    } else {
        ok = (((u * 65536) - 32768) < x) && (x <= ((u * 65536) + 32768));
    }
    return ok;
}

int main(void)
{
    qfoc_pi_t pi;
    qfoc_q15_t e = nondet_int16();
    qfoc_q15_t u;
    int32_t integ_old;

    pi.params.kp = nondet_int16();
    pi.params.kp_shift = nondet_uint8();
    pi.params.ki = nondet_int16();
    pi.params.ki_shift = nondet_uint8();
    pi.params.out_min = nondet_int16();
    pi.params.out_max = nondet_int16();
    pi.integ = nondet_int32();
    pi.limited = nondet_bool();
    __CPROVER_assume(qfoc_pi_is_valid(&pi));
    integ_old = pi.integ;

    u = qfoc_pi_step(&pi, e);

    __CPROVER_assert(qfoc_pi_is_valid(&pi), "still valid");
    __CPROVER_assert((u >= pi.params.out_min) && (u <= pi.params.out_max), "output in limits");
    if (pi.limited) {
        __CPROVER_assert((u == pi.params.out_min) || (u == pi.params.out_max),
                         "limited: output on a limit");
    }
    if (e == 0) {
        __CPROVER_assert(pi.integ == integ_old, "zero error: integrator unchanged");
        __CPROVER_assert(is_rounded((int64_t)u, (int64_t)integ_old) && !pi.limited,
                         "zero error: output is the rounded integrator");
    }
    if (pi.params.kp == 0) {
        __CPROVER_assert(is_rounded((int64_t)u, (int64_t)pi.integ) && !pi.limited,
                         "kp = 0: output is the rounded new integrator");
    }
    if (e > 0) {
        __CPROVER_assert(pi.integ >= integ_old, "positive error: integrator does not fall");
    }
    if (e < 0) {
        __CPROVER_assert(pi.integ <= integ_old, "negative error: integrator does not rise");
    }
    if (pi.params.ki == 0) {
        __CPROVER_assert(pi.integ == integ_old, "ki = 0: integrator unchanged");
    }
    return 0;
}
