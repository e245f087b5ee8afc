/*
 * CBMC harness: qfoc_vec_mag, with qfoc_isqrt32 replaced by its contract
 * (../isqrt_stub.h; its own harness is vector_isqrt).
 *
 * Part 1, every (x, y) pair of int16 values (-32768 included): no run-time
 * error (overflow, conversion, bounds), result in [0, 32767], saturation on
 * the extreme vectors.
 * Part 2, x and y of up to 8 bits (sign-extended nondet int8): the floor
 * square-root property m^2 <= x^2 + y^2 < (m + 1)^2.  (For full
 * 16 / 32-bit symbolic operands the squares make the SAT problem a
 * multiplier-equivalence problem that does not finish in minutes; the
 * property is proved for every input by Frama-C WP, contract ensures
 * floor_sqrt / behaviour exact, and tested on all v < 2^21, on every k^2 - 1,
 * k^2, k^2 + k and on random values in tests/test_vector.c.)
 * Requirements: REQ-VEC-002.
 *
 * Methods: 1b every (x, y) pair for the range, 8-bit operands for the floor square
 * root; 1c the extreme vectors (-32768, saturation at 32767)
 */
#include "qfoc/vector.h"
#include "../isqrt_stub.h"

int16_t nondet_int16(void);
int8_t nondet_int8(void);

/* v * v for |v| <= 32768, through a 16-bit magnitude. */
static uint32_t sq(int32_t v)
{
    uint16_t m = (uint16_t)((v < 0) ? -v : v);
    return (uint32_t)m * (uint32_t)m;
}

int main(void)
{
    qfoc_q15_t x = nondet_int16();
    qfoc_q15_t y = nondet_int16();
    qfoc_q15_t m = qfoc_vec_mag(x, y);
    uint32_t s;

    /* Part 1: full range */
    __CPROVER_assert((m >= 0) && (m <= 32767), "mag range");
    if ((x == -32768) || (x == 32767) || (y == -32768) || (y == 32767)) {
        __CPROVER_assert(m == 32767, "mag saturated at the extreme components");
    }

    /* Part 2: small operands, floor square root */
    x = (qfoc_q15_t)nondet_int8();
    y = (qfoc_q15_t)nondet_int8();
    m = qfoc_vec_mag(x, y);
    s = sq((int32_t)x) + sq((int32_t)y);
    __CPROVER_assert(sq((int32_t)m) <= s, "mag: m^2 <= x^2 + y^2");
    __CPROVER_assert(s < sq((int32_t)m + 1), "mag: x^2 + y^2 < (m + 1)^2");

    return 0;
}
