/*
 * CBMC harness: the whole drive state machine, 20 fast steps and 20 ticks with
 * nondeterministic ADC samples, temperatures and commands (a valid command frame with any
 * power-on bit, fault-clear bit and target, or no frame, at every tick), from any valid
 * state of the state machine, the command link and the fault debouncers
 * (REQ-DRV-002, REQ-DRV-003, REQ-DRV-005, REQ-DRV-006, REQ-DRV-008, REQ-SM-002, REQ-SM-003,
 * REQ-SM-006).
 * Malformed frames are the subject of proofs/cbmc/drive_frame (REQ-DRV-015).
 *
 * The signal-processing functions (observer, PLL, transforms, SVPWM, PI, filters, torque
 * compensation, field weakening, CRC) are replaced by stubs that return ANY value their
 * proved contracts allow (config.mk), so the properties below hold whatever the control
 * computes.  Asserted at every step:
 *  1. PWM enabled only in RUN and without the over-current latch; compare values within
 *     the period (REQ-DRV-002);
 *  2. an over-current in the samples disables the PWM in the same fast step, and the
 *     next tick is in ERROR (REQ-DRV-003);
 *  3. an over-voltage held for vdc_ms ticks, an over-temperature held for temp_ms ticks,
 *     are in ERROR by that tick (REQ-DRV-008);
 *  4. ERROR is left only to STOP, after clear_ms in ERROR, with the link's fault-clear
 *     request (REQ-SM-003);
 *  5. CLOSED_LOOP is reached from STOP only through ALIGN and OPEN_LOOP (REQ-SM-006);
 *  6. the references stay within their limits: |i_q ref| <= i_max, 0 <= i_d ref (ALIGN)
 *     <= i_align, 0 <= speed ref <= speed_max, 0 <= open-loop speed <= of_speed.
 */
#include <string.h>
#include "qfoc/drive.h"
#include "../harness_util.h"
#include "../../../tables/reference_params.h"

#define STEPS 20

#include "../drive_stubs.h"

/* ------------------------------------------------------------------ harness */
static int32_t cur(uint16_t code, uint16_t off)
{
    const int32_t c = (code > 4095u) ? 4095 : (int32_t)code;
    const int32_t o = (off > 4095u) ? 4095 : (int32_t)off;
    const int32_t x = (c - o) * 16;
    return (x > 32767) ? 32767 : ((x < -32767) ? -32767 : x);
}

static bool abs_over(int32_t x, int32_t lim)
{
    return (x > lim) || (x < -lim);
}

int main(void)
{
    qfoc_drive_t d;
    const qfoc_param_table_t *const p = &qfoc_params_reference;
    const qfoc_drive_cfg_t *const c = &p->drive;
    int k;
    int seq = 0;          /* 1: ALIGN seen after STOP, 2: then OPEN_LOOP */
    bool from_stop;
    int ov_run = 0;       /* consecutive ticks with the filtered bus above vdc_ov */
    int ot_run = 0;       /* consecutive ticks with the IPM above t_ipm_max */

    /* any valid state of the logic */
    d.p = p;
    __CPROVER_assume(qfoc_sm_is_valid(&d.s.sm));
    __CPROVER_assume(qfoc_link_is_valid(&d.s.link));
    __CPROVER_assume(d.s.link.cfg.id_cmd == c->lin_id_cmd && d.s.link.cfg.id_status == c->lin_id_status &&
                     d.s.link.cfg.rpm_max == c->rpm_max && d.s.link.cfg.timeout_ms == c->link_timeout_ms &&
                     d.s.link.cfg.can_id_a == c->can_id_a && d.s.link.cfg.can_id_b == c->can_id_b);
    __CPROVER_assume(d.s.offset_u <= 4095u && d.s.offset_v <= 4095u);
    __CPROVER_assume(d.s.speed_ref >= 0 && d.s.speed_ref <= p->speed_max);
    __CPROVER_assume(d.s.ol_speed >= 0 && d.s.ol_speed <= c->of_speed);
    __CPROVER_assume(d.s.id_ref >= 0 && d.s.id_ref <= c->i_align);
    __CPROVER_assume(d.s.iq_ref >= -p->i_max && d.s.iq_ref <= p->i_max);
    __CPROVER_assume(d.s.off_sum_u <= 4095u * 1024u && d.s.off_sum_v <= 4095u * 1024u);
    __CPROVER_assume(d.s.off_n <= 1024u);
    __CPROVER_assume(d.f.trip_count == d.s.trip_seen);   /* no trip pending at the start */
    from_stop = (d.s.sm.state == QFOC_STATE_STOP);

    for (k = 0; k < STEPS; k++) {
        qfoc_adc_t adc;
        qfoc_pwm_t pwm;
        qfoc_tick_in_t in;
        qfoc_tick_out_t out;
        uint8_t rx[QFOC_LIN_FRAME_MAX];
        uint8_t st0;
        uint16_t t0;
        bool oc;

        /* ---- fast step */
        adc.iu = nondet_uint16();
        adc.iv = nondet_uint16();
        adc.vdc = nondet_uint16();
        st0 = d.s.sm.state;
        oc = abs_over(cur(adc.iu, d.s.offset_u), p->i_trip) ||
             abs_over(cur(adc.iv, d.s.offset_v), p->i_trip) ||
             abs_over(-(cur(adc.iu, d.s.offset_u) + cur(adc.iv, d.s.offset_v)) > 32767 ? 32767 :
                      (-(cur(adc.iu, d.s.offset_u) + cur(adc.iv, d.s.offset_v)) < -32767 ? -32767 :
                       -(cur(adc.iu, d.s.offset_u) + cur(adc.iv, d.s.offset_v))), p->i_trip);
        qfoc_drive_fast_step(&d, &adc, &pwm);
        __CPROVER_assert(!pwm.enable || (st0 == QFOC_STATE_RUN && !d.f.trip),
                         "REQ-DRV-002 PWM only in RUN without the latch");
        __CPROVER_assert(pwm.cmp[0] <= p->svpwm.period && pwm.cmp[1] <= p->svpwm.period &&
                         pwm.cmp[2] <= p->svpwm.period, "REQ-DRV-002 compare within the period");
        if (oc) {
            __CPROVER_assert(!pwm.enable && d.f.trip, "REQ-DRV-003 over-current: PWM off in the same period");
        }

        /* ---- tick, with a valid command frame (any content) or none */
        in.t_ipm = nondet_int16();
        in.t_pcb = nondet_int16();
        in.rx_len = nondet_bool() ? QFOC_LIN_CMD_LEN : 0u;
        {
            const uint16_t rpm = nondet_uint16();
            __CPROVER_assume(rpm <= c->rpm_max);
            rx[0] = QFOC_LIN_SYNC;
            rx[1] = qfoc_lin_pid(c->lin_id_cmd);
            rx[2] = (uint8_t)((nondet_bool() ? 1u : 0u) | (nondet_bool() ? 2u : 0u));
            rx[3] = (uint8_t)(rpm & 0xFFu);
            rx[4] = (uint8_t)(rpm >> 8);
            rx[5] = 0u;
            rx[6] = qfoc_lin_checksum(rx[1], &rx[2], 4u);
        }
        in.rx = rx;
        ov_run = (d.f.vdc > p->vdc_ov) ? ov_run + 1 : 0;
        ot_run = (in.t_ipm > c->t_ipm_max) ? ot_run + 1 : 0;
        st0 = d.s.sm.state;
        t0 = d.s.sm.t_state;
        qfoc_drive_tick(&d, &in, &out);
        if (oc) {
            __CPROVER_assert(d.s.sm.state == QFOC_STATE_ERROR, "REQ-DRV-003 over-current: ERROR at the next tick");
        }
        if ((ov_run >= (int)c->vdc_ms) || (ot_run >= (int)c->temp_ms)) {
            __CPROVER_assert(d.s.sm.state == QFOC_STATE_ERROR, "REQ-DRV-008 OV / OT within the debounce time");
        }
        if ((st0 == QFOC_STATE_ERROR) && (d.s.sm.state != QFOC_STATE_ERROR)) {
            qfoc_cmd_t now;
            qfoc_link_command(&d.s.link, &now);
            __CPROVER_assert(d.s.sm.state == QFOC_STATE_STOP && now.fault_clear &&
                             ((t0 < 65535u) ? (uint32_t)t0 + 1u : 65535u) >= c->clear_ms,
                             "REQ-SM-003 ERROR left only after clear_ms on a clear request");
        }
        __CPROVER_assert(d.s.iq_ref >= -p->i_max && d.s.iq_ref <= p->i_max, "references: i_q");
        __CPROVER_assert(d.s.id_ref >= 0 && d.s.id_ref <= c->i_align, "references: i_d (ALIGN)");
        __CPROVER_assert(d.s.speed_ref >= 0 && d.s.speed_ref <= p->speed_max, "references: speed");
        __CPROVER_assert(d.s.ol_speed >= 0 && d.s.ol_speed <= c->of_speed, "references: open-loop speed");
        __CPROVER_assert(out.tx_len == 0u || out.tx_len == QFOC_LIN_STATUS_LEN, "status frame length");
        /* start-up order */
        if (d.s.sm.state == QFOC_STATE_STOP) {
            from_stop = true;
            seq = 0;
        } else if (from_stop && (d.s.sm.sub == QFOC_SUB_ALIGN)) {
            seq = 1;
        } else if (from_stop && (d.s.sm.sub == QFOC_SUB_OPEN_LOOP) && (seq >= 1)) {
            seq = 2;
        } else if (d.s.sm.state != QFOC_STATE_RUN) {
            from_stop = false;
            seq = 0;
        }
        if (from_stop && (d.s.sm.sub == QFOC_SUB_CLOSED_LOOP)) {
            __CPROVER_assert(seq == 2, "REQ-SM-006 CLOSED_LOOP only through ALIGN and OPEN_LOOP");
        }
    }
    return 0;
}
