/**
 * @file version.h
 * @brief qfoc release version: the header's macros and the library's function.
 *
 * The version follows semantic versioning (major.minor.patch): the major number
 * changes with an incompatible change of the public interface (a function, a type's
 * layout, the parameter table's layout), the minor number with an addition that keeps
 * the interface compatible, the patch number with a correction only.  While the major
 * number is 0 a minor change may still change the interface (the CHANGELOG names it).
 *
 * Integrator's check at start-up: the macros are the version of the headers the
 * application was compiled with, qfoc_version() the version the library was compiled
 * with.  Compare the two once, before qfoc_drive_init(), and keep the drive off when
 * they differ (e.g. a libqfoc.a of another release linked with these headers):
 * @code
 *   if (qfoc_version() != QFOC_VERSION) {
 *       // headers and library are of different releases: do not start the drive
 *   }
 * @endcode
 * A looser check compares the major number only (and, while the major number is 0,
 * the minor number as well): (qfoc_version() >> 16) == QFOC_VERSION_MAJOR.
 *
 * Requirements: REQ-VER-001, REQ-VER-002 (specs/requirements/version.md).
 */
#ifndef QFOC_VERSION_H
#define QFOC_VERSION_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Major version: incompatible interface changes. */
#define QFOC_VERSION_MAJOR ((uint8_t)0u)
/** Minor version: compatible additions. */
#define QFOC_VERSION_MINOR ((uint8_t)2u)
/** Patch version: corrections only. */
#define QFOC_VERSION_PATCH ((uint8_t)0u)

/** The version as text, "major.minor.patch" (the same numbers as the three macros). */
#define QFOC_VERSION_STRING "0.2.0"

/**
 * The version packed in one word, 0x00MMmmpp: major in bits 23..16, minor in bits
 * 15..8, patch in bits 7..0 (0.2.0 is 0x00000200); later releases compare greater.
 */
#define QFOC_VERSION ((((uint32_t)QFOC_VERSION_MAJOR) << 16u) | \
                      (((uint32_t)QFOC_VERSION_MINOR) << 8u) | \
                      ((uint32_t)QFOC_VERSION_PATCH))

/**
 * @brief The version the library was compiled with, packed as QFOC_VERSION.
 * @return 0x00MMmmpp: major << 16 | minor << 8 | patch, of the library's own build
 *         (equal to QFOC_VERSION when the headers are of the same release)
 *
 * Bad input: none (no argument).  Pure: reads and writes no memory.
 *
 * Requirements: REQ-VER-001, REQ-VER-002.
 */
/*@
  assigns \nothing;
  ensures value: \result == QFOC_VERSION;
  ensures layout: \result == (QFOC_VERSION_MAJOR * 65536 + QFOC_VERSION_MINOR * 256 +
                              QFOC_VERSION_PATCH);
  ensures range: \result <= 0x00FFFFFFu;
*/
uint32_t qfoc_version(void);

/**
 * @brief The version text the library was compiled with, for a diagnostic or a log.
 * @return a pointer to the library's constant, zero-terminated QFOC_VERSION_STRING
 *         ("major.minor.patch", at most 11 characters); never NULL, valid for the
 *         program's lifetime, read only
 *
 * Bad input: none (no argument).  Reads and writes no memory.
 *
 * Requirements: REQ-VER-002.
 */
/*@
  assigns \result \from \nothing;
  ensures valid: \valid_read(\result + (0 .. (sizeof(QFOC_VERSION_STRING) - 1)));
  ensures terminated: \result[sizeof(QFOC_VERSION_STRING) - 1] == '\0';
*/
const char *qfoc_version_string(void);

#ifdef __cplusplus
}
#endif

#endif /* QFOC_VERSION_H */
