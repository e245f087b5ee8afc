/**
 * @file test_sm.c
 * @brief Tests of the drive state machine (sm.h): every transition and its condition
 *        (specs/requirements/sm.md), against a transition table written here from
 *        the requirements, over random input sequences.
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#define TEST_SEED 0x5E5E5E5Eu
#include "test_util.h"
#include "qfoc/sm.h"

static const qfoc_sm_cfg_t cfg = { 200u, 300u, 2000u, 2000u, 5000u, 0u };
/* the same times with two start retries (REQ-SM-011) */
static const qfoc_sm_cfg_t cfg_retry = { 200u, 300u, 2000u, 2000u, 5000u, 2u };

static qfoc_sm_in_t quiet(void)
{
    qfoc_sm_in_t in;
    in.faults = 0u;
    in.bus_ok = true;
    in.calib_done = false;
    in.run_request = false;
    in.link_lost = false;
    in.fault_clear = false;
    in.table_ok = true;
    in.converged = false;
    in.stop_reached = false;
    in.catch_lock = false;
    in.catch_still = false;
    return in;
}

static void steps(qfoc_sm_t *sm, const qfoc_sm_in_t *in, int n)
{
    int k;
    for (k = 0; k < n; k++) {
        qfoc_sm_step(sm, &cfg, in);
    }
}

/* REQ-SM-001: power-on state and the invariant check.
   Methods: 1b each part of the invariant broken in turn (sub-state of another state, a fault
   word outside ERROR, ERROR without a cause, first fault missing or undefined); 1c the
   undefined state 7 and sub-state 8, the undefined bit 0x0800; 1l the instance's fields
   overwritten, refused by the validity check */
static void test_sm_001_init_and_validity(void **state)
{
    qfoc_sm_t sm;
    (void)state;
    qfoc_sm_init(&sm);
    assert_int_equal(sm.state, QFOC_STATE_PRECHARGE);
    assert_int_equal(sm.sub, QFOC_SUB_BUS_WAIT);
    assert_int_equal(sm.faults, 0);
    assert_true(qfoc_sm_is_valid(&sm));
    sm.sub = QFOC_SUB_ALIGN;                /* RUN sub-state in PRECHARGE */
    assert_false(qfoc_sm_is_valid(&sm));
    sm.sub = QFOC_SUB_BUS_WAIT;
    sm.faults = QFOC_SM_FAULT_STALL;        /* fault word outside ERROR */
    assert_false(qfoc_sm_is_valid(&sm));
    sm.faults = 0u;
    sm.state = 7u;                          /* undefined state */
    assert_false(qfoc_sm_is_valid(&sm));
    sm.state = QFOC_STATE_ERROR;
    sm.sub = QFOC_SUB_NONE;
    assert_false(qfoc_sm_is_valid(&sm));    /* ERROR without a cause */
    sm.faults = 0x0800u;
    sm.first_fault = 0x0800u;
    assert_false(qfoc_sm_is_valid(&sm));    /* undefined bit */
    sm.faults = 0x0001u;
    sm.first_fault = 0x0001u;
    assert_true(qfoc_sm_is_valid(&sm));
    sm.first_fault = 0u;
    assert_false(qfoc_sm_is_valid(&sm));
    sm.first_fault = 0x0800u;
    assert_false(qfoc_sm_is_valid(&sm));
    sm.state = QFOC_STATE_STOP;
    sm.faults = 0u;
    sm.first_fault = 1u;
    assert_false(qfoc_sm_is_valid(&sm));
    sm.state = QFOC_STATE_RUN;
    sm.first_fault = 0u;
    sm.sub = QFOC_SUB_NONE;
    assert_false(qfoc_sm_is_valid(&sm));
    sm.sub = QFOC_SUB_STOPPING;
    assert_true(qfoc_sm_is_valid(&sm));
    sm.sub = QFOC_SUB_CATCH;
    assert_true(qfoc_sm_is_valid(&sm));
    sm.sub = 8u;
    assert_false(qfoc_sm_is_valid(&sm));
    sm.state = QFOC_STATE_STOP;
    sm.sub = QFOC_SUB_CALIB;
    assert_false(qfoc_sm_is_valid(&sm));
}

/* REQ-SM-004: PRECHARGE waits precharge_ms with the bus up, calibrates, then STOP.
   Methods: 1c the 199th and the 200th tick of precharge_ms with the bus up; 1d a bus dip
   during the settling time and the bus lost during the calibration */
static void test_sm_004_precharge(void **state)
{
    qfoc_sm_t sm;
    qfoc_sm_in_t in = quiet();
    (void)state;
    qfoc_sm_init(&sm);
    in.bus_ok = false;
    steps(&sm, &in, 1000);
    assert_int_equal(sm.sub, QFOC_SUB_BUS_WAIT);
    in.bus_ok = true;
    steps(&sm, &in, 199);                    /* t_sub reaches 199 */
    assert_int_equal(sm.sub, QFOC_SUB_BUS_WAIT);
    in.bus_ok = false;                       /* a dip restarts the settling time */
    steps(&sm, &in, 1);
    in.bus_ok = true;
    steps(&sm, &in, 199);
    assert_int_equal(sm.sub, QFOC_SUB_BUS_WAIT);
    steps(&sm, &in, 1);                      /* the 200th tick with the bus up */
    assert_int_equal(sm.sub, QFOC_SUB_CALIB);
    steps(&sm, &in, 50);
    assert_int_equal(sm.state, QFOC_STATE_PRECHARGE);
    in.calib_done = true;
    in.bus_ok = false;                       /* bus lost during calibration */
    steps(&sm, &in, 1);
    assert_int_equal(sm.sub, QFOC_SUB_BUS_WAIT);
    in.bus_ok = true;
    steps(&sm, &in, 200);
    assert_int_equal(sm.sub, QFOC_SUB_CALIB);
    steps(&sm, &in, 1);
    assert_int_equal(sm.state, QFOC_STATE_STOP);
    assert_int_equal(sm.sub, QFOC_SUB_NONE);
    assert_int_equal(sm.t_state, 0);
}

static void to_stop(qfoc_sm_t *sm)
{
    qfoc_sm_in_t in = quiet();
    qfoc_sm_init(sm);
    in.calib_done = true;
    steps(sm, &in, 202);
    assert_int_equal(sm->state, QFOC_STATE_STOP);
}

/* REQ-SM-005: STOP starts on a run request into CATCH; bus or offsets lost: PRECHARGE.
   Methods: 1b the ways out of STOP: a run request, the bus lost, the offsets not calibrated;
   1d the flying start's verdicts given in STOP, which must change nothing */
static void test_sm_005_stop(void **state)
{
    qfoc_sm_t sm;
    qfoc_sm_in_t in = quiet();
    (void)state;
    to_stop(&sm);
    in.calib_done = true;
    steps(&sm, &in, 100);
    assert_int_equal(sm.state, QFOC_STATE_STOP);
    in.run_request = true;
    in.catch_lock = true;                    /* a verdict in STOP changes nothing */
    in.catch_still = true;
    steps(&sm, &in, 1);
    assert_int_equal(sm.state, QFOC_STATE_RUN);
    assert_int_equal(sm.sub, QFOC_SUB_CATCH);
    assert_int_equal(sm.t_state, 0);
    assert_int_equal(sm.t_sub, 0);
    to_stop(&sm);
    in = quiet();
    in.calib_done = true;
    in.bus_ok = false;
    in.run_request = true;
    steps(&sm, &in, 1);
    assert_int_equal(sm.state, QFOC_STATE_PRECHARGE);
    assert_int_equal(sm.sub, QFOC_SUB_BUS_WAIT);
    to_stop(&sm);
    in = quiet();                            /* offsets not calibrated */
    in.run_request = true;
    steps(&sm, &in, 1);
    assert_int_equal(sm.state, QFOC_STATE_PRECHARGE);
}

/* REQ-SM-006, REQ-SM-010: CATCH (standing) -> ALIGN -> OPEN_LOOP -> CLOSED_LOOP, handover
   not before cl_hold_ms counted from ALIGN.
   Methods: 1c the 299th and 300th tick of align_ms, the handover one tick before and at
   cl_hold_ms; 1d an observer converged early (the handover must still wait), convergence
   lost in CLOSED_LOOP */
static void test_sm_006_run_sequence(void **state)
{
    qfoc_sm_t sm;
    qfoc_sm_in_t in = quiet();
    (void)state;
    to_stop(&sm);
    in.calib_done = true;
    in.run_request = true;
    in.converged = true;                     /* converged early: must still wait */
    in.catch_still = true;                   /* the rotor stands */
    steps(&sm, &in, 1);
    assert_int_equal(sm.sub, QFOC_SUB_CATCH);
    steps(&sm, &in, 1);
    assert_int_equal(sm.sub, QFOC_SUB_ALIGN);
    assert_int_equal(sm.t_state, 0);
    steps(&sm, &in, 299);
    assert_int_equal(sm.sub, QFOC_SUB_ALIGN);
    steps(&sm, &in, 1);                      /* the 300th tick of ALIGN */
    assert_int_equal(sm.sub, QFOC_SUB_OPEN_LOOP);
    /* t_state 300 now; the handover waits for 2000 */
    steps(&sm, &in, 1699);
    assert_int_equal(sm.sub, QFOC_SUB_OPEN_LOOP);
    steps(&sm, &in, 1);
    assert_int_equal(sm.sub, QFOC_SUB_CLOSED_LOOP);
    assert_int_equal(sm.state, QFOC_STATE_RUN);
    /* CLOSED_LOOP stays while requested, even without convergence */
    in.converged = false;
    steps(&sm, &in, 10000);
    assert_int_equal(sm.sub, QFOC_SUB_CLOSED_LOOP);
    assert_int_equal(sm.t_state, 12000);
}

/* REQ-SM-007: stop requests: at once from ALIGN and OPEN_LOOP, ramped from CLOSED_LOOP.
   Methods: 1b a stop request in each running sub-state (ALIGN, OPEN_LOOP, CLOSED_LOOP) and a
   restart while ramping down */
static void test_sm_007_stop_requests(void **state)
{
    qfoc_sm_t sm;
    qfoc_sm_in_t in = quiet();
    (void)state;
    in.calib_done = true;
    in.catch_still = true;                                 /* every start through ALIGN */
    to_stop(&sm);
    in.run_request = true;
    steps(&sm, &in, 5);
    assert_int_equal(sm.sub, QFOC_SUB_ALIGN);
    in.run_request = false;
    steps(&sm, &in, 1);
    assert_int_equal(sm.state, QFOC_STATE_STOP);          /* from ALIGN */
    in.run_request = true;
    steps(&sm, &in, 400);
    assert_int_equal(sm.sub, QFOC_SUB_OPEN_LOOP);
    in.run_request = false;
    steps(&sm, &in, 1);
    assert_int_equal(sm.state, QFOC_STATE_STOP);          /* from OPEN_LOOP */
    in.run_request = true;
    in.converged = true;
    steps(&sm, &in, 2100);
    assert_int_equal(sm.sub, QFOC_SUB_CLOSED_LOOP);
    in.run_request = false;
    steps(&sm, &in, 1);
    assert_int_equal(sm.sub, QFOC_SUB_STOPPING);
    steps(&sm, &in, 500);
    assert_int_equal(sm.sub, QFOC_SUB_STOPPING);
    in.run_request = true;                                 /* restart while ramping down */
    steps(&sm, &in, 1);
    assert_int_equal(sm.sub, QFOC_SUB_CLOSED_LOOP);
    in.run_request = false;
    steps(&sm, &in, 1);
    in.stop_reached = true;
    steps(&sm, &in, 1);
    assert_int_equal(sm.state, QFOC_STATE_STOP);
}

/* REQ-SM-002: any fault in any state enters ERROR in the same tick, PWM-off state.
   Methods: 1b every one of the 16 fault-word bits in each of the eight state and sub-state
   pairs; 1d the undefined bits 11 .. 15, which must be ignored */
static void test_sm_002_fault_to_error(void **state)
{
    const uint8_t subs[] = { QFOC_SUB_BUS_WAIT, QFOC_SUB_CALIB, QFOC_SUB_NONE, QFOC_SUB_ALIGN,
                             QFOC_SUB_OPEN_LOOP, QFOC_SUB_CLOSED_LOOP, QFOC_SUB_STOPPING,
                             QFOC_SUB_CATCH };
    const uint8_t sts[] = { QFOC_STATE_PRECHARGE, QFOC_STATE_PRECHARGE, QFOC_STATE_STOP,
                            QFOC_STATE_RUN, QFOC_STATE_RUN, QFOC_STATE_RUN, QFOC_STATE_RUN,
                            QFOC_STATE_RUN };
    unsigned k;
    unsigned bit;
    (void)state;
    for (k = 0; k < 8u; k++) {
        for (bit = 0; bit < 16u; bit++) {
            qfoc_sm_t sm;
            qfoc_sm_in_t in = quiet();
            const uint16_t f = (uint16_t)(1u << bit);
            sm.state = sts[k];
            sm.sub = subs[k];
            sm.faults = 0u;
            sm.first_fault = 0u;
            sm.t_state = 17u;
            sm.t_sub = 5u;
            in.faults = f;
            qfoc_sm_step(&sm, &cfg, &in);
            if (bit < 11u) {
                assert_int_equal(sm.state, QFOC_STATE_ERROR);
                assert_int_equal(sm.faults, f);
                assert_int_equal(sm.first_fault, f);
                assert_int_equal(sm.t_state, 0);
            } else {
                /* undefined bits are ignored */
                assert_int_not_equal(sm.state, QFOC_STATE_ERROR);
            }
            assert_true(qfoc_sm_is_valid(&sm));
        }
    }
}

/* REQ-SM-008: STALL after ol_timeout_ms of OPEN_LOOP; LINK on a lost link while running.
   Methods: 1c the 2299th and 2300th tick of OPEN_LOOP (ol_timeout_ms); 1d a stalled start,
   the link lost in ALIGN and in CLOSED_LOOP, a lost link in STOP (no fault), both faults at
   once */
static void test_sm_008_own_faults(void **state)
{
    qfoc_sm_t sm;
    qfoc_sm_in_t in = quiet();
    (void)state;
    in.calib_done = true;
    to_stop(&sm);
    in.run_request = true;
    in.catch_still = true;
    steps(&sm, &in, 303);                           /* CATCH 1 tick, ALIGN 300 */
    assert_int_equal(sm.sub, QFOC_SUB_OPEN_LOOP);   /* t_sub 1 */
    assert_int_equal(sm.t_sub, 1);
    steps(&sm, &in, 1998);
    assert_int_equal(sm.sub, QFOC_SUB_OPEN_LOOP);
    steps(&sm, &in, 1);
    assert_int_equal(sm.state, QFOC_STATE_ERROR);
    assert_int_equal(sm.faults, QFOC_SM_FAULT_STALL);
    /* link lost in ALIGN */
    to_stop(&sm);
    in = quiet();
    in.calib_done = true;
    in.run_request = true;
    in.catch_still = true;
    steps(&sm, &in, 3);
    assert_int_equal(sm.sub, QFOC_SUB_ALIGN);
    in.link_lost = true;
    in.run_request = false;
    steps(&sm, &in, 1);
    assert_int_equal(sm.state, QFOC_STATE_ERROR);
    assert_int_equal(sm.faults, QFOC_SM_FAULT_LINK);
    /* link lost in CLOSED_LOOP: ramp down first, LINK when the stop completes */
    to_stop(&sm);
    in = quiet();
    in.calib_done = true;
    in.run_request = true;
    in.converged = true;
    in.catch_still = true;
    steps(&sm, &in, 2100);
    assert_int_equal(sm.sub, QFOC_SUB_CLOSED_LOOP);
    in.link_lost = true;
    in.run_request = false;
    steps(&sm, &in, 100);
    assert_int_equal(sm.sub, QFOC_SUB_STOPPING);
    in.stop_reached = true;
    steps(&sm, &in, 1);
    assert_int_equal(sm.state, QFOC_STATE_ERROR);
    assert_int_equal(sm.faults, QFOC_SM_FAULT_LINK);
    /* a lost link in STOP is not a fault */
    to_stop(&sm);
    in = quiet();
    in.calib_done = true;
    in.link_lost = true;
    steps(&sm, &in, 100);
    assert_int_equal(sm.state, QFOC_STATE_STOP);
    /* both at once: the bits add up */
    sm.state = QFOC_STATE_RUN;
    sm.sub = QFOC_SUB_OPEN_LOOP;
    sm.t_sub = 5000u;
    in.faults = QFOC_SM_FAULT_STALL | QFOC_SM_FAULT_LINK;
    qfoc_sm_step(&sm, &cfg, &in);
    assert_int_equal(sm.faults, QFOC_SM_FAULT_STALL | QFOC_SM_FAULT_LINK);
}

/* REQ-SM-003, REQ-SM-009: ERROR is left only after clear_ms, on a clear request, with no
   fault and the table intact; to STOP, word cleared.
   Methods: 1c the clear at tick 4999 and at tick 5000 of clear_ms, the times at 65535
   (saturated); 1d a clear requested too early, with a fault still present, with the table
   failed, and a second fault while in ERROR (the word keeps its cause) */
static void test_sm_003_fault_clear(void **state)
{
    qfoc_sm_t sm;
    qfoc_sm_in_t in = quiet();
    (void)state;
    qfoc_sm_init(&sm);
    qfoc_sm_fail(&sm, 0x0001u);
    assert_int_equal(sm.state, QFOC_STATE_ERROR);
    in.fault_clear = true;
    steps(&sm, &in, 4999);
    assert_int_equal(sm.state, QFOC_STATE_ERROR);
    in.faults = 0x0008u;                     /* still hot: refused */
    steps(&sm, &in, 1);
    assert_int_equal(sm.state, QFOC_STATE_ERROR);
    assert_int_equal(sm.faults, 0x0001u);    /* word keeps the cause */
    in.faults = 0u;
    in.table_ok = false;                     /* table bad: refused */
    steps(&sm, &in, 1);
    assert_int_equal(sm.state, QFOC_STATE_ERROR);
    in.table_ok = true;
    in.fault_clear = false;
    steps(&sm, &in, 1000);
    assert_int_equal(sm.state, QFOC_STATE_ERROR);
    in.fault_clear = true;
    steps(&sm, &in, 1);
    assert_int_equal(sm.state, QFOC_STATE_STOP);
    assert_int_equal(sm.faults, 0);
    assert_int_equal(sm.first_fault, 0);
    /* exactly at clear_ms: the 5000th tick in ERROR clears */
    qfoc_sm_fail(&sm, 0u);
    assert_int_equal(sm.faults, 0x0200u);    /* no cause given: PARAM */
    in.fault_clear = true;
    steps(&sm, &in, 4999);
    assert_int_equal(sm.state, QFOC_STATE_ERROR);
    steps(&sm, &in, 1);
    assert_int_equal(sm.state, QFOC_STATE_STOP);
    /* fail while in ERROR: the word keeps its cause, the time restarts */
    qfoc_sm_fail(&sm, 0x0002u);
    steps(&sm, &in, 3000);
    qfoc_sm_fail(&sm, 0x0004u);
    assert_int_equal(sm.faults, 0x0002u);
    assert_int_equal(sm.first_fault, 0x0002u);
    assert_int_equal(sm.t_state, 0);
    /* times saturate */
    sm.t_state = 65535u;
    sm.t_sub = 65535u;
    in.fault_clear = false;
    steps(&sm, &in, 1);
    assert_int_equal(sm.t_state, 65535u);
    assert_int_equal(sm.t_sub, 65535u);
}

/* STOP -> RUN / CATCH on a run request, from a fresh STOP. */
static void to_catch(qfoc_sm_t *sm, qfoc_sm_in_t *in)
{
    to_stop(sm);
    *in = quiet();
    in->calib_done = true;
    in->run_request = true;
    steps(sm, in, 1);
    assert_int_equal(sm->state, QFOC_STATE_RUN);
    assert_int_equal(sm->sub, QFOC_SUB_CATCH);
    assert_int_equal(sm->t_state, 0);
}

/* REQ-SM-010: the flying start.  CATCH goes to CLOSED_LOOP on a lock (the lock wins over
   still, and the caught rotor does not wait for cl_hold_ms), to ALIGN on still with both
   times restarted, waits otherwise; without a run request it stops at once; STALL after
   ol_timeout_ms in CATCH without a verdict; a lost link in CATCH is LINK.
   Methods: 1b every way out of CATCH: lock, still, lock and still at once, no verdict, no
   run request, lost link; 1c the 1999th and 2000th tick of ol_timeout_ms in CATCH, and the
   timeout in the same tick as a verdict; 1d a verdict outside CATCH, a lost link over a
   lock, both faults at the timeout */
static void test_sm_010_catch(void **state)
{
    qfoc_sm_t sm;
    qfoc_sm_in_t in;
    (void)state;
    /* caught: lock and still at once, the lock wins */
    to_catch(&sm, &in);
    steps(&sm, &in, 9);                      /* no verdict yet: waits */
    assert_int_equal(sm.sub, QFOC_SUB_CATCH);
    assert_int_equal(sm.t_state, 9);
    in.catch_lock = true;
    in.catch_still = true;
    steps(&sm, &in, 1);
    assert_int_equal(sm.state, QFOC_STATE_RUN);
    assert_int_equal(sm.sub, QFOC_SUB_CLOSED_LOOP);
    assert_int_equal(sm.t_sub, 0);
    assert_int_equal(sm.t_state, 10);        /* a sub-state change: RUN's time runs on */
    assert_int_equal(sm.faults, 0);
    /* CLOSED_LOOP stays, whatever the verdicts; a lost link there is no fault at once */
    in.catch_lock = false;
    in.link_lost = true;
    steps(&sm, &in, 50);
    assert_int_equal(sm.sub, QFOC_SUB_CLOSED_LOOP);
    /* the caught rotor stops through STOPPING like any other */
    in.link_lost = false;
    in.run_request = false;
    steps(&sm, &in, 1);
    assert_int_equal(sm.sub, QFOC_SUB_STOPPING);
    in.stop_reached = true;
    steps(&sm, &in, 1);
    assert_int_equal(sm.state, QFOC_STATE_STOP);

    /* lock alone */
    to_catch(&sm, &in);
    in.catch_lock = true;
    steps(&sm, &in, 1);
    assert_int_equal(sm.sub, QFOC_SUB_CLOSED_LOOP);

    /* standing: waits while neither verdict, then ALIGN with both times 0 */
    to_catch(&sm, &in);
    steps(&sm, &in, 1500);
    assert_int_equal(sm.state, QFOC_STATE_RUN);
    assert_int_equal(sm.sub, QFOC_SUB_CATCH);
    assert_int_equal(sm.t_state, 1500);
    assert_int_equal(sm.t_sub, 1500);
    in.catch_still = true;
    steps(&sm, &in, 1);
    assert_int_equal(sm.state, QFOC_STATE_RUN);
    assert_int_equal(sm.sub, QFOC_SUB_ALIGN);
    assert_int_equal(sm.t_state, 0);
    assert_int_equal(sm.t_sub, 0);
    /* the start is timed from ALIGN: OPEN_LOOP after align_ms, the handover after
       cl_hold_ms counted from ALIGN, not from the RUN entry 1501 ticks earlier */
    in.catch_still = false;
    in.catch_lock = true;                    /* a verdict outside CATCH changes nothing */
    in.converged = true;
    steps(&sm, &in, 299);
    assert_int_equal(sm.sub, QFOC_SUB_ALIGN);
    steps(&sm, &in, 1);
    assert_int_equal(sm.sub, QFOC_SUB_OPEN_LOOP);
    assert_int_equal(sm.t_state, 300);
    steps(&sm, &in, 1699);
    assert_int_equal(sm.sub, QFOC_SUB_OPEN_LOOP);
    steps(&sm, &in, 1);
    assert_int_equal(sm.sub, QFOC_SUB_CLOSED_LOOP);

    /* no run request: STOP at once, whatever the verdicts */
    to_catch(&sm, &in);
    steps(&sm, &in, 20);
    in.run_request = false;
    in.catch_lock = true;
    in.catch_still = true;
    steps(&sm, &in, 1);
    assert_int_equal(sm.state, QFOC_STATE_STOP);
    assert_int_equal(sm.sub, QFOC_SUB_NONE);
    assert_int_equal(sm.t_state, 0);
    assert_int_equal(sm.faults, 0);

    /* STALL: ol_timeout_ms in CATCH without a verdict */
    to_catch(&sm, &in);
    steps(&sm, &in, 1999);
    assert_int_equal(sm.sub, QFOC_SUB_CATCH);
    assert_int_equal(sm.t_sub, 1999);
    steps(&sm, &in, 1);
    assert_int_equal(sm.state, QFOC_STATE_ERROR);
    assert_int_equal(sm.faults, QFOC_SM_FAULT_STALL);
    assert_int_equal(sm.first_fault, QFOC_SM_FAULT_STALL);
    /* the timeout wins over a verdict in the same tick */
    to_catch(&sm, &in);
    steps(&sm, &in, 1999);
    in.catch_lock = true;
    steps(&sm, &in, 1);
    assert_int_equal(sm.state, QFOC_STATE_ERROR);
    assert_int_equal(sm.faults, QFOC_SM_FAULT_STALL);

    /* LINK: the link lost in CATCH, with or without the run request, over a lock */
    to_catch(&sm, &in);
    steps(&sm, &in, 5);
    in.link_lost = true;
    in.catch_lock = true;
    steps(&sm, &in, 1);
    assert_int_equal(sm.state, QFOC_STATE_ERROR);
    assert_int_equal(sm.faults, QFOC_SM_FAULT_LINK);
    assert_int_equal(sm.first_fault, QFOC_SM_FAULT_LINK);
    to_catch(&sm, &in);
    in.link_lost = true;
    in.run_request = false;
    steps(&sm, &in, 1);
    assert_int_equal(sm.state, QFOC_STATE_ERROR);
    assert_int_equal(sm.faults, QFOC_SM_FAULT_LINK);
    /* both at the timeout: the bits add up */
    to_catch(&sm, &in);
    steps(&sm, &in, 1999);
    in.link_lost = true;
    steps(&sm, &in, 1);
    assert_int_equal(sm.faults, QFOC_SM_FAULT_STALL | QFOC_SM_FAULT_LINK);
    assert_true(qfoc_sm_is_valid(&sm));
}

/* REQ-SM-009: random sequences against an independent model of the rules. */
typedef struct {
    int st, sub, faults, t_state, t_sub, retry;
} model_t;

/* the times the model and the machine share in the random run: two retries, and an
   open-loop timeout short enough for a start to run out of them many times */
static const qfoc_sm_cfg_t cfg_rand = { 200u, 300u, 600u, 500u, 5000u, 2u };
static const qfoc_sm_cfg_t *mcfg = &cfg_rand;

static void model_step(model_t *m, const qfoc_sm_in_t *in)
{
    const qfoc_sm_cfg_t cfg = *mcfg;
    const int f_in = in->faults & 0x7FF;
    int f = f_in;
    m->t_state = (m->t_state < 65535) ? m->t_state + 1 : 65535;
    m->t_sub = (m->t_sub < 65535) ? m->t_sub + 1 : 65535;
#define GO(s, u) do { m->st = (s); m->sub = (u); m->t_state = 0; m->t_sub = 0; } while (0)
#define GOSUB(u) do { m->sub = (u); m->t_sub = 0; } while (0)
    if (m->st == 3) {
        if (f_in == 0 && m->t_state >= (int)cfg.clear_ms && in->fault_clear && in->table_ok) {
            GO(1, 0);
            m->faults = 0;
        }
        return;
    }
    /* STALL: OPEN_LOOP without a handover and no retry left, or CATCH without a verdict,
       for ol_timeout_ms */
    if (m->st == 2 && m->t_sub >= (int)cfg.ol_timeout_ms &&
        ((m->sub == 4 && m->retry >= (int)cfg.retries) || m->sub == 7)) {
        f |= 0x20;
    }
    /* LINK: lost before the closed loop (CATCH, ALIGN, OPEN_LOOP), or a lost-link stop done */
    if (m->st == 2 && in->link_lost &&
        (m->sub == 7 || m->sub == 3 || m->sub == 4 || (m->sub == 6 && in->stop_reached))) {
        f |= 0x100;
    }
    if (f != 0) {
        GO(3, 0);
        m->faults = f;
        return;
    }
    switch (m->st) {
    case 0:
        if (!in->bus_ok) {
            GOSUB(1);
        } else if (m->sub == 1) {
            if (m->t_sub >= (int)cfg.precharge_ms) {
                GOSUB(2);
            }
        } else if (in->calib_done) {
            GO(1, 0);
        }
        break;
    case 1:
        if (!in->bus_ok || !in->calib_done) {
            GO(0, 1);
        } else if (in->run_request) {
            GO(2, 7);                        /* every start looks for a turning rotor */
            m->retry = 0;
        }
        break;
    default:
        if (m->sub == 7) {
            if (!in->run_request) {
                GO(1, 0);
            } else if (in->catch_lock) {
                GOSUB(5);                    /* caught: t_state runs on from the RUN entry */
            } else if (in->catch_still) {
                GO(2, 3);                    /* standing: ALIGN, both times restart */
            }
        } else if (m->sub == 3) {
            if (!in->run_request) {
                GO(1, 0);
            } else if (m->t_sub >= (int)cfg.align_ms) {
                GOSUB(4);
            }
        } else if (m->sub == 4) {
            if (!in->run_request) {
                GO(1, 0);
            } else if (in->converged && m->t_state >= (int)cfg.cl_hold_ms) {
                GOSUB(5);
            } else if (m->t_sub >= (int)cfg.ol_timeout_ms) {
                GOSUB(7);                    /* a retry: CATCH again, t_state runs on */
                m->retry++;
            }
        } else if (m->sub == 5) {
            if (!in->run_request) {
                GOSUB(6);
            }
        } else {
            if (in->stop_reached) {
                GO(1, 0);
            } else if (in->run_request) {
                GOSUB(5);
            }
        }
        break;
    }
#undef GO
#undef GOSUB
}

/* REQ-SM-001, REQ-SM-002, REQ-SM-003, REQ-SM-004, REQ-SM-005, REQ-SM-006, REQ-SM-007,
   REQ-SM-008, REQ-SM-009, REQ-SM-010, REQ-SM-011: random tick sequences against the model
   above (with two start retries),
   which states every rule (faults, Faultclear, PRECHARGE, STOP, the flying-start CATCH,
   start-up, stopping, the machine's own faults, times); the invariant is checked after
   every tick.  CATCH's verdicts come in spells (a rotor that stands, one that can be
   caught, one that does neither), so that every way out of CATCH, the STALL of a CATCH
   without a verdict included, is taken many times.
   Methods: 1b 2000000 random ticks with spells of each CATCH verdict, rare random fault
   words, every sub-state visited more than 1000 times and every way out of CATCH and
   OPEN_LOOP taken; 1d random fault words with undefined bits, lost links, clears at any
   time; 1n the transition model written from the requirements in the test */
static void test_sm_009_random_against_model(void **state)
{
    qfoc_sm_t sm;
    qfoc_sm_in_t in;
    model_t m = { 0, 1, 0, 0, 0, 0 };
    long k;
    long visits[8] = { 0 };
    long caught = 0;
    long standing = 0;
    long catch_stall = 0;
    long catch_link = 0;
    bool still_spell = false;
    bool lock_spell = false;
    bool stuck_spell = false;
    long retries = 0;
    long ol_stall = 0;
    (void)state;
    qfoc_sm_init(&sm);
    in = quiet();
    for (k = 0; k < 2000000L; k++) {
        const uint32_t r = lcg_next() >> 8;
        const uint32_t flip = (lcg_next() >> 12) % 4096u;
        const uint32_t c = lcg_next() >> 16;
        const qfoc_sm_t old = sm;
        still_spell = (flip == 10u || flip == 11u) ? !still_spell : still_spell;
        lock_spell = (flip == 12u) ? !lock_spell : lock_spell;
        /* spells without convergence, for OPEN_LOOP's timeout, its retries and its STALL */
        stuck_spell = (flip == 13u) ? !stuck_spell : stuck_spell;
        in.catch_still = still_spell && ((c % 4u) != 0u);
        in.catch_lock = lock_spell && (((c >> 2) % 8u) == 0u);
        /* persistent conditions that change now and then, rare faults */
        in.faults = ((r % 6000u) == 0u) ? (uint16_t)(lcg_next() >> 16) : 0u;
        in.bus_ok = (flip == 0u) ? !in.bus_ok : (in.bus_ok || ((r % 50u) == 0u));
        in.calib_done = (flip == 1u) ? !in.calib_done : (in.calib_done || ((r % 300u) == 0u));
        /* the run request held longer in CATCH, for its timeout to be reached */
        in.run_request = (flip < (((sm.sub == QFOC_SUB_CATCH) || stuck_spell) ? 1u : 8u))
                             ? !in.run_request : in.run_request;
        in.link_lost = (flip == 9u) ? !in.link_lost : (in.link_lost && ((r % 100u) != 0u));
        in.fault_clear = ((r >> 3) & 0x1u) != 0u;
        in.table_ok = ((r >> 4) & 0x3Fu) != 0u;
        in.converged = !stuck_spell && (((r >> 10) & 0x3u) != 0u);
        in.stop_reached = ((r >> 12) & 0x3FFu) == 0u;
        qfoc_sm_step(&sm, mcfg, &in);
        model_step(&m, &in);
        assert_int_equal(sm.state, m.st);
        assert_int_equal(sm.sub, m.sub);
        assert_int_equal(sm.faults, m.faults);
        assert_int_equal(sm.t_state, m.t_state);
        assert_int_equal(sm.t_sub, m.t_sub);
        assert_int_equal(sm.retry, m.retry);
        assert_true(qfoc_sm_is_valid(&sm));
        visits[sm.sub]++;
        if (old.state == QFOC_STATE_RUN && old.sub == QFOC_SUB_OPEN_LOOP) {
            retries += (sm.sub == QFOC_SUB_CATCH) ? 1 : 0;
            ol_stall += (sm.state == QFOC_STATE_ERROR &&
                         (sm.faults & QFOC_SM_FAULT_STALL) != 0u) ? 1 : 0;
        }
        if (old.state == QFOC_STATE_RUN && old.sub == QFOC_SUB_CATCH) {
            caught += (sm.sub == QFOC_SUB_CLOSED_LOOP) ? 1 : 0;
            standing += (sm.sub == QFOC_SUB_ALIGN) ? 1 : 0;
            catch_stall += (sm.state == QFOC_STATE_ERROR &&
                            (sm.faults & QFOC_SM_FAULT_STALL) != 0u) ? 1 : 0;
            catch_link += (sm.state == QFOC_STATE_ERROR &&
                           (sm.faults & QFOC_SM_FAULT_LINK) != 0u) ? 1 : 0;
        }
    }
    print_message("sub-state visits: none %ld wait %ld calib %ld align %ld ol %ld cl %ld "
                  "stopping %ld catch %ld\n", visits[0], visits[1], visits[2], visits[3],
                  visits[4], visits[5], visits[6], visits[7]);
    print_message("out of CATCH: caught %ld standing %ld stall %ld link %ld; out of OPEN_LOOP: "
                  "retries %ld stall %ld\n", caught, standing, catch_stall, catch_link,
                  retries, ol_stall);
    assert_true(retries > 20 && ol_stall > 5);
    for (k = 0; k < 8; k++) {
        assert_true(visits[k] > 1000);
    }
    assert_true(caught > 100);
    assert_true(standing > 100);
    assert_true(catch_stall > 10);
    assert_true(catch_link > 10);
}

/* the machine stepped n ticks with cfg_retry */
static void step_r(qfoc_sm_t *sm, const qfoc_sm_in_t *in, int n)
{
    int k;
    for (k = 0; k < n; k++) {
        qfoc_sm_step(sm, &cfg_retry, in);
    }
}

/* REQ-SM-011: the start retries, with two (cfg_retry): an OPEN_LOOP without a handover for
   ol_timeout_ms goes to CATCH (the retry counted, t_sub restarted, t_state running on), a
   standing rotor to ALIGN and OPEN_LOOP again; the third timeout is STALL, in exactly the
   tick ol_timeout_ms after the last OPEN_LOOP entry.  A handover on a retry keeps the
   count; a new RUN entry starts it at 0.  Without retries (cfg) the first timeout is
   STALL (test_sm_008).
   Methods: 1c the 1999th and 2000th tick of OPEN_LOOP on each of the two retries and the
   third timeout (STALL); 1d an OPEN_LOOP without a handover, a handover on a retry, CATCH's
   own timeout with retries left */
static void test_sm_011_start_retries(void **state)
{
    qfoc_sm_t sm;
    qfoc_sm_in_t in;
    int r;
    (void)state;
    to_catch(&sm, &in);
    in.catch_still = true;
    for (r = 0; r <= 2; r++) {
        uint16_t t_state;
        step_r(&sm, &in, 1);                          /* CATCH: standing */
        assert_int_equal(sm.sub, QFOC_SUB_ALIGN);
        assert_int_equal(sm.t_state, 0);
        step_r(&sm, &in, 300);
        assert_int_equal(sm.sub, QFOC_SUB_OPEN_LOOP);
        step_r(&sm, &in, 1999);                       /* t_sub 1999: no timeout yet */
        assert_int_equal(sm.state, QFOC_STATE_RUN);
        assert_int_equal(sm.sub, QFOC_SUB_OPEN_LOOP);
        assert_int_equal(sm.retry, r);
        t_state = sm.t_state;
        step_r(&sm, &in, 1);
        if (r < 2) {
            assert_int_equal(sm.state, QFOC_STATE_RUN);
            assert_int_equal(sm.sub, QFOC_SUB_CATCH);
            assert_int_equal(sm.retry, r + 1);
            assert_int_equal(sm.t_sub, 0);
            assert_int_equal(sm.t_state, t_state + 1);
            assert_int_equal(sm.faults, 0u);
        } else {
            assert_int_equal(sm.state, QFOC_STATE_ERROR);
            assert_int_equal(sm.faults, QFOC_SM_FAULT_STALL);
        }
    }
    /* a handover on the first retry keeps the count; the next RUN entry starts at 0 */
    to_catch(&sm, &in);
    in.catch_still = true;
    step_r(&sm, &in, 301 + 2000);
    assert_int_equal(sm.sub, QFOC_SUB_CATCH);
    assert_int_equal(sm.retry, 1);
    step_r(&sm, &in, 301);
    assert_int_equal(sm.sub, QFOC_SUB_OPEN_LOOP);
    in.converged = true;
    step_r(&sm, &in, 2000);
    assert_int_equal(sm.sub, QFOC_SUB_CLOSED_LOOP);
    assert_int_equal(sm.retry, 1);
    in.run_request = false;
    in.stop_reached = true;
    step_r(&sm, &in, 2);
    assert_int_equal(sm.state, QFOC_STATE_STOP);
    in.run_request = true;
    step_r(&sm, &in, 1);
    assert_int_equal(sm.sub, QFOC_SUB_CATCH);
    assert_int_equal(sm.retry, 0);
    /* CATCH's own timeout is STALL whatever the retries left */
    in.catch_still = false;
    in.converged = false;
    step_r(&sm, &in, 2000);
    assert_int_equal(sm.state, QFOC_STATE_ERROR);
    assert_int_equal(sm.faults, QFOC_SM_FAULT_STALL);
    assert_true(qfoc_sm_is_valid(&sm));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_sm_001_init_and_validity),
        cmocka_unit_test(test_sm_002_fault_to_error),
        cmocka_unit_test(test_sm_003_fault_clear),
        cmocka_unit_test(test_sm_004_precharge),
        cmocka_unit_test(test_sm_005_stop),
        cmocka_unit_test(test_sm_006_run_sequence),
        cmocka_unit_test(test_sm_007_stop_requests),
        cmocka_unit_test(test_sm_008_own_faults),
        cmocka_unit_test(test_sm_009_random_against_model),
        cmocka_unit_test(test_sm_010_catch),
        cmocka_unit_test(test_sm_011_start_retries),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
