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
   period T, for the high-side times tx and the present phase currents. */
static void sim_phase_v(const sim_t *s, double a, double h, double T, const double tx[3],
                        double v_ab[2])
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
        if (s->en_active) {
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

    for (j = 0; j < 3; j++) {
        tx[j] = T * (double)s->cmp_active[j] / (double)s->bases.period;
    }
    for (k = 0; k < n; k++) {
        double v_ab[2];
        const double w0 = s->w_m;
        sim_phase_v(s, (double)k * h, h, T, tx, v_ab);
        sim_break_release(s);
        if (s->inj.open == 0u) {
            const sim_x_t x = { s->id, s->iq, s->w_m, s->theta_m };
            sim_x_t y;
            sim_rk4(s, sim_deriv, &x, v_ab, h, &y);
            s->id = y.id;
            s->iq = y.iq;
            s->w_m = y.w_m;
            s->theta_m = y.th_m;
        } else {
            sim_step_open(s, v_ab, h);
        }
        sim_break_catch(s, w0);
        if (!s->en_active && (s->extinct || hypot(s->id, s->iq) < 0.3)) {
            s->extinct = true;
            s->id = 0.0;
            s->iq = 0.0;
            v_ab[0] = 0.0;
            v_ab[1] = 0.0;
        }
        vsum[0] += v_ab[0];
        vsum[1] += v_ab[1];
        tsum += sim_te(&s->cfg.motor, s->id, s->iq);
    }
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
    if (s->en_pending && !s->en_active) {
        s->extinct = false;
    }
    s->en_active = s->en_pending;
}

void sim_set_enable(sim_t *s, bool enable)
{
    s->en_pending = enable;
}
