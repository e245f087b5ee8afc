/*
 * tests/test_util.h -- helpers shared by the unit tests (host only, not library code).
 *
 * A 32-bit linear congruential generator (Numerical Recipes constants 1664525,
 * 1013904223), so every random test is reproducible from its seed, and the
 * double-precision saturations, wraps and conversions the references use.
 * Each test file is its own program: define TEST_SEED before including this
 * header to choose the generator's start value.
 */
#ifndef QFOC_TEST_UTIL_H
#define QFOC_TEST_UTIL_H

#include <stdint.h>
#include <math.h>

#ifndef TEST_SEED
#define TEST_SEED 12345u
#endif

static uint32_t lcg_state = TEST_SEED;

static inline uint32_t lcg_next(void)
{
    lcg_state = (lcg_state * 1664525u) + 1013904223u;
    return lcg_state;
}

/* uniform over the whole int16_t range, -32768 included */
static inline int16_t rand_i16(void)
{
    return (int16_t)((int32_t)(lcg_next() >> 16) - 32768);
}

/* uniform over [lo, hi] (any int32_t bounds, lo <= hi), from 64 random bits */
static inline int32_t rand_range(int32_t lo, int32_t hi)
{
    uint64_t span = (uint64_t)((int64_t)hi - (int64_t)lo + 1);
    uint64_t r = ((uint64_t)lcg_next() << 32) | (uint64_t)lcg_next();
    return (int32_t)((int64_t)lo + (int64_t)(r % span));
}

/* saturation to the symmetric Q15 range [-32767, 32767] */
static inline double sat15d(double x)
{
    return (x > 32767.0) ? 32767.0 : ((x < -32767.0) ? -32767.0 : x);
}

/* saturation to the symmetric Q31 range [-(2^31 - 1), 2^31 - 1] */
static inline double sat31d(double x)
{
    return (x > 2147483647.0) ? 2147483647.0 : ((x < -2147483647.0) ? -2147483647.0 : x);
}

/* an angle in radians wrapped to [-pi, pi) */
static inline double wrap_pi(double x)
{
    const double two_pi = 6.28318530717958647692;
    return x - (two_pi * floor((x + (0.5 * two_pi)) / two_pi));
}

/* a real value in per unit to Q15, rounded to nearest and saturated */
static inline int16_t q15_of(double x)
{
    return (int16_t)sat15d(round(x * 32768.0));
}

#endif /* QFOC_TEST_UTIL_H */
