/**
 * @file qfoc_drive_mon.c
 * @brief The drive's tick-evaluated monitors (drive.h, REQ-DRV-008, REQ-DRV-020,
 *        REQ-DRV-021, REQ-DRV-023, REQ-DRV-025): the bus and temperature thresholds, the
 *        fast step's new over-current trips, stall and the flux plausibility check, phase
 *        loss and ALIGN without current, the table's last check, the stuck current sample
 *        and the fast step's rate.  The tick (qfoc_drive.c) calls qfoc_drive_mon_tick(),
 *        qfoc_drive_mon_sensor() and qfoc_drive_mon_timing() once a millisecond, before
 *        the state machine.
 */
#include "qfoc/drive.h"
#include "qfoc/q15.h"
#include "qfoc/trig.h"
#include "qfoc/vector.h"
#include "qfoc_drive_mon.h"

/* Samples of 2 ms of fast steps: a current code unchanged that long is stuck. */
#define DRV_STUCK_MS 2u

/* Whether a healthy phase current can hold one code for DRV_STUCK_MS (REQ-DRV-020).  A
   noise-free sinusoid of amplitude A codes at electrical speed w holds a code longest at its
   peak, for at most 2 acos(1 - 1/A) / w; that is below the window T = DRV_STUCK_MS when
   A (1 - cos(w T / 2)) > 1.  The monitor judges only where A (1 - cos(w T / 2)) >= 3/2: the
   sampled run ends up to one period after the dwell (a factor 1.14 at 8 kHz and 50 Hz), and
   A is taken as max(|i_d|, |i_q|) <= |i_dq|, never above the amplitude.  In Q15 counts of
   current (16 per code): i (1 - cos) / 2 >= 12, the product rounded by qfoc_q15_mul.  Inside the
   table's dead band (svpwm.i_deadband) the current is no sinusoid: the dead time clamps it
   near its zero crossings, where it holds the zero code longer; the monitor judges only
   from there up.  The angle w T / 2
   is |speed_f| k_theta per period (2^32 per turn) over half the window, at most half a turn
   (from there a period is shorter than the window). */
/*@
  requires valid: \valid_read(d) && \valid_read(d->p);
  assigns \nothing;
*/
static bool mon_stuck_judged(const qfoc_drive_t *d)
{
    const qfoc_drive_fast_t *const f = &d->f;
    /* f_pwm <= 65535: at most 65 periods in half the window */
    const uint32_t half32 = ((uint32_t)d->p->f_pwm_hz / 1000u) * (DRV_STUCK_MS / 2u);
    const uint64_t half = (uint64_t)half32;
    /* the angle per period, |speed_f| x k_theta (2^32 per turn), each factor at most 32767 */
    const uint32_t k_theta = (uint32_t)d->p->pll.k_theta;
    const uint32_t k = (k_theta > 32767u) ? 32767u : k_theta;
    const uint64_t inc = (uint64_t)qfoc_q15_abs(f->speed_f) * (uint64_t)k;
    /* inc <= 32767^2 < 2^30, x 65: < 2^37 in uint64; in 2^16 per turn */
    const uint64_t th16 = (inc * half) / 65536u;
    const qfoc_angle_t th = (th16 >= 32768u) ? (qfoc_angle_t)32768u : (qfoc_angle_t)th16;
    const int32_t ad = (int32_t)qfoc_q15_abs(f->i_dq.d);
    const int32_t aq = (int32_t)qfoc_q15_abs(f->i_dq.q);
    const int32_t i_pk = (ad > aq) ? ad : aq;
    qfoc_sincos_t sc;
    qfoc_q15_t half_vers;
    qfoc_q15_t crit;
    qfoc_sincos(th, &sc);
    /* (1 - cos) / 2 in Q15: (32768 - cos) / 2, cos in -32767 .. 32767 */
    half_vers = (qfoc_q15_t)((32768 - (int32_t)sc.cosine) / 2);
    /* i (1 - cos) / 2 >= 12 Q15 counts: A (1 - cos) >= 3/2 with A = i / 16 codes */
    crit = qfoc_q15_mul((qfoc_q15_t)i_pk, half_vers);
    return (crit >= (qfoc_q15_t)((3 * QFOC_DRIVE_I_PER_CODE) / 4)) &&
           (i_pk >= (int32_t)d->p->svpwm.i_deadband);
}

/* public interface of the unit (qfoc_drive_mon.h) */
qfoc_q15_t qfoc_drive_li(int16_t l, qfoc_q15_t i)
{
    return qfoc_q15_sat(((int32_t)l * (int32_t)i) / 4096);
}

/* Tick-evaluated faults of the bus and the temperatures, and the fast step's new trips
   (fault.h; reaction times in drive.h, REQ-DRV-008). */
/*@
  requires valid: \valid(d) && \valid_read(d->p) && \valid_read(in);
  requires sep: \separated(&d->s, d->p) && \separated(&d->s, in);
  assigns d->s.db_ov, d->s.db_uv, d->s.db_ot_ipm, d->s.db_ot_pcb, d->s.trip_seen;
  ensures bits: \result <= QFOC_FAULT_OC + QFOC_FAULT_OV + QFOC_FAULT_UV +
                           QFOC_FAULT_OT_IPM + QFOC_FAULT_OT_PCB;
*/
static uint16_t drv_faults_power(qfoc_drive_t *d, const qfoc_tick_in_t *in)
{
    qfoc_drive_slow_t *const s = &d->s;
    const qfoc_drive_fast_t *const f = &d->f;
    const qfoc_param_table_t *const p = d->p;
    const qfoc_drive_cfg_t *const c = &p->drive;
    const bool run = (s->sm.state == QFOC_STATE_RUN);
    const uint8_t trips = f->trip_count;
    uint16_t w = 0u;

    /* over-current, detected by the fast step */
    if (trips != s->trip_seen) {
        w = (uint16_t)(w + QFOC_FAULT_OC);
        s->trip_seen = trips;
    } else {
        /* no new trip */
    }
    if (qfoc_debounce_step(&s->db_ov, qfoc_fault_over(f->vdc, p->vdc_ov), c->vdc_ms)) {
        w = (uint16_t)(w + QFOC_FAULT_OV);
    } else {
        /* bus not high */
    }
    if (qfoc_debounce_step(&s->db_uv, run && qfoc_fault_under(f->vdc, p->vdc_uv), c->vdc_ms)) {
        w = (uint16_t)(w + QFOC_FAULT_UV);
    } else {
        /* bus not low while running */
    }
    if (qfoc_debounce_step(&s->db_ot_ipm, qfoc_fault_over(in->t_ipm, c->t_ipm_max), c->temp_ms)) {
        w = (uint16_t)(w + QFOC_FAULT_OT_IPM);
    } else {
        /* IPM cool */
    }
    if (qfoc_debounce_step(&s->db_ot_pcb, qfoc_fault_over(in->t_pcb, c->t_pcb_max), c->temp_ms)) {
        w = (uint16_t)(w + QFOC_FAULT_OT_PCB);
    } else {
        /* PCB cool */
    }
    return w;
}

/* The fast flux plausibility check (REQ-DRV-023): the ticks of CLOSED_LOOP before it
   applies (the handover's transient), and the ticks in a row outside the band that raise
   STALL (the band: drv_flux_band).  The speed gate is 1.5 times the handover speed
   of_speed.  The ALIGN check (REQ-DRV-025) raises PHASE after the same ticks in a row. */
#define DRV_FLUX_BLANK_MS 100u
#define DRV_FLUX_TICKS ((uint16_t)2u)

/* A voltage (Q15 of V_base) in the flux base's units over a speed: v / 2^s rounded up
   (a band built from it is never narrower than the voltage's). */
/*@
  requires v: v <= 65533;
  assigns \nothing;
  ensures range: \result <= v;
*/
static uint32_t drv_v_flux(uint32_t v, uint8_t s)
{
    uint32_t r = (v + 15u) / 16u;
    if (s == 0u) {
        r = v;
    } else if (s == 1u) {
        r = (v + 1u) / 2u;
    } else if (s == 2u) {
        r = (v + 3u) / 4u;
    } else if (s == 3u) {
        r = (v + 7u) / 8u;
    } else {
        /* 4 and above: the largest flux base */
    }
    return r;
}

/* The fast flux check's band (REQ-DRV-023), from the estimator's error model: outside it
   when dev > flux_band psi_exp + (flux_v_err + flux_r_err R |i|) / (2^s |w|) (the magnet's
   temperature and the inductances; the dead-time voltage the compensation misses and the
   winding's resistance error over the speed, a voltage over a speed: a flux of 2^s times
   the table's flux base), with k = floor(flux_band psi_exp / 32768) and
   v = ceil((flux_v_err + floor(floor(flux_r_err R / 32768) |i| / 32768)) / 2^s):
   qfoc_fault_band_over. */
/*@
  requires valid: \valid_read(p) && \valid_read(f);
  assigns \nothing;
*/
static bool drv_flux_out(const qfoc_param_table_t *p, const qfoc_drive_fast_t *f,
                         qfoc_q15_t psi_exp, qfoc_q15_t dev)
{
    const qfoc_drive_cfg_t *const c = &p->drive;
    const uint32_t pe = (uint32_t)(int32_t)qfoc_q15_abs(psi_exp);
    const uint32_t fb = (uint32_t)(int32_t)qfoc_q15_abs(c->flux_band);
    const uint32_t k = (pe * fb) / 32768u;
    const uint32_t i = (uint32_t)(int32_t)qfoc_vec_mag(f->i_dq.d, f->i_dq.q);
    const uint32_t rr = ((uint32_t)(int32_t)qfoc_q15_abs(c->flux_r_err) *
                         (uint32_t)(int32_t)qfoc_q15_abs(p->flux.r)) / 32768u;
    const uint32_t v = (uint32_t)(int32_t)qfoc_q15_abs(c->flux_v_err) + ((rr * i) / 32768u);
    /*@ assert k: k <= 32766; */
    /*@ assert v: v <= 65533; */
    return qfoc_fault_band_over(dev, (qfoc_q15_t)k, (int32_t)drv_v_flux(v, c->psi_shift),
                                f->speed_f);
}

/* ALIGN without current (REQ-DRV-025): the last command's voltage beyond twice what the
   d reference needs, 2 (R |id_ref| + flux_v_err) (the resistance drop and the dead-time
   voltage the compensation may miss), while the largest filtered phase current (the phase
   monitor's) is below a quarter of the reference: both current sensors dead, or a broken
   connection, with the d PI driving the voltage up against a current it does not see. */
/*@
  requires valid: \valid_read(p) && \valid_read(f);
  requires inv: DRV_PHASE(&f->phase);
  assigns \nothing;
*/
static bool drv_align_open(const qfoc_param_table_t *p, const qfoc_drive_fast_t *f,
                           qfoc_q15_t id_ref)
{
    const uint32_t ir = (uint32_t)(int32_t)qfoc_q15_abs(id_ref);
    const uint32_t vr = ((uint32_t)(int32_t)qfoc_q15_abs(p->flux.r) * ir) / 32768u;
    const uint32_t ve = (uint32_t)(int32_t)qfoc_q15_abs(p->drive.flux_v_err);
    const uint32_t need = 2u * (vr + ve);
    const uint32_t u = (uint32_t)(int32_t)qfoc_vec_mag(f->u_last.alpha, f->u_last.beta);
    const uint32_t i = (uint32_t)(int32_t)qfoc_phase_mon_peak(&f->phase);
    return (u > need) && ((i * 4u) < ir);
}

/* The flux magnitude the observer should estimate: the active flux psi_f + (L_d - L_q) i_d. */
/*@
  requires valid: \valid_read(p) && \valid_read(f);
  assigns \nothing;
*/
static qfoc_q15_t drv_psi_exp(const qfoc_param_table_t *p, const qfoc_drive_fast_t *f)
{
    const qfoc_q15_t dl = qfoc_q15_sat((int32_t)p->ld - (int32_t)p->lq);
    return qfoc_q15_add(p->psi_f, qfoc_drive_li((int16_t)dl, f->i_dq.d));
}

/* The stall condition (REQ-DRV-008): in CLOSED_LOOP or STOPPING, the speed error or the
   flux magnitude off its expectation psi_f + (L_d - L_q) i_d (the active flux the observer
   estimates) beyond their tolerances; debounced over stall_ms by the caller. */
/*@
  requires valid: \valid_read(d) && \valid_read(d->p);
  assigns \nothing;
*/
static bool drv_stall_cond(const qfoc_drive_t *d)
{
    const qfoc_drive_slow_t *const s = &d->s;
    const qfoc_drive_fast_t *const f = &d->f;
    const qfoc_param_table_t *const p = d->p;
    const qfoc_drive_cfg_t *const c = &p->drive;
    const uint8_t sub = s->sm.sub;
    const bool closed = (s->sm.state == QFOC_STATE_RUN) &&
                        ((sub == QFOC_SUB_CLOSED_LOOP) || (sub == QFOC_SUB_STOPPING));
    const qfoc_q15_t e_speed = qfoc_q15_sub(s->speed_ref, f->speed_f);
    const qfoc_q15_t e_psi = qfoc_q15_sub(f->psi_mag, drv_psi_exp(p, f));
    const bool bad_speed = qfoc_fault_abs_over(e_speed, c->stall_err);
    const bool bad_flux = qfoc_fault_abs_over(e_psi, c->flux_tol);
    return closed && (bad_speed || bad_flux);
}

/* The fast flux plausibility check (REQ-DRV-023), in steady CLOSED_LOOP (after the blank,
   above 1.5 times the handover speed): the flux magnitude off its expectation by more than
   the band of drv_flux_out; and the rotor lost: in CLOSED_LOOP after the blank, the
   estimate below a quarter of the handover speed and of the reference (far below where the
   observer's angle is used at start-up); a seized compressor's estimate falls there within
   milliseconds, before the lost angle unsettles the current loops. */
/*@
  requires valid: \valid_read(d) && \valid_read(d->p);
  assigns \nothing;
*/
static bool drv_flux_implausible(const qfoc_drive_t *d)
{
    const qfoc_drive_slow_t *const s = &d->s;
    const qfoc_drive_fast_t *const f = &d->f;
    const qfoc_param_table_t *const p = d->p;
    const qfoc_drive_cfg_t *const c = &p->drive;
    const bool settled = (s->sm.state == QFOC_STATE_RUN) &&
                         (s->sm.sub == QFOC_SUB_CLOSED_LOOP) &&
                         ((uint32_t)s->sm.t_sub >= DRV_FLUX_BLANK_MS);
    const int32_t w = (int32_t)qfoc_q15_abs(f->speed_f);
    const int32_t ws = (int32_t)qfoc_q15_abs(c->of_speed);
    const bool lost = settled && ((w * 4) < ws) &&
                      ((w * 4) < (int32_t)qfoc_q15_abs(s->speed_ref));
    const bool steady = settled && ((w * 2) > (ws * 3));
    const qfoc_q15_t psi_exp = drv_psi_exp(p, f);
    const qfoc_q15_t dev = qfoc_q15_abs(qfoc_q15_sub(f->psi_mag, psi_exp));
    return lost || (steady && (psi_exp > 0) && drv_flux_out(p, f, psi_exp, dev));
}

/* The slow phase-loss condition (REQ-DRV-008, REQ-DRV-018): the filtered phase currents
   imbalanced while the rotor turns (RUN outside ALIGN); in ALIGN after its current ramp
   (the first half of align_ms) imbalanced beyond half the ratio (at the alignment angle a
   healthy machine gives min / max = 1/2 >= ratio / 2); or, there and in OPEN_LOOP, where
   the drive imposes |i_align| or |i_start|, the largest filtered phase current below a
   quarter of it (the current must reach the sensors). */
/*@
  requires valid: \valid_read(d) && \valid_read(d->p);
  requires inv: DRV_PHASE(&d->f.phase);
  assigns \nothing;
*/
static bool drv_phase_cond(const qfoc_drive_t *d)
{
    const qfoc_drive_slow_t *const s = &d->s;
    const qfoc_drive_fast_t *const f = &d->f;
    const qfoc_drive_cfg_t *const c = &d->p->drive;
    const uint8_t sub = s->sm.sub;
    const bool run = (s->sm.state == QFOC_STATE_RUN);
    const bool rotating = run && (sub != QFOC_SUB_ALIGN);
    const bool aligned = run && (sub == QFOC_SUB_ALIGN) &&
                         ((uint32_t)s->sm.t_sub >= ((uint32_t)c->align_ms / 2u));
    const bool open_loop = run && (sub == QFOC_SUB_OPEN_LOOP);
    const int32_t i_imposed = aligned ? (int32_t)qfoc_q15_abs(c->i_align)
                                      : (int32_t)qfoc_q15_abs(c->i_start);
    const qfoc_q15_t half_ratio = (qfoc_q15_t)(c->phase_ratio / 2);
    const bool imbalanced = rotating &&
                            qfoc_phase_mon_imbalanced(&f->phase, c->phase_i_min, c->phase_ratio);
    const bool align_imbalanced = aligned &&
                                  qfoc_phase_mon_imbalanced(&f->phase, c->phase_i_min, half_ratio);
    const bool no_current = (aligned || open_loop) &&
                            (((int32_t)qfoc_phase_mon_peak(&f->phase) * 4) < i_imposed);
    return imbalanced || align_imbalanced || no_current;
}

/* Tick-evaluated faults of the motor and the table: stall and flux plausibility, phase
   loss and ALIGN without current, table re-check (fault.h; reaction times in drive.h,
   REQ-DRV-008, REQ-DRV-010, REQ-DRV-023, REQ-DRV-025). */
/*@
  requires valid: \valid(d) && \valid_read(d->p);
  requires sep: \separated(&d->s, d->p);
  requires inv: DRV_PHASE(&d->f.phase);
  assigns d->s.db_stall, d->s.db_flux, d->s.db_phase, d->s.db_align;
  ensures bits: \result <= QFOC_FAULT_STALL + QFOC_FAULT_PHASE + QFOC_FAULT_PARAM;
*/
static uint16_t drv_faults_motor(qfoc_drive_t *d)
{
    qfoc_drive_slow_t *const s = &d->s;
    const qfoc_drive_cfg_t *const c = &d->p->drive;
    const bool stall = drv_stall_cond(d);
    const bool implausible = drv_flux_implausible(d);
    const bool phase = drv_phase_cond(d);
    const bool open_align = (s->sm.state == QFOC_STATE_RUN) && (s->sm.sub == QFOC_SUB_ALIGN) &&
                            drv_align_open(d->p, &d->f, s->id_ref);
    const bool stall_slow = qfoc_debounce_step(&s->db_stall, stall, c->stall_ms);
    const bool stall_fast = qfoc_debounce_step(&s->db_flux, implausible, DRV_FLUX_TICKS);
    const bool phase_slow = qfoc_debounce_step(&s->db_phase, phase, c->phase_ms);
    const bool phase_fast = qfoc_debounce_step(&s->db_align, open_align, DRV_FLUX_TICKS);
    uint16_t w = 0u;

    if (stall_slow || stall_fast) {
        w = (uint16_t)(w + QFOC_FAULT_STALL);
    } else {
        /* synchronised, the flux plausible */
    }
    if (phase_slow || phase_fast) {
        w = (uint16_t)(w + QFOC_FAULT_PHASE);
    } else {
        /* balanced, the current where the voltage drives it */
    }
    if (!s->table_ok) {
        w = (uint16_t)(w + QFOC_FAULT_PARAM);
    } else {
        /* table intact */
    }
    return w;
}

/* public interface of the unit (qfoc_drive_mon.h) */
uint16_t qfoc_drive_mon_tick(qfoc_drive_t *d, const qfoc_tick_in_t *in)
{
    const uint16_t w_power = drv_faults_power(d, in);
    const uint16_t w_motor = drv_faults_motor(d);

    return (uint16_t)(w_power + w_motor);
}

/* The stuck-sample monitor (REQ-DRV-020): in CLOSED_LOOP and STOPPING, while the stall
   condition is false and the current is one a healthy phase cannot hold on a code for the
   window (mon_stuck_judged), one current code unchanged for DRV_STUCK_MS ms of fast steps
   while the other's moved gives OFFSET.  Read while the fast step may pre-empt: each count is one
   16-bit word. */
bool qfoc_drive_mon_sensor(const qfoc_drive_t *d)
{
    const qfoc_drive_fast_t *const f = &d->f;
    const qfoc_param_table_t *const p = d->p;
    const uint8_t sub = d->s.sm.sub;
    const bool closed = (d->s.sm.state == QFOC_STATE_RUN) &&
                        ((sub == QFOC_SUB_CLOSED_LOOP) || (sub == QFOC_SUB_STOPPING));
    /* f_pwm <= 65535: at most 65 x DRV_STUCK_MS samples */
    const uint32_t n_stuck = ((uint32_t)p->f_pwm_hz / 1000u) * DRV_STUCK_MS;
    const bool still_u = ((uint32_t)f->same_u >= n_stuck);
    const bool still_v = ((uint32_t)f->same_v >= n_stuck);
    /* one channel still while the other moves: where a healthy current is slowest (its
       peak), the other phase's is near its steepest */
    const bool stuck = (still_u && !still_v) || (still_v && !still_u);
    /* not while the stall condition holds (db_stall counting): a rotor at standstill
       carries a DC current, which STALL reports */
    const bool rotating = (d->s.db_stall.count == 0u);
    return closed && rotating && stuck && mon_stuck_judged(d);
}

/* The timing monitor (REQ-DRV-021): in RUN, the fast steps since the previous tick against
   f_pwm / 1000 a tick, 2 either side for the phase of the two interrupts and their
   latencies.  n_fast is one 16-bit word the fast step writes; the difference is taken
   mod 2^16.  Records the count for the next tick. */
bool qfoc_drive_mon_timing(qfoc_drive_t *d)
{
    const uint32_t n = (uint32_t)d->f.n_fast;
    const uint32_t steps = (n + 65536u - (uint32_t)d->s.fast_seen) & 0xFFFFu;
    const uint32_t f_pwm = (uint32_t)d->p->f_pwm_hz;
    const uint32_t lo = f_pwm / 1000u;
    const uint32_t hi = (f_pwm + 999u) / 1000u;
    const bool run = (d->s.sm.state == QFOC_STATE_RUN);
    d->s.fast_seen = (uint16_t)n;
    return run && (((steps + 2u) < lo) || (steps > (hi + 2u)));
}
