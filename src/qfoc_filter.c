/**
 * @file qfoc_filter.c
 * @brief First-order low-pass filter (2-34) and leaky integrator (2-17)
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
    return qfoc_flt_pow2_table[s];
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
    const int64_t y = (int64_t)f->state;
    const int64_t alpha = (int64_t)f->alpha;
    /* u - y in Q31, |d| <= 2147418112 + 2147483647 < 2^33 */
    const int64_t d = (int64_t)qfoc_flt_q31_from_input(u) - y;
    int64_t prod;
    int64_t inc;

    /*@ assert d_range: -4294901759 <= d <= 4294901759; */
    /*@ assert prod_hi: d >= 0 ==> 0 <= alpha * d <= 32767 * d; */
    /*@ assert prod_lo: d < 0 ==> 32767 * d <= alpha * d < 0; */
    /* alpha (1.15) x d (1.31) = 2.46, |.| < 2^48 */
    prod = alpha * d;
    /* back to Q31, rounded: |inc| <= |d| because alpha < 32768 */
    inc = qfoc_flt_round_q15(prod);
    /*@ assert inc_hi: d >= 0 ==> 0 <= inc <= d; */
    /*@ assert inc_lo: d < 0 ==> d <= inc <= 0; */
    /* y + inc lies between y and u (both in the symmetric Q31 range), so the
       saturation never changes the value (proved: contract of qfoc_lpf_step); it
       makes the range of the state evident to bit-level checkers as well */
    f->state = qfoc_q31_sat(y + inc);
    /* Q31 -> Q15 rounded (saturates only if the state was set outside the Q15
       range by the caller) */
    return qfoc_q15_from_q31(f->state);
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
