/**
 * @file tables_registry.h
 * @brief The parameter tables of tables/manifest.txt, in its order (the first is the
 *        reference motor).  The definition is generated from the manifest by the
 *        Makefile (build/host/gen/tables_registry.c), so a new table needs no code.
 */
#ifndef QFOC_SIM_TABLES_REGISTRY_H
#define QFOC_SIM_TABLES_REGISTRY_H

#include "scenario.h"

extern const scn_table_t scn_tables[];
extern const int scn_n_tables;

#endif /* QFOC_SIM_TABLES_REGISTRY_H */
