/* line.h: wireframe lines — clip, project, Bresenham.
 *
 * In:  a segment in clip space (two x,y,z,w), a colour, whether to depth-test.
 * Steps: clip in 3D against near (z >= -w) and far (z <= w), so geometry behind the eye never
 *        projects; perspective divide and viewport (vertex_window); Cohen-Sutherland against
 *        the viewport rectangle [0,W] x [0,H] in window coordinates; endpoints become the pixels
 *        containing them; integer Bresenham, all 8 octants, both endpoints drawn.
 * A segment is always walked from the endpoint with the smaller (y, x), so an edge shared by
 * two triangles (given in opposite directions) lights exactly the same pixels.
 * Depth (window depth, linear along the line in screen space) is tested, not written:
 * a line pixel shows when depth <= stored depth + LINE_DEPTH_BIAS(depth), which keeps edges
 * lying on a surface visible while hiding those behind it. */
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
