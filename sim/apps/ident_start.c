/**
 * @file ident_start.c
 * @brief The last link of the commissioning flow (make identify): the cold start of
 *        specs/scenarios.toml with each table made from an identification record
 *        (tools/tune/ident_flow.py), on the plant of the true motor.
 *
 * The registry is generated from the flow's manifest (build/identify/flow/manifest.txt):
 * a line "NAME_id MOTOR OVERRIDES" pairs the identified table with the motor file of the
 * true motor, so that the drive runs on what was measured while the plant is the motor as
 * it is.  Each run is the scenario cold_start (standstill to half the rated speed at the
 * nominal load), judged by the targets of the typed table's run: section
 * cold_start_NAME where the file has one, else cold_start.
 *
 * usage: qfoc_ident_start [--out DIR] [--targets FILE]
 * Exit: 0 when every start meets every target, 1 otherwise, 2 on an error.
 */
#include <stdio.h>
#include <string.h>

#include "scenario.h"
#include "tables_registry.h"

int main(int argc, char **argv)
{
    const char *out = NULL;
    const char *targets = "specs/scenarios.toml";
    int a, k, rc = 0;
    for (a = 1; a < argc; a++) {
        if (strcmp(argv[a], "--out") == 0 && a + 1 < argc) {
            out = argv[++a];
        } else if (strcmp(argv[a], "--targets") == 0 && a + 1 < argc) {
            targets = argv[++a];
        } else {
            fprintf(stderr, "qfoc_ident_start: unknown argument '%s'\n"
                    "usage: qfoc_ident_start [--out DIR] [--targets FILE]\n", argv[a]);
            return 2;
        }
    }
    if (scn_n_tables == 0) {
        fprintf(stderr, "qfoc_ident_start: no identified table in the registry\n");
        return 1;
    }
    for (k = 0; k < scn_n_tables; k++) {
        static scn_result_t r;
        scn_opts_t o;
        char name[64];
        char dir[600];
        size_t len = strlen(scn_tables[k].name);
        int m;
        /* NAME_id runs as cold_start_NAME: the typed table's targets */
        if (len > 3u && strcmp(scn_tables[k].name + len - 3u, "_id") == 0) {
            len -= 3u;
        }
        snprintf(name, sizeof name, "cold_start_%.*s", (int)len, scn_tables[k].name);
        memset(&o, 0, sizeof o);
        if (out != NULL) {
            snprintf(dir, sizeof dir, "%s/%s", out, scn_tables[k].name);
            o.out_dir = dir;
        }
        o.targets_file = targets;
        o.name = name;
        if (scn_run("cold_start", &scn_tables[k], &o, &r) != 0) {
            fprintf(stderr, "qfoc_ident_start: %s: the run failed\n", scn_tables[k].name);
            rc = (rc > 1) ? rc : 1;
            continue;
        }
        printf("%s (%s): %s", scn_tables[k].name, name, r.pass ? "PASS" : "FAIL");
        for (m = 0; m < r.n_metrics; m++) {
            if (r.m[m].pass == 0) {
                printf(" [%s = %.4g %s off its target]", r.m[m].key, r.m[m].value, r.m[m].unit);
            } else if (strcmp(r.m[m].key, "t_target_s") == 0 ||
                       strcmp(r.m[m].key, "angle_err_max_deg") == 0 ||
                       strcmp(r.m[m].key, "i_peak_pct_trip") == 0) {
                printf(" %s = %.3g", r.m[m].key, r.m[m].value);
            }
        }
        printf("\n");
        if (!r.pass) {
            rc = 1;
        }
    }
    return rc;
}
