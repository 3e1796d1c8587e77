/* skybox.c: the sky's cube map: loading, the procedural sky, the reference sample (see
 * skybox.h; render/sky.c draws it). */
#include "skybox.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "pixel.h"
#include "texture.h"
#include "workers.h"

/* GL cube-map table: face of the major axis, its sc/tc coordinates */
static int face_of(vec3 d, double *sc, double *tc, double *ma)
{
    double ax = fabs(d.x), ay = fabs(d.y), az = fabs(d.z);
    if (ax >= ay && ax >= az) {
        *ma = ax;
        *tc = -d.y;
        *sc = d.x > 0 ? -d.z : d.z;
        return d.x > 0 ? 0 : 1;
    }
    if (ay >= az) {
        *ma = ay;
        *sc = d.x;
        *tc = d.y > 0 ? d.z : -d.z;
        return d.y > 0 ? 2 : 3;
    }
    *ma = az;
    *tc = -d.y;
    *sc = d.z > 0 ? d.x : -d.x;
    return d.z > 0 ? 4 : 5;
}

/* inverse: the direction of face coordinates (sc, tc in [-1,1], may exceed for borders) */
static vec3 dir_of(int face, double sc, double tc)
{
    switch (face) {
    case 0: return v3(1, -tc, -sc);
    case 1: return v3(-1, -tc, sc);
    case 2: return v3(sc, 1, tc);
    case 3: return v3(sc, -1, -tc);
    case 4: return v3(sc, -tc, 1);
    default: return v3(-sc, -tc, -1);
    }
}

static inline uint8_t *texel(const struct skybox_level *l, int face, int i, int j)
{
    /* i, j in [-1, n]: interior plus border */
    return l->rgb[face] + ((size_t)(j + 1) * (size_t)(l->n + 2) + (size_t)(i + 1)) * 4;
}

/* border texel (i, j) of face f: the nearest interior texel of the neighbouring face in
 * that direction */
static void fill_border_texel(struct skybox_level *l, int f, int i, int j)
{
    int n = l->n;
    vec3 d = dir_of(f, 2.0 * (i + 0.5) / n - 1, 2.0 * (j + 0.5) / n - 1);
    double sc, tc, ma;
    int g = face_of(d, &sc, &tc, &ma);
    int si = (int)floor((sc / ma + 1) * 0.5 * n), sj = (int)floor((tc / ma + 1) * 0.5 * n);
    si = si < 0 ? 0 : si >= n ? n - 1 : si;
    sj = sj < 0 ? 0 : sj >= n ? n - 1 : sj;
    memcpy(texel(l, f, i, j), texel(l, g, si, sj), 4);
}

/* every face's border (its sources are interior texels: any order gives the same bytes) */
static void fill_border(struct skybox_level *l)
{
    int n = l->n;
    for (int f = 0; f < 6; f++) {
        for (int i = -1; i <= n; i++) { /* the rows above and below */
            fill_border_texel(l, f, i, -1);
            fill_border_texel(l, f, i, n);
        }
        for (int j = 0; j < n; j++) { /* the columns left and right */
            fill_border_texel(l, f, -1, j);
            fill_border_texel(l, f, n, j);
        }
    }
}

/* the six faces in one block, one after another (the sky's gathers index all of them from
 * rgb[0]) */
static int alloc_level(struct skybox_level *l, int n)
{
    size_t face = (size_t)(n + 2) * (size_t)(n + 2) * 4;
    l->n = n;
    if (!(l->rgb[0] = calloc(6, face)))
        return -1;
    for (int f = 1; f < 6; f++)
        l->rgb[f] = l->rgb[0] + f * face;
    return 0;
}

/* levels 1.. by 2x2 box filtering; every level gets its border */
static int build_chain(struct skybox *s, struct err *e)
{
    fill_border(&s->level[0]);
    while (s->n_levels < SKYBOX_MAX_LEVELS && s->level[s->n_levels - 1].n >= 2) {
        const struct skybox_level *src = &s->level[s->n_levels - 1];
        struct skybox_level *dst = &s->level[s->n_levels];
        if (alloc_level(dst, src->n / 2))
            return err_set(e, "out of memory for the skybox");
        s->n_levels++;
        for (int f = 0; f < 6; f++)
            for (int j = 0; j < dst->n; j++) /* a row from two (byte 3 too: never read) */
                texture_row_halve(texel(src, f, 0, 2 * j), texel(src, f, 0, 2 * j + 1),
                                  texel(dst, f, 0, j), dst->n);
        fill_border(dst);
    }
    return 0;
}

int skybox_load(struct skybox *s, const char *const paths[6], struct warnings *w,
                struct err *e)
{
    memset(s, 0, sizeof *s);
    /* one face at a time, straight into level 0: never six decoded images at once */
    int rc = 0;
    for (int f = 0; f < 6 && rc == 0; f++) {
        struct texture t;
        rc = texture_load_level0(paths[f], SKYBOX_MAX_FACE, &t, w, e);
        if (rc)
            break;
        int n = s->n_levels ? s->level[0].n : t.w;
        char q[200];
        err_quote(paths[f], strlen(paths[f]), 160, q, sizeof q);
        if (t.w != t.h) {
            rc = err_set(e, "%s: skybox faces must be square (this one is %dx%d)", q, t.w, t.h);
        } else if (t.w != n) {
            rc = err_set(e, "%s: skybox faces must be equal (this one is %dx%d, the first %dx%d)",
                         q, t.w, t.h, n, n);
        } else if (!s->n_levels && alloc_level(&s->level[0], n)) {
            rc = err_set(e, "out of memory for the skybox");
        } else {
            s->n_levels = 1;
            for (int j = 0; j < t.h; j++) /* (byte 3 of a texel is never read) */
                memcpy(texel(&s->level[0], f, 0, j), t.rgba + (size_t)j * t.w * 4,
                       (size_t)t.w * 4);
        }
        texture_free(&t);
    }
    if (rc == 0)
        rc = build_chain(s, e);
    if (rc)
        skybox_free(s);
    return rc;
}

/* Default sky: zenith blue to a pale horizon, darker ground below, a sun disc with glow. */
static void sky_color(vec3 d, vec3 sun, float out[3])
{
    d = v3_norm(d);
    double h = d.y;
    double r, g, b;
    if (h >= 0) {
        double k = pow(1 - h, 3); /* 1 at the horizon, 0 at the zenith */
        r = 0.18 + 0.62 * k, g = 0.36 + 0.50 * k, b = 0.78 + 0.17 * k;
    } else {
        double k = pow(1 + h, 8);
        r = 0.22 + 0.45 * k, g = 0.20 + 0.46 * k, b = 0.18 + 0.42 * k;
    }
    double c = v3_dot(d, sun);
    double glow = c > 0 ? 0.35 * pow(c, 64) : 0;
    double disc = c > 0.9993 ? 1 : c > 0.9986 ? (c - 0.9986) / 0.0007 : 0;
    out[0] = (float)(r + glow + disc), out[1] = (float)(g + glow * 0.9 + disc * 0.95);
    out[2] = (float)(b + glow * 0.7 + disc * 0.85);
}

enum { SKY_N = 128, SKY_SS = 4 }; /* 4x4 supersampling keeps the sun's edge smooth */

struct sky_job {
    struct skybox *s;
    vec3 sun;
};

/* rows [r0, r1) of the six faces' level 0 (row r: face r / SKY_N, row r % SKY_N) */
static void sky_rows(void *arg, size_t r0, size_t r1)
{
    const struct sky_job *job = arg;
    enum { N = SKY_N, SS = SKY_SS };
    for (size_t r = r0; r < r1; r++) {
        int f = (int)(r / N), j = (int)(r % N);
        for (int i = 0; i < N; i++) {
            float acc[3] = {0, 0, 0}, c[3];
            for (int sj = 0; sj < SS; sj++)
                for (int si = 0; si < SS; si++) {
                    double sc = 2.0 * (i + (si + 0.5) / SS) / N - 1;
                    double tc = 2.0 * (j + (sj + 0.5) / SS) / N - 1;
                    sky_color(dir_of(f, sc, tc), job->sun, c);
                    for (int k = 0; k < 3; k++)
                        acc[k] += c[k] / (SS * SS);
                }
            uint8_t *p = texel(&job->s->level[0], f, i, j);
            for (int k = 0; k < 3; k++)
                p[k] = pixel_quantize(acc[k]);
        }
    }
}

int skybox_procedural(struct skybox *s, vec3 sun_dir, struct err *e)
{
    memset(s, 0, sizeof *s);
    if (alloc_level(&s->level[0], SKY_N)) {
        skybox_free(s);
        return err_set(e, "out of memory for the skybox");
    }
    s->n_levels = 1;
    struct sky_job job = {s, v3_norm(sun_dir)};
    /* 1.6M sky_color calls, two pow each: 0.1-0.15 s of the viewer's first frame on one
     * core. Every texel is its own: any thread may compute it, the same bytes. Without a
     * thread (none could start) the caller computes them all. */
    struct err ignored;
    struct workers *w = workers_new(workers_cores() - 1, &ignored);
    workers_for(w, 6 * (size_t)SKY_N, 16, sky_rows, &job);
    workers_destroy(w);
    if (build_chain(s, e)) {
        skybox_free(s);
        return -1;
    }
    return 0;
}

void skybox_free(struct skybox *s)
{
    for (int l = 0; l < SKYBOX_MAX_LEVELS; l++)
        free(s->level[l].rgb[0]); /* the block of all six faces */
    memset(s, 0, sizeof *s);
}

/* bilinear sample of face f of level l at face coordinates (sc, tc) / ma in [-1, 1] */
static inline void sample_face(const struct skybox_level *l, int f, double u, double v,
                               float rgb_out[3])
{
    /* texel space: centre of texel i at i + 0.5; border texels at -1 and n cover the edges */
    double x = (u + 1) * 0.5 * l->n - 0.5, y = (v + 1) * 0.5 * l->n - 0.5;
    int i0 = (int)x, j0 = (int)y; /* floor: x, y >= -0.5 here, and finite */
    i0 -= x < i0, j0 -= y < j0;
    i0 = i0 < -1 ? -1 : i0 > l->n - 1 ? l->n - 1 : i0;
    j0 = j0 < -1 ? -1 : j0 > l->n - 1 ? l->n - 1 : j0;
    float ax = (float)(x - i0), ay = (float)(y - j0);
    ax = ax < 0 ? 0 : ax > 1 ? 1 : ax;
    ay = ay < 0 ? 0 : ay > 1 ? 1 : ay;
    const uint8_t *p00 = texel(l, f, i0, j0), *p10 = texel(l, f, i0 + 1, j0);
    const uint8_t *p01 = texel(l, f, i0, j0 + 1), *p11 = texel(l, f, i0 + 1, j0 + 1);
    for (int c = 0; c < 3; c++) {
        float a = p00[c] + ax * (p10[c] - p00[c]), b = p01[c] + ax * (p11[c] - p01[c]);
        rgb_out[c] = (a + ay * (b - a)) * (1.0f / 255.0f);
    }
}

void skybox_sample(const struct skybox *s, int level, vec3 d, float rgb_out[3])
{
    double sc, tc, ma;
    int f = face_of(d, &sc, &tc, &ma);
    if (!(ma > 0)) {
        rgb_out[0] = rgb_out[1] = rgb_out[2] = 0;
        return;
    }
    sample_face(&s->level[level], f, sc / ma, tc / ma, rgb_out);
}
