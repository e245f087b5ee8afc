/**
 * @file tt_groups.c
 * @brief Replay of every golden-vector group (tt.h): the calls, and what each digest holds.
 *
 * The same code runs on the host, where it computes the expected digests (tt_gen.c),
 * and on the target, where it recomputes them with the target build of the library
 * (tt_runner.c).  Each function below documents its vector layout (words) and its
 * digest (fields, in order).  Stateful blocks: word 0 is the operation (TT_OP_*); the
 * block is zeroed before each init, and a step, reset or query runs only while the
 * block's own validity check (qfoc_<x>_is_valid) accepts it, so a rejected init is
 * replayed as such and never followed by a call outside the contract.
 *
 * Requirements: REQ-TGT-001, REQ-TGT-002, REQ-TGT-003.
 */
#include "tt.h"

#include <stddef.h>
#include <string.h>

#include "qfoc/q15.h"
#include "qfoc/trig.h"
#include "qfoc/vector.h"
#include "qfoc/transforms.h"
#include "qfoc/svpwm.h"
#include "qfoc/ramp.h"
#include "qfoc/shunt.h"
#include "qfoc/fault.h"
#include "qfoc/filter.h"
#include "qfoc/pi.h"
#include "qfoc/fw.h"
#include "qfoc/flux.h"
#include "qfoc/pll.h"
#include "qfoc/emf.h"
#include "qfoc/trqcomp.h"
#include "qfoc/link.h"
#include "qfoc/params.h"
#include "qfoc/sm.h"
#include "qfoc/drive.h"
#include "qfoc/drive_shunt.h"
#include "reference_params.h"
#include "reference_shunt_params.h"

/* ------------------------------------------------------------------ digest helpers */

static void tt_d_ab(tt_digest_t *d, const qfoc_ab_t *v)
{
    tt_d_i16(d, v->alpha);
    tt_d_i16(d, v->beta);
}

static void tt_d_dq(tt_digest_t *d, const qfoc_dq_t *v)
{
    tt_d_i16(d, v->d);
    tt_d_i16(d, v->q);
}

static void tt_d_abc(tt_digest_t *d, const qfoc_abc_t *v)
{
    tt_d_i16(d, v->u);
    tt_d_i16(d, v->v);
    tt_d_i16(d, v->w);
}

static void tt_d_lpf(tt_digest_t *d, const qfoc_lpf_t *f)
{
    tt_d_i16(d, f->alpha);
    tt_d_i32(d, f->state);
}

static void tt_d_pi(tt_digest_t *d, const qfoc_pi_t *pi)
{
    tt_d_i16(d, pi->params.kp);
    tt_d_u8(d, pi->params.kp_shift);
    tt_d_i16(d, pi->params.ki);
    tt_d_u8(d, pi->params.ki_shift);
    tt_d_i16(d, pi->params.out_min);
    tt_d_i16(d, pi->params.out_max);
    tt_d_i32(d, pi->integ);
    tt_d_bool(d, pi->limited);
}

static void tt_pi_params(const tt_ctx_t *c, uint32_t k, uint16_t j, qfoc_pi_params_t *p)
{
    p->kp = tt_in_i16(c, k, j);
    p->kp_shift = (uint8_t)tt_in(c, k, (uint16_t)(j + 1u));
    p->ki = tt_in_i16(c, k, (uint16_t)(j + 2u));
    p->ki_shift = (uint8_t)tt_in(c, k, (uint16_t)(j + 3u));
    p->out_min = tt_in_i16(c, k, (uint16_t)(j + 4u));
    p->out_max = tt_in_i16(c, k, (uint16_t)(j + 5u));
}

static void tt_ab_in(const tt_ctx_t *c, uint32_t k, uint16_t j, qfoc_ab_t *v)
{
    v->alpha = tt_in_i16(c, k, j);
    v->beta = tt_in_i16(c, k, (uint16_t)(j + 1u));
}

/* ------------------------------------------------------------------ q15.h primitives */

/* q15_sat: [x low, x high] (int32) -> qfoc_q15_sat(x), 2 bytes. */
static void tt_replay_q15_sat(tt_ctx_t *c)
{
    uint32_t k;
    for (k = 0u; k < c->data->n; k++) {
        tt_digest_t d;
        tt_d_init(&d);
        tt_d_i16(&d, qfoc_q15_sat((int32_t)tt_in_u32(c, k, 0u)));
        tt_emit(c, &d);
    }
}

/* q31_sat: [x words 0..3, little-endian] (int64) -> qfoc_q31_sat(x), 4 bytes. */
static void tt_replay_q31_sat(tt_ctx_t *c)
{
    uint32_t k;
    for (k = 0u; k < c->data->n; k++) {
        tt_digest_t d;
        const uint64_t u = (uint64_t)tt_in_u32(c, k, 0u) | ((uint64_t)tt_in_u32(c, k, 2u) << 32u);
        tt_d_init(&d);
        tt_d_i32(&d, qfoc_q31_sat((int64_t)u));
        tt_emit(c, &d);
    }
}

/* q15_add, q15_sub, q15_mul: [a, b] -> result, 2 bytes; q15_neg, q15_abs: [a]. */
static void tt_replay_q15_add(tt_ctx_t *c)
{
    uint32_t k;
    for (k = 0u; k < c->data->n; k++) {
        tt_digest_t d;
        tt_d_init(&d);
        tt_d_i16(&d, qfoc_q15_add(tt_in_i16(c, k, 0u), tt_in_i16(c, k, 1u)));
        tt_emit(c, &d);
    }
}

static void tt_replay_q15_sub(tt_ctx_t *c)
{
    uint32_t k;
    for (k = 0u; k < c->data->n; k++) {
        tt_digest_t d;
        tt_d_init(&d);
        tt_d_i16(&d, qfoc_q15_sub(tt_in_i16(c, k, 0u), tt_in_i16(c, k, 1u)));
        tt_emit(c, &d);
    }
}

static void tt_replay_q15_neg(tt_ctx_t *c)
{
    uint32_t k;
    for (k = 0u; k < c->data->n; k++) {
        tt_digest_t d;
        tt_d_init(&d);
        tt_d_i16(&d, qfoc_q15_neg(tt_in_i16(c, k, 0u)));
        tt_emit(c, &d);
    }
}

static void tt_replay_q15_abs(tt_ctx_t *c)
{
    uint32_t k;
    for (k = 0u; k < c->data->n; k++) {
        tt_digest_t d;
        tt_d_init(&d);
        tt_d_i16(&d, qfoc_q15_abs(tt_in_i16(c, k, 0u)));
        tt_emit(c, &d);
    }
}

static void tt_replay_q15_mul(tt_ctx_t *c)
{
    uint32_t k;
    for (k = 0u; k < c->data->n; k++) {
        tt_digest_t d;
        tt_d_init(&d);
        tt_d_i16(&d, qfoc_q15_mul(tt_in_i16(c, k, 0u), tt_in_i16(c, k, 1u)));
        tt_emit(c, &d);
    }
}

/* q15_from_q30: [x low, x high] -> 2 bytes. */
static void tt_replay_q15_from_q30(tt_ctx_t *c)
{
    uint32_t k;
    for (k = 0u; k < c->data->n; k++) {
        tt_digest_t d;
        tt_d_init(&d);
        tt_d_i16(&d, qfoc_q15_from_q30((int32_t)tt_in_u32(c, k, 0u)));
        tt_emit(c, &d);
    }
}

/* q31_add: [a low, a high, b low, b high] -> 4 bytes. */
static void tt_replay_q31_add(tt_ctx_t *c)
{
    uint32_t k;
    for (k = 0u; k < c->data->n; k++) {
        tt_digest_t d;
        tt_d_init(&d);
        tt_d_i32(&d, qfoc_q31_add((int32_t)tt_in_u32(c, k, 0u), (int32_t)tt_in_u32(c, k, 2u)));
        tt_emit(c, &d);
    }
}

/* q31_mac: [acc low, acc high, a, b] -> 4 bytes. */
static void tt_replay_q31_mac(tt_ctx_t *c)
{
    uint32_t k;
    for (k = 0u; k < c->data->n; k++) {
        tt_digest_t d;
        tt_d_init(&d);
        tt_d_i32(&d, qfoc_q31_mac((int32_t)tt_in_u32(c, k, 0u), tt_in_i16(c, k, 2u),
                                  tt_in_i16(c, k, 3u)));
        tt_emit(c, &d);
    }
}

/* q15_from_q31: [x low, x high] -> 2 bytes; q31_from_q15: [x] -> 4 bytes. */
static void tt_replay_q15_from_q31(tt_ctx_t *c)
{
    uint32_t k;
    for (k = 0u; k < c->data->n; k++) {
        tt_digest_t d;
        tt_d_init(&d);
        tt_d_i16(&d, qfoc_q15_from_q31((int32_t)tt_in_u32(c, k, 0u)));
        tt_emit(c, &d);
    }
}

static void tt_replay_q31_from_q15(tt_ctx_t *c)
{
    uint32_t k;
    for (k = 0u; k < c->data->n; k++) {
        tt_digest_t d;
        tt_d_init(&d);
        tt_d_i32(&d, qfoc_q31_from_q15(tt_in_i16(c, k, 0u)));
        tt_emit(c, &d);
    }
}

/* ------------------------------------------------------------------ trig.h, vector.h */

/* sin: every angle (width 0) -> qfoc_sin, 2 bytes. */
static void tt_replay_sin(tt_ctx_t *c)
{
    uint32_t k;
    for (k = 0u; k < c->data->n; k++) {
        tt_digest_t d;
        tt_d_init(&d);
        tt_d_i16(&d, qfoc_sin((qfoc_angle_t)(tt_in_index(c, k) & 0xFFFFu)));
        tt_emit(c, &d);
    }
}

/* sincos: every angle (width 0) -> sine, cosine, 4 bytes. */
static void tt_replay_sincos(tt_ctx_t *c)
{
    uint32_t k;
    for (k = 0u; k < c->data->n; k++) {
        tt_digest_t d;
        qfoc_sincos_t sc;
        qfoc_sincos((qfoc_angle_t)(tt_in_index(c, k) & 0xFFFFu), &sc);
        tt_d_init(&d);
        tt_d_i16(&d, sc.sine);
        tt_d_i16(&d, sc.cosine);
        tt_emit(c, &d);
    }
}

/* atan2: [y, x] -> angle, 2 bytes. */
static void tt_replay_atan2(tt_ctx_t *c)
{
    uint32_t k;
    for (k = 0u; k < c->data->n; k++) {
        tt_digest_t d;
        tt_d_init(&d);
        tt_d_u16(&d, qfoc_atan2(tt_in_i16(c, k, 0u), tt_in_i16(c, k, 1u)));
        tt_emit(c, &d);
    }
}

/* isqrt32: [v low, v high] -> floor square root, 4 bytes. */
static void tt_replay_isqrt32(tt_ctx_t *c)
{
    uint32_t k;
    for (k = 0u; k < c->data->n; k++) {
        tt_digest_t d;
        tt_d_init(&d);
        tt_d_u32(&d, qfoc_isqrt32(tt_in_u32(c, k, 0u)));
        tt_emit(c, &d);
    }
}

/* vec_mag: [x, y] -> magnitude, 2 bytes. */
static void tt_replay_vec_mag(tt_ctx_t *c)
{
    uint32_t k;
    for (k = 0u; k < c->data->n; k++) {
        tt_digest_t d;
        tt_d_init(&d);
        tt_d_i16(&d, qfoc_vec_mag(tt_in_i16(c, k, 0u), tt_in_i16(c, k, 1u)));
        tt_emit(c, &d);
    }
}

/* circle_limit: [d, q, vmax] -> out d, out q, limited (hash). */
static void tt_replay_circle_limit(tt_ctx_t *c)
{
    uint32_t k;
    for (k = 0u; k < c->data->n; k++) {
        tt_digest_t d;
        qfoc_dq_t in;
        qfoc_dq_t out;
        bool lim;
        in.d = tt_in_i16(c, k, 0u);
        in.q = tt_in_i16(c, k, 1u);
        lim = qfoc_circle_limit(&in, tt_in_i16(c, k, 2u), &out);
        tt_d_init(&d);
        tt_d_dq(&d, &out);
        tt_d_bool(&d, lim);
        tt_emit(c, &d);
    }
}

/* ------------------------------------------------------------------ transforms.h */

/* clarke: [iu, iv] -> alpha, beta, 4 bytes. */
static void tt_replay_clarke(tt_ctx_t *c)
{
    uint32_t k;
    for (k = 0u; k < c->data->n; k++) {
        tt_digest_t d;
        qfoc_ab_t out;
        qfoc_clarke(tt_in_i16(c, k, 0u), tt_in_i16(c, k, 1u), &out);
        tt_d_init(&d);
        tt_d_ab(&d, &out);
        tt_emit(c, &d);
    }
}

/* park: [alpha, beta, sine, cosine] -> d, q, 4 bytes. */
static void tt_replay_park(tt_ctx_t *c)
{
    uint32_t k;
    for (k = 0u; k < c->data->n; k++) {
        tt_digest_t d;
        qfoc_ab_t in;
        qfoc_sincos_t sc;
        qfoc_dq_t out;
        tt_ab_in(c, k, 0u, &in);
        sc.sine = tt_in_i16(c, k, 2u);
        sc.cosine = tt_in_i16(c, k, 3u);
        qfoc_park(&in, &sc, &out);
        tt_d_init(&d);
        tt_d_dq(&d, &out);
        tt_emit(c, &d);
    }
}

/* inv_park: [d, q, sine, cosine] -> alpha, beta, 4 bytes. */
static void tt_replay_inv_park(tt_ctx_t *c)
{
    uint32_t k;
    for (k = 0u; k < c->data->n; k++) {
        tt_digest_t d;
        qfoc_dq_t in;
        qfoc_sincos_t sc;
        qfoc_ab_t out;
        in.d = tt_in_i16(c, k, 0u);
        in.q = tt_in_i16(c, k, 1u);
        sc.sine = tt_in_i16(c, k, 2u);
        sc.cosine = tt_in_i16(c, k, 3u);
        qfoc_inv_park(&in, &sc, &out);
        tt_d_init(&d);
        tt_d_ab(&d, &out);
        tt_emit(c, &d);
    }
}

/* inv_clarke: [alpha, beta] -> u, v, w (hash). */
static void tt_replay_inv_clarke(tt_ctx_t *c)
{
    uint32_t k;
    for (k = 0u; k < c->data->n; k++) {
        tt_digest_t d;
        qfoc_ab_t in;
        qfoc_abc_t out;
        tt_ab_in(c, k, 0u, &in);
        qfoc_inv_clarke(&in, &out);
        tt_d_init(&d);
        tt_d_abc(&d, &out);
        tt_emit(c, &d);
    }
}

/* ------------------------------------------------------------------ svpwm.h, ramp.h, fault.h */

/* the outputs of an SVPWM step into a digest */
static void tt_d_svpwm(tt_digest_t *d, const qfoc_svpwm_out_t *out)
{
    tt_d_u16(d, out->cmp[0]);
    tt_d_u16(d, out->cmp[1]);
    tt_d_u16(d, out->cmp[2]);
    tt_d_u8(d, out->sector);
    tt_d_i16(d, out->utilisation);
    tt_d_bool(d, out->limited);
    tt_d_bool(d, out->vdc_low);
}

/* svpwm: [period, dt_comp, i_deadband, vdc_min, v_alpha, v_beta, vdc, i_u, i_v, i_w]
   -> cfg_is_valid, cmp[3], sector, utilisation, limited, vdc_low (hash) of
   qfoc_svpwm_step, then the same of qfoc_svpwm_step_lin. */
static void tt_replay_svpwm(tt_ctx_t *c)
{
    uint32_t k;
    for (k = 0u; k < c->data->n; k++) {
        tt_digest_t d;
        qfoc_svpwm_cfg_t cfg;
        qfoc_ab_t v;
        qfoc_abc_t i;
        qfoc_svpwm_out_t out;
        cfg.period = tt_in(c, k, 0u);
        cfg.dt_comp = tt_in(c, k, 1u);
        cfg.i_deadband = tt_in_i16(c, k, 2u);
        cfg.vdc_min = tt_in_i16(c, k, 3u);
        tt_ab_in(c, k, 4u, &v);
        i.u = tt_in_i16(c, k, 7u);
        i.v = tt_in_i16(c, k, 8u);
        i.w = tt_in_i16(c, k, 9u);
        (void)memset(&out, 0, sizeof out);
        qfoc_svpwm_step(&cfg, &v, tt_in_i16(c, k, 6u), &i, &out);
        tt_d_init(&d);
        tt_d_bool(&d, qfoc_svpwm_cfg_is_valid(&cfg));
        tt_d_svpwm(&d, &out);
        (void)memset(&out, 0, sizeof out);
        qfoc_svpwm_step_lin(&cfg, &v, tt_in_i16(c, k, 6u), &i, &out);
        tt_d_svpwm(&d, &out);
        tt_emit(c, &d);
    }
}

/* ramp: [value, target, step] -> qfoc_ramp_toward, 2 bytes. */
static void tt_replay_ramp(tt_ctx_t *c)
{
    uint32_t k;
    for (k = 0u; k < c->data->n; k++) {
        tt_digest_t d;
        tt_d_init(&d);
        tt_d_i16(&d, qfoc_ramp_toward(tt_in_i16(c, k, 0u), tt_in_i16(c, k, 1u), tt_in_i16(c, k, 2u)));
        tt_emit(c, &d);
    }
}

/* fault_level: [x, limit] -> qfoc_fault_over, qfoc_fault_under, qfoc_fault_abs_over, 3 bytes. */
static void tt_replay_fault_level(tt_ctx_t *c)
{
    uint32_t k;
    for (k = 0u; k < c->data->n; k++) {
        tt_digest_t d;
        const qfoc_q15_t x = tt_in_i16(c, k, 0u);
        const qfoc_q15_t lim = tt_in_i16(c, k, 1u);
        tt_d_init(&d);
        tt_d_bool(&d, qfoc_fault_over(x, lim));
        tt_d_bool(&d, qfoc_fault_under(x, lim));
        tt_d_bool(&d, qfoc_fault_abs_over(x, lim));
        tt_emit(c, &d);
    }
}

/* debounce (operations): RESET; STEP [cond, n] -> result; digest: result, count. */
static void tt_replay_debounce(tt_ctx_t *c)
{
    qfoc_debounce_t db;
    uint32_t k;
    (void)memset(&db, 0, sizeof db);
    qfoc_debounce_reset(&db);
    for (k = 0u; k < c->data->n; k++) {
        tt_digest_t d;
        const uint16_t op = tt_in(c, k, 0u);
        bool r = false;
        if (op == TT_OP_RESET) {
            qfoc_debounce_reset(&db);
        } else if (op == TT_OP_STEP) {
            r = qfoc_debounce_step(&db, tt_in(c, k, 1u) != 0u, tt_in(c, k, 2u));
        } else {
            /* unknown operation: nothing */
        }
        tt_d_init(&d);
        tt_d_bool(&d, r);
        tt_d_u16(&d, db.count);
        tt_emit(c, &d);
    }
}

/* phase_mon (operations): INIT [alpha, one] (one != 0: the coefficient
   qfoc_phase_mon_alpha3(alpha), in the digest); RESET; STEP [i_u, i_v, i_w] (update);
   AUX2 [i_u, i_v, i_w, k] (update of phase k only); AUX [i_min, ratio] (imbalanced).
   Digest: status or result, valid, three filters. */
static void tt_replay_phase_mon(tt_ctx_t *c)
{
    qfoc_phase_mon_t m;
    uint32_t k;
    (void)memset(&m, 0, sizeof m);
    for (k = 0u; k < c->data->n; k++) {
        tt_digest_t d;
        const uint16_t op = tt_in(c, k, 0u);
        const bool valid = qfoc_phase_mon_is_valid(&m);
        uint16_t j;
        tt_d_init(&d);
        if (op == TT_OP_INIT) {
            qfoc_q15_t alpha = tt_in_i16(c, k, 1u);
            (void)memset(&m, 0, sizeof m);
            if (tt_in(c, k, 2u) != 0u) {
                alpha = qfoc_phase_mon_alpha3(alpha);
                tt_d_i32(&d, (int32_t)alpha);
            }
            tt_d_i32(&d, qfoc_phase_mon_init(&m, alpha));
        } else if (!valid) {
            /* not initialised: only init is called */
        } else if (op == TT_OP_RESET) {
            qfoc_phase_mon_reset(&m);
        } else if (op == TT_OP_STEP) {
            qfoc_abc_t i;
            i.u = tt_in_i16(c, k, 1u);
            i.v = tt_in_i16(c, k, 2u);
            i.w = tt_in_i16(c, k, 3u);
            qfoc_phase_mon_update(&m, &i);
        } else if (op == TT_OP_AUX2) {
            qfoc_abc_t i;
            i.u = tt_in_i16(c, k, 1u);
            i.v = tt_in_i16(c, k, 2u);
            i.w = tt_in_i16(c, k, 3u);
            qfoc_phase_mon_update_one(&m, &i, (uint8_t)tt_in(c, k, 4u));
        } else if (op == TT_OP_AUX) {
            tt_d_bool(&d, qfoc_phase_mon_imbalanced(&m, tt_in_i16(c, k, 1u), tt_in_i16(c, k, 2u)));
        } else {
            /* unknown operation: nothing */
        }
        tt_d_bool(&d, qfoc_phase_mon_is_valid(&m));
        for (j = 0u; j < 3u; j++) {
            tt_d_lpf(&d, &m.abs_lpf[j]);
        }
        tt_emit(c, &d);
    }
}

/* ------------------------------------------------------------------ filter.h, pi.h, fw.h */

/* lpf (operations): INIT [alpha]; RESET [value]; STEP [u] -> y.
   Digest: status or output, valid, alpha, state. */
static void tt_replay_lpf(tt_ctx_t *c)
{
    qfoc_lpf_t f;
    uint32_t k;
    (void)memset(&f, 0, sizeof f);
    for (k = 0u; k < c->data->n; k++) {
        tt_digest_t d;
        const uint16_t op = tt_in(c, k, 0u);
        const bool valid = qfoc_lpf_is_valid(&f);
        tt_d_init(&d);
        if (op == TT_OP_INIT) {
            (void)memset(&f, 0, sizeof f);
            tt_d_i32(&d, qfoc_lpf_init(&f, tt_in_i16(c, k, 1u)));
        } else if (!valid) {
            /* only init */
        } else if (op == TT_OP_RESET) {
            qfoc_lpf_reset(&f, tt_in_i16(c, k, 1u));
        } else if (op == TT_OP_STEP) {
            tt_d_i16(&d, qfoc_lpf_step(&f, tt_in_i16(c, k, 1u)));
        } else {
            /* unknown operation: nothing */
        }
        tt_d_bool(&d, qfoc_lpf_is_valid(&f));
        tt_d_lpf(&d, &f);
        tt_emit(c, &d);
    }
}

/* leaky (operations): INIT [gain, gain_shift, leak]; RESET [value]; STEP [x] -> y.
   Digest: status or output, valid, gain, shift, leak, state. */
static void tt_replay_leaky(tt_ctx_t *c)
{
    qfoc_leaky_int_t f;
    uint32_t k;
    (void)memset(&f, 0, sizeof f);
    for (k = 0u; k < c->data->n; k++) {
        tt_digest_t d;
        const uint16_t op = tt_in(c, k, 0u);
        const bool valid = qfoc_leaky_is_valid(&f);
        tt_d_init(&d);
        if (op == TT_OP_INIT) {
            (void)memset(&f, 0, sizeof f);
            tt_d_i32(&d, qfoc_leaky_init(&f, tt_in_i16(c, k, 1u), (uint8_t)tt_in(c, k, 2u),
                                         tt_in_i16(c, k, 3u)));
        } else if (!valid) {
            /* only init */
        } else if (op == TT_OP_RESET) {
            qfoc_leaky_reset(&f, tt_in_i16(c, k, 1u));
        } else if (op == TT_OP_STEP) {
            tt_d_i16(&d, qfoc_leaky_step(&f, tt_in_i16(c, k, 1u)));
        } else {
            /* unknown operation: nothing */
        }
        tt_d_bool(&d, qfoc_leaky_is_valid(&f));
        tt_d_i16(&d, f.gain);
        tt_d_u8(&d, f.gain_shift);
        tt_d_i16(&d, f.leak);
        tt_d_i32(&d, f.state);
        tt_emit(c, &d);
    }
}

/* pi (operations): INIT [kp, kp_shift, ki, ki_shift, out_min, out_max]; RESET [preset];
   STEP [error] -> output.  Digest: status, params_is_valid or output; valid; the PI. */
static void tt_replay_pi(tt_ctx_t *c)
{
    qfoc_pi_t pi;
    uint32_t k;
    (void)memset(&pi, 0, sizeof pi);
    for (k = 0u; k < c->data->n; k++) {
        tt_digest_t d;
        const uint16_t op = tt_in(c, k, 0u);
        const bool valid = qfoc_pi_is_valid(&pi);
        tt_d_init(&d);
        if (op == TT_OP_INIT) {
            qfoc_pi_params_t p;
            tt_pi_params(c, k, 1u, &p);
            (void)memset(&pi, 0, sizeof pi);
            tt_d_i32(&d, qfoc_pi_init(&pi, &p));
            tt_d_bool(&d, qfoc_pi_params_is_valid(&p));
        } else if (!valid) {
            /* only init */
        } else if (op == TT_OP_RESET) {
            qfoc_pi_reset(&pi, tt_in_i16(c, k, 1u));
        } else if (op == TT_OP_STEP) {
            tt_d_i16(&d, qfoc_pi_step(&pi, tt_in_i16(c, k, 1u)));
        } else {
            /* unknown operation: nothing */
        }
        tt_d_bool(&d, qfoc_pi_is_valid(&pi));
        tt_d_pi(&d, &pi);
        tt_emit(c, &d);
    }
}

/* fw (operations): INIT [pi 6 words, level, alpha]; RESET; STEP [utilisation, enable]
   -> i_d reference.  Digest: status, params_is_valid or output; valid; PI, low-pass,
   level, id_ref. */
static void tt_replay_fw(tt_ctx_t *c)
{
    qfoc_fw_t fw;
    uint32_t k;
    (void)memset(&fw, 0, sizeof fw);
    for (k = 0u; k < c->data->n; k++) {
        tt_digest_t d;
        const uint16_t op = tt_in(c, k, 0u);
        const bool valid = qfoc_fw_is_valid(&fw);
        tt_d_init(&d);
        if (op == TT_OP_INIT) {
            qfoc_fw_params_t p;
            tt_pi_params(c, k, 1u, &p.pi);
            p.level = tt_in_i16(c, k, 7u);
            p.alpha = tt_in_i16(c, k, 8u);
            (void)memset(&fw, 0, sizeof fw);
            tt_d_i32(&d, qfoc_fw_init(&fw, &p));
            tt_d_bool(&d, qfoc_fw_params_is_valid(&p));
        } else if (!valid) {
            /* only init */
        } else if (op == TT_OP_RESET) {
            qfoc_fw_reset(&fw);
        } else if (op == TT_OP_STEP) {
            tt_d_i16(&d, qfoc_fw_step(&fw, tt_in_i16(c, k, 1u), tt_in(c, k, 2u) != 0u));
        } else {
            /* unknown operation: nothing */
        }
        tt_d_bool(&d, qfoc_fw_is_valid(&fw));
        tt_d_pi(&d, &fw.pi);
        tt_d_lpf(&d, &fw.util_lpf);
        tt_d_i16(&d, fw.level);
        tt_d_i16(&d, fw.id_ref);
        tt_emit(c, &d);
    }
}

/* ------------------------------------------------------------------ flux.h, pll.h, emf.h */

/* flux (operations): INIT [gain, gain_shift, r, l, kg]; RESET [psi0 a, b, i0 a, b];
   STEP [u a, b, i a, b] -> psi_r; AUX [w] -> lead.  Digest: status, params_is_valid,
   psi_r or lead; valid; psi_alpha, psi_beta, i_prev. */
static void tt_replay_flux(tt_ctx_t *c)
{
    qfoc_flux_t o;
    uint32_t k;
    (void)memset(&o, 0, sizeof o);
    for (k = 0u; k < c->data->n; k++) {
        tt_digest_t d;
        const uint16_t op = tt_in(c, k, 0u);
        const bool valid = qfoc_flux_is_valid(&o);
        tt_d_init(&d);
        if (op == TT_OP_INIT) {
            qfoc_flux_params_t p;
            p.gain = tt_in_i16(c, k, 1u);
            p.gain_shift = (uint8_t)tt_in(c, k, 2u);
            p.r = tt_in_i16(c, k, 3u);
            p.l = tt_in_i16(c, k, 4u);
            p.kg = tt_in_i16(c, k, 5u);
            (void)memset(&o, 0, sizeof o);
            tt_d_i32(&d, qfoc_flux_init(&o, &p));
            tt_d_bool(&d, qfoc_flux_params_is_valid(&p));
        } else if (!valid) {
            /* only init */
        } else if (op == TT_OP_RESET) {
            qfoc_ab_t psi0;
            qfoc_ab_t i0;
            tt_ab_in(c, k, 1u, &psi0);
            tt_ab_in(c, k, 3u, &i0);
            qfoc_flux_reset(&o, &psi0, &i0);
        } else if (op == TT_OP_STEP) {
            qfoc_ab_t u;
            qfoc_ab_t i;
            qfoc_ab_t psi;
            tt_ab_in(c, k, 1u, &u);
            tt_ab_in(c, k, 3u, &i);
            qfoc_flux_step(&o, &u, &i, &psi);
            tt_d_ab(&d, &psi);
        } else if (op == TT_OP_AUX) {
            tt_d_u16(&d, qfoc_flux_lead(&o, tt_in_i16(c, k, 1u)));
        } else {
            /* unknown operation: nothing */
        }
        tt_d_bool(&d, qfoc_flux_is_valid(&o));
        tt_d_i32(&d, o.psi_alpha);
        tt_d_i32(&d, o.psi_beta);
        tt_d_ab(&d, &o.i_prev);
        tt_emit(c, &d);
    }
}

static void tt_d_pll(tt_digest_t *d, const qfoc_pll_t *pll)
{
    tt_d_bool(d, qfoc_pll_is_valid(pll));
    tt_d_pi(d, &pll->pi);
    tt_d_lpf(d, &pll->speed_lpf);
    tt_d_u32(d, pll->theta_acc);
    tt_d_i16(d, pll->speed);
}

static void tt_d_pll_out(tt_digest_t *d, const qfoc_pll_out_t *o)
{
    tt_d_u16(d, o->theta);
    tt_d_u16(d, o->theta_next);
    tt_d_i16(d, o->sc.sine);
    tt_d_i16(d, o->sc.cosine);
    tt_d_i16(d, o->speed);
    tt_d_i16(d, o->speed_f);
    tt_d_i16(d, o->error);
    tt_d_i16(d, o->mag);
}

/* pll (operations): INIT [pi 6 words, err_clamp, mag_min, k_theta, speed_alpha];
   RESET [theta, speed]; STEP [psi a, b] (qfoc_pll_step); AUX2 [emf a, b]
   (qfoc_pll_step_emf).  Digest: status, params_is_valid or the output; the PLL. */
static void tt_replay_pll(tt_ctx_t *c)
{
    qfoc_pll_t pll;
    uint32_t k;
    (void)memset(&pll, 0, sizeof pll);
    for (k = 0u; k < c->data->n; k++) {
        tt_digest_t d;
        const uint16_t op = tt_in(c, k, 0u);
        const bool valid = qfoc_pll_is_valid(&pll);
        tt_d_init(&d);
        if (op == TT_OP_INIT) {
            qfoc_pll_params_t p;
            tt_pi_params(c, k, 1u, &p.pi);
            p.err_clamp = tt_in_i16(c, k, 7u);
            p.mag_min = tt_in_i16(c, k, 8u);
            p.k_theta = tt_in(c, k, 9u);
            p.speed_alpha = tt_in_i16(c, k, 10u);
            (void)memset(&pll, 0, sizeof pll);
            tt_d_i32(&d, qfoc_pll_init(&pll, &p));
            tt_d_bool(&d, qfoc_pll_params_is_valid(&p));
        } else if (!valid) {
            /* only init */
        } else if (op == TT_OP_RESET) {
            qfoc_pll_reset(&pll, tt_in(c, k, 1u), tt_in_i16(c, k, 2u));
        } else if ((op == TT_OP_STEP) || (op == TT_OP_AUX2)) {
            qfoc_ab_t in;
            qfoc_pll_out_t out;
            tt_ab_in(c, k, 1u, &in);
            (void)memset(&out, 0, sizeof out);
            if (op == TT_OP_STEP) {
                qfoc_pll_step(&pll, &in, &out);
            } else {
                qfoc_pll_step_emf(&pll, &in, &out);
            }
            tt_d_pll_out(&d, &out);
        } else {
            /* unknown operation: nothing */
        }
        tt_d_pll(&d, &pll);
        tt_emit(c, &d);
    }
}

static void tt_d_emf_out(tt_digest_t *d, const qfoc_emf_out_t *o)
{
    tt_d_ab(d, &o->emf);
    tt_d_u16(d, o->theta);
}

/* emf (operations): INIT [r, l, alpha, k_theta]; RESET [i0 a, b]; STEP [u a, b, i a, b];
   AUX [w] (lag).  Digest: status, params_is_valid, output or lag; valid, i_prev,
   both low-passes, active. */
static void tt_replay_emf(tt_ctx_t *c)
{
    qfoc_emf_t e;
    uint32_t k;
    (void)memset(&e, 0, sizeof e);
    for (k = 0u; k < c->data->n; k++) {
        tt_digest_t d;
        const uint16_t op = tt_in(c, k, 0u);
        const bool valid = qfoc_emf_is_valid(&e);
        tt_d_init(&d);
        if (op == TT_OP_INIT) {
            qfoc_emf_params_t p;
            p.r = tt_in_i16(c, k, 1u);
            p.l = tt_in_i16(c, k, 2u);
            p.alpha = tt_in_i16(c, k, 3u);
            p.k_theta = tt_in(c, k, 4u);
            (void)memset(&e, 0, sizeof e);
            tt_d_i32(&d, qfoc_emf_init(&e, &p));
            tt_d_bool(&d, qfoc_emf_params_is_valid(&p));
        } else if (!valid) {
            /* only init */
        } else if (op == TT_OP_RESET) {
            qfoc_ab_t i0;
            tt_ab_in(c, k, 1u, &i0);
            qfoc_emf_reset(&e, &i0);
        } else if (op == TT_OP_STEP) {
            qfoc_ab_t u;
            qfoc_ab_t i;
            qfoc_emf_out_t out;
            tt_ab_in(c, k, 1u, &u);
            tt_ab_in(c, k, 3u, &i);
            (void)memset(&out, 0, sizeof out);
            qfoc_emf_step(&e, &u, &i, &out);
            tt_d_emf_out(&d, &out);
        } else if (op == TT_OP_AUX) {
            tt_d_u16(&d, qfoc_emf_lag(&e, tt_in_i16(c, k, 1u)));
        } else {
            /* unknown operation: nothing */
        }
        tt_d_bool(&d, qfoc_emf_is_valid(&e));
        tt_d_ab(&d, &e.i_prev);
        tt_d_lpf(&d, &e.lpf_alpha);
        tt_d_lpf(&d, &e.lpf_beta);
        tt_d_bool(&d, e.active);
        tt_emit(c, &d);
    }
}

/* dob (operations): INIT [ki, ki_shift, r, g, k_theta]; RESET [i0 a, b];
   STEP [u a, b, i a, b]; AUX [w] (lag).  Digest: status, params_is_valid, output or
   lag; valid, ih_alpha, ih_beta, i_prev, e_prev. */
static void tt_replay_dob(tt_ctx_t *c)
{
    qfoc_dob_t o;
    uint32_t k;
    (void)memset(&o, 0, sizeof o);
    for (k = 0u; k < c->data->n; k++) {
        tt_digest_t d;
        const uint16_t op = tt_in(c, k, 0u);
        const bool valid = qfoc_dob_is_valid(&o);
        tt_d_init(&d);
        if (op == TT_OP_INIT) {
            qfoc_dob_params_t p;
            p.ki = tt_in_i16(c, k, 1u);
            p.ki_shift = (uint8_t)tt_in(c, k, 2u);
            p.r = tt_in_i16(c, k, 3u);
            p.g = tt_in_i16(c, k, 4u);
            p.k_theta = tt_in(c, k, 5u);
            (void)memset(&o, 0, sizeof o);
            tt_d_i32(&d, qfoc_dob_init(&o, &p));
            tt_d_bool(&d, qfoc_dob_params_is_valid(&p));
        } else if (!valid) {
            /* only init */
        } else if (op == TT_OP_RESET) {
            qfoc_ab_t i0;
            tt_ab_in(c, k, 1u, &i0);
            qfoc_dob_reset(&o, &i0);
        } else if (op == TT_OP_STEP) {
            qfoc_ab_t u;
            qfoc_ab_t i;
            qfoc_emf_out_t out;
            tt_ab_in(c, k, 1u, &u);
            tt_ab_in(c, k, 3u, &i);
            (void)memset(&out, 0, sizeof out);
            qfoc_dob_step(&o, &u, &i, &out);
            tt_d_emf_out(&d, &out);
        } else if (op == TT_OP_AUX) {
            tt_d_u16(&d, qfoc_dob_lag(&o, tt_in_i16(c, k, 1u)));
        } else {
            /* unknown operation: nothing */
        }
        tt_d_bool(&d, qfoc_dob_is_valid(&o));
        tt_d_i32(&d, o.ih_alpha);
        tt_d_i32(&d, o.ih_beta);
        tt_d_ab(&d, &o.i_prev);
        tt_d_ab(&d, &o.e_prev);
        tt_emit(c, &d);
    }
}

/* ------------------------------------------------------------------ trqcomp.h */

/* mech (operations): INIT [pole_pairs, theta_e]; STEP [theta_e] -> theta_m.
   Digest: status or theta_m; valid, turn, theta_e, recip. */
static void tt_replay_mech(tt_ctx_t *c)
{
    qfoc_mech_t m;
    uint32_t k;
    (void)memset(&m, 0, sizeof m);
    for (k = 0u; k < c->data->n; k++) {
        tt_digest_t d;
        const uint16_t op = tt_in(c, k, 0u);
        const bool valid = qfoc_mech_is_valid(&m);
        tt_d_init(&d);
        if (op == TT_OP_INIT) {
            (void)memset(&m, 0, sizeof m);
            tt_d_i32(&d, qfoc_mech_init(&m, (uint8_t)tt_in(c, k, 1u), tt_in(c, k, 2u)));
        } else if (!valid) {
            /* only init */
        } else if (op == TT_OP_STEP) {
            tt_d_u16(&d, qfoc_mech_update(&m, tt_in(c, k, 1u)));
        } else {
            /* unknown operation: nothing */
        }
        tt_d_bool(&d, qfoc_mech_is_valid(&m));
        tt_d_u8(&d, m.pole_pairs);
        tt_d_u8(&d, m.turn);
        tt_d_u16(&d, m.theta_e);
        tt_d_u32(&d, m.recip);
        tt_emit(c, &d);
    }
}

/* trqcomp (operations): INIT [gain, amp_max, speed_min, speed_max, pole_pairs]; RESET;
   STEP [theta_m, speed_err, speed] (learn); AUX [theta_m, speed] (output); AUX2 (phase1).
   Digest: status, params_is_valid, output or phase; valid, a[], b[]. */
static void tt_replay_trqcomp(tt_ctx_t *c)
{
    qfoc_trqcomp_t tc;
    uint32_t k;
    (void)memset(&tc, 0, sizeof tc);
    for (k = 0u; k < c->data->n; k++) {
        tt_digest_t d;
        const uint16_t op = tt_in(c, k, 0u);
        const bool valid = qfoc_trqcomp_is_valid(&tc);
        uint16_t h;
        tt_d_init(&d);
        if (op == TT_OP_INIT) {
            qfoc_trqcomp_params_t p;
            p.gain = tt_in_i16(c, k, 1u);
            p.amp_max = tt_in_i16(c, k, 2u);
            p.speed_min = tt_in_i16(c, k, 3u);
            p.speed_max = tt_in_i16(c, k, 4u);
            p.pole_pairs = (uint8_t)tt_in(c, k, 5u);
            (void)memset(&tc, 0, sizeof tc);
            tt_d_i32(&d, qfoc_trqcomp_init(&tc, &p));
            tt_d_bool(&d, qfoc_trqcomp_params_is_valid(&p));
        } else if (!valid) {
            /* only init */
        } else if (op == TT_OP_RESET) {
            qfoc_trqcomp_reset(&tc);
        } else if (op == TT_OP_STEP) {
            qfoc_trqcomp_learn(&tc, tt_in(c, k, 1u), tt_in_i16(c, k, 2u), tt_in_i16(c, k, 3u));
        } else if (op == TT_OP_AUX) {
            tt_d_i16(&d, qfoc_trqcomp_output(&tc, tt_in(c, k, 1u), tt_in_i16(c, k, 2u)));
        } else if (op == TT_OP_AUX2) {
            tt_d_u16(&d, qfoc_trqcomp_phase1(&tc));
        } else {
            /* unknown operation: nothing */
        }
        tt_d_bool(&d, qfoc_trqcomp_is_valid(&tc));
        for (h = 0u; h < QFOC_TRQCOMP_HARMONICS; h++) {
            tt_d_i32(&d, tc.a[h]);
            tt_d_i32(&d, tc.b[h]);
        }
        tt_emit(c, &d);
    }
}

/* ------------------------------------------------------------------ link.h */

static void tt_link_cfg(const tt_ctx_t *c, uint32_t k, uint16_t j, qfoc_link_cfg_t *cfg)
{
    cfg->id_cmd = (uint8_t)tt_in(c, k, j);
    cfg->id_status = (uint8_t)tt_in(c, k, (uint16_t)(j + 1u));
    cfg->rpm_max = tt_in(c, k, (uint16_t)(j + 2u));
    cfg->timeout_ms = tt_in(c, k, (uint16_t)(j + 3u));
    cfg->can_id_a = tt_in(c, k, (uint16_t)(j + 4u));
    cfg->can_id_b = tt_in(c, k, (uint16_t)(j + 5u));
}

static void tt_status_in(const tt_ctx_t *c, uint32_t k, uint16_t j, qfoc_status_t *st)
{
    st->state = (uint8_t)tt_in(c, k, j);
    st->substate = (uint8_t)tt_in(c, k, (uint16_t)(j + 1u));
    st->faults = tt_in(c, k, (uint16_t)(j + 2u));
    st->speed_rpm = tt_in(c, k, (uint16_t)(j + 3u));
    st->vdc_dv = tt_in(c, k, (uint16_t)(j + 4u));
    st->current_ca = tt_in(c, k, (uint16_t)(j + 5u));
    st->temp_dc = tt_in_i16(c, k, (uint16_t)(j + 6u));
}

static void tt_d_cmd(tt_digest_t *d, const qfoc_cmd_t *cmd)
{
    tt_d_bool(d, cmd->power_on);
    tt_d_bool(d, cmd->fault_clear);
    tt_d_u16(d, cmd->target_rpm);
    tt_d_bool(d, cmd->identify);
}

static void tt_d_can(tt_digest_t *d, const qfoc_can_frame_t *f)
{
    uint16_t b;
    tt_d_u16(d, f->id);
    tt_d_u8(d, f->dlc);
    for (b = 0u; b < 8u; b++) {
        tt_d_u8(d, f->data[b]);
    }
}

/* lin_pid: every identifier byte (width 0, 256 vectors) -> PID, 1 byte. */
static void tt_replay_lin_pid(tt_ctx_t *c)
{
    uint32_t k;
    for (k = 0u; k < c->data->n; k++) {
        tt_digest_t d;
        tt_d_init(&d);
        tt_d_u8(&d, qfoc_lin_pid((uint8_t)(tt_in_index(c, k) & 0xFFu)));
        tt_emit(c, &d);
    }
}

/* lin_checksum: [pid, n, 6 words = 12 data bytes] -> checksum over n <= 12 bytes, 1 byte. */
static void tt_replay_lin_checksum(tt_ctx_t *c)
{
    uint32_t k;
    for (k = 0u; k < c->data->n; k++) {
        tt_digest_t d;
        uint8_t buf[12];
        uint16_t n = tt_in(c, k, 1u);
        if (n > 12u) {
            n = 12u;
        }
        tt_in_bytes(c, k, 2u, buf, 12u);
        tt_d_init(&d);
        tt_d_u8(&d, qfoc_lin_checksum((uint8_t)tt_in(c, k, 0u), buf, (uint8_t)n));
        tt_emit(c, &d);
    }
}

/* lin_decode: [link cfg 6 words, len, 6 words = 12 frame bytes]; the frame buffer is
   256 bytes (zero beyond the 12), so any len 0..255 is within it.
   Digest: status, cmd (initialised to a pattern, written only on success). */
static void tt_replay_lin_decode(tt_ctx_t *c)
{
    static uint8_t buf[256];
    uint32_t k;
    for (k = 0u; k < c->data->n; k++) {
        tt_digest_t d;
        qfoc_link_cfg_t cfg;
        qfoc_cmd_t cmd;
        tt_link_cfg(c, k, 0u, &cfg);
        tt_in_bytes(c, k, 7u, buf, 12u);
        cmd.power_on = true;
        cmd.fault_clear = true;
        cmd.target_rpm = 0xA5A5u;
        cmd.identify = true;
        tt_d_init(&d);
        tt_d_i32(&d, qfoc_lin_decode_cmd(&cfg, buf, (uint8_t)(tt_in(c, k, 6u) & 0xFFu), &cmd));
        tt_d_cmd(&d, &cmd);
        tt_emit(c, &d);
    }
}

/* lin_encode: [link cfg 6 words, status 7 words] -> length and the frame bytes. */
static void tt_replay_lin_encode(tt_ctx_t *c)
{
    uint32_t k;
    for (k = 0u; k < c->data->n; k++) {
        tt_digest_t d;
        qfoc_link_cfg_t cfg;
        qfoc_status_t st;
        uint8_t buf[QFOC_LIN_FRAME_MAX];
        uint8_t len;
        uint16_t b;
        tt_link_cfg(c, k, 0u, &cfg);
        tt_status_in(c, k, 6u, &st);
        (void)memset(buf, 0, sizeof buf);
        len = qfoc_lin_encode_status(&cfg, &st, buf);
        tt_d_init(&d);
        tt_d_u8(&d, len);
        for (b = 0u; b < QFOC_LIN_FRAME_MAX; b++) {
            tt_d_u8(&d, buf[b]);
        }
        tt_emit(c, &d);
    }
}

/* link (operations): INIT [cfg 6 words]; STEP [rx_len, 6 words = 12 bytes] (service, then
   command and lost); AUX [status 7 words] (can_status).  Digest: status, service
   result, command, lost, or the CAN frame; valid and every field of the link. */
static void tt_replay_link(tt_ctx_t *c)
{
    static uint8_t buf[256];
    qfoc_link_t l;
    uint32_t k;
    (void)memset(&l, 0, sizeof l);
    for (k = 0u; k < c->data->n; k++) {
        tt_digest_t d;
        const uint16_t op = tt_in(c, k, 0u);
        const bool valid = qfoc_link_is_valid(&l);
        tt_d_init(&d);
        if (op == TT_OP_INIT) {
            qfoc_link_cfg_t cfg;
            tt_link_cfg(c, k, 1u, &cfg);
            (void)memset(&l, 0, sizeof l);
            tt_d_i32(&d, qfoc_link_init(&l, &cfg));
            tt_d_bool(&d, qfoc_link_cfg_is_valid(&cfg));
        } else if (!valid) {
            /* only init */
        } else if (op == TT_OP_STEP) {
            qfoc_cmd_t cmd;
            tt_in_bytes(c, k, 2u, buf, 12u);
            tt_d_bool(&d, qfoc_link_service(&l, buf, (uint8_t)(tt_in(c, k, 1u) & 0xFFu)));
            (void)memset(&cmd, 0, sizeof cmd);
            qfoc_link_command(&l, &cmd);
            tt_d_cmd(&d, &cmd);
            tt_d_bool(&d, qfoc_link_lost(&l));
        } else if (op == TT_OP_AUX) {
            qfoc_status_t st;
            qfoc_can_frame_t f;
            tt_status_in(c, k, 1u, &st);
            (void)memset(&f, 0, sizeof f);
            qfoc_can_status(&l, &st, &f);
            tt_d_can(&d, &f);
        } else {
            /* unknown operation: nothing */
        }
        tt_d_bool(&d, qfoc_link_is_valid(&l));
        tt_d_cmd(&d, &l.cmd);
        tt_d_u16(&d, l.silent_ms);
        tt_d_bool(&d, l.cfg_ok);
        tt_d_bool(&d, l.seen);
        tt_d_bool(&d, l.lost);
        tt_d_bool(&d, l.can_b);
        tt_d_u16(&d, l.n_ok);
        tt_d_u16(&d, l.n_len);
        tt_d_u16(&d, l.n_sync);
        tt_d_u16(&d, l.n_id);
        tt_d_u16(&d, l.n_checksum);
        tt_d_u16(&d, l.n_reserved);
        tt_d_u16(&d, l.n_range);
        tt_emit(c, &d);
    }
}

/* ------------------------------------------------------------------ params.h */

/* crc32_byte: [crc low, crc high, byte] -> register, 4 bytes. */
static void tt_replay_crc32_byte(tt_ctx_t *c)
{
    uint32_t k;
    for (k = 0u; k < c->data->n; k++) {
        tt_digest_t d;
        tt_d_init(&d);
        tt_d_u32(&d, qfoc_crc32_byte(tt_in_u32(c, k, 0u), (uint8_t)(tt_in(c, k, 2u) & 0xFFu)));
        tt_emit(c, &d);
    }
}

/* A copy of the reference table with byte `offset` XOR `mask` (offset 0xFFFF: none),
   resealed with its CRC when `reseal` is not 0. */
static void tt_table_mutant(const tt_ctx_t *c, uint32_t k, qfoc_param_table_t *t)
{
    const uint16_t offset = tt_in(c, k, 0u);
    *t = qfoc_params_reference;
    if ((uint32_t)offset < (uint32_t)sizeof(qfoc_param_table_t)) {
        uint8_t *bytes = (uint8_t *)t;
        bytes[offset] ^= (uint8_t)(tt_in(c, k, 1u) & 0xFFu);
    }
    if (tt_in(c, k, 2u) != 0u) {
        t->crc = qfoc_params_crc(t);
    }
}

/* params: [byte offset, XOR mask, reseal] on the reference table.
   Digest: qfoc_params_crc, is_valid, check, load status, the loaded copy's crc field and
   computed CRC, and the block checks (drive_cfg, svpwm, four PI, flux, pll). */
static void tt_replay_params(tt_ctx_t *c)
{
    static qfoc_param_table_t t;
    static qfoc_param_table_t ram;
    uint32_t k;
    for (k = 0u; k < c->data->n; k++) {
        tt_digest_t d;
        tt_table_mutant(c, k, &t);
        (void)memset(&ram, 0, sizeof ram);
        tt_d_init(&d);
        tt_d_u32(&d, qfoc_params_crc(&t));
        tt_d_bool(&d, qfoc_params_is_valid(&t));
        tt_d_i32(&d, qfoc_params_check(&t));
        tt_d_i32(&d, qfoc_params_load(&ram, &t));
        tt_d_u32(&d, ram.crc);
        tt_d_u32(&d, qfoc_params_crc(&ram));
        tt_d_bool(&d, qfoc_drive_cfg_is_valid(&t.drive));
        tt_d_bool(&d, qfoc_svpwm_cfg_is_valid(&t.svpwm));
        tt_d_bool(&d, qfoc_pi_params_is_valid(&t.pi_id));
        tt_d_bool(&d, qfoc_pi_params_is_valid(&t.pi_iq));
        tt_d_bool(&d, qfoc_pi_params_is_valid(&t.pi_speed));
        tt_d_bool(&d, qfoc_pi_params_is_valid(&t.pi_fw));
        tt_d_bool(&d, qfoc_flux_params_is_valid(&t.flux));
        tt_d_bool(&d, qfoc_pll_params_is_valid(&t.pll));
        tt_emit(c, &d);
    }
}

/* ------------------------------------------------------------------ sm.h */

/* sm (operations): INIT [precharge_ms, align_ms, ol_timeout_ms, cl_hold_ms, clear_ms]
   (configuration kept for the steps); AUX [faults] (qfoc_sm_fail); STEP [faults, inputs:
   bit 0 bus_ok, 1 calib_done, 2 run_request, 3 link_lost, 4 fault_clear, 5 table_ok,
   6 converged, 7 stop_reached].  Digest: valid and every field of the machine. */
static void tt_replay_sm(tt_ctx_t *c)
{
    qfoc_sm_t sm;
    qfoc_sm_cfg_t cfg;
    uint32_t k;
    (void)memset(&sm, 0, sizeof sm);
    (void)memset(&cfg, 0, sizeof cfg);
    for (k = 0u; k < c->data->n; k++) {
        tt_digest_t d;
        const uint16_t op = tt_in(c, k, 0u);
        const bool valid = qfoc_sm_is_valid(&sm);
        if (op == TT_OP_INIT) {
            cfg.precharge_ms = tt_in(c, k, 1u);
            cfg.align_ms = tt_in(c, k, 2u);
            cfg.ol_timeout_ms = tt_in(c, k, 3u);
            cfg.cl_hold_ms = tt_in(c, k, 4u);
            cfg.clear_ms = tt_in(c, k, 5u);
            (void)memset(&sm, 0, sizeof sm);
            qfoc_sm_init(&sm);
        } else if (!valid) {
            /* only init */
        } else if (op == TT_OP_AUX) {
            qfoc_sm_fail(&sm, tt_in(c, k, 1u));
        } else if (op == TT_OP_STEP) {
            qfoc_sm_in_t in;
            const uint16_t bits = tt_in(c, k, 2u);
            in.faults = tt_in(c, k, 1u);
            in.bus_ok = (bits & 0x01u) != 0u;
            in.calib_done = (bits & 0x02u) != 0u;
            in.run_request = (bits & 0x04u) != 0u;
            in.link_lost = (bits & 0x08u) != 0u;
            in.fault_clear = (bits & 0x10u) != 0u;
            in.table_ok = (bits & 0x20u) != 0u;
            in.converged = (bits & 0x40u) != 0u;
            in.stop_reached = (bits & 0x80u) != 0u;
            qfoc_sm_step(&sm, &cfg, &in);
        } else {
            /* unknown operation: nothing */
        }
        tt_d_init(&d);
        tt_d_bool(&d, qfoc_sm_is_valid(&sm));
        tt_d_u8(&d, sm.state);
        tt_d_u8(&d, sm.sub);
        tt_d_u16(&d, sm.faults);
        tt_d_u16(&d, sm.first_fault);
        tt_d_u16(&d, sm.t_state);
        tt_d_u16(&d, sm.t_sub);
        tt_emit(c, &d);
    }
}

/* ------------------------------------------------------------------ drive.h */

uint32_t tt_drive_fast_digest(const qfoc_drive_t *d, const qfoc_pwm_t *out)
{
    tt_digest_t g;
    tt_d_init(&g);
    tt_d_u16(&g, out->cmp[0]);
    tt_d_u16(&g, out->cmp[1]);
    tt_d_u16(&g, out->cmp[2]);
    tt_d_bool(&g, out->enable);
    tt_d_bool(&g, d->f.trip);
    tt_d_bool(&g, d->f.active);
    tt_d_bool(&g, d->f.hs);
    tt_d_u16(&g, d->f.theta_est);
    tt_d_u16(&g, d->f.theta_m);
    tt_d_u32(&g, d->f.theta_ol);
    tt_d_i16(&g, d->f.speed);
    tt_d_i16(&g, d->f.speed_f);
    tt_d_i16(&g, d->f.psi_mag);
    tt_d_u16(&g, (uint16_t)d->f.phase_k);
    tt_d_i16(&g, d->s.id_ref);
    tt_d_i16(&g, d->f.vdc);
    tt_d_dq(&g, &d->f.i_dq);
    tt_d_abc(&g, &d->f.i_abc);
    tt_d_ab(&g, &d->f.u_last);
    tt_d_i32(&g, d->f.flux.psi_alpha);
    tt_d_i32(&g, d->f.flux.psi_beta);
    tt_d_u32(&g, d->f.pll.theta_acc);
    tt_d_i32(&g, d->f.pi_id.integ);
    tt_d_i32(&g, d->f.pi_iq.integ);
    tt_d_i32(&g, d->s.fw.pi.integ);
    tt_d_u8(&g, d->f.trip_count);
    tt_d_u8(&g, d->f.clamp_count);
    return tt_d_final(&g);
}

uint32_t tt_drive_tick_digest(const qfoc_drive_t *d, const qfoc_tick_out_t *out)
{
    tt_digest_t g;
    uint16_t b;
    uint16_t h;
    tt_d_init(&g);
    tt_d_u8(&g, out->tx_len);
    for (b = 0u; (b < (uint16_t)out->tx_len) && (b < QFOC_LIN_FRAME_MAX); b++) {
        tt_d_u8(&g, out->tx[b]);
    }
    tt_d_bool(&g, out->can_send);
    if (out->can_send) {
        tt_d_can(&g, &out->can);
    }
    tt_d_u8(&g, d->s.sm.state);
    tt_d_u8(&g, d->s.sm.sub);
    tt_d_u16(&g, d->s.sm.faults);
    tt_d_u16(&g, d->s.sm.first_fault);
    tt_d_u16(&g, d->s.sm.t_state);
    tt_d_u16(&g, d->s.sm.t_sub);
    tt_d_i16(&g, d->s.speed_target);
    tt_d_i16(&g, d->s.speed_ref);
    tt_d_i16(&g, d->s.ol_speed);
    tt_d_i16(&g, d->s.id_ref);
    tt_d_i16(&g, d->s.iq_ref);
    tt_d_u16(&g, d->s.lead);
    tt_d_i16(&g, d->s.util);
    tt_d_i32(&g, d->s.pi_speed.integ);
    for (h = 0u; h < QFOC_TRQCOMP_HARMONICS; h++) {
        tt_d_i32(&g, d->s.tc.a[h]);
        tt_d_i32(&g, d->s.tc.b[h]);
    }
    tt_d_u16(&g, d->s.offset_u);
    tt_d_u16(&g, d->s.offset_v);
    tt_d_u16(&g, d->s.link.n_ok);
    tt_d_u32(&g, d->s.run_ms);
    tt_d_bool(&g, d->s.table_ok);
    tt_d_bool(&g, d->s.calib_done);
    tt_d_bool(&g, d->s.hs);
    tt_d_bool(&g, qfoc_drive_is_valid(d));
    return tt_d_final(&g);
}

static qfoc_drive_t tt_drv;

/* drive_init: [byte offset, XOR mask, reseal] on the reference table (as params), then
   one fast step at mid-scale and one tick without a frame.
   Digest: init status, drive_is_valid, the fast step's and the tick's digests. */
static void tt_replay_drive_init(tt_ctx_t *c)
{
    static qfoc_param_table_t t;
    uint32_t k;
    for (k = 0u; k < c->data->n; k++) {
        tt_digest_t d;
        qfoc_adc_t adc;
        qfoc_tick_in_t in;
        qfoc_pwm_t pwm;
        qfoc_tick_out_t out;
        tt_table_mutant(c, k, &t);
        (void)memset(&tt_drv, 0, sizeof tt_drv);
        tt_d_init(&d);
        tt_d_i32(&d, qfoc_drive_init(&tt_drv, &t));
        tt_d_bool(&d, qfoc_drive_is_valid(&tt_drv));
        adc.iu = QFOC_ADC_MID;
        adc.iv = QFOC_ADC_MID;
        adc.vdc = 2621u;   /* 320 V x 4096 / 500 V */
        pwm = qfoc_drive_fast_step(&tt_drv, &adc);
        tt_d_u32(&d, tt_drive_fast_digest(&tt_drv, &pwm));
        in.t_ipm = 250;
        in.t_pcb = 250;
        in.rx = NULL;
        in.rx_len = 0u;
        out = qfoc_drive_tick(&tt_drv, &in);
        tt_d_u32(&d, tt_drive_tick_digest(&tt_drv, &out));
        tt_emit(c, &d);
    }
}

/* One tick of a drive run: vector t of the tick group c (t_ipm, t_pcb, rx_len, the frame's
   bytes), its digest emitted. */
static void tt_replay_tick(tt_ctx_t *c, uint32_t t)
{
    static uint8_t rx[TT_TICK_RX_MAX];
    tt_digest_t d;
    qfoc_tick_in_t in;
    qfoc_tick_out_t out;
    uint16_t len = tt_in(c, t, 2u);
    if (len > (uint16_t)TT_TICK_RX_MAX) {
        len = (uint16_t)TT_TICK_RX_MAX;
    }
    tt_in_bytes(c, t, 3u, rx, (uint16_t)TT_TICK_RX_MAX);
    in.t_ipm = tt_in_i16(c, t, 0u);
    in.t_pcb = tt_in_i16(c, t, 1u);
    in.rx = rx;
    in.rx_len = (uint8_t)len;
    out = qfoc_drive_tick(&tt_drv, &in);
    tt_d_init(&d);
    tt_d_u32(&d, tt_drive_tick_digest(&tt_drv, &out));
    tt_emit(c, &d);
}

/* drive_fast [iu, iv, vdc] and drive_tick [t_ipm, t_pcb, rx_len, 6 words = 12 frame
   bytes]: the closed-loop run, replayed in its order: after every (f_pwm / 1 kHz)-th
   fast step, one tick.  c[0] is drive_fast, c[1] drive_tick.  REQ-TGT-003: the open-loop
   replay of the recorded inputs reproduces the closed-loop run's outputs. */
static void tt_replay_drive(tt_ctx_t *c)
{
    const uint32_t ppm = ((uint32_t)qfoc_params_reference.f_pwm_hz + 500u) / 1000u;
    uint32_t k;
    uint32_t t = 0u;
    (void)memset(&tt_drv, 0, sizeof tt_drv);
    (void)qfoc_drive_init(&tt_drv, &qfoc_params_reference);
    for (k = 0u; k < c[0].data->n; k++) {
        tt_digest_t d;
        qfoc_adc_t adc;
        qfoc_pwm_t pwm;
        adc.iu = tt_in(&c[0], k, 0u);
        adc.iv = tt_in(&c[0], k, 1u);
        adc.vdc = tt_in(&c[0], k, 2u);
        pwm = qfoc_drive_fast_step(&tt_drv, &adc);
        tt_d_init(&d);
        tt_d_u32(&d, tt_drive_fast_digest(&tt_drv, &pwm));
        tt_emit(&c[0], &d);
        if ((((k + 1u) % ppm) == 0u) && (t < c[1].data->n)) {
            tt_replay_tick(&c[1], t);
            t++;
        }
    }
}

/* ------------------------------------------------------------------ drive_shunt.h */

uint32_t tt_drive_shunt_digest(const qfoc_drive_t *d, const qfoc_drive_shunt_t *sd,
                               const qfoc_adc_t *codes, const qfoc_pwm_t *out,
                               const qfoc_shunt_plan_t *plan)
{
    tt_digest_t g;
    tt_d_init(&g);
    tt_d_u32(&g, tt_drive_fast_digest(d, out));
    tt_d_u16(&g, codes->iu);
    tt_d_u16(&g, codes->iv);
    tt_d_u16(&g, codes->vdc);
    tt_d_u16(&g, plan->up[0]);
    tt_d_u16(&g, plan->up[1]);
    tt_d_u16(&g, plan->up[2]);
    tt_d_u16(&g, plan->down[0]);
    tt_d_u16(&g, plan->down[1]);
    tt_d_u16(&g, plan->down[2]);
    tt_d_u16(&g, plan->trig[0]);
    tt_d_u16(&g, plan->trig[1]);
    tt_d_u8(&g, plan->hi);
    tt_d_u8(&g, plan->lo);
    tt_d_bool(&g, plan->ok);
    tt_d_bool(&g, plan->shifted);
    tt_d_u8(&g, sd->status);
    tt_d_bool(&g, sd->lost);
    tt_d_u8(&g, sd->head);
    tt_d_u16(&g, sd->rec.n_hold);
    tt_d_i16(&g, sd->rec.i[0]);
    tt_d_i16(&g, sd->rec.i[1]);
    tt_d_i16(&g, sd->rec.i[2]);
    return tt_d_final(&g);
}

static qfoc_drive_shunt_t tt_sd;

/* drive_shunt_fast [iu, iv, vdc, s1, s2] and drive_shunt_tick (as drive_tick): the
   closed-loop run on the single-shunt table, replayed in its order: each period the three
   calls of the port's interrupt (measure, fast step, output) and the plan, after every
   (f_pwm / 1 kHz)-th period one tick.  REQ-TGT-003 as for the two-sensor drive. */
static void tt_replay_drive_shunt(tt_ctx_t *c)
{
    const uint32_t ppm = ((uint32_t)qfoc_params_reference_shunt.f_pwm_hz + 500u) / 1000u;
    uint32_t k;
    uint32_t t = 0u;
    (void)memset(&tt_drv, 0, sizeof tt_drv);
    (void)memset(&tt_sd, 0, sizeof tt_sd);
    (void)qfoc_drive_init(&tt_drv, &qfoc_params_reference_shunt);
    (void)qfoc_drive_shunt_init(&tt_sd, &tt_drv, 2u);
    for (k = 0u; k < c[0].data->n; k++) {
        tt_digest_t d;
        qfoc_adc_t adc;
        qfoc_adc_t codes;
        qfoc_pwm_t pwm;
        const qfoc_shunt_plan_t *plan;
        adc.iu = tt_in(&c[0], k, 0u);
        adc.iv = tt_in(&c[0], k, 1u);
        adc.vdc = tt_in(&c[0], k, 2u);
        codes = qfoc_drive_shunt_measure(&tt_sd, &tt_drv, &adc, tt_in_i16(&c[0], k, 3u),
                                         tt_in_i16(&c[0], k, 4u));
        pwm = qfoc_drive_shunt_output(&tt_sd, qfoc_drive_fast_step(&tt_drv, &codes));
        plan = qfoc_drive_shunt_plan(&tt_sd, &tt_drv);
        tt_d_init(&d);
        tt_d_u32(&d, tt_drive_shunt_digest(&tt_drv, &tt_sd, &codes, &pwm, plan));
        tt_emit(&c[0], &d);
        if ((((k + 1u) % ppm) == 0u) && (t < c[1].data->n)) {
            tt_replay_tick(&c[1], t);
            t++;
        }
    }
}

/* ------------------------------------------------------------------ shunt.h */

/* shunt: [period, t_settle, t_sample, hold_max, cmp u, v, w, s1, s2] -> the check, the
   init's status, the plan, the currents of the plan, those currents referred to the
   instant by qfoc_shunt_align() (s1 / 4 as the angle per period, s2 as the ripple gain, the
   lead 0 or 1 by the vector's parity), the currents of a period without a measurement
   (held or lost), the count. */
static void tt_replay_shunt(tt_ctx_t *c)
{
    uint32_t k;
    for (k = 0u; k < c->data->n; k++) {
        tt_digest_t d;
        qfoc_shunt_cfg_t cfg;
        qfoc_shunt_t s;
        qfoc_shunt_plan_t pl;
        qfoc_q15_t out[3];
        uint16_t cmp[3];
        uint16_t j;
        cfg.period = (uint16_t)tt_in_i16(c, k, 0u);
        cfg.t_settle = (uint16_t)tt_in_i16(c, k, 1u);
        cfg.t_sample = (uint16_t)tt_in_i16(c, k, 2u);
        cfg.hold_max = (uint16_t)tt_in_i16(c, k, 3u);
        for (j = 0u; j < 3u; j++) {
            cmp[j] = (uint16_t)tt_in_i16(c, k, (uint16_t)(4u + j));
        }
        tt_d_init(&d);
        tt_d_bool(&d, qfoc_shunt_cfg_is_valid(&cfg));
        tt_d_u8(&d, qfoc_shunt_init(&s, &cfg));
        (void)memset(&pl, 0, sizeof pl);
        qfoc_shunt_plan(&cfg, cmp, &pl);
        for (j = 0u; j < 3u; j++) {
            tt_d_u16(&d, pl.up[j]);
            tt_d_u16(&d, pl.down[j]);
        }
        tt_d_u16(&d, pl.trig[0]);
        tt_d_u16(&d, pl.trig[1]);
        tt_d_u8(&d, pl.hi);
        tt_d_u8(&d, pl.lo);
        tt_d_bool(&d, pl.ok);
        tt_d_bool(&d, pl.shifted);
        tt_d_u8(&d, qfoc_shunt_currents(&s, &pl, tt_in_i16(c, k, 7u), tt_in_i16(c, k, 8u), out));
        tt_d_i16(&d, out[0]);
        tt_d_i16(&d, out[1]);
        tt_d_i16(&d, out[2]);
        {
            qfoc_q15_t al[3];
            (void)memcpy(al, out, sizeof al);
            qfoc_shunt_align(&cfg, &pl, (int32_t)tt_in_i16(c, k, 7u) / 4, (int32_t)tt_in_i16(c, k, 8u),
                             (uint8_t)(k & 1u), al);
            tt_d_i16(&d, al[0]);
            tt_d_i16(&d, al[1]);
            tt_d_i16(&d, al[2]);
        }
        pl.ok = false;
        tt_d_u8(&d, qfoc_shunt_currents(&s, &pl, tt_in_i16(c, k, 8u), tt_in_i16(c, k, 7u), out));
        tt_d_i16(&d, out[0]);
        tt_d_i16(&d, out[1]);
        tt_d_i16(&d, out[2]);
        tt_d_u16(&d, s.n_hold);
        tt_emit(c, &d);
    }
}

/* ------------------------------------------------------------------ the suites */

/* TT_N_SUITES entries (tt.h); a missing one would be all zero, which the runner and the
   generator refuse (tt_runner.c: tt_consistent).  Every group: REQ-TGT-001 (its golden
   vectors), REQ-TGT-002 (its outputs bit-identical on the Cortex-M4F).  The comment right
   above an entry is its group's method tag: how tt_gen.c derives the group's inputs
   (tools/evidence/verif_counts.py reads it). */
const tt_suite_t tt_suites[TT_N_SUITES] = {
    /* Methods: 1b 2048 random int32 in four classes (corners, the Q15 band, near +-2^30,
       uniform); 1c the 33 int32 corners C32 (INT32_MIN, INT32_MAX, +-32767 / 32768, +-2^30,
       ...); 1n the Cortex-M4F build's digests against the host build's */
    { { "q15_sat", NULL }, 1u, tt_replay_q15_sat },
    /* Methods: 1b 2048 random int64 (uniform, near +-(2^31 - 1), int32 and twice int32); 1c
       INT64_MIN, INT64_MAX and the values beside +-2^31; 1n the Cortex-M4F build's digests
       against the host build's */
    { { "q31_sat", NULL }, 1u, tt_replay_q31_sat },
    /* Methods: 1b 2048 random pairs of the classes of rq15 (corners, small, near full scale,
       uniform); 1c every pair of the 16 int16 corners C16 (-32768 .. 32767, +-16384 +-1); 1n
       the Cortex-M4F build's digests against the host build's */
    { { "q15_add", NULL }, 1u, tt_replay_q15_add },
    /* Methods: 1b 2048 random pairs of the classes of rq15; 1c every pair of the 16 int16
       corners C16; 1n the Cortex-M4F build's digests against the host build's */
    { { "q15_sub", NULL }, 1u, tt_replay_q15_sub },
    /* Methods: 1b 1024 random values of the classes of rq15; 1c the 16 int16 corners C16,
       -32768 included; 1n the Cortex-M4F build's digests against the host build's */
    { { "q15_neg", NULL }, 1u, tt_replay_q15_neg },
    /* Methods: 1b 1024 random values of the classes of rq15; 1c the 16 int16 corners C16,
       -32768 included; 1n the Cortex-M4F build's digests against the host build's */
    { { "q15_abs", NULL }, 1u, tt_replay_q15_abs },
    /* Methods: 1b 2048 random pairs of the classes of rq15; 1c every pair of the 16 int16
       corners C16; 1n the Cortex-M4F build's digests against the host build's */
    { { "q15_mul", NULL }, 1u, tt_replay_q15_mul },
    /* Methods: 1b 2048 random int32 of the classes of ri32; 1c the int32 corners C32, and 40 %
       of the draws beside a rounding tie (m 32768 + 16384 + -1, 0, 1); 1n the Cortex-M4F
       build's digests against the host build's */
    { { "q15_from_q30", NULL }, 1u, tt_replay_q15_from_q30 },
    /* Methods: 1b 2048 random pairs of the classes of ri32; 1c every pair of every other int32
       corner of C32; 1n the Cortex-M4F build's digests against the host build's */
    { { "q31_add", NULL }, 1u, tt_replay_q31_add },
    /* Methods: 1b 2048 random (acc, a, b) of the classes of ri32 and rq15; 1c int32 corners
       crossed with int16 corners; 1n the Cortex-M4F build's digests against the host build's */
    { { "q31_mac", NULL }, 1u, tt_replay_q31_mac },
    /* Methods: 1b 2048 random int32 of the classes of ri32; 1c the int32 corners C32, and 40 %
       of the draws beside a rounding tie (m 65536 + 32768 + -1, 0, 1); 1n the Cortex-M4F
       build's digests against the host build's */
    { { "q15_from_q31", NULL }, 1u, tt_replay_q15_from_q31 },
    /* Methods: 1b 1024 random values of the classes of rq15; 1c the 16 int16 corners C16; 1n
       the Cortex-M4F build's digests against the host build's */
    { { "q31_from_q15", NULL }, 1u, tt_replay_q31_from_q15 },
    /* Methods: 1b every one of the 65536 angles (the domain enumerated); 1n the Cortex-M4F
       build's digests against the host build's */
    { { "sin", NULL }, 1u, tt_replay_sin },
    /* Methods: 1b every one of the 65536 angles (the domain enumerated); 1n the Cortex-M4F
       build's digests against the host build's */
    { { "sincos", NULL }, 1u, tt_replay_sincos },
    /* Methods: 1b 8192 random pairs of the classes of rq15; 1c every pair of the C16 corners,
       the axes and diagonals of nine magnitudes (1 .. 32767) exactly and one count off, in all
       eight sign combinations; 1n the Cortex-M4F build's digests against the host build's */
    { { "atan2", NULL }, 1u, tt_replay_atan2 },
    /* Methods: 1b 4096 random uint32 (uniform, shifted down, near squares); 1c 0 .. 4,
       0xFFFFFFFF, 0xFFFE0000 .. 0xFFFE0002, 0x80000000, 0x7FFFFFFF, 0x40000000, 0x3FFFFFFF, q^2
       - 1, q^2, q^2 + 1; 1n the Cortex-M4F build's digests against the host build's */
    { { "isqrt32", NULL }, 1u, tt_replay_isqrt32 },
    /* Methods: 1b 4096 random pairs of the classes of rq15; 1c every pair of the 16 int16
       corners C16; 1n the Cortex-M4F build's digests against the host build's */
    { { "vec_mag", NULL }, 1u, tt_replay_vec_mag },
    /* Methods: 1b 4096 random (d, q, limit), the limits mostly non-negative; 1c every other C16
       corner of d and q crossed with the limits -32768, -1, 0, 1, 15892, 16384, 32767; 1d
       negative limits; 1n the Cortex-M4F build's digests against the host build's */
    { { "circle_limit", NULL }, 1u, tt_replay_circle_limit },
    /* Methods: 1b 4096 random pairs of the classes of rq15; 1c every pair of the 16 int16
       corners C16; 1n the Cortex-M4F build's digests against the host build's */
    { { "clarke", NULL }, 1u, tt_replay_clarke },
    /* Methods: 1b 4096 random vectors with the sine and cosine of a real angle (75 %) or any
       pair; 1c C16 corners at the axis angles, (-32768, -32768), (32767, 32767) and 45 degrees;
       1d sine and cosine words that are not a unit pair; 1n the Cortex-M4F build's digests
       against the host build's */
    { { "park", NULL }, 1u, tt_replay_park },
    /* Methods: 1b 4096 random vectors with the sine and cosine of a real angle (75 %) or any
       pair; 1c C16 corners at the axis angles, (-32768, -32768), (32767, 32767) and 45 degrees;
       1d sine and cosine words that are not a unit pair; 1n the Cortex-M4F build's digests
       against the host build's */
    { { "inv_park", NULL }, 1u, tt_replay_inv_park },
    /* Methods: 1b 4096 random pairs of the classes of rq15; 1c every pair of the 16 int16
       corners C16; 1n the Cortex-M4F build's digests against the host build's */
    { { "inv_clarke", NULL }, 1u, tt_replay_inv_clarke },
    /* Methods: 1b 6144 cases: the reference table's configuration, random valid ones, random
       words, vectors of any angle up to 1.3 x the linear range; 1c 30 % on a sector boundary or
       one count beside it, currents around the dead band; 1d invalid configurations and bus
       voltages at or below 0; 1n the Cortex-M4F build's digests against the host build's */
    { { "svpwm", NULL }, 1u, tt_replay_svpwm },
    /* Methods: 1b 4096 random (value, target, step), 70 % of the steps small; 1c every other
       C16 corner for value and target crossed with the steps -32768, -1, 0, 1, 10, 32767; 1n
       the Cortex-M4F build's digests against the host build's */
    { { "ramp", NULL }, 1u, tt_replay_ramp },
    /* Methods: 1b 2048 random pairs of the classes of rq15; 1c every pair of the 16 int16
       corners C16; 1n the Cortex-M4F build's digests against the host build's */
    { { "fault_level", NULL }, 1u, tt_replay_fault_level },
    /* Methods: 1b sequences of 10 .. 120 steps with conditions toggling at random; 1c n = 0, 1,
       2, 3, 5, 10, 100 and 65535, random n; 1n the Cortex-M4F build's digests against the host
       build's */
    { { "debounce", NULL }, 1u, tt_replay_debounce },
    /* Methods: 1b sequences of balanced currents of any amplitude and speed, all phases and one
       per period (alpha3), random thresholds; 1c coefficients and thresholds of any int16,
       -32768; 1d a lost phase in 3 of 5 sequences, phase indices up to 255, corrupted samples
       (5 %); 1l the lost phase and the corrupted samples injected into the currents; 1n the
       Cortex-M4F build's digests against the host build's */
    { { "phase_mon", NULL }, 1u, tt_replay_phase_mon },
    /* Methods: 1b sequences of 20 .. 150 steps with random coefficients and inputs, resets; 1c
       coefficients of any int16 (15 %), inputs of the classes of rq15; 1d invalid coefficients;
       1n the Cortex-M4F build's digests against the host build's */
    { { "lpf", NULL }, 1u, tt_replay_lpf },
    /* Methods: 1b sequences of 20 .. 150 steps with random gains, shifts and leaks, resets; 1c
       shifts 16 .. 255 and any int16 gains and leaks (invalid); 1d invalid parameters; 1n the
       Cortex-M4F build's digests against the host build's */
    { { "leaky", NULL }, 1u, tt_replay_leaky },
    /* Methods: 1b sequences of 20 .. 200 steps with the reference table's four PIs, random
       valid-looking and random parameters, errors wandering and jumping; 1c shifts up to 20,
       any int16 limits; 1d invalid parameters; 1n the Cortex-M4F build's digests against the
       host build's */
    { { "pi", NULL }, 1u, tt_replay_pi },
    /* Methods: 1b sequences of 50 .. 300 steps with the reference table's field weakening or
       random parameters, utilisations wandering around the level, enable on and off; 1c
       utilisations of any int16 (5 %); 1d invalid parameters; 1n the Cortex-M4F build's digests
       against the host build's */
    { { "fw", NULL }, 1u, tt_replay_fw },
    /* Methods: 1b sequences of 50 .. 400 steps of rotating voltages and currents at random
       speeds of both signs, the reference table's or random parameters; 1c shifts 16 .. 40 and
       any int16 parameters, inputs of the classes of rq15 (5 %); 1d invalid parameters; 1n the
       Cortex-M4F build's digests against the host build's */
    { { "flux", NULL }, 1u, tt_replay_flux },
    /* Methods: 1b sequences of 50 .. 400 steps of a rotating flux or EMF at random speeds of
       both signs and amplitudes (10 % below 200: coasting), the reference table's or random
       parameters; 1c k_theta of any uint16, any int16 parameters; 1d invalid parameters; 1n the
       Cortex-M4F build's digests against the host build's */
    { { "pll", NULL }, 1u, tt_replay_pll },
    /* Methods: 1b sequences of 50 .. 300 steps of rotating voltages and currents at random
       speeds of both signs, random parameters; 1c k_theta of any uint16 and any int16
       parameters (10 %), inputs of the classes of rq15 (5 %); 1d invalid parameters; 1n the
       Cortex-M4F build's digests against the host build's */
    { { "emf", NULL }, 1u, tt_replay_emf },
    /* Methods: 1b sequences of 50 .. 300 steps of rotating voltages and currents at random
       speeds of both signs, random observer parameters; 1c shifts 16 .. 30, k_theta of any
       uint16 and any int16 parameters (10 %); 1d invalid parameters; 1n the Cortex-M4F build's
       digests against the host build's */
    { { "dob", NULL }, 1u, tt_replay_dob },
    /* Methods: 1b sequences of 50 .. 300 angle steps, forward and reverse, pole pairs 1 .. 16;
       1c steps of any int16 (-32768 .. 32767) and pole-pair counts 0 .. 255; 1d invalid
       pole-pair counts; 1n the Cortex-M4F build's digests against the host build's */
    { { "mech", NULL }, 1u, tt_replay_mech },
    /* Methods: 1b sequences of 100 .. 600 steps with the reference table's or random
       parameters, speeds of both signs inside and outside the window, learning, output and
       phase calls; 1c speeds of any int16, pole pairs 0 .. 40; 1d invalid parameters; 1n the
       Cortex-M4F build's digests against the host build's */
    { { "trqcomp", NULL }, 1u, tt_replay_trqcomp },
    /* Methods: 1b every identifier 0 .. 255 (the domain enumerated); 1n the Cortex-M4F build's
       digests against the host build's */
    { { "lin_pid", NULL }, 1u, tt_replay_lin_pid },
    /* Methods: 1b 4096 random identifiers and byte strings; 1c lengths 0 .. 12, 30 % of the
       bytes 0xFF; 1n the Cortex-M4F build's digests against the host build's */
    { { "lin_checksum", NULL }, 1u, tt_replay_lin_checksum },
    /* Methods: 1b 4096 frames for the reference or a random configuration, well-formed or with
       one defect; 1c lengths 0 .. 255, targets up to 65535; 1d one bit flipped, a wrong length,
       a reserved bit or byte, random bytes, another identifier; 1l each defect injected into a
       well-formed frame; 1n the Cortex-M4F build's digests against the host build's */
    { { "lin_decode", NULL }, 1u, tt_replay_lin_decode },
    /* Methods: 1b 2048 status records in the drive's ranges (70 %) or any words, with the
       reference or a random configuration; 1c words of any value (saturation of the payload);
       1n the Cortex-M4F build's digests against the host build's */
    { { "lin_encode", NULL }, 1u, tt_replay_lin_encode },
    /* Methods: 1b sequences of 50 .. 400 milliseconds with frames, silence and CAN status
       requests; 1c short timeouts of 1 .. 30 ms, so that the link is lost within the run; 1d
       frames with one defect, random bytes, silence; 1l the defects injected into well-formed
       frames; 1n the Cortex-M4F build's digests against the host build's */
    { { "link", NULL }, 1u, tt_replay_link },
    /* Methods: 1b 2048 random register values and bytes; 1c the registers 0, 1, 0xFFFFFFFF,
       0x80000000, 0x7FFFFFFF and the polynomial with every 17th byte; 1n the Cortex-M4F build's
       digests against the host build's */
    { { "crc32_byte", NULL }, 1u, tt_replay_crc32_byte },
    /* Methods: 1b the reference table unchanged and resealed, every byte mutated with a random
       mask, 768 random single-bit mutations, resealed or not; 1d corrupted tables and tables
       written wrongly with a correct CRC; 1l each mutation injected into the table; 1n the
       Cortex-M4F build's digests against the host build's */
    { { "params", NULL }, 1u, tt_replay_params },
    /* Methods: 1b sequences of 100 .. 600 ticks with the reference table's or random times,
       input bits toggling at random; 1c times 0 .. 40 and any uint16; 1d fault words with one
       bit or any bits, bits of undefined meaning; 1n the Cortex-M4F build's digests against the
       host build's */
    { { "sm", NULL }, 1u, tt_replay_sm },
    /* Methods: 1b the reference table unchanged and resealed, every byte mutated with a random
       mask, 256 random single-bit mutations, resealed or not; 1d an init from a corrupted
       table; 1l each mutation injected into the table; 1n the Cortex-M4F build's digests
       against the host build's */
    { { "drive_init", NULL }, 1u, tt_replay_drive_init },
    /* Methods: 1b a closed-loop run on the plant: start, field weakening at 5800 rpm,
       high-speed inductances, torque compensation, 0.05 A rms current noise; 1d two command
       frames with a wrong checksum, an over-current pulse; 1l the +50 A pulse on the sensed
       phase-u current and the wrong checksums injected; 1n the Cortex-M4F build's digests at
       both entry points against the host build's, recorded in the closed loop and replayed open
       loop */
    { { "drive_fast", "drive_tick" }, 2u, tt_replay_drive },
    /* Methods: 1b 4096 rows: configurations of 8 and 16 kHz, the smallest and largest
       period, random ones, random bit patterns, compare values near half the period (both
       vectors short), in any order, random; 1c the window at a quarter period and one tick
       beyond, hold 1 .. 16 and out of range, compare values at 0, at the period and beyond;
       1n the Cortex-M4F build's digests against the host build's */
    { { "shunt", NULL }, 1u, tt_replay_shunt },
    /* Methods: 1b a closed-loop run on the plant's DC-link current with the single-shunt
       table: cold start (edges shifted at standstill and low speed), 3000 and 5000 rpm,
       torque compensation, 0.05 A rms noise; 1d two command frames with a wrong checksum, an
       over-current pulse on both DC-link samples; 1l the pulse and the wrong checksums
       injected; 1n the Cortex-M4F build's digests of the three calls, the plan and the tick
       against the host build's, recorded in the closed loop and replayed open loop */
    { { "drive_shunt_fast", "drive_shunt_tick" }, 2u, tt_replay_drive_shunt },
};
