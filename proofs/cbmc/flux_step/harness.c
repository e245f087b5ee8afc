/*
 * CBMC harness: qfoc_flux_step() on any valid instance and any inputs.
 *
 * Properties checked for every int16_t input (-32768 included) and every
 * instance accepted by qfoc_flux_is_valid() (REQ-FLUX-001, REQ-FLUX-003, REQ-FLUX-004,
 * REQ-FLUX-005):
 *  - no undefined behaviour: signed/unsigned overflow, conversion, shift, bounds,
 *    pointer and division checks of the command line (the 64-bit products, the
 *    unsigned 32-bit quotient of the step division);
 *  - the instance is still valid afterwards and the parameters are unchanged;
 *  - the remembered current is the saturated input current;
 *  - each output is its new state rounded to Q15 (nearest, ties away from zero),
 *    saturated to [-32767, 32767];
 *  - with gain = 0 and l = 0 the state is unchanged.
 * The exact update (behaviours alpha_exact/upper/lower, beta_...) and the
 * flux-bound invariance (2-25/2-26) are proved by Frama-C WP (contract of
 * qfoc_flux_step, lemma FluxBoundInvariant) and tested bit-exactly against a
 * double reference (tests/test_flux.c): properties that relate the products of
 * the step to each other (e.g. the sign of -l di) need bit-level reasoning through
 * the multipliers that does not finish within the time budget (over 10 min).
 *
 * Methods: 1b every int16 input and every valid instance; 1c -32768 inputs, the output
 * saturated to +-32767, gain = 0 and l = 0 (state unchanged)
 */
#include <stdint.h>
#include <stdbool.h>
#include "qfoc/flux.h"

int16_t nondet_int16(void);
int32_t nondet_int32(void);
uint8_t nondet_uint8(void);

/* q is x / 4096 rounded to nearest, ties away from zero, then saturated to the
   symmetric Q15 range (checked by multiplication with a constant, no divider) */
static bool is_rounded_sat(int64_t q, int64_t x)
{
    bool ok;
    if (x >= ((32767 * 4096) + 2048)) {
        ok = (q == 32767);
    } else if (x <= -((32767 * 4096) + 2048)) {
        ok = (q == -32767);
    } else if (x >= 0) {
        ok = (((q * 4096) - 2048) <= x) && (x < ((q * 4096) + 2048));
    } else {
        ok = (((q * 4096) - 2048) < x) && (x <= ((q * 4096) + 2048));
    }
    return ok;
}

static int64_t sat15(int64_t x)
{
    return (x < -32767) ? -32767 : x;
}

int main(void)
{
    qfoc_flux_t o;
    qfoc_flux_t old;
    qfoc_ab_t u;
    qfoc_ab_t i;
    qfoc_ab_t out;

    o.params.gain = nondet_int16();
    o.params.gain_shift = nondet_uint8();
    o.params.r = nondet_int16();
    o.params.l = nondet_int16();
    o.params.kg = nondet_int16();
    o.psi_alpha = nondet_int32();
    o.psi_beta = nondet_int32();
    o.i_prev.alpha = nondet_int16();
    o.i_prev.beta = nondet_int16();
    u.alpha = nondet_int16();
    u.beta = nondet_int16();
    i.alpha = nondet_int16();
    i.beta = nondet_int16();
    __CPROVER_assume(qfoc_flux_is_valid(&o));
    old = o;

    qfoc_flux_step(&o, &u, &i, &out);

    __CPROVER_assert(qfoc_flux_is_valid(&o), "still valid");
    __CPROVER_assert((o.params.gain == old.params.gain)
                     && (o.params.gain_shift == old.params.gain_shift)
                     && (o.params.r == old.params.r) && (o.params.l == old.params.l)
                     && (o.params.kg == old.params.kg), "parameters unchanged");
    __CPROVER_assert((o.i_prev.alpha == (int16_t)sat15((int64_t)i.alpha))
                     && (o.i_prev.beta == (int16_t)sat15((int64_t)i.beta)),
                     "remembered current is the saturated input");
    __CPROVER_assert((out.alpha >= -32767) && (out.alpha <= 32767)
                     && (out.beta >= -32767) && (out.beta <= 32767),
                     "outputs in symmetric Q15");
    __CPROVER_assert(is_rounded_sat((int64_t)out.alpha, (int64_t)o.psi_alpha),
                     "alpha output is the rounded, saturated state");
    __CPROVER_assert(is_rounded_sat((int64_t)out.beta, (int64_t)o.psi_beta),
                     "beta output is the rounded, saturated state");
    if ((old.params.gain == 0) && (old.params.l == 0)) {
        __CPROVER_assert((o.psi_alpha == old.psi_alpha) && (o.psi_beta == old.psi_beta),
                         "gain 0 and l 0: state unchanged");
    }
    return 0;
}
