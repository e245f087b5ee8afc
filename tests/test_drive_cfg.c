/*
 * tests/test_drive_cfg.c -- the drive configuration range check
 * (include/qfoc/drive_cfg.h, src/qfoc_drive_cfg.c).
 *
 * The reference is a range table written here from the field comments of drive_cfg.h
 * (section F of the drive interfaces): for every field its lowest and highest accepted
 * value, with the three relations (rpm_min <= rpm_max, tc_speed_min <= tc_speed_max,
 * lin_id_status != lin_id_cmd) written out separately.  Every field is tested at its
 * lowest and highest accepted value and one step outside each (where the type can hold
 * it); random configurations, about half of them valid, are compared with the
 * reference check.
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>
#include <string.h>

#include "qfoc/drive_cfg.h"
#include "test_util.h"

typedef enum { T_U8, T_U16, T_I16 } ftype_t;

typedef struct {
    const char *name;
    size_t off;
    ftype_t type;
    int32_t lo;   /* lowest accepted value (drive_cfg.h) */
    int32_t hi;   /* highest accepted value */
} fdesc_t;

#define FD(m, t, lo, hi) { #m, offsetof(qfoc_drive_cfg_t, m), (t), (lo), (hi) }

/* drive_cfg.h, field by field; rpm_min, rpm_max, tc_speed_min, lin_id_status have a
   bound set by another field: listed with their widest range, the relation below */
static const fdesc_t fields[] = {
    FD(pole_pairs, T_U8, 1, 16),
    FD(k_rpm, T_U16, 1, 65535),
    FD(k_speed_rpm, T_U16, 1, 65535),
    FD(rpm_min, T_U16, 1, 65535),
    FD(rpm_max, T_U16, 1, 65535),
    FD(speed_ramp, T_I16, 1, 32767),
    FD(precharge_ms, T_U16, 1, 60000),
    FD(offset_shift, T_U8, 4, 10),
    FD(offset_window, T_U16, 0, 2047),
    FD(i_align, T_I16, 1, 32767),
    FD(align_ms, T_U16, 2, 60000),
    FD(i_start, T_I16, 1, 32767),
    FD(of_accel, T_I16, 1, 32767),
    FD(of_speed, T_I16, 1, 32767),
    FD(ho_angle, T_U16, 1, 16384),
    FD(ho_dwell_ms, T_U16, 1, 60000),
    FD(ol_timeout_ms, T_U16, 1, 60000),
    FD(cl_hold_ms, T_U16, 0, 60000),
    FD(t_ipm_max, T_I16, -399, 2000),   /* above t_ipm_derate >= -400 */
    FD(t_pcb_max, T_I16, -399, 2000),
    FD(vdc_ms, T_U16, 1, 10),
    FD(temp_ms, T_U16, 1, 10),
    FD(stall_err, T_I16, 1, 32767),
    FD(flux_tol, T_I16, 1, 32767),
    FD(stall_ms, T_U16, 1, 60000),
    FD(phase_alpha, T_I16, 1, 32767),
    FD(phase_i_min, T_I16, 1, 32767),
    FD(phase_ratio, T_I16, 0, 32767),
    FD(phase_ms, T_U16, 1, 60000),
    FD(link_timeout_ms, T_U16, 1, 60000),
    FD(clear_ms, T_U16, 1, 60000),
    FD(fw_level, T_I16, 1, 32767),
    FD(fw_alpha, T_I16, 1, 32767),
    FD(tc_gain, T_I16, 0, 32767),
    FD(tc_amp_max, T_I16, 0, 32767),
    FD(tc_speed_min, T_I16, 0, 32767),
    FD(tc_speed_max, T_I16, 0, 32767),
    FD(para_speed, T_I16, 1, 32767),
    FD(ld_hs, T_I16, 0, 32767),
    FD(lq_hs, T_I16, 0, 32767),
    FD(lin_id_cmd, T_U8, 0, 0x3B),
    FD(lin_id_status, T_U8, 0, 0x3B),
    FD(can_id_a, T_U16, 0, 0x7FF),
    FD(can_id_b, T_U16, 0, 0x7FF),
    FD(mtpa_speed, T_I16, 0, 32767),
    FD(t_ipm_derate, T_I16, -400, 1999),  /* below t_ipm_max <= 2000 */
    FD(t_pcb_derate, T_I16, -400, 1999),
    FD(rpm_derate, T_U16, 1, 65535),
    FD(flux_band, T_I16, 1, 32767),
    FD(flux_v_err, T_I16, 0, 32767),
    FD(flux_r_err, T_I16, 0, 32767),
    FD(psi_shift, T_U8, 0, 4),
    FD(ho_retries, T_U8, 0, 3),
    FD(sensing, T_U8, 0, 1),
    FD(shunt_settle, T_U16, 0, 65535),   /* its fit in the period is a table check */
    FD(shunt_sample, T_U16, 1, 65535),
    FD(shunt_hold, T_U16, 1, 16),
};
#define NFIELDS (sizeof fields / sizeof fields[0])

static int32_t type_min(ftype_t t)
{
    return (t == T_I16) ? -32768 : 0;
}

static int32_t type_max(ftype_t t)
{
    return (t == T_U8) ? 255 : ((t == T_U16) ? 65535 : 32767);
}

static void set_field(qfoc_drive_cfg_t *c, const fdesc_t *f, int32_t v)
{
    uint8_t *p = (uint8_t *)c + f->off;
    if (f->type == T_U8) {
        uint8_t x = (uint8_t)v;
        memcpy(p, &x, 1);
    } else if (f->type == T_U16) {
        uint16_t x = (uint16_t)v;
        memcpy(p, &x, 2);
    } else {
        int16_t x = (int16_t)v;
        memcpy(p, &x, 2);
    }
}

static int32_t get_field(const qfoc_drive_cfg_t *c, const fdesc_t *f)
{
    const uint8_t *p = (const uint8_t *)c + f->off;
    int32_t v;
    if (f->type == T_U8) {
        uint8_t x;
        memcpy(&x, p, 1);
        v = x;
    } else if (f->type == T_U16) {
        uint16_t x;
        memcpy(&x, p, 2);
        v = x;
    } else {
        int16_t x;
        memcpy(&x, p, 2);
        v = x;
    }
    return v;
}

/* the reference check: every field in its range and the three relations */
static bool ref_valid(const qfoc_drive_cfg_t *c)
{
    size_t k;
    bool ok = true;
    for (k = 0u; k < NFIELDS; k++) {
        const int32_t v = get_field(c, &fields[k]);
        if (v < fields[k].lo || v > fields[k].hi) {
            ok = false;
        }
    }
    return ok && (c->rpm_min <= c->rpm_max) && (c->tc_speed_min <= c->tc_speed_max)
           && (c->lin_id_status != c->lin_id_cmd) && (c->t_ipm_derate < c->t_ipm_max)
           && (c->t_pcb_derate < c->t_pcb_max) && (c->rpm_min <= c->rpm_derate)
           && (c->rpm_derate <= c->rpm_max);
}

/* a configuration in the middle of every range (the tool's defaults for the reference
   motor, written here by hand) */
static void base_cfg(qfoc_drive_cfg_t *c)
{
    memset(c, 0, sizeof *c);
    c->pole_pairs = 3u;
    c->k_rpm = 13422u;
    c->k_speed_rpm = 10000u;
    c->rpm_min = 1000u;
    c->rpm_max = 8000u;
    c->speed_ramp = 10;
    c->precharge_ms = 200u;
    c->offset_shift = 6u;
    c->offset_window = 100u;
    c->i_align = 8192;
    c->align_ms = 300u;
    c->i_start = 16384;
    c->of_accel = 3;
    c->of_speed = 3277;
    c->ho_angle = 2731u;
    c->ho_dwell_ms = 50u;
    c->ol_timeout_ms = 2000u;
    c->cl_hold_ms = 2000u;
    c->t_ipm_max = 1100;
    c->t_pcb_max = 1000;
    c->vdc_ms = 2u;
    c->temp_ms = 10u;
    c->stall_err = 5898;
    c->flux_tol = 6692;
    c->stall_ms = 500u;
    c->phase_alpha = 129;
    c->phase_i_min = 1638;
    c->phase_ratio = 8192;
    c->phase_ms = 100u;
    c->link_timeout_ms = 500u;
    c->clear_ms = 5000u;
    c->fw_level = 30147;
    c->fw_alpha = 1287;
    c->tc_gain = 1000;
    c->tc_amp_max = 8192;
    c->tc_speed_min = 1638;
    c->tc_speed_max = 9830;
    c->para_speed = 18350;
    c->ld_hs = 2677;
    c->lq_hs = 4324;
    c->lin_id_cmd = 0x10u;
    c->lin_id_status = 0x11u;
    c->can_id_a = 0x310u;
    c->can_id_b = 0x311u;
    c->mtpa_speed = 3277;
    c->t_ipm_derate = 1000;
    c->t_pcb_derate = 900;
    c->rpm_derate = 2000u;
    c->flux_band = 9830;
    c->flux_v_err = 394;
    c->flux_r_err = 9830;
    c->sensing = QFOC_SENSING_SHUNT;
    c->shunt_settle = 160u;
    c->shunt_sample = 40u;
    c->shunt_hold = 4u;
}

/* the partner fields set so that field f's own bound is the only one that matters */
static void widen_partners(qfoc_drive_cfg_t *c, const fdesc_t *f)
{
    if (strcmp(f->name, "rpm_min") == 0) {
        c->rpm_max = 65535u;
        c->rpm_derate = 65535u;
    } else if (strcmp(f->name, "rpm_max") == 0) {
        c->rpm_min = 1u;
        c->rpm_derate = 1u;
    } else if (strcmp(f->name, "rpm_derate") == 0) {
        c->rpm_min = 1u;
        c->rpm_max = 65535u;
    } else if (strcmp(f->name, "t_ipm_max") == 0) {
        c->t_ipm_derate = -400;
    } else if (strcmp(f->name, "t_pcb_max") == 0) {
        c->t_pcb_derate = -400;
    } else if (strcmp(f->name, "t_ipm_derate") == 0) {
        c->t_ipm_max = 2000;
    } else if (strcmp(f->name, "t_pcb_derate") == 0) {
        c->t_pcb_max = 2000;
    } else if (strcmp(f->name, "tc_speed_min") == 0) {
        c->tc_speed_max = 32767;
    } else if (strcmp(f->name, "tc_speed_max") == 0) {
        c->tc_speed_min = 0;
    } else if (strcmp(f->name, "lin_id_status") == 0) {
        c->lin_id_cmd = 0x20u;   /* inside the range, equal to neither end */
    } else if (strcmp(f->name, "lin_id_cmd") == 0) {
        c->lin_id_status = 0x20u;
    } else {
        /* no partner */
    }
}

static void check_value(const fdesc_t *f, int32_t v, bool expect)
{
    qfoc_drive_cfg_t c;
    base_cfg(&c);
    widen_partners(&c, f);
    set_field(&c, f, v);
    if (qfoc_drive_cfg_is_valid(&c) != expect) {
        fail_msg("drive.%s = %d: expected %s", f->name, (int)v, expect ? "accepted" : "refused");
    }
    assert_int_equal(ref_valid(&c), expect);
}

/* REQ-DCFG-001, REQ-DCFG-002, REQ-DCFG-003, REQ-DCFG-004, REQ-DCFG-005, REQ-DCFG-006: the base
   configuration is valid.
   Methods: 1a the base configuration valid by the rules of REQ-DCFG-001 .. REQ-DCFG-006; 1n
   the reference check written in the test */
static void test_dcfg_base_valid(void **state)
{
    qfoc_drive_cfg_t c;
    (void)state;
    base_cfg(&c);
    assert_true(qfoc_drive_cfg_is_valid(&c));
    assert_true(ref_valid(&c));
}

/* REQ-DCFG-001, REQ-DCFG-002, REQ-DCFG-003, REQ-DCFG-004, REQ-DCFG-005, REQ-DCFG-006: every field:
   its lowest and highest value accepted, one below the lowest and one above the highest refused (where
   the type holds them), and the type's extremes refused when outside the range.
   Methods: 1c every field at its lowest and highest value, one below and one above, and the
   extremes of its C type where they lie outside the range */
static void test_dcfg_field_boundaries(void **state)
{
    size_t k;
    uint32_t n = 0u;
    (void)state;
    for (k = 0u; k < NFIELDS; k++) {
        const fdesc_t *f = &fields[k];
        check_value(f, f->lo, true);
        check_value(f, f->hi, true);
        n += 2u;
        if (f->lo > type_min(f->type)) {
            check_value(f, f->lo - 1, false);
            check_value(f, type_min(f->type), false);
            n += 2u;
        }
        if (f->hi < type_max(f->type)) {
            check_value(f, f->hi + 1, false);
            check_value(f, type_max(f->type), false);
            n += 2u;
        }
    }
    print_message("drive_cfg: %u boundary values of %u fields checked\n", (unsigned)n,
                  (unsigned)NFIELDS);
}

/* REQ-DCFG-001, REQ-DCFG-004, REQ-DCFG-005: the relations between fields: rpm_min <= rpm_max,
   tc_speed_min <= tc_speed_max, lin_id_status != lin_id_cmd; equality accepted where
   allowed, one past refused.
   Methods: 1c each relation at equality and one past it: rpm_min = rpm_max, tc_speed_min =
   tc_speed_max, the derating start one below and at its trip, rpm_derate at rpm_min and
   rpm_max and one outside, the LIN identifiers 0 and 0x3B; 1d equal command and status
   identifiers */
static void test_dcfg_relations(void **state)
{
    qfoc_drive_cfg_t c;
    (void)state;
    base_cfg(&c);
    c.rpm_min = 4000u;
    c.rpm_max = 4000u;
    c.rpm_derate = 4000u;
    assert_true(qfoc_drive_cfg_is_valid(&c));
    c.rpm_min = 4001u;
    assert_false(qfoc_drive_cfg_is_valid(&c));
    c.rpm_min = 1u;
    c.rpm_max = 0u;
    assert_false(qfoc_drive_cfg_is_valid(&c));

    base_cfg(&c);
    c.tc_speed_min = 5000;
    c.tc_speed_max = 5000;
    assert_true(qfoc_drive_cfg_is_valid(&c));
    c.tc_speed_min = 5001;
    assert_false(qfoc_drive_cfg_is_valid(&c));
    c.tc_speed_min = 0;
    c.tc_speed_max = 0;
    assert_true(qfoc_drive_cfg_is_valid(&c));

    base_cfg(&c);
    c.lin_id_status = c.lin_id_cmd;
    assert_false(qfoc_drive_cfg_is_valid(&c));
    c.lin_id_cmd = 0u;
    c.lin_id_status = 0x3Bu;
    assert_true(qfoc_drive_cfg_is_valid(&c));
    c.lin_id_cmd = 0x3Bu;
    c.lin_id_status = 0u;
    assert_true(qfoc_drive_cfg_is_valid(&c));

    /* REQ-DCFG-005: a derating window must start below its trip; the derated speed lies in
       [rpm_min, rpm_max] */
    base_cfg(&c);
    c.t_ipm_derate = (int16_t)(c.t_ipm_max - 1);
    assert_true(qfoc_drive_cfg_is_valid(&c));
    c.t_ipm_derate = c.t_ipm_max;
    assert_false(qfoc_drive_cfg_is_valid(&c));
    base_cfg(&c);
    c.t_pcb_derate = (int16_t)(c.t_pcb_max - 1);
    assert_true(qfoc_drive_cfg_is_valid(&c));
    c.t_pcb_derate = (int16_t)(c.t_pcb_max + 1);
    assert_false(qfoc_drive_cfg_is_valid(&c));
    base_cfg(&c);
    c.rpm_derate = c.rpm_min;
    assert_true(qfoc_drive_cfg_is_valid(&c));
    c.rpm_derate = (uint16_t)(c.rpm_min - 1u);
    assert_false(qfoc_drive_cfg_is_valid(&c));
    c.rpm_derate = c.rpm_max;
    assert_true(qfoc_drive_cfg_is_valid(&c));
    c.rpm_derate = (uint16_t)(c.rpm_max + 1u);
    assert_false(qfoc_drive_cfg_is_valid(&c));
}

/* REQ-DCFG-001, REQ-DCFG-002, REQ-DCFG-003, REQ-DCFG-004, REQ-DCFG-005, REQ-DCFG-006: random
   configurations against the reference check: each field inside its range with probability 0.98, else any bit
   pattern (about half of the configurations are valid), and wholly random bit patterns.
   Methods: 1b 200000 random configurations, each field inside its range with probability
   0.98 (about half of them valid), every tenth a random bit pattern; 1d configurations with
   fields out of range and garbage bit patterns; 1n the reference check written in the test
   from the requirements */
static void test_dcfg_random_vs_reference(void **state)
{
    uint32_t k;
    uint32_t n_valid = 0u;
    uint32_t n_invalid = 0u;
    (void)state;
    lcg_state = 4242u;
    for (k = 0u; k < 200000u; k++) {
        qfoc_drive_cfg_t c;
        size_t i;
        bool expect;
        if ((k % 10u) == 9u) {
            uint8_t *raw = (uint8_t *)&c;
            for (i = 0u; i < sizeof c; i++) {
                raw[i] = (uint8_t)(lcg_next() >> 24);
            }
        } else {
            memset(&c, 0, sizeof c);
            for (i = 0u; i < NFIELDS; i++) {
                const fdesc_t *f = &fields[i];
                int32_t v;
                if ((lcg_next() % 50u) == 0u) {
                    v = rand_range(type_min(f->type), type_max(f->type));
                } else {
                    v = rand_range(f->lo, f->hi);
                }
                set_field(&c, f, v);
            }
            /* most of the time order the related pairs as the valid tables do */
            if ((lcg_next() % 8u) != 0u && c.rpm_min > c.rpm_max) {
                const uint16_t t = c.rpm_min;
                c.rpm_min = c.rpm_max;
                c.rpm_max = t;
            }
            if ((lcg_next() % 8u) != 0u && c.tc_speed_min > c.tc_speed_max) {
                const int16_t t = c.tc_speed_min;
                c.tc_speed_min = c.tc_speed_max;
                c.tc_speed_max = t;
            }
            if ((lcg_next() % 8u) != 0u && c.t_ipm_derate >= c.t_ipm_max) {
                const int16_t t = c.t_ipm_derate;
                c.t_ipm_derate = (int16_t)(c.t_ipm_max - 1);
                c.t_ipm_max = (int16_t)((t < 2000) ? (t + 1) : 2000);
            }
            if ((lcg_next() % 8u) != 0u && c.t_pcb_derate >= c.t_pcb_max) {
                const int16_t t = c.t_pcb_derate;
                c.t_pcb_derate = (int16_t)(c.t_pcb_max - 1);
                c.t_pcb_max = (int16_t)((t < 2000) ? (t + 1) : 2000);
            }
            if ((lcg_next() % 8u) != 0u && c.rpm_min <= c.rpm_max) {
                c.rpm_derate = (uint16_t)rand_range(c.rpm_min, c.rpm_max);
            }
        }
        expect = ref_valid(&c);
        assert_int_equal(qfoc_drive_cfg_is_valid(&c), expect);
        if (expect) {
            n_valid++;
        } else {
            n_invalid++;
        }
    }
    print_message("drive_cfg: 200000 random configurations, %u valid, %u invalid, all agree\n",
                  (unsigned)n_valid, (unsigned)n_invalid);
    assert_true(n_valid > 20000u);
    assert_true(n_invalid > 20000u);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_dcfg_base_valid),
        cmocka_unit_test(test_dcfg_field_boundaries),
        cmocka_unit_test(test_dcfg_relations),
        cmocka_unit_test(test_dcfg_random_vs_reference),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
