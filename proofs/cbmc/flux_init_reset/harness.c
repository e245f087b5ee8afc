/*
 * CBMC harness: qfoc_flux_init() on any parameter set, then qfoc_flux_reset()
 * with any flux and current (REQ-FLUX-001, REQ-FLUX-002).
 *
 * Properties:
 *  - no undefined behaviour (all checks of the command line);
 *  - init returns 0 exactly for the sets accepted by qfoc_flux_params_is_valid()
 *    and stores them; otherwise it returns -1 and sets the safe state (all
 *    parameters 0); the state and the remembered current are 0 and the instance
 *    is valid in both cases;
 *  - reset sets each flux state to the saturated Q15 value x 4096 and the
 *    remembered current to the saturated current; the instance stays valid.
 *
 * Methods: 1b every parameter set, valid and invalid, every flux and current of the
 * reset; 1c -32768 saturated in the reset; 1d invalid parameters: the safe state
 */
#include <stdint.h>
#include <stdbool.h>
#include "qfoc/flux.h"
#include "../harness_util.h"


int main(void)
{
    qfoc_flux_params_t p;
    qfoc_flux_t o;
    qfoc_ab_t psi0;
    qfoc_ab_t i0;
    int32_t rc;
    bool ok;

    p.gain = nondet_int16();
    p.gain_shift = nondet_uint8();
    p.r = nondet_int16();
    p.l = nondet_int16();
    p.kg = nondet_int16();
    ok = qfoc_flux_params_is_valid(&p);
    __CPROVER_assert(ok == ((p.gain >= 0) && (p.gain_shift <= 15u) && (p.r >= 0)
                            && (p.l >= 0) && (p.kg >= 0)),
                     "parameter check is exactly the documented ranges");

    rc = qfoc_flux_init(&o, &p);
    __CPROVER_assert(qfoc_flux_is_valid(&o), "init result valid");
    __CPROVER_assert((o.psi_alpha == 0) && (o.psi_beta == 0) && (o.i_prev.alpha == 0)
                     && (o.i_prev.beta == 0), "init clears the state");
    if (ok) {
        __CPROVER_assert((rc == QFOC_FLUX_OK) && (o.params.gain == p.gain)
                         && (o.params.gain_shift == p.gain_shift) && (o.params.r == p.r)
                         && (o.params.l == p.l) && (o.params.kg == p.kg),
                         "accepted: parameters stored, result 0");
    } else {
        __CPROVER_assert((rc == QFOC_FLUX_ERR_PARAM) && (o.params.gain == 0)
                         && (o.params.gain_shift == 0u) && (o.params.r == 0)
                         && (o.params.l == 0) && (o.params.kg == 0),
                         "rejected: safe state, result -1");
    }

    psi0.alpha = nondet_int16();
    psi0.beta = nondet_int16();
    i0.alpha = nondet_int16();
    i0.beta = nondet_int16();
    qfoc_flux_reset(&o, &psi0, &i0);
    __CPROVER_assert((o.psi_alpha == (sat15((int32_t)psi0.alpha) * 4096))
                     && (o.psi_beta == (sat15((int32_t)psi0.beta) * 4096)),
                     "reset state is sat(psi0) x 4096");
    __CPROVER_assert((o.i_prev.alpha == (int16_t)sat15((int32_t)i0.alpha))
                     && (o.i_prev.beta == (int16_t)sat15((int32_t)i0.beta)),
                     "reset current is the saturated current");
    __CPROVER_assert(qfoc_flux_is_valid(&o), "reset result valid");
    return 0;
}
