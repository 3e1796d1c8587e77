/* cellfit.h: pixels -> cells, the encoder's first pass: what each terminal cell should show.
 *
 * For every cell of a frame, the colours as the terminal will really show them (palette.h:
 * truecolor as they are, 256/16 the nearest palette colour, none a ramp level), written into
 * the screen's `target` cells; encode.c then decides which cells to send and how (encode.h
 * has the picture and the byte format). Palette searches are memoised in the screen's caches
 * (pure caches: they never change the result).
 * Packed colours are 0xIIRRGGBB (encode.h, struct encode_cell). */
#ifndef RASTTY_CELLFIT_H
#define RASTTY_CELLFIT_H

#include <stdint.h>
#include <string.h>

#include "encode.h"

static inline uint32_t cellfit_pack(const uint8_t *px)
{
    return (uint32_t)px[0] << 16 | (uint32_t)px[1] << 8 | px[2];
}

static inline unsigned cellfit_chan(uint32_t c, int k) /* k = 0 red, 1 green, 2 blue */
{
    return (c >> (16 - 8 * k)) & 255;
}

/* Fill s->target from the w x h frame (see encode_frame for the sizes). */
void cellfit_frame(struct encode_screen *s, const uint8_t *rgb, int w, int h,
                   const struct encode_opts *o);
/* One colour as a palette mode shows it (256 or 16), dithered for pixel (x, y) when asked. */
uint32_t cellfit_quant(struct encode_screen *s, enum palette_mode mode, const uint8_t *px, int x,
                       int y, bool dither);

#endif
