/**
 * @file qfoc_iref.c
 * @brief Current-reference generation: MTPA, current-vector limit, derating
 *        (see include/qfoc/iref.h).
 *
 * Requirements: REQ-IREF-001 .. REQ-IREF-004 (specs/requirements/iref.md).
 */
#include "qfoc/iref.h"
#include "qfoc/vector.h"

/** Largest reluctance flux dL |i_q| taken by MTPA: 1 psi_base (32767 in Q15), in Q27. */
#define IREF_XHI_MAX ((uint32_t)134213632u)

/* A temperature as an offset from the lowest: t + 32768 in [0, 65535]. */
/*@
  assigns \nothing;
  ensures \result == t + 32768;
*/
static uint32_t iref_temp_u(int16_t t)
{
    const int32_t s = (int32_t)t + 32768;
    return (uint32_t)s;
}

/* The limit m = max(i_max, 0). */
/*@
  assigns \nothing;
  ensures \result == ((i_max > 0) ? i_max : 0);
*/
static uint32_t iref_mag(qfoc_q15_t i_max)
{
    return (i_max > 0) ? (uint32_t)i_max : 0u;
}

/* public interface, also called by qfoc_iref_step (DEV-002) */
/* cppcheck-suppress misra-c2012-8.7 ; DEV-002 */
qfoc_q15_t qfoc_iref_q_limit(qfoc_q15_t i_max, qfoc_q15_t i_d)
{
    const uint32_t m = iref_mag(i_max);
    const uint32_t ad = (i_d < 0) ? (uint32_t)(-(int32_t)i_d) : (uint32_t)i_d;
    const uint32_t a = (ad < m) ? ad : m;
    uint32_t r;
    /*@ assert sq: a * a <= m * m; */
    r = qfoc_isqrt32((m * m) - (a * a));
    /*@ assert le: r * r <= m * m; */
    /*@ assert r_le_m: r <= m; */
    return (qfoc_q15_t)r;
}

/* public interface, also called by qfoc_iref_step (DEV-002) */
/* cppcheck-suppress misra-c2012-8.7 ; DEV-002 */
qfoc_q15_t qfoc_iref_mtpa(qfoc_q15_t i_q, qfoc_q15_t psi_f, int16_t ld, int16_t lq)
{
    const int32_t dl = (int32_t)lq - (int32_t)ld;
    const uint32_t iq_abs = (i_q == (qfoc_q15_t)-32768) ? 32767u
                        : ((i_q < 0) ? (uint32_t)(-(int32_t)i_q) : (uint32_t)i_q);
    qfoc_q15_t id = 0;
    if ((dl > 0) && (iq_abs > 0u)) {
        /* x = dL |i_q|: Q12 x Q15 = Q27 (x_hi), Q15 of psi_base after / 4096; limited to
           1 psi_base */
        const uint32_t x_raw = (uint32_t)dl * iq_abs;
        const uint32_t x_hi = (x_raw < IREF_XHI_MAX) ? x_raw : IREF_XHI_MAX;
        /* 2 x, Q15 of psi_base, rounded ((x_hi + 1024) / 2048 <= 65534) */
        const uint32_t x2 = (x_hi + 1024u) / 2048u;
        const uint32_t pf = (psi_f > 0) ? (uint32_t)psi_f : 0u;
        /* sqrt(psi_f^2 + 4 x^2) rounded: r = floor(sqrt(sum / 4)); floor(sqrt(sum)) is 2 r
           or 2 r + 1 (fl); it rounds up when fl^2 + fl < sum */
        const uint64_t sum = ((uint64_t)pf * (uint64_t)pf) + ((uint64_t)x2 * (uint64_t)x2);
        const uint32_t r = qfoc_isqrt32((uint32_t)(sum / 4u));
        const uint64_t odd = (2u * (uint64_t)r) + 1u;
        const uint32_t fl = ((odd * odd) <= sum) ? ((2u * r) + 1u) : (2u * r);
        const uint64_t fl_up = ((uint64_t)fl * (uint64_t)fl) + (uint64_t)fl;
        uint32_t root = fl;
        uint32_t den;
        if (fl_up < sum) {
            root = fl + 1u;
        } else {
            /* the floor is the nearest */
        }
        den = pf + root;
        uint32_t q = 0u;
        if (den > 0u) {
            /* g = 2 x / den in Q15, from the unrounded x: 2 (x_hi / 4096) 32768 = 16 x_hi */
            const uint32_t g = (16u * x_hi) / den;
            const uint64_t p = ((uint64_t)g * (uint64_t)iq_abs) + 16384u;
            const uint64_t q64 = p / 32768u;
            /* |i_d| <= |i_q| (the formula's bound; the truncated root may pass it) */
            q = (q64 < (uint64_t)iq_abs) ? (uint32_t)q64 : iq_abs;
        } else {
            /* psi_f = 0 and x < 1: no MTPA current at this resolution */
        }
        id = (qfoc_q15_t)(-(int32_t)q);
    } else {
        /* no saliency (L_q <= L_d) or no q current: i_d = 0 */
    }
    return id;
}

uint16_t qfoc_iref_derate(uint16_t hi, uint16_t lo, int16_t t, int16_t t_start, int16_t t_end)
{
    const uint16_t low = (lo < hi) ? lo : hi;
    uint16_t r = hi;
    if (t <= t_start) {
        /* below the window: the full limit */
    } else if (t >= t_end) {
        r = low;
    } else {
        /* t_start < t < t_end: the span and the position fit 16 bits */
        const uint32_t span = iref_temp_u(t_end) - iref_temp_u(t_start);
        const uint32_t pos = iref_temp_u(t) - iref_temp_u(t_start);
        const uint32_t gap = (uint32_t)hi - (uint32_t)low;
        /*@ assert pos_lt: 1 <= pos < span <= 65535; */
        /*@ assert gap_le: gap <= 65535; */
        /* (gap pos) / span <= gap since pos < span; the minimum states it without the
           division's algebra */
        const uint32_t q = (gap * pos) / span;
        const uint32_t drop = (q < gap) ? q : gap;
        r = (uint16_t)((uint32_t)hi - drop);
    }
    return r;
}

void qfoc_iref_step(const qfoc_iref_in_t *in, qfoc_iref_out_t *out)
{
    const int32_t m = (int32_t)iref_mag(in->i_max);
    const int32_t mtpa = in->mtpa ? (int32_t)qfoc_iref_mtpa(in->iq_dem, in->psi_f, in->ld, in->lq)
                                  : 0;
    int32_t id = mtpa + (int32_t)in->id_fw;
    if (id > 0) {
        id = 0;
    } else if (id < -m) {
        id = -m;
    } else {
        /* inside [-i_max, 0] */
    }
    out->id = (qfoc_q15_t)id;
    out->iq_lim = qfoc_iref_q_limit((qfoc_q15_t)m, (qfoc_q15_t)id);
}
