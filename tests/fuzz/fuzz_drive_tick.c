/*
 * fuzz_drive_tick.c -- libFuzzer harness of the drive's 1 ms tick on arbitrary inputs
 * (REQ-FUZZ-003).
 *
 * Start: a drive initialised from a committed table (tables/reference_params.c,
 * reference16k, traction350), in one of the states of tests/fuzz/snapshots.h (PRECHARGE,
 * calibration, STOP, ERROR, RUN in ALIGN, OPEN_LOOP, CLOSED_LOOP at 2000 and 5800 rpm,
 * STOPPING), picked by the first byte.  Then operations until the input ends, each a code
 * byte and its operands, interleaved as the input dictates:
 *   - a tick with any temperatures and any received bytes (length 0 .. 255);
 *   - a tick with a well-formed command frame (any power-on and fault-clear bits and
 *     target), or that frame with one byte changed, at any or at bench temperatures;
 *   - 1 .. 64 fast steps with any ADC samples or the bench samples;
 *   - 1 .. 256 ms of the bench (fast steps, a tick each, the master's frame every 10 ms)
 *     after changing the master's command, to let the state machine move.
 *
 * Guarantees asserted after every call (fz_tick() and fz_fast() of tests/fuzz/fuzz.h;
 * REQ-DRV-001 .. REQ-DRV-005, REQ-DRV-011, REQ-DRV-015): the drive invariant
 * qfoc_drive_is_valid(); the tick writes only d->s, the fast step only d->f; tx_len is 0
 * or 11 and a status frame (its PID, payload and checksum) answers exactly a frame the
 * decoding order accepts; the CAN frame alternates its identifiers and carries the
 * status payload; ERROR is left only to STOP, RUN is entered only from STOP in ALIGN; a
 * rejected frame leaves the drive exactly as a twin that ran the tick without it, but for
 * its cause's counter (byte-for-byte comparison); compare values <= period, PWM only in
 * RUN, an over-current switches off in the same fast step.
 *
 * Requirements: REQ-FUZZ-003.
 */
#include "fuzz.h"
#include "snapshots.h"

int LLVMFuzzerInitialize(int *argc, char ***argv);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc;
    (void)argv;
    fz_snapshots_init();
    return 0;
}

/* work units (a fast step 1, a tick 16) an input may spend */
#define BUDGET 20000L

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static fz_rig_t r;
    fz_in_t in = { data, size };
    long spent = 0;

    fz_snap_pick(&r, fz_u8(&in), 0xFFu);
    while (in.n > 0u && spent < BUDGET) {
        const uint8_t op = fz_u8(&in);
        switch (op % 6u) {
        case 0u: { /* raw tick */
            qfoc_tick_in_t t;
            uint8_t *buf;
            size_t len;
            t.t_ipm = fz_i16(&in);
            t.t_pcb = fz_i16(&in);
            len = fz_u8(&in);
            if (len > in.n) {
                len = in.n;
            }
            buf = (uint8_t *)malloc((len > 0u) ? len : 1u);
            if (buf == NULL) {
                return 0;
            }
            if (len > 0u) {
                memcpy(buf, in.p, len);
            }
            in.p += len;
            in.n -= len;
            t.rx = (len > 0u) ? buf : NULL;
            t.rx_len = (uint8_t)len;
            (void)fz_tick(&r.d, &t);
            r.ms++;
            free(buf);
            spent += 16;
            break;
        }
        case 1u:   /* tick with a well-formed frame */
        case 2u: { /* ... with one byte changed */
            qfoc_tick_in_t t;
            uint8_t f[7];
            const uint8_t bits = fz_u8(&in);
            uint16_t rpm = fz_u16(&in);
            if ((bits & 4u) == 0u) {
                rpm = (uint16_t)(rpm % ((uint32_t)r.d.s.link.cfg.rpm_max + 1u));
            }
            (void)fz_frame(f, r.d.s.link.cfg.id_cmd, (bits & 1u) != 0u, (bits & 2u) != 0u, rpm);
            if (op % 6u == 2u) {
                const uint8_t at = fz_u8(&in);
                f[at % 7u] = (uint8_t)(f[at % 7u] ^ fz_u8(&in));
            }
            if ((bits & 8u) != 0u) {
                t.t_ipm = fz_i16(&in);
                t.t_pcb = fz_i16(&in);
            } else {
                t.t_ipm = r.t_ipm;
                t.t_pcb = r.t_pcb;
            }
            t.rx = f;
            t.rx_len = 7u;
            (void)fz_tick(&r.d, &t);
            r.ms++;
            spent += 16;
            break;
        }
        case 3u: { /* fast steps, any samples */
            const int n = 1 + (fz_u8(&in) & 63);
            int k;
            for (k = 0; k < n; k++) {
                qfoc_adc_t a;
                a.iu = fz_u16(&in);
                a.iv = fz_u16(&in);
                a.vdc = fz_u16(&in);
                (void)fz_fast(&r.d, &a);
            }
            spent += n;
            break;
        }
        case 4u: { /* fast steps, bench samples */
            const int n = 1 + (fz_u8(&in) & 63);
            int k;
            for (k = 0; k < n; k++) {
                (void)fz_fast(&r.d, &r.adc);
            }
            spent += n;
            break;
        }
        default: { /* the bench for a while, with a new master command */
            const uint8_t bits = fz_u8(&in);
            const int n = 1 + (int)fz_u8(&in);
            r.power_on = (bits & 1u) != 0u;
            r.fault_clear = (bits & 2u) != 0u;
            if ((bits & 4u) != 0u) {
                r.rpm = (uint16_t)(r.d.p->drive.rpm_min +
                                   fz_u16(&in) % ((uint32_t)r.d.p->drive.rpm_max -
                                                  r.d.p->drive.rpm_min + 1u));
            }
            fz_rig_ms(&r, n);
            spent += (long)n * (r.ppm + 16);
            break;
        }
        }
    }
    return 0;
}
