SRCS = src/qfoc_svpwm.c src/qfoc_transforms.c src/qfoc_vector.c
UNWIND = 17
