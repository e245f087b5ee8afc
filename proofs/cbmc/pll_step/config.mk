SRCS = src/qfoc_pll.c src/qfoc_pi.c src/qfoc_filter.c src/qfoc_vector.c
UNWIND = 17
