/**
 * @file qfoc_ident.c
 * @brief Standstill identification: the steps, bounds and window sums of ident.h.
 *
 * Requirements: REQ-IDENT-001 .. REQ-IDENT-006 (specs/requirements/ident.md).
 */
#include "qfoc/ident.h"
#include "qfoc/q15.h"

/* The PI parameters of the idle state: every gain and limit 0 (a valid set). */
static const qfoc_pi_params_t ident_pi_off = { 0, 0u, 0, 0u, 0, 0 };

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

/*@
  logic integer IdentSat32(integer v) =
    (v > QFOC_IDENT_SUM32_MAX) ? QFOC_IDENT_SUM32_MAX :
    (v < -QFOC_IDENT_SUM32_MAX) ? -QFOC_IDENT_SUM32_MAX : v;
*/

/* Saturating 32-bit accumulation of a term |x| <= 2^17 to any sum s. */
/*@
  requires term: -131072 <= x <= 131072;
  assigns \nothing;
  ensures result: \result == IdentSat32(s + x);
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
    if (r < -QFOC_IDENT_SUM32_MAX) {
        r = -QFOC_IDENT_SUM32_MAX;  /* s = -2^31 and x = 0 */
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
  assigns id->rec;
*/
static void ident_clear_record(qfoc_ident_t *id)
{
    uint8_t s;
    /*@
      loop invariant range: 0 <= s <= QFOC_IDENT_STEPS;
      loop assigns s, id->rec;
      loop variant QFOC_IDENT_STEPS - s;
    */
    for (s = 0u; s < QFOC_IDENT_STEPS; s++) {
        ident_zero(&id->rec.s[s][0]);
        ident_zero(&id->rec.s[s][1]);
    }
}

/* Both current loops from one parameter set. */
/*@
  requires valid: \valid(id) && \valid_read(p);
  requires sep: \separated(id, p);
  assigns id->pi_a, id->pi_b;
  ensures inv: IDENT_PI(&id->pi_a) && IDENT_PI(&id->pi_b);
  ensures params: PiParamsValid(p) ==> id->pi_a.params == *p && id->pi_b.params == *p;
*/
static void ident_init_pi(qfoc_ident_t *id, const qfoc_pi_params_t *p)
{
    (void)qfoc_pi_init(&id->pi_a, p);
    (void)qfoc_pi_init(&id->pi_b, p);
}

/* cppcheck-suppress misra-c2012-8.7 ; DEV-002 */
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

/* The idle configuration: every field 0 (not valid: the mode cannot run on it). */
/*@
  requires valid: \valid(id);
  assigns id->cfg;
*/
static void ident_idle_cfg(qfoc_ident_t *id)
{
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
    id->cfg.pi.kp = 0;
    id->cfg.pi.kp_shift = 0u;
    id->cfg.pi.ki = 0;
    id->cfg.pi.ki_shift = 0u;
    id->cfg.pi.out_min = 0;
    id->cfg.pi.out_max = 0;
    id->cfg.pwm.period = 0u;
    id->cfg.pwm.dt_comp = 0u;
    id->cfg.pwm.i_deadband = 0;
    id->cfg.pwm.vdc_min = 0;
}

/* The state at a step's start with result r: ALIGN, zero reference, an empty record. */
/*@
  requires valid: \valid(id);
  requires result: r <= QFOC_IDENT_ERR_ABORT;
  assigns id->rec, id->ref, id->n, id->step, id->k,
          id->result;
  ensures state: id->step == QFOC_IDENT_ALIGN && id->n == 0 && id->ref == 0 && id->k == 0 &&
                 id->result == r;
*/
static void ident_reset(qfoc_ident_t *id, uint8_t r)
{
    ident_clear_record(id);
    id->ref = 0;
    id->n = 0u;
    id->step = QFOC_IDENT_ALIGN;
    id->k = 0u;
    id->result = r;
}

/* cppcheck-suppress misra-c2012-8.7 ; DEV-002 */
void qfoc_ident_init(qfoc_ident_t *id)
{
    ident_idle_cfg(id);
    ident_init_pi(id, &ident_pi_off);
    ident_reset(id, QFOC_IDENT_IDLE);
}

/* Take a valid configuration. */
/*@
  requires valid: \valid(id) && \valid_read(c);
  requires sep: \separated(id, c);
  requires cfg: IDENT_CFG_VALID(c);
  assigns id->cfg;
  ensures cfg: IDENT_CFG_VALID(&id->cfg);
*/
static void ident_take_cfg(qfoc_ident_t *id, const qfoc_ident_cfg_t *c)
{
    id->cfg = *c;
}

uint8_t qfoc_ident_start(qfoc_ident_t *id, const qfoc_ident_cfg_t *c)
{
    uint8_t r;
    if (qfoc_ident_cfg_is_valid(c)) {
        ident_take_cfg(id, c);
        ident_init_pi(id, &c->pi);
        r = QFOC_IDENT_RUNNING;
    } else {
        ident_idle_cfg(id);
        ident_init_pi(id, &ident_pi_off);
        r = QFOC_IDENT_ERR_CFG;
    }
    ident_reset(id, r);
    return r;
}

void qfoc_ident_abort(qfoc_ident_t *id)
{
    if (id->result == QFOC_IDENT_RUNNING) {
        id->result = QFOC_IDENT_ERR_ABORT;
    }
}

/* Half a window, 2^(win_shift - 1) periods. */
/*@
  requires shift: QFOC_IDENT_WIN_MIN <= s <= QFOC_IDENT_WIN_MAX;
  assigns \nothing;
  ensures result: 16 <= \result <= 8192;
*/
static uint16_t ident_half(uint8_t s)
{
    static const uint16_t halves[10] = { 16u, 32u, 64u, 128u, 256u, 512u, 1024u, 2048u,
                                         4096u, 8192u };
    return halves[s - QFOC_IDENT_WIN_MIN];
}

/* The step after one that is not the last. */
/*@
  requires step: step < QFOC_IDENT_L_Q;
  assigns \nothing;
  ensures result: \result == step + 1;
*/
static uint8_t ident_next(uint8_t step)
{
    uint8_t n;
    switch (step) {
    case QFOC_IDENT_ALIGN:
        n = QFOC_IDENT_R_LO;
        break;
    case QFOC_IDENT_R_LO:
        n = QFOC_IDENT_R_HI;
        break;
    case QFOC_IDENT_R_HI:
        n = QFOC_IDENT_L_D;
        break;
    default:
        n = QFOC_IDENT_L_Q;
        break;
    }
    return n;
}

/* The alpha current level of a step. */
/*@
  requires valid: \valid_read(c);
  requires cfg: IDENT_CFG_VALID(c);
  assigns \nothing;
  ensures result: 0 < \result <= c->i_hi;
*/
static qfoc_q15_t ident_level(const qfoc_ident_cfg_t *c, uint8_t step)
{
    qfoc_q15_t level = c->i_hi;
    if (step == QFOC_IDENT_R_LO) {
        level = c->i_lo;
    }
    return level;
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
    qfoc_q15_t r = level;
    if ((ref <= level) && (up < (int32_t)level)) {
        r = (qfoc_q15_t)up;
    } else if ((ref > level) && (down > (int32_t)level)) {
        r = (qfoc_q15_t)down;
    } else {
        /* the level is within one step */
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
    const uint8_t ks = (k >= 4u) ? (uint8_t)(k - 4u) : (uint8_t)(k + 12u);
    const int16_t s = ident_cos16[ks];
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

/* Add this period to the half window h of the step the mode is in. */
/*@
  requires valid: \valid(id) && \valid_read(i) && \valid_read(cmp + (0 .. 2));
  requires sep: \separated(id, i) && \separated(id, cmp + (0 .. 2));
  requires cmp_range: \forall integer j; 0 <= j < 3 ==> cmp[j] <= 32767;
  requires ranges: id->step < QFOC_IDENT_STEPS && h < 2 && id->k <= 15;
  assigns id->rec;
*/
static void ident_sum(qfoc_ident_t *id, uint8_t h, const qfoc_ab_t *i, const uint16_t *cmp,
                      qfoc_q15_t vdc, qfoc_q15_t vb_cmd)
{
    ident_accumulate(&id->rec.s[id->step][h], i, cmp, vdc, vb_cmd, id->step == QFOC_IDENT_L_Q,
                     id->k);
}

/* The verdict at a window's end: QFOC_IDENT_RUNNING (go on) or the error. */
/*@
  requires valid: \valid_read(id);
  requires state: id->step < QFOC_IDENT_STEPS && IDENT_CFG_VALID(&id->cfg);
  assigns \nothing;
  ensures result: \result == QFOC_IDENT_RUNNING || \result == QFOC_IDENT_ERR_NO_CURRENT ||
                  \result == QFOC_IDENT_ERR_MOVED;
*/
static uint8_t ident_verdict(const qfoc_ident_t *id)
{
    const qfoc_ident_sums_t *h0 = &id->rec.s[id->step][0];
    const qfoc_ident_sums_t *h1 = &id->rec.s[id->step][1];
    const int64_t m = 2 * (int64_t)ident_half(id->cfg.win_shift);
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
            const uint16_t half = ident_half(id->cfg.win_shift);
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
            if (id->step == QFOC_IDENT_L_D) {
                inj = qfoc_q15_mul(id->cfg.v_inj, ident_cos16[id->k]);
                v.alpha = qfoc_q15_add(v.alpha, inj);
            } else if (id->step == QFOC_IDENT_L_Q) {
                inj = qfoc_q15_mul(id->cfg.v_inj, ident_cos16[id->k]);
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
                ident_sum(id, h, i, so.cmp, vdc, v.beta);
            }
            id->k = (id->k >= 15u) ? 0u : (uint8_t)(id->k + 1u);
            id->n++;
            if (id->n >= ((uint32_t)settle + (2u * (uint32_t)half))) {
                const uint8_t r = ident_verdict(id);
                if (r != QFOC_IDENT_RUNNING) {
                    id->result = r;
                } else if (id->step == QFOC_IDENT_L_Q) {
                    id->result = QFOC_IDENT_DONE;
                } else {
                    id->step = ident_next(id->step);
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
        *out = id->rec.s[step][half];
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
        buf[5] = (uint8_t)(id->cfg.pwm.period / 256u);
        buf[6] = (uint8_t)(QFOC_IDENT_FRAMES & 0xFFu);
        buf[7] = (uint8_t)(QFOC_IDENT_FRAMES / 256u);
    } else if (k < QFOC_IDENT_FRAMES) {
        const uint32_t j = (uint32_t)k - 1u;
        const uint32_t step = j / (2u * QFOC_IDENT_FIELDS);
        const uint32_t half = (j / QFOC_IDENT_FIELDS) % 2u;
        const uint32_t field = j % QFOC_IDENT_FIELDS;
        int64_t v;
        /*@ assert ranges: step < QFOC_IDENT_STEPS && half < 2 && field < QFOC_IDENT_FIELDS; */
        v = ident_field(&id->rec.s[step][half], (uint8_t)field);
        uint64_t u;
        if (v > lim48) {
            v = lim48;
        } else if (v < -lim48) {
            v = -lim48;
        } else {
            /* fits */
        }
        /* the 48-bit two's complement: v + 2^48 for a negative v */
        if (v < 0) {
            v += 281474976710656LL;
        }
        u = (uint64_t)v;
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
