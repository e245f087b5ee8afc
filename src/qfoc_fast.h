/**
 * @file qfoc_fast.h
 * @brief Internal steps of the drive's fast path (not part of the public API).
 *
 * The public functions accept every value of every input and clamp what could
 * overflow.  The steps declared here do the same arithmetic without those clamps:
 * their contracts *require* what the caller has already proved (the symmetric Q15
 * range of every factor, as the outputs of qfoc_clarke, qfoc_sincos and
 * qfoc_circle_limit guarantee), and ensure exactly what the public function
 * ensures for such inputs (stated on the equations themselves, QfocParkD and the
 * like, which for such inputs equal the clamped forms QfocParkDQ30 and the like).  The public functions are the clamps followed by these
 * steps, so both give the same value for every input the steps accept.
 *
 * Scaling, rounding and overflow are those of include/qfoc/transforms.h (the two
 * 2.30 products of factors in [-32767, 32767] sum to at most 2 x 32767^2 =
 * 2147352578 < 2^31; qfoc_q15_from_q30 rounds to nearest, ties away from zero,
 * and saturates).
 *
 * Requirements: REQ-TRF-003 .. REQ-TRF-006, REQ-TRF-009, REQ-TRF-010.
 */
#ifndef QFOC_FAST_H
#define QFOC_FAST_H

#include "qfoc/transforms.h"

/**
 * @brief Park transform (E2-7), (E2-8) of factors already in [-32767, 32767].
 * @param[in]  in   i_alpha, i_beta, Q15, each in [-32767, 32767]
 * @param[in]  sc   sine and cosine, Q15, each in [-32767, 32767]
 * @param[out] out  i_d, i_q as qfoc_park() gives them
 */
/*@
  requires valid_in: \valid_read(in);
  requires valid_sc: \valid_read(sc);
  requires valid_out: \valid(out);
  requires separated: \separated(out, in) && \separated(out, sc);
  requires sym_in: QfocQ15Sym(in->alpha) && QfocQ15Sym(in->beta);
  requires sym_sc: QfocQ15Sym(sc->sine) && QfocQ15Sym(sc->cosine);
  assigns *out;
  ensures range: QfocQ15Sym(out->d) && QfocQ15Sym(out->q);
  behavior d_exact:
    assumes QfocQ30Fits(QfocParkD(in->alpha, in->beta, sc->sine, sc->cosine));
    ensures out->d == QfocRoundDiv(QfocParkD(in->alpha, in->beta, sc->sine, sc->cosine), 32768);
  behavior d_saturated:
    assumes !QfocQ30Fits(QfocParkD(in->alpha, in->beta, sc->sine, sc->cosine));
    ensures out->d == ((QfocParkD(in->alpha, in->beta, sc->sine, sc->cosine) > 0) ? 32767 : -32767);
  behavior q_exact:
    assumes QfocQ30Fits(QfocParkQ(in->alpha, in->beta, sc->sine, sc->cosine));
    ensures out->q == QfocRoundDiv(QfocParkQ(in->alpha, in->beta, sc->sine, sc->cosine), 32768);
  behavior q_saturated:
    assumes !QfocQ30Fits(QfocParkQ(in->alpha, in->beta, sc->sine, sc->cosine));
    ensures out->q == ((QfocParkQ(in->alpha, in->beta, sc->sine, sc->cosine) > 0) ? 32767 : -32767);
  complete behaviors d_exact, d_saturated;
  disjoint behaviors d_exact, d_saturated;
  complete behaviors q_exact, q_saturated;
  disjoint behaviors q_exact, q_saturated;
*/
void qfoc_park_sym(const qfoc_ab_t *in, const qfoc_sincos_t *sc, qfoc_dq_t *out);

/**
 * @brief Inverse Park transform of factors already in [-32767, 32767].
 * @param[in]  in   u_d, u_q, Q15, each in [-32767, 32767]
 * @param[in]  sc   sine and cosine, Q15, each in [-32767, 32767]
 * @param[out] out  u_alpha, u_beta as qfoc_inv_park() gives them
 */
/*@
  requires valid_in: \valid_read(in);
  requires valid_sc: \valid_read(sc);
  requires valid_out: \valid(out);
  requires separated: \separated(out, in) && \separated(out, sc);
  requires sym_in: QfocQ15Sym(in->d) && QfocQ15Sym(in->q);
  requires sym_sc: QfocQ15Sym(sc->sine) && QfocQ15Sym(sc->cosine);
  assigns *out;
  ensures range: QfocQ15Sym(out->alpha) && QfocQ15Sym(out->beta);
  behavior alpha_exact:
    assumes QfocQ30Fits(QfocInvParkAlpha(in->d, in->q, sc->sine, sc->cosine));
    ensures out->alpha == QfocRoundDiv(QfocInvParkAlpha(in->d, in->q, sc->sine, sc->cosine), 32768);
  behavior alpha_saturated:
    assumes !QfocQ30Fits(QfocInvParkAlpha(in->d, in->q, sc->sine, sc->cosine));
    ensures out->alpha == ((QfocInvParkAlpha(in->d, in->q, sc->sine, sc->cosine) > 0) ? 32767 : -32767);
  behavior beta_exact:
    assumes QfocQ30Fits(QfocInvParkBeta(in->d, in->q, sc->sine, sc->cosine));
    ensures out->beta == QfocRoundDiv(QfocInvParkBeta(in->d, in->q, sc->sine, sc->cosine), 32768);
  behavior beta_saturated:
    assumes !QfocQ30Fits(QfocInvParkBeta(in->d, in->q, sc->sine, sc->cosine));
    ensures out->beta == ((QfocInvParkBeta(in->d, in->q, sc->sine, sc->cosine) > 0) ? 32767 : -32767);
  complete behaviors alpha_exact, alpha_saturated;
  disjoint behaviors alpha_exact, alpha_saturated;
  complete behaviors beta_exact, beta_saturated;
  disjoint behaviors beta_exact, beta_saturated;
*/
void qfoc_inv_park_sym(const qfoc_dq_t *in, const qfoc_sincos_t *sc, qfoc_ab_t *out);

#endif /* QFOC_FAST_H */
