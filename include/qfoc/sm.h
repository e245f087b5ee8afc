/**
 * @file sm.h
 * @brief The compressor drive's state machine (PRECHARGE, RUN, STOP,
 *        ERROR; specs/equations.md section 8.3), as a pure transition function
 *        evaluated once per 1 ms tick.
 *
 * The drive (drive.h) measures, detects faults and evaluates the handover and stop
 * conditions; this unit decides the state from them, and owns the state times.  Keeping
 * the rules here, apart from the signal processing, lets each rule be stated as a
 * contract clause and proved, and lets CBMC run the state machine over long horizons.
 *
 * States and sub-states (specs/requirements/sm.md gives every transition an ID):
 *
 *   PRECHARGE  BUS_WAIT -> CALIB        PWM off; wait for the DC bus above its
 *                                       under-voltage threshold for precharge_ms, then
 *                                       calibrate the current-sensor offsets
 *   STOP       NONE                     PWM off, ready; leaves on a run request; back
 *                                       to PRECHARGE when the bus drops or the offsets
 *                                       are not calibrated (after an OFFSET fault)
 *   RUN        CATCH -> ALIGN -> OPEN_LOOP -> CLOSED_LOOP <-> STOPPING
 *              CATCH -> CLOSED_LOOP     CATCH: zero-current control, the observer
 *                                       looks for a coasting rotor (flying start,
 *                                       catch.h): caught, to CLOSED_LOOP at its speed;
 *                                       standing, to ALIGN (the state time
 *                                       restarts: the start is timed from ALIGN);
 *                                       else it waits;
 *                                       ALIGN: fixed angle, d-current ramp
 *                                       (formerly park); OPEN_LOOP: I/f start,
 *                                       back to CATCH after ol_timeout_ms
 *                                       without a handover while start retries
 *                                       are left (cfg->retries; the count
 *                                       `retry` is 0 at the RUN entry and the
 *                                       state time runs on, REQ-SM-011);
 *                                       CLOSED_LOOP: sensorless speed control;
 *                                       STOPPING: speed ramp down, then STOP
 *   ERROR      NONE                     PWM off; faults latched; left only after
 *                                       clear_ms in ERROR and a fault-clear request
 *
 * Transition rules, evaluated in this order in one step (times count whole ticks):
 *  1. The state and sub-state times advance by one tick (saturating at 65535).
 *  2. Outside ERROR, the faults of this tick are collected: the drive's (in->faults),
 *     plus STALL when OPEN_LOOP has lasted ol_timeout_ms without a handover and no
 *     start retry is left, or CATCH as long without a verdict, plus LINK
 *     when the command link is lost in CATCH, ALIGN or OPEN_LOOP, or when a stop caused by the
 *     lost link completes.  Any fault: ERROR, the fault word and the first-fault record
 *     are the faults of this tick (REQ-SM-002).
 *  3. In ERROR the fault word keeps the faults that caused it (a fault still present
 *     refuses the clear, it is not added); the state is left, to STOP, only when
 *     the state time has reached clear_ms, the fault-clear request is present, no fault
 *     was detected in this tick, and the parameter table is intact; the fault word and
 *     the first-fault record are then cleared (formerly Faultclear, REQ-SM-003).
 *  4. Otherwise the state's own rule applies (REQ-SM-004 .. REQ-SM-011).
 * A transition sets both times to 0, but the handover (CLOSED_LOOP from OPEN_LOOP or
 * CATCH) and a start retry (CATCH from OPEN_LOOP) keep the state time running.
 *
 * Requirements: REQ-SM-001 .. REQ-SM-011.
 */
#ifndef QFOC_SM_H
#define QFOC_SM_H

#include "qfoc/types.h"
#include "qfoc/fault.h"

#ifdef __cplusplus
extern "C" {
#endif

/* States (the four of specs/equations.md section 8.3). */
#define QFOC_STATE_PRECHARGE ((uint8_t)0u)  /**< PWM off: DC bus settling, then the offset calibration */
#define QFOC_STATE_STOP      ((uint8_t)1u)  /**< PWM off, ready: left on a run request */
#define QFOC_STATE_RUN       ((uint8_t)2u)  /**< the motor driven: sub-states CATCH .. STOPPING */
#define QFOC_STATE_ERROR     ((uint8_t)3u)  /**< PWM off, faults latched until a fault clear */

/** Sub-states (one code space). */
#define QFOC_SUB_NONE        ((uint8_t)0u)  /**< STOP, ERROR */
#define QFOC_SUB_BUS_WAIT    ((uint8_t)1u)  /**< PRECHARGE: DC bus settling */
#define QFOC_SUB_CALIB       ((uint8_t)2u)  /**< PRECHARGE: current-offset calibration */
#define QFOC_SUB_ALIGN       ((uint8_t)3u)  /**< RUN: rotor alignment */
#define QFOC_SUB_OPEN_LOOP   ((uint8_t)4u)  /**< RUN: I/f open-loop acceleration */
#define QFOC_SUB_CLOSED_LOOP ((uint8_t)5u)  /**< RUN: sensorless speed control */
#define QFOC_SUB_STOPPING    ((uint8_t)6u)  /**< RUN: ramp down before STOP */
#define QFOC_SUB_CATCH       ((uint8_t)7u)  /**< RUN: flying-start detection (catch.h) */

/* Fault bits raised by the state machine itself (the fault word of fault.h). */
#define QFOC_SM_FAULT_STALL QFOC_FAULT_STALL  /**< OPEN_LOOP or CATCH for ol_timeout_ms without a
                                                   handover or a verdict, no start retry left */
#define QFOC_SM_FAULT_LINK  QFOC_FAULT_LINK   /**< command link lost in CATCH, ALIGN or OPEN_LOOP, or
                                                   a stop for a lost link completed */
/** Every defined fault bit. */
#define QFOC_SM_FAULT_ALL   QFOC_FAULT_ALL

/** Times of the state machine, ms (from the parameter table, drive_cfg.h). */
typedef struct {
    uint16_t precharge_ms;   /**< DC bus above the UV threshold this long: CALIB */
    uint16_t align_ms;       /**< ALIGN duration */
    uint16_t ol_timeout_ms;  /**< OPEN_LOOP without handover this long: STALL */
    uint16_t cl_hold_ms;     /**< no handover before this long after the ALIGN entry (2 s; 0: at convergence) */
    uint16_t clear_ms;       /**< ERROR this long before a clear is accepted (5 s) */
    uint8_t retries;         /**< OPEN_LOOP timeouts retried through CATCH before STALL */
} qfoc_sm_cfg_t;

/** What the drive evaluated in this tick. */
typedef struct {
    uint16_t faults;     /**< fault bits detected in this tick (fault.h) */
    bool bus_ok;         /**< filtered DC bus at or above the UV threshold */
    bool calib_done;     /**< the offset calibration has finished in range */
    bool run_request;    /**< power-on with a valid target speed, link alive */
    bool link_lost;      /**< no valid command frame for the link timeout */
    bool fault_clear;    /**< fault-clear request of the command link */
    bool table_ok;       /**< the parameter table passed its last check */
    bool converged;      /**< the handover condition has held for its dwell time */
    bool stop_reached;   /**< STOPPING: the speed reference is down at the stop speed */
    bool catch_lock;     /**< CATCH: a coasting rotor caught, its speed measured (catch.h) */
    bool catch_still;    /**< CATCH: the rotor stands (its back-EMF below the error bound) */
} qfoc_sm_in_t;

/** State of the machine. */
typedef struct {
    uint8_t state;        /**< QFOC_STATE_* */
    uint8_t sub;          /**< QFOC_SUB_* consistent with state (SmValid) */
    uint16_t faults;      /**< latched fault word (non-zero exactly in ERROR) */
    uint16_t first_fault; /**< faults of the tick that entered ERROR (0 outside ERROR) */
    uint16_t t_state;     /**< ticks since the state was entered, saturating */
    uint16_t t_sub;       /**< ticks since the sub-state was entered, saturating */
    uint8_t retry;        /**< start retries taken since the RUN entry (REQ-SM-011) */
} qfoc_sm_t;

#ifdef __FRAMAC__
/* ACSL predicates over the types above, read by Frama-C only (DEV-001). */
/* cppcheck-suppress misra-c2012-20.1 ; DEV-001 */
#include "sm.acsl"
#endif

/**
 * @brief Check the state-machine invariant (the logic twin of SmValid).
 * @param[in] sm state machine (any bit pattern)
 * @return true iff the state is one of the four, the sub-state belongs to it
 *         (PRECHARGE: BUS_WAIT or CALIB; RUN: ALIGN, OPEN_LOOP, CLOSED_LOOP, STOPPING or
 *         CATCH;
 *         STOP and ERROR: NONE), the fault word has only defined bits and is non-zero
 *         exactly in ERROR, and first_fault is non-zero with defined bits only in
 *         ERROR and 0 elsewhere.
 * Requirements: REQ-SM-001.
 */
/*@
  requires valid_sm: \valid_read(sm);
  assigns \nothing;
  ensures result: \result <==> SmValid(sm);
*/
bool qfoc_sm_is_valid(const qfoc_sm_t *sm);

/**
 * @brief Power-on state: PRECHARGE / BUS_WAIT, no fault, times 0.  When the
 *        parameter table failed its check, the drive calls qfoc_sm_fail() next.
 * @param[out] sm state machine
 * Requirements: REQ-SM-001.
 */
/*@
  requires valid_sm: \valid(sm);
  assigns *sm;
  ensures valid: SmValid(sm);
  ensures state: sm->state == QFOC_STATE_PRECHARGE && sm->sub == QFOC_SUB_BUS_WAIT;
  ensures clean: sm->faults == 0 && sm->t_state == 0 && sm->t_sub == 0 && sm->retry == 0;
*/
void qfoc_sm_init(qfoc_sm_t *sm);

/**
 * @brief Enter ERROR at once with the given faults (used outside the tick: a
 *        parameter table refused at initialisation).
 * @param[in,out] sm     valid state machine
 * @param[in]     faults fault bits; undefined bits are dropped; 0 is replaced by
 *                       the PARAM bit (0x0200) so ERROR always has a cause.  Already in
 *                       ERROR: the word keeps its cause and the clear time restarts.
 * Requirements: REQ-SM-002.
 */
/*@
  requires valid_sm: \valid(sm);
  requires inv: SmValid(sm);
  assigns *sm;
  ensures valid: SmValid(sm);
  ensures error: sm->state == QFOC_STATE_ERROR && sm->t_state == 0;
*/
void qfoc_sm_fail(qfoc_sm_t *sm, uint16_t faults);

/**
 * @brief One tick of the state machine (rules in the file comment).
 * @param[in,out] sm  valid state machine
 * @param[in]     cfg times (any values; 0 means "at once")
 * @param[in]     in  this tick's evaluated conditions (any values; undefined fault bits
 *                    are ignored)
 * Contract clauses: fault_to_error (REQ-SM-002); error_exit, error_latched
 * (REQ-SM-003); stop_entry (REQ-SM-004); run_entry (REQ-SM-005); to_open_loop,
 * to_closed_loop, closed_loop_origin, stopping_origin (REQ-SM-006, REQ-SM-007);
 * to_align, to_caught, catch_origin (REQ-SM-010); retry, retry_kept (REQ-SM-011).
 * Requirements: REQ-SM-002 .. REQ-SM-011.
 */
/*@
  requires valid: \valid(sm) && \valid_read(cfg) && \valid_read(in);
  requires sep: \separated(sm, cfg, in);
  requires inv: SmValid(sm);
  assigns *sm;
  ensures inv: SmValid(sm);
  ensures fault_to_error: \old(sm->state) != QFOC_STATE_ERROR &&
      SmMask(in->faults) != 0 ==>
      sm->state == QFOC_STATE_ERROR && sm->t_state == 0 &&
      sm->faults == sm->first_fault && SmMask(in->faults) <= sm->faults;
  ensures error_exit: \old(sm->state) == QFOC_STATE_ERROR && sm->state != QFOC_STATE_ERROR ==>
      sm->state == QFOC_STATE_STOP && in->fault_clear && in->table_ok &&
      SmMask(in->faults) == 0 && SmTick(\old(sm->t_state)) >= cfg->clear_ms;
  ensures error_latched: \old(sm->state) == QFOC_STATE_ERROR && sm->state == QFOC_STATE_ERROR ==>
      sm->faults == \old(sm->faults) && sm->first_fault == \old(sm->first_fault);
  ensures run_entry: \old(sm->state) != QFOC_STATE_RUN && sm->state == QFOC_STATE_RUN ==>
      \old(sm->state) == QFOC_STATE_STOP && in->run_request && sm->sub == QFOC_SUB_CATCH &&
      sm->retry == 0;
  ensures to_align: sm->sub == QFOC_SUB_ALIGN && \old(sm->sub) != QFOC_SUB_ALIGN ==>
      \old(sm->sub) == QFOC_SUB_CATCH && in->catch_still && !in->catch_lock &&
      sm->t_state == 0;
  ensures to_caught: sm->sub == QFOC_SUB_CLOSED_LOOP && \old(sm->sub) == QFOC_SUB_CATCH ==>
      in->catch_lock;
  ensures catch_origin: sm->state == QFOC_STATE_RUN && sm->sub == QFOC_SUB_CATCH ==>
      \old(sm->state) == QFOC_STATE_STOP ||
      (\old(sm->state) == QFOC_STATE_RUN && \old(sm->sub) == QFOC_SUB_CATCH) ||
      (\old(sm->state) == QFOC_STATE_RUN && \old(sm->sub) == QFOC_SUB_OPEN_LOOP);
  ensures retry: \old(sm->state) == QFOC_STATE_RUN && \old(sm->sub) == QFOC_SUB_OPEN_LOOP &&
      sm->sub == QFOC_SUB_CATCH ==>
      SmTick(\old(sm->t_sub)) >= cfg->ol_timeout_ms && \old(sm->retry) < cfg->retries &&
      sm->retry == \old(sm->retry) + 1 && sm->t_sub == 0 &&
      sm->t_state == SmTick(\old(sm->t_state));
  ensures retry_kept: \old(sm->state) == QFOC_STATE_RUN && sm->state == QFOC_STATE_RUN &&
      !(\old(sm->sub) == QFOC_SUB_OPEN_LOOP && sm->sub == QFOC_SUB_CATCH) ==>
      sm->retry == \old(sm->retry);
  ensures to_open_loop: sm->sub == QFOC_SUB_OPEN_LOOP && \old(sm->sub) != QFOC_SUB_OPEN_LOOP ==>
      \old(sm->sub) == QFOC_SUB_ALIGN && SmTick(\old(sm->t_sub)) >= cfg->align_ms;
  ensures to_closed_loop: sm->sub == QFOC_SUB_CLOSED_LOOP && \old(sm->sub) == QFOC_SUB_OPEN_LOOP ==>
      in->converged && SmTick(\old(sm->t_state)) >= cfg->cl_hold_ms;
  ensures closed_loop_origin: sm->sub == QFOC_SUB_CLOSED_LOOP ==>
      \old(sm->sub) == QFOC_SUB_OPEN_LOOP || \old(sm->sub) == QFOC_SUB_CLOSED_LOOP ||
      \old(sm->sub) == QFOC_SUB_STOPPING || \old(sm->sub) == QFOC_SUB_CATCH;
  ensures stopping_origin: sm->sub == QFOC_SUB_STOPPING ==>
      \old(sm->sub) == QFOC_SUB_CLOSED_LOOP || \old(sm->sub) == QFOC_SUB_STOPPING;
  ensures stop_entry: sm->state == QFOC_STATE_STOP && \old(sm->state) == QFOC_STATE_PRECHARGE ==>
      in->calib_done && in->bus_ok && \old(sm->sub) == QFOC_SUB_CALIB;
*/
void qfoc_sm_step(qfoc_sm_t *sm, const qfoc_sm_cfg_t *cfg, const qfoc_sm_in_t *in);

#ifdef __cplusplus
}
#endif

#endif /* QFOC_SM_H */
