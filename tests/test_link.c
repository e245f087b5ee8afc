/*
 * test_link.c -- unit tests of the command link (include/qfoc/link.h).
 *
 * References written here independently of src/qfoc_link.c:
 *  - LIN 2.x protected identifier from parity look-up tables over bit masks
 *    (P0 = even parity of id & 0x17, P1 = odd parity of id & 0x3A) and the
 *    published values of the LIN 2.x identifier table (0x3C -> 0x3C, 0x3D -> 0x7D, ...);
 *  - LIN 2.x enhanced checksum as a one's-complement sum: all bytes summed in 32
 *    bits, the carries folded back once at the end, then inverted; and the example
 *    of the LIN 2.x specification (PID 0x4A, data 0x55 0x93 0xE5 -> 0xE6);
 *  - command frames built by a frame writer in this file; status payload from
 *    double-precision rounding (floor(x + 0.5)) and explicit saturation.
 * Errors: every comparison is exact (integer protocol), the measured maximum
 * payload rounding errors are printed.
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>
#include <math.h>
#include <string.h>
#include <stdlib.h>

#include "qfoc/link.h"

#define TEST_SEED 20240611u
#include "test_util.h"

/* ---- independent references ---------------------------------------------- */

/* uniform over 0 .. n-1 from the high bits of the generator (its low bits have
   short periods) */
static uint32_t rnd(uint32_t n)
{
    return (lcg_next() >> 8) % n;
}

/* parity (number of set bits mod 2) of a nibble */
static const uint8_t nibble_parity[16] = {0, 1, 1, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 1, 1, 0};

static uint8_t parity8(uint8_t v)
{
    return (uint8_t)(nibble_parity[v & 0x0Fu] ^ nibble_parity[v >> 4]);
}

/* LIN 2.x PID: P0 = id0^id1^id2^id4 (mask 0x17), P1 = !(id1^id3^id4^id5) (mask 0x3A) */
static uint8_t ref_pid(uint8_t id)
{
    const uint8_t id6 = (uint8_t)(id & 0x3Fu);
    const uint8_t p0 = parity8((uint8_t)(id6 & 0x17u));
    const uint8_t p1 = (uint8_t)(parity8((uint8_t)(id6 & 0x3Au)) ^ 1u);
    return (uint8_t)(id6 | (uint8_t)(p0 << 6) | (uint8_t)(p1 << 7));
}

/* enhanced checksum: plain 32-bit sum, carries folded at the end, inverted */
static uint8_t ref_checksum(uint8_t pid, const uint8_t *d, size_t n)
{
    uint32_t s = pid;
    size_t k;
    for (k = 0; k < n; k++) {
        s += d[k];
    }
    while (s > 0xFFu) {
        s = (s & 0xFFu) + (s >> 8);
    }
    return (uint8_t)(~s & 0xFFu);
}

/* a command frame written from the layout of specs/link-frames.md */
static void make_cmd_frame(uint8_t *f, uint8_t id, int power, int clear, uint16_t rpm)
{
    f[0] = 0x55u;
    f[1] = ref_pid(id);
    f[2] = (uint8_t)((power ? 1u : 0u) | (clear ? 2u : 0u));
    f[3] = (uint8_t)(rpm & 0xFFu);
    f[4] = (uint8_t)(rpm >> 8);
    f[5] = 0u;
    f[6] = ref_checksum(f[1], &f[2], 4u);
}

/* decoding status written from the table of specs/link-frames.md section 4 */
static int32_t ref_decode(const qfoc_link_cfg_t *c, const uint8_t *f, size_t len)
{
    int32_t st = 0;
    if (len != 7u) {
        st = -1;
    } else if (f[0] != 0x55u) {
        st = -2;
    } else if (f[1] != ref_pid(c->id_cmd)) {
        st = -3;
    } else if (f[6] != ref_checksum(f[1], &f[2], 4u)) {
        st = -4;
    } else if (((f[2] & 0xFCu) != 0u) || (f[5] != 0u)) {
        st = -5;
    } else if ((uint32_t)(f[3] | (f[4] << 8)) > c->rpm_max) {
        st = -6;
    }
    return st;
}

static void reseal(uint8_t *f)
{
    f[6] = ref_checksum(f[1], &f[2], 4u);
}

static qfoc_link_cfg_t make_cfg(void)
{
    qfoc_link_cfg_t c;
    c.id_cmd = 0x10u;
    c.id_status = 0x11u;
    c.rpm_max = 8000u;
    c.timeout_ms = 500u;
    c.can_id_a = 0x301u;
    c.can_id_b = 0x302u;
    return c;
}

static int cmd_eq(const qfoc_cmd_t *a, const qfoc_cmd_t *b)
{
    return (a->power_on == b->power_on) && (a->fault_clear == b->fault_clear)
           && (a->target_rpm == b->target_rpm) && (a->identify == b->identify);
}

static const qfoc_cmd_t sentinel = {true, true, 12345u, true};

/* ---- REQ-LINK-001 protected identifier ------------------------------------ */

/* REQ-LINK-001: every identifier against the parity tables and the published values.
   Methods: 1b every identifier 0 .. 255, bits 6 and 7 ignored; 1n the parity tables of the
   LIN 2.x specification and its published values, written in the test */
static void test_link_001_pid(void **state)
{
    static const uint8_t known[][2] = {
        {0x00u, 0x80u}, {0x01u, 0xC1u}, {0x02u, 0x42u}, {0x03u, 0x03u},
        {0x10u, 0x50u}, {0x20u, 0x20u}, {0x21u, 0x61u}, {0x22u, 0xE2u},
        {0x23u, 0xA3u}, {0x3Cu, 0x3Cu}, {0x3Du, 0x7Du}, {0x3Eu, 0xFEu}, {0x3Fu, 0xBFu},
    };
    uint32_t id;
    size_t k;
    (void)state;
    for (k = 0; k < sizeof(known) / sizeof(known[0]); k++) {
        assert_int_equal(qfoc_lin_pid(known[k][0]), known[k][1]);
        assert_int_equal(ref_pid(known[k][0]), known[k][1]);
    }
    for (id = 0u; id <= 255u; id++) {
        assert_int_equal(qfoc_lin_pid((uint8_t)id), ref_pid((uint8_t)id));
        /* bits 6, 7 of the argument are ignored */
        assert_int_equal(qfoc_lin_pid((uint8_t)id), qfoc_lin_pid((uint8_t)(id & 0x3Fu)));
    }
}

/* ---- REQ-LINK-002 enhanced checksum --------------------------------------- */

/* REQ-LINK-002: the specification's example, corners and random byte strings.
   Methods: 1b 20000 random byte strings of random length (up to 8, every fourth up to 255)
   and identifier; 1c all-zero and all-0xFF data, length 0; 1n the specification's example
   (0x4A: 0xE6), the reference sum with carry and the receiver's view (the sum over the whole
   frame is 0xFF) */
static void test_link_002_checksum(void **state)
{
    static const uint8_t ex[3] = {0x55u, 0x93u, 0xE5u};
    static const uint8_t ff[8] = {0xFFu, 0xFFu, 0xFFu, 0xFFu, 0xFFu, 0xFFu, 0xFFu, 0xFFu};
    static const uint8_t zero[8] = {0};
    uint8_t d[255];
    uint32_t t;
    uint32_t k;
    (void)state;
    assert_int_equal(qfoc_lin_checksum(0x4Au, ex, 3u), 0xE6u);
    assert_int_equal(qfoc_lin_checksum(0x4Au, ex, 0u), (uint8_t)(0xFFu - 0x4Au));
    assert_int_equal(qfoc_lin_checksum(0x00u, zero, 8u), 0xFFu);
    assert_int_equal(qfoc_lin_checksum(0xFFu, ff, 8u), 0x00u);
    for (t = 0u; t < 20000u; t++) {
        const uint8_t pid = (uint8_t)lcg_next();
        const uint8_t n = (uint8_t)(((t % 4u) == 0u) ? rnd(256u) : rnd(9u));
        uint32_t s;
        for (k = 0u; k < n; k++) {
            d[k] = (uint8_t)(lcg_next() >> 24);
        }
        assert_int_equal(qfoc_lin_checksum(pid, d, n), ref_checksum(pid, d, n));
        /* receiver view: the sum with carry over PID, data and checksum is 0xFF */
        s = pid;
        for (k = 0u; k < n; k++) {
            s += d[k];
        }
        s += qfoc_lin_checksum(pid, d, n);
        while (s > 0xFFu) {
            s = (s & 0xFFu) + (s >> 8);
        }
        assert_int_equal(s, 0xFFu);
    }
}

/* ---- REQ-LINK-003 / 004 command frame ------------------------------------- */

/* REQ-LINK-003, REQ-LINK-004: round trip of random commands, both flags, all corners.
   Methods: 1b 20000 random commands with both flags of each value and random identifiers and
   rpm_max; 1c the target 0 and rpm_max */
static void test_link_003_004_roundtrip(void **state)
{
    qfoc_link_cfg_t c = make_cfg();
    uint8_t f[QFOC_LIN_CMD_LEN];
    uint32_t t;
    (void)state;
    for (t = 0u; t < 20000u; t++) {
        qfoc_cmd_t cmd = sentinel;
        const int power = (int)(lcg_next() >> 31);
        const int clear = (int)(lcg_next() >> 31);
        uint16_t rpm;
        c.id_cmd = (uint8_t)rnd(0x3Cu);
        c.rpm_max = (uint16_t)(1u + rnd(65535u));
        rpm = (uint16_t)(((t % 3u) == 0u) ? c.rpm_max : rnd(((uint32_t)c.rpm_max + 1u)));
        if ((t % 7u) == 0u) {
            rpm = 0u;
        }
        make_cmd_frame(f, c.id_cmd, power, clear, rpm);
        assert_int_equal(qfoc_lin_decode_cmd(&c, f, QFOC_LIN_CMD_LEN, &cmd), QFOC_LINK_OK);
        assert_int_equal(cmd.power_on, power != 0);
        assert_int_equal(cmd.fault_clear, clear != 0);
        assert_int_equal(cmd.target_rpm, rpm);
        assert_false(cmd.identify);   /* no frame requests the identification */
    }
}

/* REQ-LINK-003: every single-byte corruption of a valid frame.  The enhanced
   checksum is a sum modulo 255, so it cannot see a data byte changed from 0x00 to
   0xFF or back (LIN 2.x property); every other single-byte corruption is rejected
   with the cause of the corrupted byte (sync, identifier, else checksum).  The
   0x00 <-> 0xFF changes are caught by the reserved-bit check in data bytes 0 and 3
   and by the range check in the target high byte; in the target low byte (a
   change of the target by 255 rpm within [0, rpm_max]) they are accepted: counted
   and printed as the residual.  *cmd is untouched by every rejection.
   Methods: 1b every value of every byte of 64 frames; 1c targets with 0x00 / 0xFF bytes (0,
   255, 256, 511, 7936, 7999, 8000); 1d the 0x00 <-> 0xFF changes the checksum cannot see; 1l
   every single-byte corruption injected into a valid frame; 1n the reference decoder written
   in the test */
static void test_link_003_single_byte_corruption(void **state)
{
    const qfoc_link_cfg_t c = make_cfg();
    uint8_t good[QFOC_LIN_CMD_LEN];
    uint32_t frames;
    uint32_t n = 0u;
    uint32_t rejected = 0u;
    uint32_t blind = 0u;
    uint32_t residual = 0u;
    (void)state;
    for (frames = 0u; frames < 64u; frames++) {
        size_t pos;
        /* targets with 0x00 / 0xFF bytes included (0, 255, 256, 511, 7936, 7999) */
        static const uint16_t rpm_set[8] = {0u, 255u, 256u, 511u, 7936u, 7999u, 8000u, 1u};
        const uint16_t rpm = (frames < 32u) ? rpm_set[frames % 8u] : (uint16_t)rnd(8001u);
        make_cmd_frame(good, c.id_cmd, (int)(frames & 1u), (int)((frames >> 1) & 1u), rpm);
        for (pos = 0u; pos < QFOC_LIN_CMD_LEN; pos++) {
            uint32_t v;
            for (v = 0u; v <= 255u; v++) {
                uint8_t f[QFOC_LIN_CMD_LEN];
                qfoc_cmd_t cmd = sentinel;
                int32_t st;
                const int swap = (pos >= 2u) && (pos <= 5u)
                                 && (((good[pos] == 0x00u) && (v == 0xFFu))
                                     || ((good[pos] == 0xFFu) && (v == 0x00u)));
                if (v == good[pos]) {
                    continue;
                }
                memcpy(f, good, sizeof f);
                f[pos] = (uint8_t)v;
                st = qfoc_lin_decode_cmd(&c, f, QFOC_LIN_CMD_LEN, &cmd);
                assert_int_equal(st, ref_decode(&c, f, QFOC_LIN_CMD_LEN));
                n++;
                if (!swap) {
                    assert_int_equal(st, (pos == 0u) ? QFOC_LINK_ERR_SYNC
                                     : ((pos == 1u) ? QFOC_LINK_ERR_ID : QFOC_LINK_ERR_CHECKSUM));
                } else {
                    blind++;
                    assert_true((st != QFOC_LINK_OK) || (pos == 3u));
                }
                if (st == QFOC_LINK_OK) {
                    residual++;
                    assert_int_equal(cmd.target_rpm, (uint16_t)(f[3] | (f[4] << 8)));
                } else {
                    rejected++;
                    assert_true(cmd_eq(&cmd, &sentinel));
                }
            }
        }
    }
    print_message("single-byte corruptions: %u, rejected %u, checksum-blind 0x00<->0xFF %u, "
                  "accepted (target low byte) %u\n", (unsigned)n, (unsigned)rejected,
                  (unsigned)blind, (unsigned)residual);
    assert_true(residual > 0u);
}

/* REQ-LINK-003: every length 0 .. QFOC_LIN_FRAME_MAX + 1 (and up to 255) of a
   buffer of exactly that size holding a valid frame prefix or padding.
   Methods: 1b every length 0 .. 255 of the length argument, in a buffer of exactly that
   size; 1c the command frame's length 7 and one either side, QFOC_LIN_FRAME_MAX and one
   above; 1d truncated and padded frames (an overread seen by memory checkers) */
static void test_link_003_lengths(void **state)
{
    const qfoc_link_cfg_t c = make_cfg();
    uint8_t good[QFOC_LIN_CMD_LEN];
    uint32_t len;
    (void)state;
    make_cmd_frame(good, c.id_cmd, 1, 0, 3000u);
    for (len = 0u; len <= 255u; len++) {
        /* heap buffer of exactly len bytes: an overread is seen by memory checkers */
        uint8_t *buf = malloc((len == 0u) ? 1u : len);
        qfoc_cmd_t cmd = sentinel;
        uint32_t k;
        int32_t st;
        assert_non_null(buf);
        for (k = 0u; k < len; k++) {
            buf[k] = (k < QFOC_LIN_CMD_LEN) ? good[k] : 0u;
        }
        st = qfoc_lin_decode_cmd(&c, buf, (uint8_t)len, &cmd);
        if (len == QFOC_LIN_CMD_LEN) {
            assert_int_equal(st, QFOC_LINK_OK);
            assert_int_equal(cmd.target_rpm, 3000u);
        } else {
            assert_int_equal(st, QFOC_LINK_ERR_LEN);
            assert_true(cmd_eq(&cmd, &sentinel));
        }
        free(buf);
    }
}

/* REQ-LINK-003: each reserved bit (data byte 0 bits 2..7, data byte 3) with a
   correct checksum is rejected as reserved.
   Methods: 1b each reserved bit of data byte 0 and every value of data byte 3; 1d reserved
   bits set with a correct checksum; 1l the reserved bits injected into a valid frame,
   resealed */
static void test_link_003_reserved_bits(void **state)
{
    const qfoc_link_cfg_t c = make_cfg();
    uint8_t f[QFOC_LIN_CMD_LEN];
    uint32_t bit;
    uint32_t v;
    (void)state;
    for (bit = 2u; bit < 8u; bit++) {
        qfoc_cmd_t cmd = sentinel;
        make_cmd_frame(f, c.id_cmd, 1, 1, 100u);
        f[2] = (uint8_t)(f[2] | (1u << bit));
        reseal(f);
        assert_int_equal(qfoc_lin_decode_cmd(&c, f, QFOC_LIN_CMD_LEN, &cmd), QFOC_LINK_ERR_RESERVED);
        assert_true(cmd_eq(&cmd, &sentinel));
    }
    for (v = 1u; v <= 255u; v++) {
        qfoc_cmd_t cmd = sentinel;
        make_cmd_frame(f, c.id_cmd, 0, 0, 100u);
        f[5] = (uint8_t)v;
        reseal(f);
        assert_int_equal(qfoc_lin_decode_cmd(&c, f, QFOC_LIN_CMD_LEN, &cmd), QFOC_LINK_ERR_RESERVED);
        assert_true(cmd_eq(&cmd, &sentinel));
    }
}

/* REQ-LINK-003: target speed range [0, rpm_max].
   Methods: 1c the target at rpm_max and rpm_max + 1, 65535 with rpm_max 65535, the target 0
   with rpm_max 1 */
static void test_link_003_target_range(void **state)
{
    qfoc_link_cfg_t c = make_cfg();
    uint8_t f[QFOC_LIN_CMD_LEN];
    qfoc_cmd_t cmd = sentinel;
    (void)state;
    make_cmd_frame(f, c.id_cmd, 1, 0, 8000u);
    assert_int_equal(qfoc_lin_decode_cmd(&c, f, QFOC_LIN_CMD_LEN, &cmd), QFOC_LINK_OK);
    assert_int_equal(cmd.target_rpm, 8000u);
    cmd = sentinel;
    make_cmd_frame(f, c.id_cmd, 1, 0, 8001u);
    assert_int_equal(qfoc_lin_decode_cmd(&c, f, QFOC_LIN_CMD_LEN, &cmd), QFOC_LINK_ERR_RANGE);
    assert_true(cmd_eq(&cmd, &sentinel));
    make_cmd_frame(f, c.id_cmd, 1, 0, 65535u);
    assert_int_equal(qfoc_lin_decode_cmd(&c, f, QFOC_LIN_CMD_LEN, &cmd), QFOC_LINK_ERR_RANGE);
    c.rpm_max = 65535u;
    assert_int_equal(qfoc_lin_decode_cmd(&c, f, QFOC_LIN_CMD_LEN, &cmd), QFOC_LINK_OK);
    assert_int_equal(cmd.target_rpm, 65535u);
    c.rpm_max = 1u;
    make_cmd_frame(f, c.id_cmd, 0, 0, 0u);
    assert_int_equal(qfoc_lin_decode_cmd(&c, f, QFOC_LIN_CMD_LEN, &cmd), QFOC_LINK_OK);
    assert_int_equal(cmd.target_rpm, 0u);
}

/* REQ-LINK-003: identifier errors (other identifier, parity bit flipped) and the
   decoding order when several checks fail.
   Methods: 1b every one of the 64 identifiers; 1d the parity bits flipped with the
   identifier bits right, several checks failing at once (the decoding order); 1l parity bit
   flips injected into the identifier byte */
static void test_link_003_id_and_order(void **state)
{
    const qfoc_link_cfg_t c = make_cfg();
    uint8_t f[QFOC_LIN_CMD_LEN];
    qfoc_cmd_t cmd = sentinel;
    uint32_t id;
    (void)state;
    for (id = 0u; id < 64u; id++) {
        make_cmd_frame(f, (uint8_t)id, 1, 0, 10u);
        assert_int_equal(qfoc_lin_decode_cmd(&c, f, QFOC_LIN_CMD_LEN, &cmd),
                         (id == c.id_cmd) ? QFOC_LINK_OK : QFOC_LINK_ERR_ID);
    }
    /* parity bits flipped, identifier bits right, checksum resealed */
    make_cmd_frame(f, c.id_cmd, 1, 0, 10u);
    f[1] = (uint8_t)(f[1] ^ 0x40u);
    reseal(f);
    assert_int_equal(qfoc_lin_decode_cmd(&c, f, QFOC_LIN_CMD_LEN, &cmd), QFOC_LINK_ERR_ID);
    make_cmd_frame(f, c.id_cmd, 1, 0, 10u);
    f[1] = (uint8_t)(f[1] ^ 0x80u);
    reseal(f);
    assert_int_equal(qfoc_lin_decode_cmd(&c, f, QFOC_LIN_CMD_LEN, &cmd), QFOC_LINK_ERR_ID);
    /* order: sync before id before checksum before reserved before range */
    cmd = sentinel;
    make_cmd_frame(f, c.id_cmd, 1, 0, 9000u);
    f[2] = 0xFFu;   /* reserved and range both fail: reserved first */
    reseal(f);
    assert_int_equal(qfoc_lin_decode_cmd(&c, f, QFOC_LIN_CMD_LEN, &cmd), QFOC_LINK_ERR_RESERVED);
    f[6] = (uint8_t)(f[6] + 1u); /* checksum too */
    assert_int_equal(qfoc_lin_decode_cmd(&c, f, QFOC_LIN_CMD_LEN, &cmd), QFOC_LINK_ERR_CHECKSUM);
    f[1] = 0x00u;                /* identifier too */
    assert_int_equal(qfoc_lin_decode_cmd(&c, f, QFOC_LIN_CMD_LEN, &cmd), QFOC_LINK_ERR_ID);
    f[0] = 0x00u;                /* sync too */
    assert_int_equal(qfoc_lin_decode_cmd(&c, f, QFOC_LIN_CMD_LEN, &cmd), QFOC_LINK_ERR_SYNC);
    assert_int_equal(qfoc_lin_decode_cmd(&c, f, 8u, &cmd), QFOC_LINK_ERR_LEN);
    assert_true(cmd_eq(&cmd, &sentinel));
}

/* ---- REQ-LINK-005 status payload ------------------------------------------ */

static uint8_t ref_round_sat(double x)
{
    const double r = floor(x + 0.5);
    return (uint8_t)((r < 0.0) ? 0.0 : ((r > 255.0) ? 255.0 : r));
}

/* reference payload from the physical values (specs/link-frames.md section 5) */
static void ref_payload(const qfoc_status_t *st, uint8_t *d)
{
    const unsigned s = (st->state > 15u) ? 15u : st->state;
    const unsigned ss = (st->substate > 15u) ? 15u : st->substate;
    d[0] = (uint8_t)(s | (ss << 4));
    d[1] = (uint8_t)(st->faults & 0xFFu);
    d[2] = (uint8_t)(st->faults >> 8);
    d[3] = (uint8_t)(st->speed_rpm & 0xFFu);
    d[4] = (uint8_t)(st->speed_rpm >> 8);
    /* (0.1 V x vdc) / 4 V, (0.01 A x i) / 0.25 A, 0.1 degC x t + 40 degC; each
       written as one correctly rounded double division so that exact halves stay
       exact */
    d[5] = ref_round_sat((double)st->vdc_dv / 40.0);
    d[6] = ref_round_sat((double)st->current_ca / 25.0);
    d[7] = ref_round_sat(((double)st->temp_dc / 10.0) + 40.0);
}

static qfoc_status_t rand_status(void)
{
    qfoc_status_t st;
    st.state = (uint8_t)lcg_next();
    st.substate = (uint8_t)(lcg_next() >> 8);
    st.faults = (uint16_t)lcg_next();
    st.speed_rpm = (uint16_t)(lcg_next() >> 16);
    st.vdc_dv = (uint16_t)((rnd(2u) == 0u) ? rnd(11000u) : (lcg_next() >> 16));
    st.current_ca = (uint16_t)((rnd(2u) == 0u) ? rnd(7000u) : (lcg_next() >> 16));
    st.temp_dc = (rnd(2u) == 0u) ? (int16_t)rand_range(-500, 2200) : rand_i16();
    return st;
}

/* REQ-LINK-005: LIN status frame and CAN payload against the reference, random
   and extreme inputs (saturation).
   Methods: 1b 40000 random status records; 1c 0, 1 and 65535 for the bus and the current,
   the temperatures -32768, -406 / -405 and 2144 / 2145 (the ends of the byte's range),
   undefined states and sub-states 255, 16; 1n the reference payload and checksum written in
   the test, rounding error <= 0.5 LSB */
static void test_link_005_status_payload(void **state)
{
    const qfoc_link_cfg_t c = make_cfg();
    qfoc_link_t l;
    uint32_t t;
    double max_vdc = 0.0;
    double max_cur = 0.0;
    double max_temp = 0.0;
    (void)state;
    assert_int_equal(qfoc_link_init(&l, &c), QFOC_LINK_OK);
    for (t = 0u; t < 40000u; t++) {
        qfoc_status_t st = rand_status();
        uint8_t frame[QFOC_LIN_FRAME_MAX + 4u];
        uint8_t ref[8];
        qfoc_can_frame_t cf;
        double e;
        if (t < 6u) {
            static const uint16_t u16c[3] = {0u, 1u, 65535u};
            static const int16_t tc[6] = {-32768, -406, -405, 2144, 2145, 32767};
            st.state = (uint8_t)((t % 2u) ? 255u : 15u);
            st.substate = (uint8_t)((t % 2u) ? 16u : 0u);
            st.vdc_dv = u16c[t % 3u];
            st.current_ca = u16c[(t + 1u) % 3u];
            st.temp_dc = tc[t];
        }
        memset(frame, 0xA5, sizeof frame);
        ref_payload(&st, ref);
        assert_int_equal(qfoc_lin_encode_status(&c, &st, frame), QFOC_LIN_STATUS_LEN);
        assert_int_equal(frame[0], 0x55u);
        assert_int_equal(frame[1], ref_pid(c.id_status));
        assert_memory_equal(&frame[2], ref, 8u);
        assert_int_equal(frame[10], ref_checksum(frame[1], &frame[2], 8u));
        assert_int_equal(frame[11], 0xA5u); /* nothing written past the frame */
        qfoc_can_status(&l, &st, &cf);
        assert_int_equal(cf.dlc, 8u);
        assert_memory_equal(cf.data, ref, 8u);
        /* quantisation error against the unrounded physical value, in LSB */
        e = fabs((double)frame[7] - ((double)st.vdc_dv / 40.0));
        if ((st.vdc_dv <= 10180u) && (e > max_vdc)) {
            max_vdc = e;
        }
        e = fabs((double)frame[8] - ((double)st.current_ca / 25.0));
        if ((st.current_ca <= 6362u) && (e > max_cur)) {
            max_cur = e;
        }
        e = fabs((double)frame[9] - (((double)st.temp_dc / 10.0) + 40.0));
        if ((st.temp_dc >= -405) && (st.temp_dc < 2145) && (e > max_temp)) {
            max_temp = e;
        }
    }
    print_message("payload max rounding error (LSB): vdc %.3f, current %.3f, temp %.3f\n",
                  max_vdc, max_cur, max_temp);
    assert_true(max_vdc <= 0.5);
    assert_true(max_cur <= 0.5);
    assert_true(max_temp <= 0.5);
}

/* REQ-LINK-005: the saturation ends explicitly.
   Methods: 1c every field at its largest value (saturated to 0xFF) and at its smallest
   (-32768 degrees, 0), and the scaling points 320 V, 40 A, 25 and -40 degrees C computed by
   hand */
static void test_link_005_saturation(void **state)
{
    const qfoc_link_cfg_t c = make_cfg();
    qfoc_status_t st;
    uint8_t f[QFOC_LIN_FRAME_MAX];
    (void)state;
    st.state = 255u;
    st.substate = 200u;
    st.faults = 0xFFFFu;
    st.speed_rpm = 0xFFFFu;
    st.vdc_dv = 65535u;
    st.current_ca = 65535u;
    st.temp_dc = 32767;
    (void)qfoc_lin_encode_status(&c, &st, f);
    assert_int_equal(f[2], 0xFFu);
    assert_int_equal(f[3], 0xFFu);
    assert_int_equal(f[4], 0xFFu);
    assert_int_equal(f[5], 0xFFu);
    assert_int_equal(f[6], 0xFFu);
    assert_int_equal(f[7], 255u);
    assert_int_equal(f[8], 255u);
    assert_int_equal(f[9], 255u);
    st.state = 3u;
    st.substate = 2u;
    st.faults = 0x0102u;
    st.speed_rpm = 0x0304u;
    st.vdc_dv = 0u;
    st.current_ca = 0u;
    st.temp_dc = -32768;
    (void)qfoc_lin_encode_status(&c, &st, f);
    assert_int_equal(f[2], 0x23u);
    assert_int_equal(f[3], 0x02u);
    assert_int_equal(f[4], 0x01u);
    assert_int_equal(f[5], 0x04u);
    assert_int_equal(f[6], 0x03u);
    assert_int_equal(f[7], 0u);
    assert_int_equal(f[8], 0u);
    assert_int_equal(f[9], 0u);
    /* 320.0 V -> 80; 40.00 A -> 160; 25.0 degC -> 65; -40.0 degC -> 0 */
    st.vdc_dv = 3200u;
    st.current_ca = 4000u;
    st.temp_dc = 250;
    (void)qfoc_lin_encode_status(&c, &st, f);
    assert_int_equal(f[7], 80u);
    assert_int_equal(f[8], 160u);
    assert_int_equal(f[9], 65u);
    st.temp_dc = -400;
    (void)qfoc_lin_encode_status(&c, &st, f);
    assert_int_equal(f[9], 0u);
}

/* ---- REQ-LINK-006 configuration and instance ------------------------------ */

/* REQ-LINK-006: each configuration field at and beyond its bounds; rejected init
   gives the safe, permanently lost link.
   Methods: 1b each configuration rule broken alone; 1c each field at its bounds (identifiers
   0x3B / 0x3C, rpm_max 0 / 1, timeout 0, 1, 60000, 60001, CAN identifiers 0x7FF / 0x800); 1d
   an invalid configuration (the safe, permanently lost link that never powers the drive) and
   an instance filled with 0x5A before init */
static void test_link_006_cfg_and_init(void **state)
{
    qfoc_link_cfg_t c = make_cfg();
    qfoc_link_t l;
    qfoc_cmd_t cmd;
    uint8_t f[QFOC_LIN_CMD_LEN];
    uint32_t k;
    (void)state;
    assert_true(qfoc_link_cfg_is_valid(&c));
    c.id_cmd = 0x3Bu; c.id_status = 0u; c.rpm_max = 1u; c.timeout_ms = 1u;
    c.can_id_a = 0u; c.can_id_b = 0x7FFu;
    assert_true(qfoc_link_cfg_is_valid(&c));
    c.timeout_ms = 60000u;
    assert_true(qfoc_link_cfg_is_valid(&c));
    for (k = 0u; k < 8u; k++) {
        c = make_cfg();
        switch (k) {
        case 0u: c.id_cmd = 0x3Cu; break;
        case 1u: c.id_status = 0x3Cu; break;
        case 2u: c.id_status = c.id_cmd; break;
        case 3u: c.rpm_max = 0u; break;
        case 4u: c.timeout_ms = 0u; break;
        case 5u: c.timeout_ms = 60001u; break;
        case 6u: c.can_id_a = 0x800u; break;
        default: c.can_id_b = 0x800u; break;
        }
        assert_false(qfoc_link_cfg_is_valid(&c));
        memset(&l, 0x5A, sizeof l);
        assert_int_equal(qfoc_link_init(&l, &c), QFOC_LINK_ERR_CFG);
        assert_true(qfoc_link_is_valid(&l));
        assert_true(qfoc_link_lost(&l));
        assert_int_equal(l.cfg.can_id_a, 0x7FFu);
        /* even a well-formed frame of the safe configuration never powers the drive */
        make_cmd_frame(f, 0x00u, 1, 1, 1u);
        assert_true(qfoc_link_service(&l, f, QFOC_LIN_CMD_LEN));
        assert_true(qfoc_link_lost(&l));
        qfoc_link_command(&l, &cmd);
        assert_false(cmd.power_on);
        assert_false(cmd.fault_clear);
        assert_false(qfoc_link_service(&l, NULL, 0u));
        assert_true(qfoc_link_lost(&l));
    }
    c = make_cfg();
    memset(&l, 0x5A, sizeof l);
    assert_int_equal(qfoc_link_init(&l, &c), QFOC_LINK_OK);
    assert_true(qfoc_link_is_valid(&l));
    assert_false(qfoc_link_lost(&l));
    assert_int_equal(l.n_ok + l.n_len + l.n_sync + l.n_id + l.n_checksum + l.n_reserved
                     + l.n_range, 0);
    assert_int_equal(l.cfg.rpm_max, c.rpm_max);
}

/* REQ-LINK-006: qfoc_link_is_valid() rejects each broken invariant.
   Methods: 1b each part of the invariant broken in turn, and the combinations that are
   allowed; 1c silent_ms one above the timeout; 1l the link's fields overwritten, refused by
   the validity check */
static void test_link_006_is_valid(void **state)
{
    const qfoc_link_cfg_t c = make_cfg();
    qfoc_link_t l;
    qfoc_link_t b;
    (void)state;
    assert_int_equal(qfoc_link_init(&l, &c), QFOC_LINK_OK);
    b = l; b.cfg.rpm_max = 0u;
    assert_false(qfoc_link_is_valid(&b));
    b = l; b.cmd.target_rpm = (uint16_t)(c.rpm_max + 1u);
    assert_false(qfoc_link_is_valid(&b));
    b = l; b.cmd.power_on = true;
    assert_false(qfoc_link_is_valid(&b));
    b = l; b.cmd.fault_clear = true;
    assert_false(qfoc_link_is_valid(&b));
    b = l; b.cmd.target_rpm = 1u;
    assert_false(qfoc_link_is_valid(&b));
    b = l; b.cmd.identify = true;   /* an identification request before any command */
    assert_false(qfoc_link_is_valid(&b));
    b = l; b.seen = true; b.cmd.power_on = true; b.cmd.target_rpm = 1u;
    assert_true(qfoc_link_is_valid(&b));
    b.cmd.identify = true;
    assert_true(qfoc_link_is_valid(&b));
    b.cmd.identify = false;
    b.silent_ms = (uint16_t)(c.timeout_ms + 1u);
    assert_false(qfoc_link_is_valid(&b));
    b.lost = true;
    assert_true(qfoc_link_is_valid(&b));
    b = l; b.lost = true;
    assert_false(qfoc_link_is_valid(&b));
    b = l; b.cfg_ok = false;
    assert_false(qfoc_link_is_valid(&b));
    b.lost = true;
    assert_true(qfoc_link_is_valid(&b));
}

/* ---- REQ-LINK-007 effective command --------------------------------------- */

/* REQ-LINK-007, REQ-LINK-009: before the first valid frame the drive is off and the link
   not lost; malformed frames of every cause change neither the command nor the timer.
   Methods: 1b 70000 service calls over eight kinds of frames (each malformation cause,
   valid, out of range, none); 1d the first 2000 calls only malformed or no frames; 1l random
   corruptions of the length, sync, identifier, data and checksum injected; 1n a twin link
   that sees only the well-formed frames */
static void test_link_007_malformed_no_effect(void **state)
{
    const qfoc_link_cfg_t c = make_cfg();
    qfoc_link_t a;
    qfoc_link_t b;
    qfoc_cmd_t ca;
    qfoc_cmd_t cb;
    uint8_t f[QFOC_LIN_FRAME_MAX + 1u];
    uint32_t t;
    uint32_t accepted = 0u;
    (void)state;
    assert_int_equal(qfoc_link_init(&a, &c), QFOC_LINK_OK);
    b = a;
    for (t = 0u; t < 70000u; t++) {
        bool ra;
        bool rb;
        uint8_t len;
        int32_t expect;
        uint32_t kind = rnd(8u);
        make_cmd_frame(f, c.id_cmd, (int)(lcg_next() >> 31), (int)(lcg_next() >> 31),
                       (uint16_t)rnd(9000u));
        len = QFOC_LIN_CMD_LEN;
        if (t < 2000u) {
            kind = 7u + (kind % 7u); /* first 2000 calls: only malformed or no frame */
        }
        switch (kind) {
        case 0u: len = (uint8_t)rnd((QFOC_LIN_FRAME_MAX + 2u)); break;
        case 1u: f[0] = (uint8_t)(f[0] ^ (1u + rnd(255u))); break;
        case 2u: f[1] = (uint8_t)(f[1] ^ (1u + rnd(255u))); break;
        case 3u: f[2 + rnd(5u)] ^= (uint8_t)(1u + rnd(255u)); break;
        case 4u: f[5] = 1u; reseal(f); break;
        case 5u: case 6u: break; /* valid (or out of range above 8000 rpm) */
        case 7u: len = 0u; break;
        case 8u: len = 3u; break;
        case 9u: f[0] = 0u; break;
        case 10u: f[1] = 0u; break;
        case 11u: f[6] = (uint8_t)(f[6] + 1u); break;
        case 12u: f[2] = 4u; reseal(f); break;
        default: f[3] = 0xFFu; f[4] = 0xFFu; reseal(f); break;
        }
        {
            qfoc_cmd_t probe = sentinel;
            expect = (len == 0u) ? 1 : qfoc_lin_decode_cmd(&c, f, len, &probe);
        }
        ra = qfoc_link_service(&a, f, len);
        /* b sees the frame only when it is well-formed, otherwise nothing */
        rb = qfoc_link_service(&b, f, (expect == QFOC_LINK_OK) ? len : 0u);
        assert_int_equal(ra, expect == QFOC_LINK_OK);
        assert_int_equal(ra, rb);
        accepted += ra ? 1u : 0u;
        qfoc_link_command(&a, &ca);
        qfoc_link_command(&b, &cb);
        assert_true(cmd_eq(&ca, &cb));
        assert_int_equal(qfoc_link_lost(&a), qfoc_link_lost(&b));
        assert_int_equal(a.silent_ms, b.silent_ms);
        assert_true(qfoc_link_is_valid(&a));
        if (t < 2000u) {
            assert_false(qfoc_link_lost(&a));
            assert_false(ca.power_on);
            assert_false(ca.fault_clear);
            assert_int_equal(ca.target_rpm, 0u);
        }
    }
    print_message("service calls 70000, accepted %u, rejected: len %u sync %u id %u "
                  "checksum %u reserved %u range %u\n", (unsigned)accepted,
                  a.n_len, a.n_sync, a.n_id, a.n_checksum, a.n_reserved, a.n_range);
    assert_int_equal(a.n_ok, accepted);
    assert_true((a.n_len > 0u) && (a.n_sync > 0u) && (a.n_id > 0u) && (a.n_checksum > 0u)
                && (a.n_reserved > 0u) && (a.n_range > 0u));
}

/* REQ-LINK-007: the effective command follows the last valid frame.
   Methods: 1a the command of the last valid frame taken, the drive off before the first */
static void test_link_007_effective_command(void **state)
{
    const qfoc_link_cfg_t c = make_cfg();
    qfoc_link_t l;
    qfoc_cmd_t cmd;
    uint8_t f[QFOC_LIN_CMD_LEN];
    (void)state;
    assert_int_equal(qfoc_link_init(&l, &c), QFOC_LINK_OK);
    qfoc_link_command(&l, &cmd);
    assert_false(cmd.power_on);
    assert_int_equal(cmd.target_rpm, 0u);
    make_cmd_frame(f, c.id_cmd, 1, 0, 4000u);
    assert_true(qfoc_link_service(&l, f, QFOC_LIN_CMD_LEN));
    qfoc_link_command(&l, &cmd);
    assert_true(cmd.power_on);
    assert_false(cmd.fault_clear);
    assert_int_equal(cmd.target_rpm, 4000u);
    make_cmd_frame(f, c.id_cmd, 0, 1, 0u);
    assert_true(qfoc_link_service(&l, f, QFOC_LIN_CMD_LEN));
    qfoc_link_command(&l, &cmd);
    assert_false(cmd.power_on);
    assert_true(cmd.fault_clear);
    assert_int_equal(cmd.target_rpm, 0u);
}

/* ---- REQ-LINK-008 timeout ------------------------------------------------- */

static void run_timeout(uint16_t timeout, int malformed)
{
    qfoc_link_cfg_t c = make_cfg();
    qfoc_link_t l;
    qfoc_cmd_t cmd;
    uint8_t f[QFOC_LIN_CMD_LEN];
    uint8_t bad[QFOC_LIN_CMD_LEN];
    uint32_t k;
    c.timeout_ms = timeout;
    assert_int_equal(qfoc_link_init(&l, &c), QFOC_LINK_OK);
    make_cmd_frame(f, c.id_cmd, 1, 1, 2500u);
    memcpy(bad, f, sizeof bad);
    bad[6] = (uint8_t)(bad[6] ^ 0x01u);
    assert_true(qfoc_link_service(&l, f, QFOC_LIN_CMD_LEN));
    /* timeout_ms calls without a valid command: not lost */
    for (k = 1u; k <= timeout; k++) {
        (void)qfoc_link_service(&l, malformed ? bad : NULL, malformed ? QFOC_LIN_CMD_LEN : 0u);
        assert_false(qfoc_link_lost(&l));
        qfoc_link_command(&l, &cmd);
        assert_true(cmd.power_on);
        assert_true(cmd.fault_clear);
    }
    /* the (timeout_ms + 1)-th: lost, drive off, target kept */
    (void)qfoc_link_service(&l, malformed ? bad : NULL, malformed ? QFOC_LIN_CMD_LEN : 0u);
    assert_true(qfoc_link_lost(&l));
    qfoc_link_command(&l, &cmd);
    assert_false(cmd.power_on);
    assert_false(cmd.fault_clear);
    assert_int_equal(cmd.target_rpm, 2500u);
    /* stays lost through the saturation of the silent time */
    for (k = 0u; k < 70000u; k++) {
        (void)qfoc_link_service(&l, NULL, 0u);
    }
    assert_int_equal(l.silent_ms, 65535u);
    assert_true(qfoc_link_lost(&l));
    /* a valid frame restores the link */
    assert_true(qfoc_link_service(&l, f, QFOC_LIN_CMD_LEN));
    assert_false(qfoc_link_lost(&l));
    qfoc_link_command(&l, &cmd);
    assert_true(cmd.power_on);
    assert_true(qfoc_link_is_valid(&l));
}

/* REQ-LINK-008: lost exactly at timeout_ms + 1 calls, not at timeout_ms; for the
   smallest, a typical and the largest timeout, with silence and malformed frames.
   Methods: 1c timeout_ms and timeout_ms + 1 calls for the timeouts 1, 500 and 60000, and the
   silent time saturated at 65535; 1d the link lost by silence and by malformed frames (a
   wrong checksum) */
static void test_link_008_timeout_exact(void **state)
{
    (void)state;
    run_timeout(1u, 0);
    run_timeout(1u, 1);
    run_timeout(500u, 0);
    run_timeout(500u, 1);
    run_timeout(60000u, 0);
}

/* REQ-LINK-008: before the first valid frame the link never times out.
   Methods: 1c 70000 calls, past the saturation of the silent time at 65535; 1d no frame ever
   received */
static void test_link_008_not_lost_before_first_frame(void **state)
{
    const qfoc_link_cfg_t c = make_cfg();
    qfoc_link_t l;
    uint32_t k;
    (void)state;
    assert_int_equal(qfoc_link_init(&l, &c), QFOC_LINK_OK);
    for (k = 0u; k < 70000u; k++) {
        assert_false(qfoc_link_service(&l, NULL, 0u));
        assert_false(qfoc_link_lost(&l));
    }
    assert_int_equal(l.silent_ms, 65535u);
}

/* ---- REQ-LINK-009 counters ------------------------------------------------- */

/* REQ-LINK-009: each counter counts its cause only and saturates at 65535.
   Methods: 1b each of the seven causes counted alone; 1c each counter across 65535 by 65537
   calls and from 65534; 1d a frame of each malformation cause */
static void test_link_009_counters_saturate(void **state)
{
    const qfoc_link_cfg_t c = make_cfg();
    qfoc_link_t l;
    uint8_t f[QFOC_LIN_CMD_LEN];
    uint32_t cause;
    (void)state;
    for (cause = 0u; cause < 7u; cause++) {
        uint16_t *ctr;
        uint32_t k;
        uint8_t len = QFOC_LIN_CMD_LEN;
        assert_int_equal(qfoc_link_init(&l, &c), QFOC_LINK_OK);
        make_cmd_frame(f, c.id_cmd, 1, 0, 100u);
        switch (cause) {
        case 0u: ctr = &l.n_ok; break;
        case 1u: ctr = &l.n_len; len = 6u; break;
        case 2u: ctr = &l.n_sync; f[0] = 0x54u; break;
        case 3u: ctr = &l.n_id; f[1] = ref_pid(0x11u); reseal(f); break;
        case 4u: ctr = &l.n_checksum; f[6] = (uint8_t)(f[6] ^ 0x80u); break;
        case 5u: ctr = &l.n_reserved; f[2] = 0x80u; reseal(f); break;
        default: ctr = &l.n_range; f[4] = 0x20u; reseal(f); break;
        }
        /* by a loop across the saturation */
        for (k = 0u; k < 65537u; k++) {
            (void)qfoc_link_service(&l, f, len);
        }
        assert_int_equal(*ctr, 65535u);
        assert_int_equal(l.n_ok + l.n_len + l.n_sync + l.n_id + l.n_checksum + l.n_reserved
                         + l.n_range, 65535);
        /* by setting the state next to the limit */
        *ctr = 65534u;
        (void)qfoc_link_service(&l, f, len);
        assert_int_equal(*ctr, 65535u);
        (void)qfoc_link_service(&l, f, len);
        assert_int_equal(*ctr, 65535u);
        /* no frame counts nothing */
        *ctr = 7u;
        (void)qfoc_link_service(&l, f, 0u);
        assert_int_equal(*ctr, 7u);
        assert_true(qfoc_link_is_valid(&l));
    }
}

/* ---- REQ-LINK-010 CAN ------------------------------------------------------ */

/* REQ-LINK-010: CAN identifiers alternate a, b, a, ... from init; DLC 8.
   Methods: 1a the identifiers a, b, a, ... from init and after a re-init, over 1000 frames */
static void test_link_010_can_alternation(void **state)
{
    const qfoc_link_cfg_t c = make_cfg();
    qfoc_link_t l;
    qfoc_can_frame_t f;
    qfoc_status_t st = rand_status();
    uint32_t k;
    (void)state;
    assert_int_equal(qfoc_link_init(&l, &c), QFOC_LINK_OK);
    for (k = 0u; k < 1000u; k++) {
        qfoc_can_status(&l, &st, &f);
        assert_int_equal(f.id, ((k % 2u) == 0u) ? c.can_id_a : c.can_id_b);
        assert_int_equal(f.dlc, 8u);
        assert_true(qfoc_link_is_valid(&l));
    }
    /* re-init restarts with can_id_a */
    qfoc_can_status(&l, &st, &f);
    assert_int_equal(f.id, c.can_id_a);
    assert_int_equal(qfoc_link_init(&l, &c), QFOC_LINK_OK);
    qfoc_can_status(&l, &st, &f);
    assert_int_equal(f.id, c.can_id_a);
}

/* ---- REQ-LINK-011 decoded commands ------------------------------------------- */

/* REQ-LINK-011: a decoded command is taken like the same command in a frame (twin links
   fed the frame and the command give the same link state), refused above rpm_max with
   only n_range counted; the silent time and the loss follow the frame's rule.
   Methods: 1b 5000 random commands, targets around rpm_max and anywhere in 0 .. 65535; 1c
   rpm_max and rpm_max + 1, the loss at timeout_ms and timeout_ms + 1, the counters at 65535;
   1d a rejected configuration; 1n a twin link fed the same commands as frames */
static void test_link_011_accept(void **state)
{
    const qfoc_link_cfg_t c = make_cfg();
    qfoc_link_t a;
    qfoc_link_t b;
    qfoc_link_t before;
    qfoc_cmd_t cmd;
    qfoc_cmd_t eff;
    uint8_t f[QFOC_LIN_FRAME_MAX];
    uint32_t k;
    uint32_t n;
    (void)state;
    assert_int_equal(qfoc_link_init(&a, &c), QFOC_LINK_OK);
    assert_int_equal(qfoc_link_init(&b, &c), QFOC_LINK_OK);
    for (k = 0u; k < 5000u; k++) {
        const int power = (int)rnd(2u);
        const int clear = (int)rnd(2u);
        /* targets around rpm_max and anywhere in 0 .. 65535 */
        const uint16_t rpm = (uint16_t)((rnd(2u) == 0u) ? (c.rpm_max - 3u + rnd(7u)) : rnd(65536u));
        const bool in_range = rpm <= c.rpm_max;
        cmd.power_on = (power != 0);
        cmd.fault_clear = (clear != 0);
        cmd.target_rpm = rpm;
        cmd.identify = false;   /* as a frame's (test_req_ident_007_link_request) */
        /* a: the frame, then idle ticks; b: the command between the same ticks */
        make_cmd_frame(f, c.id_cmd, power, clear, rpm);
        before = b;
        assert_int_equal(qfoc_link_service(&a, f, QFOC_LIN_CMD_LEN), in_range);
        assert_int_equal(qfoc_link_accept(&b, &cmd), in_range ? QFOC_LINK_OK : QFOC_LINK_ERR_RANGE);
        if (in_range) {
            assert_true(cmd_eq(&b.cmd, &cmd));
            assert_true(b.seen);
            assert_int_equal(b.silent_ms, 0u);
            assert_false(b.lost);
            assert_int_equal(b.n_ok, (before.n_ok < 65535u) ? before.n_ok + 1u : 65535u);
            assert_int_equal(b.n_range, before.n_range);
            /* the frame's silent time was restarted in its own service call */
            assert_int_equal(a.silent_ms, 0u);
        } else {
            /* refused: nothing but n_range moved (the frame's service call advanced its
               own timer; the command's timer advances in the next service call) */
            assert_true(cmd_eq(&b.cmd, &before.cmd));
            assert_int_equal(b.seen, before.seen);
            assert_int_equal(b.silent_ms, before.silent_ms);
            assert_int_equal(b.lost, before.lost);
            assert_int_equal(b.n_ok, before.n_ok);
            assert_int_equal(b.n_range, before.n_range + 1u);
        }
        assert_true(qfoc_link_is_valid(&b));
        assert_true(cmd_eq(&a.cmd, &b.cmd));
        assert_int_equal(a.n_ok, b.n_ok);
        assert_int_equal(a.n_range, b.n_range);
        /* one idle service call on b stands for the call a made with its frame */
        if (!in_range) {
            (void)qfoc_link_service(&b, f, 0u);
        }
        n = rnd(4u);
        while (n > 0u) {
            (void)qfoc_link_service(&a, f, 0u);
            (void)qfoc_link_service(&b, f, 0u);
            n--;
        }
        qfoc_link_command(&a, &eff);
        qfoc_link_command(&b, &cmd);
        assert_true(cmd_eq(&eff, &cmd));
        assert_int_equal(a.lost, b.lost);
    }
    /* the loss after the last command: at the (timeout_ms + 1)-th service call after the
       one that took the frame, and after the command taken between two calls (it counts
       as received at the call before it) */
    cmd.power_on = true;
    cmd.fault_clear = false;
    cmd.target_rpm = 3000u;
    cmd.identify = false;
    make_cmd_frame(f, c.id_cmd, 1, 0, 3000u);
    assert_true(qfoc_link_service(&a, f, QFOC_LIN_CMD_LEN));
    assert_int_equal(qfoc_link_accept(&b, &cmd), QFOC_LINK_OK);
    for (k = 1u; k <= (uint32_t)c.timeout_ms + 1u; k++) {
        (void)qfoc_link_service(&a, f, 0u);
        (void)qfoc_link_service(&b, f, 0u);
        assert_int_equal(a.lost, k > c.timeout_ms);
        assert_int_equal(b.lost, k > c.timeout_ms);
    }
    /* a rejected configuration: a taken command never makes the link usable */
    {
        qfoc_link_cfg_t bad = c;
        bad.id_status = bad.id_cmd;
        assert_int_equal(qfoc_link_init(&b, &bad), QFOC_LINK_ERR_CFG);
        cmd.target_rpm = 0u;
        assert_int_equal(qfoc_link_accept(&b, &cmd), QFOC_LINK_OK);
        assert_true(b.lost);
        qfoc_link_command(&b, &eff);
        assert_false(eff.power_on);
    }
    /* n_ok and n_range saturate */
    assert_int_equal(qfoc_link_init(&b, &c), QFOC_LINK_OK);
    b.n_ok = 65535u;
    b.n_range = 65535u;
    cmd.target_rpm = c.rpm_max;
    assert_int_equal(qfoc_link_accept(&b, &cmd), QFOC_LINK_OK);
    assert_int_equal(b.n_ok, 65535u);
    cmd.target_rpm = (uint16_t)(c.rpm_max + 1u);
    assert_int_equal(qfoc_link_accept(&b, &cmd), QFOC_LINK_ERR_RANGE);
    assert_int_equal(b.n_range, 65535u);
}

/* REQ-IDENT-007: the identification request lives only in commands given through the
   function: a taken command with identify set makes it the effective command's; a refused
   one (target above rpm_max) changes nothing; the next well-formed frame replaces it with
   identify false (the frame cannot carry it); the link lost at timeout_ms + 1 silent calls
   clears it in the effective command; a rejected configuration never gives it.
   Methods: 1b each way the request ends; 1c the loss at timeout_ms and timeout_ms + 1;
   1d a rejected configuration; 1n the link rules of link.h written here */
static void test_req_ident_007_link_request(void **state)
{
    const qfoc_link_cfg_t c = make_cfg();
    qfoc_link_t l;
    qfoc_cmd_t cmd = { false, false, 0u, true };
    qfoc_cmd_t eff = sentinel;
    uint8_t f[QFOC_LIN_FRAME_MAX];
    uint32_t k;
    (void)state;
    assert_int_equal(qfoc_link_init(&l, &c), QFOC_LINK_OK);
    assert_false(l.cmd.identify);
    qfoc_link_command(&l, &eff);
    assert_false(eff.identify);     /* none before the first command */
    assert_int_equal(qfoc_link_accept(&l, &cmd), QFOC_LINK_OK);
    qfoc_link_command(&l, &eff);
    assert_true(eff.identify);
    assert_false(eff.power_on);
    /* refused: the request stands */
    cmd.identify = false;
    cmd.target_rpm = (uint16_t)(c.rpm_max + 1u);
    assert_int_equal(qfoc_link_accept(&l, &cmd), QFOC_LINK_ERR_RANGE);
    qfoc_link_command(&l, &eff);
    assert_true(eff.identify);
    /* a well-formed frame replaces it */
    make_cmd_frame(f, c.id_cmd, 0, 0, 0u);
    assert_true(qfoc_link_service(&l, f, QFOC_LIN_CMD_LEN));
    qfoc_link_command(&l, &eff);
    assert_false(eff.identify);
    assert_false(l.cmd.identify);
    /* requested again, then silent: in effect through timeout_ms calls, cleared after */
    cmd.identify = true;
    cmd.target_rpm = 0u;
    assert_int_equal(qfoc_link_accept(&l, &cmd), QFOC_LINK_OK);
    for (k = 1u; k <= (uint32_t)c.timeout_ms + 1u; k++) {
        (void)qfoc_link_service(&l, f, 0u);
        qfoc_link_command(&l, &eff);
        assert_int_equal(eff.identify, k <= c.timeout_ms);
    }
    assert_true(qfoc_link_lost(&l));
    /* a rejected configuration: a taken command never gives it */
    {
        qfoc_link_cfg_t bad = c;
        bad.id_status = bad.id_cmd;
        assert_int_equal(qfoc_link_init(&l, &bad), QFOC_LINK_ERR_CFG);
        assert_int_equal(qfoc_link_accept(&l, &cmd), QFOC_LINK_OK);
        qfoc_link_command(&l, &eff);
        assert_false(eff.identify);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_link_001_pid),
        cmocka_unit_test(test_link_002_checksum),
        cmocka_unit_test(test_link_003_004_roundtrip),
        cmocka_unit_test(test_link_003_single_byte_corruption),
        cmocka_unit_test(test_link_003_lengths),
        cmocka_unit_test(test_link_003_reserved_bits),
        cmocka_unit_test(test_link_003_target_range),
        cmocka_unit_test(test_link_003_id_and_order),
        cmocka_unit_test(test_link_005_status_payload),
        cmocka_unit_test(test_link_005_saturation),
        cmocka_unit_test(test_link_006_cfg_and_init),
        cmocka_unit_test(test_link_006_is_valid),
        cmocka_unit_test(test_link_007_malformed_no_effect),
        cmocka_unit_test(test_link_007_effective_command),
        cmocka_unit_test(test_link_008_timeout_exact),
        cmocka_unit_test(test_link_008_not_lost_before_first_frame),
        cmocka_unit_test(test_link_009_counters_saturate),
        cmocka_unit_test(test_link_010_can_alternation),
        cmocka_unit_test(test_link_011_accept),
        cmocka_unit_test(test_req_ident_007_link_request),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
