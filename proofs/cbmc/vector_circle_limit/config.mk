SRCS = src/qfoc_vector.c
UNWIND = 17
