/*
 * CBMC harness: qfoc_circle_limit with nondet (d, q, vmax), every int16 value.
 * Checks: no run-time error, output inside the circle of radius
 * max(vmax, 0), d' = clamp(d, -vmax, vmax), output == input and result false
 * when the input is inside, result true otherwise.  The in-place call
 * (in == out, allowed by the contract) is covered by the WP proof, which does
 * not assume separation, and by tests/test_vector.c.
 * Requirements: REQ-VEC-003, REQ-VEC-004.
 */
#include "qfoc/vector.h"

int16_t nondet_int16(void);

/* v * v for |v| <= 32768, through a 16-bit magnitude so that the solver
 * sees a 16 x 16 bit product. */
static uint32_t sq(int32_t v)
{
    uint16_t m = (uint16_t)((v < 0) ? -v : v);
    return (uint32_t)m * (uint32_t)m;
}

int main(void)
{
    qfoc_dq_t in;
    qfoc_dq_t out;
    qfoc_q15_t vmax = nondet_int16();
    int32_t vm;
    int32_t d;
    int32_t q;
    uint32_t r2_in;
    uint32_t r2_out;
    bool lim;

    in.d = nondet_int16();
    in.q = nondet_int16();
    vm = (vmax < 0) ? 0 : (int32_t)vmax;
    d = (int32_t)in.d;
    q = (int32_t)in.q;

    lim = qfoc_circle_limit(&in, vmax, &out);

    /* squares <= 2^30, sums <= 2^31 in uint32 */
    r2_in = sq(d) + sq(q);
    r2_out = sq((int32_t)out.d) + sq((int32_t)out.q);
    __CPROVER_assert(r2_out <= sq(vm), "output inside the circle");
    __CPROVER_assert((int32_t)out.d == ((d > vm) ? vm : ((d < -vm) ? -vm : d)),
                     "d priority: d' = clamp(d, -vmax, vmax)");
    if (r2_in <= sq(vm)) {
        __CPROVER_assert((out.d == in.d) && (out.q == in.q), "inside: unchanged");
        __CPROVER_assert(!lim, "inside: not limited");
    } else {
        __CPROVER_assert(lim, "outside: limited");
    }
    return 0;
}
