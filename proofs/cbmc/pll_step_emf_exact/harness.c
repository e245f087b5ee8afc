/*
 * CBMC harness: exact values of qfoc_pll_step_emf() on small EMF vectors.
 *
 * Any valid instance, EMF components of 8 bits (nondet int8_t).  Properties
 * (REQ-PLL-002, REQ-PLL-004, REQ-PLL-006, REQ-PLL-008, REQ-PLL-010): every property
 * of the pll_step harness; the magnitude of the flux direction the loop uses is the
 * floor square root of e_alpha^2 + e_beta^2 (= |e|), and the coasting decision
 * equals e_alpha^2 + e_beta^2 < mag_min^2.  Which direction is used,
 * (e_beta, -e_alpha) for an integrator >= 0 and (-e_beta, e_alpha) otherwise,
 * and the rounded error on it are proved by Frama-C WP (ensures mag, error of
 * qfoc_pll_step_emf with PllAtoX / PllAtoY) and tested exactly in
 * tests/test_pll.c (test_pll_req008_emf_one_step_vs_reference).
 *
 * Methods: 1b every valid instance and every EMF vector of 8 bits; 1c the coasting
 * decision at mag_min^2, the magnitude as the floor square root
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
    int32_t ea;
    int32_t eb;

    build(&pll);
    old = pll;
    emf.alpha = (int16_t)nondet_int8();
    emf.beta = (int16_t)nondet_int8();
    ea = sat15((int32_t)emf.alpha);
    eb = sat15((int32_t)emf.beta);
    qfoc_pll_step_emf(&pll, &emf, &out);
    check_full(&old, &pll, &out);
    /* the flux direction (e_beta, -e_alpha) or (-e_beta, e_alpha) has the length
       of the EMF: its squares are e_alpha^2 + e_beta^2 in either case */
    check_exact(&old, &out, ea, eb);
    return 0;
}
