# ---------------------------------------------------------------- fault injection
# The fault-injection campaign of sim/apps/faults.c: the drive in the loop with the plant of
# sim/, on the reference motor and its table (a RAM copy the campaign owns); the classes, the
# item's fault tolerant time intervals (specs/item-assumptions.toml), the library's budgets
# and the verdict rule are in specs/fault-campaign.md, the
# requirements in specs/requirements/faults.md (REQ-FINJ-001 .. REQ-FINJ-008):
#   make faults        every class, every bit of the RAM table copy and FAULTS_FLIPS (10000)
#                      random single-bit flips of the drive object (seed FAULTS_SEED), in
#                      FAULTS_JOBS processes
#   make faults-check  the short pass of make check: every class, one bit of each byte of the
#                      table and FAULTS_CHECK_FLIPS (400) drive-object flips, in one process
# Both write build/faults/results.json, flips.csv, results.md, index.html and
# build/junit/faults.xml, and fail when an injection is neither detected within its FTTI and
# budget nor harmless, when a mechanism's specified reaction exceeds its FTTI, or when a
# fault-free run or a disturbance within the limits raises a fault.
# They need gcc and Debian's python3 with matplotlib (make deps installs them).

FAULTS_DIR         := $(BUILD)/faults
FAULTS_FLIPS       ?= 10000
FAULTS_CHECK_FLIPS ?= 400
FAULTS_SEED        ?= 1
FAULTS_JOBS        ?= 2
# the campaign, then its report whatever the verdict; exit 2 (no results) stops at once; the
# report's verdict is the gate's (the open findings of specs/fault-findings.toml reported,
# any other failure or a finding that no longer fails failing it)
FAULTS_RUN = rm -rf $(FAULTS_DIR) && mkdir -p $(FAULTS_DIR) && \
    rc=0; $(BUILD)/host/qfoc_faults --seed $(FAULTS_SEED) --out $(FAULTS_DIR) \
    --assumptions specs/item-assumptions.toml

.PHONY: faults faults-check

## faults: the fault-injection campaign (every class, every table bit, 10000 drive-object flips): build/faults/index.html; fails on a finding
faults: $(BUILD)/host/qfoc_faults
	@$(FAULTS_RUN) --mode full --flips $(FAULTS_FLIPS) --jobs $(FAULTS_JOBS) || rc=$$?; \
	 if [ $$rc -ge 2 ]; then exit $$rc; fi; \
	 $(PYTHON) tools/demo/faults_report.py $(FAULTS_DIR) --findings specs/fault-findings.toml --junit $(BUILD)/junit/faults.xml

## faults-check: the short pass of the campaign (every class, one bit per table byte, 400 flips), one process
faults-check: $(BUILD)/host/qfoc_faults
	@$(FAULTS_RUN) --mode check --flips $(FAULTS_CHECK_FLIPS) --jobs 1 || rc=$$?; \
	 if [ $$rc -ge 2 ]; then exit $$rc; fi; \
	 $(PYTHON) tools/demo/faults_report.py $(FAULTS_DIR) --findings specs/fault-findings.toml --junit $(BUILD)/junit/faults.xml
