/* texture.c: image decoding through stb_image and texture sampling (see texture.h). */
#include "texture.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <stb_image.h>

#define TEXTURE_MAX_DIM 16384

static int from_hdr(const char *path, FILE *f, struct texture *out, struct err *e)
{
    int w, h, n;
    float *px = stbi_loadf_from_file(f, &w, &h, &n, 3);
    if (!px)
        return err_set(e, "%s: cannot decode HDR image (%s)", path, stbi_failure_reason());
    out->rgba = malloc((size_t)w * (size_t)h * 4);
    if (!out->rgba) {
        stbi_image_free(px);
        return err_set(e, "%s: out of memory", path);
    }
    out->w = w;
    out->h = h;
    for (size_t i = 0; i < (size_t)w * (size_t)h; i++) {
        for (int c = 0; c < 3; c++) {
            float x = px[3 * i + c];
            x = x > 0 ? x / (1.0f + x) : 0; /* Reinhard */
            out->rgba[4 * i + c] = (uint8_t)(powf(x, 1.0f / 2.2f) * 255.0f + 0.5f);
        }
        out->rgba[4 * i + 3] = 255;
    }
    stbi_image_free(px);
    return 0;
}

int texture_load(const char *path_raw, struct texture *out, struct err *e)
{
    /* the path may come from an MTL file: never echo its raw bytes */
    char path[200];
    err_quote(path_raw, strlen(path_raw), 160, path, sizeof path);
    memset(out, 0, sizeof *out);
    FILE *f = fopen(path_raw, "rb");
    if (!f)
        return err_set(e, "%s: cannot open texture: %s", path, strerror(errno));
    int w, h, n, rc;
    if (!stbi_info_from_file(f, &w, &h, &n)) {
        rc = err_set(e, "%s: not a readable image (%s)", path, stbi_failure_reason());
    } else if (w < 1 || h < 1 || w > TEXTURE_MAX_DIM || h > TEXTURE_MAX_DIM) {
        rc = err_set(e, "%s: image is %dx%d (limit %d per side)", path, w, h, TEXTURE_MAX_DIM);
    } else if (stbi_is_hdr_from_file(f)) {
        rc = from_hdr(path, f, out, e);
    } else {
        uint8_t *px = stbi_load_from_file(f, &w, &h, &n, 4);
        if (!px) {
            rc = err_set(e, "%s: cannot decode image (%s)", path, stbi_failure_reason());
        } else {
            rc = texture_from_rgba(w, h, px, out, e);
            stbi_image_free(px);
        }
    }
    fclose(f);
    return rc;
}

int texture_from_rgba(int w, int h, const uint8_t *rgba, struct texture *out, struct err *e)
{
    size_t n = (size_t)w * (size_t)h * 4;
    out->rgba = malloc(n);
    if (!out->rgba)
        return err_set(e, "out of memory for a %dx%d texture", w, h);
    memcpy(out->rgba, rgba, n);
    out->w = w;
    out->h = h;
    return 0;
}

void texture_free(struct texture *t)
{
    free(t->rgba);
    memset(t, 0, sizeof *t);
}

/* floor(x) mod n for any finite x, in [0, n). */
static inline int wrap(float x, int n)
{
    float f = floorf(x);
    /* huge or non-finite coordinates: pick texel 0 rather than overflow an int */
    if (!(f > -1e9f && f < 1e9f))
        return 0;
    int i = (int)f % n;
    return i < 0 ? i + n : i;
}

/* texel at column i, row j counted from the bottom */
static inline const uint8_t *texel(const struct texture *t, int i, int j)
{
    return t->rgba + ((size_t)(t->h - 1 - j) * (size_t)t->w + (size_t)i) * 4;
}

void texture_sample(const struct texture *t, enum tex_filter f, float u, float v, float rgb_out[3])
{
    const float k = 1.0f / 255.0f;
    if (f == TEX_NEAREST) {
        const uint8_t *p = texel(t, wrap(u * (float)t->w, t->w), wrap(v * (float)t->h, t->h));
        rgb_out[0] = p[0] * k;
        rgb_out[1] = p[1] * k;
        rgb_out[2] = p[2] * k;
        return;
    }
    float x = u * (float)t->w - 0.5f, y = v * (float)t->h - 0.5f;
    if (!isfinite(x) || !isfinite(y)) { /* u*W overflowed: as nearest does, texel 0 */
        x = 0;
        y = 0;
    }
    float fx = floorf(x), fy = floorf(y);
    float ax = x - fx, ay = y - fy;
    int i0 = wrap(fx, t->w), j0 = wrap(fy, t->h);
    int i1 = i0 + 1 == t->w ? 0 : i0 + 1, j1 = j0 + 1 == t->h ? 0 : j0 + 1;
    const uint8_t *p00 = texel(t, i0, j0), *p10 = texel(t, i1, j0);
    const uint8_t *p01 = texel(t, i0, j1), *p11 = texel(t, i1, j1);
    for (int c = 0; c < 3; c++) {
        float a = p00[c] + ax * (p10[c] - p00[c]);
        float b = p01[c] + ax * (p11[c] - p01[c]);
        rgb_out[c] = (a + ay * (b - a)) * k;
    }
}
