/*
 * CBMC harness: qfoc_emf_step() on any valid back-EMF instance and any input.
 *
 * Properties checked for every int16_t voltage and current (-32768 included) and
 * every instance accepted by qfoc_emf_is_valid() (REQ-EMF-001, REQ-EMF-003,
 * REQ-EMF-004, REQ-EMF-005, REQ-EMF-006):
 *  - no undefined behaviour: signed/unsigned overflow, conversion, shift, bounds,
 *    pointer and division checks of the command line;
 *  - the instance is still valid afterwards, parameters and filter coefficients
 *    unchanged;
 *  - i_prev is the saturated current;
 *  - each output is its filter state rounded to Q15 (nearest, ties away from
 *    zero), in the symmetric Q15 range;
 *  - an inactive instance (rejected parameters) outputs EMF 0 and angle 0;
 *  - product-free exactness: with r = 0 and an unchanged current (or l = 0) the
 *    EMF sample is the saturated voltage, and each filter state moves in its
 *    direction (the bound "not past it" is the low-pass convexity, proved by WP
 *    for qfoc_lpf_step: behaviours rising / falling).
 * The exact products r (i + i_prev) and l (i - i_prev) of e_raw are proved by
 * Frama-C WP (contract of qfoc_emf_step, behaviour active, EmfRaw) and tested
 * bit-exactly (tests/test_emf.c): a bit-level miter of two multipliers does not
 * finish within the time budget.
 *
 * qfoc_atan2() is replaced by its contract (trig.h): any angle, 0 for the zero
 * vector.  Its own harness (trig_atan2) and WP prove the function against that
 * contract; with the real divider behind two 64-bit filter multipliers the
 * problem does not finish within the time budget.  The stub returns every value
 * the contract allows, so no behaviour of the real function is left out.
 *
 * Methods: 1b every int16 voltage and current and every valid instance, active and
 * inactive; 1c -32768 inputs, r = 0 and l = 0 (product-free special cases), the output
 * rounding ties; 1d an inactive instance (rejected parameters): output 0
 */
#include <stdint.h>
#include <stdbool.h>
#include "qfoc/emf.h"
#include "../emf_common.h"

uint16_t nondet_angle(void);

/* qfoc_atan2() by its contract: 0 for the zero vector, otherwise any angle */
qfoc_angle_t qfoc_atan2(qfoc_q15_t y, qfoc_q15_t x)
{
    qfoc_angle_t a = nondet_angle();
    if ((x == 0) && (y == 0)) {
        a = 0u;
    }
    return a;
}

/* the filter state moved from old in the direction of target (Q31) */
static bool moved_towards(int64_t old, int64_t now, int64_t target)
{
    bool ok;
    if (old <= target) {
        ok = (now >= old);
    } else {
        ok = (now <= old);
    }
    return ok;
}

int main(void)
{
    qfoc_emf_t e;
    qfoc_emf_t old;
    qfoc_ab_t u;
    qfoc_ab_t i;
    qfoc_emf_out_t out;

    build_emf(&e);
    u.alpha = nondet_int16();
    u.beta = nondet_int16();
    i.alpha = nondet_int16();
    i.beta = nondet_int16();
    old = e;

    qfoc_emf_step(&e, &u, &i, &out);

    __CPROVER_assert(qfoc_emf_is_valid(&e), "still valid");
    __CPROVER_assert((e.params.r == old.params.r) && (e.params.l == old.params.l)
                     && (e.params.alpha == old.params.alpha)
                     && (e.params.k_theta == old.params.k_theta)
                     && (e.active == old.active)
                     && (e.lpf_alpha.alpha == old.lpf_alpha.alpha)
                     && (e.lpf_beta.alpha == old.lpf_beta.alpha), "parameters unchanged");
    __CPROVER_assert((e.i_prev.alpha == sat15(i.alpha)) && (e.i_prev.beta == sat15(i.beta)),
                     "i_prev is the saturated current");
    __CPROVER_assert((out.emf.alpha >= -32767) && (out.emf.beta >= -32767),
                     "output in symmetric Q15");
    __CPROVER_assert(is_rounded_sat(out.emf.alpha, e.lpf_alpha.state)
                     && is_rounded_sat(out.emf.beta, e.lpf_beta.state),
                     "output is the rounded filter state");
    if (!old.active) {
        __CPROVER_assert((out.emf.alpha == 0) && (out.emf.beta == 0) && (out.theta == 0)
                         && (e.lpf_alpha.state == 0) && (e.lpf_beta.state == 0),
                         "inactive: output 0, angle 0");
    }
    if (old.active && (old.params.r == 0)
        && ((old.params.l == 0) || (sat15(i.alpha) == old.i_prev.alpha))) {
        __CPROVER_assert(moved_towards(old.lpf_alpha.state, e.lpf_alpha.state,
                                       (int64_t)sat15(u.alpha) * 65536),
                         "r = 0, no inductive drop: alpha state moves towards the voltage");
    }
    if (old.active && (old.params.r == 0)
        && ((old.params.l == 0) || (sat15(i.beta) == old.i_prev.beta))) {
        __CPROVER_assert(moved_towards(old.lpf_beta.state, e.lpf_beta.state,
                                       (int64_t)sat15(u.beta) * 65536),
                         "r = 0, no inductive drop: beta state moves towards the voltage");
    }
    return 0;
}
