# ---------------------------------------------------------------- fuzzing (libFuzzer)
# The harnesses of tests/fuzz/ (one per target, specs/requirements/fuzz.md) built with
# Debian's clang and libFuzzer, AddressSanitizer and UndefinedBehaviorSanitizer, the
# library sources compiled again with the same instrumentation:
#   make fuzz        each target fuzzed for FUZZ_TIME seconds by FUZZ_WORKERS processes
#                    (working corpus build/fuzz/<target>/corpus, seeded from the committed
#                    tests/fuzz/corpus/<target>/), then its corpus replayed for the coverage
#   make fuzz-check  the short pass of make check: each target replays its committed corpus,
#                    then is fuzzed for FUZZ_CHECK_TIME seconds (two targets at a time)
# Both write build/fuzz/results.md and results.json (field "mode": full or check) and fail
# on any finding: a crash, a broken guarantee (the harness aborts), a sanitizer report, a
# leak, a timeout (FUZZ timeout 25 s per input) or an out-of-memory (2 GB); the input that
# caused it is in build/fuzz/[check/]<target>/artifacts/.
#
# Sanitizers: -fsanitize=fuzzer,address,undefined,integer -fno-sanitize-recover=all on the
# library and the harnesses.  'integer' adds to 'undefined' (signed overflow, shifts,
# division by zero, bounds, alignment, null, bool and enum loads, float casts) the checks of
# unsigned overflow, unsigned shift bases and implicit conversions that change a value: the
# library makes every modulo-2^16 angle and modulo-2^32 accumulator wrap explicit (casts and
# corrections, "no wrap-around in a C type"), so none of these flags an intended wrap
# (measured: none reported over the campaign).  The plant model and the tables (sim/, tables/,
# test equipment for the drive harnesses' start states) get address and undefined only, and
# no coverage instrumentation.
#
# FUZZ_TIME is the time per target: 6 targets x 400 s x 2 processes made 1.62 x 10^8
# executions in all (the goal: at least 10^8) in 41 minutes on the 2-core development machine
# under a load of about 5; 6 x 600 s x 1 process made 2.18 x 10^8 in 60 minutes beside one
# other job (README.md, "Fuzzing").
# Override any of them: make fuzz FUZZ_TIME=60 FUZZ_WORKERS=1, make fuzz FUZZ_TARGETS="link_decode".
# Minimise the committed corpus after a campaign with make fuzz-corpus.

FUZZ_CC       ?= clang
FUZZ_DIR      := $(BUILD)/fuzz
FUZZ_TARGETS  ?= link_decode link_service drive_tick drive_fast_step drive_command params_check
FUZZ_TIME     ?= 400
FUZZ_WORKERS  ?= 2
FUZZ_CHECK_TIME ?= 8
FUZZ_SAN      := -fsanitize=address,undefined,integer -fno-sanitize-recover=all
FUZZ_CFLAGS   := -std=c99 -Wall -Wextra -Werror -O1 -g -Iinclude
FUZZ_LIB_OBJS := $(patsubst src/%.c,$(FUZZ_DIR)/obj/%.o,$(SRCS))
FUZZ_EQ_OBJS  := $(patsubst %.c,$(FUZZ_DIR)/eq/%.o,$(notdir $(SIM_SRCS) $(TABLE_SRCS)))
FUZZ_TBL_OBJS := $(patsubst %.c,$(FUZZ_DIR)/eq/%.o,$(notdir $(TABLE_SRCS)))
FUZZ_HDRS     := tests/fuzz/fuzz.h tests/fuzz/snapshots.h
FUZZ_BINS     := $(patsubst %,$(FUZZ_DIR)/fuzz_%,$(FUZZ_TARGETS))
FUZZ_RUN      := $(PYTHON) tests/fuzz/run.py --build $(FUZZ_DIR) --corpus tests/fuzz/corpus \
                 --flags "$(FUZZ_CFLAGS) -fsanitize=fuzzer $(FUZZ_SAN)"

.PHONY: fuzz fuzz-check fuzz-build fuzz-corpus

# the library, instrumented for coverage (libFuzzer) and checked by the sanitizers
$(FUZZ_DIR)/obj/%.o: src/%.c $(HDRS)
	@mkdir -p $(@D)
	$(FUZZ_CC) $(FUZZ_CFLAGS) -fsanitize=fuzzer-no-link $(FUZZ_SAN) -c $< -o $@

# test equipment: the plant model and the tables
$(FUZZ_DIR)/eq/%.o: sim/%.c $(SIM_HDRS) $(HDRS)
	@mkdir -p $(@D)
	$(FUZZ_CC) -std=c99 -O2 -g -Iinclude -Isim -fsanitize=address,undefined -fno-sanitize-recover=all \
	    -c $< -o $@

$(FUZZ_DIR)/eq/%.o: tables/%.c $(TABLE_HDRS) $(HDRS)
	@mkdir -p $(@D)
	$(FUZZ_CC) -std=c99 -O2 -g -Iinclude -Itables -fsanitize=address,undefined -fno-sanitize-recover=all \
	    -c $< -o $@

# the harnesses of the link and of the table check need no plant
$(FUZZ_DIR)/fuzz_link_decode $(FUZZ_DIR)/fuzz_link_service $(FUZZ_DIR)/fuzz_params_check: \
$(FUZZ_DIR)/fuzz_%: tests/fuzz/fuzz_%.c $(FUZZ_HDRS) $(FUZZ_LIB_OBJS) $(FUZZ_TBL_OBJS)
	$(FUZZ_CC) $(FUZZ_CFLAGS) -Itables -fsanitize=fuzzer $(FUZZ_SAN) $< $(FUZZ_LIB_OBJS) \
	    $(FUZZ_TBL_OBJS) -o $@

$(FUZZ_DIR)/fuzz_drive_tick $(FUZZ_DIR)/fuzz_drive_fast_step $(FUZZ_DIR)/fuzz_drive_command: \
$(FUZZ_DIR)/fuzz_%: tests/fuzz/fuzz_%.c $(FUZZ_HDRS) $(FUZZ_LIB_OBJS) $(FUZZ_EQ_OBJS)
	$(FUZZ_CC) $(FUZZ_CFLAGS) -Itables -Isim -DQFOC_FUZZ_ROOT='"$(CURDIR)"' -fsanitize=fuzzer \
	    $(FUZZ_SAN) $< $(FUZZ_LIB_OBJS) $(FUZZ_EQ_OBJS) -lm -o $@

## fuzz-build: the libFuzzer harnesses of tests/fuzz/ (clang, ASan, UBSan) in build/fuzz/
fuzz-build: deps $(FUZZ_BINS)

## fuzz: every fuzz target for FUZZ_TIME s (default 400) x FUZZ_WORKERS (2) processes: build/fuzz/results.md; fails on a finding
fuzz: fuzz-build
	@$(FUZZ_RUN) --mode full --time $(FUZZ_TIME) --workers $(FUZZ_WORKERS) $(FUZZ_TARGETS)

## fuzz-check: the short pass of make check: the committed corpus replayed, then FUZZ_CHECK_TIME s per target
fuzz-check: fuzz-build
	@$(FUZZ_RUN) --mode check --time $(FUZZ_CHECK_TIME) --workers 1 --parallel 2 $(FUZZ_TARGETS)

## fuzz-corpus: the committed corpus tests/fuzz/corpus/ minimised (-merge=1) from itself and make fuzz's corpora
fuzz-corpus: fuzz-build
	@for t in $(FUZZ_TARGETS); do \
	    rm -rf $(FUZZ_DIR)/merge/$$t && mkdir -p $(FUZZ_DIR)/merge/$$t tests/fuzz/corpus/$$t $(FUZZ_DIR)/$$t/corpus && \
	    $(FUZZ_DIR)/fuzz_$$t -merge=1 $(FUZZ_DIR)/merge/$$t tests/fuzz/corpus/$$t $(FUZZ_DIR)/$$t/corpus \
	        > $(FUZZ_DIR)/merge/$$t.log 2>&1 || { tail -n 20 $(FUZZ_DIR)/merge/$$t.log; exit 1; }; \
	    rm -rf tests/fuzz/corpus/$$t && mv $(FUZZ_DIR)/merge/$$t tests/fuzz/corpus/$$t && \
	    echo "fuzz-corpus: $$t: $$(ls tests/fuzz/corpus/$$t | wc -l) inputs, $$(cat tests/fuzz/corpus/$$t/* 2>/dev/null | wc -c) B"; \
	done
