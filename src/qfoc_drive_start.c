/**
 * @file qfoc_drive_start.c
 * @brief The drive's start-up sequence, run by the tick (drive.h, REQ-DRV-006,
 *        REQ-DRV-026, REQ-SM-011): ALIGN's d reference with the samples for the learning
 *        of the inverter's error, OPEN_LOOP's I/f references, the hand-over condition
 *        and the q current of the bumpless transfer.  The tick (qfoc_drive.c) calls
 *        these functions from drv_run(), drv_sm_inputs() and drv_on_transition().
 */
#include "qfoc/drive.h"
#include "qfoc/q15.h"
#include "qfoc/ramp.h"
#include "qfoc/trig.h"
#include "qfoc_drive_mon.h"
#include "qfoc_drive_start.h"

/** A quarter turn, 90 electrical degrees, in angle units. */
#define DRV_QUARTER_TURN ((int32_t)16384)
/* The current references move from ALIGN's d current to the I/f q current over at most
   this many ticks (REQ-DRV-006): a step would overshoot the current loop and jerk a held
   rotor; a ramp of a few current-loop time constants does neither. */
#define DRV_OL_RAMP_MS ((int32_t)16)

/* Signed difference a - b of two angles, in (-32768, 32767]. */
/*@
  assigns \nothing;
  ensures range: -32768 <= \result <= 32767;
*/
static int32_t drv_angle_diff(qfoc_angle_t a, qfoc_angle_t b)
{
    int32_t d = (int32_t)a - (int32_t)b;
    /*@ assert span: -65535 <= d <= 65535; */
    if (d > 32767) {
        d -= 65536;
    } else if (d < -32768) {
        d += 65536;
    } else {
        /* in range */
    }
    return d;
}

/* The product of two Q15 values in 32 bits (2.30, |a b| <= 2^30). */
/*@
  assigns \nothing;
  ensures value: \result == a * b;
  ensures range: -1073741824 <= \result <= 1073741824;
*/
static int32_t drv_product(qfoc_q15_t a, qfoc_q15_t b)
{
    return (int32_t)a * (int32_t)b;
}

/* The I/f start current of a start (REQ-SM-011): |i_start| raised by a quarter of itself
   per retry taken, at most |i_max| (which the table's check keeps at or above |i_start|). */
/*@
  requires valid: \valid_read(p);
  assigns \nothing;
  ensures range: 0 <= \result <= 32767;
*/
static qfoc_q15_t drv_start_current(const qfoc_param_table_t *p, uint8_t retry)
{
    const int32_t i0 = (int32_t)qfoc_q15_abs(p->drive.i_start);
    const int32_t im = (int32_t)qfoc_q15_abs(p->i_max);
    const int32_t i = i0 + ((i0 * (int32_t)retry) / 4);
    return (qfoc_q15_t)((i <= im) ? i : im);
}

/* public interface of the unit (qfoc_drive_start.h) */
bool qfoc_drive_start_converged(qfoc_drive_slow_t *s, const qfoc_drive_fast_t *f,
                                const qfoc_param_table_t *p, bool open_loop)
{
    const int32_t wol = (int32_t)s->ol_speed;
    const int32_t ew = (int32_t)f->speed_f - wol;
    const int32_t tol = ((wol > 0) ? wol : (int32_t)0) / 4;
    const int32_t dth = drv_angle_diff((qfoc_angle_t)(f->theta_ol / 65536u), f->theta_est);
    const int32_t ho = (int32_t)p->drive.ho_angle;
    const bool speed_ok = (ew <= tol) && (ew >= -tol);
    const bool mag_ok = (f->psi_mag >= p->pll.mag_min);
    const bool angle_ok = (dth < ho) && (dth > -(DRV_QUARTER_TURN + ho));
    /* the minimum speed: the I/f ramp has reached the handover speed */
    const bool ramp_done = (s->ol_speed >= qfoc_q15_abs(p->drive.of_speed));
    return qfoc_debounce_step(&s->db_ho,
                              open_loop && ramp_done && speed_ok && mag_ok && angle_ok,
                              p->drive.ho_dwell_ms);
}

qfoc_q15_t qfoc_drive_start_bumpless_iq(const qfoc_drive_t *d)
{
    const qfoc_param_table_t *const p = d->p;
    const int32_t dth = drv_angle_diff((qfoc_angle_t)(d->f.theta_ol / 65536u), d->f.theta_est);
    const int32_t i_max = (int32_t)qfoc_q15_abs(p->i_max);
    qfoc_sincos_t sc;
    int32_t iq;
    const int32_t a = dth + 65536;
    qfoc_sincos((qfoc_angle_t)((uint32_t)a & 0xFFFFu), &sc);
    {
        const qfoc_q15_t i = qfoc_q15_sat((int32_t)d->s.iq_ref);
        const qfoc_q15_t id_r = qfoc_q15_neg(qfoc_q15_mul(i, sc.sine));
        const qfoc_q15_t iq_r = qfoc_q15_mul(i, sc.cosine);
        const qfoc_q15_t dl = qfoc_q15_sat((int32_t)p->ld - (int32_t)p->lq);
        const qfoc_q15_t psi_act = qfoc_q15_add(p->psi_f, qfoc_drive_li((int16_t)dl, id_r));
        if (p->psi_f > 0) {
            iq = drv_product(iq_r, psi_act) / (int32_t)p->psi_f;
        } else {
            iq = (int32_t)iq_r;
        }
    }
    if (iq > i_max) {
        iq = i_max;
    } else if (iq < -i_max) {
        iq = -i_max;
    } else {
        /* within the current limit */
    }
    return (qfoc_q15_t)iq;
}

void qfoc_drive_start_open_loop(qfoc_drive_slow_t *s, const qfoc_param_table_t *p)
{
    const int32_t im = (int32_t)qfoc_q15_abs(p->i_max);
    const qfoc_q15_t step = qfoc_q15_sat((im + DRV_OL_RAMP_MS - 1) / DRV_OL_RAMP_MS);
    s->id_ref = qfoc_ramp_toward(s->id_ref, 0, step);
    s->iq_ref = qfoc_ramp_toward(s->iq_ref, drv_start_current(p, s->sm.retry), step);
    s->ol_speed = qfoc_ramp_toward(s->ol_speed, qfoc_q15_abs(p->drive.of_speed),
                                   p->drive.of_accel);
}

void qfoc_drive_start_align(qfoc_drive_t *d)
{
    qfoc_drive_slow_t *const s = &d->s;
    const qfoc_drive_cfg_t *const c = &d->p->drive;
    /* d-current ramp over the first half of align_ms, hold to three quarters, then half
       the current for the last quarter: the d voltages at five and seven eighths and
       at the end of the full-current hold are kept for the learning of the inverter's
       error (REQ-DRV-026) */
    const int32_t half = (int32_t)c->align_ms / 2;
    const uint32_t q3 = ((uint32_t)c->align_ms * 3u) / 4u;
    const uint32_t t = (uint32_t)s->sm.t_sub;
    const qfoc_q15_t u_now = qfoc_q15_sat(d->f.pi_id.integ / 65536);
    const int32_t ia = (int32_t)qfoc_q15_abs(c->i_align);
    /* the ramp's step, ceil(ia / half), at most ia: saturated, a no-op the proof
       needs no division bound for */
    const qfoc_q15_t step = qfoc_q15_sat((half > 0) ? ((ia + half - 1) / half) : ia);
    const qfoc_q15_t lo = (qfoc_q15_t)(ia / 2);
    if (t == (((uint32_t)c->align_ms * 5u) / 8u)) {
        s->dt_u0 = u_now;
    } else if (t == (((uint32_t)c->align_ms * 7u) / 8u)) {
        s->dt_u1 = u_now;
    } else {
        /* no eighth */
    }
    if ((t < q3) || ((s->id_ref != lo) && (s->id_ref != (qfoc_q15_t)ia))) {
        /* the ramp and the full-current hold (also a ramp not done by three quarters,
           which only a table changed after the start can give) */
        s->id_ref = qfoc_ramp_toward(s->id_ref, (qfoc_q15_t)ia, step);
    } else if (s->id_ref == (qfoc_q15_t)ia) {
        s->dt_u = u_now;
        s->id_ref = lo;
    } else {
        /* the half-current hold */
    }
}
