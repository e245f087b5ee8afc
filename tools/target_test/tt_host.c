/**
 * @file tt_host.c
 * @brief Host build of the runner (tt_io.h): stdio console, the command line from argv.
 *
 * The host build replays the vectors with the host library: it must find every group
 * identical (the generator and the runner agree), and it is where the runner's
 * self-test shows that a corrupted digest or input is reported (make target-test).
 */
#define _POSIX_C_SOURCE 200809L

#include <stdio.h>
#include <string.h>
#include <time.h>

#include "tt_io.h"

void tt_io_puts(const char *s)
{
    (void)fputs(s, stdout);
    (void)fflush(stdout);
}

uint32_t tt_io_clock_cs(void)
{
    struct timespec ts;
    (void)clock_gettime(CLOCK_MONOTONIC, &ts);
    return (uint32_t)((uint64_t)ts.tv_sec * 100u + (uint64_t)ts.tv_nsec / 10000000u);
}

const char *tt_io_platform(void)
{
    return "the host (gcc " __VERSION__ ")";
}

int main(int argc, char **argv)
{
    static char line[1024];
    size_t len = 0u;
    int k;
    for (k = 0; k < argc; k++) {
        const size_t n = strlen(argv[k]);
        if (len + n + 2u > sizeof line) {
            (void)fputs("tt_runner: command line too long\n", stderr);
            return 2;
        }
        memcpy(&line[len], argv[k], n);
        len += n;
        line[len] = ' ';
        len++;
    }
    line[len] = '\0';
    return (int)tt_run(line);
}
