/**
 * @file qfoc_drive_start.h
 * @brief Internal interface between the drive (qfoc_drive.c) and its start-up sequence
 *        (qfoc_drive_start.c): the references of ALIGN and OPEN_LOOP, the hand-over
 *        condition and the bumpless transfer to CLOSED_LOOP; not part of the public API.
 *
 * Requirements: REQ-DRV-006, REQ-DRV-026, REQ-SM-011.
 */
#ifndef QFOC_DRIVE_START_H
#define QFOC_DRIVE_START_H

#include "qfoc/drive.h"
#include "qfoc/q15.h"

/**
 * @brief Handover condition (REQ-DRV-006).  The I/f current lies on the q axis of the open-loop
 *        frame; with the load torque T the rotor settles where K i cos(delta) = T, delta =
 *        theta_ol - theta_est in [-90 deg, 0]: -90 deg without load (the rotor's d axis on the
 *        current), towards 0 as the load grows; past 0 the rotor falls behind the frame and slips
 *        (delta sweeps through +180 deg).  The observer has converged on a rotor that follows the
 *        frame when, for ho_dwell_ms: the I/f ramp has reached the handover speed of_speed (the
 *        minimum speed: below it the back-EMF is not known to dominate the inverter's voltage
 *        error), the filtered estimated speed is within 1/4 of the frame speed, the flux
 *        magnitude is at least the PLL's mag_min, and -(90 deg + ho_angle) < delta < ho_angle.
 *        delta is not required to be small: a pulsating load swings it by tens of degrees; the
 *        transfer presets the speed PI with the rotor's torque.
 */
/*@
  requires valid: \valid(s) && \valid_read(f) && \valid_read(p);
  requires sep: \separated(s, f, p);
  assigns s->db_ho;
*/
bool qfoc_drive_start_converged(qfoc_drive_slow_t *s, const qfoc_drive_fast_t *f,
                                const qfoc_param_table_t *p, bool open_loop);

/**
 * @brief Bumpless transfer (REQ-DRV-006): the q current that gives, with i_d = 0, the torque the
 *        rotor produces at the end of OPEN_LOOP.  The I/f current i lies on the q axis of the
 *        open-loop frame, delta = theta_ol - theta_est ahead of the rotor: in the rotor frame i_d
 *        = -i sin(delta), i_q = i cos(delta), and the torque 3/2 n_p i_q (psi_f + (L_d - L_q)
 *        i_d) equals 3/2 n_p psi_f i_q' for i_q' = i_q (psi_f + (L_d - L_q) i_d) / psi_f.
 */
/*@
  requires valid: \valid_read(d) && \valid_read(d->p);
  assigns \nothing;
*/
qfoc_q15_t qfoc_drive_start_bumpless_iq(const qfoc_drive_t *d);

/**
 * @brief OPEN_LOOP's references (REQ-DRV-006): the d current to 0 and the q current to the start
 *        current, each by ceil(i_max / DRV_OL_RAMP_MS) per tick (i_start <= i_max, i_align <=
 *        i_max), and the I/f frame speed to of_speed at of_accel.
 */
/*@
  requires valid: \valid(s) && \valid_read(p);
  requires sep: \separated(s, p);
  assigns s->id_ref, s->iq_ref, s->ol_speed;
*/
void qfoc_drive_start_open_loop(qfoc_drive_slow_t *s, const qfoc_param_table_t *p);

/**
 * @brief ALIGN's d reference (REQ-DRV-006, REQ-DRV-026).
 */
/*@
  requires valid: \valid(d) && \valid_read(d->p);
  requires sep: \separated(&d->s, d->p);
  assigns d->s.id_ref, d->s.dt_u, d->s.dt_u0, d->s.dt_u1;
*/
void qfoc_drive_start_align(qfoc_drive_t *d);

#endif /* QFOC_DRIVE_START_H */
