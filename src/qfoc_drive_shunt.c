/**
 * @file qfoc_drive_shunt.c
 * @brief The drive on a single-shunt inverter (drive_shunt.h): the phase currents rebuilt
 *        from two DC-link samples handed to the drive's fast step, and the plan of the next
 *        period.
 *
 * Requirements: REQ-SHUNT-006, REQ-SHUNT-007, REQ-SHUNT-008 (specs/requirements/shunt.md).
 */
#include "qfoc/drive_shunt.h"
#include "qfoc/q15.h"

/* The ADC code of zero current. */
#define DSH_MID ((int32_t)2048)

/* A plan before any period: nothing shifted, nothing measured (ok false). */
/*@
  requires valid: \valid(p);
  assigns *p;
  ensures not_ok: !p->ok;
  ensures idx: ShuntPlanIdx(p);
*/
static void dsh_plan_none(qfoc_shunt_plan_t *p)
{
    uint32_t k;
    /*@ loop invariant 0 <= k <= 3;
        loop assigns k, p->up[0 .. 2], p->down[0 .. 2];
        loop variant 3 - k; */
    for (k = 0u; k < 3u; k++) {
        p->up[k] = 0u;
        p->down[k] = 0u;
    }
    p->trig[0] = 0u;
    p->trig[1] = 0u;
    p->hi = 0u;
    p->lo = 1u;
    p->ok = false;
    p->shifted = false;
}

/* The state of a front end after its set-up: no plan yet (the first samples are read as
   the amplifier's zero), the latency, lost when refused. */
/*@
  requires valid: \valid(sd);
  requires latency: ok ==> 1 <= latency <= QFOC_DRIVE_SHUNT_LATENCY_MAX;
  assigns sd->plan[0 .. 1], sd->plan_on[0 .. 1], sd->head, sd->latency, sd->lost, sd->status;
  ensures head: sd->head == 0;
  ensures latency: 1 <= sd->latency <= QFOC_DRIVE_SHUNT_LATENCY_MAX;
  ensures status: sd->status <= QFOC_SHUNT_ERR_CFG;
  ensures lost: sd->lost <==> !ok;
  ensures kept: ok ==> sd->latency == latency;
*/
static void dsh_reset(qfoc_drive_shunt_t *sd, bool ok, uint8_t latency)
{
    dsh_plan_none(&sd->plan[0]);
    dsh_plan_none(&sd->plan[1]);
    sd->plan_on[0] = false;
    sd->plan_on[1] = false;
    sd->head = 0u;
    sd->latency = ok ? latency : 1u;
    sd->lost = !ok;
    sd->status = ok ? QFOC_SHUNT_HELD : QFOC_SHUNT_ERR_CFG;
}

uint8_t qfoc_drive_shunt_init(qfoc_drive_shunt_t *sd, const qfoc_drive_t *d, uint8_t latency)
{
    const qfoc_param_table_t *const t = d->p;
    const bool mode = (t->drive.sensing == QFOC_SENSING_SHUNT) && (latency >= 1u)
                      && (latency <= QFOC_DRIVE_SHUNT_LATENCY_MAX);
    qfoc_shunt_cfg_t c;
    bool ok;

    c.period = t->svpwm.period;
    c.t_settle = t->drive.shunt_settle;
    c.t_sample = t->drive.shunt_sample;
    c.hold_max = t->drive.shunt_hold;
    sd->cfg = c;
    /* (L_d + L_q) / 2, each read as 0 .. 32767 */
    sd->l_mean = (int16_t)((((t->ld > 0) ? (int32_t)t->ld : 0) + ((t->lq > 0) ? (int32_t)t->lq : 0)) / 2);
    ok = (qfoc_shunt_init(&sd->rec, &c) == QFOC_SHUNT_OK) && mode;
    dsh_reset(sd, ok, latency);
    return ok ? QFOC_SHUNT_OK : QFOC_SHUNT_ERR_CFG;
}

/* A current as the code the drive reads with the offset off: off + i / 16 (truncated),
   within the ADC's range. */
/*@
  requires off: off <= 4095;
  assigns \nothing;
  ensures range: \result <= 4095;
*/
static uint16_t dsh_code(qfoc_q15_t i, uint16_t off)
{
    int32_t c = (int32_t)off + ((int32_t)i / 16);
    if (c < 0) {
        c = 0;
    } else if (c > 4095) {
        c = 4095;
    } else {
        /* within range */
    }
    return (uint16_t)c;
}

/* A calibrated offset as an ADC code (at most 4095). */
/*@
  assigns \nothing;
  ensures range: \result <= 4095;
  ensures kept: off <= 4095 ==> \result == off;
*/
static uint16_t dsh_offset(uint16_t off)
{
    return (off > QFOC_ADC_MAX) ? QFOC_ADC_MAX : off;
}

/* E13-8: the change of a phase current over one period at the full DC bus, Q15:
   V_dc T / L = vdc x (w_base T) / l, w_base T = 2 pi k_theta / 2^17, l = (L_d + L_q) / 2 in
   Q12: (vdc kt / 32768) x 2048 / l, then x pi (25736 / 8192); 0 for an inductance of 0 or
   a bus at or below 0, at most 32767. */
/*@
  requires range: 0 <= kt <= 32767;
  assigns \nothing;
  ensures range: 0 <= \result <= 32767;
*/
static int32_t dsh_ripple_gain(qfoc_q15_t vdc, qfoc_q15_t kt, int16_t l_mean)
{
    const int32_t l = (int32_t)l_mean;
    int32_t g = 0;
    if ((l > 0) && (vdc > 0)) {
        const int32_t m = (int32_t)qfoc_q15_mul(vdc, kt);
        const int32_t a = (((m > 0) ? m : 0) * 2048) / l;
        g = (((a > 10430) ? 10430 : a) * 25736) / 8192;
    }
    return g;
}

qfoc_adc_t qfoc_drive_shunt_measure(qfoc_drive_shunt_t *sd, const qfoc_drive_t *d,
                                    const qfoc_adc_t *adc, qfoc_q15_t s1, qfoc_q15_t s2)
{
    /* the plan in force: the last call's (latency 1) or the one before (latency 2) */
    const uint32_t j = (sd->latency >= 2u) ? (1u - (uint32_t)sd->head) : (uint32_t)sd->head;
    const uint16_t off_u = dsh_offset(d->s.offset_u);
    const uint16_t off_v = dsh_offset(d->s.offset_v);
    qfoc_adc_t a;
    uint8_t m = QFOC_SHUNT_OK;

    a.vdc = adc->vdc;
    if (!sd->plan_on[j]) {
        /* no switching: the samples read the amplifier's zero (the offset calibration);
           s / 16 lies in [-2048, 2047], the code in [0, 4095] */
        const int32_t c1 = DSH_MID + ((int32_t)s1 / 16);
        const int32_t c2 = DSH_MID + ((int32_t)s2 / 16);
        a.iu = (uint16_t)c1;
        a.iv = (uint16_t)c2;
    } else {
        const int32_t e = ((int32_t)off_u - DSH_MID) * 16;
        qfoc_q15_t i[3];
        m = qfoc_shunt_currents(&sd->rec, &sd->plan[j], qfoc_q15_sat((int32_t)s1 - e),
                                qfoc_q15_sat((int32_t)s2 - e), i);
        if ((m == QFOC_SHUNT_OK) && (d->s.sm.sub != QFOC_SUB_CATCH)) {
            /* E13-7: referred to the instant the drive takes its currents for, latency - 1
               periods after the start of the sampled period (not in CATCH: drive_shunt.h);
               the angle per period of the drive's speed, speed_f x k_theta / 65536 (2^16
               per turn; k_theta above 32767, which no valid table has, read as 32767) */
            qfoc_q15_t kt = 32767;
            if (d->f.pll.k_theta <= 32767u) {
                kt = (qfoc_q15_t)d->f.pll.k_theta;
            } else {
                /* no valid table: read as 32767 */
            }
            const int32_t dth = (int32_t)qfoc_q15_mul(d->f.speed_f, kt) / 2;
            qfoc_shunt_align(&sd->cfg, &sd->plan[j], dth, dsh_ripple_gain(d->f.vdc, kt, sd->l_mean),
                             (uint8_t)(sd->latency - 1u), i);
        }
        a.iu = dsh_code(i[0], off_u);
        a.iv = dsh_code(i[1], off_v);
    }
    if (m == QFOC_SHUNT_LOST) {
        sd->lost = true;
    }
    if (sd->lost) {
        /* full scale: the drive's over-current trip */
        a.iu = QFOC_ADC_MAX;
        a.iv = 0u;
    }
    sd->status = m;
    return a;
}

qfoc_pwm_t qfoc_drive_shunt_output(const qfoc_drive_shunt_t *sd, qfoc_pwm_t out)
{
    qfoc_pwm_t r = out;
    if (sd->lost) {
        r.enable = false;
    }
    return r;
}

const qfoc_shunt_plan_t *qfoc_drive_shunt_plan(qfoc_drive_shunt_t *sd, const qfoc_drive_t *d)
{
    const uint8_t next = (sd->head != 0u) ? (uint8_t)0u : (uint8_t)1u;
    qfoc_shunt_plan(&sd->cfg, d->f.out.cmp, &sd->plan[next]);
    sd->plan_on[next] = d->f.out.enable && (!sd->lost);
    sd->head = next;
    return &sd->plan[next];
}
