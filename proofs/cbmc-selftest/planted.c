/* proofs/cbmc-selftest/planted.c -- the CBMC gate's own check of its SAT back end.
 *
 * tools/gates/cbmc.sh runs this program with the flags and the solver of every harness before
 * the harnesses, and stops unless CBMC reports exactly what is planted here: the signed
 * product overflows for some inputs (a FAILURE with a counterexample, which needs the
 * solver's model to be read back), and the assertion holds for every input (a SUCCESS,
 * which needs the solver's UNSAT verdict to be read back).  A back end that loses either
 * answer would make every harness's result meaningless.
 */
#include <stdint.h>

int32_t nondet_i32(void);

int main(void)
{
    int32_t a = nondet_i32();
    int32_t b = nondet_i32();
    __CPROVER_assume((a > 40000) && (b > 60000));
    int32_t planted = a * b;              /* overflows: 40001 * 60001 > INT32_MAX */
    (void)planted;
    int16_t x = (int16_t)(nondet_i32() & 0x3FFF);
    __CPROVER_assert((int32_t)x * (int32_t)x <= 0x0FFF8001, "selftest: square of a 14-bit value");
    return 0;
}
