/**
 * @file harness.c
 * @brief Target side of the instruction bench (harness.h).
 */
#include "harness.h"

#include <stddef.h>

#include "reference_params.h"

const uint32_t bench_info[BENCH_INFO_N] = {
    1u,
    (uint32_t)sizeof(qfoc_drive_t),
    (uint32_t)sizeof(qfoc_param_table_t),
    (uint32_t)offsetof(qfoc_param_table_t, svpwm),
    0u,
    (uint32_t)sizeof(qfoc_drive_fast_t),
    (uint32_t)sizeof(qfoc_drive_slow_t),
    (uint32_t)sizeof(qfoc_svpwm_out_t),
    (uint32_t)sizeof(qfoc_pll_out_t),
    (uint32_t)sizeof(qfoc_tick_in_t),
    (uint32_t)sizeof(qfoc_tick_out_t),
    (uint32_t)offsetof(qfoc_tick_out_t, tx_len),
    (uint32_t)offsetof(qfoc_tick_out_t, can_send)
};

qfoc_pi_t bench_pi;
qfoc_lpf_t bench_lpf;
qfoc_flux_t bench_flux;
qfoc_pll_t bench_pll;
qfoc_fw_t bench_fw;
qfoc_trqcomp_t bench_tc;
qfoc_mech_t bench_mech;
qfoc_phase_mon_t bench_phase;
qfoc_drive_t bench_drive;
uint32_t bench_arg[64];
uint32_t bench_res[64];
int32_t bench_probe_out[BENCH_PROBE_N];
qfoc_tick_in_t bench_tick_in;
uint32_t bench_scale[3];

int32_t bench_setup(void)
{
    const qfoc_param_table_t *const p = &qfoc_params_reference;
    qfoc_fw_params_t fwp;
    qfoc_trqcomp_params_t tcp;
    fwp.pi = p->pi_fw;
    fwp.level = p->drive.fw_level;
    fwp.alpha = p->drive.fw_alpha;
    tcp.gain = p->drive.tc_gain;
    tcp.amp_max = p->drive.tc_amp_max;
    tcp.speed_min = p->drive.tc_speed_min;
    tcp.speed_max = p->drive.tc_speed_max;
    tcp.pole_pairs = p->drive.pole_pairs;
    bench_scale[0] = p->i_base_ma;
    bench_scale[1] = p->f_base_mhz;
    bench_scale[2] = (uint32_t)p->drive.pole_pairs;
    (void)qfoc_pi_init(&bench_pi, &p->pi_iq);
    (void)qfoc_lpf_init(&bench_lpf, p->alpha_vdc);
    (void)qfoc_flux_init(&bench_flux, &p->flux);
    (void)qfoc_pll_init(&bench_pll, &p->pll);
    (void)qfoc_fw_init(&bench_fw, &fwp);
    (void)qfoc_trqcomp_init(&bench_tc, &tcp);
    (void)qfoc_mech_init(&bench_mech, p->drive.pole_pairs, 0u);
    (void)qfoc_phase_mon_init(&bench_phase, p->drive.phase_alpha);
    return qfoc_drive_init(&bench_drive, p);
}

/* The recording's header is sane and [first, first + count) lies inside it. */
static bool bench_rec_ok(const bench_rec_hdr_t *rec, uint32_t first, uint32_t count)
{
    bool ok = (rec->magic == BENCH_REC_MAGIC) && (rec->version == BENCH_REC_VERSION) &&
              (rec->periods_per_ms > 0u) &&
              (rec->n_ticks == (rec->n_periods / rec->periods_per_ms));
    if (ok) {
        ok = (first <= rec->n_periods) && (count <= (rec->n_periods - first));
    } else {
        /* malformed */
    }
    return ok;
}

const qfoc_tick_in_t *bench_tick_input(const bench_rec_hdr_t *rec, uint32_t ms)
{
    const qfoc_tick_in_t *res = NULL;
    if (bench_rec_ok(rec, 0u, 0u) && (ms < rec->n_ticks)) {
        const bench_rec_tick_t *const t =
            (const bench_rec_tick_t *)((const uint8_t *)rec + rec->tick_off) + ms;
        bench_tick_in.t_ipm = t->t_ipm;
        bench_tick_in.t_pcb = t->t_pcb;
        bench_tick_in.rx = t->rx;
        bench_tick_in.rx_len = t->rx_len;
        res = &bench_tick_in;
    } else {
        /* outside the recording */
    }
    return res;
}

uint32_t bench_replay(const bench_rec_hdr_t *rec, uint32_t first, uint32_t count)
{
    uint32_t bad = 0xFFFFFFFFu;
    if (bench_rec_ok(rec, first, count)) {
        const bench_rec_period_t *const per =
            (const bench_rec_period_t *)((const uint8_t *)rec + rec->period_off);
        uint32_t k;
        bad = 0u;
        for (k = first; k < (first + count); k++) {
            qfoc_adc_t adc;
            qfoc_pwm_t pwm;
            adc.iu = per[k].iu;
            adc.iv = per[k].iv;
            adc.vdc = per[k].vdc;
            pwm = qfoc_drive_fast_step(&bench_drive, &adc);
            if ((pwm.cmp[0] != per[k].cmp[0]) || (pwm.cmp[1] != per[k].cmp[1]) ||
                (pwm.cmp[2] != per[k].cmp[2]) ||
                (pwm.enable != (per[k].enable != 0u))) {
                bad++;
            } else {
                /* the host's output */
            }
            if (((k + 1u) % rec->periods_per_ms) == 0u) {
                const qfoc_tick_in_t *const in =
                    bench_tick_input(rec, ((k + 1u) / rec->periods_per_ms) - 1u);
                if (in != NULL) {
                    (void)qfoc_drive_tick(&bench_drive, in);
                } else {
                    bad++;
                }
            } else {
                /* no tick after this period */
            }
        }
    } else {
        /* malformed recording or range */
    }
    return bad;
}

void bench_probe(void)
{
    bench_probe_out[0] = (int32_t)bench_drive.s.sm.state;
    bench_probe_out[1] = (int32_t)bench_drive.s.sm.sub;
    bench_probe_out[2] = (int32_t)bench_drive.s.fw.id_ref;
    bench_probe_out[3] = (int32_t)bench_drive.s.util;
    bench_probe_out[4] = (int32_t)bench_drive.f.speed_f;
    bench_probe_out[5] = bench_drive.s.tc.a[0];
    bench_probe_out[6] = bench_drive.s.tc.b[0];
    bench_probe_out[7] = (int32_t)bench_drive.s.iq_ref;
}
