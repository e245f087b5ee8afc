/*
 * CBMC harness: qfoc_circle_limit, with qfoc_isqrt32 replaced by its contract
 * (../isqrt_stub.h; its own harness is vector_isqrt).
 *
 * Part 1, every int16 value of (d, q, vmax): no run-time error (overflow,
 * conversion, bounds, pointer), and the properties that are linear in the
 * inputs: d' = clamp(d, -max(vmax, 0), max(vmax, 0)), q' has the sign of q
 * and |q'| <= |q|.
 *
 * Part 2, |d|, |q|, vmax of up to 8 bits (sign-extended nondet int8): the
 * quadratic properties: the output lies inside the circle, the output equals
 * the input and the result is false when the input lies inside, the result is
 * true otherwise, and the result is true exactly when some component changed
 * (the function decides on d^2 + q^2 <= vmax^2, a quadratic test).  (Squares of full 16-bit symbolic values make the SAT
 * problem a multiplier-equivalence problem that does not finish in minutes;
 * these properties are proved for the full range by Frama-C WP, contract
 * behaviours inside / limited and ensures in_circle, and tested on random
 * full-range inputs in tests/test_vector.c.)
 *
 * The in-place call (in == out, allowed by the contract) is covered by the
 * WP proof, which does not assume separation, and by tests/test_vector.c.
 * Requirements: REQ-VEC-003, REQ-VEC-004.
 *
 * Methods: 1b every int16 (d, q, vmax) for the linear properties, inside and outside
 * the circle for 8-bit operands; 1c negative vmax (taken as 0), vectors exactly on the
 * circle; 1d a negative limit
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

static int32_t clamp(int32_t v, int32_t lim)
{
    return (v > lim) ? lim : ((v < -lim) ? -lim : v);
}

int main(void)
{
    qfoc_dq_t in;
    qfoc_dq_t out;
    qfoc_q15_t vmax = nondet_int16();
    int32_t vm;
    int32_t d;
    int32_t q;
    int32_t od;
    int32_t oq;
    bool lim;

    /* Part 1: full range, linear properties */
    in.d = nondet_int16();
    in.q = nondet_int16();
    vm = (vmax < 0) ? 0 : (int32_t)vmax;
    d = (int32_t)in.d;
    q = (int32_t)in.q;
    lim = qfoc_circle_limit(&in, vmax, &out);
    od = (int32_t)out.d;
    oq = (int32_t)out.q;
    __CPROVER_assert(od == clamp(d, vm), "d priority: d' = clamp(d, -vmax, vmax)");
    __CPROVER_assert((q >= 0) ? ((oq >= 0) && (oq <= q)) : ((oq <= 0) && (oq >= q)),
                     "q' keeps the sign of q and does not grow");

    /* Part 2: 8-bit operands, quadratic properties */
    vmax = (qfoc_q15_t)nondet_int8();
    in.d = (qfoc_q15_t)nondet_int8();
    in.q = (qfoc_q15_t)nondet_int8();
    vm = (vmax < 0) ? 0 : (int32_t)vmax;
    d = (int32_t)in.d;
    q = (int32_t)in.q;
    lim = qfoc_circle_limit(&in, vmax, &out);
    __CPROVER_assert((sq((int32_t)out.d) + sq((int32_t)out.q)) <= sq(vm),
                     "output inside the circle");
    if ((sq(d) + sq(q)) <= sq(vm)) {
        __CPROVER_assert((out.d == in.d) && (out.q == in.q), "inside: unchanged");
        __CPROVER_assert(!lim, "inside: not limited");
    } else {
        __CPROVER_assert(lim, "outside: limited");
    }
    __CPROVER_assert(lim == ((out.d != in.d) || (out.q != in.q)), "result true iff limited");
    return 0;
}
