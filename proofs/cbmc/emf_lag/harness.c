/*
 * CBMC harness: qfoc_emf_lag() on any valid back-EMF instance and any speed.
 *
 * Properties checked for every int16_t speed (-32768 included) and every instance
 * accepted by qfoc_emf_is_valid() (REQ-EMF-007):
 *  - no undefined behaviour: signed/unsigned overflow, conversion, shift, bounds,
 *    pointer and division checks of the command line, in the lag computation
 *    and in the qfoc_sincos / qfoc_atan2 calls it makes (real trig code);
 *  - the normalisation loop ends within 34 halvings (unwinding assertion);
 *  - zero speed or k_theta = 0: lag 0;
 *  - positive speed: lag in [0, 0x6000] (0 .. 135 degrees: filter phase < 90,
 *    half sample <= 45 degrees); negative speed: 0 or in [0xA000, 0xFFFF].
 * The odd symmetry lag(-w) = -lag(w) and the value against the double formula
 * are tested for every speed (tests/test_emf.c, test_lag_all_speeds): a miter of
 * two lag computations does not finish within the time budget.
 *
 * Methods: 1b every int16 speed and every valid instance; 1c zero speed, k_theta = 0,
 * -32768, the lag range [0, 0x6000] (135 degrees) and [0xA000, 0xFFFF]
 */
#include <stdint.h>
#include <stdbool.h>
#include "qfoc/emf.h"
#include "../emf_common.h"

int main(void)
{
    qfoc_emf_t e;
    qfoc_q15_t w = nondet_int16();
    qfoc_angle_t lag;

    build_emf(&e);

    lag = qfoc_emf_lag(&e, w);

    check_lag(lag, w, e.params.k_theta);
    return 0;
}
