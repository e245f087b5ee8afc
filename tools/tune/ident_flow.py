#!/usr/bin/env python3
"""ident_flow.py -- the commissioning flow on every table of a manifest: identification
record -> qfoc_ident.py -> motor file and parameter table.

    python3 tools/tune/ident_flow.py RECORD_DIR --out DIR [--manifest tables/manifest.txt]
                                     [--known NAME ...]

For each line "NAME MOTOR [SECTION.KEY=VALUE ...]" of the manifest:
  1. the ratings file DIR/ratings/NAME.toml: the motor file without the four keys of its
     [motor] section that the identification measures (rs_ohm, ld_h, lq_h, psi_f_wb), so
     that no measured value is typed;
  2. tools/tune/qfoc_ident.py with RECORD_DIR/NAME.json (ident_decode.py --record-dir) and
     those ratings, the line's overrides passed on: DIR/motors/NAME_id.toml and the table
     DIR/tables/NAME_id_params.c/.h, with every check of a typed motor file.
Writes DIR/manifest.txt, a line "NAME_id MOTOR OVERRIDES" for each table made: the cold
start (sim/apps/ident_start.c) runs the identified table on the plant of the true motor.

Exit: 0 when every motor has its table; 1 when one has none (no record: the
identification did not end DONE; or qfoc_ident.py refused it), except the motors named by
--known, whose refusal is reported as a known shortfall; 2 on malformed input.

Requirement: REQ-TUNE-009 (specs/requirements/tune.md).
"""
import argparse
import io
import re
import sys
from contextlib import redirect_stderr, redirect_stdout
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

import qfoc_ident as qi  # noqa: E402

SECTION_RE = re.compile(r"^\s*\[\s*([A-Za-z_][A-Za-z0-9_]*)\s*\]")
KEY_RE = re.compile(r"^\s*([A-Za-z_][A-Za-z0-9_]*)\s*=")


def manifest(path):
    """[(name, motor, [overrides])] of a manifest; ValueError naming the line."""
    out = []
    for no, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
        words = line.split()
        if not words or words[0].startswith("#"):
            continue
        if len(words) < 2:
            raise ValueError(f"{path}:{no}: '{line.strip()}': expected NAME MOTOR [OVERRIDES]")
        out.append((words[0], words[1], words[2:]))
    return out


def ratings_text(motor):
    """The motor file without the measured keys of its [motor] section."""
    keep, section = [], None
    for line in motor.read_text(encoding="utf-8").splitlines():
        m = SECTION_RE.match(line)
        if m:
            section = m.group(1)
        k = KEY_RE.match(line)
        if not (section == "motor" and k and k.group(1) in qi.MEASURED):
            keep.append(line)
    return "\n".join(keep) + "\n"


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("records", type=Path)
    ap.add_argument("--out", type=Path, required=True)
    ap.add_argument("--manifest", type=Path, default=Path("tables/manifest.txt"))
    ap.add_argument("--known", action="append", default=[], metavar="NAME",
                    help="a motor whose refusal is a known shortfall (reported, not failed)")
    a = ap.parse_args(argv)
    try:
        lines = manifest(a.manifest)
    except (OSError, ValueError) as e:
        print(f"ident_flow.py: {e}", file=sys.stderr)
        return 2
    names = [n for n, _, _ in lines]
    for k in a.known:
        if k not in names:
            print(f"ident_flow.py: --known '{k}': not a table of {a.manifest}", file=sys.stderr)
            return 2
    for d in ("ratings", "motors", "tables", "tune"):
        (a.out / d).mkdir(parents=True, exist_ok=True)
    made, rows, bad = [], [], []
    for name, motor, over in lines:
        rec = a.records / f"{name}.json"
        if any(o.replace(" ", "") in ("sensing.mode=shunt", 'sensing.mode="shunt"') for o in over):
            # the identification measures with two phase-current sensors (ident.h)
            rows.append((name, "single-shunt table: not identified (the identification needs "
                               "two phase-current sensors)"))
            continue
        if not rec.exists():
            rows.append((name, "no record (the identification did not end DONE)"))
            bad.append(name)
            continue
        rat = a.out / "ratings" / f"{name}.toml"
        rat.write_text(ratings_text(Path(motor)), encoding="utf-8")
        out = a.out / "motors" / f"{name}_id.toml"
        args = [str(rec), str(rat), "--motor-out", str(out), "--force", "--name", f"{name}_id",
                "--table-dir", str(a.out / "tables"), "--out-dir", str(a.out / "tune" / name),
                "--no-plots"]
        for o in over:
            args += ["--set", o]
        log = io.StringIO()
        with redirect_stdout(log), redirect_stderr(log):
            rc = qi.main(args)
        (a.out / "tune" / f"{name}.log").write_text(log.getvalue(), encoding="utf-8")
        if rc == 0:
            made.append(f"{name}_id {motor} {' '.join(over)}".rstrip())
            rows.append((name, f"table {a.out / 'tables' / (name + '_id_params.c')}"))
        else:
            why = [ln.strip() for ln in log.getvalue().splitlines() if ln.strip()]
            rows.append((name, " / ".join(why[:3])))
            bad.append(name)
    (a.out / "manifest.txt").write_text(
        "# tables made from identification records (tools/tune/ident_flow.py): the table is the\n"
        "# identified one, the motor file the true motor of the plant\n" +
        "".join(m + "\n" for m in made), encoding="utf-8")
    for name, what in rows:
        print(f"ident_flow.py: {name}: {what}")
    failed = [n for n in bad if n not in a.known]
    for n in bad:
        if n in a.known:
            print(f"ident_flow.py: {n}: no table: a known shortfall (--known)")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
