/*
 * CBMC harness: qfoc_flux_lead() on any valid instance and any speed
 * (REQ-FLUX-007).
 *
 * Properties:
 *  - no undefined behaviour (all checks of the command line), in particular no
 *    unsigned wrap-around in the negation modulo 2^16;
 *  - kg = 0 (pure integrator): lead 0 at every speed;
 *  - kg > 0 at standstill: lead 16384 (90 degrees);
 *  - forward rotation (w > 0): lead in [0, 90] degrees; reverse rotation
 *    (w < 0, -32768 included): lead in [-90, 0] degrees modulo 2^16.
 * The value atan2(kg, |w|) and the symmetry lead(-w) = -lead(w) are tested
 * against atan() in tests/test_flux.c (test_flux_007_lead); a second call in
 * this harness (to compare the two directions) needs bit-level reasoning through
 * two dividers that does not finish within the time budget.
 *
 * Methods: 1b every int16 speed (forward, reverse, standstill) and every valid
 * instance; 1c kg = 0, w = 0 (90 degrees), w = -32768, the range [0, 90] and [-90, 0]
 * degrees modulo 2^16
 */
#include <stdint.h>
#include <stdbool.h>
#include "qfoc/flux.h"

int16_t nondet_int16(void);
int32_t nondet_int32(void);
uint8_t nondet_uint8(void);

int main(void)
{
    qfoc_flux_t o;
    qfoc_q15_t w = nondet_int16();
    qfoc_angle_t a;

    o.params.gain = nondet_int16();
    o.params.gain_shift = nondet_uint8();
    o.params.r = nondet_int16();
    o.params.l = nondet_int16();
    o.params.kg = nondet_int16();
    o.psi_alpha = nondet_int32();
    o.psi_beta = nondet_int32();
    o.i_prev.alpha = nondet_int16();
    o.i_prev.beta = nondet_int16();
    __CPROVER_assume(qfoc_flux_is_valid(&o));

    a = qfoc_flux_lead(&o, w);
    if (o.params.kg == 0) {
        __CPROVER_assert(a == 0u, "no high-pass: lead 0");
    }
    if ((o.params.kg > 0) && (w == 0)) {
        __CPROVER_assert(a == 16384u, "standstill: 90 deg");
    }
    if (w > 0) {
        __CPROVER_assert((uint32_t)a <= 16384u, "forward: lead in [0, 90] deg");
    }
    if (w < 0) {
        __CPROVER_assert((a == 0u) || ((uint32_t)a >= 49152u),
                         "reverse: lead in [-90, 0] deg (mod 2^16)");
    }
    return 0;
}
