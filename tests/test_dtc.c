/*
 * test_dtc.c -- unit tests of the inverter's residual voltage error (include/qfoc/dtc.h).
 *
 * Reference: the model of specs/equations.md section 10 in double precision:
 *  - the fade f(i) = clamp(i / i_db, -1, 1) (sign(i) for i_db <= 0), in Q15 counts;
 *  - an aligned rotor at i_hi and at i_lo = i_hi / 2: u = R' i + dV s_d(i),
 *    s_d(i) = (2/3)(f(i) - f(-i / 2)); the learnt error is dV, clamped to the accepted
 *    bound, when R' is within the table's allowance of R, and 0 when it is clearly not;
 *  - the error vector dV Clarke(f(i_u), f(i_v), f(i_w)) (amplitude-invariant Clarke).
 * Tolerances come from the truncations the header states: the fade is exact; the learnt
 * error within 3 + 2 / |den| LSB (the rounded voltages, the quotient); the vector within
 * 1 + 2.4 |dV| / 32768 LSB (the fades' and factors' truncations, scaled by dV).
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>
#include <math.h>
#include <stdlib.h>
#include <stdbool.h>

#include "qfoc/dtc.h"
#define TEST_SEED 2718u
#include "test_util.h"

/* ---- double references ---------------------------------------------------- */

static double ref_fade(double i, double db)
{
    if (db <= 0.0) {
        return (i > 0.0) ? 1.0 : ((i < 0.0) ? -1.0 : 0.0);
    }
    if (i >= db) {
        return 1.0;
    }
    if (i <= -db) {
        return -1.0;
    }
    return i / db;
}

/* s_d with the half current truncated to an integer, as the header states */
static double ref_sd(int i_a, double db)
{
    return (2.0 / 3.0) * (ref_fade((double)i_a, db) - ref_fade(-(double)(i_a / 2), db));
}

static double clampd(double x, double lo, double hi)
{
    return (x < lo) ? lo : ((x > hi) ? hi : x);
}

/* ---- the fade --------------------------------------------------------------- */

/* REQ-DTC-001: every corner: no band, the band's edges, zero, the extremes; the band's
   inside exact against i x 32767 / i_db truncated towards zero.
   Methods: 1c no band (i_db 0 and negative), the band's edges +-1000 and one inside, zero,
   -32768 and 32767 with the largest band; 1a the inside of the band exact against i x 32767
   / i_db truncated, computed in the test */
static void test_dtc_fade_corners(void **state)
{
    (void)state;
    assert_int_equal(qfoc_dtc_fade(0, 0), 0);
    assert_int_equal(qfoc_dtc_fade(1, 0), 32767);
    assert_int_equal(qfoc_dtc_fade(-1, 0), -32767);
    assert_int_equal(qfoc_dtc_fade(-32768, -5), -32767);
    assert_int_equal(qfoc_dtc_fade(32767, -32768), 32767);
    assert_int_equal(qfoc_dtc_fade(0, 1000), 0);
    assert_int_equal(qfoc_dtc_fade(1000, 1000), 32767);
    assert_int_equal(qfoc_dtc_fade(-1000, 1000), -32767);
    assert_int_equal(qfoc_dtc_fade(999, 1000), (999 * 32767) / 1000);
    assert_int_equal(qfoc_dtc_fade(-999, 1000), -((999 * 32767) / 1000));
    assert_int_equal(qfoc_dtc_fade(500, 1000), 16383);
    assert_int_equal(qfoc_dtc_fade(-32768, 32767), -32767);
    assert_int_equal(qfoc_dtc_fade(32766, 32767), 32766);
    assert_int_equal(qfoc_dtc_fade(1, 32767), 1);
}

/* REQ-DTC-001: 200000 random pairs against the double fade (exact to the truncation).
   Methods: 1b 200000 random currents and dead bands, every fourth band any int16 (negative
   included); 1n the double-precision fade, exact to the truncation */
static void test_dtc_fade_random(void **state)
{
    (void)state;
    for (int k = 0; k < 200000; k++) {
        const int16_t i = rand_i16();
        const int16_t db = (k % 4 == 0) ? rand_i16() : (int16_t)rand_range(0, 4000);
        const double want = ref_fade((double)i, (double)db) * 32767.0;
        const int got = qfoc_dtc_fade(i, db);
        assert_true(fabs((double)got - want) < 1.0);
        assert_true((got == 0) == (i == 0));
    }
}

/* ---- the learnt error ------------------------------------------------------- */

static int learn_s(int u_hi, int u_hi0, int u_lo, int u_lo0, int i_hi, int i_db, int v_max,
                   int r, int r_err)
{
    qfoc_dtc_align_t al;
    al.u_hi = (int16_t)u_hi;
    al.u_hi0 = (int16_t)u_hi0;
    al.u_lo = (int16_t)u_lo;
    al.u_lo0 = (int16_t)u_lo0;
    al.i_hi = (int16_t)i_hi;
    al.i_db = (int16_t)i_db;
    al.v_max = (int16_t)v_max;
    al.r = (int16_t)r;
    al.r_err = (int16_t)r_err;
    return qfoc_dtc_learn(&al);
}

/* settled holds: each voltage the same an eighth of ALIGN earlier */
static int learn(int u_hi, int u_lo, int i_hi, int i_db, int v_max, int r, int r_err)
{
    return learn_s(u_hi, u_hi, u_lo, u_lo, i_hi, i_db, v_max, r, r_err);
}

/* REQ-DTC-002: two settled alignments at i_hi and i_lo = i_hi / 2 of a motor whose
   resistance R' is within the table's allowance of R (30 % here) give back the inverter's
   error within 3 + 2 / |den| LSB (the rounded voltages and the quotient's truncation),
   clamped to the accepted bound; 0 where the dead band hides the error's shape; 0 when R'
   is off R by more than the allowance (by 40 % to 100 %, where the allowance and the
   quantisation are clearly exceeded).  200000 random alignments.
   Methods: 1b 200000 random alignments: currents of both signs, dead bands, resistances,
   inverter errors, two thirds with R' within the allowance and a third off by 40 .. 100 %;
   1d a motor resistance off the table's by more than the allowance (nothing learnt); 1n the
   inverter error of the model the alignments were computed from */
static void test_dtc_learn_model(void **state)
{
    (void)state;
    for (int k = 0; k < 200000; k++) {
        const int16_t i_hi = (int16_t)(2 * rand_range(-10000, 10000));
        const int16_t i_lo = (int16_t)(i_hi / 2);
        const int16_t db = (int16_t)rand_range(0, 3000);
        const double r = (double)rand_range(0, 12000);
        const bool wrong = (k % 3 == 0);
        const double e = wrong ? (double)rand_range(4000, 10000) / 10000.0 *
                                     ((k % 2 == 0) ? 1.0 : -1.0)
                               : (double)rand_range(-2900, 2900) / 10000.0;
        const double r_true = r * (1.0 + e);
        const int16_t v_max = (int16_t)rand_range(0, 3000);
        const double dv = (double)rand_range(-2500, 2500);
        const double sd_hi = ref_sd(i_hi, (double)db);
        const double sd_lo = ref_sd(i_lo, (double)db);
        const double den = sd_hi - 2.0 * sd_lo;
        const double u_hi = r_true * (double)i_hi / 32768.0 + dv * sd_hi;
        const double u_lo = r_true * (double)i_lo / 32768.0 + dv * sd_lo;
        const double ri_lo = fabs(r * (double)i_lo / 32768.0);
        double want;
        int got;
        if ((fabs(u_hi) > 32767.0) || (fabs(u_lo) > 32767.0)) {
            continue;
        }
        got = learn((int)lround(u_hi), (int)lround(u_lo), i_hi, db, v_max, (int)r, 9830);
        assert_true(abs(got) <= v_max);
        if (fabs(den) < 0.5 - 2.0 / 16384.0) {
            assert_int_equal(got, 0);
            continue;
        }
        if (fabs(den) < 0.5 + 2.0 / 16384.0) {
            continue;   /* the threshold itself: either answer is right */
        }
        if (wrong) {
            /* (|e| - 0.3) R i_lo beyond the allowance's quantisation (4 + 2 LSB) */
            if ((fabs(e) - 0.3) * ri_lo > 6.0 + 2.0 * fabs(sd_lo) / fabs(den) + 1.0) {
                assert_int_equal(got, 0);
            }
            continue;
        }
        if ((0.3 - fabs(e)) * ri_lo < 4.0 * fabs(sd_lo) / fabs(den) + 2.0 - 4.0) {
            continue;   /* at the allowance's edge within the quantisation */
        }
        want = clampd(dv, -(double)v_max, (double)v_max);
        assert_true(fabs((double)got - want) <= 3.0 + 2.0 / fabs(den));
    }
}

/* REQ-DTC-002: the corners: no bound accepted, alignments inside the dead band, either
   clamp of the difference and of the result, the resistance check and the settling check
   at their edges, the extremes of every argument.
   Methods: 1c v_max 0 and -32768, alignments inside the dead band, the clamps of the
   difference and of the result, the resistance allowance and the settling check one count
   inside and outside, the extremes of every argument crossed (7^5 combinations); 1d a drop
   far from R i_lo, unsettled alignments */
static void test_dtc_learn_corners(void **state)
{
    (void)state;
    /* v_max <= 0: no correction */
    assert_int_equal(learn(1400, 900, 10000, 100, 0, 3277, 9830), 0);
    assert_int_equal(learn(1400, 900, 10000, 100, -32768, 3277, 9830), 0);
    /* both alignments inside the band: the shape is linear, no measurement */
    assert_int_equal(learn(5000, 100, 100, 1000, 3000, 3277, 9830), 0);
    assert_int_equal(learn(5000, 0, 0, 0, 3000, 3277, 9830), 0);
    /* outside the band: den = -4/3, dV = -(u_hi - 2 u_lo) x 3 / 4; R i_lo = 500 */
    assert_int_equal(learn(1400, 900, 10000, 0, 3000, 3277, 9830), 300);
    assert_int_equal(learn(600, 100, 10000, 0, 3000, 3277, 9830), -300);
    /* a negative alignment current: the sign of the error kept */
    assert_int_equal(learn(-1400, -900, -10000, 0, 3000, 3277, 9830), 300);
    /* the result clamped to +-v_max (the drop it implies: 501, 499) */
    assert_int_equal(learn(6000, 5500, 10000, 0, 3000, 3277, 9830), 3000);
    assert_int_equal(learn(-4000, -4500, 10000, 0, 3000, 3277, 9830), -3000);
    /* the resistance check with dV = 300 (v s_lo / 32768 = 399): R i_lo = 500, allowance
       trunc(0.3 x 500) + 4 = 153: drops of 500 + 153 and 500 - 153 pass, one count beyond
       does not; r_err < 0 reads as 0 (allowance 4) */
    assert_int_equal(learn(1704, 1052, 10000, 0, 3000, 3277, 9830), 300);
    assert_int_equal(learn(1706, 1053, 10000, 0, 3000, 3277, 9830), 0);
    assert_int_equal(learn(1092, 746, 10000, 0, 3000, 3277, 9830), 300);
    assert_int_equal(learn(1090, 745, 10000, 0, 3000, 3277, 9830), 0);
    assert_int_equal(learn(1406, 903, 10000, 0, 3000, 3277, -5), 300);
    assert_int_equal(learn(1408, 904, 10000, 0, 3000, 3277, -5), 0);
    /* settled holds: with v_max = 3000 a change of 3000 / 4 + 4 = 754 counts over the last
       eighth passes, 755 does not, on either hold and in either direction; with v_max = 7
       the allowance is 5 */
    assert_int_equal(learn_s(1400, 646, 900, 1654, 10000, 0, 3000, 3277, 9830), 300);
    assert_int_equal(learn_s(1400, 2154, 900, 146, 10000, 0, 3000, 3277, 9830), 300);
    assert_int_equal(learn_s(1400, 645, 900, 900, 10000, 0, 3000, 3277, 9830), 0);
    assert_int_equal(learn_s(1400, 2155, 900, 900, 10000, 0, 3000, 3277, 9830), 0);
    assert_int_equal(learn_s(1400, 1400, 900, 145, 10000, 0, 3000, 3277, 9830), 0);
    assert_int_equal(learn_s(1400, 1400, 900, 1655, 10000, 0, 3000, 3277, 9830), 0);
    assert_int_equal(learn_s(1400, 1395, 900, 905, 10000, 0, 7, 3277, 9830), 7);
    assert_int_equal(learn_s(1400, 1394, 900, 900, 10000, 0, 7, 3277, 9830), 0);
    assert_int_equal(learn_s(-32768, 32767, 900, 900, 10000, 0, 3000, 3277, 9830), 0);
    assert_int_equal(learn_s(1400, 1400, 32767, -32768, 10000, 0, 3000, 3277, 9830), 0);
    /* the difference beyond +-65535 (its clamp), v beyond +-49151, the largest bound:
       a drop far from R i_lo: nothing learnt */
    assert_int_equal(learn(-32768, 32767, 32767, 0, 32767, 3277, 9830), 0);
    assert_int_equal(learn(32767, -32768, -32768, 0, 32767, 32767, 32767), 0);
    /* every extreme stays within the bound */
    {
        const int16_t ext[] = { -32768, -32767, -1, 0, 1, 32766, 32767 };
        for (size_t a = 0; a < 7u; a++) {
            for (size_t b = 0; b < 7u; b++) {
                for (size_t c = 0; c < 7u; c++) {
                    for (size_t e = 0; e < 7u; e++) {
                        for (size_t f = 0; f < 7u; f++) {
                            const int got = learn_s(ext[a], ext[(a + b) % 7u], ext[b],
                                                    ext[(b + c) % 7u], ext[c], ext[e], 32767,
                                                    ext[f], ext[(a + f) % 7u]);
                            assert_true(got >= -32767 && got <= 32767);
                        }
                    }
                }
            }
        }
    }
}

/* ---- the speed fade ---------------------------------------------------------- */

/* REQ-DTC-004: whole up to w_full, none from 2 w_full, linear between (truncated towards
   zero), for either sign of the speed and of the error; the corners of every argument;
   200000 random triples against the formula in double precision.
   Methods: 1b 200000 random triples, every fourth w_full any int16; 1c w = w_full, 2 w_full
   and one below, w_full 0 and negative, w = -32768, -32768 and 32767 for every argument; 1n
   the formula in double precision */
static void test_dtc_speed_fade(void **state)
{
    (void)state;
    assert_int_equal(qfoc_dtc_speed_fade(300, 0, 1000), 300);
    assert_int_equal(qfoc_dtc_speed_fade(300, 1000, 1000), 300);
    assert_int_equal(qfoc_dtc_speed_fade(300, -1000, 1000), 300);
    assert_int_equal(qfoc_dtc_speed_fade(300, 1500, 1000), 150);
    assert_int_equal(qfoc_dtc_speed_fade(-300, -1500, 1000), -150);
    assert_int_equal(qfoc_dtc_speed_fade(300, 1999, 1000), 0);
    assert_int_equal(qfoc_dtc_speed_fade(300, 2000, 1000), 0);
    assert_int_equal(qfoc_dtc_speed_fade(300, -32768, 1000), 0);
    assert_int_equal(qfoc_dtc_speed_fade(300, 0, 0), 300);
    assert_int_equal(qfoc_dtc_speed_fade(300, 1, 0), 0);
    assert_int_equal(qfoc_dtc_speed_fade(300, 0, -5), 300);
    assert_int_equal(qfoc_dtc_speed_fade(300, -1, -32768), 0);
    assert_int_equal(qfoc_dtc_speed_fade(-32768, -32768, 32767), -32766);
    assert_int_equal(qfoc_dtc_speed_fade(32767, 32767, 32767), 32767);
    for (int k = 0; k < 200000; k++) {
        const int16_t dv = rand_i16();
        const int16_t w = rand_i16();
        const int16_t wf = (k % 4 == 0) ? rand_i16() : (int16_t)rand_range(0, 20000);
        const double aw = fabs((double)w);
        const double f = ((wf > 0) ? (double)wf : 0.0);
        double want;
        const int got = qfoc_dtc_speed_fade(dv, w, wf);
        if (aw <= f) {
            want = (double)dv;
        } else if (aw >= 2.0 * f) {
            want = 0.0;
        } else {
            want = trunc((double)dv * (2.0 * f - aw) / f);
        }
        assert_true(fabs((double)got - want) < 1e-9);
    }
}

/* ---- the error vector ------------------------------------------------------- */

/* REQ-DTC-003: 200000 random currents, dead bands and errors against dV Clarke(f) in
   double precision (saturated to +-32767 as the header states).
   Methods: 1b 200000 random currents, dead bands (every eighth any int16) and errors (every
   16th any int16); 1n dV Clarke(f) in double precision, saturated to +-32767 */
static void test_dtc_error_random(void **state)
{
    (void)state;
    for (int k = 0; k < 200000; k++) {
        qfoc_abc_t i;
        qfoc_ab_t e;
        const int16_t db = (k % 8 == 0) ? rand_i16() : (int16_t)rand_range(0, 3000);
        const int16_t dv = (k % 16 == 0) ? rand_i16() : (int16_t)rand_range(-3000, 3000);
        double fu;
        double fv;
        double fw;
        double a;
        double b;
        i.u = rand_i16();
        i.v = rand_i16();
        i.w = rand_i16();
        qfoc_dtc_error(dv, &i, db, &e);
        fu = ref_fade((double)i.u, (double)db);
        fv = ref_fade((double)i.v, (double)db);
        fw = ref_fade((double)i.w, (double)db);
        a = clampd((double)dv * (2.0 * fu - fv - fw) / 3.0 * (32767.0 / 32768.0), -32767.0, 32767.0);
        b = clampd((double)dv * (fv - fw) / sqrt(3.0) * (32767.0 / 32768.0), -32767.0, 32767.0);
        /* the fades' and the factors' truncations (< 2.4 counts) scaled by |dv| / 32768,
           and the product's truncation */
        assert_true(fabs((double)e.alpha - a) <= 1.0 + 2.4 * fabs((double)dv) / 32768.0);
        assert_true(fabs((double)e.beta - b) <= 1.0 + 2.4 * fabs((double)dv) / 32768.0);
    }
}

/* REQ-DTC-003: the shape of a balanced current: for dV > 0 the error points along the
   current (its projection on the current vector is positive, its magnitude between
   2 / sqrt 3 dV and 4/3 dV, the hexagon of the six active vectors); dV = 0 gives 0;
   saturation.
   Methods: 1b 3600 angles of a balanced current; 1c dV = 0, dV and currents at -32768 and
   32767 (saturated); 1a the error along the current, its magnitude within the hexagon of the
   six active vectors */
static void test_dtc_error_shape(void **state)
{
    (void)state;
    for (int k = 0; k < 3600; k++) {
        const double th = (double)k * (2.0 * 3.14159265358979323846 / 3600.0);
        qfoc_abc_t i;
        qfoc_ab_t e;
        double dot;
        double mag;
        i.u = (int16_t)lround(20000.0 * cos(th));
        i.v = (int16_t)lround(20000.0 * cos(th - 2.0 * 3.14159265358979323846 / 3.0));
        i.w = (int16_t)lround(20000.0 * cos(th + 2.0 * 3.14159265358979323846 / 3.0));
        qfoc_dtc_error(1000, &i, 0, &e);
        dot = (double)e.alpha * cos(th) + (double)e.beta * sin(th);
        mag = hypot((double)e.alpha, (double)e.beta);
        assert_true(dot > 0.0);
        assert_true(mag >= 1000.0 * 2.0 / sqrt(3.0) - 3.0 && mag <= 1000.0 * 4.0 / 3.0 + 2.0);
        qfoc_dtc_error(0, &i, 0, &e);
        assert_int_equal(e.alpha, 0);
        assert_int_equal(e.beta, 0);
    }
    {
        qfoc_abc_t i = { 32767, -32768, -32768 };
        qfoc_ab_t e;
        qfoc_dtc_error(-32768, &i, 0, &e);
        assert_int_equal(e.alpha, -32767);
        assert_int_equal(e.beta, 0);
        qfoc_dtc_error(32767, &i, 0, &e);
        assert_int_equal(e.alpha, 32767);
        i.u = 0;
        i.v = 32767;
        i.w = -32768;
        qfoc_dtc_error(-32768, &i, -1, &e);
        assert_int_equal(e.beta, -32767);
        assert_int_equal(e.alpha, 0);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_dtc_fade_corners),
        cmocka_unit_test(test_dtc_fade_random),
        cmocka_unit_test(test_dtc_learn_model),
        cmocka_unit_test(test_dtc_learn_corners),
        cmocka_unit_test(test_dtc_speed_fade),
        cmocka_unit_test(test_dtc_error_random),
        cmocka_unit_test(test_dtc_error_shape),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
