/* plan_tiles.c: a frame by screen tiles (see plan_tiles.h). */
#include "plan_tiles.h"

#include <assert.h>
#include <stdlib.h>
#include <string.h>

int plan_tiles_init(struct plan_tiles *t, uint32_t batch_cap, struct err *e)
{
    memset(t, 0, sizeof *t);
    return frontend_init(&t->fe, batch_cap, e);
}

void plan_tiles_free(struct plan_tiles *t)
{
    frontend_free(&t->fe);
    free(t->ctx);
    memset(t, 0, sizeof *t);
}

/* a span context for each of n threads (kept until another count is asked) */
static int contexts(struct plan_tiles *t, int n, struct err *e)
{
    if (n == t->n_ctx)
        return 0;
    free(t->ctx);
    t->n_ctx = 0;
    t->ctx = aligned_alloc(64, (size_t)n * sizeof *t->ctx); /* (whole lines each) */
    if (!t->ctx)
        return err_set(e, "out of memory for %d threads", n);
    memset(t->ctx, 0, (size_t)n * sizeof *t->ctx);
    t->n_ctx = n;
    return 0;
}

int plan_tiles_draw(struct plan_tiles *t, struct workers *w, const struct kernel_set *ks,
                    const struct draw_item *items, int n_items, const struct skybox *sky,
                    const struct camera *cam, const struct render_opts *o, struct fb *fb,
                    mat4 pv, struct frame_stats *stats, struct err *e)
{
    const int threads = workers_count(w) + 1;
    if (contexts(t, threads, e))
        return -1;
    frame_clear(w, fb, o->background);
    /* the frame's state is ~11 KB: on the heap, so a 64 KiB stack (ulimit -s 64) holds the
     * whole call chain */
    struct frame *f = malloc(sizeof *f);
    if (!f)
        return err_set(e, "out of memory for a frame");
    frame_init(f, cam, o, ks, fb, stats);
    frontend_begin(&t->fe, f, w, t->ctx, threads);
    const bool wire = f->span.mode == SHADE_WIRE;
    const bool show_sky = sky && (o->view == VIEW_COLOR || o->view == VIEW_WIRE_OVERLAY);

    /* wire frames have no surface colour: the sky goes everywhere, before anything else */
    if (show_sky && wire)
        frame_sky(w, f->k, sky, cam, fb);
    /* pass 1: surfaces (wire: depth only, for hidden lines), through the batch; pass 2:
     * edges, depth-tested against every item's surfaces when asked */
    bool pass1 = !wire || o->hidden_lines;
    bool pass2 = wire || o->view == VIEW_WIRE_OVERLAY;
    struct frame_stats pre = {0}; /* the hidden-line pre-pass: its counts are not the frame's */
    if (wire)
        f->stats = &pre;
    for (int pass = 1; pass <= 2; pass++) {
        if ((pass == 1 && !pass1) || (pass == 2 && !pass2))
            continue;
        /* a culled item is counted once: by the first pass that looks at it */
        bool counts = pass == 1 || !pass1;
        for (int it = 0; it < n_items; it++) {
            const struct draw_item *item = &items[it];
            const struct mesh *m = item->mesh;
            if (m->n_tris == 0)
                continue;
            frame_item(f, item, pv);
            double scale = frame_item_scale(item->model);
            if (frame_item_outside(item, f->u.mvp, scale, counts, stats))
                continue;
            if (!frontend_item_verts(&t->fe, it, m->n_verts, e)) /* (the item's record) */
                goto fail;
            if (counts) /* once a frame: a background build may add levels meanwhile */
                t->fe.items[it].level = frame_item_level(item, cam, fb->w, fb->h, o, scale, stats);
            m = t->fe.items[it].level;
            /* room for the mesh in full (or the cluster hierarchy's, which has more):
             * changing levels never allocates (a batch the pool is drawing points into
             * earlier items' arrays only) */
            struct vertex_out *vo = frontend_item_verts(
                &t->fe, it, m->n_verts > item->mesh->n_verts ? m->n_verts : item->mesh->n_verts, e);
            if (!vo)
                goto fail;
            /* pass 1 runs the vertex stage as its triangles need it (the front end), on
             * the calling thread, also while the pool draws; pass 2 reuses pass 1's
             * vertices, or runs the stage on every thread when there was no pass 1 */
            if (pass == 2 && !pass1)
                frame_vertices(w, f->k, m, &f->u, vo);
            if (pass == 1) {
                t->fe.occ_item = &t->fe.items[it];
                if (frontend_triangles(&t->fe, f, item, m, vo, wire, 0, m->n_opaque, 0, e))
                    goto fail;
            } else {
                frontend_edges(&t->fe, it, m, vo, o, !wire || o->hidden_lines, !wire, fb,
                               stats);
            }
        }
        if (pass == 1) {
            if (frontend_finish(&t->fe, f, e)) { /* the surfaces are complete */
                free(f);
                return -1;
            }
            if (!wire)
                for (int k = 0; k < threads; k++) {
                    stats->pixels_tested += t->ctx[k].tested;
                    stats->pixels_shaded += t->ctx[k].shaded;
                }
            if (show_sky && !wire) /* the sky goes where the surfaces left room */
                frame_sky(w, f->k, sky, cam, fb);
            /* the blended triangles over both, back to front, on this thread */
            if (!wire && plan_blend_draw(&t->fe, &t->ctx[0], ks, items, n_items, cam, o, fb,
                                         pv, stats, e)) {
                free(f);
                return -1;
            }
        }
    }
    free(f);
    return 0;
fail: /* nothing may be left drawing once the caller has the frame back */
    frontend_abandon(&t->fe, f);
    free(f);
    return -1;
}
