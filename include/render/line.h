/* line.h: wireframe lines — clip, project, Bresenham.
 *
 * In:  a segment in clip space (two x,y,z,w), a colour, whether to depth-test.
 * Steps: clip in 3D against near (z >= -w) and far (z <= w), so geometry behind the eye never
 *        projects; perspective divide and viewport (viewport.h); Cohen-Sutherland against
 *        the viewport rectangle [0,W] x [0,H] in window coordinates; endpoints become the pixels
 *        containing them; integer Bresenham, all 8 octants, both endpoints drawn.
 * A segment is always walked from the endpoint with the smaller (y, x), so an edge shared by
 * two triangles (given in opposite directions) lights exactly the same pixels.
 * Depth (window depth, linear along the line in screen space) is tested, not written:
 * a line pixel shows unless the stored surface is strictly nearer than the line's depth
 * moved toward the eye by a small bias (1% of 1 - depth, at least 1e-5), compared in the
 * depth method's own measure (fb.h); edges lying on a surface stay visible while those behind
 * it are hidden. */
#ifndef RASTTY_LINE_H
#define RASTTY_LINE_H

#include <stdint.h>

#include "fb.h"

/* Draw a clip-space segment. Returns the number of pixels written. */
int line_draw_clip(struct fb *fb, const double a[4], const double b[4], const uint8_t rgb[3],
                   int depth_test);
/* Draw between two pixels (any coordinates; pixels outside fb are skipped). Depth z0/z1 as
 * above; depth_test 0 ignores them. Returns the number of pixels written. */
int line_draw_px(struct fb *fb, int x0, int y0, float z0, int x1, int y1, float z1,
                 const uint8_t rgb[3], int depth_test);

#endif
