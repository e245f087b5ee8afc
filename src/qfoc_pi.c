/**
 * @file qfoc_pi.c
 * @brief Discrete PI controller with clamping anti-windup (see include/qfoc/pi.h).
 *
 * Requirements: REQ-PI-001 .. REQ-PI-008 (specs/requirements/pi.md).
 */
#include "qfoc/pi.h"
#include "qfoc/q15.h"

/** Q15 -> Q31 widening factor: 2^16 = 65536. */
#define QFOC_PI_Q15_TO_Q31 ((int32_t)65536)
/** Q31 -> Q15 divisor, 2^16, for the rounding of the output. */
#define QFOC_PI_Q31_ONE_U ((uint32_t)65536u)
/** Rounding bias: 32768 x 65536 (makes every clamped output non-negative) plus
    the round-to-nearest offset 32768: 2147516416. */
#define QFOC_PI_ROUND_BIAS ((int64_t)2147516416)
/** The bias in Q15: 32768. */
#define QFOC_PI_Q15_BIAS ((int32_t)32768)

/**
 * @brief Gain scale 2^(s+1) for a gain shift s in 0..15: the shift and the
 *        Q30 -> Q31 factor 2 in one table look-up (no shift operator).
 */
/*@
  requires shift_range: s <= 15;
  assigns \nothing;
  ensures value: \result == 2 * PiPow2(s);
  ensures range: 2 <= \result <= 65536;
*/
static int32_t qfoc_pi_scale(uint8_t s)
{
    /* 2^(s+1) for s = 0..15; exact integers 2 .. 65536 */
    static const int32_t qfoc_pi_scale_table[16] = {
        2, 4, 8, 16, 32, 64, 128, 256,
        512, 1024, 2048, 4096, 8192, 16384, 32768, 65536
    };
    /* s % 16: the contract's s <= 15 leaves it unchanged; a shift corrupted in RAM (a
       random hardware fault the RAM check, REQ-DRV-019, reports within 4 ms) still
       reads inside the table */
    return qfoc_pi_scale_table[s % 16u];
}

/**
 * @brief x / 65536 rounded to nearest, ties away from zero, for x inside the
 *        symmetric Q15 range widened to Q31 (the clamped PI output).
 *
 * Scaling and overflow: round(x / 65536) = floor((x + 32768 - [x < 0]) / 65536);
 * the floor is taken of the value biased by 32768 x 65536, which lies in
 * [98303, 4294934528] (non-negative, below 2^32), as an unsigned quotient, so no
 * right shift of a negative value is needed; the bias is taken off the quotient.
 */
/*@
  requires x_range: -2147418112 <= x <= 2147418112;
  assigns \nothing;
  ensures value: \result == QfocRoundDiv(x, 65536);
  ensures range: QfocQ15Sym(\result);
*/
static qfoc_q15_t qfoc_pi_round(int32_t x)
{
    /* tie correction: 1 for a negative x, which rounds its ties downwards */
    const int64_t tie = (x < 0) ? (int64_t)1 : (int64_t)0;
    const int64_t biased = ((int64_t)x + QFOC_PI_ROUND_BIAS) - tie;
    /*@ assert biased_range: 98303 <= biased <= 4294934528; */
    const uint32_t ub = (uint32_t)biased;
    const uint32_t uq = ub / QFOC_PI_Q31_ONE_U;
    const int32_t q = (int32_t)uq;
    /*@ assert q_value: q - 32768 == QfocRoundDiv(x, 65536); */
    return (qfoc_q15_t)(q - QFOC_PI_Q15_BIAS);
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

void qfoc_pi_set_limit(qfoc_pi_t *pi, qfoc_q15_t lim)
{
    const int32_t hi = (lim > 0) ? (int32_t)lim : 0;
    const int32_t hi31 = hi * 65536;
    pi->params.out_max = (qfoc_q15_t)hi;
    pi->params.out_min = (qfoc_q15_t)(-hi);
    if (pi->integ > hi31) {
        pi->integ = hi31;
    } else if (pi->integ < -hi31) {
        pi->integ = -hi31;
    } else {
        /* the integrator is inside the new limits */
    }
}

qfoc_q15_t qfoc_pi_step(qfoc_pi_t *pi, qfoc_q15_t error)
{
    const int32_t integ_old = pi->integ;
    const int32_t kp_scale = qfoc_pi_scale(pi->params.kp_shift);
    const int32_t ki_scale = qfoc_pi_scale(pi->params.ki_shift);
    int32_t integ;
    uint32_t room;
    qfoc_q15_t out;
    bool limited;

    if (error >= 0) {
        /* e kp and e ki (2.30): <= 32767 x 32767 < 2^30, exact in 32 bits */
        const int32_t pprod = (int32_t)error * (int32_t)pi->params.kp;
        const int32_t iprod = (int32_t)error * (int32_t)pi->params.ki;
        /* P = e kp 2^kp_shift x 2, Q31, in [0, 2^46): one 32 x 32 -> 64 bit product */
        const int64_t pmag = (int64_t)pprod * (int64_t)kp_scale;
        /* increment e ki 2^ki_shift x 2, Q31, in [0, 2^46): the same */
        const int64_t imag = (int64_t)iprod * (int64_t)ki_scale;
        /* P >= 0 and the increment >= 0: only the upper limit can be reached.
           room = out_max x 65536 - I, in [0, 2^32) (I inside the limits) */
        const int32_t hi = (int32_t)pi->params.out_max * QFOC_PI_Q15_TO_Q31;
        const int64_t room0 = (int64_t)hi - (int64_t)integ_old;
        /*@ assert pmag_value: pmag == PiProp(error, pi->params.kp, pi->params.kp_shift); */
        /*@ assert imag_value: imag == PiIncr(error, pi->params.ki, pi->params.ki_shift); */
        /*@ assert room0_range: 0 <= room0 <= 4294836224; */
        room = (uint32_t)room0;
        /* anti-windup: I(k) = min(I(k-1) + increment, out_max x 65536) */
        if (imag > (int64_t)room) {
            integ = hi;
            room = 0u;
        } else {
            const int64_t room1 = (int64_t)room - imag;
            integ = (int32_t)((int64_t)integ_old + imag);
            room = (uint32_t)room1;
        }
        /*@ assert room_left: integ + room == hi; */
        /*@ assert integ_value: integ == PiNextInteg(pi, error); */
        /* u = P + I(k) clamped; a clamped output is the limit itself (no rounding) */
        if (pmag > (int64_t)room) {
            out = pi->params.out_max;
            limited = true;
        } else {
            /* P + I(k) in [I(k), out_max x 65536]: fits 32 bits; Q31 -> Q15 rounded */
            const int64_t sum = (int64_t)integ + pmag;
            /*@ assert sum_value: sum == PiNextSum(pi, error); */
            /*@ assert sum_range: sum <= 2147483647; */
            out = qfoc_pi_round((int32_t)sum);
            limited = false;
        }
    } else {
        /* |e| kp and |e| ki (2.30): <= 32768 x 32767 < 2^30, exact in 32 bits */
        const int32_t mag = -(int32_t)error;
        const int32_t pprod = mag * (int32_t)pi->params.kp;
        const int32_t iprod = mag * (int32_t)pi->params.ki;
        /* |P| = |e| kp 2^kp_shift x 2, Q31, < 2^46: one 32 x 32 -> 64 bit product */
        const int64_t pmag = (int64_t)pprod * (int64_t)kp_scale;
        /* |increment| = |e| ki 2^ki_shift x 2, Q31, < 2^46: the same */
        const int64_t imag = (int64_t)iprod * (int64_t)ki_scale;
        /* P <= 0 and the increment <= 0: only the lower limit can be reached.
           room = I - out_min x 65536, in [0, 2^32) */
        const int32_t lo = (int32_t)pi->params.out_min * QFOC_PI_Q15_TO_Q31;
        const int64_t room0 = (int64_t)integ_old - (int64_t)lo;
        /*@ assert pmag_value: pmag == -PiProp(error, pi->params.kp, pi->params.kp_shift); */
        /*@ assert imag_value: imag == -PiIncr(error, pi->params.ki, pi->params.ki_shift); */
        /*@ assert room0_range: 0 <= room0 <= 4294836224; */
        room = (uint32_t)room0;
        /* anti-windup: I(k) = max(I(k-1) + increment, out_min x 65536) */
        if (imag > (int64_t)room) {
            integ = lo;
            room = 0u;
        } else {
            const int64_t room1 = (int64_t)room - imag;
            integ = (int32_t)((int64_t)integ_old - imag);
            room = (uint32_t)room1;
        }
        /*@ assert room_left: integ - room == lo; */
        /*@ assert integ_value: integ == PiNextInteg(pi, error); */
        if (pmag > (int64_t)room) {
            out = pi->params.out_min;
            limited = true;
        } else {
            /* P + I(k) in [out_min x 65536, I(k)]: fits 32 bits; Q31 -> Q15 rounded */
            const int64_t sum = (int64_t)integ - pmag;
            /*@ assert sum_value: sum == PiNextSum(pi, error); */
            /*@ assert sum_range: -2147483648 <= sum; */
            out = qfoc_pi_round((int32_t)sum);
            limited = false;
        }
    }

    pi->integ = integ;
    pi->limited = limited;
    return out;
}
