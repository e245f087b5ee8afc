/*
 * test_fw.c -- unit tests of the field-weakening loop (include/qfoc/fw.h).
 *
 * Reference: a double-precision model of the same equations (document
 * FireldWeakeningControl): the utilisation (negative read as 0) low-passed by
 * y += alpha / 32768 (u - y) (2-34), the error e = FWK_LVL - util_f, and the
 * discrete PI of pi.h (u = kp e + I, I += ki T e, integrator and output clamped to
 * [out_min, 0]); release (enable false): reference, filter and integrator 0.
 * Error bounds, checked stage by stage:
 *  - filtered utilisation vs the double low-pass: <= 0.75 LSB (filter.h);
 *  - i_d reference vs the double PI driven by the loop's own filtered
 *    utilisation: <= 0.5 LSB (pi.h: the final rounding only);
 *  - end to end vs the all-double model: <= 0.5 + 0.75 (kp + ki k) LSB after k
 *    samples since the last release (the filter's error enters the error e; the
 *    clamps are 1-Lipschitz).
 * A closed-loop test with an algebraic voltage model of the reference motor
 * (specs/reference-motor.md, 8000 rpm, 320 V) checks that the loop settles with
 * the utilisation at the level and i_d at the analytic field-weakening current.
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>
#include <math.h>

#include "qfoc/fw.h"
#define TEST_SEED 2024u
#include "test_util.h"

/* ---- double model --------------------------------------------------------- */

typedef struct {
    double kp;     /* real gains */
    double ki;
    double lo;     /* out_min, Q15 LSB */
    double level;  /* Q15 LSB */
    double alpha;  /* real */
    double y;      /* filtered utilisation, Q15 LSB */
    double integ;  /* integrator, Q15 LSB */
} ref_fw_t;

static double clampd(double x, double lo, double hi)
{
    return (x > hi) ? hi : ((x < lo) ? lo : x);
}

static void ref_init(ref_fw_t *r, const qfoc_fw_params_t *p)
{
    r->kp = (double)p->pi.kp / 32768.0 * ldexp(1.0, p->pi.kp_shift);
    r->ki = (double)p->pi.ki / 32768.0 * ldexp(1.0, p->pi.ki_shift);
    r->lo = (double)p->pi.out_min;
    r->level = (double)p->level;
    r->alpha = (double)p->alpha / 32768.0;
    r->y = 0.0;
    r->integ = 0.0;
}

/* the PI of pi.h with limits [lo, 0], error e (Q15 LSB) */
static double ref_pi(ref_fw_t *r, double e)
{
    r->integ = clampd(r->integ + (r->ki * e), r->lo, 0.0);
    return clampd((r->kp * e) + r->integ, r->lo, 0.0);
}

/* low-pass of the (non-negative) utilisation */
static double ref_lpf(ref_fw_t *r, int16_t util)
{
    const double u = (util < 0) ? 0.0 : (double)util;
    r->y += r->alpha * (u - r->y);
    return r->y;
}

/* the loop's own filtered utilisation, Q15: state (>= 0) rounded to nearest */
static double util_f_of(const qfoc_fw_t *fw)
{
    return floor(((double)fw->util_lpf.state / 65536.0) + 0.5);
}

static qfoc_fw_params_t make_params(int16_t kp, uint8_t kps, int16_t ki, uint8_t kis,
                                    int16_t out_min, int16_t level, int16_t alpha)
{
    qfoc_fw_params_t p;
    p.pi.kp = kp;
    p.pi.kp_shift = kps;
    p.pi.ki = ki;
    p.pi.ki_shift = kis;
    p.pi.out_min = out_min;
    p.pi.out_max = 0;
    p.level = level;
    p.alpha = alpha;
    return p;
}

/* ---- tests ---------------------------------------------------------------- */

/* REQ-FW-002, REQ-FW-003, REQ-FW-004, REQ-FW-005, REQ-FW-006: random parameters and
   utilisation sequences against the double model, stage by stage and end to end
   Methods: 1b 300 random parameter sets with 400-sample random-walk utilisations each,
   enabled and (2 %) disabled samples, limited samples reached more than 1000 times; 1c the
   utilisation -32768 every 50th sample; 1n the double-precision low-pass and PI, stage by
   stage and end to end */
static void test_fw_random_vs_model(void **state)
{
    double max_filt = 0.0;
    double max_pi = 0.0;
    double max_e2e_ratio = 0.0;
    uint32_t n_limited = 0u;
    uint32_t set;
    (void)state;
    for (set = 0u; set < 300u; set++) {
        const qfoc_fw_params_t p = make_params((int16_t)rand_range(0, 32767),
                                               (uint8_t)rand_range(0, 2),
                                               (int16_t)rand_range(0, 32767),
                                               (uint8_t)rand_range(0, 1),
                                               (int16_t)rand_range(-32767, 0),
                                               (int16_t)rand_range(1, 32767),
                                               (int16_t)rand_range(1, 32767));
        qfoc_fw_t fw;
        ref_fw_t r;      /* PI driven by the loop's filtered utilisation */
        ref_fw_t full;   /* all-double model */
        int32_t u = rand_range(0, 32767);
        uint32_t since = 0u;
        uint32_t k;
        assert_int_equal(qfoc_fw_init(&fw, &p), QFOC_FW_OK);
        ref_init(&r, &p);
        ref_init(&full, &p);
        for (k = 0u; k < 400u; k++) {
            const bool enable = (rand_range(0, 99) >= 2);
            int16_t util;
            int16_t id;
            u += rand_range(-3000, 3000);
            u = (u > 32767) ? 32767 : ((u < -32768) ? -32768 : u);
            util = ((k % 50u) == 7u) ? (int16_t)-32768 : (int16_t)u;
            id = qfoc_fw_step(&fw, util, enable);
            assert_true(qfoc_fw_is_valid(&fw));
            assert_true((id >= p.pi.out_min) && (id <= 0));
            assert_int_equal(id, fw.id_ref);
            if (!enable) {
                assert_int_equal(id, 0);
                assert_int_equal(fw.pi.integ, 0);
                assert_int_equal(fw.util_lpf.state, 0);
                r.y = 0.0;
                r.integ = 0.0;
                full.y = 0.0;
                full.integ = 0.0;
                since = 0u;
            } else {
                const double y = ref_lpf(&r, util);
                const double uf = util_f_of(&fw);
                const double u_ref = ref_pi(&r, r.level - uf);
                const double u_full = ref_pi(&full, full.level - ref_lpf(&full, util));
                const double bound = 0.5 + (0.75 * (full.kp + (full.ki * (double)(since + 1u))));
                since++;
                max_filt = fmax(max_filt, fabs(uf - y));
                max_pi = fmax(max_pi, fabs((double)id - u_ref));
                max_e2e_ratio = fmax(max_e2e_ratio, fabs((double)id - u_full) / bound);
                n_limited += fw.pi.limited ? 1u : 0u;
            }
        }
    }
    print_message("fw: max |util_f - double low-pass| = %.3f LSB (bound 0.75); "
                  "max |i_d - double PI| = %.3f LSB (bound 0.5); end to end: max error / bound "
                  "= %.3f; %u limited samples\n", max_filt, max_pi, max_e2e_ratio,
                  (unsigned)n_limited);
    assert_true(max_filt <= 0.75);
    assert_true(max_pi <= 0.5);
    assert_true(max_e2e_ratio <= 1.0);
    assert_true(n_limited > 1000u);
}

/* REQ-FW-004: step responses: utilisation above the level drives i_d down to
   out_min, below the level it returns to 0 and never becomes positive
   Methods: 1b utilisations above (1.0), below (0.5) and at the level; 1c the utilisation
   exactly at the level (the reference stays 0), i_d driven to out_min; 1d wind-up on
   out_min: i_d must return to 0 as soon as the filtered utilisation falls below the level;
   1n the double-precision model */
static void test_fw_step_response(void **state)
{
    /* kp 0.1, ki T 0.00177 (58), out_min -0.375 (-12288), level 0.95 (31130),
       alpha 50 Hz at 8 kHz (1287) */
    const qfoc_fw_params_t p = make_params(3277, 0u, 58, 0u, -12288, 31130, 1287);
    qfoc_fw_t fw;
    ref_fw_t r;
    int16_t prev = 0;
    int16_t id = 0;
    uint32_t k;
    uint32_t t_min = 0u;
    uint32_t t_zero = 0u;
    double max_err = 0.0;
    (void)state;
    assert_int_equal(qfoc_fw_init(&fw, &p), QFOC_FW_OK);
    ref_init(&r, &p);
    /* utilisation 1.0: above the level, unreachable: i_d falls to out_min */
    for (k = 0u; k < 40000u; k++) {
        id = qfoc_fw_step(&fw, 32767, true);
        (void)ref_lpf(&r, 32767);
        max_err = fmax(max_err, fabs((double)id - ref_pi(&r, r.level - util_f_of(&fw))));
        if (k > 200u) {
            assert_true(id <= prev);   /* monotone once the filter has risen */
        }
        if ((t_min == 0u) && (id == p.pi.out_min)) {
            t_min = k + 1u;
        }
        prev = id;
    }
    assert_int_equal(id, -12288);
    assert_true(fw.pi.limited);
    assert_int_equal(fw.pi.integ, -12288 * 65536);
    /* utilisation 0.5: below the level: back to 0 as soon as the filtered utilisation
       falls below the level (no windup delay: the integrator sits on out_min) */
    for (k = 0u; k < 20000u; k++) {
        id = qfoc_fw_step(&fw, 16384, true);
        (void)ref_lpf(&r, 16384);
        max_err = fmax(max_err, fabs((double)id - ref_pi(&r, r.level - util_f_of(&fw))));
        assert_true(id <= 0);
        if ((t_zero == 0u) && (id == 0)) {
            t_zero = k + 1u;
        }
    }
    assert_int_equal(id, 0);
    assert_int_equal(fw.pi.integ, 0);
    print_message("fw step: out_min reached after %u samples, 0 regained after %u samples, "
                  "max |i_d - double model| = %.3f LSB\n", (unsigned)t_min, (unsigned)t_zero,
                  max_err);
    assert_true((t_min > 0u) && (t_zero > 0u));
    assert_true(max_err <= 0.5);
    /* utilisation exactly at the level: the reference stays 0 */
    qfoc_fw_reset(&fw);
    for (k = 0u; k < 20000u; k++) {
        id = qfoc_fw_step(&fw, 31130, true);
    }
    assert_int_equal(id, 0);
}

/* REQ-FW-005: release: enable false sets the reference, filter and integrator to
   0, and a re-enabled loop starts from 0
   Methods: 1a the release of REQ-FW-005: reference, filter and integrator 0 on enable false,
   a re-enabled loop starting from 0 (util_f computed by hand) */
static void test_fw_release(void **state)
{
    const qfoc_fw_params_t p = make_params(16384, 0u, 1000, 0u, -20000, 20000, 5000);
    qfoc_fw_t fw;
    uint32_t k;
    int16_t id = 0;
    (void)state;
    assert_int_equal(qfoc_fw_init(&fw, &p), QFOC_FW_OK);
    for (k = 0u; k < 500u; k++) {
        id = qfoc_fw_step(&fw, 30000, true);
    }
    assert_true(id < 0);
    assert_true(fw.util_lpf.state > 0);
    id = qfoc_fw_step(&fw, 30000, false);
    assert_int_equal(id, 0);
    assert_int_equal(fw.id_ref, 0);
    assert_int_equal(fw.pi.integ, 0);
    assert_int_equal(fw.util_lpf.state, 0);
    assert_false(fw.pi.limited);
    assert_true(qfoc_fw_is_valid(&fw));
    /* first sample after re-enable: filter from 0, integrator from 0 */
    id = qfoc_fw_step(&fw, 30000, true);
    {
        /* util_f = round(5000/32768 x 30000) = 4578; e = 20000 - 4578 > 0 -> 0 */
        const double uf = floor((5000.0 / 32768.0 * 30000.0) + 0.5);
        assert_true(fabs(util_f_of(&fw) - uf) <= 0.75);
    }
    assert_int_equal(id, 0);
    /* reset keeps the parameters */
    qfoc_fw_reset(&fw);
    assert_int_equal(fw.pi.params.out_min, -20000);
    assert_int_equal(fw.level, 20000);
    assert_int_equal(fw.util_lpf.alpha, 5000);
}

/* REQ-FW-001, REQ-FW-002: invalid parameters give the safe state (always 0)
   Methods: 1b eight invalid parameter sets, each rule broken alone, and the valid extremes;
   1c out_max 1, level 0 and -32768, alpha 0 and -32768, shift 16, out_min -32768 refused,
   out_min -32767 and 0, level and alpha 1 and 32767 accepted; 1d invalid parameters (the
   safe state: always 0 for random utilisations) */
static void test_fw_invalid_params(void **state)
{
    qfoc_fw_params_t bad[8];
    size_t k;
    (void)state;
    bad[0] = make_params(1000, 0u, 100, 0u, -1000, 1000, 1000);
    bad[0].pi.out_max = 1;                           /* positive upper limit */
    bad[1] = make_params(1000, 0u, 100, 0u, -1000, 0, 1000);      /* level 0 */
    bad[2] = make_params(1000, 0u, 100, 0u, -1000, -32768, 1000); /* level < 0 */
    bad[3] = make_params(1000, 0u, 100, 0u, -1000, 1000, 0);      /* alpha 0 */
    bad[4] = make_params(1000, 0u, 100, 0u, -1000, 1000, -32768); /* alpha < 0 */
    bad[5] = make_params(-1, 0u, 100, 0u, -1000, 1000, 1000);     /* kp < 0 */
    bad[6] = make_params(1000, 16u, 100, 0u, -1000, 1000, 1000);  /* shift > 15 */
    bad[7] = make_params(1000, 0u, 100, 0u, -32768, 1000, 1000);  /* out_min -32768 */
    for (k = 0u; k < 8u; k++) {
        qfoc_fw_t fw;
        uint32_t n;
        assert_false(qfoc_fw_params_is_valid(&bad[k]));
        assert_int_equal(qfoc_fw_init(&fw, &bad[k]), QFOC_FW_ERR_PARAM);
        assert_true(qfoc_fw_is_valid(&fw));
        assert_int_equal(fw.pi.params.kp, 0);
        assert_int_equal(fw.pi.params.ki, 0);
        assert_int_equal(fw.pi.params.out_min, 0);
        assert_int_equal(fw.pi.params.out_max, 0);
        assert_int_equal(fw.level, 32767);
        assert_int_equal(fw.util_lpf.alpha, 32767);
        for (n = 0u; n < 100u; n++) {
            assert_int_equal(qfoc_fw_step(&fw, rand_i16(), true), 0);
        }
    }
    /* limits: out_min -32767 and 0 are valid, level and alpha 1 and 32767 are valid */
    {
        qfoc_fw_params_t ok = make_params(0, 0u, 0, 0u, -32767, 1, 1);
        assert_true(qfoc_fw_params_is_valid(&ok));
        ok = make_params(32767, 15u, 32767, 15u, 0, 32767, 32767);
        assert_true(qfoc_fw_params_is_valid(&ok));
    }
}

/* REQ-FW-002: the validity check rejects each broken part
   Methods: 1b each part of the instance broken in turn; 1c the filter state 2147418112 and
   2147418113, -1, the reference at out_min and one below, 1 above 0; 1l the instance's
   fields overwritten, refused by the validity check */
static void test_fw_is_valid(void **state)
{
    const qfoc_fw_params_t p = make_params(1000, 0u, 100, 0u, -1000, 1000, 1000);
    qfoc_fw_t fw;
    qfoc_fw_t b;
    (void)state;
    assert_int_equal(qfoc_fw_init(&fw, &p), QFOC_FW_OK);
    assert_true(qfoc_fw_is_valid(&fw));
    b = fw; b.pi.params.out_max = 1; b.pi.params.out_min = 0;
    assert_false(qfoc_fw_is_valid(&b));                   /* out_max != 0 */
    b = fw; b.pi.integ = 1;
    assert_false(qfoc_fw_is_valid(&b));                   /* PI invalid */
    b = fw; b.util_lpf.alpha = 0;
    assert_false(qfoc_fw_is_valid(&b));                   /* filter invalid */
    b = fw; b.util_lpf.state = -1;
    assert_false(qfoc_fw_is_valid(&b));                   /* negative utilisation */
    b = fw; b.util_lpf.state = 2147418113;
    assert_false(qfoc_fw_is_valid(&b));                   /* above 32767 x 65536 */
    b = fw; b.util_lpf.state = 2147418112;
    assert_true(qfoc_fw_is_valid(&b));
    b = fw; b.level = 0;
    assert_false(qfoc_fw_is_valid(&b));                   /* level */
    b = fw; b.id_ref = 1;
    assert_false(qfoc_fw_is_valid(&b));                   /* positive reference */
    b = fw; b.id_ref = -1001;
    assert_false(qfoc_fw_is_valid(&b));                   /* below out_min */
    b = fw; b.id_ref = -1000;
    assert_true(qfoc_fw_is_valid(&b));
}

/* REQ-FW-003, REQ-FW-004, REQ-FW-006: corners: utilisation -32768 / 0 / 32767, level 1
   and 32767, out_min -32767, the largest gains
   Methods: 1c the utilisation -32768 (read as 0), 0 and 32767, the level 1 and 32767,
   out_min -32767 and 0, the largest gains (32767, shift 15); 1a a kp-only step computed by
   hand */
static void test_fw_corners(void **state)
{
    qfoc_fw_t fw;
    qfoc_fw_params_t p = make_params(32767, 15u, 32767, 15u, -32767, 1, 32767);
    uint32_t k;
    (void)state;
    assert_int_equal(qfoc_fw_init(&fw, &p), QFOC_FW_OK);
    /* -32768 is read as 0: util_f 0, e = 1 > 0 -> 0 */
    assert_int_equal(qfoc_fw_step(&fw, -32768, true), 0);
    assert_int_equal(fw.util_lpf.state, 0);
    /* 32767 with the largest gains: at once out_min */
    assert_int_equal(qfoc_fw_step(&fw, 32767, true), -32767);
    assert_true(fw.pi.limited);
    /* input 0: util_f = round(32767/32768 x 32767) / 32768-th ~ 1, e = 1 - 1 = 0:
       the integrator holds out_min for one more sample */
    assert_int_equal(qfoc_fw_step(&fw, 0, true), -32767);
    for (k = 0u; k < 10u; k++) {
        (void)qfoc_fw_step(&fw, 0, true);
    }
    assert_int_equal(fw.id_ref, 0);
    /* level 32767 with utilisation 32767: e = 0, nothing moves */
    p = make_params(32767, 15u, 32767, 15u, -32767, 32767, 32767);
    assert_int_equal(qfoc_fw_init(&fw, &p), QFOC_FW_OK);
    for (k = 0u; k < 10u; k++) {
        assert_int_equal(qfoc_fw_step(&fw, 32767, true), 0);
    }
    /* out_min 0: field weakening disabled by its limit */
    p = make_params(32767, 15u, 32767, 15u, 0, 1, 32767);
    assert_int_equal(qfoc_fw_init(&fw, &p), QFOC_FW_OK);
    for (k = 0u; k < 10u; k++) {
        assert_int_equal(qfoc_fw_step(&fw, 32767, true), 0);
    }
    /* small step with kp only: e = 1 - round(alpha u) exact */
    p = make_params(16384, 1u, 0, 0u, -32767, 16384, 32767);  /* kp = 1.0 */
    assert_int_equal(qfoc_fw_init(&fw, &p), QFOC_FW_OK);
    /* util_f = round(32767/32768 x 20000) = 19999, e = 16384 - 19999 = -3615 */
    assert_int_equal(qfoc_fw_step(&fw, 20000, true), -3615);
}

/* REQ-FW-006: closed loop on the reference motor (8000 rpm, 320 V, i_q 12 A) with
   the algebraic steady-state voltage model
     u_d = -w L_q i_q,  u_q = w (psi_f + L_d i_d),
     utilisation = |(u_d, u_q)| / (V_dc / sqrt 3)   (per unit, R neglected),
   i_d following its reference with one sample delay (ideal current loop): the
   loop settles with the utilisation at the level and i_d at the analytic value
   Methods: 1n the loop closed over the algebraic steady-state voltage model of the reference
   motor at 8000 rpm, 320 V, i_q 12 A, against the analytic i_d at the level */
static void test_fw_closed_loop_reference_motor(void **state)
{
    /* per unit (V_base 500 V, I_base 40 A, w_base 2 pi 500 rad/s) */
    const double w = 0.8;                 /* 8000 rpm x 3 / 60 = 400 Hz / 500 Hz */
    const double ld = 0.0026 / 0.0039789; /* L_d / L_base = 0.6535 */
    const double lq = 0.0042 / 0.0039789; /* L_q / L_base = 1.0556 */
    const double psi = 0.065 / 0.159155;  /* psi_f / psi_base = 0.4084 */
    const double vmax = (320.0 / sqrt(3.0)) / 500.0; /* V_dc / sqrt 3 = 0.3695 */
    const double iq = 12.0 / 40.0;
    const double level = 31130.0 / 32768.0;         /* 0.95 */
    const qfoc_fw_params_t p = make_params(3277, 0u, 58, 0u, -12288, 31130, 1287);
    /* analytic: |v| = level vmax -> u_q -> i_d */
    const double ud = w * lq * iq;
    const double uq_star = sqrt(((level * vmax) * (level * vmax)) - (ud * ud));
    const double id_star = ((uq_star / w) - psi) / ld;
    qfoc_fw_t fw;
    double id = 0.0;
    double util = 0.0;
    uint32_t k;
    uint32_t t_settle = 0u;
    (void)state;
    assert_int_equal(qfoc_fw_init(&fw, &p), QFOC_FW_OK);
    for (k = 0u; k < 16000u; k++) {   /* 2 s at 8 kHz */
        const double uq = w * (psi + (ld * id));
        int16_t ref;
        util = sqrt((ud * ud) + (uq * uq)) / vmax;
        ref = qfoc_fw_step(&fw, q15_of(util), true);
        id = (double)ref / 32768.0;
        if (fabs(util - level) > 0.01) {
            t_settle = k + 1u;
        }
    }
    print_message("fw closed loop (8000 rpm, 320 V, i_q 12 A): utilisation %.5f (level %.5f), "
                  "i_d %.3f A (analytic %.3f A), within 1 %% after %.1f ms\n", util, level,
                  id * 40.0, id_star * 40.0, (double)t_settle / 8.0);
    assert_true(fabs(util - level) < (4.0 / 32768.0));
    assert_true(fabs(id - id_star) < 0.002);           /* 0.08 A */
    assert_true(t_settle < 4000u);                     /* settled within 0.5 s */
    assert_true(id < 0.0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_fw_random_vs_model),
        cmocka_unit_test(test_fw_step_response),
        cmocka_unit_test(test_fw_release),
        cmocka_unit_test(test_fw_invalid_params),
        cmocka_unit_test(test_fw_is_valid),
        cmocka_unit_test(test_fw_corners),
        cmocka_unit_test(test_fw_closed_loop_reference_motor),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
