/*
 * CBMC harness: qfoc_emf_params_is_valid(), qfoc_emf_init(), qfoc_emf_reset()
 * on any parameter set and any current.
 *
 * Properties (REQ-EMF-001, REQ-EMF-002):
 *  - no undefined behaviour (checks of the command line);
 *  - init returns 0 exactly for the parameter sets qfoc_emf_params_is_valid()
 *    accepts (r >= 0, l >= 0, alpha >= 1, 1 <= k_theta <= 32767) and -1 otherwise;
 *  - accepted: parameters copied, active, filters with coefficient alpha;
 *    rejected: the safe state r = l = 0, alpha = 32767, k_theta = 0, inactive;
 *  - in both cases the instance is valid with all states 0;
 *  - reset keeps it valid, sets i_prev to the saturated current and the filter
 *    states to 0, and keeps parameters and the active flag.
 *
 * Methods: 1b every parameter set, valid and invalid, and every current; 1c k_theta 0,
 * 1, 32767 and 32768, alpha 0 and 1, r and l -1 and 0, the current -32768 (saturated);
 * 1d invalid parameters: the safe, inactive state
 */
#include <stdint.h>
#include <stdbool.h>
#include "qfoc/emf.h"

int16_t nondet_int16(void);
uint16_t nondet_uint16(void);

int main(void)
{
    qfoc_emf_params_t p;
    qfoc_emf_t e;
    qfoc_ab_t i0;
    int32_t rc;
    bool ok;

    p.r = nondet_int16();
    p.l = nondet_int16();
    p.alpha = nondet_int16();
    p.k_theta = nondet_uint16();
    i0.alpha = nondet_int16();
    i0.beta = nondet_int16();

    ok = qfoc_emf_params_is_valid(&p);
    __CPROVER_assert(ok == ((p.r >= 0) && (p.l >= 0) && (p.alpha >= 1) && (p.k_theta >= 1u)
                            && (p.k_theta <= 32767u)), "parameter check as specified");
    rc = qfoc_emf_init(&e, &p);
    __CPROVER_assert(qfoc_emf_is_valid(&e), "valid after init");
    __CPROVER_assert((e.lpf_alpha.state == 0) && (e.lpf_beta.state == 0)
                     && (e.i_prev.alpha == 0) && (e.i_prev.beta == 0), "state 0 after init");
    if (ok) {
        __CPROVER_assert((rc == QFOC_EMF_OK) && e.active && (e.params.r == p.r)
                         && (e.params.l == p.l) && (e.params.alpha == p.alpha)
                         && (e.params.k_theta == p.k_theta)
                         && (e.lpf_alpha.alpha == p.alpha) && (e.lpf_beta.alpha == p.alpha),
                         "accepted: parameters stored, active");
    } else {
        __CPROVER_assert((rc == QFOC_EMF_ERR_PARAM) && !e.active && (e.params.r == 0)
                         && (e.params.l == 0) && (e.params.alpha == 32767)
                         && (e.params.k_theta == 0u), "rejected: safe state");
    }

    qfoc_emf_reset(&e, &i0);
    __CPROVER_assert(qfoc_emf_is_valid(&e), "valid after reset");
    __CPROVER_assert((e.i_prev.alpha == ((i0.alpha < -32767) ? -32767 : i0.alpha))
                     && (e.i_prev.beta == ((i0.beta < -32767) ? -32767 : i0.beta)),
                     "reset: i_prev is the saturated current");
    __CPROVER_assert((e.lpf_alpha.state == 0) && (e.lpf_beta.state == 0)
                     && (e.active == ok), "reset: estimate 0, flag kept");
    return 0;
}
