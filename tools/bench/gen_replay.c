/**
 * @file gen_replay.c
 * @brief Host generator of a bench replay file (replay.h): the whole drive (host build of
 *        the library) in closed loop with the plant model (sim/drive_sim.h), from a cold
 *        start to a steady operating point; every ADC sample, every tick input and every
 *        output is recorded.  The target build replays the inputs in the instruction
 *        counter, reaches the same state and is checked against the outputs.
 *
 * usage: gen_replay --out FILE [--motor TOML] [--vdc V] [--rpm N] [--load NM]
 *                   [--pulse FRAC] [--measure-ms N] [--settle-ms N] [--max-s S]
 *                   [--need-tc] [--name NAME]
 *   --vdc V        DC-bus voltage (default 320)
 *   --rpm N        commanded speed, mechanical rpm (default 5800)
 *   --load NM      mean load torque (passive compressor load; default 3.0)
 *   --pulse FRAC   load pulsation at 1x mechanical, fraction of the mean (default 0)
 *   --measure-ms N length of the measured window (default 100: one 100 ms job)
 *   --settle-ms N  the operating point must hold this long before the window (default 300)
 *   --max-s S      give up when it is not reached after S seconds (default 12)
 *   --need-tc      torque compensation must be active (speed inside its window and its
 *                  coefficients non-zero) before and during the window
 * Beside FILE, FILE.json describes the run (motor, bus, speed, load, warm-up) for the report.
 * The operating point: RUN / CLOSED_LOOP, speed within 2 % of the command, field
 * weakening active (d-current reference below zero) and, with --need-tc, torque
 * compensation active.  Exit 0 with the file written; 1 when the point is not reached
 * or does not hold through the window (the message says which condition failed);
 * 2 on a usage error.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "drive_sim.h"
#include "reference_params.h"
#include "replay.h"

typedef struct {
    bench_rec_period_t *per;
    bench_rec_tick_t *tick;
    long cap_per;
    long cap_tick;
    long n_per;
    long n_tick;
} rec_t;

static void *grow(void *p, long *cap, long need, size_t elem)
{
    if (need > *cap) {
        long c = (*cap > 0) ? *cap : 4096;
        while (c < need) {
            c *= 2;
        }
        p = realloc(p, (size_t)c * elem);
        if (p == NULL) {
            fprintf(stderr, "gen_replay: out of memory\n");
            exit(1);
        }
        *cap = c;
    }
    return p;
}

/* The tick of sim/drive_sim.c (LIN master frame every frame_every_ms), recorded. */
static void gen_tick(dsim_t *ds, rec_t *r)
{
    bench_rec_tick_t t;
    qfoc_tick_in_t in;
    memset(&t, 0, sizeof t);
    t.t_ipm = ds->t_ipm;
    t.t_pcb = ds->t_pcb;
    if (ds->link_alive && (ds->ms % ds->frame_every_ms) == 0) {
        t.rx[0] = 0x55u;
        t.rx[1] = dsim_lin_pid(ds->table->drive.lin_id_cmd);
        t.rx[2] = (uint8_t)((ds->power_on ? 1u : 0u) | (ds->fault_clear ? 2u : 0u));
        t.rx[3] = (uint8_t)(ds->target_rpm & 0xFFu);
        t.rx[4] = (uint8_t)(ds->target_rpm >> 8);
        t.rx[5] = 0u;
        t.rx[6] = dsim_lin_checksum(&t.rx[1], 5);
        t.rx_len = 7u;
    }
    in.t_ipm = t.t_ipm;
    in.t_pcb = t.t_pcb;
    in.rx = t.rx;
    in.rx_len = t.rx_len;
    ds->out = qfoc_drive_tick(&ds->drv, &in);
    r->tick = grow(r->tick, &r->cap_tick, r->n_tick + 1, sizeof *r->tick);
    r->tick[r->n_tick++] = t;
    ds->ms++;
}

/* One PWM period as dsim_period(), recorded. */
static void gen_period(dsim_t *ds, rec_t *r)
{
    sim_adc_t a;
    qfoc_adc_t adc;
    bench_rec_period_t p;
    ds->theta_sample = sim_theta_e(&ds->plant);
    sim_sample(&ds->plant, &a);
    adc.iu = a.iu;
    adc.iv = a.iv;
    adc.vdc = a.vdc;
    ds->pwm = qfoc_drive_fast_step(&ds->drv, &adc);
    memset(&p, 0, sizeof p);
    p.iu = adc.iu;
    p.iv = adc.iv;
    p.vdc = adc.vdc;
    p.cmp[0] = ds->pwm.cmp[0];
    p.cmp[1] = ds->pwm.cmp[1];
    p.cmp[2] = ds->pwm.cmp[2];
    p.enable = ds->pwm.enable ? 1u : 0u;
    r->per = grow(r->per, &r->cap_per, r->n_per + 1, sizeof *r->per);
    r->per[r->n_per++] = p;
    sim_set_compare(&ds->plant, ds->pwm.cmp);
    sim_set_enable(&ds->plant, ds->pwm.enable);
    sim_step_period(&ds->plant);
    ds->period++;
    if ((ds->period % ds->periods_per_ms) == 0) {
        gen_tick(ds, r);
    }
}

/* The operating point; returns NULL when it holds, else the failed condition. */
static const char *op_point(const dsim_t *ds, double rpm, int need_tc)
{
    const qfoc_drive_t *d = &ds->drv;
    const int32_t w = (d->f.speed_f < 0) ? -(int32_t)d->f.speed_f : (int32_t)d->f.speed_f;
    const char *why = NULL;
    if (d->s.sm.state != QFOC_STATE_RUN || d->s.sm.sub != QFOC_SUB_CLOSED_LOOP) {
        why = "not in RUN / CLOSED_LOOP";
    } else if (fabs(dsim_rpm(ds) - rpm) > 0.02 * rpm) {
        why = "speed not within 2 % of the command";
    } else if (d->s.fw.id_ref >= 0) {
        why = "field weakening inactive (id_fw >= 0)";
    } else if (need_tc && (w < d->s.tc.params.speed_min || w > d->s.tc.params.speed_max)) {
        why = "speed outside the torque-compensation window";
    } else if (need_tc && d->s.tc.a[0] == 0 && d->s.tc.b[0] == 0) {
        why = "torque-compensation coefficients zero";
    } else {
        /* holds */
    }
    return why;
}

/* The state the target's bench_probe() reports, in its order. */
static void probe(const qfoc_drive_t *d, int32_t out[8])
{
    out[0] = d->s.sm.state;
    out[1] = d->s.sm.sub;
    out[2] = d->s.fw.id_ref;
    out[3] = d->s.util;
    out[4] = d->f.speed_f;
    out[5] = d->s.tc.a[0];
    out[6] = d->s.tc.b[0];
    out[7] = d->s.iq_ref;
}

static void usage(void)
{
    fprintf(stderr, "usage: gen_replay --out FILE [--motor TOML] [--vdc V] [--rpm N] [--load NM] "
                    "[--pulse FRAC] [--measure-ms N] [--settle-ms N] [--max-s S] [--need-tc]\n");
    exit(2);
}

int main(int argc, char **argv)
{
    const char *out = NULL;
    const char *motor_file = "specs/motors/reference.toml";
    double vdc = 320.0;
    double rpm = 5800.0;
    double load = 3.0;
    double pulse = 0.0;
    long measure_ms = 100;
    long settle_ms = 300;
    double max_s = 12.0;
    int need_tc = 0;
    static dsim_t ds;
    sim_motor_t m;
    sim_cfg_t cfg;
    rec_t r;
    bench_rec_hdr_t h;
    long held = 0;
    long ms;
    long warm_ms = -1;
    const char *why = "never evaluated";
    FILE *f;
    int a;

    for (a = 1; a < argc; a++) {
        if (a + 1 < argc && strcmp(argv[a], "--out") == 0) {
            out = argv[++a];
        } else if (a + 1 < argc && strcmp(argv[a], "--motor") == 0) {
            motor_file = argv[++a];
        } else if (a + 1 < argc && strcmp(argv[a], "--vdc") == 0) {
            vdc = atof(argv[++a]);
        } else if (a + 1 < argc && strcmp(argv[a], "--rpm") == 0) {
            rpm = atof(argv[++a]);
        } else if (a + 1 < argc && strcmp(argv[a], "--load") == 0) {
            load = atof(argv[++a]);
        } else if (a + 1 < argc && strcmp(argv[a], "--pulse") == 0) {
            pulse = atof(argv[++a]);
        } else if (a + 1 < argc && strcmp(argv[a], "--measure-ms") == 0) {
            measure_ms = atol(argv[++a]);
        } else if (a + 1 < argc && strcmp(argv[a], "--settle-ms") == 0) {
            settle_ms = atol(argv[++a]);
        } else if (a + 1 < argc && strcmp(argv[a], "--max-s") == 0) {
            max_s = atof(argv[++a]);
        } else if (strcmp(argv[a], "--need-tc") == 0) {
            need_tc = 1;
        } else {
            usage();
        }
    }
    if (out == NULL || measure_ms < 1 || rpm < 1.0 || rpm > 65535.0) {
        usage();
    }
    if (sim_motor_load(motor_file, &m) != 0) {
        return 1;
    }
    memset(&cfg, 0, sizeof cfg);
    cfg.motor = m;
    cfg.vdc_v = vdc;
    cfg.dead_time_s = m.dead_time_s;
    cfg.substeps = 20;
    cfg.noise_i_rms_a = 0.05;
    cfg.seed = 7u;
    cfg.load.t_mean = load;
    cfg.load.t_1x = pulse * load;
    cfg.load.knee_rpm = 30.0;
    memset(&r, 0, sizeof r);
    if (dsim_init(&ds, &cfg, &qfoc_params_reference) != QFOC_PARAMS_OK) {
        fprintf(stderr, "gen_replay: the reference table is refused\n");
        return 1;
    }
    ds.power_on = true;
    ds.target_rpm = (uint16_t)lround(rpm);

    /* warm-up: until the operating point has held for settle_ms */
    for (ms = 0; ms < (long)(max_s * 1000.0) && warm_ms < 0; ms++) {
        int k;
        for (k = 0; k < ds.periods_per_ms; k++) {
            gen_period(&ds, &r);
        }
        if (ds.drv.s.sm.state == QFOC_STATE_ERROR) {
            fprintf(stderr, "gen_replay: the drive went to ERROR (faults 0x%04x) at %ld ms\n",
                    ds.drv.s.sm.faults, ms);
            return 1;
        }
        why = op_point(&ds, rpm, need_tc);
        held = (why == NULL) ? held + 1 : 0;
        if (held >= settle_ms) {
            warm_ms = ms + 1;
        }
    }
    if (warm_ms < 0) {
        fprintf(stderr, "gen_replay: operating point not held for %ld ms within %.1f s: %s\n",
                settle_ms, max_s, (why != NULL) ? why : "it held, but not long enough");
        return 1;
    }
    memset(&h, 0, sizeof h);
    probe(&ds.drv, h.probe);
    /* the measured window: the point must hold throughout */
    for (ms = 0; ms < measure_ms; ms++) {
        int k;
        for (k = 0; k < ds.periods_per_ms; k++) {
            gen_period(&ds, &r);
        }
        why = op_point(&ds, rpm, need_tc);
        if (why != NULL) {
            fprintf(stderr, "gen_replay: operating point lost in the window at +%ld ms: %s\n",
                    ms, why);
            return 1;
        }
    }
    probe(&ds.drv, h.probe_end);
    h.magic = BENCH_REC_MAGIC;
    h.version = BENCH_REC_VERSION;
    h.n_periods = (uint32_t)r.n_per;
    h.n_ticks = (uint32_t)r.n_tick;
    h.periods_per_ms = (uint32_t)ds.periods_per_ms;
    h.period_off = (uint32_t)sizeof h;
    h.tick_off = (uint32_t)(sizeof h + (size_t)r.n_per * sizeof *r.per);
    h.warm_periods = (uint32_t)(warm_ms * ds.periods_per_ms);
    f = fopen(out, "wb");
    if (f == NULL || fwrite(&h, sizeof h, 1, f) != 1 ||
        fwrite(r.per, sizeof *r.per, (size_t)r.n_per, f) != (size_t)r.n_per ||
        fwrite(r.tick, sizeof *r.tick, (size_t)r.n_tick, f) != (size_t)r.n_tick ||
        fclose(f) != 0) {
        fprintf(stderr, "gen_replay: cannot write %s\n", out);
        return 1;
    }
    /* the run's description beside the recording, for the report */
    {
        char meta[600];
        snprintf(meta, sizeof meta, "%s.json", out);
        f = fopen(meta, "w");
        if (f == NULL) {
            fprintf(stderr, "gen_replay: cannot write %s\n", meta);
            return 1;
        }
        fprintf(f, "{\"motor\": \"%s\", \"table\": \"qfoc_params_reference\", "
                   "\"vdc_v\": %.1f, \"target_rpm\": %.0f, \"load_nm\": %.3f, "
                   "\"pulse_1x\": %.3f, \"noise_i_rms_a\": %.3f, \"f_pwm_hz\": %.0f, "
                   "\"warm_s\": %.3f, \"measure_ms\": %ld, \"settle_ms\": %ld, "
                   "\"need_tc\": %s, \"rpm_end\": %.1f}\n",
                m.name, vdc, rpm, load, pulse, cfg.noise_i_rms_a, m.f_pwm_hz, warm_ms * 1e-3,
                measure_ms, settle_ms, need_tc ? "true" : "false", dsim_rpm(&ds));
        if (fclose(f) != 0) {
            fprintf(stderr, "gen_replay: cannot write %s\n", meta);
            return 1;
        }
    }
    printf("gen_replay: %s: %.3f s warm-up (%u periods), %ld ms measured; %.0f rpm at %.0f V, "
           "load %.2f N m %+.0f %%; id_fw %.2f A, utilisation %.3f, tc a1 %.3f A b1 %.3f A\n",
           out, warm_ms * 1e-3, h.warm_periods, measure_ms, dsim_rpm(&ds), vdc, load,
           100.0 * pulse, ds.drv.s.fw.id_ref / 32768.0 * m.i_full_scale_a,
           ds.drv.s.util / 32768.0, ds.drv.s.tc.a[0] / 2147483648.0 * m.i_full_scale_a,
           ds.drv.s.tc.b[0] / 2147483648.0 * m.i_full_scale_a);
    free(r.per);
    free(r.tick);
    return 0;
}
