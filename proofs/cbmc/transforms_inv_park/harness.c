/* CBMC harness: qfoc_inv_park over all int16 inputs.
 * Checks REQ-TRF-005 (range, rounding of the exact Q30 sums alpha = d cos - q sin,
 * beta = d sin + q cos over the clamped inputs, saturation) and REQ-TRF-006
 * (document bound in vector form d^2 + q^2 <= 32767^2, sin^2 + cos^2 <= 32768^2
 * implies exactness),
 * against an independent int64 computation.
 *
 * Scope of the bit-level check: the runtime-error checks (overflow, conversion,
 * pointers) and the output ranges hold over ALL int16 inputs.  Equality with the
 * independent reference needs the solver to prove two multiplier circuits equal,
 * which does not finish for full 16-bit operands; it is checked here for every
 * input vector at the four axis angles (sin, cos in {0, +-32767}) and at the
 * saturation corners, and over all inputs by WP
 * (the contract's exact behaviours) and by tests/test_transforms.c.
 *
 * Methods: 1b every int16 input for the ranges, every input vector at the four axis
 * angles for the exact values; 1c the axis angles (sin, cos in 0, +-32767), the
 * saturation corners, the document's bound */
#include <stdint.h>
#include "qfoc/transforms.h"

int16_t nondet_int16(void);

static int32_t sat_in(int16_t x)
{
    return (x == -32768) ? (int32_t)-32767 : (int32_t)x;
}

/* product of two clamped Q15 values: |x y| <= 32767^2 fits 32 bits exactly */
static int64_t prod(int32_t x, int32_t y)
{
    return (int64_t)(x * y);
}

/* x / 2^15 rounded to nearest, ties away from zero, saturated to +-32767;
   shifts only of non-negative values */
static int64_t round_sat_q30(int64_t x)
{
    int64_t r;
    if (x >= 0) {
        r = (x + 16384) >> 15;
    } else {
        r = -((16384 - x) >> 15);
    }
    if (r > 32767) {
        r = 32767;
    } else if (r < -32767) {
        r = -32767;
    } else {
        /* in range */
    }
    return r;
}

int main(void)
{
    qfoc_dq_t in;
    qfoc_sincos_t sc;
    qfoc_ab_t out;
    int32_t d;
    int32_t q;
    int32_t s;
    int32_t c;
    int64_t x1;
    int64_t x2;
    int64_t a_ref;
    int64_t b_ref;
    int axis;
    int corner;

    in.d = nondet_int16();
    in.q = nondet_int16();
    sc.sine = nondet_int16();
    sc.cosine = nondet_int16();
    d = sat_in(in.d);
    q = sat_in(in.q);
    s = sat_in(sc.sine);
    c = sat_in(sc.cosine);
    x1 = prod(d, c) - prod(q, s);   /* products exact in 32 bits, sum in 64 bits */
    x2 = prod(d, s) + prod(q, c);
    a_ref = round_sat_q30(x1);
    b_ref = round_sat_q30(x2);

    qfoc_inv_park(&in, &sc, &out);

    __CPROVER_assert((out.alpha >= -32767) && (out.alpha <= 32767), "alpha range");
    __CPROVER_assert((out.beta >= -32767) && (out.beta <= 32767), "beta range");
    axis = ((s == 0) && ((c == 32767) || (c == -32767))) ||
           ((c == 0) && ((s == 32767) || (s == -32767)));
    corner = ((d == 32767) || (d == -32767)) && ((q == 32767) || (q == -32767)) &&
             ((s == 32767) || (s == -32767)) && ((c == 32767) || (c == -32767));
    if (axis || corner) {
        __CPROVER_assert((int64_t)out.alpha == a_ref, "alpha = round/sat of exact sum");
        __CPROVER_assert((int64_t)out.beta == b_ref, "beta = round/sat of exact sum");
    }
    /* Inside the bound of specs/equations.md E2-39 (|exact result| <= 32767, ParkDocBound /
       InvParkDocBound: |Q30 sum| <= 32767 * 32768) the result is the exact sum
       rounded, without saturation.  The vector form of the bound is proved to
       imply it by WP (lemmas park_doc_bound, inv_park_doc_bound); a SAT solver
       cannot prove that nonlinear implication in reasonable time. */
    if (axis && (x1 >= -1073709056) && (x1 <= 1073709056)) {
        __CPROVER_assert((int64_t)out.alpha == ((x1 >= 0) ? ((x1 + 16384) >> 15) : -((16384 - x1) >> 15)),
                         "doc bound: alpha exact, not saturated");
    }
    if (axis && (x2 >= -1073709056) && (x2 <= 1073709056)) {
        __CPROVER_assert((int64_t)out.beta == ((x2 >= 0) ? ((x2 + 16384) >> 15) : -((16384 - x2) >> 15)),
                         "doc bound: beta exact, not saturated");
    }
    return 0;
}
