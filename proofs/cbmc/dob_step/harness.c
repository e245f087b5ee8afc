/*
 * CBMC harness: qfoc_dob_step() on any valid disturbance-observer instance and
 * any input.
 *
 * Properties checked for every int16_t voltage and current (-32768 included) and
 * every instance accepted by qfoc_dob_is_valid() (REQ-EMF-008, REQ-EMF-010,
 * REQ-EMF-005, REQ-EMF-014):
 *  - no undefined behaviour: signed/unsigned overflow, conversion, shift, bounds,
 *    pointer and division checks of the command line (the 64-bit products
 *    x ki 2^(15 - ki_shift) and G (i_hat - i) included);
 *  - the instance is still valid afterwards, parameters unchanged;
 *  - i_prev is the saturated current, e_prev is the output EMF, both in the
 *    symmetric Q15 range;
 *  - the safe state (G = 0) outputs EMF 0 and angle 0;
 *  - product-free exactness: k_i = 0 leaves the predicted current unchanged;
 *    with r = 0 the predicted current moves in the direction of u - e_prev; the
 *    EMF has the sign of i_hat - i (G >= 0).
 * The exact values of the products are proved by Frama-C WP (contract of
 * qfoc_dob_step: DobNext, DobEmf) and tested bit-exactly (tests/test_emf.c).
 *
 * qfoc_atan2() is replaced by its contract (trig.h): any angle, 0 for the zero
 * vector.  Its own harness (trig_atan2) and WP prove the function against that
 * contract; the stub returns every value the contract allows, so no behaviour of
 * the real function is left out.
 *
 * Methods: 1b every int16 voltage and current and every valid instance; 1c -32768
 * inputs, the safe state G = 0, k_i = 0, r = 0 (product-free special cases)
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

int main(void)
{
    qfoc_dob_t d;
    qfoc_dob_t old;
    qfoc_ab_t u;
    qfoc_ab_t i;
    qfoc_emf_out_t out;

    build_dob(&d);
    u.alpha = nondet_int16();
    u.beta = nondet_int16();
    i.alpha = nondet_int16();
    i.beta = nondet_int16();
    old = d;

    qfoc_dob_step(&d, &u, &i, &out);

    __CPROVER_assert(qfoc_dob_is_valid(&d), "still valid");
    __CPROVER_assert((d.params.ki == old.params.ki) && (d.params.ki_shift == old.params.ki_shift)
                     && (d.params.r == old.params.r) && (d.params.g == old.params.g)
                     && (d.params.k_theta == old.params.k_theta), "parameters unchanged");
    __CPROVER_assert((d.i_prev.alpha == sat15(i.alpha)) && (d.i_prev.beta == sat15(i.beta)),
                     "i_prev is the saturated current");
    __CPROVER_assert((out.emf.alpha == d.e_prev.alpha) && (out.emf.beta == d.e_prev.beta),
                     "output is e_prev");
    __CPROVER_assert((out.emf.alpha >= -32767) && (out.emf.beta >= -32767),
                     "output in symmetric Q15");
    if (old.params.g == 0) {
        __CPROVER_assert((out.emf.alpha == 0) && (out.emf.beta == 0) && (out.theta == 0),
                         "G = 0: output 0, angle 0");
    }
    if (old.params.ki == 0) {
        __CPROVER_assert((d.ih_alpha == old.ih_alpha) && (d.ih_beta == old.ih_beta),
                         "k_i = 0: predicted current unchanged");
    }
    if (old.params.r == 0) {
        if (sat15(u.alpha) >= old.e_prev.alpha) {
            __CPROVER_assert(d.ih_alpha >= old.ih_alpha, "r = 0, u >= e_prev: i_hat does not fall");
        } else {
            __CPROVER_assert(d.ih_alpha <= old.ih_alpha, "r = 0, u < e_prev: i_hat does not rise");
        }
    }
    if ((int64_t)d.ih_alpha >= ((int64_t)sat15(i.alpha) * 4096)) {
        __CPROVER_assert(d.e_prev.alpha >= 0, "i_hat >= i: EMF >= 0");
    } else {
        __CPROVER_assert(d.e_prev.alpha <= 0, "i_hat < i: EMF <= 0");
    }
    return 0;
}
