SRCS = src/qfoc_drive_cfg.c src/qfoc_pi.c src/qfoc_svpwm.c src/qfoc_flux.c src/qfoc_pll.c src/qfoc_filter.c src/qfoc_trig.c src/qfoc_trig_tables.c src/qfoc_vector.c src/qfoc_isqrt.c
UNWIND = 9
