"""Tests of the processor-in-the-loop emulator (port_s32k/pil/core.py, periph.py) on small
Thumb images assembled here (arm-none-eabi-gcc), and one short run of the firmware image
when it is built (build/s32k144/qfoc_compressor.elf).

    /usr/bin/python3 -m pytest -q port_s32k/pil/tests        (make pil-test)
"""
import os
import shutil
import struct
import subprocess
import sys

import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
PIL = os.path.dirname(HERE)
ROOT = os.path.normpath(os.path.join(PIL, "..", ".."))
sys.path.insert(0, PIL)
import core  # noqa: E402
import periph  # noqa: E402

pytestmark = pytest.mark.skipif(shutil.which("arm-none-eabi-gcc") is None,
                                reason="arm-none-eabi-gcc not installed")

LD = """
MEMORY { FLASH (rx) : ORIGIN = 0, LENGTH = 512K }
SECTIONS { .text : { KEEP(*(.vectors)) *(.text*) } > FLASH }
"""

# Vector table: SP at the top of SRAM_U, reset, then the IRQ vectors named in `irqs`.
def vectors(irqs):
    words = ["    .word 0x20007000", "    .word reset + 1"] + ["    .word trap + 1"] * 14
    for n in range(123):
        words.append("    .word %s + 1" % irqs[n] if n in irqs else "    .word trap + 1")
    return "\n".join(words)


HEAD = """
    .syntax unified
    .cpu cortex-m4
    .thumb
    .section .vectors, "a"
%s
    .text
    .thumb_func
trap:
    b trap
"""

# SRAM_L words used by the tests (each written before it is read: the ECC check)
LOG = 0x1FFF8000


def build(tmp_path, name, body, irqs):
    src = tmp_path / (name + ".S")
    src.write_text(HEAD % vectors(irqs) + body)
    ld = tmp_path / "t.ld"
    ld.write_text(LD)
    elf = tmp_path / (name + ".elf")
    subprocess.check_call(["arm-none-eabi-gcc", "-mcpu=cortex-m4", "-mthumb", "-nostdlib",
                           "-nostartfiles", "-T", str(ld), str(src), "-o", str(elf)])
    return str(elf)


def rd(c, a):
    return struct.unpack("<I", c.mu.mem_read(a, 4))[0]


def sym(elf, name):
    out = subprocess.check_output(["arm-none-eabi-nm", elf]).decode()
    for line in out.splitlines():
        p = line.split()
        if p[-1] == name:
            return int(p[0], 16)
    raise KeyError(name)


# ---------------------------------------------------------------------- entry / return
ROUND_TRIP = """
    .thumb_func
reset:
    ldr r0, =0x1FFF8000        @ clear the log words (32-bit writes: ECC initialised)
    movs r1, #0
    movs r2, #32
1:  str r1, [r0], #4
    subs r2, #1
    bne 1b
    ldr r0, =0xE000E104        @ NVIC_ISER1: IRQ 40
    movs r1, #1
    lsls r1, r1, #8
    str r1, [r0]
    ldr r0, =0xE000E204        @ NVIC_ISPR1: pend IRQ 40 (masked: PRIMASK set below)
    cpsid i
    str r1, [r0]
    ldr r0, =0x10101010
    ldr r1, =0x21212121
    ldr r2, =0x32323232
    ldr r3, =0x43434343
    ldr r4, =0x54545454
    ldr r12, =0xC0C0C0C0
    ldr lr, =0xE1E1E1E1
    mov r5, sp
    ldr r6, =0x1FFF8000
    str r5, [r6, #0x40]         @ SP before the interrupt
    movs r7, #0
    cmp r7, #1                  @ flags: N = 1 (0 - 1 < 0), Z = 0, C = 0
    cpsie i                     @ the interrupt is taken right here
    .global after_cpsie
after_cpsie:
    mrs r7, apsr
    str r0, [r6, #0x00]
    str r1, [r6, #0x04]
    str r2, [r6, #0x08]
    str r3, [r6, #0x0C]
    str r4, [r6, #0x10]
    mov r8, r12
    str r8, [r6, #0x14]
    mov r8, lr
    str r8, [r6, #0x18]
    mov r8, sp
    str r8, [r6, #0x1C]
    str r7, [r6, #0x20]
2:  wfi
    b 2b
    .ltorg

    .thumb_func
isr40:
    ldr r0, =0x1FFF8000
    ldr r1, [r0, #0x44]
    adds r1, #1
    str r1, [r0, #0x44]         @ entries
    str lr, [r0, #0x48]         @ EXC_RETURN seen by the handler
    mrs r2, ipsr
    str r2, [r0, #0x4C]
    mov r1, sp
    str r1, [r0, #0x50]
    ldr r1, [sp, #24]           @ the stacked return address
    str r1, [r0, #0x54]
    ldr r1, [sp, #28]           @ the stacked xPSR
    str r1, [r0, #0x58]
    movs r1, #0                 @ clobber the caller-saved registers and the flags
    movs r2, #0
    movs r3, #0
    mov r12, r3
    cmp r3, #0                  @ Z = 1, N = 0, C = 1
    bx lr
    .ltorg
"""


def test_entry_return_round_trip_preserves_registers(tmp_path):
    """REQ-PIL-001: an interrupt taken from thread mode right after CPSIE returns with every register, SP and the flags restored.

    Methods: 1a the exception entry and return of the statement (frame, EXC_RETURN, stacked return address); 1b the class of a basic frame from thread mode with an 8-aligned SP
    """
    elf = build(tmp_path, "round", ROUND_TRIP, {40: "isr40"})
    c = core.Core(elf)
    c.boot()
    assert c.run_until(20000), c.stopped
    assert rd(c, LOG + 0x44) == 1                              # entered once
    assert rd(c, LOG + 0x48) == 0xFFFFFFF9                     # from thread mode, basic frame
    assert rd(c, LOG + 0x4C) == 16 + 40                        # IPSR in the handler
    sp0 = rd(c, LOG + 0x40)
    assert rd(c, LOG + 0x50) == sp0 - 32                       # the 8-word frame (SP 8-aligned)
    assert rd(c, LOG + 0x54) == sym(elf, "after_cpsie") & ~1   # taken right after CPSIE
    assert rd(c, LOG + 0x58) & (1 << 24)                       # xPSR: Thumb bit stacked
    assert not rd(c, LOG + 0x58) & (1 << 9)                    # no padding
    assert [rd(c, LOG + 4 * k) for k in range(5)] == [0x10101010, 0x21212121, 0x32323232,
                                                       0x43434343, 0x54545454]
    assert rd(c, LOG + 0x14) == 0xC0C0C0C0                     # R12
    assert rd(c, LOG + 0x18) == 0xE1E1E1E1                     # LR
    assert rd(c, LOG + 0x1C) == sp0                            # SP restored
    assert rd(c, LOG + 0x20) >> 28 == 0x8                      # N set, Z and C clear again
    assert c.irq_stats[40][0][0] > 0 and c.resets == 0


def test_misaligned_stack_gets_padding_and_is_restored(tmp_path):
    """REQ-PIL-001: a 4-aligned SP at the interrupt gets the alignment pad (xPSR bit 9) and the SP is restored.

    Methods: 1b the class of a stack pointer not 8-aligned at the exception; 1c the boundary of the pad, SP 4 below an 8-aligned address
    """
    body = ROUND_TRIP.replace("    mov r5, sp\n", "    sub sp, #4\n    mov r5, sp\n")
    elf = build(tmp_path, "pad", body, {40: "isr40"})
    c = core.Core(elf)
    c.boot()
    assert c.run_until(20000), c.stopped
    sp0 = rd(c, LOG + 0x40)
    assert sp0 % 8 == 4
    assert rd(c, LOG + 0x50) == sp0 - 36                       # 4 bytes of padding
    assert rd(c, LOG + 0x58) & (1 << 9)                        # recorded in xPSR bit 9
    assert rd(c, LOG + 0x1C) == sp0


# ---------------------------------------------------------------------- pre-emption
# IRQ 33 (low priority 4) and IRQ 122 (high priority 1): the higher interrupt number has
# the higher priority.  Each handler appends its mark to a log at 0x1FFF8000 (count at
# +0x7C).  33 pends 122 in its middle: 122 must pre-empt.  122 pends 33 again: 33 must
# wait until 122 returns (tail chain).
PREEMPT = """
    .thumb_func
reset:
    ldr r0, =0x1FFF8000
    movs r1, #0
    movs r2, #32
1:  str r1, [r0], #4
    subs r2, #1
    bne 1b
    cpsid i
    ldr r0, =0xE000E420         @ NVIC_IPR8: IRQ 33 in byte 1
    ldr r1, =0x00004000         @ priority 4 << 4
    str r1, [r0]
    ldr r0, =0xE000E478         @ NVIC_IPR30: IRQ 122 in byte 2
    ldr r1, =0x00100000         @ priority 1 << 4
    str r1, [r0]
    ldr r0, =0xE000E104         @ ISER1: IRQ 33 (bit 1)
    movs r1, #2
    str r1, [r0]
    ldr r0, =0xE000E10C         @ ISER3: IRQ 122 (bit 26)
    ldr r1, =0x04000000
    str r1, [r0]
    ldr r0, =0xE000E204         @ ISPR1: pend IRQ 33
    movs r1, #2
    str r1, [r0]
    cpsie i
2:  wfi
    b 2b
    .ltorg

    .thumb_func
mark:                           @ r1 = mark; uses r2, r3
    ldr r2, =0x1FFF8000
    ldr r3, [r2, #0x7C]
    str r1, [r2, r3, lsl #2]
    adds r3, #1
    str r3, [r2, #0x7C]
    bx lr
    .ltorg

    .thumb_func
isr33:
    push {r4, lr}
    ldr r4, =0x1FFF8000
    ldr r0, [r4, #0x78]         @ second entry: just mark and leave
    cbz r0, 3f
    movs r1, #0x3B
    bl mark
    pop {r4, pc}
3:  movs r0, #1
    str r0, [r4, #0x78]
    movs r1, #0x31              @ low: start
    bl mark
    ldr r0, =0xE000E20C         @ ISPR3: pend IRQ 122 -> pre-empts here
    ldr r1, =0x04000000
    str r1, [r0]
    movs r1, #0x32              @ low: end
    bl mark
    pop {r4, pc}
    .ltorg

    .thumb_func
isr122:
    push {r4, lr}
    movs r1, #0xA1              @ high: start
    bl mark
    ldr r0, =0xE000E204         @ ISPR1: pend IRQ 33 -> must not pre-empt
    movs r1, #2
    str r1, [r0]
    movs r1, #0xA2              @ high: end
    bl mark
    pop {r4, pc}
    .ltorg
"""


def test_priority_inverted_pair_preempts_correctly(tmp_path):
    """REQ-PIL-001: IRQ 122 of the higher priority pre-empts IRQ 33 at once; IRQ 33 pended again
    meanwhile does not pre-empt itself and runs tail-chained after it.

    Methods: 1a pre-emption by priority and tail chaining of the statement; 1d the error guessed: pre-emption decided by the IRQ number instead of the priority
    """
    elf = build(tmp_path, "preempt", PREEMPT, {33: "isr33", 122: "isr122"})
    c = core.Core(elf)
    c.boot()
    assert c.run_until(50000), c.stopped
    n = rd(c, LOG + 0x7C)
    log = [rd(c, LOG + 4 * k) for k in range(n)]
    # 33 starts; 122 pre-empts it at once and runs to its end (33 pended again waits);
    # 33 resumes and ends; its second request then runs (tail-chained)
    assert log == [0x31, 0xA1, 0xA2, 0x32, 0x3B]
    assert c.preemptions == 1
    assert c.tailchains == 1
    assert len(c.irq_stats[33]) == 2 and len(c.irq_stats[122]) == 1


# ---------------------------------------------------------------------- stops
UNKNOWN = """
    .thumb_func
reset:
    ldr r0, =0x40001000
    .global bad
bad:
    ldr r1, [r0]
1:  b 1b
    .ltorg
"""


def test_unknown_register_stops_with_address_and_pc(tmp_path):
    """REQ-PIL-002: an access to a register no model defines stops the run with the address and the PC.

    Methods: 1a the stop on an unknown register; 1d the error guessed: a model that reads 0 for a register it does not know
    """
    elf = build(tmp_path, "unknown", UNKNOWN, {})
    c = core.Core(elf)
    periph.build(c)
    c.boot()
    assert not c.run_until(10000)
    assert "0x40001000" in c.stopped
    assert "pc 0x%08X" % (sym(elf, "bad") & ~1) in c.stopped
    assert "do not know" in c.stopped


READ_ONLY = """
    .thumb_func
reset:
    ldr r0, =0x4006509C         @ PCC_ADC1: clock on (SPLLDIV2)
    ldr r1, =0x46000000
    str r1, [r0]
    ldr r0, =0x40027048         @ ADC1_RA: read-only
    movs r1, #5
    .global bad
bad:
    str r1, [r0]
1:  b 1b
    .ltorg
"""


def test_write_to_read_only_register_stops(tmp_path):
    """REQ-PIL-002: a write to a read-only register stops the run.

    Methods: 1a the stop on a read-only register; 1b the class of read-only registers
    """
    elf = build(tmp_path, "ro", READ_ONLY, {})
    c = core.Core(elf)
    periph.build(c)
    c.boot()
    assert not c.run_until(10000)
    assert "read-only register ADC1_RA" in c.stopped
    assert "0x40027048" in c.stopped and "pc 0x%08X" % (sym(elf, "bad") & ~1) in c.stopped


UNINIT = """
    .thumb_func
reset:
    ldr r0, =0x1FFF8100
    .global bad
bad:
    ldr r1, [r0]
1:  b 1b
    .ltorg
"""


def test_sram_read_before_write_stops(tmp_path):
    """REQ-PIL-002: a read of SRAM before its first write stops the run (the part's ECC fault).

    Methods: 1a the stop on SRAM read before written; 1d the error guessed: start-up code that skips the RAM initialisation
    """
    elf = build(tmp_path, "ecc", UNINIT, {})
    c = core.Core(elf)
    c.boot()
    assert not c.run_until(10000)
    assert "SRAM read before its first 32-bit write" in c.stopped and "0x1FFF8100" in c.stopped


FTM_WP = """
    .thumb_func
reset:
    ldr r0, =0x40065098         @ PCC_FTM3: clock on
    ldr r1, =0x46000000
    str r1, [r0]
    ldr r0, =0x40026074         @ FTM3_FMS: WPEN
    movs r1, #0x40
    str r1, [r0]
    ldr r0, =0x40026068         @ FTM3_DEADTIME, write-protected now
    movs r1, #5
    .global bad
bad:
    str r1, [r0]
1:  b 1b
    .ltorg
"""


def test_ftm_write_while_protected_stops(tmp_path):
    """REQ-PIL-002: a change of a write-protected FTM3 register stops the run.

    Methods: 1a the stop on a write-protected FTM3 register; 1d the error guessed: configuration written after FMS[WPEN]
    """
    elf = build(tmp_path, "wp", FTM_WP, {})
    c = core.Core(elf)
    periph.build(c)
    c.boot()
    assert not c.run_until(10000)
    assert "write-protected" in c.stopped and "0x40026068" in c.stopped


MISALIGNED = """
    .thumb_func
reset:
    ldr r0, =0x40065099
    .global bad
bad:
    ldrb r1, [r0]
1:  b 1b
    .ltorg
"""


def test_partial_peripheral_access_stops(tmp_path):
    """REQ-PIL-002: a byte read at an address inside a 32-bit peripheral register stops the run.

    Methods: 1a the stop on a partial access; 1b the class of byte and half-word accesses
    """
    elf = build(tmp_path, "mis", MISALIGNED, {})
    c = core.Core(elf)
    periph.build(c)
    c.boot()
    assert not c.run_until(10000)
    assert "0x40065099" in c.stopped


# ---------------------------------------------------------------------- the image
FW = os.path.join(ROOT, "build", "s32k144", "qfoc_compressor.elf")


@pytest.mark.skipif(not os.path.exists(FW), reason="make firmware first")
def test_firmware_interrupt_rates(tmp_path):
    """REQ-PIL-001: 20 ms of the firmware image: FTM3 and ADC1 once per PWM period, LPIT0 once per ms, every tick refreshes the watchdog, the ADC1 request at MOD plus three conversions.

    Methods: 1a the interrupt rates of the statement on the image
    """
    import plant as plant_mod
    import run
    lib = plant_mod.build(str(tmp_path / "libpilplant.so"))
    pil = run.PIL(FW, os.path.join(ROOT, "specs", "motors", "reference.toml"), 320.0, lib)
    c = pil.core
    c.boot()
    assert c.run_until(20 * 80_000), c.stopped            # 20 ms
    per = pil.dev["FTM3"].reloads
    assert abs(len(c.irq_stats[122]) - per) <= 1 and per >= 150
    assert abs(len(c.irq_stats[40]) - per) <= 1
    assert abs(len(c.irq_stats[48]) - 20) <= 1
    assert pil.dev["WDOG"].refreshes == len(c.irq_stats[48])
    assert pil.latencies and max(pil.latencies) < 2 * pil.dev["FTM3"].r["MOD"]
    # the ADC1 request: PDB1 pre-trigger 0 after CH0DLY0 = MOD clocks, then 3 conversions
    trig = pil.dev["PDB1"].trigger_times
    req = c.irq_stats[40][-1][3]
    last = max(t for t in trig if t <= req)
    assert req - last == pil.dev["FTM3"].r["MOD"] + 3 * pil.dev["ADC1"].conv_cycles()


# ---------------------------------------------------------------------- watchdog
# WDOG on after reset (CS reset value: enabled, unlocked); the image sets TOVAL = 8 LPO
# clocks (8 x 625 = 5000 core clocks) and never refreshes: each timeout resets the part,
# which boots and configures it again.  The fed variant refreshes every ~300 clocks.
WDOG_MISS = """
    .thumb_func
reset:
    ldr r0, =0x40052000
    ldr r1, =0xD928C520
    str r1, [r0, #4]            @ unlock
    movs r1, #8
    str r1, [r0, #8]            @ TOVAL = 8 LPO clocks
    ldr r1, =0x21A0             @ CMD32EN, LPO, EN, UPDATE
    str r1, [r0]
1:  b 1b
    .ltorg
"""

WDOG_FED = WDOG_MISS.replace("1:  b 1b", """    ldr r2, =0xB480A602
1:  str r2, [r0, #4]            @ refresh
    movs r3, #100
2:  subs r3, #1
    bne 2b
    b 1b""")


def test_missed_watchdog_refresh_resets_the_image(tmp_path):
    """REQ-PIL-001: an image that never refreshes the watchdog is reset at each timeout and boots again.

    Methods: 1a the watchdog reset of the statement; 1l the fault injected: the refresh left out
    """
    elf = build(tmp_path, "wdog", WDOG_MISS, {})
    c = core.Core(elf)
    periph.build(c)
    c.boot()
    assert c.run_until(12_000), c.stopped
    assert c.resets == 2                                    # 8 x 625 clocks after each boot


def test_refreshed_watchdog_does_not_reset(tmp_path):
    """REQ-PIL-001: an image that refreshes the watchdog is never reset.

    Methods: 1a no reset while refreshed; 1b the class of a refresh well within the timeout
    """
    elf = build(tmp_path, "wdogok", WDOG_FED, {})
    c = core.Core(elf)
    d = periph.build(c)
    c.boot()
    assert c.run_until(50_000), c.stopped
    assert c.resets == 0 and d["WDOG"].refreshes > 10


# ---------------------------------------------------------------------- Unicorn's behaviour
# The two facts of Unicorn that core.py relies on, checked on the installed version.
def _uc(code):
    from unicorn import Uc, UC_ARCH_ARM, UC_MODE_THUMB, UC_MODE_MCLASS
    from unicorn.arm_const import UC_ARM_REG_SP
    mu = Uc(UC_ARCH_ARM, UC_MODE_THUMB | UC_MODE_MCLASS)
    mu.mem_map(0, 0x1000)
    mu.mem_write(0, code)
    mu.mem_map(0x20000000, 0x1000)
    mu.reg_write(UC_ARM_REG_SP, 0x20000800)
    return mu


def test_unicorn_reports_exc_return_as_exception_8():
    """REQ-PIL-001: Unicorn's behaviour the core relies on: a branch to EXC_RETURN reported as exception 8.

    Methods: 1a the exception return the core implements on Unicorn's report; 1d the error guessed: a Unicorn version that changes the report
    """
    from unicorn import UcError, UC_HOOK_INTR, UC_ERR_EXCEPTION
    from unicorn.arm_const import UC_ARM_REG_LR, UC_ARM_REG_PC, UC_ARM_REG_R0
    code = bytes.fromhex("0530" "7047")            # adds r0, #5 ; bx lr
    for exc_return in (0xFFFFFFF9, 0xFFFFFFF1):
        mu = _uc(code)
        mu.reg_write(UC_ARM_REG_LR, exc_return)
        with pytest.raises(UcError) as e:          # no hook: an unhandled CPU exception
            mu.emu_start(1, 0xFFFF, count=10)
        assert e.value.errno == UC_ERR_EXCEPTION
        mu = _uc(code)
        mu.reg_write(UC_ARM_REG_LR, exc_return)
        seen = []
        mu.hook_add(UC_HOOK_INTR, lambda uc, n, u: (seen.append((n, uc.reg_read(UC_ARM_REG_PC))),
                                                    uc.emu_stop()))
        mu.emu_start(1, 0xFFFF, count=10)
        assert seen == [(core.EXCP_EXCEPTION_EXIT, exc_return & ~1)]
        assert mu.reg_read(UC_ARM_REG_R0) == 5     # nothing unstacked: the host's job


def test_unicorn_repeats_a_store_stopped_in_its_hook():
    """REQ-PIL-001: Unicorn's behaviour the core relies on: a store stopped in its hook is executed again on restart.

    Methods: 1a the store applied once per nesting depth; 1d the error guessed: a store applied twice
    """
    from unicorn import UC_HOOK_MEM_WRITE
    from unicorn.arm_const import UC_ARM_REG_PC
    code = bytes.fromhex("4ff00052" "0120" "1060" "0130" "fee7")  # mov.w r2,#0x20000000; movs r0,#1; str r0,[r2]; adds r0,#1; b .
    mu = _uc(code)
    hits = []

    def w(uc, acc, addr, size, value, user):
        hits.append(uc.reg_read(UC_ARM_REG_PC))
        if len(hits) == 1:
            uc.emu_stop()
    mu.hook_add(UC_HOOK_MEM_WRITE, w)
    mu.emu_start(1, 0xFFFF, count=100)
    assert mu.reg_read(UC_ARM_REG_PC) == 6         # stopped at the store, not after it
    mu.emu_start(6 | 1, 0xFFFF, count=2)
    assert hits == [6, 6]                          # the store's hook runs again on restart


def test_unicorn_count_skips_failed_it_instructions_and_the_core_does_not(tmp_path):
    """REQ-PIL-001: the time base counts an IT-block instruction whose condition fails (Unicorn's count does not).

    Methods: 1a the time base of one clock per instruction; 1c the boundary of an IT block whose condition fails
    """
    # movs r0,#0; cmp r0,#0; it ne; movne r1,#1 (condition fails); movs r2,#2; b .
    code = bytes.fromhex("0020" "0028" "18bf" "0121" "0222" "fee7")
    from unicorn.arm_const import UC_ARM_REG_PC
    mu = _uc(code)
    mu.emu_start(1, 0xFFFF, count=3)
    assert mu.reg_read(UC_ARM_REG_PC) == 8         # 3 counted, the skipped movne not
    body = """
    .thumb_func
reset:
    movs r0, #0
    cmp r0, #0
    it ne
    movne r1, #1
    movs r2, #2
1:  b 1b
"""
    elf = build(tmp_path, "it", body, {})
    c = core.Core(elf)
    c.boot()
    assert c.run_until(4), c.stopped
    # the chunk of count=4 ran past the movs r2 (5 instructions) and the time base counted
    # all five: the skipped movne takes its cycle
    assert c.mu.reg_read(UC_ARM_REG_PC) == (sym(elf, "reset") & ~1) + 10
    assert c.insns == 5 and c.cycles == 5


# ---------------------------------------------------------------------- FTM3 model
# FTM3 up-down, MOD 100: a compare value written with LDOK loads at the reload point
# (counter at MOD, SYNC[CNTMAX]) and not before; RF is set there; CNT counts up then down.
FTM_LOAD = """
    .thumb_func
reset:
    ldr r0, =0x40065098         @ PCC_FTM3: SPLLDIV1 (PCS 110), clock on
    ldr r1, =0x46000000
    str r1, [r0]
    ldr r0, =0x40026000
    movs r1, #100
    str r1, [r0, #0x08]         @ MOD (counter stopped: written at once)
    movs r1, #50
    str r1, [r0, #0x10]         @ C0V
    movs r1, #0x20
    str r1, [r0, #0x64]         @ COMBINE: SYNCEN0
    movs r1, #0x02
    str r1, [r0, #0x58]         @ SYNC: CNTMAX
    movs r1, #0x28
    str r1, [r0, #0x00]         @ SC: CLKS = 01, CPWMS: the counter starts
    movs r1, #20
    .global wr_c0v
wr_c0v:
    str r1, [r0, #0x10]         @ C0V = 20 (buffered)
    mov r1, #0x200
    str r1, [r0, #0x98]         @ PWMLOAD[LDOK]
1:  b 1b
    .ltorg
"""


def test_ftm_compare_loads_at_the_reload_point(tmp_path):
    """REQ-PIL-001: FTM3 compare values written with LDOK load at the reload point, not at the write.

    Methods: 1a the compare values in effect at the reload point; 1c the boundary: written just before and just after a reload point
    """
    elf = build(tmp_path, "ftm", FTM_LOAD, {})
    c = core.Core(elf)
    d = periph.build(c)
    c.boot()
    ftm = d["FTM3"]
    assert c.run_until(40), c.stopped
    t0 = ftm.t_ref
    assert ftm.r["C0V"] == 50 and ftm.buf["C0V"] == 20 and ftm.r["PWMLOAD"] & 0x200
    assert c.run_until(t0 + 99), c.stopped
    assert ftm.r["C0V"] == 50 and not ftm.r["SC"] & 0x80       # not yet at MOD
    assert c.run_until(t0 + 101), c.stopped
    assert ftm.r["C0V"] == 20 and ftm.r["SC"] & 0x80           # loaded; RF set
    assert ftm.r["SC"] & 0x200                                 # TOF: MOD -> MOD - 1
    assert c.run_until(t0 + 150), c.stopped
    c.chunk_end = None
    assert ftm.rd_CNT() == 50 and ftm.dir == -1                # counting down
    assert ftm.reloads == 1


# ---------------------------------------------------------------------- FP guard
# Unicorn executes FP instructions and sets CONTROL.FPCA as the core does; an interrupt
# taken after that would need the extended frame, which core.py does not stack: it stops.
FP_USE = """
    .fpu fpv4-sp-d16
    .thumb_func
reset:
    vmov s0, r0
    ldr r0, =0xE000E104         @ ISER1, ISPR1: IRQ 40 enabled and pending
    movs r1, #1
    lsls r1, r1, #8
    str r1, [r0]
    ldr r0, =0xE000E204
    str r1, [r0]
1:  b 1b
    .ltorg

    .thumb_func
isr40:
    bx lr
"""


def test_interrupt_after_fp_use_stops(tmp_path):
    """REQ-PIL-002: an interrupt taken after a floating-point instruction (CONTROL.FPCA set) stops the run.

    Methods: 1a the stop on the extended frame, not modelled; 1d the error guessed: port code compiled with FP instructions in a handler
    """
    elf = build(tmp_path, "fp", FP_USE, {40: "isr40"})
    c = core.Core(elf)
    c.boot()
    assert not c.run_until(10000)
    assert "FPCA" in c.stopped


# ---------------------------------------------------------------------- lock-step and scenarios
@pytest.fixture(scope="module")
def libs(tmp_path_factory):
    import plant as plant_mod
    import twin as twin_mod
    d = tmp_path_factory.mktemp("pil")
    return (plant_mod.build(str(d / "libpilplant.so")), twin_mod.build(str(d / "libpiltwin.so")))


def fw_run(libs, *argv):
    import run
    args = run.parse_args([FW, "--lib", libs[0], "--twin-lib", libs[1], "--lockstep"] + list(argv))
    return args, run


@pytest.mark.skipif(not os.path.exists(FW), reason="make firmware first")
def test_lockstep_short_run_without_divergence(libs, capsys):
    """REQ-PIL-003: 150 ms of the image (PRECHARGE) in lock-step with the host build: every
    period's C0V..C5V and enable and every tick's outputs equal the host's.

    Methods: 1a the comparison of the statement, period by period and tick by tick;
    1n back-to-back comparison of the image against the host build of the same drive
    """
    args, run = fw_run(libs, "--ms", "150", "--expect", "PRECHARGE")
    r = run.execute(args)
    ls = r["lockstep"]
    assert r["ok"], capsys.readouterr().out
    assert ls.divergence is None and ls.periods >= 1150 and ls.ticks_compared >= 149
    assert ls.inits == 1 and ls.fast_calls >= ls.periods


@pytest.mark.skipif(not os.path.exists(FW), reason="make firmware first")
def test_lockstep_reports_an_injected_divergence(libs, monkeypatch, capsys):
    """REQ-PIL-003: the host's compare value of phase u made one count larger from its 400th
    fast step on: the run fails with the first divergence at that fast step (its result,
    read at its return), the image's and the host's values.

    Methods: 1l the fault injected into the host's output (one count on one phase from one
    period on); 1c the boundary of a one-count difference
    """
    import twin as twin_mod
    fast = twin_mod.Twin.fast
    calls = []

    def skewed(self, iu, iv, vdc):
        cmp_, en = fast(self, iu, iv, vdc)
        calls.append(1)
        if len(calls) >= 400:
            cmp_ = [cmp_[0] + 1] + cmp_[1:]
        return cmp_, en
    monkeypatch.setattr(twin_mod.Twin, "fast", skewed)
    args, run = fw_run(libs, "--ms", "80")
    r = run.execute(args)
    out = capsys.readouterr().out
    period, field, img, host, t = r["lockstep"].divergence
    assert not r["ok"] and field == "fast step 400 result"
    assert host[0][0] == img[0][0] + 1 and host[0][1:] == img[0][1:]
    assert abs(period - 400) <= 2
    assert "FIRST DIVERGENCE" in out


@pytest.mark.skipif(not os.path.exists(FW), reason="make firmware first")
def test_stalled_adc_handler_resets_the_image_by_the_watchdog(libs, capsys):
    """REQ-PIL-004: the ADC1 handler spins from 50 ms on: the tick no longer runs, the
    watchdog (10 ms) resets the image within the timeout plus one tick; the lock-step holds
    up to the stall.

    Methods: 1l the fault injected: a handler that never returns; 1c the boundary of the
    watchdog timeout plus one tick
    """
    args, run = fw_run(libs, "--ms", "75", "--stall-adc-isr-ms", "50", "--expect", "ANY")
    r = run.execute(args)
    pil = r["pil"]
    assert r["ok"], capsys.readouterr().out
    assert len(pil.reset_times) == 1
    assert 0 < pil.reset_times[0] - 50 * 80_000 <= 11 * 80_000
    assert r["lockstep"].periods > 350 and r["lockstep"].divergence is None


@pytest.mark.skipif(not os.path.exists(FW), reason="make firmware first")
def test_stuck_converter_latches_the_fault_output(libs, capsys):
    """REQ-PIL-004: ADC1 converts nothing from 50 ms on: the tick's supervision (more than 2
    periods without a fast step in a millisecond) masks the six outputs and disables the
    gate driver within 2 ms; no watchdog reset.

    Methods: 1l the fault injected: no conversion complete; 1c the boundary of the 2 ms
    from the last conversion to the latched output
    """
    args, run = fw_run(libs, "--ms", "60", "--stuck-adc-ms", "50", "--expect", "ANY")
    r = run.execute(args)
    pil = r["pil"]
    assert r["ok"], capsys.readouterr().out
    assert pil.t_gate_off is not None and pil.t_gate_off - 50 * 80_000 <= 2 * 80_000
    assert pil.core.resets == 0


@pytest.mark.skipif(not os.path.exists(FW), reason="make firmware first")
def test_tick_preempted_by_the_adc_interrupt_at_once(libs, capsys):
    """REQ-PIL-004: the tick's phase shifted by 5000 clocks (requested 335 clocks before the
    ADC1 request): the ADC1 interrupt pre-empts every tick with a latency of at most 100
    clocks, and the lock-step holds with the tick pre-empted.

    Methods: 1a the priorities of the port (REQ-PORT-015) seen as latency; 1c the boundary of
    a tick requested just before the ADC1 request
    """
    args, run = fw_run(libs, "--ms", "60", "--tick-phase-clk", "5000", "--adc-latency-max", "100",
                       "--expect", "ANY")
    r = run.execute(args)
    c = r["pil"].core
    assert r["ok"], capsys.readouterr().out
    assert c.preempt_pairs.get((48, 40), 0) >= 50
    assert r["adc_latency_max"] <= 100


def test_seeded_defects_apply_exactly_once():
    """REQ-PIL-005: each seeded defect of defects.py is one substitution whose text occurs
    exactly once in the port's source file and differs from its replacement; the control
    has none.

    Methods: 1d the errors guessed: a PDB delay off by half a PWM period, a compare value on
    the wrong channel pair, the dead time not inserted, the low side not the complement, a
    clock divider off by a factor of 2, the ADC interrupt below the tick in priority
    """
    import defects
    names = [d[0] for d in defects.DEFECTS]
    assert names[0] == "control" and len(names) == 7
    for name, fname, old, new, what in defects.DEFECTS[1:]:
        text = open(os.path.join(ROOT, "port_s32k", fname)).read()
        assert text.count(old) == 1 and old != new and new not in text, name


@pytest.mark.skipif(not os.path.exists(FW), reason="make firmware first")
def test_library_counts_within_the_static_bound(libs, monkeypatch, capsys):
    """REQ-PIL-006: the instructions the image executes inside qfoc_drive_fast_step and
    qfoc_drive_tick, counted at their entry and return in the running image, are at most the
    static bound tools/bench/wcet.py computes for them on the same image; the RUN entry
    (power on at 350 ms) is inside the run.  Each fast step runs inside an ADC1 handler, so
    the handler's own instructions are at least the fast step's.  With the bound made one
    below the longest measured call the run fails on that check.

    Methods: 1a the comparison of the statement; 1c the boundary of a bound one below the
    measured maximum
    """
    import timing
    args, run = fw_run(libs, "--ms", "420", "--lin-period-ms", "20", "--power-on-ms", "350")
    r = run.execute(args)
    out = capsys.readouterr().out
    assert r["ok"], out
    lib, c = r["lib"], r["pil"].core
    bounds = r["timing"]["static_bound"]
    fast, tick = lib.calls["qfoc_drive_fast_step"], lib.calls["qfoc_drive_tick"]
    adc = [s[0] for s in c.irq_stats[40]]
    assert len(fast) == len(adc) and len(tick) == len(c.irq_stats[48])
    assert 1000 < max(fast) <= bounds["qfoc_drive_fast_step"]
    assert max(tick) <= bounds["qfoc_drive_tick"]
    assert all(a >= f for a, f in zip(adc, fast))
    assert r["timing"]["lib"]["qfoc_drive_fast_step"]["max"] == max(fast)

    low = dict(bounds, qfoc_drive_fast_step=max(fast) - 1)
    monkeypatch.setattr(timing, "static_bounds", lambda elf: low)
    args, run = fw_run(libs, "--ms", "420", "--lin-period-ms", "20", "--power-on-ms", "350")
    r = run.execute(args)
    out = capsys.readouterr().out
    assert not r["ok"]
    assert "FAIL the library's measured instructions within their static bound" in out


# ---------------------------------------------------------------------- FTM3 outputs
def ftm_cpwm(c0v=(1200, 2500, 4000), deadtime=0x94, comb_pair=0x72, pol=0, outmask=0):
    """An FTM3 model in the port's set-up, without a core: up-down counting, MOD 5000,
    six high-true channels, the pairs complementary with dead time (COMP, DTEN, SYNCEN,
    FAULTEN: 0x72), DEADTIME 0x94 (DTPS /4, DTVAL 20: 80 clocks)."""
    f = periph.FTM()
    f.running = True
    f.r["SC"] = 0x20 | (1 << 3) | (0x3F << 16)
    f.r["MOD"] = 5000
    for ch in range(6):
        f.r["C%dSC" % ch] = 0x28
        f.r["C%dV" % ch] = c0v[ch // 2] if ch % 2 == 0 else 2500
    f.r["COMBINE"] = comb_pair | (comb_pair << 8) | (comb_pair << 16)
    f.r["DEADTIME"], f.r["POL"], f.r["OUTMASK"] = deadtime, pol, outmask
    return f


def test_ftm_outputs_complementary_with_dead_time():
    """REQ-PIL-007: in the port's set-up each high side is on from MOD - CnV + dead time to
    MOD + CnV of the period that starts at the reload point, its low side before MOD - CnV and
    from MOD + CnV + dead time on; the plant gets CnV and the dead time 80 FTM clocks
    (DTPS /4 x DTVAL 20); DTVALEX extends DTVAL; a high-side pulse no longer than the dead
    time disappears and the plant keeps its nominal width (the diode conducts in the gap).

    Methods: 1a the RM's output of a complementary pair with dead time; 1b prescalers /1, /4,
    /16 and DTVALEX; 1c the boundary of a pulse as long as the dead time
    """
    f = ftm_cpwm()
    assert f.dead_ticks() == 80
    pins = f.pin_on()
    assert pins[0] == [(5000 - 1200 + 80, 5000 + 1200)]
    assert pins[1] == [(0, 5000 - 1200), (5000 + 1200 + 80, 10000)]
    assert periph.bridge(pins, 5000) == ([1200, 2500, 4000], 80, True)
    for reg, ticks in ((0x05, 5), (0x45, 5), (0x85, 20), (0xC5, 80), ((1 << 16) | 0x05, 69),
                       ((0xF << 16) | 0xFF, 16 * 1023)):
        assert ftm_cpwm(deadtime=reg).dead_ticks() == ticks, hex(reg)
    f = ftm_cpwm(c0v=(40, 2500, 5000))
    pins = f.pin_on()
    assert pins[0] == [] and pins[4] == [(0, 10000)] and pins[5] == []
    assert periph.bridge(pins, 5000) == ([40, 2500, 5000], 80, True)


def test_ftm_outputs_without_dead_time_mask_polarity_and_shoot_through():
    """REQ-PIL-007: DTEN clear gives dead time 0 to the plant; OUTMASK of all six outputs
    switches the bridge off; COMP clear (the low side a PWM of its own CnV) or POL set on a
    low side puts both switches of a leg on together: the run stops on the shoot-through.

    Methods: 1d the errors guessed: dead time off, complementary mode off, an inverted
    output; 1b the masked bridge
    """
    f = ftm_cpwm(comb_pair=0x62)
    assert periph.bridge(f.pin_on(), 5000) == ([1200, 2500, 4000], 0, True)
    f = ftm_cpwm(outmask=0x3F)
    assert periph.bridge(f.pin_on(), 5000) == ([0, 0, 0], None, False)
    for kw in ({"comb_pair": 0x70}, {"pol": 0x02}):
        with pytest.raises(core.Stop, match="shoot-through"):
            periph.bridge(ftm_cpwm(**kw).pin_on(), 5000)


@pytest.mark.skipif(not os.path.exists(FW), reason="make firmware first")
def test_dead_time_mismatch_with_the_table_is_reported(libs, monkeypatch, capsys):
    """REQ-PIL-007: the image's FTM3 inserts 80 FTM clocks, the table compensates dt_comp =
    40 compare counts (80 clocks): the run passes and the plant switches with the registers'
    dead time (1 us); with the registers read as 60 clocks the run fails on the dead-time
    check, which names both figures.

    Methods: 1a the comparison of the statement; 1l the fault injected: a dead time 20 clocks
    short of the compensation
    """
    args, run = fw_run(libs, "--ms", "420", "--lin-period-ms", "20", "--power-on-ms", "350")
    r = run.execute(args)
    out = capsys.readouterr().out
    assert r["ok"], out
    pil = r["pil"]
    assert set(pil.dead_ticks) == {80} and pil.dead_ticks[80] > 100
    assert abs(pil.plant.dead_time_s - 1.0e-6) < 1e-12
    monkeypatch.setattr(periph.FTM, "dead_ticks", lambda self: 60)
    args, run = fw_run(libs, "--ms", "60")
    r = run.execute(args)
    out = capsys.readouterr().out
    assert not r["ok"]
    assert "FAIL the inverter's dead time from the FTM3 registers" in out
    assert "registers 60" in out and "table 80" in out


# ---------------------------------------------------------------------- clocks
def scg_regs(**kw):
    """An SCG model with the port's clock set-up (mcu.c, qfoc_s32k_clock_init): SOSC 8 MHz
    crystal, SOSCDIV1 = SOSCDIV2 = /1, SPLL PREDIV 0, MULT 24, SPLLDIV1 /2, SPLLDIV2 /4,
    RCCR SCS = SPLL, DIVCORE 1, DIVBUS 1, DIVSLOW 2; keyword arguments replace registers."""
    g = periph.SCG()
    g.r.update({"SOSCCSR": 1, "SOSCCFG": 0x24, "SOSCDIV": 0x101, "SPLLCSR": 1,
                "SPLLCFG": 24 << 16, "SPLLDIV": 0x302, "RCCR": 0x06010012})
    g.r.update(kw)
    g._tree = None
    return g


def test_clock_tree_from_the_scg_registers():
    """REQ-PIL-008: the port's set-up gives VCO 320 MHz, SPLL_CLK 160 MHz, SPLLDIV1 80,
    SPLLDIV2 40, SOSCDIV2 8, CORE = SYS 80, BUS 40, FLASH 80 / 3 MHz; PREDIV divides the
    source by PREDIV + 1, MULT multiplies by MULT + 16, a divider field n by 2^(n - 1), 0
    turns the output off; without the crystal (EREFS 0) or the SOSC disabled the SPLL is off.

    Methods: 1a the RM's formulas; 1b each divider code; 1c the boundaries 0 (off) and 7
    (/64) of a divider field
    """
    t = scg_regs().clock_tree()
    assert (t["VCO"], t["SPLL"], t["SPLLDIV1"], t["SPLLDIV2"]) == (320e6, 160e6, 80e6, 40e6)
    assert (t["SOSCDIV1"], t["SOSCDIV2"], t["CORE"], t["SYS"], t["BUS"]) == (8e6, 8e6, 80e6, 80e6, 40e6)
    assert t["FLASH"] == 80_000_000 // 3
    t = scg_regs(SPLLCFG=(24 << 16) | (1 << 8)).clock_tree()
    assert t["VCO"] == 160e6 and t["SPLLDIV1"] == 40e6
    t = scg_regs(SPLLCFG=4 << 16).clock_tree()
    assert t["SPLL"] == 80e6
    for field, div in ((1, 1), (2, 2), (3, 4), (7, 64)):
        assert scg_regs(SOSCDIV=field << 8).clock_tree()["SOSCDIV2"] == 8e6 / div
    assert scg_regs(SOSCDIV=0).clock_tree()["SOSCDIV2"] is None
    assert scg_regs(SOSCCFG=0x20).clock_tree()["SPLL"] is None
    assert scg_regs(SOSCCSR=0).clock_tree()["SOSCDIV2"] is None


def test_peripheral_clocks_follow_the_registers(tmp_path):
    """REQ-PIL-008: the core clocks per count of FTM3 (CLKS 01: SYS_CLK), the PDBs (SYS_CLK),
    the ADCs (PCC PCS: SPLLDIV2 / 2^ADIV), LPIT0 and LPUART1 (PCC PCS: SOSCDIV2) follow the
    SCG and PCC registers: SOSCDIV2 halved doubles the LPIT0 and LPUART1 counts, SPLLDIV2
    halved doubles the ADC conversion; a clock that is off, a PCC source not modelled, or
    a core clock other than the 80 MHz time base stops the run.

    Methods: 1a the clock of each peripheral per the RM; 1d the errors guessed: a divider
    off by 2, a clock left off, the core switched to another frequency
    """
    elf = build(tmp_path, "idle", "    .thumb_func\nreset:\n    b reset\n", {})
    c = core.Core(elf)
    dev = periph.build(c)
    g = dev["SCG"]
    g.r.update(scg_regs().r)
    g._tree = None
    for off, pcs in ((0xDC, 1), (0x1AC, 1), (0xEC, 6), (0x9C, 6), (0x98, 6)):
        dev["PCC"].r[off] = (1 << 31) | periph.CGC | (pcs << 24)
    ftm, pdb, adc, lpit, uart = dev["FTM3"], dev["PDB1"], dev["ADC1"], dev["LPIT0"], dev["LPUART1"]
    ftm.r["SC"] = 1 << 3
    adc.r["CFG2"] = 12
    uart.r["BAUD"] = 0x0F00801A
    assert (ftm.tick(), pdb.clk(), lpit.clk(), adc.conv_cycles()) == (1, 1, 10, 2 * 33)
    assert uart.bit_cycles() == 16 * 26 * 10
    g.r["SOSCDIV"] = 0x201
    g._tree = None
    assert (lpit.clk(), uart.bit_cycles()) == (20, 16 * 26 * 20)
    g.r["SPLLDIV"] = 0x402
    g._tree = None
    assert adc.conv_cycles() == 4 * 33 and ftm.tick() == 1
    g.r["SPLLDIV"] = 0x002
    g._tree = None
    with pytest.raises(core.Stop, match="SPLLDIV2 is off"):
        adc.conv_cycles()
    dev["PCC"].r[0xDC] = (1 << 31) | periph.CGC | (3 << 24)
    with pytest.raises(core.Stop, match="FIRCDIV2 is not modelled"):
        lpit.clk()
    with pytest.raises(core.Stop, match="time base"):
        g.wr_RCCR(0x06020012)


@pytest.mark.skipif(not os.path.exists(FW), reason="make firmware first")
def test_image_rates_from_the_clock_tree(libs, monkeypatch, capsys):
    """REQ-PIL-008: the image's registers give the table's PWM frequency (8000 Hz), a 1 ms
    LPIT0 period, LIN 19230.8 baud (19200 +-1.5 %) and CAN 500 kbit/s; with the crystal
    taken as 4 MHz (every clock derived from it halved) the image's switch of the core to
    the SPLL stops the run: CORE_CLK 40 MHz from the registers, not the 80 MHz time base.

    Methods: 1a the rates of the statement from the registers; 1l the fault injected: the
    crystal at half its frequency
    """
    args, run = fw_run(libs, "--ms", "60", "--expect", "ANY")
    r = run.execute(args)
    out = capsys.readouterr().out
    assert r["ok"], out
    assert "PWM 8000.0 Hz (table f_pwm_hz 8000)" in out and "19230.8 baud" in out
    assert "500000 bit/s (network 500000)" in out and "period 80000 clocks" in out
    monkeypatch.setattr(periph, "SOSC_HZ", 4_000_000)
    args, run = fw_run(libs, "--ms", "60", "--expect", "ANY")
    r = run.execute(args)
    out = capsys.readouterr().out
    assert not r["ok"] and "CORE_CLK 40000000 Hz" in out


# ---------------------------------------------------------------------- sampling instant
def test_plant_sampled_at_an_instant_of_the_period(libs):
    """REQ-PIL-009: the plant's codes at tau after the period's start (sim_sample_at): at
    tau = 0 those of the period's start, at tau = T those the plant gives after the period
    with the same compare values and enable, in between the current's ripple (a code other
    than the start's); the plant itself is not changed.

    Methods: 1a the statement; 1c the boundaries tau = 0 and tau = T
    """
    import plant as plant_mod
    p = plant_mod.Plant(libs[0], os.path.join(ROOT, "specs", "motors", "reference.toml"), 320.0)
    p.set_dead_time(1e-6)
    cmp3 = [2700, 2500, 2300]
    for _ in range(40):
        p.step(cmp3, True)
    start = p.sample()
    T = 2.0 * p.period / 80e6
    assert p.sample_at(0.0) == start
    mid = [p.sample_at(T * k / 8.0) for k in range(1, 8)]
    end = p.sample_at(T)
    assert p.sample() == start                      # unchanged by sample_at
    assert any(m[:2] != start[:2] for m in mid)
    p.step(cmp3, True)
    assert p.sample() == end


@pytest.mark.skipif(not os.path.exists(FW), reason="make firmware first")
def test_conversions_convert_the_plant_at_their_instant(libs, monkeypatch, capsys):
    """REQ-PIL-009: a conversion that starts after the reload point (V_dc on ADC1_SE8, back to
    back after i_v) converts the plant at its own instant: sample_at is called with the
    clocks since the reload point (132 for V_dc) and its code is the one converted; with the
    plant's bus read as 0 V at those instants the drive never leaves PRECHARGE.

    Methods: 1a the instant of each conversion; 1l the fault injected: the bus code of the
    conversion instant 0
    """
    import plant as plant_mod
    taus = []
    orig = plant_mod.Plant.sample_at

    def spy(self, tau):
        taus.append(round(tau * 80e6))
        return orig(self, tau)
    monkeypatch.setattr(plant_mod.Plant, "sample_at", spy)
    args, run = fw_run(libs, "--ms", "150", "--expect", "PRECHARGE")
    r = run.execute(args)
    out = capsys.readouterr().out
    assert r["ok"], out
    pil = r["pil"]
    assert pil.tau_log == {(1, 8): 132} and set(taus) == {132}
    assert len(taus) == pil.off_instant > 1000

    def bus_zero(self, tau):
        return orig(self, tau)[:2] + [0]
    monkeypatch.setattr(plant_mod.Plant, "sample_at", bus_zero)
    args, run = fw_run(libs, "--ms", "450", "--lin-period-ms", "20", "--power-on-ms", "350",
                       "--expect", "STOP")
    r = run.execute(args)
    out = capsys.readouterr().out
    assert not r["ok"]
    assert all(run.STATES.get(s) == "PRECHARGE" for _, s, _ in r["seen"])


# ---------------------------------------------------------------------- library counts
# Two functions named as the drive's entry points, called from thread mode: the first runs
# 6 instructions (its bx lr included); the second pends IRQ 40 in its third store, which is
# taken at once (nested in the call: 4 instructions, entry and return), then runs on: 12
# instructions of its own.
LIB_COUNT = """
    .thumb_func
reset:
    bl qfoc_drive_fast_step
    bl qfoc_drive_tick
    ldr r0, =0x1FFF8000
    str r0, [r0]
1:  b 1b

    .thumb_func
qfoc_drive_fast_step:
    movs r0, #1
    adds r0, r0, #1
    adds r0, r0, #1
    adds r0, r0, #1
    adds r0, r0, #1
    bx lr

    .thumb_func
qfoc_drive_tick:
    ldr r0, =0xE000E104         @ ISER1: IRQ 40 enabled
    movs r1, #1
    lsls r1, r1, #8
    str r1, [r0]
    ldr r0, =0xE000E204         @ ISPR1: IRQ 40 pending: taken after this store
    str r1, [r0]
    movs r2, #1
    adds r2, r2, #1
    adds r2, r2, #1
    adds r2, r2, #1
    adds r2, r2, #1
    bx lr
    .ltorg

    .thumb_func
isr40:
    movs r3, #1
    adds r3, r3, #1
    adds r3, r3, #1
    bx lr
"""


def test_library_counts_exclude_nested_handlers(tmp_path):
    """REQ-PIL-006: the count of a call is its own instructions from the first to the return
    instruction: 6 for a straight function, 12 for one in which an interrupt (4 instructions,
    12 clocks of entry and 10 of return) is taken, the handler's 26 clocks left out.

    Methods: 1a the count of the statement on known instruction sequences; 1b a call with and
    without a nested handler
    """
    import timing
    elf = build(tmp_path, "libcount", LIB_COUNT, {40: "isr40"})
    c = core.Core(elf)
    lib = timing.LibTiming(c)
    c.log_isr = True
    c.boot()
    assert c.run_until(400), c.stopped
    assert lib.calls["qfoc_drive_fast_step"] == [6]
    assert lib.calls["qfoc_drive_tick"] == [12]
    assert [s[0] for s in c.irq_stats[40]] == [4] and c.handler_clocks == 4 + 12 + 10
    t_tick = lib.max_at["qfoc_drive_tick"]
    enter = [t for t, irq, what in c.isr_log if irq == 40 and what == "enter"]
    assert len(enter) == 1 and t_tick < enter[0] < t_tick + 12 + 26      # nested in the call
