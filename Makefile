# rastty: a software rasterizer for the terminal.  `make help` lists the targets.
CC      ?= cc
PREFIX  ?= /usr/local
BUILD   ?= build
PKGS    := ncursesw stb libpng libjpeg assimp
WARN    := -std=c11 -Wall -Wextra -Werror -Wshadow -Wstrict-prototypes -Wmissing-prototypes
DEFS    := -D_DEFAULT_SOURCE -D_POSIX_C_SOURCE=200809L -fno-math-errno -ffp-contract=off
OPT     ?= -O3 -g
CFLAGS  += $(WARN) $(DEFS) $(FLOOR) $(OPT) -DRASTTY_DATADIR='"$(PREFIX)/share/rastty"'  $(shell pkg-config --cflags $(PKGS) 2>/dev/null)
# meshoptimizer (mesh level of detail) has no pkg-config file in Debian: its shared library
# brings its own C++ runtime (libstdc++) as a dependency
LDLIBS  += $(shell pkg-config --libs $(PKGS) 2>/dev/null || echo -lncursesw -lstb -lpng16 -ljpeg -lassimp) \
           -lmeshoptimizer -ldraco -lstdc++ -lpthread -lm
# Draco (draco.h) is a C++ library: its one shim, src/scene/draco_shim.cc, is the project's
# only C++ source (no exceptions leave it; it is called in the sandbox's child only)
CXX     ?= g++
CXXFLAGS += -std=c++17 -Wall -Wextra -Werror -D_DEFAULT_SOURCE $(OPT) $(shell pkg-config --cflags draco 2>/dev/null)

# `make V=1` shows full command lines
Q       := $(if $(V),,@)

# One job per core unless the command line says -j (make -j1: one at a time); `make test`
# then builds the plain and the sanitizer trees side by side. Only the top make sets it: the
# sub-makes (asan-build, floor-build) share its job slots.
ifeq ($(MAKELEVEL)$(filter -j%,$(MAKEFLAGS)),0)
MAKEFLAGS += -j$(shell nproc 2>/dev/null || echo 1)
endif

# Layers (README, "The map"): src/LAYER/*.c with its headers in include/LAYER/. A file
# includes its own layer and the layers below it, never above and never a sibling:
#     main.c -> {cmd, viewer, bench} -> cli -> term -> render -> scene -> base
# Each layer compiles with the include paths of exactly those layers, so an include
# against the rule fails the build; `make layers` (tests/layers.py, run by every build)
# also checks that term reaches render only through fb.h and that no includes go round
# in a circle.
LAYERS      := base scene render term cli cmd viewer bench
BELOW_base  :=
BELOW_scene := base
BELOW_render:= scene base
BELOW_term  := render scene base
BELOW_cli   := term render scene base
BELOW_cmd   := cli term render scene base
BELOW_viewer:= cli term render scene base
BELOW_bench := cli term render scene base
layer_inc    = $(foreach l,$(1) $(BELOW_$(1)),-Iinclude/$(l))
ALL_INC     := $(foreach l,$(LAYERS),-Iinclude/$(l))
# The kernels (include/render/kernel.h): one file per instruction set in src/render/kernel/.
# On x86-64 the AVX2 ones are built too (KERNELS_AVX2=no leaves them out: the sanitizer
# build does, the AVX2 kernels' own tests run in the plain build).
KERNELS_AVX2 ?= $(if $(findstring x86_64,$(shell $(CC) -dumpmachine)),yes,no)
AVX2_SRCS := src/render/kernel/kernel_avx2.c src/render/kernel/kernel_avx2_4.c
SRCS    := $(filter-out $(if $(filter yes,$(KERNELS_AVX2)),,$(AVX2_SRCS)),\
                        $(wildcard src/*/*.c src/*/*/*.c)) src/main.c
CXXSRCS := $(wildcard src/*/*.cc)
LIBOBJS := $(patsubst src/%.c,$(BUILD)/obj/%.o,$(filter-out src/main.c,$(SRCS))) \
           $(patsubst src/%.cc,$(BUILD)/obj/%.o,$(CXXSRCS))
MAINOBJ := $(BUILD)/obj/main.o
UNITSRC := $(wildcard tests/unit/*.c)
UNITOBJ := $(patsubst tests/unit/%.c,$(BUILD)/tests/%.o,$(UNITSRC))

# build: the first nine; tests: OSMesa (the oracle), chafa (the glyph fitting's reference),
# tmux and procps (pkill) for the
# end-to-end tests, ncurses-term (xterm-direct terminfo), python3 (asset checks)
DEBIAN_PKGS := build-essential pkg-config libncurses-dev libstb-dev libpng-dev \
               libjpeg62-turbo-dev libassimp-dev libmeshoptimizer-dev libdraco-dev libosmesa6-dev \
               chafa tmux ncurses-term procps python3 groff-base

.PHONY: all layers test unit check-asan asan-build floor-build bench chart deps install uninstall clean help fuzz deb

all: rastty assets

include assets/assets.mk
include tests/oracle/oracle.mk

help:
	@echo "make            build ./rastty"
	@echo "make test       unit + oracle (Mesa) + end-to-end tests, then the same under ASan+UBSan"
	@echo "make layers     the include graph against the layer rule: files per layer, circles"
	@echo "make check-asan unit + end-to-end tests built with -fsanitize=address,undefined"
	@echo "make bench      speed and bytes/frame benchmarks (not a test)"
	@echo "make deb        a Debian package of this build: build/rastty_VERSION_ARCH.deb"
	@echo "make floor-build  the measuring builds of tests/bench_floor.sh (make bench makes them)"
	@echo "make chart      regenerate assets/doc/chart.svg (+ .csv): every method's speed against accuracy"
	@echo "make fuzz       libFuzzer on every parser and decoder (FUZZ_SECONDS=60 each)"
	@echo "make deps       install Debian build/test packages (root) or print the apt-get line"
	@echo "make install    PREFIX=/usr/local: binary, man page, built-in assets"

rastty: $(MAINOBJ) $(BUILD)/librastty.a
	@echo "  LD      $@"
	$(Q)$(CC) $(CFLAGS) $(LDFLAGS) -o $@ $^ $(LDLIBS)

$(BUILD)/librastty.a: $(LIBOBJS)
	@rm -f $@
	$(Q)$(AR) rcs $@ $^

$(foreach l,$(LAYERS),$(eval $(BUILD)/obj/$(l)/%.o: LAYER_INC := $(call layer_inc,$(l))))
$(MAINOBJ): LAYER_INC := $(ALL_INC)
$(BUILD)/obj/render/kernel/kernel.o: KERNEL_FLAGS := $(if $(filter yes,$(KERNELS_AVX2)),-DRASTTY_KERNEL_AVX2)
$(AVX2_SRCS:src/%.c=$(BUILD)/obj/%.o): KERNEL_FLAGS := -mavx2 -mno-fma
$(BUILD)/obj/%.o: src/%.c
	@mkdir -p $(dir $@)
	@echo "  CC      $< $(KERNEL_FLAGS)"
	$(Q)$(CC) $(CFLAGS) $(LAYER_INC) $(KERNEL_FLAGS) -MMD -MP -c -o $@ $<

$(BUILD)/obj/%.o: src/%.cc
	@mkdir -p $(dir $@)
	@echo "  CXX     $<"
	$(Q)$(CXX) $(CXXFLAGS) $(LAYER_INC) -MMD -MP -c -o $@ $<

$(BUILD)/tests/%.o: tests/unit/%.c | $(BUILD)/tests
	@echo "  CC      $<"
	$(Q)$(CC) $(CFLAGS) $(ALL_INC) -Itests/unit -MMD -MP -c -o $@ $<

$(BUILD)/unit-tests: $(UNITOBJ) $(BUILD)/librastty.a
	@echo "  LD      $@"
	$(Q)$(CC) $(CFLAGS) $(LDFLAGS) -o $@ $^ $(LDLIBS)

$(BUILD)/tests:
	@mkdir -p $@

-include $(wildcard $(BUILD)/obj/*.d $(BUILD)/obj/*/*.d $(BUILD)/obj/*/*/*.d $(BUILD)/tests/*.d)

# The whole suite, plain and under ASan+UBSan; tests/run.sh prints one summary line at the end.
test: rastty assets $(BUILD)/unit-tests asan-build oracle-build
	@tests/run.sh --all

unit: $(BUILD)/unit-tests
	$(BUILD)/unit-tests

# The include graph against the layer rule (tests/layers.py; also a suite of make test)
layers:
	@python3 tests/layers.py --report

# Same sources, separate build tree, sanitizers on; tests/run.sh --asan runs what applies.
SAN := -fsanitize=address,undefined,float-cast-overflow -fno-sanitize-recover=all -fno-omit-frame-pointer
asan-build:
	@$(MAKE) --no-print-directory BUILD=build/asan OPT="-O1 -g $(SAN)" LDFLAGS="$(SAN)" \
	    KERNELS_AVX2=no build/asan/unit-tests build/asan/rastty

check-asan: asan-build
	@tests/run.sh --asan

build/asan/rastty: $(BUILD)/librastty.a $(MAINOBJ)
	@echo "  LD      $@"
	$(Q)$(CC) $(CFLAGS) $(LDFLAGS) -o $@ $(MAINOBJ) $(BUILD)/librastty.a $(LDLIBS)

bench: rastty assets oracle-build build/bench/reorder build/bench/gensphere build/bench/genvoxels floor-build
	@tests/bench.sh

# Measuring builds for tests/bench_floor.sh (never installed): the same sources with the
# texture's cache misses taken out, and with interpolation setup done twice (texture.h,
# span.c say how); the difference from ./rastty is what that work costs a frame.
FLOORS := texels setup2
floor-build:
	@$(MAKE) --no-print-directory BUILD=build/floor-texels FLOOR=-DRASTTY_FLOOR_TEXELS \
	    build/floor-texels/rastty
	@$(MAKE) --no-print-directory BUILD=build/floor-setup2 FLOOR=-DRASTTY_FLOOR_SETUP_TWICE \
	    build/floor-setup2/rastty

$(FLOORS:%=build/floor-%/rastty): $(BUILD)/librastty.a $(MAINOBJ)
	@echo "  LD      $@"
	$(Q)$(CC) $(CFLAGS) $(LDFLAGS) -o $@ $(MAINOBJ) $(BUILD)/librastty.a $(LDLIBS)

# does meshoptimizer's vertex-cache / overdraw reordering pay? (tests/bench_lod.sh runs it)
build/bench/reorder: tests/bench/reorder.c $(BUILD)/librastty.a
	@mkdir -p $(dir $@)
	$(Q)$(CC) $(CFLAGS) $(ALL_INC) -o $@ $< $(BUILD)/librastty.a $(LDLIBS)

# the scale benchmark's displaced sphere at any triangle count (tests/bench_scale.sh)
build/bench/gensphere: tests/bench/gensphere.c
	@mkdir -p $(dir $@)
	$(Q)$(CC) $(CFLAGS) -o $@ $< -lm

# the scale benchmark's block world (tests/bench_scale.sh)
build/bench/genvoxels: tests/bench/genvoxels.c
	@mkdir -p $(dir $@)
	$(Q)$(CC) $(CFLAGS) -o $@ $<

# The README's chart: every method on the scene set at 160x96 and 640x480 (several minutes;
# run it on a quiet machine). Shared models from ../shared/models (or RASTTY_SHARED).
chart: rastty assets
	./rastty bench --chart --svg assets/doc/chart.svg --csv assets/doc/chart.csv

# libFuzzer targets for every parser (clang); FUZZ_SECONDS each. See tests/fuzz/README.
FUZZ_SECONDS ?= 60
FUZZ_TARGETS := obj mtl decode scene texture stl ply import
FUZZ_CFLAGS  := -g -O1 -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=all \
                -std=c11 $(DEFS) $(ALL_INC) $(shell pkg-config --cflags $(PKGS) 2>/dev/null)
build/fuzz_%: tests/fuzz/fuzz_%.c tests/fuzz/fuzz_mesh.h tests/fuzz/stb_impl.c $(SRCS)
	@mkdir -p build/fuzz-work/$*
	clang++ -g -O1 -fsanitize=fuzzer-no-link,address,undefined -fno-sanitize=vptr -std=c++17 -D_DEFAULT_SOURCE $(ALL_INC) -c src/scene/draco_shim.cc -o build/fuzz-work/$*/draco_shim.o
	clang $(FUZZ_CFLAGS) $< tests/fuzz/stb_impl.c $(filter-out src/main.c $(AVX2_SRCS),$(SRCS)) build/fuzz-work/$*/draco_shim.o -o $@ $(LDLIBS)
fuzz: $(addprefix build/fuzz_,$(FUZZ_TARGETS))
	@for t in $(FUZZ_TARGETS); do \
	    echo "== fuzz_$$t ($(FUZZ_SECONDS) s)"; \
	    LSAN_OPTIONS=suppressions=tests/fuzz/lsan_assimp.supp \
	    build/fuzz_$$t build/fuzz-work/$$t tests/fuzz/corpus/$$t -max_total_time=$(FUZZ_SECONDS) \
	        -max_len=4096 -print_final_stats=1 2>&1 | grep -E "stat::number_of_executed_units|ERROR|SUMMARY" || exit 1; \
	done

deps:
	@if [ "$$(id -u)" = 0 ]; then \
	    apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq $(DEBIAN_PKGS); \
	else \
	    echo "run as root:  apt-get install -y $(DEBIAN_PKGS)"; \
	fi

install: rastty assets
	install -d $(DESTDIR)$(PREFIX)/bin $(DESTDIR)$(PREFIX)/share/man/man1 \
	    $(DESTDIR)$(PREFIX)/share/rastty
	install -m 755 rastty $(DESTDIR)$(PREFIX)/bin/rastty
	install -m 644 man/rastty.1 $(DESTDIR)$(PREFIX)/share/man/man1/rastty.1
	install -m 644 $(ASSET_FILES) assets/demo.rsc $(DESTDIR)$(PREFIX)/share/rastty/

# A Debian package of this build (dpkg-deb, no network): build/rastty_VERSION_ARCH.deb
deb: rastty assets
	@packaging/mkdeb.sh

uninstall:
	rm -f $(DESTDIR)$(PREFIX)/bin/rastty $(DESTDIR)$(PREFIX)/share/man/man1/rastty.1
	rm -rf $(DESTDIR)$(PREFIX)/share/rastty

clean:
	rm -rf $(BUILD) rastty
