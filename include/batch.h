/* batch.h: the set-up triangle array — what the front end hands to the back end.
 *
 * The front end (pipeline.c: vertex -> clip -> setup) appends, in submission order, one
 * struct setup_tri per triangle that reaches the rasterizer, one struct shade_tri per source
 * triangle (material, texture, flat-shading terms; the pieces of a clipped triangle share
 * it) and the new vertices clipping made. The back end (batch_draw) then rasterizes the
 * triangles in the same order into a rectangle of the framebuffer. The arrays have a fixed
 * capacity, allocated once: when the next source triangle might not fit, the pipeline draws
 * the batch and starts a new one (as llvmpipe flushes a full scene), so memory stays bounded
 * on any mesh and the picture never depends on the capacity (a test checks it).
 *
 * Designed for a threaded back end: batch_draw only reads the batch, writes only pixels
 * inside its rectangle, and keeps all per-triangle scratch in its span_ctx, so several
 * workers can each draw a different screen tile of the same batch. */
#ifndef RASTTY_BATCH_H
#define RASTTY_BATCH_H

#include <stdbool.h>
#include <stdint.h>

#include "clip.h"
#include "err.h"
#include "raster.h"
#include "setup.h"
#include "shade.h"
#include "span.h"

/* worst case of one source triangle: a clipped polygon of CLIP_MAX_VERTS corners, fanned */
#define BATCH_MIN_CAPACITY CLIP_MAX_VERTS
#define BATCH_DEFAULT_CAPACITY 8192

struct batch {
    struct setup_tri *tris;
    struct shade_tri *shades;
    struct vertex_out *verts; /* made by clipping; never moved while the batch lives */
    uint32_t n_tris, n_shades, n_verts, cap;
};

/* cap (>= BATCH_MIN_CAPACITY) triangles, shading records and clip vertices */
int batch_init(struct batch *b, uint32_t cap, struct err *e);
void batch_free(struct batch *b);
static inline void batch_reset(struct batch *b)
{
    b->n_tris = b->n_shades = b->n_verts = 0;
}
/* Is there room for one more source triangle, whatever clipping makes of it? */
static inline bool batch_has_room(const struct batch *b)
{
    return b->n_tris + CLIP_MAX_VERTS <= b->cap && b->n_shades < b->cap &&
           b->n_verts + CLIP_MAX_VERTS <= b->cap;
}

/* Rasterize every triangle of the batch, in order, inside r. */
void batch_draw(const struct batch *b, raster_fn raster, struct raster_rect r, struct span_ctx *s);

#endif
