SRCS = src/qfoc_emf.c src/qfoc_filter.c src/qfoc_trig.c src/qfoc_trig_tables.c
UNWIND = 35
