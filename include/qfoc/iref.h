/**
 * @file iref.h
 * @brief Current-reference generation of the 1 ms tick: maximum torque per ampere
 *        (MTPA), the current-vector limit with d-axis priority, and thermal derating.
 *
 * The speed loop asks for a q current; the drive's tick turns it into the (i_d, i_q)
 * references the fast step's current loops follow (specs/equations.md section 9):
 *
 *     i_d     = clamp(i_d,MTPA(i_q) + i_d,FW, -i_max, 0)              (qfoc_iref_mtpa)
 *     i_q,lim = sqrt(i_max^2 - i_d^2)                                  (qfoc_iref_q_limit)
 *     i_q     = clamp(i_q, -i_q,lim, i_q,lim)        (the speed PI's own limits, the fast step)
 *
 * so that |(i_d, i_q)| <= i_max on every path (REQ-IREF-002), with the d axis served
 * first: field weakening keeps its current and the torque current takes what is left.
 * MTPA is the d current that gives the most torque per ampere of a salient motor
 * (L_q > L_d); field weakening's d current (fw.h) acts on top of it, so that it takes
 * over as soon as the voltage is short.  The speed target falls linearly with the
 * temperature between a derating temperature and the over-temperature trip
 * (qfoc_iref_derate): a compressor's load torque falls with its speed, so a lower speed
 * lowers the current and the losses, and the speed loop never sees a torque it cannot
 * give (a torque limit would leave a speed error that the stall monitor reads as a
 * stalled rotor).
 *
 * Scaling (specs/scaling.md): currents Q15 of I_base, fluxes Q15 of psi_base, inductances
 * Q12 of L_base = psi_base / I_base, so L i = l x i / 4096 in Q15 of psi_base;
 * temperatures in 0.1 degC.
 *
 * Every function is total on every value of its argument types, has no state and
 * no side effect.
 *
 * Requirements: REQ-IREF-001 .. REQ-IREF-004 (specs/requirements/iref.md).
 */
#ifndef QFOC_IREF_H
#define QFOC_IREF_H

#include "qfoc/types.h"
#include "qfoc/vector.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Inputs of the reference generation of one tick. */
typedef struct {
    qfoc_q15_t i_max;   /**< current-vector limit, Q15 of I_base (a value <= 0 reads as 0) */
    qfoc_q15_t iq_dem;  /**< q current the speed loop asks for, Q15 of I_base, any value */
    qfoc_q15_t id_fw;   /**< field weakening's d current, Q15 of I_base (fw.h: <= 0) */
    qfoc_q15_t psi_f;   /**< magnet flux, Q15 of psi_base (a value < 0 reads as 0) */
    int16_t ld;         /**< L_d / L_base, Q12, of the inductance set in use */
    int16_t lq;         /**< L_q / L_base, Q12 */
    bool mtpa;          /**< true: MTPA on (a salient motor); false: i_d = i_d,FW alone */
} qfoc_iref_in_t;

/** Outputs of the reference generation of one tick. */
typedef struct {
    qfoc_q15_t id;      /**< d-current reference, in [-i_max, 0] */
    qfoc_q15_t iq_lim;  /**< the largest |i_q| reference: sqrt(i_max^2 - id^2), in [0, i_max] */
} qfoc_iref_out_t;

/**
 * @brief The q-current limit that keeps the current vector inside the circle of radius
 *        i_max when the d current is i_d (d-axis priority).
 * @param[in] i_max the vector limit, Q15 (any value; a value <= 0 reads as 0)
 * @param[in] i_d   the d current, Q15 (any value, -32768 included; |i_d| above i_max
 *                  reads as i_max)
 * @return floor(sqrt(m^2 - a^2)) with m = max(i_max, 0) and a = min(|i_d|, m): in [0, m],
 *         and m^2 - a^2 < (result + 1)^2, so a^2 + result^2 <= m^2 (inside the circle) and
 *         the result is less than 1 LSB below the exact limit.
 * Scaling and overflow: m, a <= 32767; m^2 - a^2 in [0, 32767^2] in uint32; the integer
 * square root of vector.h.
 * Requirements: REQ-IREF-002.
 */
/*@
  assigns \nothing;
  ensures range: 0 <= \result && \result <= ((i_max > 0) ? i_max : 0);
  ensures root: QfocIsSqrt(\result, ((i_max > 0) ? i_max : 0) * ((i_max > 0) ? i_max : 0)
      - \min(((i_d < 0) ? -i_d : i_d), ((i_max > 0) ? i_max : 0))
      * \min(((i_d < 0) ? -i_d : i_d), ((i_max > 0) ? i_max : 0)));
*/
qfoc_q15_t qfoc_iref_q_limit(qfoc_q15_t i_max, qfoc_q15_t i_d);

/**
 * @brief The MTPA d current of a salient motor for the q current i_q.
 * With dL = L_q - L_d > 0 and x = dL |i_q| (the reluctance flux, Q15 of psi_base), the
 * torque 3/2 n_p i_q (psi_f - dL i_d) per ampere is largest for
 *
 *     i_d = psi_f / (2 dL) - sqrt(psi_f^2 / (4 dL^2) + i_q^2)
 *         = -2 x |i_q| / (psi_f + sqrt(psi_f^2 + 4 x^2))
 *
 * (the second form, free of the division by dL, is what is computed; specs/equations.md
 * E9-2).  It lies in [-|i_q|, 0]: 0 for i_q = 0 or a motor without saliency, -|i_q| (45
 * degrees) for a motor without magnet.
 * @param[in] i_q   q current, Q15 (any value; |-32768| reads as 32767)
 * @param[in] psi_f magnet flux, Q15 (a value < 0 reads as 0)
 * @param[in] ld    L_d, Q12 (any value)
 * @param[in] lq    L_q, Q12 (any value); lq <= ld gives 0 (no MTPA d current)
 * @return the d current, Q15, in [-min(|i_q|, 32767), 0].
 * Accuracy: x = dL |i_q| is limited to 1 psi_base (a reluctance flux beyond it gives the
 * d current of that flux); 2 x and the root are rounded to Q15, the ratio
 * g = 2 x / (psi_f + root) is formed in Q15 from the unrounded x, and i_d = -round(g |i_q|)
 * (|i_d| at most |i_q|): within 2 + 2 |i_d| / (psi_f + 2 x) LSB of the formula (psi_f and
 * x in Q15 counts), i.e. 2 LSB plus 2 / 10000 of i_d at psi_f = 10000 counts
 * (tests/test_iref.c checks it on 200000 random inputs against double precision).
 * Scaling and overflow: dL |i_q| <= 65535 x 32767 < 2^32 in uint32 (x_hi, Q27); the
 * root's argument psi_f^2 + (2 x)^2 < 2^33 and the rounding squares in uint64, a quarter of
 * it (< 2^31) into the 32-bit square root; 16 x_hi <= 16 x 32767 x 4096 < 2^31; g |i_q| in
 * uint64.
 * Requirements: REQ-IREF-001.
 */
/*@
  assigns \nothing;
  ensures range: -32767 <= \result <= 0;
  ensures bound: \result >= -((i_q < 0) ? -i_q : i_q);
  ensures zero: (lq <= ld || i_q == 0) ==> \result == 0;
*/
qfoc_q15_t qfoc_iref_mtpa(qfoc_q15_t i_q, qfoc_q15_t psi_f, int16_t ld, int16_t lq);

/**
 * @brief Thermal derating of a limit: hi up to t_start, falling linearly to lo at t_end,
 *        lo from there on.
 * @param[in] hi      the limit below the derating window (any value)
 * @param[in] lo      the limit at and above t_end (a value above hi reads as hi)
 * @param[in] t       the temperature, 0.1 degC (any value)
 * @param[in] t_start the derating temperature, 0.1 degC (any value)
 * @param[in] t_end   the end of the window (the trip), 0.1 degC; t_end <= t_start makes a
 *                    step at t_start
 * @return hi when t <= t_start; lo' = min(lo, hi) when t >= t_end (or t > t_start with an
 *         empty window); between them hi - floor((hi - lo') (t - t_start) / (t_end -
 *         t_start)), in [lo', hi], falling with t.
 * Scaling and overflow: (hi - lo') <= 65535 and (t - t_start) < (t_end - t_start) <= 65535:
 * the product < 2^32 in uint32.
 * Requirements: REQ-IREF-003.
 */
/*@
  assigns \nothing;
  ensures range: \min(lo, hi) <= \result <= hi;
  ensures below: t <= t_start ==> \result == hi;
  ensures above: (t > t_start && t >= t_end) ==> \result == \min(lo, hi);
*/
uint16_t qfoc_iref_derate(uint16_t hi, uint16_t lo, int16_t t, int16_t t_start, int16_t t_end);

/**
 * @brief The (i_d, i_q-limit) references of one tick: MTPA plus field weakening on the
 *        d axis, then the q limit of the current vector.
 * @param[in]  in  the inputs (any values)
 * @param[out] out id = clamp(MTPA(iq_dem) (when in->mtpa) + id_fw, -m, 0) and
 *                 iq_lim = qfoc_iref_q_limit(m, id), m = max(i_max, 0)
 * Scaling and overflow: the sum of two Q15 values in int32, then clamped.
 * Requirements: REQ-IREF-001, REQ-IREF-002, REQ-IREF-004.
 */
/*@
  requires valid: \valid_read(in) && \valid(out);
  requires sep: \separated(in, out);
  assigns *out;
  ensures id: -((in->i_max > 0) ? in->i_max : 0) <= out->id <= 0;
  ensures iq_lim: 0 <= out->iq_lim <= ((in->i_max > 0) ? in->i_max : 0);
  ensures circle: out->id * out->id + out->iq_lim * out->iq_lim <=
                  ((in->i_max > 0) ? in->i_max : 0) * ((in->i_max > 0) ? in->i_max : 0);
*/
void qfoc_iref_step(const qfoc_iref_in_t *in, qfoc_iref_out_t *out);

#ifdef __cplusplus
}
#endif

#endif /* QFOC_IREF_H */
