/*
 * CBMC harness: qfoc_vec_mag over every (x, y) pair (nondet int16, -32768
 * included) and qfoc_isqrt32 over every uint32_t.
 * Checks: no run-time error, result in [0, 32767], floor square root
 * r^2 <= x^2 + y^2 < (r + 1)^2 when not saturated, 32767 when saturated.
 * Requirements: REQ-VEC-001, REQ-VEC-002.
 */
#include "qfoc/vector.h"

int16_t nondet_int16(void);
uint32_t nondet_uint32(void);

int main(void)
{
    qfoc_q15_t x = nondet_int16();
    qfoc_q15_t y = nondet_int16();
    uint32_t v = nondet_uint32();
    uint64_t s = ((uint64_t)((int64_t)x * (int64_t)x)) + ((uint64_t)((int64_t)y * (int64_t)y));
    qfoc_q15_t m = qfoc_vec_mag(x, y);
    uint64_t mu = (uint64_t)m;
    uint64_t r = (uint64_t)qfoc_isqrt32(v);

    __CPROVER_assert((r * r) <= (uint64_t)v, "isqrt: r^2 <= v");
    __CPROVER_assert((uint64_t)v < ((r + 1u) * (r + 1u)), "isqrt: v < (r + 1)^2");
    __CPROVER_assert((m >= 0) && (m <= 32767), "mag range");
    if (s < (32767u * 32767u)) {
        __CPROVER_assert((mu * mu) <= s, "mag: r^2 <= s");
        __CPROVER_assert(s < ((mu + 1u) * (mu + 1u)), "mag: s < (r + 1)^2");
    } else {
        __CPROVER_assert(m == 32767, "mag saturated");
    }
    return 0;
}
