/*
 * CBMC harness: qfoc_trqcomp_output() and qfoc_trqcomp_phase1() on any valid
 * instance and any inputs.
 *
 * Properties (REQ-TC-005, REQ-TC-008, REQ-TC-009) for every valid parameter set and
 * coefficient state, every angle and every int16 speed (-32768 included):
 *  - no undefined behaviour (overflow of the int64 sum, conversion, shift, bounds,
 *    pointer checks);
 *  - the output is in [-32767, 32767]; for amp_max <= 255: |output| <= 4 amp_max
 *    (the bound for every amp_max, a product of symbolic values, is proved by
 *    Frama-C WP: contract of qfoc_trqcomp_output, ensures bound; as a SAT problem
 *    it does not finish within the time budget);
 *  - outside the speed window the output is 0; all coefficients 0 give 0;
 *  - phase1 is total (no undefined behaviour for any coefficients).
 *
 * Methods: 1b every valid parameter set and coefficient state, every angle and speed;
 * 1c -32768, the speed window's edges, amp_max up to 255, all coefficients 0, the
 * output range [-32767, 32767]
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

qfoc_angle_t stub_atan2(qfoc_q15_t y, qfoc_q15_t x)
{
    (void)y;
    (void)x;
    return nondet_uint16();
}

int main(void)
{
    qfoc_trqcomp_t tc;
    const qfoc_angle_t theta = nondet_uint16();
    const int16_t speed = nondet_int16();
    int32_t mag;
    int32_t out;
    qfoc_angle_t ph;

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
    mag = (speed < 0) ? -(int32_t)speed : (int32_t)speed;

    out = (int32_t)qfoc_trqcomp_output(&tc, theta, speed);
    ph = qfoc_trqcomp_phase1(&tc);
    (void)ph;

    __CPROVER_assert((out >= -32767) && (out <= 32767), "symmetric Q15 range");
    if (tc.params.amp_max <= 255) {
        __CPROVER_assert((out <= (4 * (int32_t)tc.params.amp_max))
                         && (out >= -(4 * (int32_t)tc.params.amp_max)),
                         "amp_max <= 255: |output| <= 4 amp_max");
    }
    if ((mag < (int32_t)tc.params.speed_min) || (mag > (int32_t)tc.params.speed_max)) {
        __CPROVER_assert(out == 0, "zero outside the speed window");
    }
    if ((tc.a[0] == 0) && (tc.b[0] == 0) && (tc.a[1] == 0) && (tc.b[1] == 0)) {
        __CPROVER_assert(out == 0, "zero coefficients: zero output");
    }
    return 0;
}
