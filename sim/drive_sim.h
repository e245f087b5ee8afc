/**
 * @file drive_sim.h
 * @brief The whole qfoc drive (drive.h) in the loop with the double-precision plant:
 *        ADC samples -> qfoc_drive_fast_step -> compare values and enable -> inverter
 *        and motor; qfoc_drive_tick every 1 ms with a LIN master that sends the
 *        command frame every 10 ms.  Host only.
 */
#ifndef QFOC_SIM_DRIVE_SIM_H
#define QFOC_SIM_DRIVE_SIM_H

#include "sim.h"
#include "qfoc/drive.h"
#include "qfoc/commission.h"
#include "qfoc/drive_shunt.h"

typedef struct {
    sim_t plant;
    qfoc_drive_t drv;
    const qfoc_param_table_t *table;
    int periods_per_ms;      /**< f_pwm / 1 kHz */
    long period;             /**< PWM periods simulated */
    long ms;                 /**< ticks run */
    /* LIN master */
    bool power_on;
    bool fault_clear;
    uint16_t target_rpm;
    bool identify;           /**< true: a service tool instead of the LIN master gives the
                                  command, with the identification request, through
                                  qfoc_drive_command() on each frame period (commission.h) */
    bool link_alive;         /**< false: the master stops sending (link loss) */
    int frame_every_ms;      /**< command frame period, ms (10) */
    bool corrupt_next;       /**< send the next frame with a wrong checksum */
    /* slow inputs and injections */
    int16_t t_ipm;           /**< 0.1 degC */
    int16_t t_pcb;
    int adc_iu_add;          /**< added to the phase-u current code (fault injection) */
    /* fault injection (sim/apps/faults.c, REQ-FINJ-001): none after dsim_init */
    int skip_fast;           /**< the next periods whose fast step is not called: the
                                  inverter keeps the last compare values and enable */
    int skip_tick;           /**< the next ticks not called (the frames of those ms are lost) */
    uint32_t garbage;        /**< != 0: a frame of random bytes, never a valid command frame,
                                  on every tick without a command frame (xorshift state) */
    qfoc_ident_t *ident;     /**< NULL: the drive's fast step; else the identification
                                  beside it: qfoc_commission_fast_step() (commission.h) */
    qfoc_drive_shunt_t *shunt; /**< NULL: two phase-current sensors; else the single-shunt
                                  front end (drive_shunt.h, initialised with latency 2: the
                                  fast step runs at the start of a period with the samples
                                  of the one before), the plant's shunt sensing active */
    const qfoc_shunt_cfg_t *shift; /**< NULL: the two-sensor drive's compare values applied
                                  as they are; else (two sensors only) the edge shifting of a
                                  single shunt alone: the plant gets qfoc_shunt_plan()'s
                                  up- and down-counting values for this configuration, the
                                  drive still reads its phase-current sensors (REQ-SCN-018) */
    uint8_t fast_state;      /**< the drive state the last fast step ran in */
    bool fast_ran;           /**< the fast step ran in the last period */
    /* last outputs */
    qfoc_pwm_t pwm;
    qfoc_tick_out_t out;
    double theta_sample;     /**< true electrical angle at the last ADC sample, rad */
    long status_frames;      /**< status frames answered */
    long can_frames;         /**< CAN frames sent */
    uint16_t can_last_id;
} dsim_t;

/** Build the plant and initialise the drive from a table; returns the table status. */
int32_t dsim_init(dsim_t *ds, const sim_cfg_t *cfg, const qfoc_param_table_t *table);

/** One PWM period; the 1 ms tick runs after every periods_per_ms periods. */
void dsim_period(dsim_t *ds);

/** Run for t seconds. */
void dsim_run(dsim_t *ds, double t_s);

/** True mechanical speed, rpm. */
double dsim_rpm(const dsim_t *ds);

/** Estimated mechanical speed (filtered PLL speed), rpm. */
double dsim_est_rpm(const dsim_t *ds);

/** Estimated minus true electrical angle (lead-corrected estimate), degrees in (-180, 180]. */
double dsim_angle_err_deg(const dsim_t *ds);

/** LIN 2.x protected identifier and enhanced checksum, written independently of the
    library (sim side of the link). */
uint8_t dsim_lin_pid(uint8_t id);
uint8_t dsim_lin_checksum(const uint8_t *pid_and_data, int n);

#endif /* QFOC_SIM_DRIVE_SIM_H */
