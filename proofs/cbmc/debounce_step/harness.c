/*
 * CBMC harness: qfoc_debounce_step(), one step from any state and a sequence of
 * steps from reset (REQ-FAULT-002), and the threshold compares (REQ-FAULT-006).
 *
 * Properties checked:
 *  - no undefined behaviour (overflow, conversion, bounds, pointer checks of the
 *    command line) for every count, condition and length n;
 *  - one step from any count: cond false gives count 0 and false; cond true gives
 *    count = min(count + 1, n) and the result count >= n;
 *  - twelve steps from qfoc_debounce_reset() with an arbitrary condition sequence
 *    and any n: after each step the count equals min(k, n), where k is the number
 *    of consecutive trues ending at this step (counted here independently), and
 *    the result is true exactly when k >= max(n, 1): the condition has held for
 *    the last max(n, 1) calls;
 *  - qfoc_fault_over / _under / _abs_over agree with x > limit, x < limit and
 *    |x| > limit computed in 32 bits, for every x and limit (-32768 included).
 *
 * Methods: 1b every count, condition and length n of one step, and every sequence of
 * twelve conditions from reset; 1c n = 0 (confirmed at the first true), the count at n
 * and 65535, every x and limit of the threshold compares with -32768 included; 1d a
 * count above n (an instance not initialised)
 */
#include <stdint.h>
#include <stdbool.h>
#include "qfoc/fault.h"
#include "../harness_util.h"

/* number of steps of the sequence check (the loop bound is SEQ_STEPS + 1 = UNWIND) */
#define SEQ_STEPS 12u

int main(void)
{
    qfoc_debounce_t d;
    const uint16_t n = nondet_uint16();
    const uint16_t c0 = nondet_uint16();
    const bool cond = nondet_bool();
    bool r;
    uint32_t k;
    uint32_t step;
    const int16_t x = nondet_int16();
    const int16_t lim = nondet_int16();
    const int32_t mag = (x < 0) ? -(int32_t)x : (int32_t)x;

    /* one step from any counter value */
    d.count = c0;
    r = qfoc_debounce_step(&d, cond, n);
    if (!cond) {
        __CPROVER_assert((d.count == 0u) && !r, "cond false: count 0, not confirmed");
    } else {
        const uint32_t expect = ((uint32_t)c0 < (uint32_t)n) ? ((uint32_t)c0 + 1u) : (uint32_t)n;
        __CPROVER_assert((uint32_t)d.count == expect, "cond true: count = min(count + 1, n)");
        __CPROVER_assert(r == (d.count >= n), "cond true: result is count >= n");
    }

    /* a sequence from reset: the run-length semantics */
    qfoc_debounce_reset(&d);
    __CPROVER_assert(d.count == 0u, "reset clears the count");
    k = 0u;
    for (step = 0u; step < SEQ_STEPS; step++) {
        const bool c = nondet_bool();
        const uint32_t need = (n == 0u) ? 1u : (uint32_t)n;
        k = c ? (k + 1u) : 0u;
        r = qfoc_debounce_step(&d, c, n);
        __CPROVER_assert((uint32_t)d.count == ((k < (uint32_t)n) ? k : (uint32_t)n),
                         "count = min(run length, n)");
        __CPROVER_assert(r == (k >= need), "true iff cond held for the last max(n, 1) calls");
    }

    /* threshold compares */
    __CPROVER_assert(qfoc_fault_over(x, lim) == ((int32_t)x > (int32_t)lim), "over: x > limit");
    __CPROVER_assert(qfoc_fault_under(x, lim) == ((int32_t)x < (int32_t)lim), "under: x < limit");
    __CPROVER_assert(qfoc_fault_abs_over(x, lim) == (mag > (int32_t)lim), "abs_over: |x| > limit");
    if (x == (int16_t)-32768) {
        __CPROVER_assert(qfoc_fault_abs_over(x, (int16_t)32767), "-32768 trips the full-scale limit");
    }
    return 0;
}
