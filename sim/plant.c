/**
 * @file plant.c
 * @brief PMSM, inverter, load and sensing models (see sim.h and
 *        specs/reference-motor.md).
 */
#include "sim.h"

#include <math.h>
#include <string.h>

/* sqrt(3) and 1/sqrt(3) in double precision */
#define SIM_SQRT3 1.73205080756887729353
#define SIM_INV_SQRT3 0.57735026918962576451

/* ------------------------------------------------------------------ noise */

static uint32_t sim_xorshift(uint32_t *s)
{
    uint32_t x = *s;
    x ^= x << 13;
    x ^= x >> 17;
    x ^= x << 5;
    *s = x;
    return x;
}

static double sim_uniform(uint32_t *s)
{
    /* (0, 1], never 0 so that log() below is finite */
    return ((double)sim_xorshift(s) + 1.0) / 4294967296.0;
}

/* Standard normal sample (Box-Muller). */
static double sim_gauss(uint32_t *s)
{
    const double u1 = sim_uniform(s);
    const double u2 = sim_uniform(s);
    return sqrt(-2.0 * log(u1)) * cos(2.0 * SIM_PI * u2);
}

/* ------------------------------------------------------------------ helpers */

double sim_wrap_pi(double x)
{
    double y = fmod(x + SIM_PI, 2.0 * SIM_PI);
    if (y < 0.0) {
        y += 2.0 * SIM_PI;
    }
    return y - SIM_PI;
}

int16_t sim_adc_current_q15(uint16_t code)
{
    return (int16_t)(((int32_t)code - 2048) * 16);
}

int16_t sim_adc_vdc_q15(uint16_t code)
{
    return (int16_t)((int32_t)code * 8);
}

static uint16_t sim_adc(double counts)
{
    double c = floor(counts + 0.5);
    if (c < 0.0) {
        c = 0.0;
    }
    if (c > 4095.0) {
        c = 4095.0;
    }
    return (uint16_t)c;
}

/* ------------------------------------------------------------------ model */

double sim_theta_e(const sim_t *s)
{
    const double th = fmod(s->cfg.motor.pole_pairs * s->theta_m, 2.0 * SIM_PI);
    return (th < 0.0) ? th + 2.0 * SIM_PI : th;
}

double sim_w_e(const sim_t *s)
{
    return s->cfg.motor.pole_pairs * s->w_m;
}

static void sim_dq_to_ab(double id, double iq, double th, double out[2])
{
    out[0] = id * cos(th) - iq * sin(th);
    out[1] = id * sin(th) + iq * cos(th);
}

void sim_i_ab(const sim_t *s, double i_ab[2])
{
    sim_dq_to_ab(s->id, s->iq, s->cfg.motor.pole_pairs * s->theta_m, i_ab);
}

static double sim_te(const sim_motor_t *m, double id, double iq)
{
    /* amplitude-invariant transform: T_e = 3/2 n_p (psi_f i_q + (L_d - L_q) i_d i_q) */
    return 1.5 * m->pole_pairs * (m->psi_f_wb * iq + (m->ld_h - m->lq_h) * id * iq);
}

double sim_torque(const sim_t *s)
{
    return sim_te(&s->cfg.motor, s->id, s->iq);
}

static double sim_tl(const sim_load_t *l, double theta_m, double w_m)
{
    double t = l->t_mean + l->t_1x * sin(theta_m + l->phi_1x) + l->t_2x * sin(2.0 * theta_m + l->phi_2x);
    if (l->knee_rpm > 0.0) {
        /* passive load: opposes the motion, fades in over +-knee_rpm */
        const double x = w_m * 60.0 / (2.0 * SIM_PI) / l->knee_rpm;
        t *= (x > 1.0) ? 1.0 : ((x < -1.0) ? -1.0 : x);
    }
    return t;
}

double sim_load_torque(const sim_t *s)
{
    return sim_tl(&s->cfg.load, s->theta_m, s->w_m);
}

void sim_init(sim_t *s, const sim_cfg_t *cfg)
{
    memset(s, 0, sizeof *s);
    s->cfg = *cfg;
    if (s->cfg.substeps < 1) {
        s->cfg.substeps = 20;
    }
    sim_bases(&s->cfg.motor, &s->bases);
    s->rng = (cfg->seed != 0u) ? cfg->seed : 0x12345678u;
    s->cmp_active[0] = s->cmp_active[1] = s->cmp_active[2] = (uint16_t)(s->bases.period / 2u);
    memcpy(s->cmp_pending, s->cmp_active, sizeof s->cmp_pending);
    s->en_active = true;
    s->en_pending = true;
    s->extinct = false;
    s->inj.gain[0] = s->inj.gain[1] = 1.0;
    s->inj.vdc_gain = 1.0;
    s->inj.stuck[0] = s->inj.stuck[1] = s->inj.stuck[2] = -1;
    if (s->cfg.speed_locked) {
        s->w_m = s->cfg.locked_speed_e / s->cfg.motor.pole_pairs;
    }
    s->held = !s->cfg.speed_locked && s->cfg.load.t_break > 0.0;
}

void sim_set_state(sim_t *s, double theta_e, double w_e, double id, double iq)
{
    double th = fmod(theta_e, 2.0 * SIM_PI);
    if (th < 0.0) {
        th += 2.0 * SIM_PI;
    }
    s->theta_m = th / s->cfg.motor.pole_pairs;
    s->w_m = w_e / s->cfg.motor.pole_pairs;
    s->id = id;
    s->iq = iq;
    s->held = !s->cfg.speed_locked && s->cfg.load.t_break > 0.0 && w_e == 0.0;
}

void sim_sample(sim_t *s, sim_adc_t *adc)
{
    double i_ab[2];
    double iu;
    double iv;
    const double cps = 2048.0 / s->cfg.motor.i_full_scale_a; /* counts per ampere */
    double vdc = s->cfg.vdc_v;

    sim_i_ab(s, i_ab);
    iu = i_ab[0];
    iv = -0.5 * i_ab[0] + 0.5 * SIM_SQRT3 * i_ab[1];
    if (s->cfg.noise_i_rms_a > 0.0) {
        iu += s->cfg.noise_i_rms_a * sim_gauss(&s->rng);
        iv += s->cfg.noise_i_rms_a * sim_gauss(&s->rng);
    }
    if (s->cfg.noise_vdc_rms_v > 0.0) {
        vdc += s->cfg.noise_vdc_rms_v * sim_gauss(&s->rng);
    }
    adc->iu = sim_adc(2048.0 + iu * cps + s->cfg.adc_offset_counts);
    adc->iv = sim_adc(2048.0 + iv * cps + s->cfg.adc_offset_counts);
    adc->vdc = sim_adc(vdc / s->cfg.motor.vdc_full_scale_v * 4096.0);
    if (s->inj.sense) {
        const sim_inj_t *f = &s->inj;
        adc->iu = sim_adc(2048.0 + f->gain[0] * iu * cps + s->cfg.adc_offset_counts + f->offset[0]);
        adc->iv = sim_adc(2048.0 + f->gain[1] * iv * cps + s->cfg.adc_offset_counts + f->offset[1]);
        adc->vdc = sim_adc(f->vdc_gain * vdc / s->cfg.motor.vdc_full_scale_v * 4096.0);
        adc->iu = (f->stuck[0] >= 0) ? sim_adc((double)f->stuck[0]) : adc->iu;
        adc->iv = (f->stuck[1] >= 0) ? sim_adc((double)f->stuck[1]) : adc->iv;
        adc->vdc = (f->stuck[2] >= 0) ? sim_adc((double)f->stuck[2]) : adc->vdc;
    }
}

void sim_set_current_ab(sim_t *s, const double i_ab[2])
{
    const double th = sim_theta_e(s);
    s->id = i_ab[0] * cos(th) + i_ab[1] * sin(th);
    s->iq = -i_ab[0] * sin(th) + i_ab[1] * cos(th);
}

void sim_set_compare(sim_t *s, const uint16_t cmp[3])
{
    int k;
    for (k = 0; k < 3; k++) {
        s->cmp_pending[k] = (cmp[k] > s->bases.period) ? s->bases.period : cmp[k];
    }
    s->asym_pending = false;
}

void sim_set_compare2(sim_t *s, const uint16_t up[3], const uint16_t down[3])
{
    int k;
    for (k = 0; k < 3; k++) {
        s->up_pending[k] = (up[k] > s->bases.period) ? s->bases.period : up[k];
        s->down_pending[k] = (down[k] > s->bases.period) ? s->bases.period : down[k];
        s->cmp_pending[k] = (uint16_t)(((unsigned)s->up_pending[k] + s->down_pending[k]) / 2u);
    }
    s->asym_pending = true;
}

void sim_set_triggers(sim_t *s, const uint16_t trig[2], bool on)
{
    int j;
    for (j = 0; j < 2; j++) {
        s->trig_pending_v[j] = (trig[j] > s->bases.period) ? s->bases.period : trig[j];
    }
    s->trig_pending = on;
}

bool sim_sample_shunt(const sim_t *s, uint16_t code[2])
{
    code[0] = s->shunt_taken ? s->shunt_code[0] : 2048u;
    code[1] = s->shunt_taken ? s->shunt_code[1] : 2048u;
    return s->shunt_taken;
}

/*
 * Average pole voltage (against the DC-bus midpoint) of one phase over the
 * window [a, b] of the period [0, T], for compare value cmp and current sign.
 * Gate: high side commanded on in the centred interval [T/2 - Tx/2, T/2 + Tx/2],
 * Tx = T cmp / period.  Dead time td after each gate edge with both switches
 * off: the freewheeling diode makes the pole follow the current sign (low for
 * i > 0, high for i < 0), so a positive current loses td of high time at the
 * rising edge, a negative current gains td at the falling edge.
 */
static double sim_pole_avg(double a, double b, double T, double tx, double td, double i,
                           double vdc)
{
    double on0;
    double on1;
    double overlap = 0.0;

    if (tx >= T) {
        on0 = 0.0;
        on1 = T;
    } else if (tx <= 0.0) {
        on0 = 0.0;
        on1 = 0.0;
    } else if (i > 0.0) {
        on0 = 0.5 * (T - tx) + td;
        on1 = 0.5 * (T + tx);
    } else {
        on0 = 0.5 * (T - tx);
        on1 = fmin(T, 0.5 * (T + tx) + td);
    }
    if (on1 > on0) {
        const double lo = fmax(a, on0);
        const double hi = fmin(b, on1);
        if (hi > lo) {
            overlap = hi - lo;
        }
    }
    return vdc * (overlap / (b - a)) - 0.5 * vdc;
}

/*
 * The interval [on0, on1) of the period [0, T] in which a pole is high, for the
 * high-side gate on from T/2 - tu to T/2 + tdn (the up- and down-counting halves) and
 * the current sign, with the dead time td as in sim_pole_avg() (a symmetric pair tu =
 * tdn = Tx / 2 gives its interval).  on1 <= on0: never high.
 */
static void sim_pole_on(double T, double tu, double tdn, double td, double i, double *on0,
                        double *on1)
{
    if (tu + tdn >= T) {
        *on0 = 0.0;
        *on1 = T;
    } else if (tu + tdn <= 0.0) {
        *on0 = 0.0;
        *on1 = 0.0;
    } else if (i > 0.0) {
        *on0 = 0.5 * T - tu + td;
        *on1 = 0.5 * T + tdn;
    } else {
        *on0 = 0.5 * T - tu;
        *on1 = fmin(T, 0.5 * T + tdn + td);
    }
}

/* sim_pole_avg() for asymmetric gate times (up-counting tu, down-counting tdn). */
static double sim_pole_avg2(double a, double b, double T, double tu, double tdn, double td,
                            double i, double vdc)
{
    double on0;
    double on1;
    double overlap = 0.0;

    sim_pole_on(T, tu, tdn, td, i, &on0, &on1);
    if (on1 > on0) {
        const double lo = fmax(a, on0);
        const double hi = fmin(b, on1);
        if (hi > lo) {
            overlap = hi - lo;
        }
    }
    return vdc * (overlap / (b - a)) - 0.5 * vdc;
}

typedef struct {
    double id, iq, w_m, th_m;
} sim_x_t;

/* The derivative of a state x under the voltage v_ab (alpha, beta, V). */
typedef void (*sim_deriv_fn)(const sim_t *s, const sim_x_t *x, const double v_ab[2], sim_x_t *dx);

/* Mechanics: dw_m/dt for the currents id, iq (0 with the speed imposed). */
static double sim_accel(const sim_t *s, double id, double iq, double th_m, double w_m)
{
    const sim_motor_t *m = &s->cfg.motor;
    if (s->cfg.speed_locked || s->held) {
        return 0.0;
    }
    return (sim_te(m, id, iq) - sim_tl(&s->cfg.load, th_m, w_m) - m->b_nms * w_m) / m->j_kgm2;
}

static void sim_deriv(const sim_t *s, const sim_x_t *x, const double v_ab[2], sim_x_t *dx)
{
    const sim_motor_t *m = &s->cfg.motor;
    const double th = m->pole_pairs * x->th_m;
    const double we = m->pole_pairs * x->w_m;
    const double c = cos(th);
    const double sn = sin(th);
    const double vd = v_ab[0] * c + v_ab[1] * sn;
    const double vq = -v_ab[0] * sn + v_ab[1] * c;

    dx->id = (vd - m->rs_ohm * x->id + we * m->lq_h * x->iq) / m->ld_h;
    dx->iq = (vq - m->rs_ohm * x->iq - we * m->ld_h * x->id - we * m->psi_f_wb) / m->lq_h;
    dx->w_m = sim_accel(s, x->id, x->iq, x->th_m, x->w_m);
    dx->th_m = x->w_m;
}

static void sim_axpy(const sim_x_t *x, double h, const sim_x_t *d, sim_x_t *out)
{
    out->id = x->id + h * d->id;
    out->iq = x->iq + h * d->iq;
    out->w_m = x->w_m + h * d->w_m;
    out->th_m = x->th_m + h * d->th_m;
}

/* One classical RK4 step of h from x under a constant v_ab. */
static void sim_rk4(const sim_t *s, sim_deriv_fn f, const sim_x_t *x, const double v_ab[2], double h,
                    sim_x_t *out)
{
    sim_x_t k1, k2, k3, k4, tmp;
    f(s, x, v_ab, &k1);
    sim_axpy(x, 0.5 * h, &k1, &tmp);
    f(s, &tmp, v_ab, &k2);
    sim_axpy(x, 0.5 * h, &k2, &tmp);
    f(s, &tmp, v_ab, &k3);
    sim_axpy(x, h, &k3, &tmp);
    f(s, &tmp, v_ab, &k4);
    out->id = x->id + h / 6.0 * (k1.id + 2.0 * k2.id + 2.0 * k3.id + k4.id);
    out->iq = x->iq + h / 6.0 * (k1.iq + 2.0 * k2.iq + 2.0 * k3.iq + k4.iq);
    out->w_m = x->w_m + h / 6.0 * (k1.w_m + 2.0 * k2.w_m + 2.0 * k3.w_m + k4.w_m);
    out->th_m = x->th_m + h / 6.0 * (k1.th_m + 2.0 * k2.th_m + 2.0 * k3.th_m + k4.th_m);
}

/* ---- open phases (sim_inj_t) */

/* The axis phi of the only current path (one phase open): true; false when two or three
   phases are open and no current can flow. */
static bool sim_open_axis(unsigned open, double *phi)
{
    int n = 0;
    int j = 0;
    int k;
    for (k = 0; k < 3; k++) {
        if ((open & (1u << k)) != 0u) {
            n++;
            j = k;
        }
    }
    *phi = ((double)j * 120.0 + 90.0) * SIM_PI / 180.0;
    return n == 1;
}

/* L_e(theta) = L_d cos^2(theta - phi) + L_q sin^2(theta - phi) and psi_f cos(theta - phi). */
static double sim_open_l(const sim_motor_t *m, double th, double phi, double *psi_pm)
{
    const double c = cos(th - phi);
    const double sn = sin(th - phi);
    *psi_pm = m->psi_f_wb * c;
    return m->ld_h * c * c + m->lq_h * sn * sn;
}

/* The current along e from the flux linkage along it. */
static double sim_open_i(const sim_t *s, double psi_e, double th_m, double phi)
{
    double psi_pm;
    const double l = sim_open_l(&s->cfg.motor, s->cfg.motor.pole_pairs * th_m, phi, &psi_pm);
    return (psi_e - psi_pm) / l;
}

/* One phase open: x->id carries psi_e (Wb), x->iq is unused (0); v_ab[0] carries e . v. */
static void sim_deriv_open(const sim_t *s, const sim_x_t *x, const double v_ab[2], sim_x_t *dx)
{
    double phi;
    const sim_motor_t *m = &s->cfg.motor;
    const bool conducts = sim_open_axis(s->inj.open, &phi);
    const double th = m->pole_pairs * x->th_m;
    const double i = conducts ? sim_open_i(s, x->id, x->th_m, phi) : 0.0;
    /* i_ab = i e: i_d = i cos(phi - theta), i_q = i sin(phi - theta) */
    dx->id = conducts ? v_ab[0] - m->rs_ohm * i : 0.0;
    dx->iq = 0.0;
    dx->w_m = sim_accel(s, i * cos(phi - th), i * sin(phi - th), x->th_m, x->w_m);
    dx->th_m = x->w_m;
}

/* One sub-step of h with open phases. */
static void sim_step_open(sim_t *s, const double v_ab[2], double h)
{
    double phi;
    double psi_pm;
    const sim_motor_t *m = &s->cfg.motor;
    const bool conducts = sim_open_axis(s->inj.open, &phi);
    const double th = m->pole_pairs * s->theta_m;
    /* the current along e; the component along the open phase is cut */
    const double i0 = conducts ? s->id * cos(phi - th) + s->iq * sin(phi - th) : 0.0;
    const double l = sim_open_l(m, th, phi, &psi_pm);
    const double v_e[2] = { v_ab[0] * cos(phi) + v_ab[1] * sin(phi), 0.0 };
    const sim_x_t x = { l * i0 + psi_pm, 0.0, s->w_m, s->theta_m };
    sim_x_t y;
    double i;
    double th1;
    sim_rk4(s, sim_deriv_open, &x, v_e, h, &y);
    th1 = m->pole_pairs * y.th_m;
    i = conducts ? sim_open_i(s, y.id, y.th_m, phi) : 0.0;
    s->id = i * cos(phi - th1);
    s->iq = i * sin(phi - th1);
    s->w_m = y.w_m;
    s->theta_m = y.th_m;
}

/* Average phase-to-neutral voltages (alpha, beta) over the sub-step [a, a + h] of the
   period T, for the high-side times tx and the present phase currents; with tdn not
   NULL, tx and tdn are the asymmetric gate times of the up- and down-counting halves. */
static void sim_phase_v(const sim_t *s, double a, double h, double T, const double tx[3],
                        const double tdn[3], double v_ab[2])
{
    const double td = s->cfg.dead_time_s;
    const double vdc = s->cfg.vdc_v;
    double i_ab[2];
    double iph[3];
    double vp[3];
    double vn0;
    int j;

    sim_i_ab(s, i_ab);
    iph[0] = i_ab[0];
    iph[1] = -0.5 * i_ab[0] + 0.5 * SIM_SQRT3 * i_ab[1];
    iph[2] = -0.5 * i_ab[0] - 0.5 * SIM_SQRT3 * i_ab[1];
    for (j = 0; j < 3; j++) {
        if (s->en_active && tdn != NULL) {
            vp[j] = sim_pole_avg2(a, a + h, T, tx[j], tdn[j], td, iph[j], vdc);
        } else if (s->en_active) {
            vp[j] = sim_pole_avg(a, a + h, T, tx[j], td, iph[j], vdc);
        } else {
            /* switches off: the diode of the current's direction conducts */
            vp[j] = (iph[j] > 0.0) ? -0.5 * vdc : 0.5 * vdc;
        }
    }
    vn0 = (vp[0] + vp[1] + vp[2]) / 3.0;
    /* phase-to-neutral voltages, then amplitude-invariant Clarke */
    v_ab[0] = vp[0] - vn0;
    v_ab[1] = ((vp[1] - vn0) - (vp[2] - vn0)) * SIM_INV_SQRT3;
}

/* Breakaway torque: a held rotor starts when the torque on it exceeds t_break. */
static void sim_break_release(sim_t *s)
{
    if (s->held) {
        const double net = sim_te(&s->cfg.motor, s->id, s->iq) - sim_tl(&s->cfg.load, s->theta_m, 0.0);
        if (fabs(net) > s->cfg.load.t_break) {
            s->held = false;
        }
    }
}

/* ... and a turning rotor whose speed passes through zero (w0 before the sub-step) is
   held again. */
static void sim_break_catch(sim_t *s, double w0)
{
    if (!s->held && !s->cfg.speed_locked && s->cfg.load.t_break > 0.0 && w0 != 0.0 &&
        (w0 * s->w_m < 0.0 || s->w_m == 0.0)) {
        s->w_m = 0.0;
        s->held = true;
    }
}

/* The phase currents u, v, w now, A. */
static void sim_phase_i(const sim_t *s, double iph[3])
{
    double i_ab[2];
    sim_i_ab(s, i_ab);
    iph[0] = i_ab[0];
    iph[1] = -0.5 * i_ab[0] + 0.5 * SIM_SQRT3 * i_ab[1];
    iph[2] = -0.5 * i_ab[0] - 0.5 * SIM_SQRT3 * i_ab[1];
}

/* The DC-link current at instant t of the period, for the phase currents iph, with the
   ringing of the period's pole transitions (ring false: without it). */
static double sim_idc(const sim_t *s, double t, double T, const double tu[3],
                      const double tdn[3], const double iph[3], bool ring)
{
    const sim_shunt_cfg_t *c = &s->cfg.shunt;
    double idc = 0.0;
    int k;
    for (k = 0; k < 3; k++) {
        double on0;
        double on1;
        if (s->en_active) {
            sim_pole_on(T, tu[k], tdn[k], s->cfg.dead_time_s, iph[k], &on0, &on1);
        } else {
            /* switches off: the high-side diode conducts a negative current */
            on0 = 0.0;
            on1 = (iph[k] < 0.0) ? T : 0.0;
        }
        if (on1 > on0 && t >= on0 && t < on1) {
            idc += iph[k];
        }
        if (ring && c->t_ring_s > 0.0 && s->en_active && on1 > on0) {
            /* the rising transition steps i_dc by +i, the falling one by -i */
            const double e[2] = { on0, on1 };
            const double d[2] = { iph[k], -iph[k] };
            int m;
            for (m = 0; m < 2; m++) {
                const double x = t - e[m];
                if (e[m] > 0.0 && e[m] < T && x >= 0.0 && x < c->t_ring_s) {
                    idc += c->ring_gain * d[m] * exp(-3.0 * x / c->t_ring_s) *
                           cos(2.0 * SIM_PI * c->f_ring_hz * x);
                }
            }
        }
    }
    return idc;
}

/* One DC-link sample starting at t (the phase currents of now): the mean over the
   sample-and-hold aperture, converted by the ADC. */
static void sim_shunt_take(sim_t *s, int j, double t, double T, const double tu[3],
                           const double tdn[3])
{
    const sim_shunt_cfg_t *c = &s->cfg.shunt;
    const double cps = 2048.0 / s->cfg.motor.i_full_scale_a;
    double iph[3];
    double sum = 0.0;
    double x;
    int m;

    sim_phase_i(s, iph);
    s->shunt_iph[j][0] = iph[0];
    s->shunt_iph[j][1] = iph[1];
    s->shunt_iph[j][2] = iph[2];
    s->shunt_true[j] = sim_idc(s, t, T, tu, tdn, iph, false);
    if (c->t_sh_s > 0.0) {
        for (m = 0; m < 16; m++) {
            sum += sim_idc(s, t + ((double)m + 0.5) / 16.0 * c->t_sh_s, T, tu, tdn, iph, true);
        }
        x = sum / 16.0;
    } else {
        x = sim_idc(s, t, T, tu, tdn, iph, true);
    }
    if (s->inj.shunt_open) {
        x = 0.0;
    }
    if (s->cfg.noise_i_rms_a > 0.0) {
        x += s->cfg.noise_i_rms_a * sim_gauss(&s->rng);
    }
    s->shunt_code[j] = sim_adc(2048.0 + x * cps + s->cfg.adc_offset_counts + s->inj.shunt_offset);
}

/* One sub-step [a, a + hh] of the period: the state integrated under the voltage of the
   gate times (tdn NULL: symmetric tx), the sums of the period's averages weighted by
   hh / h. */
static void sim_substep(sim_t *s, double a, double hh, double T, const double tx[3],
                        const double tdn[3], double w, double vsum[2], double *tsum)
{
    double v_ab[2];
    const double w0 = s->w_m;
    sim_phase_v(s, a, hh, T, tx, tdn, v_ab);
    sim_break_release(s);
    if (s->inj.open == 0u) {
        const sim_x_t x = { s->id, s->iq, s->w_m, s->theta_m };
        sim_x_t y;
        sim_rk4(s, sim_deriv, &x, v_ab, hh, &y);
        s->id = y.id;
        s->iq = y.iq;
        s->w_m = y.w_m;
        s->theta_m = y.th_m;
    } else {
        sim_step_open(s, v_ab, hh);
    }
    sim_break_catch(s, w0);
    if (!s->en_active && (s->extinct || hypot(s->id, s->iq) < 0.3)) {
        s->extinct = true;
        s->id = 0.0;
        s->iq = 0.0;
        v_ab[0] = 0.0;
        v_ab[1] = 0.0;
    }
    vsum[0] += w * v_ab[0];
    vsum[1] += w * v_ab[1];
    *tsum += w * sim_te(&s->cfg.motor, s->id, s->iq);
}

/* The recording (sim_rec_t): one sample at the end of a uniform sub-step. */
static void sim_rec_sample(sim_t *s)
{
    sim_rec_t *r = s->rec;
    if (r != NULL) {
        if (r->n < r->cap) {
            double iph[3];
            const double th = s->cfg.motor.pole_pairs * s->theta_m;
            if (r->n > 0) {
                /* the mechanical angle's wrap at a period end is n_p whole electrical
                   turns; the angle moves far less than pi per sub-step otherwise */
                r->th_turns -= 2.0 * SIM_PI * floor((th - r->th_last) / (2.0 * SIM_PI) + 0.5);
            }
            r->th_last = th;
            sim_phase_i(s, iph);
            r->buf[4 * r->n] = th + r->th_turns;
            r->buf[4 * r->n + 1] = iph[0];
            r->buf[4 * r->n + 2] = iph[1];
            r->buf[4 * r->n + 3] = iph[2];
            r->n++;
        } else {
            r->dropped++;
        }
    }
}

void sim_record(sim_t *s, sim_rec_t *rec)
{
    s->rec = rec;
    if (rec != NULL) {
        rec->n = 0;
        rec->dropped = 0;
        rec->th_last = 0.0;
        rec->th_turns = 0.0;
    }
}

/* The period with asymmetric compare values or single-shunt samples: the uniform
   sub-steps, split at the samples' start instants. */
static void sim_step_asym(sim_t *s, double vsum[2], double *tsum)
{
    const double T = s->bases.t_s;
    const int n = s->cfg.substeps;
    const double h = T / (double)n;
    const double P = (double)s->bases.period;
    const bool take = s->cfg.shunt.active && s->trig_active;
    double tu[3];
    double tdn[3];
    double ts[2] = { 2.0 * T, 2.0 * T };
    bool done[2] = { !take, !take };
    int j;
    int k;

    for (j = 0; j < 3; j++) {
        const double up = s->asym_active ? (double)s->up_active[j] : (double)s->cmp_active[j];
        const double dn = s->asym_active ? (double)s->down_active[j] : (double)s->cmp_active[j];
        tu[j] = 0.5 * T * up / P;
        tdn[j] = 0.5 * T * dn / P;
    }
    if (take) {
        ts[0] = 0.5 * T * (double)s->trig_active_v[0] / P;
        ts[1] = 0.5 * T * (double)s->trig_active_v[1] / P;
    }
    for (k = 0; k < n; k++) {
        double a = (double)k * h;
        const double b = (double)(k + 1) * h;
        for (;;) {
            /* the next sample start in [a, b), if any (the earlier one first) */
            int nx = -1;
            for (j = 0; j < 2; j++) {
                if (!done[j] && ts[j] < b && (nx < 0 || ts[j] < ts[nx])) {
                    nx = j;
                }
            }
            if (nx < 0) {
                break;
            }
            if (ts[nx] > a) {
                sim_substep(s, a, ts[nx] - a, T, tu, tdn, (ts[nx] - a) / h, vsum, tsum);
                a = ts[nx];
            }
            sim_shunt_take(s, nx, a, T, tu, tdn);
            done[nx] = true;
        }
        if (b > a) {
            sim_substep(s, a, b - a, T, tu, tdn, (b - a) / h, vsum, tsum);
        }
        sim_rec_sample(s);
    }
    s->shunt_taken = take;
}

static void sim_period_end(sim_t *s, const double vsum[2], double tsum);

void sim_step_period(sim_t *s)
{
    const double T = s->bases.t_s;
    const int n = s->cfg.substeps;
    const double h = T / (double)n;
    double tx[3];
    double vsum[2] = { 0.0, 0.0 };
    double tsum = 0.0;
    int k;
    int j;

    if (s->asym_active || (s->cfg.shunt.active && s->trig_active)) {
        sim_step_asym(s, vsum, &tsum);
        sim_period_end(s, vsum, tsum);
        return;
    }
    s->shunt_taken = false;
    for (j = 0; j < 3; j++) {
        tx[j] = T * (double)s->cmp_active[j] / (double)s->bases.period;
    }
    for (k = 0; k < n; k++) {
        /* the weight 1.0 leaves the sums exactly those of the uniform sub-steps */
        sim_substep(s, (double)k * h, h, T, tx, NULL, 1.0, vsum, &tsum);
        sim_rec_sample(s);
    }
    sim_period_end(s, vsum, tsum);
}

void sim_sample_at(const sim_t *s, double tau, sim_adc_t *adc)
{
    sim_t c = *s;
    const double T = c.bases.t_s;
    const double h = T / (double)c.cfg.substeps;
    double tx[3];
    double vsum[2] = { 0.0, 0.0 };
    double tsum = 0.0;
    double a = 0.0;
    int j;

    c.rec = NULL;
    if (!c.asym_active && !(c.cfg.shunt.active && c.trig_active)) {
        for (j = 0; j < 3; j++) {
            tx[j] = T * (double)c.cmp_active[j] / (double)c.bases.period;
        }
        while ((tau - a) > 1e-15) {
            const double hh = fmin(h, tau - a);
            sim_substep(&c, a, hh, T, tx, NULL, hh / h, vsum, &tsum);
            a += hh;
        }
    }
    sim_sample(&c, adc);
}

/* The end of a period: the angle wrapped, the averages, the pending settings active. */
static void sim_period_end(sim_t *s, const double vsum[2], double tsum)
{
    const int n = s->cfg.substeps;
    const double T = s->bases.t_s;
    /* keep the mechanical angle in [0, 2 pi) without disturbing the electrical one
       (2 pi mechanical is n_p whole electrical turns) */
    s->theta_m = fmod(s->theta_m, 2.0 * SIM_PI);
    if (s->theta_m < 0.0) {
        s->theta_m += 2.0 * SIM_PI;
    }
    s->v_ab_avg[0] = vsum[0] / (double)n;
    s->v_ab_avg[1] = vsum[1] / (double)n;
    s->torque_avg = tsum / (double)n;
    s->t += T;
    memcpy(s->cmp_active, s->cmp_pending, sizeof s->cmp_active);
    memcpy(s->up_active, s->up_pending, sizeof s->up_active);
    memcpy(s->down_active, s->down_pending, sizeof s->down_active);
    s->asym_active = s->asym_pending;
    memcpy(s->trig_active_v, s->trig_pending_v, sizeof s->trig_active_v);
    s->trig_active = s->trig_pending;
    if (s->en_pending && !s->en_active) {
        s->extinct = false;
    }
    s->en_active = s->en_pending;
}

void sim_set_enable(sim_t *s, bool enable)
{
    s->en_pending = enable;
}
