/**
 * @file qfoc_pi.c
 * @brief Discrete PI controller with clamping anti-windup (see include/qfoc/pi.h).
 *
 * Requirements: REQ-PI-001 .. REQ-PI-008 (specs/requirements/pi.md).
 */
#include "qfoc/pi.h"
#include "qfoc/q15.h"

/** Q15 -> Q31 widening factor: 2^16 = 65536. */
#define QFOC_PI_Q15_TO_Q31 ((int64_t)65536)
/** Q30 -> Q31 factor: a Q15 x Q15 product (2.30) times 2 is 1.31. */
#define QFOC_PI_Q30_TO_Q31 ((int64_t)2)

/**
 * @brief 2^s for a gain shift s in 0..15 (table look-up, no shift operator).
 */
/*@
  requires shift_range: s <= 15;
  assigns \nothing;
  ensures value: \result == PiPow2(s);
  ensures range: 1 <= \result <= 32768;
*/
static int64_t qfoc_pi_pow2(uint8_t s)
{
    /* 2^s for s = 0..15 (the gain shifts); exact integers 1 .. 32768 */
    static const int32_t qfoc_pi_pow2_table[16] = {
        1, 2, 4, 8, 16, 32, 64, 128,
        256, 512, 1024, 2048, 4096, 8192, 16384, 32768
    };
    return (int64_t)qfoc_pi_pow2_table[s];
}

/**
 * @brief Gain term e x g x 2^s x 2 in Q31 (g >= 0, s <= 15), exact in 64 bits.
 */
/*@
  requires gain_range: 0 <= g <= 32767;
  requires shift_range: s <= 15;
  assigns \nothing;
  ensures value: \result == 2 * (e * g) * PiPow2(s);
  ensures range: -70366596694016 <= \result <= 70364449275904;
*/
static int64_t qfoc_pi_gain_term(qfoc_q15_t e, qfoc_q15_t g, uint8_t s)
{
    /* |e g| <= 32768 x 32767 = 1073709056 < 2^31: exact in 32 bits (Q30) */
    const int32_t prod = (int32_t)e * (int32_t)g;
    const int64_t p2 = qfoc_pi_pow2(s);
    /*@ assert prod_range: -1073709056 <= prod <= 1073676289; */
    /*@ assert scaled_hi: prod * p2 <= 1073676289 * 32768; */
    /*@ assert scaled_lo: prod * p2 >= -1073709056 * 32768; */
    /* |prod x 2^s x 2| <= 1073709056 x 32768 x 2 < 2^46 */
    return ((int64_t)prod * p2) * QFOC_PI_Q30_TO_Q31;
}

/**
 * @brief Load the integrator with clamp(v, out_min, out_max) x 65536 and clear
 *        the limit flag (shared by qfoc_pi_init() and qfoc_pi_reset()).
 */
/*@
  requires valid_pi: \valid(pi);
  requires params_valid: PiParamsValid(&pi->params);
  assigns pi->integ, pi->limited;
  ensures valid: PiValid(pi);
  ensures integ: pi->integ == QfocClamp(v, pi->params.out_min, pi->params.out_max) * 65536;
  ensures flag: pi->limited == \false;
*/
static void qfoc_pi_preset(qfoc_pi_t *pi, qfoc_q15_t v)
{
    int32_t c = (int32_t)v;
    if (c > (int32_t)pi->params.out_max) {
        c = (int32_t)pi->params.out_max;
    } else if (c < (int32_t)pi->params.out_min) {
        c = (int32_t)pi->params.out_min;
    } else {
        /* value inside the limits */
    }
    /* |c| <= 32767: c x 65536 fits 32 bits (Q15 -> Q31) */
    pi->integ = c * (int32_t)65536;
    pi->limited = false;
}

bool qfoc_pi_params_is_valid(const qfoc_pi_params_t *p)
{
    bool ok = true;
    if ((p->kp < 0) || (p->ki < 0)) {
        ok = false;
    } else if ((p->kp_shift > QFOC_PI_SHIFT_MAX) || (p->ki_shift > QFOC_PI_SHIFT_MAX)) {
        ok = false;
    } else if ((p->out_min < QFOC_Q15_MIN) || (p->out_min > p->out_max)) {
        ok = false;
    } else {
        /* out_max <= 32767 holds for every int16_t */
    }
    return ok;
}

bool qfoc_pi_is_valid(const qfoc_pi_t *pi)
{
    bool ok = qfoc_pi_params_is_valid(&pi->params);
    if (ok) {
        /* |limit| <= 32767, so limit x 65536 <= 2147418112 fits 32 bits */
        const int32_t lo = (int32_t)pi->params.out_min * (int32_t)65536;
        const int32_t hi = (int32_t)pi->params.out_max * (int32_t)65536;
        if ((pi->integ < lo) || (pi->integ > hi)) {
            ok = false;
        } else {
            /* integrator inside the limits */
        }
    } else {
        /* invalid parameters */
    }
    return ok;
}

int32_t qfoc_pi_init(qfoc_pi_t *pi, const qfoc_pi_params_t *p)
{
    int32_t status;
    if (qfoc_pi_params_is_valid(p)) {
        pi->params.kp = p->kp;
        pi->params.kp_shift = p->kp_shift;
        pi->params.ki = p->ki;
        pi->params.ki_shift = p->ki_shift;
        pi->params.out_min = p->out_min;
        pi->params.out_max = p->out_max;
        status = QFOC_PI_OK;
    } else {
        pi->params.kp = 0;
        pi->params.kp_shift = 0u;
        pi->params.ki = 0;
        pi->params.ki_shift = 0u;
        pi->params.out_min = 0;
        pi->params.out_max = 0;
        status = QFOC_PI_ERR_PARAM;
    }
    /* integrator at the point of [out_min, out_max] nearest to 0 */
    qfoc_pi_preset(pi, 0);
    return status;
}

void qfoc_pi_reset(qfoc_pi_t *pi, qfoc_q15_t preset)
{
    qfoc_pi_preset(pi, preset);
}

qfoc_q15_t qfoc_pi_step(qfoc_pi_t *pi, qfoc_q15_t error)
{
    /* limits in Q31 (x 65536): within [-2147418112, 2147418112] */
    const int64_t lo = (int64_t)pi->params.out_min * QFOC_PI_Q15_TO_Q31;
    const int64_t hi = (int64_t)pi->params.out_max * QFOC_PI_Q15_TO_Q31;
    /* P = e kp 2^kp_shift, Q31, |P| < 2^46 */
    const int64_t prop = qfoc_pi_gain_term(error, pi->params.kp, pi->params.kp_shift);
    /* I(k-1) + e ki 2^ki_shift, Q31, |.| < 2^47 */
    int64_t integ = (int64_t)pi->integ
                    + qfoc_pi_gain_term(error, pi->params.ki, pi->params.ki_shift);
    int64_t sum;
    bool limited;

    /* anti-windup: the integrator never leaves the output limits */
    if (integ > hi) {
        integ = hi;
    } else if (integ < lo) {
        integ = lo;
    } else {
        /* integrator inside the limits */
    }

    /* u = P + I(k), Q31, |u| < 2^47, then clamped to the limits */
    sum = prop + integ;
    if (sum > hi) {
        sum = hi;
        limited = true;
    } else if (sum < lo) {
        sum = lo;
        limited = true;
    } else {
        limited = false;
    }

    pi->integ = (qfoc_q31_t)integ;
    pi->limited = limited;
    /* Q31 -> Q15, rounded to nearest; the limits are multiples of 65536, so the
       rounded value stays inside them */
    return qfoc_q15_from_q31((qfoc_q31_t)sum);
}
