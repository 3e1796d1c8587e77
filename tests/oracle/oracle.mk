# tests/oracle/oracle.mk: the Mesa oracle (included by the top-level Makefile).
#
#   make oracle-build   build/oracle/glref (reference renderer, needs libosmesa6-dev) and
#                       build/oracle/compare (image comparison)
#   make oracle         both, plus ./rastty, then tests/oracle/run.sh
#   make oracle-calibrate  Mesa softpipe against llvmpipe on the same scenes (no rastty)
# Without OSMesa only compare is built and run.sh reports every scene as skipped.
# Uses CC, WARN, DEFS and OPT from the top-level Makefile; links nothing of rastty's.

ORACLE_DIR    := build/oracle
ORACLE_CFLAGS := $(WARN) $(DEFS) $(OPT) $(shell pkg-config --cflags stb 2>/dev/null || echo -I/usr/include/stb)
ORACLE_STB    := $(shell pkg-config --libs stb 2>/dev/null || echo -lstb)
ORACLE_HAVE_OSMESA := $(shell pkg-config --exists osmesa 2>/dev/null && echo yes)
ORACLE_BINS   := $(ORACLE_DIR)/compare $(if $(ORACLE_HAVE_OSMESA),$(ORACLE_DIR)/glref build/bench/glbench)

.PHONY: oracle oracle-build oracle-calibrate

oracle-build: $(ORACLE_BINS)
ifeq ($(ORACLE_HAVE_OSMESA),)
	@echo "oracle: OSMesa not found (apt-get install libosmesa6-dev); glref not built"
endif

oracle: rastty oracle-build
	tests/oracle/run.sh

oracle-calibrate: oracle-build
	tests/oracle/run.sh --calibrate

$(ORACLE_DIR)/glref: tests/oracle/glref.c tests/oracle/oracle.mk | $(ORACLE_DIR)
	$(CC) $(ORACLE_CFLAGS) $(shell pkg-config --cflags osmesa) -o $@ $< \
	    $(shell pkg-config --libs osmesa) $(ORACLE_STB) -lm

# Mesa's time for make bench's workloads (tests/bench/glbench.c)
build/bench/glbench: tests/bench/glbench.c tests/oracle/oracle.mk
	@mkdir -p build/bench
	$(CC) $(ORACLE_CFLAGS) $(shell pkg-config --cflags osmesa) -o $@ $< \
	    $(shell pkg-config --libs osmesa) $(ORACLE_STB) -lm

$(ORACLE_DIR)/compare: tests/oracle/compare.c tests/oracle/oracle.mk | $(ORACLE_DIR)
	$(CC) $(ORACLE_CFLAGS) -o $@ $< $(ORACLE_STB) -lm

$(ORACLE_DIR):
	@mkdir -p $@
