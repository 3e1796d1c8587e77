/* cellfit.h: pixels -> cells, the encoder's first pass: what each terminal cell should show.
 *
 * For every cell of a frame, the colours as the terminal will really show them (palette.h:
 * truecolor as they are, 256/16 the nearest palette colour, none a ramp level), written into
 * the screen's `target` cells; encode.c then decides which cells to send and how (encode.h
 * has the picture and the byte format). Palette searches are memoised in the screen's caches
 * (pure caches: they never change the result).
 * Packed colours are 0xIIRRGGBB (encode_screen.h, struct encode_cell). */
#ifndef RASTTY_CELLFIT_H
#define RASTTY_CELLFIT_H

#include <stdint.h>
#include <string.h>

#include "encode_screen.h"

static inline uint32_t cellfit_pack(const uint8_t *px)
{
    return (uint32_t)px[0] << 16 | (uint32_t)px[1] << 8 | px[2];
}

static inline unsigned cellfit_chan(uint32_t c, int k) /* k = 0 red, 1 green, 2 blue */
{
    return (c >> (16 - 8 * k)) & 255;
}

/* The terminal's own colours, as the decoder shows them: its background (braille's, where no
 * dot is; none mode's dark) and its foreground (none mode's ink). The II byte keeps them apart
 * from any colour an SGR sets. */
#define CELLFIT_TERM_BG 0xFD000000u /* black */
#define CELLFIT_TERM_FG 0xFEE5E5E5u /* 229 grey */

/* none mode, with a coverage (encode_opts.cover): what a model covers is drawn with at
 * least CELLFIT_MONO_FLOOR of ink (its luminance range, 2nd to 98th percentile, stretched
 * onto FLOOR..255), the rest (sky, background) at CELLFIT_MONO_SKY / 256 of its level. */
#define CELLFIT_MONO_FLOOR 64
#define CELLFIT_MONO_SKY 32

/* Cell c in canonical form (encode_screen.h): one colour is mask 0; two colours have bit 0 set,
 * unless fg_only (braille keeps its background in bot); `full` = every pixel's bit. */
static inline struct encode_cell cellfit_canon(struct encode_cell c, unsigned full, bool fg_only)
{
    if (c.mask == 0 || c.mask == full || c.top == c.bot) {
        uint32_t x = c.mask == 0 ? c.bot : c.top;
        if (fg_only && c.mask != 0 && c.top != c.bot) /* every dot: still dots on the bg */
            return c;
        return (struct encode_cell){x, x, 0};
    }
    if (!fg_only && !(c.mask & 1))
        return (struct encode_cell){c.bot, c.top, c.mask ^ full};
    return c;
}

/* One pixel as the terminal will show it in a palette mode. The nearest-colour search costs
 * ~30 ns, so results are memoised in the screen's direct-mapped cache (key = RGB | mode << 24;
 * a pure function of the key, so entries never go stale). Dithered pixels bypass it. */
static inline uint32_t cellfit_quant(struct encode_screen *s, enum palette_mode mode,
                                     const uint8_t *px, int x, int y, bool dither)
{
    uint8_t q[3];
    uint32_t *slot = NULL, key = 0;
    if (dither) {
        int d = palette_dither(x, y);
        for (int k = 0; k < 3; k++) {
            int v = px[k] + d;
            q[k] = (uint8_t)(v < 0 ? 0 : v > 255 ? 255 : v);
        }
    } else {
        key = cellfit_pack(px) | (uint32_t)mode << 24;
        slot = s->qcache + 2 * ((key * 2654435761u) >> (32 - ENCODE_QCACHE_BITS));
        if (slot[0] == key)
            return slot[1];
        memcpy(q, px, 3);
    }
    int idx = mode == PALETTE_256 ? palette_nearest_256(q) : palette_nearest_16(q);
    uint8_t shown[3];
    palette_rgb(idx, shown);
    uint32_t out = (uint32_t)idx << 24 | cellfit_pack(shown);
    if (slot) {
        slot[0] = key;
        slot[1] = out;
    }
    return out;
}

/* Fill s->target from the w x h frame (see encode_frame for the sizes). */
void cellfit_frame(struct encode_screen *s, const uint8_t *rgb, int w, int h,
                   const struct encode_opts *o);

#endif
