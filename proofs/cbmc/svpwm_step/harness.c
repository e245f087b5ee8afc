/*
 * CBMC harness: qfoc_svpwm_step over every configuration (valid or not), every
 * voltage command, bus voltage and phase current (nondet int16, -32768 included).
 * Checks: no run-time error (overflow, conversion, division by zero), the safe
 * zero-voltage output for an invalid configuration, and for a valid one:
 * compare values in [0, period], sector 1..6 ordering the compare values as the
 * document's table, utilisation in [0, 32767], vdc_low flag, centred pulses.
 * Requirements: REQ-SVPWM-001 .. REQ-SVPWM-006, REQ-SVPWM-008, REQ-SVPWM-009.
 */
#include "qfoc/svpwm.h"

int16_t nondet_int16(void);
uint16_t nondet_uint16(void);

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
