SRCS = src/qfoc_flux.c
UNWIND = 1
