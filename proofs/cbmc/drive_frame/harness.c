/*
 * CBMC harness: a malformed command frame never changes the drive (REQ-DRV-015,
 * REQ-LINK rules as seen by the drive).
 *
 * From ANY valid state of the state machine, the command link and the debouncers, one
 * tick receives ANY byte sequence of length 0 .. QFOC_LIN_FRAME_MAX; when the link's
 * decoder rejects it, the drive after the tick equals a twin that received no frame in
 * everything but the rejection counters: state, sub-state, fault word, first fault,
 * times, references and the effective command; and no status frame is sent.
 * The signal-processing functions are the stubs of ../drive_stubs.h.
 *
 * Methods: 1b any valid state of the state machine, the link and the debouncers; 1c
 * frame lengths 0 .. QFOC_LIN_FRAME_MAX; 1d any byte sequence the decoder rejects: a
 * malformed frame must change nothing
 */
#define DRIVE_STUBS_PURE
#include "../drive_stubs.h"
#include "../../../tables/reference_params.h"

int main(void)
{
    qfoc_drive_t d;
    qfoc_drive_t twin;
    const qfoc_param_table_t *const p = &qfoc_params_reference;
    const qfoc_drive_cfg_t *const c = &p->drive;
    qfoc_tick_in_t in;
    qfoc_tick_in_t none;
    qfoc_tick_out_t out;
    qfoc_tick_out_t out2;
    uint8_t rx[QFOC_LIN_FRAME_MAX];
    qfoc_cmd_t probe;
    qfoc_cmd_t a;
    qfoc_cmd_t b;
    unsigned j;

    stubs_fix();
    d.p = p;
    __CPROVER_assume(qfoc_sm_is_valid(&d.s.sm));
    __CPROVER_assume(qfoc_link_is_valid(&d.s.link));
    __CPROVER_assume(d.s.link.cfg.id_cmd == c->lin_id_cmd && d.s.link.cfg.id_status == c->lin_id_status &&
                     d.s.link.cfg.rpm_max == c->rpm_max && d.s.link.cfg.timeout_ms == c->link_timeout_ms &&
                     d.s.link.cfg.can_id_a == c->can_id_a && d.s.link.cfg.can_id_b == c->can_id_b);
    __CPROVER_assume(d.s.offset_u <= 4095u && d.s.offset_v <= 4095u);
    /* the calibration sums of the drive invariant: off_n samples of 12-bit codes */
    __CPROVER_assume(d.s.off_n <= 1024u);
    __CPROVER_assume(d.s.off_sum_u <= 4095u * (uint32_t)d.s.off_n &&
                     d.s.off_sum_v <= 4095u * (uint32_t)d.s.off_n);

    in.t_ipm = nondet_int16();
    in.t_pcb = nondet_int16();
    in.rx_len = (uint8_t)(nondet_uint8() % (QFOC_LIN_FRAME_MAX + 1u));
    for (j = 0u; j < QFOC_LIN_FRAME_MAX; j++) {
        rx[j] = nondet_uint8();
    }
    in.rx = rx;
    __CPROVER_assume(in.rx_len > 0u);
    __CPROVER_assume(qfoc_lin_decode_cmd(&d.s.link.cfg, rx, in.rx_len, &probe) != QFOC_LINK_OK);
    twin = d;
    none = in;
    none.rx_len = 0u;
    out = qfoc_drive_tick(&d, &in);
    out2 = qfoc_drive_tick(&twin, &none);

    __CPROVER_assert(d.s.sm.state == twin.s.sm.state && d.s.sm.sub == twin.s.sm.sub &&
                     d.s.sm.faults == twin.s.sm.faults && d.s.sm.first_fault == twin.s.sm.first_fault &&
                     d.s.sm.t_state == twin.s.sm.t_state && d.s.sm.t_sub == twin.s.sm.t_sub,
                     "REQ-DRV-015 malformed frame: same state as without it");
    __CPROVER_assert(d.s.speed_ref == twin.s.speed_ref && d.s.speed_target == twin.s.speed_target &&
                     d.s.iq_ref == twin.s.iq_ref && d.s.id_ref == twin.s.id_ref &&
                     d.s.ol_speed == twin.s.ol_speed,
                     "REQ-DRV-015 malformed frame: same references");
    qfoc_link_command(&d.s.link, &a);
    qfoc_link_command(&twin.s.link, &b);
    __CPROVER_assert(a.power_on == b.power_on && a.fault_clear == b.fault_clear &&
                     a.target_rpm == b.target_rpm && a.identify == b.identify &&
                     qfoc_link_lost(&d.s.link) == qfoc_link_lost(&twin.s.link),
                     "REQ-DRV-015 malformed frame: same effective command");
    __CPROVER_assert(out.tx_len == 0u, "REQ-DRV-015 malformed frame: not answered");
    return 0;
}
