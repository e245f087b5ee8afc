/**
 * @file test_transforms.c
 * @brief Tests of the Clarke, Park, inverse Park and inverse Clarke transforms
 *        against independent double-precision references of the equations
 *        E2-3, E2-4, E2-7, E2-8 (specs/equations.md section 3) and the inverse transforms.
 *
 * Requirements: REQ-TRF-001 .. REQ-TRF-010 (specs/requirements/transforms.md).
 * Sine and cosine inputs are computed here as round(32767 sin x), independent of
 * the library's trigonometry.
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>
#include <math.h>
#include <stdlib.h>

#include "qfoc/transforms.h"
#include "../src/qfoc_fast.h"

/* error bounds stated in include/qfoc/transforms.h, in LSB */
#define CLARKE_BETA_BOUND   0.70  /* inside ClarkeDocBound */
#define PARK_BOUND          0.50  /* against the equations with the same Q15 sin/cos */
#define INV_CLARKE_BOUND    0.60
#define ROUND_TRIP_CLARKE   1     /* Clarke(InvClarke(x)) - x, beta, LSB */
#define ROUND_TRIP_PARK     4     /* InvPark(Park(x)) - x, LSB: 2 from the sin/cos gain
                                     (32767/32768)^2 at full scale, 1 from the two
                                     roundings, 1 from sin^2 + cos^2 != 1 after rounding */
#define PARK_IDEAL_BOUND    2.5   /* against the exact angle, incl. sin/cos quantisation
                                     and the 32767 scale of the test's sin/cos */

#define N_RANDOM 200000u
#define PI_D 3.14159265358979323846

static const int16_t corners[] = { -32768, -32767, -16384, -1, 0, 1, 16384, 32767 };
#define N_CORNERS (sizeof(corners) / sizeof(corners[0]))

/* ------------------------------------------------------------------ helpers */

static uint32_t lcg_state;

static void lcg_seed(uint32_t s)
{
    lcg_state = s;
}

static uint32_t lcg_next(void)
{
    lcg_state = (lcg_state * 1664525u) + 1013904223u;
    return lcg_state;
}

static int16_t rand_q15(void)
{
    return (int16_t)(uint16_t)(lcg_next() >> 16);
}

/* uniform double in [0, 1) */
static double rand_unit(void)
{
    return (double)(lcg_next() >> 8) / 16777216.0;
}

/* the documented reading of an input: -32768 is taken as -32767 */
static double sat_in(int16_t x)
{
    return (x == -32768) ? -32767.0 : (double)x;
}

static double clamp_out(double x)
{
    double r = x;
    if (r > 32767.0) {
        r = 32767.0;
    } else if (r < -32767.0) {
        r = -32767.0;
    } else {
        /* in range */
    }
    return r;
}

static qfoc_sincos_t sincos_of(double x)
{
    qfoc_sincos_t sc;
    sc.sine = (int16_t)lround(32767.0 * sin(x));
    sc.cosine = (int16_t)lround(32767.0 * cos(x));
    return sc;
}

static void assert_sym(int16_t x)
{
    assert_true(x != -32768);   /* [-32767, 32767] for an int16_t */
}

/* ------------------------------------------------------------------ Clarke */

static double clarke_max_err;

/* check one Clarke call against (2-3), (2-4) in double precision */
static void check_clarke(int16_t iu, int16_t iv)
{
    qfoc_ab_t out;
    double sum = (double)iu + (2.0 * (double)iv);
    double beta_ref = sum / sqrt(3.0);
    bool in_bound = (iu != -32768) && ((sum * sum) <= (3.0 * 32767.0 * 32767.0));

    qfoc_clarke(iu, iv, &out);
    assert_sym(out.alpha);
    assert_sym(out.beta);
    assert_int_equal(out.alpha, (iu == -32768) ? -32767 : iu);
    if (in_bound) {
        double e = fabs((double)out.beta - beta_ref);
        if (e > clarke_max_err) {
            clarke_max_err = e;
        }
        assert_true(e <= CLARKE_BETA_BOUND);
    } else if (beta_ref > 32767.0) {
        assert_int_equal(out.beta, 32767);
    } else if (beta_ref < -32767.0) {
        assert_int_equal(out.beta, -32767);
    } else {
        /* only alpha out of range (iu = -32768): beta still accurate */
        assert_true(fabs((double)out.beta - beta_ref) <= CLARKE_BETA_BOUND);
    }
}

/* REQ-TRF-001, REQ-TRF-002: every numerator i_u + 2 i_v, random pairs, corners
 * Methods: 1b every numerator i_u + 2 i_v in [-98304, 98302] (the domain of beta enumerated)
 * and 200000 random pairs; 1c eight corners (-32768, -32767, -16384, -1, 0, 1, 16384, 32767)
 * crossed, and |i_u + 2 i_v| = 56754 and 56755 either side of the saturation bound; 1n
 * equations (2-3), (2-4) in double precision */
static void test_req_trf_001_002_clarke(void **state)
{
    int32_t s;
    uint32_t i;
    size_t a;
    size_t b;
    (void)state;

    clarke_max_err = 0.0;
    /* exhaustive over the numerator i_u + 2 i_v in [-98304, 98302] */
    for (s = -98304; s <= 98302; s++) {
        int32_t iv = s / 2;
        int32_t iu;
        if (iv > 32767) {
            iv = 32767;
        } else if (iv < -32768) {
            iv = -32768;
        } else {
            /* in range */
        }
        iu = s - (2 * iv);
        check_clarke((int16_t)iu, (int16_t)iv);
    }
    lcg_seed(0x12345678u);
    for (i = 0u; i < N_RANDOM; i++) {
        check_clarke(rand_q15(), rand_q15());
    }
    for (a = 0u; a < N_CORNERS; a++) {
        for (b = 0u; b < N_CORNERS; b++) {
            check_clarke(corners[a], corners[b]);
        }
    }
    /* edges of the bound: |i_u + 2 i_v| = 56754 inside, 56755 outside */
    check_clarke(0, 28377);
    check_clarke(2, 28376);
    check_clarke(-2, -28376);
    check_clarke(1, 28377);
    check_clarke(-1, -28377);
    print_message("Clarke beta max |error| inside the bound: %.4f LSB (bound %.2f)\n",
                  clarke_max_err, CLARKE_BETA_BOUND);
}

/* REQ-TRF-001, REQ-TRF-002: saturation outside the bound, values spelled out
 * Methods: 1c the corners (32767, 32767), (-32768, -32768), (-32768, 16384) and the
 * numerators 56754 and 56755 either side of the saturation, results computed by hand */
static void test_req_trf_002_clarke_saturation(void **state)
{
    qfoc_ab_t out;
    (void)state;

    qfoc_clarke(32767, 32767, &out);      /* 98301 / sqrt(3) = 56754 -> 32767 */
    assert_int_equal(out.alpha, 32767);
    assert_int_equal(out.beta, 32767);
    qfoc_clarke(-32768, -32768, &out);    /* alpha and beta saturate */
    assert_int_equal(out.alpha, -32767);
    assert_int_equal(out.beta, -32767);
    qfoc_clarke(-32768, 16384, &out);     /* alpha saturates, beta = 0 exact */
    assert_int_equal(out.alpha, -32767);
    assert_int_equal(out.beta, 0);
    qfoc_clarke(1, 28377, &out);          /* 56755 / sqrt(3) = 32767.5 -> 32767 */
    assert_int_equal(out.beta, 32767);
    qfoc_clarke(0, 28377, &out);          /* 56754 / sqrt(3) = 32766.94 -> 32767 */
    assert_int_equal(out.beta, 32767);
}

/* REQ-TRF-009: a balanced three-phase set of amplitude A gives |(alpha, beta)| = A
 * Methods: 1b 3600 angles of a balanced three-phase set at four amplitudes; 1c the amplitude
 * 32767 (full scale); 1n A sin(x) and -A cos(x) in double precision */
static void test_req_trf_009_clarke_balanced(void **state)
{
    const double amps[] = { 1000.0, 16384.0, 30000.0, 32767.0 };
    double max_err = 0.0;
    size_t k;
    uint32_t n;
    (void)state;

    for (k = 0u; k < (sizeof(amps) / sizeof(amps[0])); k++) {
        for (n = 0u; n < 3600u; n++) {
            double x = (2.0 * PI_D * (double)n) / 3600.0;
            int16_t iu = (int16_t)lround(amps[k] * sin(x));
            int16_t iv = (int16_t)lround(amps[k] * sin(x - ((2.0 * PI_D) / 3.0)));
            qfoc_ab_t out;
            double e_a;
            double e_b;
            qfoc_clarke(iu, iv, &out);
            /* sin(x) + 2 sin(x - 120 deg) = -sqrt(3) cos(x): beta = -A cos(x) */
            e_a = fabs((double)out.alpha - (amps[k] * sin(x)));
            e_b = fabs((double)out.beta + (amps[k] * cos(x)));
            if (e_a > max_err) {
                max_err = e_a;
            }
            if (e_b > max_err) {
                max_err = e_b;
            }
            /* input rounding (0.5 LSB each, x sqrt(3) on beta) + 0.70 */
            assert_true(e_a <= 0.5);
            assert_true(e_b <= 1.6);
        }
    }
    print_message("Clarke balanced set max |error| vs A sin, -A cos: %.4f LSB\n", max_err);
}

/* ------------------------------------------------------------------ Park */

static double park_max_err;
static double park_max_err_ideal;

/* The input sweep shared by the Park and inverse Park tests: random vectors at
 * random exact angles (compared with the ideal rotation too), random raw
 * sine/cosine words that are not a unit pair (totality), and every combination
 * of the corner values for both inputs and both sin/cos words. */
typedef void (*rotation_check_t)(int16_t x1, int16_t x2, qfoc_sincos_t sc, double x, bool ideal);

static void sweep_rotation(rotation_check_t check, uint32_t seed)
{
    uint32_t i;
    size_t a;
    size_t b;
    size_t s;
    size_t c;

    lcg_seed(seed);
    for (i = 0u; i < N_RANDOM; i++) {
        double x = 2.0 * PI_D * rand_unit();
        check(rand_q15(), rand_q15(), sincos_of(x), x, true);
    }
    for (i = 0u; i < N_RANDOM; i++) {
        qfoc_sincos_t sc;
        sc.sine = rand_q15();
        sc.cosine = rand_q15();
        check(rand_q15(), rand_q15(), sc, 0.0, false);
    }
    for (a = 0u; a < N_CORNERS; a++) {
        for (b = 0u; b < N_CORNERS; b++) {
            for (s = 0u; s < N_CORNERS; s++) {
                for (c = 0u; c < N_CORNERS; c++) {
                    qfoc_sincos_t sc;
                    sc.sine = corners[s];
                    sc.cosine = corners[c];
                    check(corners[a], corners[b], sc, 0.0, false);
                }
            }
        }
    }
}

static void check_park(int16_t alpha, int16_t beta, qfoc_sincos_t sc, double x, bool ideal)
{
    qfoc_ab_t in;
    qfoc_dq_t out;
    double a = sat_in(alpha);
    double b = sat_in(beta);
    double s = sat_in(sc.sine);
    double c = sat_in(sc.cosine);
    double d_ref = ((a * c) + (b * s)) / 32768.0;   /* (2-7) */
    double q_ref = ((b * c) - (a * s)) / 32768.0;   /* (2-8) */
    double e_d;
    double e_q;

    in.alpha = alpha;
    in.beta = beta;
    qfoc_park(&in, &sc, &out);
    assert_sym(out.d);
    assert_sym(out.q);
    e_d = fabs((double)out.d - clamp_out(d_ref));
    e_q = fabs((double)out.q - clamp_out(q_ref));
    if (e_d > park_max_err) {
        park_max_err = e_d;
    }
    if (e_q > park_max_err) {
        park_max_err = e_q;
    }
    assert_true(e_d <= PARK_BOUND);
    assert_true(e_q <= PARK_BOUND);
    if (ideal) {
        /* against the exact angle: adds the sin/cos quantisation and 32767 scale */
        double di = (a * cos(x)) + (b * sin(x));
        double qi = (b * cos(x)) - (a * sin(x));
        double ei = fmax(fabs((double)out.d - clamp_out(di)), fabs((double)out.q - clamp_out(qi)));
        if (ei > park_max_err_ideal) {
            park_max_err_ideal = ei;
        }
        assert_true(ei <= PARK_IDEAL_BOUND);
    }
}

/* REQ-TRF-003, REQ-TRF-004, REQ-TRF-010: random vectors and angles, all corners
 * Methods: 1b 200000 random vectors at random exact angles and 200000 random sine and cosine
 * words that are not a unit pair; 1c every combination of eight corners (-32768 .. 32767)
 * for both inputs and both sine and cosine words; 1n equations (2-7), (2-8) in double
 * precision, with the same and with the exact sine and cosine */
static void test_req_trf_003_004_park(void **state)
{
    (void)state;

    park_max_err = 0.0;
    park_max_err_ideal = 0.0;
    sweep_rotation(check_park, 0xCAFEF00Du);
    print_message("Park max |error| vs (2-7),(2-8) with the same Q15 sin/cos: %.4f LSB (bound %.2f)\n",
                  park_max_err, PARK_BOUND);
    print_message("Park max |error| vs the exact angle (incl. sin/cos quantisation): %.4f LSB\n",
                  park_max_err_ideal);
}

/* REQ-TRF-004: inside the Park bound of specs/equations.md E2-9, E2-10 (|i| <= 32767, unit sin/cos) no saturation
 * Methods: 1b 200000 random vectors inside the full-scale circle at random angles; 1c the
 * full-scale vector along the rotor axis (d = 32766); 1n equations (2-7), (2-8) in double
 * precision */
static void test_req_trf_004_park_doc_bound(void **state)
{
    uint32_t i;
    (void)state;

    lcg_seed(0x0BADBEEFu);
    for (i = 0u; i < N_RANDOM; i++) {
        double r = 32767.0 * sqrt(rand_unit());
        double phi = 2.0 * PI_D * rand_unit();
        double x = 2.0 * PI_D * rand_unit();
        int16_t alpha = (int16_t)trunc(r * cos(phi));
        int16_t beta = (int16_t)trunc(r * sin(phi));
        qfoc_sincos_t sc = sincos_of(x);
        qfoc_ab_t in;
        qfoc_dq_t out;
        double d_ref = (((double)alpha * sc.cosine) + ((double)beta * sc.sine)) / 32768.0;
        double q_ref = (((double)beta * sc.cosine) - ((double)alpha * sc.sine)) / 32768.0;
        in.alpha = alpha;
        in.beta = beta;
        qfoc_park(&in, &sc, &out);
        assert_true(fabs(d_ref) < 32767.0);
        assert_true(fabs(q_ref) < 32767.0);
        assert_true(fabs((double)out.d - d_ref) <= PARK_BOUND);
        assert_true(fabs((double)out.q - q_ref) <= PARK_BOUND);
    }
    /* full-scale vector along the rotor axis: d = 32767 * 32767 / 32768 */
    {
        qfoc_ab_t in = { 32767, 0 };
        qfoc_sincos_t sc = { 0, 32767 };
        qfoc_dq_t out;
        qfoc_park(&in, &sc, &out);
        assert_int_equal(out.d, 32766);
        assert_int_equal(out.q, 0);
    }
}

/* REQ-TRF-003: saturation outside the bound
 * Methods: 1c full-scale vectors at 45 degrees, -32768 included, whose d or q exceeds 32767
 * sqrt(2) / sqrt(2): the saturation, results computed by hand */
static void test_req_trf_003_park_saturation(void **state)
{
    qfoc_ab_t in = { 32767, 32767 };
    qfoc_sincos_t sc = { 23170, 23170 };   /* 45 degrees */
    qfoc_dq_t out;
    (void)state;

    qfoc_park(&in, &sc, &out);             /* d = 32767 sqrt(2) */
    assert_int_equal(out.d, 32767);
    assert_int_equal(out.q, 0);
    in.alpha = -32768;
    in.beta = -32768;
    qfoc_park(&in, &sc, &out);
    assert_int_equal(out.d, -32767);
    assert_int_equal(out.q, 0);
    in.alpha = 32767;
    in.beta = -32767;
    qfoc_park(&in, &sc, &out);             /* q = -32767 sqrt(2) */
    assert_int_equal(out.d, 0);
    assert_int_equal(out.q, -32767);
}

/* ------------------------------------------------------------------ inverse Park */

static double inv_park_max_err;
static double inv_park_max_err_ideal;

static void check_inv_park(int16_t d, int16_t q, qfoc_sincos_t sc, double x, bool ideal)
{
    qfoc_dq_t in;
    qfoc_ab_t out;
    double dd = sat_in(d);
    double qq = sat_in(q);
    double s = sat_in(sc.sine);
    double c = sat_in(sc.cosine);
    double a_ref = ((dd * c) - (qq * s)) / 32768.0;
    double b_ref = ((dd * s) + (qq * c)) / 32768.0;
    double e_a;
    double e_b;

    in.d = d;
    in.q = q;
    qfoc_inv_park(&in, &sc, &out);
    assert_sym(out.alpha);
    assert_sym(out.beta);
    e_a = fabs((double)out.alpha - clamp_out(a_ref));
    e_b = fabs((double)out.beta - clamp_out(b_ref));
    if (e_a > inv_park_max_err) {
        inv_park_max_err = e_a;
    }
    if (e_b > inv_park_max_err) {
        inv_park_max_err = e_b;
    }
    assert_true(e_a <= PARK_BOUND);
    assert_true(e_b <= PARK_BOUND);
    if (ideal) {
        double ai = (dd * cos(x)) - (qq * sin(x));
        double bi = (dd * sin(x)) + (qq * cos(x));
        double ei = fmax(fabs((double)out.alpha - clamp_out(ai)), fabs((double)out.beta - clamp_out(bi)));
        if (ei > inv_park_max_err_ideal) {
            inv_park_max_err_ideal = ei;
        }
        assert_true(ei <= PARK_IDEAL_BOUND);
    }
}

/* The fast path's Park and inverse Park steps (src/qfoc_fast.h) against the equations
   in exact integer arithmetic: the sum of the two products of factors in
   [-32767, 32767], divided by 32768, rounded to nearest with ties away from zero,
   saturated to +-32767.  The reference is formed in double (every value is an integer
   below 2^32, exact), so the step must match it exactly; and the public function, which
   clamps and then calls the step, gives the same. */
static int16_t ref_round_sat(double q30)
{
    double r = floor((fabs(q30) / 32768.0) + 0.5);
    if (r > 32767.0) {
        r = 32767.0;
    } else {
        /* in range */
    }
    return (int16_t)((q30 < 0.0) ? -r : r);
}

static int16_t rand_sym(void)
{
    int16_t x = rand_q15();
    return (x == -32768) ? (int16_t)-32767 : x;
}

/* REQ-TRF-003, REQ-TRF-005, REQ-TRF-009: the steps without clamps, random and corners
 * Methods: 1b 200000 random symmetric inputs and sine and cosine words; 1c every combination
 * of eight corners (-32767, -32766, -16384, -1, 0, 1, 16384, 32767) for the four inputs; 1n
 * the rounded and saturated products in double precision, and the public functions against
 * the unclamped steps */
static void test_req_trf_003_005_sym_steps(void **state)
{
    static const int16_t sym_corners[] = { -32767, -32766, -16384, -1, 0, 1, 16384, 32767 };
    const uint32_t nc = (uint32_t)(sizeof(sym_corners) / sizeof(sym_corners[0]));
    uint32_t i;
    (void)state;

    lcg_seed(0x5EEDF00Du);
    for (i = 0u; i < (N_RANDOM + (nc * nc * nc * nc)); i++) {
        qfoc_ab_t ab;
        qfoc_dq_t dq;
        qfoc_sincos_t sc;
        qfoc_dq_t park;
        qfoc_dq_t park_pub;
        qfoc_ab_t inv;
        qfoc_ab_t inv_pub;
        double a;
        double b;
        double sn;
        double cs;
        if (i < N_RANDOM) {
            ab.alpha = rand_sym();
            ab.beta = rand_sym();
            sc.sine = rand_sym();
            sc.cosine = rand_sym();
        } else {
            uint32_t k = i - N_RANDOM;
            ab.alpha = sym_corners[k % nc];
            ab.beta = sym_corners[(k / nc) % nc];
            sc.sine = sym_corners[(k / (nc * nc)) % nc];
            sc.cosine = sym_corners[(k / (nc * nc * nc)) % nc];
        }
        dq.d = ab.alpha;
        dq.q = ab.beta;
        a = (double)ab.alpha;
        b = (double)ab.beta;
        sn = (double)sc.sine;
        cs = (double)sc.cosine;

        qfoc_park_sym(&ab, &sc, &park);
        assert_int_equal(park.d, ref_round_sat((a * cs) + (b * sn)));
        assert_int_equal(park.q, ref_round_sat((b * cs) - (a * sn)));
        qfoc_park(&ab, &sc, &park_pub);
        assert_int_equal(park.d, park_pub.d);
        assert_int_equal(park.q, park_pub.q);

        qfoc_inv_park_sym(&dq, &sc, &inv);
        assert_int_equal(inv.alpha, ref_round_sat((a * cs) - (b * sn)));
        assert_int_equal(inv.beta, ref_round_sat((a * sn) + (b * cs)));
        qfoc_inv_park(&dq, &sc, &inv_pub);
        assert_int_equal(inv.alpha, inv_pub.alpha);
        assert_int_equal(inv.beta, inv_pub.beta);
    }
}

/* REQ-TRF-005, REQ-TRF-006, REQ-TRF-010
 * Methods: 1b 200000 random vectors at random angles, 200000 random non-unit sine and cosine
 * pairs, 3600 angles of a voltage with harmonics (E2-39); 1c every combination of the eight
 * corners for both inputs and both sine and cosine words; 1n the inverse Park equations in
 * double precision */
static void test_req_trf_005_006_inv_park(void **state)
{
    uint32_t i;
    (void)state;

    inv_park_max_err = 0.0;
    inv_park_max_err_ideal = 0.0;
    sweep_rotation(check_inv_park, 0x5EED1234u);
    /* harmonics on U_d, U_q as in specs/equations.md E2-39: M + A_d sin(wt + phi_d), ... */
    for (i = 0u; i < 3600u; i++) {
        double x = (2.0 * PI_D * (double)i) / 3600.0;
        int16_t d = (int16_t)lround(12000.0 + (3000.0 * sin(x + 0.3)));
        int16_t q = (int16_t)lround(-15000.0 + (4000.0 * sin(x - 1.1)));
        check_inv_park(d, q, sincos_of(x), x, true);
    }
    print_message("Inverse Park max |error| vs equations with the same Q15 sin/cos: %.4f LSB (bound %.2f)\n",
                  inv_park_max_err, PARK_BOUND);
    print_message("Inverse Park max |error| vs the exact angle: %.4f LSB\n", inv_park_max_err_ideal);
}

/* REQ-TRF-005: saturation outside the bound
 * Methods: 1c full-scale (d, q) at 45 degrees, -32768 included, whose alpha or beta exceed
 * full scale: the saturation, results computed by hand */
static void test_req_trf_005_inv_park_saturation(void **state)
{
    qfoc_dq_t in = { 32767, -32767 };
    qfoc_sincos_t sc = { 23170, 23170 };
    qfoc_ab_t out;
    (void)state;

    qfoc_inv_park(&in, &sc, &out);         /* alpha = 32767 sqrt(2) */
    assert_int_equal(out.alpha, 32767);
    assert_int_equal(out.beta, 0);
    in.d = -32768;
    in.q = -32768;
    qfoc_inv_park(&in, &sc, &out);         /* beta = -32767 sqrt(2) */
    assert_int_equal(out.alpha, 0);
    assert_int_equal(out.beta, -32767);
}

/* ------------------------------------------------------------------ inverse Clarke */

static double inv_clarke_max_err;

static void check_inv_clarke(int16_t alpha, int16_t beta)
{
    qfoc_ab_t in;
    qfoc_abc_t out;
    double a = sat_in(alpha);
    double b = sat_in(beta);
    double v_ref = (-a + (sqrt(3.0) * b)) / 2.0;
    double w_ref = (-a - (sqrt(3.0) * b)) / 2.0;
    double e_v;
    double e_w;

    in.alpha = alpha;
    in.beta = beta;
    qfoc_inv_clarke(&in, &out);
    assert_sym(out.u);
    assert_sym(out.v);
    assert_sym(out.w);
    assert_int_equal(out.u, (int16_t)a);
    e_v = fabs((double)out.v - clamp_out(v_ref));
    e_w = fabs((double)out.w - clamp_out(w_ref));
    if (e_v > inv_clarke_max_err) {
        inv_clarke_max_err = e_v;
    }
    if (e_w > inv_clarke_max_err) {
        inv_clarke_max_err = e_w;
    }
    assert_true(e_v <= INV_CLARKE_BOUND);
    assert_true(e_w <= INV_CLARKE_BOUND);
}

/* REQ-TRF-007, REQ-TRF-008
 * Methods: 1b 200000 random pairs; 1c eight corners (-32768 .. 32767) crossed; 1n the
 * inverse Clarke equations in double precision */
static void test_req_trf_007_008_inv_clarke(void **state)
{
    uint32_t i;
    size_t a;
    size_t b;
    (void)state;

    inv_clarke_max_err = 0.0;
    lcg_seed(0xA5A5A5A5u);
    for (i = 0u; i < N_RANDOM; i++) {
        check_inv_clarke(rand_q15(), rand_q15());
    }
    for (a = 0u; a < N_CORNERS; a++) {
        for (b = 0u; b < N_CORNERS; b++) {
            check_inv_clarke(corners[a], corners[b]);
        }
    }
    print_message("Inverse Clarke max |error| vs double: %.4f LSB (bound %.2f)\n",
                  inv_clarke_max_err, INV_CLARKE_BOUND);
}

/* REQ-TRF-008: saturation outside the full-scale circle; none inside
 * Methods: 1b 200000 random vectors inside the full-scale circle (no saturation); 1c the
 * corners (-32767, 32767), (32767, 32767), (-32768, -32768) outside the circle, results
 * computed by hand */
static void test_req_trf_008_inv_clarke_saturation(void **state)
{
    qfoc_ab_t in = { -32767, 32767 };
    qfoc_abc_t out;
    uint32_t i;
    (void)state;

    qfoc_inv_clarke(&in, &out);            /* v = (32767 + 56753) / 2 = 44760 */
    assert_int_equal(out.u, -32767);
    assert_int_equal(out.v, 32767);
    /* real (32767 - 56754.1) / 2 = -11993.55; Q30 32767 (16384 - 28378) / 32768
       = -11993.63 -> -11994 */
    assert_int_equal(out.w, -11994);
    in.alpha = 32767;
    in.beta = 32767;
    qfoc_inv_clarke(&in, &out);            /* w = -44760 */
    assert_int_equal(out.w, -32767);
    in.alpha = -32768;
    in.beta = -32768;
    qfoc_inv_clarke(&in, &out);
    assert_int_equal(out.u, -32767);
    assert_int_equal(out.v, -11994);
    assert_int_equal(out.w, 32767);
    /* inside the circle: no output saturates before its real value does */
    lcg_seed(0x13579BDFu);
    for (i = 0u; i < N_RANDOM; i++) {
        double r = 32767.0 * sqrt(rand_unit());
        double phi = 2.0 * PI_D * rand_unit();
        in.alpha = (int16_t)trunc(r * cos(phi));
        in.beta = (int16_t)trunc(r * sin(phi));
        check_inv_clarke(in.alpha, in.beta);
    }
}

/* REQ-TRF-009: a rotating vector of amplitude A gives a balanced three-phase set
 * Methods: 1b 3600 angles of a rotating vector at three amplitudes; 1c the amplitude 32767
 * (full scale); 1n A cos(x - k 120 degrees) in double precision */
static void test_req_trf_009_inv_clarke_balanced(void **state)
{
    const double amps[] = { 1000.0, 16384.0, 32767.0 };
    double max_err = 0.0;
    size_t k;
    uint32_t n;
    (void)state;

    for (k = 0u; k < (sizeof(amps) / sizeof(amps[0])); k++) {
        for (n = 0u; n < 3600u; n++) {
            double x = (2.0 * PI_D * (double)n) / 3600.0;
            qfoc_ab_t in;
            qfoc_abc_t out;
            double e;
            in.alpha = (int16_t)lround(amps[k] * cos(x));
            in.beta = (int16_t)lround(amps[k] * sin(x));
            qfoc_inv_clarke(&in, &out);
            e = fmax(fabs((double)out.u - (amps[k] * cos(x))),
                     fmax(fabs((double)out.v - (amps[k] * cos(x - ((2.0 * PI_D) / 3.0)))),
                          fabs((double)out.w - (amps[k] * cos(x + ((2.0 * PI_D) / 3.0))))));
            if (e > max_err) {
                max_err = e;
            }
            assert_true(e <= 1.2);   /* 0.5 input rounding + 0.6 */
            assert_true(abs((int32_t)out.u + (int32_t)out.v + (int32_t)out.w) <= 2);
        }
    }
    print_message("Inverse Clarke balanced set max |error| vs A cos(x - k 120 deg): %.4f LSB\n", max_err);
}

/* ------------------------------------------------------------------ round trips */

/* REQ-TRF-010: Clarke(InvClarke(x)) ~ x inside the full-scale circle
 * Methods: 1b 200000 random vectors inside the full-scale circle, through the inverse and
 * the forward transform */
static void test_req_trf_010_round_trip_clarke(void **state)
{
    uint32_t i;
    int32_t max_err = 0;
    (void)state;

    lcg_seed(0x2468ACE0u);
    for (i = 0u; i < N_RANDOM; i++) {
        double r = 32767.0 * sqrt(rand_unit());
        double phi = 2.0 * PI_D * rand_unit();
        qfoc_ab_t x;
        qfoc_abc_t p;
        qfoc_ab_t y;
        int32_t e;
        x.alpha = (int16_t)trunc(r * cos(phi));
        x.beta = (int16_t)trunc(r * sin(phi));
        qfoc_inv_clarke(&x, &p);
        qfoc_clarke(p.u, p.v, &y);
        assert_int_equal(y.alpha, x.alpha);
        e = abs((int32_t)y.beta - (int32_t)x.beta);
        if (e > max_err) {
            max_err = e;
        }
        assert_true(e <= ROUND_TRIP_CLARKE);
    }
    print_message("Clarke(InvClarke(x)) max |error|: %d LSB (tolerance %d)\n",
                  (int)max_err, ROUND_TRIP_CLARKE);
}

/* REQ-TRF-010: InvPark(Park(x)) ~ x inside the full-scale circle
 * Methods: 1b 200000 random vectors inside the full-scale circle at random angles, through
 * Park and inverse Park */
static void test_req_trf_010_round_trip_park(void **state)
{
    uint32_t i;
    int32_t max_err = 0;
    (void)state;

    lcg_seed(0x10203040u);
    for (i = 0u; i < N_RANDOM; i++) {
        double r = 32767.0 * sqrt(rand_unit());
        double phi = 2.0 * PI_D * rand_unit();
        qfoc_sincos_t sc = sincos_of(2.0 * PI_D * rand_unit());
        qfoc_ab_t x;
        qfoc_dq_t p;
        qfoc_ab_t y;
        int32_t e;
        x.alpha = (int16_t)trunc(r * cos(phi));
        x.beta = (int16_t)trunc(r * sin(phi));
        qfoc_park(&x, &sc, &p);
        qfoc_inv_park(&p, &sc, &y);
        e = abs((int32_t)y.alpha - (int32_t)x.alpha);
        if (abs((int32_t)y.beta - (int32_t)x.beta) > e) {
            e = abs((int32_t)y.beta - (int32_t)x.beta);
        }
        if (e > max_err) {
            max_err = e;
        }
        assert_true(e <= ROUND_TRIP_PARK);
    }
    print_message("InvPark(Park(x)) max |error|: %d LSB (tolerance %d)\n",
                  (int)max_err, ROUND_TRIP_PARK);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_req_trf_001_002_clarke),
        cmocka_unit_test(test_req_trf_002_clarke_saturation),
        cmocka_unit_test(test_req_trf_009_clarke_balanced),
        cmocka_unit_test(test_req_trf_003_004_park),
        cmocka_unit_test(test_req_trf_004_park_doc_bound),
        cmocka_unit_test(test_req_trf_003_park_saturation),
        cmocka_unit_test(test_req_trf_005_006_inv_park),
        cmocka_unit_test(test_req_trf_005_inv_park_saturation),
        cmocka_unit_test(test_req_trf_003_005_sym_steps),
        cmocka_unit_test(test_req_trf_007_008_inv_clarke),
        cmocka_unit_test(test_req_trf_008_inv_clarke_saturation),
        cmocka_unit_test(test_req_trf_009_inv_clarke_balanced),
        cmocka_unit_test(test_req_trf_010_round_trip_clarke),
        cmocka_unit_test(test_req_trf_010_round_trip_park),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
