"""Worst-case stack depth from gcc's -fstack-usage (.su) and -fcallgraph-info=su (.ci) files.

Each object compiled with both options leaves NAME.su (one line per function: location,
frame bytes, qualifier static / dynamic / dynamic,bounded) and NAME.ci (a VCG graph: one
node per function defined in the unit, labelled with its frame, one ellipse node per
function it calls that is defined elsewhere, one edge per call site).  The frame of a
function is what its prologue reserves, saved registers and the return address included
(the Cortex-M has no separate return-address push), so the depth of a call chain is the
sum of its frames.

worst(f) = frame(f) + max over callees c of worst(c), over the whole program's graph
(a static function's node is named "file:function", a global one by its name).  A call
to a function no .ci defines (a C library function, a function pointer) and a cycle
(recursion) make the result unbounded; a dynamic frame (alloca, VLA) is flagged, and
its size is the fixed part only.
"""
import glob
import os
import re

_NODE = re.compile(r'node:\s*\{\s*title:\s*"([^"]+)"\s*label:\s*"([^"]*)"(.*)\}')
_EDGE = re.compile(r'edge:\s*\{\s*sourcename:\s*"([^"]+)"\s*targetname:\s*"([^"]+)"')
_FRAME = re.compile(r"\\n(\d+) bytes \(([a-z,]+)\)")


def load(obj_dir):
    """Read every .ci file of obj_dir: frames {node: (bytes, qualifier, label)} and
    calls {node: [callee nodes]}, with the .su lines cross-checked."""
    frames = {}
    calls = {}
    for ci in sorted(glob.glob(os.path.join(obj_dir, "*.ci"))):
        with open(ci, encoding="utf-8") as f:
            for line in f:
                m = _NODE.search(line)
                if m:
                    title, label = m.group(1), m.group(2)
                    fm = _FRAME.search(label)
                    if fm:
                        frames[title] = (int(fm.group(1)), fm.group(2), label.split("\\n")[0])
                    continue
                m = _EDGE.search(line)
                if m:
                    calls.setdefault(m.group(1), []).append(m.group(2))
    su_funcs = {}
    for su in sorted(glob.glob(os.path.join(obj_dir, "*.su"))):
        with open(su, encoding="utf-8") as f:
            for line in f:
                parts = line.rstrip("\n").split("\t")
                if len(parts) == 3:
                    su_funcs[parts[0]] = (int(parts[1]), parts[2])
    return frames, calls, su_funcs


def analyse(obj_dir, entries):
    """Worst-case depth of each entry point.

    Returns {entry: {"bytes": int, "path": [(function, frame), ...], "bounded": bool,
    "dynamic": [functions with a dynamic frame on any path], "unknown": [callees without a
    frame], "recursion": [cycles]}}.
    """
    frames, calls, _ = load(obj_dir)
    memo = {}
    result = {}

    def worst(node, stack):
        # returns (depth, path, unknown set, dynamic set, cycles list)
        if node in memo:
            return memo[node]
        if node in stack:
            return (0, [], set(), set(), [stack[stack.index(node):] + [node]])
        if node not in frames:
            return (0, [(node, None)], {node}, set(), [])
        size, qual, _ = frames[node]
        best = (0, [], set(), set(), [])
        unknown = set()
        dynamic = {node} if qual.startswith("dynamic") else set()
        cycles = []
        for callee in sorted(set(calls.get(node, []))):
            r = worst(callee, stack + [node])
            unknown |= r[2]
            dynamic |= r[3]
            cycles += r[4]
            if r[0] > best[0] or (r[0] == best[0] and not best[1]):
                best = r
        out = (size + best[0], [(node, size)] + best[1], unknown, dynamic, cycles)
        if not cycles:
            memo[node] = out
        return out

    for e in entries:
        if e not in frames:
            result[e] = {"bytes": None, "path": [], "bounded": False, "dynamic": [],
                         "unknown": [e], "recursion": []}
            continue
        depth, path, unknown, dynamic, cycles = worst(e, [])
        result[e] = {
            "bytes": depth,
            "path": [(n.split(":")[-1], s) for n, s in path],
            "bounded": not unknown and not dynamic and not cycles,
            "dynamic": sorted(n.split(":")[-1] for n in dynamic),
            "unknown": sorted(unknown),
            "recursion": [[n.split(":")[-1] for n in c] for c in cycles],
        }
    return result


def dynamic_frames(obj_dir):
    """Every function of the .su files whose frame is not static."""
    _, _, su = load(obj_dir)
    return sorted(k for k, (_, q) in su.items() if q != "static")
