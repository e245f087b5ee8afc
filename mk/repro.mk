# Reproducible builds (tools/gates/repro.sh).
.PHONY: repro
## repro: the library and the firmware image built twice: identical bytes, SHA-256 recorded
repro: deps
	@sh tools/gates/repro.sh
