#!/usr/bin/env python3
"""boot_check.py -- run the S32K144 image from reset in a Cortex-M4 instruction emulator.

Usage: boot_check.py IMAGE.elf [--period TICKS]

The image (the .elf's loadable bytes) runs from its reset vector in Unicorn
(python3-unicorn) with flash, SRAM_L/SRAM_U, the peripheral space and the core's private
peripheral bus mapped.  A small model answers the status bits the port waits for (SOSC and
SPLL valid, clock switched, RUN mode, FlexCAN acknowledges, watchdog unlocked and
reconfigured, ADC calibration done).  The check fails when:

  - the first peripheral writes are not the watchdog's unlock, TOVAL and CS (the watchdog
    runs after reset and must be handled first);
  - any SRAM word is read, or written partially, before a 32-bit write initialised it
    (the S32K144 SRAM has ECC: such an access faults on the real part);
  - an access leaves the mapped regions, or the idle loop's WFI is not reached;
  - after the set-up: .data in SRAM differs from its load image in flash, FTM3_MOD
    differs from --period, the outputs are not masked, the gate driver is not enabled, the
    watchdog is not enabled at 10 ms, the four interrupts are not enabled in the NVIC, or
    interrupts are still masked (PRIMASK).

Then the interrupt functions are called as the NVIC would (they are ordinary AAPCS
functions on the Cortex-M4): eight PWM periods (FTM3 period interrupt, ADC-complete
interrupt with mid-scale samples) and one 1 ms tick; the watchdog must be refreshed and
the compare registers written; finally qfoc_hal_pwm_write() with the enable true must
unmask the outputs (no fault latched).  The executed instruction counts of these calls
are printed (instructions, not cycles).

Two more runs from reset check main()'s handling of a failed set-up (every status tested,
MISRA C:2012 Dir 4.7): the watchdog never unlocks (qfoc_s32k_wdog_init() times out), and
the parameter table's CRC is corrupted in flash (qfoc_drive_init() refuses the table).  In
both, the idle loop must be reached with the interrupts enabled, the gate driver never
enabled, and the fault output latched: qfoc_hal_pwm_write() with the enable true leaves the
six outputs masked.  Exit status 0 when every check passes.
"""
import argparse
import json
import os
import struct
import sys

try:
    from elftools.elf.elffile import ELFFile
    from unicorn import Uc, UcError, UC_ARCH_ARM, UC_MODE_THUMB, UC_MODE_MCLASS
    from unicorn import UC_HOOK_MEM_READ, UC_HOOK_MEM_WRITE, UC_HOOK_CODE, UC_HOOK_MEM_INVALID
    from unicorn.arm_const import UC_ARM_REG_SP, UC_ARM_REG_PC, UC_ARM_REG_LR, UC_ARM_REG_PRIMASK
    from unicorn.arm_const import UC_ARM_REG_R0
except ImportError as e:  # pragma: no cover
    print("boot_check: needs python3-unicorn and python3-pyelftools (%s)" % e)
    sys.exit(1)

FLASH = (0x00000000, 0x80000)
SRAM = (0x1FFF8000, 0x0F000)          # SRAM_L 32 KiB + SRAM_U 28 KiB
PERIPH = (0x40000000, 0x100000)
PPB = (0xE0000000, 0x100000)

WDOG_CS, WDOG_CNT, WDOG_TOVAL = 0x40052000, 0x40052004, 0x40052008
FTM3_C0V, FTM3_MOD, FTM3_OUTMASK = 0x40026010, 0x40026008, 0x40026060
GPIOD_PSOR = 0x400FF0C4
NVIC_ISER0 = 0xE000E100
IRQS = {33: "LPUART1", 40: "ADC1", 48: "LPIT0_CH0", 122: "FTM3"}
STOP = 0x0007FFF0                      # return address of the called interrupt functions


class Boot:
    def __init__(self, elf_path):
        with open(elf_path, "rb") as f:
            elf = ELFFile(f)
            symtab = list(elf.get_section_by_name(".symtab").iter_symbols())
            self.syms = {s.name: s["st_value"] for s in symtab}
            self.sizes = {s.name: s["st_size"] for s in symtab}
            self.segments = [(seg["p_paddr"], seg.data()) for seg in elf.iter_segments()
                             if seg["p_type"] == "PT_LOAD" and seg["p_filesz"] > 0]
        self.mu = Uc(UC_ARCH_ARM, UC_MODE_THUMB | UC_MODE_MCLASS)
        for base, size in (FLASH, SRAM, PERIPH, PPB):
            self.mu.mem_map(base, size)
        for addr, data in self.segments:
            if FLASH[0] <= addr < FLASH[0] + FLASH[1]:
                self.mu.mem_write(addr, data)
        self.errors = []
        self.written = bytearray(SRAM[1] // 4)   # SRAM words initialised by a 32-bit write
        self.periph_writes = []
        self.iser = [0, 0, 0, 0]
        self.insns = 0
        self.wfi = False
        self.withhold_unlock = False           # the watchdog never unlocks (failure run)
        self.gate_enabled = False              # a write set PTD5 (GPIOD_PSOR bit 5)
        self.mu.hook_add(UC_HOOK_MEM_READ, self.on_periph_read, begin=PERIPH[0], end=PERIPH[0] + PERIPH[1] - 1)
        self.mu.hook_add(UC_HOOK_MEM_WRITE, self.on_write)
        self.mu.hook_add(UC_HOOK_MEM_READ, self.on_sram_read, begin=SRAM[0], end=SRAM[0] + SRAM[1] - 1)
        self.mu.hook_add(UC_HOOK_CODE, self.on_code)
        self.mu.hook_add(UC_HOOK_MEM_INVALID, self.on_invalid)

    def rd(self, a):
        return struct.unpack("<I", self.mu.mem_read(a, 4))[0]

    def wr(self, a, v):
        self.mu.mem_write(a, struct.pack("<I", v & 0xFFFFFFFF))

    # the hardware's answers
    def on_periph_read(self, uc, access, addr, size, value, user):
        for csr in (0x40064100, 0x40064600):                     # SOSCCSR, SPLLCSR: VLD follows EN
            v = self.rd(csr)
            self.wr(csr, (v | 0x01000000) if v & 1 else (v & ~0x01000000))
        self.wr(0x40064010, self.rd(0x40064014))                 # SCG_CSR follows SCG_RCCR
        self.wr(0x4007E014, 0x01)                                # SMC_PMSTAT: RUN
        v = self.rd(0x40024000)                                  # CAN0_MCR acknowledges
        mdis = (v >> 31) & 1
        frz = ((v >> 30) & 1) and ((v >> 28) & 1) and not mdis
        v &= ~(0x00100000 | 0x01000000 | 0x08000000)
        if mdis:
            v |= 0x00100000 | 0x08000000
        if frz:
            v |= 0x01000000 | 0x08000000
        self.wr(0x40024000, v)
        cs = self.rd(WDOG_CS) | 0x400                            # RCS
        unlocked = self.rd(WDOG_CNT) == 0xD928C520 and not self.withhold_unlock
        cs = (cs | 0x800) if unlocked else (cs & ~0x800)         # ULK
        self.wr(WDOG_CS, cs)
        for base in (0x4003B000, 0x40027000):                    # ADC calibration done
            if self.rd(base + 0x94) & 0x80:
                self.wr(base + 0x94, self.rd(base + 0x94) & ~0x80)
                self.wr(base, self.rd(base) | 0x80)

    def on_write(self, uc, access, addr, size, value, user):
        if SRAM[0] <= addr < SRAM[0] + SRAM[1]:
            w = (addr - SRAM[0]) // 4
            if size == 4 and addr % 4 == 0:
                self.written[w] = 1
            elif not self.written[w]:
                self.errors.append("partial write of uninitialised SRAM at 0x%08X" % addr)
        elif PERIPH[0] <= addr < PERIPH[0] + PERIPH[1]:
            if len(self.periph_writes) < 8:
                self.periph_writes.append((addr, value))
            if addr == GPIOD_PSOR and value & (1 << 5):
                self.gate_enabled = True
        elif NVIC_ISER0 <= addr < NVIC_ISER0 + 16:
            self.iser[(addr - NVIC_ISER0) // 4] |= value

    def on_sram_read(self, uc, access, addr, size, value, user):
        if not self.written[(addr - SRAM[0]) // 4]:
            self.errors.append("read of uninitialised SRAM at 0x%08X (pc 0x%08X)"
                               % (addr, uc.reg_read(UC_ARM_REG_PC)))
            uc.emu_stop()

    def on_code(self, uc, addr, size, user):
        self.insns += 1
        if size == 2 and bytes(uc.mem_read(addr, 2)) == b"\x30\xbf":   # WFI
            self.wfi = True
            uc.emu_stop()

    def on_invalid(self, uc, access, addr, size, value, user):
        self.errors.append("access outside the memory map at 0x%08X" % addr)
        return False

    def run_reset(self):
        sp, reset = struct.unpack("<II", self.mu.mem_read(0, 8))
        self.mu.reg_write(UC_ARM_REG_SP, sp)
        try:
            self.mu.emu_start(reset, 0xFFFFFFFF, count=50_000_000)
        except UcError as e:
            self.errors.append("emulation stopped: %s at pc 0x%08X" % (e, self.mu.reg_read(UC_ARM_REG_PC)))
        return self.insns

    def call(self, name, r0=None):
        """Call an interrupt function as the NVIC would (or any function with one pointer
        argument r0); return its instruction count."""
        self.insns = 0
        self.wfi = False
        if r0 is not None:
            self.mu.reg_write(UC_ARM_REG_R0, r0)
        self.mu.reg_write(UC_ARM_REG_LR, STOP | 1)
        try:
            self.mu.emu_start(self.syms[name] | 1, STOP, count=5_000_000)
        except UcError as e:
            self.errors.append("%s: %s at pc 0x%08X" % (name, e, self.mu.reg_read(UC_ARM_REG_PC)))
        if self.mu.reg_read(UC_ARM_REG_PC) != STOP:
            self.errors.append("%s did not return" % name)
        return self.insns

    def pwm_write_enabled(self):
        """qfoc_hal_pwm_write() with mid compare values and the enable true; the outputs'
        mask after it (0: switching, 0x3F: all six masked)."""
        arg = 0x20000100                    # in SRAM_U, far below the stack in use
        self.mu.mem_write(arg, struct.pack("<HHHBx", 100, 100, 100, 1))   # qfoc_pwm_t
        self.call("qfoc_hal_pwm_write", r0=arg)
        return self.rd(FTM3_OUTMASK) & 0x3F

    def data_copied(self):
        """.data in SRAM equals its load image in flash (qfoc_data_words words)."""
        words = self.rd(self.syms["qfoc_data_words"])
        src, dst = self.syms["qfoc_data_load"], self.syms["qfoc_data_start"]
        return all(self.rd(src + 4 * k) == self.rd(dst + 4 * k) for k in range(words))


def failed_setup(elf, how):
    """Run from reset with one failure: 'watchdog' (never unlocks) or 'table' (the
    parameter table's CRC corrupted in flash).  Returns the errors found."""
    b = Boot(elf)
    if how == "watchdog":
        b.withhold_unlock = True
    else:
        name = "qfoc_params_reference16k" if "qfoc_params_reference16k" in b.syms \
            else "qfoc_params_reference"
        crc = b.syms[name] + b.sizes[name] - 4          # the last field: uint32_t crc
        b.wr(crc, b.rd(crc) ^ 0xFFFFFFFF)
    b.run_reset()
    errors = ["%s failure: %s" % (how, e) for e in b.errors]
    if not b.wfi:
        errors.append("%s failure: the idle loop (WFI) was not reached" % how)
    if b.mu.reg_read(UC_ARM_REG_PRIMASK) & 1:
        errors.append("%s failure: interrupts still masked (PRIMASK)" % how)
    if b.gate_enabled:
        errors.append("%s failure: the gate driver (PTD5) was enabled" % how)
    if b.pwm_write_enabled() != 0x3F:
        errors.append("%s failure: the fault output is not latched (outputs unmasked)" % how)
    return errors


def image_sizes(path):
    """Flash (vectors, flash configuration, code, unwind table, .data's load image) and RAM
    (.data + .bss) of the image, bytes: the sections `make firmware` sums."""
    flash = ram = 0
    with open(path, "rb") as f:
        for sec in ELFFile(f).iter_sections():
            if sec.name in (".isr_vector", ".flash_config", ".text", ".ARM.exidx", ".data"):
                flash += sec["sh_size"]
            if sec.name in (".data", ".bss"):
                ram += sec["sh_size"]
    return flash, ram


def main(argv):
    ap = argparse.ArgumentParser(description="run the S32K144 image from reset in an emulator")
    ap.add_argument("elf")
    ap.add_argument("--period", type=int, default=5000, help="expected FTM3_MOD (svpwm.period)")
    ap.add_argument("--json", help="write the image's sizes and the instruction counts here "
                                   "(the source of the figures the documents quote)")
    args = ap.parse_args(argv[1:])
    b = Boot(args.elf)
    n_boot = b.run_reset()
    first = [a for a, _ in b.periph_writes[:3]]
    if first != [WDOG_CNT, WDOG_TOVAL, WDOG_CS] or b.periph_writes[0][1] != 0xD928C520:
        b.errors.append("the first peripheral writes are not WDOG unlock, TOVAL, CS: %s"
                        % ", ".join("0x%08X" % a for a in first))
    if not b.wfi:
        b.errors.append("the idle loop (WFI) was not reached")
    if not b.data_copied():
        b.errors.append(".data in SRAM differs from its load image")
    if b.rd(FTM3_MOD) != args.period:
        b.errors.append("FTM3_MOD = %d, expected %d" % (b.rd(FTM3_MOD), args.period))
    if b.rd(FTM3_OUTMASK) & 0x3F != 0x3F:
        b.errors.append("PWM outputs not masked after the set-up")
    if not b.rd(GPIOD_PSOR) & (1 << 5):
        b.errors.append("gate driver (PTD5) not enabled after a complete set-up")
    if not (b.rd(WDOG_CS) & 0x80) or b.rd(WDOG_TOVAL) != 1280:
        b.errors.append("watchdog not enabled at 10 ms (CS 0x%04X, TOVAL %d)" % (b.rd(WDOG_CS), b.rd(WDOG_TOVAL)))
    for irq, name in IRQS.items():
        if not b.iser[irq // 32] & (1 << (irq % 32)):
            b.errors.append("IRQ %d (%s) not enabled" % (irq, name))
    if b.mu.reg_read(UC_ARM_REG_PRIMASK) & 1:
        b.errors.append("interrupts still masked (PRIMASK)")
    # eight PWM periods with mid-scale samples (320 V bus), then one tick
    for base, offs, code in ((0x4003B000, 0x48, 2048), (0x4003B000, 0x4C, 2048), (0x40027000, 0x48, 2048),
                             (0x40027000, 0x4C, 2048), (0x40027000, 0x50, 2621)):
        b.wr(base + offs, code)
    b.wr(FTM3_C0V, 0xFFFF)
    n_ftm = n_adc = 0
    for _ in range(8):
        n_ftm = max(n_ftm, b.call("qfoc_s32k_ftm_isr"))
        n_adc = max(n_adc, b.call("qfoc_s32k_adc_isr"))
    if b.rd(FTM3_C0V) > args.period:
        b.errors.append("compare register not written by the ADC-complete interrupt")
    b.wr(WDOG_CNT, 0)
    n_tick = b.call("qfoc_s32k_tick_isr")
    if b.rd(WDOG_CNT) != 0xB480A602:
        b.errors.append("watchdog not refreshed by the tick")
    if b.pwm_write_enabled() != 0:
        b.errors.append("outputs still masked after qfoc_hal_pwm_write() with the enable true")
    for how in ("watchdog", "table"):
        b.errors += failed_setup(args.elf, how)
    for e in b.errors[:10]:
        print("boot_check: %s" % e)
    if b.errors:
        return 1
    print("boot_check: %s: reset to idle loop in %d instructions (watchdog first, SRAM initialised "
          "before use, FTM3_MOD %d, outputs masked, gate driver on, WDOG 10 ms, 4 IRQs enabled); "
          "interrupt functions: ADC-complete %d, FTM3 period %d, 1 ms tick %d instructions (PRECHARGE); "
          "failed watchdog set-up and refused table: gate driver off, fault output latched"
          % (args.elf, n_boot, args.period, n_adc, n_ftm, n_tick))
    if args.json:
        flash, ram = image_sizes(args.elf)
        with open(args.json, "w", encoding="utf-8") as f:
            json.dump({"elf": os.path.basename(args.elf), "flash_bytes": flash, "ram_bytes": ram,
                       "boot_instructions": n_boot, "isr_adc_instructions": n_adc,
                       "isr_ftm3_instructions": n_ftm, "isr_tick_instructions": n_tick,
                       "state": "PRECHARGE"}, f, indent=1)
            f.write("\n")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
