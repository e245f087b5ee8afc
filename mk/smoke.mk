# WP smoke tests (tools/gates/smoke.sh): per unit, the goals of make prove and -wp-smoke-tests;
# a smoke goal proved is dead code or a contradictory precondition.  Not part of make check
# (the units below take about half an hour on one processor).  qfoc_drive.c is left out:
# WP alone takes more than 5 minutes on it (proofs/wp/times.txt: about 19 minutes).
SMOKE_SKIP  := src/qfoc_drive.c
SMOKE_UNITS := $(filter-out $(SMOKE_SKIP),$(SRCS))

.PHONY: smoke
## smoke: WP smoke tests per unit (build/smoke/results.md); fails on dead code or an inconsistent contract
smoke: deps
	@sh tools/gates/smoke.sh $(SMOKE_UNITS)
