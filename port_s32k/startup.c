/**
 * @file startup.c
 * @brief S32K144 start-up: the vector table, the C part of the reset sequence (FPU,
 *        .data, main()) and the trap handler.
 *
 * Reset sequence (S32K1xx RM Rev. 13):
 *   1. The watchdog runs after reset (LPO clock, short timeout): it is unlocked and
 *      stopped first, with UPDATE set so that main() can configure it (RM, WDOG chapter);
 *   2. SRAM_L and SRAM_U are written with 32-bit zeros: the SRAM has ECC, and a read or
 *      a byte/half-word write of a word never written raises an ECC error (RM, SRAM/ECC);
 *      this also clears .bss.  Steps 1 and 2 run before any stack use: Reset_Handler,
 *      the assembly module reset.S, which then calls qfoc_s32k_c_start() below;
 *   3. CP10/CP11 full access (the FPU) through SCB CPACR, then DSB and ISB, before any
 *      floating-point instruction (ARMv7-M ARM, CPACR);
 *   4. .data copied from flash, word by word, qfoc_data_words words (a length the linker
 *      script computes once); main() called.  main() does not return: its idle loop is
 *      endless, and nothing follows the call.
 *
 * The flash configuration field (flash_config.c) is its own section at 0x400, placed by
 * s32k144.ld and checked in the binary by port_s32k/check_image.py.
 *
 * Every unexpected exception or interrupt ends in s32k_trap(): PWM outputs masked, gate
 * driver off, then wait for the watchdog reset.
 *
 * Deviations (misra/deviations.md): DEV-004 (Rules 8.6, 8.11) for the objects the linker
 * script defines; DEV-005 (Rule 1.2) for the section placement of the vector table.
 *
 * Requirements: REQ-PORT-019 (specs/requirements/port.md).
 */
#include <stddef.h>
#include <stdint.h>
#include "qfoc/hal.h"
#include "s32k144_port.h"
#include "s32k144_regs.h"

/* Objects defined by the linker script (s32k144.ld), not by C: deviation DEV-004.  The
   arrays have the length the script gives them (qfoc_data_words words each), which C
   cannot state in the declaration. */
/* cppcheck-suppress misra-c2012-8.6 ; DEV-004 */
extern uint32_t qfoc_stack_top;                /* end of SRAM_U: the initial stack pointer */
/* cppcheck-suppress misra-c2012-8.6 ; DEV-004 */
extern const uint32_t qfoc_data_words;         /* length of .data in 32-bit words */
/* cppcheck-suppress misra-c2012-8.6 ; DEV-004 */
/* cppcheck-suppress misra-c2012-8.11 ; DEV-004 */
extern const uint32_t qfoc_data_load[];        /* .data's initial values, in flash */
/* cppcheck-suppress misra-c2012-8.6 ; DEV-004 */
/* cppcheck-suppress misra-c2012-8.11 ; DEV-004 */
extern uint32_t qfoc_data_start[];             /* .data in SRAM_L */

int main(void);
void qfoc_s32k_c_start(void);

/* ------------------------------------------------------------------ trap */

static void s32k_trap(void)
{
    qfoc_hal_fault_output();
    for (;;) {
        /* wait for the watchdog */
    }
}

/* ------------------------------------------------------------------ vector table */

typedef void (*qfoc_s32k_vector_t)(void);

/** Initial stack pointer, then the exception and interrupt handlers (16 + 123). */
typedef struct {
    uint32_t *stack_top;
    qfoc_s32k_vector_t handler[15u + S32K_IRQ_COUNT];
} qfoc_s32k_vectors_t;

extern const qfoc_s32k_vectors_t qfoc_s32k_vectors;

/* In its own section, which s32k144.ld places at 0x0 and keeps (KEEP): a GCC attribute,
   deviation DEV-005. */
/* cppcheck-suppress misra-c2012-1.2 ; DEV-005 */
__attribute__((section(".isr_vector")))
const qfoc_s32k_vectors_t qfoc_s32k_vectors = {
    &qfoc_stack_top,
    {
        Reset_Handler,               /*   1 */
        s32k_trap,                   /*   2 */
        s32k_trap,                   /*   3 */
        s32k_trap,                   /*   4 */
        s32k_trap,                   /*   5 */
        s32k_trap,                   /*   6 */
        NULL,                        /*   7 reserved */
        NULL,                        /*   8 reserved */
        NULL,                        /*   9 reserved */
        NULL,                        /*  10 reserved */
        s32k_trap,                   /*  11 */
        s32k_trap,                   /*  12 */
        NULL,                        /*  13 reserved */
        s32k_trap,                   /*  14 */
        s32k_trap,                   /*  15 */
        s32k_trap,                   /* IRQ   0 */
        s32k_trap,                   /* IRQ   1 */
        s32k_trap,                   /* IRQ   2 */
        s32k_trap,                   /* IRQ   3 */
        s32k_trap,                   /* IRQ   4 */
        s32k_trap,                   /* IRQ   5 */
        s32k_trap,                   /* IRQ   6 */
        s32k_trap,                   /* IRQ   7 */
        s32k_trap,                   /* IRQ   8 */
        s32k_trap,                   /* IRQ   9 */
        s32k_trap,                   /* IRQ  10 */
        s32k_trap,                   /* IRQ  11 */
        s32k_trap,                   /* IRQ  12 */
        s32k_trap,                   /* IRQ  13 */
        s32k_trap,                   /* IRQ  14 */
        s32k_trap,                   /* IRQ  15 */
        s32k_trap,                   /* IRQ  16 */
        s32k_trap,                   /* IRQ  17 */
        s32k_trap,                   /* IRQ  18 */
        s32k_trap,                   /* IRQ  19 */
        s32k_trap,                   /* IRQ  20 */
        s32k_trap,                   /* IRQ  21 */
        s32k_trap,                   /* IRQ  22 */
        s32k_trap,                   /* IRQ  23 */
        s32k_trap,                   /* IRQ  24 */
        s32k_trap,                   /* IRQ  25 */
        s32k_trap,                   /* IRQ  26 */
        s32k_trap,                   /* IRQ  27 */
        s32k_trap,                   /* IRQ  28 */
        s32k_trap,                   /* IRQ  29 */
        s32k_trap,                   /* IRQ  30 */
        s32k_trap,                   /* IRQ  31 */
        s32k_trap,                   /* IRQ  32 */
        qfoc_s32k_uart_isr,          /* IRQ  33 */
        s32k_trap,                   /* IRQ  34 */
        s32k_trap,                   /* IRQ  35 */
        s32k_trap,                   /* IRQ  36 */
        s32k_trap,                   /* IRQ  37 */
        s32k_trap,                   /* IRQ  38 */
        s32k_trap,                   /* IRQ  39 */
        qfoc_s32k_adc_isr,           /* IRQ  40 */
        s32k_trap,                   /* IRQ  41 */
        s32k_trap,                   /* IRQ  42 */
        s32k_trap,                   /* IRQ  43 */
        s32k_trap,                   /* IRQ  44 */
        s32k_trap,                   /* IRQ  45 */
        s32k_trap,                   /* IRQ  46 */
        s32k_trap,                   /* IRQ  47 */
        qfoc_s32k_tick_isr,          /* IRQ  48 */
        s32k_trap,                   /* IRQ  49 */
        s32k_trap,                   /* IRQ  50 */
        s32k_trap,                   /* IRQ  51 */
        s32k_trap,                   /* IRQ  52 */
        s32k_trap,                   /* IRQ  53 */
        s32k_trap,                   /* IRQ  54 */
        s32k_trap,                   /* IRQ  55 */
        s32k_trap,                   /* IRQ  56 */
        s32k_trap,                   /* IRQ  57 */
        s32k_trap,                   /* IRQ  58 */
        s32k_trap,                   /* IRQ  59 */
        s32k_trap,                   /* IRQ  60 */
        s32k_trap,                   /* IRQ  61 */
        s32k_trap,                   /* IRQ  62 */
        s32k_trap,                   /* IRQ  63 */
        s32k_trap,                   /* IRQ  64 */
        s32k_trap,                   /* IRQ  65 */
        s32k_trap,                   /* IRQ  66 */
        s32k_trap,                   /* IRQ  67 */
        s32k_trap,                   /* IRQ  68 */
        s32k_trap,                   /* IRQ  69 */
        s32k_trap,                   /* IRQ  70 */
        s32k_trap,                   /* IRQ  71 */
        s32k_trap,                   /* IRQ  72 */
        s32k_trap,                   /* IRQ  73 */
        s32k_trap,                   /* IRQ  74 */
        s32k_trap,                   /* IRQ  75 */
        s32k_trap,                   /* IRQ  76 */
        s32k_trap,                   /* IRQ  77 */
        s32k_trap,                   /* IRQ  78 */
        s32k_trap,                   /* IRQ  79 */
        s32k_trap,                   /* IRQ  80 */
        s32k_trap,                   /* IRQ  81 */
        s32k_trap,                   /* IRQ  82 */
        s32k_trap,                   /* IRQ  83 */
        s32k_trap,                   /* IRQ  84 */
        s32k_trap,                   /* IRQ  85 */
        s32k_trap,                   /* IRQ  86 */
        s32k_trap,                   /* IRQ  87 */
        s32k_trap,                   /* IRQ  88 */
        s32k_trap,                   /* IRQ  89 */
        s32k_trap,                   /* IRQ  90 */
        s32k_trap,                   /* IRQ  91 */
        s32k_trap,                   /* IRQ  92 */
        s32k_trap,                   /* IRQ  93 */
        s32k_trap,                   /* IRQ  94 */
        s32k_trap,                   /* IRQ  95 */
        s32k_trap,                   /* IRQ  96 */
        s32k_trap,                   /* IRQ  97 */
        s32k_trap,                   /* IRQ  98 */
        s32k_trap,                   /* IRQ  99 */
        s32k_trap,                   /* IRQ 100 */
        s32k_trap,                   /* IRQ 101 */
        s32k_trap,                   /* IRQ 102 */
        s32k_trap,                   /* IRQ 103 */
        s32k_trap,                   /* IRQ 104 */
        s32k_trap,                   /* IRQ 105 */
        s32k_trap,                   /* IRQ 106 */
        s32k_trap,                   /* IRQ 107 */
        s32k_trap,                   /* IRQ 108 */
        s32k_trap,                   /* IRQ 109 */
        s32k_trap,                   /* IRQ 110 */
        s32k_trap,                   /* IRQ 111 */
        s32k_trap,                   /* IRQ 112 */
        s32k_trap,                   /* IRQ 113 */
        s32k_trap,                   /* IRQ 114 */
        s32k_trap,                   /* IRQ 115 */
        s32k_trap,                   /* IRQ 116 */
        s32k_trap,                   /* IRQ 117 */
        s32k_trap,                   /* IRQ 118 */
        s32k_trap,                   /* IRQ 119 */
        s32k_trap,                   /* IRQ 120 */
        s32k_trap,                   /* IRQ 121 */
        qfoc_s32k_ftm_isr            /* IRQ 122 */
    }
};

/* ------------------------------------------------------------------ reset */

/* Called by Reset_Handler (reset.S) once the watchdog is stopped and the SRAM written. */
void qfoc_s32k_c_start(void)
{
    const uint32_t words = qfoc_data_words;   /* read once: the loop bound */
    uint32_t k;

    s32k_modify(S32K_SCB_CPACR, 0u, S32K_SCB_CPACR_FPU);
    qfoc_s32k_data_sync_barrier();
    qfoc_s32k_instruction_sync_barrier();

    for (k = 0u; k < words; k++) {
        qfoc_data_start[k] = qfoc_data_load[k];
    }
    /* The drive's application; its idle loop does not end. */
    (void)main();
}
