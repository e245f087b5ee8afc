"""Tests of tools/evidence/arch_check.py (run: python3 -m pytest tools/evidence/tests).

The check runs on the repository itself (it must pass) and on copies of the parts it reads
(include/, src/, specs/, port_s32k/) in a temporary directory, each changed in one way that
the architecture description must catch: a function renamed in the code, a module removed
or added, a public function added to a header, an unknown requirement ID cited, an
include that the dependency table does not list.  Each must fail with the name in the
message.
"""
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

CHECK = Path(__file__).resolve().parent.parent / "arch_check.py"
ROOT = CHECK.parent.parent.parent
DOC = "specs/architecture.md"
# Requirement IDs of the made-up cases, built so that the trace gate does not read them as
# IDs named by this file.
UNKNOWN_ID = "REQ-" + "SM-" + "999"
SUMMARY = re.compile(r"^arch-check: (\d+) functions, (\d+) modules, (\d+) requirements named, "
                     r"all present$")


def run(root):
    proc = subprocess.run([sys.executable, str(CHECK), "--root", str(root)],
                          capture_output=True, text=True, check=False)
    return proc.returncode, proc.stdout + proc.stderr


def named(text, name):
    """The name appears as a whole word (qfoc_ramp_to is not qfoc_ramp_toward)."""
    return re.search(r"(?<![\w/])" + re.escape(name) + r"(?![\w])", text) is not None


def edit(path, old, new, count=None):
    text = path.read_text(encoding="utf-8")
    assert old in text, f"{old!r} not in {path}"
    if count is not None:
        assert text.count(old) == count, f"{old!r} {text.count(old)} times in {path}"
    path.write_text(text.replace(old, new), encoding="utf-8")


@pytest.fixture
def tree(tmp_path):
    """A copy of what the check reads."""
    for part in ("include", "src", "specs", "port_s32k", "proofs"):
        shutil.copytree(ROOT / part, tmp_path / part,
                        ignore=shutil.ignore_patterns("__pycache__", "*.o"))
    rc, out = run(tmp_path)
    assert rc == 0, out
    return tmp_path


# REQ-EVD-014
# Methods: 1a the architecture of specs/architecture.md against this repository's sources: every
# public function and module named, one summary line
def test_repository_passes():
    rc, out = run(ROOT)
    assert rc == 0, out
    lines = out.strip().splitlines()
    assert len(lines) == 1, out
    m = SUMMARY.match(lines[0])
    assert m, out
    functions, modules, reqs = (int(g) for g in m.groups())
    # every public function is named, every src/*.c module too
    assert functions >= 145 and modules >= len(list((ROOT / "src").glob("*.c"))) and reqs > 0


# REQ-EVD-014
# Methods: 1a the check run from another directory finds this repository
def test_default_root_is_the_repository():
    proc = subprocess.run([sys.executable, str(CHECK)], capture_output=True, text=True,
                          check=False, cwd=str(Path("/")))
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert SUMMARY.match(proc.stdout.strip())


# REQ-EVD-014
# Methods: 1d a public function renamed in the code and not in the document; 1l the rename
# injected into a copy of the tree
def test_renamed_function_fails(tree):
    # qfoc_ramp_toward renamed in the code, not in the document
    for f in ("include/qfoc/ramp.h", "src/qfoc_ramp.c", "src/qfoc_drive.c"):
        edit(tree / f, "qfoc_ramp_toward", "qfoc_ramp_approach")
    rc, out = run(tree)
    assert rc == 1
    # the old name is reported with where the document mentions it
    old = [ln for ln in out.splitlines() if named(ln, "qfoc_ramp_toward")]
    assert old and all(f"{DOC} line" in ln for ln in old), out
    # and the new public name is missing from the interface section
    assert any(named(ln, "qfoc_ramp_approach") and "interface section" in ln
               for ln in out.splitlines()), out
    assert out.strip().splitlines()[-1].startswith("arch-check: ")
    assert "problem" in out.strip().splitlines()[-1]


# REQ-EVD-014
# Methods: 1d a module the document names that no longer exists; 1l the module removed from a
# copy of the tree
def test_missing_module_fails(tree):
    # a module the document names no longer exists
    os.remove(tree / "src/qfoc_ramp.c")
    rc, out = run(tree)
    assert rc == 1
    assert any(named(ln, "src/qfoc_ramp.c") and "does not exist" in ln
               for ln in out.splitlines()), out


# REQ-EVD-014
# Methods: 1d a new module of src/ the document does not describe; 1l the module added to a copy
# of the tree
def test_undescribed_module_fails(tree):
    # a new module of src/ that the document does not describe
    (tree / "src/qfoc_extra.c").write_text(
        '#include "qfoc/types.h"\n\nbool qfoc_extra_ok(void)\n{\n    return true;\n}\n',
        encoding="utf-8")
    rc, out = run(tree)
    assert rc == 1
    assert any(named(ln, "src/qfoc_extra.c") and "not described" in ln
               for ln in out.splitlines()), out
    assert any(named(ln, "src/qfoc_extra.c") and "no row" in ln
               for ln in out.splitlines()), out


# REQ-EVD-014
# Methods: 1d a public prototype added to a header and not to the interface section; 1l the
# prototype added to a copy of the tree
def test_undocumented_public_function_fails(tree):
    # a public function added to a header, not to the interface section
    edit(tree / "include/qfoc/sm.h", "#endif /* QFOC_SM_H */",
         "bool qfoc_sm_is_stopped(const qfoc_sm_t *sm);\n\n#endif /* QFOC_SM_H */", count=1)
    rc, out = run(tree)
    assert rc == 1
    assert any(named(ln, "qfoc_sm_is_stopped") and "include/qfoc/sm.h" in ln
               and "interface section" in ln for ln in out.splitlines()), out


# REQ-EVD-014
# Methods: 1d a requirement ID in the document that no requirement defines, reported with its
# line; 1l the ID appended to a copy of the document
def test_unknown_requirement_fails(tree):
    doc = tree / DOC
    text = doc.read_text(encoding="utf-8")
    doc.write_text(text + f"\nThe stop rule is {UNKNOWN_ID}.\n", encoding="utf-8")
    line = len(text.splitlines()) + 2
    rc, out = run(tree)
    assert rc == 1
    hits = [ln for ln in out.splitlines() if named(ln, UNKNOWN_ID)]
    assert hits and f"{DOC} line {line}" in hits[0], out


# REQ-EVD-014
# Methods: 1d a function named as a call in the document that nothing defines; 1l the name
# changed in a copy of the document
def test_unknown_function_in_document_fails(tree):
    # a name written as a call that nothing defines (a static helper renamed away)
    edit(tree / DOC, "`drv_measure()`", "`drv_sample()`")
    rc, out = run(tree)
    assert rc == 1
    assert any(named(ln, "drv_sample") for ln in out.splitlines()), out


# REQ-EVD-014
# Methods: 1d an include the dependency table does not list; 1l the include added to a copy of
# src/qfoc_sm.c
def test_dependency_table_follows_the_includes(tree):
    edit(tree / "src/qfoc_sm.c", '#include "qfoc/sm.h"\n',
         '#include "qfoc/sm.h"\n#include "qfoc/trig.h"\n', count=1)
    rc, out = run(tree)
    assert rc == 1
    assert any("src/qfoc_sm.c" in ln and "qfoc/trig.h" in ln and "includes" in ln
               for ln in out.splitlines()), out


# REQ-EVD-014
# Methods: 1d a call into another module the dependency table does not list; 1l the call added
# to a copy of src/qfoc_sm.c
def test_dependency_table_follows_the_calls(tree):
    # the state machine starts to call a primitive of another module
    edit(tree / "src/qfoc_sm.c", '#include "qfoc/sm.h"\n',
         '#include "qfoc/sm.h"\n#include "qfoc/ramp.h"\n', count=1)
    with open(tree / "src/qfoc_sm.c", "a", encoding="utf-8") as f:
        f.write("\nqfoc_q15_t qfoc_sm_ramp(void)\n{\n    return qfoc_ramp_toward(0, 1, 1);\n}\n")
    rc, out = run(tree)
    assert rc == 1
    assert any("src/qfoc_sm.c" in ln and "calls into" in ln and "qfoc_ramp.c" in ln
               for ln in out.splitlines()), out


# REQ-EVD-014
# Methods: 1d the interface section renamed away; 1l the heading changed in a copy of the
# document
def test_missing_interface_section_fails(tree):
    edit(tree / DOC, "## 3. Interfaces", "## 3. Calls", count=1)
    rc, out = run(tree)
    assert rc == 1
    assert "no level-2 section 'Interfaces'" in out, out
