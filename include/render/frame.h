/* frame.h: one frame's constants and the stages every plan runs the same way (plan_tiles.h,
 * plan_slices.h): the camera, lights and methods turned into the vertex stage's uniforms,
 * the shading context and the span template; a draw item's matrices, its whole-mesh
 * culling and its level of detail; and the stages that run on every thread in bands (the
 * clear, the vertex stage, the sky). */
#ifndef RASTTY_FRAME_H
#define RASTTY_FRAME_H

#include <stdbool.h>

#include "camera.h"
#include "fb.h"
#include "kernel.h"
#include "render_opts.h"
#include "scene.h"
#include "shade.h"
#include "span.h"
#include "stats.h"
#include "vertex.h"
#include "workers.h"

#define FRAME_MAX_RICH (2 * SCENE_MAX_ITEMS + 2)

/* What one frame's front ends and back ends share (one per thread of drawing with slices:
 * each slice has its framebuffer and counts). */
struct frame {
    const struct render_opts *o;
    const struct camera *cam;
    const struct kernel_set *ks; /* the kernels that draw it (kernel.h) */
    const struct kernel *k;      /* its kernel for whole stages: vertices, rasterizer, sky */
    struct vertex_uniforms u;    /* the current item's (frame_item) */
    struct shade_ctx sc;
    struct span_ctx span;        /* the template every thread's context starts from */
    struct fb *fb;
    struct frame_stats *stats;
    /* the features path's items (shade.h, struct rich_item): one per item and pass that
     * has material features, alive for the frame (the batches point into it) */
    struct rich_item rich[FRAME_MAX_RICH];
    int n_rich;
};

/* The frame's constants: camera, lights, methods, and the span functions for the methods
 * (kernel_choose_span). */
void frame_init(struct frame *f, const struct camera *cam, const struct render_opts *o,
                const struct kernel_set *ks, struct fb *fb, struct frame_stats *stats);
/* The vertex stage's matrices for one draw item (pv: projection x view). */
void frame_item(struct frame *f, const struct draw_item *item, mat4 pv);

/* Largest factor by which the model matrix stretches any direction (bounded by column norms). */
double frame_item_scale(mat4 model);
/* Is the item's mesh wholly outside the view (its bounding sphere through mvp, scaled by
 * scale)? Then its triangles count as culled. `counts`: the frame's statistics count this
 * item here (its triangles toward tris_full either way). */
bool frame_item_outside(const struct draw_item *item, mat4 mvp, double scale, bool counts,
                        struct frame_stats *stats);
/* The item's mesh at the level of detail the frame draws (lod.h) on a fb_w x fb_h
 * framebuffer, noted in stats. */
const struct mesh *frame_item_level(const struct draw_item *item, const struct camera *cam,
                                    int fb_w, int fb_h, const struct render_opts *o, double scale,
                                    struct frame_stats *stats);

/* Stages on every thread of the pool (the caller's included), in bands of rows or chunks of
 * vertices; the result never depends on the bands. */
void frame_clear(struct workers *w, struct fb *fb, const uint8_t bg[3]);
void frame_vertices(struct workers *w, const struct kernel *k, const struct mesh *m,
                    const struct vertex_uniforms *u, struct vertex_out *out);
void frame_sky(struct workers *w, const struct kernel *k, const struct skybox *sky,
               const struct camera *cam, struct fb *fb);

#endif
