# mk/cxx.mk -- the public headers used from C++ (tools/gates/cxx_check.sh); make test runs the
# same check after the unit tests and the examples.

.PHONY: cxx-check

## cxx-check: the public headers from C++11: each compiled alone (g++ -pedantic -Werror), every
##            library function declared with C linkage, the examples built as C++ and run
cxx-check: deps $(BUILD)/host/libqfoc.a
	@sh tools/gates/cxx_check.sh $(BUILD)/host/libqfoc.a
