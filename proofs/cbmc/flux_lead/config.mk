SRCS = src/qfoc_flux.c src/qfoc_trig.c src/qfoc_trig_tables.c
UNWIND = 2
