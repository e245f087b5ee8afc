SRCS = src/qfoc_fault.c src/qfoc_filter.c
UNWIND = 13
