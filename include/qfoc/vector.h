/**
 * @file vector.h
 * @brief Integer square root, vector magnitude and circle limitation (Q15).
 *
 * Used by the current loop and the SVPWM overmodulation (qfoc_circle_limit),
 * field weakening, and estimators (qfoc_vec_mag).  All functions are total
 * and exact in integer arithmetic: no floating point; the square root takes
 * at most four compares, three unsigned divisions and one correction step,
 * so its execution time is bounded.
 *
 * Requirements: REQ-VEC-001 .. REQ-VEC-004 (specs/requirements/trig.md).
 */
#ifndef QFOC_VECTOR_H
#define QFOC_VECTOR_H

#include "qfoc/types.h"

#ifdef __cplusplus
extern "C" {
#endif

#ifdef __FRAMAC__
#include "vector.acsl"
#endif

/**
 * @brief Integer square root, rounded down: floor(sqrt(v)).
 *
 * @param[in] v any uint32_t value
 * @return r with r * r <= v < (r + 1) * (r + 1), r in [0, 65535]
 *
 * Method: at most four compares find the range [4^k, 4^(k+1)) of v; from
 * the start value 2 c, c = sqrt(2) 2^(k-1) (c = 4 for k <= 2), one Newton
 * step v / (4 c) + c comes within 6.1 % of sqrt(v) (k >= 3); two more
 * Newton steps r = (r + v / r) / 2 (unsigned divisions) leave r at
 * floor(sqrt(v)) or one above it (the last step, a mean of r and v / r, is
 * never below the floor); a correction loop decrements r while r^2 > v.
 * Over all 2^32 values of v it runs at most once (checked on every v by
 * tools/bench/isqrt_steps.sh, part of `make bench`; by CBMC for v < 2^16
 * and v >= 2^32 - 2^24), so the execution time is bounded; its invariant
 * v < (r + 1)^2 and exit r^2 <= v are the result's definition.
 *
 * Bad input: none possible.
 *
 * Scaling and overflow: plain unsigned integers; the first divisors are
 * >= 4 and >= 2, so the middle step's halves r / 2 + (v / r) / 2 and the last
 * step's sum r + v / r (two terms below 2^31) stay below 2^32; the
 * correction forms r^2 in 64 bits (r is bounded by 2^31 there only).
 *
 * Requirements: REQ-VEC-001.
 */
/*@
  assigns \nothing;
  ensures range: 0 <= \result <= 65535;
  ensures floor_sqrt: QfocIsSqrt(\result, v);
*/
uint32_t qfoc_isqrt32(uint32_t v);

/**
 * @brief Magnitude of the vector (x, y): floor(sqrt(x^2 + y^2)), saturated.
 *
 * @param[in] x first component, any int16_t (-32768 included)
 * @param[in] y second component, any int16_t (-32768 included)
 * @return floor(sqrt(x^2 + y^2)) when that is below 32767, else 32767.
 *         Rounded DOWN (never above the true magnitude), error < 1 LSB.
 *
 * Bad input: none; a vector longer than 32767 (up to 32768 * sqrt(2) = 46341)
 * saturates to 32767.
 *
 * Scaling and overflow: 1.15 x 1.15 = 2.30 per square, formed in int32
 * (<= 2^30) and converted to uint32; the sum <= 2^31 fits uint32 exactly; a
 * sum of at least 32767^2 saturates without a square root, below it the
 * square root of the 2.30 sum is a 1.15 value <= 32766.
 *
 * Requirements: REQ-VEC-002.
 */
/*@
  assigns \nothing;
  ensures range: 0 <= \result <= 32767;
  behavior exact:
    assumes x * x + y * y < 32767 * 32767;
    ensures floor_sqrt: QfocIsSqrt(\result, x * x + y * y);
  behavior saturated:
    assumes x * x + y * y >= 32767 * 32767;
    ensures \result == 32767;
  complete behaviors;
  disjoint behaviors;
*/
qfoc_q15_t qfoc_vec_mag(qfoc_q15_t x, qfoc_q15_t y);

/**
 * @brief Circle limitation of a (d, q) voltage (or current) vector with
 *        d-axis priority.
 *
 * @param[in]  in   requested vector (d, q), any int16_t components
 * @param[in]  vmax radius of the limiting circle; clamped to [0, 32767]
 *                  (a negative vmax acts as 0: the output is (0, 0))
 * @param[out] out  limited vector:
 *                  d' = clamp(d, -vmax, vmax),
 *                  q' = clamp(q, -qlim, qlim), qlim = floor(sqrt(vmax^2 - d'^2))
 * @return true when the input lay outside the circle (some component was
 *         limited), false when out == in.
 *
 * The output always lies inside or on the circle: d'^2 + q'^2 <= vmax^2
 * (qlim is rounded down).  An input inside or on the circle is passed through
 * unchanged.  The d component keeps priority (field weakening / MTPA current
 * is served first), q takes what is left; both keep their sign.
 *
 * Aliasing: in and out MAY point to the same object (in-place limiting); the
 * input is read completely before out is written.
 *
 * Bad input: in and out must be valid pointers (precondition, not checked).
 *
 * Scaling and overflow: whether the input lies inside the circle is decided
 * exactly on the squares, d^2 + q^2 <= vmax^2 in uint32 (<= 2^31); outside it,
 * vmax^2 - d'^2 is formed as the 2.30 product
 * (vmax - |d'|) (vmax + |d'|) of two factors in [0, 65534] (|d'| <= vmax),
 * a 16 x 16 bit product in uint32 (<= 32767^2 < 2^30); its integer square
 * root is a 1.15 value <= vmax <= 32767, so the final qfoc_q15_sat never
 * acts (proved) and every result fits qfoc_q15_t.
 *
 * Requirements: REQ-VEC-003, REQ-VEC-004.
 */
/*@
  requires valid_in: \valid_read(in);
  requires valid_out: \valid(out);
  assigns out->d, out->q;
  ensures in_circle:
    out->d * out->d + out->q * out->q <= QfocVmaxClamp(vmax) * QfocVmaxClamp(vmax);
  ensures d_priority:
    out->d == QfocClamp(\old(in->d), -QfocVmaxClamp(vmax), QfocVmaxClamp(vmax));
  ensures q_shrinks:
    (\old(in->q) >= 0 ==> 0 <= out->q <= \old(in->q)) &&
    (\old(in->q) < 0 ==> \old(in->q) <= out->q <= 0);
  behavior inside:
    assumes QfocInCircle(in->d, in->q, vmax);
    ensures unchanged: out->d == \old(in->d) && out->q == \old(in->q);
    ensures not_limited: \result == 0;
  behavior limited:
    assumes !QfocInCircle(in->d, in->q, vmax);
    ensures was_limited: \result == 1;
  complete behaviors;
  disjoint behaviors;
*/
bool qfoc_circle_limit(const qfoc_dq_t *in, qfoc_q15_t vmax, qfoc_dq_t *out);

#ifdef __cplusplus
}
#endif

#endif /* QFOC_VECTOR_H */
