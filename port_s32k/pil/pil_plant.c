/**
 * @file pil_plant.c
 * @brief The plant of sim/ (sim/plant.c, sim/motor.c) behind a flat C interface for the
 *        processor-in-the-loop run (port_s32k/pil/plant.py loads it with ctypes), so that
 *        the Python side never mirrors the layout of sim_t.
 *
 * Built as a shared library: gcc -O2 -shared -fPIC -Isim port_s32k/pil/pil_plant.c
 * sim/plant.c sim/motor.c -lm (mk/pil.mk).  Host only; not part of the firmware.
 */
#include <stdlib.h>
#include <string.h>
#include "sim.h"

void *pil_plant_new(const char *motor_file, double vdc_v, int substeps);
void pil_plant_free(void *p);
int pil_plant_period(const void *p);
void pil_plant_step(void *p, unsigned c0, unsigned c1, unsigned c2, int enable);
void pil_plant_sample(void *p, unsigned out[3]);
void pil_plant_state(const void *p, double out[6]);
void pil_plant_set_dead_time(void *p, double td_s);
void pil_plant_sample_at(const void *p, double tau_s, unsigned out[3]);

/* A plant of the motor file at the bus voltage: the motor's own dead time, no noise, no
   load, switching off until the first period handed in (the FTM3 outputs start masked). */
void *pil_plant_new(const char *motor_file, double vdc_v, int substeps)
{
    sim_t *s = calloc(1u, sizeof *s);
    sim_cfg_t cfg;
    if (s == NULL) {
        return NULL;
    }
    memset(&cfg, 0, sizeof cfg);
    if (sim_motor_load(motor_file, &cfg.motor) != 0) {
        free(s);
        return NULL;
    }
    cfg.vdc_v = vdc_v;
    cfg.dead_time_s = cfg.motor.dead_time_s;
    cfg.substeps = substeps;
    cfg.load.knee_rpm = 30.0;
    sim_init(s, &cfg);
    s->en_active = false;
    s->en_pending = false;
    return s;
}

void pil_plant_free(void *p)
{
    free(p);
}

/* The PWM counter top of the motor file (f_timer / (2 f_pwm)). */
int pil_plant_period(const void *p)
{
    return (int)((const sim_t *)p)->bases.period;
}

/* One PWM period: the compare values and the enable in effect from now on are handed in,
   then the period that has just ended is integrated (sim_step_period makes them active). */
void pil_plant_step(void *p, unsigned c0, unsigned c1, unsigned c2, int enable)
{
    sim_t *s = p;
    const uint16_t cmp[3] = { (uint16_t)c0, (uint16_t)c1, (uint16_t)c2 };
    sim_set_compare(s, cmp);
    sim_set_enable(s, enable != 0);
    sim_step_period(s);
}

/* The ADC codes of i_u, i_v and V_dc at the plant's present instant. */
void pil_plant_sample(void *p, unsigned out[3])
{
    sim_adc_t adc;
    sim_sample(p, &adc);
    out[0] = adc.iu;
    out[1] = adc.iv;
    out[2] = adc.vdc;
}

/* time s, electrical speed rad/s, electrical angle rad, id A, iq A, enable active */
void pil_plant_state(const void *p, double out[6])
{
    const sim_t *s = p;
    out[0] = s->t;
    out[1] = sim_w_e(s);
    out[2] = sim_theta_e(s);
    out[3] = s->id;
    out[4] = s->iq;
    out[5] = s->en_active ? 1.0 : 0.0;
}

/* The inverter's dead time from now on, s: the one the FTM3 registers insert
   (port_s32k/pil/periph.py, FTM.pin_on), in place of the motor file's. */
void pil_plant_set_dead_time(void *p, double td_s)
{
    ((sim_t *)p)->cfg.dead_time_s = td_s;
}

/* The ADC codes of i_u, i_v and V_dc at tau_s after the start of the current period (the
   last reload point): sim_sample_at(), the plant itself unchanged. */
void pil_plant_sample_at(const void *p, double tau_s, unsigned out[3])
{
    sim_adc_t adc;
    sim_sample_at(p, tau_s, &adc);
    out[0] = adc.iu;
    out[1] = adc.iv;
    out[2] = adc.vdc;
}
