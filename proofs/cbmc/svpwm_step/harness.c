/*
 * CBMC harness: qfoc_svpwm_step over every configuration (valid or not), every
 * voltage command, bus voltage and phase current (nondet int16, -32768 included).
 * Checks: no run-time error (overflow, conversion, division by zero), the safe
 * zero-voltage output for an invalid configuration, and for a valid one:
 * compare values in [0, period], sector 1..6 ordering the compare values as the
 * document's table, utilisation in [0, 32767], vdc_low flag, centred pulses.
 * The callees qfoc_vec_mag() and qfoc_inv_clarke() are replaced by stubs that
 * return ANY value their contracts allow (each has its own harness,
 * vector_mag and transforms_inv_clarke): an over-approximation, so every
 * property shown here holds for the real functions too, and the SAT problem
 * stays small (no square-root loop).
 * Requirements: REQ-SVPWM-001 .. REQ-SVPWM-006, REQ-SVPWM-008, REQ-SVPWM-009.
 *
 * Methods: 1b every configuration, valid or not, every voltage command, bus voltage and
 * phase current; 1c -32768 inputs, the period 100 and 32767 of the validity rule,
 * compare values in [0, period], utilisation in [0, 32767]; 1d an invalid
 * configuration: the safe zero-voltage output
 */
#include "qfoc/svpwm.h"
#include "qfoc/transforms.h"
#include "qfoc/vector.h"

int16_t nondet_int16(void);
uint16_t nondet_uint16(void);

/* contract of qfoc_vec_mag: 0 <= result <= 32767 (weakened: any such value) */
qfoc_q15_t qfoc_vec_mag(qfoc_q15_t x, qfoc_q15_t y)
{
    qfoc_q15_t r = nondet_int16();
    (void)x;
    (void)y;
    __CPROVER_assume((r >= 0) && (r <= 32767));
    return r;
}

/* contract of qfoc_inv_clarke: outputs in [-32767, 32767] (weakened: any such values) */
void qfoc_inv_clarke(const qfoc_ab_t *in, qfoc_abc_t *out)
{
    qfoc_abc_t r;
    __CPROVER_assert(__CPROVER_r_ok(in, sizeof(*in)) && __CPROVER_w_ok(out, sizeof(*out)),
                     "inv_clarke pointers valid");
    r.u = nondet_int16();
    r.v = nondet_int16();
    r.w = nondet_int16();
    __CPROVER_assume((r.u >= -32767) && (r.v >= -32767) && (r.w >= -32767));
    *out = r;
}

static int32_t max3(int32_t a, int32_t b, int32_t c)
{
    int32_t m = (a > b) ? a : b;
    return (m > c) ? m : c;
}

static int32_t min3(int32_t a, int32_t b, int32_t c)
{
    int32_t m = (a < b) ? a : b;
    return (m < c) ? m : c;
}

int main(void)
{
    qfoc_svpwm_cfg_t cfg;
    qfoc_ab_t ab;
    qfoc_abc_t i;
    qfoc_svpwm_out_t out;
    qfoc_q15_t vdc = nondet_int16();
    int32_t p;
    int32_t a;
    int32_t b;
    int32_t c;
    bool ok;

    cfg.period = nondet_uint16();
    cfg.dt_comp = nondet_uint16();
    cfg.i_deadband = nondet_int16();
    cfg.vdc_min = nondet_int16();
    ab.alpha = nondet_int16();
    ab.beta = nondet_int16();
    i.u = nondet_int16();
    i.v = nondet_int16();
    i.w = nondet_int16();

    ok = qfoc_svpwm_cfg_is_valid(&cfg);
    __CPROVER_assert(ok == ((cfg.period >= 100u) && (cfg.period <= 32767u) &&
                            ((uint32_t)cfg.dt_comp * 4u <= (uint32_t)cfg.period) &&
                            (cfg.i_deadband >= 0) && (cfg.vdc_min > 0)),
                     "cfg_is_valid mirrors SvpwmCfgValid");

    qfoc_svpwm_step(&cfg, &ab, vdc, &i, &out);

    p = (int32_t)cfg.period;
    a = (int32_t)out.cmp[0];
    b = (int32_t)out.cmp[1];
    c = (int32_t)out.cmp[2];
    __CPROVER_assert((out.sector >= 1u) && (out.sector <= 6u), "sector range");
    __CPROVER_assert((out.utilisation >= 0) && (out.utilisation <= 32767), "utilisation range");
    if (!ok) {
        __CPROVER_assert((a == p / 2) && (b == p / 2) && (c == p / 2), "invalid: 50 percent");
        __CPROVER_assert(out.limited && !out.vdc_low && (out.sector == 1u) &&
                         (out.utilisation == 0), "invalid: flags");
    } else {
        __CPROVER_assert((a <= p) && (b <= p) && (c <= p), "cmp in [0, period]");
        __CPROVER_assert(out.vdc_low == (vdc < cfg.vdc_min), "vdc_low flag");
        __CPROVER_assert(((out.sector == 1u) && (a >= b) && (b >= c)) ||
                         ((out.sector == 2u) && (a >= c) && (c >= b)) ||
                         ((out.sector == 3u) && (b >= c) && (c >= a)) ||
                         ((out.sector == 4u) && (b >= a) && (a >= c)) ||
                         ((out.sector == 5u) && (c >= a) && (a >= b)) ||
                         ((out.sector == 6u) && (c >= b) && (b >= a)), "sector orders cmp");
        if ((a > 0) && (a < p) && (b > 0) && (b < p) && (c > 0) && (c < p)) {
            int32_t s = max3(a, b, c) + min3(a, b, c);
            __CPROVER_assert((s >= p - 1) && (s <= p + 1), "centred pulses");
        }
    }
    return 0;
}
