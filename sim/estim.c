/**
 * @file estim.c
 * @brief Closed-loop validation of the qfoc position estimators (see estim.h).
 */
#include "estim.h"

#include "qfoc/transforms.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define EST_DEG (180.0 / SIM_PI)
/* angle counts (65536 per turn) to radians */
#define EST_CNT_TO_RAD (2.0 * SIM_PI / 65536.0)
/* convergence threshold of the cold-start test, electrical degrees */
#define EST_CONV_DEG 5.0
/* plant and controller run this long before the estimators start */
#define EST_WARMUP_S 0.05

void est_design_default(est_design_t *d)
{
    /* high-pass corner of the flux observer: 10 ms, DC offsets decay within 50 ms;
       the phase lead it causes (28 deg at 10 % speed) is removed by qfoc_flux_lead */
    d->kg_rad_s = 100.0;
    /* PLL: w_n = 2 pi 100 Hz pulls in from zero speed to 125 % (471 Hz) within
       25 ms; damping 0.9; the normalised error is clamped at sin(48.6 deg) */
    d->pll_wn_hz = 100.0;
    d->pll_zeta = 0.9;
    d->pll_clamp = 0.75;
    d->pll_mag_min = 0.05;
    d->speed_fc_hz = 20.0;
    /* back-EMF and disturbance-observer filters: the difference quotient of the
       current amplifies ADC noise (one count is 0.66 V at 8 kHz), so they are
       filtered at about 50 Hz and the lag is compensated */
    d->emf_fc_hz = 50.0;
    d->dob_lambda = 0.05;
}

static int16_t est_q15(double x)
{
    double r = floor(x * 32768.0 + 0.5);
    if (r > 32767.0) {
        r = 32767.0;
    }
    if (r < -32767.0) {
        r = -32767.0;
    }
    return (int16_t)r;
}

static int16_t est_qn(double x, int frac_bits)
{
    double r = floor(ldexp(x, frac_bits) + 0.5);
    if (r > 32767.0) {
        r = 32767.0;
    }
    if (r < 0.0) {
        r = 0.0;
    }
    return (int16_t)r;
}

/* x = mant / 2^(15 + shift), shift 0..15 as large as the mantissa allows (x < 1) */
static void est_mant_right(double x, int16_t *mant, uint8_t *shift)
{
    uint8_t s = 0u;
    while (s < 15u && ldexp(x, 16 + (int)s) < 32767.0) {
        s++;
    }
    *shift = s;
    *mant = est_qn(x, 15 + (int)s);
}

/* x = mant / 32768 * 2^shift, shift 0..15 as small as possible (qfoc_pi gains) */
static void est_mant_left(double x, int16_t *mant, uint8_t *shift)
{
    uint8_t s = 0u;
    while (s < 15u && ldexp(x, 15 - (int)s) > 32767.0) {
        s++;
    }
    *shift = s;
    *mant = est_qn(x, 15 - (int)s);
}

void est_tune(const sim_motor_t *m, const est_design_t *d, est_params_t *p)
{
    sim_bases_t b;
    double g;
    double lq_pu;
    double wn;
    double ki;

    sim_bases(m, &b);
    g = b.t_s * b.w_base;
    lq_pu = m->lq_h / b.l_base;
    memset(p, 0, sizeof *p);

    /* flux observer (2-19 .. 2-24) with L = L_q (active flux) */
    est_mant_right(g, &p->flux.gain, &p->flux.gain_shift);
    p->flux.r = est_q15(m->rs_ohm / b.z_base);
    p->flux.l = est_qn(lq_pu, 12);
    p->flux.kg = est_q15(d->kg_rad_s / b.w_base);

    /* PLL (2-27, 2-28): w = (kp + ki/s) sin(err); kp = 2 zeta wn, ki = wn^2 */
    wn = 2.0 * SIM_PI * d->pll_wn_hz;
    est_mant_left(2.0 * d->pll_zeta * wn / b.w_base, &p->pll.pi.kp, &p->pll.pi.kp_shift);
    ki = wn * wn * b.t_s / b.w_base;
    est_mant_left(ki, &p->pll.pi.ki, &p->pll.pi.ki_shift);
    p->pll.pi.out_min = -32767;
    p->pll.pi.out_max = 32767;
    p->pll.err_clamp = est_q15(d->pll_clamp);
    p->pll.mag_min = est_q15(d->pll_mag_min * m->psi_f_wb / b.psi_base);
    p->pll.k_theta = (uint16_t)lround(b.f_base / m->f_pwm_hz * 131072.0);
    p->pll.speed_alpha = est_q15(2.0 * SIM_PI * d->speed_fc_hz * b.t_s);
    /* angle-tracking observer on an EMF: same loop, coasting below 1 % of V_base */
    p->ato = p->pll;
    p->ato.mag_min = est_q15(0.01);

    /* back-EMF estimator: e = u - R i - L_q di/dt */
    p->emf.r = p->flux.r;
    p->emf.l = est_qn(lq_pu / g, 10);
    p->emf.alpha = est_q15(2.0 * SIM_PI * d->emf_fc_hz * b.t_s);
    p->emf.k_theta = p->pll.k_theta;

    /* disturbance observer: k_i = T w_base / L_q, G = lambda / k_i */
    est_mant_right(g / lq_pu, &p->dob.ki, &p->dob.ki_shift);
    p->dob.r = p->flux.r;
    p->dob.g = est_qn(d->dob_lambda / (g / lq_pu), 12);
    p->dob.k_theta = p->pll.k_theta;
}

/* running statistics of an angle error */
typedef struct {
    double sum, sum2, maxabs, spd_sum;
    long n, last_bad, k;
} est_acc_t;

static void est_acc_add(est_acc_t *a, double err, bool in_window, double spd_rel)
{
    if (fabs(err) > EST_CONV_DEG / EST_DEG) {
        a->last_bad = a->k;
    }
    if (in_window) {
        a->sum += err;
        a->sum2 += err * err;
        a->maxabs = fmax(a->maxabs, fabs(err));
        a->spd_sum += spd_rel;
        a->n++;
    }
    a->k++;
}

static void est_acc_done(const est_acc_t *a, double t_s, est_figures_t *f, bool has_speed)
{
    const double n = (a->n > 0) ? (double)a->n : 1.0;
    f->err_mean_deg = a->sum / n * EST_DEG;
    f->err_rms_deg = sqrt(a->sum2 / n) * EST_DEG;
    f->err_max_deg = a->maxabs * EST_DEG;
    f->speed_err_pct = has_speed ? a->spd_sum / n * 100.0 : NAN;
    f->conv_time_s = (a->last_bad == a->k - 1) ? -1.0 : (double)(a->last_bad + 1) * t_s;
}

static double est_angle(qfoc_angle_t a)
{
    return (double)a * EST_CNT_TO_RAD;
}

int est_run(const est_scenario_t *sc, est_result_t *res)
{
    const sim_motor_t *m = sc->motor;
    sim_motor_t m_est = *m;
    est_params_t p;
    sim_cfg_t cfg;
    sim_t s;
    sim_ctrl_t c;
    qfoc_flux_t flux;
    qfoc_pll_t pll;
    qfoc_emf_t emf;
    qfoc_pll_t emf_ato;
    qfoc_dob_t dob;
    qfoc_pll_t dob_ato;
    est_acc_t acc[EST_COUNT];
    int16_t hist[2][2] = { { 0, 0 }, { 0, 0 } }; /* commands of k-1 and k-2 */
    double we;
    double fit[2][5]; /* per axis: sum cc, cs, ss, y c, y s */
    double id_sum = 0.0;
    double iq_sum = 0.0;
    double lead_sum = 0.0;
    long n_warm;
    long n_run;
    long n_win_start;
    long k;
    FILE *trace = NULL;
    int rc = 0;

    memset(res, 0, sizeof *res);
    memset(acc, 0, sizeof acc);
    memset(fit, 0, sizeof fit);
    m_est.rs_ohm *= sc->r_fac;
    m_est.ld_h *= sc->ld_fac;
    m_est.lq_h *= sc->lq_fac;
    m_est.psi_f_wb *= sc->psi_fac;
    est_tune(&m_est, sc->design, &p);
    if (sc->table != NULL) {
        if (qfoc_params_check(sc->table) != QFOC_PARAMS_OK) {
            return -1;
        }
        p.flux = sc->table->flux;
        p.pll = sc->table->pll;
    }

    memset(&cfg, 0, sizeof cfg);
    cfg.motor = *m;
    cfg.vdc_v = sc->vdc_v;
    cfg.dead_time_s = m->dead_time_s;
    cfg.noise_i_rms_a = sc->noise_i_rms_a;
    cfg.seed = 0x5eed1234u;
    cfg.speed_locked = true;
    we = sc->speed_frac * m->rated_speed_rpm / 60.0 * 2.0 * SIM_PI * m->pole_pairs;
    cfg.locked_speed_e = we;
    cfg.substeps = 20;
    sim_init(&s, &cfg);
    sim_ctrl_init(&c, m, 800.0);
    sim_ctrl_torque_ref(&c, sc->torque_nm, we, sc->vdc_v);
    sim_set_state(&s, 0.0, we, c.id_ref, c.iq_ref);

    n_warm = lround(EST_WARMUP_S / s.bases.t_s);
    n_run = lround((sc->t_settle_s + sc->t_window_s) / s.bases.t_s);
    n_win_start = n_warm + lround(sc->t_settle_s / s.bases.t_s);
    if (sc->trace_csv != NULL) {
        trace = fopen(sc->trace_csv, "w");
        if (trace != NULL) {
            fprintf(trace, "t_s,theta_deg,err_flux_pll,err_emf_atan,err_dob_atan,err_dob_ato,"
                           "speed_flux_pll_rad_s,speed_true_rad_s\n");
        }
    }

    for (k = 0; k < n_warm + n_run; k++) {
        sim_adc_t adc;
        uint16_t cmp[3];
        const double th = sim_theta_e(&s);
        sim_sample(&s, &adc);
        if (k == n_warm) {
            /* cold start of every estimator: zero states, PLL angle off */
            const double th0 = th + sc->init_error_deg / EST_DEG;
            const qfoc_angle_t a0 =
                (qfoc_angle_t)((long)floor(th0 / EST_CNT_TO_RAD + 0.5) & 0xFFFFL);
            (void)qfoc_flux_init(&flux, &p.flux);
            (void)qfoc_pll_init(&pll, &p.pll);
            (void)qfoc_emf_init(&emf, &p.emf);
            (void)qfoc_pll_init(&emf_ato, &p.ato);
            (void)qfoc_dob_init(&dob, &p.dob);
            (void)qfoc_pll_init(&dob_ato, &p.ato);
            qfoc_pll_reset(&pll, a0, 0);
            qfoc_pll_reset(&emf_ato, a0, 0);
            qfoc_pll_reset(&dob_ato, a0, 0);
        }
        if (k >= n_warm) {
            qfoc_ab_t i_ab;
            qfoc_ab_t u_ab;
            qfoc_ab_t psi;
            qfoc_pll_out_t po;
            qfoc_pll_out_t eo;
            qfoc_pll_out_t doo;
            qfoc_emf_out_t emf_out;
            qfoc_emf_out_t dob_out;
            double e[EST_COUNT];
            const bool win = (k >= n_win_start);
            const double wtrue = sim_w_e(&s);
            double lead;
            int j;

            qfoc_clarke(sim_adc_current_q15(adc.iu), sim_adc_current_q15(adc.iv), &i_ab);
            u_ab.alpha = hist[1][0]; /* applied during the last period: computed at k-2 */
            u_ab.beta = hist[1][1];

            qfoc_flux_step(&flux, &u_ab, &i_ab, &psi);
            qfoc_pll_step(&pll, &psi, &po);
            lead = est_angle(qfoc_flux_lead(&flux, po.speed_f));
            e[EST_FLUX_PLL] = sim_wrap_pi(est_angle(po.theta) - lead - th);

            qfoc_emf_step(&emf, &u_ab, &i_ab, &emf_out);
            qfoc_pll_step_emf(&emf_ato, &emf_out.emf, &eo);
            e[EST_EMF_ATAN] =
                sim_wrap_pi(est_angle(emf_out.theta) + est_angle(qfoc_emf_lag(&emf, eo.speed_f)) - th);

            qfoc_dob_step(&dob, &u_ab, &i_ab, &dob_out);
            qfoc_pll_step_emf(&dob_ato, &dob_out.emf, &doo);
            e[EST_DOB_ATAN] =
                sim_wrap_pi(est_angle(dob_out.theta) + est_angle(qfoc_dob_lag(&dob, doo.speed_f)) - th);
            e[EST_DOB_ATO] =
                sim_wrap_pi(est_angle(doo.theta) + est_angle(qfoc_dob_lag(&dob, doo.speed_f)) - th);

            {
                const double ws = s.bases.w_base / 32768.0;
                const double rel_f = (po.speed_f * ws - wtrue) / wtrue;
                const double rel_d = (doo.speed_f * ws - wtrue) / wtrue;
                const double rel_e = (eo.speed_f * ws - wtrue) / wtrue;
                est_acc_add(&acc[EST_FLUX_PLL], e[EST_FLUX_PLL], win, rel_f);
                est_acc_add(&acc[EST_EMF_ATAN], e[EST_EMF_ATAN], win, rel_e);
                est_acc_add(&acc[EST_DOB_ATAN], e[EST_DOB_ATAN], win, rel_d);
                est_acc_add(&acc[EST_DOB_ATO], e[EST_DOB_ATO], win, rel_d);
            }
            if (win) {
                const double cc = cos(th);
                const double ss = sin(th);
                const double pa = (double)psi.alpha;
                const double pb = (double)psi.beta;
                /* psi_alpha = a1 cos + b1 sin; psi_beta = a2 sin + b2 cos */
                fit[0][0] += cc * cc;
                fit[0][1] += cc * ss;
                fit[0][2] += ss * ss;
                fit[0][3] += pa * cc;
                fit[0][4] += pa * ss;
                fit[1][3] += pb * ss;
                fit[1][4] += pb * cc;
                lead_sum += lead;
                id_sum += s.id;
                iq_sum += s.iq;
            }
            if (trace != NULL) {
                fprintf(trace, "%.6f,%.3f", s.t - EST_WARMUP_S, th * EST_DEG);
                for (j = 0; j < EST_COUNT; j++) {
                    fprintf(trace, ",%.4f", e[j] * EST_DEG);
                }
                fprintf(trace, ",%.3f,%.3f\n", po.speed_f * s.bases.w_base / 32768.0, wtrue);
            }
        }
        sim_ctrl_step(&c, &adc, th, sim_w_e(&s), cmp);
        hist[1][0] = hist[0][0];
        hist[1][1] = hist[0][1];
        hist[0][0] = c.v_cmd[0];
        hist[0][1] = c.v_cmd[1];
        sim_set_compare(&s, cmp);
        sim_step_period(&s);
        if (!(fabs(s.id) < 200.0 && fabs(s.iq) < 200.0)) {
            rc = -1;
            break;
        }
    }
    if (trace != NULL) {
        fclose(trace);
    }
    {
        int j;
        for (j = 0; j < EST_COUNT; j++) {
            est_acc_done(&acc[j], s.bases.t_s, &res->f[j], j != EST_DOB_ATAN);
        }
    }
    {
        /* least squares of the flux components against the true angle (2-29, 2-30) */
        const double n = (double)acc[0].n;
        const double scc = fit[0][0];
        const double scs = fit[0][1];
        const double sss = fit[0][2];
        const double det = scc * sss - scs * scs;
        const double a1 = (fit[0][3] * sss - fit[0][4] * scs) / det;
        const double b1 = (fit[0][4] * scc - fit[0][3] * scs) / det;
        /* beta: regressors sin (a2) and cos (b2) */
        const double a2 = (fit[1][3] * scc - fit[1][4] * scs) / det;
        const double b2 = (fit[1][4] * sss - fit[1][3] * scs) / det;
        res->psi1 = hypot(a1, b1) / 32768.0;
        res->phi_a_deg = atan2(-b1, a1) * EST_DEG;
        res->psi2 = hypot(a2, b2) / 32768.0;
        res->phi_b_deg = atan2(b2, a2) * EST_DEG;
        /* 2-31 averaged: the normalised PLL settles where psi sin(err) + mean(theta~) = 0,
           i.e. estimate - true = (psi1 phi_a + psi2 phi_b) / (psi1 + psi2); minus the lead
           correction applied to the output */
        res->bias_pred_deg = (res->psi1 * res->phi_a_deg + res->psi2 * res->phi_b_deg) /
                                 (res->psi1 + res->psi2) -
                             lead_sum / n * EST_DEG;
        res->id_a = id_sum / n;
        res->iq_a = iq_sum / n;
    }
    return rc;
}
