/**
 * @file types.h
 * @brief qfoc fixed-point types and reference-frame structs.
 *
 * Number formats (see specs/scaling.md):
 *  - qfoc_q15_t: signed 1.15, real value = raw / 32768, per unit of a named base
 *    (current, voltage, speed).  Every saturating qfoc operation returns a value in
 *    the symmetric range [-32767, 32767] (QFOC_Q15_MIN .. QFOC_Q15_MAX), so negation
 *    and absolute value of a qfoc result never overflow.  Inputs may be any int16_t,
 *    -32768 included.
 *  - qfoc_q31_t: signed 1.31, real value = raw / 2^31, used for accumulators.
 *  - qfoc_angle_t: electrical angle, 65536 counts per electrical turn
 *    (0x4000 = 90 degrees); arithmetic on angles is modulo 2^16 by design.
 */
#ifndef QFOC_TYPES_H
#define QFOC_TYPES_H

#include <stdint.h>
#include <stdbool.h>

#ifdef __cplusplus
extern "C" {
#endif

#ifdef __FRAMAC__
/* Shared ACSL logic; seen only by Frama-C (the file holds comments only). */
#include "qfoc.acsl"
#endif

typedef int16_t qfoc_q15_t;    /**< 1.15 fixed point, real = raw / 32768 */
typedef int32_t qfoc_q31_t;    /**< 1.31 fixed point, real = raw / 2^31 */
typedef uint16_t qfoc_angle_t; /**< electrical angle, 65536 counts per turn */

#define QFOC_Q15_MAX ((qfoc_q15_t)32767)   /**< +0.999969 */
#define QFOC_Q15_MIN ((qfoc_q15_t)-32767)  /**< -0.999969, symmetric range */
#define QFOC_Q31_MAX ((qfoc_q31_t)2147483647)   /**< +0.9999999995 */
#define QFOC_Q31_MIN ((qfoc_q31_t)-2147483647)  /**< symmetric range */

/** Three phase quantities u, v, w (specs/equations.md section 1). */
typedef struct {
    qfoc_q15_t u;  /**< phase u */
    qfoc_q15_t v;  /**< phase v */
    qfoc_q15_t w;  /**< phase w */
} qfoc_abc_t;

/** Stationary two-axis frame (alpha along phase u). */
typedef struct {
    qfoc_q15_t alpha;  /**< alpha axis, along phase u */
    qfoc_q15_t beta;   /**< beta axis, 90 degrees ahead of alpha */
} qfoc_ab_t;

/** Rotating frame aligned with the rotor flux (d) and 90 degrees ahead (q). */
typedef struct {
    qfoc_q15_t d;  /**< direct axis, along the rotor flux */
    qfoc_q15_t q;  /**< quadrature axis, 90 degrees ahead of d */
} qfoc_dq_t;

/** Sine and cosine of an angle, Q15, each in [-32767, 32767]. */
typedef struct {
    qfoc_q15_t sine;    /**< sin(theta) */
    qfoc_q15_t cosine;  /**< cos(theta) */
} qfoc_sincos_t;

/** Output of one PWM period (the drive's and the identification's fast step). */
typedef struct {
    uint16_t cmp[3];  /**< compare values u, v, w, 0..period */
    bool enable;      /**< true: outputs switching; false: all switches off */
} qfoc_pwm_t;

#ifdef __cplusplus
}
#endif

#endif /* QFOC_TYPES_H */
