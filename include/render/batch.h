/* batch.h: the set-up triangle array — what the front end hands to the back end.
 *
 * The front end (pipeline.c: vertex -> clip -> setup) appends, in submission order, one
 * struct setup_tri per triangle that reaches the rasterizer, one struct shade_tri per source
 * triangle (material, texture, flat-shading terms; the pieces of a clipped triangle share
 * it) and the new vertices clipping made. The back end (batch_draw_start, _finish) then
 * rasterizes the triangles in the same order into a rectangle of the framebuffer. The arrays
 * have a fixed capacity, allocated once: when the next source triangle might not fit (or the
 * pipeline's smaller batch size is reached), the pipeline draws the batch and starts a new
 * one (as llvmpipe flushes a full scene), so memory stays bounded on any mesh and the
 * picture never depends on the capacity (a test checks it).
 *
 * With several threads the back end works by screen tile, as llvmpipe does: the batch's
 * triangles are binned into BATCH_TILE x BATCH_TILE tiles (each tile's list in submission
 * order), and the threads take tiles from a shared counter, the tiles with the most
 * triangles first (the longest jobs first: the last tiles, which one thread may finish
 * while the others wait, are the short ones); a thread draws all of a tile's
 * triangles with its own span_ctx, clipped to the tile. The pool's threads start at once
 * and the caller joins when it is done with other work (the pipeline sets up the next batch
 * meanwhile). A pixel belongs to one tile and every pixel's value depends only on its
 * position and the triangles before it, so the frame is the same bytes whatever the thread
 * count (a test checks it). No lock is taken in the pixel path. */
#ifndef RASTTY_BATCH_H
#define RASTTY_BATCH_H

#include <stdatomic.h>
#include <stdbool.h>
#include <stdint.h>

#include "clip.h"
#include "err.h"
#include "raster.h"
#include "setup.h"
#include "shade.h"
#include "span.h"
#include "workers.h"

/* worst case of one source triangle: a clipped polygon of CLIP_MAX_VERTS corners, fanned */
#define BATCH_MIN_CAPACITY CLIP_MAX_VERTS
#define BATCH_DEFAULT_CAPACITY 8192
#define BATCH_TILE 64 /* tile side in pixels, for binning (32 was measured: a triangle of a
                        * 640x480 head crosses a tile edge twice as often, and pays its
                        * interpolation setup in each tile; 64 gave 2 threads 9-12% more) */

struct batch {
    struct setup_tri *tris;
    struct shade_tri *shades;
    struct vertex_out *verts; /* made by clipping; never moved while the batch lives */
    uint32_t n_tris, n_shades, n_verts, cap;
    /* tile bins (drawing with threads): tile t's triangles are
     * bin_tris[bin_start[t] .. bin_start[t + 1]) */
    uint32_t *bin_start, *bin_tris;
    size_t bin_start_cap, bin_tris_cap;
    /* the tiles that hold a triangle, most triangles first (the order threads take them;
     * low 32 bits: the tile) */
    uint64_t *tile_order;
    size_t tile_order_cap;
    /* hit[k * cap + i] = 1 once thread k found a pixel of triangle i (zeroed again by
     * batch_draw_finish) */
    uint8_t *hit;
    size_t hit_cap;
    struct batch_job { /* the drawing in progress (batch_draw_start .. finish) */
        raster_fn raster;
        struct span_ctx *ctx;  /* one per thread */
        int fb_w, fb_h, threads, tiles_x, n_tiles;
        int n_order;           /* tiles in tile_order */
        atomic_int next;       /* the next tile_order entry to hand out */
    } job;
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

/* Rasterize every triangle of the batch, in order, into the fb_w x fb_h framebuffer of the
 * span contexts (thread k uses ctx[k]): when w has no threads, on the calling thread, now;
 * else binned by tile and started on the pool's threads, returning at once — the caller
 * may set up another batch meanwhile, and joins with batch_draw_finish (nothing else may
 * use the pool in between). -1 if memory ran out (e set). */
int batch_draw_start(struct batch *b, raster_fn raster, int fb_w, int fb_h, struct workers *w,
                     struct span_ctx *ctx, struct err *e);
/* Take the tiles not taken yet on this thread (ctx[0]), wait for the pool, and return the
 * number of triangles no thread found a pixel for. */
long batch_draw_finish(struct batch *b, struct workers *w);

#endif
