/**
 * @file qfoc_ident.c
 * @brief Standstill identification: the steps, bounds and window sums of ident.h.
 *
 * Requirements: REQ-IDENT-001 .. REQ-IDENT-006 (specs/requirements/ident.md).
 */
#include "qfoc/ident.h"
#include "qfoc/q15.h"

/* cos(2 pi k / 16) in Q15 (rounded 32767 cos); sin(2 pi k / 16) is entry (k + 12) % 16. */
static const int16_t ident_cos16[16] = {
    32767, 30273, 23170, 12539, 0, -12539, -23170, -30273,
    -32767, -30273, -23170, -12539, 0, 12539, 23170, 30273
};

/*@
  assigns \nothing;
  ensures result: \result <==> IdentAbs(x) > lim;
*/
static bool ident_above(qfoc_q15_t x, qfoc_q15_t lim)
{
    const int32_t a = (x < 0) ? -(int32_t)x : (int32_t)x;
    return a > (int32_t)lim;
}

/* Saturating 32-bit accumulation of a term |x| <= 2^17. */
/*@
  requires term: -131072 <= x <= 131072;
  assigns \nothing;
  ensures result: \result == ((s + x > QFOC_IDENT_SUM32_MAX) ? QFOC_IDENT_SUM32_MAX :
                              (s + x < -QFOC_IDENT_SUM32_MAX) ? -QFOC_IDENT_SUM32_MAX : s + x);
*/
static int32_t ident_acc32(int32_t s, int32_t x)
{
    int32_t r;
    if ((x > 0) && (s > (QFOC_IDENT_SUM32_MAX - x))) {
        r = QFOC_IDENT_SUM32_MAX;
    } else if ((x < 0) && (s < (-QFOC_IDENT_SUM32_MAX - x))) {
        r = -QFOC_IDENT_SUM32_MAX;
    } else {
        r = s + x;
    }
    return r;
}

/* Saturating 64-bit accumulation of the product of a term |x| <= 2^17 and a table
   value |c| <= 32767 (|x c| < 2^32) to any sum s (first brought within the bound). */
/*@
  logic integer IdentSat64(integer v) =
    (v > QFOC_IDENT_SUM64_MAX) ? QFOC_IDENT_SUM64_MAX :
    (v < -QFOC_IDENT_SUM64_MAX) ? -QFOC_IDENT_SUM64_MAX : v;
*/
/*@
  requires term: -131072 <= x <= 131072 && -32767 <= c <= 32767;
  assigns \nothing;
  ensures result: \result == IdentSat64(IdentSat64(s) + x * c);
*/
static int64_t ident_acc64(int64_t s, int32_t x, int16_t c)
{
    const int64_t t = (int64_t)x * (int64_t)c;
    int64_t r = s;
    if (r > QFOC_IDENT_SUM64_MAX) {
        r = QFOC_IDENT_SUM64_MAX;
    } else if (r < -QFOC_IDENT_SUM64_MAX) {
        r = -QFOC_IDENT_SUM64_MAX;
    } else {
        /* within the bound */
    }
    r += t;
    if (r > QFOC_IDENT_SUM64_MAX) {
        r = QFOC_IDENT_SUM64_MAX;
    } else if (r < -QFOC_IDENT_SUM64_MAX) {
        r = -QFOC_IDENT_SUM64_MAX;
    } else {
        /* within the bound */
    }
    return r;
}

/*@
  requires valid: \valid(z);
  assigns *z;
  ensures zero: z->n == 0 && z->i_a == 0 && z->i_b == 0 && z->u_a == 0 && z->u_b == 0 &&
                z->vdc == 0 && z->vb_cmd == 0 && z->u_c == 0 && z->u_s == 0 &&
                z->i_c == 0 && z->i_s == 0 && z->j_c == 0 && z->j_s == 0;
*/
static void ident_zero(qfoc_ident_sums_t *z)
{
    z->n = 0;
    z->i_a = 0;
    z->i_b = 0;
    z->u_a = 0;
    z->u_b = 0;
    z->vdc = 0;
    z->vb_cmd = 0;
    z->u_c = 0;
    z->u_s = 0;
    z->i_c = 0;
    z->i_s = 0;
    z->j_c = 0;
    z->j_s = 0;
}

/*@
  requires valid: \valid(id);
  assigns id->rec[0 .. QFOC_IDENT_STEPS - 1][0 .. 1];
*/
static void ident_clear_record(qfoc_ident_t *id)
{
    uint8_t s;
    /*@
      loop invariant range: 0 <= s <= QFOC_IDENT_STEPS;
      loop assigns s, id->rec[0 .. QFOC_IDENT_STEPS - 1][0 .. 1];
      loop variant QFOC_IDENT_STEPS - s;
    */
    for (s = 0u; s < QFOC_IDENT_STEPS; s++) {
        ident_zero(&id->rec[s][0]);
        ident_zero(&id->rec[s][1]);
    }
}

/* Both current loops from one parameter set. */
/*@
  requires valid: \valid(id) && \valid_read(p);
  requires sep: \separated(id, p);
  assigns id->pi_a, id->pi_b;
  ensures inv: PiValid(&id->pi_a) && PiValid(&id->pi_b);
  ensures params: PiParamsValid(p) ==> id->pi_a.params == *p && id->pi_b.params == *p;
*/
static void ident_init_pi(qfoc_ident_t *id, const qfoc_pi_params_t *p)
{
    (void)qfoc_pi_init(&id->pi_a, p);
    (void)qfoc_pi_init(&id->pi_b, p);
}

bool qfoc_ident_cfg_is_valid(const qfoc_ident_cfg_t *c)
{
    bool ok = (c->i_lo > 0) && (c->i_hi > c->i_lo) && (c->i_lim > c->i_hi);
    ok = ok && (c->i_ramp > 0) && (c->v_inj > 0) && (c->v_move > 0) && (c->vdc_min > 0);
    ok = ok && (c->n_align > 0u) && (c->n_settle > 0u);
    ok = ok && (c->win_shift >= QFOC_IDENT_WIN_MIN) && (c->win_shift <= QFOC_IDENT_WIN_MAX);
    ok = ok && qfoc_pi_params_is_valid(&c->pi) && (c->pi.out_min < 0) && (c->pi.out_max > 0);
    ok = ok && qfoc_svpwm_cfg_is_valid(&c->pwm) && (c->pwm.dt_comp == 0u);
    return ok;
}

void qfoc_ident_init(qfoc_ident_t *id)
{
    static const qfoc_pi_params_t off = { 0, 0u, 0, 0u, 0, 0 };
    ident_clear_record(id);
    id->cfg.i_lo = 0;
    id->cfg.i_hi = 0;
    id->cfg.i_lim = 0;
    id->cfg.i_ramp = 0;
    id->cfg.v_inj = 0;
    id->cfg.v_move = 0;
    id->cfg.vdc_min = 0;
    id->cfg.n_align = 0u;
    id->cfg.n_settle = 0u;
    id->cfg.win_shift = 0u;
    id->cfg.pi = off;
    id->cfg.pwm.period = 0u;
    id->cfg.pwm.dt_comp = 0u;
    id->cfg.pwm.i_deadband = 0;
    id->cfg.pwm.vdc_min = 0;
    id->ref = 0;
    id->n = 0u;
    id->step = QFOC_IDENT_ALIGN;
    id->result = QFOC_IDENT_IDLE;
    id->k = 0u;
    ident_init_pi(id, &off);
}

uint8_t qfoc_ident_start(qfoc_ident_t *id, const qfoc_ident_cfg_t *c)
{
    uint8_t r;
    qfoc_ident_init(id);
    if (qfoc_ident_cfg_is_valid(c)) {
        id->cfg = *c;
        ident_init_pi(id, &c->pi);
        r = QFOC_IDENT_RUNNING;
    } else {
        r = QFOC_IDENT_ERR_CFG;
    }
    id->result = r;
    return r;
}

void qfoc_ident_abort(qfoc_ident_t *id)
{
    if (id->result == QFOC_IDENT_RUNNING) {
        id->result = QFOC_IDENT_ERR_ABORT;
    }
}

/* The alpha current level of a step. */
/*@
  requires cfg: IdentCfgValid(c);
  assigns \nothing;
  ensures result: 0 < \result <= c->i_hi;
*/
static qfoc_q15_t ident_level(const qfoc_ident_cfg_t *c, uint8_t step)
{
    return (step == QFOC_IDENT_R_LO) ? c->i_lo : c->i_hi;
}

/* The reference one period on: towards the level by at most i_ramp. */
/*@
  requires ranges: 0 <= ref && 0 < level && 0 < ramp;
  assigns \nothing;
  ensures result: 0 <= \result && (\result <= ref || \result <= level);
  ensures up: ref <= level ==> \result <= level;
  ensures down: ref > level ==> \result <= ref;
*/
static qfoc_q15_t ident_ramp(qfoc_q15_t ref, qfoc_q15_t level, qfoc_q15_t ramp)
{
    const int32_t up = (int32_t)ref + (int32_t)ramp;
    const int32_t down = (int32_t)ref - (int32_t)ramp;
    qfoc_q15_t r;
    if (ref <= level) {
        r = (up >= (int32_t)level) ? level : (qfoc_q15_t)up;
    } else {
        r = (down <= (int32_t)level) ? level : (qfoc_q15_t)down;
    }
    return r;
}

/* Add this period to the half window's sums. */
/*@
  requires valid: \valid(z) && \valid_read(i) && \valid_read(cmp + (0 .. 2));
  requires sep: \separated(z, i) && \separated(z, cmp + (0 .. 2));
  requires cmp_range: \forall integer j; 0 <= j < 3 ==> cmp[j] <= 32767;
  requires k: k <= 15;
  assigns *z;
*/
static void ident_accumulate(qfoc_ident_sums_t *z, const qfoc_ab_t *i, const uint16_t *cmp,
                             qfoc_q15_t vdc, qfoc_q15_t vb_cmd, bool beta, uint8_t k)
{
    const int32_t ua = (2 * (int32_t)cmp[0]) - (int32_t)cmp[1] - (int32_t)cmp[2];
    const int32_t ub = (int32_t)cmp[1] - (int32_t)cmp[2];
    const int16_t c = ident_cos16[k];
    const int16_t s = ident_cos16[(uint8_t)((k + 12u) & 15u)];
    const int32_t ux = beta ? ub : ua;
    const int32_t ix = beta ? (int32_t)i->beta : (int32_t)i->alpha;
    const int32_t iy = beta ? (int32_t)i->alpha : (int32_t)i->beta;
    z->n = ident_acc32(z->n, 1);
    z->i_a = ident_acc32(z->i_a, (int32_t)i->alpha);
    z->i_b = ident_acc32(z->i_b, (int32_t)i->beta);
    z->u_a = ident_acc32(z->u_a, ua);
    z->u_b = ident_acc32(z->u_b, ub);
    z->vdc = ident_acc32(z->vdc, (int32_t)vdc);
    z->vb_cmd = ident_acc32(z->vb_cmd, (int32_t)vb_cmd);
    z->u_c = ident_acc64(z->u_c, ux, c);
    z->u_s = ident_acc64(z->u_s, ux, s);
    z->i_c = ident_acc64(z->i_c, ix, c);
    z->i_s = ident_acc64(z->i_s, ix, s);
    z->j_c = ident_acc64(z->j_c, iy, c);
    z->j_s = ident_acc64(z->j_s, iy, s);
}

/* The verdict at a window's end: QFOC_IDENT_RUNNING (go on) or the error. */
/*@
  requires valid: \valid_read(id);
  requires inv: IdentValid(id) && id->result == QFOC_IDENT_RUNNING;
  assigns \nothing;
  ensures result: \result == QFOC_IDENT_RUNNING || \result == QFOC_IDENT_ERR_NO_CURRENT ||
                  \result == QFOC_IDENT_ERR_MOVED;
*/
static uint8_t ident_verdict(const qfoc_ident_t *id)
{
    const qfoc_ident_sums_t *h0 = &id->rec[id->step][0];
    const qfoc_ident_sums_t *h1 = &id->rec[id->step][1];
    const int64_t m = (int64_t)((uint32_t)1u << id->cfg.win_shift);
    const int64_t level = (int64_t)ident_level(&id->cfg, id->step);
    const int64_t sa = (int64_t)h0->i_a + (int64_t)h1->i_a;
    const int64_t sb = (int64_t)h0->i_b + (int64_t)h1->i_b;
    const int64_t sv = (int64_t)h0->vb_cmd + (int64_t)h1->vb_cmd;
    const int64_t tol = (m * level) / 4;
    const int64_t ea = sa - (m * level);
    uint8_t r = QFOC_IDENT_RUNNING;
    if ((ea > tol) || (ea < -tol) || (sb > tol) || (sb < -tol)) {
        r = QFOC_IDENT_ERR_NO_CURRENT;
    } else if ((id->step != QFOC_IDENT_ALIGN) &&
               ((sv > (m * (int64_t)id->cfg.v_move)) || (sv < -(m * (int64_t)id->cfg.v_move)))) {
        r = QFOC_IDENT_ERR_MOVED;
    } else {
        /* both bounds hold */
    }
    return r;
}

qfoc_pwm_t qfoc_ident_step(qfoc_ident_t *id, const qfoc_ab_t *i, qfoc_q15_t vdc)
{
    qfoc_pwm_t out;
    const uint16_t mid = (uint16_t)(id->cfg.pwm.period / 2u);
    out.cmp[0] = mid;
    out.cmp[1] = mid;
    out.cmp[2] = mid;
    out.enable = false;
    if (id->result == QFOC_IDENT_RUNNING) {
        if (ident_above(i->alpha, id->cfg.i_lim) || ident_above(i->beta, id->cfg.i_lim)) {
            id->result = QFOC_IDENT_ERR_OC;
        } else if (vdc < id->cfg.vdc_min) {
            id->result = QFOC_IDENT_ERR_BUS;
        } else {
            static const qfoc_abc_t no_dtc = { 0, 0, 0 };
            const uint16_t settle = (id->step == QFOC_IDENT_ALIGN) ? id->cfg.n_align
                                                                    : id->cfg.n_settle;
            const uint16_t half = (uint16_t)(1u << (id->cfg.win_shift - 1u));
            const qfoc_q15_t level = ident_level(&id->cfg, id->step);
            qfoc_ab_t v;
            qfoc_q15_t inj;
            qfoc_svpwm_out_t so;
            id->ref = ident_ramp(id->ref, level, id->cfg.i_ramp);
            v.alpha = qfoc_pi_step(&id->pi_a, qfoc_q15_sub(id->ref, i->alpha));
            if (id->step == QFOC_IDENT_ALIGN) {
                /* the beta axis short-circuited through the inverter: the current a
                   swinging rotor's back-EMF drives there brakes it */
                v.beta = 0;
            } else {
                v.beta = qfoc_pi_step(&id->pi_b, qfoc_q15_neg(i->beta));
            }
            inj = qfoc_q15_mul(id->cfg.v_inj, ident_cos16[id->k]);
            if (id->step == QFOC_IDENT_L_D) {
                v.alpha = qfoc_q15_add(v.alpha, inj);
            } else if (id->step == QFOC_IDENT_L_Q) {
                v.beta = qfoc_q15_add(v.beta, inj);
            } else {
                /* no injection */
            }
            qfoc_svpwm_step(&id->cfg.pwm, &v, vdc, &no_dtc, &so);
            out.cmp[0] = so.cmp[0];
            out.cmp[1] = so.cmp[1];
            out.cmp[2] = so.cmp[2];
            out.enable = true;
            if (id->n >= settle) {
                const uint8_t h = ((id->n - (uint32_t)settle) >= (uint32_t)half) ? 1u : 0u;
                ident_accumulate(&id->rec[id->step][h], i, so.cmp, vdc, v.beta,
                                 id->step == QFOC_IDENT_L_Q, id->k);
            }
            id->k = (uint8_t)((id->k + 1u) & 15u);
            id->n++;
            if (id->n >= ((uint32_t)settle + (2u * (uint32_t)half))) {
                const uint8_t r = ident_verdict(id);
                if (r != QFOC_IDENT_RUNNING) {
                    id->result = r;
                } else if (id->step == QFOC_IDENT_L_Q) {
                    id->result = QFOC_IDENT_DONE;
                } else {
                    id->step++;
                    id->n = 0u;
                }
            }
            if (id->result != QFOC_IDENT_RUNNING) {
                /* the mode ended at this window's end: this period's compare values
                   (already in the sums) are not applied */
                out.cmp[0] = mid;
                out.cmp[1] = mid;
                out.cmp[2] = mid;
                out.enable = false;
            }
        }
    }
    return out;
}

uint8_t qfoc_ident_result(const qfoc_ident_t *id)
{
    return id->result;
}

uint8_t qfoc_ident_step_now(const qfoc_ident_t *id)
{
    return id->step;
}

bool qfoc_ident_sums(const qfoc_ident_t *id, uint8_t step, uint8_t half,
                     qfoc_ident_sums_t *out)
{
    bool ok = false;
    if ((step < QFOC_IDENT_STEPS) && (half < 2u)) {
        *out = id->rec[step][half];
        ok = true;
    } else {
        ident_zero(out);
    }
    return ok;
}

/* Field f (0 .. 12, qfoc_ident_sums_t's order) of a half window's sums. */
/*@
  requires valid: \valid_read(z);
  assigns \nothing;
*/
static int64_t ident_field(const qfoc_ident_sums_t *z, uint8_t f)
{
    int64_t v;
    switch (f) {
    case 0u: v = (int64_t)z->n; break;
    case 1u: v = (int64_t)z->i_a; break;
    case 2u: v = (int64_t)z->i_b; break;
    case 3u: v = (int64_t)z->u_a; break;
    case 4u: v = (int64_t)z->u_b; break;
    case 5u: v = (int64_t)z->vdc; break;
    case 6u: v = (int64_t)z->vb_cmd; break;
    case 7u: v = z->u_c; break;
    case 8u: v = z->u_s; break;
    case 9u: v = z->i_c; break;
    case 10u: v = z->i_s; break;
    case 11u: v = z->j_c; break;
    default: v = z->j_s; break;
    }
    return v;
}

bool qfoc_ident_frame(const qfoc_ident_t *id, uint16_t k, uint8_t buf[8])
{
    static const int64_t lim48 = 140737488355327LL;  /* 2^47 - 1 */
    bool ok = true;
    uint8_t b;
    /*@
      loop invariant range: 0 <= b <= 8;
      loop assigns b, buf[0 .. 7];
      loop variant 8 - b;
    */
    for (b = 0u; b < 8u; b++) {
        buf[b] = 0u;
    }
    if (k == 0u) {
        buf[0] = 0xA5u;
        buf[1] = id->result;
        buf[2] = id->step;
        buf[3] = id->cfg.win_shift;
        buf[4] = (uint8_t)(id->cfg.pwm.period & 0xFFu);
        buf[5] = (uint8_t)(id->cfg.pwm.period >> 8u);
        buf[6] = (uint8_t)(QFOC_IDENT_FRAMES & 0xFFu);
        buf[7] = (uint8_t)(QFOC_IDENT_FRAMES >> 8u);
    } else if (k < QFOC_IDENT_FRAMES) {
        const uint16_t j = (uint16_t)(k - 1u);
        const uint8_t step = (uint8_t)(j / (2u * QFOC_IDENT_FIELDS));
        const uint8_t half = (uint8_t)((j / QFOC_IDENT_FIELDS) % 2u);
        const uint8_t field = (uint8_t)(j % QFOC_IDENT_FIELDS);
        int64_t v = ident_field(&id->rec[step][half], field);
        uint64_t u;
        if (v > lim48) {
            v = lim48;
        } else if (v < -lim48) {
            v = -lim48;
        } else {
            /* fits */
        }
        /* the 48-bit two's complement: v + 2^48 for a negative v */
        u = (uint64_t)((v < 0) ? (v + 281474976710656LL) : v);
        buf[0] = (uint8_t)(k & 0xFFu);
        buf[1] = (uint8_t)((32u * step) + (16u * half) + field);
        /*@
          loop invariant range: 2 <= b <= 8;
          loop assigns b, u, buf[2 .. 7];
          loop variant 8 - b;
        */
        for (b = 2u; b < 8u; b++) {
            buf[b] = (uint8_t)(u & 0xFFu);
            u >>= 8u;
        }
    } else {
        ok = false;
    }
    return ok;
}
