SRCS = src/qfoc_fw.c src/qfoc_pi.c src/qfoc_filter.c
UNWIND = 1
