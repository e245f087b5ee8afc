/**
 * @file qfoc_fault.c
 * @brief Fault-detection primitives (see include/qfoc/fault.h).
 *
 * Requirements: REQ-FAULT-001 .. REQ-FAULT-009 (specs/requirements/fault.md).
 */
#include "qfoc/fault.h"
#include "qfoc/q15.h"

/** Largest low-pass state of a filtered magnitude: 32767 x 65536 (Q15 1.0 in Q31). */
#define QFOC_FAULT_STATE_MAX ((qfoc_q31_t)2147418112)
/** Q15 scale of the imbalance ratio: 1.0 = 2^15 = 32768. */
#define QFOC_FAULT_Q15_ONE ((int32_t)32768)

/**
 * @brief One filter of the monitor: alpha > 0 and state in [0, 32767 x 65536].
 */
/*@
  requires valid_f: \valid_read(f);
  assigns \nothing;
  ensures result: \result <==> PhaseMonLpfOk(f);
*/
static bool qfoc_phase_lpf_ok(const qfoc_lpf_t *f)
{
    bool ok = false;
    if ((f->alpha > 0) && (f->state >= 0) && (f->state <= QFOC_FAULT_STATE_MAX)) {
        ok = true;
    } else {
        /* invalid coefficient, or a negative / too large state */
    }
    return ok;
}

void qfoc_debounce_reset(qfoc_debounce_t *d)
{
    d->count = 0u;
}

bool qfoc_debounce_step(qfoc_debounce_t *d, bool cond, uint16_t n)
{
    bool confirmed = false;
    if (!cond) {
        /* a single false sample restarts the count */
        d->count = 0u;
    } else if (d->count < n) {
        /* count < n <= 65535: count + 1 fits 16 bits */
        d->count = (uint16_t)(d->count + 1u);
        confirmed = (d->count >= n);
    } else {
        /* already confirmed (or count above n): cap at n */
        d->count = n;
        confirmed = true;
    }
    return confirmed;
}

bool qfoc_phase_mon_is_valid(const qfoc_phase_mon_t *m)
{
    bool ok = false;
    if (qfoc_phase_lpf_ok(&m->abs_lpf[0]) && qfoc_phase_lpf_ok(&m->abs_lpf[1])
        && qfoc_phase_lpf_ok(&m->abs_lpf[2])) {
        ok = true;
    } else {
        /* at least one filter out of its invariant */
    }
    return ok;
}

int32_t qfoc_phase_mon_init(qfoc_phase_mon_t *m, qfoc_q15_t alpha)
{
    /* the three inits see the same alpha, so they return the same status */
    int32_t status = QFOC_FAULT_ERR_PARAM;
    if (qfoc_lpf_init(&m->abs_lpf[0], alpha) == QFOC_FILTER_OK) {
        status = QFOC_FAULT_OK;
    }
    (void)qfoc_lpf_init(&m->abs_lpf[1], alpha);
    (void)qfoc_lpf_init(&m->abs_lpf[2], alpha);
    return status;
}

void qfoc_phase_mon_reset(qfoc_phase_mon_t *m)
{
    qfoc_lpf_reset(&m->abs_lpf[0], 0);
    qfoc_lpf_reset(&m->abs_lpf[1], 0);
    qfoc_lpf_reset(&m->abs_lpf[2], 0);
}

void qfoc_phase_mon_update(qfoc_phase_mon_t *m, const qfoc_abc_t *i)
{
    /* |i| in [0, 32767] (|-32768| saturated) */
    const qfoc_q15_t au = qfoc_q15_abs(i->u);
    const qfoc_q15_t av = qfoc_q15_abs(i->v);
    const qfoc_q15_t aw = qfoc_q15_abs(i->w);
    /*@ assert abs_u: au == FaultAbs15(i->u); */
    /*@ assert abs_v: av == FaultAbs15(i->v); */
    /*@ assert abs_w: aw == FaultAbs15(i->w); */
    /* the filter outputs are not needed here (read by qfoc_phase_mon_imbalanced) */
    (void)qfoc_lpf_step(&m->abs_lpf[0], au);
    (void)qfoc_lpf_step(&m->abs_lpf[1], av);
    (void)qfoc_lpf_step(&m->abs_lpf[2], aw);
}

void qfoc_phase_mon_update_one(qfoc_phase_mon_t *m, const qfoc_abc_t *i, uint8_t k)
{
    /* the filter output is not needed here (read by qfoc_phase_mon_imbalanced) */
    if (k == 0u) {
        (void)qfoc_lpf_step(&m->abs_lpf[0], qfoc_q15_abs(i->u));
    } else if (k == 1u) {
        (void)qfoc_lpf_step(&m->abs_lpf[1], qfoc_q15_abs(i->v));
    } else {
        (void)qfoc_lpf_step(&m->abs_lpf[2], qfoc_q15_abs(i->w));
    }
}

qfoc_q15_t qfoc_phase_mon_alpha3(qfoc_q15_t alpha)
{
    const int32_t a = (alpha < 1) ? (int32_t)1 : (int32_t)alpha;
    /* b = 1 - alpha in [1, 32767]; b^2 and b^3 rounded to Q15, each in [0, 32767] */
    const int32_t b = 32768 - a;
    const int32_t b2 = ((b * b) + 16384) / 32768;
    const int32_t b3 = ((b2 * b) + 16384) / 32768;
    int32_t r = 32768 - b3;
    /*@ assert b_value: b == PhaseMonB(alpha); */
    /*@ assert b2_range: 0 <= b2 <= 32767; */
    /*@ assert b3_value: b3 == (((b * b + 16384) / 32768) * b + 16384) / 32768; */
    /*@ assert b3_logic: b3 == PhaseMonB3(alpha); */
    /*@ assert b3_range: 0 <= b3 <= 32767; */
    if (r > 32767) {
        r = 32767;
    } else {
        /* b3 >= 1 */
    }
    return (qfoc_q15_t)r;
}

bool qfoc_phase_mon_imbalanced(const qfoc_phase_mon_t *m, qfoc_q15_t i_min, qfoc_q15_t ratio)
{
    /* filtered magnitudes, Q15, each in [0, 32767] (state in [0, 32767 x 65536]) */
    const int32_t a = (int32_t)qfoc_q15_from_q31(m->abs_lpf[0].state);
    const int32_t b = (int32_t)qfoc_q15_from_q31(m->abs_lpf[1].state);
    const int32_t c = (int32_t)qfoc_q15_from_q31(m->abs_lpf[2].state);
    int32_t hi = a;
    int32_t lo = a;
    int32_t lhs;
    int32_t rhs;
    bool imbalanced = false;

    if (b > hi) {
        hi = b;
    }
    if (c > hi) {
        hi = c;
    }
    if (b < lo) {
        lo = b;
    }
    if (c < lo) {
        lo = c;
    }
    /*@ assert hi_range: 0 <= hi <= 32767; */
    /*@ assert lo_range: 0 <= lo <= 32767; */
    /*@ assert rhs_hi: ratio * hi <= 32767 * hi; */
    /*@ assert rhs_lo: ratio * hi >= -32768 * hi; */
    /* min x 32768 <= 1073709056 and |ratio x max| <= 1073709056: exact in 32 bits */
    lhs = lo * QFOC_FAULT_Q15_ONE;
    rhs = (int32_t)ratio * hi;
    if ((hi >= (int32_t)i_min) && (lhs < rhs)) {
        imbalanced = true;
    } else {
        /* balanced, or too little current to judge */
    }
    return imbalanced;
}

qfoc_q15_t qfoc_phase_mon_peak(const qfoc_phase_mon_t *m)
{
    /* filtered magnitudes, Q15, each in [0, 32767] (state in [0, 32767 x 65536]) */
    const qfoc_q15_t a = qfoc_q15_from_q31(m->abs_lpf[0].state);
    const qfoc_q15_t b = qfoc_q15_from_q31(m->abs_lpf[1].state);
    const qfoc_q15_t c = qfoc_q15_from_q31(m->abs_lpf[2].state);
    qfoc_q15_t hi = a;

    if (b > hi) {
        hi = b;
    } else {
        /* a stays the largest so far */
    }
    if (c > hi) {
        hi = c;
    } else {
        /* the largest is a or b */
    }
    return hi;
}

bool qfoc_fault_over(qfoc_q15_t x, qfoc_q15_t limit)
{
    return (x > limit);
}

bool qfoc_fault_under(qfoc_q15_t x, qfoc_q15_t limit)
{
    return (x < limit);
}

bool qfoc_fault_band_over(qfoc_q15_t dev, qfoc_q15_t k, int32_t v, qfoc_q15_t w)
{
    const int32_t kk = (k > 0) ? (int32_t)k : 0;
    const int32_t vc = (v < 0) ? 0 : ((v > 65535) ? 65535 : v);
    const int32_t aw = (w < 0) ? -(int32_t)w : (int32_t)w;
    bool over = false;
    if ((int32_t)dev > kk) {
        /* dev - k' in [1, 32767], |w| in [0, 32768]: the product at most 2^30 - 2^15;
           32768 v' at most 2147450880 < 2^31 - 1: both in int32 */
        const int32_t e = (int32_t)dev - kk;
        const int32_t lhs = e * aw;
        const int32_t rhs = vc * 32768;
        over = (lhs > rhs);
    } else {
        /* within the speed-independent part */
    }
    return over;
}

bool qfoc_fault_abs_over(qfoc_q15_t x, qfoc_q15_t limit)
{
    /* |x| in [0, 32768], exact in 32 bits (no saturation of -32768) */
    const int32_t mag = (x < 0) ? -(int32_t)x : (int32_t)x;
    return (mag > (int32_t)limit);
}

const char *qfoc_fault_name(uint16_t bit)
{
    /* the texts, each in static read-only storage of its exact size */
    static const char txt_oc[] = "OC";
    static const char txt_ov[] = "OV";
    static const char txt_uv[] = "UV";
    static const char txt_ot_ipm[] = "OT_IPM";
    static const char txt_ot_pcb[] = "OT_PCB";
    static const char txt_stall[] = "STALL";
    static const char txt_phase[] = "PHASE";
    static const char txt_offset[] = "OFFSET";
    static const char txt_link[] = "LINK";
    static const char txt_param[] = "PARAM";
    static const char txt_timing[] = "TIMING";
    static const char txt_none[] = "none";
    /* the longest text: QFOC_FAULT_NAME_LEN_MAX characters and the terminating zero */
    static const char txt_unknown[QFOC_FAULT_NAME_LEN_MAX + 1u] = "unknown";
    const char *name;
    switch (bit) {
    case QFOC_FAULT_OC:
        name = txt_oc;
        break;
    case QFOC_FAULT_OV:
        name = txt_ov;
        break;
    case QFOC_FAULT_UV:
        name = txt_uv;
        break;
    case QFOC_FAULT_OT_IPM:
        name = txt_ot_ipm;
        break;
    case QFOC_FAULT_OT_PCB:
        name = txt_ot_pcb;
        break;
    case QFOC_FAULT_STALL:
        name = txt_stall;
        break;
    case QFOC_FAULT_PHASE:
        name = txt_phase;
        break;
    case QFOC_FAULT_OFFSET:
        name = txt_offset;
        break;
    case QFOC_FAULT_LINK:
        name = txt_link;
        break;
    case QFOC_FAULT_PARAM:
        name = txt_param;
        break;
    case QFOC_FAULT_TIMING:
        name = txt_timing;
        break;
    case 0u:
        name = txt_none;
        break;
    default:
        /* several bits, or a bit no fault uses */
        name = txt_unknown;
        break;
    }
    return name;
}
