#!/bin/sh
# tools/bench/isqrt_steps.sh -- every 32-bit input of qfoc_isqrt32: exact result, and
# at most ISQRT_BOUND correction steps a call (the bound include/qfoc/vector.h states).
# The library source is compiled as it is, with one counter added to the correction
# statement; the two halves of the range run in parallel.  Part of `make bench`.
set -eu
TOP=$(cd "$(dirname "$0")/../.." && pwd)
cd "$TOP"
OUT=${1:-build/bench}/isqrt_steps
CC=${CC:-gcc}
ISQRT_BOUND=1
mkdir -p "$OUT"
# the correction statement, exactly once in the source
n=$(grep -c '^        r--;$' src/qfoc_isqrt.c || true)
if [ "$n" != 1 ]; then
    echo "isqrt_steps: expected one correction statement 'r--;' in src/qfoc_isqrt.c, found $n"
    exit 1
fi
sed 's/^        r--;$/        r--; isqrt_steps++;/' src/qfoc_isqrt.c > "$OUT/qfoc_isqrt_counted.c"
sed -i 's#^\#include "qfoc/vector.h"$#\#include "qfoc/vector.h"\nextern unsigned int isqrt_steps;#' \
    "$OUT/qfoc_isqrt_counted.c"
"$CC" -std=c99 -O2 -Wall -Wextra -Werror -Iinclude tools/bench/isqrt_steps.c \
    "$OUT/qfoc_isqrt_counted.c" -o "$OUT/isqrt_steps"
"$OUT/isqrt_steps" 0 0x7FFFFFFF $ISQRT_BOUND > "$OUT/low.txt" &
lo=$!
hi_rc=0
"$OUT/isqrt_steps" 0x80000000 0xFFFFFFFF $ISQRT_BOUND > "$OUT/high.txt" || hi_rc=$?
lo_rc=0
wait $lo || lo_rc=$?
cat "$OUT/low.txt" "$OUT/high.txt"
[ "$lo_rc" = 0 ] && [ "$hi_rc" = 0 ]
