/**
 * @file scenario.h
 * @brief Compressor-drive scenarios: the whole qfoc drive (drive_sim.h) on the plant,
 *        scripted like a vehicle would use it, with metrics measured on the plant's
 *        true state and judged against the targets of specs/scenarios.toml.
 *        Host only; used by the demonstration (sim/apps/demo.c), the robustness
 *        campaign (sim/apps/robust.c) and the closed-loop regression tests
 *        (tests/test_scenarios.c).
 *
 * Scenarios (specs/requirements/scenarios.md gives the script and the targets of each):
 *   cold_start     standstill -> half the rated speed at the nominal load (any table)
 *   speed_steps    3000 -> 6000 -> 8000 (field weakening) -> 1500 rpm
 *   pulsating_load 1500 rpm, +-50 % load pulsation at 1x mechanical, without and with
 *                  torque compensation
 *   load_step      100 % rated torque applied at 3000 rpm
 *   bus_sag        DC bus 320 -> 250 -> 320 V at 6000 rpm
 *   fault_oc, fault_ov, fault_ot, fault_stall, fault_link
 *                  phase over-current, DC-bus over-voltage, IPM over-temperature, locked
 *                  rotor, command-link loss: detection, ERROR, PWM off, the 5 s stop, a
 *                  clear request and the restart
 */
#ifndef QFOC_SIM_SCENARIO_H
#define QFOC_SIM_SCENARIO_H

#include <stdbool.h>
#include <stdint.h>

#include "drive_sim.h"

#define SCN_MAX_METRICS 32
#define SCN_MAX_EVENTS 16

/** A parameter table and the motor it was generated for (tables/manifest.txt). */
typedef struct {
    const char *name;                   /**< table name, e.g. "reference" */
    const qfoc_param_table_t *table;    /**< the generated table */
    const char *motor_file;             /**< its motor file */
    const char *overrides;              /**< space-separated SECTION.KEY=VALUE, or "" */
} scn_table_t;

/** One measured figure and its target. */
typedef struct {
    char key[40];        /**< identifier, e.g. "t_closed_loop_s" */
    char label[96];      /**< what it is, for the report */
    char unit[16];
    double value;        /**< NAN: not measurable (never reached): fails any target */
    double min;          /**< NAN: no lower bound */
    double max;          /**< NAN: no upper bound */
    int pass;            /**< 1 pass, 0 fail, -1 informative (no target) */
} scn_metric_t;

typedef struct {
    double t_s;
    char label[64];
} scn_event_t;

/** Further start conditions of the campaign's axes (scn_opts_t.start_ext). */
typedef struct {
    double dead_time_ratio;  /**< plant dead time = ratio x the table's dead-time compensation
                                  (svpwm.dt_comp) */
    double t_break_nm;       /**< breakaway torque (static friction) of the plant, N m (0: none) */
    double w0_frac;          /**< the rotor's speed when the run command comes, a fraction of the
                                  rated speed (0: standing; else the command waits for STOP and
                                  the rotor coasts at this speed: a flying start, REQ-DRV-027) */
} scn_start_ext_t;

/** Run options. */
typedef struct {
    const char *out_dir;       /**< NULL: no files; else metrics.json, trace.csv, zoom.csv */
    const char *targets_file;  /**< specs/scenarios.toml; NULL: every metric informative */
    const char *name;          /**< output name (section of the targets); NULL: the scenario */
    bool progress;             /**< progress line on stderr */
    int index;                 /**< this run's number, for the progress line (1-based) */
    int count;                 /**< runs in the batch */
    const scn_start_ext_t *start_ext;  /**< scn_run_start(): the plant's dead time and
                                            breakaway torque; NULL: the motor file's dead
                                            time, no breakaway torque */
} scn_opts_t;

/** Result of one scenario run. */
typedef struct {
    char name[64];
    char title[128];
    char description[800];
    char requirements[64];
    char motor[96];
    char table[32];
    double f_pwm_hz;
    double vdc_v;
    double t_end_s;
    double zoom_t0_s;
    double zoom_t1_s;
    char compare_file[32];     /**< "" or the comparison trace (pulsating_load) */
    char compare_label[64];
    scn_metric_t m[SCN_MAX_METRICS];
    int n_metrics;
    scn_event_t ev[SCN_MAX_EVENTS];
    int n_events;
    bool pass;                 /**< every metric with a target passes */
} scn_result_t;

/** Randomised start conditions of the robustness campaign (plant errors are relative). */
typedef struct {
    double rs_err;       /**< plant R_s = (1 + rs_err) x the table's motor */
    double ld_err;
    double lq_err;
    double psi_err;
    double load_nm;      /**< mean compressor load */
    double vdc_v;
    double noise_a;      /**< current-sample noise, A rms */
    double theta0_deg;   /**< initial electrical rotor angle */
    uint32_t seed;       /**< noise seed */
} scn_start_t;

/** Names of the scenarios that scn_run() knows, NULL-terminated. */
extern const char *const scn_names[];

/**
 * @brief Run one scenario with a table.
 * @return 0 when the run was made (r->pass tells the verdict); -1 on a bad scenario
 *         name, a motor file that cannot be read or an output that cannot be written.
 */
int scn_run(const char *scenario, const scn_table_t *tab, const scn_opts_t *o, scn_result_t *r);

/**
 * @brief One cold start of the robustness campaign: cold_start with the start
 *        conditions st (parameter errors in the plant, load, bus, noise, initial angle)
 *        and o->start_ext (dead time, breakaway torque).
 */
int scn_run_start(const scn_table_t *tab, const scn_start_t *st, const scn_opts_t *o,
                  scn_result_t *r);

/** The motor of a table: its motor file with the table's overrides; 0, or -1 when the
    file cannot be read or an override is malformed. */
int scn_table_motor(const scn_table_t *tab, sim_motor_t *m);

/** The plant's single-shunt sensing for a single-shunt table, as every run on it is rigged
    (the demonstration, the fault campaign, the target test's recording): the DC-link current
    rings for as long as the table's settle time allows after the motor's dead time, at half
    the step and 2 MHz, and is sampled over the table's sample time (specs/reference-motor.md
    section 2).  Sets cfg->shunt only. */
void scn_shunt_plant(sim_cfg_t *cfg, const qfoc_param_table_t *table, const sim_motor_t *m);

/** The value of metric key, NAN when absent. */
double scn_value(const scn_result_t *r, const char *key);

/** Write r as metrics.json into dir; 0 or -1. */
int scn_write_json(const scn_result_t *r, const char *dir);

#endif /* QFOC_SIM_SCENARIO_H */
