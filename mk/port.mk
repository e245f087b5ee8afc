# mk/port.mk -- the NXP S32K144 port (port_s32k/): the firmware image and the host tests
# of the port against a fake register file.  Included by the Makefile (mk/*.mk).
#
#   make firmware               build/s32k144/qfoc_compressor.{elf,map,bin}, 8 kHz table;
#                               checks the flash configuration field (check_image.py) and
#                               runs the image from reset in an emulator (boot_check.py); and
#                               the calibration description .a2l beside it (mk/a2l.mk)
#   make firmware FW_PWM_KHZ=16 build/s32k144/qfoc_compressor_16k.*, the 16 kHz table
#   make port-test              tests/test_port.c on the host (fake registers, CMocka)

PORT_SRCS    := $(sort $(wildcard port_s32k/*.c))
PORT_ASMS    := $(sort $(wildcard port_s32k/*.S))
PORT_HDRS    := $(sort $(wildcard port_s32k/*.h))
FW_DIR       := $(BUILD)/s32k144
FW_LD        := port_s32k/s32k144.ld
FW_PWM_KHZ   ?= 8
ifeq ($(FW_PWM_KHZ),16)
FW_NAME      := qfoc_compressor_16k
FW_TABLE_SRC := tables/reference16k_params.c
FW_DEFS      := -DQFOC_S32K_PWM_16K
FW_PERIOD    := 2500
else
FW_NAME      := qfoc_compressor
FW_TABLE_SRC := tables/reference_params.c
FW_DEFS      :=
FW_PERIOD    := 5000
endif
FW_ELF       := $(FW_DIR)/$(FW_NAME).elf
FW_MAP       := $(FW_DIR)/$(FW_NAME).map
FW_BIN       := $(FW_DIR)/$(FW_NAME).bin
# the calibration description beside the image (mk/a2l.mk, tools/a2l/)
FW_A2L       := $(FW_DIR)/$(FW_NAME).a2l
FW_OBJ_DIR   := $(FW_DIR)/obj-$(FW_PWM_KHZ)k
# -g: the DWARF the calibration description (tools/a2l/) reads the table's and the drive's
# layout from; it adds debug sections only (the image, .bin, is the same), with the checkout's
# path mapped to '.' so that the ELF does not depend on where the tree lies.
FW_CFLAGS    := $(ARM_CFLAGS) $(FW_DEFS) -Iport_s32k -Itables -g -fdebug-prefix-map=$(CURDIR)=.
FW_OBJS      := $(patsubst port_s32k/%.c,$(FW_OBJ_DIR)/%.o,$(PORT_SRCS)) \
                $(patsubst port_s32k/%.S,$(FW_OBJ_DIR)/%.o,$(PORT_ASMS)) \
                $(FW_OBJ_DIR)/$(notdir $(FW_TABLE_SRC:.c=.o))
FW_LDFLAGS   := -mcpu=cortex-m4 -mthumb -mfloat-abi=hard -mfpu=fpv4-sp-d16 -nostartfiles \
                --specs=nano.specs -T $(FW_LD) -Wl,--gc-sections -Wl,-Map=$(FW_MAP) \
                -Wl,--fatal-warnings

.PHONY: firmware port-test

$(FW_OBJ_DIR)/%.o: port_s32k/%.c $(PORT_HDRS) $(HDRS) $(TABLE_HDRS) mk/port.mk
	@mkdir -p $(@D)
	$(ARM_CC) $(FW_CFLAGS) -c $< -o $@

# The assembly module (reset.S): preprocessed, then assembled for the same core.
$(FW_OBJ_DIR)/%.o: port_s32k/%.S mk/port.mk
	@mkdir -p $(@D)
	$(ARM_CC) $(FW_CFLAGS) -c $< -o $@

$(FW_OBJ_DIR)/%.o: tables/%.c $(HDRS) $(TABLE_HDRS) mk/port.mk
	@mkdir -p $(@D)
	$(ARM_CC) $(FW_CFLAGS) -c $< -o $@

$(FW_ELF): $(FW_OBJS) $(BUILD)/target/libqfoc.a $(FW_LD) mk/port.mk
	@mkdir -p $(@D)
	$(ARM_CC) $(FW_LDFLAGS) $(FW_OBJS) $(BUILD)/target/libqfoc.a -o $@

$(FW_BIN): $(FW_ELF)
	arm-none-eabi-objcopy -O binary $< $@

## firmware: S32K144 image build/s32k144/qfoc_compressor.{elf,map,bin,a2l}, sizes, FSEC and boot checks
firmware: deps $(FW_BIN) $(FW_A2L)
	@$(PYTHON) port_s32k/check_image.py $(FW_BIN)
	@$(PYTHON) port_s32k/boot_check.py $(FW_ELF) --period $(FW_PERIOD) --json $(BUILD)/s32k144/firmware.json
	@arm-none-eabi-size -A $(FW_ELF) | awk ' \
	  $$1==".isr_vector"||$$1==".flash_config"||$$1==".text"||$$1==".ARM.exidx" {flash+=$$2} \
	  $$1==".data" {flash+=$$2; ram+=$$2} $$1==".bss" {ram+=$$2} \
	  END {printf "firmware: %s (%s kHz table): flash %d B of 524288 (%.1f %%), RAM %d B .data+.bss of 32768 SRAM_L (%.1f %%), stack 28672 B SRAM_U\n", \
	       "$(FW_ELF)", "$(FW_PWM_KHZ)", flash, 100.0*flash/524288, ram, 100.0*ram/32768}'

# The test includes the port's sources itself (fake register file on), so the generic
# test rule of the Makefile builds it too; this target adds the strict warnings.
PORT_TEST_BIN := $(BUILD)/host/port/test_port
$(PORT_TEST_BIN): tests/test_port.c tests/test_util.h $(PORT_SRCS) $(PORT_HDRS) \
                  port_s32k/fake/fake_regs.c port_s32k/fake/fake_regs.h \
                  $(BUILD)/host/libqfoc.a $(SIM_SRCS) $(TABLE_SRCS) $(TABLE_HDRS)
	@mkdir -p $(@D)
	$(CC) $(TEST_CFLAGS) -Wconversion -Wsign-conversion -Wshadow -Wstrict-prototypes \
	    -Iinclude -Isim -Itables $< $(SIM_SRCS) $(TABLE_SRCS) $(BUILD)/host/libqfoc.a \
	    -lcmocka -lm -o $@

## port-test: the S32K144 port's host tests against a fake register file (CMocka)
port-test: deps $(PORT_TEST_BIN)
	@$(PORT_TEST_BIN)
