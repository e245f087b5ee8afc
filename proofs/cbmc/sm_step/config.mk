SRCS = src/qfoc_sm.c
UNWIND = 41
