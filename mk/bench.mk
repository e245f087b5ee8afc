# ---------------------------------------------------------------- bench (Cortex-M4F)
# Instructions executed by every library function and by the drive's two entry points,
# counted in Unicorn on the -O2 Cortex-M4F build; flash, RAM, worst-case stack
# (tools/bench/, specs/requirements/bench.md).  Report: build/bench/bench.md and bench.json.
# The bench fails when a figure is above its limit or a measured count above its static bound
# (tools/bench/wcet.py, tested by tools/bench/tests; the goals are reported only).
# bench.json and bench.md are stamped with the run's UTC time and the SHA-256 of their inputs
# (tools/evidence/inputs.py bench; the list in build/bench/inputs-bench.sha256).
# When make pil has run, its measured timing of the firmware image (build/pil/timing.json,
# port_s32k/pil/timing.py) is reported beside the static bounds (REQ-PIL-006); a measured
# count above its static bound fails the bench.
#
# The library objects are compiled again here with $(ARM_CFLAGS) plus -fcallgraph-info=su,
# which only adds the call graph with frame sizes (.ci beside each .o and .su).

BENCH_DIR   := $(BUILD)/bench
BENCH_OBJ   := $(BENCH_DIR)/obj
BENCH_LIB_OBJS := $(patsubst src/%.c,$(BENCH_OBJ)/%.o,$(SRCS))
BENCH_ARM_LDFLAGS := $(filter -mcpu=% -mthumb -mfloat-abi=% -mfpu=%,$(ARM_CFLAGS)) \
                     -nostartfiles -nostdlib
BENCH_HDRS  := tools/bench/harness.h tools/bench/replay.h

# The recordings: the host build of the drive in closed loop with the plant model
# (reference motor and table).  fwtc: field weakening and torque compensation active at
# once.  The compensation's window ends at the table's tc_speed_max (5160 rpm, derived by
# the tool from the loops' phase, docs/tune.md), so field weakening must start below it:
# the lowest operating bus (250 V) and a load above nominal (4.7 N m, +-10 % at 1x, which
# keeps the d current negative through the pulsation's trough); fw8000: deep field
# weakening at the top speed.
BENCH_FWTC_ARGS   := --vdc 250 --rpm 5150 --load 4.7 --pulse 0.1 --need-tc
BENCH_FWTC_TITLE  := CLOSED_LOOP at 5150 rpm and 250 V, field weakening and torque compensation active
BENCH_FW8000_ARGS := --vdc 320 --rpm 8000 --load 4.5
BENCH_FW8000_TITLE := CLOSED_LOOP at 8000 rpm and 320 V, deep field weakening

.PHONY: bench

$(BENCH_OBJ)/%.o: src/%.c $(HDRS)
	@mkdir -p $(@D)
	$(ARM_CC) $(ARM_CFLAGS) -fcallgraph-info=su -c $< -o $@

$(BENCH_OBJ)/reference_params.o: tables/reference_params.c $(TABLE_HDRS) $(HDRS)
	@mkdir -p $(@D)
	$(ARM_CC) $(ARM_CFLAGS) -Itables -c $< -o $@

$(BENCH_OBJ)/harness.o: tools/bench/harness.c $(BENCH_HDRS) $(TABLE_HDRS) $(HDRS)
	@mkdir -p $(@D)
	$(ARM_CC) $(ARM_CFLAGS) -Itables -Itools/bench -c $< -o $@

# The bench image: every function kept (bench.ld), no start-up code; newlib only for the
# memcpy of qfoc_params_load.
$(BENCH_DIR)/bench.elf: $(BENCH_LIB_OBJS) $(BENCH_OBJ)/reference_params.o $(BENCH_OBJ)/harness.o \
                        tools/bench/bench.ld
	$(ARM_CC) $(BENCH_ARM_LDFLAGS) -T tools/bench/bench.ld -Wl,-Map=$(BENCH_DIR)/bench.map \
	    $(BENCH_LIB_OBJS) $(BENCH_OBJ)/reference_params.o $(BENCH_OBJ)/harness.o -lc -o $@

# What a drive firmware links of the library: its three entry points, --gc-sections.
$(BENCH_DIR)/drive_only.elf: $(BENCH_LIB_OBJS)
	$(ARM_CC) $(BENCH_ARM_LDFLAGS) -Wl,--gc-sections -Wl,-e,qfoc_drive_init \
	    -Wl,-u,qfoc_drive_fast_step -Wl,-u,qfoc_drive_tick $(BENCH_LIB_OBJS) -lc -o $@

$(BENCH_DIR)/gen_replay: tools/bench/gen_replay.c tools/bench/replay.h $(SIM_SRCS) $(SIM_HDRS) \
                         $(TABLE_SRCS) $(TABLE_HDRS) $(BUILD)/host/libqfoc.a
	@mkdir -p $(@D)
	$(CC) $(TEST_CFLAGS) -O2 -Isim -Itables -Itools/bench $< $(SIM_SRCS) $(TABLE_SRCS) \
	    $(BUILD)/host/libqfoc.a -lm -o $@

$(BENCH_DIR)/fwtc.bin: $(BENCH_DIR)/gen_replay specs/motors/reference.toml
	$(BENCH_DIR)/gen_replay --out $@ --motor specs/motors/reference.toml $(BENCH_FWTC_ARGS)

$(BENCH_DIR)/fw8000.bin: $(BENCH_DIR)/gen_replay specs/motors/reference.toml
	$(BENCH_DIR)/gen_replay --out $@ --motor specs/motors/reference.toml $(BENCH_FW8000_ARGS)

## bench: instructions per function and per drive step on the Cortex-M4F (Unicorn) and their static bounds (wcet.py), flash, RAM, stack: build/bench/bench.md
bench: deps $(BENCH_DIR)/bench.elf $(BENCH_DIR)/drive_only.elf $(BENCH_DIR)/fwtc.bin \
       $(BENCH_DIR)/fw8000.bin
	@sh tools/bench/isqrt_steps.sh $(BENCH_DIR)
	@mkdir -p $(BUILD)/junit && $(PYTHON) -m pytest -q -p no:cacheprovider \
	    --junitxml=$(BUILD)/junit/pytest-bench.xml -o junit_suite_name=pytest tools/bench/tests
	@t0=$$(date +%s); rc=0; rm -f $(BENCH_DIR)/bench.json $(BENCH_DIR)/bench.md; \
	 $(PYTHON) tools/bench/count.py --elf $(BENCH_DIR)/bench.elf \
	    --drive-elf $(BENCH_DIR)/drive_only.elf --obj-dir $(BENCH_OBJ) \
	    --replay "fwtc=$(BENCH_DIR)/fwtc.bin=$(BENCH_FWTC_TITLE)" \
	    --replay "fw8000=$(BENCH_DIR)/fw8000.bin=$(BENCH_FW8000_TITLE)" \
	    --out-dir $(BENCH_DIR) --cc $(ARM_CC) --cflags "$(ARM_CFLAGS) -fcallgraph-info=su" \
	    $(if $(wildcard $(BUILD)/pil/timing.json),--pil-timing $(BUILD)/pil/timing.json) || rc=$$?; \
	 for f in $(BENCH_DIR)/bench.json $(BENCH_DIR)/bench.md; do \
	     [ -f "$$f" ] && { $(PYTHON) tools/evidence/inputs.py --stamp "$$f" bench --started "$$t0" > /dev/null || rc=1; }; \
	 done; exit $$rc
