# mk/release.mk -- the release package (tools/release/).
#
#   make release         dist/qfoc-<version>.tar.gz (+ .sha256): sources, requirements and
#                        specifications, the Cortex-M4F libqfoc.a, the tuning tool, the tables,
#                        the safety manual, the evidence bundle, LICENSE, CHANGELOG, README,
#                        CMake files, SHA256SUMS; the same bytes on every run
#   make release-check   the package unpacked in an empty directory: sums verified, an example
#                        built against it on the host (and run) and for the Cortex-M4F
#
# The version is QFOC_VERSION_STRING of include/qfoc/version.h.  The evidence bundle is the
# one `make evidence` last wrote (make check runs the release after the evidence gate); when
# there is none, `make evidence` is run first and its red rows ("not run") are packaged as
# they are.

RELEASE_VERSION := $(shell sed -n 's/^\#define QFOC_VERSION_STRING "\(.*\)".*/\1/p' include/qfoc/version.h)
RELEASE_DIST    := dist
RELEASE_TAR     := $(RELEASE_DIST)/qfoc-$(RELEASE_VERSION).tar.gz

.PHONY: release release-check

## release: the release package dist/qfoc-<version>.tar.gz with SHA256SUMS (after make evidence)
release: deps $(BUILD)/target/libqfoc.a
	@if [ ! -f $(EVIDENCE_DIR)/evidence.json ]; then \
	    echo "release: no evidence bundle yet: make evidence"; \
	    $(MAKE) --no-print-directory evidence > $(BUILD)/release-evidence.log 2>&1 || \
	        { cat $(BUILD)/release-evidence.log; exit 1; }; \
	    tail -n 1 $(BUILD)/release-evidence.log; fi
	@DIST=$(RELEASE_DIST) ARM_CFLAGS="$(ARM_CFLAGS)" RELEASE_STAGE=$(BUILD)/release \
	    REPRO_JSON=$(BUILD)/repro/repro.json \
	    sh tools/release/release.sh $(BUILD)/target/libqfoc.a $(EVIDENCE_DIR)

## release-check: the release package unpacked, sums verified, an example built (host and Cortex-M4F) and run
release-check: deps
	@CC="$(CC)" CFLAGS="$(CFLAGS)" ARM_CC="$(ARM_CC)" ARM_CFLAGS="$(ARM_CFLAGS)" \
	    EXAMPLE=tools/release/release_example.c sh tools/release/release_check.sh $(RELEASE_TAR)

# make clean also removes the staging tree and the packages
clean: release-clean
.PHONY: release-clean
release-clean:
	rm -rf $(BUILD)/release $(RELEASE_DIST)
