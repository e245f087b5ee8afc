SRCS = src/qfoc_pi.c
UNWIND = 1
