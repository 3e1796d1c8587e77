/* plan_blend.h: the blended pass — the triangles of alpha BLEND materials (mesh.h: each
 * mesh keeps them after its n_opaque others), drawn after every opaque surface and the sky,
 * back to front.
 *
 * Order: every blended triangle of every item in view, by its centroid's depth (clip w; an
 * orthographic camera's clip z), the farthest first; ties by item, then triangle. A
 * triangle's pixels are tested against the depth the opaque pass left (LESS), not written,
 * and mixed over the framebuffer: src a + dst (1 - a) (kernel_rich_pixel). Sorting by
 * triangle, not by object as many viewers do, keeps two interleaved transparent objects
 * right; it cannot order two triangles that cross each other (no renderer without
 * per-pixel sorting can).
 *
 * Threads: the pass runs on the calling thread alone, after both plans' opaque pass (after
 * the slices are merged), through one front end without a pool, in that one order: the
 * picture is the same bytes at any thread count and split. */
#ifndef RASTTY_PLAN_BLEND_H
#define RASTTY_PLAN_BLEND_H

#include "camera.h"
#include "fb.h"
#include "frontend.h"
#include "kernel.h"
#include "render_opts.h"
#include "scene.h"
#include "span.h"
#include "stats.h"

/* Draw the items' blended triangles into fb (whose opaque pass and sky are done) with front
 * end fe and span context ctx. 0, or -1 (out of memory). */
int plan_blend_draw(struct frontend *fe, struct span_ctx *ctx, const struct kernel_set *ks,
                    const struct draw_item *items, int n_items, const struct camera *cam,
                    const struct render_opts *o, struct fb *fb, mat4 pv,
                    struct frame_stats *stats, struct err *e);

#endif
