/**
 * @file harness.h
 * @brief Target side of the instruction bench (Cortex-M4F, run in the instruction
 *        counter tools/bench/count.py): instances of the library's stateful blocks
 *        initialised from the reference parameter table, a drive object, scratch memory
 *        for the arguments the counter passes by pointer, and the replay of a recorded
 *        closed-loop run (replay.h) that brings the drive into a given state.
 *
 * The counter calls the library functions themselves from their symbol addresses with
 * these objects as arguments; the harness functions run uncounted, between measurements.
 */
#ifndef QFOC_BENCH_HARNESS_H
#define QFOC_BENCH_HARNESS_H

#include "qfoc/drive.h"
#include "qfoc/emf.h"
#include "qfoc/vector.h"
#include "qfoc/transforms.h"
#include "qfoc/trig.h"
#include "replay.h"

/** Indices of bench_info[]. */
#define BENCH_INFO_VERSION          0u   /**< layout of this table: 1 */
#define BENCH_INFO_SIZEOF_DRIVE     1u   /**< sizeof(qfoc_drive_t): RAM per motor */
#define BENCH_INFO_SIZEOF_TABLE     2u   /**< sizeof(qfoc_param_table_t) */
#define BENCH_INFO_SVPWM_OFF        3u   /**< offsetof(qfoc_param_table_t, svpwm) */
#define BENCH_INFO_RESERVED         4u   /**< 0 */
#define BENCH_INFO_SIZEOF_FAST      5u   /**< sizeof(qfoc_drive_fast_t) */
#define BENCH_INFO_SIZEOF_SLOW      6u   /**< sizeof(qfoc_drive_slow_t) */
#define BENCH_INFO_SIZEOF_SV_OUT    7u   /**< sizeof(qfoc_svpwm_out_t) */
#define BENCH_INFO_SIZEOF_PLL_OUT   8u   /**< sizeof(qfoc_pll_out_t) */
#define BENCH_INFO_SIZEOF_TICK_IN   9u   /**< sizeof(qfoc_tick_in_t) */
#define BENCH_INFO_SIZEOF_TICK_OUT 10u   /**< sizeof(qfoc_tick_out_t) */
#define BENCH_INFO_TICK_TX_LEN    11u   /**< offsetof(qfoc_tick_out_t, tx_len) */
#define BENCH_INFO_TICK_CAN_SEND  12u   /**< offsetof(qfoc_tick_out_t, can_send) */
#define BENCH_INFO_N               13u

/** Sizes and addresses the counter reads from the ELF (no layout is hard-coded there). */
extern const uint32_t bench_info[BENCH_INFO_N];

/** Probe of the drive's state (bench_probe()), same order as bench_rec_hdr_t.probe. */
#define BENCH_PROBE_N 8u

/* Instances for the function benches. */
extern qfoc_pi_t bench_pi;              /**< the q-current PI of the table */
extern qfoc_lpf_t bench_lpf;            /**< the DC-bus low-pass of the table */
extern qfoc_flux_t bench_flux;          /**< flux observer */
extern qfoc_pll_t bench_pll;            /**< PLL */
extern qfoc_fw_t bench_fw;              /**< field weakening */
extern qfoc_trqcomp_t bench_tc;         /**< torque compensation */
extern qfoc_mech_t bench_mech;          /**< mechanical angle */
extern qfoc_phase_mon_t bench_phase;    /**< phase-loss monitor */
extern qfoc_drive_t bench_drive;        /**< one motor */
extern uint32_t bench_arg[64];          /**< arguments passed by pointer (256 bytes) */
extern uint32_t bench_res[64];          /**< results returned through pointers */
extern int32_t bench_probe_out[BENCH_PROBE_N];  /**< written by bench_probe() */
extern qfoc_tick_in_t bench_tick_in;    /**< written by bench_tick_input() */
/** The reference table's I_base (mA), f_base (mHz) and pole pairs, set by bench_setup(). */
extern uint32_t bench_scale[3];

/**
 * @brief Initialise every instance above from the reference table (as the drive does),
 *        and the drive with qfoc_drive_init().
 * @return the drive's initialisation status (QFOC_PARAMS_OK expected).
 */
int32_t bench_setup(void);

/**
 * @brief Replay periods [first, first + count) of a recording into bench_drive: each
 *        period's fast step with its samples, and the tick after every periods_per_ms-th
 *        period, as the host run did.
 * @param[in] rec   the recording (replay.h), in memory as written
 * @param[in] first first period
 * @param[in] count number of periods
 * @return the number of periods whose output (compare values and enable) differs from
 *         the host build's; 0xFFFFFFFF when the recording is malformed or the range is
 *         outside it.
 */
uint32_t bench_replay(const bench_rec_hdr_t *rec, uint32_t first, uint32_t count);

/**
 * @brief Fill bench_tick_in with the inputs of tick ms of a recording.
 * @return &bench_tick_in, or a null pointer when ms is outside the recording.
 */
const qfoc_tick_in_t *bench_tick_input(const bench_rec_hdr_t *rec, uint32_t ms);

/**
 * @brief The drive's state into bench_probe_out: state, sub-state, id_fw, utilisation,
 *        speed_f, torque-compensation a[0], b[0], iq_ref.
 */
void bench_probe(void);

#endif /* QFOC_BENCH_HARNESS_H */
