/**
 * @file mcu.c
 * @brief S32K144 set-up: clocks, power mode, pins, trigger chain, PDB, ADC, UART, PWM,
 *        CAN, time base, watchdog and interrupt priorities (formerly McuXxxConfig, specs/equations.md section 8
 *        functions and intenable).  Register facts: s32k144_regs.h (S32K1xx RM Rev. 13).
 *
 * Every register is reached through s32k_read/s32k_write/s32k_modify (one accessor).
 * Waits on hardware status bits are bounded (QFOC_S32K_WAIT_POLLS) and report a timeout.
 *
 * Requirements: REQ-PORT-001 .. REQ-PORT-015, REQ-PORT-020 (specs/requirements/port.md).
 */
#include "s32k144_port.h"
#include "s32k144_regs.h"

/* Register fields whose configured value is zero are not written (they stay 0 from the
   register write that sets the other fields; MISRA C:2012 Rule 2.2: no operation without
   effect); the code relies on these values being zero: */
#if (QFOC_S32K_SPLL_PREDIV != 0u)
#error "SCG_SPLLCFG[PREDIV] is left 0 in qfoc_s32k_clock_init(): write the field"
#endif
#if (QFOC_S32K_CAN_PRESDIV != 0u)
#error "CAN0_CTRL1[PRESDIV] is left 0 in qfoc_s32k_can_init(): write the field"
#endif
#if (QFOC_S32K_CAN_TX_MB != 0u)
#error "the port transmits from MB0 only (S32K_CAN0_MB0_*, MCR[MAXMB] 0)"
#endif

/* Poll until (register & mask) == value, at most QFOC_S32K_WAIT_POLLS reads. */
static bool s32k_wait(uint32_t addr, uint32_t mask, uint32_t value)
{
    uint32_t n = 0u;
    bool done = false;
    while ((!done) && (n < QFOC_S32K_WAIT_POLLS)) {
        done = ((s32k_read(addr) & mask) == value);
        n++;
    }
    return done;
}

/* Gate a peripheral's clock with its functional clock source: PCS may only change while
   CGC = 0 (RM, PCC chapter: PCS can only be written while CGC is 0). */
static void s32k_pcc_enable(uint32_t pcc, uint32_t pcs)
{
    const uint32_t src = s32k_fld(pcs, S32K_PCC_PCS_SHIFT, S32K_PCC_PCS_MASK);
    s32k_write(pcc, 0u);
    s32k_write(pcc, src);
    s32k_write(pcc, src | S32K_PCC_CGC);
}

/* ------------------------------------------------------------------ clock and power */

int32_t qfoc_s32k_clock_init(void)
{
    int32_t status = QFOC_S32K_OK;
    const uint32_t scs = s32k_fld(S32K_SCG_SCS_SPLL, S32K_SCG_SCS_SHIFT, S32K_SCG_SCS_MASK);

    /* SOSC: 8 MHz crystal, medium range (RANGE = 2, 4..8 MHz), low gain; both dividers
       /1 (SOSCDIV2 clocks the UART, the CAN engine and the time base). */
    s32k_write(S32K_SCG_SOSCCSR, 0u);
    s32k_write(S32K_SCG_SOSCDIV,
               s32k_fld(QFOC_S32K_SOSCDIV1_FIELD, S32K_SCG_DIV1_SHIFT, S32K_SCG_DIV1_MASK) |
               s32k_fld(QFOC_S32K_SOSCDIV2_FIELD, S32K_SCG_DIV2_SHIFT, S32K_SCG_DIV2_MASK));
    s32k_write(S32K_SCG_SOSCCFG,
               s32k_fld(2u, S32K_SCG_SOSCCFG_RANGE_SHIFT, S32K_SCG_SOSCCFG_RANGE_MASK) |
               S32K_SCG_SOSCCFG_EREFS);
    s32k_write(S32K_SCG_SOSCCSR, S32K_SCG_XCSR_EN);
    if (!s32k_wait(S32K_SCG_SOSCCSR, S32K_SCG_XCSR_VLD, S32K_SCG_XCSR_VLD)) {
        status = QFOC_S32K_ERR_TIMEOUT;
    } else {
        /* SPLL: VCO = 8 MHz / 1 x 40 = 320 MHz, SPLL_CLK 160 MHz; SPLLDIV1 /2 = 80 MHz,
           SPLLDIV2 /4 = 40 MHz (ADC clock).  PREDIV left 0 (QFOC_S32K_SPLL_PREDIV:
           divide by 1). */
        s32k_write(S32K_SCG_SPLLCSR, 0u);
        s32k_write(S32K_SCG_SPLLDIV,
                   s32k_fld(QFOC_S32K_SPLLDIV1_FIELD, S32K_SCG_DIV1_SHIFT, S32K_SCG_DIV1_MASK) |
                   s32k_fld(QFOC_S32K_SPLLDIV2_FIELD, S32K_SCG_DIV2_SHIFT, S32K_SCG_DIV2_MASK));
        s32k_write(S32K_SCG_SPLLCFG,
                   s32k_fld(QFOC_S32K_SPLL_MULT, S32K_SCG_MULT_SHIFT, S32K_SCG_MULT_MASK));
        s32k_write(S32K_SCG_SPLLCSR, S32K_SCG_XCSR_EN);
        if (!s32k_wait(S32K_SCG_SPLLCSR, S32K_SCG_XCSR_VLD, S32K_SCG_XCSR_VLD)) {
            status = QFOC_S32K_ERR_TIMEOUT;
        } else {
            /* RUN mode from the SPLL: core 80 MHz, bus 40 MHz, flash 26.67 MHz. */
            s32k_write(S32K_SCG_RCCR, scs |
                       s32k_fld(QFOC_S32K_DIVCORE, S32K_SCG_DIVCORE_SHIFT, S32K_SCG_DIVCORE_MASK) |
                       s32k_fld(QFOC_S32K_DIVBUS, S32K_SCG_DIVBUS_SHIFT, S32K_SCG_DIVBUS_MASK) |
                       s32k_fld(QFOC_S32K_DIVSLOW, S32K_SCG_DIVSLOW_SHIFT, S32K_SCG_DIVSLOW_MASK));
            if (!s32k_wait(S32K_SCG_CSR, S32K_SCG_SCS_MASK, scs)) {
                status = QFOC_S32K_ERR_TIMEOUT;
            } else {
                /* running from the SPLL */
            }
        }
    }
    return status;
}

int32_t qfoc_s32k_power_init(void)
{
    int32_t status = QFOC_S32K_OK;
    /* PMPROT is write-once after reset: 0 refuses HSRUN (AHSRUN) and VLPR/VLPS (AVLP), so
       no later write can leave the 80 MHz RUN mode the clock tree is set up for. */
    s32k_write(S32K_SMC_PMPROT, 0u);
    s32k_modify(S32K_SMC_PMCTRL, S32K_SMC_PMCTRL_RUNM_MASK, 0u);
    if (!s32k_wait(S32K_SMC_PMSTAT, 0xFFu, S32K_SMC_PMSTAT_RUN)) {
        status = QFOC_S32K_ERR_TIMEOUT;
    } else {
        /* in RUN */
    }
    return status;
}

/* ------------------------------------------------------------------ pins */

static void s32k_pin_mux(uint32_t port_base, uint32_t pin, uint32_t alt, uint32_t extra)
{
    s32k_write(port_base + (4u * pin), s32k_fld(alt, S32K_PCR_MUX_SHIFT, S32K_PCR_MUX_MASK) | extra);
}

void qfoc_s32k_pins_init(void)
{
    s32k_pcc_enable(S32K_PCC_PORTA, 0u);
    s32k_pcc_enable(S32K_PCC_PORTB, 0u);
    s32k_pcc_enable(S32K_PCC_PORTC, 0u);
    s32k_pcc_enable(S32K_PCC_PORTD, 0u);
    s32k_pcc_enable(S32K_PCC_PORTE, 0u);

    /* Gate-driver enable PTD5: output, low (driver off) before any PWM pin is muxed. */
    s32k_write(S32K_GPIOD_PCOR, (uint32_t)1u << QFOC_S32K_GATE_EN_PIN);
    s32k_modify(S32K_GPIOD_PDDR, 0u, (uint32_t)1u << QFOC_S32K_GATE_EN_PIN);
    s32k_pin_mux(S32K_PORTD_BASE, QFOC_S32K_GATE_EN_PIN, 1u, 0u);

    /* FTM3 CH0..CH3 on PTB8..PTB11, CH4/CH5 on PTC10/PTC11: ALT2. */
    s32k_pin_mux(S32K_PORTB_BASE, 8u, 2u, 0u);
    s32k_pin_mux(S32K_PORTB_BASE, 9u, 2u, 0u);
    s32k_pin_mux(S32K_PORTB_BASE, 10u, 2u, 0u);
    s32k_pin_mux(S32K_PORTB_BASE, 11u, 2u, 0u);
    s32k_pin_mux(S32K_PORTC_BASE, 10u, 2u, 0u);
    s32k_pin_mux(S32K_PORTC_BASE, 11u, 2u, 0u);
    /* FTM3_FLT0 on PTE7 ALT3, pull-up (open-drain comparator, active low). */
    s32k_pin_mux(S32K_PORTE_BASE, 7u, 3u, S32K_PCR_PE | S32K_PCR_PS);
    /* LPUART1 RX PTC6, TX PTC7: ALT2; RX pulled up (recessive LIN level). */
    s32k_pin_mux(S32K_PORTC_BASE, 6u, 2u, S32K_PCR_PE | S32K_PCR_PS);
    s32k_pin_mux(S32K_PORTC_BASE, 7u, 2u, 0u);
    /* CAN0 RX PTE4, TX PTE5: ALT5. */
    s32k_pin_mux(S32K_PORTE_BASE, 4u, 5u, 0u);
    s32k_pin_mux(S32K_PORTE_BASE, 5u, 5u, 0u);
    /* Analog inputs: ALT0 (pin disabled, analog path). */
    s32k_pin_mux(S32K_PORTA_BASE, 7u, 0u, 0u);   /* ADC0_SE3  i_u */
    s32k_pin_mux(S32K_PORTC_BASE, 14u, 0u, 0u);  /* ADC0_SE12 T_IPM */
    s32k_pin_mux(S32K_PORTD_BASE, 2u, 0u, 0u);   /* ADC1_SE2  i_v */
    s32k_pin_mux(S32K_PORTB_BASE, 12u, 0u, 0u);  /* ADC1_SE7  T_PCB */
    s32k_pin_mux(S32K_PORTB_BASE, 13u, 0u, 0u);  /* ADC1_SE8  V_dc */
}

void qfoc_s32k_pins_init_shunt(void)
{
    qfoc_s32k_pins_init();
    s32k_pin_mux(S32K_PORTC_BASE, 15u, 0u, 0u);  /* ADC0_SE13 i_dc (DC-link shunt amplifier) */
}

void qfoc_s32k_gate_enable(bool on)
{
    const uint32_t bit = (uint32_t)1u << QFOC_S32K_GATE_EN_PIN;
    if (on) {
        s32k_write(S32K_GPIOD_PSOR, bit);
    } else {
        s32k_write(S32K_GPIOD_PCOR, bit);
    }
}

/* ------------------------------------------------------------------ trigger chain */

void qfoc_s32k_trgmux_init(void)
{
    /* PDB0 and PDB1 trigger input 0 = FTM3 initialization trigger (counter at CNTIN);
       locked so that no later write can detach the current sampling from the PWM. */
    s32k_write(S32K_TRGMUX_PDB0, (S32K_TRGMUX_SRC_FTM3_INIT & S32K_TRGMUX_SEL0_MASK) | S32K_TRGMUX_LK);
    s32k_write(S32K_TRGMUX_PDB1, (S32K_TRGMUX_SRC_FTM3_INIT & S32K_TRGMUX_SEL0_MASK) | S32K_TRGMUX_LK);
}

/* One PDB: one-shot per trigger (CONT = 0), SYS_CLK / 1, trigger input 0; pre-trigger 0
   after `period` clocks (the counter at MOD: centre of the zero vector with all low-side
   switches on), pre-triggers 1 .. n-1 back to back after the previous conversion. */
static void s32k_pdb_setup(uint32_t base, uint32_t n_pretriggers, uint16_t period)
{
    const uint32_t en = ((uint32_t)1u << n_pretriggers) - 1u;
    const uint32_t bb = en & ~(uint32_t)1u;
    s32k_pcc_enable((base == S32K_PDB0_BASE) ? S32K_PCC_PDB0 : S32K_PCC_PDB1, 0u);
    s32k_write(base + S32K_PDB_SC, S32K_PDB_SC_PDBEN);
    s32k_write(base + S32K_PDB_MOD, (2u * (uint32_t)period) - 1u);
    s32k_write(base + S32K_PDB_IDLY, 0u);
    s32k_write(base + S32K_PDB_CH0C1, (en << S32K_PDB_C1_EN_SHIFT) |
                                      ((uint32_t)1u << S32K_PDB_C1_TOS_SHIFT) |
                                      (bb << S32K_PDB_C1_BB_SHIFT));
    s32k_write(base + S32K_PDB_CH0DLY0, (uint32_t)period);
    s32k_write(base + S32K_PDB_CH0S, 0u);   /* no stale sequence-error flag */
    s32k_write(base + S32K_PDB_SC, S32K_PDB_SC_PDBEN | S32K_PDB_SC_LDOK);
}

void qfoc_s32k_pdb_init(uint16_t period)
{
    s32k_pdb_setup(S32K_PDB0_BASE, 2u, period);   /* ADC0: i_u, T_IPM */
    s32k_pdb_setup(S32K_PDB1_BASE, 3u, period);   /* ADC1: i_v, T_PCB, V_dc */
}

/* Single-shunt sensing.  FTM3 counts up from 0 (CNTIN, the initialization trigger) to
   2 period - 1, so the PDB counter (SYS_CLK / 1, the FTM3 clock) equals the FTM3 counter
   and a sampling instant of qfoc_shunt_plan_t (a counter value of the up-counting half,
   0 .. period - 1) is its PDB delay as it stands.  PDB0 channel 0 (ADC0): pre-trigger 0
   after CH0DLY0 (first DC-link sample, ADC0 SC1A), pre-trigger 1 after CH0DLY1 (second
   sample, SC1B), pre-trigger 2 back to back after the second conversion (T_IPM, SC1C).
   The delays are loaded at once here, then (LDMOD = 01) each time the counter reaches MOD =
   2 period - 1 after an LDOK: the delays qfoc_hal_pwm_write_shunt() writes in period k
   load at the end of period k, with the compare values (the FTM's reload point is the
   counter at its MOD, the same clock), and are used in period k + 1.  PDB1 (ADC1: i_v,
   T_PCB, V_dc after `period` clocks, the centre) as in qfoc_s32k_pdb_init(): its last
   conversion raises the ADC1 interrupt after the three ADC1 conversions from the centre,
   later than the end of ADC0's two conversions that follow the second sample (before
   the centre). */
void qfoc_s32k_pdb_init_shunt(uint16_t period)
{
    const uint32_t p = (uint32_t)period;
    const uint32_t ldmod = s32k_fld(S32K_PDB_LDMOD_AT_MOD, S32K_PDB_SC_LDMOD_SHIFT, S32K_PDB_SC_LDMOD_MASK);
    s32k_pcc_enable(S32K_PCC_PDB0, 0u);
    s32k_write(S32K_PDB0_BASE + S32K_PDB_SC, S32K_PDB_SC_PDBEN);
    s32k_write(S32K_PDB0_BASE + S32K_PDB_MOD, (2u * p) - 1u);
    s32k_write(S32K_PDB0_BASE + S32K_PDB_IDLY, 0u);
    s32k_write(S32K_PDB0_BASE + S32K_PDB_CH0C1, ((uint32_t)0x07u << S32K_PDB_C1_EN_SHIFT) |
                                                ((uint32_t)0x03u << S32K_PDB_C1_TOS_SHIFT) |
                                                ((uint32_t)0x04u << S32K_PDB_C1_BB_SHIFT));
    s32k_write(S32K_PDB0_BASE + S32K_PDB_CH0DLY0, p / QFOC_S32K_SHUNT_IDLE_DIV0);
    s32k_write(S32K_PDB0_BASE + S32K_PDB_CH0DLY0 + 4u, p / QFOC_S32K_SHUNT_IDLE_DIV1);
    s32k_write(S32K_PDB0_BASE + S32K_PDB_CH0S, 0u);   /* no stale sequence-error flag */
    s32k_write(S32K_PDB0_BASE + S32K_PDB_SC, S32K_PDB_SC_PDBEN | S32K_PDB_SC_LDOK);
    s32k_write(S32K_PDB0_BASE + S32K_PDB_SC, S32K_PDB_SC_PDBEN | ldmod);
    s32k_pdb_setup(S32K_PDB1_BASE, 3u, period);       /* ADC1: i_v (not used), T_PCB, V_dc */
}

/* One ADC: functional clock SPLLDIV2 40 MHz, ADICLK = ALTCLK1, /1, 12 bit; calibration
   with 32-sample averaging (RM, ADC chapter, "Calibration function"); then hardware trigger. */
static int32_t s32k_adc_setup(uint32_t base, uint32_t pcc)
{
    int32_t status = QFOC_S32K_OK;
    uint32_t k;
    s32k_pcc_enable(pcc, S32K_PCC_PCS_SPLLDIV);
    s32k_write(base + S32K_ADC_CFG1, S32K_ADC_CFG1_MODE_12);
    s32k_write(base + S32K_ADC_CFG2, QFOC_S32K_ADC_SMPLTS);
    s32k_write(base + S32K_ADC_SC2, 0u);
    for (k = 0u; k < 7u; k++) {
        s32k_write(base + S32K_ADC_CLPS + (4u * k), 0u);  /* CLPS, CLP3..CLP0, CLPX, CLP9 */
    }
    s32k_write(base + S32K_ADC_SC3, S32K_ADC_SC3_CAL | S32K_ADC_SC3_AVGE | S32K_ADC_SC3_AVGS_32);
    if (!s32k_wait(base + S32K_ADC_SC1A, S32K_ADC_SC1_COCO, S32K_ADC_SC1_COCO)) {
        status = QFOC_S32K_ERR_TIMEOUT;
    } else {
        (void)s32k_read(base + S32K_ADC_RA);  /* clears COCO */
    }
    s32k_write(base + S32K_ADC_SC3, 0u);                  /* single conversions */
    s32k_write(base + S32K_ADC_SC2, S32K_ADC_SC2_ADTRG);  /* triggered by the PDB */
    return status;
}

int32_t qfoc_s32k_adc_init(void)
{
    int32_t status;
    int32_t status1;
    s32k_write(S32K_SIM_ADCOPT, 0u);  /* triggers and pre-triggers from PDB0 / PDB1 */
    status = s32k_adc_setup(S32K_ADC0_BASE, S32K_PCC_ADC0);
    status1 = s32k_adc_setup(S32K_ADC1_BASE, S32K_PCC_ADC1);
    /* SC1n selects the channel of pre-trigger n. */
    s32k_write(S32K_ADC0_BASE + S32K_ADC_SC1A, QFOC_S32K_ADC0_CH_IU & S32K_ADC_SC1_ADCH_MASK);
    s32k_write(S32K_ADC0_BASE + S32K_ADC_SC1A + 4u, QFOC_S32K_ADC0_CH_TIPM & S32K_ADC_SC1_ADCH_MASK);
    s32k_write(S32K_ADC1_BASE + S32K_ADC_SC1A, QFOC_S32K_ADC1_CH_IV & S32K_ADC_SC1_ADCH_MASK);
    s32k_write(S32K_ADC1_BASE + S32K_ADC_SC1A + 4u, QFOC_S32K_ADC1_CH_TPCB & S32K_ADC_SC1_ADCH_MASK);
    /* The last conversion of the sequence (ADC1, pre-trigger 2) raises the interrupt;
       ADC0's two conversions are complete by then. */
    s32k_write(S32K_ADC1_BASE + S32K_ADC_SC1A + 8u,
               (QFOC_S32K_ADC1_CH_VDC & S32K_ADC_SC1_ADCH_MASK) | S32K_ADC_SC1_AIEN);
    if (status1 != QFOC_S32K_OK) {
        status = status1;
    } else {
        /* status of ADC0 */
    }
    return status;
}

int32_t qfoc_s32k_adc_init_shunt(void)
{
    const int32_t status = qfoc_s32k_adc_init();
    /* ADC0: the DC-link shunt amplifier (ADC0_SE13, PTC15) for pre-triggers 0 and 1, then
       T_IPM; ADC1 keeps i_v (not read), T_PCB and V_dc with the interrupt. */
    s32k_write(S32K_ADC0_BASE + S32K_ADC_SC1A, QFOC_S32K_ADC0_CH_IDC & S32K_ADC_SC1_ADCH_MASK);
    s32k_write(S32K_ADC0_BASE + S32K_ADC_SC1A + 4u, QFOC_S32K_ADC0_CH_IDC & S32K_ADC_SC1_ADCH_MASK);
    s32k_write(S32K_ADC0_BASE + S32K_ADC_SC1A + 8u, QFOC_S32K_ADC0_CH_TIPM & S32K_ADC_SC1_ADCH_MASK);
    return status;
}

/* ------------------------------------------------------------------ UART */

/* LPUART1 baud-rate divisor: baud = f / ((OSR + 1) x SBR) (RM, LPUART chapter, "Baud
   rate generation"), so SBR = f / (16 x 19200) = 26.04 -> 26 (rounded to nearest):
   19230.8 baud, +0.16 %. */
#define QFOC_S32K_LIN_SBR_DEN ((QFOC_S32K_LIN_OSR + 1u) * QFOC_S32K_LIN_BAUD)
#define QFOC_S32K_LIN_SBR     ((QFOC_S32K_SOSCDIV2_HZ + (QFOC_S32K_LIN_SBR_DEN / 2u)) / QFOC_S32K_LIN_SBR_DEN)
#if (QFOC_S32K_LIN_SBR < 1u) || (QFOC_S32K_LIN_SBR > 0x1FFFu)
#error "LPUART1 SBR out of its 13-bit range"
#endif

void qfoc_s32k_uart_init(void)
{
    s32k_pcc_enable(S32K_PCC_LPUART1, S32K_PCC_PCS_SOSCDIV);
    s32k_write(S32K_LPUART1_CTRL, 0u);  /* transmitter and receiver off while configuring */
    s32k_write(S32K_LPUART1_BAUD,
               s32k_fld(QFOC_S32K_LIN_OSR, S32K_LPUART_BAUD_OSR_SHIFT, S32K_LPUART_BAUD_OSR_MASK) |
               S32K_LPUART_BAUD_LBKDIE | (QFOC_S32K_LIN_SBR & S32K_LPUART_BAUD_SBR_MASK));
    /* LIN break detection on, 13-bit breaks sent (LIN 2.x: at least 13 dominant bits);
       every flag cleared. */
    s32k_write(S32K_LPUART1_STAT, S32K_LPUART_STAT_LBKDE | S32K_LPUART_STAT_BRK13 |
                                  S32K_LPUART_STAT_W1C);
    /* 8N1 (M = 0, PE = 0), idle after 2 characters counted from the stop bit, receive
       and idle interrupts; the transmit interrupts are enabled per frame. */
    s32k_write(S32K_LPUART1_CTRL, S32K_LPUART_CTRL_ILT | S32K_LPUART_CTRL_IDLECFG_2 |
                                  S32K_LPUART_CTRL_RIE | S32K_LPUART_CTRL_ILIE |
                                  S32K_LPUART_CTRL_RE | S32K_LPUART_CTRL_TE);
}

/* ------------------------------------------------------------------ PWM */

static uint32_t s32k_deadtime_reg(uint16_t ticks)
{
    /* Dead time = prescaler x DTVAL FTM clocks, prescaler 1, 4 or 16 (DTPS 0, 2, 3),
       DTVAL 0..63: the smallest prescaler that holds the dead time, DTVAL rounded up so
       the inserted dead time is never shorter than asked (RM, FTM chapter, "Deadtime insertion"). */
    uint32_t t = (uint32_t)ticks;
    uint32_t dtps;
    uint32_t dtval;
    if (t > QFOC_S32K_DEADTIME_MAX) {
        t = QFOC_S32K_DEADTIME_MAX;
    } else {
        /* in range */
    }
    if (t <= 63u) {
        dtps = 0u;
        dtval = t;
    } else if (t <= (63u * 4u)) {
        dtps = 2u;
        dtval = (t + 3u) / 4u;
    } else {
        dtps = 3u;
        dtval = (t + 15u) / 16u;
    }
    return s32k_fld(dtps, S32K_FTM_DT_DTPS_SHIFT, S32K_FTM_DT_DTPS_MASK) |
           (dtval & S32K_FTM_DT_DTVAL_MASK);
}

int32_t qfoc_s32k_pwm_cfg(const qfoc_param_table_t *table, qfoc_s32k_ftm_int_t int_option,
                          qfoc_s32k_pwm_cfg_t *cfg)
{
    int32_t status = QFOC_S32K_OK;
    const uint32_t period = (uint32_t)table->svpwm.period;
    uint32_t dt = 2u * (uint32_t)table->svpwm.dt_comp;
    /* The table's period must be the FTM's: f_FTM = 2 x period x f_pwm (up-down counter).
       The range is checked first: with period <= 32767 the product is below 2^32. */
    if ((period < (uint32_t)QFOC_SVPWM_PERIOD_MIN) || (period > (uint32_t)QFOC_SVPWM_PERIOD_MAX)) {
        status = QFOC_S32K_ERR_PARAM;
    } else if ((2u * period * (uint32_t)table->f_pwm_hz) != QFOC_S32K_FTM_HZ) {
        status = QFOC_S32K_ERR_PARAM;
    } else {
        /* consistent */
    }
    if (dt < QFOC_S32K_DEADTIME_MIN) {
        dt = QFOC_S32K_DEADTIME_MIN;
    } else if (dt > QFOC_S32K_DEADTIME_MAX) {
        dt = QFOC_S32K_DEADTIME_MAX;
    } else {
        /* as the table says */
    }
    cfg->period = (uint16_t)(period & 0xFFFFu);
    cfg->deadtime_ticks = (uint16_t)dt;
    cfg->int_option = int_option;
    return status;
}

/* FTM3 set-up of either sensing: two phase-current sensors (shunt false: up-down
   counting, MOD = period) or the single shunt (shunt true: up counting, MOD = 2 period - 1,
   the three pairs combined). */
static void s32k_ftm_setup(const qfoc_s32k_pwm_cfg_t *cfg, bool shunt)
{
    const uint32_t comb = shunt ? S32K_FTM_COMB_COMBINE : 0u;
    const uint32_t pair = comb | S32K_FTM_COMB_COMP | S32K_FTM_COMB_DTEN | S32K_FTM_COMB_SYNCEN |
                          S32K_FTM_COMB_FAULTEN;
    const uint32_t p = (uint32_t)cfg->period;
    const uint32_t half = p / 2u;
    const uint32_t modulo = shunt ? ((2u * p) - 1u) : p;
    const uint32_t cpwms = shunt ? 0u : S32K_FTM_SC_CPWMS;
    const uint32_t irq = (cfg->int_option == QFOC_S32K_FTM_INT_RELOAD) ? S32K_FTM_SC_RIE : S32K_FTM_SC_TOIE;
    uint32_t ch;

    s32k_pcc_enable(S32K_PCC_FTM3, S32K_PCC_PCS_SPLLDIV);
    s32k_write(S32K_FTM3_MODE, S32K_FTM_MODE_WPDIS | S32K_FTM_MODE_FTMEN);
    s32k_write(S32K_FTM3_SC, 0u);                         /* counter stopped */
    s32k_write(S32K_FTM3_OUTMASK, QFOC_S32K_PWM_CH_MASK); /* all six outputs off */
    s32k_write(S32K_FTM3_CNTIN, 0u);
    s32k_write(S32K_FTM3_MOD, modulo);
    s32k_write(S32K_FTM3_CNT, 0u);                        /* loads CNTIN */
    /* CPWM, high-true (ELSB:ELSA = 10): channel n is high while the counter is below
       CnV, i.e. the high side conducts for 2 CnV of 2 MOD ticks: duty = cmp / period,
       as svpwm.h defines; the odd channel is its complement (COMP) with dead time.
       Combined (shunt): the even channel of pair k is high from the C(2k)V match to the
       C(2k+1)V match (MSnB:MSnA ignored), high for C(2k+1)V - C(2k)V = 2 cmp of 2 period
       ticks: the same duty; 50 % at C(2k)V = period - period / 2, C(2k+1)V = period +
       period / 2. */
    for (ch = 0u; ch < 6u; ch++) {
        uint32_t v = half;
        if (shunt) {
            if ((ch % 2u) == 0u) {
                v = p - half;   /* C(2k)V: set */
            } else {
                v = p + half;   /* C(2k+1)V: clear */
            }
        } else {
            /* every channel at MOD / 2 */
        }
        s32k_write(S32K_FTM3_C0SC + (8u * ch), S32K_FTM_CNSC_MSB | S32K_FTM_CNSC_ELSB);
        s32k_write(S32K_FTM3_C0V + (8u * ch), v);
    }
    s32k_write(S32K_FTM3_COMBINE, pair | (pair << 8u) | (pair << 16u));
    s32k_write(S32K_FTM3_DEADTIME, s32k_deadtime_reg(cfg->deadtime_ticks));
    s32k_write(S32K_FTM3_POL, 0u);                        /* inactive level low = switch off */
    s32k_write(S32K_FTM3_OUTINIT, 0u);
    s32k_write(S32K_FTM3_EXTTRIG, S32K_FTM_EXTTRIG_INITTRIGEN);
    /* Hardware over-current path: fault input 0 (PTE7), active low, filtered; on a fault
       every channel goes to its inactive (safe) level (FSTATE = 0) until software clears
       the flag with the input inactive (FAULTM = 10, manual clearing). */
    s32k_write(S32K_FTM3_FLTPOL, S32K_FTM_FLTPOL_FLT0POL);
    s32k_write(S32K_FTM3_FLTCTRL, S32K_FTM_FLT_FAULT0EN | S32K_FTM_FLT_FFLTR0EN |
               s32k_fld(QFOC_S32K_FAULT_FFVAL, S32K_FTM_FLT_FFVAL_SHIFT, S32K_FTM_FLT_FFVAL_MASK));
    /* Compare values load at the reload point at MOD after LDOK (the sampling instant of
       the two sensors; the end of the period when combined). */
    s32k_write(S32K_FTM3_SYNCONF, S32K_FTM_SYNCONF_SYNCMODE | S32K_FTM_SYNCONF_SWWRBUF);
    s32k_write(S32K_FTM3_SYNC, S32K_FTM_SYNC_CNTMAX);
    s32k_write(S32K_FTM3_PWMLOAD, S32K_FTM_PWMLOAD_LDOK);
    s32k_write(S32K_FTM3_MODE, S32K_FTM_MODE_WPDIS | S32K_FTM_MODE_FTMEN | S32K_FTM_MODE_INIT |
               s32k_fld(2u, S32K_FTM_MODE_FAULTM_SHIFT, S32K_FTM_MODE_FAULTM_MASK));
    (void)s32k_read(S32K_FTM3_FMS);
    s32k_write(S32K_FTM3_FMS, 0u);                        /* no stale fault flag */
    /* Start: FTM input clock (SYS_CLK 80 MHz), /1, up-down (up when combined), six
       outputs, period interrupt. */
    s32k_write(S32K_FTM3_SC, (QFOC_S32K_PWM_CH_MASK << S32K_FTM_SC_PWMEN_SHIFT) |
               cpwms | irq | s32k_fld(1u, S32K_FTM_SC_CLKS_SHIFT, S32K_FTM_SC_CLKS_MASK));
    /* Write protection of the mode, dead time, combine and fault set-up. */
    s32k_write(S32K_FTM3_FMS, S32K_FTM_FMS_WPEN);
}

void qfoc_s32k_ftm_init(const qfoc_s32k_pwm_cfg_t *cfg)
{
    s32k_ftm_setup(cfg, false);
}

void qfoc_s32k_ftm_init_shunt(const qfoc_s32k_pwm_cfg_t *cfg)
{
    s32k_ftm_setup(cfg, true);
}

/* ------------------------------------------------------------------ CAN */

int32_t qfoc_s32k_can_init(void)
{
    int32_t status = QFOC_S32K_OK;
    uint32_t k;
    s32k_pcc_enable(S32K_PCC_FLEXCAN0, 0u);
    /* Clock source may only change while the module is disabled (RM, FlexCAN chapter, CTRL1[CLKSRC]). */
    s32k_modify(S32K_CAN0_MCR, 0u, S32K_CAN_MCR_MDIS);
    if (!s32k_wait(S32K_CAN0_MCR, S32K_CAN_MCR_LPMACK, S32K_CAN_MCR_LPMACK)) {
        status = QFOC_S32K_ERR_TIMEOUT;
    } else {
        /* disabled */
    }
    s32k_modify(S32K_CAN0_CTRL1, S32K_CAN_CTRL1_CLKSRC, 0u);  /* oscillator clock SOSCDIV2 8 MHz */
    s32k_modify(S32K_CAN0_MCR, S32K_CAN_MCR_MDIS, S32K_CAN_MCR_FRZ | S32K_CAN_MCR_HALT);
    if (!s32k_wait(S32K_CAN0_MCR, S32K_CAN_MCR_FRZACK, S32K_CAN_MCR_FRZACK)) {
        status = QFOC_S32K_ERR_TIMEOUT;
    } else {
        /* freeze mode: configuration allowed */
    }
    /* PRESDIV left 0 (QFOC_S32K_CAN_PRESDIV: time quantum = 1 oscillator clock). */
    s32k_write(S32K_CAN0_CTRL1,
               ((uint32_t)QFOC_S32K_CAN_RJW << S32K_CAN_CTRL1_RJW_SHIFT) |
               ((uint32_t)QFOC_S32K_CAN_PSEG1 << S32K_CAN_CTRL1_PSEG1_SHIFT) |
               ((uint32_t)QFOC_S32K_CAN_PSEG2 << S32K_CAN_CTRL1_PSEG2_SHIFT) |
               ((uint32_t)QFOC_S32K_CAN_PROPSEG << S32K_CAN_CTRL1_PROPSEG_SHIFT));
    /* Message-buffer RAM and individual masks have ECC: written once before use. */
    for (k = 0u; k < S32K_CAN0_RAM_WORDS; k++) {
        s32k_write(S32K_CAN0_RAM + (4u * k), 0u);
    }
    for (k = 0u; k < S32K_CAN0_RXIMR_WORDS; k++) {
        s32k_write(S32K_CAN0_RXIMR0 + (4u * k), 0xFFFFFFFFu);
    }
    s32k_write(S32K_CAN0_RXMGMASK, 0xFFFFFFFFu);
    /* MB0 (QFOC_S32K_CAN_TX_MB): inactive transmit buffer. */
    s32k_write(S32K_CAN0_MB0_CS, (uint32_t)S32K_CAN_CODE_TX_INACTIVE << S32K_CAN_CS_CODE_SHIFT);
    /* Leave freeze: one MB (MAXMB left 0: MB0 is the last buffer in use), individual
       masks, no self reception. */
    s32k_write(S32K_CAN0_MCR, S32K_CAN_MCR_SRXDIS | S32K_CAN_MCR_IRMQ);
    if (!s32k_wait(S32K_CAN0_MCR, S32K_CAN_MCR_FRZACK, 0u)) {
        status = QFOC_S32K_ERR_TIMEOUT;
    } else if (!s32k_wait(S32K_CAN0_MCR, S32K_CAN_MCR_NOTRDY, 0u)) {
        status = QFOC_S32K_ERR_TIMEOUT;
    } else {
        /* on the bus */
    }
    return status;
}

/* ------------------------------------------------------------------ time base, watchdog */

void qfoc_s32k_tick_init(void)
{
    s32k_pcc_enable(S32K_PCC_LPIT, S32K_PCC_PCS_SOSCDIV);   /* 8 MHz */
    s32k_write(S32K_LPIT0_MCR, S32K_LPIT_MCR_M_CEN | S32K_LPIT_MCR_DBG_EN);
    s32k_write(S32K_LPIT0_TVAL0, QFOC_S32K_TICK_TVAL);      /* 8000 clocks = 1 ms */
    s32k_write(S32K_LPIT0_MSR, S32K_LPIT_CH0);              /* flag cleared */
    s32k_write(S32K_LPIT0_MIER, S32K_LPIT_CH0);
    s32k_write(S32K_LPIT0_TCTRL0, S32K_LPIT_CH0);           /* 32-bit periodic (MODE 00), on */
}

int32_t qfoc_s32k_wdog_init(void)
{
    int32_t status = QFOC_S32K_OK;
    /* Unlock (32-bit key, CMD32EN set by the startup code), then the whole new
       configuration within the unlock window (RM, WDOG chapter, "Configuring the Watchdog");
       UPDATE = 0 locks it until reset.  10 ms on the 128 kHz LPO = 1280 counts. */
    s32k_write(S32K_WDOG_CNT, S32K_WDOG_UNLOCK_KEY);
    if (!s32k_wait(S32K_WDOG_CS, S32K_WDOG_CS_ULK, S32K_WDOG_CS_ULK)) {
        status = QFOC_S32K_ERR_TIMEOUT;
    } else {
        s32k_write(S32K_WDOG_TOVAL, (QFOC_S32K_WDOG_LPO_HZ / 1000u) * QFOC_S32K_WDOG_TIMEOUT_MS);
        s32k_write(S32K_WDOG_WIN, 0u);
        s32k_write(S32K_WDOG_CS, S32K_WDOG_CS_CMD32EN | S32K_WDOG_CS_CLK_LPO | S32K_WDOG_CS_EN);
        if (!s32k_wait(S32K_WDOG_CS, S32K_WDOG_CS_RCS, S32K_WDOG_CS_RCS)) {
            status = QFOC_S32K_ERR_TIMEOUT;
        } else {
            /* new configuration active */
        }
    }
    return status;
}

/* ------------------------------------------------------------------ NVIC */

static void s32k_nvic_setup(uint32_t irq, uint32_t prio)
{
    const uint32_t word = S32K_NVIC_IPR0 + (4u * (irq / 4u));
    const uint32_t shift = 8u * (irq % 4u);
    const uint32_t value = (prio << (8u - S32K_NVIC_PRIO_BITS)) & 0xFFu;
    const uint32_t bit = (uint32_t)1u << (irq % 32u);
    s32k_modify(word, (uint32_t)0xFFu << shift, value << shift);
    s32k_write(S32K_NVIC_ICPR0 + (4u * (irq / 32u)), bit);
    s32k_write(S32K_NVIC_ISER0 + (4u * (irq / 32u)), bit);
}

void qfoc_s32k_irq_init(void)
{
    /* FTM3 overflow and reload share one vector (IRQ 122). */
    s32k_nvic_setup(S32K_IRQ_ADC1, QFOC_S32K_PRIO_ADC);
    s32k_nvic_setup(S32K_IRQ_FTM3_OVF, QFOC_S32K_PRIO_FTM);
    s32k_nvic_setup(S32K_IRQ_LPIT0_CH0, QFOC_S32K_PRIO_TICK);
    s32k_nvic_setup(S32K_IRQ_LPUART1, QFOC_S32K_PRIO_UART);
}
