/**
 * @file cpu.c
 * @brief The Cortex-M4 instructions that C cannot express, one function per instruction:
 *        the only inline assembly of the port.
 *
 *   qfoc_s32k_irq_global_enable()        CPSIE i  unmask interrupts (PRIMASK = 0)
 *   qfoc_s32k_irq_global_disable()       CPSID i  mask interrupts (PRIMASK = 1)
 *   qfoc_s32k_wait_for_interrupt()       WFI      sleep until an interrupt is pending
 *   qfoc_s32k_data_sync_barrier()        DSB      every earlier memory access completes
 *                                                 before the next instruction runs
 *   qfoc_s32k_instruction_sync_barrier() ISB      the pipeline is refilled: the following
 *                                                 instructions see a changed system
 *                                                 register (CPACR, ARMv7-M ARM "ISB")
 *
 * Each function holds its one asm statement and nothing else (MISRA C:2012 Dir 4.3: the
 * assembly is encapsulated in functions and isolated in this file); the callers are C
 * code that never sees an instruction.  The "memory" clobber keeps the compiler from
 * moving memory accesses across the instruction, as the hardware barrier does.  GCC's asm
 * statement is a language extension: deviation DEV-005 (Rule 1.2), tagged at each site.
 * The reset handler, which runs before any stack exists, is the assembly module reset.S.
 *
 * Host tests (QFOC_PORT_FAKE_REGS): the interrupt mask is a flag the tests read; the other
 * three instructions have no host counterpart and are not built.
 *
 * Requirements: REQ-PORT-015 (interrupts unmasked after the set-up), REQ-PORT-019
 * (start-up: FPU enable, idle loop) (specs/requirements/port.md).
 */
#include "s32k144_port.h"

#if defined(QFOC_PORT_FAKE_REGS)
/* Host build: the global mask is a flag the tests read (declared in fake/fake_regs.h). */
extern bool qfoc_fake_irq_enabled;
bool qfoc_fake_irq_enabled = false;

void qfoc_s32k_irq_global_enable(void)
{
    qfoc_fake_irq_enabled = true;
}

void qfoc_s32k_irq_global_disable(void)
{
    qfoc_fake_irq_enabled = false;
}
#else
void qfoc_s32k_irq_global_enable(void)
{
    /* cppcheck-suppress misra-c2012-1.2 ; DEV-005 */
    __asm__ volatile ("cpsie i" ::: "memory");
}

void qfoc_s32k_irq_global_disable(void)
{
    /* cppcheck-suppress misra-c2012-1.2 ; DEV-005 */
    __asm__ volatile ("cpsid i" ::: "memory");
}

void qfoc_s32k_wait_for_interrupt(void)
{
    /* cppcheck-suppress misra-c2012-1.2 ; DEV-005 */
    __asm__ volatile ("wfi" ::: "memory");
}

void qfoc_s32k_data_sync_barrier(void)
{
    /* cppcheck-suppress misra-c2012-1.2 ; DEV-005 */
    __asm__ volatile ("dsb" ::: "memory");
}

void qfoc_s32k_instruction_sync_barrier(void)
{
    /* cppcheck-suppress misra-c2012-1.2 ; DEV-005 */
    __asm__ volatile ("isb" ::: "memory");
}
#endif
