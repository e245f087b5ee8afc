/**
 * @file shunt.h
 * @brief Single-shunt current measurement: the two DC-link samples of a PWM period, the
 *        edge shift that gives them time, and the phase currents rebuilt from them.
 *
 * An inverter with one shunt in the DC link sees a phase current only while an active
 * vector is applied (specs/equations.md section 13).  In the up-counting half of the
 * centre-aligned PWM (counter 0 .. period; a phase is high while the counter is at or
 * above period - its compare value), the phase with the largest compare value (hi) is
 * switched on first: while it alone is high the DC-link current is +i_hi (E13-2); then
 * the middle one follows, and while only the smallest (lo) is low the DC-link current is
 * -i_lo (E13-3).  Each window must last t_settle (dead time and ringing after the edge)
 * plus t_sample (the ADC's sample-and-hold) ticks.
 *
 * qfoc_shunt_plan() takes the SVPWM's compare values (svpwm.h) and gives, for the next
 * period: an up-counting and a down-counting compare value per phase (the FTM's combined
 * mode), the two sampling instants (counter values of the up-counting half, for the PDB's
 * delays), and the phases the two samples will read.  When a window is shorter than
 * t_settle + t_sample (low modulation, a vector near a sector border) it shifts the
 * edges of the up-counting half apart and those of the down-counting half the other way
 * by the same amount, so that every phase's on-time in the period, and so the period's
 * mean voltage, is unchanged (up + down = 2 x cmp, exactly: E13-5).  It moves the middle
 * phase only when the outer ones cannot move far enough within [0, period] (E13-4).
 *
 * qfoc_shunt_currents() takes the two samples of a period with the plan that was in
 * force for that period (the caller keeps the last plan: the samples of period k belong
 * to the plan written in period k - 1) and rebuilds the three phase currents (E13-6):
 * i_hi = s1, i_lo = -s2, the third -(i_hi + i_lo).  A period whose plan could not open
 * both windows reports HELD and gives the last rebuilt currents, for at most hold_max
 * periods in a row; after that it reports LOST (the caller's fault), and so it does from
 * init until the first measured period.
 *
 * qfoc_shunt_align() refers the rebuilt currents of a measured period to one instant (E13-7):
 * the two samples are taken at two instants of the up-counting half, while the drive's
 * estimator and current loop take the currents of the instant a two-sensor inverter samples
 * (the centre of the zero vector with every phase low, 1.5 periods before the centre of the
 * voltage computed from them, specs/equations.md E12-3).  The PWM ripple of each sample is
 * taken off (E13-8: the current at that instant is the mean trajectory's), and each measured
 * phase is turned to the instant by the angle the rotor travels in between, from the drive's
 * speed.
 *
 * Every function is total: any configuration (an invalid one is refused and measures
 * nothing: every period LOST), any compare value (above the period: clamped, as the PWM
 * applies it), any sample and any plan (indices out of range: not measured).
 *
 * Scaling: compare values, instants and times in timer ticks (those of svpwm.h); the
 * samples and currents in Q15 of the current base, the DC-link sample scaled as a phase
 * current (code less its offset, x 16, as the drive reads its phase samples).  All
 * arithmetic is in 32 bits on values at most 2 x 32767.
 *
 * Requirements: REQ-SHUNT-001 .. REQ-SHUNT-004, REQ-SHUNT-008 (specs/requirements/shunt.md).
 */
#ifndef QFOC_SHUNT_H
#define QFOC_SHUNT_H

#include "qfoc/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Configuration of the single-shunt measurement (from the table). */
typedef struct {
    uint16_t period;    /**< PWM counter top in ticks, 100 .. 32767 (the SVPWM's period) */
    uint16_t t_settle;  /**< ticks from a switching edge to a settled DC-link current: dead
                             time plus ringing; 0 .. */
    uint16_t t_sample;  /**< ticks of the ADC's sample-and-hold, >= 1; each window lasts at
                             least t_settle + t_sample, at most period / 4 */
    uint16_t hold_max;  /**< periods the last currents may stand in for a missed
                             measurement, 1 .. 1000 */
} qfoc_shunt_cfg_t;

/** The PWM and sampling of one period. */
typedef struct {
    uint16_t up[3];     /**< compare values u, v, w of the up-counting half, 0 .. period */
    uint16_t down[3];   /**< compare values of the down-counting half, 0 .. period;
                             up[k] + down[k] = 2 x cmp[k] */
    uint16_t trig[2];   /**< counter values of the up-counting half at which the two
                             samples start (0 when ok is false) */
    uint8_t hi;         /**< phase (0 u, 1 v, 2 w) the first sample reads: +i_hi */
    uint8_t lo;         /**< phase the second sample reads: -i_lo */
    bool ok;            /**< both windows at least t_settle + t_sample ticks long */
    bool shifted;       /**< an edge was moved (up differs from cmp for some phase) */
} qfoc_shunt_plan_t;

/** State of the reconstruction. */
typedef struct {
    qfoc_q15_t i[3];    /**< last rebuilt phase currents u, v, w (0 before the first) */
    uint16_t n_hold;    /**< periods in a row without a measurement, 0 .. hold_max */
    uint16_t hold_max;  /**< the configuration's hold_max (1 after a refused one) */
} qfoc_shunt_t;

/** The currents were rebuilt from this period's samples. */
#define QFOC_SHUNT_OK      ((uint8_t)0u)
/** No measurement this period: the last currents stand in (at most hold_max periods). */
#define QFOC_SHUNT_HELD    ((uint8_t)1u)
/** No measurement for more than hold_max periods (or none yet): the currents are stale. */
#define QFOC_SHUNT_LOST    ((uint8_t)2u)
/** qfoc_shunt_init(): the configuration was refused. */
#define QFOC_SHUNT_ERR_CFG ((uint8_t)3u)

/** Largest angle per period qfoc_shunt_align() turns by: 5215 / 65536 of a turn, 0.5 rad
    (the reference motor turns 0.30 rad per period at 8000 rpm); a larger one is clamped. */
#define QFOC_SHUNT_DTH_MAX ((int32_t)5215)
/** 1 / sqrt(3) in Q15: round(32768 / sqrt(3)) = 18919. */
#define QFOC_SHUNT_INV_SQRT3 ((int32_t)18919)

#ifdef __FRAMAC__
/* ACSL logic of this module, read by Frama-C only (DEV-001). */
/* cppcheck-suppress misra-c2012-20.1 ; DEV-001 */
#include "shunt.acsl"
#endif

/**
 * @brief Check a configuration.
 * @param[in] c the configuration (any values)
 * @return true when period is 100 .. 32767, t_sample >= 1,
 *         4 x (t_settle + t_sample) <= period and hold_max is 1 .. 1000.
 * Requirements: REQ-SHUNT-001.
 */
/*@
  requires valid: \valid_read(c);
  assigns \nothing;
  ensures result: \result <==> ShuntCfgValid(c);
*/
bool qfoc_shunt_cfg_is_valid(const qfoc_shunt_cfg_t *c);

/**
 * @brief Initialise the reconstruction: no currents yet (the first period without a
 *        measurement reports LOST).
 * @param[out] s the state (any contents)
 * @param[in]  c the configuration (any values)
 * @return QFOC_SHUNT_OK, or QFOC_SHUNT_ERR_CFG for a configuration
 *         qfoc_shunt_cfg_is_valid() refuses: hold_max is then 1, and since no plan of
 *         that configuration opens the windows, every period reports LOST.
 * Requirements: REQ-SHUNT-001, REQ-SHUNT-003.
 */
/*@
  requires valid: \valid(s) && \valid_read(c);
  requires sep: \separated(s, c);
  assigns *s;
  ensures inv: ShuntValid(s);
  ensures none: s->n_hold == s->hold_max && s->i[0] == 0 && s->i[1] == 0 && s->i[2] == 0;
  behavior accepted:
    assumes ShuntCfgValid(c);
    ensures result: \result == QFOC_SHUNT_OK;
    ensures hold: s->hold_max == c->hold_max;
  behavior refused:
    assumes !ShuntCfgValid(c);
    ensures result: \result == QFOC_SHUNT_ERR_CFG;
    ensures hold: s->hold_max == 1;
  complete behaviors;
  disjoint behaviors;
*/
uint8_t qfoc_shunt_init(qfoc_shunt_t *s, const qfoc_shunt_cfg_t *c);

/**
 * @brief The PWM and the sampling of the next period from the SVPWM's compare values.
 * @param[in]  c   the configuration (any values; a refused one gives ok false)
 * @param[in]  cmp compare values u, v, w (any; above the period: clamped to it)
 * @param[out] p   the plan
 *
 * With x_k the clamped compare values, hi the phase of the largest (the first of equal
 * ones), lo that of the smallest (the last of equal ones), m the third, T = t_settle +
 * t_sample and P the period (E13-4): the middle phase's up-counting value is x_m held
 * within [L, H], L = max(2 x_m - P, 0, max(2 x_lo - P, 0) + T), H = min(2 x_m, P,
 * min(2 x_hi, P) - T); then up_hi = max(x_hi, up_m + T), up_lo = min(x_lo, up_m - T),
 * and down_k = 2 x_k - up_k.  ok is L <= H (false only when all three values are within
 * T of 0 or of P, which the SVPWM's centred vectors never give); without it nothing is
 * shifted.  The samples start at trig[0] = P - up_hi + t_settle and trig[1] = P - up_m
 * + t_settle, each t_settle after the edge that opens its window and done t_sample
 * later, before the next edge.
 *
 * Requirements: REQ-SHUNT-001, REQ-SHUNT-002.
 */
/*@
  requires valid: \valid_read(c) && \valid_read(cmp + (0 .. 2)) && \valid(p);
  requires sep: \separated(p, c) && \separated(p, cmp + (0 .. 2));
  assigns *p;
  ensures idx: ShuntPlanIdx(p);
  ensures order: ShuntX{Pre}(cmp, p->hi, \old(c->period)) >= ShuntX{Pre}(cmp, 3 - p->hi - p->lo, \old(c->period)) &&
                 ShuntX{Pre}(cmp, 3 - p->hi - p->lo, \old(c->period)) >= ShuntX{Pre}(cmp, p->lo, \old(c->period));
  ensures volt_seconds: p->up[0] + p->down[0] == 2 * ShuntX{Pre}(cmp, 0, \old(c->period)) &&
                        p->up[1] + p->down[1] == 2 * ShuntX{Pre}(cmp, 1, \old(c->period)) &&
                        p->up[2] + p->down[2] == 2 * ShuntX{Pre}(cmp, 2, \old(c->period));
  ensures range: p->up[0] <= \old(c->period) && p->up[1] <= \old(c->period) && p->up[2] <= \old(c->period) &&
                 p->down[0] <= \old(c->period) && p->down[1] <= \old(c->period) && p->down[2] <= \old(c->period);
  ensures shifted: p->shifted <==> (p->up[0] != ShuntX{Pre}(cmp, 0, \old(c->period)) ||
                                    p->up[1] != ShuntX{Pre}(cmp, 1, \old(c->period)) ||
                                    p->up[2] != ShuntX{Pre}(cmp, 2, \old(c->period)));
  ensures unshifted: !p->ok ==> (p->up[0] == ShuntX{Pre}(cmp, 0, \old(c->period)) &&
                                 p->up[1] == ShuntX{Pre}(cmp, 1, \old(c->period)) &&
                                 p->up[2] == ShuntX{Pre}(cmp, 2, \old(c->period)) &&
                                 p->trig[0] == 0 && p->trig[1] == 0);
  behavior valid_cfg:
    assumes ShuntCfgValid(c);
    ensures ok: p->ok <==> ShuntFeasible(ShuntX{Pre}(cmp, p->hi, \old(c->period)),
                                         ShuntX{Pre}(cmp, 3 - p->hi - p->lo, \old(c->period)),
                                         ShuntX{Pre}(cmp, p->lo, \old(c->period)), \old(c->period), ShuntT{Pre}(c));
    ensures mid: p->ok ==> p->up[3 - p->hi - p->lo] ==
                           ShuntMid(ShuntX{Pre}(cmp, p->hi, \old(c->period)),
                                    ShuntX{Pre}(cmp, 3 - p->hi - p->lo, \old(c->period)),
                                    ShuntX{Pre}(cmp, p->lo, \old(c->period)), \old(c->period), ShuntT{Pre}(c));
    ensures outer: p->ok ==>
      (p->up[p->hi] == ShuntMax(ShuntX{Pre}(cmp, p->hi, \old(c->period)), p->up[3 - p->hi - p->lo] + ShuntT{Pre}(c)) &&
       p->up[p->lo] == ShuntMin(ShuntX{Pre}(cmp, p->lo, \old(c->period)), p->up[3 - p->hi - p->lo] - ShuntT{Pre}(c)));
    ensures windows: p->ok ==> (p->up[p->hi] >= p->up[3 - p->hi - p->lo] + ShuntT{Pre}(c) &&
                                p->up[3 - p->hi - p->lo] >= p->up[p->lo] + ShuntT{Pre}(c));
    ensures trig: p->ok ==> (p->trig[0] == \old(c->period) - p->up[p->hi] + \old(c->t_settle) &&
                             p->trig[1] == \old(c->period) - p->up[3 - p->hi - p->lo] + \old(c->t_settle));
  behavior refused:
    assumes !ShuntCfgValid(c);
    ensures not_ok: p->ok == \false;
  complete behaviors;
  disjoint behaviors;
*/
void qfoc_shunt_plan(const qfoc_shunt_cfg_t *c, const uint16_t cmp[3], qfoc_shunt_plan_t *p);

/**
 * @brief The phase currents of a period from its two DC-link samples.
 * @param[in,out] s   the state (valid: as qfoc_shunt_init() and this function leave it)
 * @param[in]     p   the plan in force while the samples were taken (any contents)
 * @param[in]     s1  the first sample (+i_hi), Q15, any value (-32768 read as -32767)
 * @param[in]     s2  the second sample (-i_lo), Q15, any value
 * @param[out]    out phase currents u, v, w, Q15 in [-32767, 32767]
 * @return QFOC_SHUNT_OK when p opened both windows (ok, and hi, lo two distinct phases):
 *         out[hi] = sat(s1), out[lo] = sat(-s2), the third sat(s2 - s1) (E13-6), stored,
 *         and the count of missed periods restarts; otherwise QFOC_SHUNT_HELD while fewer
 *         than hold_max periods in a row were missed (this one counted), or
 *         QFOC_SHUNT_LOST: out is then the last stored currents.
 * Requirements: REQ-SHUNT-003, REQ-SHUNT-004.
 */
/*@
  requires valid: \valid(s) && \valid_read(p) && \valid(out + (0 .. 2));
  requires sep: \separated(s, p) && \separated(out + (0 .. 2), s) &&
                \separated(out + (0 .. 2), p);
  requires inv: ShuntValid(s);
  assigns *s, out[0 .. 2];
  ensures inv: ShuntValid(s);
  ensures hold_max: s->hold_max == \old(s->hold_max);
  ensures out: out[0] == s->i[0] && out[1] == s->i[1] && out[2] == s->i[2];
  behavior measured:
    assumes p->ok && ShuntPlanIdx(p);
    ensures result: \result == QFOC_SHUNT_OK;
    ensures count: s->n_hold == 0;
    ensures hi: out[p->hi] == QfocSat15(s1);
    ensures lo: out[p->lo] == QfocSat15(-s2);
    ensures third: out[3 - p->hi - p->lo] == QfocSat15(s2 - s1);
  behavior held:
    assumes !(p->ok && ShuntPlanIdx(p)) && s->n_hold < s->hold_max;
    ensures result: \result == QFOC_SHUNT_HELD;
    ensures count: s->n_hold == \old(s->n_hold) + 1;
    ensures last: s->i[0] == \old(s->i[0]) && s->i[1] == \old(s->i[1]) && s->i[2] == \old(s->i[2]);
  behavior lost:
    assumes !(p->ok && ShuntPlanIdx(p)) && s->n_hold >= s->hold_max;
    ensures result: \result == QFOC_SHUNT_LOST;
    ensures count: s->n_hold == \old(s->n_hold);
    ensures last: s->i[0] == \old(s->i[0]) && s->i[1] == \old(s->i[1]) && s->i[2] == \old(s->i[2]);
  complete behaviors;
  disjoint behaviors;
*/
uint8_t qfoc_shunt_currents(qfoc_shunt_t *s, const qfoc_shunt_plan_t *p, qfoc_q15_t s1,
                            qfoc_q15_t s2, qfoc_q15_t out[3]);

/**
 * @brief The rebuilt currents of a measured period referred to one instant (E13-7).
 * @param[in]     c    the configuration (any values; a refused one changes nothing)
 * @param[in]     p    the plan in force while the samples were taken (any contents; one
 *                     that did not open both windows changes nothing)
 * @param[in]     dth  the electrical angle the rotor turns per PWM period, 65536 per turn,
 *                     signed (any value; clamped to +-QFOC_SHUNT_DTH_MAX)
 * @param[in]     g    the change of a phase current over one period (2 P ticks) under the
 *                     full DC-bus voltage, V_dc T / L, Q15 of the current base (any value;
 *                     held within 0 .. 32767; 0: no ripple taken off)
 * @param[in]     lead whole periods from the start of the sampled period to the instant:
 *                     0 or 1 (any other value read as 1)
 * @param[in,out] i    the phase currents u, v, w qfoc_shunt_currents() rebuilt from p's
 *                     samples (any values); on return referred to the instant
 *
 * With P the period, the samples' mid-points (their sample-and-hold) lie at t_j = trig[j]
 * + t_sample / 2 ticks from the start of the period (2 P ticks), the instant at r = lead x
 * 2 P; w = pi dth / 32768 rad per period and phi_j = w (r - t_j) / (2 P) the angle from
 * sample j to the instant (Q15 rad: the ratio (r - t_j) / (2 P) in Q15, truncated and held
 * within [-1, 1], times w rounded; within +-16384).  With q_k = (i_k+1 -
 * i_k+2) / sqrt 3 the quadrature of phase k (u, v, w cyclic: the current vector turning
 * by a, i_k goes to i_k cos a - q_k sin a) and R(i, q, a) = i - i a^2 / 2 - q a the
 * small-angle rotation:
 *   0. the PWM ripple of each sample is taken off (E13-8): the phase voltage less its mean
 *      over the period, integrated from the start of the period (where the ripple is zero,
 *      as it is again at the end) to the sample, r_k(n) = g [(C_k(n) - C(n)) - n (x_k -
 *      x) / P] / (2 P), C_k(n) the ticks phase k was high up to tick n (up-counting half:
 *      n - P + up_k, at least 0), x_k = (up_k + down_k) / 2 its mean compare value, C and
 *      x the means of the three; each ratio to 2 P in Q15, truncated;
 *   1. the phase lo is turned to the first sample's instant: i_lo' = R(i_lo, q_lo,
 *      phi_2 - phi_1), q_lo from the currents as rebuilt (i_hi, i_lo, -(i_hi + i_lo));
 *   2. both are turned to the instant: i_hi'' = R(i_hi, q_hi, phi_1), i_lo'' = R(i_lo',
 *      q_lo', phi_1), the quadratures from (i_hi, i_lo', -(i_hi + i_lo'));
 *   3. the third phase is -(i_hi'' + i_lo'').
 * Every product is a Q15 product rounded to nearest (qfoc_q15_mul()), every sum saturated
 * to [-32767, 32767].
 *
 * Error bound (REQ-SHUNT-008): for phase currents that are those of a current vector of
 * magnitude I turning at the constant rate w, |I| <= 30000, plus the ripple of E13-8 (the
 * plant's inductance the one g is made with, no dead time), each of the three
 * returned currents lies within
 *     I (1.2 d^2 (1 + 1.2 |phi_1|) + 0.2 (|d|^3 + |phi_1|^3)) + 12 LSB,   d = phi_2 - phi_1
 * of the vector's phase current at the instant: the truncation of the small-angle rotation
 * (a^3 / 6), the quadrature of step 1 taken from two instants (2 / sqrt 3 I |d| per rad of
 * turn) and the roundings (the ripple's within 4 LSB for g <= 32767).  |d| <= |w| / 2 (both samples lie in one half period) and
 * |phi_1| <= |w|: at the reference motor's 0.23 rad per period (6000 rpm) the bound is
 * 2.3 % of I + 12 LSB, at 0.30 rad (8000 rpm) 4.3 %; the currents as rebuilt are off by up
 * to 22 % and 29 % of I there (tests/test_shunt.c checks the bound against a
 * double-precision reference: at most 0.8 of it reached, 1.2 % and 2.1 % of I).
 *
 * Scaling and overflow: every tick difference is held within +-2 P (+-4 P for the compare
 * sums) before its ratio to 2 P, so that times 32768 (16384) it stays below 2^31; each
 * ratio is held within the Q15 range, and the products of two Q15 values are
 * qfoc_q15_mul()'s (rounded, saturated); dth is clamped to |dth| <= 5215 and w = dth x
 * 25736 / 8192 (pi in Q13) lies within +-16383; the quadratures come from sums of at most
 * 3 x 32767 times 18919 < 2^31, rounded by qfoc_q15_from_q30() (saturated).  Only a
 * configuration qfoc_shunt_cfg_is_valid() accepts is used (P >= 100: no division by 0).
 *
 * Requirements: REQ-SHUNT-008.
 */
/*@
  requires valid: \valid_read(c) && \valid_read(p) && \valid(i + (0 .. 2));
  requires sep: \separated(i + (0 .. 2), c) && \separated(i + (0 .. 2), p);
  assigns i[0 .. 2];
  behavior turned:
    assumes ShuntCfgValid(c) && p->ok && ShuntPlanIdx(p);
    ensures range: QfocQ15Sym(i[0]) && QfocQ15Sym(i[1]) && QfocQ15Sym(i[2]);
    ensures third: i[3 - p->hi - p->lo] == QfocSat15(-(i[p->hi] + i[p->lo]));
    ensures still: dth == 0 && g <= 0 && QfocQ15Sym(\old(i[p->hi])) && QfocQ15Sym(\old(i[p->lo])) ==>
                   i[p->hi] == \old(i[p->hi]) && i[p->lo] == \old(i[p->lo]);
  behavior kept:
    assumes !(ShuntCfgValid(c) && p->ok && ShuntPlanIdx(p));
    ensures kept: i[0] == \old(i[0]) && i[1] == \old(i[1]) && i[2] == \old(i[2]);
  complete behaviors;
  disjoint behaviors;
*/
void qfoc_shunt_align(const qfoc_shunt_cfg_t *c, const qfoc_shunt_plan_t *p, int32_t dth,
                      int32_t g, uint8_t lead, qfoc_q15_t i[3]);

#ifdef __cplusplus
}
#endif

#endif /* QFOC_SHUNT_H */
