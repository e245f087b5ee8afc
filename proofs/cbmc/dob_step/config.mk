SRCS = src/qfoc_emf.c
UNWIND = 2
