/*
 * CBMC harness: the CRC-32 of the parameter table (REQ-PAR-002).
 *
 * The library file is included, so that its static helpers can be checked one by one.
 *  - qfoc_crc32_byte() equals the CRC-32 register update written here from the
 *    definition (reflected polynomial 0xEDB88320, LSB first, 8 steps per byte) for
 *    every register value and every byte: the 16-entry nibble table of
 *    qfoc_crc32_nibble() is checked entry by entry through it;
 *  - the helpers that take several bytes at once equal the byte-wise definition
 *    over their bytes in little-endian order, for every register value and every
 *    field value: qfoc_crc_u16() (2 bytes), qfoc_crc_u32() (4 bytes),
 *    qfoc_crc_2x16() (two 16-bit fields, the first one first), and qfoc_bits16() is
 *    the two's-complement pattern of every int16_t;
 *  - qfoc_params_crc() runs without undefined behaviour on any bit pattern of the
 *    table (every field nondet), the drive configuration of layout version 2 included
 *    (REQ-PAR-006).
 * That the serialisation covers every field in the order of params.h is tested
 * against an independent table-driven CRC over 2000 random tables and the
 * generated tables (tests/test_params.c); an equivalence miter of the whole
 * 199-byte serialisation does not finish within the time budget.
 *
 * Methods: 1b every register value and every byte, every int16 and field value of the
 * helpers, every bit pattern of the table; 1c the 16 entries of the nibble table
 * checked one by one
 */
#include <stdint.h>
#include <stdbool.h>
#include "qfoc/params.h"
#include "../harness_util.h"
/* the unit under proof, its static helpers included (not in SRCS: config.mk) */
#include "../../../src/qfoc_params.c"

/* the CRC-32 register after one byte, from the definition: 8 steps, LSB first */
static uint32_t def_byte(uint32_t reg, uint32_t byte)
{
    uint32_t r = reg ^ byte;
    int k;

    for (k = 0; k < 8; k++) {
        r = ((r & 1u) != 0u) ? ((r >> 1) ^ 0xEDB88320u) : (r >> 1);
    }
    return r;
}

int main(void)
{
    qfoc_param_table_t t;
    const uint32_t reg = nondet_uint32();
    const uint8_t byte = nondet_uint8();
    const uint16_t lo = nondet_uint16();
    const uint16_t hi = nondet_uint16();
    const int16_t s = nondet_int16();
    const uint32_t w = nondet_uint32();
    uint32_t crc;

    __CPROVER_assert(qfoc_crc32_byte(reg, byte) == def_byte(reg, byte),
                     "byte update equals the CRC-32 definition");
    __CPROVER_assert(qfoc_crc_u16(reg, lo) == def_byte(def_byte(reg, lo & 0xFFu), lo >> 8),
                     "16-bit update equals its two bytes, low byte first");
    __CPROVER_assert(qfoc_crc_u32(reg, w)
                         == def_byte(def_byte(def_byte(def_byte(reg, w & 0xFFu),
                                                       (w >> 8) & 0xFFu),
                                              (w >> 16) & 0xFFu),
                                     w >> 24),
                     "32-bit update equals its four bytes, little-endian");
    __CPROVER_assert(qfoc_crc_2x16(reg, lo, hi)
                         == def_byte(def_byte(def_byte(def_byte(reg, lo & 0xFFu), lo >> 8),
                                              hi & 0xFFu),
                                     hi >> 8),
                     "two 16-bit fields equal their four bytes, the first field first");
    __CPROVER_assert((uint32_t)qfoc_bits16(s) == ((s < 0) ? (uint32_t)((int32_t)s + 65536)
                                                           : (uint32_t)s),
                     "bit pattern of a signed 16-bit field");

    __CPROVER_havoc_object(&t);
    crc = qfoc_params_crc(&t);
    (void)crc;
    return 0;
}
