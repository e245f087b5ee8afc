/**
 * @file flash_config.c
 * @brief The S32K144 flash configuration field, 16 bytes at 0x400..0x40F (S32K1xx
 *        Reference Manual Rev. 13, "Flash configuration field").
 *
 * The chip reads these bytes at every reset.  FSEC (0x40C) decides whether the part is
 * secured: 0xFE = SEC 10 (unsecured), FSLACC and MEEN 11 (factory access and mass erase
 * allowed), KEYEN 11 (backdoor key disabled).  A wrong FSEC can lock a real part for
 * good, so the value is checked three times: here at compile time, by the host test
 * (tests/test_port.c, test_port_019_flash_config_field), and in the binary image by
 * port_s32k/check_image.py (make firmware); s32k144.ld places the section at 0x400 and
 * asserts its size.  The section attribute is a GCC extension: deviation DEV-005 (Rule 1.2).
 *
 * Requirements: REQ-PORT-019 (specs/requirements/port.md).
 */
#include <stdint.h>
#include "s32k144_regs.h"

/* Compile-time check: FSEC must be 0xFE. */
#if (S32K_FLASH_CFG_FSEC != 0xFEu)
#error "FSEC must be 0xFE (unsecured): another value can lock the part"
#endif

/** The 16 bytes, in address order. */
extern const uint8_t qfoc_s32k_flash_config[16];

/* In its own section, which s32k144.ld places at 0x400 and keeps (KEEP): a GCC attribute,
   deviation DEV-005. */
/* cppcheck-suppress misra-c2012-1.2 ; DEV-005 */
__attribute__((section(".flash_config")))
const uint8_t qfoc_s32k_flash_config[16] = {
    0xFFu, 0xFFu, 0xFFu, 0xFFu, 0xFFu, 0xFFu, 0xFFu, 0xFFu,  /* 0x400: backdoor key (unused) */
    0xFFu, 0xFFu, 0xFFu, 0xFFu,                              /* 0x408: FPROT3..0, no protection */
    S32K_FLASH_CFG_FSEC,                                     /* 0x40C: FSEC */
    S32K_FLASH_CFG_FOPT,                                     /* 0x40D: FOPT */
    0xFFu,                                                   /* 0x40E: FEPROT */
    0xFFu                                                    /* 0x40F: FDPROT */
};
