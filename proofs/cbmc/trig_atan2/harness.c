/*
 * CBMC harness: qfoc_atan2 over every (y, x) pair (nondet int16, -32768 included).
 * Checks: no run-time error (division by zero, overflow, conversion, bounds),
 * atan2(0, 0) == 0, exact axes and diagonals, and the quadrant of the result
 * (with the real tables, closed: a vector one count off an axis may round
 * onto it): x > 0, y > 0 -> [0, 0x4000], and so on.
 * Requirements: REQ-TRIG-003, REQ-TRIG-004.
 *
 * Methods: 1b every (y, x) pair, the quadrant of each result; 1c (0, 0), the four axes
 * and the diagonals, -32768
 */
#include "qfoc/trig.h"

int16_t nondet_int16(void);

int main(void)
{
    qfoc_q15_t y = nondet_int16();
    qfoc_q15_t x = nondet_int16();
    qfoc_angle_t a = qfoc_atan2(y, x);
    uint32_t au = (uint32_t)a;

    if ((x == 0) && (y == 0)) {
        __CPROVER_assert(a == 0u, "atan2(0, 0) = 0");
    }
    if ((y == 0) && (x > 0)) {
        __CPROVER_assert(a == 0u, "+x axis");
    }
    if ((x == 0) && (y > 0)) {
        __CPROVER_assert(a == 0x4000u, "+y axis");
    }
    if ((y == 0) && (x < 0)) {
        __CPROVER_assert(a == 0x8000u, "-x axis");
    }
    if ((x == 0) && (y < 0)) {
        __CPROVER_assert(a == 0xC000u, "-y axis");
    }
    if ((x != 0) && ((x == y) || ((int32_t)x == -(int32_t)y))) {
        __CPROVER_assert((au % 0x4000u) == 0x2000u, "diagonal = 45 deg + k 90 deg");
    }
    if ((x > 0) && (y > 0)) {
        __CPROVER_assert(au <= 0x4000u, "first quadrant [0, 90] deg");
    }
    if ((x < 0) && (y > 0)) {
        __CPROVER_assert((au >= 0x4000u) && (au <= 0x8000u), "second quadrant [90, 180] deg");
    }
    if ((x < 0) && (y < 0)) {
        __CPROVER_assert((au >= 0x8000u) && (au <= 0xC000u), "third quadrant [180, 270] deg");
    }
    if ((x > 0) && (y < 0)) {
        __CPROVER_assert((au >= 0xC000u) || (au == 0u), "fourth quadrant [270, 360] deg");
    }
    return 0;
}
