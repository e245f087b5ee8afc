/**
 * @file qfoc_trqcomp.c
 * @brief Torque compensation of the pulsating compressor load and the
 *        mechanical-angle tracker (see include/qfoc/trqcomp.h).
 *
 * Requirements: REQ-TC-001 .. REQ-TC-010 (specs/requirements/trqcomp.md).
 */
#include "qfoc/trqcomp.h"
#include "qfoc/q15.h"
#include "qfoc/trig.h"

/** Counts per turn of a qfoc_angle_t: 2^16 = 65536. */
#define QFOC_TC_TURN ((uint32_t)65536u)
/** Largest forward step of the angle read as one step: +32767 counts (< half a turn). */
#define QFOC_TC_HALF_POS ((int32_t)32767)
/** Largest reverse step of the angle read as one step: -32768 counts (half a turn). */
#define QFOC_TC_HALF_NEG ((int32_t)-32768)
/** Reciprocal scale of the tracker: 2^28 = 268435456 (exact for n < 2^20, pp <= 16). */
#define QFOC_TC_RECIP_ONE ((uint32_t)268435456u)
/** Q15 -> Q31 widening factor: 2^16 = 65536. */
#define QFOC_TC_Q15_TO_Q31 ((int32_t)65536)
/** Q46 -> Q15 divisor: Q31 coefficient x Q15 trig = Q46; 2^31 = 2147483648. */
#define QFOC_TC_Q46_TO_Q15 ((int64_t)2147483648)
/** Half of QFOC_TC_Q46_TO_Q15 for rounding to nearest: 2^30 = 1073741824. */
#define QFOC_TC_Q46_HALF ((int64_t)1073741824)

/**
 * @brief floor(n / pp) as (n x recip) / 2^28 with recip = ceil(2^28 / pp), for
 *        n < 2^20: exact (lemmas MechExact1..16 of specs/trqcomp.acsl, one per
 *        pole-pair count; the reciprocals of 1..16 are distinct).
 */
/*@
  requires n_range: n < 1048576;
  requires r_valid: r == MechRecip(1) || r == MechRecip(2) || r == MechRecip(3) || r == MechRecip(4) ||
                        r == MechRecip(5) || r == MechRecip(6) || r == MechRecip(7) || r == MechRecip(8) ||
                        r == MechRecip(9) || r == MechRecip(10) || r == MechRecip(11) || r == MechRecip(12) ||
                        r == MechRecip(13) || r == MechRecip(14) || r == MechRecip(15) || r == MechRecip(16);
  assigns \nothing;
  ensures exact1: r == MechRecip(1) ==> \result == n / 1;
  ensures exact2: r == MechRecip(2) ==> \result == n / 2;
  ensures exact3: r == MechRecip(3) ==> \result == n / 3;
  ensures exact4: r == MechRecip(4) ==> \result == n / 4;
  ensures exact5: r == MechRecip(5) ==> \result == n / 5;
  ensures exact6: r == MechRecip(6) ==> \result == n / 6;
  ensures exact7: r == MechRecip(7) ==> \result == n / 7;
  ensures exact8: r == MechRecip(8) ==> \result == n / 8;
  ensures exact9: r == MechRecip(9) ==> \result == n / 9;
  ensures exact10: r == MechRecip(10) ==> \result == n / 10;
  ensures exact11: r == MechRecip(11) ==> \result == n / 11;
  ensures exact12: r == MechRecip(12) ==> \result == n / 12;
  ensures exact13: r == MechRecip(13) ==> \result == n / 13;
  ensures exact14: r == MechRecip(14) ==> \result == n / 14;
  ensures exact15: r == MechRecip(15) ==> \result == n / 15;
  ensures exact16: r == MechRecip(16) ==> \result == n / 16;
  ensures range: \result <= n;
*/
static uint32_t qfoc_mech_div(uint32_t n, uint32_t r)
{
    /* n < 2^20, r <= 2^28: product < 2^48 in uint64; the division by the power
       of two 2^28 is a shift (no divider); the quotient is <= n < 2^20 */
    const uint64_t q = ((uint64_t)n * (uint64_t)r) / (uint64_t)QFOC_TC_RECIP_ONE;
    /*@ assert c1: r == MechRecip(1) ==> q == n / 1; */
    /*@ assert c2: r == MechRecip(2) ==> q == n / 2; */
    /*@ assert c3: r == MechRecip(3) ==> q == n / 3; */
    /*@ assert c4: r == MechRecip(4) ==> q == n / 4; */
    /*@ assert c5: r == MechRecip(5) ==> q == n / 5; */
    /*@ assert c6: r == MechRecip(6) ==> q == n / 6; */
    /*@ assert c7: r == MechRecip(7) ==> q == n / 7; */
    /*@ assert c8: r == MechRecip(8) ==> q == n / 8; */
    /*@ assert c9: r == MechRecip(9) ==> q == n / 9; */
    /*@ assert c10: r == MechRecip(10) ==> q == n / 10; */
    /*@ assert c11: r == MechRecip(11) ==> q == n / 11; */
    /*@ assert c12: r == MechRecip(12) ==> q == n / 12; */
    /*@ assert c13: r == MechRecip(13) ==> q == n / 13; */
    /*@ assert c14: r == MechRecip(14) ==> q == n / 14; */
    /*@ assert c15: r == MechRecip(15) ==> q == n / 15; */
    /*@ assert c16: r == MechRecip(16) ==> q == n / 16; */
    return (uint32_t)q;
}

/**
 * @brief The tracker's mechanical angle floor((turn x 65536 + theta_e) / pp).
 */
/*@
  requires valid_m: \valid_read(m);
  requires m_valid: MechValid(m);
  assigns \nothing;
  ensures exact: \result == MechCount(m->turn, m->theta_e) / m->pole_pairs;
*/
static qfoc_angle_t qfoc_mech_scale(const qfoc_mech_t *m)
{
    /* electrical counts since the mechanical zero: < 16 x 65536 = 2^20 */
    const uint32_t n = ((uint32_t)m->turn * QFOC_TC_TURN) + (uint32_t)m->theta_e;
    uint32_t q;
    /*@ assert cases: m->pole_pairs == 1 || m->pole_pairs == 2 || m->pole_pairs == 3 ||
          m->pole_pairs == 4 || m->pole_pairs == 5 || m->pole_pairs == 6 ||
          m->pole_pairs == 7 || m->pole_pairs == 8 || m->pole_pairs == 9 ||
          m->pole_pairs == 10 || m->pole_pairs == 11 || m->pole_pairs == 12 ||
          m->pole_pairs == 13 || m->pole_pairs == 14 || m->pole_pairs == 15 ||
          m->pole_pairs == 16; */
    q = qfoc_mech_div(n, m->recip);
    /*@ assert exact: q == n / m->pole_pairs; */
    /* q = floor(n / pp) < 65536 because n < pp x 65536 */
    return (qfoc_angle_t)q;
}

bool qfoc_mech_is_valid(const qfoc_mech_t *m)
{
    bool ok = false;
    if ((m->pole_pairs >= 1u) && (m->pole_pairs <= QFOC_MECH_PP_MAX)) {
        /* ceil(2^28 / pp): 2^28 + 15 < 2^32 */
        const uint32_t pp = (uint32_t)m->pole_pairs;
        const uint32_t recip = (QFOC_TC_RECIP_ONE + (pp - 1u)) / pp;
        if ((m->turn < m->pole_pairs) && (m->recip == recip)) {
            ok = true;
        } else {
            /* count or reciprocal corrupted */
        }
    } else {
        /* pole-pair count out of range */
    }
    return ok;
}

int32_t qfoc_mech_init(qfoc_mech_t *m, uint8_t pole_pairs, qfoc_angle_t theta_e)
{
    int32_t status;
    uint32_t pp;
    if ((pole_pairs >= 1u) && (pole_pairs <= QFOC_MECH_PP_MAX)) {
        pp = (uint32_t)pole_pairs;
        status = QFOC_TRQCOMP_OK;
    } else {
        pp = 1u;
        status = QFOC_TRQCOMP_ERR_PARAM;
    }
    m->pole_pairs = (uint8_t)pp;
    m->turn = 0u;
    m->theta_e = theta_e;
    /* ceil(2^28 / pp), 2^20 .. 2^28: the one division, at initialisation */
    m->recip = (QFOC_TC_RECIP_ONE + (pp - 1u)) / pp;
    return status;
}

qfoc_angle_t qfoc_mech_update(qfoc_mech_t *m, qfoc_angle_t theta_e)
{
    /* signed change of the electrical angle, [-65535, 65535] */
    const int32_t diff = (int32_t)theta_e - (int32_t)m->theta_e;
    const uint32_t pp = (uint32_t)m->pole_pairs;
    uint32_t turn = (uint32_t)m->turn;

    if (diff < QFOC_TC_HALF_NEG) {
        /* forward through 0: one more electrical revolution */
        if ((turn + 1u) == pp) {
            turn = 0u;
        } else {
            turn = turn + 1u;
        }
    } else if (diff > QFOC_TC_HALF_POS) {
        /* backward through 0: one electrical revolution less */
        if (turn == 0u) {
            turn = pp - 1u;
        } else {
            turn = turn - 1u;
        }
    } else {
        /* step of less than half a turn without wrap */
    }
    m->turn = (uint8_t)turn;
    m->theta_e = theta_e;

    return qfoc_mech_scale(m);
}

bool qfoc_trqcomp_params_is_valid(const qfoc_trqcomp_params_t *p)
{
    bool ok = true;
    if ((p->gain < 0) || (p->amp_max < 0)) {
        ok = false;
    } else if ((p->speed_min < 0) || (p->speed_min > p->speed_max)) {
        ok = false;
    } else if ((p->pole_pairs < 1u) || (p->pole_pairs > QFOC_MECH_PP_MAX)) {
        ok = false;
    } else {
        /* every field inside its range */
    }
    return ok;
}

/**
 * @brief c inside [-amp x 65536, amp x 65536] (amp >= 0).
 */
/*@
  requires amp_range: 0 <= amp;
  assigns \nothing;
  ensures result: \result <==> TcCoefIn(c, amp);
*/
static bool qfoc_trqcomp_coef_in(qfoc_q31_t c, qfoc_q15_t amp)
{
    /* amp <= 32767: amp x 65536 <= 2147418112 fits int32 */
    const int32_t lim = (int32_t)amp * QFOC_TC_Q15_TO_Q31;
    return (c >= -lim) && (c <= lim);
}

bool qfoc_trqcomp_is_valid(const qfoc_trqcomp_t *tc)
{
    bool ok = qfoc_trqcomp_params_is_valid(&tc->params);
    if (ok) {
        const qfoc_q15_t amp = tc->params.amp_max;
        if (!qfoc_trqcomp_coef_in(tc->a[0], amp)) {
            ok = false;
        } else if (!qfoc_trqcomp_coef_in(tc->b[0], amp)) {
            ok = false;
        } else if (!qfoc_trqcomp_coef_in(tc->a[1], amp)) {
            ok = false;
        } else if (!qfoc_trqcomp_coef_in(tc->b[1], amp)) {
            ok = false;
        } else {
            /* every coefficient inside +-amp_max */
        }
    } else {
        /* invalid parameters */
    }
    return ok;
}

/**
 * @brief Clear the four learned coefficients (shared by init and reset).
 */
/*@
  requires valid_tc: \valid(tc);
  requires params_valid: TcParamsValid(&tc->params);
  assigns tc->a[0 .. 1], tc->b[0 .. 1];
  ensures valid: TcValid(tc);
  ensures zero: tc->a[0] == 0 && tc->b[0] == 0 && tc->a[1] == 0 && tc->b[1] == 0;
*/
static void qfoc_trqcomp_clear(qfoc_trqcomp_t *tc)
{
    tc->a[0] = 0;
    tc->b[0] = 0;
    tc->a[1] = 0;
    tc->b[1] = 0;
}

int32_t qfoc_trqcomp_init(qfoc_trqcomp_t *tc, const qfoc_trqcomp_params_t *p)
{
    int32_t status;
    if (qfoc_trqcomp_params_is_valid(p)) {
        tc->params.gain = p->gain;
        tc->params.amp_max = p->amp_max;
        tc->params.speed_min = p->speed_min;
        tc->params.speed_max = p->speed_max;
        tc->params.pole_pairs = p->pole_pairs;
        status = QFOC_TRQCOMP_OK;
    } else {
        /* safe state: no learning, coefficients held at 0, output 0 */
        tc->params.gain = 0;
        tc->params.amp_max = 0;
        tc->params.speed_min = 0;
        tc->params.speed_max = 0;
        tc->params.pole_pairs = 1u;
        status = QFOC_TRQCOMP_ERR_PARAM;
    }
    qfoc_trqcomp_clear(tc);
    return status;
}

void qfoc_trqcomp_reset(qfoc_trqcomp_t *tc)
{
    qfoc_trqcomp_clear(tc);
}

/**
 * @brief speed_min <= |speed| <= speed_max, |speed| exact in int32 (-32768 -> 32768).
 */
/*@
  requires valid_tc: \valid_read(tc);
  assigns \nothing;
  ensures result: \result <==> TcInWindow(tc, speed);
*/
static bool qfoc_trqcomp_in_window(const qfoc_trqcomp_t *tc, qfoc_q15_t speed)
{
    int32_t mag = (int32_t)speed;
    if (mag < 0) {
        mag = -mag;
    } else {
        /* already non-negative */
    }
    return (mag >= (int32_t)tc->params.speed_min) && (mag <= (int32_t)tc->params.speed_max);
}

/**
 * @brief The second harmonic learns only while its frequency is at most the first's at
 *        speed_max: 2 |speed| <= speed_max (REQ-TC-005).
 */
/*@
  requires valid_tc: \valid_read(tc);
  assigns \nothing;
  ensures result: \result <==> 2 * TcAbs(speed) <= tc->params.speed_max;
*/
static bool qfoc_trqcomp_learns_2x(const qfoc_trqcomp_t *tc, qfoc_q15_t speed)
{
    int32_t mag = (int32_t)speed;
    if (mag < 0) {
        mag = -mag;
    } else {
        /* already non-negative */
    }
    return (2 * mag) <= (int32_t)tc->params.speed_max;
}

/**
 * @brief The second harmonic from the first: sin 2x = 2 sin x cos x,
 *        cos 2x = cos^2 x - sin^2 x, each rounded to Q15 (qfoc_q15_from_q30).
 *
 * Scaling and overflow: |sin|, |cos| <= 32767: |2 s c| <= 2 x 32767^2 = 2147352578
 * and |c^2 - s^2| <= 32767^2, exact in int32 (Q30); the rounding saturates to the
 * symmetric Q15 range.  Against sin / cos of the doubled angle: the error of the
 * first harmonic doubled, plus 1/2 LSB (tests/test_trqcomp.c).
 */
/*@
  requires valid: \valid_read(h1) && \valid(h2);
  requires sep: \separated(h1, h2);
  requires sym: QfocQ15Sym(h1->sine) && QfocQ15Sym(h1->cosine);
  assigns *h2;
  ensures sym: QfocQ15Sym(h2->sine) && QfocQ15Sym(h2->cosine);
*/
static void qfoc_trqcomp_double(const qfoc_sincos_t *h1, qfoc_sincos_t *h2)
{
    const int32_t s = (int32_t)h1->sine;
    const int32_t c = (int32_t)h1->cosine;
    const int32_t sc = s * c;
    h2->sine = qfoc_q15_from_q30(sc * 2);
    h2->cosine = qfoc_q15_from_q30((c * c) - (s * s));
}

/**
 * @brief One coefficient update: clamp(c + 2 g round(e r / 32768), +-amp x 65536).
 */
/*@
  requires gain_range: 0 <= g;
  requires amp_range: 0 <= amp;
  requires reg_range: QfocQ15Sym(r);
  requires coef_range: TcCoefIn(c, amp);
  assigns \nothing;
  ensures value: \result == TcAdapt(c, e, r, g, amp);
  ensures range: TcCoefIn(\result, amp);
  ensures step: \abs(\result - c) <= 2 * 32767 * g;
  ensures zero_step: (e == 0 || g == 0) ==> \result == c;
*/
static qfoc_q31_t qfoc_trqcomp_adapt(qfoc_q31_t c, qfoc_q15_t e, qfoc_q15_t r, qfoc_q15_t g,
                                     qfoc_q15_t amp)
{
    /* |e r| <= 32768 x 32767 < 2^30: rounded to Q15 without saturation */
    const qfoc_q15_t p = qfoc_q15_mul(e, r);
    /* 2 g p: |.| <= 2 x 32767^2 = 2147352578 < 2^31, exact in int32 (Q31) */
    const int32_t gp = (int32_t)g * (int32_t)p;
    const int64_t lim = (int64_t)amp * (int64_t)QFOC_TC_Q15_TO_Q31;
    int64_t v;
    /*@ assert p_value: p == TcProd(e, r); */
    /*@ assert p_range: -32767 <= p <= 32767; */
    /*@ assert gp_hi: gp <= 32767 * g; */
    /*@ assert gp_lo: gp >= -32767 * g; */
    v = (int64_t)c + ((int64_t)gp * 2);
    if (v > lim) {
        v = lim;
    } else if (v < -lim) {
        v = -lim;
    } else {
        /* inside the amplitude limit */
    }
    return (qfoc_q31_t)v;
}

/**
 * @brief The regressor sigma x (+-x) of the learning law: x for forward rotation,
 *        -x for reverse (x in the symmetric range: the negation is exact).
 */
/*@
  requires x_range: QfocQ15Sym(x);
  assigns \nothing;
  ensures range: QfocQ15Sym(\result);
  ensures value: \result == (forward ? x : -x);
*/
static qfoc_q15_t qfoc_trqcomp_signed(qfoc_q15_t x, bool forward)
{
    qfoc_q15_t r = x;
    if (!forward) {
        r = qfoc_q15_neg(x);
    } else {
        /* forward rotation: regressor as is */
    }
    return r;
}

void qfoc_trqcomp_learn(qfoc_trqcomp_t *tc, qfoc_angle_t theta_m, qfoc_q15_t speed_err,
                        qfoc_q15_t speed)
{
    if (qfoc_trqcomp_in_window(tc, speed)) {
        const bool forward = (speed >= 0);
        const qfoc_q15_t g = tc->params.gain;
        const qfoc_q15_t amp = tc->params.amp_max;
        qfoc_sincos_t h1;
        qfoc_sincos_t h2;
        qfoc_sincos(theta_m, &h1);
        qfoc_trqcomp_double(&h1, &h2);
        /* shifted regressors (model phase -90 degrees, +90 in reverse):
           a_h with +sigma sin(h theta), b_h with -sigma cos(h theta) */
        tc->a[0] = qfoc_trqcomp_adapt(tc->a[0], speed_err,
                                      qfoc_trqcomp_signed(h1.sine, forward), g, amp);
        tc->b[0] = qfoc_trqcomp_adapt(tc->b[0], speed_err,
                                      qfoc_trqcomp_signed(h1.cosine, !forward), g, amp);
        if (qfoc_trqcomp_learns_2x(tc, speed)) {
            tc->a[1] = qfoc_trqcomp_adapt(tc->a[1], speed_err,
                                          qfoc_trqcomp_signed(h2.sine, forward), g, amp);
            tc->b[1] = qfoc_trqcomp_adapt(tc->b[1], speed_err,
                                          qfoc_trqcomp_signed(h2.cosine, !forward), g, amp);
        } else {
            /* above half the window's top: the second harmonic held (its frequency beyond
               the first's at speed_max, where the learning law's phase model is not
               known to hold) */
        }
    } else {
        /* outside the speed window: coefficients held */
    }
}

/**
 * @brief One harmonic a cos + b sin in Q46: coefficient (Q31) x cos / sin (Q15,
 *        |.| <= 32767), each product |.| <= 2^31 x 32767 < 2^46, exact in int64.
 */
/*@
  requires c_range: QfocQ15Sym(c);
  requires s_range: QfocQ15Sym(s);
  assigns \nothing;
  ensures value: \result == a * c + b * s;
  ensures range: -((\abs(a) + \abs(b)) * 32767) <= \result <= (\abs(a) + \abs(b)) * 32767;
*/
static int64_t qfoc_trqcomp_harmonic(qfoc_q31_t a, qfoc_q31_t b, qfoc_q15_t c, qfoc_q15_t s)
{
    const int64_t ta = (int64_t)a * (int64_t)c;
    const int64_t tb = (int64_t)b * (int64_t)s;
    /*@ assert ta_range: -(\abs(a) * 32767) <= ta <= \abs(a) * 32767; */
    /*@ assert tb_range: -(\abs(b) * 32767) <= tb <= \abs(b) * 32767; */
    return ta + tb;
}

/**
 * @brief Q46 -> Q15: x / 2^31 rounded to nearest (ties away from zero), saturated.
 */
/*@
  requires x_range: -281474976710656 <= x <= 281474976710656;
  assigns \nothing;
  ensures range: QfocQ15Sym(\result);
  ensures value: \result == QfocSat15(QfocRoundDiv(x, 2147483648));
*/
static qfoc_q15_t qfoc_trqcomp_q46_to_q15(int64_t x)
{
    int64_t q;
    if (x >= 0) {
        q = (x + QFOC_TC_Q46_HALF) / QFOC_TC_Q46_TO_Q15;
    } else {
        q = -((QFOC_TC_Q46_HALF - x) / QFOC_TC_Q46_TO_Q15);
    }
    /* |x| <= 2^48: |q| <= 2^17 + 1 fits int32 */
    return qfoc_q15_sat((int32_t)q);
}

qfoc_q15_t qfoc_trqcomp_output(const qfoc_trqcomp_t *tc, qfoc_angle_t theta_m, qfoc_q15_t speed)
{
    qfoc_q15_t out = 0;
    if (qfoc_trqcomp_in_window(tc, speed)) {
        qfoc_sincos_t h1;
        qfoc_sincos_t h2;
        int64_t sum;
        qfoc_sincos(theta_m, &h1);
        qfoc_trqcomp_double(&h1, &h2);
        /* two harmonics, each |.| <= 2 amp x 65536 x 32767 < 2^47: sum < 2^48 */
        sum = qfoc_trqcomp_harmonic(tc->a[0], tc->b[0], h1.cosine, h1.sine)
              + qfoc_trqcomp_harmonic(tc->a[1], tc->b[1], h2.cosine, h2.sine);
        /*@ assert sum_hi: sum <= 4 * (tc->params.amp_max * 65536 * 32767); */
        /*@ assert sum_lo: sum >= -4 * (tc->params.amp_max * 65536 * 32767); */
        out = qfoc_trqcomp_q46_to_q15(sum);
    } else {
        /* outside the speed window: no feed-forward */
    }
    return out;
}

qfoc_angle_t qfoc_trqcomp_phase1(const qfoc_trqcomp_t *tc)
{
    /* i_ff,1 = a_1 cos(theta) + b_1 sin(theta) = A cos(theta - atan2(b_1, a_1)) */
    return qfoc_atan2(qfoc_q15_from_q31(tc->b[0]), qfoc_q15_from_q31(tc->a[0]));
}
