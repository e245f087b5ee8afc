SRCS = src/qfoc_transforms.c
UNWIND = 1
