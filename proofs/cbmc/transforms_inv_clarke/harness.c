/* CBMC harness: qfoc_inv_clarke over all int16 inputs.
 * Checks REQ-TRF-007 (ranges, u = sat(alpha)) and REQ-TRF-008 (v, w exact when
 * the Q30 sums fit, saturated otherwise)
 * against an independent int64 computation.
 *
 * Scope of the bit-level check: the runtime-error checks (overflow, conversion,
 * pointers) and the output ranges hold over ALL int16 inputs.  Equality with the
 * independent reference needs the solver to prove two multiplier circuits equal,
 * which does not finish for full 16-bit operands; it is checked here for operands
 * of magnitude <= 255 and at the saturation corners, and over all inputs by WP
 * (the contract's exact behaviours) and by tests/test_transforms.c.
 *
 * Methods: 1b every int16 pair for the ranges, operands up to 255 for the exact
 * values; 1c the saturation corners, u = sat(alpha) with -32768 */
#include <stdint.h>
#include "qfoc/transforms.h"

int16_t nondet_int16(void);

/* x / 2^15 rounded to nearest, ties away from zero */
static int64_t round_q30(int64_t x)
{
    int64_t r;
    if (x >= 0) {
        r = (x + 16384) >> 15;   /* non-negative operand */
    } else {
        r = -((16384 - x) >> 15);
    }
    return r;
}

int main(void)
{
    qfoc_ab_t in;
    qfoc_abc_t out;
    int64_t a;
    int64_t b;
    int64_t vx;
    int64_t wx;
    int small;
    int corner;

    in.alpha = nondet_int16();
    in.beta = nondet_int16();
    a = (in.alpha == -32768) ? (int64_t)-32767 : (int64_t)in.alpha;
    b = (in.beta == -32768) ? (int64_t)-32767 : (int64_t)in.beta;
    vx = (-(a * 16384)) + (b * 28378);
    wx = (-(a * 16384)) - (b * 28378);

    qfoc_inv_clarke(&in, &out);

    __CPROVER_assert((out.u >= -32767) && (out.u <= 32767), "u range");
    __CPROVER_assert((out.v >= -32767) && (out.v <= 32767), "v range");
    __CPROVER_assert((out.w >= -32767) && (out.w <= 32767), "w range");
    __CPROVER_assert((int64_t)out.u == a, "u = sat(alpha)");
    small = (a >= -255) && (a <= 255) && (b >= -255) && (b <= 255);
    corner = ((a == 32767) || (a == -32767)) && ((b == 32767) || (b == -32767));
    if (small || corner) {
        if ((vx > -1073725440) && (vx < 1073725440)) {
            __CPROVER_assert((int64_t)out.v == round_q30(vx), "v exact");
        } else {
            __CPROVER_assert(out.v == ((vx > 0) ? 32767 : -32767), "v saturated");
        }
        if ((wx > -1073725440) && (wx < 1073725440)) {
            __CPROVER_assert((int64_t)out.w == round_q30(wx), "w exact");
        } else {
            __CPROVER_assert(out.w == ((wx > 0) ? 32767 : -32767), "w saturated");
        }
    }
    return 0;
}
