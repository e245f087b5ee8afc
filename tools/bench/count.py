#!/usr/bin/python3
"""Instruction bench of qfoc on the Cortex-M4F (make bench).

Runs the library's functions, built with the project's ARM_CFLAGS (-O2), in Unicorn
(Thumb-2, Cortex-M4 model, FPU enabled) and counts the instructions executed from a
function's first instruction to its return, with a code hook; the same input gives the
same count in every run.  Adds the sizes, the worst-case stack from gcc's call-graph
files, and writes build/bench/bench.md and bench.json.

usage: count.py --elf BENCH.ELF --drive-elf DRIVE_ONLY.ELF --obj-dir DIR
                --replay NAME=FILE=TITLE [--replay ...] --out-dir DIR [--objdump TOOL]
                [--size TOOL] [--cc TOOL] [--cflags TEXT]
  BENCH.ELF       the bench image (library, reference table, tools/bench/harness.c)
  DRIVE_ONLY.ELF  the library linked with --gc-sections from the drive's entry points
  DIR             the objects with their .su and .ci files
  FILE            a recording of tools/bench/gen_replay.c (FILE.json beside it); the first
                  --replay is the main operating point of the report

What is measured:
  functions   each library function over a set of inputs (corners, saturating cases,
              random values from a fixed seed) and states reached through the library's
              own reset and step functions; min and max instructions.
  drive       a recording made on the host (tools/bench/gen_replay.c: the drive in closed
              loop with the plant model) is replayed into the target build until the
              operating point; every output is compared with the host build's, the
              drive's state is probed; then every fast step and tick of the recorded
              window is counted (max = longest path seen).  During the warm-up one fast
              step every 50 ms is counted, by sub-state.
  sizes       text + rodata, data, bss of the library objects; the part a drive firmware
              links (the drive's entry points with --gc-sections); sizeof(qfoc_drive_t)
              and of the parameter table from the bench image.
  stack       worst case from the .su / .ci files (stack.py), and the deepest stack seen
              in the emulator (painted stack) for comparison.
  static      the longest path of each measured function and entry point over every input,
              in instructions and estimated cycles, from the linked image (wcet.py); the
              limits of the functions and the entry points' static limits apply to it, and
              a measured count above it fails the bench.
Exit status: 0 when every figure is within its limit; 1 when one is above its limit (the
goals are reported, not enforced), when the bench could not run or the target build
disagreed with the host build.

Requirements: REQ-BENCH-001 .. REQ-BENCH-008 (specs/requirements/bench.md).
"""
import argparse
import bisect
import json
import math
import os
import random
import re
import struct
import subprocess
import sys
import time

from elftools.elf.elffile import ELFFile
from unicorn import UC_ARCH_ARM, UC_HOOK_CODE, UC_MODE_MCLASS, UC_MODE_THUMB, Uc, UcError
from unicorn import arm_const as A

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import stack  # noqa: E402  (tools/bench/stack.py)
import wcet  # noqa: E402  (tools/bench/wcet.py)

# Memory map: the bench image's linker script (tools/bench/bench.ld) plus the recording.
FLASH_BASE, FLASH_SIZE = 0x00000000, 0x00100000
RAM_BASE, RAM_SIZE = 0x20000000, 0x00010000
REC_BASE = 0x60000000
STACK_TOP = RAM_BASE + RAM_SIZE
HALT = FLASH_BASE + FLASH_SIZE - 0x10        # return sentinel: a Thumb 'b .' planted here
PAINT = 0x1000                               # bytes of stack painted before a counted call
PAINT_BYTE = 0xA5
MAX_INSNS = 50_000_000                       # per call: a runaway is an error

# bench_info[] indices (tools/bench/harness.h)
INFO = {"version": 0, "sizeof_drive": 1, "sizeof_table": 2, "svpwm_off": 3, "reserved": 4,
        "sizeof_fast": 5, "sizeof_slow": 6, "sizeof_sv_out": 7, "sizeof_pll_out": 8,
        "sizeof_tick_in": 9, "sizeof_tick_out": 10, "tick_tx_len": 11, "tick_can_send": 12}

# Limits: the budgets make bench enforces (specs/requirements/bench.md states their
# rationale); a figure above its limit makes the bench fail.  Each is the figure reached
# plus at most 10 %, so that a change that makes a block slower fails the bench and is
# reviewed.  Goals: the project's targets, reported (met or not) beside each limit.
# The entry points: the limits of the longest path the bench measured (REQ-BENCH-002), and
# the limits and goals of the static bound no input can exceed (tools/bench/wcet.py,
# REQ-BENCH-008).  The goals of the static bounds are the project's targets: fast step
# 1000 (800 the aim), tick 3000, CPU load at 16 kHz and 80 MHz 40 % (25 % the aim).
LIMIT_FAST_STEP = 1615
LIMIT_TICK = 2640
STATIC_LIMIT_FAST_STEP = 1960
STATIC_LIMIT_TICK = 4200
GOAL_FAST_STEP = 1000
GOAL_TICK = 3000
GOAL_LOAD_PCT = 40
GOAL_FLASH = 8 * 1024
GOAL_FLASH_DRIVE = 14 * 1024
LIMIT_FLASH = 34 * 1024
LIMIT_FLASH_DRIVE = 22528
LIMIT_RAM_MOTOR = 496
LIMIT_STACK_FAST = 224
# per function (bench key): (limit, goal) in instructions on the static bound of the
# function (every input); the bench also fails when a measured case is above it
FUNC_BUDGET = {
    "clarke": (23, 18),
    "park": (50, 23),
    "inv_park": (50, 23),
    "inv_clarke": (44, 22),
    "sincos": (42, 42),
    "pi": (44, 36),
    "lpf": (28, None),
    "vec_mag": (56, None),
    "circle_limit": (92, None),
    "svpwm": (330, None),
    "flux": (166, None),
    "pll": (254, None),
    "params_scan": (610, None),
}
# the drive's SVPWM chain in the fast step: the circle limit, then the SVPWM without its own
# limit (inverse Clarke by min-max injection, phase times, dead-time compensation)
SVPWM_CHAIN = ("qfoc_circle_limit", "qfoc_svpwm_step_lin")
LIMIT_SVPWM_CHAIN = 320
GOAL_SVPWM_CHAIN = 150
LIMIT_CLARKE, LIMIT_PARK, LIMIT_SVPWM = (FUNC_BUDGET[k][0] for k in ("clarke", "park", "svpwm"))
# PWM frequencies of the load table (the tick runs at 1 kHz)
LOAD_F_PWM_HZ = (8000, 10000, 16000, 20000)

F_CPU_HZ = 80e6


def s32(v):
    """An argument as the 32-bit register value (int16 values sign-extended)."""
    return int(v) & 0xFFFFFFFF


def i16(*vals):
    return struct.pack("<%dh" % len(vals), *[int(v) for v in vals])


def sat16(x):
    return max(-32768, min(32767, int(round(x))))


class Target:
    """The bench image in a fresh Unicorn Cortex-M4.

    counting=True installs the instruction hook once, for good: Unicorn instruments a block
    with the hooks present when it translates it, so a hook added later would miss the
    blocks already translated.  Every call on a counting target then runs through the
    hook (slow), so the long uncounted work (the replay) runs on a plain target, and the
    RAM is moved between the two (ram() / set_ram())."""

    def __init__(self, elf_path, rec=None, counting=False):
        mu = Uc(UC_ARCH_ARM, UC_MODE_THUMB | UC_MODE_MCLASS)
        mu.ctl_set_cpu_model(A.UC_CPU_ARM_CORTEX_M4)      # before any mem_map
        mu.mem_map(FLASH_BASE, FLASH_SIZE)
        mu.mem_map(RAM_BASE, RAM_SIZE)
        self.syms = {}
        self.funcs = []
        with open(elf_path, "rb") as f:
            elf = ELFFile(f)
            for seg in elf.iter_segments():
                if seg["p_type"] == "PT_LOAD" and seg["p_filesz"] > 0:
                    mu.mem_write(seg["p_vaddr"], seg.data())   # run address: no copy needed
            symtab = elf.get_section_by_name(".symtab")
            for s in symtab.iter_symbols():
                kind = s["st_info"]["type"]
                if kind in ("STT_FUNC", "STT_OBJECT") and s.name:
                    self.syms[s.name] = (s["st_value"], s["st_size"], kind)
                    if kind == "STT_FUNC":
                        self.funcs.append((s["st_value"] & ~1, s["st_size"], s.name))
        self.funcs.sort()
        self._starts = [a for a, _, _ in self.funcs]
        mu.mem_write(HALT, b"\xfe\xe7")
        # Cortex-M4F: CP10/CP11 full access and the FPU on, as start-up code would do
        mu.reg_write(A.UC_ARM_REG_C1_C0_2, mu.reg_read(A.UC_ARM_REG_C1_C0_2) | (0xF << 20))
        mu.reg_write(A.UC_ARM_REG_FPEXC, 0x40000000)
        if rec is not None:
            size = (len(rec) + 0xFFF) & ~0xFFF
            mu.mem_map(REC_BASE, size)
            mu.mem_write(REC_BASE, rec)
        self.mu = mu
        self.counting = counting
        self._n = 0
        self._trace = None
        if counting:
            def cb(uc, address, size, user):
                self._n += 1
                if self._trace is not None:
                    self._trace.append((address, size))
            mu.hook_add(UC_HOOK_CODE, cb, begin=FLASH_BASE, end=HALT - 1)
        self.info = [struct.unpack("<I", self.read(self.addr("bench_info") + 4 * i, 4))[0]
                     for i in range(len(INFO))]
        if self.info[INFO["version"]] != 1:
            raise RuntimeError("bench_info: layout version differs from this counter's")

    def addr(self, name):
        if name not in self.syms:
            raise KeyError(f"{name}: no such symbol in the bench image")
        return self.syms[name][0] & ~1

    def read(self, a, n):
        return bytes(self.mu.mem_read(a, n))

    def write(self, a, data):
        self.mu.mem_write(a, data)

    def ram(self):
        return self.read(RAM_BASE, RAM_SIZE)

    def set_ram(self, image):
        self.write(RAM_BASE, image)

    def func_of(self, a):
        i = bisect.bisect_right(self._starts, a) - 1
        if i >= 0:
            start, size, name = self.funcs[i]
            if start <= a < start + max(size, 2):
                return name
        return "?"

    def call(self, func, *args, trace=False):
        """Call func(args) (AAPCS: r0..r3, then the stack) until it returns.
        Returns (r0, instructions, stack bytes used, trace); the last three are None on a
        plain target."""
        mu = self.mu
        args = [s32(a) for a in args]
        extra = args[4:]
        sp = (STACK_TOP - 4 * len(extra)) & ~7
        if self.counting:
            mu.mem_write(STACK_TOP - PAINT, bytes([PAINT_BYTE]) * PAINT)
        for i, v in enumerate(extra):
            mu.mem_write(sp + 4 * i, struct.pack("<I", v))
        mu.reg_write(A.UC_ARM_REG_SP, sp)
        mu.reg_write(A.UC_ARM_REG_LR, HALT | 1)
        for i, v in enumerate(args[:4]):
            mu.reg_write(A.UC_ARM_REG_R0 + i, v)
        self._n = 0
        self._trace = [] if (trace and self.counting) else None
        mu.emu_start(self.addr(func) | 1, HALT, count=MAX_INSNS)
        pc = mu.reg_read(A.UC_ARM_REG_PC)
        if pc != HALT:
            raise RuntimeError(f"{func}: did not return (pc 0x{pc:08x})")
        n = used = None
        if self.counting:
            n = self._n
            painted = self.read(STACK_TOP - PAINT, PAINT)
            k = 0
            while k < PAINT and painted[k] == PAINT_BYTE:
                k += 1
            if k == 0:
                raise RuntimeError(f"{func}: stack deeper than the painted {PAINT} bytes")
            used = (STACK_TOP - (STACK_TOP - PAINT + k)) - (STACK_TOP - sp)
        tr, self._trace = self._trace, None
        return mu.reg_read(A.UC_ARM_REG_R0), n, used, tr


# ------------------------------------------------------------------ function benches

class Bench:
    """One function: cases of (memory writes, uncounted calls, counted arguments, label)."""

    def __init__(self, key, label, func, limit=None, goal=None, note=""):
        self.key, self.label, self.func, self.limit, self.note = key, label, func, limit, note
        self.goal = goal
        self.cases = []

    def case(self, args, pre=(), writes=(), label=""):
        self.cases.append((list(writes), list(pre), list(args), label))


def corners():
    return [-32768, -32767, -16384, -1, 0, 1, 16384, 32767]


def park_corners(b, a0, a1, res):
    """Park and inverse Park with every input at a corner of its range, the sine and cosine
    included (-32768 among them: the functions accept any pair)."""
    K = (-32768, -1, 0, 32767)
    for x in K:
        for y in K:
            for s in K:
                for c in K:
                    b.case([a0, a1, res], writes=[(a0, i16(x, y)), (a1, i16(s, c))],
                           label=f"({x},{y}) sin={s} cos={c}")


def build_benches(t, rng):
    """The function benches and their inputs."""
    arg = t.addr("bench_arg")
    res = t.addr("bench_res")
    a0, a1, a2, a3 = arg, arg + 16, arg + 32, arg + 48
    pi, lpf, flux, pll = (t.addr(n) for n in ("bench_pi", "bench_lpf", "bench_flux", "bench_pll"))
    fw, tc, mech, phase = (t.addr(n) for n in ("bench_fw", "bench_tc", "bench_mech", "bench_phase"))
    table = t.addr("qfoc_params_reference")
    cfg = table + t.info[INFO["svpwm_off"]]
    C = corners()
    benches = []

    def rnd16(lim=32767):
        return rng.randint(-lim, lim)

    def sc_of(deg):
        r = math.radians(deg)
        return sat16(32767 * math.sin(r)), sat16(32767 * math.cos(r))

    b = Bench("clarke", "`qfoc_clarke`", "qfoc_clarke")
    for x in C:
        for y in C:
            b.case([x, y, res], label=f"iu={x} iv={y}")
    for _ in range(64):
        b.case([rnd16(), rnd16(), res], label="random")
    benches.append(b)

    b = Bench("park", "`qfoc_park` (sin/cos given)", "qfoc_park")
    for deg in range(0, 360, 15):
        s, c = sc_of(deg)
        for al, be in ((0, 0), (20000, -12000), (32767, 32767), (-32768, -32768), (-32768, 32767)):
            b.case([a0, a1, res], writes=[(a0, i16(al, be)), (a1, i16(s, c))],
                   label=f"ab=({al},{be}) at {deg} deg")
    for _ in range(64):
        s, c = sc_of(rng.uniform(0, 360))
        b.case([a0, a1, res], writes=[(a0, i16(rnd16(), rnd16())), (a1, i16(s, c))], label="random")
    park_corners(b, a0, a1, res)
    benches.append(b)

    b = Bench("inv_park", "`qfoc_inv_park` (sin/cos given)", "qfoc_inv_park")
    for deg in range(0, 360, 15):
        s, c = sc_of(deg)
        for d, q in ((0, 0), (-8000, 15000), (32767, 32767), (-32768, -32768), (32767, -32768)):
            b.case([a0, a1, res], writes=[(a0, i16(d, q)), (a1, i16(s, c))],
                   label=f"dq=({d},{q}) at {deg} deg")
    for _ in range(64):
        s, c = sc_of(rng.uniform(0, 360))
        b.case([a0, a1, res], writes=[(a0, i16(rnd16(), rnd16())), (a1, i16(s, c))], label="random")
    park_corners(b, a0, a1, res)
    benches.append(b)

    b = Bench("inv_clarke", "`qfoc_inv_clarke`", "qfoc_inv_clarke")
    for x in C:
        for y in C:
            b.case([a0, res], writes=[(a0, i16(x, y))], label=f"ab=({x},{y})")
    for _ in range(64):
        b.case([a0, res], writes=[(a0, i16(rnd16(), rnd16()))], label="random")
    benches.append(b)

    b = Bench("sincos", "`qfoc_sincos`", "qfoc_sincos")
    angles = set(range(0, 65536, 97))
    for k in range(8):
        for d in (-1, 0, 1):
            angles.add((k * 8192 + d) % 65536)
    for th in sorted(angles):
        b.case([th, res], label=f"theta={th}")
    benches.append(b)

    b = Bench("atan2", "`qfoc_atan2`", "qfoc_atan2")
    for y in C:
        for x in C:
            b.case([y, x], label=f"y={y} x={x}")
    for _ in range(200):
        b.case([rnd16(), rnd16()], label="random")
    benches.append(b)

    b = Bench("vec_mag", "`qfoc_vec_mag`", "qfoc_vec_mag")
    for x in C:
        for y in C:
            b.case([x, y], label=f"x={x} y={y}")
    for _ in range(200):
        b.case([rnd16(), rnd16()], label="random")
    benches.append(b)

    b = Bench("circle_limit", "`qfoc_circle_limit`", "qfoc_circle_limit")
    for d, q in ((0, 0), (3000, 4000), (20000, 20000), (32767, 32767), (-32768, -32768),
                 (-32768, 0), (0, 32767), (-5000, 12000)):
        for vmax in (-32768, 0, 1, 9000, 15892, 32767):
            b.case([a0, vmax, res], writes=[(a0, i16(d, q))], label=f"dq=({d},{q}) vmax={vmax}")
    for _ in range(100):
        b.case([a0, rng.randint(0, 32767), res], writes=[(a0, i16(rnd16(), rnd16()))],
               label="random")
    benches.append(b)

    b = Bench("pi", "`qfoc_pi_step` (q-current PI)", "qfoc_pi_step")
    for preset in (-15892, -5000, 0, 5000, 15892):
        for e in C + [2000, -2000]:
            b.case([pi, e], pre=[("qfoc_pi_reset", [pi, preset])], label=f"I={preset} e={e}")
    benches.append(b)

    b = Bench("lpf", "`qfoc_lpf_step` (DC-bus low-pass)", "qfoc_lpf_step")
    for y0 in C:
        for u in C:
            b.case([lpf, u], pre=[("qfoc_lpf_reset", [lpf, y0])], label=f"y={y0} u={u}")
    benches.append(b)

    b = Bench("svpwm", "`qfoc_svpwm_step` (min-max injection, dead-time compensation)",
              "qfoc_svpwm_step")
    vdcs = (20972, 13631, 32767, 3000, -32768)    # 320 V, 208 V, full scale, < vdc_min, corner
    currents = ((0, 0, 0), (200, -100, -100), (5000, -2000, -3000), (-6000, 7000, -1000))
    for deg in [x * 7.5 for x in range(48)]:
        r = math.radians(deg)
        for frac in (0.0, 0.3, 0.9, 1.3):
            for vdc in vdcs[:2]:
                for cur in currents:
                    mag = frac * max(vdc, 6554) / math.sqrt(3)
                    al, be = sat16(mag * math.cos(r)), sat16(mag * math.sin(r))
                    b.case([cfg, a0, vdc, a1, res], writes=[(a0, i16(al, be)), (a1, i16(*cur))],
                           label=f"|v|={frac} Vdc/sqrt3 at {deg} deg vdc={vdc} i={cur}")
    # beyond the full-scale circle with all three currents inside the dead band (the fade of
    # the dead-time compensation, a division per phase, on top of the overmodulation limit)
    for deg in [x * 7.5 for x in range(48)]:
        r = math.radians(deg)
        for vdc in (32767, 20972):
            for cur in ((50, -20, -30), (-1, 1, 0), (120, 120, -240)):
                al, be = sat16(40000 * math.cos(r)), sat16(40000 * math.sin(r))
                b.case([cfg, a0, vdc, a1, res], writes=[(a0, i16(al, be)), (a1, i16(*cur))],
                       label=f"|v| beyond full scale at {deg} deg vdc={vdc} i={cur} (dead band)")
    for vdc in vdcs[2:]:
        for al, be in ((0, 0), (32767, 32767), (-32768, -32768), (1000, -1000), (-32768, 32767)):
            for cur in currents + ((-32768, -32768, -32768), (50, -20, -30)):
                b.case([cfg, a0, vdc, a1, res], writes=[(a0, i16(al, be)), (a1, i16(*cur))],
                       label=f"v=({al},{be}) vdc={vdc} i={cur}")
    benches.append(b)

    b = Bench("flux", "`qfoc_flux_step` (flux observer)", "qfoc_flux_step")
    for psi0 in ((0, 0), (13383, 0), (9463, 9463), (-13383, 0), (32767, 32767), (-32768, -32768)):
        for u, i in (((0, 0), (0, 0)), ((5000, 3000), (2000, -1500)), ((15892, -15892), (16384, 0)),
                     ((32767, 32767), (-32768, 32767)), ((-32768, -32768), (32767, -32768))):
            b.case([flux, a0, a1, res],
                   writes=[(a2, i16(*psi0)), (a3, i16(0, 0)), (a0, i16(*u)), (a1, i16(*i))],
                   pre=[("qfoc_flux_reset", [flux, a2, a3])],
                   label=f"psi0={psi0} u={u} i={i}")
    for _ in range(60):
        b.case([flux, a0, a1, res],
               writes=[(a2, i16(rnd16(14000), rnd16(14000))), (a3, i16(rnd16(), rnd16())),
                       (a0, i16(rnd16(16000), rnd16(16000))), (a1, i16(rnd16(20000), rnd16(20000)))],
               pre=[("qfoc_flux_reset", [flux, a2, a3])], label="random")
    benches.append(b)

    b = Bench("flux_lead", "`qfoc_flux_lead`", "qfoc_flux_lead")
    for w in C + [4915, 19661, 26214]:
        b.case([flux, w], label=f"w={w}")
    benches.append(b)

    b = Bench("pll", "`qfoc_pll_step` (PLL, speed low-pass)", "qfoc_pll_step")
    for th, w in ((0, 0), (16384, 9830), (49152, -9830), (65535, 26214), (30000, 32767)):
        for psi in ((0, 0), (100, -50), (13383, 0), (0, -13383), (9000, 9000), (32767, 32767),
                    (-32768, -32768), (-32768, 0)):
            b.case([pll, a0, res], writes=[(a0, i16(*psi))], pre=[("qfoc_pll_reset", [pll, th, w])],
                   label=f"theta={th} w={w} psi={psi}")
    for _ in range(60):
        ang = rng.uniform(0, 2 * math.pi)
        psi = i16(sat16(13383 * math.cos(ang)), sat16(13383 * math.sin(ang)))
        b.case([pll, a0, res], writes=[(a0, psi)],
               pre=[("qfoc_pll_reset", [pll, rng.randint(0, 65535), rnd16(26214)])], label="random")
    benches.append(b)

    b = Bench("fw", "`qfoc_fw_step` (field weakening)", "qfoc_fw_step")
    for pump_u, pumps in ((0, 0), (32767, 20), (32767, 400), (0, 400)):
        pre = [("qfoc_fw_reset", [fw])] + [("qfoc_fw_step", [fw, pump_u, 1])] * pumps
        for u in (0, 20000, 30147, 32767, -32768):
            for en in (0, 1):
                b.case([fw, u, en], pre=pre, label=f"state {pumps}x u={pump_u}; u={u} enable={en}")
    benches.append(b)

    def tc_state(kind):
        pre = [("qfoc_trqcomp_reset", [tc])]
        if kind == "learned":
            pre += [("qfoc_trqcomp_learn", [tc, (k * 4099) & 0xFFFF, 1500, 9830]) for k in range(40)]
        elif kind == "saturated":
            pre += [("qfoc_trqcomp_learn", [tc, 8192, 32767, 9830])] * 60
        return pre

    b = Bench("tc_out", "`qfoc_trqcomp_output` (torque compensation, fast step)",
              "qfoc_trqcomp_output")
    for kind in ("zero", "learned", "saturated"):
        for w in (0, 1966, 9830, -9830, 19661, 19662, 32767, -32768):
            for th in (0, 12345, 40000, 65535):
                b.case([tc, th, w], pre=tc_state(kind), label=f"{kind} w={w} theta_m={th}")
    benches.append(b)

    b = Bench("tc_learn", "`qfoc_trqcomp_learn` (torque compensation, tick)",
              "qfoc_trqcomp_learn")
    for kind in ("zero", "learned", "saturated"):
        for w in (0, 9830, -9830, 32767):
            for e in (0, 1500, -32768, 32767):
                b.case([tc, 22222, e, w], pre=tc_state(kind), label=f"{kind} w={w} e={e}")
    benches.append(b)

    b = Bench("mech", "`qfoc_mech_update` (mechanical angle)", "qfoc_mech_update")
    for th0 in (0, 65000, 32768):
        for th in (0, 100, 40000, 65535, 500):
            b.case([mech, th], pre=[("qfoc_mech_init", [mech, 3, th0])], label=f"{th0} -> {th}")
    benches.append(b)

    b = Bench("phase_mon", "`qfoc_phase_mon_update` (phase-loss monitor, three phases)",
              "qfoc_phase_mon_update")
    for cur in ((0, 0, 0), (5000, -2000, -3000), (32767, -32768, 1), (-32768, -32768, -32768)):
        b.case([phase, a0], writes=[(a0, i16(*cur))], pre=[("qfoc_phase_mon_reset", [phase])],
               label=f"i={cur}")
    benches.append(b)

    b = Bench("phase_mon_one", "`qfoc_phase_mon_update_one` (phase-loss monitor, one phase: "
              "the fast step's)", "qfoc_phase_mon_update_one")
    for cur in ((0, 0, 0), (5000, -2000, -3000), (32767, -32768, 1), (-32768, -32768, -32768)):
        for k in (0, 1, 2, 200):
            b.case([phase, a0, k], writes=[(a0, i16(*cur))], pre=[("qfoc_phase_mon_reset", [phase])],
                   label=f"i={cur} k={k}")
    benches.append(b)

    b = Bench("params_check", "`qfoc_params_check` (table identity, CRC, ranges)",
              "qfoc_params_check")
    b.case([table], label="reference table")
    benches.append(b)

    b = Bench("params_scan", "`qfoc_params_scan_step` (one step of the table check)",
              "qfoc_params_scan_step")
    for k in range(6):
        b.case([res, table, k], writes=[(res, struct.pack("<I", 0xFFFFFFFF))],
               label=f"step {k}, reference table")
    benches.append(b)
    for b in benches:
        if b.key in FUNC_BUDGET:
            b.limit, b.goal = FUNC_BUDGET[b.key]
    return benches


def run_benches(t, benches):
    """Every case from the RAM image bench_setup() left (t is a counting target)."""
    if t.call("bench_setup")[0] != 0:
        raise RuntimeError("bench_setup: the reference table was refused")
    image = t.ram()

    def prepare(writes, pre):
        t.set_ram(image)
        for a, data in writes:
            t.write(a, data)
        for fn, pargs in pre:
            t.call(fn, *pargs)

    out = {}
    for b in benches:
        counts = []
        stack_max = 0
        for writes, pre, args, label in b.cases:
            prepare(writes, pre)
            _, n, used, _ = t.call(b.func, *args)
            counts.append((n, label))
            stack_max = max(stack_max, used)
        lo = min(counts)
        hi = max(counts)
        # repeatability: the longest case once more from the same state
        writes, pre, args, _ = b.cases[counts.index(hi)]
        prepare(writes, pre)
        _, again, _, tr = t.call(b.func, *args, trace=True)
        out[b.key] = {"label": b.label, "symbol": b.func, "cases": len(counts), "min": lo[0],
                      "max": hi[0], "min_case": lo[1], "max_case": hi[1], "limit": b.limit,
                      "goal": b.goal,
                      "stack_bytes_seen": stack_max, "repeatable": again == hi[0],
                      "max_breakdown": breakdown(t, tr)}
    return out


# ------------------------------------------------------------------ cycle estimate

_OBJ = re.compile(r"^\s*([0-9a-f]+):\s+([0-9a-f]{4}(?: [0-9a-f]{4})?)\s+(\S+)\s*(.*)$")


def disassembly(objdump, elf):
    """{address: (mnemonic, operands, size in bytes)} of the bench image."""
    text = subprocess.run([objdump, "-d", elf], check=True, capture_output=True, text=True).stdout
    insns = {}
    for line in text.splitlines():
        m = _OBJ.match(line)
        if m:
            insns[int(m.group(1), 16)] = (m.group(3).lower(), m.group(4),
                                          2 * len(m.group(2).split()))
    return insns


def _nregs(ops):
    n = 0
    body = ops[ops.find("{") + 1:ops.find("}")] if "{" in ops else ""
    for part in body.split(","):
        part = part.strip()
        if "-" in part:
            lo, hi = part.split("-")
            n += int(hi.strip()[1:]) - int(lo.strip()[1:]) + 1
        elif part:
            n += 1
    return n


def estimate_cycles(trace, insns, pipeline=2, div=12):
    """Cycles of a trace by the Cortex-M4 instruction timings (ARM DDI 0439B, 3.3.1):
    1 per data-processing and multiply or MAC instruction, 2 per single load or store
    (1 when it directly follows another single load or store: their phases pipeline),
    1 + N for LDM / STM / PUSH / POP and LDRD / STRD, taken branches 1 + P, SDIV / UDIV
    `div`, TBB / TBH 2 + P, + P when the PC is loaded; P (pipeline refill, 1..3) =
    `pipeline`.  An instruction skipped inside an IT block still costs 1.  Memory wait
    states are not modelled."""
    cyc = 0
    prev_ls = False
    for i, (addr, size) in enumerate(trace):
        mn, ops, _ = insns.get(addr, ("?", "", size))
        base = mn.split(".")[0]
        nxt = trace[i + 1][0] if i + 1 < len(trace) else None
        taken = nxt is not None and nxt != addr + size
        ls_single = bool(re.match(r"^(ldr|str)(b|h|sb|sh|ex|exb|exh)?([a-z]{2})?$", base)) \
            and not base.startswith(("ldrd", "strd"))
        if base.startswith("it") and len(base) <= 4 and all(c in "te" for c in base[2:]):
            c = 1
            k = len(base) - 1                       # it, itt, ite, ...: 1 .. 4 instructions
            # the IT block's instructions in program order; the skipped ones are absent
            a = addr + size
            block = []
            for _ in range(k):
                block.append(a)
                a += insns[a][2] if a in insns else 2
            j = i + 1
            done = 0
            while j < len(trace) and done < k and trace[j][0] in block:
                j += 1
                done += 1
            c += k - done
        elif base in ("push", "pop", "stm", "stmia", "stmdb", "ldm", "ldmia", "ldmdb", "stmfd",
                      "ldmfd"):
            c = 1 + _nregs(ops)
            if base in ("pop", "ldm", "ldmia", "ldmfd") and "pc" in ops:
                c += pipeline
        elif base in ("ldrd", "strd"):
            c = 3
        elif ls_single:
            c = 1 if prev_ls else 2
            if base.startswith("ldr") and ops.startswith("pc"):
                c += pipeline
        elif base in ("sdiv", "udiv"):
            c = div
        elif base in ("tbb", "tbh"):
            c = 2 + pipeline
        elif base.startswith("b") and base not in ("bic", "bics", "bfi", "bfc"):
            c = 1 + pipeline if (taken or base in ("bl", "blx", "bx")) else 1
        elif base.startswith(("cbz", "cbnz")):
            c = 1 + pipeline if taken else 1
        else:
            c = 1
        prev_ls = ls_single
        cyc += c
    return cyc


def breakdown(t, trace):
    """[(function, its own instructions, calls)] of a trace, largest first; a call is an
    execution of the function's first instruction."""
    per = {}
    starts = {a: n for a, _, n in t.funcs}
    for addr, _ in trace:
        fn = t.func_of(addr)
        ins, calls = per.get(fn, (0, 0))
        per[fn] = (ins + 1, calls + (1 if starts.get(addr) == fn else 0))
    return sorted(((f, i, c) for f, (i, c) in per.items()), key=lambda x: -x[1])


# ------------------------------------------------------------------ drive bench

HDR = struct.Struct("<8I8i8i")


def static_bounds(elf, names):
    """The static bound (tools/bench/wcet.py) of each named function of the image: the
    longest path in instructions and in estimated cycles over every input, and the calls on
    the longest path in instructions."""
    image = wcet.Image(elf)
    ins, cyc = wcet.Analysis(image, "instructions"), wcet.Analysis(image, "cycles")
    out = {}
    try:
        for n in names:
            out[n] = {"instructions": ins.of(n), "cycles": cyc.of(n),
                      "path": [c for c, _ in ins.path.get(n, [])]}
    except wcet.Refused as e:
        raise RuntimeError(f"static bound: {e}") from e
    return out


def drive_bench(elf, rec_path, insns, sample_ms=50):
    with open(rec_path, "rb") as f:
        data = f.read()
    h = HDR.unpack_from(data, 0)
    magic, version, n_per, n_ticks, ppm, per_off, tick_off, warm = h[:8]
    probe_warm, probe_end = list(h[8:16]), list(h[16:24])
    if magic != 0x50524251 or version != 1:
        raise RuntimeError(f"{rec_path}: not a bench recording")
    plain = Target(elf, rec=data)                  # the replay, at full speed
    t = Target(elf, rec=data, counting=True)       # every counted call
    if plain.call("bench_setup")[0] != 0:
        raise RuntimeError("qfoc_drive_init refused the reference table")
    drv = t.addr("bench_drive")
    res = t.addr("bench_res")
    res2 = res + 64
    probe_at = t.addr("bench_probe_out")
    tx_len_off = t.info[INFO["tick_tx_len"]]
    can_off = t.info[INFO["tick_can_send"]]
    subs = {(0, 1): "PRECHARGE / BUS_WAIT", (0, 2): "PRECHARGE / CALIB", (1, 0): "STOP",
            (2, 3): "RUN / ALIGN", (2, 4): "RUN / OPEN_LOOP", (2, 5): "RUN / CLOSED_LOOP",
            (2, 6): "RUN / STOPPING", (2, 7): "RUN / CATCH", (3, 0): "ERROR"}
    mismatch = 0

    def probe():
        plain.call("bench_probe")
        return list(struct.unpack("<8i", plain.read(probe_at, 32)))

    def period(k, trace=False):
        """Period k (and its tick) counted on t, from and back to the plain target's RAM."""
        nonlocal mismatch
        t.set_ram(plain.ram())
        adc = REC_BASE + per_off + 16 * k
        _, n, used, tr = t.call("qfoc_drive_fast_step", res, drv, adc, trace=trace)
        cmp0, cmp1, cmp2, en = struct.unpack("<3HB", t.read(res, 7))
        rec = struct.unpack_from("<8H", data, per_off + 16 * k)
        if (cmp0, cmp1, cmp2, en) != (rec[3], rec[4], rec[5], rec[6]):
            mismatch += 1
        tick = None
        if (k + 1) % ppm == 0:
            ms = (k + 1) // ppm - 1
            inp = t.call("bench_tick_input", REC_BASE, ms)[0]
            if inp == 0:
                raise RuntimeError("bench_tick_input: outside the recording")
            _, tn, tused, ttr = t.call("qfoc_drive_tick", res2, drv, inp, trace=trace)
            out = t.read(res2, t.info[INFO["sizeof_tick_out"]])
            rx_len = data[tick_off + 16 * ms + 4]
            tick = {"n": tn, "stack": tused, "trace": ttr, "job100": out[can_off] != 0,
                    "answered": out[tx_len_off] != 0, "frame": rx_len > 0}
        plain.set_ram(t.ram())
        return n, used, tr, tick

    # warm-up: replayed uncounted, one fast step counted every sample_ms, by sub-state
    t0 = time.time()
    by_sub = {}
    step = sample_ms * ppm
    # the periods that enter RUN (the output enable of the recording goes from off to on):
    # the fast half restarts its estimator, current PIs and monitors there, then controls
    entries = [j for j in range(1, warm)
               if struct.unpack_from("<8H", data, per_off + 16 * j)[6] and
               not struct.unpack_from("<8H", data, per_off + 16 * (j - 1))[6]]
    k = 0
    while k < warm:
        nxt = min(k + step, warm) - 1             # the sampled period
        pending = [j for j in entries if k <= j < nxt]
        if pending:
            nxt = pending[0]
        if nxt > k:
            bad = plain.call("bench_replay", REC_BASE, k, nxt - k)[0]
            if bad:
                raise RuntimeError(f"replay: {bad} periods differ from the host build")
        st = probe()
        n, _, _, _ = period(nxt)
        name = subs.get((st[0], st[1]), f"{st[0]}/{st[1]}")
        if nxt in entries:
            name = "RUN entry (first controlled period, after " + name + ")"
        lo, hi, cnt = by_sub.get(name, (n, n, 0))
        by_sub[name] = (min(lo, n), max(hi, n), cnt + 1)
        k = nxt + 1
    warm_s = time.time() - t0
    got = probe()
    if got != probe_warm:
        raise RuntimeError(f"state after the warm-up {got} differs from the host's {probe_warm}")
    # the measured window: every fast step and tick counted, the state probed every tick
    held = 0
    fast = []
    ticks = []
    best_fast = None
    best_tick = None
    stack_fast = 0
    stack_tick = 0
    for k in range(warm, n_per):
        n, used, tr, tick = period(k, trace=True)
        fast.append(n)
        stack_fast = max(stack_fast, used)
        if best_fast is None or n > best_fast[0]:
            best_fast = (n, tr)
        if tick is not None:
            st = probe()
            if st[0] == 2 and st[1] == 5 and st[2] < 0:
                held += 1
            ticks.append(tick)
            stack_tick = max(stack_tick, tick["stack"])
            if best_tick is None or tick["n"] > best_tick[0]:
                best_tick = (tick["n"], tick["trace"])
    got_end = probe()
    if got_end != probe_end:
        raise RuntimeError(f"state at the end {got_end} differs from the host's {probe_end}")
    if mismatch:
        raise RuntimeError(f"{mismatch} fast steps differ from the host build's output")
    plain = [x["n"] for x in ticks if not x["job100"] and not x["frame"]]
    framed = [x["n"] for x in ticks if not x["job100"] and x["frame"]]
    job = [x["n"] for x in ticks if x["job100"]]
    cyc_fast = estimate_cycles(best_fast[1], insns)
    cyc_tick = estimate_cycles(best_tick[1], insns)
    return {
        "recording": rec_path, "warm_periods": warm, "window_periods": n_per - warm,
        "window_ticks": len(ticks), "periods_per_ms": ppm,
        "state": {"warm": probe_warm, "end": probe_end,
                  "fields": ["state", "sub", "id_fw", "utilisation", "speed_f", "tc_a1",
                             "tc_b1", "iq_ref"]},
        "outputs_match_host": True, "replay_wall_s": round(warm_s, 2), "mismatches": mismatch,
        "ticks_closed_loop_fw": held,
        "fast": {"min": min(fast), "max": max(fast), "mean": round(sum(fast) / len(fast), 1),
                 "cycles_est_max": cyc_fast, "stack_bytes_seen": stack_fast,
                 "breakdown": breakdown(t, best_fast[1])},
        "tick": {"min": min(x["n"] for x in ticks), "max": max(x["n"] for x in ticks),
                 "plain_max": max(plain) if plain else None,
                 "frame_max": max(framed) if framed else None,
                 "job100_max": max(job) if job else None, "job100_count": len(job),
                 "cycles_est_max": cyc_tick, "stack_bytes_seen": stack_tick,
                 "breakdown": breakdown(t, best_tick[1])},
        "by_sub": {k: {"min": v[0], "max": v[1], "samples": v[2]} for k, v in by_sub.items()},
    }


# ------------------------------------------------------------------ sizes

def sizes(size_tool, obj_dir, drive_elf, t):
    lib = sorted(os.path.join(obj_dir, f) for f in os.listdir(obj_dir)
                 if f.startswith("qfoc_") and f.endswith(".o"))
    out = subprocess.run([size_tool] + lib, check=True, capture_output=True, text=True).stdout
    per = {}
    tot = [0, 0, 0]
    for line in out.splitlines()[1:]:
        parts = line.split()
        text, dat, bss = int(parts[0]), int(parts[1]), int(parts[2])
        per[os.path.basename(parts[5])] = text
        tot = [tot[0] + text, tot[1] + dat, tot[2] + bss]
    # the part a drive firmware links: symbols of the library in the --gc-sections image
    lib_syms = set()
    for o in lib:
        with open(o, "rb") as f:
            for s in ELFFile(f).get_section_by_name(".symtab").iter_symbols():
                if s["st_info"]["type"] in ("STT_FUNC", "STT_OBJECT") and s["st_shndx"] != "SHN_UNDEF":
                    lib_syms.add(s.name)
    used = 0
    linked = set()
    with open(drive_elf, "rb") as f:
        for s in ELFFile(f).get_section_by_name(".symtab").iter_symbols():
            if s["st_info"]["type"] in ("STT_FUNC", "STT_OBJECT") and s.name in lib_syms:
                used += s["st_size"]
                linked.add(s.name)
    # what a drive does not link, by object
    unused = {}
    for o in lib:
        with open(o, "rb") as f:
            for s in ELFFile(f).get_section_by_name(".symtab").iter_symbols():
                if (s["st_info"]["type"] in ("STT_FUNC", "STT_OBJECT") and s["st_shndx"] != "SHN_UNDEF"
                        and s.name not in linked):
                    k = os.path.basename(o)
                    unused[k] = unused.get(k, 0) + s["st_size"]
    return {"lib_text_rodata": tot[0], "lib_data": tot[1], "lib_bss": tot[2], "per_object": per,
            "drive_linked": used, "drive_unused_by_object": unused,
            "sizeof_drive": t.info[INFO["sizeof_drive"]],
            "sizeof_fast": t.info[INFO["sizeof_fast"]], "sizeof_slow": t.info[INFO["sizeof_slow"]],
            "sizeof_table": t.info[INFO["sizeof_table"]]}


# ------------------------------------------------------------------ report

def verdict(value, limit):
    if limit is None or value is None:
        return "-"
    return "OK" if value <= limit else "OVER"


def cpu_load(cyc_fast, cyc_tick, f_pwm_hz):
    """Per cent of an 80 MHz CPU taken by a fast step every PWM period and a tick every
    millisecond, each at its bound in cycles."""
    return round(100.0 * (cyc_fast * f_pwm_hz + cyc_tick * 1000.0) / F_CPU_HZ, 1)


def kib(n):
    return f"{n} B ({n / 1024:.1f} KiB)"


COST_NOTES = {
    "qfoc_drive_fast_step": "measurement, over-current check, references, decoupling "
                            "feed-forward, the advance angle, and the drive's inlined helpers",
    "qfoc_lpf_step": "low-pass with a Q31 state (64-bit product, rounding, saturation): DC bus, "
                     "PLL speed, field-weakening utilisation, the phase monitor (one phase "
                     "a period, in turn)",
    "qfoc_pi_step": "PI in 64-bit Q31 with shifted gains, anti-windup and rounding: d and q "
                    "currents, PLL, field weakening",
    "qfoc_vec_mag": "magnitude (saturation decided on the squares): PLL input, SVPWM "
                    "utilisation",
    "qfoc_isqrt32": "floor square root: range estimate, three Newton steps (unsigned "
                    "divisions), at most one correction: PLL, SVPWM, circle limit",
    "qfoc_sin": "quarter-wave table with interpolation, twice per `qfoc_sincos`",
    "qfoc_sincos": "control angle, advanced angle, PLL, torque compensation (1x; the 2x "
                   "harmonic from it by the double-angle identities)",
    "qfoc_svpwm_step": "SVPWM without the magnitude (see below)",
    "qfoc_svpwm_step_lin": "SVPWM after the circle limit: configuration check, bus clamp "
                           "(no magnitude, no overmodulation limit, no utilisation)",
    "svpwm_core.isra.0": "SVPWM phase times (one division), dead-time compensation, sector, "
                         "min-max injection, clamp",
    "qfoc_park_sym": "Park of the measured current, without the input clamps (the drive's "
                     "factors are proved in range, src/qfoc_fast.h)",
    "qfoc_inv_park_sym": "inverse Park of the voltage command, without the input clamps",
    "qfoc_circle_limit": "voltage limit V_dc / sqrt 3; when the vector is outside, the q room "
                         "left by a square root",
    "qfoc_flux_axis": "flux observer, per axis (2-19 .. 2-24)",
    "qfoc_pll_loop": "PLL phase detector (normalised, clamped error) and angle update",
    "qfoc_flux_step": "flux observer",
    "qfoc_trqcomp_output": "torque-compensation feed-forward, two harmonics",
    "qfoc_phase_mon_update_one": "phase-loss monitor: |i| of one phase a period, in turn",
}


PIL_IRQS = (("adc1", "ADC1 conversion complete (IRQ 40, priority 1): `qfoc_s32k_adc_isr`, the fast step"),
            ("lpit0", "LPIT0 1 ms (IRQ 48, priority 3): `qfoc_s32k_tick_isr`, the tick"),
            ("ftm3", "FTM3 period (IRQ 122, priority 2)"),
            ("lpuart1", "LPUART1 (IRQ 33, priority 4): LIN"))


def pil_section(r):
    """The firmware image's measured timing (make pil, build/pil/timing.json) beside the
    static bounds and the bench's measured figures (REQ-PIL-006)."""
    pil = r.get("pil")
    sb = r["static"]
    dr = r["drive"]
    L = ["## The firmware image in the loop (`make pil`)\n"]
    if not pil:
        L.append("Not reported: no `build/pil/timing.json` (run `make pil` before `make bench`).\n")
        return L

    def mmm(x, f="{}"):
        return "-" if not x else f"{x['min']} / {x['mean']} / {x['max']}"
    L.append(f"The image `{pil['image']}` (SHA-256 `{pil['image_sha256'][:16]}`) run from reset in "
             f"`port_s32k/pil/` over the scenarios of `make pil` ({', '.join(pil['runs'])}; "
             f"{'all passed' if pil['all_passed'] else 'NOT ALL PASSED'}; {pil['run_utc']}).  "
             "One instruction is one clock at 80 MHz there (no wait states); an instruction of "
             "an IT block counts whether its condition holds or not, as in the static bound "
             "(the bench's own counts skip those whose condition fails, so they may be a few "
             "below the image's on the same path).  The library's entry points: instructions "
             "from their first to their return instruction, callees included, nested handlers "
             "excluded; the static bound of `tools/bench/wcet.py` on the bench's image and on "
             "the firmware image; a measured count above either is UNSOUND and fails the "
             "bench.\n")
    L.append("| entry point | static bound (bench image) | static bound (firmware image) | "
             "bench measured max (windows and start-ups) | firmware image min / mean / max | "
             "calls | longest in |")
    L.append("|---|---:|---:|---:|---:|---:|---|")
    for e, k in (("qfoc_drive_fast_step", "fast"), ("qfoc_drive_tick", "tick")):
        m = pil["lib"].get(e)
        bench_max = max(d[k]["max"] for d in dr.values())
        if k == "fast":
            bench_max = max([bench_max] + [v["max"] for d in dr.values() for v in d["by_sub"].values()])
        L.append(f"| `{e}` | {sb[e]['instructions']} | {pil['static_bound'][e]} | "
                 f"{bench_max} | {mmm(m)} | "
                 f"{m['n'] if m else '-'} | {m['max_in'] if m else '-'} |")
    L.append("")
    L.append("The image's interrupts (instructions: the handler's own, nested handlers "
             "excluded; clocks: with the exception entry, 12, 6 when tail-chained, and the "
             "return, 10; latency: the request to the handler's first instruction):\n")
    L.append("| interrupt | count | instructions min / mean / max | clocks with entry and return "
             "| latency, clocks | longest in |")
    L.append("|---|---:|---:|---:|---:|---|")
    for key, label in PIL_IRQS:
        x = pil["irqs"].get(key, {})
        ins = x.get("instructions")
        L.append(f"| {label} | {ins['n'] if ins else 0} | {mmm(ins)} | {mmm(x.get('clocks'))} | "
                 f"{mmm(x.get('latency'))} | {ins['max_in'] if ins else '-'} |")
    s2l = pil.get("sample_to_ldok")
    L.append("")
    if s2l:
        L.append(f"Sampling instant (PDB1 pre-trigger 0, the reload point) to the compare values "
                 f"loaded (the PWMLOAD[LDOK] write of the ADC1 handler): {mmm(s2l)} clocks = "
                 f"{s2l['max'] / F_CPU_HZ * 1e6:.1f} us at most, against the next reload point "
                 f"one PWM period later.\n")
    return L


def write_report(md_path, r):
    fn = r["functions"]
    dr = r["drive"]
    sz = r["sizes"]
    st = r["stack"]
    main = dr[r["main_scenario"]]
    rows = []

    sb = r["static"]

    def row(req, item, lo, hi, limit, unit="", v=None, goal=None, static=None, gated="max"):
        """gated: the figure the limit and the goal apply to, the measured max or the static
        bound; a measured max above the static bound is UNSOUND (the bench fails)."""
        value = static if gated == "static" else hi
        if v is None:
            v = verdict(value, limit)
            if static is not None and hi is not None and hi > static:
                v = "UNSOUND"
        rows.append((item, lo, hi, limit, v, unit, req, goal, verdict(value, goal), static))

    fs, tk = sb["qfoc_drive_fast_step"], sb["qfoc_drive_tick"]
    row("REQ-BENCH-008", "`qfoc_drive_fast_step`, static bound (every input, every state)", None,
        None, STATIC_LIMIT_FAST_STEP, "instructions", goal=GOAL_FAST_STEP,
        static=fs["instructions"], gated="static")
    row("REQ-BENCH-008", "`qfoc_drive_tick`, static bound (every input, every state, every kind "
        "of tick)", None, None, STATIC_LIMIT_TICK, "instructions", goal=GOAL_TICK,
        static=tk["instructions"], gated="static")
    if "qfoc_ident_step" in sb:
        row("REQ-IDENT-002", "`qfoc_ident_step`, static bound (the identification's period, "
            "in place of the fast step while the drive is stopped; not on the drive's path)",
            None, None, None, "instructions", static=sb["qfoc_ident_step"]["instructions"],
            gated="static")
    if "qfoc_commission_fast_step" in sb:
        row("REQ-IDENT-007", "`qfoc_commission_fast_step`, static bound (the fast step of a "
            "firmware that commissions: the drive's fast step or the identification's, one "
            "of the two, every input, every state; the fast step's limit)", None, None,
            STATIC_LIMIT_FAST_STEP, "instructions",
            static=sb["qfoc_commission_fast_step"]["instructions"], gated="static")
    if "qfoc_drive_shunt_measure" in sb and "qfoc_drive_shunt_plan" in sb:
        row("REQ-SHUNT-006", "single-shunt period, static bound: `qfoc_drive_shunt_measure` + "
            "`qfoc_drive_fast_step` + `qfoc_drive_shunt_output` + `qfoc_drive_shunt_plan` "
            "(every input, every state; reported beside the fast step's limit, not gated)",
            None, None, None, "instructions",
            static=(sb["qfoc_drive_shunt_measure"]["instructions"] + fs["instructions"]
                    + sb["qfoc_drive_shunt_output"]["instructions"]
                    + sb["qfoc_drive_shunt_plan"]["instructions"]), gated="static")
    row("REQ-BENCH-008", "CPU load at 16 kHz and 80 MHz, fast step + tick, static bounds in "
        "estimated cycles", None, None, None, "% of the CPU", goal=GOAL_LOAD_PCT,
        static=cpu_load(fs["cycles"], tk["cycles"], 16000), gated="static")
    for name, d in dr.items():
        row("REQ-BENCH-002", f"`qfoc_drive_fast_step`, {d['title']}", d["fast"]["min"],
            d["fast"]["max"], LIMIT_FAST_STEP, "instructions", static=fs["instructions"])
    for name, d in dr.items():
        if d["by_sub"]:
            row("REQ-BENCH-002", f"`qfoc_drive_fast_step`, start-up of the recording of "
                f"{d['title'].split(',')[0]} (a period every 50 ms and every RUN entry)",
                min(v["min"] for v in d["by_sub"].values()),
                max(v["max"] for v in d["by_sub"].values()), LIMIT_FAST_STEP, "instructions",
                static=fs["instructions"])
    for name, d in dr.items():
        row("REQ-BENCH-002", f"`qfoc_drive_tick`, {d['title']} (100 ms job included)",
            d["tick"]["min"], d["tick"]["max"], LIMIT_TICK, "instructions",
            static=tk["instructions"])
    for key, f in fn.items():
        row("REQ-BENCH-003" if f["limit"] is not None else "REQ-BENCH-001", f["label"], f["min"],
            f["max"], f["limit"], "instructions", goal=f.get("goal"), static=f["static"],
            gated="static")
    pil = r.get("pil")
    if pil:
        for e, what in (("qfoc_drive_fast_step", fs), ("qfoc_drive_tick", tk)):
            m = pil["lib"].get(e)
            if m:
                row("REQ-PIL-006", f"`{e}`, the firmware image in the loop (`make pil`, "
                    f"{len(pil['runs'])} scenarios, {m['n']} calls; static bound of the image "
                    f"{pil['static_bound'][e]})", m["min"], m["max"], None, "instructions",
                    static=min(what["instructions"], pil["static_bound"][e]))
    row("REQ-BENCH-003", "the drive's SVPWM chain in the fast step (`qfoc_circle_limit` + "
        "`qfoc_svpwm_step_lin`)", None, None, LIMIT_SVPWM_CHAIN, "instructions",
        goal=GOAL_SVPWM_CHAIN, static=sum(sb[n]["instructions"] for n in SVPWM_CHAIN),
        gated="static")
    row("REQ-BENCH-004", "library flash, all of `src/` (text + rodata)", None,
        sz["lib_text_rodata"], LIMIT_FLASH, "bytes", goal=GOAL_FLASH)
    row("REQ-BENCH-004", "library flash a drive links (`--gc-sections`, 3 entry points)", None,
        sz["drive_linked"], LIMIT_FLASH_DRIVE, "bytes", goal=GOAL_FLASH_DRIVE)
    row("REQ-BENCH-004", "parameter table, `sizeof(qfoc_param_table_t)` (flash)", None,
        sz["sizeof_table"], None, "bytes")
    ram = sz["lib_data"] + sz["lib_bss"]
    row("REQ-BENCH-005", "library RAM (data + bss)", None, ram, 0, "bytes")
    row("REQ-BENCH-005", "RAM per motor, `sizeof(qfoc_drive_t)`", None, sz["sizeof_drive"],
        LIMIT_RAM_MOTOR, "bytes")
    compared = sum(d["warm_periods"] + d["window_periods"] for d in dr.values())
    row("REQ-BENCH-007", f"periods whose output differs from the host build's ({compared} "
        "compared)", None, 0, 0, "periods")
    for e, seen, limit in (("qfoc_drive_fast_step", main["fast"]["stack_bytes_seen"], LIMIT_STACK_FAST),
                           ("qfoc_drive_tick", main["tick"]["stack_bytes_seen"], None),
                           ("qfoc_drive_init", None, None)):
        se = st[e]
        sound = se["bounded"] and (seen is None or seen <= se["bytes"])
        v = verdict(se["bytes"], limit) if sound else "UNBOUNDED"
        row("REQ-BENCH-006", f"stack, `{e}` (" + ("seen / " if seen is not None else "")
            + "static worst case)", seen, se["bytes"], limit, "bytes",
            v if limit is not None or not sound else "-")

    def cell(x):
        return "-" if x is None else str(x)

    L = []
    L.append("# qfoc on the Cortex-M4F: instructions, sizes, stack\n")
    L.append(f"Build: `{r['cc']}` with the project's `ARM_CFLAGS` (`{r['cflags']}`); "
             "the library objects, `tables/reference_params.c` and `tools/bench/harness.c` linked "
             "into `build/bench/bench.elf` (`tools/bench/bench.ld`).  Instructions executed from a "
             "function's entry to its return, counted in Unicorn "
             f"{r['unicorn']} (Cortex-M4, Thumb-2) by `tools/bench/count.py`; "
             + ("the longest case of every function, run a second time from the same state, "
                "gave the same count.\n" if all(f["repeatable"] for f in fn.values()) else
                "NOTE: a repeated case gave a different count (see bench.json, `repeatable`).\n"))
    L.append("| item | min | max | static bound | limit | result | goal | goal met | unit "
             "| requirement |")
    L.append("|---|---:|---:|---:|---:|---|---:|---|---|---|")
    for item, lo, hi, limit, v, unit, req, goal, gv, stat in rows:
        gm = {"OK": "yes", "OVER": "no"}.get(gv, "-")
        L.append(f"| {item} | {cell(lo)} | {cell(hi)} | {cell(stat)} | {cell(limit)} | {v} "
                 f"| {cell(goal)} | {gm} | {unit} | {req} |")
    L.append("")
    budgets = ", ".join(f"`{fn[k]['symbol']}` {lim}" + (f" (goal {g})" if g else "")
                        for k, (lim, g) in FUNC_BUDGET.items() if k in fn)
    L.append(f"Limits (enforced: a figure above its limit fails `make bench` and `make check`; "
             f"rationale in `specs/requirements/bench.md`): static bounds (every input) of the fast "
             f"step {STATIC_LIMIT_FAST_STEP} (goal {GOAL_FAST_STEP}) and of the tick "
             f"{STATIC_LIMIT_TICK} (goal {GOAL_TICK}) instructions; the longest paths measured at "
             f"the operating points, fast step {LIMIT_FAST_STEP} and tick {LIMIT_TICK}; per "
             f"function, instructions on its static bound: {budgets}; the drive's SVPWM chain "
             f"{LIMIT_SVPWM_CHAIN} (goal {GOAL_SVPWM_CHAIN}); a measured figure above the static "
             "bound of its function is UNSOUND and fails the bench; library "
             f"flash {LIMIT_FLASH} B (goal {GOAL_FLASH}), the part a drive links "
             f"{LIMIT_FLASH_DRIVE} B (goal {GOAL_FLASH_DRIVE}); no static RAM, {LIMIT_RAM_MOTOR} B "
             f"of RAM per motor, fast-step stack {LIMIT_STACK_FAST} B, no output differing from "
             "the host build.  Each limit is the figure reached plus at most 10 %; the goals are "
             "the project's targets (for the functions, within about 1.3 times the instructions "
             "of established motor-control libraries built the same way, which truncate instead "
             "of rounding and do not saturate symmetrically); the CPU-load goal is "
             f"{GOAL_LOAD_PCT} % at 16 kHz and 80 MHz.  A `-` is a figure reported "
             "without a limit or goal.  For the stack rows, min is the deepest stack seen in the "
             "emulator (painted stack) and max the static worst case from the call graph.\n")
    # the static bound
    fs, tk = sb["qfoc_drive_fast_step"], sb["qfoc_drive_tick"]
    L.append("## The static bound: a worst case no input can exceed\n")
    L.append("`tools/bench/wcet.py` reads the linked image, builds each function's control-flow "
             "graph from its disassembly (capstone, Thumb-2; data in the code skipped through the "
             "ELF's mapping symbols; TBB / TBH tables read with the compare that bounds their "
             "index), and takes the longest path from the entry to any return, each call counted "
             "as the callee's own bound.  Every instruction of an IT block counts, whether its "
             "condition holds or not; a branch counts as taken.  A loop counts its bound plus one "
             "times its longest iteration; the bounds, and where in the code each comes from:\n")
    L.append("| function | iterations at most | source of the bound |")
    L.append("|---|---:|---|")
    for name, (n, why) in sorted(wcet.LOOP_BOUNDS.items()):
        L.append(f"| `{name}` | {n} | {why} |")
    L.append("")
    L.append("An indirect branch other than a bounded table, a call through a register, a loop "
             "without a bound or recursion makes the bench fail.  The bound does not know which "
             "paths the state cannot take together (the tick's bound adds the flying start, the "
             "bumpless transfer, the learning of the torque compensation, a step of the table "
             "scan and the 100 ms job's frames, which no single tick runs all together), so it is "
             "above every measured path; it is the figure to plan with.  Every measured function "
             "and entry point is checked against it (a measured count above its bound fails the "
             "bench as UNSOUND).\n")
    L.append("| entry point | static bound, instructions | measured max | static bound, "
             "estimated cycles | at 80 MHz |")
    L.append("|---|---:|---:|---:|---:|")
    L.append(f"| `qfoc_drive_fast_step` | {fs['instructions']} | "
             f"{max(d['fast']['max'] for d in dr.values())} | {fs['cycles']} | "
             f"{fs['cycles'] / F_CPU_HZ * 1e6:.1f} us |")
    L.append(f"| `qfoc_drive_tick` | {tk['instructions']} | "
             f"{max(d['tick']['max'] for d in dr.values())} | {tk['cycles']} | "
             f"{tk['cycles'] / F_CPU_HZ * 1e6:.1f} us |")
    ini = sb["qfoc_drive_init"]
    L.append(f"| `qfoc_drive_init` | {ini['instructions']} | - | {ini['cycles']} | "
             f"{ini['cycles'] / F_CPU_HZ * 1e6:.1f} us |")
    L.append("")
    L.append("CPU load of the drive at 80 MHz, a fast step every PWM period and a tick every "
             "millisecond, both at their static bounds in estimated cycles (the Cortex-M4 "
             "timings of the section below taken at their worst: every load 2 cycles, every "
             "branch taken, every division 12 cycles; no flash wait states):\n")
    L.append("| PWM frequency | period | fast step | tick (1 kHz) | load |")
    L.append("|---:|---:|---:|---:|---:|")
    for f_pwm in LOAD_F_PWM_HZ:
        L.append(f"| {f_pwm / 1000:g} kHz | {1e6 / f_pwm:.1f} us | "
                 f"{100.0 * fs['cycles'] * f_pwm / F_CPU_HZ:.1f} % | "
                 f"{100.0 * tk['cycles'] * 1000.0 / F_CPU_HZ:.1f} % | "
                 f"{cpu_load(fs['cycles'], tk['cycles'], f_pwm):.1f} % |")
    L.append("")
    for e in ("qfoc_drive_fast_step", "qfoc_drive_tick"):
        L.append(f"Calls on the longest static path of `{e}`: "
                 + ", ".join(f"`{c}` {sb[c]['instructions'] if c in sb else ''}".rstrip()
                             for c in sb[e]["path"]) + ".\n")
    L.extend(pil_section(r))
    # what costs the instructions
    L.append("## What costs the instructions\n")
    f = main["fast"]
    L.append(f"The longest fast step of {main['title']}: {f['max']} instructions (limit "
             f"{LIMIT_FAST_STEP}; static bound {fs['instructions']}, goal {GOAL_FAST_STEP}).  "
             "Every block is a "
             "function of its own unit (no inlining across units); every one saturates and "
             "rounds its results, and all but the Park steps of src/qfoc_fast.h accept any input "
             "value.  The observer's phase lead (`qfoc_flux_lead`, an arc tangent) and the "
             "voltage utilisation for field weakening (a magnitude and a division) are computed "
             "by the tick, once a millisecond; the SVPWM runs without its own limit after the "
             "circle limit (`qfoc_svpwm_step_lin`), the phase monitor filters one phase a period; "
             "the largest shares:\n")
    L.append("| function | instructions | calls | per call | what it does there |")
    L.append("|---|---:|---:|---:|---|")
    for fname, n, c in f["breakdown"][:10]:
        per = f"{n / c:.0f}" if c else "-"
        L.append(f"| `{fname}` | {n} | {c} | {per} | {COST_NOTES.get(fname, '')} |")
    rest = sum(n for _, n, _ in f["breakdown"][10:])
    L.append(f"| the other {len(f['breakdown']) - 10} functions | {rest} | | | |")
    L.append("")
    L.append("Functions against their goals: `qfoc_clarke` "
             f"{fn['clarke']['min']}..{fn['clarke']['max']} "
             f"(goal {FUNC_BUDGET['clarke'][1]}) and `qfoc_park` {fn['park']['min']}..{fn['park']['max']} "
             f"(goal {FUNC_BUDGET['park'][1]}): the products are rounded to nearest (ties away from zero) "
             "and each output is saturated to the symmetric Q15 range, a compare and a "
             "conditional move or two per bound, on top of the multiplies; the longest cases "
             "are at the corners of the input range.  `qfoc_svpwm_step` "
             f"{fn['svpwm']['min']}..{fn['svpwm']['max']} (goal {FUNC_BUDGET['svpwm'][1]}): besides the "
             "min-max injection it computes the vector's magnitude (a square root by Newton steps, for "
             "the utilisation and the overmodulation limit), scales the vector onto the circle "
             "when it is outside, clamps the DC bus, divides for the phase times, adds the "
             "dead-time compensation per phase with its fade inside the current dead band (a "
             "division), finds the sector and clamps the three compare values.  Its longest case "
             f"({fn['svpwm']['max_case']}): "
             + ", ".join(f"`{n}` {i}" + (f" ({c} calls)" if c > 1 else "")
                         for n, i, c in fn["svpwm"]["max_breakdown"]) + ".\n")
    L.append(f"Tick: the table is re-checked in five steps of `qfoc_params_scan_step` on ticks "
             f"94 .. 98 of every 100 ms period (at most {fn['params_scan']['max']} "
             "instructions a step; the CRC-32 takes two lookups in a 16-entry table per byte, "
             "199 bytes; against "
             f"{fn['params_check']['max']} for the whole `qfoc_params_check` at initialisation); "
             f"the longest tick takes {main['tick']['max']} (every kind of tick counted: "
             "with a step of the scan, with a command frame answered, with the 100 ms job's "
             f"CAN frame: at most {cell(main['tick']['job100_max'])}).\n")
    big = sorted(sz["drive_unused_by_object"].items(), key=lambda kv: -kv[1])
    L.append(f"Flash: {sz['lib_text_rodata']} B for all of `src/` against the goal of "
             f"{GOAL_FLASH} (limit {LIMIT_FLASH}); a drive "
             f"firmware links {sz['drive_linked']} B of it.  Not linked by a drive (functions and "
             "constants no entry point reaches), by object: "
             + ", ".join(f"`{o}` {n} B" for o, n in big if n > 0) + ".  The largest object is "
             f"`qfoc_drive.o`, {sz['per_object'].get('qfoc_drive.o', 0)} B: the two entry points "
             "with the state handling, faults, start-up and command handling inlined.\n")
    # instructions are not cycles
    L.append("## Instructions are not cycles\n")
    L.append("A count is the number of instructions executed, not the time they take.  On the "
             "Cortex-M4 a single load takes 2 cycles (1 when it follows another load or store), "
             "LDM / STM / PUSH / POP 1 + N, a taken branch 1 + P (P = 1..3 for the pipeline refill), "
             "a division 2..12, and an instruction skipped inside an IT block still takes a cycle "
             "(the count leaves it out); flash wait states and cache misses come on top.  Estimate "
             "from these timings (ARM DDI 0439B, section 3.3.1; P = 2, division 12, zero wait "
             "states) on the longest traced path, at 80 MHz:\n")
    L.append("| entry point | instructions | estimated cycles | estimated time at 80 MHz "
             "| share of the period | share of a 16 kHz period (62.5 us) |")
    L.append("|---|---:|---:|---:|---:|---:|")
    for name, d in dr.items():
        c = d["fast"]["cycles_est_max"]
        L.append(f"| fast step, {d['title']} | {d['fast']['max']} | ~{c} | ~{c / F_CPU_HZ * 1e6:.1f} us "
                 f"| ~{100.0 * c / F_CPU_HZ * d['f_pwm_hz']:.1f} % of {1e6 / d['f_pwm_hz']:.0f} us "
                 f"| ~{100.0 * c / F_CPU_HZ * 16000.0:.1f} % |")
    for name, d in dr.items():
        c = d["tick"]["cycles_est_max"]
        L.append(f"| tick, {d['title']} | {d['tick']['max']} | ~{c} | ~{c / F_CPU_HZ * 1e6:.1f} us "
                 f"| ~{100.0 * c / F_CPU_HZ * 1e3:.2f} % of 1 ms | - |")
    L.append("\nThese are estimates only: the figure to rely on is a measurement on the part "
             "(DWT cycle counter around the call).\n")
    # the drive
    L.append("## The drive on its longest path\n")
    i_base = r["scale"]["i_base_a"]
    rpm_per_q15 = r["scale"]["rpm_per_q15"]
    for name, d in dr.items():
        s = d["state"]["warm"]
        m = d["meta"]
        L.append(f"### {d['title']}\n")
        L.append(f"Recording `{os.path.basename(d['recording'])}`, made on the host by "
                 f"`tools/bench/gen_replay.c`: the host build of the drive with table "
                 f"`{m['table']}` in closed loop with the plant model of {m['motor']} "
                 f"({m['vdc_v']:.0f} V, {m['f_pwm_hz']:.0f} Hz, current noise "
                 f"{m['noise_i_rms_a']} A rms, passive compressor load {m['load_nm']:.2f} N m"
                 + (f" with a {100 * m['pulse_1x']:.0f} % pulsation at 1x mechanical"
                    if m["pulse_1x"] > 0 else "")
                 + f"), cold start, command {m['target_rpm']} rpm.  Its {d['warm_periods']} "
                 f"periods of warm-up ({m['warm_s']:.3f} s) were replayed into the target build "
                 "(`bench_replay`), every output compared with the host build's: all equal, and "
                 "the drive's state equal to the host's at the start and at the end of the "
                 f"window.  Then the {d['window_periods']} periods and {d['window_ticks']} ticks "
                 f"of the window were counted one by one; the drive was in RUN / CLOSED_LOOP with "
                 f"field weakening active at {d['ticks_closed_loop_fw']} of the "
                 f"{d['window_ticks']} ticks.  At the start of the window: field-weakening i_d "
                 f"reference {s[2] / 32768 * i_base:.2f} A, utilisation {s[3] / 32768:.3f}, "
                 f"estimated speed {s[4] * rpm_per_q15:.0f} rpm, torque-compensation "
                 f"coefficients a1 {s[5] / 2**31 * i_base:.3f} A, b1 "
                 f"{s[6] / 2**31 * i_base:.3f} A"
                 + (" (speed inside the compensation's window: its output is computed every "
                    "period and it learns every tick)" if m["need_tc"] else
                    " (speed above the compensation's window: its output is 0 and costs "
                    "little)") + ".\n")
        f = d["fast"]
        L.append(f"Fast step: min {f['min']}, mean {f['mean']}, max {f['max']} instructions; "
                 f"deepest stack seen {f['stack_bytes_seen']} bytes.  Tick: plain "
                 f"{cell(d['tick']['plain_max'])}, with a command frame answered "
                 f"{cell(d['tick']['frame_max'])}, with the 100 ms job "
                 f"{cell(d['tick']['job100_max'])} instructions (max).\n")
        L.append("Where the instructions of the longest fast step go (each function's own "
                 "instructions; inlined code counts to its caller):\n")
        L.append("| function | instructions | calls |")
        L.append("|---|---:|---:|")
        for fname, n, c in f["breakdown"]:
            L.append(f"| `{fname}` | {n} | {c} |")
        L.append("")
        L.append("Longest tick:\n")
        L.append("| function | instructions | calls |")
        L.append("|---|---:|---:|")
        for fname, n, c in d["tick"]["breakdown"][:8]:
            L.append(f"| `{fname}` | {n} | {c} |")
        L.append("")
        if d["by_sub"]:
            L.append("Fast step during the warm-up (one period counted every 50 ms):\n")
            L.append("| state / sub-state | samples | min | max |")
            L.append("|---|---:|---:|---:|")
            for k, v in d["by_sub"].items():
                L.append(f"| {k} | {v['samples']} | {v['min']} | {v['max']} |")
            L.append("")
    # functions
    L.append("## Functions\n")
    L.append("| function | cases | min | max | static bound | static bound, cycles | longest case |")
    L.append("|---|---:|---:|---:|---:|---:|---|")
    for key, f in fn.items():
        L.append(f"| {f['label']} | {f['cases']} | {f['min']} | {f['max']} | {f['static']} | "
                 f"{f['static_cycles']} | {f['max_case']} |")
    L.append("")
    # sizes
    L.append("## Sizes\n")
    L.append("Library (`arm-none-eabi-size` of the -O2 objects): text + rodata "
             f"{kib(sz['lib_text_rodata'])}, "
             f"data {sz['lib_data']} B, bss {sz['lib_bss']} B.  The part of it a drive firmware links "
             f"(entry points `qfoc_drive_init`, `qfoc_drive_fast_step`, `qfoc_drive_tick`, "
             f"`--gc-sections`): {kib(sz['drive_linked'])}.  One motor: "
             f"`sizeof(qfoc_drive_t)` = {sz['sizeof_drive']} B (fast-step half "
             f"{sz['sizeof_fast']} B, tick half {sz['sizeof_slow']} B).  Parameter table: "
             f"{sz['sizeof_table']} B of flash per motor.\n")
    L.append("| object | text + rodata (bytes) |")
    L.append("|---|---:|")
    for o, n in sorted(sz["per_object"].items(), key=lambda kv: -kv[1]):
        L.append(f"| `{o}` | {n} |")
    L.append("")
    # stack
    L.append("## Stack\n")
    L.append("Static worst case: the frames of gcc's `-fstack-usage` summed along the deepest path "
             "of the `-fcallgraph-info=su` call graph from each entry point (`tools/bench/stack.py`). "
             "The exception entry of the interrupt that calls the fast step adds its own frame "
             "(32 bytes, 104 with the FPU context) to the interrupted stack.\n")
    L.append("| entry point | worst case (bytes) | deepest path | bounded |")
    L.append("|---|---:|---|---|")
    for e, s in st.items():
        path = " -> ".join(f"`{n}` {b}" for n, b in s["path"])
        flags = "yes" if s["bounded"] else ("no: " + ", ".join(
            (["recursion"] if s["recursion"] else [])
            + (["dynamic: " + ", ".join(s["dynamic"])] if s["dynamic"] else [])
            + (["unknown callee: " + ", ".join(s["unknown"])] if s["unknown"] else [])))
        L.append(f"| `{e}` | {cell(s['bytes'])} | {path} | {flags} |")
    L.append("")
    L.append(f"Dynamic frames (`.su` qualifier other than static): "
             f"{', '.join(r['dynamic_frames']) if r['dynamic_frames'] else 'none'}; recursion: "
             f"{'none' if not any(s['recursion'] for s in st.values()) else 'yes'}.\n")
    L.append(f"Run time of `tools/bench/count.py`: {r['wall_s']:.1f} s.\n")
    with open(md_path, "w", encoding="utf-8") as f:
        f.write("\n".join(L))
    return rows


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--elf", required=True)
    ap.add_argument("--drive-elf", required=True)
    ap.add_argument("--obj-dir", required=True)
    ap.add_argument("--replay", action="append", default=[],
                    help="NAME=FILE=TITLE (FILE.json from gen_replay beside it); the first "
                         "is the main scenario")
    ap.add_argument("--out-dir", required=True)
    ap.add_argument("--objdump", default="arm-none-eabi-objdump")
    ap.add_argument("--size", default="arm-none-eabi-size")
    ap.add_argument("--cc", default="arm-none-eabi-gcc")
    ap.add_argument("--cflags", default="")
    ap.add_argument("--pil-timing", default=None,
                    help="the firmware image's measured timing from make pil "
                         "(build/pil/timing.json, port_s32k/pil/timing.py); reported beside "
                         "the static bounds, a measured count above its bound fails the bench")
    o = ap.parse_args()
    t0 = time.time()
    try:
        import unicorn
        cc_version = subprocess.run([o.cc, "--version"], check=True, capture_output=True,
                                    text=True).stdout.splitlines()[0]
        t = Target(o.elf, counting=True)
        insns = disassembly(o.objdump, o.elf)
        functions = run_benches(t, build_benches(t, random.Random(20240607)))
        drive = {}
        for spec in o.replay:
            name, path, title = spec.split("=", 2)
            with open(path + ".json", encoding="utf-8") as f:
                meta = json.load(f)
            d = drive_bench(o.elf, path, insns)
            d["title"], d["meta"], d["f_pwm_hz"] = title, meta, meta["f_pwm_hz"]
            drive[name] = d
        sz = sizes(o.size, o.obj_dir, o.drive_elf, t)
        syms = sorted({f["symbol"] for f in functions.values()} | set(SVPWM_CHAIN)
                      | {"qfoc_drive_fast_step", "qfoc_drive_tick", "qfoc_drive_init",
                         "qfoc_ident_step", "qfoc_commission_fast_step",
                         "qfoc_drive_shunt_measure", "qfoc_drive_shunt_output",
                         "qfoc_drive_shunt_plan"})
        sb = static_bounds(o.elf, syms)
        for f in functions.values():
            f["static"] = sb[f["symbol"]]["instructions"]
            f["static_cycles"] = sb[f["symbol"]]["cycles"]
        t.call("bench_setup")
        i_ma, f_mhz, npp = struct.unpack("<3I", t.read(t.addr("bench_scale"), 12))
        scale = {"i_base_a": i_ma / 1000.0, "f_base_hz": f_mhz / 1000.0, "pole_pairs": npp,
                 "rpm_per_q15": f_mhz / 1000.0 * 60.0 / npp / 32768.0}
        st = stack.analyse(o.obj_dir, ["qfoc_drive_fast_step", "qfoc_drive_tick", "qfoc_drive_init"])
        dyn = stack.dynamic_frames(o.obj_dir)
    except (RuntimeError, UcError, KeyError, OSError, subprocess.CalledProcessError) as e:
        print(f"bench: {e}", file=sys.stderr)
        return 1
    pil = None
    if o.pil_timing and os.path.exists(o.pil_timing):
        with open(o.pil_timing, encoding="utf-8") as f:
            pil = json.load(f)
    r = {"cc": cc_version, "cflags": o.cflags, "unicorn": unicorn.__version__,
         "functions": functions, "drive": drive, "main_scenario": next(iter(drive)),
         "sizes": sz, "stack": st, "dynamic_frames": dyn, "scale": scale, "static": sb,
         "pil": pil}
    r["wall_s"] = time.time() - t0
    os.makedirs(o.out_dir, exist_ok=True)
    rows = write_report(os.path.join(o.out_dir, "bench.md"), r)
    r["table"] = [{"item": i, "min": lo, "max": hi, "static": st, "limit": lim, "result": v,
                   "unit": u, "requirement": q, "goal": g, "goal_result": gv}
                  for i, lo, hi, lim, v, u, q, g, gv, st in rows]
    with open(os.path.join(o.out_dir, "bench.json"), "w", encoding="utf-8") as f:
        json.dump(r, f, indent=1)
    limited = [x for x in rows if x[3] is not None]
    ok = sum(1 for x in limited if x[4] == "OK")
    goals = [x for x in rows if x[7] is not None]
    gok = sum(1 for x in goals if x[8] == "OK")
    main_d = drive[r["main_scenario"]]
    print(f"bench: static bounds fast step {sb['qfoc_drive_fast_step']['instructions']} "
          f"(limit {STATIC_LIMIT_FAST_STEP}, goal {GOAL_FAST_STEP}), tick "
          f"{sb['qfoc_drive_tick']['instructions']} ({STATIC_LIMIT_TICK}); measured fast step "
          f"{main_d['fast']['max']} instructions (limit {LIMIT_FAST_STEP}), tick {main_d['tick']['max']} ({LIMIT_TICK}), static clarke {functions['clarke']['static']} ({LIMIT_CLARKE}), "
          f"park {functions['park']['static']} ({LIMIT_PARK}), svpwm {functions['svpwm']['static']} "
          f"({LIMIT_SVPWM}), flash {sz['lib_text_rodata']} B ({LIMIT_FLASH}), RAM/motor "
          f"{sz['sizeof_drive']} B ({LIMIT_RAM_MOTOR}), fast-step stack "
          f"{st['qfoc_drive_fast_step']['bytes']} B ({LIMIT_STACK_FAST}): {ok} of {len(limited)} "
          f"limits met, {gok} of {len(goals)} goals met; {os.path.join(o.out_dir, 'bench.md')} "
          f"({r['wall_s']:.0f} s)")
    over = [x[0] for x in limited if x[4] != "OK"] + \
        [x[0] for x in rows if x[3] is None and x[4] == "UNSOUND"]
    for item in over:
        print(f"bench: above its limit or its static bound: {item}", file=sys.stderr)
    return 1 if over else 0


if __name__ == "__main__":
    sys.exit(main())
