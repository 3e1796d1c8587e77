/* pixel.h: a shaded float colour channel to the 8-bit value the framebuffer stores — the
 * conventions' floor(c * 255 + 0.5) of c clamped to [0, 1], in one place (the framebuffer,
 * the per-pixel kernels and the procedural sky all quantise with it). */
#ifndef RASTTY_PIXEL_H
#define RASTTY_PIXEL_H

#include <stdint.h>

static inline uint8_t pixel_quantize(float c)
{
    c = c > 0 ? c : 0; /* NaN -> 0 too: converting NaN to an integer is undefined */
    c = c < 1 ? c : 1; /* two branch-free min/max instructions */
    return (uint8_t)(int)(c * 255.0f + 0.5f);
}

#endif
