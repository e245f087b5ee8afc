/*
 * test_ident.c -- unit tests of the standstill identification (include/qfoc/ident.h).
 *
 * Reference: the rules of ident.h, written here from the header, and a double-precision
 * R-L model of the motor at standstill, one first-order axis per stationary axis:
 *     i[k+1] = a i[k] + b u[k],  a = exp(-T R / L),  b = (1 - a) / R,
 * in Q15 units (currents Q15 of I_base, voltages Q15 of V_base, R in V_base / I_base).
 * The voltage u[k] that acts in period k is the one the header reconstructs from the
 * compare values written in period k - 1 (one period delay):
 *     u_alpha = (2 cmp_u - cmp_v - cmp_w) V_dc / (3 P),  u_beta = (cmp_v - cmp_w) V_dc / (sqrt 3 P),
 * zero while the PWM is off.  The model adds an inverter voltage error v_err opposing the
 * alpha current (which the R_LO / R_HI difference cancels, as the header says) and, for
 * a turning rotor, a back-EMF e on beta (u_beta - e acts).  The currents the mode sees
 * are the model's, rounded to Q15.
 *
 * Checked against that reference: the schedule (n_align + 5 n_settle + n_ramp +
 * 6 2^win_shift periods, the step of every period), the window sums recomputed here from
 * the inputs and the outputs of every period (cos and sin of 2 pi k / 16 computed here, k
 * the periods since the start; in PSI of the rotating current's angle, recomputed here
 * from the header's speed ramp, with a slack for the Q15 sine table and the rounded
 * transform), the stator resistance from R_LO and R_HI, the admittance I / U at
 * f_pwm / 16 of L_D and L_Q against the model's b e^{-jw} / (e^{jw} - a), PSI's rotating
 * current (in the rotating frame at its level; its phasor i_hi / 2 per period), the
 * reference ramp, every bound of the header with its boundary, and the frames decoded
 * back.
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>
#include <math.h>
#include <complex.h>
#include <stdlib.h>
#include <string.h>
#include <stdbool.h>

#include "qfoc/ident.h"
#define TEST_SEED 0x1DE47u
#include "test_util.h"

#define PI_D 3.14159265358979323846
#define NSTEP 6   /* steps of the header: ALIGN .. PSI */
#define NF 15     /* fields of qfoc_ident_sums_t */
#define SQRT3_D 1.73205080756887729353

/* ---- the configuration and the model ------------------------------------------ */

/* the DC bus of the runs, Q15 of V_base (0.8), with a small ripple of +-3 LSB */
#define VDC_NOM 26214
#define PERIOD 5000u

static int16_t bus_at(int p)
{
    return (int16_t)(VDC_NOM + ((p % 7) - 3));
}

/* A valid configuration: levels 0.1 and 0.2 of I_base, bound 0.4, a ramp of 100 LSB per
   period, injection 0.05 of V_base at first (at most 0.25; the injected current's
   amplitude aimed at 800 LSB, so that L_D keeps its first amplitude on the model and L_Q
   doubles it once), v_move 300 LSB, PSI's current turning 1024 counts
   per period (64 periods a turn: two turns a half window) after a ramp of 256 periods,
   the current PI kp = 2, ki T = 0.1
   (its zero kp / (kp + ki T) = 0.952 next to the model's alpha pole a = 0.95), limits
   +-16000, a period of 5000 ticks. */
static qfoc_ident_cfg_t base_cfg(void)
{
    qfoc_ident_cfg_t c;
    memset(&c, 0, sizeof c);
    c.i_lo = 3277;
    c.i_hi = 6554;
    c.i_lim = 13107;
    c.i_ramp = 100;
    c.v_inj = 1638;
    c.v_inj_max = 8192;
    c.i_inj = 800;
    c.v_move = 300;
    c.vdc_min = 16384;
    c.vdc_max = 30000;
    c.n_align = 300u;
    c.n_settle = 200u;
    c.win_shift = 8u;
    c.w_psi = 1024u;
    c.n_ramp = 256u;
    c.pi.kp = 16384;
    c.pi.kp_shift = 2u;
    c.pi.ki = 3277;
    c.pi.ki_shift = 0u;
    c.pi.out_min = -16000;
    c.pi.out_max = 16000;
    c.pwm.period = (uint16_t)PERIOD;
    c.pwm.dt_comp = 0u;
    c.pwm.i_deadband = 0;
    c.pwm.vdc_min = 1000;
    return c;
}

typedef struct {
    double r;           /* stator resistance, V_base / I_base */
    double a_d, a_q;    /* per-period decay of the alpha (d) and beta (q) currents */
    double v_err;       /* inverter voltage error, Q15 V_base, opposing the alpha current */
    double emf;         /* back-EMF on beta, Q15 V_base, from period emf_from on */
    int emf_from;
    bool open;          /* an open phase: no current flows */
    double ia, ib;      /* the currents, Q15 LSB */
    qfoc_pwm_t acting;  /* the output written in the last period, acting in this one */
} plant_t;

static plant_t base_plant(void)
{
    plant_t pl;
    memset(&pl, 0, sizeof pl);
    pl.r = 0.5;
    pl.a_d = 0.95;
    pl.a_q = 0.97;
    pl.v_err = 200.0;
    pl.emf = 0.0;
    pl.emf_from = 0;
    pl.open = false;
    pl.acting.enable = false;
    return pl;
}

static double sgn(double x)
{
    return (x > 0.0) ? 1.0 : ((x < 0.0) ? -1.0 : 0.0);
}

/* a current of the model as the mode samples it: rounded, saturated to int16 */
static int16_t sample(double x)
{
    const double r = round(x);
    return (int16_t)((r > 32767.0) ? 32767.0 : ((r < -32768.0) ? -32768.0 : r));
}

/* the voltages of compare values on a bus (the header's reconstruction), Q15 V_base */
static double u_alpha_of(const uint16_t *cmp, double vdc)
{
    return ((2.0 * cmp[0]) - cmp[1] - cmp[2]) * vdc / (3.0 * (double)PERIOD);
}

static double u_beta_of(const uint16_t *cmp, double vdc)
{
    return ((double)cmp[1] - (double)cmp[2]) * vdc / (SQRT3_D * (double)PERIOD);
}

/* period p of the model: the output written in period p - 1 acts on the bus of period p */
static void plant_advance(plant_t *pl, int p, double vdc)
{
    double ua = 0.0;
    double ub = 0.0;
    if (pl->acting.enable) {
        ua = u_alpha_of(pl->acting.cmp, vdc);
        ub = u_beta_of(pl->acting.cmp, vdc);
    }
    ua -= pl->v_err * sgn(pl->ia);
    if (p >= pl->emf_from) {
        ub -= pl->emf;
    }
    if (pl->open) {
        pl->ia = 0.0;
        pl->ib = 0.0;
    } else {
        pl->ia = (pl->a_d * pl->ia) + (((1.0 - pl->a_d) / pl->r) * ua);
        pl->ib = (pl->a_q * pl->ib) + (((1.0 - pl->a_q) / pl->r) * ub);
    }
}

/* ---- a run and its log -------------------------------------------------------- */

typedef struct {
    int16_t ia, ib, vdc;   /* the inputs */
    qfoc_pwm_t out;        /* the output */
    uint8_t step_before;   /* qfoc_ident_step_now() before the call */
    uint8_t step_after;
    uint8_t result;        /* qfoc_ident_result() after the call */
    int16_t ref_before, ref_after;
} plog_t;

#define LOG_MAX 4000
static plog_t lg[LOG_MAX];

/* Run the mode on the model until it ends (or max periods); every period logged while
   the log has room.  Returns the number of periods run. */
static int run_plant(qfoc_ident_t *id, plant_t *pl, int max)
{
    int p = 0;
    while ((p < max) && (qfoc_ident_result(id) == QFOC_IDENT_RUNNING)) {
        qfoc_ab_t i;
        qfoc_pwm_t out;
        const int16_t vdc = bus_at(p);
        const uint8_t s0 = qfoc_ident_step_now(id);
        const int16_t r0 = id->ref;
        i.alpha = sample(pl->ia);
        i.beta = sample(pl->ib);
        out = qfoc_ident_step(id, &i, vdc);
        if (p < LOG_MAX) {
            lg[p].ia = i.alpha;
            lg[p].ib = i.beta;
            lg[p].vdc = vdc;
            lg[p].out = out;
            lg[p].step_before = s0;
            lg[p].step_after = qfoc_ident_step_now(id);
            lg[p].result = qfoc_ident_result(id);
            lg[p].ref_before = r0;
            lg[p].ref_after = id->ref;
        }
        plant_advance(pl, p, (double)vdc);
        pl->acting = out;
        p++;
    }
    return p;
}

/* one period with given inputs */
static qfoc_pwm_t feed(qfoc_ident_t *id, int alpha, int beta, int vdc)
{
    qfoc_ab_t i;
    i.alpha = (int16_t)alpha;
    i.beta = (int16_t)beta;
    return qfoc_ident_step(id, &i, (int16_t)vdc);
}

/* ---- the reference schedule and sums ------------------------------------------ */

static int settle_of(const qfoc_ident_cfg_t *c, int s)
{
    return (s == 0) ? (int)c->n_align :
           ((s == 5) ? ((int)c->n_ramp + (int)c->n_settle) : (int)c->n_settle);
}

/* PSI's angle at the start of its period o, 65536 counts a turn: the speed w_psi o /
   n_ramp (rounded down) on the ramp, w_psi after it, added period by period */
static unsigned ref_theta(const qfoc_ident_cfg_t *c, int o)
{
    unsigned th = 0u;
    int j;
    for (j = 0; j < o; j++) {
        const unsigned w = (j < (int)c->n_ramp) ?
                           (unsigned)(((long)c->w_psi * j) / (long)c->n_ramp) : c->w_psi;
        th = (th + w) % 65536u;
    }
    return th;
}

/* the step of period p of a mode that keeps running (offset: the period within it) */
static int ref_step(const qfoc_ident_cfg_t *c, int p, int *offset)
{
    int s = 0;
    int start = 0;
    while (s < (NSTEP - 1)) {
        const int len = settle_of(c, s) + (1 << c->win_shift);
        if (p < start + len) {
            break;
        }
        start += len;
        s++;
    }
    *offset = p - start;
    return s;
}

static int ref_total(const qfoc_ident_cfg_t *c)
{
    return (int)c->n_align + (5 * (int)c->n_settle) + (int)c->n_ramp +
           (NSTEP * (1 << c->win_shift));
}

/* rounded 32767 cos and sin of 2 pi k / 16, computed here */
static int64_t ref_cos(int k)
{
    return (int64_t)round(32767.0 * cos(2.0 * PI_D * (double)k / 16.0));
}

static int64_t ref_sin(int k)
{
    return (int64_t)round(32767.0 * sin(2.0 * PI_D * (double)k / 16.0));
}

/* the 15 fields of a half window, in the header's order */
typedef struct {
    int64_t f[NF];
} rsums_t;

enum { F_N, F_IA, F_IB, F_UA, F_UB, F_VDC, F_VB, F_UC, F_US, F_VC, F_VS, F_IC, F_IS, F_JC,
       F_JS };

static int64_t field_of(const qfoc_ident_sums_t *z, int f)
{
    const int64_t v[NF] = { z->n, z->i_a, z->i_b, z->u_a, z->u_b, z->vdc, z->vb_cmd,
                            z->u_c, z->u_s, z->v_c, z->v_s, z->i_c, z->i_s, z->j_c, z->j_s };
    return v[f];
}

/* the record of the logged periods 0 .. n - 1, from the inputs and the outputs, and the
   slack of each field: zero, except for the voltage sums of the half that holds a
   period which ended the mode, and for PSI's rotating frame.  A period that ended the
   mode has its output disabled, so the compare values the mode modulated (and summed)
   need not be the ones it returned: the slack is the largest term of that period,
   |2 cmp_u - cmp_v - cmp_w| <= 2 P, |cmp_v - cmp_w| <= P, times 32767 in the products.
   In PSI the reference cosine and sine are the Q15 sine table's (within 1 LSB of
   32767 cos and sin, trig.h) and the current in the rotating frame is the rounded,
   saturated transform (within 1 LSB of its exact value, plus the table's error times
   |i| / 32768 <= 1 LSB per component): the slack is 2 |x| per product term and 3 LSB per
   current term, recomputed here in double precision from the exact angle. */
static void ref_record(const qfoc_ident_cfg_t *c, int n, rsums_t rec[NSTEP][2],
                       rsums_t slack[NSTEP][2])
{
    int p;
    memset(rec, 0, sizeof(rsums_t) * 2u * NSTEP);
    memset(slack, 0, sizeof(rsums_t) * 2u * NSTEP);
    for (p = 0; p < n; p++) {
        int o;
        const int s = ref_step(c, p, &o);
        const int settle = settle_of(c, s);
        if (o >= settle) {
            const int h = ((o - settle) >= (1 << (c->win_shift - 1))) ? 1 : 0;
            const uint16_t *cmp = lg[p].out.cmp;
            const int64_t ua = (2 * (int64_t)cmp[0]) - cmp[1] - cmp[2];
            const int64_t ub = (int64_t)cmp[1] - cmp[2];
            const int64_t ia = lg[p].ia;
            const int64_t ib = lg[p].ib;
            int64_t *f = rec[s][h].f;
            int64_t *sl = slack[s][h].f;
            int64_t cs;
            int64_t sn;
            if (s == 5) {
                const double th = 2.0 * PI_D * (double)ref_theta(c, o) / 65536.0;
                const double dc = cos(th);
                const double ds = sin(th);
                cs = (int64_t)round(32767.0 * dc);
                sn = (int64_t)round(32767.0 * ds);
                f[F_IA] += (int64_t)round(((double)ia * dc) + ((double)ib * ds));
                f[F_IB] += (int64_t)round(((double)ib * dc) - ((double)ia * ds));
                sl[F_IA] += 3;
                sl[F_IB] += 3;
                sl[F_UC] += 2 * llabs(ua);
                sl[F_US] += 2 * llabs(ua);
                sl[F_VC] += 2 * llabs(ub);
                sl[F_VS] += 2 * llabs(ub);
                sl[F_IC] += 2 * llabs(ia);
                sl[F_IS] += 2 * llabs(ia);
                sl[F_JC] += 2 * llabs(ib);
                sl[F_JS] += 2 * llabs(ib);
            } else {
                cs = ref_cos(p % 16);
                sn = ref_sin(p % 16);
                f[F_IA] += ia;
                f[F_IB] += ib;
            }
            if (lg[p].result != QFOC_IDENT_RUNNING) {
                sl[F_UA] += 2 * (int64_t)PERIOD;
                sl[F_UB] += (int64_t)PERIOD;
                sl[F_UC] += 2 * (int64_t)PERIOD * 32767;
                sl[F_US] += 2 * (int64_t)PERIOD * 32767;
                sl[F_VC] += (int64_t)PERIOD * 32767;
                sl[F_VS] += (int64_t)PERIOD * 32767;
            }
            f[F_N] += 1;
            f[F_UA] += ua;
            f[F_UB] += ub;
            f[F_VDC] += lg[p].vdc;
            f[F_UC] += ua * cs;
            f[F_US] += ua * sn;
            f[F_VC] += ub * cs;
            f[F_VS] += ub * sn;
            f[F_IC] += ia * cs;
            f[F_IS] += ia * sn;
            f[F_JC] += ib * cs;
            f[F_JS] += ib * sn;
        }
    }
}

/* a step's two halves added */
static void both_halves(const qfoc_ident_t *id, int s, int64_t out[NF])
{
    qfoc_ident_sums_t h0;
    qfoc_ident_sums_t h1;
    int f;
    assert_true(qfoc_ident_sums(id, (uint8_t)s, 0u, &h0));
    assert_true(qfoc_ident_sums(id, (uint8_t)s, 1u, &h1));
    for (f = 0; f < NF; f++) {
        out[f] = field_of(&h0, f) + field_of(&h1, f);
    }
}

/* the admittance I / U at f_pwm / 16 of a step's sums on the alpha axis (beta: false)
   or the beta axis (true), U from the counts on the mean bus */
static double complex measured_g(const int64_t t[NF], bool beta, double counts_to_volts)
{
    const double complex i = beta ? ((double)t[F_JC] - (I * (double)t[F_JS]))
                                  : ((double)t[F_IC] - (I * (double)t[F_IS]));
    const double complex u = (beta ? ((double)t[F_VC] - (I * (double)t[F_VS]))
                                   : ((double)t[F_UC] - (I * (double)t[F_US]))) *
                             counts_to_volts;
    return i / u;
}

/* the model's I / U of the samples against the written voltages: one period of delay
   before the voltage acts and the sampled R-L response, b z^-1 / (z - a), z = e^{jw} */
static double complex model_g_at(double a, double r, double w)
{
    const double complex z = cexp(I * w);
    return ((1.0 - a) / r) / (z * (z - a));
}

static double complex model_g(double a, double r)
{
    return model_g_at(a, r, 2.0 * PI_D / 16.0);
}

/* ---- tests -------------------------------------------------------------------- */

/* A reference of the header's validity rule, with the PI rule of pi.h and the modulation
   rule of svpwm.h. */
static bool ref_cfg_valid(const qfoc_ident_cfg_t *c)
{
    const long lo = c->pi.out_min;   /* widened: the bounds of pi.h in long */
    const long hi = c->pi.out_max;
    const bool pi_ok = (c->pi.kp >= 0) && (c->pi.ki >= 0) && (c->pi.kp_shift <= 15u) &&
                       (c->pi.ki_shift <= 15u) && (lo >= -32767L) && (lo <= hi) &&
                       (hi <= 32767L);
    const bool pwm_ok = (c->pwm.period >= 100u) && (c->pwm.period <= 32767u) &&
                        (c->pwm.dt_comp <= (c->pwm.period / 4u)) && (c->pwm.i_deadband >= 0) &&
                        (c->pwm.vdc_min > 0);
    return (0 < c->i_lo) && (c->i_lo < c->i_hi) && (c->i_hi < c->i_lim) && (c->i_ramp > 0) &&
           (c->v_inj > 0) && (c->v_inj <= c->v_inj_max) && (c->i_inj > 0) && (c->v_move > 0) &&
           (c->vdc_max > c->vdc_min) && (c->vdc_min > 0) && (c->n_align > 0u) &&
           (c->n_settle > 0u) && (c->win_shift >= 5u) && (c->win_shift <= 14u) &&
           (c->w_psi > 0u) && (c->w_psi <= 4096u) && (c->n_ramp > 0u) && pi_ok &&
           (c->pi.out_min < 0) && (c->pi.out_max > 0) && pwm_ok && (c->pwm.dt_comp == 0u);
}

static void check_cfg_at(const qfoc_ident_cfg_t *c, bool want, int line)
{
    qfoc_ident_t id;
    qfoc_pwm_t out;
    _assert_int_equal(cast_to_largest_integral_type(ref_cfg_valid(c)),
                      cast_to_largest_integral_type(want), __FILE__, line);
    _assert_int_equal(cast_to_largest_integral_type(qfoc_ident_cfg_is_valid(c)),
                      cast_to_largest_integral_type(want), __FILE__, line);
    /* start takes it or refuses it */
    memset(&id, 0xA5, sizeof id);
    qfoc_ident_init(&id);
    _assert_int_equal(qfoc_ident_start(&id, c),
                      want ? QFOC_IDENT_RUNNING : QFOC_IDENT_ERR_CFG, __FILE__, line);
    if (!want) {
        out = feed(&id, 0, 0, VDC_NOM);
        _assert_true(!out.enable, "enable", __FILE__, line);
        _assert_int_equal(qfoc_ident_result(&id), QFOC_IDENT_ERR_CFG, __FILE__, line);
    }
}
#define check_cfg(c, want) check_cfg_at((c), (want), __LINE__)

/* REQ-IDENT-001: the validity of a configuration: the valid base, each condition of the
   header broken on its own (and so every operand of the conjunction false while the
   others hold), each boundary one code either side.
   Methods: 1b valid and invalid configurations, one class per condition; 1c every
   threshold at and beside its edge (i_lo 0 / 1, i_hi = i_lo, i_lim = i_hi, win_shift 4, 5,
   14, 15, w_psi 0 / 1 / 4096 / 4097, n_ramp 0 / 1, the PI's out_min and out_max at 0, dt_comp 0 / 1, period 99 / 100); 1n the
   header's rule written here, with the PI and modulation rules of pi.h and svpwm.h */
static void test_req_ident_001_cfg_conditions(void **state)
{
    qfoc_ident_cfg_t c;
    (void)state;
    c = base_cfg(); check_cfg(&c, true);
    c = base_cfg(); c.i_lo = 0; check_cfg(&c, false);
    c = base_cfg(); c.i_lo = -5; check_cfg(&c, false);
    c = base_cfg(); c.i_lo = 1; check_cfg(&c, true);
    c = base_cfg(); c.i_hi = c.i_lo; check_cfg(&c, false);
    c = base_cfg(); c.i_hi = (int16_t)(c.i_lo + 1); check_cfg(&c, true);
    c = base_cfg(); c.i_lim = c.i_hi; check_cfg(&c, false);
    c = base_cfg(); c.i_lim = 32767; check_cfg(&c, true);
    c = base_cfg(); c.i_ramp = 0; check_cfg(&c, false);
    c = base_cfg(); c.i_ramp = -1; check_cfg(&c, false);
    c = base_cfg(); c.i_ramp = 1; check_cfg(&c, true);
    c = base_cfg(); c.v_inj = 0; check_cfg(&c, false);
    c = base_cfg(); c.v_inj_max = (int16_t)(c.v_inj - 1); check_cfg(&c, false);
    c = base_cfg(); c.v_inj_max = c.v_inj; check_cfg(&c, true);
    c = base_cfg(); c.i_inj = 0; check_cfg(&c, false);
    c = base_cfg(); c.i_inj = 1; check_cfg(&c, true);
    c = base_cfg(); c.v_move = 0; check_cfg(&c, false);
    c = base_cfg(); c.vdc_min = 0; check_cfg(&c, false);
    c = base_cfg(); c.vdc_min = -32768; check_cfg(&c, false);
    c = base_cfg(); c.vdc_max = c.vdc_min; check_cfg(&c, false);
    c = base_cfg(); c.vdc_max = (int16_t)(c.vdc_min + 1); check_cfg(&c, true);
    c = base_cfg(); c.n_align = 0u; check_cfg(&c, false);
    c = base_cfg(); c.n_settle = 0u; check_cfg(&c, false);
    c = base_cfg(); c.n_align = 1u; c.n_settle = 1u; check_cfg(&c, true);
    c = base_cfg(); c.win_shift = 4u; check_cfg(&c, false);
    c = base_cfg(); c.win_shift = 5u; check_cfg(&c, true);
    c = base_cfg(); c.win_shift = 14u; check_cfg(&c, true);
    c = base_cfg(); c.win_shift = 15u; check_cfg(&c, false);
    c = base_cfg(); c.w_psi = 0u; check_cfg(&c, false);
    c = base_cfg(); c.w_psi = 1u; check_cfg(&c, true);
    c = base_cfg(); c.w_psi = 4096u; check_cfg(&c, true);
    c = base_cfg(); c.w_psi = 4097u; check_cfg(&c, false);
    c = base_cfg(); c.n_ramp = 0u; check_cfg(&c, false);
    c = base_cfg(); c.n_ramp = 1u; check_cfg(&c, true);
    c = base_cfg(); c.pi.kp = -1; check_cfg(&c, false);          /* PI parameters invalid */
    c = base_cfg(); c.pi.ki_shift = 16u; check_cfg(&c, false);
    c = base_cfg(); c.pi.out_min = 0; check_cfg(&c, false);      /* valid PI, out_min = 0 */
    c = base_cfg(); c.pi.out_min = -1; check_cfg(&c, true);
    c = base_cfg(); c.pi.out_max = 0; check_cfg(&c, false);      /* valid PI, out_max = 0 */
    c = base_cfg(); c.pi.out_max = 1; check_cfg(&c, true);
    c = base_cfg(); c.pwm.period = 99u; check_cfg(&c, false);    /* modulation invalid */
    c = base_cfg(); c.pwm.period = 100u; check_cfg(&c, true);
    c = base_cfg(); c.pwm.vdc_min = 0; check_cfg(&c, false);
    c = base_cfg(); c.pwm.dt_comp = 1u; check_cfg(&c, false);    /* valid modulation, dt_comp */
    c = base_cfg(); c.pwm.dt_comp = 1250u; check_cfg(&c, false);
}

/* REQ-IDENT-001: 20000 configurations drawn around every threshold at once against the
   reference rule.
   Methods: 1b random configurations over every class, valid and invalid; 1c every field
   drawn from the values at and beside its thresholds and the type's extremes; 1n the
   header's rule written here */
static void test_req_ident_001_cfg_random(void **state)
{
    static const int16_t q[] = { -32768, -1, 0, 1, 2, 3276, 3277, 6554, 13107, 32766, 32767 };
    static const uint16_t u[] = { 0u, 1u, 2u, 99u, 100u, 1250u, 4096u, 4097u, 5000u, 32767u,
                                  32768u, 65535u };
    static const uint8_t ws[] = { 0u, 4u, 5u, 6u, 13u, 14u, 15u, 255u };
    static const uint8_t sh[] = { 0u, 2u, 15u, 16u };
    const size_t nq = sizeof q / sizeof q[0];
    const size_t nu = sizeof u / sizeof u[0];
    int n;
    int valid = 0;
    (void)state;
    for (n = 0; n < 20000; n++) {
        qfoc_ident_cfg_t c = base_cfg();
        /* each field is changed with probability 1/8, so that valid ones occur too */
#define PICK(field, tab, cnt) \
        if ((lcg_next() >> 29) == 0u) { field = tab[(lcg_next() >> 8) % (cnt)]; }
        PICK(c.i_lo, q, nq)
        PICK(c.i_hi, q, nq)
        PICK(c.i_lim, q, nq)
        PICK(c.i_ramp, q, nq)
        PICK(c.v_inj, q, nq)
        PICK(c.v_inj_max, q, nq)
        PICK(c.i_inj, q, nq)
        PICK(c.v_move, q, nq)
        PICK(c.vdc_min, q, nq)
        PICK(c.vdc_max, q, nq)
        PICK(c.n_align, u, nu)
        PICK(c.n_settle, u, nu)
        PICK(c.win_shift, ws, sizeof ws)
        PICK(c.w_psi, u, nu)
        PICK(c.n_ramp, u, nu)
        PICK(c.pi.kp, q, nq)
        PICK(c.pi.kp_shift, sh, sizeof sh)
        PICK(c.pi.ki, q, nq)
        PICK(c.pi.ki_shift, sh, sizeof sh)
        PICK(c.pi.out_min, q, nq)
        PICK(c.pi.out_max, q, nq)
        PICK(c.pwm.period, u, nu)
        PICK(c.pwm.dt_comp, u, nu)
        PICK(c.pwm.i_deadband, q, nq)
        PICK(c.pwm.vdc_min, q, nq)
#undef PICK
        assert_int_equal(qfoc_ident_cfg_is_valid(&c), ref_cfg_valid(&c));
        valid += ref_cfg_valid(&c) ? 1 : 0;
    }
    /* both classes sampled often */
    assert_true(valid > 1000);
    assert_true(valid < 19000);
}

static void check_record_zero(const qfoc_ident_t *id)
{
    int s;
    int h;
    int f;
    for (s = 0; s < NSTEP; s++) {
        for (h = 0; h < 2; h++) {
            qfoc_ident_sums_t z;
            assert_true(qfoc_ident_sums(id, (uint8_t)s, (uint8_t)h, &z));
            for (f = 0; f < NF; f++) {
                assert_true(field_of(&z, f) == 0);
            }
        }
    }
}

/* REQ-IDENT-001: init gives the idle state from any contents; start with a valid
   configuration gives RUNNING at ALIGN with the reference 0 and an empty record, from
   any state (a finished run's record is cleared); start with an invalid one gives
   ERR_CFG and the PWM stays off (every compare value 0: no valid modulation) in the
   following periods, with the result kept.
   Methods: 1b the idle, running, finished and refused states; 1d a state full of garbage
   before init, a restart after a complete run; 1n the header's idle and start states */
static void test_req_ident_001_init_start(void **state)
{
    static qfoc_ident_t id;
    qfoc_ident_cfg_t c = base_cfg();
    plant_t pl = base_plant();
    qfoc_pwm_t out;
    int p;
    (void)state;
    memset(&id, 0x5A, sizeof id);
    qfoc_ident_init(&id);
    assert_int_equal(qfoc_ident_result(&id), QFOC_IDENT_IDLE);
    assert_int_equal(qfoc_ident_step_now(&id), QFOC_IDENT_ALIGN);
    assert_int_equal(id.ref, 0);
    check_record_zero(&id);
    /* a step while idle: off, nothing changes */
    out = feed(&id, 1000, 1000, VDC_NOM);
    assert_false(out.enable);
    assert_int_equal(out.cmp[0], 0);
    assert_int_equal(out.cmp[1], 0);
    assert_int_equal(out.cmp[2], 0);
    assert_int_equal(qfoc_ident_result(&id), QFOC_IDENT_IDLE);
    check_record_zero(&id);

    assert_int_equal(qfoc_ident_start(&id, &c), QFOC_IDENT_RUNNING);
    assert_int_equal(qfoc_ident_result(&id), QFOC_IDENT_RUNNING);
    assert_int_equal(qfoc_ident_step_now(&id), QFOC_IDENT_ALIGN);
    assert_int_equal(id.ref, 0);
    assert_int_equal(id.n, 0);
    check_record_zero(&id);
    /* the first period: on, the reference one ramp step up */
    out = feed(&id, 0, 0, VDC_NOM);
    assert_true(out.enable);
    assert_int_equal(id.ref, c.i_ramp);

    /* a complete run, then a restart clears it */
    assert_int_equal(qfoc_ident_start(&id, &c), QFOC_IDENT_RUNNING);
    p = run_plant(&id, &pl, 100000);
    assert_int_equal(p, ref_total(&c));
    assert_int_equal(qfoc_ident_result(&id), QFOC_IDENT_DONE);
    assert_int_equal(qfoc_ident_start(&id, &c), QFOC_IDENT_RUNNING);
    assert_int_equal(qfoc_ident_step_now(&id), QFOC_IDENT_ALIGN);
    assert_int_equal(id.ref, 0);
    assert_int_equal(id.n, 0);
    check_record_zero(&id);

    /* an invalid configuration from a running state: refused, idle with ERR_CFG */
    (void)feed(&id, 0, 0, VDC_NOM);
    c.win_shift = 15u;
    assert_int_equal(qfoc_ident_start(&id, &c), QFOC_IDENT_ERR_CFG);
    assert_int_equal(qfoc_ident_result(&id), QFOC_IDENT_ERR_CFG);
    assert_int_equal(qfoc_ident_step_now(&id), QFOC_IDENT_ALIGN);
    assert_int_equal(id.ref, 0);
    assert_int_equal(id.n, 0);
    check_record_zero(&id);
    for (p = 0; p < 3; p++) {
        out = feed(&id, 0, 0, VDC_NOM);
        assert_false(out.enable);
        assert_int_equal(out.cmp[0], 0);
        assert_int_equal(out.cmp[1], 0);
        assert_int_equal(out.cmp[2], 0);
        assert_int_equal(qfoc_ident_result(&id), QFOC_IDENT_ERR_CFG);
    }
    check_record_zero(&id);
}

/* REQ-IDENT-002, REQ-IDENT-004, REQ-IDENT-005: the whole mode on the R-L model.
   The run: n_align + 4 n_settle + 5 2^win_shift periods, the step of every period as the
   schedule says, the PWM on in every period before the end and off in the last one and
   after (every compare value at half the period), each half window of 2^(win_shift - 1)
   periods, every window sum as recomputed here from the period's inputs and outputs, the
   mean alpha current at each step's level and the mean beta current at zero, R from
   (V_hi - V_lo) / (I_hi - I_lo) within 2 % of the model's and the inverter's error
   V_lo - R I_lo near the model's, the admittance of L_D and L_Q at f_pwm / 16 within 3 %
   of the model's, the mean beta voltage command near the applied beta voltage, the
   reference ramp (|change| <= i_ramp, within 0 .. i_hi, at the level when the window
   opens) and no overshoot of the current (1 % of i_hi without injection, a tenth of i_hi
   with L_D's).
   Methods: 1b every step and both halves of each window; 1c the end of each step's
   settling, the half boundary, the last period; 1n the double-precision R-L model with a
   one-period delay and an inverter error, and the window sums recomputed here */
static void test_req_ident_002_model_run(void **state)
{
    static qfoc_ident_t id;
    static const int level[NSTEP] = { 6554, 3277, 6554, 6554, 6554, 6554 };
    const qfoc_ident_cfg_t c = base_cfg();
    plant_t pl = base_plant();
    rsums_t rec[NSTEP][2];
    rsums_t slack[NSTEP][2];
    int64_t t[NSTEP][NF];
    const int half = 1 << (c.win_shift - 1);
    const int total = ref_total(&c);
    int p;
    int s;
    int h;
    int f;
    double ia_max = 0.0;
    (void)state;
    assert_int_equal(qfoc_ident_start(&id, &c), QFOC_IDENT_RUNNING);
    p = run_plant(&id, &pl, 100000);
    assert_int_equal(total, 300 + 1000 + 256 + 1536);
    assert_int_equal(p, total);
    assert_int_equal(qfoc_ident_result(&id), QFOC_IDENT_DONE);
    assert_int_equal(qfoc_ident_step_now(&id), QFOC_IDENT_PSI);

    for (p = 0; p < total; p++) {
        int o;
        const int sref = ref_step(&c, p, &o);
        const bool last = (p == (total - 1));
        const int settle = settle_of(&c, sref);
        int d;
        assert_int_equal(lg[p].step_before, sref);
        assert_int_equal(lg[p].result, last ? QFOC_IDENT_DONE : QFOC_IDENT_RUNNING);
        assert_int_equal(lg[p].out.enable, !last);
        /* the ramp */
        d = lg[p].ref_after - lg[p].ref_before;
        assert_true(abs(d) <= c.i_ramp);
        assert_true((lg[p].ref_after >= 0) && (lg[p].ref_after <= c.i_hi));
        if (o >= settle) {
            assert_int_equal(lg[p].ref_after, level[sref]);
        }
        if ((sref < 5) && (lg[p].ia > ia_max)) {
            ia_max = lg[p].ia;
        }
        /* the rotating current of PSI: its magnitude within a fifth of i_hi (the model's
           saliency stands still while the current turns, L_q / L_d = 1.7: a ripple at
           twice the speed that the rotating frame's PI sees as a disturbance of 15 %) */
        if (sref == 5) {
            assert_true(hypot(lg[p].ia, lg[p].ib) < (1.2 * c.i_hi));
        }
        /* without injection (ALIGN, R_LO, R_HI) the ramped reference gives no overshoot
           beyond 1 % of i_hi, nor below i_lo by 1 % once the reference has fallen to it */
        if (sref < 3) {
            assert_true(lg[p].ia <= (c.i_hi + (c.i_hi / 100)));
        }
        if ((sref == 1) && (o >= 100)) {
            assert_true(lg[p].ia >= (c.i_lo - (c.i_lo / 100)));
        }
        /* beta held near zero outside L_Q */
        if (sref < 4) {
            assert_true(abs(lg[p].ib) < 100);
        }
    }
    /* with the injection of L_D on top, the alpha current stays within a tenth of i_hi */
    assert_true(ia_max < (c.i_hi + (c.i_hi / 10)));

    /* the PWM off after the end, the result kept, the record unchanged */
    {
        qfoc_ident_sums_t before;
        qfoc_ident_sums_t after;
        assert_true(qfoc_ident_sums(&id, 5u, 1u, &before));
        for (p = 0; p < 3; p++) {
            const qfoc_pwm_t out = feed(&id, 20000, -20000, 0);
            assert_false(out.enable);
            assert_int_equal(out.cmp[0], PERIOD / 2u);
            assert_int_equal(out.cmp[1], PERIOD / 2u);
            assert_int_equal(out.cmp[2], PERIOD / 2u);
            assert_int_equal(qfoc_ident_result(&id), QFOC_IDENT_DONE);
        }
        assert_true(qfoc_ident_sums(&id, 5u, 1u, &after));
        for (f = 0; f < NF; f++) {
            assert_true(field_of(&before, f) == field_of(&after, f));
        }
    }

    /* the record against the sums recomputed here (every field but vb_cmd exactly, up to
       the slack of the last period's voltages) */
    ref_record(&c, total, rec, slack);
    for (s = 0; s < NSTEP; s++) {
        for (h = 0; h < 2; h++) {
            qfoc_ident_sums_t z;
            assert_true(qfoc_ident_sums(&id, (uint8_t)s, (uint8_t)h, &z));
            assert_int_equal(z.n, half);
            for (f = 0; f < NF; f++) {
                if (f != F_VB) {
                    const int64_t d = field_of(&z, f) - rec[s][h].f[f];
                    assert_true((d <= slack[s][h].f[f]) && (d >= -slack[s][h].f[f]));
                }
            }
        }
        both_halves(&id, s, t[s]);
    }

    /* the currents at the steps' levels (PSI: in the rotating frame): the mean within 1 %
       (the second axis within 5 LSB) */
    for (s = 0; s < NSTEP; s++) {
        const double m = (double)t[s][F_N];
        const double mean_a = (double)t[s][F_IA] / m;
        const double mean_b = (double)t[s][F_IB] / m;
        assert_true(fabs(mean_a - level[s]) < (0.01 * level[s]));
        assert_true(fabs(mean_b) < 5.0);
        /* the beta voltage command against the beta voltage the compare values give
           (the standstill steps, whose control frame is the stationary one) */
        if (s < 5) {
            const double vdc = (double)t[s][F_VDC] / m;
            const double ub = ((double)t[s][F_UB] / m) * vdc / (SQRT3_D * (double)PERIOD);
            assert_true(fabs(((double)t[s][F_VB] / m) - ub) < 3.0);
        }
    }

    /* R_s and the inverter's error from R_LO and R_HI */
    {
        const double vdc_lo = (double)t[1][F_VDC] / (double)t[1][F_N];
        const double vdc_hi = (double)t[2][F_VDC] / (double)t[2][F_N];
        const double v_lo = ((double)t[1][F_UA] / (double)t[1][F_N]) * vdc_lo / (3.0 * PERIOD);
        const double v_hi = ((double)t[2][F_UA] / (double)t[2][F_N]) * vdc_hi / (3.0 * PERIOD);
        const double i_lo = (double)t[1][F_IA] / (double)t[1][F_N];
        const double i_hi = (double)t[2][F_IA] / (double)t[2][F_N];
        const double r = (v_hi - v_lo) / (i_hi - i_lo);
        const double e = v_lo - (r * i_lo);
        print_message("R = %.5f (model %.5f), error %.1f LSB (model %.1f)\n", r, pl.r, e,
                      pl.v_err);
        assert_true(fabs((r / pl.r) - 1.0) < 0.02);
        assert_true(fabs(e - pl.v_err) < 0.1 * pl.v_err);
    }

    /* the admittance at f_pwm / 16: alpha in L_D, beta in L_Q */
    {
        const double vdc_d = (double)t[3][F_VDC] / (double)t[3][F_N];
        const double vdc_q = (double)t[4][F_VDC] / (double)t[4][F_N];
        const double complex gd = measured_g(t[3], false, vdc_d / (3.0 * PERIOD));
        const double complex gq = measured_g(t[4], true, vdc_q / (SQRT3_D * PERIOD));
        const double complex md = model_g(pl.a_d, pl.r);
        const double complex mq = model_g(pl.a_q, pl.r);
        print_message("G_d = %.4f%+.4fj (model %.4f%+.4fj), G_q = %.4f%+.4fj (model %.4f%+.4fj)\n",
                      creal(gd), cimag(gd), creal(md), cimag(md), creal(gq), cimag(gq),
                      creal(mq), cimag(mq));
        assert_true(cabs((gd / md) - 1.0) < 0.03);
        assert_true(cabs((gq / mq) - 1.0) < 0.03);
        /* the injection is on the step's own axis: the x sums of L_D and L_Q are large,
           the cross-coupling sums small */
        assert_true(cabs((double)t[3][F_JC] - (I * (double)t[3][F_JS])) <
                    0.05 * cabs((double)t[3][F_IC] - (I * (double)t[3][F_IS])));
        assert_true(cabs((double)t[4][F_IC] - (I * (double)t[4][F_IS])) <
                    0.05 * cabs((double)t[4][F_JC] - (I * (double)t[4][F_JS])));
    }

    /* PSI: the current turns with the reference angle at i_hi: its positive-sequence
       phasor sum (i_alpha + j i_beta) e^{-j theta} = I_alpha + j I_beta is n i_hi (within
       1 %; the standing saliency's negative sequence cancels in it),
       and the voltage phasors drive the currents the model's admittance at PSI's speed
       gives (alpha less the inverter error's fundamental, 4 / pi v_err along the alpha
       current; within 3 %) */
    {
        const double n = (double)t[5][F_N];
        const double complex ia = ((double)t[5][F_IC] - (I * (double)t[5][F_IS])) / 32767.0;
        const double complex ib = ((double)t[5][F_JC] - (I * (double)t[5][F_JS])) / 32767.0;
        const double vdc = (double)t[5][F_VDC] / n;
        const double w = 2.0 * PI_D * (double)c.w_psi / 65536.0;
        const double complex ua = ((double)t[5][F_UC] - (I * (double)t[5][F_US])) / 32767.0 *
                                  vdc / (3.0 * PERIOD);
        const double complex ub = ((double)t[5][F_VC] - (I * (double)t[5][F_VS])) / 32767.0 *
                                  vdc / (SQRT3_D * PERIOD);
        const double complex ua_net = ua - ((4.0 / PI_D) * pl.v_err * (n / 2.0) * ia / cabs(ia));
        print_message("PSI: I_alpha %.1f%+.1fj I_beta %.1f%+.1fj (n i_hi / 2 = %.1f)\n",
                      creal(ia), cimag(ia), creal(ib), cimag(ib), n * c.i_hi / 2.0);
        assert_true(cabs(((ia + (I * ib)) / (n * c.i_hi)) - 1.0) < 0.01);
        print_message("PSI: G_alpha %.5f G_beta %.5f (model %.5f, %.5f)\n", cabs(ia / ua_net),
                      cabs(ib / ub), cabs(model_g_at(pl.a_d, pl.r, w)),
                      cabs(model_g_at(pl.a_q, pl.r, w)));
        assert_true(cabs(((ia / ua_net) / model_g_at(pl.a_d, pl.r, w)) - 1.0) < 0.03);
        assert_true(cabs(((ib / ub) / model_g_at(pl.a_q, pl.r, w)) - 1.0) < 0.03);
    }
}

/* REQ-IDENT-002, REQ-IDENT-005: the largest window, 2^14 periods (halves of 8192), and
   the smallest, 2^5, with the shortest settling (one period): the schedule and the
   halves' lengths.
   Methods: 1c win_shift at WIN_MAX and WIN_MIN, n_align = n_settle = 1; 1n the
   header's schedule on the R-L model */
static void test_req_ident_002_window_extremes(void **state)
{
    static qfoc_ident_t id;
    static const uint8_t shifts[2] = { 14u, 5u };
    int j;
    (void)state;
    for (j = 0; j < 2; j++) {
        qfoc_ident_cfg_t c = base_cfg();
        plant_t pl = base_plant();
        int p;
        int s;
        int h;
        c.win_shift = shifts[j];
        c.n_align = (j == 0) ? 300u : 100u;
        c.n_settle = (j == 0) ? 1u : 60u;
        c.i_ramp = 6554;  /* the level at once: the PI does not overshoot on this model */
        assert_int_equal(qfoc_ident_start(&id, &c), QFOC_IDENT_RUNNING);
        p = run_plant(&id, &pl, 200000);
        assert_int_equal(p, ref_total(&c));
        assert_int_equal(qfoc_ident_result(&id), QFOC_IDENT_DONE);
        for (s = 0; s < NSTEP; s++) {
            for (h = 0; h < 2; h++) {
                qfoc_ident_sums_t z;
                assert_true(qfoc_ident_sums(&id, (uint8_t)s, (uint8_t)h, &z));
                assert_int_equal(z.n, 1 << (c.win_shift - 1));
            }
        }
    }
}

/* Run a configuration on the model to its end, checking the injection amplitude of L_D
   and L_Q in every period against the header's rule written here: v_inj at each step's
   start; over each injection period (the PWM periods from k = 0 to k = 15) of the first
   half of the settling, the injected axis's peak-to-peak current; at its end, unless it
   is the step's first (partial) period or the one after a change, the amplitude doubles
   (at most v_inj_max) when the peak-to-peak is below i_inj and halves (at least 1) when
   it is above 4 i_inj; held from then on (the whole window).  amp[0], amp[1]: L_D's and
   L_Q's amplitude in their windows. */
static void run_amplitude(qfoc_ident_t *id, const qfoc_ident_cfg_t *c, plant_t *pl,
                          int amp[2])
{
    int p = 0;
    int want = c->v_inj;   /* the rule's amplitude */
    int hi = -32768;       /* the injection period's extremes */
    int lo = 32767;
    bool hold = true;
    assert_int_equal(qfoc_ident_start(id, c), QFOC_IDENT_RUNNING);
    assert_int_equal(id->inj, c->v_inj);
    amp[0] = -1;
    amp[1] = -1;
    while ((p < 200000) && (qfoc_ident_result(id) == QFOC_IDENT_RUNNING)) {
        qfoc_ab_t i;
        qfoc_pwm_t out;
        const int16_t vdc = bus_at(p);
        const uint8_t s = qfoc_ident_step_now(id);
        const int n = (int)id->n;
        const int k = id->k;
        const int settle = settle_of(c, s);
        i.alpha = sample(pl->ia);
        i.beta = sample(pl->ib);
        out = qfoc_ident_step(id, &i, vdc);
        plant_advance(pl, p, (double)vdc);
        pl->acting = out;
        p++;
        if (((s == QFOC_IDENT_L_D) || (s == QFOC_IDENT_L_Q)) && (n < (settle / 2))) {
            const int x = (s == QFOC_IDENT_L_D) ? i.alpha : i.beta;
            hi = (x > hi) ? x : hi;
            lo = (x < lo) ? x : lo;
            if (k == 15) {
                const int before = want;
                if (!hold) {
                    const int pp = hi - lo;
                    if (pp < c->i_inj) {
                        want = (2 * want > c->v_inj_max) ? c->v_inj_max : 2 * want;
                    } else if ((pp > 4 * c->i_inj) && (want / 2 >= 1)) {
                        want = want / 2;
                    }
                }
                hold = (want != before);
                hi = -32767;
                lo = 32767;
            }
        }
        if (qfoc_ident_step_now(id) != s) {
            /* a new step starts from v_inj */
            want = c->v_inj;
            hi = -32767;
            lo = 32767;
            hold = true;
        }
        assert_int_equal(id->inj, want);
        if (((s == QFOC_IDENT_L_D) || (s == QFOC_IDENT_L_Q)) && (n >= settle) &&
            (qfoc_ident_step_now(id) == s)) {
            const int j = (s == QFOC_IDENT_L_D) ? 0 : 1;
            if (amp[j] < 0) {
                amp[j] = id->inj;
            }
            assert_int_equal(id->inj, amp[j]);
        }
    }
    assert_int_equal(qfoc_ident_result(id), QFOC_IDENT_DONE);
}

/* the injected current's amplitude of a step's window: 2 |I| / n (its phasor) */
static double inj_amplitude(const qfoc_ident_t *id, int s)
{
    int64_t t[NF];
    both_halves(id, s, t);
    return (s == 3) ? 2.0 * cabs((double)t[F_IC] - (I * (double)t[F_IS])) / 32767.0 / (double)t[F_N]
                    : 2.0 * cabs((double)t[F_JC] - (I * (double)t[F_JS])) / 32767.0 / (double)t[F_N];
}

/* REQ-IDENT-002: L_D's and L_Q's injection amplitude is adapted in the first half of the
   settling: from a start far below the aim it doubles until the injected current's
   peak-to-peak reaches i_inj, from one far above it halves until it is at most 4 i_inj;
   it never exceeds v_inj_max nor falls below 1, each step starts again from v_inj, and
   the window runs on one amplitude.  On the R-L model (|G_d| = 0.26, |G_q| = 0.155
   at f_pwm / 16) the window's current amplitude then lies within [i_inj / 2, 2 i_inj]
   unless the cap holds it lower.
   Methods: 1b below the aim, above it, capped, at the floor; 1c v_inj_max = v_inj and the
   amplitude 1; 1n the header's rule and the model's admittance */
static void test_req_ident_002_injection_amplitude(void **state)
{
    static qfoc_ident_t id;
    int amp[2];
    int j;
    (void)state;
    {   /* from below: 100 doubles (a power of two times 100) until the current's
           peak-to-peak reaches 1638 */
        qfoc_ident_cfg_t c = base_cfg();
        plant_t pl = base_plant();
        c.v_inj = 100;
        c.i_inj = 1638;
        c.n_settle = 400u;  /* 200 periods of adaptation: 6 judged injection periods */
        run_amplitude(&id, &c, &pl, amp);
        for (j = 0; j < 2; j++) {
            const double a = inj_amplitude(&id, 3 + j);
            print_message("from below: L_%c amplitude %d, current %.0f LSB (aim %d)\n",
                          (j == 0) ? 'd' : 'q', amp[j], a, c.i_inj);
            assert_true((amp[j] > 100) && ((amp[j] % 100) == 0) &&
                        (((amp[j] / 100) & ((amp[j] / 100) - 1)) == 0));
            assert_true((a >= (c.i_inj / 3.0)) && (a <= (1.05 * 2.0 * c.i_inj)));
        }
    }
    {   /* from above: 8000 halves until the peak-to-peak is at most 4 x 200 */
        qfoc_ident_cfg_t c = base_cfg();
        plant_t pl = base_plant();
        c.v_inj = 8000;
        c.v_inj_max = 8000;
        c.i_inj = 200;
        c.i_lim = 32767;
        c.n_settle = 400u;
        run_amplitude(&id, &c, &pl, amp);
        for (j = 0; j < 2; j++) {
            const double a = inj_amplitude(&id, 3 + j);
            print_message("from above: L_%c amplitude %d, current %.0f LSB (aim %d)\n",
                          (j == 0) ? 'd' : 'q', amp[j], a, c.i_inj);
            assert_true((amp[j] < 8000) && ((8000 % amp[j]) == 0) &&
                        (((8000 / amp[j]) & ((8000 / amp[j]) - 1)) == 0));
            assert_true((a >= (c.i_inj / 3.0)) && (a <= (1.05 * 2.0 * c.i_inj)));
        }
    }
    {   /* capped: v_inj_max 300 holds both below the aim */
        qfoc_ident_cfg_t c = base_cfg();
        plant_t pl = base_plant();
        c.v_inj = 100;
        c.v_inj_max = 300;
        c.i_inj = 5000;
        run_amplitude(&id, &c, &pl, amp);
        assert_int_equal(amp[0], 300);
        assert_int_equal(amp[1], 300);
    }
    {   /* v_inj_max = v_inj: never changed */
        qfoc_ident_cfg_t c = base_cfg();
        plant_t pl = base_plant();
        c.v_inj_max = c.v_inj;
        c.i_inj = 5000;
        run_amplitude(&id, &c, &pl, amp);
        assert_int_equal(amp[0], c.v_inj);
        assert_int_equal(amp[1], c.v_inj);
    }
    {   /* the floor: amplitude 1 with an aim of 1 LSB stays at 1 */
        qfoc_ident_cfg_t c = base_cfg();
        plant_t pl = base_plant();
        c.v_inj = 1;
        c.i_inj = 1;
        pl.v_err = 0.0;
        run_amplitude(&id, &c, &pl, amp);
        assert_int_equal(amp[0], 1);
        assert_int_equal(amp[1], 1);
    }
    {   /* the floor from above: a current swinging +-100 LSB (peak-to-peak 200 > 4 x 1)
           at the amplitude 1 leaves it at 1 */
        qfoc_ident_cfg_t c = base_cfg();
        int p;
        c.v_inj = 1;
        c.i_inj = 1;
        c.n_align = 1u;
        c.n_settle = 64u;
        c.win_shift = 5u;
        assert_int_equal(qfoc_ident_start(&id, &c), QFOC_IDENT_RUNNING);
        for (p = 0; (p < 1000) && (qfoc_ident_step_now(&id) != QFOC_IDENT_L_D); p++) {
            const int a = (qfoc_ident_step_now(&id) == QFOC_IDENT_R_LO) ? c.i_lo : c.i_hi;
            (void)feed(&id, a, 0, VDC_NOM);
        }
        assert_int_equal(qfoc_ident_step_now(&id), QFOC_IDENT_L_D);
        for (p = 0; p < 64; p++) {
            (void)feed(&id, c.i_hi + (((p % 2) == 0) ? 100 : -100), 0, VDC_NOM);
            assert_int_equal(id.inj, 1);
        }
        assert_int_equal(qfoc_ident_result(&id), QFOC_IDENT_RUNNING);
    }
}

/* REQ-IDENT-002: the longest settling the configuration admits: n_align, n_settle or
   n_ramp 65535 (valid: the header bounds them by > 0 only) with the largest and the
   smallest window; the mode, fed its levels exactly (PSI: the current turning with its
   angle), still ends (DONE) after n_align + 5 n_settle + n_ramp + 6 2^win_shift periods,
   the header's bound on its length, with halves of 2^(win_shift - 1) periods.  A
   configuration the unit refuses instead passes as well.
   Methods: 1c n_align = 65535 with win_shift 14, n_settle = 65535 with win_shift 5,
   n_ramp = n_settle = 65535 with win_shift 14 (PSI's period count 2 x 65535 + 2^14, the
   invariant's bound); 1d a counter that wraps; 1n the header's schedule */
static void test_req_ident_002_longest_settling(void **state)
{
    static qfoc_ident_t id;
    static const uint16_t na[3] = { 65535u, 1u, 1u };
    static const uint16_t ns[3] = { 1u, 65535u, 65535u };
    static const uint16_t nr[3] = { 1u, 1u, 65535u };
    static const uint8_t ws[3] = { 14u, 5u, 14u };
    int j;
    (void)state;
    for (j = 0; j < 3; j++) {
        qfoc_ident_cfg_t c = base_cfg();
        long p;
        long total;
        int s;
        int h;
        c.n_align = na[j];
        c.n_settle = ns[j];
        c.n_ramp = nr[j];
        c.win_shift = ws[j];
        total = (long)c.n_align + (5L * (long)c.n_settle) + (long)c.n_ramp +
                (6L << c.win_shift);
        if (!qfoc_ident_cfg_is_valid(&c)) {
            continue;
        }
        assert_int_equal(qfoc_ident_start(&id, &c), QFOC_IDENT_RUNNING);
        for (p = 0; (p <= total) && (qfoc_ident_result(&id) == QFOC_IDENT_RUNNING); p++) {
            const int a = (qfoc_ident_step_now(&id) == QFOC_IDENT_R_LO) ? c.i_lo : c.i_hi;
            if (qfoc_ident_step_now(&id) == QFOC_IDENT_PSI) {
                const double th = 2.0 * PI_D * (double)id.theta / 65536.0;
                (void)feed(&id, (int)lround(a * cos(th)), (int)lround(a * sin(th)), VDC_NOM);
            } else {
                (void)feed(&id, a, 0, VDC_NOM);
            }
        }
        assert_int_equal(qfoc_ident_result(&id), QFOC_IDENT_DONE);
        assert_int_equal(p, total);
        for (s = 0; s < NSTEP; s++) {
            for (h = 0; h < 2; h++) {
                qfoc_ident_sums_t z;
                assert_true(qfoc_ident_sums(&id, (uint8_t)s, (uint8_t)h, &z));
                assert_int_equal(z.n, 1 << (c.win_shift - 1));
            }
        }
    }
}

/* start a run of the base configuration and take it to period n on the model */
static void run_to(qfoc_ident_t *id, plant_t *pl, const qfoc_ident_cfg_t *c, int n)
{
    assert_int_equal(qfoc_ident_start(id, c), QFOC_IDENT_RUNNING);
    assert_int_equal(run_plant(id, pl, n), n);
    assert_int_equal(qfoc_ident_result(id), QFOC_IDENT_RUNNING);
}

static void check_off_at(qfoc_pwm_t out, int line)
{
    _assert_true(!out.enable, "enable", __FILE__, line);
    _assert_int_equal(out.cmp[0], PERIOD / 2u, __FILE__, line);
    _assert_int_equal(out.cmp[1], PERIOD / 2u, __FILE__, line);
    _assert_int_equal(out.cmp[2], PERIOD / 2u, __FILE__, line);
}
#define check_off(out) check_off_at((out), __LINE__)

/* REQ-IDENT-003: a current above i_lim, alpha or beta, either sign (-32768 included),
   ends the mode with ERR_OC and the PWM off in that same period and after; a current of
   exactly i_lim does not; over-current wins over a low bus in the same period.
   Methods: 1b alpha and beta, positive and negative, in ALIGN and in a later step; 1c
   |i| = i_lim and i_lim + 1, -32768; 1d a shorted phase; 1l an over-current pulse in
   the measured current; 1n the header's bound */
static void test_req_ident_003_overcurrent(void **state)
{
    static qfoc_ident_t id;
    static const int cases[][2] = {
        { 13108, 0 }, { -13108, 0 }, { -32768, 0 }, { 32767, 0 },
        { 0, 13108 }, { 0, -13108 }, { 0, -32768 }, { 13108, 13108 },
    };
    const qfoc_ident_cfg_t c = base_cfg();
    size_t j;
    (void)state;
    for (j = 0; j < sizeof cases / sizeof cases[0]; j++) {
        plant_t pl = base_plant();
        qfoc_pwm_t out;
        /* the boundary: exactly i_lim on both axes keeps it running */
        run_to(&id, &pl, &c, 50 + (int)(j * 150u));
        out = feed(&id, c.i_lim, -c.i_lim, VDC_NOM);
        assert_true(out.enable);
        out = feed(&id, -c.i_lim, c.i_lim, VDC_NOM);
        assert_true(out.enable);
        assert_int_equal(qfoc_ident_result(&id), QFOC_IDENT_RUNNING);
        /* over: off in this period; a low bus at the same time does not change the verdict */
        out = feed(&id, cases[j][0], cases[j][1], ((j % 2u) == 0u) ? VDC_NOM : 0);
        check_off(out);
        assert_int_equal(qfoc_ident_result(&id), QFOC_IDENT_ERR_OC);
        out = feed(&id, 0, 0, VDC_NOM);
        check_off(out);
        assert_int_equal(qfoc_ident_result(&id), QFOC_IDENT_ERR_OC);
    }
}

/* REQ-IDENT-003: a DC bus below vdc_min or above vdc_max ends the mode with ERR_BUS, PWM
   off in that period and after; vdc_min and vdc_max themselves do not.
   Methods: 1b a low and a high bus in ALIGN and in L_Q; 1c vdc = vdc_min and
   vdc_min - 1, vdc_max and vdc_max + 1, 0, -32768, 32767; 1d a collapsing or a rising DC
   link; 1l a bus measurement out of range; 1n the header's bounds */
static void test_req_ident_003_bus(void **state)
{
    static qfoc_ident_t id;
    static const int low[5] = { 16383, 0, -32768, 30001, 32767 };
    const qfoc_ident_cfg_t c = base_cfg();
    int j;
    (void)state;
    for (j = 0; j < 5; j++) {
        plant_t pl = base_plant();
        qfoc_pwm_t out;
        run_to(&id, &pl, &c, (j == 1) ? 2300 : 20);
        out = feed(&id, sample(pl.ia), sample(pl.ib), c.vdc_min);
        assert_true(out.enable);
        out = feed(&id, sample(pl.ia), sample(pl.ib), c.vdc_max);
        assert_true(out.enable);
        out = feed(&id, sample(pl.ia), sample(pl.ib), low[j]);
        check_off(out);
        assert_int_equal(qfoc_ident_result(&id), QFOC_IDENT_ERR_BUS);
        out = feed(&id, 0, 0, VDC_NOM);
        check_off(out);
        assert_int_equal(qfoc_ident_result(&id), QFOC_IDENT_ERR_BUS);
    }
}

/* REQ-IDENT-003: an open phase: no current flows, the PI's voltage at its limit, and at
   the end of ALIGN's window (n_align + 2^win_shift periods) the mode ends with
   ERR_NO_CURRENT, PWM off in that period.
   Methods: 1b an open circuit; 1c the last period of ALIGN's window; 1d a motor not
   connected; 1l the current sensor reading 0; 1n the model with no current and the
   header's bound */
static void test_req_ident_003_open_circuit(void **state)
{
    static qfoc_ident_t id;
    const qfoc_ident_cfg_t c = base_cfg();
    plant_t pl = base_plant();
    const int n = (int)c.n_align + (1 << c.win_shift);
    int p;
    (void)state;
    pl.open = true;
    assert_int_equal(qfoc_ident_start(&id, &c), QFOC_IDENT_RUNNING);
    p = run_plant(&id, &pl, 100000);
    assert_int_equal(p, n);
    assert_int_equal(qfoc_ident_result(&id), QFOC_IDENT_ERR_NO_CURRENT);
    assert_int_equal(qfoc_ident_step_now(&id), QFOC_IDENT_ALIGN);
    for (p = 0; p < (n - 1); p++) {
        assert_true(lg[p].out.enable);
    }
    assert_false(lg[n - 1].out.enable);  /* its compare values: test_req_ident_004_off_at_window_end */
    check_off(feed(&id, 0, 0, VDC_NOM));
}

/* one run of ALIGN (and R_LO) with constant currents; returns the result after the
   window of the given step */
static uint8_t run_const(qfoc_ident_t *id, int alpha_align, int alpha_lo, int beta,
                         int upto_step)
{
    const qfoc_ident_cfg_t c = base_cfg();
    int n = (int)c.n_align + (1 << c.win_shift);
    int p;
    if (upto_step == 1) {
        n += (int)c.n_settle + (1 << c.win_shift);
    }
    assert_int_equal(qfoc_ident_start(id, &c), QFOC_IDENT_RUNNING);
    for (p = 0; (p < n) && (qfoc_ident_result(id) == QFOC_IDENT_RUNNING); p++) {
        const int a = (qfoc_ident_step_now(id) == QFOC_IDENT_ALIGN) ? alpha_align : alpha_lo;
        (void)feed(id, a, beta, VDC_NOM);
    }
    assert_int_equal(p, n);
    return qfoc_ident_result(id);
}

/* REQ-IDENT-003: the current bound at each window's end: the mean alpha current off the
   step's level by more than a quarter of it, or the mean beta current more than that
   from zero, gives ERR_NO_CURRENT; exactly a quarter does not.  The level is the step's
   own (i_hi in ALIGN, i_lo in R_LO).
   Methods: 1b alpha high and low, beta positive and negative (a beta current offset),
   ALIGN and R_LO; 1c the mean at level +- level / 4 (6554 +- 1638 passes, +- 1639 fails,
   beta +- 1638 / +- 1639, in R_LO 3277 +- 819 / 820); 1d a beta sensor offset, a test
   current not reached; 1l constant measured currents; 1n the header's rule evaluated
   here */
static void test_req_ident_003_no_current(void **state)
{
    static qfoc_ident_t id;
    static const int al[][3] = {
        /* alpha in ALIGN, beta, the alpha current in R_LO */
        { 6554 + 1638, 0, 3277 }, { 6554 + 1639, 0, 3277 },
        { 6554 - 1638, 0, 3277 }, { 6554 - 1639, 0, 3277 },
        { 6554, 1638, 3277 }, { 6554, 1639, 3277 },
        { 6554, -1638, 3277 }, { 6554, -1639, 3277 },
    };
    static const int lo[] = { 3277 + 819, 3277 + 820, 3277 - 819, 3277 - 820, 6554 };
    size_t j;
    (void)state;
    for (j = 0; j < sizeof al / sizeof al[0]; j++) {
        const double level = 6554.0;
        const bool fail = (fabs((double)al[j][0] - level) > (level / 4.0)) ||
                          (fabs((double)al[j][1]) > (level / 4.0));
        const uint8_t r = run_const(&id, al[j][0], al[j][2], al[j][1], 0);
        assert_int_equal(r, fail ? QFOC_IDENT_ERR_NO_CURRENT : QFOC_IDENT_RUNNING);
        assert_int_equal(qfoc_ident_step_now(&id), fail ? QFOC_IDENT_ALIGN : QFOC_IDENT_R_LO);
    }
    for (j = 0; j < sizeof lo / sizeof lo[0]; j++) {
        const double level = 3277.0;
        const bool fail = fabs((double)lo[j] - level) > (level / 4.0);
        const uint8_t r = run_const(&id, 6554, lo[j], 0, 1);
        assert_int_equal(r, fail ? QFOC_IDENT_ERR_NO_CURRENT : QFOC_IDENT_RUNNING);
        assert_int_equal(qfoc_ident_step_now(&id), fail ? QFOC_IDENT_R_LO : QFOC_IDENT_R_HI);
    }
}

/* REQ-IDENT-003: a turning rotor: a back-EMF on beta that the beta loop cancels with a
   mean command above v_move ends the mode with ERR_MOVED at the end of R_LO; in ALIGN
   the rule does not apply (a back-EMF from the start passes ALIGN); either sign; a
   back-EMF below v_move lets the mode finish.
   Methods: 1b a positive back-EMF from the start, a negative one after ALIGN, a small
   one; 1c the first step the rule applies to (R_LO) and the one it does not (ALIGN);
   1d a rotor that turns during the test; 1n the R-L model with a back-EMF and the
   header's bound on the mean beta command */
static void test_req_ident_003_moved(void **state)
{
    static qfoc_ident_t id;
    static const double emf[3] = { 600.0, -600.0, 150.0 };
    const qfoc_ident_cfg_t c = base_cfg();
    const int n_lo = (int)c.n_align + (int)c.n_settle + (2 << c.win_shift);
    int j;
    (void)state;
    for (j = 0; j < 3; j++) {
        plant_t pl = base_plant();
        qfoc_ident_sums_t h0;
        qfoc_ident_sums_t h1;
        int p;
        double vb;
        pl.emf = emf[j];
        pl.emf_from = (j == 1) ? ((int)c.n_align + (1 << c.win_shift)) : 0;
        assert_int_equal(qfoc_ident_start(&id, &c), QFOC_IDENT_RUNNING);
        p = run_plant(&id, &pl, 100000);
        assert_true(qfoc_ident_sums(&id, QFOC_IDENT_R_LO, 0u, &h0));
        assert_true(qfoc_ident_sums(&id, QFOC_IDENT_R_LO, 1u, &h1));
        vb = (double)(h0.vb_cmd + h1.vb_cmd) / (double)(h0.n + h1.n);
        /* the beta loop cancels the back-EMF: its mean command is the EMF within 2 % */
        assert_true(fabs(vb - emf[j]) < (0.02 * fabs(emf[j])));
        if (fabs(emf[j]) > c.v_move) {
            assert_int_equal(p, n_lo);
            assert_int_equal(qfoc_ident_result(&id), QFOC_IDENT_ERR_MOVED);
            assert_int_equal(qfoc_ident_step_now(&id), QFOC_IDENT_R_LO);
            assert_false(lg[n_lo - 1].out.enable);
            assert_true(lg[n_lo - 2].out.enable);
        } else {
            assert_int_equal(p, ref_total(&c));
            assert_int_equal(qfoc_ident_result(&id), QFOC_IDENT_DONE);
        }
    }
}

/* REQ-IDENT-003: abort ends a running mode at once (ERR_ABORT, PWM off in the following
   periods); in any other state it changes nothing.
   Methods: 1b running, idle, refused, finished, already failed; 1d an operator's stop;
   1n the header's rule */
static void test_req_ident_003_abort(void **state)
{
    static qfoc_ident_t id;
    qfoc_ident_cfg_t c = base_cfg();
    plant_t pl = base_plant();
    qfoc_pwm_t out;
    (void)state;
    run_to(&id, &pl, &c, 700);
    qfoc_ident_abort(&id);
    assert_int_equal(qfoc_ident_result(&id), QFOC_IDENT_ERR_ABORT);
    assert_int_equal(qfoc_ident_step_now(&id), QFOC_IDENT_R_LO);
    out = feed(&id, 0, 0, VDC_NOM);
    check_off(out);
    assert_int_equal(qfoc_ident_result(&id), QFOC_IDENT_ERR_ABORT);
    qfoc_ident_abort(&id);
    assert_int_equal(qfoc_ident_result(&id), QFOC_IDENT_ERR_ABORT);
    /* idle */
    qfoc_ident_init(&id);
    qfoc_ident_abort(&id);
    assert_int_equal(qfoc_ident_result(&id), QFOC_IDENT_IDLE);
    /* refused */
    c.i_lo = 0;
    assert_int_equal(qfoc_ident_start(&id, &c), QFOC_IDENT_ERR_CFG);
    qfoc_ident_abort(&id);
    assert_int_equal(qfoc_ident_result(&id), QFOC_IDENT_ERR_CFG);
    /* finished */
    c = base_cfg();
    pl = base_plant();
    assert_int_equal(qfoc_ident_start(&id, &c), QFOC_IDENT_RUNNING);
    (void)run_plant(&id, &pl, 100000);
    assert_int_equal(qfoc_ident_result(&id), QFOC_IDENT_DONE);
    qfoc_ident_abort(&id);
    assert_int_equal(qfoc_ident_result(&id), QFOC_IDENT_DONE);
    /* failed */
    run_to(&id, &pl, &c, 10);
    check_off(feed(&id, 0, 0, 0));
    qfoc_ident_abort(&id);
    assert_int_equal(qfoc_ident_result(&id), QFOC_IDENT_ERR_BUS);
}

/* REQ-IDENT-004: the output of a period that ends the mode at a window's end (the
   verdict ERR_NO_CURRENT or ERR_MOVED, or DONE after PSI) is "disabled, with every
   compare value at half the period" (ident.h, qfoc_ident_step's @return), as in every
   other disabled period: the compare values of that period are P / 2, not the modulated
   ones.
   Methods: 1b the three ways a window's end disables the output (DONE, NO_CURRENT,
   MOVED); 1c the last period of ALIGN, R_LO and L_Q; 1n the header's rule for a
   disabled output */
static void test_req_ident_004_off_at_window_end(void **state)
{
    static qfoc_ident_t id;
    const qfoc_ident_cfg_t c = base_cfg();
    int j;
    (void)state;
    for (j = 0; j < 3; j++) {
        plant_t pl = base_plant();
        int p;
        pl.open = (j == 1);
        pl.emf = (j == 2) ? 600.0 : 0.0;
        assert_int_equal(qfoc_ident_start(&id, &c), QFOC_IDENT_RUNNING);
        p = run_plant(&id, &pl, 100000);
        assert_int_equal(qfoc_ident_result(&id), (j == 0) ? QFOC_IDENT_DONE :
                         ((j == 1) ? QFOC_IDENT_ERR_NO_CURRENT : QFOC_IDENT_ERR_MOVED));
        assert_true(lg[p - 2].out.enable);
        check_off(lg[p - 1].out);
    }
}

/* the reference of a saturating accumulation */
static int64_t ref_sat(int64_t s, int64_t x, int64_t lim)
{
    const int64_t r = s + x;
    return (r > lim) ? lim : ((r < -lim) ? -lim : r);
}

/* REQ-IDENT-005: the window sums saturate: a 32-bit sum next to +-(2^31 - 1) and a 64-bit
   sum next to +-2^62 (set in the record directly, as no input can take them there)
   stop at the bound; a sum not at the bound adds exactly.
   Methods: 1c each sum one term from its bound, each sign; 1d a record overwritten with
   large values; 1l record fields set beyond what a run reaches; 1n the header's bounds
   QFOC_IDENT_SUM32_MAX and QFOC_IDENT_SUM64_MAX and the terms recomputed here */
static void test_req_ident_005_saturation(void **state)
{
    static qfoc_ident_t id;
    const qfoc_ident_cfg_t c = base_cfg();
    const int64_t m32 = 2147483647;
    const int64_t m64 = (int64_t)1 << 62;
    int p;
    int j;
    (void)state;
    assert_true(m32 == QFOC_IDENT_SUM32_MAX);
    assert_true(m64 == QFOC_IDENT_SUM64_MAX);
    for (j = 0; j < 2; j++) {
        const int sg = (j == 0) ? 1 : -1;
        const int alpha = 6554;
        const int beta = -100 * sg;
        qfoc_ident_sums_t z0;
        qfoc_ident_sums_t z1;
        qfoc_pwm_t out;
        int k;
        int64_t cs;
        int64_t sn;
        int64_t ua;
        int64_t ub;
        assert_int_equal(qfoc_ident_start(&id, &c), QFOC_IDENT_RUNNING);
        /* to the window's first period, k = n_align % 16 + 2 = 14 (cos, sin = +-23170) */
        for (p = 0; p < ((int)c.n_align + 2); p++) {
            (void)feed(&id, alpha, 0, VDC_NOM);
        }
        k = p % 16;
        id.rec.s[0][0].n = (int32_t)m32;
        id.rec.s[0][0].i_a = (int32_t)((m32 - alpha) + 1);
        id.rec.s[0][0].i_b = (int32_t)(sg * (-m32 + 50));
        id.rec.s[0][0].u_a = (int32_t)(sg * 5);
        id.rec.s[0][0].vdc = (int32_t)(m32 - 5);
        id.rec.s[0][0].u_c = sg * (m64 - 1);
        id.rec.s[0][0].u_s = -sg * (m64 - 1);
        id.rec.s[0][0].v_c = -sg * (m64 - 1);
        id.rec.s[0][0].v_s = sg * 77;
        id.rec.s[0][0].i_c = m64 - 1;
        id.rec.s[0][0].i_s = -(m64 - 1);
        id.rec.s[0][0].j_c = sg * (m64 - 1);
        id.rec.s[0][0].j_s = 12345;
        z0 = id.rec.s[0][0];
        out = feed(&id, alpha, beta, VDC_NOM);
        assert_true(out.enable);
        z1 = id.rec.s[0][0];
        cs = ref_cos(k);
        sn = ref_sin(k);
        ua = (2 * (int64_t)out.cmp[0]) - out.cmp[1] - out.cmp[2];
        ub = (int64_t)out.cmp[1] - out.cmp[2];
        assert_true(z1.n == m32);                         /* saturated */
        assert_true(z1.i_a == m32);                       /* saturated */
        assert_true(z1.i_b == ref_sat(z0.i_b, beta, m32));
        assert_true(z1.u_a == ref_sat(z0.u_a, ua, m32));
        assert_true(z1.u_b == ref_sat(z0.u_b, ub, m32));
        assert_true(z1.vdc == m32);                       /* saturated */
        assert_true(z1.u_c == ref_sat(z0.u_c, ua * cs, m64));
        assert_true(z1.u_s == ref_sat(z0.u_s, ua * sn, m64));
        assert_true(z1.v_c == ref_sat(z0.v_c, ub * cs, m64));
        assert_true(z1.v_s == z0.v_s + (ub * sn));
        assert_true(z1.i_c == ref_sat(z0.i_c, alpha * cs, m64));
        assert_true(z1.i_s == ref_sat(z0.i_s, alpha * sn, m64));
        assert_true(z1.j_c == ref_sat(z0.j_c, beta * cs, m64));
        assert_true(z1.j_s == z0.j_s + (beta * sn));
        /* k = 14: cos > 0, sin < 0: alpha's cos term takes i_c to the upper bound, its
           sin term i_s to the lower one; beta's cos term moves j_c away from its bound,
           exactly */
        assert_true((cs > 0) && (sn < 0));
        assert_true(z1.i_c == m64);
        assert_true(z1.i_s == -m64);
        assert_true(z1.j_c == (z0.j_c + (beta * cs)));
        /* the 32-bit sum i_b at -sg (2^31 - 50) and a term of the same sign: its bound */
        if (sg == 1) {
            assert_true(z1.i_b == -m32);
        } else {
            assert_true(z1.i_b == m32);
        }
    }
}

/* REQ-IDENT-005: a sum already beyond its bound (a record written by other code than the
   mode's) is first brought to the bound, then the term is added and the result saturated
   again: the 32-bit sums from -2^31 with a zero term, the 64-bit ones from the type's
   extremes.
   Methods: 1c -2^31 and +-(2^63 - 1) or -2^63 in the sums, a zero and a non-zero term;
   1d a record changed behind the mode's back */
static void test_req_ident_005_sums_beyond_bound(void **state)
{
    static qfoc_ident_t id;
    const qfoc_ident_cfg_t c = base_cfg();
    const int64_t m32 = 2147483647;
    const int64_t m64 = (int64_t)1 << 62;
    const int alpha = 6554;
    qfoc_ident_sums_t z1;
    qfoc_pwm_t out;
    int64_t cs;
    int64_t sn;
    int64_t ua;
    int p;
    int k;
    (void)state;
    assert_int_equal(qfoc_ident_start(&id, &c), QFOC_IDENT_RUNNING);
    for (p = 0; p < ((int)c.n_align + 2); p++) {
        (void)feed(&id, alpha, 0, VDC_NOM);
    }
    k = p % 16;
    id.rec.s[0][0].i_b = INT32_MIN;
    id.rec.s[0][0].vb_cmd = INT32_MIN;
    id.rec.s[0][0].u_c = INT64_MAX;
    id.rec.s[0][0].u_s = INT64_MIN;
    id.rec.s[0][0].i_c = INT64_MIN;
    id.rec.s[0][0].j_s = INT64_MAX;
    out = feed(&id, alpha, 0, VDC_NOM);
    assert_true(out.enable);
    z1 = id.rec.s[0][0];
    cs = ref_cos(k);
    sn = ref_sin(k);
    ua = (2 * (int64_t)out.cmp[0]) - out.cmp[1] - out.cmp[2];
    /* beta 0 and ALIGN's beta command 0: -2^31 + 0 is brought to -(2^31 - 1) */
    assert_true(z1.i_b == -m32);
    assert_true(z1.vb_cmd == -m32);
    /* from the bound of each sign, the term added, then saturated */
    assert_true(z1.u_c == ref_sat(m64, ua * cs, m64));
    assert_true(z1.u_s == ref_sat(-m64, ua * sn, m64));
    assert_true(z1.i_c == ref_sat(-m64, alpha * cs, m64));
    assert_true(z1.j_s == m64);  /* beta 0: the bound itself */
    assert_true((cs > 0) && (z1.i_c == -m64 + (alpha * cs)));
}

/* REQ-IDENT-005: the record's accessor: every step and half in range copies the sums,
   step 6 or half 2 (and the type's largest values) give false and all zero.
   Methods: 1b in and out of range, each index on its own; 1c step 5 / 6, half 1 / 2,
   255; 1n the header's contract */
static void test_req_ident_005_sums_range(void **state)
{
    static qfoc_ident_t id;
    static const uint8_t bad[][2] = { { 6u, 0u }, { 0u, 2u }, { 6u, 2u }, { 255u, 1u },
                                      { 5u, 255u } };
    qfoc_ident_sums_t z;
    size_t j;
    int s;
    int h;
    int f;
    (void)state;
    qfoc_ident_init(&id);
    for (s = 0; s < NSTEP; s++) {
        for (h = 0; h < 2; h++) {
            id.rec.s[s][h].n = (int32_t)((s * 2) + h + 1);
            id.rec.s[s][h].j_s = -(int64_t)((s * 2) + h + 1) * 1000000007;
        }
    }
    for (s = 0; s < NSTEP; s++) {
        for (h = 0; h < 2; h++) {
            memset(&z, 0x77, sizeof z);
            assert_true(qfoc_ident_sums(&id, (uint8_t)s, (uint8_t)h, &z));
            for (f = 0; f < NF; f++) {
                assert_true(field_of(&z, f) == field_of(&id.rec.s[s][h], f));
            }
            assert_int_equal(z.n, (s * 2) + h + 1);
        }
    }
    for (j = 0; j < sizeof bad / sizeof bad[0]; j++) {
        memset(&z, 0x77, sizeof z);
        assert_false(qfoc_ident_sums(&id, bad[j][0], bad[j][1], &z));
        for (f = 0; f < NF; f++) {
            assert_true(field_of(&z, f) == 0);
        }
    }
}

/* a data frame's value: bytes 2 .. 7, 48-bit two's complement, little endian */
static int64_t decode48(const uint8_t *b)
{
    uint64_t u = 0u;
    int j;
    for (j = 7; j >= 2; j--) {
        u = (u << 8) | b[j];
    }
    return (u >= ((uint64_t)1 << 47)) ? ((int64_t)u - ((int64_t)1 << 48)) : (int64_t)u;
}

/* every data frame of a state against qfoc_ident_sums (values within 48 bits);
   returns the number of negative values seen */
static int check_frames(const qfoc_ident_t *id)
{
    const int frames = 1 + (NSTEP * 2 * NF);
    int negative = 0;
    int k;
    for (k = 1; k < frames; k++) {
        const int j = k - 1;
        const int s = j / (2 * NF);
        const int h = (j / NF) % 2;
        const int f = j % NF;
        uint8_t buf[8];
        qfoc_ident_sums_t z;
        int64_t v;
        memset(buf, 0xEE, sizeof buf);
        assert_true(qfoc_ident_frame(id, (uint16_t)k, buf));
        assert_int_equal(buf[0], k & 0xFF);
        assert_int_equal(buf[1], (32 * s) + (16 * h) + f);
        assert_true(qfoc_ident_sums(id, (uint8_t)s, (uint8_t)h, &z));
        v = decode48(buf);
        assert_true(v == field_of(&z, f));
        negative += (v < 0) ? 1 : 0;
    }
    return negative;
}

/* REQ-IDENT-005: the frames: frame 0's layout (0xA5, result, step, win_shift, period and
   the frame count little endian), every data frame decoded back (byte 0 = k, byte 1 =
   32 step + 16 half + field, a 48-bit two's complement little-endian value) equal to
   qfoc_ident_sums's field, for a real record and for random values of either sign; a
   value beyond 48 bits sent as the bound of its sign, +-(2^47 - 1) (the library's
   symmetric saturation); k out of range false with all eight bytes zero.
   Methods: 1b header and data frames, every step, half and field, both signs; 1c values
   +-(2^47 - 1), +-2^47, +-2^62 and the 32-bit extremes, k = 180 / 181 / 65535; 1d a
   saturated sum sent over a narrower field; 1n the decoding written here from the
   header */
static void test_req_ident_005_frames(void **state)
{
    static qfoc_ident_t id;
    const qfoc_ident_cfg_t c = base_cfg();
    plant_t pl = base_plant();
    const int frames = 1 + (NSTEP * 2 * NF);
    const int64_t l47 = ((int64_t)1 << 47) - 1;
    uint8_t buf[8];
    int s;
    int h;
    int j;
    (void)state;
    assert_int_equal(QFOC_IDENT_FRAMES, frames);
    assert_int_equal(qfoc_ident_start(&id, &c), QFOC_IDENT_RUNNING);
    (void)run_plant(&id, &pl, 100000);
    assert_int_equal(qfoc_ident_result(&id), QFOC_IDENT_DONE);

    /* frame 0 */
    memset(buf, 0xEE, sizeof buf);
    assert_true(qfoc_ident_frame(&id, 0u, buf));
    assert_int_equal(buf[0], 0xA5);
    assert_int_equal(buf[1], QFOC_IDENT_DONE);
    assert_int_equal(buf[2], QFOC_IDENT_PSI);
    assert_int_equal(buf[3], c.win_shift);
    assert_int_equal(buf[4] | (buf[5] << 8), PERIOD);
    assert_int_equal(buf[6] | (buf[7] << 8), frames);

    /* the run's record: the beta sums and the sin sums hold negative values */
    assert_true(check_frames(&id) > 0);

    /* random values of either sign in every field */
    for (s = 0; s < NSTEP; s++) {
        for (h = 0; h < 2; h++) {
            qfoc_ident_sums_t *z = &id.rec.s[s][h];
            z->n = (int32_t)lcg_next();
            z->i_a = (int32_t)lcg_next();
            z->i_b = (int32_t)lcg_next();
            z->u_a = (int32_t)lcg_next();
            z->u_b = (int32_t)lcg_next();
            z->vdc = (int32_t)lcg_next();
            z->vb_cmd = (int32_t)lcg_next();
            z->u_c = (int64_t)rand_range(INT32_MIN, INT32_MAX) * 65536;
            z->u_s = (int64_t)rand_range(INT32_MIN, INT32_MAX) * 1024;
            z->v_c = -(int64_t)rand_range(0, INT32_MAX) * 4096;
            z->v_s = (int64_t)rand_range(INT32_MIN, INT32_MAX) * 3;
            z->i_c = (int64_t)rand_range(INT32_MIN, INT32_MAX);
            z->i_s = (int64_t)rand_range(-100, 100);
            z->j_c = (int64_t)rand_range(INT32_MIN, INT32_MAX) * 32768;
            z->j_s = (int64_t)rand_range(INT32_MIN, INT32_MAX) * 65535;
        }
    }
    id.rec.s[0][0].i_a = INT32_MIN;
    id.rec.s[0][1].i_b = INT32_MAX;
    id.rec.s[1][0].u_c = l47;
    id.rec.s[1][1].u_s = -l47;
    id.rec.s[5][1].j_s = -1;
    id.rec.s[5][0].v_s = -l47;
    assert_true(check_frames(&id) > 20);

    /* beyond 48 bits: the bound of the sign */
    {
        static const int64_t big[] = { (int64_t)1 << 47, -((int64_t)1 << 47),
                                       (int64_t)1 << 62, -((int64_t)1 << 62),
                                       INT64_MAX, INT64_MIN };
        for (j = 0; j < (int)(sizeof big / sizeof big[0]); j++) {
            const int f = 7 + (j % 8);          /* u_c .. j_s */
            const int st = j % NSTEP;
            const int hf = j % 2;
            const int k = 1 + (st * 2 * NF) + (hf * NF) + f;
            int64_t *p64[8];
            p64[0] = &id.rec.s[st][hf].u_c;
            p64[1] = &id.rec.s[st][hf].u_s;
            p64[2] = &id.rec.s[st][hf].v_c;
            p64[3] = &id.rec.s[st][hf].v_s;
            p64[4] = &id.rec.s[st][hf].i_c;
            p64[5] = &id.rec.s[st][hf].i_s;
            p64[6] = &id.rec.s[st][hf].j_c;
            p64[7] = &id.rec.s[st][hf].j_s;
            *p64[f - 7] = big[j];
            memset(buf, 0xEE, sizeof buf);
            assert_true(qfoc_ident_frame(&id, (uint16_t)k, buf));
            assert_int_equal(buf[1], (32 * st) + (16 * hf) + f);
            assert_true(decode48(buf) == ((big[j] > 0) ? l47 : -l47));
        }
    }

    /* the last frame and those beyond */
    assert_true(qfoc_ident_frame(&id, (uint16_t)(frames - 1), buf));
    assert_int_equal(buf[1], (32 * 5) + 16 + 14);
    {
        static const uint16_t out[] = { 181u, 182u, 256u, 65535u };
        for (j = 0; j < 4; j++) {
            int b;
            memset(buf, 0xEE, sizeof buf);
            assert_false(qfoc_ident_frame(&id, out[j], buf));
            for (b = 0; b < 8; b++) {
                assert_int_equal(buf[b], 0);
            }
        }
    }
    /* frame 0 of an idle state */
    qfoc_ident_init(&id);
    assert_true(qfoc_ident_frame(&id, 0u, buf));
    assert_int_equal(buf[0], 0xA5);
    assert_int_equal(buf[1], QFOC_IDENT_IDLE);
    assert_int_equal(buf[2], QFOC_IDENT_ALIGN);
    assert_int_equal(buf[3], 0);
    assert_int_equal(buf[4] | (buf[5] << 8), 0);
    assert_int_equal(buf[6] | (buf[7] << 8), frames);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_req_ident_001_cfg_conditions),
        cmocka_unit_test(test_req_ident_001_cfg_random),
        cmocka_unit_test(test_req_ident_001_init_start),
        cmocka_unit_test(test_req_ident_002_model_run),
        cmocka_unit_test(test_req_ident_002_window_extremes),
        cmocka_unit_test(test_req_ident_002_injection_amplitude),
        cmocka_unit_test(test_req_ident_002_longest_settling),
        cmocka_unit_test(test_req_ident_003_overcurrent),
        cmocka_unit_test(test_req_ident_003_bus),
        cmocka_unit_test(test_req_ident_003_open_circuit),
        cmocka_unit_test(test_req_ident_003_no_current),
        cmocka_unit_test(test_req_ident_003_moved),
        cmocka_unit_test(test_req_ident_003_abort),
        cmocka_unit_test(test_req_ident_004_off_at_window_end),
        cmocka_unit_test(test_req_ident_005_saturation),
        cmocka_unit_test(test_req_ident_005_sums_beyond_bound),
        cmocka_unit_test(test_req_ident_005_sums_range),
        cmocka_unit_test(test_req_ident_005_frames),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
