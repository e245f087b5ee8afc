"""Tests of tools/gates/wp_cache.py, the store of WP's prover results (run: python3 -m pytest
tools/evidence/tests).

The store is read back entry for entry; a malformed line is refused with its file, line and
text; an update keeps what was there and adds only new entries; the job proved without the
store is a job of the plan, the same for the same commit.  The last cases run Frama-C WP on
a made-up unit: a goal proved once is replayed from the store, and a goal whose text
changed, here a contract that no longer holds, is sent to the prover and fails, whatever
the store holds.
Requirement: REQ-EVD-032 (prover results replayed only for the same goal).
"""
import json
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parent.parent.parent.parent
TOOL = REPO / "tools" / "gates" / "wp_cache.py"

A = "0" * 31 + "a"
B = "0" * 31 + "b"


def run(*args):
    return subprocess.run([sys.executable, str(TOOL), *map(str, args)], capture_output=True,
                          text=True, check=False)


def sources_file(tmp_path):
    """A full run's record of its sources, in the form `wp_cache.py sources` prints."""
    f = tmp_path / "sources.txt"
    f.write_text("flags -wp\ntool frama-c: 25.0\nfile " + "1" * 64 + " include/qfoc/q15.h\n",
                 encoding="utf-8")
    return f


def write_entry(d, digest, obj):
    d.mkdir(parents=True, exist_ok=True)
    (d / (digest + ".json")).write_text(json.dumps(obj), encoding="utf-8")


def test_wp_cache_pack_unpack_round_trip(tmp_path):
    """REQ-EVD-032: the entries WP wrote come back, field for field, after a pack and an
    unpack, WP's own float format ("2.", not JSON) included; the pack is sorted, one entry a
    line, with the header of a full run.
    Methods: 1b the store's format; 1c an entry with every field WP writes, a float as WP
    prints it"""
    src = tmp_path / "src"
    (src).mkdir()
    (src / (("0" * 31) + "c.json")).write_text(
        '{ "prover": "Z3:4.8.12", "verdict": "valid", "time": 2., "steps": 2404443 }\n',
        encoding="utf-8")
    write_entry(src, B, {"prover": "CVC4:1.8", "verdict": "timeout", "time": 120.0})
    write_entry(src, A, {"prover": "Z3:4.8.12", "verdict": "valid", "time": 0.05, "steps": 64917})
    pack = tmp_path / "cache.txt"
    r = run("pack", src, pack, "--mode", "full", "--run", "2026-12-07 22:00:00 UTC",
            "--sources", sources_file(tmp_path))
    assert r.returncode == 0, r.stderr
    assert r.stdout.strip() == "3"
    lines = [x for x in pack.read_text(encoding="utf-8").splitlines() if not x.startswith("#")]
    assert [x.split()[0] for x in lines] == [A, B, "0" * 31 + "c"]
    assert "last full run (make prove-full, no entry read): 2026-12-07 22:00:00 UTC, 3 prover calls" \
        in pack.read_text(encoding="utf-8")
    out = tmp_path / "out"
    r = run("unpack", pack, out)
    assert r.returncode == 0 and r.stdout.strip() == "3"
    assert (out / ("0" * 31 + "c.json")).read_text(encoding="utf-8") == \
        '{ "prover": "Z3:4.8.12", "verdict": "valid", "time": 2., "steps": 2404443 }\n'
    assert json.loads((out / (A + ".json")).read_text()) == \
        {"prover": "Z3:4.8.12", "verdict": "valid", "time": 0.05, "steps": 64917}
    assert json.loads((out / (B + ".json")).read_text())["verdict"] == "timeout"


def test_wp_cache_update_adds_and_keeps(tmp_path):
    """REQ-EVD-032: an update keeps every entry of the store and the full run's header, and
    adds only the entries it did not hold; a full run replaces the store.
    Methods: 1b the two modes of the pack"""
    pack = tmp_path / "cache.txt"
    first = tmp_path / "first"
    write_entry(first, A, {"prover": "Z3:4.8.12", "verdict": "valid", "time": 0.1})
    srcs = sources_file(tmp_path)
    assert run("pack", first, pack, "--mode", "full", "--run", "T1", "--sources", srcs).returncode == 0
    second = tmp_path / "second"
    write_entry(second, B, {"prover": "Z3:4.8.12", "verdict": "valid", "time": 0.2})
    r = run("pack", second, pack, "--mode", "update", "--run", "T2")
    assert r.returncode == 0 and r.stdout.strip() == "2"
    text = pack.read_text(encoding="utf-8")
    assert "full run (make prove-full, no entry read): T1" in text
    assert "updated by the replay run of T2: +1 prover calls" in text
    assert "# full run over: file " + "1" * 64 + " include/qfoc/q15.h" in text
    r = run("pack", second, pack, "--mode", "full", "--run", "T3")
    assert r.returncode != 0 and "a full run's pack needs --sources" in r.stderr
    r = run("pack", second, pack, "--mode", "full", "--run", "T3", "--sources", srcs)
    assert r.returncode == 0 and r.stdout.strip() == "1"
    assert A not in pack.read_text(encoding="utf-8")


def test_wp_cache_full_check_names_what_changed(tmp_path):
    """REQ-EVD-032: the store of a full run over this tree's sources passes full-check; a
    source changed since, a store without the record, and an update run over changed sources
    fail it, each difference named (make release refuses such a tree).
    Methods: 1b the record a full run writes; 1c a changed file, no record, an update"""
    srcs = tmp_path / "sources.txt"
    r = run("sources")
    assert r.returncode == 0, r.stderr
    srcs.write_text(r.stdout, encoding="utf-8")
    assert "file " in r.stdout and "include/qfoc/q15.h" in r.stdout and "src/qfoc_pi.c" in r.stdout
    named = [x.split()[2] for x in r.stdout.splitlines() if x.startswith("file ")]
    assert not [x for x in named if x.startswith("tools/") or x == "proofs/wp/cache.txt"]
    d = tmp_path / "d"
    write_entry(d, A, {"prover": "Z3:4.8.12", "verdict": "valid", "time": 0.1})
    pack = tmp_path / "cache.txt"
    assert run("pack", d, pack, "--mode", "full", "--run", "T", "--sources", srcs).returncode == 0
    r = run("full-check", pack)
    assert r.returncode == 0 and "the last full run proved the sources and tools of this tree" \
        in r.stdout, r.stdout
    # the record of one source as if it had been another text
    text = pack.read_text(encoding="utf-8")
    line = next(x for x in text.splitlines() if x.endswith(" src/qfoc_pi.c"))
    pack.write_text(text.replace(line, line.split()[0] + " full run over: file " + "0" * 64
                                 + " src/qfoc_pi.c"), encoding="utf-8")
    r = run("full-check", pack)
    assert r.returncode == 1 and "(1 difference)" in r.stdout \
        and "src/qfoc_pi.c: changed since the last full run" in r.stdout, r.stdout
    # an update run keeps the old record: still not a full run over this tree
    e = tmp_path / "e"
    write_entry(e, B, {"prover": "Z3:4.8.12", "verdict": "valid", "time": 0.1})
    assert run("pack", e, pack, "--mode", "update", "--run", "T2").returncode == 0
    r = run("full-check", pack)
    assert r.returncode == 1 and "src/qfoc_pi.c: changed since the last full run" in r.stdout
    # no record at all
    pack.write_text("# header\n" + A + ' { "prover": "Z3:4.8.12", "verdict": "valid" }\n',
                    encoding="utf-8")
    r = run("full-check", pack)
    assert r.returncode == 1 and "records no full run over named sources" in r.stdout


@pytest.mark.parametrize("line,expect", [
    ("xyz {}", "'xyz' is not a goal digest"),
    (A + " {not a record", "is not a record: '{not a record'"),
    (A + ' {"verdict": "valid"}', "names no prover or verdict"),
])
def test_wp_cache_refuses_malformed_store(tmp_path, line, expect):
    """REQ-EVD-032: a malformed line of the store stops the unpack with the file, the line
    number and what it holds; nothing is written.
    Methods: 1c a digest, an entry and a field each malformed"""
    pack = tmp_path / "cache.txt"
    pack.write_text("# header\n" + line + "\n", encoding="utf-8")
    out = tmp_path / "out"
    r = run("unpack", pack, out)
    assert r.returncode != 0
    assert f"{pack}:2:" in r.stderr and expect in r.stderr
    assert not out.exists() or not list(out.iterdir())


def test_wp_cache_pick_is_a_job_of_the_plan(tmp_path):
    """REQ-EVD-032: the job proved without the store is one of the plan's jobs with
    functions (a data-only unit proves nothing), the same for the same commit, and the
    commits reach every job.
    Methods: 1b the choice over 64 made-up commits; 1c a seed that is not hex"""
    jobs = tmp_path / "jobs.txt"
    jobs.write_text("qfoc_a@1 src/a.c z3,cvc4 f,g\nqfoc_b src/b.c cvc4,z3 h\n"
                    "qfoc_c src/c.c z3,cvc4 -\n", encoding="utf-8")
    seen = set()
    for k in range(64):
        seed = f"{k * 2654435761 % (1 << 40):010x}"
        a = run("pick", jobs, seed).stdout.strip()
        assert a == run("pick", jobs, seed).stdout.strip()
        seen.add(a)
    assert seen == {"qfoc_a@1", "qfoc_b"}
    r = run("pick", jobs, "HEAD")
    assert r.returncode != 0 and "the seed 'HEAD' is not a hex string" in r.stderr


UNIT = """/*@ requires 0 <= x <= LIMIT && 0 <= y <= LIMIT;
    assigns \\nothing;
    ensures \\result == x * y; */
int mul(int x, int y) { return x * y; }
"""


def proved(out):
    m = re.search(r"Proved goals:\s+(\d+) / (\d+)", out)
    assert m, out
    return int(m.group(1)), int(m.group(2))


def wp(unit, cache, mode):
    return subprocess.run(["frama-c", str(unit), "-wp", "-wp-rte", "-warn-signed-overflow",
                           "-wp-prover", "z3", "-wp-par", "1", "-wp-timeout", "10",
                           f"-wp-cache={mode}", f"-wp-cache-dir={cache}"],
                          capture_output=True, text=True, check=False).stdout


@pytest.mark.skipif(shutil.which("frama-c") is None, reason="frama-c not installed (make deps)")
def test_wp_cache_replays_only_the_same_goal(tmp_path):
    """REQ-EVD-032: Frama-C WP with the store: a goal proved once is replayed (WP marks it
    cached, no prover call); the unit changed so that the product can overflow, the
    overflow goal is new, goes to the prover and is not proved, with the store unchanged
    and packed and unpacked as make prove does.
    Methods: 1b the store in WP's own run; 1c a contract changed to one that does not hold"""
    unit = tmp_path / "m.c"
    unit.write_text(UNIT.replace("LIMIT", "1000"), encoding="utf-8")
    cache = tmp_path / "cache"
    cache.mkdir()
    first = wp(unit, cache, "rebuild")
    assert proved(first) == (4, 4)
    assert "(cached)" not in first and "[Cache] updated:2" in first
    pack = tmp_path / "cache.txt"
    assert run("pack", cache, pack, "--mode", "full", "--run", "T",
               "--sources", sources_file(tmp_path)).returncode == 0
    replay = tmp_path / "replay"
    assert run("unpack", pack, replay).returncode == 0
    again = wp(unit, replay, "update")
    assert proved(again) == (4, 4)
    assert "[Cache] found:2" in again
    assert len([x for x in again.splitlines() if x.endswith("(cached)")]) == 2
    unit.write_text(UNIT.replace("LIMIT", "100000"), encoding="utf-8")
    changed = wp(unit, replay, "update")
    overflow = [x for x in changed.splitlines() if "rte_signed_overflow" in x]
    # both overflow goals changed text: neither is replayed; the upper bound fails
    assert len(overflow) == 2 and not any(x.endswith("(cached)") for x in overflow)
    assert any(x.endswith(": Failed") or ": Timeout" in x or ": Unknown" in x for x in overflow)
    assert proved(changed)[0] < 4
