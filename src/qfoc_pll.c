/**
 * @file qfoc_pll.c
 * @brief PLL on the rotor flux and angle-tracking observer on the back-EMF
 *        (specs/equations.md E2-27, E2-28, E2-34; see include/qfoc/pll.h).
 *
 * Requirements: REQ-PLL-001 .. REQ-PLL-012 (specs/requirements/pll.md).
 */
#include "qfoc/pll.h"
#include "qfoc/q15.h"
#include "qfoc/trig.h"
#include "qfoc/vector.h"

/** Accumulator counts per electrical turn: 2^32 = 4294967296. */
#define QFOC_PLL_ACC_TURN ((int64_t)4294967296)
/** Largest accumulator value: 2^32 - 1 = 4294967295. */
#define QFOC_PLL_ACC_MAX ((int64_t)4294967295)
/** Accumulator counts per qfoc_angle_t count: 2^32 / 2^16 = 65536. */
#define QFOC_PLL_ACC_PER_COUNT (65536u)
/** Half an angle count in accumulator counts, the rounding threshold: 32768. */
#define QFOC_PLL_ACC_HALF_COUNT (32768u)
/** Angle counts per turn (qfoc_angle_t modulo): 2^16 = 65536. */
#define QFOC_PLL_ANGLE_MOD (65536u)
/** Safe state: error clamp 1 / 32768 (a rejected configuration never moves). */
#define QFOC_PLL_SAFE_ERR_CLAMP ((qfoc_q15_t)1)
/** Safe state: mag_min 32767 = 0.99997 (coasts unless the input saturates). */
#define QFOC_PLL_SAFE_MAG_MIN ((qfoc_q15_t)32767)
/** Safe state: k_theta 1 (2^-32 turn per speed LSB; the safe speed is 0 anyway). */
#define QFOC_PLL_SAFE_K_THETA ((uint16_t)1u)
/** Safe state: speed low-pass alpha 32767 / 32768 = 0.99997 (passes the speed on). */
#define QFOC_PLL_SAFE_ALPHA ((qfoc_q15_t)32767)

/**
 * @brief Output angle of an accumulator value: round(acc / 65536) mod 2^16.
 */
/*@
  assigns \nothing;
  ensures value: \result == PllAngle(acc);
*/
static qfoc_angle_t qfoc_pll_angle(uint32_t acc)
{
    /* acc / 2^16 in [0, 65535]; + 1 for a remainder of half a count or more */
    uint32_t counts = acc / QFOC_PLL_ACC_PER_COUNT;
    const uint32_t rem = acc % QFOC_PLL_ACC_PER_COUNT;
    if (rem >= QFOC_PLL_ACC_HALF_COUNT) {
        counts = counts + 1u;
    } else {
        /* rounds down */
    }
    /* counts <= 65536: one turn maps back to 0 (modulo 2^16) */
    return (qfoc_angle_t)(counts % QFOC_PLL_ANGLE_MOD);
}

/**
 * @brief Accumulator update (acc + speed x k) mod 2^32 (E2-28), without any
 *        wrap-around in a C type.
 */
/*@
  requires k_range: 1 <= k <= 32767;
  assigns \nothing;
  ensures value: \result == PllAccNext(acc, speed * k);
  ensures modulo: (\result - (acc + speed * k)) % 4294967296 == 0;
*/
static uint32_t qfoc_pll_acc_add(uint32_t acc, qfoc_q15_t speed, uint16_t k)
{
    int32_t inc;
    int64_t sum;
    /*@ assert inc_hi: speed * k <= 32767 * 32767; */
    /*@ assert inc_lo: speed * k >= -32768 * 32767; */
    /* speed (Q15 of w_base) x k_theta = 2^-32 turns per sample,
       |.| <= 32768 x 32767 < 2^30 */
    inc = (int32_t)speed * (int32_t)k;
    /* acc + inc in (-2^30, 2^32 + 2^30): 64-bit signed, exact */
    sum = (int64_t)acc + (int64_t)inc;
    /* modulo 2^32 by one correction: the angle wraps at a full turn by design */
    if (sum < 0) {
        sum = sum + QFOC_PLL_ACC_TURN;
    } else if (sum > QFOC_PLL_ACC_MAX) {
        sum = sum - QFOC_PLL_ACC_TURN;
    } else {
        /* inside [0, 2^32 - 1] */
    }
    return (uint32_t)sum;
}

/**
 * @brief Normalised, clamped phase-detector output; 0 below mag_min.
 */
/*@
  requires x_range: QfocQ15Sym(x);
  requires y_range: QfocQ15Sym(y);
  requires s_range: QfocQ15Sym(s);
  requires c_range: QfocQ15Sym(c);
  requires mag_range: 0 <= mag <= 32767;
  requires mag_min_range: 1 <= mag_min;
  requires clamp_range: 1 <= clamp;
  assigns \nothing;
  ensures value: \result == PllErr(PllE30(x, y, s, c), mag, mag_min, clamp);
  ensures range: -clamp <= \result <= clamp;
  ensures coast: mag < mag_min ==> \result == 0;
  ensures track: mag >= mag_min ==>
    \result == QfocClamp(QfocRoundDiv(PllE30(x, y, s, c), mag), -clamp, clamp);
*/
static qfoc_q15_t qfoc_pll_error(qfoc_q15_t x, qfoc_q15_t y, qfoc_q15_t s, qfoc_q15_t c,
                                 qfoc_q15_t mag, qfoc_q15_t mag_min, qfoc_q15_t clamp)
{
    int32_t err = 0;
    if (mag >= mag_min) {
        const int32_t m = (int32_t)mag;
        const int32_t half = m / 2;
        const int32_t lim = (int32_t)clamp;
        int32_t e30;
        /*@ assert yc_hi: y * c <= 32767 * 32767; */
        /*@ assert yc_lo: y * c >= -(32767 * 32767); */
        /*@ assert xs_hi: x * s <= 32767 * 32767; */
        /*@ assert xs_lo: x * s >= -(32767 * 32767); */
        /* Delta theta = psi_beta cos - psi_alpha sin: Q15 x Q15 = Q30,
           |.| <= 2 x 32767^2 = 2147352578 < 2^31 */
        e30 = ((int32_t)y * (int32_t)c) - ((int32_t)x * (int32_t)s);
        /* Q30 / Q15 magnitude = Q15 sin(theta_r - theta), rounded to nearest
           (ties away from zero); m >= mag_min >= 1, e30 +- m / 2 < 2^31 */
        if (e30 >= 0) {
            err = (e30 + half) / m;
        } else {
            err = -((half - e30) / m);
        }
        /*@ assert rounded: err == QfocRoundDiv(e30, m); */
        if (err > lim) {
            err = lim;
        } else if (err < -lim) {
            err = -lim;
        } else {
            /* inside the clamp */
        }
    } else {
        /* magnitude below mag_min: coast with error 0 */
    }
    return (qfoc_q15_t)err;
}

/**
 * @brief Write the results of one sample to the output struct.
 */
/*@
  requires valid_out: \valid(out);
  assigns *out;
  ensures theta: out->theta == theta && out->theta_next == theta_next;
  ensures sc: out->sc.sine == sine && out->sc.cosine == cosine;
  ensures speed: out->speed == speed && out->speed_f == speed_f;
  ensures error: out->error == error && out->mag == mag;
*/
static void qfoc_pll_put(qfoc_pll_out_t *out, qfoc_angle_t theta, qfoc_angle_t theta_next,
                         qfoc_q15_t sine, qfoc_q15_t cosine, qfoc_q15_t speed,
                         qfoc_q15_t speed_f, qfoc_q15_t error, qfoc_q15_t mag)
{
    out->theta = theta;
    out->theta_next = theta_next;
    out->sc.sine = sine;
    out->sc.cosine = cosine;
    out->speed = speed;
    out->speed_f = speed_f;
    out->error = error;
    out->mag = mag;
}

/**
 * @brief One sample of the loop (steps 1 to 6 of qfoc_pll_step()) on an
 *        already saturated vector (x, y).  Every intermediate value is a local
 *        variable; the instance is updated first, the outputs are written last.
 */
/*@
  requires valid_pll: \valid(pll);
  requires valid_out: \valid(out);
  requires sep: \separated(pll, out);
  requires pll_valid: PllValid(pll);
  requires x_range: QfocQ15Sym(x);
  requires y_range: QfocQ15Sym(y);
  assigns pll->pi.integ, pll->pi.limited, pll->speed_lpf.state, pll->theta_acc,
          pll->speed, *out;
  ensures still_valid: PllValid(pll);
  ensures config: pll->mag_min == \old(pll->mag_min) &&
                  pll->err_clamp == \old(pll->err_clamp) &&
                  pll->k_theta == \old(pll->k_theta);
  ensures theta: out->theta == PllAngle(\old(pll->theta_acc));
  ensures sincos_range: QfocQ15Sym(out->sc.sine) && QfocQ15Sym(out->sc.cosine);
  ensures mag: PllMag(out->mag, x, y);
  ensures below: PllCoast(x, y, \old(pll->mag_min)) <==> out->mag < \old(pll->mag_min);
  ensures error: out->error ==
    PllErr(PllE30(x, y, out->sc.sine, out->sc.cosine), out->mag,
           \old(pll->mag_min), \old(pll->err_clamp));
  ensures error_range: -\old(pll->err_clamp) <= out->error <= \old(pll->err_clamp);
  ensures coast: out->mag < \old(pll->mag_min) ==> out->error == 0;
  ensures track: out->mag >= \old(pll->mag_min) ==>
    out->error == QfocClamp(QfocRoundDiv(PllE30(x, y, out->sc.sine, out->sc.cosine), out->mag),
                            -\old(pll->err_clamp), \old(pll->err_clamp));
  ensures speed: out->speed == PllPiOut{Pre}(&pll->pi, out->error);
  ensures speed_range: pll->pi.params.out_min <= out->speed <= pll->pi.params.out_max;
  ensures speed_state: pll->speed == out->speed;
  ensures integ: pll->pi.integ == PiNextInteg{Pre}(&pll->pi, out->error);
  ensures acc: pll->theta_acc ==
    PllAccNext(\old(pll->theta_acc), out->speed * \old(pll->k_theta));
  ensures acc_mod:
    (pll->theta_acc - (\old(pll->theta_acc) + out->speed * \old(pll->k_theta)))
      % 4294967296 == 0;
  ensures theta_next: out->theta_next == PllAngle(pll->theta_acc);
  ensures speed_lpf: pll->speed_lpf.state ==
    LpfNext(\old(pll->speed_lpf.state), out->speed, \old(pll->speed_lpf.alpha));
  ensures speed_f: out->speed_f == QfocSat15(QfocRoundDiv(pll->speed_lpf.state, 65536));
*/
static void qfoc_pll_loop(qfoc_pll_t *pll, qfoc_q15_t x, qfoc_q15_t y, qfoc_pll_out_t *out)
{
    const uint32_t acc = pll->theta_acc;
    const qfoc_angle_t theta = qfoc_pll_angle(acc);
    qfoc_sincos_t sc;
    qfoc_q15_t sine;
    qfoc_q15_t cosine;
    qfoc_q15_t mag;
    qfoc_q15_t error;
    qfoc_q15_t speed;
    qfoc_q15_t speed_f;
    uint32_t acc_next;

    /* 1. sine and cosine of the present estimate */
    qfoc_sincos(theta, &sc);
    sine = sc.sine;
    cosine = sc.cosine;
    /* 2. magnitude of the input */
    mag = qfoc_vec_mag(x, y);
    /*@ assert mm_sq: pll->mag_min * pll->mag_min <= 32767 * 32767; */
    /*@ assert below: PllCoast(x, y, pll->mag_min) <==> mag < pll->mag_min; */
    /* 3. normalised phase detector; coasting below mag_min */
    error = qfoc_pll_error(x, y, sine, cosine, mag, pll->mag_min, pll->err_clamp);
    /* 4. speed = Delta theta (kp + ki / s) (E2-27) */
    speed = qfoc_pi_step(&pll->pi, error);
    /* 5. theta = theta + omega / f_pwm (E2-28), modulo one turn */
    acc_next = qfoc_pll_acc_add(acc, speed, pll->k_theta);
    /* 6. speed low-pass (E2-34) */
    speed_f = qfoc_lpf_step(&pll->speed_lpf, speed);
    pll->theta_acc = acc_next;
    pll->speed = speed;
    /*@ assert valid_before_output: PllValid(pll); */

    qfoc_pll_put(out, theta, qfoc_pll_angle(acc_next), sine, cosine, speed, speed_f,
                 error, mag);
}

/**
 * @brief An input component saturated to the symmetric Q15 range.
 */
/*@
  assigns \nothing;
  ensures value: \result == QfocSat15(v);
  ensures range: QfocQ15Sym(\result);
*/
static qfoc_q15_t qfoc_pll_in(qfoc_q15_t v)
{
    return qfoc_q15_sat((int32_t)v);
}

/**
 * @brief First component of the flux direction from an EMF: e_beta for a
 *        non-negative speed integrator, -e_beta otherwise.
 */
/*@
  assigns \nothing;
  ensures value: \result == PllAtoX(integ, eb);
  ensures range: QfocQ15Sym(\result);
*/
static qfoc_q15_t qfoc_pll_ato_x(qfoc_q31_t integ, qfoc_q15_t eb)
{
    const qfoc_q15_t b = qfoc_q15_sat((int32_t)eb);
    qfoc_q15_t r;
    if (integ >= 0) {
        r = b;
    } else {
        /* exact: b is in [-32767, 32767] */
        r = qfoc_q15_neg(b);
    }
    return r;
}

/**
 * @brief Second component of the flux direction from an EMF: -e_alpha for a
 *        non-negative speed integrator, e_alpha otherwise.
 */
/*@
  assigns \nothing;
  ensures value: \result == PllAtoY(integ, ea);
  ensures range: QfocQ15Sym(\result);
*/
static qfoc_q15_t qfoc_pll_ato_y(qfoc_q31_t integ, qfoc_q15_t ea)
{
    const qfoc_q15_t a = qfoc_q15_sat((int32_t)ea);
    qfoc_q15_t r;
    if (integ >= 0) {
        /* exact: a is in [-32767, 32767] */
        r = qfoc_q15_neg(a);
    } else {
        r = a;
    }
    return r;
}

/**
 * @brief Store a parameter set in an instance (no check; see qfoc_pll_init()).
 */
/*@
  requires valid_pll: \valid(pll);
  requires valid_pi: \valid_read(pi);
  requires sep: \separated(pll, pi);
  assigns pll->pi.params, pll->speed_lpf.alpha, pll->err_clamp, pll->mag_min, pll->k_theta;
  ensures pi: pll->pi.params.kp == \old(pi->kp) && pll->pi.params.kp_shift == \old(pi->kp_shift) &&
              pll->pi.params.ki == \old(pi->ki) && pll->pi.params.ki_shift == \old(pi->ki_shift) &&
              pll->pi.params.out_min == \old(pi->out_min) &&
              pll->pi.params.out_max == \old(pi->out_max);
  ensures params: pll->err_clamp == err_clamp && pll->mag_min == mag_min &&
                  pll->k_theta == k_theta && pll->speed_lpf.alpha == alpha;
*/
static void qfoc_pll_store(qfoc_pll_t *pll, const qfoc_pi_params_t *pi, qfoc_q15_t err_clamp,
                           qfoc_q15_t mag_min, uint16_t k_theta, qfoc_q15_t alpha)
{
    pll->pi.params.kp = pi->kp;
    pll->pi.params.kp_shift = pi->kp_shift;
    pll->pi.params.ki = pi->ki;
    pll->pi.params.ki_shift = pi->ki_shift;
    pll->pi.params.out_min = pi->out_min;
    pll->pi.params.out_max = pi->out_max;
    pll->speed_lpf.alpha = alpha;
    pll->err_clamp = err_clamp;
    pll->mag_min = mag_min;
    pll->k_theta = k_theta;
}

/**
 * @brief Angle and speed preset shared by qfoc_pll_init() and qfoc_pll_reset()
 *        (contract of qfoc_pll_reset()).
 */
/*@
  requires valid_pll: \valid(pll);
  requires config_valid: PllConfigValid(pll);
  assigns pll->theta_acc, pll->speed, pll->pi.integ, pll->pi.limited,
          pll->speed_lpf.state;
  ensures valid: PllValid(pll);
  ensures acc: pll->theta_acc == theta * 65536;
  ensures speed: pll->speed == QfocClamp(speed, pll->pi.params.out_min, pll->pi.params.out_max);
  ensures integ: pll->pi.integ == pll->speed * 65536;
  ensures lpf: pll->speed_lpf.state == pll->speed * 65536;
*/
static void qfoc_pll_preset(qfoc_pll_t *pll, qfoc_angle_t theta, qfoc_q15_t speed)
{
    qfoc_q15_t s = speed;
    if (s > pll->pi.params.out_max) {
        s = pll->pi.params.out_max;
    } else if (s < pll->pi.params.out_min) {
        s = pll->pi.params.out_min;
    } else {
        /* inside the speed limits */
    }
    /* theta x 2^16 <= 65535 x 65536 < 2^32: the accumulator of that angle */
    pll->theta_acc = (uint32_t)theta * QFOC_PLL_ACC_PER_COUNT;
    qfoc_pi_reset(&pll->pi, s);
    qfoc_lpf_reset(&pll->speed_lpf, s);
    pll->speed = s;
}

/* public interface, also called by qfoc_pll_init (DEV-002) */
/* cppcheck-suppress misra-c2012-8.7 ; DEV-002 */
bool qfoc_pll_params_is_valid(const qfoc_pll_params_t *p)
{
    bool ok = qfoc_pi_params_is_valid(&p->pi);
    if (!ok) {
        /* invalid PI parameters */
    } else if ((p->err_clamp < 1) || (p->mag_min < 1) || (p->speed_alpha < 1)) {
        ok = false;
    } else if ((p->k_theta < 1u) || (p->k_theta > QFOC_PLL_K_THETA_MAX)) {
        ok = false;
    } else {
        /* every parameter in range */
    }
    return ok;
}

bool qfoc_pll_is_valid(const qfoc_pll_t *pll)
{
    bool ok = qfoc_pi_is_valid(&pll->pi) && qfoc_lpf_is_valid(&pll->speed_lpf);
    if (!ok) {
        /* invalid PI or low-pass */
    } else if ((pll->err_clamp < 1) || (pll->mag_min < 1)) {
        ok = false;
    } else if ((pll->k_theta < 1u) || (pll->k_theta > QFOC_PLL_K_THETA_MAX)) {
        ok = false;
    } else if ((pll->speed < pll->pi.params.out_min) || (pll->speed > pll->pi.params.out_max)) {
        ok = false;
    } else {
        /* valid instance */
    }
    return ok;
}

int32_t qfoc_pll_init(qfoc_pll_t *pll, const qfoc_pll_params_t *p)
{
    int32_t status;
    if (qfoc_pll_params_is_valid(p)) {
        qfoc_pll_store(pll, &p->pi, p->err_clamp, p->mag_min, p->k_theta, p->speed_alpha);
        status = QFOC_PLL_OK;
    } else {
        /* safe state: zero gains and limits [0, 0] (the speed stays 0), coasting
           unless the input saturates, smallest angle step, fastest low-pass */
        const qfoc_pi_params_t safe_pi = { 0, 0u, 0, 0u, 0, 0 };
        qfoc_pll_store(pll, &safe_pi, QFOC_PLL_SAFE_ERR_CLAMP, QFOC_PLL_SAFE_MAG_MIN,
                       QFOC_PLL_SAFE_K_THETA, QFOC_PLL_SAFE_ALPHA);
        status = QFOC_PLL_ERR_PARAM;
    }
    /* angle 0, speed at the point of [out_min, out_max] nearest to 0: PI
       integrator and limit flag (qfoc_pi_reset()), low-pass state
       (qfoc_lpf_reset()) and stored speed */
    qfoc_pll_preset(pll, 0u, 0);
    return status;
}

void qfoc_pll_reset(qfoc_pll_t *pll, qfoc_angle_t theta, qfoc_q15_t speed)
{
    qfoc_pll_preset(pll, theta, speed);
}

void qfoc_pll_step(qfoc_pll_t *pll, const qfoc_ab_t *psi, qfoc_pll_out_t *out)
{
    /* -32768 -> -32767: the symmetric range keeps every product below 2^30 */
    const qfoc_q15_t x = qfoc_pll_in(psi->alpha);
    const qfoc_q15_t y = qfoc_pll_in(psi->beta);
    qfoc_pll_loop(pll, x, y, out);
}

void qfoc_pll_step_emf(qfoc_pll_t *pll, const qfoc_ab_t *emf, qfoc_pll_out_t *out)
{
    /* e = w psi (-sin, cos): the flux direction is (e_beta, -e_alpha) for w >= 0
       and (-e_beta, e_alpha) for w < 0; the sign is the speed integrator's */
    const qfoc_q15_t x = qfoc_pll_ato_x(pll->pi.integ, emf->beta);
    const qfoc_q15_t y = qfoc_pll_ato_y(pll->pi.integ, emf->alpha);
    /*@ assert same_length: PllCoast(x, y, pll->mag_min) <==>
          PllCoast(QfocSat15(emf->alpha), QfocSat15(emf->beta), pll->mag_min); */
    qfoc_pll_loop(pll, x, y, out);
}
