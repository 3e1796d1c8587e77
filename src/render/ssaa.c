/* ssaa.c: supersampling around pipeline_draw, box-filter resolve (see ssaa.h). */
#include "ssaa.h"

#include <string.h>

#include "timing.h"

void ssaa_free(struct ssaa *s)
{
    fb_free(&s->big);
    fb_free(&s->lines);
}

int ssaa_check(enum ssaa_method m, int w, int h, struct err *e)
{
    int k = render_ssaa_factor(m);
    if ((long)w * k > FB_MAX_DIM || (long)h * k > FB_MAX_DIM)
        return err_set(e, "rastty: --ssaa %d at %dx%d needs a %ldx%ld framebuffer (at most %d a "
                          "side)", k, w, h, (long)w * k, (long)h * k, FB_MAX_DIM);
    return 0;
}

/* fb sized w x h (with an overdraw counter when asked), reallocated only when that changes */
static int ensure(struct fb *fb, int w, int h, bool overdraw, struct err *e)
{
    if (fb->rgb && fb->w == w && fb->h == h && (fb->overdraw != NULL) == overdraw)
        return 0;
    fb_free(fb);
    return fb_init(fb, w, h, overdraw, e);
}

void ssaa_resolve(const struct fb *big, int k, struct fb *out)
{
    const int w = out->w, h = out->h, bw = big->w, n = k * k;
    const bool reversed = big->depth_mode == DEPTH_RZ; /* the test is GREATER */
    out->depth_mode = big->depth_mode;
    out->proj = big->proj;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            unsigned sum[3] = {0, 0, 0};
            uint64_t od = 0;
            float d = big->depth[(size_t)y * k * bw + (size_t)x * k];
            for (int j = 0; j < k; j++) {
                size_t row = (size_t)(y * k + j) * bw + (size_t)x * k;
                const uint8_t *c = big->rgb + 3 * row;
                for (int i = 0; i < k; i++) {
                    sum[0] += c[3 * i];
                    sum[1] += c[3 * i + 1];
                    sum[2] += c[3 * i + 2];
                    float s = big->depth[row + i];
                    d = (reversed ? s > d : s < d) ? s : d;
                    if (big->overdraw)
                        od += big->overdraw[row + i];
                }
            }
            size_t o = (size_t)y * w + x;
            for (int c = 0; c < 3; c++)
                out->rgb[3 * o + c] = (uint8_t)((sum[c] + (unsigned)n / 2) / (unsigned)n);
            out->depth[o] = d;
            if (out->overdraw && big->overdraw)
                out->overdraw[o] = (uint32_t)((od + (uint64_t)n / 2) / (uint64_t)n);
        }
}

/* The lines of the frame, at the small size, over the resolved picture: drawn alone on a
 * background no line has, then their pixels copied. */
static int draw_lines(struct ssaa *s, struct pipeline *p, const struct draw_item *items,
                      int n_items, const struct camera *cam, const struct render_opts *o,
                      struct fb *fb, struct frame_stats *st, struct err *e)
{
    if (ensure(&s->lines, fb->w, fb->h, false, e))
        return -1;
    s->lines.pixel_aspect = fb->pixel_aspect;
    struct render_opts lo = *o;
    lo.shade = SHADE_WIRE;
    lo.view = VIEW_COLOR;
    lo.hidden_lines = o->hidden_lines || o->view == VIEW_WIRE_OVERLAY;
    for (int c = 0; c < 3; c++)
        lo.background[c] = (uint8_t)(o->wire_color[c] ^ 0x80);
    if (pipeline_draw(p, items, n_items, NULL, cam, &lo, &s->lines, st, e))
        return -1;
    size_t n = (size_t)fb->w * fb->h;
    for (size_t i = 0; i < n; i++) {
        const uint8_t *c = s->lines.rgb + 3 * i;
        if (c[0] != lo.background[0] || c[1] != lo.background[1] || c[2] != lo.background[2])
            memcpy(fb->rgb + 3 * i, c, 3);
    }
    if (o->shade == SHADE_WIRE) /* a wire frame's depth is its hidden-line pass */
        memcpy(fb->depth, s->lines.depth, n * sizeof *fb->depth);
    return 0;
}

int ssaa_draw(struct ssaa *s, struct pipeline *p, const struct draw_item *items, int n_items,
              const struct skybox *sky, const struct camera *cam, const struct render_opts *o,
              struct fb *fb, struct frame_stats *stats, struct err *e)
{
    int k = render_ssaa_factor(o->ssaa);
    if (k == 1)
        return pipeline_draw(p, items, n_items, sky, cam, o, fb, stats, e);
    double t0 = timing_now_ms();
    if (ssaa_check(o->ssaa, fb->w, fb->h, e) ||
        ensure(&s->big, k * fb->w, k * fb->h, fb->overdraw && o->view == VIEW_OVERDRAW, e))
        return -1;
    s->big.pixel_aspect = fb->pixel_aspect; /* the same picture, k times the pixels */
    bool wire = o->shade == SHADE_WIRE;
    bool lines_after = o->view == VIEW_WIRE_OVERLAY || (wire && o->view == VIEW_COLOR);
    struct render_opts so = *o;
    int n_surfaces = n_items;
    if (lines_after) {
        so.view = VIEW_COLOR;
        if (wire) { /* no surfaces: only the sky (or the background) is drawn big */
            so.shade = SHADE_PHONG;
            n_surfaces = 0;
        }
    }
    if (pipeline_draw(p, items, n_surfaces, sky, cam, &so, &s->big, stats, e))
        return -1;
    ssaa_resolve(&s->big, k, fb);
    if (lines_after) {
        struct frame_stats ls;
        if (draw_lines(s, p, items, n_items, cam, o, fb, &ls, e))
            return -1;
        if (wire)
            *stats = ls;
    }
    stats->render_ms = timing_now_ms() - t0;
    return 0;
}
