/**
 * @file ctrl.c
 * @brief Double-precision current controller on the true rotor angle, with the
 *        library's SVPWM producing the compare values (see sim.h).
 */
#include "sim.h"

#include "qfoc/svpwm.h"

#include <math.h>
#include <string.h>

#define SIM_SQRT3 1.73205080756887729353

void sim_ctrl_init(sim_ctrl_t *c, const sim_motor_t *m, double bw_hz)
{
    memset(c, 0, sizeof *c);
    c->m = *m;
    sim_bases(m, &c->b);
    c->bw_hz = bw_hz;
    c->u_margin = 0.92;
    c->dt_comp_s = m->dead_time_s;
}

/* Steady-state voltage magnitude at currents id, iq and electrical speed w. */
static double sim_ctrl_umag(const sim_motor_t *m, double id, double iq, double w)
{
    const double vd = m->rs_ohm * id - w * m->lq_h * iq;
    const double vq = m->rs_ohm * iq + w * (m->ld_h * id + m->psi_f_wb);
    return sqrt(vd * vd + vq * vq);
}

static double sim_ctrl_iq_for(const sim_motor_t *m, double torque, double id)
{
    const double k = 1.5 * m->pole_pairs * (m->psi_f_wb + (m->ld_h - m->lq_h) * id);
    return torque / k;
}

void sim_ctrl_torque_ref(sim_ctrl_t *c, double torque_nm, double w_e, double vdc)
{
    const sim_motor_t *m = &c->m;
    const double umax = c->u_margin * vdc / SIM_SQRT3;
    double id = 0.0;
    double iq = sim_ctrl_iq_for(m, torque_nm, 0.0);

    if (sim_ctrl_umag(m, 0.0, iq, w_e) > umax) {
        /* field weakening: the largest i_d <= 0 that keeps the steady-state
           voltage inside the limit (bisection; the magnitude falls with -i_d
           in the range searched) */
        double lo = -m->psi_f_wb / m->ld_h; /* characteristic current */
        double hi = 0.0;
        int k;
        for (k = 0; k < 60; k++) {
            const double mid = 0.5 * (lo + hi);
            const double iqm = sim_ctrl_iq_for(m, torque_nm, mid);
            if (sim_ctrl_umag(m, mid, iqm, w_e) > umax) {
                hi = mid;
            } else {
                lo = mid;
            }
        }
        id = lo;
        iq = sim_ctrl_iq_for(m, torque_nm, id);
    }
    c->id_ref = id;
    c->iq_ref = iq;
}

static int16_t sim_ctrl_q15(double x)
{
    double r = floor(x * 32768.0 + 0.5);
    if (r > 32767.0) {
        r = 32767.0;
    }
    if (r < -32767.0) {
        r = -32767.0;
    }
    return (int16_t)r;
}

void sim_ctrl_step(sim_ctrl_t *c, const sim_adc_t *adc, double theta_e, double w_e,
                   uint16_t cmp[3])
{
    const sim_motor_t *m = &c->m;
    const double ifs = m->i_full_scale_a;
    const double iu = ((double)adc->iu - 2048.0) / 2048.0 * ifs;
    const double iv = ((double)adc->iv - 2048.0) / 2048.0 * ifs;
    const double ia = iu;
    const double ib = (iu + 2.0 * iv) / SIM_SQRT3;
    const double vdc = (double)adc->vdc / 4096.0 * m->vdc_full_scale_v;
    const double T = c->b.t_s;
    const double wbw = 2.0 * SIM_PI * c->bw_hz;
    const double cs = cos(theta_e);
    const double sn = sin(theta_e);
    const double id = ia * cs + ib * sn;
    const double iq = -ia * sn + ib * cs;
    const double ed = c->id_ref - id;
    const double eq = c->iq_ref - iq;
    const double ffd = -w_e * m->lq_h * iq;
    const double ffq = w_e * (m->ld_h * id + m->psi_f_wb);
    const double umax = vdc / SIM_SQRT3;
    double vd;
    double vq;
    double mag;
    double th;
    double va;
    double vb;
    qfoc_svpwm_cfg_t cfg;
    qfoc_ab_t v_ab;
    qfoc_abc_t i_abc;
    qfoc_svpwm_out_t out;

    /* PI with pole-zero cancellation: kp = L w_bw, ki = R w_bw */
    c->int_d += m->rs_ohm * wbw * T * ed;
    c->int_q += m->rs_ohm * wbw * T * eq;
    vd = m->ld_h * wbw * ed + c->int_d + ffd;
    vq = m->lq_h * wbw * eq + c->int_q + ffq;
    mag = sqrt(vd * vd + vq * vq);
    if (mag > umax) {
        const double k = umax / mag;
        /* back-calculation: the integrators hold what the limited output allows */
        c->int_d = vd * k - m->ld_h * wbw * ed - ffd;
        c->int_q = vq * k - m->lq_h * wbw * eq - ffq;
        vd *= k;
        vq *= k;
    }
    /* applied during the period after next: centre 1.5 periods after the sample */
    th = theta_e + 1.5 * w_e * T;
    va = vd * cos(th) - vq * sin(th);
    vb = vd * sin(th) + vq * cos(th);
    c->v_ab_q15[0] = va / c->b.v_base;
    c->v_ab_q15[1] = vb / c->b.v_base;
    c->v_cmd[0] = sim_ctrl_q15(c->v_ab_q15[0]);
    c->v_cmd[1] = sim_ctrl_q15(c->v_ab_q15[1]);

    cfg.period = c->b.period;
    cfg.dt_comp = (uint16_t)lround(c->dt_comp_s / T * (double)c->b.period);
    cfg.i_deadband = sim_ctrl_q15(0.5 / c->b.i_base);
    cfg.vdc_min = sim_ctrl_q15(100.0 / c->b.v_base);
    v_ab.alpha = c->v_cmd[0];
    v_ab.beta = c->v_cmd[1];
    i_abc.u = sim_adc_current_q15(adc->iu);
    i_abc.v = sim_adc_current_q15(adc->iv);
    {
        int32_t w = -(int32_t)i_abc.u - (int32_t)i_abc.v;
        i_abc.w = (int16_t)((w > 32767) ? 32767 : ((w < -32767) ? -32767 : w));
    }
    qfoc_svpwm_step(&cfg, &v_ab, sim_adc_vdc_q15(adc->vdc), &i_abc, &out);
    cmp[0] = out.cmp[0];
    cmp[1] = out.cmp[1];
    cmp[2] = out.cmp[2];
}
