/**
 * @file demo.c
 * @brief The demonstration's simulation runner (make demo): every scenario of
 *        scenario.h on the reference motor's table, the cold start on every other table
 *        of tables/manifest.txt, each into its own directory with metrics.json,
 *        trace.csv and zoom.csv; then summary.json.  tools/demo/demo_report.py makes the
 *        report from them.
 *
 * usage: qfoc_demo [--out DIR] [--targets FILE] [--only NAME] [--quiet]
 *   --out DIR       output root (default build/demo)
 *   --targets FILE  scenario targets (default specs/scenarios.toml)
 *   --only NAME     run one output (e.g. fault_ov, cold_start_traction350) only
 *   --quiet         no progress line
 * Exit: 0 when every run was made (the verdicts are in the metrics), 1 on an error.
 */
#define _POSIX_C_SOURCE 200809L  /* clock_gettime, fork, mkdir */

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "scenario.h"
#include "tables_registry.h"

#define MAX_RUNS 64

typedef struct {
    const char *scenario;
    const scn_table_t *tab;
    char name[64];
} run_t;

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

int main(int argc, char **argv)
{
    const char *out = "build/demo";
    const char *targets = "specs/scenarios.toml";
    const char *only = NULL;
    bool quiet = false;
    run_t runs[MAX_RUNS];
    int n = 0;
    int rc = 0;
    int k;
    int a;
    double t0;
    FILE *f;
    char path[600];
    static scn_result_t r;

    for (a = 1; a < argc; a++) {
        if (strcmp(argv[a], "--out") == 0 && a + 1 < argc) {
            out = argv[++a];
        } else if (strcmp(argv[a], "--targets") == 0 && a + 1 < argc) {
            targets = argv[++a];
        } else if (strcmp(argv[a], "--only") == 0 && a + 1 < argc) {
            only = argv[++a];
        } else if (strcmp(argv[a], "--quiet") == 0) {
            quiet = true;
        } else {
            fprintf(stderr, "usage: qfoc_demo [--out DIR] [--targets FILE] [--only NAME] [--quiet]\n");
            return 1;
        }
    }
    /* every scenario on the first table of the manifest (the reference motor) */
    for (k = 0; scn_names[k] != NULL; k++) {
        runs[n].scenario = scn_names[k];
        runs[n].tab = &scn_tables[0];
        snprintf(runs[n].name, sizeof runs[n].name, "%s", scn_names[k]);
        n++;
    }
    /* the cold start on every other table: variants and other motors */
    for (k = 1; k < scn_n_tables && n < MAX_RUNS; k++) {
        runs[n].scenario = "cold_start";
        runs[n].tab = &scn_tables[k];
        snprintf(runs[n].name, sizeof runs[n].name, "cold_start_%s", scn_tables[k].name);
        n++;
    }
    /* a single-shunt table of the reference motor: the pulsating load with torque
       compensation, the controlled stop on a lost link with the restart and the speed changes
       to 8000 rpm on it too, against the targets of the two-sensor runs (REQ-SCN-017) */
    for (k = 1; k < scn_n_tables && n + 3 <= MAX_RUNS; k++) {
        static const char *const shunt_scn[3] = { "pulsating_load", "fault_link", "speed_steps" };
        int j;
        if (scn_tables[k].table->drive.sensing != QFOC_SENSING_SHUNT ||
            strcmp(scn_tables[k].motor_file, scn_tables[0].motor_file) != 0) {
            continue;
        }
        for (j = 0; j < 3; j++) {
            runs[n].scenario = shunt_scn[j];
            runs[n].tab = &scn_tables[k];
            snprintf(runs[n].name, sizeof runs[n].name, "%s_%s", shunt_scn[j], scn_tables[k].name);
            n++;
        }
    }
    t0 = now_s();
    for (k = 0; k < n; k++) {
        scn_opts_t o;
        char dir[600];
        if (only != NULL && strcmp(only, runs[k].name) != 0) {
            continue;
        }
        snprintf(dir, sizeof dir, "%s/%s", out, runs[k].name);
        memset(&o, 0, sizeof o);
        o.out_dir = dir;
        o.targets_file = targets;
        o.name = runs[k].name;
        o.progress = !quiet;
        o.index = k + 1;
        o.count = n;
        if (scn_run(runs[k].scenario, runs[k].tab, &o, &r) != 0) {
            fprintf(stderr, "%s: the run failed\n", runs[k].name);
            rc = 1;
        }
    }
    snprintf(path, sizeof path, "%s/summary.json", out);
    f = fopen(path, "w");
    if (f == NULL) {
        fprintf(stderr, "%s: cannot write\n", path);
        return 1;
    }
    fputs("{\n  \"scenarios\": [", f);
    {
        int first = 1;
        for (k = 0; k < n; k++) {
            if (only == NULL || strcmp(only, runs[k].name) == 0) {
                fprintf(f, "%s\"%s\"", first ? "" : ", ", runs[k].name);
                first = 0;
            }
        }
    }
    fprintf(f, "],\n  \"sim_wall_s\": %.2f,\n  \"robustness\": \"../robustness/campaign.json\"\n}\n",
            now_s() - t0);
    fclose(f);
    return rc;
}
