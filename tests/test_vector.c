/**
 * @file test_vector.c
 * @brief Unit tests of qfoc_isqrt32, qfoc_vec_mag and qfoc_circle_limit.
 *
 * References are independent: sqrt() of math.h in double (exact enough for
 * integers below 2^52) and the defining inequalities r^2 <= v < (r + 1)^2 in
 * 64-bit integers; the circle limitation is recomputed in double from its
 * definition (include/qfoc/vector.h).  Inputs: exhaustive ranges where cheap,
 * the corners -32768, -32767, -1, 0, 1, 32767, and pseudo-random values from
 * a fixed-seed LCG.
 * Requirements: REQ-VEC-001 .. REQ-VEC-004 (specs/requirements/trig.md).
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>
#include <math.h>

#include "qfoc/vector.h"

static uint32_t lcg_state = 777u;

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

static const int16_t corners[] = { -32768, -32767, -23170, -16384, -1, 0, 1, 16384, 23170, 32767 };
#define N_CORNERS (sizeof(corners) / sizeof(corners[0]))

/* floor(sqrt(v)) from the C library, in double. */
static uint64_t isqrt_ref(uint64_t v)
{
    return (uint64_t)floor(sqrt((double)v));
}

static void isqrt_check(uint32_t v)
{
    uint64_t r = (uint64_t)qfoc_isqrt32(v);
    assert_true((r * r) <= (uint64_t)v);
    assert_true((uint64_t)v < ((r + 1u) * (r + 1u)));
    assert_int_equal(r, isqrt_ref(v));
}

/* REQ-VEC-001: isqrt exhaustive on [0, 2^21), on every k^2 - 1, k^2, k^2 + k
 * (the values next to each root change), and on random 32-bit values.
 * Methods: 1b every value of [0, 2^21) and 1000000 random 32-bit values; 1c every k^2 - 1,
 * k^2 and k^2 + k (the values beside each change of the root), 0x80000000, 0xFFFE0000,
 * 0xFFFE0001 and 0xFFFFFFFF; 1n floor(sqrt()) of the C library in double precision */
static void test_req_vec_001_isqrt(void **state)
{
    uint32_t v;
    uint32_t k;
    (void)state;
    for (v = 0u; v < (1u << 21); v++) {
        isqrt_check(v);
    }
    for (k = 1u; k <= 65535u; k++) {
        isqrt_check((k * k) - 1u);
        isqrt_check(k * k);
        isqrt_check((k * k) + k);
    }
    isqrt_check(0xFFFFFFFFu);
    isqrt_check(0x80000000u);
    lcg_state = 99u;
    for (k = 0u; k < 1000000u; k++) {
        isqrt_check(lcg_next());
    }
    assert_int_equal(qfoc_isqrt32(0xFFFFFFFFu), 65535u);
    assert_int_equal(qfoc_isqrt32(0xFFFE0001u), 65535u);   /* 65535^2 */
    assert_int_equal(qfoc_isqrt32(0xFFFE0000u), 65534u);
}

static void mag_check(int32_t x, int32_t y, double *max_err)
{
    qfoc_q15_t m = qfoc_vec_mag((qfoc_q15_t)x, (qfoc_q15_t)y);
    double exact = sqrt(((double)x * x) + ((double)y * y));
    double expect = floor(exact);
    if (expect > 32767.0) {
        expect = 32767.0;
    }
    assert_int_equal((int32_t)m, (int32_t)expect);
    if (exact <= 32767.0) {
        double e = exact - (double)m;    /* floor: 0 <= e < 1 */
        assert_true(e >= 0.0);
        if (e > *max_err) {
            *max_err = e;
        }
    }
}

/* REQ-VEC-002: magnitude on corners, a grid, random vectors, saturation.
 * Methods: 1b a grid of every 97th value in both components over the whole plane and 1000000
 * random vectors; 1c ten corners (-32768, -32767, +-23170, +-16384, -1, 0, 1, 32767)
 * crossed, the saturation of (-32768, -32768) and (-32768, 0); 1n sqrt() in double
 * precision, error below 1 LSB */
static void test_req_vec_002_mag(void **state)
{
    double max_err = 0.0;
    size_t i;
    size_t j;
    int32_t x;
    int32_t y;
    uint32_t k;
    (void)state;
    for (i = 0u; i < N_CORNERS; i++) {
        for (j = 0u; j < N_CORNERS; j++) {
            mag_check(corners[i], corners[j], &max_err);
        }
    }
    for (x = -32768; x <= 32767; x += 97) {
        for (y = -32768; y <= 32767; y += 97) {
            mag_check(x, y, &max_err);
        }
    }
    lcg_state = 4242u;
    for (k = 0u; k < 1000000u; k++) {
        mag_check((int32_t)lcg_int16(), (int32_t)lcg_int16(), &max_err);
    }
    print_message("REQ-VEC-002 vec_mag: max error %.6f LSB (floor, bound < 1)\n", max_err);
    assert_true(max_err < 1.0);
    assert_int_equal(qfoc_vec_mag(-32768, -32768), 32767);   /* 46341 saturated */
    assert_int_equal(qfoc_vec_mag(-32768, 0), 32767);        /* 32768 saturated */
    assert_int_equal(qfoc_vec_mag(32767, 0), 32767);
    assert_int_equal(qfoc_vec_mag(3, -4), 5);
    assert_int_equal(qfoc_vec_mag(0, 0), 0);
    assert_int_equal(qfoc_vec_mag(1, 1), 1);                 /* floor(1.414) */
}

/* Independent double reference of the circle limitation. */
static void circle_ref(int32_t d, int32_t q, int32_t vmax, int32_t *rd, int32_t *rq, int *rlim)
{
    double vm = (vmax < 0) ? 0.0 : (double)vmax;
    double dd = (double)d;
    double qq = (double)q;
    double ql;
    if (dd > vm) {
        dd = vm;
    } else if (dd < -vm) {
        dd = -vm;
    }
    ql = floor(sqrt((vm * vm) - (dd * dd)));
    if (qq > ql) {
        qq = ql;
    } else if (qq < -ql) {
        qq = -ql;
    }
    *rd = (int32_t)dd;
    *rq = (int32_t)qq;
    *rlim = ((((double)d * d) + ((double)q * q)) > (vm * vm)) ? 1 : 0;
}

static void circle_check(int32_t d, int32_t q, int32_t vmax, double *max_short)
{
    qfoc_dq_t in;
    qfoc_dq_t out;
    qfoc_dq_t io;
    int32_t rd;
    int32_t rq;
    int rlim;
    bool lim;
    bool lim_io;
    double vm = (vmax < 0) ? 0.0 : (double)vmax;
    in.d = (qfoc_q15_t)d;
    in.q = (qfoc_q15_t)q;
    io = in;
    lim = qfoc_circle_limit(&in, (qfoc_q15_t)vmax, &out);
    lim_io = qfoc_circle_limit(&io, (qfoc_q15_t)vmax, &io);   /* in-place */
    circle_ref(d, q, vmax, &rd, &rq, &rlim);
    assert_int_equal(out.d, rd);
    assert_int_equal(out.q, rq);
    assert_int_equal(lim ? 1 : 0, rlim);
    assert_int_equal(io.d, out.d);
    assert_int_equal(io.q, out.q);
    assert_int_equal(lim_io ? 1 : 0, rlim);
    /* inside the circle */
    assert_true((((double)out.d * out.d) + ((double)out.q * out.q)) <= (vm * vm));
    if (rlim != 0) {
        /* a limited output lies on the circle within 1 LSB (q rounded down) */
        double s = vm - sqrt(((double)out.d * out.d) + ((double)out.q * out.q));
        if (s > *max_short) {
            *max_short = s;
        }
    } else {
        assert_int_equal(out.d, d);
        assert_int_equal(out.q, q);
    }
}

/* REQ-VEC-003 / REQ-VEC-004: corners (negative vmax, -32768 components).
 * Methods: 1b the behaviours inside, limited in q and d beyond the limit (q = 0); 1c ten
 * corners of d and q crossed with eight limits (-32768, -1, 0, 1, 100, 23170, 32766, 32767),
 * a vector exactly on the circle and one LSB outside; 1d a negative limit, taken as 0; 1n
 * the double-precision limitation model */
static void test_req_vec_003_circle_corners(void **state)
{
    static const int16_t vmaxes[] = { -32768, -1, 0, 1, 100, 23170, 32766, 32767 };
    double max_short = 0.0;
    size_t i;
    size_t j;
    size_t k;
    qfoc_dq_t in;
    qfoc_dq_t out;
    (void)state;
    for (k = 0u; k < (sizeof(vmaxes) / sizeof(vmaxes[0])); k++) {
        for (i = 0u; i < N_CORNERS; i++) {
            for (j = 0u; j < N_CORNERS; j++) {
                circle_check(corners[i], corners[j], vmaxes[k], &max_short);
            }
        }
    }
    /* d priority: d beyond the limit takes the whole circle, q = 0 */
    in.d = -32768;
    in.q = 1000;
    assert_true(qfoc_circle_limit(&in, 20000, &out));
    assert_int_equal(out.d, -20000);
    assert_int_equal(out.q, 0);
    /* inside: untouched, false */
    in.d = 3000;
    in.q = -4000;
    assert_false(qfoc_circle_limit(&in, 5000, &out));   /* exactly on the circle */
    assert_int_equal(out.d, 3000);
    assert_int_equal(out.q, -4000);
    assert_true(qfoc_circle_limit(&in, 4999, &out));
    assert_int_equal(out.d, 3000);
    assert_int_equal(out.q, -3998);   /* floor(sqrt(4999^2 - 3000^2)) = 3998.75 -> 3998 */
    /* negative vmax acts as 0 */
    assert_true(qfoc_circle_limit(&in, -5, &out));
    assert_int_equal(out.d, 0);
    assert_int_equal(out.q, 0);
}

/* REQ-VEC-003 / REQ-VEC-004: random inputs, all vmax signs.
 * Methods: 1b 500000 random (d, q, limit) triples of every sign, and the same scaled down so
 * that inside and outside the circle both occur often; 1d negative limits among the draws;
 * 1n the double-precision limitation model, in place and out of place */
static void test_req_vec_004_circle_random(void **state)
{
    double max_short = 0.0;
    uint32_t k;
    (void)state;
    lcg_state = 31337u;
    for (k = 0u; k < 500000u; k++) {
        int32_t d = (int32_t)lcg_int16();
        int32_t q = (int32_t)lcg_int16();
        int32_t v = (int32_t)lcg_int16();
        circle_check(d, q, v, &max_short);
        /* small vectors near a small circle: inside and outside both frequent */
        circle_check(d / 512, q / 512, v / 512, &max_short);
    }
    print_message("REQ-VEC-004 circle_limit: max radial shortfall of a limited output %.6f LSB\n",
                  max_short);
    assert_true(max_short < 1.0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_req_vec_001_isqrt),
        cmocka_unit_test(test_req_vec_002_mag),
        cmocka_unit_test(test_req_vec_003_circle_corners),
        cmocka_unit_test(test_req_vec_004_circle_random),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
