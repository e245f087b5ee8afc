# Whole-program abstract interpretation of the drive (tools/gates/eva.sh).
.PHONY: eva eva-reference
## eva: Frama-C EVA over the fast step and the tick with every input over its full range, on every
##      table the drive accepts (build/eva/eva-all.md)
eva: deps
	@sh tools/gates/eva.sh

## eva-reference: the same analysis on the reference table alone, outside make check (build/eva/eva.md)
eva-reference: deps
	@EVA_RUN=eva sh tools/gates/eva.sh
