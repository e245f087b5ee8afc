/**
 * @file svpwm.h
 * @brief Space-vector PWM: stationary-frame voltage command to three compare
 *        values of a centre-aligned (up-down) PWM counter.
 *
 * Signal chain of one call (specs/equations.md section 6, E2-40 .. E2-45):
 *  1. DC-bus voltage clamped to [vdc_min, 32767] (no division by zero, ever).
 *  2. Overmodulation limit: |v_ab| is limited to the inscribed circle of the
 *     voltage hexagon, radius Vdc / sqrt(3), by proportional scaling of alpha
 *     and beta (the angle is kept).
 *  3. Inverse Clarke transform (qfoc_inv_clarke(), E2-40) to the phase voltages Uu, Uv, Uw.
 *  4. Phase times Tx = Ux / Vdc * Tpwm (ticks, E2-41), one division per call.
 *  5. Dead-time compensation Tx += sign(ix) * dt_comp (E2-42), faded linearly inside the
 *     current dead band.
 *  6. Sector 1..6 from the sector table E2-43.
 *  7. Min-max zero-sequence injection Tx += Tpwm/2 - (Tmax + Tmin)/2, which
 *     centres the three pulses in the period (E2-44, equivalent to the
 *     sector-wise T_mid).
 *  8. Compare values clamped to [0, period].
 *
 * Conventions chosen here:
 *  - Counter: centre-aligned up-down counter, `period` ticks from 0 to the top
 *    (for example 80 MHz / 8 kHz / 2 = 5000).  The duty of phase x is
 *    cmp[x] / period; a LARGER compare value means a LONGER high-side on-time
 *    (phase x is connected to +Vdc for cmp[x] of every period ticks).  The port
 *    configures the timer output polarity so that this holds.
 *  - cmp = period / 2 on all three phases is zero voltage (the safe output).
 *  - Phase currents ix are positive when flowing from the inverter into the
 *    motor.  A positive current loses high-side time during the dead time, so
 *    the compensation adds +dt_comp ticks for ix > 0 and -dt_comp for ix < 0.
 *  - Dead band: for |ix| >= i_deadband the full dt_comp is applied; inside the
 *    band the compensation fades linearly, ix * dt_comp / i_deadband (truncated
 *    towards zero), and is exactly zero for ix == 0.  i_deadband == 0 gives
 *    a pure sign() compensation.
 *  - Sector numbering of the table E2-43 (Ta, Tb, Tc the compensated
 *    phase times of u, v, w; electrical angle of the voltage vector, alpha on
 *    phase u): 1: Ta>=Tb>=Tc (0..60 deg), 4: Tb>=Ta>=Tc (60..120), 3: Tb>=Tc>=Ta
 *    (120..180), 6: Tc>=Tb>=Ta (180..240), 5: Tc>=Ta>=Tb (240..300),
 *    2: Ta>=Tc>=Tb (300..360).  Tie rule: the first row of the table, in the
 *    order 1, 2, 3, 4, 5, 6, whose ordering holds is taken (so on a boundary the
 *    lower sector number wins; the zero vector is sector 1).
 *  - utilisation is |v_ab| / (Vdc / sqrt(3)) in Q15 (t_all of E2-45, which
 *    field weakening regulates, E2-46), of the COMMANDED vector before the limit,
 *    saturated to 32767 (= 1.0, reached whenever the limit is active).
 *
 * Error bound (REQ-SVPWM-010), Vdc the clamped bus voltage, P the period,
 * against an ideal real-valued SVPWM of the same Q15 inputs:
 *  - linear range (limited false), every compare value (both clamped to [0, P]):
 *    |cmp - cmp_ideal| <= 3 + 2 * P / Vdc ticks, plus 2 ticks when the
 *    dead-time compensation fades inside the dead band.  The P / Vdc term is
 *    the quantisation of the Q15 phase voltages (one LSB of voltage is P / Vdc
 *    ticks); the constant part is rounding of the scale factor, of the phase
 *    times and of the injected offset.
 *  - limited (overmodulation) case: |cmp - cmp_ideal| <= 3 + 8 * P / Vdc ticks
 *    (the scaled alpha, beta are re-quantised to Q15 and the vector magnitude
 *    is itself rounded).
 *  - line-to-line (linear range, no compare value clamped, zero currents):
 *    |(cmp_x - cmp_y) - (Ux - Uy) * P / Vdc| <= 2 + 2 * P / Vdc ticks against
 *    the ideal transform (tests); i.e. duty differences times
 *    Vdc reproduce the commanded line-to-line voltages.
 *  - centring: whenever no compare value is clamped (0 < cmp < P on all
 *    phases), max(cmp) + min(cmp) == P within 1 tick (proved: ensures centred).
 *  - magnitude: |v| is the floor square root of qfoc_vec_mag() (error < 1 LSB);
 *    the limited flag is therefore exact except within about 1 LSB of the
 *    circle.
 *
 * Requirements: REQ-SVPWM-001 .. REQ-SVPWM-011 (specs/requirements/svpwm.md).
 */
#ifndef QFOC_SVPWM_H
#define QFOC_SVPWM_H

#include "qfoc/types.h"

#ifdef __cplusplus
extern "C" {
#endif

#ifdef __FRAMAC__
#include "svpwm.acsl"
#endif

/** Smallest supported PWM period in counter ticks. */
#define QFOC_SVPWM_PERIOD_MIN ((uint16_t)100u)
/** Largest supported PWM period in counter ticks (keeps period * 65536 in int32). */
#define QFOC_SVPWM_PERIOD_MAX ((uint16_t)32767u)

/* Index of phase u, v, w in qfoc_svpwm_out_t::cmp. */
#define QFOC_SVPWM_U (0u)  /**< index of phase u in qfoc_svpwm_out_t::cmp */
#define QFOC_SVPWM_V (1u)  /**< index of phase v in qfoc_svpwm_out_t::cmp */
#define QFOC_SVPWM_W (2u)  /**< index of phase w in qfoc_svpwm_out_t::cmp */

/** Configuration of the SVPWM stage (constant while running). */
typedef struct {
    uint16_t period;        /**< counter top in ticks, 100 .. 32767 */
    uint16_t dt_comp;       /**< dead-time compensation in ticks, 0 .. period / 4 */
    qfoc_q15_t i_deadband;  /**< current dead band, Q15 of the current base, >= 0 */
    qfoc_q15_t vdc_min;     /**< smallest DC-bus voltage used, Q15 of the voltage base, > 0 */
} qfoc_svpwm_cfg_t;

/** Result of one SVPWM step. */
typedef struct {
    uint16_t cmp[3];           /**< compare values u, v, w in [0, period]; duty = cmp / period */
    uint8_t sector;            /**< 1 .. 6, table E2-43, see the file comment */
    qfoc_q15_t utilisation;    /**< |v| / (Vdc / sqrt 3), Q15, 0 .. 32767 */
    bool limited;              /**< the vector was scaled onto the inscribed circle,
                                    or the configuration was invalid */
    bool vdc_low;              /**< vdc < vdc_min: vdc_min was used instead */
} qfoc_svpwm_out_t;

/**
 * @brief Check the SVPWM configuration invariant.
 * @param[in] c configuration
 * @return true iff 100 <= period <= 32767, dt_comp <= period / 4,
 *         i_deadband >= 0 and vdc_min > 0.
 *
 * Scaling and overflow: compares only.
 *
 * Requirements: REQ-SVPWM-001.
 */
/*@
  requires valid_c: \valid_read(c);
  assigns \nothing;
  ensures result: \result <==> SvpwmCfgValid(c->period, c->dt_comp, c->i_deadband, c->vdc_min);
*/
bool qfoc_svpwm_cfg_is_valid(const qfoc_svpwm_cfg_t *c);

/**
 * @brief One SVPWM step: voltage vector to three compare values.
 *
 * @param[in]  cfg   configuration; when qfoc_svpwm_cfg_is_valid(cfg) is false the
 *                   output is the safe zero-voltage pattern cmp = period / 2 on
 *                   all phases, sector 1, utilisation 0, limited true,
 *                   vdc_low false (REQ-SVPWM-002).
 * @param[in]  v_ab  voltage command, Q15 of the voltage base, any int16 values
 *                   (-32768 included).
 * @param[in]  vdc   DC-bus voltage, Q15 of the SAME voltage base, any value;
 *                   below vdc_min (zero and negative included) vdc_min is used
 *                   and vdc_low is set (REQ-SVPWM-003).
 * @param[in]  i_abc phase currents, Q15 of the current base, any values;
 *                   only their sign and magnitude relative to i_deadband are used.
 * @param[out] out   compare values, sector, utilisation and flags.
 *
 * Scaling and overflow (all arithmetic in int32, every bound proved by WP):
 *  - r_lim = Vdc * 37837 / 65536 (1/sqrt 3 in Q16, floor) <= 18918, Q15 volts;
 *    Vdc * 37837 <= 1.24e9.
 *  - |v|^2 = alpha^2 + beta^2 <= 2^31 (uint32) picks the one square root: below
 *    32767^2, |v| = qfoc_vec_mag(alpha, beta) (exact); from 32767^2 on (|v| up to
 *    sqrt 2 * 32768, where qfoc_vec_mag() saturates) the halved vector is
 *    measured and doubled, so |v| <= 65534.
 *  - |v| > r_lim: g = r_lim * 65536 / |v| (Q16, 0 <= g <= 65535, one division),
 *    alpha' = alpha * g / 65536 (|alpha * g| <= 32768 * 65535 < 2^31),
 *    truncated towards zero so the limited vector never grows; utilisation = 32767.
 *  - |v| <= r_lim <= 18918: utilisation = |v| * 56756 / Vdc rounded
 *    (sqrt 3 in Q15; |v| * 56756 <= 1.08e9), saturated to 32767.
 *  - Phase voltages are clamped to [-Vdc, Vdc] (never active after the limit;
 *    it makes the next bound independent of the transform's accuracy).
 *  - k = P * 65536 / Vdc (Q16 ticks per voltage LSB, the one division of the
 *    phase times; P * 65536 <= 2147418112); Ux * k is bounded by
 *    Vdc * k <= P * 65536 and rounded to ticks (half away from zero): |Tx| <= P,
 *    formed in 32 bits as |Ux| kh + (|Ux| kl + 32768) / 65536 with
 *    k = kh * 65536 + kl (each product of a 15-bit and a 16-bit factor).
 *  - Dead-time compensation |c| <= P / 4 (|ix| * dt_comp <= 32767 * 8191);
 *    |Tx| <= 5 P / 4 afterwards; the injected offset (P - Tmax - Tmin) / 2
 *    (truncated towards zero) and Tx + offset stay within +-4 P; clamped to [0, P].
 *
 * Requirements: REQ-SVPWM-002, REQ-SVPWM-003, REQ-SVPWM-004, REQ-SVPWM-005,
 *   REQ-SVPWM-006, REQ-SVPWM-007, REQ-SVPWM-008, REQ-SVPWM-009, REQ-SVPWM-010,
 *   REQ-SVPWM-011.
 */
/*@
  requires valid_cfg: \valid_read(cfg);
  requires valid_v: \valid_read(v_ab);
  requires valid_i: \valid_read(i_abc);
  requires valid_out: \valid(out);
  requires sep: \separated(out, cfg) && \separated(out, v_ab) && \separated(out, i_abc);
  assigns *out;
  ensures range_sector: 1 <= out->sector <= 6;
  ensures range_util: 0 <= out->utilisation <= 32767;
  behavior invalid_cfg:
    assumes !SvpwmCfgValid(cfg->period, cfg->dt_comp, cfg->i_deadband, cfg->vdc_min);
    ensures safe_cmp: out->cmp[0] == cfg->period / 2 && out->cmp[1] == cfg->period / 2 &&
                      out->cmp[2] == cfg->period / 2;
    ensures safe_flags: out->limited == \true && out->vdc_low == \false &&
                        out->sector == 1 && out->utilisation == 0;
  behavior valid_cfg:
    assumes SvpwmCfgValid(cfg->period, cfg->dt_comp, cfg->i_deadband, cfg->vdc_min);
    ensures range_cmp: \forall integer j; 0 <= j < 3 ==> 0 <= out->cmp[j] <= cfg->period;
    ensures vdc_flag: out->vdc_low == \true <==> vdc < cfg->vdc_min;
    ensures sector_order: SvpwmSectorOrder(out->sector, out->cmp[0], out->cmp[1], out->cmp[2]);
    ensures centred: (\forall integer j; 0 <= j < 3 ==> 0 < out->cmp[j] < cfg->period) ==>
      cfg->period - 1 <= SvpwmMax3(out->cmp[0], out->cmp[1], out->cmp[2]) +
                         SvpwmMin3(out->cmp[0], out->cmp[1], out->cmp[2]) <= cfg->period + 1;
  complete behaviors;
  disjoint behaviors;
*/
void qfoc_svpwm_step(const qfoc_svpwm_cfg_t *cfg, const qfoc_ab_t *v_ab, qfoc_q15_t vdc,
                     const qfoc_abc_t *i_abc, qfoc_svpwm_out_t *out);

/**
 * @brief One SVPWM step without the overmodulation limit: voltage vector to three
 *        compare values, for a caller that keeps the vector inside the linear range.
 *
 * The same as qfoc_svpwm_step() without its step (2): the vector's magnitude is not
 * computed, the vector is not scaled onto the inscribed circle, the utilisation is
 * not computed (0) and limited is false.  A vector beyond Vdc / sqrt 3 is not
 * rejected: its phase voltages are clamped to [-Vdc, Vdc] and the compare values to
 * [0, period] as in qfoc_svpwm_step(), which distorts the output voltage instead of
 * scaling it.  Any input value is accepted; an invalid configuration gives the safe
 * pattern of qfoc_svpwm_step().
 *
 * @param[in]  cfg   configuration, as for qfoc_svpwm_step()
 * @param[in]  v_ab  voltage command, Q15 of the voltage base, any int16 values
 * @param[in]  vdc   DC-bus voltage, Q15 of the same voltage base, any value (below
 *                   vdc_min, vdc_min is used and vdc_low is set)
 * @param[in]  i_abc phase currents, Q15 of the current base, any values; only their
 *                   sign and magnitude relative to i_deadband are used
 * @param[out] out   compare values, sector and flags (with a valid configuration:
 *                   utilisation 0, limited false)
 *
 * Drive use: every PWM period, after the circle limit V_dc / sqrt 3 of the current
 * loop (qfoc_circle_limit) and the inverse Park transform, which keep the vector in
 * the linear range (up to the rounding of the rotation); the utilisation for field
 * weakening is computed by the tick.
 *
 * Scaling and overflow: as qfoc_svpwm_step(), steps (1) and (3) .. (8).
 *
 * Requirements: REQ-SVPWM-012.
 */
/*@
  requires valid_cfg: \valid_read(cfg);
  requires valid_v: \valid_read(v_ab);
  requires valid_i: \valid_read(i_abc);
  requires valid_out: \valid(out);
  requires sep: \separated(out, cfg) && \separated(out, v_ab) && \separated(out, i_abc);
  assigns *out;
  ensures range_sector: 1 <= out->sector <= 6;
  behavior invalid_cfg:
    assumes !SvpwmCfgValid(cfg->period, cfg->dt_comp, cfg->i_deadband, cfg->vdc_min);
    ensures safe_cmp: out->cmp[0] == cfg->period / 2 && out->cmp[1] == cfg->period / 2 &&
                      out->cmp[2] == cfg->period / 2;
    ensures safe_flags: out->limited == \true && out->vdc_low == \false &&
                        out->sector == 1 && out->utilisation == 0;
  behavior valid_cfg:
    assumes SvpwmCfgValid(cfg->period, cfg->dt_comp, cfg->i_deadband, cfg->vdc_min);
    ensures range_cmp: \forall integer j; 0 <= j < 3 ==> 0 <= out->cmp[j] <= cfg->period;
    ensures flags: out->limited == \false && out->utilisation == 0;
    ensures vdc_flag: out->vdc_low == \true <==> vdc < cfg->vdc_min;
    ensures sector_order: SvpwmSectorOrder(out->sector, out->cmp[0], out->cmp[1], out->cmp[2]);
    ensures centred: (\forall integer j; 0 <= j < 3 ==> 0 < out->cmp[j] < cfg->period) ==>
      cfg->period - 1 <= SvpwmMax3(out->cmp[0], out->cmp[1], out->cmp[2]) +
                         SvpwmMin3(out->cmp[0], out->cmp[1], out->cmp[2]) <= cfg->period + 1;
  complete behaviors;
  disjoint behaviors;
*/
void qfoc_svpwm_step_lin(const qfoc_svpwm_cfg_t *cfg, const qfoc_ab_t *v_ab, qfoc_q15_t vdc,
                         const qfoc_abc_t *i_abc, qfoc_svpwm_out_t *out);

#ifdef __cplusplus
}
#endif

#endif /* QFOC_SVPWM_H */
