/**
 * @file qfoc_vector.c
 * @brief Integer square root, vector magnitude and circle limitation.
 *
 * See include/qfoc/vector.h for the contracts and the scaling.
 *
 * Requirements: REQ-VEC-001 .. REQ-VEC-004 (specs/requirements/trig.md).
 */
#include "qfoc/vector.h"
#include "qfoc/q15.h"

/* Upper end (exclusive) of the square-root search: 65536^2 = 2^32 > any uint32_t. */
#define VEC_ISQRT_HI (65536u)

/* m * m for a 16-bit m (<= 65535^2 = 4294836225 < 2^32).  The 16-bit
 * parameter type states the operand width to the provers and to CBMC. */
/*@
  assigns \nothing;
  ensures value: \result == m * m;
*/
static uint32_t vec_sq_u16(uint16_t m)
{
    uint32_t w = (uint32_t)m;
    //@ assert sq_u16: w * w <= 4294836225;
    return w * w;
}

uint32_t qfoc_isqrt32(uint32_t v)
{
    uint32_t lo = 0u;            /* lo * lo <= v */
    uint32_t hi = VEC_ISQRT_HI;  /* v < hi * hi */

    /*@
      loop invariant bounds: 0 <= lo < hi <= 65536;
      loop invariant low: lo * lo <= v;
      loop invariant high: v < hi * hi;
      loop assigns lo, hi;
      loop variant hi - lo;
    */
    while ((hi - lo) > 1u) {
        uint32_t mid = lo + ((hi - lo) / 2u);   /* lo < mid < hi <= 65536 */
        //@ assert mid_range: lo < mid < hi;
        if (vec_sq_u16((uint16_t)mid) <= v) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    return lo;
}

/* v * v as uint32 for |v| <= 32768 (<= 2^30). */
/*@
  requires v_range: -32768 <= v <= 32768;
  assigns \nothing;
  ensures value: \result == v * v;
  ensures bound: \result <= 1073741824;
*/
static uint32_t vec_square(int32_t v)
{
    int32_t a = v;

    if (a < 0) {
        a = -a;                          /* |v| <= 32768 */
    }
    //@ assert sq_bound: 0 <= a * a <= 1073741824;
    return vec_sq_u16((uint16_t)a);
}

qfoc_q15_t qfoc_vec_mag(qfoc_q15_t x, qfoc_q15_t y)
{
    uint32_t s = vec_square((int32_t)x) + vec_square((int32_t)y);   /* 2.30, <= 2^31 */
    uint32_t r = qfoc_isqrt32(s);                 /* 1.15, <= 46341 */
    int32_t m;

    if (r > (uint32_t)QFOC_Q15_MAX) {
        /* longer than the Q15 range: saturate */
        m = (int32_t)QFOC_Q15_MAX;
    } else {
        m = (int32_t)r;
    }
    return (qfoc_q15_t)m;
}

/* v clamped to [-lim, lim], lim >= 0. */
/*@
  requires lim_range: 0 <= lim <= 32767;
  assigns \nothing;
  ensures value: \result == QfocClamp(v, -lim, lim);
*/
static int32_t vec_clamp(int32_t v, int32_t lim)
{
    int32_t r = v;

    if (v > lim) {
        r = lim;
    } else if (v < -lim) {
        r = -lim;
    } else {
        /* inside the limits */
    }
    return r;
}

bool qfoc_circle_limit(const qfoc_dq_t *in, qfoc_q15_t vmax, qfoc_dq_t *out)
{
    /* read the whole input first: in and out may alias */
    int32_t d = (int32_t)in->d;
    int32_t q = (int32_t)in->q;
    int32_t vm = (int32_t)vmax;
    int32_t dl;
    int32_t ql;
    int32_t qo;
    uint32_t w;
    bool limited;

    if (vm < 0) {
        /* negative radius acts as zero */
        vm = 0;
    }
    dl = vec_clamp(d, vm);                   /* d priority: |dl| <= vm */
    //@ assert dl_sq: dl * dl <= vm * vm;
    w = vec_square(vm) - vec_square(dl);     /* 2.30, in [0, 32767^2] */
    ql = (int32_t)qfoc_isqrt32(w);           /* q room left, 1.15 */
    //@ assert ql_sq: ql * ql <= vm * vm;
    //@ assert ql_bound: 0 <= ql <= vm;
    qo = vec_clamp(q, ql);
    //@ assert qo_sq: qo * qo <= ql * ql;
    limited = (dl != d) || (qo != q);
    out->d = (qfoc_q15_t)dl;
    out->q = (qfoc_q15_t)qo;
    return limited;
}
