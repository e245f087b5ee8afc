/**
 * @file tt_core.c
 * @brief Digests, input access and comparison of the golden-vector replay (tt.h).
 *
 * Runs on the target (the runner) and on the host (the generator and the host build of
 * the runner).  Requirements: REQ-TGT-002, REQ-TGT-004.
 */
#include "tt.h"

#include <stddef.h>

/* FNV-1a, 32 bits: offset basis 2166136261, prime 16777619 (Fowler, Noll, Vo;
   IETF draft-eastlake-fnv). */
#define TT_FNV_BASIS ((uint32_t)2166136261u)
#define TT_FNV_PRIME ((uint32_t)16777619u)

void tt_d_init(tt_digest_t *d)
{
    d->fnv = TT_FNV_BASIS;
    d->raw = 0u;
    d->count = 0u;
}

void tt_d_u8(tt_digest_t *d, uint8_t v)
{
    if (d->count < 4u) {
        d->raw |= (uint32_t)v << (8u * d->count);
    }
    d->fnv = (d->fnv ^ (uint32_t)v) * TT_FNV_PRIME;
    d->count++;
}

void tt_d_bool(tt_digest_t *d, bool v)
{
    tt_d_u8(d, v ? (uint8_t)1u : (uint8_t)0u);
}

void tt_d_u16(tt_digest_t *d, uint16_t v)
{
    tt_d_u8(d, (uint8_t)(v & 0xFFu));
    tt_d_u8(d, (uint8_t)(v >> 8u));
}

void tt_d_i16(tt_digest_t *d, int16_t v)
{
    tt_d_u16(d, (uint16_t)v);
}

void tt_d_u32(tt_digest_t *d, uint32_t v)
{
    tt_d_u16(d, (uint16_t)(v & 0xFFFFu));
    tt_d_u16(d, (uint16_t)(v >> 16u));
}

void tt_d_i32(tt_digest_t *d, int32_t v)
{
    tt_d_u32(d, (uint32_t)v);
}

uint32_t tt_d_final(const tt_digest_t *d)
{
    uint32_t r = d->fnv;
    if (d->count <= 4u) {
        r = d->raw;
    }
    return r;
}

uint16_t tt_in(const tt_ctx_t *c, uint32_t k, uint16_t j)
{
    uint16_t w = 0u;
    const uint16_t width = c->data->width;
    if ((k < c->data->n) && (j < width)) {
        w = c->data->in[(k * (uint32_t)width) + (uint32_t)j];
        if ((k == c->corrupt_in) && (j == 0u)) {
            w ^= 1u;
        }
    }
    return w;
}

int16_t tt_in_i16(const tt_ctx_t *c, uint32_t k, uint16_t j)
{
    return (int16_t)tt_in(c, k, j);
}

uint32_t tt_in_u32(const tt_ctx_t *c, uint32_t k, uint16_t j)
{
    return (uint32_t)tt_in(c, k, j) | ((uint32_t)tt_in(c, k, (uint16_t)(j + 1u)) << 16u);
}

uint32_t tt_in_index(const tt_ctx_t *c, uint32_t k)
{
    uint32_t v = k;
    if (k == c->corrupt_in) {
        v ^= 1u;
    }
    return v;
}

void tt_in_bytes(const tt_ctx_t *c, uint32_t k, uint16_t j, uint8_t *buf, uint16_t n)
{
    uint16_t b;
    for (b = 0u; b < n; b++) {
        const uint16_t w = tt_in(c, k, (uint16_t)(j + (b / 2u)));
        if ((b % 2u) == 0u) {
            buf[b] = (uint8_t)(w & 0xFFu);
        } else {
            buf[b] = (uint8_t)(w >> 8u);
        }
    }
}

void tt_emit(tt_ctx_t *c, const tt_digest_t *d)
{
    const uint32_t got = tt_d_final(d);
    if (c->record != NULL) {
        c->record[c->k] = got;
    } else if (c->k < c->data->n) {
        uint32_t exp = c->data->exp[c->k];
        if (c->k == c->corrupt_exp) {
            exp ^= 1u;
        }
        if (got != exp) {
            if (c->n_bad == 0u) {
                c->first_bad = c->k;
                c->got_first = got;
                c->exp_first = exp;
            }
            c->n_bad++;
        }
    } else {
        /* more digests than vectors: counted as a difference */
        if (c->n_bad == 0u) {
            c->first_bad = c->k;
            c->got_first = got;
            c->exp_first = 0u;
        }
        c->n_bad++;
    }
    c->k++;
}
