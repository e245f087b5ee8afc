/*
 * tools/bench/isqrt_steps.c -- the correction steps of qfoc_isqrt32 over every
 * 32-bit input.
 *
 * Linked with a copy of src/qfoc_isqrt.c made by tools/bench/isqrt_steps.sh,
 * in which the one statement of the correction loop (r--) also increments
 * isqrt_steps; nothing else of the source changes.  For every v in
 * [first, last] it checks the result against an independent reference
 * (the floor square root in 64-bit integers) and records the largest number
 * of correction steps one call takes.  Exit 0 when every result is exact and
 * no call takes more than the stated bound (argument 3).
 */
#include <stdio.h>
#include <stdlib.h>
#include <stdint.h>
#include "qfoc/vector.h"

unsigned int isqrt_steps;

int main(int argc, char **argv)
{
    uint32_t v;
    uint32_t last;
    unsigned int bound;
    unsigned int most = 0u;
    uint64_t wrong = 0u;
    uint64_t corrected = 0u;
    uint64_t r = 0u;              /* reference root of v, non-decreasing in v */

    if (argc != 4) {
        fprintf(stderr, "usage: isqrt_steps FIRST LAST BOUND\n");
        return 2;
    }
    v = (uint32_t)strtoul(argv[1], NULL, 0);
    last = (uint32_t)strtoul(argv[2], NULL, 0);
    bound = (unsigned int)strtoul(argv[3], NULL, 0);
    while (((r + 1u) * (r + 1u)) <= (uint64_t)v) {
        r++;
    }
    for (;;) {
        uint32_t got;
        if (((r + 1u) * (r + 1u)) <= (uint64_t)v) {
            r++;
        }
        isqrt_steps = 0u;
        got = qfoc_isqrt32(v);
        if ((uint64_t)got != r) {
            if (wrong < 5u) {
                fprintf(stderr, "isqrt_steps: qfoc_isqrt32(%lu) = %lu, floor sqrt is %lu\n",
                        (unsigned long)v, (unsigned long)got, (unsigned long)r);
            }
            wrong++;
        }
        if (isqrt_steps > most) {
            most = isqrt_steps;
        }
        if (isqrt_steps > 0u) {
            corrected++;
        }
        if (v == last) {
            break;
        }
        v++;
    }
    printf("isqrt_steps: [%s, %s]: %llu wrong results, at most %u correction step(s) a call "
           "(bound %u), %llu calls corrected\n", argv[1], argv[2],
           (unsigned long long)wrong, most, bound, (unsigned long long)corrected);
    return ((wrong == 0u) && (most <= bound)) ? 0 : 1;
}
