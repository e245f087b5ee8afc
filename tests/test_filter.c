/*
 * test_filter.c -- unit tests of the first-order filters (include/qfoc/filter.h).
 *
 * References (double precision, values in Q15 LSB):
 *  - low-pass (2-34): y(k+1) = a u(k) + (1 - a) y(k), a = alpha / 32768;
 *  - leaky integrator (2-17): y(k+1) = y(k) + g x(k) - l y(k),
 *    g = gain / 32768 / 2^gain_shift, l = leak / 32768, saturated to the symmetric
 *    Q31 range; discrete transfer function H(z) = g / (z - (1 - l)).
 * Error bounds stated in filter.h: low-pass state within 0.25 Q15 LSB of the
 * real-valued recursion, output within 0.75 LSB; leaky-integrator state within
 * min(k, 1/l) Q31 LSB of the real-valued recursion after k samples.
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>
#include <math.h>
#include <stdlib.h>

#include "qfoc/filter.h"
#define TEST_SEED 777u
#include "test_util.h"

#define Q31_PER_Q15 65536.0
#define Q31_SYM_MAX_Q15 (2147483647.0 / 65536.0)

static const double pi_d = 3.14159265358979323846;


static double clampd(double x, double lim)
{
    return (x > lim) ? lim : ((x < -lim) ? -lim : x);
}

/* ------------------------------------------------------------------------ */
/* low-pass                                                                  */
/* ------------------------------------------------------------------------ */

/* REQ-FLT-002, REQ-FLT-003: random coefficients and inputs vs the 2-34 recursion.
   Methods: 1b 200 random coefficients in three classes (very slow 1 .. 16, almost
   pass-through 32000 .. 32767, any) with 2000 random inputs each; 1c the input -32768 every
   50th sample; 1n recursion 2-34 in double precision */
static void test_lpf_random_vs_reference(void **state)
{
    double max_state_err = 0.0;
    double max_out_err = 0.0;
    uint32_t set;
    (void)state;
    lcg_state = 777u;
    for (set = 0u; set < 200u; set++) {
        qfoc_lpf_t f;
        int16_t alpha;
        double a;
        double y = 0.0;
        qfoc_q15_t prev_out = 0;
        uint32_t k;
        int32_t mode = rand_range(0, 3);
        if (mode == 0) {
            alpha = (int16_t)rand_range(1, 16);        /* very slow filters */
        } else if (mode == 1) {
            alpha = (int16_t)rand_range(32000, 32767); /* almost pass-through */
        } else {
            alpha = (int16_t)rand_range(1, 32767);
        }
        a = (double)alpha / 32768.0;
        assert_int_equal(qfoc_lpf_init(&f, alpha), QFOC_FILTER_OK);
        for (k = 0u; k < 2000u; k++) {
            int16_t u = rand_i16();
            qfoc_q15_t out;
            double us;
            if ((k % 50u) == 0u) {
                u = (int16_t)-32768;
            }
            us = sat15d((double)u);
            y = (a * us) + ((1.0 - a) * y);
            out = qfoc_lpf_step(&f, u);
            /* REQ-FLT-003: no overshoot: between the input and the previous output */
            assert_true((double)out >= fmin(us, (double)prev_out));
            assert_true((double)out <= fmax(us, (double)prev_out));
            prev_out = out;
            max_state_err = fmax(max_state_err, fabs(((double)f.state / Q31_PER_Q15) - y));
            max_out_err = fmax(max_out_err, fabs((double)out - y));
            assert_true(qfoc_lpf_is_valid(&f));
        }
    }
    print_message("LPF vs double 2-34: max state error = %.6f LSB (bound 0.25), "
                  "max output error = %.6f LSB (bound 0.75)\n", max_state_err, max_out_err);
    assert_true(max_state_err <= 0.25);
    assert_true(max_out_err <= 0.75);
}

/* REQ-FLT-002: step response, 63 % after about 1 / alpha samples.
   Methods: 1b five coefficients from 33 to 16384 (slow to fast); 1n the exact recursion's
   step response, n = ceil(ln(0.368) / ln(1 - a)), and 1 / alpha */
static void test_lpf_time_constant(void **state)
{
    static const int16_t alphas[5] = { 33, 328, 1029, 3277, 16384 };
    uint32_t i;
    (void)state;
    for (i = 0u; i < 5u; i++) {
        qfoc_lpf_t f;
        double a = (double)alphas[i] / 32768.0;
        /* first sample n with 1 - (1 - a)^n >= 0.632: n = ceil(ln(0.368) / ln(1 - a)) */
        double n_exact = ceil(log(1.0 - 0.632) / log(1.0 - a));
        uint32_t n = 0u;
        qfoc_q15_t out = 0;
        assert_int_equal(qfoc_lpf_init(&f, alphas[i]), QFOC_FILTER_OK);
        while (out < (qfoc_q15_t)20709) {   /* 0.632 x 32767 = 20708.7 */
            out = qfoc_lpf_step(&f, 32767);
            n++;
        }
        print_message("LPF alpha=%d: 63%% after %u samples (exact recursion %.0f, 1/alpha = %.1f)\n",
                      alphas[i], (unsigned)n, n_exact, 1.0 / a);
        assert_true(fabs((double)n - n_exact) <= 1.0);
        if (a < 0.05) {
            assert_true(fabs((double)n - (1.0 / a)) <= (0.05 / a));
        }
    }
}

/* REQ-FLT-004: DC gain exactly 1 in Q15 after settling, corners included.
   Methods: 1c the coefficients 1 and 32767 and the inputs -32768, -32767, -1, 0, 1, 32767,
   settled from either end of the range; 1a the DC gain 1 of REQ-FLT-004 */
static void test_lpf_dc_gain(void **state)
{
    static const int16_t alphas[4] = { 1, 100, 10000, 32767 };
    static const int16_t inputs[8] = { (int16_t)-32768, -32767, -12345, -1, 0, 1, 23456, 32767 };
    uint32_t i;
    uint32_t j;
    (void)state;
    for (i = 0u; i < 4u; i++) {
        for (j = 0u; j < 8u; j++) {
            qfoc_lpf_t f;
            uint32_t k;
            qfoc_q15_t out = 0;
            /* settle: (1 - a)^n x 65534 < 0.25 LSB */
            uint32_t n = (uint32_t)ceil(log(0.25 / 65534.0) / log(1.0 - ((double)alphas[i] / 32768.0))) + 2u;
            assert_int_equal(qfoc_lpf_init(&f, alphas[i]), QFOC_FILTER_OK);
            qfoc_lpf_reset(&f, (j < 4u) ? 32767 : (int16_t)-32768);
            for (k = 0u; k < n; k++) {
                out = qfoc_lpf_step(&f, inputs[j]);
            }
            assert_int_equal(out, (int32_t)sat15d((double)inputs[j]));
        }
    }
}

/* REQ-FLT-001, REQ-FLT-003: init rejects alpha <= 0, reset saturates, validity check.
   Methods: 1b valid and invalid coefficients; 1c alpha 0, -1, -32768 refused and 1, 32767
   accepted, the reset to -32768 and 32767, the state INT32_MAX and INT32_MIN; 1d invalid
   coefficients (the safe state follows the input), fields overwritten by hand; 1l a
   corrupted state and coefficient refused by the validity check */
static void test_lpf_init_reset_valid(void **state)
{
    static const int16_t bad[3] = { 0, -1, (int16_t)-32768 };
    qfoc_lpf_t f;
    uint32_t i;
    (void)state;
    for (i = 0u; i < 3u; i++) {
        f.state = 99;
        assert_int_equal(qfoc_lpf_init(&f, bad[i]), QFOC_FILTER_ERR_PARAM);
        assert_int_equal(f.alpha, 32767);
        assert_int_equal(f.state, 0);
        assert_true(qfoc_lpf_is_valid(&f));
        /* safe state: follows the input with one sample delay, within 1 LSB */
        assert_true(abs(qfoc_lpf_step(&f, 12000) - 12000) <= 1);
    }
    assert_int_equal(qfoc_lpf_init(&f, 1), QFOC_FILTER_OK);
    assert_int_equal(qfoc_lpf_init(&f, 32767), QFOC_FILTER_OK);
    qfoc_lpf_reset(&f, (int16_t)-32768);
    assert_int_equal(f.state, -32767 * 65536);
    qfoc_lpf_reset(&f, 32767);
    assert_int_equal(f.state, 32767 * 65536);
    assert_true(qfoc_lpf_is_valid(&f));
    /* validity is the symmetric Q31 range; a state beyond the Q15 range (set by
       hand) is still handled: the output saturates, the state moves towards u */
    f.state = INT32_MAX;
    assert_true(qfoc_lpf_is_valid(&f));
    assert_int_equal(qfoc_lpf_step(&f, 32767), 32767);
    /* y + round(a (u - y)) = 2147483647 + round(32767/32768 x (-65535)) = 2147418114 */
    assert_int_equal(f.state, (int32_t)(2147483647.0
                     + round((32767.0 / 32768.0) * (2147418112.0 - 2147483647.0))));
    f.state = INT32_MIN;
    assert_false(qfoc_lpf_is_valid(&f));
    f.state = 0;
    f.alpha = 0;
    assert_false(qfoc_lpf_is_valid(&f));
}

/* REQ-FLT-003: extreme jumps, no overflow, output between input and old output.
   Methods: 1c jumps from full scale to -32768 and back with alpha 32767, and one-LSB inputs
   with alpha 1, results computed by hand */
static void test_lpf_corners(void **state)
{
    qfoc_lpf_t f;
    (void)state;
    assert_int_equal(qfoc_lpf_init(&f, 32767), QFOC_FILTER_OK);
    qfoc_lpf_reset(&f, 32767);
    /* from +full scale to -32768 in one step: y = 32767 + (32767/32768)(-65534) */
    assert_int_equal(qfoc_lpf_step(&f, (int16_t)-32768), -32765);
    assert_int_equal(qfoc_lpf_step(&f, (int16_t)-32768), -32767);
    assert_int_equal(qfoc_lpf_step(&f, 32767), 32765);
    /* tiny alpha, one LSB: state moves by 2 Q31 LSB, output stays */
    assert_int_equal(qfoc_lpf_init(&f, 1), QFOC_FILTER_OK);
    assert_int_equal(qfoc_lpf_step(&f, 1), 0);
    assert_int_equal(f.state, 2);
    assert_int_equal(qfoc_lpf_step(&f, -1), 0);
    assert_int_equal(f.state, 0);
}

/* REQ-FLT-002, REQ-FLT-003: a state at the ends of the symmetric Q31 range (set by
   hand) moves towards the input by round(alpha (u - y) / 32768); its output,
   state / 65536 rounded = +-32768, saturates to +-32767.
   Methods: 1c the state at +-2147483647 with the smallest and the largest alpha (the largest
   distance 2^32 - 65537), the output saturated to +-32767, results computed by hand */
static void test_lpf_output_saturation(void **state)
{
    qfoc_lpf_t f;
    (void)state;
    assert_int_equal(qfoc_lpf_init(&f, 1), QFOC_FILTER_OK);
    f.state = 2147483647;
    assert_int_equal(qfoc_lpf_step(&f, 32767), 32767);
    /* 2147483647 + round((2147418112 - 2147483647) / 32768) = 2147483647 - 2 */
    assert_int_equal(f.state, (int32_t)(2147483647.0
                     + round((2147418112.0 - 2147483647.0) / 32768.0)));
    f.state = -2147483647;
    assert_int_equal(qfoc_lpf_step(&f, -32767), -32767);
    assert_int_equal(f.state, (int32_t)(-2147483647.0
                     + round((2147483647.0 - 2147418112.0) / 32768.0)));
    /* the largest distance, 2^32 - 65537, crossed with the largest alpha */
    assert_int_equal(qfoc_lpf_init(&f, 32767), QFOC_FILTER_OK);
    f.state = -2147483647;
    assert_int_equal(qfoc_lpf_step(&f, 32767), 32765);
    assert_int_equal(f.state, (int32_t)(-2147483647.0
                     + round((32767.0 / 32768.0) * (2147418112.0 + 2147483647.0))));
}

/* ------------------------------------------------------------------------ */
/* leaky integrator                                                          */
/* ------------------------------------------------------------------------ */

typedef struct {
    double g;
    double l;
    double y;   /* Q15 LSB */
} ref_leaky_t;

static double ref_leaky_step(ref_leaky_t *r, double x)
{
    r->y = clampd(r->y + (r->g * x) - (r->l * r->y), Q31_SYM_MAX_Q15);
    return r->y;
}

/* REQ-FLT-006, REQ-FLT-007: random coefficients and inputs vs the 2-17 recursion.
   Methods: 1b 200 random gains, shifts and leaks (every fifth a pure integrator) with 3000
   random inputs each, a third of them small; 1c the input -32768 every 101st sample and the
   saturation of the state reached; 1n recursion 2-17 in double precision, within its
   rounding bound */
static void test_leaky_random_vs_reference(void **state)
{
    double max_rel = 0.0;   /* error / bound */
    double max_err_q31 = 0.0;
    uint32_t n_sat = 0u;
    uint32_t set;
    (void)state;
    lcg_state = 4242u;
    for (set = 0u; set < 200u; set++) {
        qfoc_leaky_int_t f;
        ref_leaky_t ref;
        int16_t gain = (int16_t)rand_range(0, 32767);
        uint8_t sh = (uint8_t)rand_range(0, 15);
        int16_t leak = (int16_t)(((set % 5u) == 0u) ? 0 : rand_range(0, 32767));
        uint32_t k;
        assert_int_equal(qfoc_leaky_init(&f, gain, sh, leak), QFOC_FILTER_OK);
        ref.g = (double)gain / 32768.0 / ldexp(1.0, sh);
        ref.l = (double)leak / 32768.0;
        ref.y = 0.0;
        for (k = 1u; k <= 3000u; k++) {
            int16_t x = rand_i16();
            qfoc_q15_t out;
            double err_q31;
            double bound;
            if ((k % 3u) == 0u) {
                x = (int16_t)(x / 64);   /* small inputs as well */
            }
            if ((k % 101u) == 0u) {
                x = (int16_t)-32768;
            }
            (void)ref_leaky_step(&ref, (double)x);
            out = qfoc_leaky_step(&f, x);
            err_q31 = fabs((double)f.state - (ref.y * Q31_PER_Q15));
            /* per-step rounding <= 1 Q31 LSB, decaying with (1 - l): sum <= min(k, 1/l) */
            bound = (leak == 0) ? (double)k : fmin((double)k, 1.0 / ref.l);
            max_rel = fmax(max_rel, err_q31 / bound);
            max_err_q31 = fmax(max_err_q31, err_q31);
            assert_true(err_q31 <= bound + 1e-6);
            assert_true(fabs((double)out - sat15d(ref.y)) <= 0.5 + (bound / Q31_PER_Q15) + 1e-9);
            assert_true(qfoc_leaky_is_valid(&f));
            n_sat += ((f.state == 2147483647) || (f.state == -2147483647)) ? 1u : 0u;
        }
    }
    print_message("Leaky vs double 2-17: max state error = %.3f Q31 LSB (= %.6f Q15 LSB), "
                  "max error / bound = %.3f, saturated samples = %u\n",
                  max_err_q31, max_err_q31 / Q31_PER_Q15, max_rel, (unsigned)n_sat);
    assert_true(n_sat > 0u);
}

/* REQ-FLT-006: DC gain g / l (document 2-25/2-26 form).
   Methods: 1c the inputs -32768 and 32767 among five; 1a the DC gain g / l (2-25, 2-26) for
   gains 1 and 0.25 */
static void test_leaky_dc_gain(void **state)
{
    qfoc_leaky_int_t f;
    /* g = 16384 / 32768 / 2^4 = 1/32, l = 1024 / 32768 = 1/32: DC gain 1 */
    static const int16_t xs[5] = { (int16_t)-32768, -20000, 1, 5000, 32767 };
    uint32_t i;
    (void)state;
    for (i = 0u; i < 5u; i++) {
        uint32_t k;
        qfoc_q15_t out = 0;
        assert_int_equal(qfoc_leaky_init(&f, 16384, 4u, 1024), QFOC_FILTER_OK);
        for (k = 0u; k < 2000u; k++) {
            out = qfoc_leaky_step(&f, xs[i]);
        }
        assert_true(fabs((double)out - sat15d((double)xs[i])) <= 0.5);
    }
    /* DC gain 0.25: g = 1/128 (16384, shift 6), l = 1/32 */
    assert_int_equal(qfoc_leaky_init(&f, 16384, 6u, 1024), QFOC_FILTER_OK);
    for (i = 0u; i < 2000u; i++) {
        (void)qfoc_leaky_step(&f, 20000);
    }
    assert_true(fabs((double)qfoc_leaky_step(&f, 20000) - 5000.0) <= 0.5);
}

/* REQ-FLT-006: gain and phase for sines vs H(z) = g / (z - (1 - l)).
   Methods: 1b five frequencies from 5 Hz to 1 kHz, below and above the corner; 1n the
   analytic transfer function H(z) = g / (z - (1 - l)), gain within 1 % and phase within 0.5
   degrees */
static void test_leaky_sine_gain_phase(void **state)
{
    /* fs = 10 kHz, tau = 20 ms: l = 1e-4 / 0.02 = 0.005 -> 164 / 32768;
       g = 0.0025 -> 0.0025 x 32768 x 2^3 = 655.36 -> gain 655, shift 3 */
    static const double f_in[5] = { 5.0, 20.0, 50.0, 200.0, 1000.0 };
    const int16_t gain = 655;
    const uint8_t sh = 3u;
    const int16_t leak = 164;
    const double g = 655.0 / 32768.0 / 8.0;
    const double l = 164.0 / 32768.0;
    const double fs = 10000.0;
    const double amp = 30000.0;
    double max_gain_err = 0.0;
    double max_phase_err = 0.0;
    uint32_t i;
    (void)state;
    for (i = 0u; i < 5u; i++) {
        qfoc_leaky_int_t f;
        const double w = 2.0 * pi_d * f_in[i] / fs;
        /* 1 s of data after 1 s of settling (> 50 time constants), whole periods */
        const uint32_t n_settle = 10000u;
        const uint32_t n_meas = 10000u;
        double s_sin = 0.0;
        double s_cos = 0.0;
        double h_mag;
        double h_ph;
        double m_mag;
        double m_ph;
        double dph;
        uint32_t k;
        assert_int_equal(qfoc_leaky_init(&f, gain, sh, leak), QFOC_FILTER_OK);
        for (k = 0u; k < (n_settle + n_meas); k++) {
            /* y(k+1) is returned by the step with x(k) */
            int16_t x = (int16_t)lround(amp * sin(w * (double)k));
            double y = (double)qfoc_leaky_step(&f, x);
            if (k >= n_settle) {
                double t = (double)(k + 1u);
                s_sin += y * sin(w * t);
                s_cos += y * cos(w * t);
            }
        }
        /* y(k) = A M sin(w k + phi) -> s_sin = N/2 A M cos(phi), s_cos = N/2 A M sin(phi) */
        m_mag = sqrt((s_sin * s_sin) + (s_cos * s_cos)) * 2.0 / (double)n_meas / amp;
        m_ph = atan2(s_cos, s_sin);
        h_mag = g / sqrt(1.0 - (2.0 * (1.0 - l) * cos(w)) + ((1.0 - l) * (1.0 - l)));
        h_ph = -atan2(sin(w), cos(w) - (1.0 - l));
        dph = m_ph - h_ph;
        print_message("Leaky sine %6.1f Hz: |H| measured %.6f analytic %.6f (rel err %.2e), "
                      "phase measured %.3f deg analytic %.3f deg\n", f_in[i], m_mag, h_mag,
                      fabs(m_mag - h_mag) / h_mag, m_ph * 180.0 / pi_d, h_ph * 180.0 / pi_d);
        max_gain_err = fmax(max_gain_err, fabs(m_mag - h_mag) / h_mag);
        max_phase_err = fmax(max_phase_err, fabs(dph) * 180.0 / pi_d);
        assert_true(fabs(m_mag - h_mag) / h_mag < 0.01);
        assert_true(fabs(dph) * 180.0 / pi_d < 0.5);
    }
    print_message("Leaky sine: max relative gain error %.2e, max phase error %.4f deg\n",
                  max_gain_err, max_phase_err);
}

/* REQ-FLT-007, REQ-FLT-008: saturation at the symmetric Q31 limits, no overflow.
   Methods: 1c the state driven to +-2147483647 by a pure integrator, the strongest leak on a
   saturated state, the smallest step (gain 1, shift 15) that rounds to 0 and the one that
   gives 1 */
static void test_leaky_saturation(void **state)
{
    qfoc_leaky_int_t f;
    uint32_t k;
    (void)state;
    /* pure integrator (leak 0), g = 1: full scale in about one sample */
    assert_int_equal(qfoc_leaky_init(&f, 32767, 0u, 0), QFOC_FILTER_OK);
    for (k = 0u; k < 5u; k++) {
        (void)qfoc_leaky_step(&f, 32767);
    }
    assert_int_equal(f.state, 2147483647);
    assert_int_equal(qfoc_leaky_step(&f, 32767), 32767);
    for (k = 0u; k < 5u; k++) {
        (void)qfoc_leaky_step(&f, (int16_t)-32768);
    }
    assert_int_equal(f.state, -2147483647);
    assert_int_equal(qfoc_leaky_step(&f, (int16_t)-32768), -32767);
    assert_true(qfoc_leaky_is_valid(&f));
    /* saturated state with the strongest leak: decays, no overflow */
    assert_int_equal(qfoc_leaky_init(&f, 32767, 0u, 32767), QFOC_FILTER_OK);
    f.state = -2147483647;
    assert_int_equal(qfoc_leaky_step(&f, 0), -1);   /* -32767.99998 / 32768 */
    /* smallest step: x = 1, gain = 1, shift 15 -> 2 / 32768 rounds to 0 */
    assert_int_equal(qfoc_leaky_init(&f, 1, 15u, 0), QFOC_FILTER_OK);
    assert_int_equal(qfoc_leaky_step(&f, 1), 0);
    assert_int_equal(f.state, 0);
    assert_int_equal(qfoc_leaky_init(&f, 16384, 15u, 0), QFOC_FILTER_OK);
    (void)qfoc_leaky_step(&f, 1);     /* 2 x 16384 / 32768 = 1 */
    assert_int_equal(f.state, 1);
    (void)qfoc_leaky_step(&f, -1);
    assert_int_equal(f.state, 0);
}

/* REQ-FLT-005: init rejects bad coefficients (safe state), reset, validity.
   Methods: 1b valid and invalid coefficient sets; 1c gain -1, shift 16 and 255, leak -1,
   -32768 refused, the extremes 0 / 15 / 0 and 32767 / 0 / 32767 accepted, state INT32_MIN
   and INT32_MAX; 1d invalid coefficients (the safe state: output 0), fields overwritten by
   hand; 1l corrupted state, gain, shift and leak refused by the validity check */
static void test_leaky_init_reset_valid(void **state)
{
    qfoc_leaky_int_t f;
    (void)state;
    assert_int_equal(qfoc_leaky_init(&f, -1, 0u, 10), QFOC_FILTER_ERR_PARAM);
    assert_int_equal(f.gain, 0);
    assert_int_equal(f.gain_shift, 0);
    assert_int_equal(f.leak, 32767);
    assert_int_equal(f.state, 0);
    assert_true(qfoc_leaky_is_valid(&f));
    assert_int_equal(qfoc_leaky_step(&f, 32767), 0);
    assert_int_equal(qfoc_leaky_init(&f, 10, 16u, 10), QFOC_FILTER_ERR_PARAM);
    assert_int_equal(qfoc_leaky_init(&f, 10, 255u, 10), QFOC_FILTER_ERR_PARAM);
    assert_int_equal(qfoc_leaky_init(&f, 10, 0u, -1), QFOC_FILTER_ERR_PARAM);
    assert_int_equal(qfoc_leaky_init(&f, (int16_t)-32768, 0u, (int16_t)-32768), QFOC_FILTER_ERR_PARAM);
    assert_int_equal(qfoc_leaky_init(&f, 0, 15u, 0), QFOC_FILTER_OK);
    assert_int_equal(qfoc_leaky_init(&f, 32767, 0u, 32767), QFOC_FILTER_OK);
    qfoc_leaky_reset(&f, (int16_t)-32768);
    assert_int_equal(f.state, -32767 * 65536);
    qfoc_leaky_reset(&f, 1000);
    assert_int_equal(f.state, 1000 * 65536);
    assert_true(qfoc_leaky_is_valid(&f));
    f.state = INT32_MIN;
    assert_false(qfoc_leaky_is_valid(&f));
    f.state = INT32_MAX;
    assert_true(qfoc_leaky_is_valid(&f));
    f.gain = -1;
    assert_false(qfoc_leaky_is_valid(&f));
    f.gain = 0;
    f.gain_shift = 16u;
    assert_false(qfoc_leaky_is_valid(&f));
    f.gain_shift = 0u;
    f.leak = -1;
    assert_false(qfoc_leaky_is_valid(&f));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_lpf_random_vs_reference),
        cmocka_unit_test(test_lpf_time_constant),
        cmocka_unit_test(test_lpf_dc_gain),
        cmocka_unit_test(test_lpf_init_reset_valid),
        cmocka_unit_test(test_lpf_corners),
        cmocka_unit_test(test_lpf_output_saturation),
        cmocka_unit_test(test_leaky_random_vs_reference),
        cmocka_unit_test(test_leaky_dc_gain),
        cmocka_unit_test(test_leaky_sine_gain_phase),
        cmocka_unit_test(test_leaky_saturation),
        cmocka_unit_test(test_leaky_init_reset_valid),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
