/* CBMC harness: qfoc_park over all int16 inputs.
 * Checks REQ-TRF-003 (range, rounding of the exact Q30 sums of (2-7), (2-8) over
 * the clamped inputs, saturation) and REQ-TRF-004 (document bound in vector form
 * alpha^2 + beta^2 <= 32767^2, sin^2 + cos^2 <= 32768^2 implies exactness),
 * against an independent int64 computation. */
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
    qfoc_ab_t in;
    qfoc_sincos_t sc;
    qfoc_dq_t out;
    int64_t a;
    int64_t b;
    int64_t s;
    int64_t c;
    int64_t d_ref;
    int64_t q_ref;

    in.alpha = nondet_int16();
    in.beta = nondet_int16();
    sc.sine = nondet_int16();
    sc.cosine = nondet_int16();
    a = sat_in(in.alpha);
    b = sat_in(in.beta);
    s = sat_in(sc.sine);
    c = sat_in(sc.cosine);
    d_ref = round_sat_q30((a * c) + (b * s));
    q_ref = round_sat_q30((b * c) - (a * s));

    qfoc_park(&in, &sc, &out);

    __CPROVER_assert((out.d >= -32767) && (out.d <= 32767), "d range");
    __CPROVER_assert((out.q >= -32767) && (out.q <= 32767), "q range");
    __CPROVER_assert((int64_t)out.d == d_ref, "d = round/sat of exact sum");
    __CPROVER_assert((int64_t)out.q == q_ref, "q = round/sat of exact sum");
    if ((((int64_t)in.alpha * in.alpha) + ((int64_t)in.beta * in.beta) <= (int64_t)32767 * 32767) &&
        (sc.sine != -32768) && (sc.cosine != -32768) &&
        (((int64_t)sc.sine * sc.sine) + ((int64_t)sc.cosine * sc.cosine) <= (int64_t)32768 * 32768)) {
        int64_t dx = ((int64_t)in.alpha * sc.cosine) + ((int64_t)in.beta * sc.sine);
        int64_t qx = ((int64_t)in.beta * sc.cosine) - ((int64_t)in.alpha * sc.sine);
        __CPROVER_assert((dx > -1073725440) && (dx < 1073725440), "doc bound: d not saturated");
        __CPROVER_assert((qx > -1073725440) && (qx < 1073725440), "doc bound: q not saturated");
        __CPROVER_assert((int64_t)out.d == round_sat_q30(dx), "doc bound: d exact");
        __CPROVER_assert((int64_t)out.q == round_sat_q30(qx), "doc bound: q exact");
    }
    return 0;
}
