SRCS = src/qfoc_ramp.c
UNWIND = 1
