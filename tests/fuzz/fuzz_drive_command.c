/*
 * fuzz_drive_command.c -- libFuzzer harness of the command API and the status readers
 * (REQ-FUZZ-005).
 *
 * Start: a drive initialised from a committed table in one of the states of
 * tests/fuzz/snapshots.h, picked by the first byte.  Then operations until the input ends:
 * qfoc_drive_command() with any qfoc_cmd_t (power-on and fault-clear bits, any target, or
 * one folded into 0 .. rpm_max); every reader (qfoc_drive_state, _substate, _faults,
 * _first_fault, _status, _speed_rpm, _target_rpm, _run_requested, _angle_est,
 * _currents_q15, _vdc_q15); a tick without a frame at bench or any temperatures; 1 .. 64
 * fast steps of bench or any samples; 1 .. 256 ms of the bench with the master silent
 * (the commands above alone keep the link alive, or let it time out).
 *
 * Guarantees asserted after every call (drive.h; REQ-DRV-016, REQ-DRV-017, REQ-LINK-011):
 * the drive invariant; qfoc_drive_command() with a target <= rpm_max returns QFOC_LINK_OK
 * and changes exactly the link's command, seen, silent time (0), lost (!cfg_ok) and n_ok
 * (saturating), one above rpm_max returns QFOC_LINK_ERR_RANGE and changes exactly n_range:
 * the whole drive object is compared byte for byte with the documented change applied to
 * its copy; every reader returns the field its contract names and changes nothing; the
 * fault word and the first fault are 0 outside ERROR, equal and non-zero in ERROR; after a
 * tick the run request is off while the link is lost or before the first command, the
 * target is the link's, the speed is 0 while the control does not run, the temperature is
 * the hotter one; and after every tick and fast step those of fz_tick() and fz_fast().
 *
 * Requirements: REQ-FUZZ-005.
 */
#include "fuzz.h"
#include "snapshots.h"

int LLVMFuzzerInitialize(int *argc, char ***argv);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc;
    (void)argv;
    fz_snapshots_init();
    return 0;
}

#define BUDGET 15000L

static qfoc_drive_t before;
static qfoc_drive_t expect;

static void readers(const qfoc_drive_t *d)
{
    qfoc_status_t st;
    qfoc_dq_t i;
    memcpy(&before, d, sizeof before);
    FZ_CHECK(qfoc_drive_state(d) == d->s.sm.state, "state: the state");
    FZ_CHECK(qfoc_drive_substate(d) == d->s.sm.sub, "substate: the sub-state");
    FZ_CHECK(qfoc_drive_faults(d) == d->s.sm.faults, "faults: the fault word");
    FZ_CHECK(qfoc_drive_first_fault(d) == d->s.sm.first_fault, "first_fault: the first fault");
    if (qfoc_drive_state(d) == QFOC_STATE_ERROR) {
        FZ_CHECK(qfoc_drive_faults(d) != 0u && qfoc_drive_first_fault(d) == qfoc_drive_faults(d),
                 "faults: in ERROR the fault word is latched and equals the first fault");
    } else {
        FZ_CHECK(qfoc_drive_faults(d) == 0u && qfoc_drive_first_fault(d) == 0u,
                 "faults: 0 outside ERROR");
    }
    memset(&st, 0xC3, sizeof st);
    qfoc_drive_status(d, &st);
    FZ_CHECK(st.state == d->s.status.state && st.substate == d->s.status.substate &&
             st.faults == d->s.status.faults && st.speed_rpm == d->s.status.speed_rpm &&
             st.vdc_dv == d->s.status.vdc_dv && st.current_ca == d->s.status.current_ca &&
             st.temp_dc == d->s.status.temp_dc, "status: a copy of the last status");
    FZ_CHECK(qfoc_drive_speed_rpm(d) == d->s.status.speed_rpm, "speed_rpm: the status speed");
    FZ_CHECK(qfoc_drive_target_rpm(d) == d->s.cmd.target_rpm, "target_rpm: the command's");
    FZ_CHECK(qfoc_drive_run_requested(d) == d->s.cmd.power_on, "run_requested: the command's");
    FZ_CHECK(qfoc_drive_identify_requested(d) == d->s.cmd.identify,
             "identify_requested: the command's");
    FZ_CHECK(qfoc_drive_angle_est(d) == d->f.theta_est, "angle_est: the estimate");
    memset(&i, 0x3C, sizeof i);
    qfoc_drive_currents_q15(d, &i);
    FZ_CHECK(i.d == d->f.i_dq.d && i.q == d->f.i_dq.q, "currents_q15: the d/q currents");
    FZ_CHECK(qfoc_drive_vdc_q15(d) == d->f.vdc, "vdc_q15: the filtered bus");
    FZ_CHECK(memcmp(&before, d, sizeof before) == 0, "readers change nothing");
}

/* after a tick: the effective command in the readers */
static void after_tick(const qfoc_drive_t *d, const qfoc_tick_in_t *t)
{
    const qfoc_link_t *const l = &d->s.link;
    readers(d);
    FZ_CHECK(qfoc_drive_target_rpm(d) == l->cmd.target_rpm,
             "target_rpm: the last command taken");
    FZ_CHECK(!qfoc_drive_run_requested(d) || (l->seen && !l->lost && l->cmd.power_on),
             "run_requested: off before the first command and while the link is lost");
    FZ_CHECK(qfoc_drive_run_requested(d) == (l->seen && !l->lost && l->cmd.power_on),
             "run_requested: the last command's power-on while the link is alive");
    FZ_CHECK(qfoc_drive_identify_requested(d) == (l->seen && !l->lost && l->cmd.identify),
             "identify_requested: the last command's identify while the link is alive");
    FZ_CHECK(d->f.active || qfoc_drive_speed_rpm(d) == 0u, "speed_rpm: 0 while the PWM is off");
    {
        qfoc_status_t st;
        qfoc_drive_status(d, &st);
        FZ_CHECK(st.temp_dc == ((t->t_ipm > t->t_pcb) ? t->t_ipm : t->t_pcb),
                 "status: the hotter temperature");
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static fz_rig_t r;
    fz_in_t in = { data, size };
    long spent = 0;

    fz_snap_pick(&r, fz_u8(&in), 0xFFu);
    while (in.n > 0u && spent < BUDGET) {
        const uint8_t op = fz_u8(&in);
        switch (op % 6u) {
        case 0u:
        case 1u: { /* command */
            qfoc_cmd_t c;
            const uint8_t bits = fz_u8(&in);
            int32_t res;
            c.power_on = (bits & 1u) != 0u;
            c.fault_clear = (bits & 2u) != 0u;
            c.identify = (bits & 8u) != 0u;
            c.target_rpm = fz_u16(&in);
            if ((bits & 4u) == 0u) {
                c.target_rpm = (uint16_t)(c.target_rpm % ((uint32_t)r.d.s.link.cfg.rpm_max + 1u));
            }
            memcpy(&expect, &r.d, sizeof expect);
            res = qfoc_drive_command(&r.d, &c);
            if (c.target_rpm <= expect.s.link.cfg.rpm_max) {
                FZ_CHECK(res == QFOC_LINK_OK, "command: a target <= rpm_max is taken");
                fz_cmd_set(&expect.s.link.cmd, &c);
                expect.s.link.seen = true;
                expect.s.link.silent_ms = 0u;
                expect.s.link.lost = !expect.s.link.cfg_ok;
                expect.s.link.n_ok = fz_sat_inc(expect.s.link.n_ok);
            } else {
                FZ_CHECK(res == QFOC_LINK_ERR_RANGE, "command: a target > rpm_max is refused");
                expect.s.link.n_range = fz_sat_inc(expect.s.link.n_range);
            }
            FZ_CHECK(memcmp(&expect, &r.d, sizeof expect) == 0,
                     "command: changes exactly the link fields its contract assigns");
            FZ_CHECK(qfoc_drive_is_valid(&r.d), "command: the drive invariant holds");
            spent += 1;
            break;
        }
        case 2u: /* readers */
            readers(&r.d);
            spent += 1;
            break;
        case 3u: { /* a tick without a frame */
            qfoc_tick_in_t t;
            const uint8_t bits = fz_u8(&in);
            if ((bits & 1u) != 0u) {
                t.t_ipm = fz_i16(&in);
                t.t_pcb = fz_i16(&in);
            } else {
                t.t_ipm = r.t_ipm;
                t.t_pcb = r.t_pcb;
            }
            t.rx = NULL;
            t.rx_len = 0u;
            (void)fz_tick(&r.d, &t);
            r.ms++;
            after_tick(&r.d, &t);
            spent += 8;
            break;
        }
        case 4u: { /* fast steps */
            const uint8_t bits = fz_u8(&in);
            const int n = 1 + (bits & 63);
            int k;
            for (k = 0; k < n; k++) {
                qfoc_adc_t a = r.adc;
                if ((bits & 64u) != 0u) {
                    a.iu = fz_u16(&in);
                    a.iv = fz_u16(&in);
                    a.vdc = fz_u16(&in);
                }
                (void)fz_fast(&r.d, &a);
            }
            spent += n;
            break;
        }
        default: { /* the bench with a silent master */
            const int n = 1 + (int)fz_u8(&in);
            int k;
            int j;
            for (k = 0; k < n; k++) {
                qfoc_tick_in_t t;
                for (j = 0; j < r.ppm; j++) {
                    (void)fz_fast(&r.d, &r.adc);
                }
                t.t_ipm = r.t_ipm;
                t.t_pcb = r.t_pcb;
                t.rx = NULL;
                t.rx_len = 0u;
                (void)fz_tick(&r.d, &t);
                r.ms++;
            }
            after_tick(&r.d, &(qfoc_tick_in_t){ r.t_ipm, r.t_pcb, NULL, 0u });
            spent += (long)n * (r.ppm + 8);
            break;
        }
        }
    }
    return 0;
}
