SRCS = src/qfoc_isqrt.c
UNWIND = 3
