/**
 * @file qfoc_drive_mon.h
 * @brief Internal interface between the drive (qfoc_drive.c) and its tick-evaluated
 *        monitors (qfoc_drive_mon.c); not part of the public API.
 *
 * Requirements: REQ-DRV-008, REQ-DRV-020, REQ-DRV-021, REQ-DRV-023, REQ-DRV-025.
 */
#ifndef QFOC_DRIVE_MON_H
#define QFOC_DRIVE_MON_H

#include "qfoc/drive.h"
#include "qfoc/q15.h"

/** ADC code to Q15 current: 2048 codes = I_base, so x 16 (the drive's samples). */
#define QFOC_DRIVE_I_PER_CODE ((int32_t)16)

/**
 * @brief An inductance times a current: L (Q12 of L_base) x i (Q15 of I_base) -> Q15 flux
 *        of psi_base, saturated (the drive's decoupling and bumpless transfer, the
 *        monitors' expected flux).
 */
/*@
  assigns \nothing;
  ensures range: -32767 <= \result <= 32767;
*/
qfoc_q15_t qfoc_drive_li(int16_t l, qfoc_q15_t i);

/**
 * @brief The faults of one tick (fault.h; reaction times in drive.h, REQ-DRV-008): the
 *        bus, the temperatures and the fast step's new trips, then stall, flux
 *        plausibility, phase loss and the table check, each through its debounce.
 * @param[in,out] d  the drive (its debounce counts and the trips seen are updated)
 * @param[in]     in the tick's inputs (temperatures)
 * @return the fault bits raised in this tick (OFFSET and TIMING are the drive's own)
 */
/*@
  requires valid: \valid(d) && \valid_read(d->p) && \valid_read(in);
  requires sep: \separated(&d->s, d->p) && \separated(&d->s, in);
  requires inv: DRV_PHASE(&d->f.phase);
  assigns d->s.db_ov, d->s.db_uv, d->s.db_ot_ipm, d->s.db_ot_pcb, d->s.db_stall, d->s.db_flux,
          d->s.db_phase, d->s.db_align, d->s.trip_seen;
  ensures bits: \result <= QFOC_FAULT_ALL - QFOC_FAULT_OFFSET - QFOC_FAULT_TIMING;
*/
uint16_t qfoc_drive_mon_tick(qfoc_drive_t *d, const qfoc_tick_in_t *in);

/**
 * @brief The stuck-sample monitor (REQ-DRV-020): in CLOSED_LOOP and STOPPING, while the stall
 *        condition is false and the current is one a healthy phase cannot hold on a code for
 *        the window, one current code unchanged for 2 ms of fast steps while the other's
 *        moved gives OFFSET.  Read while the fast step may pre-empt: each count is one 16-bit
 *        word.
 */
/*@
  requires valid: \valid_read(d) && \valid_read(d->p);
  assigns \nothing;
*/
bool qfoc_drive_mon_sensor(const qfoc_drive_t *d);

/**
 * @brief The timing monitor (REQ-DRV-021): in RUN, the fast steps since the previous tick
 *        against f_pwm / 1000 a tick, 2 either side for the phase of the two interrupts and
 *        their latencies.  n_fast is one 16-bit word the fast step writes; the difference is
 *        taken mod 2^16.  Records the count for the next tick.
 */
/*@
  requires valid: \valid(d) && \valid_read(d->p);
  requires sep: \separated(&d->s, d->p);
  assigns d->s.fast_seen;
  ensures seen: d->s.fast_seen == d->f.n_fast;
*/
bool qfoc_drive_mon_timing(qfoc_drive_t *d);

#endif /* QFOC_DRIVE_MON_H */
