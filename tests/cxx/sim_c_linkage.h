/*
 * sim_c_linkage.h -- the plant model's header (sim/sim.h) with C linkage, for
 * examples/host_plant.c compiled as C++ by tools/gates/cxx_check.sh (g++ -include).
 *
 * The plant model is host-only C outside the library, compiled by gcc; its header has no
 * extern "C" guards.  Included first, it declares the plant's functions with C linkage;
 * the example's own #include "sim.h" then finds the header's guard defined.
 */
#ifndef QFOC_TESTS_SIM_C_LINKAGE_H
#define QFOC_TESTS_SIM_C_LINKAGE_H

#ifndef __cplusplus
#error "sim_c_linkage.h is for C++ translation units only"
#endif

#include <stdbool.h>
#include <stdint.h>

extern "C" {
#include "sim.h"
}

#endif /* QFOC_TESTS_SIM_C_LINKAGE_H */
