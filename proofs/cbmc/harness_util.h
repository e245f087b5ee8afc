/*
 * proofs/cbmc/harness_util.h -- declarations and checks shared by the CBMC harnesses.
 *
 * The nondet_* functions have no body: CBMC gives each call an unconstrained value
 * of the return type.  The checks below compare a library result with its
 * specification by multiplications with constants only (no divider), which keeps
 * the SAT problems small.
 */
#ifndef QFOC_HARNESS_UTIL_H
#define QFOC_HARNESS_UTIL_H

#include <stdint.h>
#include <stdbool.h>

int8_t nondet_int8(void);
int16_t nondet_int16(void);
int32_t nondet_int32(void);
uint8_t nondet_uint8(void);
uint16_t nondet_uint16(void);
uint32_t nondet_uint32(void);
bool nondet_bool(void);

/* q is x / 65536 rounded to nearest, ties away from zero, then saturated to the
   symmetric Q15 range */
static inline bool is_rounded_sat(int64_t q, int64_t x)
{
    bool ok;
    if (x > ((32767 * 65536) + 32767)) {
        ok = (q == 32767);
    } else if (x < -((32767 * 65536) + 32767)) {
        ok = (q == -32767);
    } else if (x >= 0) {
        ok = (((q * 65536) - 32768) <= x) && (x < ((q * 65536) + 32768));
    } else {
        ok = (((q * 65536) - 32768) < x) && (x <= ((q * 65536) + 32768));
    }
    return ok;
}

/* saturation to the symmetric Q15 range [-32767, 32767] */
static inline int32_t sat15(int32_t v)
{
    return (v > 32767) ? 32767 : ((v < -32767) ? -32767 : v);
}

/* round(acc / 2^16) mod 2^16: the output angle of a 32-bit phase accumulator */
static inline uint16_t angle_of(uint32_t acc)
{
    return (uint16_t)((((uint64_t)acc + 32768u) >> 16) & 0xFFFFu);
}

#endif /* QFOC_HARNESS_UTIL_H */
