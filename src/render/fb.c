/* fb.c: framebuffer storage and debug views (see fb.h). */
#include "fb.h"

#include <stdlib.h>
#include <string.h>

int fb_init(struct fb *fb, int w, int h, bool count_overdraw, struct err *e)
{
    memset(fb, 0, sizeof *fb);
    if (w < 1 || h < 1 || w > FB_MAX_DIM || h > FB_MAX_DIM)
        return err_set(e, "framebuffer size %dx%d out of range (1..%d per side)", w, h,
                       FB_MAX_DIM);
    size_t n = (size_t)w * (size_t)h;
    fb->w = w;
    fb->h = h;
    fb->pixel_aspect = 1;
    fb->rgb = malloc(n * 3);
    fb->depth = malloc(n * sizeof *fb->depth);
    fb->overdraw = count_overdraw ? calloc(n, sizeof *fb->overdraw) : NULL;
    if (!fb->rgb || !fb->depth || (count_overdraw && !fb->overdraw)) {
        fb_free(fb);
        return err_set(e, "out of memory for a %dx%d framebuffer", w, h);
    }
    return 0;
}

void fb_free(struct fb *fb)
{
    free(fb->rgb);
    free(fb->depth);
    free(fb->overdraw);
    memset(fb, 0, sizeof *fb);
}

void fb_clear_rows(struct fb *fb, const uint8_t bg[3], int y0, int y1)
{
    size_t w = (size_t)fb->w, i0 = (size_t)y0 * w, n = (size_t)(y1 - y0) * w;
    if (n == 0)
        return;
    float clear = fb_depth_clear_value(fb->depth_mode);
    if (bg[0] == bg[1] && bg[1] == bg[2]) { /* grey (black): one memset */
        memset(fb->rgb + 3 * i0, bg[0], n * 3);
    } else { /* one row by pattern, then copies of it */
        uint8_t *row = fb->rgb + 3 * i0;
        for (size_t x = 0; x < w; x++)
            memcpy(row + 3 * x, bg, 3);
        for (int y = y0 + 1; y < y1; y++)
            memcpy(fb->rgb + (size_t)y * w * 3, row, w * 3);
    }
    float *d = fb->depth + i0;
    for (size_t i = 0; i < n; i++) /* a constant store: the compiler vectorises it */
        d[i] = clear;
    if (fb->overdraw)
        memset(fb->overdraw + i0, 0, n * sizeof *fb->overdraw);
}

void fb_clear(struct fb *fb, const uint8_t bg[3])
{
    fb_clear_rows(fb, bg, 0, fb->h);
}

float fb_depth_encode(const struct fb *fb, double z01)
{
    const struct fb_depth_proj *p = &fb->proj;
    switch (fb->depth_mode) {
    case DEPTH_W: {
        double zn = 2 * z01 - 1, f = p->far, n = p->near;
        if (p->ortho) /* z_ndc = (2e - (f + n)) / (f - n) */
            return (float)(0.5 * (zn * (f - n) + (f + n)));
        /* z_ndc = (f + n)/(f - n) - 2fn / ((f - n) e) */
        double den = (f + n) - zn * (f - n);
        return den > 0 ? (float)(2 * f * n / den) : INFINITY;
    }
    case DEPTH_Z16: {
        double q = floor(z01 * 65535.0 + 0.5);
        return (float)(q < 0 ? 0 : q > 65535 ? 65535 : q);
    }
    case DEPTH_RZ: return (float)(1.0 - z01);
    default: return (float)z01;
    }
}

double fb_depth_window(const struct fb *fb, size_t i)
{
    if (!fb_covered(fb, i))
        return 1.0;
    double d = fb->depth[i];
    const struct fb_depth_proj *p = &fb->proj;
    switch (fb->depth_mode) {
    case DEPTH_W: {
        double f = p->far, n = p->near, zn;
        if (p->ortho)
            zn = (2 * d - (f + n)) / (f - n);
        else
            zn = (f + n) / (f - n) - 2 * f * n / ((f - n) * d);
        return 0.5 * zn + 0.5;
    }
    case DEPTH_Z16: return d / 65535.0;
    case DEPTH_RZ: return 1.0 - d;
    default: return d;
    }
}

void fb_show_depth(struct fb *fb)
{
    size_t n = (size_t)fb->w * (size_t)fb->h;
    float lo = 1, hi = 0;
    for (size_t i = 0; i < n; i++)
        if (fb_covered(fb, i)) {
            float z = (float)fb_depth_window(fb, i);
            lo = z < lo ? z : lo;
            hi = z > hi ? z : hi;
        }
    /* stretch the used range: perspective depth crowds near 1, so a fixed map is all white */
    float scale = hi > lo ? 1.0f / (hi - lo) : 0;
    for (size_t i = 0; i < n; i++) {
        uint8_t g = 0;
        if (fb_covered(fb, i))
            g = pixel_quantize(0.15f + 0.85f * (1.0f - ((float)fb_depth_window(fb, i) - lo) * scale));
        fb->rgb[3 * i] = fb->rgb[3 * i + 1] = fb->rgb[3 * i + 2] = g;
    }
}

void fb_show_overdraw(struct fb *fb)
{
    static const uint8_t ramp[][3] = {
        {0, 0, 0}, {40, 60, 200}, {40, 180, 60}, {230, 210, 40}, {230, 60, 40}, {255, 255, 255},
    };
    enum { RAMP_LAST = sizeof ramp / sizeof ramp[0] - 1 };
    if (!fb->overdraw)
        return;
    size_t n = (size_t)fb->w * (size_t)fb->h;
    for (size_t i = 0; i < n; i++) {
        uint32_t k = fb->overdraw[i] > RAMP_LAST ? RAMP_LAST : fb->overdraw[i];
        memcpy(fb->rgb + 3 * i, ramp[k], 3);
    }
}
