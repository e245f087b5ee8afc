/**
 * @file replay.h
 * @brief Layout of a bench replay file: the inputs of a closed-loop run of the drive on
 *        the plant model (ADC samples of every PWM period, tick inputs of every
 *        millisecond) with the outputs the host build of the library gave, so that the
 *        target build can be driven into the same state and checked against it.
 *
 * Written by tools/bench/gen_replay.c (host), read by tools/bench/harness.c (target, in
 * the instruction counter) and tools/bench/count.py.  Every field is little-endian and
 * naturally aligned; the file is placed in memory as it is.
 *
 *   bench_rec_hdr_t                       header (96 bytes)
 *   bench_rec_period_t [n_periods]        at hdr.period_off
 *   bench_rec_tick_t   [n_ticks]          at hdr.tick_off
 *
 * The tick of millisecond m runs after the fast step of period
 * (m + 1) x periods_per_ms - 1, as in sim/drive_sim.c.
 */
#ifndef QFOC_BENCH_REPLAY_H
#define QFOC_BENCH_REPLAY_H

#include <stdint.h>

/** ASCII "QBRP" read as a little-endian uint32_t. */
#define BENCH_REC_MAGIC ((uint32_t)0x50524251u)
/** Layout version. */
#define BENCH_REC_VERSION ((uint32_t)1u)

/** File header. */
typedef struct {
    uint32_t magic;           /**< BENCH_REC_MAGIC */
    uint32_t version;         /**< BENCH_REC_VERSION */
    uint32_t n_periods;       /**< PWM periods recorded */
    uint32_t n_ticks;         /**< ticks recorded, n_periods / periods_per_ms */
    uint32_t periods_per_ms;  /**< f_pwm / 1 kHz */
    uint32_t period_off;      /**< byte offset of the period records */
    uint32_t tick_off;        /**< byte offset of the tick records */
    uint32_t warm_periods;    /**< periods before the measured window (a multiple of
                                   periods_per_ms) */
    int32_t probe[8];         /**< host drive at the end of the warm-up: state, sub,
                                   id_fw, utilisation, speed_f, tc a[0], tc b[0], iq_ref */
    int32_t probe_end[8];     /**< the same at the end of the recording */
} bench_rec_hdr_t;

/** One PWM period: the ADC samples and the host's output for them. */
typedef struct {
    uint16_t iu;       /**< phase u current code */
    uint16_t iv;       /**< phase v current code */
    uint16_t vdc;      /**< DC-bus code */
    uint16_t cmp[3];   /**< compare values the host build returned */
    uint16_t enable;   /**< PWM enable the host build returned (0 / 1) */
    uint16_t pad;      /**< 0 */
} bench_rec_period_t;

/** One tick's inputs. */
typedef struct {
    int16_t t_ipm;     /**< IPM temperature, 0.1 degC */
    int16_t t_pcb;     /**< PCB temperature, 0.1 degC */
    uint8_t rx_len;    /**< frame length, 0 = none */
    uint8_t rx[11];    /**< frame bytes */
} bench_rec_tick_t;

#endif /* QFOC_BENCH_REPLAY_H */
