/**
 * @file qfoc_emf.c
 * @brief Back-EMF estimator and disturbance observer (see include/qfoc/emf.h).
 *
 * Requirements: REQ-EMF-001 .. REQ-EMF-014 (specs/requirements/emf.md).
 */
#include "qfoc/emf.h"
#include "qfoc/q15.h"
#include "qfoc/filter.h"
#include "qfoc/trig.h"

/** Q15 -> Q31 widening factor: 2^16 = 65536. */
#define QFOC_EMF_Q15_TO_Q31 ((int64_t)65536)
/** Q25 -> Q31 factor for l (Q10) x current (Q15): 2^6 = 64. */
#define QFOC_EMF_Q25_TO_Q31 ((int64_t)64)
/** Q15 -> Q27 widening factor of the predicted current: 2^12 = 4096. */
#define QFOC_EMF_Q15_TO_Q27 ((int32_t)4096)
/** Safe low-pass coefficient after a rejected init: 32767 / 32768 = 0.99997. */
#define QFOC_EMF_ALPHA_SAFE ((qfoc_q15_t)32767)
/** Q15 one: 1.0 = 2^15 = 32768 (1 - a = (32768 - alpha) / 32768). */
#define QFOC_EMF_Q15_ONE ((int32_t)32768)
/** lambda <= 1: ki g <= 2^27 x 2^ki_shift (ki Q15+shift, g Q12: 15 + 12 = 27). */
#define QFOC_DOB_LAMBDA_ONE ((int64_t)134217728)
/** Divisor of ki g to lambda in Q15: 2^12 = 4096 (times 2^ki_shift). */
#define QFOC_DOB_LAMBDA_DIV ((int32_t)4096)
/** Largest low-pass coefficient, for the clamp of lambda: 32767 / 32768. */
#define QFOC_EMF_ALPHA_MAX ((int32_t)32767)
/** One angle turn, 2^16 counts, and the mask of the reduction modulo 2^16. */
#define QFOC_EMF_TURN ((int32_t)65536)
#define QFOC_EMF_ANGLE_MASK (0xFFFFu)
/** Speed x k_theta is in 2^-32 turns: / 2^16 gives counts W, / 2^17 gives W/2. */
#define QFOC_EMF_W_DIV ((int32_t)65536)
#define QFOC_EMF_W_HALF ((int32_t)32768)
#define QFOC_EMF_HW_DIV ((int32_t)131072)
#define QFOC_EMF_HW_HALF ((int32_t)65536)
/** Largest atan2 argument after normalisation: 32767. */
#define QFOC_EMF_ATAN_MAX ((int64_t)32767)
/** Rounding divisors 2^n and their halves 2^(n-1) (round to nearest, ties away from
    zero): Q31 -> Q15 (2^16), Q39 -> Q15 (2^24), current-model increment (2^34). */
#define QFOC_EMF_2P16 ((int64_t)65536)
#define QFOC_EMF_2P15 ((int64_t)32768)
#define QFOC_EMF_2P24 ((int64_t)16777216)
#define QFOC_EMF_2P23 ((int64_t)8388608)
#define QFOC_EMF_2P34 ((int64_t)17179869184)
#define QFOC_EMF_2P33 ((int64_t)8589934592)

/**
 * @brief 2^s for a gain shift s in 0..15 (table look-up, no shift operator).
 */
/*@
  requires shift_range: s <= 15;
  assigns \nothing;
  ensures value: \result == FilterPow2(s);
  ensures range: 1 <= \result <= 32768;
*/
static int32_t qfoc_emf_pow2(uint8_t s)
{
    /* 2^s for s = 0..15 (the gain shifts); exact integers 1 .. 32768 */
    static const int32_t qfoc_emf_pow2_table[16] = {
        1, 2, 4, 8, 16, 32, 64, 128,
        256, 512, 1024, 2048, 4096, 8192, 16384, 32768
    };
    /* s % 16: the contract's s <= 15 leaves it unchanged; a shift corrupted in RAM (a
       random hardware fault the RAM check, REQ-DRV-019, reports within 4 ms) still
       reads inside the table */
    return qfoc_emf_pow2_table[s % 16u];
}

/**
 * @brief Saturate a 64-bit value to the symmetric Q15 range.
 */
/*@
  assigns \nothing;
  ensures value: \result == QfocSat15(x);
  ensures range: QfocQ15Sym(\result);
*/
static qfoc_q15_t qfoc_emf_sat15(int64_t x)
{
    /* first to the symmetric 32-bit range (no change inside Q15), then to Q15 */
    return qfoc_q15_sat(qfoc_q31_sat(x));
}

/**
 * @brief x / 2^16 rounded to nearest, ties away from zero, for |x| < 2^62.
 */
/*@
  requires x_range: -4611686018427387904 < x < 4611686018427387904;
  assigns \nothing;
  ensures value: \result == QfocRoundDiv(x, 65536);
*/
static int64_t qfoc_emf_round16(int64_t x)
{
    int64_t r;
    if (x >= 0) {
        r = (x + QFOC_EMF_2P15) / QFOC_EMF_2P16;
    } else {
        r = -((QFOC_EMF_2P15 - x) / QFOC_EMF_2P16);
    }
    return r;
}

/**
 * @brief x / 2^24 rounded to nearest, ties away from zero, for |x| < 2^62.
 */
/*@
  requires x_range: -4611686018427387904 < x < 4611686018427387904;
  assigns \nothing;
  ensures value: \result == QfocRoundDiv(x, 16777216);
*/
static int64_t qfoc_emf_round24(int64_t x)
{
    int64_t r;
    if (x >= 0) {
        r = (x + QFOC_EMF_2P23) / QFOC_EMF_2P24;
    } else {
        r = -((QFOC_EMF_2P23 - x) / QFOC_EMF_2P24);
    }
    return r;
}

/**
 * @brief x / 2^34 rounded to nearest, ties away from zero, for |x| < 2^63 - 2^33.
 */
/*@
  requires x_range: -9223372028264841216 < x < 9223372028264841216;
  assigns \nothing;
  ensures value: \result == QfocRoundDiv(x, 17179869184);
*/
static int64_t qfoc_emf_round34(int64_t x)
{
    int64_t r;
    if (x >= 0) {
        r = (x + QFOC_EMF_2P33) / QFOC_EMF_2P34;
    } else {
        r = -((QFOC_EMF_2P33 - x) / QFOC_EMF_2P34);
    }
    return r;
}

/**
 * @brief Product of two sums of sines / cosines (|a|, |b| <= 65534), exact.
 */
/*@
  requires a_range: -65534 <= a <= 65534;
  requires b_range: -65534 <= b <= 65534;
  assigns \nothing;
  ensures value: \result == a * b;
  ensures range: -4294705156 <= \result <= 4294705156;
*/
static int64_t qfoc_emf_mul_trig(int32_t a, int32_t b)
{
    /*@ assert hi: b >= 0 ==> -(65534 * b) <= a * b <= 65534 * b; */
    /*@ assert lo: b < 0 ==> 65534 * b <= a * b <= -(65534 * b); */
    /* |a b| <= 65534^2 = 4294705156 < 2^33 */
    return (int64_t)a * (int64_t)b;
}

/**
 * @brief Square of a sum of sines (|a| <= 65534), exact, non-negative.
 */
/*@
  requires a_range: -65534 <= a <= 65534;
  assigns \nothing;
  ensures value: \result == a * a;
  ensures range: 0 <= \result <= 4294705156;
*/
static int64_t qfoc_emf_square(int32_t a)
{
    /*@ assert hi: a >= 0 ==> 0 <= a * a <= 65534 * a; */
    /*@ assert lo: a < 0 ==> 0 <= a * a <= -65534 * a; */
    /* a^2 <= 65534^2 = 4294705156 */
    return (int64_t)a * (int64_t)a;
}

/**
 * @brief (1 - a) in Q15 (1..32767) times a Q30 trigonometric product, exact.
 */
/*@
  requires b_range: 1 <= b <= 32767;
  requires v_range: -4294705156 <= v <= 4294705156;
  assigns \nothing;
  ensures value: \result == b * v;
  ensures range: -140724603846652 <= \result <= 140724603846652;
  ensures sign: 0 <= v ==> 0 <= \result;
*/
static int64_t qfoc_emf_mul_coef(int32_t b, int64_t v)
{
    /*@ assert hi: v >= 0 ==> 0 <= b * v <= 32767 * v; */
    /*@ assert lo: v < 0 ==> 32767 * v <= b * v <= 0; */
    /* |b v| <= 32767 x 4294705156 = 140724603846652 < 2^48 */
    return (int64_t)b * v;
}

/**
 * @brief Current-model drive (Q31, |x| <= 6442188802) times the k_i mantissa, exact.
 */
/*@
  requires x_range: -6442188802 <= x <= 6442188802;
  requires ki_range: 0 <= ki;
  assigns \nothing;
  ensures value: \result == x * ki;
  ensures range: -211091200475134 <= \result <= 211091200475134;
*/
static int64_t qfoc_emf_mul_ki(int64_t x, qfoc_q15_t ki)
{
    /*@ assert hi: x >= 0 ==> 0 <= x * ki <= x * 32767; */
    /*@ assert lo: x < 0 ==> x * 32767 <= x * ki <= 0; */
    /* |x ki| <= 6442188802 x 32767 = 211091200475134 < 2^48 */
    return x * (int64_t)ki;
}

/**
 * @brief A product x ki (|.| <= 211091200475134) times 2^(15 - ki_shift), exact.
 */
/*@
  requires x_range: -211091200475134 <= x <= 211091200475134;
  requires p2_range: 1 <= p2 <= 32768;
  assigns \nothing;
  ensures value: \result == x * p2;
  ensures range: -6917036457169190912 <= \result <= 6917036457169190912;
*/
static int64_t qfoc_emf_mul_pow2(int64_t x, int32_t p2)
{
    /*@ assert hi: x >= 0 ==> 0 <= x * p2 <= x * 32768; */
    /*@ assert lo: x < 0 ==> x * 32768 <= x * p2 <= 0; */
    /* |x 2^(15 - s)| <= 211091200475134 x 32768 = 6917036457169190912 < 2^63 */
    return x * (int64_t)p2;
}

/**
 * @brief Angle of an EMF vector: atan2(-e_alpha, e_beta); 0 for the zero vector.
 */
/*@
  requires e_range: QfocQ15Sym(ea) && QfocQ15Sym(eb);
  assigns \nothing;
  ensures zero: (ea == 0 && eb == 0) ==> \result == 0;
*/
static qfoc_angle_t qfoc_emf_angle(qfoc_q15_t ea, qfoc_q15_t eb)
{
    /* EMF = w psi (-sin theta, cos theta): the flux direction is (e_beta, -e_alpha);
       e_alpha is in the symmetric range, so the negation is exact */
    return qfoc_atan2(qfoc_q15_neg(ea), eb);
}

/**
 * @brief Unfiltered back-EMF sample of one axis (REQ-EMF-003):
 *        u - R (i + i_prev)/2 - l (i - i_prev), Q15, rounded and saturated.
 */
/*@
  requires r_range: 0 <= r;
  requires l_range: 0 <= l;
  requires ip_range: QfocQ15Sym(ip);
  assigns \nothing;
  ensures value: \result == EmfRaw(u, i, ip, r, l);
  ensures range: QfocQ15Sym(\result);
*/
static qfoc_q15_t qfoc_emf_raw(qfoc_q15_t u, qfoc_q15_t i, qfoc_q15_t ip,
                               qfoc_q15_t r, qfoc_q15_t l)
{
    const int32_t us = (int32_t)qfoc_q15_sat((int32_t)u);
    const int32_t is = (int32_t)qfoc_q15_sat((int32_t)i);
    const int32_t sum = is + (int32_t)ip;    /* |.| <= 65534 */
    const int32_t dif = is - (int32_t)ip;    /* |.| <= 65534 */
    int32_t rdrop;
    int32_t ldrop;
    int64_t x31;

    /*@ assert us_eq: us == QfocSat15(u); */
    /*@ assert is_eq: is == QfocSat15(i); */
    /*@ assert sum_hi: sum >= 0 ==> 0 <= r * sum <= 32767 * sum; */
    /*@ assert sum_lo: sum < 0 ==> 32767 * sum <= r * sum <= 0; */
    /* r (Q15) x (i + i_prev): Q30 of the sum = Q31 of the mean, |.| <= 2147352578 */
    rdrop = (int32_t)r * sum;
    /*@ assert dif_hi: dif >= 0 ==> 0 <= l * dif <= 32767 * dif; */
    /*@ assert dif_lo: dif < 0 ==> 32767 * dif <= l * dif <= 0; */
    /* l (Q10) x (i - i_prev): Q25, |.| <= 2147352578 */
    ldrop = (int32_t)l * dif;
    /* u (Q31) - mean resistive drop (Q31) - inductive drop (Q25 x 64 = Q31), < 2^38 */
    x31 = (((int64_t)us * QFOC_EMF_Q15_TO_Q31) - (int64_t)rdrop)
          - ((int64_t)ldrop * QFOC_EMF_Q25_TO_Q31);
    /* Q31 -> Q15 rounded to nearest, saturated */
    return qfoc_emf_sat15(qfoc_emf_round16(x31));
}

/**
 * @brief Lag of a low-pass-filtered difference-quotient estimate at speed w
 *        (REQ-EMF-007, REQ-EMF-012): W/2 + atan2((1-a) sin W, 1 - (1-a) cos W).
 */
/*@
  requires a_range: 1 <= a <= 32767;
  requires k_range: k_theta <= 32767;
  assigns \nothing;
  ensures zero_speed: (QfocSat15(w) == 0 || k_theta == 0) ==> \result == 0;
*/
static qfoc_angle_t qfoc_emf_lag_core(qfoc_q15_t a, uint16_t k_theta, qfoc_q15_t w)
{
    const int32_t ws = (int32_t)qfoc_q15_sat((int32_t)w);
    int32_t p;
    uint32_t res = 0u;

    /*@ assert p_hi: ws >= 0 ==> 0 <= ws * k_theta <= 32767 * 32767; */
    /*@ assert p_lo: ws < 0 ==> -32767 * 32767 <= ws * k_theta <= 0; */
    /* speed x k_theta: angle per sample in 2^-32 turns, |p| <= 1073676289 */
    p = ws * (int32_t)k_theta;
    if (p != 0) {
        const int32_t pm = (p < 0) ? -p : p;
        /* W/2 in counts, rounded: |half| <= 8192 */
        const int32_t half = (p < 0) ? -((pm + QFOC_EMF_HW_HALF) / QFOC_EMF_HW_DIV)
                                     : ((pm + QFOC_EMF_HW_HALF) / QFOC_EMF_HW_DIV);
        /* |W| in counts, rounded: 0 .. 16383; split into two half angles */
        const int32_t wm = (pm + QFOC_EMF_W_HALF) / QFOC_EMF_W_DIV;
        const int32_t h0 = wm / 2;
        const int32_t h1 = wm - h0;
        const int32_t b = QFOC_EMF_Q15_ONE - (int32_t)a;   /* 1 - a, Q15, 1 .. 32767 */
        qfoc_sincos_t sc0;
        qfoc_sincos_t sc1;
        int32_t s2;
        int32_t c2;
        int64_t sq;
        int64_t cs;
        int64_t bsq;
        int64_t ax;
        int64_t x;
        int64_t y;
        int64_t ym;
        int32_t yq;
        int32_t sum;
        qfoc_angle_t phi;

        /* sin and cos of |W|/2: the sums of the two half angles h0, h1 (equal for
           an even W) are 2 x 32767 sin(|W|/2), 2 x 32767 cos(|W|/2), |.| <= 65534 */
        qfoc_sincos((qfoc_angle_t)h0, &sc0);
        qfoc_sincos((qfoc_angle_t)h1, &sc1);
        s2 = (int32_t)sc0.sine + (int32_t)sc1.sine;
        c2 = (int32_t)sc0.cosine + (int32_t)sc1.cosine;
        /*@ assert s2_range: -65534 <= s2 <= 65534; */
        /*@ assert c2_range: -65534 <= c2 <= 65534; */
        /* 4 sin^2(W/2) and 4 sin(W/2) cos(W/2) = 2 sin W in Q30 (scale 32767^2),
           |.| <= 4294705156 */
        sq = qfoc_emf_square(s2);
        cs = qfoc_emf_mul_trig(s2, c2);
        /* (1 - a) sin W = 2 (1 - a) sin(W/2) cos(W/2): Q15 x Q30 x 2 = scale 2^47,
           |y| <= 281449207693304 < 2^49 */
        y = qfoc_emf_mul_coef(b, cs) * 2;
        /* 1 - (1 - a) cos W = a + 2 (1 - a) sin^2(W/2): scale 2^47,
           2^32 <= x <= 422182401081336 < 2^49 */
        bsq = qfoc_emf_mul_coef(b, sq);
        /*@ assert bsq_range: 0 <= bsq <= 140724603846652; */
        ax = ((int64_t)a * QFOC_EMF_Q15_TO_Q31) * QFOC_EMF_Q15_TO_Q31;
        /*@ assert ax_range: 4294967296 <= ax <= 140733193388032; */
        x = ax + (bsq * 2);
        if (p < 0) {
            /* sin is odd, cos even: the lag of -w is the negated lag of w */
            y = -y;
        }
        ym = (y < 0) ? -y : y;
        /* halve both together until they fit the atan2 arguments (ratio kept) */
        /*@ loop invariant x_range: 0 <= x <= 422182401081336;
            loop invariant y_range: 0 <= ym <= 281449207693304;
            loop assigns x, ym;
            loop variant x + ym; */
        while ((x > QFOC_EMF_ATAN_MAX) || (ym > QFOC_EMF_ATAN_MAX)) {
            x = x / 2;
            ym = ym / 2;
        }
        yq = (y < 0) ? -(int32_t)ym : (int32_t)ym;
        phi = qfoc_atan2((qfoc_q15_t)yq, (qfoc_q15_t)x);
        /* filter phase + half sample, reduced modulo 2^16 from a non-negative sum
           (phi <= 65535, |half| <= 8192) */
        sum = ((int32_t)phi + half) + QFOC_EMF_TURN;
        res = (uint32_t)sum & QFOC_EMF_ANGLE_MASK;
    } else {
        /* no rotation or no angle scale: no lag */
    }
    return (qfoc_angle_t)res;
}

/**
 * @brief Predicted current of one axis (REQ-EMF-010):
 *        sat(i_hat + k_i (u - R (i + i_prev)/2 - e_prev)), Q4.27.
 */
/*@
  requires ih_range: QfocQ31Sym(ih);
  requires ip_range: QfocQ15Sym(ip);
  requires ep_range: QfocQ15Sym(ep);
  requires r_range: 0 <= r;
  requires ki_range: 0 <= ki;
  requires shift_range: s <= 15;
  assigns \nothing;
  ensures value: \result == DobNext(ih, DobSum(u, i, ip, ep, r), ki, s);
  ensures range: QfocQ31Sym(\result);
*/
static int32_t qfoc_dob_next(int32_t ih, qfoc_q15_t u, qfoc_q15_t i, qfoc_q15_t ip,
                             qfoc_q15_t ep, qfoc_q15_t r, qfoc_q15_t ki, uint8_t s)
{
    const int32_t us = (int32_t)qfoc_q15_sat((int32_t)u);
    const int32_t is = (int32_t)qfoc_q15_sat((int32_t)i);
    const int32_t sum = is + (int32_t)ip;    /* |.| <= 65534 */
    const int32_t p2 = qfoc_emf_pow2((uint8_t)(15u - (uint32_t)s));
    int32_t rdrop;
    int64_t x;
    int64_t xk;
    int64_t xs;
    int64_t inc;

    /*@ assert us_eq: us == QfocSat15(u); */
    /*@ assert is_eq: is == QfocSat15(i); */
    /*@ assert sum_hi: sum >= 0 ==> 0 <= r * sum <= 32767 * sum; */
    /*@ assert sum_lo: sum < 0 ==> 32767 * sum <= r * sum <= 0; */
    /* r (Q15) x (i + i_prev): Q31 of the mean current's drop, |.| <= 2147352578 */
    rdrop = (int32_t)r * sum;
    /* u - R i_mean - e_prev in Q31, |x| <= 6442188802 */
    x = (((int64_t)us * QFOC_EMF_Q15_TO_Q31) - (int64_t)rdrop)
        - ((int64_t)ep * QFOC_EMF_Q15_TO_Q31);
    /*@ assert x_range: -6442188802 <= x <= 6442188802; */
    /* x (Q31) x ki (mantissa), then x 2^(15 - s): |.| < 2^63 */
    xk = qfoc_emf_mul_ki(x, ki);
    xs = qfoc_emf_mul_pow2(xk, p2);
    /* x ki 2^(15-s) / 2^34 = x ki / 2^(15+s) / 2^4: k_i x in Q27, rounded */
    inc = qfoc_emf_round34(xs);
    return qfoc_q31_sat((int64_t)ih + inc);
}

/**
 * @brief EMF estimate of one axis from the current error (REQ-EMF-010):
 *        sat(G (i_hat - i)), Q15.
 */
/*@
  requires g_range: 0 <= g;
  assigns \nothing;
  ensures value: \result == DobEmf(ih, i, g);
  ensures range: QfocQ15Sym(\result);
*/
static qfoc_q15_t qfoc_dob_emf(int32_t ih, qfoc_q15_t i, qfoc_q15_t g)
{
    const int32_t is = (int32_t)qfoc_q15_sat((int32_t)i);
    /* i_hat - i in Q27: |.| <= 2^31 + 134213632 */
    const int64_t err = (int64_t)ih - ((int64_t)is * (int64_t)QFOC_EMF_Q15_TO_Q27);
    int64_t prod;

    /*@ assert is_eq: is == QfocSat15(i); */
    /*@ assert err_eq: err == ih - 4096 * QfocSat15(i); */
    /*@ assert err_range: -2281701376 <= err <= 2281701376; */
    /*@ assert prod_hi: err >= 0 ==> 0 <= g * err <= 32767 * err; */
    /*@ assert prod_lo: err < 0 ==> 32767 * err <= g * err <= 0; */
    /* G (Q12) x (i_hat - i) (Q27) = Q39, |.| < 2^47 */
    prod = (int64_t)g * err;
    /*@ assert prod_eq: prod == g * (ih - 4096 * QfocSat15(i)); */
    /* Q39 -> Q15 rounded, saturated */
    return qfoc_emf_sat15(qfoc_emf_round24(prod));
}

/**
 * @brief Back-EMF update of the instance (REQ-EMF-003, REQ-EMF-004): e_raw per axis
 *        (0 when inactive), low-pass, i_prev = i; returns the filtered EMF.
 */
/*@
  requires valid_e: \valid(e);
  requires e_valid: EmfValid(e);
  assigns e->i_prev, e->lpf_alpha.state, e->lpf_beta.state;
  ensures still_valid: EmfValid(e);
  ensures i_prev: e->i_prev.alpha == QfocSat15(ia) && e->i_prev.beta == QfocSat15(ib);
  ensures out_alpha: \result.alpha == QfocSat15(QfocRoundDiv(e->lpf_alpha.state, 65536));
  ensures out_beta: \result.beta == QfocSat15(QfocRoundDiv(e->lpf_beta.state, 65536));
  ensures range: QfocQ15Sym(\result.alpha) && QfocQ15Sym(\result.beta);
  behavior active:
    assumes e->active != 0;
    ensures state_alpha: e->lpf_alpha.state ==
      LpfNext(\old(e->lpf_alpha.state),
              EmfRaw(ua, ia, \old(e->i_prev.alpha), \old(e->params.r), \old(e->params.l)),
              \old(e->lpf_alpha.alpha));
    ensures state_beta: e->lpf_beta.state ==
      LpfNext(\old(e->lpf_beta.state),
              EmfRaw(ub, ib, \old(e->i_prev.beta), \old(e->params.r), \old(e->params.l)),
              \old(e->lpf_beta.alpha));
  behavior inactive:
    assumes e->active == 0;
    ensures zero: \result.alpha == 0 && \result.beta == 0;
  complete behaviors;
  disjoint behaviors;
*/
static qfoc_ab_t qfoc_emf_update(qfoc_emf_t *e, qfoc_q15_t ua, qfoc_q15_t ub,
                                 qfoc_q15_t ia, qfoc_q15_t ib)
{
    qfoc_q15_t raw_alpha = 0;
    qfoc_q15_t raw_beta = 0;
    qfoc_ab_t emf;
    if (e->active) {
        raw_alpha = qfoc_emf_raw(ua, ia, e->i_prev.alpha, e->params.r, e->params.l);
        raw_beta = qfoc_emf_raw(ub, ib, e->i_prev.beta, e->params.r, e->params.l);
    } else {
        /* rejected parameters: the EMF input stays 0, so the output stays 0 */
    }
    /* low-pass (E2-34) per axis, Q31 state */
    emf.alpha = qfoc_lpf_step(&e->lpf_alpha, raw_alpha);
    /*@ assert lpf_alpha: e->lpf_alpha.state ==
          LpfNext(\at(e->lpf_alpha.state, Pre), raw_alpha, \at(e->lpf_alpha.alpha, Pre)); */
    emf.beta = qfoc_lpf_step(&e->lpf_beta, raw_beta);
    /*@ assert lpf_beta: e->lpf_beta.state ==
          LpfNext(\at(e->lpf_beta.state, Pre), raw_beta, \at(e->lpf_beta.alpha, Pre)); */
    e->i_prev.alpha = qfoc_q15_sat((int32_t)ia);
    e->i_prev.beta = qfoc_q15_sat((int32_t)ib);
    return emf;
}

/**
 * @brief Disturbance-observer update of the instance (REQ-EMF-010): current model,
 *        EMF from the current error, i_prev = i, e_prev = EMF; returns the EMF.
 */
/*@
  requires valid_d: \valid(d);
  requires d_valid: DobValid(d);
  assigns d->ih_alpha, d->ih_beta, d->i_prev, d->e_prev;
  ensures still_valid: DobValid(d);
  ensures ih_alpha: d->ih_alpha ==
    DobNext(\old(d->ih_alpha),
            DobSum(ua, ia, \old(d->i_prev.alpha), \old(d->e_prev.alpha), \old(d->params.r)),
            \old(d->params.ki), \old(d->params.ki_shift));
  ensures ih_beta: d->ih_beta ==
    DobNext(\old(d->ih_beta),
            DobSum(ub, ib, \old(d->i_prev.beta), \old(d->e_prev.beta), \old(d->params.r)),
            \old(d->params.ki), \old(d->params.ki_shift));
  ensures e_alpha: d->e_prev.alpha == DobEmf(d->ih_alpha, ia, \old(d->params.g));
  ensures e_beta: d->e_prev.beta == DobEmf(d->ih_beta, ib, \old(d->params.g));
  ensures i_prev: d->i_prev.alpha == QfocSat15(ia) && d->i_prev.beta == QfocSat15(ib);
  ensures result: \result.alpha == d->e_prev.alpha && \result.beta == d->e_prev.beta;
  ensures range: QfocQ15Sym(\result.alpha) && QfocQ15Sym(\result.beta);
  ensures safe: d->params.g == 0 ==> (\result.alpha == 0 && \result.beta == 0);
*/
static qfoc_ab_t qfoc_dob_update(qfoc_dob_t *d, qfoc_q15_t ua, qfoc_q15_t ub,
                                 qfoc_q15_t ia, qfoc_q15_t ib)
{
    const qfoc_q15_t r = d->params.r;
    const qfoc_q15_t ki = d->params.ki;
    const uint8_t s = d->params.ki_shift;
    const qfoc_q15_t g = d->params.g;
    /* current model: prediction of i(k) */
    const int32_t iha = qfoc_dob_next(d->ih_alpha, ua, ia, d->i_prev.alpha,
                                      d->e_prev.alpha, r, ki, s);
    const int32_t ihb = qfoc_dob_next(d->ih_beta, ub, ib, d->i_prev.beta,
                                      d->e_prev.beta, r, ki, s);
    qfoc_ab_t emf;
    /* EMF from the current error */
    emf.alpha = qfoc_dob_emf(iha, ia, g);
    emf.beta = qfoc_dob_emf(ihb, ib, g);
    d->ih_alpha = iha;
    d->ih_beta = ihb;
    d->i_prev.alpha = qfoc_q15_sat((int32_t)ia);
    d->i_prev.beta = qfoc_q15_sat((int32_t)ib);
    d->e_prev = emf;
    return emf;
}

/**
 * @brief Back-EMF parameter check (shared by qfoc_emf_params_is_valid() and
 *        qfoc_emf_init()).
 */
/*@
  requires valid_p: \valid_read(p);
  assigns \nothing;
  ensures result: \result <==> EmfParamsValid(p);
*/
static bool qfoc_emf_params_ok(const qfoc_emf_params_t *p)
{
    bool ok = false;
    if ((p->r >= 0) && (p->l >= 0) && (p->alpha > 0) && (p->k_theta >= 1u)
        && (p->k_theta <= QFOC_EMF_KTHETA_MAX)) {
        ok = true;
    } else {
        /* a coefficient out of range */
    }
    return ok;
}

/**
 * @brief Disturbance-observer parameter check (shared by
 *        qfoc_dob_params_is_valid() and qfoc_dob_init()).
 */
/*@
  requires valid_p: \valid_read(p);
  assigns \nothing;
  ensures result: \result <==> DobParamsValid(p);
*/
static bool qfoc_dob_params_ok(const qfoc_dob_params_t *p)
{
    bool ok = false;
    if ((p->ki > 0) && (p->ki_shift <= QFOC_DOB_SHIFT_MAX) && (p->r >= 0) && (p->g > 0)
        && (p->k_theta >= 1u) && (p->k_theta <= QFOC_EMF_KTHETA_MAX)) {
        /* lambda = ki g / 2^(27 + ki_shift) <= 1; ki g <= 32767^2 fits 32 bits */
        const int32_t kg = (int32_t)p->ki * (int32_t)p->g;
        const int64_t one = QFOC_DOB_LAMBDA_ONE * (int64_t)qfoc_emf_pow2(p->ki_shift);
        if ((int64_t)kg <= one) {
            ok = true;
        } else {
            /* lambda > 1: overshooting (or, above 2, unstable) observer */
        }
    } else {
        /* a coefficient out of range */
    }
    return ok;
}

bool qfoc_emf_params_is_valid(const qfoc_emf_params_t *p)
{
    return qfoc_emf_params_ok(p);
}

bool qfoc_emf_is_valid(const qfoc_emf_t *e)
{
    bool ok = false;
    if ((e->params.r >= 0) && (e->params.l >= 0) && (e->params.alpha > 0)
        && (e->params.k_theta <= QFOC_EMF_KTHETA_MAX)
        && (e->lpf_alpha.alpha == e->params.alpha) && (e->lpf_beta.alpha == e->params.alpha)
        && qfoc_lpf_is_valid(&e->lpf_alpha) && qfoc_lpf_is_valid(&e->lpf_beta)
        && (e->i_prev.alpha >= QFOC_Q15_MIN) && (e->i_prev.beta >= QFOC_Q15_MIN)) {
        if (e->active) {
            ok = true;
        } else if ((e->lpf_alpha.state == 0) && (e->lpf_beta.state == 0)) {
            ok = true;
        } else {
            /* inactive instance with a non-zero output */
        }
    } else {
        /* a coefficient or a state out of range */
    }
    return ok;
}

int32_t qfoc_emf_init(qfoc_emf_t *e, const qfoc_emf_params_t *p)
{
    int32_t status;
    if (qfoc_emf_params_ok(p)) {
        e->params.r = p->r;
        e->params.l = p->l;
        e->params.alpha = p->alpha;
        e->params.k_theta = p->k_theta;
        e->active = true;
        status = QFOC_EMF_OK;
    } else {
        e->params.r = 0;
        e->params.l = 0;
        e->params.alpha = QFOC_EMF_ALPHA_SAFE;
        e->params.k_theta = 0u;
        e->active = false;
        status = QFOC_EMF_ERR_PARAM;
    }
    /* alpha > 0 in both branches: the filters accept it */
    (void)qfoc_lpf_init(&e->lpf_alpha, e->params.alpha);
    (void)qfoc_lpf_init(&e->lpf_beta, e->params.alpha);
    e->i_prev.alpha = 0;
    e->i_prev.beta = 0;
    return status;
}

void qfoc_emf_reset(qfoc_emf_t *e, const qfoc_ab_t *i0)
{
    e->i_prev.alpha = qfoc_q15_sat((int32_t)i0->alpha);
    e->i_prev.beta = qfoc_q15_sat((int32_t)i0->beta);
    qfoc_lpf_reset(&e->lpf_alpha, 0);
    qfoc_lpf_reset(&e->lpf_beta, 0);
}

void qfoc_emf_step(qfoc_emf_t *e, const qfoc_ab_t *u, const qfoc_ab_t *i,
                   qfoc_emf_out_t *out)
{
    /* inputs read once; the instance is updated by one call, the output written once */
    const qfoc_ab_t emf = qfoc_emf_update(e, u->alpha, u->beta, i->alpha, i->beta);
    out->emf = emf;
    out->theta = qfoc_emf_angle(emf.alpha, emf.beta);
}

qfoc_angle_t qfoc_emf_lag(const qfoc_emf_t *e, qfoc_q15_t w)
{
    return qfoc_emf_lag_core(e->params.alpha, e->params.k_theta, w);
}

bool qfoc_dob_params_is_valid(const qfoc_dob_params_t *p)
{
    return qfoc_dob_params_ok(p);
}

bool qfoc_dob_is_valid(const qfoc_dob_t *d)
{
    bool ok = false;
    if ((d->params.ki >= 0) && (d->params.ki_shift <= QFOC_DOB_SHIFT_MAX)
        && (d->params.r >= 0) && (d->params.g >= 0)
        && (d->params.k_theta <= QFOC_EMF_KTHETA_MAX)
        && (d->ih_alpha >= QFOC_Q31_MIN) && (d->ih_beta >= QFOC_Q31_MIN)
        && (d->i_prev.alpha >= QFOC_Q15_MIN) && (d->i_prev.beta >= QFOC_Q15_MIN)
        && (d->e_prev.alpha >= QFOC_Q15_MIN) && (d->e_prev.beta >= QFOC_Q15_MIN)) {
        ok = true;
    } else {
        /* a coefficient or a state out of range */
    }
    return ok;
}

int32_t qfoc_dob_init(qfoc_dob_t *d, const qfoc_dob_params_t *p)
{
    int32_t status;
    if (qfoc_dob_params_ok(p)) {
        d->params.ki = p->ki;
        d->params.ki_shift = p->ki_shift;
        d->params.r = p->r;
        d->params.g = p->g;
        d->params.k_theta = p->k_theta;
        status = QFOC_EMF_OK;
    } else {
        d->params.ki = 0;
        d->params.ki_shift = 0u;
        d->params.r = 0;
        d->params.g = 0;
        d->params.k_theta = 0u;
        status = QFOC_EMF_ERR_PARAM;
    }
    d->ih_alpha = 0;
    d->ih_beta = 0;
    d->i_prev.alpha = 0;
    d->i_prev.beta = 0;
    d->e_prev.alpha = 0;
    d->e_prev.beta = 0;
    return status;
}

void qfoc_dob_reset(qfoc_dob_t *d, const qfoc_ab_t *i0)
{
    d->i_prev.alpha = qfoc_q15_sat((int32_t)i0->alpha);
    d->i_prev.beta = qfoc_q15_sat((int32_t)i0->beta);
    /* Q15 -> Q27: |.| <= 32767 x 4096 = 134213632 */
    d->ih_alpha = (int32_t)d->i_prev.alpha * QFOC_EMF_Q15_TO_Q27;
    d->ih_beta = (int32_t)d->i_prev.beta * QFOC_EMF_Q15_TO_Q27;
    d->e_prev.alpha = 0;
    d->e_prev.beta = 0;
}

void qfoc_dob_step(qfoc_dob_t *d, const qfoc_ab_t *u, const qfoc_ab_t *i,
                   qfoc_emf_out_t *out)
{
    /* inputs read once; the instance is updated by one call, the output written once */
    const qfoc_ab_t emf = qfoc_dob_update(d, u->alpha, u->beta, i->alpha, i->beta);
    out->emf = emf;
    out->theta = qfoc_emf_angle(emf.alpha, emf.beta);
}

qfoc_angle_t qfoc_dob_lag(const qfoc_dob_t *d, qfoc_q15_t w)
{
    /* lambda = ki g / 2^(12 + ki_shift) in Q15, rounded: ki g <= 32767^2 and the
       divisor 4096 x 2^ki_shift <= 2^27 fit 32 bits */
    const int32_t kg = (int32_t)d->params.ki * (int32_t)d->params.g;
    const int32_t div = QFOC_DOB_LAMBDA_DIV * qfoc_emf_pow2(d->params.ki_shift);
    int32_t lambda;

    /*@ assert kg_range: 0 <= kg <= 32767 * 32767; */
    lambda = (kg + (div / 2)) / div;
    if (lambda > QFOC_EMF_ALPHA_MAX) {
        lambda = QFOC_EMF_ALPHA_MAX;
    } else if (lambda < 1) {
        lambda = 1;
    } else {
        /* already a low-pass coefficient */
    }
    return qfoc_emf_lag_core((qfoc_q15_t)lambda, d->params.k_theta, w);
}
