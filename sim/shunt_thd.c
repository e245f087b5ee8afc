/**
 * @file shunt_thd.c
 * @brief The phase-current distortion at a steady operating point (shunt_thd.h).
 */
#include "shunt_thd.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void sht_shunt_cfg(const qfoc_param_table_t *t, qfoc_shunt_cfg_t *c)
{
    c->period = t->svpwm.period;
    c->t_settle = t->drive.shunt_settle;
    c->t_sample = t->drive.shunt_sample;
    c->hold_max = t->drive.shunt_hold;
}

static bool sht_in_cl(const dsim_t *ds)
{
    return ds->drv.s.sm.state == QFOC_STATE_RUN && ds->drv.s.sm.sub == QFOC_SUB_CLOSED_LOOP;
}

/* Was the plan of the period just run shifted? */
static bool sht_shifted(const dsim_t *ds, const sht_point_t *p)
{
    if (p->mode == SHT_SHUNT && ds->shunt != NULL) {
        return ds->shunt->plan[ds->shunt->head].shifted;
    }
    if (p->mode == SHT_SHIFT) {
        qfoc_shunt_plan_t plan;
        qfoc_shunt_plan(&p->shift, ds->pwm.cmp, &plan);
        return plan.shifted;
    }
    return false;
}

static int sht_body(dsim_t *ds, const sht_point_t *p, sht_result_t *r)
{
    const double t_max = 20.0;
    const double pp = ds->plant.cfg.motor.pole_pairs;
    const double t_s = ds->plant.bases.t_s;
    double t_reach = -1.0;
    double f_e;
    long periods;
    long k;
    long shifted = 0;
    long best;
    double th_end;
    sim_rec_t rec;
    int j;

    ds->power_on = true;
    ds->target_rpm = (uint16_t)lround(p->rpm);
    while (t_reach < 0.0 && (double)ds->ms * 1e-3 < t_max) {
        for (k = 0; k < ds->periods_per_ms; k++) {
            dsim_period(ds);
        }
        if (ds->drv.s.sm.state == QFOC_STATE_ERROR) {
            snprintf(r->why, sizeof r->why, "ERROR at %.3f s", (double)ds->ms * 1e-3);
            return 0;
        }
        if (sht_in_cl(ds) && fabs(dsim_rpm(ds) - p->rpm) < 0.01 * p->rpm) {
            t_reach = (double)ds->ms * 1e-3;
        }
    }
    if (t_reach < 0.0) {
        snprintf(r->why, sizeof r->why, "not at %.0f rpm within %.0f s", p->rpm, t_max);
        return 0;
    }
    r->t_reach_s = t_reach;
    dsim_run(ds, p->settle_s);
    if (!sht_in_cl(ds) || fabs(dsim_rpm(ds) - p->rpm) > 0.02 * p->rpm) {
        snprintf(r->why, sizeof r->why, "left the point while settling (%.0f rpm)", dsim_rpm(ds));
        return 0;
    }
    f_e = p->rpm * pp / 60.0;
    r->cycles = (int)lround(p->window_s * f_e);
    if (r->cycles < 2) {
        r->cycles = 2;
    }
    /* the window and 5 % to spare (the speed is within 2 %) */
    periods = (long)ceil(1.05 * (double)r->cycles / f_e / t_s) + 2;
    rec.cap = periods * (long)ds->plant.cfg.substeps;
    rec.buf = (double *)malloc((size_t)rec.cap * 4u * sizeof(double));
    if (rec.buf == NULL) {
        snprintf(r->why, sizeof r->why, "no memory for %ld samples", rec.cap);
        return 0;
    }
    sim_record(&ds->plant, &rec);
    for (k = 0; k < periods; k++) {
        dsim_period(ds);
        if (sht_shifted(ds, p)) {
            shifted++;
        }
    }
    sim_record(&ds->plant, NULL);
    /* the window: from sample 0 to the sample whose angle is closest to 2 pi cycles on */
    th_end = rec.buf[0] + 2.0 * SIM_PI * (double)r->cycles;
    best = -1;
    for (k = 1; k < rec.n; k++) {
        if (best < 0 || fabs(rec.buf[4 * k] - th_end) < fabs(rec.buf[4 * best] - th_end)) {
            best = k;
        }
    }
    if (best < 0 || rec.buf[4 * (rec.n - 1)] < th_end || !sht_in_cl(ds)) {
        snprintf(r->why, sizeof r->why, "the record is short of %d periods", r->cycles);
        free(rec.buf);
        return 0;
    }
    r->n = best;
    r->rpm_mean = (rec.buf[4 * best] - rec.buf[0]) /
                  ((double)best * t_s / (double)ds->plant.cfg.substeps) / pp * 60.0 / (2.0 * SIM_PI);
    r->shifted_frac = (double)shifted / (double)periods;
    if (p->dump_csv != NULL) {
        FILE *f = fopen(p->dump_csv, "w");
        const double h = t_s / (double)ds->plant.cfg.substeps;
        if (f != NULL) {
            fputs("t_s,theta_e,i_u,i_v,i_w\n", f);
            for (k = 0; k < r->n; k++) {
                fprintf(f, "%.9f,%.6f,%.5f,%.5f,%.5f\n", (double)k * h, rec.buf[4 * k],
                        rec.buf[4 * k + 1], rec.buf[4 * k + 2], rec.buf[4 * k + 3]);
            }
            fclose(f);
        }
    }
    for (j = 0; j < 3; j++) {
        if (sim_harmonics(&rec.buf[1 + j], 4, r->n, r->cycles, p->h_max, &r->ph[j]) != 0) {
            snprintf(r->why, sizeof r->why, "the analysis refused the record");
            free(rec.buf);
            return 0;
        }
        r->fund_rms += r->ph[j].fund_rms / 3.0;
        r->thd += r->ph[j].thd / 3.0;
        r->tdd += r->ph[j].tdd / 3.0;
    }
    if (ds->plant.cfg.substeps % 4 == 0 && r->n >= 4L * 2L * (long)p->h_max * (long)r->cycles) {
        /* the same window with every 4th sample: the recording's resolution alone */
        const long n4 = (r->n + 2) / 4;
        for (j = 0; j < 3; j++) {
            sim_harm_t hd;
            if (sim_harmonics(&rec.buf[1 + j], 16, n4, r->cycles, p->h_max, &hd) == 0) {
                r->thd_dec4 += hd.thd / 3.0;
                r->tdd_dec4 += hd.tdd / 3.0;
            }
        }
        r->dec4 = 1;
    }
    free(rec.buf);
    r->ok = 1;
    return 0;
}

int sht_run(const sht_point_t *p, sht_result_t *r)
{
    sim_motor_t m;
    sim_cfg_t cfg;
    dsim_t *ds;
    qfoc_drive_shunt_t sh;
    int rc;

    memset(r, 0, sizeof *r);
    if (scn_table_motor(p->tab, &m) != 0) {
        return -1;
    }
    memset(&cfg, 0, sizeof cfg);
    cfg.motor = m;
    cfg.vdc_v = m.vdc_nominal_v;
    cfg.dead_time_s = m.dead_time_s;
    cfg.substeps = p->substeps;
    cfg.noise_i_rms_a = p->noise_a;
    cfg.seed = 7u;
    cfg.load.t_mean = p->load_nm;
    cfg.load.knee_rpm = 30.0;
    if (p->mode == SHT_SHUNT) {
        scn_shunt_plant(&cfg, p->tab->table, &m);
    }
    ds = (dsim_t *)malloc(sizeof *ds);
    if (ds == NULL) {
        return -1;
    }
    if (dsim_init(ds, &cfg, p->tab->table) != QFOC_PARAMS_OK) {
        free(ds);
        return -1;
    }
    if (p->mode == SHT_SHUNT) {
        if (qfoc_drive_shunt_init(&sh, &ds->drv, 2u) != QFOC_SHUNT_OK) {
            free(ds);
            return -1;
        }
        ds->shunt = &sh;
    } else if (p->mode == SHT_SHIFT) {
        ds->shift = &p->shift;
    } else {
        /* two sensors as they are */
    }
    rc = sht_body(ds, p, r);
    free(ds);
    return rc;
}
