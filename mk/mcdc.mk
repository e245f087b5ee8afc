# ---------------------------------------------------------------- MC/DC (gcc 14)
# Modified condition/decision coverage (ISO 26262-6, table 9) of src/*.c and the inline
# code of include/qfoc/, measured while the unit tests run.  Debian bookworm has gcc 12;
# -fcondition-coverage needs gcc 14, so tools/setup/mkchroot.sh makes a Debian trixie chroot
# (build/trixie-chroot: debootstrap minbase + gcc-14, libcmocka-dev; about 430 MB, one
# minute the first time, network needed) and tools/gates/mcdc.sh builds and runs the tests in
# it.  Both need root (debootstrap, chroot).
#
#   make mcdc                   report build/mcdc/mcdc.md and mcdc.json; fails below
#                               MCDC_MIN % in src/ or the inline header code, on an
#                               outcome not covered without a justification, or on a
#                               justification that matches nothing
#   make mcdc MCDC_MIN=95       another gate
#   make mcdc-chroot            the chroot alone
#
# Justifications of outcomes that cannot be covered: specs/mcdc-justifications.md.

MCDC_MIN    ?= 100
MCDC_CHROOT := $(BUILD)/trixie-chroot

.PHONY: mcdc mcdc-chroot

## mcdc-chroot: the Debian trixie chroot with gcc 14 for MC/DC (build/trixie-chroot, root)
mcdc-chroot:
	@sh tools/setup/mkchroot.sh $(MCDC_CHROOT)

## mcdc: MC/DC coverage (gcc 14 -fcondition-coverage, chroot) of src/ by the unit tests: build/mcdc/mcdc.md
mcdc: deps mcdc-chroot
	@MCDC_CHROOT=$(abspath $(MCDC_CHROOT)) MCDC_WARN="$(WARN)" PYTHON=$(PYTHON) \
	    sh tools/gates/mcdc.sh --min $(MCDC_MIN) --strict
