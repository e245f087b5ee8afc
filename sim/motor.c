/**
 * @file motor.c
 * @brief Motor-file reader (TOML subset) and per-unit bases for the plant model.
 *
 * Accepted syntax: `[section]` headers, `key = value` lines where value is a
 * decimal number (with optional exponent) or a double-quoted string without
 * escapes, `#` comments, blank lines.  Keys are looked up as "section.key".
 */
#include "sim.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <stddef.h>

typedef struct {
    const char *key;
    size_t offset;
} sim_key_t;

#define SIM_KEY(k, f) { k, offsetof(sim_motor_t, f) }

static const sim_key_t sim_keys[] = {
    SIM_KEY("motor.pole_pairs", pole_pairs),
    SIM_KEY("motor.rs_ohm", rs_ohm),
    SIM_KEY("motor.ld_h", ld_h),
    SIM_KEY("motor.lq_h", lq_h),
    SIM_KEY("motor.psi_f_wb", psi_f_wb),
    SIM_KEY("motor.j_kgm2", j_kgm2),
    SIM_KEY("motor.b_nms", b_nms),
    SIM_KEY("motor.rated_speed_rpm", rated_speed_rpm),
    SIM_KEY("motor.max_speed_rpm", max_speed_rpm),
    SIM_KEY("motor.rated_current_a", rated_current_a),
    SIM_KEY("motor.nominal_torque_nm", nominal_torque_nm),
    SIM_KEY("inverter.vdc_nominal_v", vdc_nominal_v),
    SIM_KEY("inverter.vdc_min_v", vdc_min_v),
    SIM_KEY("inverter.vdc_max_v", vdc_max_v),
    SIM_KEY("inverter.f_pwm_hz", f_pwm_hz),
    SIM_KEY("inverter.f_timer_hz", f_timer_hz),
    SIM_KEY("inverter.dead_time_s", dead_time_s),
    SIM_KEY("sensing.i_full_scale_a", i_full_scale_a),
    SIM_KEY("sensing.vdc_full_scale_v", vdc_full_scale_v),
    SIM_KEY("sensing.adc_bits", adc_bits),
    SIM_KEY("scaling.f_base_hz", f_base_hz),
};
#define SIM_NKEYS (sizeof sim_keys / sizeof sim_keys[0])

static char *sim_trim(char *s)
{
    char *e;
    while (*s != '\0' && isspace((unsigned char)*s)) {
        s++;
    }
    e = s + strlen(s);
    while (e > s && isspace((unsigned char)e[-1])) {
        e--;
    }
    *e = '\0';
    return s;
}

/* Remove a comment that is not inside a string. */
static void sim_strip_comment(char *s)
{
    int in_str = 0;
    for (; *s != '\0'; s++) {
        if (*s == '"') {
            in_str = !in_str;
        } else if (*s == '#' && !in_str) {
            *s = '\0';
            break;
        }
    }
}

int sim_motor_load(const char *path, sim_motor_t *m)
{
    FILE *f = fopen(path, "r");
    char line[512];
    char section[64] = "";
    int seen[SIM_NKEYS];
    int lineno = 0;
    int rc = 0;
    size_t k;

    memset(m, 0, sizeof *m);
    memset(seen, 0, sizeof seen);
    if (f == NULL) {
        fprintf(stderr, "%s: cannot open\n", path);
        return -1;
    }
    while (rc == 0 && fgets(line, (int)sizeof line, f) != NULL) {
        char *s;
        char *eq;
        char *key;
        char *val;
        char full[160];
        lineno++;
        sim_strip_comment(line);
        s = sim_trim(line);
        if (*s == '\0') {
            continue;
        }
        if (*s == '[') {
            char *close = strchr(s, ']');
            if (close == NULL || (size_t)(close - s - 1) >= sizeof section) {
                fprintf(stderr, "%s:%d: malformed section header\n", path, lineno);
                rc = -1;
                break;
            }
            *close = '\0';
            snprintf(section, sizeof section, "%s", sim_trim(s + 1));
            continue;
        }
        eq = strchr(s, '=');
        if (eq == NULL) {
            fprintf(stderr, "%s:%d: expected key = value\n", path, lineno);
            rc = -1;
            break;
        }
        *eq = '\0';
        key = sim_trim(s);
        val = sim_trim(eq + 1);
        snprintf(full, sizeof full, "%s.%s", section, key);
        if (*val == '"') {
            char *end = strrchr(val + 1, '"');
            if (end == NULL) {
                fprintf(stderr, "%s:%d: unterminated string\n", path, lineno);
                rc = -1;
                break;
            }
            *end = '\0';
            if (strcmp(full, "motor.name") == 0) {
                snprintf(m->name, sizeof m->name, "%s", val + 1);
            }
            continue;
        }
        for (k = 0; k < SIM_NKEYS; k++) {
            if (strcmp(full, sim_keys[k].key) == 0) {
                char *endp;
                double v = strtod(val, &endp);
                if (endp == val || *sim_trim(endp) != '\0') {
                    fprintf(stderr, "%s:%d: %s: not a number\n", path, lineno, full);
                    rc = -1;
                } else {
                    *(double *)((char *)m + sim_keys[k].offset) = v;
                    seen[k] = 1;
                }
                break;
            }
        }
    }
    fclose(f);
    for (k = 0; rc == 0 && k < SIM_NKEYS; k++) {
        const double v = *(const double *)((const char *)m + sim_keys[k].offset);
        const int may_be_zero = (strcmp(sim_keys[k].key, "inverter.dead_time_s") == 0) ||
                                (strcmp(sim_keys[k].key, "motor.b_nms") == 0);
        if (!seen[k] || !(v > 0.0 || (may_be_zero && v == 0.0))) {
            fprintf(stderr, "%s: %s missing or not positive\n", path, sim_keys[k].key);
            rc = -1;
        }
    }
    return rc;
}

void sim_bases(const sim_motor_t *m, sim_bases_t *b)
{
    b->v_base = m->vdc_full_scale_v;
    b->i_base = m->i_full_scale_a;
    b->f_base = m->f_base_hz;
    b->w_base = 2.0 * SIM_PI * m->f_base_hz;
    b->psi_base = b->v_base / b->w_base;
    b->z_base = b->v_base / b->i_base;
    b->l_base = b->z_base / b->w_base;
    b->t_s = 1.0 / m->f_pwm_hz;
    b->period = (uint16_t)lround(m->f_timer_hz / (2.0 * m->f_pwm_hz));
}

int sim_motor_set(sim_motor_t *m, const char *assignment)
{
    char key[160];
    const char *eq = strchr(assignment, '=');
    int rc = -1;
    size_t k;
    if (eq != NULL && (size_t)(eq - assignment) < sizeof key) {
        char *endp;
        const double v = strtod(eq + 1, &endp);
        memcpy(key, assignment, (size_t)(eq - assignment));
        key[eq - assignment] = '\0';
        for (k = 0; k < SIM_NKEYS; k++) {
            if (strcmp(sim_trim(key), sim_keys[k].key) == 0 && endp != eq + 1 && *endp == '\0') {
                *(double *)((char *)m + sim_keys[k].offset) = v;
                rc = 0;
            }
        }
    }
    /* the table's single-shunt keys ([sensing] of the tuning tool): the plant's sensing
       follows the table (sim/scenario.c), nothing to set here */
    if (rc != 0 && eq != NULL) {
        static const char *const table_only[] = { "sensing.mode", "sensing.shunt_settle_ns",
                                                  "sensing.shunt_sample_ns",
                                                  "sensing.shunt_hold" };
        for (k = 0; k < sizeof table_only / sizeof table_only[0]; k++) {
            const size_t n = strlen(table_only[k]);
            if ((size_t)(eq - assignment) == n && strncmp(assignment, table_only[k], n) == 0) {
                rc = 0;
            }
        }
    }
    if (rc != 0) {
        fprintf(stderr, "override '%s': expected SECTION.KEY=NUMBER with a known key\n", assignment);
    }
    return rc;
}
