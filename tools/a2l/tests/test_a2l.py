"""Tests of tools/a2l/qfoc_a2l.py, the calibration description (run: make a2l-check, or
QFOC_A2L_ELF=build/s32k144/qfoc_compressor.elf python3 -m pytest tools/a2l/tests).

The A2L is read back with the tests' own reader (a2l_reader.py) and checked against
references that share no code with the tool: the ELF's symbols, sections and DWARF walked
here (elf_walk.py), the motor files read with tomllib, the ranges and codes written in the
library's headers, and hand computations of the derived gains.  Besides the firmware image
of make firmware (the drive included), every table of tables/manifest.txt is compiled into
an image of its own (arm-none-eabi-gcc -g) and described, so that every committed table,
its shifts and its flux base are read back.
"""
import os
import re
import shutil
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest

HERE = Path(__file__).resolve().parent
REPO = HERE.parents[2]
sys.path.insert(0, str(HERE))
sys.path.insert(0, str(HERE.parent))
sys.path.insert(0, str(REPO / "tools" / "tune"))

import a2l_reader as ar  # noqa: E402
import elf_walk as ew  # noqa: E402
import qfoc_a2l as qa  # noqa: E402
import qfoc_tune as qt  # noqa: E402

ELF = Path(os.environ.get("QFOC_A2L_ELF", REPO / "build" / "s32k144" / "qfoc_compressor.elf"))
ARM_CC = "arm-none-eabi-gcc"
ARM_FLAGS = ["-mcpu=cortex-m4", "-mthumb", "-mfloat-abi=hard", "-mfpu=fpv4-sp-d16", "-O2", "-g"]


def manifest():
    out = {}
    for line in (REPO / "tables" / "manifest.txt").read_text().splitlines():
        w = line.split()
        if w and not w[0].startswith("#"):
            out[w[0]] = (w[1], w[2:])
    return out


def run_tool(capsys, *args):
    """The tool in-process: (exit code, stdout, stderr)."""
    rc = qa.main([str(a) for a in args])
    cap = capsys.readouterr()
    return rc, cap.out, cap.err


def header_define(path: str, name: str) -> int:
    m = re.search(r"#define\s+" + name + r"\s+\(\((?:u?int\d+_t|qfoc_q15_t)\)(-?(?:0x[0-9A-Fa-f]+|\d+))u?\)",
                  (REPO / path).read_text())
    assert m, f"{name} not in {path}"
    return int(m.group(1), 0)


@pytest.fixture(scope="module")
def firmware(tmp_path_factory):
    """(ELF, A2L path, A2L text, parsed A2L) of the firmware image."""
    assert ELF.is_file(), f"{ELF}: no firmware image (make a2l-check builds it)"
    out = tmp_path_factory.mktemp("fw") / "fw.a2l"
    assert qa.main([str(ELF), "-o", str(out)]) == 0
    text = out.read_text()
    return ELF, out, text, ar.parse(text)


@pytest.fixture(scope="module")
def fw_table(firmware):
    """(symbol, table name) of the table in the firmware image (its one qfoc_params_ symbol)."""
    syms = [n for n in ew.Elf(firmware[0]).symbols if n.startswith("qfoc_params_")]
    assert len(syms) == 1, syms
    return syms[0], syms[0][len("qfoc_params_"):]


@pytest.fixture(scope="module")
def table_images(tmp_path_factory):
    """name -> (ELF, parsed A2L) of every table of the manifest, each linked into an image of
    its own and described without a drive."""
    d = tmp_path_factory.mktemp("tables")
    out = {}
    for name in manifest():
        elf = d / f"{name}.elf"
        subprocess.run([ARM_CC, *ARM_FLAGS, f"-I{REPO / 'include'}", f"-I{REPO / 'tables'}",
                        "-nostdlib", "-nostartfiles", "-Wl,-e,0", str(REPO / "tables" / f"{name}_params.c"),
                        "-o", str(elf)], check=True, capture_output=True)
        a2l = d / f"{name}.a2l"
        assert qa.main([str(elf), "--no-drive", "-o", str(a2l)]) == 0
        out[name] = (elf, ar.parse(a2l.read_text()))
    return out


def motor_value(motor: str, overrides: list, key: str, cfg: dict):
    """The value of section.key as the motor file (with the manifest's overrides) writes it;
    the tool's default when the file does not set it."""
    raw = tomllib.loads((REPO / motor).read_text())
    for o in overrides:
        k, v = o.split("=", 1)
        sec, name = k.split(".")
        try:
            val = tomllib.loads(f"v = {v}")["v"]
        except tomllib.TOMLDecodeError:
            val = v.strip()   # a bare word, as the tool's --set takes it (sensing.mode=shunt)
        raw.setdefault(sec, {})[name] = val
    section, name = key.split(".")
    if name in raw.get(section, {}):
        return raw[section][name]
    return cfg[section][name]


def conversion_findings(doc: ar.A2l, elf: ew.Elf, table: str) -> list[str]:
    """Every CHARACTERISTIC's raw value read from the ELF at its A2L address, converted by its
    A2L COMPU_METHOD, against the tuning tool's input: the motor-file value of the field's
    key (the tool's default when the file does not set it), else the design value; within
    the field's rounding (half an LSB of its Q format, one LSB for a value rounded down)."""
    motor, overrides = manifest()[table]
    cfg = qt.load_config(REPO / motor, overrides)
    b = qt.make_bases(cfg)
    items = qt.build_table(cfg, qt.design_loops(cfg, b))
    fields = dict(qt.flatten(items))
    layouts = doc.of("RECORD_LAYOUT")
    sym = qa.TABLE_PREFIX + table
    out = []
    for c in doc.module.blocks("CHARACTERISTIC"):
        path = c.name[len(sym) + 1:]
        if path == "crc":
            continue
        f = fields[path]
        size, signed = ar.DATATYPES[layouts[c.params[4]].kw("FNC_VALUES")[1]]
        raw = elf.read_int(c.params[3], size, signed)
        conv = doc.conversion(c.params[6])
        phys = conv.phys(raw)
        if f.phys.key is not None:
            expected = motor_value(motor, overrides, f.phys.key, cfg)
            unit = qt.SCHEMA_BY_NAME[f.phys.key].unit or "-"
            if (conv.unit or "-") != unit:
                out.append(f"{c.name}: unit {conv.unit!r} in the A2L, {unit!r} in the motor file "
                           f"({f.phys.key})")
        else:
            expected = f.phys.real
        tol = f.phys.lsb * abs(conv.factor) * (1 + 1e-9) + 1e-12 * abs(expected)
        if abs(phys - expected) > tol:
            out.append(f"{c.name}: {phys} from the A2L (raw {raw}), {expected} expected "
                       f"({f.phys.key or 'design value'}), difference {abs(phys - expected)} > {tol}")
        if not c.params[7] - 1e-9 * abs(phys) <= phys <= c.params[8] + 1e-9 * abs(phys):
            out.append(f"{c.name}: {phys} outside its limits {c.params[7]} .. {c.params[8]}")
    return out


# REQ-A2L-001: ASAP2 1.71 with PROJECT, MODULE, MOD_PAR and MOD_COMMON (BYTE_ORDER MSB_LAST);
# every /begin closed by its /end, names unique, identifiers valid, every COMPU_METHOD,
# COMPU_VTAB, RECORD_LAYOUT and GROUP member referenced defined; every table field one
# CHARACTERISTIC, the table's and the drive's memory in MEMORY_SEGMENTs.
# Methods: 1a the ASAP2 1.71 structure of REQ-A2L-001 checked block by block (every /begin
# closed, names unique, references defined, one CHARACTERISTIC per field, the memory segments);
# 1b the firmware's table and every committed table image
def test_a2l_structure(firmware, fw_table, table_images):
    elf_path, _out, text, doc = firmware
    sym, table = fw_table
    assert text.startswith("/*") and "\nASAP2_VERSION 1 71\n" in text
    assert ar.check(doc) == []
    assert doc.version == (1, 71)
    assert doc.project.name == "qfoc" and len(doc.project.blocks("MODULE")) == 1
    assert doc.module.blocks("MOD_COMMON")[0].kw("BYTE_ORDER") == ["MSB_LAST"]
    elf = ew.Elf(elf_path)
    chars = {c.name for c in doc.module.blocks("CHARACTERISTIC")}
    assert chars == {f"{sym}.{p}" for p in ew.scalars(elf, sym)}
    assert len(chars) == 117
    assert all(c.params[2] == "VALUE" for c in doc.module.blocks("CHARACTERISTIC"))
    segs = {s.name: s for s in doc.module.blocks("MOD_PAR")[0].blocks("MEMORY_SEGMENT")}
    addr, size = elf.symbols[sym]
    assert segs["table_FLASH"].params[2:7] == ["DATA", "FLASH", "INTERN", addr, size]
    assert segs["drive_RAM"].params[2:4] == ["VARIABLES", "RAM"]
    consts = dict(s for s in (k[1] for k in doc.module.blocks("MOD_PAR")[0].keywords
                              if k[0] == "SYSTEM_CONSTANT"))
    crc = elf.read_int(addr + size - 4, 4, False)
    assert consts["QFOC_TABLE_CRC"] == f"0x{crc:08X}"
    assert consts["QFOC_MOTOR_FILE"] == manifest()[table][0]
    assert consts["QFOC_TABLE"] == table
    for name, (_elf, tdoc) in table_images.items():
        assert ar.check(tdoc) == [], name
        assert len(tdoc.module.blocks("CHARACTERISTIC")) == 117, name
        assert tdoc.module.blocks("MEASUREMENT") == [], name


# REQ-A2L-002: every CHARACTERISTIC and MEASUREMENT at the address, of the size, signedness
# and dimensions the ELF gives: the variable's symbol or DWARF location plus the DWARF member
# offset, computed here; SYMBOL_LINK consistent; inside the MEMORY_SEGMENT of its section.
# Methods: 1b every CHARACTERISTIC and MEASUREMENT, of every table image; 1n the address, size,
# signedness and dimensions computed independently from the ELF's symbols and DWARF in the test
def test_a2l_addresses_against_elf(firmware, fw_table, table_images):
    elf_path, _out, _text, doc = firmware
    sym, _table = fw_table
    elf = ew.Elf(elf_path)
    assert ew.check_against_elf(doc, elf) == []
    # the table by its symbol: address = symbol value + DWARF offset of the member
    base = elf.symbols[sym][0]
    kp = doc.of("CHARACTERISTIC")[f"{sym}.pi_id.kp"]
    assert kp.params[3] == base + elf.locate(f"{sym}.pi_id.kp").offset
    crc = doc.of("CHARACTERISTIC")[f"{sym}.crc"]
    assert crc.params[3] == base + elf.symbols[sym][1] - 4
    # the drive, a static object of main(): its DWARF name, its symbol 'motor.<n>'
    state = doc.of("MEASUREMENT")["motor.s.status.state"]
    place = elf.locate("motor.s.status.state")
    assert state.kw("ECU_ADDRESS")[0] == place.address
    sym = state.kw("SYMBOL_LINK")[0]
    assert sym.startswith("motor.") and elf.symbols[sym][0] == place.base
    for name, (telf, tdoc) in table_images.items():
        assert ew.check_against_elf(tdoc, ew.Elf(telf)) == [], name


# REQ-A2L-003: the physical value of every field, read from the image at its A2L address and
# converted by its A2L COMPU_METHOD, is the motor file's value (or the design value the tool
# derives) within the field's rounding, in the motor file's unit; for every committed table.
# Methods: 1b every field of every committed table; 1a the physical value read from the image
# and converted by the A2L, against the motor file's value within the field's rounding
def test_a2l_conversions_match_motor_file(firmware, fw_table, table_images):
    elf_path, _out, _text, doc = firmware
    assert conversion_findings(doc, ew.Elf(elf_path), fw_table[1]) == []
    for name, (telf, tdoc) in table_images.items():
        assert conversion_findings(tdoc, ew.Elf(telf), name) == [], name


# REQ-A2L-003: the derived fields' conversions against hand computations from the motor file
# (current loops: k_cp = L / (2 T_sigma), k_ci = R / (2 T_sigma), T_sigma = 1.5 / f_pwm +
# t_filter; PLL: 2 zeta w_n and w_n^2; low-pass coefficients: their corner frequency; the flux
# observer's gain: the sample time 1 / f_pwm; the dead-time compensation: the dead time).
# Methods: 1a the derived fields' conversions against hand computations from the motor file
# (k_cp = L / (2 T_sigma), 2 zeta w_n, w_n^2, corner frequencies, 1 / f_pwm, the dead time), the
# reference motor's k_cp 6.933 ohm written out
def test_a2l_derived_gains_by_hand(firmware, fw_table):
    elf_path, _out, _text, doc = firmware
    sym, table = fw_table
    motor, overrides = manifest()[table]
    cfg = qt.load_config(REPO / motor, overrides)

    def v(key):
        return motor_value(motor, overrides, key, cfg)

    elf = ew.Elf(elf_path)
    chars = doc.of("CHARACTERISTIC")

    def phys(path):
        c = chars[f"{sym}.{path}"]
        size, signed = ar.DATATYPES[doc.of("RECORD_LAYOUT")[c.params[4]].kw("FNC_VALUES")[1]]
        conv = doc.conversion(c.params[6])
        return conv.phys(elf.read_int(c.params[3], size, signed)), conv.factor, conv.unit

    pi = 3.141592653589793
    f_pwm = v("inverter.f_pwm_hz")
    t_sigma = 1.5 / f_pwm + v("design.t_filter_current_s")
    w_n = 2 * pi * v("design.pll_wn_hz")
    checks = (("pi_id.kp", v("motor.ld_h") / (2 * t_sigma), "ohm"),
              ("pi_iq.kp", v("motor.lq_h") / (2 * t_sigma), "ohm"),
              ("pi_id.ki", v("motor.rs_ohm") / (2 * t_sigma), "ohm/s"),
              ("pll.pi.kp", 2 * v("design.pll_zeta") * w_n, "1/s"),
              ("pll.pi.ki", w_n ** 2, "1/s^2"),
              ("pll.speed_alpha", v("design.speed_fc_hz"), "Hz"),
              ("alpha_vdc", v("design.vdc_fc_hz"), "Hz"),
              ("flux.gain", 1 / f_pwm, "s"),
              ("svpwm.dt_comp", v("inverter.dead_time_s"), "s"),
              ("pll.pi.out_max", 32767 / 32768 * v("scaling.f_base_hz") * 60 / v("motor.pole_pairs"),
               "rpm"))
    for path, want, unit in checks:
        value, factor, u = phys(path)
        assert u == unit, path
        assert abs(value - want) <= 0.5 * factor * (1 + 1e-9), (path, value, want, factor)
    # the reference motor's numbers, written out (L_d 2.6 mH, 8 kHz: k_cp = 6.933 ohm)
    if table == "reference":
        assert phys("pi_id.kp")[0] == pytest.approx(6.9333, abs=0.0002)
        assert phys("flux.gain")[0] == pytest.approx(125e-6, rel=1e-4)


# REQ-A2L-003: LOWER_LIMIT and UPPER_LIMIT are the library's range check (the bounds written in
# params.h and drive_cfg.h, and the cross-field bounds at the other field's value), physical.
# Methods: 1c LOWER_LIMIT and UPPER_LIMIT of each field against the bounds of params.h and
# drive_cfg.h, the cross-field bounds at the other field's value (i_trip from i_max, vdc_ov from
# vdc_uv + 1), the read-only identity and bases
def test_a2l_limits_are_the_range_check(firmware, fw_table):
    elf_path, _out, _text, doc = firmware
    sym, _table = fw_table
    elf = ew.Elf(elf_path)
    chars = doc.of("CHARACTERISTIC")
    p, d = "include/qfoc/params.h", "include/qfoc/drive_cfg.h"

    def raw_of(path):
        c = chars[f"{sym}.{path}"]
        size, signed = ar.DATATYPES[doc.of("RECORD_LAYOUT")[c.params[4]].kw("FNC_VALUES")[1]]
        return elf.read_int(c.params[3], size, signed)

    expect = {
        "f_pwm_hz": (header_define(p, "QFOC_PARAMS_F_PWM_MIN"), header_define(p, "QFOC_PARAMS_F_PWM_MAX")),
        "drive.pole_pairs": (1, header_define(d, "QFOC_DRIVE_POLE_PAIRS_MAX")),
        "drive.offset_shift": (header_define(d, "QFOC_DRIVE_OFFSET_SHIFT_MIN"),
                               header_define(d, "QFOC_DRIVE_OFFSET_SHIFT_MAX")),
        "drive.offset_window": (0, header_define(d, "QFOC_DRIVE_OFFSET_WINDOW_MAX")),
        "drive.ho_angle": (1, header_define(d, "QFOC_DRIVE_HO_ANGLE_MAX")),
        "drive.t_ipm_max": (header_define(d, "QFOC_DRIVE_TEMP_MIN"), header_define(d, "QFOC_DRIVE_TEMP_MAX")),
        "drive.vdc_ms": (1, header_define(d, "QFOC_DRIVE_DEBOUNCE_MAX")),
        "drive.precharge_ms": (1, header_define(d, "QFOC_DRIVE_MS_MAX")),
        "drive.lin_id_cmd": (0, header_define(d, "QFOC_DRIVE_LIN_ID_MAX")),
        "drive.can_id_a": (0, header_define(d, "QFOC_DRIVE_CAN_ID_MAX")),
        "drive.psi_shift": (0, header_define(d, "QFOC_DRIVE_PSI_SHIFT_MAX")),
        "drive.ho_retries": (0, header_define(d, "QFOC_DRIVE_HO_RETRIES_MAX")),
        "i_max": (1, 32767),
        "i_trip": (raw_of("i_max"), 32767),                  # i_max .. 32767
        "vdc_ov": (raw_of("vdc_uv") + 1, header_define(p, "QFOC_PARAMS_VDC_READ_MAX") - 1),
        "drive.i_align": (1, raw_of("i_max")),               # <= i_max in the table
        "pi_id.out_min": (-32767, raw_of("pi_id.out_max")),
        "magic": (0x434F4651, 0x434F4651),
    }
    for path, (lo, hi) in expect.items():
        c = chars[f"{sym}.{path}"]
        f = doc.conversion(c.params[6]).factor
        assert (c.params[7], c.params[8]) == pytest.approx((lo * f, hi * f), rel=1e-12), path
    # the identity, the bases and the shifts may not be calibrated alone
    for path in ("magic", "version", "crc", "v_base_mv", "pi_speed.kp_shift", "drive.psi_shift"):
        assert chars[f"{sym}.{path}"].kw("READ_ONLY") == [], path
    assert chars[f"{sym}.i_max"].kw("READ_ONLY") is None


# REQ-A2L-004: the drive's status (qfoc_status_t, every member), state and sub-state (the
# codes of sm.h as COMPU_VTABs), the fault bits of fault.h (BIT_MASK of the latched word) and
# the Q15 estimates with the bases of the image's own table.
# Methods: 1b every member of the drive's status, every state and sub-state code, each of the 11
# fault bits; 1a the conversions of the status units and of the estimates with the image's own
# bases
def test_a2l_measurements(firmware, fw_table):
    elf_path, _out, _text, doc = firmware
    sym, _table = fw_table
    elf = ew.Elf(elf_path)
    meas = doc.of("MEASUREMENT")
    for member in ew.scalars(elf, "motor"):
        if member.startswith("s.status."):
            assert f"motor.{member}" in meas, member
    sm_h = (REPO / "include/qfoc/sm.h").read_text()
    states = {int(v): n for n, v in re.findall(r"#define QFOC_STATE_(\w+)\s+\(\(uint8_t\)(\d+)u\)", sm_h)}
    subs = {int(v): n for n, v in re.findall(r"#define QFOC_SUB_(\w+)\s+\(\(uint8_t\)(\d+)u\)", sm_h)}
    assert states and subs
    for name, codes in (("motor.s.status.state", states), ("motor.s.sm.state", states),
                        ("motor.s.status.substate", subs), ("motor.s.sm.sub", subs)):
        conv = doc.conversion(meas[name].params[3])
        assert conv.kind == "TAB_VERB", name
        assert {v: conv.text(v) for v in codes} == codes, name
        assert (meas[name].params[6], meas[name].params[7]) == (min(codes), max(codes))
    faults = re.findall(r"#define QFOC_FAULT_(\w+)\s+\(\(uint16_t\)0x([0-9A-Fa-f]+)u\)",
                        (REPO / "include/qfoc/fault.h").read_text())
    bits = {n: int(v, 16) for n, v in faults if n != "ALL"}
    assert len(bits) == 11
    word = elf.locate("motor.s.sm.faults").address
    for n, mask in bits.items():
        m = meas[f"motor.s.sm.faults.{n}"]
        assert m.kw("BIT_MASK") == [mask] and m.kw("ECU_ADDRESS") == [word], n
    # conversions: the status in its decimal units (link.h), the estimates with the bases of
    # the table in the image (its own fields, read here)
    base = elf.symbols[sym][0]

    def table(path):
        pl = elf.locate(f"{sym}.{path}")
        return elf.read_int(base + pl.offset, pl.size, pl.signed)

    i_base = table("i_base_ma") / 1000.0
    v_base = table("v_base_mv") / 1000.0
    f_base = table("f_base_mhz") / 1000.0
    psi_base = 2 ** table("drive.psi_shift") * v_base / (2 * 3.141592653589793 * f_base)
    rpm = f_base * 60.0 / table("drive.pole_pairs")
    for name, factor, unit in (
            ("motor.s.status.vdc_dv", 0.1, "V"), ("motor.s.status.current_ca", 0.01, "A"),
            ("motor.s.status.temp_dc", 0.1, "degC"), ("motor.s.status.speed_rpm", 1.0, "rpm"),
            ("motor.f.i_dq.d", i_base / 32768, "A"), ("motor.s.iq_ref", i_base / 32768, "A"),
            ("motor.f.vdc", v_base / 32768, "V"), ("motor.f.speed_f", rpm / 32768, "rpm"),
            ("motor.s.speed_ref", rpm / 32768, "rpm"), ("motor.f.psi_mag", psi_base / 32768, "Wb"),
            ("motor.f.theta_est", 360 / 65536, "deg")):
        conv = doc.conversion(meas[name].params[3])
        assert conv.factor == pytest.approx(factor, rel=1e-12) and conv.unit == unit, name
    cmp_ = meas["motor.f.out.cmp"]
    assert cmp_.kw("MATRIX_DIM") == [3] and cmp_.params[2] == "UWORD"


# REQ-A2L-001: the same image gives the same file, byte for byte, wherever it lies; the file
# make writes beside the image is the tool's; no absolute path and no time in it.
# Methods: 1a the same image gives the same file byte for byte from another directory, the file
# beside the image is the tool's, no absolute path and no time in it
def test_a2l_reproducible(firmware, tmp_path, capsys):
    elf_path, _out, text, _doc = firmware
    copy = tmp_path / "elsewhere" / elf_path.name
    copy.parent.mkdir()
    shutil.copy(elf_path, copy)
    rc, _o, err = run_tool(capsys, copy, "-o", tmp_path / "again.a2l")
    assert rc == 0, err
    assert (tmp_path / "again.a2l").read_text() == text
    beside = elf_path.with_suffix(".a2l")
    assert beside.is_file(), f"{beside}: make firmware / make a2l writes the A2L beside the image"
    assert beside.read_text() == text
    assert str(REPO) not in text and str(tmp_path) not in text


# REQ-A2L-002: the checker catches a corrupted description: a missing /end, a wrong address, a
# conversion that is not the field's, a reference to a COMPU_METHOD that does not exist, a
# name used twice, an invalid identifier, a data type that is not the member's.
# Methods: 1b seven kinds of corruption, one per parameter; 1d a missing /end, a wrong address,
# a conversion not the field's, an undefined COMPU_METHOD, a duplicate name, an invalid
# identifier, a wrong data type; 1l each corruption injected into the generated description
@pytest.mark.parametrize("what", ["missing_end", "address", "factor", "method_ref", "duplicate",
                                  "identifier", "datatype"])
def test_a2l_checker_catches_corruption(firmware, fw_table, what):
    elf_path, _out, text, doc = firmware
    sym, table = fw_table
    elf = ew.Elf(elf_path)
    kp = doc.of("CHARACTERISTIC")[f"{sym}.pi_id.kp"]
    head = f"/begin CHARACTERISTIC {sym}.pi_id.kp\n"
    assert text.count(head) == 1
    start = text.index(head)
    block = text[start:text.index("/end CHARACTERISTIC", start) + len("/end CHARACTERISTIC")]
    if what == "missing_end":
        bad = text.replace(block, block[:-len("/end CHARACTERISTIC")])
        with pytest.raises(ar.A2lError, match=rf"line {kp.line}: /begin CHARACTERISTIC "
                                              rf"{sym}\.pi_id\.kp has no /end "
                                              r"CHARACTERISTIC before /begin CHARACTERISTIC"):
            ar.parse(bad)
        # an /end of another block, and the end of the file, are caught the same way
        with pytest.raises(ar.A2lError, match=r"has no /end MODULE: /end PROJECT at line \d+ closes it"):
            ar.parse(text.replace("  /end MODULE\n", ""))
        with pytest.raises(ar.A2lError, match=r"/begin PROJECT qfoc has no /end PROJECT \(end of file\)"):
            ar.parse(text.replace("/end PROJECT\n", ""))
        return
    if what == "address":
        wrong = kp.params[3] + 2
        bad = text.replace(block, block.replace(f"0x{kp.params[3]:08X}", f"0x{wrong:08X}"))
        found = ew.check_against_elf(ar.parse(bad), elf)
        assert found and "pi_id.kp" in found[0] and f"0x{wrong:08X} in the A2L" in found[0]
        return
    if what == "factor":
        conv = doc.of("COMPU_METHOD")[kp.params[6]]
        a = conv.kw("COEFFS_LINEAR")[0]
        mtext = text[text.index(f"/begin COMPU_METHOD {conv.name}\n"):]
        mtext = mtext[:mtext.index("/end COMPU_METHOD")]
        bad = text.replace(mtext, mtext.replace(f"COEFFS_LINEAR {qa.num(a)} 0",
                                                f"COEFFS_LINEAR {qa.num(a * 2)} 0"))
        assert bad != text
        found = conversion_findings(ar.parse(bad), elf, table)
        assert any("pi_id.kp:" in f for f in found), found
        return
    if what == "method_ref":
        bad = text.replace(block, block.replace(f" {kp.params[6]} ", " CM_no_such_method "))
        found = ar.check(ar.parse(bad))
        assert found == [f"CHARACTERISTIC {sym}.pi_id.kp (line {kp.line}): "
                         "COMPU_METHOD CM_no_such_method: no such COMPU_METHOD"]
        return
    if what == "duplicate":
        bad = text.replace(block, block + "\n" + block)
        found = ar.check(ar.parse(bad))
        assert any(f"{sym}.pi_id.kp" in f and "name is taken" in f for f in found)
        return
    if what == "identifier":
        bad = text.replace(head, f"/begin CHARACTERISTIC {sym}.pi-id.kp\n")
        with pytest.raises(ar.A2lError, match=rf"'{sym}\.pi-id\.kp' is not a valid ASAP2 "
                                              r"identifier"):
            ar.parse(bad)
        return
    if what == "datatype":
        bad = text.replace(block, block.replace(" RL_SWORD ", " RL_ULONG "))
        assert bad != text
        found = ew.check_against_elf(ar.parse(bad), elf)
        assert any("pi_id.kp" in f and "ULONG in the A2L, signed 2 bytes" in f for f in found), found
        return
    raise AssertionError(what)


# REQ-A2L-001: an array member is a VAL_BLK with MATRIX_DIM (the table has none; the writer's
# rule is read back on a three-element array).
# Methods: 1a an array member written as a VAL_BLK with MATRIX_DIM, read back on a three-element
# array
def test_a2l_val_blk_for_arrays():
    mod = qa.Module()
    leaf = qa.Leaf("cmp", 0x10, 2, "int", False, (3,))
    conv = mod.linear(1.0, "ticks", "timer ticks")
    qa.characteristic(mod, "tbl.cmp", "compare values", leaf, 0x1000, conv, 1.0, (0, 5000),
                      False, "tbl")
    text = "\n".join(["ASAP2_VERSION 1 71", '/begin PROJECT p ""', '/begin MODULE m ""',
                      '/begin MOD_COMMON "" BYTE_ORDER MSB_LAST /end MOD_COMMON',
                      *mod.characteristics[0],
                      f'/begin COMPU_METHOD {conv} "" LINEAR "%8.0" "ticks" COEFFS_LINEAR 1 0 '
                      "/end COMPU_METHOD",
                      "/begin RECORD_LAYOUT RL_UWORD FNC_VALUES 1 UWORD COLUMN_DIR DIRECT "
                      "/end RECORD_LAYOUT", "/end MODULE", "/end PROJECT"])
    doc = ar.parse(text)
    assert ar.check(doc) == []
    c = doc.of("CHARACTERISTIC")["tbl.cmp"]
    assert c.params[2:5] == ["VAL_BLK", 0x1000, "RL_UWORD"]
    assert c.kw("MATRIX_DIM") == [3] and (c.params[7], c.params[8]) == (0, 5000)


def strip_debug(src: Path, dst: Path) -> None:
    subprocess.run(["arm-none-eabi-objcopy", "--strip-debug", str(src), str(dst)], check=True)


def tampered(src: Path, dst: Path, sym: str) -> None:
    """A copy of the image with the table's pi_id.kp one count higher."""
    elf = ew.Elf(src)
    place = elf.locate(f"{sym}.pi_id.kp")
    sec = elf.section(place.address, 2)
    off = sec["sh_offset"] + place.address - sec["sh_addr"]
    data = bytearray(src.read_bytes())
    value = int.from_bytes(data[off:off + 2], "little", signed=True)
    data[off:off + 2] = (value + 1).to_bytes(2, "little", signed=True)
    dst.write_bytes(bytes(data))


# REQ-A2L-005: bad input is refused with exit code 1 and a message naming what was typed, and
# nothing is written (an existing output file is left as it was).
# Methods: 1b nine kinds of bad input, one per parameter, each with a fresh and an existing
# output file; 1d a missing ELF, a file that is no ELF, no DWARF, unknown or absent tables and
# drives, a drive of the wrong type, conflicting options, another table's values in the image
@pytest.mark.parametrize("case", ["missing_elf", "not_elf", "no_dwarf", "unknown_table",
                                  "table_not_in_image", "unknown_drive", "drive_wrong_type",
                                  "drive_and_no_drive", "other_table_in_image"])
def test_a2l_bad_input(firmware, fw_table, tmp_path, capsys, case):
    elf = firmware[0]
    sym, table = fw_table
    out = tmp_path / "out.a2l"
    kept = tmp_path / "kept.a2l"
    kept.write_text("earlier\n")
    if case == "missing_elf":
        args, msg = [tmp_path / "nosuch.elf"], f"{tmp_path / 'nosuch.elf'}: no such ELF file"
    elif case == "not_elf":
        args, msg = [REPO / "Makefile"], "Makefile: not an ELF file"
    elif case == "no_dwarf":
        strip_debug(elf, tmp_path / "stripped.elf")
        args, msg = [tmp_path / "stripped.elf"], "stripped.elf: the ELF has no DWARF"
    elif case == "unknown_table":
        args, msg = [elf, "--table", "bogus"], "--table bogus: no table 'bogus' in tables/manifest.txt"
    elif case == "table_not_in_image":
        other = "lowflux" if table != "lowflux" else "reference"
        args, msg = [elf, "--table", other], f"--table {other}: no object qfoc_params_{other}"
    elif case == "unknown_drive":
        args, msg = [elf, "--drive", "engine"], "--drive engine: no variable or symbol 'engine'"
    elif case == "drive_wrong_type":
        args, msg = [elf, "--drive", "s_drive"], ("--drive s_drive: 's_drive' in "
                                                  f"{elf} is of type qfoc_drive_t *, not qfoc_drive_t")
    elif case == "drive_and_no_drive":
        args, msg = [elf, "--drive", "motor", "--no-drive"], "--drive motor and --no-drive"
    else:
        tampered(elf, tmp_path / "other.elf", sym)
        args, msg = [tmp_path / "other.elf"], f"{sym}.pi_id.kp = "
    for target in (out, kept):
        rc, stdout, err = run_tool(capsys, *args, "-o", target)
        assert rc == 1
        assert msg in err, err
        assert "refused, nothing written" in err and stdout == ""
    assert not out.exists()
    assert kept.read_text() == "earlier\n"
    assert [p.name for p in tmp_path.iterdir() if p.name.startswith(".")] == []
    if case == "other_table_in_image":
        assert "in the image, but the tuning tool makes" in err and manifest()[table][0] in err
