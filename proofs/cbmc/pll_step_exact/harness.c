/*
 * CBMC harness: exact values of qfoc_pll_step() on small flux vectors.
 *
 * Any valid instance (as proofs/cbmc/pll_step), flux components of 8 bits
 * (nondet int8_t, |x|, |y| <= 128).  Besides every property of the pll_step
 * harness (REQ-PLL-002, REQ-PLL-003, REQ-PLL-004, REQ-PLL-005, REQ-PLL-006,
 * REQ-PLL-007, REQ-PLL-010):
 *  - the magnitude is the floor square root, mag^2 <= x^2 + y^2 < (mag + 1)^2;
 *  - the coasting decision equals x^2 + y^2 < mag_min^2 (REQ-PLL-004).
 * Small operands keep the multiplier miters tractable.  The rounded, clamped
 * error (REQ-PLL-003) and sc = qfoc_sincos(theta) are proved for every input
 * by Frama-C WP (ensures mag, error, behaviour track) and tested exactly
 * against an integer reference in tests/test_pll.c.
 *
 * Methods: 1b every valid instance and every flux vector of 8 bits (|x|, |y| <= 128);
 * 1c the coasting decision at mag_min^2, mag^2 <= x^2 + y^2 < (mag + 1)^2
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
    psi.alpha = (int16_t)nondet_int8();
    psi.beta = (int16_t)nondet_int8();
    qfoc_pll_step(&pll, &psi, &out);
    check_full(&old, &pll, &out);
    check_exact(&old, &out, sat15((int32_t)psi.alpha), sat15((int32_t)psi.beta));
    return 0;
}
