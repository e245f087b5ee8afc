/**
 * @file qfoc_drive_api.c
 * @brief The drive's command and status functions: a decoded command in, the state,
 *        faults, speeds, angle, currents and bus voltage out, without LIN frames.
 *
 * See include/qfoc/drive.h ("command and status") for the contracts and the calling
 * context.  Requirements: REQ-DRV-016, REQ-DRV-017.
 */
#include "qfoc/drive.h"

int32_t qfoc_drive_command(qfoc_drive_t *d, const qfoc_cmd_t *cmd)
{
    /* the link's rule for a command, as for a valid command frame (link.h) */
    return qfoc_link_accept(&d->s.link, cmd);
}

uint8_t qfoc_drive_state(const qfoc_drive_t *d)
{
    return d->s.sm.state;
}

uint8_t qfoc_drive_substate(const qfoc_drive_t *d)
{
    return d->s.sm.sub;
}

uint16_t qfoc_drive_faults(const qfoc_drive_t *d)
{
    return d->s.sm.faults;
}

uint16_t qfoc_drive_first_fault(const qfoc_drive_t *d)
{
    return d->s.sm.first_fault;
}

void qfoc_drive_status(const qfoc_drive_t *d, qfoc_status_t *st)
{
    *st = d->s.status;
}

uint16_t qfoc_drive_speed_rpm(const qfoc_drive_t *d)
{
    return d->s.status.speed_rpm;
}

uint16_t qfoc_drive_target_rpm(const qfoc_drive_t *d)
{
    return d->s.cmd.target_rpm;
}

bool qfoc_drive_run_requested(const qfoc_drive_t *d)
{
    return d->s.cmd.power_on;
}

bool qfoc_drive_identify_requested(const qfoc_drive_t *d)
{
    return d->s.cmd.identify;
}

bool qfoc_drive_derated(const qfoc_drive_t *d)
{
    return d->s.derated;
}

qfoc_angle_t qfoc_drive_angle_est(const qfoc_drive_t *d)
{
    return d->f.theta_est;
}

void qfoc_drive_currents_q15(const qfoc_drive_t *d, qfoc_dq_t *i_dq)
{
    i_dq->d = d->f.i_dq.d;
    i_dq->q = d->f.i_dq.q;
}

qfoc_q15_t qfoc_drive_vdc_q15(const qfoc_drive_t *d)
{
    return d->f.vdc;
}
