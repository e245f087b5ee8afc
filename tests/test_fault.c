/*
 * test_fault.c -- unit tests of the fault-detection primitives (include/qfoc/fault.h).
 *
 * References (double precision / independent models):
 *  - debounce: the run length k of consecutive trues counted by the test; the
 *    result must be k >= max(n, 1) and the count min(k, n) (exact, 0 error);
 *  - phase monitor: the low-pass of document 2-34, y += alpha / 32768 (|i| - y),
 *    in double on each |i_x|; the filtered magnitude (state rounded to Q15) must be
 *    within 0.75 LSB of it (filter.h: 1/4 LSB state error + 1/2 LSB rounding); the
 *    criterion max >= i_min && min < ratio / 32768 max evaluated in double on the
 *    filtered magnitudes;
 *  - thresholds: x > limit, x < limit, |x| > limit in double (exact);
 *  - fault-bit names: the header's own macro names, QFOC_FAULT_<name> -> "<name>" (made
 *    by the preprocessor from the macro names, not typed), and the rule of fault.h for
 *    every other value: 0 "none", anything but a single defined bit "unknown".
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>
#include <math.h>
#include <string.h>

#include "qfoc/fault.h"
#define TEST_SEED 777u
#include "test_util.h"

/* REQ-FAULT-001: the fault bits are the interface values, distinct, one bit each
   Methods: 1a the fault bits of REQ-FAULT-001: each the interface value, one bit each,
   distinct, their union QFOC_FAULT_ALL */
static void test_fault_bits(void **state)
{
    static const uint16_t bits[] = { QFOC_FAULT_OC, QFOC_FAULT_OV, QFOC_FAULT_UV,
                                     QFOC_FAULT_OT_IPM, QFOC_FAULT_OT_PCB, QFOC_FAULT_STALL,
                                     QFOC_FAULT_PHASE, QFOC_FAULT_OFFSET, QFOC_FAULT_LINK,
                                     QFOC_FAULT_PARAM, QFOC_FAULT_TIMING };
    uint16_t all = 0u;
    size_t k;
    (void)state;
    for (k = 0u; k < (sizeof(bits) / sizeof(bits[0])); k++) {
        assert_int_equal(bits[k], (uint16_t)(1u << k));
        assert_int_equal(all & bits[k], 0u);
        all = (uint16_t)(all | bits[k]);
    }
    assert_int_equal(all, QFOC_FAULT_ALL);
    assert_int_equal(QFOC_FAULT_ALL, 0x07FFu);
    assert_int_equal(QFOC_FAULT_TIMING, 0x0400u);
    assert_int_equal(QFOC_FAULT_OC, 0x0001u);
    assert_int_equal(QFOC_FAULT_PHASE, 0x0040u);
    assert_int_equal(QFOC_FAULT_PARAM, 0x0200u);
}

/* REQ-FAULT-002: random condition sequences against the run-length model
   Methods: 1b 2000 random condition sequences with true rates of 50 .. 97 %, run lengths 0
   .. 12 and, for a hundred, 0 .. 65535; 1n the run-length model written in the test */
static void test_debounce_run_length(void **state)
{
    uint32_t trial;
    uint32_t n_confirm = 0u;
    (void)state;
    for (trial = 0u; trial < 2000u; trial++) {
        qfoc_debounce_t d;
        const uint16_t n = (trial < 1900u) ? (uint16_t)rand_range(0, 12)
                                           : (uint16_t)rand_range(0, 65535);
        /* probability of a true sample between 50 % and 97 % */
        const uint32_t p_true = (uint32_t)rand_range(50, 97);
        uint32_t k = 0u;
        uint32_t step;
        qfoc_debounce_reset(&d);
        assert_int_equal(d.count, 0u);
        for (step = 0u; step < 60u; step++) {
            const bool c = ((uint32_t)rand_range(0, 99) < p_true);
            const uint32_t need = (n == 0u) ? 1u : (uint32_t)n;
            bool r;
            k = c ? (k + 1u) : 0u;
            r = qfoc_debounce_step(&d, c, n);
            assert_int_equal(r, (k >= need));
            assert_int_equal(d.count, (k < (uint32_t)n) ? k : (uint32_t)n);
            n_confirm += r ? 1u : 0u;
        }
    }
    print_message("debounce: %u confirmations in 120000 random steps, all matching the model\n",
                  (unsigned)n_confirm);
    assert_true(n_confirm > 1000u);
}

/* REQ-FAULT-002: corners: n = 0, 1, 10 (the drive's 10 ms), 65535, count above n
   Methods: 1c n = 0, 1, 10 (the drive's 10 ms) and 65535, the n-th call and one before it,
   the count at 65535 without wrapping; 1d a count above n (n lowered, or an instance not
   initialised) */
static void test_debounce_corners(void **state)
{
    qfoc_debounce_t d;
    uint32_t k;
    (void)state;
    /* n = 0 and n = 1: confirmed at the first true call */
    qfoc_debounce_reset(&d);
    assert_true(qfoc_debounce_step(&d, true, 0u));
    assert_int_equal(d.count, 0u);
    assert_false(qfoc_debounce_step(&d, false, 0u));
    qfoc_debounce_reset(&d);
    assert_true(qfoc_debounce_step(&d, true, 1u));
    assert_int_equal(d.count, 1u);
    assert_true(qfoc_debounce_step(&d, true, 1u));
    assert_int_equal(d.count, 1u);
    /* n = 10: the 10th consecutive true call confirms, one false restarts */
    qfoc_debounce_reset(&d);
    for (k = 1u; k <= 9u; k++) {
        assert_false(qfoc_debounce_step(&d, true, 10u));
    }
    assert_false(qfoc_debounce_step(&d, false, 10u));
    for (k = 1u; k <= 9u; k++) {
        assert_false(qfoc_debounce_step(&d, true, 10u));
    }
    assert_true(qfoc_debounce_step(&d, true, 10u));
    assert_true(qfoc_debounce_step(&d, true, 10u));
    assert_int_equal(d.count, 10u);
    /* count above n (n lowered, or uninitialised): confirmed and capped */
    d.count = 65535u;
    assert_true(qfoc_debounce_step(&d, true, 3u));
    assert_int_equal(d.count, 3u);
    d.count = 65535u;
    assert_false(qfoc_debounce_step(&d, false, 3u));
    assert_int_equal(d.count, 0u);
    /* n = 65535: the count reaches 65535 without wrapping */
    d.count = 65533u;
    assert_false(qfoc_debounce_step(&d, true, 65535u));
    assert_int_equal(d.count, 65534u);
    assert_true(qfoc_debounce_step(&d, true, 65535u));
    assert_int_equal(d.count, 65535u);
    assert_true(qfoc_debounce_step(&d, true, 65535u));
    assert_int_equal(d.count, 65535u);
}

/* ---- phase monitor ------------------------------------------------------- */

static double absq(int16_t x)
{
    return (x == (int16_t)-32768) ? 32767.0 : fabs((double)x);
}

static double out_of(const qfoc_lpf_t *f)
{
    /* state >= 0: nearest, ties up */
    return floor(((double)f->state / 65536.0) + 0.5);
}

static bool ref_criterion(const double a[3], int16_t i_min, int16_t ratio)
{
    const double hi = fmax(a[0], fmax(a[1], a[2]));
    const double lo = fmin(a[0], fmin(a[1], a[2]));
    return (hi >= (double)i_min) && (lo < (((double)ratio / 32768.0) * hi));
}

/* REQ-FAULT-007: qfoc_phase_mon_peak is the largest of the three filter states rounded to
   nearest (x / 65536, ties away from zero, as the imbalance check reads them), against a
   double-precision reference, on random valid states, the extremes and ties.
   Methods: 1b 200000 random valid filter states, equal states among them (ties between
   phases); 1c eleven corner states (0, 1, 32767, 32768 .. 2147418112: the rounding ties and
   the largest state) pairwise on two phases, rotated; 1n the largest state rounded in double
   precision */
static void test_phase_mon_peak(void **state)
{
    static const int32_t corner[] = { 0, 1, 32767, 32768, 65535, 65536, 98303, 98304,
                                      2147385344, 2147418111, 2147418112 };
    const size_t nc = sizeof corner / sizeof corner[0];
    qfoc_phase_mon_t m;
    uint32_t k;
    size_t a;
    size_t b;
    (void)state;
    assert_int_equal(qfoc_phase_mon_init(&m, 129), QFOC_FAULT_OK);
    for (k = 0u; k < 200000u; k++) {
        double hi = 0.0;
        size_t x;
        for (x = 0u; x < 3u; x++) {
            const int32_t v = ((k % 7u) == 0u) ? corner[rand_range(0, (int32_t)nc - 1)]
                                               : rand_range(0, 2147418112);
            m.abs_lpf[x].state = ((k % 11u) == 0u) ? m.abs_lpf[0].state : v;
            hi = fmax(hi, floor((double)m.abs_lpf[x].state / 65536.0 + 0.5));
        }
        assert_true(qfoc_phase_mon_is_valid(&m));
        assert_int_equal(qfoc_phase_mon_peak(&m), (int32_t)hi);
    }
    /* every pair of corners on u and v, w at 0, and the same rotated */
    for (a = 0u; a < nc; a++) {
        for (b = 0u; b < nc; b++) {
            const double ra = floor((double)corner[a] / 65536.0 + 0.5);
            const double rb = floor((double)corner[b] / 65536.0 + 0.5);
            m.abs_lpf[0].state = corner[a];
            m.abs_lpf[1].state = corner[b];
            m.abs_lpf[2].state = 0;
            assert_int_equal(qfoc_phase_mon_peak(&m), (int32_t)fmax(ra, rb));
            m.abs_lpf[0].state = 0;
            m.abs_lpf[1].state = corner[a];
            m.abs_lpf[2].state = corner[b];
            assert_int_equal(qfoc_phase_mon_peak(&m), (int32_t)fmax(ra, rb));
        }
    }
}

/* REQ-FAULT-003, REQ-FAULT-005: random currents against the double low-pass, and
   the criterion on random thresholds
   Methods: 1b 40 coefficients (1, 32767 and random) with 2000 random samples each, phase v
   often small to reach the imbalance, random thresholds and ratios; 1c the current -32768
   every fifth sample, negative ratios every 97th; 1n the double-precision low-pass of |i|
   and the criterion written from the requirement */
static void test_phase_mon_random_vs_reference(void **state)
{
    qfoc_phase_mon_t m;
    double y[3] = { 0.0, 0.0, 0.0 };
    double max_err = 0.0;
    uint32_t n_true = 0u;
    uint32_t seq;
    uint32_t k;
    (void)state;
    for (seq = 0u; seq < 40u; seq++) {
        const int16_t alpha = (seq < 4u) ? ((seq < 2u) ? (int16_t)1 : (int16_t)32767)
                                         : (int16_t)rand_range(1, 32767);
        assert_int_equal(qfoc_phase_mon_init(&m, alpha), QFOC_FAULT_OK);
        y[0] = 0.0;
        y[1] = 0.0;
        y[2] = 0.0;
        for (k = 0u; k < 2000u; k++) {
            qfoc_abc_t i;
            double a[3];
            size_t x;
            const int16_t i_min = (int16_t)rand_range(-100, 20000);
            const int16_t ratio = ((k % 97u) == 0u) ? rand_i16() : (int16_t)rand_range(0, 32767);
            i.u = rand_i16();
            /* phase v often small, to exercise the imbalance */
            i.v = ((k & 1u) != 0u) ? rand_i16() : (int16_t)rand_range(-500, 500);
            i.w = ((k % 5u) == 0u) ? (int16_t)-32768 : rand_i16();
            qfoc_phase_mon_update(&m, &i);
            y[0] += ((double)alpha / 32768.0) * (absq(i.u) - y[0]);
            y[1] += ((double)alpha / 32768.0) * (absq(i.v) - y[1]);
            y[2] += ((double)alpha / 32768.0) * (absq(i.w) - y[2]);
            assert_true(qfoc_phase_mon_is_valid(&m));
            for (x = 0u; x < 3u; x++) {
                a[x] = out_of(&m.abs_lpf[x]);
                max_err = fmax(max_err, fabs(a[x] - y[x]));
            }
            {
                const bool r = qfoc_phase_mon_imbalanced(&m, i_min, ratio);
                assert_int_equal(r, ref_criterion(a, i_min, ratio));
                n_true += r ? 1u : 0u;
            }
        }
    }
    print_message("phase monitor: max |filtered |i| - double low-pass| = %.3f LSB "
                  "(bound 0.75), %u of 80000 samples imbalanced\n", max_err, (unsigned)n_true);
    assert_true(max_err <= 0.75);
    assert_true(n_true > 1000u);
}

/* REQ-FAULT-003: one phase per call, every index (3 and above select w), against the
   double low-pass of the selected phase; the two others unchanged
   Methods: 1b 20 coefficients with 3000 random samples each, every phase index 0 .. 255 (3
   and above select w); 1c the current -32768 every seventh sample; 1n the double-precision
   low-pass of the selected phase, the two others unchanged */
static void test_phase_mon_update_one_vs_reference(void **state)
{
    qfoc_phase_mon_t m;
    double y[3] = { 0.0, 0.0, 0.0 };
    double max_err = 0.0;
    uint32_t seq;
    uint32_t k;
    (void)state;
    for (seq = 0u; seq < 20u; seq++) {
        const int16_t alpha = (seq == 0u) ? (int16_t)32767 : (int16_t)rand_range(1, 32767);
        assert_int_equal(qfoc_phase_mon_init(&m, alpha), QFOC_FAULT_OK);
        y[0] = 0.0;
        y[1] = 0.0;
        y[2] = 0.0;
        for (k = 0u; k < 3000u; k++) {
            qfoc_abc_t i;
            const uint8_t idx = ((k % 11u) == 0u) ? (uint8_t)rand_range(0, 255) : (uint8_t)(k % 3u);
            const size_t sel = (idx >= 2u) ? 2u : (size_t)idx;
            int32_t before[3];
            size_t x;
            i.u = rand_i16();
            i.v = ((k % 7u) == 0u) ? (int16_t)-32768 : rand_i16();
            i.w = rand_i16();
            for (x = 0u; x < 3u; x++) {
                before[x] = m.abs_lpf[x].state;
            }
            qfoc_phase_mon_update_one(&m, &i, idx);
            {
                const double in = (sel == 0u) ? absq(i.u) : ((sel == 1u) ? absq(i.v) : absq(i.w));
                y[sel] += ((double)alpha / 32768.0) * (in - y[sel]);
            }
            assert_true(qfoc_phase_mon_is_valid(&m));
            for (x = 0u; x < 3u; x++) {
                if (x == sel) {
                    max_err = fmax(max_err, fabs(out_of(&m.abs_lpf[x]) - y[x]));
                } else {
                    assert_int_equal(m.abs_lpf[x].state, before[x]);
                }
            }
        }
    }
    print_message("phase monitor, one phase per call: max |filtered |i| - double low-pass| = "
                  "%.3f LSB (bound 0.75)\n", max_err);
    assert_true(max_err <= 0.75);
}

/* REQ-FAULT-003: the coefficient for every third period, for every int16_t alpha,
   against 1 - (1 - alpha / 32768)^3 in double (alpha below 1 taken as 1)
   Methods: 1b every int16 coefficient (the domain enumerated); 1c alpha below 1 taken as 1
   and the result saturated at 32767; 1n 1 - (1 - alpha / 32768)^3 in double precision */
static void test_phase_mon_alpha3(void **state)
{
    double max_err = 0.0;
    int32_t a;
    (void)state;
    for (a = -32768; a <= 32767; a++) {
        const double al = (a < 1) ? 1.0 : (double)a;
        const double b = 1.0 - (al / 32768.0);
        double ref = (1.0 - (b * b * b)) * 32768.0;
        const qfoc_q15_t r = qfoc_phase_mon_alpha3((qfoc_q15_t)a);
        if (ref > 32767.0) {
            ref = 32767.0;
        }
        assert_true(r >= 1);
        assert_true((a < 1) || (r >= a));
        max_err = fmax(max_err, fabs((double)r - ref));
    }
    print_message("phase monitor alpha3: max |result - 1 - (1 - alpha)^3| = %.3f LSB "
                  "(bound 1.5)\n", max_err);
    assert_true(max_err <= 1.5);
}

/* REQ-FAULT-003, REQ-FAULT-004, REQ-FAULT-005: the drive's use, one phase per period
   with the coefficient alpha3: a lost phase is reported, balanced currents never, and
   each filtered magnitude follows the all-phases monitor at alpha (time constant kept)
   Methods: 1d a phase lost after 8000 periods of balanced currents; 1l the lost phase
   injected into the sampled currents, reported within 100 ms; 1n one phase per period with
   alpha3 against the all-phases monitor at alpha */
static void test_phase_mon_round_robin(void **state)
{
    const double two_pi = 6.28318530717958647692;
    const double amp = 0.5 * 32768.0;
    const double w = two_pi * 300.0 / 8000.0;
    const int16_t alpha = 515;                  /* 20 Hz at 8 kHz */
    const int16_t i_min = 3277;
    const int16_t ratio = 8192;
    qfoc_phase_mon_t full;
    qfoc_phase_mon_t one;
    double max_diff = 0.0;
    uint32_t k;
    uint32_t first = 0u;
    (void)state;
    assert_int_equal(qfoc_phase_mon_init(&full, alpha), QFOC_FAULT_OK);
    assert_int_equal(qfoc_phase_mon_init(&one, qfoc_phase_mon_alpha3(alpha)), QFOC_FAULT_OK);
    for (k = 0u; k < 16000u; k++) {
        const bool lost = (k >= 8000u);
        const double th = w * (double)k;
        qfoc_abc_t i;
        size_t x;
        i.u = (int16_t)lround(amp * cos(th));
        i.v = lost ? (int16_t)0 : (int16_t)lround(amp * cos(th - (two_pi / 3.0)));
        i.w = (int16_t)(-(int32_t)i.u - (int32_t)i.v);
        qfoc_phase_mon_update(&full, &i);
        qfoc_phase_mon_update_one(&one, &i, (uint8_t)(k % 3u));
        if ((k >= 2000u) && (k < 8000u)) {
            for (x = 0u; x < 3u; x++) {
                max_diff = fmax(max_diff, fabs(out_of(&one.abs_lpf[x]) - out_of(&full.abs_lpf[x])));
            }
            assert_false(qfoc_phase_mon_imbalanced(&one, i_min, ratio));
        }
        if (lost && (first == 0u) && qfoc_phase_mon_imbalanced(&one, i_min, ratio)) {
            first = k;
        }
    }
    /* settled magnitude 2 A / pi = 10430 LSB; ripple at twice 300 Hz differs */
    print_message("phase monitor, one phase per period: max |magnitude - all-phases monitor| = "
                  "%.1f LSB of 10430, phase loss reported after %u periods\n", max_diff,
                  (unsigned)(first - 8000u));
    assert_true(max_diff <= 0.02 * 10430.0);
    assert_true(first > 8000u);
    assert_true((first - 8000u) < 800u);        /* within 100 ms at 8 kHz */
}

/* REQ-FAULT-003, REQ-FAULT-004, REQ-FAULT-005: balanced sinusoidal currents are never
   reported, a lost phase is reported once the filter has settled
   Methods: 1c the thresholds i_min 32767 and 0 and the ratios 0 and -32768 (never reported);
   1d a lost phase (i_w = 0, i_u = -i_v) after balanced currents; 1l the lost phase injected
   into the sampled currents, reported within 100 ms; 1a the mean |i| of a sine, 2 A / pi */
static void test_phase_mon_phase_loss(void **state)
{
    const double two_pi = 6.28318530717958647692;
    const double amp = 0.5 * 32768.0;     /* 20 A of I_base 40 A */
    const double w = two_pi * 300.0 / 8000.0; /* 300 Hz electrical at 8 kHz */
    /* f_c = 20 Hz: 2 pi 20 / 8000 x 32768 = 514.7 -> 515 */
    const int16_t alpha = 515;
    const int16_t i_min = 3277;   /* 4 A */
    const int16_t ratio = 8192;   /* 0.25 */
    qfoc_phase_mon_t m;
    uint32_t k;
    uint32_t first = 0u;
    (void)state;
    assert_int_equal(qfoc_phase_mon_init(&m, alpha), QFOC_FAULT_OK);
    assert_false(qfoc_phase_mon_imbalanced(&m, i_min, ratio)); /* at rest: never */
    assert_false(qfoc_phase_mon_imbalanced(&m, 0, ratio));
    for (k = 0u; k < 8000u; k++) {
        const double th = w * (double)k;
        qfoc_abc_t i;
        i.u = q15_of(amp * sin(th) / 32768.0);
        i.v = q15_of(amp * sin(th - (two_pi / 3.0)) / 32768.0);
        i.w = q15_of(amp * sin(th + (two_pi / 3.0)) / 32768.0);
        qfoc_phase_mon_update(&m, &i);
        assert_false(qfoc_phase_mon_imbalanced(&m, i_min, ratio));
    }
    /* mean |i| of a sine is 2 A / pi */
    assert_true(fabs(out_of(&m.abs_lpf[0]) - (2.0 * amp / 3.14159265358979)) < 300.0);
    /* phase w lost: i_w = 0, i_u = -i_v */
    for (k = 0u; k < 8000u; k++) {
        const double th = w * (double)k;
        qfoc_abc_t i;
        i.u = q15_of(0.866 * amp * sin(th) / 32768.0);
        i.v = (int16_t)(-i.u);
        i.w = 0;
        qfoc_phase_mon_update(&m, &i);
        if ((first == 0u) && qfoc_phase_mon_imbalanced(&m, i_min, ratio)) {
            first = k + 1u;
        }
    }
    print_message("phase monitor: phase loss reported %u samples (%.1f ms) after it occurred\n",
                  (unsigned)first, (double)first / 8.0);
    assert_true(first > 0u);
    assert_true(first < 800u);   /* within 100 ms with f_c = 20 Hz */
    assert_true(qfoc_phase_mon_imbalanced(&m, i_min, ratio));
    assert_false(qfoc_phase_mon_imbalanced(&m, 32767, ratio)); /* below i_min */
    assert_false(qfoc_phase_mon_imbalanced(&m, i_min, 0));     /* ratio 0 */
    assert_false(qfoc_phase_mon_imbalanced(&m, i_min, -32768)); /* negative ratio */
    qfoc_phase_mon_reset(&m);
    assert_true(qfoc_phase_mon_is_valid(&m));
    assert_int_equal(m.abs_lpf[0].state, 0);
    assert_int_equal(m.abs_lpf[1].state, 0);
    assert_int_equal(m.abs_lpf[2].state, 0);
    assert_int_equal(m.abs_lpf[0].alpha, alpha);
    assert_false(qfoc_phase_mon_imbalanced(&m, i_min, ratio));
}

/* REQ-FAULT-004: init, invalid coefficient, validity check
   Methods: 1b valid and invalid coefficients and states; 1c alpha 0, -32768 and 1, the
   states -1, 2147418112 and 2147418113, full-scale currents with -32768 settling at exactly
   32767 x 65536; 1d an invalid coefficient (the safe state); 1l filter states and
   coefficients overwritten, refused by the validity check */
static void test_phase_mon_init_valid(void **state)
{
    qfoc_phase_mon_t m;
    size_t x;
    (void)state;
    assert_int_equal(qfoc_phase_mon_init(&m, 0), QFOC_FAULT_ERR_PARAM);
    assert_true(qfoc_phase_mon_is_valid(&m));
    assert_int_equal(qfoc_phase_mon_init(&m, -32768), QFOC_FAULT_ERR_PARAM);
    for (x = 0u; x < 3u; x++) {
        assert_int_equal(m.abs_lpf[x].alpha, 32767);
        assert_int_equal(m.abs_lpf[x].state, 0);
    }
    assert_true(qfoc_phase_mon_is_valid(&m));
    assert_int_equal(qfoc_phase_mon_init(&m, 1), QFOC_FAULT_OK);
    assert_true(qfoc_phase_mon_is_valid(&m));
    for (x = 0u; x < 3u; x++) {
        qfoc_phase_mon_t b = m;
        b.abs_lpf[x].state = -1;
        assert_false(qfoc_phase_mon_is_valid(&b));
        b.abs_lpf[x].state = 2147418113;
        assert_false(qfoc_phase_mon_is_valid(&b));
        b.abs_lpf[x].state = 2147418112;
        assert_true(qfoc_phase_mon_is_valid(&b));
        b.abs_lpf[x].alpha = 0;
        assert_false(qfoc_phase_mon_is_valid(&b));
    }
    /* full-scale currents, -32768 included: the states reach exactly 32767 x 65536 */
    assert_int_equal(qfoc_phase_mon_init(&m, 32767), QFOC_FAULT_OK);
    for (x = 0u; x < 40u; x++) {
        const qfoc_abc_t i = { -32768, 32767, -32767 };
        qfoc_phase_mon_update(&m, &i);
    }
    assert_true(qfoc_phase_mon_is_valid(&m));
    assert_int_equal(m.abs_lpf[0].state, 2147418112);
    assert_false(qfoc_phase_mon_imbalanced(&m, 1, 32767));
}

/* REQ-FAULT-006: thresholds against the definitions, corners and random values
   Methods: 1b 200000 random values and limits; 1c seven corners (-32768, -32767, -1, 0, 1,
   32766, 32767) crossed, -32768 tripping the full-scale limit; 1n the comparisons in double
   precision */
static void test_fault_thresholds(void **state)
{
    static const int16_t c[] = { -32768, -32767, -1, 0, 1, 32766, 32767 };
    size_t i;
    size_t j;
    uint32_t k;
    (void)state;
    for (i = 0u; i < 7u; i++) {
        for (j = 0u; j < 7u; j++) {
            assert_int_equal(qfoc_fault_over(c[i], c[j]), ((double)c[i] > (double)c[j]));
            assert_int_equal(qfoc_fault_under(c[i], c[j]), ((double)c[i] < (double)c[j]));
            assert_int_equal(qfoc_fault_abs_over(c[i], c[j]), (fabs((double)c[i]) > (double)c[j]));
        }
    }
    for (k = 0u; k < 200000u; k++) {
        const int16_t x = rand_i16();
        const int16_t l = rand_i16();
        assert_int_equal(qfoc_fault_over(x, l), ((double)x > (double)l));
        assert_int_equal(qfoc_fault_under(x, l), ((double)x < (double)l));
        assert_int_equal(qfoc_fault_abs_over(x, l), (fabs((double)x) > (double)l));
    }
    /* -32768 (|x| = 32768) trips even the full-scale limit */
    assert_true(qfoc_fault_abs_over(-32768, 32767));
    assert_false(qfoc_fault_abs_over(-32767, 32767));
    assert_false(qfoc_fault_over(32767, 32767));
    assert_false(qfoc_fault_under(-32768, -32768));
    assert_true(qfoc_fault_abs_over(0, -1));
}

/* REQ-FAULT-008: the error-model band compare against its definition in double precision,
   dev > k' + 32768 v' / |w| (k' = max(k, 0), v' = clamp(v, 0, 65535)), on every corner and
   200000 random inputs; w = 0 never exceeds.
   Methods: 1b 200000 random inputs over the domain of dev, k, v and w; 1c every combination
   of the corners of dev and k (-32768 .. 32767), v (-100000, -1, 0, 1, 65535, 65536,
   2000000) and w (-32768, -1, 0, 1, 32767), w = 0 never exceeding, and the drive's band one
   code either side (4948, 4949); 1n the definition dev > k' + 32768 v' / |w| in double
   precision */
static void test_fault_008_band_over(void **state)
{
    static const int16_t devs[] = { (int16_t)-32768, -1, 0, 1, 100, 5000, 32767 };
    static const int16_t ks[] = { (int16_t)-32768, -5, 0, 1, 99, 4999, 32767 };
    static const int32_t vs[] = { -100000, -1, 0, 1, 280, 65535, 65536, 2000000 };
    static const int16_t ws[] = { (int16_t)-32768, -9830, -1, 0, 1, 9830, 32767 };
    size_t a, b, c, e;
    int k;
    (void)state;
    for (a = 0u; a < sizeof devs / sizeof devs[0]; a++) {
        for (b = 0u; b < sizeof ks / sizeof ks[0]; b++) {
            for (c = 0u; c < sizeof vs / sizeof vs[0]; c++) {
                for (e = 0u; e < sizeof ws / sizeof ws[0]; e++) {
                    const double kk = (ks[b] > 0) ? ks[b] : 0.0;
                    const double vv = (vs[c] < 0) ? 0.0 : ((vs[c] > 65535) ? 65535.0 : vs[c]);
                    const double aw = fabs((double)ws[e]);
                    const bool want = (aw > 0.0) && ((double)devs[a] > kk + 32768.0 * vv / aw);
                    assert_int_equal(qfoc_fault_band_over(devs[a], ks[b], vs[c], ws[e]), want);
                }
            }
        }
    }
    for (k = 0; k < 200000; k++) {
        const int16_t dev = rand_i16();
        const int16_t kq = rand_i16();
        const int32_t v = (int32_t)(lcg_next() % 80000u) - 5000;
        const int16_t w = rand_i16();
        const double kk = (kq > 0) ? kq : 0.0;
        const double vv = (v < 0) ? 0.0 : ((v > 65535) ? 65535.0 : v);
        const double aw = fabs((double)w);
        const bool want = (aw > 0.0) && ((double)dev > kk + 32768.0 * vv / aw);
        assert_int_equal(qfoc_fault_band_over(dev, kq, v, w), want);
    }
    /* the drive's use: the reference table at 3000 rpm (9830), psi_exp 13385, band 0.3 and
       4.28 V: k = 4015, v = 280: the band is 4015 + 933 */
    assert_false(qfoc_fault_band_over(4948, 4015, 280, 9830));
    assert_true(qfoc_fault_band_over(4949, 4015, 280, 9830));
}

/* Each defined fault bit with its expected name: the macro's name without QFOC_FAULT_. */
#define FAULT_NAMED(m) { QFOC_FAULT_##m, #m }
static const struct {
    uint16_t bit;
    const char *name;
} fault_names_ref[] = {
    FAULT_NAMED(OC), FAULT_NAMED(OV), FAULT_NAMED(UV), FAULT_NAMED(OT_IPM),
    FAULT_NAMED(OT_PCB), FAULT_NAMED(STALL), FAULT_NAMED(PHASE), FAULT_NAMED(OFFSET),
    FAULT_NAMED(LINK), FAULT_NAMED(PARAM), FAULT_NAMED(TIMING)
};
#define FAULT_NAMES_REF_N (sizeof(fault_names_ref) / sizeof(fault_names_ref[0]))

/* the name fault.h promises for any value: a single defined bit its entry, 0 "none",
   everything else "unknown" */
static const char *fault_name_ref(uint32_t v)
{
    const char *want = "unknown";
    size_t k;
    if (v == 0u) {
        want = "none";
    }
    for (k = 0u; k < FAULT_NAMES_REF_N; k++) {
        if (v == fault_names_ref[k].bit) {
            want = fault_names_ref[k].name;
        }
    }
    return want;
}

/* REQ-FAULT-009: every defined bit has its own name (the macro's), short, distinct from the
   others and from the texts of no fault and of an unknown value; the reference list covers
   QFOC_FAULT_ALL exactly (a bit added to fault.h without a name fails here)
   Methods: 1b every defined fault bit, against the reference list that covers QFOC_FAULT_ALL
   exactly; 1c the longest text, QFOC_FAULT_NAME_LEN_MAX long */
static void test_fault_009_name_each_bit(void **state)
{
    uint16_t covered = 0u;
    size_t k;
    size_t j;
    (void)state;
    for (k = 0u; k < FAULT_NAMES_REF_N; k++) {
        const char *got = qfoc_fault_name(fault_names_ref[k].bit);
        assert_non_null(got);
        assert_string_equal(got, fault_names_ref[k].name);
        assert_true(strlen(got) >= 2u);
        assert_true(strlen(got) <= QFOC_FAULT_NAME_LEN_MAX);
        assert_string_not_equal(got, "none");
        assert_string_not_equal(got, "unknown");
        for (j = 0u; j < k; j++) {
            assert_string_not_equal(got, qfoc_fault_name(fault_names_ref[j].bit));
        }
        /* one bit each, in order from bit 0 */
        assert_int_equal(fault_names_ref[k].bit, 1u << k);
        covered = (uint16_t)(covered | fault_names_ref[k].bit);
    }
    assert_int_equal(covered, QFOC_FAULT_ALL);
    /* spelled out, as the safety manual's fault table writes them */
    assert_string_equal(qfoc_fault_name(0x0001u), "OC");
    assert_string_equal(qfoc_fault_name(0x0008u), "OT_IPM");
    assert_string_equal(qfoc_fault_name(0x0010u), "OT_PCB");
    assert_string_equal(qfoc_fault_name(0x0400u), "TIMING");
    /* the longest text is QFOC_FAULT_NAME_LEN_MAX long */
    assert_int_equal(strlen(qfoc_fault_name(0x0800u)), QFOC_FAULT_NAME_LEN_MAX);
}

/* REQ-FAULT-009: total: every one of the 65536 values against the reference rule, with the
   corners named: 0, two bits, the union of all bits, each undefined bit, the top bit, 0xFFFF;
   the same value gives the same constant text at every call
   Methods: 1b every one of the 65536 values (the domain enumerated); 1c 0, the union of all
   bits, each undefined bit 0x0800 .. 0x8000, 0xFFFF; 1d values that are no single fault (two
   bits, undefined bits): 'unknown'; 1n the reference rule written in the test */
static void test_fault_009_name_every_value(void **state)
{
    uint32_t v;
    uint32_t n_unknown = 0u;
    uint32_t b;
    (void)state;
    for (v = 0u; v <= 0xFFFFu; v++) {
        const char *got = qfoc_fault_name((uint16_t)v);
        assert_non_null(got);
        assert_true(strlen(got) <= QFOC_FAULT_NAME_LEN_MAX);
        assert_string_equal(got, fault_name_ref(v));
        assert_ptr_equal(got, qfoc_fault_name((uint16_t)v));
        n_unknown += (strcmp(got, "unknown") == 0) ? 1u : 0u;
    }
    /* all but 0 and the 11 single bits */
    assert_int_equal(n_unknown, 65536u - 1u - FAULT_NAMES_REF_N);
    assert_string_equal(qfoc_fault_name(0u), "none");
    assert_string_equal(qfoc_fault_name((uint16_t)(QFOC_FAULT_OC | QFOC_FAULT_OV)), "unknown");
    assert_string_equal(qfoc_fault_name((uint16_t)(QFOC_FAULT_LINK | QFOC_FAULT_TIMING)), "unknown");
    assert_string_equal(qfoc_fault_name(QFOC_FAULT_ALL), "unknown");
    for (b = 11u; b < 16u; b++) {
        /* the undefined bits 0x0800 .. 0x8000, alone and with a defined bit */
        assert_string_equal(qfoc_fault_name((uint16_t)(1u << b)), "unknown");
        assert_string_equal(qfoc_fault_name((uint16_t)((1u << b) | QFOC_FAULT_OC)), "unknown");
    }
    assert_string_equal(qfoc_fault_name(0x8000u), "unknown");
    assert_string_equal(qfoc_fault_name(0xFFFFu), "unknown");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_fault_008_band_over),
        cmocka_unit_test(test_fault_bits),
        cmocka_unit_test(test_debounce_run_length),
        cmocka_unit_test(test_debounce_corners),
        cmocka_unit_test(test_phase_mon_random_vs_reference),
        cmocka_unit_test(test_phase_mon_peak),
        cmocka_unit_test(test_phase_mon_phase_loss),
        cmocka_unit_test(test_phase_mon_update_one_vs_reference),
        cmocka_unit_test(test_phase_mon_alpha3),
        cmocka_unit_test(test_phase_mon_round_robin),
        cmocka_unit_test(test_phase_mon_init_valid),
        cmocka_unit_test(test_fault_thresholds),
        cmocka_unit_test(test_fault_009_name_each_bit),
        cmocka_unit_test(test_fault_009_name_every_value),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
