/*
 * test_pi.c -- unit tests of the PI controller (include/qfoc/pi.h).
 *
 * Reference: the discrete PI of document chapter 2,
 *     u(k) = kp e(k) + I(k),  I(k) = I(k-1) + ki T e(k),
 * evaluated in double precision with the same clamping anti-windup (integrator
 * clamped to [out_min, out_max], output clamped to the same interval).  Values are
 * in Q15 LSB; the fixed-point integrator is exact, so the expected output error is
 * the final rounding only: |u - u_ref| <= 0.5 LSB (pi.h).
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>
#include <math.h>

#include "qfoc/pi.h"
#include "test_util.h"

/* ---- helpers ------------------------------------------------------------ */


typedef struct {
    double kp;   /* real proportional gain */
    double ki;   /* real integral gain per sample */
    double lo;   /* limits, Q15 LSB */
    double hi;
    double integ; /* integrator, Q15 LSB */
    int limited;
} ref_pi_t;

static void ref_init(ref_pi_t *r, const qfoc_pi_params_t *p)
{
    r->kp = (double)p->kp / 32768.0 * ldexp(1.0, p->kp_shift);
    r->ki = (double)p->ki / 32768.0 * ldexp(1.0, p->ki_shift);
    r->lo = (double)p->out_min;
    r->hi = (double)p->out_max;
    r->integ = (0.0 < r->lo) ? r->lo : ((0.0 > r->hi) ? r->hi : 0.0);
    r->limited = 0;
}

static double clampd(double x, double lo, double hi)
{
    return (x > hi) ? hi : ((x < lo) ? lo : x);
}

static double ref_step(ref_pi_t *r, int16_t e)
{
    double u;
    r->integ = clampd(r->integ + (r->ki * (double)e), r->lo, r->hi);
    u = (r->kp * (double)e) + r->integ;
    r->limited = (u > r->hi) || (u < r->lo);
    return clampd(u, r->lo, r->hi);
}

static qfoc_pi_params_t make_params(int16_t kp, uint8_t kps, int16_t ki, uint8_t kis,
                                    int16_t lo, int16_t hi)
{
    qfoc_pi_params_t p;
    p.kp = kp;
    p.kp_shift = kps;
    p.ki = ki;
    p.ki_shift = kis;
    p.out_min = lo;
    p.out_max = hi;
    return p;
}

/* ---- tests --------------------------------------------------------------- */

/* REQ-PI-004, REQ-PI-005, REQ-PI-007, REQ-PI-008: random gains, limits and error
   sequences against the double-precision reference with the same anti-windup.
   Methods: 1b 400 random gain, shift and limit sets with 500 random errors each, of every
   magnitude from full scale down to a few LSB; 1c the error -32768 every 97th sample,
   limited and unlimited outputs both reached; 1n the double-precision PI with the same
   anti-windup, error <= 0.5 LSB */
static void test_pi_random_vs_reference(void **state)
{
    double max_err = 0.0;
    double max_integ_err = 0.0;
    uint32_t n_limited = 0u;
    uint32_t set;
    (void)state;
    lcg_state = 12345u;
    for (set = 0u; set < 400u; set++) {
        qfoc_pi_t pi;
        ref_pi_t ref;
        int32_t a = rand_range(-32767, 32767);
        int32_t b = rand_range(-32767, 32767);
        qfoc_pi_params_t p = make_params((int16_t)rand_range(0, 32767),
                                         (uint8_t)rand_range(0, 15),
                                         (int16_t)rand_range(0, 32767),
                                         (uint8_t)rand_range(0, 15),
                                         (int16_t)((a < b) ? a : b),
                                         (int16_t)((a < b) ? b : a));
        uint32_t k;
        int32_t err_scale = rand_range(0, 15);
        assert_int_equal(qfoc_pi_init(&pi, &p), QFOC_PI_OK);
        ref_init(&ref, &p);
        for (k = 0u; k < 500u; k++) {
            /* errors of all magnitudes: full range down to a few LSB */
            int32_t e32 = (int32_t)rand_i16() / (int32_t)(1 << err_scale);
            int16_t e = (int16_t)e32;
            double u_ref;
            qfoc_q15_t u;
            if ((k % 97u) == 0u) {
                e = (int16_t)-32768;
            }
            u_ref = ref_step(&ref, e);
            u = qfoc_pi_step(&pi, e);
            max_err = fmax(max_err, fabs((double)u - u_ref));
            max_integ_err = fmax(max_integ_err, fabs(((double)pi.integ / 65536.0) - ref.integ));
            assert_true(fabs((double)u - u_ref) <= 0.5);
            assert_true((u >= p.out_min) && (u <= p.out_max));
            assert_int_equal(pi.limited ? 1 : 0, ref.limited);
            assert_true(qfoc_pi_is_valid(&pi));
            n_limited += pi.limited ? 1u : 0u;
        }
    }
    assert_true(max_integ_err == 0.0);
    assert_true(n_limited > 0u);
    print_message("PI vs double reference: max |u - u_ref| = %.6f LSB (bound 0.5), "
                  "max integrator error = %.6g LSB, limited samples = %u\n",
                  max_err, max_integ_err, (unsigned)n_limited);
}

/* REQ-PI-004: step response of a constant error: u(k) = kp e + k ki e.
   Methods: 1a the step response u(k) = kp e + k ki T e of REQ-PI-004 computed by hand for a
   PI and for a proportional-only controller */
static void test_pi_step_response(void **state)
{
    qfoc_pi_t pi;
    /* kp = 0.5, ki T = 1/64 */
    qfoc_pi_params_t p = make_params(16384, 0u, 512, 0u, -32767, 32767);
    int32_t k;
    (void)state;
    assert_int_equal(qfoc_pi_init(&pi, &p), QFOC_PI_OK);
    for (k = 1; k <= 100; k++) {
        qfoc_q15_t u = qfoc_pi_step(&pi, 1000);
        double expect = (0.5 * 1000.0) + ((double)k * 1000.0 / 64.0);
        assert_true(fabs((double)u - expect) <= 0.5);
        assert_false(pi.limited);
    }
    /* proportional-only step: immediate, no ramp */
    p = make_params(8192, 0u, 0, 0u, -32767, 32767);
    assert_int_equal(qfoc_pi_init(&pi, &p), QFOC_PI_OK);
    for (k = 0; k < 10; k++) {
        assert_int_equal(qfoc_pi_step(&pi, -4000), -1000);
    }
}

/* REQ-PI-001, REQ-PI-004: gains above 1 through the shift.
   Methods: 1c the largest gain 32767 x 2^15 (one LSB of error reaches 32767, two are
   limited); 1d gains of 1 and above, which a Q15 mantissa alone cannot hold (a shift
   mishandled would wrap them); 1a gains of 2.5 and 3.0 through the shifts, results
   computed by hand */
static void test_pi_gain_above_one(void **state)
{
    qfoc_pi_t pi;
    /* kp = 20480 / 32768 x 2^2 = 2.5 */
    qfoc_pi_params_t p = make_params(20480, 2u, 0, 0u, -32767, 32767);
    (void)state;
    assert_int_equal(qfoc_pi_init(&pi, &p), QFOC_PI_OK);
    assert_int_equal(qfoc_pi_step(&pi, 1000), 2500);
    assert_int_equal(qfoc_pi_step(&pi, -1000), -2500);
    /* kp = 32767 x 2^15 / 32768 = 32767: one LSB of error gives 32767 LSB */
    p = make_params(32767, 15u, 0, 0u, -32767, 32767);
    assert_int_equal(qfoc_pi_init(&pi, &p), QFOC_PI_OK);
    assert_int_equal(qfoc_pi_step(&pi, 1), 32767);
    assert_false(pi.limited);
    assert_int_equal(qfoc_pi_step(&pi, 2), 32767);
    assert_true(pi.limited);
    /* ki T = 3.0 (24576 x 2^2): each sample adds 3 e */
    p = make_params(0, 0u, 24576, 2u, -32767, 32767);
    assert_int_equal(qfoc_pi_init(&pi, &p), QFOC_PI_OK);
    assert_int_equal(qfoc_pi_step(&pi, 100), 300);
    assert_int_equal(qfoc_pi_step(&pi, 100), 600);
}

/* REQ-PI-005, REQ-PI-007, REQ-PI-008: output clamped to the limits, flag set
   exactly then.
   Methods: 1c errors one LSB inside and outside each limit, and -32768 and 32767: the flag
   set exactly when the output is clamped */
static void test_pi_limit_flag(void **state)
{
    qfoc_pi_t pi;
    qfoc_pi_params_t p = make_params(32767, 0u, 0, 0u, -1000, 2000);
    (void)state;
    assert_int_equal(qfoc_pi_init(&pi, &p), QFOC_PI_OK);
    assert_int_equal(qfoc_pi_step(&pi, 1999), 1999);
    assert_false(pi.limited);
    assert_int_equal(qfoc_pi_step(&pi, 2001), 2000);
    assert_true(pi.limited);
    assert_int_equal(qfoc_pi_step(&pi, -999), -999);
    assert_false(pi.limited);
    assert_int_equal(qfoc_pi_step(&pi, -1001), -1000);
    assert_true(pi.limited);
    assert_int_equal(qfoc_pi_step(&pi, (int16_t)-32768), -1000);
    assert_true(pi.limited);
    assert_int_equal(qfoc_pi_step(&pi, 32767), 2000);
    assert_true(pi.limited);
    assert_int_equal(qfoc_pi_step(&pi, 0), 0);
    assert_false(pi.limited);
}

/* REQ-PI-009: moving symmetric limits; the integrator follows a limit that falls, the
   gains and the flag stay.
   Methods: 1b limits that fall below the integrator and that rise above it, positive and
   negative integrators; 1c the limits -32768, -5, 0, 1 and 32767 (non-positive limits taken
   as 0) */
static void test_pi_set_limit(void **state)
{
    static const int16_t lims[] = { (int16_t)-32768, -5, 0, 1, 700, 20000, 32767 };
    qfoc_pi_t pi;
    qfoc_pi_params_t p = make_params(3000, 1u, 16384, 0u, -30000, 30000);
    size_t i;
    (void)state;
    assert_int_equal(qfoc_pi_init(&pi, &p), QFOC_PI_OK);
    /* integrator at +25000 (x 65536): 100 samples of the error 500 with ki T = 0.5 */
    qfoc_pi_reset(&pi, 25000);
    for (i = 0u; i < sizeof lims / sizeof lims[0]; i++) {
        qfoc_pi_t q = pi;
        const int32_t want = (lims[i] > 0) ? lims[i] : 0;
        const int32_t old = q.integ;
        q.limited = true;
        qfoc_pi_set_limit(&q, lims[i]);
        assert_int_equal(q.params.out_max, want);
        assert_int_equal(q.params.out_min, -want);
        assert_int_equal(q.integ, (old > want * 65536) ? want * 65536
                                  : ((old < -want * 65536) ? -want * 65536 : old));
        assert_int_equal(q.params.kp, 3000);
        assert_int_equal(q.params.kp_shift, 1);
        assert_int_equal(q.params.ki, 16384);
        assert_true(q.limited);
        assert_true(qfoc_pi_is_valid(&q));
        /* the output stays inside the new limits */
        assert_true(qfoc_pi_step(&q, 32767) <= want);
        assert_true(qfoc_pi_step(&q, (int16_t)-32768) >= -want);
    }
    /* a negative integrator is clamped from below */
    qfoc_pi_reset(&pi, -25000);
    qfoc_pi_set_limit(&pi, 1000);
    assert_int_equal(pi.integ, -1000 * 65536);
    /* the limit rises again: the integrator stays where it is */
    qfoc_pi_set_limit(&pi, 32767);
    assert_int_equal(pi.integ, -1000 * 65536);
}

/* REQ-PI-005: after a long saturation the output leaves the limit in the first
   sample in which the error changes sign (no stored windup).
   Methods: 1c 100000 samples on the upper and on the lower limit (error 30000 and -32768);
   1d integrator wind-up: the output must leave the limit in the first sample with the
   opposite error */
static void test_pi_windup_recovery(void **state)
{
    qfoc_pi_t pi;
    qfoc_pi_params_t p = make_params(16384, 0u, 3277, 0u, -20000, 20000);
    int32_t k;
    qfoc_q15_t u;
    (void)state;
    assert_int_equal(qfoc_pi_init(&pi, &p), QFOC_PI_OK);
    for (k = 0; k < 100000; k++) {
        u = qfoc_pi_step(&pi, 30000);
        assert_true(u <= 20000);
    }
    assert_int_equal(u, 20000);
    assert_true(pi.limited);
    assert_int_equal(pi.integ, 20000 * 65536);
    /* error changes sign: u = 20000 - 0.5 x 100 - 0.1 x 100 = 19940 */
    u = qfoc_pi_step(&pi, -100);
    assert_true(u < 20000);
    assert_false(pi.limited);
    assert_true(fabs((double)u - (20000.0 - 50.0 - (3277.0 / 32768.0 * 100.0))) <= 0.5);
    /* same at the lower limit */
    for (k = 0; k < 100000; k++) {
        u = qfoc_pi_step(&pi, (int16_t)-32768);
    }
    assert_int_equal(u, -20000);
    assert_true(pi.limited);
    u = qfoc_pi_step(&pi, 1);
    assert_true(u > -20000);
    assert_false(pi.limited);
}

/* REQ-PI-001, REQ-PI-003: invalid parameters rejected, safe zero-gain state.
   Methods: 1b valid and invalid parameter sets, one rule broken each; 1c shifts 16 and 255,
   gains -1 and -32768, out_min -32768, min > max by one, and the valid extremes (shift 15,
   gain 32767, a single-point range); 1d invalid parameters (the safe zero-gain state with
   stale fields) */
static void test_pi_invalid_params(void **state)
{
    const qfoc_pi_params_t bad[8] = {
        { 1000, 16u, 1000, 0u, -100, 100 },   /* kp_shift > 15 */
        { 1000, 0u, 1000, 16u, -100, 100 },   /* ki_shift > 15 */
        { 1000, 255u, 1000, 255u, -100, 100 },/* both shifts far out */
        { -1, 0u, 1000, 0u, -100, 100 },      /* negative kp */
        { 1000, 0u, -1, 0u, -100, 100 },      /* negative ki */
        { 1000, 0u, 1000, 0u, 101, 100 },     /* min > max */
        { 1000, 0u, 1000, 0u, -32768, 100 },  /* min below symmetric range */
        { -32768, 0u, -32768, 0u, 32767, -32767 } /* everything wrong */
    };
    uint32_t i;
    (void)state;
    for (i = 0u; i < 8u; i++) {
        qfoc_pi_t pi;
        int32_t k;
        assert_false(qfoc_pi_params_is_valid(&bad[i]));
        pi.integ = 12345;
        pi.limited = true;
        assert_int_equal(qfoc_pi_init(&pi, &bad[i]), QFOC_PI_ERR_PARAM);
        assert_true(qfoc_pi_is_valid(&pi));
        assert_int_equal(pi.params.kp, 0);
        assert_int_equal(pi.params.ki, 0);
        assert_int_equal(pi.params.kp_shift, 0);
        assert_int_equal(pi.params.ki_shift, 0);
        assert_int_equal(pi.params.out_min, 0);
        assert_int_equal(pi.params.out_max, 0);
        assert_int_equal(pi.integ, 0);
        assert_false(pi.limited);
        for (k = 0; k < 20; k++) {
            assert_int_equal(qfoc_pi_step(&pi, rand_i16()), 0);
        }
    }
    {
        /* boundary values that are valid */
        const qfoc_pi_params_t good = { 0, 15u, 32767, 15u, -32767, 32767 };
        const qfoc_pi_params_t point = { 5, 0u, 5, 0u, 7, 7 };
        assert_true(qfoc_pi_params_is_valid(&good));
        assert_true(qfoc_pi_params_is_valid(&point));
    }
}

/* REQ-PI-002: instance validity checks the integrator against the limits.
   Methods: 1c the integrator at each limit and one Q31 LSB beyond, the shift 16; 1l
   integrator and shift overwritten by hand, refused by the validity check */
static void test_pi_is_valid(void **state)
{
    qfoc_pi_t pi;
    qfoc_pi_params_t p = make_params(100, 0u, 100, 0u, -100, 200);
    (void)state;
    assert_int_equal(qfoc_pi_init(&pi, &p), QFOC_PI_OK);
    assert_true(qfoc_pi_is_valid(&pi));
    pi.integ = 200 * 65536;
    assert_true(qfoc_pi_is_valid(&pi));
    pi.integ = (200 * 65536) + 1;
    assert_false(qfoc_pi_is_valid(&pi));
    pi.integ = -100 * 65536;
    assert_true(qfoc_pi_is_valid(&pi));
    pi.integ = (-100 * 65536) - 1;
    assert_false(qfoc_pi_is_valid(&pi));
    pi.integ = 0;
    pi.params.kp_shift = 16u;
    assert_false(qfoc_pi_is_valid(&pi));
}

/* REQ-PI-006, REQ-PI-003: bumpless preset, clamped; init with limits excluding 0.
   Methods: 1c presets beyond the upper limit and at -32768, limits that exclude 0 on either
   side; 1a the bumpless preset of REQ-PI-006 */
static void test_pi_reset(void **state)
{
    qfoc_pi_t pi;
    qfoc_pi_params_t p = make_params(16384, 0u, 1000, 0u, -5000, 5000);
    (void)state;
    assert_int_equal(qfoc_pi_init(&pi, &p), QFOC_PI_OK);
    qfoc_pi_reset(&pi, 1234);
    assert_int_equal(pi.integ, 1234 * 65536);
    assert_int_equal(qfoc_pi_step(&pi, 0), 1234);   /* bumpless */
    qfoc_pi_reset(&pi, 6000);
    assert_int_equal(qfoc_pi_step(&pi, 0), 5000);
    assert_false(pi.limited);
    qfoc_pi_reset(&pi, (int16_t)-32768);
    assert_int_equal(qfoc_pi_step(&pi, 0), -5000);
    /* limits that exclude 0: the integrator starts at the nearest limit */
    p = make_params(0, 0u, 0, 0u, 100, 200);
    assert_int_equal(qfoc_pi_init(&pi, &p), QFOC_PI_OK);
    assert_int_equal(pi.integ, 100 * 65536);
    assert_int_equal(qfoc_pi_step(&pi, 0), 100);
    p = make_params(0, 0u, 0, 0u, -200, -100);
    assert_int_equal(qfoc_pi_init(&pi, &p), QFOC_PI_OK);
    assert_int_equal(qfoc_pi_step(&pi, 32767), -100);
}

/* REQ-PI-004, REQ-PI-007: corner errors and rounding (ties away from zero).
   Methods: 1c the errors -32768, -32767, -1, 0, 1, 32766, 32767, the rounding ties +-0.5,
   the largest gains with -32768, a single-point range; 1n the double-precision product */
static void test_pi_corners(void **state)
{
    static const int16_t errs[7] = { (int16_t)-32768, -32767, -1, 0, 1, 32766, 32767 };
    qfoc_pi_t pi;
    qfoc_pi_params_t p = make_params(32767, 0u, 0, 0u, -32767, 32767);
    uint32_t i;
    (void)state;
    assert_int_equal(qfoc_pi_init(&pi, &p), QFOC_PI_OK);
    for (i = 0u; i < 7u; i++) {
        double ref = clampd((double)errs[i] * 32767.0 / 32768.0, -32767.0, 32767.0);
        qfoc_q15_t u = qfoc_pi_step(&pi, errs[i]);
        assert_true(fabs((double)u - ref) <= 0.5);
    }
    /* -32768 x 32767/32768 = -32767.0 exactly: not limited */
    (void)qfoc_pi_step(&pi, (int16_t)-32768);
    assert_false(pi.limited);
    /* ties: kp = 0.5, e = +-1 -> +-0.5 -> +-1 (away from zero); e = +-3 -> +-2 */
    p = make_params(16384, 0u, 0, 0u, -32767, 32767);
    assert_int_equal(qfoc_pi_init(&pi, &p), QFOC_PI_OK);
    assert_int_equal(qfoc_pi_step(&pi, 1), 1);
    assert_int_equal(qfoc_pi_step(&pi, -1), -1);
    assert_int_equal(qfoc_pi_step(&pi, 3), 2);
    assert_int_equal(qfoc_pi_step(&pi, -3), -2);
    /* largest gains with the most negative error: both terms saturate */
    p = make_params(32767, 15u, 32767, 15u, -32767, 32767);
    assert_int_equal(qfoc_pi_init(&pi, &p), QFOC_PI_OK);
    assert_int_equal(qfoc_pi_step(&pi, (int16_t)-32768), -32767);
    assert_true(pi.limited);
    assert_int_equal(pi.integ, -32767 * 65536);
    assert_int_equal(qfoc_pi_step(&pi, 32767), 32767);
    assert_true(qfoc_pi_is_valid(&pi));
    /* single-point limits */
    p = make_params(32767, 15u, 32767, 15u, 7, 7);
    assert_int_equal(qfoc_pi_init(&pi, &p), QFOC_PI_OK);
    assert_int_equal(qfoc_pi_step(&pi, 0), 7);
    assert_false(pi.limited);
    assert_int_equal(qfoc_pi_step(&pi, (int16_t)-32768), 7);
    assert_true(pi.limited);
}

/* REQ-PI-004, REQ-PI-005, REQ-PI-007: the whole span between the limits (2^32 - 2^17
   in Q31) covered in one step, exactly and one LSB beyond, in both directions.
   Methods: 1c the whole span between the limits (2^32 - 2^17 in Q31) covered in one step,
   exactly and one LSB beyond, in both directions, and the rounding ties next to the limits */
static void test_pi_full_span(void **state)
{
    /* 2 x 32767 x 2^15 x 2 = 65534 x 65536: the distance from -32767 to 32767 in Q31 */
    qfoc_pi_t pi;
    qfoc_pi_params_t p = make_params(0, 0u, 32767, 15u, -32767, 32767);
    (void)state;
    assert_int_equal(qfoc_pi_init(&pi, &p), QFOC_PI_OK);
    qfoc_pi_reset(&pi, -32767);
    /* integral term: the increment reaches the upper limit exactly, not limited */
    assert_int_equal(qfoc_pi_step(&pi, 2), 32767);
    assert_int_equal(pi.integ, 32767 * 65536);
    assert_false(pi.limited);
    /* and back to the lower limit exactly */
    assert_int_equal(qfoc_pi_step(&pi, -2), -32767);
    assert_int_equal(pi.integ, -32767 * 65536);
    assert_false(pi.limited);
    /* one more error LSB: clamped (anti-windup), the output on the limit, unlimited
       because P = 0 */
    assert_int_equal(qfoc_pi_step(&pi, 3), 32767);
    assert_int_equal(pi.integ, 32767 * 65536);
    assert_false(pi.limited);
    assert_int_equal(qfoc_pi_step(&pi, -3), -32767);
    assert_int_equal(pi.integ, -32767 * 65536);
    assert_false(pi.limited);
    /* proportional term: P + I lands on the opposite limit exactly, then beyond it */
    p = make_params(32767, 15u, 0, 0u, -32767, 32767);
    assert_int_equal(qfoc_pi_init(&pi, &p), QFOC_PI_OK);
    qfoc_pi_reset(&pi, -32767);
    assert_int_equal(qfoc_pi_step(&pi, 2), 32767);
    assert_false(pi.limited);
    assert_int_equal(qfoc_pi_step(&pi, 3), 32767);
    assert_true(pi.limited);
    qfoc_pi_reset(&pi, 32767);
    assert_int_equal(qfoc_pi_step(&pi, -2), -32767);
    assert_false(pi.limited);
    assert_int_equal(qfoc_pi_step(&pi, -3), -32767);
    assert_true(pi.limited);
    assert_int_equal(pi.integ, 32767 * 65536);
    /* rounding ties next to the limits: kp = 0.5, I = -32000, e = -1 gives
       -32000.5 -> -32001, e = 1 gives -31999.5 -> -32000 (away from zero) */
    p = make_params(16384, 0u, 0, 0u, -32767, 32767);
    assert_int_equal(qfoc_pi_init(&pi, &p), QFOC_PI_OK);
    qfoc_pi_reset(&pi, -32000);
    assert_int_equal(qfoc_pi_step(&pi, -1), -32001);
    assert_int_equal(qfoc_pi_step(&pi, 1), -32000);
    qfoc_pi_reset(&pi, 32000);
    assert_int_equal(qfoc_pi_step(&pi, 1), 32001);
    assert_int_equal(qfoc_pi_step(&pi, -1), 32000);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_pi_random_vs_reference),
        cmocka_unit_test(test_pi_step_response),
        cmocka_unit_test(test_pi_gain_above_one),
        cmocka_unit_test(test_pi_limit_flag),
        cmocka_unit_test(test_pi_windup_recovery),
        cmocka_unit_test(test_pi_invalid_params),
        cmocka_unit_test(test_pi_is_valid),
        cmocka_unit_test(test_pi_reset),
        cmocka_unit_test(test_pi_set_limit),
        cmocka_unit_test(test_pi_corners),
        cmocka_unit_test(test_pi_full_span),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
