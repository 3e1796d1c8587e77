/* fb.h: the framebuffer, the one thing the renderer writes and the encoder reads.
 *
 * Exactly the pixels shown: for a terminal of C x R cells it is C x 2R (each cell shows a top
 * and a bottom pixel). Row 0 is the top row. Colour is 8-bit RGB, quantised once from the
 * shaded float colour c in [0,1] as floor(c*255 + 0.5). Depth is float window depth in [0,1]
 * (0.5 * z_ndc + 0.5), cleared to 1.0, test LESS. The overdraw counter, when present,
 * counts fragments that passed the coverage test (before the depth test) per pixel.
 * The caller allocates once per size change (fb_init) and clears every frame (fb_clear). */
#ifndef RASTTY_FB_H
#define RASTTY_FB_H

#include <stdbool.h>
#include <stdint.h>

#include "err.h"

#define FB_MAX_DIM 8192 /* per side; keeps fixed-point edge functions well inside int64 */

struct fb {
    int w, h;
    uint8_t *rgb;       /* w*h*3 */
    float *depth;       /* w*h */
    uint32_t *overdraw; /* w*h, or NULL when not counted */
};

int fb_init(struct fb *fb, int w, int h, bool count_overdraw, struct err *e);
void fb_free(struct fb *fb);
/* Colour to bg, depth to 1, overdraw to 0. */
void fb_clear(struct fb *fb, const uint8_t bg[3]);

/* Debug views: replace the colour with a picture of another buffer. */
void fb_show_depth(struct fb *fb);    /* near = white .. far = black, empty = black */
void fb_show_overdraw(struct fb *fb); /* 0 black, 1 blue, 2 green, 3 yellow, 4+ red..white */

static inline uint8_t fb_quantize(float c)
{
    c = c > 0 ? (c < 1 ? c : 1) : 0; /* NaN -> 0: converting NaN to an integer is undefined */
    return (uint8_t)(c * 255.0f + 0.5f);
}

#endif
