/**
 * @file qfoc_version.c
 * @brief Release version compiled into the library (see include/qfoc/version.h).
 *
 * Requirements: REQ-VER-001, REQ-VER-002 (specs/requirements/version.md).
 */
#include "qfoc/version.h"

uint32_t qfoc_version(void)
{
    /* the macros of the header this unit was compiled with: the library's version */
    return QFOC_VERSION;
}

const char *qfoc_version_string(void)
{
    /* static storage in the library's read-only data, zero-terminated */
    static const char text[] = QFOC_VERSION_STRING;
    return text;
}
