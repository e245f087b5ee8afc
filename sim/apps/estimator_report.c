/**
 * @file estimator_report.c
 * @brief `make estimator-report`: validation of the qfoc position estimators on
 *        the plant, written as Markdown tables and CSV files for the plots.
 *
 * usage: estimator_report MOTOR_FILE OUT_DIR
 */
#include "estim.h"
#include "reference_params.h"

#include "qfoc/pll.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

static const char *const est_names[EST_COUNT] = {
    "flux observer + PLL", "back-EMF + atan2", "disturbance obs. + atan2",
    "disturbance obs. + ATO"
};

static void base_scenario(est_scenario_t *sc, const sim_motor_t *m, const est_design_t *d)
{
    memset(sc, 0, sizeof *sc);
    sc->motor = m;
    sc->torque_nm = m->nominal_torque_nm;
    sc->vdc_v = m->vdc_nominal_v;
    sc->r_fac = sc->ld_fac = sc->lq_fac = sc->psi_fac = 1.0;
    sc->t_settle_s = 0.25;
    sc->t_window_s = 0.25;
    sc->init_error_deg = 90.0;
    sc->design = d;
}

static void fmt_conv(char *buf, size_t n, double t)
{
    if (t < 0.0) {
        snprintf(buf, n, "not converged");
    } else {
        snprintf(buf, n, "%.1f", t * 1000.0);
    }
}

static void fmt_speed(char *buf, size_t n, double p)
{
    if (isnan(p)) {
        snprintf(buf, n, "-");
    } else {
        snprintf(buf, n, "%+.3f", p);
    }
}

/* 1. steady state and convergence against speed, nominal parameters */
static int speed_sweep(const sim_motor_t *m, const est_design_t *d, const char *dir, FILE *md,
                       double noise)
{
    static const double speeds[] = { 0.05, 0.10, 0.25, 0.50, 0.75, 1.00, 1.25 };
    char path[512];
    FILE *csv;
    size_t i;
    int j;

    snprintf(path, sizeof path, "%s/estimators_speed%s.csv", dir, noise > 0.0 ? "_noise" : "");
    csv = fopen(path, "w");
    if (csv == NULL) {
        return -1;
    }
    fprintf(csv, "speed_pct,estimator,err_mean_deg,err_max_deg,err_rms_deg,speed_err_pct,conv_ms\n");
    for (j = 0; j < EST_COUNT; j++) {
        fprintf(md, "\n**%s**%s\n\n", est_names[j],
                noise > 0.0 ? " (with ADC noise)" : "");
        fprintf(md, "| speed (%% rated) | rpm | i_d, i_q (A) | angle error mean (deg) | "
                    "max abs (deg) | rms (deg) | speed error (%%) | convergence from 90 deg (ms) |\n");
        fprintf(md, "|---|---|---|---|---|---|---|---|\n");
        for (i = 0; i < sizeof speeds / sizeof speeds[0]; i++) {
            est_scenario_t sc;
            est_result_t r;
            char conv[32];
            char spd[32];
            base_scenario(&sc, m, d);
            sc.speed_frac = speeds[i];
            sc.noise_i_rms_a = noise;
            sc.table = &qfoc_params_reference;  /* the generated table (tables/) */
            if (est_run(&sc, &r) != 0) {
                fprintf(md, "| %.0f | plant diverged |\n", speeds[i] * 100.0);
                continue;
            }
            fmt_conv(conv, sizeof conv, r.f[j].conv_time_s);
            fmt_speed(spd, sizeof spd, r.f[j].speed_err_pct);
            fprintf(md, "| %.0f | %.0f | %.1f, %.1f | %+.3f | %.3f | %.3f | %s | %s |\n",
                    speeds[i] * 100.0, speeds[i] * m->rated_speed_rpm, r.id_a, r.iq_a,
                    r.f[j].err_mean_deg, r.f[j].err_max_deg, r.f[j].err_rms_deg, spd, conv);
            fprintf(csv, "%.0f,%d,%.5f,%.5f,%.5f,%.5f,%.3f\n", speeds[i] * 100.0, j,
                    r.f[j].err_mean_deg, r.f[j].err_max_deg, r.f[j].err_rms_deg,
                    isnan(r.f[j].speed_err_pct) ? 0.0 : r.f[j].speed_err_pct,
                    r.f[j].conv_time_s * 1000.0);
        }
    }
    fclose(csv);
    return 0;
}

/* 2. parameter errors: measured bias against the 2-31 prediction from the fitted flux */
static int param_sweep(const sim_motor_t *m, const est_design_t *d, const char *dir, FILE *md)
{
    typedef struct {
        const char *name;
        double r, ld, lq, psi;
    } case_t;
    static const case_t cases[] = {
        { "nominal", 1.0, 1.0, 1.0, 1.0 },   { "R_s +30 %", 1.3, 1.0, 1.0, 1.0 },
        { "R_s -30 %", 0.7, 1.0, 1.0, 1.0 }, { "L_d +20 %", 1.0, 1.2, 1.0, 1.0 },
        { "L_d -20 %", 1.0, 0.8, 1.0, 1.0 }, { "L_q +20 %", 1.0, 1.0, 1.2, 1.0 },
        { "L_q -20 %", 1.0, 1.0, 0.8, 1.0 }, { "psi_f +10 %", 1.0, 1.0, 1.0, 1.1 },
        { "psi_f -10 %", 1.0, 1.0, 1.0, 0.9 },
    };
    static const double speeds[] = { 0.10, 0.25, 0.50, 1.00 };
    char path[512];
    FILE *csv;
    size_t i;
    size_t s;

    snprintf(path, sizeof path, "%s/estimators_params.csv", dir);
    csv = fopen(path, "w");
    if (csv == NULL) {
        return -1;
    }
    fprintf(csv, "case,speed_pct,flux_mean,flux_max,pred_bias,emf_mean,dob_mean,ato_mean\n");
    fprintf(md, "| parameter error | speed (%% rated) | flux+PLL mean (deg) | max abs (deg) | "
                "fitted psi1, psi2 (pu) | fitted phi_a, phi_b (deg) | 2-31 predicted bias (deg) | "
                "back-EMF mean | DOB mean | DOB+ATO mean |\n");
    fprintf(md, "|---|---|---|---|---|---|---|---|---|---|\n");
    for (i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        for (s = 0; s < sizeof speeds / sizeof speeds[0]; s++) {
            est_scenario_t sc;
            est_result_t r;
            base_scenario(&sc, m, d);
            sc.speed_frac = speeds[s];
            sc.r_fac = cases[i].r;
            sc.ld_fac = cases[i].ld;
            sc.lq_fac = cases[i].lq;
            sc.psi_fac = cases[i].psi;
            if (est_run(&sc, &r) != 0) {
                continue;
            }
            fprintf(md, "| %s | %.0f | %+.2f | %.2f | %.4f, %.4f | %+.2f, %+.2f | %+.2f | %+.2f | %+.2f | %+.2f |\n",
                    cases[i].name, speeds[s] * 100.0, r.f[EST_FLUX_PLL].err_mean_deg,
                    r.f[EST_FLUX_PLL].err_max_deg, r.psi1, r.psi2, r.phi_a_deg, r.phi_b_deg,
                    r.bias_pred_deg, r.f[EST_EMF_ATAN].err_mean_deg, r.f[EST_DOB_ATAN].err_mean_deg,
                    r.f[EST_DOB_ATO].err_mean_deg);
            fprintf(csv, "%s,%.0f,%.5f,%.5f,%.5f,%.5f,%.5f,%.5f\n", cases[i].name, speeds[s] * 100.0,
                    r.f[EST_FLUX_PLL].err_mean_deg, r.f[EST_FLUX_PLL].err_max_deg, r.bias_pred_deg,
                    r.f[EST_EMF_ATAN].err_mean_deg, r.f[EST_DOB_ATAN].err_mean_deg,
                    r.f[EST_DOB_ATO].err_mean_deg);
        }
    }
    fclose(csv);
    return 0;
}

/* 3. the bias analysis of specs/equations.md E2-29 .. E2-31 on the PLL alone: synthetic
   psi_alpha = psi1 cos(th + phi_a), psi_beta = psi2 sin(th + phi_b) */
static void bias_synthetic(const sim_motor_t *m, const est_design_t *d, FILE *md)
{
    typedef struct {
        double psi1, psi2, pa_deg, pb_deg;
    } case_t;
    static const case_t cases[] = {
        { 0.40, 0.40, 0.0, 0.0 },  { 0.40, 0.40, 4.0, 4.0 },  { 0.40, 0.40, 6.0, 0.0 },
        { 0.40, 0.40, -3.0, 5.0 }, { 0.36, 0.44, 0.0, 0.0 },  { 0.44, 0.36, 0.0, 0.0 },
        { 0.36, 0.44, 4.0, 2.0 },  { 0.44, 0.36, 4.0, 2.0 },  { 0.30, 0.40, -5.0, 3.0 },
    };
    est_params_t p;
    size_t i;

    est_tune(m, d, &p);
    fprintf(md, "| psi1 | psi2 | phi_a (deg) | phi_b (deg) | predicted mean bias (deg) | "
                "measured mean bias (deg) | predicted 2-theta ripple through the loop (deg) | measured peak-to-peak / 2 (deg) |\n");
    fprintf(md, "|---|---|---|---|---|---|---|---|\n");
    for (i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        const case_t *c = &cases[i];
        const double pa = c->pa_deg * SIM_PI / 180.0;
        const double pb = c->pb_deg * SIM_PI / 180.0;
        /* 0.3 pu of w_base: 150 Hz electrical */
        const double w = 0.3;
        const double dth = w * 3141.5926535 / m->f_pwm_hz;
        const double pred = (c->psi1 * pa + c->psi2 * pb) / (c->psi1 + c->psi2) * 180.0 / SIM_PI;
        /* 2 theta terms of 2-31 (first case, which holds for either order of psi1, psi2:
           see pll.h) divided by the mean magnitude */
        const double rs = (c->psi2 - c->psi1) / 2.0;
        const double rc = (c->psi2 * pb - c->psi1 * pa) / 2.0;
        /* the PLL passes a disturbance of its error at 2 w to the angle through its
           closed-loop response T(s) = (2 zeta wn s + wn^2) / (s^2 + 2 zeta wn s + wn^2) */
        const double wn = 2.0 * SIM_PI * d->pll_wn_hz;
        const double big_w = 2.0 * w * 3141.5926535;
        const double tr = wn * wn;
        const double ti = 2.0 * d->pll_zeta * wn * big_w;
        const double br = wn * wn - big_w * big_w;
        const double t_mag = hypot(tr, ti) / hypot(br, ti);
        const double ripple =
            t_mag * hypot(rs, rc) / ((c->psi1 + c->psi2) / 2.0) * 180.0 / SIM_PI;
        qfoc_pll_t pll;
        double sum = 0.0;
        double mx = -1e9;
        double mn = 1e9;
        long n = 0;
        long k;
        double th = 0.0;
        (void)qfoc_pll_init(&pll, &p.pll);
        qfoc_pll_reset(&pll, 0u, (int16_t)lround(w * 32768.0));
        for (k = 0; k < 16000; k++) {
            qfoc_ab_t psi;
            qfoc_pll_out_t o;
            double e;
            psi.alpha = (int16_t)lround(32768.0 * c->psi1 * cos(th + pa));
            psi.beta = (int16_t)lround(32768.0 * c->psi2 * sin(th + pb));
            qfoc_pll_step(&pll, &psi, &o);
            e = sim_wrap_pi((double)o.theta * 2.0 * SIM_PI / 65536.0 - th) * 180.0 / SIM_PI;
            if (k >= 8000) {
                sum += e;
                mx = fmax(mx, e);
                mn = fmin(mn, e);
                n++;
            }
            th = fmod(th + dth, 2.0 * SIM_PI);
        }
        fprintf(md, "| %.2f | %.2f | %+.1f | %+.1f | %+.3f | %+.3f | %.3f | %.3f |\n", c->psi1,
                c->psi2, c->pa_deg, c->pb_deg, pred, sum / (double)n, ripple, (mx - mn) / 2.0);
    }
}

int main(int argc, char **argv)
{
    sim_motor_t m;
    est_design_t d;
    char path[512];
    FILE *md;
    est_scenario_t sc;
    est_result_t r;

    if (argc != 3) {
        fprintf(stderr, "usage: %s MOTOR_FILE OUT_DIR\n", argv[0]);
        return 2;
    }
    if (sim_motor_load(argv[1], &m) != 0) {
        return 1;
    }
    est_design_default(&d);
    snprintf(path, sizeof path, "%s/estimators.md", argv[2]);
    md = fopen(path, "w");
    if (md == NULL) {
        fprintf(stderr, "%s: cannot write\n", path);
        return 1;
    }
    fprintf(md, "# Position estimators validated on the plant: %s\n\n", m.name);
    fprintf(md, "Plant: `specs/reference-motor.md` model, RK4 20 steps per period, dead time %.1f us "
                "with the library's compensation, 12-bit current ADC, one period of computation "
                "delay; speed locked, load %.1f N m, V_dc %.0f V, f_pwm %.0f Hz.  Controller: "
                "double-precision current loop on the true angle.  Estimators: the Q15 library "
                "modules fed with the ADC samples and the Q15 voltage commands; in sections 1 and 2 "
                "the flux observer and the PLL take their parameters from the generated table "
                "`tables/reference_params.c` (CRC 0x%08lX, checked), elsewhere from the same design "
                "computed with the scaled motor data.  Design: K_gain "
                "%.0f rad/s, PLL w_n 2 pi %.0f Hz, zeta %.2f, error clamp %.2f, speed filter "
                "%.0f Hz, back-EMF filter %.0f Hz, DOB lambda %.2f.  Angle error = estimate - "
                "true angle at the current sample, electrical degrees; window %.2f s after %.2f s "
                "of settling from a cold start with the PLL %.0f deg off and at zero speed.\n",
                m.dead_time_s * 1e6, m.nominal_torque_nm, m.vdc_nominal_v, m.f_pwm_hz,
                (unsigned long)qfoc_params_reference.crc, d.kg_rad_s,
                d.pll_wn_hz, d.pll_zeta, d.pll_clamp, d.speed_fc_hz, d.emf_fc_hz, d.dob_lambda,
                0.25, 0.25, 90.0);
    fprintf(md, "\nTargets (flux observer + PLL, nominal parameters): |mean| <= 2 deg and max "
                "<= 5 deg at >= 10 %% rated speed; speed error <= 0.5 %% at >= 25 %%; converged "
                "(|error| < 5 deg for good) within 50 ms at >= 25 %%.\n");
    fprintf(md, "\n## 1. Angle and speed error against speed (nominal parameters)\n");
    if (speed_sweep(&m, &d, argv[2], md, 0.0) != 0) {
        return 1;
    }
    fprintf(md, "\n## 2. With ADC noise (0.2 A rms on each current sample)\n");
    if (speed_sweep(&m, &d, argv[2], md, 0.2) != 0) {
        return 1;
    }
    fprintf(md, "\n## 3. Parameter errors (estimators' motor data scaled; plant exact)\n\n");
    fprintf(md, "The flux components of the flux observer are fitted over the window to "
                "psi_alpha = psi1 cos(th + phi_a), psi_beta = psi2 sin(th + phi_b) (2-29, 2-30, "
                "th the true angle); the predicted bias is the mean of 2-31 divided by the flux, "
                "(psi1 phi_a + psi2 phi_b) / (psi1 + psi2), minus the high-pass lead correction "
                "applied to the output.\n\n");
    if (param_sweep(&m, &d, argv[2], md) != 0) {
        return 1;
    }
    fprintf(md, "\n## 4. The PLL bias analysis (2-29 .. 2-32) on synthetic flux\n\n");
    bias_synthetic(&m, &d, md);

    fprintf(md, "\n## 5. Convergence of the flux observer + PLL from other initial errors (ms)\n\n"
                "At zero speed the lead correction is 90 deg, so +90 deg on the PLL alone starts "
                "the corrected output near the true angle; -90 and 180 deg start it 180 and 90 deg "
                "off.\n\n| speed (%% rated) | +90 deg | -90 deg | 180 deg |\n|---|---|---|---|\n");
    {
        static const double sp[] = { 0.10, 0.25, 0.50, 1.00, 1.25 };
        static const double e0[] = { 90.0, -90.0, 180.0 };
        size_t i;
        size_t j;
        for (i = 0; i < sizeof sp / sizeof sp[0]; i++) {
            fprintf(md, "| %.0f |", sp[i] * 100.0);
            for (j = 0; j < 3; j++) {
                char conv[32];
                base_scenario(&sc, &m, &d);
                sc.speed_frac = sp[i];
                sc.init_error_deg = e0[j];
                (void)est_run(&sc, &r);
                fmt_conv(conv, sizeof conv, r.f[EST_FLUX_PLL].conv_time_s);
                fprintf(md, " %s |", conv);
            }
            fprintf(md, "\n");
        }
    }

    /* convergence traces for the plots */
    base_scenario(&sc, &m, &d);
    sc.t_settle_s = 0.1;
    sc.t_window_s = 0.1;
    sc.speed_frac = 0.25;
    snprintf(path, sizeof path, "%s/trace_25pct.csv", argv[2]);
    sc.trace_csv = path;
    (void)est_run(&sc, &r);
    sc.speed_frac = 1.0;
    snprintf(path, sizeof path, "%s/trace_100pct.csv", argv[2]);
    sc.trace_csv = path;
    (void)est_run(&sc, &r);
    fclose(md);
    printf("estimator report: %s/estimators.md\n", argv[2]);
    return 0;
}
