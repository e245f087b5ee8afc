/**
 * @file qfoc_commission.c
 * @brief The identification beside the drive: requested through the drive's command and
 *        run only while the drive is stopped, one writer of the PWM per period
 *        (commission.h).
 *
 * Requirements: REQ-IDENT-007 (specs/requirements/ident.md).
 */
#include "qfoc/commission.h"
#include "qfoc/q15.h"
#include "qfoc/transforms.h"

/* Phase current of a sample as the drive reads it (REQ-DRV-004): the code taken as at
   most 4095, less the calibrated offset (an ADC code: the drive's invariant), x 16,
   saturated. */
/*@
  requires offset: offset <= 4095;
  assigns \nothing;
  ensures range: -32767 <= \result <= 32767;
*/
static qfoc_q15_t comm_current(uint16_t code, uint16_t offset)
{
    const int32_t c = (code > QFOC_ADC_MAX) ? (int32_t)QFOC_ADC_MAX : (int32_t)code;
    return qfoc_q15_sat((c - (int32_t)offset) * 16);
}

/* True while the drive is stopped and requests the identification: state STOP, and the
   effective command (the link's rules applied by the tick) with identify set and no run
   request. */
/*@
  requires valid: \valid_read(d);
  assigns \nothing;
  ensures result: \result <==> (d->s.sm.state == QFOC_STATE_STOP && d->s.cmd.identify &&
                               !d->s.cmd.power_on);
*/
static bool comm_stopped(const qfoc_drive_t *d)
{
    return (d->s.sm.state == QFOC_STATE_STOP) && d->s.cmd.identify && !d->s.cmd.power_on;
}

uint8_t qfoc_commission_start(qfoc_ident_t *id, const qfoc_drive_t *d,
                              const qfoc_ident_cfg_t *c)
{
    uint8_t r;
    if (comm_stopped(d) && (c->i_lim <= d->p->i_trip) && (c->vdc_max <= d->p->vdc_ov)) {
        r = qfoc_ident_start(id, c);
    } else {
        qfoc_ident_refuse(id);
        r = QFOC_IDENT_ERR_DRIVE;
    }
    return r;
}

/* The identification's period on the samples as the drive reads them. */
/*@
  requires valid: \valid_read(d) && \valid(id) && \valid_read(adc);
  requires sep: \separated(d, id) && \separated(id, adc);
  requires inv: IDENT_VALID(id) && d->s.offset_u <= 4095 && d->s.offset_v <= 4095;
  assigns *id;
  ensures inv: IDENT_VALID(id);
*/
static qfoc_pwm_t comm_ident_period(const qfoc_drive_t *d, qfoc_ident_t *id,
                                    const qfoc_adc_t *adc)
{
    qfoc_ab_t i;
    const qfoc_q15_t iu = comm_current(adc->iu, d->s.offset_u);
    const qfoc_q15_t iv = comm_current(adc->iv, d->s.offset_v);
    const uint16_t vdc = (adc->vdc > QFOC_ADC_MAX) ? QFOC_ADC_MAX : adc->vdc;
    qfoc_clarke(iu, iv, &i);
    return qfoc_ident_step(id, &i, (qfoc_q15_t)((int32_t)vdc * 8));
}

qfoc_pwm_t qfoc_commission_fast_step(qfoc_drive_t *d, qfoc_ident_t *id, const qfoc_adc_t *adc)
{
    qfoc_pwm_t out;
    if ((qfoc_ident_result(id) == QFOC_IDENT_RUNNING) && comm_stopped(d)) {
        out = comm_ident_period(d, id, adc);
    } else {
        /* the drive first: a running identification ends as soon as the drive is no
           longer stopped or no longer requests it, and the drive's fast step has this
           period */
        qfoc_ident_abort(id);
        out = qfoc_drive_fast_step(d, adc);
    }
    return out;
}
