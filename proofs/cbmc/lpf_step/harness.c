/*
 * CBMC harness: qfoc_lpf_step() on any valid instance and any input.
 * Properties (REQ-FLT-002, REQ-FLT-003, REQ-FLT-004):
 *  - no undefined behaviour (overflow, conversion, shift, bounds checks on);
 *  - the instance is still valid afterwards (qfoc_lpf_is_valid);
 *  - the new state equals y + round(alpha (u - y) / 32768) and lies between the
 *    old state and the (saturated) input, in Q31;
 *  (rounding is checked through its defining inequalities, without a divider,
 *   which keeps the SAT problem small)
 *  - the output is the rounded state and lies between the input and the old
 *    output, in Q15.
 */
#include <stdint.h>
#include <stdbool.h>
#include "qfoc/filter.h"

int16_t nondet_int16(void);
int32_t nondet_int32(void);
int64_t nondet_int64(void);

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
    qfoc_lpf_t f;
    qfoc_q15_t u = nondet_int16();
    qfoc_q15_t out;
    int64_t y_old;
    int64_t u15;
    int64_t u31;
    int64_t prod;
    int64_t out_old = nondet_int64();

    f.alpha = nondet_int16();
    f.state = nondet_int32();
    __CPROVER_assume(qfoc_lpf_is_valid(&f));

    y_old = (int64_t)f.state;
    u15 = (u < -32767) ? (int64_t)-32767 : (int64_t)u;
    u31 = u15 * 65536;
    prod = (int64_t)f.alpha * (u31 - y_old);
    /* previous output: the old state rounded to Q15 (defined by the rounding
       relation; it always exists and is unique) */
    __CPROVER_assume((out_old >= -40000) && (out_old <= 40000));
    __CPROVER_assume(is_rounded(out_old, y_old, 65536));

    out = qfoc_lpf_step(&f, u);

    __CPROVER_assert(qfoc_lpf_is_valid(&f), "still valid");
    __CPROVER_assert(is_rounded((int64_t)f.state - y_old, prod, 32768),
                     "state update 2-34: y + round(alpha (u - y) / 32768)");
    __CPROVER_assert(is_rounded((int64_t)out, (int64_t)f.state, 65536),
                     "output is the rounded state");
    if (u31 >= y_old) {
        __CPROVER_assert((y_old <= (int64_t)f.state) && ((int64_t)f.state <= u31),
                         "state between (rising)");
        __CPROVER_assert((out_old <= (int64_t)out) && ((int64_t)out <= u15),
                         "output between (rising)");
    } else {
        __CPROVER_assert((u31 <= (int64_t)f.state) && ((int64_t)f.state <= y_old),
                         "state between (falling)");
        __CPROVER_assert((u15 <= (int64_t)out) && ((int64_t)out <= out_old),
                         "output between (falling)");
    }
    return 0;
}
