/**
 * @file drive_rig.h
 * @brief The test rig shared by the drive tests (tests/test_drive*.c):
 *        one drive on a RAM copy of a table, synthetic ADC samples, and a master that
 *        sends the command frame every 10 ms through the sim's independent LIN encoder.
 *        Every fast step is checked for compare values within the period and the PWM
 *        enabled only in RUN; every tick for the drive invariant.
 *        A run request enters RUN in CATCH (flying start, REQ-DRV-027); the rig's motor
 *        stands, so CATCH ends in ALIGN (rig_catch_ms, rig_catch_ticks) after the ticks
 *        rig_catch_still_ticks counts, and the start-up is timed from there.
 *        Include after cmocka.h, test_util.h, qfoc/drive.h and drive_sim.h.
 */
#ifndef QFOC_TESTS_DRIVE_RIG_H
#define QFOC_TESTS_DRIVE_RIG_H

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* ADC code of a DC-bus voltage (4096 codes = V_base = 500 V) */
static inline uint16_t vdc_code(double v)
{
    return (uint16_t)floor(v / 500.0 * 4096.0 + 0.5);
}

typedef struct {
    qfoc_drive_t d;
    qfoc_param_table_t table;   /* RAM copy, so tests can change or corrupt it */
    qfoc_adc_t adc;
    qfoc_pwm_t pwm;
    qfoc_tick_out_t out;
    int16_t t_ipm;
    int16_t t_pcb;
    bool power_on;
    bool fault_clear;
    uint16_t rpm;
    bool send;                  /* the master sends a frame every 10 ms (rig_ms) */
    long ms;
    long enabled_outside_run;   /* enable seen while the state was not RUN */
    bool motor_current;         /* before each tick the phase monitor reads, on all three
                                   phases, the current the drive imposes (|i_align| or
                                   |i_start|; none in CATCH, the zero-current control of
                                   REQ-DRV-027): a connected motor, for tests that feed zero
                                   current samples; false: only what the samples give;
                                   and, in the same way, current codes that move (the
                                   stuck-sample counts at 0, REQ-DRV-020) */
    uint16_t n_fast_seen;       /* the fast-step count at the last tick */
    bool raw_count;             /* false: when fewer fast steps than f_pwm / 1000 ran since
                                   the last tick (none when the test plays the fast step),
                                   the rig adds the rest to the count (REQ-DRV-021); true:
                                   the count the fast steps give */
} rig_t;

/* A drive on a copy of t: 320 V, zero currents, 40 / 35 degC, the master sending rpm. */
static inline void rig_init_table(rig_t *r, const qfoc_param_table_t *t, uint16_t rpm)
{
    memset(r, 0, sizeof *r);
    r->table = *t;
    assert_int_equal(qfoc_drive_init(&r->d, &r->table), QFOC_PARAMS_OK);
    r->adc.iu = QFOC_ADC_MID;
    r->adc.iv = QFOC_ADC_MID;
    r->adc.vdc = vdc_code(320.0);
    r->t_ipm = 400;
    r->t_pcb = 350;
    r->send = true;
    r->rpm = rpm;
    r->motor_current = true;
}

/* command frame as the master sends it (sim/drive_sim.c's independent LIN encoder) */
static inline uint8_t rig_frame(const rig_t *r, uint8_t *f)
{
    f[0] = 0x55u;
    f[1] = dsim_lin_pid(r->table.drive.lin_id_cmd);
    f[2] = (uint8_t)((r->power_on ? 1u : 0u) | (r->fault_clear ? 2u : 0u));
    f[3] = (uint8_t)(r->rpm & 0xFFu);
    f[4] = (uint8_t)(r->rpm >> 8);
    f[5] = 0u;
    f[6] = dsim_lin_checksum(&f[1], 5);
    return 7u;
}

static inline void rig_fast(rig_t *r)
{
    const uint8_t st = r->d.s.sm.state;
    r->pwm = qfoc_drive_fast_step(&r->d, &r->adc);
    assert_true(r->pwm.cmp[0] <= r->table.svpwm.period);
    assert_true(r->pwm.cmp[1] <= r->table.svpwm.period);
    assert_true(r->pwm.cmp[2] <= r->table.svpwm.period);
    if (r->pwm.enable && (st != QFOC_STATE_RUN)) {
        r->enabled_outside_run++;
    }
    assert_true(!r->pwm.enable || (r->d.s.sm.state == QFOC_STATE_RUN));
}

/* REQ-DRV-022: the guard word of the tick's seven references (DRV_REF_GUARD of
   specs/drive.acsl): their sum plus 239013, modulo 2^16. */
static inline uint16_t rig_guard(const qfoc_drive_t *d)
{
    const long sum = (long)d->s.speed_target + (long)d->s.speed_ref + (long)d->s.ol_speed +
                     (long)d->s.id_ref + (long)d->s.iq_ref + (long)d->s.iq_lim +
                     (long)d->s.dt_dv + 239013L;
    return (uint16_t)(sum % 65536L);
}

/* after a test writes one of the references: the guard a tick would have left */
static inline void rig_reguard(rig_t *r)
{
    r->d.s.ref_guard = rig_guard(&r->d);
}

/* one tick with the bytes rx[0 .. len-1] received */
static inline void rig_tick_rx(rig_t *r, const uint8_t *rx, uint8_t len)
{
    qfoc_tick_in_t in;
    if (r->motor_current) {
        const int32_t ia = abs((int32_t)r->table.drive.i_align);
        const int32_t is = abs((int32_t)r->table.drive.i_start);
        const uint8_t sub = r->d.s.sm.sub;
        const int32_t i = (sub == QFOC_SUB_ALIGN) ? ia : ((sub == QFOC_SUB_CATCH) ? 0 : is);
        int k;
        for (k = 0; k < 3; k++) {
            r->d.f.phase.abs_lpf[k].state = i * 65536;
        }
        r->d.f.same_u = 0u;
        r->d.f.same_v = 0u;
    }
    if (!r->raw_count) {
        /* fewer fast steps than a millisecond holds (none when the test plays the fast
           step): the rig counts the rest */
        const uint32_t per_ms = (uint32_t)r->table.f_pwm_hz / 1000u;
        const uint32_t ran = ((uint32_t)r->d.f.n_fast + 65536u - (uint32_t)r->n_fast_seen) & 0xFFFFu;
        if (ran < per_ms) {
            r->d.f.n_fast = (uint16_t)(((uint32_t)r->n_fast_seen + per_ms) & 0xFFFFu);
        }
    }
    in.t_ipm = r->t_ipm;
    in.t_pcb = r->t_pcb;
    in.rx = rx;
    in.rx_len = len;
    r->out = qfoc_drive_tick(&r->d, &in);
    r->n_fast_seen = r->d.f.n_fast;
    r->ms++;
    assert_true(qfoc_drive_is_valid(&r->d));
    assert_int_equal(r->d.s.ref_guard, rig_guard(&r->d));
}

/* one tick, with the master's command frame when `frame` */
static inline void rig_tick(rig_t *r, bool frame)
{
    uint8_t f[QFOC_LIN_FRAME_MAX];
    const uint8_t len = frame ? rig_frame(r, f) : 0u;
    rig_tick_rx(r, f, len);
}

/* n ms of f_pwm / 1000 fast steps and one tick, the master's frame every 10 ms while
   r->send */
static inline void rig_ms(rig_t *r, int n)
{
    const int per_ms = (int)(r->table.f_pwm_hz / 1000u);
    int k;
    int j;
    for (k = 0; k < n; k++) {
        for (j = 0; j < per_ms; j++) {
            rig_fast(r);
        }
        rig_tick(r, r->send && ((r->ms % 10) == 0));
    }
}

/* The tick of the handover, counted from the tick that entered ALIGN, for an observer
   that follows the frame from the start (drive.h, REQ-DRV-006): ALIGN lasts align_ms
   ticks, the I/f ramp of_accel per tick reaches of_speed after ceil(of_speed / of_accel)
   ticks, that tick is the first of the ho_dwell_ms converged ticks; and not before
   cl_hold_ms. */
static inline long rig_ho_tick(const qfoc_param_table_t *t)
{
    const long w = (long)((t->drive.of_speed < 0) ? -t->drive.of_speed : t->drive.of_speed);
    const long a = (long)t->drive.of_accel;
    const long conv = (long)t->drive.align_ms + ((w + a - 1) / a) +
                      (long)t->drive.ho_dwell_ms - 1;
    return (conv > (long)t->drive.cl_hold_ms) ? conv : (long)t->drive.cl_hold_ms;
}

/* REQ-DRV-027 (flying start, catch.h): the ticks a standing rotor spends in CATCH, from
   the tick that entered RUN to the tick that enters ALIGN, when the loops' voltage
   command stays 0 (the rig's samples at the offsets, or ticks without fast steps).
   Computed here in double precision from catch.h's rules, not by the library: the first
   verdict comes in the tick after the RUN entry; the filter of qfoc_catch_step starts at
   32767 and moves an eighth of the way to |u| = 0 per tick, rounded away from zero
   (u_f - ceil(u_f / 8)), so the verdict is STILL (the speed 0 is below of_speed: never
   LOCK) from the n-th tick on, the first with u_f <= v_still = max(2 |flux_v_err|,
   e_min / 4), e_min = |of_speed| |psi_f| 2^s / 32768 (s = min(psi_shift, 4), the flux
   base; each quotient truncated); it must then
   hold for ho_dwell_ms ticks (0 reads as 1): ALIGN on tick n + dwell - 1. */
static inline long rig_catch_still_ticks(const qfoc_param_table_t *t)
{
    const int s = (t->drive.psi_shift < 4u) ? (int)t->drive.psi_shift : 4;
    const double e_min = trunc(fabs((double)t->drive.of_speed) * fabs((double)t->psi_f) *
                               ldexp(1.0, s) / 32768.0);
    const double v_still = fmax(2.0 * fabs((double)t->drive.flux_v_err), trunc(e_min / 4.0));
    const long dwell = (t->drive.ho_dwell_ms > 0u) ? (long)t->drive.ho_dwell_ms : 1L;
    double uf = 32767.0;
    long n = 0;
    do {
        uf -= ceil(uf / 8.0);
        n++;
    } while (uf > v_still);
    return n + dwell - 1;
}

/* one CATCH tick's checks (REQ-DRV-027): zero-current control, no fault */
static inline void rig_catch_check(const rig_t *r)
{
    assert_int_equal(r->d.s.sm.state, QFOC_STATE_RUN);
    assert_int_equal(r->d.s.sm.faults, 0u);
    if (r->d.s.sm.sub == QFOC_SUB_CATCH) {
        assert_int_equal(r->d.s.id_ref, 0);
        assert_int_equal(r->d.s.iq_ref, 0);
        assert_int_equal(r->d.s.iq_lim, 0);
        assert_int_equal(r->d.s.speed_ref, 0);
    }
}

/* the tick that left CATCH on the rig's standing rotor: to ALIGN, the state time
   restarted (the start-up is timed from here, as it was from the RUN entry), after
   exactly the ticks of rig_catch_still_ticks */
static inline long rig_catch_done(const rig_t *r, long ticks)
{
    assert_int_equal(r->d.s.sm.state, QFOC_STATE_RUN);
    assert_int_equal(r->d.s.sm.sub, QFOC_SUB_ALIGN);
    assert_int_equal(r->d.s.sm.t_state, 0u);
    assert_int_equal(r->d.s.sm.t_sub, 0u);
    assert_false(r->d.s.caught);
    assert_int_equal(ticks, rig_catch_still_ticks(&r->table));
    return ticks;
}

/* REQ-DRV-027: from the tick that entered RUN (sub-state CATCH), whole milliseconds
   (rig_ms: fast steps, PWM on, and the tick) until the sub-state leaves CATCH; on the
   rig's standing rotor it enters ALIGN.  Returns the ms spent in CATCH. */
static inline long rig_catch_ms(rig_t *r)
{
    long ms = 0;
    assert_int_equal(r->d.s.sm.state, QFOC_STATE_RUN);
    assert_int_equal(r->d.s.sm.sub, QFOC_SUB_CATCH);
    assert_int_equal(r->d.s.sm.t_state, 0u);
    rig_catch_check(r);
    while ((r->d.s.sm.sub == QFOC_SUB_CATCH) && (ms < 10000L)) {
        const int per_ms = (int)(r->table.f_pwm_hz / 1000u);
        int j;
        for (j = 0; j < per_ms; j++) {
            rig_fast(r);
            assert_true(r->pwm.enable);   /* zero-current control: the PWM on */
        }
        rig_tick(r, r->send && ((r->ms % 10) == 0));
        ms++;
        rig_catch_check(r);
    }
    return rig_catch_done(r, ms);
}

/* REQ-DRV-027: the same in ticks only (the test plays the fast step: the voltage command
   stays 0), the master's frame in every tick. */
static inline long rig_catch_ticks(rig_t *r)
{
    long k = 0;
    assert_int_equal(r->d.s.sm.state, QFOC_STATE_RUN);
    assert_int_equal(r->d.s.sm.sub, QFOC_SUB_CATCH);
    assert_int_equal(r->d.s.sm.t_state, 0u);
    rig_catch_check(r);
    while ((r->d.s.sm.sub == QFOC_SUB_CATCH) && (k < 10000L)) {
        rig_tick(r, true);
        k++;
        rig_catch_check(r);
    }
    return rig_catch_done(r, k);
}

#endif /* QFOC_TESTS_DRIVE_RIG_H */
