"""Tests of the requirement attributes, the clause-level trace, the generated ASR table and the
figure check (tools/evidence/req_attrs.py, trace.py, gen_manual.py, figures.py, evidence.py;
run: python3 -m pytest tools/evidence/tests).

Most tests make up a small repository in a temporary directory (one header with a contract,
one source, one CMocka file, two requirements, the ASR list, a safety manual) and run the
tools on it; each broken input must fail with a message naming the requirement or the
figure.  The requirements are REQ-EVD-015 .. REQ-EVD-020 of specs/requirements/evidence.md.
"""
import json
import subprocess
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent.parent  # tools/evidence
ROOT = HERE.parent.parent
sys.path.insert(0, str(HERE))

import evidence as ev  # noqa: E402
import figures  # noqa: E402
import gen_manual  # noqa: E402
import req_attrs  # noqa: E402

# Requirement IDs of the made-up repository, built so that the trace gate of the real one
# does not read them as IDs named by this file.
XA1, XA2 = "REQ-" + "XA-001", "REQ-" + "XA-002"
SEP = req_attrs.SEP

HEADER = """/**
 * @file x.h
 * @brief The made-up module; the init is named here only: XA2.
 */
#ifndef X_H
#define X_H
/**
 * @brief One step.
 * Requirements: XA1.
 */
/*@
  requires valid: \\valid(p);
  assigns *p;
  ensures bounded: *p <= 10;
  behavior small:
    assumes *p < 5;
    ensures kept: *p == \\old(*p);
  behavior large:
    assumes *p >= 5;
    ensures cut: *p == 10;
*/
int qfoc_x_step(int *p);
#endif
""".replace("XA1", XA1).replace("XA2", XA2)

SOURCE = """#include "qfoc/x.h"
int qfoc_x_step(int *p)
{
    if (*p >= 5) {
        *p = 10;
    }
    return *p;
}
"""

TESTS = """#include <cmocka.h>
/* XA1 */
static void test_xa_001_step(void **state)
{
    (void)state;
}
/* XA2 */
static void test_xa_002_init(void **state)
{
    (void)state;
}
int main(void)
{
    const struct CMUnitTest t[] = {cmocka_unit_test(test_xa_001_step), cmocka_unit_test(test_xa_002_init)};
    return cmocka_run_group_tests(t, NULL, NULL);
}
""".replace("XA1", XA1).replace("XA2", XA2)

WP_RESULTS = ("# Frama-C WP results, per function\n\n**proved 5 / 5 goals**\n\n"
              "| unit | function | goals | proved | provers | time (ms) |\n|---|---|---:|---:|---|---:|\n"
              "| qfoc_x | qfoc_x_step | 5 | 5 | Qed | 1 |\n")

ASR_TOML = """[[asr]]
id = "ASR-01"
asil = "D"
scope = "library"
statement = "The step is bounded."
note = "{wp.proved} of {wp.goals} goals"
"""

MANUAL = """# made-up manual

<!-- BEGIN GENERATED: asr -->
<!-- END GENERATED: asr -->

The text quotes 5 / 5 goals proved.
"""


def req_file(attrs1=None, clauses1=None, attrs2=None):
    a1 = attrs1 if attrs1 is not None else f"Attributes: ASIL D{SEP}kind safety{SEP}verification proof, test{SEP}ASR ASR-01"
    c1 = clauses1 if clauses1 is not None else "Clauses: qfoc_x_step:bounded, qfoc_x_step:small, test test_xa_001_step"
    a2 = attrs2 if attrs2 is not None else f"Attributes: ASIL QM{SEP}kind functional{SEP}verification test"
    lines = ["# X requirements", "", f"### {XA1} Step"]
    lines += [x for x in (a1, c1) if x]
    lines += ["Statement: the step bounds the value.", "Verified by: contract of `qfoc_x_step`; test.", "",
              f"### {XA2} Init"]
    lines += [x for x in (a2,) if x]
    lines += ["Statement: the init.", "Verified by: test.", ""]
    return "\n".join(lines)


def make_repo(root, **kw):
    files = {"include/qfoc/x.h": HEADER, "src/qfoc_x.c": SOURCE, "tests/test_x.c": TESTS,
             "proofs/wp/results.md": WP_RESULTS, "specs/asr.toml": ASR_TOML,
             "specs/safety-manual.md": MANUAL, "specs/requirements/x.md": req_file(**kw)}
    for rel, text in files.items():
        p = root / rel
        p.parent.mkdir(parents=True, exist_ok=True)
        p.write_text(text, encoding="utf-8")


def run_trace(root):
    proc = subprocess.run([sys.executable, str(HERE / "trace.py")], cwd=root, capture_output=True,
                          text=True, check=False)
    return proc.returncode, proc.stdout + proc.stderr


def matrix(root):
    return {e["id"]: e for e in json.loads((root / "build/trace/trace.json").read_text())["requirements"]}


def test_made_up_repository_passes_and_clauses_have_no_result(tmp_path):
    """REQ-EVD-015, REQ-EVD-017: valid attribute and clause lines pass the gate; without the
    WP report a contract clause reads 'no WP result' and is not a pass.

    Methods: 1a valid attribute and clause lines on a made-up repository pass, a clause without
    a WP report reads 'no WP result' (not a pass)
    """
    make_repo(tmp_path)
    rc, out = run_trace(tmp_path)
    assert rc == 0, out
    e = matrix(tmp_path)[XA1]
    assert e["attributes"] == {"asil": "D", "kind": "safety", "verification": ["proof", "test"],
                               "asr": ["ASR-01"]}
    st = {c["ref"]: c for c in e["clauses"]}
    assert st["qfoc_x_step:bounded"]["status"] == "no WP result"
    assert st["qfoc_x_step:bounded"]["ok"] is None
    assert st["test test_xa_001_step"]["ok"] is None
    assert "attributes: ASIL D 1" in out


def test_missing_attribute_line_fails(tmp_path):
    """REQ-EVD-015: a requirement without its attribute line fails the trace, named.

    Methods: 1d a requirement without its attribute line; 1l the line left out of a made-up
    repository
    """
    make_repo(tmp_path, attrs2="")
    rc, out = run_trace(tmp_path)
    assert rc == 1
    assert f"{XA2} (specs/requirements/x.md:" in out and "no 'Attributes:' line right after the heading" in out


def test_invalid_asil_fails(tmp_path):
    """REQ-EVD-015: an ASIL outside QM, A .. D fails, naming the requirement and the value.

    Methods: 1c the ASIL E just outside QM, A .. D; 1d an invalid value, named with the
    requirement
    """
    make_repo(tmp_path, attrs2=f"Attributes: ASIL E{SEP}kind functional{SEP}verification test")
    rc, out = run_trace(tmp_path)
    assert rc == 1
    assert XA2 in out and "invalid ASIL 'E'" in out


def test_malformed_fields_fail():
    """REQ-EVD-015: the fields are parsed strictly: separator, order, values, method order.

    Methods: 1b each field malformed in turn: separators, order, kind, method, method order,
    ASR; 1d malformed attribute lines
    """
    ok, err = req_attrs.parse_attributes(f"Attributes: ASIL QM{SEP}kind tool{SEP}verification test")
    assert ok and err is None
    for line, reason in (
            ("Attributes: ASIL QM; kind tool; verification test", "expected"),
            (f"Attributes: kind tool{SEP}ASIL QM{SEP}verification test", "field 'kind' where 'ASIL'"),
            (f"Attributes: ASIL QM{SEP}kind hardware{SEP}verification test", "invalid kind 'hardware'"),
            (f"Attributes: ASIL QM{SEP}kind tool{SEP}verification inspection", "invalid verification method"),
            (f"Attributes: ASIL QM{SEP}kind tool{SEP}verification test, proof", "in the order"),
            (f"Attributes: ASIL D{SEP}kind safety{SEP}verification test{SEP}ASR 7", "invalid ASR '7'")):
        attrs, err = req_attrs.parse_attributes(line)
        assert attrs is None and reason in err, (line, err)


def test_inconsistent_asil_kind_asr_fail(tmp_path):
    """REQ-EVD-015: kind safety without an ASR, an ASIL other than the one assumed for the
    ASR, and an ASIL above QM without clauses each fail, named.

    Methods: 1b each inconsistency alone: kind safety without an ASR, an ASIL other than the
    ASR's, an ASR that is not defined, ASIL above QM without clauses; 1d inconsistent attributes
    """
    make_repo(tmp_path, attrs2=f"Attributes: ASIL D{SEP}kind functional{SEP}verification test")
    rc, out = run_trace(tmp_path)
    assert rc == 1
    assert f"{XA2} (specs/requirements/x.md:" in out
    assert "ASIL D, but the highest ASIL assumed for its ASRs (none) is QM" in out
    assert "without a 'Clauses:' line" in out
    make_repo(tmp_path, attrs1=f"Attributes: ASIL B{SEP}kind safety{SEP}verification proof, test{SEP}ASR ASR-01")
    rc, out = run_trace(tmp_path)
    assert rc == 1 and "ASIL B, but the highest ASIL assumed for its ASRs (ASR-01) is D" in out
    make_repo(tmp_path, attrs1=f"Attributes: ASIL D{SEP}kind safety{SEP}verification proof, test{SEP}ASR ASR-09")
    rc, out = run_trace(tmp_path)
    assert rc == 1 and "names ASR-09, which specs/asr.toml does not define" in out


def test_claimed_proof_without_proof_fails(tmp_path):
    """REQ-EVD-016: 'proof' claimed for a requirement that no contract with WP goals, lemma
    or CBMC harness names fails, named; the same with 'analysis' without a bench row.

    Methods: 1d 'proof' claimed without a contract, lemma or harness, 'analysis' without a bench
    row
    """
    make_repo(tmp_path, attrs2=f"Attributes: ASIL QM{SEP}kind functional{SEP}verification proof, analysis, test")
    rc, out = run_trace(tmp_path)
    assert rc == 1
    assert f"{XA2} (specs/requirements/x.md) claims verification 'proof', but the trace finds no" in out
    assert f"{XA2} (specs/requirements/x.md) claims verification 'analysis'" in out
    assert f"{XA1} (specs/requirements/x.md) claims" not in out


def test_unknown_clause_fails(tmp_path):
    """REQ-EVD-017: a clause that is not a label of the function's contract, a missing test
    or a test that does not name the requirement fails, named.

    Methods: 1b a label that is no clause of the contract, a test that does not name the
    requirement, an unknown kind, a malformed clause; 1d unknown and malformed clauses
    """
    make_repo(tmp_path, clauses1="Clauses: qfoc_x_step:unbounded, test test_xa_002_init, cbmc nowhere")
    rc, out = run_trace(tmp_path)
    assert rc == 1
    assert f"{XA1}: unknown clause 'qfoc_x_step:unbounded'" in out
    assert "has no behaviour or ensures / requires clause named 'unbounded'" in out
    assert f"{XA1}: clause 'test test_xa_002_init': the test does not name {XA1}" in out
    assert f"{XA1}: unknown clause 'cbmc nowhere'" in out
    _refs, errs = req_attrs.parse_clauses("Clauses: qfoc_x_step bounded")
    assert errs and "is not '<function>:<label>'" in errs[0]


def wp_report(bounded_valid):
    """A -wp-report-json file of the made-up unit (the property names WP gives)."""
    def res(t, v):
        return {"wp:main": {"total": t, "valid": v}}
    return {"wp:functions": {"qfoc_x_step": {
        "qfoc_x_step_ensures_bounded": res(1, bounded_valid),
        "qfoc_x_step_small_ensures_kept": res(1, 1), "qfoc_x_step_large_ensures_cut": res(1, 1),
        "qfoc_x_step_assigns": res(2, 2), "qfoc_x_step_assert_rte_signed_overflow": res(1, 1),
        "wp:section": res(6, 5 + bounded_valid)}},
        "wp:axiomatics": {}}


def test_clause_status_from_the_wp_report(tmp_path):
    """REQ-EVD-017: with build/wp/<unit>.json a clause shows the goals of its property
    (a behaviour all of its clauses); a clause not proved fails the gate, named.

    Methods: 1b behaviours, ensures, assigns and RTE clauses; 1d a clause the WP report does not
    prove (NOT PROVED 0/1)
    """
    make_repo(tmp_path, clauses1="Clauses: qfoc_x_step:bounded, qfoc_x_step:small, qfoc_x_step:assigns, "
                                 "qfoc_x_step:rte, test test_xa_001_step")
    (tmp_path / "build/wp").mkdir(parents=True)
    (tmp_path / "build/wp/qfoc_x.json").write_text(json.dumps(wp_report(1)))
    (tmp_path / "build/wp/wp-summary.json").write_text("{}")
    rc, out = run_trace(tmp_path)
    assert rc == 0, out
    st = {c["ref"]: c for c in matrix(tmp_path)[XA1]["clauses"]}
    assert st["qfoc_x_step:bounded"]["status"] == "proved 1/1" and st["qfoc_x_step:bounded"]["ok"] is True
    assert st["qfoc_x_step:small"]["goals"] == 1
    assert st["qfoc_x_step:assigns"]["goals"] == 2
    assert st["qfoc_x_step:rte"]["goals"] == 1
    (tmp_path / "build/wp/qfoc_x.json").write_text(json.dumps(wp_report(0)))
    rc, out = run_trace(tmp_path)
    assert rc == 1
    assert f"{XA1}: clause 'qfoc_x_step:bounded' does not hold in the WP report" in out
    assert "NOT PROVED 0/1" in out


def test_requires_clause_counts_call_sites():
    """REQ-EVD-017: a precondition's goals are those WP generates at the call sites.

    Methods: 1a a precondition's goals taken from the call sites' goals of the WP report
    """
    index = {"f": {"file": "x.h", "behaviors": set(), "ensures": set(), "requires": {"ok"}, "assigns": True}}
    wp = {"functions": {("u", "g"): {"f_requires_ok": (2, 2), "g_ensures_ok": (1, 1)}}, "lemmas": {}}
    total, valid, _s = req_attrs.wp_goals({"name": "f", "label": "ok"}, index, wp, {})
    assert (total, valid) == (2, 2)


def test_real_requirements_name_the_drive_clauses():
    """REQ-EVD-017: the over-current and PWM requirements of the drive are traced to their
    clauses, not to the function's goals.

    Methods: 1a the drive's over-current and PWM requirements traced to their contract clauses,
    every ACSL clause of this repository's requirements existing
    """
    attrs = req_attrs.load_attributes(ROOT)
    drv2 = [r["ref"] for r in attrs["REQ-DRV-002"]["clauses"]]
    drv3 = [r["ref"] for r in attrs["REQ-DRV-003"]["clauses"]]
    assert drv2 == ["qfoc_drive_fast_step:pwm_only_in_run", "qfoc_drive_fast_step:cmp"]
    assert drv3[0] == "qfoc_drive_fast_step:over_current"
    index, defined = req_attrs.acsl_index(ROOT)
    for rid, rec in attrs.items():
        for ref in rec["clauses"] or []:
            if ref["kind"] == "acsl":
                assert req_attrs.clause_exists(ref, index, defined) is None, (rid, ref)


def test_asr_table_generated_and_stale_table_fails(tmp_path, capsys):
    """REQ-EVD-018: the table is written from the ASR list and the attribute and clause
    lines; --check fails, naming the row, once a requirement changes.

    Methods: 1d an empty block and a row gone stale after a requirement changed; 1l the
    requirement changed in a made-up repository
    """
    make_repo(tmp_path)
    root = str(tmp_path)
    assert gen_manual.main(["--root", root, "--check"]) == 1  # the empty block is stale
    assert gen_manual.main(["--root", root]) == 0
    text = (tmp_path / "specs/safety-manual.md").read_text()
    row = [ln for ln in text.splitlines() if ln.startswith("| ASR-01 |")][0]
    assert f"| D | {XA1} |" in row
    assert "WP: `qfoc_x_step` `bounded`, `small`; test `test_xa_001_step`; 5 of 5 goals" in row
    assert gen_manual.main(["--root", root, "--check"]) == 0
    make_repo(tmp_path, attrs2=f"Attributes: ASIL D{SEP}kind safety{SEP}verification test{SEP}ASR ASR-01",
              clauses1=None)
    (tmp_path / "specs/safety-manual.md").write_text(text)
    capsys.readouterr()
    assert gen_manual.main(["--root", root, "--check"]) == 1
    assert "the row ASR-01 of the ASR table is stale" in capsys.readouterr().out


def test_asr_without_requirement_fails(tmp_path, capsys):
    """REQ-EVD-018: an ASR that no requirement names fails the check, named.

    Methods: 1d an ASR that no requirement names
    """
    make_repo(tmp_path, attrs1=f"Attributes: ASIL QM{SEP}kind functional{SEP}verification proof, test")
    assert gen_manual.main(["--root", str(tmp_path), "--check"]) == 1
    assert "ASR-01: no requirement names it" in capsys.readouterr().out


def test_stale_figure_fails_and_write_fixes_it(tmp_path):
    """REQ-EVD-019: a figure differing from its source fails, naming the file, line, figure
    and both values; --write replaces it; a count no template covers fails as well.

    Methods: 1d a figure differing from its source and a hand-typed count no template covers; 1l
    the wrong figure written into a made-up document
    """
    make_repo(tmp_path)
    (tmp_path / "specs/safety-manual.md").write_text("x\n\nWP: 4 / 5 goals proved; 12 harnesses in all.\n")
    reg = [("specs/safety-manual.md", "{wp.proved} / {wp.goals} goals proved")]
    failures, _notes = figures.check(str(tmp_path), registry=reg)
    assert any("specs/safety-manual.md:3: figure wp.proved is 4, the source says 5" in f for f in failures), failures
    assert any("hand-typed figure '12 harnesses'" in f for f in failures), failures
    figures.check(str(tmp_path), write=True, registry=reg)
    assert "WP: 5 / 5 goals proved" in (tmp_path / "specs/safety-manual.md").read_text()


def test_built_figure_checked_only_when_present(tmp_path):
    """REQ-EVD-019: a figure of build/ is not checked without its source (a note says so),
    but must read the same in every document; with the source it is checked.

    Methods: 1b a built figure with and without its source; 1d the same figure differing between
    two documents and from its source
    """
    make_repo(tmp_path)
    (tmp_path / "specs/safety-manual.md").write_text("A: 48 groups, 333879 vectors\n")
    (tmp_path / "README.md").write_text("B: 48 groups, 333890 vectors\n")
    reg = [("specs/safety-manual.md", "48 groups, {tt.vectors} vectors"),
           ("README.md", "48 groups, {tt.vectors} vectors")]
    failures, notes = figures.check(str(tmp_path), registry=reg)
    assert any("tt.vectors: not checked, build/target_test/target.txt not present" in n for n in notes)
    assert any("figure tt.vectors differs between documents" in f for f in failures), failures
    (tmp_path / "build/target_test").mkdir(parents=True)
    (tmp_path / "build/target_test/target.txt").write_text("result: 48 groups, 333879 vectors, all identical\n")
    failures, notes = figures.check(str(tmp_path), registry=reg)
    assert failures == ["README.md:1: figure tt.vectors is 333890, the source says 333879 "
                        "(build/target_test/target.txt): '48 groups, 333890 vectors'"]


def test_firmware_figure_from_make_firmware(tmp_path):
    """REQ-EVD-019: the image's flash and RAM quoted in the port's README come from the
    record `make firmware` writes (build/s32k144/firmware.json); a seeded wrong one fails.

    Methods: 1b the firmware record absent and present; 1d a seeded wrong flash figure (26899
    against 26900); 1l the wrong figure written into the port's README
    """
    make_repo(tmp_path)
    (tmp_path / "port_s32k").mkdir(exist_ok=True)
    (tmp_path / "port_s32k/README.md").write_text("| 8 kHz | 26899 B of 512 KiB (5.1 %) | 576 B of 32 KiB |\n")
    reg = [("port_s32k/README.md", "| {fw.flash} B of 512 KiB"), ("port_s32k/README.md", "| {fw.ram} B of 32 KiB |")]
    failures, notes = figures.check(str(tmp_path), registry=reg)
    assert failures == [] and any(n.startswith("fw.flash: not checked") for n in notes), (failures, notes)
    (tmp_path / "build/s32k144").mkdir(parents=True)
    (tmp_path / "build/s32k144/firmware.json").write_text(json.dumps({"flash_bytes": 26900, "ram_bytes": 576}))
    failures, _notes = figures.check(str(tmp_path), registry=reg)
    assert len(failures) == 1 and "port_s32k/README.md:1: figure fw.flash is 26899, the source says 26900" \
        in failures[0], failures


def test_changelog_current_section_checked(tmp_path):
    """REQ-EVD-019: a figure of the changelog's current section is checked against its source
    and a seeded wrong one fails; a count no template covers fails there, while the sections
    of older releases are history and are not scanned.

    Methods: 1b the current section and the sections of older releases; 1d a wrong figure and a
    hand-typed count in the current section; 1l the wrong figures written into a made-up
    changelog
    """
    make_repo(tmp_path)
    (tmp_path / "CHANGELOG.md").write_text(
        "# Changelog\n\n## [Unreleased]\n\n- WP: 4 / 5 goals proved.\n- 7 harnesses added.\n\n"
        "## [0.1.0] - 2026-01-01\n\n- 3 harnesses, 2 of 9 goals.\n")
    reg = [("CHANGELOG.md", "{wp.proved} / {wp.goals} goals proved")]
    failures, _notes = figures.check(str(tmp_path), registry=reg)
    assert any("CHANGELOG.md:5: figure wp.proved is 4, the source says 5" in f for f in failures), failures
    assert any("CHANGELOG.md:6: hand-typed figure '7 harnesses'" in f for f in failures), failures
    assert not any("CHANGELOG.md:10" in f for f in failures), failures
    figures.check(str(tmp_path), write=True, registry=reg)
    failures, _notes = figures.check(str(tmp_path), registry=[("CHANGELOG.md", "{wp.proved} / {wp.goals} goals proved"),
                                                              ("CHANGELOG.md", "7 harnesses added")])
    assert failures == [], failures


def test_repository_figures_and_table_agree():
    """REQ-EVD-018, REQ-EVD-019: the committed documents pass both checks.

    Methods: 1a the committed documents of this repository pass the figures check and the ASR
    table's generation
    """
    failures, _notes = figures.check(str(ROOT))
    assert failures == []
    table, errors = gen_manual.generate(str(ROOT))
    assert errors == []
    assert table in (ROOT / "specs/safety-manual.md").read_text()


def test_evidence_page_groups_by_asil(tmp_path, capsys):
    """REQ-EVD-020: the page lists the requirements per ASIL with their clauses, counts per
    kind and method, under the summary and in the printed summary; no script.

    Methods: 1a the evidence page's requirements per ASIL, their clauses and counts per kind and
    method, no script
    """
    make_repo(tmp_path)
    assert run_trace(tmp_path)[0] == 0
    assert ev.main(["--root", str(tmp_path)]) == 0
    out = capsys.readouterr().out
    assert "requirements per ASIL: D 1, QM 1; per kind: safety 1, functional 1" in out
    page = (tmp_path / "build/evidence/index.html").read_text()
    assert "<script" not in page
    assert "<b>ASIL D</b>: 1 requirements" in page and "qfoc_x_step:bounded: no WP result" in page
    data = json.loads((tmp_path / "build/evidence/evidence.json").read_text())
    assert [r["id"] for r in data["sections"]["attrs"]["by_asil"]["D"]] == [XA1]


def test_evidence_page_without_attributes_not_run(tmp_path, capsys):
    """REQ-EVD-020: without attributes in the matrix the counts read 'not run'.

    Methods: 1d a matrix without attributes: the counts read 'not run'
    """
    assert ev.main(["--root", str(tmp_path)]) == 0
    assert "requirement attributes: not run" in capsys.readouterr().out


def test_manual_markers_not_rendered():
    """REQ-EVD-018: the markers of the generated table are not shown on the page.

    Methods: 1a the markers of the generated table are not shown on the page
    """
    html = ev.md_to_html("a\n\n<!-- BEGIN GENERATED: asr -->\n| x |\n|---|\n| 1 |\n<!-- END GENERATED: asr -->\n")
    assert "GENERATED" not in html and "<table>" in html


def test_methods_derived_from_the_verified_by_text():
    """REQ-EVD-016: the rule that gave the verification attribute from a 'Verified by' text.

    Methods: 1b a 'Verified by' text of each kind (contract and CBMC, bench, test file, review
    record)
    """
    assert req_attrs.derive_methods("contract of `f` (ensures `x`); CBMC harness `h`; test `t`") == ["proof", "test"]
    assert req_attrs.derive_methods("`make bench`, rows of `build/bench/bench.md`.") == ["analysis"]
    assert req_attrs.derive_methods("`tools/evidence/tests/test_evidence.py`.") == ["test"]
    assert req_attrs.derive_methods("design review record R-1") == ["review"]
