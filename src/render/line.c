/* line.c: homogeneous + Cohen-Sutherland clipping and Bresenham (see line.h). */
#include "line.h"

#include <math.h>
#include <stdlib.h>

#include "viewport.h"

/* surfaces store the depth of the pixel centre; a line on that surface differs by a little */
static inline float depth_bias(float z)
{
    float b = 0.01f * (1.0f - z);
    return b > 1e-5f ? b : 1e-5f;
}

int line_draw_px(struct fb *fb, int x0, int y0, float z0, int x1, int y1, float z1,
                 const uint8_t rgb[3], int depth_test)
{
    if (y1 < y0 || (y1 == y0 && x1 < x0)) { /* canonical direction */
        int tx = x0, ty = y0;
        float tz = z0;
        x0 = x1, y0 = y1, z0 = z1;
        x1 = tx, y1 = ty, z1 = tz;
    }
    int dx = abs(x1 - x0), dy = -abs(y1 - y0);
    int sx = x0 < x1 ? 1 : -1, sy = y0 < y1 ? 1 : -1;
    int n = dx > -dy ? dx : -dy, step = 0, written = 0;
    int err = dx + dy;
    float dz = n ? (z1 - z0) / (float)n : 0;
    for (int x = x0, y = y0;; step++) {
        if (x >= 0 && y >= 0 && x < fb->w && y < fb->h) {
            size_t i = (size_t)y * (size_t)fb->w + (size_t)x;
            float z = z0 + dz * (float)step;
            /* biased toward the eye, then in the depth method's measure: shown unless the
             * stored surface is strictly nearer */
            if (!depth_test || !fb_depth_passes(fb->depth_mode, fb->depth[i],
                                                fb_depth_encode(fb, (double)z - depth_bias(z)))) {
                fb->rgb[3 * i + 0] = rgb[0];
                fb->rgb[3 * i + 1] = rgb[1];
                fb->rgb[3 * i + 2] = rgb[2];
                written++;
            }
        }
        if (x == x1 && y == y1)
            break;
        int e2 = 2 * err;
        if (e2 >= dy) {
            err += dy;
            x += sx;
        }
        if (e2 <= dx) {
            err += dx;
            y += sy;
        }
    }
    return written;
}

/* Clip the parametric segment a + t(b-a), t in [*t0,*t1], to dist >= 0 (dist linear in t). */
static int clip_param(double da, double db, double *t0, double *t1)
{
    if (da < 0 && db < 0)
        return 0;
    if (da < 0)
        *t0 = fmax(*t0, da / (da - db));
    else if (db < 0)
        *t1 = fmin(*t1, da / (da - db));
    return *t0 <= *t1;
}

enum { CS_LEFT = 1, CS_RIGHT = 2, CS_TOP = 4, CS_BOTTOM = 8 };

static int cs_code(double x, double y, double w, double h)
{
    return (x < 0 ? CS_LEFT : x > w ? CS_RIGHT : 0) | (y < 0 ? CS_TOP : y > h ? CS_BOTTOM : 0);
}

/* Cohen-Sutherland: clip (x0,y0)-(x1,y1) to [0,w]x[0,h]; z follows linearly. */
static int cohen_sutherland(double p[2][3], double w, double h)
{
    int c0 = cs_code(p[0][0], p[0][1], w, h), c1 = cs_code(p[1][0], p[1][1], w, h);
    for (int iter = 0; iter < 8; iter++) {
        if (!(c0 | c1))
            return 1;
        if (c0 & c1)
            return 0;
        int i = c0 ? 0 : 1, c = c0 ? c0 : c1;
        double *q = p[i], *o = p[1 - i], t;
        if (c & CS_LEFT)
            t = (0 - q[0]) / (o[0] - q[0]);
        else if (c & CS_RIGHT)
            t = (w - q[0]) / (o[0] - q[0]);
        else if (c & CS_TOP)
            t = (0 - q[1]) / (o[1] - q[1]);
        else
            t = (h - q[1]) / (o[1] - q[1]);
        for (int k = 0; k < 3; k++)
            q[k] += t * (o[k] - q[k]);
        if (c & (CS_LEFT | CS_RIGHT))
            q[0] = (c & CS_LEFT) ? 0 : w; /* exact, so the next code is clean */
        else
            q[1] = (c & CS_TOP) ? 0 : h;
        if (i == 0)
            c0 = cs_code(q[0], q[1], w, h);
        else
            c1 = cs_code(q[0], q[1], w, h);
    }
    return !(c0 | c1);
}

static int to_pixel(double v, int n)
{
    int i = (int)floor(v);
    return i < 0 ? 0 : i >= n ? n - 1 : i;
}

int line_draw_clip(struct fb *fb, const double a[4], const double b[4], const uint8_t rgb[3],
                   int depth_test)
{
    double t0 = 0, t1 = 1;
    if (!clip_param(a[2] + a[3], b[2] + b[3], &t0, &t1) || /* near */
        !clip_param(a[3] - a[2], b[3] - b[2], &t0, &t1))   /* far */
        return 0;
    double ca[4], cb[4];
    for (int k = 0; k < 4; k++) {
        ca[k] = a[k] + t0 * (b[k] - a[k]);
        cb[k] = a[k] + t1 * (b[k] - a[k]);
    }
    if (!(ca[3] > 0 && cb[3] > 0))
        return 0; /* degenerate: a point at the eye */
    double p[2][3];
    viewport_window(ca, fb->w, fb->h, p[0]);
    viewport_window(cb, fb->w, fb->h, p[1]);
    for (int i = 0; i < 2; i++)
        for (int k = 0; k < 3; k++)
            if (!isfinite(p[i][k])) /* overflowed: Cohen-Sutherland would see NaN as inside */
                return 0;
    if (!cohen_sutherland(p, fb->w, fb->h))
        return 0;
    return line_draw_px(fb, to_pixel(p[0][0], fb->w), to_pixel(p[0][1], fb->h), (float)p[0][2],
                        to_pixel(p[1][0], fb->w), to_pixel(p[1][1], fb->h), (float)p[1][2], rgb,
                        depth_test);
}
