/*
 * CBMC harness: qfoc_dob_lag() on any valid disturbance-observer instance and
 * any speed.
 *
 * Properties checked for every int16_t speed (-32768 included) and every instance
 * accepted by qfoc_dob_is_valid() (REQ-EMF-012), lambda = k_i G of any size
 * (the rounding to Q15 and the clamp to [1, 32767] included):
 *  - no undefined behaviour: signed/unsigned overflow, conversion, shift, bounds,
 *    pointer and division checks of the command line, in the lag computation
 *    and in the qfoc_sincos / qfoc_atan2 calls it makes (real trig code);
 *  - the normalisation loop ends within 34 halvings (unwinding assertion);
 *  - zero speed or k_theta = 0: lag 0;
 *  - positive speed: lag in [0, 0x6000]; negative speed: 0 or in [0xA000, 0xFFFF].
 * Equality with qfoc_emf_lag() at alpha = lambda is tested (tests/test_emf.c,
 * test_dob_lag).
 *
 * Methods: 1b every int16 speed and every valid instance, lambda of any size; 1c zero
 * speed, k_theta = 0, -32768, lambda rounded and clamped to [1, 32767], the lag range
 * [0, 0x6000] and [0xA000, 0xFFFF]
 */
#include <stdint.h>
#include <stdbool.h>
#include "qfoc/emf.h"
#include "../emf_common.h"

int main(void)
{
    qfoc_dob_t d;
    qfoc_q15_t w = nondet_int16();
    qfoc_angle_t lag;

    build_dob(&d);

    lag = qfoc_dob_lag(&d, w);

    check_lag(lag, w, d.params.k_theta);
    return 0;
}
