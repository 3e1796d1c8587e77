/* plan_slices.h: a frame by slices of its triangles (SPLIT_SLICES, render_opts.h) — thread k
 * takes the k-th run of the frame's triangles (in submission order) through the whole
 * pipeline, front end (frontend.h) and back end, into a framebuffer of its own; the
 * framebuffers are then merged pixel by pixel, the nearer fragment winning and on a tie the
 * earlier slice — which is what one thread drawing every slice in turn keeps, since the
 * depth test is strict — so the bytes are one thread's.
 *
 *   the meshes and their levels of detail chosen once, the frame's triangles counted
 *   every slice on its thread: clear, front end and back end for triangles cut[k] ..
 *     cut[k+1] of the frame (the vertex stage from the lowest vertex they use)
 *   the cuts moved toward slices of equal time (they never change a picture)
 *   the framebuffers merged by depth, in bands of rows on every thread; the sky after
 * Surfaces only: wireframe, the wire-overlay view and the overdraw count go by tiles
 * (pipeline.c chooses). Owns a front end, a span context, a framebuffer and the results of
 * each slice, each slice on cache lines of its own (a slice's thread alone writes them). */
#ifndef RASTTY_PLAN_SLICES_H
#define RASTTY_PLAN_SLICES_H

#include "frontend.h"
#include "plan_blend.h"

struct plan_slice {
    _Alignas(64) struct frontend fe;
    struct span_ctx ctx;
    struct fb fb;            /* slice k > 0 draws here; slice 0 into the frame's */
    struct frame_stats st;   /* its counts */
    struct err err;
    int rc;
    double ms;               /* how long it took */
};

struct plan_slices {
    struct plan_slice *slice;
    int n;
    uint32_t batch_cap;
    const struct mesh **mesh; /* the frame's meshes at their levels (NULL: not drawn) */
    int mesh_cap;
    /* where the slices end, as fractions of the frame's triangles (slice k: cut[k] ..
     * cut[k+1]), moved after each frame toward equal times (balance) */
    double cut[WORKERS_MAX + 2];
    double step[WORKERS_MAX + 2]; /* how far cut k may move next */
    int dir[WORKERS_MAX + 2];     /* which way it moved last: -1, 0, 1 */
    uint64_t tris; /* the triangle count the cuts were made for */
};

void plan_slices_init(struct plan_slices *s, uint32_t batch_cap);
void plan_slices_free(struct plan_slices *s);
/* The frame's surfaces and sky (pipeline_draw's arguments; w: the pool, which draws with this
 * thread, a slice each; pv: projection x view). 0, or -1 with e set. */
int plan_slices_draw(struct plan_slices *s, struct workers *w, const struct kernel_set *ks,
                     const struct draw_item *items, int n_items, const struct skybox *sky,
                     const struct camera *cam, const struct render_opts *o, struct fb *fb,
                     mat4 pv, struct frame_stats *stats, struct err *e);

#endif
