/* texture.c: loading textures (once per file, within a budget) and sampling them
 * (see texture.h). */
#include "texture.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <sys/stat.h>

#include "file.h"
#include "imgdec.h"

/* imgdec_decode into a texture without levels: it takes the image's texels over */
static int decode(struct texture *out, const uint8_t *data, size_t len, const char *name,
                  int max_side, struct warnings *w, struct err *e)
{
    struct imgdec_image img;
    memset(out, 0, sizeof *out);
    if (imgdec_decode(data, len, name, max_side, &img, w, e))
        return -1;
    out->w = img.w, out->h = img.h, out->rgba = img.rgba;
    return 0;
}

int texture_load_level0(const char *path_raw, int max_side, struct texture *out,
                        struct warnings *w, struct err *e)
{
    /* the path may come from an MTL file: never echo its raw bytes */
    char path[FILE_QUOTE_SIZE];
    file_quote(path_raw, path, sizeof path);
    memset(out, 0, sizeof *out);
    char *data;
    size_t len;
    int rc = file_read(path_raw, FILE_MAX_IMAGE, &data, &len);
    if (rc)
        return err_set(e, "%s: cannot open texture: %s", path, file_strerror(rc));
    rc = decode(out, (const uint8_t *)data, len, path, max_side, w, e);
    free(data);
    return rc;
}

int texture_load(const char *path_raw, int max_side, struct texture *out, struct warnings *w,
                 struct err *e)
{
    int rc = texture_load_level0(path_raw, max_side, out, w, e);
    if (rc == 0 && texture_build_mips(out, e) < 0) {
        texture_free(out);
        return -1;
    }
    return rc;
}

/* texel bytes of every level */
static size_t texture_bytes(const struct texture *t)
{
    size_t n = (size_t)t->w * (size_t)t->h * 4;
    for (int l = 1; l < t->n_levels; l++)
        n += (size_t)t->level[l].w * (size_t)t->level[l].h * 4;
    return n;
}

static struct texture_cache_entry *cache_add(struct texture_cache *c, struct texture *t,
                                             unsigned long long dev, unsigned long long ino,
                                             const char *name, struct err *e)
{
    size_t budget = c->budget ? c->budget : TEXTURE_BUDGET;
    size_t bytes = texture_bytes(t);
    if (bytes > budget - c->bytes) {
        texture_free(t);
        return err_set(e, "%s: texture would pass the %zu MiB texture budget (%zu MiB in use)",
                       name, budget >> 20, c->bytes >> 20),
               NULL;
    }
    if (c->n == c->cap) {
        int cap = c->cap ? c->cap * 2 : 8;
        struct texture_cache_entry **ne = realloc(c->entries, (size_t)cap * sizeof *ne);
        if (!ne) {
            texture_free(t);
            return err_set(e, "%s: out of memory", name), NULL;
        }
        c->entries = ne;
        c->cap = cap;
    }
    struct texture_cache_entry *en = malloc(sizeof *en);
    if (!en) {
        texture_free(t);
        return err_set(e, "%s: out of memory", name), NULL;
    }
    en->dev = dev;
    en->ino = ino;
    en->tex = *t;
    en->tex.borrowed = false;
    c->entries[c->n++] = en;
    c->bytes += bytes;
    return en;
}

int texture_cache_load(struct texture_cache *c, const char *path, const struct texture **out,
                       struct warnings *w, struct err *e)
{
    char q[FILE_QUOTE_SIZE];
    *out = NULL;
    struct stat st;
    if (stat(path, &st) == 0 && S_ISREG(st.st_mode))
        for (int i = 0; i < c->n; i++)
            if (c->entries[i]->ino == (unsigned long long)st.st_ino &&
                c->entries[i]->dev == (unsigned long long)st.st_dev && c->entries[i]->ino) {
                *out = &c->entries[i]->tex;
                return 0;
            }
    struct texture t;
    if (texture_load(path, TEXTURE_MAX_SIDE, &t, w, e))
        return -1;
    struct texture_cache_entry *en =
        cache_add(c, &t, (unsigned long long)st.st_dev, (unsigned long long)st.st_ino,
                  file_quote(path, q, sizeof q), e);
    if (!en)
        return -1;
    *out = &en->tex;
    return 0;
}

int texture_cache_decode(struct texture_cache *c, const uint8_t *data, size_t len,
                         const char *name, struct texture *out, struct warnings *w,
                         struct err *e)
{
    if (decode(out, data, len, name, TEXTURE_MAX_SIDE, w, e))
        return -1;
    if (texture_build_mips(out, e) < 0) {
        texture_free(out);
        return -1;
    }
    if (!c)
        return 0;
    struct texture_cache_entry *en = cache_add(c, out, 0, 0, name, e);
    if (!en) {
        memset(out, 0, sizeof *out);
        return -1;
    }
    *out = en->tex;
    out->borrowed = true;
    return 0;
}

void texture_cache_free(struct texture_cache *c)
{
    for (int i = 0; i < c->n; i++) {
        texture_free(&c->entries[i]->tex);
        free(c->entries[i]);
    }
    free(c->entries);
    memset(c, 0, sizeof *c);
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
    out->borrowed = false;
    out->mip_data = NULL;
    if (texture_build_mips(out, e) < 0) {
        texture_free(out);
        return -1;
    }
    return 0;
}

void texture_free(struct texture *t)
{
    if (!t->borrowed) {
        free(t->rgba);
        free(t->mip_data);
    }
    memset(t, 0, sizeof *t);
}

void texture_row_halve(const uint8_t *r0, const uint8_t *r1, uint8_t *d, int dw)
{
    for (int x = 0; x < dw; x++, d += 4, r0 += 8, r1 += 8)
        for (int c = 0; c < 4; c++)
            d[c] = (uint8_t)((r0[c] + r0[c + 4] + r1[c] + r1[c + 4] + 2) >> 2);
}

/* one box-filtered level: dst (dw x dh) from src (sw x sh), each destination texel the
 * area-weighted mean of the source texels under it; rows stay top-first */
static void box_down(const uint8_t *src, int sw, int sh, uint8_t *dst, int dw, int dh,
                     float *tmp)
{
    if (sw == 2 * dw && sh == 2 * dh) { /* each texel the mean of a 2x2 block: the float sums
                                           below are exact there, (a+b+c+d)/4 + 0.5 floored */
        for (int y = 0; y < dh; y++) {
            const uint8_t *r0 = src + (size_t)(2 * y) * (size_t)sw * 4, *r1 = r0 + (size_t)sw * 4;
            texture_row_halve(r0, r1, dst + (size_t)y * (size_t)dw * 4, dw);
        }
        return;
    }
    /* horizontal: tmp is sh rows of dw texels (4 floats each) */
    for (int y = 0; y < sh; y++)
        for (int x = 0; x < dw; x++) {
            double x0 = (double)x * sw / dw, x1 = (double)(x + 1) * sw / dw;
            float acc[4] = {0, 0, 0, 0};
            for (int i = (int)x0; i < sw && i < x1; i++) {
                double wgt = (i + 1 < x1 ? i + 1 : x1) - (i > x0 ? i : x0);
                const uint8_t *p = src + ((size_t)y * sw + i) * 4;
                for (int c = 0; c < 4; c++)
                    acc[c] += (float)wgt * p[c];
            }
            for (int c = 0; c < 4; c++)
                tmp[((size_t)y * dw + x) * 4 + c] = acc[c] / (float)(x1 - x0);
        }
    for (int y = 0; y < dh; y++) {
        double y0 = (double)y * sh / dh, y1 = (double)(y + 1) * sh / dh;
        for (int x = 0; x < dw; x++) {
            float acc[4] = {0, 0, 0, 0};
            for (int j = (int)y0; j < sh && j < y1; j++) {
                double wgt = (j + 1 < y1 ? j + 1 : y1) - (j > y0 ? j : y0);
                for (int c = 0; c < 4; c++)
                    acc[c] += (float)wgt * tmp[((size_t)j * dw + x) * 4 + c];
            }
            for (int c = 0; c < 4; c++) {
                float v = acc[c] / (float)(y1 - y0) + 0.5f;
                dst[((size_t)y * dw + x) * 4 + c] = (uint8_t)(v < 255 ? v : 255);
            }
        }
    }
}

long texture_build_mips(struct texture *t, struct err *e)
{
    if (!t->borrowed)
        free(t->mip_data);
    t->mip_data = NULL;
    t->level[0] = (struct texture_level){t->w, t->h, t->rgba};
    int n = 1;
    size_t bytes = 0;
    for (int w = t->w, h = t->h; (w > 1 || h > 1) && n < TEXTURE_MAX_LEVELS; n++) {
        w = w > 1 ? w / 2 : 1, h = h > 1 ? h / 2 : 1;
        bytes += (size_t)w * (size_t)h * 4;
    }
    t->n_levels = 1;
    if (n == 1)
        return 0;
    uint8_t *block = malloc(bytes);
    float *tmp = malloc((size_t)t->h * (size_t)(t->w > 1 ? t->w / 2 : 1) * 4 * sizeof *tmp);
    if (!block || !tmp) {
        free(block);
        free(tmp);
        return err_set(e, "out of memory for the mip levels of a %dx%d texture", t->w, t->h);
    }
    uint8_t *p = block;
    for (int l = 1; l < n; l++) {
        const struct texture_level *up = &t->level[l - 1];
        int w = up->w > 1 ? up->w / 2 : 1, h = up->h > 1 ? up->h / 2 : 1;
        box_down(up->rgba, up->w, up->h, p, w, h, tmp);
        t->level[l] = (struct texture_level){w, h, p};
        p += (size_t)w * (size_t)h * 4;
    }
    free(tmp);
    t->mip_data = block;
    t->n_levels = n;
    return (long)bytes;
}
