# qfoc_sincos replaced by a stub returning any value of its proved range (harness.c)
SRCS = src/qfoc_trqcomp.c
UNWIND = 2
GOTO_INSTRUMENT = --replace-calls qfoc_sincos:stub_sincos
