/**
 * @file estim.h
 * @brief Closed-loop validation of the qfoc position estimators on the plant.
 *
 * The plant (sim.h) runs under the ideal double-precision current controller on
 * the true angle; the library's estimators observe it through the quantised ADC
 * samples and the Q15 voltage commands, exactly as on the target:
 *  - flux observer (qfoc_flux_step) + PLL (qfoc_pll_step), angle corrected by
 *    qfoc_flux_lead;
 *  - back-EMF estimator (qfoc_emf_step), angle by arctangent, corrected by qfoc_emf_lag;
 *  - disturbance observer (qfoc_dob_step), angle by arctangent, corrected by qfoc_dob_lag;
 *  - disturbance observer + angle-tracking observer (qfoc_pll_step_emf).
 * Estimator parameters are computed from the controller's copy of the motor data,
 * so parameter errors are applied by scaling that copy.
 */
#ifndef QFOC_SIM_ESTIM_H
#define QFOC_SIM_ESTIM_H

#include "sim.h"

#include "qfoc/emf.h"
#include "qfoc/flux.h"
#include "qfoc/pll.h"
#include "qfoc/params.h"

/** Estimators compared. */
enum { EST_FLUX_PLL = 0, EST_EMF_ATAN, EST_DOB_ATAN, EST_DOB_ATO, EST_COUNT };

/** Design choices of the estimators (physical units, converted to Q15 by est_tune). */
typedef struct {
    double kg_rad_s;        /**< flux-observer high-pass corner K_gain, rad/s */
    double pll_wn_hz;       /**< PLL natural frequency, Hz */
    double pll_zeta;        /**< PLL damping */
    double pll_clamp;       /**< PLL error clamp, sin of the angle error (0..1) */
    double pll_mag_min;     /**< PLL coasting threshold, fraction of psi_f (flux) */
    double speed_fc_hz;     /**< speed low-pass cut-off, Hz */
    double emf_fc_hz;       /**< back-EMF low-pass cut-off, Hz */
    double dob_lambda;      /**< disturbance-observer pole 1 - lambda per sample */
} est_design_t;

/** Library parameter sets for one motor (what the tuning tool produces). */
typedef struct {
    qfoc_flux_params_t flux;
    qfoc_pll_params_t pll;
    qfoc_pll_params_t ato;
    qfoc_emf_params_t emf;
    qfoc_dob_params_t dob;
} est_params_t;

/** Default design for the reference motor (see the estimator report). */
void est_design_default(est_design_t *d);

/** Convert a design and motor data (controller's copy) into library parameters. */
void est_tune(const sim_motor_t *m, const est_design_t *d, est_params_t *p);

/** One validation scenario. */
typedef struct {
    const sim_motor_t *motor;  /**< true motor */
    double speed_frac;         /**< electrical speed as a fraction of rated */
    double torque_nm;          /**< load torque (speed locked: the controller's torque) */
    double vdc_v;
    double noise_i_rms_a;
    double r_fac, ld_fac, lq_fac, psi_fac; /**< estimator parameter errors (1 = exact) */
    double t_settle_s;         /**< run before the measurement window */
    double t_window_s;         /**< measurement window */
    double init_error_deg;     /**< cold start: estimator states zero, PLL angle off by this */
    const est_design_t *design;
    const qfoc_param_table_t *table; /**< if not NULL: the flux observer and the PLL take
                                          their parameters from this generated table
                                          (tables/), checked by qfoc_params_check(); the
                                          parameter-error factors then do not apply to them */
    const char *trace_csv;     /**< if not NULL: write a per-sample trace here */
} est_scenario_t;

/** Figures of one estimator in one scenario. */
typedef struct {
    double err_mean_deg;   /**< mean of (estimate - true), electrical degrees */
    double err_max_deg;    /**< max |estimate - true| in the window */
    double err_rms_deg;
    double speed_err_pct;  /**< mean speed error, % of the true speed (PLL-based) */
    double conv_time_s;    /**< from the cold start until |error| stays below 5 deg
                                (negative: never within the run) */
} est_figures_t;

/** Result of a scenario. */
typedef struct {
    est_figures_t f[EST_COUNT];
    /* flux fit over the window (document 2-29, 2-30): psi_alpha = psi1 cos(th + phi_a),
       psi_beta = psi2 sin(th + phi_b), th the true angle; the bias they predict for the
       PLL (mean of 2-31 / psi) after the lead correction, and the bias measured */
    double psi1, psi2, phi_a_deg, phi_b_deg;
    double bias_pred_deg;
    double id_a, iq_a;     /**< operating point */
} est_result_t;

/** Run a scenario; returns 0, or -1 if the plant left its operating range or the
    scenario's table is refused by qfoc_params_check(). */
int est_run(const est_scenario_t *sc, est_result_t *res);

#endif /* QFOC_SIM_ESTIM_H */
