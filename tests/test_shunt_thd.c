/**
 * @file test_shunt_thd.c
 * @brief The phase-current distortion of the single shunt (REQ-SCN-018): the harmonic
 *        analysis sim_harmonics() against signals of known content, the plant's sub-step
 *        recording against the plant without it, and the closed loop at 3000 rpm and the
 *        rated load on two sensors, on two sensors with the shunt's edge shifting and on the
 *        single shunt (sim/shunt_thd.h).
 *
 * Requirement: REQ-SCN-018 (specs/requirements/scenarios.md).
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <math.h>
#include <cmocka.h>

#include "shunt_thd.h"
#include "reference_params.h"
#include "reference_shunt_params.h"

static const scn_table_t tab_two = {
    "reference", &qfoc_params_reference, "specs/motors/reference.toml", ""
};
static const scn_table_t tab_shunt = {
    "reference_shunt", &qfoc_params_reference_shunt, "specs/motors/reference.toml",
    "sensing.mode=shunt"
};

/* A synthetic current: DC, a fundamental and harmonics (rms values), and one component
   at a frequency that is no harmonic of the fundamental (the PWM ripple's stand-in). */
static void synth(double *x, long n, int cycles, double dc, const double *h_rms, int n_h,
                  double ih_rms, double ih_bin)
{
    long k;
    for (k = 0; k < n; k++) {
        double v = dc;
        int h;
        for (h = 1; h < n_h; h++) {
            v += sqrt(2.0) * h_rms[h] *
                 cos(2.0 * SIM_PI * (double)(h * cycles) * (double)k / (double)n + 0.3 * h);
        }
        v += sqrt(2.0) * ih_rms * sin(2.0 * SIM_PI * ih_bin * (double)k / (double)n);
        x[k] = v;
    }
}

/* REQ-SCN-018: the DFT analysis gives the known THD, total distortion, fundamental and
   phase of a signal built from set harmonics over a whole number of periods, and refuses
   what it cannot analyse.
   Methods: 1b harmonics inside the THD's range (5, 7, 11, 40), outside it (41, 63) and a
   component between bins at a PWM-like frequency, DC; 1c the highest harmonic counted
   (h_max = 40) and the first one not (41), the fewest samples accepted and one fewer,
   cycles 0, h_max 1 and SIM_HARM_MAX + 1, a zero signal; 1n the closed-form THD
   sqrt(sum h_rms^2) / I_1 and total sqrt(dc^2 + sum of every other component's rms^2) / I_1 */
static void test_req_scn_018_harmonics(void **state)
{
    enum { CYC = 7, N = 7 * 3200 };
    static double x[N];
    double h_rms[64];
    sim_harm_t r;
    const double i1 = 10.0;
    double thd;
    double tot;
    (void)state;

    memset(h_rms, 0, sizeof h_rms);
    h_rms[1] = i1;
    h_rms[5] = 0.30;
    h_rms[7] = 0.20;
    h_rms[11] = 0.10;
    h_rms[40] = 0.05;
    h_rms[41] = 0.40;   /* above the THD's range: in the total only */
    h_rms[63] = 0.25;
    /* a component at 160.37 fundamental periods' frequency: no harmonic, in the total only */
    synth(x, N, CYC, 0.12, h_rms, 64, 0.6, 160.37 * CYC);
    thd = sqrt(0.30 * 0.30 + 0.20 * 0.20 + 0.10 * 0.10 + 0.05 * 0.05) / i1;
    tot = sqrt(0.12 * 0.12 + 0.30 * 0.30 + 0.20 * 0.20 + 0.10 * 0.10 + 0.05 * 0.05 + 0.40 * 0.40 +
               0.25 * 0.25 + 0.6 * 0.6) / i1;
    assert_int_equal(sim_harmonics(x, 1, N, CYC, 40, &r), 0);
    /* DC and the bins: exact but for the leakage of the component between bins, about its
       amplitude / (pi x the distance in bins) from each of its two images, 2 x 0.85 /
       (pi x 1100) = 5e-4 A (3.1e-4 A measured at the fundamental) */
    assert_true(fabs(r.dc - 0.12) < 5e-4);
    assert_true(fabs(r.fund_rms - i1) < 5e-4);
    assert_true(fabs(r.fund_phase - 0.3) < 1e-4);
    assert_true(fabs(r.h_rms[5] - 0.30) < 5e-4);
    assert_true(fabs(r.h_rms[41]) < 1e-12);  /* not evaluated above h_max */
    assert_true(fabs(r.thd - thd) < 3e-5);
    assert_true(fabs(r.tdd - tot) < 3e-5);
    print_message("harmonics: THD %.6f %% (%.6f %%), total %.6f %% (%.6f %%)\n", 100.0 * r.thd,
                  100.0 * thd, 100.0 * r.tdd, 100.0 * tot);

    /* no component between bins: exact to rounding, and h_max = 41 takes the 41st in */
    synth(x, N, CYC, 0.12, h_rms, 64, 0.0, 0.0);
    assert_int_equal(sim_harmonics(x, 1, N, CYC, 41, &r), 0);
    thd = sqrt(0.30 * 0.30 + 0.20 * 0.20 + 0.10 * 0.10 + 0.05 * 0.05 + 0.40 * 0.40) / i1;
    assert_true(fabs(r.fund_rms - i1) < 1e-9);
    assert_true(fabs(r.dc - 0.12) < 1e-12);
    assert_true(fabs(r.thd - thd) < 1e-9);
    assert_true(fabs(r.tdd - sqrt(tot * tot - 0.36 / (i1 * i1))) < 1e-9);

    /* a stride: the same samples interleaved with others */
    {
        static double y[2 * N];
        long k;
        for (k = 0; k < N; k++) {
            y[2 * k] = 1e3;
            y[2 * k + 1] = x[k];
        }
        assert_int_equal(sim_harmonics(&y[1], 2, N, CYC, 41, &r), 0);
        assert_true(fabs(r.thd - thd) < 1e-9);
    }

    /* what it refuses */
    assert_int_equal(sim_harmonics(x, 1, N, 0, 40, &r), -1);
    assert_int_equal(sim_harmonics(x, 1, N, CYC, 1, &r), -1);
    assert_int_equal(sim_harmonics(x, 1, N, CYC, SIM_HARM_MAX + 1, &r), -1);
    assert_int_equal(sim_harmonics(x, 1, 2L * 40 * CYC, CYC, 40, &r), -1);
    assert_int_equal(sim_harmonics(x, 1, 2L * 40 * CYC + 1, CYC, 40, &r), 0);
    memset(x, 0, sizeof x);
    assert_int_equal(sim_harmonics(x, 1, N, CYC, 40, &r), -1);
    assert_true(r.thd == 0.0 && r.fund_rms == 0.0);
}

/* REQ-SCN-018: the recording changes nothing: the plant with the single shunt's asymmetric
   compare values and samples, and with symmetric ones, runs to the same state, the same
   DC-link codes and the same period averages with and without it; it records substeps
   samples per period, the last one the plant's current at the period's end, the angle
   unwrapped across the mechanical angle's wrap; a full buffer drops, never overruns.
   Methods: 1b symmetric periods and asymmetric periods with samples; 1c a buffer one
   period short (dropped counted); 1d a recording that perturbs the integration (the
   sub-steps split at the sampling instants); 1n the plant without the recording */
static void test_req_scn_018_recording(void **state)
{
    enum { PERIODS = 2400, SUB = 20 };
    static double buf[4 * (PERIODS - 1) * SUB];
    sim_cfg_t cfg;
    sim_t a;
    sim_t b;
    sim_rec_t rec;
    qfoc_shunt_cfg_t sc;
    int run;
    long k;
    (void)state;

    memset(&cfg, 0, sizeof cfg);
    assert_int_equal(sim_motor_load("specs/motors/reference.toml", &cfg.motor), 0);
    cfg.vdc_v = 320.0;
    cfg.dead_time_s = 1e-6;
    cfg.substeps = SUB;
    cfg.noise_i_rms_a = 0.05;
    cfg.seed = 3u;
    cfg.speed_locked = true;
    cfg.locked_speed_e = 2.0 * SIM_PI * 150.0;
    scn_shunt_plant(&cfg, &qfoc_params_reference_shunt, &cfg.motor);
    sht_shunt_cfg(&qfoc_params_reference_shunt, &sc);
    for (run = 0; run < 2; run++) {
        sim_init(&a, &cfg);
        sim_init(&b, &cfg);
        assert_null(a.rec);
        rec.buf = buf;
        rec.cap = (PERIODS - 1) * SUB;
        sim_record(&b, &rec);
        for (k = 0; k < PERIODS; k++) {
            /* a voltage vector turning at 150 Hz, 0.3 of the bus: every sector and border */
            const double th = 2.0 * SIM_PI * 150.0 * (double)k * a.bases.t_s;
            const double m = 0.3;
            uint16_t cmp[3];
            int j;
            for (j = 0; j < 3; j++) {
                const double v = m * cos(th - 2.0 * SIM_PI * (double)j / 3.0);
                cmp[j] = (uint16_t)lround(0.5 * (1.0 + v) * (double)a.bases.period);
            }
            if (run == 0) {
                sim_set_compare(&a, cmp);
                sim_set_compare(&b, cmp);
            } else {
                qfoc_shunt_plan_t plan;
                qfoc_shunt_plan(&sc, cmp, &plan);
                sim_set_compare2(&a, plan.up, plan.down);
                sim_set_compare2(&b, plan.up, plan.down);
                sim_set_triggers(&a, plan.trig, plan.ok);
                sim_set_triggers(&b, plan.trig, plan.ok);
            }
            sim_step_period(&a);
            sim_step_period(&b);
            assert_true(a.id == b.id && a.iq == b.iq && a.theta_m == b.theta_m && a.w_m == b.w_m);
            assert_true(a.v_ab_avg[0] == b.v_ab_avg[0] && a.v_ab_avg[1] == b.v_ab_avg[1]);
            assert_true(a.shunt_code[0] == b.shunt_code[0] && a.shunt_code[1] == b.shunt_code[1]);
            if (k < PERIODS - 1) {
                double i_ab[2];
                const long last = 4 * ((k + 1) * SUB - 1);
                sim_i_ab(&b, i_ab);
                assert_int_equal(rec.n, (k + 1) * SUB);
                assert_true(fabs(buf[last + 1] - i_ab[0]) < 1e-12);
                assert_true(fabs(buf[last + 1] + buf[last + 2] + buf[last + 3]) < 1e-9);
            }
        }
        assert_int_equal(rec.n, (PERIODS - 1) * SUB);
        assert_int_equal(rec.dropped, SUB);
        /* the angle unwrapped: it advanced by 150 Hz x the time (the mechanical angle wrapped
           at each 1/50 s) */
        assert_true(fabs(buf[4 * (rec.n - 1)] - buf[0] -
                         2.0 * SIM_PI * 150.0 * (double)(rec.n - 1) * a.bases.t_s / SUB) < 1e-6);
        sim_record(&b, NULL);
        assert_null(b.rec);
    }
}

static void point(sht_point_t *p, const scn_table_t *tab, int mode)
{
    memset(p, 0, sizeof *p);
    p->tab = tab;
    p->mode = mode;
    sht_shunt_cfg(&qfoc_params_reference_shunt, &p->shift);
    p->rpm = 3000.0;
    p->load_nm = 4.5;
    p->noise_a = 0.0;
    p->substeps = 20;
    p->settle_s = 1.5;
    p->window_s = 0.1;
    p->h_max = 40;
}

/* REQ-SCN-018: at 3000 rpm and the rated load (no noise): with the measurement window made
   the smallest the library accepts (t_settle 0, t_sample 1: an edge moves only where two
   compare values are equal) the shifted-PWM path agrees with the two-sensor run within
   0.05 points of THD and of total distortion; with the single shunt's own window (200
   ticks) the edge shifting alone changes them by less than 0.3 points; the single shunt,
   its currents referred to the two-sensor instant (REQ-SHUNT-008), adds some THD but less
   than 1.5 points (more than 5 before), and every run holds the fundamental within 2 % of
   the two-sensor run's.
   Methods: 1b the three ways of measuring and switching (two sensors, the shift alone, the
   single shunt); 1c the smallest window the library accepts (the shift practically off);
   1d a shifted PWM that distorts the current by itself; 1n the DFT of the plant's true
   phase currents over whole electrical periods (sim_harmonics(), test_req_scn_018_harmonics) */
static void test_req_scn_018_shunt_thd(void **state)
{
    sht_point_t p;
    sht_result_t two;
    sht_result_t off;
    sht_result_t shift;
    sht_result_t sh;
    (void)state;

    point(&p, &tab_two, SHT_TWO_SENSOR);
    assert_int_equal(sht_run(&p, &two), 0);
    point(&p, &tab_two, SHT_SHIFT);
    p.shift.t_settle = 0u;
    p.shift.t_sample = 1u;
    assert_int_equal(sht_run(&p, &off), 0);
    point(&p, &tab_two, SHT_SHIFT);
    assert_int_equal(sht_run(&p, &shift), 0);
    point(&p, &tab_shunt, SHT_SHUNT);
    assert_int_equal(sht_run(&p, &sh), 0);
    assert_true(two.ok && off.ok && shift.ok && sh.ok);
    print_message("3000 rpm, 4.5 N m: THD / total %%: two sensors %.3f / %.3f, window 1 tick "
                  "%.3f / %.3f (shifted %.1f %%), shift alone %.3f / %.3f (shifted %.1f %%), "
                  "single shunt %.3f / %.3f\n",
                  100.0 * two.thd, 100.0 * two.tdd, 100.0 * off.thd, 100.0 * off.tdd,
                  100.0 * off.shifted_frac, 100.0 * shift.thd, 100.0 * shift.tdd,
                  100.0 * shift.shifted_frac, 100.0 * sh.thd, 100.0 * sh.tdd);
    assert_true(fabs(off.thd - two.thd) < 0.0005);
    assert_true(fabs(off.tdd - two.tdd) < 0.0005);
    assert_true(shift.shifted_frac > 0.05);
    assert_true(fabs(shift.thd - two.thd) < 0.003);
    assert_true(fabs(shift.tdd - two.tdd) < 0.003);
    assert_true(sh.thd > two.thd);
    assert_true(sh.thd - two.thd < 0.015);
    print_message("single shunt, phase u: 2nd .. 5th harmonic %.4f %.4f %.4f %.4f A rms\n",
                  sh.ph[0].h_rms[2], sh.ph[0].h_rms[3], sh.ph[0].h_rms[4], sh.ph[0].h_rms[5]);
    assert_true(fabs(sh.fund_rms / two.fund_rms - 1.0) < 0.02);
    assert_true(fabs(shift.fund_rms / two.fund_rms - 1.0) < 0.02);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_req_scn_018_harmonics),
        cmocka_unit_test(test_req_scn_018_recording),
        cmocka_unit_test(test_req_scn_018_shunt_thd),
    };
    return cmocka_run_group_tests_name("shunt_thd", tests, NULL, NULL);
}
