# ---------------------------------------------------------------- single-shunt THD
# The phase-current distortion that the single shunt's edge shifting adds (REQ-SCN-018,
# sim/apps/shunt_thd.c): the reference motor at 1000, 3000 and 6000 rpm, light and rated
# load, on its two-sensor table, its single-shunt table and the two-sensor table with the
# edge shifting alone; the true phase currents at every plant sub-step over whole electrical
# periods, their DFT; then a speed sweep at the rated load and one point at 80 sub-steps;
# build/reports/shunt_thd.md and .csv.  About 25 s: not part of
# make check.

.PHONY: shunt-thd

## shunt-thd: the phase-current THD of the single shunt against two sensors: build/reports/shunt_thd.md
shunt-thd: $(BUILD)/host/qfoc_shunt_thd
	@mkdir -p $(BUILD)/reports
	@$(BUILD)/host/qfoc_shunt_thd --out $(BUILD)/reports
	@cat $(BUILD)/reports/shunt_thd.md

$(BUILD)/host/qfoc_shunt_thd: sim/apps/shunt_thd.c sim/apps/tables_registry.h \
        $(BUILD)/host/gen/tables_registry.c $(SIM_SRCS) $(SIM_HDRS) $(TABLE_SRCS) $(TABLE_HDRS) \
        $(BUILD)/host/libqfoc.a
	$(CC) $(SIM_APP_CFLAGS) $< $(BUILD)/host/gen/tables_registry.c $(SIM_SRCS) $(TABLE_SRCS) \
	    $(BUILD)/host/libqfoc.a -lm -o $@
