/**
 * @file drive_sim.c
 * @brief The qfoc drive in the loop with the plant (drive_sim.h).
 */
#include "drive_sim.h"

#include <math.h>
#include <string.h>

uint8_t dsim_lin_pid(uint8_t id)
{
    const int b[6] = { id & 1, (id >> 1) & 1, (id >> 2) & 1, (id >> 3) & 1, (id >> 4) & 1,
                       (id >> 5) & 1 };
    const int p0 = b[0] ^ b[1] ^ b[2] ^ b[4];
    const int p1 = 1 - (b[1] ^ b[3] ^ b[4] ^ b[5]);
    return (uint8_t)((id & 0x3F) | (p0 << 6) | (p1 << 7));
}

uint8_t dsim_lin_checksum(const uint8_t *pid_and_data, int n)
{
    unsigned sum = 0;
    int k;
    for (k = 0; k < n; k++) {
        sum += pid_and_data[k];
        if (sum > 255u) {
            sum -= 255u;
        }
    }
    return (uint8_t)(~sum & 0xFFu);
}

int32_t dsim_init(dsim_t *ds, const sim_cfg_t *cfg, const qfoc_param_table_t *table)
{
    memset(ds, 0, sizeof *ds);
    sim_init(&ds->plant, cfg);
    ds->table = table;
    ds->periods_per_ms = (int)floor(cfg->motor.f_pwm_hz / 1000.0 + 0.5);
    if (ds->periods_per_ms < 1) {
        ds->periods_per_ms = 1;
    }
    ds->link_alive = true;
    ds->frame_every_ms = 10;
    ds->t_ipm = 400;
    ds->t_pcb = 350;
    return qfoc_drive_init(&ds->drv, table);
}

/* A garbage frame: 0 .. QFOC_LIN_FRAME_MAX random bytes, half of them behind a valid sync
   byte and command identifier; never a valid command frame (a checksum that would match is
   changed). */
static uint8_t dsim_garbage(dsim_t *ds, uint8_t *frame)
{
    uint32_t x = ds->garbage;
    uint8_t n;
    uint8_t k;
    x ^= x << 13;
    x ^= x >> 17;
    x ^= x << 5;
    n = (uint8_t)(x % (QFOC_LIN_FRAME_MAX + 1u));
    for (k = 0u; k < n; k++) {
        x ^= x << 13;
        x ^= x >> 17;
        x ^= x << 5;
        frame[k] = (uint8_t)(x >> 24);
    }
    if ((ds->garbage & 1u) != 0u && n >= 2u) {
        frame[0] = 0x55u;
        frame[1] = dsim_lin_pid(ds->table->drive.lin_id_cmd);
    }
    if (n == 7u && frame[0] == 0x55u && frame[1] == dsim_lin_pid(ds->table->drive.lin_id_cmd) &&
        frame[6] == dsim_lin_checksum(&frame[1], 5)) {
        frame[6] = (uint8_t)(frame[6] ^ 0x01u);
    }
    ds->garbage = (x != 0u) ? x : 1u;
    return n;
}

static void dsim_tick(dsim_t *ds)
{
    uint8_t frame[QFOC_LIN_FRAME_MAX];
    qfoc_tick_in_t in;
    if (ds->skip_tick > 0) {
        ds->skip_tick--;
        ds->ms++;
        return;
    }
    in.t_ipm = ds->t_ipm;
    in.t_pcb = ds->t_pcb;
    in.rx = frame;
    in.rx_len = 0u;
    if (ds->link_alive && ds->identify && (ds->ms % ds->frame_every_ms) == 0) {
        qfoc_cmd_t cmd;
        cmd.power_on = ds->power_on;
        cmd.fault_clear = ds->fault_clear;
        cmd.target_rpm = ds->target_rpm;
        cmd.identify = true;
        (void)qfoc_drive_command(&ds->drv, &cmd);
    } else if (ds->link_alive && (ds->ms % ds->frame_every_ms) == 0) {
        frame[0] = 0x55u;
        frame[1] = dsim_lin_pid(ds->table->drive.lin_id_cmd);
        frame[2] = (uint8_t)((ds->power_on ? 1u : 0u) | (ds->fault_clear ? 2u : 0u));
        frame[3] = (uint8_t)(ds->target_rpm & 0xFFu);
        frame[4] = (uint8_t)(ds->target_rpm >> 8);
        frame[5] = 0u;
        frame[6] = dsim_lin_checksum(&frame[1], 5);
        if (ds->corrupt_next) {
            frame[6] = (uint8_t)(frame[6] ^ 0x01u);
            ds->corrupt_next = false;
        }
        in.rx_len = 7u;
    } else if (ds->garbage != 0u) {
        in.rx_len = dsim_garbage(ds, frame);
    }
    ds->out = qfoc_drive_tick(&ds->drv, &in);
    if (ds->out.pwm_off) {
        /* the port's second path to the safe state (drive.h, REQ-DRV-021) */
        sim_set_enable(&ds->plant, false);
    }
    if (ds->out.tx_len > 0u) {
        ds->status_frames++;
    }
    if (ds->out.can_send) {
        ds->can_frames++;
        ds->can_last_id = ds->out.can.id;
    }
    ds->ms++;
}

void dsim_period(dsim_t *ds)
{
    sim_adc_t a;
    qfoc_adc_t adc;
    int iu;
    ds->theta_sample = sim_theta_e(&ds->plant);
    sim_sample(&ds->plant, &a);
    iu = (int)a.iu + ds->adc_iu_add;
    adc.iu = (uint16_t)(iu < 0 ? 0 : (iu > 4095 ? 4095 : iu));
    adc.iv = a.iv;
    adc.vdc = a.vdc;
    ds->fast_ran = (ds->skip_fast <= 0);
    if (ds->fast_ran) {
        ds->fast_state = ds->drv.s.sm.state;
        if (ds->shunt != NULL) {
            uint16_t code[2];
            (void)sim_sample_shunt(&ds->plant, code);
            const qfoc_shunt_plan_t *plan;
            const qfoc_adc_t codes = qfoc_drive_shunt_measure(ds->shunt, &ds->drv, &adc,
                                                              sim_adc_current_q15(code[0]),
                                                              sim_adc_current_q15(code[1]));
            ds->pwm = qfoc_drive_shunt_output(ds->shunt, qfoc_drive_fast_step(&ds->drv, &codes));
            plan = qfoc_drive_shunt_plan(ds->shunt, &ds->drv);
            sim_set_compare2(&ds->plant, plan->up, plan->down);
            sim_set_triggers(&ds->plant, plan->trig, plan->ok);
        } else {
            ds->pwm = (ds->ident != NULL) ? qfoc_commission_fast_step(&ds->drv, ds->ident, &adc)
                                          : qfoc_drive_fast_step(&ds->drv, &adc);
            if (ds->shift != NULL) {
                qfoc_shunt_plan_t plan;
                qfoc_shunt_plan(ds->shift, ds->pwm.cmp, &plan);
                sim_set_compare2(&ds->plant, plan.up, plan.down);
            } else {
                sim_set_compare(&ds->plant, ds->pwm.cmp);
            }
        }
        sim_set_enable(&ds->plant, ds->pwm.enable);
    } else {
        ds->skip_fast--;   /* a missed interrupt: the PWM unit goes on with its last values */
    }
    sim_step_period(&ds->plant);
    ds->period++;
    if ((ds->period % ds->periods_per_ms) == 0) {
        dsim_tick(ds);
    }
}

void dsim_run(dsim_t *ds, double t_s)
{
    const long n = (long)floor(t_s / ds->plant.bases.t_s + 0.5);
    long k;
    for (k = 0; k < n; k++) {
        dsim_period(ds);
    }
}

double dsim_rpm(const dsim_t *ds)
{
    return ds->plant.w_m * 60.0 / (2.0 * SIM_PI);
}

double dsim_est_rpm(const dsim_t *ds)
{
    return (double)ds->drv.f.speed_f / 32768.0 * ds->plant.bases.w_base /
           ds->plant.cfg.motor.pole_pairs * 60.0 / (2.0 * SIM_PI);
}

double dsim_angle_err_deg(const dsim_t *ds)
{
    const double est = (double)ds->drv.f.theta_est * 2.0 * SIM_PI / 65536.0;
    return sim_wrap_pi(est - ds->theta_sample) * 180.0 / SIM_PI;
}
