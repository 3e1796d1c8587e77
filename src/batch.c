/* batch.c: the set-up triangle array and the back end's loop over it (see batch.h). */
#include "batch.h"

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
    memset(b, 0, sizeof *b);
}

void batch_draw(const struct batch *b, raster_fn raster, struct raster_rect r, struct span_ctx *s)
{
    for (uint32_t i = 0; i < b->n_tris; i++) {
        const struct setup_tri *t = &b->tris[i];
        span_begin(s, t, &b->shades[t->shade]);
        raster(t, r, s);
        span_end(s);
    }
}
