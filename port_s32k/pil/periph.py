"""periph.py -- register-level models of the S32K144 peripherals the qfoc port uses, for
the processor-in-the-loop run (core.py).  Addresses and fields are those of
port_s32k/s32k144_regs.h (S32K1xx Reference Manual Rev. 13); the RM chapter of each
behaviour is named beside it.  Every register not listed here stops the run (core.py).

Common rules:
  - Clock gating (RM chapter "Peripheral Clock Control (PCC)"): an access to a module
    whose PCC[CGC] is 0 ends in a bus error on the part; here it stops the run.  PCC[PCS]
    may change only while CGC is 0 (PCC chapter, PCS field); a change with CGC set stops.
  - Accesses are 32-bit and aligned (the port's one accessor, s32k_reg()); anything else
    stops the run (core.py).

Simplifications (stated; not RM behaviour):
  - Clocks: the frequencies the models count with are computed from the registers the
    image writes (SCG.clock_tree: the SOSC crystal, 8 MHz, is the board's and assumed;
    SPLLCFG PREDIV and MULT, SPLLDIV, SOSCDIV, RCCR DIVCORE, DIVBUS, DIVSLOW) and the PCC
    PCS selections, each peripheral on the clock the S32K1xx RM (Rev. 13, chapter "Clock
    distribution", the peripheral clocking table; corroborated by NXP's S32K1 SDK, whose
    clock names group PDB0/PDB1 with the SYS_CLK modules, the FTMs with the DIV1 and the
    ADCs, LPIT and LPUART with the DIV2 functional clocks, and whose FTM driver counts
    SC[CLKS] = 01 at CORE_CLK) gives it: FTM3 with SC[CLKS] = 01 and the PDBs on SYS_CLK,
    the ADCs on the DIV2 output of their PCS source (ALTCLK1, ADICLK = 00) divided by ADIV,
    LPIT0 and LPUART1 on the DIV2 output of their PCS source, the CAN engine with
    CTRL1[CLKSRC] = 0 on SOSCDIV2, WDOG on the 128 kHz LPO.  A clock that is off, a PCS
    source whose dividers are not modelled (SIRC, FIRC), a frequency that is not a whole
    fraction of the 80 MHz time base, or a core clock other than 80 MHz at the switch of
    RCCR stops the run.  SCG valid flags follow their enables at once (no oscillator or PLL
    start-up time); the clock switch of RCCR shows in CSR at once; the core clock is 80 MHz
    from reset (core.py; the FIRC 48 MHz phase before the switch is not distinguished).
  - FTM3: the counter in up-down (CPWMS = 1) and up counting (CPWMS = 0).  The six
    channel outputs are computed from the registers at each reload point for the period
    that starts there (FTM.pin_on: the centre-aligned PWM of each even channel, COMBINE
    [COMPm] complement or an own PWM for the odd channel, COMBINE[DTENm] with DEADTIME
    [DTPS, DTVAL, DTVALEX], POL, OUTMASK, PWMENn, the fault flag with FAULTENm; combine
    mode and a non-zero CNTIN are not modelled and stop); the gate signals are turned into
    the plant's inverter (periph.bridge: the three compare values, the dead time, the
    enable) or stop the run on a pattern the plant's model does not have (a shoot-through,
    a floating leg, an asymmetric or per-phase dead time).  PAIRnDEADTIME (0xA0 ..) is not
    modelled (an access stops: the port writes DEADTIME only).  The outputs, the output
    mask, the fault flag and the gate enable are sampled at each reload point, so that a
    change within a period takes effect at the next one (the part applies OUTMASK at once:
    FTM chapter, OUTMASK, with SYNCONF[SWOM] = 0; and the fault within the input filter).  The write-protected set modelled is SC[CLKS, PS,
    CPWMS], MODE (except WPDIS), COMBINE, DEADTIME, POL, FLTCTRL, FLTPOL, FILTER,
    SYNCONF, as recalled from the FTM chapter's "Write protection" list and not checked
    against RM Rev. 13 here; after setting WPEN the port writes none of them (SC only with
    the same CLKS, PS, CPWMS), so the run does not depend on the exact list.  A write that
    would change a protected field while FMS[WPEN] = 1 stops the run (the part ignores
    it).
    Whether the hardware clears PWMLOAD[LDOK] after the loading is not modelled: LDOK
    stays set until software writes it 0 (the port sets it in every period, so the values
    it loads do not depend on this).
  - ADC: conversion time = (SMPLTS + 1) sample clocks + ADC_COMPARE_CLOCKS (20) ADC
    clocks (an ASSUMPTION for a 12-bit conversion: the RM's conversion-time formula was
    not found in the sources at hand, so the 20 compare clocks stay the port's
    assumption); the input is sampled at the conversion's start; calibration completes
    CAL_CYCLES after CAL is set (its duration on the part is longer).
  - PDB: channel 0 only; pre-trigger delays counted on SYS_CLK with PRESCALER and MULT.
  - LPUART: 8N1 frames at the configured bit time, one data buffer and the shift
    register (no FIFO), no echo of the own transmission on the receive line (the LIN
    transceiver's loop-back is not modelled), no noise or framing errors.
  - FlexCAN: transmission of MB0 takes CAN_FRAME_BITS bit times at the configured rate
    (no stuffing, always acknowledged); the frame is recorded.
  - WDOG: counts the LPO while enabled; a refresh (0xB480A602 written to CNT) restarts
    it; the unlock is valid until the CS write (the 128-bus-clock window after the
    unlock is not timed); a timeout resets the part (core.Core.reset).

Requirements: REQ-PIL-001, REQ-PIL-002, REQ-PIL-007, REQ-PIL-008, REQ-PIL-009 (the ADC's
input taken at the conversion's start: run.PIL.analog converts the plant at that instant)
(specs/requirements/pil.md).
"""
from core import Stop, CORE_HZ

PCC_BASE = 0x40065000
CGC = 1 << 30
PCS_SHIFT = 24


def bits(v, lo, n):
    return (v >> lo) & ((1 << n) - 1)


def clock_hz(core, name):
    """The frequency of a clock of the tree (SCG.clock_tree), stopping when it is off."""
    f = core.scg_dev.clock_tree().get(name)
    if not f:
        raise Stop("%s is off (SCG registers)" % name)
    return f


def pcc_hz(core, pcc_off, div, who):
    """The functional clock PCC[PCS] selects for a peripheral, its DIV1 or DIV2 output
    (RM chapter PCC; which one by the peripheral: S32K1xx RM, chapter "Clock distribution",
    the peripheral clocking table)."""
    pcs = core.pcc_dev.pcs(pcc_off)
    src = PCS_SOURCES.get(pcs)
    if src is None:
        raise Stop("%s: PCC[PCS] = %d selects no modelled clock" % (who, pcs))
    if src in ("SIRC", "FIRC"):
        raise Stop("%s: %sDIV%d is not modelled" % (who, src, div))
    return clock_hz(core, "%sDIV%d" % (src, div))


def cycles_per(core, hz, who):
    """Core clocks (the 80 MHz time base) per clock of `hz`: an integer, or the run stops."""
    if CORE_HZ % hz:
        raise Stop("%s: clock %d Hz is not a whole fraction of the %d Hz time base" % (who, hz, CORE_HZ))
    return CORE_HZ // hz


class Periph:
    """A module at `base` with a table {offset: (name, reset value)}; read-only names in
    `ro`.  Subclasses define rd_NAME / wr_NAME for behaviour."""
    name = "?"
    base = 0
    pcc = None            # offset of the module's PCC register, or None (not gated)
    table = {}
    ro = ()

    def __init__(self):
        self.core = None
        self.regs = {off: n for off, (n, _) in self.table.items()}
        self.reset()

    def reset(self):
        self.r = {n: rv for (n, rv) in self.table.values()}
        self.gen = 0

    def start(self):
        pass

    def now(self):
        return self.core.now()

    def gated(self):
        return self.pcc is not None and not (self.core.pcc_dev.r.get(self.pcc, 0) & CGC)

    def read(self, off):
        if self.gated():
            raise Stop("%s read with its clock gated (PCC CGC = 0)" % self.name)
        n = self.regs[off]
        f = getattr(self, "rd_" + n, None)
        return f() if f else self.r[n]

    def write(self, off, v):
        if self.gated():
            raise Stop("%s write with its clock gated (PCC CGC = 0)" % self.name)
        n = self.regs[off]
        if n in self.ro:
            raise Stop("write to the read-only register %s_%s" % (self.name, n))
        f = getattr(self, "wr_" + n, None)
        if f:
            f(v)
        else:
            self.r[n] = v

    def at(self, cycle, cb):
        """Schedule cb(t) at core clock `cycle`, cancelled by the next self.gen += 1."""
        g = self.gen
        self.core.schedule(cycle, lambda t: cb(t) if g == self.gen else None)


# ---------------------------------------------------------------------- system
class PCC(Periph):
    """RM chapter PCC: PR (bit 31, read-only 1: present), CGC (bit 30), PCS (26:24)."""
    name = "PCC"
    base = PCC_BASE
    table = {o: ("R%03X" % o, 1 << 31) for o in (0x90, 0x98, 0x9C, 0xC4, 0xD8, 0xDC, 0xEC, 0x124,
                                                  0x128, 0x12C, 0x130, 0x134, 0x1AC)}

    def write(self, off, v):
        old = self.r[off] if off in self.r else 0
        if old & CGC and bits(v, PCS_SHIFT, 3) != bits(old, PCS_SHIFT, 3):
            raise Stop("PCC 0x%03X: PCS changed while CGC = 1" % off)
        self.r[off] = (v & 0x47000000) | (1 << 31)

    def read(self, off):
        return self.r[off]

    def reset(self):
        self.r = {o: 1 << 31 for o in self.table}
        self.gen = 0

    def pcs(self, off):
        return bits(self.r[off], PCS_SHIFT, 3)


SOSC_HZ = 8_000_000          # the board: an 8 MHz crystal on EXTAL/XTAL (port_s32k/README.md)
SIRC_HZ = 8_000_000          # RM SCG chapter: the slow IRC, 8 MHz range
FIRC_HZ = 48_000_000         # RM SCG chapter: the fast IRC, 48 MHz (the clock at reset)
# PCC[PCS] (RM chapter PCC, PCS field): the functional clock of a peripheral with one;
# which divider output (DIV1 or DIV2) depends on the peripheral (pcc_hz() and its users)
PCS_SOURCES = {1: "SOSC", 2: "SIRC", 3: "FIRC", 6: "SPLL"}


def scg_div(field):
    """SCG xDIV1 / xDIV2 (RM SCG chapter, SOSCDIV and SPLLDIV): 0 = output disabled, n =
    divide by 2^(n - 1) (1, 2, 4, .. 64); None when disabled."""
    return None if field == 0 else 1 << (field - 1)


class SCG(Periph):
    """RM chapter SCG: SOSCCSR/SPLLCSR[VLD] (bit 24) with the enable (bit 0); CSR shows
    RCCR; SOSCCFG/SPLLCFG written only with the source disabled.

    The clock tree (clock_tree(): Hz of every clock the models count with), from the
    registers the image writes, per the RM's SCG chapter (S32K1xx RM Rev. 13):
      SOSC_CLK   SOSC_HZ (8 MHz crystal: the board's, an assumption) with SOSCCSR[SOSCEN]
                 and SOSCCFG[EREFS] = 1 (crystal);
      VCO_CLK    SPLL source (SOSC_CLK) / (SPLLCFG[PREDIV] + 1) x (SPLLCFG[MULT] + 16);
                 SPLL_CLK = VCO_CLK / 2 (SPLLCFG description; NXP's S32K144 cookbook
                 example: "SPLL_CLK = 8MHz / 1 * 20 / 2 = 80 MHz").  The VCO's range (180 ..
                 320 MHz by the port's statement, s32k144_port.h) is not checked here;
      xDIVn_CLK  source / scg_div(xDIVn) (SOSCDIV, SPLLDIV);
      CORE_CLK = SYS_CLK  the RCCR[SCS] source / (DIVCORE + 1); BUS_CLK = CORE_CLK /
                 (DIVBUS + 1); FLASH_CLK = CORE_CLK / (DIVSLOW + 1) (RCCR description,
                 "divide by n + 1"; the dividers in series as in the RM's clocking
                 diagram);
    SIRC and FIRC dividers are not modelled (their registers stop the run).  The time base
    of core.py is 80 MHz: a switch of RCCR to another CORE_CLK stops the run; until the
    image writes RCCR, CORE_CLK = SYS_CLK is taken as that time base's 80 MHz (the FIRC
    phase after reset is not distinguished, core.py)."""
    name = "SCG"
    base = 0x40064000
    table = {0x010: ("CSR", 0x03010001), 0x014: ("RCCR", 0x03010001), 0x100: ("SOSCCSR", 0),
             0x104: ("SOSCDIV", 0), 0x108: ("SOSCCFG", 0x10), 0x600: ("SPLLCSR", 0),
             0x604: ("SPLLDIV", 0), 0x608: ("SPLLCFG", 0)}
    ro = ("CSR",)

    def rd_CSR(self):
        return self.r["RCCR"]

    def reset(self):
        super().reset()
        self._tree = None
        self.rccr_written = False

    def write(self, off, v):
        self._tree = None
        super().write(off, v)

    def wr_RCCR(self, v):
        self.r["RCCR"] = v
        self.rccr_written = True
        self._tree = None
        core = self.clock_tree()["CORE"]
        if core != CORE_HZ:
            raise Stop("SCG_RCCR: CORE_CLK %s Hz from the registers; the time base is %d Hz"
                       % (core, CORE_HZ))

    def clock_tree(self):
        """{clock name: Hz or None (off)} from the registers (the class docstring)."""
        if self._tree is not None:
            return self._tree
        r = self.r
        t = {"SIRC": SIRC_HZ, "FIRC": FIRC_HZ}
        sosc = SOSC_HZ if (r["SOSCCSR"] & 1 and r["SOSCCFG"] & 0x4) else None
        t["SOSC"] = sosc
        spll = None
        if r["SPLLCSR"] & 1 and sosc is not None:
            prediv, mult = bits(r["SPLLCFG"], 8, 3), bits(r["SPLLCFG"], 16, 5)
            vco = sosc * (mult + 16) // (prediv + 1)
            t["VCO"] = vco
            spll = vco // 2
        t["SPLL"] = spll
        for src, reg in (("SOSC", "SOSCDIV"), ("SPLL", "SPLLDIV")):
            for n, lo in ((1, 0), (2, 8)):
                d = scg_div(bits(r[reg], lo, 3))
                t["%sDIV%d" % (src, n)] = t[src] // d if (t[src] is not None and d) else None
        scs = bits(r["RCCR"], 24, 4)
        src = {1: "SOSC", 2: "SIRC", 3: "FIRC", 6: "SPLL"}.get(scs)
        f = t.get(src) if src else None
        core = f // (bits(r["RCCR"], 16, 4) + 1) if f else None
        if not self.rccr_written:
            core = CORE_HZ          # before the switch: the time base's 80 MHz (core.py)
        t["CORE"] = t["SYS"] = core
        t["BUS"] = core // (bits(r["RCCR"], 4, 4) + 1) if core else None
        t["FLASH"] = core // (bits(r["RCCR"], 0, 4) + 1) if core else None
        self._tree = t
        return t

    def rd_SOSCCSR(self):
        v = self.r["SOSCCSR"]
        return (v | (1 << 24)) if v & 1 else (v & ~(1 << 24))

    def rd_SPLLCSR(self):
        v = self.r["SPLLCSR"]
        return (v | (1 << 24)) if (v & 1 and self.r["SOSCCSR"] & 1) else (v & ~(1 << 24))

    def wr_SOSCCFG(self, v):
        if self.r["SOSCCSR"] & 1:
            raise Stop("SCG_SOSCCFG written with the SOSC enabled")
        self.r["SOSCCFG"] = v

    def wr_SPLLCFG(self, v):
        if self.r["SPLLCSR"] & 1:
            raise Stop("SCG_SPLLCFG written with the SPLL enabled")
        self.r["SPLLCFG"] = v


class SMC(Periph):
    """RM chapter SMC: PMPROT is write-once after reset; PMSTAT 0x01 = RUN."""
    name = "SMC"
    base = 0x4007E000
    table = {0x08: ("PMPROT", 0), 0x0C: ("PMCTRL", 0), 0x14: ("PMSTAT", 0x01)}
    ro = ("PMSTAT",)

    def reset(self):
        super().reset()
        self.pmprot_written = False

    def wr_PMPROT(self, v):
        if self.pmprot_written:
            return                      # write-once: later writes are ignored
        self.pmprot_written = True
        self.r["PMPROT"] = v & 0xA0

    def wr_PMCTRL(self, v):
        if bits(v, 5, 2) != 0:
            raise Stop("SMC_PMCTRL: a run mode other than RUN is not modelled")
        self.r["PMCTRL"] = v


class SIM(Periph):
    name = "SIM"
    base = 0x40048000
    table = {0x18: ("ADCOPT", 0)}


class PORT(Periph):
    """RM chapter PORT: PCRn (MUX 10:8, PE, PS), plain read/write here."""
    def __init__(self, letter, base, pcc):
        self.name = "PORT" + letter
        self.base = base
        self.pcc = pcc
        self.table = {4 * n: ("PCR%d" % n, 0) for n in range(32)}
        super().__init__()


class GPIOD(Periph):
    """RM chapter GPIO: PDOR, PSOR/PCOR/PTOR (write-only, read 0), PDIR (read-only),
    PDDR.  The gate-driver enable is PTD5 driven high (PDDR bit set, PCR MUX = 1)."""
    name = "GPIOD"
    base = 0x400FF0C0
    table = {0x0: ("PDOR", 0), 0x4: ("PSOR", 0), 0x8: ("PCOR", 0), 0xC: ("PTOR", 0),
             0x10: ("PDIR", 0), 0x14: ("PDDR", 0)}
    ro = ("PDIR",)

    def __init__(self, port):
        self.port = port
        super().__init__()

    def rd_PSOR(self):
        return 0

    rd_PCOR = rd_PTOR = rd_PSOR

    def rd_PDIR(self):
        return self.r["PDOR"] & self.r["PDDR"]

    def wr_PSOR(self, v):
        self.r["PDOR"] |= v

    def wr_PCOR(self, v):
        self.r["PDOR"] &= ~v

    def wr_PTOR(self, v):
        self.r["PDOR"] ^= v

    def pin_high(self, n):
        mux = bits(self.port.r["PCR%d" % n], 8, 3)
        return bool(self.r["PDDR"] & self.r["PDOR"] & (1 << n)) and mux == 1


class TRGMUX(Periph):
    """RM chapter TRGMUX: TRGMUX_PDB0/PDB1 SEL0 (6:0), LK (bit 31: no write until reset)."""
    name = "TRGMUX"
    base = 0x40063000
    table = {0x38: ("PDB0", 0), 0x3C: ("PDB1", 0)}

    def write(self, off, v):
        n = self.regs[off]
        if self.r[n] & (1 << 31):
            raise Stop("TRGMUX_%s written while locked (LK)" % n)
        self.r[n] = v & 0x8000007F


class WDOG(Periph):
    """RM chapter WDOG: CS (EN 7, UPDATE 5, CLK 9:8, RCS 10, ULK 11, CMD32EN 13), CNT
    (unlock 0xD928C520, refresh 0xB480A602), TOVAL, WIN.  Reset: enabled, LPO,
    TOVAL 0x400.  A timeout resets the part."""
    name = "WDOG"
    base = 0x40052000
    table = {0x0: ("CS", 0x2980), 0x4: ("CNT", 0), 0x8: ("TOVAL", 0x400), 0xC: ("WIN", 0)}
    LPO_CYCLES = CORE_HZ // 128_000

    def reset(self):
        super().reset()
        self.unlocked = True           # CS reset value 0x2980: ULK = 1 (configurable after reset)
        self.refreshes = 0
        self.t_start = 0

    def start(self):
        self._arm(self.now())

    def _arm(self, t):
        self.gen += 1
        self.t_start = t
        if self.r["CS"] & 0x80:
            self.at(t + self.r["TOVAL"] * self.LPO_CYCLES, self._timeout)

    def _timeout(self, t):
        self.core.wdog_timeouts = getattr(self.core, "wdog_timeouts", 0) + 1
        self.core.reset()

    def rd_CS(self):
        return (self.r["CS"] & ~0x800) | (0x800 if self.unlocked else 0)

    def rd_CNT(self):
        return (self.now() - self.t_start) // self.LPO_CYCLES & 0xFFFF

    def wr_CNT(self, v):
        if v == 0xD928C520:
            if not self.r["CS"] & 0x20 and not self.unlocked:
                raise Stop("WDOG unlock with CS[UPDATE] = 0 (the part resets)")
            self.unlocked = True
        elif v == 0xB480A602:
            self.refreshes += 1
            self._arm(self.now())
        else:
            raise Stop("WDOG_CNT: neither the unlock nor the refresh key (the part resets)")

    def _cfg(self, n, v):
        if not self.unlocked:
            raise Stop("WDOG_%s written while locked" % n)
        self.r[n] = v

    def wr_TOVAL(self, v):
        self._cfg("TOVAL", v & 0xFFFF)

    def wr_WIN(self, v):
        self._cfg("WIN", v & 0xFFFF)

    def wr_CS(self, v):
        self._cfg("CS", (v & 0xF3FF) | 0x400)            # RCS: reconfiguration success
        self.unlocked = False
        if bits(v, 8, 2) != 1 and v & 0x80:
            raise Stop("WDOG clock other than the LPO is not modelled")
        self._arm(self.now())


# ---------------------------------------------------------------------- FTM3
class FTM(Periph):
    """RM chapter FlexTimer Module (FTM3)."""
    name = "FTM3"
    base = 0x40026000
    pcc = 0x98
    IRQ = 122
    table = dict([(0x00, ("SC", 0)), (0x04, ("CNT", 0)), (0x08, ("MOD", 0))] +
                 [(0x0C + 8 * n, ("C%dSC" % n, 0)) for n in range(8)] +
                 [(0x10 + 8 * n, ("C%dV" % n, 0)) for n in range(8)] +
                 [(0x4C, ("CNTIN", 0)), (0x50, ("STATUS", 0)), (0x54, ("MODE", 0x4)),
                  (0x58, ("SYNC", 0)), (0x5C, ("OUTINIT", 0)), (0x60, ("OUTMASK", 0)),
                  (0x64, ("COMBINE", 0)), (0x68, ("DEADTIME", 0)), (0x6C, ("EXTTRIG", 0)),
                  (0x70, ("POL", 0)), (0x74, ("FMS", 0)), (0x78, ("FILTER", 0)),
                  (0x7C, ("FLTCTRL", 0)), (0x88, ("FLTPOL", 0)), (0x8C, ("SYNCONF", 0)),
                  (0x98, ("PWMLOAD", 0))])
    on_reload = None                           # callback(t): the plant's period
    on_init_trigger = None                     # callback(t): TRGMUX input 28
    PROTECTED = ("MODE", "COMBINE", "DEADTIME", "POL", "FLTCTRL", "FLTPOL", "FILTER", "SYNCONF")

    def reset(self):
        super().reset()
        self.buf = {"MOD": 0, "CNTIN": 0}
        self.buf.update({"C%dV" % n: 0 for n in range(8)})
        self.running = False
        self.armed = {"SC": 0, "FMS": 0}      # flags read as 1 (cleared by writing 0 after)
        self.t_ref, self.cnt_ref, self.dir = 0, 0, 1
        self.fault_in = False                  # FTM3_FLT0 asserted (over-current)
        self.reloads = 0
        self.ldok_loads = 0
        self.last_ldok_write = None
        self.ldok_writes = []                  # LDOK writes since the last reload point

    # protection: FMS[WPEN] (RM FTM chapter, "Write protection")
    def wpen(self):
        return bool(self.r["FMS"] & 0x40)

    def write(self, off, v):
        n = self.regs[off]
        if self.wpen() and n in self.PROTECTED and n != "MODE" and v != self.r[n]:
            raise Stop("FTM3_%s changed while write-protected (FMS[WPEN] = 1)" % n)
        super().write(off, v)

    # counter
    def tick(self):
        """Core clocks per counter clock: SC[CLKS] = 01 selects the FTM input clock, SYS_CLK
        on the S32K1xx (RM FTM chapter, SC[CLKS], and the chip's FTM clocking: the
        synchronous clock; NXP's S32K1 SDK counts CLKS = 01 at CORE_CLK = SYS_CLK); 11 the
        external clock, the DIV1 output PCC[PCS] selects; 10 (the fixed-frequency RTC clock)
        stops.  Then the prescaler SC[PS] (1 << PS)."""
        clks, ps = bits(self.r["SC"], 3, 2), bits(self.r["SC"], 0, 3)
        if clks == 1:
            hz = clock_hz(self.core, "SYS")
        elif clks == 3:
            hz = pcc_hz(self.core, self.pcc, 1, "FTM3 external clock")
        else:
            raise Stop("FTM3 clock source CLKS = %d is not modelled" % clks)
        return cycles_per(self.core, hz, "FTM3") << ps

    def cpwm(self):
        return bool(self.r["SC"] & 0x20)

    def rd_CNT(self):
        if not self.running:
            return self.cnt_ref
        return self.cnt_ref + self.dir * ((self.now() - self.t_ref) // self.tick())

    def wr_CNT(self, v):
        self.cnt_ref = self.r["CNTIN"]            # any write loads CNTIN (RM, CNT)
        if self.running:
            self._start(self.now())

    def _start(self, t):
        self.gen += 1
        self.t_ref, self.cnt_ref, self.dir = t, self.r["CNTIN"], 1
        self.at(t + (self.r["MOD"] - self.r["CNTIN"]) * self.tick(), self._at_mod)

    def _at_mod(self, t):
        """Counter at MOD: the reload point with SYNC[CNTMAX] (RM FTM, "Reload points");
        TOF in up-down counting (counter MOD -> MOD - 1, RM FTM, "Up-down counting")."""
        self.reloads += 1
        if self.r["SYNC"] & 0x2:
            self._reload(t)
        if self.cpwm():
            self.r["SC"] |= 0x200                      # TOF
            self.t_ref, self.cnt_ref, self.dir = t, self.r["MOD"], -1
            self.at(t + (self.r["MOD"] - self.r["CNTIN"]) * self.tick(), self._at_cntin)
        else:
            self.t_ref, self.cnt_ref, self.dir = t + self.tick(), self.r["CNTIN"], 1
            self.r["SC"] |= 0x200                      # TOF: MOD -> CNTIN (up counting)
            self.at(t + self.tick(), self._at_cntin)
        self._line()
        if self.on_reload:
            self.on_reload(t)

    def _at_cntin(self, t):
        """Counter at CNTIN: the initialization trigger with EXTTRIG[INITTRIGEN]."""
        if self.r["SYNC"] & 0x1:
            self._reload(t)
        self.t_ref, self.cnt_ref, self.dir = t, self.r["CNTIN"], 1
        self.at(t + (self.r["MOD"] - self.r["CNTIN"]) * self.tick(), self._at_mod)
        if self.r["EXTTRIG"] & 0x40 and self.on_init_trigger:
            self.on_init_trigger(t)

    def _reload(self, t):
        self.r["SC"] |= 0x80                           # RF at each reload point
        if self.r["PWMLOAD"] & 0x200:                  # LDOK: buffers to the registers
            self.ldok_loads += 1
            self.r["MOD"], self.r["CNTIN"] = self.buf["MOD"], self.buf["CNTIN"]
            for pair in range(4):
                if self.r["COMBINE"] & (0x20 << (8 * pair)):       # SYNCENm
                    for ch in (2 * pair, 2 * pair + 1):
                        self.r["C%dV" % ch] = self.buf["C%dV" % ch]

    def _line(self):
        sc = self.r["SC"]
        self.core.set_line(self.IRQ, bool((sc & 0x80 and sc & 0x40) or (sc & 0x200 and sc & 0x100)))

    # registers
    def rd_SC(self):
        self.armed["SC"] = self.r["SC"] & 0x280
        return self.r["SC"]

    def wr_SC(self, v):
        old = self.r["SC"]
        if self.wpen() and (v ^ old) & 0x3F:
            raise Stop("FTM3_SC[CLKS, PS, CPWMS] changed while write-protected")
        flags = old & 0x280
        cleared = self.armed["SC"] & ~v & 0x280        # read as 1, written 0 (RM, SC[RF], SC[TOF])
        self.armed["SC"] = 0
        self.r["SC"] = (v & ~0x280) | (flags & ~cleared)
        was, self.running = self.running, bits(v, 3, 2) != 0
        if self.running and not was:
            self.tick()
            self._start(self.now())
        elif was and not self.running:
            self.gen += 1                              # counter stopped: no more events
        self._line()

    def _buffered(self, n, v):
        self.buf[n] = v & 0xFFFF
        if not self.running:                           # CLKS = 00: updated when written
            self.r[n] = v & 0xFFFF

    def wr_MOD(self, v):
        self._buffered("MOD", v)

    def wr_CNTIN(self, v):
        self._buffered("CNTIN", v)

    def wr_MODE(self, v):
        if self.wpen():
            if v & 0x4:                                # WPDIS = 1 clears WPEN
                self.r["FMS"] &= ~0x40
                self.r["MODE"] = v
                return
            if (v ^ self.r["MODE"]) & ~0x4:
                raise Stop("FTM3_MODE changed while write-protected")
        self.r["MODE"] = v

    def rd_FMS(self):
        fms = self.r["FMS"] & ~0x20
        if self.fault_in:
            fms |= 0x20                                # FAULTIN
        self.armed["FMS"] = fms & 0x8F
        return fms

    def wr_FMS(self, v):
        fms = self.r["FMS"]
        if v & 0x40:
            fms |= 0x40                                # WPEN: write 1 sets it
        # fault flags: read as 1, written 0, with the fault input inactive (FAULTM = 10)
        if not self.fault_in:
            fms &= ~(self.armed["FMS"] & ~v & 0x8F)
        self.armed["FMS"] = 0
        self.r["FMS"] = fms

    def wr_PWMLOAD(self, v):
        self.r["PWMLOAD"] = v
        if v & 0x200:
            self.last_ldok_write = self.now()
            self.ldok_writes.append(self.last_ldok_write)

    def set_fault(self, asserted):
        """FTM3_FLT0 (active low pin, FLTPOL[FLT0POL] = 1): asserted = over-current."""
        self.fault_in = asserted
        if asserted and self.r["FLTCTRL"] & 0x1:
            self.r["FMS"] |= 0x81                      # FAULTF0, FAULTF

    # ------------------------------------------------------------------ channel outputs
    def dead_ticks(self):
        """The inserted dead time in FTM clocks (RM FTM chapter, "Deadtime insertion",
        register DEADTIME): the prescaler of DTPS (0x: 1, 10: 4, 11: 16) times the count
        DTVALEX:DTVAL (DTVAL bits 5:0, DTVALEX bits 19:16 its upper 4 bits)."""
        dt = self.r["DEADTIME"]
        ps = (1, 1, 4, 16)[bits(dt, 6, 2)]
        return ps * ((bits(dt, 16, 4) << 6) | bits(dt, 0, 6))

    def _cpwm_on(self, ch):
        """The on-intervals in [0, 2 MOD) of channel ch's PWM in up-down counting, the
        period counted from the reload point at MOD (RM FTM, "Center-aligned PWM (CPWM)
        mode"): ELSB:ELSA = 10 high-true (cleared at the up-counting match, set at the
        down-counting match: high while CNT < CnV), 01 low-true (the complement); CnV = 0 (=
        CNTIN) never high, CnV >= MOD always high."""
        m, v = self.r["MOD"], self.r["C%dV" % ch]
        els = bits(self.r["C%dSC" % ch], 2, 2)
        if els not in (1, 2):
            raise Stop("FTM3 channel %d: ELSB:ELSA = %d is not modelled (the output is "
                       "not a PWM)" % (ch, els))
        if v <= self.r["CNTIN"]:
            on = []
        elif v >= m:
            on = [(0, 2 * m)]
        else:
            on = [(m - v, m + v)]
        return on if els == 2 else _complement(on, 2 * m)

    def pin_on(self):
        """Each of the six channel outputs as its on-intervals (pin high) in the PWM period
        [0, 2 MOD) FTM clocks that begins at this reload point, from the registers in effect
        (RM FTM chapter): COMBINE[COMPm] makes channel 2m+1 the complement of channel 2m
        (else it is a PWM of its own CnV); COMBINE[DTENm] delays every rising edge of both
        channels of the pair by the dead time (dead_ticks()), and a pulse no longer than
        the dead time disappears; POL[POLn] inverts channel n; a channel whose PWMENn is 0,
        masked by OUTMASK, or of a pair with FAULTENm while a fault flag is set is at its
        inactive level (low with POLn = 0, high with POLn = 1: "Output mask", "Fault
        control").  An edge at the period's start or end is the continuation of the
        previous period, not an edge.  Only the up-down counting of the two-sensor image is
        modelled: COMBINEm, up counting or a non-zero CNTIN stop the run."""
        m = self.r["MOD"]
        if not self.cpwm() or self.r["CNTIN"] != 0:
            raise Stop("FTM3 outputs: only up-down counting from CNTIN = 0 is modelled")
        comb, pol, mask = self.r["COMBINE"], self.r["POL"], self.r["OUTMASK"]
        dt = self.dead_ticks()
        out = []
        for pair in range(3):
            f = bits(comb, 8 * pair, 8)
            if f & 0x1:
                raise Stop("FTM3 pair %d: combine mode (COMBINE%d) is not modelled" % (pair, pair))
            n0, n1 = 2 * pair, 2 * pair + 1
            w0 = self._cpwm_on(n0)
            w1 = _complement(w0, 2 * m) if f & 0x2 else self._cpwm_on(n1)
            if f & 0x10:
                w0, w1 = _delay_rising(w0, dt, 2 * m), _delay_rising(w1, dt, 2 * m)
            fault = bool(f & 0x40) and bool(self.r["FMS"] & 0x80)
            for n, w in ((n0, w0), (n1, w1)):
                inv = bool(pol & (1 << n))
                if not self.running or not bits(self.r["SC"], 16 + n, 1) or mask & (1 << n) or fault:
                    w = [(0, 2 * m)] if inv else []
                elif inv:
                    w = _complement(w, 2 * m)
                out.append(w)
        return out

    def outputs_on(self):
        """Every one of the six outputs switching: counter running, PWMEN0..5, not
        masked, no fault flag (FAULTM = 10 keeps them safe until the flag is cleared)."""
        sc = self.r["SC"]
        return (self.running and bits(sc, 16, 6) == 0x3F and self.r["OUTMASK"] & 0x3F == 0
                and not self.r["FMS"] & 0x80)


def _complement(on, length):
    """The complement of sorted disjoint on-intervals within [0, length)."""
    res, t = [], 0
    for a, b in on:
        if a > t:
            res.append((t, a))
        t = max(t, b)
    if t < length:
        res.append((t, length))
    return res


def _delay_rising(on, dt, length):
    """Every rising edge (an interval's start other than the period's start) delayed by dt;
    an interval no longer than dt disappears."""
    res = []
    for a, b in on:
        a2 = a + dt if a > 0 else a
        if a2 < b:
            res.append((a2, b))
    return res


def _overlap(u, v):
    return sum(max(0, min(b, d) - max(a, c)) for a, b in u for c, d in v)


def bridge(pins, mod):
    """The inverter seen by the plant from the six gate signals (pins[2k]: the high side
    of phase k, pins[2k+1]: its low side; on-intervals in [0, 2 mod)): (cmp, td, on) with
    cmp the three compare values (the high side's nominal half-width around the period's
    centre, FTM clocks), td the dead time between each switch's turn-off and the other's
    turn-on (FTM clocks; None when no phase switches), on whether the bridge switches.
    A phase whose two switches are on at once (shoot-through), a phase left floating while
    the others switch, an asymmetric gap or phases with different dead times stop the run:
    none of them is a pattern of the plant's inverter model (sim/plant.c, sim_pole_avg)."""
    full = 2 * mod
    cmp, tds = [], []
    if all(not p for p in pins):
        return [0, 0, 0], None, False
    for k in range(3):
        hs, ls = pins[2 * k], pins[2 * k + 1]
        ov = _overlap(hs, ls)
        if ov:
            raise Stop("FTM3 phase %d: high and low side on together for %d FTM clocks a period "
                       "(shoot-through)" % (k, ov))
        if hs == [(0, full)]:
            cmp.append(mod)
        elif ls == [(0, full)]:
            cmp.append(0)
        elif len(ls) == 2 and ls[0][0] == 0 and ls[1][1] == full and len(hs) <= 1:
            c, d = ls[0][1], ls[1][0]
            x = mod - c                                   # nominal half-width
            td = d - (mod + x)
            if hs and (hs[0][0] - c != td or hs[0][1] != mod + x):
                raise Stop("FTM3 phase %d: gaps %d and %d FTM clocks around the high side: "
                           "asymmetric dead time, not modelled" % (k, hs[0][0] - c, d - hs[0][1]))
            cmp.append(x)
            tds.append(td)
        else:
            raise Stop("FTM3 phase %d: gate pattern high %s low %s is not a complementary pair "
                       "(not modelled)" % (k, hs, ls))
    if len(set(tds)) > 1:
        raise Stop("FTM3: different dead times per phase %s (not modelled)" % tds)
    return cmp, (tds[0] if tds else None), True


for _n in range(8):
    setattr(FTM, "wr_C%dV" % _n, (lambda n: lambda self, v: self._buffered("C%dV" % n, v))(_n))


def _cnsc_wr(n):
    def f(self, v):
        self.r["C%dSC" % n] = v & 0x7F
    return f


for _n in range(8):
    setattr(FTM, "wr_C%dSC" % _n, _cnsc_wr(_n))


# ---------------------------------------------------------------------- ADC and PDB
ADC_COMPARE_CLOCKS = 20          # ASSUMPTION (see the module docstring)
CAL_CYCLES = 2000


class ADC(Periph):
    """RM chapter ADC: SC1A..SC1P (ADCH 4:0, AIEN 6, COCO 7 read-only), CFG1, CFG2
    (SMPLTS), RA..RP (read-only; reading Rn clears SC1n[COCO]), SC2 (ADTRG 6, ADACT 7),
    SC3 (CAL 7, AVGE, AVGS), calibration registers CLPS..CLP9.  A pre-trigger n of the
    PDB converts the channel of SC1n into Rn (SIM_ADCOPT = 0: RM chapter SIM, ADCOPT)."""
    def __init__(self, idx, base, pcc, irq):
        self.name = "ADC%d" % idx
        self.idx, self.base, self.pcc, self.irq = idx, base, pcc, irq
        t = {4 * n: ("SC1%s" % chr(65 + n), 0x1F) for n in range(16)}
        t.update({0x48 + 4 * n: ("R%s" % chr(65 + n), 0) for n in range(16)})
        t.update({0x40: ("CFG1", 0), 0x44: ("CFG2", 0x0C), 0x90: ("SC2", 0), 0x94: ("SC3", 0),
                  0xB4: ("CLPS", 0), 0xB8: ("CLP3", 0), 0xBC: ("CLP2", 0), 0xC0: ("CLP1", 0),
                  0xC4: ("CLP0", 0), 0xC8: ("CLPX", 0), 0xCC: ("CLP9", 0)})
        self.table = t
        self.ro = tuple("R%s" % chr(65 + n) for n in range(16))
        self.analog = None            # callback(adc, channel, t) -> 12-bit code
        self.on_complete = None       # callback(n, t): PDB back-to-back chain
        super().__init__()

    def reset(self):
        super().reset()
        self.busy_until = 0
        self.conversions = 0
        self.conflicts = 0

    def adck_hz(self):
        """ADCK: CFG1[ADICLK] = 00 selects ALTCLK1, the functional clock of PCC[PCS] (its
        DIV2 output: the ADCs are among the peripherals on the DIV2 clocks, S32K1xx RM
        "Clock distribution"), divided by 2^CFG1[ADIV]; another ADICLK stops."""
        if bits(self.r["CFG1"], 0, 2) != 0:
            raise Stop("%s: ADICLK other than 00 (ALTCLK1) is not modelled" % self.name)
        return pcc_hz(self.core, self.pcc, 2, self.name) >> bits(self.r["CFG1"], 5, 2)

    def conv_cycles(self):
        adck = (self.r["CFG2"] & 0xFF) + 1 + ADC_COMPARE_CLOCKS
        return adck * cycles_per(self.core, self.adck_hz(), self.name)

    def _line(self):
        on = any(self.r["SC1%s" % chr(65 + n)] & 0xC0 == 0xC0 for n in range(16))
        self.core.set_line(self.irq, on)

    def pretrigger(self, n, t):
        """PDB pre-trigger n at core clock t: convert SC1n's channel."""
        if not self.r["SC2"] & 0x40:
            return                                       # software trigger selected
        if t < self.busy_until:
            self.conflicts += 1
            return
        sc1 = "SC1%s" % chr(65 + n)
        ch = self.r[sc1] & 0x1F
        if ch == 0x1F:
            return                                       # module disabled
        code = self.analog(self.idx, ch, t) & 0xFFF
        done = t + self.conv_cycles()
        self.busy_until = done

        def complete(tc, n=n, sc1=sc1, code=code):
            self.r["R%s" % chr(65 + n)] = code
            self.r[sc1] |= 0x80                          # COCO
            self.conversions += 1
            self._line()
            if self.on_complete:
                self.on_complete(n, tc)
        self.core.schedule(done, complete)

    def read(self, off):
        v = super().read(off)
        n = self.regs[off]
        if n.startswith("R") and len(n) == 2:
            sc1 = "SC1" + n[1]
            self.r[sc1] &= ~0x80                         # reading Rn clears COCO
            self._line()
        return v

    def rd_SC2(self):
        return self.r["SC2"] | (0x80 if self.now() < self.busy_until else 0)

    def wr_SC2(self, v):
        self.r["SC2"] = v & 0x7F

    def wr_SC3(self, v):
        self.r["SC3"] = v
        if v & 0x80:                                     # CAL: calibration starts

            def cal_done(t):
                self.r["SC3"] &= ~0x80
                self.r["SC1A"] |= 0x80                   # COCO of SC1A at its end
                self._line()
            self.core.schedule(self.now() + CAL_CYCLES, cal_done)


for _n in range(16):
    def _w(self, v, n=_n):
        sc1 = "SC1%s" % chr(65 + n)
        self.r[sc1] = v & 0x7F                           # writing SC1n clears COCO
        if not self.r["SC2"] & 0x40 and (v & 0x1F) != 0x1F and not self.r["SC3"] & 0x80:
            raise Stop("%s software-triggered conversion is not modelled" % self.name)
        self._line()
    setattr(ADC, "wr_SC1%s" % chr(65 + _n), _w)


def _pdb_dly(m):
    return lambda self, v: self._buffered("CH0DLY%d" % m, v)


class PDB(Periph):
    """RM chapter PDB: SC (LDOK 0, CONT 1, MULT 3:2, PDBEN 7, TRGSEL 11:8, PRESCALER 14:12,
    LDMOD 19:18), MOD, CNT (read-only), IDLY, channel 0: C1 (EN 7:0, TOS 15:8, BB 23:16),
    S (ERR 7:0, CF 23:16), DLY0..DLY7.  MOD, IDLY and the delays are double-buffered:
    LDOK loads them per LDMOD (00 at once, 01 at the counter's MOD, 10 at the next trigger,
    11 either).  Trigger input 0 (TRGSEL = 0) is TRGMUX_PDBn; a trigger restarts the
    counter from 0; pre-trigger m fires at the counter's DLYm (TOS), or back-to-back (BB)
    when the ADC completes pre-trigger m - 1; one shot (CONT = 0) stops at MOD."""
    def __init__(self, idx, base, pcc, adc):
        self.name = "PDB%d" % idx
        self.idx, self.base, self.pcc, self.adc = idx, base, pcc, adc
        t = {0x0: ("SC", 0), 0x4: ("MOD", 0xFFFF), 0x8: ("CNT", 0), 0xC: ("IDLY", 0xFFFF),
             0x10: ("CH0C1", 0), 0x14: ("CH0S", 0)}
        t.update({0x18 + 4 * m: ("CH0DLY%d" % m, 0) for m in range(8)})
        self.table = t
        self.ro = ("CNT",)
        super().__init__()
        adc.on_complete = self._adc_done

    def reset(self):
        super().reset()
        self.buf = {"MOD": 0xFFFF, "IDLY": 0xFFFF}
        self.buf.update({"CH0DLY%d" % m: 0 for m in range(8)})
        self.t_trig = None
        self.triggers = 0
        self.pretrig_times = []
        self.trigger_times = []
        self.ldok_pending = False

    def clk(self):
        """Core clocks per PDB count: the PDB counts its peripheral clock, SYS_CLK (the PDBs
        are among the SYS_CLK modules of the S32K1xx RM's peripheral clocking table; NXP's
        S32K1 SDK lists PDB0_CLK and PDB1_CLK with the SYS clocks), divided by
        2^PRESCALER x MULT (1, 10, 20, 40)."""
        sc = self.r["SC"]
        return (cycles_per(self.core, clock_hz(self.core, "SYS"), self.name)
                * (1 << bits(sc, 12, 3)) * (1, 10, 20, 40)[bits(sc, 2, 2)])

    def _load(self):
        for k, v in self.buf.items():
            self.r[k] = v
        self.r["SC"] &= ~0x1
        self.ldok_pending = False

    def wr_SC(self, v):
        if v & 0x1 and not v & 0x80:
            raise Stop("PDB%d_SC[LDOK] written with PDBEN = 0" % self.idx)
        if bits(v, 8, 4) != 0 and v & 0x80:
            raise Stop("PDB%d trigger input other than 0 (TRGMUX) is not modelled" % self.idx)
        if v & 0x2:
            raise Stop("PDB%d continuous mode is not modelled" % self.idx)
        self.r["SC"] = v & ~0x10000
        if not v & 0x80:
            self.gen += 1
        if v & 0x1:
            self.ldok_pending = True
            if bits(v, 18, 2) == 0:
                self._load()

    def _buffered(self, n, v):
        self.buf[n] = v & 0xFFFF

    def wr_MOD(self, v):
        self._buffered("MOD", v)

    def wr_IDLY(self, v):
        self._buffered("IDLY", v)

    def wr_CH0S(self, v):
        self.r["CH0S"] &= ~(~v & 0xFF)                   # ERR: write 0 to clear

    def rd_CNT(self):
        if self.t_trig is None:
            return 0
        return min((self.now() - self.t_trig) // self.clk(), self.r["MOD"])

    def trigger(self, t):
        """Trigger input 0 (TRGMUX output) at core clock t."""
        sc = self.r["SC"]
        if not sc & 0x80:
            return
        if self.ldok_pending and bits(sc, 18, 2) in (2, 3):
            self._load()
        self.gen += 1
        self.triggers += 1
        self.t_trig = t
        self.trigger_times.append(t)
        c1 = self.r["CH0C1"]
        for m in range(8):
            if c1 & (1 << m) and not c1 & (1 << (16 + m)):
                d = self.r["CH0DLY%d" % m] if c1 & (1 << (8 + m)) else 0
                if d <= self.r["MOD"]:
                    self.at(t + max(d, 1 if not c1 & (1 << (8 + m)) else 0) * self.clk(),
                            lambda tt, m=m: self._fire(m, tt))
        self.at(t + self.r["MOD"] * self.clk(), self._at_mod)

    def _at_mod(self, t):
        if self.ldok_pending and bits(self.r["SC"], 18, 2) in (1, 3):
            self._load()

    def _fire(self, m, t):
        if self.adc.r["SC1%s" % chr(65 + m)] & 0x80:
            self.r["CH0S"] |= 1 << m                     # sequence error: result not read
        self.r["CH0S"] |= 1 << (16 + m)                  # CF
        if m == 0:
            self.pretrig_times.append(t)
        self.adc.pretrigger(m, t)

    def _adc_done(self, n, t):
        c1 = self.r["CH0C1"]
        m = n + 1
        if m < 8 and c1 & (1 << m) and c1 & (1 << (16 + m)) and self.t_trig is not None:
            self._fire(m, t)


for _m in range(8):
    setattr(PDB, "wr_CH0DLY%d" % _m, _pdb_dly(_m))


# ---------------------------------------------------------------------- LPIT0
class LPIT(Periph):
    """RM chapter LPIT: MCR (M_CEN 0, DBG_EN 3), MSR (TIF0, write 1 to clear), MIER
    (TIE0), TVAL0, CVAL0 (read-only), TCTRL0 (T_EN 0, MODE 3:2 = 00 32-bit periodic).
    Channel 0 counts TVAL0 .. 0 on its functional clock, sets TIF0 at 0 and reloads:
    TVAL0 + 1 clocks per period."""
    name = "LPIT0"
    base = 0x40037000
    pcc = 0xDC
    IRQ = 48
    table = {0x8: ("MCR", 0), 0xC: ("MSR", 0), 0x10: ("MIER", 0), 0x20: ("TVAL0", 0),
             0x24: ("CVAL0", 0xFFFFFFFF), 0x28: ("TCTRL0", 0)}
    ro = ("CVAL0",)

    first_delay = 0                   # scenario: extra core clocks before the first timeout

    def reset(self):
        super().reset()
        self.t_load = None
        self.timeouts = 0

    def clk(self):
        """Core clocks per LPIT count: the functional clock of PCC[PCS], its DIV2 output."""
        return cycles_per(self.core, pcc_hz(self.core, self.pcc, 2, "LPIT0"), "LPIT0")

    def _line(self):
        self.core.set_line(self.IRQ, bool(self.r["MSR"] & self.r["MIER"] & 1))

    def _run(self, t):
        self.gen += 1
        self.t_load = t
        self.at(t + (self.r["TVAL0"] + 1) * self.clk(), self._timeout)

    def _timeout(self, t):
        self.timeouts += 1
        self.r["MSR"] |= 1
        self._line()
        self._run(t)

    def wr_MCR(self, v):
        self.r["MCR"] = v & 0xF

    def wr_MSR(self, v):
        self.r["MSR"] &= ~(v & 0xF)
        self._line()

    def wr_MIER(self, v):
        self.r["MIER"] = v & 0xF
        self._line()

    def wr_TCTRL0(self, v):
        if bits(v, 2, 2) != 0:
            raise Stop("LPIT0 channel mode other than 32-bit periodic is not modelled")
        if not self.r["MCR"] & 1 and v & 1:
            raise Stop("LPIT0 channel enabled with MCR[M_CEN] = 0")
        was = self.r["TCTRL0"] & 1
        self.r["TCTRL0"] = v
        if v & 1 and not was:
            self._run(self.now() + self.first_delay)
        elif not v & 1:
            self.gen += 1
            self.t_load = None

    def rd_CVAL0(self):
        if self.t_load is None:
            return 0xFFFFFFFF
        return self.r["TVAL0"] - (self.now() - self.t_load) // self.clk()


# ---------------------------------------------------------------------- LPUART1
class LPUART(Periph):
    """RM chapter LPUART: BAUD (SBR 12:0, LBKDIE 15, OSR 28:24), STAT (flags: LBKDIF 31
    w1c, TDRE 23, TC 22, RDRF 21, IDLE 20 w1c, OR 19 w1c, NF/FE/PF w1c; configuration:
    BRK13 26, LBKDE 25), CTRL (ILT 2, IDLECFG 10:8, SBK 16, RE 18, TE 19, ILIE 20, RIE 21,
    TCIE 22, TIE 23), DATA (write: transmit; read: received byte, clears RDRF).  Writing
    SBK 1 then 0 queues a break character (13 bit times with BRK13).  With LBKDE a
    received break sets LBKDIF and no data.  Idle: IDLE after 2^IDLECFG idle characters
    counted from the stop bit (ILT = 1)."""
    name = "LPUART1"
    base = 0x4006B000
    pcc = 0x1AC
    IRQ = 33
    table = {0x10: ("BAUD", 0x0F000004), 0x14: ("STAT", 0x00C00000), 0x18: ("CTRL", 0),
             0x1C: ("DATA", 0x1000)}

    def reset(self):
        super().reset()
        self.tx_queue = []             # bytes, or 'BRK'
        self.shifting = False
        self.tx_log = []               # (cycle, byte or 'BRK')
        self.rx_byte = 0

    def bit_cycles(self):
        """Core clocks per bit: (OSR + 1) x SBR clocks of the functional clock of PCC[PCS],
        its DIV2 output (RM LPUART chapter, "Baud rate generation")."""
        b = self.r["BAUD"]
        return (bits(b, 24, 5) + 1) * (b & 0x1FFF) * cycles_per(
            self.core, pcc_hz(self.core, self.pcc, 2, "LPUART1"), "LPUART1")

    def _line(self):
        s, c, b = self.r["STAT"], self.r["CTRL"], self.r["BAUD"]
        on = ((s & (1 << 31) and b & (1 << 15)) or (s & (1 << 23) and c & (1 << 23)) or
              (s & (1 << 22) and c & (1 << 22)) or (s & (1 << 21) and c & (1 << 21)) or
              (s & (1 << 20) and c & (1 << 20)))
        self.core.set_line(self.IRQ, bool(on))

    def wr_BAUD(self, v):
        self.r["BAUD"] = v

    def wr_STAT(self, v):
        w1c = 0xC01FC000
        s = self.r["STAT"]
        s &= ~(v & w1c)
        s = (s & ~0x3C000000) | (v & 0x3C000000)        # MSBF, RXINV, RWUID, BRK13, LBKDE
        self.r["STAT"] = s
        self._line()

    def wr_CTRL(self, v):
        old = self.r["CTRL"]
        self.r["CTRL"] = v
        if old & (1 << 16) and not v & (1 << 16):
            self._queue("BRK")
        self._line()

    def wr_DATA(self, v):
        if not self.r["CTRL"] & (1 << 19):
            raise Stop("LPUART1_DATA written with the transmitter off (TE = 0)")
        if not self.r["STAT"] & (1 << 23):
            raise Stop("LPUART1_DATA written with TDRE = 0 (data lost)")
        self._queue(v & 0xFF)

    def rd_DATA(self):
        self.r["STAT"] &= ~(1 << 21)                     # reading DATA clears RDRF
        self._line()
        return self.rx_byte

    def _queue(self, item):
        self.tx_queue.append(item)
        self.r["STAT"] &= ~(1 << 22)                     # TC: a transmission pending
        if self.shifting:
            self.r["STAT"] &= ~(1 << 23)                 # TDRE: the data buffer is full
        else:
            self._shift(self.now())
        self._line()

    def _shift(self, t):
        item = self.tx_queue.pop(0)
        self.shifting = True
        self.r["STAT"] |= 1 << 23                        # buffer moved to the shifter
        nbits = (13 if self.r["STAT"] & (1 << 26) else 10) + 1 if item == "BRK" else 10
        self.tx_log.append((t, item))
        self.core.schedule(t + nbits * self.bit_cycles(), self._shift_done)

    def _shift_done(self, t):
        self.shifting = False
        if self.tx_queue:
            self._shift(t)
        else:
            self.r["STAT"] |= 1 << 22                    # TC
        self._line()

    def inject(self, t, frame):
        """A LIN frame from the master on the receive line, from core clock t: a 13-bit
        break with its delimiter, then the bytes back to back, then the idle line."""
        bc = self.bit_cycles()

        def brk(tt):
            if self.r["STAT"] & (1 << 25):
                self.r["STAT"] |= 1 << 31                # LBKDIF
                self._line()
        self.core.schedule(t + 13 * bc, brk)
        t_b = t + 14 * bc
        for byte in frame:
            t_b += 10 * bc

            def rx(tt, byte=byte):
                if not self.r["CTRL"] & (1 << 18):
                    return
                if self.r["STAT"] & (1 << 21):
                    self.r["STAT"] |= 1 << 19            # OR: the previous byte not read
                else:
                    self.rx_byte = byte
                    self.r["STAT"] |= 1 << 21            # RDRF
                self._line()
            self.core.schedule(t_b, rx)
        idle_chars = 1 << bits(self.r["CTRL"], 8, 3)

        def idle(tt):
            self.r["STAT"] |= 1 << 20                    # IDLE
            self._line()
        self.core.schedule(t_b + idle_chars * 10 * bc, idle)
        return t_b + idle_chars * 10 * bc


# ---------------------------------------------------------------------- FlexCAN0
CAN_FRAME_BITS = 111              # standard data frame, 8 bytes, without stuff bits


class FlexCAN(Periph):
    """RM chapter FlexCAN: MCR (MDIS 31, FRZ 30, HALT 28, NOTRDY 27, FRZACK 24, LPMACK 20,
    SRXDIS 17, IRMQ 16); CTRL1 written only in freeze mode; message buffers (CAN0_RAMn),
    RXIMRn, RXMGMASK; IFLAG1 (write 1 to clear).  MB0 with CODE 1100 transmits; after the
    frame CODE becomes 1000 and IFLAG1[BUF0I] is set."""
    name = "CAN0"
    base = 0x40024000
    pcc = 0x90
    table = dict([(0x0, ("MCR", 0xD890000F)), (0x4, ("CTRL1", 0)), (0x10, ("RXMGMASK", 0)),
                  (0x30, ("IFLAG1", 0))] +
                 [(0x80 + 4 * k, ("RAM%d" % k, 0)) for k in range(128)] +
                 [(0x880 + 4 * k, ("RXIMR%d" % k, 0)) for k in range(32)])

    def reset(self):
        super().reset()
        self.frames = []              # (cycle, id, dlc, data bytes)

    def rd_MCR(self):
        v = self.r["MCR"] & ~(0x00100000 | 0x01000000 | 0x08000000)
        mdis = v & (1 << 31)
        if mdis:
            v |= 0x00100000 | 0x08000000                 # LPMACK, NOTRDY
        elif v & (1 << 30) and v & (1 << 28):
            v |= 0x01000000 | 0x08000000                 # FRZACK, NOTRDY
        return v

    def frozen(self):
        return bool(self.rd_MCR() & 0x01000000)

    def wr_CTRL1(self, v):
        if not self.frozen() and not self.r["MCR"] & (1 << 31):
            raise Stop("CAN0_CTRL1 written outside freeze mode")
        self.r["CTRL1"] = v

    def wr_IFLAG1(self, v):
        self.r["IFLAG1"] &= ~v

    def bit_cycles(self):
        c = self.r["CTRL1"]
        tq = 1 + (bits(c, 0, 3) + 1) + (bits(c, 19, 3) + 1) + (bits(c, 16, 3) + 1)
        presdiv = bits(c, 24, 8) + 1
        if c & (1 << 13):
            raise Stop("CAN0_CTRL1[CLKSRC] = 1 (peripheral clock) is not modelled")
        # CLKSRC = 0: the oscillator clock, SOSCDIV2_CLK on the S32K1xx (RM FlexCAN chapter,
        # the chip-specific clocking)
        return tq * presdiv * cycles_per(self.core, clock_hz(self.core, "SOSCDIV2"), "CAN0")

    def wr_RAM0(self, v):
        self.r["RAM0"] = v
        if bits(v, 24, 4) == 0xC:
            if self.frozen():
                raise Stop("CAN0 MB0 activated in freeze mode")
            t = self.now()

            def sent(tt):
                w0 = self.r["RAM0"]
                d = self.r["RAM2"].to_bytes(4, "big") + self.r["RAM3"].to_bytes(4, "big")
                dlc = bits(w0, 16, 4)
                self.frames.append((tt, bits(self.r["RAM1"], 18, 11), dlc, d[:dlc]))
                self.r["RAM0"] = (w0 & ~0x0F000000) | (0x8 << 24)
                self.r["IFLAG1"] |= 1
            self.core.schedule(t + CAN_FRAME_BITS * self.bit_cycles(), sent)


def build(core):
    """Attach every model to the core; return them by name."""
    pcc = PCC()
    core.pcc_dev = pcc
    scg = SCG()
    core.scg_dev = scg
    portd = PORT("D", 0x4004C000, 0x130)
    adc0 = ADC(0, 0x4003B000, 0xEC, 39)
    adc1 = ADC(1, 0x40027000, 0x9C, 40)
    d = {"PCC": pcc, "SCG": scg, "SMC": SMC(), "SIM": SIM(),
         "PORTA": PORT("A", 0x40049000, 0x124), "PORTB": PORT("B", 0x4004A000, 0x128),
         "PORTC": PORT("C", 0x4004B000, 0x12C), "PORTD": portd,
         "PORTE": PORT("E", 0x4004D000, 0x134), "GPIOD": GPIOD(portd), "TRGMUX": TRGMUX(),
         "WDOG": WDOG(), "FTM3": FTM(), "ADC0": adc0, "ADC1": adc1,
         "PDB0": PDB(0, 0x40036000, 0xD8, adc0), "PDB1": PDB(1, 0x40031000, 0xC4, adc1),
         "LPIT0": LPIT(), "LPUART1": LPUART(), "CAN0": FlexCAN()}
    for dev in d.values():
        core.attach(dev)
    trg = d["TRGMUX"]

    def init_trigger(t):
        # TRGMUX input 28 (FTM3 initialization trigger) to each PDB that selects it
        for k in (0, 1):
            if trg.r["PDB%d" % k] & 0x7F == 28:
                if d["SIM"].r["ADCOPT"] != 0:
                    raise Stop("SIM_ADCOPT other than 0 (PDB triggers) is not modelled")
                d["PDB%d" % k].trigger(t)
    d["FTM3"].on_init_trigger = init_trigger
    return d
