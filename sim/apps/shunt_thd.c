/**
 * @file shunt_thd.c
 * @brief The phase-current THD that the single shunt's edge shifting adds (make shunt-thd,
 *        REQ-SCN-018): the reference motor in closed loop at steady operating points, on its
 *        two-sensor table, on its single-shunt table, and on the two-sensor table with the
 *        single shunt's edge shifting alone; the true phase currents recorded at every plant
 *        sub-step over a whole number of electrical periods and analysed by their DFT
 *        (sim_harmonics()), with the scenarios' sample noise and without; then a speed
 *        sweep at the rated load (2000 .. 6000 rpm, two sensors and single shunt, no noise)
 *        and one point with 80 sub-steps instead of 20.
 *
 * usage: qfoc_shunt_thd [--out DIR] [--noise A] [--points N]
 *   --out DIR    build/reports by default: shunt_thd.md and shunt_thd.csv
 *   --noise A    current-sample noise, A rms (0.05, the scenarios' rig)
 *   --points N   the first N operating points only (all 6 by default)
 * Exit: 0 when every point was reached and analysed, 1 otherwise, 2 on a usage or set-up
 * error.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <math.h>

#include "shunt_thd.h"
#include "tables_registry.h"

#define N_MODES 3

static const char *const mode_name[N_MODES] = { "two_sensor", "shunt", "shift_only" };

static const scn_table_t *find_table(const char *name)
{
    int k;
    for (k = 0; k < scn_n_tables; k++) {
        if (strcmp(scn_tables[k].name, name) == 0) {
            return &scn_tables[k];
        }
    }
    return NULL;
}

typedef struct {
    double rpm;
    double load_nm;
    const char *label;
} op_t;

/* 1000 rpm is the table's lowest closed-loop speed (drive.rpm_min); there the drive holds
   2 N m steady but not 3 or 4.5 N m (the speed hunts between about 730 and 1280 rpm) */
static const op_t ops[] = {
    { 1000.0, 1.0, "light" }, { 1000.0, 2.0, "highest steady" },
    { 3000.0, 1.0, "light" }, { 3000.0, 4.5, "rated" },
    { 6000.0, 1.0, "light" }, { 6000.0, 4.5, "rated" },
};
#define N_OPS ((int)(sizeof ops / sizeof ops[0]))
/* the speed sweep at the rated load: 2000 .. 6000 rpm in 500 rpm steps */
#define N_SWEEP 9

static int run_point(const scn_table_t *two, const scn_table_t *sh, const op_t *op, int mode,
                     int substeps, double noise, sht_result_t *r)
{
    sht_point_t p;
    memset(&p, 0, sizeof p);
    p.tab = (mode == SHT_SHUNT) ? sh : two;
    p.mode = mode;
    sht_shunt_cfg(sh->table, &p.shift);
    p.rpm = op->rpm;
    p.load_nm = op->load_nm;
    p.noise_a = noise;
    p.substeps = substeps;
    p.settle_s = 1.5;
    p.window_s = 0.2;
    p.h_max = 40;
    if (sht_run(&p, r) != 0) {
        fprintf(stderr, "shunt-thd: %s: the run could not be set up\n", p.tab->name);
        return -1;
    }
    fprintf(stderr, "shunt-thd: %5.0f rpm %.1f N m %-10s substeps %d: %s", op->rpm, op->load_nm,
            mode_name[mode], substeps, r->ok ? "" : r->why);
    if (r->ok) {
        fprintf(stderr, "I1 %.3f A rms, THD %.3f %%, total %.3f %%, %d periods, %ld samples, "
                "%.1f rpm, shifted %.0f %%", r->fund_rms, 100.0 * r->thd, 100.0 * r->tdd,
                r->cycles, r->n, r->rpm_mean, 100.0 * r->shifted_frac);
    }
    fputc('\n', stderr);
    return 0;
}

static void pct(FILE *f, const sht_result_t *r, double v)
{
    if (r->ok) {
        fprintf(f, " %.3f |", 100.0 * v);
    } else {
        fputs(" - |", f);
    }
}

static void dpct(FILE *f, const sht_result_t *a, const sht_result_t *b, double va, double vb)
{
    if (a->ok && b->ok) {
        fprintf(f, " %+.3f |", 100.0 * (va - vb));
    } else {
        fputs(" - |", f);
    }
}

/* the largest harmonic 2 .. 40 of phase u, "h (x.xx %)" */
static void top_harm(const sht_result_t *r, char *buf, size_t len)
{
    int h;
    int best = 2;
    for (h = 3; h <= 40; h++) {
        if (r->ph[0].h_rms[h] > r->ph[0].h_rms[best]) {
            best = h;
        }
    }
    snprintf(buf, len, "%d (%.3f %%)", best, 100.0 * r->ph[0].h_rms[best] / r->ph[0].fund_rms);
}

/* One table of the report: the points at one noise level. */
static void md_table(FILE *md, sht_result_t res[][N_MODES], int n_ops)
{
    int k;
    fprintf(md, "| speed, load | I1 (A rms) | THD two sensors | THD shunt | THD shunt - two | "
                "total two sensors | total shunt | total shunt - two | THD shift only - two | "
                "total shift only - two | periods shifted (shunt) | largest harmonic of u, two / shunt |\n");
    fprintf(md, "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|\n");
    for (k = 0; k < n_ops; k++) {
        const sht_result_t *r2 = &res[k][SHT_TWO_SENSOR];
        const sht_result_t *rs = &res[k][SHT_SHUNT];
        const sht_result_t *rf = &res[k][SHT_SHIFT];
        char h2[40];
        char hs[40];
        fprintf(md, "| %.0f rpm, %.1f N m (%s) |", ops[k].rpm, ops[k].load_nm, ops[k].label);
        if (r2->ok) {
            fprintf(md, " %.2f |", r2->fund_rms);
        } else {
            fprintf(md, " %s |", r2->why);
        }
        pct(md, r2, r2->thd);
        pct(md, rs, rs->thd);
        dpct(md, rs, r2, rs->thd, r2->thd);
        pct(md, r2, r2->tdd);
        pct(md, rs, rs->tdd);
        dpct(md, rs, r2, rs->tdd, r2->tdd);
        dpct(md, rf, r2, rf->thd, r2->thd);
        dpct(md, rf, r2, rf->tdd, r2->tdd);
        if (rs->ok) {
            fprintf(md, " %.0f %% |", 100.0 * rs->shifted_frac);
        } else {
            fprintf(md, " %s |", rs->why);
        }
        top_harm(r2, h2, sizeof h2);
        top_harm(rs, hs, sizeof hs);
        fprintf(md, " %s / %s |\n", r2->ok ? h2 : "-", rs->ok ? hs : "-");
    }
}

static void csv_row(FILE *csv, const op_t *op, int mode, int substeps, double noise,
                    const sht_result_t *r)
{
    fprintf(csv, "%.0f,%.2f,%s,%d,%.3f,%d,%.3f,%.2f,%d,%ld,%.5f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,"
                 "%.4f,%.1f\n",
            op->rpm, op->load_nm, mode_name[mode], substeps, noise, r->ok, r->t_reach_s, r->rpm_mean,
            r->cycles, r->n, r->fund_rms, 100.0 * r->thd, 100.0 * r->tdd, 100.0 * r->ph[0].thd,
            100.0 * r->ph[1].thd, 100.0 * r->ph[2].thd,
            r->ok ? 100.0 * r->ph[0].h_rms[2] / r->ph[0].fund_rms : 0.0,
            r->ok ? 100.0 * r->ph[0].h_rms[4] / r->ph[0].fund_rms : 0.0,
            r->ok ? 100.0 * r->ph[0].h_rms[5] / r->ph[0].fund_rms : 0.0, 100.0 * r->shifted_frac);
}

int main(int argc, char **argv)
{
    const char *out = "build/reports";
    double noise[2] = { 0.05, 0.0 };
    int n_ops = N_OPS;
    int a;
    int k;
    int m;
    int q;
    int bad = 0;
    const scn_table_t *two = find_table("reference");
    const scn_table_t *sh = find_table("reference_shunt");
    static sht_result_t res[2][N_OPS][N_MODES];
    static sht_result_t fine[2];
    static sht_result_t sweep[N_SWEEP][2];
    const int fine_op = 3;  /* 3000 rpm, rated load */
    int kf;
    char path[600];
    FILE *md;
    FILE *csv;

    for (a = 1; a < argc; a++) {
        if (strcmp(argv[a], "--out") == 0 && a + 1 < argc) {
            out = argv[++a];
        } else if (strcmp(argv[a], "--noise") == 0 && a + 1 < argc) {
            noise[0] = atof(argv[++a]);
        } else if (strcmp(argv[a], "--points") == 0 && a + 1 < argc) {
            n_ops = atoi(argv[++a]);
            n_ops = (n_ops < 1) ? 1 : ((n_ops > N_OPS) ? N_OPS : n_ops);
        } else {
            fprintf(stderr, "usage: qfoc_shunt_thd [--out DIR] [--noise A] [--points N]\n");
            return 2;
        }
    }
    if (two == NULL || sh == NULL) {
        fprintf(stderr, "shunt-thd: the tables reference and reference_shunt are not in the manifest\n");
        return 2;
    }
    kf = (fine_op < n_ops) ? fine_op : 0;
    for (q = 0; q < 2; q++) {
        for (k = 0; k < n_ops; k++) {
            for (m = 0; m < N_MODES; m++) {
                if (run_point(two, sh, &ops[k], m, 20, noise[q], &res[q][k][m]) != 0) {
                    return 2;
                }
                bad += res[q][k][m].ok ? 0 : 1;
            }
        }
    }
    /* the sweep: rated load, no noise, 2000 .. 6000 rpm, two sensors and single shunt */
    for (k = 0; k < N_SWEEP; k++) {
        const op_t op = { 2000.0 + 500.0 * (double)k, 4.5, "rated" };
        for (m = 0; m < 2; m++) {
            if (run_point(two, sh, &op, m, 20, 0.0, &sweep[k][m]) != 0) {
                return 2;
            }
            bad += sweep[k][m].ok ? 0 : 1;
        }
    }
    /* the resolution: the same point with 80 sub-steps */
    for (m = 0; m < 2; m++) {
        if (run_point(two, sh, &ops[kf], m, 80, noise[0], &fine[m]) != 0) {
            return 2;
        }
        bad += fine[m].ok ? 0 : 1;
    }

    snprintf(path, sizeof path, "%s/shunt_thd.csv", out);
    csv = fopen(path, "w");
    snprintf(path, sizeof path, "%s/shunt_thd.md", out);
    md = fopen(path, "w");
    if (csv == NULL || md == NULL) {
        fprintf(stderr, "shunt-thd: cannot write into %s\n", out);
        return 2;
    }
    fprintf(csv, "rpm,load_nm,mode,substeps,noise_a,ok,t_reach_s,rpm_mean,cycles,samples,fund_rms_a,"
                 "thd_pct,total_dist_pct,thd_u_pct,thd_v_pct,thd_w_pct,h2_u_pct,h4_u_pct,h5_u_pct,"
                 "shifted_pct\n");
    for (q = 0; q < 2; q++) {
        for (k = 0; k < n_ops; k++) {
            for (m = 0; m < N_MODES; m++) {
                csv_row(csv, &ops[k], m, 20, noise[q], &res[q][k][m]);
            }
        }
    }
    for (m = 0; m < 2; m++) {
        csv_row(csv, &ops[kf], m, 80, noise[0], &fine[m]);
    }
    for (k = 0; k < N_SWEEP; k++) {
        const op_t op = { 2000.0 + 500.0 * (double)k, 4.5, "rated" };
        for (m = 0; m < 2; m++) {
            csv_row(csv, &op, m, 20, 0.0, &sweep[k][m]);
        }
    }
    fclose(csv);

    fprintf(md, "# Phase-current distortion: single shunt against two phase sensors\n\n");
    fprintf(md, "Reference motor (specs/motors/reference.toml), tables `reference` (two sensors) and "
                "`reference_shunt` (single shunt, window %u + %u ticks of a %u-tick half period), "
                "320 V, 8 kHz PWM, dead time 1 us, passive compressor load; closed loop, held 1.5 s "
                "at the point, then the plant's true phase currents at each of its 20 sub-steps "
                "per PWM period over a whole number of electrical periods (about 0.2 s). "
                "THD: harmonics 2 .. 40 of the fundamental; total: RMS(i - fundamental) / RMS "
                "fundamental (the PWM ripple included); the three phases' mean, in %% of the "
                "fundamental; differences in points. Shift only: the two-sensor drive with the "
                "single shunt's edge shifting applied to its compare values (the phase sensors "
                "still sampled at the counter's zero).\n\n",
            (unsigned)sh->table->drive.shunt_settle, (unsigned)sh->table->drive.shunt_sample,
            (unsigned)sh->table->svpwm.period);
    for (q = 0; q < 2; q++) {
        fprintf(md, "%s: %.3g A rms noise on each current sample%s\n\n",
                (q == 0) ? "As the scenarios rig the plant" : "Without noise",
                noise[q], (q == 0) ? " (seed 7)" : "");
        md_table(md, res[q], n_ops);
        fputc('\n', md);
    }
    fprintf(md, "Resolution: %.0f rpm, %.1f N m (%.3g A rms noise) with 80 sub-steps per PWM "
                "period instead of 20: the run again (another integration, so another "
                "trajectory), and its record with every 4th sample only (the same trajectory "
                "seen at 20 samples per period):\n\n", ops[kf].rpm, ops[kf].load_nm, noise[0]);
    fprintf(md, "| sensing | THD, 20 | THD, 80 | THD, 80 every 4th | total, 20 | total, 80 | "
                "total, 80 every 4th |\n");
    fprintf(md, "|---|---:|---:|---:|---:|---:|---:|\n");
    for (m = 0; m < 2; m++) {
        const sht_result_t *c = &res[0][kf][m];
        const sht_result_t *f = &fine[m];
        fprintf(md, "| %s |", mode_name[m]);
        pct(md, c, c->thd);
        pct(md, f, f->thd);
        pct(md, f, f->dec4 ? f->thd_dec4 : NAN);
        pct(md, c, c->tdd);
        pct(md, f, f->tdd);
        pct(md, f, f->dec4 ? f->tdd_dec4 : NAN);
        fputc('\n', md);
    }
    fprintf(md, "\nThe speed sweep: rated load (4.5 N m), no noise; phase u's harmonics in %% of its "
                "fundamental (is the single shunt's distortion locked to the speed, and of which "
                "orders?):\n\n");
    fprintf(md, "| speed | THD two sensors | THD shunt | shunt: 2nd | 4th | 5th | 7th | "
                "largest of 2 .. 40, shunt | two sensors: 2nd | 4th |\n");
    fprintf(md, "|---|---:|---:|---:|---:|---:|---:|---|---:|---:|\n");
    for (k = 0; k < N_SWEEP; k++) {
        const sht_result_t *r2 = &sweep[k][SHT_TWO_SENSOR];
        const sht_result_t *rs = &sweep[k][SHT_SHUNT];
        char hs[40];
        fprintf(md, "| %.0f rpm |", 2000.0 + 500.0 * (double)k);
        pct(md, r2, r2->thd);
        pct(md, rs, rs->thd);
        pct(md, rs, rs->ok ? rs->ph[0].h_rms[2] / rs->ph[0].fund_rms : NAN);
        pct(md, rs, rs->ok ? rs->ph[0].h_rms[4] / rs->ph[0].fund_rms : NAN);
        pct(md, rs, rs->ok ? rs->ph[0].h_rms[5] / rs->ph[0].fund_rms : NAN);
        pct(md, rs, rs->ok ? rs->ph[0].h_rms[7] / rs->ph[0].fund_rms : NAN);
        top_harm(rs, hs, sizeof hs);
        fprintf(md, " %s |", rs->ok ? hs : "-");
        pct(md, r2, r2->ok ? r2->ph[0].h_rms[2] / r2->ph[0].fund_rms : NAN);
        pct(md, r2, r2->ok ? r2->ph[0].h_rms[4] / r2->ph[0].fund_rms : NAN);
        fputc('\n', md);
    }
    fclose(md);
    printf("shunt-thd: %s/shunt_thd.md, %s/shunt_thd.csv; %d of %d runs analysed\n", out, out,
           2 * n_ops * N_MODES + 2 + 2 * N_SWEEP - bad, 2 * n_ops * N_MODES + 2 + 2 * N_SWEEP);
    return (bad == 0) ? 0 : 1;
}
