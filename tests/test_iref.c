/*
 * test_iref.c -- unit tests of the current-reference generation (include/qfoc/iref.h).
 *
 * Reference: the equations in double precision (specs/equations.md section 9):
 *  - the q limit sqrt(m^2 - a^2), m = max(i_max, 0), a = min(|i_d|, m); the library's
 *    result is its floor: exact to the integer, checked on every corner and 200000
 *    random pairs;
 *  - MTPA i_d = psi_f / (2 dL) - sqrt(psi_f^2 / (4 dL^2) + i_q^2), dL = (L_q - L_d) / 4096
 *    (Q12 -> per unit), in the textbook form (not the rationalised form the library
 *    computes), with the reluctance flux dL |i_q| limited to 1 psi_base as the header
 *    states; error <= 3 LSB where x is not limited (the truncation of x, the floor of the
 *    root and the quotient's rounding);
 *  - MTPA optimality: the torque psi_f i_q - dL i_d i_q at the library's (i_d, i_q) is the
 *    largest over the current circle of the same magnitude (brute force in double);
 *  - derating: the linear interpolation, floor;
 *  - the step: id = clamp(mtpa + id_fw, -m, 0), iq_lim from it, and the circle.
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>
#include <math.h>
#include <stdlib.h>

#include "qfoc/iref.h"
#define TEST_SEED 3407u
#include "test_util.h"

#define TEST_PI 3.14159265358979323846

/* ---- double references ---------------------------------------------------- */

static double ref_q_limit(int i_max, int i_d)
{
    const double m = (i_max > 0) ? (double)i_max : 0.0;
    double a = fabs((double)i_d);
    if (a > m) {
        a = m;
    }
    return sqrt(m * m - a * a);
}

/* textbook MTPA in Q15 counts; x limited to 32767 counts as the header states */
static double ref_mtpa(int i_q, int psi_f, int ld, int lq)
{
    const double dl = (double)(lq - ld) / 4096.0;   /* per unit of L_base */
    double iq = fabs((double)i_q);
    const double pf = (psi_f > 0) ? (double)psi_f : 0.0;
    double x;
    if (iq > 32767.0) {
        iq = 32767.0;
    }
    if ((dl <= 0.0) || (iq == 0.0)) {
        return 0.0;
    }
    x = dl * iq;
    if (x > 32767.0) {
        /* the limited reluctance flux: the same formula with dL = 32767 / |i_q| */
        x = 32767.0;
    }
    {
        const double dle = x / iq;
        return pf / (2.0 * dle) - sqrt(pf * pf / (4.0 * dle * dle) + iq * iq);
    }
}

static double ref_derate(int hi, int lo, int t, int t0, int t1)
{
    const double low = (lo < hi) ? lo : hi;
    if (t <= t0) {
        return hi;
    }
    if (t >= t1) {
        return low;
    }
    return hi - floor((hi - low) * (double)(t - t0) / (double)(t1 - t0));
}

/* ---- q limit --------------------------------------------------------------- */

/* REQ-IREF-002: every corner of both arguments; the floor of the exact limit, inside the
   circle and less than 1 LSB below it.
   Methods: 1c every corner of both arguments (limit -32768, -1, 0, 1, 2, 100, 16384, 32766,
   32767, i_d -32768 .. 32767), |i_d| at the limit and beyond it, the exact 3-4-5 triangle;
   1n the double-precision floor of sqrt(limit^2 - i_d^2) */
static void test_iref_q_limit_corners(void **state)
{
    static const int lim[] = { -32768, -1, 0, 1, 2, 100, 16384, 32766, 32767 };
    static const int idv[] = { -32768, -32767, -16384, -2, -1, 0, 1, 2, 16384, 32767 };
    size_t i;
    size_t j;
    (void)state;
    for (i = 0u; i < sizeof lim / sizeof lim[0]; i++) {
        for (j = 0u; j < sizeof idv / sizeof idv[0]; j++) {
            const int r = qfoc_iref_q_limit((qfoc_q15_t)lim[i], (qfoc_q15_t)idv[j]);
            const double e = ref_q_limit(lim[i], idv[j]);
            const double m = (lim[i] > 0) ? lim[i] : 0;
            double a = fabs((double)idv[j]);
            if (a > m) {
                a = m;
            }
            assert_int_equal(r, (int)floor(e + 1e-9));
            /* inside the circle, and less than 1 LSB below it */
            assert_true(a * a + (double)r * r <= m * m);
            assert_true(a * a + ((double)r + 1.0) * ((double)r + 1.0) > m * m);
        }
    }
    /* d priority: no d current leaves the whole limit to q; |i_d| = i_max leaves none */
    assert_int_equal(qfoc_iref_q_limit(20000, 0), 20000);
    assert_int_equal(qfoc_iref_q_limit(20000, -20000), 0);
    assert_int_equal(qfoc_iref_q_limit(20000, -32768), 0);
    /* 3-4-5: exact */
    assert_int_equal(qfoc_iref_q_limit(25000, -15000), 20000);
}

/* REQ-IREF-002: 200000 random pairs against the double-precision limit.
   Methods: 1b 200000 random pairs over the whole int16 domain; 1n the double-precision limit */
static void test_iref_q_limit_random(void **state)
{
    int k;
    (void)state;
    for (k = 0; k < 200000; k++) {
        const int lim = rand_i16();
        const int id = rand_i16();
        const int r = qfoc_iref_q_limit((qfoc_q15_t)lim, (qfoc_q15_t)id);
        assert_int_equal(r, (int)floor(ref_q_limit(lim, id) + 1e-9));
    }
}

/* ---- MTPA ------------------------------------------------------------------ */

/* REQ-IREF-001: 200000 random inputs against the textbook formula in double precision.
   Methods: 1b 200000 random currents, magnet fluxes and inductances; 1n the textbook MTPA
   formula in double precision, within the bound of iref.h */
static void test_iref_mtpa_vs_formula(void **state)
{
    int k;
    int checked = 0;
    (void)state;
    for (k = 0; k < 200000; k++) {
        const int iq = rand_i16();
        const int pf = (int)(lcg_next() % 32768u);
        const int ld = (int)(lcg_next() % 16384u);
        const int lq = (int)(lcg_next() % 32768u);
        const int r = qfoc_iref_mtpa((qfoc_q15_t)iq, (qfoc_q15_t)pf, (int16_t)ld, (int16_t)lq);
        const double e = ref_mtpa(iq, pf, ld, lq);
        const double aiq = (iq == -32768) ? 32767.0 : fabs((double)iq);
        assert_true(r <= 0);
        assert_true((double)r >= -aiq);
        {
            /* iref.h: within 2 + 2 |i_d| / (psi_f + 2 x) LSB */
            double x = (double)(lq - ld) * aiq / 4096.0;
            if (x > 32767.0) {
                x = 32767.0;
            }
            if (x > 0.0) {
                assert_true(fabs((double)r - e) <= 2.0 + 2.0 * fabs(e) / ((double)pf + 2.0 * x));
                checked++;
            }
        }
    }
    assert_true(checked > 140000);
}

/* the reference motor's numbers (specs/motors/reference.toml): L_d = 2.6 mH, L_q = 4.2 mH,
   psi_f = 0.065 Wb, in the bases of its table (500 V, 40 A, 500 Hz); the library's i_d
   maximises the torque on the current circle (REQ-IREF-001)
   Methods: 1b the reference motor's currents 1000 .. 32000 in steps of 1000; 1n a
   brute-force search of the torque-maximising current angle on the same circle */
static void test_iref_mtpa_is_optimal(void **state)
{
    const double v_base = 500.0;
    const double i_base = 40.0;
    const double w_base = 2.0 * TEST_PI * 500.0;
    const double psi_base = v_base / w_base;
    const double l_base = psi_base / i_base;
    const int ld = (int)lround(2.6e-3 / l_base * 4096.0);
    const int lq = (int)lround(4.2e-3 / l_base * 4096.0);
    const int pf = (int)lround(0.065 / psi_base * 32768.0);
    const double dl = (double)(lq - ld) / 4096.0;
    int iq;
    (void)state;
    for (iq = 1000; iq <= 32000; iq += 1000) {
        const int id = qfoc_iref_mtpa((qfoc_q15_t)iq, (qfoc_q15_t)pf, (int16_t)ld, (int16_t)lq);
        const double mag = sqrt((double)id * id + (double)iq * iq);
        const double t_lib = (double)pf * iq - dl * id * iq;
        double t_best = 0.0;
        double g;
        /* brute force over the current angle at the same magnitude */
        for (g = 0.0; g < TEST_PI / 2.0; g += 1e-5) {
            const double d = -mag * sin(g);
            const double q = mag * cos(g);
            const double t = (double)pf * q - dl * d * q;
            if (t > t_best) {
                t_best = t;
            }
        }
        /* within the quantisation of a 3 LSB d current */
        assert_true(t_lib >= t_best * (1.0 - 1e-4));
        assert_true(id < 0);
    }
}

/* REQ-IREF-001: no saliency, inverse saliency, no current, no magnet, either sign, the
   extremes of the types.
   Methods: 1b no saliency, inverse saliency, no current, no magnet, either sign of i_q; 1c a
   reluctance flux below half a count, the extremes -32768 and 32767 of every argument */
static void test_iref_mtpa_corners(void **state)
{
    (void)state;
    /* no saliency, inverse saliency, no current: 0 */
    assert_int_equal(qfoc_iref_mtpa(20000, 5000, 3000, 3000), 0);
    assert_int_equal(qfoc_iref_mtpa(20000, 5000, 4000, 3000), 0);
    assert_int_equal(qfoc_iref_mtpa(0, 5000, 3000, 6000), 0);
    assert_int_equal(qfoc_iref_mtpa(-32768, 5000, -32768, 32767) <= 0, 1);
    /* no magnet and a reluctance flux below half a count: no MTPA current at this
       resolution (the divisor psi_f + root is 0) */
    assert_int_equal(qfoc_iref_mtpa(1, 0, 0, 1), 0);
    assert_int_equal(qfoc_iref_mtpa(-30, 0, 1000, 1034), 0);
    /* no magnet: 45 degrees, i_d = -|i_q| (synchronous reluctance) */
    assert_true(abs(qfoc_iref_mtpa(20000, 0, 2000, 6000) + 20000) <= 1);
    assert_true(abs(qfoc_iref_mtpa(-20000, -5, 2000, 6000) + 20000) <= 1);
    /* the sign of i_q does not matter */
    assert_int_equal(qfoc_iref_mtpa(12345, 8000, 2000, 5000),
                     qfoc_iref_mtpa(-12345, 8000, 2000, 5000));
    /* the extremes: bounded */
    assert_true(qfoc_iref_mtpa(-32768, 0, -32768, 32767) >= -32767);
    assert_true(qfoc_iref_mtpa(32767, 32767, -32768, 32767) >= -32767);
}

/* ---- derating -------------------------------------------------------------- */

/* REQ-IREF-003: the window, its ends, an empty window, lo above hi, random inputs.
   Methods: 1b 200000 random speeds, temperatures and windows; 1c the window's ends and one
   inside them, an empty window (a step), lo above hi, the whole range of the types (65535,
   0, -32768, 32767); 1n the derating written in the test from its definition */
static void test_iref_derate(void **state)
{
    int k;
    (void)state;
    /* 10000 rpm at 100 degC falling to 2000 rpm at 120 degC */
    assert_int_equal(qfoc_iref_derate(10000u, 2000u, 1000, 1000, 1200), 10000);
    assert_int_equal(qfoc_iref_derate(10000u, 2000u, 999, 1000, 1200), 10000);
    assert_int_equal(qfoc_iref_derate(10000u, 2000u, 1100, 1000, 1200), 6000);
    assert_int_equal(qfoc_iref_derate(10000u, 2000u, 1001, 1000, 1200), 9960);
    assert_int_equal(qfoc_iref_derate(10000u, 2000u, 1200, 1000, 1200), 2000);
    assert_int_equal(qfoc_iref_derate(10000u, 2000u, 2000, 1000, 1200), 2000);
    /* lo above hi reads as hi; an empty window is a step */
    assert_int_equal(qfoc_iref_derate(1000u, 5000u, 1100, 1000, 1200), 1000);
    assert_int_equal(qfoc_iref_derate(10000u, 2000u, 1000, 1000, 900), 10000);
    assert_int_equal(qfoc_iref_derate(10000u, 2000u, 1001, 1000, 900), 2000);
    /* the whole range of the types */
    assert_int_equal(qfoc_iref_derate(65535u, 0u, 0, -32768, 32767), 65535 - 32768);
    for (k = 0; k < 200000; k++) {
        const int hi = (int)(lcg_next() % 65536u);
        const int lo = (int)(lcg_next() % 65536u);
        const int t0 = rand_i16();
        const int t1 = rand_i16();
        const int t = rand_i16();
        const int r = qfoc_iref_derate((uint16_t)hi, (uint16_t)lo, (int16_t)t, (int16_t)t0,
                                       (int16_t)t1);
        assert_int_equal(r, (int)ref_derate(hi, lo, t, t0, t1));
    }
}

/* ---- the step -------------------------------------------------------------- */

/* REQ-IREF-004: the step against its definition on random inputs; the circle.
   Methods: 1b 200000 random inputs, MTPA on and off, field weakening of any sign; 1c field
   weakening beyond the circle (i_d at -i_max, no q current left); 1n the step recomposed
   from its definition (MTPA + field weakening clamped, the q limit) */
static void test_iref_step(void **state)
{
    int k;
    (void)state;
    for (k = 0; k < 200000; k++) {
        qfoc_iref_in_t in;
        qfoc_iref_out_t out;
        int m;
        double want_id;
        in.i_max = rand_i16();
        in.iq_dem = rand_i16();
        in.id_fw = (qfoc_q15_t)((k % 3 == 0) ? rand_i16() : -(int)(lcg_next() % 20000u));
        in.psi_f = rand_i16();
        in.ld = (int16_t)(lcg_next() % 16384u);
        in.lq = (int16_t)(lcg_next() % 32768u);
        in.mtpa = (k % 2) == 0;
        qfoc_iref_step(&in, &out);
        m = (in.i_max > 0) ? in.i_max : 0;
        want_id = (in.mtpa ? (double)qfoc_iref_mtpa(in.iq_dem, in.psi_f, in.ld, in.lq) : 0.0)
                  + (double)in.id_fw;
        if (want_id > 0.0) {
            want_id = 0.0;
        }
        if (want_id < -m) {
            want_id = -m;
        }
        assert_int_equal(out.id, (int)want_id);
        assert_int_equal(out.iq_lim, (int)floor(ref_q_limit(m, out.id) + 1e-9));
        assert_true((double)out.id * out.id + (double)out.iq_lim * out.iq_lim
                    <= (double)m * m);
    }
    {
        /* field weakening on top of MTPA, limited to the circle */
        qfoc_iref_in_t in = { 20000, 15000, -8000, 9000, 2000, 5000, true };
        qfoc_iref_out_t out;
        const int mt = qfoc_iref_mtpa(15000, 9000, 2000, 5000);
        qfoc_iref_step(&in, &out);
        assert_int_equal(out.id, mt - 8000);
        in.id_fw = -30000;
        qfoc_iref_step(&in, &out);
        assert_int_equal(out.id, -20000);
        assert_int_equal(out.iq_lim, 0);
        in.mtpa = false;
        in.id_fw = 0;
        qfoc_iref_step(&in, &out);
        assert_int_equal(out.id, 0);
        assert_int_equal(out.iq_lim, 20000);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_iref_q_limit_corners),
        cmocka_unit_test(test_iref_q_limit_random),
        cmocka_unit_test(test_iref_mtpa_vs_formula),
        cmocka_unit_test(test_iref_mtpa_is_optimal),
        cmocka_unit_test(test_iref_mtpa_corners),
        cmocka_unit_test(test_iref_derate),
        cmocka_unit_test(test_iref_step),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
