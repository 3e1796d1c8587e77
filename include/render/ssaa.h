/* ssaa.h: supersampling (--ssaa 1|2|4|8) around pipeline_draw — how every command draws.
 *
 * With k = render_ssaa_factor(o->ssaa) > 1 the frame is drawn by pipeline_draw into a
 * framebuffer k times larger on each side (same camera, fov and aspect, so sample (i, j) of
 * pixel (x, y) sits at ((x + (i + 0.5)/k), (y + (j + 0.5)/k)) in the small image) and
 * resolved with a box filter:
 *   colour = (sum of the k*k samples' 8-bit values + k*k/2) / (k*k), per channel;
 *   depth  = the nearest sample's (the one that would win the depth test), so a pixel is
 *            covered (fb_covered) when any of its samples is; overdraw = mean count, rounded.
 * Lines (shade wire, the wire-overlay view) are drawn after the resolve, at the small size,
 * so they stay one pixel wide and as bright as without supersampling: the surfaces (and the
 * sky) are drawn big without them, then a second pipeline_draw at the small size draws the
 * lines alone — hidden by a depth-only pass over every face (the hidden-line pre-pass; it
 * ignores culling) when hidden lines or the overlay view ask for it — and its line pixels
 * are copied over the resolved picture. Debug views (depth, normals, overdraw) are drawn big
 * and box-filtered like colour.
 * k = 1 is pipeline_draw itself, byte for byte.
 *
 * Cost: k*k times the per-pixel work (the front end is the same per frame), plus the
 * resolve (one pass over the samples) and memory for k*k*(3 + 4) bytes a pixel
 * (+4 with the overdraw view): 140 MB for --ssaa 8 at 640x480. Limit: the big framebuffer
 * is at most FB_MAX_DIM (8192) a side, so --ssaa 8 stops at 1024 pixels a side.
 * Accuracy: the box filter is the ideal image's (render_opts_ideal); a test compares the
 * ideal with Mesa drawing 8x the size, box-filtered the same way (tests/oracle/run.sh). */
#ifndef RASTTY_SSAA_H
#define RASTTY_SSAA_H

#include "fb.h"
#include "pipeline.h"

/* The caller's per-size scratch, kept across frames; zero-initialise before first use. */
struct ssaa {
    struct fb big;   /* k*w x k*h samples (k > 1 only) */
    struct fb lines; /* w x h: the lines drawn after the resolve */
};

void ssaa_free(struct ssaa *s);

/* Can --ssaa m draw a w x h framebuffer? 0, or -1 with e set:
 * "--ssaa 8 at 1280x800 needs a 10240x6400 framebuffer (at most 8192 a side)". */
int ssaa_check(enum ssaa_method m, int w, int h, struct err *e);

/* pipeline_draw with o->ssaa's supersampling (arguments and result as pipeline_draw's).
 * stats_out counts the big frame's triangles and pixels (the lines frame's triangles for
 * shade wire); render_ms is the whole frame: drawing, resolve, lines. */
int ssaa_draw(struct ssaa *s, struct pipeline *p, const struct draw_item *items, int n_items,
              const struct skybox *sky, const struct camera *cam, const struct render_opts *o,
              struct fb *fb, struct frame_stats *stats_out, struct err *e);

/* The box filter alone: big (k*out->w x k*out->h) -> out (colour, depth, overdraw when both
 * have it); out takes big's depth mode and projection. */
void ssaa_resolve(const struct fb *big, int k, struct fb *out);

#endif
