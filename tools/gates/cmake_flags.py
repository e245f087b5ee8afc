#!/usr/bin/env python3
"""Compare the compile flags of a CMake build of qfoc with the Makefile's (make cmake-check).

usage: cmake_flags.py COMPILE_COMMANDS.json SOURCE_DIR NAME 'MAKE FLAGS'

Reads the compile command of every src/*.c of SOURCE_DIR from CMake's compile_commands.json
(CMAKE_EXPORT_COMPILE_COMMANDS) and keeps its flags: the command without the compiler,
'-o FILE', '-c' and the source file, with '-I<SOURCE_DIR>/dir' written '-Idir' as the
Makefile writes it.  Each source's flags must be the Makefile's ('MAKE FLAGS', e.g. the
output of make print-arm-cflags) as a multiset: the same flags, each as many times; the
order may differ.  Every src/*.c must have a command.  Prints one line; exit 1 when a
source is missing or its flags differ (the differences listed).
"""
import collections
import glob
import json
import os
import shlex
import sys


def flags_of(entry, src_dir):
    args = entry.get("arguments") or shlex.split(entry["command"])
    out = []
    skip = False
    for a in args[1:]:
        if skip:
            skip = False
            continue
        if a == "-o":
            skip = True
            continue
        if a == "-c" or os.path.abspath(os.path.join(entry["directory"], a)) == entry["file"]:
            continue
        if a.startswith("-I"):
            path = os.path.abspath(os.path.join(entry["directory"], a[2:]))
            rel = os.path.relpath(path, src_dir)
            a = "-I" + (rel if not rel.startswith("..") else path)
        out.append(a)
    return out


def main():
    if len(sys.argv) != 5:
        sys.exit(__doc__)
    cc_json, src_dir, name, make_flags = sys.argv[1:]
    src_dir = os.path.abspath(src_dir)
    want = shlex.split(make_flags)
    with open(cc_json, encoding="utf-8") as f:
        entries = {os.path.abspath(os.path.join(e["directory"], e["file"])): e for e in json.load(f)}
    sources = sorted(glob.glob(os.path.join(src_dir, "src", "*.c")))
    bad = []
    for s in sources:
        e = entries.get(s)
        if e is None:
            bad.append(f"{os.path.relpath(s, src_dir)}: no compile command")
            continue
        got = flags_of(e, src_dir)
        if collections.Counter(got) != collections.Counter(want):
            extra = sorted((collections.Counter(got) - collections.Counter(want)).elements())
            missing = sorted((collections.Counter(want) - collections.Counter(got)).elements())
            bad.append(f"{os.path.relpath(s, src_dir)}: CMake adds {extra or 'nothing'}, "
                       f"lacks {missing or 'nothing'}")
    if bad:
        print(f"cmake-check: {name}: compile flags differ from the Makefile's:")
        for b in bad:
            print("  " + b)
        return 1
    print(f"cmake-check: {name}: the compile flags of all {len(sources)} sources equal the "
          f"Makefile's: {' '.join(want)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
