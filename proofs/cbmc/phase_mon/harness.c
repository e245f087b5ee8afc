/*
 * CBMC harness: the phase-loss monitor on any valid state and any currents
 * (REQ-FAULT-003, REQ-FAULT-004, REQ-FAULT-005).
 *
 * Properties checked:
 *  - no undefined behaviour (overflow, conversion, bounds, pointer checks of the
 *    command line) in qfoc_phase_mon_update() for every phase current (-32768
 *    included), every coefficient and every state accepted by
 *    qfoc_phase_mon_is_valid(), and in qfoc_phase_mon_imbalanced() for every
 *    i_min and ratio;
 *  - after the update each coefficient is unchanged and each state has moved
 *    toward the new input |i_x| x 65536 (|-32768| taken as 32767), never away;
 *  - the criterion, on any valid monitor, with the filtered magnitudes
 *    recomputed here from the states (rounded to nearest): for every i_min and
 *    ratio, a largest magnitude below i_min or 0 is never reported and a zero
 *    magnitude next to a largest one >= max(i_min, 1) is reported for ratio > 0;
 *    for the ratios 0, 1 LSB, 0.25, 0.5 and -1 the result equals
 *    (max >= i_min && min x 32768 < ratio x max) exactly (the general product is
 *    proved by WP: contract of qfoc_phase_mon_imbalanced, ensures result);
 *  - no undefined behaviour in qfoc_phase_mon_update_one() for every phase index,
 *    current and valid state; the two phases not selected and every coefficient
 *    are kept (the step of the selected filter and the invariant after it are
 *    proved by WP: contract of qfoc_phase_mon_update_one, state_u/v/w, valid); qfoc_phase_mon_alpha3() of every int16_t
 *    lies in [1, 32767] and is not below a positive alpha;
 *  - init and reset leave a valid monitor with zero states.
 * The exact recursion (lpf semantics, y + round(alpha (u - y) / 32768)), the
 * no-overshoot half of the convex combination and hence the invariant after an
 * update (states in [0, 32767 x 65536]) are nonlinear in alpha and the state; they
 * are proved by Frama-C WP (contract of qfoc_phase_mon_update: valid, state_u/v/w)
 * and tested against a double reference (tests/test_fault.c): bit-level reasoning
 * through three 64-bit multipliers does not finish within the time budget.
 *
 * Methods: 1b every phase current, coefficient, valid state, i_min, ratio and phase
 * index; 1c -32768 currents (taken as 32767), the ratios 0, 1 LSB, 0.25, 0.5 and -1, a
 * zero magnitude beside the largest, alpha3 of every int16; 1d a lost phase (a zero
 * magnitude) reported, a magnitude below i_min never
 */
#include <stdint.h>
#include <stdbool.h>
#include "qfoc/fault.h"
#include "../harness_util.h"

/* |x| of a phase current as the monitor uses it (|-32768| saturated) */
static int64_t abs15(int16_t x)
{
    return (x == (int16_t)-32768) ? 32767 : ((x < 0) ? -(int64_t)x : (int64_t)x);
}

/* a non-negative Q31 state rounded to Q15 (nearest, ties up) */
static int32_t out15(int32_t s)
{
    return (int32_t)(((int64_t)s + 32768) / 65536);
}

/* ratios checked exactly: 0, 1 LSB, 0.25, 0.5, -1 (powers of two: a general
   constant makes the comparison with the library product exceed the time budget) */
#define N_RATIOS 5u
static const int16_t ratios[N_RATIOS] = { 0, 1, 8192, 16384, -32768 };

int main(void)
{
    qfoc_phase_mon_t m;
    qfoc_phase_mon_t m2;
    qfoc_phase_mon_t m3;
    const uint8_t kk = nondet_uint8();
    qfoc_q15_t alpha_old[3];
    qfoc_abc_t i;
    int64_t old[3];
    int64_t in[3];
    int32_t a[3];
    int32_t hi;
    int32_t lo;
    uint32_t k;
    const int16_t i_min = nondet_int16();
    const int16_t ratio = nondet_int16();
    bool r;
    bool expect;

    for (k = 0u; k < 3u; k++) {
        m.abs_lpf[k].alpha = nondet_int16();
        m.abs_lpf[k].state = nondet_int32();
        m2.abs_lpf[k].alpha = nondet_int16();
        m2.abs_lpf[k].state = nondet_int32();
        alpha_old[k] = m.abs_lpf[k].alpha;
    }
    __CPROVER_assume(qfoc_phase_mon_is_valid(&m));
    __CPROVER_assume(qfoc_phase_mon_is_valid(&m2));
    i.u = nondet_int16();
    i.v = nondet_int16();
    i.w = nondet_int16();
    old[0] = m.abs_lpf[0].state;
    old[1] = m.abs_lpf[1].state;
    old[2] = m.abs_lpf[2].state;
    in[0] = abs15(i.u) * 65536;
    in[1] = abs15(i.v) * 65536;
    in[2] = abs15(i.w) * 65536;

    m3 = m;
    qfoc_phase_mon_update(&m, &i);

    /* one phase only: that phase as in the full update, the others kept */
    qfoc_phase_mon_update_one(&m3, &i, kk);
    for (k = 0u; k < 3u; k++) {
        const uint32_t sel = (kk >= 2u) ? 2u : (uint32_t)kk;
        __CPROVER_assert(m3.abs_lpf[k].alpha == alpha_old[k], "one phase: coefficient unchanged");
        if (k != sel) {
            __CPROVER_assert(m3.abs_lpf[k].state == old[k], "one phase: the others are kept");
        }
    }
    {
        const int16_t a1 = nondet_int16();
        const int16_t a3 = qfoc_phase_mon_alpha3(a1);
        __CPROVER_assert((a3 >= 1) && (a3 <= 32767), "alpha3 in [1, 32767]");
        __CPROVER_assert((a1 < 1) || (a3 >= a1), "alpha3 >= alpha: a third of the steps, not slower");
    }

    for (k = 0u; k < 3u; k++) {
        const int64_t s = m.abs_lpf[k].state;
        __CPROVER_assert(m.abs_lpf[k].alpha == alpha_old[k], "coefficient unchanged");
        if (old[k] <= in[k]) {
            __CPROVER_assert(s >= old[k], "rising magnitude: state does not fall");
        } else {
            __CPROVER_assert(s <= old[k], "falling magnitude: state does not rise");
        }
    }

    /* the criterion for any i_min and ratio: overflow-free, product-free facts */
    a[0] = out15(m2.abs_lpf[0].state);
    a[1] = out15(m2.abs_lpf[1].state);
    a[2] = out15(m2.abs_lpf[2].state);
    hi = a[0];
    lo = a[0];
    for (k = 1u; k < 3u; k++) {
        hi = (a[k] > hi) ? a[k] : hi;
        lo = (a[k] < lo) ? a[k] : lo;
    }
    r = qfoc_phase_mon_imbalanced(&m2, i_min, ratio);
    if (hi < (int32_t)i_min) {
        __CPROVER_assert(!r, "largest magnitude below i_min: not reported");
    }
    if (hi == 0) {
        __CPROVER_assert(!r, "no current: never reported");
    }
    if ((lo == 0) && (hi > 0) && (hi >= (int32_t)i_min) && (ratio > 0)) {
        __CPROVER_assert(r, "one magnitude 0, the largest above i_min: reported");
    }

    /* the exact criterion for the ratios in use (each passed as a constant, so that
       both products are constant multiplications) */
    for (k = 0u; k < N_RATIOS; k++) {
        const int16_t rk = ratios[k];
        expect = (hi >= (int32_t)i_min) && (((int64_t)lo * 32768) < ((int64_t)rk * (int64_t)hi));
        __CPROVER_assert(qfoc_phase_mon_imbalanced(&m2, i_min, rk) == expect,
                         "criterion: max >= i_min and min < ratio x max");
    }

    qfoc_phase_mon_reset(&m);
    __CPROVER_assert(qfoc_phase_mon_is_valid(&m) && (m.abs_lpf[0].state == 0) &&
                     (m.abs_lpf[1].state == 0) && (m.abs_lpf[2].state == 0), "reset: zero, valid");
    (void)qfoc_phase_mon_init(&m, nondet_int16());
    __CPROVER_assert(qfoc_phase_mon_is_valid(&m) && (m.abs_lpf[0].state == 0) &&
                     (m.abs_lpf[1].state == 0) && (m.abs_lpf[2].state == 0), "init: zero, valid");
    return 0;
}
