/**
 * @file qfoc_link.c
 * @brief Command link: LIN-style frames over a UART, 1 ms link service, CAN status
 *        frame (see include/qfoc/link.h and specs/link-frames.md).
 *
 * Requirements: REQ-LINK-001 .. REQ-LINK-011 (specs/requirements/link.md).
 */
#include "qfoc/link.h"

/* Divisors 2^k that select bit k of an identifier by division (k = 1..5). */
#define QFOC_LINK_BIT1 (2u)    /* 2^1 */
#define QFOC_LINK_BIT2 (4u)    /* 2^2 */
#define QFOC_LINK_BIT3 (8u)    /* 2^3 */
#define QFOC_LINK_BIT4 (16u)   /* 2^4 */
#define QFOC_LINK_BIT5 (32u)   /* 2^5 */
/** Number of 6-bit frame identifiers: 2^6 = 64. */
#define QFOC_LINK_ID_SPAN (64u)
/** Weight of parity bit P0 (bit 6): 2^6 = 64. */
#define QFOC_LINK_P0_WEIGHT (64u)
/** Weight of parity bit P1 (bit 7): 2^7 = 128. */
#define QFOC_LINK_P1_WEIGHT (128u)
/** Largest 8-bit value, 255; also the fold of a carry (- 256 + 1 = - 255). */
#define QFOC_LINK_BYTE_MAX (255u)
/** Weight of the high byte of a little-endian 16-bit value: 2^8 = 256. */
#define QFOC_LINK_BYTE_SPAN (256u)
/** Largest value of data byte 0 of the command frame with bits 2..7 clear: 3. */
#define QFOC_LINK_CMD_B0_MAX (3u)
/** Largest state / sub-state code of the status payload (one nibble): 15. */
#define QFOC_LINK_NIBBLE_MAX (15u)
/** Weight of the sub-state nibble (bits 4..7): 2^4 = 16. */
#define QFOC_LINK_NIBBLE_SPAN (16u)
/** DC bus: 4 V per bit = 40 units of 0.1 V; half a step = 20. */
#define QFOC_LINK_VDC_STEP (40u)
#define QFOC_LINK_VDC_HALF (20u)
/** Current: 0.25 A per bit = 25 units of 0.01 A; 12 rounds to nearest (no ties). */
#define QFOC_LINK_CUR_STEP (25u)
#define QFOC_LINK_CUR_HALF (12u)
/** Temperature: 1 degC per bit = 10 units of 0.1 degC; offset 40 degC = 400
    units, plus half a step 5: 405. */
#define QFOC_LINK_TEMP_STEP (10u)
#define QFOC_LINK_TEMP_OFFSET ((int32_t)405)
/** Safe configuration after a rejected init: command id 0x00, status id 0x01,
    rpm_max 1, timeout 1 ms, CAN id 0x7FF (lowest priority). */
#define QFOC_LINK_SAFE_ID_CMD ((uint8_t)0x00u)
#define QFOC_LINK_SAFE_ID_STATUS ((uint8_t)0x01u)
#define QFOC_LINK_SAFE_RPM_MAX ((uint16_t)1u)
#define QFOC_LINK_SAFE_TIMEOUT ((uint16_t)1u)

/**
 * @brief Bit of v selected by the divisor d = 2^k: (v / d) mod 2.
 */
/*@
  requires divisor: d == 1 || d == 2 || d == 4 || d == 8 || d == 16 || d == 32;
  assigns \nothing;
  ensures result: \result == LinBit(v, d);
*/
static uint32_t qfoc_link_bit(uint32_t v, uint32_t d)
{
    return (v / d) % 2u;
}

uint8_t qfoc_lin_pid(uint8_t id)
{
    /* id6 = id mod 64 <= 63 */
    const uint32_t id6 = (uint32_t)id % QFOC_LINK_ID_SPAN;
    /* XOR of bits = their sum modulo 2; each sum <= 4 */
    const uint32_t p0 = (qfoc_link_bit(id6, 1u) + qfoc_link_bit(id6, QFOC_LINK_BIT1)
                         + qfoc_link_bit(id6, QFOC_LINK_BIT2) + qfoc_link_bit(id6, QFOC_LINK_BIT4))
                        % 2u;
    const uint32_t p1 = 1u - ((qfoc_link_bit(id6, QFOC_LINK_BIT1) + qfoc_link_bit(id6, QFOC_LINK_BIT3)
                               + qfoc_link_bit(id6, QFOC_LINK_BIT4) + qfoc_link_bit(id6, QFOC_LINK_BIT5))
                              % 2u);
    /* <= 63 + 64 + 128 = 255 */
    return (uint8_t)(id6 + (QFOC_LINK_P0_WEIGHT * p0) + (QFOC_LINK_P1_WEIGHT * p1));
}

/**
 * @brief One addition of the 8-bit sum with carry: s + b, minus 255 when a carry
 *        leaves bit 7 (the carry is added back into bit 0).
 */
/*@
  requires s_range: s <= 255;
  assigns \nothing;
  ensures result: \result == LinAdd(s, b);
  ensures range: \result <= 255;
*/
static uint32_t qfoc_link_add_carry(uint32_t s, uint8_t b)
{
    /* s + b <= 510 */
    uint32_t t = s + (uint32_t)b;
    if (t > QFOC_LINK_BYTE_MAX) {
        t -= QFOC_LINK_BYTE_MAX;
    } else {
        /* no carry */
    }
    return t;
}

uint8_t qfoc_lin_checksum(uint8_t pid, const uint8_t *data, uint8_t n)
{
    uint32_t s = (uint32_t)pid;
    uint8_t i = 0u;
    /*@
      loop invariant index: 0 <= i <= n;
      loop invariant range: s <= 255;
      loop invariant sum: s == LinSumFrom(pid, data, i);
      loop assigns i, s;
      loop variant n - i;
    */
    while (i < n) {
        s = qfoc_link_add_carry(s, data[i]);
        i++;
    }
    /* inverted 8-bit sum: 255 - s, in 0..255 */
    return (uint8_t)(QFOC_LINK_BYTE_MAX - s);
}

bool qfoc_link_cfg_is_valid(const qfoc_link_cfg_t *c)
{
    bool ok = true;
    if ((c->id_cmd > QFOC_LIN_ID_MAX) || (c->id_status > QFOC_LIN_ID_MAX)
        || (c->id_cmd == c->id_status)) {
        ok = false;
    } else if ((c->rpm_max == 0u) || (c->timeout_ms == 0u)
               || (c->timeout_ms > QFOC_LINK_TIMEOUT_MAX)) {
        ok = false;
    } else if ((c->can_id_a > QFOC_CAN_ID_MAX) || (c->can_id_b > QFOC_CAN_ID_MAX)) {
        ok = false;
    } else {
        /* every field in range */
    }
    return ok;
}

bool qfoc_link_is_valid(const qfoc_link_t *l)
{
    bool ok = qfoc_link_cfg_is_valid(&l->cfg);
    if (!ok) {
        /* invalid configuration */
    } else if (l->cmd.target_rpm > l->cfg.rpm_max) {
        ok = false;
    } else if ((!l->seen)
               && (l->cmd.power_on || l->cmd.fault_clear || (l->cmd.target_rpm != 0u)
                   || l->cmd.identify)) {
        ok = false;
    } else {
        const bool timed_out = l->seen && (l->silent_ms > l->cfg.timeout_ms);
        const bool should_be_lost = (!l->cfg_ok) || timed_out;
        ok = (l->lost == should_be_lost);
    }
    return ok;
}

int32_t qfoc_link_init(qfoc_link_t *l, const qfoc_link_cfg_t *c)
{
    /* the new state is built in a local copy and stored with one assignment */
    qfoc_link_t n;
    int32_t status;
    if (qfoc_link_cfg_is_valid(c)) {
        n.cfg = *c;
        n.cfg_ok = true;
        n.lost = false;
        status = QFOC_LINK_OK;
    } else {
        n.cfg.id_cmd = QFOC_LINK_SAFE_ID_CMD;
        n.cfg.id_status = QFOC_LINK_SAFE_ID_STATUS;
        n.cfg.rpm_max = QFOC_LINK_SAFE_RPM_MAX;
        n.cfg.timeout_ms = QFOC_LINK_SAFE_TIMEOUT;
        n.cfg.can_id_a = QFOC_CAN_ID_MAX;
        n.cfg.can_id_b = QFOC_CAN_ID_MAX;
        n.cfg_ok = false;
        n.lost = true;
        status = QFOC_LINK_ERR_CFG;
    }
    n.cmd.power_on = false;
    n.cmd.fault_clear = false;
    n.cmd.target_rpm = 0u;
    n.cmd.identify = false;
    n.silent_ms = 0u;
    n.seen = false;
    n.can_b = false;
    n.n_ok = 0u;
    n.n_len = 0u;
    n.n_sync = 0u;
    n.n_id = 0u;
    n.n_checksum = 0u;
    n.n_reserved = 0u;
    n.n_range = 0u;
    *l = n;
    return status;
}

/**
 * @brief Little-endian 16-bit value of two bytes: lo + 256 hi.
 */
/*@
  assigns \nothing;
  ensures result: \result == LinLe16(lo, hi);
*/
static uint16_t qfoc_link_le16(uint8_t lo, uint8_t hi)
{
    /* <= 255 + 256 x 255 = 65535 */
    return (uint16_t)((uint32_t)lo + (QFOC_LINK_BYTE_SPAN * (uint32_t)hi));
}

/**
 * @brief Enhanced checksum of a command frame of 7 bytes (PID and 4 data bytes).
 */
/*@
  requires valid_buf: \valid_read(buf + (0 .. 6));
  assigns \nothing;
  ensures result: \result == 255 - LinSum4(buf[1], buf[2], buf[3], buf[4], buf[5]);
*/
static uint8_t qfoc_link_cmd_checksum(const uint8_t *buf)
{
    const uint8_t chk = qfoc_lin_checksum(buf[1], &buf[2], QFOC_LIN_CMD_DATA);
    /*@ assert shifted: LinSumFrom(buf[1], buf + 2, 4) ==
          LinSum4(buf[1], (buf + 2)[0], (buf + 2)[1], (buf + 2)[2], (buf + 2)[3]); */
    return chk;
}

/**
 * @brief Decoding status of a received buffer (the checks of
 *        qfoc_lin_decode_cmd() in the decoding order).
 */
/*@
  requires valid_c: \valid_read(c);
  requires valid_buf: \valid_read(buf + (0 .. len - 1));
  assigns \nothing;
  ensures status: \result == LinCmdStatus(c, buf, len);
  ensures range: -6 <= \result <= 0;
*/
static int32_t qfoc_link_classify(const qfoc_link_cfg_t *c, const uint8_t *buf, uint8_t len)
{
    int32_t status;
    if (len != QFOC_LIN_CMD_LEN) {
        status = QFOC_LINK_ERR_LEN;
    } else if (buf[0] != QFOC_LIN_SYNC) {
        status = QFOC_LINK_ERR_SYNC;
    } else if (buf[1] != qfoc_lin_pid(c->id_cmd)) {
        status = QFOC_LINK_ERR_ID;
    } else if (buf[6] != qfoc_link_cmd_checksum(buf)) {
        status = QFOC_LINK_ERR_CHECKSUM;
    } else if ((buf[2] > QFOC_LINK_CMD_B0_MAX) || (buf[5] != 0u)) {
        status = QFOC_LINK_ERR_RESERVED;
    } else if (qfoc_link_le16(buf[3], buf[4]) > c->rpm_max) {
        status = QFOC_LINK_ERR_RANGE;
    } else {
        status = QFOC_LINK_OK;
    }
    return status;
}

/**
 * @brief Decoder shared by qfoc_lin_decode_cmd() and qfoc_link_service() (same
 *        contract as the public function).
 */
/*@
  requires valid_c: \valid_read(c);
  requires valid_buf: \valid_read(buf + (0 .. len - 1));
  requires valid_cmd: \valid(cmd);
  requires sep: \separated(cmd, c) && \separated(cmd, buf + (0 .. len - 1));
  assigns *cmd;
  ensures status: \result == LinCmdStatus(c, buf, len);
  behavior well_formed:
    assumes LinCmdWellFormed(c, buf, len);
    ensures result: \result == 0;
    ensures fields: LinCmdFields(cmd, buf);
    ensures no_identify: cmd->identify == \false;
    ensures in_range: cmd->target_rpm <= c->rpm_max;
  behavior rejected:
    assumes !LinCmdWellFormed(c, buf, len);
    ensures result: \result < 0;
    ensures unchanged: LinCmdSame{Pre, Post}(cmd);
  complete behaviors;
  disjoint behaviors;
*/
static int32_t qfoc_link_decode(const qfoc_link_cfg_t *c, const uint8_t *buf, uint8_t len,
                                qfoc_cmd_t *cmd)
{
    const int32_t status = qfoc_link_classify(c, buf, len);
    if (status == QFOC_LINK_OK) {
        /* well-formed, so len == 7 and data byte 0 <= 3:
           bit 0 of data byte 0: power_on; bit 1: fault_clear */
        cmd->power_on = ((buf[2] % 2u) == 1u);
        cmd->fault_clear = (buf[2] >= 2u);
        cmd->target_rpm = qfoc_link_le16(buf[3], buf[4]);
        cmd->identify = false;   /* no frame requests the identification */
    } else {
        /* rejected: *cmd untouched */
    }
    return status;
}

int32_t qfoc_lin_decode_cmd(const qfoc_link_cfg_t *c, const uint8_t *buf, uint8_t len,
                            qfoc_cmd_t *cmd)
{
    return qfoc_link_decode(c, buf, len, cmd);
}

/**
 * @brief An unsigned value saturated to one byte.
 */
/*@
  assigns \nothing;
  ensures result: \result == LinByte(v);
*/
static uint8_t qfoc_link_sat_byte(uint32_t v)
{
    uint32_t r = v;
    if (r > QFOC_LINK_BYTE_MAX) {
        r = QFOC_LINK_BYTE_MAX;
    } else {
        /* fits */
    }
    return (uint8_t)r;
}

/**
 * @brief A code saturated to one nibble (0..15).
 */
/*@
  assigns \nothing;
  ensures result: \result == LinNib(v);
*/
static uint32_t qfoc_link_nibble(uint8_t v)
{
    uint32_t r = (uint32_t)v;
    if (r > QFOC_LINK_NIBBLE_MAX) {
        r = QFOC_LINK_NIBBLE_MAX;
    } else {
        /* fits */
    }
    return r;
}

/**
 * @brief Offset-encoded temperature byte: round(T / 1 degC) + 40, saturated to
 *        0..255 (-40..215 degC), from T in 0.1 degC.
 */
/*@
  assigns \nothing;
  ensures result: \result == LinTempByte(t);
*/
static uint8_t qfoc_link_temp_byte(int16_t t)
{
    /* t + 405 in -32363 .. 33172, exact in 32 bits */
    const int32_t shifted = (int32_t)t + QFOC_LINK_TEMP_OFFSET;
    uint8_t r;
    if (shifted < 0) {
        r = 0u;
    } else {
        /* non-negative: division rounds toward zero = floor; <= 3317 */
        r = qfoc_link_sat_byte((uint32_t)shifted / QFOC_LINK_TEMP_STEP);
    }
    return r;
}

/**
 * @brief The 8-byte status payload of specs/link-frames.md.
 */
/*@
  requires valid_st: \valid_read(st);
  requires valid_d: \valid(d + (0 .. 7));
  requires sep: \separated(d + (0 .. 7), st);
  assigns d[0 .. 7];
  ensures payload: LinPayload(st, d);
*/
static void qfoc_link_payload(const qfoc_status_t *st, uint8_t *d)
{
    /* state in bits 0..3, sub-state in bits 4..7: <= 15 + 16 x 15 = 255 */
    d[0] = (uint8_t)(qfoc_link_nibble(st->state)
                     + (QFOC_LINK_NIBBLE_SPAN * qfoc_link_nibble(st->substate)));
    /* little-endian 16-bit words: low byte = v mod 256, high byte = v / 256 */
    d[1] = (uint8_t)(st->faults % QFOC_LINK_BYTE_SPAN);
    d[2] = (uint8_t)(st->faults / QFOC_LINK_BYTE_SPAN);
    d[3] = (uint8_t)(st->speed_rpm % QFOC_LINK_BYTE_SPAN);
    d[4] = (uint8_t)(st->speed_rpm / QFOC_LINK_BYTE_SPAN);
    /* (vdc + 20) / 40 <= 65555 / 40 = 1638 before saturation */
    d[5] = qfoc_link_sat_byte(((uint32_t)st->vdc_dv + QFOC_LINK_VDC_HALF) / QFOC_LINK_VDC_STEP);
    /* (i + 12) / 25 <= 65547 / 25 = 2621 before saturation */
    d[6] = qfoc_link_sat_byte(((uint32_t)st->current_ca + QFOC_LINK_CUR_HALF) / QFOC_LINK_CUR_STEP);
    d[7] = qfoc_link_temp_byte(st->temp_dc);
}

/**
 * @brief Enhanced checksum of a status frame of 11 bytes (PID and 8 data bytes).
 */
/*@
  requires valid_buf: \valid_read(buf + (0 .. 10));
  assigns \nothing;
  ensures result: \result == 255 - LinSum4(LinSum4(buf[1], buf[2], buf[3], buf[4], buf[5]),
                                           buf[6], buf[7], buf[8], buf[9]);
*/
static uint8_t qfoc_link_status_checksum(const uint8_t *buf)
{
    const uint8_t chk = qfoc_lin_checksum(buf[1], &buf[2], QFOC_LIN_STATUS_DATA);
    /*@ assert shifted: LinSumFrom(buf[1], buf + 2, 8) ==
          LinSum4(LinSum4(buf[1], (buf + 2)[0], (buf + 2)[1], (buf + 2)[2], (buf + 2)[3]),
                  (buf + 2)[4], (buf + 2)[5], (buf + 2)[6], (buf + 2)[7]); */
    return chk;
}

uint8_t qfoc_lin_encode_status(const qfoc_link_cfg_t *c, const qfoc_status_t *st, uint8_t *buf)
{
    uint8_t chk;
    buf[0] = QFOC_LIN_SYNC;
    buf[1] = qfoc_lin_pid(c->id_status);
    qfoc_link_payload(st, &buf[2]);
    chk = qfoc_link_status_checksum(buf);
    /* the checksum is the last byte of the longest frame: index 11 - 1 = 10 */
    buf[QFOC_LIN_FRAME_MAX - 1u] = chk;
    return QFOC_LIN_STATUS_LEN;
}

/**
 * @brief Saturating increment of a 16-bit counter.
 */
/*@
  assigns \nothing;
  ensures result: \result == LinSatInc(v);
*/
static uint16_t qfoc_link_sat_inc(uint16_t v)
{
    uint16_t r = v;
    if (r < QFOC_LINK_COUNT_MAX) {
        r++;
    } else {
        /* saturated */
    }
    return r;
}

/**
 * @brief Count a rejected frame by its cause (an accepted one is counted by
 *        qfoc_link_accept()).
 */
/*@
  requires valid_l: \valid(l);
  requires link_valid: LinkValid(l);
  requires status_range: -6 <= status <= -1;
  assigns l->n_len, l->n_sync, l->n_id, l->n_checksum, l->n_reserved, l->n_range;
  ensures still_valid: LinkValid(l);
  ensures len_count: l->n_len == ((status == -1) ? LinSatInc(\old(l->n_len)) : \old(l->n_len));
  ensures sync_count: l->n_sync == ((status == -2) ? LinSatInc(\old(l->n_sync)) : \old(l->n_sync));
  ensures id_count: l->n_id == ((status == -3) ? LinSatInc(\old(l->n_id)) : \old(l->n_id));
  ensures checksum_count: l->n_checksum ==
    ((status == -4) ? LinSatInc(\old(l->n_checksum)) : \old(l->n_checksum));
  ensures reserved_count: l->n_reserved ==
    ((status == -5) ? LinSatInc(\old(l->n_reserved)) : \old(l->n_reserved));
  ensures range_count: l->n_range ==
    ((status == -6) ? LinSatInc(\old(l->n_range)) : \old(l->n_range));
*/
static void qfoc_link_count(qfoc_link_t *l, int32_t status)
{
    if (status == QFOC_LINK_ERR_LEN) {
        l->n_len = qfoc_link_sat_inc(l->n_len);
    } else if (status == QFOC_LINK_ERR_SYNC) {
        l->n_sync = qfoc_link_sat_inc(l->n_sync);
    } else if (status == QFOC_LINK_ERR_ID) {
        l->n_id = qfoc_link_sat_inc(l->n_id);
    } else if (status == QFOC_LINK_ERR_CHECKSUM) {
        l->n_checksum = qfoc_link_sat_inc(l->n_checksum);
    } else if (status == QFOC_LINK_ERR_RESERVED) {
        l->n_reserved = qfoc_link_sat_inc(l->n_reserved);
    } else {
        /* QFOC_LINK_ERR_RANGE, the last status of the decoding order */
        l->n_range = qfoc_link_sat_inc(l->n_range);
    }
}

/**
 * @brief One millisecond without a valid command: advance the silent time and
 *        apply the lost rule.
 */
/*@
  requires valid_l: \valid(l);
  requires link_valid: LinkValid(l);
  assigns l->silent_ms, l->lost;
  ensures still_valid: LinkValid(l);
  ensures timer: l->silent_ms == LinSatInc(\old(l->silent_ms));
*/
static void qfoc_link_idle(qfoc_link_t *l)
{
    l->silent_ms = qfoc_link_sat_inc(l->silent_ms);
    /* silent_ms saturates at 65535 > 60000 >= timeout_ms: a loss never ends by
       saturation */
    l->lost = (!l->cfg_ok) || (l->seen && (l->silent_ms > l->cfg.timeout_ms));
}

int32_t qfoc_link_accept(qfoc_link_t *l, const qfoc_cmd_t *cmd)
{
    int32_t status = QFOC_LINK_ERR_RANGE;
    if (cmd->target_rpm <= l->cfg.rpm_max) {
        l->cmd.power_on = cmd->power_on;
        l->cmd.fault_clear = cmd->fault_clear;
        l->cmd.target_rpm = cmd->target_rpm;
        l->cmd.identify = cmd->identify;
        /* a valid command: restart the silent time */
        l->seen = true;
        l->silent_ms = 0u;
        l->lost = !l->cfg_ok;
        l->n_ok = qfoc_link_sat_inc(l->n_ok);
        status = QFOC_LINK_OK;
    } else {
        /* above rpm_max: refused and counted like a frame out of range */
        l->n_range = qfoc_link_sat_inc(l->n_range);
    }
    return status;
}

bool qfoc_link_service(qfoc_link_t *l, const uint8_t *rx, uint8_t rx_len)
{
    bool accepted = false;
    if (rx_len > 0u) {
        /* the decoder writes the command only for a well-formed frame, whose target is
           within rpm_max: qfoc_link_accept() then takes it */
        qfoc_cmd_t cmd = l->cmd;
        const int32_t status = qfoc_link_decode(&l->cfg, rx, rx_len, &cmd);
        if (status == QFOC_LINK_OK) {
            accepted = (qfoc_link_accept(l, &cmd) == QFOC_LINK_OK);
            /*@ assert taken_power: l->cmd.power_on == \true <==> rx[2] % 2 == 1; */
            /*@ assert taken_clear: l->cmd.fault_clear == \true <==> rx[2] >= 2; */
            /*@ assert taken_target: l->cmd.target_rpm == LinLe16(rx[3], rx[4]); */
        } else {
            qfoc_link_count(l, status);
        }
    } else {
        /* no frame this millisecond */
    }
    if (!accepted) {
        qfoc_link_idle(l);
    } else {
        /* the silent time restarted */
    }
    return accepted;
}

void qfoc_link_command(const qfoc_link_t *l, qfoc_cmd_t *cmd)
{
    if (l->seen && (!l->lost)) {
        cmd->power_on = l->cmd.power_on;
        cmd->fault_clear = l->cmd.fault_clear;
        cmd->identify = l->cmd.identify;
    } else {
        /* lost, or no valid command yet: the drive ramps down and stops */
        cmd->power_on = false;
        cmd->fault_clear = false;
        cmd->identify = false;
    }
    cmd->target_rpm = l->cmd.target_rpm;
}

bool qfoc_link_lost(const qfoc_link_t *l)
{
    return l->lost;
}

void qfoc_can_status(qfoc_link_t *l, const qfoc_status_t *st, qfoc_can_frame_t *f)
{
    if (l->can_b) {
        f->id = l->cfg.can_id_b;
    } else {
        f->id = l->cfg.can_id_a;
    }
    /* formerly Can_send_id_change_count: the next frame uses the other id */
    l->can_b = !l->can_b;
    f->dlc = QFOC_LIN_STATUS_DATA;
    qfoc_link_payload(st, &f->data[0]);
}
