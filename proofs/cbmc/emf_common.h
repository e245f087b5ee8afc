/*
 * proofs/cbmc/emf_common.h -- instance builders and the lag check shared by the
 * back-EMF and disturbance-observer harnesses (emf_step, emf_lag, dob_step, dob_lag).
 *
 * build_emf() / build_dob(): any instance that qfoc_emf_is_valid() /
 * qfoc_dob_is_valid() accepts, every field nondet.
 * check_lag(): the range of the lag of either block (REQ-EMF-007, REQ-EMF-012).
 */
#ifndef QFOC_EMF_COMMON_H
#define QFOC_EMF_COMMON_H

#include "qfoc/emf.h"
#include "harness_util.h"

static void build_emf(qfoc_emf_t *e)
{
    e->params.r = nondet_int16();
    e->params.l = nondet_int16();
    e->params.alpha = nondet_int16();
    e->params.k_theta = nondet_uint16();
    e->i_prev.alpha = nondet_int16();
    e->i_prev.beta = nondet_int16();
    e->lpf_alpha.alpha = nondet_int16();
    e->lpf_alpha.state = nondet_int32();
    e->lpf_beta.alpha = nondet_int16();
    e->lpf_beta.state = nondet_int32();
    e->active = nondet_bool();
    __CPROVER_assume(qfoc_emf_is_valid(e));
}

static void build_dob(qfoc_dob_t *d)
{
    d->params.ki = nondet_int16();
    d->params.ki_shift = nondet_uint8();
    d->params.r = nondet_int16();
    d->params.g = nondet_int16();
    d->params.k_theta = nondet_uint16();
    d->ih_alpha = nondet_int32();
    d->ih_beta = nondet_int32();
    d->i_prev.alpha = nondet_int16();
    d->i_prev.beta = nondet_int16();
    d->e_prev.alpha = nondet_int16();
    d->e_prev.beta = nondet_int16();
    __CPROVER_assume(qfoc_dob_is_valid(d));
}

/* the lag of either block for speed w: 0 at standstill or with k_theta = 0,
   within [0, 135 deg] for w > 0 and within [-135 deg, 0] for w < 0 */
static void check_lag(qfoc_angle_t lag, qfoc_q15_t w, uint16_t k_theta)
{
    if ((w == 0) || (k_theta == 0u)) {
        __CPROVER_assert(lag == 0u, "zero speed: no lag");
    }
    if (w > 0) {
        __CPROVER_assert(lag <= 0x6000u, "positive speed: lag in [0, 135 deg]");
    }
    if (w < 0) {
        __CPROVER_assert((lag == 0u) || (lag >= 0xA000u), "negative speed: lag in [-135 deg, 0]");
    }
}

#endif /* QFOC_EMF_COMMON_H */
