/*
 * CBMC harness: qfoc_pll_step_emf() (angle-tracking observer) on any valid
 * instance and any back-EMF vector.
 *
 * Any valid instance (as proofs/cbmc/pll_step), EMF components any int16_t
 * values (-32768 included), real bodies of the called functions but qfoc_sincos (a
 * stub returning any pair its contract allows, pll_common.h).  Properties
 * (REQ-PLL-002, REQ-PLL-004, REQ-PLL-006, REQ-PLL-008, REQ-PLL-010): every
 * property of the pll_step harness (no undefined behaviour, still valid,
 * configuration unchanged, theta / theta_next, accumulator modulo 2^32,
 * error clamp, speed limits, speed_f, coasting).  The flux direction chosen
 * from the integrator sign is checked on small vectors by
 * proofs/cbmc/pll_step_emf_exact.
 *
 * Methods: 1b every valid instance and every int16 EMF vector, integrators of both
 * signs; 1c -32768 components, the accumulator modulo 2^32, |error| at err_clamp,
 * coasting below mag_min
 */
#include <stdint.h>
#include <stdbool.h>
#include "qfoc/pll.h"
#include "../pll_common.h"

int main(void)
{
    qfoc_pll_t pll;
    qfoc_pll_t old;
    qfoc_pll_out_t out;
    qfoc_ab_t emf;

    build(&pll);
    old = pll;
    emf.alpha = nondet_int16();
    emf.beta = nondet_int16();
    qfoc_pll_step_emf(&pll, &emf, &out);
    check_full(&old, &pll, &out);
    return 0;
}
