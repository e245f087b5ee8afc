/*
 * test_version.c -- unit tests of the release version (include/qfoc/version.h).
 *
 * Reference: the version text QFOC_VERSION_STRING, parsed here as three decimal
 * numbers, against the three integer macros, the packed word and the library's
 * qfoc_version().
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <cmocka.h>

#include "qfoc/version.h"

/* parse "M.m.p" (decimal, each 0 .. 255) into three numbers; 1 when it parses */
static int parse_version(const char *s, unsigned *major, unsigned *minor, unsigned *patch)
{
    char tail = '\0';
    const int n = sscanf(s, "%3u.%3u.%3u%c", major, minor, patch, &tail);
    return (n == 3) && (*major <= 255u) && (*minor <= 255u) && (*patch <= 255u);
}

/* REQ-VER-001: the string, the three numbers and the packed word agree; this release
 * Methods: 1a the string, the three numbers and the packed word of REQ-VER-001 computed from
 * each other (word = major << 16 | minor << 8 | patch) and the release's value */
static void test_version_macros(void **state)
{
    unsigned major = 0u;
    unsigned minor = 0u;
    unsigned patch = 0u;
    char text[16];
    (void)state;
    assert_true(parse_version(QFOC_VERSION_STRING, &major, &minor, &patch));
    assert_int_equal(major, QFOC_VERSION_MAJOR);
    assert_int_equal(minor, QFOC_VERSION_MINOR);
    assert_int_equal(patch, QFOC_VERSION_PATCH);
    /* the string is exactly the three numbers in decimal, no leading zeros, no suffix */
    (void)snprintf(text, sizeof text, "%u.%u.%u", major, minor, patch);
    assert_string_equal(text, QFOC_VERSION_STRING);
    assert_int_equal(QFOC_VERSION, (major << 16) | (minor << 8) | patch);
    assert_true(QFOC_VERSION <= 0x00FFFFFFu);
    /* the release these sources are */
    assert_string_equal(QFOC_VERSION_STRING, "0.2.0");
    assert_int_equal(QFOC_VERSION, 0x00000200u);
    /* the macros' types: 8-bit constants, the word 32 bits */
    assert_int_equal(sizeof(QFOC_VERSION_MAJOR), 1u);
    assert_int_equal(sizeof(QFOC_VERSION), 4u);
}

/* REQ-VER-002: the library's word is the headers' version; its fields read back
 * Methods: 1a the library's word and string of REQ-VER-002 against the headers' macros,
 * field by field */
static void test_version_library(void **state)
{
    const uint32_t v = qfoc_version();
    unsigned major = 0u;
    unsigned minor = 0u;
    unsigned patch = 0u;
    (void)state;
    assert_int_equal(v, QFOC_VERSION);
    assert_int_equal(v, qfoc_version());
    assert_true(parse_version(QFOC_VERSION_STRING, &major, &minor, &patch));
    assert_int_equal((v >> 16) & 0xFFu, major);
    assert_int_equal((v >> 8) & 0xFFu, minor);
    assert_int_equal(v & 0xFFu, patch);
    assert_int_equal(v >> 24, 0u);
    /* the library's text: the headers' string, the same storage on every call */
    assert_non_null(qfoc_version_string());
    assert_string_equal(qfoc_version_string(), QFOC_VERSION_STRING);
    assert_ptr_equal(qfoc_version_string(), qfoc_version_string());
    assert_true(strlen(qfoc_version_string()) <= 11u);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_version_macros),
        cmocka_unit_test(test_version_library),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
