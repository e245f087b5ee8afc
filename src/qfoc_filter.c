/**
 * @file qfoc_filter.c
 * @brief First-order low-pass filter (E2-34) and leaky integrator (E2-17) of specs/equations.md
 *        (see include/qfoc/filter.h).
 *
 * Requirements: REQ-FLT-001 .. REQ-FLT-008 (specs/requirements/filter.md).
 */
#include "qfoc/filter.h"
#include "qfoc/q15.h"

/** Q15 coefficient scale: 1.0 = 2^15 = 32768. */
#define QFOC_FLT_Q15_ONE ((int64_t)32768)
/** Half of QFOC_FLT_Q15_ONE, the round-to-nearest offset: 16384. */
#define QFOC_FLT_Q15_HALF ((int64_t)16384)
/** Q30 -> Q31 factor: a Q15 x Q15 product (2.30) times 2 is 1.31. */
#define QFOC_FLT_Q30_TO_Q31 ((int32_t)2)
/** Round-to-nearest offset of the Q31 -> Q15 conversion: 2^15 = 32768. */
#define QFOC_FLT_Q31_HALF_U ((uint32_t)32768u)
/** Q31 -> Q15 divisor: 2^16 = 65536. */
#define QFOC_FLT_Q31_ONE_U ((uint32_t)65536u)
/** Largest Q15 magnitude of the symmetric range: 32767. */
#define QFOC_FLT_Q15_MAX_U ((uint32_t)32767u)
/** Low-pass coefficient scale 2^17: alpha (Q15) x 2^17 puts the increment (Q31)
    in the high word of the 64-bit product. */
#define QFOC_LPF_ALPHA_SCALE ((uint32_t)131072u)
/** Round-to-nearest offset 16384 x 2^17 = 2^31 of that product. */
#define QFOC_LPF_ROUND_HALF ((uint64_t)2147483648u)
/** 2^32: the weight of the high word. */
#define QFOC_LPF_HIGH_WORD ((uint64_t)4294967296u)
/** Safe low-pass coefficient after a rejected init: 32767 / 32768 = 0.99997. */
#define QFOC_LPF_ALPHA_SAFE ((qfoc_q15_t)32767)
/** Safe leak after a rejected init: 32767 / 32768 = 0.99997 (state decays at once). */
#define QFOC_LEAKY_LEAK_SAFE ((qfoc_q15_t)32767)

/**
 * @brief 2^s for a gain shift s in 0..15 (table look-up, no shift operator).
 */
/*@
  requires shift_range: s <= 15;
  assigns \nothing;
  ensures value: \result == FilterPow2(s);
  ensures range: 1 <= \result <= 32768;
*/
static int32_t qfoc_flt_pow2(uint8_t s)
{
    /* 2^s for s = 0..15 (the gain shifts); exact integers 1 .. 32768 */
    static const int32_t qfoc_flt_pow2_table[16] = {
        1, 2, 4, 8, 16, 32, 64, 128,
        256, 512, 1024, 2048, 4096, 8192, 16384, 32768
    };
    /* s % 16: the contract's s <= 15 leaves it unchanged; a shift corrupted in RAM (a
       random hardware fault the RAM check, REQ-DRV-019, reports within 4 ms) still
       reads inside the table */
    return qfoc_flt_pow2_table[s % 16u];
}

/**
 * @brief x / 32768 rounded to nearest, ties away from zero (no right shift of a
 *        negative value), for |x| < 2^62.
 */
/*@
  requires x_range: -4611686018427387904 < x < 4611686018427387904;
  assigns \nothing;
  ensures value: \result == QfocRoundDiv(x, 32768);
*/
static int64_t qfoc_flt_round_q15(int64_t x)
{
    int64_t r;
    if (x >= 0) {
        r = (x + QFOC_FLT_Q15_HALF) / QFOC_FLT_Q15_ONE;
    } else {
        r = -((QFOC_FLT_Q15_HALF - x) / QFOC_FLT_Q15_ONE);
    }
    return r;
}

/**
 * @brief Q31 -> Q15: x / 65536 rounded to nearest (ties away from zero) and
 *        saturated to [-32767, 32767], for x in the symmetric Q31 range.
 *
 * Scaling and overflow: the magnitude |x| <= 2^31 - 1 is rounded as an unsigned
 * value, |x| + 32768 < 2^32, so no right shift of a negative value is needed; the
 * quotient is at most 32768 and is saturated before the sign is restored.
 */
/*@
  requires x_range: QfocQ31Sym(x);
  assigns \nothing;
  ensures value: \result == QfocSat15(QfocRoundDiv(x, 65536));
  ensures range: QfocQ15Sym(\result);
*/
static qfoc_q15_t qfoc_flt_q15_from_q31(qfoc_q31_t x)
{
    int32_t r;
    if (x >= 0) {
        const uint32_t ux = (uint32_t)x;
        uint32_t m = (ux + QFOC_FLT_Q31_HALF_U) / QFOC_FLT_Q31_ONE_U;
        if (m > QFOC_FLT_Q15_MAX_U) {
            m = QFOC_FLT_Q15_MAX_U;
        }
        r = (int32_t)m;
    } else {
        const int32_t nx = -x;
        const uint32_t ux = (uint32_t)nx;
        uint32_t m = (ux + QFOC_FLT_Q31_HALF_U) / QFOC_FLT_Q31_ONE_U;
        if (m > QFOC_FLT_Q15_MAX_U) {
            m = QFOC_FLT_Q15_MAX_U;
        }
        r = -(int32_t)m;
    }
    return (qfoc_q15_t)r;
}

/**
 * @brief Rounded low-pass increment magnitude: alpha x d / 32768 rounded to
 *        nearest (ties away from zero), for a distance 0 <= d < 2^32.
 *
 * Scaling and overflow: alpha x 2^17 < 2^32; (alpha 2^17) x d + 2^31 =
 * 2^17 (alpha d + 16384) < 2^64 in one unsigned 32 x 32 -> 64 bit
 * multiply-accumulate, whose high word is (alpha d + 16384) / 32768 (no shift
 * of a 64-bit value).  The result is at most d (alpha < 32768).
 */
/*@
  requires alpha_range: 0 < alpha <= 32767;
  requires d_range: 0 <= d <= 4294967295;
  assigns \nothing;
  ensures value: \result == QfocRoundDiv(alpha * d, 32768);
  ensures bound: \result <= d;
*/
static uint32_t qfoc_lpf_inc(qfoc_q15_t alpha, uint32_t d)
{
    const uint32_t a17 = (uint32_t)alpha * QFOC_LPF_ALPHA_SCALE;
    const uint64_t p = ((uint64_t)a17 * (uint64_t)d) + QFOC_LPF_ROUND_HALF;
    /*@ assert p_value: p == 131072 * (alpha * d + 16384); */
    return (uint32_t)(p / QFOC_LPF_HIGH_WORD);
}

/**
 * @brief Saturate a Q15 input to the symmetric range and widen it to Q31.
 */
/*@
  assigns \nothing;
  ensures value: \result == QfocSat15(u) * 65536;
  ensures range: FilterQ15InQ31(\result);
*/
static qfoc_q31_t qfoc_flt_q31_from_input(qfoc_q15_t u)
{
    /* |sat(u)| <= 32767: x 65536 <= 2147418112 fits 32 bits */
    return (qfoc_q31_t)qfoc_q15_sat((int32_t)u) * (int32_t)65536;
}

bool qfoc_lpf_is_valid(const qfoc_lpf_t *f)
{
    bool ok = false;
    if ((f->alpha > 0) && (f->state >= QFOC_Q31_MIN)) {
        ok = true;
    } else {
        /* invalid coefficient or state -2^31 */
    }
    return ok;
}

int32_t qfoc_lpf_init(qfoc_lpf_t *f, qfoc_q15_t alpha)
{
    int32_t status;
    if (alpha > 0) {
        f->alpha = alpha;
        status = QFOC_FILTER_OK;
    } else {
        f->alpha = QFOC_LPF_ALPHA_SAFE;
        status = QFOC_FILTER_ERR_PARAM;
    }
    f->state = 0;
    return status;
}

void qfoc_lpf_reset(qfoc_lpf_t *f, qfoc_q15_t value)
{
    f->state = qfoc_flt_q31_from_input(value);
}

qfoc_q15_t qfoc_lpf_step(qfoc_lpf_t *f, qfoc_q15_t u)
{
    const qfoc_q31_t y = f->state;
    /* u in Q31, within [-32767, 32767] x 65536 */
    const qfoc_q31_t in = qfoc_flt_q31_from_input(u);
    qfoc_q31_t next;

    if (in >= y) {
        /* rising: d = u - y in [0, 2^32); 0 <= increment <= d, so y + increment
           lies in [y, u] and fits 32 bits */
        const int64_t d64 = (int64_t)in - (int64_t)y;
        const uint32_t d = (uint32_t)d64;
        const uint32_t inc = qfoc_lpf_inc(f->alpha, d);
        const int64_t sum = (int64_t)y + (int64_t)inc;
        /*@ assert inc_value: inc == QfocRoundDiv(f->alpha * (LpfInput(u) - y), 32768); */
        /*@ assert sum_range: sum <= in; */
        next = (qfoc_q31_t)sum;
    } else {
        /* falling: d = y - u in (0, 2^32); the increment is -round(alpha d / 32768)
           (rounding ties away from zero is symmetric), y - |increment| in [u, y] */
        const int64_t d64 = (int64_t)y - (int64_t)in;
        const uint32_t d = (uint32_t)d64;
        const uint32_t inc = qfoc_lpf_inc(f->alpha, d);
        /*@ assert inc_value: -inc == QfocRoundDiv(f->alpha * (LpfInput(u) - y), 32768); */
        next = (qfoc_q31_t)((int64_t)y - (int64_t)inc);
    }
    f->state = next;
    /* Q31 -> Q15 rounded (saturates only if the state was set outside the Q15
       range by the caller) */
    return qfoc_flt_q15_from_q31(next);
}

bool qfoc_leaky_is_valid(const qfoc_leaky_int_t *f)
{
    bool ok = false;
    if ((f->gain >= 0) && (f->gain_shift <= QFOC_LEAKY_SHIFT_MAX) && (f->leak >= 0)
        && (f->state >= QFOC_Q31_MIN)) {
        ok = true;
    } else {
        /* invalid coefficient or state -2^31 */
    }
    return ok;
}

int32_t qfoc_leaky_init(qfoc_leaky_int_t *f, qfoc_q15_t gain, uint8_t gain_shift,
                        qfoc_q15_t leak)
{
    int32_t status;
    if ((gain >= 0) && (gain_shift <= QFOC_LEAKY_SHIFT_MAX) && (leak >= 0)) {
        f->gain = gain;
        f->gain_shift = gain_shift;
        f->leak = leak;
        status = QFOC_FILTER_OK;
    } else {
        f->gain = 0;
        f->gain_shift = 0u;
        f->leak = QFOC_LEAKY_LEAK_SAFE;
        status = QFOC_FILTER_ERR_PARAM;
    }
    f->state = 0;
    return status;
}

void qfoc_leaky_reset(qfoc_leaky_int_t *f, qfoc_q15_t value)
{
    f->state = qfoc_flt_q31_from_input(value);
}

qfoc_q15_t qfoc_leaky_step(qfoc_leaky_int_t *f, qfoc_q15_t x)
{
    const int64_t y = (int64_t)f->state;
    const int32_t pw2 = qfoc_flt_pow2(f->gain_shift);
    const int32_t half = pw2 / 2;
    /* x (1.15) x gain (1.15) = 2.30, |.| <= 32768 x 32767 < 2^30: exact in 32 bits */
    const int32_t xg = (int32_t)x * (int32_t)f->gain;
    int32_t p;
    int32_t step;
    int64_t loss;

    /*@ assert xg_range: -1073709056 <= xg <= 1073676289; */
    /* x 2 -> 1.31: |p| <= 2147418112 < 2^31, exact in 32 bits */
    p = xg * QFOC_FLT_Q30_TO_Q31;
    /* integration step T x: p / 2^gain_shift rounded to nearest (ties away from
       zero); p + half and half - p stay below 2^31 (half <= 16384) */
    if (p >= 0) {
        step = (p + half) / pw2;
    } else {
        step = -((half - p) / pw2);
    }
    /*@ assert step_eq: step == QfocRoundDiv(p, pw2); */

    /*@ assert loss_hi: y >= 0 ==> 0 <= f->leak * y <= 32767 * y; */
    /*@ assert loss_lo: y < 0 ==> 32767 * y <= f->leak * y <= 0; */
    /* leak term (T / tau) y: leak (1.15) x y (1.31) = 2.46, |.| < 2^46, back to
       Q31 rounded; |loss| <= |y| */
    loss = qfoc_flt_round_q15((int64_t)f->leak * y);

    /* y + T x - (T / tau) y, |.| < 2^33 in 64 bits, saturated to the symmetric
       Q31 range */
    f->state = qfoc_q31_sat((y + (int64_t)step) - loss);
    return qfoc_q15_from_q31(f->state);
}
