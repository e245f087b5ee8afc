/**
 * @file robust.c
 * @brief The robustness campaign (make robustness): cold starts of the reference
 *        motor with the plant's parameters off the table's, random load, bus, ADC noise
 *        and initial rotor angle.  Every run is defined by its seed alone, so any run
 *        can be replayed exactly (--replay SEED) with its traces.
 *
 * usage: qfoc_robust --count N [--seed0 S] [--jobs J] [--out DIR] [--targets FILE]
 *        qfoc_robust --replay SEED [--out DIR] [--targets FILE]
 * Writes DIR/runs.csv (one row per run), DIR/campaign.json (rate, ranges, worst cases)
 * and DIR/replay_<seed>/ for the worst cases (metrics.json, trace.csv, zoom.csv).
 * A start succeeds when every target of the section [robust_start] of
 * specs/scenarios.toml is met.  Exit: 0 when every start succeeded, 1 otherwise,
 * 2 on an error.
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

/* Ranges of the campaign (the robustness requirement, REQ-SCN-011). */
#define RS_ERR 0.30
#define LDQ_ERR 0.20
#define PSI_ERR 0.10
#define VDC_MIN 250.0
#define VDC_MAX 420.0
#define NOISE_MAX 0.10      /* A rms: 5 ADC codes at 40 A full scale */
#define N_WORST 8
#define N_REPLAY 3

typedef struct {
    scn_start_t st;
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

static void draw(uint32_t seed, double nominal_nm, scn_start_t *st)
{
    uint64_t s = seed;
    st->rs_err = uni(&s, -RS_ERR, RS_ERR);
    st->ld_err = uni(&s, -LDQ_ERR, LDQ_ERR);
    st->lq_err = uni(&s, -LDQ_ERR, LDQ_ERR);
    st->psi_err = uni(&s, -PSI_ERR, PSI_ERR);
    st->load_nm = uni(&s, 0.0, 1.0) * nominal_nm;
    st->vdc_v = uni(&s, VDC_MIN, VDC_MAX);
    st->noise_a = uni(&s, 0.0, NOISE_MAX);
    st->theta0_deg = uni(&s, 0.0, 360.0);
    st->seed = seed;
}

static double nominal_torque(void)
{
    sim_motor_t m;
    return (sim_motor_load(scn_tables[0].motor_file, &m) == 0) ? m.nominal_torque_nm : -1.0;
}

static int one(uint32_t seed, double nominal, const char *targets, const char *dir, rec_t *rec)
{
    static scn_result_t r;
    scn_opts_t o;
    int k;
    int rc;
    memset(&o, 0, sizeof o);
    memset(rec, 0, sizeof *rec);
    o.targets_file = targets;
    o.out_dir = dir;
    o.name = "robust_start";
    draw(seed, nominal, &rec->st);
    rc = scn_run_start(&scn_tables[0], &rec->st, &o, &r);
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
        }
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
    fprintf(f, "{\"seed\": %u, \"success\": %s, \"rs_err\": %.4f, \"ld_err\": %.4f, \"lq_err\": %.4f, "
               "\"psi_err\": %.4f, \"load_nm\": %.3f, \"vdc_v\": %.1f, \"noise_a\": %.4f, "
               "\"theta0_deg\": %.1f, \"t_closed_loop_s\": ",
            (unsigned)r->st.seed, r->success ? "true" : "false", r->st.rs_err, r->st.ld_err,
            r->st.lq_err, r->st.psi_err, r->st.load_nm, r->st.vdc_v, r->st.noise_a, r->st.theta0_deg);
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
    fprintf(f, ", \"reason\": \"%s\", \"replay\": \"make robustness-replay SEED=%u\"}", r->reason,
            (unsigned)r->st.seed);
}

int main(int argc, char **argv)
{
    const char *out = "build/robustness";
    const char *targets = "specs/scenarios.toml";
    long count = 200;
    long seed0 = 1;
    long replay = -1;
    int jobs = 1;
    double nominal;
    rec_t *recs;
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
            fprintf(stderr, "usage: qfoc_robust --count N [--seed0 S] [--jobs J] [--out DIR] "
                            "[--targets FILE] | --replay SEED [--out DIR]\n");
            return 2;
        }
    }
    nominal = nominal_torque();
    if (nominal <= 0.0 || count < 1 || jobs < 1 || jobs > 16 || seed0 < 0) {
        fprintf(stderr, "qfoc_robust: bad arguments or motor file\n");
        return 2;
    }
    mkdir(out, 0777);
    if (replay >= 0) {
        rec_t r;
        snprintf(path, sizeof path, "%s/replay_%ld", out, replay);
        if (one((uint32_t)replay, nominal, targets, path, &r) != 0) {
            return 2;
        }
        printf("replay of seed %ld: %s%s%s\n", replay, r.success ? "success" : "FAILED: ",
               r.success ? "" : r.reason, "");
        return r.success ? 0 : 1;
    }
    recs = calloc((size_t)count, sizeof *recs);
    if (recs == NULL) {
        return 2;
    }
    clock_gettime(CLOCK_MONOTONIC, &t0);
    /* jobs processes, run k in process k % jobs; each writes its records to a file */
    for (j = 0; j < jobs; j++) {
        const pid_t pid = fork();
        if (pid == 0) {
            snprintf(path, sizeof path, "%s/.part%d", out, j);
            f = fopen(path, "wb");
            for (k = j; k < count && f != NULL; k += jobs) {
                rec_t r;
                if (one((uint32_t)(seed0 + k), nominal, targets, NULL, &r) != 0) {
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
        int st;
        if (wait(&st) < 0 || !WIFEXITED(st) || WEXITSTATUS(st) != 0) {
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
    fputs("seed,rs_err,ld_err,lq_err,psi_err,load_nm,vdc_v,noise_a,theta0_deg,success,"
          "t_closed_loop_s,t_reach_s,overshoot_pct,ss_err_pct,ss_err_max_pct,angle_err_rms_deg,"
          "angle_err_max_deg,i_peak_a,fault,reason\n", f);
    for (k = 0; k < count; k++) {
        const rec_t *r = &recs[k];
        ok += r->success;
        fprintf(f, "%u,%.4f,%.4f,%.4f,%.4f,%.3f,%.1f,%.4f,%.1f,%d,%.4g,%.4g,%.4g,%.4g,%.4g,%.4g,%.4g,"
                   "%.4g,%.0f,%s\n",
                (unsigned)r->st.seed, r->st.rs_err, r->st.ld_err, r->st.lq_err, r->st.psi_err,
                r->st.load_nm, r->st.vdc_v, r->st.noise_a, r->st.theta0_deg, r->success, r->t_cl,
                r->t_reach, r->overshoot, r->ss_err, r->ss_err_max, r->ang_rms, r->ang_max,
                r->i_peak, r->faults, r->reason);
    }
    fclose(f);
    qsort(recs, (size_t)count, sizeof *recs, worse);
    snprintf(path, sizeof path, "%s/campaign.json", out);
    f = fopen(path, "w");
    if (f == NULL) {
        return 2;
    }
    fprintf(f, "{\n  \"count\": %ld,\n  \"seed0\": %ld,\n  \"successes\": %ld,\n  \"rate_pct\": %.2f,\n"
               "  \"wall_s\": %.1f,\n  \"table\": \"%s\",\n",
            count, seed0, ok, 100.0 * (double)ok / (double)count,
            (double)(t1.tv_sec - t0.tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec),
            scn_tables[0].name);
    fprintf(f, "  \"ranges\": {\"rs\": [%.2f, %.2f], \"ld\": [%.2f, %.2f], \"lq\": [%.2f, %.2f], "
               "\"psi_f\": [%.2f, %.2f], \"load_nm\": [0, %.3g], \"vdc_v\": [%.0f, %.0f], "
               "\"noise_a_rms\": [0, %.2f], \"theta0_deg\": [0, 360]},\n",
            -RS_ERR, RS_ERR, -LDQ_ERR, LDQ_ERR, -LDQ_ERR, LDQ_ERR, -PSI_ERR, PSI_ERR, nominal, VDC_MIN,
            VDC_MAX, NOISE_MAX);
    fputs("  \"criteria\": \"a start succeeds when it meets every target of [robust_start] in "
          "specs/scenarios.toml: closed loop reached, the target speed within 2 % in time, no "
          "overshoot above the limit, the speed held within 2 % over the last second, no fault\",\n",
          f);
    fputs("  \"worst\": [\n", f);
    for (k = 0; k < count && k < N_WORST; k++) {
        fputs((k > 0) ? ",\n    " : "    ", f);
        json_rec(f, &recs[k]);
    }
    fprintf(f, "\n  ],\n  \"replay\": \"make robustness-replay SEED=<seed>\"\n}\n");
    fclose(f);
    /* the worst cases again, with their traces */
    for (k = 0; k < count && k < N_REPLAY; k++) {
        rec_t r;
        snprintf(path, sizeof path, "%s/replay_%u", out, (unsigned)recs[k].st.seed);
        if (one(recs[k].st.seed, nominal, targets, path, &r) != 0 || r.success != recs[k].success) {
            fprintf(stderr, "qfoc_robust: the replay of seed %u differs\n", (unsigned)recs[k].st.seed);
            return 2;
        }
    }
    printf("robustness: %ld of %ld cold starts successful (%.1f %%), worst seed %u\n", ok, count,
           100.0 * (double)ok / (double)count, (unsigned)recs[0].st.seed);
    free(recs);
    return (ok == count) ? 0 : 1;
}
