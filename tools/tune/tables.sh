#!/bin/sh
# Generate (write) or re-check (check) every parameter table of tables/manifest.txt.
#   tools/tune/tables.sh write   tables/<name>_params.c/.h and build/tune/<name>/report.md
#   tools/tune/tables.sh check   the same into build/tune-check/, compared byte for byte
# PYTHON names the interpreter (default /usr/bin/python3, which sees python3-matplotlib).
set -u
mode=${1:-check}
py=${PYTHON:-/usr/bin/python3}
[ -x "$py" ] || py=python3
n=0
rc=0
rm -rf build/tune-check
mkdir -p build/tune build/tune-check
while read -r name motor rest; do
    case "$name" in ''|'#'*) continue ;; esac
    set --
    for o in $rest; do set -- "$@" --set "$o"; done
    n=$((n + 1))
    if [ "$mode" = write ]; then
        "$py" tools/tune/qfoc_tune.py "$motor" --name "$name" --out-dir "build/tune/$name" "$@" || rc=1
    else
        if ! "$py" tools/tune/qfoc_tune.py "$motor" --name "$name" --out-dir "build/tune/$name" \
                --table-dir build/tune-check "$@" > "build/tune/$name.log" 2>&1; then
            cat "build/tune/$name.log"
            echo "tune-check: $name ($motor $rest): the tool failed"
            rc=1
        elif ! cmp -s "build/tune-check/${name}_params.c" "tables/${name}_params.c" ||
             ! cmp -s "build/tune-check/${name}_params.h" "tables/${name}_params.h"; then
            echo "tune-check: tables/${name}_params.* differ from the tool's output for $motor $rest"
            rc=1
        fi
    fi
done < tables/manifest.txt
for c in tables/*_params.c; do
    b=$(basename "$c" _params.c)
    grep -q "^$b[[:space:]]" tables/manifest.txt ||
        { echo "tune-check: $c is not listed in tables/manifest.txt"; rc=1; }
done
if [ "$mode" = check ] && [ $rc -eq 0 ]; then
    echo "tune-check: $n tables tuned, every bound and loop margin met, tables reproduce byte for byte"
fi
exit $rc
