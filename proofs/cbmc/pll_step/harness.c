/*
 * CBMC harness: qfoc_pll_step() on any valid instance and any flux vector.
 *
 * The instance is built from nondet parameters and state and kept only when
 * qfoc_pll_is_valid() accepts it (any gains, limits, integrator inside them,
 * low-pass coefficient and state, theta_acc, clamp, mag_min, k_theta); the
 * flux components are any int16_t values (-32768 included).  The real bodies
 * of qfoc_vec_mag, qfoc_pi_step and qfoc_lpf_step are linked; qfoc_sincos is a
 * stub returning any pair its contract allows (pll_common.h).
 * Properties (REQ-PLL-002, REQ-PLL-003, REQ-PLL-004, REQ-PLL-005, REQ-PLL-006,
 * REQ-PLL-007, REQ-PLL-010):
 *  - no undefined behaviour anywhere in the step (signed/unsigned overflow,
 *    conversion, shift, bounds, pointer, division checks of the command line);
 *  - the instance is still valid, its configuration unchanged;
 *  - theta is the old accumulator rounded to 2^-16 turn (mod 2^16),
 *    theta_next the new one;
 *  - the accumulator advances by speed x k_theta modulo 2^32 (for k_theta 1,
 *    8192 and 32767, see check_full);
 *  - |error| <= err_clamp; speed inside the PI limits and stored; speed_f is
 *    the new low-pass state rounded to Q15;
 *  - coasting: mag < mag_min gives error 0 and a held integrator; otherwise the
 *    divisor is at least 1.
 * The magnitude and the coasting decision are checked exactly on small vectors
 * by proofs/cbmc/pll_step_exact; the exact error and sc are proved for every
 * input by Frama-C WP and tested exactly in tests/test_pll.c.
 *
 * Methods: 1b every valid instance and every int16 flux vector; 1c -32768 components,
 * k_theta 1, 8192 and 32767, the accumulator modulo 2^32, |error| at err_clamp, a
 * magnitude just below mag_min (coasting)
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
    qfoc_ab_t psi;

    build(&pll);
    old = pll;
    psi.alpha = nondet_int16();
    psi.beta = nondet_int16();
    qfoc_pll_step(&pll, &psi, &out);
    check_full(&old, &pll, &out);
    return 0;
}
