# mk/static.mk -- static analysis beyond MISRA, results as SARIF 2.1.0 (tools/gates/static.sh,
# tools/gates/sarif.py): cppcheck's warning, style, performance and portability checks over
# src/ and port_s32k/, gcc -fanalyzer over src/ with the project's warnings, clang-tidy's
# bugprone and cert checks over src/ and port_s32k/.  Raw outputs, one SARIF file per
# tool, the merged build/static/qfoc.sarif and build/static/static.md; the gate fails on
# any finding that specs/static-accepted.md does not accept with a justification.

.PHONY: static

## static: cppcheck, gcc -fanalyzer, clang-tidy as SARIF (build/static/qfoc.sarif, static.md); fails on a finding not in specs/static-accepted.md
static: deps
	@WARN="$(filter-out -Werror,$(WARN))" CC="$(CC)" PYTHON="$(PYTHON)" sh tools/gates/static.sh
