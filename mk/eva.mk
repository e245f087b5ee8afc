# Whole-program abstract interpretation of the drive (tools/gates/eva.sh).
.PHONY: eva
## eva: Frama-C EVA over the fast step and the tick with every input over its full range
eva: deps
	@sh tools/gates/eva.sh
