# mk/a2l.mk -- the calibration description (tools/a2l/): an ASAM MCD-2 MC file (A2L, ASAP2
# 1.71) of the parameter table and the drive in the firmware image, written beside the image
# (build/s32k144/<image>.a2l; make firmware writes it too, mk/port.mk).  Included by the
# Makefile (mk/*.mk).
#
#   make a2l                  build/s32k144/qfoc_compressor.a2l (the image built first); needs
#                             only the ARM tool chain, make and Python (deps-a2l)
#   make a2l FW_PWM_KHZ=16    build/s32k144/qfoc_compressor_16k.a2l
#   make a2l-check            tools/a2l/tests: the A2L read back with the tests' own reader,
#                             its structure checked, every address and size against the ELF's
#                             symbols and DWARF, every conversion against the motor file

# What the description is made from besides the image: the tool, the tuning tool that knows
# every field's scale, the table list and motor files, the headers whose codes it lists.
A2L_INPUTS := tools/a2l/qfoc_a2l.py tools/tune/qfoc_tune.py tables/manifest.txt $(MOTORS) \
              include/qfoc/sm.h include/qfoc/fault.h include/qfoc/version.h

$(BUILD)/s32k144/%.a2l: $(BUILD)/s32k144/%.elf $(A2L_INPUTS)
	@$(PYTHON) tools/a2l/qfoc_a2l.py $< -o $@

.PHONY: a2l a2l-check deps-a2l

## deps-a2l: only what make a2l needs (make, the ARM tool chain, python3 with numpy, pyelftools, pytest)
deps-a2l:
	@sh tools/setup/deps.sh --a2l

## a2l: the calibration description (A2L, ASAP2 1.71) of the firmware image, build/s32k144/qfoc_compressor.a2l
a2l: deps-a2l
	@$(MAKE) --no-print-directory $(FW_A2L)

## a2l-check: the A2L read back and checked against the ELF, the tuning tool and the motor files (pytest)
a2l-check: deps-a2l
	@$(MAKE) --no-print-directory $(FW_A2L)
	@mkdir -p $(BUILD)/junit
	@QFOC_A2L_ELF=$(FW_ELF) $(PYTHON) -m pytest -q -p no:cacheprovider \
	    --junitxml=$(BUILD)/junit/pytest-a2l.xml -o junit_suite_name=pytest tools/a2l/tests
