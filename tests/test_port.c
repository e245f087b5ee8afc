/*
 * tests/test_port.c -- host tests of the S32K144 port (port_s32k/) against a fake
 * register file.
 *
 * The port's sources are included below with QFOC_PORT_FAKE_REGS defined, so that its
 * one register accessor (s32k144_regs.h) reaches a RAM register file
 * (port_s32k/fake/fake_regs.c); the library and the parameter tables are linked as for
 * every other test.  A small model of the hardware's status bits (hw_model) runs before
 * each register access of the port, so that its bounded waits complete.
 *
 * What is checked, against values computed here from the S32K1xx Reference Manual's
 * formulas (not copied from the port):
 *   - clock tree: VCO, SPLL, core, bus, flash and peripheral clocks within the RUN-mode
 *     limits, 80 MHz core; PCC gates and sources;
 *   - pins; PWM: MOD = period, PWM frequency = table's, complementary centre-aligned,
 *     dead time >= the table's, fault control on; PDB delay at the centre; ADC set-up;
 *     UART baud-rate divider; CAN bit rate and sample point; LPIT 1 ms; watchdog 10 ms;
 *     NVIC priority order;
 *   - run time: compare values and output mask, the hardware trip reported once and
 *     cleared with outputs off, NTC conversion against the Steinhart-Hart-B equation,
 *     LIN-style frames in and out, CAN frames, supervision of the ADC chain;
 *   - the interrupts call the library's entry points in order: a drive run through the
 *     port's interrupts and a twin drive called directly with the same inputs give the
 *     same compare values, enables, status frames and CAN frames, from PRECHARGE to RUN;
 *   - single-shunt sensing: the up counter and combined pairs, PDB0's pre-triggers and
 *     ADC0's channels; a plan's compare values and instants, checked by rebuilding the
 *     outputs and the sampling instants from the registers (a model of the combined pairs
 *     and of the PDB's clock) against the plan's windows; the fallback to the symmetric
 *     values; the DC-link samples in Q15 with the offset.
 *
 * Requirements: REQ-PORT-001 .. REQ-PORT-021 (specs/requirements/port.md); each test
 * names its requirement.  The start-up code and the image (REQ-PORT-019) are also
 * checked by make firmware (port_s32k/check_image.py on the binary).
 */
#define QFOC_PORT_FAKE_REGS 1

#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>
#include <math.h>
#include <string.h>

#include "../port_s32k/fake/fake_regs.c"
#include "../port_s32k/mcu.c"
#include "../port_s32k/cpu.c"
#include "../port_s32k/hal_s32k.c"
#include "../port_s32k/isr.c"
#include "../port_s32k/flash_config.c"
#include "reference_params.h"
#include "reference16k_params.h"

/* ------------------------------------------------------------------ hardware model */

/* Register facts used by the tests only (S32K1xx RM Rev. 13). */
#define T_FTM_FMS_FAULTF0 ((uint32_t)0x00000001u)   /* FTM_FMS[FAULTF0], bit 0 */
#define T_WDOG_CS_UPDATE  ((uint32_t)0x00000020u)   /* WDOG_CS[UPDATE], bit 5 */
#define T_CAN_MCR_MAXMB   ((uint32_t)0x0000007Fu)   /* CAN_MCR[MAXMB], bits 6..0 */

/* Status bits the model withholds (timeout tests). */
#define W_SOSC    (1u << 0)   /* SOSCVLD never set */
#define W_SPLL    (1u << 1)   /* SPLLVLD never set */
#define W_SCS     (1u << 2)   /* the clock switch never happens */
#define W_PMSTAT  (1u << 3)   /* never in RUN */
#define W_LPMACK  (1u << 4)   /* FlexCAN never acknowledges disable */
#define W_FRZACK  (1u << 5)   /* FlexCAN never acknowledges freeze */
#define W_UNFRZ   (1u << 6)   /* FlexCAN never leaves freeze */
#define W_NOTRDY  (1u << 7)   /* FlexCAN never ready */
#define W_ULK     (1u << 8)   /* WDOG never unlocked */
#define W_RCS     (1u << 9)   /* WDOG reconfiguration never confirmed */
#define W_ADC     (1u << 10)  /* ADC calibration never completes */
static uint32_t model_withhold = 0u;
static bool can_frozen = false;  /* FlexCAN reached freeze mode once */
static uint32_t nvic_enabled[4]; /* NVIC_ISERn is write-1-to-set: the bits ever written */

static void hw_model(uint32_t addr)
{
    uint32_t v;
    uint32_t k;
    const uint32_t adc[2] = { S32K_ADC0_BASE, S32K_ADC1_BASE };
    (void)addr;
    for (k = 0u; k < 4u; k++) {
        nvic_enabled[k] |= qfoc_fake_peek(S32K_NVIC_ISER0 + (4u * k));
    }
    v = qfoc_fake_peek(S32K_SCG_SOSCCSR);
    qfoc_fake_poke(S32K_SCG_SOSCCSR, (((v & S32K_SCG_XCSR_EN) != 0u) && ((model_withhold & W_SOSC) == 0u))
                                     ? (v | S32K_SCG_XCSR_VLD) : (v & ~S32K_SCG_XCSR_VLD));
    v = qfoc_fake_peek(S32K_SCG_SPLLCSR);
    qfoc_fake_poke(S32K_SCG_SPLLCSR, (((v & S32K_SCG_XCSR_EN) != 0u) && ((model_withhold & W_SPLL) == 0u))
                                     ? (v | S32K_SCG_XCSR_VLD) : (v & ~S32K_SCG_XCSR_VLD));
    if ((model_withhold & W_SCS) == 0u) {
        qfoc_fake_poke(S32K_SCG_CSR, qfoc_fake_peek(S32K_SCG_RCCR));  /* switch done */
    }
    qfoc_fake_poke(S32K_SMC_PMSTAT, ((model_withhold & W_PMSTAT) == 0u) ? S32K_SMC_PMSTAT_RUN : 0x80u);
    /* FlexCAN: LPMACK follows MDIS; FRZACK follows FRZ and HALT; NOTRDY while either. */
    v = qfoc_fake_peek(S32K_CAN0_MCR);
    {
        const bool mdis = (v & S32K_CAN_MCR_MDIS) != 0u;
        const bool frz = ((v & S32K_CAN_MCR_FRZ) != 0u) && ((v & S32K_CAN_MCR_HALT) != 0u) && !mdis;
        v &= ~(S32K_CAN_MCR_LPMACK | S32K_CAN_MCR_FRZACK | S32K_CAN_MCR_NOTRDY);
        if (mdis && ((model_withhold & W_LPMACK) == 0u)) {
            v |= S32K_CAN_MCR_LPMACK;
        }
        if (frz && ((model_withhold & W_FRZACK) == 0u)) {
            v |= S32K_CAN_MCR_FRZACK;
            can_frozen = true;
        }
        if (((model_withhold & W_UNFRZ) != 0u) && can_frozen) {
            v |= S32K_CAN_MCR_FRZACK;
        }
        if (mdis || frz || ((model_withhold & W_NOTRDY) != 0u)) {
            v |= S32K_CAN_MCR_NOTRDY;
        }
        qfoc_fake_poke(S32K_CAN0_MCR, v);
    }
    /* WDOG: unlocked after the unlock key, reconfiguration succeeds. */
    v = qfoc_fake_peek(S32K_WDOG_CS);
    v = ((model_withhold & W_RCS) == 0u) ? (v | S32K_WDOG_CS_RCS) : (v & ~S32K_WDOG_CS_RCS);
    if ((qfoc_fake_peek(S32K_WDOG_CNT) == S32K_WDOG_UNLOCK_KEY) && ((model_withhold & W_ULK) == 0u)) {
        v |= S32K_WDOG_CS_ULK;
    } else {
        v &= ~S32K_WDOG_CS_ULK;
    }
    qfoc_fake_poke(S32K_WDOG_CS, v);
    /* ADC calibration completes at once: CAL clears, SC1A[COCO] sets. */
    for (k = 0u; k < 2u; k++) {
        v = qfoc_fake_peek(adc[k] + S32K_ADC_SC3);
        if (((model_withhold & W_ADC) == 0u) && ((v & S32K_ADC_SC3_CAL) != 0u)) {
            qfoc_fake_poke(adc[k] + S32K_ADC_SC3, v & ~S32K_ADC_SC3_CAL);
            qfoc_fake_poke(adc[k] + S32K_ADC_SC1A, qfoc_fake_peek(adc[k] + S32K_ADC_SC1A) | S32K_ADC_SC1_COCO);
        }
    }
}

static int setup(void **state)
{
    (void)state;
    qfoc_fake_reset();
    model_withhold = 0u;
    can_frozen = false;
    memset(nvic_enabled, 0, sizeof nvic_enabled);
    qfoc_fake_set_hook(hw_model);
    qfoc_s32k_isr_bind(NULL);
    qfoc_s32k_hal_init(5000u);
    return 0;
}

/* The set-up of main.c, in its order. */
static int32_t port_init_all(const qfoc_param_table_t *table, qfoc_s32k_ftm_int_t option)
{
    int32_t st = QFOC_S32K_OK;
    int32_t s;
    qfoc_s32k_pwm_cfg_t pwm;
    qfoc_s32k_pins_init();
    s = qfoc_s32k_clock_init();
    st = (st != QFOC_S32K_OK) ? st : s;
    s = qfoc_s32k_power_init();
    st = (st != QFOC_S32K_OK) ? st : s;
    s = qfoc_s32k_pwm_cfg(table, option, &pwm);
    st = (st != QFOC_S32K_OK) ? st : s;
    qfoc_s32k_trgmux_init();
    qfoc_s32k_pdb_init(pwm.period);
    s = qfoc_s32k_adc_init();
    st = (st != QFOC_S32K_OK) ? st : s;
    qfoc_s32k_uart_init();
    s = qfoc_s32k_can_init();
    st = (st != QFOC_S32K_OK) ? st : s;
    qfoc_s32k_tick_init();
    qfoc_s32k_ftm_init(&pwm);
    qfoc_s32k_hal_init(pwm.period);
    s = qfoc_s32k_wdog_init();
    st = (st != QFOC_S32K_OK) ? st : s;
    qfoc_s32k_irq_init();
    qfoc_s32k_irq_global_enable();
    return st;
}

static uint32_t field(uint32_t reg, uint32_t shift, uint32_t width)
{
    return (reg >> shift) & ((1u << width) - 1u);
}

/* ------------------------------------------------------------------ REQ-PORT-001 */

/* REQ-PORT-001: every register the port touches during set-up and at run time is an
   aligned word inside a peripheral block of the S32K144 memory map that the port is
   meant to use; nothing else is written.
   Methods: 1a every register written during set-up and at run time checked against the
   peripheral blocks of the S32K144 memory map, aligned words only */
static void test_port_001_registers_in_known_blocks(void **state)
{
    static const struct { uint32_t base; uint32_t size; const char *name; } blocks[] = {
        { 0x40064000u, 0x1000u, "SCG" },     { 0x40065000u, 0x1000u, "PCC" },
        { 0x4007E000u, 0x1000u, "SMC" },     { 0x40048000u, 0x1000u, "SIM" },
        { 0x40049000u, 0x5000u, "PORTA..E" }, { 0x400FF0C0u, 0x40u, "GPIOD" },
        { 0x40063000u, 0x1000u, "TRGMUX" },  { 0x40026000u, 0x1000u, "FTM3" },
        { 0x40036000u, 0x1000u, "PDB0" },    { 0x40031000u, 0x1000u, "PDB1" },
        { 0x4003B000u, 0x1000u, "ADC0" },    { 0x40027000u, 0x1000u, "ADC1" },
        { 0x40037000u, 0x1000u, "LPIT0" },   { 0x4006B000u, 0x1000u, "LPUART1" },
        { 0x40024000u, 0x1000u, "FlexCAN0" }, { 0x40052000u, 0x1000u, "WDOG" },
        { 0xE000E100u, 0x400u, "NVIC" },
    };
    static qfoc_drive_t d;
    const qfoc_can_frame_t can = { 0x310u, 8u, { 1u, 2u, 3u, 4u, 5u, 6u, 7u, 8u } };
    const uint8_t frame[3] = { 1u, 2u, 3u };
    uint32_t i;
    (void)state;
    assert_int_equal(port_init_all(&qfoc_params_reference, QFOC_S32K_FTM_INT_RELOAD), QFOC_S32K_OK);
    assert_int_equal(qfoc_drive_init(&d, &qfoc_params_reference), QFOC_PARAMS_OK);
    qfoc_s32k_isr_bind(&d);
    qfoc_s32k_ftm_isr();
    qfoc_s32k_adc_isr();
    qfoc_s32k_tick_isr();
    assert_true(qfoc_hal_lin_transmit(frame, 3u));
    qfoc_s32k_uart_isr();
    assert_true(qfoc_hal_can_send(&can));
    qfoc_hal_fault_output();
    for (i = 0u; i < qfoc_fake_count(); i++) {
        const uint32_t a = qfoc_fake_addr(i);
        size_t b;
        bool inside = false;
        for (b = 0u; b < (sizeof blocks / sizeof blocks[0]); b++) {
            if ((a >= blocks[b].base) && (a < (blocks[b].base + blocks[b].size))) {
                inside = true;
            }
        }
        if (!inside) {
            print_message("register 0x%08lX outside the port's peripherals\n", (unsigned long)a);
        }
        assert_true(inside);
        assert_int_equal(a % 4u, 0u);
    }
    print_message("port touched %lu registers in %lu accesses\n", (unsigned long)qfoc_fake_count(),
                  (unsigned long)qfoc_fake_accesses());
    qfoc_s32k_isr_bind(NULL);
}

/* ------------------------------------------------------------------ REQ-PORT-002 */

/* REQ-PORT-002: 8 MHz SOSC -> SPLL -> 80 MHz core in RUN mode, every clock within the
   RM's RUN-mode limits (VCO 180..320 MHz, PLL reference 8..16 MHz, core <= 80 MHz,
   bus <= 48 MHz, flash <= 26.67 MHz, core an integer multiple of bus and flash).
   Methods: 1a the clock tree 8 MHz SOSC -> SPLL -> 80 MHz computed from the reference
   manual's formulas; 1c each clock against its RUN-mode limit (VCO 180 .. 320 MHz, reference
   8 .. 16 MHz, core 80, bus 48, flash 26.67 MHz) */
static void test_port_002_clock_run_mode(void **state)
{
    uint32_t cfg;
    uint32_t rccr;
    double ref;
    double vco;
    double spll;
    double core;
    double bus;
    double flash;
    double div1;
    double div2;
    (void)state;
    assert_int_equal(qfoc_s32k_clock_init(), QFOC_S32K_OK);
    assert_int_equal(qfoc_s32k_power_init(), QFOC_S32K_OK);
    cfg = qfoc_fake_peek(S32K_SCG_SOSCCFG);
    assert_int_equal(field(cfg, 4u, 2u), 2u);           /* RANGE: medium, 4..8 MHz crystal */
    assert_int_equal(field(cfg, 2u, 1u), 1u);           /* EREFS: crystal */
    assert_true((qfoc_fake_peek(S32K_SCG_SOSCCSR) & 1u) != 0u);
    cfg = qfoc_fake_peek(S32K_SCG_SPLLCFG);
    ref = 8.0e6 / (double)(field(cfg, 8u, 3u) + 1u);
    vco = ref * (double)(field(cfg, 16u, 5u) + 16u);
    spll = vco / 2.0;
    rccr = qfoc_fake_peek(S32K_SCG_RCCR);
    assert_int_equal(field(rccr, 24u, 4u), 6u);          /* SCS: SPLL */
    core = spll / (double)(field(rccr, 16u, 4u) + 1u);
    bus = core / (double)(field(rccr, 4u, 4u) + 1u);
    flash = core / (double)(field(rccr, 0u, 4u) + 1u);
    div1 = spll / pow(2.0, (double)field(qfoc_fake_peek(S32K_SCG_SPLLDIV), 0u, 3u) - 1.0);
    div2 = spll / pow(2.0, (double)field(qfoc_fake_peek(S32K_SCG_SPLLDIV), 8u, 3u) - 1.0);
    print_message("PLL ref %.3f MHz, VCO %.1f MHz, SPLL %.1f, core %.2f, bus %.2f, flash %.3f, "
                  "SPLLDIV1 %.1f, SPLLDIV2 %.1f MHz\n", ref / 1e6, vco / 1e6, spll / 1e6, core / 1e6,
                  bus / 1e6, flash / 1e6, div1 / 1e6, div2 / 1e6);
    assert_true((ref >= 8.0e6) && (ref <= 16.0e6));
    assert_true((vco >= 180.0e6) && (vco <= 320.0e6));
    assert_true(fabs(core - 80.0e6) < 1.0);
    assert_true(bus <= 48.0e6);
    assert_true(flash <= 26.67e6);
    assert_int_equal(field(rccr, 16u, 4u) + 1u, (field(rccr, 16u, 4u) + 1u));
    assert_true(fmod(core, bus) == 0.0);
    assert_true(fabs(div1 - 80.0e6) < 1.0);
    assert_true(fabs(div2 - 40.0e6) < 1.0);
    assert_true(fabs(core - (double)QFOC_S32K_FTM_HZ) < 1.0);
    /* SOSCDIV1 and SOSCDIV2 = 8 MHz (field 1: divide by 1). */
    assert_int_equal(field(qfoc_fake_peek(S32K_SCG_SOSCDIV), 0u, 3u), 1u);
    assert_int_equal(field(qfoc_fake_peek(S32K_SCG_SOSCDIV), 8u, 3u), 1u);
    /* Power: RUN only, PMPROT 0 (no HSRUN, no VLP), RUNM = RUN. */
    assert_int_equal(qfoc_fake_peek(S32K_SMC_PMPROT), 0u);
    assert_int_equal(field(qfoc_fake_peek(S32K_SMC_PMCTRL), 5u, 2u), 0u);
}

/* REQ-PORT-002: a clock that does not come up is reported after a bounded wait.
   Methods: 1d an oscillator that never comes up; 1l the fake register file withholds the
   SOSC valid flag */
static void test_port_002_clock_timeout(void **state)
{
    (void)state;
    model_withhold = W_SOSC;
    assert_int_equal(qfoc_s32k_clock_init(), QFOC_S32K_ERR_TIMEOUT);
    assert_int_equal(field(qfoc_fake_peek(S32K_SCG_RCCR), 24u, 4u), 0u);  /* never switched */
}

/* ------------------------------------------------------------------ REQ-PORT-003 */

/* REQ-PORT-003: each peripheral's clock gate is on, with the functional clock the
   port's timing assumes.
   Methods: 1a each peripheral's clock gate and functional clock source as the port's timing
   assumes them */
static void test_port_003_peripheral_clocks(void **state)
{
    static const struct { uint32_t pcc; uint32_t pcs; } gates[] = {
        { S32K_PCC_FTM3, 6u }, { S32K_PCC_ADC0, 6u }, { S32K_PCC_ADC1, 6u },
        { S32K_PCC_LPUART1, 1u }, { S32K_PCC_LPIT, 1u }, { S32K_PCC_FLEXCAN0, 0u },
        { S32K_PCC_PDB0, 0u }, { S32K_PCC_PDB1, 0u }, { S32K_PCC_PORTA, 0u },
        { S32K_PCC_PORTB, 0u }, { S32K_PCC_PORTC, 0u }, { S32K_PCC_PORTD, 0u },
        { S32K_PCC_PORTE, 0u },
    };
    size_t k;
    (void)state;
    assert_int_equal(port_init_all(&qfoc_params_reference, QFOC_S32K_FTM_INT_RELOAD), QFOC_S32K_OK);
    for (k = 0u; k < (sizeof gates / sizeof gates[0]); k++) {
        const uint32_t v = qfoc_fake_peek(gates[k].pcc);
        assert_true((v & (1u << 30)) != 0u);                 /* CGC */
        assert_int_equal(field(v, 24u, 3u), gates[k].pcs);   /* PCS */
    }
    /* ADC clock: SPLLDIV2 40 MHz, ADIV /1 -> within the ADC's 2..50 MHz. */
    assert_int_equal(field(qfoc_fake_peek(S32K_ADC0_BASE + S32K_ADC_CFG1), 5u, 2u), 0u);
}

/* ------------------------------------------------------------------ REQ-PORT-004 */

/* REQ-PORT-004: pin functions (S32K144 LQFP100 IO signal table) and the gate-driver
   enable, low until enabled.
   Methods: 1a each pin's function from the S32K144 LQFP100 IO signal table, the gate-driver
   enable low until enabled */
static void test_port_004_pins(void **state)
{
    static const struct { uint32_t base; uint32_t pin; uint32_t alt; } pins[] = {
        { S32K_PORTB_BASE, 8u, 2u }, { S32K_PORTB_BASE, 9u, 2u },    /* FTM3 CH0, CH1 */
        { S32K_PORTB_BASE, 10u, 2u }, { S32K_PORTB_BASE, 11u, 2u },  /* FTM3 CH2, CH3 */
        { S32K_PORTC_BASE, 10u, 2u }, { S32K_PORTC_BASE, 11u, 2u },  /* FTM3 CH4, CH5 */
        { S32K_PORTE_BASE, 7u, 3u },                                 /* FTM3_FLT0 */
        { S32K_PORTC_BASE, 6u, 2u }, { S32K_PORTC_BASE, 7u, 2u },    /* LPUART1 RX, TX */
        { S32K_PORTE_BASE, 4u, 5u }, { S32K_PORTE_BASE, 5u, 5u },    /* CAN0 RX, TX */
        { S32K_PORTA_BASE, 7u, 0u }, { S32K_PORTC_BASE, 14u, 0u },   /* ADC0_SE3, ADC0_SE12 */
        { S32K_PORTD_BASE, 2u, 0u }, { S32K_PORTB_BASE, 12u, 0u },   /* ADC1_SE2, ADC1_SE7 */
        { S32K_PORTB_BASE, 13u, 0u }, { S32K_PORTD_BASE, 5u, 1u },   /* ADC1_SE8, GPIO */
    };
    size_t k;
    (void)state;
    qfoc_s32k_pins_init();
    for (k = 0u; k < (sizeof pins / sizeof pins[0]); k++) {
        const uint32_t pcr = qfoc_fake_peek(pins[k].base + (4u * pins[k].pin));
        assert_int_equal(field(pcr, 8u, 3u), pins[k].alt);
    }
    /* Fault input pulled up (active low), gate enable an output driven low. */
    assert_int_equal(qfoc_fake_peek(S32K_PORTE_BASE + 28u) & 3u, 3u);
    assert_true((qfoc_fake_peek(S32K_GPIOD_PDDR) & (1u << 5)) != 0u);
    assert_int_equal(qfoc_fake_peek(S32K_GPIOD_PCOR), 1u << 5);
    qfoc_s32k_gate_enable(true);
    assert_int_equal(qfoc_fake_peek(S32K_GPIOD_PSOR), 1u << 5);
}

/* ------------------------------------------------------------------ REQ-PORT-005 */

static void check_pwm_setup(const qfoc_param_table_t *t, qfoc_s32k_ftm_int_t option)
{
    qfoc_s32k_pwm_cfg_t cfg;
    uint32_t sc;
    uint32_t comb;
    uint32_t ch;
    double f_pwm;
    assert_int_equal(qfoc_s32k_pwm_cfg(t, option, &cfg), QFOC_S32K_OK);
    qfoc_s32k_ftm_init(&cfg);
    sc = qfoc_fake_peek(S32K_FTM3_SC);
    assert_int_equal(qfoc_fake_peek(S32K_FTM3_MOD), t->svpwm.period);   /* MOD = period */
    assert_int_equal(qfoc_fake_peek(S32K_FTM3_CNTIN), 0u);
    assert_int_equal(field(sc, 3u, 2u), 1u);      /* CLKS: FTM input clock = SYS_CLK */
    assert_int_equal(field(sc, 0u, 3u), 0u);      /* PS: /1 */
    assert_int_equal(field(sc, 5u, 1u), 1u);      /* CPWMS: up-down */
    assert_int_equal(field(sc, 16u, 8u), 0x3Fu);  /* PWMEN0..5 */
    assert_int_equal(field(sc, 6u, 1u), (option == QFOC_S32K_FTM_INT_RELOAD) ? 1u : 0u);  /* RIE */
    assert_int_equal(field(sc, 8u, 1u), (option == QFOC_S32K_FTM_INT_OVF) ? 1u : 0u);     /* TOIE */
    /* Up-down counter: one PWM period = 2 MOD counts of the 80 MHz clock. */
    f_pwm = 80.0e6 / (2.0 * (double)qfoc_fake_peek(S32K_FTM3_MOD) * pow(2.0, (double)field(sc, 0u, 3u)));
    print_message("FTM3 MOD %lu -> PWM %.1f Hz (table %u Hz)\n",
                  (unsigned long)qfoc_fake_peek(S32K_FTM3_MOD), f_pwm, t->f_pwm_hz);
    assert_true(fabs(f_pwm - (double)t->f_pwm_hz) < 1e-6);
    /* Complementary pairs (0,1), (2,3), (4,5): COMP, DTEN, SYNCEN, FAULTEN; COMBINE and
       DECAPEN off (centre-aligned, not combined); high-true channels; 50 % at start. */
    comb = qfoc_fake_peek(S32K_FTM3_COMBINE);
    for (ch = 0u; ch < 3u; ch++) {
        const uint32_t p = field(comb, 8u * ch, 8u);
        assert_int_equal(p & 0x01u, 0u);   /* COMBINE */
        assert_int_equal(p & 0x04u, 0u);   /* DECAPEN */
        assert_int_equal(p & 0x72u, 0x72u);
    }
    assert_int_equal(field(comb, 24u, 8u), 0u);
    for (ch = 0u; ch < 6u; ch++) {
        const uint32_t csc = qfoc_fake_peek(S32K_FTM3_C0SC + (8u * ch));
        assert_int_equal(field(csc, 2u, 2u), 2u);  /* ELSB:ELSA = 10 high-true */
        assert_int_equal(qfoc_fake_peek(S32K_FTM3_C0V + (8u * ch)), t->svpwm.period / 2u);
    }
    assert_int_equal(qfoc_fake_peek(S32K_FTM3_POL), 0u);
    assert_int_equal(qfoc_fake_peek(S32K_FTM3_OUTMASK), 0x3Fu);      /* off until enabled */
    assert_true((qfoc_fake_peek(S32K_FTM3_EXTTRIG) & (1u << 6)) != 0u);   /* INITTRIGEN */
    assert_true((qfoc_fake_peek(S32K_FTM3_SYNC) & (1u << 1)) != 0u);      /* CNTMAX */
    assert_true((qfoc_fake_peek(S32K_FTM3_MODE) & 1u) != 0u);             /* FTMEN */
}

/* REQ-PORT-005: 8 kHz table: MOD 5000, 8000.0 Hz; reload interrupt.
   Methods: 1a the 8 kHz table: MOD 5000, 8000.0 Hz, the reload interrupt, from the timer's
   formulas */
static void test_port_005_pwm_8k(void **state)
{
    (void)state;
    check_pwm_setup(&qfoc_params_reference, QFOC_S32K_FTM_INT_RELOAD);
}

/* REQ-PORT-005: 16 kHz table: MOD 2500, 16000.0 Hz; overflow interrupt.
   Methods: 1a the 16 kHz table: MOD 2500, 16000.0 Hz, the overflow interrupt, from the
   timer's formulas */
static void test_port_005_pwm_16k(void **state)
{
    (void)state;
    check_pwm_setup(&qfoc_params_reference16k, QFOC_S32K_FTM_INT_OVF);
}

/* REQ-PORT-005: a table whose period does not match the 80 MHz timer is refused.
   Methods: 1c periods 0, 99, 4999 and 5001 (one beside the timer's 5000), 32768, 65535; 1d a
   table whose period does not fit the 80 MHz timer */
static void test_port_005_table_mismatch(void **state)
{
    static const uint16_t periods[] = { 0u, 99u, 4999u, 5001u, 32768u, 65535u };
    qfoc_param_table_t t = qfoc_params_reference;
    qfoc_s32k_pwm_cfg_t cfg;
    size_t k;
    (void)state;
    for (k = 0u; k < (sizeof periods / sizeof periods[0]); k++) {
        t.svpwm.period = periods[k];
        assert_int_equal(qfoc_s32k_pwm_cfg(&t, QFOC_S32K_FTM_INT_RELOAD, &cfg), QFOC_S32K_ERR_PARAM);
    }
    t = qfoc_params_reference;
    t.f_pwm_hz = 10000u;
    assert_int_equal(qfoc_s32k_pwm_cfg(&t, QFOC_S32K_FTM_INT_RELOAD, &cfg), QFOC_S32K_ERR_PARAM);
    t.f_pwm_hz = 65535u;
    t.svpwm.period = 32767u;   /* largest product 2 x 32767 x 65535 < 2^32 */
    assert_int_equal(qfoc_s32k_pwm_cfg(&t, QFOC_S32K_FTM_INT_RELOAD, &cfg), QFOC_S32K_ERR_PARAM);
}

/* ------------------------------------------------------------------ REQ-PORT-006 */

static uint32_t deadtime_ticks(uint32_t reg)
{
    static const uint32_t prescale[4] = { 1u, 1u, 4u, 16u };   /* DTPS 0x, 10, 11 */
    return prescale[field(reg, 6u, 2u)] * field(reg, 0u, 6u);
}

/* REQ-PORT-006: the inserted dead time is never shorter than asked, at most one
   prescaler step longer; the table's 1 us is exactly 80 clocks; below the port's floor
   the floor applies.
   Methods: 1b every dead time 0 .. 1200 clocks, across the three prescaler ranges; 1c the
   port's floor (dt_comp 0) and its largest value (dt_comp 30000 and beyond the register),
   the prescaler steps at 63 / 64 and 252 / 253; 1a the table's 1 us exactly 80 clocks */
static void test_port_006_deadtime(void **state)
{
    uint32_t t;
    qfoc_param_table_t tab = qfoc_params_reference;
    qfoc_s32k_pwm_cfg_t cfg;
    (void)state;
    for (t = 0u; t <= 1200u; t++) {
        uint32_t reg;
        cfg.period = 5000u;
        cfg.deadtime_ticks = (uint16_t)t;
        cfg.int_option = QFOC_S32K_FTM_INT_RELOAD;
        qfoc_s32k_ftm_init(&cfg);
        reg = qfoc_fake_peek(S32K_FTM3_DEADTIME);
        const uint32_t want = (t > QFOC_S32K_DEADTIME_MAX) ? QFOC_S32K_DEADTIME_MAX : t;
        const uint32_t got = deadtime_ticks(reg);
        const uint32_t step = (want <= 63u) ? 1u : ((want <= 252u) ? 4u : 16u);
        assert_true(got >= want);
        assert_true(got < (want + step));
        assert_int_equal(reg & ~0xFFu, 0u);
    }
    assert_int_equal(qfoc_s32k_pwm_cfg(&tab, QFOC_S32K_FTM_INT_RELOAD, &cfg), QFOC_S32K_OK);
    assert_int_equal(cfg.deadtime_ticks, 2u * tab.svpwm.dt_comp);
    qfoc_s32k_ftm_init(&cfg);
    print_message("dead time: table 2 x dt_comp = %u clocks, DEADTIME 0x%02lX = %lu clocks = %.3f us\n",
                  2u * tab.svpwm.dt_comp, (unsigned long)qfoc_fake_peek(S32K_FTM3_DEADTIME),
                  (unsigned long)deadtime_ticks(qfoc_fake_peek(S32K_FTM3_DEADTIME)),
                  (double)deadtime_ticks(qfoc_fake_peek(S32K_FTM3_DEADTIME)) / 80.0);
    assert_int_equal(deadtime_ticks(qfoc_fake_peek(S32K_FTM3_DEADTIME)), 80u);
    tab.svpwm.dt_comp = 0u;
    assert_int_equal(qfoc_s32k_pwm_cfg(&tab, QFOC_S32K_FTM_INT_RELOAD, &cfg), QFOC_S32K_OK);
    assert_int_equal(cfg.deadtime_ticks, QFOC_S32K_DEADTIME_MIN);
    tab.svpwm.dt_comp = 30000u;
    assert_int_equal(qfoc_s32k_pwm_cfg(&tab, QFOC_S32K_FTM_INT_RELOAD, &cfg), QFOC_S32K_OK);
    assert_int_equal(cfg.deadtime_ticks, QFOC_S32K_DEADTIME_MAX);
}

/* ------------------------------------------------------------------ REQ-PORT-007 */

/* REQ-PORT-007: hardware over-current path: fault input 0 enabled, filtered, active low;
   all channels to their inactive level on a fault, manual clearing; set-up protected.
   Methods: 1a the fault input 0 enabled, filtered and active low, every channel's inactive
   level, manual clearing and the write protection, from the reference manual */
static void test_port_007_fault_control(void **state)
{
    qfoc_s32k_pwm_cfg_t cfg;
    uint32_t flt;
    (void)state;
    assert_int_equal(qfoc_s32k_pwm_cfg(&qfoc_params_reference, QFOC_S32K_FTM_INT_RELOAD, &cfg), QFOC_S32K_OK);
    qfoc_s32k_ftm_init(&cfg);
    flt = qfoc_fake_peek(S32K_FTM3_FLTCTRL);
    assert_int_equal(flt & 0x0Fu, 0x01u);          /* FAULT0EN only */
    assert_int_equal(flt & 0x10u, 0x10u);          /* FFLTR0EN */
    assert_true(field(flt, 8u, 4u) > 0u);          /* FFVAL: filter on */
    assert_int_equal(flt & (1u << 15), 0u);        /* FSTATE 0: inactive level, not tri-state */
    assert_int_equal(qfoc_fake_peek(S32K_FTM3_FLTPOL) & 1u, 1u);           /* active low */
    assert_int_equal(field(qfoc_fake_peek(S32K_FTM3_MODE), 5u, 2u), 2u);   /* FAULTM 10 */
    assert_int_equal(qfoc_fake_peek(S32K_FTM3_COMBINE) & 0x404040u, 0x404040u);  /* FAULTEN0..2 */
    assert_true((qfoc_fake_peek(S32K_FTM3_FMS) & S32K_FTM_FMS_WPEN) != 0u);
}

static void set_samples(uint16_t iu, uint16_t iv, uint16_t vdc, uint16_t t_ipm, uint16_t t_pcb)
{
    qfoc_fake_poke(S32K_ADC0_BASE + S32K_ADC_RA, iu);
    qfoc_fake_poke(S32K_ADC0_BASE + S32K_ADC_RA + 4u, t_ipm);
    qfoc_fake_poke(S32K_ADC1_BASE + S32K_ADC_RA, iv);
    qfoc_fake_poke(S32K_ADC1_BASE + S32K_ADC_RA + 4u, t_pcb);
    qfoc_fake_poke(S32K_ADC1_BASE + S32K_ADC_RA + 8u, vdc);
}

/* The port set up, drive d initialised and bound, one fast step on samples at mid-scale:
   no trip. */
static void port_bind_untripped(qfoc_drive_t *d)
{
    assert_int_equal(port_init_all(&qfoc_params_reference, QFOC_S32K_FTM_INT_RELOAD), QFOC_S32K_OK);
    assert_int_equal(qfoc_drive_init(d, &qfoc_params_reference), QFOC_PARAMS_OK);
    qfoc_s32k_isr_bind(d);
    set_samples(2048u, 2048u, 2621u, 2048u, 2048u);
    qfoc_s32k_adc_isr();
    assert_false(d->f.trip);
}

/* REQ-PORT-007: a hardware trip is reported to the drive once (full-scale currents, the
   drive latches its over-current fault in the same step), and cleared only with the
   outputs masked and the fault input back to inactive.
   Methods: 1d a hardware over-current trip with its input still active, a clear attempted
   while active; 1l the comparator's fault flag set in the fake register file */
static void test_port_007_trip_reported_once_then_cleared(void **state)
{
    static qfoc_drive_t d;
    const uint32_t wpen = S32K_FTM_FMS_WPEN;
    const qfoc_pwm_t off = { { 2500u, 2500u, 2500u }, false };
    qfoc_adc_t a;
    (void)state;
    port_bind_untripped(&d);
    /* Comparator trips; its input still active. */
    qfoc_fake_poke(S32K_FTM3_FMS, S32K_FTM_FMS_FAULTF | T_FTM_FMS_FAULTF0 | S32K_FTM_FMS_FAULTIN | wpen);
    qfoc_s32k_adc_isr();
    assert_true(d.f.trip);
    assert_false(d.f.out.enable);
    assert_int_equal(qfoc_fake_peek(S32K_FTM3_OUTMASK), 0x3Fu);
    assert_true((qfoc_fake_peek(S32K_FTM3_FMS) & S32K_FTM_FMS_FAULTF) != 0u);  /* not cleared */
    qfoc_hal_adc_read(&a);
    assert_int_equal(a.iu, 2048u);   /* reported once only */
    assert_int_equal(a.iv, 2048u);
    /* Input inactive: the next write with the outputs off clears the flags, keeps WPEN. */
    qfoc_fake_poke(S32K_FTM3_FMS, S32K_FTM_FMS_FAULTF | T_FTM_FMS_FAULTF0 | wpen);
    qfoc_hal_pwm_write(&off);
    assert_int_equal(qfoc_fake_peek(S32K_FTM3_FMS), wpen);
    /* A new trip is reported again. */
    qfoc_fake_poke(S32K_FTM3_FMS, S32K_FTM_FMS_FAULTF | T_FTM_FMS_FAULTF0 | S32K_FTM_FMS_FAULTIN | wpen);
    qfoc_hal_adc_read(&a);
    assert_int_equal(a.iu, 4095u);
    assert_int_equal(a.iv, 4095u);
    qfoc_s32k_isr_bind(NULL);
}

/* REQ-PORT-007: a hardware trip that the tick's write of the outputs off (REQ-PORT-017)
   meets before the next fast step has reported it stays set: a short comparator pulse
   (its input already inactive again) between two fast steps is still reported to the
   drive, which latches OC; only then is the flag cleared.
   Methods: 1d a trip between the two interrupts, the tick running first with the fault
   input already inactive; 1l the comparator's fault flag set in the fake register file */
static void test_port_007_trip_kept_until_reported(void **state)
{
    static qfoc_drive_t d;
    const uint32_t wpen = S32K_FTM_FMS_WPEN;
    const qfoc_pwm_t off = { { 0u, 0u, 0u }, false };
    (void)state;
    port_bind_untripped(&d);
    assert_int_not_equal(d.s.sm.state, QFOC_STATE_RUN);   /* the tick writes the outputs off */
    /* A short comparator pulse: flag latched, input inactive again. */
    qfoc_fake_poke(S32K_FTM3_FMS, S32K_FTM_FMS_FAULTF | T_FTM_FMS_FAULTF0 | wpen);
    qfoc_s32k_tick_isr();
    assert_int_equal(qfoc_fake_peek(S32K_FTM3_OUTMASK), 0x3Fu);
    assert_int_equal(qfoc_fake_peek(S32K_FTM3_FMS), S32K_FTM_FMS_FAULTF | T_FTM_FMS_FAULTF0 | wpen);
    qfoc_hal_pwm_write(&off);   /* any write before the report keeps it too */
    assert_int_equal(qfoc_fake_peek(S32K_FTM3_FMS), S32K_FTM_FMS_FAULTF | T_FTM_FMS_FAULTF0 | wpen);
    /* The next fast step sees the trip and latches OC; its write then clears the flag. */
    qfoc_s32k_adc_isr();
    assert_true(d.f.trip);
    assert_false(d.f.out.enable);
    assert_int_equal(qfoc_fake_peek(S32K_FTM3_FMS), wpen);
    qfoc_s32k_isr_bind(NULL);
}

/* ------------------------------------------------------------------ REQ-PORT-008 */

/* REQ-PORT-008: compare values to the even channels, clamped to the period, loaded at
   the next reload point (LDOK); the enable drives the output mask.  REQ-PORT-018: a
   latched fault output keeps the outputs masked.
   Methods: 1c compare values 0, P / 2 and beyond the period (6000, 65535: clamped to 5000);
   1d a latched fault output (the outputs stay masked) */
static void test_port_008_pwm_write(void **state)
{
    qfoc_pwm_t p = { { 0u, 2500u, 6000u }, true };
    (void)state;
    qfoc_s32k_hal_init(5000u);
    qfoc_hal_pwm_write(&p);
    assert_int_equal(qfoc_fake_peek(S32K_FTM3_C0V), 0u);
    assert_int_equal(qfoc_fake_peek(S32K_FTM3_C0V + 16u), 2500u);
    assert_int_equal(qfoc_fake_peek(S32K_FTM3_C0V + 32u), 5000u);   /* clamped */
    assert_true((qfoc_fake_peek(S32K_FTM3_PWMLOAD) & (1u << 9)) != 0u);
    assert_int_equal(qfoc_fake_peek(S32K_FTM3_OUTMASK), 0u);
    p.enable = false;
    p.cmp[0] = 65535u;
    qfoc_hal_pwm_write(&p);
    assert_int_equal(qfoc_fake_peek(S32K_FTM3_C0V), 5000u);
    assert_int_equal(qfoc_fake_peek(S32K_FTM3_OUTMASK), 0x3Fu);
    p.enable = true;
    qfoc_hal_pwm_write(&p);
    assert_int_equal(qfoc_fake_peek(S32K_FTM3_OUTMASK), 0u);
    qfoc_hal_fault_output();
    assert_true(qfoc_hal_fault_latched());
    assert_int_equal(qfoc_fake_peek(S32K_FTM3_OUTMASK), 0x3Fu);
    qfoc_hal_pwm_write(&p);
    assert_int_equal(qfoc_fake_peek(S32K_FTM3_OUTMASK), 0x3Fu);
}

/* ------------------------------------------------------------------ REQ-PORT-009 */

/* REQ-PORT-009: FTM3 initialization trigger -> TRGMUX -> PDB0/PDB1 -> ADC0/ADC1, samples
   at the centre of the period: PDB delay = half a PWM period = the counter at MOD.
   Methods: 1a the trigger chain FTM3 -> TRGMUX -> PDB0 / PDB1 -> ADC0 / ADC1 and the PDB
   delay of half a PWM period, from the reference manual */
static void test_port_009_trigger_chain(void **state)
{
    static const uint32_t pdb[2] = { S32K_PDB0_BASE, S32K_PDB1_BASE };
    static const uint32_t n_pre[2] = { 2u, 3u };
    const uint32_t period = qfoc_params_reference.svpwm.period;
    uint32_t k;
    (void)state;
    assert_int_equal(port_init_all(&qfoc_params_reference, QFOC_S32K_FTM_INT_RELOAD), QFOC_S32K_OK);
    assert_int_equal(qfoc_fake_peek(S32K_TRGMUX_PDB0), 28u | 0x80000000u);  /* FTM3_INIT_TRIG, LK */
    assert_int_equal(qfoc_fake_peek(S32K_TRGMUX_PDB1), 28u | 0x80000000u);
    for (k = 0u; k < 2u; k++) {
        const uint32_t sc = qfoc_fake_peek(pdb[k] + S32K_PDB_SC);
        const uint32_t c1 = qfoc_fake_peek(pdb[k] + S32K_PDB_CH0C1);
        const uint32_t en = (1u << n_pre[k]) - 1u;
        double t_sample;
        double t_centre;
        assert_true((sc & (1u << 7)) != 0u);                 /* PDBEN */
        assert_int_equal(field(sc, 8u, 4u), 0u);             /* TRGSEL: trigger input 0 */
        assert_int_equal(field(sc, 12u, 3u), 0u);            /* PRESCALER /1 */
        assert_int_equal(field(sc, 2u, 2u), 0u);             /* MULT x1 */
        assert_int_equal(field(sc, 1u, 1u), 0u);             /* one shot per trigger */
        assert_true((sc & 1u) != 0u);                        /* LDOK */
        assert_int_equal(field(c1, 0u, 8u), en);
        assert_int_equal(field(c1, 8u, 8u), 1u);             /* pre-trigger 0 after its delay */
        assert_int_equal(field(c1, 16u, 8u), en & ~1u);      /* the others back to back */
        /* PDB clock = SYS_CLK 80 MHz; the sampling instant after the init trigger (counter
           at 0) must be half a PWM period: the counter at MOD, all low-side switches on. */
        t_sample = (double)qfoc_fake_peek(pdb[k] + S32K_PDB_CH0DLY0) / 80.0e6;
        t_centre = 0.5 / (double)qfoc_params_reference.f_pwm_hz;
        assert_true(fabs(t_sample - t_centre) < 1e-12);
        assert_true(qfoc_fake_peek(pdb[k] + S32K_PDB_MOD) > qfoc_fake_peek(pdb[k] + S32K_PDB_CH0DLY0));
        assert_true(qfoc_fake_peek(pdb[k] + S32K_PDB_MOD) < (2u * period));  /* done before the next trigger */
    }
    /* ADCs: 12 bit, hardware trigger, channels in pre-trigger order, one interrupt on the
       last conversion (ADC1 SC1[2], the DC bus). */
    assert_int_equal(field(qfoc_fake_peek(S32K_ADC0_BASE + S32K_ADC_CFG1), 2u, 2u), 1u);
    assert_int_equal(field(qfoc_fake_peek(S32K_ADC1_BASE + S32K_ADC_CFG1), 2u, 2u), 1u);
    assert_true((qfoc_fake_peek(S32K_ADC0_BASE + S32K_ADC_SC2) & (1u << 6)) != 0u);
    assert_true((qfoc_fake_peek(S32K_ADC1_BASE + S32K_ADC_SC2) & (1u << 6)) != 0u);
    assert_int_equal(qfoc_fake_peek(S32K_ADC0_BASE + S32K_ADC_SC1A), 3u);
    assert_int_equal(qfoc_fake_peek(S32K_ADC0_BASE + S32K_ADC_SC1A + 4u), 12u);
    assert_int_equal(qfoc_fake_peek(S32K_ADC1_BASE + S32K_ADC_SC1A), 2u);
    assert_int_equal(qfoc_fake_peek(S32K_ADC1_BASE + S32K_ADC_SC1A + 4u), 7u);
    assert_int_equal(qfoc_fake_peek(S32K_ADC1_BASE + S32K_ADC_SC1A + 8u), 8u | (1u << 6));
    assert_int_equal(qfoc_fake_peek(S32K_SIM_ADCOPT), 0u);
    /* Calibration ran (gain registers cleared, averaging off again). */
    assert_int_equal(qfoc_fake_peek(S32K_ADC0_BASE + S32K_ADC_SC3), 0u);
    assert_int_equal(qfoc_fake_peek(S32K_ADC1_BASE + S32K_ADC_SC3), 0u);
}

/* REQ-PORT-009: an ADC that never finishes its calibration is reported.
   Methods: 1d an ADC that never finishes its calibration; 1l the fake register file
   withholds the calibration's completion */
static void test_port_009_adc_calibration_timeout(void **state)
{
    (void)state;
    model_withhold = W_ADC;
    assert_int_equal(qfoc_s32k_adc_init(), QFOC_S32K_ERR_TIMEOUT);
}

/* ------------------------------------------------------------------ REQ-PORT-010 */

static double ntc_reference_dc(uint32_t code)
{
    const double r = 10000.0 * (double)code / (4096.0 - (double)code);
    const double inv = (1.0 / 298.15) + (log(r / 10000.0) / 3435.0);
    return ((1.0 / inv) - 273.15) * 10.0;
}

/* REQ-PORT-010: NTC conversion against the B-parameter equation: within 0.2 degC from -40
   to 150 degC, 0.4 degC to 180 degC, 0.8 degC to 200 degC; colder readings -40.0 degC;
   hotter, shorted and open sensors 200.0 degC.
   Methods: 1b every 12-bit code; 1c the ends of the ranges -40 and 150, 180, 200 degrees C,
   the open-sensor code and above, code 0 (shorted), 65535; 1d shorted and open sensors; 1n
   the B-parameter equation in double precision */
static void test_port_010_ntc(void **state)
{
    uint32_t code;
    double e_mid = 0.0;
    double e_hot = 0.0;
    double e_top = 0.0;
    (void)state;
    for (code = 0u; code < 4096u; code++) {
        const int16_t t = qfoc_s32k_ntc_to_dc((uint16_t)code);
        assert_true((t >= -400) && (t <= 2000));
        if (code > QFOC_S32K_NTC_OPEN_CODE) {
            assert_int_equal(t, 2000);
        } else if (code == 0u) {
            assert_int_equal(t, 2000);
        } else {
            const double ref = ntc_reference_dc(code);
            const double e = fabs((double)t - ref);
            if (ref > 2000.0) {
                assert_int_equal(t, 2000);
            } else if (ref < -400.0) {
                assert_int_equal(t, -400);
            } else if (ref <= 1500.0) {
                e_mid = (e > e_mid) ? e : e_mid;
            } else if (ref <= 1800.0) {
                e_hot = (e > e_hot) ? e : e_hot;
            } else {
                e_top = (e > e_top) ? e : e_top;
            }
        }
    }
    print_message("NTC max error: %.2f degC (-40..150), %.2f degC (150..180), %.2f degC (180..200)\n",
                  e_mid / 10.0, e_hot / 10.0, e_top / 10.0);
    assert_true(e_mid <= 2.0);
    assert_true(e_hot <= 4.0);
    assert_true(e_top <= 8.0);
    assert_int_equal(qfoc_s32k_ntc_to_dc(2048u), 250);   /* R = R25: 25.0 degC */
    assert_int_equal(qfoc_s32k_ntc_to_dc(65535u), 2000);
}

/* REQ-PORT-010: the fast step's read leaves the slow channels for the tick.
   Methods: 1c bits above the 12-bit result (0xF123); 1n the B-parameter equation at code
   1000 */
static void test_port_010_adc_read_and_temps(void **state)
{
    qfoc_adc_t a;
    int16_t t1;
    int16_t t2;
    (void)state;
    set_samples(0x1123u, 0x2234u, 0x3345u, 2048u, 1000u);
    qfoc_fake_poke(S32K_ADC0_BASE + S32K_ADC_RA, 0xF123u);   /* bits above 12 ignored */
    qfoc_hal_adc_read(&a);
    assert_int_equal(a.iu, 0x123u);
    assert_int_equal(a.iv, 0x234u);
    assert_int_equal(a.vdc, 0x345u);
    qfoc_hal_temps_read(&t1, &t2);
    assert_int_equal(t1, 250);
    assert_int_equal(t2, qfoc_s32k_ntc_to_dc(1000u));
    assert_true(fabs((double)t2 - ntc_reference_dc(1000u)) <= 5.0);
}

/* ------------------------------------------------------------------ REQ-PORT-011 */

static uint8_t t_pid(uint8_t id)
{
    const uint32_t b0 = id & 1u;
    const uint32_t b1 = (id >> 1) & 1u;
    const uint32_t b2 = (id >> 2) & 1u;
    const uint32_t b3 = (id >> 3) & 1u;
    const uint32_t b4 = (id >> 4) & 1u;
    const uint32_t b5 = (id >> 5) & 1u;
    const uint32_t p0 = b0 ^ b1 ^ b2 ^ b4;
    const uint32_t p1 = 1u ^ b1 ^ b3 ^ b4 ^ b5;
    return (uint8_t)((id & 0x3Fu) | (p0 << 6) | (p1 << 7));
}

static uint8_t t_checksum(const uint8_t *b, size_t n)
{
    uint32_t sum = 0u;
    size_t k;
    for (k = 0u; k < n; k++) {
        sum += b[k];
        if (sum > 255u) {
            sum -= 255u;
        }
    }
    return (uint8_t)(255u - sum);
}

static void t_cmd_frame(uint8_t f[7], bool on, bool clear, uint16_t rpm)
{
    f[0] = 0x55u;
    f[1] = t_pid(qfoc_params_reference.drive.lin_id_cmd);
    f[2] = (uint8_t)((on ? 1u : 0u) | (clear ? 2u : 0u));
    f[3] = (uint8_t)(rpm & 0xFFu);
    f[4] = (uint8_t)(rpm >> 8);
    f[5] = 0u;
    f[6] = t_checksum(&f[1], 5u);
}

/* One UART interrupt with the given status flags (and received byte). */
static void uart_event(uint32_t stat, uint32_t data)
{
    const uint32_t cfg = qfoc_fake_peek(S32K_LPUART1_STAT) & (S32K_LPUART_STAT_LBKDE | S32K_LPUART_STAT_BRK13);
    qfoc_fake_poke(S32K_LPUART1_DATA, data);
    qfoc_fake_poke(S32K_LPUART1_STAT, stat | cfg);
    qfoc_s32k_uart_isr();
}

/* A LIN break, the bytes, an idle line. */
static void uart_rx_frame(const uint8_t *b, size_t n)
{
    size_t k;
    uart_event(S32K_LPUART_STAT_LBKDIF, 0u);
    for (k = 0u; k < n; k++) {
        uart_event(S32K_LPUART_STAT_RDRF, b[k]);
    }
    uart_event(S32K_LPUART_STAT_IDLE, 0u);
}

/* Let the transmitter run: every byte the interrupt writes is captured. */
static size_t uart_drain_tx(uint8_t *out, size_t max)
{
    const uint32_t sentinel = 0xFFFFFFFFu;
    size_t n = 0u;
    uint32_t guard;
    for (guard = 0u; guard < 64u; guard++) {
        const uint32_t ctrl = qfoc_fake_peek(S32K_LPUART1_CTRL);
        if ((ctrl & S32K_LPUART_CTRL_TIE) != 0u) {
            uart_event(S32K_LPUART_STAT_TDRE, sentinel);
            if ((qfoc_fake_peek(S32K_LPUART1_DATA) != sentinel) && (n < max)) {
                out[n] = (uint8_t)qfoc_fake_peek(S32K_LPUART1_DATA);
                n++;
            }
        } else if ((ctrl & S32K_LPUART_CTRL_TCIE) != 0u) {
            uart_event(S32K_LPUART_STAT_TC, sentinel);
        } else {
            guard = 64u;
        }
    }
    return n;
}

/* REQ-PORT-011: LPUART1 19200 baud 8N1 (baud = 8 MHz / ((OSR + 1) SBR)), LIN break
   detection and 13-bit breaks, receive and idle interrupts.
   Methods: 1a LPUART1 at 19200 baud 8N1 from baud = 8 MHz / ((OSR + 1) SBR), within 0.5 %,
   LIN break detection and the interrupts */
static void test_port_011_uart_setup(void **state)
{
    uint32_t baud;
    uint32_t ctrl;
    double sbr_ideal;
    double rate;
    (void)state;
    qfoc_s32k_uart_init();
    baud = qfoc_fake_peek(S32K_LPUART1_BAUD);
    ctrl = qfoc_fake_peek(S32K_LPUART1_CTRL);
    sbr_ideal = 8.0e6 / ((double)(field(baud, 24u, 5u) + 1u) * 19200.0);
    rate = 8.0e6 / ((double)(field(baud, 24u, 5u) + 1u) * (double)field(baud, 0u, 13u));
    print_message("LPUART1 OSR %lu SBR %lu -> %.1f baud (%+.3f %%)\n", (unsigned long)(field(baud, 24u, 5u) + 1u),
                  (unsigned long)field(baud, 0u, 13u), rate, 100.0 * (rate - 19200.0) / 19200.0);
    assert_int_equal(field(baud, 24u, 5u), 15u);
    assert_int_equal(field(baud, 0u, 13u), (uint32_t)floor(sbr_ideal + 0.5));
    assert_true(fabs(rate - 19200.0) / 19200.0 < 0.005);
    assert_int_equal(field(baud, 13u, 1u), 0u);    /* SBNS: one stop bit */
    assert_int_equal(field(baud, 29u, 1u), 0u);    /* M10 off */
    assert_int_equal(ctrl & 0x13u, 0u);            /* PT, PE, M: 8 bits, no parity */
    assert_int_equal(ctrl & 0x3C0000u, 0x3C0000u); /* RE, TE, ILIE, RIE */
    assert_int_equal(ctrl & S32K_LPUART_CTRL_TIE, 0u);
    assert_true((qfoc_fake_peek(S32K_LPUART1_STAT) & (S32K_LPUART_STAT_LBKDE | S32K_LPUART_STAT_BRK13)) ==
                (S32K_LPUART_STAT_LBKDE | S32K_LPUART_STAT_BRK13));
    assert_true((baud & S32K_LPUART_BAUD_LBKDIE) != 0u);
}

/* REQ-PORT-011: frames delimited by break and idle; erroneous, overlong, echoed and
   unclaimed frames dropped.
   Methods: 1b a valid frame, a framing error, an overlong frame, two frames before the tick,
   a frame larger than the caller's buffer, an echo; 1d erroneous, overlong, echoed and
   unclaimed frames; 1l a framing error injected in the middle of a frame */
static void test_port_011_frame_receive(void **state)
{
    uint8_t f[7];
    uint8_t buf[QFOC_LIN_FRAME_MAX];
    uint8_t longf[12];
    uint8_t n;
    (void)state;
    qfoc_s32k_hal_init(5000u);
    qfoc_s32k_uart_init();
    t_cmd_frame(f, true, false, 3000u);
    assert_int_equal(qfoc_hal_lin_receive(buf, QFOC_LIN_FRAME_MAX), 0u);
    uart_rx_frame(f, 7u);
    n = qfoc_hal_lin_receive(buf, QFOC_LIN_FRAME_MAX);
    assert_int_equal(n, 7u);
    assert_memory_equal(buf, f, 7u);
    assert_int_equal(qfoc_hal_lin_receive(buf, QFOC_LIN_FRAME_MAX), 0u);   /* taken once */
    /* A framing error in the middle: dropped. */
    uart_event(S32K_LPUART_STAT_LBKDIF, 0u);
    uart_event(S32K_LPUART_STAT_RDRF, f[0]);
    uart_event(S32K_LPUART_STAT_RDRF | S32K_LPUART_STAT_FE, f[1]);
    uart_event(S32K_LPUART_STAT_RDRF, f[2]);
    uart_event(S32K_LPUART_STAT_IDLE, 0u);
    assert_int_equal(qfoc_hal_lin_receive(buf, QFOC_LIN_FRAME_MAX), 0u);
    /* Overlong: dropped. */
    memset(longf, 0x55, sizeof longf);
    uart_rx_frame(longf, sizeof longf);
    assert_int_equal(qfoc_hal_lin_receive(buf, QFOC_LIN_FRAME_MAX), 0u);
    /* Two frames before the tick: the first is kept. */
    uart_rx_frame(f, 7u);
    uart_rx_frame(longf, 3u);
    assert_int_equal(qfoc_hal_lin_receive(buf, QFOC_LIN_FRAME_MAX), 7u);
    /* A frame that does not fit the caller's buffer: dropped. */
    uart_rx_frame(f, 7u);
    assert_int_equal(qfoc_hal_lin_receive(buf, 6u), 0u);
    assert_int_equal(qfoc_hal_lin_receive(buf, QFOC_LIN_FRAME_MAX), 0u);
    /* Bytes received while transmitting (echo): dropped. */
    assert_true(qfoc_hal_lin_transmit(f, 7u));
    uart_rx_frame(f, 7u);
    assert_int_equal(qfoc_hal_lin_receive(buf, QFOC_LIN_FRAME_MAX), 0u);
    /* Dropped by the UART interrupt: framing error, overlong, second frame, echo (the
       frame too long for the caller is dropped by the tick, not counted here). */
    assert_int_equal(qfoc_s32k_lin_dropped(), 4u);
}

/* REQ-PORT-011: a queued frame is sent byte by byte by the transmit interrupt, after a
   break; the transmitter is busy until the last stop bit.
   Methods: 1c frames of length 0, QFOC_LIN_FRAME_MAX and QFOC_LIN_FRAME_MAX + 1; 1d a
   transmit while busy, interrupt flags without their enables */
static void test_port_011_transmit(void **state)
{
    uint8_t tx[QFOC_LIN_FRAME_MAX];
    uint8_t out[16];
    size_t n;
    size_t k;
    (void)state;
    qfoc_s32k_hal_init(5000u);
    qfoc_s32k_uart_init();
    for (k = 0u; k < QFOC_LIN_FRAME_MAX; k++) {
        tx[k] = (uint8_t)(0xA0u + k);
    }
    assert_false(qfoc_hal_lin_transmit(tx, 0u));
    assert_false(qfoc_hal_lin_transmit(tx, (uint8_t)(QFOC_LIN_FRAME_MAX + 1u)));
    assert_true(qfoc_hal_lin_transmit(tx, QFOC_LIN_FRAME_MAX));
    assert_true((qfoc_fake_peek(S32K_LPUART1_CTRL) & S32K_LPUART_CTRL_TIE) != 0u);
    assert_int_equal(qfoc_fake_peek(S32K_LPUART1_CTRL) & S32K_LPUART_CTRL_SBK, 0u);  /* toggled */
    assert_false(qfoc_hal_lin_transmit(tx, 3u));      /* busy */
    uart_event(0u, 0xFFFFFFFFu);                      /* no transmit event: nothing written */
    assert_int_equal(qfoc_fake_peek(S32K_LPUART1_DATA), 0xFFFFFFFFu);
    n = uart_drain_tx(out, sizeof out);
    assert_int_equal(n, QFOC_LIN_FRAME_MAX);
    assert_memory_equal(out, tx, QFOC_LIN_FRAME_MAX);
    assert_int_equal(qfoc_fake_peek(S32K_LPUART1_CTRL) & (S32K_LPUART_CTRL_TIE | S32K_LPUART_CTRL_TCIE), 0u);
    uart_event(S32K_LPUART_STAT_TC | S32K_LPUART_STAT_TDRE, 0xFFFFFFFFu);  /* flags without enables */
    assert_int_equal(qfoc_fake_peek(S32K_LPUART1_DATA), 0xFFFFFFFFu);
    assert_true(qfoc_hal_lin_transmit(tx, 3u));       /* free again */
}

/* ------------------------------------------------------------------ REQ-PORT-012 */

/* REQ-PORT-012: FlexCAN0 500 kbit/s from the 8 MHz oscillator clock, sample point
   75..90 %, out of freeze mode, MB0 an inactive transmit buffer.
   Methods: 1a FlexCAN0 at 500 kbit/s from the 8 MHz oscillator, its time quanta and sample
   point (75 .. 90 %) computed from the reference manual's formulas */
static void test_port_012_can_setup(void **state)
{
    uint32_t c1;
    uint32_t mcr;
    uint32_t tq;
    double rate;
    double sp;
    (void)state;
    assert_int_equal(qfoc_s32k_can_init(), QFOC_S32K_OK);
    c1 = qfoc_fake_peek(S32K_CAN0_CTRL1);
    mcr = qfoc_fake_peek(S32K_CAN0_MCR);
    tq = 1u + (field(c1, 0u, 3u) + 1u) + (field(c1, 19u, 3u) + 1u) + (field(c1, 16u, 3u) + 1u);
    rate = 8.0e6 / ((double)(field(c1, 24u, 8u) + 1u) * (double)tq);
    sp = (double)(tq - (field(c1, 16u, 3u) + 1u)) / (double)tq;
    print_message("CAN0: %lu tq/bit, %.0f bit/s, sample point %.1f %%, RJW %lu tq\n", (unsigned long)tq, rate,
                  100.0 * sp, (unsigned long)(field(c1, 22u, 2u) + 1u));
    assert_true(fabs(rate - 500000.0) < 1e-6);
    assert_true((sp >= 0.75) && (sp <= 0.90));
    assert_true((tq >= 8u) && (tq <= 25u));
    assert_true((field(c1, 22u, 2u) + 1u) <= (field(c1, 16u, 3u) + 1u));   /* RJW <= PSEG2 */
    assert_true((field(c1, 16u, 3u) + 1u) >= 2u);
    assert_int_equal(c1 & S32K_CAN_CTRL1_CLKSRC, 0u);                      /* oscillator clock */
    assert_int_equal(mcr & (S32K_CAN_MCR_MDIS | S32K_CAN_MCR_FRZ | S32K_CAN_MCR_HALT), 0u);
    assert_int_equal(mcr & T_CAN_MCR_MAXMB, 0u);
    assert_true((mcr & S32K_CAN_MCR_SRXDIS) != 0u);
    assert_int_equal(field(qfoc_fake_peek(S32K_CAN0_RAM), 24u, 4u), 8u);   /* TX inactive */
}

/* REQ-PORT-012: a frame goes to MB0 (identifier, DLC, big-endian data, CODE last);
   while it is pending the next one is refused.
   Methods: 1c the identifier 0xFFFF and DLC 9 (limited to 0x7FF and 8); 1d a frame sent
   while MB0 is still pending */
static void test_port_012_can_send(void **state)
{
    qfoc_can_frame_t f = { 0x310u, 8u, { 0x11u, 0x22u, 0x33u, 0x44u, 0x55u, 0x66u, 0x77u, 0x88u } };
    (void)state;
    assert_int_equal(qfoc_s32k_can_init(), QFOC_S32K_OK);
    assert_true(qfoc_hal_can_send(&f));
    assert_int_equal(field(qfoc_fake_peek(S32K_CAN0_RAM), 24u, 4u), 12u);     /* DATA: transmit */
    assert_int_equal(field(qfoc_fake_peek(S32K_CAN0_RAM), 16u, 4u), 8u);      /* DLC */
    assert_int_equal(field(qfoc_fake_peek(S32K_CAN0_RAM), 21u, 1u), 0u);      /* IDE: standard */
    assert_int_equal(qfoc_fake_peek(S32K_CAN0_RAM + 4u), 0x310u << 18);
    assert_int_equal(qfoc_fake_peek(S32K_CAN0_RAM + 8u), 0x11223344u);
    assert_int_equal(qfoc_fake_peek(S32K_CAN0_RAM + 12u), 0x55667788u);
    f.id = 0xFFFFu;
    f.dlc = 9u;
    assert_false(qfoc_hal_can_send(&f));                                      /* pending */
    qfoc_fake_poke(S32K_CAN0_RAM, 8u << 24);                                  /* sent */
    assert_true(qfoc_hal_can_send(&f));
    assert_int_equal(qfoc_fake_peek(S32K_CAN0_RAM + 4u), 0x7FFu << 18);
    assert_int_equal(field(qfoc_fake_peek(S32K_CAN0_RAM), 16u, 4u), 8u);
}

/* ------------------------------------------------------------------ REQ-PORT-013 */

/* REQ-PORT-013: LPIT0 channel 0 periodic at 8 MHz: (TVAL + 1) / 8 MHz = 1 ms; the tick
   acknowledges, counts and flags.
   Methods: 1a LPIT0 at 8 MHz: (TVAL + 1) / 8 MHz = 1 ms, the tick's acknowledge, count and
   flag */
static void test_port_013_tick(void **state)
{
    uint32_t k;
    (void)state;
    qfoc_s32k_tick_init();
    assert_true(fabs(((double)qfoc_fake_peek(S32K_LPIT0_TVAL0) + 1.0) / 8.0e6 - 1.0e-3) < 1e-12);
    assert_true((qfoc_fake_peek(S32K_LPIT0_MCR) & 1u) != 0u);
    assert_int_equal(qfoc_fake_peek(S32K_LPIT0_TCTRL0), 1u);   /* T_EN, 32-bit periodic */
    assert_int_equal(qfoc_fake_peek(S32K_LPIT0_MIER), 1u);
    qfoc_s32k_hal_init(5000u);
    assert_false(qfoc_hal_ms_flag_take());
    for (k = 1u; k <= 5u; k++) {
        qfoc_fake_poke(S32K_LPIT0_MSR, 0u);
        assert_int_equal(qfoc_hal_ms_tick(), k);
        assert_int_equal(qfoc_fake_peek(S32K_LPIT0_MSR), 1u);   /* TIF0 written 1 */
    }
    assert_int_equal(qfoc_hal_ms_count(), 5u);
    assert_true(qfoc_hal_ms_flag_take());
    assert_false(qfoc_hal_ms_flag_take());
}

/* ------------------------------------------------------------------ REQ-PORT-014 */

/* REQ-PORT-014: watchdog unlocked with its key, 10 ms on the 128 kHz LPO, enabled,
   configuration locked (UPDATE 0), refreshed from the tick.
   Methods: 1a the watchdog's key, 10 ms on the 128 kHz LPO, the locked configuration and its
   refresh from the tick */
static void test_port_014_watchdog(void **state)
{
    uint32_t cs;
    (void)state;
    assert_int_equal(qfoc_s32k_wdog_init(), QFOC_S32K_OK);
    cs = qfoc_fake_peek(S32K_WDOG_CS);
    print_message("WDOG timeout %.2f ms\n", (double)qfoc_fake_peek(S32K_WDOG_TOVAL) / 128.0);
    assert_true(fabs((double)qfoc_fake_peek(S32K_WDOG_TOVAL) / 128000.0 - 0.010) < 1e-12);
    assert_true((cs & S32K_WDOG_CS_EN) != 0u);
    assert_int_equal(field(cs, 8u, 2u), 1u);                 /* LPO */
    assert_true((cs & S32K_WDOG_CS_CMD32EN) != 0u);
    assert_int_equal(cs & T_WDOG_CS_UPDATE, 0u);
    assert_int_equal(cs & 0x8000u, 0u);                      /* no window */
    qfoc_s32k_tick_isr();
    assert_int_equal(qfoc_fake_peek(S32K_WDOG_CNT), 0xB480A602u);
}

/* ------------------------------------------------------------------ REQ-PORT-015 */

static uint32_t irq_prio(uint32_t irq)
{
    return field(qfoc_fake_peek(S32K_NVIC_IPR0 + (4u * (irq / 4u))), 8u * (irq % 4u), 8u);
}

/* REQ-PORT-015: ADC-complete above the PWM-period interrupt above the 1 ms tick above
   the UART; all four enabled; priorities in the 4 implemented bits.
   Methods: 1a the four interrupts enabled, their order of priority in the 4 implemented bits */
static void test_port_015_nvic(void **state)
{
    static const uint32_t irqs[4] = { 40u, 122u, 48u, 33u };
    uint32_t k;
    (void)state;
    qfoc_s32k_irq_init();
    qfoc_s32k_irq_global_enable();
    (void)qfoc_fake_reg(S32K_NVIC_ISER0);   /* the model sees the last write */
    assert_true(qfoc_fake_irq_enabled);
    for (k = 0u; k < 4u; k++) {
        assert_true((nvic_enabled[irqs[k] / 32u] & (1u << (irqs[k] % 32u))) != 0u);
        assert_int_equal(irq_prio(irqs[k]) & 0x0Fu, 0u);
        if (k > 0u) {
            assert_true(irq_prio(irqs[k - 1u]) < irq_prio(irqs[k]));
        }
    }
    assert_true(irq_prio(40u) > 0u);   /* priority 0 left free */
    qfoc_s32k_irq_global_disable();
    assert_false(qfoc_fake_irq_enabled);
}

/* ------------------------------------------------------------------ REQ-PORT-016/017 */

/* REQ-PORT-016, REQ-PORT-017 (with REQ-PORT-008 compare values and output mask,
   REQ-PORT-011 status frames on the UART, REQ-PORT-012 CAN frames in MB0, as the
   interrupts use them): the interrupts call the library in order.  Drive A runs
   through the port's interrupts only (samples in ADC result registers, command frames
   byte by byte through the UART interrupt, status frames and CAN frames taken from the
   registers); twin B is called directly with the same samples, temperatures and frames.
   For 600 ms (PRECHARGE, calibration, STOP, RUN/CATCH, ALIGN, the samples in ALIGN carrying the
   alignment current of a motor at rest) every PWM period's compare
   registers and output mask equal B's output, every status frame on the UART equals
   B's, every CAN frame in MB0 equals B's, and the states agree at every tick.  RUN is
   entered in CATCH (flying start, REQ-DRV-027), whose zero-current loops see only the
   samples' noise here (the samples do not answer the voltage): the rotor is found
   standing once CATCH's filter and dwell have passed (about 80 ms), and ALIGN follows and
   lasts align_ms (300 ms); the twins run for 600 ms, so that they end in ALIGN.  (With the
   decoupling feed-forward that CATCH once ran, the observer wandered on its own voltage and
   ALIGN came some 300 ms after the RUN entry.)
   Methods: 1b 600 ms through PRECHARGE, calibration, STOP, RUN / CATCH and ALIGN with noisy
   samples; 1n a twin drive called directly with the same samples, temperatures and frames:
   the same compare registers, output mask, status and CAN frames in every period and tick */
static void test_port_016_017_isr_twin(void **state)
{
    static qfoc_drive_t da;
    static qfoc_drive_t db;
    const qfoc_param_table_t *t = &qfoc_params_reference;
    const uint32_t per_ms = t->f_pwm_hz / 1000u;
    uint32_t ms;
    uint32_t p;
    uint32_t frames_tx = 0u;
    uint32_t frames_can = 0u;
    uint32_t moved = 0u;
    uint32_t lcg = 12345u;
    uint32_t ms_align = 0u;   /* ticks that left both twins in ALIGN */
    uint32_t ms_run = 0u;     /* the tick that entered RUN */
    uint32_t ms_to_align = 0u;
    (void)state;
    assert_int_equal(port_init_all(t, QFOC_S32K_FTM_INT_RELOAD), QFOC_S32K_OK);
    assert_int_equal(qfoc_drive_init(&da, t), QFOC_PARAMS_OK);
    assert_int_equal(qfoc_drive_init(&db, t), QFOC_PARAMS_OK);
    qfoc_s32k_isr_bind(&da);
    for (ms = 0u; ms < 600u; ms++) {
        uint8_t frame[7];
        uint8_t tx[16];
        size_t ntx;
        qfoc_tick_in_t in;
        qfoc_tick_out_t ob;
        for (p = 0u; p < per_ms; p++) {
            qfoc_adc_t a;
            qfoc_pwm_t pb;
            /* in ALIGN a motor at rest carries the d reference on phase u (angle 0):
               i_u = i_d, i_v = -i_d / 2, 16 Q15 counts per code */
            const int32_t ia = ((db.s.sm.state == QFOC_STATE_RUN) &&
                                (db.s.sm.sub == QFOC_SUB_ALIGN)) ? ((int32_t)db.s.id_ref / 16) : 0;
            lcg = (lcg * 1664525u) + 1013904223u;
            a.iu = (uint16_t)((int32_t)(2046u + ((lcg >> 16) % 5u)) + ia);
            a.iv = (uint16_t)((int32_t)(2046u + ((lcg >> 20) % 5u)) - (ia / 2));
            a.vdc = (uint16_t)(2619u + ((lcg >> 24) % 5u));
            set_samples(a.iu, a.iv, a.vdc, 2048u, 2100u);
            qfoc_s32k_ftm_isr();
            qfoc_s32k_adc_isr();
            pb = qfoc_drive_fast_step(&db, &a);
            assert_int_equal(qfoc_fake_peek(S32K_FTM3_C0V), pb.cmp[0]);
            assert_int_equal(qfoc_fake_peek(S32K_FTM3_C0V + 16u), pb.cmp[1]);
            assert_int_equal(qfoc_fake_peek(S32K_FTM3_C0V + 32u), pb.cmp[2]);
            assert_int_equal(qfoc_fake_peek(S32K_FTM3_OUTMASK), pb.enable ? 0u : 0x3Fu);
            if (pb.cmp[0] != (t->svpwm.period / 2u)) {
                moved++;
            }
        }
        in.t_ipm = qfoc_s32k_ntc_to_dc(2048u);
        in.t_pcb = qfoc_s32k_ntc_to_dc(2100u);
        in.rx = frame;
        in.rx_len = 0u;
        if ((ms % 10u) == 0u) {
            t_cmd_frame(frame, true, false, 3000u);
            uart_rx_frame(frame, 7u);
            in.rx_len = 7u;
        }
        qfoc_fake_poke(S32K_LPIT0_MSR, 0u);
        qfoc_s32k_tick_isr();
        assert_int_equal(qfoc_fake_peek(S32K_LPIT0_MSR), 1u);   /* timer acknowledged */
        ob = qfoc_drive_tick(&db, &in);
        ntx = uart_drain_tx(tx, sizeof tx);
        assert_int_equal(ntx, ob.tx_len);
        if (ob.tx_len > 0u) {
            assert_memory_equal(tx, ob.tx, ob.tx_len);
            frames_tx++;
        }
        if (ob.can_send) {
            const uint32_t w2 = ((uint32_t)ob.can.data[0] << 24) | ((uint32_t)ob.can.data[1] << 16) |
                                ((uint32_t)ob.can.data[2] << 8) | ob.can.data[3];
            assert_int_equal(field(qfoc_fake_peek(S32K_CAN0_RAM), 24u, 4u), 12u);
            assert_int_equal(qfoc_fake_peek(S32K_CAN0_RAM + 4u), (uint32_t)ob.can.id << 18);
            assert_int_equal(qfoc_fake_peek(S32K_CAN0_RAM + 8u), w2);
            qfoc_fake_poke(S32K_CAN0_RAM, 8u << 24);   /* transmitted */
            frames_can++;
        } else {
            assert_int_equal(field(qfoc_fake_peek(S32K_CAN0_RAM), 24u, 4u), 8u);   /* nothing new */
        }
        assert_int_equal(da.s.sm.state, db.s.sm.state);
        assert_int_equal(da.s.sm.sub, db.s.sm.sub);
        assert_int_equal(qfoc_fake_peek(S32K_WDOG_CNT), 0xB480A602u);
        if ((db.s.sm.state == QFOC_STATE_RUN) && (db.s.sm.t_state == 0u) &&
            (db.s.sm.sub == QFOC_SUB_CATCH)) {
            ms_run = ms;
        }
        if ((db.s.sm.state == QFOC_STATE_RUN) && (db.s.sm.sub == QFOC_SUB_ALIGN)) {
            if (ms_align == 0u) {
                ms_to_align = ms - ms_run;
            }
            ms_align++;
        }
    }
    print_message("twin run: state %d sub %d after 600 ms, RUN at %lu ms, ALIGN %lu ms later "
                  "and for %lu ms, %lu status frames, %lu CAN frames, %lu periods off 50 %%, "
                  "%lu fast steps\n", (int)da.s.sm.state, (int)da.s.sm.sub,
                  (unsigned long)ms_run, (unsigned long)ms_to_align, (unsigned long)ms_align,
                  (unsigned long)frames_tx, (unsigned long)frames_can, (unsigned long)moved,
                  (unsigned long)qfoc_s32k_fast_steps());
    assert_int_equal(da.s.sm.state, QFOC_STATE_RUN);
    assert_int_equal(da.s.sm.sub, QFOC_SUB_ALIGN);
    assert_true(ms_align >= 100u);   /* the twins agreed through ALIGN */
    assert_int_equal(qfoc_fake_peek(S32K_FTM3_OUTMASK), 0u);
    assert_true(moved > 0u);
    assert_int_equal(frames_tx, 60u);   /* a status frame per command, every 10 ms */
    assert_int_equal(frames_can, 6u);   /* a CAN frame every 100 ms */
    assert_int_equal(qfoc_s32k_fast_steps(), 600u * per_ms);
    assert_false(qfoc_hal_fault_latched());
    qfoc_s32k_isr_bind(NULL);
}

/* REQ-PORT-017: one valid command frame in the fake UART -> the next tick sends a
   status frame: sync, PID of the status identifier, 8 data bytes, valid checksum.
   Methods: 1a one valid command frame in the UART and the status frame of the next tick:
   sync, PID, 8 data bytes, valid checksum */
static void test_port_017_status_frame_after_command(void **state)
{
    static qfoc_drive_t d;
    uint8_t f[7];
    uint8_t tx[16];
    size_t n;
    (void)state;
    assert_int_equal(port_init_all(&qfoc_params_reference, QFOC_S32K_FTM_INT_RELOAD), QFOC_S32K_OK);
    assert_int_equal(qfoc_drive_init(&d, &qfoc_params_reference), QFOC_PARAMS_OK);
    qfoc_s32k_isr_bind(&d);
    set_samples(2048u, 2048u, 2621u, 2048u, 2048u);
    qfoc_s32k_tick_isr();
    assert_int_equal(uart_drain_tx(tx, sizeof tx), 0u);   /* no command, no answer */
    t_cmd_frame(f, false, false, 0u);
    uart_rx_frame(f, 7u);
    qfoc_s32k_tick_isr();
    n = uart_drain_tx(tx, sizeof tx);
    assert_int_equal(n, 11u);
    assert_int_equal(tx[0], 0x55u);
    assert_int_equal(tx[1], t_pid(qfoc_params_reference.drive.lin_id_status));
    assert_int_equal(tx[10], t_checksum(&tx[1], 9u));
    /* A corrupted command is not answered. */
    f[6] = (uint8_t)(f[6] ^ 1u);
    uart_rx_frame(f, 7u);
    qfoc_s32k_tick_isr();
    assert_int_equal(uart_drain_tx(tx, sizeof tx), 0u);
    qfoc_s32k_isr_bind(NULL);
}

/* REQ-PORT-017: a status frame the UART refuses (the transmitter still busy with the
   previous frame) and a CAN frame the controller refuses (MB0 still pending) are dropped
   and counted, not retried; the next command is answered and the next CAN frame sent;
   binding a drive resets the counts.
   Methods: 1d a status frame while the transmitter is busy, a CAN frame while MB0 is
   pending: dropped and counted, not retried */
static void test_port_017_refused_frames_counted(void **state)
{
    static qfoc_drive_t d;
    uint8_t f[7];
    uint8_t tx[16];
    const uint8_t other[3] = { 0x01u, 0x02u, 0x03u };
    uint32_t ms;
    (void)state;
    assert_int_equal(port_init_all(&qfoc_params_reference, QFOC_S32K_FTM_INT_RELOAD), QFOC_S32K_OK);
    assert_int_equal(qfoc_drive_init(&d, &qfoc_params_reference), QFOC_PARAMS_OK);
    qfoc_s32k_isr_bind(&d);
    set_samples(2048u, 2048u, 2621u, 2048u, 2048u);
    assert_int_equal(qfoc_s32k_lin_tx_refused(), 0u);
    assert_int_equal(qfoc_s32k_can_tx_refused(), 0u);
    /* LIN: a command is taken while the transmitter still sends another frame. */
    t_cmd_frame(f, false, false, 0u);
    uart_rx_frame(f, 7u);
    assert_true(qfoc_hal_lin_transmit(other, 3u));
    qfoc_s32k_tick_isr();
    assert_int_equal(qfoc_s32k_lin_tx_refused(), 1u);
    assert_int_equal(uart_drain_tx(tx, sizeof tx), 3u);          /* only the other frame */
    uart_rx_frame(f, 7u);                                         /* the master polls again */
    qfoc_s32k_tick_isr();
    assert_int_equal(uart_drain_tx(tx, sizeof tx), 11u);
    assert_int_equal(qfoc_s32k_lin_tx_refused(), 1u);
    /* CAN: the first status frame stays pending in MB0 (the fake bus never sends it). */
    for (ms = 0u; (ms < 200u) && (field(qfoc_fake_peek(S32K_CAN0_MB0_CS), 24u, 4u) != 12u); ms++) {
        qfoc_s32k_tick_isr();
    }
    assert_int_equal(field(qfoc_fake_peek(S32K_CAN0_MB0_CS), 24u, 4u), 12u);
    assert_int_equal(qfoc_s32k_can_tx_refused(), 0u);
    for (ms = 0u; ms < 100u; ms++) {
        qfoc_s32k_tick_isr();
    }
    assert_int_equal(qfoc_s32k_can_tx_refused(), 1u);             /* 100 ms later: refused */
    qfoc_fake_poke(S32K_CAN0_MB0_CS, 8u << 24);                   /* the bus sent it */
    for (ms = 0u; ms < 100u; ms++) {
        qfoc_s32k_tick_isr();
    }
    assert_int_equal(field(qfoc_fake_peek(S32K_CAN0_MB0_CS), 24u, 4u), 12u);
    assert_int_equal(qfoc_s32k_can_tx_refused(), 1u);
    assert_false(qfoc_hal_fault_latched());
    qfoc_s32k_isr_bind(&d);
    assert_int_equal(qfoc_s32k_lin_tx_refused(), 0u);
    assert_int_equal(qfoc_s32k_can_tx_refused(), 0u);
    qfoc_s32k_isr_bind(NULL);
}

/* ------------------------------------------------------------------ REQ-PORT-018 */

/* REQ-PORT-018: the ADC chain is supervised: up to QFOC_S32K_MISSED_STEPS_MAX missing
   fast steps per millisecond are tolerated; more latch the fault output (outputs masked,
   gate driver off) for good.
   Methods: 1c QFOC_S32K_MISSED_STEPS_MAX missing fast steps per millisecond (tolerated) and
   one more (the fault output latched); 1d missed fast steps of the ADC chain; 1l ADC
   interrupts withheld for the periods */
static void test_port_018_supervision(void **state)
{
    static qfoc_drive_t d;
    const qfoc_pwm_t on = { { 2500u, 2500u, 2500u }, true };
    uint32_t p;
    (void)state;
    assert_int_equal(port_init_all(&qfoc_params_reference, QFOC_S32K_FTM_INT_RELOAD), QFOC_S32K_OK);
    assert_int_equal(qfoc_drive_init(&d, &qfoc_params_reference), QFOC_PARAMS_OK);
    qfoc_s32k_isr_bind(&d);
    qfoc_s32k_gate_enable(true);
    set_samples(2048u, 2048u, 2621u, 2048u, 2048u);
    /* 8 periods, 6 fast steps: tolerated. */
    for (p = 0u; p < 8u; p++) {
        qfoc_s32k_ftm_isr();
        if (p < 6u) {
            qfoc_s32k_adc_isr();
        }
    }
    qfoc_s32k_tick_isr();
    assert_false(qfoc_hal_fault_latched());
    /* 8 periods, 5 fast steps: fault. */
    for (p = 0u; p < 8u; p++) {
        qfoc_s32k_ftm_isr();
        if (p < 5u) {
            qfoc_s32k_adc_isr();
        }
    }
    qfoc_s32k_tick_isr();
    assert_true(qfoc_hal_fault_latched());
    assert_int_equal(qfoc_fake_peek(S32K_FTM3_OUTMASK), 0x3Fu);
    assert_int_equal(qfoc_fake_peek(S32K_GPIOD_PCOR), 1u << 5);
    qfoc_hal_pwm_write(&on);
    assert_int_equal(qfoc_fake_peek(S32K_FTM3_OUTMASK), 0x3Fu);
    /* Periods counted by either interrupt flag; both flags cleared. */
    qfoc_fake_poke(S32K_FTM3_SC, qfoc_fake_peek(S32K_FTM3_SC) | S32K_FTM_SC_TOF | S32K_FTM_SC_RF);
    p = qfoc_hal_pwm_periods();
    qfoc_s32k_ftm_isr();
    assert_int_equal(qfoc_hal_pwm_periods(), p + 1u);
    assert_int_equal(qfoc_fake_peek(S32K_FTM3_SC) & (S32K_FTM_SC_TOF | S32K_FTM_SC_RF), 0u);
    qfoc_s32k_isr_bind(NULL);
}

/* REQ-PORT-016: without a drive bound the ADC interrupt keeps the outputs off.
   Methods: 1d the ADC interrupt with no drive bound: the outputs stay off */
static void test_port_016_unbound_isr_outputs_off(void **state)
{
    (void)state;
    qfoc_s32k_isr_bind(NULL);
    qfoc_s32k_hal_init(5000u);
    qfoc_fake_poke(S32K_FTM3_OUTMASK, 0u);
    qfoc_s32k_adc_isr();
    assert_int_equal(qfoc_fake_peek(S32K_FTM3_OUTMASK), 0x3Fu);
    qfoc_s32k_tick_isr();
    assert_int_equal(qfoc_hal_ms_count(), 1u);
}

/* REQ-PORT-002, REQ-PORT-012, REQ-PORT-014: every bounded wait of the set-up ends with a timeout status
   when the hardware never answers (and the set-up goes on, so main() can keep the
   outputs off).
   Methods: 1b each bounded wait of the set-up (SPLL, SCS, PMSTAT, LPMACK, FRZACK, UNFRZ,
   NOTRDY, ULK, RCS); 1d hardware that never answers; 1l the fake register file withholds
   each flag */
static void test_port_002_012_014_wait_timeouts(void **state)
{
    static const struct { uint32_t withhold; int which; } cases[] = {
        { W_SPLL, 0 }, { W_SCS, 0 }, { W_PMSTAT, 1 }, { W_LPMACK, 2 }, { W_FRZACK, 2 },
        { W_UNFRZ, 2 }, { W_NOTRDY, 2 }, { W_ULK, 3 }, { W_RCS, 3 },
    };
    size_t k;
    (void)state;
    for (k = 0u; k < (sizeof cases / sizeof cases[0]); k++) {
        int32_t st;
        qfoc_fake_reset();
        qfoc_fake_set_hook(hw_model);
        model_withhold = cases[k].withhold;
        can_frozen = false;
        if (cases[k].which == 0) {
            st = qfoc_s32k_clock_init();
        } else if (cases[k].which == 1) {
            st = qfoc_s32k_power_init();
        } else if (cases[k].which == 2) {
            st = qfoc_s32k_can_init();
        } else {
            st = qfoc_s32k_wdog_init();
        }
        if (st != QFOC_S32K_ERR_TIMEOUT) {
            print_message("case %lu: no timeout\n", (unsigned long)k);
        }
        assert_int_equal(st, QFOC_S32K_ERR_TIMEOUT);
    }
    model_withhold = 0u;
}

/* ------------------------------------------------------------------ REQ-PORT-019 */

/* REQ-PORT-019: the flash configuration field: no backdoor key, no protection,
   FSEC = 0xFE (SEC = 10: unsecured; KEYEN = 11: backdoor disabled), FOPT 0x7F.
   Methods: 1a the 16 bytes of the flash configuration field (no backdoor key, no protection,
   FSEC 0xFE, FOPT 0x7F) */
static void test_port_019_flash_config_field(void **state)
{
    static const uint8_t expected[16] = {
        0xFFu, 0xFFu, 0xFFu, 0xFFu, 0xFFu, 0xFFu, 0xFFu, 0xFFu,
        0xFFu, 0xFFu, 0xFFu, 0xFFu, 0xFEu, 0x7Fu, 0xFFu, 0xFFu
    };
    (void)state;
    assert_int_equal(field(qfoc_s32k_flash_config[12], 0u, 2u), 2u);   /* SEC: unsecured */
    assert_int_equal(field(qfoc_s32k_flash_config[12], 6u, 2u), 3u);   /* KEYEN: disabled */
    assert_memory_equal(qfoc_s32k_flash_config, expected, sizeof expected);
}

/* ------------------------------------------------------------------ REQ-PORT-020/021 */

/* The single-shunt set-up of the port (s32k144_port.h), in main.c's order. */
static int32_t port_init_shunt_all(const qfoc_param_table_t *table, qfoc_s32k_ftm_int_t option)
{
    int32_t st = QFOC_S32K_OK;
    int32_t s;
    qfoc_s32k_pwm_cfg_t pwm;
    qfoc_s32k_pins_init_shunt();
    s = qfoc_s32k_clock_init();
    st = (st != QFOC_S32K_OK) ? st : s;
    s = qfoc_s32k_power_init();
    st = (st != QFOC_S32K_OK) ? st : s;
    s = qfoc_s32k_pwm_cfg(table, option, &pwm);
    st = (st != QFOC_S32K_OK) ? st : s;
    qfoc_s32k_trgmux_init();
    qfoc_s32k_pdb_init_shunt(pwm.period);
    s = qfoc_s32k_adc_init_shunt();
    st = (st != QFOC_S32K_OK) ? st : s;
    qfoc_s32k_uart_init();
    s = qfoc_s32k_can_init();
    st = (st != QFOC_S32K_OK) ? st : s;
    qfoc_s32k_tick_init();
    qfoc_s32k_ftm_init_shunt(&pwm);
    qfoc_s32k_hal_init_shunt(pwm.period);
    s = qfoc_s32k_wdog_init();
    st = (st != QFOC_S32K_OK) ? st : s;
    qfoc_s32k_irq_init();
    qfoc_s32k_irq_global_enable();
    return st;
}

/* Register facts of the single-shunt path used by the tests only (S32K1xx RM Rev. 13). */
#define T_PCR_PTC15 (S32K_PORTC_BASE + (4u * 15u))   /* PORTC_PCR15 */
#define T_PDB0_DLY1 (S32K_PDB0_BASE + 0x01Cu)       /* PDB0_CH0DLY1 */

/* The FTM3 counter value at which a PDB0 pre-trigger with delay `dly` fires: the PDB is
   started by the FTM3 initialization trigger (counter at CNTIN) and counts its own clock
   (SYS_CLK / (PRESCALER x MULT), SC fields), the FTM its (SYS_CLK / 2^PS). */
static double pdb_instant_ftm_counts(uint32_t dly)
{
    static const double mult[4] = { 1.0, 10.0, 20.0, 40.0 };   /* MULT 00, 01, 10, 11 */
    const uint32_t sc = qfoc_fake_peek(S32K_PDB0_BASE + S32K_PDB_SC);
    const double pdb_clk = 80.0e6 / (pow(2.0, (double)field(sc, 12u, 3u)) * mult[field(sc, 2u, 2u)]);
    const double ftm_clk = 80.0e6 / pow(2.0, (double)field(qfoc_fake_peek(S32K_FTM3_SC), 0u, 3u));
    return (double)qfoc_fake_peek(S32K_FTM3_CNTIN) + ((double)dly * ftm_clk / pdb_clk);
}

/* Whether phase k's high side conducts at FTM3 counter value c, from the registers: a
   combined pair (COMBINEm) of an up counter (CPWMS 0), high-true (ELSB:ELSA = 10), is set at
   the C(2k)V match and cleared at the C(2k+1)V match. */
static bool combined_high(uint32_t k, uint32_t c)
{
    const uint32_t set = qfoc_fake_peek(S32K_FTM3_C0V + (16u * k));
    const uint32_t clr = qfoc_fake_peek(S32K_FTM3_C0V + (16u * k) + 8u);
    return (c >= set) && (c < clr);
}

/* The switching state (bit k: phase k high) at counter value c. */
static uint32_t combined_state(uint32_t c)
{
    return (combined_high(0u, c) ? 1u : 0u) | (combined_high(1u, c) ? 2u : 0u) |
           (combined_high(2u, c) ? 4u : 0u);
}

/* REQ-PORT-020: the single-shunt set-up: FTM3 counts up from 0 to MOD = 2 period - 1 (the
   table's PWM frequency), the three complementary pairs combined with dead time,
   synchronized loading and fault control, 50 % and masked at start; PDB0 pre-triggers 0
   and 1 after their own delays, 2 back to back, delays loaded at the counter's MOD; ADC0
   converts ADC0_SE13 (PTC15, analog) twice, then T_IPM; PDB1 and ADC1 as with two sensors.
   Methods: 1a the timer, PDB and ADC fields of the single-shunt set-up from the reference
   manual: the PWM frequency of the up counter, the combined pairs, the pre-trigger modes,
   the load mode, the channels and the pin */
static void test_port_020_shunt_setup(void **state)
{
    const qfoc_param_table_t *t = &qfoc_params_reference;
    const uint32_t period = t->svpwm.period;
    uint32_t sc;
    uint32_t comb;
    uint32_t ch;
    uint32_t c1;
    double f_pwm;
    (void)state;
    qfoc_fake_poke(T_PCR_PTC15, 0x700u);   /* not analog before the set-up */
    assert_int_equal(port_init_shunt_all(t, QFOC_S32K_FTM_INT_RELOAD), QFOC_S32K_OK);
    assert_int_equal(field(qfoc_fake_peek(T_PCR_PTC15), 8u, 3u), 0u);   /* ALT0: ADC0_SE13 */
    /* FTM3: up counter, one period = MOD - CNTIN + 1 clocks. */
    sc = qfoc_fake_peek(S32K_FTM3_SC);
    assert_int_equal(field(sc, 5u, 1u), 0u);       /* CPWMS 0: up counting */
    assert_int_equal(field(sc, 3u, 2u), 1u);       /* CLKS: SYS_CLK */
    assert_int_equal(field(sc, 0u, 3u), 0u);       /* PS /1 */
    assert_int_equal(field(sc, 16u, 8u), 0x3Fu);   /* PWMEN0..5 */
    assert_int_equal(field(sc, 6u, 1u), 1u);       /* RIE */
    assert_int_equal(qfoc_fake_peek(S32K_FTM3_CNTIN), 0u);
    assert_int_equal(qfoc_fake_peek(S32K_FTM3_MOD), (2u * period) - 1u);
    f_pwm = 80.0e6 / ((double)(qfoc_fake_peek(S32K_FTM3_MOD) - qfoc_fake_peek(S32K_FTM3_CNTIN) + 1u));
    print_message("shunt FTM3 MOD %lu (up) -> PWM %.1f Hz (table %u Hz)\n",
                  (unsigned long)qfoc_fake_peek(S32K_FTM3_MOD), f_pwm, t->f_pwm_hz);
    assert_true(fabs(f_pwm - (double)t->f_pwm_hz) < 1e-6);
    /* Pairs: COMBINE, COMP, DTEN, SYNCEN, FAULTEN; DECAPEN, DECAP, MCOMBINE off. */
    comb = qfoc_fake_peek(S32K_FTM3_COMBINE);
    for (ch = 0u; ch < 3u; ch++) {
        assert_int_equal(field(comb, 8u * ch, 8u), 0x73u);
    }
    assert_int_equal(field(comb, 24u, 8u), 0u);
    for (ch = 0u; ch < 6u; ch++) {
        assert_int_equal(field(qfoc_fake_peek(S32K_FTM3_C0SC + (8u * ch)), 2u, 2u), 2u);   /* high-true */
    }
    for (ch = 0u; ch < 3u; ch++) {
        uint32_t c;
        uint32_t on = 0u;
        for (c = 0u; c <= qfoc_fake_peek(S32K_FTM3_MOD); c++) {
            on += combined_high(ch, c) ? 1u : 0u;
        }
        assert_int_equal(on, period);                                          /* 50 % */
        assert_true(combined_high(ch, period) && !combined_high(ch, 0u));      /* centred */
    }
    assert_int_equal(deadtime_ticks(qfoc_fake_peek(S32K_FTM3_DEADTIME)), 80u);
    assert_int_equal(qfoc_fake_peek(S32K_FTM3_OUTMASK), 0x3Fu);
    assert_true((qfoc_fake_peek(S32K_FTM3_EXTTRIG) & (1u << 6)) != 0u);    /* INITTRIGEN */
    assert_true((qfoc_fake_peek(S32K_FTM3_SYNC) & (1u << 1)) != 0u);       /* CNTMAX */
    assert_int_equal(qfoc_fake_peek(S32K_FTM3_FLTCTRL) & 0x11u, 0x11u);    /* FAULT0EN, filter */
    assert_int_equal(field(qfoc_fake_peek(S32K_FTM3_MODE), 5u, 2u), 2u);   /* FAULTM 10 */
    /* PDB0: one shot, SYS_CLK / 1, trigger input 0 (TRGMUX: FTM3 init trigger), delays
       loaded when the counter reaches MOD; pre-triggers 0, 1 after their delays, 2 back to
       back; the idle instants period / 4, period / 2; done before the next trigger. */
    assert_int_equal(qfoc_fake_peek(S32K_TRGMUX_PDB0), 28u | 0x80000000u);
    sc = qfoc_fake_peek(S32K_PDB0_BASE + S32K_PDB_SC);
    assert_true((sc & (1u << 7)) != 0u);              /* PDBEN */
    assert_int_equal(field(sc, 18u, 2u), 1u);         /* LDMOD 01 */
    assert_int_equal(field(sc, 8u, 4u), 0u);          /* TRGSEL */
    assert_int_equal(field(sc, 12u, 3u), 0u);         /* PRESCALER */
    assert_int_equal(field(sc, 2u, 2u), 0u);          /* MULT */
    assert_int_equal(field(sc, 1u, 1u), 0u);          /* CONT 0 */
    c1 = qfoc_fake_peek(S32K_PDB0_BASE + S32K_PDB_CH0C1);
    assert_int_equal(field(c1, 0u, 8u), 0x07u);       /* EN: pre-triggers 0, 1, 2 */
    assert_int_equal(field(c1, 8u, 8u), 0x03u);       /* TOS: 0 and 1 after their delays */
    assert_int_equal(field(c1, 16u, 8u), 0x04u);      /* BB: 2 after the conversion of 1 */
    assert_int_equal(qfoc_fake_peek(S32K_PDB0_BASE + S32K_PDB_CH0DLY0), period / 4u);
    assert_int_equal(qfoc_fake_peek(T_PDB0_DLY1), period / 2u);
    assert_true(fabs(pdb_instant_ftm_counts(qfoc_fake_peek(T_PDB0_DLY1)) - (double)(period / 2u)) < 1e-9);
    assert_int_equal(qfoc_fake_peek(S32K_PDB0_BASE + S32K_PDB_MOD), (2u * period) - 1u);
    /* PDB1 as with two sensors: pre-trigger 0 at the centre, then back to back. */
    c1 = qfoc_fake_peek(S32K_PDB1_BASE + S32K_PDB_CH0C1);
    assert_int_equal(c1, 0x060107u);
    assert_int_equal(qfoc_fake_peek(S32K_PDB1_BASE + S32K_PDB_CH0DLY0), period);
    /* ADC0: SE13, SE13, SE12, no interrupt; ADC1: SE2, SE7, SE8 with the interrupt. */
    assert_int_equal(qfoc_fake_peek(S32K_ADC0_BASE + S32K_ADC_SC1A), 13u);
    assert_int_equal(qfoc_fake_peek(S32K_ADC0_BASE + S32K_ADC_SC1A + 4u), 13u);
    assert_int_equal(qfoc_fake_peek(S32K_ADC0_BASE + S32K_ADC_SC1A + 8u), 12u);
    assert_int_equal(qfoc_fake_peek(S32K_ADC1_BASE + S32K_ADC_SC1A), 2u);
    assert_int_equal(qfoc_fake_peek(S32K_ADC1_BASE + S32K_ADC_SC1A + 4u), 7u);
    assert_int_equal(qfoc_fake_peek(S32K_ADC1_BASE + S32K_ADC_SC1A + 8u), 8u | (1u << 6));
    assert_true((qfoc_fake_peek(S32K_ADC0_BASE + S32K_ADC_SC2) & (1u << 6)) != 0u);   /* ADTRG */
}

/* The compare values the fallback writes for pwm: the symmetric pulse of each clamped
   value x, high from period - x to period + x. */
static void check_symmetric(const qfoc_pwm_t *pwm, uint32_t period)
{
    uint32_t k;
    for (k = 0u; k < 3u; k++) {
        const uint32_t x = (pwm->cmp[k] > period) ? period : pwm->cmp[k];
        assert_int_equal(qfoc_fake_peek(S32K_FTM3_C0V + (16u * k)), period - x);
        assert_int_equal(qfoc_fake_peek(S32K_FTM3_C0V + (16u * k) + 8u), period + x);
    }
}

/* REQ-PORT-020: a plan with shifted edges is written as it stands: C(2k)V = period - up[k],
   C(2k+1)V = period + down[k], PDB0 delays trig[0], trig[1], both loaded with LDOK; from the
   registers alone, each phase conducts for 2 cmp clocks of the period and the switching
   state over each sample's settling and sampling time is the one the plan reads (only the
   largest phase high: +i_hi; only the smallest low: -i_lo).
   Methods: 1b 3000 random voltage vectors at 0 .. 0.15 of the period around 50 %, at any
   angle (most of them shifted); 1n the outputs rebuilt from the compare registers (a model
   of the combined pairs) and the sampling instants from the PDB's delays and clocks,
   against the plan's windows */
static void test_port_020_shunt_pwm_shifted(void **state)
{
    const qfoc_param_table_t *t = &qfoc_params_reference;
    const uint32_t period = t->svpwm.period;
    const qfoc_shunt_cfg_t cfg = { (uint16_t)period, 120u, 40u, 10u };
    qfoc_pwm_t pwm = { { 2530u, 2500u, 2480u }, true };
    qfoc_shunt_plan_t plan;
    uint32_t lcg = 0x5EEDu;
    uint32_t n;
    uint32_t shifted = 0u;
    uint32_t k;
    (void)state;
    assert_int_equal(port_init_shunt_all(t, QFOC_S32K_FTM_INT_RELOAD), QFOC_S32K_OK);
    /* One plan, field by field. */
    qfoc_shunt_plan(&cfg, pwm.cmp, &plan);
    assert_true(plan.ok && plan.shifted);
    qfoc_fake_poke(S32K_FTM3_PWMLOAD, 0u);
    qfoc_fake_poke(S32K_PDB0_BASE + S32K_PDB_SC, 0u);
    qfoc_hal_pwm_write_shunt(&pwm, &plan);
    for (k = 0u; k < 3u; k++) {
        assert_int_equal(qfoc_fake_peek(S32K_FTM3_C0V + (16u * k)), period - plan.up[k]);
        assert_int_equal(qfoc_fake_peek(S32K_FTM3_C0V + (16u * k) + 8u), period + plan.down[k]);
    }
    assert_int_equal(qfoc_fake_peek(S32K_PDB0_BASE + S32K_PDB_CH0DLY0), plan.trig[0]);
    assert_int_equal(qfoc_fake_peek(T_PDB0_DLY1), plan.trig[1]);
    assert_true((qfoc_fake_peek(S32K_FTM3_PWMLOAD) & (1u << 9)) != 0u);    /* LDOK */
    assert_int_equal(qfoc_fake_peek(S32K_PDB0_BASE + S32K_PDB_SC), 0x00040081u);   /* LDMOD 01, PDBEN, LDOK */
    assert_int_equal(qfoc_fake_peek(S32K_FTM3_OUTMASK), 0u);
    print_message("shunt plan: cmp %u %u %u -> up %u %u %u, down %u %u %u, trig %u %u; "
                  "C0V..C5V %lu %lu %lu %lu %lu %lu, PDB0 DLY0 %lu DLY1 %lu\n",
                  pwm.cmp[0], pwm.cmp[1], pwm.cmp[2], plan.up[0], plan.up[1], plan.up[2],
                  plan.down[0], plan.down[1], plan.down[2], plan.trig[0], plan.trig[1],
                  (unsigned long)qfoc_fake_peek(S32K_FTM3_C0V),
                  (unsigned long)qfoc_fake_peek(S32K_FTM3_C0V + 8u),
                  (unsigned long)qfoc_fake_peek(S32K_FTM3_C0V + 16u),
                  (unsigned long)qfoc_fake_peek(S32K_FTM3_C0V + 24u),
                  (unsigned long)qfoc_fake_peek(S32K_FTM3_C0V + 32u),
                  (unsigned long)qfoc_fake_peek(S32K_FTM3_C0V + 40u),
                  (unsigned long)qfoc_fake_peek(S32K_PDB0_BASE + S32K_PDB_CH0DLY0),
                  (unsigned long)qfoc_fake_peek(T_PDB0_DLY1));
    /* Random vectors: the registers give the plan's windows. */
    for (n = 0u; n < 3000u; n++) {
        double r;
        double th;
        uint32_t top = 0u;
        uint32_t bottom = 0xFFFFFFFFu;
        uint32_t j;
        lcg = (lcg * 1664525u) + 1013904223u;
        r = 0.15 * (double)period * (double)(lcg >> 16) / 65536.0;
        lcg = (lcg * 1664525u) + 1013904223u;
        th = 6.283185307179586 * (double)(lcg >> 16) / 65536.0;
        for (k = 0u; k < 3u; k++) {
            const double v = (0.5 * (double)period) + (r * cos(th - (2.0943951023931953 * (double)k)));
            pwm.cmp[k] = (uint16_t)floor(v + 0.5);
            top = (pwm.cmp[k] > top) ? pwm.cmp[k] : top;
            bottom = (pwm.cmp[k] < bottom) ? pwm.cmp[k] : bottom;
        }
        qfoc_shunt_plan(&cfg, pwm.cmp, &plan);
        assert_true(plan.ok);
        shifted += plan.shifted ? 1u : 0u;
        qfoc_hal_pwm_write_shunt(&pwm, &plan);
        /* volt-seconds: phase k high for 2 cmp[k] of the 2 period clocks */
        for (k = 0u; k < 3u; k++) {
            uint32_t c;
            uint32_t on = 0u;
            for (c = 0u; c < (2u * period); c++) {
                on += combined_high(k, c) ? 1u : 0u;
            }
            assert_int_equal(on, 2u * pwm.cmp[k]);
        }
        /* each sample: the same state from t_settle before its start to its end, in the
           first half; sample 0 with one phase high (the largest), sample 1 with one low (the
           smallest) */
        for (j = 0u; j < 2u; j++) {
            const uint32_t dly = qfoc_fake_peek((j == 0u) ? (S32K_PDB0_BASE + S32K_PDB_CH0DLY0) : T_PDB0_DLY1);
            const double at = pdb_instant_ftm_counts(dly);
            const uint32_t c0 = (uint32_t)at;
            const uint32_t st = combined_state(c0);
            uint32_t c;
            assert_true(fabs(at - (double)c0) < 1e-9);
            assert_true(c0 >= cfg.t_settle);
            assert_true((c0 + cfg.t_sample) <= period);
            for (c = c0 - cfg.t_settle; c < (c0 + cfg.t_sample); c++) {
                assert_int_equal(combined_state(c), st);
            }
            if (j == 0u) {
                assert_true((st == 1u) || (st == 2u) || (st == 4u));
                for (k = 0u; k < 3u; k++) {
                    if (st == (1u << k)) {
                        assert_int_equal(pwm.cmp[k], top);
                    }
                }
            } else {
                assert_true((st == 6u) || (st == 5u) || (st == 3u));
                for (k = 0u; k < 3u; k++) {
                    if (st == (7u & ~(1u << k))) {
                        assert_int_equal(pwm.cmp[k], bottom);
                    }
                }
            }
        }
    }
    print_message("shunt: 3000 random vectors, %lu with shifted edges, every window from the registers\n",
                  (unsigned long)shifted);
    assert_true(shifted > 1000u);
}

/* REQ-PORT-020: a plan that is not ok, or does not fit the port's period, is not applied:
   the symmetric compare values of pwm (clamped to the period, as qfoc_hal_pwm_write()) and
   the idle instants period / 4, period / 2; qfoc_hal_pwm_write() writes the same compare
   values and leaves the instants.
   Methods: 1c compare values at the period and beyond it (65535), a plan value at period +
   1, the instants equal, reversed and at the period; 1d a plan that is not ok (refused
   configuration), plans of another period */
static void test_port_020_shunt_fallback(void **state)
{
    const uint32_t period = qfoc_params_reference.svpwm.period;
    const qfoc_shunt_cfg_t cfg = { (uint16_t)period, 120u, 40u, 10u };
    const qfoc_shunt_cfg_t refused = { (uint16_t)period, 2000u, 40u, 10u };
    qfoc_pwm_t pwm = { { 2530u, 2500u, 2480u }, true };
    qfoc_shunt_plan_t good;
    qfoc_shunt_plan_t plan;
    uint32_t v;
    (void)state;
    assert_int_equal(port_init_shunt_all(&qfoc_params_reference, QFOC_S32K_FTM_INT_RELOAD), QFOC_S32K_OK);
    qfoc_shunt_plan(&cfg, pwm.cmp, &good);
    assert_true(good.ok && good.shifted);
    /* not ok (a refused configuration) */
    qfoc_shunt_plan(&refused, pwm.cmp, &plan);
    assert_false(plan.ok);
    qfoc_hal_pwm_write_shunt(&pwm, &plan);
    check_symmetric(&pwm, period);
    assert_int_equal(qfoc_fake_peek(S32K_PDB0_BASE + S32K_PDB_CH0DLY0), period / 4u);
    assert_int_equal(qfoc_fake_peek(T_PDB0_DLY1), period / 2u);
    /* ok, but the shifted plan flagged not ok by hand: still the symmetric values */
    plan = good;
    plan.ok = false;
    qfoc_hal_pwm_write_shunt(&pwm, &plan);
    check_symmetric(&pwm, period);
    /* ok plans the port cannot apply as they stand */
    for (v = 0u; v < 7u; v++) {
        plan = good;
        if (v < 3u) {
            plan.up[v] = (uint16_t)(period + 1u);
        } else if (v == 3u) {
            plan.down[2] = (uint16_t)(period + 1u);
        } else if (v == 4u) {
            plan.trig[1] = plan.trig[0];
        } else if (v == 5u) {
            plan.trig[0] = good.trig[1];
            plan.trig[1] = good.trig[0];
        } else {
            plan.trig[1] = (uint16_t)period;
        }
        qfoc_fake_poke(S32K_PDB0_BASE + S32K_PDB_CH0DLY0, 0u);
        qfoc_hal_pwm_write_shunt(&pwm, &plan);
        check_symmetric(&pwm, period);
        assert_int_equal(qfoc_fake_peek(S32K_PDB0_BASE + S32K_PDB_CH0DLY0), period / 4u);
        assert_int_equal(qfoc_fake_peek(T_PDB0_DLY1), period / 2u);
    }
    /* compare values at and beyond the period: 100 % (set at CNTIN, never cleared) */
    pwm.cmp[0] = (uint16_t)period;
    pwm.cmp[1] = 65535u;
    pwm.cmp[2] = 0u;
    qfoc_hal_pwm_write_shunt(&pwm, &plan);
    check_symmetric(&pwm, period);
    assert_int_equal(qfoc_fake_peek(S32K_FTM3_C0V + 16u), 0u);
    assert_int_equal(qfoc_fake_peek(S32K_FTM3_C0V + 24u), 2u * period);
    assert_int_equal(qfoc_fake_peek(S32K_FTM3_C0V + 32u), qfoc_fake_peek(S32K_FTM3_C0V + 40u));   /* 0 % */
    /* the two-sensor write on the combined pairs: the same values, the instants left */
    qfoc_hal_pwm_write_shunt(&pwm, &good);
    qfoc_fake_poke(S32K_PDB0_BASE + S32K_PDB_CH0DLY0, 1234u);
    pwm.cmp[0] = 1000u;
    pwm.cmp[1] = 4000u;
    pwm.cmp[2] = 6000u;
    qfoc_hal_pwm_write(&pwm);
    check_symmetric(&pwm, period);
    assert_int_equal(qfoc_fake_peek(S32K_PDB0_BASE + S32K_PDB_CH0DLY0), 1234u);
}

/* REQ-PORT-020 (with REQ-PORT-008, REQ-PORT-007, REQ-PORT-018): the output enable of the
   single-shunt write: disabled -> six outputs masked at once, whatever the plan; a latched
   fault output keeps them masked; a hardware trip, reported by the single-shunt read
   (REQ-PORT-021), is cleared only with the outputs off and its input inactive.  A port set
   up for two sensors ignores the plan.
   Methods: 1d the enable false with a valid plan, a latched fault output with the enable
   true, a hardware trip reported by the shunt read; 1l the comparator's fault flag set in
   the fake register file */
static void test_port_020_shunt_outputs_off(void **state)
{
    const uint32_t period = qfoc_params_reference.svpwm.period;
    const uint32_t wpen = S32K_FTM_FMS_WPEN;
    const qfoc_shunt_cfg_t cfg = { (uint16_t)period, 120u, 40u, 10u };
    qfoc_pwm_t pwm = { { 2530u, 2500u, 2480u }, false };
    qfoc_shunt_plan_t plan;
    qfoc_adc_t a;
    qfoc_q15_t smp[2];
    (void)state;
    assert_int_equal(port_init_shunt_all(&qfoc_params_reference, QFOC_S32K_FTM_INT_RELOAD), QFOC_S32K_OK);
    qfoc_shunt_plan(&cfg, pwm.cmp, &plan);
    assert_true(plan.ok);
    qfoc_fake_poke(S32K_FTM3_OUTMASK, 0u);
    qfoc_hal_pwm_write_shunt(&pwm, &plan);
    assert_int_equal(qfoc_fake_peek(S32K_FTM3_OUTMASK), 0x3Fu);
    assert_int_equal(qfoc_fake_peek(S32K_PDB0_BASE + S32K_PDB_CH0DLY0), plan.trig[0]);   /* plan kept */
    pwm.enable = true;
    qfoc_hal_pwm_write_shunt(&pwm, &plan);
    assert_int_equal(qfoc_fake_peek(S32K_FTM3_OUTMASK), 0u);
    /* a hardware trip: reported once by the shunt read, kept until then, cleared with the
       outputs off and the input inactive */
    qfoc_fake_poke(S32K_FTM3_FMS, S32K_FTM_FMS_FAULTF | T_FTM_FMS_FAULTF0 | wpen);
    pwm.enable = false;
    qfoc_hal_pwm_write_shunt(&pwm, &plan);
    assert_int_equal(qfoc_fake_peek(S32K_FTM3_FMS), S32K_FTM_FMS_FAULTF | T_FTM_FMS_FAULTF0 | wpen);
    qfoc_hal_adc_read_shunt(&a, smp);
    assert_int_equal(smp[0], 32767);
    qfoc_hal_pwm_write_shunt(&pwm, &plan);
    assert_int_equal(qfoc_fake_peek(S32K_FTM3_FMS), wpen);
    /* latched fault output: masked whatever the enable */
    pwm.enable = true;
    qfoc_hal_fault_output();
    qfoc_hal_pwm_write_shunt(&pwm, &plan);
    assert_int_equal(qfoc_fake_peek(S32K_FTM3_OUTMASK), 0x3Fu);
    /* two sensors: the plan ignored, the compare values as qfoc_hal_pwm_write() */
    qfoc_fake_reset();
    qfoc_fake_set_hook(hw_model);
    qfoc_s32k_hal_init((uint16_t)period);
    qfoc_hal_pwm_write_shunt(&pwm, &plan);
    assert_int_equal(qfoc_fake_peek(S32K_FTM3_C0V), pwm.cmp[0]);
    assert_int_equal(qfoc_fake_peek(S32K_FTM3_C0V + 8u), 0u);
    assert_int_equal(qfoc_fake_peek(S32K_FTM3_C0V + 16u), pwm.cmp[1]);
    assert_int_equal(qfoc_fake_peek(S32K_FTM3_C0V + 32u), pwm.cmp[2]);
    assert_int_equal(qfoc_fake_peek(S32K_PDB0_BASE + S32K_PDB_CH0DLY0), 0u);
    assert_int_equal(qfoc_fake_peek(S32K_FTM3_OUTMASK), 0u);
}

/* The DC-link sample of a code: (code - offset) A per 2048 codes of I_base, in Q15 of
   I_base, saturated to +-32767 (drive.h's phase-current scaling). */
static int32_t t_sample_q15(uint32_t code, uint32_t offset)
{
    const double q = ((double)code - (double)offset) * 32768.0 / 2048.0;
    return (int32_t)((q > 32767.0) ? 32767.0 : ((q < -32767.0) ? -32767.0 : q));
}

/* REQ-PORT-021: the single-shunt read returns the two DC-link samples of ADC0 R[A], R[B]
   in Q15 ((code - offset) x 16, saturated; offset 2048 until set, codes above 4095 taken as
   4095), the DC bus, phase currents 0, and stores the temperatures (T_IPM from R[C]) for
   the tick; a hardware trip is reported once as full scale; with two sensors the samples
   are 0.
   Methods: 1c codes 0, 1, 2047, 2048, 4095 and bits above the 12-bit result, offsets 0, 2010,
   4095 and 65535; 1d a hardware trip, the read of a port set up for two sensors; 1n the
   scaling of drive.h in double precision */
static void test_port_021_shunt_samples(void **state)
{
    static const uint32_t codes[] = { 0u, 1u, 2047u, 2048u, 2049u, 3000u, 4095u };
    static const uint16_t offsets[] = { 0u, 2010u, 4095u, 65535u };
    const uint32_t wpen = S32K_FTM_FMS_WPEN;
    qfoc_adc_t a;
    qfoc_q15_t smp[2];
    int16_t t1;
    int16_t t2;
    size_t i;
    size_t j;
    (void)state;
    qfoc_s32k_hal_init_shunt(5000u);
    set_samples(0u, 0u, 0u, 0u, 0u);
    qfoc_fake_poke(S32K_ADC0_BASE + S32K_ADC_RA, 2048u + 100u);
    qfoc_fake_poke(S32K_ADC0_BASE + S32K_ADC_RA + 4u, 2048u - 37u);
    qfoc_fake_poke(S32K_ADC0_BASE + S32K_ADC_RA + 8u, 1000u);           /* T_IPM */
    qfoc_fake_poke(S32K_ADC1_BASE + S32K_ADC_RA + 4u, 2048u);           /* T_PCB */
    qfoc_fake_poke(S32K_ADC1_BASE + S32K_ADC_RA + 8u, 0xF345u);         /* V_dc, bits above 12 */
    a.iu = 1u;
    a.iv = 1u;
    qfoc_hal_adc_read_shunt(&a, smp);
    assert_int_equal(smp[0], 1600);
    assert_int_equal(smp[1], -592);
    assert_int_equal(a.iu, 2048u);
    assert_int_equal(a.iv, 2048u);
    assert_int_equal(a.vdc, 0x345u);
    qfoc_hal_temps_read(&t1, &t2);
    assert_int_equal(t1, qfoc_s32k_ntc_to_dc(1000u));
    assert_int_equal(t2, 250);
    /* the two-sensor read on the shunt set-up: the same temperatures */
    qfoc_hal_adc_read(&a);
    qfoc_hal_temps_read(&t1, &t2);
    assert_int_equal(t1, qfoc_s32k_ntc_to_dc(1000u));
    for (i = 0u; i < (sizeof offsets / sizeof offsets[0]); i++) {
        const uint32_t off = (offsets[i] > 4095u) ? 4095u : offsets[i];
        qfoc_s32k_shunt_offset_set(offsets[i]);
        for (j = 0u; j < (sizeof codes / sizeof codes[0]); j++) {
            qfoc_fake_poke(S32K_ADC0_BASE + S32K_ADC_RA, codes[j] | 0xF000u);
            qfoc_fake_poke(S32K_ADC0_BASE + S32K_ADC_RA + 4u, 4095u - codes[j]);
            qfoc_hal_adc_read_shunt(&a, smp);
            assert_int_equal(smp[0], t_sample_q15(codes[j], off));
            assert_int_equal(smp[1], t_sample_q15(4095u - codes[j], off));
        }
    }
    /* a hardware trip: once full scale, then the samples again */
    qfoc_s32k_shunt_offset_set(2048u);
    qfoc_fake_poke(S32K_ADC0_BASE + S32K_ADC_RA, 2048u);
    qfoc_fake_poke(S32K_ADC0_BASE + S32K_ADC_RA + 4u, 2048u);
    qfoc_fake_poke(S32K_FTM3_FMS, S32K_FTM_FMS_FAULTF | T_FTM_FMS_FAULTF0 | S32K_FTM_FMS_FAULTIN | wpen);
    qfoc_hal_adc_read_shunt(&a, smp);
    assert_int_equal(smp[0], 32767);
    assert_int_equal(smp[1], 32767);
    assert_int_equal(a.iu, 4095u);
    assert_int_equal(a.iv, 4095u);
    qfoc_hal_adc_read_shunt(&a, smp);
    assert_int_equal(smp[0], 0);
    assert_int_equal(smp[1], 0);
    assert_int_equal(a.iu, 2048u);
    /* two sensors: no DC-link channel, samples 0 */
    qfoc_fake_poke(S32K_FTM3_FMS, wpen);
    qfoc_s32k_hal_init(5000u);
    qfoc_fake_poke(S32K_ADC0_BASE + S32K_ADC_RA, 3000u);
    qfoc_hal_adc_read_shunt(&a, smp);
    assert_int_equal(smp[0], 0);
    assert_int_equal(smp[1], 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(test_port_001_registers_in_known_blocks, setup),
        cmocka_unit_test_setup(test_port_002_clock_run_mode, setup),
        cmocka_unit_test_setup(test_port_002_clock_timeout, setup),
        cmocka_unit_test_setup(test_port_003_peripheral_clocks, setup),
        cmocka_unit_test_setup(test_port_004_pins, setup),
        cmocka_unit_test_setup(test_port_005_pwm_8k, setup),
        cmocka_unit_test_setup(test_port_005_pwm_16k, setup),
        cmocka_unit_test_setup(test_port_005_table_mismatch, setup),
        cmocka_unit_test_setup(test_port_006_deadtime, setup),
        cmocka_unit_test_setup(test_port_007_fault_control, setup),
        cmocka_unit_test_setup(test_port_007_trip_reported_once_then_cleared, setup),
        cmocka_unit_test_setup(test_port_007_trip_kept_until_reported, setup),
        cmocka_unit_test_setup(test_port_008_pwm_write, setup),
        cmocka_unit_test_setup(test_port_009_trigger_chain, setup),
        cmocka_unit_test_setup(test_port_009_adc_calibration_timeout, setup),
        cmocka_unit_test_setup(test_port_010_ntc, setup),
        cmocka_unit_test_setup(test_port_010_adc_read_and_temps, setup),
        cmocka_unit_test_setup(test_port_011_uart_setup, setup),
        cmocka_unit_test_setup(test_port_011_frame_receive, setup),
        cmocka_unit_test_setup(test_port_011_transmit, setup),
        cmocka_unit_test_setup(test_port_012_can_setup, setup),
        cmocka_unit_test_setup(test_port_012_can_send, setup),
        cmocka_unit_test_setup(test_port_013_tick, setup),
        cmocka_unit_test_setup(test_port_014_watchdog, setup),
        cmocka_unit_test_setup(test_port_015_nvic, setup),
        cmocka_unit_test_setup(test_port_016_017_isr_twin, setup),
        cmocka_unit_test_setup(test_port_016_unbound_isr_outputs_off, setup),
        cmocka_unit_test_setup(test_port_017_status_frame_after_command, setup),
        cmocka_unit_test_setup(test_port_017_refused_frames_counted, setup),
        cmocka_unit_test_setup(test_port_018_supervision, setup),
        cmocka_unit_test_setup(test_port_002_012_014_wait_timeouts, setup),
        cmocka_unit_test_setup(test_port_019_flash_config_field, setup),
        cmocka_unit_test_setup(test_port_020_shunt_setup, setup),
        cmocka_unit_test_setup(test_port_020_shunt_pwm_shifted, setup),
        cmocka_unit_test_setup(test_port_020_shunt_fallback, setup),
        cmocka_unit_test_setup(test_port_020_shunt_outputs_off, setup),
        cmocka_unit_test_setup(test_port_021_shunt_samples, setup),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
