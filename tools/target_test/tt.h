/**
 * @file tt.h
 * @brief Golden-vector equivalence tests: the library on the Cortex-M4F against the host.
 *
 * The host generator (tt_gen.c) produces the input vectors of every public function
 * group and of a whole closed-loop drive run, and the host's outputs, and writes them
 * as C arrays (build/target_test/vectors.c).  The runner (tt_runner.c) replays every
 * group with the library compiled for the target and compares each output with the
 * host's.  Both sides run the same replay code (tt_groups.c): the only difference is
 * the compiler, the instruction set and the library build.
 *
 * Vectors.  A group holds n vectors of `width` 16-bit input words each (width 0: the
 * input is the vector's index, e.g. every angle of qfoc_sincos) and one 32-bit
 * expected digest per vector.  A digest is the output of one call (and, for a
 * stateful block, the block's state after it) serialised field by field, each integer
 * little-endian in its own width: when the serialisation has at most 4 bytes the digest
 * IS those bytes (the exact output, readable in a mismatch report), otherwise it is
 * the 32-bit FNV-1a hash of them.  A mismatch therefore names the group (the
 * function), the vector index and its inputs.
 *
 * Stateful blocks are replayed as operation streams: word 0 of every vector is the
 * operation (TT_OP_*), the following words its arguments; the block's state carries
 * from one vector to the next, so a group is a sequence of init / reset / step calls.
 *
 * Requirements (specs/requirements/target.md): REQ-TGT-001 golden vectors of every public
 * function group and of the whole drive, REQ-TGT-002 bit-identical outputs on the
 * Cortex-M4F, REQ-TGT-003 the replayed drive reproduces the closed loop, REQ-TGT-004 a
 * difference is reported and fails the test, REQ-TGT-005 a self-contained target image.
 */
#ifndef QFOC_TT_H
#define QFOC_TT_H

#include <stdint.h>
#include <stdbool.h>

#include "qfoc/drive.h"
#include "qfoc/drive_shunt.h"

/** Operation codes of the stateful groups (word 0 of a vector). */
#define TT_OP_INIT  ((uint16_t)0u)  /**< init from the parameters in the vector */
#define TT_OP_RESET ((uint16_t)1u)  /**< reset (with the values in the vector) */
#define TT_OP_STEP  ((uint16_t)2u)  /**< one step */
#define TT_OP_AUX   ((uint16_t)3u)  /**< a read-only query (lead, lag, output, ...) */
#define TT_OP_AUX2  ((uint16_t)4u)  /**< a second query or step variant */

/** No corruption requested (tt_ctx_t). */
#define TT_NONE ((uint32_t)0xFFFFFFFFu)

/** One group of golden vectors, as written by the generator. */
typedef struct {
    const char *name;      /**< group name (the function or block) */
    uint32_t n;            /**< number of vectors */
    uint16_t width;        /**< input words per vector; 0: the input is the index */
    const uint16_t *in;    /**< n x width input words (NULL when width is 0) */
    const uint32_t *exp;   /**< n expected digests, computed on the host */
} tt_data_t;

/** Digest accumulator of one output. */
typedef struct {
    uint32_t fnv;    /**< FNV-1a state */
    uint32_t raw;    /**< the first 4 bytes, little-endian */
    uint32_t count;  /**< bytes added */
} tt_digest_t;

/** Replay context of one group. */
typedef struct {
    const tt_data_t *data;  /**< the group's vectors */
    uint32_t k;             /**< digests emitted so far */
    uint32_t n_bad;         /**< vectors whose digest differs */
    uint32_t first_bad;     /**< index of the first of them (TT_NONE: none) */
    uint32_t got_first;     /**< its digest here */
    uint32_t exp_first;     /**< its expected digest */
    uint32_t *record;       /**< generator only: store the digests here, compare nothing */
    uint32_t corrupt_exp;   /**< self-test: this vector's expected digest XOR 1 (TT_NONE) */
    uint32_t corrupt_in;    /**< self-test: bit 0 of this vector's first input word flipped */
} tt_ctx_t;

/** Replay of a suite: ctx points at one context per group of the suite. */
typedef void (*tt_replay_fn_t)(tt_ctx_t *ctx);

/** A suite: one replay function covering one group, or two (the drive's two entry points). */
typedef struct {
    const char *name[2];  /**< group names (the second is NULL for one group) */
    uint8_t groups;       /**< 1 or 2 */
    tt_replay_fn_t fn;    /**< replay */
} tt_suite_t;

/** Number of suites (tt_groups.c). */
#define TT_N_SUITES (49u)
/** Every suite, in the order of the groups in vectors.c (tt_groups.c). */
extern const tt_suite_t tt_suites[TT_N_SUITES];

/* ------------------------------------------------------------------ digests */
void tt_d_init(tt_digest_t *d);
void tt_d_u8(tt_digest_t *d, uint8_t v);
void tt_d_bool(tt_digest_t *d, bool v);
void tt_d_u16(tt_digest_t *d, uint16_t v);
void tt_d_i16(tt_digest_t *d, int16_t v);
void tt_d_u32(tt_digest_t *d, uint32_t v);
void tt_d_i32(tt_digest_t *d, int32_t v);
/** The digest: the bytes themselves (at most 4), else their FNV-1a hash. */
uint32_t tt_d_final(const tt_digest_t *d);

/* ------------------------------------------------------------------ replay helpers */
/** Word j of vector k (with the self-test corruption applied). */
uint16_t tt_in(const tt_ctx_t *c, uint32_t k, uint16_t j);
/** The same word read as a signed 16-bit value. */
int16_t tt_in_i16(const tt_ctx_t *c, uint32_t k, uint16_t j);
/** Words j (low half) and j + 1 (high half) of vector k as a 32-bit value. */
uint32_t tt_in_u32(const tt_ctx_t *c, uint32_t k, uint16_t j);
/** The input of a width-0 vector: its index (with the self-test corruption applied). */
uint32_t tt_in_index(const tt_ctx_t *c, uint32_t k);
/** Bytes packed two per word (low byte first) from word j on; n <= 2 x (width - j). */
void tt_in_bytes(const tt_ctx_t *c, uint32_t k, uint16_t j, uint8_t *buf, uint16_t n);
/** Compare (or record) the digest of the next vector. */
void tt_emit(tt_ctx_t *c, const tt_digest_t *d);

/* ------------------------------------------------------------------ the drive */
/* Shared by the replay and by the generator's recording of the closed-loop run. */

/** Words of a drive_tick vector: t_ipm, t_pcb, rx_len, 6 words of frame bytes. */
#define TT_TICK_WIDTH ((uint16_t)9u)
/** Longest received frame a drive_tick vector holds: 2 bytes in each of its last 6 words. */
#define TT_TICK_RX_MAX ((uint8_t)(2u * (TT_TICK_WIDTH - 3u)))

/** Digest of one fast step: its output and the fast half's main observables. */
uint32_t tt_drive_fast_digest(const qfoc_drive_t *d, const qfoc_pwm_t *out);
/** Digest of one tick: its output and the tick half's main observables. */
uint32_t tt_drive_tick_digest(const qfoc_drive_t *d, const qfoc_tick_out_t *out);
/** Digest of one single-shunt period: the fast step's digest, the codes handed to it, the
    next plan and the front end's state. */
uint32_t tt_drive_shunt_digest(const qfoc_drive_t *d, const qfoc_drive_shunt_t *sd,
                               const qfoc_adc_t *codes, const qfoc_pwm_t *out,
                               const qfoc_shunt_plan_t *plan);

#endif /* QFOC_TT_H */
