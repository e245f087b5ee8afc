/**
 * @file eva_all_tables.c
 * @brief Whole-program abstract interpretation of the drive (Frama-C EVA) over every
 *        parameter table the drive accepts: every field of the table (the CRC included)
 *        any value of its type, kept where the table is accepted, then qfoc_drive_init()
 *        and, on the path where it returned QFOC_PARAMS_OK, fast steps and ticks with
 *        every input over its full range, in any number and order, as
 *        proofs/eva/eva_main.c does for the reference table (tools/gates/eva.sh, eva-all).
 *
 * What makes the analysis tractable (the reduction), and why it is sound:
 *  1. The table is filtered before qfoc_drive_init() by eva_table_ok(): the identity
 *     (ParamsIdOk) and each group of ParamsValid (specs/params.acsl) tested condition by
 *     condition, one function per group.  EVA cannot reduce the table's fields from the
 *     boolean that qfoc_params_check() returns (the fields are tested in callees, the
 *     verdict is a value); tested here, each condition reduces the fields on the path
 *     where it holds, and -eva-split-return-function (with a slevel of 50 inside each
 *     filter function) keeps the accepted states apart from the refused ones.  The filter
 *     leaves out no accepted table: eva_table_ok() returns true exactly when ParamsIdOk
 *     and ParamsValid hold (its contract and those of the group functions, proved by WP
 *     in tools/gates/eva.sh before the analysis runs), and qfoc_params_check() returns
 *     QFOC_PARAMS_OK only when they hold (its contract, proved by make prove).  The
 *     library itself still checks the filtered table (qfoc_drive_init() calls
 *     qfoc_params_check(), CRC included), and only its QFOC_PARAMS_OK path is followed.
 *  2. Only the interval of each field is kept, not the relations between fields
 *     (i_max <= i_trip, out_min <= out_max, rpm_min <= rpm_max, ...): the analysed set
 *     of tables contains every accepted table, and more.
 *  3. qfoc_mech_scale (src/qfoc_trqcomp.c) is analysed by its contract
 *     (-eva-use-spec): its quotient is below 65536 because turn < pole_pairs, a relation
 *     with the reciprocal ceil(2^28 / pole_pairs) that intervals lose when pole_pairs
 *     ranges over 1 .. 16; the contract is proved by WP with every runtime-error check
 *     (make prove), and the function reads *m only.  qfoc_isqrt32 likewise, as in
 *     eva_main.c.
 * The tables the drive refuses are outside this analysis: with one, qfoc_drive_init()
 * puts the drive in ERROR (the invariant of the drive, and the absence of runtime
 * errors, are proved by WP for any table).
 */
#include "qfoc/drive.h"

volatile uint32_t eva_u32;     /* any value, read anew at each access */
volatile uint16_t eva_u16;
volatile int16_t eva_i16;
volatile uint8_t eva_u8;

static qfoc_param_table_t table;
static qfoc_drive_t drive;

/* a PI parameter block, every field any value of its type */
static void eva_pi(qfoc_pi_params_t *p)
{
    p->kp = eva_i16;
    p->kp_shift = eva_u8;
    p->ki = eva_i16;
    p->ki_shift = eva_u8;
    p->out_min = eva_i16;
    p->out_max = eva_i16;
}

/* the drive configuration, every field any value of its type */
static void eva_drive_cfg(qfoc_drive_cfg_t *c)
{
    c->pole_pairs = eva_u8;
    c->k_rpm = eva_u16;
    c->k_speed_rpm = eva_u16;
    c->rpm_min = eva_u16;
    c->rpm_max = eva_u16;
    c->speed_ramp = eva_i16;
    c->precharge_ms = eva_u16;
    c->offset_shift = eva_u8;
    c->offset_window = eva_u16;
    c->i_align = eva_i16;
    c->align_ms = eva_u16;
    c->i_start = eva_i16;
    c->of_accel = eva_i16;
    c->of_speed = eva_i16;
    c->ho_angle = eva_u16;
    c->ho_dwell_ms = eva_u16;
    c->ol_timeout_ms = eva_u16;
    c->cl_hold_ms = eva_u16;
    c->t_ipm_max = eva_i16;
    c->t_pcb_max = eva_i16;
    c->vdc_ms = eva_u16;
    c->temp_ms = eva_u16;
    c->stall_err = eva_i16;
    c->flux_tol = eva_i16;
    c->stall_ms = eva_u16;
    c->phase_alpha = eva_i16;
    c->phase_i_min = eva_i16;
    c->phase_ratio = eva_i16;
    c->phase_ms = eva_u16;
    c->link_timeout_ms = eva_u16;
    c->clear_ms = eva_u16;
    c->fw_level = eva_i16;
    c->fw_alpha = eva_i16;
    c->tc_gain = eva_i16;
    c->tc_amp_max = eva_i16;
    c->tc_speed_min = eva_i16;
    c->tc_speed_max = eva_i16;
    c->para_speed = eva_i16;
    c->ld_hs = eva_i16;
    c->lq_hs = eva_i16;
    c->lin_id_cmd = eva_u8;
    c->lin_id_status = eva_u8;
    c->can_id_a = eva_u16;
    c->can_id_b = eva_u16;
    c->mtpa_speed = eva_i16;
    c->t_ipm_derate = eva_i16;
    c->t_pcb_derate = eva_i16;
    c->rpm_derate = eva_u16;
    c->flux_band = eva_i16;
    c->flux_v_err = eva_i16;
    c->flux_r_err = eva_i16;
    c->psi_shift = eva_u8;
    c->ho_retries = eva_u8;
    c->sensing = eva_u8;
    c->shunt_settle = eva_u16;
    c->shunt_sample = eva_u16;
    c->shunt_hold = eva_u16;
}

/* the whole table, every field any value of its type */
static void eva_table(qfoc_param_table_t *t)
{
    t->magic = eva_u32;
    t->version = eva_u16;
    t->f_pwm_hz = eva_u16;
    t->v_base_mv = eva_u32;
    t->i_base_ma = eva_u32;
    t->f_base_mhz = eva_u32;
    t->svpwm.period = eva_u16;
    t->svpwm.dt_comp = eva_u16;
    t->svpwm.i_deadband = eva_i16;
    t->svpwm.vdc_min = eva_i16;
    eva_pi(&t->pi_id);
    eva_pi(&t->pi_iq);
    eva_pi(&t->pi_speed);
    eva_pi(&t->pi_fw);
    t->flux.gain = eva_i16;
    t->flux.gain_shift = eva_u8;
    t->flux.r = eva_i16;
    t->flux.l = eva_i16;
    t->flux.kg = eva_i16;
    eva_pi(&t->pll.pi);
    t->pll.err_clamp = eva_i16;
    t->pll.mag_min = eva_i16;
    t->pll.k_theta = eva_u16;
    t->pll.speed_alpha = eva_i16;
    t->alpha_vdc = eva_i16;
    t->ld = eva_i16;
    t->lq = eva_i16;
    t->psi_f = eva_i16;
    t->i_max = eva_i16;
    t->i_trip = eva_i16;
    t->speed_max = eva_i16;
    t->vdc_uv = eva_i16;
    t->vdc_ov = eva_i16;
    t->v_max = eva_i16;
    eva_drive_cfg(&t->drive);
    t->crc = eva_u32;
}

/* The table accepted by the drive, group by group: identity (ParamsIdOk) and every
   range of ParamsValid (specs/params.acsl and the predicates it uses).  Each group is a
   function whose contract states that it is exactly its predicate (proved by WP, in
   tools/gates/eva.sh before the analysis); each condition is a test of its own, so that
   EVA reduces the table's fields on the path where the group holds, and the
   accepted and the refused states of each group are kept apart at its return
   (-eva-split-return-function).  No table that qfoc_params_check() accepts is left out
   of the analysis. */

/*@
  requires valid_t: \valid_read(t);
  assigns \nothing;
  ensures ok: \result != 0 <==> ParamsScalingOk(t);
*/
static bool eva_scaling_ok(const qfoc_param_table_t *t)
{
    return (t->f_pwm_hz >= QFOC_PARAMS_F_PWM_MIN) && (t->f_pwm_hz <= QFOC_PARAMS_F_PWM_MAX)
           && (t->v_base_mv > 0u) && (t->i_base_ma > 0u) && (t->f_base_mhz > 0u);
}

/*@
  requires valid_s: \valid_read(s);
  assigns \nothing;
  ensures ok: \result != 0 <==> SvpwmCfgValid(s->period, s->dt_comp, s->i_deadband,
                                                s->vdc_min);
*/
static bool eva_svpwm_ok(const qfoc_svpwm_cfg_t *s)
{
    return (s->period >= 100u) && (s->period <= 32767u) && (s->dt_comp <= (s->period / 4u))
           && (s->i_deadband >= 0) && (s->vdc_min > 0);
}

/*@
  requires valid_p: \valid_read(p);
  assigns \nothing;
  ensures ok: \result != 0 <==> PiParamsValid(p);
*/
static bool eva_pi_ok(const qfoc_pi_params_t *p)
{
    return (p->kp >= 0) && (p->kp_shift <= 15u) && (p->ki >= 0) && (p->ki_shift <= 15u)
           && (p->out_min >= -32767) && (p->out_min <= p->out_max);
}

/*@
  requires valid_f: \valid_read(f);
  assigns \nothing;
  ensures ok: \result != 0 <==> FluxParamsValid(f);
*/
static bool eva_flux_ok(const qfoc_flux_params_t *f)
{
    return (f->gain >= 0) && (f->gain_shift <= 15u) && (f->r >= 0) && (f->l >= 0)
           && (f->kg >= 0);
}

/*@
  requires valid_p: \valid_read(p);
  assigns \nothing;
  ensures ok: \result != 0 <==> (p->err_clamp >= 1 && p->mag_min >= 1 &&
                                  1 <= p->k_theta <= 32767 && p->speed_alpha >= 1);
*/
static bool eva_pll_ok(const qfoc_pll_params_t *p)
{
    return (p->err_clamp >= 1) && (p->mag_min >= 1) && (p->k_theta >= 1u)
           && (p->k_theta <= 32767u) && (p->speed_alpha >= 1);
}

/*@
  requires valid_t: \valid_read(t);
  assigns \nothing;
  ensures ok: \result != 0 <==> ParamsLimitsOk(t);
*/
static bool eva_limits_ok(const qfoc_param_table_t *t)
{
    const int32_t i_max = (int32_t)t->i_max;
    return (t->alpha_vdc >= 1) && (t->ld >= 0) && (t->lq >= 0) && (t->psi_f >= 0)
           && (t->i_max >= 1) && (t->i_trip >= t->i_max) && (t->speed_max >= 1)
           && (t->vdc_uv >= 1) && (t->vdc_ov > t->vdc_uv)
           && (t->vdc_ov < QFOC_PARAMS_VDC_READ_MAX) && (t->v_max >= 1)
           && ((int32_t)t->pi_speed.out_min >= -i_max) && (t->pi_speed.out_max <= t->i_max)
           && ((int32_t)t->pi_fw.out_min >= -i_max) && (t->pi_fw.out_max <= 0);
}

/*@
  requires valid_c: \valid_read(c);
  assigns \nothing;
  ensures ok: \result != 0 <==> DriveCfgSpeedOk(c);
*/
static bool eva_cfg_speed_ok(const qfoc_drive_cfg_t *c)
{
    return (c->pole_pairs >= 1u) && (c->pole_pairs <= QFOC_DRIVE_POLE_PAIRS_MAX)
           && (c->k_rpm >= 1u) && (c->k_speed_rpm >= 1u) && (c->rpm_min >= 1u)
           && (c->rpm_max >= c->rpm_min) && (c->speed_ramp >= 1);
}

/*@
  requires valid_c: \valid_read(c);
  assigns \nothing;
  ensures ok: \result != 0 <==> DriveCfgStartOk(c);
*/
static bool eva_cfg_start_ok(const qfoc_drive_cfg_t *c)
{
    return (c->precharge_ms >= 1u) && (c->precharge_ms <= QFOC_DRIVE_MS_MAX)
           && (c->offset_shift >= QFOC_DRIVE_OFFSET_SHIFT_MIN)
           && (c->offset_shift <= QFOC_DRIVE_OFFSET_SHIFT_MAX)
           && (c->offset_window <= QFOC_DRIVE_OFFSET_WINDOW_MAX) && (c->i_align >= 1)
           && (c->align_ms >= 2u) && (c->align_ms <= QFOC_DRIVE_MS_MAX)
           && (c->i_start >= 1) && (c->of_accel >= 1) && (c->of_speed >= 1)
           && (c->ho_angle >= 1u) && (c->ho_angle <= QFOC_DRIVE_HO_ANGLE_MAX)
           && (c->ho_dwell_ms >= 1u) && (c->ho_dwell_ms <= QFOC_DRIVE_MS_MAX)
           && (c->ol_timeout_ms >= 1u) && (c->ol_timeout_ms <= QFOC_DRIVE_MS_MAX)
           && (c->cl_hold_ms <= QFOC_DRIVE_MS_MAX);
}

/*@
  requires valid_c: \valid_read(c);
  assigns \nothing;
  ensures ok: \result != 0 <==> DriveCfgProtOk(c);
*/
static bool eva_cfg_prot_ok(const qfoc_drive_cfg_t *c)
{
    return (c->t_ipm_max >= QFOC_DRIVE_TEMP_MIN) && (c->t_ipm_max <= QFOC_DRIVE_TEMP_MAX)
           && (c->t_pcb_max >= QFOC_DRIVE_TEMP_MIN) && (c->t_pcb_max <= QFOC_DRIVE_TEMP_MAX)
           && (c->vdc_ms >= 1u) && (c->vdc_ms <= QFOC_DRIVE_DEBOUNCE_MAX)
           && (c->temp_ms >= 1u) && (c->temp_ms <= QFOC_DRIVE_DEBOUNCE_MAX)
           && (c->stall_err >= 1) && (c->flux_tol >= 1)
           && (c->stall_ms >= 1u) && (c->stall_ms <= QFOC_DRIVE_MS_MAX)
           && (c->phase_alpha >= 1) && (c->phase_i_min >= 1) && (c->phase_ratio >= 0)
           && (c->phase_ms >= 1u) && (c->phase_ms <= QFOC_DRIVE_MS_MAX)
           && (c->link_timeout_ms >= 1u) && (c->link_timeout_ms <= QFOC_DRIVE_MS_MAX)
           && (c->clear_ms >= 1u) && (c->clear_ms <= QFOC_DRIVE_MS_MAX);
}

/*@
  requires valid_c: \valid_read(c);
  assigns \nothing;
  ensures ok: \result != 0 <==> DriveCfgFeatOk(c);
*/
static bool eva_cfg_feat_ok(const qfoc_drive_cfg_t *c)
{
    return (c->fw_level >= 1) && (c->fw_alpha >= 1) && (c->tc_gain >= 0)
           && (c->tc_amp_max >= 0) && (c->tc_speed_min >= 0)
           && (c->tc_speed_max >= c->tc_speed_min) && (c->para_speed >= 1)
           && (c->ld_hs >= 0) && (c->lq_hs >= 0)
           && (c->lin_id_cmd <= QFOC_DRIVE_LIN_ID_MAX)
           && (c->lin_id_status <= QFOC_DRIVE_LIN_ID_MAX)
           && (c->lin_id_status != c->lin_id_cmd)
           && (c->can_id_a <= QFOC_DRIVE_CAN_ID_MAX) && (c->can_id_b <= QFOC_DRIVE_CAN_ID_MAX);
}

/*@
  requires valid_c: \valid_read(c);
  assigns \nothing;
  ensures ok: \result != 0 <==> DriveCfgDerateOk(c);
*/
static bool eva_cfg_derate_ok(const qfoc_drive_cfg_t *c)
{
    return (c->mtpa_speed >= 0) && (c->t_ipm_derate >= QFOC_DRIVE_TEMP_MIN)
           && (c->t_ipm_derate < c->t_ipm_max) && (c->t_pcb_derate >= QFOC_DRIVE_TEMP_MIN)
           && (c->t_pcb_derate < c->t_pcb_max) && (c->rpm_derate >= c->rpm_min)
           && (c->rpm_derate <= c->rpm_max) && (c->flux_band >= 1) && (c->flux_v_err >= 0)
           && (c->flux_r_err >= 0) && (c->psi_shift <= QFOC_DRIVE_PSI_SHIFT_MAX)
           && (c->ho_retries <= QFOC_DRIVE_HO_RETRIES_MAX);
}

/*@
  requires valid_c: \valid_read(c);
  assigns \nothing;
  ensures ok: \result != 0 <==> DriveCfgSenseOk(c);
*/
static bool eva_cfg_sense_ok(const qfoc_drive_cfg_t *c)
{
    return ((c->sensing == QFOC_SENSING_PHASES) || (c->sensing == QFOC_SENSING_SHUNT))
           && (c->shunt_sample >= 1u) && (c->shunt_hold >= 1u)
           && (c->shunt_hold <= QFOC_DRIVE_SHUNT_HOLD_MAX);
}

/*@
  requires valid_t: \valid_read(t);
  assigns \nothing;
  ensures ok: \result != 0 <==> ParamsDriveCrossOk(t);
*/
static bool eva_cross_ok(const qfoc_param_table_t *t)
{
    const qfoc_drive_cfg_t *const c = &t->drive;
    const uint32_t rpm_max = (uint32_t)c->rpm_max;
    const uint32_t k_rpm = (uint32_t)c->k_rpm;
    uint32_t prod;

    /*@ assert prod_bound: rpm_max * k_rpm <= 65535 * 65535; */
    prod = rpm_max * k_rpm;
    return (c->i_align <= t->i_max) && (c->i_start <= t->i_max)
           && (c->tc_amp_max <= t->i_max) && (c->of_speed <= t->speed_max)
           && ((int32_t)((prod + 2048u) / 4096u) <= (int32_t)t->speed_max)
           && ((4u * ((uint32_t)c->shunt_settle + (uint32_t)c->shunt_sample))
               <= (uint32_t)t->svpwm.period);
}

/*@
  requires valid_t: \valid_read(t);
  assigns \nothing;
  ensures accepted: \result != 0 <==> (ParamsIdOk(t) && ParamsValid(t));
*/
static bool eva_table_ok(const qfoc_param_table_t *t)
{
    return (t->magic == QFOC_PARAMS_MAGIC) && (t->version == QFOC_PARAMS_VERSION)
           && eva_scaling_ok(t) && eva_svpwm_ok(&t->svpwm)
           && eva_pi_ok(&t->pi_id) && eva_pi_ok(&t->pi_iq) && eva_pi_ok(&t->pi_speed)
           && eva_pi_ok(&t->pi_fw) && eva_flux_ok(&t->flux) && eva_pi_ok(&t->pll.pi)
           && eva_pll_ok(&t->pll) && eva_limits_ok(t) && eva_cfg_speed_ok(&t->drive)
           && eva_cfg_start_ok(&t->drive) && eva_cfg_prot_ok(&t->drive)
           && eva_cfg_feat_ok(&t->drive) && eva_cfg_derate_ok(&t->drive)
           && eva_cfg_sense_ok(&t->drive) && eva_cross_ok(t);
}

int main(void)
{
    eva_table(&table);
    if (eva_table_ok(&table) && (qfoc_drive_init(&drive, &table) == QFOC_PARAMS_OK)) {
        /* the table was accepted: any number of calls, in any order (eva_main.c) */
        while (eva_u8 != 0u) {
            if (eva_u8 != 0u) {
                qfoc_adc_t adc;
                adc.iu = eva_u16;
                adc.iv = eva_u16;
                adc.vdc = eva_u16;
                (void)qfoc_drive_fast_step(&drive, &adc);
            } else {
                qfoc_tick_in_t in;
                uint8_t rx[QFOC_LIN_FRAME_MAX];
                uint32_t j;
                for (j = 0u; j < QFOC_LIN_FRAME_MAX; j++) {
                    rx[j] = eva_u8;
                }
                in.t_ipm = eva_i16;
                in.t_pcb = eva_i16;
                in.rx = rx;
                in.rx_len = (uint8_t)(eva_u8 % (QFOC_LIN_FRAME_MAX + 1u));
                (void)qfoc_drive_tick(&drive, &in);
            }
        }
    }
    return 0;
}
