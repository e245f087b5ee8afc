/**
 * @file fault.h
 * @brief Fault-detection primitives: the fault word, a debounce counter, the
 *        phase-loss monitor and threshold compares.
 *
 * The drive's fault detection (formerly Fault_Warning_Detect(); specs/equations.md
 * section 8.4) checks the phase currents, the DC bus and the temperatures and
 * stops the motor when a fault is present.  This module holds
 * the pure building blocks; the drive (include/qfoc/drive.h) owns the reactions:
 *
 *  - Over-current (QFOC_FAULT_OC) is decided in the fast step, in the same PWM
 *    period as the sample, without debounce: qfoc_fault_abs_over() on each phase
 *    current against the trip level.
 *  - The other faults are decided by the 1 ms tick through a qfoc_debounce_t of
 *    n ticks each, with n <= 10 for the DC bus and the temperatures, so that every
 *    fault is reported within 10 ms of its condition becoming true:
 *    OV = qfoc_fault_over(vdc, ov_level), UV = qfoc_fault_under(vdc, uv_level)
 *    while running, OT = qfoc_fault_over(temperature, t_max), PHASE =
 *    qfoc_phase_mon_imbalanced() (its low-pass fed by qfoc_phase_mon_update() in
 *    the fast step), STALL from the speed and flux errors with
 *    qfoc_fault_abs_over() and from the drive's fast flux plausibility check; OFFSET while running and TIMING from the drive's
 *    sensor and timing monitors (drive.h).
 *  - A fault sets its bit in the fault word (uint16_t, bits below); the drive
 *    clears the word only on an explicit fault-clear command.
 *
 * All functions are total on every value of their input types.
 *
 * qfoc_fault_name() gives each bit its short name for a log or a diagnostic.
 *
 * Requirements: REQ-FAULT-001 .. REQ-FAULT-009 (specs/requirements/fault.md).
 */
#ifndef QFOC_FAULT_H
#define QFOC_FAULT_H

#include "qfoc/types.h"
#include "qfoc/filter.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- fault word bits (REQ-FAULT-001) ------------------------------------- */
#define QFOC_FAULT_OC     ((uint16_t)0x0001u)  /**< phase over-current (fast step) */
#define QFOC_FAULT_OV     ((uint16_t)0x0002u)  /**< DC-bus over-voltage */
#define QFOC_FAULT_UV     ((uint16_t)0x0004u)  /**< DC-bus under-voltage (while running) */
#define QFOC_FAULT_OT_IPM ((uint16_t)0x0008u)  /**< IPM over-temperature */
#define QFOC_FAULT_OT_PCB ((uint16_t)0x0010u)  /**< PCB over-temperature */
#define QFOC_FAULT_STALL  ((uint16_t)0x0020u)  /**< stall / loss of synchronisation, or the
                                                   estimated flux implausible in steady closed
                                                   loop: a sensing fault such as a current
                                                   offset or a DC-bus gain (REQ-DRV-023) */
#define QFOC_FAULT_PHASE  ((uint16_t)0x0040u)  /**< phase loss (current imbalance) */
#define QFOC_FAULT_OFFSET ((uint16_t)0x0080u)  /**< current sensor implausible: offset out of window at
                                                   the calibration, or a stuck sample while running
                                                   (REQ-DRV-020) */
#define QFOC_FAULT_LINK   ((uint16_t)0x0100u)  /**< command-link timeout */
#define QFOC_FAULT_PARAM  ((uint16_t)0x0200u)  /**< parameter table or drive object corrupted */
#define QFOC_FAULT_TIMING ((uint16_t)0x0400u)  /**< fast steps per tick out of range in RUN
                                                   (REQ-DRV-021) */
#define QFOC_FAULT_ALL    ((uint16_t)0x07FFu)  /**< every fault bit above */

/** Longest text of qfoc_fault_name(), in characters without the terminating '\0'
    ("unknown"); a buffer of QFOC_FAULT_NAME_LEN_MAX + 1 characters holds any of them. */
#define QFOC_FAULT_NAME_LEN_MAX (7u)

/** Phase-monitor init status: coefficient accepted. */
#define QFOC_FAULT_OK ((int32_t)0)
/** Phase-monitor init status: coefficient rejected, safe coefficient used. */
#define QFOC_FAULT_ERR_PARAM ((int32_t)-1)

/** Debounce counter: consecutive calls with the condition true, capped at n. */
typedef struct {
    uint16_t count;  /**< consecutive trues so far, capped at the length n */
} qfoc_debounce_t;

/** Phase-loss monitor: low-passed |i_u|, |i_v|, |i_w| (index 0, 1, 2). */
typedef struct {
    qfoc_lpf_t abs_lpf[3];  /**< filters of the phase-current magnitudes */
} qfoc_phase_mon_t;

#ifdef __FRAMAC__
/* ACSL predicates over the types above, read by Frama-C only (DEV-001). */
/* cppcheck-suppress misra-c2012-20.1 ; DEV-001 */
#include "fault.acsl"
#endif

/**
 * @brief Clear a debounce counter (count 0).
 * @param[out] d counter
 *
 * Used by the drive at start-up and on a fault clear.
 *
 * Scaling and overflow: stores only.
 *
 * Requirements: REQ-FAULT-002.
 */
/*@
  requires valid_d: \valid(d);
  assigns d->count;
  ensures count: d->count == 0;
*/
void qfoc_debounce_reset(qfoc_debounce_t *d);

/**
 * @brief One debounce update: true once `cond` has held for n consecutive calls.
 * @param[in,out] d    counter (any count value is accepted)
 * @param[in]     cond the raw condition of this call
 * @param[in]     n    required number of consecutive calls, 0..65535
 *                     (0 and 1 both confirm at the first call with cond)
 * @return cond false: count = 0, false.  cond true: count = min(count + 1, n),
 *         returns count >= n.
 *
 * Semantics (contract `run_length`): if the counter equals min(k, n), where k is
 * the number of consecutive calls with cond true before this one (true after
 * qfoc_debounce_reset(), k = 0), then afterwards it equals min(k', n) with k' the
 * new run length, and the result is true exactly when k' >= max(n, 1): the
 * condition has held for the last max(n, 1) calls, this one included.
 *
 * Drive use: the 1 ms tick, one counter per debounced fault; with n = 10 a fault
 * is confirmed 10 ms after its condition became true and a single false sample
 * restarts the count.
 *
 * Bad input: a count above n (n lowered between calls, or an uninitialised
 * counter) is treated as "already confirmed": with cond true the count becomes n
 * and the result is true.
 *
 * Scaling and overflow: count + 1 is only formed when count < n <= 65535, so it
 * fits 16 bits.
 *
 * Requirements: REQ-FAULT-002.
 */
/*@
  requires valid_d: \valid(d);
  assigns d->count;
  ensures count: d->count == DebounceNext(\old(d->count), cond != 0, n);
  ensures capped: d->count <= n;
  ensures run_length: \forall integer k; k >= 0 && \old(d->count) == FaultMin(k, n) ==>
            (d->count == ((cond != 0) ? FaultMin(k + 1, n) : 0) &&
             (\result != 0 <==> (cond != 0 && k + 1 >= n)));
  behavior released:
    assumes cond == 0;
    ensures count: d->count == 0;
    ensures result: \result == 0;
  behavior counting:
    assumes cond != 0 && d->count < n;
    ensures count: d->count == \old(d->count) + 1;
    ensures result: \result != 0 <==> d->count == n;
  behavior confirmed:
    assumes cond != 0 && d->count >= n;
    ensures count: d->count == n;
    ensures result: \result != 0;
  complete behaviors;
  disjoint behaviors;
*/
bool qfoc_debounce_step(qfoc_debounce_t *d, bool cond, uint16_t n);

/**
 * @brief Check a phase monitor (run-time twin of PhaseMonValid).
 * @param[in] m monitor (read only)
 * @return true when each of the three filters has alpha > 0 and a state in
 *         [0, 32767 x 65536] (a filtered magnitude is never negative).
 *
 * Scaling and overflow: compares only.
 *
 * Requirements: REQ-FAULT-004.
 */
/*@
  requires valid_m: \valid_read(m);
  assigns \nothing;
  ensures result: \result <==> PhaseMonValid(m);
*/
bool qfoc_phase_mon_is_valid(const qfoc_phase_mon_t *m);

/**
 * @brief Initialise the phase monitor: the three filters get coefficient alpha,
 *        their outputs are 0.
 * @param[out] m     monitor
 * @param[in]  alpha low-pass coefficient 2 pi f_c / f_pwm, Q15, 1..32767
 *                   (e.g. f_c = 20 Hz at 8 kHz: 2 pi 20 / 8000 x 32768 = 514.7 -> 515)
 * @return QFOC_FAULT_OK (0), or QFOC_FAULT_ERR_PARAM (-1) when alpha <= 0.
 *
 * Bad input: alpha <= 0 is rejected; the filters then use the safe coefficient of
 * qfoc_lpf_init() (32767: no filtering) and the monitor is still valid.
 *
 * Scaling and overflow: stores only.
 *
 * Requirements: REQ-FAULT-004.
 */
/*@
  requires valid_m: \valid(m);
  assigns *m;
  ensures valid: PhaseMonValid(m);
  ensures zero: m->abs_lpf[0].state == 0 && m->abs_lpf[1].state == 0 &&
                m->abs_lpf[2].state == 0;
  behavior accepted:
    assumes alpha > 0;
    ensures result: \result == 0;
    ensures alpha: m->abs_lpf[0].alpha == alpha && m->abs_lpf[1].alpha == alpha &&
                   m->abs_lpf[2].alpha == alpha;
  behavior rejected:
    assumes alpha <= 0;
    ensures result: \result == -1;
    ensures alpha: m->abs_lpf[0].alpha == 32767 && m->abs_lpf[1].alpha == 32767 &&
                   m->abs_lpf[2].alpha == 32767;
  complete behaviors;
  disjoint behaviors;
*/
int32_t qfoc_phase_mon_init(qfoc_phase_mon_t *m, qfoc_q15_t alpha);

/**
 * @brief Set the three filtered magnitudes to 0 (coefficients kept).
 * @param[in,out] m valid monitor
 *
 * Drive use: whenever the inverter is switched on again, so that a stop does not
 * leave a stale imbalance.
 *
 * Scaling and overflow: stores only.
 *
 * Requirements: REQ-FAULT-004.
 */
/*@
  requires valid_m: \valid(m);
  requires m_valid: PhaseMonValid(m);
  assigns m->abs_lpf[0].state, m->abs_lpf[1].state, m->abs_lpf[2].state;
  ensures valid: PhaseMonValid(m);
  ensures zero: m->abs_lpf[0].state == 0 && m->abs_lpf[1].state == 0 &&
                m->abs_lpf[2].state == 0;
*/
void qfoc_phase_mon_reset(qfoc_phase_mon_t *m);

/**
 * @brief One fast-step update: low-pass |i_u|, |i_v|, |i_w| (specs/equations.md E2-34).
 * @param[in,out] m valid monitor
 * @param[in]     i phase currents, Q15 of I_base, any int16_t (|-32768| is
 *                  saturated to 32767)
 *
 * Each filter computes y(k+1) = y(k) + alpha (|i_x(k)| - y(k)) with the semantics
 * of qfoc_lpf_step(): the filtered magnitude of a sinusoidal phase current of
 * amplitude A settles at its mean 2 A / pi, with a ripple at twice the electrical
 * frequency reduced by the filter.
 *
 * Drive use: none (the drive filters one phase a period with
 * qfoc_phase_mon_update_one()); for a monitor that filters all three every period.
 *
 * Scaling and overflow: |i| in [0, 32767] (Q15); the filter states stay between
 * their old value and the new input (qfoc_lpf_step contract `between`), hence in
 * [0, 32767 x 65536] (Q31): the invariant holds after the call.
 *
 * Requirements: REQ-FAULT-003.
 */
/*@
  requires valid_m: \valid(m);
  requires valid_i: \valid_read(i);
  requires sep: \separated(m, i);
  requires m_valid: PhaseMonValid(m);
  assigns m->abs_lpf[0].state, m->abs_lpf[1].state, m->abs_lpf[2].state;
  ensures valid: PhaseMonValid(m);
  ensures state_u: m->abs_lpf[0].state ==
                   LpfNext(\old(m->abs_lpf[0].state), FaultAbs15(i->u), m->abs_lpf[0].alpha);
  ensures state_v: m->abs_lpf[1].state ==
                   LpfNext(\old(m->abs_lpf[1].state), FaultAbs15(i->v), m->abs_lpf[1].alpha);
  ensures state_w: m->abs_lpf[2].state ==
                   LpfNext(\old(m->abs_lpf[2].state), FaultAbs15(i->w), m->abs_lpf[2].alpha);
*/
void qfoc_phase_mon_update(qfoc_phase_mon_t *m, const qfoc_abc_t *i);

/**
 * @brief One phase of the monitor per call: low-pass |i_k| of phase k only
 *        (k = 0: u, 1: v, any other value: w); the two other filters are kept.
 * @param[in,out] m valid monitor
 * @param[in]     i phase currents, Q15 of I_base, any int16_t (|-32768| is
 *                  saturated to 32767)
 * @param[in]     k phase to update, any value (2 and above select w)
 *
 * The filter of phase k computes y(k+1) = y(k) + alpha (|i_k| - y(k)) with the
 * semantics of qfoc_lpf_step(), as qfoc_phase_mon_update() does for all three.
 *
 * Drive use: every PWM period, k cycling 0, 1, 2, the monitor initialised with
 * qfoc_phase_mon_alpha3() of the per-period coefficient: each filter then sees
 * every third sample with the same time constant (one filter step instead of
 * three per period; the sampled |i| of each phase is the same sinusoid at a third
 * of the rate, far above twice the largest electrical frequency).
 *
 * Scaling and overflow: as qfoc_phase_mon_update().
 *
 * Requirements: REQ-FAULT-003.
 */
/*@
  requires valid_m: \valid(m);
  requires valid_i: \valid_read(i);
  requires sep: \separated(m, i);
  requires m_valid: PhaseMonValid(m);
  assigns m->abs_lpf[0].state, m->abs_lpf[1].state, m->abs_lpf[2].state;
  ensures valid: PhaseMonValid(m);
  behavior phase_u:
    assumes k == 0;
    ensures state_u: m->abs_lpf[0].state ==
                     LpfNext(\old(m->abs_lpf[0].state), FaultAbs15(i->u), m->abs_lpf[0].alpha);
    ensures kept: m->abs_lpf[1].state == \old(m->abs_lpf[1].state) &&
                  m->abs_lpf[2].state == \old(m->abs_lpf[2].state);
  behavior phase_v:
    assumes k == 1;
    ensures state_v: m->abs_lpf[1].state ==
                     LpfNext(\old(m->abs_lpf[1].state), FaultAbs15(i->v), m->abs_lpf[1].alpha);
    ensures kept: m->abs_lpf[0].state == \old(m->abs_lpf[0].state) &&
                  m->abs_lpf[2].state == \old(m->abs_lpf[2].state);
  behavior phase_w:
    assumes k >= 2;
    ensures state_w: m->abs_lpf[2].state ==
                     LpfNext(\old(m->abs_lpf[2].state), FaultAbs15(i->w), m->abs_lpf[2].alpha);
    ensures kept: m->abs_lpf[0].state == \old(m->abs_lpf[0].state) &&
                  m->abs_lpf[1].state == \old(m->abs_lpf[1].state);
  complete behaviors;
  disjoint behaviors;
*/
void qfoc_phase_mon_update_one(qfoc_phase_mon_t *m, const qfoc_abc_t *i, uint8_t k);

/**
 * @brief The coefficient of a low-pass stepped every third period with the time
 *        constant of alpha stepped every period: 1 - (1 - alpha)^3, Q15.
 * @param[in] alpha per-period coefficient, Q15, any int16_t (taken as 1 below 1)
 * @return b = 32768 - alpha, b2 = b^2 / 32768 and b3 = b2 b / 32768, each rounded
 *         to nearest; the result 32768 - b3, at most 32767; always in [1, 32767].
 *
 * Against the real 1 - (1 - alpha / 32768)^3 (x 32768): within 1.5 LSB
 * (tests/test_fault.c measures it for every alpha).
 *
 * Drive use: at initialisation, for qfoc_phase_mon_update_one().
 *
 * Scaling and overflow: b in [1, 32767]; b^2 + 16384 and b2 b + 16384 are below
 * 2^30 + 2^14, exact in 32 bits.
 *
 * Requirements: REQ-FAULT-003.
 */
/*@
  assigns \nothing;
  ensures range: 1 <= \result <= 32767;
  ensures value: \result == PhaseMonAlpha3(alpha);
*/
qfoc_q15_t qfoc_phase_mon_alpha3(qfoc_q15_t alpha);

/**
 * @brief Phase-loss criterion on the filtered magnitudes.
 * @param[in] m     valid monitor
 * @param[in] i_min smallest largest-magnitude at which the check applies, Q15 of
 *                  I_base (below it the motor carries too little current to
 *                  judge; 1..32767 in use, any int16_t accepted)
 * @param[in] ratio imbalance ratio, Q15 (0..32767 in use; e.g. 0.25 = 8192)
 * @return with a_x = filtered |i_x| in Q15 (the filter state rounded to nearest),
 *         max = largest, min = smallest: true when max >= i_min and
 *         min < ratio / 32768 x max (compared exactly, no rounding).
 *
 * A lost phase carries no current: its filtered magnitude decays to 0 while the
 * two others carry the full current, so min / max drops toward 0.  In a healthy
 * machine the three magnitudes are equal (min / max near 1).  With max = 0 the
 * result is false (0 < 0 fails), so a motor at rest never reports a phase loss.
 *
 * Bad input: ratio <= 0 never reports (min >= 0); i_min <= 0 applies the check at
 * any current.
 *
 * Drive use: the 1 ms tick, as the condition of a debounce counter (phase_ms).
 *
 * Scaling and overflow: a_x in [0, 32767] (from the invariant); min x 32768 <=
 * 32767 x 32768 < 2^31 and |ratio x max| <= 32768 x 32767 < 2^31: both products
 * are exact in 32 bits.
 *
 * Requirements: REQ-FAULT-005.
 */
/*@
  requires valid_m: \valid_read(m);
  requires m_valid: PhaseMonValid(m);
  assigns \nothing;
  ensures result: \result != 0 <==> PhaseMonImbalanced(m, i_min, ratio);
*/
bool qfoc_phase_mon_imbalanced(const qfoc_phase_mon_t *m, qfoc_q15_t i_min, qfoc_q15_t ratio);

/**
 * @brief Largest of the three filtered phase-current magnitudes.
 * @param[in] m valid monitor
 * @return max(a_u, a_v, a_w), a_x = filtered |i_x| in Q15 of I_base (the filter state
 *         rounded to nearest, as qfoc_phase_mon_imbalanced() reads it); in [0, 32767].
 *
 * A current that the inverter imposes but that does not reach the sensors (no motor, an
 * open phase on the measured path, a current sensor stuck at its zero code) leaves all
 * three magnitudes near 0.  At the drive's alignment angle (0, phase u on the d axis) a
 * healthy machine gives a_u = |i_d| and a_v = a_w = |i_d| / 2; turning at any speed,
 * the largest of the three is at least 2 / pi of the current amplitude.
 *
 * Drive use: the 1 ms tick, the current-response check of ALIGN and OPEN_LOOP
 * (REQ-DRV-018).
 *
 * Scaling and overflow: the states are in [0, 32767 x 65536] (PhaseMonValid); the rounded
 * outputs are in [0, 32767]; compares only.
 *
 * Requirements: REQ-FAULT-007.
 */
/*@
  requires valid_m: \valid_read(m);
  requires m_valid: PhaseMonValid(m);
  assigns \nothing;
  ensures range: 0 <= \result <= 32767;
  ensures value: \result == FaultMax3(PhaseMonOut(m, 0), PhaseMonOut(m, 1), PhaseMonOut(m, 2));
*/
qfoc_q15_t qfoc_phase_mon_peak(const qfoc_phase_mon_t *m);

/**
 * @brief Over-threshold compare: x > limit.
 * @param[in] x     measured value, Q15 (or any int16_t scaling shared with limit)
 * @param[in] limit trip level in the same scaling
 * @return true when x > limit.
 *
 * Drive use (1 ms tick): DC-bus over-voltage, IPM and PCB over-temperature
 * (temperatures in 0.1 degC).
 *
 * Scaling and overflow: compares only.
 *
 * Requirements: REQ-FAULT-006.
 */
/*@
  assigns \nothing;
  ensures result: \result != 0 <==> x > limit;
*/
bool qfoc_fault_over(qfoc_q15_t x, qfoc_q15_t limit);

/**
 * @brief Under-threshold compare: x < limit.
 * @param[in] x     measured value
 * @param[in] limit trip level in the same scaling
 * @return true when x < limit.
 *
 * Drive use (1 ms tick): DC-bus under-voltage while running.
 *
 * Scaling and overflow: compares only.
 *
 * Requirements: REQ-FAULT-006.
 */
/*@
  assigns \nothing;
  ensures result: \result != 0 <==> x < limit;
*/
bool qfoc_fault_under(qfoc_q15_t x, qfoc_q15_t limit);

/**
 * @brief Magnitude compare: |x| > limit, exact for x = -32768 (|x| = 32768).
 * @param[in] x     signed measured value, Q15, any int16_t
 * @param[in] limit trip level in the same scaling (a negative limit always trips)
 * @return true when |x| > limit.
 *
 * Drive use: phase over-current in the fast step, in the same PWM period as the
 * sample and without debounce (each of i_u, i_v, i_w against the trip current);
 * stall detection (|speed error|, |flux error|) in the tick.
 *
 * Scaling and overflow: |x| is formed in 32 bits (0..32768), so -32768 is not
 * saturated and a full-scale negative current trips every limit up to 32767.
 *
 * Requirements: REQ-FAULT-006.
 */
/*@
  assigns \nothing;
  ensures result: \result != 0 <==> \abs(x) > limit;
*/
bool qfoc_fault_abs_over(qfoc_q15_t x, qfoc_q15_t limit);

/**
 * @brief Error-model band compare: is a deviation beyond k + v / |w|?  (The drive's fast
 *        flux check, REQ-DRV-023: a flux deviation against a band with a part that does not
 *        depend on the speed, k, and a voltage error over the speed, v / |w|; a voltage in
 *        Q15 of V_base over a speed in Q15 of w_base is a flux in Q15 of psi_base, times
 *        32768.)
 * @param[in] dev the deviation, Q15, any int16_t (a negative one never exceeds)
 * @param[in] k   the speed-independent part, Q15 (a negative value reads as 0)
 * @param[in] v   the voltage error, Q15 of V_base, clamped to [0, 65535]
 * @param[in] w   the speed, Q15, any int16_t; |w| is used (w = 0: never exceeds)
 * @return true exactly when dev > k' and (dev - k') |w| > 32768 v' (k', v' the clamped
 *         values), which is dev > k' + floor(32768 v' / |w|) for w != 0: decided with two
 *         products, without a division.
 * Scaling and overflow: dev - k' <= 32767 and |w| <= 32768 give a product below 2^30;
 * 32768 v' <= 32768 x 65535 < 2^31 - 1; both in int32.
 * Requirements: REQ-FAULT-008.
 */
/*@
  assigns \nothing;
  ensures result: \result != 0 <==>
      (dev > \max(k, 0) &&
       (dev - \max(k, 0)) * \abs(w) > 32768 * ((v < 0) ? 0 : ((v > 65535) ? 65535 : v)));
*/
bool qfoc_fault_band_over(qfoc_q15_t dev, qfoc_q15_t k, int32_t v, qfoc_q15_t w);

/**
 * @brief The short name of one fault bit, for a log, a diagnostic or a display.
 * @param[in] bit a fault word value, any uint16_t; normally one of the QFOC_FAULT_*
 *                bits (a word with several bits is named bit by bit, below)
 * @return a pointer to a constant, zero-terminated text of at most
 *         QFOC_FAULT_NAME_LEN_MAX (7) characters, valid for the program's lifetime,
 *         read only, never NULL:
 *         - a single defined bit: its name, the macro's name without QFOC_FAULT_:
 *           QFOC_FAULT_OC "OC", QFOC_FAULT_OV "OV", QFOC_FAULT_UV "UV",
 *           QFOC_FAULT_OT_IPM "OT_IPM", QFOC_FAULT_OT_PCB "OT_PCB",
 *           QFOC_FAULT_STALL "STALL", QFOC_FAULT_PHASE "PHASE",
 *           QFOC_FAULT_OFFSET "OFFSET", QFOC_FAULT_LINK "LINK",
 *           QFOC_FAULT_PARAM "PARAM", QFOC_FAULT_TIMING "TIMING";
 *         - 0 (no fault): "none";
 *         - anything else (two or more bits, a bit above QFOC_FAULT_ALL): "unknown".
 *
 * The names are those of the safety manual's fault table; they do not change between
 * releases (a new fault bit gets a new name).
 * The lower-case texts "none" and "unknown" cannot be taken for a fault's name.  A
 * word with several bits, such as the fault word of qfoc_drive_faults(), is named bit
 * by bit:
 * @code
 *   for (uint16_t b = 1u; b <= QFOC_FAULT_ALL; b = (uint16_t)(b << 1u)) {
 *       if ((faults & b) != 0u) { log_text(qfoc_fault_name(b)); }
 *   }
 * @endcode
 *
 * Bad input: none; every value is named ("unknown" when it is not a single defined
 * bit).  Reads and writes no memory; the texts are constants of the library.
 *
 * Requirements: REQ-FAULT-009.
 */
/*@
  assigns \nothing;
  ensures valid: \valid_read(\result);
  behavior oc:
    assumes bit == QFOC_FAULT_OC;
    ensures name: FaultText2(\result, 'O', 'C');
  behavior ov:
    assumes bit == QFOC_FAULT_OV;
    ensures name: FaultText2(\result, 'O', 'V');
  behavior uv:
    assumes bit == QFOC_FAULT_UV;
    ensures name: FaultText2(\result, 'U', 'V');
  behavior ot_ipm:
    assumes bit == QFOC_FAULT_OT_IPM;
    ensures name: FaultText6(\result, 'O', 'T', '_', 'I', 'P', 'M');
  behavior ot_pcb:
    assumes bit == QFOC_FAULT_OT_PCB;
    ensures name: FaultText6(\result, 'O', 'T', '_', 'P', 'C', 'B');
  behavior stall:
    assumes bit == QFOC_FAULT_STALL;
    ensures name: FaultText5(\result, 'S', 'T', 'A', 'L', 'L');
  behavior phase:
    assumes bit == QFOC_FAULT_PHASE;
    ensures name: FaultText5(\result, 'P', 'H', 'A', 'S', 'E');
  behavior offset:
    assumes bit == QFOC_FAULT_OFFSET;
    ensures name: FaultText6(\result, 'O', 'F', 'F', 'S', 'E', 'T');
  behavior link:
    assumes bit == QFOC_FAULT_LINK;
    ensures name: FaultText4(\result, 'L', 'I', 'N', 'K');
  behavior param:
    assumes bit == QFOC_FAULT_PARAM;
    ensures name: FaultText5(\result, 'P', 'A', 'R', 'A', 'M');
  behavior timing:
    assumes bit == QFOC_FAULT_TIMING;
    ensures name: FaultText6(\result, 'T', 'I', 'M', 'I', 'N', 'G');
  behavior none:
    assumes bit == 0;
    ensures name: FaultText4(\result, 'n', 'o', 'n', 'e');
  behavior unknown:
    assumes bit != 0 && !FaultNamedBit(bit);
    ensures name: FaultText7(\result, 'u', 'n', 'k', 'n', 'o', 'w', 'n');
  complete behaviors;
  disjoint behaviors;
*/
const char *qfoc_fault_name(uint16_t bit);

#ifdef __cplusplus
}
#endif

#endif /* QFOC_FAULT_H */
