#!/bin/sh
# tools/gates/repro.sh -- reproducible builds: the Cortex-M4F library and the S32K144 firmware
# image built twice from the same sources in two separate build trees must be identical
# byte for byte.  Prints and records (build/repro/repro.json) the SHA-256 of each
# artefact and the compiler that built it; exit 1 when the two builds differ.
set -u
TOP=$(cd "$(dirname "$0")/../.." && pwd)
cd "$TOP"
OUT=build/repro
rm -rf "$OUT"
mkdir -p "$OUT"
for side in a b; do
    if ! make --no-print-directory -s BUILD="$OUT/$side" "$OUT/$side/target/libqfoc.a" firmware \
            > "$OUT/$side.log" 2>&1; then
        cat "$OUT/$side.log"
        echo "repro: build $side failed"
        exit 1
    fi
done
rc=0
json="$OUT/repro.json"
printf '{\n  "compiler": "%s",\n  "artefacts": [\n' "$(arm-none-eabi-gcc --version | head -n 1)" > "$json"
sep=
for f in target/libqfoc.a s32k144/qfoc_compressor.elf s32k144/qfoc_compressor.bin; do
    ha=$(sha256sum "$OUT/a/$f" | cut -d' ' -f1)
    hb=$(sha256sum "$OUT/b/$f" | cut -d' ' -f1)
    if [ "$ha" = "$hb" ]; then same=true; else same=false; rc=1; fi
    echo "repro: $f sha256 $ha ($([ "$same" = true ] && echo identical in both builds || echo "DIFFERS: $hb"))"
    printf '%s    {"file": "%s", "sha256": "%s", "sha256_second": "%s", "identical": %s}' \
        "$sep" "$f" "$ha" "$hb" "$same" >> "$json"
    sep=',
'
done
printf '\n  ]\n}\n' >> "$json"
if [ "$rc" = 0 ]; then
    echo "repro: two builds from the same sources are identical byte for byte ($json)"
fi
exit "$rc"
