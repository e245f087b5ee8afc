/* Unit tests of include/qfoc/q15.h against double-precision references.
 * Requirements: REQ-Q15-001 .. REQ-Q15-008 (specs/requirements/q15.md).
 *
 * Every 16-bit input pair that is cheap to enumerate is enumerated; 32-bit inputs
 * are covered by their boundaries and a fixed-seed random sample. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <math.h>
#include <cmocka.h>

#include "qfoc/q15.h"

static uint32_t lcg_state = 12345u;

static uint32_t lcg_next(void)
{
    lcg_state = (lcg_state * 1664525u) + 1013904223u;
    return lcg_state;
}

static int32_t rand_i32(void)
{
    return (int32_t)lcg_next();
}

/* reference: saturate a real value to the symmetric range [-lim, lim] */
static double ref_sat(double x, double lim)
{
    return (x > lim) ? lim : ((x < -lim) ? -lim : x);
}

/* reference: round to nearest, ties away from zero */
static double ref_round(double x)
{
    return (x >= 0.0) ? floor(x + 0.5) : -floor(-x + 0.5);
}

/* REQ-Q15-001: saturation to the symmetric Q15 range
 * Methods: 1b 200000 random int32 values, half of them scaled into the Q15 band; 1c
 * INT32_MIN, INT32_MIN + 1, -32769, -32768, -32767, 32767, 32768, INT32_MAX; 1n the
 * double-precision saturation model */
static void test_req_q15_001_sat(void **state)
{
    (void)state;
    const int32_t corners[] = { INT32_MIN, INT32_MIN + 1, -32769, -32768, -32767, -1, 0, 1,
                                32766, 32767, 32768, INT32_MAX };
    for (size_t i = 0u; i < (sizeof corners / sizeof corners[0]); i++) {
        assert_int_equal(qfoc_q15_sat(corners[i]), (int32_t)ref_sat((double)corners[i], 32767.0));
    }
    for (int32_t k = 0; k < 200000; k++) {
        int32_t x = rand_i32() / ((k % 2 == 0) ? 1 : 30000);
        assert_int_equal(qfoc_q15_sat(x), (int32_t)ref_sat((double)x, 32767.0));
    }
}

/* REQ-Q15-002: saturating add and sub, all 2^32 pairs would take too long: the
 * corners crossed with every value, plus random pairs.
 * Methods: 1b 500000 random pairs; 1c nine corners (-32768, -32767, -16384, -1, 0, 1, 16384,
 * 32766, 32767) crossed with every int16 value, in both operand orders; 1n the
 * double-precision sum saturated */
static void test_req_q15_002_add_sub(void **state)
{
    (void)state;
    const int16_t corners[] = { -32768, -32767, -16384, -1, 0, 1, 16384, 32766, 32767 };
    for (size_t i = 0u; i < (sizeof corners / sizeof corners[0]); i++) {
        for (int32_t b = -32768; b <= 32767; b++) {
            int16_t a = corners[i];
            assert_int_equal(qfoc_q15_add(a, (int16_t)b), (int32_t)ref_sat((double)a + b, 32767.0));
            assert_int_equal(qfoc_q15_sub(a, (int16_t)b), (int32_t)ref_sat((double)a - b, 32767.0));
            assert_int_equal(qfoc_q15_sub((int16_t)b, a), (int32_t)ref_sat((double)b - a, 32767.0));
        }
    }
    for (int32_t k = 0; k < 500000; k++) {
        int16_t a = (int16_t)lcg_next();
        int16_t b = (int16_t)lcg_next();
        assert_int_equal(qfoc_q15_add(a, b), (int32_t)ref_sat((double)a + b, 32767.0));
        assert_int_equal(qfoc_q15_sub(a, b), (int32_t)ref_sat((double)a - b, 32767.0));
    }
}

/* REQ-Q15-003: negate and absolute value, exhaustive
 * Methods: 1b every int16 value (the domain enumerated); 1c -32768, whose negation and
 * absolute value saturate to 32767; 1n the double-precision negation and absolute value
 * saturated */
static void test_req_q15_003_neg_abs(void **state)
{
    (void)state;
    for (int32_t a = -32768; a <= 32767; a++) {
        int16_t r = qfoc_q15_neg((int16_t)a);
        int16_t m = qfoc_q15_abs((int16_t)a);
        assert_int_equal(r, (int32_t)ref_sat(-(double)a, 32767.0));
        assert_int_equal(m, (int32_t)ref_sat(fabs((double)a), 32767.0));
        assert_true(r != -32768);
        /* a result is always safe to negate again */
        assert_int_equal(qfoc_q15_neg(r), -r);
    }
    assert_int_equal(qfoc_q15_neg(-32768), 32767);
    assert_int_equal(qfoc_q15_abs(-32768), 32767);
}

/* REQ-Q15-004: Q30 -> Q15 with rounding to nearest, ties away from zero
 * Methods: 1b 1000000 random int32 values; 1c INT32_MIN, INT32_MAX, the values beside the
 * saturation of +-32767 and the rounding ties +-16384 and +-16383 (half an LSB); 1n the
 * double-precision quotient rounded half away from zero and saturated */
static void test_req_q15_004_from_q30(void **state)
{
    (void)state;
    const int32_t corners[] = { INT32_MIN, -1073741824, -1073725441, -1073725440, -1073725439,
                                -1073709056, -49152, -16385, -16384, -16383, -1, 0, 1,
                                16383, 16384, 16385, 49151, 49152, 1073709056, 1073725439,
                                1073725440, 1073741824, INT32_MAX };
    for (size_t i = 0u; i < (sizeof corners / sizeof corners[0]); i++) {
        double ref = ref_sat(ref_round((double)corners[i] / 32768.0), 32767.0);
        assert_int_equal(qfoc_q15_from_q30(corners[i]), (int32_t)ref);
    }
    /* ties: +0.5 LSB rounds away from zero in both directions (no bias) */
    assert_int_equal(qfoc_q15_from_q30(16384), 1);
    assert_int_equal(qfoc_q15_from_q30(-16384), -1);
    assert_int_equal(qfoc_q15_from_q30(16383), 0);
    assert_int_equal(qfoc_q15_from_q30(-16383), 0);
    double max_err = 0.0;
    for (int32_t k = 0; k < 1000000; k++) {
        int32_t x = rand_i32() / ((k % 3 == 0) ? 1 : 2);
        double exact = (double)x / 32768.0;
        double ref = ref_sat(ref_round(exact), 32767.0);
        int16_t r = qfoc_q15_from_q30(x);
        assert_int_equal(r, (int32_t)ref);
        if (fabs(exact) < 32767.0) {
            double e = fabs((double)r - exact);
            max_err = (e > max_err) ? e : max_err;
        }
    }
    assert_true(max_err <= 0.5);
    print_message("from_q30: max |error| inside range = %.6f LSB\n", max_err);
}

/* REQ-Q15-005: Q15 x Q15, error <= 0.5 LSB, only -1 x -1 saturates
 * Methods: 1b 1000000 random pairs; 1c ten corners (-32768, -32767, -16384, -2 .. 2, 16384,
 * 32767) crossed with every int16 value, -32768 x -32768 the only saturating product; 1n the
 * double-precision product rounded and saturated, error <= 0.5 LSB */
static void test_req_q15_005_mul(void **state)
{
    (void)state;
    double max_err = 0.0;
    const int16_t corners[] = { -32768, -32767, -16384, -2, -1, 0, 1, 2, 16384, 32767 };
    for (size_t i = 0u; i < (sizeof corners / sizeof corners[0]); i++) {
        for (int32_t b = -32768; b <= 32767; b++) {
            int16_t a = corners[i];
            double exact = ((double)a * (double)b) / 32768.0;
            int16_t r = qfoc_q15_mul(a, (int16_t)b);
            assert_int_equal(r, (int32_t)ref_sat(ref_round(exact), 32767.0));
        }
    }
    for (int32_t k = 0; k < 1000000; k++) {
        int16_t a = (int16_t)lcg_next();
        int16_t b = (int16_t)lcg_next();
        double exact = ((double)a * (double)b) / 32768.0;
        int16_t r = qfoc_q15_mul(a, b);
        assert_int_equal(r, (int32_t)ref_sat(ref_round(exact), 32767.0));
        if (fabs(exact) <= 32767.0) {
            double e = fabs((double)r - exact);
            max_err = (e > max_err) ? e : max_err;
        }
    }
    assert_int_equal(qfoc_q15_mul(-32768, -32768), 32767);
    assert_int_equal(qfoc_q15_mul(32767, 32767), 32766);
    assert_int_equal(qfoc_q15_mul(-32768, 32767), -32767);
    assert_true(max_err <= 0.5);
    print_message("mul: max |error| = %.6f LSB\n", max_err);
}

/* REQ-Q15-006: Q31 saturation and addition
 * Methods: 1b 500000 random int32 pairs; 1c INT64_MIN, INT64_MAX, +-2^31, INT32_MIN +
 * INT32_MIN and INT32_MAX + 1 at the saturation; 1n the double-precision sum saturated to
 * +-(2^31 - 1) */
static void test_req_q15_006_q31(void **state)
{
    (void)state;
    const double lim = 2147483647.0;
    assert_int_equal(qfoc_q31_sat(INT64_MIN), -2147483647);
    assert_int_equal(qfoc_q31_sat(INT64_MAX), 2147483647);
    assert_int_equal(qfoc_q31_sat(-2147483648LL), -2147483647);
    assert_int_equal(qfoc_q31_sat(2147483648LL), 2147483647);
    assert_int_equal(qfoc_q31_sat(0), 0);
    assert_int_equal(qfoc_q31_add(INT32_MIN, INT32_MIN), -2147483647);
    assert_int_equal(qfoc_q31_add(INT32_MAX, 1), 2147483647);
    for (int32_t k = 0; k < 500000; k++) {
        int32_t a = rand_i32();
        int32_t b = rand_i32();
        assert_int_equal(qfoc_q31_add(a, b), (int64_t)ref_sat((double)a + (double)b, lim));
    }
}

/* REQ-Q15-007: multiply-accumulate acc + 2ab in Q31
 * Methods: 1b 500000 random (acc, a, b) triples; 1c -32768 x -32768, -32768 x 32767 and the
 * accumulator at INT32_MIN and INT32_MAX; 1n the double-precision acc + 2ab saturated */
static void test_req_q15_007_mac(void **state)
{
    (void)state;
    const double lim = 2147483647.0;
    assert_int_equal(qfoc_q31_mac(0, -32768, -32768), 2147483647);
    assert_int_equal(qfoc_q31_mac(0, -32768, 32767), -2147418112);
    assert_int_equal(qfoc_q31_mac(INT32_MIN, -32768, 32767), -2147483647);
    assert_int_equal(qfoc_q31_mac(INT32_MAX, 32767, 32767), 2147483647);
    for (int32_t k = 0; k < 500000; k++) {
        int32_t acc = rand_i32();
        int16_t a = (int16_t)lcg_next();
        int16_t b = (int16_t)lcg_next();
        double exact = (double)acc + (2.0 * (double)a * (double)b);
        assert_int_equal(qfoc_q31_mac(acc, a, b), (int64_t)ref_sat(exact, lim));
    }
}

/* REQ-Q15-008: Q31 <-> Q15 conversions
 * Methods: 1b every int16 value through Q31 and back, 1000000 random int32 values; 1c
 * INT32_MIN, INT32_MAX, the rounding ties +-32768 and the values beside the saturation; 1n
 * the double-precision quotient rounded and saturated */
static void test_req_q15_008_q31_q15(void **state)
{
    (void)state;
    for (int32_t a = -32768; a <= 32767; a++) {
        assert_int_equal(qfoc_q31_from_q15((int16_t)a), (int64_t)a * 65536);
        if (a != -32768) {
            assert_int_equal(qfoc_q15_from_q31(qfoc_q31_from_q15((int16_t)a)), a);
        }
    }
    const int32_t corners[] = { INT32_MIN, -2147450881, -2147450880, -32769, -32768, -32767,
                                -1, 0, 1, 32767, 32768, 98304, 2147450879, 2147450880, INT32_MAX };
    for (size_t i = 0u; i < (sizeof corners / sizeof corners[0]); i++) {
        double ref = ref_sat(ref_round((double)corners[i] / 65536.0), 32767.0);
        assert_int_equal(qfoc_q15_from_q31(corners[i]), (int32_t)ref);
    }
    for (int32_t k = 0; k < 1000000; k++) {
        int32_t x = rand_i32();
        double ref = ref_sat(ref_round((double)x / 65536.0), 32767.0);
        assert_int_equal(qfoc_q15_from_q31(x), (int32_t)ref);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_req_q15_001_sat),
        cmocka_unit_test(test_req_q15_002_add_sub),
        cmocka_unit_test(test_req_q15_003_neg_abs),
        cmocka_unit_test(test_req_q15_004_from_q30),
        cmocka_unit_test(test_req_q15_005_mul),
        cmocka_unit_test(test_req_q15_006_q31),
        cmocka_unit_test(test_req_q15_007_mac),
        cmocka_unit_test(test_req_q15_008_q31_q15),
    };
    return cmocka_run_group_tests_name("q15", tests, NULL, NULL);
}
