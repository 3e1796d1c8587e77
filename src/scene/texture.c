/* texture.c: loading textures (once per file, within a budget) and sampling them
 * (see texture.h). */
#include "texture.h"

#include <errno.h>
#include <pthread.h>
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

/* ---- the process's textures: one budget, each file decoded once ----------------------
 * Every cache's texels count against one TEXTURE_BUDGET, and a file one cache decoded is
 * shared with the others (the viewer's scenes): a record per file, counted by the caches
 * that use it, freed by the last. The store and its byte count are the module's mutable
 * state, behind one lock (scenes may be loaded from more than one thread). */
struct texture_shared {
    unsigned long long dev, ino;
    long long size, mtime_s, mtime_ns; /* a file rewritten since is another file */
    struct texture tex;
    size_t bytes;
    int refs;
};

static pthread_mutex_t store_lock = PTHREAD_MUTEX_INITIALIZER;
static struct texture_shared **store;
static int store_n, store_cap;
static size_t store_bytes; /* texel bytes of every cache but solo ones */

size_t texture_process_bytes(void)
{
    pthread_mutex_lock(&store_lock);
    size_t n = store_bytes;
    pthread_mutex_unlock(&store_lock);
    return n;
}

static bool same_file(const struct texture_shared *r, const struct stat *st)
{
    return r->ino == (unsigned long long)st->st_ino && r->dev == (unsigned long long)st->st_dev &&
           r->size == (long long)st->st_size && r->mtime_s == (long long)st->st_mtim.tv_sec &&
           r->mtime_ns == (long long)st->st_mtim.tv_nsec;
}

/* the record of the file st names, one more reference to it; NULL when none (lock held) */
static struct texture_shared *store_find(const struct stat *st)
{
    for (int i = 0; i < store_n; i++)
        if (same_file(store[i], st)) {
            store[i]->refs++;
            return store[i];
        }
    return NULL;
}

/* (lock held) */
static void store_release(struct texture_shared *r)
{
    if (--r->refs > 0)
        return;
    for (int i = 0; i < store_n; i++)
        if (store[i] == r) {
            store[i] = store[--store_n];
            break;
        }
    store_bytes -= r->bytes;
    texture_free(&r->tex);
    free(r);
    if (store_n == 0) {
        free(store);
        store = NULL;
        store_cap = 0;
    }
}

/* A new entry of c for t (taken over: freed on failure); shared (st not NULL, c not solo):
 * recorded in the store for the other caches. Counted against the process's budget. */
static struct texture_cache_entry *cache_add(struct texture_cache *c, struct texture *t,
                                             const struct stat *st, const char *name,
                                             struct err *e)
{
    size_t budget = c->budget ? c->budget : TEXTURE_BUDGET;
    size_t bytes = texture_bytes(t);
    struct texture_cache_entry *en = NULL;
    struct texture_shared *r = NULL;
    pthread_mutex_lock(&store_lock);
    if (st && !c->solo && (r = store_find(st))) { /* decoded meanwhile by another thread */
        texture_free(t);
        bytes = r->bytes;
    } else {
        size_t used = store_bytes + (c->solo ? c->bytes : 0);
        if (bytes > budget || used > budget - bytes) {
            pthread_mutex_unlock(&store_lock);
            texture_free(t);
            return err_set(e, "%s: texture would pass the %zu MiB texture budget (%zu MiB in "
                              "use)",
                           name, budget >> 20, used >> 20),
                   NULL;
        }
    }
    if (c->n == c->cap) {
        int cap = c->cap ? c->cap * 2 : 8;
        struct texture_cache_entry **ne = realloc(c->entries, (size_t)cap * sizeof *ne);
        if (!ne)
            goto oom;
        c->entries = ne;
        c->cap = cap;
    }
    if (!(en = malloc(sizeof *en)))
        goto oom;
    if (st && !c->solo && !r) {
        if (store_n == store_cap) {
            int cap = store_cap ? store_cap * 2 : 8;
            struct texture_shared **ns = realloc(store, (size_t)cap * sizeof *ns);
            if (!ns)
                goto oom;
            store = ns;
            store_cap = cap;
        }
        if (!(r = malloc(sizeof *r)))
            goto oom;
        *r = (struct texture_shared){(unsigned long long)st->st_dev,
                                     (unsigned long long)st->st_ino,
                                     (long long)st->st_size,
                                     (long long)st->st_mtim.tv_sec,
                                     (long long)st->st_mtim.tv_nsec,
                                     *t,
                                     bytes,
                                     1};
        r->tex.borrowed = false;
        store[store_n++] = r;
        store_bytes += bytes;
    } else if (!r && !c->solo) {
        store_bytes += bytes; /* an embedded image: this cache's alone, counted */
    }
    pthread_mutex_unlock(&store_lock);
    en->dev = st ? (unsigned long long)st->st_dev : 0;
    en->ino = st ? (unsigned long long)st->st_ino : 0;
    en->shared = r;
    en->bytes = bytes;
    if (r) {
        en->tex = r->tex;
        en->tex.borrowed = true;
    } else {
        en->tex = *t;
        en->tex.borrowed = false;
    }
    c->entries[c->n++] = en;
    c->bytes += bytes;
    return en;
oom:
    if (r)
        store_release(r);
    pthread_mutex_unlock(&store_lock);
    free(en);
    if (!r)
        texture_free(t);
    return err_set(e, "%s: out of memory", name), NULL;
}

int texture_cache_load(struct texture_cache *c, const char *path, const struct texture **out,
                       struct warnings *w, struct err *e)
{
    char q[FILE_QUOTE_SIZE];
    *out = NULL;
    struct stat st;
    bool have = stat(path, &st) == 0 && S_ISREG(st.st_mode) && st.st_ino;
    if (have) {
        for (int i = 0; i < c->n; i++)
            if (c->entries[i]->ino == (unsigned long long)st.st_ino &&
                c->entries[i]->dev == (unsigned long long)st.st_dev) {
                *out = &c->entries[i]->tex;
                return 0;
            }
        if (!c->solo) { /* another cache's (another scene): shared, not decoded again */
            pthread_mutex_lock(&store_lock);
            struct texture_shared *r = store_find(&st);
            pthread_mutex_unlock(&store_lock);
            if (r) {
                struct texture t = r->tex;
                t.borrowed = true; /* r's texels: cache_add frees only its copy */
                struct texture_cache_entry *en =
                    cache_add(c, &t, &st, file_quote(path, q, sizeof q), e);
                pthread_mutex_lock(&store_lock);
                store_release(r); /* cache_add took its own reference */
                pthread_mutex_unlock(&store_lock);
                if (!en)
                    return -1;
                *out = &en->tex;
                return 0;
            }
        }
    }
    struct texture t;
    if (texture_load(path, TEXTURE_MAX_SIDE, &t, w, e))
        return -1;
    struct texture_cache_entry *en =
        cache_add(c, &t, have ? &st : NULL, file_quote(path, q, sizeof q), e);
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
    struct texture_cache_entry *en = cache_add(c, out, NULL, name, e);
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
    pthread_mutex_lock(&store_lock);
    for (int i = 0; i < c->n; i++) {
        struct texture_cache_entry *en = c->entries[i];
        if (en->shared) {
            store_release(en->shared);
        } else {
            if (!c->solo)
                store_bytes -= en->bytes;
            texture_free(&en->tex);
        }
        free(en);
    }
    pthread_mutex_unlock(&store_lock);
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
