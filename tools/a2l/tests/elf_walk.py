"""The tests' own view of a firmware ELF (pyelftools): symbols, section contents and the DWARF
member paths of the objects, computed independently of tools/a2l/qfoc_a2l.py, and the check
of an A2L's addresses, sizes, types and memory segments against them.

  Elf(path)                       the image
  Elf.locate(name) -> Place       an A2L object name '<variable>.<member>.<member>[...]': the
                                  variable (DWARF name or symbol), the member's address, size,
                                  signedness, array dimensions, and what is left of the name
                                  when it goes below a scalar (a bit of a fault word)
  check_against_elf(doc, elf)     the findings, [] when every CHARACTERISTIC and MEASUREMENT is
                                  where the ELF says and of its type
"""
from __future__ import annotations

import io
from dataclasses import dataclass

from elftools.elf.elffile import ELFFile

import a2l_reader as ar

QUALIFIERS = ("DW_TAG_typedef", "DW_TAG_const_type", "DW_TAG_volatile_type")


@dataclass
class Place:
    variable: str
    base: int            # the variable's address
    offset: int          # the member's offset in it
    size: int            # bytes of one element
    signed: bool
    dims: tuple
    rest: str            # the part of the name below a scalar ('' normally)

    @property
    def address(self) -> int:
        return self.base + self.offset


def _strip(die):
    while die.tag in QUALIFIERS:
        die = die.get_DIE_from_attribute("DW_AT_type")
    return die


class Elf:
    def __init__(self, path):
        self.data = open(path, "rb").read()
        self.elf = ELFFile(io.BytesIO(self.data))
        self.order = "little" if self.elf.little_endian else "big"
        self.symbols = {}
        for s in self.elf.get_section_by_name(".symtab").iter_symbols():
            if s["st_info"]["type"] == "STT_OBJECT":
                self.symbols[s.name] = (s["st_value"], s["st_size"])
        self.vars = {}      # DWARF name -> (address, type DIE)
        for cu in self.elf.get_dwarf_info().iter_CUs():
            for die in cu.iter_DIEs():
                loc = die.attributes.get("DW_AT_location")
                if die.tag != "DW_TAG_variable" or loc is None or not isinstance(loc.value, list):
                    continue
                if not loc.value or loc.value[0] != 0x03:        # DW_OP_addr
                    continue
                spec = die.get_DIE_from_attribute("DW_AT_specification") \
                    if "DW_AT_specification" in die.attributes else die
                name = (die.attributes.get("DW_AT_name") or spec.attributes.get("DW_AT_name"))
                tdie = die if "DW_AT_type" in die.attributes else spec
                if name is None or "DW_AT_type" not in tdie.attributes:
                    continue
                addr = int.from_bytes(bytes(loc.value[1:]), self.order)
                self.vars[name.value.decode()] = (addr, tdie.get_DIE_from_attribute("DW_AT_type"))

    def variable(self, name: str):
        """(address, type DIE) of a variable named in the DWARF or the symbol table."""
        if name in self.vars:
            return self.vars[name]
        if name in self.symbols:
            addr = self.symbols[name][0]
            for a, t in self.vars.values():
                if a == addr:
                    return a, t
        return None

    def locate(self, ident: str) -> Place | None:
        var, _dot, path = ident.partition(".")
        found = self.variable(var)
        if found is None:
            return None
        base, die = found
        offset = 0
        parts = path.split(".") if path else []
        k = 0
        while k < len(parts):
            t = _strip(die)
            if t.tag != "DW_TAG_structure_type":
                break
            name, _b, index = parts[k].partition("[")
            member = None
            for m in t.iter_children():
                if m.tag == "DW_TAG_member" and m.attributes["DW_AT_name"].value.decode() == name:
                    member = m
            if member is None:
                return None
            offset += member.attributes["DW_AT_data_member_location"].value
            die = member.get_DIE_from_attribute("DW_AT_type")
            if index:
                arr = _strip(die)
                el = arr.get_DIE_from_attribute("DW_AT_type")
                offset += int(index.rstrip("]")) * _strip(el).attributes["DW_AT_byte_size"].value
                die = el
            k += 1
        t = _strip(die)
        dims = ()
        if t.tag == "DW_TAG_array_type":
            dims = tuple(s.attributes["DW_AT_upper_bound"].value + 1 for s in t.iter_children()
                         if s.tag == "DW_TAG_subrange_type")
            t = _strip(t.get_DIE_from_attribute("DW_AT_type"))
        if t.tag != "DW_TAG_base_type":
            return None
        enc = t.attributes["DW_AT_encoding"].value
        return Place(var, base, offset, t.attributes["DW_AT_byte_size"].value,
                     enc in (0x05, 0x06), dims, ".".join(parts[k:]))

    def section(self, address: int, size: int):
        for sec in self.elf.iter_sections():
            lo = sec["sh_addr"]
            if sec["sh_flags"] & 0x2 and lo <= address and address + size <= lo + sec["sh_size"]:
                return sec
        return None

    def read_int(self, address: int, size: int, signed: bool) -> int:
        sec = self.section(address, size)
        assert sec is not None and sec["sh_type"] != "SHT_NOBITS", hex(address)
        off = address - sec["sh_addr"]
        return int.from_bytes(sec.data()[off:off + size], self.order, signed=signed)


def scalars(elf: Elf, var: str) -> list[str]:
    """The member paths of every scalar (or array of scalars) of a variable, in order."""
    _addr, die = elf.variable(var)
    out = []

    def walk(d, path):
        t = _strip(d)
        if t.tag == "DW_TAG_structure_type":
            for m in t.iter_children():
                if m.tag == "DW_TAG_member":
                    name = m.attributes["DW_AT_name"].value.decode()
                    walk(m.get_DIE_from_attribute("DW_AT_type"), f"{path}.{name}" if path else name)
        else:
            out.append(path)
    walk(die, "")
    return out


def check_against_elf(doc: ar.A2l, elf: Elf) -> list[str]:
    """Every object's address, size, signedness, dimensions, symbol link and memory segment
    against the ELF's symbols, DWARF and sections."""
    err = []
    layouts = doc.of("RECORD_LAYOUT")
    common = doc.module.blocks("MOD_COMMON")[0]
    align = {1: (common.kw("ALIGNMENT_BYTE") or [1])[0], 2: (common.kw("ALIGNMENT_WORD") or [2])[0],
             4: (common.kw("ALIGNMENT_LONG") or [4])[0], 8: (common.kw("ALIGNMENT_INT64") or [8])[0]}
    order = common.kw("BYTE_ORDER")[0]
    if order != ("MSB_LAST" if elf.order == "little" else "MSB_FIRST"):
        err.append(f"MOD_COMMON: BYTE_ORDER {order} for a {elf.order}-endian image")
    segments = [s for mp in doc.module.blocks("MOD_PAR") for s in mp.blocks("MEMORY_SEGMENT")]
    objs = [(c, c.params[3], layouts[c.params[4]].kw("FNC_VALUES")[1] if c.params[4] in layouts
             else None) for c in doc.module.blocks("CHARACTERISTIC")]
    objs += [(m, (m.kw("ECU_ADDRESS") or [None])[0], m.params[2])
             for m in doc.module.blocks("MEASUREMENT")]
    for blk, address, datatype in objs:
        where = f"{blk.kind} {blk.name} (line {blk.line})"
        place = elf.locate(blk.name)
        if place is None:
            err.append(f"{where}: no such variable and member in the ELF's DWARF")
            continue
        if place.rest:
            mask = blk.kw("BIT_MASK")
            if mask is None or "." in place.rest or mask[0] & (mask[0] - 1) or \
                    mask[0] >= 1 << (8 * place.size):
                err.append(f"{where}: {place.rest} is below the scalar {blk.name[:-len(place.rest) - 1]}"
                           " without a one-bit BIT_MASK within it")
        if address != place.address:
            err.append(f"{where}: address 0x{address or 0:08X} in the A2L, 0x{place.address:08X} "
                       f"from the ELF ({place.variable} + {place.offset})")
        if datatype is None:
            continue
        size, signed = ar.DATATYPES[datatype]
        if size != place.size or (signed != place.signed and not datatype.startswith("FLOAT")):
            err.append(f"{where}: {datatype} in the A2L, {'signed' if place.signed else 'unsigned'} "
                       f"{place.size} bytes in the ELF")
        dims = tuple(blk.kw("MATRIX_DIM") or ())
        if dims != place.dims:
            err.append(f"{where}: MATRIX_DIM {dims or 'none'} in the A2L, {place.dims or 'none'} in "
                       "the ELF")
        link = blk.kw("SYMBOL_LINK")
        if link is not None:
            sym = elf.symbols.get(link[0])
            if sym is None or sym[0] + link[1] != place.address:
                err.append(f"{where}: SYMBOL_LINK {link[0]} + {link[1]} is not its address")
        if place.address % align.get(place.size, 1):
            err.append(f"{where}: address 0x{place.address:08X} not aligned to "
                       f"{align.get(place.size)} (MOD_COMMON)")
        n = 1
        for d in place.dims:
            n *= d
        prg = ("DATA", "CALIBRATION_VARIABLES") if blk.kind == "CHARACTERISTIC" else \
            ("VARIABLES", "DATA", "CALIBRATION_VARIABLES")
        inside = [s for s in segments if s.params[2] in prg and
                  s.params[5] <= place.address and place.address + n * place.size <= s.params[5] + s.params[6]]
        if not inside:
            err.append(f"{where}: in no MEMORY_SEGMENT of type {' or '.join(prg)}")
        sec = elf.section(place.address, n * place.size)
        for s in inside:
            mem = "RAM" if sec is not None and sec["sh_flags"] & 0x1 else "FLASH"
            if s.params[3] != mem:
                err.append(f"{where}: MEMORY_SEGMENT {s.name} is {s.params[3]}, the ELF section "
                           f"{sec.name if sec is not None else '?'} is {mem}")
    return err
