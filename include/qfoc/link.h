/**
 * @file link.h
 * @brief Command link: LIN-style command and status frames over a UART, the 1 ms
 *        link service with timeout and rejection counters, and the CAN status
 *        frame with the alternating identifier.
 *
 * Source: specs/equations.md section 8.2; formerly `Communication_service()` /
 * `Double_communication()` (receive the power-on bit, the fault-clearing bit and
 * the target speed, transmit the motor state via UART), `Inner_time1ms_mission()`
 * (check that LIN is connected, every 1 ms) and `Can_send_id_change_count()`
 * (interchange the CAN identifier of the status frame every 0.1 s).
 *
 * The byte layouts are specified in specs/link-frames.md:
 *  - command frame (master -> drive), 7 bytes on the UART:
 *    SYNC 0x55, PID(id_cmd), 4 data bytes, enhanced checksum;
 *  - status frame (drive -> master), 11 bytes: SYNC, PID(id_status),
 *    8 data bytes (the status payload), enhanced checksum;
 *  - CAN status frame: DLC 8, the same 8 payload bytes.
 * The LIN break field delimits frames on the bus; it is the port's business and is
 * not part of the buffers handled here.  The protected identifier and the enhanced
 * checksum follow the LIN 2.x specification (sections "Protected identifier" and
 * "Checksum" of the protocol specification).
 *
 * Use: qfoc_link_init() once; qfoc_link_service() every 1 ms with the frame that
 * the port received during that millisecond (length 0 for none); when it returns
 * true, send the frame of qfoc_lin_encode_status(); read the effective command
 * with qfoc_link_command() and the timeout with qfoc_link_lost(); call
 * qfoc_can_status() from the 100 ms job and send the frame it fills.  A command
 * that arrives decoded (CAN, AUTOSAR COM, a test) goes in through qfoc_link_accept(),
 * which takes it by the same rule as a well-formed command frame: qfoc_link_service()
 * decodes the frame and hands the command to qfoc_link_accept().
 *
 * All functions are total: every byte content and every length 0..255 of a
 * received buffer is handled (a buffer is read only within its length), every
 * counter saturates.  Pointers must be valid (contracts).
 *
 * Requirements: REQ-LINK-001 .. REQ-LINK-011 (specs/requirements/link.md).
 */
#ifndef QFOC_LINK_H
#define QFOC_LINK_H

#include "qfoc/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Decoding status: well-formed command frame. */
#define QFOC_LINK_OK ((int32_t)0)
/** Decoding status: length is not the command frame length (7 bytes). */
#define QFOC_LINK_ERR_LEN ((int32_t)-1)
/** Decoding status: first byte is not the sync byte 0x55. */
#define QFOC_LINK_ERR_SYNC ((int32_t)-2)
/** Decoding status: protected identifier is not PID(id_cmd) (wrong id or parity). */
#define QFOC_LINK_ERR_ID ((int32_t)-3)
/** Decoding status: enhanced checksum mismatch. */
#define QFOC_LINK_ERR_CHECKSUM ((int32_t)-4)
/** Decoding status: a reserved bit (data byte 0 bits 2..7, data byte 3) is set. */
#define QFOC_LINK_ERR_RESERVED ((int32_t)-5)
/** Decoding status: target speed above rpm_max. */
#define QFOC_LINK_ERR_RANGE ((int32_t)-6)
/** qfoc_link_init() status: configuration rejected, link set to the safe state. */
#define QFOC_LINK_ERR_CFG ((int32_t)-7)

/** Longest frame on the UART in bytes (the status frame). */
#define QFOC_LIN_FRAME_MAX (11u)
/** Sync byte of every frame (LIN 2.x: 0x55). */
#define QFOC_LIN_SYNC ((uint8_t)0x55u)
/** Length of the command frame on the UART: sync, PID, 4 data, checksum = 7. */
#define QFOC_LIN_CMD_LEN ((uint8_t)7u)
/** Length of the status frame on the UART: sync, PID, 8 data, checksum = 11. */
#define QFOC_LIN_STATUS_LEN ((uint8_t)11u)
/** Data bytes of the command frame. */
#define QFOC_LIN_CMD_DATA ((uint8_t)4u)
/** Data bytes of the status frame and of the CAN status frame (DLC). */
#define QFOC_LIN_STATUS_DATA ((uint8_t)8u)
/** Largest frame identifier of a signal-carrying frame (0x3C..0x3F are diagnostic). */
#define QFOC_LIN_ID_MAX ((uint8_t)0x3Bu)
/** Largest standard (11-bit) CAN identifier. */
#define QFOC_CAN_ID_MAX ((uint16_t)0x7FFu)
/** Largest link timeout, ms. */
#define QFOC_LINK_TIMEOUT_MAX ((uint16_t)60000u)
/** Saturation value of the counters and of the silent-time counter. */
#define QFOC_LINK_COUNT_MAX ((uint16_t)65535u)

/** Command of the master (power-on bit, fault-clearing bit, target speed) and the
    commissioning request.  A command frame never carries identify (the decoder sets it
    false): only a command given through qfoc_drive_command() can request the
    identification (commission.h, REQ-IDENT-007). */
typedef struct {
    bool power_on;        /**< run request */
    bool fault_clear;     /**< fault-clear request */
    uint16_t target_rpm;  /**< target speed, rpm mechanical, 0..rpm_max */
    bool identify;        /**< identification request (commission.h); false from a frame */
} qfoc_cmd_t;

/** Link configuration. */
typedef struct {
    uint8_t  id_cmd;      /**< LIN frame identifier of the command frame, 0..0x3B */
    uint8_t  id_status;   /**< identifier of the status frame, 0..0x3B, != id_cmd */
    uint16_t rpm_max;     /**< largest target speed accepted, rpm, >= 1 */
    uint16_t timeout_ms;  /**< link lost after this long without a valid command, 1..60000 */
    uint16_t can_id_a;    /**< CAN status identifiers (11-bit, 0..0x7FF), alternated */
    uint16_t can_id_b;    /**< every frame (formerly Can_send_id_change_count) */
} qfoc_link_cfg_t;

/** Drive status reported on LIN and CAN (encoding: specs/link-frames.md). */
typedef struct {
    uint8_t  state;        /**< drive state code (sent saturated to 0..15) */
    uint8_t  substate;     /**< RUN sub-state code (sent saturated to 0..15) */
    uint16_t faults;       /**< fault word (sent exactly) */
    uint16_t speed_rpm;    /**< |estimated speed|, rpm mechanical (sent exactly); the drive
                                reports 0 while its PWM is off */
    uint16_t vdc_dv;       /**< DC-bus voltage, 0.1 V (sent in 4 V steps, 0..1020 V) */
    uint16_t current_ca;   /**< current-vector amplitude, 0.01 A (sent in 0.25 A steps, 0..63.75 A) */
    int16_t  temp_dc;      /**< hottest of IPM and PCB, 0.1 degC (sent in 1 degC, -40..215 degC) */
} qfoc_status_t;

/** Link instance. */
typedef struct {
    qfoc_link_cfg_t cfg;   /**< configuration copy (the safe configuration after a rejected init) */
    qfoc_cmd_t cmd;        /**< last valid command (all zero before the first one) */
    uint16_t silent_ms;    /**< service calls since the last valid command, saturating */
    bool cfg_ok;           /**< false after a rejected init: the link stays lost */
    bool seen;             /**< a valid command has been accepted since init */
    bool lost;             /**< link lost (timeout or unusable configuration) */
    bool can_b;            /**< the next CAN status frame uses can_id_b */
    uint16_t n_ok;         /**< accepted command frames, saturating */
    uint16_t n_len;        /**< frames rejected for their length, saturating */
    uint16_t n_sync;       /**< ... for the sync byte */
    uint16_t n_id;         /**< ... for the identifier or its parity */
    uint16_t n_checksum;   /**< ... for the checksum */
    uint16_t n_reserved;   /**< ... for a reserved bit */
    uint16_t n_range;      /**< ... for a target above rpm_max */
} qfoc_link_t;

/** CAN frame (standard identifier). */
typedef struct {
    uint16_t id;           /**< 11-bit identifier */
    uint8_t dlc;           /**< data length code, 8 */
    uint8_t data[8];       /**< payload */
} qfoc_can_frame_t;

#ifdef __FRAMAC__
/* ACSL predicates over the types above, read by Frama-C only (DEV-001). */
/* cppcheck-suppress misra-c2012-20.1 ; DEV-001 */
#include "link.acsl"
#endif

/**
 * @brief LIN 2.x protected identifier of a frame identifier.
 * @param[in] id frame identifier; only bits 0..5 are used (any uint8_t accepted)
 * @return id6 | P0 << 6 | P1 << 7 with id6 = id mod 64,
 *         P0 = id0 ^ id1 ^ id2 ^ id4, P1 = !(id1 ^ id3 ^ id4 ^ id5).
 *
 * Bad input: bits 6 and 7 of id are ignored.
 *
 * Scaling and overflow: bits are extracted by division by powers of two of a
 * value <= 63; the result is <= 255.
 *
 * Requirements: REQ-LINK-001.
 */
/*@
  assigns \nothing;
  ensures result: \result == LinPid(id);
*/
uint8_t qfoc_lin_pid(uint8_t id);

/**
 * @brief LIN 2.x enhanced checksum over the protected identifier and n data bytes.
 * @param[in] pid  protected identifier (first addend)
 * @param[in] data data bytes, read data[0 .. n-1] only (not read for n = 0)
 * @param[in] n    number of data bytes, any uint8_t
 * @return 255 - s, where s is the 8-bit sum with carry (a carry out of bit 7 is
 *         added to bit 0) of pid and the data bytes.
 *
 * Scaling and overflow: the running sum stays in 0..255; each addition is done in
 * 32 bits (<= 510) and folded (- 255) when above 255.
 *
 * Requirements: REQ-LINK-002.
 */
/*@
  requires valid_data: \valid_read(data + (0 .. n - 1));
  assigns \nothing;
  ensures result: \result == LinChecksum(pid, data, n);
*/
uint8_t qfoc_lin_checksum(uint8_t pid, const uint8_t *data, uint8_t n);

/**
 * @brief Check a link configuration.
 * @param[in] c configuration (read only)
 * @return true when id_cmd, id_status <= 0x3B and differ, rpm_max >= 1,
 *         1 <= timeout_ms <= 60000, can_id_a, can_id_b <= 0x7FF.
 *
 * Scaling and overflow: compares only.
 *
 * Requirements: REQ-LINK-006.
 */
/*@
  requires valid_c: \valid_read(c);
  assigns \nothing;
  ensures result: \result == \true <==> LinkCfgValid(c);
*/
bool qfoc_link_cfg_is_valid(const qfoc_link_cfg_t *c);

/**
 * @brief Check a link instance (the run-time twin of the ACSL predicate LinkValid).
 * @param[in] l instance (read only)
 * @return true when the configuration is valid, the stored target is <= rpm_max,
 *         the stored command is all zero while no valid command was seen, and
 *         lost == (!cfg_ok || (seen && silent_ms > timeout_ms)).
 *
 * Scaling and overflow: compares only.
 *
 * Requirements: REQ-LINK-006, REQ-LINK-008.
 */
/*@
  requires valid_l: \valid_read(l);
  assigns \nothing;
  ensures result: \result == \true <==> LinkValid(l);
*/
bool qfoc_link_is_valid(const qfoc_link_t *l);

/**
 * @brief Initialise a link: store the configuration, clear the command, the timer
 *        and the counters.
 * @param[out] l link to initialise
 * @param[in]  c configuration (copied; not referenced afterwards)
 * @return QFOC_LINK_OK (0) when qfoc_link_cfg_is_valid(c); QFOC_LINK_ERR_CFG (-7)
 *         otherwise.
 *
 * After init: no valid command seen, stored command all zero (power off), not
 * lost, counters 0, silent time 0, next CAN identifier can_id_a.
 *
 * Bad input: an invalid configuration is not stored.  The link then holds the
 * safe configuration (id_cmd 0x00, id_status 0x01, rpm_max 1, timeout 1 ms, both
 * CAN identifiers 0x7FF, the lowest CAN priority) and is permanently lost
 * (cfg_ok false): its effective command never powers the drive.
 *
 * Scaling and overflow: copies only.
 *
 * Requirements: REQ-LINK-006, REQ-LINK-007.
 */
/*@
  requires valid_l: \valid(l);
  requires valid_c: \valid_read(c);
  requires sep: \separated(l, c);
  assigns *l;
  ensures valid: LinkValid(l);
  ensures cleared: l->seen == \false && l->silent_ms == 0 && l->can_b == \false &&
                   l->cmd.power_on == \false && l->cmd.fault_clear == \false &&
                   l->cmd.target_rpm == 0 && l->cmd.identify == \false;
  ensures counters: l->n_ok == 0 && l->n_len == 0 && l->n_sync == 0 && l->n_id == 0 &&
                    l->n_checksum == 0 && l->n_reserved == 0 && l->n_range == 0;
  behavior accepted:
    assumes LinkCfgValid(c);
    ensures result: \result == 0;
    ensures usable: l->cfg_ok == \true && l->lost == \false;
    ensures copy: l->cfg.id_cmd == c->id_cmd && l->cfg.id_status == c->id_status &&
                  l->cfg.rpm_max == c->rpm_max && l->cfg.timeout_ms == c->timeout_ms &&
                  l->cfg.can_id_a == c->can_id_a && l->cfg.can_id_b == c->can_id_b;
  behavior rejected:
    assumes !LinkCfgValid(c);
    ensures result: \result == -7;
    ensures unusable: l->cfg_ok == \false && l->lost == \true;
  complete behaviors;
  disjoint behaviors;
*/
int32_t qfoc_link_init(qfoc_link_t *l, const qfoc_link_cfg_t *c);

/**
 * @brief Decode a received command frame.
 * @param[in]  c   configuration (id_cmd, rpm_max; any values accepted)
 * @param[in]  buf received bytes, read buf[0 .. len-1] only (nothing for len = 0)
 * @param[in]  len number of received bytes, any uint8_t
 * @param[out] cmd decoded command, written only when the frame is well-formed
 * @return QFOC_LINK_OK, or the first failed check in the decoding order:
 *   1. len == 7                                      else QFOC_LINK_ERR_LEN
 *   2. buf[0] == 0x55                                else QFOC_LINK_ERR_SYNC
 *   3. buf[1] == qfoc_lin_pid(id_cmd)                else QFOC_LINK_ERR_ID
 *   4. buf[6] == qfoc_lin_checksum(buf[1], buf+2, 4) else QFOC_LINK_ERR_CHECKSUM
 *   5. buf[2] <= 3 (bits 2..7 clear), buf[5] == 0    else QFOC_LINK_ERR_RESERVED
 *   6. target = buf[3] + 256 buf[4] <= rpm_max       else QFOC_LINK_ERR_RANGE
 * On OK: power_on = bit 0 of buf[2], fault_clear = bit 1 of buf[2],
 * target_rpm = target, identify = false (no frame requests the identification).
 *
 * Bad input: any content and length is classified; a rejected frame leaves *cmd
 * untouched.  A length other than 7 (longer than a command frame included) is
 * rejected before any byte is read.
 *
 * Scaling and overflow: the little-endian target is formed in 32 bits (<= 65535).
 *
 * Requirements: REQ-LINK-003, REQ-LINK-004.
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
int32_t qfoc_lin_decode_cmd(const qfoc_link_cfg_t *c, const uint8_t *buf, uint8_t len,
                            qfoc_cmd_t *cmd);

/**
 * @brief Encode the status frame.
 * @param[in]  c   configuration (id_status; any value accepted, bits 0..5 used)
 * @param[in]  st  status to report (any field values)
 * @param[out] buf frame buffer, at least QFOC_LIN_FRAME_MAX (11) bytes
 * @return the frame length, 11.
 *
 * Frame: 0x55, PID(id_status), the 8-byte status payload (specs/link-frames.md),
 * enhanced checksum over the PID and the payload.
 *
 * Bad input: out-of-range fields are saturated as documented in
 * specs/link-frames.md (codes to 15, DC bus to 1020 V, current to 63.75 A,
 * temperature to -40 .. 215 degC).
 *
 * Scaling and overflow: the payload quantities are rounded by integer division in
 * 32 bits (at most 65535 + 20); see qfoc_can_status().
 *
 * Requirements: REQ-LINK-005.
 */
/*@
  requires valid_c: \valid_read(c);
  requires valid_st: \valid_read(st);
  requires valid_buf: \valid(buf + (0 .. 10));
  requires sep: \separated(buf + (0 .. 10), c) && \separated(buf + (0 .. 10), st);
  assigns buf[0 .. 10];
  ensures result: \result == 11;
  ensures sync: buf[0] == 0x55;
  ensures pid: buf[1] == LinPid(c->id_status);
  ensures payload: LinPayload(st, buf + 2);
  ensures checksum: buf[10] == 255 - LinSum4(LinSum4(buf[1], buf[2], buf[3], buf[4], buf[5]),
                                             buf[6], buf[7], buf[8], buf[9]);
*/
uint8_t qfoc_lin_encode_status(const qfoc_link_cfg_t *c, const qfoc_status_t *st, uint8_t *buf);

/**
 * @brief 1 ms link service: decode the frame received this millisecond, count
 *        it, and advance the link timer.
 * @param[in,out] l      valid link (qfoc_link_is_valid())
 * @param[in]     rx     received bytes, read rx[0 .. rx_len-1] only (not read,
 *                       may be NULL, for rx_len = 0)
 * @param[in]     rx_len number of received bytes; 0 = no frame this millisecond
 * @return true when a well-formed command frame was accepted in this call (the
 *         drive then answers with the status frame).
 *
 * A well-formed frame (qfoc_lin_decode_cmd() returns OK): it becomes the stored
 * command, n_ok counts it, the silent time restarts at 0 and the link is not lost
 * (unless the configuration was rejected at init).
 * No frame, or a malformed frame: the stored command and `seen` are unchanged; a
 * malformed frame increments the counter of its cause (the first failed check of
 * the decoding order); the silent time counts up by one (saturating at 65535) and
 * lost = !cfg_ok || (seen && silent_ms > timeout_ms).  So after a valid command
 * the link is lost at the (timeout_ms + 1)-th consecutive call without a valid
 * command; a malformed frame acts on the state exactly like no frame, apart from
 * its counter.
 *
 * Scaling and overflow: counters and the silent time saturate at 65535
 * (> 60000 >= timeout_ms, so saturation never ends a loss).
 *
 * Requirements: REQ-LINK-007, REQ-LINK-008, REQ-LINK-009.
 */
/*@
  requires valid_l: \valid(l);
  requires link_valid: LinkValid(l);
  requires valid_rx: \valid_read(rx + (0 .. rx_len - 1));
  requires sep: \separated(l, rx + (0 .. rx_len - 1));
  assigns l->cmd, l->seen, l->silent_ms, l->lost, l->n_ok, l->n_len, l->n_sync,
          l->n_id, l->n_checksum, l->n_reserved, l->n_range;
  ensures still_valid: LinkValid(l);
  behavior accepted:
    assumes rx_len > 0 && LinCmdWellFormed(&l->cfg, rx, rx_len);
    ensures result: \result == \true;
    ensures cmd: LinCmdFields(&l->cmd, rx);
    ensures no_identify: l->cmd.identify == \false;
    ensures timer: l->seen == \true && l->silent_ms == 0 && (l->lost == \true <==> l->cfg_ok == \false);
    ensures count: l->n_ok == LinSatInc(\old(l->n_ok));
    ensures others: l->n_len == \old(l->n_len) && l->n_sync == \old(l->n_sync) &&
                    l->n_id == \old(l->n_id) && l->n_checksum == \old(l->n_checksum) &&
                    l->n_reserved == \old(l->n_reserved) && l->n_range == \old(l->n_range);
  behavior no_frame_or_rejected:
    assumes rx_len == 0 || !LinCmdWellFormed(&l->cfg, rx, rx_len);
    ensures result: \result == \false;
    ensures cmd_unchanged: LinCmdSame{Pre, Post}(&l->cmd) && l->seen == \old(l->seen);
    ensures timer: l->silent_ms == LinSatInc(\old(l->silent_ms));
    ensures ok_count: l->n_ok == \old(l->n_ok);
    ensures len_count: l->n_len ==
      ((rx_len > 0 && LinCmdStatus(&l->cfg, rx, rx_len) == -1) ? LinSatInc(\old(l->n_len)) : \old(l->n_len));
    ensures sync_count: l->n_sync ==
      ((rx_len > 0 && LinCmdStatus(&l->cfg, rx, rx_len) == -2) ? LinSatInc(\old(l->n_sync)) : \old(l->n_sync));
    ensures id_count: l->n_id ==
      ((rx_len > 0 && LinCmdStatus(&l->cfg, rx, rx_len) == -3) ? LinSatInc(\old(l->n_id)) : \old(l->n_id));
    ensures checksum_count: l->n_checksum ==
      ((rx_len > 0 && LinCmdStatus(&l->cfg, rx, rx_len) == -4) ? LinSatInc(\old(l->n_checksum)) : \old(l->n_checksum));
    ensures reserved_count: l->n_reserved ==
      ((rx_len > 0 && LinCmdStatus(&l->cfg, rx, rx_len) == -5) ? LinSatInc(\old(l->n_reserved)) : \old(l->n_reserved));
    ensures range_count: l->n_range ==
      ((rx_len > 0 && LinCmdStatus(&l->cfg, rx, rx_len) == -6) ? LinSatInc(\old(l->n_range)) : \old(l->n_range));
  complete behaviors;
  disjoint behaviors;
*/
bool qfoc_link_service(qfoc_link_t *l, const uint8_t *rx, uint8_t rx_len);

/**
 * @brief Take a decoded command (from CAN, AUTOSAR COM or any source other than the
 *        LIN command frame) by the rule of a well-formed command frame.
 * @param[in,out] l   valid link (qfoc_link_is_valid())
 * @param[in]     cmd the command (any field values)
 * @return QFOC_LINK_OK when the command was taken; QFOC_LINK_ERR_RANGE when its
 *         target_rpm is above the configured rpm_max (refused).
 *
 * Taken: it becomes the stored command, n_ok counts it, the silent time restarts at
 * 0 and the link is not lost (unless the configuration was rejected at init), exactly
 * as for a frame accepted by qfoc_link_service().  Refused: n_range counts it and
 * nothing else changes, like a frame rejected for its range.  The silent time advances
 * only in qfoc_link_service(), once a millisecond: a command taken between two
 * service calls counts as received at the earlier one.
 *
 * Scaling and overflow: copies, one compare, saturating counters.
 *
 * Requirements: REQ-LINK-011.
 */
/*@
  requires valid_l: \valid(l);
  requires link_valid: LinkValid(l);
  requires valid_cmd: \valid_read(cmd);
  requires sep: \separated(l, cmd);
  assigns l->cmd, l->seen, l->silent_ms, l->lost, l->n_ok, l->n_range;
  ensures still_valid: LinkValid(l);
  behavior taken:
    assumes cmd->target_rpm <= l->cfg.rpm_max;
    ensures result: \result == QFOC_LINK_OK;
    ensures cmd: l->cmd.power_on == cmd->power_on && l->cmd.fault_clear == cmd->fault_clear &&
                 l->cmd.target_rpm == cmd->target_rpm && l->cmd.identify == cmd->identify;
    ensures timer: l->seen == \true && l->silent_ms == 0 && (l->lost == \true <==> l->cfg_ok == \false);
    ensures count: l->n_ok == LinSatInc(\old(l->n_ok)) && l->n_range == \old(l->n_range);
  behavior refused:
    assumes cmd->target_rpm > l->cfg.rpm_max;
    ensures result: \result == QFOC_LINK_ERR_RANGE;
    ensures unchanged: LinCmdSame{Pre, Post}(&l->cmd) && l->seen == \old(l->seen) &&
                       l->silent_ms == \old(l->silent_ms) && l->lost == \old(l->lost);
    ensures count: l->n_range == LinSatInc(\old(l->n_range)) && l->n_ok == \old(l->n_ok);
  complete behaviors;
  disjoint behaviors;
*/
int32_t qfoc_link_accept(qfoc_link_t *l, const qfoc_cmd_t *cmd);

/**
 * @brief Effective command of the link.
 * @param[in]  l   valid link
 * @param[out] cmd the last valid command; power_on and fault_clear are false while
 *                 the link is lost or before the first valid command (target_rpm
 *                 is then the last valid target, 0 before the first).
 *
 * Scaling and overflow: copies only.
 *
 * Requirements: REQ-LINK-007, REQ-LINK-008.
 */
/*@
  requires valid_l: \valid_read(l);
  requires link_valid: LinkValid(l);
  requires valid_cmd: \valid(cmd);
  requires sep: \separated(l, cmd);
  assigns *cmd;
  ensures target: cmd->target_rpm == l->cmd.target_rpm;
  behavior active:
    assumes l->seen == \true && l->lost == \false;
    ensures copy: cmd->power_on == l->cmd.power_on && cmd->fault_clear == l->cmd.fault_clear &&
                  cmd->identify == l->cmd.identify;
  behavior off:
    assumes l->seen == \false || l->lost == \true;
    ensures off: cmd->power_on == \false && cmd->fault_clear == \false &&
                 cmd->identify == \false;
  complete behaviors;
  disjoint behaviors;
*/
void qfoc_link_command(const qfoc_link_t *l, qfoc_cmd_t *cmd);

/**
 * @brief Link-lost flag (to be reported as QFOC_FAULT_LINK by the drive).
 * @param[in] l valid link
 * @return true when the link is lost: a valid command was accepted once and no
 *         valid command followed for more than timeout_ms service calls, or the
 *         configuration was rejected at init.  False before the first valid
 *         command of a usable link.
 *
 * Requirements: REQ-LINK-008.
 */
/*@
  requires valid_l: \valid_read(l);
  assigns \nothing;
  ensures result: \result == l->lost;
*/
bool qfoc_link_lost(const qfoc_link_t *l);

/**
 * @brief Fill the CAN status frame (100 ms job) and alternate its identifier.
 * @param[in,out] l  valid link (its `can_b` toggles)
 * @param[in]     st status to report (any field values)
 * @param[out]    f  frame: id can_id_a and can_id_b in turn (a first after init),
 *                   dlc 8, data = the status payload of specs/link-frames.md
 *
 * Scaling and overflow: state and sub-state saturate at 15 (one nibble each);
 * DC bus (vdc_dv + 20) / 40 and current (current_ca + 12) / 25 in 32 bits,
 * saturated at 255; temperature (temp_dc + 405) / 10 in 32 bits for
 * temp_dc >= -405 (0 below), saturated at 255.
 *
 * Requirements: REQ-LINK-005, REQ-LINK-010.
 */
/*@
  requires valid_l: \valid(l);
  requires link_valid: LinkValid(l);
  requires valid_st: \valid_read(st);
  requires valid_f: \valid(f);
  requires sep: \separated(l, st, f);
  assigns l->can_b, *f;
  ensures still_valid: LinkValid(l);
  ensures toggle: l->can_b == \true <==> \old(l->can_b) == \false;
  ensures id: f->id == ((\old(l->can_b) == \true) ? l->cfg.can_id_b : l->cfg.can_id_a);
  ensures dlc: f->dlc == 8;
  ensures payload: LinPayload(st, &f->data[0]);
*/
void qfoc_can_status(qfoc_link_t *l, const qfoc_status_t *st, qfoc_can_frame_t *f);

#ifdef __cplusplus
}
#endif

#endif /* QFOC_LINK_H */
