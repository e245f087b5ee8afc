#!/usr/bin/env python3
"""CMocka output -> JUnit XML (one file per test executable).

usage: junit.py OUT_DIR SUITE=OUTPUT_FILE...

Each OUTPUT_FILE holds the standard output of one CMocka executable (the '[ RUN      ]',
'[       OK ]', '[  FAILED  ]', '[  SKIPPED ]' lines and the messages between them);
SUITE names it; SUITE=vectors:OUTPUT_FILE reads instead the report of the
target-equivalence runner (tools/target_test/tt_runner.c: one '<group>: <n> vectors,
identical' or '<group>: DIFFERENT: ...' line per group, then a 'result:' line), one
<testcase> per group; SUITE=checks:OUTPUT_FILE reads one '<name>: OK' or
'<name>: FAILED: <message>' line per check (the checking programs of the target test,
tools/target_test/target_test.sh), one <testcase> per line.  Writes OUT_DIR/SUITE.xml with
one <testcase> per test, the messages as <system-out>, a failure's messages as its
<failure> text, and an executable that ended without its summary line as an <error>; the
<testsuite> carries the run's UTC time (timestamp), which tools/evidence/evidence.py shows.
Prints 'junit: N suites, T tests, F failures'.
"""
import datetime
import os
import re
import sys
from xml.sax.saxutils import escape, quoteattr

RUN = re.compile(r"^\[ RUN      \] (\S+)")
END = re.compile(r"^\[ +(OK|FAILED|SKIPPED|ERROR) +\] (\S+)")
DONE = re.compile(r"^\[==========\] \d+ test\(s\) run\.")


def parse(text):
    """Test records (name, status, messages) and whether the run completed."""
    tests = []
    current = None
    lines = []
    done = False
    for line in text.splitlines():
        m = RUN.match(line)
        if m:
            current, lines = m.group(1), []
            continue
        m = END.match(line)
        if m and current is not None and m.group(2) == current:
            tests.append((current, m.group(1), "\n".join(lines)))
            current = None
            continue
        if DONE.match(line):
            done = True
        if current is not None:
            lines.append(line)
    if current is not None:
        tests.append((current, "ERROR", "\n".join(lines) + "\n(the executable ended inside this test)"))
    return tests, done


GROUP = re.compile(r"^([A-Za-z0-9_]+): (\d+ vectors, identical|DIFFERENT: .*)$")


def parse_vectors(text):
    """Golden-vector groups as test records; the run is complete with its 'result:' line."""
    tests = []
    done = False
    for line in text.splitlines():
        m = GROUP.match(line)
        if m:
            ok = m.group(2).endswith("identical")
            tests.append((m.group(1), "OK" if ok else "FAILED", m.group(2)))
        elif line.startswith("result: "):
            done = True
    return tests, done


CHECK = re.compile(r"^([A-Za-z0-9_.\-]+): (OK|FAILED)(?:: (.*))?$")


def parse_checks(text):
    """Checks as test records: '<name>: OK' or '<name>: FAILED: <message>'; always complete."""
    tests = []
    for line in text.splitlines():
        m = CHECK.match(line.strip())
        if m:
            tests.append((m.group(1), m.group(2), m.group(3) or ""))
    return tests, True


def write(out_dir, suite, tests, done):
    """One JUnit XML file; returns (tests, failures, errors)."""
    fails = sum(1 for t in tests if t[1] == "FAILED")
    errs = sum(1 for t in tests if t[1] == "ERROR") + (0 if done else 1)
    skips = sum(1 for t in tests if t[1] == "SKIPPED")
    stamp = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%dT%H:%M:%SZ")
    out = ['<?xml version="1.0" encoding="UTF-8"?>',
           f'<testsuites tests="{len(tests)}" failures="{fails}" errors="{errs}">',
           f'  <testsuite name={quoteattr(suite)} tests="{len(tests)}" failures="{fails}" '
           f'errors="{errs}" skipped="{skips}" timestamp="{stamp}">']
    for name, status, msg in tests:
        out.append(f'    <testcase classname={quoteattr(suite)} name={quoteattr(name)}>')
        if status == "FAILED":
            out.append(f'      <failure message="failed">{escape(msg)}</failure>')
        elif status == "ERROR":
            out.append(f'      <error message="error">{escape(msg)}</error>')
        elif status == "SKIPPED":
            out.append('      <skipped/>')
        if msg and status not in ("FAILED", "ERROR"):
            out.append(f'      <system-out>{escape(msg)}</system-out>')
        out.append('    </testcase>')
    if not done:
        out.append(f'    <testcase classname={quoteattr(suite)} name="(run)">')
        out.append('      <error message="the executable did not complete its run"/>')
        out.append('    </testcase>')
    out.append('  </testsuite>')
    out.append('</testsuites>')
    with open(os.path.join(out_dir, suite + ".xml"), "w", encoding="utf-8") as f:
        f.write("\n".join(out) + "\n")
    return len(tests), fails, errs


def main(argv):
    if len(argv) < 2:
        print(__doc__, file=sys.stderr)
        return 2
    out_dir = argv[0]
    os.makedirs(out_dir, exist_ok=True)
    n_t = n_f = n_s = 0
    for arg in argv[1:]:
        suite, path = arg.split("=", 1)
        reader = parse
        if path.startswith("vectors:"):
            reader, path = parse_vectors, path[len("vectors:"):]
        elif path.startswith("checks:"):
            reader, path = parse_checks, path[len("checks:"):]
        with open(path, encoding="utf-8", errors="replace") as f:
            tests, done = reader(f.read())
        t, fl, er = write(out_dir, suite, tests, done)
        n_s += 1
        n_t += t
        n_f += fl + er
    print(f"junit: {n_s} suites, {n_t} tests, {n_f} failures or errors ({out_dir})")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
