/**
 * @file snapshots.h
 * @brief Drive states the drive harnesses start from, made once per process
 *        (LLVMFuzzerInitialize): every committed table's drive after a valid init in
 *        PRECHARGE, in the offset calibration, in STOP, in RUN (ALIGN and OPEN_LOOP, through
 *        the master's RUN command as tests/test_drive.c does it) and in ERROR; and, on the
 *        plant model of sim/ with the reference motor, in CLOSED_LOOP at 2000 rpm, at
 *        5800 rpm with field weakening, and in STOPPING.  A fuzz input picks one and is
 *        applied to a copy, so it reaches every state without spending its bytes on the
 *        start-up.  Include after fuzz.h; link the sources of sim/ and tables/.
 */
#ifndef QFOC_TESTS_FUZZ_SNAPSHOTS_H
#define QFOC_TESTS_FUZZ_SNAPSHOTS_H

#include "drive_sim.h"
#include "reference_params.h"
#include "reference16k_params.h"
#include "traction350_params.h"

#ifndef QFOC_FUZZ_ROOT
#define QFOC_FUZZ_ROOT "."
#endif

#define FZ_SNAP_MAX 24

typedef struct {
    char name[32];
    fz_rig_t rig;   /* the drive and its master's command, bench inputs */
} fz_snap_t;

static fz_snap_t fz_snaps[FZ_SNAP_MAX];
static int fz_nsnaps;

static inline void fz_snap_add(const char *name, const fz_rig_t *r)
{
    FZ_CHECK(fz_nsnaps < FZ_SNAP_MAX, "snapshots: room");
    snprintf(fz_snaps[fz_nsnaps].name, sizeof fz_snaps[fz_nsnaps].name, "%s", name);
    memcpy(&fz_snaps[fz_nsnaps].rig, r, sizeof *r);
    fz_nsnaps++;
}

/* the synthetic states of one table (zero currents, nominal bus and temperatures) */
static inline void fz_snap_table(const char *tname, const qfoc_param_table_t *t)
{
    static fz_rig_t r;
    static fz_rig_t e;
    char name[32];
    fz_rig_init(&r, t);
    snprintf(name, sizeof name, "%s/precharge", tname);
    fz_snap_add(name, &r);
    fz_rig_until(&r, QFOC_STATE_PRECHARGE, QFOC_SUB_CALIB, 5000);
    fz_rig_ms(&r, 3);
    snprintf(name, sizeof name, "%s/calib", tname);
    fz_snap_add(name, &r);
    fz_rig_until(&r, QFOC_STATE_STOP, 0xFFu, 5000);
    fz_rig_ms(&r, 10);
    snprintf(name, sizeof name, "%s/stop", tname);
    fz_snap_add(name, &r);
    /* ERROR: the IPM over-temperature from STOP */
    memcpy(&e, &r, sizeof e);
    e.t_ipm = (int16_t)(t->drive.t_ipm_max + 100);
    fz_rig_until(&e, QFOC_STATE_ERROR, 0xFFu, 70000);
    e.t_ipm = 400;
    fz_rig_ms(&e, 2);
    snprintf(name, sizeof name, "%s/error", tname);
    fz_snap_add(name, &e);
    /* RUN through the master's command */
    r.power_on = true;
    fz_rig_until(&r, QFOC_STATE_RUN, QFOC_SUB_CATCH, 100);
    fz_rig_ms(&r, 5);
    snprintf(name, sizeof name, "%s/catch", tname);
    fz_snap_add(name, &r);
    fz_rig_until(&r, QFOC_STATE_RUN, QFOC_SUB_ALIGN, 1000);
    fz_rig_ms(&r, 5);
    snprintf(name, sizeof name, "%s/align", tname);
    fz_snap_add(name, &r);
    fz_rig_until(&r, QFOC_STATE_RUN, QFOC_SUB_OPEN_LOOP, 70000);
    fz_rig_ms(&r, 20);
    snprintf(name, sizeof name, "%s/open_loop", tname);
    fz_snap_add(name, &r);
}

/* the plant's states: the reference motor started to closed loop */
static inline void fz_snap_plant(void)
{
    static dsim_t ds;
    static sim_motor_t motor;
    static fz_rig_t r;
    sim_cfg_t cfg;
    long k;
    if (sim_motor_load(QFOC_FUZZ_ROOT "/specs/motors/reference.toml", &motor) != 0) {
        fz_fail("snapshots: specs/motors/reference.toml (set QFOC_FUZZ_ROOT)", __FILE__, __LINE__);
    }
    memset(&cfg, 0, sizeof cfg);
    cfg.motor = motor;
    cfg.vdc_v = 320.0;
    cfg.dead_time_s = motor.dead_time_s;
    cfg.substeps = 4;
    cfg.noise_i_rms_a = 0.05;
    cfg.seed = 7u;
    cfg.load.t_mean = 2.0;
    cfg.load.knee_rpm = 30.0;
    FZ_CHECK(dsim_init(&ds, &cfg, &qfoc_params_reference) == QFOC_PARAMS_OK, "plant: init");
    fz_rig_init(&r, &qfoc_params_reference);
    ds.power_on = true;
    ds.target_rpm = 2000u;
    for (k = 0; k < 9000L * ds.periods_per_ms; k++) {
        dsim_period(&ds);
        if (ds.drv.s.sm.sub == QFOC_SUB_CLOSED_LOOP && ds.ms > 3500) {
            break;
        }
    }
    FZ_CHECK(ds.drv.s.sm.sub == QFOC_SUB_CLOSED_LOOP, "plant: closed loop at 2000 rpm");
    memcpy(&r.d, &ds.drv, sizeof r.d);
    r.power_on = true;
    r.rpm = 2000u;
    r.ms = (uint32_t)ds.ms;
    fz_snap_add("reference/closed_loop_2000", &r);
    ds.target_rpm = 5800u;
    for (k = 0; k < 3000L * ds.periods_per_ms; k++) {
        dsim_period(&ds);
    }
    FZ_CHECK(ds.drv.s.sm.sub == QFOC_SUB_CLOSED_LOOP, "plant: closed loop at 5800 rpm");
    memcpy(&r.d, &ds.drv, sizeof r.d);
    r.rpm = 5800u;
    r.ms = (uint32_t)ds.ms;
    fz_snap_add("reference/closed_loop_5800", &r);
    ds.power_on = false;
    for (k = 0; k < 30L * ds.periods_per_ms; k++) {
        dsim_period(&ds);
    }
    FZ_CHECK(ds.drv.s.sm.sub == QFOC_SUB_STOPPING, "plant: stopping");
    memcpy(&r.d, &ds.drv, sizeof r.d);
    r.power_on = false;
    r.ms = (uint32_t)ds.ms;
    fz_snap_add("reference/stopping", &r);
}

static inline void fz_snapshots_init(void)
{
    if (fz_nsnaps > 0) {
        return;
    }
    fz_snap_table("reference", &qfoc_params_reference);
    fz_snap_table("reference16k", &qfoc_params_reference16k);
    fz_snap_table("traction350", &qfoc_params_traction350);
    fz_snap_plant();
    if (getenv("QFOC_FUZZ_VERBOSE") != NULL) {
        int k;
        for (k = 0; k < fz_nsnaps; k++) {
            fprintf(stderr, "snapshot %2d %-28s state %u sub %u faults 0x%04x\n", k,
                    fz_snaps[k].name, fz_snaps[k].rig.d.s.sm.state, fz_snaps[k].rig.d.s.sm.sub,
                    fz_snaps[k].rig.d.s.sm.faults);
        }
    }
}

/* the snapshot an input's first byte picks (among those whose state is `state` when
   state is not 0xFF), copied into r */
static inline void fz_snap_pick(fz_rig_t *r, uint8_t b, uint8_t state)
{
    int idx[FZ_SNAP_MAX];
    int n = 0;
    int k;
    for (k = 0; k < fz_nsnaps; k++) {
        if (state == 0xFFu || fz_snaps[k].rig.d.s.sm.state == state) {
            idx[n] = k;
            n++;
        }
    }
    FZ_CHECK(n > 0, "snapshots: one in the state asked for");
    memcpy(r, &fz_snaps[idx[b % n]].rig, sizeof *r);
}

#endif /* QFOC_TESTS_FUZZ_SNAPSHOTS_H */
