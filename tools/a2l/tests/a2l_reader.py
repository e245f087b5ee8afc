"""A small, strict reader of ASAM MCD-2 MC files (A2L) and the checks of the tests of
tools/a2l/ (written for them: it shares no code with the tool it checks).

It reads the part of ASAP2 1.71 a calibration description of qfoc uses (PROJECT, HEADER,
MODULE, MOD_PAR with MEMORY_SEGMENT, MOD_COMMON, CHARACTERISTIC, MEASUREMENT, COMPU_METHOD,
COMPU_VTAB, RECORD_LAYOUT, GROUP) with the positional parameters and the optional keywords of
each, typed: an element the subset does not know is an error, not skipped.  The syntax
facts (parameter order, keyword names, enumerations) are those of the ASAM MCD-2 MC standard,
version 1.7.1, section 3.5 (keyword reference).

  parse(text) -> A2l        the tree; A2lError (with the line) on a syntax error: a /begin
                            without its /end, an /end of another block, a parameter of the
                            wrong type, an unknown keyword, an invalid identifier
  check(doc) -> [str]       the structure's rules: ASAP2_VERSION 1 71, names unique, every
                            referenced COMPU_METHOD, COMPU_VTAB, RECORD_LAYOUT and GROUP member
                            defined, limits ordered and within EXTENDED_LIMITS, VAL_BLK with
                            MATRIX_DIM, a MEASUREMENT with ECU_ADDRESS
  Conversion.phys(raw)      the physical value of a raw integer (IDENTICAL, LINEAR, RAT_FUNC,
                            TAB_VERB)
"""
from __future__ import annotations

import re
from dataclasses import dataclass, field

DATATYPES = {"UBYTE": (1, False), "SBYTE": (1, True), "UWORD": (2, False), "SWORD": (2, True),
             "ULONG": (4, False), "SLONG": (4, True), "A_UINT64": (8, False),
             "A_INT64": (8, True), "FLOAT32_IEEE": (4, True), "FLOAT64_IEEE": (8, True)}
E_DATATYPE = "enum:" + "|".join(DATATYPES)
E_BYTE_ORDER = "enum:MSB_LAST|MSB_FIRST|LITTLE_ENDIAN|BIG_ENDIAN|MSB_FIRST_MSW_LAST|MSB_LAST_MSW_FIRST"
E_CHAR_TYPE = "enum:ASCII|CURVE|MAP|CUBOID|CUBE_4|CUBE_5|VAL_BLK|VALUE"
E_CONV_TYPE = "enum:IDENTICAL|FORM|LINEAR|RAT_FUNC|TAB_INTP|TAB_NOINTP|TAB_VERB"
E_PRG_TYPE = ("enum:CALIBRATION_VARIABLES|CODE|DATA|EXCLUDE_FROM_FLASH|OFFLINE_DATA|RESERVED|"
              "SERAM|VARIABLES")
E_MEM_TYPE = "enum:EEPROM|EPROM|FLASH|RAM|ROM|REGISTER|NOT_IN_ECU"
E_MEM_ATTR = "enum:INTERN|EXTERN"
E_INDEX_MODE = "enum:ALTERNATE_CURVES|ALTERNATE_WITH_X|ALTERNATE_WITH_Y|COLUMN_DIR|ROW_DIR"
E_ADDR_TYPE = "enum:PBYTE|PWORD|PLONG|PLONGLONG|DIRECT"
E_DEPOSIT = "enum:ABSOLUTE|DIFFERENCE"

ALIGN = {k: ["int"] for k in ("ALIGNMENT_BYTE", "ALIGNMENT_WORD", "ALIGNMENT_LONG",
                              "ALIGNMENT_INT64", "ALIGNMENT_FLOAT16_IEEE",
                              "ALIGNMENT_FLOAT32_IEEE", "ALIGNMENT_FLOAT64_IEEE")}

# block -> (positional parameters, child blocks allowed, keywords with their parameters).
# A parameter type ending in '*' takes every following token of that type (at least none),
# '+' at least one.
BLOCKS = {
    "PROJECT": (["ident", "string"], {"HEADER", "MODULE"}, {}),
    "HEADER": (["string"], set(), {"VERSION": ["string"], "PROJECT_NO": ["ident"]}),
    "MODULE": (["ident", "string"], {"MOD_PAR", "MOD_COMMON", "CHARACTERISTIC", "MEASUREMENT",
                                     "COMPU_METHOD", "COMPU_VTAB", "RECORD_LAYOUT", "GROUP"}, {}),
    "MOD_PAR": (["string"], {"MEMORY_SEGMENT"},
                {"VERSION": ["string"], "CPU_TYPE": ["string"], "ECU": ["string"],
                 "SUPPLIER": ["string"], "USER": ["string"], "CUSTOMER": ["string"],
                 "NO_OF_INTERFACES": ["int"], "SYSTEM_CONSTANT": ["string", "string"],
                 "ADDR_EPK": ["int"], "EPK": ["string"]}),
    "MEMORY_SEGMENT": (["ident", "string", E_PRG_TYPE, E_MEM_TYPE, E_MEM_ATTR, "int", "int",
                        "int", "int", "int", "int", "int"], set(), {}),
    "MOD_COMMON": (["string"], set(),
                   {"BYTE_ORDER": [E_BYTE_ORDER], "DEPOSIT": [E_DEPOSIT], "DATA_SIZE": ["int"],
                    **ALIGN}),
    "CHARACTERISTIC": (["ident", "string", E_CHAR_TYPE, "int", "ident", "float", "ident",
                        "float", "float"], set(),
                       {"EXTENDED_LIMITS": ["float", "float"], "READ_ONLY": [],
                        "MATRIX_DIM": ["int+"], "NUMBER": ["int"],
                        "SYMBOL_LINK": ["string", "int"], "FORMAT": ["string"],
                        "PHYS_UNIT": ["string"], "DISPLAY_IDENTIFIER": ["ident"],
                        "BYTE_ORDER": [E_BYTE_ORDER], "ECU_ADDRESS_EXTENSION": ["int"],
                        "BIT_MASK": ["int"], "DISCRETE": [], "GUARD_RAILS": [],
                        "STEP_SIZE": ["float"]}),
    "MEASUREMENT": (["ident", "string", E_DATATYPE, "ident", "int", "float", "float", "float"],
                    set(),
                    {"ECU_ADDRESS": ["int"], "MATRIX_DIM": ["int+"], "ARRAY_SIZE": ["int"],
                     "BIT_MASK": ["int"], "SYMBOL_LINK": ["string", "int"], "FORMAT": ["string"],
                     "PHYS_UNIT": ["string"], "READ_WRITE": [], "DISCRETE": [],
                     "BYTE_ORDER": [E_BYTE_ORDER], "DISPLAY_IDENTIFIER": ["ident"],
                     "ECU_ADDRESS_EXTENSION": ["int"]}),
    "COMPU_METHOD": (["ident", "string", E_CONV_TYPE, "string", "string"], set(),
                     {"COEFFS_LINEAR": ["float", "float"], "COEFFS": ["float"] * 6,
                      "COMPU_TAB_REF": ["ident"], "REF_UNIT": ["ident"],
                      "STATUS_STRING_REF": ["ident"]}),
    "COMPU_VTAB": (["ident", "string", "enum:TAB_VERB", "int", "pairs"], set(),
                   {"DEFAULT_VALUE": ["string"]}),
    "RECORD_LAYOUT": (["ident"], set(),
                      {"FNC_VALUES": ["int", E_DATATYPE, E_INDEX_MODE, E_ADDR_TYPE], **ALIGN}),
    "GROUP": (["ident", "string"], {"REF_CHARACTERISTIC", "REF_MEASUREMENT", "SUB_GROUP"},
              {"ROOT": []}),
    "REF_CHARACTERISTIC": (["ident*"], set(), {}),
    "REF_MEASUREMENT": (["ident*"], set(), {}),
    "SUB_GROUP": (["ident*"], set(), {}),
}

PARTIAL = re.compile(r"[A-Za-z_][A-Za-z0-9_]*(?:\[[0-9]+\])*")
INT = re.compile(r"[+-]?(?:0[xX][0-9A-Fa-f]+|[0-9]+)")
FLOAT = re.compile(r"[+-]?(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][+-]?[0-9]+)?|[+-]?0[xX][0-9A-Fa-f]+")


class A2lError(Exception):
    """A syntax error, with the line it was found on."""


def valid_identifier(name: str) -> bool:
    """ASAP2 identifier: partial identifiers joined by '.', each a letter or '_' then letters,
    digits and '_', at most 128 characters, optionally followed by array indices [n]; the
    whole at most 1024 characters."""
    if not name or len(name) > 1024:
        return False
    for part in name.split("."):
        if not PARTIAL.fullmatch(part) or len(part.split("[")[0]) > 128:
            return False
    return True


@dataclass
class Token:
    kind: str     # "begin", "end", "string", "word"
    text: str
    line: int


def tokenize(text: str) -> list[Token]:
    out, i, line, n = [], 0, 1, len(text)
    while i < n:
        c = text[i]
        if c == "\n":
            line += 1
            i += 1
        elif c.isspace():
            i += 1
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            if j < 0:
                raise A2lError(f"line {line}: a comment /* without */")
            line += text.count("\n", i, j)
            i = j + 2
        elif text.startswith("//", i):
            j = text.find("\n", i)
            i = n if j < 0 else j
        elif c == '"':
            j, buf, start = i + 1, [], line
            while True:
                if j >= n:
                    raise A2lError(f"line {start}: a string without its closing quote")
                ch = text[j]
                if ch == "\\" and j + 1 < n:
                    buf.append(text[j + 1])
                    j += 2
                elif ch == '"' and text.startswith('""', j):
                    buf.append('"')
                    j += 2
                elif ch == '"':
                    j += 1
                    break
                else:
                    if ch == "\n":
                        line += 1
                    buf.append(ch)
                    j += 1
            out.append(Token("string", "".join(buf), start))
            i = j
        else:
            j = i
            while j < n and not text[j].isspace() and text[j] != '"':
                j += 1
            word = text[i:j]
            if word == "/begin":
                out.append(Token("begin", word, line))
            elif word == "/end":
                out.append(Token("end", word, line))
            else:
                out.append(Token("word", word, line))
            i = j
    return out


@dataclass
class Block:
    kind: str
    params: list
    line: int
    keywords: list = field(default_factory=list)   # (name, [values], line)
    children: list = field(default_factory=list)

    @property
    def name(self) -> str:
        return self.params[0] if self.params else ""

    def kw(self, name: str):
        """The values of a keyword (None when absent; [] for a flag)."""
        for k, v, _line in self.keywords:
            if k == name:
                return v
        return None

    def blocks(self, kind: str) -> list:
        return [c for c in self.children if c.kind == kind]


def _value(tok: Token, typ: str, where: str):
    if typ == "string":
        if tok.kind != "string":
            raise A2lError(f"line {tok.line}: {where}: a string expected, found {tok.text!r}")
        return tok.text
    if tok.kind != "word":
        raise A2lError(f"line {tok.line}: {where}: {typ} expected, found {tok.text!r}")
    if typ == "ident":
        if not valid_identifier(tok.text):
            raise A2lError(f"line {tok.line}: {where}: {tok.text!r} is not a valid ASAP2 identifier")
        return tok.text
    if typ == "int":
        if not INT.fullmatch(tok.text):
            raise A2lError(f"line {tok.line}: {where}: an integer expected, found {tok.text!r}")
        return int(tok.text, 0)
    if typ == "float":
        if not FLOAT.fullmatch(tok.text):
            raise A2lError(f"line {tok.line}: {where}: a number expected, found {tok.text!r}")
        return float(int(tok.text, 16)) if "x" in tok.text.lower() else float(tok.text)
    if typ.startswith("enum:"):
        if tok.text not in typ[5:].split("|"):
            raise A2lError(f"line {tok.line}: {where}: {tok.text!r} is not one of "
                           f"{typ[5:].replace('|', ', ')}")
        return tok.text
    raise AssertionError(typ)


def _is(tok: Token, typ: str) -> bool:
    try:
        _value(tok, typ, "")
        return True
    except A2lError:
        return False


class _Parser:
    def __init__(self, tokens: list[Token]):
        self.t = tokens
        self.i = 0

    def peek(self) -> Token | None:
        return self.t[self.i] if self.i < len(self.t) else None

    def take(self, what: str) -> Token:
        tok = self.peek()
        if tok is None:
            raise A2lError(f"end of file: {what} expected")
        self.i += 1
        return tok

    def values(self, types: list, where: str) -> list:
        out = []
        for typ in types:
            if typ == "pairs":
                count = out[-1]
                for _k in range(count):
                    out.append((_value(self.take(f"{where}: a value"), "float", where),
                                _value(self.take(f"{where}: a text"), "string", where)))
            elif typ[-1] in "*+":
                base, got = typ[:-1], 0
                while self.peek() is not None and self.peek().kind == "word" and \
                        _is(self.peek(), base):
                    out.append(_value(self.take(where), base, where))
                    got += 1
                if typ[-1] == "+" and not got:
                    tok = self.peek()
                    raise A2lError(f"line {tok.line if tok else '?'}: {where}: at least one {base} "
                                   "expected")
            else:
                out.append(_value(self.take(f"{where}: {typ}"), typ, where))
        return out

    def block(self, begin: Token) -> Block:
        kind_tok = self.take("a block name after /begin")
        kind = kind_tok.text
        if kind not in BLOCKS:
            raise A2lError(f"line {kind_tok.line}: /begin {kind}: a block this reader does not know")
        params, allowed, keywords = BLOCKS[kind]
        blk = Block(kind, self.values(params, f"/begin {kind}"), begin.line)
        where = f"{kind} {blk.name}".strip()
        opened = f"line {begin.line}: /begin {where} has no /end {kind}"
        while True:
            tok = self.peek()
            if tok is None:
                raise A2lError(f"{opened} (end of file)")
            if tok.kind == "end":
                self.i += 1
                end = self.take(f"the block name after /end (closing {kind})")
                if end.text != kind:
                    raise A2lError(f"{opened}: /end {end.text} at line {end.line} closes it")
                return blk
            if tok.kind == "begin":
                self.i += 1
                nxt = self.peek()
                if nxt is not None and nxt.text not in allowed:
                    raise A2lError(f"{opened} before /begin {nxt.text} at line {tok.line}, which "
                                   f"a {kind} cannot contain")
                blk.children.append(self.block(tok))
                continue
            if tok.kind == "string" or tok.text not in keywords:
                raise A2lError(f"line {tok.line}: {where}: unexpected {tok.text!r} (not a keyword "
                               f"of {kind})")
            self.i += 1
            blk.keywords.append((tok.text, self.values(keywords[tok.text], f"{where} {tok.text}"),
                                 tok.line))


@dataclass
class A2l:
    version: tuple
    project: Block

    @property
    def module(self) -> Block:
        return self.project.blocks("MODULE")[0]

    def of(self, kind: str) -> dict:
        """name -> block of the module's blocks of a kind (the first of a name)."""
        out = {}
        for b in self.module.blocks(kind):
            out.setdefault(b.name, b)
        return out

    def conversion(self, name: str) -> "Conversion":
        m = self.of("COMPU_METHOD")[name]
        vt = None
        if m.kw("COMPU_TAB_REF") is not None:
            vt = self.of("COMPU_VTAB").get(m.kw("COMPU_TAB_REF")[0])
        return Conversion(m, vt)


def parse(text: str) -> A2l:
    p = _Parser(tokenize(text))
    version = None
    project = None
    while p.peek() is not None:
        tok = p.take("ASAP2_VERSION or PROJECT")
        if tok.kind == "word" and tok.text == "ASAP2_VERSION":
            if version is not None:
                raise A2lError(f"line {tok.line}: a second ASAP2_VERSION")
            version = tuple(p.values(["int", "int"], "ASAP2_VERSION"))
        elif tok.kind == "word" and tok.text == "A2ML_VERSION":
            p.values(["int", "int"], "A2ML_VERSION")
        elif tok.kind == "begin" and p.peek() is not None and p.peek().text == "PROJECT":
            if project is not None:
                raise A2lError(f"line {tok.line}: a second PROJECT")
            project = p.block(tok)
        elif tok.kind == "end":
            nxt = p.peek()
            raise A2lError(f"line {tok.line}: /end {nxt.text if nxt else ''} without its /begin")
        else:
            raise A2lError(f"line {tok.line}: {tok.text!r} outside PROJECT")
    if version is None:
        raise A2lError("no ASAP2_VERSION")
    if project is None:
        raise A2lError("no PROJECT")
    if not project.blocks("MODULE"):
        raise A2lError("PROJECT without MODULE")
    return A2l(version, project)


@dataclass
class Conversion:
    method: Block
    vtab: Block | None

    @property
    def kind(self) -> str:
        return self.method.params[2]

    @property
    def unit(self) -> str:
        return self.method.params[4]

    @property
    def factor(self) -> float:
        """The physical value of one raw step (LINEAR; 1 for IDENTICAL)."""
        if self.kind == "LINEAR":
            return self.method.kw("COEFFS_LINEAR")[0]
        if self.kind == "IDENTICAL":
            return 1.0
        if self.kind == "RAT_FUNC":
            a, b, c, d, e, f = self.method.kw("COEFFS")
            if a == 0 and d == 0 and e == 0 and b != 0:
                return f / b
        raise ValueError(f"{self.method.name}: no constant factor")

    def phys(self, raw: int) -> float:
        if self.kind == "IDENTICAL":
            return float(raw)
        if self.kind == "LINEAR":
            a, b = self.method.kw("COEFFS_LINEAR")
            return a * raw + b
        if self.kind == "RAT_FUNC":
            # raw = (a x^2 + b x + c) / (d x^2 + e x + f), solved for x when linear (a = d = e = 0)
            a, b, c, d, e, f = self.method.kw("COEFFS")
            if a == 0 and d == 0 and e == 0 and b != 0:
                return (raw * f - c) / b
            raise ValueError(f"{self.method.name}: a RAT_FUNC this reader does not invert")
        if self.kind == "TAB_VERB":
            return float(raw)
        raise ValueError(f"{self.method.name}: conversion {self.kind} not read")

    def text(self, raw: int) -> str | None:
        """The verbal value of a TAB_VERB conversion."""
        if self.vtab is None:
            return None
        for v, t in self.vtab.params[4:]:
            if v == raw:
                return t
        return self.vtab.kw("DEFAULT_VALUE")[0] if self.vtab.kw("DEFAULT_VALUE") else None


def check(doc: A2l) -> list[str]:
    """The structural rules; a list of findings, empty when the description holds them."""
    err = []
    if doc.version != (1, 71):
        err.append(f"ASAP2_VERSION {doc.version[0]} {doc.version[1]}, not 1 71")
    mod = doc.module
    # names unique: measurement and characteristic objects share one name space
    objects: dict[str, int] = {}
    for kind in ("CHARACTERISTIC", "MEASUREMENT"):
        for b in mod.blocks(kind):
            if b.name in objects:
                err.append(f"{kind} {b.name} (line {b.line}): the name is taken (line "
                           f"{objects[b.name]})")
            objects.setdefault(b.name, b.line)
    for kind in ("COMPU_METHOD", "COMPU_VTAB", "RECORD_LAYOUT", "GROUP"):
        seen: dict[str, int] = {}
        for b in mod.blocks(kind):
            if b.name in seen:
                err.append(f"{kind} {b.name} (line {b.line}): defined twice (line {seen[b.name]})")
            seen.setdefault(b.name, b.line)
    segs: dict[str, int] = {}
    for mp in mod.blocks("MOD_PAR"):
        for s in mp.blocks("MEMORY_SEGMENT"):
            if s.name in segs:
                err.append(f"MEMORY_SEGMENT {s.name} (line {s.line}): defined twice")
            segs.setdefault(s.name, s.line)
    if len(mod.blocks("MOD_COMMON")) != 1 or mod.blocks("MOD_COMMON")[0].kw("BYTE_ORDER") is None:
        err.append("MODULE: one MOD_COMMON with BYTE_ORDER expected")
    methods, vtabs, layouts = doc.of("COMPU_METHOD"), doc.of("COMPU_VTAB"), doc.of("RECORD_LAYOUT")
    groups = doc.of("GROUP")
    for m in methods.values():
        kind = m.params[2]
        need = {"LINEAR": "COEFFS_LINEAR", "RAT_FUNC": "COEFFS", "TAB_VERB": "COMPU_TAB_REF"}.get(kind)
        if need and m.kw(need) is None:
            err.append(f"COMPU_METHOD {m.name} (line {m.line}): {kind} without {need}")
        ref = m.kw("COMPU_TAB_REF")
        if ref is not None and ref[0] not in vtabs:
            err.append(f"COMPU_METHOD {m.name} (line {m.line}): COMPU_TAB_REF {ref[0]}: no such "
                       "COMPU_VTAB")
        if kind == "LINEAR" and m.kw("COEFFS_LINEAR") is not None and m.kw("COEFFS_LINEAR")[0] == 0:
            err.append(f"COMPU_METHOD {m.name} (line {m.line}): LINEAR with factor 0")
        if not re.fullmatch(r"%[0-9]+\.[0-9]+", m.params[3]):
            err.append(f"COMPU_METHOD {m.name} (line {m.line}): format {m.params[3]!r} is not "
                       "%length.layout")
    for v in vtabs.values():
        pairs = v.params[4:]
        if len(pairs) != v.params[3]:
            err.append(f"COMPU_VTAB {v.name} (line {v.line}): {v.params[3]} pairs announced, "
                       f"{len(pairs)} given")
        if len({p[0] for p in pairs}) != len(pairs):
            err.append(f"COMPU_VTAB {v.name} (line {v.line}): a value listed twice")
    for r in layouts.values():
        if r.kw("FNC_VALUES") is None:
            err.append(f"RECORD_LAYOUT {r.name} (line {r.line}): no FNC_VALUES")
    for c in mod.blocks("CHARACTERISTIC"):
        _name, _long, kind, _addr, deposit, _md, conv, lo, hi = c.params
        if deposit not in layouts:
            err.append(f"CHARACTERISTIC {c.name} (line {c.line}): RECORD_LAYOUT {deposit}: no such "
                       "RECORD_LAYOUT")
        if conv != "NO_COMPU_METHOD" and conv not in methods:
            err.append(f"CHARACTERISTIC {c.name} (line {c.line}): COMPU_METHOD {conv}: no such "
                       "COMPU_METHOD")
        err += _limits(c, lo, hi)
        dims = c.kw("MATRIX_DIM") or c.kw("NUMBER")
        if kind == "VAL_BLK" and not dims:
            err.append(f"CHARACTERISTIC {c.name} (line {c.line}): VAL_BLK without MATRIX_DIM")
        if kind == "VALUE" and c.kw("MATRIX_DIM") is not None:
            err.append(f"CHARACTERISTIC {c.name} (line {c.line}): VALUE with MATRIX_DIM")
    for m in mod.blocks("MEASUREMENT"):
        conv = m.params[3]
        if conv != "NO_COMPU_METHOD" and conv not in methods:
            err.append(f"MEASUREMENT {m.name} (line {m.line}): COMPU_METHOD {conv}: no such "
                       "COMPU_METHOD")
        if m.kw("ECU_ADDRESS") is None:
            err.append(f"MEASUREMENT {m.name} (line {m.line}): no ECU_ADDRESS")
        err += _limits(m, m.params[6], m.params[7])
    chars = {c.name for c in mod.blocks("CHARACTERISTIC")}
    meas = {m.name for m in mod.blocks("MEASUREMENT")}
    for g in groups.values():
        for kind, names in (("REF_CHARACTERISTIC", chars), ("REF_MEASUREMENT", meas),
                            ("SUB_GROUP", set(groups))):
            for sub in g.blocks(kind):
                for ident in sub.params:
                    if ident not in names:
                        err.append(f"GROUP {g.name} (line {g.line}): {kind} {ident}: not defined")
    return err


def _limits(b: Block, lo: float, hi: float) -> list[str]:
    out = []
    if lo > hi:
        out.append(f"{b.kind} {b.name} (line {b.line}): lower limit {lo} above upper limit {hi}")
    ext = b.kw("EXTENDED_LIMITS")
    if ext is not None and not ext[0] <= lo <= hi <= ext[1]:
        out.append(f"{b.kind} {b.name} (line {b.line}): limits {lo} .. {hi} outside "
                   f"EXTENDED_LIMITS {ext[0]} .. {ext[1]}")
    return out
