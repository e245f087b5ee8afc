/* CBMC harness: the Q15/Q31 primitives of include/qfoc/q15.h over their whole
 * input domains (part: q15_mul).  Requirements: REQ-Q15-001 .. REQ-Q15-008.
 *
 * A bit-level solver cannot afford to prove two 16 x 16 multipliers equal, so this
 * harness checks the runtime-error properties (no overflow, no conversion loss)
 * and the range and sign of the result over the whole input domain; the exact value
 * is proved by WP (contract behaviour 'exact') and tested against double precision
 * (tests/test_q15.c).
 *
 * Methods: 1b every pair of int16 values; 1c -32768 (multiplication by -1), zero
 * factors, the range [-32767, 32767] */
#include "qfoc/q15.h"

int16_t nondet_int16(void);


int main(void)
{
    int16_t a = nondet_int16();
    int16_t b = nondet_int16();
    int16_t r = qfoc_q15_mul(a, b);

    __CPROVER_assert((r >= -32767) && (r <= 32767), "REQ-Q15-005 mul range");
    __CPROVER_assert(((a >= 0) == (b >= 0)) ? (r >= 0) : (r <= 0), "REQ-Q15-005 mul sign");
    __CPROVER_assert(((a == 0) || (b == 0)) ? (r == 0) : 1, "REQ-Q15-005 mul zero");
    __CPROVER_assert((b == -32768) && (a != -32768) ? (r == (int16_t)-a) : 1,
                     "REQ-Q15-005 mul by -1");
    return 0;
}
