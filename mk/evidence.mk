# mk/evidence.mk -- the verification evidence bundle for an assessor (tools/evidence/evidence.py).
# Collects what the gates wrote (build/ and the committed proofs/, misra/, specs/ results)
# into build/evidence/: index.html (one self-contained page: the one-screen summary, then
# traceability, formal verification, MISRA, coverage, tests, resource usage, static
# analysis, tool confidence, safety manual, reproducibility, gate log), evidence.json and
# artefacts/ (a copy of every underlying file, linked relatively: the directory can be
# archived as it is; MANIFEST.sha256 over every file).  Runs no gate: run `make check` (or
# the single gates) first.  A missing result is a red row ("not run"); a result whose inputs
# stamp (tools/evidence/inputs.py) differs from the inputs now is a red row ("STALE"); a
# requirement is verified only from the results (tools/evidence/verdict.py): a test that did
# not run is "not run", amber, red with EVIDENCE_STRICT=1.
#
#   make evidence                   exit 0 when the page was written
#   make evidence EVIDENCE_STRICT=1 exit 1 when a summary row is red (= make evidence-strict)

EVIDENCE_DIR ?= $(BUILD)/evidence
EVIDENCE_STRICT ?=
EVIDENCE_ARGS = --build $(BUILD) --out $(EVIDENCE_DIR) \
                $(if $(filter 1 yes true,$(EVIDENCE_STRICT)),--strict)

.PHONY: evidence evidence-strict

## evidence: the evidence bundle from the gates' results (build/evidence/index.html, evidence.json, artefacts/); runs no gate
evidence:
	@$(PYTHON) tools/evidence/evidence.py $(EVIDENCE_ARGS)

## evidence-strict: as evidence, and exits 1 when a summary row is red
evidence-strict:
	@$(PYTHON) tools/evidence/evidence.py $(EVIDENCE_ARGS) --strict
