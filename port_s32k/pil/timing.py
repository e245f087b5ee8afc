"""timing.py -- the image's measured timing in the processor-in-the-loop run: the
instructions executed inside the library's two periodic entry points, qfoc_drive_fast_step
(from the ADC1 handler) and qfoc_drive_tick (from the 1 ms handler), on the image as
linked, against the static bound of the bench's analysis (tools/bench/wcet.py) of the same
functions in the same image; and the summary of every run's per-interrupt figures written
for the bench report (make pil: build/pil/timing.json; make bench reads it, mk/bench.mk).

Counting: a code hook on the function's first instruction records the core clock and the
clocks spent so far in completed handlers (core.Core.handler_clocks); a hook on the
return address (LR at the entry) takes the difference of both.  Since one instruction is
one clock (core.py) and a handler nested in the call has returned before the call
returns, the difference is the function's own instructions from its first instruction to
its return instruction included, callees included, nested handlers (their instructions,
entry and return) excluded: the quantity wcet.py bounds.  A call is identified by the
function and the stack pointer at its entry; a hook that fires again at a restarted
instruction (a chunk stopped there, an interrupt taken before it) replaces the entry with
the later clock pair, which gives the same difference.  A watchdog reset drops the calls
in progress.

Requirement: REQ-PIL-006 (specs/requirements/pil.md).
"""
import hashlib
import json
import os
import sys

from unicorn import UC_HOOK_CODE
from unicorn.arm_const import UC_ARM_REG_LR, UC_ARM_REG_SP

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", ".."))
FUNCS = ("qfoc_drive_fast_step", "qfoc_drive_tick")
# the interrupts of the report (core IRQ numbers, run.IRQS)
IRQ_KEYS = {122: "ftm3", 40: "adc1", 48: "lpit0", 33: "lpuart1"}


def static_bounds(elf, names=FUNCS):
    """The bench's static bound (tools/bench/wcet.py: the longest path over every input, in
    instructions) of each named function, computed on `elf` itself."""
    sys.path.insert(0, os.path.join(ROOT, "tools", "bench"))
    try:
        import wcet
    finally:
        sys.path.pop(0)
    an = wcet.Analysis(wcet.Image(elf), "instructions")
    return {n: an.of(n) for n in names}


class LibTiming:
    """Instructions per call of the library's entry points in the running image."""

    def __init__(self, core, names=FUNCS):
        self.core = core
        self.calls = {n: [] for n in names}       # name -> [instructions of each call]
        self.max_at = {n: None for n in names}    # name -> core clock of the longest call's entry
        self.open = {}                            # (name, sp) -> (clock, handler clocks, resets)
        self.ret_hooked = set()
        for n in names:
            a = core.syms[n] & ~1
            core.mu.hook_add(UC_HOOK_CODE, lambda mu, addr, size, data, n=n: self._entry(n),
                             begin=a, end=a)

    def _entry(self, name):
        c, mu = self.core, self.core.mu
        sp = mu.reg_read(UC_ARM_REG_SP)
        self.open[(name, sp)] = (c.now(), c.handler_clocks, c.resets)
        ret = mu.reg_read(UC_ARM_REG_LR) & ~1
        if (name, ret) not in self.ret_hooked:
            self.ret_hooked.add((name, ret))
            mu.hook_add(UC_HOOK_CODE, lambda mu_, addr, size, data, n=name: self._ret(n),
                        begin=ret, end=ret)

    def _ret(self, name):
        c = self.core
        e = self.open.pop((name, c.mu.reg_read(UC_ARM_REG_SP)), None)
        if e is None or e[2] != c.resets:
            return
        n = (c.now() - e[0]) - (c.handler_clocks - e[1])
        if not self.calls[name] or n > max(self.calls[name]):
            self.max_at[name] = e[0]
        self.calls[name].append(n)


def summary(core, pil, lib):
    """The figures of one run for the bench report: per interrupt (own instructions, clocks
    with entry and return, latency: min / mean / max, count), the library's entry points,
    the sampling instant -> LDOK latency."""
    def mmm(xs):
        return None if not xs else {"n": len(xs), "min": min(xs), "mean": round(sum(xs) / len(xs), 1),
                                    "max": max(xs)}
    irqs = {}
    for irq, key in IRQ_KEYS.items():
        st = core.irq_stats.get(irq, [])
        irqs[key] = {"instructions": mmm([s[0] for s in st]), "clocks": mmm([s[1] for s in st]),
                     "latency": mmm([s[2] for s in st])}
    return {"irqs": irqs, "lib": {n: mmm(v) for n, v in lib.calls.items()},
            "sample_to_ldok": mmm(pil.latencies)}


def merge(runs):
    """The summaries of several runs (name -> summary) into one: the smallest minimum, the
    largest maximum, the count-weighted mean; each maximum with the run it came from."""
    def comb(items):
        items = [(n, x) for n, x in items if x]
        if not items:
            return None
        tot = sum(x["n"] for _, x in items)
        mx = max(items, key=lambda i: i[1]["max"])
        return {"n": tot, "min": min(x["min"] for _, x in items),
                "mean": round(sum(x["mean"] * x["n"] for _, x in items) / tot, 1),
                "max": mx[1]["max"], "max_in": mx[0]}
    names = sorted(runs)
    out = {"runs": names, "irqs": {}, "lib": {}}
    for key in IRQ_KEYS.values():
        out["irqs"][key] = {f: comb([(n, runs[n]["irqs"][key][f]) for n in names])
                            for f in ("instructions", "clocks", "latency")}
    for f in FUNCS:
        out["lib"][f] = comb([(n, runs[n]["lib"].get(f)) for n in names])
    out["sample_to_ldok"] = comb([(n, runs[n]["sample_to_ldok"]) for n in names])
    return out


def sha256(path):
    with open(path, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()


def write(path, data):
    d = os.path.dirname(path)
    if d:
        os.makedirs(d, exist_ok=True)
    with open(path, "w") as f:
        json.dump(data, f, indent=1, sort_keys=True)
        f.write("\n")
