/*
 * fuzz_link_decode.c -- libFuzzer harness of the command-frame decoder (REQ-FUZZ-001).
 *
 * Input: id_cmd (1 byte, any value), rpm_max (2 bytes, any value), then the received
 * buffer: every remaining byte, up to 255 (its length is the frame length, 0 .. 255).  The
 * buffer is handed over in an allocation of exactly its length, so a read beyond it is an
 * AddressSanitizer report.
 *
 * Guarantees asserted after every call (include/qfoc/link.h, specs/link-frames.md;
 * REQ-LINK-001 .. REQ-LINK-004): qfoc_lin_decode_cmd() returns the status of the first
 * failed check of the decoding order (length, sync, PID, checksum, reserved bits, range),
 * computed again by tests/fuzz/fuzz.h; on OK the command holds the frame's fields and its
 * target is <= rpm_max; on a rejection the command is untouched (compared byte for byte);
 * qfoc_lin_pid() and qfoc_lin_checksum() equal the LIN 2.x definitions for the id and the
 * buffer; qfoc_lin_encode_status() writes 11 bytes, a frame that is the status payload of
 * specs/link-frames.md with its PID and checksum, for a status taken from the same bytes.
 *
 * Requirements: REQ-FUZZ-001.
 */
#include "fuzz.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fz_in_t in = { data, size };
    qfoc_link_cfg_t cfg;
    qfoc_cmd_t cmd;
    qfoc_cmd_t canary;
    qfoc_cmd_t ref_cmd;
    qfoc_status_t st;
    uint8_t frame[QFOC_LIN_FRAME_MAX + 1u];
    uint8_t *buf;
    size_t len;
    int32_t status;
    int32_t ref;

    memset(&cfg, 0, sizeof cfg);
    cfg.id_cmd = fz_u8(&in);
    cfg.rpm_max = fz_u16(&in);
    cfg.id_status = (uint8_t)(cfg.id_cmd ^ 0x01u);
    len = (in.n > 255u) ? 255u : in.n;
    buf = (uint8_t *)malloc((len > 0u) ? len : 1u);
    if (buf == NULL) {
        return 0;
    }
    if (len > 0u) {
        memcpy(buf, in.p, len);
    }

    /* the decoder against the decoding order */
    memset(&canary, 0xA5, sizeof canary);
    canary.power_on = true;
    canary.fault_clear = false;
    canary.identify = true;
    memcpy(&cmd, &canary, sizeof cmd);
    memset(&ref_cmd, 0, sizeof ref_cmd);
    status = qfoc_lin_decode_cmd(&cfg, buf, (uint8_t)len, &cmd);
    ref = fz_ref_decode(cfg.id_cmd, cfg.rpm_max, buf, len, &ref_cmd);
    FZ_CHECK(status == ref, "decode: the status of the first failed check");
    if (status == QFOC_LINK_OK) {
        FZ_CHECK(cmd.power_on == ref_cmd.power_on && cmd.fault_clear == ref_cmd.fault_clear &&
                 cmd.target_rpm == ref_cmd.target_rpm && !cmd.identify,
                 "decode: the frame's fields, never the identification request");
        FZ_CHECK(cmd.target_rpm <= cfg.rpm_max, "decode: target <= rpm_max");
    } else {
        FZ_CHECK(memcmp(&cmd, &canary, sizeof cmd) == 0, "decode: a rejected frame leaves cmd");
    }

    /* identifier and checksum against LIN 2.x */
    FZ_CHECK(qfoc_lin_pid(cfg.id_cmd) == fz_pid(cfg.id_cmd), "pid: LIN 2.x parity");
    FZ_CHECK(qfoc_lin_checksum(cfg.id_cmd, buf, (uint8_t)len) ==
             fz_checksum(cfg.id_cmd, buf, len), "checksum: LIN 2.x enhanced checksum");

    /* the status frame of a status made of the first bytes */
    {
        fz_in_t s = { buf, len };
        uint8_t n;
        st.state = fz_u8(&s);
        st.substate = fz_u8(&s);
        st.faults = fz_u16(&s);
        st.speed_rpm = fz_u16(&s);
        st.vdc_dv = fz_u16(&s);
        st.current_ca = fz_u16(&s);
        st.temp_dc = fz_i16(&s);
        frame[QFOC_LIN_FRAME_MAX] = 0x5Au;
        n = qfoc_lin_encode_status(&cfg, &st, frame);
        FZ_CHECK(n == QFOC_LIN_STATUS_LEN, "encode: 11 bytes");
        FZ_CHECK(frame[QFOC_LIN_FRAME_MAX] == 0x5Au, "encode: nothing beyond 11 bytes");
        fz_check_status_frame(frame, cfg.id_status, &st);
    }
    free(buf);
    return 0;
}
