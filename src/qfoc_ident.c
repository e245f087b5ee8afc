/**
 * @file qfoc_ident.c
 * @brief Standstill identification: the steps, bounds and window sums of ident.h.
 *
 * Requirements: REQ-IDENT-001 .. REQ-IDENT-007 (specs/requirements/ident.md).
 */
#include "qfoc/ident.h"
#include "qfoc/q15.h"
#include "qfoc/transforms.h"
#include "qfoc/trig.h"

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
                z->v_c == 0 && z->v_s == 0 &&
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
    z->v_c = 0;
    z->v_s = 0;
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
    ok = ok && (c->i_ramp > 0) && (c->v_inj > 0) && (c->v_inj <= c->v_inj_max);
    ok = ok && (c->i_inj > 0) && (c->v_move > 0) && (c->vdc_min > 0) && (c->vdc_max > c->vdc_min);
    ok = ok && (c->n_align > 0u) && (c->n_settle > 0u);
    ok = ok && (c->win_shift >= QFOC_IDENT_WIN_MIN) && (c->win_shift <= QFOC_IDENT_WIN_MAX);
    ok = ok && (c->w_psi > 0u) && (c->w_psi <= QFOC_IDENT_W_MAX) && (c->n_ramp > 0u);
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
    id->cfg.v_inj_max = 0;
    id->cfg.i_inj = 0;
    id->cfg.v_move = 0;
    id->cfg.vdc_min = 0;
    id->cfg.vdc_max = 0;
    id->cfg.n_align = 0u;
    id->cfg.n_settle = 0u;
    id->cfg.win_shift = 0u;
    id->cfg.w_psi = 0u;
    id->cfg.n_ramp = 0u;
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
  requires result: r <= QFOC_IDENT_ERR_DRIVE;
  assigns id->rec, id->ref, id->n, id->theta, id->inj, id->pk_max, id->pk_min, id->inj_hold,
          id->step, id->k, id->result;
  ensures state: id->step == QFOC_IDENT_ALIGN && id->n == 0 && id->ref == 0 && id->k == 0 &&
                 id->result == r && id->inj == id->cfg.v_inj;
*/
static void ident_reset(qfoc_ident_t *id, uint8_t r)
{
    ident_clear_record(id);
    id->ref = 0;
    id->n = 0u;
    id->theta = 0u;
    id->inj = id->cfg.v_inj;
    id->pk_max = QFOC_Q15_MIN;
    id->pk_min = QFOC_Q15_MAX;
    id->inj_hold = true;
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

void qfoc_ident_refuse(qfoc_ident_t *id)
{
    ident_idle_cfg(id);
    ident_init_pi(id, &ident_pi_off);
    ident_reset(id, QFOC_IDENT_ERR_DRIVE);
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
  requires step: step < QFOC_IDENT_PSI;
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
    case QFOC_IDENT_L_D:
        n = QFOC_IDENT_L_Q;
        break;
    default:
        n = QFOC_IDENT_PSI;
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

/* Add this period to the half window's sums: ic the current in the control frame, i the
   stationary current, (c, s) the reference angle's cosine and sine. */
/*@
  requires valid: \valid(z) && \valid_read(ic) && \valid_read(i) && \valid_read(cmp + (0 .. 2));
  requires sep: \separated(z, ic) && \separated(z, i) && \separated(z, cmp + (0 .. 2));
  requires cmp_range: \forall integer j; 0 <= j < 3 ==> cmp[j] <= 32767;
  requires ref: -32767 <= c <= 32767 && -32767 <= s <= 32767;
  assigns *z;
*/
static void ident_accumulate(qfoc_ident_sums_t *z, const qfoc_ab_t *ic, const qfoc_ab_t *i,
                             const uint16_t *cmp, qfoc_q15_t vdc, qfoc_q15_t vb_cmd,
                             int16_t c, int16_t s)
{
    const int32_t ua = (2 * (int32_t)cmp[0]) - (int32_t)cmp[1] - (int32_t)cmp[2];
    const int32_t ub = (int32_t)cmp[1] - (int32_t)cmp[2];
    z->n = ident_acc32(z->n, 1);
    z->i_a = ident_acc32(z->i_a, (int32_t)ic->alpha);
    z->i_b = ident_acc32(z->i_b, (int32_t)ic->beta);
    z->u_a = ident_acc32(z->u_a, ua);
    z->u_b = ident_acc32(z->u_b, ub);
    z->vdc = ident_acc32(z->vdc, (int32_t)vdc);
    z->vb_cmd = ident_acc32(z->vb_cmd, (int32_t)vb_cmd);
    z->u_c = ident_acc64(z->u_c, ua, c);
    z->u_s = ident_acc64(z->u_s, ua, s);
    z->v_c = ident_acc64(z->v_c, ub, c);
    z->v_s = ident_acc64(z->v_s, ub, s);
    z->i_c = ident_acc64(z->i_c, (int32_t)i->alpha, c);
    z->i_s = ident_acc64(z->i_s, (int32_t)i->alpha, s);
    z->j_c = ident_acc64(z->j_c, (int32_t)i->beta, c);
    z->j_s = ident_acc64(z->j_s, (int32_t)i->beta, s);
}

/* Add this period to the half window h of the step the mode is in. */
/*@
  requires valid: \valid(id) && \valid_read(ic) && \valid_read(i) && \valid_read(cmp + (0 .. 2));
  requires sep: \separated(id, ic) && \separated(id, i) && \separated(id, cmp + (0 .. 2));
  requires cmp_range: \forall integer j; 0 <= j < 3 ==> cmp[j] <= 32767;
  requires ranges: id->step < QFOC_IDENT_STEPS && h < 2;
  requires ref: -32767 <= c <= 32767 && -32767 <= s <= 32767;
  assigns id->rec;
*/
static void ident_sum(qfoc_ident_t *id, uint8_t h, const qfoc_ab_t *ic, const qfoc_ab_t *i,
                      const uint16_t *cmp, qfoc_q15_t vdc, qfoc_q15_t vb_cmd, int16_t c,
                      int16_t s)
{
    ident_accumulate(&id->rec.s[id->step][h], ic, i, cmp, vdc, vb_cmd, c, s);
}

/* L_D's and L_Q's injection amplitude: the injected axis's current x tracked over each
   injection period (16 PWM periods, k = 0 .. 15); at the end of one that is judged, a
   peak-to-peak below i_inj (an amplitude below half the aim) doubles the amplitude, up to
   v_inj_max, one above 4 i_inj (an amplitude above twice the aim) halves it.  The period
   after a change, and the first (partial) period of a step, are not judged: the current
   settles on the new amplitude first. */
/*@
  requires valid: \valid(id);
  requires ranges: 0 < id->inj <= id->cfg.v_inj_max && id->k <= 15 && 0 < id->cfg.i_inj;
  assigns id->inj, id->pk_max, id->pk_min, id->inj_hold;
  ensures range: 0 < id->inj <= id->cfg.v_inj_max;
*/
static void ident_adapt(qfoc_ident_t *id, qfoc_q15_t x)
{
    if (x > id->pk_max) {
        id->pk_max = x;
    }
    if (x < id->pk_min) {
        id->pk_min = x;
    }
    if (id->k >= 15u) {
        const qfoc_q15_t before = id->inj;
        if (!id->inj_hold) {
            const int32_t pp = (int32_t)id->pk_max - (int32_t)id->pk_min;
            const int32_t aim = (int32_t)id->cfg.i_inj;
            const int32_t up = 2 * (int32_t)id->inj;
            const int32_t down = (int32_t)id->inj / 2;
            if ((pp < aim) && (up > (int32_t)id->cfg.v_inj_max)) {
                id->inj = id->cfg.v_inj_max;
            } else if (pp < aim) {
                id->inj = (qfoc_q15_t)up;
            } else if ((pp > (4 * aim)) && (down >= 1)) {
                id->inj = (qfoc_q15_t)down;
            } else {
                /* within the aim's band */
            }
        }
        id->inj_hold = (id->inj != before);
        id->pk_max = QFOC_Q15_MIN;
        id->pk_min = QFOC_Q15_MAX;
    }
}

/* The control frame of this period: the reference angle (PSI: the rotating current's
   angle; the other steps: the injection's, 2 pi k / 16) and the current in the control
   frame (PSI: d and q of the rotating frame; the other steps: alpha and beta). */
/*@
  requires valid: \valid_read(i) && \valid(sc) && \valid(ic);
  requires sep: \separated(sc, ic) && \separated(i, sc) && \separated(i, ic);
  requires k: k <= 15;
  assigns *sc, *ic;
  ensures ref: QfocQ15Sym(sc->sine) && QfocQ15Sym(sc->cosine);
  ensures still: !psi ==> ic->alpha == i->alpha && ic->beta == i->beta;
*/
static void ident_ctrl_frame(bool psi, qfoc_angle_t theta, uint8_t k, const qfoc_ab_t *i,
                             qfoc_sincos_t *sc, qfoc_ab_t *ic)
{
    if (psi) {
        qfoc_dq_t dq;
        qfoc_sincos(theta, sc);
        qfoc_park(i, sc, &dq);
        ic->alpha = dq.d;
        ic->beta = dq.q;
    } else {
        const uint8_t ks = (k >= 4u) ? (uint8_t)(k - 4u) : (uint8_t)(k + 12u);
        sc->cosine = ident_cos16[k];
        sc->sine = ident_cos16[ks];
        ic->alpha = i->alpha;
        ic->beta = i->beta;
    }
}

/* The stationary voltage command of the control frame's vc: turned back by the reference
   angle in PSI, vc itself in the other steps. */
/*@
  requires valid: \valid_read(vc) && \valid_read(sc) && \valid(v);
  requires sep: \separated(v, vc) && \separated(v, sc);
  assigns *v;
*/
static void ident_voltage(bool psi, const qfoc_ab_t *vc, const qfoc_sincos_t *sc, qfoc_ab_t *v)
{
    if (psi) {
        qfoc_dq_t vdq;
        vdq.d = vc->alpha;
        vdq.q = vc->beta;
        qfoc_inv_park(&vdq, sc, v);
    } else {
        v->alpha = vc->alpha;
        v->beta = vc->beta;
    }
}

/* The periods before a step's window: ALIGN n_align, PSI its ramp and n_settle, the
   others n_settle. */
/*@
  requires valid: \valid_read(c);
  assigns \nothing;
  ensures result: \result <= 65535 + 65535;
*/
static uint32_t ident_settle(const qfoc_ident_cfg_t *c, uint8_t step)
{
    uint32_t n = (uint32_t)c->n_settle;
    if (step == QFOC_IDENT_ALIGN) {
        n = (uint32_t)c->n_align;
    } else if (step == QFOC_IDENT_PSI) {
        n = (uint32_t)c->n_ramp + (uint32_t)c->n_settle;
    } else {
        /* n_settle */
    }
    return n;
}

/* PSI's angle step in period n: w_psi n / n_ramp on the ramp, w_psi after it. */
/*@
  requires cfg: 0 < c->n_ramp && c->w_psi <= QFOC_IDENT_W_MAX;
  requires valid: \valid_read(c);
  assigns \nothing;
  ensures result: \result <= c->w_psi;
*/
static uint16_t ident_speed(const qfoc_ident_cfg_t *c, uint32_t n)
{
    uint16_t w = c->w_psi;
    if (n < (uint32_t)c->n_ramp) {
        w = (uint16_t)(((uint32_t)c->w_psi * n) / (uint32_t)c->n_ramp);
    }
    return w;
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
    } else if ((id->step != QFOC_IDENT_ALIGN) && (id->step != QFOC_IDENT_PSI) &&
               ((sv > (m * (int64_t)id->cfg.v_move)) || (sv < -(m * (int64_t)id->cfg.v_move)))) {
        r = QFOC_IDENT_ERR_MOVED;
    } else {
        /* both bounds hold */
    }
    return r;
}

/* This period's voltage command in the control frame (ic: the current in that frame):
   the reference ramped towards the step's level, both current loops (the second axis
   short-circuited in ALIGN), the injection of L_D on the first axis and of L_Q on the
   second. */
/*@
  requires valid: \valid(id) && \valid_read(ic) && \valid(vc);
  requires sep: \separated(id, ic) && \separated(id, vc) && \separated(ic, vc);
  requires state: id->step < QFOC_IDENT_STEPS && id->k <= 15 && IDENT_CFG_VALID(&id->cfg) &&
                  IDENT_PI(&id->pi_a) && IDENT_PI(&id->pi_b) &&
                  0 <= id->ref && id->ref <= id->cfg.i_hi;
  assigns id->ref, id->pi_a, id->pi_b, *vc;
  ensures state: IDENT_PI(&id->pi_a) && IDENT_PI(&id->pi_b) &&
                 0 <= id->ref && id->ref <= id->cfg.i_hi;
*/
static void ident_command(qfoc_ident_t *id, const qfoc_ab_t *ic, qfoc_ab_t *vc)
{
    const qfoc_q15_t level = ident_level(&id->cfg, id->step);
    id->ref = ident_ramp(id->ref, level, id->cfg.i_ramp);
    vc->alpha = qfoc_pi_step(&id->pi_a, qfoc_q15_sub(id->ref, ic->alpha));
    if (id->step == QFOC_IDENT_ALIGN) {
        /* the beta axis short-circuited through the inverter: the current a swinging
           rotor's back-EMF drives there brakes it */
        vc->beta = 0;
    } else {
        vc->beta = qfoc_pi_step(&id->pi_b, qfoc_q15_neg(ic->beta));
    }
    if (id->step == QFOC_IDENT_L_D) {
        vc->alpha = qfoc_q15_add(vc->alpha, qfoc_q15_mul(id->inj, ident_cos16[id->k]));
    } else if (id->step == QFOC_IDENT_L_Q) {
        vc->beta = qfoc_q15_add(vc->beta, qfoc_q15_mul(id->inj, ident_cos16[id->k]));
    } else {
        /* no injection */
    }
}

/* What this period adds: the window's sums from the settling's end on (half h by the
   period's place in the window), or, in the first half of L_D's and L_Q's settling, the
   injection amplitude's adaptation on the injected axis's current. */
/*@
  requires valid: \valid(id) && \valid_read(ic) && \valid_read(i) &&
                  \valid_read(cmp + (0 .. 2));
  requires sep: \separated(id, ic) && \separated(id, i) && \separated(id, cmp + (0 .. 2));
  requires cmp_range: \forall integer j; 0 <= j < 3 ==> cmp[j] <= 32767;
  requires ref: -32767 <= c <= 32767 && -32767 <= s <= 32767;
  requires state: id->step < QFOC_IDENT_STEPS && id->k <= 15 && 0 < id->cfg.i_inj &&
                  0 < id->inj && id->inj <= id->cfg.v_inj_max;
  assigns id->rec, id->inj, id->pk_max, id->pk_min, id->inj_hold;
  ensures inj: 0 < id->inj && id->inj <= id->cfg.v_inj_max;
*/
static void ident_observe(qfoc_ident_t *id, uint32_t settle, uint16_t half, const qfoc_ab_t *ic,
                          const qfoc_ab_t *i, const uint16_t *cmp, qfoc_q15_t vdc,
                          qfoc_q15_t vb, int16_t c, int16_t s)
{
    if (id->n >= settle) {
        const uint8_t h = ((id->n - settle) >= (uint32_t)half) ? 1u : 0u;
        ident_sum(id, h, ic, i, cmp, vdc, vb, c, s);
    } else if ((id->step == QFOC_IDENT_L_D) && (id->n < (settle / 2u))) {
        ident_adapt(id, ic->alpha);
    } else if ((id->step == QFOC_IDENT_L_Q) && (id->n < (settle / 2u))) {
        ident_adapt(id, ic->beta);
    } else {
        /* settling with the amplitude held */
    }
}

/* The period's end: the injection phase and PSI's angle advanced, the period counted;
   at a window's end the verdict, then the next step (its amplitude back to v_inj), DONE
   after PSI, or the error. */
/*@
  requires valid: \valid(id);
  requires state: id->step < QFOC_IDENT_STEPS && id->k <= 15 && IDENT_CFG_VALID(&id->cfg) &&
                  0 < id->inj && id->inj <= id->cfg.v_inj_max &&
                  id->result == QFOC_IDENT_RUNNING;
  requires window: settle <= 65535 + 65535 && 16 <= half <= 8192 &&
                   id->n <= 65535 + 65535 + 16384;
  assigns id->k, id->theta, id->n, id->step, id->result, id->inj, id->pk_max, id->pk_min,
          id->inj_hold;
  ensures state: id->step < QFOC_IDENT_STEPS && id->k <= 15 &&
                 0 < id->inj && id->inj <= id->cfg.v_inj_max;
  ensures n: id->result == QFOC_IDENT_RUNNING ==> id->n <= 65535 + 65535 + 16384;
  ensures result: id->result == QFOC_IDENT_RUNNING || id->result == QFOC_IDENT_DONE ||
                  id->result == QFOC_IDENT_ERR_NO_CURRENT ||
                  id->result == QFOC_IDENT_ERR_MOVED;
*/
static void ident_advance(qfoc_ident_t *id, uint32_t settle, uint16_t half)
{
    id->k = (id->k >= 15u) ? 0u : (uint8_t)(id->k + 1u);
    if (id->step == QFOC_IDENT_PSI) {
        const uint32_t th = (uint32_t)id->theta + (uint32_t)ident_speed(&id->cfg, id->n);
        id->theta = (qfoc_angle_t)(th % 65536u);
    }
    id->n++;
    if (id->n >= (settle + (2u * (uint32_t)half))) {
        const uint8_t r = ident_verdict(id);
        if (r != QFOC_IDENT_RUNNING) {
            id->result = r;
        } else if (id->step == QFOC_IDENT_PSI) {
            id->result = QFOC_IDENT_DONE;
        } else {
            id->step = ident_next(id->step);
            id->n = 0u;
            id->inj = id->cfg.v_inj;
            id->pk_max = QFOC_Q15_MIN;
            id->pk_min = QFOC_Q15_MAX;
            id->inj_hold = true;
        }
    }
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
        } else if ((vdc < id->cfg.vdc_min) || (vdc > id->cfg.vdc_max)) {
            id->result = QFOC_IDENT_ERR_BUS;
        } else {
            static const qfoc_abc_t no_dtc = { 0, 0, 0 };
            const bool psi = (id->step == QFOC_IDENT_PSI);
            const uint32_t settle = ident_settle(&id->cfg, id->step);
            const uint16_t half = ident_half(id->cfg.win_shift);
            qfoc_sincos_t sc;
            qfoc_ab_t ic;
            qfoc_ab_t vc;
            qfoc_ab_t v;
            qfoc_svpwm_out_t so;
            ident_ctrl_frame(psi, id->theta, id->k, i, &sc, &ic);
            ident_command(id, &ic, &vc);
            ident_voltage(psi, &vc, &sc, &v);
            qfoc_svpwm_step(&id->cfg.pwm, &v, vdc, &no_dtc, &so);
            ident_observe(id, settle, half, &ic, i, so.cmp, vdc, vc.beta, sc.cosine, sc.sine);
            ident_advance(id, settle, half);
            if (id->result == QFOC_IDENT_RUNNING) {
                /* a period that ends the mode at its window's end keeps the PWM off:
                   its compare values (already in the sums) are not applied */
                out.cmp[0] = so.cmp[0];
                out.cmp[1] = so.cmp[1];
                out.cmp[2] = so.cmp[2];
                out.enable = true;
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

/* Field f (0 .. 14, qfoc_ident_sums_t's order) of a half window's sums. */
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
    case 9u: v = z->v_c; break;
    case 10u: v = z->v_s; break;
    case 11u: v = z->i_c; break;
    case 12u: v = z->i_s; break;
    case 13u: v = z->j_c; break;
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
