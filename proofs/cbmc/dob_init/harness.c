/*
 * CBMC harness: qfoc_dob_params_is_valid(), qfoc_dob_init(), qfoc_dob_reset()
 * on any parameter set and any current.
 *
 * Properties (REQ-EMF-008, REQ-EMF-009):
 *  - no undefined behaviour (checks of the command line);
 *  - qfoc_dob_params_is_valid() accepts only ki >= 1, ki_shift <= 15, r >= 0,
 *    g >= 1, 1 <= k_theta <= 32767, and among those every set with
 *    lambda = ki g / 2^(27 + ki_shift) < 1 by a product-free bound (g <= 4096,
 *    or ki_shift >= 3); it rejects ki = g = 32767 at ki_shift 0 .. 2.  The exact
 *    lambda <= 1 boundary is proved by WP (DobParamsValid) and tested at its
 *    edges (tests/test_emf.c): a miter of the two products does not finish
 *    within the time budget;
 *  - init returns 0 exactly when the check accepts, -1 otherwise;
 *  - accepted: parameters copied; rejected: the safe state (all 0);
 *  - in both cases the instance is valid with all states 0;
 *  - reset keeps it valid: i_hat = 4096 i0, i_prev = i0 (saturated), e_prev = 0.
 *
 * Methods: 1b every parameter set, valid and invalid, and every current; 1c ki = g =
 * 32767 at ki_shift 0 .. 2 (lambda above 1, rejected), the currents -32768 (saturated);
 * 1d invalid parameters: the safe state
 */
#include <stdint.h>
#include <stdbool.h>
#include "qfoc/emf.h"

int16_t nondet_int16(void);
uint16_t nondet_uint16(void);
uint8_t nondet_uint8(void);

int main(void)
{
    qfoc_dob_params_t p;
    qfoc_dob_t d;
    qfoc_ab_t i0;
    int32_t rc;
    bool ok;
    bool expect;
    int32_t ia;
    int32_t ib;

    p.ki = nondet_int16();
    p.ki_shift = nondet_uint8();
    p.r = nondet_int16();
    p.g = nondet_int16();
    p.k_theta = nondet_uint16();
    i0.alpha = nondet_int16();
    i0.beta = nondet_int16();

    ok = qfoc_dob_params_is_valid(&p);
    expect = (p.ki >= 1) && (p.ki_shift <= 15u) && (p.r >= 0) && (p.g >= 1)
             && (p.k_theta >= 1u) && (p.k_theta <= 32767u);
    if (ok) {
        __CPROVER_assert(expect, "accepted sets satisfy the range conditions");
    }
    if (expect && ((p.g <= 4096) || (p.ki_shift >= 3u))) {
        /* ki g < 2^15 x 2^12 = 2^27, or ki g < 2^30 <= 2^(27 + ki_shift): lambda < 1 */
        __CPROVER_assert(ok, "lambda < 1 by bound: accepted");
    }
    if ((p.ki == 32767) && (p.g == 32767) && (p.ki_shift <= 2u)) {
        /* 32767^2 > 2^29 >= 2^(27 + ki_shift): lambda > 1 */
        __CPROVER_assert(!ok, "lambda > 1: rejected");
    }
    rc = qfoc_dob_init(&d, &p);
    __CPROVER_assert(qfoc_dob_is_valid(&d), "valid after init");
    __CPROVER_assert((d.ih_alpha == 0) && (d.ih_beta == 0) && (d.i_prev.alpha == 0)
                     && (d.i_prev.beta == 0) && (d.e_prev.alpha == 0) && (d.e_prev.beta == 0),
                     "state 0 after init");
    if (ok) {
        __CPROVER_assert((rc == QFOC_EMF_OK) && (d.params.ki == p.ki)
                         && (d.params.ki_shift == p.ki_shift) && (d.params.r == p.r)
                         && (d.params.g == p.g) && (d.params.k_theta == p.k_theta),
                         "accepted: parameters stored");
    } else {
        __CPROVER_assert((rc == QFOC_EMF_ERR_PARAM) && (d.params.ki == 0)
                         && (d.params.ki_shift == 0u) && (d.params.r == 0) && (d.params.g == 0)
                         && (d.params.k_theta == 0u), "rejected: safe state");
    }

    qfoc_dob_reset(&d, &i0);
    ia = (i0.alpha < -32767) ? -32767 : i0.alpha;
    ib = (i0.beta < -32767) ? -32767 : i0.beta;
    __CPROVER_assert(qfoc_dob_is_valid(&d), "valid after reset");
    __CPROVER_assert((d.i_prev.alpha == ia) && (d.i_prev.beta == ib)
                     && (d.ih_alpha == (ia * 4096)) && (d.ih_beta == (ib * 4096))
                     && (d.e_prev.alpha == 0) && (d.e_prev.beta == 0),
                     "reset: i_hat = i_prev = i0, e_prev = 0");
    return 0;
}
