# mk/misra_summary.mk -- the MISRA Compliance:2020 guideline compliance summary
# (tools/gates/misra_summary.py): every guideline of MISRA C:2012 with Amendments 1 and 2, its
# category, its verification methods (misra/enforcement-plan.csv) and its status
# (compliant, deviations with their records and sites, disapplied, violations) from the
# cppcheck result of `make misra`, misra/deviations.md and the review records of
# misra/reviews.md; the re-categorisation plan and the tool versions.  Fails on a
# violation or on a guideline missing from the plan.  Both files are stamped with the run's
# UTC time and the SHA-256 of their inputs (tools/evidence/inputs.py misra).

.PHONY: misra-summary

$(BUILD)/misra/cppcheck.xml: $(SRCS) $(HDRS) $(TABLE_SRCS) $(TABLE_HDRS) \
                             $(wildcard port_s32k/*.c port_s32k/*.h) \
                             misra/guidelines.txt misra/deviations.md tools/gates/misra.sh tools/gates/misra_report.py
	-@sh tools/gates/misra.sh

## misra-summary: MISRA Compliance:2020 summary of every guideline (build/misra/compliance-summary.md, .json); fails on a violation
misra-summary: deps $(BUILD)/misra/cppcheck.xml
	@t0=$$(date +%s); rc=0; $(PYTHON) tools/gates/misra_summary.py || rc=$$?; \
	 for f in $(BUILD)/misra/compliance-summary.json $(BUILD)/misra/compliance-summary.md; do \
	     [ -f "$$f" ] && { $(PYTHON) tools/evidence/inputs.py --stamp "$$f" misra --started "$$t0" > /dev/null || rc=1; }; \
	 done; exit $$rc
