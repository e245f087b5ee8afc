/* CBMC harness: the Q15/Q31 primitives of include/qfoc/q15.h over their whole
 * input domains (part: q15_mac).  Requirements: REQ-Q15-001 .. REQ-Q15-008.
 *
 * A bit-level solver cannot afford to prove two 16 x 16 multipliers equal, so this
 * harness checks the runtime-error properties (no overflow, no conversion loss)
 * and the range and sign of the result over the whole input domain; the exact value
 * is proved by WP (contract behaviour 'exact') and tested against double precision
 * (tests/test_q15.c).
 *
 * Methods: 1b every accumulator and every pair of int16 factors; 1c the accumulator
 * INT32_MIN (the result never INT32_MIN), zero products */
#include "qfoc/q15.h"

int16_t nondet_int16(void);
int32_t nondet_int32(void);


int main(void)
{
    int32_t acc = nondet_int32();
    int16_t a = nondet_int16();
    int16_t b = nondet_int16();
    int32_t r = qfoc_q31_mac(acc, a, b);

    __CPROVER_assert(r != INT32_MIN, "REQ-Q15-007 mac symmetric range");
    __CPROVER_assert(((a == 0) || (b == 0)) ? (r == ((acc == INT32_MIN) ? -2147483647 : acc)) : 1,
                     "REQ-Q15-007 mac zero product");
    __CPROVER_assert((((a >= 0) == (b >= 0)) && (acc > INT32_MIN)) ? (r >= acc) : 1,
                     "REQ-Q15-007 mac monotone, positive product");
    __CPROVER_assert((((a >= 0) != (b >= 0)) && (acc > INT32_MIN)) ? (r <= acc) : 1,
                     "REQ-Q15-007 mac monotone, negative product");
    return 0;
}
