# mk/docs.mk -- the API reference of the public headers (Doxyfile).
#
#   make docs        doxygen over include/qfoc/ with docs/api-reference.md as the front page:
#                    build/docs/html/index.html (HTML only).  Every doxygen warning fails the
#                    target: an undocumented public function, parameter, return value, type,
#                    struct member or macro, or a documentation error.  The pages carry no
#                    time stamp and no absolute path: the same sources give the same bytes.
#   make deps-docs   what it needs and nothing more: make and Debian's doxygen
#                    (tools/setup/deps.sh --docs), not the verification chain of make deps.
#
# The version on the pages is QFOC_VERSION_STRING of include/qfoc/version.h.  Doxygen's own
# output goes to build/docs/doxygen.log, beside the pages.

DOCS_DIR     := $(BUILD)/docs
DOCS_VERSION := $(shell sed -n 's/^\#define QFOC_VERSION_STRING "\(.*\)".*/\1/p' include/qfoc/version.h)

.PHONY: docs deps-docs docs-clean

## deps-docs: only the API reference's packages (make, doxygen)
deps-docs:
	@sh tools/setup/deps.sh --docs

## docs: the API reference of include/qfoc/ (doxygen HTML): build/docs/html/index.html; fails on any warning
docs: deps-docs
	@rm -rf $(DOCS_DIR)
	@mkdir -p $(DOCS_DIR)
	@rc=0; QFOC_DOC_VERSION='$(DOCS_VERSION)' doxygen Doxyfile > $(DOCS_DIR)/doxygen.log 2>&1 || rc=$$?; \
	  n=$$(grep -c . $(DOCS_DIR)/doxygen.log || true); \
	  if [ "$$rc" != 0 ] || [ "$$n" != 0 ]; then \
	      cat $(DOCS_DIR)/doxygen.log; \
	      echo "docs: FAILED: doxygen exit status $$rc, $$n warning lines (every warning fails: Doxyfile)"; \
	      exit 1; \
	  fi; \
	  test -f $(DOCS_DIR)/html/index.html || { echo "docs: FAILED: no $(DOCS_DIR)/html/index.html"; exit 1; }; \
	  echo "docs: $(DOCS_DIR)/html/index.html: qfoc $(DOCS_VERSION), $$(ls include/qfoc/*.h | wc -l) headers, 0 doxygen warnings (doxygen $$(doxygen --version))"

# make clean also removes the pages
clean: docs-clean
docs-clean:
	rm -rf $(DOCS_DIR)
