#!/usr/bin/env python3
"""The committed store of WP's prover results (proofs/wp/cache.txt; REQ-EVD-032).

usage: wp_cache.py unpack PACK DIR
       wp_cache.py pack DIR PACK --mode full|update --run UTC [--sources FILE]
       wp_cache.py pick JOBS_FILE SEED
       wp_cache.py sources
       wp_cache.py full-check PACK

Frama-C WP can keep the result of every prover call in a cache directory
(-wp-cache, -wp-cache-dir): one JSON file per call, named by a digest of the goal
exactly as it was sent to the prover (the Why3 task printed by the prover's driver)
together with the prover and its version.  A goal whose text changes in any way -- a
contract, the code, a lemma it uses, the Frama-C or Why3 version that generated it --
has another digest and is proved again.  WP still parses every unit, generates every
goal and runs Qed on it in every run; only the prover call of a goal it has already
seen proved is replaced by the recorded verdict.

The pack is that directory as one sorted text file, one call a line:
    <digest> <the record that WP wrote, on one line>
so that a change of the sources changes only the lines of the goals it changed.

  unpack  writes PACK's entries into DIR as WP's JSON files;
  pack    writes DIR's entries into PACK, with a header naming how they were made:
          'full' (every goal proved by a prover, no entry read: make prove-full), which
          replaces the pack, or 'update' (a run that read the pack), which adds the new
          entries to those already there;
  pick    prints the job of JOBS_FILE that a run proves without the cache, chosen
          from SEED (a hex string: the commit), so that each commit re-proves one job
          from scratch and over many commits every job is proved again;
  sources prints what the goals are made of: the SHA-256 of every source, header, ACSL
          file and proof driver that make prove reads (tools/evidence/inputs.py's wp
          inputs without the tool scripts and the store itself), the WP flags and the
          versions of Frama-C, Why3 and the provers, one line each; a full run records
          them (pack --sources, written by prove.sh when the run starts) in the header;
  full-check
          compares that record with the tree: exit 0 when the last full run proved these
          very sources with these tools, else 1 with every difference named (make release
          refuses the tree then: tools/release/release_ready.py).  An update run keeps the
          record as it was, so a replay run that added entries for changed sources leaves
          the store "not re-proved in full over these sources".
"""
import os
import re
import sys

DIGEST = re.compile(r"^[0-9a-f]{32}$")
HERE = os.path.dirname(os.path.abspath(__file__))
TOP = os.path.dirname(os.path.dirname(HERE))
# the lines of the header that record what the last full run proved
REC = "# full run over: "
# wp inputs that do not make goals: the scripts that run WP and report, and the store
NOT_SOURCES = ("tools/", "proofs/wp/cache.txt")


def fail(msg):
    sys.exit(f"wp_cache: {msg}")


def check_entry(where, digest, body):
    """An entry as WP wrote it: one line of its own JSON-like record (WP prints floats as
    OCaml does, e.g. "2.", so it is kept as text, not re-encoded)."""
    if not DIGEST.match(digest):
        fail(f"{where}: '{digest}' is not a goal digest (32 hex digits)")
    if not (body.startswith("{") and body.endswith("}")):
        fail(f"{where}: the entry of {digest} is not a record: '{body}'")
    if '"prover"' not in body or '"verdict"' not in body:
        fail(f"{where}: the entry of {digest} names no prover or verdict: '{body}'")
    return body


def read_pack(path):
    entries, header = {}, []
    if not os.path.exists(path):
        return entries, header
    with open(path, encoding="utf-8") as f:
        for n, line in enumerate(f, 1):
            line = line.rstrip("\n")
            if line.startswith("#"):
                header.append(line)
                continue
            if not line:
                continue
            digest, _, body = line.partition(" ")
            entries[digest] = check_entry(f"{path}:{n}", digest, body.strip())
    return entries, header


def read_dir(path):
    entries = {}
    for name in sorted(os.listdir(path)):
        digest = name[:-5]
        if not name.endswith(".json") or not DIGEST.match(digest):
            continue
        with open(os.path.join(path, name), encoding="utf-8") as f:
            body = " ".join(f.read().split())
        entries[digest] = check_entry(f"{path}/{name}", digest, body)
    return entries


def unpack(pack, outdir):
    entries, _ = read_pack(pack)
    os.makedirs(outdir, exist_ok=True)
    for digest, body in entries.items():
        with open(os.path.join(outdir, digest + ".json"), "w", encoding="utf-8") as f:
            f.write(body + "\n")
    print(f"{len(entries)}")


def sources(root=TOP):
    """The lines that say what WP's goals are made of (see `sources` above)."""
    sys.path.insert(0, os.path.join(root, "tools", "evidence"))
    import inputs as inp  # noqa: E402  (tools/evidence/inputs.py)
    paths = [p for p in inp.files("wp", root) if not p.startswith(NOT_SOURCES)]
    lines = [f"flags {inp.flags('wp')}"]
    lines += [f"tool {t}" for t in inp.tools("wp", root)]
    lines += [f"file {h} {p}" for p, h in sorted(inp.hashes_of(paths, root).items())]
    return lines


def read_sources(path):
    with open(path, encoding="utf-8") as f:
        lines = [ln.rstrip("\n") for ln in f if ln.strip()]
    if not any(ln.startswith("file ") for ln in lines):
        fail(f"{path} names no source file: not written by 'wp_cache.py sources'")
    return lines


def pack_dir(outdir, pack, mode, run, source_file=None):
    new = read_dir(outdir)
    old, header = read_pack(pack)
    if mode == "full":
        if source_file is None:
            fail("a full run's pack needs --sources (what the run proved)")
        entries = new
        header = [f"# last full run (make prove-full, no entry read): {run}, {len(new)} prover calls"]
        header += [REC + ln for ln in read_sources(source_file)]
    else:
        entries = dict(old)
        added = {d: o for d, o in new.items() if d not in old}
        entries.update(added)
        header = [h for h in header if h.startswith(("# last full run", REC))]
        header.append(f"# updated by the replay run of {run}: +{len(added)} prover calls")
    head = ["# proofs/wp/cache.txt -- Frama-C WP's prover results, one prover call a line:",
            "# <digest of the goal as sent to the prover> <WP's record of the call>.",
            "# Written by tools/gates/prove.sh (tools/gates/wp_cache.py); read by make prove."]
    with open(pack, "w", encoding="utf-8") as f:
        for h in head + header:
            f.write(h + "\n")
        for digest in sorted(entries):
            f.write(digest + " " + entries[digest] + "\n")
    print(f"{len(entries)}")


def pick(jobs_file, seed):
    with open(jobs_file, encoding="utf-8") as f:
        jobs = sorted(line.split()[0] for line in f if len(line.split()) == 4
                      and line.split()[3] != "-")
    if not jobs:
        return
    if not re.fullmatch(r"[0-9a-fA-F]+", seed or ""):
        fail(f"the seed '{seed}' is not a hex string")
    print(jobs[int(seed[:12], 16) % len(jobs)])


def full_check(pack, root=TOP):
    """[] when the last full run recorded in PACK proved the tree's sources with the
    tools installed now, else the differences, one line each."""
    if not os.path.exists(pack):
        return [f"{pack} does not exist: no prover result is recorded (make prove-full)"]
    _, header = read_pack(pack)
    rec = [h[len(REC):] for h in header if h.startswith(REC)]
    if not rec:
        return [f"{pack} records no full run over named sources (make prove-full writes it)"]
    now = sources(root)
    out = []
    files_rec = {ln.split(" ", 2)[2]: ln.split(" ", 2)[1] for ln in rec if ln.startswith("file ")}
    files_now = {ln.split(" ", 2)[2]: ln.split(" ", 2)[1] for ln in now if ln.startswith("file ")}
    for p in sorted(set(files_rec) | set(files_now)):
        if p not in files_now:
            out.append(f"{p}: proved in the last full run, not in the tree now")
        elif p not in files_rec:
            out.append(f"{p}: in the tree, not proved in the last full run")
        elif files_rec[p] != files_now[p]:
            out.append(f"{p}: changed since the last full run")
    for kind in ("flags", "tool"):
        was = [ln for ln in rec if ln.startswith(kind + " ")]
        is_ = [ln for ln in now if ln.startswith(kind + " ")]
        if was != is_:
            out.append(f"{kind}: the last full run had '{'; '.join(was)}', the tree has "
                       f"'{'; '.join(is_)}'")
    return out


def main(argv):
    if len(argv) == 3 and argv[0] == "unpack":
        unpack(argv[1], argv[2])
    elif len(argv) in (7, 9) and argv[0] == "pack" and argv[3] == "--mode" \
            and argv[4] in ("full", "update") and argv[5] == "--run" \
            and (len(argv) == 7 or argv[7] == "--sources"):
        pack_dir(argv[1], argv[2], argv[4], argv[6], argv[8] if len(argv) == 9 else None)
    elif len(argv) == 3 and argv[0] == "pick":
        pick(argv[1], argv[2])
    elif len(argv) == 1 and argv[0] == "sources":
        print("\n".join(sources()))
    elif len(argv) == 2 and argv[0] == "full-check":
        diff = full_check(argv[1])
        if diff:
            print(f"wp_cache: the prover results in {argv[1]} were not all proved by one full "
                  f"run over the sources and tools of this tree ({len(diff)} difference"
                  f"{'s' if len(diff) != 1 else ''}):")
            for d in diff[:40]:
                print(f"  {d}")
            if len(diff) > 40:
                print(f"  ... and {len(diff) - 40} more")
            return 1
        print(f"wp_cache: {argv[1]}: the last full run proved the sources and tools of this tree")
    else:
        fail("usage: unpack PACK DIR | pack DIR PACK --mode full|update --run UTC "
             "[--sources FILE] | pick JOBS_FILE SEED | sources | full-check PACK")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
