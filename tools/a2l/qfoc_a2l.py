#!/usr/bin/env python3
"""qfoc calibration description: an ASAM MCD-2 MC file (A2L, ASAP2 version 1.71) for a
parameter table and the firmware image it is linked into.

Usage:
    python3 tools/a2l/qfoc_a2l.py ELF [-o OUT.a2l] [--table NAME] [--drive NAME | --no-drive]

What it writes (OUT, default: ELF with the suffix .a2l):
  - a PROJECT with one MODULE: MOD_PAR (the memory segments that hold the table and the
    drive: the ELF sections, addresses and sizes from their headers; the table's name, motor
    file and CRC as system constants) and MOD_COMMON (BYTE_ORDER MSB_LAST for a
    little-endian image, the alignments of the ARM EABI);
  - every field of the parameter table (include/qfoc/params.h, qfoc_param_table_t) as a
    CHARACTERISTIC: VALUE, or VAL_BLK with MATRIX_DIM for an array member, with its
    RECORD_LAYOUT, a LINEAR COMPU_METHOD whose factor is the physical value of one LSB of
    its Q format and base (a Q15 current: I_base / 32768 A; a pi.h gain: its mantissa with
    the table's shift, in SI units) in the motor file's unit, LOWER_LIMIT / UPPER_LIMIT the
    range the library's check accepts (qfoc_params_check; the tuning tool's field_ranges(),
    which mirrors it), physical; READ_ONLY for the fields that are the identity or the
    representation of others (bases, shifts, CRC);
  - the drive's status and state (qfoc_drive_t of include/qfoc/drive.h: the qfoc_status_t
    the drive reports on LIN and CAN, the state machine, the references and estimates) as
    MEASUREMENTs, with the state and sub-state codes of sm.h as COMPU_VTABs and one
    MEASUREMENT per fault bit of fault.h (BIT_MASK of the latched fault word).

Where each number comes from:
  - addresses, sizes, data types and member offsets: the ELF's symbol table and its DWARF
    (the firmware is compiled with -g, mk/port.mk); the table is the object of type
    qfoc_param_table_t (symbol qfoc_params_<NAME>), the drive the object of type qfoc_drive_t;
  - the physical meaning of every field (factor, unit, motor-file key, whether it is fixed):
    the tuning tool, tools/tune/qfoc_tune.py (Field.phys), which regenerates the table from
    its line of tables/manifest.txt; the image's table must be that table, field for field,
    else nothing is written (an A2L must not describe other values than the image holds);
  - the limits: the tuning tool's field_ranges() (the library's range check);
  - the bases of the measurements' Q15 conversions: the same table.

The output depends only on the ELF's bytes and the repository's sources: the same inputs
give the same file, byte for byte (no time stamp, no absolute path).

Exit codes: 0 written; 1 refused (the ELF is missing, unreadable or without DWARF, a symbol
or table name that does not exist, an image whose table differs from the tuning tool's),
with a message naming what was typed, and nothing written.

Requirements: REQ-A2L-001 .. REQ-A2L-005 (specs/requirements/a2l.md).
"""
from __future__ import annotations

import argparse
import hashlib
import math
import os
import re
import sys
from dataclasses import dataclass
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(REPO / "tools" / "tune"))

import qfoc_tune as qt  # noqa: E402

ASAP2_VERSION = (1, 71)
TABLE_TYPE = "qfoc_param_table_t"
DRIVE_TYPE = "qfoc_drive_t"
TABLE_PREFIX = "qfoc_params_"
MANIFEST = REPO / "tables" / "manifest.txt"
SM_H = REPO / "include" / "qfoc" / "sm.h"
FAULT_H = REPO / "include" / "qfoc" / "fault.h"
VERSION_H = REPO / "include" / "qfoc" / "version.h"

# DWARF base-type encodings (DWARF 5, 7.8)
ATE_BOOLEAN, ATE_FLOAT, ATE_SIGNED, ATE_SIGNED_CHAR, ATE_UNSIGNED, ATE_UNSIGNED_CHAR = \
    0x02, 0x04, 0x05, 0x06, 0x07, 0x08
DW_OP_ADDR = 0x03

# ASAP2 data types by (kind, size, signed)
DATATYPES = {("int", 1, False): "UBYTE", ("int", 1, True): "SBYTE",
             ("int", 2, False): "UWORD", ("int", 2, True): "SWORD",
             ("int", 4, False): "ULONG", ("int", 4, True): "SLONG",
             ("int", 8, False): "A_UINT64", ("int", 8, True): "A_INT64",
             ("float", 4, True): "FLOAT32_IEEE", ("float", 8, True): "FLOAT64_IEEE"}

# The drive's values a calibration engineer watches (drive.h, link.h, sm.h): the member of
# qfoc_drive_t, the long identifier and the quantity (QUANTITIES below).  The status is what
# the drive sends on LIN and CAN (qfoc_status_t, link.h: decimal units); the rest are the
# state machine and the control's references and estimates (Q15 of the table's bases).
MEASUREMENTS = (
    ("s.status.state", "drive state reported on LIN and CAN (sm.h QFOC_STATE_*)", "state"),
    ("s.status.substate", "RUN sub-state reported on LIN and CAN (sm.h QFOC_SUB_*)", "substate"),
    ("s.status.faults", "fault word reported on LIN and CAN (fault.h)", "faults"),
    ("s.status.speed_rpm", "estimated speed magnitude, mechanical; 0 while the PWM is off", "rpm"),
    ("s.status.vdc_dv", "DC-bus voltage reported (0.1 V)", "dV"),
    ("s.status.current_ca", "current-vector amplitude reported (0.01 A)", "cA"),
    ("s.status.temp_dc", "hottest of IPM and PCB reported (0.1 degC)", "ddegC"),
    ("s.sm.state", "state machine: state (sm.h QFOC_STATE_*)", "state"),
    ("s.sm.sub", "state machine: sub-state (sm.h QFOC_SUB_*)", "substate"),
    ("s.sm.faults", "latched fault word, non-zero exactly in ERROR (fault.h)", "faults"),
    ("s.sm.first_fault", "faults of the tick that entered ERROR (fault.h)", "faults"),
    ("s.sm.t_state", "time in the state (ticks of 1 ms, saturating)", "ms"),
    ("s.sm.t_sub", "time in the sub-state (ticks of 1 ms, saturating)", "ms"),
    ("s.sm.retry", "start retries taken since the RUN entry", "count"),
    ("s.speed_target", "commanded speed, mechanical", "speed"),
    ("s.speed_ref", "ramped speed reference, mechanical", "speed"),
    ("s.ol_speed", "open-loop frame speed, mechanical", "speed"),
    ("f.speed_f", "estimated speed after the low-pass, mechanical", "speed"),
    ("s.id_ref", "d-current reference", "current"),
    ("s.iq_ref", "q-current reference", "current"),
    ("s.iq_lim", "q-current limit of the closed loop", "current"),
    ("f.i_dq.d", "measured d current in the control frame", "current"),
    ("f.i_dq.q", "measured q current in the control frame", "current"),
    ("f.vdc", "filtered DC-bus voltage", "voltage"),
    ("f.psi_mag", "flux magnitude of the observer", "flux"),
    ("s.util", "voltage utilisation of the last command, |v| / (V_dc / sqrt 3)", "ratio"),
    ("f.theta_est", "estimated rotor angle, electrical", "angle"),
    ("s.offset_u", "calibrated current offset, phase u", "adc"),
    ("s.offset_v", "calibrated current offset, phase v", "adc"),
    ("s.run_ms", "time in RUN (saturating)", "ms"),
    ("s.table_ok", "result of the last table check", "bool"),
    ("s.derated", "a temperature holds the speed limit below rpm_max", "bool"),
    ("f.trip_count", "over-current events (mod 256)", "count"),
    ("f.out.cmp", "compare values u, v, w of this period", "ticks"),
    ("f.out.enable", "PWM outputs switching", "bool"),
    ("s.link.n_ok", "accepted command frames (saturating)", "count"),
    ("s.link.lost", "command link lost", "bool"),
)
# The latched fault word whose bits are MEASUREMENTs of their own (BIT_MASK).
FAULT_WORD = "s.sm.faults"


class Refused(Exception):
    """Bad input: the message names what was typed; nothing is written (exit code 1)."""


# ----------------------------------------------------------------------------- ELF, DWARF

@dataclass
class Leaf:
    """A scalar (or an array of scalars) inside an object."""
    path: str            # member path from the object, e.g. "pi_id.kp", "out.cmp"
    offset: int          # byte offset in the object
    size: int            # bytes of one element
    kind: str            # "int", "bool", "float"
    signed: bool
    dims: tuple          # array dimensions, () for a scalar

    @property
    def datatype(self) -> str:
        return DATATYPES[("int" if self.kind == "bool" else self.kind, self.size,
                          self.signed and self.kind != "bool")]


@dataclass
class Variable:
    """An object with a static address: the DWARF variable and its symbol."""
    name: str            # DWARF name
    address: int
    type_die: object     # the DIE of its type (qualifiers and typedefs included)
    type_name: str       # the typedef name of its type, or ""
    scope: str           # "" for a file-scope object, else the function it is local to
    cu_name: str
    symbol: str = ""     # the symbol at its address with its size
    size: int = 0


def _attr(die, name):
    a = die.attributes.get(name)
    return None if a is None else a.value


def _text(v) -> str:
    return v.decode("utf-8", "replace") if isinstance(v, bytes) else str(v)


def _strip(die):
    """(the DIE with const, volatile and typedef removed, the first typedef name seen)."""
    name = ""
    while die is not None and die.tag in ("DW_TAG_typedef", "DW_TAG_const_type",
                                          "DW_TAG_volatile_type", "DW_TAG_restrict_type"):
        if die.tag == "DW_TAG_typedef" and not name:
            name = _text(_attr(die, "DW_AT_name"))
        if "DW_AT_type" not in die.attributes:
            return None, name
        die = die.get_DIE_from_attribute("DW_AT_type")
    return die, name


def type_name(die) -> str:
    """The typedef (or struct / base type) name of a type DIE."""
    base, name = _strip(die)
    if name:
        return name
    if base is not None and base.tag == "DW_TAG_pointer_type":
        return (type_name(base.get_DIE_from_attribute("DW_AT_type"))
                if "DW_AT_type" in base.attributes else "void") + " *"
    return _text(_attr(base, "DW_AT_name")) if base is not None and \
        "DW_AT_name" in base.attributes else ""


def type_size(die) -> int:
    base, _n = _strip(die)
    if base is None:
        return 0
    if base.tag == "DW_TAG_array_type":
        n = 1
        for d in array_dims(base):
            n *= d
        return n * type_size(base.get_DIE_from_attribute("DW_AT_type"))
    return int(_attr(base, "DW_AT_byte_size") or 0)


def array_dims(die) -> tuple:
    dims = []
    for sub in die.iter_children():
        if sub.tag != "DW_TAG_subrange_type":
            continue
        if "DW_AT_count" in sub.attributes:
            dims.append(int(_attr(sub, "DW_AT_count")))
        elif "DW_AT_upper_bound" in sub.attributes:
            dims.append(int(_attr(sub, "DW_AT_upper_bound")) + 1)
        else:
            raise Refused("an array of unknown length in the DWARF (a flexible array member)")
    return tuple(dims)


def member_offset(die) -> int:
    v = _attr(die, "DW_AT_data_member_location")
    if isinstance(v, int):
        return v
    if isinstance(v, list) and len(v) >= 2 and v[0] == 0x23:   # DW_OP_plus_uconst (DWARF 2)
        off, shift = 0, 0
        for byte in v[1:]:
            off |= (byte & 0x7F) << shift
            shift += 7
            if not byte & 0x80:
                break
        return off
    return 0          # the first member of a union or a struct without the attribute


def leaves(type_die, path: str = "", offset: int = 0) -> list[Leaf]:
    """Every scalar of a type in declaration order (arrays of scalars as one leaf)."""
    base, _n = _strip(type_die)
    if base is None:
        raise Refused(f"{path or 'the object'}: a member of type void")
    if base.tag == "DW_TAG_structure_type":
        out = []
        for m in base.iter_children():
            if m.tag != "DW_TAG_member":
                continue
            if "DW_AT_bit_size" in m.attributes or "DW_AT_data_bit_offset" in m.attributes:
                raise Refused(f"{path}: a bit-field member, which a calibration description "
                              "cannot address")
            name = _text(_attr(m, "DW_AT_name"))
            out += leaves(m.get_DIE_from_attribute("DW_AT_type"),
                          f"{path}.{name}" if path else name, offset + member_offset(m))
        return out
    if base.tag == "DW_TAG_array_type":
        el = base.get_DIE_from_attribute("DW_AT_type")
        el_base, _n = _strip(el)
        dims = array_dims(base)
        if el_base is not None and el_base.tag == "DW_TAG_base_type":
            (leaf,) = leaves(el, path, offset)
            leaf.dims = dims
            return [leaf]
        out, step, n = [], type_size(el), 1
        for d in dims:
            n *= d
        for i in range(n):
            out += leaves(el, f"{path}[{i}]", offset + i * step)
        return out
    if base.tag == "DW_TAG_base_type":
        enc = _attr(base, "DW_AT_encoding")
        size = int(_attr(base, "DW_AT_byte_size"))
        if enc == ATE_BOOLEAN:
            return [Leaf(path, offset, size, "bool", False, ())]
        if enc == ATE_FLOAT:
            return [Leaf(path, offset, size, "float", True, ())]
        return [Leaf(path, offset, size, "int", enc in (ATE_SIGNED, ATE_SIGNED_CHAR), ())]
    if base.tag == "DW_TAG_enumeration_type":
        size = int(_attr(base, "DW_AT_byte_size"))
        return [Leaf(path, offset, size, "int", False, ())]
    if base.tag == "DW_TAG_pointer_type":
        return [Leaf(path, offset, int(_attr(base, "DW_AT_byte_size") or 4), "int", False, ())]
    raise Refused(f"{path}: a member of DWARF kind {base.tag}, which the tool does not describe")


class Image:
    """The ELF: its symbols, its sections and the variables of its DWARF."""

    def __init__(self, path: Path):
        try:
            from elftools.common.exceptions import ELFError, DWARFError
            from elftools.elf.elffile import ELFFile
        except ImportError as exc:
            raise Refused("pyelftools is missing: install Debian's python3-pyelftools "
                          "(make deps-a2l)") from exc
        self.path = path
        try:
            self.data = path.read_bytes()
        except OSError as exc:
            raise Refused(f"{path}: cannot read the ELF: {exc.strerror}") from exc
        if self.data[:4] != b"\x7fELF":
            raise Refused(f"{path}: not an ELF file (no ELF magic number)")
        import io
        try:
            self.elf = ELFFile(io.BytesIO(self.data))
            self.little = self.elf.little_endian
            self.symbols = self._symbols()
            if not self.elf.has_dwarf_info() or self.elf.get_section_by_name(".debug_info") is None:
                raise Refused(f"{path}: the ELF has no DWARF debug information (.debug_info): "
                              "compile with -g (mk/port.mk does)")
            self.variables = self._variables()
        except (ELFError, DWARFError) as exc:
            raise Refused(f"{path}: unreadable ELF or DWARF: {exc}") from exc

    def _symbols(self) -> dict:
        """name -> (address, size) of every data object of .symtab."""
        tab = self.elf.get_section_by_name(".symtab")
        if tab is None:
            raise Refused(f"{self.path}: the ELF has no symbol table (.symtab): do not strip it")
        out = {}
        for s in tab.iter_symbols():
            if s["st_info"]["type"] == "STT_OBJECT" and s.name:
                out[s.name] = (int(s["st_value"]), int(s["st_size"]))
        return out

    def _variables(self) -> list[Variable]:
        out = []
        dwarf = self.elf.get_dwarf_info()
        for cu in dwarf.iter_CUs():
            top = cu.get_top_DIE()
            cu_name = _text(_attr(top, "DW_AT_name"))
            asz = cu["address_size"]
            for die in cu.iter_DIEs():
                if die.tag != "DW_TAG_variable" or "DW_AT_location" not in die.attributes:
                    continue
                loc = _attr(die, "DW_AT_location")
                if not isinstance(loc, list) or len(loc) != 1 + asz or loc[0] != DW_OP_ADDR:
                    continue
                addr = int.from_bytes(bytes(loc[1:]), "little" if self.little else "big")
                decl = die
                if "DW_AT_specification" in die.attributes:
                    decl = die.get_DIE_from_attribute("DW_AT_specification")
                elif "DW_AT_abstract_origin" in die.attributes:
                    decl = die.get_DIE_from_attribute("DW_AT_abstract_origin")
                name = _text(_attr(die, "DW_AT_name") or _attr(decl, "DW_AT_name") or "")
                tsrc = die if "DW_AT_type" in die.attributes else decl
                if not name or "DW_AT_type" not in tsrc.attributes:
                    continue
                tdie = tsrc.get_DIE_from_attribute("DW_AT_type")
                scope, p = "", die.get_parent()
                while p is not None and p.tag != "DW_TAG_compile_unit":
                    if p.tag == "DW_TAG_subprogram":
                        scope = _text(_attr(p, "DW_AT_name") or "")
                        break
                    p = p.get_parent()
                v = Variable(name, addr, tdie, type_name(tdie), scope, cu_name)
                v.size = type_size(tdie)
                syms = sorted(n for n, (a, sz) in self.symbols.items()
                              if a == addr and sz == v.size)
                v.symbol = name if name in syms else (syms[0] if syms else "")
                out.append(v)
        # one entry per object (a declaration seen from several units has one address)
        seen, uniq = set(), []
        for v in sorted(out, key=lambda v: (v.address, v.name)):
            if (v.address, v.name) not in seen:
                seen.add((v.address, v.name))
                uniq.append(v)
        return uniq

    def of_type(self, tname: str) -> list[Variable]:
        return [v for v in self.variables if v.type_name == tname]

    def find(self, name: str) -> list[Variable]:
        """The objects named name in the DWARF or in the symbol table."""
        by_dwarf = [v for v in self.variables if v.name == name]
        if by_dwarf:
            return by_dwarf
        if name in self.symbols:
            addr, _sz = self.symbols[name]
            return [v for v in self.variables if v.address == addr]
        return []

    def section_of(self, address: int, size: int):
        """The allocated section that holds [address, address + size)."""
        for sec in self.elf.iter_sections():
            if not sec["sh_flags"] & 0x2:            # SHF_ALLOC
                continue
            lo, n = int(sec["sh_addr"]), int(sec["sh_size"])
            if lo <= address and address + size <= lo + n:
                return sec
        return None

    def read(self, address: int, size: int) -> bytes | None:
        """The initial bytes at an address (None for a NOBITS section such as .bss)."""
        sec = self.section_of(address, size)
        if sec is None or sec["sh_type"] == "SHT_NOBITS":
            return None
        off = address - int(sec["sh_addr"])
        return sec.data()[off:off + size]

    def decode(self, raw: bytes, signed: bool) -> int:
        return int.from_bytes(raw, "little" if self.little else "big", signed=signed)

    def cpu(self) -> str:
        sec = self.elf.get_section_by_name(".ARM.attributes")
        if sec is not None:
            try:
                for sub in sec.iter_subsections():
                    for ss in sub.iter_subsubsections():
                        for a in ss.iter_attributes():
                            if a.tag == "TAG_CPU_NAME":
                                return f"ARM {a.value}"
            except Exception:   # noqa: BLE001 - an attribute section the reader cannot parse
                pass
        return f"{self.elf['e_machine']}"


# ----------------------------------------------------------------------------- inputs

def manifest() -> dict:
    """name -> (motor file, overrides) of tables/manifest.txt."""
    out = {}
    for line in MANIFEST.read_text(encoding="utf-8").splitlines():
        words = line.split()
        if words and not words[0].startswith("#"):
            out[words[0]] = (words[1], words[2:])
    return out


def header_codes(path: Path, prefix: str, ctype: str) -> list[tuple[str, int]]:
    """(name, value) of the '#define PREFIX<name> ((ctype)<value>u)' lines of a header."""
    pat = re.compile(r"^#define\s+" + re.escape(prefix) + r"(\w+)\s+\(\(" + re.escape(ctype)
                     + r"\)(0x[0-9A-Fa-f]+|\d+)u\)", re.M)
    return [(m.group(1), int(m.group(2), 0)) for m in pat.finditer(path.read_text(encoding="utf-8"))]


def version_string() -> str:
    m = re.search(r'#define\s+QFOC_VERSION_STRING\s+"([^"]+)"', VERSION_H.read_text(encoding="utf-8"))
    return m.group(1) if m else "unknown"


@dataclass
class Table:
    """The tuning tool's table for a manifest line: fields with their physical meaning."""
    name: str
    motor: str
    overrides: list
    fields: list          # (dotted name, qt.Field) in declaration order, crc last
    ranges: dict          # dotted name -> (low, high) raw
    bases: object         # qt.Bases
    pole_pairs: int


def tune(name: str) -> Table:
    lines = manifest()
    if name not in lines:
        raise Refused(f"table '{name}' is not in tables/manifest.txt (tables: "
                      f"{', '.join(sorted(lines))})")
    motor, overrides = lines[name]
    try:
        cfg = qt.load_config(REPO / motor, overrides)
        b = qt.make_bases(cfg)
    except qt.InputError as exc:
        raise Refused(f"table '{name}': the tuning tool refuses {motor}: {exc}") from exc
    ds = qt.design_loops(cfg, b)
    items = qt.build_table(cfg, ds)
    crc = qt.crc32_iso_hdlc(qt.serialise(items))
    fields = qt.flatten(items) + [("crc", qt.crc_field(crc))]
    return Table(name, motor, overrides, fields, qt.field_ranges(items), b,
                 int(cfg["motor"]["pole_pairs"]))


# ----------------------------------------------------------------------------- A2L model

def num(x: float) -> str:
    """A float as the A2L writes it: the shortest text that reads back to the same double."""
    x = float(x)
    if x == 0.0:
        return "0"
    if x == int(x) and abs(x) < 1e15:
        return str(int(x))
    return repr(x)


def fmt_string(factor: float) -> str:
    """The display format '%<width>.<decimals>' for a conversion of this factor."""
    dec = 0 if factor >= 1.0 else min(9, int(math.ceil(-math.log10(factor) - 1e-9)))
    return f"%{dec + 8}.{dec}"


def ident_part(text: str) -> str:
    """A partial ASAP2 identifier from free text."""
    s = re.sub(r"_+", "_", re.sub(r"[^A-Za-z0-9_]", "_", text)).strip("_") or "x"
    return s if not s[0].isdigit() else "_" + s


def a2l_string(text: str) -> str:
    return '"' + text.replace("\\", "/").replace('"', "'") + '"'


@dataclass
class Conversion:
    name: str
    long: str
    kind: str            # "LINEAR" or "TAB_VERB"
    unit: str
    factor: float = 1.0
    vtab: str = ""
    fmt: str = "%8.0"


class Module:
    """The objects of the MODULE, named uniquely, in a fixed order."""

    def __init__(self):
        self.conversions: dict[tuple, Conversion] = {}
        self.conv_names: set = set()
        self.layouts: dict[str, str] = {}          # name -> datatype
        self.vtabs: dict[str, tuple] = {}          # name -> (long, [(value, text)])
        self.characteristics: list[list[str]] = []
        self.measurements: list[list[str]] = []
        self.groups: list[tuple] = []              # (name, long, root, chars, meas, subs)
        self.n_char = 0
        self.n_meas = 0

    def linear(self, factor: float, unit: str, rep: str) -> str:
        unit = unit or "-"
        key = ("LINEAR", num(factor), unit, rep)
        if key not in self.conversions:
            base = "CM_" + ident_part(rep + ("" if unit == "-" else "_" + unit))[:100]
            name, i = base, 1
            while name in self.conv_names:
                i += 1
                name = f"{base}_{i}"
            self.conv_names.add(name)
            self.conversions[key] = Conversion(name, f"{rep}: {num(factor)} {unit} per LSB",
                                               "LINEAR", unit, factor, fmt=fmt_string(factor))
        return self.conversions[key].name

    def verbal(self, vtab: str, long: str, pairs: list) -> str:
        key = ("TAB_VERB", vtab)
        if key not in self.conversions:
            name = "CM_" + vtab
            self.conv_names.add(name)
            self.vtabs[vtab] = (long, pairs)
            self.conversions[key] = Conversion(name, long, "TAB_VERB", "", vtab=vtab,
                                               fmt="%4.0")
        return self.conversions[key].name

    def layout(self, datatype: str) -> str:
        name = "RL_" + datatype
        self.layouts[name] = datatype
        return name


def limits_of(leaf: Leaf) -> tuple[int, int]:
    """The raw range of a leaf's data type."""
    if leaf.kind == "bool":
        return 0, 1
    bits = 8 * leaf.size
    return (-(1 << (bits - 1)), (1 << (bits - 1)) - 1) if leaf.signed else (0, (1 << bits) - 1)


def phys_pair(lo: float, hi: float) -> tuple[float, float]:
    return (lo, hi) if lo <= hi else (hi, lo)


def a2l_object(block: str, ident: str, long: str, head: list[str], leaf: Leaf,
               tail: list[str], symbol: str) -> list[str]:
    """The lines of a CHARACTERISTIC or MEASUREMENT: HEAD after the long name, MATRIX_DIM for
    an array, TAIL, then the SYMBOL_LINK to the ELF symbol."""
    lines = [f"/begin {block} {ident}", f"  {a2l_string(long)}"] + head
    if leaf.dims:
        lines.append("  MATRIX_DIM " + " ".join(str(d) for d in leaf.dims))
    return lines + tail + [f"  SYMBOL_LINK {a2l_string(symbol)} {leaf.offset}", f"/end {block}"]


def characteristic(mod: Module, ident: str, long: str, leaf: Leaf, address: int, conv: str,
                   factor: float, raw_range: tuple, read_only: bool, symbol: str) -> None:
    """A CHARACTERISTIC: VALUE for a scalar, VAL_BLK with MATRIX_DIM for an array."""
    kind = "VAL_BLK" if leaf.dims else "VALUE"
    lo, hi = phys_pair(raw_range[0] * factor, raw_range[1] * factor)
    elo, ehi = phys_pair(*(v * factor for v in limits_of(leaf)))
    head = [f"  {kind} 0x{address:08X} {mod.layout(leaf.datatype)} 0 {conv} {num(lo)} {num(hi)}",
            f"  EXTENDED_LIMITS {num(elo)} {num(ehi)}"]
    tail = ["  READ_ONLY"] if read_only else []
    mod.characteristics.append(a2l_object("CHARACTERISTIC", ident, long, head, leaf, tail, symbol))
    mod.n_char += 1


def measurement(mod: Module, ident: str, long: str, leaf: Leaf, address: int, conv: str,
                factor: float, raw_range: tuple, symbol: str, mask: int = 0) -> None:
    """A MEASUREMENT of the drive's state, with BIT_MASK for one flag of a word."""
    lo, hi = phys_pair(raw_range[0] * factor, raw_range[1] * factor)
    head = [f"  {leaf.datatype} {conv} 0 0 {num(lo)} {num(hi)}", f"  ECU_ADDRESS 0x{address:08X}"]
    tail = [f"  BIT_MASK 0x{mask:X}"] if mask else []
    mod.measurements.append(a2l_object("MEASUREMENT", ident, long, head, leaf, tail, symbol))
    mod.n_meas += 1


# ----------------------------------------------------------------------------- the table

def table_object(img: Image, name: str | None) -> tuple[Variable, str]:
    """The table object and its name (qfoc_params_<name>)."""
    tables = img.of_type(TABLE_TYPE)
    if name is not None:
        lines = manifest()
        if name not in lines:
            raise Refused(f"--table {name}: no table '{name}' in tables/manifest.txt (tables: "
                          f"{', '.join(sorted(lines))})")
        sym = TABLE_PREFIX + name
        found = [v for v in tables if v.name == sym or v.symbol == sym]
        if not found:
            raise Refused(f"--table {name}: no object {sym} of type {TABLE_TYPE} in {img.path} "
                          f"(tables in it: {', '.join(v.name for v in tables) or 'none'})")
        return found[0], name
    if not tables:
        raise Refused(f"{img.path}: no object of type {TABLE_TYPE} in the ELF's DWARF "
                      "(link a table of tables/ into the image)")
    if len(tables) > 1:
        raise Refused(f"{img.path}: {len(tables)} objects of type {TABLE_TYPE} "
                      f"({', '.join(v.name for v in tables)}): choose one with --table NAME")
    v = tables[0]
    if not v.name.startswith(TABLE_PREFIX):
        raise Refused(f"{img.path}: the table object {v.name} is not named {TABLE_PREFIX}<name> "
                      "(tables/<name>_params.c)")
    return v, v.name[len(TABLE_PREFIX):]


def describe_table(mod: Module, img: Image, var: Variable, tab: Table) -> list[str]:
    """The CHARACTERISTICs of the table; returns the group lines' member names."""
    if not var.symbol:
        raise Refused(f"{img.path}: {var.name} (DWARF, 0x{var.address:08X}, {var.size} B) has no "
                      "symbol of that address and size in the symbol table")
    lv = leaves(var.type_die)
    names = [n for n, _f in tab.fields]
    paths = [leaf.path for leaf in lv]
    if paths != names:
        extra = [p for p in paths if p not in names]
        missing = [n for n in names if n not in paths]
        raise Refused(f"{img.path}: the layout of {TABLE_TYPE} in the ELF differs from the tuning "
                      f"tool's (tools/tune/qfoc_tune.py): members only in the ELF: "
                      f"{', '.join(extra) or 'none'}; only in the tool: {', '.join(missing) or 'none'}"
                      + ("" if extra or missing else "; the order differs"))
    raw = img.read(var.address, var.size)
    if raw is None:
        raise Refused(f"{img.path}: {var.name} lies in no section with contents (.bss?): the table "
                      "must be an initialised constant")
    for leaf, (n, f) in zip(lv, tab.fields):
        width, signed = qt.CTYPES[f.ctype]
        if leaf.size != width or (leaf.signed if leaf.kind == "int" else False) != signed:
            raise Refused(f"{img.path}: {var.name}.{n} is {leaf.datatype} in the ELF, {f.ctype} in "
                          "the tuning tool")
        value = img.decode(raw[leaf.offset:leaf.offset + leaf.size], leaf.signed)
        if value != f.value:
            raise Refused(f"{img.path}: {var.name}.{n} = {value} in the image, but the tuning tool "
                          f"makes {f.value} of {tab.motor}"
                          + (f" ({' '.join(tab.overrides)})" if tab.overrides else "")
                          + ": the image holds another table (make tune, then rebuild the image)")
    groups: dict[str, list] = {}
    for leaf, (n, f) in zip(lv, tab.fields):
        p = f.phys
        conv = mod.linear(p.factor, p.unit, p.rep)
        long = f"{n}: {p.rep}" + (f"; motor file {p.key}" if p.key else "") \
            + ("; READ_ONLY: the identity or the scaling of other fields, changed by the tuning tool"
               if p.fixed else "")
        characteristic(mod, f"{var.name}.{n}", long, leaf, var.address + leaf.offset, conv,
                       p.factor, tab.ranges[n], p.fixed, var.symbol)
        head = n.rsplit(".", 1)[0] if "." in n else ""
        groups.setdefault(head, []).append(f"{var.name}.{n}")
    subs = []
    for head in sorted(h for h in groups if h):
        subs.append(f"{var.name}.{head}")
        mod.groups.append((f"{var.name}.{head}", f"{head} of the parameter table", False,
                           groups[head], [], []))
    mod.groups.append((var.name, f"parameter table {tab.name} ({tab.motor})", True,
                       groups.get("", []), [], subs))
    return names


# ----------------------------------------------------------------------------- the drive

def drive_object(img: Image, name: str | None) -> Variable:
    drives = img.of_type(DRIVE_TYPE)
    if name is not None:
        found = img.find(name)
        if not found:
            raise Refused(f"--drive {name}: no variable or symbol '{name}' in {img.path} "
                          f"({DRIVE_TYPE} objects: {', '.join(v.name for v in drives) or 'none'})")
        ok = [v for v in found if v.type_name == DRIVE_TYPE]
        if not ok:
            raise Refused(f"--drive {name}: '{name}' in {img.path} is of type "
                          f"{found[0].type_name or 'unnamed'}, not {DRIVE_TYPE}")
        return ok[0]
    if not drives:
        raise Refused(f"{img.path}: no object of type {DRIVE_TYPE} in the ELF's DWARF (give "
                      "--no-drive for a description of the table alone)")
    if len(drives) > 1:
        raise Refused(f"{img.path}: {len(drives)} objects of type {DRIVE_TYPE} "
                      f"({', '.join(v.name for v in drives)}): choose one with --drive NAME")
    return drives[0]


def quantities(tab: Table) -> dict:
    """quantity -> (factor, unit, representation) of the measurements."""
    b = tab.bases
    rpm_pu = b.f_base * 60.0 / tab.pole_pairs
    return {
        "rpm": (1.0, "rpm", "rpm"), "dV": (0.1, "V", "0.1 V"), "cA": (0.01, "A", "0.01 A"),
        "ddegC": (0.1, "degC", "0.1 degC"), "ms": (1.0, "ms", "ticks of 1 ms"),
        "count": (1.0, "-", "integer"), "adc": (1.0, "ADC codes", "12-bit ADC code"),
        "ticks": (1.0, "ticks", "timer ticks"),
        "speed": (rpm_pu / 32768.0, "rpm", "Q15 of w_base (60 f_base / n_p rpm)"),
        "current": (b.i_base / 32768.0, "A", "Q15 of I_base"),
        "voltage": (b.v_base / 32768.0, "V", "Q15 of V_base"),
        "flux": (b.psi_base / 32768.0, "Wb", "Q15 of psi_base"),
        "ratio": (1.0 / 32768.0, "-", "Q15"),
        "angle": (360.0 / 65536.0, "deg", "65536 counts per electrical turn"),
    }


def describe_drive(mod: Module, img: Image, var: Variable, tab: Table) -> None:
    if not var.symbol:
        raise Refused(f"{img.path}: {var.name} (DWARF, 0x{var.address:08X}, {var.size} B) has no "
                      "symbol of that address and size in the symbol table")
    by_path = {leaf.path: leaf for leaf in leaves(var.type_die)}
    states = header_codes(SM_H, "QFOC_STATE_", "uint8_t")
    subs = header_codes(SM_H, "QFOC_SUB_", "uint8_t")
    faults = [(n, v) for n, v in header_codes(FAULT_H, "QFOC_FAULT_", "uint16_t")
              if v and not v & (v - 1)]
    if not states or not subs or not faults:
        raise Refused("include/qfoc/sm.h or fault.h: no QFOC_STATE_, QFOC_SUB_ or QFOC_FAULT_ "
                      "codes found")
    q = quantities(tab)
    names = []
    for path, long, kind in MEASUREMENTS:
        leaf = by_path.get(path)
        if leaf is None:
            raise Refused(f"{img.path}: {var.name} ({DRIVE_TYPE}) has no member {path}")
        ident = f"{var.name}.{path}"
        if kind in ("state", "substate", "bool"):
            pairs = {"state": states, "substate": subs,
                     "bool": [("false", 0), ("true", 1)]}[kind]
            vt = {"state": "VT_state", "substate": "VT_substate", "bool": "VT_bool"}[kind]
            conv = mod.verbal(vt, {"state": "sm.h QFOC_STATE_*", "substate": "sm.h QFOC_SUB_*",
                                   "bool": "false / true"}[kind],
                              sorted((v, n) for n, v in pairs))
            measurement(mod, ident, long, leaf, var.address + leaf.offset, conv, 1.0,
                        (min(v for _n, v in pairs), max(v for _n, v in pairs)), var.symbol)
        elif kind == "faults":
            conv = mod.linear(1.0, "-", "fault bits of fault.h")
            measurement(mod, ident, long, leaf, var.address + leaf.offset, conv, 1.0,
                        (0, sum(v for _n, v in faults)), var.symbol)
        else:
            factor, unit, rep = q[kind]
            conv = mod.linear(factor, unit, rep)
            measurement(mod, ident, long, leaf, var.address + leaf.offset, conv, factor,
                        limits_of(leaf), var.symbol)
        names.append(ident)
    word = by_path[FAULT_WORD]
    conv = mod.verbal("VT_bool", "false / true", [(0, "false"), (1, "true")])
    for fname, mask in faults:
        ident = f"{var.name}.{FAULT_WORD}.{fname}"
        measurement(mod, ident, f"fault {fname} latched (fault.h QFOC_FAULT_{fname}, bit mask "
                    f"0x{mask:04X} of {FAULT_WORD})", word, var.address + word.offset, conv, 1.0,
                    (0, 1), var.symbol, mask)
        names.append(ident)
    mod.groups.append((var.name, f"drive {var.name} ({DRIVE_TYPE}): status, state, references "
                       "and estimates", True, [], names, []))


# ----------------------------------------------------------------------------- the file

def segment(img: Image, ident: str, address: int, size: int, prg: str, what: str,
            whole: bool) -> list[str]:
    """A MEMORY_SEGMENT: the object's extent (whole=False) or the ELF section that holds it;
    FLASH for a read-only section, RAM for a writable one."""
    sec = img.section_of(address, size)
    if sec is None:
        raise Refused(f"{img.path}: {what} at 0x{address:08X} lies in no allocated section")
    mem = "RAM" if sec["sh_flags"] & 0x1 else "FLASH"           # SHF_WRITE
    if whole:
        address, size = int(sec["sh_addr"]), int(sec["sh_size"])
        what = f"ELF section {sec.name} ({what})"
    else:
        what = f"{what} (in ELF section {sec.name})"
    return [f"/begin MEMORY_SEGMENT {ident}_{mem}", f"  {a2l_string(what)}",
            f"  {prg} {mem} INTERN 0x{address:08X} 0x{size:X} -1 -1 -1 -1 -1",
            "/end MEMORY_SEGMENT"]


def indent(lines: list[str], n: int) -> list[str]:
    return [(" " * n + ln) if ln else ln for ln in lines]


def build(elf: Path, table: str | None, drive: str | None, no_drive: bool) -> tuple[str, Module]:
    img = Image(elf)
    var, name = table_object(img, table)
    tab = tune(name)
    mod = Module()
    describe_table(mod, img, var, tab)
    dvar = None
    if not no_drive:
        dvar = drive_object(img, drive)
        describe_drive(mod, img, dvar, tab)
    crc = tab.fields[-1][1].value
    sha = hashlib.sha256(img.data).hexdigest()
    module = f"qfoc_{ident_part(name)}"
    segs = segment(img, "table", var.address, var.size, "DATA", f"parameter table {var.name}",
                   False)
    if dvar is not None:
        segs += segment(img, "drive", dvar.address, dvar.size, "VARIABLES",
                        f"holds the drive object {dvar.name}", True)
    order = "MSB_LAST" if img.little else "MSB_FIRST"
    consts = [("QFOC_TABLE", name), ("QFOC_TABLE_SYMBOL", var.name),
              ("QFOC_TABLE_CRC", f"0x{crc:08X}"), ("QFOC_MOTOR_FILE", tab.motor),
              ("QFOC_MOTOR_OVERRIDES", " ".join(tab.overrides)),
              ("QFOC_PARAMS_VERSION", str(qt.PARAMS_VERSION)),
              ("QFOC_IMAGE", f"{elf.name} sha256 {sha}")]
    body = []
    body += [f"/begin MOD_PAR {a2l_string('memory and identity of the image')}",
             f"  VERSION {a2l_string(f'table {name} CRC 0x{crc:08X}')}",
             f"  CPU_TYPE {a2l_string(img.cpu())}"]
    body += indent(segs, 2)
    body += [f"  SYSTEM_CONSTANT {a2l_string(k)} {a2l_string(v)}" for k, v in consts]
    body += ["/end MOD_PAR", "",
             f"/begin MOD_COMMON {a2l_string('ARM EABI: little-endian, natural alignment')}",
             f"  BYTE_ORDER {order}", "  ALIGNMENT_BYTE 1", "  ALIGNMENT_WORD 2",
             "  ALIGNMENT_LONG 4", "  ALIGNMENT_INT64 8", "  ALIGNMENT_FLOAT32_IEEE 4",
             "  ALIGNMENT_FLOAT64_IEEE 8", "  DEPOSIT ABSOLUTE", "/end MOD_COMMON", ""]
    for lines in mod.characteristics + mod.measurements:
        body += lines + [""]
    for c in sorted(mod.conversions.values(), key=lambda c: c.name):
        body += [f"/begin COMPU_METHOD {c.name}", f"  {a2l_string(c.long)}",
                 f"  {c.kind} {a2l_string(c.fmt)} {a2l_string('' if c.unit == '-' else c.unit)}"]
        body += [f"  COEFFS_LINEAR {num(c.factor)} 0"] if c.kind == "LINEAR" else \
            [f"  COMPU_TAB_REF {c.vtab}"]
        body += ["/end COMPU_METHOD", ""]
    for vt in sorted(mod.vtabs):
        long, pairs = mod.vtabs[vt]
        body += [f"/begin COMPU_VTAB {vt}", f"  {a2l_string(long)}", f"  TAB_VERB {len(pairs)}"]
        body += [f"  {v} {a2l_string(t)}" for v, t in pairs]
        body += ["/end COMPU_VTAB", ""]
    for rl in sorted(mod.layouts):
        body += [f"/begin RECORD_LAYOUT {rl}",
                 f"  FNC_VALUES 1 {mod.layouts[rl]} COLUMN_DIR DIRECT", "/end RECORD_LAYOUT", ""]
    for gname, long, root, chars, meas, subs in mod.groups:
        body += [f"/begin GROUP {gname}", f"  {a2l_string(long)}"]
        if root:
            body.append("  ROOT")
        for kw, items in (("REF_CHARACTERISTIC", chars), ("REF_MEASUREMENT", meas),
                          ("SUB_GROUP", subs)):
            if items:
                body += [f"  /begin {kw}"] + [f"    {i}" for i in items] + [f"  /end {kw}"]
        body += ["/end GROUP", ""]
    while body and not body[-1]:
        body.pop()
    source = tab.motor + "".join(" " + o for o in tab.overrides)
    version = version_string()
    project = a2l_string(f"qfoc {version}: fixed-point FOC for PMSM compressor drives")
    module_long = a2l_string(f"{var.name} and " + (dvar.name if dvar is not None else "no drive")
                             + f" in {elf.name}")
    head = [
        "/* qfoc calibration description (ASAM MCD-2 MC, ASAP2 1.71), generated by",
        f"   tools/a2l/qfoc_a2l.py from {elf.name} (sha256 {sha})",
        f"   and tables/{name}_params.c ({source}, CRC 0x{crc:08X}): do not edit.",
        "   The table lies in flash and carries a CRC over its fields (include/qfoc/params.h):",
        "   the drive refuses a table whose CRC does not match (QFOC_PARAMS_ERR_CRC).  A",
        "   calibrated value goes into the image through the motor file and the tuning tool;",
        "   a calibration tool that writes a field must write the field crc with it. */",
        "",
        f"ASAP2_VERSION {ASAP2_VERSION[0]} {ASAP2_VERSION[1]}",
        "",
        f"/begin PROJECT qfoc {project}",
        f"  /begin HEADER {a2l_string(f'image {elf.name}, table {name}')}",
        f"    VERSION {a2l_string(f'qfoc {version}, table CRC 0x{crc:08X}')}",
        f"    PROJECT_NO {module}",
        "  /end HEADER",
        "",
        f"  /begin MODULE {module} {module_long}",
    ]
    text = "\n".join(head + indent(body, 4) + ["  /end MODULE", "/end PROJECT", ""])
    return text, mod


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(
        prog="qfoc_a2l.py",
        description="Write the ASAM MCD-2 MC (A2L, ASAP2 1.71) calibration description of the "
                    "parameter table and the drive in a firmware image: addresses, types and "
                    "offsets from the ELF's symbols and DWARF, conversions and limits from the "
                    "tuning tool (tools/tune/qfoc_tune.py).",
        epilog="Exit codes: 0 written; 1 refused (nothing written).  tools/a2l/README.md "
               "describes the file and how it is checked.")
    ap.add_argument("elf", type=Path, help="the firmware image, e.g. build/s32k144/qfoc_compressor.elf")
    ap.add_argument("-o", "--out", type=Path, help="the A2L file (default: the ELF's path with .a2l)")
    ap.add_argument("--table", help="table name of tables/manifest.txt (symbol qfoc_params_NAME); "
                                    "default: the one qfoc_param_table_t object of the image")
    ap.add_argument("--drive", help="the qfoc_drive_t object (its DWARF name or symbol); default: "
                                    "the one qfoc_drive_t object of the image")
    ap.add_argument("--no-drive", action="store_true", help="describe the table alone")
    args = ap.parse_args(argv)
    out = args.out if args.out is not None else args.elf.with_suffix(".a2l")
    try:
        if args.no_drive and args.drive is not None:
            raise Refused(f"--drive {args.drive} and --no-drive: give one of them")
        if not args.elf.is_file():
            raise Refused(f"{args.elf}: no such ELF file" + (
                " (build it: make firmware)" if not args.elf.exists() else " (not a file)"))
        text, mod = build(args.elf, args.table, args.drive, args.no_drive)
    except Refused as exc:
        print(f"qfoc_a2l: {exc}", file=sys.stderr)
        print("qfoc_a2l: refused, nothing written", file=sys.stderr)
        return 1
    tmp = out.with_name(f".{out.name}.tmp")
    out.parent.mkdir(parents=True, exist_ok=True)
    tmp.write_text(text, encoding="utf-8")
    os.replace(tmp, out)
    print(f"a2l: {out}: ASAP2 {ASAP2_VERSION[0]}.{ASAP2_VERSION[1]}, {mod.n_char} CHARACTERISTICs, "
          f"{mod.n_meas} MEASUREMENTs, {len(mod.conversions)} COMPU_METHODs, "
          f"{len(mod.layouts)} RECORD_LAYOUTs")
    return 0


if __name__ == "__main__":
    sys.exit(main())
