/**
 * @file drive_shunt.h
 * @brief The drive on a single-shunt inverter: the fast step with the phase currents
 *        rebuilt from two DC-link samples per period (shunt.h).
 *
 * With a table whose drive.sensing is QFOC_SENSING_SHUNT, the port's ADC-complete
 * interrupt runs, each period:
 *
 *     codes = qfoc_drive_shunt_measure(&sd, &motor, &adc, s[0], s[1]);
 *     out   = qfoc_drive_shunt_output(&sd, qfoc_drive_fast_step(&motor, &codes));
 *     qfoc_hal_pwm_write_shunt(&out, qfoc_drive_shunt_plan(&sd, &motor));
 *
 * The measurement rebuilds the phase currents of the period from the two DC-link samples
 * (qfoc_shunt_currents() with the plan that was in force when they were taken) and hands
 * them to the drive's fast step as the phase-current codes it expects; the drive's output
 * goes to the port with the plan of the next period (the shifted compare values and the
 * two sampling instants), which
 * the port applies: qfoc_drive_shunt_plan(), called once after each fast step, makes it
 * from the drive's output (hal.h qfoc_hal_pwm_write_shunt() writes it).  A period in which
 * the port does not call it leaves the plan before in force (the timer keeps its compare
 * values and instants), which is what the measurement assumes with a latency of 1.  The tick is the drive's own
 * (qfoc_drive_tick()).
 *
 * Offsets: the DC-link amplifier's zero is learnt by the drive's own offset calibration.
 * While the plan in force was made for a disabled output (no switching: the samples read
 * the amplifier's zero), the two samples are handed over as the u and v codes
 * (2048 + s / 16), so the calibration learns offset_u, offset_v = 2048 + e / 16, e the
 * zero in Q15.  While switching, e (from offset_u) is taken off both samples before the
 * currents are rebuilt, and each rebuilt current i_k is handed over as offset_k + i_k / 16,
 * which the drive turns back into i_k (to 16 LSB).

Instant: the currents of a measured period are referred to the instant a two-sensor drive
samples (qfoc_shunt_align(), E13-7): `latency - 1` periods after the start of the sampled
period, 1.5 periods before the centre of the voltage the fast step then computes, with the
angle per period of the drive's filtered speed (speed_f x k_theta / 65536, 2^16 per turn),
and the PWM ripple of each sample taken off (E13-8: the drive's filtered DC bus across the
table's mean inductance (L_d + L_q) / 2).  A held period hands over the last currents as
rebuilt, and so does every period of the flying-start detection (the drive's sub-state
QFOC_SUB_CATCH: zero currents held while the estimator's speed settles; samples that do not
measure, an open sense line, are not turned into a current there).
 *
 * Quality: a period without a measurement (a plan that could not open both windows) holds
 * the last currents for at most drive.shunt_hold periods (QFOC_SHUNT_HELD); beyond it the
 * sensing is lost (QFOC_SHUNT_LOST): the output is held off from that call on (latched
 * until qfoc_drive_shunt_init()), and the drive is handed full-scale currents (u 4095,
 * v 0) so that its over-current trip stops it in the same call (PWM off, ERROR with OC at
 * the next tick) for every table whose i_trip the sensor can read (the tool's rule
 * 'over-current trip').
 *
 * Latency: the samples read in a call were taken in a period whose plan was written
 * `latency` calls before (1 on the S32K144 port: the ADC-complete interrupt of period k
 * runs after both samples of period k, whose plan the interrupt of period k - 1 wrote;
 * 2 where the fast step runs at the start of a period with the samples of the one before,
 * as the simulator does).
 *
 * Requirements: REQ-SHUNT-006 .. REQ-SHUNT-008 (specs/requirements/shunt.md).
 */
#ifndef QFOC_DRIVE_SHUNT_H
#define QFOC_DRIVE_SHUNT_H

#include "qfoc/drive.h"
#include "qfoc/shunt.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Largest latency: samples taken with the plan written two calls before. */
#define QFOC_DRIVE_SHUNT_LATENCY_MAX ((uint8_t)2u)

/** The single-shunt front end of one motor (beside its qfoc_drive_t). */
typedef struct {
    qfoc_shunt_cfg_t cfg;       /**< from the table: period, settle, sample, hold */
    qfoc_shunt_t rec;           /**< the rebuilt currents and the count of missed periods */
    qfoc_shunt_plan_t plan[2];  /**< the plans of the last two calls: plan[head] the last */
    bool plan_on[2];            /**< the output each of those plans was made for was enabled */
    uint8_t head;               /**< 0 .. 1: the index of the last call's plan */
    uint8_t latency;            /**< 1 .. QFOC_DRIVE_SHUNT_LATENCY_MAX */
    int16_t l_mean;             /**< (L_d + L_q) / 2 of the table, Q12 of L_base, 0 .. 32767:
                                     the inductance of the PWM ripple (E13-8) */
    uint8_t status;             /**< the last call's measurement: QFOC_SHUNT_OK, _HELD, _LOST;
                                     QFOC_SHUNT_ERR_CFG after a refused initialisation */
    bool lost;                  /**< the sensing was lost or never configured: output off */
} qfoc_drive_shunt_t;

#ifdef __FRAMAC__
/* ACSL predicates over the type above, read by Frama-C only (DEV-001). */
/* cppcheck-suppress misra-c2012-20.1 ; DEV-001 */
#include "drive_shunt.acsl"
#endif

/**
 * @brief Set up the front end of a drive from its table.
 * @param[out] sd      the front end
 * @param[in]  d       the drive (its table d->p is read: any contents)
 * @param[in]  latency 1 or 2 (see above); any other value refused
 * @return QFOC_SHUNT_OK; QFOC_SHUNT_ERR_CFG when the table's sensing is not
 *         QFOC_SENSING_SHUNT, its single-shunt configuration is not usable (shunt.h) or
 *         the latency is out of range: the front end is then lost from the start (its
 *         output always off).
 * Requirements: REQ-SHUNT-006.
 */
/*@
  requires valid: \valid(sd) && \valid_read(d) && \valid_read(d->p);
  requires sep: \separated(sd, d) && \separated(sd, d->p);
  assigns *sd;
  ensures inv: DshValid(sd);
  ensures result: \result == QFOC_SHUNT_OK || \result == QFOC_SHUNT_ERR_CFG;
  ensures refused: \result != QFOC_SHUNT_OK ==> sd->lost;
  ensures accepted: \result == QFOC_SHUNT_OK ==> !sd->lost && sd->latency == latency &&
                    d->p->drive.sensing == QFOC_SENSING_SHUNT;
*/
uint8_t qfoc_drive_shunt_init(qfoc_drive_shunt_t *sd, const qfoc_drive_t *d, uint8_t latency);

/**
 * @brief Before the drive's fast step: the phase-current codes of this period from its two
 *        DC-link samples, for qfoc_drive_fast_step() (see above).
 * @param[in,out] sd  the front end (valid)
 * @param[in]     d   the drive (its calibrated offsets are read, above 4095 read as 4095;
 *                    its filtered speed and the PLL's k_theta give the angle per period)
 * @param[in]     adc this period's DC-bus code (its phase-current codes are not read)
 * @param[in]     s1  the first DC-link sample of this period, Q15 (hal.h), any value
 * @param[in]     s2  the second, any value
 * @return the codes the drive's fast step takes: the DC-bus code as read, the phase
 *         codes within 0 .. 4095; u 4095, v 0 once the sensing is lost
 * Requirements: REQ-SHUNT-006, REQ-SHUNT-007, REQ-SHUNT-008.
 */
/*@
  requires valid: \valid(sd) && \valid_read(d) && \valid_read(adc);
  requires sep: \separated(sd, d) && \separated(sd, adc);
  requires inv: DshValid(sd);
  assigns sd->rec, sd->lost, sd->status;
  ensures inv: DshValid(sd);
  ensures latched: \old(sd->lost) ==> sd->lost;
  ensures vdc: \result.vdc == \old(adc->vdc);
  ensures codes: \result.iu <= 4095 && \result.iv <= 4095;
  ensures tripped: sd->lost ==> \result.iu == 4095 && \result.iv == 0;
*/
qfoc_adc_t qfoc_drive_shunt_measure(qfoc_drive_shunt_t *sd, const qfoc_drive_t *d,
                                    const qfoc_adc_t *adc, qfoc_q15_t s1, qfoc_q15_t s2);

/**
 * @brief After the drive's fast step: its output, the enable false once the sensing is
 *        lost.
 * @param[in] sd  the front end (any contents)
 * @param[in] out the drive's output (qfoc_drive_fast_step())
 * @return out, its enable false when sd->lost
 * Requirements: REQ-SHUNT-007.
 */
/*@
  requires valid: \valid_read(sd);
  assigns \nothing;
  ensures off_when_lost: \result.enable <==> (out.enable && !sd->lost);
  ensures cmp: \result.cmp[0] == out.cmp[0] && \result.cmp[1] == out.cmp[1] &&
               \result.cmp[2] == out.cmp[2];
*/
qfoc_pwm_t qfoc_drive_shunt_output(const qfoc_drive_shunt_t *sd, qfoc_pwm_t out);

/**
 * @brief The plan of the next period, from the drive's output of the fast step just run:
 *        the port's compare values and sampling instants (hal.h qfoc_hal_pwm_write_shunt()).
 * @param[in,out] sd the front end (valid)
 * @param[in]     d  the drive, after its fast step (d->f.out is read)
 * @return a pointer into sd: the plan, every compare value within the table's period
 *         (the edges shifted apart where an active vector is too short, shunt.h)
 * Requirements: REQ-SHUNT-006.
 */
/*@
  requires valid: \valid(sd) && \valid_read(d);
  requires sep: \separated(sd, d);
  requires inv: DshValid(sd);
  assigns sd->plan[0 .. 1], sd->plan_on[0 .. 1], sd->head;
  ensures inv: DshValid(sd);
  ensures last: \result == &sd->plan[sd->head];
  ensures range: DshPlanRange(&sd->plan[sd->head], sd->cfg.period);
  ensures on: sd->plan_on[sd->head] <==> (d->f.out.enable && !sd->lost);
*/
const qfoc_shunt_plan_t *qfoc_drive_shunt_plan(qfoc_drive_shunt_t *sd, const qfoc_drive_t *d);

#ifdef __cplusplus
}
#endif

#endif /* QFOC_DRIVE_SHUNT_H */
