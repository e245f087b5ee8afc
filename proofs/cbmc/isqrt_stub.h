/*
 * proofs/cbmc/isqrt_stub.h -- qfoc_isqrt32 replaced by its contract, for the
 * harnesses of its callers (vector_mag, vector_circle_limit, the PLL harnesses).
 *
 * The stub returns the one r the contract of include/qfoc/vector.h allows,
 * 0 <= r <= 65535 and r^2 <= v < (r + 1)^2 (the floor square root is
 * unique, so the callers' exact properties are checked against the exact
 * value), computed digit by digit: sixteen steps of additions, compares and
 * products by a constant power of two, a model the SAT back end solves where
 * the library's Newton steps (three symbolic unsigned divisions) are too
 * large for it.  Before the step with trial bit p, r^2 <= v < (r + 2 p)^2,
 * so after the last one (p = 1) r is the floor square root.
 * The library's qfoc_isqrt32 is proved to meet the same contract for every v
 * by Frama-C WP (src/qfoc_isqrt.c: ensures range, floor_sqrt, no run-time
 * error, loop variant), checked by its own harness (proofs/cbmc/vector_isqrt)
 * and compared with a reference on every v by tools/bench/isqrt_steps.sh.
 */
#ifndef QFOC_ISQRT_STUB_H
#define QFOC_ISQRT_STUB_H

#include "qfoc/vector.h"

uint32_t qfoc_isqrt32(uint32_t v)
{
    uint32_t r = 0u;              /* root so far, r^2 <= v */
    uint32_t rem = v;             /* v - r^2 */
    uint32_t p = 32768u;          /* trial root bit */
    uint32_t k;

    for (k = 0u; k < 16u; k++) {
        const uint32_t t = ((2u * r) + p) * p;   /* (r + p)^2 - r^2 < 2^31 */
        if (t <= rem) {
            rem = rem - t;
            r = r + p;
        }
        p = p / 2u;
    }
    return r;
}

#endif
