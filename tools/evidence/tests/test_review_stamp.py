"""Tests of tools/evidence/review_stamp.py: review records tied to the files they reviewed
(run: python3 -m pytest tools/evidence/tests).

The MISRA review records and the FMEA rows are made up in temporary directories, except in
the tests of the repository's own records.  The requirement is REQ-EVD-031 of
specs/requirements/evidence.md.
"""
import csv
import os
import re
import shutil
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent.parent  # tools/evidence
REPO = HERE.parent.parent
sys.path.insert(0, str(HERE))

import review_stamp as rs  # noqa: E402

# Requirement IDs of the made-up trees, written so that the trace gate does not read them as
# IDs named by this file.
X1, X2 = "REQ-" + "X-001", "REQ-" + "X-002"

REVIEWS = """# MISRA C:2012 manual review records

Header text.

## Dir 4.10 Include guards
- Guideline: Dir 4.10 (required)
- Scope: `include/qfoc/*.h`
- Method: each header read.
- Checked: every header has its guard.
- Result: compliant
- Reviewed: 2025-01-01, by the maintainers

## Rule 17.2 No recursion
- Guideline: Rule 17.2 (required)
- Scope: every unit of the code (`src/*.c`), with its headers (`include/qfoc/*.h`)
- Method: the call graph,
  searched for cycles.
- Checked: no cycle.
- Result: compliant
- Reviewed: 2025-01-01, by the maintainers
"""

ANALYSIS = f"""# Safety analysis

## 1. Method

Text.

## 2. Software FMEA

Columns: ...

Reviewed: 2025-01-01, by the maintainers

### 2.1 Fast step

| ID | block | failure mode | detection / mitigation | evidence | residual |
|---|---|---|---|---|---|
| F-01 | `qfoc_a_step` in `d->x` | value wrong | saturated | {X1}; test `test_a` | - |
| F-02 | `qfoc_b_step`, `not_in_the_code` | omitted | none | {X1} .. {X2} | - |

## 3. Dependent failures

Text.
"""


def tree(root):
    files = {
        "include/qfoc/a.h": "#ifndef A_H\n#define A_H\nint qfoc_a_step(int x);\n#endif\n",
        "include/qfoc/b.h": "#ifndef B_H\n#define B_H\nint qfoc_b_step(int x);\n#endif\n",
        "src/qfoc_a.c": "#include \"qfoc/a.h\"\nint qfoc_a_step(int x)\n{\n    return x;\n}\n",
        "src/qfoc_b.c": "#include \"qfoc/b.h\"\n/* qfoc_a_step in a comment */\nint qfoc_b_step(int x)\n{\n    return -x;\n}\n",
        "specs/requirements/x.md": f"# X\n\n### {X1} One\n\nText.\n\n### {X2} Two\n\nText.\n",
        "misra/reviews.md": REVIEWS,
        "specs/safety-analysis.md": ANALYSIS,
    }
    for rel, text in files.items():
        p = root / rel
        p.parent.mkdir(parents=True, exist_ok=True)
        p.write_text(text, encoding="utf-8")
    return root


def records(doc, root):
    res = rs.check(doc, str(root))
    return res, {r["id"]: r for r in res["records"]}


def test_misra_record_stale_names_the_changed_file(tmp_path, capsys):
    """REQ-EVD-031: a review record carries the SHA-256 of the files its Scope names; after a
    change of one of them the record is stale and names the file (from the manifest), the
    records that do not cover it stay current, and --check exits 1.
    Methods: 1d one covered file changed after the review: the record stale, the file named; 1b records that cover it and records that do not."""
    root = tree(tmp_path)
    rs.stamp("misra", str(root), date="2025-02-03")
    text = (root / "misra/reviews.md").read_text(encoding="utf-8")
    assert re.search(r"^- Files: sha256 [0-9a-f]{64} over 2 files \(tools/evidence/review_stamp\.py\)$", text, re.M)
    assert re.search(r"^- Files: sha256 [0-9a-f]{64} over 4 files", text, re.M)
    assert "- Reviewed: 2025-02-03, by the maintainers" in text
    assert "  searched for cycles." in text and "Header text." in text
    assert (root / "misra/reviews.sha256").read_text(encoding="utf-8").count("# stamp ") == 2
    res, recs = records("misra", root)
    assert rs.ok(res) and {r["state"] for r in recs.values()} == {"current"}
    assert recs["Rule 17.2"]["files"] == ["include/qfoc/a.h", "include/qfoc/b.h", "src/qfoc_a.c", "src/qfoc_b.c"]
    assert rs.main(["--root", str(root), "--check", "misra"]) == 0
    (root / "src/qfoc_b.c").write_text("int qfoc_b_step(int x)\n{\n    return x;\n}\n", encoding="utf-8")
    (root / "src/qfoc_c.c").write_text("int c;\n", encoding="utf-8")
    res, recs = records("misra", root)
    assert recs["Dir 4.10"]["state"] == "current"
    st = recs["Rule 17.2"]
    assert st["state"] == "stale"
    assert "1 file changed since the review: src/qfoc_b.c" in st["reasons"]
    assert "1 file new since the review: src/qfoc_c.c" in st["reasons"]
    capsys.readouterr()
    assert rs.main(["--root", str(root), "--check", "misra"]) == 1
    out = capsys.readouterr().out
    assert "Rule 17.2: stale: 4 files reviewed, 5 now" in out
    assert re.search(r"misra/reviews\.md:\d+: Rule 17\.2: stale: .*src/qfoc_b\.c", out)


def test_stamping_one_record_keeps_the_others_stale(tmp_path):
    """REQ-EVD-031: stamping the records named after their review leaves the others stale,
    still naming the changed file (their manifest section is kept).
    Methods: 1b the records stamped and those left unstamped after one change."""
    root = tree(tmp_path)
    rs.stamp("misra", str(root), date="2025-02-03")
    (root / "include/qfoc/a.h").write_text("#ifndef A_H\n#define A_H\nint qfoc_a_step(int y);\n#endif\n",
                                           encoding="utf-8")
    rs.stamp("misra", str(root), ids=["Dir 4.10"], date="2025-02-04")
    _res, recs = records("misra", root)
    assert recs["Dir 4.10"]["state"] == "current" and recs["Dir 4.10"]["reviewed"][0] == "2025-02-04"
    assert recs["Rule 17.2"]["state"] == "stale" and recs["Rule 17.2"]["reviewed"][0] == "2025-02-03"
    assert "1 file changed since the review: include/qfoc/a.h" in recs["Rule 17.2"]["reasons"]
    rs.stamp("misra", str(root), ids=["Rule 17.2"], date="2025-02-05")
    res, _recs = records("misra", root)
    assert rs.ok(res)
    assert (root / "misra/reviews.sha256").read_text(encoding="utf-8").count("# stamp ") == 2


def test_record_without_digest_or_reviewer_is_refused(tmp_path, capsys):
    """REQ-EVD-031: a record without its Files digest, or without a Reviewed line with the date
    and the reviewer, is unstamped (never current); a Scope that names no file is invalid and
    cannot be stamped; --check exits 1.
    Methods: 1d a record without its digest, without its Reviewed line, a Scope naming no file."""
    root = tree(tmp_path)
    _res, recs = records("misra", root)
    assert {r["state"] for r in recs.values()} == {"unstamped"}
    assert "no digest of its files" in recs["Dir 4.10"]["reasons"][0]
    rs.stamp("misra", str(root), date="2025-02-03")
    text = (root / "misra/reviews.md").read_text(encoding="utf-8")
    (root / "misra/reviews.md").write_text(text.replace("- Reviewed: 2025-02-03, by the maintainers\n", "", 1),
                                           encoding="utf-8")
    _res, recs = records("misra", root)
    assert recs["Dir 4.10"]["state"] == "unstamped"
    assert "'Reviewed:'" in recs["Dir 4.10"]["reasons"][0]
    assert recs["Rule 17.2"]["state"] == "current"
    capsys.readouterr()
    assert rs.main(["--root", str(root), "--check", "misra"]) == 1
    (root / "misra/reviews.md").write_text(text.replace("- Scope: `include/qfoc/*.h`", "- Scope: `port/*.c`"),
                                           encoding="utf-8")
    _res, recs = records("misra", root)
    assert recs["Dir 4.10"]["state"] == "invalid"
    assert recs["Dir 4.10"]["reasons"] == ["the Scope pattern `port/*.c` matches no file"]
    assert rs.main(["--root", str(root), "--stamp", "misra", "Dir 4.10"]) == 1
    assert "matches no file" in capsys.readouterr().err


def test_fmea_rows_follow_their_code_and_requirements(tmp_path):
    """REQ-EVD-031: an FMEA row covers the files that define or declare the identifiers of its
    block column and the requirement files of its evidence (a range names every ID in it); the
    stamp table and the Reviewed line are written; a change of the code, of a requirement file,
    or of the function the block names makes the row stale, naming the cause.
    Methods: 1b a change of the code, of a requirement file, of neither; 1c a requirement range."""
    root = tree(tmp_path)
    res, rows = records("fmea", root)
    assert {r["state"] for r in rows.values()} == {"unstamped"}
    assert rows["F-01"]["files"] == ["include/qfoc/a.h", "specs/requirements/x.md", "src/qfoc_a.c"]
    assert rows["F-02"]["reqs"] == [X1, X2]
    assert rows["F-02"]["notes"] == ["not found in the code: not_in_the_code"]
    rs.stamp("fmea", str(root), date="2025-03-01")
    text = (root / "specs/safety-analysis.md").read_text(encoding="utf-8")
    assert "Reviewed: 2025-03-01, by the maintainers" in text
    assert "### 2.6 Review stamps of the rows" in text and text.index("### 2.6") < text.index("## 3.")
    assert re.search(r"^\| F-01 \| `include/qfoc/a\.h`, `specs/requirements/x\.md`, `src/qfoc_a\.c` \| `[0-9a-f]{64}` \|$",
                     text, re.M)
    res, rows = records("fmea", root)
    assert rs.ok(res)
    rs.stamp("fmea", str(root), date="2025-03-01")
    assert (root / "specs/safety-analysis.md").read_text(encoding="utf-8") == text  # stamping twice: the same
    (root / "src/qfoc_a.c").write_text("int qfoc_a_step(int x)\n{\n    return 2 * x;\n}\n", encoding="utf-8")
    _res, rows = records("fmea", root)
    assert rows["F-01"]["state"] == "stale" and rows["F-02"]["state"] == "current"
    assert rows["F-01"]["reasons"] == ["1 file changed since the review: src/qfoc_a.c"]
    rs.stamp("fmea", str(root), ids=["F-01"], date="2025-03-02")
    (root / "specs/requirements/x.md").write_text(f"# X\n\n### {X1} One\n\n### {X2} Two, changed\n",
                                                  encoding="utf-8")
    _res, rows = records("fmea", root)
    assert rows["F-02"]["reasons"] == ["1 file changed since the review: specs/requirements/x.md"]
    rs.stamp("fmea", str(root), date="2025-03-03")
    text = (root / "specs/safety-analysis.md").read_text(encoding="utf-8")
    (root / "specs/safety-analysis.md").write_text(text.replace("| F-01 | `qfoc_a_step` in", "| F-01 | `qfoc_b_step` in"),
                                                   encoding="utf-8")
    _res, rows = records("fmea", root)
    assert rows["F-01"]["state"] == "stale"
    assert rows["F-01"]["reasons"][0] == ("its files are not those reviewed: now also include/qfoc/b.h, "
                                          "src/qfoc_b.c; no longer include/qfoc/a.h, src/qfoc_a.c")


def test_fmea_row_without_code_or_with_unknown_requirement_is_invalid(tmp_path):
    """REQ-EVD-031: a row whose block names nothing of the code, or whose evidence names a
    requirement that does not exist, is invalid, and the analysis without a Reviewed line is
    unstamped.
    Methods: 1d a block naming no code, an unknown requirement, no Reviewed line."""
    root = tree(tmp_path)
    text = ANALYSIS.replace("| F-01 | `qfoc_a_step` in `d->x` |", "| F-01 | both entry points |")
    text = text.replace(f"| {X1} .. {X2} |", "| REQ-" + "X-009 |")
    (root / "specs/safety-analysis.md").write_text(text, encoding="utf-8")
    _res, rows = records("fmea", root)
    assert rows["F-01"]["state"] == "invalid"
    assert rows["F-02"]["state"] == "invalid" and "undefined requirements: REQ-" + "X-009" in rows["F-02"]["reasons"][0]
    (root / "specs/safety-analysis.md").write_text(ANALYSIS.replace("Reviewed: 2025-01-01, by the maintainers\n", ""),
                                                   encoding="utf-8")
    rs.stamp("fmea", str(root), date="2025-03-01")
    assert "Reviewed: 2025-03-01, by the qfoc maintainers" in (root / "specs/safety-analysis.md").read_text(encoding="utf-8")
    (root / "specs/safety-analysis.md").write_text(
        (root / "specs/safety-analysis.md").read_text(encoding="utf-8").replace("Reviewed: 2025-03-01, by", "Reviewed: by"),
        encoding="utf-8")
    _res, rows = records("fmea", root)
    assert {r["state"] for r in rows.values()} == {"unstamped"}


# ----------------------------------------------------------------------------- the repository's own records

def test_repository_records_are_stamped_and_valid():
    """REQ-EVD-031: every record of misra/reviews.md and every FMEA row of
    specs/safety-analysis.md carries its digest and a Reviewed line with a date and a reviewer
    (a role, no commit identifier), and names files that exist; misra/reviews.md holds one
    record per guideline whose plan names a review.
    Methods: 1a every record and row of the repository against REQ-EVD-031's stamp."""
    for doc in ("misra", "fmea"):
        res = rs.check(doc, str(REPO))
        assert res["present"] and not res["errors"], res["errors"]
        bad = [(r["id"], r["state"], r["reasons"]) for r in res["records"] if r["state"] in ("invalid", "unstamped")]
        assert not bad, bad
        for r in res["records"]:
            assert re.fullmatch(r"\d{4}-\d\d-\d\d", r["reviewed"][0]) and r["reviewed"][1], r["id"]
    text = (REPO / "misra/reviews.md").read_text(encoding="utf-8")
    assert not re.search(r"commit `?[0-9a-f]{7,40}\b", text)
    with open(REPO / "misra/enforcement-plan.csv", encoding="utf-8", newline="") as f:
        reviewed = {r["id"] for r in csv.DictReader(f)
                    if "review" in r["methods"].split(";") and r["plan"] != "outside-baseline"}
    assert {r["id"] for r in rs.check("misra", str(REPO))["records"]} == reviewed
    assert len(rs.check("fmea", str(REPO))["records"]) >= 60


def test_repository_records_are_current_after_stamping(tmp_path):
    """REQ-EVD-031: a copy of the repository's records and the files they cover, stamped, is
    current record by record; stamping it again changes nothing.
    Methods: 1a the repository's records stamped in a copy: current, stamping again changes nothing."""
    for d in ("src", "include", "tables", "port_s32k", "specs/requirements"):
        shutil.copytree(REPO / d, tmp_path / d, ignore=shutil.ignore_patterns("fake", "__pycache__"))
    for rel in ("misra/reviews.md", "misra/reviews.sha256", "specs/safety-analysis.md",
                "specs/safety-analysis.sha256"):
        if (REPO / rel).exists():
            (tmp_path / rel).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy(REPO / rel, tmp_path / rel)
    for doc, path in (("misra", "misra/reviews.md"), ("fmea", "specs/safety-analysis.md")):
        rs.stamp(doc, str(tmp_path), date="2030-01-01")
        res = rs.check(doc, str(tmp_path))
        assert rs.ok(res), [(r["id"], r["state"], r["reasons"]) for r in res["records"] if r["state"] != "current"]
        once = (tmp_path / path).read_text(encoding="utf-8")
        rs.stamp(doc, str(tmp_path), date="2030-01-01")
        assert (tmp_path / path).read_text(encoding="utf-8") == once
        # the stamp changes only the Reviewed and Files lines (and the generated table)
        orig = [ln for ln in (REPO / path).read_text(encoding="utf-8").splitlines()
                if not ln.startswith(("- Reviewed:", "- Files:", "Reviewed:", "| ")) and "GENERATED: fmea" not in ln]
        new = [ln for ln in once.splitlines()
               if not ln.startswith(("- Reviewed:", "- Files:", "Reviewed:", "| ")) and "GENERATED: fmea" not in ln]
        assert orig == new, doc
    assert os.path.exists(tmp_path / "misra/reviews.sha256")


def test_fmea_row_with_a_bar_in_a_cell_is_refused(tmp_path):
    """REQ-EVD-031: a row whose cells do not match its table (a '|' written inside a cell) is
    named as an error, never silently left out; a bar written '\\|' is part of its cell.
    Methods: 1d a bar inside a cell (malformed row); 1c an escaped bar, the edge of the cell syntax."""
    root = tree(tmp_path)
    bad = ANALYSIS.replace("| value wrong | saturated |", "| value wrong | |x| saturated |")
    (root / "specs/safety-analysis.md").write_text(bad, encoding="utf-8")
    res, rows = records("fmea", root)
    assert "F-01" not in rows and not rs.ok(res)
    assert any("row F-01" in e and "'\\|'" in e for e in res["errors"]), res["errors"]
    good = ANALYSIS.replace("| value wrong | saturated |", "| value wrong | \\|x\\| saturated |")
    (root / "specs/safety-analysis.md").write_text(good, encoding="utf-8")
    res, rows = records("fmea", root)
    assert "F-01" in rows and not [e for e in res["errors"] if "row F-01" in e]
