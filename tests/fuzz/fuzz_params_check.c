/*
 * fuzz_params_check.c -- libFuzzer harness of the parameter-table check on arbitrary
 * tables (REQ-FUZZ-006).
 *
 * Input: a mode byte, then the table's bytes.  Mode 0: the bytes are the table itself
 * (sizeof(qfoc_param_table_t) bytes, zero-filled when the input is shorter), as a flash
 * full of anything.  Modes 1 .. 3: a committed table (tables/reference_params.c,
 * reference16k, traction350, picked by the mode) mutated by the input: (offset, value)
 * byte pairs written into it; with the mode's bit 2 set the identity is restored and the CRC
 * recomputed after the mutation (qfoc_params_crc), so the range checks see the mutated
 * fields behind a valid identity and CRC.  The table lives in an allocation of exactly
 * its size (AddressSanitizer sees any read beyond it).
 *
 * Guarantees asserted (include/qfoc/params.h, drive.h; REQ-PAR-001 .. REQ-PAR-005,
 * REQ-PAR-008, REQ-DRV-001): qfoc_params_check() returns OK, ERR_ID, ERR_CRC or ERR_RANGE,
 * the first failure in the order identity (magic, version), CRC (the stored CRC against
 * qfoc_params_crc), ranges (qfoc_params_is_valid); the check reads the table only (its
 * bytes are unchanged); the five steps of qfoc_params_scan_step() give the same status
 * and BUSY before; qfoc_params_load() leaves the RAM copy untouched on a failure and
 * copies the table exactly on OK; qfoc_drive_init() on the table returns the same status,
 * gives a valid drive, in PRECHARGE when the table passes and in ERROR with the PARAM fault
 * otherwise; and 20 ms of bench inputs (2 ms on a refused table) (fast steps and ticks, each with the guarantees of
 * fz_fast() and fz_tick()) keep the invariant, the PWM off outside RUN, and a refused
 * table's drive in ERROR.
 *
 * Requirements: REQ-FUZZ-006.
 */
#include "fuzz.h"
#include "reference_params.h"
#include "reference16k_params.h"
#include "traction350_params.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

#define TSIZE sizeof(qfoc_param_table_t)

static void bench(qfoc_drive_t *d, int32_t status)
{
    qfoc_adc_t a;
    qfoc_tick_in_t t;
    int32_t vdc = ((int32_t)d->p->vdc_uv + (int32_t)d->p->vdc_ov) / 16;
    int ppm = (int)((d->p->f_pwm_hz + 500u) / 1000u);
    int ms;
    int k;
    if (vdc < 0) {
        vdc = 0;
    }
    a.iu = QFOC_ADC_MID;
    a.iv = QFOC_ADC_MID;
    a.vdc = (uint16_t)((vdc > 4095) ? 4095 : vdc);
    if (ppm < 1 || ppm > 40) {
        ppm = 8;
    }
    t.t_ipm = 400;
    t.t_pcb = 350;
    t.rx = NULL;
    t.rx_len = 0u;
    for (ms = 0; ms < ((status == QFOC_PARAMS_OK) ? 20 : 2); ms++) {
        for (k = 0; k < ppm; k++) {
            const qfoc_pwm_t pwm = fz_fast(d, &a);
            FZ_CHECK(status == QFOC_PARAMS_OK || !pwm.enable, "refused table: PWM off");
        }
        (void)fz_tick(d, &t);
        FZ_CHECK(status == QFOC_PARAMS_OK || d->s.sm.state == QFOC_STATE_ERROR,
                 "refused table: the drive stays in ERROR");
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static const qfoc_param_table_t *const tables[3] = {
        &qfoc_params_reference, &qfoc_params_reference16k, &qfoc_params_traction350
    };
    static qfoc_drive_t d;
    static qfoc_param_table_t ram;
    static qfoc_param_table_t ram_before;
    fz_in_t in = { data, size };
    const uint8_t mode = fz_u8(&in);
    qfoc_param_table_t *t = (qfoc_param_table_t *)calloc(1u, TSIZE);
    uint8_t *tb = (uint8_t *)t;
    uint8_t copy[TSIZE];
    int32_t status;
    int32_t expect;
    int32_t scan = QFOC_PARAMS_BUSY;
    uint32_t crc = 0u;
    uint8_t step;
    bool id_ok;

    if (t == NULL) {
        return 0;
    }
    if ((mode & 3u) == 0u) {
        memcpy(tb, in.p, (in.n < TSIZE) ? in.n : TSIZE);
    } else {
        memcpy(t, tables[(mode & 3u) - 1u], TSIZE);
        while (in.n >= 2u) {
            const uint8_t at = fz_u8(&in);
            const uint8_t v = fz_u8(&in);
            tb[at % TSIZE] = v;
        }
        if ((mode & 4u) != 0u) {
            t->magic = QFOC_PARAMS_MAGIC;
            t->version = QFOC_PARAMS_VERSION;
            t->crc = qfoc_params_crc(t);
        }
    }
    memcpy(copy, tb, TSIZE);

    /* the check, against the order identity, CRC, ranges */
    id_ok = t->magic == QFOC_PARAMS_MAGIC && t->version == QFOC_PARAMS_VERSION;
    if (!id_ok) {
        expect = QFOC_PARAMS_ERR_ID;
    } else if (t->crc != qfoc_params_crc(t)) {
        expect = QFOC_PARAMS_ERR_CRC;
    } else if (!qfoc_params_is_valid(t)) {
        expect = QFOC_PARAMS_ERR_RANGE;
    } else {
        expect = QFOC_PARAMS_OK;
    }
    status = qfoc_params_check(t);
    FZ_CHECK(status == expect, "check: the first failure of identity, CRC, ranges");
    FZ_CHECK(memcmp(copy, tb, TSIZE) == 0, "check: the table is only read");

    /* the same check in five steps */
    for (step = 0u; step < QFOC_PARAMS_SCAN_STEPS; step++) {
        scan = qfoc_params_scan_step(&crc, t, step);
        if (step + 1u < QFOC_PARAMS_SCAN_STEPS) {
            FZ_CHECK(scan == QFOC_PARAMS_BUSY, "scan: BUSY before the last step");
        }
    }
    FZ_CHECK(scan == status, "scan: the status of qfoc_params_check");
    {
        const uint32_t keep = crc;
        FZ_CHECK(qfoc_params_scan_step(&crc, t, (uint8_t)(QFOC_PARAMS_SCAN_STEPS + (mode >> 3)))
                 == QFOC_PARAMS_BUSY && crc == keep, "scan: a step out of range does nothing");
    }

    /* the copy to RAM */
    memset(&ram, (int)(mode ^ 0x5Au), sizeof ram);
    memcpy(&ram_before, &ram, sizeof ram);
    {
        const int32_t ls = qfoc_params_load(&ram, t);
        FZ_CHECK(ls == status, "load: the status of the check");
        if (ls == QFOC_PARAMS_OK) {
            FZ_CHECK(memcmp(&ram, t, TSIZE) == 0, "load: an exact copy");
        } else {
            FZ_CHECK(memcmp(&ram, &ram_before, sizeof ram) == 0, "load: RAM untouched on a failure");
        }
    }

    /* the drive on this table */
    memset(&d, (int)mode, sizeof d);
    {
        const int32_t ds = qfoc_drive_init(&d, t);
        FZ_CHECK(ds == status, "drive init: the status of the check");
        FZ_CHECK(d.p == t, "drive init: the table pointer");
        FZ_CHECK(qfoc_drive_is_valid(&d), "drive init: the invariant for any table");
        if (ds == QFOC_PARAMS_OK) {
            FZ_CHECK(d.s.sm.state == QFOC_STATE_PRECHARGE && d.s.table_ok,
                     "drive init: PRECHARGE on an accepted table");
        } else {
            FZ_CHECK(d.s.sm.state == QFOC_STATE_ERROR && !d.s.table_ok &&
                     (d.s.sm.faults & QFOC_FAULT_PARAM) != 0u,
                     "drive init: ERROR with PARAM on a refused table");
        }
        bench(&d, ds);
    }
    FZ_CHECK(memcmp(copy, tb, TSIZE) == 0, "the table is only read");
    free(t);
    return 0;
}
