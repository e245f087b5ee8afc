/**
 * @file test_svpwm.c
 * @brief Tests of the SVPWM stage against an independent double-precision
 *        reference written from specs/equations.md section 6 (inverse
 *        Clarke, Tx = Ux / Vdc * Tpwm, Tx += Txd, sector table, T_mid injection).
 *
 * Requirements: REQ-SVPWM-001 .. REQ-SVPWM-011 (specs/requirements/svpwm.md).
 * Error bounds: include/qfoc/svpwm.h (REQ-SVPWM-010).
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "qfoc/svpwm.h"

#define SQRT3 1.7320508075688772
#define TEST_PI 3.14159265358979323846

/* ---------------------------------------------------------------- helpers */

static uint64_t lcg_state = 0x2545F4914F6CDD1DULL;

static uint32_t lcg_next(void)
{
    lcg_state = lcg_state * 6364136223846793005ULL + 1442695040888963407ULL;
    return (uint32_t)(lcg_state >> 32);
}

/* uniform integer in [lo, hi] */
static int32_t lcg_range(int32_t lo, int32_t hi)
{
    uint32_t span = (uint32_t)(hi - lo) + 1u;
    return lo + (int32_t)(lcg_next() % span);
}

/** Result of the double reference. */
typedef struct {
    double t[3];       /* compensated phase times before injection, ticks */
    double cmp[3];     /* compare values after injection and clamp, ticks */
    double ux[3];      /* phase voltages after the limit, volts LSB */
    double vdc;        /* bus voltage used */
    double mag;        /* commanded |v| */
    double util;       /* |v| / (vdc / sqrt 3) * 32768, saturated */
    int limited;       /* commanded vector outside the circle */
    int unclamped;     /* no compare value clamped */
} ref_t;

/* Document: Tx = Ux / Vdc * Tpwm; Tx += Txd; Tmid = Tpwm/2 - (max + min)/2. */
static void ref_svpwm(const qfoc_svpwm_cfg_t *c, double alpha, double beta, double vdc,
                      double iu, double iv, double iw, ref_t *r)
{
    const double p = (double)c->period;
    const double cur[3] = { iu, iv, iw };
    double v = vdc;
    double a = alpha;
    double b = beta;
    double rad;
    double tmax;
    double tmin;
    double off;
    int j;

    if (v < (double)c->vdc_min) {
        v = (double)c->vdc_min;
    }
    r->vdc = v;
    rad = v / SQRT3;
    r->mag = sqrt(a * a + b * b);
    r->util = r->mag * SQRT3 / v * 32768.0;
    if (r->util > 32767.0) {
        r->util = 32767.0;
    }
    r->limited = (r->mag > rad) ? 1 : 0;
    if (r->limited != 0) {
        a = a * rad / r->mag;
        b = b * rad / r->mag;
    }
    /* inverse Clarke, ideal */
    r->ux[0] = a;
    r->ux[1] = (-a + SQRT3 * b) / 2.0;
    r->ux[2] = (-a - SQRT3 * b) / 2.0;
    for (j = 0; j < 3; j++) {
        double comp = 0.0;
        double ai = fabs(cur[j]);
        if (cur[j] != 0.0) {
            comp = (ai >= (double)c->i_deadband) ? (double)c->dt_comp
                                                 : ai * (double)c->dt_comp / (double)c->i_deadband;
            if (cur[j] < 0.0) {
                comp = -comp;
            }
        }
        r->t[j] = r->ux[j] / v * p + comp;
    }
    tmax = fmax(r->t[0], fmax(r->t[1], r->t[2]));
    tmin = fmin(r->t[0], fmin(r->t[1], r->t[2]));
    off = p / 2.0 - (tmax + tmin) / 2.0;
    r->unclamped = 1;
    for (j = 0; j < 3; j++) {
        double x = r->t[j] + off;
        if (x < 0.0) {
            x = 0.0;
            r->unclamped = 0;
        } else if (x > p) {
            x = p;
            r->unclamped = 0;
        }
        r->cmp[j] = x;
    }
}

/* Does sector s order the reference times a, b, c within tolerance tol? */
static int ref_sector_ok(int s, const double t[3], double tol)
{
    const double a = t[0];
    const double b = t[1];
    const double c = t[2];
    int ok = 0;
    switch (s) {
    case 1: ok = (a >= b - tol) && (b >= c - tol); break;
    case 2: ok = (a >= c - tol) && (c >= b - tol); break;
    case 3: ok = (b >= c - tol) && (c >= a - tol); break;
    case 4: ok = (b >= a - tol) && (a >= c - tol); break;
    case 5: ok = (c >= a - tol) && (a >= b - tol); break;
    case 6: ok = (c >= b - tol) && (b >= a - tol); break;
    default: ok = 0; break;
    }
    return ok;
}

/* Bound of the header (REQ-SVPWM-010), ticks. */
static double bound_ticks(const qfoc_svpwm_cfg_t *c, double vdc, int limited, int fade)
{
    double b = 3.0 + ((limited != 0) ? 8.0 : 2.0) * (double)c->period / vdc;
    if (fade != 0) {
        b += 2.0;
    }
    return b;
}

static int in_fade(const qfoc_svpwm_cfg_t *c, const qfoc_abc_t *i)
{
    int32_t db = (int32_t)c->i_deadband;
    return ((i->u != 0 && abs(i->u) < db) || (i->v != 0 && abs(i->v) < db) ||
            (i->w != 0 && abs(i->w) < db)) ? 1 : 0;
}

/* measured maxima, printed at the end of the random test */
static double max_err_lin = 0.0;
static double max_err_lim = 0.0;
static double max_err_ll = 0.0;
static double max_err_util = 0.0;
static double max_err_lin_typ = 0.0;
static double max_frac_bound = 0.0;   /* max of error / bound */

/* Run one case: implementation vs reference, assert every property. */
static void check_case(const qfoc_svpwm_cfg_t *c, qfoc_q15_t alpha, qfoc_q15_t beta,
                       qfoc_q15_t vdc, const qfoc_abc_t *i)
{
    qfoc_ab_t ab = { alpha, beta };
    qfoc_svpwm_out_t o;
    ref_t r;
    int j;
    int lim;
    int fade = in_fade(c, i);
    double bnd;
    double tol;

    qfoc_svpwm_step(c, &ab, vdc, i, &o);
    ref_svpwm(c, (double)alpha, (double)beta, (double)vdc, (double)i->u, (double)i->v,
              (double)i->w, &r);

    /* REQ-SVPWM-004: ranges */
    for (j = 0; j < 3; j++) {
        assert_true(o.cmp[j] <= c->period);
    }
    assert_true((o.sector >= 1u) && (o.sector <= 6u));
    assert_true(o.utilisation >= 0);

    /* REQ-SVPWM-003: bus clamp flag */
    assert_int_equal(o.vdc_low ? 1 : 0, (vdc < c->vdc_min) ? 1 : 0);

    /* REQ-SVPWM-005: limit flag, away from the circle (rounding of |v| and r) */
    {
        double rad = r.vdc / SQRT3;
        if (r.mag > rad + 3.0) {
            assert_true(o.limited);
        } else if (r.mag < rad - 3.0) {
            assert_false(o.limited);
        }
    }
    lim = (o.limited || (r.limited != 0)) ? 1 : 0;

    /* REQ-SVPWM-010: compare values vs the reference */
    bnd = bound_ticks(c, r.vdc, lim, fade);
    for (j = 0; j < 3; j++) {
        double e = fabs((double)o.cmp[j] - r.cmp[j]);
        if (e > bnd) {
            print_message("cmp[%d] P=%u dt=%u db=%d a=%d b=%d vdc=%d i=%d,%d,%d: %u vs %.3f\n", j,
                          c->period, c->dt_comp, c->i_deadband, alpha, beta, vdc, i->u, i->v,
                          i->w, o.cmp[j], r.cmp[j]);
        }
        assert_true(e <= bnd);
        max_frac_bound = fmax(max_frac_bound, e / bnd);
        if (lim != 0) {
            max_err_lim = fmax(max_err_lim, e);
        } else {
            max_err_lin = fmax(max_err_lin, e);
            if ((r.vdc >= 8000.0) && (c->period <= 5000u)) {
                max_err_lin_typ = fmax(max_err_lin_typ, e);
            }
        }
    }

    /* REQ-SVPWM-006: sector from the reference ordering (ties within the bound) */
    tol = 2.0 * bnd;
    assert_true(ref_sector_ok((int)o.sector, r.t, tol));

    /* REQ-SVPWM-009: utilisation (|v| one LSB -> 56756 / vdc LSB of utilisation) */
    {
        double eu = fabs((double)o.utilisation - r.util);
        double bu = 2.0 + 2.0 * SQRT3 * 32768.0 / r.vdc;
        if ((r.mag > r.vdc / SQRT3 + 3.0) || (o.limited)) {
            /* saturated region: exactly 1.0 */
            if (r.mag > r.vdc / SQRT3 + 3.0) {
                assert_int_equal(o.utilisation, 32767);
            }
        } else {
            assert_true(eu <= bu);
            max_err_util = fmax(max_err_util, eu);
        }
    }

    /* REQ-SVPWM-007, REQ-SVPWM-008: linear range, unclamped, no compensation:
     * line-to-line voltages reproduced and pulses centred */
    if ((lim == 0) && (r.unclamped != 0) && (c->dt_comp == 0u) &&
        (o.cmp[0] > 0u) && (o.cmp[1] > 0u) && (o.cmp[2] > 0u) &&
        (o.cmp[0] < c->period) && (o.cmp[1] < c->period) && (o.cmp[2] < c->period)) {
        const double p = (double)c->period;
        int x;
        uint32_t mx = o.cmp[0];
        uint32_t mn = o.cmp[0];
        for (x = 0; x < 3; x++) {
            int y = (x + 1) % 3;
            double ull = ((double)o.cmp[x] - (double)o.cmp[y]) / p * r.vdc;
            double uref = r.ux[x] - r.ux[y];
            double ell = fabs(ull - uref);
            double bll = 2.0 + 2.0 * r.vdc / p;   /* = (2 + 2 P / vdc) ticks in volts */
            assert_true(ell <= bll);
            max_err_ll = fmax(max_err_ll, ell / r.vdc * p);
            if (o.cmp[x] > mx) {
                mx = o.cmp[x];
            }
            if (o.cmp[x] < mn) {
                mn = o.cmp[x];
            }
        }
        assert_true(abs((int)(mx + mn) - (int)c->period) <= 1);
    }
}

static qfoc_svpwm_cfg_t make_cfg(uint16_t p, uint16_t dt, qfoc_q15_t db, qfoc_q15_t vmin)
{
    qfoc_svpwm_cfg_t c;
    c.period = p;
    c.dt_comp = dt;
    c.i_deadband = db;
    c.vdc_min = vmin;
    return c;
}

static const qfoc_abc_t i_zero = { 0, 0, 0 };

/* ------------------------------------------------------------------ tests */

/* REQ-SVPWM-001: configuration invariant
   Methods: 1b valid and invalid configurations, one field out of range each; 1c the period
   99 / 100 and 32767 / 32768, the dead-time compensation at and above P / 4, vdc_min -1 and
   0, the dead band 0 and -32768 */
static void test_req_svpwm_001_cfg_valid(void **state)
{
    qfoc_svpwm_cfg_t c;
    (void)state;
    c = make_cfg(5000u, 100u, 300, 1000);
    assert_true(qfoc_svpwm_cfg_is_valid(&c));
    c = make_cfg(100u, 25u, 0, 1);
    assert_true(qfoc_svpwm_cfg_is_valid(&c));
    c = make_cfg(32767u, 8191u, 32767, 32767);
    assert_true(qfoc_svpwm_cfg_is_valid(&c));
    c = make_cfg(99u, 0u, 0, 1);
    assert_false(qfoc_svpwm_cfg_is_valid(&c));
    c = make_cfg(32768u, 0u, 0, 1);
    assert_false(qfoc_svpwm_cfg_is_valid(&c));
    c = make_cfg(100u, 26u, 0, 1);
    assert_false(qfoc_svpwm_cfg_is_valid(&c));
    c = make_cfg(5000u, 0u, -1, 1);
    assert_false(qfoc_svpwm_cfg_is_valid(&c));
    c = make_cfg(5000u, 0u, 0, 0);
    assert_false(qfoc_svpwm_cfg_is_valid(&c));
    c = make_cfg(5000u, 0u, 0, -32768);
    assert_false(qfoc_svpwm_cfg_is_valid(&c));
}

/* REQ-SVPWM-002: invalid configuration gives the safe zero-voltage output
   Methods: 1b seven invalid configurations, each rule broken; 1c periods 0, 99 and 65535,
   compensation 1251 for P = 5000; 1d an invalid configuration reaching the step: the safe
   zero-voltage pattern */
static void test_req_svpwm_002_invalid_cfg_safe(void **state)
{
    const qfoc_svpwm_cfg_t bad[] = {
        { 0u, 0u, 0, 100 }, { 99u, 0u, 0, 100 }, { 65535u, 0u, 0, 100 },
        { 5000u, 1251u, 0, 100 }, { 5000u, 0u, -5, 100 }, { 5000u, 0u, 0, 0 },
        { 40001u, 10u, 10, -1 }
    };
    const qfoc_ab_t ab = { 32767, -32768 };
    const qfoc_abc_t i = { 1000, -1000, 0 };
    size_t n;
    (void)state;
    for (n = 0; n < sizeof(bad) / sizeof(bad[0]); n++) {
        qfoc_svpwm_out_t o;
        uint16_t half = (uint16_t)(bad[n].period / 2u);
        qfoc_svpwm_step(&bad[n], &ab, 20000, &i, &o);
        assert_int_equal(o.cmp[0], half);
        assert_int_equal(o.cmp[1], half);
        assert_int_equal(o.cmp[2], half);
        assert_true(o.limited);
        assert_false(o.vdc_low);
        assert_int_equal(o.sector, 1);
        assert_int_equal(o.utilisation, 0);
    }
}

/* REQ-SVPWM-003: bus voltage below vdc_min (0, negative, -32768) is replaced
   Methods: 1c bus voltages -32768, -32767, -1, 0, 1 and vdc_min - 1, vdc_min, vdc_min + 1,
   32767 crossed with six voltage vectors; 1d a bus voltage at or below 0 (a failed
   measurement); 1n the double-precision reference of section 6 of specs/equations.md */
static void test_req_svpwm_003_vdc_clamp(void **state)
{
    const qfoc_svpwm_cfg_t c = make_cfg(5000u, 0u, 0, 4000);
    const qfoc_q15_t vd[] = { -32768, -32767, -1, 0, 1, 3999, 4000, 4001, 32767 };
    const qfoc_q15_t av[] = { 0, 1000, -2000, 2309, 32767, -32768 };
    size_t n;
    size_t m;
    (void)state;
    for (n = 0; n < sizeof(vd) / sizeof(vd[0]); n++) {
        for (m = 0; m < sizeof(av) / sizeof(av[0]); m++) {
            qfoc_ab_t ab = { av[m], (qfoc_q15_t)(av[m] / 3) };
            qfoc_svpwm_out_t o;
            qfoc_svpwm_out_t o_min;
            check_case(&c, ab.alpha, ab.beta, vd[n], &i_zero);
            qfoc_svpwm_step(&c, &ab, vd[n], &i_zero, &o);
            assert_int_equal(o.vdc_low ? 1 : 0, (vd[n] < 4000) ? 1 : 0);
            if (vd[n] < 4000) {
                /* identical to a call with vdc = vdc_min */
                qfoc_svpwm_step(&c, &ab, 4000, &i_zero, &o_min);
                assert_memory_equal(o.cmp, o_min.cmp, sizeof(o.cmp));
                assert_int_equal(o.sector, o_min.sector);
            }
        }
    }
}

/* REQ-SVPWM-004, REQ-SVPWM-010: Q15 corners of every input, three periods
   Methods: 1c eight Q15 corners (-32768 .. 32767) of alpha, beta and the bus and of the
   three currents, at the periods 100, 5000 and 32767, with and without compensation; 1n the
   double-precision reference */
static void test_req_svpwm_004_corners(void **state)
{
    const qfoc_q15_t q[] = { -32768, -32767, -16384, -1, 0, 1, 16384, 32767 };
    const qfoc_q15_t vd[] = { -32768, -1, 0, 1, 2, 100, 16384, 32767 };
    const uint16_t per[] = { 100u, 5000u, 32767u };
    size_t a;
    size_t b;
    size_t v;
    size_t p;
    (void)state;
    for (p = 0; p < 3u; p++) {
        for (a = 0; a < 8u; a++) {
            for (b = 0; b < 8u; b++) {
                for (v = 0; v < 8u; v++) {
                    qfoc_svpwm_cfg_t c = make_cfg(per[p], 0u, 0, 1);
                    qfoc_abc_t i = { q[b], q[a], q[v] };
                    check_case(&c, q[a], q[b], vd[v], &i_zero);
                    c.dt_comp = (uint16_t)(per[p] / 4u);
                    c.i_deadband = 1000;
                    check_case(&c, q[a], q[b], vd[v], &i);
                }
            }
        }
    }
}

/* REQ-SVPWM-006: vectors on the six sector boundaries and just beside them
   Methods: 1b every sector: vectors 10 degrees inside each of the six wedges at six radii;
   1c the vectors on the six sector boundaries, the zero vector and the exact ties of the
   equations (beta = 0); 1n the double-precision reference */
static void test_req_svpwm_006_sector_boundaries(void **state)
{
    const qfoc_svpwm_cfg_t c = make_cfg(5000u, 0u, 0, 1000);
    const double radii[] = { 0.0, 1.0, 3000.0, 24000.0 / SQRT3, 30000.0 / SQRT3, 30000.0 };
    /* document's sector of the open 60-degree wedge starting at k*60 degrees */
    const int wedge[6] = { 1, 4, 3, 6, 5, 2 };
    size_t r;
    int k;
    qfoc_svpwm_out_t o;
    qfoc_ab_t ab;
    (void)state;
    for (r = 0; r < sizeof(radii) / sizeof(radii[0]); r++) {
        for (k = 0; k < 6; k++) {
            int d;
            for (d = -1; d <= 1; d++) {
                double th = ((double)k * 60.0 + (double)d * 10.0) * TEST_PI / 180.0;
                qfoc_q15_t al = (qfoc_q15_t)lround(radii[r] * cos(th));
                qfoc_q15_t be = (qfoc_q15_t)lround(radii[r] * sin(th));
                check_case(&c, al, be, 24000, &i_zero);
                if ((r >= 2u) && (d != 0)) {
                    /* well inside a wedge: the sector is unique */
                    int s = wedge[(d > 0) ? k : ((k + 5) % 6)];
                    ab.alpha = al;
                    ab.beta = be;
                    qfoc_svpwm_step(&c, &ab, 24000, &i_zero, &o);
                    assert_int_equal(o.sector, s);
                }
            }
        }
    }
    /* exact ties from the equations: beta = 0 gives Uv == Uw; zero vector all equal */
    ab.alpha = 0;
    ab.beta = 0;
    qfoc_svpwm_step(&c, &ab, 24000, &i_zero, &o);
    assert_int_equal(o.sector, 1);              /* all equal: first row */
    ab.alpha = 5000;
    qfoc_svpwm_step(&c, &ab, 24000, &i_zero, &o);
    assert_int_equal(o.sector, 1);              /* Ta > Tb == Tc: rows 1 and 2, first wins */
    assert_int_equal(o.cmp[1], o.cmp[2]);
    ab.alpha = -5000;
    qfoc_svpwm_step(&c, &ab, 24000, &i_zero, &o);
    assert_int_equal(o.sector, 3);              /* Tb == Tc > Ta: rows 3 and 6 */
    assert_int_equal(o.cmp[1], o.cmp[2]);
}

/* REQ-SVPWM-005, REQ-SVPWM-009: overmodulation limited onto the inscribed circle
   Methods: 1b 72 angles on the full-scale circle at four bus voltages; 1c |v|^2 on both
   sides of 32767^2 (where the magnitude switches to the halved vector), the corners (32767,
   32767) and (-32768, -32768); 1n the applied voltage reconstructed from the pole voltages
   against Vdc / sqrt(3) */
static void test_req_svpwm_005_overmodulation(void **state)
{
    const qfoc_q15_t vd[] = { 100, 1000, 16000, 32767 };
    size_t v;
    int k;
    double max_rad_err = 0.0;
    (void)state;
    for (v = 0; v < 4u; v++) {
        for (k = 0; k < 72; k++) {
            const qfoc_svpwm_cfg_t c = make_cfg(5000u, 0u, 0, 1);
            double th = (double)k * 5.0 * TEST_PI / 180.0;
            qfoc_ab_t ab = { (qfoc_q15_t)lround(32767.0 * cos(th)),
                             (qfoc_q15_t)lround(32767.0 * sin(th)) };
            qfoc_svpwm_out_t o;
            double p = 5000.0;
            double vdc = (double)vd[v];
            double u[3];
            double al;
            double be;
            double rad;
            check_case(&c, ab.alpha, ab.beta, vd[v], &i_zero);
            qfoc_svpwm_step(&c, &ab, vd[v], &i_zero, &o);
            assert_true(o.limited);
            assert_int_equal(o.utilisation, 32767);
            /* voltage actually applied, from the pole voltages */
            u[0] = (double)o.cmp[0] / p * vdc;
            u[1] = (double)o.cmp[1] / p * vdc;
            u[2] = (double)o.cmp[2] / p * vdc;
            al = (2.0 * u[0] - u[1] - u[2]) / 3.0;
            be = (u[1] - u[2]) / SQRT3;
            rad = sqrt(al * al + be * be);
            /* on the circle vdc / sqrt 3, within the bound of REQ-SVPWM-010 */
            assert_true(fabs(rad - vdc / SQRT3) <= (3.0 + 8.0 * p / vdc) * vdc / p);
            max_rad_err = fmax(max_rad_err, fabs(rad - vdc / SQRT3) / vdc * p);
            /* the angle is kept (for radii of at least a few LSB) */
            if (vd[v] >= 1000) {
                double dth = atan2(be, al) - atan2((double)ab.beta, (double)ab.alpha);
                dth = remainder(dth, 2.0 * TEST_PI);
                assert_true(fabs(dth) < 0.01);
            }
        }
    }
    /* alpha = beta = 32767: |v| = 46339 exceeds the Q15 range of the magnitude */
    {
        const qfoc_svpwm_cfg_t c = make_cfg(5000u, 0u, 0, 1);
        check_case(&c, 32767, 32767, 32767, &i_zero);
        check_case(&c, -32768, -32768, 32767, &i_zero);
        check_case(&c, -32768, 32767, 20000, &i_zero);
    }
    /* |v|^2 on both sides of 32767^2, where the magnitude switches to the halved
     * vector: (32766, 255) has |v|^2 = 32767^2 - 508, (32766, 256) and (32767, 0)
     * reach 32767^2 or more; every such vector is limited onto the circle */
    {
        const qfoc_svpwm_cfg_t c = make_cfg(5000u, 0u, 0, 1);
        const qfoc_q15_t edge[][2] = { { 32766, 255 }, { 32766, 256 }, { 32767, 0 },
                                       { 0, -32768 }, { -32768, 0 }, { -255, -32766 } };
        size_t e;
        for (e = 0; e < sizeof(edge) / sizeof(edge[0]); e++) {
            qfoc_ab_t ab = { edge[e][0], edge[e][1] };
            qfoc_svpwm_out_t o;
            check_case(&c, edge[e][0], edge[e][1], 32767, &i_zero);
            check_case(&c, edge[e][0], edge[e][1], 100, &i_zero);
            qfoc_svpwm_step(&c, &ab, 32767, &i_zero, &o);
            assert_true(o.limited);
            assert_int_equal(o.utilisation, 32767);
        }
    }
    print_message("overmodulation: max |radius - vdc/sqrt3| = %.3f ticks\n", max_rad_err);
}

/* REQ-SVPWM-008, REQ-SVPWM-011: dead-time compensation sign and dead band
   Methods: 1b currents of each sign, inside and outside the dead band; 1c currents exactly
   at the band edge, the smallest current (1 LSB), dead band 0 with -32768, compensation that
   pushes a phase beyond the period; 1n the double-precision reference */
static void test_req_svpwm_008_dead_time(void **state)
{
    const qfoc_svpwm_cfg_t c = make_cfg(5000u, 200u, 1000, 1000);
    const qfoc_svpwm_cfg_t c0 = make_cfg(5000u, 200u, 0, 1000);
    const qfoc_ab_t ab = { 0, 0 };
    qfoc_svpwm_out_t o;
    qfoc_abc_t i;
    (void)state;
    /* zero vector, full compensation: u +200, v -200, w 0 -> centred on 2500 */
    i.u = 5000;
    i.v = -5000;
    i.w = 0;
    qfoc_svpwm_step(&c, &ab, 20000, &i, &o);
    assert_int_equal((int)o.cmp[0] - (int)o.cmp[2], 200);
    assert_int_equal((int)o.cmp[1] - (int)o.cmp[2], -200);
    assert_int_equal((int)o.cmp[0] + (int)o.cmp[1], 5000);
    check_case(&c, 0, 0, 20000, &i);
    /* exactly at the band edge: full compensation */
    i.u = 1000;
    i.v = -1000;
    qfoc_svpwm_step(&c, &ab, 20000, &i, &o);
    assert_int_equal((int)o.cmp[0] - (int)o.cmp[2], 200);
    assert_int_equal((int)o.cmp[1] - (int)o.cmp[2], -200);
    /* inside the band: linear fade 500 / 1000 * 200 = 100 */
    i.u = 500;
    i.v = -500;
    qfoc_svpwm_step(&c, &ab, 20000, &i, &o);
    assert_int_equal((int)o.cmp[0] - (int)o.cmp[2], 100);
    assert_int_equal((int)o.cmp[1] - (int)o.cmp[2], -100);
    check_case(&c, 0, 0, 20000, &i);
    /* smallest currents: 1 / 1000 * 200 = 0.2 -> 0 */
    i.u = 1;
    i.v = -1;
    qfoc_svpwm_step(&c, &ab, 20000, &i, &o);
    assert_int_equal(o.cmp[0], o.cmp[2]);
    assert_int_equal(o.cmp[1], o.cmp[2]);
    /* dead band 0: pure sign, zero current gives no compensation */
    i.u = 1;
    i.v = -32768;
    i.w = 0;
    qfoc_svpwm_step(&c0, &ab, 20000, &i, &o);
    assert_int_equal((int)o.cmp[0] - (int)o.cmp[2], 200);
    assert_int_equal((int)o.cmp[1] - (int)o.cmp[2], -200);
    check_case(&c0, 0, 0, 20000, &i);
    /* with a voltage: compensation adds to the reference times */
    i.u = 32767;
    i.v = -32767;
    i.w = -300;
    check_case(&c, 8000, -3000, 20000, &i);
    check_case(&c0, 8000, -3000, 20000, &i);
    /* compensation pushing a phase beyond the period: clamped to [0, P] */
    check_case(&c, 11000, 0, 20000, &i);
}

/* REQ-SVPWM-004, REQ-SVPWM-005, REQ-SVPWM-006, REQ-SVPWM-007, REQ-SVPWM-008, REQ-SVPWM-009,
   REQ-SVPWM-010: random inputs vs the reference, every case through check_case (ranges,
   limit flag, sector, line-to-line voltages and centred pulses, utilisation, compare
   values)
   Methods: 1b 300000 random cases in four classes: any input, typical drive at 5000 ticks,
   any period, with dead-time compensation; 1n the double-precision reference of every
   output, within the bound of REQ-SVPWM-010 */
static void test_req_svpwm_010_random(void **state)
{
    uint32_t n;
    (void)state;
    for (n = 0u; n < 300000u; n++) {
        qfoc_svpwm_cfg_t c;
        qfoc_abc_t i;
        qfoc_q15_t al;
        qfoc_q15_t be;
        qfoc_q15_t vd;
        uint32_t mode = n % 4u;
        if (mode == 0u) {
            /* anything */
            c.period = (uint16_t)lcg_range(100, 32767);
            c.vdc_min = (qfoc_q15_t)lcg_range(1, 32767);
            vd = (qfoc_q15_t)lcg_range(-32768, 32767);
            al = (qfoc_q15_t)lcg_range(-32768, 32767);
            be = (qfoc_q15_t)lcg_range(-32768, 32767);
        } else {
            /* typical drive: 8 kHz at 80 MHz, bus 0.25 .. 1.0 of the base,
             * vectors mostly inside the circle (linear range) */
            c.period = (mode == 1u) ? 5000u : (uint16_t)lcg_range(100, 32767);
            c.vdc_min = 1000;
            vd = (qfoc_q15_t)lcg_range(8000, 32767);
            al = (qfoc_q15_t)lcg_range(-(int32_t)vd * 6 / 10, (int32_t)vd * 6 / 10);
            be = (qfoc_q15_t)lcg_range(-(int32_t)vd * 6 / 10, (int32_t)vd * 6 / 10);
        }
        if (mode == 3u) {
            c.dt_comp = (uint16_t)lcg_range(0, (int32_t)c.period / 4);
            c.i_deadband = (qfoc_q15_t)lcg_range(0, 3000);
        } else {
            c.dt_comp = 0u;
            c.i_deadband = 0;
        }
        i.u = (qfoc_q15_t)lcg_range(-32768, 32767) / (qfoc_q15_t)lcg_range(1, 20);
        i.v = (qfoc_q15_t)lcg_range(-32768, 32767) / (qfoc_q15_t)lcg_range(1, 20);
        i.w = (qfoc_q15_t)lcg_range(-32768, 32767) / (qfoc_q15_t)lcg_range(1, 20);
        check_case(&c, al, be, vd, &i);
    }
    print_message("max |cmp - ref| linear: %.3f ticks (typical: vdc >= 8000, P <= 5000: %.3f)\n",
                  max_err_lin, max_err_lin_typ);
    print_message("max |cmp - ref| limited: %.3f ticks\n", max_err_lim);
    print_message("max |cmp - ref| / bound of REQ-SVPWM-010 (all checks so far): %.3f\n",
                  max_frac_bound);
    print_message("max line-to-line voltage error: %.3f ticks (bound 2 + 2 P / Vdc)\n", max_err_ll);
    print_message("max utilisation error (linear range): %.3f LSB\n", max_err_util);
}

/* REQ-SVPWM-012: without the overmodulation limit.  Inside the circle (|v| <= Vdc /
   sqrt 3 of the bus used) the compare values, sector and bus flag equal those of
   qfoc_svpwm_step() (which the double reference checks above), and the double
   reference of specs/equations.md section 6 holds as well; outside, the compare values stay
   in [0, P]; an invalid configuration gives the safe pattern; utilisation 0, limited
   false.
   Methods: 1b 200000 random cases: vectors inside the circle and anywhere, random periods,
   compensation and bus voltages, every 17th bus voltage any value; 1d an invalid
   configuration (period 50): the safe pattern; 1n qfoc_svpwm_step() inside the circle and
   the double-precision reference */
static void test_req_svpwm_012_linear_step(void **state)
{
    uint32_t n;
    uint32_t n_inside = 0u;
    double max_err = 0.0;
    (void)state;
    for (n = 0u; n < 200000u; n++) {
        qfoc_svpwm_cfg_t c;
        qfoc_abc_t i;
        qfoc_ab_t v;
        qfoc_svpwm_out_t a;
        qfoc_svpwm_out_t b;
        qfoc_q15_t vd;
        double vbus;
        double mag;
        int j;
        c.period = (n % 3u == 0u) ? 5000u : (uint16_t)lcg_range(100, 32767);
        c.vdc_min = (qfoc_q15_t)lcg_range(1, 12000);
        c.dt_comp = (uint16_t)lcg_range(0, (int32_t)c.period / 4);
        c.i_deadband = (qfoc_q15_t)lcg_range(0, 3000);
        vd = (n % 17u == 0u) ? (qfoc_q15_t)lcg_range(-32768, 32767)
                             : (qfoc_q15_t)lcg_range(2000, 32767);
        if (n % 5u == 0u) {
            v.alpha = (qfoc_q15_t)lcg_range(-32768, 32767);
            v.beta = (qfoc_q15_t)lcg_range(-32768, 32767);
        } else {
            const int32_t r = ((int32_t)(vd > c.vdc_min ? vd : c.vdc_min) * 55) / 100;
            v.alpha = (qfoc_q15_t)lcg_range(-r, r);
            v.beta = (qfoc_q15_t)lcg_range(-r, r);
        }
        i.u = (qfoc_q15_t)lcg_range(-4000, 4000);
        i.v = (qfoc_q15_t)lcg_range(-4000, 4000);
        i.w = (qfoc_q15_t)lcg_range(-32768, 32767);
        qfoc_svpwm_step_lin(&c, &v, vd, &i, &a);
        qfoc_svpwm_step(&c, &v, vd, &i, &b);
        assert_false(a.limited);
        assert_int_equal(a.utilisation, 0);
        assert_int_equal(a.vdc_low, b.vdc_low);
        assert_true((a.sector >= 1u) && (a.sector <= 6u));
        for (j = 0; j < 3; j++) {
            assert_true(a.cmp[j] <= c.period);
        }
        vbus = (vd < c.vdc_min) ? (double)c.vdc_min : (double)vd;
        mag = sqrt((double)v.alpha * v.alpha + (double)v.beta * v.beta);
        if (mag <= vbus / SQRT3 - 1.0) {
            ref_t r;
            n_inside++;
            assert_false(b.limited);
            assert_int_equal(a.sector, b.sector);
            for (j = 0; j < 3; j++) {
                assert_int_equal(a.cmp[j], b.cmp[j]);
            }
            ref_svpwm(&c, (double)v.alpha, (double)v.beta, (double)vd, (double)i.u,
                      (double)i.v, (double)i.w, &r);
            {
                const double bnd = bound_ticks(&c, r.vdc, 0, in_fade(&c, &i));
                for (j = 0; j < 3; j++) {
                    const double e = fabs((double)a.cmp[j] - r.cmp[j]);
                    assert_true(e <= bnd);
                    max_err = fmax(max_err, e / bnd);
                }
            }
        }
    }
    {
        /* invalid configuration: the safe pattern */
        qfoc_svpwm_cfg_t c = { 50u, 0u, 0, 100 };
        qfoc_ab_t v = { 1000, -1000 };
        qfoc_abc_t i = { 0, 0, 0 };
        qfoc_svpwm_out_t a;
        qfoc_svpwm_step_lin(&c, &v, 20000, &i, &a);
        assert_int_equal(a.cmp[0], 25u);
        assert_int_equal(a.cmp[1], 25u);
        assert_int_equal(a.cmp[2], 25u);
        assert_true(a.limited);
        assert_false(a.vdc_low);
        assert_int_equal(a.sector, 1u);
    }
    print_message("linear step: %u vectors inside the circle equal to qfoc_svpwm_step, max "
                  "|cmp - double reference| / bound of REQ-SVPWM-010 %.3f\n", (unsigned)n_inside,
                  max_err);
    assert_true(n_inside > 100000u);
}

/* REQ-SVPWM-007, REQ-SVPWM-010, REQ-SVPWM-011: period extremes 100 and 32767
   Methods: 1b 52 angles of the voltage and current vectors; 1c the period extremes 100 and
   32767, the bus at 100 and 32767; 1n the double-precision reference */
static void test_req_svpwm_011_periods(void **state)
{
    const uint16_t per[] = { 100u, 32767u };
    size_t p;
    int k;
    (void)state;
    for (p = 0; p < 2u; p++) {
        const qfoc_svpwm_cfg_t c = make_cfg(per[p], 0u, 0, 100);
        const qfoc_svpwm_cfg_t cd = make_cfg(per[p], (uint16_t)(per[p] / 4u), 200, 100);
        for (k = 0; k < 360; k += 7) {
            double th = (double)k * TEST_PI / 180.0;
            qfoc_abc_t i = { (qfoc_q15_t)lround(3000.0 * cos(th)),
                             (qfoc_q15_t)lround(3000.0 * cos(th - 2.0944)),
                             (qfoc_q15_t)lround(3000.0 * cos(th + 2.0944)) };
            qfoc_q15_t al = (qfoc_q15_t)lround(18000.0 * cos(th));
            qfoc_q15_t be = (qfoc_q15_t)lround(18000.0 * sin(th));
            check_case(&c, al, be, 32767, &i_zero);
            check_case(&c, al, be, 31000, &i_zero);
            check_case(&cd, al, be, 32767, &i);
            check_case(&c, al, be, 100, &i_zero);
        }
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_req_svpwm_001_cfg_valid),
        cmocka_unit_test(test_req_svpwm_002_invalid_cfg_safe),
        cmocka_unit_test(test_req_svpwm_003_vdc_clamp),
        cmocka_unit_test(test_req_svpwm_004_corners),
        cmocka_unit_test(test_req_svpwm_005_overmodulation),
        cmocka_unit_test(test_req_svpwm_006_sector_boundaries),
        cmocka_unit_test(test_req_svpwm_008_dead_time),
        cmocka_unit_test(test_req_svpwm_010_random),
        cmocka_unit_test(test_req_svpwm_011_periods),
        cmocka_unit_test(test_req_svpwm_012_linear_step),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
