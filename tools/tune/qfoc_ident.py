#!/usr/bin/env python3
"""qfoc_ident.py -- from an identification record to a motor file and its parameter table.

    python3 tools/tune/qfoc_ident.py RECORD.json RATINGS.toml --motor-out MOTOR.toml
            [--name NAME] [--table-dir DIR] [--out-dir DIR] [--no-plots] [--force]
            [--set SECTION.KEY=VALUE ...]

An identification measures the machine's electrical parameters on the inverter; the
integrator types only the ratings and limits.  This tool joins the two:

RECORD.json, format "qfoc-ident/1", the measured values in SI units:

    {"format": "qfoc-ident/1",
     "source": "what measured it: drive, table, date (free text, copied into the motor file)",
     "conditions": {"vdc_v": 320.0, "winding_temp_degc": 25.0},   (optional, copied)
     "results": {
        "rs_ohm":   {"value": 0.351,   "repeat_pct": 0.3, "residual_pct": 0.5},
        "ld_h":     {"value": 2.61e-3, "repeat_pct": 0.8, "residual_pct": 1.1},
        "lq_h":     {"value": 4.18e-3, "repeat_pct": 0.9, "residual_pct": 1.0},
        "psi_f_wb": {"value": 0.0652,  "repeat_pct": 0.4, "residual_pct": 0.6}}}

    Each result carries its quality: repeat_pct, the difference of two repeats of the
    measurement in % of the value, and residual_pct, the residual of the measurement's model
    fit in % of the value.

RATINGS.toml is a motor file (docs/motor-file.md) without the four measured keys of [motor]
(rs_ohm, ld_h, lq_h, psi_f_wb): the ratings, the inverter, the sensing and any limits.

The tool checks the record, writes MOTOR.toml (the ratings file with the measured values
added to [motor], each marked "identified" with its quality), and runs the tuning tool
(qfoc_tune.py) on it: the same checks as a typed motor file (ranges, plausibility with the
unit-slip hint, every rule, the fixed-point bounds, the loop margins), and the table
tables/<name>_params.c/.h.  On any refusal it writes neither the motor file nor the table
(an existing MOTOR.toml, replaced only with --force, is left as it was).

Acceptance of a measured value (besides the motor-file checks): finite and positive, and
each quality figure at most half the identification's accuracy target (R_s 5 %, L_d and L_q
10 %, psi_f 5 %: QUALITY_LIMIT_PCT), so that the spread leaves the other half of the target
to the systematic errors.

Exit codes: 0 written; 1 refused (a value or quality out of range, a measured key typed in
the ratings file, an existing output without --force, or the tuning tool's refusal); 2
malformed input (the record is not JSON of this format, a field is missing or not a number,
a text copied into the motor file holds a line break, the ratings file is unreadable).

Requirement: REQ-TUNE-008 (specs/requirements/tune.md).  tools/tune/ident_flow.py runs this
tool on the record of each table of a manifest (REQ-TUNE-009).
"""
import argparse
import json
import math
import re
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

import qfoc_tune as qt  # noqa: E402

FORMAT = "qfoc-ident/1"
# The measured [motor] keys and the largest quality figure accepted for each, in % of the
# value: half the identification's accuracy target (R_s 5 %, L 10 %, psi_f 5 %).
QUALITY_LIMIT_PCT = {"rs_ohm": 2.5, "ld_h": 5.0, "lq_h": 5.0, "psi_f_wb": 2.5}
MEASURED = tuple(QUALITY_LIMIT_PCT)
QUALITY_FIGURES = ("repeat_pct", "residual_pct")


def number(where: str, obj: dict, key: str) -> float:
    """obj[key] as a finite float; qt.InputError naming where.key otherwise."""
    if key not in obj:
        raise qt.InputError(f"{where}.{key}: missing")
    v = obj[key]
    if isinstance(v, bool) or not isinstance(v, (int, float)):
        raise qt.InputError(f"{where}.{key} = {json.dumps(v)}: not a number")
    if not math.isfinite(float(v)):
        raise qt.InputError(f"{where}.{key} = {json.dumps(v)}: not a finite number")
    return float(v)


def read_record(path: Path) -> dict:
    """The record's results {key: (value, repeat_pct, residual_pct)}, source and conditions."""
    try:
        text = path.read_text(encoding="utf-8")
    except OSError as exc:
        raise qt.InputError(f"{path}: cannot be read ({exc.strerror})") from exc
    try:
        rec = json.loads(text)
    except json.JSONDecodeError as exc:
        raise qt.InputError(f"{path}: not JSON: {exc.msg} at line {exc.lineno}, column {exc.colno}") \
            from exc
    if not isinstance(rec, dict):
        raise qt.InputError(f"{path}: the record must be a JSON object, not {type(rec).__name__}")
    if rec.get("format") != FORMAT:
        raise qt.InputError(f"{path}: format = {json.dumps(rec.get('format'))}: expected "
                        f"\"{FORMAT}\"")
    res = rec.get("results")
    if not isinstance(res, dict):
        raise qt.InputError(f"{path}: results: missing or not an object")
    unknown = sorted(set(res) - set(MEASURED))
    if unknown:
        raise qt.InputError(f"{path}: results.{unknown[0]}: not a measured key (the record carries "
                        f"{', '.join(MEASURED)})")
    out = {}
    for key in MEASURED:
        if key not in res:
            raise qt.InputError(f"{path}: results.{key}: missing")
        r = res[key]
        if not isinstance(r, dict):
            raise qt.InputError(f"{path}: results.{key}: not an object with value, repeat_pct, "
                            "residual_pct")
        where = f"{path}: results.{key}"
        out[key] = tuple(number(where, r, f) for f in ("value",) + QUALITY_FIGURES)
    src = one_line(f"{path}: source", rec.get("source", ""))
    cond = rec.get("conditions", {})
    if not isinstance(cond, dict):
        raise qt.InputError(f"{path}: conditions: not an object")
    for k, v in cond.items():
        one_line(f"{path}: conditions", k)
        if isinstance(v, bool) or not isinstance(v, (int, float, str)):
            raise qt.InputError(f"{path}: conditions.{k} = {json.dumps(v)}: not a number or a text")
        if isinstance(v, str):
            one_line(f"{path}: conditions.{k}", v)
    return {"results": out, "source": src, "conditions": cond}


def one_line(where: str, text: object) -> str:
    """text, when it is a text of one line (it is copied into a comment of the motor file:
    a line break would start a line of its own there); qt.InputError otherwise."""
    if not isinstance(text, str):
        raise qt.InputError(f"{where} = {json.dumps(text)}: not a text")
    if any(ord(c) < 0x20 or ord(c) == 0x7F for c in text):
        raise qt.InputError(f"{where} = {json.dumps(text)}: a control character (a line break "
                        "would start a line of its own in the motor file)")
    return text


def check_results(path: Path, results: dict) -> None:
    """qt.Refusal when a value is not positive or a quality figure is beyond its limit."""
    problems = []
    for key, (value, repeat, resid) in results.items():
        k = qt.SCHEMA_BY_NAME[f"motor.{key}"]
        u = qt.unit_text(k)
        if value <= 0.0:
            problems.append(f"{path}: results.{key}.value = {qt.fmt(value)}{u}: must be > 0")
        lim = QUALITY_LIMIT_PCT[key]
        for fig, val in zip(QUALITY_FIGURES, (repeat, resid)):
            if not 0.0 <= val <= lim:
                problems.append(
                    f"{path}: results.{key}.{fig} = {qt.fmt(val)} %: outside 0 .. {qt.fmt(lim)} % "
                    f"(half the accuracy target of {k.desc}): repeat the identification")
    if problems:
        raise qt.Refusal("\n".join(problems))


SECTION_RE = re.compile(r"^\s*\[\s*([A-Za-z_][A-Za-z0-9_]*)\s*\]\s*(#.*)?$")
KEY_RE = re.compile(r"^\s*([A-Za-z_][A-Za-z0-9_]*)\s*=")


def motor_text(ratings: Path, rec_path: Path, rec: dict) -> str:
    """The ratings file with the measured keys added at the top of its [motor] section."""
    try:
        lines = ratings.read_text(encoding="utf-8").splitlines()
    except (OSError, UnicodeDecodeError) as exc:
        raise qt.InputError(f"{ratings}: cannot be read ({exc})") from exc
    section = None
    motor_at = None
    typed = []
    for n, line in enumerate(lines):
        m = SECTION_RE.match(line)
        if m:
            section = m.group(1)
            if section == "motor" and motor_at is None:
                motor_at = n
            continue
        m = KEY_RE.match(line)
        if m and section == "motor" and m.group(1) in MEASURED:
            typed.append(f"{ratings}:{n + 1}: motor.{m.group(1)} is typed "
                         f"({line.strip()}): the identification measures it; remove the line")
    if typed:
        raise qt.Refusal("\n".join(typed))
    if motor_at is None:
        raise qt.InputError(f"{ratings}: no [motor] section")
    cond = ", ".join(f"{k} {v}" for k, v in sorted(rec["conditions"].items()))
    added = [f"# identified ({rec_path.name}{': ' + rec['source'] if rec['source'] else ''}"
             f"{'; ' + cond if cond else ''}); quality: repeat / residual in % of the value"]
    for key in MEASURED:
        value, repeat, resid = rec["results"][key]
        added.append(f"{key} = {value:.6g}".ljust(26)
                     + f" # identified: repeat {qt.fmt(repeat)} %, residual {qt.fmt(resid)} %")
    return "\n".join(lines[:motor_at + 1] + added + lines[motor_at + 1:]) + "\n"


def main(argv: list[str] | None = None) -> int:
    """Command-line entry point; returns the exit code."""
    ap = argparse.ArgumentParser(
        prog="qfoc_ident.py",
        description="From an identification record (JSON, format qfoc-ident/1) and a ratings "
                    "file (a motor file without motor.rs_ohm, ld_h, lq_h, psi_f_wb) to a motor "
                    "file and its parameter table, with every check of a typed motor file.",
        epilog="Exit codes: 0 written; 1 refused, nothing written; 2 malformed input.")
    ap.add_argument("record", type=Path, help="identification record (JSON)")
    ap.add_argument("ratings", type=Path, help="motor file without the measured keys")
    ap.add_argument("--motor-out", type=Path, required=True,
                    help="the motor file to write, e.g. specs/motors/<name>.toml")
    ap.add_argument("--force", action="store_true",
                    help="replace an existing --motor-out (kept as it was on a refusal)")
    ap.add_argument("--name", help="table name (default: the stem of --motor-out)")
    ap.add_argument("--table-dir", type=Path, default=Path("tables"),
                    help="directory of <name>_params.c/.h (default tables/)")
    ap.add_argument("--out-dir", type=Path, help="report directory (default build/tune/<name>/)")
    ap.add_argument("--no-plots", action="store_true", help="skip the PNG figures")
    ap.add_argument("--set", action="append", default=[], metavar="SECTION.KEY=VALUE",
                    help="an override for the tuning tool, as in tables/manifest.txt (never "
                         "one of the measured keys)")
    args = ap.parse_args(argv)

    out = args.motor_out
    try:
        for s in args.set:
            if s.split("=", 1)[0].strip() in {f"motor.{k}" for k in MEASURED}:
                raise qt.InputError(f"--set {s}: motor.{s.split('=', 1)[0].strip()[6:]} is "
                                    "measured by the identification, not set")
        rec = read_record(args.record)
        check_results(args.record, rec["results"])
        text = motor_text(args.ratings, args.record, rec)
        if out.exists() and not args.force:
            raise qt.Refusal(f"{out}: exists; --force replaces it")
    except qt.InputError as exc:
        return qt.exit_on(exc, "qfoc_ident", "no motor file and no table written")

    old = out.read_bytes() if out.exists() else None
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text(text, encoding="utf-8")
    tune_args = [str(out), "--table-dir", str(args.table_dir),
                 "--name", args.name if args.name else out.stem]
    if args.out_dir:
        tune_args += ["--out-dir", str(args.out_dir)]
    if args.no_plots:
        tune_args.append("--no-plots")
    for s in args.set:
        tune_args += ["--set", s]
    rc = qt.main(tune_args)
    if rc != 0:
        # the tuning tool wrote no table; the motor file goes too (or returns to what it was)
        if old is None:
            out.unlink()
        else:
            out.write_bytes(old)
        print(f"qfoc_ident: the tuning tool refused {out} (above): no motor file and no table "
              "written", file=sys.stderr)
        return rc
    print(f"qfoc_ident: wrote {out} from {args.record} and {args.ratings}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
