/**
 * @file host_minimal.c
 * @brief The smallest integration of qfoc: a drive initialised from its parameter
 *        table, the fast step in the PWM interrupt, the tick in the 1 ms task, a run
 *        command and the status read back, all through include/qfoc/drive.h.
 *
 * On the target, the ADC samples come from the ADC-complete interrupt and the PWM
 * output goes to the timer (port_s32k/ shows the S32K144).  Here the samples are those of
 * an inverter on a 320 V bus with no motor connected (zero current, whatever the PWM
 * does), as on a first bench run: the drive goes through PRECHARGE and STOP, starts when
 * the command comes (RUN: ALIGN, switching), sees that the current it imposes does not
 * reach the sensors, and stops in ERROR with fault PHASE and the PWM off, align_ms / 2 +
 * phase_ms after the start (REQ-DRV-018).  examples/host_plant.c runs the same calls
 * against the simulated compressor.  Built and run by `make test`; exit status 0 when the
 * drive switched in RUN and then stopped with PHASE as its first fault, the PWM off.
 */
#include <stdio.h>
#include "qfoc/drive.h"
#include "reference_params.h"   /* the table tools/tune/qfoc_tune.py generated for the motor */

static qfoc_drive_t drive;      /* one per motor; no other state in the library */

int main(void)
{
    const qfoc_adc_t adc = { QFOC_ADC_MID, QFOC_ADC_MID, 2621u };  /* 0 A, 0 A, 320 V: no motor */
    const qfoc_tick_in_t in = { 400, 350, NULL, 0u };  /* 40.0 / 35.0 degC, no LIN frame */
    const qfoc_cmd_t run = { true, false, 3000u, false };     /* run at 3000 rpm */
    qfoc_status_t st;
    int ms;
    int k;
    int failed;
    bool switching = false;
    bool switched = false;

    if (qfoc_drive_init(&drive, &qfoc_params_reference) != QFOC_PARAMS_OK) {
        return 1;                                      /* the table was refused */
    }
    for (ms = 0; ms < 1000; ms++) {
        for (k = 0; k < 8; k++) {                      /* 8 PWM periods per ms (8 kHz) */
            const qfoc_pwm_t pwm = qfoc_drive_fast_step(&drive, &adc);
            switching = pwm.enable;                    /* cmp[3], enable -> the timer */
            switched = switched || switching;
        }
        if (ms >= 500) {
            (void)qfoc_drive_command(&drive, &run);    /* e.g. from the CAN handler */
        }
        (void)qfoc_drive_tick(&drive, &in);            /* 1 ms task */
    }
    qfoc_drive_status(&drive, &st);
    printf("host_minimal: state %u sub-state %u faults 0x%04x, bus %u.%u V, %d.%d degC, "
           "target %u rpm\n", (unsigned)st.state, (unsigned)st.substate, (unsigned)st.faults,
           (unsigned)(st.vdc_dv / 10u), (unsigned)(st.vdc_dv % 10u), st.temp_dc / 10,
           st.temp_dc % 10, (unsigned)qfoc_drive_target_rpm(&drive));
    printf("host_minimal: %s in RUN, first fault 0x%04x (PHASE: no current with no motor)\n",
           switched ? "switched" : "never switched", (unsigned)qfoc_drive_first_fault(&drive));
    failed = (qfoc_drive_state(&drive) != QFOC_STATE_ERROR) || !switched || switching ||
             (qfoc_drive_first_fault(&drive) != QFOC_FAULT_PHASE);
    return failed ? 1 : 0;
}
