# qfoc -- verified Q15 field-oriented control for sensorless PMSM compressor drives.
#
#   make demo      build and run the demonstration (installs what it needs)
#   make check     every test and gate; non-zero exit on any shortfall
#
# Every target that needs a tool depends on 'deps', which installs the Debian
# packages and CBMC on a fresh bookworm machine and returns at once when they are
# already there.  See README.md for the full list of targets.

SHELL := /bin/sh
.DEFAULT_GOAL := help

BUILD   := build
SRCS    := $(sort $(wildcard src/*.c))
HDRS    := $(sort $(wildcard include/qfoc/*.h))
TESTS   := $(sort $(wildcard tests/test_*.c))
SIM_SRCS := $(sort $(wildcard sim/*.c))
SIM_HDRS := $(sort $(wildcard sim/*.h))
TEST_BINS := $(patsubst tests/%.c,$(BUILD)/host/tests/%,$(TESTS))

WARN    := -std=c99 -Wall -Wextra -Wconversion -Wsign-conversion -Wshadow \
           -Wstrict-prototypes -Wmissing-prototypes -Wundef -Wcast-qual -Werror
CC      := gcc
CFLAGS  := $(WARN) -O2 -g -Iinclude
TEST_CFLAGS := -std=c99 -Wall -Wextra -Werror -O1 -g -Iinclude

ARM_CC  := arm-none-eabi-gcc
ARM_AR  := arm-none-eabi-ar
ARM_CFLAGS := $(WARN) -mcpu=cortex-m4 -mthumb -mfloat-abi=hard -mfpu=fpv4-sp-d16 -O2 \
              -ffunction-sections -fdata-sections -ffreestanding -fstack-usage -Iinclude

HOST_OBJS := $(patsubst src/%.c,$(BUILD)/host/obj/%.o,$(SRCS))
ARM_OBJS  := $(patsubst src/%.c,$(BUILD)/target/obj/%.o,$(SRCS))
COV_OBJS  := $(patsubst src/%.c,$(BUILD)/cov/obj/%.o,$(SRCS))

.PHONY: help deps lib test coverage prove cbmc misra target trace check demo clean estimator-report

help:
	@echo "qfoc: make demo | make check   (README.md describes every target)"
	@sed -n 's/^## /  /p' $(firstword $(MAKEFILE_LIST))

## deps: install the Debian packages and CBMC (idempotent)
deps:
	@sh tools/deps.sh

# ---------------------------------------------------------------- host library
$(BUILD)/host/obj/%.o: src/%.c $(HDRS)
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) -c $< -o $@

$(BUILD)/host/libqfoc.a: $(HOST_OBJS)
	@rm -f $@
	ar rcs $@ $^

## lib: the host library build/host/libqfoc.a
lib: $(BUILD)/host/libqfoc.a

# ---------------------------------------------------------------- unit tests
# Tests link the plant model of sim/ (double precision, host only) as well.
$(BUILD)/host/tests/%: tests/%.c $(BUILD)/host/libqfoc.a $(SIM_SRCS) $(SIM_HDRS)
	@mkdir -p $(@D)
	$(CC) $(TEST_CFLAGS) -Isim $< $(SIM_SRCS) $(BUILD)/host/libqfoc.a -lcmocka -lm -o $@

## test: CMocka unit tests against double-precision references
test: deps $(TEST_BINS)
	@sh tools/run_tests.sh $(TEST_BINS)

# ---------------------------------------------------------------- coverage
# Library objects built with --coverage (one -c per file, so gcc names the notes
# after the source), the same tests linked against them, gcovr gate on src/ and the
# inline header code in include/: 100 % of lines and branches.
$(BUILD)/cov/obj/%.o: src/%.c $(HDRS)
	@mkdir -p $(@D)
	$(CC) $(WARN) -O0 -g --coverage -Iinclude -c $< -o $@

## coverage: 100 % line and branch gate (gcovr), HTML report
coverage: deps $(COV_OBJS)
	@sh tools/coverage.sh "$(COV_OBJS)" $(TESTS)

# ---------------------------------------------------------------- formal proofs
## prove: Frama-C WP on every unit, proved N / M goals
prove: deps
	@sh tools/prove.sh

## cbmc: every CBMC harness under proofs/cbmc
cbmc: deps
	@sh tools/cbmc.sh

# ---------------------------------------------------------------- traceability
## trace: every requirement exercised by a test or harness and named in a header
trace:
	@python3 tools/trace.py

# ---------------------------------------------------------------- MISRA C:2012
## misra: cppcheck MISRA C:2012 addon, deviations recorded
misra: deps
	@sh tools/misra.sh

# ---------------------------------------------------------------- Cortex-M4F build
$(BUILD)/target/obj/%.o: src/%.c $(HDRS)
	@mkdir -p $(@D)
	$(ARM_CC) $(ARM_CFLAGS) -c $< -o $@

$(BUILD)/target/libqfoc.a: $(ARM_OBJS)
	@rm -f $@
	$(ARM_AR) rcs $@ $^

# The library must contain no floating-point instruction and call no soft-float or
# division helper: checked on the disassembly of the Cortex-M4F build.
## target: the library for Cortex-M4F (arm-none-eabi-gcc -O2 -Werror)
target: deps $(BUILD)/target/libqfoc.a
	@arm-none-eabi-objdump -d $(BUILD)/target/libqfoc.a > $(BUILD)/target/libqfoc.dis
	@if grep -E '\bv[a-z]+\.(f32|f64)\b|__aeabi_[a-z0-9]*(f|d)[a-z0-9]*|__aeabi_.div|__aeabi_l' \
	    $(BUILD)/target/libqfoc.dis; then echo "target: floating point or a runtime helper in libqfoc.a"; exit 1; fi
	@arm-none-eabi-size -t $(BUILD)/target/libqfoc.a | tail -n 1 | \
	  awk '{printf "target: build/target/libqfoc.a (Cortex-M4F, -O2): text %s B, data %s B, bss %s B; no floating point, no runtime helpers\n", $$1, $$2, $$3}'

# ---------------------------------------------------------------- estimator report
# Debian's interpreter sees the python3-matplotlib package (a PATH python may not).
PYTHON := $(shell [ -x /usr/bin/python3 ] && echo /usr/bin/python3 || echo python3)

$(BUILD)/host/estimator_report: sim/apps/estimator_report.c $(SIM_SRCS) $(SIM_HDRS) $(BUILD)/host/libqfoc.a
	@mkdir -p $(@D)
	$(CC) $(TEST_CFLAGS) -O2 -Isim $< $(SIM_SRCS) $(BUILD)/host/libqfoc.a -lm -o $@

## estimator-report: estimators validated on the plant: tables and plots in build/reports/
estimator-report: deps $(BUILD)/host/estimator_report
	@mkdir -p $(BUILD)/reports
	@$(BUILD)/host/estimator_report specs/motors/reference.toml $(BUILD)/reports
	@$(PYTHON) tools/plot_estimators.py $(BUILD)/reports

# ---------------------------------------------------------------- demo
$(BUILD)/host/accuracy: tools/accuracy.c $(BUILD)/host/libqfoc.a
	$(CC) $(TEST_CFLAGS) $< $(BUILD)/host/libqfoc.a -lm -o $@

## demo: the core's measured accuracy against double precision
demo: deps $(BUILD)/host/accuracy
	@$(BUILD)/host/accuracy

# ---------------------------------------------------------------- all gates
## check: unit tests, coverage, WP proofs, CBMC, MISRA, traceability, Cortex-M4F build
check: deps
	@sh tools/check.sh

clean:
	rm -rf $(BUILD)/host $(BUILD)/reports $(BUILD)/target $(BUILD)/cov $(BUILD)/wp $(BUILD)/cbmc $(BUILD)/misra $(BUILD)/coverage
