/**
 * @file test_drive_api.c
 * @brief Tests of the drive's command and status functions (drive.h, "command and
 *        status"; specs/requirements/drive.md REQ-DRV-016, REQ-DRV-017): a drive
 *        commanded through qfoc_drive_command() against a twin commanded by LIN frames,
 *        refused commands, and the readers against the inputs applied.
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <string.h>
#include <math.h>
#include <cmocka.h>

#define TEST_SEED 0xD21E0A01u
#include "test_util.h"
#include "qfoc/drive.h"
#include "reference_params.h"
#include "drive_sim.h"

#include "drive_rig.h"

/* The command a master would send now. */
static qfoc_cmd_t rig_cmd(const rig_t *r)
{
    qfoc_cmd_t c;
    c.power_on = r->power_on;
    c.fault_clear = r->fault_clear;
    c.target_rpm = r->rpm;
    c.identify = false;
    return c;
}

/* One millisecond of both rigs: 8 periods each with the same samples (the same PWM
   output required), then the tick; fr gets the master's frame every 10 ms, api the
   same command through qfoc_drive_command() just before its tick. */
static void twin_ms(rig_t *fr, rig_t *api, bool master)
{
    int j;
    const bool frame = master && ((fr->ms % 10) == 0);
    for (j = 0; j < 8; j++) {
        rig_fast(fr);
        rig_fast(api);
        assert_int_equal(fr->pwm.enable, api->pwm.enable);
        assert_int_equal(fr->pwm.cmp[0], api->pwm.cmp[0]);
        assert_int_equal(fr->pwm.cmp[1], api->pwm.cmp[1]);
        assert_int_equal(fr->pwm.cmp[2], api->pwm.cmp[2]);
    }
    if (frame) {
        const qfoc_cmd_t c = rig_cmd(fr);
        assert_int_equal(qfoc_drive_command(&api->d, &c), QFOC_LINK_OK);
    }
    rig_tick(fr, frame);
    rig_tick_rx(api, NULL, 0u);
    /* the frame is answered on LIN, the function call is not */
    assert_int_equal(fr->out.tx_len, frame ? QFOC_LIN_STATUS_LEN : 0u);
    assert_int_equal(api->out.tx_len, 0u);
}

static void twin_same(const rig_t *fr, const rig_t *api)
{
    assert_int_equal(qfoc_drive_state(&api->d), fr->d.s.sm.state);
    assert_int_equal(qfoc_drive_substate(&api->d), fr->d.s.sm.sub);
    assert_int_equal(qfoc_drive_faults(&api->d), fr->d.s.sm.faults);
    assert_int_equal(qfoc_drive_first_fault(&api->d), fr->d.s.sm.first_fault);
    assert_int_equal(qfoc_drive_run_requested(&api->d), fr->d.s.cmd.power_on);
    assert_int_equal(qfoc_drive_target_rpm(&api->d), fr->d.s.cmd.target_rpm);
    assert_false(qfoc_drive_identify_requested(&api->d));
    assert_false(fr->d.s.cmd.identify);
}

/* REQ-DRV-016: through start (ALIGN, OPEN_LOOP without a rotor: the open-loop timeout
   ends in STALL, on the reference table without start retries), ERROR, fault clear, a
   second start, stop, and a link loss, the drive
   commanded by the function gives the PWM output and the state of the drive commanded
   by frames, period by period; the loss comes one tick earlier, because the function's
   command is given before the tick in which the twin receives its frame.
   Methods: 1b a master's script through start, STALL without a rotor, ERROR, fault clear, a
   second start, stop and silence; 1d a start that stalls, a link lost; 1n a twin drive
   commanded by frames, the same PWM output and state period by period */
static void test_drv_016_command_like_frame(void **state)
{
    rig_t fr;
    rig_t api;
    long k;
    long lost_fr = -1;
    long lost_api = -1;
    bool seen_run = false;
    bool seen_error = false;
    bool seen_clear = false;
    bool was_run = false;
    qfoc_param_table_t t = qfoc_params_reference;
    (void)state;
    t.drive.ho_retries = 0u;
    t.crc = qfoc_params_crc(&t);
    assert_int_equal(qfoc_params_check(&t), QFOC_PARAMS_OK);
    rig_init_table(&fr, &t, 3000u);
    rig_init_table(&api, &t, 3000u);
    api.send = false;
    for (k = 0; k < 24000; k++) {
        /* the master's script: run, clear the fault 6 s after it, run again, stop */
        fr.power_on = (k >= 400) && (k < 18000);
        fr.fault_clear = (k >= 12000) && (k < 12500);
        fr.rpm = (k < 15000) ? 3000u : 2000u;
        twin_ms(&fr, &api, k < 20000);
        twin_same(&fr, &api);
        /* no speed is reported once the PWM has been off for a whole millisecond */
        if (!was_run && (qfoc_drive_state(&api.d) != QFOC_STATE_RUN)) {
            assert_int_equal(qfoc_drive_speed_rpm(&api.d), 0u);
        }
        was_run = qfoc_drive_state(&api.d) == QFOC_STATE_RUN;
        seen_run = seen_run || (qfoc_drive_state(&api.d) == QFOC_STATE_RUN);
        seen_error = seen_error || (qfoc_drive_state(&api.d) == QFOC_STATE_ERROR);
        seen_clear = seen_clear || (seen_error && (qfoc_drive_state(&api.d) == QFOC_STATE_STOP));
        if (k == 19999) {
            break;
        }
    }
    assert_true(seen_run);
    assert_true(seen_error);
    assert_true(seen_clear);
    /* the master goes silent: the function's drive loses the link one tick before */
    for (k = 0; k < 1000; k++) {
        int j;
        for (j = 0; j < 8; j++) {
            rig_fast(&fr);
            rig_fast(&api);
        }
        rig_tick(&fr, false);
        rig_tick_rx(&api, NULL, 0u);
        if ((lost_fr < 0) && qfoc_link_lost(&fr.d.s.link)) {
            lost_fr = k;
        }
        if ((lost_api < 0) && qfoc_link_lost(&api.d.s.link)) {
            lost_api = k;
        }
    }
    assert_true(lost_fr > 0);
    assert_int_equal(lost_api, lost_fr - 1);
    assert_int_equal(qfoc_drive_state(&api.d), fr.d.s.sm.state);
    assert_int_equal(qfoc_drive_faults(&api.d), fr.d.s.sm.faults);
    print_message("link lost at tick %ld of the silence, the last frame 9 ticks before it "
                  "(timeout %u ms)\n", lost_fr + 1, fr.table.drive.link_timeout_ms);
}

/* REQ-DRV-016: a target above rpm_max is refused and counted; the drive goes on exactly
   as a twin that was never given it.
   Methods: 1b 3000 random targets above rpm_max with random clear flags, a valid command
   every tenth; 1c rpm_max (accepted) and rpm_max + 1 (refused); 1d commands out of range; 1n
   a twin drive that is never given them, the same PWM output, state and target in every tick */
static void test_drv_016_refused_command(void **state)
{
    rig_t r;
    rig_t twin;
    long k;
    uint16_t n_range;
    (void)state;
    rig_init_table(&r, &qfoc_params_reference, 3000u);
    r.send = false;
    rig_ms(&r, 400);
    assert_int_equal(qfoc_drive_state(&r.d), QFOC_STATE_STOP);
    twin = r;
    twin.d.p = &twin.table;
    n_range = r.d.s.link.n_range;
    for (k = 0; k < 3000; k++) {
        qfoc_cmd_t c;
        const bool good = (k % 10) == 0;
        c.power_on = true;
        c.identify = false;
        c.fault_clear = (lcg_next() & 1u) != 0u;
        c.target_rpm = (uint16_t)(r.table.drive.rpm_max + 1u + (lcg_next() % 3000u));
        assert_int_equal(qfoc_drive_command(&r.d, &c), QFOC_LINK_ERR_RANGE);
        n_range++;
        assert_int_equal(r.d.s.link.n_range, n_range);
        if (good) {
            /* both get the same valid command now and then */
            c.target_rpm = 3000u;
            c.fault_clear = false;
            assert_int_equal(qfoc_drive_command(&r.d, &c), QFOC_LINK_OK);
            assert_int_equal(qfoc_drive_command(&twin.d, &c), QFOC_LINK_OK);
        }
        rig_ms(&r, 1);
        rig_ms(&twin, 1);
        assert_int_equal(r.pwm.enable, twin.pwm.enable);
        assert_int_equal(r.pwm.cmp[0], twin.pwm.cmp[0]);
        assert_int_equal(qfoc_drive_state(&r.d), qfoc_drive_state(&twin.d));
        assert_int_equal(qfoc_drive_substate(&r.d), qfoc_drive_substate(&twin.d));
        assert_int_equal(qfoc_drive_faults(&r.d), qfoc_drive_faults(&twin.d));
        assert_int_equal(qfoc_drive_target_rpm(&r.d), qfoc_drive_target_rpm(&twin.d));
    }
    assert_int_equal(qfoc_drive_target_rpm(&r.d), 3000u);
    assert_true(qfoc_drive_run_requested(&r.d));
    /* the largest accepted target, and one above */
    {
        qfoc_cmd_t c = { true, false, 0u, false };
        c.target_rpm = r.table.drive.rpm_max;
        assert_int_equal(qfoc_drive_command(&r.d, &c), QFOC_LINK_OK);
        c.target_rpm = (uint16_t)(r.table.drive.rpm_max + 1u);
        assert_int_equal(qfoc_drive_command(&r.d, &c), QFOC_LINK_ERR_RANGE);
        rig_ms(&r, 1);
        assert_int_equal(qfoc_drive_target_rpm(&r.d), r.table.drive.rpm_max);
    }
}

/* REQ-DRV-017: the readers against what was applied: bus voltage from its ADC code,
   temperatures, phase currents from their codes (d and q in the ALIGN frame, angle 0),
   commands.
   Methods: 1a each reader against what was applied: the bus from its ADC code (300 V, 280
   V), the temperature, d and q currents in the ALIGN frame (i_d = i_u, i_q = (i_u + 2 i_v) /
   sqrt(3)) and their amplitude, the command, computed in the test */
static void test_drv_017_status_readers(void **state)
{
    rig_t r;
    qfoc_status_t st;
    qfoc_dq_t i;
    const double v_base = 500.0;                     /* the reference table's V_base */
    double i_base;
    (void)state;
    rig_init_table(&r, &qfoc_params_reference, 3000u);
    i_base = r.table.i_base_ma / 1000.0;
    r.send = false;
    r.adc.vdc = vdc_code(300.0);
    rig_ms(&r, 600);
    assert_int_equal(qfoc_drive_state(&r.d), QFOC_STATE_STOP);
    assert_int_equal(qfoc_drive_substate(&r.d), QFOC_SUB_NONE);
    assert_int_equal(qfoc_drive_faults(&r.d), 0u);
    assert_int_equal(qfoc_drive_first_fault(&r.d), 0u);
    assert_false(qfoc_drive_run_requested(&r.d));
    assert_false(qfoc_drive_identify_requested(&r.d));
    assert_int_equal(qfoc_drive_target_rpm(&r.d), 0u);
    /* the identification request: in effect from the tick after the command, the run
       request off; withdrawn by the next command */
    {
        qfoc_cmd_t c = { false, false, 0u, true };
        assert_int_equal(qfoc_drive_command(&r.d, &c), QFOC_LINK_OK);
        rig_ms(&r, 1);
        assert_true(qfoc_drive_identify_requested(&r.d));
        assert_false(qfoc_drive_run_requested(&r.d));
        assert_int_equal(qfoc_drive_state(&r.d), QFOC_STATE_STOP);
        c.identify = false;
        assert_int_equal(qfoc_drive_command(&r.d, &c), QFOC_LINK_OK);
        rig_ms(&r, 1);
        assert_false(qfoc_drive_identify_requested(&r.d));
    }
    qfoc_drive_status(&r.d, &st);
    assert_int_equal(st.state, QFOC_STATE_STOP);
    /* the bus: the code of 300 V read back in 0.1 V, within the ADC step (0.12 V) and
       the rounding of the scaling */
    assert_true(fabs(st.vdc_dv - 3000.0) <= 2.0);
    assert_true(fabs(qfoc_drive_vdc_q15(&r.d) / 32768.0 * v_base - 300.0) <= 0.2);
    assert_int_equal(st.temp_dc, 400);
    assert_int_equal(st.current_ca, 0u);
    assert_int_equal(st.speed_rpm, 0u);
    assert_int_equal(qfoc_drive_speed_rpm(&r.d), 0u);
    r.t_pcb = 455;
    r.adc.vdc = vdc_code(280.0);
    rig_ms(&r, 200);
    qfoc_drive_status(&r.d, &st);
    assert_int_equal(st.temp_dc, 455);
    assert_true(fabs(st.vdc_dv - 2800.0) <= 2.0);
    /* run: ALIGN holds angle 0, so d = i_alpha = i_u and q = i_beta = (i_u + 2 i_v)/sqrt 3 */
    {
        const qfoc_cmd_t c = { true, false, 3000u, false };
        int k;
        assert_int_equal(qfoc_drive_command(&r.d, &c), QFOC_LINK_OK);
        for (k = 0; (k < 2) && (qfoc_drive_state(&r.d) != QFOC_STATE_RUN); k++) {
            rig_ms(&r, 1);
        }
        assert_int_equal(qfoc_drive_state(&r.d), QFOC_STATE_RUN);
        /* RUN is entered in CATCH (REQ-DRV-027); the rig's rotor stands: ALIGN */
        assert_int_equal(qfoc_drive_substate(&r.d), QFOC_SUB_CATCH);
        (void)rig_catch_ms(&r);
        assert_int_equal(qfoc_drive_substate(&r.d), QFOC_SUB_ALIGN);
        assert_true(qfoc_drive_run_requested(&r.d));
        assert_int_equal(qfoc_drive_target_rpm(&r.d), 3000u);
        r.adc.iu = (uint16_t)(QFOC_ADC_MID + 100u);
        r.adc.iv = (uint16_t)(QFOC_ADC_MID + 30u);
        for (k = 0; k < 8; k++) {
            rig_fast(&r);
        }
        qfoc_drive_currents_q15(&r.d, &i);
        assert_int_equal(qfoc_drive_angle_est(&r.d), r.d.f.theta_est);
        {
            const double iu = 100.0 / 2048.0;        /* per unit of I_base */
            const double iv = 30.0 / 2048.0;
            assert_true(fabs(i.d / 32768.0 - iu) <= 2.0 / 32768.0);
            assert_true(fabs(i.q / 32768.0 - (iu + 2.0 * iv) / sqrt(3.0)) <= 2.0 / 32768.0);
            rig_tick(&r, false);
            qfoc_drive_status(&r.d, &st);
            /* amplitude in 0.01 A */
            assert_true(fabs(st.current_ca / 100.0 - hypot(iu, (iu + 2.0 * iv) / sqrt(3.0)) * i_base)
                        <= 0.02);
        }
    }
}

/* REQ-DRV-017: the fault word and the first fault hold the faults of the tick that
   entered ERROR; a later fault changes neither; both read 0 outside ERROR.
   Methods: 1b one fault, a later second fault, two faults in the same tick, the words after
   a clear; 1d a later fault that must not change the first fault; 1l over-temperatures of
   the IPM and the PCB injected at the inputs */
static void test_drv_017_first_fault(void **state)
{
    rig_t r;
    (void)state;
    rig_init_table(&r, &qfoc_params_reference, 3000u);
    rig_ms(&r, 400);
    r.t_ipm = (int16_t)(r.table.drive.t_ipm_max + 50);
    rig_ms(&r, 200);
    assert_int_equal(qfoc_drive_state(&r.d), QFOC_STATE_ERROR);
    assert_int_equal(qfoc_drive_first_fault(&r.d), QFOC_FAULT_OT_IPM);
    r.t_pcb = (int16_t)(r.table.drive.t_pcb_max + 50);
    rig_ms(&r, 200);
    assert_int_equal(qfoc_drive_faults(&r.d), QFOC_FAULT_OT_IPM);
    assert_int_equal(qfoc_drive_first_fault(&r.d), QFOC_FAULT_OT_IPM);
    /* cooled down, cleared after clear_ms: STOP, both words 0 */
    r.t_ipm = 300;
    r.t_pcb = 300;
    r.fault_clear = true;
    rig_ms(&r, (int)r.table.drive.clear_ms + 100);
    assert_int_equal(qfoc_drive_state(&r.d), QFOC_STATE_STOP);
    assert_int_equal(qfoc_drive_faults(&r.d), 0u);
    assert_int_equal(qfoc_drive_first_fault(&r.d), 0u);
    /* two faults in the same tick: both bits in both words */
    r.fault_clear = false;
    r.t_ipm = (int16_t)(r.table.drive.t_ipm_max + 50);
    r.t_pcb = (int16_t)(r.table.drive.t_pcb_max + 50);
    rig_ms(&r, 200);
    assert_int_equal(qfoc_drive_faults(&r.d), QFOC_FAULT_OT_IPM | QFOC_FAULT_OT_PCB);
    assert_int_equal(qfoc_drive_first_fault(&r.d), QFOC_FAULT_OT_IPM | QFOC_FAULT_OT_PCB);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_drv_016_command_like_frame),
        cmocka_unit_test(test_drv_016_refused_command),
        cmocka_unit_test(test_drv_017_status_readers),
        cmocka_unit_test(test_drv_017_first_fault),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
