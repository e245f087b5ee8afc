# mk/reviews.mk -- the manual review records tied to the files they reviewed
# (tools/evidence/review_stamp.py, REQ-EVD-031): every MISRA review record of misra/reviews.md
# and every row of the software FMEA (specs/safety-analysis.md, section 2) carries the
# SHA-256 of its files as they were reviewed.  `make review-check` lists each record current
# or stale (the files that changed) and fails on one that is not current; `make evidence`
# shows the same.  After a review, the reviewer stamps the records re-read:
#
#   python3 tools/evidence/review_stamp.py --stamp misra "Dir 4.1" "Rule 13.2"
#   python3 tools/evidence/review_stamp.py --stamp fmea F-04 F-05

.PHONY: review-check

## review-check: every MISRA review record and FMEA row current against the files it reviewed
review-check:
	@$(PYTHON) tools/evidence/review_stamp.py --check
