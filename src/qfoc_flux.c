/**
 * @file qfoc_flux.c
 * @brief Rotor (active) flux observer, specs/equations.md E2-13 .. E2-26
 *        (see include/qfoc/flux.h).
 *
 * Requirements: REQ-FLUX-001 .. REQ-FLUX-008 (specs/requirements/flux.md).
 */
#include "qfoc/flux.h"
#include "qfoc/q15.h"
#include "qfoc/trig.h"

/** Q15 -> Q30 factor for the voltage: u (1.15) x 32768 = Q30. */
#define QFOC_FLUX_Q15_ONE ((int32_t)32768)
/** Constant part of the step divisor: Q30 x Q15 = Q45 -> Q27 is / 2^18 = 262144. */
#define QFOC_FLUX_STEP_DIV ((int64_t)262144)
/** Half of QFOC_FLUX_STEP_DIV: 2^17 = 131072 (times 2^gain_shift: the rounding offset). */
#define QFOC_FLUX_STEP_HALF ((int64_t)131072)
/** Unsigned 4096 (floor division of the offset state by 2^12). */
#define QFOC_FLUX_Q12_ONE_U ((uint32_t)4096u)
/** Unsigned 2048, the round-to-nearest offset of the leak term. */
#define QFOC_FLUX_Q12_HALF_U ((uint32_t)2048u)
/** 32-bit 2048, the round-to-nearest offset of the output. */
#define QFOC_FLUX_Q12_HALF32 ((int32_t)2048)
/** Offset that makes a symmetric Q31 state non-negative: 2^31. */
#define QFOC_FLUX_Q31_OFFSET ((int64_t)2147483648)
/** 2^31 / 4096 = 2^19: the offset of floor(psi / 4096) formed on psi + 2^31. */
#define QFOC_FLUX_PH_OFFSET ((int32_t)524288)
/** Largest output magnitude before the rounding: 32767 x 4096 + 2047 (rounds to 32767). */
#define QFOC_FLUX_OUT_LIM ((int32_t)134215679)
/** Angle counts per turn: 65536 (the lead is negated modulo 2^16 for w < 0). */
#define QFOC_FLUX_TURN ((uint32_t)65536u)

/*
 * Bounds used in the proofs (not in the code):
 *   |x30|  <= 32767 x 32768 + 32767 x 32767 = 2147385345
 *   psi = -4096 phn + pl, phn in [-524287, 524288], pl in [0, 4095]
 *   leak = kg (-phn) + lr, lr in [0, 32760]
 *   |(x30 - lr) gain| <= 2147418105 x 32767, |(kg gain) phn| <= 1073676289 x 524288
 *   |(x30 - leak) gain| <= 633280043253767 < 2^50
 *   (|.| + 2^(17+15)) / 2^18 <= 2415788033 < 2^32
 */

/**
 * @brief 2^s for a gain shift s in 0..15 (table look-up, no shift operator).
 */
/*@
  requires shift_range: s <= 15;
  assigns \nothing;
  ensures value: \result == FluxPow2(s);
  ensures range: 1 <= \result <= 32768;
*/
static uint32_t qfoc_flux_pow2(uint8_t s)
{
    /* 2^s for s = 0..15 (the gain shifts); exact integers 1 .. 32768 */
    static const uint32_t qfoc_flux_pow2_table[16] = {
        1u, 2u, 4u, 8u, 16u, 32u, 64u, 128u,
        256u, 512u, 1024u, 2048u, 4096u, 8192u, 16384u, 32768u
    };
    /* s % 16: the contract's s <= 15 leaves it unchanged; a shift corrupted in RAM (a
       random hardware fault the RAM check, REQ-DRV-019, reports within 4 ms) still
       reads inside the table */
    return qfoc_flux_pow2_table[s % 16u];
}

/**
 * @brief Product of a non-negative Q15 coefficient and a symmetric Q15 value,
 *        exact in 32 bits (|a x| <= 32767^2 = 1073676289 < 2^30).
 */
/*@
  requires a_range: 0 <= a <= 32767;
  requires x_range: -32767 <= x <= 32767;
  assigns \nothing;
  ensures value: \result == a * x;
  ensures range: -1073676289 <= \result <= 1073676289;
  ensures sign: x >= 0 ==> \result >= 0;
*/
static int32_t qfoc_flux_mul15(int32_t a, int32_t x)
{
    /*@ assert hi: x >= 0 ==> 0 <= a * x <= 32767 * x; */
    /*@ assert lo: x < 0 ==> 32767 * x <= a * x <= 0; */
    return a * x;
}

/**
 * @brief Product of a non-negative Q15 coefficient and a 12-bit fraction
 *        0 <= x < 4096, exact in 32 bits (<= 32767 x 4095 < 2^27).
 */
/*@
  requires a_range: 0 <= a <= 32767;
  requires x_range: x <= 4095;
  assigns \nothing;
  ensures value: \result == a * x;
  ensures range: 0 <= \result <= 134180865;
*/
static inline uint32_t qfoc_flux_mul12(int32_t a, uint32_t x)
{
    /*@ assert hi: 0 <= a * x <= 32767 * x; */
    return (uint32_t)a * x;
}

/**
 * @brief (x30 - leak) x gain, exact in 64 bits (|.| <= 2147418105 x 32767).
 */
/*@
  requires x_range: -2147418105 <= x <= 2147385345;
  requires g_range: 0 <= g <= 32767;
  assigns \nothing;
  ensures value: \result == x * g;
  ensures range: -70364449046535 <= \result <= 70363375599615;
*/
static inline int64_t qfoc_flux_mul_xg(int32_t x, int32_t g)
{
    /*@ assert hi: x >= 0 ==> 0 <= x * g <= x * 32767; */
    /*@ assert lo: x < 0 ==> x * 32767 <= x * g <= 0; */
    return (int64_t)x * (int64_t)g;
}

/**
 * @brief (kg gain) x (-floor(psi / 4096)), exact in 64 bits
 *        (|.| <= 1073676289 x 524288).
 */
/*@
  requires k_range: 0 <= k <= 1073676289;
  requires p_range: -524287 <= p <= 524288;
  assigns \nothing;
  ensures value: \result == k * p;
  ensures range: -562914520530943 <= \result <= 562915594207232;
*/
static inline int64_t qfoc_flux_mul_kp(int32_t k, int32_t p)
{
    /*@ assert hi: p >= 0 ==> 0 <= k * p <= 1073676289 * p; */
    /*@ assert lo: p < 0 ==> 1073676289 * p <= k * p <= 0; */
    return (int64_t)k * (int64_t)p;
}

/**
 * @brief High-pass drive of one axis: (x30 - RoundDiv(kg psi, 4096)) x gain, the
 *        numerator of the integration step, without a 64-bit rounding division.
 *
 * The state is split as psi = 4096 ph + pl with 0 <= pl < 4096 (floor division,
 * formed on psi + 2^31 in unsigned arithmetic: no shift or division of a negative
 * value).  Then kg psi = 4096 kg ph + kg pl and, as 4096 kg ph is a multiple of
 * 4096, RoundDiv(kg psi, 4096) = kg ph + floor((kg pl + 2048 - n) / 4096) with
 * n = 1 for psi < 0 (ties away from zero) and 0 otherwise; kg pl < 2^27 is
 * rounded in 32 bits.  The product is one 32 x 32 multiply plus one
 * multiply-accumulate: (x30 - lr) gain + (kg gain) (-ph).
 */
/*@
  requires psi_range: QfocQ31Sym(psi);
  requires x30_range: -2147385345 <= x30 <= 2147385345;
  requires kg_range: 0 <= kg <= 32767;
  requires gain_range: 0 <= gain <= 32767;
  requires kgg_def: kgg == kg * gain;
  requires kgg_range: 0 <= kgg <= 1073676289;
  assigns \nothing;
  ensures value: \result == (x30 - FluxLeak30(psi, kg)) * gain;
  ensures range: -633280043253767 <= \result <= 633280043253767;
*/
static inline int64_t qfoc_flux_drive(int32_t psi, int32_t x30, int32_t kg, int32_t gain,
                                      int32_t kgg)
{
    /* psi + 2^31 in [1, 2^32 - 1]: phn = -floor(psi / 4096), pl = psi + 4096 phn */
    const int64_t ps = (int64_t)psi + QFOC_FLUX_Q31_OFFSET;
    const uint32_t pb = (uint32_t)ps;
    const uint32_t phu = pb / QFOC_FLUX_Q12_ONE_U;
    const int32_t phn = QFOC_FLUX_PH_OFFSET - (int32_t)phu;
    const uint32_t pl = pb % QFOC_FLUX_Q12_ONE_U;
    const uint32_t n = (psi < 0) ? (uint32_t)1u : (uint32_t)0u;
    /* floor((kg pl + 2048 - n) / 4096): kg pl <= 32767 x 4095 < 2^27, lr <= 32760 */
    const uint32_t lr = (qfoc_flux_mul12(kg, pl) + (QFOC_FLUX_Q12_HALF_U - n))
                        / QFOC_FLUX_Q12_ONE_U;

    /*@ assert pb_def: pb == psi + 2147483648; */
    /*@ assert split: psi == -4096 * phn + pl && 0 <= pl < 4096; */
    /*@ assert ph_range: -524287 <= phn <= 524288; */
    /*@ assert prod_split: kg * psi == 4096 * (kg * (-phn)) + kg * pl; */
    /*@ assert kgph_sign: (psi >= 0 ==> kg * (-phn) >= 0) && (psi < 0 ==> kg * (-phn) <= 0); */
    /*@ assert leak_split: FluxLeak30(psi, kg) == kg * (-phn) + lr; */
    /*@ assert xl_range: -2147418105 <= x30 - lr <= 2147385345; */
    /* (x30 - lr) x gain + (kg gain) x phn:
       |.| <= 2147418105 x 32767 + 1073676289 x 524288 = 633280043253767 < 2^50 */
    const int32_t xl = x30 - (int32_t)lr;
    const int64_t pa = qfoc_flux_mul_xg(xl, gain);
    const int64_t pb2 = qfoc_flux_mul_kp(kgg, phn);
    /*@ assert sum_value: pa + pb2 == (x30 - FluxLeak30(psi, kg)) * gain; */
    return pa + pb2;
}

/**
 * @brief Integration step: x / 2^(18 + s), rounded to nearest (ties away from
 *        zero), without a 64-bit division by a variable.
 *
 * The magnitude plus the offset 2^(17 + s) is divided by the constant 2^18 in
 * 64 bits (quotient < 2^32) and then by 2^s in 32 bits.  The two floor
 * divisions equal one floor division by 2^(18 + s); the proofs use the two-step
 * form (FluxScaleDiv) and its rounding error |2^(18+s) q - x| <= 2^(17+s)
 * (lemmas FluxDivNestedRem, FluxScaleDivErr).
 */
/*@
  requires x_range: -633280043253767 <= x <= 633280043253767;
  requires shift_range: s <= 15;
  assigns \nothing;
  ensures value: \result == FluxScaleDiv(x, s);
  ensures range: -2415788033 <= \result <= 2415788033;
*/
static inline int64_t qfoc_flux_scale(int64_t x, uint8_t s)
{
    const uint32_t pw2 = qfoc_flux_pow2(s);
    /* rounding offset 2^(17 + s) = FluxDiv(s) / 2 */
    const int64_t half = (int64_t)pw2 * QFOC_FLUX_STEP_HALF;
    int64_t a;
    int64_t t;
    uint32_t q;
    int64_t r;

    if (x >= 0) {
        a = x + half;
    } else {
        a = half - x;
    }
    /*@ assert a_range: 0 <= a <= 633284338221063; */
    /* floor(a / 2^18) < 2^32 */
    t = a / QFOC_FLUX_STEP_DIV;
    /*@ assert t_range: 0 <= t <= 2415788033; */
    /* floor(t / 2^s) = floor(a / 2^(18 + s)), unsigned 32-bit division */
    q = (uint32_t)t / pw2;
    /*@ assert q_nested: q == (a / 262144) / FluxPow2(s); */
    if (x >= 0) {
        r = (int64_t)q;
    } else {
        r = -(int64_t)q;
    }
    return r;
}

/**
 * @brief One axis of the observer: the new Q27 state (see qfoc_flux_step()),
 *        from the current already saturated by the caller (is = QfocSat15(i),
 *        which leaves FluxSum unchanged).
 */
/*@
  requires valid_p: \valid_read(p);
  requires params_valid: FluxParamsValid(p);
  requires kgg_def: kgg == p->kg * p->gain;
  requires kgg_range: 0 <= kgg <= 1073676289;
  requires psi_range: QfocQ31Sym(psi);
  requires is_range: QfocQ15Sym(is);
  requires ip_range: QfocQ15Sym(ip);
  assigns \nothing;
  ensures value: \result == QfocSat31(FluxSum(p, psi, u, is, ip));
  ensures range: QfocQ31Sym(\result);
*/
static inline int32_t qfoc_flux_axis(const qfoc_flux_params_t *p, int32_t kgg, int32_t psi,
                                     qfoc_q15_t u, int32_t is, int32_t ip)
{
    const int32_t us = (int32_t)qfoc_q15_sat((int32_t)u);
    int32_t x30;
    int64_t inc;
    int32_t ldi;
    int64_t v;
    int32_t r;

    /*@ assert us_def: us == QfocSat15(u); */
    /* u - R i: u (1.15) x 32768 and r (1.15) x i (1.15) are Q30,
       |x30| <= 32767 x 32768 + 32767^2 = 2147385345 < 2^31 */
    x30 = (us * QFOC_FLUX_Q15_ONE) - qfoc_flux_mul15((int32_t)p->r, is);
    /*@ assert x30_def: x30 == FluxX30(u, is, p->r); */
    /* g (u - R i - kg psi): Q30 x gain -> Q27, rounded */
    inc = qfoc_flux_scale(qfoc_flux_drive(psi, x30, (int32_t)p->kg, (int32_t)p->gain, kgg),
                          p->gain_shift);
    /*@ assert inc_def: inc == FluxInc(psi, x30, p->gain, p->gain_shift, p->kg); */
    /* L (i - i_prev): l (Q12) x (i - i_prev) (Q15) = Q27, exact,
       |.| <= 32767 x 65534 = 2147352578 < 2^31 */
    ldi = qfoc_flux_mul15((int32_t)p->l, is) - qfoc_flux_mul15((int32_t)p->l, ip);
    /*@ assert ldi_def: ldi == p->l * FluxDi(is, ip); */
    /*@ assert sum_def: (psi + inc) - ldi == FluxSum(p, psi, u, is, ip); */
    /* psi + inc - ldi, |.| < 2^33, saturated to the symmetric Q31 range */
    v = ((int64_t)psi + inc) - (int64_t)ldi;
    if (v > (int64_t)QFOC_Q31_MAX) {
        r = QFOC_Q31_MAX;
    } else if (v < (int64_t)QFOC_Q31_MIN) {
        r = QFOC_Q31_MIN;
    } else {
        r = (int32_t)v;
    }
    return r;
}

/**
 * @brief Output of one axis: the Q27 state rounded to Q15, saturated, in 32 bits.
 *
 * A state beyond +-(32767 x 4096 + 2047) rounds to +-32767 or beyond: it is
 * limited to that value first, so that the rounding offset cannot overflow and
 * the quotient needs no saturation.
 */
/*@
  assigns \nothing;
  ensures value: \result == FluxOut(psi);
  ensures range: QfocQ15Sym(\result);
*/
static inline qfoc_q15_t qfoc_flux_out(int32_t psi)
{
    int32_t y = psi;
    int32_t c;
    if (y > QFOC_FLUX_OUT_LIM) {
        y = QFOC_FLUX_OUT_LIM;
    }
    if (y < -QFOC_FLUX_OUT_LIM) {
        y = -QFOC_FLUX_OUT_LIM;
    }
    if (y < 0) {
        c = -QFOC_FLUX_Q12_HALF32;
    } else {
        c = QFOC_FLUX_Q12_HALF32;
    }
    /*@ assert y_range: -134215679 <= y <= 134215679; */
    /* Q27 -> Q15: (y +- 2048) / 4096, truncated = rounded to nearest */
    return (qfoc_q15_t)((y + c) / QFOC_FLUX_Q27_PER_Q15);
}

bool qfoc_flux_params_is_valid(const qfoc_flux_params_t *p)
{
    bool ok = false;
    if ((p->gain >= 0) && (p->gain_shift <= QFOC_FLUX_SHIFT_MAX) && (p->r >= 0)
        && (p->l >= 0) && (p->kg >= 0)) {
        ok = true;
    } else {
        /* a negative coefficient or a gain shift above 15 */
    }
    return ok;
}

bool qfoc_flux_is_valid(const qfoc_flux_t *o)
{
    bool ok = false;
    if (qfoc_flux_params_is_valid(&o->params)
        && (o->psi_alpha >= QFOC_Q31_MIN) && (o->psi_beta >= QFOC_Q31_MIN)
        && (o->i_prev.alpha >= QFOC_Q15_MIN) && (o->i_prev.beta >= QFOC_Q15_MIN)) {
        ok = true;
    } else {
        /* invalid parameters, a state of -2^31 or a current of -32768 */
    }
    return ok;
}

int32_t qfoc_flux_init(qfoc_flux_t *o, const qfoc_flux_params_t *p)
{
    int32_t status;
    if (qfoc_flux_params_is_valid(p)) {
        o->params.gain = p->gain;
        o->params.gain_shift = p->gain_shift;
        o->params.r = p->r;
        o->params.l = p->l;
        o->params.kg = p->kg;
        status = QFOC_FLUX_OK;
    } else {
        /* safe state: no integration, no inductance term: the output stays 0 */
        o->params.gain = 0;
        o->params.gain_shift = 0u;
        o->params.r = 0;
        o->params.l = 0;
        o->params.kg = 0;
        status = QFOC_FLUX_ERR_PARAM;
    }
    o->psi_alpha = 0;
    o->psi_beta = 0;
    o->i_prev.alpha = 0;
    o->i_prev.beta = 0;
    return status;
}

void qfoc_flux_reset(qfoc_flux_t *o, const qfoc_ab_t *psi0, const qfoc_ab_t *i0)
{
    /* Q15 -> Q27: x 4096, |.| <= 134213632 after the saturation */
    o->psi_alpha = (int32_t)qfoc_q15_sat((int32_t)psi0->alpha) * QFOC_FLUX_Q27_PER_Q15;
    o->psi_beta = (int32_t)qfoc_q15_sat((int32_t)psi0->beta) * QFOC_FLUX_Q27_PER_Q15;
    o->i_prev.alpha = qfoc_q15_sat((int32_t)i0->alpha);
    o->i_prev.beta = qfoc_q15_sat((int32_t)i0->beta);
}

void qfoc_flux_step(qfoc_flux_t *o, const qfoc_ab_t *u, const qfoc_ab_t *i,
                    qfoc_ab_t *psi_r)
{
    /* kg gain, shared by the two axes: <= 32767^2 < 2^30 */
    const int32_t kgg = qfoc_flux_mul15((int32_t)o->params.kg, (int32_t)o->params.gain);
    const int32_t isa = (int32_t)qfoc_q15_sat((int32_t)i->alpha);
    const int32_t isb = (int32_t)qfoc_q15_sat((int32_t)i->beta);
    int32_t na;
    int32_t nb;
    /*@ assert sum_alpha: FluxSum(&o->params, o->psi_alpha, u->alpha, isa, o->i_prev.alpha)
          == FluxSum(&o->params, o->psi_alpha, u->alpha, i->alpha, o->i_prev.alpha); */
    /*@ assert sum_beta: FluxSum(&o->params, o->psi_beta, u->beta, isb, o->i_prev.beta)
          == FluxSum(&o->params, o->psi_beta, u->beta, i->beta, o->i_prev.beta); */
    /* each axis is finished (state, current, output) before the next one starts */
    na = qfoc_flux_axis(&o->params, kgg, o->psi_alpha, u->alpha, isa,
                        (int32_t)o->i_prev.alpha);
    o->psi_alpha = na;
    o->i_prev.alpha = (qfoc_q15_t)isa;
    psi_r->alpha = qfoc_flux_out(na);
    nb = qfoc_flux_axis(&o->params, kgg, o->psi_beta, u->beta, isb,
                        (int32_t)o->i_prev.beta);
    o->psi_beta = nb;
    o->i_prev.beta = (qfoc_q15_t)isb;
    psi_r->beta = qfoc_flux_out(nb);
}

qfoc_angle_t qfoc_flux_lead(const qfoc_flux_t *o, qfoc_q15_t w)
{
    /* |w| saturated: |-32768| -> 32767 */
    const qfoc_q15_t wa = qfoc_q15_abs(w);
    /* lead atan(kg / |w|) in counts, first quadrant (kg >= 0, |w| >= 0) */
    const qfoc_angle_t a = qfoc_atan2(o->params.kg, wa);
    uint32_t r = (uint32_t)a;
    if ((w < 0) && (r > 0u)) {
        /* negative lead for reverse rotation: 65536 - a, in [1, 65535] for
           a in [1, 65535] (-0 is 0: kept by the condition) */
        r = QFOC_FLUX_TURN - r;
    } else {
        /* forward rotation, standstill or no lead: the lead as it is */
    }
    return (qfoc_angle_t)r;
}
