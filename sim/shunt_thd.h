/**
 * @file shunt_thd.h
 * @brief The phase-current distortion of the drive at one steady operating point, on two
 *        phase-current sensors, on a single shunt, or on two sensors with the single shunt's
 *        edge shifting alone (REQ-SCN-018, specs/requirements/scenarios.md).  Host only;
 *        used by sim/apps/shunt_thd.c (make shunt-thd) and tests/test_shunt_thd.c.
 *
 * A run rigs the plant as the scenarios do (sim/scenario.c: nominal bus, the motor's dead
 * time, a passive compressor load of the given torque, noise seed 7; a single-shunt table
 * with scn_shunt_plant()), starts the drive from standstill to the target speed through the
 * LIN command, holds it for settle_s after the speed is within 1 % in CLOSED_LOOP, then
 * records the plant's true phase currents at every sub-step (sim_record()) over a whole
 * number of electrical periods, the window's end found on the recorded electrical angle,
 * and analyses each phase with sim_harmonics().
 */
#ifndef QFOC_SIM_SHUNT_THD_H
#define QFOC_SIM_SHUNT_THD_H

#include "scenario.h"

/** What measures the currents and what the inverter applies. */
#define SHT_TWO_SENSOR 0  /**< two phase sensors, symmetric centre-aligned PWM */
#define SHT_SHUNT      1  /**< the single-shunt table: DC-link samples, shifted edges */
#define SHT_SHIFT      2  /**< two phase sensors, the edges shifted by qfoc_shunt_plan() (shift) */

/** One operating point. */
typedef struct {
    const scn_table_t *tab;  /**< the table the drive runs (SHT_SHUNT: a single-shunt one) */
    int mode;                /**< SHT_* */
    qfoc_shunt_cfg_t shift;  /**< SHT_SHIFT: the measurement window's configuration */
    double rpm;              /**< target speed */
    double load_nm;          /**< mean compressor load torque */
    double noise_a;          /**< current-sample noise, A rms */
    int substeps;            /**< plant sub-steps per PWM period */
    double settle_s;         /**< held at the target before the record */
    double window_s;         /**< the record's length, rounded to whole electrical periods (>= 2) */
    int h_max;               /**< highest harmonic of the THD (e.g. 40) */
    const char *dump_csv;    /**< NULL; else the window's samples are written there (t_s,
                                  theta_e, i_u, i_v, i_w) */
} sht_point_t;

/** Its figures. */
typedef struct {
    int ok;                  /**< 1: the point was reached, recorded and analysed */
    char why[96];            /**< else the reason */
    double t_reach_s;        /**< the speed within 1 % in CLOSED_LOOP after the command */
    double rpm_mean;         /**< true mean speed over the window, from the recorded angle */
    int cycles;              /**< electrical periods in the window */
    long n;                  /**< samples in the window */
    sim_harm_t ph[3];        /**< phases u, v, w */
    double fund_rms;         /**< the three phases' mean: RMS of the fundamental, A */
    double thd;              /**< the three phases' mean: harmonics 2 .. h_max / fundamental */
    double tdd;              /**< the three phases' mean: RMS(i - fundamental) / fundamental */
    double shifted_frac;     /**< periods of the window with an edge shifted (SHT_SHUNT,
                                  SHT_SHIFT; 0 otherwise) */
    int dec4;                /**< 1: substeps is a multiple of 4 and the two below are set */
    double thd_dec4;         /**< thd of the same window with every 4th sample only */
    double tdd_dec4;         /**< tdd of the same window with every 4th sample only */
} sht_result_t;

/** Run one point; 0, or -1 when the motor file cannot be read or the table is refused
    (r->ok tells whether the point was reached and analysed). */
int sht_run(const sht_point_t *p, sht_result_t *r);

/** The single-shunt measurement window of a table: period, settle, sample and hold as
    qfoc_drive_shunt_init() takes them. */
void sht_shunt_cfg(const qfoc_param_table_t *t, qfoc_shunt_cfg_t *c);

#endif /* QFOC_SIM_SHUNT_THD_H */
