/**
 * @file qfoc_drive.c
 * @brief The compressor drive (drive.h): fast step, 1 ms tick, 100 ms job.
 *
 * Every value read from the parameter table is used through saturating arithmetic
 * or an explicit bound, so the two entry points are free of undefined behaviour for
 * any table content; the table's own check (qfoc_params_check) decides whether the
 * drive may run.
 */
#include "qfoc/drive.h"
#include "qfoc/dtc.h"
#include "qfoc/iref.h"
#include "qfoc/q15.h"
#include "qfoc/trig.h"
#include "qfoc/transforms.h"
#include "qfoc/vector.h"
#include "qfoc/ramp.h"
#include "qfoc_fast.h"
#include "qfoc_drive_mon.h"
#include "qfoc_drive_start.h"

/** 1 / sqrt(3) in Q15: 0.57735 x 32768 = 18918.6 -> 18919. */
#define DRV_INV_SQRT3 ((qfoc_q15_t)18919)
/** ADC code to Q15 DC bus: 4096 codes = V_base, so x 8. */
#define DRV_V_PER_CODE ((int32_t)8)
/** Largest offset-calibration shift (2^10 samples). */
#define DRV_OFFSET_SHIFT_MAX ((uint8_t)10u)
/** The 100 ms job runs when ms100 reaches this (first run 100 ms after init). */
#define DRV_MS100_LAST ((uint8_t)99u)
/** The table check's steps run at ms100 = 94 .. 98, one a tick, the verdict at 98. */
#define DRV_SCAN_FIRST ((uint8_t)(DRV_MS100_LAST - QFOC_PARAMS_SCAN_STEPS))
/** motorParaChange hysteresis: switch back below para_speed x 15/16. */
#define DRV_HS_HYST_DIV ((int32_t)16)

/* ================================================================== helpers */

/*@
  assigns \nothing;
  ensures range: 0 <= \result <= 4095;
  ensures value: \result == ((code <= 4095) ? code : 4095);
*/
static uint16_t drv_adc12(uint16_t code)
{
    uint16_t c = code;
    if (c > QFOC_ADC_MAX) {
        c = QFOC_ADC_MAX;
    } else {
        /* a 12-bit code */
    }
    return c;
}

/* Phase current from an ADC code and its offset: (code - offset) x 16, saturated. */
/*@
  assigns \nothing;
  ensures range: -32767 <= \result <= 32767;
  ensures value: \result == DrvCurrent(code, offset);
*/
static qfoc_q15_t drv_current(uint16_t code, uint16_t offset)
{
    const int32_t c = (int32_t)drv_adc12(code);
    const int32_t o = (int32_t)drv_adc12(offset);
    return qfoc_q15_sat((c - o) * QFOC_DRIVE_I_PER_CODE);
}

/* Modular add of a non-negative increment to a 2^32-per-turn angle. */
/*@
  assigns \nothing;
  ensures wrap: \result == (acc + inc) % 4294967296;
*/
static uint32_t drv_angle_add(uint32_t acc, uint32_t inc)
{
    const uint32_t room = 0xFFFFFFFFu - acc;
    uint32_t r;
    if (inc <= room) {
        r = acc + inc;
    } else {
        r = inc - room - 1u;
    }
    return r;
}

/* theta + delta modulo one turn (delta any int32 in +-65536). */
/*@
  requires d: -65536 <= delta <= 65536;
  assigns \nothing;
*/
static qfoc_angle_t drv_angle_shift(qfoc_angle_t theta, int32_t delta)
{
    const int32_t t = (int32_t)theta + delta + 65536;
    const uint32_t s = (uint32_t)t & 0xFFFFu;
    return (qfoc_angle_t)s;
}


/* Angle advance of one sample at speed w: w x k_theta / 65536 (65536 per turn). */
/*@
  assigns \nothing;
  ensures range: -16384 <= \result <= 16384;
*/
static int32_t drv_advance(qfoc_q15_t w, uint16_t k_theta)
{
    const int32_t k = (k_theta > 32767u) ? (int32_t)32767 : (int32_t)k_theta;
    const int32_t ws = (int32_t)qfoc_q15_sat((int32_t)w);
    return (ws * k) / 65536;
}

/* 2^s of the flux base psi_base = 2^s V_base / w_base (drive_cfg.h psi_shift; the range
   check keeps s <= 4, and a larger value reads as 4). */
/*@
  assigns \nothing;
  ensures range: 1 <= \result <= 16;
*/
static int32_t drv_psi_k(uint8_t s)
{
    int32_t k = 16;
    if (s == 0u) {
        k = 1;
    } else if (s == 1u) {
        k = 2;
    } else if (s == 2u) {
        k = 4;
    } else if (s == 3u) {
        k = 8;
    } else {
        /* 4 and above: the largest flux base */
    }
    return k;
}

/* A speed (Q15 of w_base) times a flux (Q15 of psi_base) as a voltage, Q15 of V_base:
   the Q15 product times 2^s, saturated. */
/*@
  requires k: 1 <= k <= 16;
  assigns \nothing;
  ensures range: -32767 <= \result <= 32767;
*/
static qfoc_q15_t drv_emf(qfoc_q15_t w, qfoc_q15_t psi, int32_t k)
{
    const int32_t v = (int32_t)qfoc_q15_mul(w, psi);
    /*@ assert v: -32767 <= v <= 32767; */
    return qfoc_q15_sat(v * k);
}

/* The flux observer's phase lead at the filtered speed (flux.h qfoc_flux_lead).  In the
   flux base 2^s V_base / w_base the observer's parameters are g / 2^s and kg 2^s (the
   recursion's decay g kg per sample is the same), so its high-pass corner in per unit of
   w_base is kg / 2^s, rounded to nearest: the lead is that of an observer with this corner
   (it depends on the corner and the speed alone; the other fields of the observer given
   to qfoc_flux_lead are 0). */
/*@
  requires valid: \valid_read(f) && \valid_read(p);
  requires kg: 0 <= f->flux.params.kg <= 32767;
  assigns \nothing;
*/
static qfoc_angle_t drv_lead(const qfoc_drive_fast_t *f, const qfoc_param_table_t *p)
{
    const uint8_t s = p->drive.psi_shift;
    const int32_t kg = (int32_t)f->flux.params.kg;
    int32_t c = (kg + 8) / 16;
    qfoc_flux_t o;
    if (s == 0u) {
        c = kg;
    } else if (s == 1u) {
        c = (kg + 1) / 2;
    } else if (s == 2u) {
        c = (kg + 2) / 4;
    } else if (s == 3u) {
        c = (kg + 4) / 8;
    } else {
        /* 4 and above: the largest flux base */
    }
    o.params.gain = 0;
    o.params.gain_shift = 0u;
    o.params.r = 0;
    o.params.l = 0;
    o.params.kg = (qfoc_q15_t)c;
    o.psi_alpha = 0;
    o.psi_beta = 0;
    o.i_prev.alpha = 0;
    o.i_prev.beta = 0;
    return qfoc_flux_lead(&o, f->speed_f);
}

/* ================================================================== fast step */

/*@
  requires valid: \valid(out);
  assigns *out;
  ensures off: out->enable == \false;
  ensures cmp: out->cmp[0] == 0 && out->cmp[1] == 0 && out->cmp[2] == 0;
*/
static void drv_pwm_off(qfoc_pwm_t *out)
{
    out->cmp[0] = 0u;
    out->cmp[1] = 0u;
    out->cmp[2] = 0u;
    out->enable = false;
}

/* |x| > limit of one phase current (qfoc_fault_abs_over, in the unit so that it inlines). */
/*@
  assigns \nothing;
  ensures result: \result <==> DrvAbsOver(x, limit);
*/
static bool drv_abs_over(qfoc_q15_t x, qfoc_q15_t limit)
{
    /* |x| in [0, 32768], exact in 32 bits */
    const int32_t mag = (x < 0) ? -(int32_t)x : (int32_t)x;
    return (mag > (int32_t)limit);
}

/*@
  requires valid: \valid_read(i);
  assigns \nothing;
  ensures result: \result <==> (DrvAbsOver(i->u, limit) || DrvAbsOver(i->v, limit) ||
                                DrvAbsOver(i->w, limit));
*/
static bool drv_overcurrent(const qfoc_abc_t *i, qfoc_q15_t limit)
{
    const bool ou = drv_abs_over(i->u, limit);
    const bool ov = drv_abs_over(i->v, limit);
    const bool ow = drv_abs_over(i->w, limit);
    return ou || ov || ow;
}

/* Reset of the fast-step controllers when the control (re)starts, in three steps of at
   most two module calls each, so that each module's precondition is read from the drive
   invariant at the entry of its step. */
/*@
  requires valid: \valid(f);
  requires inv: DRV_FAST(f);
  assigns f->flux.psi_alpha, f->flux.psi_beta, f->flux.i_prev, f->pll.pi.integ,
          f->pll.pi.limited, f->pll.speed_lpf.state, f->pll.theta_acc, f->pll.speed;
  ensures inv: DRV_FAST(f);
*/
static void drv_restart_estimator(qfoc_drive_fast_t *f)
{
    const qfoc_ab_t zero = { 0, 0 };
    qfoc_flux_reset(&f->flux, &zero, &zero);
    qfoc_pll_reset(&f->pll, 0u, 0);
}

/*@
  requires valid: \valid(f);
  requires inv: DRV_FAST(f);
  assigns f->pi_id.integ, f->pi_id.limited, f->pi_iq.integ, f->pi_iq.limited;
  ensures inv: DRV_FAST(f);
*/
static void drv_restart_current(qfoc_drive_fast_t *f)
{
    qfoc_pi_reset(&f->pi_id, 0);
    qfoc_pi_reset(&f->pi_iq, 0);
}

/*@
  requires valid: \valid(f) && \valid_read(p);
  requires sep: \separated(f, p);
  requires inv: DRV_FAST(f);
  assigns f->phase, f->mech;
  ensures inv: DRV_FAST(f);
*/
static void drv_restart_monitors(qfoc_drive_fast_t *f, const qfoc_param_table_t *p)
{
    qfoc_phase_mon_reset(&f->phase);
    (void)qfoc_mech_init(&f->mech, p->drive.pole_pairs, 0u);
}

/* Estimator: flux observer and PLL on this period's currents and the voltage applied
   during the period that ended at this sample; the rotor angle is the PLL angle less
   the observer's phase lead, which the tick computes from the filtered speed
   (qfoc_flux_lead, once a millisecond: the lead follows the speed, which moves little
   in 1 ms). */
/*@
  requires valid: \valid(f) && \valid_read(i_ab) && \valid_read(u);
  requires sep: \separated(f, i_ab) && \separated(f, u);
  requires inv: DRV_FAST(f);
  assigns f->flux.psi_alpha, f->flux.psi_beta, f->flux.i_prev, f->pll.pi.integ,
          f->pll.pi.limited, f->pll.speed_lpf.state, f->pll.theta_acc, f->pll.speed,
          f->theta_est, f->speed, f->speed_f, f->psi_mag;
  ensures inv: DRV_FAST(f);
*/
static void drv_estimate(qfoc_drive_fast_t *f, const qfoc_ab_t *i_ab, const qfoc_ab_t *u,
                         qfoc_angle_t lead)
{
    qfoc_ab_t psi;
    qfoc_pll_out_t po;
    qfoc_flux_step(&f->flux, u, i_ab, &psi);
    qfoc_pll_step(&f->pll, &psi, &po);
    f->theta_est = drv_angle_shift(po.theta, -(int32_t)lead);
    f->speed = po.speed;
    f->speed_f = po.speed_f;
    f->psi_mag = po.mag;
}

/* Current references of the sub-state (REQ-DRV-006, REQ-DRV-013); returns true when the
   closed-loop q reference (speed PI + torque-compensation feed-forward ff) was clamped to
   +-iq_lim, the q limit the tick left with its d reference (REQ-IREF-002). */
/*@
  requires valid: \valid_read(d) && \valid_read(d->p) && \valid(ref);
  requires sep: \separated(ref, d) && \separated(ref, d->p);
  assigns *ref;
  ensures id: -32767 <= ref->d <= 32767;
  ensures iq: -32767 <= ref->q <= 32767;
  ensures align: sub == QFOC_SUB_ALIGN ==> ref->q == 0;
  ensures q_limit: sub != QFOC_SUB_ALIGN && sub != QFOC_SUB_OPEN_LOOP ==>
                   (d->s.iq_lim > 0 ? -d->s.iq_lim <= ref->q <= d->s.iq_lim : ref->q == 0);
*/
static bool drv_references(const qfoc_drive_t *d, uint8_t sub, qfoc_q15_t ff, qfoc_dq_t *ref)
{
    qfoc_q15_t lim = 0;
    bool clamped = false;
    if (d->s.iq_lim > 0) {
        lim = d->s.iq_lim;
    } else {
        /* a negative limit (never written by the tick) reads as 0 */
    }
    if (sub == QFOC_SUB_ALIGN) {
        ref->d = qfoc_q15_sat((int32_t)d->s.id_ref);
        ref->q = 0;
    } else if (sub == QFOC_SUB_OPEN_LOOP) {
        /* ALIGN's d current ramping out, the I/f current ramping in (drv_run) */
        ref->d = qfoc_q15_sat((int32_t)d->s.id_ref);
        ref->q = qfoc_q15_sat((int32_t)d->s.iq_ref);
    } else {
        const int32_t q = (int32_t)d->s.iq_ref + (int32_t)ff;
        ref->d = qfoc_q15_sat((int32_t)d->s.id_ref);
        if (q > (int32_t)lim) {
            ref->q = lim;
            clamped = true;
        } else if (q < -(int32_t)lim) {
            ref->q = (qfoc_q15_t)(-lim);
            clamped = true;
        } else {
            ref->q = (qfoc_q15_t)q;
        }
    }
    return clamped;
}

/* Current PIs with the decoupling feed-forward, then the voltage circle limit. */
/*@
  requires valid: \valid(f) && \valid_read(p) && \valid_read(ref) && \valid(v);
  requires sep: \separated(f, p, ref, v);
  requires inv: DRV_FAST(f);
  assigns f->pi_id.integ, f->pi_id.limited, f->pi_iq.integ, f->pi_iq.limited, *v;
  ensures inv: DRV_FAST(f);
  ensures v_range: QfocQ15Sym(v->d) && QfocQ15Sym(v->q);
*/
static void drv_current_loop(qfoc_drive_fast_t *f, const qfoc_param_table_t *p,
                             const qfoc_dq_t *ref, qfoc_q15_t w, qfoc_dq_t *v)
{
    const int16_t ld = f->hs ? p->drive.ld_hs : p->ld;
    const int16_t lq = f->hs ? p->drive.lq_hs : p->lq;
    /* decoupling (rotor frame): u_d -= w L_q i_q, u_q += w (L_d i_d + psi_f), each a flux
       times the speed: a voltage of 2^psi_shift V_base */
    const int32_t k = drv_psi_k(p->drive.psi_shift);
    const qfoc_q15_t psi_d = qfoc_q15_add(qfoc_drive_li(ld, f->i_dq.d), p->psi_f);
    const qfoc_q15_t ff_d = qfoc_q15_neg(drv_emf(w, qfoc_drive_li(lq, f->i_dq.q), k));
    const qfoc_q15_t ff_q = drv_emf(w, psi_d, k);
    const qfoc_q15_t pi_d = qfoc_pi_step(&f->pi_id, qfoc_q15_sub(ref->d, f->i_dq.d));
    const qfoc_q15_t pi_q = qfoc_pi_step(&f->pi_iq, qfoc_q15_sub(ref->q, f->i_dq.q));
    /* the linear SVPWM range: |v| <= V_dc / sqrt 3; field weakening keeps the
       utilisation at fw_level below it, leaving the current loop its headroom */
    const qfoc_q15_t v_lim = qfoc_q15_mul(f->vdc, DRV_INV_SQRT3);
    qfoc_dq_t raw;
    raw.d = qfoc_q15_add(pi_d, ff_d);
    raw.q = qfoc_q15_add(pi_q, ff_q);
    (void)qfoc_circle_limit(&raw, qfoc_q15_abs(v_lim), v);
}

/* The control of one period in RUN (REQ-DRV-006). */
/*@
  requires valid: \valid(d) && \valid_read(d->p);
  requires sep: \separated(&d->f, d->p);
  requires inv: DRV_FAST(&d->f);
  assigns d->f;
  ensures inv: DRV_FAST(&d->f);
  ensures cmp: d->f.out.cmp[0] <= d->p->svpwm.period && d->f.out.cmp[1] <= d->p->svpwm.period &&
               d->f.out.cmp[2] <= d->p->svpwm.period;
  ensures on: d->f.out.enable == \true;
  ensures latch: d->f.trip == \old(d->f.trip);
*/
static void drv_control(qfoc_drive_t *d, uint8_t sub, qfoc_q15_t ff)
{
    qfoc_drive_fast_t *const f = &d->f;
    const qfoc_abc_t *const i_abc = &f->i_abc;
    const qfoc_param_table_t *const p = d->p;
    qfoc_ab_t i_ab;
    qfoc_angle_t theta;
    qfoc_q15_t w;
    qfoc_q15_t w_ff;
    qfoc_sincos_t sc;
    qfoc_dq_t ref;
    qfoc_dq_t v_dq;
    qfoc_ab_t v_ab;
    qfoc_svpwm_out_t sv;

    qfoc_clarke(i_abc->u, i_abc->v, &i_ab);
    /* the observer's voltage: the command applied during the period that ended at this
       sample, less the inverter's residual error learnt at ALIGN (dtc.h, REQ-DRV-026) */
    {
        qfoc_ab_t e;
        qfoc_ab_t u_obs;
        qfoc_dtc_error(d->s.dt_dv, i_abc, p->svpwm.i_deadband, &e);
        u_obs.alpha = qfoc_q15_sub(f->u_applied.alpha, e.alpha);
        u_obs.beta = qfoc_q15_sub(f->u_applied.beta, e.beta);
        drv_estimate(f, &i_ab, &u_obs, d->s.lead);
    }
    /* control angle and speed of the sub-state */
    if (sub == QFOC_SUB_ALIGN) {
        theta = 0u;
        w = 0;
    } else if (sub == QFOC_SUB_OPEN_LOOP) {
        theta = (qfoc_angle_t)(f->theta_ol / 65536u);
        w = qfoc_q15_sat((int32_t)d->s.ol_speed);
    } else {
        theta = f->theta_est;
        w = f->speed_f;
    }
    qfoc_sincos(theta, &sc);
    /* Clarke and sincos give symmetric Q15: the Park step needs no clamps */
    qfoc_park_sym(&i_ab, &sc, &f->i_dq);
    if (drv_references(d, sub, ff, &ref)) {
        f->clamp_count = (uint8_t)(((uint32_t)f->clamp_count + 1u) % 256u);
    } else {
        /* within the current limit */
    }
    /* CATCH measures the back-EMF by the voltage the zero-current PIs need: no feed-forward
       of the estimate's own speed, which would put on the terminals the very back-EMF the
       verdict looks for, kept by the inverter's dead band at zero current (REQ-DRV-027) */
    w_ff = w;
    if (sub == QFOC_SUB_CATCH) {
        w_ff = 0;
    } else {
        /* the decoupling at the loops' speed */
    }
    drv_current_loop(f, p, &ref, w_ff, &v_dq);
    /* the command acts from the next period on, on average 1.5 periods later */
    {
        const int32_t adv = drv_advance(w, p->pll.k_theta);
        qfoc_sincos(drv_angle_shift(theta, adv + (adv / 2)), &sc);
    }
    /* the circle limit and sincos give symmetric Q15: no clamps */
    qfoc_inv_park_sym(&v_dq, &sc, &v_ab);
    /* the circle limit kept |v| within V_dc / sqrt 3: SVPWM without its own limit; the
       tick computes the utilisation for field weakening */
    qfoc_svpwm_step_lin(&p->svpwm, &v_ab, f->vdc, i_abc, &sv);
    f->out.cmp[0] = sv.cmp[0];
    f->out.cmp[1] = sv.cmp[1];
    f->out.cmp[2] = sv.cmp[2];
    f->out.enable = true;
    /* voltage history for the observer: this command is applied during the next period */
    f->u_applied = f->u_last;
    f->u_last = v_ab;
}

/* Open-loop angle increment per period: w_ol x k_theta, 2^32 per turn. */
/*@
  assigns \nothing;
  ensures range: 0 <= \result <= 32767 * 32767;
*/
static uint32_t drv_ol_increment(qfoc_q15_t w_ol, uint16_t k_theta)
{
    const uint32_t w = (w_ol > 0) ? (uint32_t)w_ol : 0u;
    const uint32_t k = (k_theta > 32767u) ? 32767u : (uint32_t)k_theta;
    /*@ assert w: w <= 32767; */
    /*@ assert k: k <= 32767; */
    return w * k;
}

/* The rest of a controlled period: the open-loop angle, the mechanical angle and the
   phase monitor (field weakening runs in the tick, drv_iref). */
/*@
  requires valid: \valid(d) && \valid_read(d->p);
  requires sep: \separated(&d->f, d->p);
  requires inv: DRV_FAST(&d->f);
  assigns d->f.theta_ol, d->f.mech, d->f.theta_m, d->f.phase, d->f.phase_k;
  ensures inv: DRV_FAST(&d->f);
*/
static void drv_control_after(qfoc_drive_t *d, uint8_t sub)
{
    qfoc_drive_fast_t *const f = &d->f;
    if (sub == QFOC_SUB_OPEN_LOOP) {
        f->theta_ol = drv_angle_add(f->theta_ol, drv_ol_increment(d->s.ol_speed,
                                                                  d->p->pll.k_theta));
    } else {
        /* the open-loop frame stands still outside OPEN_LOOP */
    }
    f->theta_m = qfoc_mech_update(&f->mech, f->theta_est);
    /* one phase per period, in turn (the monitor's coefficient is for every third
       period, qfoc_phase_mon_alpha3) */
    qfoc_phase_mon_update_one(&f->phase, &f->i_abc, f->phase_k);
    f->phase_k = (f->phase_k >= 2u) ? 0u : (uint8_t)(f->phase_k + 1u);
}

/* The count of samples in a row with the same code: one more, capped at 65535, or 0. */
/*@
  assigns \nothing;
  ensures same: same ==> \result == ((n < 65535) ? n + 1 : 65535);
  ensures moved: !same ==> \result == 0;
*/
static uint16_t drv_same(uint16_t n, bool same)
{
    uint16_t r = 0u;
    if (same) {
        r = (n < 65535u) ? (uint16_t)(n + 1u) : n;
    } else {
        /* the code moved */
    }
    return r;
}

/* Measurement and the over-current latch (REQ-DRV-003, REQ-DRV-004). */
/*@
  requires valid: \valid(d) && \valid_read(d->p) && \valid_read(adc);
  requires sep: \separated(d, d->p) && \separated(d, adc);
  requires inv: DRV_FAST(&d->f);
  assigns d->f.adc_iu, d->f.adc_iv, d->f.same_u, d->f.same_v, d->f.vdc, d->f.vdc_lpf.state,
          d->f.trip, d->f.trip_count, d->f.clear_ack, d->f.i_abc;
  ensures inv: DRV_FAST(&d->f);
  ensures oc: DriveOverCurrent{Pre}(d, adc) ==> d->f.trip;
*/
static void drv_measure(qfoc_drive_t *d, const qfoc_adc_t *adc)
{
    qfoc_drive_fast_t *const f = &d->f;
    qfoc_abc_t *const i_abc = &f->i_abc;
    const uint8_t clear_seq = d->s.clear_seq;
    const uint16_t code_u = drv_adc12(adc->iu);
    const uint16_t code_v = drv_adc12(adc->iv);
    bool oc;
    /* stuck-sample monitor (REQ-DRV-020): samples in a row with the same code */
    f->same_u = drv_same(f->same_u, code_u == f->adc_iu);
    f->same_v = drv_same(f->same_v, code_v == f->adc_iv);
    f->adc_iu = code_u;
    f->adc_iv = code_v;
    i_abc->u = drv_current(adc->iu, d->s.offset_u);
    i_abc->v = drv_current(adc->iv, d->s.offset_v);
    i_abc->w = qfoc_q15_sat(-((int32_t)i_abc->u + (int32_t)i_abc->v));
    f->vdc = qfoc_lpf_step(&f->vdc_lpf,
                           (qfoc_q15_t)((int32_t)drv_adc12(adc->vdc) * DRV_V_PER_CODE));
    /* over-current: PWM off in this period, latched until a fault clear */
    oc = drv_overcurrent(i_abc, d->p->i_trip);
    if (oc) {
        f->trip = true;
        f->trip_count = (uint8_t)(((uint32_t)f->trip_count + 1u) % 256u);
    } else if (f->trip && (f->clear_ack != clear_seq)) {
        f->trip = false;
        f->clear_ack = clear_seq;
    } else {
        f->clear_ack = clear_seq;
    }
}

/* motorParaChange in the fast step (REQ-DRV-012): the observer's inductance follows the
   set the tick selected. */
/*@
  requires valid: \valid(f) && \valid_read(p);
  requires sep: \separated(f, p);
  requires inv: DRV_FAST(f);
  assigns f->hs, f->flux.params.l;
  ensures inv: DRV_FAST(f);
*/
static void drv_inductance(qfoc_drive_fast_t *f, const qfoc_param_table_t *p, bool hs)
{
    if (f->hs != hs) {
        const int16_t l = hs ? p->drive.lq_hs : p->lq;
        f->hs = hs;
        f->flux.params.l = (l > 0) ? l : (int16_t)0;
    } else {
        /* same inductance set */
    }
}

/* PWM off (REQ-DRV-002). */
/*@
  requires valid: \valid(f);
  requires inv: DRV_FAST(f);
  assigns f->active, f->i_dq, f->out;
  ensures inv: DRV_FAST(f);
  ensures off: f->out.enable == \false;
  ensures cmp: f->out.cmp[0] == 0 && f->out.cmp[1] == 0 && f->out.cmp[2] == 0;
*/
static void drv_off(qfoc_drive_fast_t *f)
{
    drv_pwm_off(&f->out);
    f->active = false;
    f->i_dq.d = 0;
    f->i_dq.q = 0;
}

/* The fast half at the start of a controlled period: the state of a RUN entry when RUN
   was entered, ALIGN follows CATCH (the rotor found standing) or CATCH starts again for
   a start retry (REQ-DRV-027, REQ-SM-011); the sub-state remembered. */
/*@
  requires valid: \valid(f) && \valid_read(p);
  requires sep: \separated(f, p);
  requires inv: DRV_FAST(f);
  assigns f->flux.psi_alpha, f->flux.psi_beta, f->flux.i_prev, f->pll.pi.integ,
          f->pll.pi.limited, f->pll.speed_lpf.state, f->pll.theta_acc, f->pll.speed,
          f->pi_id.integ, f->pi_id.limited, f->pi_iq.integ, f->pi_iq.limited,
          f->phase, f->mech, f->u_last, f->u_applied, f->theta_ol, f->sub_last;
  ensures inv: DRV_FAST(f);
  ensures sub: f->sub_last == sub;
*/
static void drv_period_entry(qfoc_drive_fast_t *f, const qfoc_param_table_t *p, uint8_t sub)
{
    /* RUN entered, ALIGN after CATCH found the rotor standing, or CATCH again for a start
       retry: from the state of a RUN entry.  The sub-state is stored before the restart:
       a store after a conditional call leaves WP a goal over the joined memory. */
    const bool restart = !f->active ||
                         ((sub == QFOC_SUB_ALIGN) && (f->sub_last != QFOC_SUB_ALIGN)) ||
                         ((sub == QFOC_SUB_CATCH) && (f->sub_last != QFOC_SUB_CATCH));
    f->sub_last = sub;
    if (restart) {
        const qfoc_ab_t zero = { 0, 0 };
        drv_restart_estimator(f);
        drv_restart_current(f);
        drv_restart_monitors(f, p);
        f->u_last = zero;
        f->u_applied = zero;
        f->theta_ol = 0u;
    } else {
        /* running on */
    }
}

/* One controlled period in RUN (REQ-DRV-006). */
/*@
  requires valid: \valid(d) && \valid_read(d->p);
  requires sep: \separated(d, d->p);
  requires inv: DRV_FAST(&d->f);
  assigns d->f;
  ensures inv: DRV_FAST(&d->f);
  ensures on: d->f.out.enable == \true;
  ensures cmp: d->f.out.cmp[0] <= d->p->svpwm.period && d->f.out.cmp[1] <= d->p->svpwm.period &&
               d->f.out.cmp[2] <= d->p->svpwm.period;
  ensures latch: d->f.trip == \old(d->f.trip);
*/
static void drv_run_period(qfoc_drive_t *d, uint8_t sub, qfoc_q15_t ff)
{
    drv_period_entry(&d->f, d->p, sub);
    drv_control(d, sub, ff);
    drv_control_after(d, sub);
    d->f.active = true;
}

/* The output of the period: the control in RUN without a trip, PWM off otherwise. */
/*@
  requires valid: \valid(d) && \valid_read(d->p);
  requires sep: \separated(d, d->p);
  requires inv: DRV_FAST(&d->f);
  assigns d->f;
  ensures inv: DRV_FAST(&d->f);
  ensures latch: d->f.trip == \old(d->f.trip);
  ensures cmp: d->f.out.cmp[0] <= d->p->svpwm.period && d->f.out.cmp[1] <= d->p->svpwm.period &&
               d->f.out.cmp[2] <= d->p->svpwm.period;
  ensures on: d->f.out.enable == \true <==> run == \true;
*/
static void drv_period(qfoc_drive_t *d, bool run, uint8_t sub, qfoc_q15_t ff)
{
    if (run) {
        drv_run_period(d, sub, ff);
    } else {
        drv_off(&d->f);
    }
}

qfoc_pwm_t qfoc_drive_fast_step(qfoc_drive_t *d, const qfoc_adc_t *adc)
{
    const uint8_t state = d->s.sm.state;
    const uint8_t sub = d->s.sm.sub;
    /* torque-compensation feed-forward at the mechanical angle of the last period */
    const qfoc_q15_t ff = qfoc_trqcomp_output(&d->s.tc, d->f.theta_m, d->f.speed_f);
    bool run;
    /* fast steps so far, mod 2^16, for the tick's timing monitor (REQ-DRV-021) */
    d->f.n_fast = (uint16_t)(((uint32_t)d->f.n_fast + 1u) & 0xFFFFu);
    drv_measure(d, adc);
    drv_inductance(&d->f, d->p, d->s.hs);
    run = (state == QFOC_STATE_RUN) && !d->f.trip;
    drv_period(d, run, sub, ff);
    return d->f.out;
}

/* ================================================================== tick */

/* Target speed: mechanical rpm to Q15 electrical, (rpm k_rpm + 2048) / 4096, at most
   speed_max (REQ-DRV-009). */
/*@
  assigns \nothing;
  ensures range: 0 <= \result <= 32767;
*/
static qfoc_q15_t drv_rpm_to_speed(uint16_t rpm, uint16_t k_rpm, qfoc_q15_t speed_max)
{
    const uint32_t s = (((uint32_t)rpm * (uint32_t)k_rpm) + 2048u) / 4096u;
    const int32_t smax = (speed_max > 0) ? (int32_t)speed_max : (int32_t)0;
    int32_t r = (s > 32767u) ? (int32_t)32767 : (int32_t)s;
    if (r > smax) {
        r = smax;
    } else {
        /* within the limit */
    }
    return (qfoc_q15_t)r;
}

/* x k / 32768 for a Q15 magnitude x and a 16-bit scale k: at most 65533. */
/*@
  requires x: x <= 32767;
  requires k: k <= 65535;
  assigns \nothing;
  ensures value: \result == (x * k) / 32768;
  ensures range: \result <= 65533;
*/
static uint16_t drv_scale(uint32_t x, uint32_t k)
{
    const uint32_t r = (x * k) / 32768u;
    /*@ assert fits: r <= 65533; */   /* 32767 x 65535 / 32768 */
    return (uint16_t)r;
}

/* |speed| in mechanical rpm: |speed| k_speed_rpm / 32768, saturated to 65535. */
/*@
  assigns \nothing;
*/
static uint16_t drv_speed_to_rpm(qfoc_q15_t speed, uint16_t k_speed_rpm)
{
    return drv_scale((uint32_t)qfoc_q15_abs(speed), (uint32_t)k_speed_rpm);
}

/* Offset calibration in PRECHARGE / CALIB (formerly Int_AD_GetPhaseCurrent, REQ-DRV-007):
   one sample of each channel per tick, 2^offset_shift samples averaged, each offset
   within offset_window of 2048.  Returns the OFFSET fault bit or 0. */
/*@
  requires valid: \valid(s) && \valid_read(f) && \valid_read(c);
  requires sep: \separated(s, f, c);
  requires sums: DRV_OFF_SUMS(s);
  assigns s->off_sum_u, s->off_sum_v, s->off_n, s->offset_u, s->offset_v, s->calib_done;
  ensures sums: DRV_OFF_SUMS(s);
  ensures offsets: s->offset_u <= 4095 && s->offset_v <= 4095;
  ensures result: \result == 0 || \result == QFOC_FAULT_OFFSET;
*/
static uint16_t drv_calibrate(qfoc_drive_slow_t *s, const qfoc_drive_fast_t *f,
                              const qfoc_drive_cfg_t *c, bool calibrating)
{
    uint16_t fault = 0u;
    /* 2^offset_shift samples, 1 .. 1024 */
    static const uint16_t pow2[11] = { 1u, 2u, 4u, 8u, 16u, 32u, 64u, 128u, 256u, 512u, 1024u };
    const uint8_t shift = (c->offset_shift > DRV_OFFSET_SHIFT_MAX) ? DRV_OFFSET_SHIFT_MAX
                                                                   : c->offset_shift;
    const uint16_t n = pow2[shift];
    const uint32_t n32 = (uint32_t)n;
    if (!calibrating) {
        s->off_sum_u = 0u;
        s->off_sum_v = 0u;
        s->off_n = 0u;
    } else if (s->off_n < n) {
        /*@ assert count: n <= 1024 && s->off_n < 1024; */
        /*@ assert room: s->off_sum_u <= 4095 * 1023 && s->off_sum_v <= 4095 * 1023; */
        s->off_sum_u += (uint32_t)drv_adc12(f->adc_iu);
        s->off_sum_v += (uint32_t)drv_adc12(f->adc_iv);
        s->off_n = (uint16_t)(s->off_n + 1u);
        /*@ assert sums: DRV_OFF_SUMS(s); */
        if (s->off_n == n) {
            /* n samples of at most 4095 each: the means are ADC codes */
            /*@ assert total: s->off_sum_u <= 4095 * n32 && s->off_sum_v <= 4095 * n32; */
            const uint32_t mu = s->off_sum_u / n32;
            const uint32_t mv = s->off_sum_v / n32;
            /*@ assert means: mu <= 4095 && mv <= 4095; */
            const uint16_t ou = (uint16_t)mu;
            const uint16_t ov = (uint16_t)mv;
            const int32_t du = (int32_t)ou - (int32_t)QFOC_ADC_MID;
            const int32_t dv = (int32_t)ov - (int32_t)QFOC_ADC_MID;
            const int32_t win = (int32_t)c->offset_window;
            if ((du > win) || (du < -win) || (dv > win) || (dv < -win)) {
                fault = QFOC_FAULT_OFFSET;
            } else {
                s->offset_u = ou;
                s->offset_v = ov;
                s->calib_done = true;
            }
        } else {
            /* collecting */
        }
    } else {
        /* more samples than the table's current 2^offset_shift (the table changed
           during the calibration): start the average again */
        s->off_sum_u = 0u;
        s->off_sum_v = 0u;
        s->off_n = 0u;
    }
    s->offset_u = drv_adc12(s->offset_u);
    s->offset_v = drv_adc12(s->offset_v);
    return fault;
}

/* Actions on a state or sub-state change (REQ-DRV-006). */
/*@
  requires valid: \valid(d) && \valid_read(d->p);
  requires sep: \separated(&d->s, d->p);
  requires inv: DRV_PI(&d->s.pi_speed) && DRV_FW(&d->s.fw) && DRV_TC(&d->s.tc);
  assigns d->s.pi_speed.integ, d->s.pi_speed.limited, d->s.fw.pi.integ, d->s.fw.pi.limited,
          d->s.fw.util_lpf.state, d->s.fw.id_ref, d->s.tc, d->s.speed_ref, d->s.ol_speed,
          d->s.id_ref, d->s.iq_ref, d->s.iq_lim, d->s.dt_dv, d->s.dt_learn, d->s.dt_u, d->s.dt_u0,
          d->s.dt_u1, d->s.clear_seq,
          d->s.run_ms, d->s.catch_st, d->s.caught,
          d->s.calib_done;
  ensures inv: DRV_PI(&d->s.pi_speed) && DRV_FW(&d->s.fw) && DRV_TC(&d->s.tc);
*/
static void drv_on_transition(qfoc_drive_t *d, uint8_t old_state, uint8_t old_sub)
{
    qfoc_drive_slow_t *const s = &d->s;
    const qfoc_param_table_t *const p = d->p;
    const uint8_t st = s->sm.state;
    const uint8_t sub = s->sm.sub;
    if (old_state == QFOC_STATE_ERROR) {
        /* a change out of ERROR is a fault clear (ERROR has no sub-states): the fast
           step releases its over-current latch */
        s->clear_seq = (uint8_t)(((uint32_t)s->clear_seq + 1u) & 0xFFu);
    } else {
        /* no clear */
    }
    if ((st != QFOC_STATE_RUN) || (old_state != QFOC_STATE_RUN) || (sub == QFOC_SUB_CATCH)) {
        /* entering or leaving RUN (or not running), or a start retried through CATCH (within
           RUN, CATCH is entered only from OPEN_LOOP, REQ-SM-011): everything from zero */
        s->speed_ref = 0;
        s->ol_speed = 0;
        s->id_ref = 0;
        s->iq_ref = 0;
        s->iq_lim = 0;
        s->dt_dv = 0;
        s->dt_learn = 0;
        s->dt_u = 0;
        s->dt_u0 = 0;
        s->dt_u1 = 0;
        s->run_ms = 0u;
        s->caught = false;
        qfoc_catch_reset(&s->catch_st);
        qfoc_pi_reset(&s->pi_speed, 0);
        qfoc_fw_reset(&s->fw);
        qfoc_trqcomp_reset(&s->tc);
    } else if (sub == QFOC_SUB_OPEN_LOOP) {
        /* OPEN_LOOP is entered from ALIGN only (sm.h, to_open_loop): the rotor stands
           aligned and the d PI's integrator holds the whole d voltage of the half alignment
           current (w = 0: no decoupling term); with the voltage at the full current, the
           inverter's residual voltage error (REQ-DTC-002, REQ-DRV-026), within the table's
           dead-time voltage error */
        const qfoc_q15_t ia = qfoc_q15_abs(p->drive.i_align);
        if ((ia > 1) && (s->id_ref == (qfoc_q15_t)(ia / 2))) {
            qfoc_dtc_align_t al;
            al.u_hi = s->dt_u;
            al.u_hi0 = s->dt_u0;
            al.u_lo = qfoc_q15_sat(d->f.pi_id.integ / 65536);
            al.u_lo0 = s->dt_u1;
            al.i_hi = ia;
            al.i_db = p->svpwm.i_deadband;
            al.v_max = p->drive.flux_v_err;
            al.r = p->flux.r;
            al.r_err = p->drive.flux_r_err;
            s->dt_learn = qfoc_dtc_learn(&al);
        } else {
            /* ALIGN ended before its half-current hold: nothing learnt */
        }
        /* the d reference ramps out from ALIGN's, the q reference in from 0 (drv_run) */
        s->iq_ref = 0;
    } else if ((sub == QFOC_SUB_CLOSED_LOOP) && (old_sub == QFOC_SUB_CATCH)) {
        /* a coasting rotor caught (REQ-DRV-027): the speed reference from its measured
           speed, within [0, speed_max]; no torque acted in CATCH, so the speed PI starts
           from zero q current; no 2 s hold, the observer has converged */
        s->speed_ref = qfoc_ramp_toward(0, (d->f.speed_f > 0) ? d->f.speed_f : (qfoc_q15_t)0,
                                        qfoc_q15_abs(p->speed_max));
        s->iq_ref = 0;
        s->iq_lim = qfoc_q15_abs(p->i_max);
        s->caught = true;
        qfoc_pi_reset(&s->pi_speed, 0);
    } else if ((sub == QFOC_SUB_CLOSED_LOOP) && (old_sub == QFOC_SUB_OPEN_LOOP)) {
        /* speed reference from the estimate, within [0, speed_max] */
        s->speed_ref = qfoc_ramp_toward(0, (d->f.speed_f > 0) ? d->f.speed_f : (qfoc_q15_t)0,
                                        qfoc_q15_abs(p->speed_max));
        s->iq_ref = qfoc_drive_start_bumpless_iq(d);
        /* the whole current limit until the tick's first MTPA / field-weakening step */
        s->iq_lim = qfoc_q15_abs(p->i_max);
        qfoc_pi_reset(&s->pi_speed, s->iq_ref);
    } else {
        /* no action */
    }
    if (st == QFOC_STATE_PRECHARGE) {
        s->calib_done = false;   /* (re)entering PRECHARGE: calibrate again */
    } else {
        /* offsets kept */
    }
}

/* The closed loop's current references (REQ-DRV-006, REQ-IREF-001 .. REQ-IREF-004): field
   weakening on the utilisation of the last command, MTPA of the speed loop's q current with
   the inductance set in use, the d reference clamped to [-i_max, 0], and the q limit of the
   current vector, to which the q reference is clamped; the fast step keeps the q reference
   plus the torque-compensation feed-forward within the same limit. */
/*@
  requires valid: \valid(d) && \valid_read(d->p);
  requires sep: \separated(&d->s, d->p);
  requires inv: DRV_FW(&d->s.fw);
  assigns d->s.fw.pi.integ, d->s.fw.pi.limited, d->s.fw.util_lpf.state, d->s.fw.id_ref,
          d->s.id_ref, d->s.iq_ref, d->s.iq_lim;
  ensures inv: DRV_FW(&d->s.fw);
  ensures q_limit: -d->s.iq_lim <= d->s.iq_ref <= d->s.iq_lim;
  ensures circle: DrvInCircle(d->s.id_ref, d->s.iq_lim, (d->p->i_max > 0) ? d->p->i_max : 0);
*/
static void drv_iref(qfoc_drive_t *d)
{
    qfoc_drive_slow_t *const s = &d->s;
    const qfoc_param_table_t *const p = d->p;
    qfoc_iref_in_t in;
    qfoc_iref_out_t out;
    in.i_max = p->i_max;
    in.iq_dem = s->iq_ref;
    in.id_fw = qfoc_fw_step(&s->fw, s->util, true);
    in.psi_f = p->psi_f;
    if (s->hs) {
        in.ld = p->drive.ld_hs;
        in.lq = p->drive.lq_hs;
    } else {
        in.ld = p->ld;
        in.lq = p->lq;
    }
    /* MTPA acts where L_q > L_d (qfoc_iref_mtpa gives 0 otherwise) and above mtpa_speed,
       where the angle estimate is trusted (the tool's default: the handover speed; a
       stalled or slowing rotor falls back to i_d = 0) */
    in.mtpa = drv_abs_over(d->f.speed_f, qfoc_q15_abs(p->drive.mtpa_speed));
    qfoc_iref_step(&in, &out);
    /*@ assert circle: DrvInCircle(out.id, out.iq_lim, (p->i_max > 0) ? p->i_max : 0); */
    s->id_ref = out.id;
    s->iq_lim = out.iq_lim;
    if (s->iq_ref > out.iq_lim) {
        s->iq_ref = out.iq_lim;
    } else if (s->iq_ref < (qfoc_q15_t)(-out.iq_lim)) {
        s->iq_ref = (qfoc_q15_t)(-out.iq_lim);
    } else {
        /* inside the q limit */
    }
}



/* CLOSED_LOOP's and STOPPING's references: the speed ramp, the speed loop, the reference
   block and the torque compensation's learning (REQ-DRV-006, REQ-DRV-009). */
/*@
  requires valid: \valid(d) && \valid_read(d->p);
  requires sep: \separated(&d->s, d->p);
  requires inv: DRV_PI(&d->s.pi_speed) && DRV_FW(&d->s.fw) && DRV_TC(&d->s.tc);
  assigns d->s.pi_speed.integ, d->s.pi_speed.limited, d->s.pi_speed.params.out_min,
          d->s.pi_speed.params.out_max, d->s.fw.pi.integ, d->s.fw.pi.limited,
          d->s.fw.util_lpf.state, d->s.fw.id_ref, d->s.tc, d->s.speed_ref,
          d->s.id_ref, d->s.iq_ref, d->s.iq_lim, d->s.clamp_seen;
  ensures inv: DRV_PI(&d->s.pi_speed) && DRV_FW(&d->s.fw) && DRV_TC(&d->s.tc);
*/
static void drv_closed_refs(qfoc_drive_t *d)
{
    qfoc_drive_slow_t *const s = &d->s;
    const qfoc_drive_cfg_t *const c = &d->p->drive;
    const uint8_t sub = s->sm.sub;
    const qfoc_q15_t stop_speed = qfoc_q15_abs(c->of_speed);
    qfoc_q15_t target = s->speed_ref;
    if (sub == QFOC_SUB_STOPPING) {
        target = stop_speed;
    } else if ((s->sm.t_state >= c->cl_hold_ms) || s->caught) {
        target = s->speed_target;
    } else {
        /* the 2 s of specs/equations.md section 8.3: hold the handover speed */
    }
    s->speed_ref = qfoc_ramp_toward(s->speed_ref, target, c->speed_ramp);
    const uint8_t clamps = d->f.clamp_count;
    /* the speed loop within the q limit of the last tick's d reference */
    qfoc_pi_set_limit(&s->pi_speed, s->iq_lim);
    s->iq_ref = qfoc_pi_step(&s->pi_speed, qfoc_q15_sub(s->speed_ref, d->f.speed_f));
    drv_iref(d);
    if (clamps == s->clamp_seen) {
        /* no period of the last millisecond hit the current limit: learn (a clamped
           feed-forward would wind the coefficients up, trqcomp.h) */
        qfoc_trqcomp_learn(&s->tc, d->f.theta_m, qfoc_q15_sub(s->speed_ref, d->f.speed),
                           d->f.speed_f);
    } else {
        /* limited: hold the coefficients */
    }
    s->clamp_seen = clamps;
}

/* References of the running sub-states, speed loop and torque compensation
   (REQ-DRV-006, REQ-DRV-009). */
/*@
  requires valid: \valid(d) && \valid_read(d->p);
  requires sep: \separated(&d->s, d->p);
  requires inv: DRV_PI(&d->s.pi_speed) && DRV_FW(&d->s.fw) && DRV_TC(&d->s.tc);
  assigns d->s.pi_speed.integ, d->s.pi_speed.limited, d->s.pi_speed.params.out_min,
          d->s.pi_speed.params.out_max, d->s.fw.pi.integ, d->s.fw.pi.limited,
          d->s.fw.util_lpf.state, d->s.fw.id_ref, d->s.tc, d->s.speed_ref, d->s.ol_speed,
          d->s.id_ref, d->s.iq_ref, d->s.iq_lim, d->s.dt_u, d->s.dt_u0, d->s.dt_u1,
          d->s.clamp_seen;
  ensures inv: DRV_PI(&d->s.pi_speed) && DRV_FW(&d->s.fw) && DRV_TC(&d->s.tc);
*/
static void drv_run(qfoc_drive_t *d)
{
    qfoc_drive_slow_t *const s = &d->s;
    const uint8_t sub = s->sm.sub;
    if ((s->sm.state != QFOC_STATE_RUN) || (sub == QFOC_SUB_CATCH)) {
        /* nothing runs; CATCH keeps the zero references and the zero q limit of RUN
           entry (zero-current control, REQ-DRV-027) */
    } else if (sub == QFOC_SUB_ALIGN) {
        qfoc_drive_start_align(d);
    } else if (sub == QFOC_SUB_OPEN_LOOP) {
        qfoc_drive_start_open_loop(s, d->p);
    } else {
        drv_closed_refs(d);
    }
}

/* Status for the LIN response and the CAN frame (REQ-DRV-011). */
/*@
  requires valid: \valid(d) && \valid_read(d->p) && \valid_read(in);
  requires sep: \separated(&d->s, d->p) && \separated(&d->s, in);
  assigns d->s.status;
*/
static void drv_status(qfoc_drive_t *d, const qfoc_tick_in_t *in)
{
    qfoc_status_t *const st = &d->s.status;
    const qfoc_param_table_t *const p = d->p;
    const uint32_t v_dv_per_lsb = p->v_base_mv / 100u;   /* 0.1 V per V_base */
    const uint32_t i_ca_per_lsb = p->i_base_ma / 10u;    /* 0.01 A per I_base */
    const uint32_t vdc = (d->f.vdc > 0) ? (uint32_t)d->f.vdc : 0u;
    const uint32_t imag = (uint32_t)qfoc_vec_mag(d->f.i_dq.d, d->f.i_dq.q);
    const uint32_t vk = (v_dv_per_lsb > 65535u) ? 65535u : v_dv_per_lsb;
    const uint32_t ik = (i_ca_per_lsb > 65535u) ? 65535u : i_ca_per_lsb;
    st->state = d->s.sm.state;
    st->substate = d->s.sm.sub;
    st->faults = d->s.sm.faults;
    /* the estimate has no input while the PWM is off: 0 unless the control ran */
    st->speed_rpm = d->f.active ? drv_speed_to_rpm(d->f.speed_f, p->drive.k_speed_rpm) : 0u;
    st->vdc_dv = drv_scale(vdc, vk);
    st->current_ca = drv_scale(imag, ik);
    st->temp_dc = (in->t_ipm > in->t_pcb) ? in->t_ipm : in->t_pcb;
}

/* The table re-check (REQ-DRV-010), one step of qfoc_params_scan_step() a tick at
   ms100 = 94 .. 98: four quarters of the CRC, then identity, CRC and ranges; a failed
   verdict clears table_ok for good.  Called on the ticks before the 100 ms job only. */
/*@
  requires valid: \valid(d) && \valid_read(d->p);
  requires sep: \separated(&d->s, d->p);
  requires before_job: d->s.ms100 < DRV_MS100_LAST;
  assigns d->s.table_ok, d->s.scan_crc;
  ensures kept: !\old(d->s.table_ok) ==> !d->s.table_ok;
*/
static void drv_table_scan(qfoc_drive_t *d)
{
    qfoc_drive_slow_t *const s = &d->s;
    if (s->ms100 >= DRV_SCAN_FIRST) {
        const int32_t st = qfoc_params_scan_step(&s->scan_crc, d->p,
                                                 (uint8_t)(s->ms100 - DRV_SCAN_FIRST));
        if (st != QFOC_PARAMS_BUSY) {
            s->table_ok = s->table_ok && (st == QFOC_PARAMS_OK);
        } else {
            /* the scan goes on */
        }
    } else {
        /* no step of the scan in this tick */
    }
}

/* The 100 ms job (formerly Ms_100_job, REQ-DRV-011, REQ-DRV-012): CAN status frame with
   the alternating identifier, motorParaChange. */
/*@
  requires valid: \valid(d) && \valid_read(d->p);
  requires sep: \separated(&d->s, d->p);
  requires inv: DRV_LINK(&d->s.link);
  assigns d->s.hs, d->s.link.can_b, d->s.out.can, d->s.out.can_send;
  ensures inv: DRV_LINK(&d->s.link);
*/
static void drv_job_100ms(qfoc_drive_t *d)
{
    qfoc_drive_slow_t *const s = &d->s;
    const qfoc_param_table_t *const p = d->p;
    const qfoc_q15_t w = qfoc_q15_abs(d->f.speed_f);
    const qfoc_q15_t hs_on = qfoc_q15_abs(p->drive.para_speed);
    const qfoc_q15_t hs_off = (qfoc_q15_t)((int32_t)hs_on - ((int32_t)hs_on / DRV_HS_HYST_DIV));
    qfoc_can_status(&s->link, &s->status, &s->out.can);
    s->out.can_send = true;
    if (w > hs_on) {
        s->hs = true;
    } else if (w < hs_off) {
        s->hs = false;
    } else {
        /* hysteresis band: keep */
    }
}

/* The state machine on this tick's inputs (sm.h); the drive's copy of its invariant is
   the expanded form, the module's own contract gives the transition rules. */
/*@
  requires valid: \valid(s);
  requires inv: DRV_SM(&s->sm);
  assigns s->sm;
  ensures inv: DRV_SM(&s->sm);
  ensures error_exit: \old(s->sm.state) == QFOC_STATE_ERROR && s->sm.state != QFOC_STATE_ERROR ==>
      s->sm.state == QFOC_STATE_STOP;
  ensures run_entry: \old(s->sm.state) != QFOC_STATE_RUN && s->sm.state == QFOC_STATE_RUN ==>
      \old(s->sm.state) == QFOC_STATE_STOP && s->sm.sub == QFOC_SUB_CATCH;
*/
static void drv_sm_step(qfoc_drive_slow_t *s)
{
    qfoc_sm_step(&s->sm, &s->sm_cfg, &s->sm_in);
}

/* The actions of a state or sub-state change, when there is one. */
/*@
  requires valid: \valid(d) && \valid_read(d->p);
  requires sep: \separated(&d->s, d->p);
  requires inv: DRV_PI(&d->s.pi_speed) && DRV_FW(&d->s.fw) && DRV_TC(&d->s.tc);
  assigns d->s.pi_speed.integ, d->s.pi_speed.limited, d->s.fw.pi.integ, d->s.fw.pi.limited,
          d->s.fw.util_lpf.state, d->s.fw.id_ref, d->s.tc, d->s.speed_ref, d->s.ol_speed,
          d->s.id_ref, d->s.iq_ref, d->s.iq_lim, d->s.dt_dv, d->s.dt_learn, d->s.dt_u, d->s.dt_u0,
          d->s.dt_u1, d->s.clear_seq,
          d->s.run_ms, d->s.catch_st, d->s.caught,
          d->s.calib_done;
  ensures inv: DRV_PI(&d->s.pi_speed) && DRV_FW(&d->s.fw) && DRV_TC(&d->s.tc);
*/
static void drv_transition(qfoc_drive_t *d, uint8_t old_state, uint8_t old_sub)
{
    if ((d->s.sm.state != old_state) || (d->s.sm.sub != old_sub)) {
        drv_on_transition(d, old_state, old_sub);
    } else {
        /* no change */
    }
}

/* Run-time counter (Motor_Run_Time), ms in RUN, saturating. */
/*@
  requires valid: \valid(s);
  assigns s->run_ms;
*/
static void drv_count_run(qfoc_drive_slow_t *s)
{
    if ((s->sm.state == QFOC_STATE_RUN) && (s->run_ms < 0xFFFFFFFFu)) {
        s->run_ms = s->run_ms + 1u;
    } else {
        /* not running, or saturated */
    }
}

/* The status answer to an accepted command frame (REQ-LINK). */
/*@
  requires valid: \valid(s);
  requires none: s->out.tx_len == 0;
  assigns s->out;
  ensures tx: s->out.tx_len == 0 || s->out.tx_len == QFOC_LIN_STATUS_LEN;
*/
static void drv_answer(qfoc_drive_slow_t *s, bool accepted)
{
    if (accepted) {
        s->out.tx_len = qfoc_lin_encode_status(&s->link.cfg, &s->status, s->out.tx);
    } else {
        /* answer valid command frames only */
    }
}

/* The 100 ms period: the table check on its ticks 94 .. 98, the job on the last. */
/*@
  requires valid: \valid(d) && \valid_read(d->p);
  requires sep: \separated(&d->s, d->p);
  requires inv: DRV_LINK(&d->s.link);
  assigns d->s.ms100, d->s.table_ok, d->s.scan_crc, d->s.hs, d->s.link.can_b, d->s.out.can,
          d->s.out.can_send;
  ensures inv: DRV_LINK(&d->s.link);
*/
static void drv_ms100(qfoc_drive_t *d)
{
    /* the job and the scan never share a tick: on separate branches, the bound of the
       tick's longest path (tools/bench/wcet.py) counts the longer of the two only */
    if (d->s.ms100 >= DRV_MS100_LAST) {
        d->s.ms100 = 0u;
        drv_job_100ms(d);
    } else {
        drv_table_scan(d);
        d->s.ms100 = (uint8_t)(d->s.ms100 + 1u);
    }
}

/* The received frame through the command link, and the command it holds (REQ-DRV-009,
   REQ-DRV-015). */
/*@
  requires valid: \valid(s);
  requires valid_rx: \valid_read(rx + (0 .. rx_len - 1));
  requires sep: \separated(s, rx + (0 .. rx_len - 1));
  requires inv: DRV_LINK(&s->link);
  assigns s->link, s->cmd;
  ensures inv: DRV_LINK(&s->link);
*/
static bool drv_link_in(qfoc_drive_slow_t *s, const uint8_t *rx, uint8_t rx_len)
{
    const bool accepted = qfoc_link_service(&s->link, rx, rx_len);

    qfoc_link_command(&s->link, &s->cmd);
    return accepted;
}

/* The state machine's inputs of this tick (REQ-DRV-008, REQ-DRV-009). */
/*@
  requires valid: \valid(d) && \valid_read(d->p);
  requires sep: \separated(d, d->p);
  assigns d->s.sm_in, d->s.db_ho, d->s.catch_st;
*/
static void drv_sm_inputs(qfoc_drive_t *d, uint16_t faults, uint8_t old_state,
                          uint8_t old_sub)
{
    qfoc_drive_slow_t *const s = &d->s;
    const qfoc_param_table_t *const p = d->p;
    const qfoc_drive_cfg_t *const c = &p->drive;
    qfoc_q15_t of_speed;

    s->sm_in.faults = faults;
    s->sm_in.bus_ok = !qfoc_fault_under(d->f.vdc, p->vdc_uv);
    s->sm_in.calib_done = s->calib_done;
    /* the link passes power_on only while it is not lost (link.h) */
    s->sm_in.run_request = s->cmd.power_on && (s->cmd.target_rpm >= c->rpm_min) &&
                           s->calib_done;
    s->sm_in.link_lost = qfoc_link_lost(&s->link);
    s->sm_in.fault_clear = s->cmd.fault_clear;
    s->sm_in.table_ok = s->table_ok;
    s->sm_in.converged = qfoc_drive_start_converged(s, &d->f, p,
                                                    (old_state == QFOC_STATE_RUN) &&
                                                    (old_sub == QFOC_SUB_OPEN_LOOP));
    of_speed = qfoc_q15_abs(c->of_speed);
    s->sm_in.stop_reached = (old_sub == QFOC_SUB_STOPPING) && (s->speed_ref <= of_speed);
    /* flying start (REQ-DRV-027): CATCH's verdict on the zero-current loops' voltage and
       the observer, caught between the handover speed and speed_max */
    {
        uint8_t v = QFOC_CATCH_WAIT;
        if ((old_state == QFOC_STATE_RUN) && (old_sub == QFOC_SUB_CATCH)) {
            qfoc_catch_cfg_t k;
            k.psi_f = p->psi_f;
            k.psi_tol = c->flux_tol;
            k.v_err = c->flux_v_err;
            k.w_min = of_speed;
            k.w_max = p->speed_max;
            k.psi_shift = c->psi_shift;
            v = qfoc_catch_step(&s->catch_st,
                                qfoc_vec_mag(d->f.u_last.alpha, d->f.u_last.beta),
                                d->f.speed_f, d->f.psi_mag, &k, c->ho_dwell_ms);
        } else {
            /* not looking */
        }
        s->sm_in.catch_lock = (v == QFOC_CATCH_LOCK);
        s->sm_in.catch_still = (v == QFOC_CATCH_STILL);
    }
}

/* Thermal derating (REQ-DRV-024): the commanded speed within the lower of the two
   temperatures' limits, each rpm_max up to its derating temperature and falling linearly to
   rpm_derate at its trip (qfoc_iref_derate); s->derated says that a limit is below rpm_max.
   A target of 0 stays 0 and one at or above rpm_min stays at or above rpm_derate >=
   rpm_min. */
/*@
  requires valid: \valid(s) && \valid_read(c) && \valid_read(in);
  requires sep: \separated(s, c) && \separated(s, in);
  assigns s->derated;
  ensures below: \result <= s->cmd.target_rpm;
*/
static uint16_t drv_derate(qfoc_drive_slow_t *s, const qfoc_drive_cfg_t *c,
                           const qfoc_tick_in_t *in)
{
    const uint16_t lim_ipm = qfoc_iref_derate(c->rpm_max, c->rpm_derate, in->t_ipm,
                                              c->t_ipm_derate, c->t_ipm_max);
    const uint16_t lim_pcb = qfoc_iref_derate(c->rpm_max, c->rpm_derate, in->t_pcb,
                                              c->t_pcb_derate, c->t_pcb_max);
    const uint16_t lim = (lim_ipm < lim_pcb) ? lim_ipm : lim_pcb;
    const uint16_t rpm = s->cmd.target_rpm;
    s->derated = (lim < c->rpm_max);
    return (rpm < lim) ? rpm : lim;
}

/* The tick's first half: the command link, the faults, the offset calibration and the
   state machine's inputs (REQ-DRV-005, REQ-DRV-008, REQ-DRV-009); the state machine
   itself is not stepped. */
/*@
  requires valid: \valid(d) && \valid_read(in);
  requires rx: in->rx_len > 0 ==> \valid_read(in->rx + (0 .. in->rx_len - 1));
  requires sep: \separated(d, in) &&
                (in->rx_len > 0 ==> \separated(d, in->rx + (0 .. in->rx_len - 1)));
  requires inv: DRV_VALID(d);
  assigns d->s;
  ensures inv_table: DrvTableOk(d);
  ensures inv_fast: DRV_FAST(&d->f);
  ensures inv_modules: DRV_SM(&d->s.sm) && DRV_PI(&d->s.pi_speed) && DRV_FW(&d->s.fw) &&
                       DRV_TC(&d->s.tc);
  ensures inv_link: DRV_LINK(&d->s.link);
  ensures inv_offsets: d->s.offset_u <= 4095 && d->s.offset_v <= 4095 && DRV_OFF_SUMS(&d->s);
  ensures table: d->p == \old(d->p);
  ensures none: d->s.out.tx_len == 0;
  ensures sm: d->s.sm.state == \old(d->s.sm.state) && d->s.sm.sub == \old(d->s.sm.sub);
*/
static bool drv_tick_in(qfoc_drive_t *d, const qfoc_tick_in_t *in, uint8_t old_state,
                        uint8_t old_sub)
{
    qfoc_drive_slow_t *const s = &d->s;
    const qfoc_param_table_t *const p = d->p;
    const qfoc_drive_cfg_t *const c = &p->drive;
    static const uint8_t no_frame[1] = { 0u };
    const uint8_t *const rx = (in->rx_len > 0u) ? in->rx : no_frame;
    bool accepted;
    uint16_t faults;

    s->out.tx_len = 0u;
    s->out.can_send = false;
    /* command link (formerly Communication_service) */
    accepted = drv_link_in(s, rx, in->rx_len);
    s->speed_target = drv_rpm_to_speed(drv_derate(s, c, in), c->k_rpm, p->speed_max);
    /* faults and the offset calibration */
    faults = qfoc_drive_mon_tick(d, in);
    {
        const uint16_t cal = drv_calibrate(s, &d->f, c,
                                           (old_state == QFOC_STATE_PRECHARGE) &&
                                           (old_sub == QFOC_SUB_CALIB));
        const bool sensor = qfoc_drive_mon_sensor(d);
        const bool timing = qfoc_drive_mon_timing(d);
        if ((cal != 0u) || sensor) {
            faults = (uint16_t)(faults + QFOC_FAULT_OFFSET);
        } else {
            /* the current sensors are plausible */
        }
        if (timing) {
            faults = (uint16_t)(faults + QFOC_FAULT_TIMING);
        } else {
            /* the fast step runs at its rate */
        }
    }
    drv_sm_inputs(d, faults, old_state, old_sub);
    return accepted;
}

/* Voltage utilisation of a command, |v| / (V_dc / sqrt 3) in Q15 (REQ-DRV-006): |v| sqrt 3
   / V_dc rounded (sqrt 3 in Q15: 56756), the bus at least vdc_min and 1, at most 32767;
   the formula of qfoc_svpwm_step() for a vector inside the linear range. */
/*@
  requires valid: \valid_read(v);
  assigns \nothing;
  ensures range: 0 <= \result <= 32767;
*/
static qfoc_q15_t drv_utilisation(const qfoc_ab_t *v, qfoc_q15_t vdc, qfoc_q15_t vdc_min)
{
    /* |v| in [0, 32767]: |v| 56756 + 16383 < 2^31 */
    const int32_t mag = (int32_t)qfoc_vec_mag(v->alpha, v->beta);
    int32_t bus = (int32_t)vdc;
    int32_t u;
    if (bus < (int32_t)vdc_min) {
        bus = (int32_t)vdc_min;
    } else {
        /* the bus above its minimum */
    }
    if (bus < 1) {
        bus = 1;
    } else {
        /* a positive bus */
    }
    u = ((mag * 56756) + (bus / 2)) / bus;
    if (u > 32767) {
        u = 32767;
    } else {
        /* inside the linear range */
    }
    return (qfoc_q15_t)u;
}

/* Ticks per pass of the RAM check: a quarter of the drive object a tick. */
#define DRV_CHECK_SLICES ((uint8_t)4u)

/* One quarter of the RAM check (REQ-DRV-019): slice k of the drive invariant, and in the
   last slice two relations the invariant does not state: the calibrated offsets lie within
   offset_window of mid-scale (drv_calibrate stores no other) and the PLL's angle gain and the observer's constants are
   the table's (only the init writes it). */
/*@
  requires valid: \valid_read(d) && \valid_read(d->p) && \separated(d, d->p);
  requires slice: k < DRV_CHECK_SLICES;
  assigns \nothing;
*/
static bool drv_object_slice(const qfoc_drive_t *d, uint8_t k)
{
    bool ok;
    if (k == 0u) {
        const bool flux = qfoc_flux_is_valid(&d->f.flux);
        const bool pll = qfoc_pll_is_valid(&d->f.pll);
        const bool vdc = qfoc_lpf_is_valid(&d->f.vdc_lpf);
        ok = flux && pll && vdc;
    } else if (k == 1u) {
        const bool pid = qfoc_pi_is_valid(&d->f.pi_id);
        const bool piq = qfoc_pi_is_valid(&d->f.pi_iq);
        const bool ph = qfoc_phase_mon_is_valid(&d->f.phase);
        const bool mech = qfoc_mech_is_valid(&d->f.mech);
        ok = pid && piq && ph && mech;
    } else if (k == 2u) {
        const bool sm = qfoc_sm_is_valid(&d->s.sm);
        const bool pis = qfoc_pi_is_valid(&d->s.pi_speed);
        const bool fw = qfoc_fw_is_valid(&d->s.fw);
        const bool tc = qfoc_trqcomp_is_valid(&d->s.tc);
        const bool link = qfoc_link_is_valid(&d->s.link);
        ok = sm && pis && fw && tc && link;
    } else {
        const qfoc_drive_slow_t *const s = &d->s;
        const int32_t win = (int32_t)d->p->drive.offset_window;
        const int32_t du = (int32_t)s->offset_u - (int32_t)QFOC_ADC_MID;
        const int32_t dv = (int32_t)s->offset_v - (int32_t)QFOC_ADC_MID;
        /* off_n <= 1024 < 65536: 4095 x off_n fits in 32 bits */
        const bool sums = (s->off_n <= 1024u) &&
                          (s->off_sum_u <= (4095u * (uint32_t)s->off_n)) &&
                          (s->off_sum_v <= (4095u * (uint32_t)s->off_n));
        const bool offsets = (du <= win) && (du >= -win) && (dv <= win) && (dv >= -win);
        /* the table's constants the fast half holds a copy of: the PLL's angle gain and
           the observer's gain, resistance and back-EMF scale (its inductance follows the
           inductance set the fast step selects, and is not compared) */
        const bool copies = (d->f.pll.k_theta == d->p->pll.k_theta) &&
                            (d->f.flux.params.r == d->p->flux.r) &&
                            (d->f.flux.params.kg == d->p->flux.kg) &&
                            (d->f.flux.params.gain == d->p->flux.gain) &&
                            (d->f.flux.params.gain_shift == d->p->flux.gain_shift);
        ok = sums && offsets && copies;
    }
    return ok;
}

/* Bias of the reference guard (REQ-DRV-022, DRV_REF_GUARD of specs/drive.acsl): it makes
   the sum of the seven references non-negative (7 x 32768 <= 239013) and the guard of an
   object of zeros (42405) other than 0. */
#define DRV_GUARD_BIAS ((int32_t)239013)
/* The guard of seven references at 0 (the reset values): 239013 modulo 2^16. */
#define DRV_GUARD_ZERO ((uint16_t)42405u)

/* The guard word of the tick's seven references (REQ-DRV-022): their sum with the bias,
   modulo 2^16, which a single flipped bit of any of them changes. */
/*@
  requires valid: \valid_read(s);
  assigns \nothing;
  ensures guard: \result == DRV_REF_GUARD(s);
*/
static uint16_t drv_ref_guard(const qfoc_drive_slow_t *s)
{
    /* seven terms in [-32768, 32767]: the sum with the bias in [9637, 468382] */
    const int32_t sum = (int32_t)s->speed_target + (int32_t)s->speed_ref + (int32_t)s->ol_speed +
                        (int32_t)s->id_ref + (int32_t)s->iq_ref + (int32_t)s->iq_lim +
                        (int32_t)s->dt_dv + DRV_GUARD_BIAS;
    return (uint16_t)((uint32_t)sum % 65536u);
}

/* The drive object in RAM against its invariant, a quarter of it at the start of every
   tick, the whole in 4 ticks (REQ-DRV-019): a random hardware fault (a flipped RAM bit, a
   stray write) that breaks the invariant or the two relations checked with it clears
   table_ok for good, so that tick raises PARAM and enters ERROR and the next fast step
   turns the PWM off.  The window check of the last slice also covers the invariant's
   offset_u, offset_v <= 4095 (offset_window is at most QFOC_DRIVE_OFFSET_WINDOW_MAX = 2047,
   and 2048 + 2047 = 4095).  Under the tick's precondition the invariant holds; the check is the
   run-time monitor of what the proof assumes of the hardware.  Reading the fast step's
   half while it may pre-empt is sound: every relation checked bounds one field the fast
   step writes by constants of the table or by fields only the tick or the init write, so
   a mix of two periods' values passes.  Every tick also checks the guard word of the
   seven references against their values (REQ-DRV-022): only the tick and the init write
   them, and both leave the guard matching (ensures guard), so a mismatch at the start of
   a tick is a change since the last tick that no code made; it clears table_ok the same
   way, before any of the seven is used. */
/*@
  requires valid: \valid(d) && \valid_read(d->p) && \separated(d, d->p);
  assigns d->s.table_ok;
  ensures kept: !\old(d->s.table_ok) ==> !d->s.table_ok;
  ensures guard: !DRV_GUARD_OK(d) ==> !d->s.table_ok;
*/
static void drv_object_check(qfoc_drive_t *d)
{
    const uint8_t k = (uint8_t)(d->s.ms100 % DRV_CHECK_SLICES);
    const bool refs = (d->s.ref_guard == drv_ref_guard(&d->s));
    const bool slice = drv_object_slice(d, k);

    if (!(refs && slice)) {
        d->s.table_ok = false;
    } else {
        /* this quarter of the drive object is intact */
    }
}

/* The tick's second half: the state machine step and its transition, the speed loop,
   the status, the answer frame and the 100 ms period (REQ-DRV-005, REQ-DRV-006,
   REQ-DRV-010, REQ-DRV-011). */
/*@
  requires valid: \valid(d) && \valid_read(in);
  requires sep: \separated(d, in);
  requires inv: DRV_VALID(d);
  requires none: d->s.out.tx_len == 0;
  requires sm: old_state == d->s.sm.state && old_sub == d->s.sm.sub;
  assigns d->s;
  ensures inv: DRV_VALID(d);
  ensures table: d->p == \old(d->p);
  ensures tx: d->s.out.tx_len == 0 || d->s.out.tx_len == QFOC_LIN_STATUS_LEN;
  ensures error_exit: old_state == QFOC_STATE_ERROR &&
      d->s.sm.state != QFOC_STATE_ERROR ==> d->s.sm.state == QFOC_STATE_STOP;
  ensures run_entry: old_state != QFOC_STATE_RUN && d->s.sm.state == QFOC_STATE_RUN ==>
      old_state == QFOC_STATE_STOP && d->s.sm.sub == QFOC_SUB_CATCH;
  ensures pwm_off: d->s.out.pwm_off == \true <==> d->s.sm.state != QFOC_STATE_RUN;
  ensures guard: DRV_GUARD_OK(d);
*/
static void drv_tick_out(qfoc_drive_t *d, const qfoc_tick_in_t *in, uint8_t old_state,
                         uint8_t old_sub, bool accepted)
{
    qfoc_drive_slow_t *const s = &d->s;

    drv_sm_step(s);
    drv_transition(d, old_state, old_sub);
    drv_run(d);
    /* the learnt inverter error as the fast step's observer uses it at this speed: whole up
       to twice the handover speed, none from four times (REQ-DRV-026); 0 outside RUN */
    {
        const int32_t w_full = 2 * (int32_t)qfoc_q15_abs(d->p->drive.of_speed);
        qfoc_q15_t w = s->speed_ref;
        if (s->sm.sub == QFOC_SUB_OPEN_LOOP) {
            w = s->ol_speed;
        } else {
            /* the speed reference */
        }
        s->dt_dv = qfoc_dtc_speed_fade(s->dt_learn, w, qfoc_q15_sat(w_full));
    }
    /* the observer's phase lead at the present speed, for the fast step's rotor angle */
    s->lead = drv_lead(&d->f, d->p);
    /* the voltage utilisation of the last command, for the fast step's field weakening */
    s->util = drv_utilisation(&d->f.u_last, d->f.vdc, d->p->svpwm.vdc_min);
    drv_count_run(s);
    drv_status(d, in);
    drv_answer(s, accepted);
    drv_ms100(d);
    /* the second path to the safe state: the port turns the inverter off at once */
    s->out.pwm_off = (s->sm.state != QFOC_STATE_RUN);
    /* the references of this tick under their guard, checked at the next tick */
    s->ref_guard = drv_ref_guard(s);
}

qfoc_tick_out_t qfoc_drive_tick(qfoc_drive_t *d, const qfoc_tick_in_t *in)
{
    const uint8_t old_state = d->s.sm.state;
    const uint8_t old_sub = d->s.sm.sub;
    bool accepted;

    drv_object_check(d);
    accepted = drv_tick_in(d, in, old_state, old_sub);
    drv_tick_out(d, in, old_state, old_sub, accepted);
    return d->s.out;
}

/* ================================================================== init */

/* The fast step's modules from the table, two at a time (REQ-DRV-001): every module's
   init establishes its own invariant whatever the table holds (a refused block gets the
   module's safe values). */
/*@
  requires valid: \valid(f) && \valid_read(p);
  requires sep: \separated(f, p);
  assigns f->flux, f->pll;
  ensures inv: DRV_FLUX(&f->flux) && DRV_PLL(&f->pll);
*/
static void drv_init_estimator(qfoc_drive_fast_t *f, const qfoc_param_table_t *p)
{
    (void)qfoc_flux_init(&f->flux, &p->flux);
    (void)qfoc_pll_init(&f->pll, &p->pll);
}

/*@
  requires valid: \valid(f) && \valid_read(p);
  requires sep: \separated(f, p);
  assigns f->pi_id, f->pi_iq;
  ensures inv: DRV_PI(&f->pi_id) && DRV_PI(&f->pi_iq);
*/
static void drv_init_current(qfoc_drive_fast_t *f, const qfoc_param_table_t *p)
{
    (void)qfoc_pi_init(&f->pi_id, &p->pi_id);
    (void)qfoc_pi_init(&f->pi_iq, &p->pi_iq);
}

/*@
  requires valid: \valid(f) && \valid_read(p);
  requires sep: \separated(f, p);
  assigns f->vdc_lpf;
  ensures inv: DRV_LPF(&f->vdc_lpf);
*/
static void drv_init_vdc(qfoc_drive_fast_t *f, const qfoc_param_table_t *p)
{
    (void)qfoc_lpf_init(&f->vdc_lpf, p->alpha_vdc);
}

/*@
  requires valid: \valid(f) && \valid_read(p);
  requires sep: \separated(f, p);
  assigns f->phase, f->phase_k, f->sub_last, f->mech;
  ensures inv: DRV_PHASE(&f->phase) && DRV_MECH(&f->mech);
*/
static void drv_init_monitors(qfoc_drive_fast_t *f, const qfoc_param_table_t *p)
{
    /* each phase is filtered every third period: the coefficient for that rate */
    (void)qfoc_phase_mon_init(&f->phase, qfoc_phase_mon_alpha3(p->drive.phase_alpha));
    f->phase_k = 0u;
    f->sub_last = QFOC_SUB_NONE;
    (void)qfoc_mech_init(&f->mech, p->drive.pole_pairs, 0u);
}

/* Fast-step data from the table (REQ-DRV-001). */
/*@
  requires valid: \valid(f) && \valid_read(p);
  requires sep: \separated(f, p);
  assigns *f;
  ensures inv: DRV_FAST(f);
*/
static void drv_init_fast(qfoc_drive_fast_t *f, const qfoc_param_table_t *p)
{
    const qfoc_ab_t zero = { 0, 0 };
    drv_init_estimator(f, p);
    drv_init_current(f, p);
    drv_init_vdc(f, p);
    drv_init_monitors(f, p);
    f->u_last = zero;
    f->u_applied = zero;
    f->theta_ol = 0u;
    f->i_dq.d = 0;
    f->i_dq.q = 0;
    f->vdc = 0;
    f->adc_iu = QFOC_ADC_MID;
    f->adc_iv = QFOC_ADC_MID;
    f->theta_est = 0u;
    f->theta_m = 0u;
    f->speed = 0;
    f->speed_f = 0;
    f->psi_mag = 0;
    f->trip_count = 0u;
    f->clamp_count = 0u;
    f->clear_ack = 0u;
    f->trip = false;
    f->active = false;
    f->hs = false;
    f->i_abc.u = 0;
    f->i_abc.v = 0;
    f->i_abc.w = 0;
    f->same_u = 0u;
    f->same_v = 0u;
    f->n_fast = 0u;
    drv_pwm_off(&f->out);
}

/* The tick's references, counters, link buffers and state-machine inputs at their reset
   values (REQ-DRV-001); a part of drv_init_slow() of its own, so that the invariant
   drv_init_slow() establishes is proved over a short sequence of updates. */
/*@
  requires valid: \valid(s) && \valid_read(c);
  requires sep: \separated(s, c);
  assigns s->speed_target, s->speed_ref, s->ol_speed, s->id_ref, s->iq_ref, s->iq_lim, s->dt_dv,
          s->dt_learn, s->dt_u, s->dt_u0, s->dt_u1, s->lead, s->util, s->trip_seen, s->clamp_seen, s->clear_seq, s->ms100,
          s->scan_crc, s->calib_done,
          s->hs, s->derated, s->run_ms, s->status, s->cmd, s->sm_cfg, s->sm_in, s->out,
          s->fast_seen, s->ref_guard;
  ensures refs: s->speed_target == 0 && s->speed_ref == 0 && s->ol_speed == 0 &&
                s->id_ref == 0 && s->iq_ref == 0 && s->iq_lim == 0 && s->dt_dv == 0 &&
                s->ref_guard == 42405;
*/
static void drv_init_slow_io(qfoc_drive_slow_t *s, const qfoc_drive_cfg_t *c)
{
    uint32_t k;

    s->speed_target = 0;
    s->speed_ref = 0;
    s->ol_speed = 0;
    s->id_ref = 0;
    s->iq_ref = 0;
    s->iq_lim = 0;
    s->dt_dv = 0;
    s->dt_learn = 0;
    s->dt_u = 0;
    s->dt_u0 = 0;
    s->dt_u1 = 0;
    s->lead = 0u;
    s->util = 0;
    s->trip_seen = 0u;
    s->clamp_seen = 0u;
    s->clear_seq = 0u;
    s->ms100 = 0u;
    s->scan_crc = 0u;
    s->calib_done = false;
    s->hs = false;
    s->derated = false;
    s->run_ms = 0u;
    s->status.state = QFOC_STATE_PRECHARGE;
    s->status.substate = QFOC_SUB_BUS_WAIT;
    s->status.faults = 0u;
    s->status.speed_rpm = 0u;
    s->status.vdc_dv = 0u;
    s->status.current_ca = 0u;
    s->status.temp_dc = 0;
    s->cmd.power_on = false;
    s->cmd.fault_clear = false;
    s->cmd.target_rpm = 0u;
    s->cmd.identify = false;
    s->sm_cfg.precharge_ms = c->precharge_ms;
    s->sm_cfg.align_ms = c->align_ms;
    s->sm_cfg.ol_timeout_ms = c->ol_timeout_ms;
    s->sm_cfg.cl_hold_ms = c->cl_hold_ms;
    s->sm_cfg.clear_ms = c->clear_ms;
    s->sm_cfg.retries = c->ho_retries;
    s->sm_in.faults = 0u;
    s->sm_in.bus_ok = false;
    s->sm_in.calib_done = false;
    s->sm_in.run_request = false;
    s->sm_in.link_lost = false;
    s->sm_in.fault_clear = false;
    s->sm_in.table_ok = false;
    s->sm_in.converged = false;
    s->sm_in.stop_reached = false;
    /*@ loop invariant k: 0 <= k <= QFOC_LIN_FRAME_MAX;
        loop assigns k, s->out.tx[0 .. QFOC_LIN_FRAME_MAX - 1];
        loop variant QFOC_LIN_FRAME_MAX - k; */
    for (k = 0u; k < QFOC_LIN_FRAME_MAX; k++) {
        s->out.tx[k] = 0u;
    }
    s->out.tx_len = 0u;
    s->out.can.id = c->can_id_a;
    s->out.can.dlc = 0u;
    /*@ loop invariant k: 0 <= k <= 8;
        loop assigns k, s->out.can.data[0 .. 7];
        loop variant 8 - k; */
    for (k = 0u; k < 8u; k++) {
        s->out.can.data[k] = 0u;
    }
    s->out.can_send = false;
    s->out.pwm_off = true;
    s->fast_seen = 0u;
    s->ref_guard = DRV_GUARD_ZERO;
}

/* Field weakening from the table (REQ-DRV-001): a refused block gets fw.h's safe values
   (no field weakening). */
/*@
  requires valid: \valid(s) && \valid_read(p);
  requires sep: \separated(s, p);
  assigns s->fw;
  ensures inv: DRV_FW(&s->fw);
*/
static void drv_init_fw(qfoc_drive_slow_t *s, const qfoc_param_table_t *p)
{
    qfoc_fw_params_t fwp;
    fwp.pi = p->pi_fw;
    fwp.level = p->drive.fw_level;
    fwp.alpha = p->drive.fw_alpha;
    (void)qfoc_fw_init(&s->fw, &fwp);
}

/* The state machine at initialisation: PRECHARGE for an accepted table, ERROR (PARAM)
   for a refused one (REQ-DRV-001, REQ-SM-002). */
/*@
  requires valid: \valid(sm);
  assigns *sm;
  ensures inv: DRV_SM(sm);
  ensures accepted: accepted == \true ==> sm->state == QFOC_STATE_PRECHARGE;
  ensures refused: accepted == \false ==> sm->state == QFOC_STATE_ERROR;
*/
static void drv_init_sm(qfoc_sm_t *sm, bool accepted)
{
    qfoc_sm_init(sm);
    if (!accepted) {
        qfoc_sm_fail(sm, QFOC_FAULT_PARAM);
    } else {
        /* the table passed its check: PRECHARGE */
    }
}

/* Tick data from the table (REQ-DRV-001). */
/*@
  requires valid: \valid(s) && \valid_read(p);
  requires sep: \separated(s, p);
  assigns s->sm, s->pi_speed, s->fw, s->tc, s->db_ov, s->db_uv, s->db_ot_ipm, s->db_ot_pcb,
          s->db_stall, s->db_flux, s->db_phase, s->db_align, s->db_ho, s->catch_st, s->caught,
          s->off_sum_u, s->off_sum_v, s->off_n,
          s->offset_u, s->offset_v, s->speed_target, s->speed_ref, s->ol_speed, s->id_ref,
          s->iq_ref, s->iq_lim, s->dt_dv, s->dt_learn, s->dt_u, s->dt_u0, s->dt_u1, s->lead,
          s->util, s->trip_seen,
          s->clamp_seen,
          s->clear_seq, s->ms100, s->table_ok,
          s->scan_crc, s->calib_done, s->hs, s->derated, s->run_ms, s->status, s->cmd, s->sm_cfg,
          s->sm_in, s->out, s->fast_seen, s->ref_guard;
  ensures refs: s->speed_target == 0 && s->speed_ref == 0 && s->ol_speed == 0 &&
                s->id_ref == 0 && s->iq_ref == 0 && s->iq_lim == 0 && s->dt_dv == 0 &&
                s->ref_guard == 42405;
  ensures inv: DRV_SM(&s->sm) && DRV_PI(&s->pi_speed) && DRV_FW(&s->fw) && DRV_TC(&s->tc) &&
               s->offset_u <= 4095 && s->offset_v <= 4095 && DRV_OFF_SUMS(s);
  ensures accepted: st == QFOC_PARAMS_OK ==>
      s->sm.state == QFOC_STATE_PRECHARGE && s->table_ok;
  ensures refused: st != QFOC_PARAMS_OK ==> s->sm.state == QFOC_STATE_ERROR && !s->table_ok;
*/
static void drv_init_slow(qfoc_drive_slow_t *s, const qfoc_param_table_t *p, int32_t st)
{
    const qfoc_drive_cfg_t *const c = &p->drive;
    qfoc_trqcomp_params_t tcp;

    tcp.gain = c->tc_gain;
    tcp.amp_max = c->tc_amp_max;
    tcp.speed_min = c->tc_speed_min;
    tcp.speed_max = c->tc_speed_max;
    tcp.pole_pairs = c->pole_pairs;
    drv_init_sm(&s->sm, st == QFOC_PARAMS_OK);
    (void)qfoc_pi_init(&s->pi_speed, &p->pi_speed);
    drv_init_fw(s, p);
    (void)qfoc_trqcomp_init(&s->tc, &tcp);
    qfoc_debounce_reset(&s->db_ov);
    qfoc_debounce_reset(&s->db_uv);
    qfoc_debounce_reset(&s->db_ot_ipm);
    qfoc_debounce_reset(&s->db_ot_pcb);
    qfoc_debounce_reset(&s->db_stall);
    qfoc_debounce_reset(&s->db_flux);
    qfoc_debounce_reset(&s->db_phase);
    qfoc_debounce_reset(&s->db_align);
    qfoc_debounce_reset(&s->db_ho);
    qfoc_catch_reset(&s->catch_st);
    s->caught = false;
    s->off_sum_u = 0u;
    s->off_sum_v = 0u;
    s->off_n = 0u;
    s->offset_u = QFOC_ADC_MID;
    s->offset_v = QFOC_ADC_MID;
    s->table_ok = (st == QFOC_PARAMS_OK);
    drv_init_slow_io(s, c);
}

/* The command link from the table's identifiers, speed limit and timeout (REQ-DRV-001). */
/*@
  requires valid: \valid(d) && \valid_read(p);
  requires sep: \separated(d, p);
  assigns d->s.link;
  ensures inv: DRV_LINK(&d->s.link);
*/
static void drv_init_link(qfoc_drive_t *d, const qfoc_param_table_t *p)
{
    const qfoc_drive_cfg_t *const c = &p->drive;
    qfoc_link_cfg_t lc;
    lc.id_cmd = c->lin_id_cmd;
    lc.id_status = c->lin_id_status;
    lc.rpm_max = c->rpm_max;
    lc.timeout_ms = c->link_timeout_ms;
    lc.can_id_a = c->can_id_a;
    lc.can_id_b = c->can_id_b;
    (void)qfoc_link_init(&d->s.link, &lc);
}

int32_t qfoc_drive_init(qfoc_drive_t *d, const qfoc_param_table_t *table)
{
    const int32_t st = qfoc_params_check(table);
    d->p = table;
    drv_init_link(d, table);
    drv_init_slow(&d->s, table, st);
    drv_init_fast(&d->f, table);
    return st;
}

bool qfoc_drive_is_valid(const qfoc_drive_t *d)
{
    const bool flux = qfoc_flux_is_valid(&d->f.flux);
    const bool pll = qfoc_pll_is_valid(&d->f.pll);
    const bool pid = qfoc_pi_is_valid(&d->f.pi_id);
    const bool piq = qfoc_pi_is_valid(&d->f.pi_iq);
    const bool fw = qfoc_fw_is_valid(&d->s.fw);
    const bool vdc = qfoc_lpf_is_valid(&d->f.vdc_lpf);
    const bool ph = qfoc_phase_mon_is_valid(&d->f.phase);
    const bool mech = qfoc_mech_is_valid(&d->f.mech);
    const bool sm = qfoc_sm_is_valid(&d->s.sm);
    const bool pis = qfoc_pi_is_valid(&d->s.pi_speed);
    const bool tc = qfoc_trqcomp_is_valid(&d->s.tc);
    const bool link = qfoc_link_is_valid(&d->s.link);
    const bool offs = (d->s.offset_u <= QFOC_ADC_MAX) && (d->s.offset_v <= QFOC_ADC_MAX);
    /* off_n <= 1024 < 65536: 4095 x off_n fits in 32 bits */
    const bool sums = (d->s.off_n <= 1024u) &&
                      (d->s.off_sum_u <= (4095u * (uint32_t)d->s.off_n)) &&
                      (d->s.off_sum_v <= (4095u * (uint32_t)d->s.off_n));
    return flux && pll && pid && piq && fw && vdc && ph && mech && sm && pis && tc && link && offs &&
           sums;
}
