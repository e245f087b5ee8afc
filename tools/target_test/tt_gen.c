/**
 * @file tt_gen.c
 * @brief Host generator of the golden vectors (tt.h): inputs and the host's outputs.
 *
 *   tt_gen --motor specs/motors/reference.toml --out build/target_test
 *
 * Writes <out>/vectors.c and <out>/vectors.h.  Every input comes from a fixed-seed
 * linear congruential generator (or, for the drive, from the plant model), so two runs
 * write the same files byte for byte.  The expected digests are computed by the replay
 * code (tt_groups.c) linked against the host library, run twice (a replay that reads
 * anything uninitialised would differ between the runs); for the drive they are taken
 * from the closed-loop run itself, recorded at the library's two entry points (the
 * link option --wrap puts tt_gen between sim/drive_sim.c and libqfoc.a), and the
 * open-loop replay of the recorded inputs must reproduce them exactly.
 *
 * The closed-loop run: reference motor and table (qfoc_params_reference), 250 V bus,
 * 3 N m load pulsating +-50 % once per mechanical turn, 0.05 A rms current noise; run
 * command at 3000 rpm at t = 0 (PRECHARGE, offset calibration, ALIGN, I/f start,
 * handover), then 5800 rpm at 2.9 s (above the base speed at 250 V: field weakening;
 * above para_speed: high-speed inductances; within the torque compensation's window),
 * IPM and PCB temperatures rising, two command frames sent with a wrong checksum; at
 * 4.5 s a +50 A pulse on the sensed phase-u current for three periods (over-current
 * trip, ERROR); 4.8 s in all.  The generator checks that the drive reached closed loop
 * without a fault, that field weakening, the high-speed inductances and the torque
 * compensation were active, and that the trip switched the PWM off in the period of the
 * sample, else it fails: the vectors would not test what they claim.
 *
 * Host only (stdio, malloc, double).  Requirements: REQ-TGT-001, REQ-TGT-003.
 */
#define _POSIX_C_SOURCE 200809L

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <stddef.h>

#include "tt.h"
#include "drive_sim.h"
#include "scenario.h"
#include "reference_params.h"
#include "reference_shunt_params.h"
#include "qfoc/trig.h"

/* ------------------------------------------------------------------ random inputs */

static uint64_t g_lcg = 0x51F0C0DEu;   /* fixed seed */

/* Knuth's MMIX LCG (a = 6364136223846793005, c = 1442695040888963407); upper 32 bits. */
static uint32_t rnd(void)
{
    g_lcg = g_lcg * 6364136223846793005ull + 1442695040888963407ull;
    return (uint32_t)(g_lcg >> 32);
}

/* uniform in [lo, hi] */
static int32_t rr(int32_t lo, int32_t hi)
{
    const uint64_t span = (uint64_t)((int64_t)hi - (int64_t)lo + 1);
    return (int32_t)((int64_t)lo + (int64_t)((uint64_t)rnd() % span));
}

static bool chance(unsigned percent)
{
    return (rnd() % 100u) < percent;
}

static const int16_t C16[] = { -32768, -32767, -32766, -16385, -16384, -16383, -2, -1,
                               0, 1, 2, 16383, 16384, 16385, 32766, 32767 };
#define N_C16 ((int)(sizeof C16 / sizeof C16[0]))

static const int32_t C32[] = {
    INT32_MIN, INT32_MIN + 1, -1073741825, -1073741824, -1073725441, -1073725440,
    -1073725439, -2147418112, -65537, -65536, -32769, -32768, -32767, -16384, -2, -1, 0, 1, 2,
    16384, 32767, 32768, 32769, 65535, 65536, 1073725439, 1073725440, 1073725441,
    1073741823, 1073741824, 2147418112, INT32_MAX - 1, INT32_MAX
};
#define N_C32 ((int)(sizeof C32 / sizeof C32[0]))

/* a Q15 value: corners, small values, values near full scale, or uniform */
static int16_t rq15(void)
{
    const uint32_t s = rnd() % 16u;
    int32_t v;
    if (s < 2u) {
        v = C16[rnd() % (uint32_t)N_C16];
    } else if (s < 4u) {
        v = rr(-300, 300);
    } else if (s < 6u) {
        v = rr(32000, 32767);
        if (chance(50)) {
            v = -v - (chance(10) ? 1 : 0);
        }
    } else {
        v = (int32_t)(int16_t)(uint16_t)(rnd() & 0xFFFFu);
    }
    return (int16_t)v;
}

/* an int32: corners, the Q15 band, small, or uniform */
static int32_t ri32(void)
{
    const uint32_t s = rnd() % 8u;
    int32_t v;
    if (s == 0u) {
        v = C32[rnd() % (uint32_t)N_C32];
    } else if (s == 1u) {
        v = rr(-40000, 40000);
    } else if (s == 2u) {
        v = rr(1073700000, 1073760000) * (chance(50) ? 1 : -1);
    } else {
        v = (int32_t)rnd();
    }
    return v;
}

static int16_t clamp16(double x)
{
    double r = floor(x + 0.5);
    if (r > 32767.0) {
        r = 32767.0;
    }
    if (r < -32768.0) {
        r = -32768.0;
    }
    return (int16_t)r;
}

/* ------------------------------------------------------------------ rows */

typedef struct {
    uint16_t *w;
    uint32_t n;
    uint32_t cap;
    uint16_t width;
} rows_t;

static uint16_t *row(rows_t *r)
{
    uint16_t *p;
    if (r->n == r->cap) {
        r->cap = (r->cap == 0u) ? 1024u : 2u * r->cap;
        r->w = realloc(r->w, (size_t)r->cap * (r->width > 0u ? r->width : 1u) * sizeof(uint16_t));
        if (r->w == NULL) {
            fprintf(stderr, "tt_gen: out of memory\n");
            exit(2);
        }
    }
    p = &r->w[(size_t)r->n * r->width];
    memset(p, 0, (size_t)r->width * sizeof(uint16_t));
    r->n++;
    return p;
}

static void put32(uint16_t *p, uint32_t v)
{
    p[0] = (uint16_t)(v & 0xFFFFu);
    p[1] = (uint16_t)(v >> 16);
}

static void put_bytes(uint16_t *p, const uint8_t *b, int n)
{
    int k;
    for (k = 0; k < n; k++) {
        p[k / 2] = (uint16_t)(p[k / 2] | ((unsigned)b[k] << ((k % 2) * 8)));
    }
}

/* rows of a binary Q15 operation: every pair of corners, then n random pairs */
static void gen_pairs(rows_t *r, int n)
{
    int a;
    int b;
    for (a = 0; a < N_C16; a++) {
        for (b = 0; b < N_C16; b++) {
            uint16_t *p = row(r);
            p[0] = (uint16_t)C16[a];
            p[1] = (uint16_t)C16[b];
        }
    }
    for (a = 0; a < n; a++) {
        uint16_t *p = row(r);
        p[0] = (uint16_t)rq15();
        p[1] = (uint16_t)rq15();
    }
}

static void gen_unary(rows_t *r, int n)
{
    int a;
    for (a = 0; a < N_C16; a++) {
        row(r)[0] = (uint16_t)C16[a];
    }
    for (a = 0; a < n; a++) {
        row(r)[0] = (uint16_t)rq15();
    }
}

/* ------------------------------------------------------------------ group inputs */

static void gen_q15_sat(rows_t *r)
{
    int k;
    for (k = 0; k < N_C32; k++) {
        put32(row(r), (uint32_t)C32[k]);
    }
    for (k = 0; k < 2048; k++) {
        put32(row(r), (uint32_t)ri32());
    }
}

static void gen_q31_sat(rows_t *r)
{
    static const int64_t c[] = { INT64_MIN, INT64_MIN + 1, -2147483649LL, -2147483648LL,
                                 -2147483647LL, -1, 0, 1, 2147483646LL, 2147483647LL,
                                 2147483648LL, INT64_MAX - 1, INT64_MAX };
    int k;
    for (k = 0; k < (int)(sizeof c / sizeof c[0]); k++) {
        uint16_t *p = row(r);
        put32(p, (uint32_t)((uint64_t)c[k] & 0xFFFFFFFFu));
        put32(p + 2, (uint32_t)((uint64_t)c[k] >> 32));
    }
    for (k = 0; k < 2048; k++) {
        uint16_t *p = row(r);
        uint64_t v;
        const uint32_t s = rnd() % 4u;
        if (s == 0u) {
            v = ((uint64_t)rnd() << 32) | rnd();
        } else if (s == 1u) {
            v = (uint64_t)(int64_t)((int64_t)2147483647LL * (chance(50) ? 1 : -1) + rr(-1000, 1000));
        } else {
            v = (uint64_t)(int64_t)ri32() * (uint64_t)(chance(20) ? 2u : 1u);
        }
        put32(p, (uint32_t)(v & 0xFFFFFFFFu));
        put32(p + 2, (uint32_t)(v >> 32));
    }
}

static void gen_q15_pairs(rows_t *r) { gen_pairs(r, 2048); }
static void gen_q15_unary(rows_t *r) { gen_unary(r, 1024); }

static void gen_q15_from_q30(rows_t *r)
{
    int k;
    for (k = 0; k < N_C32; k++) {
        put32(row(r), (uint32_t)C32[k]);
    }
    for (k = 0; k < 2048; k++) {
        int32_t v = ri32();
        if (chance(40)) {
            /* around a rounding tie: m x 32768 + 16384 + {-1, 0, 1} */
            v = (int32_t)rr(-32767, 32766) * 32768 + 16384 + rr(-1, 1);
        }
        put32(row(r), (uint32_t)v);
    }
}

static void gen_q31_add(rows_t *r)
{
    int a;
    int b;
    for (a = 0; a < N_C32; a += 2) {
        for (b = 0; b < N_C32; b += 2) {
            uint16_t *p = row(r);
            put32(p, (uint32_t)C32[a]);
            put32(p + 2, (uint32_t)C32[b]);
        }
    }
    for (a = 0; a < 2048; a++) {
        uint16_t *p = row(r);
        put32(p, (uint32_t)ri32());
        put32(p + 2, (uint32_t)ri32());
    }
}

static void gen_q31_mac(rows_t *r)
{
    int a;
    int b;
    for (a = 0; a < N_C32; a += 2) {
        for (b = 0; b < N_C16; b += 3) {
            uint16_t *p = row(r);
            put32(p, (uint32_t)C32[a]);
            p[2] = (uint16_t)C16[b];
            p[3] = (uint16_t)C16[N_C16 - 1 - b];
        }
    }
    for (a = 0; a < 2048; a++) {
        uint16_t *p = row(r);
        put32(p, (uint32_t)ri32());
        p[2] = (uint16_t)rq15();
        p[3] = (uint16_t)rq15();
    }
}

static void gen_q15_from_q31(rows_t *r)
{
    int k;
    for (k = 0; k < N_C32; k++) {
        put32(row(r), (uint32_t)C32[k]);
    }
    for (k = 0; k < 2048; k++) {
        int32_t v = ri32();
        if (chance(40)) {
            /* around a rounding tie: m x 65536 + 32768 + {-1, 0, 1} */
            v = (int32_t)rr(-32768, 32766) * 65536 + 32768 + rr(-1, 1);
        }
        put32(row(r), (uint32_t)v);
    }
}

static void gen_none(rows_t *r)
{
    (void)r;   /* width 0: the vectors are the indices */
}

static void gen_atan2(rows_t *r)
{
    static const int16_t m[] = { 1, 2, 3, 100, 1000, 16384, 23170, 32766, 32767 };
    int k;
    int s;
    gen_pairs(r, 8192);
    /* octant boundaries: the axes and the diagonals, exactly and one count off */
    for (k = 0; k < (int)(sizeof m / sizeof m[0]); k++) {
        for (s = 0; s < 8; s++) {
            const int sy = (s & 1) ? -1 : 1;
            const int sx = (s & 2) ? -1 : 1;
            const int off = (s & 4) ? 1 : -1;
            uint16_t *p = row(r);
            p[0] = (uint16_t)(int16_t)(sy * m[k]);
            p[1] = (uint16_t)(int16_t)(sx * m[k]);
            p = row(r);
            p[0] = (uint16_t)(int16_t)(sy * m[k]);
            p[1] = (uint16_t)(int16_t)(sx * (m[k] + off));
            p = row(r);
            p[0] = (uint16_t)(int16_t)(sy * m[k]);
            p[1] = 0u;
            p = row(r);
            p[0] = 0u;
            p[1] = (uint16_t)(int16_t)(sx * m[k]);
        }
    }
}

static void gen_isqrt32(rows_t *r)
{
    static const uint32_t c[] = { 0u, 1u, 2u, 3u, 4u, 0xFFFFFFFFu, 0xFFFFFFFEu, 0xFFFE0001u,
                                  0xFFFE0000u, 0xFFFE0002u, 0x80000000u, 0x7FFFFFFFu,
                                  0x40000000u, 0x3FFFFFFFu };
    int k;
    for (k = 0; k < (int)(sizeof c / sizeof c[0]); k++) {
        put32(row(r), c[k]);
    }
    for (k = 0; k < 4096; k++) {
        uint32_t v = rnd();
        if (chance(40)) {
            const uint32_t q = rnd() & 0xFFFFu;
            v = q * q + (uint32_t)rr(-1, 1);
        } else if (chance(30)) {
            v >>= (rnd() % 32u);
        }
        put32(row(r), v);
    }
}

static void gen_vec_mag(rows_t *r) { gen_pairs(r, 4096); }

static void gen_circle_limit(rows_t *r)
{
    static const int16_t vm[] = { -32768, -1, 0, 1, 15892, 16384, 32767 };
    int a;
    int b;
    int v;
    for (a = 0; a < N_C16; a += 2) {
        for (b = 0; b < N_C16; b += 2) {
            for (v = 0; v < (int)(sizeof vm / sizeof vm[0]); v++) {
                uint16_t *p = row(r);
                p[0] = (uint16_t)C16[a];
                p[1] = (uint16_t)C16[b];
                p[2] = (uint16_t)vm[v];
            }
        }
    }
    for (a = 0; a < 4096; a++) {
        uint16_t *p = row(r);
        p[0] = (uint16_t)rq15();
        p[1] = (uint16_t)rq15();
        p[2] = (uint16_t)(chance(80) ? rr(0, 32767) : rq15());
    }
}

static void gen_clarke(rows_t *r) { gen_pairs(r, 4096); }

/* sine and cosine: mostly of a real angle (the library's own table on the host), or
   any pair, -32768 included */
static void rsc(int16_t *s, int16_t *c)
{
    if (chance(75)) {
        qfoc_sincos_t sc;
        qfoc_sincos((qfoc_angle_t)(rnd() & 0xFFFFu), &sc);
        *s = sc.sine;
        *c = sc.cosine;
    } else {
        *s = rq15();
        *c = rq15();
    }
}

static void gen_park(rows_t *r)
{
    static const int16_t axes[][2] = { { 0, 32767 }, { 32767, 0 }, { 0, -32767 }, { -32767, 0 },
                                       { -32768, -32768 }, { 32767, 32767 }, { 23170, 23170 } };
    int a;
    int b;
    for (a = 0; a < N_C16; a += 3) {
        for (b = 0; b < (int)(sizeof axes / sizeof axes[0]); b++) {
            uint16_t *p = row(r);
            p[0] = (uint16_t)C16[a];
            p[1] = (uint16_t)C16[N_C16 - 1 - a];
            p[2] = (uint16_t)axes[b][0];
            p[3] = (uint16_t)axes[b][1];
        }
    }
    for (a = 0; a < 4096; a++) {
        uint16_t *p = row(r);
        int16_t s;
        int16_t c;
        p[0] = (uint16_t)rq15();
        p[1] = (uint16_t)rq15();
        rsc(&s, &c);
        p[2] = (uint16_t)s;
        p[3] = (uint16_t)c;
    }
}

static void gen_inv_clarke(rows_t *r) { gen_pairs(r, 4096); }

static void gen_svpwm(rows_t *r)
{
    const qfoc_svpwm_cfg_t *ref = &qfoc_params_reference.svpwm;
    int k;
    for (k = 0; k < 6144; k++) {
        uint16_t *p = row(r);
        const uint32_t cs = rnd() % 10u;
        double ang;
        double mag;
        int16_t vdc;
        if (cs < 6u) {
            p[0] = ref->period;
            p[1] = ref->dt_comp;
            p[2] = (uint16_t)ref->i_deadband;
            p[3] = (uint16_t)ref->vdc_min;
        } else if (cs < 9u) {
            const int32_t per = rr(100, 32767);
            p[0] = (uint16_t)per;
            p[1] = (uint16_t)rr(0, per / 4);
            p[2] = (uint16_t)rr(0, 3000);
            p[3] = (uint16_t)rr(1, 32767);
        } else {
            p[0] = (uint16_t)rnd();
            p[1] = (uint16_t)rnd();
            p[2] = (uint16_t)rq15();
            p[3] = (uint16_t)rq15();
        }
        if (chance(20)) {
            vdc = rq15();
        } else {
            vdc = (int16_t)rr(6000, 28000);
        }
        if (chance(30)) {
            /* a sector boundary, or one count beside it */
            ang = (double)rr(0, 5) * SIM_PI / 3.0 + (double)rr(-1, 1) * 1e-4;
        } else {
            ang = (double)(rnd() % 100000u) * 2.0 * SIM_PI / 100000.0;
        }
        mag = (double)(rnd() % 1300u) / 1000.0 * (double)(vdc > 0 ? vdc : 20000) / sqrt(3.0);
        if (chance(10)) {
            p[4] = (uint16_t)rq15();
            p[5] = (uint16_t)rq15();
        } else {
            p[4] = (uint16_t)clamp16(mag * cos(ang));
            p[5] = (uint16_t)clamp16(mag * sin(ang));
        }
        p[6] = (uint16_t)vdc;
        if (chance(30)) {
            const int32_t db = ref->i_deadband;
            p[7] = (uint16_t)(int16_t)rr(-db - 2, db + 2);
            p[8] = (uint16_t)(int16_t)rr(-db - 2, db + 2);
            p[9] = (uint16_t)(int16_t)rr(-db - 2, db + 2);
        } else {
            p[7] = (uint16_t)rq15();
            p[8] = (uint16_t)rq15();
            p[9] = (uint16_t)rq15();
        }
    }
}

static void gen_ramp(rows_t *r)
{
    static const int16_t st[] = { -32768, -1, 0, 1, 10, 32767 };
    int a;
    int b;
    int s;
    for (a = 0; a < N_C16; a += 2) {
        for (b = 0; b < N_C16; b += 2) {
            for (s = 0; s < (int)(sizeof st / sizeof st[0]); s++) {
                uint16_t *p = row(r);
                p[0] = (uint16_t)C16[a];
                p[1] = (uint16_t)C16[b];
                p[2] = (uint16_t)st[s];
            }
        }
    }
    for (a = 0; a < 4096; a++) {
        uint16_t *p = row(r);
        p[0] = (uint16_t)rq15();
        p[1] = (uint16_t)rq15();
        p[2] = (uint16_t)(chance(70) ? rr(0, 2000) : rq15());
    }
}

static void gen_fault_level(rows_t *r) { gen_pairs(r, 2048); }

static void gen_debounce(rows_t *r)
{
    static const uint16_t ns[] = { 0u, 1u, 2u, 3u, 5u, 10u, 100u, 65535u };
    int k = 0;
    while (k < 4096) {
        const uint16_t n = chance(90) ? ns[rnd() % 8u] : (uint16_t)rnd();
        const int len = rr(10, 120);
        int j;
        bool cond = false;
        row(r)[0] = TT_OP_RESET;
        k++;
        for (j = 0; j < len; j++) {
            uint16_t *p = row(r);
            if (chance(15)) {
                cond = !cond;
            }
            p[0] = TT_OP_STEP;
            p[1] = cond ? (uint16_t)(1u + (rnd() % 3u)) : 0u;
            p[2] = n;
            k++;
        }
    }
}

static void gen_phase_mon(rows_t *r)
{
    int k = 0;
    while (k < 4096) {
        const int len = rr(20, 200);
        const double amp = (double)rr(0, 32767);
        const int lost = (int)(rnd() % 5u);   /* 0..2: this phase reads zero; else none */
        double th = 0.0;
        const double dth = (double)rr(1, 3000) * 1e-4;
        int j;
        uint16_t *p = row(r);
        const int one = chance(50);   /* the drive's use: one phase per period, alpha3 */
        p[0] = TT_OP_INIT;
        p[1] = (uint16_t)(chance(90) ? rr(1, 32767) : rq15());
        p[2] = (uint16_t)one;
        k++;
        for (j = 0; j < len; j++) {
            p = row(r);
            k++;
            if (chance(10)) {
                p[0] = TT_OP_AUX;
                p[1] = (uint16_t)(chance(80) ? rr(0, 16384) : rq15());
                p[2] = (uint16_t)(chance(80) ? rr(0, 32767) : rq15());
            } else if (chance(2)) {
                p[0] = TT_OP_RESET;
            } else {
                int ph;
                p[0] = one ? TT_OP_AUX2 : TT_OP_STEP;
                p[4] = (uint16_t)(chance(95) ? (j % 3) : rr(0, 255));
                for (ph = 0; ph < 3; ph++) {
                    double v = amp * cos(th - (double)ph * 2.0 * SIM_PI / 3.0);
                    if (ph == lost) {
                        v = 0.0;
                    }
                    p[1 + ph] = (uint16_t)(chance(5) ? rq15() : clamp16(v));
                }
                th += dth;
            }
        }
    }
}

static void gen_lpf(rows_t *r)
{
    int k = 0;
    while (k < 4096) {
        const int len = rr(20, 150);
        int j;
        int32_t x = rq15();
        uint16_t *p = row(r);
        p[0] = TT_OP_INIT;
        p[1] = (uint16_t)(chance(85) ? rr(1, 32767) : rq15());
        k++;
        for (j = 0; j < len; j++) {
            p = row(r);
            k++;
            if (chance(3)) {
                p[0] = TT_OP_RESET;
                p[1] = (uint16_t)rq15();
            } else {
                if (chance(10)) {
                    x = rq15();
                }
                p[0] = TT_OP_STEP;
                p[1] = (uint16_t)(int16_t)x;
            }
        }
    }
}

static void gen_leaky(rows_t *r)
{
    int k = 0;
    while (k < 4096) {
        const int len = rr(20, 150);
        int j;
        uint16_t *p = row(r);
        p[0] = TT_OP_INIT;
        p[1] = (uint16_t)(chance(85) ? rr(0, 32767) : rq15());
        p[2] = (uint16_t)(chance(90) ? rr(0, 15) : rr(16, 255));
        p[3] = (uint16_t)(chance(85) ? rr(0, 3000) : rq15());
        k++;
        for (j = 0; j < len; j++) {
            p = row(r);
            k++;
            if (chance(3)) {
                p[0] = TT_OP_RESET;
                p[1] = (uint16_t)rq15();
            } else {
                p[0] = TT_OP_STEP;
                p[1] = (uint16_t)rq15();
            }
        }
    }
}

/* PI parameters: one of the reference table's four, random valid-looking ones, or
   any words */
static void pi_params(uint16_t *p)
{
    const qfoc_pi_params_t *t[4] = { &qfoc_params_reference.pi_id, &qfoc_params_reference.pi_iq,
                                     &qfoc_params_reference.pi_speed, &qfoc_params_reference.pi_fw };
    const uint32_t s = rnd() % 10u;
    if (s < 4u) {
        const qfoc_pi_params_t *q = t[rnd() % 4u];
        p[0] = (uint16_t)q->kp;
        p[1] = q->kp_shift;
        p[2] = (uint16_t)q->ki;
        p[3] = q->ki_shift;
        p[4] = (uint16_t)q->out_min;
        p[5] = (uint16_t)q->out_max;
    } else if (s < 9u) {
        const int32_t lo = rr(-32767, 32767);
        const int32_t hi = rr(lo, 32767);
        p[0] = (uint16_t)rr(0, 32767);
        p[1] = (uint16_t)(chance(80) ? rr(0, 2) : rr(0, 15));
        p[2] = (uint16_t)(chance(80) ? rr(0, 3000) : rr(0, 32767));
        p[3] = (uint16_t)(chance(80) ? rr(0, 2) : rr(0, 15));
        p[4] = (uint16_t)(int16_t)lo;
        p[5] = (uint16_t)(int16_t)hi;
    } else {
        int j;
        for (j = 0; j < 6; j++) {
            p[j] = (uint16_t)rq15();
        }
        p[1] = (uint16_t)rr(0, 20);
        p[3] = (uint16_t)rr(0, 20);
    }
}

static void gen_pi(rows_t *r)
{
    int k = 0;
    while (k < 6144) {
        const int len = rr(20, 200);
        int j;
        int32_t e = 0;
        uint16_t *p = row(r);
        p[0] = TT_OP_INIT;
        pi_params(&p[1]);
        k++;
        for (j = 0; j < len; j++) {
            p = row(r);
            k++;
            if (chance(3)) {
                p[0] = TT_OP_RESET;
                p[1] = (uint16_t)rq15();
            } else {
                if (chance(20)) {
                    e = rq15();
                } else {
                    e = e / 2 + rr(-200, 200);
                }
                p[0] = TT_OP_STEP;
                p[1] = (uint16_t)(int16_t)e;
            }
        }
    }
}

static void gen_fw(rows_t *r)
{
    int k = 0;
    while (k < 4096) {
        const int len = rr(50, 300);
        int j;
        int32_t lvl;
        int32_t u;
        uint16_t *p = row(r);
        p[0] = TT_OP_INIT;
        if (chance(50)) {
            const qfoc_pi_params_t *q = &qfoc_params_reference.pi_fw;
            p[1] = (uint16_t)q->kp;
            p[2] = q->kp_shift;
            p[3] = (uint16_t)q->ki;
            p[4] = q->ki_shift;
            p[5] = (uint16_t)q->out_min;
            p[6] = (uint16_t)q->out_max;
            p[7] = (uint16_t)qfoc_params_reference.drive.fw_level;
            p[8] = (uint16_t)qfoc_params_reference.drive.fw_alpha;
        } else {
            pi_params(&p[1]);
            if (chance(70)) {
                p[5] = (uint16_t)(int16_t)rr(-32767, 0);
                p[6] = 0u;
            }
            p[7] = (uint16_t)(chance(90) ? rr(1, 32767) : rq15());
            p[8] = (uint16_t)(chance(90) ? rr(1, 32767) : rq15());
        }
        lvl = (int16_t)p[7];
        u = lvl;
        k++;
        for (j = 0; j < len; j++) {
            p = row(r);
            k++;
            if (chance(2)) {
                p[0] = TT_OP_RESET;
            } else {
                u += rr(-800, 800);
                if (u > 32767) {
                    u = 32767;
                }
                if (u < 0) {
                    u = 0;
                }
                p[0] = TT_OP_STEP;
                p[1] = (uint16_t)(chance(5) ? rq15() : (int16_t)u);
                p[2] = chance(90) ? 1u : 0u;
            }
        }
    }
}

static void gen_flux(rows_t *r)
{
    int k = 0;
    while (k < 6144) {
        const int len = rr(50, 400);
        const double w = (double)rr(-16000, 16000) / 32768.0 * 2.0 * SIM_PI * 500.0 / 8000.0;
        const double vamp = (double)rr(0, 16000);
        const double iamp = (double)rr(0, 16000);
        const double phi = (double)rr(-157, 157) / 100.0;
        double th = 0.0;
        int j;
        uint16_t *p = row(r);
        p[0] = TT_OP_INIT;
        if (chance(40)) {
            const qfoc_flux_params_t *q = &qfoc_params_reference.flux;
            p[1] = (uint16_t)q->gain;
            p[2] = q->gain_shift;
            p[3] = (uint16_t)q->r;
            p[4] = (uint16_t)q->l;
            p[5] = (uint16_t)q->kg;
        } else {
            p[1] = (uint16_t)(chance(90) ? rr(0, 32767) : rq15());
            p[2] = (uint16_t)(chance(90) ? rr(0, 15) : rr(16, 40));
            p[3] = (uint16_t)(chance(90) ? rr(0, 5000) : rq15());
            p[4] = (uint16_t)(chance(90) ? rr(0, 32767) : rq15());
            p[5] = (uint16_t)(chance(90) ? rr(0, 3000) : rq15());
        }
        k++;
        for (j = 0; j < len; j++) {
            p = row(r);
            k++;
            if (chance(2)) {
                p[0] = TT_OP_RESET;
                p[1] = (uint16_t)rq15();
                p[2] = (uint16_t)rq15();
                p[3] = (uint16_t)rq15();
                p[4] = (uint16_t)rq15();
            } else if (chance(5)) {
                p[0] = TT_OP_AUX;
                p[1] = (uint16_t)rq15();
            } else {
                p[0] = TT_OP_STEP;
                if (chance(5)) {
                    p[1] = (uint16_t)rq15();
                    p[2] = (uint16_t)rq15();
                    p[3] = (uint16_t)rq15();
                    p[4] = (uint16_t)rq15();
                } else {
                    p[1] = (uint16_t)clamp16(vamp * cos(th));
                    p[2] = (uint16_t)clamp16(vamp * sin(th));
                    p[3] = (uint16_t)clamp16(iamp * cos(th - phi) + (double)rr(-20, 20));
                    p[4] = (uint16_t)clamp16(iamp * sin(th - phi) + (double)rr(-20, 20));
                }
                th += w;
            }
        }
    }
}

static void gen_pll(rows_t *r)
{
    int k = 0;
    while (k < 6144) {
        const int len = rr(50, 400);
        const double w = (double)rr(-20000, 20000) / 32768.0 * 2.0 * SIM_PI * 500.0 / 8000.0;
        const double amp = (double)(chance(10) ? rr(0, 200) : rr(200, 32767));
        const bool emf = chance(40);
        double th = (double)rr(0, 628) / 100.0;
        int j;
        uint16_t *p = row(r);
        p[0] = TT_OP_INIT;
        if (chance(40)) {
            const qfoc_pll_params_t *q = &qfoc_params_reference.pll;
            p[1] = (uint16_t)q->pi.kp;
            p[2] = q->pi.kp_shift;
            p[3] = (uint16_t)q->pi.ki;
            p[4] = q->pi.ki_shift;
            p[5] = (uint16_t)q->pi.out_min;
            p[6] = (uint16_t)q->pi.out_max;
            p[7] = (uint16_t)q->err_clamp;
            p[8] = (uint16_t)q->mag_min;
            p[9] = q->k_theta;
            p[10] = (uint16_t)q->speed_alpha;
        } else {
            pi_params(&p[1]);
            p[7] = (uint16_t)(chance(90) ? rr(1, 32767) : rq15());
            p[8] = (uint16_t)(chance(90) ? rr(1, 5000) : rq15());
            p[9] = (uint16_t)(chance(90) ? rr(1, 32767) : (int32_t)(rnd() & 0xFFFFu));
            p[10] = (uint16_t)(chance(90) ? rr(1, 32767) : rq15());
        }
        k++;
        for (j = 0; j < len; j++) {
            p = row(r);
            k++;
            if (chance(2)) {
                p[0] = TT_OP_RESET;
                p[1] = (uint16_t)rnd();
                p[2] = (uint16_t)rq15();
            } else {
                p[0] = emf ? TT_OP_AUX2 : TT_OP_STEP;
                if (chance(3)) {
                    p[0] = (p[0] == TT_OP_STEP) ? TT_OP_AUX2 : TT_OP_STEP;
                }
                if (chance(5)) {
                    p[1] = (uint16_t)rq15();
                    p[2] = (uint16_t)rq15();
                } else {
                    p[1] = (uint16_t)clamp16(amp * cos(th) + (double)rr(-30, 30));
                    p[2] = (uint16_t)clamp16(amp * sin(th) + (double)rr(-30, 30));
                }
                th += w;
            }
        }
    }
}

/* EMF and disturbance observers: shared input streams */
static void gen_emf_common(rows_t *r, bool dob)
{
    int k = 0;
    while (k < 4096) {
        const int len = rr(50, 300);
        const double w = (double)rr(-16000, 16000) / 32768.0 * 2.0 * SIM_PI * 500.0 / 8000.0;
        const double vamp = (double)rr(0, 16000);
        const double iamp = (double)rr(0, 16000);
        double th = 0.0;
        int j;
        uint16_t *p = row(r);
        p[0] = TT_OP_INIT;
        if (!dob) {
            p[1] = (uint16_t)(chance(90) ? rr(0, 3000) : rq15());
            p[2] = (uint16_t)(chance(90) ? rr(0, 32767) : rq15());
            p[3] = (uint16_t)(chance(90) ? rr(1, 32767) : rq15());
            p[4] = (uint16_t)(chance(90) ? rr(1, 32767) : (int32_t)(rnd() & 0xFFFFu));
        } else {
            p[1] = (uint16_t)(chance(90) ? rr(1, 32767) : rq15());
            p[2] = (uint16_t)(chance(90) ? rr(0, 15) : rr(16, 30));
            p[3] = (uint16_t)(chance(90) ? rr(0, 3000) : rq15());
            p[4] = (uint16_t)(chance(90) ? rr(1, 8192) : rq15());
            p[5] = (uint16_t)(chance(90) ? rr(1, 32767) : (int32_t)(rnd() & 0xFFFFu));
        }
        k++;
        for (j = 0; j < len; j++) {
            p = row(r);
            k++;
            if (chance(2)) {
                p[0] = TT_OP_RESET;
                p[1] = (uint16_t)rq15();
                p[2] = (uint16_t)rq15();
            } else if (chance(5)) {
                p[0] = TT_OP_AUX;
                p[1] = (uint16_t)rq15();
            } else {
                p[0] = TT_OP_STEP;
                if (chance(5)) {
                    p[1] = (uint16_t)rq15();
                    p[2] = (uint16_t)rq15();
                    p[3] = (uint16_t)rq15();
                    p[4] = (uint16_t)rq15();
                } else {
                    p[1] = (uint16_t)clamp16(vamp * cos(th));
                    p[2] = (uint16_t)clamp16(vamp * sin(th));
                    p[3] = (uint16_t)clamp16(iamp * cos(th - 0.3) + (double)rr(-20, 20));
                    p[4] = (uint16_t)clamp16(iamp * sin(th - 0.3) + (double)rr(-20, 20));
                }
                th += w;
            }
        }
    }
}

static void gen_emf(rows_t *r) { gen_emf_common(r, false); }
static void gen_dob(rows_t *r) { gen_emf_common(r, true); }

static void gen_mech(rows_t *r)
{
    int k = 0;
    while (k < 4096) {
        const int len = rr(50, 300);
        const int32_t step = chance(80) ? rr(-3000, 3000) : rr(-32768, 32767);
        uint32_t th = rnd() & 0xFFFFu;
        int j;
        uint16_t *p = row(r);
        p[0] = TT_OP_INIT;
        p[1] = (uint16_t)(chance(90) ? rr(1, 16) : rr(0, 255));
        p[2] = (uint16_t)th;
        k++;
        for (j = 0; j < len; j++) {
            p = row(r);
            k++;
            p[0] = TT_OP_STEP;
            th = (th + (uint32_t)(chance(3) ? rr(-32768, 32767) : step)) & 0xFFFFu;
            p[1] = (uint16_t)th;
        }
    }
}

static void gen_trqcomp(rows_t *r)
{
    const qfoc_drive_cfg_t *dc = &qfoc_params_reference.drive;
    int k = 0;
    while (k < 6144) {
        const int len = rr(100, 600);
        const int32_t dth = rr(-2000, 2000);
        const double amp = (double)rr(0, 3000);
        int32_t speed;
        uint32_t th = rnd() & 0xFFFFu;
        int j;
        uint16_t *p = row(r);
        p[0] = TT_OP_INIT;
        if (chance(50)) {
            p[1] = (uint16_t)dc->tc_gain;
            p[2] = (uint16_t)dc->tc_amp_max;
            p[3] = (uint16_t)dc->tc_speed_min;
            p[4] = (uint16_t)dc->tc_speed_max;
            p[5] = dc->pole_pairs;
        } else {
            const int32_t smin = chance(80) ? rr(0, 4000) : rr(0, 32767);
            p[1] = (uint16_t)(chance(90) ? rr(0, 4000) : rq15());
            p[2] = (uint16_t)(chance(90) ? rr(0, 32767) : rq15());
            p[3] = (uint16_t)(int16_t)(chance(90) ? smin : rq15());
            p[4] = (uint16_t)(int16_t)(chance(90) ? rr(smin, 32767) : rq15());
            p[5] = (uint16_t)(chance(90) ? rr(1, 16) : rr(0, 40));
        }
        speed = chance(80) ? rr(2000, 19000) * (chance(80) ? 1 : -1) : rq15();
        k++;
        for (j = 0; j < len; j++) {
            p = row(r);
            k++;
            th = (th + (uint32_t)dth) & 0xFFFFu;
            if (chance(1)) {
                p[0] = TT_OP_RESET;
            } else if (chance(10)) {
                p[0] = TT_OP_AUX;
                p[1] = (uint16_t)th;
                p[2] = (uint16_t)(int16_t)speed;
            } else if (chance(3)) {
                p[0] = TT_OP_AUX2;
            } else {
                p[0] = TT_OP_STEP;
                p[1] = (uint16_t)th;
                p[2] = (uint16_t)(chance(5) ? rq15()
                                            : clamp16(amp * sin((double)th * 2.0 * SIM_PI / 65536.0 + 0.7)));
                p[3] = (uint16_t)(int16_t)speed;
            }
            if (chance(2)) {
                speed = rq15();
            }
        }
    }
}

/* the reference table's link configuration, or a random one */
static void link_cfg(uint16_t *p)
{
    const qfoc_drive_cfg_t *dc = &qfoc_params_reference.drive;
    if (chance(60)) {
        p[0] = dc->lin_id_cmd;
        p[1] = dc->lin_id_status;
        p[2] = dc->rpm_max;
        p[3] = dc->link_timeout_ms;
        p[4] = dc->can_id_a;
        p[5] = dc->can_id_b;
    } else {
        p[0] = (uint16_t)(chance(90) ? rr(0, 0x3B) : rr(0, 255));
        p[1] = (uint16_t)(chance(90) ? rr(0, 0x3B) : rr(0, 255));
        p[2] = (uint16_t)(chance(90) ? rr(1, 12000) : rr(0, 65535));
        p[3] = (uint16_t)(chance(90) ? rr(1, 100) : rr(0, 65535));
        p[4] = (uint16_t)(chance(90) ? rr(0, 0x7FF) : rr(0, 65535));
        p[5] = (uint16_t)(chance(90) ? rr(0, 0x7FF) : rr(0, 65535));
    }
}

/* a command frame for configuration p (words as link_cfg): well-formed, or with one
   defect, or random bytes; returns its length */
static int cmd_frame(const uint16_t *cfg, uint8_t f[TT_TICK_RX_MAX])
{
    const uint32_t s = rnd() % 12u;
    const uint16_t rpm_max = cfg[2];
    uint16_t rpm = (uint16_t)(chance(90) ? rr(0, rpm_max) : rr(0, 65535));
    int len = 7;
    int k;
    memset(f, 0, TT_TICK_RX_MAX);
    f[0] = 0x55u;
    f[1] = dsim_lin_pid((uint8_t)cfg[0]);
    f[2] = (uint8_t)rr(0, 3);
    f[3] = (uint8_t)(rpm & 0xFFu);
    f[4] = (uint8_t)(rpm >> 8);
    f[5] = 0u;
    f[6] = dsim_lin_checksum(&f[1], 5);
    if (s == 0u) {
        f[rr(0, 6)] ^= (uint8_t)(1u << (rnd() % 8u));            /* one bit flipped */
    } else if (s == 1u) {
        len = chance(50) ? rr(0, 12) : rr(0, 255);               /* a wrong length */
    } else if (s == 2u) {
        f[2] = (uint8_t)(f[2] | (uint8_t)(4u << (rnd() % 6u)));  /* a reserved bit */
        f[6] = dsim_lin_checksum(&f[1], 5);
    } else if (s == 3u) {
        f[5] = (uint8_t)rr(1, 255);                               /* reserved byte */
        f[6] = dsim_lin_checksum(&f[1], 5);
    } else if (s == 4u) {
        for (k = 0; k < TT_TICK_RX_MAX; k++) {                    /* random bytes */
            f[k] = (uint8_t)rnd();
        }
        len = rr(0, 12);
    } else if (s == 5u) {
        f[1] = dsim_lin_pid((uint8_t)rr(0, 63));                  /* another identifier */
        f[6] = dsim_lin_checksum(&f[1], 5);
    } else {
        /* well-formed */
    }
    return len;
}

static void gen_lin_checksum(rows_t *r)
{
    int k;
    for (k = 0; k < 4096; k++) {
        uint16_t *p = row(r);
        uint8_t b[12];
        int j;
        p[0] = (uint16_t)(rnd() & 0xFFu);
        p[1] = (uint16_t)rr(0, 12);
        for (j = 0; j < 12; j++) {
            b[j] = (uint8_t)(chance(30) ? 0xFFu : (rnd() & 0xFFu));
        }
        put_bytes(&p[2], b, 12);
    }
}

static void gen_lin_decode(rows_t *r)
{
    int k;
    for (k = 0; k < 4096; k++) {
        uint16_t *p = row(r);
        uint8_t f[TT_TICK_RX_MAX];
        link_cfg(p);
        p[6] = (uint16_t)cmd_frame(p, f);
        put_bytes(&p[7], f, TT_TICK_RX_MAX);
    }
}

static void status_words(uint16_t *p)
{
    if (chance(70)) {
        p[0] = (uint16_t)rr(0, 3);
        p[1] = (uint16_t)rr(0, 6);
        p[2] = (uint16_t)(rnd() & 0x3FFu);
        p[3] = (uint16_t)rr(0, 9000);
        p[4] = (uint16_t)rr(0, 5000);
        p[5] = (uint16_t)rr(0, 4000);
        p[6] = (uint16_t)(int16_t)rr(-400, 1500);
    } else {
        int j;
        for (j = 0; j < 7; j++) {
            p[j] = (uint16_t)rnd();
        }
        p[0] &= 0xFFu;
        p[1] &= 0xFFu;
    }
}

static void gen_lin_encode(rows_t *r)
{
    int k;
    for (k = 0; k < 2048; k++) {
        uint16_t *p = row(r);
        link_cfg(p);
        status_words(&p[6]);
    }
}

static void gen_link(rows_t *r)
{
    int k = 0;
    while (k < 6144) {
        const int len = rr(50, 400);
        uint16_t cfg[6];
        int j;
        uint16_t *p = row(r);
        p[0] = TT_OP_INIT;
        link_cfg(&p[1]);
        memcpy(cfg, &p[1], sizeof cfg);
        if (chance(50)) {
            cfg[3] = (uint16_t)rr(1, 30);   /* short timeout: the link is lost within the run */
            p[4] = cfg[3];
        }
        k++;
        for (j = 0; j < len; j++) {
            p = row(r);
            k++;
            if (chance(5)) {
                p[0] = TT_OP_AUX;
                status_words(&p[1]);
            } else {
                p[0] = TT_OP_STEP;
                if (chance(60)) {
                    p[1] = 0u;   /* nothing received this millisecond */
                } else {
                    uint8_t f[TT_TICK_RX_MAX];
                    p[1] = (uint16_t)cmd_frame(cfg, f);
                    put_bytes(&p[2], f, TT_TICK_RX_MAX);
                }
            }
        }
    }
}

static void gen_crc32_byte(rows_t *r)
{
    static const uint32_t c[] = { 0u, 1u, 0xFFFFFFFFu, 0x80000000u, 0x7FFFFFFFu, 0xEDB88320u };
    int a;
    int b;
    for (a = 0; a < (int)(sizeof c / sizeof c[0]); a++) {
        for (b = 0; b < 256; b += 17) {
            uint16_t *p = row(r);
            put32(p, c[a]);
            p[2] = (uint16_t)b;
        }
    }
    for (a = 0; a < 2048; a++) {
        uint16_t *p = row(r);
        put32(p, rnd());
        p[2] = (uint16_t)(rnd() & 0xFFu);
    }
}

/* table mutations: none, then every byte with a random mask (resealed or not) */
static void gen_table_mutants(rows_t *r, int extra)
{
    const int size = (int)sizeof(qfoc_param_table_t);
    int k;
    uint16_t *p = row(r);
    p[0] = 0xFFFFu;
    p = row(r);
    p[0] = 0xFFFFu;
    p[2] = 1u;
    for (k = 0; k < size; k++) {
        p = row(r);
        p[0] = (uint16_t)k;
        p[1] = (uint16_t)rr(1, 255);
        p[2] = chance(70) ? 1u : 0u;
    }
    for (k = 0; k < extra; k++) {
        p = row(r);
        p[0] = (uint16_t)rr(0, size - 1);
        p[1] = (uint16_t)(1u << (rnd() % 8u));
        p[2] = chance(80) ? 1u : 0u;
    }
}

/* shunt: [period, t_settle, t_sample, hold_max, cmp u, v, w, s1, s2]: configurations the
   check accepts (periods of 8 and 16 kHz, the smallest and largest, the window at a
   quarter period) and refuses, compare values in every order, at 0, at the period and
   beyond it, close together (the edge shift), any samples. */
static void gen_shunt(rows_t *r)
{
    static const int32_t per[] = { 5000, 2500, 100, 32767, 1000 };
    int k;
    for (k = 0; k < 4096; k++) {
        uint16_t *p = row(r);
        int j;
        if (chance(10)) {
            for (j = 0; j < 4; j++) {
                p[j] = (uint16_t)rnd();
            }
        } else {
            const int32_t pp = chance(70) ? per[rr(0, 4)] : rr(100, 32767);
            const int32_t q = pp / 4;
            const int32_t settle = rr(0, q / 2);
            const int32_t sample = chance(5) ? (q - settle + 1) : rr(1, q - settle);
            p[0] = (uint16_t)pp;
            p[1] = (uint16_t)settle;
            p[2] = (uint16_t)sample;
            p[3] = (uint16_t)(chance(5) ? rr(0, 2000) : rr(1, 16));
        }
        for (j = 0; j < 3; j++) {
            const int32_t pp = (int32_t)p[0];
            if (chance(30)) {
                p[4 + j] = (uint16_t)(pp / 2 + rr(-40, 40));      /* low modulation */
            } else if (chance(10)) {
                p[4 + j] = (uint16_t)(chance(50) ? rr(0, 3) : pp + rr(-3, 3)); /* rails */
            } else {
                p[4 + j] = (uint16_t)rr(0, pp + 100);
            }
        }
        p[7] = (uint16_t)rq15();
        p[8] = (uint16_t)rq15();
    }
}

static void gen_params(rows_t *r) { gen_table_mutants(r, 768); }
static void gen_drive_init(rows_t *r) { gen_table_mutants(r, 256); }

static void gen_sm(rows_t *r)
{
    int k = 0;
    while (k < 6144) {
        const int len = rr(100, 600);
        int j;
        uint16_t bits = 0x21u;   /* bus_ok, table_ok */
        uint16_t *p = row(r);
        p[0] = TT_OP_INIT;
        if (chance(30)) {
            const qfoc_drive_cfg_t *dc = &qfoc_params_reference.drive;
            p[1] = dc->precharge_ms;
            p[2] = dc->align_ms;
            p[3] = dc->ol_timeout_ms;
            p[4] = dc->cl_hold_ms;
            p[5] = dc->clear_ms;
        } else {
            for (j = 1; j <= 5; j++) {
                p[j] = (uint16_t)(chance(90) ? rr(0, 40) : rr(0, 65535));
            }
        }
        k++;
        for (j = 0; j < len; j++) {
            p = row(r);
            k++;
            if (chance(2)) {
                p[0] = TT_OP_AUX;
                p[1] = (uint16_t)(chance(70) ? (1u << (rnd() % 10u)) : rnd());
            } else {
                p[0] = TT_OP_STEP;
                p[1] = chance(95) ? 0u : (uint16_t)(chance(70) ? (1u << (rnd() % 10u)) : rnd());
                if (chance(10)) {
                    bits = (uint16_t)(bits ^ (1u << (rnd() % 8u)));
                }
                p[2] = bits;
            }
        }
    }
}

/* ------------------------------------------------------------------ the closed loop */

typedef struct {
    bool on;
    rows_t fast;
    rows_t tick;
    uint32_t *fast_exp;
    uint32_t *tick_exp;
    uint32_t fast_cap;
    uint32_t tick_cap;
    uint32_t ppm;
    bool order_ok;
    long fw_periods;     /* periods with the field-weakening current below zero */
    long tc_ticks;       /* ticks with a torque-compensation coefficient not zero */
    long hs_periods;     /* periods with the high-speed inductances */
    long cl_ticks;       /* ticks in CLOSED_LOOP */
    uint16_t faults;     /* every fault bit seen */
    uint16_t faults_before_oc;
    bool oc_same_period; /* PWM off in the period of the over-current sample */
    uint8_t end_state;
    uint16_t end_first_fault;
    long frames_ok;
    bool shunt;          /* the single-shunt run: the periods are recorded at the measurement */
    qfoc_adc_t sh_codes; /* the single-shunt run: this period's codes and output so far */
    qfoc_pwm_t sh_pwm;
    long shifted;        /* the single-shunt run: periods with an edge shifted (PWM on) */
} rec_t;

static rec_t g_rec;

qfoc_pwm_t __real_qfoc_drive_fast_step(qfoc_drive_t *d, const qfoc_adc_t *adc);
qfoc_tick_out_t __real_qfoc_drive_tick(qfoc_drive_t *d, const qfoc_tick_in_t *in);
qfoc_pwm_t __wrap_qfoc_drive_fast_step(qfoc_drive_t *d, const qfoc_adc_t *adc);
qfoc_tick_out_t __wrap_qfoc_drive_tick(qfoc_drive_t *d, const qfoc_tick_in_t *in);
qfoc_adc_t __real_qfoc_drive_shunt_measure(qfoc_drive_shunt_t *sd, const qfoc_drive_t *d,
                                           const qfoc_adc_t *adc, qfoc_q15_t s1, qfoc_q15_t s2);
qfoc_pwm_t __real_qfoc_drive_shunt_output(const qfoc_drive_shunt_t *sd, qfoc_pwm_t out);
const qfoc_shunt_plan_t *__real_qfoc_drive_shunt_plan(qfoc_drive_shunt_t *sd, const qfoc_drive_t *d);
qfoc_adc_t __wrap_qfoc_drive_shunt_measure(qfoc_drive_shunt_t *sd, const qfoc_drive_t *d,
                                           const qfoc_adc_t *adc, qfoc_q15_t s1, qfoc_q15_t s2);
qfoc_pwm_t __wrap_qfoc_drive_shunt_output(const qfoc_drive_shunt_t *sd, qfoc_pwm_t out);
const qfoc_shunt_plan_t *__wrap_qfoc_drive_shunt_plan(qfoc_drive_shunt_t *sd, const qfoc_drive_t *d);

static uint32_t *grow(uint32_t *a, uint32_t *cap, uint32_t n)
{
    if (n >= *cap) {
        *cap = (*cap == 0u) ? 4096u : 2u * *cap;
        a = realloc(a, (size_t)*cap * sizeof(uint32_t));
        if (a == NULL) {
            fprintf(stderr, "tt_gen: out of memory\n");
            exit(2);
        }
    }
    return a;
}

qfoc_pwm_t __wrap_qfoc_drive_fast_step(qfoc_drive_t *d, const qfoc_adc_t *adc)
{
    uint16_t *p = NULL;
    qfoc_pwm_t out;
    if (g_rec.shunt) {
        return __real_qfoc_drive_fast_step(d, adc);   /* recorded at the measurement */
    }
    if (g_rec.on) {
        p = row(&g_rec.fast);
        p[0] = adc->iu;
        p[1] = adc->iv;
        p[2] = adc->vdc;
    }
    out = __real_qfoc_drive_fast_step(d, adc);
    if (g_rec.on) {
        const uint32_t k = g_rec.fast.n - 1u;
        g_rec.fast_exp = grow(g_rec.fast_exp, &g_rec.fast_cap, k);
        g_rec.fast_exp[k] = tt_drive_fast_digest(d, &out);
        if (out.enable && (d->s.fw.id_ref < 0)) {
            g_rec.fw_periods++;
        }
        if (out.enable && d->f.hs) {
            g_rec.hs_periods++;
        }
    }
    return out;
}

/* The single-shunt run: the measurement's inputs are the period's vector; its digest is
   taken at the plan, the last of the period's calls. */
qfoc_adc_t __wrap_qfoc_drive_shunt_measure(qfoc_drive_shunt_t *sd, const qfoc_drive_t *d,
                                           const qfoc_adc_t *adc, qfoc_q15_t s1, qfoc_q15_t s2)
{
    if (g_rec.on && g_rec.shunt) {
        uint16_t *p = row(&g_rec.fast);
        p[0] = adc->iu;
        p[1] = adc->iv;
        p[2] = adc->vdc;
        p[3] = (uint16_t)s1;
        p[4] = (uint16_t)s2;
    }
    g_rec.sh_codes = __real_qfoc_drive_shunt_measure(sd, d, adc, s1, s2);
    return g_rec.sh_codes;
}

qfoc_pwm_t __wrap_qfoc_drive_shunt_output(const qfoc_drive_shunt_t *sd, qfoc_pwm_t out)
{
    g_rec.sh_pwm = __real_qfoc_drive_shunt_output(sd, out);
    return g_rec.sh_pwm;
}

const qfoc_shunt_plan_t *__wrap_qfoc_drive_shunt_plan(qfoc_drive_shunt_t *sd, const qfoc_drive_t *d)
{
    const qfoc_shunt_plan_t *plan = __real_qfoc_drive_shunt_plan(sd, d);
    if (g_rec.on && g_rec.shunt) {
        const uint32_t k = g_rec.fast.n - 1u;
        g_rec.fast_exp = grow(g_rec.fast_exp, &g_rec.fast_cap, k);
        g_rec.fast_exp[k] = tt_drive_shunt_digest(d, sd, &g_rec.sh_codes, &g_rec.sh_pwm, plan);
        if (g_rec.sh_pwm.enable && plan->shifted) {
            g_rec.shifted++;
        }
    }
    return plan;
}

qfoc_tick_out_t __wrap_qfoc_drive_tick(qfoc_drive_t *d, const qfoc_tick_in_t *in)
{
    qfoc_tick_out_t out;
    if (g_rec.on) {
        uint16_t *p = row(&g_rec.tick);
        if (in->rx_len > TT_TICK_RX_MAX) {
            fprintf(stderr, "tt_gen: a received frame of %u bytes\n", (unsigned)in->rx_len);
            exit(2);
        }
        p[0] = (uint16_t)in->t_ipm;
        p[1] = (uint16_t)in->t_pcb;
        p[2] = in->rx_len;
        if (in->rx_len > 0u) {
            put_bytes(&p[3], in->rx, in->rx_len);
        }
        if (g_rec.fast.n != g_rec.tick.n * g_rec.ppm) {
            g_rec.order_ok = false;
        }
    }
    out = __real_qfoc_drive_tick(d, in);
    if (g_rec.on) {
        const uint32_t k = g_rec.tick.n - 1u;
        g_rec.tick_exp = grow(g_rec.tick_exp, &g_rec.tick_cap, k);
        g_rec.tick_exp[k] = tt_drive_tick_digest(d, &out);
        if ((d->s.sm.state == QFOC_STATE_RUN) && (d->s.sm.sub == QFOC_SUB_CLOSED_LOOP)) {
            g_rec.cl_ticks++;
            if ((d->s.tc.a[0] != 0) || (d->s.tc.b[0] != 0)) {
                g_rec.tc_ticks++;
            }
        }
        g_rec.faults = (uint16_t)(g_rec.faults | d->s.sm.faults);
    }
    return out;
}

#define RUN_S 4.8         /* s in all */
#define STEP2_MS 2900L    /* second speed command */
#define OC_MS 4500L       /* over-current pulse */
#define OC_CODES 2560     /* +50 A on the sensed phase-u current: 50 / 40 x 2048 codes */
#define OC_PERIODS 3

/* The plant of the recorded runs: the motor file, a bus of vdc, its dead time, 20 RK4 steps
   a period, 0.05 A rms current noise, 3 N m of load with a 1.5 N m once-per-turn pulse. */
static int plant_cfg(sim_cfg_t *cfg, const char *motor, double vdc, uint32_t seed)
{
    memset(cfg, 0, sizeof *cfg);
    if (sim_motor_load(motor, &cfg->motor) != 0) {
        return -1;
    }
    cfg->vdc_v = vdc;
    cfg->dead_time_s = cfg->motor.dead_time_s;
    cfg->substeps = 20;
    cfg->noise_i_rms_a = 0.05;
    cfg->seed = seed;
    cfg->load.t_mean = 3.0;
    cfg->load.t_1x = 1.5;
    cfg->load.knee_rpm = 30.0;
    return 0;
}

static int record_drive(const char *motor, double *rpm_oc)
{
    static dsim_t ds;
    sim_cfg_t cfg;
    long ms_end;
    int inj = 0;
    if (plant_cfg(&cfg, motor, 250.0, 7u) != 0) {
        return -1;
    }
    g_rec.fast.width = 3u;
    g_rec.tick.width = TT_TICK_WIDTH;
    g_rec.order_ok = true;
    g_rec.ppm = (uint32_t)((qfoc_params_reference.f_pwm_hz + 500u) / 1000u);
    g_rec.on = true;
    if (dsim_init(&ds, &cfg, &qfoc_params_reference) != QFOC_PARAMS_OK) {
        fprintf(stderr, "tt_gen: the reference table is refused\n");
        return -1;
    }
    if ((long)ds.periods_per_ms != (long)g_rec.ppm) {
        fprintf(stderr, "tt_gen: %d periods per tick in the simulation, %u in the replay\n",
                ds.periods_per_ms, (unsigned)g_rec.ppm);
        return -1;
    }
    ds.power_on = true;
    ds.target_rpm = 3000u;
    ms_end = (long)(RUN_S * 1000.0 + 0.5);
    while (ds.ms < ms_end) {
        const long ms = ds.ms;
        int k;
        if (ms == STEP2_MS) {
            ds.target_rpm = 5800u;
        }
        if ((ms == 1000L) || (ms == 3500L)) {
            ds.corrupt_next = true;
        }
        if (ms == OC_MS) {
            inj = OC_PERIODS;
            g_rec.faults_before_oc = g_rec.faults;
            *rpm_oc = dsim_rpm(&ds);
        }
        ds.t_ipm = (int16_t)(400 + ms / 10);
        ds.t_pcb = (int16_t)(350 + ms / 20);
        for (k = 0; k < ds.periods_per_ms; k++) {
            ds.adc_iu_add = (inj > 0) ? OC_CODES : 0;
            dsim_period(&ds);
            if (inj == OC_PERIODS) {
                /* the PWM must be off in the very period of the first sample above i_trip */
                g_rec.oc_same_period = !ds.pwm.enable && ds.drv.f.trip;
            }
            if (inj > 0) {
                inj--;
            }
        }
    }
    g_rec.on = false;
    g_rec.frames_ok = (long)ds.drv.s.link.n_ok;
    g_rec.end_state = ds.drv.s.sm.state;
    g_rec.end_first_fault = ds.drv.s.sm.first_fault;
    return 0;
}

/* The single-shunt run: the reference motor on its single-shunt table (reference_shunt),
   320 V, the plant's DC-link current sampled where the drive asked (ringing for the
   table's settle time less the dead time, at half the step; the table's sample time), the
   front end of latency 2 as sim/scenario.c rigs it; 3000 rpm, 5000 rpm from STEP2_MS, two
   command frames with a wrong checksum, then a current surge of 36 A along phase u at
   OC_MS (the over-current trip). */
#define SH_RPM2 5000u

static int record_drive_shunt(const char *motor, double *rpm_oc)
{
    static dsim_t ds;
    static qfoc_drive_shunt_t sd;
    const qfoc_param_table_t *p = &qfoc_params_reference_shunt;
    sim_cfg_t cfg;
    long ms_end;
    if (plant_cfg(&cfg, motor, 320.0, 11u) != 0) {
        return -1;
    }
    scn_shunt_plant(&cfg, p, &cfg.motor);
    g_rec.fast.width = 5u;
    g_rec.tick.width = TT_TICK_WIDTH;
    g_rec.order_ok = true;
    g_rec.ppm = (uint32_t)((p->f_pwm_hz + 500u) / 1000u);
    g_rec.shunt = true;
    if (dsim_init(&ds, &cfg, p) != QFOC_PARAMS_OK ||
        qfoc_drive_shunt_init(&sd, &ds.drv, 2u) != QFOC_SHUNT_OK) {
        fprintf(stderr, "tt_gen: the single-shunt table is refused\n");
        return -1;
    }
    ds.shunt = &sd;
    g_rec.on = true;
    ds.power_on = true;
    ds.target_rpm = 3000u;
    ms_end = (long)(RUN_S * 1000.0 + 0.5);
    while (ds.ms < ms_end) {
        const long ms = ds.ms;
        if (ms == STEP2_MS) {
            ds.target_rpm = SH_RPM2;
        }
        if ((ms == 1000L) || (ms == 3500L)) {
            ds.corrupt_next = true;
        }
        if (ms == OC_MS) {
            const double i_ab[2] = { 36.0, 0.0 };
            g_rec.faults_before_oc = g_rec.faults;
            *rpm_oc = dsim_rpm(&ds);
            sim_set_current_ab(&ds.plant, i_ab);
        }
        ds.t_ipm = (int16_t)(400 + ms / 10);
        ds.t_pcb = (int16_t)(350 + ms / 20);
        dsim_run(&ds, 1e-3);
    }
    g_rec.on = false;
    g_rec.shunt = false;
    g_rec.frames_ok = (long)ds.drv.s.link.n_ok;
    g_rec.end_state = ds.drv.s.sm.state;
    g_rec.end_first_fault = ds.drv.s.sm.first_fault;
    return 0;
}

/* ------------------------------------------------------------------ output */

typedef struct {
    const char *name;
    uint16_t width;
    uint32_t n_implicit;      /* width 0: number of vectors */
    void (*gen)(rows_t *r);
} gen_entry_t;

static const gen_entry_t GEN[] = {
    { "q15_sat", 2u, 0u, gen_q15_sat },
    { "q31_sat", 4u, 0u, gen_q31_sat },
    { "q15_add", 2u, 0u, gen_q15_pairs },
    { "q15_sub", 2u, 0u, gen_q15_pairs },
    { "q15_neg", 1u, 0u, gen_q15_unary },
    { "q15_abs", 1u, 0u, gen_q15_unary },
    { "q15_mul", 2u, 0u, gen_q15_pairs },
    { "q15_from_q30", 2u, 0u, gen_q15_from_q30 },
    { "q31_add", 4u, 0u, gen_q31_add },
    { "q31_mac", 4u, 0u, gen_q31_mac },
    { "q15_from_q31", 2u, 0u, gen_q15_from_q31 },
    { "q31_from_q15", 1u, 0u, gen_q15_unary },
    { "sin", 0u, 65536u, gen_none },
    { "sincos", 0u, 65536u, gen_none },
    { "atan2", 2u, 0u, gen_atan2 },
    { "isqrt32", 2u, 0u, gen_isqrt32 },
    { "vec_mag", 2u, 0u, gen_vec_mag },
    { "circle_limit", 3u, 0u, gen_circle_limit },
    { "clarke", 2u, 0u, gen_clarke },
    { "park", 4u, 0u, gen_park },
    { "inv_park", 4u, 0u, gen_park },
    { "inv_clarke", 2u, 0u, gen_inv_clarke },
    { "svpwm", 10u, 0u, gen_svpwm },
    { "ramp", 3u, 0u, gen_ramp },
    { "fault_level", 2u, 0u, gen_fault_level },
    { "debounce", 3u, 0u, gen_debounce },
    { "phase_mon", 5u, 0u, gen_phase_mon },
    { "lpf", 2u, 0u, gen_lpf },
    { "leaky", 4u, 0u, gen_leaky },
    { "pi", 7u, 0u, gen_pi },
    { "fw", 9u, 0u, gen_fw },
    { "flux", 6u, 0u, gen_flux },
    { "pll", 11u, 0u, gen_pll },
    { "emf", 5u, 0u, gen_emf },
    { "dob", 6u, 0u, gen_dob },
    { "mech", 3u, 0u, gen_mech },
    { "trqcomp", 6u, 0u, gen_trqcomp },
    { "lin_pid", 0u, 256u, gen_none },
    { "lin_checksum", 8u, 0u, gen_lin_checksum },
    { "lin_decode", 13u, 0u, gen_lin_decode },
    { "lin_encode", 13u, 0u, gen_lin_encode },
    { "link", 8u, 0u, gen_link },
    { "crc32_byte", 3u, 0u, gen_crc32_byte },
    { "params", 3u, 0u, gen_params },
    { "sm", 6u, 0u, gen_sm },
    { "drive_init", 3u, 0u, gen_drive_init },
    { "shunt", 9u, 0u, gen_shunt },
};
#define N_GEN ((int)(sizeof GEN / sizeof GEN[0]))

typedef struct {
    const char *name;
    rows_t rows;
    uint32_t n;
    uint32_t *exp;
    uint32_t distinct;   /* distinct digests: a replay that gave one output for all would
                            compare equal whatever the library did */
} group_t;

static int cmp_u32(const void *a, const void *b)
{
    const uint32_t x = *(const uint32_t *)a;
    const uint32_t y = *(const uint32_t *)b;
    return (x > y) - (x < y);
}

static uint32_t count_distinct(const uint32_t *v, uint32_t n)
{
    uint32_t *c = malloc((size_t)n * sizeof(uint32_t) + 1u);
    uint32_t d = 0u;
    uint32_t k;
    if (c == NULL) {
        fprintf(stderr, "tt_gen: out of memory\n");
        exit(2);
    }
    memcpy(c, v, (size_t)n * sizeof(uint32_t));
    qsort(c, n, sizeof(uint32_t), cmp_u32);
    for (k = 0u; k < n; k++) {
        if (k == 0u || c[k] != c[k - 1u]) {
            d++;
        }
    }
    free(c);
    return d;
}

#define MAX_GROUPS 64

static void write_u16s(FILE *f, const uint16_t *w, size_t n)
{
    size_t k;
    for (k = 0; k < n; k++) {
        fprintf(f, "0x%04X,%s", (unsigned)w[k], ((k % 16u) == 15u) ? "\n" : "");
    }
    fputs("\n", f);
}

static void write_u32s(FILE *f, const uint32_t *w, size_t n)
{
    size_t k;
    for (k = 0; k < n; k++) {
        fprintf(f, "0x%08lXu,%s", (unsigned long)w[k], ((k % 10u) == 9u) ? "\n" : "");
    }
    fputs("\n", f);
}

static int replay(const tt_suite_t *s, group_t *g, uint32_t **rec)
{
    tt_data_t data[2];
    tt_ctx_t ctx[2];
    int j;
    for (j = 0; j < (int)s->groups; j++) {
        data[j].name = g[j].name;
        data[j].n = g[j].n;
        data[j].width = g[j].rows.width;
        data[j].in = g[j].rows.w;
        data[j].exp = g[j].exp;
        memset(&ctx[j], 0, sizeof ctx[j]);
        ctx[j].data = &data[j];
        ctx[j].first_bad = TT_NONE;
        ctx[j].corrupt_exp = TT_NONE;
        ctx[j].corrupt_in = TT_NONE;
        ctx[j].record = (rec != NULL) ? rec[j] : NULL;
    }
    s->fn(ctx);
    for (j = 0; j < (int)s->groups; j++) {
        if (ctx[j].k != g[j].n) {
            fprintf(stderr, "tt_gen: %s: %u digests for %u vectors\n", g[j].name, (unsigned)ctx[j].k,
                    (unsigned)g[j].n);
            return -1;
        }
        if (ctx[j].n_bad != 0u) {
            fprintf(stderr, "tt_gen: %s: the replay differs from the closed loop at vector %u "
                            "(%u of %u)\n", g[j].name, (unsigned)ctx[j].first_bad,
                    (unsigned)ctx[j].n_bad, (unsigned)g[j].n);
            return -1;
        }
    }
    return 0;
}

int main(int argc, char **argv)
{
    static group_t G[MAX_GROUPS];
    const char *motor = "specs/motors/reference.toml";
    const char *out = "build/target_test";
    int ng = 0;
    int si;
    int a;
    uint64_t total = 0;
    size_t bytes = 0;
    double rpm_end = 0.0;
    bool verbose = false;
    char path[512];
    FILE *f;
    for (a = 1; a < argc; a++) {
        if (strcmp(argv[a], "--motor") == 0 && a + 1 < argc) {
            motor = argv[++a];
        } else if (strcmp(argv[a], "--out") == 0 && a + 1 < argc) {
            out = argv[++a];
        } else if (strcmp(argv[a], "--table") == 0) {
            verbose = true;
        } else {
            fprintf(stderr, "usage: tt_gen [--motor FILE.toml] [--out DIR] [--table]\n");
            return 2;
        }
    }
    /* every suite, in order */
    for (si = 0; si < (int)TT_N_SUITES; si++) {
        const tt_suite_t *s = &tt_suites[si];
        group_t *g = &G[ng];
        if (s->fn == NULL || s->groups < 1u || s->groups > 2u || s->name[0] == NULL ||
            (s->groups == 2u && s->name[1] == NULL)) {
            fprintf(stderr, "tt_gen: suite %d of %u is incomplete (tt_groups.c)\n", si,
                    (unsigned)TT_N_SUITES);
            return 2;
        }
        if (ng + (int)s->groups > MAX_GROUPS) {
            fprintf(stderr, "tt_gen: too many groups\n");
            return 2;
        }
        if (s->groups == 2u) {
            /* the drive: record the closed loop, then check the replay against it */
            const bool shunt = (strcmp(s->name[0], "drive_shunt_fast") == 0);
            memset(&g_rec, 0, sizeof g_rec);
            if ((shunt ? record_drive_shunt(motor, &rpm_end) : record_drive(motor, &rpm_end)) != 0) {
                return 1;
            }
            if (!g_rec.order_ok || g_rec.tick.n * g_rec.ppm > g_rec.fast.n ||
                g_rec.fast.n - g_rec.tick.n * g_rec.ppm >= g_rec.ppm) {
                fprintf(stderr, "tt_gen: the simulation's order of fast steps and ticks is not "
                                "the replay's\n");
                return 1;
            }
            g[0].name = s->name[0];
            g[0].rows = g_rec.fast;
            g[0].n = g_rec.fast.n;
            g[0].exp = g_rec.fast_exp;
            g[1].name = s->name[1];
            g[1].rows = g_rec.tick;
            g[1].n = g_rec.tick.n;
            g[1].exp = g_rec.tick_exp;
            if (replay(s, g, NULL) != 0) {
                return 1;
            }
            if (shunt) {
                printf("tt_gen: single-shunt closed loop %.1f s: %u periods, %u ticks; %ld ticks "
                       "in closed loop, %.0f rpm at %.1f s; edges shifted in %ld periods (PWM on), "
                       "torque compensation learning in %ld ticks; %ld frames accepted; current "
                       "surge at %.1f s: state %u, first fault 0x%04X\n", RUN_S,
                       (unsigned)g[0].n, (unsigned)g[1].n, g_rec.cl_ticks, rpm_end,
                       (double)OC_MS / 1000.0, g_rec.shifted, g_rec.tc_ticks, g_rec.frames_ok,
                       (double)OC_MS / 1000.0, (unsigned)g_rec.end_state,
                       (unsigned)g_rec.end_first_fault);
                if (g_rec.cl_ticks < 1000 || g_rec.shifted < 1000 || g_rec.tc_ticks < 1000 ||
                    g_rec.faults_before_oc != 0u || fabs(rpm_end - (double)SH_RPM2) > 300.0 ||
                    g_rec.end_state != QFOC_STATE_ERROR || g_rec.end_first_fault != QFOC_FAULT_OC) {
                    fprintf(stderr, "tt_gen: the single-shunt run does not exercise what it "
                                    "should (closed loop, shifted edges, torque compensation, "
                                    "5000 rpm without a fault, then an over-current trip)\n");
                    return 1;
                }
            } else {
                printf("tt_gen: closed loop %.1f s: %u periods, %u ticks; %ld ticks in closed loop, "
                       "%.0f rpm at %.1f s; field weakening in %ld periods, high-speed inductances "
                       "in %ld (PWM on), torque compensation learning in %ld ticks; %ld frames accepted; "
                       "over-current at %.1f s: PWM off in the same period %s, state %u, first "
                       "fault 0x%04X\n", RUN_S, (unsigned)g[0].n, (unsigned)g[1].n, g_rec.cl_ticks,
                       rpm_end, (double)OC_MS / 1000.0, g_rec.fw_periods, g_rec.hs_periods,
                       g_rec.tc_ticks, g_rec.frames_ok, (double)OC_MS / 1000.0,
                       g_rec.oc_same_period ? "yes" : "NO", (unsigned)g_rec.end_state,
                       (unsigned)g_rec.end_first_fault);
                if (g_rec.cl_ticks < 1000 || g_rec.fw_periods < 1000 || g_rec.tc_ticks < 1000 ||
                    g_rec.hs_periods < 1000 || g_rec.faults_before_oc != 0u ||
                    fabs(rpm_end - 5800.0) > 300.0 || !g_rec.oc_same_period ||
                    g_rec.end_state != QFOC_STATE_ERROR || g_rec.end_first_fault != QFOC_FAULT_OC) {
                    fprintf(stderr, "tt_gen: the closed-loop run does not exercise what it should "
                                    "(closed loop, field weakening, high-speed inductances, torque "
                                    "compensation, 5800 rpm without a fault, then an over-current "
                                    "trip)\n");
                    return 1;
                }
            }
        } else {
            const gen_entry_t *e = NULL;
            uint32_t *rec[2];
            uint32_t *again;
            int k;
            for (k = 0; k < N_GEN; k++) {
                if (strcmp(GEN[k].name, s->name[0]) == 0) {
                    e = &GEN[k];
                }
            }
            if (e == NULL) {
                fprintf(stderr, "tt_gen: no input generator for group %s\n", s->name[0]);
                return 2;
            }
            g[0].name = s->name[0];
            memset(&g[0].rows, 0, sizeof g[0].rows);
            g[0].rows.width = e->width;
            e->gen(&g[0].rows);
            g[0].n = (e->width == 0u) ? e->n_implicit : g[0].rows.n;
            g[0].exp = calloc(g[0].n, sizeof(uint32_t));
            again = calloc(g[0].n, sizeof(uint32_t));
            if (g[0].exp == NULL || again == NULL) {
                fprintf(stderr, "tt_gen: out of memory\n");
                return 2;
            }
            rec[0] = g[0].exp;
            if (replay(s, g, rec) != 0) {
                return 1;
            }
            rec[0] = again;
            if (replay(s, g, rec) != 0) {
                return 1;
            }
            if (memcmp(again, g[0].exp, g[0].n * sizeof(uint32_t)) != 0) {
                fprintf(stderr, "tt_gen: %s: two replays on the host differ\n", g[0].name);
                return 1;
            }
            free(again);
        }
        for (a = 0; a < (int)s->groups; a++) {
            g[a].distinct = count_distinct(g[a].exp, g[a].n);
            if (g[a].n > 1u && g[a].distinct < 2u) {
                fprintf(stderr, "tt_gen: %s: every vector gives the same output\n", g[a].name);
                return 1;
            }
        }
        ng += (int)s->groups;
    }
    /* vectors.h */
    snprintf(path, sizeof path, "%s/vectors.h", out);
    f = fopen(path, "w");
    if (f == NULL) {
        fprintf(stderr, "tt_gen: cannot write %s\n", path);
        return 2;
    }
    for (a = 0; a < ng; a++) {
        total += G[a].n;
    }
    fprintf(f, "/* Generated by tools/target_test/tt_gen.c (make target-test); do not edit. */\n"
               "#ifndef QFOC_TT_VECTORS_H\n#define QFOC_TT_VECTORS_H\n\n#include \"tt.h\"\n\n"
               "/** Groups and vectors. */\n#define TT_N_GROUPS (%du)\n#define TT_N_VECTORS (%luu)\n"
               "/** sizeof and offsetof(crc) of qfoc_param_table_t on the host (the params and "
               "drive_init groups mutate its bytes). */\n#define TT_HOST_PARAMS_SIZE (%luu)\n"
               "#define TT_HOST_PARAMS_CRC_OFFSET (%luu)\n"
               "/** Host that computed the expected digests. */\n#define TT_HOST_DESC \"%s gcc %s\"\n\n"
               "extern const tt_data_t tt_data[TT_N_GROUPS];\n\n#endif\n",
            ng, (unsigned long)total, (unsigned long)sizeof(qfoc_param_table_t),
            (unsigned long)offsetof(qfoc_param_table_t, crc),
#if defined(__x86_64__)
            "x86_64",
#elif defined(__aarch64__)
            "aarch64",
#else
            "host",
#endif
            __VERSION__);
    fclose(f);
    /* vectors.c */
    snprintf(path, sizeof path, "%s/vectors.c", out);
    f = fopen(path, "w");
    if (f == NULL) {
        fprintf(stderr, "tt_gen: cannot write %s\n", path);
        return 2;
    }
    fprintf(f, "/* Generated by tools/target_test/tt_gen.c (make target-test); do not edit.\n"
               "   Inputs and host digests of every group (tools/target_test/tt.h). */\n"
               "#include <stddef.h>\n#include \"vectors.h\"\n\n");
    for (a = 0; a < ng; a++) {
        const size_t nw = (size_t)G[a].rows.n * G[a].rows.width;
        if (nw > 0u) {
            fprintf(f, "static const uint16_t tt_in_%d[%lu] = { /* %s */\n", a, (unsigned long)nw,
                    G[a].name);
            write_u16s(f, G[a].rows.w, nw);
            fputs("};\n", f);
        }
        fprintf(f, "static const uint32_t tt_exp_%d[%lu] = { /* %s */\n", a, (unsigned long)G[a].n,
                G[a].name);
        write_u32s(f, G[a].exp, G[a].n);
        fputs("};\n", f);
        bytes += nw * 2u + (size_t)G[a].n * 4u;
    }
    fputs("\n/* name, vectors, words per vector, inputs, host digests (distinct digests) */\n"
          "const tt_data_t tt_data[TT_N_GROUPS] = {\n", f);
    for (a = 0; a < ng; a++) {
        if (G[a].rows.width > 0u) {
            fprintf(f, "    { \"%s\", %uu, %uu, tt_in_%d, tt_exp_%d },  /* %u */\n", G[a].name,
                    (unsigned)G[a].n, (unsigned)G[a].rows.width, a, a, (unsigned)G[a].distinct);
        } else {
            fprintf(f, "    { \"%s\", %uu, 0u, NULL, tt_exp_%d },  /* %u */\n", G[a].name,
                    (unsigned)G[a].n, a, (unsigned)G[a].distinct);
        }
    }
    fputs("};\n", f);
    fclose(f);
    if (verbose) {
        printf("%-14s %8s %6s %9s\n", "group", "vectors", "words", "distinct");
        for (a = 0; a < ng; a++) {
            printf("%-14s %8u %6u %9u\n", G[a].name, (unsigned)G[a].n, (unsigned)G[a].rows.width,
                   (unsigned)G[a].distinct);
        }
    }
    printf("tt_gen: %d groups, %lu vectors, %lu bytes of vectors -> %s/vectors.c\n", ng,
           (unsigned long)total, (unsigned long)bytes, out);
    return 0;
}
