/*
 * CBMC harness: the drive state machine alone, 40 ticks from ANY valid state with
 * any times and any inputs at every tick (REQ-SM-001 .. REQ-SM-009).
 *
 * Asserted at every tick, against the previous state:
 *  - the invariant holds (REQ-SM-001);
 *  - a fault outside ERROR enters ERROR in the same tick (REQ-SM-002);
 *  - ERROR is left only to STOP, with a clear request, no fault in the tick, the table
 *    intact, and clear_ms reached (REQ-SM-003);
 *  - STOP is entered from PRECHARGE only from CALIB with the calibration done (REQ-SM-004);
 *  - RUN is entered only from STOP, in ALIGN, on a run request (REQ-SM-005);
 *  - OPEN_LOOP only from ALIGN after align_ms; CLOSED_LOOP only from OPEN_LOOP (converged,
 *    cl_hold_ms reached) or STOPPING; STOPPING only from CLOSED_LOOP (REQ-SM-006, REQ-SM-007);
 *  - and over the whole run: a CLOSED_LOOP reached from STOP went through ALIGN and
 *    OPEN_LOOP in that order (tracked by the harness).
 */
#include "qfoc/sm.h"
#include "../harness_util.h"

#define TICKS 40

static qfoc_sm_in_t any_in(void)
{
    qfoc_sm_in_t in;
    in.faults = nondet_uint16();
    in.bus_ok = nondet_bool();
    in.calib_done = nondet_bool();
    in.run_request = nondet_bool();
    in.link_lost = nondet_bool();
    in.fault_clear = nondet_bool();
    in.table_ok = nondet_bool();
    in.converged = nondet_bool();
    in.stop_reached = nondet_bool();
    return in;
}

int main(void)
{
    qfoc_sm_t sm;
    qfoc_sm_cfg_t cfg;
    int k;
    /* harness-side history: 0 none, 1 saw ALIGN after STOP, 2 then OPEN_LOOP */
    int seq = 0;
    bool from_stop = false;

    sm.state = nondet_uint8();
    sm.sub = nondet_uint8();
    sm.faults = nondet_uint16();
    sm.first_fault = nondet_uint16();
    sm.t_state = nondet_uint16();
    sm.t_sub = nondet_uint16();
    __CPROVER_assume(qfoc_sm_is_valid(&sm));
    /* small times so that every timed transition is reachable within 40 ticks */
    cfg.precharge_ms = (uint16_t)(nondet_uint16() % 8u);
    cfg.align_ms = (uint16_t)(nondet_uint16() % 8u);
    cfg.ol_timeout_ms = (uint16_t)(nondet_uint16() % 16u);
    cfg.cl_hold_ms = (uint16_t)(nondet_uint16() % 16u);
    cfg.clear_ms = (uint16_t)(nondet_uint16() % 16u);
    if (sm.state == QFOC_STATE_STOP) {
        from_stop = true;
    }

    for (k = 0; k < TICKS; k++) {
        const qfoc_sm_in_t in = any_in();
        const qfoc_sm_t old = sm;
        const uint16_t f = (uint16_t)(in.faults & 0x7FFu);
        const uint16_t t_old = (old.t_state < 65535u) ? (uint16_t)(old.t_state + 1u) : 65535u;
        const uint16_t ts_old = (old.t_sub < 65535u) ? (uint16_t)(old.t_sub + 1u) : 65535u;
        qfoc_sm_step(&sm, &cfg, &in);

        __CPROVER_assert(qfoc_sm_is_valid(&sm), "REQ-SM-001 invariant");
        if ((old.state != QFOC_STATE_ERROR) && (f != 0u)) {
            __CPROVER_assert(sm.state == QFOC_STATE_ERROR && (sm.faults & f) == f &&
                             sm.first_fault == sm.faults, "REQ-SM-002 fault -> ERROR");
        }
        if ((old.state == QFOC_STATE_ERROR) && (sm.state != QFOC_STATE_ERROR)) {
            __CPROVER_assert(sm.state == QFOC_STATE_STOP && in.fault_clear && in.table_ok &&
                             f == 0u && t_old >= cfg.clear_ms && sm.faults == 0u,
                             "REQ-SM-003 clear only after clear_ms, on request");
        }
        if ((old.state == QFOC_STATE_ERROR) && (sm.state == QFOC_STATE_ERROR)) {
            __CPROVER_assert(sm.faults == old.faults, "REQ-SM-003 latched");
        }
        if ((old.state == QFOC_STATE_PRECHARGE) && (sm.state == QFOC_STATE_STOP)) {
            __CPROVER_assert(old.sub == QFOC_SUB_CALIB && in.calib_done && in.bus_ok,
                             "REQ-SM-004 STOP after calibration");
        }
        if ((old.state != QFOC_STATE_RUN) && (sm.state == QFOC_STATE_RUN)) {
            __CPROVER_assert(old.state == QFOC_STATE_STOP && in.run_request &&
                             sm.sub == QFOC_SUB_ALIGN, "REQ-SM-005 RUN from STOP in ALIGN");
        }
        if ((sm.sub == QFOC_SUB_OPEN_LOOP) && (old.sub != QFOC_SUB_OPEN_LOOP)) {
            __CPROVER_assert(old.sub == QFOC_SUB_ALIGN && ts_old >= cfg.align_ms,
                             "REQ-SM-006 OPEN_LOOP after ALIGN");
        }
        if ((sm.sub == QFOC_SUB_CLOSED_LOOP) && (old.sub != QFOC_SUB_CLOSED_LOOP)) {
            __CPROVER_assert((old.sub == QFOC_SUB_OPEN_LOOP && in.converged &&
                              t_old >= cfg.cl_hold_ms) || old.sub == QFOC_SUB_STOPPING,
                             "REQ-SM-006 CLOSED_LOOP from OPEN_LOOP");
        }
        if ((sm.sub == QFOC_SUB_STOPPING) && (old.sub != QFOC_SUB_STOPPING)) {
            __CPROVER_assert(old.sub == QFOC_SUB_CLOSED_LOOP, "REQ-SM-007 STOPPING from CLOSED_LOOP");
        }
        /* the start-up order over the run, from a STOP */
        if (sm.state == QFOC_STATE_STOP) {
            from_stop = true;
            seq = 0;
        } else if (from_stop && (sm.sub == QFOC_SUB_ALIGN)) {
            seq = 1;
        } else if (from_stop && (sm.sub == QFOC_SUB_OPEN_LOOP) && (seq >= 1)) {
            seq = 2;
        } else if (sm.state != QFOC_STATE_RUN) {
            from_stop = false;
            seq = 0;
        }
        if (from_stop && (sm.sub == QFOC_SUB_CLOSED_LOOP)) {
            __CPROVER_assert(seq == 2, "REQ-SM-006 CLOSED_LOOP only through ALIGN and OPEN_LOOP");
        }
    }
    return 0;
}
