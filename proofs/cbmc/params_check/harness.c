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
 *    params.h written out here;
 *  - the status: OK only for a known, in-range table; ERR_RANGE only for a known
 *    table out of range; ERR_CRC only for a known table; nothing else;
 *  - load: returns OK only for a known, in-range table; the RAM copy equals the
 *    table on OK and is untouched otherwise.
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

/* params.h's ranges, written out from the header's documentation */
static bool ref_valid(const qfoc_param_table_t *t)
{
    return (t->f_pwm_hz >= 1000u) && (t->f_pwm_hz <= 40000u)
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
        && (t->vdc_uv >= 1) && (t->vdc_uv < t->vdc_ov) && (t->v_max >= 1)
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
