/* texture.h: decoded images and how the pipeline samples them.
 *
 * Owns: texel storage (RGBA8, row 0 = the image's top row, as the file stores it).
 * Loading goes through stb_image (PNG, JPG, TGA, BMP, GIF, PSD, PNM, HDR). HDR images are
 * tone-mapped at load time with Reinhard (x / (1 + x)) followed by a 1/2.2 gamma, so they
 * become ordinary display-referred 8-bit texels like every other texture.
 *
 * Sampling conventions (shared with the reference renderer):
 *   - OBJ v = 1 is the image's top row, v = 0 its bottom edge.
 *   - texel (i, j) (j counted from the BOTTOM row) has its centre at ((i+0.5)/W, (j+0.5)/H).
 *   - wrap = repeat in both directions.
 *   - nearest: texel floor(u*W), floor(v*H); bilinear: the 4 texels around (u*W-0.5, v*H-0.5),
 *     weighted by the fractional parts. No mipmaps.
 *   - results are in [0,1] per channel (texel / 255). */
#ifndef RASTTY_TEXTURE_H
#define RASTTY_TEXTURE_H

#include <stdint.h>

#include "err.h"

struct texture {
    int w, h;
    uint8_t *rgba; /* w*h*4 bytes, row-major, row 0 = top of the image */
};

enum tex_filter { TEX_NEAREST, TEX_BILINEAR, TEX_FILTER_COUNT };

/* Decode an image file; on failure fills e with "path: reason" and returns -1. */
int texture_load(const char *path, struct texture *out, struct err *e);
/* Wrap caller-made texels (copied). */
int texture_from_rgba(int w, int h, const uint8_t *rgba, struct texture *out, struct err *e);
void texture_free(struct texture *t);

/* Sample at (u, v) with the filter; writes rgb in [0,1]. */
void texture_sample(const struct texture *t, enum tex_filter f, float u, float v, float rgb_out[3]);

#endif
