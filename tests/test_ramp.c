/*
 * test_ramp.c -- unit tests of the rate limiter (include/qfoc/ramp.h).
 *
 * Reference: a double-precision model of "move toward the target by at most
 * |step|": v, t saturated to [-32767, 32767], s = min(|step|, 32767);
 * result = t if |t - v| <= s, else v + s sign(t - v).  The operation is exact
 * (no rounding), so the expected error is 0 LSB.
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>
#include <math.h>

#include "qfoc/ramp.h"
#define TEST_SEED 4242u
#include "test_util.h"

static double ref_ramp(int16_t value, int16_t target, int16_t step)
{
    const double v = sat15d((double)value);
    const double t = sat15d((double)target);
    const double s = fmin(fabs((double)step), 32767.0);
    double r;
    if (fabs(t - v) <= s) {
        r = t;
    } else {
        r = v + copysign(s, t - v);
    }
    return r;
}

/* one comparison plus the structural properties; returns |error| */
static double check_one(int16_t value, int16_t target, int16_t step)
{
    const double v = sat15d((double)value);
    const double t = sat15d((double)target);
    const double s = fmin(fabs((double)step), 32767.0);
    const double r = (double)qfoc_ramp_toward(value, target, step);
    const double e = fabs(r - ref_ramp(value, target, step));
    assert_true(r >= -32767.0 && r <= 32767.0);
    /* never past the target, never away from it */
    assert_true(fabs(t - r) <= fabs(t - v));
    assert_true((r - v) * (t - v) >= 0.0);
    if (fabs(t - v) > s) {
        /* distance reduced by exactly s; strictly between for s > 0 */
        assert_true(fabs(t - r) == (fabs(t - v) - s));
        if (s > 0.0) {
            assert_true(fmin(v, t) < r && r < fmax(v, t));
        }
    } else {
        assert_true(r == t);
    }
    return e;
}

/* REQ-RAMP-001, REQ-RAMP-002, REQ-RAMP-003, REQ-RAMP-004: random triples against the
   double reference
   Methods: 1b 300000 random (value, target, step) triples over the int16 domain, half of the
   steps small so that both outcomes (target reached, one step taken) occur often; 1n the
   double-precision model of the ramp */
static void test_ramp_random_vs_reference(void **state)
{
    double max_err = 0.0;
    uint32_t k;
    (void)state;
    for (k = 0u; k < 300000u; k++) {
        const int16_t v = rand_i16();
        const int16_t t = rand_i16();
        /* half of the steps small, so that both outcomes occur often */
        const int16_t s = ((k & 1u) != 0u) ? rand_i16() : (int16_t)rand_range(-300, 300);
        max_err = fmax(max_err, check_one(v, t, s));
    }
    print_message("ramp: max |error| vs double reference = %.1f LSB (300000 random triples)\n",
                  max_err);
    assert_true(max_err == 0.0);
}

/* REQ-RAMP-001, REQ-RAMP-002, REQ-RAMP-004: every combination of the corner values
   Methods: 1c every combination of twelve corner values (-32768, -32767, -32766, -1, 0, 1,
   2, 32766, 32767, ...) for value, target and step, a step of exactly the distance and one
   less; 1n the double-precision model of the ramp */
static void test_ramp_corners(void **state)
{
    static const int16_t c[] = { -32768, -32767, -32766, -1000, -1, 0, 1, 2, 1000,
                                 16384, 32766, 32767 };
    const size_t n = sizeof(c) / sizeof(c[0]);
    size_t i;
    size_t j;
    size_t k;
    double max_err = 0.0;
    (void)state;
    for (i = 0u; i < n; i++) {
        for (j = 0u; j < n; j++) {
            for (k = 0u; k < n; k++) {
                max_err = fmax(max_err, check_one(c[i], c[j], c[k]));
            }
        }
    }
    assert_true(max_err == 0.0);
    /* specific values */
    assert_int_equal(qfoc_ramp_toward(-32768, 32767, 32767), 0);       /* -32767 + 32767 */
    assert_int_equal(qfoc_ramp_toward(-32768, 32767, -32768), 0);      /* |-32768| -> 32767 */
    assert_int_equal(qfoc_ramp_toward(0, -32768, 5), -5);
    assert_int_equal(qfoc_ramp_toward(-32768, -32768, 0), -32767);     /* saturated hold */
    assert_int_equal(qfoc_ramp_toward(-32768, 0, 0), -32767);
    assert_int_equal(qfoc_ramp_toward(100, 100, 0), 100);
    assert_int_equal(qfoc_ramp_toward(100, 103, 3), 103);              /* exactly one step */
    assert_int_equal(qfoc_ramp_toward(100, 104, 3), 103);
    assert_int_equal(qfoc_ramp_toward(100, 96, -3), 97);               /* negative step */
    assert_int_equal(qfoc_ramp_toward(32767, -32767, 32767), 0);
}

/* REQ-RAMP-002, REQ-RAMP-003, REQ-RAMP-004: a ramp reaches its target in
   ceil(|t - v| / s) calls, moving monotonically, and then holds it
   Methods: 1b 200 ramps between random values with random steps 1 .. 2000, upward and
   downward, counted against ceil(distance / step) */
static void test_ramp_sequence(void **state)
{
    uint32_t trial;
    (void)state;
    for (trial = 0u; trial < 200u; trial++) {
        int16_t v = rand_i16();
        const int16_t t = rand_i16();
        const int16_t s = (int16_t)rand_range(1, 2000);
        const double dist = fabs(sat15d((double)t) - sat15d((double)v));
        const uint32_t expect = (uint32_t)ceil(dist / (double)s);
        uint32_t calls = 0u;
        while ((double)v != sat15d((double)t)) {
            const int16_t nv = qfoc_ramp_toward(v, t, s);
            assert_true(fabs((double)t - (double)nv) < fabs((double)t - sat15d((double)v)));
            v = nv;
            calls++;
            assert_true(calls <= 70000u);
        }
        assert_int_equal(calls, expect);
        assert_int_equal(qfoc_ramp_toward(v, t, s), v);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_ramp_random_vs_reference),
        cmocka_unit_test(test_ramp_corners),
        cmocka_unit_test(test_ramp_sequence),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
