/* tools/demo/accuracy.c -- the qfoc core measured against double precision.
 *
 * Host program behind 'make accuracy': runs every core function over exhaustive
 * or dense input sets, compares with the equations of specs/equations.md evaluated in double
 * precision, and prints a table of the measured worst-case errors beside the
 * bounds the headers state.  Exit status 1 when a bound is exceeded.  Not part of
 * the library (it uses floating point). */
#include <math.h>
#include <stdint.h>
#include <stdio.h>

#include "qfoc/q15.h"
#include "qfoc/trig.h"
#include "qfoc/vector.h"
#include "qfoc/transforms.h"
#include "qfoc/svpwm.h"

#define PI_D 3.14159265358979323846

static uint32_t seed = 0x2545F491u;

static uint32_t rnd(void)
{
    seed = (seed * 1664525u) + 1013904223u;
    return seed;
}

static int16_t rnd_q15(void)
{
    return (int16_t)(rnd() >> 16);
}

static double maxd(double a, double b)
{
    return (a > b) ? a : b;
}

static int failures = 0;

static void row(const char *name, const char *inputs, double measured, double bound, const char *unit)
{
    int ok = measured <= bound;
    if (!ok) {
        failures++;
    }
    printf("| %-26s | %-34s | %9.6f %-4s | %8.4f %-4s | %-4s |\n", name, inputs, measured, unit, bound,
           unit, ok ? "ok" : "FAIL");
}

int main(void)
{
    double e;
    printf("qfoc core accuracy against double precision (specs/equations.md)\n\n");
    printf("| %-26s | %-34s | %-16s | %-13s | %-4s |\n", "function", "inputs", "max abs error", "header bound",
           "");
    printf("|%s|%s|%s|%s|%s|\n", "----------------------------", "------------------------------------",
           "------------------", "---------------", "------");

    /* sin / cos over all 65536 angles */
    e = 0.0;
    for (uint32_t a = 0u; a < 65536u; a++) {
        qfoc_sincos_t sc;
        qfoc_sincos((qfoc_angle_t)a, &sc);
        double th = 2.0 * PI_D * (double)a / 65536.0;
        e = maxd(e, fabs((double)sc.sine - 32767.0 * sin(th)));
        e = maxd(e, fabs((double)sc.cosine - 32767.0 * cos(th)));
    }
    row("qfoc_sincos", "all 65536 angles", e, 1.0, "LSB");

    /* atan2 on a dense grid, error in electrical degrees */
    e = 0.0;
    for (int32_t y = -32768; y <= 32767; y += 97) {
        for (int32_t x = -32768; x <= 32767; x += 89) {
            if ((x == 0) && (y == 0)) {
                continue;
            }
            double ref = atan2((double)y, (double)x) * 65536.0 / (2.0 * PI_D);
            double got = (double)qfoc_atan2((int16_t)y, (int16_t)x);
            double d = fmod(got - ref + 3.0 * 65536.0, 65536.0);
            if (d > 32768.0) {
                d -= 65536.0;
            }
            e = maxd(e, fabs(d) * 360.0 / 65536.0);
        }
    }
    row("qfoc_atan2", "338x368 grid over [-1, 1)^2", e, 360.0 / 65536.0, "deg");

    /* magnitude */
    e = 0.0;
    for (uint32_t k = 0u; k < 1000000u; k++) {
        int16_t x = rnd_q15();
        int16_t y = rnd_q15();
        double ref = sqrt((double)x * x + (double)y * y);
        ref = (ref > 32767.0) ? 32767.0 : ref;
        e = maxd(e, fabs((double)qfoc_vec_mag(x, y) - ref));
    }
    row("qfoc_vec_mag", "1e6 random vectors", e, 1.0, "LSB");

    /* Clarke inside the bound of specs/equations.md E2-6 */
    e = 0.0;
    for (uint32_t k = 0u; k < 1000000u; k++) {
        int16_t iu = rnd_q15();
        int16_t iv = rnd_q15();
        double s = (double)iu + 2.0 * (double)iv;
        if ((iu == -32768) || (s * s > 3.0 * 32767.0 * 32767.0)) {
            continue;
        }
        qfoc_ab_t ab;
        qfoc_clarke(iu, iv, &ab);
        e = maxd(e, fabs((double)ab.alpha - iu));
        e = maxd(e, fabs((double)ab.beta - s / sqrt(3.0)));
    }
    row("qfoc_clarke", "1e6 random, inside bound 2-6", e, 0.70, "LSB");

    /* Park and inverse Park with |v| <= 32767 and exact unit vectors */
    double ep = 0.0;
    double eip = 0.0;
    for (uint32_t k = 0u; k < 1000000u; k++) {
        double th = 2.0 * PI_D * (double)(rnd() & 0xFFFFu) / 65536.0;
        double r = 32767.0 * (double)(rnd() & 0xFFFFu) / 65536.0;
        double ph = 2.0 * PI_D * (double)(rnd() & 0xFFFFu) / 65536.0;
        qfoc_sincos_t sc = { (int16_t)lround(32767.0 * sin(th)), (int16_t)lround(32767.0 * cos(th)) };
        double s = (double)sc.sine / 32768.0;
        double c = (double)sc.cosine / 32768.0;
        qfoc_ab_t ab = { (int16_t)lround(r * cos(ph)), (int16_t)lround(r * sin(ph)) };
        qfoc_dq_t dq;
        qfoc_park(&ab, &sc, &dq);
        ep = maxd(ep, fabs((double)dq.d - (ab.alpha * c + ab.beta * s)));
        ep = maxd(ep, fabs((double)dq.q - (-ab.alpha * s + ab.beta * c)));
        qfoc_dq_t v = { ab.alpha, ab.beta };
        qfoc_ab_t o;
        qfoc_inv_park(&v, &sc, &o);
        eip = maxd(eip, fabs((double)o.alpha - (v.d * c - v.q * s)));
        eip = maxd(eip, fabs((double)o.beta - (v.d * s + v.q * c)));
    }
    row("qfoc_park", "1e6 random, norm <= 32767 (2-9)", ep, 0.5, "LSB");
    row("qfoc_inv_park", "1e6 random, norm <= 32767", eip, 0.5, "LSB");

    /* inverse Clarke inside its range */
    e = 0.0;
    for (uint32_t k = 0u; k < 1000000u; k++) {
        double r = 32767.0 * (double)(rnd() & 0xFFFFu) / 65536.0;
        double ph = 2.0 * PI_D * (double)(rnd() & 0xFFFFu) / 65536.0;
        qfoc_ab_t ab = { (int16_t)lround(r * cos(ph)), (int16_t)lround(r * sin(ph)) };
        qfoc_abc_t u;
        qfoc_inv_clarke(&ab, &u);
        double rv = (-ab.alpha + sqrt(3.0) * ab.beta) / 2.0;
        double rw = (-ab.alpha - sqrt(3.0) * ab.beta) / 2.0;
        e = maxd(e, fabs((double)u.u - ab.alpha));
        e = maxd(e, fabs((double)u.v - rv));
        e = maxd(e, fabs((double)u.w - rw));
    }
    row("qfoc_inv_clarke", "1e6 random, norm <= 32767", e, 0.6, "LSB");

    /* Q15 multiply */
    e = 0.0;
    for (uint32_t k = 0u; k < 1000000u; k++) {
        int16_t a = rnd_q15();
        int16_t b = rnd_q15();
        if ((a == -32768) && (b == -32768)) {
            continue;
        }
        e = maxd(e, fabs((double)qfoc_q15_mul(a, b) - (double)a * b / 32768.0));
    }
    row("qfoc_q15_mul", "1e6 random pairs", e, 0.5, "LSB");

    /* SVPWM: compare values vs the ideal min-max injected duty, linear range */
    e = 0.0;
    qfoc_svpwm_cfg_t cfg = { 5000u, 0u, 0, 1000 };
    for (uint32_t k = 0u; k < 200000u; k++) {
        int16_t vdc = (int16_t)(8000 + (int32_t)(rnd() % 24000u));
        double rmax = (double)vdc / sqrt(3.0) * 0.999;
        double r = rmax * (double)(rnd() & 0xFFFFu) / 65536.0;
        double ph = 2.0 * PI_D * (double)(rnd() & 0xFFFFu) / 65536.0;
        qfoc_ab_t v = { (int16_t)lround(r * cos(ph)), (int16_t)lround(r * sin(ph)) };
        qfoc_abc_t i0 = { 0, 0, 0 };
        qfoc_svpwm_out_t out;
        qfoc_svpwm_step(&cfg, &v, vdc, &i0, &out);
        double ua = v.alpha;
        double ub = (-v.alpha + sqrt(3.0) * v.beta) / 2.0;
        double uc = (-v.alpha - sqrt(3.0) * v.beta) / 2.0;
        double mx = maxd(ua, maxd(ub, uc));
        double mn = -maxd(-ua, maxd(-ub, -uc));
        double off = -(mx + mn) / 2.0;
        double t[3] = { ua, ub, uc };
        for (int p = 0; p < 3; p++) {
            double ref = 2500.0 + (t[p] + off) / vdc * 5000.0;
            e = maxd(e, fabs((double)out.cmp[p] - ref));
        }
    }
    /* header bound in the linear range: 3 + 2 P / Vdc ticks; Vdc >= 8000 here */
    row("qfoc_svpwm_step", "2e5 random, linear range, T=5000", e, 3.0 + 2.0 * 5000.0 / 8000.0, "tick");

    printf("\n%s\n", (failures == 0) ? "all measured errors are within the stated bounds"
                                     : "SOME BOUNDS EXCEEDED");
    return (failures == 0) ? 0 : 1;
}
