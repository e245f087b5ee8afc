/*
 * proofs/cbmc/pll_common.h -- instance builder and post-conditions shared by the
 * four PLL harnesses (pll_step, pll_step_exact, pll_step_emf, pll_step_emf_exact).
 *
 * build():       any instance that qfoc_pll_is_valid() accepts (nondet gains,
 *                limits, integrator, low-pass coefficient and state, theta_acc,
 *                clamp, mag_min, k_theta).
 * check_full():  the post-conditions of one step for any input (REQ-PLL-002 ..
 *                REQ-PLL-007, REQ-PLL-010).
 * check_exact(): the magnitude and the coasting decision for small loop vectors.
 * qfoc_sincos():  a stub returning any pair its contract allows (see below);
 *                qfoc_isqrt32() is replaced by its contract (isqrt_stub.h).
 */
#ifndef QFOC_PLL_COMMON_H
#define QFOC_PLL_COMMON_H

#include "qfoc/pll.h"
#include "harness_util.h"
#include "isqrt_stub.h"

/* contract of qfoc_sincos: both outputs in [-32767, 32767] (weakened: any such pair).
   The PLL's properties checked here do not depend on the values of the pair, only on
   their range; qfoc_sincos has its own harness (trig_sincos), and its exact values and
   the PLL's use of them are proved for every input by Frama-C WP (ensures sc). */
void qfoc_sincos(qfoc_angle_t theta, qfoc_sincos_t *out)
{
    qfoc_sincos_t r;

    (void)theta;
    __CPROVER_assert(__CPROVER_w_ok(out, sizeof(*out)), "sincos pointer valid");
    r.sine = nondet_int16();
    r.cosine = nondet_int16();
    __CPROVER_assume((r.sine >= -32767) && (r.sine <= 32767) &&
                     (r.cosine >= -32767) && (r.cosine <= 32767));
    *out = r;
}

/* Any instance that qfoc_pll_is_valid() accepts. */
static void build(qfoc_pll_t *pll)
{
    pll->pi.params.kp = nondet_int16();
    pll->pi.params.kp_shift = nondet_uint8();
    pll->pi.params.ki = nondet_int16();
    pll->pi.params.ki_shift = nondet_uint8();
    pll->pi.params.out_min = nondet_int16();
    pll->pi.params.out_max = nondet_int16();
    pll->pi.integ = nondet_int32();
    pll->pi.limited = nondet_bool();
    pll->speed_lpf.alpha = nondet_int16();
    pll->speed_lpf.state = nondet_int32();
    pll->theta_acc = nondet_uint32();
    pll->speed = nondet_int16();
    pll->err_clamp = nondet_int16();
    pll->mag_min = nondet_int16();
    pll->k_theta = nondet_uint16();
    __CPROVER_assume(qfoc_pll_is_valid(pll));
}

/* Post-conditions of one step for any input. */
static void check_full(const qfoc_pll_t *old, const qfoc_pll_t *pll, const qfoc_pll_out_t *out)
{
    const int32_t mm = (int32_t)old->mag_min;
    const int32_t mag = (int32_t)out->mag;
    bool k_ref = true;
    int64_t inc = 0;

    __CPROVER_assert(qfoc_pll_is_valid(pll), "still valid");
    __CPROVER_assert((pll->err_clamp == old->err_clamp) && (pll->mag_min == old->mag_min)
                     && (pll->k_theta == old->k_theta)
                     && (pll->speed_lpf.alpha == old->speed_lpf.alpha)
                     && (pll->pi.params.out_min == old->pi.params.out_min)
                     && (pll->pi.params.out_max == old->pi.params.out_max),
                     "configuration unchanged");
    __CPROVER_assert(out->theta == angle_of(old->theta_acc), "theta: old accumulator rounded");
    __CPROVER_assert(out->theta_next == angle_of(pll->theta_acc),
                     "theta_next: new accumulator rounded");
    /* 2-28 modulo 2^32, for k_theta = 1, the reference 8192 and the largest
       32767 (constant multipliers; a symbolic multiplier miter against the
       code's product does not finish in minutes; all k_theta: WP, ensures
       acc / acc_mod) */
    if (old->k_theta == 1u) {
        inc = (int64_t)out->speed;
    } else if (old->k_theta == 8192u) {
        inc = (int64_t)out->speed * 8192;
    } else if (old->k_theta == 32767u) {
        inc = (int64_t)out->speed * 32767;
    } else {
        k_ref = false;
    }
    if (k_ref) {
        const int64_t d = (int64_t)pll->theta_acc - ((int64_t)old->theta_acc + inc);
        __CPROVER_assert((d == 0) || (d == 4294967296LL) || (d == -4294967296LL),
                         "accumulator: old + speed x k_theta modulo 2^32");
    }
    __CPROVER_assert((out->error >= -old->err_clamp) && (out->error <= old->err_clamp),
                     "error within the clamp");
    __CPROVER_assert((out->speed >= old->pi.params.out_min)
                     && (out->speed <= old->pi.params.out_max), "speed within the limits");
    __CPROVER_assert(pll->speed == out->speed, "speed stored");
    __CPROVER_assert(is_rounded_sat((int64_t)out->speed_f, (int64_t)pll->speed_lpf.state),
                     "speed_f: low-pass state rounded");
    __CPROVER_assert((mag >= 0) && (mag <= 32767), "magnitude range");
    if (mag < mm) {
        __CPROVER_assert(out->error == 0, "coasting: error 0 below mag_min");
        __CPROVER_assert(pll->pi.integ == old->pi.integ, "coasting: integrator held");
    } else {
        __CPROVER_assert(mag >= 1, "tracking: the divisor is at least 1");
    }
}

/* Exact values for small loop vectors (|x|, |y| <= 128): the magnitude is the
   floor square root and the coasting decision is taken on the squares.  (The
   rounded quotient e30 / mag and sc = qfoc_sincos(theta) are not re-checked
   here: a divider-against-multiplier or table-against-table miter does not
   finish within the time budget; both are proved for every input by Frama-C
   WP (ensures error, behaviour track) and tested exactly in tests/test_pll.c.) */
static void check_exact(const qfoc_pll_t *old, const qfoc_pll_out_t *out, int32_t x, int32_t y)
{
    const int32_t mm = (int32_t)old->mag_min;
    const int32_t mag = (int32_t)out->mag;
    const int32_t sq = (x * x) + (y * y);

    __CPROVER_assert(((mag * mag) <= sq) && (sq < ((mag + 1) * (mag + 1))),
                     "magnitude: floor square root");
    __CPROVER_assert((sq < (mm * mm)) == (mag < mm),
                     "coasting decided on the squares: x^2 + y^2 < mag_min^2");
}

#endif /* QFOC_PLL_COMMON_H */
