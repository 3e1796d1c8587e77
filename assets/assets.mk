# assets/assets.mk: rastty's built-in assets, generated (never copied) by assets/generate.c.
# Included by the top-level Makefile. Provides:
#   ASSET_FILES             every generated file; all live in assets/ and are not committed
#   build/generate-assets   the generator: a build tool using libc, libm and stb only (not src/)
#   assets                  phony: (re)generate ASSET_FILES when the generator's sources change
#   check-assets            phony: tests/assets_check.sh (counts, watertightness, orientation,
#                           image sizes, cubemap seams, byte-identical reruns)
# The generator is deterministic, so regenerating only rewrites the same bytes.
ASSET_NAMES := teapot.obj teapot.mtl cube.obj cube.mtl sphere.obj sphere.mtl \
               torus.obj torus.mtl floor.obj floor.mtl \
               checker.png brick.png uvgrid.png stripes.png \
               sky_posx.png sky_negx.png sky_posy.png sky_negy.png sky_posz.png sky_negz.png
ASSET_FILES := $(addprefix assets/,$(ASSET_NAMES))

ASSET_GEN        := build/generate-assets
ASSET_GEN_SRCS   := assets/generate.c $(wildcard assets/gen/*.c)
ASSET_GEN_CFLAGS := -std=c11 -Wall -Wextra -Werror -Wshadow -Wstrict-prototypes \
                    -Wmissing-prototypes -D_DEFAULT_SOURCE -O2 \
                    $(shell pkg-config --cflags stb 2>/dev/null || echo -I/usr/include/stb)
ASSET_GEN_LIBS   := $(shell pkg-config --libs stb 2>/dev/null || echo -lstb) -lm

$(ASSET_GEN): $(ASSET_GEN_SRCS) $(wildcard assets/gen/*.h) assets/assets.mk
	@mkdir -p $(dir $@)
	$(CC) $(ASSET_GEN_CFLAGS) -o $@ $(ASSET_GEN_SRCS) $(ASSET_GEN_LIBS)

# One run writes all of them (grouped target, GNU make >= 4.3).
$(ASSET_FILES) &: $(ASSET_GEN)
	$(ASSET_GEN) assets

.PHONY: assets check-assets
assets: $(ASSET_FILES)

check-assets: $(ASSET_FILES)
	tests/assets_check.sh assets $(ASSET_GEN)
