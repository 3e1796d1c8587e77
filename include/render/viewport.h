/* viewport.h: clip space -> window (pixel) coordinates, and the 1/256-pixel snap.
 *
 * The one place these conventions live; the vertex stage (vertex.c), the line drawer
 * (line.c) and setup (setup.c) all call it.
 *   window x = (x/w + 1) * W/2, window y = (1 - y/w) * H/2 (row 0 at the top),
 *   depth    = 0.5 * z/w + 0.5  (NDC z in [-1,1] -> [0,1]).
 *   Pixel (px, py) has its centre at (px + 0.5, py + 0.5).
 *   Snapped positions are window x, y in units of 1/256 pixel (VIEWPORT_SUBPIX_BITS, as
 *   Mesa's llvmpipe FIXED_ORDER 8), rounded to nearest with ties to even (the default
 *   rounding mode, like llvmpipe's lrintf). Snapping decides coverage only (setup.h).
 * w must be > 0: clip.c removes everything behind the near plane first. */
#ifndef RASTTY_VIEWPORT_H
#define RASTTY_VIEWPORT_H

#include <math.h>
#include <stdint.h>

#define VIEWPORT_SUBPIX_BITS 8
#define VIEWPORT_SUBPIX_ONE (1 << VIEWPORT_SUBPIX_BITS)

/* window x, y (pixels, y down) and depth in [0,1] of a clip-space position with w > 0 */
static inline void viewport_window(const double clip[4], int fb_w, int fb_h, double win_out[3])
{
    double rw = 1.0 / clip[3];
    win_out[0] = (clip[0] * rw + 1.0) * 0.5 * fb_w;
    win_out[1] = (1.0 - clip[1] * rw) * 0.5 * fb_h;
    win_out[2] = 0.5 * clip[2] * rw + 0.5;
}

/* a window coordinate in 1/256 pixel, rounded to nearest, ties to even; |win| must stay
 * below 2^42 pixels (the guard band keeps it below 2^15). Adding and subtracting 1.5 * 2^52
 * rounds exactly as nearbyint does in the default rounding mode, without a libm call. */
static inline int64_t viewport_snap(double win)
{
    const double magic = 6755399441055744.0; /* 1.5 * 2^52 */
    double t = win * VIEWPORT_SUBPIX_ONE + magic; /* IEEE arithmetic: never re-associated */
    return (int64_t)(t - magic);
}

#endif
