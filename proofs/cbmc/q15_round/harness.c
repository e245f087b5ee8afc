/* CBMC harness: the Q15/Q31 primitives of include/qfoc/q15.h over their whole
 * input domains (part: q15_round).  Requirements: REQ-Q15-001 .. REQ-Q15-008.
 * Each result is compared with an independent 64-bit computation.
 *
 * Methods: 1b every int16 and int32 input of the conversions */
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
    int32_t x32 = nondet_int32();

    __CPROVER_assert(qfoc_q15_from_q30(x32) == (int16_t)ref_sat(ref_round_div(x32, 15u), 32767),
                     "REQ-Q15-004 from_q30");
    __CPROVER_assert(qfoc_q15_from_q31(x32) == (int16_t)ref_sat(ref_round_div(x32, 16u), 32767),
                     "REQ-Q15-008 from_q31");
    __CPROVER_assert(qfoc_q31_from_q15(a) == (int32_t)a * 65536, "REQ-Q15-008 to_q31");
    return 0;
}
