/**
 * @file qfoc_sm.c
 * @brief The drive state machine (sm.h): PRECHARGE, STOP, RUN, ERROR.
 */
#include "qfoc/sm.h"

/** Largest value of a state time (ticks). */
#define SM_T_MAX ((uint16_t)65535u)
/** The parameter-table fault bit (fault.h QFOC_FAULT_PARAM). */
#define SM_FAULT_PARAM ((uint16_t)0x0200u)

/*@
  assigns \nothing;
  ensures result: \result == SmTick(t);
*/
static uint16_t sm_tick_time(uint16_t t)
{
    uint16_t r = SM_T_MAX;
    if (t < SM_T_MAX) {
        r = (uint16_t)(t + 1u);
    } else {
        /* saturated */
    }
    return r;
}

/*@
  requires valid_sm: \valid_read(sm);
  assigns \nothing;
  ensures result: \result <==> SmSubOk(sm->state, sm->sub);
*/
static bool sm_sub_ok(const qfoc_sm_t *sm)
{
    const uint8_t st = sm->state;
    const uint8_t sub = sm->sub;
    bool ok = false;
    if (st == QFOC_STATE_PRECHARGE) {
        ok = (sub == QFOC_SUB_BUS_WAIT) || (sub == QFOC_SUB_CALIB);
    } else if (st == QFOC_STATE_RUN) {
        ok = (sub >= QFOC_SUB_ALIGN) && (sub <= QFOC_SUB_CATCH);
    } else if ((st == QFOC_STATE_STOP) || (st == QFOC_STATE_ERROR)) {
        ok = (sub == QFOC_SUB_NONE);
    } else {
        /* undefined state */
    }
    return ok;
}

bool qfoc_sm_is_valid(const qfoc_sm_t *sm)
{
    const bool sub_ok = sm_sub_ok(sm);
    const bool in_error = (sm->state == QFOC_STATE_ERROR);
    const bool bits_ok = (sm->faults <= QFOC_SM_FAULT_ALL);
    bool first_ok;
    if (in_error) {
        first_ok = (sm->faults != 0u) && (sm->first_fault != 0u) &&
                   (sm->first_fault <= QFOC_SM_FAULT_ALL);
    } else {
        first_ok = (sm->faults == 0u) && (sm->first_fault == 0u);
    }
    return sub_ok && bits_ok && first_ok;
}

void qfoc_sm_init(qfoc_sm_t *sm)
{
    sm->state = QFOC_STATE_PRECHARGE;
    sm->sub = QFOC_SUB_BUS_WAIT;
    sm->faults = 0u;
    sm->first_fault = 0u;
    sm->t_state = 0u;
    sm->t_sub = 0u;
    sm->retry = 0u;
}

/*@
  requires valid_sm: \valid(sm);
  requires ok: SmSubOk(state, sub);
  assigns sm->state, sm->sub, sm->t_state, sm->t_sub;
  ensures state: sm->state == state && sm->sub == sub;
  ensures times: sm->t_state == 0 && sm->t_sub == 0;
*/
static void sm_enter(qfoc_sm_t *sm, uint8_t state, uint8_t sub)
{
    sm->state = state;
    sm->sub = sub;
    sm->t_state = 0u;
    sm->t_sub = 0u;
}

/*@
  requires valid_sm: \valid(sm);
  requires ok: SmSubOk(sm->state, sub);
  assigns sm->sub, sm->t_sub;
  ensures sub: sm->sub == sub && sm->t_sub == 0;
*/
static void sm_enter_sub(qfoc_sm_t *sm, uint8_t sub)
{
    sm->sub = sub;
    sm->t_sub = 0u;
}

/*@
  requires valid_sm: \valid(sm);
  requires cause: 0 < faults <= QFOC_SM_FAULT_ALL;
  assigns *sm;
  ensures error: sm->state == QFOC_STATE_ERROR && sm->sub == QFOC_SUB_NONE;
  ensures word: sm->faults == faults && sm->first_fault == faults;
  ensures times: sm->t_state == 0 && sm->t_sub == 0;
*/
static void sm_enter_error(qfoc_sm_t *sm, uint16_t faults)
{
    sm_enter(sm, QFOC_STATE_ERROR, QFOC_SUB_NONE);
    sm->faults = faults;
    sm->first_fault = faults;
}

void qfoc_sm_fail(qfoc_sm_t *sm, uint16_t faults)
{
    uint16_t f = (uint16_t)(faults % 2048u);
    if (f == 0u) {
        f = SM_FAULT_PARAM;
    } else {
        /* a cause given */
    }
    if (sm->state == QFOC_STATE_ERROR) {
        /* already latched: the word keeps its cause, the clear time restarts */
        sm->t_state = 0u;
        sm->t_sub = 0u;
    } else {
        sm_enter_error(sm, f);
    }
}

/* ------------------------------------------------------------------ per-state rules */

/*@
  requires valid: \valid(sm) && \valid_read(cfg) && \valid_read(in);
  requires sep: \separated(sm, cfg, in);
  requires inv: SmValid(sm) && sm->state == QFOC_STATE_ERROR;
  requires clean: SmMask(in->faults) == 0;
  assigns *sm;
  ensures inv: SmValid(sm);
  ensures not_running: sm->sub == QFOC_SUB_NONE;
  ensures exit: sm->state != QFOC_STATE_ERROR ==>
      sm->state == QFOC_STATE_STOP && in->fault_clear && in->table_ok &&
      sm->t_state == 0 && \old(sm->t_state) >= cfg->clear_ms;
  ensures stay: sm->state == QFOC_STATE_ERROR ==> sm->faults == \old(sm->faults) &&
      sm->first_fault == \old(sm->first_fault) &&
      sm->t_state == \old(sm->t_state) && sm->sub == QFOC_SUB_NONE;
*/
static void sm_error_rule(qfoc_sm_t *sm, const qfoc_sm_cfg_t *cfg, const qfoc_sm_in_t *in)
{
    if ((sm->t_state >= cfg->clear_ms) && in->fault_clear && in->table_ok) {
        sm_enter(sm, QFOC_STATE_STOP, QFOC_SUB_NONE);
        sm->faults = 0u;
        sm->first_fault = 0u;
    } else {
        /* stay latched */
    }
}

/*@
  requires valid: \valid(sm) && \valid_read(cfg) && \valid_read(in);
  requires sep: \separated(sm, cfg, in);
  requires inv: SmValid(sm) && sm->state == QFOC_STATE_PRECHARGE;
  assigns sm->state, sm->sub, sm->t_state, sm->t_sub;
  ensures inv: SmValid(sm);
  ensures where: sm->state == QFOC_STATE_PRECHARGE || sm->state == QFOC_STATE_STOP;
  ensures not_running: sm->sub != QFOC_SUB_CLOSED_LOOP;
  ensures stop_entry: sm->state == QFOC_STATE_STOP ==>
      in->calib_done && in->bus_ok && \old(sm->sub) == QFOC_SUB_CALIB && sm->t_state == 0;
  ensures calib_entry: sm->sub == QFOC_SUB_CALIB && \old(sm->sub) == QFOC_SUB_BUS_WAIT ==>
      in->bus_ok && \old(sm->t_sub) >= cfg->precharge_ms;
*/
static void sm_precharge_rule(qfoc_sm_t *sm, const qfoc_sm_cfg_t *cfg, const qfoc_sm_in_t *in)
{
    if (!in->bus_ok) {
        sm_enter_sub(sm, QFOC_SUB_BUS_WAIT);
    } else if (sm->sub == QFOC_SUB_BUS_WAIT) {
        if (sm->t_sub >= cfg->precharge_ms) {
            sm_enter_sub(sm, QFOC_SUB_CALIB);
        } else {
            /* settling */
        }
    } else if (in->calib_done) {
        sm_enter(sm, QFOC_STATE_STOP, QFOC_SUB_NONE);
    } else {
        /* calibrating */
    }
}

/*@
  requires valid: \valid(sm) && \valid_read(in);
  requires sep: \separated(sm, in);
  requires inv: SmValid(sm) && sm->state == QFOC_STATE_STOP;
  assigns sm->state, sm->sub, sm->t_state, sm->t_sub, sm->retry;
  ensures inv: SmValid(sm);
  ensures run_entry: sm->state == QFOC_STATE_RUN ==>
      in->run_request && sm->sub == QFOC_SUB_CATCH && sm->t_state == 0 && sm->retry == 0;
  ensures where: sm->state == QFOC_STATE_STOP || sm->state == QFOC_STATE_RUN ||
      (sm->state == QFOC_STATE_PRECHARGE && sm->sub == QFOC_SUB_BUS_WAIT);
  ensures not_running: sm->sub != QFOC_SUB_CLOSED_LOOP;
*/
static void sm_stop_rule(qfoc_sm_t *sm, const qfoc_sm_in_t *in)
{
    if (!in->bus_ok || !in->calib_done) {
        sm_enter(sm, QFOC_STATE_PRECHARGE, QFOC_SUB_BUS_WAIT);
    } else if (in->run_request) {
        sm_enter(sm, QFOC_STATE_RUN, QFOC_SUB_CATCH);
        sm->retry = 0u;
    } else {
        /* ready */
    }
}

/* RUN / CATCH (REQ-DRV-027): stop without a run request; closed loop at the caught speed;
   the normal start (ALIGN, timed as from a RUN entry) for a standing rotor; else wait. */
/*@
  requires valid: \valid(sm) && \valid_read(in);
  requires sep: \separated(sm, in);
  requires inv: SmValid(sm) && sm->state == QFOC_STATE_RUN && sm->sub == QFOC_SUB_CATCH;
  assigns sm->state, sm->sub, sm->t_state, sm->t_sub;
  ensures inv: SmValid(sm);
  ensures to_stop: sm->state == QFOC_STATE_STOP ==> sm->t_state == 0 && !in->run_request;
  ensures in_run: sm->state == QFOC_STATE_RUN ==>
      (sm->sub == QFOC_SUB_CATCH && sm->t_state == \old(sm->t_state)) ||
      (sm->sub == QFOC_SUB_CLOSED_LOOP && in->catch_lock) ||
      (sm->sub == QFOC_SUB_ALIGN && in->catch_still && !in->catch_lock && sm->t_state == 0);
  ensures where: sm->state == QFOC_STATE_RUN || sm->state == QFOC_STATE_STOP;
*/
static void sm_catch_rule(qfoc_sm_t *sm, const qfoc_sm_in_t *in)
{
    if (!in->run_request) {
        sm_enter(sm, QFOC_STATE_STOP, QFOC_SUB_NONE);
    } else if (in->catch_lock) {
        sm_enter_sub(sm, QFOC_SUB_CLOSED_LOOP);   /* caught at its speed */
    } else if (in->catch_still) {
        /* standing: the normal start, timed from here as from a RUN entry */
        sm_enter(sm, QFOC_STATE_RUN, QFOC_SUB_ALIGN);
    } else {
        /* looking, or waiting for a rotor that cannot be caught to coast down */
    }
}

/* RUN / OPEN_LOOP (REQ-SM-011): stop without a run request; the handover once converged
   after cl_hold_ms; after ol_timeout_ms without it, with a retry left (sm_faults raises
   STALL on the last), CATCH again (coasting down, or standing for a new ALIGN) and the
   next I/f start. */
/*@
  requires valid: \valid(sm) && \valid_read(cfg) && \valid_read(in);
  requires sep: \separated(sm, cfg, in);
  requires inv: SmValid(sm) && sm->state == QFOC_STATE_RUN && sm->sub == QFOC_SUB_OPEN_LOOP;
  requires no_stall: sm->t_sub >= cfg->ol_timeout_ms ==> sm->retry < cfg->retries;
  assigns sm->state, sm->sub, sm->t_state, sm->t_sub, sm->retry;
  ensures inv: SmValid(sm);
  ensures where: sm->state == QFOC_STATE_RUN || sm->state == QFOC_STATE_STOP;
  ensures to_stop: sm->state == QFOC_STATE_STOP ==> sm->t_state == 0 && !in->run_request;
  ensures in_run: sm->state == QFOC_STATE_RUN ==> sm->t_state == \old(sm->t_state) &&
      (sm->sub == QFOC_SUB_OPEN_LOOP || sm->sub == QFOC_SUB_CLOSED_LOOP ||
       sm->sub == QFOC_SUB_CATCH);
  ensures to_closed_loop: sm->sub == QFOC_SUB_CLOSED_LOOP ==>
      in->converged && \old(sm->t_state) >= cfg->cl_hold_ms;
  ensures retry: sm->sub == QFOC_SUB_CATCH ==>
      \old(sm->t_sub) >= cfg->ol_timeout_ms && \old(sm->retry) < cfg->retries &&
      sm->retry == \old(sm->retry) + 1 && sm->t_sub == 0;
  ensures retry_kept: sm->sub != QFOC_SUB_CATCH ==> sm->retry == \old(sm->retry);
*/
static void sm_open_loop_rule(qfoc_sm_t *sm, const qfoc_sm_cfg_t *cfg, const qfoc_sm_in_t *in)
{
    if (!in->run_request) {
        sm_enter(sm, QFOC_STATE_STOP, QFOC_SUB_NONE);
    } else if (in->converged && (sm->t_state >= cfg->cl_hold_ms)) {
        sm_enter_sub(sm, QFOC_SUB_CLOSED_LOOP);
    } else if (sm->t_sub >= cfg->ol_timeout_ms) {
        sm_enter_sub(sm, QFOC_SUB_CATCH);
        sm->retry = (uint8_t)(sm->retry + 1u);
    } else {
        /* accelerating, waiting for the observer */
    }
}

/*@
  requires valid: \valid(sm) && \valid_read(cfg) && \valid_read(in);
  requires sep: \separated(sm, cfg, in);
  requires inv: SmValid(sm) && sm->state == QFOC_STATE_RUN;
  requires no_stall: sm->sub == QFOC_SUB_OPEN_LOOP && sm->t_sub >= cfg->ol_timeout_ms ==>
      sm->retry < cfg->retries;
  assigns sm->state, sm->sub, sm->t_state, sm->t_sub, sm->retry;
  ensures inv: SmValid(sm);
  ensures where: sm->state == QFOC_STATE_RUN || sm->state == QFOC_STATE_STOP;
  ensures to_stop: sm->state == QFOC_STATE_STOP ==> sm->t_state == 0 &&
      ((\old(sm->sub) == QFOC_SUB_STOPPING && in->stop_reached) ||
       ((\old(sm->sub) == QFOC_SUB_ALIGN || \old(sm->sub) == QFOC_SUB_OPEN_LOOP ||
         \old(sm->sub) == QFOC_SUB_CATCH) && !in->run_request));
  ensures to_open_loop: sm->sub == QFOC_SUB_OPEN_LOOP && \old(sm->sub) != QFOC_SUB_OPEN_LOOP ==>
      \old(sm->sub) == QFOC_SUB_ALIGN && \old(sm->t_sub) >= cfg->align_ms;
  ensures to_closed_loop: sm->sub == QFOC_SUB_CLOSED_LOOP && \old(sm->sub) == QFOC_SUB_OPEN_LOOP ==>
      in->converged && \old(sm->t_state) >= cfg->cl_hold_ms;
  ensures to_caught: sm->sub == QFOC_SUB_CLOSED_LOOP && \old(sm->sub) == QFOC_SUB_CATCH ==>
      in->catch_lock;
  ensures closed_loop_origin: sm->sub == QFOC_SUB_CLOSED_LOOP ==>
      \old(sm->sub) == QFOC_SUB_OPEN_LOOP || \old(sm->sub) == QFOC_SUB_CLOSED_LOOP ||
      \old(sm->sub) == QFOC_SUB_STOPPING || \old(sm->sub) == QFOC_SUB_CATCH;
  ensures stopping_origin: sm->sub == QFOC_SUB_STOPPING ==>
      \old(sm->sub) == QFOC_SUB_CLOSED_LOOP || \old(sm->sub) == QFOC_SUB_STOPPING;
  ensures align_origin: sm->state == QFOC_STATE_RUN && sm->sub == QFOC_SUB_ALIGN ==>
      \old(sm->sub) == QFOC_SUB_ALIGN ||
      (\old(sm->sub) == QFOC_SUB_CATCH && in->catch_still && !in->catch_lock);
  ensures catch_origin: sm->state == QFOC_STATE_RUN && sm->sub == QFOC_SUB_CATCH ==>
      \old(sm->sub) == QFOC_SUB_CATCH || \old(sm->sub) == QFOC_SUB_OPEN_LOOP;
  ensures retry: \old(sm->sub) == QFOC_SUB_OPEN_LOOP && sm->sub == QFOC_SUB_CATCH ==>
      \old(sm->t_sub) >= cfg->ol_timeout_ms && \old(sm->retry) < cfg->retries &&
      sm->retry == \old(sm->retry) + 1 && sm->t_sub == 0;
  ensures retry_kept: !(\old(sm->sub) == QFOC_SUB_OPEN_LOOP && sm->sub == QFOC_SUB_CATCH) ==>
      sm->retry == \old(sm->retry);
  ensures time: sm->state == QFOC_STATE_RUN && \old(sm->sub) != QFOC_SUB_CATCH ==>
      sm->t_state == \old(sm->t_state);
  ensures align_time: sm->sub == QFOC_SUB_ALIGN && \old(sm->sub) == QFOC_SUB_CATCH ==>
      sm->t_state == 0;
*/
static void sm_run_rule(qfoc_sm_t *sm, const qfoc_sm_cfg_t *cfg, const qfoc_sm_in_t *in)
{
    const uint8_t sub = sm->sub;
    const bool run = in->run_request;
    const bool stop_reached = in->stop_reached;
    const bool aligned = (sm->t_sub >= cfg->align_ms);
    if (sub == QFOC_SUB_CATCH) {
        sm_catch_rule(sm, in);
    } else if (sub == QFOC_SUB_OPEN_LOOP) {
        sm_open_loop_rule(sm, cfg, in);
    } else if (sub == QFOC_SUB_ALIGN) {
        if (!run) {
            sm_enter(sm, QFOC_STATE_STOP, QFOC_SUB_NONE);
        } else if (aligned) {
            sm_enter_sub(sm, QFOC_SUB_OPEN_LOOP);
        } else {
            /* aligning */
        }
    } else if (sub == QFOC_SUB_CLOSED_LOOP) {
        if (!run) {
            sm_enter_sub(sm, QFOC_SUB_STOPPING);
        } else {
            /* speed control */
        }
    } else {
        /* STOPPING */
        if (stop_reached) {
            sm_enter(sm, QFOC_STATE_STOP, QFOC_SUB_NONE);
        } else if (run) {
            sm_enter_sub(sm, QFOC_SUB_CLOSED_LOOP);
        } else {
            /* ramping down */
        }
    }
}

/* Set one bit of a fault word (arithmetic form of w | bit, which the provers
   bound directly). */
/*@
  requires word: w <= QFOC_SM_FAULT_ALL;
  requires bit: bit == QFOC_SM_FAULT_STALL || bit == QFOC_SM_FAULT_LINK;
  assigns \nothing;
  ensures bits: w <= \result <= QFOC_SM_FAULT_ALL;
  ensures set: \result >= 1;
*/
static uint16_t sm_set_bit(uint16_t w, uint16_t bit)
{
    uint16_t r = w;
    if (((w / bit) % 2u) == 0u) {
        r = (uint16_t)(w + bit);
    } else {
        /* already set */
    }
    return r;
}

/*@
  requires valid: \valid_read(sm) && \valid_read(cfg) && \valid_read(in);
  requires inv: SmValid(sm) && sm->state != QFOC_STATE_ERROR;
  assigns \nothing;
  ensures bits: \result <= QFOC_SM_FAULT_ALL;
  ensures drive: SmMask(in->faults) <= \result;
  ensures none: \result == 0 ==> SmMask(in->faults) == 0;
  ensures retry_left: \result == 0 && sm->state == QFOC_STATE_RUN &&
      sm->sub == QFOC_SUB_OPEN_LOOP && sm->t_sub >= cfg->ol_timeout_ms ==>
      sm->retry < cfg->retries;
*/
static uint16_t sm_faults(const qfoc_sm_t *sm, const qfoc_sm_cfg_t *cfg, const qfoc_sm_in_t *in)
{
    uint16_t f = (uint16_t)(in->faults % 2048u);
    const bool open_loop = (sm->state == QFOC_STATE_RUN) &&
                           ((sm->sub == QFOC_SUB_OPEN_LOOP) || (sm->sub == QFOC_SUB_CATCH));
    const bool early = (sm->state == QFOC_STATE_RUN) &&
                       ((sm->sub == QFOC_SUB_ALIGN) || (sm->sub == QFOC_SUB_OPEN_LOOP) ||
                        (sm->sub == QFOC_SUB_CATCH));
    const bool stopped = (sm->state == QFOC_STATE_RUN) && (sm->sub == QFOC_SUB_STOPPING) &&
                         in->stop_reached;
    /* CATCH without a verdict, or OPEN_LOOP without a handover and no retry left */
    if (open_loop && (sm->t_sub >= cfg->ol_timeout_ms) &&
        ((sm->sub == QFOC_SUB_CATCH) || (sm->retry >= cfg->retries))) {
        f = sm_set_bit(f, QFOC_SM_FAULT_STALL);
    } else {
        /* no open-loop timeout */
    }
    if (in->link_lost && (early || stopped)) {
        f = sm_set_bit(f, QFOC_SM_FAULT_LINK);
    } else {
        /* link alive, or not running */
    }
    return f;
}

void qfoc_sm_step(qfoc_sm_t *sm, const qfoc_sm_cfg_t *cfg, const qfoc_sm_in_t *in)
{
    const uint16_t drive_faults = (uint16_t)(in->faults % 2048u);
    sm->t_state = sm_tick_time(sm->t_state);
    sm->t_sub = sm_tick_time(sm->t_sub);
    if (sm->state == QFOC_STATE_ERROR) {
        if (drive_faults == 0u) {
            sm_error_rule(sm, cfg, in);
        } else {
            /* a fault is still present: no clear in this tick */
        }
    } else {
        const uint16_t f = sm_faults(sm, cfg, in);
        if (f != 0u) {
            sm_enter_error(sm, f);
        } else if (sm->state == QFOC_STATE_PRECHARGE) {
            sm_precharge_rule(sm, cfg, in);
        } else if (sm->state == QFOC_STATE_STOP) {
            sm_stop_rule(sm, in);
        } else {
            sm_run_rule(sm, cfg, in);
        }
    }
}
