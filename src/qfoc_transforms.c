/**
 * @file qfoc_transforms.c
 * @brief Clarke, Park, inverse Park and inverse Clarke transforms in Q15.
 *
 * See include/qfoc/transforms.h for the equations, ranges, contracts and the
 * scaling of every step.  Requirements: REQ-TRF-001 .. REQ-TRF-010.
 */
#include "qfoc/transforms.h"
#include "qfoc/q15.h"
#include "qfoc_fast.h"

/** 1/sqrt(3) in Q16: 65536 / sqrt(3) = 37837.23 -> 37837 (error -6.0e-6 relative). */
#define QFOC_INV_SQRT3_Q16 ((int32_t)37837)

/**
 * Largest |i_u + 2 i_v| inside the Clarke bound E2-6 (specs/equations.md):
 * floor(sqrt(3) * 32767) = floor(56754.11) = 56754 (56754^2 <= 3 * 32767^2).
 * 56754 * 37837 = 2147401098 < 2^31 - 1, so the Q31 product cannot overflow.
 */
#define QFOC_CLARKE_SUM_MAX ((int32_t)56754)

/** 1/2 in Q15: 0.5 * 32768 = 16384 (exact). */
#define QFOC_HALF_Q15 ((int32_t)16384)

/** sqrt(3)/2 in Q15: 0.8660254 * 32768 = 28377.92 -> 28378 (error +2.8e-6 relative). */
#define QFOC_SQRT3_2_Q15 ((int32_t)28378)

void qfoc_clarke(qfoc_q15_t iu, qfoc_q15_t iv, qfoc_ab_t *out)
{
    /* (E2-4) numerator, 3.15: |iu + 2 iv| <= 98304 */
    int32_t sum = (int32_t)iu + ((int32_t)iv * 2);
    int32_t beta_q31;

    /* beyond the bound E2-6 the result saturates: clamp the numerator */
    if (sum > QFOC_CLARKE_SUM_MAX) {
        sum = QFOC_CLARKE_SUM_MAX;
    } else if (sum < -QFOC_CLARKE_SUM_MAX) {
        sum = -QFOC_CLARKE_SUM_MAX;
    } else {
        /* inside the bound: exact */
    }
    /* 3.15 x 0.16 = Q31, |beta_q31| <= 2147401098 */
    beta_q31 = sum * QFOC_INV_SQRT3_Q16;

    out->alpha = qfoc_q15_sat((int32_t)iu);           /* (E2-3) */
    out->beta = qfoc_q15_round_q31(beta_q31);         /* (E2-4), rounded (in range) */
}

void qfoc_park_sym(const qfoc_ab_t *in, const qfoc_sincos_t *sc, qfoc_dq_t *out)
{
    /* every factor is in [-32767, 32767] (required): |product| <= 32767^2 */
    const int32_t alpha = (int32_t)in->alpha;
    const int32_t beta = (int32_t)in->beta;
    const int32_t s = (int32_t)sc->sine;
    const int32_t c = (int32_t)sc->cosine;
    int32_t d_q30;
    int32_t q_q30;

    /*@ assert same: alpha == in->alpha && beta == in->beta && s == sc->sine &&
                     c == sc->cosine; */
    /*@ assert prod_ac: -1073676289 <= alpha * c <= 1073676289; */
    /*@ assert prod_bs: -1073676289 <= beta * s <= 1073676289; */
    /*@ assert prod_bc: -1073676289 <= beta * c <= 1073676289; */
    /*@ assert prod_as: -1073676289 <= alpha * s <= 1073676289; */
    /* 2.30 sums, |sum| <= 2 * 32767^2 = 2147352578 < 2^31 */
    d_q30 = (alpha * c) + (beta * s);                 /* (E2-7) */
    q_q30 = (beta * c) - (alpha * s);                 /* (E2-8) */
    /*@ assert d_sum: d_q30 == QfocParkD(in->alpha, in->beta, sc->sine, sc->cosine); */
    /*@ assert q_sum: q_q30 == QfocParkQ(in->alpha, in->beta, sc->sine, sc->cosine); */

    out->d = qfoc_q15_from_q30(d_q30);
    out->q = qfoc_q15_from_q30(q_q30);
}

void qfoc_park(const qfoc_ab_t *in, const qfoc_sincos_t *sc, qfoc_dq_t *out)
{
    /* clamp every factor to the symmetric range, then the step without clamps */
    qfoc_ab_t ab;
    qfoc_sincos_t cs;
    ab.alpha = qfoc_q15_sat((int32_t)in->alpha);
    ab.beta = qfoc_q15_sat((int32_t)in->beta);
    cs.sine = qfoc_q15_sat((int32_t)sc->sine);
    cs.cosine = qfoc_q15_sat((int32_t)sc->cosine);

    /*@ assert clamped: ab.alpha == QfocSat15(in->alpha) && ab.beta == QfocSat15(in->beta) &&
                        cs.sine == QfocSat15(sc->sine) && cs.cosine == QfocSat15(sc->cosine); */
    /*@ assert same_d: QfocParkD(ab.alpha, ab.beta, cs.sine, cs.cosine) ==
                       QfocParkDQ30(in->alpha, in->beta, sc->sine, sc->cosine); */
    /*@ assert same_q: QfocParkQ(ab.alpha, ab.beta, cs.sine, cs.cosine) ==
                       QfocParkQQ30(in->alpha, in->beta, sc->sine, sc->cosine); */
    /*@ for vector_bound: assert unclamped: ab.alpha == in->alpha && ab.beta == in->beta &&
                                            cs.sine == sc->sine && cs.cosine == sc->cosine; */
    /*@ for vector_bound: assert doc_d: QfocParkDQ30(in->alpha, in->beta, sc->sine, sc->cosine) ==
                                        QfocParkD(in->alpha, in->beta, sc->sine, sc->cosine); */
    /*@ for vector_bound: assert doc_q: QfocParkQQ30(in->alpha, in->beta, sc->sine, sc->cosine) ==
                                        QfocParkQ(in->alpha, in->beta, sc->sine, sc->cosine); */
    /*@ for vector_bound: assert doc_bound:
          ParkDocBound(QfocParkD(in->alpha, in->beta, sc->sine, sc->cosine)) &&
          ParkDocBound(QfocParkQ(in->alpha, in->beta, sc->sine, sc->cosine)); */
    /*@ for vector_bound: assert doc_fits:
          QfocQ30Fits(QfocParkD(in->alpha, in->beta, sc->sine, sc->cosine)) &&
          QfocQ30Fits(QfocParkQ(in->alpha, in->beta, sc->sine, sc->cosine)); */
    qfoc_park_sym(&ab, &cs, out);
}

void qfoc_inv_park_sym(const qfoc_dq_t *in, const qfoc_sincos_t *sc, qfoc_ab_t *out)
{
    /* every factor is in [-32767, 32767] (required): |product| <= 32767^2 */
    const int32_t d = (int32_t)in->d;
    const int32_t q = (int32_t)in->q;
    const int32_t s = (int32_t)sc->sine;
    const int32_t c = (int32_t)sc->cosine;
    int32_t alpha_q30;
    int32_t beta_q30;

    /*@ assert same: d == in->d && q == in->q && s == sc->sine && c == sc->cosine; */
    /*@ assert prod_dc: -1073676289 <= d * c <= 1073676289; */
    /*@ assert prod_qs: -1073676289 <= q * s <= 1073676289; */
    /*@ assert prod_ds: -1073676289 <= d * s <= 1073676289; */
    /*@ assert prod_qc: -1073676289 <= q * c <= 1073676289; */
    /* 2.30 sums, |sum| <= 2 * 32767^2 = 2147352578 < 2^31 */
    alpha_q30 = (d * c) - (q * s);
    beta_q30 = (d * s) + (q * c);
    /*@ assert alpha_sum: alpha_q30 == QfocInvParkAlpha(in->d, in->q, sc->sine, sc->cosine); */
    /*@ assert beta_sum: beta_q30 == QfocInvParkBeta(in->d, in->q, sc->sine, sc->cosine); */

    out->alpha = qfoc_q15_from_q30(alpha_q30);
    out->beta = qfoc_q15_from_q30(beta_q30);
}

void qfoc_inv_park(const qfoc_dq_t *in, const qfoc_sincos_t *sc, qfoc_ab_t *out)
{
    /* clamp every factor to the symmetric range, then the step without clamps */
    qfoc_dq_t dq;
    qfoc_sincos_t cs;
    dq.d = qfoc_q15_sat((int32_t)in->d);
    dq.q = qfoc_q15_sat((int32_t)in->q);
    cs.sine = qfoc_q15_sat((int32_t)sc->sine);
    cs.cosine = qfoc_q15_sat((int32_t)sc->cosine);

    /*@ assert clamped: dq.d == QfocSat15(in->d) && dq.q == QfocSat15(in->q) &&
                        cs.sine == QfocSat15(sc->sine) && cs.cosine == QfocSat15(sc->cosine); */
    /*@ assert same_alpha: QfocInvParkAlpha(dq.d, dq.q, cs.sine, cs.cosine) ==
                           QfocInvParkAlphaQ30(in->d, in->q, sc->sine, sc->cosine); */
    /*@ assert same_beta: QfocInvParkBeta(dq.d, dq.q, cs.sine, cs.cosine) ==
                          QfocInvParkBetaQ30(in->d, in->q, sc->sine, sc->cosine); */
    /*@ for vector_bound: assert unclamped: dq.d == in->d && dq.q == in->q &&
                                            cs.sine == sc->sine && cs.cosine == sc->cosine; */
    /*@ for vector_bound: assert doc_alpha:
          QfocInvParkAlphaQ30(in->d, in->q, sc->sine, sc->cosine) ==
          QfocInvParkAlpha(in->d, in->q, sc->sine, sc->cosine); */
    /*@ for vector_bound: assert doc_beta:
          QfocInvParkBetaQ30(in->d, in->q, sc->sine, sc->cosine) ==
          QfocInvParkBeta(in->d, in->q, sc->sine, sc->cosine); */
    /*@ for vector_bound: assert doc_bound:
          InvParkDocBound(QfocInvParkAlpha(in->d, in->q, sc->sine, sc->cosine)) &&
          InvParkDocBound(QfocInvParkBeta(in->d, in->q, sc->sine, sc->cosine)); */
    /*@ for vector_bound: assert doc_fits:
          QfocQ30Fits(QfocInvParkAlpha(in->d, in->q, sc->sine, sc->cosine)) &&
          QfocQ30Fits(QfocInvParkBeta(in->d, in->q, sc->sine, sc->cosine)); */
    qfoc_inv_park_sym(&dq, &cs, out);
}

void qfoc_inv_clarke(const qfoc_ab_t *in, qfoc_abc_t *out)
{
    int32_t alpha = (int32_t)qfoc_q15_sat((int32_t)in->alpha);
    int32_t beta = (int32_t)qfoc_q15_sat((int32_t)in->beta);
    int32_t half_alpha_q30;
    int32_t sqrt3_beta_q30;
    int32_t v_q30;
    int32_t w_q30;

    /*@ assert clamped: alpha == QfocSat15(in->alpha) && beta == QfocSat15(in->beta); */
    /* 2.30 terms: |alpha / 2| <= 536854528, |sqrt(3)/2 beta| <= 929861926 */
    half_alpha_q30 = alpha * QFOC_HALF_Q15;
    sqrt3_beta_q30 = beta * QFOC_SQRT3_2_Q15;
    /* |sum| <= 1466716454 < 2^31 */
    v_q30 = sqrt3_beta_q30 - half_alpha_q30;
    w_q30 = -sqrt3_beta_q30 - half_alpha_q30;
    /*@ assert v_sum: v_q30 == QfocInvClarkeVQ30(in->alpha, in->beta); */
    /*@ assert w_sum: w_q30 == QfocInvClarkeWQ30(in->alpha, in->beta); */

    out->u = (qfoc_q15_t)alpha;
    out->v = qfoc_q15_from_q30(v_q30);
    out->w = qfoc_q15_from_q30(w_q30);
}
