/*
 * CBMC harness: qfoc_pi_step() on any valid instance and any error value.
 * Properties (REQ-PI-004, REQ-PI-005, REQ-PI-007, REQ-PI-008):
 *  - no undefined behaviour (overflow, conversion, shift, bounds checks on);
 *  - the instance is still valid afterwards (qfoc_pi_is_valid);
 *  - output within [out_min, out_max];
 *  - integrator = clamp(I(k-1) + e ki 2^ki_shift x 2, limits) in Q31;
 *  - output exact (rounded P + I, limited == false) when P + I is inside the
 *    limits, otherwise equal to the violated limit with limited == true.
 */
#include <stdint.h>
#include <stdbool.h>
#include "qfoc/pi.h"

int16_t nondet_int16(void);
int32_t nondet_int32(void);
uint8_t nondet_uint8(void);
bool nondet_bool(void);

/* e x g x 2^s x 2 (Q31) by repeated doubling, without the library's 2^s table
   and without a 64-bit multiplier (keeps the SAT problem small) */
static int64_t ref_gain_term(int16_t e, int16_t g, uint8_t s)
{
    int64_t r = (int64_t)((int32_t)e * (int32_t)g);
    uint8_t i;
    for (i = 0u; i < s; i++) {
        r = r + r;
    }
    return r + r;
}

/* u is x / 65536 rounded to nearest, ties away from zero (checked by
   multiplication, without a divider) */
static bool is_rounded(int64_t u, int64_t x)
{
    bool ok;
    if (x >= 0) {
        ok = ((u * 65536) - 32768 <= x) && (x < (u * 65536) + 32768);
    } else {
        ok = ((u * 65536) - 32768 < x) && (x <= (u * 65536) + 32768);
    }
    return ok;
}

int main(void)
{
    qfoc_pi_t pi;
    qfoc_q15_t e = nondet_int16();
    qfoc_q15_t u;
    int64_t lo;
    int64_t hi;
    int64_t integ;
    int64_t sum;

    pi.params.kp = nondet_int16();
    pi.params.kp_shift = nondet_uint8();
    pi.params.ki = nondet_int16();
    pi.params.ki_shift = nondet_uint8();
    pi.params.out_min = nondet_int16();
    pi.params.out_max = nondet_int16();
    pi.integ = nondet_int32();
    pi.limited = nondet_bool();
    __CPROVER_assume(qfoc_pi_is_valid(&pi));

    lo = (int64_t)pi.params.out_min * 65536;
    hi = (int64_t)pi.params.out_max * 65536;
    integ = (int64_t)pi.integ + ref_gain_term(e, pi.params.ki, pi.params.ki_shift);
    if (integ > hi) {
        integ = hi;
    }
    if (integ < lo) {
        integ = lo;
    }
    sum = ref_gain_term(e, pi.params.kp, pi.params.kp_shift) + integ;

    u = qfoc_pi_step(&pi, e);

    __CPROVER_assert(qfoc_pi_is_valid(&pi), "still valid");
    __CPROVER_assert((u >= pi.params.out_min) && (u <= pi.params.out_max), "output in limits");
    __CPROVER_assert((int64_t)pi.integ == integ, "integrator update with clamping");
    if ((sum >= lo) && (sum <= hi)) {
        __CPROVER_assert(is_rounded((int64_t)u, sum), "exact inside the limits");
        __CPROVER_assert(!pi.limited, "flag clear inside the limits");
    } else if (sum > hi) {
        __CPROVER_assert(u == pi.params.out_max, "upper limit");
        __CPROVER_assert(pi.limited, "flag set at upper limit");
    } else {
        __CPROVER_assert(u == pi.params.out_min, "lower limit");
        __CPROVER_assert(pi.limited, "flag set at lower limit");
    }
    return 0;
}
