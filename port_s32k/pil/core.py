"""core.py -- the Cortex-M4 of the processor-in-the-loop run: the S32K144 image in
Unicorn (python3-unicorn) with a memory map, a time base, an NVIC and real exception entry
and return.

Memory map (S32K144, RM Rev. 13, chapter "Memory map"): program flash 0x0000_0000
(512 KiB), SRAM_L 0x1FFF_8000 (32 KiB) and SRAM_U 0x2000_0000 (28 KiB), the peripheral
bridge 0x4000_0000 .. 0x400F_FFFF (GPIO included), the private peripheral bus 0xE000_0000.
Flash holds the ELF's loadable bytes; nothing is patched.

Checks (each stops the run with the address and the PC, `Core.stopped`):
  - an access outside the map (Unicorn's invalid-memory hook);
  - SRAM read, or written partially, before a 32-bit write initialised the word (the
    S32K144 SRAM has ECC, RM chapter "SRAM": such an access raises an ECC error); the
    exception frames this module stacks count as 32-bit writes, as the core's stacking is;
  - any access to the peripheral space or the PPB that the peripheral models
    (periph.py) do not know, that is not 32 bits wide or not aligned, or that the part
    forbids (the models raise `Stop`).

Time base: one executed instruction = one core clock at 80 MHz (the stated
approximation; the real core takes 1..n cycles per instruction and waits on flash).
Unicorn runs in chunks with emu_start(count=N) up to the next peripheral event; no
per-instruction Python hook.  The instruction count is kept by a block hook (the count at
the start of each translated block; the PC gives the position in it, Thumb instruction
lengths decoded from the image), so it is exact at every peripheral access and at the end
of a chunk.  Unicorn's own count (found by comparing the two) does not count the
instructions of an IT block whose condition fails; the time base does (they take a cycle
on the core), so a chunk may end up to a few clocks after the event it ran to, which is
then processed that much late.
The clock starts at reset at 80 MHz (the FIRC 48 MHz phase before the PLL switch is not
distinguished).

Exceptions (ARMv7-M Architecture Reference Manual, B1.5 "ARMv7-M exception model"):
  - NVIC: set-enable, clear-enable, set-pending, clear-pending, active (read only) and the
    priority registers of 123 interrupts, 4 priority bits (S32K144: the MSBs of each byte);
    AIRCR[PRIGROUP] is never written by the image and taken as 0 (all 4 bits pre-empt).
    The peripheral requests are levels: a request that becomes asserted sets the pending
    bit (also while the interrupt is disabled); entry clears it; a request still asserted
    when its handler returns, or when software clears the pending bit, pends it again
    (ARM ARM B3.4, "Nested Vectored Interrupt Controller", level-sensitive interrupts).
  - Entry: when an enabled pending interrupt's priority is higher (numerically lower)
    than the execution priority (the highest active exception's priority, 0 with PRIMASK
    set) -- the lowest interrupt number among equal priorities first -- the basic 8-word
    frame R0-R3, R12, LR, return address, xPSR is pushed on the MSP, aligned to 8 bytes
    (CCR.STKALIGN is 1 on the Cortex-M4; xPSR bit 9 records the adjustment), LR =
    EXC_RETURN 0xFFFFFFF9 (from thread mode) or 0xFFFFFFF1 (nested), PC = the vector
    (table at VTOR = 0, never moved by the image), IPSR = the exception number.
  - The extended (FP) frame is never needed: the image has no floating-point instruction
    (arm-none-eabi-objdump finds none; the build uses -mfloat-abi=hard only for the ABI),
    so CONTROL.FPCA stays 0 and EXC_RETURN bit 4 is 1.  The entry checks CONTROL.FPCA
    and stops the run if it was ever set (Unicorn executes FP instructions whatever the
    image writes to CPACR, which is plain memory here, and sets CONTROL.FPCA as the core
    does: tests/test_pil.py).
  - Return: Unicorn 2.0.1 (its QEMU 5 core) treats a branch (BX LR, POP {.., PC}) to an
    EXC_RETURN value (tested: 0xFFFFFFF1, 0xFFFFFFF9, 0xFFFFFFFD; in thread mode and with
    IPSR written alike) as an exception return: it raises its internal exception 8
    (QEMU's EXCP_EXCEPTION_EXIT) with PC = the EXC_RETURN value with bit 0 clear and
    every register unchanged, and does nothing more (Unicorn has no NVIC): without a
    UC_HOOK_INTR hook emu_start fails with UC_ERR_EXCEPTION ("Unhandled CPU exception");
    with one, the hook gets intno 8 and may stop the emulation cleanly
    (tests/test_pil.py pins both).  This module hooks
    UC_HOOK_INTR, stops, and unstacks: R0-R3, R12, LR, PC, the flags of xPSR, the SP
    (with the alignment bit), IPSR of the context returned to.  A pending interrupt that
    may pre-empt the context returned to is tail-chained: its handler is entered with the
    same frame and the same EXC_RETURN.
  - Costs: 12 clocks entry, 10 return, 6 tail chain: the zero-wait-state figures ARM
    publishes for the Cortex-M3/M4 (not checked here against a TRM table), added to the
    time base.
  - PRIMASK (CPSID/CPSIE): read from Unicorn; a code hook on each CPSIE of the image stops
    the chunk so that a pending interrupt is taken right after it.  WFI: Unicorn stops by
    itself at a WFI (QEMU's EXCP_HLT); the core then sleeps until the next event and wakes
    on any enabled pending interrupt (taken only if PRIMASK allows: ARM ARM B1.5.19).
  - Not modelled (the image uses none of them; an access stops the run as an unknown PPB
    register): BASEPRI, FAULTMASK (no MSR instruction in the image), SysTick, VTOR,
    AIRCR, SHPR, PSP/CONTROL.SPSEL (thread mode stays on the MSP), fault exceptions (a
    Unicorn CPU exception other than the return stops the run with its number).
  - Simplification: no interrupt is taken inside an IT block (the core steps to its end,
    at most 4 instructions); the real core takes it there and stacks ICI/IT.
  - A peripheral write that makes an interrupt pending, or schedules an event earlier
    than the end of the running chunk, stops the chunk at that instruction.  Unicorn
    then reports the PC of the store, which it executes again on the restart (found by
    experiment: the store's hook runs twice): the model keeps the store's PC, address,
    value and SP per nesting depth and does not apply it a second time when that context
    resumes with it.

Requirements: REQ-PIL-001, REQ-PIL-002 (specs/requirements/pil.md).
"""
import heapq
import struct

from elftools.elf.elffile import ELFFile
from unicorn import Uc, UcError, UC_ARCH_ARM, UC_MODE_THUMB, UC_MODE_MCLASS
from unicorn import (UC_HOOK_MEM_READ, UC_HOOK_MEM_WRITE, UC_HOOK_MEM_INVALID, UC_HOOK_BLOCK,
                     UC_HOOK_CODE, UC_HOOK_INTR)
from unicorn.arm_const import (UC_ARM_REG_R0, UC_ARM_REG_R1, UC_ARM_REG_R2, UC_ARM_REG_R3,
                               UC_ARM_REG_R12, UC_ARM_REG_SP, UC_ARM_REG_LR, UC_ARM_REG_PC,
                               UC_ARM_REG_XPSR, UC_ARM_REG_IPSR, UC_ARM_REG_PRIMASK,
                               UC_ARM_REG_CONTROL)

CORE_HZ = 80_000_000
FLASH = (0x00000000, 0x80000)
SRAM = (0x1FFF8000, 0x0F000)
PERIPH = (0x40000000, 0x100000)
PPB = (0xE0000000, 0x100000)

ENTRY_CYCLES = 12
RETURN_CYCLES = 10
TAILCHAIN_CYCLES = 6
EXCP_EXCEPTION_EXIT = 8           # QEMU's internal exception number, reported by Unicorn

NVIC_ISER, NVIC_ICER, NVIC_ISPR, NVIC_ICPR, NVIC_IABR = (0xE000E100, 0xE000E180, 0xE000E200,
                                                         0xE000E280, 0xE000E300)
NVIC_IPR = 0xE000E400
N_IRQ = 123
PRIO_BITS = 4
SCB_CPACR = 0xE000ED88


class Stop(Exception):
    """A model refuses an access or detects a forbidden condition: the run stops."""


def thumb_len(hw):
    """Length of the Thumb instruction whose first halfword is hw (ARM ARM A5.1)."""
    return 4 if (hw >> 11) in (0x1D, 0x1E, 0x1F) else 2


class Core:
    def __init__(self, elf_path):
        with open(elf_path, "rb") as f:
            elf = ELFFile(f)
            symtab = elf.get_section_by_name(".symtab")
            self.syms = {s.name: s["st_value"] for s in symtab.iter_symbols()} if symtab else {}
            self.segments = [(seg["p_paddr"], seg.data()) for seg in elf.iter_segments()
                             if seg["p_type"] == "PT_LOAD" and seg["p_filesz"] > 0]
        self.flash = bytearray(b"\xff" * FLASH[1])
        for addr, data in self.segments:
            if FLASH[0] <= addr < FLASH[0] + FLASH[1]:
                self.flash[addr:addr + len(data)] = data
        self.mu = Uc(UC_ARCH_ARM, UC_MODE_THUMB | UC_MODE_MCLASS)
        for base, size in (FLASH, SRAM, PERIPH, PPB):
            self.mu.mem_map(base, size)
        self.mu.mem_write(FLASH[0], bytes(self.flash))
        self.devices = {}            # address -> (device, offset): filled by attach()
        self.events = []             # heap of (cycle, seq, callback)
        self.seq = 0
        self.cycles = 0              # core clocks since reset
        self.insns = 0               # instructions executed since reset
        self.stopped = None          # reason the run stopped, with address and PC
        self.chunk_end = None
        self.ev_now = None
        self.resets = 0
        self.preempt_pairs = {}      # (pre-empted irq, pre-empting irq) -> count
        self._len_cache = {}
        self._init_state()
        self.mu.hook_add(UC_HOOK_MEM_READ, self._on_read, begin=PERIPH[0], end=PERIPH[0] + PERIPH[1] - 1)
        self.mu.hook_add(UC_HOOK_MEM_READ, self._on_read, begin=PPB[0], end=PPB[0] + PPB[1] - 1)
        self.mu.hook_add(UC_HOOK_MEM_WRITE, self._on_write)
        self.mu.hook_add(UC_HOOK_MEM_READ, self._on_sram_read, begin=SRAM[0], end=SRAM[0] + SRAM[1] - 1)
        self.mu.hook_add(UC_HOOK_MEM_INVALID, self._on_invalid)
        self.mu.hook_add(UC_HOOK_BLOCK, self._on_block)
        self.mu.hook_add(UC_HOOK_INTR, self._on_intr)
        self.wfi_addrs = set(self._find(0xBF30))             # WFI (ARM ARM A7.7.261)
        for addr in self._find(0xB662):                      # CPSIE I (ARM ARM A7.7.27)
            self.mu.hook_add(UC_HOOK_CODE, self._on_cpsie, begin=addr, end=addr)
        self.irq_names = {}
        # irq -> list of (own instructions, cycles with entry and return, latency from the
        # request to the first handler instruction, cycle of the request)
        self.irq_stats = {}
        self.handler_clocks = 0      # clocks of every completed handler (entry, own, return)
        self.isr_log = []            # (cycle, irq, 'enter'|'return')
        self.log_isr = False
        self.preemptions = 0
        self.tailchains = 0

    # ------------------------------------------------------------------ state
    def _init_state(self):
        self.written = bytearray(SRAM[1] // 4)
        self.nvic_en = [0] * 4
        self.nvic_pend = [0] * 4
        self.nvic_prio = [0] * (N_IRQ + 1)
        self.cpacr = 0
        self.lines = {}              # irq -> asserted level (peripheral requests)
        self.active = []             # stack of [irq, exc_return, insns at entry, own insns]
        self.sleeping = False
        self.replay = {}             # nesting depth -> the store to apply once only
        self.stop_request = False
        self.reason = None
        self.blk_start = 0
        self.blk_n = 0
        self.blk_end = 0
        self.chunk_base = 0          # instructions at the chunk's start
        self.chunk_done = 0          # instructions of completed blocks in the chunk
        self.skip_cpsie = False
        self.irq_wait = {}           # irq -> cycle at which its request was asserted

    def reset(self):
        """Reset of the part (watchdog): registers and peripherals to their reset values,
        SRAM kept (but its ECC state is kept too), the CPU from the reset vector."""
        self.resets += 1
        self._init_state()
        for dev in set(d for d, _ in self.devices.values()):
            dev.reset()
        self.events = []
        self.mu.reg_write(UC_ARM_REG_PRIMASK, 0)
        self.mu.reg_write(UC_ARM_REG_IPSR, 0)
        sp, pc = struct.unpack("<II", bytes(self.flash[0:8]))
        self.mu.reg_write(UC_ARM_REG_SP, sp)
        self.mu.reg_write(UC_ARM_REG_PC, pc & ~1)
        self.pc = pc | 1
        for dev in set(d for d, _ in self.devices.values()):
            dev.start()

    def attach(self, dev):
        """Map a peripheral model: dev.base and dev.regs (offset -> register)."""
        dev.core = self
        for off in dev.regs:
            self.devices[dev.base + off] = (dev, off)

    def _find(self, halfword):
        text = self.flash
        return [a for a in range(0, len(text) - 1, 2)
                if text[a] | (text[a + 1] << 8) == halfword and a < 0x7FFF0]

    # ------------------------------------------------------------------ time
    def n_insns(self, start, end):
        key = (start, end)
        n = self._len_cache.get(key)
        if n is None:
            n, a = 0, start
            while a < end:
                a += thumb_len(self.flash[a] | (self.flash[a + 1] << 8))
                n += 1
            self._len_cache[key] = n
        return n

    def now(self):
        """Core clock of the instruction being executed (exact inside a chunk), or of the
        event being processed (its own clock, also when processed a few clocks late)."""
        if self.chunk_end is None:
            return self.cycles if self.ev_now is None else self.ev_now
        pc = self.mu.reg_read(UC_ARM_REG_PC)
        done = self.chunk_done + (self.n_insns(self.blk_start, pc)
                                  if self.blk_start <= pc <= self.blk_end else self.blk_n)
        return self.chunk_cycles + done

    def schedule(self, cycle, callback):
        self.seq += 1
        heapq.heappush(self.events, (cycle, self.seq, callback))
        if self.chunk_end is not None and cycle < self.chunk_end:
            self.stop_request = True

    def set_line(self, irq, level):
        """A peripheral's interrupt request (level); a rising request pends the IRQ."""
        old = self.lines.get(irq, False)
        self.lines[irq] = level
        if level and not old:
            self._pend(irq)

    def _pend(self, irq):
        if not self.nvic_pend[irq // 32] & (1 << (irq % 32)):
            self.nvic_pend[irq // 32] |= 1 << (irq % 32)
            self.irq_wait.setdefault(irq, self.now())
        if self.chunk_end is not None and self._deliverable() is not None:
            self.stop_request = True

    # ------------------------------------------------------------------ NVIC
    def prio(self, irq):
        return self.nvic_prio[irq] >> (8 - PRIO_BITS)

    def exec_prio(self):
        p = 256
        for irq, *_ in self.active:
            p = min(p, self.prio(irq))
        if self.mu.reg_read(UC_ARM_REG_PRIMASK) & 1:
            p = min(p, 0)
        return p

    def _pending_enabled(self):
        out = []
        for w in range(4):
            m = self.nvic_pend[w] & self.nvic_en[w]
            b = 0
            while m:
                if m & 1:
                    out.append(32 * w + b)
                m >>= 1
                b += 1
        return out

    def _deliverable(self, base_prio=None):
        p = self.exec_prio() if base_prio is None else base_prio
        best = None
        for irq in self._pending_enabled():
            if irq in [a[0] for a in self.active]:
                continue
            if self.prio(irq) < p and (best is None or self.prio(irq) < self.prio(best)):
                best = irq
        return best

    def nvic_read(self, addr):
        if NVIC_ISER <= addr < NVIC_ISER + 16:
            return self.nvic_en[(addr - NVIC_ISER) // 4]
        if NVIC_ICER <= addr < NVIC_ICER + 16:
            return self.nvic_en[(addr - NVIC_ICER) // 4]
        if NVIC_ISPR <= addr < NVIC_ISPR + 16:
            return self.nvic_pend[(addr - NVIC_ISPR) // 4]
        if NVIC_ICPR <= addr < NVIC_ICPR + 16:
            return self.nvic_pend[(addr - NVIC_ICPR) // 4]
        if NVIC_IABR <= addr < NVIC_IABR + 16:
            w = (addr - NVIC_IABR) // 4
            return sum(1 << (a[0] % 32) for a in self.active if a[0] // 32 == w)
        if NVIC_IPR <= addr < NVIC_IPR + 4 * ((N_IRQ + 3) // 4):
            i = addr - NVIC_IPR
            return sum(self.nvic_prio[i + k] << (8 * k) for k in range(4) if i + k <= N_IRQ)
        if addr == SCB_CPACR:
            return self.cpacr
        raise Stop("unknown PPB register")

    def nvic_write(self, addr, v):
        if NVIC_ISER <= addr < NVIC_ISER + 16:
            self.nvic_en[(addr - NVIC_ISER) // 4] |= v
        elif NVIC_ICER <= addr < NVIC_ICER + 16:
            self.nvic_en[(addr - NVIC_ICER) // 4] &= ~v
        elif NVIC_ISPR <= addr < NVIC_ISPR + 16:
            self.nvic_pend[(addr - NVIC_ISPR) // 4] |= v
        elif NVIC_ICPR <= addr < NVIC_ICPR + 16:
            self.nvic_pend[(addr - NVIC_ICPR) // 4] &= ~v
        elif NVIC_IPR <= addr < NVIC_IPR + 4 * ((N_IRQ + 3) // 4):
            i = addr - NVIC_IPR
            for k in range(4):
                if i + k <= N_IRQ:
                    # only the upper PRIO_BITS bits of each byte are implemented
                    self.nvic_prio[i + k] = (v >> (8 * k)) & 0xFF & (0xFF << (8 - PRIO_BITS)) & 0xFF
        elif addr == SCB_CPACR:
            self.cpacr = v & 0x00F00000
        else:
            raise Stop("unknown PPB register")
        # a level still asserted re-pends an interrupt whose pending bit was cleared
        for irq, lvl in self.lines.items():
            if lvl and irq not in [a[0] for a in self.active]:
                self.nvic_pend[irq // 32] |= 1 << (irq % 32)
        if self._deliverable() is not None:
            self.stop_request = True

    # ------------------------------------------------------------------ hooks
    def _fail(self, what, addr):
        if self.stopped is None:
            self.stopped = "%s at 0x%08X (pc 0x%08X)" % (what, addr, self.mu.reg_read(UC_ARM_REG_PC))
        self.mu.emu_stop()

    def _on_block(self, uc, addr, size, user):
        self.chunk_done += self.blk_n
        self.blk_start = addr
        self.blk_end = addr + size
        self.blk_n = self.n_insns(addr, addr + size)

    def _on_intr(self, uc, intno, user):
        if intno == EXCP_EXCEPTION_EXIT:
            self.reason = "exc_return"
        else:
            self.reason = "exception %d" % intno
        uc.emu_stop()

    def _on_cpsie(self, uc, addr, size, user):
        if self.skip_cpsie:
            self.skip_cpsie = False
            return
        self.reason = "cpsie"
        uc.emu_stop()

    def _on_invalid(self, uc, access, addr, size, value, user):
        self._fail("access outside the memory map", addr)
        return False

    def _on_sram_read(self, uc, access, addr, size, value, user):
        w = (addr - SRAM[0]) // 4
        if not self.written[w] or (addr % 4 + size > 4 and not self.written[w + 1]):
            self._fail("SRAM read before its first 32-bit write (ECC)", addr)

    def _on_read(self, uc, access, addr, size, value, user):
        if size != 4 or addr % 4:
            self._fail("%d-byte access at an unaligned or partial peripheral address" % size, addr)
            return
        try:
            if addr >= PPB[0]:
                v = self.nvic_read(addr)
            else:
                ent = self.devices.get(addr)
                if ent is None:
                    raise Stop("read of a register the models do not know")
                v = ent[0].read(ent[1])
        except Stop as e:
            self._fail(str(e), addr)
            return
        uc.mem_write(addr, struct.pack("<I", v & 0xFFFFFFFF))

    def _on_write(self, uc, access, addr, size, value, user):
        if SRAM[0] <= addr < SRAM[0] + SRAM[1]:
            w = (addr - SRAM[0]) // 4
            if size == 4 and addr % 4 == 0:
                self.written[w] = 1
            elif not self.written[w] or (addr % 4 + size > 4 and not self.written[w + 1]):
                self._fail("partial write of SRAM before its first 32-bit write (ECC)", addr)
            return
        if FLASH[0] <= addr < FLASH[0] + FLASH[1]:
            self._fail("write to program flash", addr)
            return
        pc = uc.reg_read(UC_ARM_REG_PC)
        depth = len(self.active)
        key = self.replay.pop(depth, None)
        if key is not None and key == (pc, addr, value, uc.reg_read(UC_ARM_REG_SP)):
            return                          # the store Unicorn executes again: applied once
        if size != 4 or addr % 4:
            self._fail("%d-byte access at an unaligned or partial peripheral address" % size, addr)
            return
        value &= 0xFFFFFFFF
        try:
            if addr >= PPB[0]:
                self.nvic_write(addr, value)
            else:
                ent = self.devices.get(addr)
                if ent is None:
                    raise Stop("write to a register the models do not know")
                ent[0].write(ent[1], value)
        except Stop as e:
            self._fail(str(e), addr)
            return
        if self.stop_request and self.chunk_end is not None:
            # the context at this depth resumes with this store (after any handler)
            self.replay[depth] = (pc, addr, value, uc.reg_read(UC_ARM_REG_SP))
            self.reason = "write"
            uc.emu_stop()

    # ------------------------------------------------------------------ exceptions
    def _push(self, addr, v):
        if not (SRAM[0] <= addr < SRAM[0] + SRAM[1]):
            raise Stop("exception frame outside SRAM (stack overflow)")
        self.mu.mem_write(addr, struct.pack("<I", v & 0xFFFFFFFF))
        self.written[(addr - SRAM[0]) // 4] = 1

    def _pop(self, addr):
        if not (SRAM[0] <= addr < SRAM[0] + SRAM[1]) or not self.written[(addr - SRAM[0]) // 4]:
            raise Stop("exception frame read outside initialised SRAM")
        return struct.unpack("<I", self.mu.mem_read(addr, 4))[0]

    def _vector(self, irq):
        return struct.unpack("<I", bytes(self.flash[4 * (16 + irq):4 * (16 + irq) + 4]))[0]

    def _enter(self, irq, tail=None):
        mu = self.mu
        if mu.reg_read(UC_ARM_REG_CONTROL) & 0x4:
            raise Stop("CONTROL.FPCA set: an FP instruction ran, the extended frame is not modelled")
        if tail is None:
            sp = mu.reg_read(UC_ARM_REG_SP)
            xpsr = mu.reg_read(UC_ARM_REG_XPSR) | (1 << 24)
            pad = 4 if (sp - 32) % 8 else 0
            frame = sp - 32 - pad
            if pad:
                xpsr |= 1 << 9
            else:
                xpsr &= ~(1 << 9)
            regs = [mu.reg_read(r) for r in (UC_ARM_REG_R0, UC_ARM_REG_R1, UC_ARM_REG_R2,
                                             UC_ARM_REG_R3, UC_ARM_REG_R12, UC_ARM_REG_LR)]
            for k, v in enumerate(regs + [self.pc & ~1, xpsr]):
                self._push(frame + 4 * k, v)
            mu.reg_write(UC_ARM_REG_SP, frame)
            exc_return = 0xFFFFFFF1 if self.active else 0xFFFFFFF9
            if self.active:
                self.preemptions += 1
                pair = (self.active[-1][0], irq)
                self.preempt_pairs[pair] = self.preempt_pairs.get(pair, 0) + 1
            self.cycles += ENTRY_CYCLES
        else:
            exc_return = tail
            self.tailchains += 1
            self.cycles += TAILCHAIN_CYCLES
        self.nvic_pend[irq // 32] &= ~(1 << (irq % 32))
        waited = self.irq_wait.pop(irq, self.cycles)
        if self.active:
            self.active[-1][3] += self.insns - self.active[-1][2]
        self.active.append([irq, exc_return, self.insns, 0, self.cycles, waited,
                            ENTRY_CYCLES if tail is None else TAILCHAIN_CYCLES])
        mu.reg_write(UC_ARM_REG_LR, exc_return)
        mu.reg_write(UC_ARM_REG_IPSR, 16 + irq)
        self.pc = self._vector(irq) | 1
        if self.log_isr:
            self.isr_log.append((self.cycles, irq, "enter"))

    def _return(self):
        mu = self.mu
        pc = mu.reg_read(UC_ARM_REG_PC) | 1
        if not self.active:
            raise Stop("exception return in thread mode")
        irq, exc_return, t_insn, own, t_cyc, waited, entry = self.active.pop()
        if self.active:
            self.active[-1][2] = self.insns      # the pre-empted handler resumes counting
        if pc != exc_return:
            raise Stop("EXC_RETURN 0x%08X not the one of the entry (0x%08X)" % (pc, exc_return))
        own += self.insns - t_insn
        if self.log_isr:
            self.isr_log.append((self.cycles, irq, "return"))
        if self.lines.get(irq, False):
            self._pend(irq)                  # still requesting: pending again
        # tail chain: a pending interrupt that may pre-empt the context returned to
        base = 256
        for a in self.active:
            base = min(base, self.prio(a[0]))
        if mu.reg_read(UC_ARM_REG_PRIMASK) & 1:
            base = min(base, 0)
        nxt = self._deliverable(base)
        # own instructions; clocks with the entry (12, or 6 when tail-chained) and the
        # return (10, none when it tail-chains); latency; the request's clock
        clocks = own + entry + (RETURN_CYCLES if nxt is None else 0)
        self.irq_stats.setdefault(irq, []).append((own, clocks, t_cyc - waited, waited))
        self.handler_clocks += clocks
        if nxt is not None:
            self._enter(nxt, tail=exc_return)
            return
        sp = mu.reg_read(UC_ARM_REG_SP)
        vals = [self._pop(sp + 4 * k) for k in range(8)]
        for r, v in zip((UC_ARM_REG_R0, UC_ARM_REG_R1, UC_ARM_REG_R2, UC_ARM_REG_R3,
                         UC_ARM_REG_R12, UC_ARM_REG_LR), vals[:6]):
            mu.reg_write(r, v)
        xpsr = vals[7]
        if not xpsr & (1 << 24):
            raise Stop("stacked xPSR without the Thumb bit (INVSTATE)")
        mu.reg_write(UC_ARM_REG_SP, sp + 32 + (4 if xpsr & (1 << 9) else 0))
        mu.reg_write(UC_ARM_REG_XPSR, (xpsr & 0xF80F0000) | (1 << 24))
        mu.reg_write(UC_ARM_REG_IPSR, 16 + self.active[-1][0] if self.active else 0)
        self.pc = vals[6] | 1
        self.cycles += RETURN_CYCLES
        if self.active:
            self.active[-1][2] = self.insns

    # ------------------------------------------------------------------ run
    def _process_events(self):
        while self.events and self.events[0][0] <= self.cycles:
            t, _, cb = heapq.heappop(self.events)
            self.ev_now = t
            try:
                cb(t)
            finally:
                self.ev_now = None

    def _run_chunk(self, n):
        mu = self.mu
        self.reason = None
        self.stop_request = False
        self.chunk_cycles = self.cycles
        self.chunk_end = self.cycles + n
        self.chunk_done = 0
        self.blk_start = self.blk_end = self.blk_n = 0
        try:
            mu.emu_start(self.pc, 0xFFFFFFFF, count=n)
        except UcError as e:
            self._fail("emulation error (%s)" % e, mu.reg_read(UC_ARM_REG_PC))
        pc = mu.reg_read(UC_ARM_REG_PC)
        if self.reason == "exc_return":
            done = self.chunk_done + self.blk_n        # the return branch ends its block
        else:
            # exact, also after count=n ran out: Unicorn's count skips the instructions of
            # an IT block whose condition fails, which take a cycle on the core
            done = self.chunk_done + (self.n_insns(self.blk_start, pc)
                                      if self.blk_start <= pc <= self.blk_end else self.blk_n)
        if self.reason is None and self.stopped is None:
            w = pc - 2
            if (w in self.wfi_addrs and self.blk_start <= w < self.blk_end and
                    self.n_insns(self.blk_start, w) + 1 == self.n_insns(self.blk_start, pc)):
                self.reason = "wfi"                    # Unicorn halts at WFI with PC after it
        self.chunk_end = None
        self.insns += done
        self.cycles += done
        self.pc = pc | 1
        return self.reason

    def _it_active(self):
        x = self.mu.reg_read(UC_ARM_REG_XPSR)
        return bool(x & 0x0600FC00)

    def boot(self):
        """Start from the reset vector (SP and PC from the vector table)."""
        sp, pc = struct.unpack("<II", bytes(self.flash[0:8]))
        self.mu.reg_write(UC_ARM_REG_SP, sp)
        self.pc = pc | 1
        for dev in set(d for d, _ in self.devices.values()):
            dev.start()

    def run_until(self, t_end, max_chunk=1_000_000):
        """Run until core clock t_end (or a stop).  Returns False when the run stopped."""
        while self.stopped is None and self.cycles < t_end:
            try:
                self._process_events()
                irq = self._deliverable()
                if irq is not None and not self._it_active():
                    self.sleeping = False
                    self._enter(irq)
                    continue
                if self.sleeping:
                    if self._pending_enabled():
                        self.sleeping = False          # WFI wakes on any pending interrupt
                        continue
                    nxt = self.events[0][0] if self.events else t_end
                    self.cycles = max(self.cycles, min(nxt, t_end))
                    continue
                nxt = self.events[0][0] if self.events else t_end
                n = max(1, min(nxt, t_end) - self.cycles)
                if irq is not None:
                    n = 1                               # step out of an IT block
                n = min(n, max_chunk)
                reason = self._run_chunk(n)
                if reason == "exc_return":
                    self._return()
                elif reason == "wfi":
                    self.sleeping = True
                elif reason == "cpsie":
                    self.skip_cpsie = True
                    self._run_chunk(1)
                elif reason is not None and reason not in ("write",):
                    self._fail("unexpected CPU %s" % reason, self.mu.reg_read(UC_ARM_REG_PC))
            except Stop as e:
                self._fail(str(e), self.mu.reg_read(UC_ARM_REG_PC))
        return self.stopped is None
