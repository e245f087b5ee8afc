/**
 * @file qfoc_isqrt.c
 * @brief Integer square root of a 32-bit unsigned value.
 *
 * See include/qfoc/vector.h for the contract and the method.  A unit of its
 * own so that a bounded model check of a caller can replace it by its
 * contract (proofs/cbmc/isqrt_stub.h), the contract itself being proved here
 * for every input by Frama-C WP.
 *
 * Requirements: REQ-VEC-001 (specs/requirements/trig.md).
 */
#include "qfoc/vector.h"

/* One Newton step floor((r + v / r) / 2) for r in [2, 2^31): the sum is
 * below 2^32 (each term < 2^31), and the result is never below
 * floor(sqrt(v)): with q = floor(v / r), v < r (q + 1) <= ((r + q + 1) / 2)^2
 * <= (result + 1)^2 (the mean of r and q + 1 is at least their geometric
 * mean). */
/*@
  requires r_range: 2 <= r <= 2147483647;
  assigns \nothing;
  ensures above: v < (\result + 1) * (\result + 1);
*/
static uint32_t isqrt_newton_up(uint32_t v, uint32_t r)
{
    uint32_t q = v / r;
    uint32_t n;

    //@ assert q_bound: q <= 2147483647;
    //@ assert q_hi: v < (q + 1) * r;
    //@ assert amgm_id: QfocSq(r + (q + 1)) == (4 * (r * (q + 1))) + QfocSq(r - (q + 1));
    //@ assert amgm_sq: 0 <= QfocSq(r - (q + 1));
    //@ assert amgm: 4 * (r * (q + 1)) <= QfocSq(r + (q + 1));
    n = (r + q) / 2u;
    //@ assert twice: 0 <= r + (q + 1) <= 2 * (n + 1);
    //@ assert sq_twice: QfocSq(r + (q + 1)) <= QfocSq(2 * (n + 1));
    //@ assert sq_n: QfocSq(2 * (n + 1)) == 4 * ((n + 1) * (n + 1));
    return n;
}

uint32_t qfoc_isqrt32(uint32_t v)
{
    uint32_t c;   /* sqrt(2) 2^(k-1) for v in [4^k, 4^(k+1)), at least 4 */
    uint32_t r;

    /* The range [4^k, 4^(k+1)) of v (k = 0 takes 0 too) by at most four
     * compares (three below 4^3, where c = 4 serves k = 0 .. 2);
     * c = sqrt(2) 2^(k-1) (181 2^(k-8) for k >= 8, an 8-bit constant). */
    if (v < 65536u) {
        if (v < 256u) {
            if (v < 64u) {
                c = 4u;           /* v in [0, 4^3): k = 0 .. 2 share c = 4 */
            } else {
                c = 6u;           /* v in [4^3, 4^4) */
            }
        } else {
            if (v < 4096u) {
                if (v < 1024u) {
                    c = 11u;      /* v in [4^4, 4^5) */
                } else {
                    c = 23u;      /* v in [4^5, 4^6) */
                }
            } else {
                if (v < 16384u) {
                    c = 45u;      /* v in [4^6, 4^7) */
                } else {
                    c = 91u;      /* v in [4^7, 4^8) */
                }
            }
        }
    } else {
        if (v < 16777216u) {
            if (v < 1048576u) {
                if (v < 262144u) {
                    c = 181u;     /* v in [4^8, 4^9) */
                } else {
                    c = 362u;     /* v in [4^9, 4^10) */
                }
            } else {
                if (v < 4194304u) {
                    c = 724u;     /* v in [4^10, 4^11) */
                } else {
                    c = 1448u;    /* v in [4^11, 4^12) */
                }
            }
        } else {
            if (v < 268435456u) {
                if (v < 67108864u) {
                    c = 2896u;    /* v in [4^12, 4^13) */
                } else {
                    c = 5792u;    /* v in [4^13, 4^14) */
                }
            } else {
                if (v < 1073741824u) {
                    c = 11584u;   /* v in [4^14, 4^15) */
                } else {
                    c = 23168u;   /* v in [4^15, 4^16) */
                }
            }
        }
    }
    //@ assert c_range: 4 <= c <= 23168;

    /* One Newton step from 2 c, v / (4 c) + c: within 6.1 % above sqrt(v)
     * on the range (k >= 3). */
    r = ((v / 4u) / c) + c;
    //@ assert r1_range: 4 <= r <= 1073741823 + 23168;

    /* Newton step r = (r + v / r) / 2, each half rounded down (no sum that
     * could wrap): r >= 2 since r / 2 >= 2. */
    r = (r / 2u) + ((v / r) / 2u);
    //@ assert r2_range: 2 <= r <= 2147483647;

    r = isqrt_newton_up(v, r);

    /* Down to the floor: over all 2^32 values of v this loop runs at most
     * once (checked on every v by tools/bench/isqrt_steps.sh); the product
     * is formed in 64 bits, r being bounded here only by 2^31. */
    /*@
      loop invariant above: v < (r + 1) * (r + 1);
      loop assigns r;
      loop variant r;
    */
    while (((uint64_t)r * (uint64_t)r) > (uint64_t)v) {
        r--;
    }
    //@ assert low: r * r <= v;
    //@ assert r_max: r <= 65535;
    return r;
}
