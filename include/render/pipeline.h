/* pipeline.h: draw one frame of draw items into a framebuffer — the renderer's entry point
 * (ssaa.h wraps it for supersampling, which is how every command calls it).
 *
 * A frame goes one of two ways, its plan, chosen by pipeline_plan (render_opts.h, enum
 * thread_split, says what each costs):
 *   PIPELINE_TILES   plan_tiles.h: the calling thread runs the front end (frontend.h) while
 *                    the pool draws the set-up triangles by screen tile
 *   PIPELINE_SLICES  plan_slices.h: each thread runs front end and back end for a slice of
 *                    the triangles into a framebuffer of its own; merged by depth
 * Either way, per triangle:
 *   front end (frontend.h): vertex stage, trivial reject, box, culling, clipping, setup.c
 *   back end (batch.h): a rasterizer (raster.h) finds the covered pixels as runs, the span
 *     stage (span.h) does the per-pixel work; the kernels (kernel.h) are per instruction set
 * then the sky where no surface was (kernel.h's sky_rows), wire edges as lines (line.h),
 * and the debug view (fb.h).
 *
 * Owns: the thread pool and both plans' state, allocated once and reused across frames,
 * so a frame performs no allocation once the largest mesh has been seen. Not thread-safe:
 * one struct pipeline per caller. */
#ifndef RASTTY_PIPELINE_H
#define RASTTY_PIPELINE_H

#include "camera.h"
#include "err.h"
#include "fb.h"
#include "mesh.h"
#include "render_opts.h"
#include "scene.h"
#include "skybox.h"
#include "stats.h"

struct pipeline;

enum pipeline_plan { PIPELINE_TILES, PIPELINE_SLICES };

struct pipeline *pipeline_new(void);
/* The same with a batch of the given capacity (tests: the picture must not depend on it). */
struct pipeline *pipeline_new_batch(uint32_t batch_capacity);
void pipeline_destroy(struct pipeline *p);

/* The plan a frame of these items takes with `threads` threads (see above): tiles with one
 * thread, for wireframe, the wire-overlay view and the overdraw count, or when
 * o->split says so; slices when o->split says so; SPLIT_AUTO: slices when the meshes hold a
 * triangle for every few pixels of fb (pipeline.c says how many). */
enum pipeline_plan pipeline_plan(int threads, const struct draw_item *items, int n_items,
                                 const struct render_opts *o, const struct fb *fb);
/* Clear fb to the background, draw the items by the plan pipeline_plan gives, then the sky
 * (if any) where nothing was drawn, then the debug view. stats_out->slices says which plan
 * drew. Returns 0, or -1 (out of memory, or a --kernel this CPU lacks) with e set. */
int pipeline_draw(struct pipeline *p, const struct draw_item *items, int n_items,
                  const struct skybox *sky, const struct camera *cam,
                  const struct render_opts *o, struct fb *fb, struct frame_stats *stats_out,
                  struct err *e);

#endif
