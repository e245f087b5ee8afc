SRCS = src/qfoc_trqcomp.c
UNWIND = 17
