# mk/pil.mk -- processor in the loop (port_s32k/pil/): the firmware image of `make firmware`
# run unchanged from its reset vector on an emulated Cortex-M4 (Unicorn) with register-level
# models of the S32K144 peripherals and real interrupts, driving the simulated motor of
# sim/, in lock-step with the host build of the same drive.  Included by the Makefile
# (mk/*.mk); `make check` runs the short form, make pil-check (tools/gates/check.sh).
#
#   make pil          the scenario table (port_s32k/pil/scenarios.py): start, speed step,
#                     stop, over-current, link loss, stalled and stuck ADC, pre-empted tick;
#                     exit status 1 on a failed target or a lock-step divergence; the
#                     image's measured timing in $(PIL_TIMING) for make bench
#   make pil-run      one run of port_s32k/pil/run.py with PIL_ARGS (the first slice's run)
#   make pil-test     the emulator's own tests (port_s32k/pil/tests/test_pil.py, pytest)
#   make pil-check    the short form (< 60 s): pil-test and the short scenario with lock-step
#   make pil-defects  seeded port defects, each built into its own image under
#                     build/pil/defects/: caught or missed (port_s32k/pil/defects.py)

PIL_LIB     := $(BUILD)/pil/libpilplant.so
PIL_TWIN    := $(BUILD)/pil/libpiltwin.so
# the 8 kHz image of mk/port.mk (named here: mk/port.mk is read after this file)
PIL_ELF     := $(BUILD)/s32k144/qfoc_compressor.elf
PIL_SRCS    := port_s32k/pil/pil_plant.c sim/plant.c sim/motor.c
PIL_ARGS    ?= --ms 1200 --lin-period-ms 20 --power-on-ms 350 --lockstep
PIL_LOGS    := $(BUILD)/pil/scenarios
# the measured timing of the image over the scenarios of make pil (port_s32k/pil/timing.py),
# reported by make bench beside the bench's static bounds (mk/bench.mk)
PIL_TIMING  := $(BUILD)/pil/timing.json
pil_comma   := ,

.PHONY: pil pil-run pil-test pil-check pil-defects

# The plant only (no library code): sim/plant.c, sim/motor.c and the flat interface of
# port_s32k/pil/pil_plant.c, loaded by port_s32k/pil/plant.py with ctypes.
$(PIL_LIB): $(PIL_SRCS) sim/sim.h mk/pil.mk
	@mkdir -p $(@D)
	$(CC) -std=c99 -Wall -Wextra -Werror -O2 -shared -fPIC -Isim $(PIL_SRCS) -lm -o $@

# The host twin of the image's drive: the library's sources with the image's table
# (tables/reference_params.c, as FW_TABLE_SRC of the 8 kHz image), port_s32k/pil/twin.py.
$(PIL_TWIN): port_s32k/pil/pil_twin.c $(SRCS) $(HDRS) $(wildcard src/*.h) tables/reference_params.c tables/reference_params.h mk/pil.mk
	@mkdir -p $(@D)
	$(CC) -std=c99 -Wall -Wextra -Werror -O2 -shared -fPIC -Iinclude -Itables port_s32k/pil/pil_twin.c \
	    tables/reference_params.c $(SRCS) -o $@

## pil: processor in the loop: the scenario table (image from reset in an emulator, sim/ motor, lock-step with the host build)
pil: $(PIL_ELF) $(PIL_LIB) $(PIL_TWIN)
	$(PYTHON) port_s32k/pil/scenarios.py $(PIL_ELF) --lib $(PIL_LIB) --twin-lib $(PIL_TWIN) --log-dir $(PIL_LOGS) \
	    --timing-json $(PIL_TIMING)

## pil-run: one processor-in-the-loop run with PIL_ARGS (port_s32k/pil/run.py)
pil-run: $(PIL_ELF) $(PIL_LIB) $(PIL_TWIN)
	$(PYTHON) port_s32k/pil/run.py $(PIL_ELF) --lib $(PIL_LIB) --twin-lib $(PIL_TWIN) $(PIL_ARGS)

## pil-test: the processor-in-the-loop emulator's tests (exception entry/return, pre-emption, stops)
pil-test: $(PIL_ELF) $(PIL_LIB) $(PIL_TWIN)
	@mkdir -p $(BUILD)/junit
	$(PYTHON) -m pytest -q --junitxml=$(BUILD)/junit/pytest-pil.xml -o junit_suite_name=pytest port_s32k/pil/tests

## pil-check: short form of make pil (< 60 s): the emulator's tests and the short scenario in lock-step
pil-check: $(PIL_ELF) $(PIL_LIB) $(PIL_TWIN)
	@mkdir -p $(BUILD)/junit
	$(PYTHON) -m pytest -q --junitxml=$(BUILD)/junit/pytest-pil.xml -o junit_suite_name=pytest port_s32k/pil/tests
	$(PYTHON) port_s32k/pil/scenarios.py $(PIL_ELF) --only short --lib $(PIL_LIB) --twin-lib $(PIL_TWIN) \
	    --log-dir $(PIL_LOGS)

## pil-defects: seeded port defects (PDB delay, channel pair, dead time, complementary mode, clock divider, ADC priority) each in its own image: caught or missed
pil-defects: $(BUILD)/target/libqfoc.a $(PIL_LIB) $(PIL_TWIN)
	$(PYTHON) port_s32k/pil/defects.py --cc $(ARM_CC) --cflags "$(ARM_CFLAGS) $(FW_DEFS) -g" \
	    --ldflags "$(filter-out -T $(FW_LD) -Wl$(pil_comma)-Map=$(FW_MAP),$(FW_LDFLAGS))" \
	    --lib $(BUILD)/target/libqfoc.a --plant-lib $(PIL_LIB) --twin-lib $(PIL_TWIN) --out $(BUILD)/pil/defects
