/* pipeline.h: draw one frame — the only entry point from the application into rendering.
 *
 *   for each draw item (a mesh placed by a model matrix):
 *       whole-mesh frustum cull by bounding sphere
 *       vertex.c  : each unique vertex once -> clip position, outcode, varyings
 *       for each triangle:
 *           trivial reject (all corners outside one frustum plane)
 *           clip.c   : polygon clipping, only when outcodes say a corner is outside the
 *                      near/far planes or the x/y guard band
 *           setup.c  : perspective divide, viewport, 1/256-pixel snap, cull, edge equations
 *           raster.c : pixels inside (tie rule), depth test, shade.c colour, write
 *   wire mode: line.c instead of setup/raster.
 *   skybox.c: the sky fills the pixels no triangle covered (cheaper than drawing it first)
 *
 * Owns: per-frame scratch (vertex outputs), grown as needed and reused across frames, so a
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
void pipeline_destroy(struct pipeline *p);

/* Clear fb to the background, draw the items, then the sky (if any) where nothing was
 * drawn, then the debug view. Returns 0, or -1 (out of memory). */
int pipeline_draw(struct pipeline *p, const struct draw_item *items, int n_items,
                  const struct skybox *sky, const struct camera *cam,
                  const struct render_opts *o, struct fb *fb, struct frame_stats *stats_out,
                  struct err *e);

#endif
