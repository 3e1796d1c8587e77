/* gltf_build.h: tiny glTF files written by the tests, and a small renderer around them.
 *
 *   struct gb g = {0};
 *   int pos = gb_acc(&g, positions, sizeof positions, 5126, 4, "VEC3", "");
 *   char *json = gb_json(&g, "\"meshes\":[...],\"nodes\":[...]");  // malloc'd
 *
 * Every accessor gets a buffer view of its own in one buffer, stored as a base64 data URI
 * (gb_glb: as a GLB's binary chunk instead). Test code only: sizes are generous and fixed. */
#ifndef RASTTY_GLTF_BUILD_H
#define RASTTY_GLTF_BUILD_H

#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "model.h"
#include "pipeline.h"

struct gb {
    uint8_t bin[1 << 16];
    size_t n;
    char views[8192], accs[8192];
    int n_views, n_accs;
};

/* bytes appended (4-aligned) as a buffer view of their own; its index. extra: more members
 * for the view ("" or ",\"byteStride\":8") */
static inline int gb_view(struct gb *g, const void *data, size_t bytes, const char *extra)
{
    while (g->n % 4)
        g->bin[g->n++] = 0;
    size_t at = g->n;
    memcpy(g->bin + g->n, data, bytes);
    g->n += bytes;
    size_t l = strlen(g->views);
    snprintf(g->views + l, sizeof g->views - l, "%s{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu%s}",
             g->n_views ? "," : "", at, bytes, extra);
    return g->n_views++;
}

/* an accessor over a new view of the bytes; extra: more accessor members ("" or
 * ",\"normalized\":true") */
static inline int gb_acc(struct gb *g, const void *data, size_t bytes, int ctype, int count,
                         const char *type, const char *extra)
{
    int v = gb_view(g, data, bytes, "");
    size_t l = strlen(g->accs);
    snprintf(g->accs + l, sizeof g->accs - l,
             "%s{\"bufferView\":%d,\"componentType\":%d,\"count\":%d,\"type\":\"%s\"%s}",
             g->n_accs ? "," : "", v, ctype, count, type, extra);
    return g->n_accs++;
}

static inline char *gb_base64(const uint8_t *d, size_t n)
{
    static const char t[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    char *o = malloc(4 * (n / 3 + 1) + 1), *p = o;
    for (size_t i = 0; i < n; i += 3) {
        unsigned v = (unsigned)d[i] << 16 | (i + 1 < n ? (unsigned)d[i + 1] << 8 : 0) |
                     (i + 2 < n ? d[i + 2] : 0);
        *p++ = t[v >> 18];
        *p++ = t[(v >> 12) & 63];
        *p++ = i + 1 < n ? t[(v >> 6) & 63] : '=';
        *p++ = i + 2 < n ? t[v & 63] : '=';
    }
    *p = '\0';
    return o;
}

/* the whole file: asset, buffers, views, accessors, then `rest` (members, comma-separated,
 * without the braces) */
static inline char *gb_json(const struct gb *g, const char *rest)
{
    char *b64 = gb_base64(g->bin, g->n);
    size_t cap = strlen(b64) + strlen(rest) + strlen(g->views) + strlen(g->accs) + 512;
    char *s = malloc(cap);
    snprintf(s, cap,
             "{\"asset\":{\"version\":\"2.0\"},\"buffers\":[{\"byteLength\":%zu,\"uri\":\"data:"
             "application/octet-stream;base64,%s\"}],\"bufferViews\":[%s],\"accessors\":[%s]%s%s}",
             g->n ? g->n : 1, b64, g->views, g->accs, *rest ? "," : "", rest);
    free(b64);
    return s;
}

/* the same as a GLB (the buffer its binary chunk); *len_out its length */
static inline char *gb_glb(const struct gb *g, const char *rest, size_t *len_out)
{
    size_t cap = strlen(rest) + strlen(g->views) + strlen(g->accs) + 512;
    char *js = malloc(cap);
    int jn = snprintf(js, cap,
                      "{\"asset\":{\"version\":\"2.0\"},\"buffers\":[{\"byteLength\":%zu}],"
                      "\"bufferViews\":[%s],\"accessors\":[%s]%s%s}",
                      g->n ? g->n : 1, g->views, g->accs, *rest ? "," : "", rest);
    while (jn % 4)
        js[jn++] = ' ';
    size_t bn = (g->n + 3) & ~(size_t)3;
    if (bn == 0)
        bn = 4;
    size_t len = 12 + 8 + (size_t)jn + 8 + bn;
    char *o = calloc(1, len);
    uint32_t h[3] = {0x46546c67, 2, (uint32_t)len}, c1[2] = {(uint32_t)jn, 0x4e4f534a},
             c2[2] = {(uint32_t)bn, 0x004e4942};
    memcpy(o, h, 12);
    memcpy(o + 12, c1, 8);
    memcpy(o + 20, js, (size_t)jn);
    memcpy(o + 20 + jn, c2, 8);
    memcpy(o + 28 + jn, g->bin, g->n);
    free(js);
    *len_out = len;
    return o;
}

/* load a glTF from memory (warnings into *w if given) */
static inline int gb_load(const char *data, size_t len, const struct model_opts *o,
                          struct mesh *m, struct warnings *w, struct err *e)
{
    struct model_ctx ctx = {.warn = w, .opts = o};
    if (w)
        memset(w, 0, sizeof *w);
    return model_parse(data, len, &ctx, m, e);
}

/* draw m (identity model) into fb, looking down -z from (0, 0, 3) at the origin,
 * orthographic with a view 2 units tall unless persp; the default light and methods but
 * `shade` and the culling */
static inline int gb_draw_f(const struct mesh *m, struct fb *fb, enum shade_mode shade,
                            enum cull_mode cull, const uint8_t bg[3], enum tex_filter filter)
{
    struct pipeline *p = pipeline_new();
    if (!p)
        return -1;
    struct draw_item item = {.mesh = m, .model = m4_identity()};
    struct camera cam;
    camera_default(&cam);
    cam.ortho_height = 2;
    struct render_opts o;
    render_opts_default(&o);
    o.shade = shade;
    o.cull = cull;
    o.filter = filter;
    o.threads = 1;
    if (bg)
        memcpy(o.background, bg, 3);
    struct frame_stats st;
    int rc = pipeline_draw(p, &item, 1, NULL, &cam, &o, fb, &st, NULL);
    pipeline_destroy(p);
    return rc;
}

static inline int gb_draw(const struct mesh *m, struct fb *fb, enum shade_mode shade,
                          enum cull_mode cull, const uint8_t bg[3])
{
    return gb_draw_f(m, fb, shade, cull, bg, TEX_TRILINEAR);
}

/* the pixel at window (x, y) */
static inline const uint8_t *gb_px(const struct fb *fb, int x, int y)
{
    return fb->rgb + 3 * ((size_t)y * (size_t)fb->w + (size_t)x);
}

/* a unit quad's data: 4 corners at z (x, y in [-0.9, 0.9]), +z normals, uvs 0..us x 0..vs
 * (glTF's v: 0 at the top), indices */
struct gb_quad {
    float pos[12], nrm[12], uv[8];
    uint16_t idx[6];
};

static inline void gb_quad(struct gb_quad *q, float z, float us, float vs)
{
    const float x[4] = {-0.9f, 0.9f, 0.9f, -0.9f}, y[4] = {-0.9f, -0.9f, 0.9f, 0.9f};
    for (int i = 0; i < 4; i++) {
        q->pos[3 * i] = x[i], q->pos[3 * i + 1] = y[i], q->pos[3 * i + 2] = z;
        q->nrm[3 * i] = 0, q->nrm[3 * i + 1] = 0, q->nrm[3 * i + 2] = 1;
        q->uv[2 * i] = (x[i] > 0) * us, q->uv[2 * i + 1] = (y[i] < 0) * vs;
    }
    const uint16_t idx[6] = {0, 1, 2, 0, 2, 3};
    memcpy(q->idx, idx, sizeof idx);
}

/* the quad's accessors: positions, normals, uvs, indices (their indices in a[0..3]) */
static inline void gb_quad_accs(struct gb *g, const struct gb_quad *q, int a[4])
{
    a[0] = gb_acc(g, q->pos, sizeof q->pos, 5126, 4, "VEC3",
                  ",\"min\":[-0.9,-0.9,-10],\"max\":[0.9,0.9,10]");
    a[1] = gb_acc(g, q->nrm, sizeof q->nrm, 5126, 4, "VEC3", "");
    a[2] = gb_acc(g, q->uv, sizeof q->uv, 5126, 4, "VEC2", "");
    a[3] = gb_acc(g, q->idx, sizeof q->idx, 5123, 6, "SCALAR", "");
}

/* a PNG image of w x h rgba pixels as a data URI (stored, no compression: zlib's stored
 * blocks and an Adler-32 and CRCs computed here) */
static inline uint32_t gb_crc(const uint8_t *d, size_t n, uint32_t c)
{
    c = ~c;
    for (size_t i = 0; i < n; i++) {
        c ^= d[i];
        for (int k = 0; k < 8; k++)
            c = c & 1 ? (c >> 1) ^ 0xedb88320u : c >> 1;
    }
    return ~c;
}

/* the PNG file's bytes (malloc'd), *len_out long */
static inline uint8_t *gb_png(int w, int h, const uint8_t *rgba, size_t *len_out)
{
    size_t raw_n = (size_t)h * (1 + 4 * (size_t)w);
    uint8_t *raw = malloc(raw_n);
    for (int y = 0; y < h; y++) {
        raw[(size_t)y * (1 + 4 * w)] = 0;
        memcpy(raw + (size_t)y * (1 + 4 * w) + 1, rgba + (size_t)y * 4 * w, 4 * (size_t)w);
    }
    size_t zn = 2 + 5 + raw_n + 4; /* one stored block (raw_n < 65536) */
    uint8_t *z = malloc(zn);
    z[0] = 0x78, z[1] = 0x01, z[2] = 1;
    z[3] = (uint8_t)raw_n, z[4] = (uint8_t)(raw_n >> 8);
    z[5] = (uint8_t)~raw_n, z[6] = (uint8_t)(~raw_n >> 8);
    memcpy(z + 7, raw, raw_n);
    uint32_t a = 1, b = 0;
    for (size_t i = 0; i < raw_n; i++)
        a = (a + raw[i]) % 65521, b = (b + a) % 65521;
    uint32_t ad = b << 16 | a;
    z[7 + raw_n] = (uint8_t)(ad >> 24), z[8 + raw_n] = (uint8_t)(ad >> 16);
    z[9 + raw_n] = (uint8_t)(ad >> 8), z[10 + raw_n] = (uint8_t)ad;
    size_t pn = 8 + 25 + 12 + zn + 12;
    uint8_t *png = malloc(pn), *p = png;
    memcpy(p, "\x89PNG\r\n\x1a\n", 8), p += 8;
    uint8_t ihdr[17] = {'I', 'H', 'D', 'R', (uint8_t)(w >> 24), (uint8_t)(w >> 16),
                        (uint8_t)(w >> 8), (uint8_t)w, (uint8_t)(h >> 24), (uint8_t)(h >> 16),
                        (uint8_t)(h >> 8), (uint8_t)h, 8, 6, 0, 0, 0};
    const uint8_t *chunks[3] = {ihdr, NULL, (const uint8_t *)"IEND"};
    for (int c = 0; c < 3; c++) {
        size_t n = c == 0 ? 13 : c == 1 ? zn : 0;
        p[0] = (uint8_t)(n >> 24), p[1] = (uint8_t)(n >> 16), p[2] = (uint8_t)(n >> 8),
        p[3] = (uint8_t)n;
        p += 4;
        uint8_t *start = p;
        if (c == 1) {
            memcpy(p, "IDAT", 4);
            memcpy(p + 4, z, zn);
        } else {
            memcpy(p, chunks[c], 4 + n);
        }
        p += 4 + n;
        uint32_t crc = gb_crc(start, 4 + n, 0);
        p[0] = (uint8_t)(crc >> 24), p[1] = (uint8_t)(crc >> 16), p[2] = (uint8_t)(crc >> 8),
        p[3] = (uint8_t)crc;
        p += 4;
    }
    free(z);
    free(raw);
    *len_out = (size_t)(p - png);
    return png;
}

static inline char *gb_png_uri(int w, int h, const uint8_t *rgba)
{
    size_t n;
    uint8_t *png = gb_png(w, h, rgba, &n);
    char *b64 = gb_base64(png, n);
    char *uri = malloc(strlen(b64) + 32);
    sprintf(uri, "data:image/png;base64,%s", b64);
    free(b64);
    free(png);
    return uri;
}

#endif
