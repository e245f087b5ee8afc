/**
 * @file fake_regs.c
 * @brief The RAM register file of the host tests (fake_regs.h): open addressing on the
 *        word address, 4096 cells, creation order kept for enumeration.
 */
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include "fake_regs.h"

#define QFOC_FAKE_CELLS 4096u

typedef struct {
    uint32_t addr;
    volatile uint32_t value;
    bool used;
} qfoc_fake_cell_t;

static qfoc_fake_cell_t s_cells[QFOC_FAKE_CELLS];
static uint32_t s_order[QFOC_FAKE_CELLS];
static uint32_t s_count = 0u;
static uint32_t s_accesses = 0u;
static void (*s_hook)(uint32_t addr) = NULL;
static bool s_in_hook = false;

static qfoc_fake_cell_t *fake_find(uint32_t addr, bool create)
{
    uint32_t i = ((addr >> 2) * 2654435761u) % QFOC_FAKE_CELLS;
    uint32_t n;
    qfoc_fake_cell_t *found = NULL;
    for (n = 0u; (n < QFOC_FAKE_CELLS) && (found == NULL); n++) {
        qfoc_fake_cell_t *c = &s_cells[i];
        if (c->used && (c->addr == addr)) {
            found = c;
        } else if (!c->used) {
            if (create) {
                c->used = true;
                c->addr = addr;
                c->value = 0u;
                s_order[s_count] = addr;
                s_count++;
                found = c;
            } else {
                n = QFOC_FAKE_CELLS;  /* absent */
            }
        } else {
            i = (i + 1u) % QFOC_FAKE_CELLS;
        }
    }
    if (create && (found == NULL)) {
        fprintf(stderr, "fake_regs: register file full\n");
        abort();
    }
    return found;
}

volatile uint32_t *qfoc_fake_reg(uint32_t addr)
{
    if ((addr % 4u) != 0u) {
        fprintf(stderr, "fake_regs: unaligned register address 0x%08lX\n", (unsigned long)addr);
        abort();
    }
    s_accesses++;
    if ((s_hook != NULL) && (!s_in_hook)) {
        s_in_hook = true;
        s_hook(addr);
        s_in_hook = false;
    }
    return &fake_find(addr, true)->value;
}

uint32_t qfoc_fake_peek(uint32_t addr)
{
    const qfoc_fake_cell_t *c = fake_find(addr, false);
    return (c != NULL) ? c->value : 0u;
}

void qfoc_fake_poke(uint32_t addr, uint32_t value)
{
    fake_find(addr, true)->value = value;
}

void qfoc_fake_reset(void)
{
    uint32_t i;
    for (i = 0u; i < QFOC_FAKE_CELLS; i++) {
        s_cells[i].used = false;
        s_cells[i].addr = 0u;
        s_cells[i].value = 0u;
    }
    s_count = 0u;
    s_accesses = 0u;
    s_hook = NULL;
    s_in_hook = false;
}

void qfoc_fake_set_hook(void (*hook)(uint32_t addr))
{
    s_hook = hook;
}

uint32_t qfoc_fake_count(void)
{
    return s_count;
}

uint32_t qfoc_fake_addr(uint32_t i)
{
    return (i < s_count) ? s_order[i] : 0u;
}

uint32_t qfoc_fake_accesses(void)
{
    return s_accesses;
}
