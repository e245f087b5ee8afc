/**
 * @file tt_startup.c
 * @brief Start-up of the target runner on the Cortex-M4F of QEMU's mps2-an386 board:
 *        vector table, reset handler (FPU on, .data copied, .bss zeroed), fault handler.
 *
 * Facts used: the Armv7-M exception model (Armv7-M Architecture Reference Manual,
 * DDI 0403E, B1.5: word 0 of the vector table is the initial main stack pointer, word 1
 * the reset vector, then NMI, HardFault, MemManage, BusFault, UsageFault, four reserved
 * words, SVCall, DebugMonitor, one reserved word, PendSV, SysTick); CPACR at 0xE000ED88
 * with CP10 and CP11 in bits 20..23 (B3.2.20): 0xF grants full access to the FPU, which
 * must be done before any floating-point instruction, then DSB and ISB.
 *
 * Requirements: REQ-TGT-005.
 */
#include <stdint.h>

/* linker script symbols (tt_mps2_an386.ld) */
extern uint32_t __tt_data_load;
extern uint32_t __tt_data_start;
extern uint32_t __tt_data_end;
extern uint32_t __tt_bss_start;
extern uint32_t __tt_bss_end;
extern uint32_t __tt_stack_top;

int32_t tt_target_main(void);
void tt_target_exit(int32_t status);
void tt_reset_handler(void);
void tt_fault_handler(void);

/* The start-up code converts addresses to pointers where the hardware defines them (the
   CPACR register, the initial stack pointer in the vector table) and walks the .data and
   .bss ranges between linker symbols: conversions and pointer comparisons that only
   start-up code needs (MISRA C:2012 rule 11.4, advisory; rule 18.3's comparison of
   pointers to one object, which the linker script makes them). */
#define TT_CPACR ((volatile uint32_t *)0xE000ED88u)
#define TT_CPACR_CP10_CP11_FULL ((uint32_t)0xFu << 20u)

void tt_reset_handler(void)
{
    const uint32_t *src = &__tt_data_load;
    uint32_t *dst = &__tt_data_start;
    *TT_CPACR |= TT_CPACR_CP10_CP11_FULL;
    __asm__ volatile("dsb\n\tisb" ::: "memory");
    while (dst < &__tt_data_end) {
        *dst = *src;
        dst++;
        src++;
    }
    dst = &__tt_bss_start;
    while (dst < &__tt_bss_end) {
        *dst = 0u;
        dst++;
    }
    tt_target_exit(tt_target_main());
}

/* Any fault: report it through the exit status 3 (the runner never faults). */
void tt_fault_handler(void)
{
    tt_target_exit(3);
}

typedef void (*tt_vector_t)(void);

__attribute__((section(".tt_vectors"), used))
static const tt_vector_t tt_vectors[16] = {
    (tt_vector_t)(uintptr_t)&__tt_stack_top,
    tt_reset_handler,
    tt_fault_handler,   /* NMI */
    tt_fault_handler,   /* HardFault */
    tt_fault_handler,   /* MemManage */
    tt_fault_handler,   /* BusFault */
    tt_fault_handler,   /* UsageFault */
    0, 0, 0, 0,         /* reserved */
    tt_fault_handler,   /* SVCall */
    tt_fault_handler,   /* DebugMonitor */
    0,                  /* reserved */
    tt_fault_handler,   /* PendSV */
    tt_fault_handler,   /* SysTick */
};
