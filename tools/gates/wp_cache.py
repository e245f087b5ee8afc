#!/usr/bin/env python3
"""The committed store of WP's prover results (proofs/wp/cache.txt; REQ-EVD-032).

usage: wp_cache.py unpack PACK DIR
       wp_cache.py pack DIR PACK --mode full|update --run UTC
       wp_cache.py pick JOBS_FILE SEED

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
"""
import os
import re
import sys

DIGEST = re.compile(r"^[0-9a-f]{32}$")


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


def pack_dir(outdir, pack, mode, run):
    new = read_dir(outdir)
    old, header = read_pack(pack)
    if mode == "full":
        entries = new
        header = [f"# last full run (make prove-full, no entry read): {run}, {len(new)} prover calls"]
    else:
        entries = dict(old)
        added = {d: o for d, o in new.items() if d not in old}
        entries.update(added)
        header = [h for h in header if h.startswith("# last full run")]
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


def main(argv):
    if len(argv) == 3 and argv[0] == "unpack":
        unpack(argv[1], argv[2])
    elif len(argv) == 7 and argv[0] == "pack" and argv[3] == "--mode" \
            and argv[4] in ("full", "update") and argv[5] == "--run":
        pack_dir(argv[1], argv[2], argv[4], argv[6])
    elif len(argv) == 3 and argv[0] == "pick":
        pick(argv[1], argv[2])
    else:
        fail("usage: unpack PACK DIR | pack DIR PACK --mode full|update --run UTC | "
             "pick JOBS_FILE SEED")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
