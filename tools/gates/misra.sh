#!/bin/sh
# tools/gates/misra.sh -- MISRA C:2012 gate with cppcheck's MISRA addon.
#
# Checks src/*.c, the generated parameter tables tables/*.c and the S32K144 port
# port_s32k/*.c (the code that goes on the target) with the public headers
# (the whole library in one cppcheck run, so cross-unit rules see every file).  The addon needs a rule-texts file: it is made
# from misra/guidelines.txt (qfoc's own one-line summaries).  A finding passes only
# when it is suppressed at its site by a comment that names a deviation record
# (DEV-nnn) of misra/deviations.md; tools/gates/misra_report.py checks that and writes
# build/misra/report.md, stamped with the run's UTC time and the SHA-256 of its inputs
# (tools/evidence/inputs.py misra).  Exit 1 on any unrecorded finding.
set -eu
# Debian's interpreter (a python3 earlier on PATH may lack the packages)
PY=/usr/bin/python3
[ -x "$PY" ] || PY=python3
TOP=$(cd "$(dirname "$0")/../.." && pwd)
cd "$TOP"
OUT=build/misra
mkdir -p "$OUT"
STARTED=$(date +%s)
"$PY" tools/gates/misra_rule_texts.py misra/guidelines.txt "$OUT/rule-texts.txt"
printf '{\n "script": "misra.py",\n "args": ["--rule-texts=%s/%s/rule-texts.txt"]\n}\n' "$TOP" "$OUT" > "$OUT/misra.json"
set +e
cppcheck --addon="$OUT/misra.json" --addon-python=/usr/bin/python3 \
    --std=c99 --platform=arm32-wchar_t4 --inline-suppr -Iinclude -Itables -Iport_s32k \
    --suppress=missingIncludeSystem --error-exitcode=1 -q \
    --xml --output-file="$OUT/cppcheck.xml" src/*.c tables/*.c port_s32k/*.c
rc=$?
set -e
"$PY" tools/gates/misra_report.py "$OUT/cppcheck.xml" misra/deviations.md "$OUT/report.md" src include tables port_s32k
rc2=$?
rc3=0
"$PY" tools/evidence/inputs.py --stamp "$OUT/report.md" misra --started "$STARTED" > /dev/null || rc3=$?
[ "$rc" = 0 ] && [ "$rc2" = 0 ] && [ "$rc3" = 0 ]
