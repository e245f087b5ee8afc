/**
 * @file scenario.c
 * @brief Compressor-drive scenarios on the plant (scenario.h).
 *
 * Every figure is measured on the simulation: speeds and currents on the plant's true
 * state, the angle error against the plant's true angle at each ADC sample, times from
 * the scripted event (or the instant its condition became true) to the drive's
 * reaction.  Nothing is computed from the drive's design values.
 */
#define _POSIX_C_SOURCE 200809L  /* clock_gettime, fork, mkdir */

#include "scenario.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "qfoc/trqcomp.h"

const char *const scn_names[] = {
    "cold_start", "speed_steps", "pulsating_load", "load_step", "bus_sag",
    "fault_oc", "fault_ov", "fault_ot", "fault_stall", "fault_link", "mtpa", "derating",
    "flying_start", NULL
};

/* ------------------------------------------------------------------ targets */

typedef struct {
    char section[64];
    char key[64];
    double v;
} scn_kv_t;

#define SCN_MAX_KV 512

/* specs/scenarios.toml: [section] headers, key = number, # comments. */
static int scn_targets_load(const char *path, scn_kv_t *kv, int max)
{
    FILE *f = fopen(path, "r");
    char line[256];
    char section[64] = "";
    int n = 0;
    if (f == NULL) {
        fprintf(stderr, "%s: cannot open\n", path);
        return -1;
    }
    while (fgets(line, (int)sizeof line, f) != NULL) {
        char *s = line;
        char *hash = strchr(s, '#');
        char *eq;
        char key[64];
        double v;
        if (hash != NULL) {
            *hash = '\0';
        }
        while (*s == ' ' || *s == '\t') {
            s++;
        }
        if (*s == '[') {
            char *close = strchr(s, ']');
            if (close != NULL) {
                *close = '\0';
                snprintf(section, sizeof section, "%s", s + 1);
            }
            continue;
        }
        eq = strchr(s, '=');
        if (eq == NULL) {
            continue;
        }
        if (sscanf(s, "%63[A-Za-z0-9_]", key) != 1 || sscanf(eq + 1, "%lf", &v) != 1) {
            continue;
        }
        if (n < max) {
            snprintf(kv[n].section, sizeof kv[n].section, "%s", section);
            snprintf(kv[n].key, sizeof kv[n].key, "%s", key);
            kv[n].v = v;
            n++;
        }
    }
    fclose(f);
    return n;
}

/* ------------------------------------------------------------------ context */

typedef struct {
    dsim_t *ds;
    scn_result_t *r;
    const scn_opts_t *o;
    const char *kind;          /* scenario kind: fallback section of the targets */
    scn_kv_t *kv;
    int n_kv;
    FILE *trace;
    FILE *zoom;
    double i_trip_a;
    double i_max_a;            /* the table's current-vector limit */
    /* trackers, updated every millisecond */
    double ipk_ms;             /* peak |phase current| of the last ms */
    double ipk_all;            /* ... since the start */
    double ang_sq;             /* angle error in closed loop: sum of squares, count, max */
    long ang_n;
    double ang_max;
    double t_cl;               /* first entry into CLOSED_LOOP, s (-1: not yet) */
    uint16_t faults_seen;      /* every fault bit seen */
    double next_progress;
    int inj_periods;           /* periods left of an injected current offset */
    int inj_codes;
    long p_inj;                /* period of the first injected sample (-1: none) */
    long p_off;                /* first period from p_inj on whose fast step disabled the PWM */
    double t_watch;            /* a fault condition became true at (NAN: none) */
    double t_off;              /* from then, the first period start with the PWM off */
    qfoc_drive_shunt_t shunt;  /* the single-shunt front end of a shunt table */
} scn_ctx_t;

static double scn_time(const scn_ctx_t *c)
{
    return (double)c->ds->ms * 1e-3;
}

static double scn_q15_rpm(const dsim_t *ds, double q)
{
    return q / 32768.0 * ds->plant.bases.w_base / ds->plant.cfg.motor.pole_pairs * 60.0 /
           (2.0 * SIM_PI);
}

static double scn_q15_a(const dsim_t *ds, double q)
{
    return q / 32768.0 * ds->plant.bases.i_base;
}

static void scn_phase(const sim_t *p, double i[3])
{
    double ab[2];
    sim_i_ab(p, ab);
    i[0] = ab[0];
    i[1] = -0.5 * ab[0] + 0.5 * sqrt(3.0) * ab[1];
    i[2] = -i[0] - i[1];
}

static bool scn_in_cl(const dsim_t *ds)
{
    return ds->drv.s.sm.state == QFOC_STATE_RUN &&
           (ds->drv.s.sm.sub == QFOC_SUB_CLOSED_LOOP || ds->drv.s.sm.sub == QFOC_SUB_STOPPING);
}

static void scn_event(scn_ctx_t *c, const char *label)
{
    scn_result_t *r = c->r;
    if (r->n_events < SCN_MAX_EVENTS) {
        r->ev[r->n_events].t_s = scn_time(c);
        snprintf(r->ev[r->n_events].label, sizeof r->ev[0].label, "%s", label);
        r->n_events++;
    }
}

/* Look a target up: the run's own section first, then the scenario kind's. */
static double scn_target(const scn_ctx_t *c, const char *prefix, const char *key)
{
    char k[64];
    double v = NAN;
    int pass;
    int i;
    snprintf(k, sizeof k, "%s%s", prefix, key);
    for (pass = 0; pass < 2 && isnan(v); pass++) {
        const char *sec = (pass == 0) ? c->r->name : c->kind;
        for (i = 0; i < c->n_kv; i++) {
            if (strcmp(c->kv[i].section, sec) == 0 && strcmp(c->kv[i].key, k) == 0) {
                v = c->kv[i].v;
            }
        }
    }
    return v;
}

static void scn_metric(scn_ctx_t *c, const char *key, const char *label, const char *unit,
                       double value)
{
    scn_result_t *r = c->r;
    scn_metric_t *m;
    if (r->n_metrics >= SCN_MAX_METRICS) {
        return;
    }
    m = &r->m[r->n_metrics++];
    snprintf(m->key, sizeof m->key, "%s", key);
    snprintf(m->label, sizeof m->label, "%s", label);
    snprintf(m->unit, sizeof m->unit, "%s", unit);
    /* times are differences of ms counts: rounded to 1 ns of their unit, so that 5.000 s
       does not read as 4.9999999 */
    m->value = (fabs(value) < 1e6) ? nearbyint(value * 1e6) / 1e6 : value;
    m->min = scn_target(c, "min_", key);
    m->max = scn_target(c, "max_", key);
    if (isnan(m->min) && isnan(m->max)) {
        m->pass = -1;
    } else {
        m->pass = (!isnan(m->value) && (isnan(m->min) || m->value >= m->min) &&
                   (isnan(m->max) || m->value <= m->max)) ? 1 : 0;
    }
    if (m->pass == 0) {
        r->pass = false;
    }
}

static const char scn_trace_header[] =
    "t_s,target_rpm,speed_ref_rpm,speed_est_rpm,speed_true_rpm,id_ref_a,iq_ref_a,id_a,iq_a,"
    "id_true_a,iq_true_a,angle_err_deg,i_peak_a,iu_a,iv_a,iw_a,duty_u,duty_v,duty_w,pwm_on,"
    "vdc_v,vdc_meas_v,t_ipm_c,load_nm,torque_nm,state,sub,fault\n";

static void scn_fmt(FILE *f, double v)
{
    if (isnan(v)) {
        fputs(",nan", f);
    } else {
        fprintf(f, ",%.5g", v);
    }
}

/* The references the fast step used (drv_references, REQ-DRV-006). */
static void scn_refs(const dsim_t *ds, double *id_ref, double *iq_ref)
{
    const qfoc_drive_t *d = &ds->drv;
    const uint8_t sub = d->s.sm.sub;
    double id = 0.0;
    double iq = 0.0;
    if (d->s.sm.state == QFOC_STATE_RUN) {
        if (sub == QFOC_SUB_ALIGN) {
            id = d->s.id_ref;
        } else if (sub == QFOC_SUB_OPEN_LOOP) {
            iq = d->s.iq_ref;
        } else {
            const double ff = qfoc_trqcomp_output(&d->s.tc, d->f.theta_m, d->f.speed_f);
            const double lim = (double)((d->s.iq_lim > 0) ? d->s.iq_lim : 0);
            id = d->s.id_ref;
            iq = fmax(-lim, fmin(lim, (double)d->s.iq_ref + ff));
        }
    }
    *id_ref = scn_q15_a(ds, id);
    *iq_ref = scn_q15_a(ds, iq);
}

static void scn_row(scn_ctx_t *c, FILE *f)
{
    const dsim_t *ds = c->ds;
    const qfoc_drive_t *d = &ds->drv;
    const double per = (double)ds->table->svpwm.period;
    double id_ref;
    double iq_ref;
    double i[3];
    double ref = 0.0;
    scn_refs(ds, &id_ref, &iq_ref);
    scn_phase(&ds->plant, i);
    if (d->s.sm.state == QFOC_STATE_RUN) {
        ref = (d->s.sm.sub == QFOC_SUB_OPEN_LOOP) ? d->s.ol_speed
                                                  : ((d->s.sm.sub == QFOC_SUB_ALIGN) ? 0.0
                                                                                     : d->s.speed_ref);
    }
    fprintf(f, "%.3f", scn_time(c));
    scn_fmt(f, (double)ds->target_rpm * (ds->power_on ? 1.0 : 0.0));
    scn_fmt(f, scn_q15_rpm(ds, ref));
    scn_fmt(f, dsim_est_rpm(ds));
    scn_fmt(f, dsim_rpm(ds));
    scn_fmt(f, id_ref);
    scn_fmt(f, iq_ref);
    scn_fmt(f, scn_q15_a(ds, d->f.i_dq.d));
    scn_fmt(f, scn_q15_a(ds, d->f.i_dq.q));
    scn_fmt(f, ds->plant.id);
    scn_fmt(f, ds->plant.iq);
    scn_fmt(f, (scn_in_cl(ds) && ds->pwm.enable) ? dsim_angle_err_deg(ds) : NAN);
    scn_fmt(f, c->ipk_ms);
    scn_fmt(f, i[0]);
    scn_fmt(f, i[1]);
    scn_fmt(f, i[2]);
    scn_fmt(f, ds->pwm.cmp[0] / per);
    scn_fmt(f, ds->pwm.cmp[1] / per);
    scn_fmt(f, ds->pwm.cmp[2] / per);
    fprintf(f, ",%d", ds->pwm.enable ? 1 : 0);
    scn_fmt(f, ds->plant.cfg.vdc_v);
    scn_fmt(f, (double)d->f.vdc / 32768.0 * ds->plant.bases.v_base);
    scn_fmt(f, ds->t_ipm * 0.1);
    scn_fmt(f, sim_load_torque(&ds->plant));
    scn_fmt(f, ds->plant.torque_avg);
    fprintf(f, ",%u,%u,%u\n", (unsigned)d->s.sm.state, (unsigned)d->s.sm.sub,
            (unsigned)d->s.sm.faults);
}

static void scn_zoom_row(scn_ctx_t *c)
{
    const dsim_t *ds = c->ds;
    const double per = (double)ds->table->svpwm.period;
    double i[3];
    scn_phase(&ds->plant, i);
    fprintf(c->zoom, "%.6f", ds->plant.t);
    scn_fmt(c->zoom, i[0]);
    scn_fmt(c->zoom, i[1]);
    scn_fmt(c->zoom, i[2]);
    scn_fmt(c->zoom, scn_q15_a(ds, ds->drv.f.i_abc.u));
    scn_fmt(c->zoom, scn_q15_a(ds, ds->drv.f.i_abc.v));
    scn_fmt(c->zoom, ds->pwm.cmp[0] / per);
    scn_fmt(c->zoom, ds->pwm.cmp[1] / per);
    scn_fmt(c->zoom, ds->pwm.cmp[2] / per);
    fprintf(c->zoom, ",%d\n", ds->pwm.enable ? 1 : 0);
}

/* One millisecond: the PWM periods and the tick, trackers, trace rows, progress. */
static void scn_ms(scn_ctx_t *c)
{
    dsim_t *ds = c->ds;
    int k;
    c->ipk_ms = 0.0;
    for (k = 0; k < ds->periods_per_ms; k++) {
        double i[3];
        double pk;
        const long p = ds->period;
        ds->adc_iu_add = (c->inj_periods > 0) ? c->inj_codes : 0;
        if (c->inj_periods > 0) {
            c->inj_periods--;
        }
        if (c->zoom != NULL && ds->plant.t >= c->r->zoom_t0_s && ds->plant.t < c->r->zoom_t1_s) {
            dsim_period(ds);
            scn_zoom_row(c);
        } else {
            dsim_period(ds);
        }
        if (c->p_inj >= 0 && p >= c->p_inj && c->p_off < 0 && !ds->pwm.enable) {
            c->p_off = p;
        }
        if (!isnan(c->t_watch) && isnan(c->t_off) && !ds->pwm.enable) {
            c->t_off = ds->plant.t;
        }
        scn_phase(&ds->plant, i);
        pk = fmax(fabs(i[0]), fmax(fabs(i[1]), fabs(i[2])));
        c->ipk_ms = fmax(c->ipk_ms, pk);
        if (scn_in_cl(ds) && ds->pwm.enable) {
            const double e = dsim_angle_err_deg(ds);
            c->ang_sq += e * e;
            c->ang_n++;
            c->ang_max = fmax(c->ang_max, fabs(e));
        }
    }
    c->ipk_all = fmax(c->ipk_all, c->ipk_ms);
    c->faults_seen = (uint16_t)(c->faults_seen | ds->drv.s.sm.faults);
    if (c->t_cl < 0.0 && ds->drv.s.sm.sub == QFOC_SUB_CLOSED_LOOP) {
        c->t_cl = scn_time(c);
    }
    if (c->trace != NULL) {
        scn_row(c, c->trace);
    }
    if (c->o->progress && scn_time(c) >= c->next_progress) {
        fprintf(stderr, "\r[%d/%d] %-26s simulated %6.2f s of %5.2f s ", c->o->index, c->o->count,
                c->r->name, scn_time(c), c->r->t_end_s);
        fflush(stderr);
        c->next_progress += 0.25;
    }
}

/* ------------------------------------------------------------------ set-up */

static int scn_mkdir(const char *dir)
{
    char tmp[512];
    size_t k;
    int rc = 0;
    snprintf(tmp, sizeof tmp, "%s", dir);
    for (k = 1; tmp[k] != '\0' && rc == 0; k++) {
        if (tmp[k] == '/') {
            tmp[k] = '\0';
            if (mkdir(tmp, 0777) != 0 && errno != EEXIST) {
                rc = -1;
            }
            tmp[k] = '/';
        }
    }
    if (rc == 0 && mkdir(tmp, 0777) != 0 && errno != EEXIST) {
        rc = -1;
    }
    return rc;
}

static FILE *scn_open(const scn_opts_t *o, const char *file)
{
    char path[600];
    FILE *f = NULL;
    if (o->out_dir != NULL) {
        snprintf(path, sizeof path, "%s/%s", o->out_dir, file);
        f = fopen(path, "w");
        if (f == NULL) {
            fprintf(stderr, "%s: cannot write\n", path);
        }
    }
    return f;
}

int scn_table_motor(const scn_table_t *tab, sim_motor_t *m)
{
    int rc = sim_motor_load(tab->motor_file, m);
    if (rc == 0 && tab->overrides != NULL) {
        char buf[256];
        char *tok;
        snprintf(buf, sizeof buf, "%s", tab->overrides);
        for (tok = strtok(buf, " \t"); tok != NULL && rc == 0; tok = strtok(NULL, " \t")) {
            rc = sim_motor_set(m, tok);
        }
    }
    return rc;
}

void scn_shunt_plant(sim_cfg_t *cfg, const qfoc_param_table_t *table, const sim_motor_t *m)
{
    const double tick = 1.0 / m->f_timer_hz;
    cfg->shunt.active = true;
    cfg->shunt.t_ring_s = fmax(0.0, (double)table->drive.shunt_settle * tick - m->dead_time_s);
    cfg->shunt.ring_gain = 0.5;
    cfg->shunt.f_ring_hz = 2.0e6;
    cfg->shunt.t_sh_s = (double)table->drive.shunt_sample * tick;
}

/* The plant and the drive: nominal bus, dead time, 0.05 A rms noise, passive load. */
static int scn_rig(scn_ctx_t *c, const scn_table_t *tab, const qfoc_param_table_t *table,
                   const sim_motor_t *m, double vdc, double load_nm, double pulse_1x, uint32_t seed,
                   double noise_a)
{
    sim_cfg_t cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.motor = *m;
    cfg.vdc_v = vdc;
    cfg.dead_time_s = m->dead_time_s;
    cfg.substeps = 20;
    cfg.noise_i_rms_a = noise_a;
    cfg.seed = seed;
    cfg.load.t_mean = load_nm;
    cfg.load.t_1x = pulse_1x * load_nm;
    cfg.load.knee_rpm = 30.0;
    if (table->drive.sensing == QFOC_SENSING_SHUNT) {
        scn_shunt_plant(&cfg, table, m);
    }
    if (dsim_init(c->ds, &cfg, table) != QFOC_PARAMS_OK) {
        fprintf(stderr, "%s: the table is refused by qfoc_drive_init\n", tab->name);
        return -1;
    }
    if (table->drive.sensing == QFOC_SENSING_SHUNT) {
        if (qfoc_drive_shunt_init(&c->shunt, &c->ds->drv, 2u) != QFOC_SHUNT_OK) {
            fprintf(stderr, "%s: the single-shunt set-up is refused\n", tab->name);
            return -1;
        }
        c->ds->shunt = &c->shunt;
    }
    c->i_trip_a = scn_q15_a(c->ds, (double)table->i_trip);
    c->i_max_a = scn_q15_a(c->ds, (double)table->i_max);
    c->r->f_pwm_hz = m->f_pwm_hz;
    c->r->vdc_v = vdc;
    snprintf(c->r->motor, sizeof c->r->motor, "%s", m->name);
    snprintf(c->r->table, sizeof c->r->table, "%s", tab->name);
    return 0;
}

static void scn_reset_trackers(scn_ctx_t *c)
{
    c->ipk_ms = 0.0;
    c->ipk_all = 0.0;
    c->ang_sq = 0.0;
    c->ang_n = 0;
    c->ang_max = 0.0;
    c->t_cl = -1.0;
    c->faults_seen = 0u;
    c->next_progress = 0.0;
    c->inj_periods = 0;
    c->p_inj = -1;
    c->p_off = -1;
    c->t_watch = NAN;
    c->t_off = NAN;
}

/* ------------------------------------------------------------------ common metrics */

/* Speed-tracking figures of a segment: reach (within band), overshoot, steady-state. */
typedef struct {
    double target;     /* rpm */
    double from;       /* speed at the command, rpm */
    double t_cmd;      /* s */
    double t_reach;    /* first time within the band, s after t_cmd (NAN: never) */
    double extreme;    /* furthest excursion beyond the target in the direction of travel */
    double ss_sum;     /* |error| sum over the steady-state window */
    long ss_n;
    double ss_lo;
    double ss_hi;
} scn_seg_t;

static void scn_seg_start(scn_seg_t *s, double target, double from, double t_cmd)
{
    memset(s, 0, sizeof *s);
    s->target = target;
    s->from = from;
    s->t_cmd = t_cmd;
    s->t_reach = NAN;
    s->extreme = target;
    s->ss_lo = INFINITY;
    s->ss_hi = -INFINITY;
}

/* Every ms of the segment; ss: inside the steady-state window. */
static void scn_seg_track(scn_seg_t *s, double t, double rpm, bool ss)
{
    if (isnan(s->t_reach) && fabs(rpm - s->target) <= 0.02 * s->target) {
        s->t_reach = t - s->t_cmd;
    }
    if (!isnan(s->t_reach)) {
        s->extreme = (s->target >= s->from) ? fmax(s->extreme, rpm) : fmin(s->extreme, rpm);
    }
    if (ss) {
        s->ss_sum += fabs(rpm - s->target);
        s->ss_n++;
        s->ss_lo = fmin(s->ss_lo, rpm);
        s->ss_hi = fmax(s->ss_hi, rpm);
    }
}

static double scn_seg_over_pct(const scn_seg_t *s)
{
    return isnan(s->t_reach) ? NAN : fabs(s->extreme - s->target) / s->target * 100.0;
}

static double scn_seg_ss_pct(const scn_seg_t *s)
{
    return (s->ss_n > 0) ? s->ss_sum / (double)s->ss_n / s->target * 100.0 : NAN;
}

static void scn_common_metrics(scn_ctx_t *c)
{
    scn_metric(c, "angle_err_rms_deg", "RMS angle error in closed loop (estimate - true, electrical)",
               "deg", (c->ang_n > 0) ? sqrt(c->ang_sq / (double)c->ang_n) : NAN);
    scn_metric(c, "angle_err_max_deg", "max |angle error| in closed loop", "deg",
               (c->ang_n > 0) ? c->ang_max : NAN);
    scn_metric(c, "i_peak_a", "peak phase current", "A", c->ipk_all);
    scn_metric(c, "i_peak_pct_trip", "peak phase current / over-current trip level", "%",
               c->ipk_all / c->i_trip_a * 100.0);
    scn_metric(c, "i_peak_pct_imax", "peak phase current / the table's current limit i_max", "%",
               c->ipk_all / c->i_max_a * 100.0);
}

/* ------------------------------------------------------------------ scenarios */

static void scn_describe(scn_result_t *r, const char *title, const char *req, const char *text)
{
    snprintf(r->title, sizeof r->title, "%s", title);
    snprintf(r->requirements, sizeof r->requirements, "%s", req);
    snprintf(r->description, sizeof r->description, "%s", text);
}

/* Cold start to a target at a load; shared by cold_start and the campaign. */
static void scn_cold_start_body(scn_ctx_t *c, double target_rpm, double t_end)
{
    dsim_t *ds = c->ds;
    scn_seg_t seg;
    double worst_after = 0.0;   /* max |error| in the last second */
    c->r->t_end_s = t_end;
    ds->power_on = true;
    ds->target_rpm = (uint16_t)lround(target_rpm);
    scn_event(c, "run command");
    scn_seg_start(&seg, target_rpm, 0.0, 0.0);
    while (scn_time(c) < t_end - 1e-9) {
        bool ss;
        scn_ms(c);
        ss = scn_time(c) > t_end - 1.0;
        scn_seg_track(&seg, scn_time(c), dsim_rpm(ds), ss);
        if (ss) {
            worst_after = fmax(worst_after, fabs(dsim_rpm(ds) - target_rpm));
        }
    }
    scn_metric(c, "t_closed_loop_s", "time from the run command to CLOSED_LOOP", "s",
               (c->t_cl >= 0.0) ? c->t_cl : NAN);
    scn_metric(c, "t_target_s", "time to the target speed (within 2 %)", "s", seg.t_reach);
    scn_metric(c, "overshoot_pct", "speed overshoot above the target", "%", scn_seg_over_pct(&seg));
    scn_metric(c, "ss_err_pct", "steady-state speed error, mean |error| over the last second", "%",
               scn_seg_ss_pct(&seg));
    scn_metric(c, "ss_err_max_pct", "max |speed error| over the last second", "%",
               worst_after / target_rpm * 100.0);
    scn_common_metrics(c);
    scn_metric(c, "faults", "fault bits raised", "", (double)c->faults_seen);
}

/* The cold start of a motor file: its optional [demo] section gives start_rpm and
   start_load_nm; by default half the rated speed at the nominal torque. */
static void scn_start_point(const scn_table_t *tab, const sim_motor_t *m, double *rpm, double *nm)
{
    scn_kv_t kv[64];
    const int n = scn_targets_load(tab->motor_file, kv, 64);
    int k;
    *rpm = 10.0 * floor(m->rated_speed_rpm / 20.0 + 0.5);
    *nm = m->nominal_torque_nm;
    for (k = 0; k < n; k++) {
        if (strcmp(kv[k].section, "demo") == 0 && strcmp(kv[k].key, "start_rpm") == 0) {
            *rpm = kv[k].v;
        } else if (strcmp(kv[k].section, "demo") == 0 && strcmp(kv[k].key, "start_load_nm") == 0) {
            *nm = kv[k].v;
        } else {
            /* other keys */
        }
    }
}

static int scn_cold_start(scn_ctx_t *c, const scn_table_t *tab, const sim_motor_t *m)
{
    char text[600];
    double target;
    double load;
    int rc;
    scn_start_point(tab, m, &target, &load);
    rc = scn_rig(c, tab, tab->table, m, m->vdc_nominal_v, load, 0.0, 7u, 0.05);
    if (rc == 0) {
        snprintf(c->r->title, sizeof c->r->title, "Cold start to %.0f rpm at %.3g N m (%s, %.0f kHz PWM)",
                 target, load, tab->name, m->f_pwm_hz / 1000.0);
        snprintf(text, sizeof text,
                 "From standstill at an unknown angle the drive precharges, calibrates the current "
                 "offsets, aligns the rotor (ALIGN), accelerates it with an I/f current (OPEN_LOOP) and "
                 "hands over to the sensorless speed loop (CLOSED_LOOP) once the flux observer and PLL "
                 "agree with the open-loop frame, then ramps to %.0f rpm against a passive compressor "
                 "load of %.3g N m at %.0f V. Look for the bumpless handover in the d/q currents and "
                 "the angle error settling within a few degrees.",
                 target, load, m->vdc_nominal_v);
        snprintf(c->r->description, sizeof c->r->description, "%s", text);
        snprintf(c->r->requirements, sizeof c->r->requirements, "REQ-SCN-001, REQ-DRV-014");
        c->r->zoom_t0_s = 6.0;
        c->r->zoom_t1_s = 6.0 + 3.0 * 60.0 / (target * m->pole_pairs);
        scn_cold_start_body(c, target, 7.0);
    }
    return rc;
}

static int scn_speed_steps(scn_ctx_t *c, const scn_table_t *tab, const sim_motor_t *m)
{
    static const double tgt[4] = { 3000.0, 6000.0, 8000.0, 1500.0 };
    static const double t_cmd[4] = { 0.0, 5.0, 9.0, 13.0 };
    static const char *const ev[4] = { "run, 3000 rpm", "6000 rpm", "8000 rpm", "1500 rpm" };
    dsim_t *ds = c->ds;
    scn_seg_t seg[4];
    double id_sum = 0.0;
    long id_n = 0;
    double util_max = 0.0;
    int k = -1;
    int rc = scn_rig(c, tab, tab->table, m, 320.0, m->nominal_torque_nm, 0.0, 7u, 0.05);
    if (rc != 0) {
        return rc;
    }
    scn_describe(c->r, "Speed steps 3000 -> 6000 -> 8000 -> 1500 rpm", "REQ-SCN-002, REQ-DRV-013",
                 "After a cold start to 3000 rpm the master commands 6000 rpm (rated), 8000 rpm "
                 "(maximum, above the base speed at 320 V: the field-weakening loop drives i_d "
                 "negative to keep the voltage inside the hexagon) and 1500 rpm, at the nominal "
                 "compressor load. The speed reference ramps at the table's 3000 rpm/s. Look for "
                 "i_d going negative at 8000 rpm and returning to zero at 1500 rpm, and the angle "
                 "error staying small through the transients.");
    c->r->t_end_s = 17.0;
    c->r->zoom_t0_s = 12.5;
    c->r->zoom_t1_s = 12.5 + 4.0 * 60.0 / (8000.0 * m->pole_pairs);
    ds->power_on = true;
    while (scn_time(c) < c->r->t_end_s - 1e-9) {
        const double t = scn_time(c);
        double rpm;
        if (k < 3 && t >= t_cmd[k + 1] - 1e-9) {
            k++;
            scn_seg_start(&seg[k], tgt[k], dsim_rpm(ds), t);
            ds->target_rpm = (uint16_t)tgt[k];
            scn_event(c, ev[k]);
        }
        scn_ms(c);
        rpm = dsim_rpm(ds);
        scn_seg_track(&seg[k], scn_time(c), rpm,
                      scn_time(c) > ((k < 3) ? t_cmd[k + 1] : c->r->t_end_s) - 1.0);
        if (k == 2 && scn_time(c) > t_cmd[3] - 1.0) {
            id_sum += ds->plant.id;
            id_n++;
        }
        util_max = fmax(util_max, (double)ds->drv.s.util / 32768.0);
    }
    scn_metric(c, "t_closed_loop_s", "time from the run command to CLOSED_LOOP", "s",
               (c->t_cl >= 0.0) ? c->t_cl : NAN);
    scn_metric(c, "t_reach_6000_s", "3000 -> 6000 rpm: time to within 2 %", "s", seg[1].t_reach);
    scn_metric(c, "overshoot_6000_pct", "3000 -> 6000 rpm: overshoot", "%", scn_seg_over_pct(&seg[1]));
    scn_metric(c, "ss_err_6000_pct", "6000 rpm: steady-state error (mean |error|, last second)", "%",
               scn_seg_ss_pct(&seg[1]));
    scn_metric(c, "t_reach_8000_s", "6000 -> 8000 rpm: time to within 2 %", "s", seg[2].t_reach);
    scn_metric(c, "overshoot_8000_pct", "6000 -> 8000 rpm: overshoot", "%", scn_seg_over_pct(&seg[2]));
    scn_metric(c, "ss_err_8000_pct", "8000 rpm: steady-state error (mean |error|, last second)", "%",
               scn_seg_ss_pct(&seg[2]));
    scn_metric(c, "id_8000_a", "8000 rpm: mean i_d (field weakening)", "A",
               (id_n > 0) ? id_sum / (double)id_n : NAN);
    scn_metric(c, "utilisation_max", "max SVPWM voltage utilisation", "", util_max);
    scn_metric(c, "t_reach_1500_s", "8000 -> 1500 rpm: time to within 2 %", "s", seg[3].t_reach);
    scn_metric(c, "undershoot_1500_pct", "8000 -> 1500 rpm: undershoot", "%", scn_seg_over_pct(&seg[3]));
    scn_metric(c, "ss_err_1500_pct", "1500 rpm: steady-state error (mean |error|, last second)", "%",
               scn_seg_ss_pct(&seg[3]));
    scn_common_metrics(c);
    scn_metric(c, "faults", "fault bits raised", "", (double)c->faults_seen);
    return 0;
}

/* Speed ripple (peak to peak) of the last 2 s at 1500 rpm; one run. */
static int scn_pulsating_run(scn_ctx_t *c, const scn_table_t *tab, const qfoc_param_table_t *table,
                             const sim_motor_t *m, double *ripple, double *err_pct)
{
    dsim_t *ds = c->ds;
    double lo = INFINITY;
    double hi = -INFINITY;
    double sum = 0.0;
    long n = 0;
    int rc = scn_rig(c, tab, table, m, 320.0, 3.0, 0.5, 7u, 0.05);
    if (rc == 0) {
        ds->power_on = true;
        ds->target_rpm = 1500u;
        scn_event(c, "run, 1500 rpm");
        while (scn_time(c) < c->r->t_end_s - 1e-9) {
            scn_ms(c);
            if (scn_time(c) > c->r->t_end_s - 2.0) {
                lo = fmin(lo, dsim_rpm(ds));
                hi = fmax(hi, dsim_rpm(ds));
                sum += fabs(dsim_rpm(ds) - 1500.0);
                n++;
            }
        }
        *ripple = hi - lo;
        *err_pct = sum / (double)n / 1500.0 * 100.0;
    }
    return rc;
}

static int scn_pulsating(scn_ctx_t *c, const scn_table_t *tab, const sim_motor_t *m)
{
    qfoc_param_table_t off = *tab->table;
    double r_off = NAN;
    double r_on = NAN;
    double e_off = NAN;
    double e_on = NAN;
    FILE *trace = c->trace;
    FILE *zoom = c->zoom;
    int rc;
    scn_describe(c->r, "Pulsating compressor load at 1500 rpm, without and with torque compensation",
                 "REQ-SCN-003, REQ-DRV-013",
                 "A single-cylinder compressor loads the shaft with a torque that pulsates once per "
                 "mechanical revolution: here 3 N m +-50 %. At 1500 rpm the speed loop alone cannot "
                 "follow it and the speed ripples; the torque compensation learns the pulsation "
                 "against the mechanical angle and feeds the matching q current forward. The same "
                 "scenario runs twice: with the table's compensation gain set to zero (grey, the "
                 "comparison trace) and with the generated table. Look at the speed ripple in the "
                 "last seconds and at i_q taking the shape of the load.");
    c->r->t_end_s = 14.0;
    c->r->zoom_t0_s = 13.96;
    c->r->zoom_t1_s = 14.0;
    snprintf(c->r->compare_file, sizeof c->r->compare_file, "trace_off.csv");
    snprintf(c->r->compare_label, sizeof c->r->compare_label, "without torque compensation");
    off.drive.tc_gain = 0;
    off.crc = qfoc_params_crc(&off);
    c->trace = scn_open(c->o, "trace_off.csv");
    if (c->trace != NULL) {
        fputs(scn_trace_header, c->trace);
    }
    c->zoom = NULL;
    rc = scn_pulsating_run(c, tab, &off, m, &r_off, &e_off);
    if (c->trace != NULL) {
        fclose(c->trace);
    }
    c->trace = trace;
    c->zoom = zoom;
    if (rc == 0) {
        scn_reset_trackers(c);
        c->r->n_events = 0;
        rc = scn_pulsating_run(c, tab, tab->table, m, &r_on, &e_on);
    }
    if (rc == 0) {
        scn_metric(c, "ripple_off_rpm", "speed ripple p-p, last 2 s, without compensation", "rpm", r_off);
        scn_metric(c, "ripple_on_rpm", "speed ripple p-p, last 2 s, with compensation", "rpm", r_on);
        scn_metric(c, "ripple_reduction_pct", "speed ripple removed by the compensation", "%",
                   (1.0 - r_on / r_off) * 100.0);
        scn_metric(c, "ss_err_pct", "mean |speed error|, last 2 s, with compensation", "%", e_on);
        scn_common_metrics(c);
        scn_metric(c, "faults", "fault bits raised", "", (double)c->faults_seen);
    }
    return rc;
}

/* MTPA, one run (REQ-SCN-013): 3000 rpm at the nominal load; the mean current magnitude
   (the plant's) and the mean electromagnetic torque of the last second. */
static int scn_mtpa_run(scn_ctx_t *c, const scn_table_t *tab, const qfoc_param_table_t *table,
                        const sim_motor_t *m, double *i_mean, double *t_mean, double *id_mean)
{
    dsim_t *ds = c->ds;
    double si = 0.0;
    double st = 0.0;
    double sd = 0.0;
    long n = 0;
    int rc = scn_rig(c, tab, table, m, 320.0, m->nominal_torque_nm, 0.0, 7u, 0.05);
    if (rc == 0) {
        ds->power_on = true;
        ds->target_rpm = 3000u;
        scn_event(c, "run, 3000 rpm");
        while (scn_time(c) < c->r->t_end_s - 1e-9) {
            scn_ms(c);
            if (scn_time(c) > c->r->t_end_s - 1.0) {
                si += hypot(ds->plant.id, ds->plant.iq);
                st += sim_torque(&ds->plant);
                sd += ds->plant.id;
                n++;
            }
        }
        *i_mean = si / (double)n;
        *t_mean = st / (double)n;
        *id_mean = sd / (double)n;
    }
    return rc;
}

/* The analytic MTPA current of a torque (specs/equations.md E9-2): the q current whose
   MTPA pair gives the torque, found by bisection in double precision; returns |i|. */
static double scn_mtpa_current(const sim_motor_t *m, double torque)
{
    const double k = 1.5 * m->pole_pairs;
    const double dl = m->lq_h - m->ld_h;
    double lo = 0.0;
    double hi = 4.0 * torque / (k * m->psi_f_wb) + 1.0;
    double iq = 0.0;
    double id = 0.0;
    int j;
    for (j = 0; j < 200; j++) {
        iq = 0.5 * (lo + hi);
        id = (dl > 0.0) ? (m->psi_f_wb / (2.0 * dl) -
                           sqrt(m->psi_f_wb * m->psi_f_wb / (4.0 * dl * dl) + iq * iq)) : 0.0;
        if (k * iq * (m->psi_f_wb + (m->ld_h - m->lq_h) * id) < torque) {
            lo = iq;
        } else {
            hi = iq;
        }
    }
    return hypot(id, iq);
}

static int scn_mtpa(scn_ctx_t *c, const scn_table_t *tab, const sim_motor_t *m)
{
    qfoc_param_table_t off = *tab->table;
    double i_off = NAN;
    double i_on = NAN;
    double t_off = NAN;
    double t_on = NAN;
    double id_off = NAN;
    double id_on = NAN;
    FILE *trace = c->trace;
    FILE *zoom = c->zoom;
    int rc;
    scn_describe(c->r, "MTPA at 3000 rpm and the nominal load, against i_d = 0", "REQ-SCN-013",
                 "The salient reference motor (L_q / L_d = 1.6) carries its nominal 4.5 N m at "
                 "3000 rpm twice: with MTPA off (the table's mtpa_speed above speed_max: i_d = 0, "
                 "grey) and with the generated table (MTPA above the handover speed). MTPA "
                 "gives the same torque with a negative i_d and less current; the reduction of "
                 "the current magnitude is compared with the analytic MTPA prediction for the "
                 "torque the motor delivers (specs/equations.md E9-2).");
    c->r->t_end_s = 7.0;
    c->r->zoom_t0_s = 6.98;
    c->r->zoom_t1_s = 7.0;
    snprintf(c->r->compare_file, sizeof c->r->compare_file, "trace_off.csv");
    snprintf(c->r->compare_label, sizeof c->r->compare_label, "without MTPA (i_d = 0)");
    off.drive.mtpa_speed = 32767;
    off.crc = qfoc_params_crc(&off);
    c->trace = scn_open(c->o, "trace_off.csv");
    if (c->trace != NULL) {
        fputs(scn_trace_header, c->trace);
    }
    c->zoom = NULL;
    rc = scn_mtpa_run(c, tab, &off, m, &i_off, &t_off, &id_off);
    if (c->trace != NULL) {
        fclose(c->trace);
    }
    c->trace = trace;
    c->zoom = zoom;
    if (rc == 0) {
        scn_reset_trackers(c);
        c->r->n_events = 0;
        rc = scn_mtpa_run(c, tab, tab->table, m, &i_on, &t_on, &id_on);
    }
    if (rc == 0) {
        /* the prediction for the torque of the MTPA run: the i_d = 0 current T / (k psi_f)
           against the MTPA current of the same torque */
        const double i0 = t_on / (1.5 * m->pole_pairs * m->psi_f_wb);
        const double pred = (1.0 - scn_mtpa_current(m, t_on) / i0) * 100.0;
        const double meas = (1.0 - i_on / i_off) * 100.0;
        scn_metric(c, "i_off_a", "mean |i| with i_d = 0, last second", "A", i_off);
        scn_metric(c, "i_on_a", "mean |i| with MTPA, last second", "A", i_on);
        scn_metric(c, "id_on_a", "mean i_d with MTPA, last second", "A", id_on);
        scn_metric(c, "torque_on_nm", "mean torque with MTPA, last second", "N m", t_on);
        scn_metric(c, "torque_off_nm", "mean torque with i_d = 0, last second", "N m", t_off);
        scn_metric(c, "reduction_pct", "current reduction by MTPA, measured", "%", meas);
        scn_metric(c, "reduction_pred_pct", "current reduction by MTPA, analytic (E9-2)", "%", pred);
        scn_metric(c, "reduction_err_pp", "measured - analytic reduction", "pp", fabs(meas - pred));
        scn_common_metrics(c);
        scn_metric(c, "faults", "fault bits raised", "", (double)c->faults_seen);
    }
    return rc;
}

/* Flying start (REQ-SCN-015): one restart of a coasting compressor; the run command comes
   when the drive is ready (STOP) and the rotor turns at rpm0.  Returns the time from the
   command to within 2 % of the target (NAN: never), whether CATCH caught the rotor, and
   the true speed when CLOSED_LOOP was entered. */
static int scn_flying_run(scn_ctx_t *c, const scn_table_t *tab, const sim_motor_t *m,
                          double rpm0, double target_rpm, double t_run, double *t_target,
                          bool *caught, double *rpm_cl)
{
    dsim_t *ds = c->ds;
    /* pressure equalised through the compressor: a light passive load while it coasts */
    int rc = scn_rig(c, tab, tab->table, m, 320.0, 0.2, 0.0, 23u, 0.05);
    bool in_align = false;
    *t_target = NAN;
    *caught = false;
    *rpm_cl = NAN;
    if (rc == 0) {
        double t_cmd;
        long guard = 0;
        while (ds->drv.s.sm.state != QFOC_STATE_STOP && guard < 2000) {
            scn_ms(c);
            guard++;
        }
        /* the compressor turns at rpm0 (a short stop, or the pressure equalising) */
        sim_set_state(&ds->plant, 0.3, rpm0 / 60.0 * 2.0 * SIM_PI * m->pole_pairs, 0.0, 0.0);
        ds->power_on = true;
        ds->target_rpm = (uint16_t)lround(target_rpm);
        t_cmd = scn_time(c);
        scn_event(c, "run command, rotor coasting");
        while (scn_time(c) < t_cmd + t_run - 1e-9) {
            const uint8_t sub_before = ds->drv.s.sm.sub;
            scn_ms(c);
            if (ds->drv.s.sm.sub == QFOC_SUB_ALIGN) {
                in_align = true;
            }
            if (sub_before == QFOC_SUB_CATCH && ds->drv.s.sm.sub == QFOC_SUB_CLOSED_LOOP) {
                *caught = true;
                scn_event(c, "caught");
            }
            if (isnan(*rpm_cl) && ds->drv.s.sm.sub == QFOC_SUB_CLOSED_LOOP) {
                *rpm_cl = dsim_rpm(ds);
            }
            if (isnan(*t_target) && fabs(dsim_rpm(ds) - target_rpm) <= 0.02 * target_rpm) {
                *t_target = scn_time(c) - t_cmd;
            }
        }
        if (*caught && in_align) {
            *caught = false;   /* both paths in one run: not a clean catch */
        }
    }
    return rc;
}

static int scn_flying(scn_ctx_t *c, const scn_table_t *tab, const sim_motor_t *m)
{
    /* the restart speeds: +50 %, +10 %, 0 and -20 % of the rated speed */
    static const double frac[4] = { 0.5, 0.1, 0.0, -0.2 };
    static const char *const tag[4] = { "p50", "p10", "zero", "m20" };
    const double target = 4000.0;
    FILE *trace = c->trace;
    FILE *zoom = c->zoom;
    int rc = 0;
    int k;
    scn_describe(c->r, "Flying start: restarts of a coasting compressor at +50 %, +10 %, 0 and "
                 "-20 % of the rated speed", "REQ-SCN-015, REQ-DRV-027",
                 "The drive is ready when the run command comes, with the rotor still turning "
                 "(a short stop, or the pressure equalising through the compressor, which can "
                 "turn it backwards). CATCH runs zero-current control and the observer: at +50 % "
                 "it catches the rotor and closes the loop at its speed; at +10 % (below the "
                 "handover speed, where the observer is not trusted) and at -20 % it waits, with "
                 "no torque, until the load has stopped the rotor, then starts as from standstill; "
                 "at 0 it starts at once. The trace is the +50 % restart; each run goes to "
                 "4000 rpm.");
    c->r->t_end_s = 4.3;      /* PRECHARGE (0.27 s), then 4 s from the run command */
    c->r->zoom_t0_s = 0.30;
    c->r->zoom_t1_s = 0.34;
    for (k = 0; (k < 4) && (rc == 0); k++) {
        double t_target;
        double rpm_cl;
        bool caught;
        char key[64];
        char text[128];
        const double rpm0 = frac[k] * m->rated_speed_rpm;
        const int n_ev = c->r->n_events;
        if (k > 0) {
            c->trace = NULL;
            c->zoom = NULL;
        }
        scn_reset_trackers(c);
        rc = scn_flying_run(c, tab, m, rpm0, target, 4.0, &t_target, &caught, &rpm_cl);
        if (k > 0) {
            c->r->n_events = n_ev;   /* the events of the traced run only */
        }
        if (rc == 0) {
            snprintf(key, sizeof key, "t_target_%s_s", tag[k]);
            snprintf(text, sizeof text, "%+.0f rpm: run command to within 2 %% of 4000 rpm", rpm0);
            scn_metric(c, key, text, "s", t_target);
            snprintf(key, sizeof key, "caught_%s", tag[k]);
            snprintf(text, sizeof text, "%+.0f rpm: caught by CATCH (1) or started from ALIGN (0)", rpm0);
            scn_metric(c, key, text, "", caught ? 1.0 : 0.0);
            snprintf(key, sizeof key, "rpm_closed_loop_%s", tag[k]);
            snprintf(text, sizeof text, "%+.0f rpm: true speed when the loop closed", rpm0);
            scn_metric(c, key, text, "rpm", rpm_cl);
            snprintf(key, sizeof key, "i_peak_pct_trip_%s", tag[k]);
            snprintf(text, sizeof text, "%+.0f rpm: peak phase current / over-current trip", rpm0);
            scn_metric(c, key, text, "%", c->ipk_all / c->i_trip_a * 100.0);
            snprintf(key, sizeof key, "faults_%s", tag[k]);
            snprintf(text, sizeof text, "%+.0f rpm: fault bits raised", rpm0);
            scn_metric(c, key, text, "", (double)c->faults_seen);
        }
    }
    c->trace = trace;
    c->zoom = zoom;
    return rc;
}

/* Thermal derating (REQ-SCN-014): at 6000 rpm the IPM warms from 60 degC into the derating
   window and back; the speed follows the derated limit and recovers, no OT. */
static int scn_derating(scn_ctx_t *c, const scn_table_t *tab, const sim_motor_t *m)
{
    dsim_t *ds = c->ds;
    const qfoc_drive_cfg_t *const dc = &tab->table->drive;
    const double t_start = 0.1 * (double)dc->t_ipm_derate;
    const double t_trip = 0.1 * (double)dc->t_ipm_max;
    /* the hold: three quarters into the window, below the trip */
    const double t_hold = t_start + 0.75 * (t_trip - t_start);
    const double lim = (double)dc->rpm_max -
                       floor(((double)dc->rpm_max - (double)dc->rpm_derate) * 0.75);
    const double target = 6000.0;
    double temp = 60.0;
    double t_max = 0.0;
    double rpm_hold_min = INFINITY;
    double rpm_hold_max = -INFINITY;
    double err_end = 0.0;
    bool derated_seen = false;
    bool derated_end = true;
    int rc = scn_rig(c, tab, tab->table, m, 320.0, m->nominal_torque_nm, 0.0, 7u, 0.05);
    if (rc != 0) {
        return rc;
    }
    scn_describe(c->r, "Thermal derating at 6000 rpm: the IPM warms into the window and cools",
                 "REQ-SCN-014, REQ-DRV-024",
                 "At 6000 rpm and nominal load the power module's temperature climbs at 5 degC/s "
                 "from 60 degC to three quarters into its derating window (below the trip), "
                 "holds there 4 s and cools back. The speed limit falls linearly from rpm_max at "
                 "the derating temperature to rpm_derate at the trip: the drive ramps down to "
                 "the limit, holds it without a fault and returns to 6000 rpm when the module "
                 "has cooled. Look at the speed following the limit and the temperature never "
                 "reaching the trip.");
    c->r->t_end_s = 30.0;
    c->r->zoom_t0_s = 29.98;
    c->r->zoom_t1_s = 30.0;
    ds->power_on = true;
    ds->target_rpm = (uint16_t)target;
    scn_event(c, "run, 6000 rpm");
    while (scn_time(c) < c->r->t_end_s - 1e-9) {
        const double t = scn_time(c);
        const double t_up = 6.0;
        const double t_up_end = t_up + (t_hold - 60.0) / 5.0;
        const double t_down = t_up_end + 4.0;
        if (t < t_up) {
            temp = 60.0;
        } else if (t < t_up_end) {
            temp = 60.0 + 5.0 * (t - t_up);
        } else if (t < t_down) {
            temp = t_hold;
        } else {
            temp = fmax(60.0, t_hold - 5.0 * (t - t_down));
        }
        if (fabs(t - t_up) < 1e-9) {
            scn_event(c, "IPM warms");
        }
        if (fabs(t - t_down) < 1e-9) {
            scn_event(c, "IPM cools");
        }
        ds->t_ipm = (int16_t)lround(temp * 10.0);
        t_max = fmax(t_max, temp);
        scn_ms(c);
        derated_seen = derated_seen || qfoc_drive_derated(&ds->drv);
        if ((scn_time(c) > t_down - 1.0) && (scn_time(c) <= t_down)) {
            rpm_hold_min = fmin(rpm_hold_min, dsim_rpm(ds));
            rpm_hold_max = fmax(rpm_hold_max, dsim_rpm(ds));
        }
        if (scn_time(c) > c->r->t_end_s - 1.0) {
            err_end = fmax(err_end, fabs(dsim_rpm(ds) - target) / target * 100.0);
            derated_end = derated_end && qfoc_drive_derated(&ds->drv);
        }
    }
    scn_metric(c, "t_ipm_max_c", "highest IPM temperature", "degC", t_max);
    scn_metric(c, "t_trip_margin_c", "trip temperature - highest IPM temperature", "degC",
               t_trip - t_max);
    scn_metric(c, "limit_rpm", "derated speed limit at the hold (rpm_max .. rpm_derate)", "rpm",
               lim);
    scn_metric(c, "hold_dev_pct", "max |speed - limit| in the last second of the hold", "%",
               fmax(fabs(rpm_hold_min - lim), fabs(rpm_hold_max - lim)) / lim * 100.0);
    scn_metric(c, "derated_seen", "qfoc_drive_derated() true at some tick", "",
               derated_seen ? 1.0 : 0.0);
    scn_metric(c, "derated_end", "qfoc_drive_derated() true in the last second", "",
               derated_end ? 1.0 : 0.0);
    scn_metric(c, "recovered_err_pct", "max |speed error| at 6000 rpm in the last second", "%",
               err_end);
    scn_common_metrics(c);
    scn_metric(c, "faults", "fault bits raised", "", (double)c->faults_seen);
    return 0;
}

static int scn_load_step(scn_ctx_t *c, const scn_table_t *tab, const sim_motor_t *m)
{
    dsim_t *ds = c->ds;
    const double t_step = 4.0;
    double dip = 0.0;
    double t_out = NAN;     /* last time outside the 2 % band after the step */
    double ang_max = 0.0;
    double ss_sum = 0.0;
    long ss_n = 0;
    int rc = scn_rig(c, tab, tab->table, m, 320.0, 0.0, 0.0, 7u, 0.05);
    if (rc != 0) {
        return rc;
    }
    scn_describe(c->r, "Load step of 100 % rated torque at 3000 rpm", "REQ-SCN-004",
                 "The compressor runs unloaded at 3000 rpm; at 4 s its full rated torque is applied "
                 "at once (4.5 N m, a valve opening against the discharge pressure). The speed "
                 "dips while the speed PI raises i_q, then recovers. Look at the dip, the recovery "
                 "time and the angle error during the transient.");
    c->r->t_end_s = 6.5;
    c->r->zoom_t0_s = t_step - 0.005;
    c->r->zoom_t1_s = t_step + 0.03;
    ds->power_on = true;
    ds->target_rpm = 3000u;
    scn_event(c, "run, 3000 rpm");
    while (scn_time(c) < c->r->t_end_s - 1e-9) {
        double rpm;
        if (fabs(scn_time(c) - t_step) < 1e-9) {
            ds->plant.cfg.load.t_mean = m->nominal_torque_nm;
            scn_event(c, "load step +100 %");
        }
        scn_ms(c);
        rpm = dsim_rpm(ds);
        if (scn_time(c) > t_step) {
            dip = fmax(dip, 3000.0 - rpm);
            if (fabs(rpm - 3000.0) > 60.0) {
                t_out = scn_time(c) - t_step;
            }
            if (ds->pwm.enable && scn_in_cl(ds)) {
                ang_max = fmax(ang_max, fabs(dsim_angle_err_deg(ds)));
            }
            if (scn_time(c) > c->r->t_end_s - 1.0) {
                ss_sum += fabs(rpm - 3000.0);
                ss_n++;
            }
        }
    }
    scn_metric(c, "dip_rpm", "speed dip after the step", "rpm", dip);
    scn_metric(c, "dip_pct", "speed dip after the step / 3000 rpm", "%", dip / 30.0);
    scn_metric(c, "t_recover_s", "time from the step until the speed stays within 2 %", "s",
               isnan(t_out) ? 0.0 : t_out);
    scn_metric(c, "ss_err_pct", "steady-state speed error after the step (last second)", "%",
               (ss_n > 0) ? ss_sum / (double)ss_n / 30.0 : NAN);
    scn_metric(c, "angle_err_step_max_deg", "max |angle error| after the step", "deg", ang_max);
    scn_common_metrics(c);
    scn_metric(c, "faults", "fault bits raised", "", (double)c->faults_seen);
    return 0;
}

static int scn_bus_sag(scn_ctx_t *c, const scn_table_t *tab, const sim_motor_t *m)
{
    dsim_t *ds = c->ds;
    const double t0 = 5.0;
    double dev = 0.0;
    double id_before = 0.0;
    double id_min = 0.0;
    double ang_max = 0.0;
    double ss_sum = 0.0;
    long ss_n = 0;
    long n_before = 0;
    int rc = scn_rig(c, tab, tab->table, m, 320.0, m->nominal_torque_nm, 0.0, 7u, 0.05);
    if (rc != 0) {
        return rc;
    }
    scn_describe(c->r, "DC-bus sag 320 -> 250 -> 320 V at 6000 rpm", "REQ-SCN-005",
                 "At the rated 6000 rpm and nominal load the DC bus sags from 320 V to the minimum "
                 "operating 250 V within 100 ms (the vehicle's high-voltage battery under a heavy "
                 "load), stays there 2 s and recovers. The drive measures the bus every PWM period: "
                 "the voltage limit and the field weakening follow it, so i_d goes more negative "
                 "during the sag while the speed holds. Look at the speed staying within 2 % and "
                 "no fault.");
    c->r->t_end_s = 9.5;
    c->r->zoom_t0_s = 6.5;
    c->r->zoom_t1_s = 6.5 + 3.0 * 60.0 / (6000.0 * m->pole_pairs);
    ds->power_on = true;
    ds->target_rpm = 6000u;
    scn_event(c, "run, 6000 rpm");
    while (scn_time(c) < c->r->t_end_s - 1e-9) {
        const double t = scn_time(c);
        double v = 320.0;
        if (t >= t0 && t < t0 + 0.1) {
            v = 320.0 - 700.0 * (t - t0);
        } else if (t >= t0 + 0.1 && t < t0 + 2.1) {
            v = 250.0;
        } else if (t >= t0 + 2.1 && t < t0 + 2.2) {
            v = 250.0 + 700.0 * (t - t0 - 2.1);
        } else {
            /* nominal */
        }
        if (fabs(t - t0) < 1e-9) {
            scn_event(c, "sag to 250 V");
        }
        if (fabs(t - t0 - 2.1) < 1e-9) {
            scn_event(c, "back to 320 V");
        }
        ds->plant.cfg.vdc_v = v;
        scn_ms(c);
        if (scn_time(c) > t0 - 1.0 && scn_time(c) <= t0) {
            id_before += ds->plant.id;
            n_before++;
        }
        if (scn_time(c) > t0) {
            dev = fmax(dev, fabs(dsim_rpm(ds) - 6000.0));
            id_min = fmin(id_min, ds->plant.id);
            if (scn_time(c) > c->r->t_end_s - 1.0) {
                ss_sum += fabs(dsim_rpm(ds) - 6000.0);
                ss_n++;
            }
            if (ds->pwm.enable && scn_in_cl(ds)) {
                ang_max = fmax(ang_max, fabs(dsim_angle_err_deg(ds)));
            }
        }
    }
    scn_metric(c, "speed_dev_pct", "max |speed - 6000 rpm| from the sag on", "%", dev / 60.0);
    scn_metric(c, "ss_err_pct", "mean |speed error| over the last second, after the sag", "%",
               (ss_n > 0) ? ss_sum / (double)ss_n / 60.0 : NAN);
    scn_metric(c, "id_before_a", "mean i_d in the second before the sag", "A",
               (n_before > 0) ? id_before / (double)n_before : NAN);
    scn_metric(c, "id_min_a", "most negative i_d during and after the sag", "A", id_min);
    scn_metric(c, "angle_err_sag_max_deg", "max |angle error| from the sag on", "deg", ang_max);
    scn_common_metrics(c);
    scn_metric(c, "faults", "fault bits raised", "", (double)c->faults_seen);
    return 0;
}

/* ------------------------------------------------------------------ faults */

enum { SCN_F_OC, SCN_F_OV, SCN_F_OT, SCN_F_STALL, SCN_F_LINK };

static int scn_fault(scn_ctx_t *c, const scn_table_t *tab, const sim_motor_t *m, int kind)
{
    static const uint16_t bit[5] = { QFOC_FAULT_OC, QFOC_FAULT_OV, QFOC_FAULT_OT_IPM,
                                     QFOC_FAULT_STALL, QFOC_FAULT_LINK };
    dsim_t *ds = c->ds;
    const double t_inj = 4.0;
    const double ov_v = (double)tab->table->vdc_ov / 32768.0 * m->vdc_full_scale_v;
    const double ot_c = (double)tab->table->drive.t_ipm_max * 0.1;
    double temp = 40.0;        /* IPM temperature, degC */
    double t_cond = NAN;       /* the fault condition became true */
    double t_bit = NAN;        /* the fault bit is set */
    double t_err = NAN;        /* ERROR entered */
    double t_pwm_off = NAN;    /* PWM off (end of the ms) */
    double t_removed = NAN;    /* the cause is removed */
    double t_clear = NAN;      /* ERROR left */
    double t_back = NAN;       /* target speed reached again */
    uint16_t word = 0u;        /* fault word on entering ERROR */
    double t_end = 20.0;
    int rc = scn_rig(c, tab, tab->table, m, 320.0, m->nominal_torque_nm, 0.0, 7u, 0.05);
    if (rc != 0) {
        return rc;
    }
    switch (kind) {
    case SCN_F_OC:
        scn_describe(c->r, "Fault: phase over-current", "REQ-SCN-006, REQ-DRV-003",
                     "At 3000 rpm a short-circuit current pulse is seen on phase u: +50 A on the "
                     "sensed current for three PWM periods (injected at the ADC, so the sample is "
                     "above the 30 A trip whatever the phase current was). The fast step must switch the PWM off in the period of the sample, "
                     "the tick latches OC and enters ERROR. The master sees ERROR in the status "
                     "frames and requests a fault clear; the drive accepts it only after 5 s in "
                     "ERROR, then restarts from standstill. Look at the zoom: the PWM stops in the "
                     "same period.");
        c->r->zoom_t0_s = t_inj - 0.004;
        c->r->zoom_t1_s = t_inj + 0.012;
        break;
    case SCN_F_OV:
        scn_describe(c->r, "Fault: DC-bus over-voltage", "REQ-SCN-007, REQ-DRV-008",
                     "At 3000 rpm the DC bus rises from 320 V to 460 V within 20 ms (a load dump on "
                     "the high-voltage bus), above the 441 V over-voltage level. The drive filters "
                     "the bus, debounces the fault for 2 ms, enters ERROR and switches off. The bus "
                     "returns to 320 V 1 s later, the master requests a clear, and the drive "
                     "restarts after its 5 s in ERROR.");
        c->r->zoom_t0_s = t_inj + 0.005;
        c->r->zoom_t1_s = t_inj + 0.025;
        break;
    case SCN_F_OT:
        scn_describe(c->r, "Fault: IPM over-temperature", "REQ-SCN-008, REQ-DRV-008",
                     "At 3000 rpm the power-module temperature climbs from 40 degC at 80 degC/s "
                     "past the 110 degC limit (a failed coolant pump). After the 10 ms debounce the "
                     "drive enters ERROR and switches off; the module cools, the master requests a "
                     "clear once it is below 100 degC, and the drive restarts after its 5 s in "
                     "ERROR.");
        c->r->zoom_t0_s = t_inj + 0.87;
        c->r->zoom_t1_s = t_inj + 0.90;
        break;
    case SCN_F_STALL:
        scn_describe(c->r, "Fault: stall (locked rotor)", "REQ-SCN-009, REQ-DRV-008",
                     "At 3000 rpm the compressor seizes: its load torque jumps to three times the "
                     "nominal, more than the motor can produce at its current limit, and the rotor "
                     "is brought to a standstill and held there. The estimated speed leaves the "
                     "reference and the observer's flux collapses; after 500 ms the drive declares "
                     "STALL, enters ERROR and switches off. The seizure is freed 1 s after ERROR, "
                     "the master requests a clear and the drive restarts after its 5 s in ERROR.");
        c->r->zoom_t0_s = t_inj - 0.005;
        c->r->zoom_t1_s = t_inj + 0.02;
        break;
    default:
        scn_describe(c->r, "Fault: command-link loss", "REQ-SCN-010, REQ-SM-008",
                     "At 3000 rpm the LIN master stops sending (a broken wire). After the 500 ms "
                     "link timeout the drive no longer has a run request: it ramps the speed down "
                     "in STOPPING, and at the end of the ramp, with the link still lost, it raises "
                     "LINK and enters ERROR with the PWM off, so the master sees that the drive "
                     "stopped on its own. The link returns 1 s later, the master requests a clear, "
                     "and the drive restarts after its 5 s in ERROR.");
        c->r->zoom_t0_s = t_inj + 1.1;
        c->r->zoom_t1_s = t_inj + 1.14;
        break;
    }
    c->r->t_end_s = t_end;
    ds->power_on = true;
    ds->target_rpm = 3000u;
    scn_event(c, "run, 3000 rpm");
    while (scn_time(c) < t_end - 1e-9) {
        const double t = scn_time(c);
        const bool in_error = ds->drv.s.sm.state == QFOC_STATE_ERROR;
        /* the fault and its removal */
        if (fabs(t - t_inj) < 1e-9) {
            static const char *const lab[5] = { "+50 A pulse on phase u", "bus rises to 460 V",
                                                "IPM heats up", "compressor seizes",
                                                "master stops sending" };
            scn_event(c, lab[kind]);
            if (kind == SCN_F_OC) {
                c->inj_codes = (int)lround(50.0 / m->i_full_scale_a * 2048.0);
                c->inj_periods = 3;
                c->p_inj = ds->period;
                t_cond = t;
            } else if (kind == SCN_F_STALL) {
                ds->plant.cfg.load.t_mean = 3.0 * m->nominal_torque_nm;
                t_cond = t;
            } else if (kind == SCN_F_LINK) {
                ds->link_alive = false;
                t_cond = t;
            } else {
                /* ramps below */
            }
        }
        if (t >= t_inj && isnan(t_removed)) {
            if (kind == SCN_F_OV) {
                ds->plant.cfg.vdc_v = fmin(460.0, 320.0 + 7000.0 * (t - t_inj));
                if (isnan(t_cond) && ds->plant.cfg.vdc_v > ov_v) {
                    t_cond = t;
                }
            } else if (kind == SCN_F_OT) {
                temp = fmin(120.0, 40.0 + 80.0 * (t - t_inj));
                if (isnan(t_cond) && temp > ot_c) {
                    t_cond = t;
                }
            } else {
                /* step faults */
            }
        }
        if (!isnan(t_err) && isnan(t_removed) && t >= t_err + 1.0) {
            t_removed = t;
            scn_event(c, "cause removed");
            ds->plant.cfg.vdc_v = 320.0;
            ds->plant.cfg.load.t_mean = m->nominal_torque_nm;
            ds->link_alive = true;
        }
        if (kind == SCN_F_OT && !isnan(t_removed)) {
            temp = fmax(60.0, temp - 0.08);   /* cooling at 80 degC/s */
        }
        ds->t_ipm = (int16_t)lround(temp * 10.0);
        if (!isnan(t_cond) && isnan(c->t_watch)) {
            c->t_watch = t_cond;
        }
        /* the master: a clear request while ERROR persists after the cause is gone */
        ds->fault_clear = in_error && !isnan(t_removed) &&
                          (kind != SCN_F_OT || ds->t_ipm < 1000);
        scn_ms(c);
        if (isnan(t_bit) && (ds->drv.s.sm.faults & bit[kind]) != 0u) {
            t_bit = scn_time(c);
        }
        if (isnan(t_err) && ds->drv.s.sm.state == QFOC_STATE_ERROR) {
            t_err = scn_time(c);
            word = ds->drv.s.sm.faults;
            scn_event(c, "ERROR");
        }
        t_pwm_off = c->t_off;
        if (!isnan(t_err) && isnan(t_clear) && ds->drv.s.sm.state != QFOC_STATE_ERROR) {
            t_clear = scn_time(c);
            scn_event(c, "clear accepted");
        }
        if (!isnan(t_clear) && isnan(t_back) && fabs(dsim_rpm(ds) - 3000.0) < 60.0) {
            t_back = scn_time(c);
            t_end = fmin(t_end, t_back + 1.0);
            c->r->t_end_s = t_end;
        }
    }
    scn_metric(c, "fault_bit", "the expected fault bit set on entering ERROR (1 = yes)", "",
               ((word & bit[kind]) != 0u) ? 1.0 : 0.0);
    scn_metric(c, "other_bits", "other fault bits on entering ERROR", "",
               (double)(word & (uint16_t)~bit[kind]));
    if (kind == SCN_F_OC) {
        scn_metric(c, "pwm_off_periods", "PWM periods from the over-current sample to PWM off "
                   "(0 = the same period)", "", (c->p_off >= 0) ? (double)(c->p_off - c->p_inj) : NAN);
    }
    scn_metric(c, "t_detect_ms", (kind == SCN_F_STALL || kind == SCN_F_LINK)
                   ? "time from the event to the fault bit"
                   : "time from the condition (level crossed) to the fault bit",
               "ms", (t_bit - t_cond) * 1000.0);
    scn_metric(c, "t_pwm_off_ms", "time from the condition to the first PWM period with the "
               "switches off", "ms",
               (t_pwm_off - t_cond) * 1000.0);
    scn_metric(c, "t_error_s", "time in ERROR before the clear was accepted", "s", t_clear - t_err);
    scn_metric(c, "t_recover_s", "time from the clear to 3000 rpm again (within 2 %)", "s",
               t_back - t_clear);
    scn_metric(c, "faults_end", "fault word at the end", "", (double)ds->drv.s.sm.faults);
    scn_metric(c, "i_peak_a", "peak phase current", "A", c->ipk_all);
    return 0;
}

/* ------------------------------------------------------------------ entry points */

static int scn_begin(scn_ctx_t *c, const char *scenario, const scn_opts_t *o, scn_result_t *r)
{
    memset(c, 0, sizeof *c);
    memset(r, 0, sizeof *r);
    r->pass = true;
    snprintf(r->name, sizeof r->name, "%s", (o->name != NULL) ? o->name : scenario);
    c->r = r;
    c->o = o;
    c->kind = scenario;
    c->ds = calloc(1, sizeof *c->ds);
    c->kv = calloc(SCN_MAX_KV, sizeof *c->kv);
    scn_reset_trackers(c);
    if (c->ds == NULL || c->kv == NULL) {
        return -1;
    }
    if (o->targets_file != NULL) {
        c->n_kv = scn_targets_load(o->targets_file, c->kv, SCN_MAX_KV);
        if (c->n_kv < 0) {
            return -1;
        }
    }
    if (o->out_dir != NULL) {
        if (scn_mkdir(o->out_dir) != 0) {
            fprintf(stderr, "%s: cannot create\n", o->out_dir);
            return -1;
        }
        c->trace = scn_open(o, "trace.csv");
        c->zoom = scn_open(o, "zoom.csv");
        if (c->trace == NULL || c->zoom == NULL) {
            return -1;
        }
        fputs(scn_trace_header, c->trace);
        fputs("t_s,iu_a,iv_a,iw_a,iu_meas_a,iv_meas_a,duty_u,duty_v,duty_w,pwm_on\n", c->zoom);
    }
    return 0;
}

static int scn_end(scn_ctx_t *c, int rc)
{
    if (c->trace != NULL) {
        fclose(c->trace);
    }
    if (c->zoom != NULL) {
        fclose(c->zoom);
    }
    if (rc == 0 && c->o->out_dir != NULL) {
        rc = scn_write_json(c->r, c->o->out_dir);
    }
    if (c->o->progress) {
        fprintf(stderr, "\r[%d/%d] %-26s simulated %6.2f s: %s%*s\n", c->o->index, c->o->count,
                c->r->name, scn_time(c), (rc != 0) ? "ERROR" : (c->r->pass ? "pass" : "FAIL"), 8, "");
    }
    free(c->ds);
    free(c->kv);
    return rc;
}

int scn_run(const char *scenario, const scn_table_t *tab, const scn_opts_t *o, scn_result_t *r)
{
    scn_ctx_t c;
    sim_motor_t m;
    int rc = scn_begin(&c, scenario, o, r);
    if (rc == 0) {
        rc = scn_table_motor(tab, &m);
    }
    if (rc == 0) {
        if (strcmp(scenario, "cold_start") == 0) {
            rc = scn_cold_start(&c, tab, &m);
        } else if (strcmp(scenario, "speed_steps") == 0) {
            rc = scn_speed_steps(&c, tab, &m);
        } else if (strcmp(scenario, "pulsating_load") == 0) {
            rc = scn_pulsating(&c, tab, &m);
        } else if (strcmp(scenario, "load_step") == 0) {
            rc = scn_load_step(&c, tab, &m);
        } else if (strcmp(scenario, "mtpa") == 0) {
            rc = scn_mtpa(&c, tab, &m);
        } else if (strcmp(scenario, "derating") == 0) {
            rc = scn_derating(&c, tab, &m);
        } else if (strcmp(scenario, "flying_start") == 0) {
            rc = scn_flying(&c, tab, &m);
        } else if (strcmp(scenario, "bus_sag") == 0) {
            rc = scn_bus_sag(&c, tab, &m);
        } else if (strcmp(scenario, "fault_oc") == 0) {
            rc = scn_fault(&c, tab, &m, SCN_F_OC);
        } else if (strcmp(scenario, "fault_ov") == 0) {
            rc = scn_fault(&c, tab, &m, SCN_F_OV);
        } else if (strcmp(scenario, "fault_ot") == 0) {
            rc = scn_fault(&c, tab, &m, SCN_F_OT);
        } else if (strcmp(scenario, "fault_stall") == 0) {
            rc = scn_fault(&c, tab, &m, SCN_F_STALL);
        } else if (strcmp(scenario, "fault_link") == 0) {
            rc = scn_fault(&c, tab, &m, SCN_F_LINK);
        } else {
            fprintf(stderr, "unknown scenario '%s'\n", scenario);
            rc = -1;
        }
    }
    return scn_end(&c, rc);
}

int scn_run_start(const scn_table_t *tab, const scn_start_t *st, const scn_opts_t *o,
                  scn_result_t *r)
{
    static const scn_start_ext_t none = { 1.0, 0.0, 0.0 };
    const scn_start_ext_t *x = (o->start_ext != NULL) ? o->start_ext : &none;
    scn_ctx_t c;
    sim_motor_t m;
    int rc = scn_begin(&c, "robust_start", o, r);
    if (rc == 0) {
        rc = scn_table_motor(tab, &m);
    }
    if (rc == 0) {
        const double target = 10.0 * floor(m.rated_speed_rpm / 20.0 + 0.5);
        /* the table's compensation in seconds: one compare count is 2 timer ticks */
        const double t_comp = 2.0 * (double)tab->table->svpwm.dt_comp / m.f_timer_hz;
        m.rs_ohm *= 1.0 + st->rs_err;
        m.ld_h *= 1.0 + st->ld_err;
        m.lq_h *= 1.0 + st->lq_err;
        m.psi_f_wb *= 1.0 + st->psi_err;
        rc = scn_rig(&c, tab, tab->table, &m, st->vdc_v, st->load_nm, 0.0, st->seed, st->noise_a);
        if (rc == 0) {
            char text[800];
            char more[200] = "";
            sim_t *p = &c.ds->plant;
            if (x->dead_time_ratio != 1.0) {
                p->cfg.dead_time_s = x->dead_time_ratio * t_comp;
            }
            p->cfg.load.t_break = x->t_break_nm;
            sim_set_state(p, st->theta0_deg * SIM_PI / 180.0, 0.0, 0.0, 0.0);
            if (x->w0_frac != 0.0) {
                /* a restart: the drive is ready (STOP) and the rotor still coasts */
                long guard = 0;
                while (c.ds->drv.s.sm.state != QFOC_STATE_STOP && guard < 2000) {
                    scn_ms(&c);
                    guard++;
                }
                sim_set_state(p, st->theta0_deg * SIM_PI / 180.0,
                              x->w0_frac * m.rated_speed_rpm / 60.0 * 2.0 * SIM_PI * m.pole_pairs,
                              0.0, 0.0);
                snprintf(more, sizeof more, " Restart with the rotor coasting at %+.0f rpm.",
                         x->w0_frac * m.rated_speed_rpm);
            }
            if (x->dead_time_ratio != 1.0 || x->t_break_nm > 0.0) {
                snprintf(more, sizeof more,
                         " Inverter dead time %.2f us (%.2f x the table's compensation of %.2f us); "
                         "breakaway torque %.2f N m.",
                         p->cfg.dead_time_s * 1e6, x->dead_time_ratio, t_comp * 1e6, x->t_break_nm);
            }
            snprintf(c.r->title, sizeof c.r->title, "Robustness: cold start, seed %u", (unsigned)st->seed);
            snprintf(text, sizeof text,
                     "Cold start to %.0f rpm (table %s) with the plant's parameters off the table's: "
                     "R_s %+.1f %%, L_d %+.1f %%, L_q %+.1f %%, psi_f %+.1f %%; load %.2f N m, bus %.0f V, "
                     "current noise %.3f A rms, initial rotor angle %.0f deg (electrical).%s",
                     target, tab->name, st->rs_err * 100.0, st->ld_err * 100.0, st->lq_err * 100.0,
                     st->psi_err * 100.0, st->load_nm, st->vdc_v, st->noise_a, st->theta0_deg, more);
            snprintf(c.r->description, sizeof c.r->description, "%s", text);
            snprintf(c.r->requirements, sizeof c.r->requirements, "%s",
                     (x->w0_frac != 0.0) ? "REQ-SCN-011, REQ-DRV-027" : "REQ-SCN-011");
            c.r->zoom_t0_s = 6.0;
            c.r->zoom_t1_s = 6.0 + 3.0 * 60.0 / (target * m.pole_pairs);
            scn_cold_start_body(&c, target, 7.0);
        }
    }
    return scn_end(&c, rc);
}

double scn_value(const scn_result_t *r, const char *key)
{
    double v = NAN;
    int k;
    for (k = 0; k < r->n_metrics; k++) {
        if (strcmp(r->m[k].key, key) == 0) {
            v = r->m[k].value;
        }
    }
    return v;
}

static void scn_json_str(FILE *f, const char *s)
{
    fputc('"', f);
    for (; *s != '\0'; s++) {
        if (*s == '"' || *s == '\\') {
            fputc('\\', f);
            fputc(*s, f);
        } else if ((unsigned char)*s < 0x20u) {
            fputc(' ', f);
        } else {
            fputc(*s, f);
        }
    }
    fputc('"', f);
}

static void scn_json_num(FILE *f, double v)
{
    if (isnan(v) || isinf(v)) {
        fputs("null", f);
    } else {
        fprintf(f, "%.6g", v);
    }
}

int scn_write_json(const scn_result_t *r, const char *dir)
{
    char path[600];
    FILE *f;
    int k;
    snprintf(path, sizeof path, "%s/metrics.json", dir);
    f = fopen(path, "w");
    if (f == NULL) {
        fprintf(stderr, "%s: cannot write\n", path);
        return -1;
    }
    fputs("{\n  \"scenario\": ", f);
    scn_json_str(f, r->name);
    fputs(",\n  \"title\": ", f);
    scn_json_str(f, r->title);
    fputs(",\n  \"description\": ", f);
    scn_json_str(f, r->description);
    fputs(",\n  \"motor\": ", f);
    scn_json_str(f, r->motor);
    fputs(",\n  \"table\": ", f);
    scn_json_str(f, r->table);
    fputs(",\n  \"f_pwm_hz\": ", f);
    scn_json_num(f, r->f_pwm_hz);
    fputs(",\n  \"vdc_v\": ", f);
    scn_json_num(f, r->vdc_v);
    fputs(",\n  \"t_end_s\": ", f);
    scn_json_num(f, r->t_end_s);
    fputs(",\n  \"requirements\": [", f);
    {
        char buf[64];
        char *tok;
        int first = 1;
        snprintf(buf, sizeof buf, "%s", r->requirements);
        for (tok = strtok(buf, ", "); tok != NULL; tok = strtok(NULL, ", ")) {
            fputs(first ? "" : ", ", f);
            scn_json_str(f, tok);
            first = 0;
        }
    }
    fprintf(f, "],\n  \"pass\": %s,\n  \"metrics\": [", r->pass ? "true" : "false");
    for (k = 0; k < r->n_metrics; k++) {
        const scn_metric_t *m = &r->m[k];
        fputs((k > 0) ? ",\n    {\"key\": " : "\n    {\"key\": ", f);
        scn_json_str(f, m->key);
        fputs(", \"label\": ", f);
        scn_json_str(f, m->label);
        fputs(", \"value\": ", f);
        scn_json_num(f, m->value);
        fputs(", \"unit\": ", f);
        scn_json_str(f, m->unit);
        fputs(", \"min\": ", f);
        scn_json_num(f, m->min);
        fputs(", \"max\": ", f);
        scn_json_num(f, m->max);
        fprintf(f, ", \"pass\": %s}", (m->pass < 0) ? "null" : (m->pass ? "true" : "false"));
    }
    fputs("\n  ],\n  \"events\": [", f);
    for (k = 0; k < r->n_events; k++) {
        fputs((k > 0) ? ", {\"t_s\": " : "{\"t_s\": ", f);
        scn_json_num(f, r->ev[k].t_s);
        fputs(", \"label\": ", f);
        scn_json_str(f, r->ev[k].label);
        fputc('}', f);
    }
    fputs("],\n  \"zoom\": {\"t0_s\": ", f);
    scn_json_num(f, r->zoom_t0_s);
    fputs(", \"t1_s\": ", f);
    scn_json_num(f, r->zoom_t1_s);
    fputc('}', f);
    if (r->compare_file[0] != '\0') {
        fputs(",\n  \"compare\": {\"file\": ", f);
        scn_json_str(f, r->compare_file);
        fputs(", \"label\": ", f);
        scn_json_str(f, r->compare_label);
        fputc('}', f);
    }
    fputs("\n}\n", f);
    fclose(f);
    return 0;
}
