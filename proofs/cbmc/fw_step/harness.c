/*
 * CBMC harness: qfoc_fw_step() on any valid instance, any utilisation and both
 * values of enable; qfoc_fw_init() on any parameter set.
 *
 * Properties checked (REQ-FW-001, REQ-FW-002, REQ-FW-004, REQ-FW-005, REQ-FW-006):
 *  - no undefined behaviour (overflow, conversion, shift, bounds, pointer and
 *    division checks of the command line) in the filter, the error and the PI for
 *    every instance accepted by qfoc_fw_is_valid() and every int16_t utilisation
 *    (-32768 included);
 *  - the result lies in [pi.out_min, 0] and equals fw.id_ref;
 *  - enable false (release): result 0, integrator 0, filter state 0, flag clear;
 *  - enable true: the integrator moves in the direction of the error
 *    level - util_f (util_f recomputed here from the new filter state), so the
 *    i_d reference falls while the utilisation is above the level and rises while
 *    it is below; with the error 0 the integrator is unchanged; the filter state
 *    moves toward the (non-negative) input;
 *  - qfoc_fw_init() on any parameter set leaves a valid instance with a cleared
 *    state and returns 0 exactly for valid parameters.
 * The instance invariant after a step (qfoc_fw_is_valid(), in particular the
 * filter state in [0, 32767 x 65536], which needs the no-overshoot half of the
 * low-pass convex combination) and the exact arithmetic are proved by Frama-C WP
 * (contract of qfoc_fw_step: still_valid, util, integ, result) and tested
 * against a double model (tests/test_fw.c): bit-level reasoning through the
 * 64-bit multipliers does not finish within the time budget.
 *
 * Methods: 1b every valid instance, every int16 utilisation, enable true and false,
 * every parameter set of init; 1c the utilisation -32768, the error 0, the result range
 * [out_min, 0]; 1d invalid parameters of init
 */
#include <stdint.h>
#include <stdbool.h>
#include "qfoc/fw.h"
#include "../harness_util.h"

int main(void)
{
    qfoc_fw_t fw;
    qfoc_fw_params_t p;
    const int16_t util = nondet_int16();
    const bool enable = nondet_bool();
    int32_t integ_old;
    int32_t state_old;
    int64_t input;
    int32_t util_f;
    int32_t err;
    int16_t r;
    int32_t st;

    fw.pi.params.kp = nondet_int16();
    fw.pi.params.kp_shift = nondet_uint8();
    fw.pi.params.ki = nondet_int16();
    fw.pi.params.ki_shift = nondet_uint8();
    fw.pi.params.out_min = nondet_int16();
    fw.pi.params.out_max = nondet_int16();
    fw.pi.integ = nondet_int32();
    fw.pi.limited = nondet_bool();
    fw.util_lpf.alpha = nondet_int16();
    fw.util_lpf.state = nondet_int32();
    fw.level = nondet_int16();
    fw.id_ref = nondet_int16();
    __CPROVER_assume(qfoc_fw_is_valid(&fw));
    integ_old = fw.pi.integ;
    state_old = fw.util_lpf.state;
    input = (int64_t)((util < 0) ? 0 : util) * 65536;

    r = qfoc_fw_step(&fw, util, enable);

    __CPROVER_assert((r >= fw.pi.params.out_min) && (r <= 0), "result in [out_min, 0]");
    __CPROVER_assert(r == fw.id_ref, "result stored as id_ref");
    if (!enable) {
        __CPROVER_assert((r == 0) && (fw.pi.integ == 0) && (fw.util_lpf.state == 0) &&
                         !fw.pi.limited, "release: reference, integrator and filter 0");
    } else {
        st = fw.util_lpf.state;
        if ((int64_t)state_old <= input) {
            __CPROVER_assert(st >= state_old, "rising utilisation: filter does not fall");
        } else {
            __CPROVER_assert(st <= state_old, "falling utilisation: filter does not rise");
        }
        if (st >= 0) {
            util_f = (int32_t)(((int64_t)st + 32768) / 65536);
            err = (int32_t)fw.level - util_f;
            if (err > 0) {
                __CPROVER_assert(fw.pi.integ >= integ_old,
                                 "utilisation below the level: reference does not fall");
            }
            if (err < 0) {
                __CPROVER_assert(fw.pi.integ <= integ_old,
                                 "utilisation above the level: reference does not rise");
            }
            if (err == 0) {
                __CPROVER_assert(fw.pi.integ == integ_old, "error 0: integrator unchanged");
            }
        }
    }

    /* init on any parameter set */
    p.pi.kp = nondet_int16();
    p.pi.kp_shift = nondet_uint8();
    p.pi.ki = nondet_int16();
    p.pi.ki_shift = nondet_uint8();
    p.pi.out_min = nondet_int16();
    p.pi.out_max = nondet_int16();
    p.level = nondet_int16();
    p.alpha = nondet_int16();
    {
        const int32_t status = qfoc_fw_init(&fw, &p);
        __CPROVER_assert(qfoc_fw_is_valid(&fw), "init: valid instance");
        __CPROVER_assert((fw.id_ref == 0) && (fw.pi.integ == 0) && (fw.util_lpf.state == 0),
                         "init: cleared state");
        __CPROVER_assert((status == 0) == qfoc_fw_params_is_valid(&p), "init: status");
        if (status != 0) {
            __CPROVER_assert((fw.pi.params.out_min == 0) && (fw.pi.params.out_max == 0),
                             "rejected: limits [0, 0] (no field weakening)");
        }
    }
    return 0;
}
