/**
 * @file s32k144_regs.h
 * @brief The S32K144 registers the qfoc port uses: absolute addresses, bit fields, and
 *        the one volatile accessor through which every register is reached.
 *
 * Source of every address and bit position: NXP "S32K1xx Series Reference Manual",
 * Rev. 13 (04/2020): the chapter named in each group, the register named in each comment
 * (SCG_RCCR, FTM3_MOD, ...), the memory map, and the S32K144 interrupt vector
 * assignments (the RM's attached interrupt sheet) for the IRQ numbers; pin functions:
 * the RM's attached S32K144 IO signal table.  Cortex-M4 core registers: ARMv7-M
 * Architecture Reference Manual (NVIC, SCB).  No vendor header is used.
 *
 * The accessor: s32k_reg(addr) returns a pointer to the 32-bit register at the absolute
 * address addr.  On the target it is that address; the host tests compile the port with
 * QFOC_PORT_FAKE_REGS defined, and the accessor then returns a cell of a RAM register
 * file indexed by address (port_s32k/fake/fake_regs.c), so the port's register writes
 * can be checked on the host.  Nothing else in the port forms a register pointer.
 *
 * Requirements: REQ-PORT-001.
 */
#ifndef QFOC_S32K144_REGS_H
#define QFOC_S32K144_REGS_H

#include <stdint.h>
#include <stdbool.h>

/* ------------------------------------------------------------------ accessor */
#if defined(QFOC_PORT_FAKE_REGS)
/** Host build: the cell of the fake register file that stands for address addr. */
volatile uint32_t *qfoc_fake_reg(uint32_t addr);

static inline volatile uint32_t *s32k_reg(uint32_t addr)
{
    return qfoc_fake_reg(addr);
}
#else
/** Target build: the register at the absolute address addr. */
static inline volatile uint32_t *s32k_reg(uint32_t addr)
{
    /* a memory-mapped register's address becomes a pointer: the only integer-to-pointer
       conversion of the port (DEV-003) */
    /* cppcheck-suppress misra-c2012-11.4 ; DEV-003 */
    return (volatile uint32_t *)addr;
}
#endif

/** Read a 32-bit register. */
static inline uint32_t s32k_read(uint32_t addr)
{
    return *s32k_reg(addr);
}

/** Write a 32-bit register. */
static inline void s32k_write(uint32_t addr, uint32_t value)
{
    *s32k_reg(addr) = value;
}

/** Read-modify-write: clear the bits of clr, then set the bits of set. */
static inline void s32k_modify(uint32_t addr, uint32_t clr, uint32_t set)
{
    volatile uint32_t *const r = s32k_reg(addr);
    *r = (*r & ~clr) | set;
}

/** A field value placed at its position: (value << shift) & mask. */
static inline uint32_t s32k_fld(uint32_t value, uint32_t shift, uint32_t mask)
{
    return (value << shift) & mask;
}

/* ------------------------------------------------------------------ SCG (RM chapter "System Clock Generator") */
#define S32K_SCG_CSR          ((uint32_t)0x40064010u)  /* SCG_CSR: clock status */
#define S32K_SCG_RCCR         ((uint32_t)0x40064014u)  /* SCG_RCCR: RUN clock control */
#define S32K_SCG_SOSCCSR      ((uint32_t)0x40064100u)  /* SCG_SOSCCSR: system OSC control/status */
#define S32K_SCG_SOSCDIV      ((uint32_t)0x40064104u)  /* SCG_SOSCDIV: system OSC dividers */
#define S32K_SCG_SOSCCFG      ((uint32_t)0x40064108u)  /* SCG_SOSCCFG: system OSC configuration */
#define S32K_SCG_SPLLCSR      ((uint32_t)0x40064600u)  /* SCG_SPLLCSR: system PLL control/status */
#define S32K_SCG_SPLLDIV      ((uint32_t)0x40064604u)  /* SCG_SPLLDIV: system PLL dividers */
#define S32K_SCG_SPLLCFG      ((uint32_t)0x40064608u)  /* SCG_SPLLCFG: system PLL configuration */

/* SCG_CSR / SCG_RCCR fields */
#define S32K_SCG_SCS_SHIFT     (24u)                   /* SCS[27:24]: system clock source */
#define S32K_SCG_SCS_MASK      ((uint32_t)0x0F000000u)
#define S32K_SCG_SCS_SPLL      (6u)                    /* 0110: system PLL (SPLL_CLK) */
#define S32K_SCG_DIVCORE_SHIFT (16u)                   /* DIVCORE[19:16]: core divide-by = n+1 */
#define S32K_SCG_DIVCORE_MASK  ((uint32_t)0x000F0000u)
#define S32K_SCG_DIVBUS_SHIFT  (4u)                    /* DIVBUS[7:4]: bus divide-by = n+1 */
#define S32K_SCG_DIVBUS_MASK   ((uint32_t)0x000000F0u)
#define S32K_SCG_DIVSLOW_SHIFT (0u)                    /* DIVSLOW[3:0]: flash divide-by = n+1 */
#define S32K_SCG_DIVSLOW_MASK  ((uint32_t)0x0000000Fu)
/* SCG_SOSCCSR / SCG_SPLLCSR fields (same positions) */
#define S32K_SCG_XCSR_EN      ((uint32_t)0x00000001u)  /* SOSCEN / SPLLEN, bit 0 (LK, bit 23, left 0) */
#define S32K_SCG_XCSR_VLD     ((uint32_t)0x01000000u)  /* SOSCVLD / SPLLVLD, bit 24 */
/* SCG_SOSCCFG fields */
#define S32K_SCG_SOSCCFG_EREFS ((uint32_t)0x00000004u) /* EREFS, bit 2: 1 = crystal oscillator;
                                                           HGO, bit 3, left 0: low gain */
#define S32K_SCG_SOSCCFG_RANGE_SHIFT (4u)              /* RANGE[5:4]: 2 = medium (4..8 MHz crystal) */
#define S32K_SCG_SOSCCFG_RANGE_MASK  ((uint32_t)0x00000030u)
/* SCG_xDIV fields: 0 = output off, n = divide by 2^(n-1) */
#define S32K_SCG_DIV1_SHIFT   (0u)                     /* xDIV1[2:0] */
#define S32K_SCG_DIV1_MASK    ((uint32_t)0x00000007u)
#define S32K_SCG_DIV2_SHIFT   (8u)                     /* xDIV2[10:8] */
#define S32K_SCG_DIV2_MASK    ((uint32_t)0x00000700u)
/* SCG_SPLLCFG fields: VCO = f_SOSC / (PREDIV + 1) x (MULT + 16), SPLL_CLK = VCO / 2 */
/* PREDIV[10:8]: not written, left 0 (QFOC_S32K_SPLL_PREDIV, mcu.c) */
#define S32K_SCG_MULT_SHIFT   (16u)                    /* MULT[20:16] */
#define S32K_SCG_MULT_MASK    ((uint32_t)0x001F0000u)

/* ------------------------------------------------------------------ PCC (RM chapter "Peripheral Clock Control") */
#define S32K_PCC_FLEXCAN0     ((uint32_t)0x40065090u)  /* PCC_FlexCAN0 (index 36) */
#define S32K_PCC_FTM3         ((uint32_t)0x40065098u)  /* PCC_FTM3 (index 38) */
#define S32K_PCC_ADC1         ((uint32_t)0x4006509Cu)  /* PCC_ADC1 (index 39) */
#define S32K_PCC_PDB1         ((uint32_t)0x400650C4u)  /* PCC_PDB1 (index 49) */
#define S32K_PCC_PDB0         ((uint32_t)0x400650D8u)  /* PCC_PDB0 (index 54) */
#define S32K_PCC_LPIT         ((uint32_t)0x400650DCu)  /* PCC_LPIT (index 55) */
#define S32K_PCC_ADC0         ((uint32_t)0x400650ECu)  /* PCC_ADC0 (index 59) */
#define S32K_PCC_PORTA        ((uint32_t)0x40065124u)  /* PCC_PORTA (index 73) */
#define S32K_PCC_PORTB        ((uint32_t)0x40065128u)  /* PCC_PORTB (index 74) */
#define S32K_PCC_PORTC        ((uint32_t)0x4006512Cu)  /* PCC_PORTC (index 75) */
#define S32K_PCC_PORTD        ((uint32_t)0x40065130u)  /* PCC_PORTD (index 76) */
#define S32K_PCC_PORTE        ((uint32_t)0x40065134u)  /* PCC_PORTE (index 77) */
#define S32K_PCC_LPUART1      ((uint32_t)0x400651ACu)  /* PCC_LPUART1 (index 107) */
#define S32K_PCC_CGC          ((uint32_t)0x40000000u)  /* CGC, bit 30: clock gate enabled */
#define S32K_PCC_PCS_SHIFT    (24u)                    /* PCS[26:24]: functional clock source */
#define S32K_PCC_PCS_MASK     ((uint32_t)0x07000000u)
#define S32K_PCC_PCS_SOSCDIV  (1u)                     /* 001: SOSCDIVn_CLK */
#define S32K_PCC_PCS_SPLLDIV  (6u)                     /* 110: SPLLDIVn_CLK */

/* ------------------------------------------------------------------ SMC (RM chapter "System Mode Controller") */
#define S32K_SMC_PMPROT       ((uint32_t)0x4007E008u)  /* SMC_PMPROT: allowed power modes (write once) */
#define S32K_SMC_PMCTRL       ((uint32_t)0x4007E00Cu)  /* SMC_PMCTRL: RUNM[6:5] = 0 RUN */
#define S32K_SMC_PMSTAT       ((uint32_t)0x4007E014u)  /* SMC_PMSTAT: 0x01 = RUN */
#define S32K_SMC_PMSTAT_RUN   ((uint32_t)0x00000001u)
#define S32K_SMC_PMCTRL_RUNM_MASK ((uint32_t)0x00000060u)

/* ------------------------------------------------------------------ SIM (RM chapter "System Integration Module") */
#define S32K_SIM_ADCOPT       ((uint32_t)0x40048018u)  /* SIM_ADCOPT: 0 = ADC triggers and pre-triggers from the PDBs */

/* ------------------------------------------------------------------ PORT and GPIO (RM chapters "Port Control and Interrupts", "General-Purpose Input/Output") */
#define S32K_PORTA_BASE       ((uint32_t)0x40049000u)  /* PORTA_PCRn = base + 4 n */
#define S32K_PORTB_BASE       ((uint32_t)0x4004A000u)  /* PORTB_PCRn */
#define S32K_PORTC_BASE       ((uint32_t)0x4004B000u)  /* PORTC_PCRn */
#define S32K_PORTD_BASE       ((uint32_t)0x4004C000u)  /* PORTD_PCRn */
#define S32K_PORTE_BASE       ((uint32_t)0x4004D000u)  /* PORTE_PCRn */
#define S32K_PCR_PS           ((uint32_t)0x00000001u)  /* PS, bit 0: 1 = pull-up */
#define S32K_PCR_PE           ((uint32_t)0x00000002u)  /* PE, bit 1: pull enable */
#define S32K_PCR_MUX_SHIFT    (8u)                     /* MUX[10:8]: pin function ALTn */
#define S32K_PCR_MUX_MASK     ((uint32_t)0x00000700u)
#define S32K_GPIOD_PSOR       ((uint32_t)0x400FF0C4u)  /* PTD PSOR: set output */
#define S32K_GPIOD_PCOR       ((uint32_t)0x400FF0C8u)  /* PTD PCOR: clear output */
#define S32K_GPIOD_PDDR       ((uint32_t)0x400FF0D4u)  /* PTD PDDR: direction, 1 = output */

/* ------------------------------------------------------------------ TRGMUX (RM chapter "Trigger MUX Control") */
#define S32K_TRGMUX_PDB0      ((uint32_t)0x40063038u)  /* TRGMUX_PDB0 (register index 14) */
#define S32K_TRGMUX_PDB1      ((uint32_t)0x4006303Cu)  /* TRGMUX_PDB1 (register index 15) */
#define S32K_TRGMUX_SEL0_MASK ((uint32_t)0x0000007Fu)  /* SEL0[6:0]: source of trigger input 0 */
#define S32K_TRGMUX_LK        ((uint32_t)0x80000000u)  /* LK, bit 31: locked until reset */
#define S32K_TRGMUX_SRC_FTM3_INIT (28u)                /* TRGMUX input 28: FTM3 initialization trigger */

/* ------------------------------------------------------------------ FTM3 (RM chapter "FlexTimer Module") */
#define S32K_FTM3_SC          ((uint32_t)0x40026000u)  /* FTM3_SC: status and control */
#define S32K_FTM3_CNT         ((uint32_t)0x40026004u)  /* FTM3_CNT: counter */
#define S32K_FTM3_MOD         ((uint32_t)0x40026008u)  /* FTM3_MOD: modulo */
#define S32K_FTM3_C0SC        ((uint32_t)0x4002600Cu)  /* FTM3_C0SC; CnSC = C0SC + 8 n */
#define S32K_FTM3_C0V         ((uint32_t)0x40026010u)  /* FTM3_C0V;  CnV  = C0V  + 8 n */
#define S32K_FTM3_CNTIN       ((uint32_t)0x4002604Cu)  /* FTM3_CNTIN: counter initial value */
#define S32K_FTM3_MODE        ((uint32_t)0x40026054u)  /* FTM3_MODE: features mode selection */
#define S32K_FTM3_SYNC        ((uint32_t)0x40026058u)  /* FTM3_SYNC: synchronization */
#define S32K_FTM3_OUTINIT     ((uint32_t)0x4002605Cu)  /* FTM3_OUTINIT: initial output state */
#define S32K_FTM3_OUTMASK     ((uint32_t)0x40026060u)  /* FTM3_OUTMASK: output mask */
#define S32K_FTM3_COMBINE     ((uint32_t)0x40026064u)  /* FTM3_COMBINE: linked channels */
#define S32K_FTM3_DEADTIME    ((uint32_t)0x40026068u)  /* FTM3_DEADTIME: dead-time insertion */
#define S32K_FTM3_EXTTRIG     ((uint32_t)0x4002606Cu)  /* FTM3_EXTTRIG: external trigger */
#define S32K_FTM3_POL         ((uint32_t)0x40026070u)  /* FTM3_POL: channel polarity */
#define S32K_FTM3_FMS         ((uint32_t)0x40026074u)  /* FTM3_FMS: fault mode status */
#define S32K_FTM3_FLTCTRL     ((uint32_t)0x4002607Cu)  /* FTM3_FLTCTRL: fault control */
#define S32K_FTM3_FLTPOL      ((uint32_t)0x40026088u)  /* FTM3_FLTPOL: fault input polarity */
#define S32K_FTM3_SYNCONF     ((uint32_t)0x4002608Cu)  /* FTM3_SYNCONF: synchronization config */
#define S32K_FTM3_PWMLOAD     ((uint32_t)0x40026098u)  /* FTM3_PWMLOAD: PWM load */
/* FTM_SC fields */
#define S32K_FTM_SC_CLKS_SHIFT (3u)                    /* CLKS[4:3]: 01 = FTM input clock (SYS_CLK) */
#define S32K_FTM_SC_CLKS_MASK ((uint32_t)0x00000018u)
#define S32K_FTM_SC_CPWMS     ((uint32_t)0x00000020u)  /* CPWMS, bit 5: up-down (centre-aligned) */
#define S32K_FTM_SC_RIE       ((uint32_t)0x00000040u)  /* RIE, bit 6: reload interrupt enable */
#define S32K_FTM_SC_RF        ((uint32_t)0x00000080u)  /* RF, bit 7: reload flag */
#define S32K_FTM_SC_TOIE      ((uint32_t)0x00000100u)  /* TOIE, bit 8: overflow interrupt enable */
#define S32K_FTM_SC_TOF       ((uint32_t)0x00000200u)  /* TOF, bit 9: overflow flag */
#define S32K_FTM_SC_PWMEN_SHIFT (16u)                  /* PWMEN0..7, bits 16..23: output enable */
/* FTM_SC[PS] (bits 2:0) left 0: prescaler /1. */
/* FTM_CnSC fields */
#define S32K_FTM_CNSC_ELSB    ((uint32_t)0x00000008u)  /* ELSB, bit 3 (ELSB:ELSA = 10: high-true) */
#define S32K_FTM_CNSC_MSB     ((uint32_t)0x00000020u)  /* MSB, bit 5 */
/* FTM_MODE fields */
#define S32K_FTM_MODE_FTMEN   ((uint32_t)0x00000001u)  /* FTMEN, bit 0: enhanced features */
#define S32K_FTM_MODE_INIT    ((uint32_t)0x00000002u)  /* INIT, bit 1: outputs from OUTINIT */
#define S32K_FTM_MODE_WPDIS   ((uint32_t)0x00000004u)  /* WPDIS, bit 2: write protection off */
#define S32K_FTM_MODE_FAULTM_SHIFT (5u)                /* FAULTM[6:5]: 10 = all channels, manual clear */
#define S32K_FTM_MODE_FAULTM_MASK  ((uint32_t)0x00000060u)
/* FTM_SYNC fields */
#define S32K_FTM_SYNC_CNTMAX  ((uint32_t)0x00000002u)  /* CNTMAX, bit 1: reload point at MOD */
/* FTM_COMBINE fields of pair m (shifted by 8 m) */
#define S32K_FTM_COMB_COMBINE ((uint32_t)0x00000001u)  /* COMBINEm, bit 0: combine mode (CPWMS = 0 only):
                                                          channel n high-true is set at the C(n)V match,
                                                          cleared at the C(n+1)V match */
#define S32K_FTM_COMB_COMP    ((uint32_t)0x00000002u)  /* COMPm, bit 1: channel n+1 = complement of n */
#define S32K_FTM_COMB_DTEN    ((uint32_t)0x00000010u)  /* DTENm, bit 4: dead-time insertion */
#define S32K_FTM_COMB_SYNCEN  ((uint32_t)0x00000020u)  /* SYNCENm, bit 5: synchronized CnV update */
#define S32K_FTM_COMB_FAULTEN ((uint32_t)0x00000040u)  /* FAULTENm, bit 6: fault control of the pair */
/* FTM_DEADTIME fields */
#define S32K_FTM_DT_DTVAL_MASK ((uint32_t)0x0000003Fu) /* DTVAL[5:0]: dead-time count */
#define S32K_FTM_DT_DTPS_SHIFT (6u)                    /* DTPS[7:6]: 0x = /1, 10 = /4, 11 = /16 */
#define S32K_FTM_DT_DTPS_MASK  ((uint32_t)0x000000C0u)
/* FTM_EXTTRIG fields */
#define S32K_FTM_EXTTRIG_INITTRIGEN ((uint32_t)0x00000040u) /* INITTRIGEN, bit 6: trigger at CNTIN */
/* FTM_FMS fields */
#define S32K_FTM_FMS_FAULTIN  ((uint32_t)0x00000020u)  /* FAULTIN, bit 5: fault input level (active) */
/* FAULTF0..FAULTF3 are bits 0..3 (FAULTF0: fault on input 0). */
#define S32K_FTM_FMS_WPEN     ((uint32_t)0x00000040u)  /* WPEN, bit 6: write protection */
#define S32K_FTM_FMS_FAULTF   ((uint32_t)0x00000080u)  /* FAULTF, bit 7: any fault flag */
#define S32K_FTM_FMS_FLAGS    ((uint32_t)0x0000008Fu)  /* FAULTF | FAULTF3..0 */
/* FTM_FLTCTRL fields */
#define S32K_FTM_FLT_FAULT0EN ((uint32_t)0x00000001u)  /* FAULT0EN, bit 0 */
#define S32K_FTM_FLT_FFLTR0EN ((uint32_t)0x00000010u)  /* FFLTR0EN, bit 4: input filter */
#define S32K_FTM_FLT_FFVAL_SHIFT (8u)                  /* FFVAL[11:8]: filter length */
#define S32K_FTM_FLT_FFVAL_MASK  ((uint32_t)0x00000F00u)
/* FTM_FLTCTRL[FSTATE] (bit 15) left 0: on a fault the outputs go to their safe (inactive)
   value, not tri-state. */
/* FTM_FLTPOL fields */
#define S32K_FTM_FLTPOL_FLT0POL ((uint32_t)0x00000001u) /* FLT0POL, bit 0: 1 = active low */
/* FTM_SYNCONF fields */
#define S32K_FTM_SYNCONF_SYNCMODE ((uint32_t)0x00000080u) /* SYNCMODE, bit 7: enhanced synchronization */
#define S32K_FTM_SYNCONF_SWWRBUF  ((uint32_t)0x00000200u) /* SWWRBUF, bit 9 */
/* FTM_PWMLOAD fields */
#define S32K_FTM_PWMLOAD_LDOK ((uint32_t)0x00000200u)  /* LDOK, bit 9: load MOD/CNTIN/CnV at reload */

/* ------------------------------------------------------------------ PDB0 / PDB1 (RM chapter "Programmable Delay Block") */
#define S32K_PDB0_BASE        ((uint32_t)0x40036000u)
#define S32K_PDB1_BASE        ((uint32_t)0x40031000u)
#define S32K_PDB_SC           (0x000u)                 /* PDBx_SC: status and control */
#define S32K_PDB_MOD          (0x004u)                 /* PDBx_MOD: modulus */
#define S32K_PDB_IDLY         (0x00Cu)                 /* PDBx_IDLY: interrupt delay */
#define S32K_PDB_CH0C1        (0x010u)                 /* PDBx_CH0C1: channel 0 control 1 */
#define S32K_PDB_CH0S         (0x014u)                 /* PDBx_CH0S: channel 0 status */
#define S32K_PDB_CH0DLY0      (0x018u)                 /* PDBx_CH0DLY0; CH0DLYm = +4 m */
#define S32K_PDB_SC_LDOK      ((uint32_t)0x00000001u)  /* LDOK, bit 0: load MOD and delays */
#define S32K_PDB_SC_PDBEN     ((uint32_t)0x00000080u)  /* PDBEN, bit 7 */
#define S32K_PDB_SC_LDMOD_SHIFT (18u)                  /* LDMOD[19:18]: when LDOK's values load */
#define S32K_PDB_SC_LDMOD_MASK ((uint32_t)0x000C0000u)
#define S32K_PDB_LDMOD_AT_MOD (1u)                     /* 01: when the counter reaches MOD after LDOK
                                                          (00, the value left in the two-sensor set-up:
                                                          at once) */
/* PDBx_SC fields left 0: CONT (bit 1, one shot per trigger), MULT[3:2] (x1), TRGSEL[11:8]
   (trigger input 0, from TRGMUX), PRESCALER[14:12] (/1): the PDB counts SYS_CLK. */
#define S32K_PDB_C1_EN_SHIFT  (0u)                     /* EN[7:0]: pre-trigger enable */
#define S32K_PDB_C1_TOS_SHIFT (8u)                     /* TOS[15:8]: pre-trigger after its delay */
#define S32K_PDB_C1_BB_SHIFT  (16u)                    /* BB[23:16]: back-to-back after pre-trigger m-1 */

/* ------------------------------------------------------------------ ADC0 / ADC1 (RM chapter "Analog-to-Digital Converter") */
#define S32K_ADC0_BASE        ((uint32_t)0x4003B000u)
#define S32K_ADC1_BASE        ((uint32_t)0x40027000u)
#define S32K_ADC_SC1A         (0x000u)                 /* ADCx_SC1n = +4 n: channel select */
#define S32K_ADC_CFG1         (0x040u)                 /* ADCx_CFG1: clock, mode */
#define S32K_ADC_CFG2         (0x044u)                 /* ADCx_CFG2: sample time */
#define S32K_ADC_RA           (0x048u)                 /* ADCx_Rn = +4 n: result */
#define S32K_ADC_SC2          (0x090u)                 /* ADCx_SC2: trigger select */
#define S32K_ADC_SC3          (0x094u)                 /* ADCx_SC3: calibration, averaging */
#define S32K_ADC_CLPS         (0x0B4u)                 /* ADCx_CLPS; CLP3 +4, CLP2 +8, CLP1 +C, CLP0 +10, CLPX +14, CLP9 +18 */
#define S32K_ADC_SC1_ADCH_MASK ((uint32_t)0x0000001Fu) /* ADCH[4:0]: input channel */
#define S32K_ADC_SC1_AIEN     ((uint32_t)0x00000040u)  /* AIEN, bit 6: conversion-complete interrupt */
#define S32K_ADC_SC1_COCO     ((uint32_t)0x00000080u)  /* COCO, bit 7: conversion complete */
#define S32K_ADC_CFG1_MODE_12 ((uint32_t)0x00000004u)  /* MODE[3:2] = 01: 12-bit */
#define S32K_ADC_SC2_ADTRG    ((uint32_t)0x00000040u)  /* ADTRG, bit 6: hardware trigger */
#define S32K_ADC_SC3_AVGS_32  ((uint32_t)0x00000003u)  /* AVGS[1:0] = 11: 32 samples */
#define S32K_ADC_SC3_AVGE     ((uint32_t)0x00000004u)  /* AVGE, bit 2: hardware average */
#define S32K_ADC_SC3_CAL      ((uint32_t)0x00000080u)  /* CAL, bit 7: start calibration */
#define S32K_ADC_R_MASK       ((uint32_t)0x00000FFFu)  /* D[11:0] of a 12-bit result */

/* ------------------------------------------------------------------ LPIT0 (RM chapter "Low Power Interrupt Timer") */
#define S32K_LPIT0_MCR        ((uint32_t)0x40037008u)  /* LPIT0_MCR: module control */
#define S32K_LPIT0_MSR        ((uint32_t)0x4003700Cu)  /* LPIT0_MSR: status, TIFn write-1-to-clear */
#define S32K_LPIT0_MIER       ((uint32_t)0x40037010u)  /* LPIT0_MIER: interrupt enable */
#define S32K_LPIT0_TVAL0      ((uint32_t)0x40037020u)  /* LPIT0_TVAL0: channel 0 reload value */
#define S32K_LPIT0_TCTRL0     ((uint32_t)0x40037028u)  /* LPIT0_TCTRL0: channel 0 control */
#define S32K_LPIT_MCR_M_CEN   ((uint32_t)0x00000001u)  /* M_CEN, bit 0: module clock enable */
#define S32K_LPIT_MCR_DBG_EN  ((uint32_t)0x00000008u)  /* DBG_EN, bit 3: run in debug halt */
#define S32K_LPIT_CH0         ((uint32_t)0x00000001u)  /* TIF0 / TIE0 / T_EN, bit 0 */

/* ------------------------------------------------------------------ LPUART1 (RM chapter "Low Power UART") */
#define S32K_LPUART1_BAUD     ((uint32_t)0x4006B010u)  /* LPUART1_BAUD: baud rate */
#define S32K_LPUART1_STAT     ((uint32_t)0x4006B014u)  /* LPUART1_STAT: status */
#define S32K_LPUART1_CTRL     ((uint32_t)0x4006B018u)  /* LPUART1_CTRL: control */
#define S32K_LPUART1_DATA     ((uint32_t)0x4006B01Cu)  /* LPUART1_DATA: data */
#define S32K_LPUART_BAUD_SBR_MASK  ((uint32_t)0x00001FFFu) /* SBR[12:0]: baud divisor */
#define S32K_LPUART_BAUD_LBKDIE    ((uint32_t)0x00008000u) /* LBKDIE, bit 15: LIN break interrupt */
#define S32K_LPUART_BAUD_OSR_SHIFT (24u)                   /* OSR[28:24]: oversampling = OSR + 1 */
#define S32K_LPUART_BAUD_OSR_MASK  ((uint32_t)0x1F000000u)
#define S32K_LPUART_STAT_PF   ((uint32_t)0x00010000u)  /* PF, bit 16: parity error (w1c) */
#define S32K_LPUART_STAT_FE   ((uint32_t)0x00020000u)  /* FE, bit 17: framing error (w1c) */
#define S32K_LPUART_STAT_NF   ((uint32_t)0x00040000u)  /* NF, bit 18: noise (w1c) */
#define S32K_LPUART_STAT_OR   ((uint32_t)0x00080000u)  /* OR, bit 19: overrun (w1c) */
#define S32K_LPUART_STAT_IDLE ((uint32_t)0x00100000u)  /* IDLE, bit 20: idle line (w1c) */
#define S32K_LPUART_STAT_RDRF ((uint32_t)0x00200000u)  /* RDRF, bit 21: receive data full */
#define S32K_LPUART_STAT_TC   ((uint32_t)0x00400000u)  /* TC, bit 22: transmission complete */
#define S32K_LPUART_STAT_TDRE ((uint32_t)0x00800000u)  /* TDRE, bit 23: transmit data empty */
#define S32K_LPUART_STAT_LBKDE ((uint32_t)0x02000000u) /* LBKDE, bit 25: LIN break detection */
#define S32K_LPUART_STAT_BRK13 ((uint32_t)0x04000000u) /* BRK13, bit 26: 13-bit break (LIN) */
#define S32K_LPUART_STAT_LBKDIF ((uint32_t)0x80000000u) /* LBKDIF, bit 31: LIN break (w1c) */
#define S32K_LPUART_STAT_W1C  ((uint32_t)0xC01FC000u)  /* every write-1-to-clear flag of STAT */
#define S32K_LPUART_CTRL_ILT  ((uint32_t)0x00000004u)  /* ILT, bit 2: idle count after the stop bit */
#define S32K_LPUART_CTRL_IDLECFG_2 ((uint32_t)0x00000100u) /* IDLECFG[10:8] = 001: 2 idle characters */
#define S32K_LPUART_CTRL_SBK  ((uint32_t)0x00010000u)  /* SBK, bit 16: send break */
#define S32K_LPUART_CTRL_RE   ((uint32_t)0x00040000u)  /* RE, bit 18 */
#define S32K_LPUART_CTRL_TE   ((uint32_t)0x00080000u)  /* TE, bit 19 */
#define S32K_LPUART_CTRL_ILIE ((uint32_t)0x00100000u)  /* ILIE, bit 20: idle interrupt */
#define S32K_LPUART_CTRL_RIE  ((uint32_t)0x00200000u)  /* RIE, bit 21: receive interrupt */
#define S32K_LPUART_CTRL_TCIE ((uint32_t)0x00400000u)  /* TCIE, bit 22: transmission-complete interrupt */
#define S32K_LPUART_CTRL_TIE  ((uint32_t)0x00800000u)  /* TIE, bit 23: transmit interrupt */
#define S32K_LPUART_DATA_MASK ((uint32_t)0x000000FFu)  /* 8 data bits */

/* ------------------------------------------------------------------ FlexCAN0 (RM chapter "FlexCAN") */
#define S32K_CAN0_MCR         ((uint32_t)0x40024000u)  /* CAN0_MCR: module configuration */
#define S32K_CAN0_CTRL1       ((uint32_t)0x40024004u)  /* CAN0_CTRL1: bit timing, clock source */
#define S32K_CAN0_RXMGMASK    ((uint32_t)0x40024010u)  /* CAN0_RXMGMASK */
#define S32K_CAN0_IFLAG1      ((uint32_t)0x40024030u)  /* CAN0_IFLAG1: MB flags (w1c) */
#define S32K_CAN0_RAM         ((uint32_t)0x40024080u)  /* CAN0_RAMn: message buffers, 16 bytes each */
#define S32K_CAN0_RAM_WORDS   (128u)                   /* 32 MBs x 4 words */
#define S32K_CAN0_MB0_CS      ((uint32_t)0x40024080u)  /* CAN0_RAM0: MB0 word 0 (CODE, DLC) */
#define S32K_CAN0_MB0_ID      ((uint32_t)0x40024084u)  /* CAN0_RAM1: MB0 word 1 (ID) */
#define S32K_CAN0_MB0_DATA0   ((uint32_t)0x40024088u)  /* CAN0_RAM2: MB0 data bytes 0..3 */
#define S32K_CAN0_MB0_DATA1   ((uint32_t)0x4002408Cu)  /* CAN0_RAM3: MB0 data bytes 4..7 */
#define S32K_CAN_IFLAG1_BUF0I ((uint32_t)0x00000001u)  /* IFLAG1[BUF0I], bit 0: MB0 flag */
#define S32K_CAN0_RXIMR0      ((uint32_t)0x40024880u)  /* CAN0_RXIMRn = +4 n, n < 32 */
#define S32K_CAN0_RXIMR_WORDS (32u)
/* MCR MAXMB[6:0], last MB in use: not written, left 0 (MB0 only, QFOC_S32K_CAN_TX_MB) */
#define S32K_CAN_MCR_IRMQ     ((uint32_t)0x00010000u)  /* IRMQ, bit 16: individual masks */
#define S32K_CAN_MCR_SRXDIS   ((uint32_t)0x00020000u)  /* SRXDIS, bit 17: no self reception */
#define S32K_CAN_MCR_LPMACK   ((uint32_t)0x00100000u)  /* LPMACK, bit 20: low-power acknowledge */
#define S32K_CAN_MCR_FRZACK   ((uint32_t)0x01000000u)  /* FRZACK, bit 24: freeze acknowledge */
#define S32K_CAN_MCR_NOTRDY   ((uint32_t)0x08000000u)  /* NOTRDY, bit 27 */
#define S32K_CAN_MCR_HALT     ((uint32_t)0x10000000u)  /* HALT, bit 28 */
#define S32K_CAN_MCR_FRZ      ((uint32_t)0x40000000u)  /* FRZ, bit 30 */
#define S32K_CAN_MCR_MDIS     ((uint32_t)0x80000000u)  /* MDIS, bit 31: module disable */
#define S32K_CAN_CTRL1_PROPSEG_SHIFT (0u)              /* PROPSEG[2:0]: + 1 tq */
#define S32K_CAN_CTRL1_CLKSRC ((uint32_t)0x00002000u)  /* CLKSRC, bit 13: 0 = oscillator (SOSCDIV2) */
#define S32K_CAN_CTRL1_PSEG2_SHIFT   (16u)             /* PSEG2[18:16]: + 1 tq */
#define S32K_CAN_CTRL1_PSEG1_SHIFT   (19u)             /* PSEG1[21:19]: + 1 tq */
#define S32K_CAN_CTRL1_RJW_SHIFT     (22u)             /* RJW[23:22]: + 1 tq */
/* CTRL1 PRESDIV[31:24], S clock = f / (n + 1): not written, left 0 (QFOC_S32K_CAN_PRESDIV) */
#define S32K_CAN_CS_CODE_SHIFT (24u)                   /* MB word 0 CODE[27:24] */
#define S32K_CAN_CS_CODE_MASK ((uint32_t)0x0F000000u)
#define S32K_CAN_CODE_TX_INACTIVE (8u)                 /* 1000: TX MB inactive */
#define S32K_CAN_CODE_TX_DATA (12u)                    /* 1100: transmit data frame */
#define S32K_CAN_CS_DLC_SHIFT (16u)                    /* DLC[19:16] */
#define S32K_CAN_ID_STD_SHIFT (18u)                    /* MB word 1 ID_STD[28:18] */

/* ------------------------------------------------------------------ WDOG (RM chapter "Watchdog Timer") */
#define S32K_WDOG_CS          ((uint32_t)0x40052000u)  /* WDOG_CS: control and status */
#define S32K_WDOG_CNT         ((uint32_t)0x40052004u)  /* WDOG_CNT: counter; unlock and refresh keys */
#define S32K_WDOG_TOVAL       ((uint32_t)0x40052008u)  /* WDOG_TOVAL: timeout value */
#define S32K_WDOG_WIN         ((uint32_t)0x4005200Cu)  /* WDOG_WIN: window */
#define S32K_WDOG_UNLOCK_KEY  ((uint32_t)0xD928C520u)  /* 32-bit unlock write to WDOG_CNT */
#define S32K_WDOG_REFRESH_KEY ((uint32_t)0xB480A602u)  /* 32-bit refresh write to WDOG_CNT */
#define S32K_WDOG_CS_EN       ((uint32_t)0x00000080u)  /* EN, bit 7 */
/* WDOG_CS[UPDATE] is bit 5 (0x20): set by the startup code (reconfiguration allowed), left
   0 by qfoc_s32k_wdog_init() (configuration locked until reset). */
#define S32K_WDOG_CS_CLK_LPO  ((uint32_t)0x00000100u)  /* CLK[9:8] = 01: LPO clock, 128 kHz */
#define S32K_WDOG_CS_RCS      ((uint32_t)0x00000400u)  /* RCS, bit 10: reconfiguration success */
#define S32K_WDOG_CS_ULK      ((uint32_t)0x00000800u)  /* ULK, bit 11: unlocked */
#define S32K_WDOG_CS_CMD32EN  ((uint32_t)0x00002000u)  /* CMD32EN, bit 13: 32-bit command writes */

/* ------------------------------------------------------------------ Cortex-M4 core (ARMv7-M ARM) */
#define S32K_NVIC_ISER0       ((uint32_t)0xE000E100u)  /* NVIC_ISERn = +4 n: set-enable */
#define S32K_NVIC_ICPR0       ((uint32_t)0xE000E280u)  /* NVIC_ICPRn = +4 n: clear-pending */
#define S32K_NVIC_IPR0        ((uint32_t)0xE000E400u)  /* NVIC_IPRn = +4 n: priorities, 4 per word */
#define S32K_NVIC_PRIO_BITS   (4u)                     /* S32K144: 4 priority bits (MSBs of each byte) */
#define S32K_SCB_CPACR        ((uint32_t)0xE000ED88u)  /* SCB CPACR: CP10/CP11 full access = 0xF << 20 */
#define S32K_SCB_CPACR_FPU    ((uint32_t)0x00F00000u)

/* ------------------------------------------------------------------ IRQ numbers (S32K144 interrupt vector table) */
#define S32K_IRQ_LPUART1      (33u)                    /* LPUART1 transmit / receive */
#define S32K_IRQ_ADC1         (40u)                    /* ADC1 conversion complete */
#define S32K_IRQ_LPIT0_CH0    (48u)                    /* LPIT0 channel 0 */
#define S32K_IRQ_FTM3_OVF     (122u)                   /* FTM3 counter overflow and reload */
#define S32K_IRQ_COUNT        (123u)                   /* device interrupts 0 .. 122 */

/* ------------------------------------------------------------------ flash configuration field (RM chapter "Flash Memory Module (FTFC)", 0x400..0x40F) */
#define S32K_FLASH_CFG_FSEC   (0xFEu)                  /* FSEC: SEC = 10 unsecure, KEYEN = 11 backdoor off */
#define S32K_FLASH_CFG_FOPT   (0x7Fu)                  /* FOPT: the erased default with bit 7 cleared */

#endif /* QFOC_S32K144_REGS_H */
