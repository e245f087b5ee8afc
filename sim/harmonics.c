/**
 * @file harmonics.c
 * @brief The harmonic content of a sampled periodic signal (sim.h sim_harmonics()): the
 *        double-precision reference of the phase-current THD (REQ-SCN-018).
 */
#include "sim.h"

#include <math.h>
#include <string.h>

/* The DFT bin m of the n samples: sum x_k exp(-j 2 pi m k / n), the angle reduced exactly
   in integers (m k mod n) so that a long record loses no accuracy in the cosine. */
static void sim_dft_bin(const double *x, long stride, long n, long m, double *re, double *im)
{
    double sr = 0.0;
    double si = 0.0;
    long k;
    long idx = 0;   /* (m k) mod n */
    for (k = 0; k < n; k++) {
        const double a = 2.0 * SIM_PI * (double)idx / (double)n;
        const double v = x[k * stride];
        sr += v * cos(a);
        si -= v * sin(a);
        idx += m;
        if (idx >= n) {
            idx %= n;
        }
    }
    *re = sr;
    *im = si;
}

int sim_harmonics(const double *x, long stride, long n, int cycles, int h_max, sim_harm_t *out)
{
    double re;
    double im;
    double a1;
    double ph1;
    double sum2 = 0.0;
    double d2 = 0.0;
    long k;
    int h;

    memset(out, 0, sizeof *out);
    if (cycles < 1 || h_max < 2 || h_max > SIM_HARM_MAX || stride < 1 ||
        n <= 2L * (long)h_max * (long)cycles) {
        return -1;
    }
    for (h = 0; h <= h_max; h++) {
        double amp;
        sim_dft_bin(x, stride, n, (long)h * (long)cycles, &re, &im);
        if (h == 0) {
            out->dc = re / (double)n;
            out->h_rms[0] = fabs(out->dc);
            continue;
        }
        /* a cosine of amplitude A gives |X| = A n / 2 */
        amp = 2.0 * hypot(re, im) / (double)n;
        out->h_rms[h] = amp / sqrt(2.0);
        if (h == 1) {
            out->fund_phase = atan2(im, re);
        } else {
            sum2 += out->h_rms[h] * out->h_rms[h];
        }
    }
    out->fund_rms = out->h_rms[1];
    if (!(out->fund_rms > 0.0)) {
        memset(out, 0, sizeof *out);
        return -1;
    }
    out->harm_rms = sqrt(sum2);
    out->thd = out->harm_rms / out->fund_rms;
    a1 = sqrt(2.0) * out->fund_rms;
    ph1 = out->fund_phase;
    {
        long idx = 0;   /* (cycles k) mod n */
        for (k = 0; k < n; k++) {
            const double f = a1 * cos(2.0 * SIM_PI * (double)idx / (double)n + ph1);
            const double d = x[k * stride] - f;
            d2 += d * d;
            idx += cycles;
            if (idx >= n) {
                idx %= n;
            }
        }
    }
    out->dist_rms = sqrt(d2 / (double)n);
    out->tdd = out->dist_rms / out->fund_rms;
    return 0;
}
