/* batch.c: the set-up triangle array and the back end's loop over it (see batch.h). */
#include "batch.h"

#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

int batch_init(struct batch *b, uint32_t cap, struct err *e)
{
    memset(b, 0, sizeof *b);
    cap = cap < BATCH_MIN_CAPACITY ? BATCH_MIN_CAPACITY : cap;
    b->tris = malloc(cap * sizeof *b->tris);
    b->shades = malloc(cap * sizeof *b->shades);
    b->verts = malloc(cap * sizeof *b->verts);
    if (!b->tris || !b->shades || !b->verts) {
        batch_free(b);
        return err_set(e, "out of memory for a batch of %u triangles", cap);
    }
    b->cap = cap;
    return 0;
}

void batch_free(struct batch *b)
{
    free(b->tris);
    free(b->shades);
    free(b->verts);
    free(b->bin_start);
    free(b->bin_tris);
    free(b->tile_order);
    free(b->hit);
    memset(b, 0, sizeof *b);
}

/* grow *p (elements of sz bytes, capacity *cap) to hold n */
static int reserve(void **p, size_t *cap, size_t n, size_t sz)
{
    if (n <= *cap)
        return 0;
    size_t c = *cap ? *cap : 1024;
    while (c < n)
        c *= 2;
    void *q = realloc(*p, c * sz);
    if (!q)
        return -1;
    *p = q;
    *cap = c;
    return 0;
}

static int key_cmp(const void *a, const void *b)
{
    uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return (x > y) - (x < y);
}

/* each triangle into the tiles its box overlaps, in submission order (count, offsets, fill) */
static int bin(struct batch *b, int tiles_x, int n_tiles)
{
    if (reserve((void **)&b->bin_start, &b->bin_start_cap, (size_t)n_tiles + 1, sizeof(uint32_t)))
        return -1;
    uint32_t *start = b->bin_start;
    memset(start, 0, ((size_t)n_tiles + 1) * sizeof *start);
    size_t total = 0;
    /* (box corners are inside the framebuffer: unsigned division is a shift) */
#define TILE_OF(c) (int)((unsigned)(c) / BATCH_TILE)
    for (uint32_t i = 0; i < b->n_tris; i++) {
        const struct setup_tri *t = &b->tris[i];
        const int tx0 = TILE_OF(t->x0), tx1 = TILE_OF(t->x1), ty1 = TILE_OF(t->y1);
        if (tx0 == tx1 && TILE_OF(t->y0) == ty1) { /* most triangles: one tile */
            start[ty1 * tiles_x + tx0 + 1]++;
            continue;
        }
        for (int ty = TILE_OF(t->y0); ty <= ty1; ty++)
            for (int tx = tx0; tx <= tx1; tx++)
                start[ty * tiles_x + tx + 1]++;
    }
    /* the order threads take tiles in: the non-empty ones, most triangles first (keys
     * (~count, tile): ascending keys are descending counts, ties by tile) */
    if (reserve((void **)&b->tile_order, &b->tile_order_cap, (size_t)n_tiles, sizeof(uint64_t)))
        return -1;
    uint64_t *key = b->tile_order;
    int n_order = 0;
    for (int k = 0; k < n_tiles; k++)
        if (start[k + 1])
            key[n_order++] = (uint64_t)(uint32_t)~start[k + 1] << 32 | (uint32_t)k;
    qsort(key, (size_t)n_order, sizeof *key, key_cmp);
    b->job.n_order = n_order;
    for (int k = 0; k < n_tiles; k++)
        start[k + 1] += start[k];
    total = start[n_tiles];
    if (reserve((void **)&b->bin_tris, &b->bin_tris_cap, total, sizeof(uint32_t)))
        return -1;
    /* fill, using start[t] as tile t's write position, then shift the offsets back */
    for (uint32_t i = 0; i < b->n_tris; i++) {
        const struct setup_tri *t = &b->tris[i];
        const int tx0 = TILE_OF(t->x0), tx1 = TILE_OF(t->x1), ty1 = TILE_OF(t->y1);
        if (tx0 == tx1 && TILE_OF(t->y0) == ty1) {
            b->bin_tris[start[ty1 * tiles_x + tx0]++] = i;
            continue;
        }
        for (int ty = TILE_OF(t->y0); ty <= ty1; ty++)
            for (int tx = tx0; tx <= tx1; tx++)
                b->bin_tris[start[ty * tiles_x + tx]++] = i;
    }
#undef TILE_OF
    for (int k = n_tiles; k > 0; k--)
        start[k] = start[k - 1];
    start[0] = 0;
    return 0;
}

static void draw_tiles(void *arg, int k)
{
    struct batch *b = arg;
    struct span_ctx *s = &b->job.ctx[k];
    s->hit = b->hit + (size_t)k * b->cap;
    for (;;) {
        int o = atomic_fetch_add_explicit(&b->job.next, 1, memory_order_relaxed);
        if (o >= b->job.n_order)
            return;
        int t = (int)(uint32_t)b->tile_order[o]; /* the key's low half */
        int tx = t % b->job.tiles_x, ty = t / b->job.tiles_x;
        struct raster_rect r = {tx * BATCH_TILE, ty * BATCH_TILE,
                                tx * BATCH_TILE + BATCH_TILE - 1, ty * BATCH_TILE + BATCH_TILE - 1};
        r.x1 = r.x1 < b->job.fb_w - 1 ? r.x1 : b->job.fb_w - 1;
        r.y1 = r.y1 < b->job.fb_h - 1 ? r.y1 : b->job.fb_h - 1;
        for (uint32_t n = b->bin_start[t]; n < b->bin_start[t + 1]; n++) {
            uint32_t i = b->bin_tris[n];
            const struct setup_tri *tri = &b->tris[i];
            span_begin(s, tri, &b->shades[tri->shade], i);
            b->job.raster(tri, r, s);
            span_end(s);
        }
    }
}

int batch_draw_start(struct batch *b, raster_fn raster, int fb_w, int fb_h, struct workers *w,
                     struct span_ctx *ctx, struct err *e)
{
    int threads = workers_count(w) + 1;
    size_t n_hit = (size_t)threads * b->cap;
    if (n_hit > b->hit_cap) { /* zeroed once; batch_draw_finish zeroes what it reads */
        free(b->hit);
        b->hit_cap = 0;
        if (!(b->hit = calloc(n_hit, 1)))
            return err_set(e, "out of memory for the batch's hit flags");
        b->hit_cap = n_hit;
    }
    b->job = (struct batch_job){.raster = raster, .ctx = ctx, .fb_w = fb_w, .fb_h = fb_h,
                                .threads = threads};
    if (threads == 1) { /* in submission order, on this thread, now */
        struct raster_rect all = {0, 0, fb_w - 1, fb_h - 1};
        ctx[0].hit = b->hit;
        for (uint32_t i = 0; i < b->n_tris; i++) {
            const struct setup_tri *t = &b->tris[i];
            span_begin(ctx, t, &b->shades[t->shade], i);
            raster(t, all, ctx);
            span_end(ctx);
        }
        return 0;
    }
    b->job.tiles_x = (fb_w + BATCH_TILE - 1) / BATCH_TILE;
    b->job.n_tiles = b->job.tiles_x * ((fb_h + BATCH_TILE - 1) / BATCH_TILE);
    atomic_init(&b->job.next, 0);
    if (bin(b, b->job.tiles_x, b->job.n_tiles))
        return err_set(e, "out of memory for the tile bins");
    workers_start(w, draw_tiles, b);
    return 0;
}

long batch_draw_finish(struct batch *b, struct workers *w)
{
    if (b->job.threads > 1) {
        draw_tiles(b, 0); /* the tiles nobody has taken yet */
        workers_wait(w);
    }
    long empty = 0;
    for (uint32_t i = 0; i < b->n_tris; i++) {
        int hit = 0;
        for (int k = 0; k < b->job.threads; k++) {
            hit |= b->hit[(size_t)k * b->cap + i];
            b->hit[(size_t)k * b->cap + i] = 0;
        }
        empty += !hit;
    }
    return empty;
}
