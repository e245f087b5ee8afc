/**
 * @file tt_target.c
 * @brief Target build of the runner (tt_io.h): console, clock, command line and exit
 *        status through Arm semihosting.
 *
 * Semihosting ("Semihosting for AArch32 and AArch64", Arm, version 3.0): on an
 * M-profile core the request is BKPT 0xAB with the operation number in r0 and the
 * address of its parameter block in r1; the result comes back in r0.  Operations used:
 * SYS_WRITE0 (0x04), SYS_CLOCK (0x10), SYS_GET_CMDLINE (0x15) and SYS_EXIT_EXTENDED
 * (0x20) with the reason ADP_Stopped_ApplicationExit (0x20026) and the exit status,
 * which QEMU (-semihosting-config enable=on) returns as its own exit status.
 *
 * Requirements: REQ-TGT-004, REQ-TGT-005.
 */
#include <stdint.h>

#include "tt_io.h"

#define TT_SYS_WRITE0        ((uint32_t)0x04u)
#define TT_SYS_CLOCK         ((uint32_t)0x10u)
#define TT_SYS_GET_CMDLINE   ((uint32_t)0x15u)
#define TT_SYS_EXIT_EXTENDED ((uint32_t)0x20u)
#define TT_ADP_APP_EXIT      ((uint32_t)0x20026u)

/** The runner's entry point, called by the reset handler (tt_startup.c). */
int32_t tt_target_main(void);
/** Stop the program with an exit status (SYS_EXIT_EXTENDED); does not return. */
void tt_target_exit(int32_t status);

static int32_t tt_semihost(uint32_t op, const void *arg)
{
    register uint32_t r0 __asm__("r0") = op;
    register const void *r1 __asm__("r1") = arg;
    __asm__ volatile("bkpt 0xAB" : "+r"(r0) : "r"(r1) : "memory");
    return (int32_t)r0;
}

void tt_io_puts(const char *s)
{
    (void)tt_semihost(TT_SYS_WRITE0, s);
}

uint32_t tt_io_clock_cs(void)
{
    const int32_t t = tt_semihost(TT_SYS_CLOCK, (const void *)0);
    return (t < 0) ? 0u : (uint32_t)t;
}

const char *tt_io_platform(void)
{
    return "Cortex-M4F (arm-none-eabi-gcc " __VERSION__ ", -mcpu=cortex-m4 -mfpu=fpv4-sp-d16 "
           "-mfloat-abi=hard -O2)";
}

void tt_target_exit(int32_t status)
{
    uint32_t block[2];
    block[0] = TT_ADP_APP_EXIT;
    block[1] = (uint32_t)status;
    (void)tt_semihost(TT_SYS_EXIT_EXTENDED, block);
    for (;;) {
        /* not reached under a debugger or QEMU */
    }
}

/* SYS_GET_CMDLINE parameter block: buffer address, then its size (in) or the length of
   the command line (out); two 32-bit words on the Cortex-M4. */
typedef struct {
    char *buf;
    uint32_t len;
} tt_cmdline_t;

int32_t tt_target_main(void)
{
    static char line[512];
    tt_cmdline_t block;
    int32_t status;
    block.buf = line;
    block.len = (uint32_t)(sizeof(line) - 1u);
    if (tt_semihost(TT_SYS_GET_CMDLINE, &block) != 0) {
        line[0] = '\0';
    } else if (block.len < (uint32_t)(sizeof(line) - 1u)) {
        line[block.len] = '\0';
    } else {
        line[sizeof(line) - 1u] = '\0';
    }
    status = tt_run(line);
    return status;
}
