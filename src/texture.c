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

int texture_load(const char *path_raw, int max_side, struct texture *out, struct warnings *w,
                 struct err *e)
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
    rc = imgdec_decode((const uint8_t *)data, len, path, max_side, out, w, e);
    free(data);
    return rc;
}

static struct texture_cache_entry *cache_add(struct texture_cache *c, struct texture *t,
                                             unsigned long long dev, unsigned long long ino,
                                             const char *name, struct err *e)
{
    size_t budget = c->budget ? c->budget : TEXTURE_BUDGET;
    size_t bytes = (size_t)t->w * (size_t)t->h * 4;
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
    if (imgdec_decode(data, len, name, TEXTURE_MAX_SIDE, out, w, e))
        return -1;
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
    return 0;
}

void texture_free(struct texture *t)
{
    if (!t->borrowed)
        free(t->rgba);
    memset(t, 0, sizeof *t);
}
