/*
 * reset.S -- the S32K144 reset handler: the port's assembly module (Cortex-M4, Thumb-2,
 * GNU assembler syntax, preprocessed by arm-none-eabi-gcc).
 *
 * Reset_Handler runs first after reset, before any stack exists: the SRAM has ECC, and a
 * read, or a byte or half-word write, of a word never written raises an ECC error (S32K1xx
 * RM Rev. 13, SRAM/ECC), so no C function may run before step 2, and this handler is
 * written in assembly (MISRA C:2012 Dir 4.3: assembly isolated in its own module, entered
 * through its C declaration in s32k144_port.h; its definition outside C is deviation
 * DEV-004, Rule 8.6).
 *
 *   1. interrupts masked (CPSID i); the watchdog, which runs after reset on the LPO with a
 *      short timeout, is unlocked with its 32-bit key (WDOG_CNT = 0xD928C520), given the
 *      longest timeout (TOVAL = 0xFFFF) and stopped with UPDATE set (CS = CMD32EN | CLK
 *      LPO | UPDATE, EN = 0), so that main() can configure it later (RM, WDOG chapter:
 *      the three writes within the unlock window);
 *   2. SRAM_L and SRAM_U, qfoc_sram_start .. qfoc_sram_end (s32k144.ld), written with
 *      32-bit zeros (ECC initialised; this also clears .bss and the stack);
 *   3. qfoc_s32k_c_start() (startup.c): FPU, .data, main().
 *
 * qfoc_s32k_c_start() does not return: main() ends in its endless idle loop.  The branch to
 * itself after the call gives the handler a defined end all the same (interrupts stay as
 * main() left them).
 *
 * Registers: r0 address, r1 value or end address, r2 zero.
 *
 * Requirements: REQ-PORT-014 (watchdog handled first), REQ-PORT-019 (start-up)
 * (specs/requirements/port.md).
 */
    .syntax unified
    .cpu cortex-m4
    .thumb

    .section .text.Reset_Handler, "ax", %progbits
    .global Reset_Handler
    .type Reset_Handler, %function
    .thumb_func
Reset_Handler:
    cpsid i
    /* 1. WDOG (0x40052000): CNT at +4, TOVAL at +8, CS at +0. */
    ldr r0, =0x40052000
    ldr r1, =0xD928C520
    str r1, [r0, #4]
    ldr r1, =0x0000FFFF
    str r1, [r0, #8]
    ldr r1, =0x00002120
    str r1, [r0, #0]
    /* 2. SRAM: 32-bit zero writes from qfoc_sram_start up to qfoc_sram_end. */
    ldr r0, =qfoc_sram_start
    ldr r1, =qfoc_sram_end
    movs r2, #0
1:
    cmp r0, r1
    bhs 2f
    str r2, [r0], #4
    b 1b
2:
    /* 3. C start-up. */
    bl qfoc_s32k_c_start
3:
    b 3b
    .ltorg
    .size Reset_Handler, . - Reset_Handler
