/* imgdec.h: image file bytes -> RGBA8 texels, safely, within limits.
 *
 * The decoder is chosen by the file's content (magic bytes), never by its name:
 *   PNG        libpng (row by row)           JPEG        libjpeg-turbo (DCT scaling)
 *   PNM P5/P6  rastty's own (8 and 16 bit)   Radiance HDR rastty's own (flat and RLE)
 *   TGA        rastty's own (24/32-bit colour, 8-bit grey; raw and RLE)
 *   other TGA, BMP, PSD, GIF   stb_image, only after its header was read and checked
 * Why: Debian's stb_image reads past its buffer on 16-bit PNM, loops forever on truncated
 * HDR and has undefined behaviour in its JPEG decoder; PNG and JPEG, the formats real models
 * ship, go to the libraries written and fuzzed for them (libjpeg-turbo is also several
 * times faster). The PNM and HDR readers here are small and fuzzed (tests/fuzz/fuzz_texture.c).
 *
 * Limits (rastty(1), LIMITS):
 *   - no image wider or taller than IMGDEC_MAX_INPUT (16384) is decoded;
 *   - images larger than max_side on a side come out box-filtered down by a power of two
 *     (JPEG: the decoder's own 1/2, 1/4, 1/8 scaling) so both sides fit, with a warning;
 *     PNG, JPEG, PNM and HDR are downscaled while decoding, so memory stays near the output
 *     size; TGA/BMP/PSD/GIF (decoded whole) and interlaced PNGs above
 *     IMGDEC_MAX_WHOLE (4096) per side are refused instead;
 *   - a progressive (or multi-scan) JPEG is the exception: libjpeg keeps all its DCT
 *     coefficients at full size whatever the scaling (2 bytes per pixel and component:
 *     768 MiB for 16384^2 4:2:0); it gets that memory when half of MemAvailable holds it,
 *     else it is refused naming its size and the need ("p.jpg: progressive JPEG of
 *     16384x16384 needs 768 MiB to decode, more than half of the ... available");
 *   - a file whose pixel data is shorter than its header's dimensions need is refused
 *     (truncated), before decoding where the format allows it (PNM, flat HDR).
 * HDR images are tone-mapped (Reinhard x/(1+x), then gamma 1/2.2) to 8 bits per channel.
 * Output: row 0 = the image's top row; alpha 255 where the file has none. */
#ifndef RASTTY_IMGDEC_H
#define RASTTY_IMGDEC_H

#include <stddef.h>
#include <stdint.h>

#include "err.h"

#define IMGDEC_MAX_INPUT 16384
#define IMGDEC_MAX_WHOLE 4096

/* What the bytes are, by magic: "PNG image", "JPEG image", ..., or NULL when no image
 * format is recognised (TGA has no magic: NULL). Used for "not a model (JPEG image)". */
const char *imgdec_kind(const uint8_t *data, size_t len);

/* A decoded image: w x h texels, RGBA8, row 0 = the image's top row; rgba is malloc'd (the
 * caller frees it, or a struct texture takes it over: texture.h). */
struct imgdec_image {
    int w, h;
    uint8_t *rgba;
};

/* Decode into out (owned by the caller). name is for messages (already quoted).
 * A downscale adds a warning to w. Errors: "name: reason", -1, out zeroed. */
int imgdec_decode(const uint8_t *data, size_t len, const char *name, int max_side,
                  struct imgdec_image *out, struct warnings *w, struct err *e);

#endif
