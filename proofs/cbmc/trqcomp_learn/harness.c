/*
 * CBMC harness: qfoc_trqcomp_learn() on any valid instance and any inputs.
 *
 * Properties (REQ-TC-004, REQ-TC-005, REQ-TC-006, REQ-TC-007) for every valid parameter set and
 * coefficient state, every angle, every int16 speed error and speed (-32768
 * included):
 *  - no undefined behaviour (overflow, conversion, shift, bounds, pointer checks);
 *  - the instance is still valid (every coefficient within +-amp_max x 65536);
 *  - outside the speed window, for a zero error and for a zero gain the
 *    coefficients are unchanged;
 *  - each coefficient moves by at most 2 x 32767 x 32767 (one rounded Q15 product
 *    times the largest gain, in Q31), and by at most 2 x 32767 for gain 1;
 *  - parameters are not changed.
 * The per-gain step bound |step| <= 2 x 32767 x gain (a product of two symbolic
 * values) is proved by Frama-C WP (contract of qfoc_trqcomp_learn, ensures step_*)
 * and tested against a double reference (tests/test_trqcomp.c): as a SAT problem it
 * does not finish within the time budget.
 *
 * Methods: 1b every valid parameter set and coefficient state, every angle, speed error
 * and speed; 1c -32768, the speed window's edges, zero error and zero gain,
 * coefficients at +-amp_max x 65536, gain 1
 */
#include <stdint.h>
#include <stdbool.h>
#include "qfoc/trqcomp.h"

int16_t nondet_int16(void);
int32_t nondet_int32(void);
uint8_t nondet_uint8(void);
uint16_t nondet_uint16(void);

/* Stand-ins for the trigonometry (goto-instrument --replace-calls, config.mk):
   any values its proved contracts allow (sine and cosine in [-32767, 32767], an
   angle in 0..65535); qfoc_sincos and qfoc_atan2 are verified on their own (WP,
   harnesses trig_sincos and trig_atan2).  The properties below therefore hold for
   every pair of regressors, not only for the table values. */
void stub_sincos(qfoc_angle_t theta, qfoc_sincos_t *out)
{
    int16_t s = nondet_int16();
    int16_t c = nondet_int16();
    (void)theta;
    __CPROVER_assume((s >= -32767) && (c >= -32767));
    out->sine = s;
    out->cosine = c;
}

static bool step_ok(int32_t now, int32_t old, int32_t gain)
{
    const int64_t d = (int64_t)now - (int64_t)old;
    const int64_t lim = (int64_t)2 * 32767 * (int64_t)gain;
    return (d <= lim) && (d >= -lim);
}

int main(void)
{
    qfoc_trqcomp_t tc;
    qfoc_trqcomp_t old;
    const qfoc_angle_t theta = nondet_uint16();
    const int16_t e = nondet_int16();
    const int16_t speed = nondet_int16();
    int32_t mag;
    bool in_window;

    tc.params.gain = nondet_int16();
    tc.params.amp_max = nondet_int16();
    tc.params.speed_min = nondet_int16();
    tc.params.speed_max = nondet_int16();
    tc.params.pole_pairs = nondet_uint8();
    tc.a[0] = nondet_int32();
    tc.b[0] = nondet_int32();
    tc.a[1] = nondet_int32();
    tc.b[1] = nondet_int32();
    __CPROVER_assume(qfoc_trqcomp_is_valid(&tc));
    old = tc;
    mag = (speed < 0) ? -(int32_t)speed : (int32_t)speed;
    in_window = (mag >= (int32_t)tc.params.speed_min) && (mag <= (int32_t)tc.params.speed_max);

    qfoc_trqcomp_learn(&tc, theta, e, speed);

    __CPROVER_assert(qfoc_trqcomp_is_valid(&tc), "still valid");
    __CPROVER_assert((tc.params.gain == old.params.gain) && (tc.params.amp_max == old.params.amp_max)
                     && (tc.params.speed_min == old.params.speed_min)
                     && (tc.params.speed_max == old.params.speed_max)
                     && (tc.params.pole_pairs == old.params.pole_pairs), "parameters unchanged");
    if ((!in_window) || (e == 0) || (tc.params.gain == 0)) {
        __CPROVER_assert((tc.a[0] == old.a[0]) && (tc.b[0] == old.b[0]) && (tc.a[1] == old.a[1])
                         && (tc.b[1] == old.b[1]), "held outside the window / zero error / zero gain");
    }
    if (tc.params.gain == 1) {
        __CPROVER_assert(step_ok(tc.a[0], old.a[0], 1) && step_ok(tc.b[0], old.b[0], 1)
                         && step_ok(tc.a[1], old.a[1], 1) && step_ok(tc.b[1], old.b[1], 1),
                         "gain 1: step at most 2 x 32767");
    }
    __CPROVER_assert(step_ok(tc.a[0], old.a[0], 32767) && step_ok(tc.b[0], old.b[0], 32767)
                     && step_ok(tc.a[1], old.a[1], 32767) && step_ok(tc.b[1], old.b[1], 32767),
                     "step at most 2 x 32767 x 32767");
    return 0;
}
