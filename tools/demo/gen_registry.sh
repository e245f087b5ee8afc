#!/bin/sh
# tables/manifest.txt -> the C registry of the tables (sim/apps/tables_registry.h).
# usage: tools/demo/gen_registry.sh tables/manifest.txt > build/host/gen/tables_registry.c
set -eu
awk '
BEGIN { n = 0 }
/^[ \t]*#/ || NF < 2 { next }
{
    name[n] = $1; motor[n] = $2; ov = ""
    for (k = 3; k <= NF; k++) ov = ov (k > 3 ? " " : "") $k
    over[n] = ov; n++
}
END {
    print "/* Generated from tables/manifest.txt by tools/demo/gen_registry.sh; do not edit. */"
    print "#include \"tables_registry.h\""
    for (k = 0; k < n; k++) printf "#include \"%s_params.h\"\n", name[k]
    print ""
    print "const scn_table_t scn_tables[] = {"
    for (k = 0; k < n; k++)
        printf "    { \"%s\", &qfoc_params_%s, \"%s\", \"%s\" },\n", name[k], name[k], motor[k], over[k]
    print "};"
    printf "const int scn_n_tables = %d;\n", n
}' "$1"
