/**
 * @file robust.c
 * @brief The robustness campaign (make robustness): cold starts with the plant's
 *        parameters off the table's, random load, bus, ADC noise and initial rotor angle,
 *        along the axes below (each a block of runs); every run is defined by its seed
 *        alone, so any run can be replayed exactly (--replay SEED) with its traces.
 *
 * Axes (the seed of run i of axis a is a x 100000 + seed0 + i; axis 0 keeps the seeds and
 * draws the campaign had before the axes, so its runs are unchanged):
 *   base       reference table: R_s +-30 %, L_d and L_q +-20 %, psi_f +-10 %, load 0..100 %
 *              of the nominal torque, bus 250..420 V, noise 0..0.1 A rms, any initial angle
 *   dead_time  base + the inverter's real dead time 0..2 x the table's compensation
 *   breakaway  base + a breakaway torque (static friction) 0..60 % of the nominal torque
 *   flux_rs    base with psi_f +-15 % (R_s +-30 %)
 *   low_flux   the low-flux motor (table lowflux: back-EMF at the hand-over within 3 x the
 *              dead-time voltage error), base draws
 *   low_flux_dead_time  low_flux + the dead time 0..2 x the compensation
 *   combined   every axis at once, on the reference or the low-flux motor
 *   flying     a restart with the rotor coasting at -30..+60 % of the rated speed, light load
 *              (0..20 % of nominal), the reference or the low-flux motor (REQ-DRV-027)
 *   ecomp800   a third motor, the 800 V e-compressor (table ecomp800, L_q / L_d = 2.6, bus
 *              650..900 V): every axis at once (psi_f +-15 %, dead time 0..2 x, breakaway
 *              0..60 %) with the base draws
 *
 * usage: qfoc_robust --count N [--axis-count M] [--seed0 S] [--jobs J] [--out DIR]
 *                    [--targets FILE]
 *        qfoc_robust --replay SEED [--out DIR] [--targets FILE]
 * N runs of the base axis (default 200), then M runs of each further axis (default 100;
 * 0: the base axis alone).  Writes DIR/runs.csv (one row per run), DIR/campaign.json (count
 * and successes of the base axis, the REQ-SCN-011 campaign; the totals; rates per axis,
 * failure kinds, false faults, ranges, worst cases) and DIR/replay_<seed>/ for the worst
 * case of each axis (metrics.json, trace.csv, zoom.csv).
 * A start succeeds when every target of the section [robust_start] of
 * specs/scenarios.toml is met.  Exit: 0 when every start (of every axis) succeeded, 1 otherwise,
 * 2 on an error.
 *
 * Methods: 1b uniform draws over the classes of the plant's deviation from the table
 * (R_s +-30 %, L_d and L_q +-20 %, psi_f +-10 %), load 0 .. nominal, bus 250 .. 420 V,
 * noise 0 .. 0.1 A rms and any initial angle, each start one draw of them all, and the
 * axes' classes (dead time, breakaway, low flux, flying restart, the 800 V motor); 1d
 * parameter errors of the table against the motor, ADC noise, an uncompensated dead
 * time and static friction: the errors a table meets on a real drive (the corners of
 * the ranges are test_scn_011_robust_corners)
 */
#define _POSIX_C_SOURCE 200809L  /* clock_gettime, fork, mkdir */

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>
#include <math.h>

#include "scenario.h"
#include "tables_registry.h"

/* Ranges of the base axis (the robustness requirement, REQ-SCN-011). */
#define RS_ERR 0.30
#define LDQ_ERR 0.20
#define PSI_ERR 0.10
#define VDC_MIN 250.0
#define VDC_MAX 420.0
#define NOISE_MAX 0.10      /* A rms: 5 ADC codes at 40 A full scale */
#define N_WORST 8
#define AXIS_SEEDS 100000L  /* seeds of axis a: a x AXIS_SEEDS + seed0 + i */
#define N_KINDS 8

typedef struct {
    const char *name;
    const char *what;
    const char *table;     /* table name; NULL: the reference or the low-flux table at random */
    double psi_err;        /* psi_f error range +- */
    double dt_lo;          /* plant dead time / the table's compensation: range */
    double dt_hi;
    double brk_max;        /* breakaway torque: up to this fraction of the nominal torque */
    double w0_lo;          /* speed at the run command / rated speed: range (0, 0: standing) */
    double w0_hi;
    double load_hi;        /* load: up to this fraction of the nominal torque */
} axis_t;

static const axis_t axes[] = {
    { "base", "the base draws (R_s +-30 %, L_d, L_q +-20 %, psi_f +-10 %, load 0..100 % of nominal, "
              "bus 250..420 V, noise 0..0.1 A rms, any initial angle), reference table",
      "reference", PSI_ERR, 1.0, 1.0, 0.0, 0.0, 0.0, 1.0 },
    { "dead_time", "base + the inverter's dead time 0..2 x the table's dead-time compensation",
      "reference", PSI_ERR, 0.0, 2.0, 0.0, 0.0, 0.0, 1.0 },
    { "breakaway", "base + a breakaway torque (static friction) 0..60 % of the nominal torque",
      "reference", PSI_ERR, 1.0, 1.0, 0.6, 0.0, 0.0, 1.0 },
    { "flux_rs", "base with psi_f +-15 % (R_s +-30 %)", "reference", 0.15, 1.0, 1.0, 0.0, 0.0, 0.0, 1.0 },
    { "low_flux", "the low-flux motor (back-EMF at the 1000 rpm hand-over 18.8 V, within 3 x its "
                  "6.4 V dead-time voltage error), base draws", "lowflux", PSI_ERR, 1.0, 1.0, 0.0, 0.0, 0.0, 1.0 },
    { "low_flux_dead_time", "low_flux + the inverter's dead time 0..2 x the compensation",
      "lowflux", PSI_ERR, 0.0, 2.0, 0.0, 0.0, 0.0, 1.0 },
    { "combined", "every axis at once (psi_f +-15 %, dead time 0..2 x, breakaway 0..60 %), the "
                  "reference or the low-flux motor", NULL, 0.15, 0.0, 2.0, 0.6, 0.0, 0.0, 1.0 },
    { "flying", "a restart with the rotor still coasting at -30..+60 % of the rated speed and a "
                "light load (0..20 % of nominal: the pressure equalised), base draws otherwise, the "
                "reference or the low-flux motor (flying start, REQ-DRV-027)",
      NULL, PSI_ERR, 1.0, 1.0, 0.0, -0.3, 0.6, 0.2 },
    { "ecomp800", "a third motor, the 800 V e-compressor (L_q / L_d = 2.6, 16 kHz, bus drawn over "
                  "its 650..900 V): every axis at once (psi_f +-15 %, dead time 0..2 x, breakaway "
                  "0..60 %), base draws otherwise", "ecomp800", 0.15, 0.0, 2.0, 0.6, 0.0, 0.0, 1.0 },
};
#define N_AXES ((int)(sizeof axes / sizeof axes[0]))

typedef struct {
    const scn_table_t *tab;
    double nominal_nm;
    double vdc_min;        /* the motor file's bus range, V */
    double vdc_max;
} motor_t;

#define N_MOTORS 3
static const char *const motor_names[N_MOTORS] = { "reference", "lowflux", "ecomp800" };
static motor_t motors[N_MOTORS];

typedef struct {
    scn_start_t st;
    scn_start_ext_t x;
    int axis;
    int motor;             /* index in motors[] */
    double brk_frac;       /* breakaway torque / nominal torque */
    int success;
    double t_cl;
    double t_reach;
    double overshoot;
    double ss_err;
    double ss_err_max;
    double ang_rms;
    double ang_max;
    double i_peak;
    double faults;
    char reason[96];
    char kind[48];         /* "" (success), "fault <bits>" or the first metric off target */
} rec_t;

/* splitmix64: the run's draws depend on its seed only */
static uint64_t mix(uint64_t *s)
{
    uint64_t z = (*s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

static double uni(uint64_t *s, double lo, double hi)
{
    return lo + (hi - lo) * ((double)(mix(s) >> 11) / 9007199254740992.0);
}

static const char *const fault_bits[] = { "OC", "OV", "UV", "OT_IPM", "OT_PCB", "STALL", "PHASE",
                                           "OFFSET", "LINK", "PARAM", "TIMING" };

/* The run of a seed: its axis, then the base draws in their order, then the axis's own */
static int draw(uint32_t seed, rec_t *r)
{
    uint64_t s = seed;
    const long a = (long)seed / AXIS_SEEDS;
    const axis_t *ax;
    double load_frac;
    if (a >= N_AXES) {
        return -1;
    }
    ax = &axes[a];
    r->axis = (int)a;
    r->st.rs_err = uni(&s, -RS_ERR, RS_ERR);
    r->st.ld_err = uni(&s, -LDQ_ERR, LDQ_ERR);
    r->st.lq_err = uni(&s, -LDQ_ERR, LDQ_ERR);
    r->st.psi_err = uni(&s, -ax->psi_err, ax->psi_err);
    load_frac = uni(&s, 0.0, ax->load_hi);
    r->st.vdc_v = uni(&s, VDC_MIN, VDC_MAX);
    r->st.noise_a = uni(&s, 0.0, NOISE_MAX);
    r->st.theta0_deg = uni(&s, 0.0, 360.0);
    r->st.seed = seed;
    r->x.dead_time_ratio = 1.0;
    r->brk_frac = 0.0;
    if (ax->dt_hi > ax->dt_lo) {
        r->x.dead_time_ratio = uni(&s, ax->dt_lo, ax->dt_hi);
    }
    if (ax->brk_max > 0.0) {
        r->brk_frac = uni(&s, 0.0, ax->brk_max);
    }
    r->x.w0_frac = 0.0;
    if (ax->w0_hi > ax->w0_lo) {
        r->x.w0_frac = uni(&s, ax->w0_lo, ax->w0_hi);
    }
    if (ax->table == NULL) {
        r->motor = (int)(mix(&s) >> 63);   /* the reference or the low-flux motor */
    } else {
        int k;
        r->motor = 0;
        for (k = 0; k < N_MOTORS; k++) {
            r->motor = (strcmp(ax->table, motor_names[k]) == 0) ? k : r->motor;
        }
    }
    if (motors[r->motor].vdc_min != VDC_MIN || motors[r->motor].vdc_max != VDC_MAX) {
        /* the same draw over the motor's own bus range (the base axis's motors have 250..420 V) */
        const motor_t *m = &motors[r->motor];
        r->st.vdc_v = m->vdc_min + (r->st.vdc_v - VDC_MIN) * (m->vdc_max - m->vdc_min) / (VDC_MAX - VDC_MIN);
    }
    r->st.load_nm = load_frac * motors[r->motor].nominal_nm;
    r->x.t_break_nm = r->brk_frac * motors[r->motor].nominal_nm;
    return 0;
}

/* The tables of the campaign and their motors' nominal torques. */
static int find_motors(void)
{
    const char *const *names = motor_names;
    int k;
    int t;
    for (k = 0; k < N_MOTORS; k++) {
        sim_motor_t m;
        motors[k].tab = NULL;
        for (t = 0; t < scn_n_tables; t++) {
            if (strcmp(scn_tables[t].name, names[k]) == 0) {
                motors[k].tab = &scn_tables[t];
            }
        }
        if (motors[k].tab == NULL || sim_motor_load(motors[k].tab->motor_file, &m) != 0 ||
            m.nominal_torque_nm <= 0.0) {
            fprintf(stderr, "qfoc_robust: table %s or its motor file missing\n", names[k]);
            return -1;
        }
        motors[k].nominal_nm = m.nominal_torque_nm;
        motors[k].vdc_min = m.vdc_min_v;
        motors[k].vdc_max = m.vdc_max_v;
    }
    return 0;
}

static int one(uint32_t seed, const char *targets, const char *dir, rec_t *rec)
{
    static scn_result_t r;
    scn_opts_t o;
    int k;
    int rc;
    memset(&o, 0, sizeof o);
    memset(rec, 0, sizeof *rec);
    if (draw(seed, rec) != 0) {
        fprintf(stderr, "qfoc_robust: seed %u is not in any axis\n", (unsigned)seed);
        return -1;
    }
    o.targets_file = targets;
    o.out_dir = dir;
    /* a flying start has its own section (it may close the loop at once) */
    o.name = (rec->x.w0_frac != 0.0) ? "robust_flying" : "robust_start";
    o.start_ext = &rec->x;
    rc = scn_run_start(motors[rec->motor].tab, &rec->st, &o, &r);
    rec->success = (rc == 0 && r.pass) ? 1 : 0;
    rec->t_cl = scn_value(&r, "t_closed_loop_s");
    rec->t_reach = scn_value(&r, "t_target_s");
    rec->overshoot = scn_value(&r, "overshoot_pct");
    rec->ss_err = scn_value(&r, "ss_err_pct");
    rec->ss_err_max = scn_value(&r, "ss_err_max_pct");
    rec->ang_rms = scn_value(&r, "angle_err_rms_deg");
    rec->ang_max = scn_value(&r, "angle_err_max_deg");
    rec->i_peak = scn_value(&r, "i_peak_a");
    rec->faults = scn_value(&r, "faults");
    for (k = 0; k < r.n_metrics; k++) {
        if (r.m[k].pass == 0 && rec->reason[0] == '\0') {
            snprintf(rec->reason, sizeof rec->reason, "%s = %.4g", r.m[k].key, r.m[k].value);
            snprintf(rec->kind, sizeof rec->kind, "%s", r.m[k].key);
        }
    }
    if (rec->faults > 0.0) {
        const unsigned w = (unsigned)rec->faults;
        size_t n;
        snprintf(rec->kind, sizeof rec->kind, "fault ");
        for (k = 0; k < 11; k++) {
            if ((w >> k) & 1u) {
                n = strlen(rec->kind);
                snprintf(rec->kind + n, sizeof rec->kind - n, "%s%s",
                         (rec->kind[n - 1] == ' ') ? "" : "+", fault_bits[k]);
            }
        }
    }
    if (rec->success) {
        rec->kind[0] = '\0';
    }
    return rc;
}

/* worst first: failures, then the largest angle error (the nearest to losing the rotor),
   then the longest time to the target */
static int worse(const void *a, const void *b)
{
    const rec_t *x = a;
    const rec_t *y = b;
    const double ax = isnan(x->ang_max) ? 1e9 : x->ang_max;
    const double ay = isnan(y->ang_max) ? 1e9 : y->ang_max;
    const double tx = isnan(x->t_reach) ? 1e9 : x->t_reach;
    const double ty = isnan(y->t_reach) ? 1e9 : y->t_reach;
    int c;
    if (x->success != y->success) {
        c = x->success - y->success;
    } else if (ax != ay) {
        c = (ax > ay) ? -1 : 1;
    } else {
        c = (tx > ty) ? -1 : ((tx < ty) ? 1 : (int)x->st.seed - (int)y->st.seed);
    }
    return c;
}

static void num(FILE *f, double v)
{
    if (isnan(v)) {
        fputs("null", f);
    } else {
        fprintf(f, "%.5g", v);
    }
}

static void json_rec(FILE *f, const rec_t *r)
{
    fprintf(f, "{\"seed\": %u, \"axis\": \"%s\", \"table\": \"%s\", \"success\": %s, \"rs_err\": %.4f, "
               "\"ld_err\": %.4f, \"lq_err\": %.4f, \"psi_err\": %.4f, \"load_nm\": %.3f, \"vdc_v\": %.1f, "
               "\"noise_a\": %.4f, \"theta0_deg\": %.1f, \"dead_time_ratio\": %.4f, \"t_break_nm\": %.3f, "
               "\"t_closed_loop_s\": ",
            (unsigned)r->st.seed, axes[r->axis].name, motors[r->motor].tab->name,
            r->success ? "true" : "false", r->st.rs_err, r->st.ld_err, r->st.lq_err, r->st.psi_err,
            r->st.load_nm, r->st.vdc_v, r->st.noise_a, r->st.theta0_deg, r->x.dead_time_ratio,
            r->x.t_break_nm);
    num(f, r->t_cl);
    fputs(", \"t_reach_s\": ", f);
    num(f, r->t_reach);
    fputs(", \"overshoot_pct\": ", f);
    num(f, r->overshoot);
    fputs(", \"ss_err_pct\": ", f);
    num(f, r->ss_err);
    fputs(", \"angle_err_max_deg\": ", f);
    num(f, r->ang_max);
    fputs(", \"i_peak_a\": ", f);
    num(f, r->i_peak);
    fprintf(f, ", \"fault\": %.0f, \"kind\": \"%s\", \"reason\": \"%s\", "
               "\"replay\": \"make robustness-replay SEED=%u\"}",
            r->faults, r->kind, r->reason, (unsigned)r->st.seed);
}

/* Per-axis figures */
typedef struct {
    long runs;
    long ok;
    long reached;          /* the target speed reached (within 2 %) */
    long faulted;          /* a fault raised: every fault is false here (the campaign adds no fault) */
    long faulted_reached;  /* ... in a run that reached the target */
    char kind[N_KINDS][48];
    long kind_n[N_KINDS];
    int n_kinds;
    long first;            /* index of its first record after the sort (worst first) */
} stat_t;

static void stat_add(stat_t *a, const rec_t *r)
{
    const int reached = !isnan(r->t_reach);
    int k;
    a->runs++;
    a->ok += r->success;
    a->reached += reached;
    a->faulted += (r->faults > 0.0) ? 1 : 0;
    a->faulted_reached += (r->faults > 0.0 && reached) ? 1 : 0;
    if (!r->success) {
        for (k = 0; k < a->n_kinds && strcmp(a->kind[k], r->kind) != 0; k++) {
        }
        if (k == a->n_kinds && k < N_KINDS) {
            snprintf(a->kind[k], sizeof a->kind[k], "%s", r->kind);
            a->n_kinds++;
        }
        if (k < N_KINDS) {
            a->kind_n[k]++;
        }
    }
}

/* worst first within each axis, the axes in their order */
static int by_axis(const void *a, const void *b)
{
    const rec_t *x = a;
    const rec_t *y = b;
    return (x->axis != y->axis) ? x->axis - y->axis : worse(a, b);
}

static int lowflux_seen(const rec_t *recs, long count)
{
    long k;
    for (k = 0; k < count && recs[k].motor == 0; k++) {
    }
    return k < count;
}

int main(int argc, char **argv)
{
    const char *out = "build/robustness";
    const char *targets = "specs/scenarios.toml";
    long count = 200;
    long axis_count = 100;
    long total;
    long ok_base = 0;
    long seed0 = 1;
    long replay = -1;
    int jobs = 1;
    rec_t *recs;
    uint32_t *seeds;
    stat_t st[N_AXES];
    long k;
    int j;
    int a;
    long ok = 0;
    char path[700];
    FILE *f;
    struct timespec t0;
    struct timespec t1;

    for (a = 1; a < argc; a++) {
        if (strcmp(argv[a], "--count") == 0 && a + 1 < argc) {
            count = strtol(argv[++a], NULL, 10);
        } else if (strcmp(argv[a], "--axis-count") == 0 && a + 1 < argc) {
            axis_count = strtol(argv[++a], NULL, 10);
        } else if (strcmp(argv[a], "--seed0") == 0 && a + 1 < argc) {
            seed0 = strtol(argv[++a], NULL, 10);
        } else if (strcmp(argv[a], "--jobs") == 0 && a + 1 < argc) {
            jobs = (int)strtol(argv[++a], NULL, 10);
        } else if (strcmp(argv[a], "--out") == 0 && a + 1 < argc) {
            out = argv[++a];
        } else if (strcmp(argv[a], "--targets") == 0 && a + 1 < argc) {
            targets = argv[++a];
        } else if (strcmp(argv[a], "--replay") == 0 && a + 1 < argc) {
            replay = strtol(argv[++a], NULL, 10);
        } else {
            fprintf(stderr, "usage: qfoc_robust --count N [--axis-count M] [--seed0 S] [--jobs J] "
                            "[--out DIR] [--targets FILE] | --replay SEED [--out DIR]\n");
            return 2;
        }
    }
    if (find_motors() != 0 || count < 1 || axis_count < 0 || jobs < 1 || jobs > 16 || seed0 < 0 ||
        seed0 + count > AXIS_SEEDS || seed0 + axis_count > AXIS_SEEDS) {
        fprintf(stderr, "qfoc_robust: bad arguments (seed0 + count <= %ld) or motor file\n", AXIS_SEEDS);
        return 2;
    }
    total = count + (N_AXES - 1) * axis_count;
    mkdir(out, 0777);
    if (replay >= 0) {
        rec_t r;
        snprintf(path, sizeof path, "%s/replay_%ld", out, replay);
        if (one((uint32_t)replay, targets, path, &r) != 0) {
            return 2;
        }
        printf("replay of seed %ld (axis %s, table %s): %s%s\n", replay, axes[r.axis].name,
               motors[r.motor].tab->name, r.success ? "success" : "FAILED: ",
               r.success ? "" : r.reason);
        return r.success ? 0 : 1;
    }
    recs = calloc((size_t)total, sizeof *recs);
    seeds = calloc((size_t)total, sizeof *seeds);
    if (recs == NULL || seeds == NULL) {
        return 2;
    }
    for (k = 0; k < total; k++) {
        seeds[k] = (k < count) ? (uint32_t)(seed0 + k)
                               : (uint32_t)((1 + (k - count) / axis_count) * AXIS_SEEDS + seed0 +
                                            (k - count) % axis_count);
    }
    count = total;  /* from here on: every run */
    clock_gettime(CLOCK_MONOTONIC, &t0);
    /* jobs processes, run k in process k % jobs; each writes its records to a file */
    for (j = 0; j < jobs; j++) {
        const pid_t pid = fork();
        if (pid == 0) {
            snprintf(path, sizeof path, "%s/.part%d", out, j);
            f = fopen(path, "wb");
            for (k = j; k < count && f != NULL; k += jobs) {
                rec_t r;
                if (one(seeds[k], targets, NULL, &r) != 0) {
                    _exit(2);
                }
                fwrite(&r, sizeof r, 1, f);
                if (j == 0) {
                    fprintf(stderr, "\rrobustness: %ld of %ld cold starts", k + 1, count);
                    fflush(stderr);
                }
            }
            _exit((f != NULL && fclose(f) == 0) ? 0 : 2);
        } else if (pid < 0) {
            return 2;
        }
    }
    for (j = 0; j < jobs; j++) {
        int status;
        if (wait(&status) < 0 || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
            fprintf(stderr, "\nqfoc_robust: a worker failed\n");
            return 2;
        }
    }
    clock_gettime(CLOCK_MONOTONIC, &t1);
    fprintf(stderr, "\rrobustness: %ld of %ld cold starts\n", count, count);
    for (j = 0; j < jobs; j++) {
        snprintf(path, sizeof path, "%s/.part%d", out, j);
        f = fopen(path, "rb");
        for (k = j; k < count && f != NULL; k += jobs) {
            if (fread(&recs[k], sizeof recs[k], 1, f) != 1) {
                return 2;
            }
        }
        if (f != NULL) {
            fclose(f);
        }
        remove(path);
    }
    snprintf(path, sizeof path, "%s/runs.csv", out);
    f = fopen(path, "w");
    if (f == NULL) {
        return 2;
    }
    fputs("seed,axis,table,rs_err,ld_err,lq_err,psi_err,load_nm,vdc_v,noise_a,theta0_deg,"
          "dead_time_ratio,t_break_nm,t_break_frac,success,t_closed_loop_s,t_reach_s,overshoot_pct,ss_err_pct,"
          "ss_err_max_pct,angle_err_rms_deg,angle_err_max_deg,i_peak_a,fault,kind,reason\n", f);
    memset(st, 0, sizeof st);
    for (k = 0; k < count; k++) {
        const rec_t *r = &recs[k];
        ok += r->success;
        ok_base += (r->axis == 0) ? r->success : 0;
        stat_add(&st[r->axis], r);
        fprintf(f, "%u,%s,%s,%.4f,%.4f,%.4f,%.4f,%.3f,%.1f,%.4f,%.1f,%.4f,%.3f,%.4f,%d,%.4g,%.4g,%.4g,%.4g,"
                   "%.4g,%.4g,%.4g,%.4g,%.0f,%s,%s\n",
                (unsigned)r->st.seed, axes[r->axis].name, motors[r->motor].tab->name, r->st.rs_err,
                r->st.ld_err, r->st.lq_err, r->st.psi_err, r->st.load_nm, r->st.vdc_v, r->st.noise_a,
                r->st.theta0_deg, r->x.dead_time_ratio, r->x.t_break_nm, r->brk_frac, r->success, r->t_cl,
                r->t_reach, r->overshoot, r->ss_err, r->ss_err_max, r->ang_rms, r->ang_max,
                r->i_peak, r->faults, r->kind, r->reason);
    }
    fclose(f);
    qsort(recs, (size_t)count, sizeof *recs, by_axis);
    for (k = count - 1; k >= 0; k--) {
        st[recs[k].axis].first = k;
    }
    snprintf(path, sizeof path, "%s/campaign.json", out);
    f = fopen(path, "w");
    if (f == NULL) {
        return 2;
    }
    /* count, successes, rate_pct: the base axis (REQ-SCN-011's ranges); all: every axis */
    fprintf(f, "{\n  \"count\": %ld,\n  \"seed0\": %ld,\n  \"axis_count\": %ld,\n  \"successes\": %ld,\n"
               "  \"rate_pct\": %.2f,\n  \"all\": {\"count\": %ld, \"successes\": %ld, \"rate_pct\": %.2f},\n"
               "  \"wall_s\": %.1f,\n  \"table\": \"%s\",\n",
            st[0].runs, seed0, axis_count, ok_base, 100.0 * (double)ok_base / (double)st[0].runs,
            count, ok, 100.0 * (double)ok / (double)count,
            (double)(t1.tv_sec - t0.tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec),
            lowflux_seen(recs, count) ? "reference, lowflux" : "reference");
    fprintf(f, "  \"ranges\": {\"rs\": [%.2f, %.2f], \"ld\": [%.2f, %.2f], \"lq\": [%.2f, %.2f], "
               "\"psi_f\": [%.2f, %.2f], \"load_frac\": [0, 1], \"vdc_v\": [%.0f, %.0f], "
               "\"noise_a_rms\": [0, %.2f], \"theta0_deg\": [0, 360]},\n",
            -RS_ERR, RS_ERR, -LDQ_ERR, LDQ_ERR, -LDQ_ERR, LDQ_ERR, -PSI_ERR, PSI_ERR, VDC_MIN, VDC_MAX,
            NOISE_MAX);
    fputs("  \"criteria\": \"a start succeeds when it meets every target of [robust_start] in "
          "specs/scenarios.toml: closed loop reached, the target speed within 2 % in time, no "
          "overshoot above the limit, the speed held within 2 % over the last second, no fault\",\n",
          f);
    fputs("  \"goal\": \"100 % of the starts succeed on every axis, and no false fault (no fault is "
          "injected: every fault raised is false) in the runs that reach the target speed\",\n", f);
    fputs("  \"axes\": [", f);
    for (a = 0, j = 0; a < N_AXES; a++) {
        const stat_t *x = &st[a];
        const axis_t *ax = &axes[a];
        int n;
        if (x->runs == 0) {
            continue;
        }
        fprintf(f, "%s\n    {\"axis\": \"%s\", \"what\": \"%s\", \"table\": \"%s\", "
                   "\"psi_err\": [%.2f, %.2f], \"dead_time_ratio\": [%.2f, %.2f], "
                   "\"t_break_frac\": [0, %.2f], \"runs\": %ld, \"successes\": %ld, \"rate_pct\": %.2f, "
                   "\"reached\": %ld, \"faulted\": %ld, \"false_faults_reached\": %ld, \"kinds\": {",
                (j++ > 0) ? "," : "", ax->name, ax->what,
                (ax->table != NULL) ? ax->table : "reference, lowflux", -ax->psi_err, ax->psi_err,
                ax->dt_lo, ax->dt_hi, ax->brk_max, x->runs, x->ok,
                100.0 * (double)x->ok / (double)x->runs, x->reached, x->faulted, x->faulted_reached);
        for (n = 0; n < x->n_kinds; n++) {
            fprintf(f, "%s\"%s\": %ld", (n > 0) ? ", " : "", x->kind[n], x->kind_n[n]);
        }
        fputs("}, \"worst\": [", f);
        for (k = x->first; k < count && k < x->first + 3 && recs[k].axis == a; k++) {
            fprintf(f, "%s%u", (k > x->first) ? ", " : "", (unsigned)recs[k].st.seed);
        }
        fputs("]}", f);
    }
    fputs("\n  ],\n  \"worst\": [\n", f);
    /* the worst runs overall, worst first */
    {
        rec_t *w = malloc((size_t)count * sizeof *w);
        if (w == NULL) {
            return 2;
        }
        memcpy(w, recs, (size_t)count * sizeof *w);
        qsort(w, (size_t)count, sizeof *w, worse);
        for (k = 0; k < count && k < N_WORST; k++) {
            fputs((k > 0) ? ",\n    " : "    ", f);
            json_rec(f, &w[k]);
        }
        free(w);
    }
    fprintf(f, "\n  ],\n  \"replay\": \"make robustness-replay SEED=<seed>\"\n}\n");
    fclose(f);
    /* the worst case of each axis again, with its traces */
    for (a = 0; a < N_AXES; a++) {
        rec_t r;
        const rec_t *w = &recs[st[a].first];
        if (st[a].runs == 0) {
            continue;
        }
        snprintf(path, sizeof path, "%s/replay_%u", out, (unsigned)w->st.seed);
        if (one(w->st.seed, targets, path, &r) != 0 || r.success != w->success) {
            fprintf(stderr, "qfoc_robust: the replay of seed %u differs\n", (unsigned)w->st.seed);
            return 2;
        }
    }
    printf("robustness: %ld of %ld cold starts successful (%.1f %%); base axis (REQ-SCN-011): "
           "%ld of %ld\n", ok, count, 100.0 * (double)ok / (double)count, ok_base, st[0].runs);
    printf("  %-19s %5s %8s %7s %7s %12s  %-22s %s\n", "axis", "runs", "success", "rate %", "faults",
           "false fault*", "worst seeds", "failure kinds");
    for (a = 0; a < N_AXES; a++) {
        const stat_t *x = &st[a];
        char ws[64] = "";
        int n;
        if (x->runs == 0) {
            continue;
        }
        for (k = x->first; k < count && k < x->first + 3 && recs[k].axis == a; k++) {
            const size_t l = strlen(ws);
            snprintf(ws + l, sizeof ws - l, "%s%u", (l > 0) ? " " : "", (unsigned)recs[k].st.seed);
        }
        printf("  %-19s %5ld %8ld %7.1f %7ld %12ld  %-22s", axes[a].name, x->runs, x->ok,
               100.0 * (double)x->ok / (double)x->runs, x->faulted, x->faulted_reached, ws);
        for (n = 0; n < x->n_kinds; n++) {
            printf("%s%s %ld", (n > 0) ? ", " : "", x->kind[n], x->kind_n[n]);
        }
        printf("\n");
    }
    printf("  (* runs that reached the target speed and raised a fault; no fault is injected)\n");
    free(recs);
    free(seeds);
    return (ok == count) ? 0 : 1;
}
