/* Translation unit that gives Frama-C the static inline Q15 primitives of
 * include/qfoc/q15.h to prove (they have no .c file of their own). */
#include "qfoc/q15.h"
