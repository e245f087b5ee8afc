/**
 * @file qfoc_drive_mon.h
 * @brief Internal interface between the drive (qfoc_drive.c) and its tick-evaluated
 *        monitors (qfoc_drive_mon.c); not part of the public API.
 *
 * Requirements: REQ-DRV-008, REQ-DRV-023, REQ-DRV-025.
 */
#ifndef QFOC_DRIVE_MON_H
#define QFOC_DRIVE_MON_H

#include "qfoc/drive.h"
#include "qfoc/q15.h"

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

#endif /* QFOC_DRIVE_MON_H */
