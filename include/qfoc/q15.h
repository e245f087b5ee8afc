/**
 * @file q15.h
 * @brief Saturating Q15 / Q31 arithmetic: the primitives every qfoc block uses.
 *
 * All functions are total: every value of every input type gives a defined result.
 * Saturation is the default and returns into the symmetric ranges
 * [-32767, 32767] (Q15) and [-(2^31 - 1), 2^31 - 1] (Q31), so that negating or
 * taking the absolute value of a result is always exact.
 *
 * Rounding: wherever a result loses fraction bits it is rounded to the nearest
 * representable value, ties away from zero (symmetric, no DC bias between positive
 * and negative signals).  Rounding is written with divisions by powers of two, never
 * with right shifts of negative values (implementation-defined in C99 6.5.7,
 * MISRA C:2012 Rule 10.1 / Dir 1.1).  The compiler turns the divisions into shifts
 * with a sign fix-up.
 *
 * The functions are static inline so that each transform compiles to straight-line
 * code on the Cortex-M4 (MISRA C:2012 Rule 8.10: inline functions have internal
 * linkage).
 *
 * Requirements: REQ-Q15-001 .. REQ-Q15-008 (specs/requirements/q15.md); each
 * function below names the ones it meets.
 */
#ifndef QFOC_Q15_H
#define QFOC_Q15_H

#include "qfoc/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Q30 magnitude from which a Q30 -> Q15 conversion saturates: 32767.5 * 32768. */
#define QFOC_Q30_SAT_LIMIT (1073725440L)
/** Largest Q31 magnitude that rounds (x / 65536) into the Q15 range: 32767.5 x 65536 - 1. */
#define QFOC_Q31_ROUND_MAX ((int32_t)2147450879)

/**
 * @brief Saturate a 32-bit integer to the symmetric Q15 range.
 * Requirement: REQ-Q15-001.
 * @param[in] x any int32_t value
 * @return x clamped to [-32767, 32767]
 *
 * Scaling and overflow: no scaling; compares only.
 */
/*@
  assigns \nothing;
  ensures range: QfocQ15Sym(\result);
  behavior upper:
    assumes x > 32767;
    ensures \result == 32767;
  behavior between:
    assumes -32767 <= x <= 32767;
    ensures \result == x;
  behavior lower:
    assumes x < -32767;
    ensures \result == -32767;
  complete behaviors;
  disjoint behaviors;
*/
static inline qfoc_q15_t qfoc_q15_sat(int32_t x)
{
    int32_t r = x;
    if (x > (int32_t)QFOC_Q15_MAX) {
        r = (int32_t)QFOC_Q15_MAX;
    } else if (x < (int32_t)QFOC_Q15_MIN) {
        r = (int32_t)QFOC_Q15_MIN;
    } else {
        /* already in range */
    }
    return (qfoc_q15_t)r;
}

/**
 * @brief Saturate a 64-bit integer to the symmetric Q31 range.
 * Requirement: REQ-Q15-006.
 * @param[in] x any int64_t value
 * @return x clamped to [-(2^31 - 1), 2^31 - 1]
 */
/*@
  assigns \nothing;
  ensures range: QfocQ31Sym(\result);
  ensures value: \result == QfocSat31(x);
*/
static inline qfoc_q31_t qfoc_q31_sat(int64_t x)
{
    int64_t r = x;
    if (x > (int64_t)QFOC_Q31_MAX) {
        r = (int64_t)QFOC_Q31_MAX;
    } else if (x < (int64_t)QFOC_Q31_MIN) {
        r = (int64_t)QFOC_Q31_MIN;
    } else {
        /* already in range */
    }
    return (qfoc_q31_t)r;
}

/**
 * @brief Saturating addition a + b.
 * Requirement: REQ-Q15-002.
 * @param[in] a, b addends, Q1.15 (any int16_t)
 * @return a + b saturated to [-32767, 32767]
 *
 * Scaling and overflow: 1.15 + 1.15 summed exactly in 32 bits (|sum| <= 65536),
 * then saturated to [-32767, 32767].
 */
/*@
  assigns \nothing;
  ensures range: QfocQ15Sym(\result);
  ensures value: \result == QfocSat15(a + b);
  behavior exact:
    assumes QfocQ15Sym(a + b);
    ensures \result == a + b;
  behavior saturated:
    assumes !QfocQ15Sym(a + b);
    ensures \result == 32767 || \result == -32767;
  complete behaviors;
  disjoint behaviors;
*/
static inline qfoc_q15_t qfoc_q15_add(qfoc_q15_t a, qfoc_q15_t b)
{
    return qfoc_q15_sat((int32_t)a + (int32_t)b);
}

/**
 * @brief Saturating subtraction a - b.
 * Requirement: REQ-Q15-002.
 * @param[in] a minuend, Q1.15 (any int16_t)
 * @param[in] b subtrahend, Q1.15 (any int16_t)
 * @return a - b saturated to [-32767, 32767]
 *
 * Scaling and overflow: as qfoc_q15_add; |a - b| <= 65535 in 32 bits.
 */
/*@
  assigns \nothing;
  ensures range: QfocQ15Sym(\result);
  ensures value: \result == QfocSat15(a - b);
  behavior exact:
    assumes QfocQ15Sym(a - b);
    ensures \result == a - b;
  behavior saturated:
    assumes !QfocQ15Sym(a - b);
    ensures \result == 32767 || \result == -32767;
  complete behaviors;
  disjoint behaviors;
*/
static inline qfoc_q15_t qfoc_q15_sub(qfoc_q15_t a, qfoc_q15_t b)
{
    return qfoc_q15_sat((int32_t)a - (int32_t)b);
}

/**
 * @brief Saturating negation -a (-(-32768) gives 32767).
 * Requirement: REQ-Q15-003.
 * @param[in] a Q1.15 (any int16_t)
 * @return -a, in [-32767, 32767]
 */
/*@
  assigns \nothing;
  ensures range: QfocQ15Sym(\result);
  ensures value: \result == QfocSat15(-a);
  behavior exact:
    assumes a != -32768;
    ensures \result == -a;
  behavior saturated:
    assumes a == -32768;
    ensures \result == 32767;
  complete behaviors;
  disjoint behaviors;
*/
static inline qfoc_q15_t qfoc_q15_neg(qfoc_q15_t a)
{
    return qfoc_q15_sat(-(int32_t)a);
}

/**
 * @brief Saturating absolute value |a| (|-32768| gives 32767).
 * Requirement: REQ-Q15-003.
 * @param[in] a Q1.15 (any int16_t)
 * @return |a|, in [0, 32767]
 */
/*@
  assigns \nothing;
  ensures range: 0 <= \result <= 32767;
  behavior exact:
    assumes a != -32768;
    ensures \result == \abs(a);
  behavior saturated:
    assumes a == -32768;
    ensures \result == 32767;
  complete behaviors;
  disjoint behaviors;
*/
static inline qfoc_q15_t qfoc_q15_abs(qfoc_q15_t a)
{
    int32_t r = (int32_t)a;
    if (r < 0) {
        r = -r;
    }
    return qfoc_q15_sat(r);
}

/**
 * @brief Convert a Q30 value (the product of two Q15 values) to Q15.
 * Requirement: REQ-Q15-004.
 * @param[in] x any int32_t, read as Q2.30
 * @return x / 32768 rounded to nearest (ties away from zero), saturated.
 *
 * Scaling and overflow: the rounding offset is added on the side of zero that
 * cannot overflow (|x| < QFOC_Q30_SAT_LIMIT there), so the 32-bit arithmetic is
 * exact; at and beyond +-QFOC_Q30_SAT_LIMIT the result is +-32767.
 */
/*@
  assigns \nothing;
  ensures range: QfocQ15Sym(\result);
  behavior exact:
    assumes QfocQ30Fits(x);
    ensures \result == QfocRoundDiv(x, 32768);
  behavior upper:
    assumes x >= 1073725440;
    ensures \result == 32767;
  behavior lower:
    assumes x <= -1073725440;
    ensures \result == -32767;
  complete behaviors;
  disjoint behaviors;
*/
static inline qfoc_q15_t qfoc_q15_from_q30(int32_t x)
{
    int32_t c = x;
    int32_t tie;
    int32_t biased;
    uint32_t u;
    /* clamp to the last values that round into [-32767, 32767] */
    if (c > (QFOC_Q30_SAT_LIMIT - 1)) {
        c = QFOC_Q30_SAT_LIMIT - 1;
    } else if (c < (1 - QFOC_Q30_SAT_LIMIT)) {
        c = 1 - QFOC_Q30_SAT_LIMIT;
    } else {
        /* rounds into range */
    }
    /* ties away from zero: a negative value rounds as c - 1 would round up */
    tie = (c < 0) ? (int32_t)1 : (int32_t)0;
    /* |c| < 2^30: c + 2^30 + 2^14 - tie lies in [32768, 2^31 - 1] */
    biased = (c + 1073758208) - tie;
    u = (uint32_t)biased / 32768u;
    return (qfoc_q15_t)((int32_t)u - 32768);
}

/**
 * @brief Q15 x Q15 -> Q15 multiplication, rounded and saturated.
 * Requirement: REQ-Q15-005.
 * @param[in] a, b factors, Q1.15 (any int16_t)
 * @return a b / 32768 rounded to nearest (ties away from zero), in [-32767, 32767]
 *
 * Scaling and overflow: 1.15 x 1.15 = 2.30 exact in 32 bits (|a b| <= 2^30),
 * rounded to nearest (ties away from zero) to 1.15 by qfoc_q15_from_q30; only
 * (-32768) x (-32768) = 1.0 saturates, to 32767.  Error <= 0.5 LSB otherwise.
 */
/*@
  assigns \nothing;
  ensures range: QfocQ15Sym(\result);
  behavior exact:
    assumes QfocQ30Fits(a * b);
    ensures \result == QfocRoundDiv(a * b, 32768);
  behavior saturated:
    assumes !QfocQ30Fits(a * b);
    ensures \result == 32767;
  complete behaviors;
  disjoint behaviors;
*/
static inline qfoc_q15_t qfoc_q15_mul(qfoc_q15_t a, qfoc_q15_t b)
{
    return qfoc_q15_from_q30((int32_t)a * (int32_t)b);
}

/**
 * @brief Saturating Q31 addition.
 * Requirement: REQ-Q15-006.
 * @param[in] a, b addends, Q1.31 (any int32_t)
 * @return a + b, formed in 64 bits, saturated to [-(2^31 - 1), 2^31 - 1]
 */
/*@
  assigns \nothing;
  ensures range: QfocQ31Sym(\result);
  ensures value: \result == QfocSat31(a + b);
*/
static inline qfoc_q31_t qfoc_q31_add(qfoc_q31_t a, qfoc_q31_t b)
{
    return qfoc_q31_sat((int64_t)a + (int64_t)b);
}

/**
 * @brief Multiply-accumulate in Q31: acc + a x b.
 * Requirement: REQ-Q15-007.
 * @param[in] acc accumulator, Q1.31 (any int32_t)
 * @param[in] a, b factors, Q1.15 (any int16_t)
 * @return acc + a b as Q31 (the Q30 product scaled by 2, exact), saturated.
 *
 * Scaling and overflow: 1.15 x 1.15 = 2.30; x 2 gives 1.31 (|2ab| <= 2^31);
 * the sum is formed exactly in 64 bits and saturated to the symmetric Q31 range.
 */
/*@
  assigns \nothing;
  ensures range: QfocQ31Sym(\result);
  ensures value: \result == QfocSat31(acc + 2 * a * b);
*/
static inline qfoc_q31_t qfoc_q31_mac(qfoc_q31_t acc, qfoc_q15_t a, qfoc_q15_t b)
{
    int32_t p = (int32_t)a * (int32_t)b;   /* 2.30, |p| <= 2^30 */
    int64_t p31 = (int64_t)p * 2;         /* 1.31, |p31| <= 2^31 */
    return qfoc_q31_sat((int64_t)acc + p31);
}

/**
 * @brief Q31 to Q15 without saturation, for a value already known to round into
 *        [-32767, 32767]: x / 65536 rounded to nearest (ties away from zero).
 * Requirement: REQ-Q15-008.
 * @param[in] x Q1.31, |x| <= QFOC_Q31_ROUND_MAX (required: the caller proves it)
 * @return x / 65536 rounded to nearest (ties away from zero), in [-32767, 32767]
 *
 * Scaling and overflow: x + 2^31 + 2^15 (less 1 for a negative x, which turns the
 * round-half-up of the unsigned quotient into ties away from zero) lies in
 * [65536, 2^32 - 1]: formed in 64 bits, divided as an unsigned 32-bit value (no
 * right shift of a negative value), the bias 2^15 removed from the quotient.
 */
/*@
  requires range: -2147450879 <= x <= 2147450879;
  assigns \nothing;
  ensures range: QfocQ15Sym(\result);
  ensures value: \result == QfocRoundDiv(x, 65536);
*/
static inline qfoc_q15_t qfoc_q15_round_q31(int32_t x)
{
    /* ties away from zero: a negative value rounds as x - 1 would round up */
    const int64_t tie = (x < 0) ? (int64_t)1 : (int64_t)0;
    const int64_t biased = (((int64_t)x + 2147483648LL) + 32768LL) - tie;
    const uint32_t u = (uint32_t)biased / 65536u;
    return (qfoc_q15_t)((int32_t)u - 32768);
}

/**
 * @brief Convert Q31 to Q15: x / 65536 rounded to nearest (ties away from zero),
 *        saturated to [-32767, 32767].
 * Requirement: REQ-Q15-008.
 * @param[in] x Q1.31 (any int32_t)
 * @return x / 65536 rounded to nearest (ties away from zero), in [-32767, 32767]
 *
 * Scaling and overflow: 1.31 -> 1.15 drops 16 fraction bits; x is first clamped to
 * the last values that round into [-32767, 32767], then rounded by
 * qfoc_q15_round_q31.
 */
/*@
  assigns \nothing;
  ensures range: QfocQ15Sym(\result);
  ensures value: \result == QfocSat15(QfocRoundDiv(x, 65536));
*/
static inline qfoc_q15_t qfoc_q15_from_q31(qfoc_q31_t x)
{
    int32_t c = x;
    /* clamp to the last values that round into [-32767, 32767] */
    if (c > QFOC_Q31_ROUND_MAX) {
        c = QFOC_Q31_ROUND_MAX;
    } else if (c < -QFOC_Q31_ROUND_MAX) {
        c = -QFOC_Q31_ROUND_MAX;
    } else {
        /* rounds into range */
    }
    return qfoc_q15_round_q31(c);
}

/**
 * @brief Convert Q15 to Q31 (exact: x * 65536).
 * Requirement: REQ-Q15-008.
 * @param[in] x Q1.15 (any int16_t)
 * @return x * 65536, Q1.31 (exact, no saturation needed)
 */
/*@
  assigns \nothing;
  ensures value: \result == x * 65536;
*/
static inline qfoc_q31_t qfoc_q31_from_q15(qfoc_q15_t x)
{
    return (qfoc_q31_t)x * 65536;
}

#ifdef __cplusplus
}
#endif

#endif /* QFOC_Q15_H */
