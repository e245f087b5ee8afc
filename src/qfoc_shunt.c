/**
 * @file qfoc_shunt.c
 * @brief Single-shunt current measurement (shunt.h): the plan of a period (the edge shift
 *        and the sampling instants) and the phase currents rebuilt from two DC-link
 *        samples, with the hold of the last currents.
 *
 * Requirements: REQ-SHUNT-001 .. REQ-SHUNT-004, REQ-SHUNT-008 (specs/requirements/shunt.md).
 */
#include "qfoc/shunt.h"
#include "qfoc/q15.h"

/* Largest hold (periods). */
#define SHUNT_HOLD_MAX ((uint16_t)1000u)
/* Bounds of the period (those of the SVPWM, svpwm.h). */
#define SHUNT_PERIOD_MIN ((uint16_t)100u)
#define SHUNT_PERIOD_MAX ((uint16_t)32767u)

bool qfoc_shunt_cfg_is_valid(const qfoc_shunt_cfg_t *c)
{
    const uint32_t t = (uint32_t)c->t_settle + (uint32_t)c->t_sample;
    return (c->period >= SHUNT_PERIOD_MIN) && (c->period <= SHUNT_PERIOD_MAX) &&
           (c->t_sample >= 1u) && ((4u * t) <= (uint32_t)c->period) &&
           (c->hold_max >= 1u) && (c->hold_max <= SHUNT_HOLD_MAX);
}

uint8_t qfoc_shunt_init(qfoc_shunt_t *s, const qfoc_shunt_cfg_t *c)
{
    uint8_t r;
    if (qfoc_shunt_cfg_is_valid(c)) {
        s->hold_max = c->hold_max;
        r = QFOC_SHUNT_OK;
    } else {
        s->hold_max = 1u;
        r = QFOC_SHUNT_ERR_CFG;
    }
    /* no currents yet: the first period without a measurement is LOST */
    s->n_hold = s->hold_max;
    s->i[0] = 0;
    s->i[1] = 0;
    s->i[2] = 0;
    return r;
}

/* A compare value as the PWM applies it: at most the period (E13-1). */
/*@
  assigns \nothing;
  ensures result: \result == ShuntCmp(v, period);
*/
static int32_t shunt_cmp(uint16_t v, uint16_t period)
{
    return (v > period) ? (int32_t)period : (int32_t)v;
}

/* The larger / smaller of two values. */
/*@
  assigns \nothing;
  ensures result: \result == ShuntMax(a, b);
*/
static int32_t shunt_max(int32_t a, int32_t b)
{
    return (a > b) ? a : b;
}

/*@
  assigns \nothing;
  ensures result: \result == ShuntMin(a, b);
*/
static int32_t shunt_min(int32_t a, int32_t b)
{
    return (a < b) ? a : b;
}

/* The phases of the largest (the first of equal ones) and of the smallest (the last of
   equal ones) of three values: two distinct phases. */
/*@
  requires valid: \valid_read(x + (0 .. 2)) && \valid(hi) && \valid(lo);
  requires sep: \separated(hi, lo) && \separated(hi, x + (0 .. 2)) && \separated(lo, x + (0 .. 2));
  assigns *hi, *lo;
  ensures idx: *hi <= 2 && *lo <= 2 && *hi != *lo;
  ensures order: x[*hi] >= x[3 - *hi - *lo] && x[3 - *hi - *lo] >= x[*lo];
*/
static void shunt_order(const int32_t x[3], uint8_t *hi, uint8_t *lo)
{
    const int32_t x0 = x[0];
    const int32_t x1 = x[1];
    const int32_t x2 = x[2];
    uint8_t h = 0u;
    uint8_t l = 2u;
    /* x1 is not the largest: then x2 > x0 makes x2 the largest (x2 > x1 follows) */
    if ((x1 > x0) && (x1 >= x2)) {
        h = 1u;
    } else if (x2 > x0) {
        h = 2u;
    } else {
        /* x0 is the largest (the first of equal ones) */
    }
    /* x1 is not the smallest: then x0 < x2 makes x0 the smallest (x0 < x1 follows) */
    if ((x1 < x2) && (x1 <= x0)) {
        l = 1u;
    } else if (x0 < x2) {
        l = 0u;
    } else {
        /* x2 is the smallest (the last of equal ones); all three equal: h 0, l 2 */
    }
    *hi = h;
    *lo = l;
}

/* The up-counting compare values of the largest (uh), middle (um) and smallest (ul)
   phase (E13-4): ok when the middle one can be placed so that both windows last t. */
/*@
  requires valid: \valid(uh) && \valid(um) && \valid(ul);
  requires sep: \separated(uh, um) && \separated(uh, ul) && \separated(um, ul);
  requires range: 0 <= xl <= xm <= xh <= p <= 32767 && 1 <= t && 4 * t <= p;
  assigns *uh, *um, *ul;
  behavior feasible:
    assumes ShuntFeasible(xh, xm, xl, p, t);
    ensures result: \result == \true;
    ensures mid: *um == ShuntMid(xh, xm, xl, p, t);
    ensures outer: *uh == ShuntMax(xh, *um + t) && *ul == ShuntMin(xl, *um - t);
    ensures in_range: 0 <= *ul && *uh <= p && 0 <= *um <= p &&
                      0 <= 2 * xh - *uh <= p && 0 <= 2 * xm - *um <= p &&
                      0 <= 2 * xl - *ul <= p && *ul <= p && 0 <= *uh;
  behavior infeasible:
    assumes !ShuntFeasible(xh, xm, xl, p, t);
    ensures result: \result == \false;
    ensures kept: *uh == xh && *um == xm && *ul == xl;
  complete behaviors;
  disjoint behaviors;
*/
static bool shunt_shift(int32_t xh, int32_t xm, int32_t xl, int32_t p, int32_t t,
                        int32_t *uh, int32_t *um, int32_t *ul)
{
    const int32_t lo_b = shunt_max(shunt_max((2 * xm) - p, 0), shunt_max((2 * xl) - p, 0) + t);
    const int32_t hi_b = shunt_min(shunt_min(2 * xm, p), shunt_min(2 * xh, p) - t);
    bool ok = false;
    if (lo_b <= hi_b) {
        const int32_t m = shunt_min(shunt_max(xm, lo_b), hi_b);
        *um = m;
        *uh = shunt_max(xh, m + t);
        *ul = shunt_min(xl, m - t);
        ok = true;
    } else {
        *um = xm;
        *uh = xh;
        *ul = xl;
    }
    return ok;
}

void qfoc_shunt_plan(const qfoc_shunt_cfg_t *c, const uint16_t cmp[3], qfoc_shunt_plan_t *p)
{
    const int32_t per = (int32_t)c->period;
    int32_t x[3];
    int32_t u[3];
    int32_t d[3];
    int32_t uh;
    int32_t um;
    int32_t ul;
    uint8_t hi;
    uint8_t lo;
    uint8_t mid;
    bool ok = false;
    x[0] = shunt_cmp(cmp[0], c->period);
    x[1] = shunt_cmp(cmp[1], c->period);
    x[2] = shunt_cmp(cmp[2], c->period);
    shunt_order(x, &hi, &lo);
    mid = (uint8_t)(3u - hi - lo);
    /*@ assert xh: x[hi] == ShuntX(cmp, hi, c->period); */
    /*@ assert xm: x[mid] == ShuntX(cmp, mid, c->period); */
    /*@ assert xl: x[lo] == ShuntX(cmp, lo, c->period); */
    /*@ assert ord: ShuntX(cmp, hi, c->period) >= ShuntX(cmp, mid, c->period) &&
                    ShuntX(cmp, mid, c->period) >= ShuntX(cmp, lo, c->period); */
    uh = x[hi];
    um = x[mid];
    ul = x[lo];
    if (qfoc_shunt_cfg_is_valid(c)) {
        const int32_t t = (int32_t)c->t_settle + (int32_t)c->t_sample;
        ok = shunt_shift(x[hi], x[mid], x[lo], per, t, &uh, &um, &ul);
        /*@ assert feasible: ok <==> ShuntFeasible(ShuntX(cmp, hi, c->period),
              ShuntX(cmp, mid, c->period), ShuntX(cmp, lo, c->period), c->period, ShuntT(c)); */
        /*@ assert shift: ok ==>
              (um == ShuntMid(ShuntX(cmp, hi, c->period), ShuntX(cmp, mid, c->period),
                              ShuntX(cmp, lo, c->period), c->period, ShuntT(c)) &&
               uh == ShuntMax(ShuntX(cmp, hi, c->period), um + ShuntT(c)) &&
               ul == ShuntMin(ShuntX(cmp, lo, c->period), um - ShuntT(c)) &&
               uh >= um + ShuntT(c) && um >= ul + ShuntT(c)); */
    } else {
        /* a refused configuration measures nothing: the compare values as they are */
    }
    u[hi] = uh;
    u[mid] = um;
    u[lo] = ul;
    /*@ assert u_range: 0 <= u[0] <= per && 0 <= u[1] <= per && 0 <= u[2] <= per &&
                        0 <= 2 * x[0] - u[0] <= per && 0 <= 2 * x[1] - u[1] <= per &&
                        0 <= 2 * x[2] - u[2] <= per; */
    p->up[0] = (uint16_t)u[0];
    p->up[1] = (uint16_t)u[1];
    p->up[2] = (uint16_t)u[2];
    /*@ assert up_perm: p->up[hi] == uh && p->up[mid] == um && p->up[lo] == ul; */
    /* E13-5: the down-counting half keeps each phase's on-time */
    d[0] = (2 * x[0]) - u[0];
    d[1] = (2 * x[1]) - u[1];
    d[2] = (2 * x[2]) - u[2];
    p->down[0] = (uint16_t)d[0];
    p->down[1] = (uint16_t)d[1];
    p->down[2] = (uint16_t)d[2];
    if (ok) {
        const int32_t n1 = (per - u[hi]) + (int32_t)c->t_settle;
        const int32_t n2 = (per - u[mid]) + (int32_t)c->t_settle;
        p->trig[0] = (uint16_t)n1;
        p->trig[1] = (uint16_t)n2;
    } else {
        p->trig[0] = 0u;
        p->trig[1] = 0u;
    }
    p->hi = hi;
    p->lo = lo;
    p->ok = ok;
    p->shifted = (u[0] != x[0]) || (u[1] != x[1]) || (u[2] != x[2]);
}

uint8_t qfoc_shunt_currents(qfoc_shunt_t *s, const qfoc_shunt_plan_t *p, qfoc_q15_t s1,
                            qfoc_q15_t s2, qfoc_q15_t out[3])
{
    uint8_t r;
    if (p->ok && (p->hi <= 2u) && (p->lo <= 2u) && (p->hi != p->lo)) {
        /* E13-6: +i_hi in the first window, -i_lo in the second, the third from the sum */
        const uint8_t mid = (uint8_t)(3u - p->hi - p->lo);
        s->i[p->hi] = qfoc_q15_sat((int32_t)s1);
        s->i[p->lo] = qfoc_q15_sat(-(int32_t)s2);
        s->i[mid] = qfoc_q15_sat((int32_t)s2 - (int32_t)s1);
        s->n_hold = 0u;
        r = QFOC_SHUNT_OK;
    } else if (s->n_hold < s->hold_max) {
        s->n_hold++;
        r = QFOC_SHUNT_HELD;
    } else {
        r = QFOC_SHUNT_LOST;
    }
    out[0] = s->i[0];
    out[1] = s->i[1];
    out[2] = s->i[2];
    return r;
}

/* The small-angle rotation of a phase current (E13-7): i - i a^2 / 2 - q a, with h = a^2 / 2
   given (Q15). */
/*@
  requires range: QfocQ15Sym(i) && QfocQ15Sym(q) && QfocQ15Sym(a) && QfocQ15Sym(h);
  assigns \nothing;
  ensures range: QfocQ15Sym(\result);
  ensures still: a == 0 && h == 0 ==> \result == i;
*/
static qfoc_q15_t shunt_turn(qfoc_q15_t i, qfoc_q15_t q, int32_t a, int32_t h)
{
    const int32_t di = (int32_t)qfoc_q15_mul(i, (qfoc_q15_t)h);
    const int32_t dq = (int32_t)qfoc_q15_mul(q, (qfoc_q15_t)a);
    return qfoc_q15_sat(((int32_t)i - di) - dq);
}

/* The quadrature (i_a + 2 i_b) / sqrt 3 of a phase, its sign s (+1 or -1) (E13-7). */
/*@
  requires range: QfocQ15Sym(a) && QfocQ15Sym(b) && (s == 1 || s == -1);
  assigns \nothing;
  ensures range: QfocQ15Sym(\result);
*/
static qfoc_q15_t shunt_quad(qfoc_q15_t a, qfoc_q15_t b, int32_t s)
{
    const int32_t x = s * ((int32_t)a + (2 * (int32_t)b));
    return qfoc_q15_from_q30(x * QFOC_SHUNT_INV_SQRT3);
}

/* A value held within [-b, b]. */
/*@
  requires range: 0 <= b;
  assigns \nothing;
  ensures range: -b <= \result <= b;
  ensures kept: -b <= v <= b ==> \result == v;
*/
static int32_t shunt_clamp(int32_t v, int32_t b)
{
    return shunt_min(shunt_max(v, -b), b);
}

/* The PWM ripple of a phase current at tick n of the period (E13-8): g [y / p2 - 2 (n / p2)
   (dx / p2)] / 3, y = 3 (C_k - mean C) the ticks the phase was high up to n less the mean of
   the three, dx = 3 (x_k - mean x) twice over (2 x_k = up_k + down_k), each ratio in Q15. */
/*@
  requires range: 0 <= g <= 32767 && 200 <= p2 <= 65534;
  assigns \nothing;
  ensures range: QfocQ15Sym(\result);
  ensures zero: g == 0 ==> \result == 0;
*/
static int32_t shunt_ripple(int32_t g, int32_t y, int32_t n, int32_t dx2, int32_t p2)
{
    /* each ratio held within the Q15 range (it reaches 32768 at most) */
    const int32_t yq = shunt_clamp((shunt_clamp(y, p2) * 32768) / p2, 32767);
    const int32_t nq = shunt_clamp((shunt_min(shunt_max(n, 0), p2) * 32768) / p2, 32767);
    const int32_t xq = shunt_clamp((shunt_clamp(dx2, 2 * p2) * 16384) / p2, 32767);
    const int32_t m = (int32_t)qfoc_q15_mul((qfoc_q15_t)nq, (qfoc_q15_t)xq);
    const int32_t b = shunt_clamp((yq - (2 * m)) / 3, 32767);
    return (int32_t)qfoc_q15_mul((qfoc_q15_t)g, (qfoc_q15_t)b);
}

/* The angle from a sample at tick t to the instant r (E13-7): w (r - t) / (2 P), the ratio
   (r - t) / (2 P) held within [-1, 1] (it is, for a plan of the configuration) in Q15. */
/*@
  requires range: QfocQ15Sym(w) && 0 <= r <= 65534 && 0 <= t <= 65535 + 16384 &&
                  200 <= p2 <= 65534;
  assigns \nothing;
  ensures range: QfocQ15Sym(\result);
  ensures still: w == 0 ==> \result == 0;
*/
static int32_t shunt_angle(int32_t w, int32_t r, int32_t t, int32_t p2)
{
    const int32_t f = shunt_clamp((shunt_clamp(r - t, p2) * 32768) / p2, 32767);
    return (int32_t)qfoc_q15_mul((qfoc_q15_t)w, (qfoc_q15_t)f);
}

void qfoc_shunt_align(const qfoc_shunt_cfg_t *c, const qfoc_shunt_plan_t *p, int32_t dth,
                      int32_t g, uint8_t lead, qfoc_q15_t i[3])
{
    if (qfoc_shunt_cfg_is_valid(c) && p->ok && (p->hi <= 2u) && (p->lo <= 2u) &&
        (p->hi != p->lo)) {
        const uint8_t hi = p->hi;
        const uint8_t lo = p->lo;
        const uint8_t mid = (uint8_t)(3u - hi - lo);
        const int32_t p2 = 2 * (int32_t)c->period;
        const int32_t r = (lead == 0u) ? 0 : p2;
        const int32_t half = (int32_t)c->t_sample / 2;
        const int32_t d = shunt_min(shunt_max(dth, -QFOC_SHUNT_DTH_MAX), QFOC_SHUNT_DTH_MAX);
        /* pi in Q13: 25736; |w| <= 5215 x 25736 / 8192 = 16383 */
        const int32_t w = (d * 25736) / 8192;
        const int32_t a1 = shunt_angle(w, r, (int32_t)p->trig[0] + half, p2);
        const int32_t a2 = shunt_angle(w, r, (int32_t)p->trig[1] + half, p2);
        /* the step from the second sample to the first, held within 0.5 rad (16384) */
        const int32_t ad = shunt_min(shunt_max(a2 - a1, -16384), 16384);
        /* lo follows hi in the order u, v, w: q_hi = s (i_hi + 2 i_lo) / sqrt 3,
           q_lo = -s (2 i_hi + i_lo) / sqrt 3 */
        const int32_t s = (lo == (uint8_t)((hi + 1u) % 3u)) ? (int32_t)1 : (int32_t)-1;
        /* E13-8: the ripple at the two samples, taken off */
        const int32_t gr = shunt_min(shunt_max(g, 0), 32767);
        const int32_t n1 = (int32_t)p->trig[0] + half;
        const int32_t n2 = (int32_t)p->trig[1] + half;
        const int32_t per = (int32_t)c->period;
        const int32_t s0 = (int32_t)p->up[0] + (int32_t)p->down[0];
        const int32_t s1 = (int32_t)p->up[1] + (int32_t)p->down[1];
        const int32_t s2 = (int32_t)p->up[2] + (int32_t)p->down[2];
        const int32_t sx = (s0 + s1) + s2;
        const int32_t xs[3] = { s0, s1, s2 };
        /* high ticks up to the sample: hi alone at n1; hi and the middle one at n2 */
        const int32_t c1 = shunt_max((n1 - per) + (int32_t)p->up[hi], 0);
        const int32_t c2 = shunt_max((n2 - per) + (int32_t)p->up[hi], 0) +
                           shunt_max((n2 - per) + (int32_t)p->up[mid], 0);
        const int32_t rh = shunt_ripple(gr, 2 * c1, n1, (3 * xs[hi]) - sx, p2);
        const int32_t rl = shunt_ripple(gr, -c2, n2, (3 * xs[lo]) - sx, p2);
        const qfoc_q15_t ih = qfoc_q15_sat((int32_t)i[hi] - rh);
        const qfoc_q15_t il = qfoc_q15_sat((int32_t)i[lo] - rl);
        const int32_t hd = (int32_t)qfoc_q15_mul((qfoc_q15_t)ad, (qfoc_q15_t)ad) / 2;
        const int32_t h1 = (int32_t)qfoc_q15_mul((qfoc_q15_t)a1, (qfoc_q15_t)a1) / 2;
        const qfoc_q15_t il1 = shunt_turn(il, shunt_quad(il, ih, -s), ad, hd);
        const qfoc_q15_t ih2 = shunt_turn(ih, shunt_quad(ih, il1, s), a1, h1);
        const qfoc_q15_t il2 = shunt_turn(il1, shunt_quad(il1, ih, -s), a1, h1);
        i[hi] = ih2;
        i[lo] = il2;
        i[mid] = qfoc_q15_sat(-((int32_t)ih2 + (int32_t)il2));
    } else {
        /* no measurement of this plan: nothing to refer */
    }
}
