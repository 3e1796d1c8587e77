/* plan_slices.c: a frame by slices of its triangles (see plan_slices.h). */
#include "plan_slices.h"

#include <stdlib.h>
#include <string.h>

#include "dag.h"
#include "timing.h"

void plan_slices_init(struct plan_slices *s, uint32_t batch_cap)
{
    memset(s, 0, sizeof *s);
    s->batch_cap = batch_cap;
}

static void slices_free(struct plan_slices *s)
{
    for (int k = 0; k < s->n; k++) {
        frontend_free(&s->slice[k].fe);
        fb_free(&s->slice[k].fb);
    }
    free(s->slice);
    s->slice = NULL;
    s->n = 0;
}

void plan_slices_free(struct plan_slices *s)
{
    slices_free(s);
    free(s->mesh);
    memset(s, 0, sizeof *s);
}

/* n slices, and a framebuffer of fb's size for every slice but the first */
static int slices_ready(struct plan_slices *s, int n, const struct fb *fb, int n_items,
                        struct err *e)
{
    if (s->n != n) {
        slices_free(s);
        s->slice = aligned_alloc(64, (size_t)n * sizeof *s->slice); /* (whole lines each) */
        if (!s->slice)
            return err_set(e, "out of memory for %d slices", n);
        memset(s->slice, 0, (size_t)n * sizeof *s->slice);
        s->n = n; /* (slices_free copes with the zeroes of a failure below) */
        for (int k = 0; k < n; k++)
            if (frontend_init(&s->slice[k].fe, s->batch_cap, NULL)) {
                slices_free(s);
                return err_set(e, "out of memory for %d slices", n);
            }
        s->tris = UINT64_MAX; /* the cuts are made again */
    }
    for (int k = 1; k < s->n; k++)
        if (s->slice[k].fb.w != fb->w || s->slice[k].fb.h != fb->h) {
            fb_free(&s->slice[k].fb);
            if (fb_init(&s->slice[k].fb, fb->w, fb->h, false, e))
                return -1;
        }
    if (n_items > s->mesh_cap) {
        const struct mesh **nm = realloc(s->mesh, (size_t)n_items * sizeof *nm);
        if (!nm)
            return err_set(e, "out of memory for %d draw items", n_items);
        s->mesh = nm;
        s->mesh_cap = n_items;
    }
    return 0;
}

/* the frame's index of the first triangle of slice k (k = n: the end) */
static uint64_t slice_at(const struct plan_slices *s, int k, uint64_t n_tris)
{
    return k >= s->n ? n_tris : (uint64_t)(s->cut[k] * (double)n_tris);
}

/* Move the cuts toward slices of equal time. A slice's time is taken as spread evenly over
 * its triangles and cut i heads for where the cumulative time reaches i/n of the whole,
 * but moves at most step[i]: the step halves each time the cut turns back and grows
 * by half while it keeps its way, so a cut next to a few costly triangles (the demo's
 * floor at 640x480: moving the cut across it moved 3.6 ms) settles instead of jumping
 * over them every frame, and a new view still moves it quickly. Each slice keeps at least
 * a quarter of an even share. The cuts never change a picture, only which thread draws
 * what. */
static void balance(struct plan_slices *s)
{
    const int n = s->n;
    double total = 0, most = 0, want[WORKERS_MAX + 2];
    for (int k = 0; k < n; k++) {
        total += s->slice[k].ms;
        most = s->slice[k].ms > most ? s->slice[k].ms : most;
    }
    /* within a tenth of even: left alone (each slice keeps its vertex records and batches
     * warm in its core's caches; moving on noise cost the demo 6%) */
    if (!(total > 0) || most * n < 1.1 * total)
        return;
    want[0] = 0, want[n] = 1;
    int k = 0; /* the slice in which the cumulative time reaches i/n */
    double acc = 0; /* time of slices before k */
    for (int i = 1; i < n; i++) {
        double target = total * i / n;
        while (k < n - 1 && acc + s->slice[k].ms < target)
            acc += s->slice[k++].ms;
        double t = s->slice[k].ms, w = s->cut[k + 1] - s->cut[k];
        want[i] = s->cut[k] + (t > 0 ? (target - acc) / t : 0) * w;
    }
    const double least = 0.25 / n;
    for (int i = 1; i < n; i++) {
        double d = want[i] - s->cut[i], step = s->step[i];
        int dir = d > 0 ? 1 : d < 0 ? -1 : 0;
        step *= dir && s->dir[i] && dir != s->dir[i] ? 0.5 : 1.5;
        step = step < 1e-4 ? 1e-4 : step > 0.5 / n ? 0.5 / n : step;
        s->step[i] = step, s->dir[i] = dir;
        double c = s->cut[i] + (d > step ? step : d < -step ? -step : d);
        double lo = s->cut[i - 1] + least, hi = 1 - least * (n - i);
        s->cut[i] = c < lo ? lo : c > hi ? hi : c;
    }
}

struct slice_job {
    struct plan_slices *s;
    const struct kernel_set *ks;
    const struct draw_item *items;
    int n_items;
    const struct camera *cam;
    const struct render_opts *o;
    struct fb *fb;
    mat4 pv;
    uint64_t n_tris; /* the frame's triangles (slice k draws slice_at(k) .. slice_at(k+1)) */
};

/* slice k: its triangles through the front end and the back end, on one thread */
static void slice_main(void *arg, int k)
{
    struct slice_job *j = arg;
    struct plan_slice *sl = &j->s->slice[k];
    struct fb *fb = k ? &sl->fb : j->fb;
    struct frame_stats *st = &sl->st;
    struct err *e = &sl->err;
    memset(st, 0, sizeof *st);
    sl->rc = 0;
    if (k) { /* (slice 0's is the frame's: the others read it meanwhile) */
        fb->depth_mode = j->fb->depth_mode;
        fb->proj = j->fb->proj;
        fb->pixel_aspect = j->fb->pixel_aspect;
    }
    fb_clear(fb, j->o->background);
    struct frame f;
    frame_init(&f, j->cam, j->o, j->ks, fb, st);
    frontend_begin(&sl->fe, &f, NULL, &sl->ctx, 1);
    const double t0 = timing_now_ms();
    const uint64_t lo = slice_at(j->s, k, j->n_tris), hi = slice_at(j->s, k + 1, j->n_tris);
    uint64_t base = 0; /* the frame's index of the item's first triangle */
    for (int it = 0; it < j->n_items && base < hi; it++) {
        const struct mesh *m = j->s->mesh[it];
        if (!m)
            continue;
        uint64_t first = base;
        base += m->n_opaque;
        if (base <= lo)
            continue;
        uint32_t i0 = (uint32_t)(lo > first ? lo - first : 0);
        uint32_t i1 = (uint32_t)(hi < base ? hi - first : m->n_opaque);
        frame_item(&f, &j->items[it], j->pv);
        /* the vertex stage starts at the lowest vertex the slice's triangles use (one flat
         * loop over their indices: the compiler makes it a vector minimum) */
        uint32_t from = 0;
        if (i0 && !frontend_by_clusters(m, j->o, f.span.mode == SHADE_WIRE) &&
            !dag_is_cut_mesh(m)) { /* (the front end makes those vertices itself) */
            const uint32_t *idx = m->tris[i0];
            from = m->n_verts;
            for (size_t i = 0; i < 3 * (size_t)(i1 - i0); i++)
                from = idx[i] < from ? idx[i] : from;
        }
        struct vertex_out *vo = frontend_item_verts(&sl->fe, it, m->n_verts, e);
        if (vo) /* (the occluders: what this slice drew of the item last frame) */
            sl->fe.occ_item = &sl->fe.items[it];
        if (!vo || frontend_triangles(&sl->fe, &f, &j->items[it], m, vo, false, i0, i1, from,
                                      e)) {
            sl->rc = -1;
            frontend_abandon(&sl->fe, &f);
            return;
        }
    }
    sl->rc = frontend_finish(&sl->fe, &f, e);
    st->pixels_tested += sl->ctx.tested;
    st->pixels_shaded += sl->ctx.shaded;
    sl->ms = timing_now_ms() - t0;
}

/* slices 1.. merged into slice 0 (the frame's framebuffer), rows y0 .. y1-1: the nearer
 * fragment wins, and on a tie the earlier slice (the depth test is strict) */
struct merge_job {
    struct fb *fb;
    const struct plan_slice *slice;
    int n;
};

static void merge_rows(void *arg, size_t y0, size_t y1)
{
    const struct merge_job *j = arg;
    struct fb *fb = j->fb;
    const enum depth_mode mode = fb->depth_mode;
    const size_t i0 = y0 * (size_t)fb->w, i1 = y1 * (size_t)fb->w;
    for (int k = 1; k < j->n; k++) {
        const struct fb *s = &j->slice[k].fb;
        for (size_t i = i0; i < i1; i++)
            if (fb_depth_passes(mode, s->depth[i], fb->depth[i])) {
                fb->depth[i] = s->depth[i];
                memcpy(fb->rgb + 3 * i, s->rgb + 3 * i, 3);
            }
    }
}

int plan_slices_draw(struct plan_slices *s, struct workers *w, const struct kernel_set *ks,
                     const struct draw_item *items, int n_items, const struct skybox *sky,
                     const struct camera *cam, const struct render_opts *o, struct fb *fb,
                     mat4 pv, struct frame_stats *stats, struct err *e)
{
    if (slices_ready(s, workers_count(w) + 1, fb, n_items, e))
        return -1;
    struct slice_job job = {.s = s, .ks = ks, .items = items, .n_items = n_items, .cam = cam,
                            .o = o, .fb = fb, .pv = pv},
                     *j = &job;
    /* the meshes and their levels, chosen once (as the tiles' plan does) */
    for (int it = 0; it < n_items; it++) {
        const struct draw_item *item = &items[it];
        const struct mesh *m = item->mesh;
        s->mesh[it] = NULL;
        if (m->n_tris == 0)
            continue;
        double scale = frame_item_scale(item->model);
        if (frame_item_outside(item, m4_mul(pv, item->model), scale, true, stats))
            continue;
        s->mesh[it] = frame_item_level(item, cam, fb->w, fb->h, o, scale, stats);
        j->n_tris += s->mesh[it]->n_opaque;
    }
    if (j->n_tris != s->tris) { /* another scene: even slices to start from */
        for (int k = 0; k <= s->n; k++) {
            s->cut[k] = (double)k / s->n;
            s->step[k] = 0.25 / s->n;
            s->dir[k] = 0;
        }
        s->tris = j->n_tris;
    }
    workers_run(w, slice_main, j);
    int rc = 0;
    for (int k = 0; k < s->n; k++) {
        const struct frame_stats *st = &s->slice[k].st;
        if (s->slice[k].rc && !rc) {
            rc = -1;
            if (e)
                *e = s->slice[k].err;
        }
        stats->tris_in += st->tris_in;
        stats->tris_culled += st->tris_culled;
        stats->tris_rejected += st->tris_rejected;
        stats->tris_clipped += st->tris_clipped;
        stats->tris_drawn += st->tris_drawn;
        stats->tris_empty += st->tris_empty;
        stats->tris_no_centre += st->tris_no_centre;
        stats->tris_hidden += st->tris_hidden;
        stats->verts_lit += st->verts_lit;
        stats->tris_by_position += st->tris_by_position;
        stats->pixels_tested += st->pixels_tested;
        stats->pixels_shaded += st->pixels_shaded;
        stats->clusters_tested += st->clusters_tested;
        stats->clusters_frustum += st->clusters_frustum;
        stats->clusters_facing += st->clusters_facing;
        stats->clusters_no_centre += st->clusters_no_centre;
        stats->clusters_hidden += st->clusters_hidden;
        stats->clusters_drawn += st->clusters_drawn;
        stats->occluders += st->occluders;
        stats->tris_occluded += st->tris_occluded;
        stats->clusters_occluded += st->clusters_occluded;
        stats->dag_cut += st->dag_cut;
        stats->dag_tris += st->dag_tris;
        stats->dag_levels |= st->dag_levels;
    }
    if (rc)
        return -1;
    balance(s);
    struct merge_job mj = {fb, s->slice, s->n};
    workers_for(w, (size_t)fb->h, 16, merge_rows, &mj);
    if (sky && (o->view == VIEW_COLOR || o->view == VIEW_WIRE_OVERLAY)) /* (where the surfaces
                                                                         left room) */
        frame_sky(w, ks->by_size[SPAN_SIZE_LARGE], sky, cam, fb);
    /* the blended triangles over both, back to front, on this thread */
    return plan_blend_draw(&s->slice[0].fe, &s->slice[0].ctx, ks, items, n_items, cam, o, fb,
                           pv, stats, e);
}
