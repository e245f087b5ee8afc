/*
 * CBMC harness: qfoc_sin / qfoc_sincos over every angle (nondet uint16).
 * Checks: no run-time error (overflow, conversion, bounds, shift), both
 * outputs in [-32767, 32767], exact odd symmetry of the sine
 * sin(theta + 0x8000) == -sin(theta) (so also of the cosine, which is the same
 * function 0x4000 ahead), exact axis values.  The relation
 * cosine == qfoc_sin(theta + 0x4000) is tested over all angles in
 * tests/test_trig.c (a fourth symbolic call would only slow this proof down).
 * Requirements: REQ-TRIG-001, REQ-TRIG-002.
 *
 * Methods: 1b every angle, the odd symmetry sin(theta + 0x8000) = -sin(theta); 1c the
 * axis values at 0 and 0x4000, the range [-32767, 32767]
 */
#include "qfoc/trig.h"

uint16_t nondet_uint16(void);

int main(void)
{
    qfoc_angle_t theta = nondet_uint16();
    qfoc_sincos_t sc;
    qfoc_q15_t s_half;
    qfoc_angle_t theta_half = (qfoc_angle_t)(((uint32_t)theta + 0x8000u) & 0xFFFFu);

    qfoc_sincos(theta, &sc);
    s_half = qfoc_sin(theta_half);

    __CPROVER_assert((sc.sine >= -32767) && (sc.sine <= 32767), "sine range");
    __CPROVER_assert((sc.cosine >= -32767) && (sc.cosine <= 32767), "cosine range");
    __CPROVER_assert((int32_t)s_half == -(int32_t)sc.sine,
                     "odd symmetry sin(theta + 180 deg) = -sin(theta)");
    if (theta == 0u) {
        __CPROVER_assert((sc.sine == 0) && (sc.cosine == 32767), "sincos(0) = (0, 32767)");
    }
    if (theta == 0x4000u) {
        __CPROVER_assert((sc.sine == 32767) && (sc.cosine == 0), "sincos(90 deg) = (32767, 0)");
    }
    return 0;
}
