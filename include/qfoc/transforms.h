/**
 * @file transforms.h
 * @brief Reference-frame transforms in Q15: Clarke, Park, inverse Park, inverse Clarke.
 *
 * Equations (tags E2-n of specs/equations.md, sections 3 and 6):
 *  - Clarke, equal-amplitude two-current form (E2-3), (E2-4):
 *      i_alpha = i_u,  i_beta = (i_u + 2 i_v) / sqrt(3).
 *  - Park (E2-7), (E2-8):
 *      i_d = i_alpha cos + i_beta sin,  i_q = -i_alpha sin + i_beta cos.
 *  - Inverse Park (voltage path) (E2-38):
 *      U_alpha = U_d cos - U_q sin,  U_beta = U_d sin + U_q cos.
 *  - Inverse Clarke (E2-40), the exact inverse of (E2-3), (E2-4) for a balanced set:
 *      U_u = U_alpha,  U_v = (-U_alpha + sqrt(3) U_beta) / 2,
 *      U_w = (-U_alpha - sqrt(3) U_beta) / 2.
 *
 * All functions are total: every int16_t input, -32768 included, gives a result in
 * the symmetric range [-32767, 32767].  Inside the bounds E2-6, E2-9 .. E2-12 and
 * E2-39 of specs/equations.md the result is the exact integer expression rounded
 * to nearest (ties away from zero); outside, each output saturates independently
 * to +-32767.
 *
 * Aliasing: input and output structs must not overlap (`\separated` in the contracts).
 * The implementation reads every input into a local before writing any output.
 *
 * Requirements: REQ-TRF-001 .. REQ-TRF-010 (specs/requirements/transforms.md).
 */
#ifndef QFOC_TRANSFORMS_H
#define QFOC_TRANSFORMS_H

#include "qfoc/types.h"

#ifdef __cplusplus
extern "C" {
#endif

#ifdef __FRAMAC__
#include "transforms.acsl"
#endif

/**
 * @brief Clarke transform, equal-amplitude two-current form (E2-3), (E2-4).
 *
 * @param[in]  iu   phase-u current, Q15, any int16_t
 * @param[in]  iv   phase-v current, Q15, any int16_t
 * @param[out] out  alpha = i_u, beta = (i_u + 2 i_v) / sqrt(3), Q15, each in
 *                  [-32767, 32767]
 *
 * Input range: the bound E2-6, A sqrt(m^2 + n^2) / sqrt(3) <= 32767, i.e. at
 * each instant (i_u + 2 i_v)^2 <= 3 * 32767^2 with i_u != -32768 (ClarkeDocBound).
 * Bad input: i_u = -32768 gives alpha = -32767; |i_u + 2 i_v| > 56754 gives
 * beta = +-32767 (saturated).
 *
 * Scaling and overflow: i_u + 2 i_v is formed exactly in 32 bits (|sum| <= 98304,
 * 1.15 -> 3.15) and clamped to +-56754, the largest magnitude inside the bound
 * (56754^2 <= 3 * 32767^2 < 56755^2).  It is multiplied by 1/sqrt(3) in Q16
 * (37837): 3.15 x 0.16 = Q31 with |product| <= 56754 * 37837 = 2147401098 < 2^31.
 * qfoc_q15_from_q31 rounds to nearest (ties away from zero) to 1.15; the rounded
 * value is at most 32767, so inside the bound beta is never saturated.
 * Accuracy against the real (E2-4) inside the bound: |error| <= 0.70 LSB (0.5 LSB
 * rounding + 0.2 LSB constant); alpha is exact.
 *
 * Requirements: REQ-TRF-001, REQ-TRF-002, REQ-TRF-009.
 */
/*@
  requires valid_out: \valid(out);
  assigns *out;
  ensures range: QfocQ15Sym(out->alpha) && QfocQ15Sym(out->beta);
  ensures alpha: out->alpha == QfocSat15(iu);
  ensures beta: out->beta == QfocRoundDiv(QfocClarkeBetaQ31(iu, iv), 65536);
  behavior exact:
    assumes ClarkeDocBound(iu, iv);
    ensures alpha_exact: out->alpha == iu;
    ensures beta_exact:
      out->beta == QfocRoundDiv(QfocClarkeSum(iu, iv) * 37837, 65536);
  behavior saturated:
    assumes !ClarkeDocBound(iu, iv);
    ensures alpha_sat: iu == -32768 ==> out->alpha == -32767;
    ensures beta_sat_upper: QfocClarkeSum(iu, iv) > 56754 ==> out->beta == 32767;
    ensures beta_sat_lower: QfocClarkeSum(iu, iv) < -56754 ==> out->beta == -32767;
  complete behaviors;
  disjoint behaviors;
*/
void qfoc_clarke(qfoc_q15_t iu, qfoc_q15_t iv, qfoc_ab_t *out);

/**
 * @brief Park transform (E2-7), (E2-8): stationary alpha/beta to rotating d/q.
 *
 * @param[in]  in   i_alpha, i_beta, Q15, any int16_t
 * @param[in]  sc   sine and cosine of the electrical angle, Q15, any int16_t
 *                  (normally |sin|, |cos| <= 32767, sin^2 + cos^2 <= 32768^2)
 * @param[out] out  i_d = alpha cos + beta sin, i_q = -alpha sin + beta cos, Q15,
 *                  each in [-32767, 32767]
 *
 * Input range: the bounds E2-9 .. E2-12, A1 (sqrt(m1^2 + n1^2) + |P|) <= 32767 (and
 * with |Q|), i.e. |i_d|, |i_q| <= 32767 (ParkDocBound on the Q30 sums).  It holds
 * whenever the current vector is at most full scale (alpha^2 + beta^2 <= 32767^2)
 * and sin^2 + cos^2 <= 32768^2 (behaviour vector_bound, lemma park_doc_bound).
 * Bad input: -32768 in any input is read as -32767; an output whose exact value
 * rounds beyond +-32767 saturates to +-32767.
 *
 * Scaling and overflow: each input is clamped to [-32767, 32767]; the two
 * 1.15 x 1.15 = 2.30 products are summed in 32 bits (|sum| <= 2 * 32767^2 =
 * 2147352578 < 2^31, for any input values); qfoc_q15_from_q30 rounds to nearest
 * (ties away from zero) and saturates to 1.15.  Accuracy against the real (E2-7),
 * (E2-8) with the same Q15 sin/cos: |error| <= 0.5 LSB when not saturated.
 *
 * Requirements: REQ-TRF-003, REQ-TRF-004, REQ-TRF-009, REQ-TRF-010.
 */
/*@
  requires valid_in: \valid_read(in);
  requires valid_sc: \valid_read(sc);
  requires valid_out: \valid(out);
  requires separated: \separated(out, in) && \separated(out, sc);
  assigns *out;
  ensures range: QfocQ15Sym(out->d) && QfocQ15Sym(out->q);
  behavior vector_bound:
    assumes QfocVecBound(in->alpha, in->beta);
    assumes QfocSinCosUnit(sc->sine, sc->cosine);
    ensures d_doc: out->d == QfocRoundDiv(QfocParkD(in->alpha, in->beta, sc->sine, sc->cosine), 32768);
    ensures q_doc: out->q == QfocRoundDiv(QfocParkQ(in->alpha, in->beta, sc->sine, sc->cosine), 32768);
  behavior d_exact:
    assumes QfocQ30Fits(QfocParkDQ30(in->alpha, in->beta, sc->sine, sc->cosine));
    ensures out->d == QfocRoundDiv(QfocParkDQ30(in->alpha, in->beta, sc->sine, sc->cosine), 32768);
  behavior d_saturated:
    assumes !QfocQ30Fits(QfocParkDQ30(in->alpha, in->beta, sc->sine, sc->cosine));
    ensures out->d == ((QfocParkDQ30(in->alpha, in->beta, sc->sine, sc->cosine) > 0) ? 32767 : -32767);
  behavior q_exact:
    assumes QfocQ30Fits(QfocParkQQ30(in->alpha, in->beta, sc->sine, sc->cosine));
    ensures out->q == QfocRoundDiv(QfocParkQQ30(in->alpha, in->beta, sc->sine, sc->cosine), 32768);
  behavior q_saturated:
    assumes !QfocQ30Fits(QfocParkQQ30(in->alpha, in->beta, sc->sine, sc->cosine));
    ensures out->q == ((QfocParkQQ30(in->alpha, in->beta, sc->sine, sc->cosine) > 0) ? 32767 : -32767);
  complete behaviors d_exact, d_saturated;
  disjoint behaviors d_exact, d_saturated;
  complete behaviors q_exact, q_saturated;
  disjoint behaviors q_exact, q_saturated;
*/
void qfoc_park(const qfoc_ab_t *in, const qfoc_sincos_t *sc, qfoc_dq_t *out);

/**
 * @brief Inverse Park transform (E2-38): rotating d/q to stationary alpha/beta.
 *
 * @param[in]  in   U_d, U_q, Q15, any int16_t
 * @param[in]  sc   sine and cosine of the electrical angle, Q15, any int16_t
 * @param[out] out  alpha = d cos - q sin, beta = d sin + q cos, Q15, each in
 *                  [-32767, 32767]
 *
 * Input range: the bound E2-39 on the result, Z + A_dq + C <= 32767 for
 * U_alpha and U_beta with harmonics on U_d, U_q (InvParkDocBound on the Q30 sums).
 * It holds whenever d^2 + q^2 <= 32767^2 and sin^2 + cos^2 <= 32768^2 (behaviour
 * vector_bound, lemma inv_park_doc_bound).
 * Bad input: -32768 in any input is read as -32767; an output whose exact value
 * rounds beyond +-32767 saturates to +-32767.
 *
 * Scaling and overflow: as qfoc_park: clamped inputs, two 2.30 products summed
 * in 32 bits (|sum| <= 2147352578 < 2^31), rounded and saturated to 1.15 by
 * qfoc_q15_from_q30.  |error| <= 0.5 LSB when not saturated.
 *
 * Requirements: REQ-TRF-005, REQ-TRF-006, REQ-TRF-009, REQ-TRF-010.
 */
/*@
  requires valid_in: \valid_read(in);
  requires valid_sc: \valid_read(sc);
  requires valid_out: \valid(out);
  requires separated: \separated(out, in) && \separated(out, sc);
  assigns *out;
  ensures range: QfocQ15Sym(out->alpha) && QfocQ15Sym(out->beta);
  behavior vector_bound:
    assumes QfocVecBound(in->d, in->q);
    assumes QfocSinCosUnit(sc->sine, sc->cosine);
    ensures alpha_doc: out->alpha == QfocRoundDiv(QfocInvParkAlpha(in->d, in->q, sc->sine, sc->cosine), 32768);
    ensures beta_doc: out->beta == QfocRoundDiv(QfocInvParkBeta(in->d, in->q, sc->sine, sc->cosine), 32768);
  behavior alpha_exact:
    assumes QfocQ30Fits(QfocInvParkAlphaQ30(in->d, in->q, sc->sine, sc->cosine));
    ensures out->alpha == QfocRoundDiv(QfocInvParkAlphaQ30(in->d, in->q, sc->sine, sc->cosine), 32768);
  behavior alpha_saturated:
    assumes !QfocQ30Fits(QfocInvParkAlphaQ30(in->d, in->q, sc->sine, sc->cosine));
    ensures out->alpha == ((QfocInvParkAlphaQ30(in->d, in->q, sc->sine, sc->cosine) > 0) ? 32767 : -32767);
  behavior beta_exact:
    assumes QfocQ30Fits(QfocInvParkBetaQ30(in->d, in->q, sc->sine, sc->cosine));
    ensures out->beta == QfocRoundDiv(QfocInvParkBetaQ30(in->d, in->q, sc->sine, sc->cosine), 32768);
  behavior beta_saturated:
    assumes !QfocQ30Fits(QfocInvParkBetaQ30(in->d, in->q, sc->sine, sc->cosine));
    ensures out->beta == ((QfocInvParkBetaQ30(in->d, in->q, sc->sine, sc->cosine) > 0) ? 32767 : -32767);
  complete behaviors alpha_exact, alpha_saturated;
  disjoint behaviors alpha_exact, alpha_saturated;
  complete behaviors beta_exact, beta_saturated;
  disjoint behaviors beta_exact, beta_saturated;
*/
void qfoc_inv_park(const qfoc_dq_t *in, const qfoc_sincos_t *sc, qfoc_ab_t *out);

/**
 * @brief Inverse Clarke transform (E2-40): alpha/beta to three phase quantities.
 *
 * @param[in]  in   U_alpha, U_beta, Q15, any int16_t
 * @param[out] out  u = alpha, v = (-alpha + sqrt(3) beta) / 2,
 *                  w = (-alpha - sqrt(3) beta) / 2, Q15, each in [-32767, 32767]
 *
 * This is the exact inverse of the Clarke transform (E2-3), (E2-4) for a balanced
 * set (u + v + w = 0): qfoc_clarke(u, v) returns (alpha, beta) again.
 * Input range: |v|, |w| <= 32767 in real terms; the Q30 sums then fit
 * (QfocQ30Fits) and v, w are exact.  This holds for every vector inside the
 * full-scale circle (alpha^2 + beta^2 <= 32767^2), since
 * sqrt(16384^2 + 28378^2) * 32767 < 32767.5 * 32768 (shown by test
 * test_req_trf_008_inv_clarke_saturation; not a WP behaviour).
 * Bad input: -32768 is read as -32767; an output whose exact value rounds beyond
 * +-32767 saturates to +-32767.  u always equals alpha saturated to the symmetric
 * range.
 *
 * Scaling and overflow: inputs clamped to [-32767, 32767]; -alpha/2 is formed as
 * alpha x 16384 (0.5 in Q15) and sqrt(3)/2 beta as beta x 28378 (sqrt(3)/2 x 32768
 * = 28377.9), both 2.30; the sum is at most 32767 x (16384 + 28378) = 1466716654
 * < 2^31 in magnitude; qfoc_q15_from_q30 rounds to nearest (ties away from zero)
 * and saturates to 1.15.  Accuracy against the real equations: |error| <= 0.6 LSB
 * when not saturated (0.5 LSB rounding + 0.08 LSB constant).
 *
 * Requirements: REQ-TRF-007, REQ-TRF-008, REQ-TRF-009, REQ-TRF-010.
 */
/*@
  requires valid_in: \valid_read(in);
  requires valid_out: \valid(out);
  requires separated: \separated(out, in);
  assigns *out;
  ensures range: QfocQ15Sym(out->u) && QfocQ15Sym(out->v) && QfocQ15Sym(out->w);
  ensures u_value: out->u == QfocSat15(in->alpha);
  behavior v_exact:
    assumes QfocQ30Fits(QfocInvClarkeVQ30(in->alpha, in->beta));
    ensures out->v == QfocRoundDiv(QfocInvClarkeVQ30(in->alpha, in->beta), 32768);
  behavior v_saturated:
    assumes !QfocQ30Fits(QfocInvClarkeVQ30(in->alpha, in->beta));
    ensures out->v == ((QfocInvClarkeVQ30(in->alpha, in->beta) > 0) ? 32767 : -32767);
  behavior w_exact:
    assumes QfocQ30Fits(QfocInvClarkeWQ30(in->alpha, in->beta));
    ensures out->w == QfocRoundDiv(QfocInvClarkeWQ30(in->alpha, in->beta), 32768);
  behavior w_saturated:
    assumes !QfocQ30Fits(QfocInvClarkeWQ30(in->alpha, in->beta));
    ensures out->w == ((QfocInvClarkeWQ30(in->alpha, in->beta) > 0) ? 32767 : -32767);
  complete behaviors v_exact, v_saturated;
  disjoint behaviors v_exact, v_saturated;
  complete behaviors w_exact, w_saturated;
  disjoint behaviors w_exact, w_saturated;
*/
void qfoc_inv_clarke(const qfoc_ab_t *in, qfoc_abc_t *out);

#ifdef __cplusplus
}
#endif

#endif /* QFOC_TRANSFORMS_H */
