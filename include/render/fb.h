/* fb.h: the framebuffer, the one thing the renderer writes and the encoder reads.
 *
 * Exactly the pixels shown: for a terminal of C x R cells it is C*px_w x R*px_h, the glyph
 * set's pixels per cell (cell.h: C x 2R with half blocks). Such pixels need not be square:
 * pixel_aspect is one pixel's width / height on the screen (1 unless the caller sets it), and
 * the projection uses the picture's physical aspect, fb_aspect(). Row 0 is the top row. Colour is 8-bit RGB, quantised once from the
 * shaded float colour c in [0,1] as floor(c*255 + 0.5). Depth: one float per pixel whose
 * meaning the depth method decides (below; the default is window depth, cleared to 1.0,
 * test LESS). The overdraw counter, when present,
 * counts fragments that passed the coverage test (before the depth test) per pixel.
 * The caller allocates once per size change (fb_init) and clears every frame (fb_clear). */
#ifndef RASTTY_FB_H
#define RASTTY_FB_H

#include <math.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "err.h"
#include "pixel.h"

#define FB_MAX_DIM 8192 /* per side; keeps fixed-point edge functions well inside int64 */

/* Depth buffer methods (--depth; the viewer's Z key). Every method keeps one float per pixel
 * in its own measure; the clear value, the test and the "covered" rule below are the only
 * places that know which. Window depth z01 = 0.5 * z_ndc + 0.5.
 *   DEPTH_Z   window depth z01 in float, cleared to 1, test LESS (the default; what GL does).
 *             Cost: one plane evaluation per pixel. Fails far away: z01 ~ 1 - near/D crowds
 *             toward 1, where float steps are 2^-24, so one step spans ~ D^2 * 6e-8 / near
 *             units at distance D (6e-4 units at D = 10 with near 0.01).
 *   DEPTH_W   eye-space depth (view-space w: the distance along the view axis), interpolated
 *             perspective-correctly, cleared to +inf, test LESS. Float keeps the same
 *             relative precision at every distance, so it holds at any far/near ratio. Cost:
 *             a division per pixel. Fails: nothing in range; orthographic cameras store the
 *             same linear measure (their window depth is linear in it).
 *   DEPTH_Z16 window depth as a 16-bit integer round(z01 * 65535) (what early hardware had),
 *             stored exactly in the float, cleared to 65535, test LESS. Fails first: 65536
 *             steps for the whole near..far range, so surfaces a small gap apart z-fight a few
 *             units away: a step spans ~ D^2 * 1.5e-5 / near units at distance D.
 *   DEPTH_RZ  reversed z: 1 - z01 = (w - z) / 2w per vertex, in float, cleared to 0, test
 *             GREATER (near -> 1, far -> 0). Float's dense values near 0 then fall where
 *             perspective depth is coarsest: precision close to DEPTH_W at the cost of Z.
 * A pixel is covered (something was drawn) when its depth differs from the clear value:
 * every test is strict, so a fragment at exactly the clear value can never be written. */
enum depth_mode { DEPTH_Z, DEPTH_W, DEPTH_Z16, DEPTH_RZ, DEPTH_COUNT };

/* What DEPTH_W needs to turn an eye depth back into window depth (and the reverse). */
struct fb_depth_proj {
    int ortho;
    double near, far;
};

struct fb {
    int w, h;
    uint8_t *rgb;       /* w*h*3 */
    float *depth;       /* w*h, in depth_mode's measure */
    uint32_t *overdraw; /* w*h, or NULL when not counted */
    enum depth_mode depth_mode;  /* the caller sets it (and proj) before fb_clear */
    struct fb_depth_proj proj;
    double pixel_aspect; /* a pixel's width / height on the screen; fb_init sets 1 */
};

/* The picture's width / height on the screen: the aspect the projection uses. */
static inline double fb_aspect(const struct fb *fb)
{
    return fb->w * fb->pixel_aspect / fb->h;
}

int fb_init(struct fb *fb, int w, int h, bool count_overdraw, struct err *e);
void fb_free(struct fb *fb);
/* Colour to bg, depth to depth_mode's clear value, overdraw to 0. */
void fb_clear(struct fb *fb, const uint8_t bg[3]);
/* fb_clear of rows y0 .. y1-1 only (the pipeline clears in bands, on every thread) */
void fb_clear_rows(struct fb *fb, const uint8_t bg[3], int y0, int y1);

static inline float fb_depth_clear_value(enum depth_mode m)
{
    return m == DEPTH_W ? INFINITY : m == DEPTH_Z16 ? 65535.0f : m == DEPTH_RZ ? 0.0f : 1.0f;
}

/* The depth test: does a fragment at depth a (the mode's measure) pass against stored b? */
static inline bool fb_depth_passes(enum depth_mode m, float a, float b)
{
    return m == DEPTH_RZ ? a > b : a < b;
}

static inline bool fb_covered(const struct fb *fb, size_t i)
{
    return fb->depth[i] != fb_depth_clear_value(fb->depth_mode);
}

/* Window depth z01 -> the mode's measure (lines, tests; triangles compute theirs in the kernels
 * from per-vertex values, which is the same number up to rounding). */
float fb_depth_encode(const struct fb *fb, double z01);
/* The stored measure of pixel i -> window depth z01 (1 where nothing was drawn): PFM
 * output and the depth view show the same picture whatever the method. */
double fb_depth_window(const struct fb *fb, size_t i);

/* Debug views: replace the colour with a picture of another buffer. */
void fb_show_depth(struct fb *fb);    /* near = white .. far = black, empty = black */
void fb_show_overdraw(struct fb *fb); /* 0 black, 1 blue, 2 green, 3 yellow, 4+ red..white */

#endif
