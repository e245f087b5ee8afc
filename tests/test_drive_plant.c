/**
 * @file test_drive_plant.c
 * @brief Closed-loop tests of the whole drive on the plant (sim/drive_sim.h): the
 *        reference motor (specs/reference-motor.md) with its generated table, a
 *        passive compressor load, 320 V, 8 kHz, dead time, 12-bit sensing.
 *        Every figure is measured on the plant's true state.
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

static int setup(void **state)
{
    (void)state;
    return (sim_motor_load(MOTOR_FILE, &motor) == 0) ? 0 : -1;
}

static void rig(dsim_t *ds, const qfoc_param_table_t *t, double load_nm, double pulse_1x)
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
    cfg.load.t_1x = pulse_1x * load_nm;
    cfg.load.knee_rpm = 30.0;
    assert_int_equal(dsim_init(ds, &cfg, t), QFOC_PARAMS_OK);
}

static void run_ms(dsim_t *ds, int ms)
{
    int k;
    for (k = 0; k < ms * ds->periods_per_ms; k++) {
        dsim_period(ds);
    }
}

/* REQ-DRV-014, REQ-DRV-006: cold start from standstill to 3000 rpm at the nominal load
   (4.5 N m).  The run request enters CATCH (REQ-DRV-027), which finds the rotor standing
   and goes to ALIGN; the start-up is timed from the ALIGN entry (the RUN entry before
   CATCH), and CATCH's own time is bounded apart.
   Methods: 1a the cold start of REQ-DRV-014 at the nominal load (4.5 N m) on the plant:
   CATCH to ALIGN within 0.2 s, closed loop not before cl_hold_ms nor the convergence tick,
   3000 rpm within 1 %, angle error below 20 degrees, against the plant's true speed and
   angle */
static void test_drv_014_start_3000rpm_nominal_load(void **state)
{
    dsim_t *ds = malloc(sizeof *ds);
    double t_run = -1.0;
    double t_align = -1.0;
    bool caught = false;
    double t_cl = -1.0;
    double t_reach = -1.0;
    double peak = 0.0;
    double err_max = 0.0;
    double ang_max = 0.0;
    int ms;
    (void)state;
    rig(ds, &qfoc_params_reference, 4.5, 0.0);
    ds->power_on = true;
    ds->target_rpm = 3000u;
    for (ms = 0; ms < 7000; ms++) {
        run_ms(ds, 1);
        if ((t_run < 0.0) && (ds->drv.s.sm.state == QFOC_STATE_RUN)) {
            t_run = ms * 1e-3;
            assert_int_equal(ds->drv.s.sm.sub, QFOC_SUB_CATCH);
        }
        if ((t_align < 0.0) && (ds->drv.s.sm.sub == QFOC_SUB_ALIGN)) {
            t_align = ms * 1e-3;
        }
        if ((t_align < 0.0) && (ds->drv.s.sm.sub == QFOC_SUB_CLOSED_LOOP)) {
            caught = true;   /* CATCH locked on a standing rotor: must not happen */
        }
        if ((t_cl < 0.0) && (ds->drv.s.sm.sub == QFOC_SUB_CLOSED_LOOP)) {
            t_cl = ms * 1e-3 - t_align;
        }
        if ((t_align >= 0.0) && (t_reach < 0.0) && (fabs(dsim_rpm(ds) - 3000.0) < 60.0)) {
            t_reach = ms * 1e-3 - t_align;
        }
        if (t_cl >= 0.0) {
            peak = fmax(peak, dsim_rpm(ds));
            ang_max = fmax(ang_max, fabs(dsim_angle_err_deg(ds)));
        }
        if (ms >= 6000) {
            err_max = fmax(err_max, fabs(dsim_rpm(ds) - 3000.0));
        }
        assert_int_not_equal(ds->drv.s.sm.state, QFOC_STATE_ERROR);
    }
    print_message("start to 3000 rpm at 4.5 N m: RUN at %.3f s, CATCH %.3f s to ALIGN; from "
                  "ALIGN: closed loop at %.3f s, within 2 %% at %.3f s, peak %.0f rpm, |speed "
                  "error| in the last second %.1f rpm, max angle error in closed loop %.1f deg\n",
                  t_run, t_align - t_run, t_cl, t_reach, peak, err_max, ang_max);
    /* CATCH: a standing rotor goes to ALIGN, within its filter time and dwell (0.08 s on
       the reference table, tests/drive_rig.h rig_catch_still_ticks) and a margin */
    assert_false(caught);
    assert_true(t_run >= 0.0 && t_align > t_run);
    assert_true(t_align - t_run < 0.2);
    /* not before cl_hold_ms (2 s, section 8.3) nor before the I/f ramp has reached of_speed
       and the observer has followed it for ho_dwell_ms (the handover's minimum speed,
       REQ-DRV-006) */
    {
        const qfoc_drive_cfg_t *const c = &qfoc_params_reference.drive;
        const double t_min = ((double)c->align_ms +
                              ceil((double)c->of_speed / (double)c->of_accel) +
                              (double)c->ho_dwell_ms - 1.0) * 1e-3;
        assert_true(t_cl >= t_min - 0.0015);
        assert_true(t_cl >= (double)c->cl_hold_ms * 1e-3);
    }
    assert_true(t_cl < 3.5);
    assert_true(t_reach > 0.0 && t_reach < 5.0);
    assert_true(err_max < 30.0);             /* 1 % */
    assert_true(peak < 3300.0);
    assert_true(ang_max < 20.0);
    free(ds);
}

/* REQ-DRV-003, REQ-SM-003: an over-current in closed loop: PWM off in the same period,
   ERROR at the next tick, clear only after 5 s.
   Methods: 1c the clear accepted only after 5 s in ERROR (4990 .. 5020 ms); 1d an
   over-current in closed loop and a clear requested at once; 1l a +35 A sensed phase current
   injected at the ADC for one period */
static void test_drv_003_overcurrent_on_plant(void **state)
{
    dsim_t *ds = malloc(sizeof *ds);
    int k;
    int ms;
    (void)state;
    rig(ds, &qfoc_params_reference, 2.0, 0.0);
    ds->power_on = true;
    ds->target_rpm = 2000u;
    run_ms(ds, 4000);
    assert_int_equal(ds->drv.s.sm.sub, QFOC_SUB_CLOSED_LOOP);
    /* align with the tick: the next period is the first of a millisecond */
    while ((ds->period % ds->periods_per_ms) != 0) {
        dsim_period(ds);
    }
    ds->adc_iu_add = 1800;                   /* a sensed phase current of +35 A */
    dsim_period(ds);
    assert_false(ds->pwm.enable);             /* the same PWM period */
    ds->adc_iu_add = 0;
    for (k = 1; k < ds->periods_per_ms; k++) {
        dsim_period(ds);
        assert_false(ds->pwm.enable);
    }
    assert_int_equal(ds->drv.s.sm.state, QFOC_STATE_ERROR);   /* the tick of this ms */
    assert_int_equal(ds->drv.s.sm.faults, QFOC_FAULT_OC);
    /* the master asks for a clear at once: refused until 5 s in ERROR */
    ds->fault_clear = true;
    for (ms = 0; ms < 6000 && ds->drv.s.sm.state == QFOC_STATE_ERROR; ms++) {
        run_ms(ds, 1);
        assert_false(ds->pwm.enable);
    }
    print_message("over-current: PWM off in the same period; fault cleared after %d ms\n", ms);
    assert_true(ms >= 4990 && ms <= 5020);
    assert_int_equal(ds->drv.s.sm.faults, 0);
    free(ds);
}

/* REQ-DRV-013: field weakening: 8000 rpm at 320 V with the nominal load.
   Methods: 1c 8000 rpm at 320 V, above the base speed, the peak current within i_max; 1a the
   speed within 1 % and a weakening d current on the plant */
static void test_drv_013_field_weakening_8000rpm(void **state)
{
    dsim_t *ds = malloc(sizeof *ds);
    double err_max = 0.0;
    double id_mean = 0.0;
    double i_peak = 0.0;
    int n = 0;
    int ms;
    (void)state;
    rig(ds, &qfoc_params_reference, 4.5, 0.0);
    ds->power_on = true;
    ds->target_rpm = 8000u;
    for (ms = 0; ms < 9000; ms++) {
        run_ms(ds, 1);
        assert_int_not_equal(ds->drv.s.sm.state, QFOC_STATE_ERROR);
        if (ms >= 8000) {
            err_max = fmax(err_max, fabs(dsim_rpm(ds) - 8000.0));
            id_mean += ds->plant.id;
            i_peak = fmax(i_peak, hypot(ds->plant.id, ds->plant.iq));
            n++;
        }
    }
    id_mean /= n;
    print_message("8000 rpm at 320 V, 4.5 N m: |speed error| %.1f rpm, mean i_d %.2f A, "
                  "peak |i| %.1f A, utilisation %.3f\n", err_max, id_mean, i_peak,
                  ds->drv.s.util / 32768.0);
    assert_true(err_max < 80.0);             /* 1 % */
    assert_true(id_mean < -2.0);             /* weakened */
    assert_true(i_peak < 20.5);              /* within i_max */
    free(ds);
}

/* REQ-DRV-013: torque compensation at 1500 rpm with a +-50 % pulsation at 1x
   mechanical: speed ripple with and without.  Mean load 3 N m: its peak (4.5 N m) is
   within the motor's torque at the current limit (5.85 N m); at the 4.5 N m nominal
   mean the 6.75 N m peak is not, whatever the control. */
static double ripple_pp(const qfoc_param_table_t *t)
{
    dsim_t *ds = malloc(sizeof *ds);
    double lo = 1e9;
    double hi = -1e9;
    int ms;
    rig(ds, t, 3.0, 0.5);
    ds->power_on = true;
    ds->target_rpm = 1500u;
    for (ms = 0; ms < 14000; ms++) {
        run_ms(ds, 1);
        assert_int_not_equal(ds->drv.s.sm.state, QFOC_STATE_ERROR);
        if (ms >= 12000) {
            lo = fmin(lo, dsim_rpm(ds));
            hi = fmax(hi, dsim_rpm(ds));
        }
    }
    free(ds);
    return hi - lo;
}

/* REQ-DRV-013: at 1500 rpm with a +-50 % load pulsation at 1x mechanical the torque
   compensation removes at least 70 % of the speed ripple (table with tc_gain = 0 as the
   reference).
   Methods: 1n the same run with the compensation off (tc_gain 0): at least 70 % of the speed
   ripple of a +-50 % 1x load pulsation at 1500 rpm removed */
static void test_drv_013_torque_compensation(void **state)
{
    qfoc_param_table_t off = qfoc_params_reference;
    double with;
    double without;
    (void)state;
    off.drive.tc_gain = 0;
    off.crc = qfoc_params_crc(&off);
    without = ripple_pp(&off);
    with = ripple_pp(&qfoc_params_reference);
    print_message("1500 rpm, 3 N m +-50 %% load pulsation at 1x: speed ripple %.1f rpm p-p without, "
                  "%.1f rpm with torque compensation: %.1f %% less\n", without, with,
                  100.0 * (1.0 - with / without));
    assert_true(with <= 0.3 * without);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_drv_014_start_3000rpm_nominal_load),
        cmocka_unit_test(test_drv_003_overcurrent_on_plant),
        cmocka_unit_test(test_drv_013_field_weakening_8000rpm),
        cmocka_unit_test(test_drv_013_torque_compensation),
    };
    return cmocka_run_group_tests(tests, setup, NULL);
}
