SRCS = src/qfoc_link.c
UNWIND = 13
