SRCS = src/qfoc_drive_cfg.c
UNWIND = 120
