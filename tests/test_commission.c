/*
 * test_commission.c -- unit tests of the identification beside the drive
 * (include/qfoc/commission.h, REQ-IDENT-007).
 *
 * Reference: the rules of commission.h written here, the drive's reading of its ADC
 * samples written here from drive.h ((code - offset) x 16 with both taken as at most 4095,
 * bus code x 8), and two twins: an identification object fed the currents computed here
 * (through qfoc_clarke, proved against its own reference, transforms.h) and a drive object
 * given the same calls, whose fast step gives the output the commissioning step must pass
 * on when the drive has the PWM.  The drive runs on the plant (sim/drive_sim.h) with the
 * reference table.
 */
#include <math.h>
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#define TEST_SEED 0xC0111u
#include "test_util.h"
#include "qfoc/commission.h"
#include "qfoc/transforms.h"
#include "reference_params.h"
#include "drive_sim.h"

#define MOTOR_FILE "specs/motors/reference.toml"

static sim_motor_t motor;

static int setup(void **state)
{
    (void)state;
    return (sim_motor_load(MOTOR_FILE, &motor) == 0) ? 0 : -1;
}

/* The drive on the plant with the reference table, the master sending power off. */
static void rig(dsim_t *ds)
{
    sim_cfg_t cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.motor = motor;
    cfg.vdc_v = 320.0;
    cfg.dead_time_s = motor.dead_time_s;
    cfg.substeps = 10;
    cfg.noise_i_rms_a = 0.05;
    cfg.adc_offset_counts = 5.0;
    cfg.seed = 5u;
    cfg.load.knee_rpm = 30.0;
    assert_int_equal(dsim_init(ds, &cfg, &qfoc_params_reference), QFOC_PARAMS_OK);
    ds->power_on = false;
    ds->target_rpm = 3000u;
}

/* STOP, with the identification requested through qfoc_drive_command() (the service
   tool's command, sim/drive_sim.h) and in effect */
static void to_stop(dsim_t *ds)
{
    int ms;
    ds->identify = true;
    for (ms = 0; (ms < 2000) && ((ds->drv.s.sm.state != QFOC_STATE_STOP) ||
                                 !qfoc_drive_identify_requested(&ds->drv)); ms++) {
        dsim_run(ds, 1e-3);
    }
    assert_int_equal(ds->drv.s.sm.state, QFOC_STATE_STOP);
    assert_true(qfoc_drive_identify_requested(&ds->drv));
}

/* this period's ADC samples of the plant, as the drive's interrupt receives them */
static qfoc_adc_t plant_adc(dsim_t *ds)
{
    sim_adc_t a;
    qfoc_adc_t adc;
    sim_sample(&ds->plant, &a);
    adc.iu = a.iu;
    adc.iv = a.iv;
    adc.vdc = a.vdc;
    return adc;
}

/* the 1 ms tick with the service tool's command given through the interface (identify
   as ds->identify) */
static void master_tick(dsim_t *ds, bool power_on, uint16_t target_rpm)
{
    qfoc_tick_in_t in;
    qfoc_cmd_t cmd;
    memset(&in, 0, sizeof in);
    in.t_ipm = 250;
    in.t_pcb = 250;
    cmd.power_on = power_on;
    cmd.fault_clear = false;
    cmd.target_rpm = target_rpm;
    cmd.identify = ds->identify;
    (void)qfoc_drive_command(&ds->drv, &cmd);
    (void)qfoc_drive_tick(&ds->drv, &in);
}

/* A valid configuration for the reference table: 2 and 4 A, bound 10 A (I_base 40 A),
   the table's current PI and modulation, short steps. */
static qfoc_ident_cfg_t cfg_of(const qfoc_param_table_t *t)
{
    qfoc_ident_cfg_t c;
    memset(&c, 0, sizeof c);
    c.i_lo = 1638;
    c.i_hi = 3277;
    c.i_lim = 8192;
    c.i_ramp = 100;
    c.v_inj = 300;
    c.v_inj_max = 4000;
    c.i_inj = 800;
    c.v_move = 200;
    c.vdc_min = 10000;
    c.vdc_max = t->vdc_ov;
    c.n_align = 4000u;
    c.n_settle = 400u;
    c.win_shift = 10u;
    c.w_psi = 256u;
    c.n_ramp = 4000u;
    c.pi = t->pi_id;
    c.pwm = t->svpwm;
    c.pwm.dt_comp = 0u;
    return c;
}

/* the drive's reading of a current sample (drive.h, REQ-DRV-004), written here */
static int16_t ref_current(uint16_t code, uint16_t offset)
{
    const long c = (code > 4095u) ? 4095L : (long)code;
    const long o = (offset > 4095u) ? 4095L : (long)offset;
    const long v = (c - o) * 16L;
    return (int16_t)((v > 32767L) ? 32767L : ((v < -32767L) ? -32767L : v));
}

/* REQ-IDENT-007: the identification starts only while the drive is stopped and its
   command requests it: refused (ERR_DRIVE, nothing runs, the PWM stays off) in PRECHARGE
   (requested), in STOP without the request (the LIN master's frames), with a run
   requested in STOP, in RUN and in ERROR, and with bounds beyond the drive's protections
   (i_lim above the table's i_trip, vdc_max above its vdc_ov); in STOP with the request
   and no run request it starts (RUNNING) or, with a configuration the unit refuses,
   ERR_CFG.
   Methods: 1b every state of the drive, with and without a run request, with and
   without the identification request; 1c the run request alone, i_lim at i_trip and one
   above, vdc_max one above vdc_ov; 1n the header's rule written here */
static void test_req_ident_007_start_only_when_stopped(void **state)
{
    static dsim_t ds;
    static qfoc_ident_t id;
    qfoc_ident_cfg_t c;
    int p;
    (void)state;
    rig(&ds);
    c = cfg_of(&qfoc_params_reference);
    /* STOP with the LIN master's frames: no identification request */
    ds.identify = false;
    for (p = 0; (p < 2000) && (ds.drv.s.sm.state != QFOC_STATE_STOP); p++) {
        dsim_run(&ds, 1e-3);
    }
    assert_int_equal(ds.drv.s.sm.state, QFOC_STATE_STOP);
    assert_false(qfoc_drive_identify_requested(&ds.drv));
    assert_int_equal(qfoc_commission_start(&id, &ds.drv, &c), QFOC_IDENT_ERR_DRIVE);
    /* PRECHARGE, requested */
    rig(&ds);
    ds.identify = true;
    dsim_run(&ds, 20e-3);
    assert_true(qfoc_drive_identify_requested(&ds.drv));
    assert_int_equal(ds.drv.s.sm.state, QFOC_STATE_PRECHARGE);
    memset(&id, 0x3C, sizeof id);
    assert_int_equal(qfoc_commission_start(&id, &ds.drv, &c), QFOC_IDENT_ERR_DRIVE);
    assert_int_equal(qfoc_ident_result(&id), QFOC_IDENT_ERR_DRIVE);
    ds.ident = &id;
    for (p = 0; p < 50; p++) {
        dsim_period(&ds);
        assert_false(ds.pwm.enable);
        assert_int_equal(qfoc_ident_result(&id), QFOC_IDENT_ERR_DRIVE);
    }
    ds.ident = NULL;
    /* STOP: started; an invalid configuration refused */
    to_stop(&ds);
    assert_int_equal(qfoc_commission_start(&id, &ds.drv, &c), QFOC_IDENT_RUNNING);
    c.i_lo = 0;
    assert_int_equal(qfoc_commission_start(&id, &ds.drv, &c), QFOC_IDENT_ERR_CFG);
    c = cfg_of(&qfoc_params_reference);
    /* STOP, but bounds beyond the drive's protections: refused */
    c.i_lim = (int16_t)(qfoc_params_reference.i_trip + 1);
    assert_int_equal(qfoc_commission_start(&id, &ds.drv, &c), QFOC_IDENT_ERR_DRIVE);
    c.i_lim = qfoc_params_reference.i_trip;
    assert_int_equal(qfoc_commission_start(&id, &ds.drv, &c), QFOC_IDENT_RUNNING);
    c = cfg_of(&qfoc_params_reference);
    c.vdc_max = (int16_t)(qfoc_params_reference.vdc_ov + 1);
    assert_int_equal(qfoc_commission_start(&id, &ds.drv, &c), QFOC_IDENT_ERR_DRIVE);
    c = cfg_of(&qfoc_params_reference);
    /* STOP with a run request (a target below rpm_min keeps the drive in STOP): refused */
    ds.power_on = true;
    ds.target_rpm = 0u;
    for (p = 0; (p < 20) && !ds.drv.s.cmd.power_on; p++) {
        dsim_run(&ds, 1e-3);
    }
    assert_true(ds.drv.s.cmd.power_on);
    assert_int_equal(ds.drv.s.sm.state, QFOC_STATE_STOP);
    assert_int_equal(qfoc_commission_start(&id, &ds.drv, &c), QFOC_IDENT_ERR_DRIVE);
    /* RUN: refused */
    ds.target_rpm = 3000u;
    for (p = 0; (p < 200) && (ds.drv.s.sm.state != QFOC_STATE_RUN); p++) {
        dsim_run(&ds, 1e-3);
    }
    assert_int_equal(ds.drv.s.sm.state, QFOC_STATE_RUN);
    assert_int_equal(qfoc_commission_start(&id, &ds.drv, &c), QFOC_IDENT_ERR_DRIVE);
    /* ERROR (a phase current beyond the trip): refused, also without a run request */
    ds.adc_iu_add = 2000;
    for (p = 0; (p < 50) && (ds.drv.s.sm.state != QFOC_STATE_ERROR); p++) {
        dsim_run(&ds, 1e-3);
    }
    ds.adc_iu_add = 0;
    ds.power_on = false;
    dsim_run(&ds, 20e-3);
    assert_int_equal(ds.drv.s.sm.state, QFOC_STATE_ERROR);
    assert_false(ds.drv.s.cmd.power_on);
    assert_int_equal(qfoc_commission_start(&id, &ds.drv, &c), QFOC_IDENT_ERR_DRIVE);
    assert_int_equal(qfoc_ident_result(&id), QFOC_IDENT_ERR_DRIVE);
}

/* REQ-IDENT-007: while the identification runs and the drive is stopped, each period is
   the identification's: the output equals a twin identification's step on the currents
   and bus the drive would read from the same samples (computed here), and the drive's
   fast-step half is not written; the drive keeps STOP through the whole mode, which ends
   DONE on the plant.
   Methods: 1b every step of the mode; 1d ADC noise and offsets; 1n the twin fed the
   reference reading written here */
static void test_req_ident_007_identification_has_the_pwm(void **state)
{
    static dsim_t ds;
    static qfoc_ident_t id;
    static qfoc_ident_t twin;
    static qfoc_drive_fast_t f0;
    qfoc_ident_cfg_t c;
    long p;
    (void)state;
    rig(&ds);
    to_stop(&ds);
    c = cfg_of(&qfoc_params_reference);
    assert_int_equal(qfoc_commission_start(&id, &ds.drv, &c), QFOC_IDENT_RUNNING);
    assert_int_equal(qfoc_ident_start(&twin, &c), QFOC_IDENT_RUNNING);
    f0 = ds.drv.f;
    for (p = 0; (p < 200000L) && (qfoc_ident_result(&id) == QFOC_IDENT_RUNNING); p++) {
        qfoc_adc_t adc;
        qfoc_ab_t i;
        qfoc_pwm_t out;
        qfoc_pwm_t want;
        adc = plant_adc(&ds);
        qfoc_clarke(ref_current(adc.iu, ds.drv.s.offset_u), ref_current(adc.iv, ds.drv.s.offset_v),
                    &i);
        want = qfoc_ident_step(&twin, &i, (int16_t)(((adc.vdc > 4095u) ? 4095 : adc.vdc) * 8));
        out = qfoc_commission_fast_step(&ds.drv, &id, &adc);
        assert_int_equal(out.enable, want.enable);
        assert_memory_equal(out.cmp, want.cmp, sizeof out.cmp);
        assert_memory_equal(&ds.drv.f, &f0, sizeof f0);
        sim_set_compare(&ds.plant, out.cmp);
        sim_set_enable(&ds.plant, out.enable);
        sim_step_period(&ds.plant);
        if (((p + 1) % ds.periods_per_ms) == 0) {
            master_tick(&ds, false, 0u);
            assert_int_equal(ds.drv.s.sm.state, QFOC_STATE_STOP);
        }
    }
    assert_int_equal(qfoc_ident_result(&id), QFOC_IDENT_DONE);
    assert_int_equal(qfoc_ident_result(&twin), QFOC_IDENT_DONE);
    /* after the mode, the drive's fast step again */
    {
        qfoc_adc_t adc;
        qfoc_pwm_t out;
        adc = plant_adc(&ds);
        out = qfoc_commission_fast_step(&ds.drv, &id, &adc);
        assert_false(out.enable);
        assert_true(ds.drv.f.n_fast != f0.n_fast);
    }
}

/* REQ-IDENT-007: samples beyond 12 bits are read as the drive reads them (taken as
   4095): a current sample of 65535 is the largest current above the offset (the mode's
   ERR_OC), a bus sample of 65535 is 4095 x 8 (above vdc_max: ERR_BUS), each against the
   twin identification fed the reading written here; 4095 itself is read as it is.
   Methods: 1c the codes 4095, 4096 and 65535; 1l samples out of the ADC's range; 1n the
   drive's reading written here */
static void test_req_ident_007_samples_beyond_12_bits(void **state)
{
    static dsim_t ds;
    static qfoc_ident_t id;
    static qfoc_ident_t twin;
    static const uint16_t iu[4] = { 4095u, 65535u, 0u, 0u };
    static const uint16_t vdc[4] = { 2400u, 2400u, 4096u, 65535u };
    static const uint8_t want_res[4] = { QFOC_IDENT_ERR_OC, QFOC_IDENT_ERR_OC, QFOC_IDENT_ERR_BUS,
                                         QFOC_IDENT_ERR_BUS };
    int j;
    (void)state;
    rig(&ds);
    to_stop(&ds);
    for (j = 0; j < 4; j++) {
        const qfoc_ident_cfg_t c = cfg_of(&qfoc_params_reference);
        qfoc_adc_t adc;
        qfoc_ab_t i;
        qfoc_pwm_t out;
        qfoc_pwm_t want;
        adc.iu = (j < 2) ? iu[j] : ds.drv.s.offset_u;
        adc.iv = ds.drv.s.offset_v;
        adc.vdc = vdc[j];
        assert_int_equal(qfoc_commission_start(&id, &ds.drv, &c), QFOC_IDENT_RUNNING);
        assert_int_equal(qfoc_ident_start(&twin, &c), QFOC_IDENT_RUNNING);
        qfoc_clarke(ref_current(adc.iu, ds.drv.s.offset_u), ref_current(adc.iv, ds.drv.s.offset_v),
                    &i);
        want = qfoc_ident_step(&twin, &i, (int16_t)(((adc.vdc > 4095u) ? 4095 : adc.vdc) * 8));
        out = qfoc_commission_fast_step(&ds.drv, &id, &adc);
        assert_int_equal(out.enable, want.enable);
        assert_memory_equal(out.cmp, want.cmp, sizeof out.cmp);
        assert_int_equal(qfoc_ident_result(&id), want_res[j]);
        assert_int_equal(qfoc_ident_result(&twin), want_res[j]);
    }
}

/* REQ-IDENT-007: the drive first: a run request while the identification runs ends it
   (ERR_ABORT) in the first period the drive is no longer stopped, and from that period
   on the output is the drive's fast step's (equal to a twin drive's given the same
   calls); the drive then starts the motor.  A fault of the tick that takes the drive to
   ERROR (the power module over-temperature) ends it the same way, and so does the
   request's end: withdrawn (the LIN master's frame, which never carries it, replaces the
   service tool's command) or the link lost (the command not repeated within timeout_ms).
   Methods: 1b a run request, a fault, the request withdrawn, the link lost; 1n the twin
   drive and the header's rule */
static void test_req_ident_007_drive_first(void **state)
{
    static dsim_t ds;
    static qfoc_ident_t id;
    static qfoc_drive_t twin;
    qfoc_ident_cfg_t c;
    int p;
    int j;
    (void)state;
    for (j = 0; j < 4; j++) {
        rig(&ds);
        to_stop(&ds);
        c = cfg_of(&qfoc_params_reference);
        assert_int_equal(qfoc_commission_start(&id, &ds.drv, &c), QFOC_IDENT_RUNNING);
        ds.ident = &id;
        dsim_run(&ds, 50e-3);
        assert_int_equal(qfoc_ident_result(&id), QFOC_IDENT_RUNNING);
        if (j == 0) {
            ds.power_on = true;     /* the master asks for a run */
        } else if (j == 1) {
            ds.t_ipm = 1200;   /* the power module at 120 degC: the drive's OT_IPM fault */
        } else if (j == 2) {
            ds.identify = false;    /* the LIN master's frames again */
        } else {
            ds.link_alive = false;  /* the service tool stops sending */
        }
        for (p = 0; (p < 200000) && (qfoc_ident_result(&id) == QFOC_IDENT_RUNNING); p++) {
            const bool stopped = (ds.drv.s.sm.state == QFOC_STATE_STOP) &&
                                 qfoc_drive_identify_requested(&ds.drv) &&
                                 !ds.drv.s.cmd.power_on;
            dsim_period(&ds);
            /* the fast step of this period ran the identification only on a stopped
               drive (the tick after it may leave STOP: the next period aborts) */
            assert_true(stopped || (qfoc_ident_result(&id) != QFOC_IDENT_RUNNING));
        }
        assert_int_equal(qfoc_ident_result(&id), QFOC_IDENT_ERR_ABORT);
        assert_true((ds.drv.s.sm.state != QFOC_STATE_STOP) || ds.drv.s.cmd.power_on ||
                    !qfoc_drive_identify_requested(&ds.drv));
        if (j >= 2) {
            /* withdrawn within a frame period (10 ms); lost after timeout_ms */
            assert_false(qfoc_drive_identify_requested(&ds.drv));
            assert_true(p <= ((j == 2) ? 11 : (int)qfoc_params_reference.drive.link_timeout_ms + 2) *
                             ds.periods_per_ms);
        }
        /* from now on the drive's output: a twin drive given the same calls */
        for (p = 0; p < 200; p++) {
            qfoc_adc_t adc;
            qfoc_pwm_t out;
            qfoc_pwm_t want;
            twin = ds.drv;
            adc = plant_adc(&ds);
            want = qfoc_drive_fast_step(&twin, &adc);
            out = qfoc_commission_fast_step(&ds.drv, &id, &adc);
            assert_int_equal(out.enable, want.enable);
            assert_memory_equal(out.cmp, want.cmp, sizeof out.cmp);
            assert_memory_equal(&ds.drv.f, &twin.f, sizeof twin.f);
            sim_set_compare(&ds.plant, out.cmp);
            sim_set_enable(&ds.plant, out.enable);
            sim_step_period(&ds.plant);
            if (((p + 1) % ds.periods_per_ms) == 0) {
                master_tick(&ds, ds.power_on, ds.target_rpm);
            }
        }
        ds.ident = NULL;
        if (j == 0) {
            dsim_run(&ds, 0.5);
            assert_int_equal(ds.drv.s.sm.state, QFOC_STATE_RUN);
        } else if (j == 1) {
            dsim_run(&ds, 0.05);
            assert_int_equal(ds.drv.s.sm.state, QFOC_STATE_ERROR);
            assert_true((ds.drv.s.status.faults & QFOC_FAULT_OT_IPM) != 0u);
        } else {
            /* the drive stays without PWM: stopped, or (link lost) reporting LINK */
            dsim_run(&ds, 0.05);
            assert_false(ds.pwm.enable);
            assert_true((ds.drv.s.sm.state == QFOC_STATE_STOP) ||
                        (ds.drv.s.sm.state == QFOC_STATE_ERROR));
        }
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_req_ident_007_start_only_when_stopped),
        cmocka_unit_test(test_req_ident_007_identification_has_the_pwm),
        cmocka_unit_test(test_req_ident_007_samples_beyond_12_bits),
        cmocka_unit_test(test_req_ident_007_drive_first),
    };
    return cmocka_run_group_tests(tests, setup, NULL);
}
