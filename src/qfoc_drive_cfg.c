/**
 * @file qfoc_drive_cfg.c
 * @brief Drive configuration: range check (drive_cfg.h).
 *
 * Four group checks, each with its own contract (specs/drive_cfg.acsl), combined with
 * every call made unconditionally (one path).  Comparisons only: every field is
 * compared in its own essential type against a constant of drive_cfg.h.
 */
#include "qfoc/drive_cfg.h"

/* speed scaling and targets (REQ-DCFG-001) */
/*@ requires valid_c: \valid_read(c);
    assigns \nothing;
    ensures result: \result <==> DriveCfgSpeedOk(c); */
static bool qfoc_drive_cfg_speed_ok(const qfoc_drive_cfg_t *c)
{
    return (c->pole_pairs >= 1u) && (c->pole_pairs <= QFOC_DRIVE_POLE_PAIRS_MAX)
           && (c->k_rpm >= 1u) && (c->k_speed_rpm >= 1u)
           && (c->rpm_min >= 1u) && (c->rpm_min <= c->rpm_max)
           && (c->speed_ramp >= 1);
}

/* start-up sequence (REQ-DCFG-002) */
/*@ requires valid_c: \valid_read(c);
    assigns \nothing;
    ensures result: \result <==> DriveCfgStartOk(c); */
static bool qfoc_drive_cfg_start_ok(const qfoc_drive_cfg_t *c)
{
    const bool calib = (c->precharge_ms >= 1u) && (c->precharge_ms <= QFOC_DRIVE_MS_MAX)
                       && (c->offset_shift >= QFOC_DRIVE_OFFSET_SHIFT_MIN)
                       && (c->offset_shift <= QFOC_DRIVE_OFFSET_SHIFT_MAX)
                       && (c->offset_window <= QFOC_DRIVE_OFFSET_WINDOW_MAX);
    const bool align = (c->i_align >= 1) && (c->align_ms >= 2u)
                       && (c->align_ms <= QFOC_DRIVE_MS_MAX);
    const bool open_loop = (c->i_start >= 1) && (c->of_accel >= 1) && (c->of_speed >= 1);
    const bool handover = (c->ho_angle >= 1u) && (c->ho_angle <= QFOC_DRIVE_HO_ANGLE_MAX)
                          && (c->ho_dwell_ms >= 1u) && (c->ho_dwell_ms <= QFOC_DRIVE_MS_MAX)
                          && (c->ol_timeout_ms >= 1u) && (c->ol_timeout_ms <= QFOC_DRIVE_MS_MAX)
                          && (c->cl_hold_ms <= QFOC_DRIVE_MS_MAX);
    return calib && align && open_loop && handover;
}

/* protection thresholds and debounce times (REQ-DCFG-003) */
/*@ requires valid_c: \valid_read(c);
    assigns \nothing;
    ensures result: \result <==> DriveCfgProtOk(c); */
static bool qfoc_drive_cfg_prot_ok(const qfoc_drive_cfg_t *c)
{
    const bool temp = (c->t_ipm_max >= QFOC_DRIVE_TEMP_MIN) && (c->t_ipm_max <= QFOC_DRIVE_TEMP_MAX)
                      && (c->t_pcb_max >= QFOC_DRIVE_TEMP_MIN)
                      && (c->t_pcb_max <= QFOC_DRIVE_TEMP_MAX)
                      && (c->vdc_ms >= 1u) && (c->vdc_ms <= QFOC_DRIVE_DEBOUNCE_MAX)
                      && (c->temp_ms >= 1u) && (c->temp_ms <= QFOC_DRIVE_DEBOUNCE_MAX);
    const bool stall = (c->stall_err >= 1) && (c->flux_tol >= 1)
                       && (c->stall_ms >= 1u) && (c->stall_ms <= QFOC_DRIVE_MS_MAX);
    const bool phase = (c->phase_alpha >= 1) && (c->phase_i_min >= 1) && (c->phase_ratio >= 0)
                       && (c->phase_ms >= 1u) && (c->phase_ms <= QFOC_DRIVE_MS_MAX);
    const bool times = (c->link_timeout_ms >= 1u) && (c->link_timeout_ms <= QFOC_DRIVE_MS_MAX)
                       && (c->clear_ms >= 1u) && (c->clear_ms <= QFOC_DRIVE_MS_MAX);
    return temp && stall && phase && times;
}

/* field weakening, torque compensation, parameter change, link identifiers (REQ-DCFG-004) */
/*@ requires valid_c: \valid_read(c);
    assigns \nothing;
    ensures result: \result <==> DriveCfgFeatOk(c); */
static bool qfoc_drive_cfg_feat_ok(const qfoc_drive_cfg_t *c)
{
    const bool ctrl = (c->fw_level >= 1) && (c->fw_alpha >= 1)
                      && (c->tc_gain >= 0) && (c->tc_amp_max >= 0)
                      && (c->tc_speed_min >= 0) && (c->tc_speed_min <= c->tc_speed_max)
                      && (c->para_speed >= 1) && (c->ld_hs >= 0) && (c->lq_hs >= 0);
    const bool ids = (c->lin_id_cmd <= QFOC_DRIVE_LIN_ID_MAX)
                     && (c->lin_id_status <= QFOC_DRIVE_LIN_ID_MAX)
                     && (c->lin_id_status != c->lin_id_cmd)
                     && (c->can_id_a <= QFOC_DRIVE_CAN_ID_MAX)
                     && (c->can_id_b <= QFOC_DRIVE_CAN_ID_MAX);
    return ctrl && ids;
}

/* MTPA speed, derating windows, the flux check's error model, the flux base, the start
   retries (REQ-DCFG-005); a window's
   start below its trip temperature bounds it above by QFOC_DRIVE_TEMP_MAX */
/*@ requires valid_c: \valid_read(c);
    assigns \nothing;
    ensures result: \result <==> DriveCfgDerateOk(c); */
static bool qfoc_drive_cfg_derate_ok(const qfoc_drive_cfg_t *c)
{
    const bool window = (c->t_ipm_derate >= QFOC_DRIVE_TEMP_MIN) && (c->t_ipm_derate < c->t_ipm_max)
                        && (c->t_pcb_derate >= QFOC_DRIVE_TEMP_MIN)
                        && (c->t_pcb_derate < c->t_pcb_max)
                        && (c->rpm_derate >= c->rpm_min) && (c->rpm_derate <= c->rpm_max);
    const bool model = (c->mtpa_speed >= 0) && (c->flux_band >= 1) && (c->flux_v_err >= 0)
                       && (c->flux_r_err >= 0) && (c->psi_shift <= QFOC_DRIVE_PSI_SHIFT_MAX)
                       && (c->ho_retries <= QFOC_DRIVE_HO_RETRIES_MAX);
    return window && model;
}

/* the current sensing mode, the single shunt's sample-and-hold and hold (REQ-DCFG-006) */
/*@ requires valid_c: \valid_read(c);
    assigns \nothing;
    ensures result: \result <==> DriveCfgSenseOk(c); */
static bool qfoc_drive_cfg_sense_ok(const qfoc_drive_cfg_t *c)
{
    const bool mode = (c->sensing == QFOC_SENSING_PHASES) || (c->sensing == QFOC_SENSING_SHUNT);
    return mode && (c->shunt_sample >= 1u) && (c->shunt_hold >= 1u)
           && (c->shunt_hold <= QFOC_DRIVE_SHUNT_HOLD_MAX);
}

/* public interface; qfoc_params_is_valid() (params.h) calls it for the table's drive field */
bool qfoc_drive_cfg_is_valid(const qfoc_drive_cfg_t *c)
{
    const bool speed = qfoc_drive_cfg_speed_ok(c);
    const bool start = qfoc_drive_cfg_start_ok(c);
    const bool prot = qfoc_drive_cfg_prot_ok(c);
    const bool feat = qfoc_drive_cfg_feat_ok(c);
    const bool derate = qfoc_drive_cfg_derate_ok(c);
    const bool sense = qfoc_drive_cfg_sense_ok(c);
    return speed && start && prot && feat && derate && sense;
}
