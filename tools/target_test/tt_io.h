/**
 * @file tt_io.h
 * @brief The runner's console, clock and entry point, implemented once for the target
 *        (tt_target.c: Arm semihosting) and once for the host (tt_host.c: stdio).
 */
#ifndef QFOC_TT_IO_H
#define QFOC_TT_IO_H

#include <stdint.h>

/** Write a NUL-terminated string to the console. */
void tt_io_puts(const char *s);

/** Elapsed time in centiseconds since an arbitrary origin (0 when unavailable). */
uint32_t tt_io_clock_cs(void);

/** Name of the platform the runner runs on, for the report. */
const char *tt_io_platform(void);

/**
 * @brief Replay every selected group and report (tt_runner.c).
 * @param[in] cmdline the command line: the program name, then the options
 *            --only NAME (repeatable), --corrupt-expected NAME INDEX,
 *            --corrupt-input NAME INDEX, --list
 * @return 0: every replayed group identical; 1: a difference; 2: usage or set-up error.
 */
int32_t tt_run(const char *cmdline);

#endif /* QFOC_TT_IO_H */
