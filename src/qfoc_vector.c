/**
 * @file qfoc_vector.c
 * @brief Vector magnitude and circle limitation (the integer square root is
 * in qfoc_isqrt.c).
 *
 * See include/qfoc/vector.h for the contracts and the scaling.
 *
 * Requirements: REQ-VEC-002 .. REQ-VEC-004 (specs/requirements/trig.md).
 */
#include "qfoc/vector.h"
#include "qfoc/q15.h"

/* 32767^2 = 1073676289: from this squared length on the magnitude saturates. */
#define VEC_MAG_SAT_SQ (1073676289u)

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
    const uint32_t s = vec_square((int32_t)x) + vec_square((int32_t)y);   /* 2.30, <= 2^31 */
    int32_t m;

    if (s >= VEC_MAG_SAT_SQ) {
        /* at least 32767 long: saturate (the root would be >= 32767), no root */
        m = (int32_t)QFOC_Q15_MAX;
    } else {
        m = (int32_t)qfoc_isqrt32(s);             /* 1.15, <= 32766 */
        //@ assert m_max: m * m < 32767 * 32767;
        //@ assert m_range: 0 <= m <= 32766;
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
    int32_t adl;
    int32_t ql;
    int32_t qo;
    uint32_t vmu;
    uint32_t adu;
    uint32_t aqu;
    uint32_t r2;
    uint32_t w;
    int32_t gap;
    bool limited;

    if (vm < 0) {
        /* negative radius acts as zero */
        vm = 0;
    }
    //@ assert vm_clamp: vm == QfocVmaxClamp(vmax);
    dl = vec_clamp(d, vm);                   /* d priority: |dl| <= vm */
    adl = dl;
    if (adl < 0) {
        adl = -adl;
    }
    vmu = (uint32_t)vm;
    adu = (uint32_t)((d < 0) ? -d : d);      /* |d| <= 32768 */
    aqu = (uint32_t)((q < 0) ? -q : q);      /* |q| <= 32768 */
    /* d^2 + q^2 <= 2 * 2^30 = 2^31: exact in uint32 */
    r2 = (adu * adu) + (aqu * aqu);
    //@ assert r2_value: r2 == (d * d) + (q * q);
    if (r2 <= (vmu * vmu)) {
        /* inside or on the circle: nothing to limit (decided exactly, on the
         * squared radius, so the result never depends on square-root rounding) */
        //@ assert d_sq: d * d <= vm * vm;
        //@ assert d_in: -vm <= d <= vm;
        qo = q;
        limited = false;
    } else {
        /* vm^2 - dl^2 = (vm - |dl|) (vm + |dl|).  |dl| = min(|d|, vm), so
         * vm - |dl| = max(vm - |d|, 0), in [0, 32767] on its own bounds (no
         * relation between two variables needed to see it), and vm + |dl| is
         * in [0, 65534]: the product cannot overflow 32 bits (2.30, <= 32767^2) */
        //@ assert outside: (d * d) + (q * q) > vm * vm;
        gap = vm - (int32_t)adu;
        if (gap < 0) {
            gap = 0;
        }
        //@ assert gap_value: gap == vm - adl;
        w = (uint32_t)gap * (vmu + (uint32_t)adl);
        //@ assert w_value: w == (vm * vm) - (dl * dl);
        ql = (int32_t)qfoc_isqrt32(w);       /* q room left, 1.15 */
        //@ assert ql_sq: ql * ql <= vm * vm;
        //@ assert ql_bound: 0 <= ql <= vm;
        qo = vec_clamp(q, ql);
        //@ assert qo_sq: qo * qo <= ql * ql;
        limited = true;
    }
    /* |dl|, |qo| <= vm <= 32767: the saturation never acts (proved) */
    out->d = qfoc_q15_sat(dl);
    out->q = qfoc_q15_sat(qo);
    return limited;
}
