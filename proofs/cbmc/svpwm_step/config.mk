SRCS = src/qfoc_svpwm.c
UNWIND = 2
