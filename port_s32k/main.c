/**
 * @file main.c
 * @brief The compressor drive on the S32K144: set-up in the order of specs/equations.md section 8's
 *        chapter 3 (clock, power, pins, trigger chain, PDB, ADC, UART, CAN, PWM), the
 *        drive initialised from the reference parameter table, interrupts on, idle loop.
 *
 * Table: tables/reference_params.c (8 kHz); build with -DQFOC_S32K_PWM_16K for the
 * 16 kHz table tables/reference16k_params.c.  The port checks that the table's PWM
 * period matches the 80 MHz timer (REQ-PORT-005).
 *
 * Every status is tested (MISRA C:2012 Dir 4.7) and the first failure kept: a failed
 * set-up step (an oscillator that does not start, a peripheral that does not acknowledge,
 * a table that does not fit the timer), a parameter table the drive refuses (the drive is
 * then in ERROR with its PWM off, drive.h) or a watchdog that does not take its
 * configuration latches the fault output: the six PWM outputs stay masked and the gate
 * driver stays disabled until reset; the drive still runs its tick (state and fault word
 * on LIN and CAN).  Only a set-up without failure enables the gate driver.
 *
 * Requirements: REQ-PORT-002 .. REQ-PORT-015 (set-up order), REQ-PORT-016, -017.
 */
#include "qfoc/drive.h"
#include "qfoc/hal.h"
#include "s32k144_port.h"
#if defined(QFOC_S32K_PWM_16K)
#include "reference16k_params.h"
#else
#include "reference_params.h"
#endif

static const qfoc_param_table_t *s32k_table(void)
{
#if defined(QFOC_S32K_PWM_16K)
    return &qfoc_params_reference16k;
#else
    return &qfoc_params_reference;
#endif
}

/* Keep the first failure. */
static int32_t s32k_first(int32_t status, int32_t next)
{
    return (status != QFOC_S32K_OK) ? status : next;
}

/* The drive's initialisation status as a port status: a refused table is
   QFOC_S32K_ERR_PARAM. */
static int32_t s32k_drive_status(int32_t params_status)
{
    return (params_status == QFOC_PARAMS_OK) ? QFOC_S32K_OK : QFOC_S32K_ERR_PARAM;
}

int main(void)
{
    static qfoc_drive_t motor;   /* the one drive of this ECU */
    int32_t status = QFOC_S32K_OK;
    qfoc_s32k_pwm_cfg_t pwm;
    const qfoc_param_table_t *const table = s32k_table();

    qfoc_s32k_irq_global_disable();
    qfoc_s32k_pins_init();                                   /* gate driver off first */
    status = s32k_first(status, qfoc_s32k_clock_init());     /* McuclockConfig */
    status = s32k_first(status, qfoc_s32k_power_init());     /* McuPowerConfig */
    status = s32k_first(status, qfoc_s32k_pwm_cfg(table, QFOC_S32K_FTM_INT_RELOAD, &pwm));
    qfoc_s32k_trgmux_init();                                 /* McuTrigmuxConfig */
    qfoc_s32k_pdb_init(pwm.period);                          /* McuPdbConfig */
    status = s32k_first(status, qfoc_s32k_adc_init());       /* McuAdcConfig */
    qfoc_s32k_uart_init();                                   /* McuUartConfig */
    status = s32k_first(status, qfoc_s32k_can_init());       /* McuCANConfig */
    qfoc_s32k_tick_init();
    qfoc_s32k_ftm_init(&pwm);                                /* McuFtmConfig */
    qfoc_s32k_hal_init(pwm.period);

    status = s32k_first(status, s32k_drive_status(qfoc_drive_init(&motor, table)));
    qfoc_s32k_isr_bind(&motor);
    status = s32k_first(status, qfoc_s32k_wdog_init());     /* no drive without watchdog */

    if (status == QFOC_S32K_OK) {
        qfoc_s32k_gate_enable(true);
    } else {
        qfoc_hal_fault_output();                             /* latched until reset */
    }
    qfoc_s32k_irq_init();                                    /* intenable */
    qfoc_s32k_irq_global_enable();

    for (;;) {
        /* Everything runs in the interrupts; the background only sleeps.  The flag
           (a millisecond passed) is taken so that it does not stay set; the background
           has no work to do on it. */
        (void)qfoc_hal_ms_flag_take();
        qfoc_s32k_wait_for_interrupt();
    }
}
