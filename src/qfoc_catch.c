/**
 * @file qfoc_catch.c
 * @brief Flying start: the verdict on a coasting rotor (catch.h).
 */
#include "qfoc/catch.h"

/* |x| of a 16-bit value in 32 bits. */
/*@
  assigns \nothing;
  ensures result: \result == CatchAbs(x);
*/
static int32_t catch_abs(qfoc_q15_t x)
{
    return (x < 0) ? -(int32_t)x : (int32_t)x;
}

/* The divisor 32768 / 2^s of the flux base (catch.h); a shift above 4 reads as 4. */
/*@
  assigns \nothing;
  ensures result: \result == CatchDiv(s);
  ensures range: 2048 <= \result <= 32768;
*/
static int32_t catch_div(uint8_t s)
{
    int32_t d = 2048;
    if (s == 0u) {
        d = 32768;
    } else if (s == 1u) {
        d = 16384;
    } else if (s == 2u) {
        d = 8192;
    } else if (s == 3u) {
        d = 4096;
    } else {
        /* 4 and above: the largest flux base */
    }
    return d;
}

/* The back-EMF of a speed, w |psi| 2^s / 32768 truncated (the one product of the verdict,
   kept apart so that the verdict's goals are linear). */
/*@
  requires w: -32768 <= w <= 32768;
  assigns \nothing;
  ensures result: \result == CatchEmf(w, psi, s);
  ensures range: -524288 <= \result <= 524288;
*/
static int32_t catch_emf(int32_t w, qfoc_q15_t psi, uint8_t s)
{
    const int32_t p = catch_abs(psi);
    const int32_t d = catch_div(s);
    /*@ assert p: 0 <= p <= 32768; */
    /*@ assert prod: -32768 * 32768 <= w * p <= 32768 * 32768; */
    /*@ assert quot: -524288 <= (w * p) / d <= 524288; */
    return (w * p) / d;
}

/* public interface, also called by qfoc_catch_step (DEV-002) */
/* cppcheck-suppress misra-c2012-8.7 ; DEV-002 */
uint8_t qfoc_catch_verdict(const qfoc_catch_meas_t *m, const qfoc_catch_cfg_t *c)
{
    const int32_t w = (int32_t)m->speed;
    const int32_t psi_f = catch_abs(c->psi_f);
    const int32_t v_err = catch_abs(c->v_err);
    const int32_t u = catch_abs(m->u_mag);
    const int32_t w_min = catch_abs(c->w_min);
    const int32_t e = catch_emf(w, c->psi_f, c->psi_shift);
    const int32_t e_min = catch_emf(w_min, c->psi_f, c->psi_shift);
    const int32_t de = u - e;
    const int32_t dpsi = (int32_t)m->psi_mag - psi_f;
    const int32_t band = v_err + (e / 4);
    const bool speed_ok = (w >= w_min) && (w <= catch_abs(c->w_max));
    const bool flux_ok = (dpsi <= catch_abs(c->psi_tol)) && (dpsi >= -catch_abs(c->psi_tol));
    const bool emf_ok = (de <= band) && (de >= -band);
    int32_t v_still = 2 * v_err;
    uint8_t r = QFOC_CATCH_WAIT;
    if (v_still < (e_min / 4)) {
        v_still = e_min / 4;   /* the floor: a quarter of the back-EMF at w_min */
    } else {
        /* twice the inverter's error */
    }
    if (speed_ok && flux_ok && emf_ok) {
        r = QFOC_CATCH_LOCK;
    } else if (u <= v_still) {
        r = QFOC_CATCH_STILL;
    } else {
        /* turning, not catchable */
    }
    return r;
}

void qfoc_catch_reset(qfoc_catch_t *k)
{
    k->u_f = 32767;
    qfoc_debounce_reset(&k->db_lock);
    qfoc_debounce_reset(&k->db_still);
}

uint8_t qfoc_catch_step(qfoc_catch_t *k, qfoc_q15_t u, qfoc_q15_t speed, qfoc_q15_t psi,
                        const qfoc_catch_cfg_t *c, uint16_t dwell)
{
    const int32_t uf = (int32_t)k->u_f;
    const uint16_t n = (dwell > 0u) ? dwell : 1u;
    qfoc_catch_meas_t m;
    uint8_t v;
    uint8_t r = QFOC_CATCH_WAIT;
    const int32_t du = catch_abs(u) - uf;
    /* an eighth of the difference, rounded away from zero: the filter reaches |u| */
    const int32_t step = (du >= 0) ? ((du + 7) / 8) : -((7 - du) / 8);
    const int32_t nf = uf + step;
    /* within [min(u_f, |u|), max(u_f, |u|)], but for |u| = 32768 (u = -32768) one past
       32767 at full scale: saturated */
    k->u_f = (nf > 32767) ? (qfoc_q15_t)32767 : (qfoc_q15_t)nf;
    m.speed = speed;
    m.psi_mag = psi;
    m.u_mag = k->u_f;
    v = qfoc_catch_verdict(&m, c);
    {
        const bool lock = qfoc_debounce_step(&k->db_lock, v == QFOC_CATCH_LOCK, n);
        const bool still = qfoc_debounce_step(&k->db_still, v == QFOC_CATCH_STILL, n);
        if (lock) {
            r = QFOC_CATCH_LOCK;
        } else if (still) {
            r = QFOC_CATCH_STILL;
        } else {
            /* not yet, or turning */
        }
    }
    return r;
}
