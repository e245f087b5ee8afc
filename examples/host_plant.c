/**
 * @file host_plant.c
 * @brief An ECU-style integration on the simulated compressor: the drive commanded
 *        and observed only through the command and status functions of drive.h (no
 *        LIN frame, no field of qfoc_drive_t), with the double-precision motor and
 *        inverter of sim/ in place of the hardware.
 *
 * The "ECU" sends its command every 10 ms, as a CAN message handler would: run at
 * 3000 rpm, then 2000 rpm, then stop.  Every 500 ms it prints the status it reads.
 * Built and run by `make test`; exit status 0 when the motor, with the reference
 * compressor load of 4.5 N m, reaches each target within 2 % (estimated and true
 * speed), the estimated angle is within 10 degrees of the rotor's, and the drive ends
 * in STOP without a fault.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include "qfoc/drive.h"
#include "sim.h"
#include "reference_params.h"

#define MOTOR_FILE "specs/motors/reference.toml"

static qfoc_drive_t drive;
static sim_t plant;

/* one millisecond: the PWM periods with the plant, the ECU's command, the tick */
static void run_ms(int periods_per_ms, long ms, const qfoc_cmd_t *cmd)
{
    const qfoc_tick_in_t in = { 400, 350, NULL, 0u };
    int k;
    for (k = 0; k < periods_per_ms; k++) {
        sim_adc_t a;
        qfoc_adc_t adc;
        qfoc_pwm_t pwm;
        sim_sample(&plant, &a);
        adc.iu = a.iu;
        adc.iv = a.iv;
        adc.vdc = a.vdc;
        pwm = qfoc_drive_fast_step(&drive, &adc);
        sim_set_compare(&plant, pwm.cmp);
        sim_set_enable(&plant, pwm.enable);
        sim_step_period(&plant);
    }
    if ((ms % 10) == 0) {
        (void)qfoc_drive_command(&drive, cmd);
    }
    (void)qfoc_drive_tick(&drive, &in);
}

static double true_rpm(void)
{
    return plant.w_m * 60.0 / (2.0 * SIM_PI);
}

static double angle_err_deg(void)
{
    const double est = (double)qfoc_drive_angle_est(&drive) * 2.0 * SIM_PI / 65536.0;
    return sim_wrap_pi(est - sim_theta_e(&plant)) * 180.0 / SIM_PI;
}

int main(void)
{
    sim_cfg_t cfg;
    qfoc_cmd_t cmd = { false, false, 0u, false };
    int periods_per_ms;
    long ms;
    int bad = 0;

    memset(&cfg, 0, sizeof cfg);
    if (sim_motor_load(MOTOR_FILE, &cfg.motor) != 0) {
        return 1;
    }
    cfg.vdc_v = 320.0;
    cfg.dead_time_s = cfg.motor.dead_time_s;
    cfg.substeps = 20;
    cfg.noise_i_rms_a = 0.05;
    cfg.seed = 11u;
    cfg.load.t_mean = 4.5;
    cfg.load.knee_rpm = 30.0;
    sim_init(&plant, &cfg);
    periods_per_ms = (int)floor(cfg.motor.f_pwm_hz / 1000.0 + 0.5);
    if (qfoc_drive_init(&drive, &qfoc_params_reference) != QFOC_PARAMS_OK) {
        return 1;
    }
    printf("   t s  state sub  faults  target  est rpm  true rpm  bus V  current A  angle err deg\n");
    /* (the angle error means something only while the drive runs) */
    for (ms = 0; ms < 16000; ms++) {
        cmd.power_on = (ms >= 500) && (ms < 13000);
        cmd.target_rpm = (ms < 8000) ? 3000u : 2000u;
        run_ms(periods_per_ms, ms, &cmd);
        if ((ms % 500) == 499) {
            qfoc_status_t st;
            qfoc_drive_status(&drive, &st);
            printf("%6.1f  %5u %3u  0x%04x  %6u  %7u  %8.0f  %5.1f  %9.2f  %13.1f\n",
                   (double)(ms + 1) / 1000.0, (unsigned)st.state, (unsigned)st.substate,
                   (unsigned)st.faults, (unsigned)qfoc_drive_target_rpm(&drive),
                   (unsigned)st.speed_rpm, true_rpm(), st.vdc_dv / 10.0, st.current_ca / 100.0,
                   angle_err_deg());
        }
        /* checked at the end of each speed step, and in closed loop throughout */
        if ((ms == 7999) || (ms == 12999)) {
            const double target = (ms == 7999) ? 3000.0 : 2000.0;
            bad |= fabs(true_rpm() - target) > 0.02 * target;
            bad |= fabs((double)qfoc_drive_speed_rpm(&drive) - target) > 0.02 * target;
        }
        if ((qfoc_drive_substate(&drive) == QFOC_SUB_CLOSED_LOOP) && (ms > 4000) && (ms < 13000)) {
            bad |= fabs(angle_err_deg()) > 10.0;
        }
        bad |= qfoc_drive_faults(&drive) != 0u;
    }
    bad |= qfoc_drive_state(&drive) != QFOC_STATE_STOP;
    bad |= qfoc_drive_speed_rpm(&drive) != 0u;     /* no estimate with the PWM off */
    printf("host_plant: %s\n", bad ? "FAILED" : "targets reached, stopped without a fault");
    return bad ? 1 : 0;
}
