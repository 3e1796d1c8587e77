/* pipeline.h: draw one frame — the only entry point from the application into rendering.
 *
 *   front end, for each draw item (a mesh placed by a model matrix):
 *       whole-mesh frustum cull by bounding sphere
 *       vertex.c  : each unique vertex once -> clip position, outcode, window position
 *                   snapped to 1/256 px (viewport.h), in chunks just before the first
 *                   triangle that uses them; varyings (and Gouraud's lighting) once a
 *                   triangle using the vertex passes setup
 *       for each triangle:
 *           trivial reject (all corners outside one frustum plane)
 *           setup.c  : facing and culling, once per source triangle
 *           clip.c   : polygon clipping, only when outcodes say a corner is outside the
 *                      near/far planes or the x/y guard band
 *           setup.c  : edge equations and the tie rule, per triangle or clipped piece
 *           -> batch.h: the array of set-up triangles
 *   back end, every 1024 set-up triangles on one thread (512 with threads, drawn by the
 *   pool while the front end fills the other of two batches) and at the end of the
 *   surfaces (batch_draw_start / batch_draw_finish):
 *       raster*.c : the chosen rasterizer finds each triangle's covered pixels as runs
 *       span.c    : per triangle, its queued runs — interpolation setup once it has any,
 *                   then per pixel depth test, interpolation (perspective method), shade.h
 *                   colour, write
 *   skybox.c: the sky fills the pixels no triangle covered (cheaper than drawing it first)
 *   wire mode, and the wire-overlay view: line.c draws the edges after the surfaces.
 *
 * Owns: per-item vertex outputs and the batch, allocated once and reused across frames, so a
 * frame performs no allocation once the largest mesh has been seen. Not thread-safe: one
 * struct pipeline per thread of drawing. */
#ifndef RASTTY_PIPELINE_H
#define RASTTY_PIPELINE_H

#include "camera.h"
#include "err.h"
#include "fb.h"
#include "mesh.h"
#include "render.h"
#include "skybox.h"

struct draw_item {
    const struct mesh *mesh;
    mat4 model;                              /* object -> world */
    const struct texture *texture_override;  /* --texture: replaces every map_Kd; or NULL */
    const float *kd_override;                /* replaces every material's kd; or NULL */
};

struct pipeline;

struct pipeline *pipeline_new(void);
/* The same with a batch of the given capacity (tests: the picture must not depend on it). */
struct pipeline *pipeline_new_batch(uint32_t batch_capacity);
void pipeline_destroy(struct pipeline *p);

/* Clear fb to the background, draw the items, then the sky (if any) where nothing was
 * drawn, then the debug view. Returns 0, or -1 (out of memory). */
int pipeline_draw(struct pipeline *p, const struct draw_item *items, int n_items,
                  const struct skybox *sky, const struct camera *cam,
                  const struct render_opts *o, struct fb *fb, struct frame_stats *stats_out,
                  struct err *e);

#endif
