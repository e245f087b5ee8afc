/**
 * @file test_drive_shunt.c
 * @brief The drive on a single-shunt inverter (drive_shunt.h): the set-up from the table,
 *        a cold start to 3000 rpm on the plant with the currents rebuilt from the DC-link
 *        samples (sim/drive_sim.h with the plant's shunt sensing: dead time, ringing,
 *        aperture, noise), the same start with two phase-current sensors as the reference,
 *        and the loss of the sensing (an open sense connection) stopping the drive.
 *
 * The table is the reference motor's with drive.sensing = QFOC_SENSING_SHUNT (its CRC
 * recomputed); the shunt's settle time is the tool's default (dead time + 1 us: 160 ticks).
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <string.h>
#include <stdlib.h>
#include <cmocka.h>

#include <math.h>
#include "drive_sim.h"
#include "reference_params.h"

#define MOTOR_FILE "specs/motors/reference.toml"

static sim_motor_t motor;
static qfoc_param_table_t shunt_table;

static int setup(void **state)
{
    (void)state;
    shunt_table = qfoc_params_reference;
    shunt_table.drive.sensing = QFOC_SENSING_SHUNT;
    shunt_table.crc = qfoc_params_crc(&shunt_table);
    return (sim_motor_load(MOTOR_FILE, &motor) == 0) ? 0 : -1;
}

/* One period as the port runs it: the codes, the drive's fast step, the output. */
static qfoc_pwm_t step(qfoc_drive_shunt_t *sd, qfoc_drive_t *d, const qfoc_adc_t *a,
                       qfoc_q15_t s1, qfoc_q15_t s2)
{
    const qfoc_adc_t codes = qfoc_drive_shunt_measure(sd, d, a, s1, s2);
    assert_true(codes.iu <= 4095u && codes.iv <= 4095u);
    assert_int_equal(codes.vdc, a->vdc);
    return qfoc_drive_shunt_output(sd, qfoc_drive_fast_step(d, &codes));
}

/* The reference motor's plant; with the shunt, its DC-link sensing and the front end. */
static void rig(dsim_t *ds, qfoc_drive_shunt_t *sd, double load_nm)
{
    sim_cfg_t cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.motor = motor;
    cfg.vdc_v = 320.0;
    cfg.dead_time_s = motor.dead_time_s;
    cfg.substeps = 20;
    cfg.noise_i_rms_a = 0.05;
    cfg.seed = 7u;
    cfg.load.t_mean = load_nm;
    cfg.load.knee_rpm = 30.0;
    cfg.shunt.active = (sd != NULL);
    cfg.shunt.t_ring_s = 1.0e-6;
    cfg.shunt.ring_gain = 0.5;
    cfg.shunt.f_ring_hz = 2.0e6;
    cfg.shunt.t_sh_s = 0.5e-6;
    assert_int_equal(dsim_init(ds, &cfg, (sd != NULL) ? &shunt_table : &qfoc_params_reference),
                     QFOC_PARAMS_OK);
    if (sd != NULL) {
        assert_int_equal(qfoc_drive_shunt_init(sd, &ds->drv, 2u), QFOC_SHUNT_OK);
        ds->shunt = sd;
    }
}

/* The figures of a start: the time of the closed loop, the speed error and the angle error
   in the last second, the largest current. */
typedef struct {
    double t_cl;
    double speed_err;
    double ang_max;
    double i_peak;
    int held;
} start_t;

static void cold_start(dsim_t *ds, start_t *r)
{
    int ms;
    memset(r, 0, sizeof *r);
    r->t_cl = -1.0;
    ds->power_on = true;
    ds->target_rpm = 3000u;
    for (ms = 0; ms < 6000; ms++) {
        int k;
        for (k = 0; k < ds->periods_per_ms; k++) {
            double iab[2];
            dsim_period(ds);
            sim_i_ab(&ds->plant, iab);
            r->i_peak = fmax(r->i_peak, hypot(iab[0], iab[1]));
            if ((ds->shunt != NULL) && (ds->shunt->status != QFOC_SHUNT_OK)) {
                r->held++;
            }
        }
        if ((r->t_cl < 0.0) && (ds->drv.s.sm.state == QFOC_STATE_RUN) &&
            (ds->drv.s.sm.sub == QFOC_SUB_CLOSED_LOOP)) {
            r->t_cl = (double)ms * 1e-3;
        }
        if (ms >= 5000) {
            r->speed_err = fmax(r->speed_err, fabs(dsim_rpm(ds) - 3000.0));
            r->ang_max = fmax(r->ang_max, fabs(dsim_angle_err_deg(ds)));
        }
    }
}

/* REQ-SHUNT-006: the set-up: a table whose sensing is the shunt and a latency of 1 or 2
   accepted; a two-sensor table, a latency of 0 or 3 refused, the front end then lost from
   the start and its output off.
   Methods: 1b the two sensing modes; 1c the latencies 0, 1, 2, 3; 1d a two-sensor table run
   through the single-shunt step */
static void test_req_shunt_006_init(void **state)
{
    qfoc_drive_t d;
    qfoc_drive_shunt_t sd;
    qfoc_adc_t a = { 2048u, 2048u, 2621u };
    const qfoc_shunt_plan_t *p;
    qfoc_pwm_t out;
    int k;
    (void)state;
    assert_int_equal(qfoc_drive_init(&d, &shunt_table), QFOC_PARAMS_OK);
    assert_int_equal(qfoc_drive_shunt_init(&sd, &d, 1u), QFOC_SHUNT_OK);
    assert_false(sd.lost);
    assert_int_equal(sd.cfg.period, qfoc_params_reference.svpwm.period);
    assert_int_equal(sd.cfg.t_settle, 160u);
    assert_int_equal(sd.cfg.t_sample, 40u);
    assert_int_equal(sd.cfg.hold_max, 4u);
    assert_int_equal(qfoc_drive_shunt_init(&sd, &d, 2u), QFOC_SHUNT_OK);
    assert_int_equal(qfoc_drive_shunt_init(&sd, &d, 0u), QFOC_SHUNT_ERR_CFG);
    assert_true(sd.lost);
    assert_int_equal(qfoc_drive_shunt_init(&sd, &d, 3u), QFOC_SHUNT_ERR_CFG);
    assert_true(sd.lost);
    assert_int_equal(qfoc_drive_init(&d, &qfoc_params_reference), QFOC_PARAMS_OK);
    assert_int_equal(qfoc_drive_shunt_init(&sd, &d, 1u), QFOC_SHUNT_ERR_CFG);
    assert_true(sd.lost);
    /* lost from the start: the output stays off whatever the samples */
    for (k = 0; k < 100; k++) {
        out = step(&sd, &d, &a, 0, 0);
        p = qfoc_drive_shunt_plan(&sd, &d);
        assert_false(out.enable);
        assert_true(p == &sd.plan[sd.head]);
        assert_true(p->up[0] <= sd.cfg.period && p->down[2] <= sd.cfg.period);
    }
}

/* The drive of the shunt table, initialised, its front end with the given latency, and a
   plan in force made for an enabled output (white box: a plan of the SVPWM's centred
   compare values, both windows opened). */
static void measured_rig(qfoc_drive_t *d, qfoc_drive_shunt_t *sd, uint8_t latency,
                         const uint16_t cmp[3])
{
    assert_int_equal(qfoc_drive_init(d, &shunt_table), QFOC_PARAMS_OK);
    assert_int_equal(qfoc_drive_shunt_init(sd, d, latency), QFOC_SHUNT_OK);
    qfoc_shunt_plan(&sd->cfg, cmp, &sd->plan[0]);
    qfoc_shunt_plan(&sd->cfg, cmp, &sd->plan[1]);
    assert_true(sd->plan[0].ok);
    sd->plan_on[0] = true;
    sd->plan_on[1] = true;
}

/* REQ-SHUNT-006, REQ-SHUNT-007: the codes handed to the drive, observed through its
   over-current trip: with the offsets at the edges of the table's window (2048 +- 100),
   rebuilt currents near full scale go beyond the ADC's range and are clamped to its rails
   (u at 4095, v at 0), which the drive still reads above i_trip (the tool's rule
   'over-current trip': i_trip below (2047 - offset_window) x 16): over-current in that
   call; small currents give no trip; a configuration the shunt refuses with a
   single-shunt table is refused; a lost front end keeps its plans' output off even when
   the drive's output is enabled.
   Methods: 1c the offsets at the window's edges, the samples at +-32767, u as the first
   and as the last phase of the plan, the hold 0 (refused); 1d a lost front end beside an
   enabled drive output (white box); 1n the codes' clamp observed through the drive's
   over-current condition (DriveOverCurrent, drive.h) */
static void test_req_shunt_006_codes(void **state)
{
    qfoc_drive_t d;
    qfoc_drive_shunt_t sd;
    qfoc_param_table_t tab = shunt_table;
    const qfoc_adc_t a = { 0u, 0u, 2621u };
    static const uint16_t u_hi[3] = { 2700u, 2500u, 2300u };
    static const uint16_t u_lo[3] = { 2300u, 2500u, 2700u };
    const qfoc_shunt_plan_t *p;
    qfoc_pwm_t out;
    (void)state;
    /* a single-shunt table whose hold is 0: the shunt's configuration refused (only the
       front end reads the table here) */
    tab.drive.shunt_hold = 0u;
    d.p = &tab;
    assert_int_equal(qfoc_drive_shunt_init(&sd, &d, 1u), QFOC_SHUNT_ERR_CFG);
    assert_true(sd.lost);
    /* small samples, centred offsets: no trip, the measurement OK (latency 1 and 2) */
    measured_rig(&d, &sd, 1u, u_hi);
    out = step(&sd, &d, &a, 1000, -400);
    assert_int_equal(sd.status, QFOC_SHUNT_OK);
    assert_false(d.f.trip);
    assert_false(out.enable);   /* STOP */
    measured_rig(&d, &sd, 2u, u_hi);
    (void)step(&sd, &d, &a, -1000, 400);
    assert_int_equal(sd.status, QFOC_SHUNT_OK);
    assert_false(d.f.trip);
    /* u first (hi): i_v = sat(s2' - s1') = -32767, its code 1948 - 2047 clamped to 0 */
    assert_true(qfoc_params_reference.i_trip < (2047 - 100) * 16);
    assert_int_equal(shunt_table.drive.offset_window, 100u);
    measured_rig(&d, &sd, 1u, u_hi);
    d.s.offset_u = 2148u;
    d.s.offset_v = 1948u;
    (void)step(&sd, &d, &a, 32767, -32767);
    assert_int_equal(sd.status, QFOC_SHUNT_OK);
    assert_true(d.f.trip);
    /* u last (lo): i_u = sat(e - s2) = 32767, its code 2148 + 2047 clamped to 4095 */
    measured_rig(&d, &sd, 1u, u_lo);
    assert_int_equal(sd.plan[0].lo, 0u);
    d.s.offset_u = 2148u;
    d.s.offset_v = 1948u;
    (void)step(&sd, &d, &a, 32767, -32767);
    assert_true(d.f.trip);
    /* lost beside an enabled drive output: the plan's output stays off */
    measured_rig(&d, &sd, 1u, u_hi);
    sd.lost = true;
    d.f.out.enable = true;
    p = qfoc_drive_shunt_plan(&sd, &d);
    assert_false(sd.plan_on[sd.head]);
    assert_true(p == &sd.plan[sd.head]);
    sd.lost = false;
    p = qfoc_drive_shunt_plan(&sd, &d);
    assert_true(sd.plan_on[sd.head]);
    assert_true(p->up[0] <= sd.cfg.period);
}

/* REQ-SHUNT-008: the measurement refers the rebuilt currents to the drive's instant, latency
   - 1 periods after the start of the sampled period, with the angle per period of the
   drive's filtered speed and the ripple of its filtered bus across (L_d + L_q) / 2: the
   codes equal those of the currents turned by qfoc_shunt_align() with the angle and the gain
   computed here in double precision from the table's bases (within one step of rounding of
   each: 1 code); without speed and bus the currents are those rebuilt.
   Methods: 1b speeds of both signs, both latencies; 1c no speed and no bus; 1n the angle
   (speed x f_base / f_pwm turns per period) and the gain (V_dc T / L) in double precision */
static void test_req_shunt_008_measure(void **state)
{
    static const uint16_t cmp[3] = { 2400u, 1500u, 600u };
    const qfoc_adc_t a = { 0u, 0u, 2621u };
    const qfoc_param_table_t *t = &shunt_table;
    const int16_t speeds[4] = { 0, 3000, -5000, 9000 };
    int k;
    (void)state;
    for (k = 0; k < 8; k++) {
        qfoc_drive_t d;
        qfoc_drive_shunt_t sd;
        qfoc_shunt_t rec;
        qfoc_q15_t i[3];
        qfoc_adc_t c;
        const uint8_t lat = (uint8_t)(1 + (k & 1));
        const int16_t sp = speeds[k / 2];
        const int16_t vdc = (k < 2) ? 0 : 16000;
        double dth;
        double g;
        int32_t diff[2][2];
        int m;
        measured_rig(&d, &sd, lat, cmp);
        assert_int_equal(d.s.offset_u, 2048u);
        d.f.speed_f = sp;
        d.f.vdc = vdc;
        /* the angle per period, 65536 per turn: speed / 32768 x f_base / f_pwm turns */
        dth = (double)sp / 32768.0 * ((double)t->f_base_mhz * 1e-3) / (double)t->f_pwm_hz * 65536.0;
        /* V_dc T / L in Q15 of I_base: vdc / 32768 x w_base T / l_pu, l_pu = (ld + lq) / 2 / 4096 */
        g = (double)vdc / 32768.0 * (2.0 * 3.14159265358979 * (double)t->f_base_mhz * 1e-3 /
            (double)t->f_pwm_hz) / (0.5 * ((double)t->ld + (double)t->lq) / 4096.0) * 32768.0;
        c = qfoc_drive_shunt_measure(&sd, &d, &a, 6000, -2500);
        assert_int_equal(sd.status, QFOC_SHUNT_OK);
        for (m = 0; m < 2; m++) {
            const int32_t dd = (m == 0) ? (int32_t)floor(dth) : (int32_t)ceil(dth);
            const int32_t gg = (m == 0) ? (int32_t)floor(g) : (int32_t)ceil(g);
            (void)qfoc_shunt_init(&rec, &sd.cfg);
            assert_int_equal(qfoc_shunt_currents(&rec, &sd.plan[0], 6000, -2500, i), QFOC_SHUNT_OK);
            qfoc_shunt_align(&sd.cfg, &sd.plan[0], dd, gg, (uint8_t)(lat - 1u), i);
            diff[m][0] = (int32_t)c.iu - ((int32_t)d.s.offset_u + i[0] / 16);
            diff[m][1] = (int32_t)c.iv - ((int32_t)d.s.offset_v + i[1] / 16);
        }
        assert_true(labs((long)diff[0][0]) <= 1 || labs((long)diff[1][0]) <= 1);
        assert_true(labs((long)diff[0][1]) <= 1 || labs((long)diff[1][1]) <= 1);
        if (k >= 2) {
            /* speed and bus: the currents are no longer those rebuilt */
            assert_true((c.iu != d.s.offset_u + 6000 / 16) || (c.iv != d.s.offset_v - 8500 / 16));
        }
        if (k < 2) {
            /* no speed, no bus: as rebuilt, i_u = s1 = 6000, i_v = s2 - s1 = -8500 */
            assert_int_equal(c.iu, d.s.offset_u + 6000 / 16);
            assert_int_equal(c.iv, d.s.offset_v - 8500 / 16);
        }
    }
}

/* One measured period at 3000 (Q15 speed) of the front end of measured_rig(): the bus vdc,
   the front end's mean inductance kept (l_mean < 0) or set, the PLL's k_theta kept (0) or
   set; the status must be OK. */
static qfoc_adc_t corner_measure(uint8_t lat, int16_t vdc, int16_t l_mean, uint16_t k_theta)
{
    static const uint16_t cmp[3] = { 2400u, 1500u, 600u };
    const qfoc_adc_t a = { 0u, 0u, 2621u };
    qfoc_drive_t d;
    qfoc_drive_shunt_t sd;
    qfoc_adc_t c;
    measured_rig(&d, &sd, lat, cmp);
    assert_true(sd.l_mean > 0);
    d.f.speed_f = 3000;
    d.f.vdc = vdc;
    if (l_mean >= 0) {
        sd.l_mean = l_mean;
    }
    if (k_theta != 0u) {
        d.f.pll.k_theta = k_theta;
    }
    c = qfoc_drive_shunt_measure(&sd, &d, &a, 6000, -2500);
    assert_int_equal(sd.status, QFOC_SHUNT_OK);
    return c;
}

/* REQ-SHUNT-008: the corners of the correction's factors in qfoc_drive_shunt_measure(): a
   front end whose mean inductance is 0 takes no ripple off (the same codes as with no bus,
   where the gain is 0 too), and a k_theta above 32767, which no valid table has, reads as
   32767 (the same codes as with 32767).
   Methods: 1c l_mean 0 and k_theta 32767 / 40000; 1n each against the same measurement
   with the other input giving the same factor */
static void test_req_shunt_008_measure_corners(void **state)
{
    qfoc_adc_t c0;
    qfoc_adc_t c1;
    (void)state;
    /* l_mean 0 at a bus of 16000 against a bus of 0 */
    c0 = corner_measure(2u, 0, -1, 0u);
    c1 = corner_measure(2u, 16000, 0, 0u);
    assert_int_equal(c1.iu, c0.iu);
    assert_int_equal(c1.iv, c0.iv);
    /* k_theta 40000 against 32767 */
    c0 = corner_measure(1u, 16000, -1, 32767u);
    c1 = corner_measure(1u, 16000, -1, 40000u);
    assert_int_equal(c1.iu, c0.iu);
    assert_int_equal(c1.iv, c0.iv);
    /* and the factor matters: another k_theta gives other codes */
    c1 = corner_measure(1u, 16000, -1, 8000u);
    assert_true((c1.iu != c0.iu) || (c1.iv != c0.iv));
}

/* REQ-SHUNT-006, REQ-SHUNT-007: a cold start from standstill to 3000 rpm at the nominal
   4.5 N m with the currents rebuilt from the DC-link samples: closed loop reached, the
   speed within 1 % and the angle error within 1.5 times the two-sensor start's (and at
   least 3 degrees) in the last second, the current within i_max x 1.1, no period without
   a measurement once switching.
   Methods: 1a the cold start of REQ-DRV-014 on the plant with single-shunt sensing; 1n the
   same start with two phase-current sensors, against the plant's true speed and angle */
static void test_req_shunt_006_cold_start(void **state)
{
    dsim_t *ds = malloc(sizeof *ds);
    qfoc_drive_shunt_t sd;
    start_t two;
    start_t one;
    (void)state;
    rig(ds, NULL, 4.5);
    cold_start(ds, &two);
    rig(ds, &sd, 4.5);
    cold_start(ds, &one);
    print_message("two sensors: closed loop at %.3f s, |speed error| %.1f rpm, angle %.2f deg, "
                  "peak %.1f A\n", two.t_cl, two.speed_err, two.ang_max, two.i_peak);
    print_message("single shunt: closed loop at %.3f s, |speed error| %.1f rpm, angle %.2f deg, "
                  "peak %.1f A, %d periods held\n", one.t_cl, one.speed_err, one.ang_max,
                  one.i_peak, one.held);
    assert_true(one.t_cl > 0.0);
    assert_int_equal(ds->drv.s.sm.state, QFOC_STATE_RUN);
    assert_false(sd.lost);
    assert_true(one.speed_err < 30.0);
    assert_true(one.ang_max < fmax(1.5 * two.ang_max, 3.0));
    assert_true(one.i_peak < 1.1 * 20.0);
    free(ds);
}

/* REQ-SHUNT-007: periods without a measurement while running at 3000 rpm (each plan made to
   open no window): the last currents held for shunt_hold (4) periods, then the sensing
   lost in the next: the output off in that same call and in every later one, the drive in
   ERROR with OC at the next tick.  And an open sense connection (the samples read zero
   current although the plans open their windows): not seen by the measurement, the drive's
   own monitors stop it (ERROR, PWM off) within 200 periods (25 ms).
   Methods: 1l plans that open no window injected in closed loop, and an open sense
   connection; 1c the hold at its limit (4 periods held, the 5th lost); 1d a lost
   measurement */
static void test_req_shunt_007_sensing_lost(void **state)
{
    dsim_t *ds = malloc(sizeof *ds);
    qfoc_drive_shunt_t sd;
    start_t r;
    int k;
    int held = 0;
    (void)state;
    rig(ds, &sd, 4.5);
    cold_start(ds, &r);
    assert_int_equal(ds->drv.s.sm.state, QFOC_STATE_RUN);
    assert_false(sd.lost);
    /* from now on every plan opens no window (latency 2: the first such plan is in force
       two calls later) */
    sd.plan[sd.head].ok = false;
    for (k = 1; k <= 20; k++) {
        dsim_period(ds);
        sd.plan[sd.head].ok = false;
        if (k == 1) {
            assert_int_equal(sd.status, QFOC_SHUNT_OK);
        } else if (k <= 5) {
            assert_int_equal(sd.status, QFOC_SHUNT_HELD);
            assert_true(ds->pwm.enable);
            held++;
        } else if (k == 6) {
            assert_int_equal(sd.status, QFOC_SHUNT_LOST);
            assert_true(sd.lost);
            assert_false(ds->pwm.enable);
            assert_true(ds->drv.f.trip);
        } else {
            assert_true(sd.lost);
            assert_false(ds->pwm.enable);
        }
    }
    assert_int_equal(held, 4);
    assert_int_equal(ds->drv.s.sm.state, QFOC_STATE_ERROR);
    assert_true((ds->drv.s.sm.faults & QFOC_FAULT_OC) != 0u);
    /* the open sense connection */
    rig(ds, &sd, 4.5);
    cold_start(ds, &r);
    assert_int_equal(ds->drv.s.sm.state, QFOC_STATE_RUN);
    ds->plant.inj.shunt_open = true;
    for (k = 0; (k < 200) && (ds->drv.s.sm.state != QFOC_STATE_ERROR); k++) {
        dsim_period(ds);
    }
    print_message("sense open: ERROR after %d periods, faults 0x%04x\n", k,
                  (unsigned)ds->drv.s.sm.faults);
    assert_int_equal(ds->drv.s.sm.state, QFOC_STATE_ERROR);
    dsim_period(ds);
    assert_false(ds->pwm.enable);
    free(ds);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_req_shunt_006_init),
        cmocka_unit_test(test_req_shunt_006_codes),
        cmocka_unit_test(test_req_shunt_006_cold_start),
        cmocka_unit_test(test_req_shunt_007_sensing_lost),
        cmocka_unit_test(test_req_shunt_008_measure),
        cmocka_unit_test(test_req_shunt_008_measure_corners),
    };
    return cmocka_run_group_tests_name("drive_shunt", tests, setup, NULL);
}
