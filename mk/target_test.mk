# mk/target_test.mk -- golden-vector equivalence of the library on the Cortex-M4F and the host.
#
#   make target-test
#
# 1. tools/target_test/tt_gen.c (host, linked with build/host/libqfoc.a and the plant model
#    of sim/) writes the inputs of every public function group and of a closed-loop drive
#    run, and the host's outputs, to build/target_test/vectors.c;
# 2. the runner replays them: built for the host (a self-check: every group identical, and
#    the comparison reports a corrupted digest or input; once more with the library under
#    UndefinedBehaviorSanitizer), then for the Cortex-M4F with the
#    target build of the library (build/target/libqfoc.a, -O2) and run under QEMU's
#    mps2-an386 board with semihosting: every group must be bit-identical.
# tools/target_test/tt.h describes the vectors; specs/requirements/target.md the requirements.

TT_DIR  := tools/target_test
TT_OUT  := $(BUILD)/target_test
TT_HDRS := $(TT_DIR)/tt.h $(TT_DIR)/tt_io.h
# replay code shared by the generator and both runners
TT_COMMON := $(TT_DIR)/tt_groups.c $(TT_DIR)/tt_core.c
TT_QEMU := qemu-system-arm -M mps2-an386 -nographic -monitor none -serial none

TT_ARM_SRCS := $(TT_DIR)/tt_startup.c $(TT_DIR)/tt_target.c $(TT_DIR)/tt_runner.c $(TT_COMMON) \
               $(TT_OUT)/vectors.c
TT_ARM_OBJS := $(patsubst %.c,$(TT_OUT)/arm/%.o,$(notdir $(TT_ARM_SRCS)))
TT_ARM_LDFLAGS := -mcpu=cortex-m4 -mthumb -mfloat-abi=hard -mfpu=fpv4-sp-d16 -nostartfiles \
                  --specs=nano.specs -T $(TT_DIR)/tt_mps2_an386.ld -Wl,--gc-sections

.PHONY: target-test target-test-vectors

# ---------------------------------------------------------------- generator and vectors
# The shared replay code is compiled with the project's warning set; the generator itself
# is a host tool (doubles, stdio) built like the tests.
$(TT_OUT)/host/%.o: $(TT_DIR)/%.c $(TT_HDRS) $(HDRS) $(TABLE_HDRS)
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) -I$(TT_DIR) -Itables -c $< -o $@

$(TT_OUT)/tt_gen: $(TT_DIR)/tt_gen.c $(TT_OUT)/host/tt_groups.o $(TT_OUT)/host/tt_core.o \
                  $(BUILD)/host/libqfoc.a $(SIM_SRCS) $(SIM_HDRS) $(TABLE_SRCS) $(TABLE_HDRS) $(TT_HDRS)
	@mkdir -p $(@D)
	$(CC) $(TEST_CFLAGS) -O2 -I$(TT_DIR) -Isim -Itables $< $(TT_OUT)/host/tt_groups.o \
	    $(TT_OUT)/host/tt_core.o $(SIM_SRCS) $(TABLE_SRCS) $(BUILD)/host/libqfoc.a -lm \
	    -Wl,--wrap=qfoc_drive_fast_step,--wrap=qfoc_drive_tick,--wrap=qfoc_drive_shunt_measure \
	    -Wl,--wrap=qfoc_drive_shunt_output,--wrap=qfoc_drive_shunt_plan -o $@

$(TT_OUT)/vectors.c: $(TT_OUT)/tt_gen specs/motors/reference.toml
	$(TT_OUT)/tt_gen --motor specs/motors/reference.toml --out $(TT_OUT) --table > $(TT_OUT)/vectors.txt
	@tail -n 1 $(TT_OUT)/vectors.txt

$(TT_OUT)/vectors.h: $(TT_OUT)/vectors.c ;

## target-test-vectors: the golden vectors only (build/target_test/vectors.c, table in vectors.txt)
target-test-vectors: $(TT_OUT)/vectors.c

# ---------------------------------------------------------------- host runner
$(TT_OUT)/tt_runner_host: $(TT_DIR)/tt_host.c $(TT_DIR)/tt_runner.c $(TT_OUT)/host/tt_groups.o \
                          $(TT_OUT)/host/tt_core.o $(TT_OUT)/vectors.c $(TT_OUT)/vectors.h \
                          $(BUILD)/host/libqfoc.a $(TABLE_SRCS) $(TT_HDRS)
	$(CC) $(CFLAGS) -I$(TT_DIR) -I$(TT_OUT) -Itables $(TT_DIR)/tt_host.c $(TT_DIR)/tt_runner.c \
	    $(TT_OUT)/vectors.c $(TT_OUT)/host/tt_groups.o $(TT_OUT)/host/tt_core.o \
	    tables/reference_params.c tables/reference_shunt_params.c $(BUILD)/host/libqfoc.a -o $@

# The same runner with the library compiled from source under UndefinedBehaviorSanitizer:
# undefined behaviour is where a host and a target may part without either compiler
# warning; no vector may reach any.
$(TT_OUT)/tt_runner_ubsan: $(TT_DIR)/tt_host.c $(TT_DIR)/tt_runner.c $(TT_COMMON) $(TT_OUT)/vectors.c \
                           $(TT_OUT)/vectors.h $(SRCS) $(HDRS) $(TABLE_SRCS) $(TT_HDRS)
	$(CC) $(WARN) -O1 -g -fsanitize=undefined -fno-sanitize-recover=all -Iinclude -I$(TT_DIR) \
	    -I$(TT_OUT) -Itables $(TT_DIR)/tt_host.c $(TT_DIR)/tt_runner.c $(TT_COMMON) \
	    $(TT_OUT)/vectors.c tables/reference_params.c tables/reference_shunt_params.c $(SRCS) -o $@

# ---------------------------------------------------------------- Cortex-M4F runner
$(TT_OUT)/arm/vectors.o: $(TT_OUT)/vectors.c $(TT_OUT)/vectors.h $(TT_HDRS)
	@mkdir -p $(@D)
	$(ARM_CC) $(ARM_CFLAGS) -I$(TT_DIR) -I$(TT_OUT) -c $< -o $@

$(TT_OUT)/arm/%.o: $(TT_DIR)/%.c $(TT_HDRS) $(HDRS) $(TABLE_HDRS)
	@mkdir -p $(@D)
	$(ARM_CC) $(ARM_CFLAGS) -I$(TT_DIR) -I$(TT_OUT) -Itables -c $< -o $@

$(TT_OUT)/arm/tt_runner.o: $(TT_OUT)/vectors.h

$(TT_OUT)/tt_runner.elf: $(TT_ARM_OBJS) $(TT_DIR)/tt_mps2_an386.ld $(BUILD)/target/libqfoc.a \
                         $(BUILD)/target/tables/reference_params.o \
                         $(BUILD)/target/tables/reference_shunt_params.o
	$(ARM_CC) $(TT_ARM_LDFLAGS) -Wl,-Map=$(TT_OUT)/tt_runner.map $(TT_ARM_OBJS) \
	    $(BUILD)/target/tables/reference_params.o $(BUILD)/target/tables/reference_shunt_params.o \
	    $(BUILD)/target/libqfoc.a -o $@
	@arm-none-eabi-size $@ | tail -n 1 | awk '{printf "tt_runner.elf: %d B of code and vectors (of 4 MiB), %d B of RAM\n", $$1 + $$2, $$2 + $$3}'

# ---------------------------------------------------------------- the test
## target-test: golden vectors from the host replayed on Cortex-M4F (QEMU mps2-an386), bit for bit
target-test: deps $(TT_OUT)/tt_runner_host $(TT_OUT)/tt_runner_ubsan $(TT_OUT)/tt_runner.elf
	@QEMU="$(TT_QEMU)" sh $(TT_DIR)/target_test.sh $(TT_OUT)
