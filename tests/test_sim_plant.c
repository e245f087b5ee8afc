/**
 * @file test_sim_plant.c
 * @brief The double-precision plant (sim/) against closed-form references:
 *        steady-state phasor solution of the dq equations, the first-order
 *        current response, dead-time voltage error, mechanics, load, ADCs and
 *        the motor-file reader.  The estimator validation rests on this plant,
 *        so the plant itself is checked first.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <math.h>
#include <cmocka.h>

#include "sim.h"

#define REF_MOTOR "specs/motors/reference.toml"

static sim_motor_t g_motor;

static int setup(void **state)
{
    (void)state;
    return sim_motor_load(REF_MOTOR, &g_motor);
}

static void base_cfg(sim_cfg_t *cfg, double vdc, double td, bool locked, double we)
{
    memset(cfg, 0, sizeof *cfg);
    cfg->motor = g_motor;
    cfg->vdc_v = vdc;
    cfg->dead_time_s = td;
    cfg->speed_locked = locked;
    cfg->locked_speed_e = we;
    cfg->substeps = 20;
}

/* Compare values of an ideal sine-triangle PWM (no dead time) for a phase-to-neutral
   voltage vector (alpha, beta), with min-max injection so that it is centred. */
static void open_loop_cmp(const sim_t *s, double va, double vb, uint16_t cmp[3])
{
    const double vu = va;
    const double vv = -0.5 * va + 0.8660254037844386 * vb;
    const double vw = -0.5 * va - 0.8660254037844386 * vb;
    const double mx = fmax(vu, fmax(vv, vw));
    const double mn = fmin(vu, fmin(vv, vw));
    const double off = -0.5 * (mx + mn);
    const double p = (double)s->bases.period;
    const double v[3] = { vu + off, vv + off, vw + off };
    int k;
    for (k = 0; k < 3; k++) {
        cmp[k] = (uint16_t)lround(p * (0.5 + v[k] / s->cfg.vdc_v));
    }
}

/* Motor file: every value of the reference motor as specs/reference-motor.md states.
   Methods: 1a every value of the reference motor and its bases as specs/reference-motor.md
   states them, computed by hand */
static void test_motor_file(void **state)
{
    /* REQ-SIM-001 */
    sim_bases_t b;
    (void)state;
    assert_string_equal(g_motor.name, "qfoc reference compressor IPM");
    assert_true(g_motor.pole_pairs == 3.0);
    assert_true(g_motor.rs_ohm == 0.35);
    assert_true(g_motor.ld_h == 2.6e-3);
    assert_true(g_motor.lq_h == 4.2e-3);
    assert_true(g_motor.psi_f_wb == 0.065);
    assert_true(g_motor.j_kgm2 == 3.0e-4);
    assert_true(g_motor.b_nms == 1.0e-4);
    assert_true(g_motor.rated_speed_rpm == 6000.0);
    assert_true(g_motor.max_speed_rpm == 8000.0);
    assert_true(g_motor.rated_current_a == 20.0);
    assert_true(g_motor.vdc_nominal_v == 320.0);
    assert_true(g_motor.vdc_min_v == 250.0 && g_motor.vdc_max_v == 420.0);
    assert_true(g_motor.f_pwm_hz == 8000.0);
    sim_bases(&g_motor, &b);
    assert_true(fabs(b.w_base - 3141.5926535) < 1e-6);
    assert_true(fabs(b.psi_base - 500.0 / 3141.5926535) < 1e-9);
    assert_true(fabs(b.l_base - 12.5 / 3141.5926535) < 1e-12);
    assert_int_equal(b.period, 5000);
}

/* Methods: 1d a missing file, a value that is not a number, a file with every other key
   missing */
static void test_motor_file_rejects(void **state)
{
    /* REQ-SIM-001 */
    sim_motor_t m;
    FILE *f;
    (void)state;
    assert_int_equal(sim_motor_load("build/no-such-motor.toml", &m), -1);
    f = fopen("build/bad_motor.toml", "w");
    assert_non_null(f);
    fputs("[motor]\npole_pairs = three\n", f);
    fclose(f);
    assert_int_equal(sim_motor_load("build/bad_motor.toml", &m), -1);
    f = fopen("build/bad_motor.toml", "w");
    assert_non_null(f);
    fputs("[motor]\npole_pairs = 3\n", f); /* every other key missing */
    fclose(f);
    assert_int_equal(sim_motor_load("build/bad_motor.toml", &m), -1);
}

/*
 * Steady state: a sinusoidal voltage of constant dq components at a locked speed
 * must give the dq currents of the phasor solution
 *   [R, -w L_q; w L_d, R] [i_d; i_q] = [v_d; v_q - w psi_f].
 */
static void check_steady_state(double we, double vd, double vq)
{
    sim_cfg_t cfg;
    sim_t s;
    const sim_motor_t *m = &g_motor;
    const double a11 = m->rs_ohm;
    const double a12 = -we * m->lq_h;
    const double a21 = we * m->ld_h;
    const double a22 = m->rs_ohm;
    const double b1 = vd;
    const double b2 = vq - we * m->psi_f_wb;
    const double det = a11 * a22 - a12 * a21;
    const double id_ref = (b1 * a22 - a12 * b2) / det;
    const double iq_ref = (a11 * b2 - a21 * b1) / det;
    double id_sum = 0.0;
    double iq_sum = 0.0;
    int n = 0;
    int k;

    base_cfg(&cfg, 320.0, 0.0, true, we);
    sim_init(&s, &cfg);
    sim_set_state(&s, 0.0, we, id_ref, iq_ref);
    for (k = 0; k < 4000; k++) {
        uint16_t cmp[3];
        /* voltage for the period after next (one period of delay in the plant) */
        const double th = sim_theta_e(&s) + 1.5 * we * s.bases.t_s;
        open_loop_cmp(&s, vd * cos(th) - vq * sin(th), vd * sin(th) + vq * cos(th), cmp);
        sim_set_compare(&s, cmp);
        sim_step_period(&s);
        if (k >= 3000) {
            id_sum += s.id;
            iq_sum += s.iq;
            n++;
        }
    }
    /* the PWM average of each period is the commanded vector to within the compare
       rounding (0.5 tick = 0.032 V) and the rotation of the vector inside one period
       (sinc(w T / 2) < 0.4 % at 400 Hz): 1 % of the current magnitude */
    {
        const double mag = hypot(id_ref, iq_ref);
        assert_true(fabs(id_sum / n - id_ref) < 0.01 * mag + 0.02);
        assert_true(fabs(iq_sum / n - iq_ref) < 0.01 * mag + 0.02);
    }
}

/* Methods: 1b DC, 100 Hz and 300 Hz electrical; 1n the closed-form steady-state phasor
   solution of the voltage equations */
static void test_steady_state_phasor(void **state)
{
    /* REQ-SIM-002 */
    (void)state;
    check_steady_state(0.0, 3.5, 1.75);            /* DC: i = v / R = 10 A, 5 A */
    check_steady_state(2.0 * SIM_PI * 100.0, -20.0, 60.0);
    check_steady_state(2.0 * SIM_PI * 300.0, -120.0, 130.0);
}

/* First-order response at standstill: a d-axis voltage step gives
   i_d(t) = V/R (1 - exp(-t R / L_d)) (RK4 with the PWM average voltage).
   Methods: 1n the closed-form first-order response i_d(t) = V / R (1 - exp(-t R / L_d)) at
   standstill */
static void test_current_step_response(void **state)
{
    /* REQ-SIM-003 */
    sim_cfg_t cfg;
    sim_t s;
    const double v = 7.0;
    const double tau = g_motor.ld_h / g_motor.rs_ohm;
    int k;
    double worst = 0.0;
    (void)state;
    base_cfg(&cfg, 320.0, 0.0, true, 0.0);
    sim_init(&s, &cfg);
    {
        uint16_t cmp[3];
        open_loop_cmp(&s, v, 0.0, cmp);
        /* put the step into both the active and the pending period */
        memcpy(s.cmp_active, cmp, sizeof cmp);
        sim_set_compare(&s, cmp);
    }
    for (k = 1; k <= 800; k++) {
        double ref;
        sim_step_period(&s);
        ref = v / g_motor.rs_ohm * (1.0 - exp(-s.t / tau));
        worst = fmax(worst, fabs(s.id - ref));
    }
    /* the compare rounding makes the average voltage exact to 0.5 tick of 5000:
       0.032 V / 0.35 ohm = 0.09 A at the end value 20 A */
    assert_true(worst < 0.1);
    assert_true(fabs(s.iq) < 1e-9);
}

/* Dead time: every pole loses (i > 0) or gains (i < 0) Vdc td / T of its average.
   Methods: 1b a positive and two negative phase currents; 1n each pole's average voltage
   less or plus Vdc td / T, computed in the test */
static void test_dead_time_error(void **state)
{
    /* REQ-SIM-004 */
    sim_cfg_t cfg;
    sim_t s;
    const double td = 2.0e-6;
    const double vdc = 300.0;
    const uint16_t cmp[3] = { 3000u, 2500u, 1800u };
    double vp[3];
    double va;
    double vb;
    double vn;
    int k;
    (void)state;
    base_cfg(&cfg, vdc, td, true, 0.0);
    sim_init(&s, &cfg);
    /* i_d = 6 A at theta = 0: i_u = 6 A > 0, i_v = i_w = -3 A < 0 */
    sim_set_state(&s, 0.0, 0.0, 6.0, 0.0);
    memcpy(s.cmp_active, cmp, sizeof cmp);
    sim_set_compare(&s, cmp);
    sim_step_period(&s);
    for (k = 0; k < 3; k++) {
        vp[k] = vdc * ((double)cmp[k] / 5000.0 - 0.5);
    }
    vp[0] -= vdc * td * 8000.0;
    vp[1] += vdc * td * 8000.0;
    vp[2] += vdc * td * 8000.0;
    vn = (vp[0] + vp[1] + vp[2]) / 3.0;
    va = vp[0] - vn;
    vb = ((vp[1] - vn) - (vp[2] - vn)) / sqrt(3.0);
    assert_true(fabs(s.v_ab_avg[0] - va) < 1e-9);
    assert_true(fabs(s.v_ab_avg[1] - vb) < 1e-9);
}

/* Mechanics: J dw/dt = T_e - T_L - B w.  The reference integrates the same
   equation with the plant's period-average electromagnetic torque (so that the
   check is independent of how well the controller holds the torque); a first-order
   hold of the torque over one period (125 us, mechanical time constant J/B = 3 s)
   keeps the two within 0.1 %.
   Methods: 1n the same mechanical equation J dw/dt = T_e - T_L - B w integrated in the test
   from the plant's period torque, within 0.1 % */
static void test_mechanics(void **state)
{
    /* REQ-SIM-005 */
    sim_cfg_t cfg;
    sim_t s;
    sim_ctrl_t c;
    const double j = g_motor.j_kgm2;
    const double b = g_motor.b_nms;
    double w_ref = 0.0;
    int k;
    (void)state;
    base_cfg(&cfg, 320.0, 0.0, false, 0.0);
    cfg.load.t_mean = 0.1;
    sim_init(&s, &cfg);
    sim_ctrl_init(&c, &g_motor, 1000.0);
    sim_ctrl_torque_ref(&c, 0.4, 0.0, 320.0);
    sim_set_state(&s, 0.0, 0.0, c.id_ref, c.iq_ref);
    for (k = 0; k < 800; k++) { /* 0.1 s */
        sim_adc_t a;
        uint16_t cmp[3];
        sim_sample(&s, &a);
        sim_ctrl_step(&c, &a, sim_theta_e(&s), sim_w_e(&s), cmp);
        sim_set_compare(&s, cmp);
        sim_step_period(&s);
        w_ref += (s.torque_avg - 0.1 - b * w_ref) / j * s.bases.t_s;
    }
    /* (0.4 - 0.1) / 3e-4 x 0.1 s = 100 rad/s */
    assert_true(w_ref > 95.0 && w_ref < 105.0);
    assert_true(fabs(s.w_m - w_ref) < 0.001 * w_ref);
}

/* One period under the ideal current controller at a torque command. */
static void ctrl_period(sim_t *s, sim_ctrl_t *c)
{
    sim_adc_t a;
    uint16_t cmp[3];
    sim_sample(s, &a);
    sim_ctrl_step(c, &a, sim_theta_e(s), sim_w_e(s), cmp);
    sim_set_compare(s, cmp);
    sim_step_period(s);
}

/* Breakaway torque (static friction) t_b: at standstill the rotor does not move while
   |T_e| <= t_b, starts in the period in which T_e exceeds t_b and then follows
   J dw/dt = T_e - B w (no friction torque while it turns); braked by a torque below t_b it
   stops when that equation reaches zero speed and is held there.
   Methods: 1c a torque below the breakaway torque (held), above it (starts in the first
   period that exceeds it), a braking torque below it (stops, held); 1n J dw/dt = T_e - B w
   integrated in the test, within one period */
static void test_breakaway(void **state)
{
    /* REQ-SIM-005 */
    sim_cfg_t cfg;
    sim_t s;
    sim_ctrl_t c;
    const double j = g_motor.j_kgm2;
    const double b = g_motor.b_nms;
    const double t_b = 0.5;
    double w_ref = 0.0;
    long k;
    long k_start = -1;
    long k_stop = -1;
    long k_ref = -1;
    (void)state;
    base_cfg(&cfg, 320.0, 0.0, false, 0.0);
    cfg.load.t_break = t_b;
    sim_init(&s, &cfg);
    sim_ctrl_init(&c, &g_motor, 1000.0);
    /* 0.4 N m < t_b for 50 ms: held, not a single step of motion */
    sim_ctrl_torque_ref(&c, 0.4, 0.0, 320.0);
    sim_set_state(&s, 1.0, 0.0, c.id_ref, c.iq_ref);
    for (k = 0; k < 400; k++) {
        ctrl_period(&s, &c);
        assert_true(s.w_m == 0.0);
        assert_true(s.held);
    }
    assert_true(fabs(s.torque_avg - 0.4) < 0.01);
    assert_true(fabs(sim_theta_e(&s) - 1.0) < 1e-12);
    /* 0.8 N m > t_b: starts in the first period whose torque exceeds t_b, then
       J dw/dt = T_e - B w (the reference starts one period early: within one period's
       gain of speed, 0.8 / J x 125 us = 0.33 rad/s) */
    sim_ctrl_torque_ref(&c, 0.8, 0.0, 320.0);
    for (k = 0; k < 800; k++) { /* 0.1 s */
        const double t_prev = sim_torque(&s);
        ctrl_period(&s, &c);
        if (k_start < 0 && s.w_m != 0.0) {
            k_start = k;
            assert_true(t_prev <= t_b + 1e-9);
            assert_true(sim_torque(&s) > t_b);
            assert_false(s.held);
        }
        if (k_start >= 0) {
            w_ref += (s.torque_avg - b * w_ref) / j * s.bases.t_s;
        }
    }
    assert_true(k_start >= 0 && k_start < 16);
    /* (0.8 / 3e-4) x 0.1 s = 267 rad/s */
    assert_true(w_ref > 250.0 && w_ref < 270.0);
    assert_true(fabs(s.w_m - w_ref) < 0.35 + 0.001 * w_ref);
    /* braked by -0.4 N m (below t_b): the speed follows the same equation down to zero
       (the reference with the plant's period torque, crossing zero within one period of
       the plant), then the rotor is held for good */
    sim_ctrl_torque_ref(&c, -0.4, 0.0, 320.0);
    w_ref = s.w_m;
    for (k = 0; k < 4000; k++) { /* 0.5 s */
        ctrl_period(&s, &c);
        if (k_ref < 0) {
            w_ref += (s.torque_avg - b * w_ref) / j * s.bases.t_s;
            if (w_ref <= 0.0) {
                k_ref = k;
            }
        }
        if (k_stop < 0 && s.held) {
            k_stop = k;
            assert_true(fabs(sim_torque(&s)) <= t_b);
        }
        if (k_stop >= 0) {
            assert_true(s.w_m == 0.0);
            assert_true(s.held);
        }
    }
    print_message("breakaway: start in period %ld, stop after %.4f s (reference %.4f s)\n", k_start,
                  (double)(k_stop + 1) * s.bases.t_s, (double)(k_ref + 1) * s.bases.t_s);
    assert_true(k_stop > 1000 && k_ref > 1000);
    assert_true(k_stop - k_ref <= 1 && k_ref - k_stop <= 1);
}

/* Methods: 1a the load torque t_mean + t_1x cos(theta_m + phi_1x) + t_2x cos(2 theta_m +
   phi_2x) at two angles, computed by hand */
static void test_load_profile(void **state)
{
    /* REQ-SIM-005 */
    sim_cfg_t cfg;
    sim_t s;
    (void)state;
    base_cfg(&cfg, 320.0, 0.0, true, 0.0);
    cfg.load.t_mean = 4.0;
    cfg.load.t_1x = 1.0;
    cfg.load.phi_1x = 0.0;
    cfg.load.t_2x = 0.5;
    cfg.load.phi_2x = SIM_PI / 2.0;
    sim_init(&s, &cfg);
    s.theta_m = 0.0;
    assert_true(fabs(sim_load_torque(&s) - 4.5) < 1e-12);
    s.theta_m = SIM_PI / 2.0;
    assert_true(fabs(sim_load_torque(&s) - (4.0 + 1.0 - 0.5)) < 1e-12);
}

/* ADC: offset at mid-scale, 2048 counts = full scale, clamped, noise of the stated RMS.
   Methods: 1c currents beyond full scale (clamped to 4095 and 0); 1n the offset and scale
   computed by hand, and 20000 noisy samples against the stated 0.5 A rms */
static void test_adc(void **state)
{
    /* REQ-SIM-006 */
    sim_cfg_t cfg;
    sim_t s;
    sim_adc_t a;
    double sum = 0.0;
    double sum2 = 0.0;
    const int n = 20000;
    int k;
    (void)state;
    base_cfg(&cfg, 320.0, 0.0, true, 0.0);
    sim_init(&s, &cfg);
    sim_set_state(&s, 0.0, 0.0, 10.0, 0.0); /* i_u = 10 A, i_v = -5 A */
    sim_sample(&s, &a);
    assert_int_equal(a.iu, 2048 + 512);
    assert_int_equal(a.iv, 2048 - 256);
    assert_int_equal(a.vdc, (uint16_t)lround(320.0 / 500.0 * 4096.0));
    assert_int_equal(sim_adc_current_q15(a.iu), 8192); /* 10 A of 40 A */
    assert_int_equal(sim_adc_vdc_q15(a.vdc), 2621 * 8);
    sim_set_state(&s, 0.0, 0.0, 100.0, 0.0);
    sim_sample(&s, &a);
    assert_int_equal(a.iu, 4095);
    assert_int_equal(a.iv, 0);
    cfg.noise_i_rms_a = 0.5;
    cfg.seed = 7u;
    sim_init(&s, &cfg);
    for (k = 0; k < n; k++) {
        double x;
        sim_sample(&s, &a);
        x = ((double)a.iu - 2048.0) / 2048.0 * 40.0;
        sum += x;
        sum2 += x * x;
    }
    {
        const double mean = sum / n;
        const double rms = sqrt(sum2 / n - mean * mean);
        /* quantisation adds 40/2048/sqrt(12) = 0.0056 A rms */
        assert_true(fabs(mean) < 0.02);
        assert_true(fabs(rms - 0.5) < 0.02);
    }
}

/* ------------------------------------------------------------------ single shunt */

/* The ADC code of a DC-link current, computed in the test (2048 = 0 A, 40 A full scale). */
static uint16_t shunt_code_of(double i_a, double extra_counts)
{
    double c = floor(2048.0 + i_a * 2048.0 / 40.0 + extra_counts + 0.5);
    c = (c < 0.0) ? 0.0 : ((c > 4095.0) ? 4095.0 : c);
    return (uint16_t)c;
}

/* The DC-link current the test expects at counter value c of the up-counting half: the
   phases whose high side is on (c >= period - up[k]), no dead time. */
static double shunt_idc_ideal(uint16_t c, const uint16_t up[3], const double iph[3])
{
    double idc = 0.0;
    int k;
    for (k = 0; k < 3; k++) {
        if ((unsigned)c >= 5000u - up[k]) {
            idc += iph[k];
        }
    }
    return idc;
}

/* A plant with single-shunt sensing, the asymmetric compare values and triggers set and
   active from the second period; returns after the period that took the samples. */
static void shunt_run(sim_t *s, sim_cfg_t *cfg, const uint16_t up[3], const uint16_t down[3],
                      const uint16_t trig[2])
{
    cfg->shunt.active = true;
    sim_init(s, cfg);
    sim_set_state(s, 0.0, 0.0, -4.0, 8.0); /* i_u = -4 A, i_v = 8.93 A, i_w = -4.93 A */
    sim_set_compare2(s, up, down);
    sim_set_triggers(s, trig, true);
    sim_step_period(s);
    sim_step_period(s);
}

/* Single shunt: each sample is the sum of the currents of the phases that are high at
   its instant, the period's volt-seconds are those of the symmetric compare values.
   Methods: 1n the switching states computed in the test from the compare values, and the
   period-average voltage against the symmetric PWM of the same on-times; 1b samples just
   before and after a gate edge */
static void test_shunt_samples(void **state)
{
    /* REQ-SIM-007 */
    sim_cfg_t cfg;
    sim_t s;
    sim_t r;
    const uint16_t up[3] = { 4000u, 2500u, 1000u };
    const uint16_t down[3] = { 3000u, 2700u, 600u };
    const uint16_t cmp[3] = { 3500u, 2600u, 800u };
    const uint16_t trig[2] = { 1800u, 3200u };
    const uint16_t edge[2] = { 2499u, 2500u };
    uint16_t code[2];
    int j;
    (void)state;
    base_cfg(&cfg, 30.0, 0.0, true, 0.0);
    shunt_run(&s, &cfg, up, down, trig);
    assert_true(sim_sample_shunt(&s, code));
    for (j = 0; j < 2; j++) {
        const double want = shunt_idc_ideal(trig[j], up, s.shunt_iph[j]);
        assert_true(fabs(s.shunt_iph[j][0] + s.shunt_iph[j][1] + s.shunt_iph[j][2]) < 1e-9);
        assert_int_equal(code[j], shunt_code_of(want, 0.0));
        assert_true(fabs(s.shunt_true[j] - want) < 1e-12);
    }
    /* the first sample reads +i_u (u high alone), the second -i_w (u and v high) */
    assert_true(fabs(s.shunt_true[0] - s.shunt_iph[0][0]) < 1e-12);
    assert_true(fabs(s.shunt_true[1] + s.shunt_iph[1][2]) < 1e-12);
    /* one tick either side of v's rising edge */
    shunt_run(&s, &cfg, up, down, edge);
    assert_true(fabs(s.shunt_true[0] - s.shunt_iph[0][0]) < 1e-12);
    assert_true(fabs(s.shunt_true[1] - s.shunt_iph[1][0] - s.shunt_iph[1][1]) < 1e-12);
    /* volt-seconds: the same state, one period asymmetric, one symmetric */
    cfg.shunt.active = false;
    sim_init(&s, &cfg);
    sim_init(&r, &cfg);
    sim_set_state(&s, 0.0, 0.0, -4.0, 8.0);
    sim_set_state(&r, 0.0, 0.0, -4.0, 8.0);
    sim_set_compare2(&s, up, down);
    sim_set_compare(&r, cmp);
    sim_step_period(&s);
    sim_step_period(&r);
    sim_step_period(&s);
    sim_step_period(&r);
    assert_true(s.asym_active || !s.asym_pending);
    assert_true(fabs(s.v_ab_avg[0] - r.v_ab_avg[0]) < 1e-9);
    assert_true(fabs(s.v_ab_avg[1] - r.v_ab_avg[1]) < 1e-9);
    assert_true(fabs(s.v_ab_avg[0]) > 1.0);
    /* back to symmetric compare values: the period is the uniform one again */
    sim_set_compare(&s, cmp);
    sim_step_period(&s);
    assert_false(s.asym_active);
    assert_false(sim_sample_shunt(&s, code));
    assert_int_equal(code[0], 2048);
    assert_int_equal(code[1], 2048);
}

/* Single shunt: the dead time, the ringing after a pole transition and the sample-and-hold
   aperture.
   Methods: 1n the pole states with the dead time, the ringing formula and the aperture's
   mean computed in the test; 1b samples inside and just after the dead time, inside and
   after the ringing, an aperture across an edge */
static void test_shunt_ringing(void **state)
{
    /* REQ-SIM-007 */
    sim_cfg_t cfg;
    sim_t s;
    const uint16_t up[3] = { 4000u, 2500u, 1000u };
    const uint16_t down[3] = { 3000u, 2700u, 600u };
    const uint16_t in_dt[2] = { 2540u, 2600u };
    const uint16_t ring[2] = { 2520u, 2590u };
    const uint16_t across[2] = { 1800u, 2480u };
    uint16_t code[2];
    double iu;
    double iv;
    double x;
    double want;
    int m;
    (void)state;
    /* dead time 1 us = 80 ticks: v (8.9 A > 0) goes high 80 ticks after its gate edge */
    base_cfg(&cfg, 30.0, 1.0e-6, true, 0.0);
    shunt_run(&s, &cfg, up, down, in_dt);
    assert_true(s.shunt_iph[0][1] > 0.0 && s.shunt_iph[0][0] < 0.0);
    assert_true(fabs(s.shunt_true[0] - s.shunt_iph[0][0]) < 1e-12);
    assert_true(fabs(s.shunt_true[1] - s.shunt_iph[1][0] - s.shunt_iph[1][1]) < 1e-12);
    /* ringing 1 us at 2 MHz, half the step: the first sample 0.25 us after v's transition
       (cos = -1), the second 1.125 us after it (settled) */
    base_cfg(&cfg, 30.0, 0.0, true, 0.0);
    cfg.shunt.t_ring_s = 1.0e-6;
    cfg.shunt.ring_gain = 0.5;
    cfg.shunt.f_ring_hz = 2.0e6;
    shunt_run(&s, &cfg, up, down, ring);
    assert_true(sim_sample_shunt(&s, code));
    iu = s.shunt_iph[0][0];
    iv = s.shunt_iph[0][1];
    want = iu + iv - 0.5 * iv * exp(-0.75);
    assert_int_equal(code[0], shunt_code_of(want, 0.0));
    assert_true(fabs(((double)code[0] - 2048.0) / 51.2 - (iu + iv)) > 0.15 * fabs(iv));
    assert_int_equal(code[1], shunt_code_of(s.shunt_iph[1][0] + s.shunt_iph[1][1], 0.0));
    /* aperture 0.5 us = 40 ticks across v's edge at 2500: half +i_u, half i_u + i_v */
    cfg.shunt.t_ring_s = 0.0;
    cfg.shunt.t_sh_s = 0.5e-6;
    shunt_run(&s, &cfg, up, down, across);
    assert_true(sim_sample_shunt(&s, code));
    assert_int_equal(code[0], shunt_code_of(s.shunt_iph[0][0], 0.0));
    x = 0.0;
    for (m = 0; m < 16; m++) {
        const double c = 2480.0 + ((double)m + 0.5) / 16.0 * 40.0;
        x += s.shunt_iph[1][0] + ((c >= 2500.0) ? s.shunt_iph[1][1] : 0.0);
    }
    assert_int_equal(code[1], shunt_code_of(x / 16.0, 0.0));
}

/* Single shunt: the sense faults, the ADC offset and noise, the inverter off.
   Methods: 1l an offset and an open sense connection injected; 1n the codes computed in
   the test; 1b switches off (the diodes of the negative currents conduct) */
static void test_shunt_faults(void **state)
{
    /* REQ-SIM-007 */
    sim_cfg_t cfg;
    sim_t s;
    const uint16_t up[3] = { 4000u, 2500u, 1000u };
    const uint16_t down[3] = { 3000u, 2700u, 600u };
    const uint16_t trig[2] = { 1800u, 3200u };
    uint16_t code[2];
    uint16_t ok[2];
    double sum = 0.0;
    double sum2 = 0.0;
    int k;
    (void)state;
    base_cfg(&cfg, 30.0, 0.0, true, 0.0);
    cfg.adc_offset_counts = 5.0;
    shunt_run(&s, &cfg, up, down, trig);
    assert_true(sim_sample_shunt(&s, ok));
    assert_int_equal(ok[0], shunt_code_of(s.shunt_true[0], 5.0));
    assert_int_equal(ok[1], shunt_code_of(s.shunt_true[1], 5.0));
    /* an offset of 30 counts on the shunt channel */
    cfg.shunt.active = true;
    sim_init(&s, &cfg);
    s.inj.shunt_offset = 30.0;
    sim_set_state(&s, 0.0, 0.0, -4.0, 8.0);
    sim_set_compare2(&s, up, down);
    sim_set_triggers(&s, trig, true);
    sim_step_period(&s);
    sim_step_period(&s);
    assert_true(sim_sample_shunt(&s, code));
    assert_int_equal(code[0], shunt_code_of(s.shunt_true[0], 35.0));
    assert_int_equal(code[1], shunt_code_of(s.shunt_true[1], 35.0));
    /* the sense connection open: the amplifier's zero */
    s.inj.shunt_open = true;
    sim_step_period(&s);
    assert_true(sim_sample_shunt(&s, code));
    assert_int_equal(code[0], 2048 + 35);
    assert_int_equal(code[1], 2048 + 35);
    /* the inverter off: only the negative currents (u and w) flow through the DC link */
    s.inj.shunt_open = false;
    sim_set_enable(&s, false);
    sim_step_period(&s);
    sim_step_period(&s);
    assert_true(sim_sample_shunt(&s, code));
    assert_false(s.extinct);
    {
        double neg = 0.0;
        for (k = 0; k < 3; k++) {
            neg += (s.shunt_iph[0][k] < 0.0) ? s.shunt_iph[0][k] : 0.0;
        }
        assert_true(neg < -1.0);
        assert_int_equal(code[0], shunt_code_of(neg, 35.0));
    }
    /* triggers off: no samples */
    sim_set_triggers(&s, trig, false);
    sim_step_period(&s);
    assert_true(sim_sample_shunt(&s, code)); /* set for the next period */
    sim_step_period(&s);
    assert_false(sim_sample_shunt(&s, code));
    /* noise: 0.5 A rms on the samples as on the phase channels */
    base_cfg(&cfg, 30.0, 0.0, true, 0.0);
    cfg.noise_i_rms_a = 0.5;
    cfg.seed = 11u;
    cfg.shunt.active = true;
    sim_init(&s, &cfg);
    sim_set_compare2(&s, up, down);
    sim_set_triggers(&s, trig, true);
    sim_step_period(&s);
    for (k = 0; k < 4000; k++) {
        double e;
        sim_step_period(&s);
        (void)sim_sample_shunt(&s, code);
        e = ((double)code[0] - 2048.0) / 51.2 - s.shunt_true[0];
        sum += e;
        sum2 += e * e;
    }
    {
        const double mean = sum / 4000.0;
        const double rms = sqrt(sum2 / 4000.0 - mean * mean);
        assert_true(fabs(mean) < 0.05);
        assert_true(fabs(rms - 0.5) < 0.04);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_motor_file),
        cmocka_unit_test(test_motor_file_rejects),
        cmocka_unit_test(test_steady_state_phasor),
        cmocka_unit_test(test_current_step_response),
        cmocka_unit_test(test_dead_time_error),
        cmocka_unit_test(test_mechanics),
        cmocka_unit_test(test_breakaway),
        cmocka_unit_test(test_load_profile),
        cmocka_unit_test(test_adc),
        cmocka_unit_test(test_shunt_samples),
        cmocka_unit_test(test_shunt_ringing),
        cmocka_unit_test(test_shunt_faults),
    };
    return cmocka_run_group_tests_name("sim_plant", tests, setup, NULL);
}
