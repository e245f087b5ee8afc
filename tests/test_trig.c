/**
 * @file test_trig.c
 * @brief Unit tests of qfoc_sin, qfoc_sincos, qfoc_atan2 and the trig tables.
 *
 * Every check compares with an independent double-precision reference from
 * math.h (32767 sin(2 pi theta / 65536), atan2(y, x) 32768 / pi) using the
 * error bounds stated in include/qfoc/trig.h, over all 65536 angles, a dense
 * grid of vectors, the corners and pseudo-random inputs (fixed-seed LCG).
 * Requirements: REQ-TRIG-001 .. REQ-TRIG-005 (specs/requirements/trig.md).
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>
#include <math.h>
#include <stdio.h>

#include "qfoc/trig.h"

#define PI 3.14159265358979323846

/* Header bounds (include/qfoc/trig.h). */
#define SIN_MAX_ERR_LSB   (1.0)   /* REQ-TRIG-001 allows 2, header states 1 */
#define ATAN_MAX_ERR_CNT  (1.0)   /* REQ-TRIG-003 allows 9 (0.05 deg), header states 1 */
#define COUNTS_PER_DEG    (65536.0 / 360.0)

static uint32_t lcg_state = 12345u;

static uint32_t lcg_next(void)
{
    /* Numerical Recipes LCG constants */
    lcg_state = (lcg_state * 1664525u) + 1013904223u;
    return lcg_state;
}

static int16_t lcg_int16(void)
{
    return (int16_t)(uint16_t)(lcg_next() >> 16);   /* full int16 range */
}

static double sin_ref(uint32_t theta)
{
    return 32767.0 * sin(2.0 * PI * (double)theta / 65536.0);
}

static double angle_ref(int32_t y, int32_t x)
{
    double a = atan2((double)y, (double)x) * 32768.0 / PI;   /* counts, (-32768, 32768] */
    return a;
}

/* Circular distance between a result angle and a reference in counts. */
static double angle_err(qfoc_angle_t a, double ref)
{
    double e = fmod((double)a - ref, 65536.0);
    if (e < 0.0) {
        e += 65536.0;
    }
    if (e > 32768.0) {
        e -= 65536.0;
    }
    return fabs(e);
}

/* REQ-TRIG-001: sine over all 65536 angles, range and <= 1 LSB error.
 * Methods: 1b every one of the 65536 angles (the domain enumerated); 1c the result never
 * -32768 (the symmetric range); 1n math.h sin() in double precision, error <= 1 LSB */
static void test_req_trig_001_sin_exhaustive(void **state)
{
    double max_err = 0.0;
    uint32_t worst = 0u;
    uint32_t t;
    (void)state;
    for (t = 0u; t < 65536u; t++) {
        qfoc_q15_t s = qfoc_sin((qfoc_angle_t)t);
        double e = fabs((double)s - sin_ref(t));
        assert_true(s != -32768);   /* symmetric range [-32767, 32767] */
        if (e > max_err) {
            max_err = e;
            worst = t;
        }
    }
    print_message("REQ-TRIG-001 sin: max error %.4f LSB at theta = %u (bound %.1f)\n",
                  max_err, (unsigned)worst, SIN_MAX_ERR_LSB);
    assert_true(max_err <= SIN_MAX_ERR_LSB);
}

/* REQ-TRIG-001: exact values on the axes and the 45-degree points.
 * Methods: 1c the axes (0, 90, 180, 270 degrees), the 45-degree points and one count either
 * side of 0; 1a the exact values 32767 sin(theta) rounded, computed by hand */
static void test_req_trig_001_sin_corners(void **state)
{
    (void)state;
    assert_int_equal(qfoc_sin(0u), 0);
    assert_int_equal(qfoc_sin(0x4000u), 32767);
    assert_int_equal(qfoc_sin(0x8000u), 0);
    assert_int_equal(qfoc_sin(0xC000u), -32767);
    /* 32767 / sqrt(2) = 23169.77 -> 23170 */
    assert_int_equal(qfoc_sin(0x2000u), 23170);
    assert_int_equal(qfoc_sin(0x6000u), 23170);
    assert_int_equal(qfoc_sin(0xA000u), -23170);
    assert_int_equal(qfoc_sin(0xE000u), -23170);
    /* one count: 32767 * sin(2 pi / 65536) = 3.14 -> 3 */
    assert_int_equal(qfoc_sin(1u), 3);
    assert_int_equal(qfoc_sin(0xFFFFu), -3);
}

/* REQ-TRIG-001: odd symmetry sin(theta + 180 deg) == -sin(theta), and
 * sin(180 deg - theta) == sin(theta), for all angles.
 * Methods: 1b every angle, checked for the odd and mirror symmetries of the sine */
static void test_req_trig_001_sin_symmetry(void **state)
{
    uint32_t t;
    (void)state;
    for (t = 0u; t < 65536u; t++) {
        int32_t s = (int32_t)qfoc_sin((qfoc_angle_t)t);
        int32_t s_half = (int32_t)qfoc_sin((qfoc_angle_t)((t + 0x8000u) & 0xFFFFu));
        int32_t s_mirror = (int32_t)qfoc_sin((qfoc_angle_t)((0x8000u - t) & 0xFFFFu));
        assert_int_equal(s_half, -s);
        assert_int_equal(s_mirror, s);
    }
}

/* REQ-TRIG-002: sincos over all angles against sin / cos in double.
 * Methods: 1b every one of the 65536 angles; 1c neither output ever -32768, the norm within
 * 1.5 LSB of 32767; 1n math.h sin() and cos() in double precision */
static void test_req_trig_002_sincos_exhaustive(void **state)
{
    double max_s = 0.0;
    double max_c = 0.0;
    double max_norm = 0.0;
    uint32_t t;
    (void)state;
    for (t = 0u; t < 65536u; t++) {
        qfoc_sincos_t sc;
        double ph = 2.0 * PI * (double)t / 65536.0;
        double es;
        double ec;
        double en;
        qfoc_sincos((qfoc_angle_t)t, &sc);
        es = fabs((double)sc.sine - 32767.0 * sin(ph));
        ec = fabs((double)sc.cosine - 32767.0 * cos(ph));
        en = fabs(sqrt(((double)sc.sine * sc.sine) + ((double)sc.cosine * sc.cosine)) - 32767.0);
        assert_true(sc.cosine != -32768);   /* symmetric range */
        assert_true(sc.sine != -32768);
        max_s = (es > max_s) ? es : max_s;
        max_c = (ec > max_c) ? ec : max_c;
        max_norm = (en > max_norm) ? en : max_norm;
    }
    print_message("REQ-TRIG-002 sincos: max error sine %.4f LSB, cosine %.4f LSB, "
                  "| |(cos, sin)| - 32767 | %.4f LSB\n", max_s, max_c, max_norm);
    assert_true(max_s <= SIN_MAX_ERR_LSB);
    assert_true(max_c <= SIN_MAX_ERR_LSB);
    assert_true(max_norm <= 1.5);
}

/* REQ-TRIG-001, REQ-TRIG-002: on every table node (theta = 16384 q + 64 i) the
 * result is the node's entry halved with rounding, (t + 1) / 2, with the
 * quadrant's mirror (node 256 - i in quadrants 2 and 4, the 90-degree node 256
 * included) and sign (negative in quadrants 3 and 4), for the sine and for the
 * cosine 90 degrees ahead.
 * Methods: 1b every table node of each of the four quadrants, with the quadrant's mirror and
 * sign; 1c the node 256 (90 degrees) at the quadrant boundaries */
static void test_req_trig_001_sincos_nodes(void **state)
{
    uint32_t q;
    uint32_t i;
    (void)state;
    for (q = 0u; q < 4u; q++) {
        for (i = 0u; i < 256u; i++) {
            uint32_t t = (q * 16384u) + (i * 64u);
            uint32_t qc = (q + 1u) % 4u;              /* quadrant of theta + 90 deg */
            uint32_t ns = ((q % 2u) != 0u) ? (256u - i) : i;
            uint32_t nc = ((qc % 2u) != 0u) ? (256u - i) : i;
            int32_t s = ((int32_t)qfoc_trig_sin_tab[ns] + 1) / 2;
            int32_t c = ((int32_t)qfoc_trig_sin_tab[nc] + 1) / 2;
            qfoc_sincos_t sc;
            if (q >= 2u) {
                s = -s;
            }
            if (qc >= 2u) {
                c = -c;
            }
            qfoc_sincos((qfoc_angle_t)t, &sc);
            assert_int_equal(qfoc_sin((qfoc_angle_t)t), s);
            assert_int_equal(sc.sine, s);
            assert_int_equal(sc.cosine, c);
        }
    }
}

/* REQ-TRIG-002: the pair is (qfoc_sin(theta), qfoc_sin(theta + 0x4000)) for
 * every angle, the sum taken modulo 2^16 (the definition in trig.h).
 * Methods: 1b every angle, the cosine taken 0x4000 ahead modulo 2^16 */
static void test_req_trig_002_sincos_is_sin_pair(void **state)
{
    uint32_t t;
    (void)state;
    for (t = 0u; t < 65536u; t++) {
        qfoc_sincos_t sc;
        qfoc_sincos((qfoc_angle_t)t, &sc);
        assert_int_equal(sc.sine, qfoc_sin((qfoc_angle_t)t));
        assert_int_equal(sc.cosine, qfoc_sin((qfoc_angle_t)((t + 0x4000u) & 0xFFFFu)));
    }
}

/* REQ-TRIG-002: cosine wraps modulo 2^16 (theta + 0x4000 past 0xFFFF).
 * Methods: 1c the angles 0xC000, 0xFFFF and 0 where theta + 90 degrees wraps past 0xFFFF */
static void test_req_trig_002_sincos_wrap(void **state)
{
    qfoc_sincos_t sc;
    (void)state;
    qfoc_sincos(0xC000u, &sc);           /* 270 deg: (-1, 0) */
    assert_int_equal(sc.sine, -32767);
    assert_int_equal(sc.cosine, 0);
    qfoc_sincos(0xFFFFu, &sc);           /* -1 count: cos(theta + 90) = sin(0x3FFF) */
    assert_int_equal(sc.cosine, 32767);
    assert_int_equal(sc.sine, -3);
    qfoc_sincos(0x0000u, &sc);
    assert_int_equal(sc.sine, 0);
    assert_int_equal(sc.cosine, 32767);
}

static void atan_check(int32_t y, int32_t x, double *max_err, int32_t *wy, int32_t *wx)
{
    qfoc_angle_t a = qfoc_atan2((qfoc_q15_t)y, (qfoc_q15_t)x);
    double e;
    if ((x == 0) && (y == 0)) {
        e = (double)a;                  /* defined as 0 */
    } else {
        e = angle_err(a, angle_ref(y, x));
    }
    if (e > *max_err) {
        *max_err = e;
        *wy = y;
        *wx = x;
    }
}

/* REQ-TRIG-003: dense grid (multiples of 61 from -32768) plus the corners.
 * Methods: 1b a dense grid of (y, x) over the whole plane, every 61st value from -32768 in
 * each quadrant; 1c eight corners (-32768, -32767, -16384, -1, 0, 1, 16384, 32767) crossed
 * with each other and with every int16 value on either axis; 1n math.h atan2() in double
 * precision, error <= 1 count */
static void test_req_trig_003_atan2_grid(void **state)
{
    static const int32_t corners[] = { -32768, -32767, -16384, -1, 0, 1, 16384, 32767 };
    double max_err = 0.0;
    int32_t wy = 0;
    int32_t wx = 0;
    int32_t y;
    int32_t x;
    size_t i;
    size_t j;
    (void)state;
    for (y = -32768; y <= 32767; y += 61) {
        for (x = -32768; x <= 32767; x += 61) {
            atan_check(y, x, &max_err, &wy, &wx);
        }
    }
    for (i = 0u; i < (sizeof(corners) / sizeof(corners[0])); i++) {
        for (j = 0u; j < (sizeof(corners) / sizeof(corners[0])); j++) {
            atan_check(corners[i], corners[j], &max_err, &wy, &wx);
        }
        for (x = -32768; x <= 32767; x++) {
            atan_check(corners[i], x, &max_err, &wy, &wx);
            atan_check(x, corners[i], &max_err, &wy, &wx);
        }
    }
    print_message("REQ-TRIG-003 atan2 grid: max error %.4f counts = %.5f deg at (x, y) = (%d, %d)\n",
                  max_err, max_err / COUNTS_PER_DEG, (int)wx, (int)wy);
    assert_true(max_err <= ATAN_MAX_ERR_CNT);
}

/* REQ-TRIG-003 / REQ-TRIG-004: small vectors |v| < 50, where the ratio of
 * small integers matters, exhaustively; and random full-range vectors.
 * Methods: 1b every vector of norm below 50 (the ratios of small integers) and 1000000
 * random full-range vectors; 1n math.h atan2() in double precision */
static void test_req_trig_003_atan2_small_and_random(void **state)
{
    double max_small = 0.0;
    double max_rand = 0.0;
    int32_t wy = 0;
    int32_t wx = 0;
    int32_t y;
    int32_t x;
    uint32_t k;
    (void)state;
    for (y = -49; y <= 49; y++) {
        for (x = -49; x <= 49; x++) {
            if (((x * x) + (y * y)) < 2500) {
                atan_check(y, x, &max_small, &wy, &wx);
            }
        }
    }
    print_message("REQ-TRIG-003 atan2 |v| < 50: max error %.4f counts = %.5f deg at (x, y) = (%d, %d)\n",
                  max_small, max_small / COUNTS_PER_DEG, (int)wx, (int)wy);
    lcg_state = 20240601u;
    for (k = 0u; k < 1000000u; k++) {
        atan_check((int32_t)lcg_int16(), (int32_t)lcg_int16(), &max_rand, &wy, &wx);
    }
    print_message("REQ-TRIG-003 atan2 random: max error %.4f counts = %.5f deg at (x, y) = (%d, %d)\n",
                  max_rand, max_rand / COUNTS_PER_DEG, (int)wx, (int)wy);
    assert_true(max_small <= ATAN_MAX_ERR_CNT);
    assert_true(max_rand <= ATAN_MAX_ERR_CNT);
}

/* REQ-TRIG-003: all diagonals |x| == |y| (exact 45 + k 90 deg).
 * Methods: 1c every diagonal |x| == |y| of the four quadrants (the octant boundaries),
 * -32768 included */
static void test_req_trig_003_atan2_diagonals(void **state)
{
    int32_t v;
    (void)state;
    for (v = 1; v <= 32768; v++) {
        qfoc_q15_t p = (qfoc_q15_t)((v > 32767) ? -32768 : v);
        qfoc_q15_t n = (qfoc_q15_t)(-v);
        if (v <= 32767) {
            assert_int_equal(qfoc_atan2(p, p), 0x2000u);
            assert_int_equal(qfoc_atan2(p, n), 0x6000u);
            assert_int_equal(qfoc_atan2(n, n), 0xA000u);
            assert_int_equal(qfoc_atan2(n, p), 0xE000u);
        } else {
            assert_int_equal(qfoc_atan2(p, p), 0xA000u);   /* (-32768, -32768) */
        }
    }
}

/* REQ-TRIG-004: zero vector and the axes, -32768 included.
 * Methods: 1c the zero vector, every point of the four half-axes with -32768, and the points
 * one and three counts off the axis */
static void test_req_trig_004_atan2_axes(void **state)
{
    int32_t v;
    (void)state;
    assert_int_equal(qfoc_atan2(0, 0), 0u);
    for (v = 1; v <= 32768; v++) {
        qfoc_q15_t n = (qfoc_q15_t)(-v);
        if (v <= 32767) {
            qfoc_q15_t p = (qfoc_q15_t)v;
            assert_int_equal(qfoc_atan2(0, p), 0u);
            assert_int_equal(qfoc_atan2(p, 0), 0x4000u);
        }
        assert_int_equal(qfoc_atan2(0, n), 0x8000u);
        assert_int_equal(qfoc_atan2(n, 0), 0xC000u);
    }
    /* just off the axes: one count away from the exact axis direction */
    assert_int_equal(qfoc_atan2(1, 32767), 0u);          /* 0.318 counts */
    assert_int_equal(qfoc_atan2(-1, 32767), 0u);         /* -0.318 -> 65536 mod 2^16 */
    assert_int_equal(qfoc_atan2(3, 32767), 1u);          /* 0.955 counts */
    assert_int_equal(qfoc_atan2(-3, 32767), 0xFFFFu);
}

/* REQ-TRIG-005: the committed tables equal their defining formulas
 * (recomputed here from math.h, independent of tools/codegen/gen_trig_tables.py).
 * Methods: 1b every entry of both committed tables; 1c the last entries (sine node 256 =
 * 65534, arctangent node 128 = 32768); 1n the defining formulas recomputed from math.h,
 * independently of the table generator */
static void test_req_trig_005_tables(void **state)
{
    uint32_t i;
    (void)state;
    for (i = 0u; i < QFOC_TRIG_SIN_TAB_LEN; i++) {
        double v = 2.0 * 32767.0 * sin((PI / 2.0) * (double)i / 256.0);
        assert_int_equal(qfoc_trig_sin_tab[i], (uint32_t)floor(v + 0.5));
    }
    for (i = 0u; i < QFOC_TRIG_ATAN_TAB_LEN; i++) {
        double v = 4.0 * (32768.0 / PI) * atan((double)i / 128.0);
        assert_int_equal(qfoc_trig_atan_tab[i], (uint32_t)floor(v + 0.5));
    }
    assert_int_equal(qfoc_trig_sin_tab[256], 65534u);
    assert_int_equal(qfoc_trig_atan_tab[128], 32768u);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_req_trig_001_sin_exhaustive),
        cmocka_unit_test(test_req_trig_001_sin_corners),
        cmocka_unit_test(test_req_trig_001_sin_symmetry),
        cmocka_unit_test(test_req_trig_002_sincos_exhaustive),
        cmocka_unit_test(test_req_trig_002_sincos_wrap),
        cmocka_unit_test(test_req_trig_001_sincos_nodes),
        cmocka_unit_test(test_req_trig_002_sincos_is_sin_pair),
        cmocka_unit_test(test_req_trig_003_atan2_grid),
        cmocka_unit_test(test_req_trig_003_atan2_small_and_random),
        cmocka_unit_test(test_req_trig_003_atan2_diagonals),
        cmocka_unit_test(test_req_trig_004_atan2_axes),
        cmocka_unit_test(test_req_trig_005_tables),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
