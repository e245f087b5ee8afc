/*
 * pil_twin.c -- the host twin of the image's drive for the lock-step of port_s32k/pil/:
 * the library (the src/ C files) compiled for the host with the image's parameter table
 * (tables/reference_params.c, the table of main.c for the 8 kHz image, mk/port.mk), behind
 * a flat interface called with ctypes (twin.py).  Not part of the library, not MISRA.
 */
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include "qfoc/drive.h"
#include "reference_params.h"

static qfoc_drive_t s_twin;

int32_t pil_twin_init(void);
void pil_twin_fast(uint16_t iu, uint16_t iv, uint16_t vdc, uint16_t out[4]);
void pil_twin_tick(int16_t t_ipm, int16_t t_pcb, const uint8_t *rx, uint8_t rx_len, uint8_t out[32]);
uint32_t pil_twin_size(void);
void pil_twin_save(uint8_t *buf);
void pil_twin_restore(const uint8_t *buf);

int32_t pil_twin_init(void)
{
    memset(&s_twin, 0, sizeof s_twin);
    return (int32_t)qfoc_drive_init(&s_twin, &qfoc_params_reference);
}

uint32_t pil_twin_size(void)
{
    return (uint32_t)sizeof(qfoc_drive_t);
}

/* out: cmp u, v, w, enable */
void pil_twin_fast(uint16_t iu, uint16_t iv, uint16_t vdc, uint16_t out[4])
{
    qfoc_adc_t adc;
    qfoc_pwm_t pwm;
    adc.iu = iu;
    adc.iv = iv;
    adc.vdc = vdc;
    pwm = qfoc_drive_fast_step(&s_twin, &adc);
    out[0] = pwm.cmp[0];
    out[1] = pwm.cmp[1];
    out[2] = pwm.cmp[2];
    out[3] = pwm.enable ? 1u : 0u;
}

/* out: tx[11], tx_len, can id (2, little-endian), dlc, data[8], can_send, pwm_off */
void pil_twin_tick(int16_t t_ipm, int16_t t_pcb, const uint8_t *rx, uint8_t rx_len, uint8_t out[32])
{
    qfoc_tick_in_t in;
    qfoc_tick_out_t o;
    in.t_ipm = t_ipm;
    in.t_pcb = t_pcb;
    in.rx = rx;
    in.rx_len = rx_len;
    o = qfoc_drive_tick(&s_twin, &in);
    memset(out, 0, 32u);
    memcpy(out, o.tx, QFOC_LIN_FRAME_MAX);
    out[11] = o.tx_len;
    out[12] = (uint8_t)(o.can.id & 0xFFu);
    out[13] = (uint8_t)(o.can.id >> 8);
    out[14] = o.can.dlc;
    memcpy(&out[15], o.can.data, 8u);
    out[23] = o.can_send ? 1u : 0u;
    out[24] = o.pwm_off ? 1u : 0u;
}

/* The twin's whole state, to run a fast step that pre-empted a tick in both orders. */
void pil_twin_save(uint8_t *buf)
{
    memcpy(buf, &s_twin, sizeof s_twin);
}

void pil_twin_restore(const uint8_t *buf)
{
    memcpy(&s_twin, buf, sizeof s_twin);
}

/* Where the image's table keeps the dead-time compensation: the offset of svpwm.dt_comp in
   qfoc_param_table_t (fixed-width fields only: the same layout on the Cortex-M4 as here) and
   the value of the host's copy of the table, for the check of the inverter's dead time
   (port_s32k/pil/run.py). */
uint32_t pil_twin_dt_comp_offset(void);
uint32_t pil_twin_dt_comp(void);

uint32_t pil_twin_dt_comp_offset(void)
{
    return (uint32_t)(offsetof(qfoc_param_table_t, svpwm) + offsetof(qfoc_svpwm_cfg_t, dt_comp));
}

uint32_t pil_twin_dt_comp(void)
{
    return (uint32_t)qfoc_params_reference.svpwm.dt_comp;
}

/* The offset of f_pwm_hz (uint16_t) in qfoc_param_table_t, for the check of the PWM
   frequency from the FTM3 registers and the clock tree (port_s32k/pil/run.py). */
uint32_t pil_twin_f_pwm_offset(void);

uint32_t pil_twin_f_pwm_offset(void)
{
    return (uint32_t)offsetof(qfoc_param_table_t, f_pwm_hz);
}
