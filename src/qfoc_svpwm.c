/**
 * @file qfoc_svpwm.c
 * @brief Space-vector PWM with overmodulation limit, dead-time compensation and
 *        min-max zero-sequence injection (see include/qfoc/svpwm.h).
 *
 * Requirements: REQ-SVPWM-001 .. REQ-SVPWM-011 (specs/requirements/svpwm.md).
 */
#include "qfoc/svpwm.h"
#include "qfoc/q15.h"
#include "qfoc/transforms.h"
#include "qfoc/vector.h"

/** 1/sqrt(3) in Q16: 0.5773503 * 65536 = 37837.23 -> 37837 (floor: the limit
 *  circle lies inside the ideal inscribed circle). */
#define SVPWM_INV_SQRT3_Q16 ((int32_t)37837)
/** sqrt(3) in Q15: 1.7320508 * 32768 = 56755.84 -> 56756. */
#define SVPWM_SQRT3_Q15 ((int32_t)56756)
/** 1.0 in Q16 = 65536 (scale of the overmodulation gain and of the tick factor). */
#define SVPWM_ONE_Q16 ((int32_t)65536)
/** 0.5 in Q16 = 32768 (rounding offset of a Q16 product). */
#define SVPWM_HALF_Q16 ((int32_t)32768)

/*@
  assigns \nothing;
  ensures range: 0 <= \result <= 65534;
*/
static int32_t svpwm_mag(qfoc_q15_t a, qfoc_q15_t b)
{
    int32_t m = (int32_t)qfoc_vec_mag(a, b);
    if (m >= (int32_t)QFOC_Q15_MAX) {
        /* |v| may exceed the Q15 range (up to sqrt(2) * 32768): measure half */
        qfoc_q15_t ah = (qfoc_q15_t)((int32_t)a / 2);
        qfoc_q15_t bh = (qfoc_q15_t)((int32_t)b / 2);
        m = 2 * (int32_t)qfoc_vec_mag(ah, bh);
    } else {
        /* magnitude is exact in Q15 */
    }
    return m;
}

/*@
  requires order: lo <= hi;
  assigns \nothing;
  ensures range: lo <= \result <= hi;
  behavior lower:
    assumes x < lo;
    ensures \result == lo;
  behavior between:
    assumes lo <= x <= hi;
    ensures \result == x;
  behavior upper:
    assumes x > hi;
    ensures \result == hi;
  complete behaviors;
  disjoint behaviors;
*/
static int32_t svpwm_clamp(int32_t x, int32_t lo, int32_t hi)
{
    int32_t r = x;
    if (x < lo) {
        r = lo;
    } else if (x > hi) {
        r = hi;
    } else {
        /* inside */
    }
    return r;
}

/*@
  requires range_dt: 0 <= dt <= 8191;
  requires range_db: 0 <= db <= 32767;
  assigns \nothing;
  ensures range: -dt <= \result <= dt;
  ensures sign: (i > 0 ==> \result >= 0) && (i < 0 ==> \result <= 0) &&
                (i == 0 ==> \result == 0);
  ensures full: (i >= db && i > 0 ==> \result == dt) && (-i >= db && i < 0 ==> \result == -dt);
*/
static int32_t svpwm_dt_comp(qfoc_q15_t i, int32_t dt, int32_t db)
{
    int32_t ai = (int32_t)i;
    int32_t c;
    if (ai < 0) {
        ai = -ai;
    } else {
        /* non-negative already */
    }
    if (ai == 0) {
        c = 0;
    } else if (ai >= db) {
        c = dt;
    } else {
        /* linear fade inside the dead band: 0 < ai < db, so 0 <= c < dt;
         * the clamp is a no-op that keeps the bound local */
        c = svpwm_clamp((ai * dt) / db, 0, dt);
    }
    if (i < 0) {
        c = -c;
    } else {
        /* positive current: high-side time added */
    }
    return c;
}

/*@
  assigns \nothing;
  ensures value: \result == SvpwmSector(a, b, c);
  ensures order: SvpwmSectorOrder(\result, a, b, c);
  ensures range: 1 <= \result <= 6;
*/
static uint8_t svpwm_sector(int32_t a, int32_t b, int32_t c)
{
    uint8_t s;
    if ((a >= b) && (b >= c)) {
        s = 1u;
    } else if ((a >= c) && (c >= b)) {
        s = 2u;
    } else if ((b >= c) && (c >= a)) {
        s = 3u;
    } else if ((b >= a) && (a >= c)) {
        s = 4u;
    } else if (a >= b) {
        /* rows 1 .. 4 failed, so Tc is the largest: row 5 Tc >= Ta >= Tb */
        s = 5u;
    } else {
        s = 6u;
    }
    return s;
}

/*@
  requires range_g: 0 <= g <= 65535;
  assigns \nothing;
  ensures value: \result == (x * g) / 65536;
*/
static qfoc_q15_t svpwm_scale(qfoc_q15_t x, int32_t g)
{
    int32_t p = (int32_t)x * g;
    //@ assert prod: -2147450880 <= p <= 2147385345 && -32767 <= p / 65536 <= 32766;
    /* truncated towards zero: the scaled vector never grows */
    return (qfoc_q15_t)(p / SVPWM_ONE_Q16);
}

/*@
  requires range_v: 1 <= v <= 32767;
  requires valid_in: \valid_read(in);
  requires valid_ab: \valid(ab);
  requires valid_out: \valid(out);
  requires sep: \separated(in, ab, out);
  assigns *ab, out->limited, out->utilisation;
  ensures range_util: 0 <= out->utilisation <= 32767;
*/
static void svpwm_limit(const qfoc_ab_t *in, int32_t v, qfoc_ab_t *ab, qfoc_svpwm_out_t *out)
{
    /* r_lim = Vdc / sqrt(3), Q15 of the voltage base, <= 18918 */
    int32_t r_lim = (v * SVPWM_INV_SQRT3_Q16) / SVPWM_ONE_Q16;
    int32_t mag = svpwm_mag(in->alpha, in->beta);
    //@ assert r_lim_range: 0 <= r_lim <= 18918;
    if (mag > r_lim) {
        /* proportional scaling onto the circle, gain g = r_lim / |v| in Q16 */
        int32_t g = (r_lim * SVPWM_ONE_Q16) / mag;
        //@ assert g_range: 0 <= g <= 65535;
        /* no-op (g <= 65535 proved); keeps the bound local for bit-level checkers */
        g = svpwm_clamp(g, 0, SVPWM_ONE_Q16 - 1);
        ab->alpha = svpwm_scale(in->alpha, g);
        ab->beta = svpwm_scale(in->beta, g);
        out->limited = true;
        out->utilisation = QFOC_Q15_MAX;
    } else {
        /* utilisation |v| * sqrt(3) / Vdc, rounded; |v| <= 18918 here */
        int32_t u = ((mag * SVPWM_SQRT3_Q15) + (v / 2)) / v;
        ab->alpha = in->alpha;
        ab->beta = in->beta;
        out->limited = false;
        out->utilisation = qfoc_q15_sat(u);
    }
}

/*@
  requires range_v: 1 <= v <= 32767;
  requires range_p: 100 <= p <= 32767;
  requires range_k: 0 <= k && v * k <= p * 65536;
  assigns \nothing;
  ensures range: -p <= \result <= p;
*/
static int32_t svpwm_time(qfoc_q15_t ux, int32_t v, int32_t k, int32_t p)
{
    /* phase voltage limited to what the bus can produce (never active after
     * the overmodulation limit); bounds the product independently of the
     * transform's accuracy */
    int32_t u = svpwm_clamp((int32_t)ux, -v, v);
    int64_t t;
    int64_t r;
    //@ assert prod: -(v * k) <= u * k <= v * k;
    /* |u k| <= Vdc k <= P * 65536 < 2^31 (proved above); the product is formed
     * in 64 bits (one SMULL on the Cortex-M4) so that its bound also follows
     * from the operand widths alone (2^15 * 2^31), which bit-level checkers
     * (CBMC) can establish without the nonlinear argument */
    t = (int64_t)u * (int64_t)k;
    if (t >= 0) {
        r = (t + (int64_t)SVPWM_HALF_Q16) / (int64_t)SVPWM_ONE_Q16;
    } else {
        r = -(((int64_t)SVPWM_HALF_Q16 - t) / (int64_t)SVPWM_ONE_Q16);
    }
    //@ assert r_range: -p <= r <= p;
    /* no-op (|r| <= P proved); keeps every later sum locally bounded */
    return svpwm_clamp((int32_t)r, -p, p);
}

/*@
  requires range_v: 1 <= v <= 32767;
  requires range_p: 100 <= p <= 32767;
  requires valid: \valid_read(uvw) && \valid(t + (0 .. 2));
  requires sep: \separated(uvw, t + (0 .. 2));
  assigns t[0 .. 2];
  ensures range: \forall integer j; 0 <= j < 3 ==> -p <= t[j] <= p;
*/
static void svpwm_times(const qfoc_abc_t *uvw, int32_t v, int32_t p, int32_t t[3])
{
    /* Tx = Ux / Vdc * P: k = P / Vdc in Q16 is the one division of the step */
    int32_t k = (p * SVPWM_ONE_Q16) / v;
    //@ assert k_range: 0 <= k && v * k <= p * 65536;
    t[0] = svpwm_time(uvw->u, v, k, p);
    t[1] = svpwm_time(uvw->v, v, k, p);
    t[2] = svpwm_time(uvw->w, v, k, p);
}

/*@
  requires range_p: 100 <= p <= 32767;
  requires range_t: -2 * p <= ta <= 2 * p && -2 * p <= tb <= 2 * p && -2 * p <= tc <= 2 * p;
  requires valid_out: \valid(out);
  assigns out->cmp[0 .. 2], out->sector;
  ensures range_cmp: \forall integer j; 0 <= j < 3 ==> 0 <= out->cmp[j] <= p;
  ensures range_sector: 1 <= out->sector <= 6;
  ensures sector_order: SvpwmSectorOrder(out->sector, out->cmp[0], out->cmp[1], out->cmp[2]);
  ensures centred: (\forall integer j; 0 <= j < 3 ==> 0 < out->cmp[j] < p) ==>
    p - 1 <= SvpwmMax3(out->cmp[0], out->cmp[1], out->cmp[2]) +
             SvpwmMin3(out->cmp[0], out->cmp[1], out->cmp[2]) <= p + 1;
*/
static void svpwm_modulate(int32_t ta, int32_t tb, int32_t tc, int32_t p, qfoc_svpwm_out_t *out)
{
    int32_t tmax = ta;
    int32_t tmin = ta;
    int32_t off;
    int32_t ca;
    int32_t cb;
    int32_t cc;

    /* (6) sector from the document's table */
    out->sector = svpwm_sector(ta, tb, tc);

    /* (7) min-max zero-sequence injection Tpwm/2 - (Tmax + Tmin)/2 */
    if (tb > tmax) {
        tmax = tb;
    } else {
        /* keep */
    }
    if (tc > tmax) {
        tmax = tc;
    } else {
        /* keep */
    }
    if (tb < tmin) {
        tmin = tb;
    } else {
        /* keep */
    }
    if (tc < tmin) {
        tmin = tc;
    } else {
        /* keep */
    }
    //@ assert max_min: tmax == SvpwmMax3(ta, tb, tc) && tmin == SvpwmMin3(ta, tb, tc);
    off = (p - (tmax + tmin)) / 2;

    /* (8) compare values clamped to [0, P] */
    ca = svpwm_clamp(ta + off, 0, p);
    cb = svpwm_clamp(tb + off, 0, p);
    cc = svpwm_clamp(tc + off, 0, p);
    //@ assert unclamped: (0 < ca < p && 0 < cb < p && 0 < cc < p) ==> (ca == ta + off && cb == tb + off && cc == tc + off);
    out->cmp[QFOC_SVPWM_U] = (uint16_t)ca;
    out->cmp[QFOC_SVPWM_V] = (uint16_t)cb;
    out->cmp[QFOC_SVPWM_W] = (uint16_t)cc;
}

/* public interface, also called by qfoc_svpwm_step (DEV-002) */
/* cppcheck-suppress misra-c2012-8.7 ; DEV-002 */
bool qfoc_svpwm_cfg_is_valid(const qfoc_svpwm_cfg_t *c)
{
    bool ok = false;
    if ((c->period >= QFOC_SVPWM_PERIOD_MIN) && (c->period <= QFOC_SVPWM_PERIOD_MAX)) {
        if ((c->dt_comp <= (uint16_t)(c->period / 4u)) && (c->i_deadband >= 0) &&
            (c->vdc_min > 0)) {
            ok = true;
        } else {
            /* invalid compensation, dead band or bus minimum */
        }
    } else {
        /* period out of range */
    }
    return ok;
}

void qfoc_svpwm_step(const qfoc_svpwm_cfg_t *cfg, const qfoc_ab_t *v_ab, qfoc_q15_t vdc,
                     const qfoc_abc_t *i_abc, qfoc_svpwm_out_t *out)
{
    if (qfoc_svpwm_cfg_is_valid(cfg)) {
        int32_t p = (int32_t)cfg->period;
        int32_t dt = (int32_t)cfg->dt_comp;
        int32_t db = (int32_t)cfg->i_deadband;
        int32_t v = (int32_t)vdc;
        qfoc_ab_t ab;
        qfoc_abc_t uvw;
        int32_t t[3];

        /* (1) DC bus clamped to [vdc_min, 32767] */
        if (v < (int32_t)cfg->vdc_min) {
            v = (int32_t)cfg->vdc_min;
            out->vdc_low = true;
        } else {
            out->vdc_low = false;
        }

        /* (2) overmodulation: |v_ab| limited to Vdc / sqrt(3) */
        svpwm_limit(v_ab, v, &ab, out);

        /* (3) inverse Clarke to the phase voltages */
        qfoc_inv_clarke(&ab, &uvw);

        /* (4) phase times Tx = Ux / Vdc * P, |Tx| <= P */
        svpwm_times(&uvw, v, p, t);

        /* (5) dead-time compensation, |c| <= P / 4 */
        t[0] += svpwm_dt_comp(i_abc->u, dt, db);
        t[1] += svpwm_dt_comp(i_abc->v, dt, db);
        t[2] += svpwm_dt_comp(i_abc->w, dt, db);

        /* (6) .. (8) sector, injection, clamp */
        svpwm_modulate(t[0], t[1], t[2], p, out);
    } else {
        /* invalid configuration: zero voltage, flagged as limited */
        uint16_t half = (uint16_t)(cfg->period / 2u);
        out->cmp[QFOC_SVPWM_U] = half;
        out->cmp[QFOC_SVPWM_V] = half;
        out->cmp[QFOC_SVPWM_W] = half;
        out->sector = 1u;
        out->utilisation = 0;
        out->limited = true;
        out->vdc_low = false;
    }
}
