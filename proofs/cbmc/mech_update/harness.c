/*
 * CBMC harness: qfoc_mech_update() on any valid tracker and any electrical angle.
 *
 * Properties (REQ-TC-001, REQ-TC-002), for every pole-pair count 1..16, every
 * revolution count, every previous and new angle:
 *  - no undefined behaviour (overflow, conversion, shift, bounds, pointer checks of
 *    the command line), in particular the uint64 product n x recip;
 *  - the tracker is still valid afterwards and holds the new angle;
 *  - the revolution count follows the step rule: d = theta_e - previous below
 *    -32768 is a forward wrap, above 32767 a reverse wrap (modulo pole_pairs),
 *    otherwise unchanged;
 *  - the result is exactly floor((turn x 65536 + theta_e) / pole_pairs), checked
 *    as result x pp <= n < result x pp + pp (multiplications by pp <= 16 only),
 *    for the pole-pair counts 1..4 (the reference motor: 3), 8 and 16.  For the
 *    other counts the harness checks the absence of undefined behaviour, the
 *    revolution rule and the validity; their exactness is proved by Frama-C WP
 *    (lemmas MechExact1..16, ensures `result` of qfoc_mech_update) and tested
 *    exhaustively (every count of a mechanical turn, tests/test_trqcomp.c): in CBMC
 *    each exact count costs about 10 s, all sixteen exceed the time budget.
 * The tracker is built by qfoc_mech_init() for each pole-pair count 1..16 (a loop:
 * UNWIND 17) with any previous angle and any revolution count accepted by
 * qfoc_mech_is_valid(): a single symbolic pole-pair count makes the reciprocal a
 * symbolic quotient and the 64-bit product too large for the time budget.
 *
 * Methods: 1b every pole-pair count 1 .. 16, every revolution count, every previous and
 * new angle; 1c the step -32768 / 32767 deciding a forward or reverse wrap, the exact
 * floor for 1 .. 4, 8 and 16 pole pairs
 */
#include <stdint.h>
#include <stdbool.h>
#include "qfoc/trqcomp.h"

uint8_t nondet_uint8(void);
uint16_t nondet_uint16(void);
uint32_t nondet_uint32(void);

/* one pole-pair count: any valid state of it, any new angle */
static void check_pp(uint8_t pole_pairs, bool exact)
{
    qfoc_mech_t m;
    const qfoc_angle_t theta = nondet_uint16();
    qfoc_angle_t th_m;
    uint32_t turn_old;
    uint32_t turn_exp;
    int32_t diff;
    uint32_t pp;
    uint32_t n;

    (void)qfoc_mech_init(&m, pole_pairs, nondet_uint16());
    m.turn = nondet_uint8();
    __CPROVER_assume(qfoc_mech_is_valid(&m));
    pp = (uint32_t)m.pole_pairs;
    __CPROVER_assert(pp == (uint32_t)pole_pairs, "pole pairs stored");
    turn_old = (uint32_t)m.turn;
    diff = (int32_t)theta - (int32_t)m.theta_e;

    th_m = qfoc_mech_update(&m, theta);

    __CPROVER_assert(qfoc_mech_is_valid(&m), "still valid");
    __CPROVER_assert(m.theta_e == theta, "angle stored");
    if (diff < -32768) {
        turn_exp = ((turn_old + 1u) == pp) ? 0u : (turn_old + 1u);
    } else if (diff > 32767) {
        turn_exp = (turn_old == 0u) ? (pp - 1u) : (turn_old - 1u);
    } else {
        turn_exp = turn_old;
    }
    __CPROVER_assert((uint32_t)m.turn == turn_exp, "revolution count rule");
    n = ((uint32_t)m.turn * 65536u) + (uint32_t)theta;
    __CPROVER_assert((uint32_t)th_m <= n, "result not above the count");
    if (exact) {
        __CPROVER_assert(((uint32_t)th_m * pp) <= n, "result not above n / pp");
        __CPROVER_assert(n < (((uint32_t)th_m * pp) + pp), "result is floor(n / pp)");
    }
}

int main(void)
{
    uint8_t pp;
    /* every pole-pair count 1..16 in turn: each copy of the check sees a constant
       reciprocal, so the uint64 product is a multiplication by a constant */
    for (pp = 1u; pp <= 16u; pp++) {
        /* exactness: 1..4 (the reference motor has 3), 8, 16 */
        check_pp(pp, (pp <= 4u) || (pp == 8u) || (pp == 16u));
    }
    return 0;
}
