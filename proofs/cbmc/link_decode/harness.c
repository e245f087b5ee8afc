/*
 * CBMC harness: qfoc_lin_decode_cmd() on every byte sequence of every length
 * 0 .. QFOC_LIN_FRAME_MAX + 1 and every configuration (REQ-LINK-001,
 * REQ-LINK-002, REQ-LINK-003, REQ-LINK-004).
 *
 * The buffer is a heap object of exactly len bytes, so --bounds-check and
 * --pointer-check prove that the decoder reads nothing beyond len.  The
 * configuration and the output command are fully nondet.  Checked:
 *  - no undefined behaviour (all checks of the command line);
 *  - the status equals the first failed check of the decoding order
 *    (specs/link-frames.md section 4), recomputed here independently: the
 *    protected identifier by shifts and XOR of the identifier bits, the
 *    enhanced checksum as a 32-bit sum with the carries folded at the end;
 *  - OK iff the frame is well-formed;
 *  - on OK the command fields equal the frame's bits and little-endian target;
 *  - on any rejection the output command is untouched;
 *  - qfoc_lin_checksum() for every PID, every length 0..8 and every content,
 *    against the end-around-carry definition written with mask and shift.
 * (A miter of the per-byte sum against a sum folded once at the end does not
 * finish within the time budget for 9 addends; it is done here for the 5 addends
 * of the command frame, and for 9 addends by tests/test_link.c over random data.)
 *
 * Methods: 1b every byte sequence and every configuration; 1c every length 0 ..
 * QFOC_LIN_FRAME_MAX + 1 in a buffer of exactly that size, checksums of every length 0
 * .. 8; 1d malformed frames of every cause, checked in the decoding order
 */
#include <stdint.h>
#include <stdbool.h>
#include <stdlib.h>
#include "qfoc/link.h"
#include "../harness_util.h"

/* LIN 2.x PID by shifts and XOR (P0 = id0^id1^id2^id4, P1 = !(id1^id3^id4^id5)) */
static uint8_t h_pid(uint8_t id)
{
    const uint32_t i = (uint32_t)id & 0x3Fu;
    const uint32_t p0 = ((i >> 0) ^ (i >> 1) ^ (i >> 2) ^ (i >> 4)) & 1u;
    const uint32_t p1 = (((i >> 1) ^ (i >> 3) ^ (i >> 4) ^ (i >> 5)) & 1u) ^ 1u;
    return (uint8_t)(i | (p0 << 6) | (p1 << 7));
}

/* enhanced checksum over the 5 bytes PID, data 0..3: plain sum, carries folded */
static uint8_t h_checksum5(const uint8_t *b)
{
    uint32_t s = (uint32_t)b[0] + b[1] + b[2] + b[3] + b[4];  /* <= 1275 */
    s = (s & 0xFFu) + (s >> 8);                               /* <= 259 */
    s = (s & 0xFFu) + (s >> 8);                               /* <= 255 */
    return (uint8_t)(~s & 0xFFu);
}

static int32_t h_status(const qfoc_link_cfg_t *c, const uint8_t *b, uint8_t len)
{
    int32_t st;
    if (len != 7u) {
        st = QFOC_LINK_ERR_LEN;
    } else if (b[0] != 0x55u) {
        st = QFOC_LINK_ERR_SYNC;
    } else if (b[1] != h_pid(c->id_cmd)) {
        st = QFOC_LINK_ERR_ID;
    } else if (b[6] != h_checksum5(&b[1])) {
        st = QFOC_LINK_ERR_CHECKSUM;
    } else if (((b[2] & 0xFCu) != 0u) || (b[5] != 0u)) {
        st = QFOC_LINK_ERR_RESERVED;
    } else if ((((uint32_t)b[4] << 8) | b[3]) > c->rpm_max) {
        st = QFOC_LINK_ERR_RANGE;
    } else {
        st = QFOC_LINK_OK;
    }
    return st;
}

int main(void)
{
    qfoc_link_cfg_t c;
    qfoc_cmd_t cmd;
    qfoc_cmd_t old;
    const uint8_t len = nondet_uint8();
    uint8_t *buf;
    uint32_t k;
    int32_t st;
    int32_t expect;

    __CPROVER_assume(len <= (QFOC_LIN_FRAME_MAX + 1u));
    buf = malloc(len);
    __CPROVER_assume(buf != NULL);
    for (k = 0u; k < len; k++) {
        buf[k] = nondet_uint8();
    }
    c.id_cmd = nondet_uint8();
    c.id_status = nondet_uint8();
    c.rpm_max = nondet_uint16();
    c.timeout_ms = nondet_uint16();
    c.can_id_a = nondet_uint16();
    c.can_id_b = nondet_uint16();
    cmd.power_on = nondet_bool();
    cmd.fault_clear = nondet_bool();
    cmd.target_rpm = nondet_uint16();
    cmd.identify = nondet_bool();
    old = cmd;

    expect = h_status(&c, buf, len);
    st = qfoc_lin_decode_cmd(&c, buf, len, &cmd);

    __CPROVER_assert(st == expect, "status = first failed check of the decoding order");
    __CPROVER_assert((st == QFOC_LINK_OK) == (expect == QFOC_LINK_OK),
                     "OK iff the frame is well-formed");
    if (st == QFOC_LINK_OK) {
        __CPROVER_assert(cmd.power_on == ((buf[2] & 1u) != 0u), "power_on = data 0 bit 0");
        __CPROVER_assert(cmd.fault_clear == ((buf[2] & 2u) != 0u), "fault_clear = data 0 bit 1");
        __CPROVER_assert(cmd.target_rpm == (uint16_t)(((uint32_t)buf[4] << 8) | buf[3]),
                         "target = data 1..2 little-endian");
        __CPROVER_assert(cmd.target_rpm <= c.rpm_max, "target within rpm_max");
        __CPROVER_assert(!cmd.identify, "no frame requests the identification");
    } else {
        __CPROVER_assert((cmd.power_on == old.power_on) && (cmd.fault_clear == old.fault_clear)
                         && (cmd.target_rpm == old.target_rpm) && (cmd.identify == old.identify),
                         "rejected: cmd untouched");
        __CPROVER_assert(st < 0, "rejected: negative status");
    }
    free(buf);

    /* the checksum helper for every PID, length 0..8 and content (REQ-LINK-002),
       against the definition written with mask and shift: after each byte the
       carry out of bit 7 is added back into bit 0 */
    {
        uint8_t d[8];
        const uint8_t pid = nondet_uint8();
        const uint8_t n = nondet_uint8();
        uint32_t s = pid;
        __CPROVER_assume(n <= 8u);
        for (k = 0u; k < 8u; k++) {
            d[k] = nondet_uint8();
            if (k < n) {
                s += d[k];
                s = (s & 0xFFu) + (s >> 8);
            }
        }
        __CPROVER_assert(qfoc_lin_checksum(pid, d, n) == (uint8_t)(~s & 0xFFu),
                         "checksum = inverted end-around-carry sum");
    }
    return 0;
}
