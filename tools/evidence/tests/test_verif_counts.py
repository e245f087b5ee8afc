"""Tests of tools/evidence/verif_counts.py (run: python3 -m pytest tools/evidence/tests).

A small repository is made up in a temporary directory: one CMocka file, one pytest file,
two CBMC harnesses, a target-test suite table, a robustness campaign and a specification
with the markers.  The counts and tags written for it are checked case by case, and --check
must name the suite and the figure that a change makes stale.  The last tests run the tool
on this repository.  Requirement: REQ-EVD-007 (the tests and their counts in the evidence).
"""
import re
import sys
from pathlib import Path

import pytest

EVIDENCE = Path(__file__).resolve().parent.parent
REPO = EVIDENCE.parent.parent
sys.path.insert(0, str(EVIDENCE))

import verif_counts as vc  # noqa: E402

# A requirement of the made-up tree, written so that the trace gate does not read it as an
# ID named by this file.
RID = "REQ-" + "ABC-001"

REQS = f"# made-up requirements\n\n### {RID} A thing\nStatement: it works.\n"

C_SUITE = """/* a made-up CMocka suite */
#include <cmocka.h>

static int helper(int x)
{
    return x;
}

/* %RID%: the corners of the input. */
static void test_abc_001_corners(void **state)
{
    int x = -32768;   /* the lowest value */
    (void)state;
    assert_int_equal(helper(x), x);
}

/* random inputs against the double-precision model */
static void test_model_random(void **state)
{
    (void)state;
    assert_true(helper(1) == 1);
}

/* every single-bit flip of the table is refused */
static void test_table_bit_flips(void **state)
{
    (void)state;
    /* no fault here: a negated word does not count */
    assert_true(helper(2) == 2);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_abc_001_corners),
        cmocka_unit_test(test_model_random),
        cmocka_unit_test(test_table_bit_flips),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
""".replace("%RID%", RID)

PY_SUITE = '''"""A made-up pytest suite."""
import pytest


def helper():
    return 1


# %RID%: a refused input
@pytest.mark.parametrize("x", [1, 2, 3])
def test_input_refused(x):
    assert x > 0


def test_plain():
    """Nothing in particular."""
    assert helper() == 1
'''.replace("%RID%", RID)

HARNESS = """/*
 * CBMC harness: every int16_t input (-32768 included) of the unit (%RID%).
 */
void harness(void)
{
}
""".replace("%RID%", RID)

TT_GROUPS = """/* replay functions */
/* alpha: every value */
static void tt_replay_alpha(tt_ctx_t *c)
{
    (void)c;
}

static void tt_replay_pair(tt_ctx_t *c)
{
    (void)c;
}

/* The suites.  Every group: REQ-TGT-001 (its golden vectors). */
const tt_suite_t tt_suites[2] = {
    { { "alpha", NULL }, 1u, tt_replay_alpha },
    { { "pair_a", "pair_b" }, 2u, tt_replay_pair },
};
"""

TT_GEN = """/* the generator: a closed-loop run with an over-current pulse */
/* the corners of the type, then random values */
static void gen_alpha(rows_t *r)
{
    (void)r;
}

static const gen_entry_t GEN[] = {
    { "alpha", 1u, 0u, gen_alpha },
};
"""

ROBUST = """/* the campaign: random cold starts with ADC noise (REQ-SCN-011) */
static void draw(void)
{
}
"""

SCENARIOS = """[one]
min_a = 1
max_b = 2

[two]   # a second section
max_c = 3
"""

SPEC = ("# made-up specification\n\nText before.\n\n" + vc.BEGIN + "\n" + vc.END +
        "\n\nText after.\n")


def make_tree(root):
    """The made-up repository under root."""
    files = {
        "specs/requirements/abc.md": REQS,
        "tests/test_alpha.c": C_SUITE,
        "tools/x/tests/test_tool.py": PY_SUITE,
        "proofs/cbmc/h_one/harness.c": HARNESS,
        "proofs/cbmc/h_two/harness.c": HARNESS,
        "proofs/cbmc/not_a_harness/README": "no harness here\n",
        "tools/target_test/tt_groups.c": TT_GROUPS,
        "tools/target_test/tt_gen.c": TT_GEN,
        "sim/apps/robust.c": ROBUST,
        "Makefile": "ROBUST_COUNT ?= 7\n",
        "specs/scenarios.toml": SCENARIOS,
        "specs/verification-spec.md": SPEC,
    }
    for rel, text in files.items():
        path = root / rel
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text, encoding="utf-8")
    return root / "specs" / "verification-spec.md"


def figures_of(spec):
    return vc.parse_section(vc.extract(spec.read_text(encoding="utf-8")))


# REQ-EVD-007: the cases of each suite of a made-up tree are counted and tagged by the rules.
def test_counts_and_tags_of_a_made_up_tree(tmp_path):
    spec = make_tree(tmp_path)
    assert vc.main(["--root", str(tmp_path)]) == 0
    fig = figures_of(spec)
    c = fig["tests/test_alpha.c (CMocka)"]
    assert c["cases"] == "3"                    # the helper is not a case
    assert c["T8 1a requirements"] == "1"       # the ID in the comment
    assert c["T8 1b equivalence classes"] == "2"   # random, every
    assert c["T8 1c boundary values"] == "1"    # corners, -32768
    assert c["T8 1d error guessing"] == "1"     # flip, refused; the negated fault is not
    assert c["T7 1l fault injection"] == "1"    # flip
    assert c["T7 1n back-to-back"] == "1"       # double-precision model
    p = fig["test_tool.py (pytest)"]
    assert p["cases"] == "2"                    # a parametrised function is one case
    assert p["T8 1a requirements"] == "1"
    assert p["T8 1d error guessing"] == "1"
    h = fig["proofs/cbmc (CBMC)"]
    assert h["cases"] == "2"                    # a folder without harness.c is not a case
    assert h["T8 1c boundary values"] == "2"
    assert h["T7 1l fault injection"] == "-"
    t = fig["target_test (target)"]
    assert t["cases"] == "3"                    # alpha, pair_a, pair_b
    assert t["T8 1a requirements"] == "3"       # the comment above the suite table
    assert t["T8 1b equivalence classes"] == "1"   # alpha: random, every
    assert t["T8 1c boundary values"] == "1"    # alpha: corners
    assert t["T7 1n back-to-back"] == "3"       # suite rule
    r = fig["robustness (campaign)"]
    assert r["cases"] == "7"                    # ROBUST_COUNT of the Makefile
    assert r["T8 1a requirements"] == "7" and r["T8 1b equivalence classes"] == "7"
    assert fig["specs/scenarios.toml (targets)"] == {"sections": "2",
                                                     "min_ / max_ targets": "3"}
    assert fig["Totals CMocka"]["suites"] == "1"
    text = spec.read_text(encoding="utf-8")
    assert text.startswith("# made-up specification\n\nText before.\n")
    assert text.endswith(vc.END + "\n\nText after.\n")


# REQ-EVD-007: each tag comes with the word or literal that gave it (--list).
def test_list_names_the_reason(tmp_path, capsys):
    make_tree(tmp_path)
    assert vc.main(["--root", str(tmp_path), "--list"]) == 0
    out = capsys.readouterr().out
    line = next(ln for ln in out.splitlines() if "test_abc_001_corners" in ln)
    assert f"1a({RID})" in line and "1c(corners)" in line
    line = next(ln for ln in out.splitlines() if "test_table_bit_flips" in ln)
    assert "1d(refused)" in line and "1l(flips)" in line


# REQ-EVD-007: --check passes on a fresh section and names the suite and figure of a stale one.
def test_check_detects_a_stale_figure(tmp_path, capsys):
    spec = make_tree(tmp_path)
    assert vc.main(["--root", str(tmp_path)]) == 0
    assert vc.main(["--root", str(tmp_path), "--check"]) == 0
    capsys.readouterr()
    # a figure edited by hand
    text = spec.read_text(encoding="utf-8")
    block = text.split("#### tests/test_alpha.c (CMocka)")[1].split("####")[0]
    spec.write_text(text.replace(block, block.replace("| 3 | 1 |", "| 4 | 1 |")),
                    encoding="utf-8")
    assert vc.main(["--root", str(tmp_path), "--check"]) == 1
    err = capsys.readouterr().err
    assert "tests/test_alpha.c (CMocka): cases: committed 4, sources give 3" in err
    # a case added to the sources
    assert vc.main(["--root", str(tmp_path)]) == 0
    src = tmp_path / "tests" / "test_alpha.c"
    src.write_text(src.read_text(encoding="utf-8").replace(
        "        cmocka_unit_test(test_table_bit_flips),\n",
        "        cmocka_unit_test(test_table_bit_flips),\n"
        "        cmocka_unit_test(test_model_random),\n"), encoding="utf-8")
    capsys.readouterr()
    assert vc.main(["--root", str(tmp_path), "--check"]) == 1
    err = capsys.readouterr().err
    assert "tests/test_alpha.c (CMocka): cases: committed 3, sources give 4" in err
    assert "Totals CMocka: cases: committed 3, sources give 4" in err
    # a suite removed from the sources
    (tmp_path / "tools" / "x" / "tests" / "test_tool.py").unlink()
    capsys.readouterr()
    assert vc.main(["--root", str(tmp_path), "--check"]) == 1
    assert "test_tool.py (pytest): in the committed section, no longer in the sources" in \
        capsys.readouterr().err


# REQ-EVD-007: a specification without the markers is an error, not an empty section.
def test_missing_markers_exit_2(tmp_path, capsys):
    spec = make_tree(tmp_path)
    spec.write_text("# no markers\n", encoding="utf-8")
    assert vc.main(["--root", str(tmp_path), "--check"]) == 2
    assert "has no section" in capsys.readouterr().err


# REQ-EVD-007: the committed section of specs/verification-spec.md matches this repository.
def test_repository_check_passes(capsys):
    assert vc.main(["--root", str(REPO), "--check"]) == 0
    assert "up to date" in capsys.readouterr().out


# REQ-EVD-007: every CMocka registration of tests/ is counted, and every CBMC folder.
def test_repository_counts_match_the_sources():
    suites = vc.all_suites(str(REPO))
    by_name = {s.name: s for s in suites}
    registered = 0
    for path in sorted((REPO / "tests").glob("test_*.c")):
        registered += len(re.findall(r"\bcmocka_unit_test\w*\(",
                                     path.read_text(encoding="utf-8")))
    assert sum(len(s.cases) for s in suites if s.kind == "CMocka") == registered
    harnesses = list((REPO / "proofs" / "cbmc").glob("*/harness.c"))
    assert len(by_name["proofs/cbmc"].cases) == len(harnesses)


if __name__ == "__main__":
    sys.exit(pytest.main([__file__, "-q"]))
