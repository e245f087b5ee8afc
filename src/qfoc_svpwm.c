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
/** 1.0 in Q16, unsigned (tick factor and phase times in magnitude). */
#define SVPWM_ONE_Q16_U (65536u)

/** 32767^2 = 1073676289: the squared length from which qfoc_vec_mag() saturates. */
#define SVPWM_MAG_SAT_SQ ((uint32_t)1073676289u)

/*@
  assigns \nothing;
  ensures value: \result == x * x;
  ensures bound: \result <= 1073741824;
*/
static inline uint32_t svpwm_square(qfoc_q15_t x)
{
    int32_t sq = (int32_t)x * (int32_t)x;   /* 2.30, <= 2^30 */
    return (uint32_t)sq;
}

/*@
  assigns \nothing;
  ensures range: 0 <= \result <= 65534;
*/
static inline int32_t svpwm_mag(qfoc_q15_t a, qfoc_q15_t b)
{
    /* |v|^2 <= 2^31 fits uint32; qfoc_vec_mag() saturates exactly when
     * |v|^2 >= 32767^2, so that case is decided here and only one square
     * root runs */
    uint32_t s = svpwm_square(a) + svpwm_square(b);
    bool sat = (s >= SVPWM_MAG_SAT_SQ);
    qfoc_q15_t x = a;
    qfoc_q15_t y = b;
    int32_t m;
    if (sat) {
        /* |v| may exceed the Q15 range (up to sqrt(2) * 32768): measure half,
         * |v / 2|^2 <= 2^29 never saturates */
        x = (qfoc_q15_t)((int32_t)a / 2);
        y = (qfoc_q15_t)((int32_t)b / 2);
    } else {
        /* magnitude is exact in Q15 */
    }
    m = (int32_t)qfoc_vec_mag(x, y);
    if (sat) {
        m = 2 * m;
    } else {
        /* measured at full scale */
    }
    return m;
}

/*@
  requires range_dt: 0 <= dt <= 8191;
  requires range_db: 1 <= db <= 32767;
  requires range_ai: 0 <= ai <= 32768;
  assigns \nothing;
  ensures range: 0 <= \result <= dt;
  ensures zero: ai == 0 ==> \result == 0;
  ensures full: ai >= db ==> \result == dt;
  ensures fade: ai < db ==> \result == (ai * dt) / db;
*/
static inline int32_t svpwm_dt_mag(int32_t ai, int32_t dt, int32_t db)
{
    int32_t c;
    if (ai >= db) {
        c = dt;
    } else {
        /* linear fade inside the dead band, 0 <= ai < db: 0 <= c < dt, and
         * c == 0 for ai == 0 (db >= 1 also for a pure sign() compensation) */
        //@ assert fade_num: 0 <= ai * dt <= 268402687;
        c = (ai * dt) / db;
        //@ assert fade_le: dt == 0 || ai * dt < dt * db;
        //@ assert fade_range: 0 <= c <= dt;
    }
    return c;
}

/*@
  requires range_dt: 0 <= dt <= 8191;
  requires range_db: 1 <= db <= 32767;
  requires range_t: -32767 <= t <= 32767;
  assigns \nothing;
  ensures range: t - dt <= \result <= t + dt;
  ensures sign: (i > 0 ==> \result >= t) && (i < 0 ==> \result <= t) && (i == 0 ==> \result == t);
*/
static inline int32_t svpwm_dt_add(int32_t t, qfoc_q15_t i, int32_t dt, int32_t db)
{
    int32_t r;
    if (i < 0) {
        /* negative current: high-side time removed */
        r = t - svpwm_dt_mag(-(int32_t)i, dt, db);
    } else {
        /* positive current: high-side time added; zero current: nothing */
        r = t + svpwm_dt_mag((int32_t)i, dt, db);
    }
    return r;
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
static inline int32_t svpwm_clamp(int32_t x, int32_t lo, int32_t hi)
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
  requires range_g: 0 <= g <= 65535;
  assigns \nothing;
  ensures value: \result == (x * g) / 65536;
*/
static inline qfoc_q15_t svpwm_scale(qfoc_q15_t x, int32_t g)
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
static inline void svpwm_limit(const qfoc_ab_t *in, int32_t v, qfoc_ab_t *ab,
                               qfoc_svpwm_out_t *out)
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
        /* utilisation |v| * sqrt(3) / Vdc, rounded; 0 <= |v| <= 18918 here, so
         * u >= 0 and only the upper saturation can act */
        int32_t u = ((mag * SVPWM_SQRT3_Q15) + (v / 2)) / v;
        u = svpwm_clamp(u, 0, (int32_t)QFOC_Q15_MAX);
        ab->alpha = in->alpha;
        ab->beta = in->beta;
        out->limited = false;
        out->utilisation = (qfoc_q15_t)u;
    }
}

/*@
  requires range_v: 1 <= v <= 32767;
  requires range_p: 100 <= p <= 32767;
  requires range_k: 0 <= kh <= 65535 && 0 <= kl <= 65535 && v * (kh * 65536 + kl) <= p * 65536;
  assigns \nothing;
  ensures range: -p <= \result <= p;
*/
static inline int32_t svpwm_time(qfoc_q15_t ux, int32_t v, uint32_t kh, uint32_t kl, int32_t p)
{
    int32_t u = (int32_t)ux;
    int32_t au = u;
    uint32_t ua;
    uint32_t lo;
    uint32_t q;
    int32_t r;
    if (au < 0) {
        au = -au;
    } else {
        /* non-negative already */
    }
    /* |Ux| limited to what the bus can produce, i.e. Ux clamped to [-Vdc, Vdc]
     * (never active after the overmodulation limit); bounds the product
     * independently of the transform's accuracy */
    au = svpwm_clamp(au, 0, v);
    ua = (uint32_t)au;
    //@ assert prod: 0 <= ua * (kh * 65536 + kl) <= v * (kh * 65536 + kl) <= p * 65536;
    /* |Ux| k / 65536 rounded half away from zero, k = kh 65536 + kl:
     * (|Ux| k + 32768) / 65536 = |Ux| kh + (|Ux| kl + 32768) / 65536, both
     * products below 2^31 from the operand widths alone (2^15 * 2^16), which
     * bit-level checkers (CBMC) establish without the nonlinear argument
     * |Ux| k <= Vdc k <= P * 65536 (proved above) */
    lo = ((ua * kl) + 32768u) / SVPWM_ONE_Q16_U;
    q = (ua * kh) + lo;
    //@ assert split: q == (ua * (kh * 65536 + kl) + 32768) / 65536;
    //@ assert q_range: q <= p;
    /* no-op (q <= P proved); keeps every later sum locally bounded (q < 2^31
     * from the widths) */
    r = svpwm_clamp((int32_t)q, 0, p);
    if (u < 0) {
        r = -r;
    } else {
        /* non-negative voltage, non-negative time */
    }
    return r;
}

/*@
  requires range_p: 100 <= p <= 32767;
  requires range_t: -2 * p <= ta <= 2 * p && -2 * p <= tb <= 2 * p && -2 * p <= tc <= 2 * p;
  requires valid_out: \valid(out);
  assigns out->cmp[0 .. 2], out->sector;
  ensures range_cmp: \forall integer j; 0 <= j < 3 ==> 0 <= out->cmp[j] <= p;
  ensures range_sector: 1 <= out->sector <= 6;
  ensures sector_value: out->sector == SvpwmSector(ta, tb, tc);
  ensures sector_order: SvpwmSectorOrder(out->sector, out->cmp[0], out->cmp[1], out->cmp[2]);
  ensures centred: (\forall integer j; 0 <= j < 3 ==> 0 < out->cmp[j] < p) ==>
    p - 1 <= SvpwmMax3(out->cmp[0], out->cmp[1], out->cmp[2]) +
             SvpwmMin3(out->cmp[0], out->cmp[1], out->cmp[2]) <= p + 1;
*/
static inline void svpwm_modulate(int32_t ta, int32_t tb, int32_t tc, int32_t p,
                                  qfoc_svpwm_out_t *out)
{
    int32_t tmax;
    int32_t tmin;
    uint8_t s;
    int32_t off;
    int32_t ca;
    int32_t cb;
    int32_t cc;

    /* (6) sector from the table E2-43 (first row that holds), and with it
     * the largest and smallest time: two or three compares */
    if (ta >= tb) {
        if (tb >= tc) {
            s = 1u;             /* Ta >= Tb >= Tc */
            tmax = ta;
            tmin = tc;
        } else if (ta >= tc) {
            s = 2u;             /* Ta >= Tc > Tb */
            tmax = ta;
            tmin = tb;
        } else {
            s = 5u;             /* Tc > Ta >= Tb */
            tmax = tc;
            tmin = tb;
        }
    } else if (tc < ta) {
        s = 4u;                 /* Tb > Ta > Tc */
        tmax = tb;
        tmin = tc;
    } else if (tb >= tc) {
        s = 3u;                 /* Tb >= Tc >= Ta, Tb > Ta */
        tmax = tb;
        tmin = ta;
    } else {
        s = 6u;                 /* Tc > Tb > Ta */
        tmax = tc;
        tmin = ta;
    }
    //@ assert sector: s == SvpwmSector(ta, tb, tc) && SvpwmSectorOrder(s, ta, tb, tc);
    //@ assert max_min: tmax == SvpwmMax3(ta, tb, tc) && tmin == SvpwmMin3(ta, tb, tc);
    out->sector = s;

    /* (7) min-max zero-sequence injection Tpwm/2 - (Tmax + Tmin)/2 */
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

/*
 * Steps (3) .. (8) on a valid configuration and the clamped bus v: inverse Clarke,
 * phase times, dead-time compensation, sector, injection, clamp.
 */
/*@
  requires cfg_ok: SvpwmCfgValid(cfg->period, cfg->dt_comp, cfg->i_deadband, cfg->vdc_min);
  requires range_v: cfg->vdc_min <= v <= 32767;
  requires valid_cfg: \valid_read(cfg);
  requires valid_ab: \valid_read(ab);
  requires valid_i: \valid_read(i_abc);
  requires valid_out: \valid(out);
  requires sep: \separated(out, cfg) && \separated(out, ab) && \separated(out, i_abc);
  assigns out->cmp[0 .. 2], out->sector;
  ensures range_sector: 1 <= out->sector <= 6;
  ensures range_cmp: \forall integer j; 0 <= j < 3 ==> 0 <= out->cmp[j] <= cfg->period;
  ensures sector_order: SvpwmSectorOrder(out->sector, out->cmp[0], out->cmp[1], out->cmp[2]);
  ensures centred: (\forall integer j; 0 <= j < 3 ==> 0 < out->cmp[j] < cfg->period) ==>
    cfg->period - 1 <= SvpwmMax3(out->cmp[0], out->cmp[1], out->cmp[2]) +
                       SvpwmMin3(out->cmp[0], out->cmp[1], out->cmp[2]) <= cfg->period + 1;
*/
static inline void svpwm_core(const qfoc_svpwm_cfg_t *cfg, const qfoc_ab_t *ab, int32_t v,
                       const qfoc_abc_t *i_abc, qfoc_svpwm_out_t *out)
{
    int32_t p = (int32_t)cfg->period;
    int32_t dt = (int32_t)cfg->dt_comp;
    int32_t db = (int32_t)cfg->i_deadband;
    uint32_t k;
    uint32_t kh;
    uint32_t kl;
    int32_t ta;
    int32_t tb;
    int32_t tc;
    qfoc_abc_t uvw;

    /* (3) inverse Clarke to the phase voltages */
    qfoc_inv_clarke(ab, &uvw);

    /* (4) phase times Tx = Ux / Vdc * P, |Tx| <= P: k = P / Vdc in Q16 is
     * the one division of the phase times */
    k = ((uint32_t)p * SVPWM_ONE_Q16_U) / (uint32_t)v;
    //@ assert k_range: v * k <= p * 65536;
    kh = k / SVPWM_ONE_Q16_U;
    kl = k % SVPWM_ONE_Q16_U;
    //@ assert k_split: k == kh * 65536 + kl && 0 <= kh <= 65535 && 0 <= kl <= 65535;
    ta = svpwm_time(uvw.u, v, kh, kl, p);
    tb = svpwm_time(uvw.v, v, kh, kl, p);
    tc = svpwm_time(uvw.w, v, kh, kl, p);

    /* (5) dead-time compensation, |c| <= P / 4; a zero dead band is the
     * dead band 1 (the same pure sign() compensation: |i| >= 1 for every
     * non-zero current, and the fade of a zero current is zero) */
    if (db < 1) {
        db = 1;
    } else {
        /* a dead band of its own */
    }
    ta = svpwm_dt_add(ta, i_abc->u, dt, db);
    tb = svpwm_dt_add(tb, i_abc->v, dt, db);
    tc = svpwm_dt_add(tc, i_abc->w, dt, db);

    /* (6) .. (8) sector, injection, clamp */
    svpwm_modulate(ta, tb, tc, p, out);
}

/*
 * (1) DC bus clamped to [vdc_min, 32767], with the flag.
 */
/*@
  requires valid_cfg: \valid_read(cfg);
  requires valid_out: \valid(out);
  requires sep: \separated(out, cfg);
  requires min_ok: cfg->vdc_min > 0;
  assigns out->vdc_low;
  ensures range: cfg->vdc_min <= \result <= 32767;
  ensures vdc_flag: out->vdc_low == \true <==> vdc < cfg->vdc_min;
*/
static int32_t svpwm_bus(const qfoc_svpwm_cfg_t *cfg, qfoc_q15_t vdc, qfoc_svpwm_out_t *out)
{
    int32_t v = (int32_t)vdc;
    if (v < (int32_t)cfg->vdc_min) {
        v = (int32_t)cfg->vdc_min;
        out->vdc_low = true;
    } else {
        out->vdc_low = false;
    }
    return v;
}

/*
 * The output for an invalid configuration: zero voltage, flagged as limited.
 */
/*@
  requires valid_cfg: \valid_read(cfg);
  requires valid_out: \valid(out);
  requires sep: \separated(out, cfg);
  assigns *out;
  ensures safe_cmp: out->cmp[0] == cfg->period / 2 && out->cmp[1] == cfg->period / 2 &&
                    out->cmp[2] == cfg->period / 2;
  ensures safe_flags: out->limited == \true && out->vdc_low == \false &&
                      out->sector == 1 && out->utilisation == 0;
*/
static void svpwm_safe(const qfoc_svpwm_cfg_t *cfg, qfoc_svpwm_out_t *out)
{
    uint16_t half = (uint16_t)(cfg->period / 2u);
    out->cmp[QFOC_SVPWM_U] = half;
    out->cmp[QFOC_SVPWM_V] = half;
    out->cmp[QFOC_SVPWM_W] = half;
    out->sector = 1u;
    out->utilisation = 0;
    out->limited = true;
    out->vdc_low = false;
}

void qfoc_svpwm_step_lin(const qfoc_svpwm_cfg_t *cfg, const qfoc_ab_t *v_ab, qfoc_q15_t vdc,
                         const qfoc_abc_t *i_abc, qfoc_svpwm_out_t *out)
{
    if (qfoc_svpwm_cfg_is_valid(cfg)) {
        /* no overmodulation limit and no magnitude: the caller keeps |v_ab| within
           Vdc / sqrt 3; beyond it the phase voltages are still clamped to [-Vdc, Vdc]
           by the phase times */
        const int32_t v = svpwm_bus(cfg, vdc, out);
        out->utilisation = 0;
        out->limited = false;
        svpwm_core(cfg, v_ab, v, i_abc, out);
    } else {
        svpwm_safe(cfg, out);
    }
}

void qfoc_svpwm_step(const qfoc_svpwm_cfg_t *cfg, const qfoc_ab_t *v_ab, qfoc_q15_t vdc,
                     const qfoc_abc_t *i_abc, qfoc_svpwm_out_t *out)
{
    if (qfoc_svpwm_cfg_is_valid(cfg)) {
        qfoc_ab_t ab;
        const int32_t v = svpwm_bus(cfg, vdc, out);
        /* (2) overmodulation: |v_ab| limited to Vdc / sqrt(3) */
        svpwm_limit(v_ab, v, &ab, out);
        /* (3) .. (8) */
        svpwm_core(cfg, &ab, v, i_abc, out);
    } else {
        /* invalid configuration: zero voltage, flagged as limited */
        svpwm_safe(cfg, out);
    }
}
