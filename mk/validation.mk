# mk/validation.mk -- tool validation by seeded defects (tools/validation/run.py, REQ-EVD-030).
# Every defect of tools/validation/defects.toml is seeded into a copy of the repository under
# build/validation/ and run through each gate expected to catch it, scoped to the unit it
# touches; the unmodified copy runs through the same scoped gates as the control.  Results:
# build/validation/results.md and results.json (read by make evidence).  Two gate runs at a
# time; TOOL_VALIDATION_ARGS passes options (e.g. --only TV-01,TV-07).

TOOL_VALIDATION_ARGS ?=

.PHONY: tool-validation

## tool-validation: seeded defects through the gates that must catch them, and the unmodified control (build/validation/results.md)
tool-validation: deps
	@$(PYTHON) tools/validation/run.py $(TOOL_VALIDATION_ARGS)
