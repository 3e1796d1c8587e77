/* pipeline.c: one frame over a list of draw items (see pipeline.h): which plan draws it,
 * then the debug view. */
#include "pipeline.h"

#include <stdlib.h>
#include <string.h>

#include "kernel.h"
#include "plan_slices.h"
#include "plan_tiles.h"
#include "timing.h"
#include "workers.h"

/* SPLIT_AUTO takes slices when the frame's meshes have a triangle for every
 * PIPELINE_SLICE_PIXELS pixels, or for every PIPELINE_SLICE_PIXELS_SMALL in a frame of up
 * to PIPELINE_SLICE_SMALL pixels (320x200). Two threads, fastest of each pair (ms): the
 * head 160x96 0.110 against tiles' 0.185, 320x200 0.223 against 0.276, 400x300 0.35
 * against 0.37, 480x360 even, 640x480 0.62 against 0.58; the demo 320x192 1.15 against
 * 1.24, 640x480 5.8 against 3.7 (its floor and teapot are a few large triangles: one
 * slice gets most of the pixels); lost_empire 640x480 12.4 against 14.9, the bunny even,
 * diablo3 (5k triangles) 2.1 against 1.5. */
#define PIPELINE_SLICE_PIXELS 8
#define PIPELINE_SLICE_PIXELS_SMALL 64
#define PIPELINE_SLICE_SMALL 64000

struct pipeline {
    int n_threads;           /* the frame's threads, the caller's included */
    struct workers *workers; /* n_threads - 1 of them */
    struct plan_tiles tiles;
    struct plan_slices slices;
};

struct pipeline *pipeline_new_batch(uint32_t batch_capacity)
{
    struct pipeline *p = calloc(1, sizeof *p);
    if (!p || plan_tiles_init(&p->tiles, batch_capacity, NULL)) {
        free(p);
        return NULL;
    }
    plan_slices_init(&p->slices, batch_capacity);
    return p;
}

struct pipeline *pipeline_new(void)
{
    return pipeline_new_batch(BATCH_DEFAULT_CAPACITY);
}

void pipeline_destroy(struct pipeline *p)
{
    if (!p)
        return;
    plan_tiles_free(&p->tiles);
    plan_slices_free(&p->slices);
    workers_destroy(p->workers);
    free(p);
}

/* n threads (a pool of n - 1 and the caller), kept until another count is asked */
static int use_threads(struct pipeline *p, int n, struct err *e)
{
    if (n == p->n_threads)
        return 0;
    workers_destroy(p->workers);
    p->n_threads = 0;
    if (!(p->workers = workers_new(n - 1, e)))
        return -1;
    p->n_threads = n;
    return 0;
}

enum pipeline_plan pipeline_plan(int threads, const struct draw_item *items, int n_items,
                                 const struct render_opts *o, const struct fb *fb)
{
    bool wire = o->view != VIEW_NORMALS && o->shade == SHADE_WIRE;
    if (threads < 2 || wire || o->view == VIEW_WIRE_OVERLAY || fb->overdraw ||
        o->split == SPLIT_TILES)
        return PIPELINE_TILES;
    if (o->split == SPLIT_SLICES)
        return PIPELINE_SLICES;
    uint64_t n = 0, px = (uint64_t)fb->w * (uint64_t)fb->h;
    for (int it = 0; it < n_items; it++)
        n += items[it].mesh->n_tris;
    return n * PIPELINE_SLICE_PIXELS >= px ||
                   (px <= PIPELINE_SLICE_SMALL && n * PIPELINE_SLICE_PIXELS_SMALL >= px)
               ? PIPELINE_SLICES
               : PIPELINE_TILES;
}

int pipeline_draw(struct pipeline *p, const struct draw_item *items, int n_items,
                  const struct skybox *sky, const struct camera *cam,
                  const struct render_opts *o, struct fb *fb, struct frame_stats *stats,
                  struct err *e)
{
    double t0 = timing_now_ms();
    memset(stats, 0, sizeof *stats);
    stats->lod_min = stats->lod_max = -1;
    if (use_threads(p, o->threads > 0 ? o->threads : workers_cores(), e))
        return -1;
    stats->threads = p->n_threads;
    const struct kernel_set *ks = kernel_set(o->kernel);
    if (!ks)
        return err_set(e, "--kernel %s: not in this build, or this CPU cannot run it",
                       render_kernel_names.names[o->kernel]);
    stats->kernel = ks->name;
    fb->depth_mode = o->depth;
    fb->proj = (struct fb_depth_proj){cam->ortho_height > 0, cam->near, cam->far};
    mat4 pv = m4_mul(camera_proj(cam, fb_aspect(fb)), camera_view(cam));
    enum pipeline_plan plan = pipeline_plan(p->n_threads, items, n_items, o, fb);
    stats->slices = plan == PIPELINE_SLICES;
    if (plan == PIPELINE_SLICES) {
        if (plan_slices_draw(&p->slices, p->workers, ks, items, n_items, sky, cam, o, fb, pv,
                             stats, e))
            return -1;
    } else if (plan_tiles_draw(&p->tiles, p->workers, ks, items, n_items, sky, cam, o, fb, pv,
                               stats, e)) {
        return -1;
    }
    if (o->view == VIEW_DEPTH)
        fb_show_depth(fb);
    else if (o->view == VIEW_OVERDRAW && plan == PIPELINE_TILES)
        fb_show_overdraw(fb);
    stats->render_ms = timing_now_ms() - t0;
    return 0;
}
