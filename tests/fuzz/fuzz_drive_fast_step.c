/*
 * fuzz_drive_fast_step.c -- libFuzzer harness of the drive's fast step on arbitrary ADC
 * sequences in RUN (REQ-FUZZ-004).
 *
 * Start: a drive initialised from a committed table and driven into RUN by the master's
 * RUN command (tests/fuzz/snapshots.h, as tests/test_drive.c does it: precharge, offset
 * calibration, STOP, then the command frame with power-on and a target >= rpm_min): RUN in
 * ALIGN or OPEN_LOOP on each of the three tables, and on the plant model CLOSED_LOOP at
 * 2000 rpm, at 5800 rpm with field weakening, and STOPPING; the first byte picks one.  The
 * second byte chooses whether the 1 ms tick runs between the fast steps (every f_pwm / 1 kHz
 * periods, bench temperatures, the master's frame every 10 ms) or not at all.  Then ADC
 * samples until the input ends, in groups each led by a code byte: raw samples (three
 * 16-bit values, codes above 4095 included), samples that step from the previous ones by
 * signed 8-bit deltas (a random walk around the operating point), or the previous samples
 * repeated 1 .. 256 times.
 *
 * Guarantees asserted after every fast step (fz_fast() of tests/fuzz/fuzz.h; drive.h,
 * REQ-DRV-001 .. REQ-DRV-005): compare values <= the period; the PWM enabled only in RUN
 * and without the over-current latch; a phase current of the samples above i_trip
 * (specs/drive.acsl DriveOverCurrent) switches the PWM off in the same call and latches;
 * only d->f is written (d->s compared byte for byte); the drive invariant
 * qfoc_drive_is_valid(); the result is d->f.out; and after every tick those of fz_tick().
 *
 * Requirements: REQ-FUZZ-004.
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

/* fast steps an input may run */
#define MAX_STEPS 8000L

static uint16_t walk(uint16_t x, uint8_t delta)
{
    const int32_t v = (int32_t)x + (int32_t)(int8_t)delta;
    return (uint16_t)((v < 0) ? 0 : ((v > 65535) ? 65535 : v));
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static fz_rig_t r;
    fz_in_t in = { data, size };
    qfoc_adc_t a;
    bool ticks;
    long steps = 0;
    int phase = 0;

    fz_snap_pick(&r, fz_u8(&in), QFOC_STATE_RUN);
    ticks = (fz_u8(&in) & 1u) != 0u;
    a = r.adc;                 /* the walk starts from the last samples */
    a.iu = r.d.f.adc_iu;
    a.iv = r.d.f.adc_iv;
    while (in.n > 0u && steps < MAX_STEPS) {
        const uint8_t op = fz_u8(&in);
        int n = 1;
        int k;
        switch (op % 3u) {
        case 0u:
            a.iu = fz_u16(&in);
            a.iv = fz_u16(&in);
            a.vdc = fz_u16(&in);
            break;
        case 1u:
            a.iu = walk(a.iu, fz_u8(&in));
            a.iv = walk(a.iv, fz_u8(&in));
            a.vdc = walk(a.vdc, fz_u8(&in));
            break;
        default:
            n = 1 + (int)fz_u8(&in);
            break;
        }
        for (k = 0; k < n; k++) {
            (void)fz_fast(&r.d, &a);
            steps++;
            if (ticks) {
                phase++;
                if (phase >= r.ppm) {
                    phase = 0;
                    (void)fz_rig_tick(&r, (r.ms % 10u) == 0u);
                }
            }
        }
    }
    return 0;
}
