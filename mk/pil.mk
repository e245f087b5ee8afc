# mk/pil.mk -- processor in the loop (port_s32k/pil/): the firmware image of `make firmware`
# run unchanged from its reset vector on an emulated Cortex-M4 (Unicorn) with register-level
# models of the S32K144 peripherals and real interrupts, driving the simulated motor of
# sim/.  Included by the Makefile (mk/*.mk); not part of `make check`.
#
#   make pil        the scenario: reset, PRECHARGE -> STOP, LIN start command, RUN
#                   (port_s32k/pil/run.py; exit status 1 on a failed expectation)
#   make pil-test   the emulator's own tests (port_s32k/pil/tests/test_pil.py, pytest)

PIL_LIB     := $(BUILD)/pil/libpilplant.so
# the 8 kHz image of mk/port.mk (named here: mk/port.mk is read after this file)
PIL_ELF     := $(BUILD)/s32k144/qfoc_compressor.elf
PIL_SRCS    := port_s32k/pil/pil_plant.c sim/plant.c sim/motor.c
PIL_ARGS    ?= --ms 1200 --lin-period-ms 20 --power-on-ms 350

.PHONY: pil pil-test

# The plant only (no library code): sim/plant.c, sim/motor.c and the flat interface of
# port_s32k/pil/pil_plant.c, loaded by port_s32k/pil/plant.py with ctypes.
$(PIL_LIB): $(PIL_SRCS) sim/sim.h mk/pil.mk
	@mkdir -p $(@D)
	$(CC) -std=c99 -Wall -Wextra -Werror -O2 -shared -fPIC -Isim $(PIL_SRCS) -lm -o $@

## pil: processor in the loop: the S32K144 image from reset in an emulator, real interrupts, the sim/ motor
pil: $(PIL_ELF) $(PIL_LIB)
	$(PYTHON) port_s32k/pil/run.py $(PIL_ELF) --lib $(PIL_LIB) $(PIL_ARGS)

## pil-test: the processor-in-the-loop emulator's tests (exception entry/return, pre-emption, stops)
pil-test: $(PIL_ELF) $(PIL_LIB)
	$(PYTHON) -m pytest -q port_s32k/pil/tests
