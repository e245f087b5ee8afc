/*
 * CBMC harness: qfoc_params_check() and qfoc_params_load() on any table.
 *
 * Every field of the table is nondet (any bit pattern).  The CRC computation is
 * abstracted (GOTO_INSTRUMENT --replace-calls qfoc_params_crc:harness_crc_any: every
 * call returns any value, so every stored CRC can match or not); its own harness
 * params_crc checks it.  Properties (REQ-PAR-001, REQ-PAR-003, REQ-PAR-004,
 * REQ-PAR-005):
 *  - no undefined behaviour in the range check, the check order or the copy;
 *  - identity: ERR_ID exactly for a wrong magic or version;
 *  - range check as specified: qfoc_params_is_valid() equals the conditions of
 *    params.h written out here, the drive configuration's ranges (drive_cfg.h) and the
 *    cross-field conditions of layout version 2 included (REQ-PAR-006, REQ-PAR-007);
 *  - the status: OK only for a known, in-range table; ERR_RANGE only for a known
 *    table out of range; ERR_CRC only for a known table; nothing else;
 *  - load: returns OK only for a known, in-range table; the RAM copy equals the
 *    table on OK and is untouched otherwise.
 *
 * Methods: 1b every bit pattern of every field of the table, any CRC result; 1c the
 * ranges of params.h and drive_cfg.h and the cross-field conditions written out field
 * by field; 1d a foreign, out-of-range or corrupted table: the RAM copy untouched
 */
#include <stdint.h>
#include <stdbool.h>
#include <string.h>
#include "qfoc/params.h"
#include "../harness_util.h"

/* stands for qfoc_params_crc() in this harness: any CRC value */
uint32_t harness_crc_any(const qfoc_param_table_t *t);
uint32_t harness_crc_any(const qfoc_param_table_t *t)
{
    (void)t;
    return nondet_uint32();
}

static bool pi_ok(const qfoc_pi_params_t *p)
{
    return (p->kp >= 0) && (p->kp_shift <= 15u) && (p->ki >= 0) && (p->ki_shift <= 15u)
           && (p->out_min >= -32767) && (p->out_min <= p->out_max);
}

static bool ms_ok(uint16_t v)
{
    return (v >= 1u) && (v <= 60000u);
}

/* drive_cfg.h's ranges, written out from the header's field comments */
static bool drive_ok(const qfoc_drive_cfg_t *c)
{
    return (c->pole_pairs >= 1u) && (c->pole_pairs <= 16u)
        && (c->k_rpm >= 1u) && (c->k_speed_rpm >= 1u)
        && (c->rpm_min >= 1u) && (c->rpm_min <= c->rpm_max) && (c->speed_ramp >= 1)
        && ms_ok(c->precharge_ms)
        && (c->offset_shift >= 4u) && (c->offset_shift <= 10u) && (c->offset_window <= 2047u)
        && (c->i_align >= 1) && (c->align_ms >= 2u) && (c->align_ms <= 60000u)
        && (c->i_start >= 1) && (c->of_accel >= 1) && (c->of_speed >= 1)
        && (c->ho_angle >= 1u) && (c->ho_angle <= 16384u)
        && ms_ok(c->ho_dwell_ms) && ms_ok(c->ol_timeout_ms) && (c->cl_hold_ms <= 60000u)
        && (c->t_ipm_max >= -400) && (c->t_ipm_max <= 2000)
        && (c->t_pcb_max >= -400) && (c->t_pcb_max <= 2000)
        && (c->vdc_ms >= 1u) && (c->vdc_ms <= 10u) && (c->temp_ms >= 1u) && (c->temp_ms <= 10u)
        && (c->stall_err >= 1) && (c->flux_tol >= 1) && ms_ok(c->stall_ms)
        && (c->phase_alpha >= 1) && (c->phase_i_min >= 1) && (c->phase_ratio >= 0)
        && ms_ok(c->phase_ms) && ms_ok(c->link_timeout_ms) && ms_ok(c->clear_ms)
        && (c->fw_level >= 1) && (c->fw_alpha >= 1)
        && (c->tc_gain >= 0) && (c->tc_amp_max >= 0)
        && (c->tc_speed_min >= 0) && (c->tc_speed_min <= c->tc_speed_max)
        && (c->para_speed >= 1) && (c->ld_hs >= 0) && (c->lq_hs >= 0)
        && (c->lin_id_cmd <= 0x3Bu) && (c->lin_id_status <= 0x3Bu)
        && (c->lin_id_status != c->lin_id_cmd)
        && (c->can_id_a <= 0x7FFu) && (c->can_id_b <= 0x7FFu)
        && (c->mtpa_speed >= 0)
        && (c->t_ipm_derate >= -400) && (c->t_ipm_derate < c->t_ipm_max)
        && (c->t_pcb_derate >= -400) && (c->t_pcb_derate < c->t_pcb_max)
        && (c->rpm_derate >= c->rpm_min) && (c->rpm_derate <= c->rpm_max)
        && (c->flux_band >= 1) && (c->flux_v_err >= 0) && (c->flux_r_err >= 0)
        && (c->psi_shift <= QFOC_DRIVE_PSI_SHIFT_MAX)
        && (c->ho_retries <= QFOC_DRIVE_HO_RETRIES_MAX)
        && (c->sensing <= 1u) && (c->shunt_sample >= 1u)
        && (c->shunt_hold >= 1u) && (c->shunt_hold <= 16u);
}

/* params.h's cross-field conditions of layout 2.  The rpm condition
   (rpm_max k_rpm + 2048) >> 12 <= speed_max is written here without a shift or a
   divider: x + 2048 < (speed_max + 1) x 4096 in 64 bits, false for a negative speed_max.
   The product x = rpm_max k_rpm is the same 32-bit expression as the library's (a
   second multiplier would make the SAT problem an equivalence miter of two multipliers);
   that the 32-bit product does not wrap is the library's own overflow check. */
static bool cross_ok(const qfoc_param_table_t *t)
{
    const uint32_t prod = (uint32_t)t->drive.rpm_max * (uint32_t)t->drive.k_rpm;
    const bool rpm_ok = (t->speed_max >= 0)
        && (((uint64_t)prod + 2048u) < (((uint64_t)(uint16_t)t->speed_max + 1u) * 4096u));
    /* the single shunt's window (layout 5), in 64 bits */
    const bool shunt_ok = (4u * ((uint64_t)t->drive.shunt_settle + t->drive.shunt_sample))
                          <= (uint64_t)t->svpwm.period;
    return (t->drive.i_align <= t->i_max) && (t->drive.i_start <= t->i_max)
        && (t->drive.tc_amp_max <= t->i_max) && (t->drive.of_speed <= t->speed_max)
        && rpm_ok && shunt_ok;
}

/* params.h's ranges, written out from the header's documentation */
static bool ref_valid(const qfoc_param_table_t *t)
{
    return drive_ok(&t->drive) && cross_ok(t)
        && (t->f_pwm_hz >= 1000u) && (t->f_pwm_hz <= 40000u)
        && (t->v_base_mv > 0u) && (t->i_base_ma > 0u) && (t->f_base_mhz > 0u)
        && (t->svpwm.period >= 100u) && (t->svpwm.period <= 32767u)
        && (t->svpwm.dt_comp <= (t->svpwm.period / 4u))
        && (t->svpwm.i_deadband >= 0) && (t->svpwm.vdc_min > 0)
        && pi_ok(&t->pi_id) && pi_ok(&t->pi_iq) && pi_ok(&t->pi_speed) && pi_ok(&t->pi_fw)
        && (t->flux.gain >= 0) && (t->flux.gain_shift <= 15u) && (t->flux.r >= 0)
        && (t->flux.l >= 0) && (t->flux.kg >= 0)
        && pi_ok(&t->pll.pi) && (t->pll.err_clamp >= 1) && (t->pll.mag_min >= 1)
        && (t->pll.k_theta >= 1u) && (t->pll.k_theta <= 32767u) && (t->pll.speed_alpha >= 1)
        && (t->alpha_vdc >= 1) && (t->ld >= 0) && (t->lq >= 0) && (t->psi_f >= 0)
        && (t->i_max >= 1) && (t->i_max <= t->i_trip) && (t->speed_max >= 1)
        && (t->vdc_uv >= 1) && (t->vdc_uv < t->vdc_ov) && (t->vdc_ov < 32760) && (t->v_max >= 1)
        && ((int32_t)t->pi_speed.out_min >= -(int32_t)t->i_max)
        && (t->pi_speed.out_max <= t->i_max)
        && ((int32_t)t->pi_fw.out_min >= -(int32_t)t->i_max) && (t->pi_fw.out_max <= 0);
}

int main(void)
{
    qfoc_param_table_t t;
    qfoc_param_table_t ram;
    qfoc_param_table_t before;
    int32_t st;
    int32_t ld;
    bool id_ok;
    bool valid;

    /* any bit pattern: fill the whole object, padding included */
    __CPROVER_havoc_object(&t);
    __CPROVER_havoc_object(&ram);
    before = ram;

    id_ok = (t.magic == QFOC_PARAMS_MAGIC) && (t.version == QFOC_PARAMS_VERSION);
    valid = ref_valid(&t);
    __CPROVER_assert(qfoc_params_is_valid(&t) == valid, "range check as specified");

    st = qfoc_params_check(&t);
    __CPROVER_assert((st == QFOC_PARAMS_OK) || (st == QFOC_PARAMS_ERR_ID)
                     || (st == QFOC_PARAMS_ERR_CRC) || (st == QFOC_PARAMS_ERR_RANGE),
                     "status is one of the four codes");
    __CPROVER_assert((st == QFOC_PARAMS_ERR_ID) == !id_ok, "identity");
    __CPROVER_assert((st != QFOC_PARAMS_OK) || (id_ok && valid), "OK only for a known table in range");
    __CPROVER_assert((st != QFOC_PARAMS_ERR_RANGE) || (id_ok && !valid),
                     "ERR_RANGE only for a known table out of range");
    __CPROVER_assert((st != QFOC_PARAMS_ERR_CRC) || id_ok, "ERR_CRC only for a known table");

    ld = qfoc_params_load(&ram, &t);
    __CPROVER_assert((ld != QFOC_PARAMS_OK) || (id_ok && valid), "load: OK only for a known table in range");
    if (ld == QFOC_PARAMS_OK) {
        __CPROVER_assert(memcmp(&ram, &t, sizeof t) == 0, "load: copy on OK");
    }
    if (!id_ok || !valid) {
        __CPROVER_assert(memcmp(&ram, &before, sizeof ram) == 0,
                         "load: refused table leaves RAM untouched");
    }
    return 0;
}
