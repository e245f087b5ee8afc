/**
 * @file qfoc_shunt.c
 * @brief Single-shunt current measurement (shunt.h): the plan of a period (the edge shift
 *        and the sampling instants) and the phase currents rebuilt from two DC-link
 *        samples, with the hold of the last currents.
 *
 * Requirements: REQ-SHUNT-001 .. REQ-SHUNT-004 (specs/requirements/shunt.md).
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
