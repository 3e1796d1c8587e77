/* plan_tiles.h: a frame by screen tiles (SPLIT_TILES, render_opts.h; llvmpipe's way) — the
 * calling thread runs the front end (frontend.h) over every draw item while the pool draws
 * the set-up triangles by 64x64 screen tile (batch.h), one batch while the front end fills
 * the next. One thread: the front end and the back end take turns, a batch at a time.
 *
 *   clear (every thread, in bands)
 *   wire frames: the sky first (no surface colour to keep)
 *   pass 1, the surfaces (wire: depth only, when hidden lines are asked): per item, whole-
 *     mesh culling, its level of detail, the front end as its triangles need the vertex
 *     stage; then the last batch, and the sky where the surfaces left room
 *   pass 2, the edges (wire, or the wire-overlay view): per item its vertices (pass 1's, or
 *     the vertex stage on every thread) and frontend_edges, depth-tested against pass 1
 * What it costs at terminal sizes: a dense mesh is mostly front end, which stays on one
 * thread. Owns the front end and a span context per thread, kept across frames. */
#ifndef RASTTY_PLAN_TILES_H
#define RASTTY_PLAN_TILES_H

#include "frontend.h"
#include "plan_blend.h"

struct plan_tiles {
    struct frontend fe;
    struct span_ctx *ctx; /* one per thread, each on cache lines of its own */
    int n_ctx;
};

int plan_tiles_init(struct plan_tiles *t, uint32_t batch_cap, struct err *e);
void plan_tiles_free(struct plan_tiles *t);
/* The frame (pipeline_draw's arguments; w: the pool, which draws with this thread; pv:
 * projection x view) up to, not including, the debug views. 0, or -1 with e set. */
int plan_tiles_draw(struct plan_tiles *t, struct workers *w, const struct kernel_set *ks,
                    const struct draw_item *items, int n_items, const struct skybox *sky,
                    const struct camera *cam, const struct render_opts *o, struct fb *fb,
                    mat4 pv, struct frame_stats *stats, struct err *e);

#endif
