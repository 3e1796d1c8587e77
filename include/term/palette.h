/* palette.h: terminal colour modes and mapping 24-bit RGB onto them.
 *
 * Owns the colour tables the encoder emits and the decoder reads back, so both sides agree:
 *  - xterm 256: 0..15 = the 16 ANSI colours below, 16..231 = 6x6x6 cube with channel levels
 *    0,95,135,175,215,255 (index 16 + 36r + 6g + b), 232..255 = greys 8,18,..,238.
 *    palette_nearest_256 only returns 16..255: 0..15 are redefined by many themes, so we
 *    never rely on their RGB.
 *  - 16 colours: xterm's default RGB for SGR 30-37/90-97 (a theme may differ; the decoder
 *    assumes these).
 *  - none: a 10-step ASCII luminance ramp " .:-=+*#%@" (light on dark). Level L shows grey
 *    round(L*255/9); luma is Rec.709 in integers: (54R + 183G + 19B) >> 8.
 * Metric: "redmean" (a weighted Euclidean RGB distance whose weights follow the mean red of
 * the two colours; www.compuphase.com/cmetric.htm), exact in integers. It is cheap and much
 * closer to perception than plain RGB distance. Nearest = smallest distance, ties to the
 * lowest index. The fast 256 search is exact: for a fixed red level the weights are fixed and
 * the cube separates per channel (nearest green and blue level), so it tries the 2 red levels
 * around the colour plus the 3 greys around its weighted mean (5 candidates, not 240); it
 * equals the brute-force reference on all 2^24 colours (checked once, 20 s; the unit test
 * samples).
 * Callers: encode.c (quantise), decode.c (index -> RGB), termcaps.c (mode enum). */
#ifndef RASTTY_PALETTE_H
#define RASTTY_PALETTE_H

#include <stdint.h>

#include "err.h"

enum palette_mode { PALETTE_NONE, PALETTE_16, PALETTE_256, PALETTE_TRUECOLOR, PALETTE_MODE_COUNT };

/* Largest per-channel error |c - rgb(nearest(c))| over all 2^24 colours (checked by
 * test_palette over every colour). Redmean sometimes prefers a grey to a far cube corner,
 * which is why this is above the cube's widest half-gap (47). */
#define PALETTE_256_MAX_ERR 69
#define PALETTE_16_MAX_ERR 140
/* Ordered dithering (4x4 Bayer) adds at most this much to a channel before quantising. */
#define PALETTE_DITHER_AMP 19

#define PALETTE_RAMP " .:-=+*#%@"
#define PALETTE_RAMP_LEVELS 10

/* "none", "16", "256", "truecolor". */
const char *palette_mode_name(enum palette_mode mode);
/* Accepts none, 16, 256, truecolor, 24bit (case-insensitive); else -1 naming the value. */
int palette_mode_parse(const char *s, enum palette_mode *mode_out, struct err *e);

/* RGB of xterm colour index 0..255. */
void palette_rgb(int index, uint8_t rgb_out[3]);
/* Redmean distance (squared, weighted); 0 iff equal. */
uint32_t palette_dist(const uint8_t a[3], const uint8_t b[3]);
/* Nearest of 16..255 (cube + greys). */
int palette_nearest_256(const uint8_t rgb[3]);
/* Brute force over 16..255: the reference the fast search is tested against. */
int palette_nearest_256_ref(const uint8_t rgb[3]);
/* Nearest of the 16 ANSI colours, 0..15. */
int palette_nearest_16(const uint8_t rgb[3]);
/* Ordered-dither offset for pixel (x, y), in [-PALETTE_DITHER_AMP, PALETTE_DITHER_AMP]. */
int palette_dither(int x, int y);

/* Rec.709 luma 0..255, and the none-mode ramp. */
static inline int palette_luma(const uint8_t rgb[3])
{
    return (54 * rgb[0] + 183 * rgb[1] + 19 * rgb[2]) >> 8;
}
static inline int palette_ramp_level(int luma) /* 0..255 -> 0..PALETTE_RAMP_LEVELS-1 */
{
    return (luma * (PALETTE_RAMP_LEVELS - 1) + 127) / 255;
}
static inline uint8_t palette_ramp_grey(int level)
{
    return (uint8_t)((level * 255 + (PALETTE_RAMP_LEVELS - 1) / 2) / (PALETTE_RAMP_LEVELS - 1));
}

#endif
