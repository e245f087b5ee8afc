/*
 * test_trqcomp.c -- unit and closed-loop tests of the torque compensation and the
 * mechanical-angle tracker (include/qfoc/trqcomp.h).
 *
 * References (double precision, independent of the implementation):
 *  - tracker: the unwrapped electrical angle (an integer count accumulated from the
 *    same steps), theta_m = floor(mod(count, n_p 65536) / n_p); error bound 0
 *    (exact) and < 1 count against the real quotient;
 *  - output: sum_h (a_h / 65536) cos(h theta) + (b_h / 65536) sin(h theta) with the
 *    exact cos / sin; bound 0.5 + 2 (|a_1| + |b_1| + |a_2| + |b_2|) / 32768 LSB;
 *  - one learning step: a_h + gain / 32768 x e x sigma sin(h theta) (Q15 LSB) with
 *    the exact sine, clamped; bound (0.5 + 2 |e| / 32768) x 2 gain Q31 LSB;
 *  - closed loop: the reference motor's mechanics J dw/dt = K_t i_q - T_L - B w
 *    (RK4, double), a pulsating load, the Q15 speed PI of the reference table and
 *    this module in the 1 ms tick / 8 kHz fast step: speed ripple with and without
 *    compensation (REQ-TC-010: reduction >= 70 %).
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "qfoc/trqcomp.h"
#include "qfoc/pi.h"
#include "qfoc/q15.h"
#include "reference_params.h"

#define TEST_SEED 20240611u
#include "test_util.h"

#define TWO_PI 6.28318530717958647692

/* Default parameters of the reference motor (specs/requirements/trqcomp.md,
   REQ-TC-010): every test uses these unless it tests another value. */
#define TC_GAIN_DEFAULT ((int16_t)492)        /* mu = 0.015 */
#define TC_AMP_DEFAULT ((int16_t)8192)        /* 0.25 pu = 10 A */
#define TC_SPEED_MIN_DEFAULT ((int16_t)1966)  /* 600 rpm */
#define TC_SPEED_MAX_DEFAULT ((int16_t)19661) /* 6000 rpm */

static qfoc_trqcomp_params_t default_params(void)
{
    qfoc_trqcomp_params_t p;
    p.gain = TC_GAIN_DEFAULT;
    p.amp_max = TC_AMP_DEFAULT;
    p.speed_min = TC_SPEED_MIN_DEFAULT;
    p.speed_max = TC_SPEED_MAX_DEFAULT;
    p.pole_pairs = 3u;
    return p;
}

static double clampd(double x, double lo, double hi)
{
    return (x > hi) ? hi : ((x < lo) ? lo : x);
}

/* ---- mechanical-angle tracker ------------------------------------------ */

/* REQ-TC-001: initialisation, bad pole-pair counts, the validity check.
   Methods: 1b every pole-pair count 0 .. 255 (1 .. 16 accepted, the rest refused); 1c 0, 1,
   16 and 17 at the ends of the range; 1d an invalid count (the safe tracker); 1l turn,
   reciprocal and pole pairs of a tracker overwritten, refused by the validity check */
static void test_tc_mech_init(void **state)
{
    qfoc_mech_t m;
    uint32_t pp;
    (void)state;
    for (pp = 0u; pp <= 255u; pp++) {
        int32_t st = qfoc_mech_init(&m, (uint8_t)pp, (qfoc_angle_t)(pp * 257u));
        assert_true(qfoc_mech_is_valid(&m));
        assert_int_equal(m.turn, 0);
        assert_int_equal(m.theta_e, (qfoc_angle_t)(pp * 257u));
        if ((pp >= 1u) && (pp <= 16u)) {
            assert_int_equal(st, QFOC_TRQCOMP_OK);
            assert_int_equal(m.pole_pairs, pp);
            assert_int_equal(m.recip, (uint32_t)ceil(268435456.0 / (double)pp));
        } else {
            assert_int_equal(st, QFOC_TRQCOMP_ERR_PARAM);
            assert_int_equal(m.pole_pairs, 1);
        }
    }
    /* corrupted trackers are rejected */
    (void)qfoc_mech_init(&m, 3u, 0u);
    m.turn = 3u;
    assert_false(qfoc_mech_is_valid(&m));
    (void)qfoc_mech_init(&m, 3u, 0u);
    m.recip = m.recip + 1u;
    assert_false(qfoc_mech_is_valid(&m));
    (void)qfoc_mech_init(&m, 3u, 0u);
    m.pole_pairs = 0u;
    assert_false(qfoc_mech_is_valid(&m));
    (void)qfoc_mech_init(&m, 3u, 0u);
    m.pole_pairs = 17u;
    assert_false(qfoc_mech_is_valid(&m));
}

/* REQ-TC-002: exhaustive exactness of the reciprocal scaling: for every pole-pair
   count 1..16 a forward sweep of one count per call visits every electrical count
   0 .. n_p 65536 - 1 of a mechanical turn (and wraps back to 0).
   Methods: 1b every electrical count of a mechanical turn for every pole-pair count 1 .. 16
   (the domain enumerated); 1c the wrap back to 0 at n_p 65536 */
static void test_tc_mech_exhaustive(void **state)
{
    uint32_t pp;
    uint32_t n_checked = 0u;
    (void)state;
    for (pp = 1u; pp <= 16u; pp++) {
        qfoc_mech_t m;
        uint32_t n;
        (void)qfoc_mech_init(&m, (uint8_t)pp, 0u);
        for (n = 1u; n <= (pp * 65536u); n++) {
            const uint32_t count = n % (pp * 65536u);
            const qfoc_angle_t th = qfoc_mech_update(&m, (qfoc_angle_t)(count & 0xFFFFu));
            if (th != (qfoc_angle_t)(count / pp)) {
                fail_msg("pp %u count %u: %u != %u", (unsigned)pp, (unsigned)count,
                         (unsigned)th, (unsigned)(count / pp));
            }
            n_checked++;
        }
        assert_int_equal(m.turn, 0);
    }
    print_message("mech tracker: %u counts (pole pairs 1..16, every count of a mechanical "
                  "turn) exact\n", (unsigned)n_checked);
}

/* REQ-TC-002: random step sequences, forward and reverse, every wrap-around, pole
   pairs 1..16, against the unwrapped double reference; error 0 counts vs the
   floor, < 1 count vs the real quotient.
   Methods: 1b 320 random step sequences, forward and reverse, for every pole-pair count,
   more than 1000 turn changes; 1c the largest admissible steps +32767 and -32768 every 37th
   call; 1n the unwrapped quotient in 64-bit and double precision (0 counts against the
   floor, < 1 against the real quotient) */
static void test_tc_mech_random(void **state)
{
    uint32_t pp;
    double max_real_err = 0.0;
    uint32_t wraps = 0u;
    (void)state;
    lcg_state = 777u;
    for (pp = 1u; pp <= 16u; pp++) {
        uint32_t seq;
        for (seq = 0u; seq < 20u; seq++) {
            qfoc_mech_t m;
            const int64_t period = (int64_t)pp * 65536;
            int64_t count = rand_range(0, 65535);   /* electrical count since the zero */
            int32_t dir = ((seq % 2u) == 0u) ? 1 : -1;
            int32_t max_step = rand_range(1, 32767);
            uint32_t k;
            uint8_t turn_prev = 0u;
            (void)qfoc_mech_init(&m, (uint8_t)pp, (qfoc_angle_t)count);
            for (k = 0u; k < 4000u; k++) {
                int32_t step = rand_range(0, max_step) * dir;
                double real;
                qfoc_angle_t th;
                int64_t wrapped;
                if ((k % 500u) == 499u) {
                    dir = -dir;       /* direction reversals */
                }
                if ((k % 37u) == 0u) {
                    step = (dir > 0) ? 32767 : -32768;   /* largest admissible steps */
                }
                count += step;
                wrapped = ((count % period) + period) % period;
                th = qfoc_mech_update(&m, (qfoc_angle_t)(wrapped & 0xFFFF));
                assert_int_equal(th, (qfoc_angle_t)(wrapped / (int64_t)pp));
                real = (double)wrapped / (double)pp;
                max_real_err = fmax(max_real_err, real - (double)th);
                assert_true(((real - (double)th) >= 0.0) && ((real - (double)th) < 1.0));
                assert_true(qfoc_mech_is_valid(&m));
                wraps += (m.turn != turn_prev) ? 1u : 0u;
                turn_prev = m.turn;
            }
        }
    }
    assert_true(wraps > 1000u);
    print_message("mech tracker random (forward/reverse, pp 1..16): exact; max (real - "
                  "theta_m) = %.4f count (bound < 1); %u turn changes\n", max_real_err,
                  (unsigned)wraps);
}

/* REQ-TC-002: the half-turn boundary of the step interpretation.
   Methods: 1c the half-turn boundary of the step interpretation: +32767 (forward), +32768
   (read as -32768), -32769 (read as +32767), -1, and the wraps across the last turn, 1 pole
   pair */
static void test_tc_mech_half_turn(void **state)
{
    qfoc_mech_t m;
    (void)state;
    /* +32767 is a forward step without wrap */
    (void)qfoc_mech_init(&m, 4u, 0u);
    assert_int_equal(qfoc_mech_update(&m, 32767u), 32767u / 4u);
    assert_int_equal(m.turn, 0);
    /* from 32767 to 0 is -32767: reverse, no wrap */
    assert_int_equal(qfoc_mech_update(&m, 0u), 0u);
    assert_int_equal(m.turn, 0);
    /* 0 -> 32768 is +32768, read as -32768: a reverse wrap to turn 3 */
    assert_int_equal(qfoc_mech_update(&m, 32768u), (3u * 65536u + 32768u) / 4u);
    assert_int_equal(m.turn, 3);
    /* 32768 -> 0 is -32768: reverse, no wrap */
    assert_int_equal(qfoc_mech_update(&m, 0u), (3u * 65536u) / 4u);
    assert_int_equal(m.turn, 3);
    /* 0 -> 65535 is +65535 = -1: reverse wrap to turn 2 */
    assert_int_equal(qfoc_mech_update(&m, 65535u), (2u * 65536u + 65535u) / 4u);
    assert_int_equal(m.turn, 2);
    /* 65535 -> 32766 is -32769 = +32767: forward wrap to turn 3 */
    assert_int_equal(qfoc_mech_update(&m, 32766u), (3u * 65536u + 32766u) / 4u);
    assert_int_equal(m.turn, 3);
    /* forward wrap from the last turn to turn 0 */
    assert_int_equal(qfoc_mech_update(&m, 65000u), (3u * 65536u + 65000u) / 4u);
    assert_int_equal(qfoc_mech_update(&m, 100u), 25u);
    assert_int_equal(m.turn, 0);
    /* 1 pole pair: mechanical = electrical */
    (void)qfoc_mech_init(&m, 1u, 65535u);
    assert_int_equal(qfoc_mech_update(&m, 5u), 5u);
    assert_int_equal(qfoc_mech_update(&m, 65530u), 65530u);
}

/* ---- parameters and instance --------------------------------------------- */

/* REQ-TC-003, REQ-TC-004: parameter check, safe state, reset, instance check.
   Methods: 1b each parameter field out of range alone, and the valid extremes; 1c gain -1
   and -32768, amp_max -32768, speed_min -1 and above speed_max, pole pairs 0 and 17, all-0
   and all-32767 / 16 accepted, the coefficients at +-amp_max and one beyond, INT32_MIN and
   INT32_MAX; 1d invalid parameters (the safe state never learns and outputs 0); 1l
   coefficients and pole pairs overwritten, refused by the validity check */
static void test_tc_params_init(void **state)
{
    qfoc_trqcomp_t tc;
    qfoc_trqcomp_params_t p = default_params();
    (void)state;
    assert_true(qfoc_trqcomp_params_is_valid(&p));
    assert_int_equal(qfoc_trqcomp_init(&tc, &p), QFOC_TRQCOMP_OK);
    assert_true(qfoc_trqcomp_is_valid(&tc));
    assert_int_equal(tc.params.gain, p.gain);
    assert_int_equal(tc.params.amp_max, p.amp_max);
    assert_int_equal(tc.params.speed_min, p.speed_min);
    assert_int_equal(tc.params.speed_max, p.speed_max);
    assert_int_equal(tc.params.pole_pairs, p.pole_pairs);
    assert_int_equal(tc.a[0], 0);
    assert_int_equal(tc.b[1], 0);

    /* each field out of range */
    {
        qfoc_trqcomp_params_t bad[8];
        uint32_t i;
        for (i = 0u; i < 8u; i++) {
            bad[i] = default_params();
        }
        bad[0].gain = -1;
        bad[1].amp_max = (int16_t)-32768;
        bad[2].speed_min = -1;
        bad[3].speed_min = 20000;   /* > speed_max */
        bad[4].pole_pairs = 0u;
        bad[5].pole_pairs = 17u;
        bad[6].speed_max = -5;
        bad[7].gain = (int16_t)-32768;
        for (i = 0u; i < 8u; i++) {
            assert_false(qfoc_trqcomp_params_is_valid(&bad[i]));
            tc.a[0] = 12345;
            assert_int_equal(qfoc_trqcomp_init(&tc, &bad[i]), QFOC_TRQCOMP_ERR_PARAM);
            assert_true(qfoc_trqcomp_is_valid(&tc));
            assert_int_equal(tc.params.gain, 0);
            assert_int_equal(tc.params.amp_max, 0);
            assert_int_equal(tc.params.speed_min, 0);
            assert_int_equal(tc.params.speed_max, 0);
            assert_int_equal(tc.params.pole_pairs, 1);
            assert_int_equal(tc.a[0], 0);
            /* the safe state never learns and outputs 0 */
            qfoc_trqcomp_learn(&tc, 1000u, 30000, 0);
            assert_int_equal(qfoc_trqcomp_output(&tc, 1000u, 0), 0);
            assert_int_equal(tc.a[0], 0);
            assert_int_equal(tc.b[0], 0);
        }
    }
    /* limits of the valid ranges */
    p.gain = 0;
    p.amp_max = 0;
    p.speed_min = 0;
    p.speed_max = 0;
    p.pole_pairs = 1u;
    assert_true(qfoc_trqcomp_params_is_valid(&p));
    p.gain = 32767;
    p.amp_max = 32767;
    p.speed_min = 32767;
    p.speed_max = 32767;
    p.pole_pairs = 16u;
    assert_true(qfoc_trqcomp_params_is_valid(&p));

    /* instance check: each coefficient beyond +-amp_max, invalid parameters */
    p = default_params();
    (void)qfoc_trqcomp_init(&tc, &p);
    tc.a[0] = 8192 * 65536;
    assert_true(qfoc_trqcomp_is_valid(&tc));
    tc.a[0] = -(8192 * 65536);
    assert_true(qfoc_trqcomp_is_valid(&tc));
    tc.a[0] = (8192 * 65536) + 1;
    assert_false(qfoc_trqcomp_is_valid(&tc));
    tc.a[0] = 0;
    tc.b[0] = -(8192 * 65536) - 1;
    assert_false(qfoc_trqcomp_is_valid(&tc));
    tc.b[0] = 0;
    tc.a[1] = INT32_MIN;
    assert_false(qfoc_trqcomp_is_valid(&tc));
    tc.a[1] = 0;
    tc.b[1] = INT32_MAX;
    assert_false(qfoc_trqcomp_is_valid(&tc));
    tc.b[1] = 0;
    assert_true(qfoc_trqcomp_is_valid(&tc));
    tc.params.pole_pairs = 0u;
    assert_false(qfoc_trqcomp_is_valid(&tc));
    tc.params.pole_pairs = 3u;
    /* reset clears */
    tc.a[0] = 5;
    tc.b[0] = -5;
    tc.a[1] = 7;
    tc.b[1] = -7;
    qfoc_trqcomp_reset(&tc);
    assert_int_equal(tc.a[0], 0);
    assert_int_equal(tc.b[0], 0);
    assert_int_equal(tc.a[1], 0);
    assert_int_equal(tc.b[1], 0);
}

/* ---- output -------------------------------------------------------------- */

static double ref_output(const qfoc_trqcomp_t *tc, qfoc_angle_t th)
{
    const double x = TWO_PI * (double)th / 65536.0;
    return ((double)tc->a[0] / 65536.0 * cos(x)) + ((double)tc->b[0] / 65536.0 * sin(x))
           + ((double)tc->a[1] / 65536.0 * cos(2.0 * x))
           + ((double)tc->b[1] / 65536.0 * sin(2.0 * x));
}

static int32_t rand_coef(int16_t amp)
{
    const int32_t lim = (int32_t)amp * 65536;
    return rand_range(-lim, lim);
}

/* REQ-TC-008: the output against the double sum, random coefficients and angles,
   all amplitude limits up to 32767 (saturation of the sum).
   Methods: 1b 200000 random coefficients and angles, a quarter with random amplitude limits
   up to 32767; 1c coefficients on the limit every 1000th draw, the sum saturated; 1n the
   double-precision sum of the harmonics */
static void test_tc_output_vs_reference(void **state)
{
    qfoc_trqcomp_t tc;
    qfoc_trqcomp_params_t p = default_params();
    double max_err = 0.0;
    double max_err_default = 0.0;
    uint32_t k;
    (void)state;
    lcg_state = 4242u;
    for (k = 0u; k < 200000u; k++) {
        const qfoc_angle_t th = (qfoc_angle_t)rand_range(0, 65535);
        double ref;
        double bound;
        double err;
        qfoc_q15_t out;
        p.amp_max = ((k % 4u) == 0u) ? (int16_t)rand_range(0, 32767) : TC_AMP_DEFAULT;
        assert_int_equal(qfoc_trqcomp_init(&tc, &p), QFOC_TRQCOMP_OK);
        tc.a[0] = rand_coef(p.amp_max);
        tc.b[0] = rand_coef(p.amp_max);
        tc.a[1] = rand_coef(p.amp_max);
        tc.b[1] = rand_coef(p.amp_max);
        if ((k % 1000u) == 0u) {
            tc.a[0] = (int32_t)p.amp_max * 65536;   /* coefficients on the limit */
            tc.b[0] = -(int32_t)p.amp_max * 65536;
        }
        ref = ref_output(&tc, th);
        out = qfoc_trqcomp_output(&tc, th, 4915);
        /* 1 LSB of each sine of the first harmonic, 2.5 of the second (doubled from
           the first) per unit amplitude, x 2 for the pair; 1/2 LSB rounding */
        bound = 0.5 + ((2.0 * (fabs((double)tc.a[0]) + fabs((double)tc.b[0]))
                        + 5.0 * (fabs((double)tc.a[1]) + fabs((double)tc.b[1]))) / 65536.0 / 32768.0);
        err = fabs((double)out - sat15d(ref));
        assert_true(err <= bound);
        assert_true(fabs((double)out) <= (4.0 * (double)p.amp_max));
        if (p.amp_max == TC_AMP_DEFAULT) {
            max_err_default = fmax(max_err_default, err);
            assert_true(err <= 2.5);
        } else {
            max_err = fmax(max_err, err);
        }
    }
    print_message("output vs double: max error %.3f LSB at amp_max 8192 (bound 2.5), %.3f LSB "
                  "for amp_max up to 32767 (bound 0.5 + (2 |h1| + 5 |h2|) / 32768)\n",
                  max_err_default, max_err);
}

/* REQ-TC-005, REQ-TC-008: the speed window of the output, -32768 included.
   Methods: 1c the speed window's edges speed_min and speed_max and one outside, for both
   signs, 0, 32767 and -32768 (outside even with speed_max 32767), every coefficient at
   +-32767 pu (the sum saturated) */
static void test_tc_output_window(void **state)
{
    qfoc_trqcomp_t tc;
    qfoc_trqcomp_params_t p = default_params();
    (void)state;
    assert_int_equal(qfoc_trqcomp_init(&tc, &p), QFOC_TRQCOMP_OK);
    tc.a[0] = 1000 * 65536;   /* i_ff = 1000 cos(theta) */
    assert_int_equal(qfoc_trqcomp_output(&tc, 0u, TC_SPEED_MIN_DEFAULT), 1000);
    assert_int_equal(qfoc_trqcomp_output(&tc, 0u, TC_SPEED_MAX_DEFAULT), 1000);
    assert_int_equal(qfoc_trqcomp_output(&tc, 0u, -TC_SPEED_MIN_DEFAULT), 1000);
    assert_int_equal(qfoc_trqcomp_output(&tc, 0u, -TC_SPEED_MAX_DEFAULT), 1000);
    assert_int_equal(qfoc_trqcomp_output(&tc, 0x8000u, 4915), -1000);
    assert_int_equal(qfoc_trqcomp_output(&tc, 0u, TC_SPEED_MIN_DEFAULT - 1), 0);
    assert_int_equal(qfoc_trqcomp_output(&tc, 0u, TC_SPEED_MAX_DEFAULT + 1), 0);
    assert_int_equal(qfoc_trqcomp_output(&tc, 0u, -TC_SPEED_MIN_DEFAULT + 1), 0);
    assert_int_equal(qfoc_trqcomp_output(&tc, 0u, 0), 0);
    assert_int_equal(qfoc_trqcomp_output(&tc, 0u, 32767), 0);
    assert_int_equal(qfoc_trqcomp_output(&tc, 0u, (int16_t)-32768), 0);
    /* window up to the top: -32768 (|.| = 32768) is still outside */
    p.speed_max = 32767;
    (void)qfoc_trqcomp_init(&tc, &p);
    tc.a[0] = 1000 * 65536;
    assert_int_equal(qfoc_trqcomp_output(&tc, 0u, 32767), 1000);
    assert_int_equal(qfoc_trqcomp_output(&tc, 0u, -32767), 1000);
    assert_int_equal(qfoc_trqcomp_output(&tc, 0u, (int16_t)-32768), 0);
    /* saturation: every coefficient at +32767 pu at theta = 0: 2 x 32767 -> 32767;
       at theta = 0x8000 (cos -1, cos(2 theta) = 1): 0 */
    p.amp_max = 32767;
    (void)qfoc_trqcomp_init(&tc, &p);
    tc.a[0] = 32767 * 65536;
    tc.a[1] = 32767 * 65536;
    tc.b[0] = 32767 * 65536;
    tc.b[1] = 32767 * 65536;
    assert_int_equal(qfoc_trqcomp_output(&tc, 0u, 4915), 32767);
    tc.a[0] = -(32767 * 65536);
    tc.a[1] = -(32767 * 65536);
    assert_int_equal(qfoc_trqcomp_output(&tc, 0u, 4915), -32767);
    assert_true(abs(qfoc_trqcomp_output(&tc, 0x8000u, 4915)) <= 2);
}

/* ---- learning ------------------------------------------------------------ */

/* REQ-TC-006, REQ-TC-007: one learning step against the double law, random
   states, errors, angles, both directions, clamping at amp_max.
   Methods: 1b 200000 random states, errors, angles and speeds of both directions, random
   gains and amplitude limits, clamping reached more than 100 times; 1c the error -32768
   every 101st draw, coefficients clamped at amp_max; 1n the double-precision learning law of
   the header */
static void test_tc_learn_vs_reference(void **state)
{
    qfoc_trqcomp_t tc;
    qfoc_trqcomp_params_t p = default_params();
    double max_err_rel = 0.0;
    uint32_t n_clamped = 0u;
    uint32_t k;
    (void)state;
    lcg_state = 99u;
    for (k = 0u; k < 200000u; k++) {
        const qfoc_angle_t th = (qfoc_angle_t)rand_range(0, 65535);
        const double x = TWO_PI * (double)th / 65536.0;
        int16_t e = rand_i16();
        int16_t speed = (int16_t)rand_range(TC_SPEED_MIN_DEFAULT, TC_SPEED_MAX_DEFAULT);
        double sigma;
        double reg[4];
        int32_t old[4];
        int32_t now[4];
        double lim;
        uint32_t j;
        if ((k % 3u) == 0u) {
            e = (int16_t)(e / 256);   /* small errors */
        }
        if ((k % 101u) == 0u) {
            e = (int16_t)-32768;
        }
        if ((k % 2u) == 1u) {
            speed = (int16_t)-speed;
        }
        p.gain = ((k % 5u) == 0u) ? (int16_t)rand_range(0, 32767) : TC_GAIN_DEFAULT;
        p.amp_max = ((k % 7u) == 0u) ? (int16_t)rand_range(0, 32767) : TC_AMP_DEFAULT;
        (void)qfoc_trqcomp_init(&tc, &p);
        tc.a[0] = rand_coef(p.amp_max);
        tc.b[0] = rand_coef(p.amp_max);
        tc.a[1] = rand_coef(p.amp_max);
        tc.b[1] = rand_coef(p.amp_max);
        old[0] = tc.a[0];
        old[1] = tc.b[0];
        old[2] = tc.a[1];
        old[3] = tc.b[1];
        sigma = (speed >= 0) ? 1.0 : -1.0;
        /* the law of the header: a_h with +sigma sin(h x), b_h with -sigma cos(h x) */
        reg[0] = sigma * sin(x);
        reg[1] = -sigma * cos(x);
        /* the second harmonic only while 2 |speed| <= speed_max */
        {
            const double h2 = (2.0 * fabs((double)speed) <= (double)p.speed_max) ? 1.0 : 0.0;
            reg[2] = h2 * sigma * sin(2.0 * x);
            reg[3] = -h2 * sigma * cos(2.0 * x);
        }
        qfoc_trqcomp_learn(&tc, th, e, speed);
        assert_true(qfoc_trqcomp_is_valid(&tc));
        now[0] = tc.a[0];
        now[1] = tc.b[0];
        now[2] = tc.a[1];
        now[3] = tc.b[1];
        lim = (double)p.amp_max * 65536.0;
        for (j = 0u; j < 4u; j++) {
            /* Q31 increment = 2 gain (e reg) in Q15 x ... : gain/32768 x e x reg Q15 LSB */
            const double inc = 2.0 * (double)p.gain * (double)e * reg[j];
            const double ref = clampd((double)old[j] + inc, -lim, lim);
            /* regressor error: 1 LSB (first harmonic), 2.5 LSB (second, doubled from
               the first), x 2 in the product's rounding bound */
            const double bound = 2.0 * (double)p.gain *
                                 (0.5 + (((j < 2u) ? 2.0 : 5.0) * fabs((double)e) / 32768.0));
            const double err = fabs((double)now[j] - ref);
            assert_true(err <= (bound + 1e-6));
            if (bound > 0.0) {
                max_err_rel = fmax(max_err_rel, err / (2.0 * (double)p.gain));
            }
            n_clamped += ((fabs((double)old[j] + inc) > lim) ? 1u : 0u);
        }
    }
    assert_true(n_clamped > 100u);
    print_message("learn step vs double: max error %.3f (units of 2 gain Q31 LSB = one "
                  "rounding of e x regressor; bound 0.5 + 2|e|/32768 <= 2.5); %u clamped\n",
                  max_err_rel, (unsigned)n_clamped);
}

/* REQ-TC-005, REQ-TC-006, REQ-TC-007: coefficients held outside the window, for zero gain
   and zero error; -32768 error and speed; the learning direction; the second harmonic held
   above half the window's top.
   Methods: 1b speeds outside the window, inside at both ends, both directions, the second
   harmonic below and above half the window's top; 1c the errors -32768 and 32767, speeds 0,
   1, speed_min - 1, speed_max + 1, 32767, -32768, amp_max 0 and 1, gain 0 and 32767, 2
   |speed| = speed_max and one above */
static void test_tc_learn_corners(void **state)
{
    qfoc_trqcomp_t tc;
    qfoc_trqcomp_params_t p = default_params();
    const int16_t speeds_out[] = { 0, 1, TC_SPEED_MIN_DEFAULT - 1, TC_SPEED_MAX_DEFAULT + 1,
                                   -(TC_SPEED_MIN_DEFAULT - 1), 32767, -32767, (int16_t)-32768 };
    uint32_t i;
    (void)state;
    (void)qfoc_trqcomp_init(&tc, &p);
    tc.a[0] = 100;
    tc.b[0] = -200;
    tc.a[1] = 300;
    tc.b[1] = -400;
    for (i = 0u; i < (sizeof(speeds_out) / sizeof(speeds_out[0])); i++) {
        qfoc_trqcomp_learn(&tc, 0x2000u, (int16_t)-32768, speeds_out[i]);
        qfoc_trqcomp_learn(&tc, 0x2000u, 32767, speeds_out[i]);
        assert_int_equal(tc.a[0], 100);
        assert_int_equal(tc.b[0], -200);
        assert_int_equal(tc.a[1], 300);
        assert_int_equal(tc.b[1], -400);
    }
    /* zero error: nothing changes */
    qfoc_trqcomp_learn(&tc, 0x2000u, 0, 4915);
    assert_int_equal(tc.a[0], 100);
    assert_int_equal(tc.b[1], -400);
    /* inside the window at both ends: changes */
    qfoc_trqcomp_learn(&tc, 0x4000u, 1000, TC_SPEED_MIN_DEFAULT);
    assert_true(tc.a[0] > 100);   /* a_1 with +sin(90 deg) = +1 */
    qfoc_trqcomp_learn(&tc, 0x4000u, 1000, -TC_SPEED_MAX_DEFAULT);
    assert_int_equal(tc.a[0], 100);   /* reverse: a_1 with -sin, exactly undone */
    /* theta 0, forward: b_1 -= e, b_2 -= e (cos = 1), a unchanged (sin = 0) */
    (void)qfoc_trqcomp_init(&tc, &p);
    qfoc_trqcomp_learn(&tc, 0u, 1000, 4915);
    assert_int_equal(tc.a[0], 0);
    assert_int_equal(tc.a[1], 0);
    assert_int_equal(tc.b[0], -2 * 492 * 1000);
    assert_int_equal(tc.b[1], -2 * 492 * 1000);
    /* -32768 error at the clamp: saturates at -amp_max / +amp_max */
    p.gain = 32767;
    p.amp_max = 1;
    (void)qfoc_trqcomp_init(&tc, &p);
    qfoc_trqcomp_learn(&tc, 0u, (int16_t)-32768, 4915);
    assert_int_equal(tc.b[0], 65536);
    assert_int_equal(tc.b[1], 65536);
    qfoc_trqcomp_learn(&tc, 0u, 32767, 4915);
    assert_int_equal(tc.b[0], -65536);
    /* amp_max 0: learning stays at 0 */
    p.amp_max = 0;
    (void)qfoc_trqcomp_init(&tc, &p);
    qfoc_trqcomp_learn(&tc, 0x1234u, 20000, 4915);
    assert_int_equal(tc.a[0], 0);
    assert_int_equal(tc.b[0], 0);
    assert_int_equal(tc.a[1], 0);
    assert_int_equal(tc.b[1], 0);
    /* the second harmonic learns up to 2 |speed| = speed_max, either direction, and is held
       above while the first learns */
    {
        const int16_t half = (int16_t)(TC_SPEED_MAX_DEFAULT / 2);
        const int16_t sp[4] = { half, (int16_t)-half, (int16_t)(half + 1), (int16_t)-(half + 1) };
        for (i = 0u; i < 4u; i++) {
            p = default_params();
            (void)qfoc_trqcomp_init(&tc, &p);
            qfoc_trqcomp_learn(&tc, 0u, 1000, sp[i]);
            assert_int_equal(tc.b[0], ((sp[i] > 0) ? -1 : 1) * 2 * 492 * 1000);
            assert_int_equal(tc.b[1], (i < 2u) ? (((sp[i] > 0) ? -1 : 1) * 2 * 492 * 1000) : 0);
            assert_int_equal(tc.a[1], 0);
        }
    }
    /* gain 0: held */
    p = default_params();
    p.gain = 0;
    (void)qfoc_trqcomp_init(&tc, &p);
    qfoc_trqcomp_learn(&tc, 0x1234u, 20000, 4915);
    assert_int_equal(tc.b[0], 0);
}

/* REQ-TC-009: phase of the 1x component against atan2.
   Methods: 1b 20000 random phases and amplitudes 1000 .. 8192; 1c the zero coefficients
   (phase 0); 1n atan2() in double precision */
static void test_tc_phase1(void **state)
{
    qfoc_trqcomp_t tc;
    qfoc_trqcomp_params_t p = default_params();
    double max_err = 0.0;
    uint32_t k;
    (void)state;
    (void)qfoc_trqcomp_init(&tc, &p);
    assert_int_equal(qfoc_trqcomp_phase1(&tc), 0u);
    lcg_state = 31u;
    for (k = 0u; k < 20000u; k++) {
        const double phi = TWO_PI * (double)rand_range(0, 65535) / 65536.0;
        const double amp = (double)rand_range(1000, 8192);
        double ref;
        double d;
        tc.a[0] = (int32_t)lround(amp * cos(phi) * 65536.0);
        tc.b[0] = (int32_t)lround(amp * sin(phi) * 65536.0);
        ref = atan2((double)tc.b[0], (double)tc.a[0]) * 65536.0 / TWO_PI;
        d = fabs(wrap_pi(TWO_PI * ((double)qfoc_trqcomp_phase1(&tc) - ref) / 65536.0))
            * 65536.0 / TWO_PI;
        /* atan2 1 count + coefficient rounding 0.71 / amp rad */
        assert_true(d <= (1.0 + (0.71 / amp * 65536.0 / TWO_PI)));
        max_err = fmax(max_err, d);
    }
    print_message("phase1 vs atan2: max error %.2f counts (amplitudes 1000..8192 LSB)\n", max_err);
}

/* ---- closed loop (REQ-TC-010) ------------------------------------------- */

/* reference motor (specs/reference-motor.md) */
#define M_J 3e-4
#define M_B 1e-4
#define M_KT 0.2925          /* 1.5 n_p psi_f, N m / A */
#define M_NP 3.0
#define M_IBASE 40.0
#define M_WBASE (TWO_PI * 500.0)
#define T_PWM (1.0 / 8000.0)
#define RPM_TO_RAD (TWO_PI / 60.0)

typedef struct {
    double rpm;            /* speed reference, mechanical rpm (sign: direction) */
    double t_mean;         /* mean load torque, N m (signed: opposes the motion) */
    double k1, phi1;       /* 1x pulsation: relative amplitude and phase */
    double k2, phi2;       /* 2x pulsation */
    double theta0;         /* initial mechanical angle, rad (arbitrary zero) */
    double tau_i;          /* current-loop lag, s (0: ideal) */
    int compensate;        /* 0: speed PI alone */
    double seconds;        /* run time */
    int clamp;             /* 1: the drive's clamp of the i_q reference to +-i_max */
    int hold;              /* 1: no learning in a tick after a clamped fast step */
} loop_cfg_t;

typedef struct {
    double p2p;            /* peak-to-peak of w_m over the last 2 s, rpm */
    double rms;            /* rms of w_m - mean over the last 2 s, rpm */
    double mean_rpm;
    qfoc_angle_t phase1;   /* learned 1x phase */
    double phase1_expect;  /* counts: where the cancelling 1x current peaks */
    double iff_amp1;       /* learned 1x amplitude, A */
    uint32_t clipped;      /* fast steps with the i_q reference clamped to +-i_max */
} loop_res_t;

static double load_torque(const loop_cfg_t *c, double th)
{
    return c->t_mean * (1.0 + (c->k1 * sin(th + c->phi1)) + (c->k2 * sin((2.0 * th) + c->phi2)));
}

/* state: theta_m, w_m, i_q (A) */
static void deriv(const loop_cfg_t *c, const double *x, double i_ref, double *dx)
{
    const double iq = (c->tau_i > 0.0) ? x[2] : i_ref;
    dx[0] = x[1];
    dx[1] = ((M_KT * iq) - load_torque(c, x[0]) - (M_B * x[1])) / M_J;
    dx[2] = (c->tau_i > 0.0) ? ((i_ref - x[2]) / c->tau_i) : 0.0;
}

static void rk4(const loop_cfg_t *c, double *x, double i_ref, double h)
{
    double k1[3];
    double k2[3];
    double k3[3];
    double k4[3];
    double t[3];
    uint32_t i;
    deriv(c, x, i_ref, k1);
    for (i = 0u; i < 3u; i++) { t[i] = x[i] + (0.5 * h * k1[i]); }
    deriv(c, t, i_ref, k2);
    for (i = 0u; i < 3u; i++) { t[i] = x[i] + (0.5 * h * k2[i]); }
    deriv(c, t, i_ref, k3);
    for (i = 0u; i < 3u; i++) { t[i] = x[i] + (h * k3[i]); }
    deriv(c, t, i_ref, k4);
    for (i = 0u; i < 3u; i++) {
        x[i] += h / 6.0 * (k1[i] + (2.0 * k2[i]) + (2.0 * k3[i]) + k4[i]);
    }
}

static qfoc_angle_t angle_q16(double rad)
{
    double turns = rad / TWO_PI;
    turns -= floor(turns);
    return (qfoc_angle_t)((uint32_t)floor(turns * 65536.0) & 0xFFFFu);
}

static loop_res_t run_loop(const loop_cfg_t *c)
{
    const qfoc_trqcomp_params_t p = default_params();
    const int16_t i_max = qfoc_params_reference.i_max;
    const uint32_t n_fast = (uint32_t)lround(c->seconds / T_PWM);
    const uint32_t n_last = (uint32_t)lround(2.0 / T_PWM);
    const double w0 = c->rpm * RPM_TO_RAD;
    const int16_t speed_ref = q15_of(w0 * M_NP / M_WBASE);
    double x[3];
    double theta_ms = c->theta0;   /* theta_m at the previous tick */
    double w_min = 1e9;
    double w_max = -1e9;
    double w_sum = 0.0;
    double w_sq = 0.0;
    int16_t speed_meas = speed_ref;
    int16_t iq_pi;
    qfoc_pi_t pi;
    qfoc_mech_t mech;
    qfoc_trqcomp_t tc;
    loop_res_t r;
    uint32_t k;
    double i_ref_a = 0.0;
    uint32_t clipped_ms = 0u;

    r.clipped = 0u;
    x[0] = c->theta0;
    x[1] = w0;
    x[2] = c->t_mean / M_KT;
    assert_int_equal(qfoc_pi_init(&pi, &qfoc_params_reference.pi_speed), QFOC_PI_OK);
    /* bumpless start at the mean load current */
    qfoc_pi_reset(&pi, q15_of(c->t_mean / M_KT / M_IBASE));
    iq_pi = q15_of(c->t_mean / M_KT / M_IBASE);
    assert_int_equal(qfoc_trqcomp_init(&tc, &p), QFOC_TRQCOMP_OK);
    /* the tracker's zero: wherever the rotor is at the start */
    (void)qfoc_mech_init(&mech, 3u, angle_q16(M_NP * x[0]));

    for (k = 0u; k < n_fast; k++) {
        qfoc_angle_t th_m;
        int32_t iq_ref;
        int16_t i_ff = 0;
        /* fast step (8 kHz): observer angle, mechanical angle, feed-forward */
        th_m = qfoc_mech_update(&mech, angle_q16(M_NP * x[0]));
        if ((k % 8u) == 0u) {
            /* 1 ms tick: speed = mean over the last ms, speed PI, learning */
            if (k > 0u) {
                const double w_mean = (x[0] - theta_ms) / 1e-3;
                speed_meas = q15_of(w_mean * M_NP / M_WBASE);
            }
            theta_ms = x[0];
            {
                const int16_t err = qfoc_q15_sub(speed_ref, speed_meas);
                iq_pi = qfoc_pi_step(&pi, err);
                if ((c->compensate != 0) && ((c->hold == 0) || (clipped_ms == 0u))) {
                    qfoc_trqcomp_learn(&tc, th_m, err, speed_meas);
                }
                clipped_ms = 0u;
            }
        }
        if (c->compensate != 0) {
            i_ff = qfoc_trqcomp_output(&tc, th_m, speed_meas);
        }
        /* the drive: sum clamped to +-i_max */
        iq_ref = (int32_t)iq_pi + (int32_t)i_ff;
        if (c->clamp == 0) {
            /* ideal: the current loop follows any reference */
        } else if (iq_ref > i_max) {
            iq_ref = i_max;
            r.clipped++;
            clipped_ms++;
        } else if (iq_ref < -i_max) {
            iq_ref = -i_max;
            r.clipped++;
            clipped_ms++;
        } else {
            /* inside */
        }
        i_ref_a = (double)iq_ref / 32768.0 * M_IBASE;
        /* plant over one PWM period: 2 RK4 steps of 62.5 us */
        {
            uint32_t s;
            for (s = 0u; s < 2u; s++) {
                rk4(c, x, i_ref_a, T_PWM / 2.0);
            }
        }
        if (k >= (n_fast - n_last)) {
            const double rpm = x[1] / RPM_TO_RAD;
            w_min = fmin(w_min, rpm);
            w_max = fmax(w_max, rpm);
            w_sum += rpm;
            w_sq += rpm * rpm;
        }
    }
    r.p2p = w_max - w_min;
    r.mean_rpm = w_sum / (double)n_last;
    r.rms = sqrt(fmax(0.0, (w_sq / (double)n_last) - (r.mean_rpm * r.mean_rpm)));
    r.phase1 = qfoc_trqcomp_phase1(&tc);
    r.iff_amp1 = hypot((double)tc.a[0], (double)tc.b[0]) / 65536.0 / 32768.0 * M_IBASE;
    {
        /* counted zero = true angle - offset, offset = theta0 - theta_e0 / n_p
           (theta_e0 quantised and wrapped to one electrical turn) */
        const double th_e0 = (double)angle_q16(M_NP * c->theta0) * TWO_PI / 65536.0;
        const double offset = c->theta0 - (th_e0 / M_NP);
        /* cancelling current ~ t_mean k1 sin(theta + phi1) / K_t: peaks at
           theta_true = pi/2 - phi1 (t_mean > 0) i.e. counted pi/2 - phi1 - offset */
        /* a current lag tau_i needs a reference leading by atan(W tau_i) */
        double pk = (0.5 * TWO_PI / 2.0) - c->phi1 - offset - atan(c->rpm * RPM_TO_RAD * c->tau_i);
        if (c->t_mean < 0.0) {
            pk += 0.5 * TWO_PI;
        }
        r.phase1_expect = (pk / TWO_PI - floor(pk / TWO_PI)) * 65536.0;
    }
    return r;
}

static double phase_diff_deg(qfoc_angle_t a, double b_counts)
{
    return fabs(wrap_pi(TWO_PI * ((double)a - b_counts) / 65536.0)) * 360.0 / TWO_PI;
}

static void run_pair(const char *name, loop_cfg_t cfg, double min_reduction)
{
    loop_res_t off;
    loop_res_t on;
    double red_p2p;
    double red_rms;
    cfg.compensate = 0;
    off = run_loop(&cfg);
    cfg.compensate = 1;
    on = run_loop(&cfg);
    red_p2p = 1.0 - (on.p2p / off.p2p);
    red_rms = 1.0 - (on.rms / off.rms);
    print_message("%s: ripple p2p %.1f -> %.1f rpm (-%.1f %%), rms %.2f -> %.2f rpm (-%.1f %%), "
                  "mean %.1f rpm, i_max clamp %.1f %% of steps; learned 1x %.2f A at %.1f deg "
                  "(expected %.1f deg)\n",
                  name, off.p2p, on.p2p, 100.0 * red_p2p, off.rms, on.rms, 100.0 * red_rms,
                  on.mean_rpm, 100.0 * (double)on.clipped / (cfg.seconds / T_PWM),
                  on.iff_amp1, (double)on.phase1 * 360.0 / 65536.0,
                  on.phase1_expect * 360.0 / 65536.0);
    if (min_reduction < 0.0) {
        return;
    }
    assert_true(red_p2p >= min_reduction);
    assert_true(red_rms >= min_reduction);
    assert_true(fabs(on.mean_rpm - cfg.rpm) < 5.0);
    if (fabs(cfg.k1) > 0.0) {
        assert_true(phase_diff_deg(on.phase1, on.phase1_expect) < 10.0);
    }
}

/* REQ-TC-010: 1x pulsation 4.5 N m x (1 + 0.5 sin(theta_m + phi)) at 1500 rpm,
   arbitrary mechanical zero.
   Methods: 1b an ideal current loop and a 1 ms current lag; 1a the speed ripple of a 1x load
   pulsation at 1500 rpm reduced as REQ-TC-010 states, against the same run without
   compensation */
static void test_tc_closed_loop_1x(void **state)
{
    loop_cfg_t c = { 1500.0, 4.5, 0.5, 0.7, 0.0, 0.0, 2.0, 0.0, 1, 20.0, 0, 0 };
    (void)state;
    run_pair("1x, 1500 rpm, ideal current loop", c, 0.70);
    c.tau_i = 1e-3;
    run_pair("1x, 1500 rpm, current lag 1 ms", c, 0.70);
}

/* REQ-TC-010: 2x pulsation.
   Methods: 1a the speed ripple of a 2x load pulsation at 1500 rpm with a 1 ms current lag
   reduced as REQ-TC-010 states, against the same run without compensation */
static void test_tc_closed_loop_2x(void **state)
{
    loop_cfg_t c = { 1500.0, 4.5, 0.0, 0.0, 0.5, -1.2, 4.0, 1e-3, 1, 20.0, 0, 0 };
    (void)state;
    run_pair("2x, 1500 rpm, current lag 1 ms", c, 0.70);
}

/* REQ-TC-010: mixed 1x + 2x pulsation, random phases and mechanical zeros, other
   speeds in the window, reverse rotation.
   Methods: 1b mixed 1x + 2x pulsations with random phases and mechanical zeros, the speeds
   1000, 1500 and 3000 rpm in the window, reverse rotation */
static void test_tc_closed_loop_mixed(void **state)
{
    uint32_t i;
    (void)state;
    lcg_state = 5150u;
    for (i = 0u; i < 3u; i++) {
        loop_cfg_t c = { 1500.0, 4.5, 0.35, 0.0, 0.25, 0.0, 0.0, 1e-3, 1, 20.0, 0, 0 };
        char name[96];
        c.phi1 = TWO_PI * (double)rand_range(0, 65535) / 65536.0;
        c.phi2 = TWO_PI * (double)rand_range(0, 65535) / 65536.0;
        c.theta0 = TWO_PI * (double)rand_range(0, 65535) / 65536.0;
        (void)snprintf(name, sizeof(name), "1x+2x, 1500 rpm, phi1 %.0f phi2 %.0f deg, zero %.0f deg",
                       c.phi1 * 360.0 / TWO_PI, c.phi2 * 360.0 / TWO_PI, c.theta0 * 360.0 / TWO_PI);
        run_pair(name, c, 0.70);
    }
    {
        loop_cfg_t c = { 1000.0, 3.0, 0.35, 1.0, 0.25, 2.0, 5.0, 1e-3, 1, 20.0, 0, 0 };
        run_pair("1x+2x, 1000 rpm", c, 0.70);
    }
    {
        loop_cfg_t c = { 3000.0, 4.5, 0.35, -1.0, 0.25, 0.5, 1.0, 1e-3, 1, 20.0, 0, 0 };
        run_pair("1x+2x, 3000 rpm", c, 0.70);
    }
    {
        loop_cfg_t c = { -1500.0, -4.5, 0.35, 0.3, 0.25, 1.1, 3.0, 1e-3, 1, 20.0, 0, 0 };
        run_pair("1x+2x, reverse -1500 rpm", c, 0.70);
    }
}

/* REQ-TC-010: with the drive's clamp of the i_q reference to +-i_max (20 A).
   (a) a load whose peak fits the current limit: 3.5 N m x (1 + 0.5 sin) needs at
   most 17.9 A; (b) the 4.5 N m x (1 + 0.5 sin) load needs 23.1 A at its peak: not
   feasible.  With the drive holding the learning in a tick after a clamped fast step
   (the integration rule of REQ-TC-005) the speed stays up and the ripple falls;
   without that hold the coefficients wind up to amp_max and the speed collapses,
   which is why the rule exists (measured and printed).
   Methods: 1c a load whose peak current fits the clamp (17.9 A of 20 A) and one beyond it
   (23.1 A); 1d wind-up of the coefficients into amp_max without the hold after a clamped
   step (the speed collapses) */
static void test_tc_closed_loop_current_limit(void **state)
{
    loop_cfg_t c = { 1500.0, 3.5, 0.5, 0.7, 0.0, 0.0, 2.0, 1e-3, 1, 20.0, 1, 0 };
    loop_res_t r;
    loop_res_t r_off;
    (void)state;
    run_pair("1x, 1500 rpm, 3.5 N m, i_max clamp", c, 0.70);
    c.t_mean = 4.5;
    c.hold = 1;
    run_pair("1x, 1500 rpm, 4.5 N m (peak 23 A > i_max 20 A), i_max clamp, learning held when clamped",
             c, -1.0);
    c.compensate = 0;
    r_off = run_loop(&c);
    c.compensate = 1;
    r = run_loop(&c);
    /* not feasible in full: the mean speed holds, the ripple falls by more than half */
    assert_true(fabs(r.mean_rpm - 1500.0) < 75.0);
    assert_true(r.p2p < (0.5 * r_off.p2p));
    assert_true(r.rms < (0.5 * r_off.rms));
    c.hold = 0;
    r = run_loop(&c);
    print_message("  same without the hold: mean speed %.1f rpm, ripple p2p %.1f rpm, learned 1x "
                  "%.2f A (windup)\n", r.mean_rpm, r.p2p, r.iff_amp1);
    assert_true(r.mean_rpm < 1350.0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_tc_mech_init),
        cmocka_unit_test(test_tc_mech_exhaustive),
        cmocka_unit_test(test_tc_mech_random),
        cmocka_unit_test(test_tc_mech_half_turn),
        cmocka_unit_test(test_tc_params_init),
        cmocka_unit_test(test_tc_output_vs_reference),
        cmocka_unit_test(test_tc_output_window),
        cmocka_unit_test(test_tc_learn_vs_reference),
        cmocka_unit_test(test_tc_learn_corners),
        cmocka_unit_test(test_tc_phase1),
        cmocka_unit_test(test_tc_closed_loop_1x),
        cmocka_unit_test(test_tc_closed_loop_2x),
        cmocka_unit_test(test_tc_closed_loop_mixed),
        cmocka_unit_test(test_tc_closed_loop_current_limit),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
