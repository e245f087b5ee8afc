/* CBMC harness: qfoc_inv_park over all int16 inputs.
 * Checks REQ-TRF-005 (range, rounding of the exact Q30 sums alpha = d cos - q sin,
 * beta = d sin + q cos over the clamped inputs, saturation) and REQ-TRF-006
 * (document bound in vector form d^2 + q^2 <= 32767^2, sin^2 + cos^2 <= 32768^2
 * implies exactness), against an independent int64 computation. */
#include <stdint.h>
#include "qfoc/transforms.h"

int16_t nondet_int16(void);

static int64_t sat_in(int16_t x)
{
    return (x == -32768) ? (int64_t)-32767 : (int64_t)x;
}

static int64_t round_sat_q30(int64_t x)
{
    int64_t r;
    if (x >= 0) {
        r = (x + 16384) / 32768;
    } else {
        r = -((16384 - x) / 32768);
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
    int64_t d;
    int64_t q;
    int64_t s;
    int64_t c;
    int64_t a_ref;
    int64_t b_ref;

    in.d = nondet_int16();
    in.q = nondet_int16();
    sc.sine = nondet_int16();
    sc.cosine = nondet_int16();
    d = sat_in(in.d);
    q = sat_in(in.q);
    s = sat_in(sc.sine);
    c = sat_in(sc.cosine);
    a_ref = round_sat_q30((d * c) - (q * s));
    b_ref = round_sat_q30((d * s) + (q * c));

    qfoc_inv_park(&in, &sc, &out);

    __CPROVER_assert((out.alpha >= -32767) && (out.alpha <= 32767), "alpha range");
    __CPROVER_assert((out.beta >= -32767) && (out.beta <= 32767), "beta range");
    __CPROVER_assert((int64_t)out.alpha == a_ref, "alpha = round/sat of exact sum");
    __CPROVER_assert((int64_t)out.beta == b_ref, "beta = round/sat of exact sum");
    if ((((int64_t)in.d * in.d) + ((int64_t)in.q * in.q) <= (int64_t)32767 * 32767) &&
        (sc.sine != -32768) && (sc.cosine != -32768) &&
        (((int64_t)sc.sine * sc.sine) + ((int64_t)sc.cosine * sc.cosine) <= (int64_t)32768 * 32768)) {
        int64_t ax = ((int64_t)in.d * sc.cosine) - ((int64_t)in.q * sc.sine);
        int64_t bx = ((int64_t)in.d * sc.sine) + ((int64_t)in.q * sc.cosine);
        __CPROVER_assert((ax > -1073725440) && (ax < 1073725440), "doc bound: alpha not saturated");
        __CPROVER_assert((bx > -1073725440) && (bx < 1073725440), "doc bound: beta not saturated");
        __CPROVER_assert((int64_t)out.alpha == round_sat_q30(ax), "doc bound: alpha exact");
        __CPROVER_assert((int64_t)out.beta == round_sat_q30(bx), "doc bound: beta exact");
    }
    return 0;
}
