/* raster.h: walk a set-up triangle's pixels — coverage, depth test, shading, writes.
 *
 * In:  struct setup_tri (setup.h), shading context and per-triangle constants (shade.h).
 * Out: framebuffer colour, depth and overdraw counts; pixel counts into stats.
 * Method: half-space edge functions over the triangle's bounding box (already clipped to the
 * framebuffer), stepped incrementally with exact 64-bit integers; a pixel is inside when all
 * three (tie-biased) edge values are >= 0. Depth test LESS happens before any varying is
 * interpolated, so hidden fragments cost only the depth compare.
 * shade == SHADE_WIRE draws depth only (the hidden-line pre-pass). */
#ifndef RASTTY_RASTER_H
#define RASTTY_RASTER_H

#include "fb.h"
#include "render.h"
#include "setup.h"
#include "shade.h"

void raster_triangle(const struct setup_tri *t, const struct shade_ctx *c,
                     const struct shade_tri *st, struct fb *fb, struct frame_stats *stats);

#endif
