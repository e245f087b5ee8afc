/**
 * @file fuzz.h
 * @brief What the libFuzzer harnesses of tests/fuzz/ share: reading the fuzzer's bytes,
 *        the failure report, a LIN reference written apart from the library, and the
 *        drive's entry points wrapped with the guarantees drive.h documents for them.
 *
 * Each harness tests/fuzz/fuzz_<target>.c defines LLVMFuzzerTestOneInput(); it is built by
 * mk/fuzz.mk with clang, -fsanitize=fuzzer,address,undefined (and the integer checks that
 * mk/fuzz.mk lists), the library sources compiled with the same instrumentation.  A broken
 * guarantee is reported by fz_fail() (the guarantee, the file and line) and ends the run
 * with abort(): libFuzzer stores the input as a crash artefact, so a broken guarantee is a
 * finding exactly like a sanitizer report.
 *
 * Requirements (specs/requirements/fuzz.md), one harness each:
 *   REQ-FUZZ-001 the command-frame decoder (fuzz_link_decode.c),
 *   REQ-FUZZ-002 the link service (fuzz_link_service.c),
 *   REQ-FUZZ-003 the drive's tick on arbitrary inputs (fuzz_drive_tick.c),
 *   REQ-FUZZ-004 the fast step on arbitrary ADC sequences in RUN (fuzz_drive_fast_step.c),
 *   REQ-FUZZ-005 the command API and the status readers (fuzz_drive_command.c),
 *   REQ-FUZZ-006 the parameter-table check on arbitrary tables (fuzz_params_check.c),
 *   REQ-FUZZ-007 the campaign: make fuzz (executions, findings) and make fuzz-check.
 */
#ifndef QFOC_TESTS_FUZZ_H
#define QFOC_TESTS_FUZZ_H

#include <stddef.h>
#include <stdint.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "qfoc/drive.h"

/* ------------------------------------------------------------------ failure */

/* A broken guarantee: report it and abort (libFuzzer keeps the input as crash-<sha1>). */
static inline void fz_fail(const char *what, const char *file, int line)
{
    fprintf(stderr, "qfoc-fuzz: guarantee broken: %s (%s:%d)\n", what, file, line);
    fflush(stderr);
    abort();
}

#define FZ_CHECK(cond, what) \
    do { \
        if (!(cond)) { \
            fz_fail((what), __FILE__, __LINE__); \
        } \
    } while (0)

/* ------------------------------------------------------------------ input */

/* The fuzzer's bytes, read front to back; an exhausted input reads as zeros. */
typedef struct {
    const uint8_t *p;
    size_t n;
} fz_in_t;

static inline uint8_t fz_u8(fz_in_t *in)
{
    uint8_t b = 0u;
    if (in->n > 0u) {
        b = *in->p;
        in->p++;
        in->n--;
    }
    return b;
}

static inline uint16_t fz_u16(fz_in_t *in)
{
    const uint16_t lo = fz_u8(in);
    const uint16_t hi = fz_u8(in);
    return (uint16_t)(lo | (uint16_t)(hi << 8));
}

static inline int16_t fz_i16(fz_in_t *in)
{
    return (int16_t)fz_u16(in);
}

/* a bool from one byte (its bit 0), never an invalid bool representation */
static inline bool fz_bool(fz_in_t *in)
{
    return (fz_u8(in) & 1u) != 0u;
}

static inline uint16_t fz_sat_inc(uint16_t x)
{
    return (x < 65535u) ? (uint16_t)(x + 1u) : x;
}

/* ------------------------------------------------------------------ LIN reference */

/* The LIN 2.x protected identifier and enhanced checksum and the command-frame decoding
   order of specs/link-frames.md, written again here so that the library is checked
   against the document rather than against itself. */
static inline uint8_t fz_pid(uint8_t id)
{
    const unsigned b0 = id & 1u, b1 = (id >> 1) & 1u, b2 = (id >> 2) & 1u;
    const unsigned b3 = (id >> 3) & 1u, b4 = (id >> 4) & 1u, b5 = (id >> 5) & 1u;
    const unsigned p0 = b0 ^ b1 ^ b2 ^ b4;
    const unsigned p1 = 1u ^ (b1 ^ b3 ^ b4 ^ b5);
    return (uint8_t)((id & 0x3Fu) | (p0 << 6) | (p1 << 7));
}

static inline uint8_t fz_checksum(uint8_t pid, const uint8_t *data, size_t n)
{
    unsigned s = pid;
    size_t k;
    for (k = 0u; k < n; k++) {
        s += data[k];
        if (s > 255u) {
            s -= 255u;
        }
    }
    return (uint8_t)(255u - s);
}

/* status of the decoding order (0, -1 .. -6), cmd filled on 0 */
static inline int32_t fz_ref_decode(uint8_t id_cmd, uint16_t rpm_max, const uint8_t *buf,
                                    size_t len, qfoc_cmd_t *cmd)
{
    uint32_t target;
    if (len != 7u) {
        return QFOC_LINK_ERR_LEN;
    }
    if (buf[0] != 0x55u) {
        return QFOC_LINK_ERR_SYNC;
    }
    if (buf[1] != fz_pid(id_cmd)) {
        return QFOC_LINK_ERR_ID;
    }
    if (buf[6] != fz_checksum(buf[1], &buf[2], 4u)) {
        return QFOC_LINK_ERR_CHECKSUM;
    }
    if (((buf[2] & 0xFCu) != 0u) || (buf[5] != 0u)) {
        return QFOC_LINK_ERR_RESERVED;
    }
    target = (uint32_t)buf[3] | ((uint32_t)buf[4] << 8);
    if (target > rpm_max) {
        return QFOC_LINK_ERR_RANGE;
    }
    cmd->power_on = (buf[2] & 1u) != 0u;
    cmd->fault_clear = (buf[2] & 2u) != 0u;
    cmd->target_rpm = (uint16_t)target;
    cmd->identify = false;   /* no frame carries the identification request */
    return QFOC_LINK_OK;
}

/* a command copied field by field (the padding byte of the destination kept, so a
   model compared with memcmp differs only where the code under test differs) */
static inline void fz_cmd_set(qfoc_cmd_t *dst, const qfoc_cmd_t *src)
{
    dst->power_on = src->power_on;
    dst->fault_clear = src->fault_clear;
    dst->target_rpm = src->target_rpm;
    dst->identify = src->identify;
}

/* a well-formed command frame (7 bytes) */
static inline uint8_t fz_frame(uint8_t *f, uint8_t id_cmd, bool power_on, bool fault_clear,
                               uint16_t rpm)
{
    f[0] = 0x55u;
    f[1] = fz_pid(id_cmd);
    f[2] = (uint8_t)((power_on ? 1u : 0u) | (fault_clear ? 2u : 0u));
    f[3] = (uint8_t)(rpm & 0xFFu);
    f[4] = (uint8_t)(rpm >> 8);
    f[5] = 0u;
    f[6] = fz_checksum(f[1], &f[2], 4u);
    return 7u;
}

/* the 8-byte status payload of specs/link-frames.md section 5 */
static inline void fz_payload(const qfoc_status_t *st, uint8_t *p)
{
    const unsigned state = (st->state > 15u) ? 15u : st->state;
    const unsigned sub = (st->substate > 15u) ? 15u : st->substate;
    unsigned v = ((unsigned)st->vdc_dv + 20u) / 40u;
    unsigned c = ((unsigned)st->current_ca + 12u) / 25u;
    int t = (st->temp_dc >= -405) ? ((int)st->temp_dc + 405) / 10 : 0;
    p[0] = (uint8_t)(state | (sub << 4));
    p[1] = (uint8_t)(st->faults & 0xFFu);
    p[2] = (uint8_t)(st->faults >> 8);
    p[3] = (uint8_t)(st->speed_rpm & 0xFFu);
    p[4] = (uint8_t)(st->speed_rpm >> 8);
    p[5] = (uint8_t)((v > 255u) ? 255u : v);
    p[6] = (uint8_t)((c > 255u) ? 255u : c);
    p[7] = (uint8_t)((t > 255) ? 255 : t);
}

/* a status frame as qfoc_lin_encode_status() must write it */
static inline void fz_check_status_frame(const uint8_t *f, uint8_t id_status,
                                         const qfoc_status_t *st)
{
    uint8_t p[8];
    fz_payload(st, p);
    FZ_CHECK(f[0] == 0x55u, "status frame: sync byte 0x55");
    FZ_CHECK(f[1] == fz_pid(id_status), "status frame: PID(id_status)");
    FZ_CHECK(memcmp(&f[2], p, 8u) == 0, "status frame: payload of specs/link-frames.md");
    FZ_CHECK(f[10] == fz_checksum(f[1], &f[2], 8u), "status frame: enhanced checksum");
}

/* ------------------------------------------------------------------ the drive */

/* REQ-DRV-003's condition (specs/drive.acsl, DriveOverCurrent): a phase current of these
   samples, 16 (min(code, 4095) - min(offset, 4095)) saturated to Q15, above i_trip. */
static inline int32_t fz_sat15(int32_t x)
{
    return (x > 32767) ? 32767 : ((x < -32768) ? -32768 : x);
}

static inline int32_t fz_current(uint16_t code, uint16_t off)
{
    const int32_t c = (code > 4095u) ? 4095 : (int32_t)code;
    const int32_t o = (off > 4095u) ? 4095 : (int32_t)off;
    return fz_sat15((c - o) * 16);
}

static inline bool fz_overcurrent(const qfoc_drive_t *d, const qfoc_adc_t *adc)
{
    const int32_t lim = d->p->i_trip;
    const int32_t iu = fz_current(adc->iu, d->s.offset_u);
    const int32_t iv = fz_current(adc->iv, d->s.offset_v);
    const int32_t iw = fz_sat15(-(iu + iv));
    return (iu > lim) || (iu < -lim) || (iv > lim) || (iv < -lim) || (iw > lim) || (iw < -lim);
}

/* qfoc_drive_fast_step() and its guarantees (drive.h, REQ-DRV-001 .. REQ-DRV-005):
   compare values <= period, enable only in RUN without the over-current latch, an
   over-current in these samples switches off in this call and latches, only d->f is
   written, the invariant holds, the result is d->f.out. */
static inline qfoc_pwm_t fz_fast(qfoc_drive_t *d, const qfoc_adc_t *adc)
{
    static qfoc_drive_slow_t s_before;
    const qfoc_param_table_t *const p = d->p;
    const bool oc = fz_overcurrent(d, adc);
    qfoc_pwm_t pwm;
    memcpy(&s_before, &d->s, sizeof s_before);
    pwm = qfoc_drive_fast_step(d, adc);
    FZ_CHECK(d->p == p, "fast step: the table pointer is kept");
    FZ_CHECK(memcmp(&s_before, &d->s, sizeof s_before) == 0, "fast step writes only d->f");
    FZ_CHECK(pwm.cmp[0] <= p->svpwm.period && pwm.cmp[1] <= p->svpwm.period &&
             pwm.cmp[2] <= p->svpwm.period, "fast step: compare values <= period");
    FZ_CHECK(!pwm.enable || ((d->s.sm.state == QFOC_STATE_RUN) && !d->f.trip),
             "fast step: PWM enabled only in RUN without the over-current latch");
    FZ_CHECK(!oc || (!pwm.enable && d->f.trip),
             "fast step: an over-current switches the PWM off in the same call and latches");
    FZ_CHECK(pwm.enable == d->f.out.enable && pwm.cmp[0] == d->f.out.cmp[0] &&
             pwm.cmp[1] == d->f.out.cmp[1] && pwm.cmp[2] == d->f.out.cmp[2],
             "fast step: the result is d->f.out");
    FZ_CHECK(qfoc_drive_is_valid(d), "fast step: the drive invariant holds");
    return pwm;
}

/* qfoc_drive_tick() and its guarantees (drive.h, REQ-DRV-005, REQ-DRV-011, REQ-DRV-015):
   only d->s is written, the invariant holds, ERROR is left only to STOP and RUN entered
   only from STOP in ALIGN, a status frame (well formed) answers exactly an accepted command
   frame, the CAN frame carries the status payload, and a frame the decoding order rejects
   leaves the drive exactly as the same tick without the frame, but for the counter of its
   cause (checked on a twin drive). */
static inline qfoc_tick_out_t fz_tick(qfoc_drive_t *d, const qfoc_tick_in_t *in)
{
    static qfoc_drive_fast_t f_before;
    static qfoc_drive_t twin;
    const qfoc_param_table_t *const p = d->p;
    const uint8_t old_state = d->s.sm.state;
    const qfoc_link_t link_before = d->s.link;
    qfoc_cmd_t ref_cmd;
    int32_t ref = 1;  /* 1: no frame */
    qfoc_tick_out_t out;

    memcpy(&f_before, &d->f, sizeof f_before);
    if (in->rx_len > 0u) {
        ref = fz_ref_decode(d->s.link.cfg.id_cmd, d->s.link.cfg.rpm_max, in->rx, in->rx_len,
                            &ref_cmd);
    }
    if (ref < 0) {
        qfoc_tick_in_t none = *in;
        none.rx = NULL;
        none.rx_len = 0u;
        memcpy(&twin, d, sizeof twin);
        (void)qfoc_drive_tick(&twin, &none);
    }
    out = qfoc_drive_tick(d, in);
    FZ_CHECK(d->p == p, "tick: the table pointer is kept");
    FZ_CHECK(memcmp(&f_before, &d->f, sizeof f_before) == 0, "tick writes only d->s");
    FZ_CHECK(qfoc_drive_is_valid(d), "tick: the drive invariant holds");
    FZ_CHECK(out.tx_len == 0u || out.tx_len == QFOC_LIN_STATUS_LEN,
             "tick: tx_len is 0 or 11");
    FZ_CHECK(out.tx_len == d->s.out.tx_len && out.can_send == d->s.out.can_send,
             "tick: the result is d->s.out");
    FZ_CHECK(!(old_state == QFOC_STATE_ERROR && d->s.sm.state != QFOC_STATE_ERROR) ||
             d->s.sm.state == QFOC_STATE_STOP, "tick: ERROR is left only to STOP");
    FZ_CHECK(!(old_state != QFOC_STATE_RUN && d->s.sm.state == QFOC_STATE_RUN) ||
             (old_state == QFOC_STATE_STOP && d->s.sm.sub == QFOC_SUB_CATCH),
             "tick: RUN is entered only from STOP, in CATCH");
    FZ_CHECK((out.tx_len == QFOC_LIN_STATUS_LEN) == (ref == QFOC_LINK_OK),
             "tick: a status frame answers exactly an accepted command frame");
    if (out.tx_len == QFOC_LIN_STATUS_LEN) {
        fz_check_status_frame(out.tx, d->s.link.cfg.id_status, &d->s.status);
        FZ_CHECK(d->s.link.cmd.power_on == ref_cmd.power_on &&
                 d->s.link.cmd.fault_clear == ref_cmd.fault_clear &&
                 d->s.link.cmd.target_rpm == ref_cmd.target_rpm && !d->s.link.cmd.identify,
                 "tick: an accepted frame's command is the link's command");
    }
    if (out.can_send) {
        uint8_t pl[8];
        fz_payload(&d->s.status, pl);
        FZ_CHECK(out.can.dlc == 8u && memcmp(out.can.data, pl, 8u) == 0,
                 "tick: the CAN frame carries the status payload");
        FZ_CHECK(out.can.id == (link_before.can_b ? link_before.cfg.can_id_b
                                                  : link_before.cfg.can_id_a),
                 "tick: the CAN identifiers alternate");
    }
    FZ_CHECK(d->s.status.state == d->s.sm.state && d->s.status.faults == d->s.sm.faults,
             "tick: the status reports the state and the fault word");
    FZ_CHECK(d->s.status.temp_dc == ((in->t_ipm > in->t_pcb) ? in->t_ipm : in->t_pcb),
             "tick: the status reports the hotter temperature");
    FZ_CHECK(d->f.active || d->s.status.speed_rpm == 0u,
             "tick: the reported speed is 0 while the control does not run");
    if (ref < 0) {
        /* the twin ran the same tick without the frame: equal but for the cause's counter */
        uint16_t *const cnt[6] = { &twin.s.link.n_len, &twin.s.link.n_sync, &twin.s.link.n_id,
                                   &twin.s.link.n_checksum, &twin.s.link.n_reserved,
                                   &twin.s.link.n_range };
        uint16_t *const c = cnt[-ref - 1];
        *c = fz_sat_inc(*c);
        FZ_CHECK(memcmp(&twin, d, sizeof twin) == 0,
                 "tick: a rejected frame changes nothing but the counter of its cause");
    }
    return out;
}

/* ------------------------------------------------------------------ drive rig */

/* A drive with the inputs of a quiet bench: zero currents, the bus between its under- and
   over-voltage thresholds, 40 / 35 degC, a master sending its command frame every 10 ms. */
typedef struct {
    qfoc_drive_t d;
    qfoc_adc_t adc;        /* nominal samples */
    int ppm;               /* PWM periods per ms */
    int16_t t_ipm;
    int16_t t_pcb;
    bool power_on;
    bool fault_clear;
    uint16_t rpm;
    uint32_t ms;
} fz_rig_t;

static inline void fz_rig_init(fz_rig_t *r, const qfoc_param_table_t *t)
{
    int32_t vdc;
    memset(r, 0, sizeof *r);
    FZ_CHECK(qfoc_drive_init(&r->d, t) == QFOC_PARAMS_OK, "init from a committed table");
    FZ_CHECK(qfoc_drive_is_valid(&r->d), "init: the drive invariant holds");
    vdc = ((int32_t)t->vdc_uv + (int32_t)t->vdc_ov) / 16;   /* Q15 = 8 x code */
    r->adc.iu = QFOC_ADC_MID;
    r->adc.iv = QFOC_ADC_MID;
    r->adc.vdc = (uint16_t)((vdc > 4095) ? 4095 : vdc);
    r->ppm = (int)((t->f_pwm_hz + 500u) / 1000u);
    r->t_ipm = 400;
    r->t_pcb = 350;
    r->rpm = (uint16_t)((2u * t->drive.rpm_min <= t->drive.rpm_max) ? 2u * t->drive.rpm_min
                                                                   : t->drive.rpm_min);
}

/* one tick with the master's frame when `frame` */
static inline qfoc_tick_out_t fz_rig_tick(fz_rig_t *r, bool frame)
{
    uint8_t f[QFOC_LIN_FRAME_MAX];
    qfoc_tick_in_t in;
    in.t_ipm = r->t_ipm;
    in.t_pcb = r->t_pcb;
    in.rx = f;
    in.rx_len = frame ? fz_frame(f, r->d.s.link.cfg.id_cmd, r->power_on, r->fault_clear, r->rpm)
                      : 0u;
    r->ms++;
    return fz_tick(&r->d, &in);
}

/* The current a healthy motor carries where the drive imposes one (ALIGN: i_align,
   OPEN_LOOP: i_start), put into the phase monitor's filters before a tick, as
   tests/drive_rig.h does: the rig's samples are at the offset, so without it the
   current-response monitor (REQ-DRV-018) stops every start with PHASE. */
static inline void fz_rig_motor_current(fz_rig_t *r)
{
    if (r->d.s.sm.state == QFOC_STATE_RUN) {
        const qfoc_drive_cfg_t *const c = &r->d.p->drive;
        const int32_t ia = (c->i_align < 0) ? -(int32_t)c->i_align : (int32_t)c->i_align;
        const int32_t is = (c->i_start < 0) ? -(int32_t)c->i_start : (int32_t)c->i_start;
        const int32_t i = (r->d.s.sm.sub == QFOC_SUB_ALIGN) ? ia : is;
        int k;
        for (k = 0; k < 3; k++) {
            r->d.f.phase.abs_lpf[k].state = i * 65536;
        }
    }
}

/* n ms of nominal samples, a tick each, the master's frame every 10 ms */
static inline void fz_rig_ms(fz_rig_t *r, int n)
{
    int k;
    int j;
    for (k = 0; k < n; k++) {
        for (j = 0; j < r->ppm; j++) {
            (void)fz_fast(&r->d, &r->adc);
        }
        fz_rig_motor_current(r);
        (void)fz_rig_tick(r, (r->ms % 10u) == 0u);
    }
}

/* run until the state (and, unless sub is 0xFF, the sub-state) is reached, at most max ms */
static inline void fz_rig_until(fz_rig_t *r, uint8_t state, uint8_t sub, int max_ms)
{
    int k;
    for (k = 0; k < max_ms; k++) {
        if (r->d.s.sm.state == state && (sub == 0xFFu || r->d.s.sm.sub == sub)) {
            return;
        }
        fz_rig_ms(r, 1);
    }
    FZ_CHECK(r->d.s.sm.state == state && (sub == 0xFFu || r->d.s.sm.sub == sub),
             "rig: the drive reaches the state the harness needs");
}

#endif /* QFOC_TESTS_FUZZ_H */
