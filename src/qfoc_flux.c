/**
 * @file qfoc_flux.c
 * @brief Rotor (active) flux observer, document 2-13 .. 2-26
 *        (see include/qfoc/flux.h).
 *
 * Requirements: REQ-FLUX-001 .. REQ-FLUX-008 (specs/requirements/flux.md).
 */
#include "qfoc/flux.h"
#include "qfoc/q15.h"
#include "qfoc/trig.h"

/** Q15 -> Q30 factor for the voltage: u (1.15) x 32768 = Q30. */
#define QFOC_FLUX_Q15_ONE ((int64_t)32768)
/** Q27 per Q15 LSB and Q42 -> Q30 divisor: 2^12 = 4096. */
#define QFOC_FLUX_Q12_ONE ((int64_t)4096)
/** Half of QFOC_FLUX_Q12_ONE, the round-to-nearest offset: 2048. */
#define QFOC_FLUX_Q12_HALF ((int64_t)2048)
/** Constant part of the step divisor: Q30 x Q15 = Q45 -> Q27 is / 2^18 = 262144. */
#define QFOC_FLUX_STEP_DIV ((int64_t)262144)
/** Half of QFOC_FLUX_STEP_DIV: 2^17 = 131072 (times 2^gain_shift: the rounding offset). */
#define QFOC_FLUX_STEP_HALF ((int64_t)131072)
/** Angle counts per turn: 65536 (the lead is negated modulo 2^16 for w < 0). */
#define QFOC_FLUX_TURN ((uint32_t)65536u)

/*
 * Bounds used in the proofs (not in the code):
 *   |x30|  <= 32767 x 32768 + 32767 x 32767 = 2147385345
 *   |leak| <= RoundDiv(32767 x (2^31 - 1), 4096) = 17179344888
 *   |x30 - leak| <= 19326730233, x gain (<= 32767) <= 633278969544711 < 2^50
 *   (|.| + 2^(17+15)) / 2^18 <= 2415783937 < 2^32
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
    return qfoc_flux_pow2_table[s];
}

/**
 * @brief x / 4096 rounded to nearest, ties away from zero (no right shift of a
 *        negative value), for |x| < 2^62.
 */
/*@
  requires x_range: -4611686018427387904 < x < 4611686018427387904;
  assigns \nothing;
  ensures value: \result == QfocRoundDiv(x, 4096);
*/
static int64_t qfoc_flux_round_q12(int64_t x)
{
    int64_t r;
    if (x >= 0) {
        r = (x + QFOC_FLUX_Q12_HALF) / QFOC_FLUX_Q12_ONE;
    } else {
        r = -((QFOC_FLUX_Q12_HALF - x) / QFOC_FLUX_Q12_ONE);
    }
    return r;
}

/**
 * @brief Integration step: d x gain / 2^(18 + s), rounded to nearest (ties away
 *        from zero), without a 64-bit division by a variable.
 *
 * The magnitude plus the offset 2^(17 + s) is divided by the constant 2^18 in
 * 64 bits (quotient < 2^32) and then by 2^s in 32 bits.  The two floor
 * divisions equal one floor division by 2^(18 + s); the proofs use the two-step
 * form (FluxScaleDiv) and its rounding error |2^(18+s) q - x| <= 2^(17+s)
 * (lemmas FluxDivNestedRem, FluxScaleDivErr).
 */
/*@
  requires d_range: -19326730233 <= d <= 19326730233;
  requires gain_range: 0 <= gain;
  requires shift_range: s <= 15;
  assigns \nothing;
  ensures value: \result == FluxScaleDiv(d * gain, s);
  ensures range: -2415783937 <= \result <= 2415783937;
*/
static int64_t qfoc_flux_scale(int64_t d, qfoc_q15_t gain, uint8_t s)
{
    const uint32_t pw2 = qfoc_flux_pow2(s);
    /* rounding offset 2^(17 + s) = FluxDiv(s) / 2 */
    const int64_t half = (int64_t)pw2 * QFOC_FLUX_STEP_HALF;
    int64_t p;
    int64_t a;
    int64_t t;
    uint32_t q;
    int64_t r;

    /*@ assert prod_hi: d >= 0 ==> 0 <= d * gain <= d * 32767; */
    /*@ assert prod_lo: d < 0 ==> d * 32767 <= d * gain <= 0; */
    /* (u - R i - kg psi) Q30 x gain Q15 = Q45, |p| < 2^50 */
    p = d * (int64_t)gain;
    if (p >= 0) {
        a = p + half;
    } else {
        a = half - p;
    }
    /*@ assert a_range: 0 <= a <= 633283264512007; */
    /* floor(a / 2^18) < 2^32 */
    t = a / QFOC_FLUX_STEP_DIV;
    /*@ assert t_range: 0 <= t <= 2415783937; */
    /* floor(t / 2^s) = floor(a / 2^(18 + s)), unsigned 32-bit division */
    q = (uint32_t)t / pw2;
    /*@ assert q_nested: q == (a / 262144) / FluxPow2(s); */
    if (p >= 0) {
        r = (int64_t)q;
    } else {
        r = -(int64_t)q;
    }
    return r;
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
*/
static int32_t qfoc_flux_mul15(int32_t a, int32_t x)
{
    /*@ assert hi: x >= 0 ==> 0 <= a * x <= 32767 * x; */
    /*@ assert lo: x < 0 ==> 32767 * x <= a * x <= 0; */
    return a * x;
}

/**
 * @brief Product of a non-negative Q15 coefficient and a symmetric Q31 value,
 *        exact in 64 bits (|a x| <= 32767 (2^31 - 1) < 2^46).
 */
/*@
  requires a_range: 0 <= a <= 32767;
  requires x_range: QfocQ31Sym(x);
  assigns \nothing;
  ensures value: \result == a * x;
  ensures range: -70366596661249 <= \result <= 70366596661249;
*/
static int64_t qfoc_flux_mul31(int32_t a, int32_t x)
{
    /*@ assert hi: x >= 0 ==> 0 <= a * x <= 32767 * x; */
    /*@ assert lo: x < 0 ==> 32767 * x <= a * x <= 0; */
    return (int64_t)a * (int64_t)x;
}

/**
 * @brief One axis of the observer: the new Q27 state (see qfoc_flux_step()).
 */
/*@
  requires valid_p: \valid_read(p);
  requires params_valid: FluxParamsValid(p);
  requires psi_range: QfocQ31Sym(psi);
  requires ip_range: QfocQ15Sym(ip);
  assigns \nothing;
  ensures value: \result == QfocSat31(FluxSum(p, psi, u, i, ip));
  ensures range: QfocQ31Sym(\result);
*/
static int32_t qfoc_flux_axis(const qfoc_flux_params_t *p, int32_t psi, qfoc_q15_t u,
                              qfoc_q15_t i, qfoc_q15_t ip)
{
    const int32_t us = (int32_t)qfoc_q15_sat((int32_t)u);
    const int32_t is = (int32_t)qfoc_q15_sat((int32_t)i);
    int64_t x30;
    int64_t leak;
    int64_t inc;
    int64_t ldi;

    /*@ assert us_def: us == QfocSat15(u); */
    /*@ assert is_def: is == QfocSat15(i); */
    /* u - R i: u (1.15) x 32768 and r (1.15) x i (1.15) are Q30,
       |x30| <= 32767 x 32768 + 32767^2 = 2147385345 */
    x30 = ((int64_t)us * QFOC_FLUX_Q15_ONE)
          - (int64_t)qfoc_flux_mul15((int32_t)p->r, is);
    /* high-pass term kg psi: kg (1.15) x psi (Q27) = Q42, |.| < 2^46, -> Q30
       rounded, |leak| <= 17179344888 */
    leak = qfoc_flux_round_q12(qfoc_flux_mul31((int32_t)p->kg, psi));
    /*@ assert leak_range: -17179344888 <= leak <= 17179344888; */
    /* g (u - R i - kg psi): Q30 x gain -> Q27, rounded */
    inc = qfoc_flux_scale(x30 - leak, p->gain, p->gain_shift);
    /* L (i - i_prev): l (Q12) x i (Q15) - l x i_prev = Q27, exact,
       |.| <= 2 x 32767^2 = 2147352578 */
    ldi = (int64_t)qfoc_flux_mul15((int32_t)p->l, is)
          - (int64_t)qfoc_flux_mul15((int32_t)p->l, (int32_t)ip);
    /*@ assert x30_def: x30 == FluxX30(u, i, p->r); */
    /*@ assert leak_def: leak == FluxLeak30(psi, p->kg); */
    /*@ assert inc_def: inc == FluxInc(psi, x30, p->gain, p->gain_shift, p->kg); */
    /*@ assert ldi_def: ldi == p->l * FluxDi(i, ip); */
    /*@ assert sum_def: (psi + inc) - ldi == FluxSum(p, psi, u, i, ip); */
    /* psi + inc - ldi, |.| < 2^33, saturated to the symmetric Q31 range */
    return qfoc_q31_sat(((int64_t)psi + inc) - ldi);
}

/**
 * @brief Output of one axis: the Q27 state rounded to Q15, saturated.
 */
/*@
  assigns \nothing;
  ensures value: \result == FluxOut(psi);
  ensures range: QfocQ15Sym(\result);
*/
static qfoc_q15_t qfoc_flux_out(int32_t psi)
{
    /* Q27 -> Q15: / 4096 rounded, |q| <= 524288 */
    const int64_t q = qfoc_flux_round_q12((int64_t)psi);
    /*@ assert q_range: -524288 <= q <= 524288; */
    return qfoc_q15_sat((int32_t)q);
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
    const int32_t na = qfoc_flux_axis(&o->params, o->psi_alpha, u->alpha, i->alpha,
                                      o->i_prev.alpha);
    const int32_t nb = qfoc_flux_axis(&o->params, o->psi_beta, u->beta, i->beta,
                                      o->i_prev.beta);
    o->psi_alpha = na;
    o->psi_beta = nb;
    o->i_prev.alpha = qfoc_q15_sat((int32_t)i->alpha);
    o->i_prev.beta = qfoc_q15_sat((int32_t)i->beta);
    psi_r->alpha = qfoc_flux_out(na);
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
