/**
 * @file test_drive_dtc.c
 * @brief The drive's use of the inverter's residual voltage error (REQ-DRV-026,
 *        include/qfoc/dtc.h): learnt from the d voltage when ALIGN ends, 0 before it and
 *        again once the drive leaves RUN, and taken out of the flux observer's voltage in
 *        every later period.
 *
 * The tests drive the library through its entry points on the test rig
 * (tests/drive_rig.h); where a test needs a given d voltage at the end of ALIGN it writes
 * the d current PI's integrator (the fast step's field the tick reads) and runs ticks
 * only.  Expectations come from the model of specs/equations.md section 10 in double
 * precision: the d voltage of an aligned rotor u = R' i + dV s_d(i),
 * s_d(i) = (2/3)(f(i) - f(-i / 2)), f the fade of the compensation's dead band, at the
 * full and at half the alignment current, any resistance R'; the learnt error is dV
 * clamped to the table's dead-time voltage error.
 */
#include <math.h>
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <stdbool.h>
#include <cmocka.h>

#define TEST_SEED 0x0D7C0DEu
#include "test_util.h"
#include "qfoc/drive.h"
#include "reference_params.h"
#include "drive_sim.h"
#include "drive_rig.h"

static double fade_d(double i, double db)
{
    if (db <= 0.0) {
        return (i > 0.0) ? 1.0 : ((i < 0.0) ? -1.0 : 0.0);
    }
    return (i >= db) ? 1.0 : ((i <= -db) ? -1.0 : i / db);
}

static double sd_d(double i, double db)
{
    return (2.0 / 3.0) * (fade_d(i, db) - fade_d(-trunc(i / 2.0), db));
}

/* From STOP: power on and tick (the test plays the fast step) through CATCH, which finds
   the rotor standing (REQ-DRV-027), to the tick before the first voltage ALIGN keeps
   (t_sub one below five eighths of align_ms, in the full-current hold). */
static void rig_to_align_hold(rig_t *r)
{
    const uint32_t c1 = ((uint32_t)r->table.drive.align_ms * 5u) / 8u;
    long k;
    r->power_on = true;
    for (k = 0; (k < 20) && (r->d.s.sm.state != QFOC_STATE_RUN); k++) {
        rig_tick(r, true);
    }
    (void)rig_catch_ticks(r);
    assert_int_equal(r->d.s.dt_dv, 0);
    assert_int_equal(r->d.s.dt_learn, 0);
    for (k = 0; k < 4000; k++) {
        rig_tick(r, true);
        if ((r->d.s.sm.state == QFOC_STATE_RUN) && (r->d.s.sm.sub == QFOC_SUB_ALIGN)) {
            assert_int_equal(r->d.s.dt_dv, 0);
            if ((uint32_t)r->d.s.sm.t_sub + 1u >= c1) {
                break;
            }
        }
    }
    assert_int_equal(r->d.s.sm.sub, QFOC_SUB_ALIGN);
    assert_int_equal(r->d.s.id_ref, abs(r->table.drive.i_align));
}

/* The d PI holding u_hi through the rest of the full-current hold, then u_lo through the
   half-current hold (each moved by `drift` counts between its two voltages ALIGN keeps):
   ticks until OPEN_LOOP; returns the learnt error. */
static int32_t learn_drift(rig_t *r, int32_t u_hi, int32_t u_lo, int32_t drift)
{
    const int32_t ia = abs(r->table.drive.i_align);
    const uint32_t q3 = ((uint32_t)r->table.drive.align_ms * 3u) / 4u;
    long k;
    r->d.f.pi_id.integ = (u_hi - drift) * 65536;
    for (k = 0; (k < 1000) && ((uint32_t)r->d.s.sm.t_sub + 1u < q3); k++) {
        rig_tick(r, true);
        assert_int_equal(r->d.s.id_ref, ia);
    }
    r->d.f.pi_id.integ = u_hi * 65536;
    rig_tick(r, true);
    /* three quarters: half the current */
    assert_int_equal(r->d.s.sm.sub, QFOC_SUB_ALIGN);
    assert_int_equal(r->d.s.id_ref, ia / 2);
    r->d.f.pi_id.integ = (u_lo - drift) * 65536;
    for (k = 0; (k < 1000) && (r->d.s.sm.sub == QFOC_SUB_ALIGN); k++) {
        assert_int_equal(r->d.s.dt_dv, 0);
        assert_int_equal(r->d.s.dt_learn, 0);
        assert_int_equal(r->d.s.id_ref, ia / 2);
        if ((uint32_t)r->d.s.sm.t_sub + 2u >= (uint32_t)r->table.drive.align_ms) {
            r->d.f.pi_id.integ = u_lo * 65536;
        }
        rig_tick(r, true);
    }
    assert_int_equal(r->d.s.sm.state, QFOC_STATE_RUN);
    assert_int_equal(r->d.s.sm.sub, QFOC_SUB_OPEN_LOOP);
    /* at the open-loop frame's standstill the observer uses all of it */
    assert_int_equal(r->d.s.dt_dv, r->d.s.dt_learn);
    return r->d.s.dt_learn;
}

static int32_t learn_with(rig_t *r, int32_t u_hi, int32_t u_lo)
{
    return learn_drift(r, u_hi, u_lo, 0);
}

/* REQ-DRV-026: the error learnt when ALIGN ends against the model in double precision: a
   motor whose resistance is the table's or 25 % above or below it, and an inverter error
   of 0, +-100 counts and beyond the bound on either side; nothing learnt for a resistance
   60 % above the table's (beyond the table's allowance); 0 in ALIGN; kept through the
   run; 0 again once the drive leaves RUN.
   Methods: 1b the motor's resistance the table's, 25 % above and below, inverter errors 0
   and +-100 counts; 1c inverter errors beyond the bound on either side (+-5000: clamped); 1d
   a resistance 60 % above the table's, beyond its allowance (nothing learnt); 1n the learnt
   error against the model in double precision */
static void test_req_drv_026_learn(void **state)
{
    const qfoc_param_table_t *const t = &qfoc_params_reference;
    const double ia = fabs((double)t->drive.i_align);
    const double db = (double)t->svpwm.i_deadband;
    const double s_hi = sd_d(ia, db);
    const double s_lo = sd_d(trunc(ia / 2.0), db);
    const double vmax = (double)t->drive.flux_v_err;
    const double dvs[5] = { 0.0, 100.0, -100.0, 5000.0, -5000.0 };
    const double rk[4] = { 1.0, 1.25, 0.75, 1.6 };
    rig_t base;
    int c;
    (void)state;
    assert_true(fabs(s_hi - 2.0 * s_lo) >= 0.5);
    assert_true(vmax > 0.0);
    rig_init_table(&base, t, 1000u);
    rig_ms(&base, 300);
    assert_int_equal(base.d.s.sm.state, QFOC_STATE_STOP);
    rig_to_align_hold(&base);
    for (c = 0; c < 20; c++) {
        rig_t x = base;
        const double dv = dvs[c % 5];
        const double r = (double)t->flux.r * rk[c / 5];
        const double u_hi = r * ia / 32768.0 + dv * s_hi;
        const double u_lo = r * trunc(ia / 2.0) / 32768.0 + dv * s_lo;
        /* R' 60 % above the table's, beyond its allowance (flux_r_err, 30 %): nothing */
        const double want = (c >= 15) ? 0.0 : ((dv > vmax) ? vmax : ((dv < -vmax) ? -vmax : dv));
        int32_t got;
        long k;
        x.d.p = &x.table;
        /* within the d PI's output limits (the drive invariant) */
        assert_true(fabs(u_hi) <= (double)base.d.f.pi_id.params.out_max);
        got = learn_with(&x, (int32_t)lround(u_hi), (int32_t)lround(u_lo));
        assert_true(fabs((double)got - want) <= 3.0);
        /* kept through the run, 0 once the drive leaves RUN */
        x.power_on = false;
        for (k = 0; (k < 20000) && (x.d.s.sm.state == QFOC_STATE_RUN); k++) {
            assert_int_equal(x.d.s.dt_learn, got);
            rig_tick(&x, true);
        }
        assert_int_not_equal(x.d.s.sm.state, QFOC_STATE_RUN);
        assert_int_equal(x.d.s.dt_dv, 0);
        assert_int_equal(x.d.s.dt_learn, 0);
    }
}

/* REQ-DRV-026: nothing learnt when the alignment current has no half (i_align = 1), when
   ALIGN ends at another d reference than its half-current hold (written here, as a fault
   would), or when a hold's voltage has not settled: the error stays 0 however far the d
   voltage is from the resistance drop.
   Methods: 1c i_align = 1 (no half current), a hold voltage drifting by flux_v_err / 4 + 4
   counts (learnt) and one more (not); 1d ALIGN ending at another d reference than its hold
   (written as a fault would), a hold whose voltage has not settled; 1l the d reference
   overwritten at the end of ALIGN */
static void test_req_drv_026_no_learning(void **state)
{
    qfoc_param_table_t t1 = qfoc_params_reference;
    rig_t x;
    long k;
    (void)state;
    t1.drive.i_align = 1;
    t1.crc = qfoc_params_crc(&t1);
    assert_int_equal(qfoc_params_check(&t1), QFOC_PARAMS_OK);
    rig_init_table(&x, &t1, 1000u);
    rig_ms(&x, 300);
    rig_to_align_hold(&x);
    x.d.f.pi_id.integ = 2000 * 65536;
    for (k = 0; (k < 1000) && (x.d.s.sm.sub == QFOC_SUB_ALIGN); k++) {
        rig_tick(&x, true);
    }
    assert_int_equal(x.d.s.sm.sub, QFOC_SUB_OPEN_LOOP);
    assert_int_equal(x.d.s.dt_dv, 0);

    rig_init_table(&x, &qfoc_params_reference, 1000u);
    rig_ms(&x, 300);
    rig_to_align_hold(&x);
    x.d.f.pi_id.integ = 2000 * 65536;
    for (k = 0; (k < 1000) && (x.d.s.sm.sub == QFOC_SUB_ALIGN); k++) {
        if ((uint32_t)x.d.s.sm.t_sub + 1u >= (uint32_t)x.table.drive.align_ms) {
            x.d.s.id_ref = (int16_t)abs(x.table.drive.i_align);
            rig_reguard(&x);
        }
        rig_tick(&x, true);
    }
    assert_int_equal(x.d.s.sm.sub, QFOC_SUB_OPEN_LOOP);
    assert_int_equal(x.d.s.dt_dv, 0);

    /* a hold that has not settled: the voltage moved by more than flux_v_err / 4 + 4
       counts over the last eighth of ALIGN (by that much: learnt; one more: not) */
    {
        const qfoc_param_table_t *const t = &qfoc_params_reference;
        const double ia = fabs((double)t->drive.i_align);
        const double db = (double)t->svpwm.i_deadband;
        const double r = (double)t->flux.r;
        const int32_t u_hi = (int32_t)lround(r * ia / 32768.0 + 200.0 * sd_d(ia, db));
        const int32_t u_lo = (int32_t)lround(r * trunc(ia / 2.0) / 32768.0 +
                                             200.0 * sd_d(trunc(ia / 2.0), db));
        const int32_t tol = t->drive.flux_v_err / 4 + 4;
        int32_t drift;
        for (drift = tol; drift <= tol + 1; drift++) {
            rig_init_table(&x, t, 1000u);
            rig_ms(&x, 300);
            rig_to_align_hold(&x);
            if (drift == tol) {
                assert_true(abs(learn_drift(&x, u_hi, u_lo, drift) - 200) <= 3);
            } else {
                assert_int_equal(learn_drift(&x, u_hi, u_lo, drift), 0);
            }
        }
    }
}

/* REQ-DRV-026: the observer uses the learnt error whole up to twice the handover speed
   and none from four times, linearly between (E10-5): in OPEN_LOOP at the frame's speed,
   in CLOSED_LOOP at the speed reference, checked every tick of a start to 6000 rpm played
   in ticks (the test sets the estimator's outputs on the reference).
   Methods: 1b every tick of a start to 6000 rpm, in OPEN_LOOP and CLOSED_LOOP; 1c twice and
   four times the handover speed (whole, none) and between; 1n the fade (E10-5) in double
   precision */
static void test_req_drv_026_speed_fade(void **state)
{
    const qfoc_param_table_t *const t = &qfoc_params_reference;
    const double wf = 2.0 * fabs((double)t->drive.of_speed);
    rig_t x;
    long k;
    long faded = 0;
    long none = 0;
    int32_t dv;
    (void)state;
    rig_init_table(&x, t, 6000u);
    rig_ms(&x, 300);
    rig_to_align_hold(&x);
    {
        /* an error of 200 counts on the table's resistance */
        const double ia = fabs((double)t->drive.i_align);
        const double db = (double)t->svpwm.i_deadband;
        const double r = (double)t->flux.r;
        dv = learn_with(&x, (int32_t)lround(r * ia / 32768.0 + 200.0 * sd_d(ia, db)),
                        (int32_t)lround(r * trunc(ia / 2.0) / 32768.0 +
                                        200.0 * sd_d(trunc(ia / 2.0), db)));
    }
    assert_true(abs(dv - 200) <= 3);
    for (k = 0; (k < 12000) && (x.d.s.sm.state == QFOC_STATE_RUN); k++) {
        qfoc_drive_fast_t *const f = &x.d.f;
        const bool ol = (x.d.s.sm.sub == QFOC_SUB_OPEN_LOOP);
        const double w = fabs((double)(ol ? x.d.s.ol_speed : x.d.s.speed_ref));
        double want;
        /* the estimator on the frame (OPEN_LOOP) or on the reference */
        f->speed_f = ol ? x.d.s.ol_speed : x.d.s.speed_ref;
        f->speed = f->speed_f;
        f->psi_mag = t->psi_f;
        f->theta_est = (uint16_t)(f->theta_ol / 65536u);
        f->i_dq.d = 0;
        if (w <= wf) {
            want = (double)dv;
        } else if (w >= 2.0 * wf) {
            want = 0.0;
            none++;
        } else {
            want = trunc((double)dv * (2.0 * wf - w) / wf);
            faded++;
        }
        assert_true(fabs((double)x.d.s.dt_dv - want) < 1e-9);
        assert_int_equal(x.d.s.dt_learn, dv);
        rig_tick(&x, true);
        if ((x.d.s.sm.sub == QFOC_SUB_CLOSED_LOOP) &&
            (x.d.s.speed_ref >= x.d.s.speed_target)) {
            break;
        }
    }
    assert_int_equal(x.d.s.sm.state, QFOC_STATE_RUN);
    assert_int_equal(x.d.s.sm.faults, 0u);
    assert_true(faded > 10);
    assert_true(none > 10);
}

/* REQ-DRV-026: the observer integrates the applied voltage less dV Clarke(f(i)): one
   fast step with the error learnt moves the flux estimate as one without it whose
   applied voltage is lowered by the error vector (computed here in double precision),
   and unlike one without either.
   Methods: 1n one fast step with the learnt error against twins without it whose applied
   voltage is lowered by the error vector computed in double precision, and without either */
static void test_req_drv_026_observer(void **state)
{
    const qfoc_param_table_t *const t = &qfoc_params_reference;
    const double db = (double)t->svpwm.i_deadband;
    const int32_t dv = 600;
    rig_t base;
    rig_t x;
    rig_t y;
    rig_t z;
    rig_t w;
    double fu;
    double fv;
    double fw;
    double ea;
    double eb;
    (void)state;
    rig_init_table(&base, t, 1000u);
    rig_ms(&base, 300);
    rig_to_align_hold(&base);
    (void)learn_with(&base, 0, 0);
    assert_int_equal(base.d.s.sm.sub, QFOC_SUB_OPEN_LOOP);
    base.adc.iu = (uint16_t)(QFOC_ADC_MID + 700u);
    base.adc.iv = (uint16_t)(QFOC_ADC_MID - 200u);
    base.d.s.dt_dv = 0;
    rig_reguard(&base);
    /* two periods with the PWM on: the applied voltage is the command of the period before */
    rig_fast(&base);
    rig_fast(&base);
    /* the sample this step measures */
    w = base;
    w.d.p = &w.table;
    rig_fast(&w);
    fu = fade_d((double)w.d.f.i_abc.u, db);
    fv = fade_d((double)w.d.f.i_abc.v, db);
    fw = fade_d((double)w.d.f.i_abc.w, db);
    assert_true(fu != 0.0 && fv != 0.0 && fw != 0.0);
    ea = (double)dv * (2.0 * fu - fv - fw) / 3.0;
    eb = (double)dv * (fv - fw) / sqrt(3.0);
    x = base;
    x.d.p = &x.table;
    x.d.s.dt_dv = (int16_t)dv;
    rig_reguard(&x);
    y = base;
    y.d.p = &y.table;
    y.d.f.u_applied.alpha = (int16_t)lround((double)y.d.f.u_applied.alpha - ea);
    y.d.f.u_applied.beta = (int16_t)lround((double)y.d.f.u_applied.beta - eb);
    z = base;
    z.d.p = &z.table;
    rig_fast(&x);
    rig_fast(&y);
    rig_fast(&z);
    {
        const double xa = (double)x.d.f.flux.psi_alpha - (double)z.d.f.flux.psi_alpha;
        const double xb = (double)x.d.f.flux.psi_beta - (double)z.d.f.flux.psi_beta;
        const double ya = (double)y.d.f.flux.psi_alpha - (double)z.d.f.flux.psi_alpha;
        const double yb = (double)y.d.f.flux.psi_beta - (double)z.d.f.flux.psi_beta;
        /* the error moved the estimate: 800 LSB of voltage for one period */
        assert_true(hypot(xa, xb) > 0.0);
        /* as the lowered voltage does, within the 2 LSB of the rounded error vector */
        assert_true(hypot(xa - ya, xb - yb) <= hypot(xa, xb) / 100.0 + 2.0);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_req_drv_026_learn),
        cmocka_unit_test(test_req_drv_026_no_learning),
        cmocka_unit_test(test_req_drv_026_speed_fade),
        cmocka_unit_test(test_req_drv_026_observer),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
