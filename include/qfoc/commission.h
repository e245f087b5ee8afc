/**
 * @file commission.h
 * @brief Commissioning beside the drive: the identification (ident.h) requested through
 *        the drive's command and run only while the drive is stopped, and one fast step
 *        that gives the PWM to exactly one of the two, the drive first.
 *
 * An integrator who commissions motors on the ECU calls qfoc_commission_fast_step() from
 * the ADC-complete interrupt instead of qfoc_drive_fast_step(), and qfoc_drive_tick() as
 * always.  The identification is entered only by an explicit command through
 * qfoc_drive_command() with identify set (no command frame carries it: the decoder sets
 * it false), once the tick has made it the drive's effective command, and then by
 * qfoc_commission_start() from the tick's context, which brings the mode's configuration:
 *
 *     qfoc_cmd_t cmd = { .power_on = false, .fault_clear = false, .target_rpm = 0u,
 *                        .identify = true };
 *     (void)qfoc_drive_command(&drive, &cmd);      repeat within timeout_ms
 *     out = qfoc_drive_tick(&drive, &in);          the request is now in effect
 *     if (start_wanted && qfoc_drive_identify_requested(&drive)) {
 *         start_wanted = false;
 *         r = qfoc_commission_start(&id, &drive, &cfg);   once; RUNNING, ERR_CFG or ERR_DRIVE
 *     }
 *     ... qfoc_ident_result(&id) until it is no longer RUNNING, then the record (ident.h)
 *
 * It starts only when the drive is stopped and requests it: state STOP (the offsets
 * calibrated), identify set and no run request in the effective command (the link's
 * rules: a lost link or a later command frame clears identify); and only with bounds
 * within the drive's protections: the
 * mode's current bound i_lim at most the table's i_trip and its bus bound vdc_max at most
 * the table's vdc_ov (while the mode has the PWM the drive's fast step does not run, so
 * its over-current latch and its bus measurement rest; the mode's own bounds stand in for
 * them).  Otherwise the start is refused (QFOC_IDENT_ERR_DRIVE) and nothing runs.  Each period, qfoc_commission_fast_step() runs either the drive's fast
 * step or the identification's, never both:
 *   - while the identification runs and the drive is still stopped and requesting it
 *     (state STOP, identify set, no run request), the identification's step, on the currents and the bus the drive would
 *     read from the same samples (its calibrated offsets, REQ-DRV-004); the drive's fast
 *     step is not called, so its output keeps the PWM off it set in STOP;
 *   - as soon as the drive is no longer stopped or no longer requests it (a run request,
 *     the request withdrawn, a command frame, a lost link, a fault, the tick leaving
 *     STOP), the identification is aborted (QFOC_IDENT_ERR_ABORT) and the drive's fast
 *     step runs in that same period: the drive has the PWM;
 *   - otherwise the drive's fast step.
 * The drive's object is read by the fast step as qfoc_drive_fast_step() reads it (the
 * tick's state and offsets) and written only through qfoc_drive_fast_step(); the
 * identification's object is written by this unit's two functions only.
 *
 * Requirements: REQ-IDENT-007 (specs/requirements/ident.md).
 */
#ifndef QFOC_COMMISSION_H
#define QFOC_COMMISSION_H

#include "qfoc/drive.h"
#include "qfoc/ident.h"

#ifdef __cplusplus
extern "C" {
#endif

/**
 * @brief Start the identification if the drive is stopped and its command requests it.
 * @param[out] id the identification's state (any contents)
 * @param[in]  d  the motor object
 * @param[in]  c  the configuration (any values)
 * @return QFOC_IDENT_RUNNING (started, as qfoc_ident_start()), QFOC_IDENT_ERR_CFG (the
 *         configuration refused) or QFOC_IDENT_ERR_DRIVE (the drive is not in STOP, its
 *         effective command does not request the identification, a run is requested, i_lim is above the table's i_trip or vdc_max above its
 *         vdc_ov: refused, PWM off, nothing runs).
 * Requirements: REQ-IDENT-007.
 */
/*@
  requires valid: \valid(id) && \valid_read(d) && \valid_read(c);
  requires sep: \separated(id, d) && \separated(id, c) && \separated(id, d->p);
  requires inv: DRV_VALID(d);
  assigns *id;
  ensures inv: IDENT_VALID(id);
  ensures result: \result == id->result;
  behavior stopped:
    assumes d->s.sm.state == QFOC_STATE_STOP && d->s.cmd.identify && !d->s.cmd.power_on &&
            c->i_lim <= d->p->i_trip && c->vdc_max <= d->p->vdc_ov;
    ensures started: \result == QFOC_IDENT_RUNNING || \result == QFOC_IDENT_ERR_CFG;
  behavior busy:
    assumes d->s.sm.state != QFOC_STATE_STOP || !d->s.cmd.identify || d->s.cmd.power_on ||
            c->i_lim > d->p->i_trip || c->vdc_max > d->p->vdc_ov;
    ensures refused: \result == QFOC_IDENT_ERR_DRIVE;
  complete behaviors;
  disjoint behaviors;
*/
uint8_t qfoc_commission_start(qfoc_ident_t *id, const qfoc_drive_t *d,
                              const qfoc_ident_cfg_t *c);

/**
 * @brief One PWM period: the identification's step while it runs and the drive is
 *        stopped and requests it, else the drive's fast step (the file comment's rules).
 * @param[in,out] d   the motor object (valid)
 * @param[in,out] id  the identification's state (valid)
 * @param[in]     adc raw samples of this period (any values)
 * @return the compare values and the enable of the one that ran
 * Requirements: REQ-IDENT-007.
 */
/*@
  requires valid: \valid(d) && \valid(id) && \valid_read(adc);
  requires sep: \separated(d, id) && \separated(d, adc) && \separated(id, adc) &&
                \separated(id, d->p);
  requires inv: DRV_VALID(d) && IDENT_VALID(id);
  assigns d->f, *id;
  behavior identification:
    assumes id->result == QFOC_IDENT_RUNNING && d->s.sm.state == QFOC_STATE_STOP &&
            d->s.cmd.identify && !d->s.cmd.power_on;
    ensures drv: DRV_VALID(d);
    ensures ident: IDENT_VALID(id);
    ensures one: \result.enable ==> d->s.sm.state == QFOC_STATE_STOP && d->s.cmd.identify &&
                                    !d->s.cmd.power_on;
  behavior drive:
    assumes id->result != QFOC_IDENT_RUNNING || d->s.sm.state != QFOC_STATE_STOP ||
            !d->s.cmd.identify || d->s.cmd.power_on;
    ensures drv: DRV_VALID(d);
    ensures ident: IDENT_VALID(id);
    ensures drive_first: id->result != QFOC_IDENT_RUNNING;
    ensures one: \result.enable ==> d->s.sm.state == QFOC_STATE_RUN && !d->f.trip;
  complete behaviors;
  disjoint behaviors;
*/
qfoc_pwm_t qfoc_commission_fast_step(qfoc_drive_t *d, qfoc_ident_t *id, const qfoc_adc_t *adc);

#ifdef __cplusplus
}
#endif

#endif /* QFOC_COMMISSION_H */
