/*
 * CBMC harness: qfoc_drive_cfg_is_valid() on any configuration (REQ-DCFG-001,
 * REQ-DCFG-002, REQ-DCFG-003, REQ-DCFG-004, REQ-DCFG-005, REQ-DCFG-006).
 *
 * Every byte of the configuration is nondet (any bit pattern, padding included).
 * Properties:
 *  - no undefined behaviour in the check;
 *  - the result equals the ranges of drive_cfg.h written out here field by field, the
 *    three relations (rpm_min <= rpm_max, tc_speed_min <= tc_speed_max,
 *    lin_id_status != lin_id_cmd) included;
 *  - the check reads the configuration only (it is unchanged).
 *
 * Methods: 1b every bit pattern of the configuration, padding included (valid and
 * invalid); 1c each field's range as drive_cfg.h writes it, the three relations at
 * equality; 1d garbage configurations
 */
#include <stdint.h>
#include <stdbool.h>
#include <string.h>
#include "qfoc/drive_cfg.h"
#include "../harness_util.h"

/* the 1 .. 60000 ms range of most time settings */
static bool ms_ok(uint16_t v)
{
    return (v >= 1u) && (v <= 60000u);
}

/* drive_cfg.h's ranges, written out from the header's field comments */
static bool ref_valid(const qfoc_drive_cfg_t *c)
{
    const bool speed = (c->pole_pairs >= 1u) && (c->pole_pairs <= 16u)
        && (c->k_rpm >= 1u) && (c->k_speed_rpm >= 1u)
        && (c->rpm_min >= 1u) && (c->rpm_min <= c->rpm_max) && (c->speed_ramp >= 1);
    const bool start = ms_ok(c->precharge_ms)
        && (c->offset_shift >= 4u) && (c->offset_shift <= 10u) && (c->offset_window <= 2047u)
        && (c->i_align >= 1) && (c->align_ms >= 2u) && (c->align_ms <= 60000u)
        && (c->i_start >= 1) && (c->of_accel >= 1) && (c->of_speed >= 1)
        && (c->ho_angle >= 1u) && (c->ho_angle <= 16384u)
        && ms_ok(c->ho_dwell_ms) && ms_ok(c->ol_timeout_ms) && (c->cl_hold_ms <= 60000u);
    const bool prot = (c->t_ipm_max >= -400) && (c->t_ipm_max <= 2000)
        && (c->t_pcb_max >= -400) && (c->t_pcb_max <= 2000)
        && (c->vdc_ms >= 1u) && (c->vdc_ms <= 10u) && (c->temp_ms >= 1u) && (c->temp_ms <= 10u)
        && (c->stall_err >= 1) && (c->flux_tol >= 1) && ms_ok(c->stall_ms)
        && (c->phase_alpha >= 1) && (c->phase_i_min >= 1) && (c->phase_ratio >= 0)
        && ms_ok(c->phase_ms) && ms_ok(c->link_timeout_ms) && ms_ok(c->clear_ms);
    const bool feat = (c->fw_level >= 1) && (c->fw_alpha >= 1)
        && (c->tc_gain >= 0) && (c->tc_amp_max >= 0)
        && (c->tc_speed_min >= 0) && (c->tc_speed_min <= c->tc_speed_max)
        && (c->para_speed >= 1) && (c->ld_hs >= 0) && (c->lq_hs >= 0)
        && (c->lin_id_cmd <= 0x3Bu) && (c->lin_id_status <= 0x3Bu)
        && (c->lin_id_status != c->lin_id_cmd)
        && (c->can_id_a <= 0x7FFu) && (c->can_id_b <= 0x7FFu);
    const bool derate = (c->mtpa_speed >= 0)
        && (c->t_ipm_derate >= -400) && (c->t_ipm_derate < c->t_ipm_max)
        && (c->t_pcb_derate >= -400) && (c->t_pcb_derate < c->t_pcb_max)
        && (c->rpm_derate >= c->rpm_min) && (c->rpm_derate <= c->rpm_max)
        && (c->flux_band >= 1) && (c->flux_v_err >= 0) && (c->flux_r_err >= 0)
        && (c->psi_shift <= QFOC_DRIVE_PSI_SHIFT_MAX)
        && (c->ho_retries <= QFOC_DRIVE_HO_RETRIES_MAX);
    const bool sense = (c->sensing <= 1u) && (c->shunt_sample >= 1u)
        && (c->shunt_hold >= 1u) && (c->shunt_hold <= 16u);
    return speed && start && prot && feat && derate && sense;
}

int main(void)
{
    qfoc_drive_cfg_t c;
    qfoc_drive_cfg_t before;
    bool valid;

    __CPROVER_havoc_object(&c);
    before = c;
    valid = qfoc_drive_cfg_is_valid(&c);
    __CPROVER_assert(valid == ref_valid(&c), "range check as specified");
    __CPROVER_assert(memcmp(&c, &before, sizeof c) == 0, "configuration unchanged");
    return 0;
}
