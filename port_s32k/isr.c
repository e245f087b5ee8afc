/**
 * @file isr.c
 * @brief The interrupt glue: the drive's two entry points called from the ADC-complete
 *        interrupt and the 1 ms interrupt, through the functions of include/qfoc/hal.h
 *        only (this file touches no register), and the supervision of the ADC chain.
 *
 * The former adc1isr / ftmTimerISR / Ms_1_job (specs/equations.md section 8) become:
 *   qfoc_s32k_adc_isr()  (ADC1, priority 1): samples -> qfoc_drive_fast_step -> PWM;
 *   qfoc_s32k_ftm_isr()  (FTM3, priority 2): counts PWM periods;
 *   qfoc_s32k_tick_isr() (LPIT0, priority 3): temperatures and the received frame ->
 *        qfoc_drive_tick -> status frame on the UART, CAN frame every 100 ms; the
 *        supervision; the watchdog refresh.
 * A frame the UART or the CAN controller refuses (the previous one is still being sent)
 * is dropped, as hal.h allows, and counted (qfoc_s32k_lin_tx_refused,
 * qfoc_s32k_can_tx_refused): the master polls again, the CAN status frame repeats every
 * 100 ms, so a drop loses no state.
 * The UART interrupt (priority 4) is in hal_s32k.c.
 *
 * Requirements: REQ-PORT-016, REQ-PORT-017, REQ-PORT-018 (specs/requirements/port.md).
 */
#include <stddef.h>
#include "qfoc/hal.h"
#include "s32k144_port.h"

static qfoc_drive_t *s_drive = NULL;
static volatile uint32_t s_fast_steps = 0u;   /* written by the ADC interrupt */
static uint32_t s_seen_steps = 0u;            /* tick: values at the last check */
static uint32_t s_seen_periods = 0u;
static uint16_t s_lin_refused = 0u;           /* tick: frames the UART refused */
static uint16_t s_can_refused = 0u;           /* tick: frames the CAN controller refused */

void qfoc_s32k_isr_bind(qfoc_drive_t *drive)
{
    s_drive = drive;
    s_fast_steps = 0u;
    s_seen_steps = 0u;
    s_seen_periods = qfoc_hal_pwm_periods();
    s_lin_refused = 0u;
    s_can_refused = 0u;
}

uint32_t qfoc_s32k_fast_steps(void)
{
    return s_fast_steps;
}

uint16_t qfoc_s32k_lin_tx_refused(void)
{
    return s_lin_refused;
}

uint16_t qfoc_s32k_can_tx_refused(void)
{
    return s_can_refused;
}

/* A refused frame counted, saturating. */
static uint16_t s32k_count(uint16_t n)
{
    return (n < 0xFFFFu) ? (uint16_t)(n + 1u) : n;
}

void qfoc_s32k_adc_isr(void)
{
    qfoc_adc_t adc;
    qfoc_pwm_t pwm;
    qfoc_hal_adc_read(&adc);  /* also acknowledges the conversions */
    if (s_drive != NULL) {
        pwm = qfoc_drive_fast_step(s_drive, &adc);
        s_fast_steps = s_fast_steps + 1u;
    } else {
        pwm.cmp[0] = 0u;
        pwm.cmp[1] = 0u;
        pwm.cmp[2] = 0u;
        pwm.enable = false;
    }
    qfoc_hal_pwm_write(&pwm);
}

void qfoc_s32k_ftm_isr(void)
{
    qfoc_s32k_ftm_period_ack();
}

/* The ADC-complete chain must keep pace with the PWM: more than
   QFOC_S32K_MISSED_STEPS_MAX periods without a fast step within one millisecond (a
   trigger, PDB or ADC failure) latch the fault output: the bridge must not keep
   switching with stale compare values. */
static void s32k_supervise(void)
{
    const uint32_t periods = qfoc_hal_pwm_periods();
    const uint32_t steps = s_fast_steps;
    const uint32_t dp = periods - s_seen_periods;
    const uint32_t ds = steps - s_seen_steps;
    s_seen_periods = periods;
    s_seen_steps = steps;
    if ((dp > ds) && ((dp - ds) > QFOC_S32K_MISSED_STEPS_MAX)) {
        qfoc_hal_fault_output();
    } else {
        /* the fast step keeps pace */
    }
}

void qfoc_s32k_tick_isr(void)
{
    (void)qfoc_hal_ms_tick();
    if (s_drive != NULL) {
        uint8_t rx[QFOC_LIN_FRAME_MAX];
        qfoc_tick_in_t in;
        qfoc_tick_out_t out;
        qfoc_hal_temps_read(&in.t_ipm, &in.t_pcb);
        in.rx_len = qfoc_hal_lin_receive(rx, (uint8_t)QFOC_LIN_FRAME_MAX);
        in.rx = rx;
        out = qfoc_drive_tick(s_drive, &in);
        if (out.pwm_off) {
            /* the second path to the safe state (drive.h, REQ-DRV-021): outputs off now,
               also when the fast step no longer runs; the fast step writes the same outside
               RUN, so the two writers agree */
            static const qfoc_pwm_t off = { { 0u, 0u, 0u }, false };
            qfoc_hal_pwm_write(&off);
        } else {
            /* RUN: the fast step owns the outputs */
        }
        if (out.tx_len > 0u) {
            if (!qfoc_hal_lin_transmit(out.tx, out.tx_len)) {
                /* the previous frame is still being sent: this one is dropped, the
                   master polls again (hal.h) */
                s_lin_refused = s32k_count(s_lin_refused);
            } else {
                /* queued */
            }
        } else {
            /* no answer this millisecond */
        }
        if (out.can_send) {
            if (!qfoc_hal_can_send(&out.can)) {
                /* the previous frame is still pending: this one is dropped, the status
                   frame repeats in 100 ms (hal.h) */
                s_can_refused = s32k_count(s_can_refused);
            } else {
                /* handed to the controller */
            }
        } else {
            /* not the 100 ms tick */
        }
        s32k_supervise();
    } else {
        /* not running a drive */
    }
    qfoc_hal_watchdog_refresh();
}
