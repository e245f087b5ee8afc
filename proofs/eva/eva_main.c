/**
 * @file eva_main.c
 * @brief Whole-program abstract interpretation of the drive (Frama-C EVA): the
 *        reference table, then fast steps and ticks with every input over its full
 *        range: ADC codes 0..65535 (the drive saturates above 4095), temperatures over
 *        int16, any received frame of 0..QFOC_LIN_FRAME_MAX bytes, any number of
 *        fast steps and ticks in any order (a loop with a nondeterministic exit and a
 *        nondeterministic choice: the analysis covers every state the drive can reach,
 *        in every sub-state).
 */
#include "qfoc/drive.h"
#include "reference_params.h"

volatile uint16_t eva_u16;     /* any value, read anew at each access */
volatile int16_t eva_i16;
volatile uint8_t eva_u8;

static qfoc_drive_t drive;

int main(void)
{
    (void)qfoc_drive_init(&drive, &qfoc_params_reference);
    /* any number of calls, in any order: EVA computes an invariant over every state
       the drive can reach, whatever the interleaving of fast steps and ticks (the port
       calls 8 or 16 fast steps per tick; a missed or late call is covered too) */
    while (eva_u8 != 0u) {
        if (eva_u8 != 0u) {
            qfoc_adc_t adc;
            adc.iu = eva_u16;
            adc.iv = eva_u16;
            adc.vdc = eva_u16;
            (void)qfoc_drive_fast_step(&drive, &adc);
        } else {
            qfoc_tick_in_t in;
            uint8_t rx[QFOC_LIN_FRAME_MAX];
            uint32_t j;
            for (j = 0u; j < QFOC_LIN_FRAME_MAX; j++) {
                rx[j] = eva_u8;
            }
            in.t_ipm = eva_i16;
            in.t_pcb = eva_i16;
            in.rx = rx;
            in.rx_len = (uint8_t)(eva_u8 % (QFOC_LIN_FRAME_MAX + 1u));
            (void)qfoc_drive_tick(&drive, &in);
        }
    }
    return 0;
}
