/*
 * CBMC harness: the drive state machine alone, 40 ticks from ANY valid state with
 * any times and any inputs at every tick, the flying start's verdicts (catch_lock,
 * catch_still) and the start retries included (REQ-SM-001 .. REQ-SM-011).
 *
 * Asserted at every tick, against the previous state:
 *  - the invariant holds (REQ-SM-001);
 *  - a fault outside ERROR enters ERROR in the same tick (REQ-SM-002);
 *  - ERROR is left only to STOP, with a clear request, no fault in the tick, the table
 *    intact, and clear_ms reached (REQ-SM-003);
 *  - STOP is entered from PRECHARGE only from CALIB with the calibration done (REQ-SM-004);
 *  - RUN is entered only from STOP, in CATCH, on a run request, with both times 0
 *    (REQ-SM-005);
 *  - CATCH is held only in RUN entered from STOP or kept from CATCH, and is kept only
 *    without a verdict, with the run request and the link, before ol_timeout_ms; ALIGN is
 *    entered only from CATCH, on catch_still without catch_lock, with both times 0 (the
 *    start is timed from ALIGN); CLOSED_LOOP from CATCH only on catch_lock, RUN's time
 *    running on (REQ-SM-010);
 *  - CATCH lasting ol_timeout_ms is STALL, a link lost in CATCH is LINK (REQ-SM-008);
 *  - OPEN_LOOP lasting ol_timeout_ms without a handover goes to CATCH with the retry
 *    counted while retries are left, and is STALL when none is; the count changes only
 *    there and starts at 0 on a RUN entry (REQ-SM-011);
 *  - OPEN_LOOP only from ALIGN after align_ms; CLOSED_LOOP only from OPEN_LOOP (converged,
 *    cl_hold_ms reached), CATCH (caught) or STOPPING; STOPPING only from CLOSED_LOOP
 *    (REQ-SM-006, REQ-SM-007);
 *  - and over the whole run: a CLOSED_LOOP reached from STOP went either through CATCH
 *    straight to CLOSED_LOOP (caught), or through CATCH, ALIGN and OPEN_LOOP in that order,
 *    a retry going back to CATCH (tracked by the harness).
 *
 * Methods: 1b 40 ticks from any valid state with any times and any inputs at every
 * tick, the flying start's verdicts and the retries included; 1c the timeouts
 * ol_timeout_ms, align_ms, cl_hold_ms and clear_ms reached; 1d faults, lost links and
 * clear requests at any tick, a CATCH without a verdict
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
    in.catch_lock = nondet_bool();
    in.catch_still = nondet_bool();
    return in;
}

int main(void)
{
    qfoc_sm_t sm;
    qfoc_sm_cfg_t cfg;
    int k;
    /* harness-side history since the last STOP: 0 none, 1 CATCH, 2 then ALIGN, 3 then
       OPEN_LOOP, 4 CLOSED_LOOP straight from CATCH (caught) */
    int seq = 0;
    bool from_stop = false;

    sm.state = nondet_uint8();
    sm.sub = nondet_uint8();
    sm.faults = nondet_uint16();
    sm.first_fault = nondet_uint16();
    sm.t_state = nondet_uint16();
    sm.t_sub = nondet_uint16();
    sm.retry = nondet_uint8();
    __CPROVER_assume(qfoc_sm_is_valid(&sm));
    /* small times so that every timed transition is reachable within 40 ticks */
    cfg.precharge_ms = (uint16_t)(nondet_uint16() % 8u);
    cfg.align_ms = (uint16_t)(nondet_uint16() % 8u);
    cfg.ol_timeout_ms = (uint16_t)(nondet_uint16() % 16u);
    cfg.cl_hold_ms = (uint16_t)(nondet_uint16() % 16u);
    cfg.clear_ms = (uint16_t)(nondet_uint16() % 16u);
    cfg.retries = (uint8_t)(nondet_uint8() % 4u);
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
                             sm.sub == QFOC_SUB_CATCH && sm.t_state == 0u && sm.t_sub == 0u &&
                             sm.retry == 0u,
                             "REQ-SM-005 RUN from STOP in CATCH");
        }
        if ((sm.state == QFOC_STATE_RUN) && (sm.sub == QFOC_SUB_CATCH)) {
            __CPROVER_assert(old.state == QFOC_STATE_STOP ||
                             (old.state == QFOC_STATE_RUN && old.sub == QFOC_SUB_CATCH) ||
                             (old.state == QFOC_STATE_RUN && old.sub == QFOC_SUB_OPEN_LOOP),
                             "REQ-SM-010 REQ-SM-011 CATCH only from STOP, CATCH or a retry");
        }
        if ((old.state == QFOC_STATE_RUN) && (old.sub == QFOC_SUB_OPEN_LOOP) &&
            (sm.sub == QFOC_SUB_CATCH)) {
            __CPROVER_assert(sm.state == QFOC_STATE_RUN && ts_old >= cfg.ol_timeout_ms &&
                             old.retry < cfg.retries && sm.retry == old.retry + 1u &&
                             sm.t_sub == 0u && sm.t_state == t_old && in.run_request &&
                             f == 0u && !in.link_lost,
                             "REQ-SM-011 a retry after ol_timeout_ms with retries left");
        }
        if ((old.state == QFOC_STATE_RUN) && (old.sub == QFOC_SUB_OPEN_LOOP) &&
            (ts_old >= cfg.ol_timeout_ms) && in.run_request && (f == 0u) && !in.link_lost &&
            !(in.converged && (t_old >= cfg.cl_hold_ms))) {
            if (old.retry < cfg.retries) {
                __CPROVER_assert(sm.state == QFOC_STATE_RUN && sm.sub == QFOC_SUB_CATCH,
                                 "REQ-SM-011 OPEN_LOOP timeout with a retry left: CATCH");
            } else {
                __CPROVER_assert(sm.state == QFOC_STATE_ERROR &&
                                 sm.faults == QFOC_SM_FAULT_STALL,
                                 "REQ-SM-008 REQ-SM-011 OPEN_LOOP timeout, no retry left: STALL");
            }
        }
        if ((old.state == QFOC_STATE_RUN) && (sm.state == QFOC_STATE_RUN) &&
            !((old.sub == QFOC_SUB_OPEN_LOOP) && (sm.sub == QFOC_SUB_CATCH))) {
            __CPROVER_assert(sm.retry == old.retry, "REQ-SM-011 the count kept");
        }
        if ((sm.sub == QFOC_SUB_ALIGN) && (old.sub != QFOC_SUB_ALIGN)) {
            __CPROVER_assert(old.state == QFOC_STATE_RUN && old.sub == QFOC_SUB_CATCH &&
                             in.catch_still && !in.catch_lock && in.run_request &&
                             sm.t_state == 0u && sm.t_sub == 0u,
                             "REQ-SM-010 ALIGN only from CATCH, standing, times 0");
        }
        if ((sm.sub == QFOC_SUB_CLOSED_LOOP) && (old.sub == QFOC_SUB_CATCH)) {
            __CPROVER_assert(in.catch_lock && in.run_request && f == 0u &&
                             sm.t_state == t_old && sm.t_sub == 0u,
                             "REQ-SM-010 CLOSED_LOOP from CATCH only when caught");
        }
        if ((old.state == QFOC_STATE_RUN) && (old.sub == QFOC_SUB_CATCH) &&
            (sm.state == QFOC_STATE_RUN) && (sm.sub == QFOC_SUB_CATCH)) {
            __CPROVER_assert(!in.catch_lock && !in.catch_still && in.run_request &&
                             !in.link_lost && ts_old < cfg.ol_timeout_ms,
                             "REQ-SM-010 CATCH waits only without a verdict, before its timeout");
        }
        if ((old.state == QFOC_STATE_RUN) && (old.sub == QFOC_SUB_CATCH) &&
            (ts_old >= cfg.ol_timeout_ms)) {
            __CPROVER_assert(sm.state == QFOC_STATE_ERROR &&
                             (sm.faults & QFOC_SM_FAULT_STALL) != 0u,
                             "REQ-SM-008 STALL when CATCH lasts ol_timeout_ms");
        }
        if ((old.state == QFOC_STATE_RUN) && (old.sub == QFOC_SUB_CATCH) && in.link_lost) {
            __CPROVER_assert(sm.state == QFOC_STATE_ERROR &&
                             (sm.faults & QFOC_SM_FAULT_LINK) != 0u,
                             "REQ-SM-008 LINK when the link is lost in CATCH");
        }
        if ((sm.sub == QFOC_SUB_OPEN_LOOP) && (old.sub != QFOC_SUB_OPEN_LOOP)) {
            __CPROVER_assert(old.sub == QFOC_SUB_ALIGN && ts_old >= cfg.align_ms,
                             "REQ-SM-006 OPEN_LOOP after ALIGN");
        }
        if ((sm.sub == QFOC_SUB_CLOSED_LOOP) && (old.sub != QFOC_SUB_CLOSED_LOOP)) {
            __CPROVER_assert((old.sub == QFOC_SUB_OPEN_LOOP && in.converged &&
                              t_old >= cfg.cl_hold_ms) ||
                             (old.sub == QFOC_SUB_CATCH && in.catch_lock) ||
                             old.sub == QFOC_SUB_STOPPING,
                             "REQ-SM-006 CLOSED_LOOP from OPEN_LOOP, CATCH or STOPPING");
        }
        if ((sm.sub == QFOC_SUB_STOPPING) && (old.sub != QFOC_SUB_STOPPING)) {
            __CPROVER_assert(old.sub == QFOC_SUB_CLOSED_LOOP, "REQ-SM-007 STOPPING from CLOSED_LOOP");
        }
        /* the start-up order over the run, from a STOP: CATCH, then either CLOSED_LOOP
           at once (caught) or ALIGN and OPEN_LOOP; a sub-state out of this order leaves
           seq where it was, and the assertion below fails */
        if (sm.state == QFOC_STATE_STOP) {
            from_stop = true;
            seq = 0;
        } else if (sm.state != QFOC_STATE_RUN) {
            from_stop = false;
            seq = 0;
        } else if (from_stop && (sm.sub == QFOC_SUB_CATCH) && ((seq <= 1) || (seq == 3))) {
            seq = 1;   /* the RUN entry, or a retry after OPEN_LOOP */
        } else if (from_stop && (sm.sub == QFOC_SUB_ALIGN) && (seq == 1 || seq == 2)) {
            seq = 2;
        } else if (from_stop && (sm.sub == QFOC_SUB_OPEN_LOOP) && (seq == 2 || seq == 3)) {
            seq = 3;
        } else if (from_stop && (sm.sub == QFOC_SUB_CLOSED_LOOP) && (seq == 1)) {
            seq = 4;
        } else {
            /* CLOSED_LOOP or STOPPING after the start: the order is already checked */
        }
        if (from_stop && (sm.state == QFOC_STATE_RUN)) {
            __CPROVER_assert(seq >= 1, "REQ-SM-005 RUN from STOP starts in CATCH");
        }
        if (from_stop && (sm.sub == QFOC_SUB_CLOSED_LOOP)) {
            __CPROVER_assert(seq == 3 || seq == 4,
                             "REQ-SM-006 REQ-SM-010 CLOSED_LOOP only through CATCH (caught) or "
                             "CATCH, ALIGN and OPEN_LOOP");
        }
    }
    return 0;
}
