/*
 * CBMC harness: qfoc_leaky_step() on any valid instance and any input.
 * Properties (REQ-FLT-006, REQ-FLT-007, REQ-FLT-008):
 *  - no undefined behaviour for any input and any valid state (overflow,
 *    conversion, shift, bounds checks on);
 *  - the instance is still valid afterwards (state in the symmetric Q31 range);
 *  - the state equals sat31(y + round(2 x gain / 2^gain_shift)
 *    - round(leak y / 32768)) (2-17), exact when inside the range;
 *  - the output is the rounded, saturated state.
 */
#include <stdint.h>
#include <stdbool.h>
#include "qfoc/filter.h"

int16_t nondet_int16(void);
int32_t nondet_int32(void);
int64_t nondet_int64(void);
uint8_t nondet_uint8(void);

/* x x 2^s by repeated doubling (independent of the library's 2^s table) */
static int64_t ref_mul_pow2(int64_t x, uint8_t s)
{
    int64_t r = x;
    uint8_t i;
    for (i = 0u; i < s; i++) {
        r = r + r;
    }
    return r;
}

/* q is x / 2^s rounded to nearest, ties away from zero (no divider) */
static bool is_rounded_pow2(int64_t q, int64_t x, uint8_t s)
{
    bool ok;
    int64_t qd = ref_mul_pow2(q, s);
    int64_t h = ref_mul_pow2(1, s) / 2;
    if (s == 0u) {
        ok = (q == x);
    } else if (x >= 0) {
        ok = ((qd - h) <= x) && (x < (qd + h));
    } else {
        ok = ((qd - h) < x) && (x <= (qd + h));
    }
    return ok;
}

/* q is x / d rounded to nearest, ties away from zero (d > 0 even or 1; checked
   by multiplication, without a divider) */
static bool is_rounded(int64_t q, int64_t x, int64_t d)
{
    bool ok;
    int64_t h = d / 2;
    if (d == 1) {
        ok = (q == x);
    } else if (x >= 0) {
        ok = (((q * d) - h) <= x) && (x < ((q * d) + h));
    } else {
        ok = (((q * d) - h) < x) && (x <= ((q * d) + h));
    }
    return ok;
}

int main(void)
{
    qfoc_leaky_int_t f;
    qfoc_q15_t x = nondet_int16();
    qfoc_q15_t out;
    int64_t y_old;
    int64_t xg2;
    int64_t step = nondet_int64();
    int64_t loss = nondet_int64();
    int64_t out_ref = nondet_int64();
    int64_t sum;
    int64_t expect;

    f.gain = nondet_int16();
    f.gain_shift = nondet_uint8();
    f.leak = nondet_int16();
    f.state = nondet_int32();
    __CPROVER_assume(qfoc_leaky_is_valid(&f));

    y_old = (int64_t)f.state;
    /* integration step: 2 x gain / 2^gain_shift, rounded (defined by the rounding
       relation, which always has exactly one solution) */
    xg2 = 2 * (int64_t)((int32_t)x * (int32_t)f.gain);
    __CPROVER_assume((step >= -(1LL << 32)) && (step <= (1LL << 32)));
    __CPROVER_assume(is_rounded_pow2(step, xg2, f.gain_shift));
    /* leak term: leak y / 32768, rounded */
    __CPROVER_assume((loss >= -(1LL << 32)) && (loss <= (1LL << 32)));
    __CPROVER_assume(is_rounded(loss, (int64_t)f.leak * y_old, 32768));
    sum = (y_old + step) - loss;
    expect = sum;
    if (expect > 2147483647) {
        expect = 2147483647;
    }
    if (expect < -2147483647) {
        expect = -2147483647;
    }

    out = qfoc_leaky_step(&f, x);

    __CPROVER_assume((out_ref >= -40000) && (out_ref <= 40000));
    __CPROVER_assume(is_rounded(out_ref, (int64_t)f.state, 65536));
    if (out_ref > 32767) {
        out_ref = 32767;
    }
    if (out_ref < -32767) {
        out_ref = -32767;
    }
    __CPROVER_assert(qfoc_leaky_is_valid(&f), "still valid (state in symmetric Q31)");
    __CPROVER_assert((int64_t)f.state == expect, "state update 2-17, saturated");
    __CPROVER_assert((int64_t)out == out_ref, "output is the rounded, saturated state");
    __CPROVER_assert((out >= -32767) && (out <= 32767), "output in symmetric Q15");
    return 0;
}
