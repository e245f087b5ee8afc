/*
 * release_example.c -- the smallest program an integrator writes against a qfoc release
 * (make release-check builds it from the unpacked package: on the host, where it runs,
 * and for the Cortex-M4F against the package's libqfoc.a).
 *
 * Checks that the headers and the library are of the same release, initialises one
 * drive from the reference motor's parameter table (tables/reference_params.c), and
 * calls each entry point once with the motor at rest: the drive must accept the table,
 * keep its PWM off (it starts in PRECHARGE) and stay valid.  No I/O, no library call
 * besides qfoc's: the exit status is the result (0 = pass; 1 .. 5 = the failed step).
 */
#include <stddef.h>
#include <stdint.h>
#include <stdbool.h>

#include "qfoc/version.h"
#include "qfoc/drive.h"
#include "reference_params.h"

/* the motor object: static storage, as in a firmware */
static qfoc_drive_t motor;

int main(void)
{
    int rc = 0;
    static const qfoc_adc_t adc = { 2048u, 2048u, 2000u };   /* zero current, a bus voltage */
    static const qfoc_tick_in_t tick_in = { 250, 250, NULL, 0u };  /* 25.0 degC, no frame */

    if (qfoc_version() != QFOC_VERSION) {
        rc = 1;  /* headers and library of different releases */
    } else if (qfoc_drive_init(&motor, &qfoc_params_reference) != QFOC_PARAMS_OK) {
        rc = 2;  /* table refused */
    } else {
        const qfoc_pwm_t pwm = qfoc_drive_fast_step(&motor, &adc);
        const qfoc_tick_out_t out = qfoc_drive_tick(&motor, &tick_in);
        (void)out;
        if (pwm.enable) {
            rc = 3;  /* PWM on before the drive was commanded to run */
        } else if (motor.s.sm.state == QFOC_STATE_ERROR) {
            rc = 4;  /* a fault at rest */
        } else if (!qfoc_drive_is_valid(&motor)) {
            rc = 5;  /* invariant lost */
        } else {
            rc = 0;
        }
    }
    return rc;
}
