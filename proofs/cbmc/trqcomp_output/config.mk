# qfoc_sincos and qfoc_atan2 replaced by stubs returning any value of their proved
# ranges (harness.c)
SRCS = src/qfoc_trqcomp.c
UNWIND = 2
GOTO_INSTRUMENT = --replace-calls qfoc_sincos:stub_sincos --replace-calls qfoc_atan2:stub_atan2
