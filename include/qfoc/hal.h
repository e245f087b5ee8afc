/**
 * @file hal.h
 * @brief The hardware seam: the small set of functions a port implements so that the
 *        drive's two entry points (drive.h) can run on a chip.
 *
 * The library (src/) never touches a register.  A port (port_s32k/ for the NXP S32K144)
 * implements every function below and calls the drive from two interrupts:
 *
 *   ADC-complete interrupt, once per PWM period (formerly adc1isr / ftmTimerISR):
 *       qfoc_hal_adc_read()  ->  qfoc_drive_fast_step()  ->  qfoc_hal_pwm_write()
 *   1 ms interrupt (formerly Ms_1_job, Ms_100_job, Communication_service):
 *       qfoc_hal_ms_tick(), qfoc_hal_temps_read(), qfoc_hal_lin_receive()
 *         ->  qfoc_drive_tick()  ->  qfoc_hal_lin_transmit(), qfoc_hal_can_send(),
 *       qfoc_hal_watchdog_refresh()
 *
 * With single-shunt current sensing (shunt.h) the ADC-complete interrupt reads with
 * qfoc_hal_adc_read_shunt() (the two DC-link samples) and writes with
 * qfoc_hal_pwm_write_shunt() (the period's plan: asymmetric compare values and the two
 * sampling instants); the port is set up for it (port_s32k: the *_shunt set-up functions
 * of s32k144_port.h).
 *
 * Contexts and priorities: the ADC-complete interrupt pre-empts the 1 ms interrupt,
 * which pre-empts the communication interrupts (UART).  Each function says which
 * context calls it; a function is only called from the context it names (the port's
 * data shared between contexts is written by one context each, or handed over with a
 * flag written last, as in drive.h).
 *
 * Units at the seam are those of drive.h: 12-bit ADC codes, compare values in timer
 * ticks of the centre-aligned PWM (0..period, larger = longer high-side on-time),
 * temperatures in 0.1 degC, LIN-style frames as byte buffers of at most
 * QFOC_LIN_FRAME_MAX bytes (link.h; the break field is the port's business), CAN frames
 * as qfoc_can_frame_t (link.h).
 *
 * Every function is total: any argument value is accepted (compare values above the
 * period are clamped, lengths above the buffer are refused).  Pointers must be valid.
 *
 * Requirements (specs/requirements/port.md): REQ-PORT-001 one seam and one register
 * accessor, REQ-PORT-002 clock tree and power mode, REQ-PORT-003 peripheral clocks,
 * REQ-PORT-004 pins, REQ-PORT-005 complementary centre-aligned PWM from the table,
 * REQ-PORT-006 hardware dead time, REQ-PORT-007 hardware over-current path, REQ-PORT-008
 * compare values and enable, REQ-PORT-009 sampling chain and ADC set-up, REQ-PORT-010
 * samples and temperatures, REQ-PORT-011 LIN-style UART link, REQ-PORT-012 CAN frame,
 * REQ-PORT-013 millisecond time base, REQ-PORT-014 watchdog, REQ-PORT-015 interrupt
 * priorities, REQ-PORT-016 ADC-complete interrupt, REQ-PORT-017 millisecond interrupt,
 * REQ-PORT-018 supervision and fault output, REQ-PORT-019 start-up and image,
 * REQ-PORT-020 single-shunt PWM and sampling instants, REQ-PORT-021 single-shunt samples.
 * The set-up functions of the S32K144 port are declared in port_s32k/s32k144_port.h.
 */
#ifndef QFOC_HAL_H
#define QFOC_HAL_H

#include "qfoc/types.h"
#include "qfoc/drive.h"
#include "qfoc/link.h"
#include "qfoc/shunt.h"

#ifdef __cplusplus
extern "C" {
#endif

/**
 * @brief Write the compare values and the output enable of the next PWM period.
 * @param[in] pwm compare values u, v, w in timer ticks (0..period; larger values are
 *                clamped to the period) and the enable (false: all six switches off)
 *
 * Context: the ADC-complete interrupt, right after qfoc_drive_fast_step().
 * The compare values take effect at the next reload point of the timer (one PWM
 * period after the samples, the computation delay the drive models); the enable takes
 * effect at once: enable false masks the six outputs to their inactive (off) level
 * within one timer clock.  The outputs stay masked while the port's fault output is
 * latched (qfoc_hal_fault_output()), whatever the enable says.  With the enable false
 * the port also clears a latched hardware over-current fault whose input has
 * returned to its inactive level (REQ-PORT-007).
 *
 * Requirements: REQ-PORT-008, REQ-PORT-007.
 */
/*@
  requires valid_pwm: \valid_read(pwm);
*/
void qfoc_hal_pwm_write(const qfoc_pwm_t *pwm);

/**
 * @brief Fetch the samples of this PWM period.
 * @param[out] adc phase currents u, v and DC-bus voltage, 12-bit codes 0..4095
 *
 * Context: the ADC-complete interrupt, before qfoc_drive_fast_step().  The samples
 * were taken at the centre of the PWM period (all low-side switches on).  Reading them
 * also stores the slow channels' latest codes for qfoc_hal_temps_read().  A hardware
 * over-current trip latched by the timer since the last call is reported once as
 * full-scale phase currents (u and v at 4095), so that the drive's over-current rule
 * (drive.h: |i| > i_trip) latches its own fault in this same step.
 *
 * Requirements: REQ-PORT-010, REQ-PORT-007.
 */
/*@
  requires valid_adc: \valid(adc);
  assigns *adc;
*/
void qfoc_hal_adc_read(qfoc_adc_t *adc);

/**
 * @brief Write the PWM of the next period for single-shunt sensing: the plan's asymmetric
 *        compare values and its two sampling instants.
 * @param[in] pwm  symmetric compare values u, v, w in timer ticks (0..period; larger values
 *                 are clamped to the period) and the enable (false: all six switches off)
 * @param[in] plan the plan of the next period (qfoc_shunt_plan() on pwm's compare values):
 *                 up[k], down[k] the compare values of the up- and down-counting halves,
 *                 trig[0], trig[1] the counter values of the up-counting half at which the
 *                 two DC-link samples start
 *
 * Context: the ADC-complete interrupt, right after qfoc_drive_fast_step() (in place of
 * qfoc_hal_pwm_write()).  The plan is used when it is ok, every compare value is within
 * the period and trig[0] < trig[1] < period, as qfoc_shunt_plan() gives it for a
 * configuration of the port's period; otherwise the symmetric compare values of pwm are
 * written, exactly as qfoc_hal_pwm_write() does, and the samples are taken at instants of
 * the port's choosing (their values then mean nothing: the caller's plan was not ok).
 * Written in period k, the compare values and the instants take effect together at the
 * next reload point of the timer (the end of period k): period k + 1 is switched with them
 * and samples at them, and its samples are read in period k + 1 by
 * qfoc_hal_adc_read_shunt() (the plan written in period k - 1 is the one in force for the
 * samples read in period k).  The enable, the latched fault output and the clearing of a
 * reported hardware trip act exactly as in qfoc_hal_pwm_write().  A port set up for two
 * phase-current sensors writes pwm as qfoc_hal_pwm_write() does and ignores the plan.
 *
 * Requirements: REQ-PORT-020, REQ-PORT-008, REQ-PORT-007.
 */
/*@
  requires valid_pwm: \valid_read(pwm) && \valid_read(plan);
*/
void qfoc_hal_pwm_write_shunt(const qfoc_pwm_t *pwm, const qfoc_shunt_plan_t *plan);

/**
 * @brief Fetch the samples of this PWM period for single-shunt sensing.
 * @param[out] adc    DC-bus voltage, 12-bit code 0..4095; phase currents u and v 2048
 *                    (the code of 0 A: no phase sensor), except on a hardware trip (below)
 * @param[out] sample the two DC-link current samples of this period, Q15 of the current
 *                    base: sample[0] at trig[0] (+i_hi), sample[1] at trig[1] (-i_lo) of
 *                    the plan in force, each (code - offset) x 16, saturated to
 *                    [-32767, 32767], the scaling of the drive's phase currents (drive.h)
 *
 * Context: the ADC-complete interrupt, before qfoc_drive_fast_step() (in place of
 * qfoc_hal_adc_read()).  The samples were taken in this period at the instants written in
 * the previous one (qfoc_hal_pwm_write_shunt()); the offset is the port's (port_s32k:
 * qfoc_s32k_shunt_offset_set(), 2048 until set).  Reading them also stores the slow
 * channels' latest codes for qfoc_hal_temps_read(), as qfoc_hal_adc_read() does.  A
 * hardware over-current trip latched by the timer since the last call (of either read
 * function) is reported once as full-scale samples (both 32767) and full-scale phase
 * currents (u and v at 4095).  A port set up for two phase-current sensors reports both
 * samples as 0.
 *
 * Requirements: REQ-PORT-021, REQ-PORT-010, REQ-PORT-007.
 */
/*@
  requires valid_adc: \valid(adc) && \valid(sample + (0 .. 1));
  requires sep: \separated(adc, sample + (0 .. 1));
  assigns *adc, sample[0 .. 1];
*/
void qfoc_hal_adc_read_shunt(qfoc_adc_t *adc, qfoc_q15_t sample[2]);

/**
 * @brief The two temperatures, converted from their NTC channels.
 * @param[out] t_ipm IPM temperature, 0.1 degC, -400 .. 2000
 * @param[out] t_pcb PCB temperature, 0.1 degC, -400 .. 2000
 *
 * Context: the 1 ms interrupt.  Readings below -40 degC are reported as -400; readings
 * above 200 degC, a shorted sensor and an open sensor are reported as 2000 (hot), so
 * that a broken sensor trips the drive's over-temperature fault instead of hiding it.
 *
 * Requirements: REQ-PORT-010.
 */
/*@
  requires valid_out: \valid(t_ipm) && \valid(t_pcb) && \separated(t_ipm, t_pcb);
  assigns *t_ipm, *t_pcb;
*/
void qfoc_hal_temps_read(int16_t *t_ipm, int16_t *t_pcb);

/**
 * @brief Take the LIN-style frame completed since the last call.
 * @param[out] buf  destination, at least size bytes
 * @param[in]  size capacity of buf, bytes (QFOC_LIN_FRAME_MAX is enough)
 * @return the frame's length 1 .. QFOC_LIN_FRAME_MAX, or 0 when no complete frame
 *         arrived (buf untouched), or when the frame does not fit size (dropped).
 *
 * Context: the 1 ms interrupt, before qfoc_drive_tick().  A frame starts after a LIN
 * break and ends at an idle line; frames longer than QFOC_LIN_FRAME_MAX bytes, frames
 * with a framing, noise, parity or overrun error, and the echo of the port's own
 * transmission are dropped.  At 19200 baud at most one frame completes per
 * millisecond; a second frame completed before this call replaces nothing (the first
 * is kept, the second dropped).
 *
 * Requirements: REQ-PORT-011.
 */
/*@
  requires valid_buf: \valid(buf + (0 .. size - 1));
  assigns buf[0 .. size - 1];
  ensures len: \result <= size && \result <= QFOC_LIN_FRAME_MAX;
*/
uint8_t qfoc_hal_lin_receive(uint8_t *buf, uint8_t size);

/**
 * @brief Queue a LIN-style frame for transmission (a break, then the bytes).
 * @param[in] buf bytes to send (copied)
 * @param[in] len 1 .. QFOC_LIN_FRAME_MAX
 * @return true when queued; false when len is 0 or too long, or the previous frame is
 *         still being sent (the frame is then dropped: the master polls again).
 *
 * Context: the 1 ms interrupt, after qfoc_drive_tick() returned tx_len > 0.  The bytes
 * are sent by the UART interrupt (19200 baud, 8N1: 11 bytes take 5.7 ms).
 *
 * Requirements: REQ-PORT-011.
 */
/*@
  requires valid_buf: len > 0 ==> \valid_read(buf + (0 .. len - 1));
*/
bool qfoc_hal_lin_transmit(const uint8_t *buf, uint8_t len);

/**
 * @brief Send one CAN frame (standard identifier) from the port's transmit buffer.
 * @param[in] frame identifier (11 bits; higher bits ignored), DLC (0..8; larger is sent
 *                  as 8) and data
 * @return true when handed to the controller; false when the previous frame is still
 *         pending (this one is dropped: the status frame repeats every 100 ms).
 *
 * Context: the 1 ms interrupt, on the ticks where qfoc_drive_tick() sets can_send
 * (every 100 ms).  500 kbit/s.
 *
 * Requirements: REQ-PORT-012.
 */
/*@
  requires valid_frame: \valid_read(frame);
*/
bool qfoc_hal_can_send(const qfoc_can_frame_t *frame);

/**
 * @brief Acknowledge the millisecond timer and count the millisecond.
 * @return the millisecond counter after this tick (wraps after 2^32 ms = 49.7 days)
 *
 * Context: first call of the 1 ms interrupt.  Also sets the flag that
 * qfoc_hal_ms_flag_take() returns.
 *
 * Requirements: REQ-PORT-013.
 */
uint32_t qfoc_hal_ms_tick(void);

/**
 * @brief The millisecond counter (any context; a single 32-bit read).
 * @return milliseconds since the time base started, modulo 2^32
 *
 * Requirements: REQ-PORT-013.
 */
/*@ assigns \nothing; */
uint32_t qfoc_hal_ms_count(void);

/**
 * @brief Take the millisecond flag (background loop).
 * @return true once after each millisecond tick (ticks missed by the background loop
 *         are merged into one).
 *
 * Requirements: REQ-PORT-013.
 */
bool qfoc_hal_ms_flag_take(void);

/**
 * @brief PWM periods counted by the timer's period interrupt (formerly
 *        ftmTimerISR, overflow or reload as configured).
 * @return periods since the PWM started, modulo 2^32
 *
 * Context: the 1 ms interrupt (supervision of the ADC-complete chain, REQ-PORT-018).
 *
 * Requirements: REQ-PORT-018.
 */
/*@ assigns \nothing; */
uint32_t qfoc_hal_pwm_periods(void);

/**
 * @brief Refresh the watchdog.
 *
 * Context: the 1 ms interrupt, after the drive's tick.  The watchdog resets the chip
 * when no refresh comes within its timeout (port_s32k: 10 ms).
 *
 * Requirements: REQ-PORT-014.
 */
void qfoc_hal_watchdog_refresh(void);

/**
 * @brief Assert the fault output: hardware PWM disable and fault pin.
 *
 * Any context.  Masks the six PWM outputs to their inactive (off) level at once,
 * de-asserts the gate-driver enable pin, and latches: qfoc_hal_pwm_write() keeps the
 * outputs masked until the next reset.  Used by the port's supervision
 * (REQ-PORT-018) and by the fault handlers of the startup code.
 *
 * Requirements: REQ-PORT-018.
 */
void qfoc_hal_fault_output(void);

/**
 * @brief Whether the fault output is latched.
 * @return true after qfoc_hal_fault_output() (until reset)
 *
 * Requirements: REQ-PORT-018.
 */
/*@ assigns \nothing; */
bool qfoc_hal_fault_latched(void);

#ifdef __cplusplus
}
#endif

#endif /* QFOC_HAL_H */
