#!/bin/sh
# tools/gates/static.sh -- static analysis beyond MISRA, results as SARIF 2.1.0.
#
#   sh tools/gates/static.sh    (make static; WARN, CC and PYTHON come from the Makefile)
#
# Three analysers, each output kept raw under build/static/:
#   cppcheck      --enable=warning,style,performance,portability over src/*.c and
#                 port_s32k/*.c with the project's include paths, the target platform
#                 (arm32) as for MISRA, no inline suppressions: every finding goes through
#                 specs/static-accepted.md.                       -> cppcheck.xml (XML v2)
#   gcc-analyzer  gcc -fanalyzer over src/*.c with the project's WARN flags (without
#                 -Werror, so that every diagnostic of every unit is collected) and
#                 -Iinclude, one unit at a time, JSON diagnostics (gcc 12 has no SARIF
#                 output; it came with gcc 13).                   -> gcc-analyzer/<unit>.json
#                 -O0: at -O2 the early optimisations remove code the analyser should see
#                 (a use of an uninitialised value and a double free, planted in a test
#                 unit, are reported at -O0 and missed at -O2).
#                 The exploration limits are raised (ANALYZER_PARAMS) so that no unit is
#                 cut short: with gcc's defaults the analyser gives up on parts of
#                 qfoc_drive.c, qfoc_emf.c, qfoc_link.c, qfoc_params.c and qfoc_svpwm.c.
#                 -Wanalyzer-too-complex stays on: an analysis cut short is a finding.
#   clang-tidy    bugprone-* and cert-* (minus DISABLED below) over src/*.c and
#                 port_s32k/*.c, -- -std=c99 -Iinclude -Itables -Iport_s32k; the project's
#                 headers (include/, tables/, port_s32k/) are reported too.
#                                                                  -> clang-tidy.txt
#                 The same run with every bugprone-* and cert-* check is kept as
#                 clang-tidy-all.txt: the report counts what each disabled check gives.
# Then tools/gates/sarif.py converts each output into build/static/<tool>.sarif, merges them
# into build/static/qfoc.sarif, writes build/static/static.md and applies the gate: exit 1
# on any finding that specs/static-accepted.md does not accept, on an accepted entry
# that matches no finding, or when an analyser failed.
set -u
TOP=$(cd "$(dirname "$0")/../.." && pwd)
cd "$TOP" || exit 1
OUT=build/static
PY=${PYTHON:-/usr/bin/python3}
[ -x "$PY" ] || PY=python3
CC=${CC:-gcc}
# The Makefile's WARN without -Werror (make static passes it so).
WARN=${WARN:--std=c99 -Wall -Wextra -Wconversion -Wsign-conversion -Wshadow -Wstrict-prototypes -Wmissing-prototypes -Wundef -Wcast-qual}
ANALYZER_PARAMS="--param=analyzer-bb-explosion-factor=200 --param=analyzer-max-enodes-per-program-point=64"

# clang-tidy checks disabled, one per line: "check | reason".  Only checks whose every
# finding is a property of the code base's deliberate style go here; everything else is
# accepted finding by finding in specs/static-accepted.md.
DISABLED='bugprone-easily-swappable-parameters | The Q15 interfaces take several values of one type by design (d and q, alpha and beta, a current and its limit, a gain and its shift): C99 has no distinct scalar types to tell them apart, and the project pins the order instead by its naming convention (instance first, inputs, outputs), by the ACSL contracts that WP proves against each parameter, and by tests against independent references.'

for t in cppcheck clang-tidy "$CC"; do
    command -v "$t" >/dev/null 2>&1 || { echo "static: $t is missing (make deps)"; exit 1; }
done

rm -rf "$OUT"
mkdir -p "$OUT/gcc-analyzer"
printf '%s\n' "$DISABLED" > "$OUT/clang-tidy-disabled.txt"
t_all=$(date +%s)

SRC=$(ls src/*.c)
PORT=$(ls port_s32k/*.c)

# ---------------------------------------------------------------- cppcheck
t0=$(date +%s)
# shellcheck disable=SC2086
set -- cppcheck --enable=warning,style,performance,portability --std=c99 \
    --platform=arm32-wchar_t4 -Iinclude -Itables -Iport_s32k \
    --suppress=missingIncludeSystem -q --xml --output-file="$OUT/cppcheck.xml" $SRC $PORT
printf '%s\n' "$*" > "$OUT/cppcheck.cmd"
"$@" 2> "$OUT/cppcheck.err"
echo $? > "$OUT/cppcheck.rc"
cppcheck --version > "$OUT/cppcheck.version"
cppcheck --errorlist > "$OUT/cppcheck-errorlist.xml"
echo "static: cppcheck done ($(( $(date +%s) - t0 )) s)"

# ---------------------------------------------------------------- gcc -fanalyzer
t0=$(date +%s)
rc=0
# shellcheck disable=SC2086
printf '%s\n' "$CC $WARN -O0 -Iinclude -fanalyzer -Wanalyzer-too-complex $ANALYZER_PARAMS -fdiagnostics-format=json -c <unit> -o /dev/null" \
    > "$OUT/gcc-analyzer.cmd"
for f in $SRC; do
    u=$(basename "$f" .c)
    # shellcheck disable=SC2086
    "$CC" $WARN -O0 -Iinclude -fanalyzer -Wanalyzer-too-complex $ANALYZER_PARAMS \
        -fdiagnostics-format=json -c "$f" -o /dev/null 2> "$OUT/gcc-analyzer/$u.json" || rc=1
done
echo $rc > "$OUT/gcc-analyzer.rc"
"$CC" -dumpfullversion > "$OUT/gcc-analyzer.version"
LC_ALL=C "$CC" --help=warnings > "$OUT/gcc-analyzer-options.txt" 2>/dev/null
echo "static: gcc -fanalyzer done ($(( $(date +%s) - t0 )) s)"

# ---------------------------------------------------------------- clang-tidy
t0=$(date +%s)
CHECKS='-*,bugprone-*,cert-*'
# the check's name: the first field of each line of the list
while IFS='|' read -r c _reason; do
    c=$(printf '%s' "$c" | tr -d ' ')
    [ -n "$c" ] && CHECKS="$CHECKS,-$c"
done < "$OUT/clang-tidy-disabled.txt"
HFILTER='(^|/)(include|tables|port_s32k)/'
TIDY_ARGS="-- -std=c99 -Iinclude -Itables -Iport_s32k"
printf '%s\n' "clang-tidy -checks=$CHECKS -header-filter=$HFILTER <src/*.c port_s32k/*.c> $TIDY_ARGS" \
    > "$OUT/clang-tidy.cmd"
# shellcheck disable=SC2086
clang-tidy -checks="$CHECKS" -header-filter="$HFILTER" $SRC $PORT $TIDY_ARGS \
    > "$OUT/clang-tidy.txt" 2> "$OUT/clang-tidy.err"
echo $? > "$OUT/clang-tidy.rc"
# shellcheck disable=SC2086
clang-tidy -checks='-*,bugprone-*,cert-*' -header-filter="$HFILTER" $SRC $PORT $TIDY_ARGS \
    > "$OUT/clang-tidy-all.txt" 2> "$OUT/clang-tidy-all.err"
clang-tidy -checks="$CHECKS" -list-checks > "$OUT/clang-tidy-checks.txt"
clang-tidy --version > "$OUT/clang-tidy.version"
echo "static: clang-tidy done ($(( $(date +%s) - t0 )) s)"

# ---------------------------------------------------------------- SARIF, report, gate
echo "static: analysers ran in $(( $(date +%s) - t_all )) s; SARIF in build/static/qfoc.sarif, report build/static/static.md"
"$PY" tools/gates/sarif.py --out "$OUT" --accepted specs/static-accepted.md
