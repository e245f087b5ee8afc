/**
 * @file hal_s32k.c
 * @brief The run-time half of the S32K144 port: the functions of include/qfoc/hal.h
 *        (PWM, ADC, temperatures, LIN-style UART frames, CAN, time base, watchdog,
 *        fault output) and the UART interrupt.
 *
 * Data shared between interrupt contexts (priorities: ADC > FTM > 1 ms tick > UART):
 *   - the slow-channel codes: written by the ADC interrupt, read by the tick (16-bit);
 *   - the received frame: filled by the UART interrupt while rx_ready is false, then
 *     rx_ready set last; the tick copies it and clears rx_ready (the tick pre-empts the
 *     UART interrupt, never the reverse);
 *   - the frame to send: filled by the tick while tx_busy is false, then tx_busy set
 *     last; the UART interrupt sends it and clears tx_busy after the last stop bit;
 *   - the millisecond counter and the PWM-period counter: one writer each;
 *   - the sensing (two sensors or single shunt) and the DC-link offset: written at set-up
 *     (qfoc_s32k_hal_init*, qfoc_s32k_shunt_offset_set before the interrupts run or from
 *     the ADC interrupt's own context), read by the ADC interrupt.
 *
 * Single-shunt sensing (qfoc_s32k_hal_init_shunt, after qfoc_s32k_ftm_init_shunt and
 * qfoc_s32k_pdb_init_shunt): FTM3 counts up from 0 to 2 period - 1 with the pairs combined,
 * phase k high for C(2k)V <= counter < C(2k+1)V (s32k144_port.h); PDB0's CH0DLY0 and
 * CH0DLY1 are the two sampling instants (counter values); ADC0 R[A], R[B] the two DC-link
 * samples and R[C] T_IPM.
 *
 * Requirements: REQ-PORT-007, -008, -010 .. -014, -018, -020, -021 (specs/requirements/port.md).
 */
#include "qfoc/hal.h"
#include "qfoc/q15.h"
#include "s32k144_port.h"
#include "s32k144_regs.h"

/* ------------------------------------------------------------------ state */
typedef struct {
    uint16_t period;                  /* FTM_MOD: largest compare value */
    bool fault;                       /* fault output latched (until reset) */
    bool trip_reported;               /* the latched FTM fault was reported to the drive */
    volatile uint16_t t_ipm_code;     /* slow channels, latest codes (ADC interrupt) */
    volatile uint16_t t_pcb_code;
    volatile uint32_t ms;             /* millisecond counter (tick) */
    volatile bool ms_flag;            /* set by the tick, taken by the background */
    volatile uint32_t periods;        /* PWM periods (FTM interrupt) */
    bool shunt;                       /* single-shunt sensing: pairs combined, PDB0 instants */
    uint16_t shunt_offset;            /* ADC code of zero DC-link current */
    uint32_t t_ipm_result;            /* ADC0 result register of T_IPM: R[B], R[C] with the shunt */
    /* receive, UART interrupt */
    uint8_t rx_buf[QFOC_LIN_FRAME_MAX];
    uint8_t rx_len;
    bool rx_bad;
    uint16_t rx_dropped;
    /* received frame handed to the tick (volatile: its stores stay before rx_ready's) */
    volatile uint8_t rx_frame[QFOC_LIN_FRAME_MAX];
    volatile uint8_t rx_frame_len;
    volatile bool rx_ready;
    /* transmit: buffer written by the tick, position by the UART interrupt */
    uint8_t tx_buf[QFOC_LIN_FRAME_MAX];
    uint8_t tx_len;
    uint8_t tx_pos;
    volatile bool tx_busy;
} qfoc_s32k_hal_t;

static qfoc_s32k_hal_t s_hal;

void qfoc_s32k_hal_init(uint16_t period)
{
    uint32_t k;
    s_hal.period = period;
    s_hal.fault = false;
    s_hal.trip_reported = false;
    s_hal.t_ipm_code = 0u;
    s_hal.t_pcb_code = 0u;
    s_hal.ms = 0u;
    s_hal.ms_flag = false;
    s_hal.periods = 0u;
    s_hal.shunt = false;
    s_hal.shunt_offset = QFOC_ADC_MID;
    s_hal.t_ipm_result = S32K_ADC0_BASE + S32K_ADC_RA + 4u;
    s_hal.rx_len = 0u;
    s_hal.rx_bad = false;
    s_hal.rx_dropped = 0u;
    s_hal.rx_frame_len = 0u;
    s_hal.rx_ready = false;
    s_hal.tx_len = 0u;
    s_hal.tx_pos = 0u;
    s_hal.tx_busy = false;
    for (k = 0u; k < QFOC_LIN_FRAME_MAX; k++) {
        s_hal.rx_buf[k] = 0u;
        s_hal.rx_frame[k] = 0u;
        s_hal.tx_buf[k] = 0u;
    }
}

void qfoc_s32k_hal_init_shunt(uint16_t period)
{
    qfoc_s32k_hal_init(period);
    s_hal.shunt = true;
    s_hal.t_ipm_result = S32K_ADC0_BASE + S32K_ADC_RA + 8u;
}

void qfoc_s32k_shunt_offset_set(uint16_t code)
{
    s_hal.shunt_offset = (code > QFOC_ADC_MAX) ? QFOC_ADC_MAX : code;
}

/* ------------------------------------------------------------------ PWM and ADC */

/* A compare value as the PWM applies it: at most the period. */
static uint32_t s32k_cmp(uint16_t v)
{
    uint32_t c = (uint32_t)v;
    if (c > (uint32_t)s_hal.period) {
        c = (uint32_t)s_hal.period;
    } else {
        /* within the period */
    }
    return c;
}

/* Combined pairs (single shunt): phase k high from period - up[k] to period + down[k]
   (up, down <= period), loaded at the next reload point. */
static void s32k_pwm_combined(const uint32_t up[3], const uint32_t down[3])
{
    const uint32_t p = (uint32_t)s_hal.period;
    uint32_t k;
    for (k = 0u; k < 3u; k++) {
        s32k_write(S32K_FTM3_C0V + (16u * k), p - up[k]);
        s32k_write(S32K_FTM3_C0V + (16u * k) + 8u, p + down[k]);
    }
    s32k_write(S32K_FTM3_PWMLOAD, S32K_FTM_PWMLOAD_LDOK);
}

/* The output enable (at once) and the clearing of a reported hardware trip. */
static void s32k_pwm_outputs(bool enable)
{
    if (enable && (!s_hal.fault)) {
        s32k_write(S32K_FTM3_OUTMASK, 0u);
    } else {
        const uint32_t fms = s32k_read(S32K_FTM3_FMS);
        s32k_write(S32K_FTM3_OUTMASK, QFOC_S32K_PWM_CH_MASK);
        /* A hardware trip is cleared only here, only once it was reported to the drive
           (qfoc_hal_adc_read), with the outputs masked and the fault input inactive.  The
           tick calls this function too (the second path to the safe state): before the
           report it leaves the flag set, so the next fast step still sees the trip. */
        if (((fms & S32K_FTM_FMS_FAULTF) != 0u) && ((fms & S32K_FTM_FMS_FAULTIN) == 0u) &&
            s_hal.trip_reported) {
            s32k_write(S32K_FTM3_FMS, fms & ~S32K_FTM_FMS_FLAGS);
            s_hal.trip_reported = false;
        } else {
            /* no flag, the comparator still signals over-current, or not yet reported */
        }
    }
}

void qfoc_hal_pwm_write(const qfoc_pwm_t *pwm)
{
    uint32_t k;
    if (s_hal.shunt) {
        /* combined pairs: the symmetric pulse, up = down = cmp; the sampling instants stay */
        uint32_t c[3];
        for (k = 0u; k < 3u; k++) {
            c[k] = s32k_cmp(pwm->cmp[k]);
        }
        s32k_pwm_combined(c, c);
    } else {
        for (k = 0u; k < 3u; k++) {
            /* Phase k drives the pair (2k, 2k+1); the even channel's CnV sets both. */
            s32k_write(S32K_FTM3_C0V + (16u * k), s32k_cmp(pwm->cmp[k]));
        }
        s32k_write(S32K_FTM3_PWMLOAD, S32K_FTM_PWMLOAD_LDOK);
    }
    s32k_pwm_outputs(pwm->enable);
}

/* A plan the combined pairs and PDB0 can apply as it stands: ok, every compare value
   within the period, the instants in order within the up-counting half (as
   qfoc_shunt_plan() gives them for a configuration of this period). */
static bool s32k_plan_usable(const qfoc_shunt_plan_t *plan)
{
    const uint16_t p = s_hal.period;
    bool in_range = true;
    uint32_t k;
    for (k = 0u; k < 3u; k++) {
        if ((plan->up[k] > p) || (plan->down[k] > p)) {
            in_range = false;
        } else {
            /* applicable */
        }
    }
    return plan->ok && in_range && (plan->trig[0] < plan->trig[1]) && (plan->trig[1] < p);
}

void qfoc_hal_pwm_write_shunt(const qfoc_pwm_t *pwm, const qfoc_shunt_plan_t *plan)
{
    if (s_hal.shunt) {
        const uint32_t p = (uint32_t)s_hal.period;
        uint32_t up[3];
        uint32_t down[3];
        uint32_t dly0;
        uint32_t dly1;
        uint32_t k;
        if (s32k_plan_usable(plan)) {
            for (k = 0u; k < 3u; k++) {
                up[k] = (uint32_t)plan->up[k];
                down[k] = (uint32_t)plan->down[k];
            }
            /* PDB0 counts from CNTIN on the FTM3 clock: an instant is its delay. */
            dly0 = (uint32_t)plan->trig[0];
            dly1 = (uint32_t)plan->trig[1];
        } else {
            for (k = 0u; k < 3u; k++) {
                up[k] = s32k_cmp(pwm->cmp[k]);
                down[k] = up[k];
            }
            dly0 = p / QFOC_S32K_SHUNT_IDLE_DIV0;
            dly1 = p / QFOC_S32K_SHUNT_IDLE_DIV1;
        }
        s32k_pwm_combined(up, down);
        /* The instants of the next period: loaded when PDB0's counter reaches its MOD, at
           the end of this period (LDMOD = 01, qfoc_s32k_pdb_init_shunt). */
        s32k_write(S32K_PDB0_BASE + S32K_PDB_CH0DLY0, dly0);
        s32k_write(S32K_PDB0_BASE + S32K_PDB_CH0DLY0 + 4u, dly1);
        s32k_write(S32K_PDB0_BASE + S32K_PDB_SC, S32K_PDB_SC_PDBEN | S32K_PDB_SC_LDOK |
                   s32k_fld(S32K_PDB_LDMOD_AT_MOD, S32K_PDB_SC_LDMOD_SHIFT, S32K_PDB_SC_LDMOD_MASK));
        s32k_pwm_outputs(pwm->enable);
    } else {
        /* two phase-current sensors: no asymmetric PWM, no instants to set */
        qfoc_hal_pwm_write(pwm);
    }
}

void qfoc_hal_adc_read(qfoc_adc_t *adc)
{
    const uint32_t fms = s32k_read(S32K_FTM3_FMS);
    adc->iu = (uint16_t)(s32k_read(S32K_ADC0_BASE + S32K_ADC_RA) & S32K_ADC_R_MASK);
    if (s_hal.shunt) {
        /* the second DC-link sample: read (which acknowledges it), not used */
        (void)s32k_read(S32K_ADC0_BASE + S32K_ADC_RA + 4u);
    } else {
        /* R[B] is T_IPM */
    }
    s_hal.t_ipm_code = (uint16_t)(s32k_read(s_hal.t_ipm_result) & S32K_ADC_R_MASK);
    adc->iv = (uint16_t)(s32k_read(S32K_ADC1_BASE + S32K_ADC_RA) & S32K_ADC_R_MASK);
    s_hal.t_pcb_code = (uint16_t)(s32k_read(S32K_ADC1_BASE + S32K_ADC_RA + 4u) & S32K_ADC_R_MASK);
    adc->vdc = (uint16_t)(s32k_read(S32K_ADC1_BASE + S32K_ADC_RA + 8u) & S32K_ADC_R_MASK);
    if (((fms & S32K_FTM_FMS_FAULTF) != 0u) && (!s_hal.trip_reported)) {
        adc->iu = QFOC_ADC_MAX;
        adc->iv = QFOC_ADC_MAX;
        s_hal.trip_reported = true;
    } else {
        /* no new hardware trip */
    }
}

/* A DC-link sample in Q15 of the current base, as the drive scales its phase currents:
   (code - offset) x 16, saturated. */
static qfoc_q15_t s32k_shunt_sample(uint32_t result)
{
    const uint16_t code = (uint16_t)(s32k_read(result) & S32K_ADC_R_MASK);
    const int32_t d = (int32_t)code - (int32_t)s_hal.shunt_offset;
    return qfoc_q15_sat(d * QFOC_S32K_I_PER_CODE);
}

void qfoc_hal_adc_read_shunt(qfoc_adc_t *adc, qfoc_q15_t sample[2])
{
    const uint32_t fms = s32k_read(S32K_FTM3_FMS);
    /* Every result is read, which acknowledges its conversion (COCO). */
    const qfoc_q15_t s1 = s32k_shunt_sample(S32K_ADC0_BASE + S32K_ADC_RA);
    const qfoc_q15_t s2 = s32k_shunt_sample(S32K_ADC0_BASE + S32K_ADC_RA + 4u);
    if (s_hal.shunt) {
        sample[0] = s1;
        sample[1] = s2;
    } else {
        sample[0] = 0;   /* two phase-current sensors: no DC-link channel converted */
        sample[1] = 0;
    }
    s_hal.t_ipm_code = (uint16_t)(s32k_read(s_hal.t_ipm_result) & S32K_ADC_R_MASK);
    (void)s32k_read(S32K_ADC1_BASE + S32K_ADC_RA);   /* i_v: not used */
    s_hal.t_pcb_code = (uint16_t)(s32k_read(S32K_ADC1_BASE + S32K_ADC_RA + 4u) & S32K_ADC_R_MASK);
    adc->vdc = (uint16_t)(s32k_read(S32K_ADC1_BASE + S32K_ADC_RA + 8u) & S32K_ADC_R_MASK);
    adc->iu = QFOC_ADC_MID;   /* the code of 0 A: no phase sensor */
    adc->iv = QFOC_ADC_MID;
    if (((fms & S32K_FTM_FMS_FAULTF) != 0u) && (!s_hal.trip_reported)) {
        /* reported once, as full scale: both samples and both phase currents */
        sample[0] = QFOC_Q15_MAX;
        sample[1] = QFOC_Q15_MAX;
        adc->iu = QFOC_ADC_MAX;
        adc->iv = QFOC_ADC_MAX;
        s_hal.trip_reported = true;
    } else {
        /* no new hardware trip */
    }
}

/* ------------------------------------------------------------------ temperatures */


/* NTC curve, 0.1 degC, at codes 16 k (k = 0 .. 256): T = 1 / (1/298.15 K + ln(R/R25)/B)
   - 273.15 K with R = 10 kOhm code / (4096 - code), R25 = 10 kOhm, B = 3435 K, rounded.
   The entries are not saturated (301.3 degC at code 16, -63.3 degC at code 4064), so that
   the interpolation near the ends stays on the curve; the result is saturated.  Entry 0
   (code 0, a shorted sensor) is 200.0 degC and entry 256 (code 4096) -100.0 degC; codes
   above QFOC_S32K_NTC_OPEN_CODE never reach the table.  Linear interpolation between
   entries is within 0.2 degC of the curve from -40 to 150 degC, 0.4 degC to 180 degC and
   0.8 degC to 200 degC (tests/test_port.c measures it). */
int16_t qfoc_s32k_ntc_to_dc(uint16_t code)
{
    static const int16_t ntc[257] = {
        2000, 3013, 2413, 2116, 1924, 1785, 1677, 1590, 1516, 1453, 1398, 1349, 1306,
        1266, 1230, 1197, 1166, 1138, 1111, 1086, 1063, 1041, 1020, 1000, 981, 963,
        946, 929, 913, 898, 884, 870, 856, 843, 830, 818, 806, 794, 783,
        772, 761, 751, 741, 731, 721, 712, 703, 694, 685, 676, 668, 659,
        651, 643, 636, 628, 620, 613, 606, 598, 591, 584, 578, 571, 564,
        558, 551, 545, 539, 532, 526, 520, 514, 508, 503, 497, 491, 486,
        480, 474, 469, 464, 458, 453, 448, 443, 437, 432, 427, 422, 417,
        412, 408, 403, 398, 393, 388, 384, 379, 374, 370, 365, 361, 356,
        352, 347, 343, 338, 334, 329, 325, 321, 316, 312, 308, 304, 299,
        295, 291, 287, 283, 279, 274, 270, 266, 262, 258, 254, 250, 246,
        242, 238, 234, 230, 226, 222, 218, 214, 210, 206, 202, 198, 194,
        190, 186, 182, 178, 175, 171, 167, 163, 159, 155, 151, 147, 143,
        139, 135, 131, 127, 123, 119, 115, 112, 108, 104, 100, 96, 92,
        88, 83, 79, 75, 71, 67, 63, 59, 55, 51, 47, 42, 38,
        34, 30, 25, 21, 17, 13, 8, 4, -1, -5, -10, -14, -19,
        -23, -28, -32, -37, -42, -47, -51, -56, -61, -66, -71, -76, -81,
        -87, -92, -97, -103, -108, -114, -119, -125, -131, -137, -143, -149, -155,
        -161, -168, -174, -181, -188, -195, -202, -209, -217, -224, -232, -241, -249,
        -258, -267, -276, -286, -296, -306, -317, -329, -341, -354, -368, -383, -399,
        -416, -435, -456, -479, -506, -539, -579, -633, -718, -1000
    };
    int16_t t;
    if (code > QFOC_S32K_NTC_OPEN_CODE) {
        t = QFOC_S32K_TEMP_FAIL;  /* open sensor: reported hot */
    } else {
        const uint32_t k = (uint32_t)code / 16u;   /* 0 .. 254 */
        const uint32_t fu = (uint32_t)code % 16u;  /* 0 .. 15 */
        const int32_t f = (int32_t)fu;
        const int32_t a = (int32_t)ntc[k];
        const int32_t b = (int32_t)ntc[k + 1u];
        /* |b - a| <= 1013, f <= 15: no overflow; the division truncates towards a. */
        int32_t v = a + (((b - a) * f) / 16);
        if (v > (int32_t)QFOC_S32K_TEMP_FAIL) {
            v = (int32_t)QFOC_S32K_TEMP_FAIL;     /* above 200 degC, or shorted */
        } else if (v < (int32_t)QFOC_S32K_TEMP_MIN) {
            v = (int32_t)QFOC_S32K_TEMP_MIN;      /* below -40 degC */
        } else {
            /* on the curve */
        }
        t = (int16_t)v;
    }
    return t;
}

void qfoc_hal_temps_read(int16_t *t_ipm, int16_t *t_pcb)
{
    *t_ipm = qfoc_s32k_ntc_to_dc(s_hal.t_ipm_code);
    *t_pcb = qfoc_s32k_ntc_to_dc(s_hal.t_pcb_code);
}

/* ------------------------------------------------------------------ LIN-style UART */

uint8_t qfoc_hal_lin_receive(uint8_t *buf, uint8_t size)
{
    uint8_t n = 0u;
    if (s_hal.rx_ready) {
        const uint8_t len = s_hal.rx_frame_len;
        if ((len <= size) && (len <= QFOC_LIN_FRAME_MAX)) {
            uint8_t k;
            for (k = 0u; k < len; k++) {
                buf[k] = s_hal.rx_frame[k];
            }
            n = len;
        } else {
            /* does not fit: dropped */
        }
        s_hal.rx_ready = false;
    } else {
        /* nothing completed */
    }
    return n;
}

bool qfoc_hal_lin_transmit(const uint8_t *buf, uint8_t len)
{
    bool queued = false;
    if ((len > 0u) && (len <= QFOC_LIN_FRAME_MAX) && (!s_hal.tx_busy)) {
        uint8_t k;
        for (k = 0u; k < len; k++) {
            s_hal.tx_buf[k] = buf[k];
        }
        s_hal.tx_len = len;
        s_hal.tx_pos = 0u;
        s_hal.tx_busy = true;
        /* A break first (toggling SBK queues one break character), then the bytes from
           the transmit interrupt. */
        s32k_modify(S32K_LPUART1_CTRL, 0u, S32K_LPUART_CTRL_SBK);
        s32k_modify(S32K_LPUART1_CTRL, S32K_LPUART_CTRL_SBK, S32K_LPUART_CTRL_TIE);
        queued = true;
    } else {
        /* refused: empty, too long, or the previous frame still on the line */
    }
    return queued;
}

/* End of a received frame: hand it to the tick when it is clean and the previous one
   was taken; start the next one. */
static void s32k_rx_close(void)
{
    if (s_hal.rx_len > 0u) {
        if ((!s_hal.rx_bad) && (!s_hal.rx_ready)) {
            uint8_t k;
            for (k = 0u; k < s_hal.rx_len; k++) {
                s_hal.rx_frame[k] = s_hal.rx_buf[k];
            }
            s_hal.rx_frame_len = s_hal.rx_len;
            s_hal.rx_ready = true;
        } else if (s_hal.rx_dropped < 0xFFFFu) {
            s_hal.rx_dropped++;
        } else {
            /* saturated */
        }
    } else {
        /* an idle line without bytes */
    }
    s_hal.rx_len = 0u;
    s_hal.rx_bad = false;
}

void qfoc_s32k_uart_isr(void)
{
    const uint32_t stat = s32k_read(S32K_LPUART1_STAT);
    const uint32_t ctrl = s32k_read(S32K_LPUART1_CTRL);
    const uint32_t errors = S32K_LPUART_STAT_FE | S32K_LPUART_STAT_NF | S32K_LPUART_STAT_PF |
                            S32K_LPUART_STAT_OR;
    uint32_t clear = 0u;

    if ((stat & S32K_LPUART_STAT_LBKDIF) != 0u) {
        /* LIN break: a new frame starts (our own break is an echo). */
        clear |= S32K_LPUART_STAT_LBKDIF;
        s_hal.rx_len = 0u;
        s_hal.rx_bad = s_hal.tx_busy;
    } else {
        /* no break */
    }
    if ((stat & errors) != 0u) {
        clear |= (stat & errors);
        s_hal.rx_bad = true;
    } else {
        /* clean */
    }
    if ((stat & S32K_LPUART_STAT_RDRF) != 0u) {
        const uint8_t byte = (uint8_t)(s32k_read(S32K_LPUART1_DATA) & S32K_LPUART_DATA_MASK);
        if (s_hal.tx_busy) {
            s_hal.rx_bad = true;  /* echo of the own transmission, or a collision */
        } else {
            /* a byte of the master */
        }
        if (s_hal.rx_len < QFOC_LIN_FRAME_MAX) {
            s_hal.rx_buf[s_hal.rx_len] = byte;
            s_hal.rx_len++;
        } else {
            s_hal.rx_bad = true;  /* longer than any frame */
        }
    } else {
        /* no byte */
    }
    if ((stat & S32K_LPUART_STAT_IDLE) != 0u) {
        clear |= S32K_LPUART_STAT_IDLE;
        s32k_rx_close();
    } else {
        /* line busy */
    }
    if (clear != 0u) {
        /* Write 1 to the flags to clear only; keep the configuration bits of STAT. */
        s32k_write(S32K_LPUART1_STAT, (stat & ~S32K_LPUART_STAT_W1C) | clear);
    } else {
        /* nothing to clear */
    }

    if (((ctrl & S32K_LPUART_CTRL_TIE) != 0u) && ((stat & S32K_LPUART_STAT_TDRE) != 0u)) {
        if (s_hal.tx_pos < s_hal.tx_len) {
            s32k_write(S32K_LPUART1_DATA, (uint32_t)s_hal.tx_buf[s_hal.tx_pos]);
            s_hal.tx_pos++;
        } else {
            /* all written */
        }
        if (s_hal.tx_pos >= s_hal.tx_len) {
            s32k_modify(S32K_LPUART1_CTRL, S32K_LPUART_CTRL_TIE, S32K_LPUART_CTRL_TCIE);
        } else {
            /* more to send */
        }
    } else if (((ctrl & S32K_LPUART_CTRL_TCIE) != 0u) && ((stat & S32K_LPUART_STAT_TC) != 0u)) {
        s32k_modify(S32K_LPUART1_CTRL, S32K_LPUART_CTRL_TCIE, 0u);
        s_hal.tx_busy = false;  /* last: the tick may queue the next frame */
    } else {
        /* no transmit event */
    }
}

/* ------------------------------------------------------------------ CAN */

bool qfoc_hal_can_send(const qfoc_can_frame_t *frame)
{
    const uint32_t code = (s32k_read(S32K_CAN0_MB0_CS) & S32K_CAN_CS_CODE_MASK) >> S32K_CAN_CS_CODE_SHIFT;
    bool sent = false;
    if (code != S32K_CAN_CODE_TX_DATA) {
        const uint32_t dlc = (frame->dlc > 8u) ? 8u : (uint32_t)frame->dlc;
        const uint8_t *const d = frame->data;
        s32k_write(S32K_CAN0_MB0_CS, (uint32_t)S32K_CAN_CODE_TX_INACTIVE << S32K_CAN_CS_CODE_SHIFT);
        s32k_write(S32K_CAN0_MB0_ID, ((uint32_t)frame->id & 0x7FFu) << S32K_CAN_ID_STD_SHIFT);
        s32k_write(S32K_CAN0_MB0_DATA0, ((uint32_t)d[0] << 24u) | ((uint32_t)d[1] << 16u) |
                                        ((uint32_t)d[2] << 8u) | (uint32_t)d[3]);
        s32k_write(S32K_CAN0_MB0_DATA1, ((uint32_t)d[4] << 24u) | ((uint32_t)d[5] << 16u) |
                                        ((uint32_t)d[6] << 8u) | (uint32_t)d[7]);
        s32k_write(S32K_CAN0_IFLAG1, S32K_CAN_IFLAG1_BUF0I);
        /* CODE last: the controller arbitrates from this write on. */
        s32k_write(S32K_CAN0_MB0_CS, ((uint32_t)S32K_CAN_CODE_TX_DATA << S32K_CAN_CS_CODE_SHIFT) |
                                     (dlc << S32K_CAN_CS_DLC_SHIFT));
        sent = true;
    } else {
        /* the previous frame is still pending */
    }
    return sent;
}

/* ------------------------------------------------------------------ time base, watchdog */

uint32_t qfoc_hal_ms_tick(void)
{
    s32k_write(S32K_LPIT0_MSR, S32K_LPIT_CH0);  /* TIF0, write 1 to clear */
    s_hal.ms = s_hal.ms + 1u;
    s_hal.ms_flag = true;
    return s_hal.ms;
}

uint32_t qfoc_hal_ms_count(void)
{
    return s_hal.ms;
}

bool qfoc_hal_ms_flag_take(void)
{
    const bool f = s_hal.ms_flag;
    if (f) {
        s_hal.ms_flag = false;
    } else {
        /* no tick since the last take */
    }
    return f;
}

/* FTM3 period interrupt: clear TOF and RF (read, then write 0), count the period. */
void qfoc_s32k_ftm_period_ack(void)
{
    const uint32_t sc = s32k_read(S32K_FTM3_SC);
    s32k_write(S32K_FTM3_SC, sc & ~(S32K_FTM_SC_TOF | S32K_FTM_SC_RF));
    s_hal.periods = s_hal.periods + 1u;
}

uint32_t qfoc_hal_pwm_periods(void)
{
    return s_hal.periods;
}

void qfoc_hal_watchdog_refresh(void)
{
    s32k_write(S32K_WDOG_CNT, S32K_WDOG_REFRESH_KEY);
}

/* ------------------------------------------------------------------ fault output */

void qfoc_hal_fault_output(void)
{
    s_hal.fault = true;
    s32k_write(S32K_FTM3_OUTMASK, QFOC_S32K_PWM_CH_MASK);
    qfoc_s32k_gate_enable(false);
}

bool qfoc_hal_fault_latched(void)
{
    return s_hal.fault;
}

uint16_t qfoc_s32k_lin_dropped(void)
{
    return s_hal.rx_dropped;
}
