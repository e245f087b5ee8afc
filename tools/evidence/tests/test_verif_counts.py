"""Tests of tools/evidence/verif_counts.py (run: python3 -m pytest tools/evidence/tests).

A small repository is made up in a temporary directory: one CMocka file, one pytest file,
two CBMC harnesses, a target-test suite table, a robustness campaign and a specification
with the markers.  Each case states its methods in a 'Methods:' tag; the counts written
for the tree must be those of the tags, whatever the names and comments say, and --check
must name the file, the line and the case of a missing or invalid tag, and the suite and
the figure that a change makes stale.  The last tests run the tool on this repository.
Requirement: REQ-EVD-007 (the tests and their counts in the evidence).
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

/* %RID%: the corners of the input.
   Methods: 1c the input -32768 and 32767; 1n the double-precision
   model of the helper */
static void test_abc_001_corners(void **state)
{
    int x = -32768;   /* the lowest value */
    (void)state;
    assert_int_equal(helper(x), x);
}

/* random, invalid, corrupted corners and every class, says the comment; the tag decides
 * Methods: 1b 1000 random values over the whole domain
 */
static void test_model_random(void **state)
{
    (void)state;
    assert_true(helper(1) == 1);
}

// every single-bit flip of the table is refused
// Methods: 1d a corrupted table; 1l every single-bit flip of it
static void test_table_bit_flips(void **state)
{
    (void)state;
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
# Methods: 1d a negative input; 1c zero, the lowest accepted value
@pytest.mark.parametrize("x", [1, 2, 3])
def test_input_refused(x):
    assert x > 0


def test_plain():
    """Nothing in particular.

    Methods: 1b any value of the helper's one class
    """
    assert helper() == 1
'''.replace("%RID%", RID)

HARNESS = """/*
 * CBMC harness: every int16_t input of the unit (%RID%).
 *
 * Methods: 1b every int16_t input; 1c -32768
 */
void harness(void)
{
}
""".replace("%RID%", RID)

TT_GROUPS = """/* replay functions */
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
    /* Methods: 1b random values; 1c the corners of the type; 1n the target build against
       the host build */
    { { "alpha", NULL }, 1u, tt_replay_alpha },
    /* Methods: 1n the target build against the host build */
    { { "pair_a", "pair_b" }, 2u, tt_replay_pair },
};
"""

TT_GEN = """/* the generator */
static void gen_alpha(rows_t *r)
{
    (void)r;
}
"""

ROBUST = """/* the campaign: random cold starts with ADC noise (REQ-SCN-011)
 *
 * Methods: 1b uniform draws over the plant's deviations; 1d ADC noise
 */
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


def edit(path, old, new):
    text = path.read_text(encoding="utf-8")
    assert old in text, old
    path.write_text(text.replace(old, new, 1), encoding="utf-8")


# REQ-EVD-007: the cases of each suite of a made-up tree are counted by their method tags.
# Methods: 1b one suite of each kind (CMocka, pytest, CBMC, target, campaign), each tag
# place (a /* */ block, // lines, # lines above decorators, a docstring, a harness header,
# a table entry, a campaign header); 1n the counts worked out by hand from the fixture's tags
def test_counts_are_the_tags_of_a_made_up_tree(tmp_path):
    spec = make_tree(tmp_path)
    assert vc.main(["--root", str(tmp_path)]) == 0
    fig = figures_of(spec)
    c = fig["tests/test_alpha.c (CMocka)"]
    assert c["cases"] == "3"                    # the helper is not a case
    assert c["T8 1a requirements"] == "1"       # the ID in the comment
    assert c["T8 1b equivalence classes"] == "1"   # test_model_random's tag only
    assert c["T8 1c boundary values"] == "1"    # test_abc_001_corners
    assert c["T8 1d error guessing"] == "1"     # test_table_bit_flips
    assert c["T7 1l fault injection"] == "1"
    assert c["T7 1n back-to-back"] == "1"
    p = fig["test_tool.py (pytest)"]
    assert p["cases"] == "2"                    # a parametrised function is one case
    assert p["T8 1a requirements"] == "1"
    assert p["T8 1b equivalence classes"] == "1"   # the docstring's tag
    assert p["T8 1c boundary values"] == "1"    # the tag above the decorator
    assert p["T8 1d error guessing"] == "1"
    h = fig["proofs/cbmc (CBMC)"]
    assert h["cases"] == "2"                    # a folder without harness.c is not a case
    assert h["T8 1b equivalence classes"] == "2" and h["T8 1c boundary values"] == "2"
    assert h["T8 1d error guessing"] == "0"
    assert h["T7 1l fault injection"] == "-" and h["T7 1n back-to-back"] == "-"
    t = fig["target_test (target)"]
    assert t["cases"] == "3"                    # alpha, pair_a, pair_b
    assert t["T8 1a requirements"] == "3"       # the comment above the suite table
    assert t["T8 1b equivalence classes"] == "1" and t["T8 1c boundary values"] == "1"
    assert t["T7 1n back-to-back"] == "3"       # the pair's entry gives both groups
    r = fig["robustness (campaign)"]
    assert r["cases"] == "7"                    # ROBUST_COUNT of the Makefile
    assert (r["T8 1a requirements"], r["T8 1b equivalence classes"],
            r["T8 1c boundary values"], r["T8 1d error guessing"]) == ("7", "7", "0", "7")
    assert fig["specs/scenarios.toml (targets)"] == {"sections": "2",
                                                     "min_ / max_ targets": "3"}
    assert fig["Totals CMocka"]["suites"] == "1"
    text = spec.read_text(encoding="utf-8")
    assert text.startswith("# made-up specification\n\nText before.\n")
    assert text.endswith(vc.END + "\n\nText after.\n")
    assert "its method tag lists 1b" in text and "random*" not in text


# REQ-EVD-007: a tag changed in the sources changes the counts; names and comments do not.
# Methods: 1b a method added to a tag, a method removed from one, the rest of the comment
# changed; 1n the counts before and after the edit
def test_counts_follow_the_tags_not_the_words(tmp_path):
    spec = make_tree(tmp_path)
    src = tmp_path / "tests" / "test_alpha.c"
    edit(src, "Methods: 1b 1000 random values over the whole domain",
         "Methods: 1b 1000 random values over the whole domain; 1c INT16_MIN")
    edit(src, "// Methods: 1d a corrupted table; 1l every single-bit flip of it",
         "// Methods: 1d a corrupted table")
    edit(src, "the corners of the input.", "no corner, nothing random, no fault.")
    assert vc.main(["--root", str(tmp_path)]) == 0
    c = figures_of(spec)["tests/test_alpha.c (CMocka)"]
    assert c["T8 1b equivalence classes"] == "1"
    assert c["T8 1c boundary values"] == "2"
    assert c["T7 1l fault injection"] == "0"


# REQ-EVD-007: each counted method comes with the reason its tag gives (--list).
# Methods: 1b a case with a requirement and a tag, a case with a tag alone; 1a the list's
# columns: suite, case, file:line of the tag, methods with their reasons
def test_list_names_the_reason(tmp_path, capsys):
    make_tree(tmp_path)
    assert vc.main(["--root", str(tmp_path), "--list"]) == 0
    out = capsys.readouterr().out
    line = next(ln for ln in out.splitlines() if "test_abc_001_corners" in ln)
    assert f"tests/test_alpha.c:10\t1a {RID}; 1c the input -32768 and 32767; " \
           "1n the double-precision model of the helper" in line
    line = next(ln for ln in out.splitlines() if "\ttest_plain\t" in ln)
    assert line.endswith("tools/x/tests/test_tool.py:19\t1b any value of the helper's one class")


# REQ-EVD-007: a case without a tag fails --check, named with its file, line and name.
# Methods: 1b a CMocka case, a pytest case, a harness, a target group and the campaign
# each left without a tag; 1d a tag removed from a made-up tree
def test_case_without_a_tag_fails_the_check(tmp_path, capsys):
    make_tree(tmp_path)
    assert vc.main(["--root", str(tmp_path)]) == 0
    assert vc.main(["--root", str(tmp_path), "--check"]) == 0
    edit(tmp_path / "tests" / "test_alpha.c", "// Methods: 1d a corrupted table; 1l every "
         "single-bit flip of it\n", "")
    edit(tmp_path / "tools" / "x" / "tests" / "test_tool.py", "\n\n    Methods: 1b any value "
         "of the helper's one class\n    ", "")
    edit(tmp_path / "proofs" / "cbmc" / "h_two" / "harness.c", " * Methods: 1b every int16_t "
         "input; 1c -32768\n", "")
    edit(tmp_path / "tools" / "target_test" / "tt_groups.c", "    /* Methods: 1n the target "
         "build against the host build */\n", "")
    edit(tmp_path / "sim" / "apps" / "robust.c", " * Methods: 1b uniform draws over the "
         "plant's deviations; 1d ADC noise\n", "")
    capsys.readouterr()
    assert vc.main(["--root", str(tmp_path), "--check"]) == 1
    err = capsys.readouterr().err
    assert "tests/test_alpha.c:29: test_table_bit_flips: no 'Methods:' tag (in the comment " \
           "right above the test function)" in err
    assert "tools/x/tests/test_tool.py:16: test_plain: no 'Methods:' tag" in err
    assert "proofs/cbmc/h_two/harness.c:1: h_two: no 'Methods:' tag" in err
    assert "tools/target_test/tt_groups.c:17: pair_a: no 'Methods:' tag" in err
    assert "tools/target_test/tt_groups.c:17: pair_b: no 'Methods:' tag" in err
    assert "sim/apps/robust.c:1: cold start (seeded draw): no 'Methods:' tag" in err
    assert "6 method tag error(s)" in err
    # and nothing is written while a tag is missing
    assert vc.main(["--root", str(tmp_path)]) == 1


# REQ-EVD-007: an unknown method code fails --check, named with the case and the code.
# Methods: 1b a code of another table (1e), a misspelt code (1B), a word; 1d unknown codes
@pytest.mark.parametrize("code", ["1e", "1B", "equivalence"])
def test_unknown_method_code_fails_the_check(tmp_path, capsys, code):
    make_tree(tmp_path)
    assert vc.main(["--root", str(tmp_path)]) == 0
    edit(tmp_path / "tests" / "test_alpha.c", "Methods: 1b 1000 random values",
         f"Methods: {code} 1000 random values")
    capsys.readouterr()
    assert vc.main(["--root", str(tmp_path), "--check"]) == 1
    err = capsys.readouterr().err
    assert (f"tests/test_alpha.c:20: test_model_random: unknown method code '{code}' "
            "(known: 1a, 1b, 1c, 1d, 1l, 1n)") in err


# REQ-EVD-007: the other malformed tags fail --check, each named.
# Methods: 1b each rule of the tag broken alone, one per parameter; 1d a misspelt keyword,
# a code without a reason, a code twice, an empty tag, an empty entry, two tags, 1a without
# a requirement, a Table 7 code on a harness
@pytest.mark.parametrize("path, old, new, message", [
    ("tests/test_alpha.c", "// Methods: 1d", "// methods: 1d", "malformed tag 'methods': write 'Methods:'"),
    ("tests/test_alpha.c", "// Methods: 1d", "// Method: 1d", "malformed tag 'Method': write 'Methods:'"),
    ("tests/test_alpha.c", "1l every single-bit flip of it", "1l", "method 1l without a reason"),
    ("tests/test_alpha.c", "1l every single-bit flip of it", "1d again", "method 1d twice"),
    ("tests/test_alpha.c", "// Methods: 1d a corrupted table; 1l every single-bit flip of it",
     "// Methods:", "empty tag"),
    ("tests/test_alpha.c", "1d a corrupted table; 1l", "1d a corrupted table;; 1l", "empty entry"),
    ("tests/test_alpha.c", "// every single-bit flip of the table is refused",
     "// Methods: 1b all flips", "a second tag (the first on line 28)"),
    ("tests/test_alpha.c", "1d a corrupted table; 1l", "1a by hand; 1d a corrupted table; 1l",
     "1a in the tag, but the case names no requirement"),
    ("tools/x/tests/test_tool.py", "Nothing in particular.",
     "Nothing in particular.\n\n    Methods: 1d twice", "a second tag"),
    ("proofs/cbmc/h_one/harness.c", "1c -32768", "1c -32768; 1n a twin",
     "1n in the tag of a CBMC harness"),
])
def test_malformed_tag_fails_the_check(tmp_path, capsys, path, old, new, message):
    make_tree(tmp_path)
    assert vc.main(["--root", str(tmp_path)]) == 0
    edit(tmp_path / path, old, new)
    capsys.readouterr()
    assert vc.main(["--root", str(tmp_path), "--check"]) == 1
    err = capsys.readouterr().err
    assert message in err and path in err, err


# REQ-EVD-007: the tag's syntax: the comment leaders, the lines that continue it, its end.
# Methods: 1b each comment form ('/*', ' * ', '//', '#', a docstring), a tag that goes on
# over several lines and one followed by more text after a blank line; 1c a semicolon closing the
# last entry, a reason that holds '1c' and ':'
def test_parse_tag_syntax():
    tag, errs = vc.parse_tag("/* text\n * Methods: 1b the classes;\n *   1c the ends\n */", 7)
    assert errs == [] and tag == {"line": 8, "methods": {"1b": "the classes", "1c": "the ends"}}
    tag, errs = vc.parse_tag("# Methods: 1d x: y 1c z;\n#\n# 1n not part of it", 3)
    assert errs == [] and tag["methods"] == {"1d": "x: y 1c z"}
    tag, errs = vc.parse_tag("/* Methods: 1n a twin */", 1)
    assert errs == [] and tag["methods"] == {"1n": "a twin"}
    tag, errs = vc.parse_tag("Doc.\n\nMethods: 1a REQ by hand\nsecond line.\n\nMore.", 10)
    assert errs == [] and tag == {"line": 12, "methods": {"1a": "REQ by hand second line."}}
    assert vc.parse_tag("/* no tag here: the methods are elsewhere */", 1) == (None, [])


# REQ-EVD-007: --check passes on a fresh section and names the suite and figure of a stale one.
# Methods: 1b a figure edited by hand, a case added to the sources, a suite removed; 1d a
# stale section
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
        "        cmocka_unit_test(helper_case),\n") + "\n/* Methods: 1b one more */\n"
        "static void helper_case(void **state)\n{\n    (void)state;\n}\n", encoding="utf-8")
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
# Methods: 1d a specification without the markers (exit status 2)
def test_missing_markers_exit_2(tmp_path, capsys):
    spec = make_tree(tmp_path)
    spec.write_text("# no markers\n", encoding="utf-8")
    assert vc.main(["--root", str(tmp_path), "--check"]) == 2
    assert "has no section" in capsys.readouterr().err


# REQ-EVD-007: every case of this repository has a valid tag and the committed section of
# specs/verification-spec.md matches the tags.
# Methods: 1a the repository's own tags and section, checked as make trace checks them
def test_repository_check_passes(capsys):
    assert vc.main(["--root", str(REPO), "--check"]) == 0
    assert "up to date" in capsys.readouterr().out


# REQ-EVD-007: every CMocka registration of tests/ is counted, and every CBMC folder.
# Methods: 1n the registrations and harness folders counted independently in the test
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
