/**
 * @file s32k144_port.h
 * @brief The qfoc port to the NXP S32K144 (Cortex-M4F, 80 MHz RUN mode): chip set-up
 *        (the HAL functions of specs/equations.md section 8), interrupt handlers, and the board
 *        choices (pins, clocks, priorities) in one place.
 *
 * Mapping to the former names (specs/equations.md section 8, HAL / IL):
 *   McuclockConfig    -> qfoc_s32k_clock_init()   SOSC 8 MHz -> SPLL -> 80 MHz core
 *   McuPowerConfig    -> qfoc_s32k_power_init()   RUN mode only (HSRUN, VLPR refused)
 *   McuPinsConfig     -> qfoc_s32k_pins_init()    FTM3 CH0..5, FTM3_FLT0, LPUART1, CAN0, ADC
 *   McuTrigmuxConfig  -> qfoc_s32k_trgmux_init()  FTM3 init trigger -> PDB0, PDB1
 *   McuPdbConfig      -> qfoc_s32k_pdb_init()     samples at the centre of the PWM period
 *   McuAdcConfig      -> qfoc_s32k_adc_init()     calibration, 12 bit, hardware trigger
 *   McuDmaConfig      -> (none)                   UART by interrupt, CAN by one mailbox
 *   McuUartConfig     -> qfoc_s32k_uart_init()    LPUART1 19200 8N1, LIN break and idle
 *   McuFtmConfig      -> qfoc_s32k_ftm_init()     FTM3 complementary centre-aligned PWM
 *   McuCANConfig      -> qfoc_s32k_can_init()     FlexCAN0 500 kbit/s, MB0 transmit
 *   (1 ms time base)  -> qfoc_s32k_tick_init()    LPIT0 channel 0
 *   (watchdog)        -> qfoc_s32k_wdog_init()    WDOG, 10 ms, refreshed every 1 ms
 *   intenable         -> qfoc_s32k_irq_init()     NVIC priorities and enables
 *   adc1isr           -> qfoc_s32k_adc_isr()      the drive's fast step
 *   ftmTimerISR       -> qfoc_s32k_ftm_isr()      PWM period count (overflow or reload,
 *                                                 formerly ftm_INT_option_t)
 *   Ms_1_job ...      -> qfoc_s32k_tick_isr()     the drive's tick, status, CAN, watchdog
 *   InCom_Uart_Drive  -> qfoc_s32k_uart_isr()     LIN-style frames in and out
 *
 * Every function returning int32_t returns QFOC_S32K_OK (0) or a negative status
 * through a single exit; a bounded wait that times out (an oscillator that does not
 * start, a peripheral that does not acknowledge) returns QFOC_S32K_ERR_TIMEOUT and the
 * caller (main.c) keeps the outputs off.
 *
 * Single-shunt current sensing (include/qfoc/shunt.h) replaces qfoc_s32k_pins_init,
 * qfoc_s32k_pdb_init, qfoc_s32k_adc_init, qfoc_s32k_ftm_init and qfoc_s32k_hal_init with
 * their *_shunt twins, in the same order; the samples are then read with
 * qfoc_hal_adc_read_shunt() and the PWM written with qfoc_hal_pwm_write_shunt() (main.c and
 * isr.c run the two-sensor set-up).
 *
 * Requirements: REQ-PORT-001 .. REQ-PORT-021 (specs/requirements/port.md).
 */
#ifndef QFOC_S32K144_PORT_H
#define QFOC_S32K144_PORT_H

#include <stdint.h>
#include <stdbool.h>
#include "qfoc/drive.h"
#include "qfoc/params.h"

/* ------------------------------------------------------------------ status */
#define QFOC_S32K_OK            ((int32_t)0)
#define QFOC_S32K_ERR_TIMEOUT   ((int32_t)-1)  /**< a bounded wait expired */
#define QFOC_S32K_ERR_PARAM     ((int32_t)-2)  /**< a table does not fit this port */

/* ------------------------------------------------------------------ clocks (RM, SCG chapter, RUN-mode limits) */
/** Crystal on EXTAL/XTAL (PTB7/PTB6): 8 MHz. */
/** SPLL: VCO = 8 MHz / (PREDIV 0 + 1) x (MULT 24 + 16) = 320 MHz (RM range 180..320 MHz). */
#define QFOC_S32K_SPLL_PREDIV   (0u)
#define QFOC_S32K_SPLL_MULT     (24u)
/* SPLL_CLK = VCO / 2 = 160 MHz. */
/** RUN mode: CORE_CLK = SYS_CLK = SPLL / 2 = 80 MHz (limit 80), BUS_CLK = CORE / 2 = 40 MHz
    (limit 48), FLASH_CLK = CORE / 3 = 26.67 MHz (limit 26.67). RCCR holds divide-by minus 1. */
#define QFOC_S32K_DIVCORE       (1u)
#define QFOC_S32K_DIVBUS        (1u)
#define QFOC_S32K_DIVSLOW       (2u)
#define QFOC_S32K_CORE_HZ       (80000000u)
/** Asynchronous peripheral clocks: SPLLDIV1 = 160 / 2 = 80 MHz, SPLLDIV2 = 160 / 4 = 40 MHz,
    SOSCDIV1 = SOSCDIV2 = 8 MHz (xDIV field n divides by 2^(n-1)). */
#define QFOC_S32K_SPLLDIV1_FIELD (2u)
#define QFOC_S32K_SPLLDIV2_FIELD (3u)
#define QFOC_S32K_SOSCDIV1_FIELD (1u)
#define QFOC_S32K_SOSCDIV2_FIELD (1u)
#define QFOC_S32K_SOSCDIV2_HZ   (8000000u)
/** FTM3 counter and PDB counter clock: SYS_CLK = CORE_CLK (FTM CLKS = 01; the PDB runs on
    SYS_CLK). */
#define QFOC_S32K_FTM_HZ        QFOC_S32K_CORE_HZ

/* ------------------------------------------------------------------ PWM (FTM3, RM FlexTimer chapter) */
/** Smallest hardware dead time, FTM clocks: 0.5 us at 80 MHz, whatever the table says. */
#define QFOC_S32K_DEADTIME_MIN  (40u)
/** Largest dead time the DEADTIME register holds: 63 x 16 FTM clocks = 12.6 us. */
#define QFOC_S32K_DEADTIME_MAX  (1008u)
/** Fault input filter, FTM_FLTCTRL[FFVAL] (a filter of a few FTM clocks). */
#define QFOC_S32K_FAULT_FFVAL   (2u)
/** The six PWM outputs (FTM3 CH0..CH5) in FTM_OUTMASK / FTM_SC[PWMENn]. */
#define QFOC_S32K_PWM_CH_MASK   ((uint32_t)0x3Fu)

/** Which FTM3 interrupt marks the PWM period (formerly ftm_INT_option_t). */
typedef enum {
    QFOC_S32K_FTM_INT_OVF = 0,     /**< counter overflow (TOF, FTM_SC[TOIE]) */
    QFOC_S32K_FTM_INT_RELOAD = 1   /**< reload point at MOD (RF, FTM_SC[RIE]) */
} qfoc_s32k_ftm_int_t;

/** PWM set-up derived from the parameter table. */
typedef struct {
    uint16_t period;             /**< FTM_MOD = svpwm.period, ticks of the up-down counter */
    uint16_t deadtime_ticks;     /**< dead time in FTM clocks, 2 x svpwm.dt_comp, floored */
    qfoc_s32k_ftm_int_t int_option; /**< period interrupt */
} qfoc_s32k_pwm_cfg_t;

/* ------------------------------------------------------------------ pins (LQFP100 S32K144, RM "IO signal table") */
/* FTM3 CH0 PTB8  ALT2 (U high)     FTM3 CH1 PTB9  ALT2 (U low)
   FTM3 CH2 PTB10 ALT2 (V high)     FTM3 CH3 PTB11 ALT2 (V low)
   FTM3 CH4 PTC10 ALT2 (W high)     FTM3 CH5 PTC11 ALT2 (W low)
   FTM3_FLT0 PTE7 ALT3 (over-current comparator, active low, pull-up)
   LPUART1_RX PTC6 ALT2, LPUART1_TX PTC7 ALT2 (LIN transceiver)
   CAN0_RX PTE4 ALT5, CAN0_TX PTE5 ALT5
   ADC0_SE3  PTA7  ALT0: phase current u     ADC1_SE2 PTD2  ALT0: phase current v
   ADC0_SE12 PTC14 ALT0: IPM NTC             ADC1_SE7 PTB12 ALT0: PCB NTC
   ADC1_SE8  PTB13 ALT0: DC-bus voltage
   ADC0_SE13 PTC15 ALT0: DC-link shunt amplifier (single-shunt set-up only)
   PTD5 ALT1 GPIO output: gate-driver enable (high = enabled) */
#define QFOC_S32K_ADC0_CH_IU    (3u)
#define QFOC_S32K_ADC0_CH_TIPM  (12u)
#define QFOC_S32K_ADC1_CH_IV    (2u)
#define QFOC_S32K_ADC1_CH_TPCB  (7u)
#define QFOC_S32K_ADC1_CH_VDC   (8u)
#define QFOC_S32K_ADC0_CH_IDC   (13u)
#define QFOC_S32K_GATE_EN_PIN   (5u)   /* PTD5 */
/** ADC sample time: CFG2[SMPLTS] + 1 = 13 ADC clocks = 325 ns at 40 MHz. */
#define QFOC_S32K_ADC_SMPLTS    (12u)

/* ------------------------------------------------------------------ single-shunt sensing (the *_shunt set-up) */
/* FTM3 counts up (CPWMS = 0, combine mode) from CNTIN = 0 to MOD = 2 period - 1: one PWM
   period of 2 period clocks, the frequency of the up-down counter with MOD = period.  A
   counter value n of shunt.h's up-counting half is the FTM counter c = n (0 .. period), one
   of its down-counting half c = 2 period - n; phase k is high for period - up[k] <= c <
   period + down[k]: C(2k)V = period - up[k], C(2k+1)V = period + down[k].  The period starts
   at CNTIN, where the initialization trigger starts PDB0 on the same 80 MHz clock
   (QFOC_S32K_FTM_HZ): a sampling instant trig (a counter value of the up-counting half) is
   the PDB delay trig, in PDB clocks. */
/** Q15 counts of the current base per ADC code of the DC-link samples: (code - offset) x
    I_base / 2048, the scaling of the drive's phase currents (drive.h). */
#define QFOC_S32K_I_PER_CODE    ((int32_t)16)
/** Sampling instants after set-up and in a period without a usable plan, counter values:
    period / QFOC_S32K_SHUNT_IDLE_DIV0 and period / QFOC_S32K_SHUNT_IDLE_DIV1 (apart by
    more than a conversion, both before the centre, where ADC1 starts). */
#define QFOC_S32K_SHUNT_IDLE_DIV0 (4u)
#define QFOC_S32K_SHUNT_IDLE_DIV1 (2u)

/* ------------------------------------------------------------------ NTC (both temperature channels) */
/** NTC 10 kOhm at 25 degC, B25/85 = 3435 K, to ground; 10 kOhm pull-up to VREFH:
    code = 4096 R / (R + 10 kOhm). */
#define QFOC_S32K_NTC_OPEN_CODE (4064u)  /**< above: sensor open (R > 1.27 MOhm, below -68 degC) */
#define QFOC_S32K_TEMP_FAIL     ((int16_t)2000)  /**< above 200 degC and failed sensors: 200.0 degC */
#define QFOC_S32K_TEMP_MIN      ((int16_t)-400)  /**< below -40 degC: -40.0 degC */

/* ------------------------------------------------------------------ link */
#define QFOC_S32K_LIN_BAUD      (19200u)
#define QFOC_S32K_LIN_OSR       (15u)    /* oversampling OSR + 1 = 16 */
/** CAN bit timing, 500 kbit/s at 8 MHz (SOSCDIV2): PRESDIV 0 -> 8 MHz time quanta, 16 tq per bit:
    SYNC 1 + PROPSEG 8 + PSEG1 5 + PSEG2 2 = 16; sample point 14 / 16 = 87.5 %; RJW 2.
    Fields hold tq - 1. */
#define QFOC_S32K_CAN_PRESDIV   (0u)
#define QFOC_S32K_CAN_PROPSEG   (7u)
#define QFOC_S32K_CAN_PSEG1     (4u)
#define QFOC_S32K_CAN_PSEG2     (1u)
#define QFOC_S32K_CAN_RJW       (1u)
/** The transmit message buffer. */
#define QFOC_S32K_CAN_TX_MB     (0u)

/* ------------------------------------------------------------------ time base and watchdog */
/** LPIT0 channel 0 at SOSCDIV2 = 8 MHz: TVAL = 8 MHz x 1 ms - 1 = 7999. */
#define QFOC_S32K_TICK_TVAL     (7999u)
/** Watchdog on the 128 kHz LPO: 10 ms timeout = 1280 counts. */
#define QFOC_S32K_WDOG_LPO_HZ   (128000u)
#define QFOC_S32K_WDOG_TIMEOUT_MS (10u)

/* ------------------------------------------------------------------ interrupts (4 priority bits, 0 = highest) */
#define QFOC_S32K_PRIO_ADC      (1u)   /**< fast step: highest */
#define QFOC_S32K_PRIO_FTM      (2u)   /**< PWM period count */
#define QFOC_S32K_PRIO_TICK     (3u)   /**< 1 ms tick */
#define QFOC_S32K_PRIO_UART     (4u)   /**< communication: lowest */
/** ADC-complete chain supervision: a fault when, within one millisecond, more than this
    many PWM periods passed without a fast step. */
#define QFOC_S32K_MISSED_STEPS_MAX (2u)

/* ------------------------------------------------------------------ bounded waits */
/** Polls of a status bit before a wait gives up (several ms at 48..80 MHz). */
#define QFOC_S32K_WAIT_POLLS    (200000u)

/* ------------------------------------------------------------------ set-up (mcu.c) */

/** McuclockConfig: SOSC, SPLL, RUN-mode dividers; REQ-PORT-002. */
int32_t qfoc_s32k_clock_init(void);
/** McuPowerConfig: RUN mode, HSRUN and VLP modes refused until reset; REQ-PORT-002. */
int32_t qfoc_s32k_power_init(void);
/** McuPinsConfig: port clocks and pin functions, gate driver disabled; REQ-PORT-004. */
void qfoc_s32k_pins_init(void);
/** McuPinsConfig for single-shunt sensing: qfoc_s32k_pins_init() and the DC-link shunt
    amplifier's input PTC15 (ADC0_SE13) analog; REQ-PORT-020. */
void qfoc_s32k_pins_init_shunt(void);
/** McuTrigmuxConfig: FTM3 initialization trigger to PDB0 and PDB1, locked; REQ-PORT-009. */
void qfoc_s32k_trgmux_init(void);
/** McuPdbConfig: one-shot PDBs, pre-trigger 0 at the centre, the rest back to back;
    @param period FTM_MOD of the PWM; REQ-PORT-009. */
void qfoc_s32k_pdb_init(uint16_t period);
/** McuPdbConfig for single-shunt sensing: PDB0 pre-triggers 0 and 1 after their delays
    CH0DLY0, CH0DLY1 (the two DC-link samples, set each period by
    qfoc_hal_pwm_write_shunt(), loaded when the counter reaches MOD), pre-trigger 2 back to
    back (T_IPM); PDB1 as qfoc_s32k_pdb_init();
    @param period the PWM period (FTM3 counts 2 period clocks); REQ-PORT-020. */
void qfoc_s32k_pdb_init_shunt(uint16_t period);
/** McuAdcConfig: ADC0/ADC1 clocks, calibration, 12 bit, hardware trigger, channels;
    REQ-PORT-009. */
int32_t qfoc_s32k_adc_init(void);
/** McuAdcConfig for single-shunt sensing: qfoc_s32k_adc_init(), then ADC0 converts
    ADC0_SE13 (SC1A, SC1B: the two DC-link samples) and T_IPM (SC1C); ADC1 unchanged;
    REQ-PORT-020. */
int32_t qfoc_s32k_adc_init_shunt(void);
/** McuUartConfig: LPUART1 19200 8N1, LIN break and idle detection, interrupts;
    REQ-PORT-011. */
void qfoc_s32k_uart_init(void);
/** McuFtmConfig: FTM3 six-channel complementary centre-aligned PWM, hardware dead time,
    fault control, outputs masked; REQ-PORT-005, -006, -007. */
void qfoc_s32k_ftm_init(const qfoc_s32k_pwm_cfg_t *cfg);
/** McuFtmConfig for single-shunt sensing: as qfoc_s32k_ftm_init() (dead time, fault
    control, synchronized loading at the reload point at MOD, outputs masked) but counting
    up from 0 to MOD = 2 cfg->period - 1 with the three pairs combined, so that the edges
    of the two halves of the period are set apart (C(2k)V, C(2k+1)V); 50 % at start;
    REQ-PORT-020. */
void qfoc_s32k_ftm_init_shunt(const qfoc_s32k_pwm_cfg_t *cfg);
/** The PWM set-up a parameter table asks for: period, dead time (floored to
    QFOC_S32K_DEADTIME_MIN, capped to QFOC_S32K_DEADTIME_MAX);
    @return QFOC_S32K_ERR_PARAM when the table's period and PWM frequency do not match
    the FTM clock (2 x period x f_pwm != 80 MHz) or the period does not fit the PDB;
    REQ-PORT-005, -006. */
int32_t qfoc_s32k_pwm_cfg(const qfoc_param_table_t *table, qfoc_s32k_ftm_int_t int_option,
                          qfoc_s32k_pwm_cfg_t *cfg);
/** McuCANConfig: FlexCAN0 500 kbit/s, MB0 transmit; REQ-PORT-012. */
int32_t qfoc_s32k_can_init(void);
/** The 1 ms time base (LPIT0 channel 0); REQ-PORT-013. */
void qfoc_s32k_tick_init(void);
/** The watchdog: 10 ms on the LPO, configuration locked until reset; REQ-PORT-014. */
int32_t qfoc_s32k_wdog_init(void);
/** intenable: NVIC priorities, pending flags cleared, enables; REQ-PORT-015.
    Interrupts stay globally masked until qfoc_s32k_irq_global_enable(). */
void qfoc_s32k_irq_init(void);
/** Gate-driver enable pin PTD5 (true = driver enabled); REQ-PORT-004. */
void qfoc_s32k_gate_enable(bool on);

/* ------------------------------------------------------------------ core instructions (cpu.c) */
/* One function per instruction, the port's only inline assembly (Dir 4.3). */

/** Unmask interrupts (CPSIE i); REQ-PORT-015. */
void qfoc_s32k_irq_global_enable(void);
/** Mask interrupts (CPSID i); REQ-PORT-015. */
void qfoc_s32k_irq_global_disable(void);
/** Sleep until an interrupt is pending (WFI): the idle loop of main(); target only. */
void qfoc_s32k_wait_for_interrupt(void);
/** Data synchronization barrier (DSB); target only. */
void qfoc_s32k_data_sync_barrier(void);
/** Instruction synchronization barrier (ISB): after a system register write such as CPACR
    (FPU enable, startup.c); target only. */
void qfoc_s32k_instruction_sync_barrier(void);

/* ------------------------------------------------------------------ runtime (hal_s32k.c) */

/** Reset the HAL's run-time state for a PWM period (called once after qfoc_s32k_ftm_init). */
void qfoc_s32k_hal_init(uint16_t period);
/** Reset the HAL's run-time state for single-shunt sensing (called once after
    qfoc_s32k_ftm_init_shunt): compare values written to the combined pairs, sampling
    instants to PDB0, DC-link offset QFOC_ADC_MID; REQ-PORT-020, REQ-PORT-021. */
void qfoc_s32k_hal_init_shunt(uint16_t period);
/** The ADC code of zero DC-link current (codes above 4095 are taken as 4095), used by
    qfoc_hal_adc_read_shunt() from the next call on; REQ-PORT-021. */
void qfoc_s32k_shunt_offset_set(uint16_t code);
/** NTC code (12 bit) to 0.1 degC, REQ-PORT-010. */
int16_t qfoc_s32k_ntc_to_dc(uint16_t code);
/** FTM3 period interrupt flags (TOF, RF) cleared, PWM period counted; REQ-PORT-018. */
void qfoc_s32k_ftm_period_ack(void);
/** Received frames dropped (errors, echo, overlong, not taken in time), saturating. */
uint16_t qfoc_s32k_lin_dropped(void);

/* ------------------------------------------------------------------ interrupts (isr.c) */

/** The drive the interrupts run (NULL: the handlers only acknowledge their flags). */
void qfoc_s32k_isr_bind(qfoc_drive_t *drive);
/** ADC1 conversion complete (adc1isr): samples -> fast step -> PWM; REQ-PORT-016. */
void qfoc_s32k_adc_isr(void);
/** FTM3 overflow / reload (ftmTimerISR): count PWM periods; REQ-PORT-018. */
void qfoc_s32k_ftm_isr(void);
/** LPIT0 channel 0, every 1 ms: the drive's tick, frames, watchdog; REQ-PORT-017. */
void qfoc_s32k_tick_isr(void);
/** LPUART1 receive / transmit; REQ-PORT-011. */
void qfoc_s32k_uart_isr(void);
/** Fast steps run since start (supervision and tests). */
uint32_t qfoc_s32k_fast_steps(void);
/** Status frames the UART refused since qfoc_s32k_isr_bind() (the previous frame was still
    being sent: the frame is dropped, the master polls again), saturating at 65535;
    REQ-PORT-017. */
uint16_t qfoc_s32k_lin_tx_refused(void);
/** CAN frames the controller refused since qfoc_s32k_isr_bind() (the previous frame was
    still pending: the frame is dropped, the next follows 100 ms later), saturating at
    65535; REQ-PORT-017. */
uint16_t qfoc_s32k_can_tx_refused(void);

/* ------------------------------------------------------------------ reset (reset.S, startup.c) */
/** The reset vector, defined in the assembly module reset.S (it runs before any stack
    exists): an identifier defined outside C, deviation DEV-004 (Rule 8.6).  The vector
    table (startup.c) holds it and the four interrupt functions above: IRQ 33 LPUART1
    qfoc_s32k_uart_isr, IRQ 40 ADC1 qfoc_s32k_adc_isr, IRQ 48 LPIT0 channel 0
    qfoc_s32k_tick_isr, IRQ 122 FTM3 overflow/reload qfoc_s32k_ftm_isr. */
/* cppcheck-suppress misra-c2012-8.6 ; DEV-004 */
void Reset_Handler(void);

#endif /* QFOC_S32K144_PORT_H */
