SRCS = src/qfoc_emf.c src/qfoc_filter.c
UNWIND = 2
