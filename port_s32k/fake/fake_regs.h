/**
 * @file fake_regs.h
 * @brief A RAM register file for the host tests of the S32K144 port.
 *
 * Compiled only into host tests, with QFOC_PORT_FAKE_REGS defined: the port's one
 * register accessor (s32k144_regs.h, s32k_reg()) then returns qfoc_fake_reg(addr), a
 * 32-bit cell per absolute address, created (zero) on first use.  A test may install a
 * hook that runs before every access the port makes: a small model of the hardware's
 * status bits (an oscillator becoming valid, a module acknowledging freeze mode), so
 * that the port's bounded waits complete.  The hook and the test use qfoc_fake_peek()
 * and qfoc_fake_poke(), which do not run the hook.
 */
#ifndef QFOC_FAKE_REGS_H
#define QFOC_FAKE_REGS_H

#include <stdint.h>
#include <stdbool.h>

/** The cell of address addr (runs the hook first); the port's accessor. */
volatile uint32_t *qfoc_fake_reg(uint32_t addr);
/** Value of a register (0 if never touched), without the hook. */
uint32_t qfoc_fake_peek(uint32_t addr);
/** Set a register, without the hook. */
void qfoc_fake_poke(uint32_t addr, uint32_t value);
/** Forget every register and the hook. */
void qfoc_fake_reset(void);
/** Install the hardware model run before each port access (NULL: none). */
void qfoc_fake_set_hook(void (*hook)(uint32_t addr));
/** Number of distinct addresses the port touched, and the i-th of them. */
uint32_t qfoc_fake_count(void);
uint32_t qfoc_fake_addr(uint32_t i);
/** Number of accessor calls since the last reset. */
uint32_t qfoc_fake_accesses(void);

/** The interrupt mask of the host build (cpu.c): true after qfoc_s32k_irq_global_enable(). */
extern bool qfoc_fake_irq_enabled;

#endif /* QFOC_FAKE_REGS_H */
