/*
 * Stubs of the signal-processing functions for the drive harnesses (drive_sm,
 * drive_frame): each returns ANY value its proved contract allows (ranges only), so the
 * drive's control logic is checked whatever the control computes.  Installed with
 * goto-instrument --replace-calls (the harnesses' config.mk).
 */
#ifndef QFOC_DRIVE_STUBS_H
#define QFOC_DRIVE_STUBS_H

#include "qfoc/drive.h"
#include "qfoc/dtc.h"
#include "qfoc/iref.h"
#include "harness_util.h"

/* DRIVE_STUBS_PURE (drive_frame): every stub returns values fixed once per run by
   stubs_fix(), the same for every call, so two runs from the same state compute the same
   things (the stubs are then arbitrary but deterministic functions).  Otherwise every
   call returns fresh values. */
#ifdef DRIVE_STUBS_PURE
static int16_t g_s16[4];
static uint16_t g_u16[4];
static uint8_t g_u8;
static bool g_b[2];
static void stubs_fix(void)
{
    unsigned k;
    for (k = 0u; k < 4u; k++) {
        g_s16[k] = nondet_int16();
        g_u16[k] = nondet_uint16();
    }
    g_u8 = nondet_uint8();
    g_b[0] = nondet_bool();
    g_b[1] = nondet_bool();
}
#define ANY_S16(k) (g_s16[(k)])
#define ANY_U16(k) (g_u16[(k)])
#define ANY_U8() (g_u8)
#define ANY_B(k) (g_b[(k)])
#else
#define ANY_S16(k) nondet_int16()
#define ANY_U16(k) nondet_uint16()
#define ANY_U8() nondet_uint8()
#define ANY_B(k) nondet_bool()
#endif


void stub_flux_step(qfoc_flux_t *o, const qfoc_ab_t *u, const qfoc_ab_t *i, qfoc_ab_t *psi_r)
{
    (void)o; (void)u; (void)i;
    psi_r->alpha = ANY_S16(0);
    psi_r->beta = ANY_S16(1);
    __CPROVER_assume(psi_r->alpha >= -32767 && psi_r->beta >= -32767);
}
void stub_pll_step(qfoc_pll_t *pll, const qfoc_ab_t *psi, qfoc_pll_out_t *out)
{
    (void)pll; (void)psi;
    out->theta = ANY_U16(0);
    out->theta_next = ANY_U16(1);
    out->sc.sine = ANY_S16(2);
    out->sc.cosine = ANY_S16(3);
    out->speed = ANY_S16(0);
    out->speed_f = ANY_S16(1);
    out->error = ANY_S16(2);
    out->mag = ANY_S16(3);
    __CPROVER_assume(out->speed >= -32767 && out->speed_f >= -32767 && out->mag >= 0);
}
qfoc_angle_t stub_flux_lead(const qfoc_flux_t *o, qfoc_q15_t w) { (void)o; (void)w; return ANY_U16(2); }
void stub_sincos(qfoc_angle_t theta, qfoc_sincos_t *out)
{
    (void)theta;
    out->sine = ANY_S16(0);
    out->cosine = ANY_S16(1);
    __CPROVER_assume(out->sine >= -32767 && out->cosine >= -32767);
}
void stub_park(const qfoc_ab_t *in, const qfoc_sincos_t *sc, qfoc_dq_t *out)
{
    (void)in; (void)sc;
    out->d = ANY_S16(2);
    out->q = ANY_S16(3);
    __CPROVER_assume(out->d >= -32767 && out->q >= -32767);
}
void stub_clarke(qfoc_q15_t iu, qfoc_q15_t iv, qfoc_ab_t *out)
{
    (void)iu; (void)iv;
    out->alpha = ANY_S16(0);
    out->beta = ANY_S16(1);
    __CPROVER_assume(out->alpha >= -32767 && out->beta >= -32767);
}
void stub_inv_park(const qfoc_dq_t *in, const qfoc_sincos_t *sc, qfoc_ab_t *out)
{
    (void)in; (void)sc;
    out->alpha = ANY_S16(2);
    out->beta = ANY_S16(3);
    __CPROVER_assume(out->alpha >= -32767 && out->beta >= -32767);
}
void stub_svpwm_step(const qfoc_svpwm_cfg_t *cfg, const qfoc_ab_t *v_ab, qfoc_q15_t vdc,
                     const qfoc_abc_t *i_abc, qfoc_svpwm_out_t *out)
{
    (void)v_ab; (void)vdc; (void)i_abc;
    out->cmp[0] = ANY_U16(3);
    out->cmp[1] = ANY_U16(0);
    out->cmp[2] = ANY_U16(1);
    __CPROVER_assume(out->cmp[0] <= cfg->period && out->cmp[1] <= cfg->period &&
                     out->cmp[2] <= cfg->period);
    out->sector = ANY_U8();
    out->utilisation = ANY_S16(0);
    __CPROVER_assume(out->utilisation >= 0);
    out->limited = ANY_B(0);
    out->vdc_low = ANY_B(1);
}
bool stub_circle_limit(const qfoc_dq_t *in, qfoc_q15_t vmax, qfoc_dq_t *out)
{
    (void)in; (void)vmax;
    out->d = ANY_S16(1);
    out->q = ANY_S16(2);
    __CPROVER_assume(out->d >= -32767 && out->q >= -32767);
    return ANY_B(0);
}
qfoc_q15_t stub_pi_step(qfoc_pi_t *pi, qfoc_q15_t error)
{
    const qfoc_q15_t y = ANY_S16(3);
    (void)error;
    __CPROVER_assume(pi->params.out_min <= y && y <= pi->params.out_max);
    return y;
}
void stub_pi_reset(qfoc_pi_t *pi, qfoc_q15_t preset) { (void)pi; (void)preset; }
qfoc_q15_t stub_fw_step(qfoc_fw_t *fw, qfoc_q15_t u, bool enable)
{
    const qfoc_q15_t y = ANY_S16(0);
    (void)fw; (void)u;
    __CPROVER_assume(enable ? (y <= 0 && y >= -16384) : (y == 0));
    return y;
}
void stub_fw_reset(qfoc_fw_t *fw) { (void)fw; }
/* qfoc_iref_step (iref.h): i_d in [-m, 0], the q limit in [0, m], m = max(i_max, 0) */
void stub_iref_step(const qfoc_iref_in_t *in, qfoc_iref_out_t *out)
{
    const int32_t m = (in->i_max > 0) ? (int32_t)in->i_max : 0;
    out->id = ANY_S16(2);
    out->iq_lim = ANY_S16(3);
    __CPROVER_assume(out->id >= -m && out->id <= 0 && out->iq_lim >= 0 && out->iq_lim <= m);
}
/* qfoc_phase_mon_peak (fault.h): in [0, 32767] for a valid monitor */
qfoc_q15_t stub_pm_peak(const qfoc_phase_mon_t *m)
{
    const qfoc_q15_t y = ANY_S16(0);
    (void)m;
    __CPROVER_assume(y >= 0);
    return y;
}
/* qfoc_fault_band_over (fault.h): any verdict */
bool stub_band_over(qfoc_q15_t dev, qfoc_q15_t k, int32_t v, qfoc_q15_t w)
{
    (void)dev; (void)k; (void)v; (void)w;
    return ANY_B(1);
}
/* qfoc_iref_derate (iref.h): in [min(lo, hi), hi] */
uint16_t stub_iref_derate(uint16_t hi, uint16_t lo, int16_t t, int16_t t0, int16_t t1)
{
    const uint16_t r = ANY_U16(3);
    (void)t; (void)t0; (void)t1;
    __CPROVER_assume(r <= hi && r >= ((lo < hi) ? lo : hi));
    return r;
}
/* qfoc_pi_set_limit (pi.h): its contract, linear: limits [-l, l], l = clamp(lim, 0, 32767),
   the integrator clamped into them */
void stub_pi_set_limit(qfoc_pi_t *pi, qfoc_q15_t lim)
{
    const int32_t l = (lim > 0) ? (int32_t)lim : 0;
    pi->params.out_max = (qfoc_q15_t)l;
    pi->params.out_min = (qfoc_q15_t)(-l);
    if (pi->integ > l * 65536) {
        pi->integ = l * 65536;
    } else if (pi->integ < -l * 65536) {
        pi->integ = -l * 65536;
    }
}
qfoc_q15_t stub_lpf_step(qfoc_lpf_t *f, qfoc_q15_t u)
{
    const qfoc_q15_t y = ANY_S16(1);
    (void)f; (void)u;
    __CPROVER_assume(y >= -32767);
    return y;
}
qfoc_q15_t stub_tc_output(const qfoc_trqcomp_t *tc, qfoc_angle_t t, qfoc_q15_t w)
{
    const qfoc_q15_t y = ANY_S16(2);
    (void)tc; (void)t; (void)w;
    __CPROVER_assume(y >= -32767);
    return y;
}
void stub_tc_learn(qfoc_trqcomp_t *tc, qfoc_angle_t t, qfoc_q15_t e, qfoc_q15_t w) { (void)tc; (void)t; (void)e; (void)w; }
void stub_tc_reset(qfoc_trqcomp_t *tc) { (void)tc; }
qfoc_angle_t stub_mech_update(qfoc_mech_t *m, qfoc_angle_t t) { (void)m; (void)t; return ANY_U16(2); }
int32_t stub_mech_init(qfoc_mech_t *m, uint8_t pp, qfoc_angle_t t) { (void)m; (void)pp; (void)t; return 0; }
void stub_pm_update(qfoc_phase_mon_t *m, const qfoc_abc_t *i) { (void)m; (void)i; }
void stub_pm_reset(qfoc_phase_mon_t *m) { (void)m; }
bool stub_pm_imbalanced(const qfoc_phase_mon_t *m, qfoc_q15_t a, qfoc_q15_t b) { (void)m; (void)a; (void)b; return ANY_B(1); }
int32_t stub_params_check(const qfoc_param_table_t *t) { (void)t; return ANY_B(0) ? QFOC_PARAMS_OK : QFOC_PARAMS_ERR_CRC; }
int32_t stub_params_scan_step(uint32_t *crc, const qfoc_param_table_t *t, uint8_t step)
{
    int32_t st = QFOC_PARAMS_BUSY;
    (void)t;
    if (step == (uint8_t)(QFOC_PARAMS_SCAN_STEPS - 1u)) {
        st = ANY_B(0) ? QFOC_PARAMS_OK : QFOC_PARAMS_ERR_CRC;
    } else if (step < QFOC_PARAMS_SCAN_STEPS) {
        *crc = (uint32_t)ANY_U16(1);
    } else {
        /* not a step: nothing */
    }
    return st;
}
qfoc_q15_t stub_vec_mag(qfoc_q15_t x, qfoc_q15_t y)
{
    const qfoc_q15_t m = ANY_S16(3);
    (void)x; (void)y;
    __CPROVER_assume(m >= 0);
    return m;
}
/* qfoc_dtc_learn (dtc.h): in [-m, m], m = max(v_max, 0) */
qfoc_q15_t stub_dtc_learn(const qfoc_dtc_align_t *a)
{
    const qfoc_q15_t y = ANY_S16(1);
    const int32_t m = (a->v_max > 0) ? (int32_t)a->v_max : 0;
    __CPROVER_assume((int32_t)y >= -m && (int32_t)y <= m);
    return y;
}
/* qfoc_dtc_speed_fade (dtc.h): between 0 and dv */
qfoc_q15_t stub_dtc_speed_fade(qfoc_q15_t dv, qfoc_q15_t w, qfoc_q15_t w_full)
{
    const qfoc_q15_t y = ANY_S16(0);
    (void)w; (void)w_full;
    __CPROVER_assume((dv >= 0) ? (y >= 0 && y <= dv) : (y >= dv && y <= 0));
    return y;
}
/* qfoc_dtc_error (dtc.h): both components in [-32767, 32767] */
void stub_dtc_error(qfoc_q15_t dv, const qfoc_abc_t *i, qfoc_q15_t i_db, qfoc_ab_t *e)
{
    (void)dv; (void)i; (void)i_db;
    e->alpha = ANY_S16(2);
    e->beta = ANY_S16(3);
    __CPROVER_assume(e->alpha >= -32767 && e->beta >= -32767);
}
void stub_flux_reset(qfoc_flux_t *o, const qfoc_ab_t *p, const qfoc_ab_t *i) { (void)o; (void)p; (void)i; }
void stub_pll_reset(qfoc_pll_t *pll, qfoc_angle_t t, qfoc_q15_t w) { (void)pll; (void)t; (void)w; }


uint8_t stub_lin_encode_status(const qfoc_link_cfg_t *c, const qfoc_status_t *st, uint8_t *buf)
{
    unsigned k;
    (void)c; (void)st;
    for (k = 0u; k < QFOC_LIN_FRAME_MAX; k++) {
        buf[k] = ANY_U8();
    }
    return QFOC_LIN_STATUS_LEN;
}
void stub_can_status(qfoc_link_t *l, const qfoc_status_t *st, qfoc_can_frame_t *f)
{
    unsigned k;
    (void)st;
    f->id = l->can_b ? l->cfg.can_id_b : l->cfg.can_id_a;
    l->can_b = !l->can_b;
    f->dlc = 8u;
    for (k = 0u; k < 8u; k++) {
        f->data[k] = ANY_U8();
    }
}

/* The module invariant checks the tick's RAM check calls (REQ-DRV-019): any verdict, the
   same one for every call of a run when DRIVE_STUBS_PURE. */
bool stub_flux_is_valid(const qfoc_flux_t *o) { (void)o; return ANY_B(0); }
bool stub_pll_is_valid(const qfoc_pll_t *q) { (void)q; return ANY_B(0); }
bool stub_lpf_is_valid(const qfoc_lpf_t *f) { (void)f; return ANY_B(0); }
bool stub_pi_is_valid(const qfoc_pi_t *pi) { (void)pi; return ANY_B(0); }
bool stub_fw_is_valid(const qfoc_fw_t *w) { (void)w; return ANY_B(0); }
bool stub_mech_is_valid(const qfoc_mech_t *m) { (void)m; return ANY_B(0); }
bool stub_tc_is_valid(const qfoc_trqcomp_t *t) { (void)t; return ANY_B(0); }

#endif /* QFOC_DRIVE_STUBS_H */
