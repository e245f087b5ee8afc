# mk/release.mk -- the release package (tools/release/).
#
#   make release         dist/qfoc-<version>.tar.gz (+ .sha256) of the commit checked out:
#                        sources, requirements and specifications, the Cortex-M4F libqfoc.a,
#                        the tuning tool, the tables, the safety manual, the porting guide,
#                        port_s32k/, misra/, the evidence bundle, the package's own README.md
#                        and Makefile, RELEASE.txt, LICENSE, CHANGELOG, CMake files,
#                        SHA256SUMS; the same bytes on every run.  Refused (exit 1, nothing
#                        built or packaged, every reason said) unless the working tree is a
#                        clean git checkout (untracked files count; build/ and dist/ aside)
#                        and the evidence bundle (EVIDENCE_DIR, default build/evidence) is
#                        of HEAD, made in a clean tree, with every summary row green, and
#                        the WP prover results (proofs/wp/cache.txt) are those of a full run
#                        (make prove-full) over HEAD's proof sources; QFOC_RELEASE_CANDIDATE=1
#                        makes a package of such a tree that RELEASE.txt calls a candidate
#   make release-check   the package unpacked in an empty directory: sums verified, its
#                        evidence green and of its commit, built with its own Makefile (host,
#                        Cortex-M4F identical to the shipped library, the example run, the
#                        S32K144 image booted in the emulator) and with its CMake files, its
#                        tuning tool regenerating its tables
#   make release-test    the refusals of make release, each seeded in a temporary repository
#                        (tools/release/tests/release_test.sh)
#   make release-gate    the release gate of make check (tools/release/check_gate.sh)
#
# The version is QFOC_VERSION_STRING of include/qfoc/version.h.  The evidence bundle is the
# one `make evidence` last wrote; make release runs no gate and makes no evidence.

RELEASE_VERSION := $(shell sed -n 's/^\#define QFOC_VERSION_STRING "\(.*\)".*/\1/p' include/qfoc/version.h)
RELEASE_DIST    := dist
RELEASE_TAR     := $(RELEASE_DIST)/qfoc-$(RELEASE_VERSION).tar.gz

.PHONY: release release-check release-test release-gate

## release: the release package dist/qfoc-<version>.tar.gz; refused unless the tree is clean and the evidence green and of HEAD
release:
	@$(PYTHON) tools/release/release_ready.py tree --evidence $(EVIDENCE_DIR)
	@sh tools/setup/deps.sh --release
	@$(MAKE) --no-print-directory $(BUILD)/target/libqfoc.a docs
	@DIST=$(RELEASE_DIST) WARN="$(WARN)" CFLAGS="$(CFLAGS)" ARM_CFLAGS="$(ARM_CFLAGS)" \
	    RELEASE_STAGE=$(BUILD)/release REPRO_JSON=$(BUILD)/repro/repro.json \
	    sh tools/release/release.sh $(BUILD)/target/libqfoc.a $(EVIDENCE_DIR)

## release-check: the release package unpacked and checked as an integrator receives it
release-check: deps
	@ARM_CC="$(ARM_CC)" ARM_CFLAGS="$(ARM_CFLAGS)" EXAMPLE=tools/release/release_example.c \
	    sh tools/release/release_check.sh $(RELEASE_TAR)

## release-test: make release's refusals, seeded in temporary repositories
release-test:
	@sh tools/release/tests/release_test.sh

## release-gate: make check's release gate: release-test, then the release of this checkout and release-check
release-gate:
	@sh tools/release/check_gate.sh

# make clean also removes the staging tree and the packages
clean: release-clean
.PHONY: release-clean
release-clean:
	rm -rf $(BUILD)/release $(BUILD)/release-gate $(RELEASE_DIST)
