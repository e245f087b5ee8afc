/*
 * CBMC harness: five consecutive 1 ms link services with nondet frames and
 * lengths, plus the CAN status frame every step (REQ-LINK-006, REQ-LINK-007,
 * REQ-LINK-008, REQ-LINK-009, REQ-LINK-010, REQ-LINK-005).
 *
 * The link starts either from qfoc_link_init() of a nondet configuration or from
 * any state accepted by qfoc_link_is_valid() (counters and silent time anywhere,
 * saturated included), with a timeout of 1..3 ms to keep the state space small.
 * Each step gets a heap buffer of exactly len bytes, len 0..QFOC_LIN_FRAME_MAX+1,
 * nondet content.  Checked at each step:
 *  - no undefined behaviour; the link stays valid;
 *  - the return value is true iff a well-formed frame (harness-side check) came;
 *  - the counter of the frame's cause (or n_ok) is incremented saturating, every
 *    other counter unchanged, no counter wraps; no frame counts nothing;
 *  - a reference model (stored command, seen, silent time) predicts the lost flag
 *    exactly: lost == !cfg_ok || (seen && silent > timeout_ms), with silent the
 *    number of consecutive calls without a valid command (saturating);
 *  - the effective command equals the model's: last valid command, power_on and
 *    fault_clear false while lost or before the first valid command;
 *  - a twin link that gets no frame whenever the frame is malformed has the same
 *    effective command and lost flag (a malformed frame acts like no frame);
 *  - the CAN identifier alternates a, b, a, ... and the DLC is 8.
 *
 * Methods: 1b five services from a fresh or any valid link with any frames and lengths,
 * well-formed and malformed; 1c counters and the silent time saturated, lengths 0 ..
 * QFOC_LIN_FRAME_MAX + 1, timeouts 1 .. 3 ms; 1d malformed frames and silence (a
 * malformed frame must act like no frame)
 */
#include <stdint.h>
#include <stdbool.h>
#include <stdlib.h>
#include "qfoc/link.h"
#include "../harness_util.h"

#define STEPS 5u

static uint8_t h_pid(uint8_t id)
{
    const uint32_t i = (uint32_t)id & 0x3Fu;
    const uint32_t p0 = ((i >> 0) ^ (i >> 1) ^ (i >> 2) ^ (i >> 4)) & 1u;
    const uint32_t p1 = (((i >> 1) ^ (i >> 3) ^ (i >> 4) ^ (i >> 5)) & 1u) ^ 1u;
    return (uint8_t)(i | (p0 << 6) | (p1 << 7));
}

static uint8_t h_checksum5(const uint8_t *b)
{
    uint32_t s = (uint32_t)b[0] + b[1] + b[2] + b[3] + b[4];
    s = (s & 0xFFu) + (s >> 8);
    s = (s & 0xFFu) + (s >> 8);
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

static uint16_t h_inc(uint16_t v, bool cond)
{
    return (cond && (v < 65535u)) ? (uint16_t)(v + 1u) : v;
}

int main(void)
{
    qfoc_link_t a;
    qfoc_link_t b;
    qfoc_status_t st;
    uint32_t step;
    /* reference model */
    bool m_seen;
    uint32_t m_silent;
    qfoc_cmd_t m_cmd;
    bool m_can_b;

    if (nondet_bool()) {
        qfoc_link_cfg_t c;
        c.id_cmd = nondet_uint8();
        c.id_status = nondet_uint8();
        c.rpm_max = nondet_uint16();
        c.timeout_ms = nondet_uint16();
        c.can_id_a = nondet_uint16();
        c.can_id_b = nondet_uint16();
        (void)qfoc_link_init(&a, &c);
    } else {
        __CPROVER_havoc_object(&a);
    }
    __CPROVER_assume(qfoc_link_is_valid(&a));
    __CPROVER_assume((a.cfg.timeout_ms >= 1u) && (a.cfg.timeout_ms <= 3u));
    b = a;
    m_seen = a.seen;
    m_silent = a.silent_ms;
    m_cmd = a.cmd;
    m_can_b = a.can_b;
    __CPROVER_havoc_object(&st);

    for (step = 0u; step < STEPS; step++) {
        const uint8_t len = nondet_uint8();
        uint8_t *buf;
        uint32_t k;
        int32_t cause;
        bool ok;
        bool r;
        qfoc_link_t old;
        qfoc_cmd_t ea;
        qfoc_cmd_t eb;
        qfoc_can_frame_t f;

        __CPROVER_assume(len <= (QFOC_LIN_FRAME_MAX + 1u));
        buf = malloc(len);
        __CPROVER_assume(buf != NULL);
        for (k = 0u; k < len; k++) {
            buf[k] = nondet_uint8();
        }
        cause = h_status(&a.cfg, buf, len);
        ok = (len > 0u) && (cause == QFOC_LINK_OK);
        old = a;

        r = qfoc_link_service(&a, buf, len);
        (void)qfoc_link_service(&b, ok ? buf : NULL, ok ? len : 0u);

        __CPROVER_assert(qfoc_link_is_valid(&a), "still valid");
        __CPROVER_assert(r == ok, "accepted iff well-formed");
        /* counters: exactly the cause's counter, saturating, never wrapping */
        __CPROVER_assert(a.n_ok == h_inc(old.n_ok, ok), "n_ok");
        __CPROVER_assert(a.n_len == h_inc(old.n_len, (len > 0u) && (cause == QFOC_LINK_ERR_LEN)),
                         "n_len");
        __CPROVER_assert(a.n_sync == h_inc(old.n_sync, (len > 0u) && (cause == QFOC_LINK_ERR_SYNC)),
                         "n_sync");
        __CPROVER_assert(a.n_id == h_inc(old.n_id, (len > 0u) && (cause == QFOC_LINK_ERR_ID)),
                         "n_id");
        __CPROVER_assert(a.n_checksum == h_inc(old.n_checksum,
                                               (len > 0u) && (cause == QFOC_LINK_ERR_CHECKSUM)),
                         "n_checksum");
        __CPROVER_assert(a.n_reserved == h_inc(old.n_reserved,
                                               (len > 0u) && (cause == QFOC_LINK_ERR_RESERVED)),
                         "n_reserved");
        __CPROVER_assert(a.n_range == h_inc(old.n_range, (len > 0u) && (cause == QFOC_LINK_ERR_RANGE)),
                         "n_range");
        __CPROVER_assert((a.n_ok >= old.n_ok) && (a.n_len >= old.n_len) && (a.n_sync >= old.n_sync)
                         && (a.n_id >= old.n_id) && (a.n_checksum >= old.n_checksum)
                         && (a.n_reserved >= old.n_reserved) && (a.n_range >= old.n_range),
                         "no counter wraps");

        /* reference model of the timer and the stored command */
        if (ok) {
            m_seen = true;
            m_silent = 0u;
            m_cmd.power_on = (buf[2] & 1u) != 0u;
            m_cmd.fault_clear = (buf[2] & 2u) != 0u;
            m_cmd.target_rpm = (uint16_t)(((uint32_t)buf[4] << 8) | buf[3]);
            m_cmd.identify = false;
        } else {
            m_silent = (m_silent < 65535u) ? (m_silent + 1u) : 65535u;
        }
        __CPROVER_assert(a.silent_ms == m_silent, "silent time = calls since the last valid command");
        __CPROVER_assert(qfoc_link_lost(&a)
                         == ((!a.cfg_ok) || (m_seen && (m_silent > a.cfg.timeout_ms))),
                         "lost exactly per the timeout rule");
        qfoc_link_command(&a, &ea);
        qfoc_link_command(&b, &eb);
        __CPROVER_assert(ea.target_rpm == m_cmd.target_rpm, "target = last valid target");
        if (m_seen && !qfoc_link_lost(&a)) {
            __CPROVER_assert((ea.power_on == m_cmd.power_on) && (ea.fault_clear == m_cmd.fault_clear)
                             && (ea.identify == m_cmd.identify),
                             "active: flags of the last valid command");
        } else {
            __CPROVER_assert(!ea.power_on && !ea.fault_clear && !ea.identify,
                             "lost or none yet: drive off");
        }
        __CPROVER_assert((ea.power_on == eb.power_on) && (ea.fault_clear == eb.fault_clear)
                         && (ea.identify == eb.identify)
                         && (ea.target_rpm == eb.target_rpm)
                         && (qfoc_link_lost(&a) == qfoc_link_lost(&b)),
                         "a malformed frame acts like no frame");

        /* CAN status frame */
        qfoc_can_status(&a, &st, &f);
        __CPROVER_assert(f.id == (m_can_b ? a.cfg.can_id_b : a.cfg.can_id_a), "CAN id alternates");
        __CPROVER_assert(f.dlc == 8u, "CAN dlc 8");
        m_can_b = !m_can_b;
        free(buf);
    }
    return 0;
}
