/*
 * fuzz_link_service.c -- libFuzzer harness of the command link (REQ-FUZZ-002).
 *
 * Input: a configuration (10 bytes: used as they are when the first bit of the mode byte
 * is set, else folded into a valid one), then operations until the input ends, each a
 * code byte and its operands: a service call with a raw buffer (length 0 .. 255 and its
 * bytes), with a well-formed command frame (built here, fields from the input), with a
 * well-formed frame with one byte changed, with no frame, a run of service calls without
 * a frame (1 .. 256, to reach the timeout), qfoc_link_accept() with any command,
 * qfoc_link_command(), qfoc_link_lost(), qfoc_can_status() with any status; at most 4096
 * calls per input.
 *
 * Guarantees asserted after every call (include/qfoc/link.h; REQ-LINK-006 .. REQ-LINK-011):
 * the link stays valid (qfoc_link_is_valid); the whole link object equals a model that
 * applies the documented rules to the object before the call and is compared byte for
 * byte: init stores a valid configuration or the safe one (id_cmd 0, id_status 1,
 * rpm_max 1, timeout 1 ms, CAN 0x7FF) and is then lost for good; a frame the decoding order
 * accepts becomes the command, restarts the silent time, counts in n_ok and is answered;
 * no frame or a rejected frame changes nothing but its cause's counter and the silent
 * time (saturating), and lost = !cfg_ok || (seen && silent > timeout); accept takes a
 * target <= rpm_max like a frame and otherwise counts n_range only; the effective command
 * is off while lost or before the first command; the CAN frame alternates its identifier
 * and carries the status payload of specs/link-frames.md.
 *
 * Requirements: REQ-FUZZ-002.
 */
#include "fuzz.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static void model_rx(qfoc_link_t *m, int32_t st, size_t len, const qfoc_cmd_t *c)
{
    if (len > 0u && st == QFOC_LINK_OK) {
        fz_cmd_set(&m->cmd, c);
        m->seen = true;
        m->silent_ms = 0u;
        m->lost = !m->cfg_ok;
        m->n_ok = fz_sat_inc(m->n_ok);
        return;
    }
    if (len > 0u) {
        uint16_t *const cnt[6] = { &m->n_len, &m->n_sync, &m->n_id, &m->n_checksum,
                                   &m->n_reserved, &m->n_range };
        *cnt[-st - 1] = fz_sat_inc(*cnt[-st - 1]);
    }
    m->silent_ms = fz_sat_inc(m->silent_ms);
    m->lost = !m->cfg_ok || (m->seen && m->silent_ms > m->cfg.timeout_ms);
}

/* service calls an input may make */
#define MAX_CALLS 4096

static int calls;

static void service(qfoc_link_t *l, qfoc_link_t *m, const uint8_t *rx, size_t len)
{
    qfoc_cmd_t c;
    int32_t st = 1;
    bool got;
    memset(&c, 0, sizeof c);
    if (len > 0u) {
        st = fz_ref_decode(l->cfg.id_cmd, l->cfg.rpm_max, rx, len, &c);
    }
    calls++;
    got = qfoc_link_service(l, (len > 0u) ? rx : NULL, (uint8_t)len);
    model_rx(m, st, len, &c);
    FZ_CHECK(got == (st == QFOC_LINK_OK), "service: true exactly for an accepted frame");
    FZ_CHECK(memcmp(l, m, sizeof *l) == 0, "service: the link follows the documented rules");
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static qfoc_link_t l;
    static qfoc_link_t m;
    fz_in_t in = { data, size };
    qfoc_link_cfg_t cfg;
    uint8_t mode = fz_u8(&in);
    bool cfg_valid;

    cfg.id_cmd = fz_u8(&in);
    cfg.id_status = fz_u8(&in);
    cfg.rpm_max = fz_u16(&in);
    cfg.timeout_ms = fz_u16(&in);
    cfg.can_id_a = fz_u16(&in);
    cfg.can_id_b = fz_u16(&in);
    if ((mode & 1u) == 0u) {
        cfg.id_cmd = (uint8_t)(cfg.id_cmd % 0x3Cu);
        cfg.id_status = (uint8_t)((cfg.id_cmd + 1u + (cfg.id_status % 0x3Bu)) % 0x3Cu);
        cfg.rpm_max = (cfg.rpm_max == 0u) ? 1u : cfg.rpm_max;
        cfg.timeout_ms = (uint16_t)(1u + (cfg.timeout_ms % 300u));
        cfg.can_id_a &= 0x7FFu;
        cfg.can_id_b &= 0x7FFu;
    }
    cfg_valid = cfg.id_cmd <= 0x3Bu && cfg.id_status <= 0x3Bu && cfg.id_cmd != cfg.id_status &&
                cfg.rpm_max >= 1u && cfg.timeout_ms >= 1u && cfg.timeout_ms <= 60000u &&
                cfg.can_id_a <= 0x7FFu && cfg.can_id_b <= 0x7FFu;

    /* init on a link full of garbage */
    memset(&l, mode, sizeof l);
    FZ_CHECK(qfoc_link_cfg_is_valid(&cfg) == cfg_valid, "cfg_is_valid: the documented ranges");
    FZ_CHECK(qfoc_link_init(&l, &cfg) == (cfg_valid ? QFOC_LINK_OK : QFOC_LINK_ERR_CFG),
             "init: OK exactly for a valid configuration");
    memcpy(&m, &l, sizeof m);   /* padding bytes as the library left them */
    if (cfg_valid) {
        m.cfg = cfg;
    } else {
        m.cfg.id_cmd = 0x00u;
        m.cfg.id_status = 0x01u;
        m.cfg.rpm_max = 1u;
        m.cfg.timeout_ms = 1u;
        m.cfg.can_id_a = 0x7FFu;
        m.cfg.can_id_b = 0x7FFu;
    }
    m.cmd.power_on = false;       /* field by field: the padding byte as the library left it */
    m.cmd.fault_clear = false;
    m.cmd.target_rpm = 0u;
    m.cmd.identify = false;
    m.silent_ms = 0u;
    m.cfg_ok = cfg_valid;
    m.seen = false;
    m.lost = !cfg_valid;
    m.can_b = false;
    m.n_ok = m.n_len = m.n_sync = m.n_id = m.n_checksum = m.n_reserved = m.n_range = 0u;
    FZ_CHECK(memcmp(&l, &m, sizeof l) == 0, "init: the configuration (or the safe one), all cleared");
    FZ_CHECK(qfoc_link_is_valid(&l), "init: the link is valid");

    calls = 0;
    while (in.n > 0u && calls < MAX_CALLS) {
        const uint8_t op = fz_u8(&in);
        calls++;
        switch (op % 9u) {
        case 0u: { /* raw buffer */
            size_t len = fz_u8(&in);
            uint8_t *buf;
            if (len > in.n) {
                len = in.n;
            }
            buf = (uint8_t *)malloc((len > 0u) ? len : 1u);
            if (buf == NULL) {
                return 0;
            }
            if (len > 0u) {
                memcpy(buf, in.p, len);
            }
            in.p += len;
            in.n -= len;
            service(&l, &m, buf, len);
            free(buf);
            break;
        }
        case 1u:   /* well-formed frame */
        case 2u: { /* well-formed frame, one byte changed */
            uint8_t f[7];
            const uint8_t bits = fz_u8(&in);
            uint16_t rpm = fz_u16(&in);
            if ((bits & 4u) == 0u) {
                rpm = (uint16_t)(rpm % ((uint32_t)l.cfg.rpm_max + 1u));
            }
            (void)fz_frame(f, l.cfg.id_cmd, (bits & 1u) != 0u, (bits & 2u) != 0u, rpm);
            if (op % 9u == 2u) {
                const uint8_t at = fz_u8(&in);
                f[at % 7u] = (uint8_t)(f[at % 7u] ^ fz_u8(&in));
            }
            service(&l, &m, f, 7u);
            break;
        }
        case 3u: /* no frame */
            service(&l, &m, NULL, 0u);
            break;
        case 4u: { /* a run of silent milliseconds */
            const int n = 1 + (int)fz_u8(&in);
            int k;
            for (k = 0; k < n; k++) {
                service(&l, &m, NULL, 0u);
            }
            break;
        }
        case 5u: { /* accept */
            qfoc_cmd_t c;
            const uint8_t bits = fz_u8(&in);
            int32_t r;
            c.power_on = (bits & 1u) != 0u;
            c.fault_clear = (bits & 2u) != 0u;
            c.identify = (bits & 8u) != 0u;
            c.target_rpm = fz_u16(&in);
            if ((bits & 4u) == 0u) {
                c.target_rpm = (uint16_t)(c.target_rpm % ((uint32_t)l.cfg.rpm_max + 1u));
            }
            r = qfoc_link_accept(&l, &c);
            if (c.target_rpm <= m.cfg.rpm_max) {
                FZ_CHECK(r == QFOC_LINK_OK, "accept: a target <= rpm_max is taken");
                fz_cmd_set(&m.cmd, &c);
                m.seen = true;
                m.silent_ms = 0u;
                m.lost = !m.cfg_ok;
                m.n_ok = fz_sat_inc(m.n_ok);
            } else {
                FZ_CHECK(r == QFOC_LINK_ERR_RANGE, "accept: a target > rpm_max is refused");
                m.n_range = fz_sat_inc(m.n_range);
            }
            FZ_CHECK(memcmp(&l, &m, sizeof l) == 0, "accept: the link follows the documented rules");
            break;
        }
        case 6u: { /* effective command */
            qfoc_cmd_t c;
            memset(&c, 0xFF, sizeof c);
            qfoc_link_command(&l, &c);
            FZ_CHECK(c.target_rpm == l.cmd.target_rpm, "command: the last valid target");
            if (l.seen && !l.lost) {
                FZ_CHECK(c.power_on == l.cmd.power_on && c.fault_clear == l.cmd.fault_clear &&
                         c.identify == l.cmd.identify,
                         "command: the last valid command while the link is alive");
            } else {
                FZ_CHECK(!c.power_on && !c.fault_clear && !c.identify,
                         "command: off while lost or unseen");
            }
            FZ_CHECK(memcmp(&l, &m, sizeof l) == 0, "command: the link is not changed");
            break;
        }
        case 7u: /* lost */
            FZ_CHECK(qfoc_link_lost(&l) == m.lost, "lost: the lost flag");
            FZ_CHECK(memcmp(&l, &m, sizeof l) == 0, "lost: the link is not changed");
            break;
        default: { /* CAN status frame */
            qfoc_status_t st;
            qfoc_can_frame_t f;
            uint8_t pl[8];
            st.state = fz_u8(&in);
            st.substate = fz_u8(&in);
            st.faults = fz_u16(&in);
            st.speed_rpm = fz_u16(&in);
            st.vdc_dv = fz_u16(&in);
            st.current_ca = fz_u16(&in);
            st.temp_dc = fz_i16(&in);
            memset(&f, 0xEE, sizeof f);
            qfoc_can_status(&l, &st, &f);
            fz_payload(&st, pl);
            FZ_CHECK(f.id == (m.can_b ? m.cfg.can_id_b : m.cfg.can_id_a),
                     "CAN: can_id_a and can_id_b in turn");
            FZ_CHECK(f.dlc == 8u && memcmp(f.data, pl, 8u) == 0, "CAN: DLC 8, the status payload");
            m.can_b = !m.can_b;
            FZ_CHECK(memcmp(&l, &m, sizeof l) == 0, "CAN: only the identifier toggle changes");
            break;
        }
        }
        FZ_CHECK(qfoc_link_is_valid(&l), "the link stays valid");
    }
    return 0;
}
