#!/usr/bin/env python3
"""Write the cppcheck MISRA addon's rule-texts file from misra/guidelines.txt.

usage: misra_rule_texts.py GUIDELINES OUT
The addon expects 'Appendix A Summary of guidelines', then per rule a line
'Rule N.M Category' followed by one line of text.
"""
import sys

CATEGORY = {"M": "Mandatory", "R": "Required", "A": "Advisory"}


def read_guidelines(path):
    """misra/guidelines.txt (and misra/directives.txt): the 'N.M C|summary' lines, as
    (number, category letter M/R/A, summary) in file order."""
    out = []
    with open(path, encoding="utf-8") as f:
        for raw in f:
            raw = raw.strip()
            if not raw or raw.startswith("#"):
                continue
            head, text = raw.split("|", 1)
            num, cat = head.split()
            out.append((num, cat, text.strip()))
    return out


def main() -> int:
    src, dst = sys.argv[1], sys.argv[2]
    lines = ["Appendix A Summary of guidelines"]
    for rule, cat, text in read_guidelines(src):
        lines.append(f"Rule {rule} {CATEGORY[cat]}")
        # the addon takes a text line only when it starts with a capital letter
        lines.append(text[:1].upper() + text[1:])
    with open(dst, "w", encoding="utf-8") as f:
        f.write("\n".join(lines) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
