#!/usr/bin/env python3
"""Whether a release may be made, or has been made, from what it claims (make release,
make release-check).

usage:
  release_ready.py tree [--root DIR] [--evidence DIR]
      before make release packs anything: the working tree at ROOT (default: this checkout)
      and the evidence bundle in DIR (default build/evidence under ROOT).
  release_ready.py package DIR
      an unpacked release package DIR (make release-check): its evidence/ bundle against
      the commit its RELEASE.txt records.

Refusal (exit status 1, every reason printed, one per line, after "release: refused:"):

  tree     - ROOT is not a git work tree (a release is made from a commit);
           - `git status` is not clean: a tracked file modified, added, deleted or renamed,
             or an untracked file anywhere in the tree (untracked files under the source
             directories count: the build takes src/*.c by wildcard); build/ and dist/ are
             set aside, as are the files .gitignore ignores;
           - the evidence bundle is missing, or its evidence.json is unreadable;
           - the bundle is of another commit than HEAD, or was made in a modified working
             tree ("working tree modified"), or outside git;
           - a summary row of the bundle is not green (a gate's result missing, failed, or
             STALE: computed from other inputs than the tree's), each row named;
           - a result the bundle took as current is stale now (its inputs stamp checked again
             against the tree with tools/evidence/inputs.py: a tool version changed since);
           - the bundle's MANIFEST.sha256 does not match its files;
           - the WP prover results the proofs replayed (proofs/wp/cache.txt, REQ-EVD-032)
             were not all proved by one full run (make prove-full) over the tree's sources,
             headers, ACSL files and proof drivers with the installed Frama-C, Why3 and
             provers: every changed file named (tools/gates/wp_cache.py full-check).  With
             QFOC_RELEASE_CANDIDATE=1 in the environment this one reason does not refuse:
             the package is made as a candidate, and its RELEASE.txt says so
             (tools/release/release.sh; the release gate of make check does this, so that
             every commit's packaging is checked before its store is re-proved in full).
  package  - RELEASE.txt missing or without its commit line;
           - evidence/evidence.json missing or unreadable, of another commit than the
             package's, made in a modified tree, or with a summary row that is not green;
           - evidence/MANIFEST.sha256 does not match the bundle's files.

Exit status 0 with one line saying what was checked.  Reads only; writes nothing.
"""
import argparse
import hashlib
import json
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
TOP = os.path.dirname(os.path.dirname(HERE))
MANIFEST = "MANIFEST.sha256"
SET_ASIDE = ("build", "dist")
LIST_MAX = 40


def git(root, *args):
    """stdout of a git command in ROOT, or None when it fails."""
    try:
        r = subprocess.run(["git", "-C", root, *args], capture_output=True, text=True,
                           timeout=60, check=False)
    except (OSError, subprocess.SubprocessError):
        return None
    return r.stdout if r.returncode == 0 else None


def tree_changes(root):
    """The lines of `git status --porcelain` (untracked files listed one by one), build/ and
    dist/ set aside; None when ROOT is not a git work tree."""
    if (git(root, "rev-parse", "--is-inside-work-tree") or "").strip() != "true":
        return None
    top = (git(root, "rev-parse", "--show-toplevel") or "").strip()
    spec = ["."] + [f":(exclude,top){d}" for d in SET_ASIDE]
    out = git(top or root, "status", "--porcelain=v1", "--untracked-files=all",
              "--ignore-submodules=none", "--", *spec)
    if out is None:
        return None
    return [ln for ln in out.splitlines() if ln.strip()]


def describe_change(line):
    code, path = line[:2], line[3:]
    if code == "??":
        kind = "untracked"
    elif "D" in code:
        kind = "deleted"
    elif "R" in code:
        kind = "renamed"
    elif "A" in code:
        kind = "added, not committed"
    else:
        kind = "modified"
    return f"{kind}: {path}"


def listed(lines):
    shown = [f"  {x}" for x in lines[:LIST_MAX]]
    if len(lines) > LIST_MAX:
        shown.append(f"  ... and {len(lines) - LIST_MAX} more")
    return shown


def sha256_file(path):
    """SHA-256 of a bundle file (this checker stands alone: a package has no tools/evidence)."""
    with open(path, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()


def manifest_problems(bundle):
    """Differences between BUNDLE/MANIFEST.sha256 and the files of BUNDLE."""
    mpath = os.path.join(bundle, MANIFEST)
    if not os.path.isfile(mpath):
        return [f"{MANIFEST} missing"]
    listed_sums = {}
    with open(mpath, encoding="utf-8") as f:
        for ln in f:
            ln = ln.rstrip("\n")
            if len(ln) > 66 and ln[64:66] == "  ":
                listed_sums[ln[66:]] = ln[:64]
    present = set()
    for dirpath, dirs, fnames in os.walk(bundle):
        dirs.sort()
        for fn in fnames:
            rel = os.path.relpath(os.path.join(dirpath, fn), bundle).replace(os.sep, "/")
            if rel != MANIFEST:
                present.add(rel)
    problems = [f"not in {MANIFEST}: {p}" for p in sorted(present - set(listed_sums))]
    problems += [f"listed in {MANIFEST}, missing: {p}" for p in sorted(set(listed_sums) - present)]
    for rel in sorted(present & set(listed_sums)):
        if sha256_file(os.path.join(bundle, rel)) != listed_sums[rel]:
            problems.append(f"changed since {MANIFEST} was written: {rel}")
    return problems


def load_bundle(bundle, shown):
    """(evidence.json as a dict, None) or (None, reason)."""
    path = os.path.join(bundle, "evidence.json")
    if not os.path.isfile(path):
        return None, (f"no evidence bundle in {shown} (no evidence.json): run the gates "
                      "(make check), then make evidence")
    try:
        with open(path, encoding="utf-8") as f:
            data = json.load(f)
    except (OSError, ValueError) as exc:
        return None, f"{shown}/evidence.json is unreadable: {exc}"
    if not isinstance(data, dict) or not isinstance(data.get("summary"), list) \
            or not isinstance(data.get("commit"), dict):
        return None, f"{shown}/evidence.json has no summary rows or no commit record"
    return data, None


def bundle_problems(data, shown, commit):
    """Why the bundle DATA is not evidence for COMMIT: its commit, its tree, its rows."""
    out = []
    rec = data["commit"]
    made_at = rec.get("commit")
    dirty = rec.get("dirty")
    if made_at != commit:
        out.append(f"the evidence bundle {shown} is of commit {made_at}, not {commit}: run the "
                   "gates on this commit, then make evidence")
    if dirty is True:
        out.append(f"the evidence bundle {shown} was made in a modified working tree "
                   "(evidence.json: working tree modified): it is not evidence of any commit")
    elif dirty is None:
        out.append(f"the evidence bundle {shown} was not made in a git checkout "
                   "(no commit and no tree state recorded)")
    rows = data["summary"]
    bad = [r for r in rows if r.get("status") != "PASS" or r.get("stale")]
    if not rows:
        out.append(f"the evidence bundle {shown} has no summary rows")
    if bad:
        out.append(f"the evidence bundle {shown} is not green: {len(bad)} of {len(rows)} "
                   "summary rows red")
        for r in bad:
            tag = "STALE" if r.get("stale") else "FAIL"
            out.append(f"  {tag:<5} {r.get('label', r.get('key', '?'))}: {r.get('figure', '')}")
    red = data.get("red")
    if not bad and red not in (0, None):
        out.append(f"the evidence bundle {shown} counts {red} red rows (evidence.json: red)")
    return out


def stamps_now(data, root):
    """The results the bundle took as current whose inputs stamp is not current now."""
    sys.path.insert(0, os.path.join(root, "tools", "evidence"))
    try:
        import inputs as inp  # noqa: E402  (tools/evidence/inputs.py of ROOT)
    except ImportError as exc:
        return [f"tools/evidence/inputs.py cannot be loaded to check the stamps again: {exc}"]
    out = []
    for key, sec in sorted((data.get("sections") or {}).items()):
        st = sec.get("stamp") if isinstance(sec, dict) else None
        if not isinstance(st, dict) or not st.get("file") or st.get("state") != inp.CURRENT:
            continue
        path = st["file"] if os.path.isabs(st["file"]) else os.path.join(root, st["file"])
        res = inp.check(path, st.get("gate"), root=root)
        if res["state"] != inp.CURRENT:
            why = "; ".join(res.get("reasons") or [res["state"]])
            out.append(f"  STALE {key}: {st['file']} is {res['state']} now: {why}")
    if out:
        out.insert(0, "results the evidence bundle shows as current are stale now "
                      "(run those gates again, then make evidence):")
    return out


def wp_store_problems(root):
    """[] when the store of WP's prover results was written by a full run over the tree's
    proof sources and tools, else the reasons (tools/gates/wp_cache.py full-check)."""
    sys.path.insert(0, os.path.join(root, "tools", "gates"))
    try:
        import wp_cache  # noqa: E402  (tools/gates/wp_cache.py of ROOT)
    except ImportError as exc:
        return [f"tools/gates/wp_cache.py cannot be loaded to check the WP store: {exc}"]
    diff = wp_cache.full_check(os.path.join(root, "proofs", "wp", "cache.txt"), root)
    if not diff:
        return []
    return [f"the WP prover results of proofs/wp/cache.txt were not all proved by one full run "
            f"over this tree's proof sources and tools ({len(diff)} difference"
            f"{'s' if len(diff) != 1 else ''}): run make prove-full and commit proofs/wp/"] + \
        listed(diff)


def check_tree(root, evidence):
    root = os.path.abspath(root)
    bundle = evidence if os.path.isabs(evidence) else os.path.join(root, evidence)
    shown = os.path.relpath(bundle, root) if not os.path.relpath(bundle, root).startswith("..") \
        else bundle
    reasons = []
    changes = tree_changes(root)
    head = (git(root, "rev-parse", "HEAD") or "").strip()
    if changes is None or not head:
        reasons.append(f"{root} is not a git work tree with a commit: a release is made from a "
                       "commit (clone the repository)")
    elif changes:
        reasons.append(f"the working tree is not clean (git status; build/ and dist/ set aside): "
                       f"{len(changes)} path{'s' if len(changes) != 1 else ''}")
        reasons += listed([describe_change(c) for c in changes])
    data, why = load_bundle(bundle, shown)
    if data is None:
        reasons.append(why)
    else:
        reasons += bundle_problems(data, shown, head or "(no commit)")
        if not reasons:
            mp = manifest_problems(bundle)
            if mp:
                reasons.append(f"the evidence bundle {shown} does not match its {MANIFEST}:")
                reasons += listed(mp)
        if not reasons:
            reasons += stamps_now(data, root)
    store = wp_store_problems(root)
    if store and os.environ.get("QFOC_RELEASE_CANDIDATE") == "1":
        print(f"release: candidate (QFOC_RELEASE_CANDIDATE=1), not for production: {store[0]}")
        for r in store[1:]:
            print(r)
    else:
        reasons += store
    if reasons:
        for r in reasons:
            print(r if r.startswith("  ") else f"release: refused: {r}")
        print("release: nothing packaged.  A release is made from a clean checkout of a commit "
              "whose gates ran on it: make check, commit the results it rewrote "
              "(proofs/wp/, proofs/cbmc/), then make evidence and make release")
        return 1
    rows = data["summary"]
    print(f"release: tree clean at {head}; evidence {shown}: commit {head}, {len(rows)} of "
          f"{len(rows)} summary rows green, its results current, {MANIFEST} verified")
    return 0


def package_commit(pkg):
    path = os.path.join(pkg, "RELEASE.txt")
    if not os.path.isfile(path):
        return None
    with open(path, encoding="utf-8") as f:
        for ln in f:
            words = ln.split()
            if len(words) >= 2 and words[0] == "commit:":
                return words[1]
    return None


def check_package(pkg):
    pkg = os.path.abspath(pkg)
    reasons = []
    commit = package_commit(pkg)
    if commit is None:
        reasons.append("RELEASE.txt missing, or without its 'commit: ' line")
    bundle = os.path.join(pkg, "evidence")
    data, why = load_bundle(bundle, "evidence")
    if data is None:
        reasons.append(why)
    else:
        reasons += bundle_problems(data, "evidence", commit or "(none recorded)")
        mp = manifest_problems(bundle)
        if mp:
            reasons.append(f"the evidence bundle does not match its {MANIFEST}:")
            reasons += listed(mp)
    if reasons:
        for r in reasons:
            print(r if r.startswith("  ") else f"release-check: refused: {r}")
        return 1
    rows = data["summary"]
    print(f"release-check: evidence/ of commit {commit} (the package's, RELEASE.txt), made in a "
          f"clean tree, {len(rows)} of {len(rows)} summary rows green, {MANIFEST} verified")
    return 0


def main(argv=None):
    ap = argparse.ArgumentParser(description="Whether a release may be made (tree) or was made "
                                             "(package) from green evidence of its commit.")
    sub = ap.add_subparsers(dest="mode", required=True)
    t = sub.add_parser("tree", help="the working tree and its evidence bundle (make release)")
    t.add_argument("--root", default=TOP, help="the repository (default: this checkout)")
    t.add_argument("--evidence", default="build/evidence",
                   help="the evidence bundle, relative to the root (default build/evidence)")
    p = sub.add_parser("package", help="an unpacked release package (make release-check)")
    p.add_argument("dir", help="the package's top directory (qfoc-<version>/)")
    args = ap.parse_args(argv)
    if args.mode == "tree":
        return check_tree(args.root, args.evidence)
    return check_package(args.dir)


if __name__ == "__main__":
    sys.exit(main())
