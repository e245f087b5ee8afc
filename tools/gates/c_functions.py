#!/usr/bin/env python3
"""Print the comma-separated names of the functions a C file defines (empty
for a file of data only, such as a constant table).

qfoc's style puts a definition's return type and name on one line, its parameters
after it, and the opening brace alone on the line after the parameter list.
"""
import re
import sys

DEF = re.compile(
    r"^(?:static\s+)?(?:inline\s+)?(?:const\s+)?[A-Za-z_][A-Za-z0-9_]*\s*\**\s*"
    r"([A-Za-z_][A-Za-z0-9_]*)\s*\(([^;{}]*)\)\s*\n\{",
    re.MULTILINE,
)


def main() -> int:
    text = open(sys.argv[1], encoding="utf-8").read()
    names = [m.group(1) for m in DEF.finditer(text)]
    print(",".join(names))
    return 0


if __name__ == "__main__":
    sys.exit(main())
