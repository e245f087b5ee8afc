SRCS = src/qfoc_filter.c
UNWIND = 1
