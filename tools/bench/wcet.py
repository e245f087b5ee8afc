#!/usr/bin/python3
"""Static worst-case instruction bound of qfoc's functions on the Cortex-M4 (make bench).

Reads the linked Thumb-2 image, builds each function's control-flow graph from its
disassembly (capstone) and its call graph, and computes the longest path in instructions
from the function's entry to any of its returns, callees included.  A loop counts its
bound times its longest iteration plus one more iteration (the path that leaves it);
every loop bound comes from the table LOOP_BOUNDS below, which names where in the code
the bound comes from.  The bound holds for every input: no input can take a longer path.

usage: wcet.py --elf IMAGE.ELF [--function NAME ...] [--json OUT]
  IMAGE.ELF  a linked image (the bench's drive_only.elf: the drive's entry points with
             --gc-sections)
  NAME       the functions to report (default: every function of the image)

What is counted: every instruction on the path, an instruction in an IT block whether
its condition holds or not (the core issues it either way), a call as the call
instruction plus the callee's bound.  Data in the code (literal pools, TBB/TBH tables)
is skipped through the ELF's mapping symbols ($t, $d).  Indirect branches other than
TBB/TBH and calls through registers are refused (exit 1), as is recursion.

Exit status: 0 when every requested function is bounded; 1 when one is not (a loop
without a bound, an indirect branch, a cycle in the call graph), with the reason.

Requirements: REQ-BENCH-001, REQ-BENCH-002 (specs/requirements/bench.md).
"""
import argparse
import json
import sys

import capstone as cs
from capstone import arm_const as AC
from elftools.elf.elffile import ELFFile

# Loop bounds: function -> (largest number of times any back edge of the function can be
# taken on one call, where the bound comes from).  A function with a loop that is not
# listed here is refused.
LOOP_BOUNDS = {
    "qfoc_isqrt32": (1, "src/qfoc_isqrt.c, the correction loop down to the floor: at most one "
                        "step over all 2^32 inputs (tools/bench/isqrt_steps.sh, run by make "
                        "bench, checks every input)"),
    "qfoc_link_classify": (4, "src/qfoc_link.c, qfoc_lin_checksum inlined with n = "
                              "QFOC_LIN_CMD_DATA = 4 bytes (its loop variant n - i)"),
    "qfoc_lin_encode_status": (8, "src/qfoc_link.c, qfoc_lin_checksum inlined with n = "
                                  "QFOC_LIN_STATUS_DATA = 8 bytes (its loop variant n - i)"),
    "qfoc_drive_init": (11, "src/qfoc_drive.c, drv_init_slow_io: QFOC_LIN_FRAME_MAX = 11 bytes "
                            "of the status frame, 8 bytes of the CAN data (loop variants)"),
}


class Refused(Exception):
    """A function the analysis cannot bound, with the reason."""


class Image:
    """The functions, mapping symbols and code bytes of a linked Thumb-2 image."""

    def __init__(self, path):
        with open(path, "rb") as fh:
            elf = ELFFile(fh)
            self.sections = []
            for sec in elf.iter_sections():
                if sec["sh_flags"] & 0x4 and sec["sh_type"] == "SHT_PROGBITS":
                    self.sections.append((sec["sh_addr"], sec.data()))
            symtab = elf.get_section_by_name(".symtab")
            self.funcs = {}
            self.by_addr = {}
            maps = []
            for sym in symtab.iter_symbols():
                name = sym.name
                typ = sym["st_info"]["type"]
                addr = sym["st_value"]
                if typ == "STT_FUNC" and sym["st_size"] > 0:
                    start = addr & ~1
                    self.funcs[name] = (start, sym["st_size"])
                    self.by_addr[start] = name
                elif name.startswith("$t") or name.startswith("$d"):
                    maps.append((addr & ~1, name[1]))
            maps.sort()
            self.maps = maps

    def code(self, addr, size):
        for base, data in self.sections:
            if base <= addr and addr + size <= base + len(data):
                return data[addr - base:addr - base + size]
        raise Refused("0x%x: not in an executable section" % addr)

    def data_ranges(self, start, end):
        """The [a, b) ranges of data ($d) inside [start, end)."""
        out = []
        kind = "t"
        cur = start
        for addr, k in self.maps:
            if addr <= start:
                kind = k
                continue
            if addr >= end:
                break
            if kind == "d":
                out.append((cur, addr))
            kind = k
            cur = addr
        if kind == "d":
            out.append((cur, end))
        return out


CONDS = ("eq", "ne", "cs", "hs", "cc", "lo", "mi", "pl", "vs", "vc", "hi", "ls", "ge", "lt",
         "gt", "le", "al")


def _is_branch(m):
    """b, b<cond> (a conditional branch), cbz, cbnz; not bl, blx, bx, bic, bfi, ..."""
    return m in ("b", "cbz", "cbnz") or (m.startswith("b") and m[1:] in CONDS)


def _is_return(insn):
    m = insn.mnemonic.split(".")[0]
    if m == "bx" and insn.op_str == "lr":
        return True
    if m in ("pop", "ldm", "ldmia") and "pc" in insn.op_str:
        return True
    if m == "ldr" and insn.op_str.startswith("pc,"):
        return True
    return False


def _imm_target(insn):
    for op in insn.operands:
        if op.type == AC.ARM_OP_IMM:
            return op.imm
    return None


PIPELINE = 2      # pipeline refill after a taken branch, 1..3 on the Cortex-M4
DIVIDE = 12       # SDIV / UDIV, at most 12 cycles


def cycles(insn):
    """An upper bound of the instruction's cycles by the Cortex-M4 timings (ARM DDI 0439B,
    3.3.1), the same model as count.py's estimate taken at its worst: a single load or store
    2 (no credit for pipelining with its neighbour), LDM / STM / PUSH / POP 1 + N (+ P when
    the PC is loaded), LDRD / STRD 3, SDIV / UDIV 12, TBB / TBH 2 + P, a branch 1 + P as if
    taken, BL 1 + P.  Memory wait states are not modelled."""
    m = insn.mnemonic.split(".")[0]
    ops = insn.op_str
    if m in ("push", "pop", "stm", "stmia", "stmdb", "ldm", "ldmia", "ldmdb"):
        n = len(insn.operands) - (1 if m not in ("push", "pop") else 0)
        return 1 + n + (PIPELINE if "pc" in ops and m.startswith(("pop", "ldm")) else 0)
    if m in ("ldrd", "strd"):
        return 3
    if m.startswith(("ldr", "str")) and not m.startswith(("ldrex", "strex")):
        return 2 + (PIPELINE if m == "ldr" and ops.startswith("pc") else 0)
    if m in ("sdiv", "udiv"):
        return DIVIDE
    if m in ("tbb", "tbh"):
        return 2 + PIPELINE
    if _is_branch(m) or m in ("bl", "blx", "bx"):
        return 1 + PIPELINE
    return 1


class Function:
    """One function's instructions and control-flow edges."""

    def __init__(self, image, name):
        self.name = name
        start, size = image.funcs[name]
        self.start, self.end = start, start + size
        md = cs.Cs(cs.CS_ARCH_ARM, cs.CS_MODE_THUMB | cs.CS_MODE_MCLASS)
        md.detail = True
        data = image.data_ranges(self.start, self.end)
        self.insns = {}
        pos = self.start
        for a, b in data + [(self.end, self.end)]:
            if pos < a:
                for insn in md.disasm(image.code(pos, a - pos), pos):
                    self.insns[insn.address] = insn
            pos = max(pos, b)
        self.order = sorted(self.insns)
        self.image = image
        self.succ = {}
        self.calls = {}
        self._edges(data)

    def _next(self, addr):
        insn = self.insns[addr]
        n = addr + insn.size
        return n if n in self.insns else None

    def _edges(self, data):
        it_left = 0
        for addr in self.order:
            insn = self.insns[addr]
            m = insn.mnemonic.split(".")[0]
            in_it = it_left > 0
            if in_it:
                it_left -= 1
            nxt = self._next(addr)
            succ = []
            if m.startswith("it") and m != "it" or m == "it":
                it_left = len(m) - 1
                succ = [nxt]
            elif m in ("tbb", "tbh"):
                succ = self._table(addr, insn, m)
            elif _is_return(insn):
                succ = [nxt] if in_it else []
                self.calls.setdefault(addr, None)
                self.calls.pop(addr)
            elif m in ("bl", "blx"):
                tgt = _imm_target(insn)
                if tgt is None or m == "blx" and insn.operands[0].type == AC.ARM_OP_REG:
                    raise Refused("%s: 0x%x: call through a register (%s %s)"
                                  % (self.name, addr, insn.mnemonic, insn.op_str))
                callee = self.image.by_addr.get(tgt)
                if callee is None:
                    raise Refused("%s: 0x%x: call to 0x%x, no function there"
                                  % (self.name, addr, tgt))
                self.calls[addr] = callee
                succ = [nxt]
            elif _is_branch(m):
                tgt = _imm_target(insn)
                cond = (m != "b") or in_it
                if self.start <= tgt < self.end:
                    succ = [tgt] + ([nxt] if cond else [])
                else:
                    callee = self.image.by_addr.get(tgt)
                    if callee is None:
                        raise Refused("%s: 0x%x: branch to 0x%x outside any function"
                                      % (self.name, addr, tgt))
                    # a tail call: the callee returns for this function
                    self.calls[addr] = callee
                    succ = [nxt] if cond else []
            elif m in ("bx", "blx", "mov") and insn.op_str.startswith("pc") or \
                    m == "bx":
                raise Refused("%s: 0x%x: indirect branch (%s %s)"
                              % (self.name, addr, insn.mnemonic, insn.op_str))
            else:
                if any(r == AC.ARM_REG_PC for r in insn.regs_write) and m not in ("bl",):
                    raise Refused("%s: 0x%x: writes the pc (%s %s)"
                                  % (self.name, addr, insn.mnemonic, insn.op_str))
                succ = [nxt]
            self.succ[addr] = [s for s in succ if s is not None]
            for s in self.succ[addr]:
                if s not in self.insns:
                    raise Refused("%s: 0x%x: successor 0x%x is not an instruction"
                                  % (self.name, addr, s))

    def _table(self, addr, insn, m):
        """Targets of a TBB / TBH: the table follows the instruction; its length comes from
        the compare that guards the index (cmp rX, #n; bhi default)."""
        idx_reg = insn.operands[0].mem.index
        n = None
        prev = [a for a in self.order if a < addr][-4:]
        for a in reversed(prev):
            p = self.insns[a]
            if p.mnemonic.split(".")[0] == "cmp" and p.operands[0].reg == idx_reg and \
                    p.operands[1].type == AC.ARM_OP_IMM:
                n = p.operands[1].imm + 1
                break
        if n is None:
            raise Refused("%s: 0x%x: %s without a bounding compare" % (self.name, addr, m))
        width = 1 if m == "tbb" else 2
        raw = self.image.code(addr + 4, n * width)
        base = addr + 4
        out = []
        for i in range(n):
            off = raw[i] if width == 1 else int.from_bytes(raw[2 * i:2 * i + 2], "little")
            out.append(base + 2 * off)
        return sorted(set(out))


def _sccs(nodes, succ):
    """Strongly connected components (Tarjan, iterative)."""
    index, low, on, stack, out = {}, {}, set(), [], []
    counter = [0]
    for root in nodes:
        if root in index:
            continue
        work = [(root, iter(succ[root]))]
        index[root] = low[root] = counter[0]
        counter[0] += 1
        stack.append(root)
        on.add(root)
        while work:
            v, it = work[-1]
            advanced = False
            for w in it:
                if w not in index:
                    index[w] = low[w] = counter[0]
                    counter[0] += 1
                    stack.append(w)
                    on.add(w)
                    work.append((w, iter(succ[w])))
                    advanced = True
                    break
                if w in on:
                    low[v] = min(low[v], index[w])
            if advanced:
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[v])
            if low[v] == index[v]:
                comp = []
                while True:
                    w = stack.pop()
                    on.discard(w)
                    comp.append(w)
                    if w == v:
                        break
                out.append(comp)
    return out


class Analysis:
    """Bounds of every function reachable from the requested ones."""

    def __init__(self, image, metric="instructions"):
        self.image = image
        self.metric = metric
        self.funcs = {}
        self.bound = {}
        self.path = {}
        self.active = []

    def function(self, name):
        if name not in self.funcs:
            self.funcs[name] = Function(self.image, name)
        return self.funcs[name]

    def of(self, name):
        if name in self.bound:
            return self.bound[name]
        if name in self.active:
            raise Refused("recursion: %s" % " -> ".join(self.active + [name]))
        self.active.append(name)
        f = self.function(name)
        weight = {}
        for a in f.order:
            callee = f.calls.get(a)
            own = 1 if self.metric == "instructions" else cycles(f.insns[a])
            weight[a] = own + (self.of(callee) if callee else 0)
        self.bound[name] = self._longest(f, weight)
        self.active.pop()
        return self.bound[name]

    def _longest(self, f, weight):
        nodes = [a for a in f.order]
        comps = _sccs(nodes, f.succ)
        comp_of = {}
        for i, c in enumerate(comps):
            for a in c:
                comp_of[a] = i
        cweight = []
        for i, c in enumerate(comps):
            loop = len(c) > 1 or c[0] in f.succ[c[0]]
            if not loop:
                cweight.append(weight[c[0]])
                continue
            if f.name not in LOOP_BOUNDS:
                raise Refused("%s: a loop at 0x%x with no bound in LOOP_BOUNDS"
                              % (f.name, min(c)))
            n = LOOP_BOUNDS[f.name][0]
            cweight.append((n + 1) * self._iteration(f, set(c), weight))
        # the graph of components is acyclic: longest path from the entry's component
        csucc = {i: set() for i in range(len(comps))}
        for a in nodes:
            for s in f.succ[a]:
                if comp_of[a] != comp_of[s]:
                    csucc[comp_of[a]].add(comp_of[s])
        memo, nxt = {}, {}
        for i in range(len(comps)):   # Tarjan yields components in reverse topological order
            best = max(csucc[i], key=lambda j: memo[j], default=None)
            nxt[i] = best
            memo[i] = cweight[i] + (memo[best] if best is not None else 0)
        # the calls on the longest path, for the report
        path, i = [], comp_of[f.start]
        while i is not None:
            for a in comps[i]:
                if f.calls.get(a):
                    path.append((f.calls[a], self.bound.get(f.calls[a], 0)))
            i = nxt[i]
        self.path[f.name] = path
        return memo[comp_of[f.start]]

    def _iteration(self, f, comp, weight):
        """Longest path through one iteration of a loop: from any node of the component
        to any node of it, without repeating a node (the loop's body, every branch)."""
        best = 0
        for head in comp:
            # longest simple path from head inside comp, by DFS (loops here are short)
            stack = [(head, weight[head], {head})]
            while stack:
                v, w, seen = stack.pop()
                best = max(best, w)
                for s in f.succ[v]:
                    if s in comp and s not in seen:
                        stack.append((s, w + weight[s], seen | {s}))
        return best


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--elf", required=True)
    ap.add_argument("--function", action="append", default=[])
    ap.add_argument("--json")
    ap.add_argument("--cycles", action="store_true",
                    help="bound estimated cycles (Cortex-M4 timings) instead of instructions")
    ap.add_argument("--explain", action="store_true",
                    help="list the calls on each function's longest path")
    args = ap.parse_args(argv)
    image = Image(args.elf)
    names = args.function or sorted(image.funcs)
    an = Analysis(image, "cycles" if args.cycles else "instructions")
    out, bad = {}, []
    for name in names:
        if name not in image.funcs:
            print("wcet: %s: no such function in %s" % (name, args.elf), file=sys.stderr)
            bad.append(name)
            continue
        try:
            out[name] = an.of(name)
            print("%-36s %6d" % (name, out[name]))
            if args.explain:
                for callee, b in an.path.get(name, []):
                    print("    %-32s %6d" % (callee, b))
        except Refused as e:
            print("wcet: %s: refused: %s" % (name, e), file=sys.stderr)
            bad.append(name)
            an.active = []
    if args.json:
        with open(args.json, "w") as fh:
            json.dump(out, fh, indent=1, sort_keys=True)
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
