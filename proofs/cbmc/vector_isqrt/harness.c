/*
 * CBMC harness: qfoc_isqrt32 on two windows of its input.
 *
 * Part 1, every v < 2^16 (the range estimate's branches for k = 0 .. 7), and
 * part 2, every v >= 2^32 - 2^24 (the top of the range, the largest roots and
 * the largest Newton sums): no run-time error (division by zero, overflow,
 * conversion), the floor square-root property r^2 <= v < (r + 1)^2, and the
 * correction loop ends after at most one step (unwinding assertion, UNWIND 3).
 * For the whole 32-bit range the three symbolic unsigned divisions make the
 * bit-level model too large for the SAT back end; there the contract (range,
 * floor_sqrt) and the absence of run-time errors are proved by Frama-C WP, and
 * tests/test_vector.c compares the result with an independent reference on
 * every v < 2^21, on every k^2 - 1, k^2, k^2 + k and on random values.
 * Requirements: REQ-VEC-001.
 *
 * Methods: 1b every v < 2^16 (the branches of the range estimate for k = 0 .. 7); 1c
 * every v >= 2^32 - 2^24 (the top of the range, the largest roots and Newton sums)
 */
#include "qfoc/vector.h"

uint16_t nondet_uint16(void);
uint32_t nondet_uint32(void);

static void check(uint32_t v)
{
    const uint32_t r = qfoc_isqrt32(v);
    const uint64_t r64 = (uint64_t)r;

    __CPROVER_assert(r <= 65535u, "isqrt range");
    __CPROVER_assert((r64 * r64) <= (uint64_t)v, "isqrt: r^2 <= v");
    __CPROVER_assert((uint64_t)v < ((r64 + 1u) * (r64 + 1u)), "isqrt: v < (r + 1)^2");
}

int main(void)
{
    /* Part 1: v < 2^16 */
    check((uint32_t)nondet_uint16());
    /* Part 2: v in [2^32 - 2^24, 2^32) */
    check(0xFF000000u | (nondet_uint32() & 0x00FFFFFFu));
    return 0;
}
