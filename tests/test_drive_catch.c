/**
 * @file test_drive_catch.c
 * @brief The drive's flying start (REQ-DRV-027, include/qfoc/catch.h): a run request
 *        enters RUN in CATCH, where the drive runs zero-current control with the flux
 *        observer; a standing rotor goes on to ALIGN (the normal start, timed from there),
 *        a coasting rotor is caught in CLOSED_LOOP at its measured speed, and a rotor that
 *        cannot be caught (turning backwards) is left to coast down without torque.
 *
 * The standing rotor is shown on the test rig (tests/drive_rig.h: synthetic samples at
 * the offsets, the loops' voltage command 0) with the exact tick count of CATCH's filter
 * and dwell, and on the plant; the coasting and the reverse rotor on the plant
 * (sim/drive_sim.h: the reference motor with its generated table, 320 V, 8 kHz, dead
 * time, 12-bit sensing with noise), the rotor's speed set with sim_set_state once the
 * drive is in STOP.  Every figure is measured on the plant's true state.
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

#define TEST_SEED 0x0CA7C4u
#include "test_util.h"
#include "qfoc/drive.h"
#include "reference_params.h"
#include "drive_sim.h"
#include "drive_rig.h"

#define MOTOR_FILE "specs/motors/reference.toml"

static sim_motor_t motor;

static int setup(void **state)
{
    (void)state;
    return (sim_motor_load(MOTOR_FILE, &motor) == 0) ? 0 : -1;
}

/* ------------------------------------------------------------------ the plant */

/* The drive on the plant, the master asking for target_rpm with power off, a passive
   compressor load (mean load_nm, fading in over +-knee_rpm: it always opposes the motion). */
static void plant_rig(dsim_t *ds, double load_nm, uint16_t target_rpm)
{
    sim_cfg_t cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.motor = motor;
    cfg.vdc_v = 320.0;
    cfg.dead_time_s = motor.dead_time_s;
    cfg.substeps = 20;
    cfg.noise_i_rms_a = 0.05;
    cfg.seed = 11u;
    cfg.load.t_mean = load_nm;
    cfg.load.knee_rpm = 30.0;
    assert_true(cfg.load.knee_rpm > 0.0);   /* passive */
    assert_int_equal(dsim_init(ds, &cfg, &qfoc_params_reference), QFOC_PARAMS_OK);
    ds->power_on = false;
    ds->target_rpm = target_rpm;
}

/* whole milliseconds of the plant until the drive is in STOP (offsets calibrated) */
static void plant_to_stop(dsim_t *ds)
{
    int ms;
    for (ms = 0; (ms < 2000) && (ds->drv.s.sm.state != QFOC_STATE_STOP); ms++) {
        dsim_run(ds, 1e-3);
    }
    assert_int_equal(ds->drv.s.sm.state, QFOC_STATE_STOP);
    /* on to the start of a millisecond: the next period is the first of a tick's */
    while ((ds->period % ds->periods_per_ms) != 0) {
        dsim_period(ds);
    }
}

/* a Q15 electrical speed of the reference table in mechanical rpm */
static double q15_rpm(const dsim_t *ds, int32_t w)
{
    return (double)w / 32768.0 * ds->plant.bases.w_base / ds->plant.cfg.motor.pole_pairs * 60.0 /
           (2.0 * SIM_PI);
}

/* the plant's true phase-current magnitude, A */
static double plant_i(const dsim_t *ds)
{
    return hypot(ds->plant.id, ds->plant.iq);
}

/* What one run from the run request showed. */
typedef struct {
    long ms_run;          /* the tick that entered RUN (CATCH), ms after the request */
    long ms_catch;        /* ticks from the RUN entry to the tick that left CATCH */
    uint8_t sub_after;    /* the sub-state CATCH went to */
    double rpm_run;       /* the true speed at the RUN entry */
    double rpm_exit;      /* the true speed in the tick that left CATCH */
    double ref_exit;      /* the speed reference in that tick, rpm */
    double est_exit;      /* the observer's filtered speed in that tick, rpm */
    double i_peak;        /* the largest true current in CATCH, A */
    long ms_i_peak;       /* its tick, from the RUN entry */
    long ms_backwards;    /* CATCH ticks that left the rotor turning backwards */
    long ms_cl;           /* ticks from the RUN entry to CLOSED_LOOP (-1: not reached) */
    bool cl_backwards;    /* CLOSED_LOOP entered while the rotor turned backwards */
    bool lock_backwards;  /* a LOCK verdict counted while the rotor turned backwards */
    bool still_lock;      /* a LOCK verdict counted on a standing rotor */
} catch_run_t;

/* From STOP: the rotor at rpm_start (mechanical; sim_set_state), power on, and ms_max
   milliseconds of the plant; the PWM period by period (the current peak), the state
   machine tick by tick.  No fault at any tick. */
static void plant_catch_run(dsim_t *ds, double rpm_start, long ms_max, catch_run_t *o)
{
    const double pp = ds->plant.cfg.motor.pole_pairs;
    long ms;
    memset(o, 0, sizeof *o);
    o->ms_run = -1;
    o->ms_catch = -1;
    o->ms_cl = -1;
    sim_set_state(&ds->plant, 0.0, rpm_start * 2.0 * SIM_PI / 60.0 * pp, 0.0, 0.0);
    ds->power_on = true;
    for (ms = 0; ms < ms_max; ms++) {
        const bool in_catch = (ds->drv.s.sm.state == QFOC_STATE_RUN) &&
                              (ds->drv.s.sm.sub == QFOC_SUB_CATCH);
        int k;
        for (k = 0; k < ds->periods_per_ms; k++) {
            dsim_period(ds);   /* the last period of the ms runs the tick */
            if (in_catch) {
                /* zero-current control: every fast step of a CATCH ms switches */
                assert_true(ds->pwm.enable);
                if (plant_i(ds) > o->i_peak) {
                    o->i_peak = plant_i(ds);
                    o->ms_i_peak = ms - o->ms_run;
                }
            }
        }
        assert_int_not_equal(ds->drv.s.sm.state, QFOC_STATE_ERROR);
        assert_int_equal(ds->drv.s.sm.faults, 0u);
        if ((o->ms_run < 0) && (ds->drv.s.sm.state == QFOC_STATE_RUN)) {
            o->ms_run = ms;
            o->rpm_run = dsim_rpm(ds);
            assert_int_equal(ds->drv.s.sm.sub, QFOC_SUB_CATCH);
        }
        if (ds->drv.s.sm.state != QFOC_STATE_RUN) {
            continue;
        }
        if (ds->drv.s.sm.sub == QFOC_SUB_CATCH) {
            /* zero-current control: every reference 0 */
            assert_int_equal(ds->drv.s.id_ref, 0);
            assert_int_equal(ds->drv.s.iq_ref, 0);
            assert_int_equal(ds->drv.s.iq_lim, 0);
            assert_int_equal(ds->drv.s.speed_ref, 0);
            if (dsim_rpm(ds) < 0.0) {
                o->ms_backwards++;
                if (ds->drv.s.catch_st.db_lock.count > 0u) {
                    o->lock_backwards = true;
                }
            }
            if ((fabs(dsim_rpm(ds)) < 1.0) && (ds->drv.s.catch_st.db_lock.count > 0u)) {
                o->still_lock = true;
            }
        } else if (o->ms_catch < 0) {
            o->ms_catch = ms - o->ms_run;
            o->sub_after = ds->drv.s.sm.sub;
            o->rpm_exit = dsim_rpm(ds);
            o->ref_exit = q15_rpm(ds, ds->drv.s.speed_ref);
            o->est_exit = dsim_est_rpm(ds);
        } else {
            /* after CATCH */
        }
        if ((o->ms_cl < 0) && (ds->drv.s.sm.sub == QFOC_SUB_CLOSED_LOOP)) {
            o->ms_cl = ms - o->ms_run;
            o->cl_backwards = (dsim_rpm(ds) < 0.0);
        }
    }
}

/* ------------------------------------------------------------------ tests */

/* REQ-DRV-027, REQ-CATCH-003: a standing rotor on the rig (the loops' voltage command 0):
   the run request enters RUN in CATCH; the PWM is on with every current reference 0
   (zero-current control: id_ref = iq_ref = iq_lim = 0); the filtered magnitude starts at
   32767 and falls by an eighth of itself per tick, rounded up (catch.h's CatchStep:
   u_f - (7 + u_f) / 8 = floor(7 u_f / 8)), reaches v_still = max(2 |flux_v_err|, e_min / 4),
   e_min = of_speed psi_f / 32768, on the n-th tick after the RUN entry, where
   ln(32767 / (v_still + 7)) / ln(8 / 7) < n <= ceil(ln(32767 / v_still) / ln(8 / 7))
   (the sequence lies in (32767 (7/8)^n - 7, 32767 (7/8)^n]; with the reference table
   v_still = max(560, 1338 / 4 = 334) = 560, 30.4 < n <= 31: n = 31, catch.h's "30" being
   the untruncated 30.5), and the verdict STILL must then hold ho_dwell_ms ticks: ALIGN
   exactly on tick n + ho_dwell_ms - 1 (80), with the state time restarted, never
   CLOSED_LOOP.  The same with the fast step played by the test (ticks only).  The count
   here is formed in 32-bit integers as catch.h writes it, the rig's
   (rig_catch_still_ticks) in double precision: both independent of the library.
   Methods: 1c the tick n of the first STILL (30.4 < n <= 31 on the reference table) and
   ALIGN exactly on tick n + ho_dwell_ms - 1; 1n the count formed in 32-bit integers as
   catch.h writes it and the rig's in double precision, both independent of the library, with
   the fast step run and played by the test */
static void test_req_drv_027_standing_rotor(void **state)
{
    const qfoc_param_table_t *const t = &qfoc_params_reference;
    const int32_t e_min = (abs((int32_t)t->drive.of_speed) * abs((int32_t)t->psi_f)) / 32768;
    const int32_t lim = (2 * abs((int32_t)t->drive.flux_v_err) >= e_min / 4)
                            ? 2 * abs((int32_t)t->drive.flux_v_err) : e_min / 4;
    const double n_lo = log(32767.0 / ((double)lim + 7.0)) / log(8.0 / 7.0);
    const double n_hi = ceil(log(32767.0 / (double)lim) / log(8.0 / 7.0));
    long n = 0;
    long bound;
    int mode;
    (void)state;
    /* the filter, as catch.h writes it: u_f + CatchStep(0 - u_f), d < 0 */
    {
        int32_t uf = 32767;
        while (uf > lim) {
            uf = uf - ((7 - (0 - uf)) / 8);
            n++;
        }
    }
    bound = n + (long)t->drive.ho_dwell_ms - 1;
    assert_true((double)n > n_lo);
    assert_true((double)n <= n_hi);
    assert_int_equal(bound, rig_catch_still_ticks(t));
    print_message("standing rotor: v_still = max(2 flux_v_err, e_min / 4 = %d / 4) = %d, the "
                  "filter there after %ld ticks (%.1f < n <= %.0f), ALIGN %ld ticks after the RUN "
                  "entry (dwell %u)\n", e_min, lim, n, n_lo, n_hi, bound, t->drive.ho_dwell_ms);
    for (mode = 0; mode < 2; mode++) {
        rig_t r;
        long k;
        int ms;
        rig_init_table(&r, t, 3000u);
        rig_ms(&r, 300);
        assert_int_equal(r.d.s.sm.state, QFOC_STATE_STOP);
        r.power_on = true;
        for (ms = 0; (ms < 20) && (r.d.s.sm.state != QFOC_STATE_RUN); ms++) {
            rig_ms(&r, 1);
        }
        assert_int_equal(r.d.s.sm.state, QFOC_STATE_RUN);
        assert_int_equal(r.d.s.sm.sub, QFOC_SUB_CATCH);
        assert_int_equal(r.d.s.catch_st.u_f, 32767);
        for (k = 1; k <= bound; k++) {
            if (mode == 0) {
                int j;
                for (j = 0; j < (int)(t->f_pwm_hz / 1000u); j++) {
                    rig_fast(&r);
                    assert_true(r.pwm.enable);
                    assert_int_equal(r.d.f.u_last.alpha, 0);
                    assert_int_equal(r.d.f.u_last.beta, 0);
                }
                rig_tick(&r, (r.ms % 10) == 0);
            } else {
                rig_tick(&r, true);
            }
            assert_int_equal(r.d.s.sm.state, QFOC_STATE_RUN);
            assert_int_equal(r.d.s.sm.faults, 0u);
            if (k < bound) {
                assert_int_equal(r.d.s.sm.sub, QFOC_SUB_CATCH);
                assert_int_equal(r.d.s.id_ref, 0);
                assert_int_equal(r.d.s.iq_ref, 0);
                assert_int_equal(r.d.s.iq_lim, 0);
                assert_int_equal(r.d.s.catch_st.db_lock.count, 0u);
                assert_int_equal(r.d.s.catch_st.db_still.count, (k >= n) ? (uint16_t)(k - n + 1) : 0u);
                assert_int_equal(r.d.s.sm.t_state, (uint16_t)k);
            }
        }
        assert_int_equal(r.d.s.sm.sub, QFOC_SUB_ALIGN);
        assert_int_equal(r.d.s.sm.t_state, 0u);
        assert_int_equal(r.d.s.sm.t_sub, 0u);
        assert_false(r.d.s.caught);
        /* the start goes on as before: OPEN_LOOP after align_ms from here */
        if (mode == 0) {
            for (k = 1; (k <= 1000) && (r.d.s.sm.sub == QFOC_SUB_ALIGN); k++) {
                rig_ms(&r, 1);
            }
            assert_int_equal(r.d.s.sm.sub, QFOC_SUB_OPEN_LOOP);
            assert_int_equal(k - 1, (long)t->drive.align_ms);
            assert_int_equal(r.enabled_outside_run, 0);
        }
    }
}

/* REQ-DRV-027: in CATCH the current loops put out only what the zero-current PIs need,
   with no decoupling feed-forward at the estimated speed.  On the rig (zero current
   samples) the observer's PLL is set to a speed w (half the reference table's speed_max)
   once the drive is in CATCH; in the next fast steps the estimate still says about w, yet
   the voltage command stays 0.  With the feed-forward, it would be w psi_f / 2^psi_shift
   on the q axis (the expected value is computed here and shown to be far from 0): a
   voltage that, held by the inverter's dead band at zero current, the observer reads back
   as the back-EMF of a rotor turning at w, so that CATCH caught a standing rotor (the
   robustness campaign, axis ecomp800, seeds 800016 and 800052: dead time 1.59 and 1.75
   times the compensated one, rotor held by its breakaway torque).
   Methods: 1b the sub-state CATCH with a speed estimate far from 0; 1n the feed-forward
   voltage by hand */
static void test_req_drv_027_no_feedforward_in_catch(void **state)
{
    const qfoc_param_table_t *const t = &qfoc_params_reference;
    const int32_t w = abs((int32_t)t->speed_max) / 2;
    const int32_t ff = (w * abs((int32_t)t->psi_f) / 32768) * (1 << t->drive.psi_shift);
    rig_t r;
    int ms;
    int j;
    (void)state;
    rig_init_table(&r, t, 3000u);
    rig_ms(&r, 300);
    r.power_on = true;
    for (ms = 0; (ms < 20) && (r.d.s.sm.state != QFOC_STATE_RUN); ms++) {
        rig_ms(&r, 1);
    }
    assert_int_equal(r.d.s.sm.sub, QFOC_SUB_CATCH);
    print_message("CATCH with the estimate at w = %d (Q15): the feed-forward would be %d\n",
                  (int)w, (int)ff);
    assert_true(ff > 1000);
    /* past the first fast step in RUN, which restarts the estimator */
    for (j = 0; j < 4; j++) {
        rig_fast(&r);
    }
    qfoc_pll_reset(&r.d.f.pll, 0u, (qfoc_q15_t)w);
    for (j = 0; j < 8; j++) {
        rig_fast(&r);
        assert_true(r.pwm.enable);
        assert_int_equal(r.d.s.sm.sub, QFOC_SUB_CATCH);
        assert_int_equal(r.d.f.speed_f, w);
        assert_int_equal(r.d.f.u_last.alpha, 0);
        assert_int_equal(r.d.f.u_last.beta, 0);
    }
}

/* REQ-DRV-027, REQ-CATCH-002: the STILL threshold's floor on the rig: the reference table
   (of_speed 3277, psi_f 13383: e_min / 4 = 334) with flux_v_err 0, 3, 173 (v_still
   = max(2 |flux_v_err|, 334) = 334, 334, 346) and 174, 280 (348, 560), ho_dwell_ms 50 and
   1: a standing rotor goes from CATCH to ALIGN on tick N(v_still) + dwell - 1, N by hand
   from the filter's fall 32767 -> floor(7 u_f / 8) (397, 347 on tick 34, 303 on 35):
   N = 35, 35, 35, 34, 31.  With flux_v_err 0 the old filter (truncated eighths) stuck at
   7 and CATCH never ended in STILL.  The rig's count (rig_catch_still_ticks, double
   precision) against the hand value, the drive against both (rig_catch_ticks), and the
   filter's value at the exit.
   Methods: 1b flux_v_err 0, 3, 173, 174 and 280 (the floor deciding, and 2 |flux_v_err|),
   ho_dwell_ms 50 and 1; 1c flux_v_err 173 / 174 either side of the floor 334, dwell 1; 1d
   flux_v_err 0, where the truncated filter stuck at 7 and CATCH never ended; 1n the ticks by
   hand against the rig's double-precision count and the drive */
static void test_req_drv_027_standing_rotor_floor(void **state)
{
    static const struct {
        int16_t v_err;
        uint16_t dwell;
        long ticks;   /* by hand: N + dwell - 1 */
    } tab[] = {
        { 0, 50u, 84 }, { 3, 50u, 84 }, { 173, 50u, 84 }, { 174, 50u, 83 }, { 280, 50u, 80 },
        { 0, 1u, 35 },  { 174, 1u, 34 }, { 280, 1u, 31 },
    };
    unsigned i;
    (void)state;
    assert_int_equal(qfoc_params_reference.drive.of_speed, 3277);
    assert_int_equal(qfoc_params_reference.psi_f, 13383);
    for (i = 0; i < (sizeof tab / sizeof tab[0]); i++) {
        qfoc_param_table_t t = qfoc_params_reference;
        rig_t r;
        int ms;
        t.drive.flux_v_err = tab[i].v_err;
        t.drive.ho_dwell_ms = tab[i].dwell;
        t.crc = qfoc_params_crc(&t);
        assert_int_equal(rig_catch_still_ticks(&t), tab[i].ticks);
        rig_init_table(&r, &t, 3000u);
        rig_ms(&r, 300);
        assert_int_equal(r.d.s.sm.state, QFOC_STATE_STOP);
        r.power_on = true;
        for (ms = 0; (ms < 20) && (r.d.s.sm.state != QFOC_STATE_RUN); ms++) {
            rig_ms(&r, 1);
        }
        assert_int_equal(rig_catch_ticks(&r), tab[i].ticks);
        /* the filter ran in every CATCH tick: u_f after `ticks` steps towards 0 */
        {
            int32_t uf = 32767;
            long k;
            for (k = 0; k < tab[i].ticks; k++) {
                uf -= (7 + uf) / 8;
            }
            assert_int_equal(r.d.s.catch_st.u_f, uf);
        }
    }
}

/* REQ-DRV-027: a standing rotor on the plant (held by the nominal compressor load): the
   current stays at the noise in CATCH, CATCH goes to ALIGN after about the rig's count
   (the loops' voltage is the noise's, not 0) and never to CLOSED_LOOP, and the start
   reaches CLOSED_LOOP at the convergence tick after the ALIGN entry (rig_ho_tick).
   Methods: 1d a rotor held by the compressor load, the loops' voltage at the noise (not 0);
   1n the plant's true current and the rig's count (rig_catch_still_ticks, rig_ho_tick) */
static void test_req_drv_027_standing_rotor_plant(void **state)
{
    dsim_t *ds = malloc(sizeof *ds);
    const qfoc_param_table_t *const t = &qfoc_params_reference;
    const double i_max_a = (double)t->i_max / 32768.0 * (double)t->i_base_ma / 1000.0;
    const long n = rig_catch_still_ticks(t);
    catch_run_t o;
    (void)state;
    assert_non_null(ds);
    plant_rig(ds, 4.5, 3000u);
    plant_to_stop(ds);
    plant_catch_run(ds, 0.0, 2600, &o);
    print_message("standing rotor on the plant: RUN %ld ms after the request, CATCH %ld ms "
                  "(rig: %ld), peak current in CATCH %.2f A (i_max %.1f A), CLOSED_LOOP %ld ms "
                  "after the RUN entry\n", o.ms_run, o.ms_catch, n, o.i_peak, i_max_a, o.ms_cl);
    assert_int_equal(o.sub_after, QFOC_SUB_ALIGN);
    assert_false(o.still_lock);
    assert_true(o.ms_catch >= n - 2 && o.ms_catch <= n + 20);
    assert_true(fabs(o.rpm_exit) < 1.0);
    assert_true(o.i_peak < 0.1 * i_max_a);
    assert_int_equal(o.ms_cl, o.ms_catch + rig_ho_tick(t));
    free(ds);
}

/* REQ-DRV-027: a rotor coasting at 3000 rpm (a light passive load: it slows down) is
   caught: CATCH enters CLOSED_LOOP directly (no ALIGN, no open loop), the speed
   reference in that tick from the measured speed, within 10 % of the true speed; the
   true current in CATCH stays below half of i_max (no torque while the drive measures);
   no fault; the closed loop then takes the rotor to the master's 3000 rpm without the
   cl_hold_ms hold.
   Methods: 1b a rotor coasting at 3000 rpm under a light passive load (caught without
   ALIGN); 1n the plant's true speed (within 10 %) and current (below half of i_max) */
static void test_req_drv_027_coasting_rotor_caught(void **state)
{
    dsim_t *ds = malloc(sizeof *ds);
    const qfoc_param_table_t *const t = &qfoc_params_reference;
    const double i_max_a = (double)t->i_max / 32768.0 * (double)t->i_base_ma / 1000.0;
    catch_run_t o;
    double err_max = 0.0;
    int ms;
    (void)state;
    assert_non_null(ds);
    assert_int_equal(t->drive.pole_pairs, 3u);
    plant_rig(ds, 0.1, 3000u);
    plant_to_stop(ds);
    plant_catch_run(ds, 3000.0, 1500, &o);
    for (ms = 0; ms < 500; ms++) {
        dsim_run(ds, 1e-3);
        assert_int_equal(ds->drv.s.sm.faults, 0u);
        err_max = fmax(err_max, fabs(dsim_rpm(ds) - 3000.0));
    }
    print_message("coasting at 3000 rpm: RUN %ld ms after the request at %.0f rpm, CATCH %ld ms, "
                  "locked at %.0f rpm true, %.0f rpm estimated, reference %.0f rpm (%.1f %%), "
                  "peak current in CATCH %.2f A (i_max %.1f A); |speed error| at 3000 rpm "
                  "in the last 0.5 s %.1f rpm\n", o.ms_run, o.rpm_run, o.ms_catch, o.rpm_exit,
                  o.est_exit, o.ref_exit, 100.0 * (o.ref_exit - o.rpm_exit) / o.rpm_exit,
                  o.i_peak, i_max_a, err_max);
    assert_true(o.rpm_run > 2500.0);
    assert_int_equal(o.sub_after, QFOC_SUB_CLOSED_LOOP);
    assert_int_equal(o.ms_cl, o.ms_catch);
    assert_true(o.rpm_exit > 1000.0);
    assert_true(fabs(o.ref_exit - o.rpm_exit) <= 0.10 * o.rpm_exit);
    assert_true(o.i_peak < 0.5 * i_max_a);
    assert_true(ds->drv.s.caught);
    assert_int_equal(ds->drv.s.sm.state, QFOC_STATE_RUN);
    assert_int_equal(ds->drv.s.sm.sub, QFOC_SUB_CLOSED_LOOP);
    assert_true(err_max < 60.0);   /* 2 % */
    free(ds);
}

/* REQ-DRV-027: a rotor turning backwards at 1200 rpm (pressure equalising through the
   compressor) with a passive compressor load, light (0.1 N m: the rotor still turns
   backwards when CATCH ends) and heavier (0.5 N m: it has stopped): CATCH waits with zero
   current (no torque, the load slows the rotor down), longer than on a standing rotor, and
   never counts a LOCK verdict nor enters CLOSED_LOOP while the rotor turns backwards; once
   the back-EMF is below the STILL bound it goes to ALIGN with the rotor slowed below
   max(3 flux_v_err / psi_f, of_speed / 4 + flux_v_err / psi_f) (catch.h), and the start
   reaches CLOSED_LOOP, forwards, without fault.
   Methods: 1b backward rotation at 1200 rpm under a light (still turning at the end of
   CATCH) and a heavier load (stopped); 1d a rotor turning backwards when the start is
   requested (pressure equalising); 1n the plant's true speed against the STILL bound of
   catch.h */
static void test_req_drv_027_reverse_rotation(void **state)
{
    static const double loads[2] = { 0.1, 0.5 };
    const qfoc_param_table_t *const t = &qfoc_params_reference;
    const double i_max_a = (double)t->i_max / 32768.0 * (double)t->i_base_ma / 1000.0;
    /* the speed below which the back-EMF is within max(3 v_err, v_err + e_min / 4):
       w psi_f = that (Q15); e_min = of_speed psi_f / 32768 */
    const double e_min = trunc(fabs((double)t->drive.of_speed) * fabs((double)t->psi_f) /
                               32768.0);
    const double v_err = fabs((double)t->drive.flux_v_err);
    const int32_t w_still = (int32_t)lround(fmax(3.0 * v_err, v_err + trunc(e_min / 4.0)) /
                                            fabs((double)t->psi_f) * 32768.0);
    int c;
    (void)state;
    for (c = 0; c < 2; c++) {
        dsim_t *ds = malloc(sizeof *ds);
        catch_run_t o;
        double still;
        assert_non_null(ds);
        plant_rig(ds, loads[c], 3000u);
        plant_to_stop(ds);
        plant_catch_run(ds, -1200.0, 4500, &o);
        still = q15_rpm(ds, w_still);
        print_message("backwards at 1200 rpm, %.1f N m passive load: RUN %ld ms after the request "
                      "at %.0f rpm, CATCH %ld ms (%ld ms of them backwards), ALIGN at %.0f rpm "
                      "true (STILL bound %.0f rpm), peak current in CATCH %.2f A (i_max %.1f A), "
                      "CLOSED_LOOP %ld ms after the RUN entry, at %.0f rpm\n", loads[c], o.ms_run,
                      o.rpm_run, o.ms_catch, o.ms_backwards, o.rpm_exit, still, o.i_peak, i_max_a,
                      o.ms_cl, dsim_rpm(ds));
        assert_true(o.rpm_run < -900.0);
        assert_false(o.lock_backwards);
        assert_false(o.cl_backwards);
        assert_int_equal(o.sub_after, QFOC_SUB_ALIGN);
        assert_true(fabs(o.rpm_exit) < still);
        /* longer than a standing rotor's CATCH: it waited while the rotor turned */
        assert_true(o.ms_catch > rig_catch_still_ticks(t));
        assert_true(o.ms_backwards > rig_catch_still_ticks(t) / 2);
        assert_true(o.i_peak < 0.5 * i_max_a);
        /* the normal start from there: CLOSED_LOOP at convergence (rig_ho_tick) */
        assert_int_equal(o.ms_cl, o.ms_catch + rig_ho_tick(t));
        assert_int_equal(ds->drv.s.sm.sub, QFOC_SUB_CLOSED_LOOP);
        assert_false(ds->drv.s.caught);
        assert_true(dsim_rpm(ds) > 2000.0);
        free(ds);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_req_drv_027_standing_rotor),
        cmocka_unit_test(test_req_drv_027_standing_rotor_floor),
        cmocka_unit_test(test_req_drv_027_no_feedforward_in_catch),
        cmocka_unit_test(test_req_drv_027_standing_rotor_plant),
        cmocka_unit_test(test_req_drv_027_coasting_rotor_caught),
        cmocka_unit_test(test_req_drv_027_reverse_rotation),
    };
    return cmocka_run_group_tests(tests, setup, NULL);
}
