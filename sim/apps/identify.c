/**
 * @file identify.c
 * @brief The standstill identification (ident.h) with the library in the loop on the
 *        double-precision plant, for every table of tables/manifest.txt (make identify).
 *
 * For each motor: the plant with the table's dead time uncompensated, ADC noise, a
 * current-sensor offset and DC-bus noise; the offsets calibrated with the PWM off (as the
 * drive's PRECHARGE does); then qfoc_ident_step() every period, from the ADC samples
 * (offset-corrected, qfoc_clarke()) to the compare values and the enable, until the mode
 * ends.  The configuration comes from the table (current PI, PWM period) and the motor's
 * ratings only (rated current and speed, bus, pole pairs): no value the identification is
 * to find is used.  The output, on stdout, is what a host reads from the drive: a
 * "motor" line with the truth (for the report only), the bases and the configuration, and
 * the record as qfoc_ident_frame() frames in hex, which tools/tune/ident_decode.py turns
 * into R_s, L_d, L_q and the inverter's voltage error.
 *
 * usage: qfoc_identify [--only NAME] [--fault open|short|low_bus|move] [--seed S]
 *                      [--angle DEG]   (the rotor's electrical angle at the start, 120)
 * Faults: open (phase v open: ERR_NO_CURRENT), short (a short's current surge in R_HI:
 * ERR_OC), low_bus (the bus at 30 % of nominal: ERR_BUS), move (an external torque of 1.1
 * times the aligned rotor's holding torque from L_D on: ERR_MOVED).
 * Exit: 0 when every run ended DONE (with --fault: in that fault's result, PWM off), 1
 * otherwise, 2 on an error.
 *
 * Methods: 1b the manifest's motors (three saliency ratios, 3 to 8 pole pairs, 10 mOhm to
 * 0.6 Ohm), 1d ADC noise, offsets and the inverter's dead time uncompensated.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "drive_sim.h"
#include "scenario.h"
#include "tables_registry.h"
#include "qfoc/commission.h"
#include "qfoc/ident.h"
#include "qfoc/transforms.h"

#define SQ3 1.73205080756887729353

static int16_t q15_of(double x)
{
    double r = floor(x * 32768.0 + 0.5);
    if (r > 32767.0) r = 32767.0;
    if (r < -32767.0) r = -32767.0;
    return (int16_t)r;
}

static uint16_t periods(double t_s, double ts)
{
    double n = floor(t_s / ts + 0.5);
    return (uint16_t)(n > 65535.0 ? 65535.0 : (n < 1.0 ? 1.0 : n));
}

/* The configuration from the table and the ratings (specs/equations.md section 12.4). */
static void ident_cfg_of(const qfoc_param_table_t *t, const sim_motor_t *m, const sim_bases_t *b,
                         qfoc_ident_cfg_t *c)
{
    const double i_hi = 0.4 * m->rated_current_a;
    const double w_rated = m->rated_speed_rpm / 60.0 * 2.0 * SIM_PI * m->pole_pairs;
    const double v_phase = m->vdc_nominal_v / SQ3;
    /* ratings-only guesses: a reactance drop of 0.3 and a back-EMF of 0.6 of the phase
       voltage at the rated point (the injection amplitude and the movement bound only) */
    const double l_guess = 0.3 * v_phase / (w_rated * m->rated_current_a);
    const double psi_guess = 0.6 * v_phase / w_rated;
    const double w_inj = 2.0 * SIM_PI / (16.0 * b->t_s);
    double win;
    memset(c, 0, sizeof *c);
    c->i_lo = q15_of(0.2 * m->rated_current_a / b->i_base);
    c->i_hi = q15_of(i_hi / b->i_base);
    c->i_lim = q15_of(fmin(m->rated_current_a, 0.95 * b->i_base) / b->i_base);
    /* the injection starts at half the ratings guess and doubles (or halves) every
       second injection period of the first half of the settling until the injected
       current's amplitude lies within [1/2, 2] of i_hi / 4; at most a quarter of the
       phase voltage */
    c->v_inj = q15_of(0.5 * 0.25 * i_hi * w_inj * l_guess / b->v_base);
    if (c->v_inj < 1) c->v_inj = 1;
    c->v_inj_max = q15_of(0.25 * v_phase / b->v_base);
    if (c->v_inj_max < c->v_inj) c->v_inj_max = c->v_inj;
    c->i_inj = q15_of(0.25 * i_hi / b->i_base);
    /* 4 PWM counts of beta voltage at the nominal bus: a rotor turning at
       4 V_dc / (sqrt 3 P psi_f) rad/s (electrical) or faster */
    c->v_move = q15_of(4.0 * m->vdc_nominal_v / (SQ3 * (double)t->svpwm.period) / b->v_base);
    (void)psi_guess;
    c->vdc_min = q15_of(0.5 * m->vdc_nominal_v / b->v_base);
    /* the drive's own bounds (commission.h refuses wider ones) */
    c->vdc_max = t->vdc_ov;
    if (c->i_lim > t->i_trip) c->i_lim = t->i_trip;
    c->n_align = periods(2.5, b->t_s);
    c->n_settle = periods(0.05, b->t_s);
    c->i_ramp = q15_of(i_hi / b->i_base / (0.1 / b->t_s));
    if (c->i_ramp < 1) c->i_ramp = 1;
    win = log2(0.2 / b->t_s);
    c->win_shift = (uint8_t)fmax(QFOC_IDENT_WIN_MIN, fmin(QFOC_IDENT_WIN_MAX, ceil(win)));
    /* PSI: the current turns at 0.2 of the rated speed, rounded to whole turns in each
       half window (a multiple of 2^(17 - win_shift) counts a period), after a ramp of
       1 s from standstill */
    {
        const double quantum = ldexp(1.0, 17 - (int)c->win_shift);
        const double w = 0.2 * w_rated * b->t_s * 65536.0 / (2.0 * SIM_PI);
        double q = quantum * floor(w / quantum + 0.5);
        if (q < quantum) q = quantum;
        if (q > (double)QFOC_IDENT_W_MAX) q = quantum * floor((double)QFOC_IDENT_W_MAX / quantum);
        c->w_psi = (uint16_t)q;
        c->n_ramp = periods(1.0, b->t_s);
    }
    c->pi = t->pi_id;
    c->pwm = t->svpwm;
    c->pwm.dt_comp = 0u;
}

typedef struct {
    const char *fault;  /* NULL, "open", "short", "low_bus", "move" */
    uint32_t seed;
    double angle_deg;   /* the rotor's electrical angle at the start */
} opts_t;

static int run_one(const scn_table_t *tab, const opts_t *o)
{
    static dsim_t ds;
    sim_motor_t m;
    sim_cfg_t cfg;
    sim_t *s = &ds.plant;
    qfoc_ident_cfg_t ic;
    qfoc_ident_t id;
    long k, n_run = 0, n_on = 0;
    uint16_t f;
    uint8_t res;
    bool surged = false;
    if (scn_table_motor(tab, &m) != 0) {
        fprintf(stderr, "qfoc_identify: cannot read the motor of table %s (%s)\n", tab->name,
                tab->motor_file);
        return 2;
    }
    memset(&cfg, 0, sizeof cfg);
    cfg.motor = m;
    cfg.vdc_v = m.vdc_nominal_v;
    cfg.dead_time_s = m.dead_time_s;
    cfg.noise_i_rms_a = 0.004 * m.i_full_scale_a;
    cfg.noise_vdc_rms_v = 0.002 * m.vdc_full_scale_v;
    cfg.adc_offset_counts = 6.0;
    cfg.seed = o->seed;
    cfg.substeps = 20;
    cfg.load.knee_rpm = 50.0;
    /* the drive on the table, stopped: PRECHARGE calibrates the offsets, then STOP; the
       service tool gives the command through qfoc_drive_command() from the start (power
       off, identify set), so the request is in effect when the drive reaches STOP */
    if (dsim_init(&ds, &cfg, tab->table) != QFOC_PARAMS_OK) {
        fprintf(stderr, "qfoc_identify: table %s refused by the drive\n", tab->name);
        return 2;
    }
    sim_set_state(s, o->angle_deg * SIM_PI / 180.0, 0.0, 0.0, 0.0);
    ds.power_on = false;
    ds.identify = true;
    for (k = 0; k < 5000L * ds.periods_per_ms && qfoc_drive_state(&ds.drv) != QFOC_STATE_STOP; k++) {
        dsim_period(&ds);
    }
    ident_cfg_of(tab->table, &m, &s->bases, &ic);
    if (o->fault != NULL && strcmp(o->fault, "open") == 0) {
        s->inj.open = 2u;  /* phase v open */
    }
    if (qfoc_commission_start(&id, &ds.drv, &ic) != QFOC_IDENT_RUNNING) {
        fprintf(stderr, "qfoc_identify: table %s: start refused (result %u, drive state %u)\n",
                tab->name, (unsigned)qfoc_ident_result(&id), (unsigned)qfoc_drive_state(&ds.drv));
        return 2;
    }
    ds.ident = &id;
    while (qfoc_ident_result(&id) == QFOC_IDENT_RUNNING && n_run < 40L * 65536L) {
        if (o->fault != NULL && strcmp(o->fault, "move") == 0 &&
            qfoc_ident_step_now(&id) == QFOC_IDENT_L_D && !s->held) {
            /* an external torque turns the rotor (a fan or the compressor's pressure) */
            s->cfg.load.t_mean = -1.1 * 1.5 * m.pole_pairs * m.psi_f_wb * 0.4 *
                                 m.rated_current_a;
        }
        if (o->fault != NULL && strcmp(o->fault, "low_bus") == 0 &&
            qfoc_ident_step_now(&id) == QFOC_IDENT_R_LO) {
            s->cfg.vdc_v = 0.3 * m.vdc_nominal_v;  /* the bus collapses */
        }
        if (o->fault != NULL && strcmp(o->fault, "short") == 0 && !surged &&
            qfoc_ident_step_now(&id) == QFOC_IDENT_R_HI) {
            /* a short between phases u and v: the current a short draws from the bus */
            const double surge[2] = { 1.2 * m.rated_current_a, 0.0 };
            sim_set_current_ab(s, surge);
            surged = true;
        }
        dsim_period(&ds);
        n_run++;
        n_on += ds.pwm.enable ? 1 : 0;
    }
    ds.ident = NULL;
    res = qfoc_ident_result(&id);
    printf("motor %s rs_ohm=%.9g ld_h=%.9g lq_h=%.9g psi_f_wb=%.9g dead_time_s=%.9g "
           "t_s=%.9g period=%u v_base=%.9g i_base=%.9g pole_pairs=%g w_psi=%u result=%u step=%u "
           "periods=%ld enabled=%ld motor_time_s=%.6f theta_end_deg=%.3f w_end=%.4g\n",
           tab->name, m.rs_ohm, m.ld_h, m.lq_h, m.psi_f_wb, m.dead_time_s, s->bases.t_s,
           (unsigned)ic.pwm.period, s->bases.v_base, s->bases.i_base, m.pole_pairs,
           (unsigned)ic.w_psi, (unsigned)res, (unsigned)qfoc_ident_step_now(&id), n_run, n_on,
           (double)n_run * s->bases.t_s, sim_wrap_pi(sim_theta_e(s)) * 180.0 / SIM_PI, sim_w_e(s));
    for (f = 0u; f < QFOC_IDENT_FRAMES; f++) {
        uint8_t buf[8];
        (void)qfoc_ident_frame(&id, f, buf);
        printf("frame %02X %02X %02X %02X %02X %02X %02X %02X\n", buf[0], buf[1], buf[2],
               buf[3], buf[4], buf[5], buf[6], buf[7]);
    }
    printf("end %s\n", tab->name);
    if (o->fault == NULL) {
        return res == QFOC_IDENT_DONE ? 0 : 1;
    } else {
        /* each failure ends in its own stated result, with the PWM off */
        const uint8_t want = (strcmp(o->fault, "open") == 0) ? QFOC_IDENT_ERR_NO_CURRENT :
                             (strcmp(o->fault, "short") == 0) ? QFOC_IDENT_ERR_OC :
                             (strcmp(o->fault, "low_bus") == 0) ? QFOC_IDENT_ERR_BUS :
                             QFOC_IDENT_ERR_MOVED;
        if (res != want || s->en_pending) {
            fprintf(stderr, "qfoc_identify: table %s, fault %s: ended with result %u "
                    "(expected %u), PWM %s\n", tab->name, o->fault, (unsigned)res,
                    (unsigned)want, s->en_pending ? "on" : "off");
            return 1;
        }
        return 0;
    }
}

int main(int argc, char **argv)
{
    const char *only = NULL;
    opts_t o = { NULL, 7u, 120.0 };
    int i, rc = 0, ran = 0;
    for (i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--only") == 0 && i + 1 < argc) {
            only = argv[++i];
        } else if (strcmp(argv[i], "--fault") == 0 && i + 1 < argc) {
            o.fault = argv[++i];
            if (strcmp(o.fault, "open") != 0 && strcmp(o.fault, "short") != 0 &&
                strcmp(o.fault, "low_bus") != 0 && strcmp(o.fault, "move") != 0) {
                fprintf(stderr, "qfoc_identify: --fault '%s': expected open, short, low_bus "
                        "or move\n", o.fault);
                return 2;
            }
        } else if (strcmp(argv[i], "--angle") == 0 && i + 1 < argc) {
            char *end;
            o.angle_deg = strtod(argv[++i], &end);
            if (*end != '\0' || !(fabs(o.angle_deg) <= 360.0)) {
                fprintf(stderr, "qfoc_identify: --angle '%s': expected degrees in "
                        "[-360, 360]\n", argv[i]);
                return 2;
            }
        } else if (strcmp(argv[i], "--seed") == 0 && i + 1 < argc) {
            o.seed = (uint32_t)strtoul(argv[++i], NULL, 10);
        } else {
            fprintf(stderr, "qfoc_identify: unknown argument '%s'\n"
                    "usage: qfoc_identify [--only NAME] [--fault open|short|low_bus|move] "
                    "[--seed S] [--angle DEG]\n", argv[i]);
            return 2;
        }
    }
    for (i = 0; i < scn_n_tables; i++) {
        int r;
        if (only != NULL && strcmp(only, scn_tables[i].name) != 0) {
            continue;
        }
        if (scn_tables[i].table->drive.sensing == QFOC_SENSING_SHUNT) {
            /* the identification measures with two phase-current sensors (ident.h) */
            fprintf(stderr, "qfoc_identify: %s: a single-shunt table, not identified (the "
                    "identification needs two phase-current sensors)\n", scn_tables[i].name);
            continue;
        }
        r = run_one(&scn_tables[i], &o);
        ran++;
        if (r > rc) {
            rc = r;
        }
    }
    if (ran == 0) {
        fprintf(stderr, "qfoc_identify: no table named '%s' in tables/manifest.txt\n",
                only != NULL ? only : "");
        return 2;
    }
    return rc;
}
