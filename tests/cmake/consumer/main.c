/*
 * main.c -- the consumer program of the CMake check (make cmake-check, mk/cmake.mk): built
 * against qfoc::qfoc through add_subdirectory and through the installed package.
 *
 * REQ-VER-002: the library it links reports the version of the headers it was compiled
 * with; then one drive is initialised from the reference motor's table and each entry
 * point called once at rest.  Exit status 0 when all of it holds.
 */
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "qfoc/version.h"
#include "qfoc/drive.h"
#include "reference_params.h"

static qfoc_drive_t motor;

int main(void)
{
    static const qfoc_adc_t adc = { 2048u, 2048u, 2000u };
    static const qfoc_tick_in_t tick_in = { 250, 250, NULL, 0u };
    int rc = 0;
    int32_t init;
    qfoc_pwm_t pwm;

    if ((qfoc_version() != QFOC_VERSION) || (strcmp(qfoc_version_string(), QFOC_VERSION_STRING) != 0)) {
        (void)printf("consumer: headers %s, library %s: different releases\n", QFOC_VERSION_STRING,
                     qfoc_version_string());
        return 1;
    }
    init = qfoc_drive_init(&motor, &qfoc_params_reference);
    pwm = qfoc_drive_fast_step(&motor, &adc);
    (void)qfoc_drive_tick(&motor, &tick_in);
    if ((init != QFOC_PARAMS_OK) || pwm.enable || !qfoc_drive_is_valid(&motor)) {
        (void)printf("consumer: drive init %d, pwm %s\n", (int)init, pwm.enable ? "on" : "off");
        rc = 1;
    } else {
        (void)printf("consumer: qfoc %s (0x%06lx), drive initialised, one fast step and one tick: pass\n",
                     qfoc_version_string(), (unsigned long)qfoc_version());
    }
    return rc;
}
