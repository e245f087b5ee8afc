/**
 * @file tt_runner.c
 * @brief Golden-vector runner: replays every group and compares with the host (tt.h).
 *
 * Output, one line per group:
 *   "<name>: <n> vectors, identical"
 * or
 *   "<name>: DIFFERENT: <d> of <n> vectors differ, first at vector <i>: here 0x...,
 *    host 0x...; inputs w0 w1 ..."
 * then "result: <g> groups, <v> vectors, all identical" (exit status 0) or
 * "result: <b> of <g> groups differ" (exit status 1).
 *
 * Self-test options (the comparison must be able to fail): --corrupt-expected NAME INDEX
 * flips bit 0 of one expected digest, --corrupt-input NAME INDEX flips bit 0 of the first
 * input word of one vector (of the index for a width-0 group); --only NAME restricts the
 * run to the suite holding that group.
 *
 * Requirements: REQ-TGT-002, REQ-TGT-004.
 */
#include "tt.h"
#include "tt_io.h"
#include "vectors.h"

#include <stddef.h>

#include "qfoc/params.h"

#define TT_LINE_MAX (240u)
#define TT_TOKENS_MAX (16u)
#define TT_TOKEN_LEN (40u)

typedef struct {
    char only[TT_TOKENS_MAX][TT_TOKEN_LEN];
    uint16_t n_only;
    char corrupt_exp_name[TT_TOKEN_LEN];
    uint32_t corrupt_exp_index;
    char corrupt_in_name[TT_TOKEN_LEN];
    uint32_t corrupt_in_index;
    bool list;
} tt_opts_t;

/* ------------------------------------------------------------------ text */

typedef struct {
    char s[TT_LINE_MAX];
    uint32_t len;
} tt_line_t;

static void tt_l_clear(tt_line_t *l)
{
    l->len = 0u;
    l->s[0] = '\0';
}

static void tt_l_str(tt_line_t *l, const char *s)
{
    uint32_t k = 0u;
    while ((s[k] != '\0') && (l->len < (TT_LINE_MAX - 2u))) {
        l->s[l->len] = s[k];
        l->len++;
        k++;
    }
    l->s[l->len] = '\0';
}

static void tt_l_dec(tt_line_t *l, uint32_t v)
{
    static const char digit[] = "0123456789";
    char buf[11];
    uint32_t n = 0u;
    uint32_t x = v;
    char out[2];
    do {
        buf[n] = digit[x % 10u];
        n++;
        x /= 10u;
    } while (x != 0u);
    out[1] = '\0';
    while (n > 0u) {
        n--;
        out[0] = buf[n];
        tt_l_str(l, out);
    }
}

static void tt_l_hex(tt_line_t *l, uint32_t v, uint32_t digits)
{
    static const char hex[] = "0123456789abcdef";
    char out[2];
    uint32_t d = digits;
    out[1] = '\0';
    tt_l_str(l, "0x");
    while (d > 0u) {
        d--;
        out[0] = hex[(v >> (4u * d)) & 0xFu];
        tt_l_str(l, out);
    }
}

static void tt_l_put(tt_line_t *l)
{
    tt_l_str(l, "\n");
    tt_io_puts(l->s);
    tt_l_clear(l);
}

static bool tt_streq(const char *a, const char *b)
{
    uint32_t k = 0u;
    bool eq = true;
    bool done = false;
    while (!done) {
        if (a[k] != b[k]) {
            eq = false;
            done = true;
        } else if (a[k] == '\0') {
            done = true;
        } else {
            k++;
        }
    }
    return eq;
}

/* ------------------------------------------------------------------ command line */

/* Next whitespace-separated token of s from *pos into tok; false at the end. */
static bool tt_token(const char *s, uint32_t *pos, char tok[TT_TOKEN_LEN])
{
    uint32_t p = *pos;
    uint32_t n = 0u;
    bool found = false;
    while ((s[p] == ' ') || (s[p] == '\t') || (s[p] == '\n') || (s[p] == '\r')) {
        p++;
    }
    while ((s[p] != '\0') && (s[p] != ' ') && (s[p] != '\t') && (s[p] != '\n') && (s[p] != '\r')) {
        if (n < (TT_TOKEN_LEN - 1u)) {
            tok[n] = s[p];
            n++;
        }
        p++;
        found = true;
    }
    tok[n] = '\0';
    *pos = p;
    return found;
}

static bool tt_parse_u32(const char *s, uint32_t *v)
{
    uint32_t k = 0u;
    uint32_t x = 0u;
    bool ok = (s[0] != '\0');
    while (ok && (s[k] != '\0')) {
        const uint32_t c = (uint32_t)(uint8_t)s[k];
        if ((c >= 48u) && (c <= 57u) && (x <= 429496728u)) {   /* ASCII '0' .. '9' */
            x = (x * 10u) + (c - 48u);
            k++;
        } else {
            ok = false;
        }
    }
    *v = x;
    return ok;
}

static void tt_copy(char dst[TT_TOKEN_LEN], const char *src)
{
    uint32_t k = 0u;
    while ((src[k] != '\0') && (k < (TT_TOKEN_LEN - 1u))) {
        dst[k] = src[k];
        k++;
    }
    dst[k] = '\0';
}

static bool tt_parse(const char *cmdline, tt_opts_t *o)
{
    char tok[TT_TOKEN_LEN];
    char arg[TT_TOKEN_LEN];
    uint32_t pos = 0u;
    bool ok = true;
    o->n_only = 0u;
    o->corrupt_exp_name[0] = '\0';
    o->corrupt_exp_index = TT_NONE;
    o->corrupt_in_name[0] = '\0';
    o->corrupt_in_index = TT_NONE;
    o->list = false;
    (void)tt_token(cmdline, &pos, tok);   /* the program name */
    while (ok && tt_token(cmdline, &pos, tok)) {
        if (tt_streq(tok, "--only") && tt_token(cmdline, &pos, arg) && (o->n_only < TT_TOKENS_MAX)) {
            tt_copy(o->only[o->n_only], arg);
            o->n_only++;
        } else if (tt_streq(tok, "--corrupt-expected") && tt_token(cmdline, &pos, arg) &&
                   tt_token(cmdline, &pos, tok) && tt_parse_u32(tok, &o->corrupt_exp_index)) {
            tt_copy(o->corrupt_exp_name, arg);
        } else if (tt_streq(tok, "--corrupt-input") && tt_token(cmdline, &pos, arg) &&
                   tt_token(cmdline, &pos, tok) && tt_parse_u32(tok, &o->corrupt_in_index)) {
            tt_copy(o->corrupt_in_name, arg);
        } else if (tt_streq(tok, "--list")) {
            o->list = true;
        } else {
            ok = false;
        }
    }
    return ok;
}

/* ------------------------------------------------------------------ the run */

static bool tt_selected(const tt_opts_t *o, const tt_suite_t *s)
{
    bool sel = (o->n_only == 0u);
    uint16_t k;
    uint16_t j;
    for (k = 0u; k < o->n_only; k++) {
        for (j = 0u; j < (uint16_t)s->groups; j++) {
            if (tt_streq(o->only[k], s->name[j])) {
                sel = true;
            }
        }
    }
    return sel;
}

static void tt_report(const tt_ctx_t *c, tt_line_t *l)
{
    const tt_data_t *g = c->data;
    tt_l_str(l, g->name);
    if ((c->n_bad == 0u) && (c->k == g->n)) {
        tt_l_str(l, ": ");
        tt_l_dec(l, g->n);
        tt_l_str(l, " vectors, identical");
    } else if (c->n_bad == 0u) {
        tt_l_str(l, ": DIFFERENT: the replay gave ");
        tt_l_dec(l, c->k);
        tt_l_str(l, " outputs for ");
        tt_l_dec(l, g->n);
        tt_l_str(l, " vectors");
    } else {
        uint16_t j;
        tt_l_str(l, ": DIFFERENT: ");
        tt_l_dec(l, c->n_bad);
        tt_l_str(l, " of ");
        tt_l_dec(l, g->n);
        tt_l_str(l, " vectors differ, first at vector ");
        tt_l_dec(l, c->first_bad);
        tt_l_str(l, ": here ");
        tt_l_hex(l, c->got_first, 8u);
        tt_l_str(l, ", host ");
        tt_l_hex(l, c->exp_first, 8u);
        tt_l_str(l, "; inputs");
        if (g->width == 0u) {
            tt_l_str(l, " ");
            tt_l_dec(l, tt_in_index(c, c->first_bad));
        }
        for (j = 0u; j < g->width; j++) {
            tt_l_str(l, " ");
            tt_l_hex(l, tt_in(c, c->first_bad, j), 4u);
        }
    }
    tt_l_put(l);
}

/* The group names of vectors.c must be the suites' names, in order. */
static bool tt_consistent(tt_line_t *l)
{
    uint16_t s;
    uint16_t g = 0u;
    bool ok = true;
    for (s = 0u; s < TT_N_SUITES; s++) {
        uint16_t j;
        if ((tt_suites[s].fn == NULL) || (tt_suites[s].groups < 1u) || (tt_suites[s].groups > 2u)) {
            ok = false;
        } else {
            for (j = 0u; j < (uint16_t)tt_suites[s].groups; j++) {
                if ((g >= TT_N_GROUPS) || (tt_suites[s].name[j] == NULL) ||
                    !tt_streq(tt_suites[s].name[j], tt_data[g].name)) {
                    ok = false;
                }
                g++;
            }
        }
    }
    if (g != TT_N_GROUPS) {
        ok = false;
    }
    if (!ok) {
        tt_l_str(l, "setup: the vectors do not match the replay code (regenerate them)");
        tt_l_put(l);
    }
    return ok;
}

int32_t tt_run(const char *cmdline)
{
    static tt_opts_t o;
    static tt_line_t l;
    int32_t status = 0;
    tt_l_clear(&l);
    if (!tt_parse(cmdline, &o)) {
        tt_l_str(&l, "usage: tt_runner [--only NAME]... [--corrupt-expected NAME INDEX] "
                     "[--corrupt-input NAME INDEX] [--list]");
        tt_l_put(&l);
        status = 2;
    } else if (!tt_consistent(&l)) {
        status = 2;
    } else if (o.list) {
        uint16_t g;
        for (g = 0u; g < TT_N_GROUPS; g++) {
            tt_l_str(&l, tt_data[g].name);
            tt_l_str(&l, " ");
            tt_l_dec(&l, tt_data[g].n);
            tt_l_put(&l);
        }
    } else {
        uint16_t s;
        uint16_t g = 0u;
        uint32_t groups = 0u;
        uint32_t vectors = 0u;
        uint32_t bad = 0u;
        const uint32_t t0 = tt_io_clock_cs();
        uint32_t dt;
        tt_l_str(&l, "qfoc golden vectors: ");
        tt_l_dec(&l, TT_N_GROUPS);
        tt_l_str(&l, " groups, ");
        tt_l_dec(&l, TT_N_VECTORS);
        tt_l_str(&l, " vectors computed on ");
        tt_l_str(&l, TT_HOST_DESC);
        tt_l_str(&l, ", replayed on ");
        tt_l_str(&l, tt_io_platform());
        tt_l_put(&l);
        if (((uint32_t)sizeof(qfoc_param_table_t) != (uint32_t)TT_HOST_PARAMS_SIZE) ||
            ((uint32_t)offsetof(qfoc_param_table_t, crc) != (uint32_t)TT_HOST_PARAMS_CRC_OFFSET)) {
            tt_l_str(&l, "layout: qfoc_param_table_t differs from the host's (size ");
            tt_l_dec(&l, (uint32_t)sizeof(qfoc_param_table_t));
            tt_l_str(&l, " here, ");
            tt_l_dec(&l, TT_HOST_PARAMS_SIZE);
            tt_l_str(&l, " on the host)");
            tt_l_put(&l);
            bad++;
        }
        for (s = 0u; s < TT_N_SUITES; s++) {
            const tt_suite_t *su = &tt_suites[s];
            if (tt_selected(&o, su)) {
                tt_ctx_t ctx[2];
                uint16_t j;
                for (j = 0u; j < (uint16_t)su->groups; j++) {
                    const tt_data_t *d = &tt_data[g + j];
                    ctx[j].data = d;
                    ctx[j].k = 0u;
                    ctx[j].n_bad = 0u;
                    ctx[j].first_bad = TT_NONE;
                    ctx[j].got_first = 0u;
                    ctx[j].exp_first = 0u;
                    ctx[j].record = NULL;
                    ctx[j].corrupt_exp = tt_streq(o.corrupt_exp_name, d->name) ? o.corrupt_exp_index
                                                                               : TT_NONE;
                    ctx[j].corrupt_in = tt_streq(o.corrupt_in_name, d->name) ? o.corrupt_in_index
                                                                             : TT_NONE;
                }
                su->fn(ctx);
                for (j = 0u; j < (uint16_t)su->groups; j++) {
                    tt_report(&ctx[j], &l);
                    groups++;
                    vectors += ctx[j].data->n;
                    if ((ctx[j].n_bad != 0u) || (ctx[j].k != ctx[j].data->n)) {
                        bad++;
                    }
                }
            }
            g = (uint16_t)(g + (uint16_t)su->groups);
        }
        if (bad == 0u) {
            tt_l_str(&l, "result: ");
            tt_l_dec(&l, groups);
            tt_l_str(&l, " groups, ");
            tt_l_dec(&l, vectors);
            tt_l_str(&l, " vectors, all identical");
        } else {
            tt_l_str(&l, "result: ");
            tt_l_dec(&l, bad);
            tt_l_str(&l, " of ");
            tt_l_dec(&l, groups);
            tt_l_str(&l, " groups differ");
            status = 1;
        }
        dt = tt_io_clock_cs() - t0;
        tt_l_str(&l, " (");
        tt_l_dec(&l, dt / 100u);
        tt_l_str(&l, ".");
        tt_l_dec(&l, (dt % 100u) / 10u);
        tt_l_str(&l, " s)");
        tt_l_put(&l);
    }
    return status;
}
