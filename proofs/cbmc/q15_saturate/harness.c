/* CBMC harness: the Q15/Q31 primitives of include/qfoc/q15.h over their whole
 * input domains (part: q15_saturate).  Requirements: REQ-Q15-001 .. REQ-Q15-008.
 * Each result is compared with an independent 64-bit computation.
 *
 * Methods: 1b every int16, int32 and int64 input of the saturating operations */
#include "qfoc/q15.h"

int16_t nondet_int16(void);
int32_t nondet_int32(void);
int64_t nondet_int64(void);

static int64_t ref_sat(int64_t x, int64_t lim)
{
    int64_t r = x;
    if (x > lim) {
        r = lim;
    } else if (x < -lim) {
        r = -lim;
    } else {
        /* in range */
    }
    return r;
}

/* x / 2^k rounded to nearest, ties away from zero (independent of the library:
 * works on the magnitude, where a shift is exact and cheap for the solver) */
static int64_t ref_round_div(int64_t x, uint32_t k)
{
    int64_t a = (x < 0) ? -x : x;
    int64_t q = (a + ((int64_t)1 << (k - 1u))) >> k;
    return (x < 0) ? -q : q;
}

int main(void)
{
    int16_t a = nondet_int16();
    int16_t b = nondet_int16();
    int32_t x32 = nondet_int32();
    int64_t x64 = nondet_int64();
    int32_t acc = nondet_int32();

    __CPROVER_assert(qfoc_q15_sat(x32) == (int16_t)ref_sat(x32, 32767), "REQ-Q15-001 sat");
    __CPROVER_assert(qfoc_q31_sat(x64) == (int32_t)ref_sat(x64, 2147483647), "REQ-Q15-006 sat31");
    __CPROVER_assert(qfoc_q15_add(a, b) == (int16_t)ref_sat((int64_t)a + b, 32767), "REQ-Q15-002 add");
    __CPROVER_assert(qfoc_q15_sub(a, b) == (int16_t)ref_sat((int64_t)a - b, 32767), "REQ-Q15-002 sub");
    __CPROVER_assert(qfoc_q15_neg(a) == (int16_t)ref_sat(-(int64_t)a, 32767), "REQ-Q15-003 neg");
    __CPROVER_assert(qfoc_q15_abs(a) == (int16_t)ref_sat((a < 0) ? -(int64_t)a : a, 32767),
                     "REQ-Q15-003 abs");
    __CPROVER_assert(qfoc_q31_add(acc, x32) == (int32_t)ref_sat((int64_t)acc + x32, 2147483647),
                     "REQ-Q15-006 add31");
    return 0;
}
