SRCS = src/qfoc_params.c src/qfoc_drive_cfg.c src/qfoc_pi.c src/qfoc_svpwm.c src/qfoc_flux.c src/qfoc_pll.c src/qfoc_filter.c src/qfoc_trig.c src/qfoc_trig_tables.c src/qfoc_vector.c src/qfoc_isqrt.c
UNWIND = 250
GOTO_INSTRUMENT = --replace-calls qfoc_params_crc:harness_crc_any
# The rpm cross-field condition multiplies two 16-bit fields in the library and in the
# harness's reference: as a propositional miter of two multipliers it does not finish;
# the SMT back end (z3) identifies the two products and proves the harness in ~2 min.
CBMC_EXTRA = --z3
