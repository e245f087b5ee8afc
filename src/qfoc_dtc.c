/**
 * @file qfoc_dtc.c
 * @brief The inverter's residual voltage error: learnt at ALIGN, taken out of the
 *        observer's voltage (see include/qfoc/dtc.h).
 *
 * Requirements: REQ-DTC-001 .. REQ-DTC-004 (specs/requirements/dtc.md).
 */
#include "qfoc/dtc.h"

/** 1 / sqrt 3 in Q15 (18918.6, rounded up: the beta factor stays within 37836). */
#define DTC_INV_SQRT3 ((int32_t)18919)
/** The largest |u_hi - 2 u_lo| kept before the division of qfoc_dtc_learn (dtc.h). */
#define DTC_N_MAX ((int32_t)65535)
/** The largest |v| kept for the resistance check of qfoc_dtc_learn (dtc.h). */
#define DTC_V_MAX ((int32_t)49151)

/* x saturated to [-32767, 32767]. */
/*@
  assigns \nothing;
  ensures range: QfocQ15Sym(\result);
  ensures exact: -32767 <= x <= 32767 ==> \result == x;
*/
static qfoc_q15_t dtc_sym(int32_t x)
{
    qfoc_q15_t y;
    if (x > 32767) {
        y = 32767;
    } else if (x < -32767) {
        y = -32767;
    } else {
        y = (qfoc_q15_t)x;
    }
    return y;
}

/* public interface, also called by qfoc_dtc_learn and qfoc_dtc_error (DEV-002) */
/* cppcheck-suppress misra-c2012-8.7 ; DEV-002 */
qfoc_q15_t qfoc_dtc_fade(qfoc_q15_t i, qfoc_q15_t i_db)
{
    const int32_t x = (int32_t)i;
    const int32_t db = (int32_t)i_db;
    int32_t f;
    if ((db <= 0) || (x >= db) || (x <= -db)) {
        if (x > 0) {
            f = 32767;
        } else if (x < 0) {
            f = -32767;
        } else {
            f = 0;
        }
    } else {
        /* inside the band: |x| < db <= 32767 */
        f = (x * 32767) / db;
    }
    return (qfoc_q15_t)f;
}

/* s_d(i) = (2/3)(f(i) - f(-i / 2)), Q15 of the error's shape on the d axis (E10-4) */
/*@
  assigns \nothing;
  ensures range: -43690 <= \result <= 43690;
*/
static int32_t dtc_sd(qfoc_q15_t i, qfoc_q15_t i_db)
{
    const int32_t half = -((int32_t)i / 2);
    const int32_t fa = (int32_t)qfoc_dtc_fade(i, i_db);
    const int32_t fb = (int32_t)qfoc_dtc_fade((qfoc_q15_t)half, i_db);
    return (2 * (fa - fb)) / 3;
}

/* x clamped to [-lim, lim], lim >= 0 */
/*@
  requires lim: lim >= 0;
  assigns \nothing;
  ensures range: -lim <= \result <= lim;
  ensures exact: -lim <= x <= lim ==> \result == x;
*/
static int32_t dtc_clamp(int32_t x, int32_t lim)
{
    int32_t y = x;
    if (x > lim) {
        y = lim;
    } else if (x < -lim) {
        y = -lim;
    } else {
        /* within the limit */
    }
    return y;
}

qfoc_q15_t qfoc_dtc_learn(const qfoc_dtc_align_t *a)
{
    const int32_t m = (a->v_max > 0) ? (int32_t)a->v_max : 0;
    const qfoc_q15_t i_lo = (qfoc_q15_t)((int32_t)a->i_hi / 2);
    const int32_t s_lo = dtc_sd(i_lo, a->i_db);
    const int32_t den = dtc_sd(a->i_hi, a->i_db) - (2 * s_lo);
    const int32_t n = dtc_clamp((int32_t)a->u_hi - (2 * (int32_t)a->u_lo), DTC_N_MAX);
    const int32_t ch = (int32_t)a->u_hi - (int32_t)a->u_hi0;
    const int32_t cl = (int32_t)a->u_lo - (int32_t)a->u_lo0;
    const int32_t tol = (m / 4) + QFOC_DTC_SETTLE_TOL;
    const bool settled = (ch <= tol) && (ch >= -tol) && (cl <= tol) && (cl >= -tol);
    int32_t dv = 0;
    if (settled && ((den >= QFOC_DTC_DEN_MIN) || (den <= -QFOC_DTC_DEN_MIN))) {
        const int32_t v = dtc_clamp((n * 32768) / den, DTC_V_MAX);
        const int32_t ri = ((int32_t)a->r * (int32_t)i_lo) / 32768;
        const int32_t ri_abs = (ri < 0) ? -ri : ri;
        const int32_t re = (a->r_err > 0) ? (int32_t)a->r_err : 0;
        /*@ assert vs: -49151 * 43690 <= v * s_lo <= 49151 * 43690; */
        const int32_t drop = (int32_t)a->u_lo - ((v * s_lo) / 32768);
        const int32_t band = ((re * ri_abs) / 32768) + QFOC_DTC_R_TOL;
        const int32_t off = drop - ri;
        if ((off <= band) && (off >= -band)) {
            dv = dtc_clamp(v, m);
        } else {
            /* a drop the table's resistance does not explain: nothing learnt */
        }
    } else {
        /* a hold that has not settled, or the alignment currents inside the dead band:
           nothing to measure */
    }
    return (qfoc_q15_t)dv;
}

qfoc_q15_t qfoc_dtc_speed_fade(qfoc_q15_t dv, qfoc_q15_t w, qfoc_q15_t w_full)
{
    const int32_t aw = (w < 0) ? -(int32_t)w : (int32_t)w;
    const int32_t wf = (w_full > 0) ? (int32_t)w_full : 0;
    int32_t y;
    if (aw <= wf) {
        y = (int32_t)dv;
    } else if (aw >= (2 * wf)) {
        y = 0;
    } else {
        /* wf < aw < 2 wf: 0 < 2 wf - aw < wf */
        const int32_t k = (2 * wf) - aw;
        const int32_t x = (int32_t)dv * k;
        /*@ assert k: 0 < k < wf; */
        /*@ assert pos: dv >= 0 ==> 0 <= x <= dv * wf; */
        /*@ assert neg: dv < 0 ==> dv * wf <= x <= 0; */
        y = x / wf;
        /*@ assert pos_y: dv >= 0 ==> 0 <= y <= dv; */
        /*@ assert neg_y: dv < 0 ==> dv <= y <= 0; */
    }
    return (qfoc_q15_t)y;
}

void qfoc_dtc_error(qfoc_q15_t dv, const qfoc_abc_t *i, qfoc_q15_t i_db, qfoc_ab_t *e)
{
    const int32_t fu = (int32_t)qfoc_dtc_fade(i->u, i_db);
    const int32_t fv = (int32_t)qfoc_dtc_fade(i->v, i_db);
    const int32_t fw = (int32_t)qfoc_dtc_fade(i->w, i_db);
    const int32_t sa = ((2 * fu) - fv - fw) / 3;
    const int32_t sb = ((fv - fw) * DTC_INV_SQRT3) / 32768;
    /*@ assert sa: -43690 <= sa <= 43690; */
    /*@ assert sb: -37837 <= sb <= 37837; */
    /*@ assert pa: -32768 * 43690 <= dv * sa <= 32768 * 43690; */
    /*@ assert pb: -32768 * 37837 <= dv * sb <= 32768 * 37837; */
    e->alpha = dtc_sym(((int32_t)dv * sa) / 32768);
    e->beta = dtc_sym(((int32_t)dv * sb) / 32768);
}
