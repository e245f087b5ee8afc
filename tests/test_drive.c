/**
 * @file test_drive.c
 * @brief Tests of the drive's entry points with synthetic ADC samples and frames
 *        (specs/requirements/drive.md): initialisation, measurement, over-current,
 *        PWM gating, offset calibration, fault detection and reaction times, the
 *        command link, the status and CAN frames, the table re-check and the
 *        inductance switch.  The closed-loop behaviour on the plant is in
 *        test_drive_plant.c.
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <string.h>
#include <math.h>
#include <cmocka.h>

#define TEST_SEED 0xD21E0001u
#include "test_util.h"
#include "qfoc/drive.h"
#include "reference_params.h"
#include "drive_sim.h"

#include "drive_rig.h"

static void rig_init(rig_t *r)
{
    rig_init_table(r, &qfoc_params_reference, 3000u);
}

static uint8_t st(const rig_t *r)
{
    return r->d.s.sm.state;
}

static void rig_to_stop(rig_t *r)
{
    rig_ms(r, 300);
    assert_int_equal(st(r), QFOC_STATE_STOP);
}

/* REQ-DRV-001: initialisation from the generated table; a refused table is ERROR/PARAM
   for good, PWM never enabled.
   Methods: 1b a byte corruption at every seventh byte of the table; 1d a corrupted or
   refused table: ERROR / PARAM for good, never cleared, PWM never enabled; 1l 0x5A XORed
   into each byte of the table and the CRC flipped before init */
static void test_drv_001_init(void **state)
{
    rig_t r;
    unsigned byte;
    (void)state;
    rig_init(&r);
    assert_true(qfoc_drive_is_valid(&r.d));
    assert_int_equal(st(&r), QFOC_STATE_PRECHARGE);
    assert_int_equal(r.d.s.sm.faults, 0);
    /* every single-byte corruption of the table at init is refused */
    for (byte = 0u; byte < sizeof(qfoc_param_table_t); byte += 7u) {
        qfoc_drive_t d;
        qfoc_param_table_t t = qfoc_params_reference;
        ((uint8_t *)&t)[byte] ^= 0x5Au;
        if (qfoc_params_check(&t) != QFOC_PARAMS_OK) {
            assert_int_not_equal(qfoc_drive_init(&d, &t), QFOC_PARAMS_OK);
            assert_int_equal(d.s.sm.state, QFOC_STATE_ERROR);
            assert_int_equal(d.s.sm.faults, QFOC_FAULT_PARAM);
            assert_true(qfoc_drive_is_valid(&d));
        }
    }
    /* a refused table never runs and is never cleared */
    r.table.crc ^= 1u;
    assert_int_equal(qfoc_drive_init(&r.d, &r.table), QFOC_PARAMS_ERR_CRC);
    r.power_on = true;
    r.fault_clear = true;
    rig_ms(&r, 7000);
    assert_int_equal(st(&r), QFOC_STATE_ERROR);
    assert_int_equal(r.d.s.sm.faults & QFOC_FAULT_PARAM, QFOC_FAULT_PARAM);
    assert_false(r.pwm.enable);
    assert_int_equal(r.enabled_outside_run, 0);
}

/* REQ-DRV-007: PRECHARGE waits for the bus, then averages 2^offset_shift samples;
   offsets outside the window are a fault.
   Methods: 1c the offset at the window's edge (accepted) and one code outside (OFFSET
   fault); 1d a bus below vdc_uv at power-on, an offset out of range, a recalibration after
   an OFFSET fault is cleared; 1l current-sensor offsets out of the window injected at the
   ADC */
static void test_drv_007_precharge_and_offsets(void **state)
{
    rig_t r;
    (void)state;
    rig_init(&r);
    r.adc.vdc = vdc_code(100.0);            /* below vdc_uv */
    rig_ms(&r, 1000);
    assert_int_equal(st(&r), QFOC_STATE_PRECHARGE);
    assert_int_equal(r.d.s.sm.sub, QFOC_SUB_BUS_WAIT);
    r.adc.vdc = vdc_code(320.0);
    r.adc.iu = (uint16_t)(QFOC_ADC_MID + 37u);
    r.adc.iv = (uint16_t)(QFOC_ADC_MID - 21u);
    rig_ms(&r, 20 + (int)r.table.drive.precharge_ms);   /* filter settles, bus time */
    assert_int_equal(r.d.s.sm.sub, QFOC_SUB_CALIB);
    rig_ms(&r, (1 << r.table.drive.offset_shift) + 2);
    assert_int_equal(st(&r), QFOC_STATE_STOP);
    assert_int_equal(r.d.s.offset_u, QFOC_ADC_MID + 37u);
    assert_int_equal(r.d.s.offset_v, QFOC_ADC_MID - 21u);
    /* out of the window */
    rig_init(&r);
    r.adc.iu = (uint16_t)(QFOC_ADC_MID + r.table.drive.offset_window + 1u);
    rig_ms(&r, 400);
    assert_int_equal(st(&r), QFOC_STATE_ERROR);
    assert_int_equal(r.d.s.sm.faults, QFOC_FAULT_OFFSET);
    /* at the window edge: accepted */
    rig_init(&r);
    r.adc.iv = (uint16_t)(QFOC_ADC_MID - r.table.drive.offset_window);
    rig_ms(&r, 400);
    assert_int_equal(st(&r), QFOC_STATE_STOP);
    /* after an OFFSET fault is cleared, the drive calibrates again */
    rig_init(&r);
    r.adc.iu = 3000u;
    rig_ms(&r, 400);
    assert_int_equal(st(&r), QFOC_STATE_ERROR);
    r.adc.iu = QFOC_ADC_MID;
    r.fault_clear = true;
    rig_ms(&r, 5100);
    assert_int_not_equal(st(&r), QFOC_STATE_ERROR);
    rig_ms(&r, 400);
    assert_int_equal(st(&r), QFOC_STATE_STOP);
    assert_int_equal(r.d.s.offset_u, QFOC_ADC_MID);
}

/* REQ-DRV-009: run request = power-on, target >= rpm_min, link alive; rpm conversion.
   Methods: 1c the target at rpm_min - 1 and rpm_min, rpm_max + 1 (refused by the link) and
   rpm_max (within speed_max); 1a the rpm conversion floor(rpm k_rpm / 4096 + 0.5) and k_rpm
   = n_p 32768 / (60 f_base) computed in the test */
static void test_drv_009_command(void **state)
{
    rig_t r;
    (void)state;
    rig_init(&r);
    rig_to_stop(&r);
    r.power_on = true;
    r.rpm = (uint16_t)(r.table.drive.rpm_min - 1u);
    rig_ms(&r, 100);
    assert_int_equal(st(&r), QFOC_STATE_STOP);
    r.rpm = r.table.drive.rpm_min;
    {
        int ms;
        for (ms = 0; (ms < 20) && (st(&r) != QFOC_STATE_RUN); ms++) {
            rig_ms(&r, 1);
        }
    }
    assert_int_equal(st(&r), QFOC_STATE_RUN);
    /* RUN is entered in CATCH (REQ-DRV-027); the rig's rotor stands: ALIGN */
    assert_int_equal(r.d.s.sm.sub, QFOC_SUB_CATCH);
    (void)rig_catch_ms(&r);
    assert_int_equal(r.d.s.sm.sub, QFOC_SUB_ALIGN);
    {
        const double expect = floor((double)r.rpm * r.table.drive.k_rpm / 4096.0 + 0.5);
        assert_int_equal(r.d.s.speed_target, (int)expect);
        /* and the k_rpm of the table is n_p 32768 / (60 f_base) in Q12 */
        assert_true(fabs(r.table.drive.k_rpm / 4096.0 - 3.0 * 32768.0 / 30000.0) < 1e-3);
    }
    /* a target above rpm_max is rejected by the link: the last valid one stays */
    r.rpm = (uint16_t)(r.table.drive.rpm_max + 1u);
    rig_ms(&r, 30);
    assert_int_equal(r.d.s.link.cmd.target_rpm, r.table.drive.rpm_min);
    assert_true(r.d.s.link.n_range >= 2u);
    /* the largest target converts to at most speed_max */
    r.rpm = r.table.drive.rpm_max;
    rig_ms(&r, 20);
    assert_true(r.d.s.speed_target <= r.table.speed_max);
    assert_true(r.d.s.speed_target > 0);
}

/* REQ-DRV-002, REQ-DRV-003, REQ-DRV-004 (current scaling): over-current: PWM off in the same call, ERROR at the next
   tick, latched until a fault clear after clear_ms.
   Methods: 1b each direction and each phase (u, and w derived from u and v); 1c the trip
   exactly one code above i_trip / 16, at i_trip not, the clear at clear_ms - 20 and after;
   1d an over-current sample; 1l the over-current injected at the ADC, the PWM off in the
   same call */
static void test_drv_003_overcurrent(void **state)
{
    rig_t r;
    int trip_codes;
    int j;
    (void)state;
    rig_init(&r);
    rig_to_stop(&r);
    r.power_on = true;
    rig_ms(&r, 20);
    assert_int_equal(st(&r), QFOC_STATE_RUN);
    rig_fast(&r);
    assert_true(r.pwm.enable);
    /* (code - offset) x 16 > i_trip trips; == i_trip does not */
    trip_codes = r.table.i_trip / 16;
    r.adc.iu = (uint16_t)(QFOC_ADC_MID + trip_codes);
    if ((trip_codes * 16) > r.table.i_trip) {
        r.adc.iu = (uint16_t)(QFOC_ADC_MID + trip_codes - 1);
    }
    rig_fast(&r);
    assert_true(r.pwm.enable);
    assert_false(r.d.f.trip);
    r.adc.iu = (uint16_t)(QFOC_ADC_MID + (r.table.i_trip / 16) + 1);
    rig_fast(&r);
    assert_false(r.pwm.enable);               /* the same PWM period */
    assert_true(r.d.f.trip);
    r.adc.iu = QFOC_ADC_MID;
    for (j = 0; j < 7; j++) {
        rig_fast(&r);
        assert_false(r.pwm.enable);           /* latched until the tick */
    }
    rig_tick_rx(&r, NULL, 0u);
    assert_int_equal(st(&r), QFOC_STATE_ERROR);
    assert_int_equal(r.d.s.sm.faults, QFOC_FAULT_OC);
    assert_int_equal(r.d.s.sm.first_fault, QFOC_FAULT_OC);
    /* the negative direction and the third phase trip too */
    {
        rig_t q;
        rig_init(&q);
        rig_to_stop(&q);
        q.power_on = true;
        rig_ms(&q, 20);
        q.adc.iu = (uint16_t)(QFOC_ADC_MID - (q.table.i_trip / 32) - 2);
        q.adc.iv = (uint16_t)(QFOC_ADC_MID - (q.table.i_trip / 32) - 2);   /* i_w > trip */
        rig_fast(&q);
        assert_false(q.pwm.enable);
        q.adc.iu = 0u;
        q.adc.iv = QFOC_ADC_MID;
        rig_fast(&q);
        assert_false(q.pwm.enable);
    }
    /* clear: not before clear_ms, then STOP and the latch released */
    r.fault_clear = true;
    rig_ms(&r, (int)r.table.drive.clear_ms - 20);
    assert_int_equal(st(&r), QFOC_STATE_ERROR);
    for (j = 0; j < 40 && st(&r) == QFOC_STATE_ERROR; j++) {
        rig_ms(&r, 1);
    }
    assert_int_equal(st(&r), QFOC_STATE_STOP);
    assert_int_equal(r.d.s.sm.faults, 0);
    r.fault_clear = false;
    rig_ms(&r, 20);
    assert_int_equal(st(&r), QFOC_STATE_RUN);   /* power-on still set: restarts */
    rig_fast(&r);
    assert_true(r.pwm.enable);
    assert_false(r.d.f.trip);
    assert_int_equal(r.enabled_outside_run, 0);
}

/* REQ-DRV-008: DC-bus and temperature faults within their reaction times.
   Methods: 1c the temperature at its limit (no fault) and one above for temp_ms - 1 and
   temp_ms ticks, the debounce of vdc_ms; 1d over-voltage from STOP, under-voltage while
   running, a bus drop in STOP (no fault), a clear refused while still hot; 1l bus steps to
   480 V and 150 V and temperatures above the limits injected at the inputs */
static void test_drv_008_fault_reaction_times(void **state)
{
    rig_t r;
    int ms;
    (void)state;
    /* over-voltage from STOP: 320 V -> 480 V step */
    rig_init(&r);
    rig_to_stop(&r);
    r.adc.vdc = vdc_code(480.0);
    for (ms = 1; ms <= 20 && st(&r) != QFOC_STATE_ERROR; ms++) {
        rig_ms(&r, 1);
    }
    assert_int_equal(st(&r), QFOC_STATE_ERROR);
    assert_int_equal(r.d.s.sm.faults, QFOC_FAULT_OV);
    print_message("OV 320 -> 480 V: ERROR after %d ms (debounce %u ms)\n", ms - 1,
                  r.table.drive.vdc_ms);
    assert_true((ms - 1) >= (int)r.table.drive.vdc_ms);
    assert_true((ms - 1) <= 10);
    /* under-voltage while running: 320 -> 150 V */
    rig_init(&r);
    rig_to_stop(&r);
    r.power_on = true;
    rig_ms(&r, 20);
    assert_int_equal(st(&r), QFOC_STATE_RUN);
    r.adc.vdc = vdc_code(150.0);
    for (ms = 1; ms <= 20 && st(&r) != QFOC_STATE_ERROR; ms++) {
        rig_ms(&r, 1);
    }
    assert_int_equal(r.d.s.sm.faults, QFOC_FAULT_UV);
    print_message("UV 320 -> 150 V in RUN: ERROR after %d ms\n", ms - 1);
    assert_true((ms - 1) <= 10);
    /* the same bus drop in STOP is not a fault: back to PRECHARGE */
    rig_init(&r);
    rig_to_stop(&r);
    r.adc.vdc = vdc_code(150.0);
    rig_ms(&r, 50);
    assert_int_equal(st(&r), QFOC_STATE_PRECHARGE);
    /* over-temperature: exactly temp_ms ticks above the limit */
    rig_init(&r);
    rig_to_stop(&r);
    r.t_ipm = (int16_t)(r.table.drive.t_ipm_max + 1);
    rig_ms(&r, (int)r.table.drive.temp_ms - 1);
    assert_int_equal(st(&r), QFOC_STATE_STOP);
    rig_ms(&r, 1);
    assert_int_equal(st(&r), QFOC_STATE_ERROR);
    assert_int_equal(r.d.s.sm.faults, QFOC_FAULT_OT_IPM);
    /* at the limit: no fault; a clear is refused while still hot */
    rig_init(&r);
    rig_to_stop(&r);
    r.t_pcb = r.table.drive.t_pcb_max;
    rig_ms(&r, 100);
    assert_int_equal(st(&r), QFOC_STATE_STOP);
    r.t_pcb = (int16_t)(r.t_pcb + 1);
    rig_ms(&r, (int)r.table.drive.temp_ms);
    assert_int_equal(r.d.s.sm.faults, QFOC_FAULT_OT_PCB);
    r.fault_clear = true;
    rig_ms(&r, 6000);
    assert_int_equal(st(&r), QFOC_STATE_ERROR);
    r.t_pcb = 300;
    rig_ms(&r, 20);
    assert_int_equal(st(&r), QFOC_STATE_STOP);
}

/* A flipped bit in one of the four quarters of the table's serialisation (head, flux,
   drive_run, drive_feat: qfoc_params_scan_step's steps 0 .. 3). */
static void drv_010_flip(qfoc_param_table_t *t, int part)
{
    if (part == 0) {
        t->f_base_mhz ^= 0x10u;
    } else if (part == 1) {
        t->flux.kg = (int16_t)(t->flux.kg ^ 0x0004);
    } else if (part == 2) {
        t->drive.ho_dwell_ms ^= 0x0200u;
    } else {
        t->drive.clear_ms ^= 0x0100u;
    }
}

/* REQ-DRV-010: the table is re-checked in every 100 ms period; a flipped bit anywhere in
   it, flipped at any tick of the period, is PARAM (ERROR) within 105 ms, and is not
   cleared.
   Methods: 1b a bit flipped in each quarter of the table at each of the 100 ticks of the
   re-check period; 1c the detection bound 105 ms reached (at least 101); 1d a table
   corrupted while running, and repaired afterwards (still latched); 1l the bit flips
   injected into the table in "flash" */
static void test_drv_010_table_recheck(void **state)
{
    rig_t r0;
    rig_t r;
    int ms;
    int part;
    int phase;
    int worst = 0;
    (void)state;
    rig_init(&r0);
    rig_to_stop(&r0);
    for (part = 0; part < 4; part++) {
        for (phase = 0; phase < 100; phase++) {
            r = r0;
            r.d.p = &r.table;                 /* the copy's drive reads the copy's table */
            rig_ms(&r, phase);
            assert_int_equal(st(&r), QFOC_STATE_STOP);
            drv_010_flip(&r.table, part);     /* a flipped bit in "flash" */
            assert_int_not_equal(qfoc_params_check(&r.table), QFOC_PARAMS_OK);
            for (ms = 1; ms <= 300 && st(&r) != QFOC_STATE_ERROR; ms++) {
                rig_ms(&r, 1);
            }
            assert_true((ms - 1) <= 105);
            assert_int_equal(r.d.s.sm.faults, QFOC_FAULT_PARAM);
            worst = ((ms - 1) > worst) ? (ms - 1) : worst;
        }
    }
    print_message("table corruption detected after at most %d ms (4 parts x 100 phases)\n",
                  worst);
    assert_true(worst >= 101);   /* the bound is reached: a bit flipped just after its
                                    quarter was folded waits for the next scan */
    assert_int_equal(r.d.s.sm.faults, QFOC_FAULT_PARAM);
    r.table.drive.clear_ms ^= 0x0100u;     /* even repaired: latched for good */
    r.fault_clear = true;
    rig_ms(&r, 20000);
    assert_int_equal(st(&r), QFOC_STATE_ERROR);
}

/* REQ-DRV-011, REQ-DRV-015: a status frame answers every valid command frame; CAN every
   100 ms with alternating identifiers; a malformed frame changes nothing but its
   counter.
   Methods: 1d malformed frames, and 2000 ms of silence (the link lost in STOP, no fault); 1l
   a random bit flipped in each of 2000 valid frames; 1n a twin drive that receives nothing,
   the status frame's checksum and identifier by the simulator's own LIN functions */
static void test_drv_011_status_and_can(void **state)
{
    rig_t r;
    rig_t twin;
    long k;
    int can = 0;
    uint16_t last_id = 0u;
    (void)state;
    rig_init(&r);
    for (k = 0; k < 1000; k++) {
        rig_ms(&r, 1);
        if ((r.ms % 10) == 1) {
            /* the frame of this tick was a valid command */
            assert_int_equal(r.out.tx_len, QFOC_LIN_STATUS_LEN);
            assert_int_equal(r.out.tx[0], 0x55u);
            assert_int_equal(r.out.tx[1], dsim_lin_pid(r.table.drive.lin_id_status));
            assert_int_equal(r.out.tx[10], dsim_lin_checksum(&r.out.tx[1], 9));
        } else {
            assert_int_equal(r.out.tx_len, 0u);
        }
        if (r.out.can_send) {
            assert_int_equal(r.ms % 100, 0);
            assert_int_equal(r.out.can.dlc, 8u);
            assert_int_equal(r.out.can.id, (can % 2 == 0) ? r.table.drive.can_id_a
                                                           : r.table.drive.can_id_b);
            assert_int_not_equal(r.out.can.id, last_id);
            last_id = r.out.can.id;
            can++;
        }
    }
    assert_int_equal(can, 10);
    /* malformed frames: same state as a twin that received nothing */
    rig_init(&r);
    rig_to_stop(&r);
    twin = r;
    twin.d.p = &twin.table;
    for (k = 0; k < 2000; k++) {
        uint8_t f[QFOC_LIN_FRAME_MAX];
        uint8_t len;
        int j;
        r.power_on = true;
        r.fault_clear = true;
        len = rig_frame(&r, f);
        f[(lcg_next() >> 8) % len] ^= (uint8_t)(1u << ((lcg_next() >> 8) % 8u));
        for (j = 0; j < 8; j++) {
            rig_fast(&r);
            rig_fast(&twin);
        }
        rig_tick_rx(&r, f, len);
        rig_tick_rx(&twin, NULL, 0u);
        assert_int_equal(r.out.tx_len, 0u);
        assert_int_equal(r.d.s.sm.state, twin.d.s.sm.state);
        assert_int_equal(r.d.s.sm.sub, twin.d.s.sm.sub);
        assert_int_equal(r.d.s.sm.faults, twin.d.s.sm.faults);
    }
    /* with 2000 ms of silence from the master, both lost the link: not a fault in STOP */
    assert_true(qfoc_link_lost(&r.d.s.link));
    assert_int_equal(st(&r), QFOC_STATE_STOP);
    print_message("malformed frames rejected: len %u sync %u id %u checksum %u reserved %u range %u\n",
                  r.d.s.link.n_len, r.d.s.link.n_sync, r.d.s.link.n_id, r.d.s.link.n_checksum,
                  r.d.s.link.n_reserved, r.d.s.link.n_range);
}

/* REQ-DRV-012: motorParaChange: high-speed inductances above para_speed, back below
   15/16 of it; the observer's inductance follows.
   Methods: 1c the speed one above para_speed, inside the hysteresis band (1/32 below) and
   below it (1/8 below, past 15/16) */
static void test_drv_012_para_change(void **state)
{
    rig_t r;
    (void)state;
    rig_init(&r);
    r.table.drive.lq_hs = (int16_t)(r.table.lq + 100);
    r.table.crc = qfoc_params_crc(&r.table);
    assert_int_equal(qfoc_drive_init(&r.d, &r.table), QFOC_PARAMS_OK);
    rig_to_stop(&r);
    r.d.f.speed_f = (int16_t)(r.table.drive.para_speed + 1);
    rig_tick_rx(&r, NULL, 0u);
    r.ms = 0;
    while (r.d.s.ms100 != 0u) {
        r.d.f.speed_f = (int16_t)(r.table.drive.para_speed + 1);
        rig_tick_rx(&r, NULL, 0u);
    }
    assert_true(r.d.s.hs);
    rig_fast(&r);
    assert_true(r.d.f.hs);
    assert_int_equal(r.d.f.flux.params.l, r.table.lq + 100);
    /* inside the hysteresis band: kept */
    {
        int k;
        for (k = 0; k < 100; k++) {
            r.d.f.speed_f = (int16_t)(r.table.drive.para_speed - (r.table.drive.para_speed / 32));
            rig_tick_rx(&r, NULL, 0u);
        }
        assert_true(r.d.s.hs);
        for (k = 0; k < 100; k++) {
            r.d.f.speed_f = (int16_t)(r.table.drive.para_speed - (r.table.drive.para_speed / 8));
            rig_tick_rx(&r, NULL, 0u);
        }
        assert_false(r.d.s.hs);
    }
    rig_fast(&r);
    assert_int_equal(r.d.f.flux.params.l, r.table.lq);
}

/* REQ-DRV-006: the tick's voltage utilisation of the last command, |v| sqrt 3 / V_dc
   (V_dc at least vdc_min), against the double formula, for random commands and buses
   (the fast step's field weakening reads it).
   Methods: 1b 20000 random commands and buses, every 50th command and every 40th bus any
   int16; 1c the magnitude saturated at 32767, a bus of 0 and -7 with vdc_min 0 (the bus
   taken as 1); 1d a refused table whose bus minimum is 0; 1n |v| sqrt(3) / V_dc in double
   precision */
static void test_req_drv_006_utilisation_tick(void **state)
{
    rig_t r;
    double max_err = 0.0;
    int k;
    (void)state;
    rig_init(&r);
    rig_to_stop(&r);
    for (k = 0; k < 20000; k++) {
        const qfoc_q15_t vmin = r.table.svpwm.vdc_min;
        double bus;
        double ref;
        r.d.f.u_last.alpha = (k % 50 == 0) ? rand_i16() : (int16_t)rand_range(-12000, 12000);
        r.d.f.u_last.beta = (k % 50 == 1) ? rand_i16() : (int16_t)rand_range(-12000, 12000);
        r.d.f.vdc = (k % 40 == 0) ? rand_i16() : (int16_t)rand_range(1000, 32767);
        rig_tick_rx(&r, NULL, 0u);
        bus = (r.d.f.vdc < vmin) ? (double)vmin : (double)r.d.f.vdc;
        if (bus < 1.0) {
            bus = 1.0;
        }
        ref = sqrt((double)r.d.f.u_last.alpha * r.d.f.u_last.alpha +
                   (double)r.d.f.u_last.beta * r.d.f.u_last.beta);
        if (ref > 32767.0) {
            ref = 32767.0;    /* the magnitude saturates at 32767 */
        }
        ref = ref * 1.7320508075688772 / bus * 32768.0;
        if (ref > 32767.0) {
            ref = 32767.0;
        }
        assert_true((r.d.s.util >= 0) && (r.d.s.util <= 32767));
        /* floor square root (< 1 LSB of |v|) scaled by sqrt 3 / V_dc, and the rounding */
        max_err = fmax(max_err, fabs((double)r.d.s.util - ref) / (0.5 + 1.7320508075688772 *
                                                                  32768.0 / bus));
        assert_true(fabs((double)r.d.s.util - ref) <= 0.5 + 1.7320508075688772 * 32768.0 / bus);
    }
    print_message("utilisation of the tick: max error / bound (0.5 + sqrt 3 x 32768 / V_dc) = %.3f\n",
                  max_err);
    {
        /* a refused table whose bus minimum is 0 and a bus of 0: the bus is taken as 1 */
        rig_t z;
        memset(&z, 0, sizeof z);
        z.table = qfoc_params_reference;
        z.table.svpwm.vdc_min = 0;
        assert_int_not_equal(qfoc_drive_init(&z.d, &z.table), QFOC_PARAMS_OK);
        z.d.f.u_last.alpha = 0;
        z.d.f.u_last.beta = 0;
        z.d.f.vdc = 0;
        rig_tick_rx(&z, NULL, 0u);
        assert_int_equal(z.d.s.util, 0);
        z.d.f.u_last.alpha = 1;
        z.d.f.vdc = -7;
        rig_tick_rx(&z, NULL, 0u);
        assert_int_equal(z.d.s.util, 32767);   /* 1 x 56756 / 1, saturated */
    }
}

/* REQ-DRV-001, REQ-DRV-002, REQ-DRV-005: random ADC samples, temperatures and frames: the PWM is
   enabled only in RUN, the compare values never exceed the period, the invariant holds.
   Methods: 1b 60000 ticks of random ADC samples, temperatures, commands and frames, power on
   and off; 1d rare out-of-range current and bus samples, over-temperatures, corrupted
   frames; 1l random current and bus spikes and a bit flipped in every fourth frame */
static void test_drv_002_random_inputs(void **state)
{
    rig_t r;
    long k;
    long run_ms = 0;
    (void)state;
    rig_init(&r);
    for (k = 0; k < 60000; k++) {
        uint8_t f[QFOC_LIN_FRAME_MAX];
        uint8_t len = 0u;
        int j;
        if ((k % 3000) == 0) {
            r.power_on = (lcg_next() & 0x100u) != 0u;
            r.fault_clear = (lcg_next() & 0x100u) != 0u;
            r.rpm = (uint16_t)(lcg_next() >> 19);
        }
        for (j = 0; j < 8; j++) {
            const uint32_t x = lcg_next();
            r.adc.iu = (uint16_t)((x & 0x3FFFu) == 0u ? (x >> 16) : QFOC_ADC_MID + ((x >> 20) & 0x3Fu));
            r.adc.iv = (uint16_t)(QFOC_ADC_MID - ((x >> 26) & 0x1Fu));
            r.adc.vdc = (uint16_t)(((x >> 8) & 0x3FFFu) == 0u ? (x >> 20) : vdc_code(320.0));
            rig_fast(&r);
        }
        r.t_ipm = (int16_t)(((lcg_next() >> 8) & 0x3FFFu) == 0u ? 1500 : 400);
        if ((k % 10) == 0) {
            len = rig_frame(&r, f);
            if ((lcg_next() & 0x3u) == 0u) {
                f[(lcg_next() >> 8) % len] ^= 0x10u;
            }
        }
        rig_tick_rx(&r, f, len);
        if (st(&r) == QFOC_STATE_RUN) {
            run_ms++;
        }
        assert_true(qfoc_drive_is_valid(&r.d));
    }
    print_message("random inputs: %ld ms in RUN of 60000\n", run_ms);
    assert_true(run_ms > 0);
    assert_int_equal(r.enabled_outside_run, 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_drv_001_init),
        cmocka_unit_test(test_drv_002_random_inputs),
        cmocka_unit_test(test_drv_003_overcurrent),
        cmocka_unit_test(test_drv_007_precharge_and_offsets),
        cmocka_unit_test(test_drv_008_fault_reaction_times),
        cmocka_unit_test(test_drv_009_command),
        cmocka_unit_test(test_drv_010_table_recheck),
        cmocka_unit_test(test_drv_011_status_and_can),
        cmocka_unit_test(test_drv_012_para_change),
        cmocka_unit_test(test_req_drv_006_utilisation_tick),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
