/**
 * @file qfoc_fw.c
 * @brief Field-weakening loop (see include/qfoc/fw.h).
 *
 * Requirements: REQ-FW-001 .. REQ-FW-006 (specs/requirements/fw.md).
 */
#include "qfoc/fw.h"
#include "qfoc/q15.h"

/** Safe filter coefficient after a rejected init: 32767 / 32768 = 0.99997. */
#define QFOC_FW_ALPHA_SAFE ((qfoc_q15_t)32767)
/** Safe level after a rejected init: 32767 / 32768 = 0.99997 (never reached
    with the safe PI limits [0, 0] the output is 0 anyway). */
#define QFOC_FW_LEVEL_SAFE ((qfoc_q15_t)32767)
/** Largest filter state: 32767 x 65536 (Q15 1.0 widened to Q31). */
#define QFOC_FW_STATE_MAX ((qfoc_q31_t)2147418112)

/**
 * @brief Store valid parameters and clear the state (shared by both outcomes of
 *        qfoc_fw_init()).
 */
/*@
  requires valid_fw: \valid(fw);
  requires valid_pi: \valid_read(pi);
  requires sep: \separated(fw, pi);
  requires pi_ok: PiParamsValid(pi) && pi->out_max == 0;
  requires scalars: 1 <= alpha && 1 <= level;
  assigns *fw;
  ensures valid: FwValid(fw);
  ensures cleared: fw->id_ref == 0 && fw->pi.integ == 0 && fw->util_lpf.state == 0 &&
                   fw->pi.limited == \false;
  ensures gains: fw->pi.params.kp == pi->kp && fw->pi.params.kp_shift == pi->kp_shift &&
                 fw->pi.params.ki == pi->ki && fw->pi.params.ki_shift == pi->ki_shift;
  ensures limits: fw->pi.params.out_min == pi->out_min && fw->pi.params.out_max == 0;
  ensures level: fw->level == level && fw->util_lpf.alpha == alpha;
*/
static void qfoc_fw_store(qfoc_fw_t *fw, const qfoc_pi_params_t *pi, qfoc_q15_t alpha,
                          qfoc_q15_t level)
{
    fw->pi.params.kp = pi->kp;
    fw->pi.params.kp_shift = pi->kp_shift;
    fw->pi.params.ki = pi->ki;
    fw->pi.params.ki_shift = pi->ki_shift;
    fw->pi.params.out_min = pi->out_min;
    fw->pi.params.out_max = pi->out_max;
    /* cleared state: integrator 0 (inside [out_min, 0]), filter 0, reference 0 */
    fw->pi.integ = 0;
    fw->pi.limited = false;
    fw->util_lpf.alpha = alpha;
    fw->util_lpf.state = 0;
    fw->level = level;
    fw->id_ref = 0;
}

/**
 * @brief Release: i_d reference, filter and integrator 0 (qfoc_fw_reset() and
 *        qfoc_fw_step() with enable false).
 */
/*@
  requires valid_fw: \valid(fw);
  requires fw_valid: FwValid(fw);
  assigns fw->pi.integ, fw->pi.limited, fw->util_lpf.state, fw->id_ref;
  ensures valid: FwValid(fw);
  ensures cleared: fw->id_ref == 0 && fw->pi.integ == 0 && fw->util_lpf.state == 0 &&
                   fw->pi.limited == \false;
*/
static void qfoc_fw_release(qfoc_fw_t *fw)
{
    /* out_min <= 0 = out_max: the preset 0 is inside the limits, integrator 0 */
    qfoc_pi_reset(&fw->pi, 0);
    qfoc_lpf_reset(&fw->util_lpf, 0);
    fw->id_ref = 0;
}

/* cppcheck-suppress misra-c2012-8.7 ; DEV-002 */
bool qfoc_fw_params_is_valid(const qfoc_fw_params_t *p)
{
    bool ok = false;
    if (qfoc_pi_params_is_valid(&p->pi) && (p->pi.out_max == 0) && (p->level > 0)
        && (p->alpha > 0)) {
        ok = true;
    } else {
        /* invalid PI, positive upper limit, or non-positive level / alpha */
    }
    return ok;
}

bool qfoc_fw_is_valid(const qfoc_fw_t *fw)
{
    bool ok = false;
    if (qfoc_pi_is_valid(&fw->pi) && (fw->pi.params.out_max == 0)
        && qfoc_lpf_is_valid(&fw->util_lpf) && (fw->util_lpf.state >= 0)
        && (fw->util_lpf.state <= QFOC_FW_STATE_MAX) && (fw->level > 0)
        && (fw->id_ref >= fw->pi.params.out_min) && (fw->id_ref <= 0)) {
        ok = true;
    } else {
        /* some part out of its invariant */
    }
    return ok;
}

int32_t qfoc_fw_init(qfoc_fw_t *fw, const qfoc_fw_params_t *p)
{
    /* safe PI parameters after a rejected init: zero gains, limits [0, 0] */
    static const qfoc_pi_params_t qfoc_fw_pi_safe = { 0, 0u, 0, 0u, 0, 0 };
    int32_t status;
    if (qfoc_fw_params_is_valid(p)) {
        qfoc_fw_store(fw, &p->pi, p->alpha, p->level);
        status = QFOC_FW_OK;
    } else {
        /* safe state: zero gains, limits [0, 0]: the output stays 0 */
        qfoc_fw_store(fw, &qfoc_fw_pi_safe, QFOC_FW_ALPHA_SAFE, QFOC_FW_LEVEL_SAFE);
        status = QFOC_FW_ERR_PARAM;
    }
    return status;
}

void qfoc_fw_reset(qfoc_fw_t *fw)
{
    qfoc_fw_release(fw);
}

qfoc_q15_t qfoc_fw_step(qfoc_fw_t *fw, qfoc_q15_t utilisation, bool enable)
{
    if (enable) {
        qfoc_q15_t u = utilisation;
        qfoc_q15_t util_f;
        qfoc_q15_t err;
        if (u < 0) {
            /* a utilisation is a magnitude: a negative value is read as 0 */
            u = 0;
        }
        /* filtered utilisation, Q15, in [0, 32767] (filter state stays >= 0) */
        util_f = qfoc_lpf_step(&fw->util_lpf, u);
        /* e = FWK_LVL - util_f in [-32766, 32767] */
        err = qfoc_q15_sub(fw->level, util_f);
        /* i_d reference, limited to [out_min, 0] by the PI */
        fw->id_ref = qfoc_pi_step(&fw->pi, err);
    } else {
        /* release (E2-46: i_d reference 0, filter output 0) and integrator 0 */
        qfoc_fw_release(fw);
    }
    return fw->id_ref;
}
