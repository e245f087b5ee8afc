/**
 * @file qfoc_params.c
 * @brief Parameter table: CRC-32, range check, checked copy to RAM (params.h).
 */
#include "qfoc/params.h"

/* CRC-32/ISO-HDLC: reflected polynomial 0x04C11DB7 -> 0xEDB88320, initial
   register 0xFFFFFFFF, final XOR 0xFFFFFFFF (params.h). */
#define QFOC_CRC32_POLY ((uint32_t)0xEDB88320u)
#define QFOC_CRC32_INIT ((uint32_t)0xFFFFFFFFu)
#define QFOC_CRC32_XOROUT ((uint32_t)0xFFFFFFFFu)

uint32_t qfoc_crc32_byte(uint32_t crc, uint8_t byte)
{
    uint32_t c = crc ^ (uint32_t)byte;
    uint32_t bit;

    /*@ loop invariant bits: 0 <= bit <= 8;
        loop assigns bit, c;
        loop variant 8 - bit; */
    for (bit = 0u; bit < 8u; bit++) {
        if ((c & 1u) != 0u) {
            c = (c >> 1u) ^ QFOC_CRC32_POLY;
        } else {
            c = c >> 1u;
        }
    }
    return c;
}

/* a 16-bit value, little-endian */
/*@ assigns \nothing; */
static uint32_t qfoc_crc_u16(uint32_t crc, uint16_t v)
{
    const uint32_t lo = qfoc_crc32_byte(crc, (uint8_t)(v & 0xFFu));
    return qfoc_crc32_byte(lo, (uint8_t)((uint32_t)v / 256u));   /* high byte */
}

/* a signed 16-bit value as its two's-complement bit pattern, little-endian */
/*@ assigns \nothing; */
static uint32_t qfoc_crc_i16(uint32_t crc, int16_t v)
{
    /* v + 65536 for v < 0: the two's-complement pattern, computed in int32_t */
    const int32_t w = (v < 0) ? ((int32_t)v + 65536) : (int32_t)v;
    return qfoc_crc_u16(crc, (uint16_t)w);
}

/* a 32-bit value, little-endian */
/*@ assigns \nothing; */
static uint32_t qfoc_crc_u32(uint32_t crc, uint32_t v)
{
    const uint32_t lo = qfoc_crc_u16(crc, (uint16_t)(v & 0xFFFFu));
    return qfoc_crc_u16(lo, (uint16_t)(v / 65536u));   /* high half */
}

/* a PI parameter block: kp, kp_shift, ki, ki_shift, out_min, out_max */
/*@ requires valid_p: \valid_read(p);
    assigns \nothing; */
static uint32_t qfoc_crc_pi(uint32_t crc, const qfoc_pi_params_t *p)
{
    uint32_t c = qfoc_crc_i16(crc, p->kp);
    c = qfoc_crc32_byte(c, p->kp_shift);
    c = qfoc_crc_i16(c, p->ki);
    c = qfoc_crc32_byte(c, p->ki_shift);
    c = qfoc_crc_i16(c, p->out_min);
    return qfoc_crc_i16(c, p->out_max);
}

/* identity and scaling record: magic, version, f_pwm_hz, the three bases */
/*@ requires valid_t: \valid_read(t);
    assigns \nothing; */
static uint32_t qfoc_crc_head(uint32_t crc, const qfoc_param_table_t *t)
{
    uint32_t c = qfoc_crc_u32(crc, t->magic);
    c = qfoc_crc_u16(c, t->version);
    c = qfoc_crc_u16(c, t->f_pwm_hz);
    c = qfoc_crc_u32(c, t->v_base_mv);
    c = qfoc_crc_u32(c, t->i_base_ma);
    return qfoc_crc_u32(c, t->f_base_mhz);
}

/* SVPWM configuration: period, dt_comp, i_deadband, vdc_min */
/*@ requires valid_s: \valid_read(s);
    assigns \nothing; */
static uint32_t qfoc_crc_svpwm(uint32_t crc, const qfoc_svpwm_cfg_t *s)
{
    uint32_t c = qfoc_crc_u16(crc, s->period);
    c = qfoc_crc_u16(c, s->dt_comp);
    c = qfoc_crc_i16(c, s->i_deadband);
    return qfoc_crc_i16(c, s->vdc_min);
}

/* flux observer: gain, gain_shift, r, l, kg */
/*@ requires valid_f: \valid_read(f);
    assigns \nothing; */
static uint32_t qfoc_crc_flux(uint32_t crc, const qfoc_flux_params_t *f)
{
    uint32_t c = qfoc_crc_i16(crc, f->gain);
    c = qfoc_crc32_byte(c, f->gain_shift);
    c = qfoc_crc_i16(c, f->r);
    c = qfoc_crc_i16(c, f->l);
    return qfoc_crc_i16(c, f->kg);
}

/* PLL: PI block, err_clamp, mag_min, k_theta, speed_alpha */
/*@ requires valid_p: \valid_read(p);
    assigns \nothing; */
static uint32_t qfoc_crc_pll(uint32_t crc, const qfoc_pll_params_t *p)
{
    uint32_t c = qfoc_crc_pi(crc, &p->pi);
    c = qfoc_crc_i16(c, p->err_clamp);
    c = qfoc_crc_i16(c, p->mag_min);
    c = qfoc_crc_u16(c, p->k_theta);
    return qfoc_crc_i16(c, p->speed_alpha);
}

/* motor data and limits: alpha_vdc .. v_max */
/*@ requires valid_t: \valid_read(t);
    assigns \nothing; */
static uint32_t qfoc_crc_limits(uint32_t crc, const qfoc_param_table_t *t)
{
    uint32_t c = qfoc_crc_i16(crc, t->alpha_vdc);
    c = qfoc_crc_i16(c, t->ld);
    c = qfoc_crc_i16(c, t->lq);
    c = qfoc_crc_i16(c, t->psi_f);
    c = qfoc_crc_i16(c, t->i_max);
    c = qfoc_crc_i16(c, t->i_trip);
    c = qfoc_crc_i16(c, t->speed_max);
    c = qfoc_crc_i16(c, t->vdc_uv);
    c = qfoc_crc_i16(c, t->vdc_ov);
    return qfoc_crc_i16(c, t->v_max);
}

/* drive configuration, speed and calibration fields: pole_pairs .. i_align */
/*@ requires valid_d: \valid_read(d);
    assigns \nothing; */
static uint32_t qfoc_crc_drive_start(uint32_t crc, const qfoc_drive_cfg_t *d)
{
    uint32_t c = qfoc_crc32_byte(crc, d->pole_pairs);
    c = qfoc_crc_u16(c, d->k_rpm);
    c = qfoc_crc_u16(c, d->k_speed_rpm);
    c = qfoc_crc_u16(c, d->rpm_min);
    c = qfoc_crc_u16(c, d->rpm_max);
    c = qfoc_crc_i16(c, d->speed_ramp);
    c = qfoc_crc_u16(c, d->precharge_ms);
    c = qfoc_crc32_byte(c, d->offset_shift);
    c = qfoc_crc_u16(c, d->offset_window);
    return qfoc_crc_i16(c, d->i_align);
}

/* drive configuration, ALIGN time to the closed-loop hold: align_ms .. cl_hold_ms */
/*@ requires valid_d: \valid_read(d);
    assigns \nothing; */
static uint32_t qfoc_crc_drive_run(uint32_t crc, const qfoc_drive_cfg_t *d)
{
    uint32_t c = qfoc_crc_u16(crc, d->align_ms);
    c = qfoc_crc_i16(c, d->i_start);
    c = qfoc_crc_i16(c, d->of_accel);
    c = qfoc_crc_i16(c, d->of_speed);
    c = qfoc_crc_u16(c, d->ho_angle);
    c = qfoc_crc_u16(c, d->ho_dwell_ms);
    c = qfoc_crc_u16(c, d->ol_timeout_ms);
    return qfoc_crc_u16(c, d->cl_hold_ms);
}

/* drive configuration, protection: t_ipm_max .. clear_ms */
/*@ requires valid_d: \valid_read(d);
    assigns \nothing; */
static uint32_t qfoc_crc_drive_prot(uint32_t crc, const qfoc_drive_cfg_t *d)
{
    uint32_t c = qfoc_crc_i16(crc, d->t_ipm_max);
    c = qfoc_crc_i16(c, d->t_pcb_max);
    c = qfoc_crc_u16(c, d->vdc_ms);
    c = qfoc_crc_u16(c, d->temp_ms);
    c = qfoc_crc_i16(c, d->stall_err);
    c = qfoc_crc_i16(c, d->flux_tol);
    c = qfoc_crc_u16(c, d->stall_ms);
    c = qfoc_crc_i16(c, d->phase_alpha);
    c = qfoc_crc_i16(c, d->phase_i_min);
    c = qfoc_crc_i16(c, d->phase_ratio);
    c = qfoc_crc_u16(c, d->phase_ms);
    c = qfoc_crc_u16(c, d->link_timeout_ms);
    return qfoc_crc_u16(c, d->clear_ms);
}

/* drive configuration, features and link identifiers: fw_level .. can_id_b */
/*@ requires valid_d: \valid_read(d);
    assigns \nothing; */
static uint32_t qfoc_crc_drive_feat(uint32_t crc, const qfoc_drive_cfg_t *d)
{
    uint32_t c = qfoc_crc_i16(crc, d->fw_level);
    c = qfoc_crc_i16(c, d->fw_alpha);
    c = qfoc_crc_i16(c, d->tc_gain);
    c = qfoc_crc_i16(c, d->tc_amp_max);
    c = qfoc_crc_i16(c, d->tc_speed_min);
    c = qfoc_crc_i16(c, d->tc_speed_max);
    c = qfoc_crc_i16(c, d->para_speed);
    c = qfoc_crc_i16(c, d->ld_hs);
    c = qfoc_crc_i16(c, d->lq_hs);
    c = qfoc_crc32_byte(c, d->lin_id_cmd);
    c = qfoc_crc32_byte(c, d->lin_id_status);
    c = qfoc_crc_u16(c, d->can_id_a);
    return qfoc_crc_u16(c, d->can_id_b);
}

/* public interface, also called by qfoc_params_check (DEV-002) */
/* cppcheck-suppress misra-c2012-8.7 ; DEV-002 */
uint32_t qfoc_params_crc(const qfoc_param_table_t *t)
{
    /* the fields in declaration order (params.h), group by group */
    uint32_t c = qfoc_crc_head(QFOC_CRC32_INIT, t);
    c = qfoc_crc_svpwm(c, &t->svpwm);
    c = qfoc_crc_pi(c, &t->pi_id);
    c = qfoc_crc_pi(c, &t->pi_iq);
    c = qfoc_crc_pi(c, &t->pi_speed);
    c = qfoc_crc_pi(c, &t->pi_fw);
    c = qfoc_crc_flux(c, &t->flux);
    c = qfoc_crc_pll(c, &t->pll);
    c = qfoc_crc_limits(c, t);
    c = qfoc_crc_drive_start(c, &t->drive);
    c = qfoc_crc_drive_run(c, &t->drive);
    c = qfoc_crc_drive_prot(c, &t->drive);
    c = qfoc_crc_drive_feat(c, &t->drive);
    return c ^ QFOC_CRC32_XOROUT;
}

/* sampling frequency and the record of the bases */
/*@ requires valid_t: \valid_read(t);
    assigns \nothing;
    ensures result: \result <==> ParamsScalingOk(t); */
static bool qfoc_params_scaling_ok(const qfoc_param_table_t *t)
{
    return (t->f_pwm_hz >= QFOC_PARAMS_F_PWM_MIN) && (t->f_pwm_hz <= QFOC_PARAMS_F_PWM_MAX)
           && (t->v_base_mv > 0u) && (t->i_base_ma > 0u) && (t->f_base_mhz > 0u);
}

/* every block checked by its own module; each call made unconditionally (one path) */
/*@ requires valid_t: \valid_read(t);
    assigns \nothing;
    ensures result: \result <==> ParamsBlocksOk(t); */
static bool qfoc_params_blocks_ok(const qfoc_param_table_t *t)
{
    const bool svpwm_ok = qfoc_svpwm_cfg_is_valid(&t->svpwm);
    const bool id_ok = qfoc_pi_params_is_valid(&t->pi_id);
    const bool iq_ok = qfoc_pi_params_is_valid(&t->pi_iq);
    const bool speed_ok = qfoc_pi_params_is_valid(&t->pi_speed);
    const bool fw_ok = qfoc_pi_params_is_valid(&t->pi_fw);
    const bool flux_ok = qfoc_flux_params_is_valid(&t->flux);
    const bool pll_ok = qfoc_pll_params_is_valid(&t->pll);
    return svpwm_ok && id_ok && iq_ok && speed_ok && fw_ok && flux_ok && pll_ok;
}

/* motor data, limits, and the loops' current references within the current limit */
/*@ requires valid_t: \valid_read(t);
    assigns \nothing;
    ensures result: \result <==> ParamsLimitsOk(t); */
static bool qfoc_params_limits_ok(const qfoc_param_table_t *t)
{
    const int32_t i_max = (int32_t)t->i_max;
    const bool motor = (t->alpha_vdc >= 1) && (t->ld >= 0) && (t->lq >= 0) && (t->psi_f >= 0);
    const bool limits = (i_max >= 1) && (i_max <= (int32_t)t->i_trip) && (t->speed_max >= 1)
                        && (t->vdc_uv >= 1) && (t->vdc_uv < t->vdc_ov) && (t->v_max >= 1);
    const bool refs = ((int32_t)t->pi_speed.out_min >= -i_max)
                      && ((int32_t)t->pi_speed.out_max <= i_max)
                      && ((int32_t)t->pi_fw.out_min >= -i_max)
                      && (t->pi_fw.out_max <= 0);
    return motor && limits && refs;
}

/* the drive configuration within the table's limits: currents within i_max, speeds
   within speed_max; the largest target rpm_max converted to Q15 with k_rpm (Q12,
   rounded): at most (65535 x 65535 + 2048) / 4096 = 1048543, the sum below
   4294838273 < 2^32 */
/*@ requires valid_t: \valid_read(t);
    assigns \nothing;
    ensures result: \result <==> ParamsDriveCrossOk(t); */
static bool qfoc_params_drive_cross_ok(const qfoc_param_table_t *t)
{
    const uint32_t rpm_max = (uint32_t)t->drive.rpm_max;
    const uint32_t k_rpm = (uint32_t)t->drive.k_rpm;
    uint32_t prod;
    uint32_t top;

    /*@ assert prod_bound: rpm_max * k_rpm <= 65535 * 65535; */
    prod = rpm_max * k_rpm;
    top = (prod + 2048u) / 4096u;   /* (x + 2048) >> 12 of x >= 0: at most 1048543 */
    return (t->drive.i_align <= t->i_max) && (t->drive.i_start <= t->i_max)
           && (t->drive.tc_amp_max <= t->i_max) && (t->drive.of_speed <= t->speed_max)
           && ((int32_t)top <= (int32_t)t->speed_max);
}

/* public interface, also called by qfoc_params_check (DEV-002) */
/* cppcheck-suppress misra-c2012-8.7 ; DEV-002 */
bool qfoc_params_is_valid(const qfoc_param_table_t *t)
{
    const bool scaling = qfoc_params_scaling_ok(t);
    const bool blocks = qfoc_params_blocks_ok(t);
    const bool limits = qfoc_params_limits_ok(t);
    const bool drive = qfoc_drive_cfg_is_valid(&t->drive);
    const bool cross = qfoc_params_drive_cross_ok(t);
    return scaling && blocks && limits && drive && cross;
}

/* public interface, also called by qfoc_params_load (DEV-002) */
/* cppcheck-suppress misra-c2012-8.7 ; DEV-002 */
int32_t qfoc_params_check(const qfoc_param_table_t *t)
{
    int32_t status;

    if ((t->magic != QFOC_PARAMS_MAGIC) || (t->version != QFOC_PARAMS_VERSION)) {
        status = QFOC_PARAMS_ERR_ID;
    } else if (t->crc != qfoc_params_crc(t)) {
        status = QFOC_PARAMS_ERR_CRC;
    } else if (!qfoc_params_is_valid(t)) {
        status = QFOC_PARAMS_ERR_RANGE;
    } else {
        status = QFOC_PARAMS_OK;
    }
    return status;
}

int32_t qfoc_params_load(qfoc_param_table_t *ram, const qfoc_param_table_t *rom)
{
    int32_t status = qfoc_params_check(rom);

    if (status == QFOC_PARAMS_OK) {
        *ram = *rom;
        /* the copy is checked where it will be used */
        status = qfoc_params_check(ram);
    } else {
        /* refused: RAM keeps what it held, the caller stays in its safe state */
    }
    return status;
}
