/* test_batch.c: the back end's tiles with threads — every triangle reaches every tile its box
 * overlaps, once, in submission order within the tile, clipped to the tile; threads take the
 * tiles with the most triangles first, and never an empty one. */
#include <stdatomic.h>
#include <string.h>

#include "batch.h"
#include "test.h"

#define MAX_CALLS 64

/* what the rasterizer was asked: triangle and tile rectangle, in the order of the calls */
static struct call {
    uint32_t tri;
    struct raster_rect r;
} calls[MAX_CALLS];
static atomic_int n_calls;

static void record(const struct setup_tri *t, struct raster_rect r, struct span_ctx *s)
{
    int k = atomic_fetch_add(&n_calls, 1);
    if (k < MAX_CALLS)
        calls[k] = (struct call){s->tri_index, r};
    (void)t;
}

TEST(tiles_most_triangles_first_each_in_submission_order)
{
    /* 200x130 px: tiles of 64 are 4 x 3; boxes (inclusive) */
    static const int boxes[][4] = {
        {1, 1, 2, 2},      /* tile 0 */
        {70, 10, 80, 100}, /* tiles 1 and 5 */
        {65, 1, 66, 2},    /* tile 1 */
        {120, 60, 127, 63}, /* tile 1 */
        {199, 129, 199, 129}, /* tile 11 */
    };
    const int n = sizeof boxes / sizeof *boxes;
    struct batch b;
    REQUIRE(batch_init(&b, 64, NULL) == 0);
    memset(b.shades, 0, sizeof *b.shades);
    for (int i = 0; i < n; i++) {
        struct setup_tri *tri = &b.tris[i];
        memset(tri, 0, sizeof *tri);
        tri->x0 = boxes[i][0], tri->y0 = boxes[i][1], tri->x1 = boxes[i][2], tri->y1 = boxes[i][3];
    }
    b.n_tris = (uint32_t)n;
    b.n_shades = 1;
    struct workers *w = workers_new(1, NULL);
    REQUIRE(w != NULL);
    struct span_ctx ctx[2];
    memset(ctx, 0, sizeof ctx);
    atomic_init(&n_calls, 0);
    REQUIRE(batch_draw_start(&b, record, 200, 130, w, ctx, NULL) == 0);
    batch_draw_finish(&b, w);
    workers_destroy(w);

    /* the order tiles are handed out: tile 1 (three triangles), then 0, 5, 11 (one each,
     * ties by tile); the eight empty tiles never */
    const int want_order[] = {1, 0, 5, 11};
    CHECK_EQ_INT(b.job.n_order, 4);
    for (int k = 0; k < 4 && k < b.job.n_order; k++)
        CHECK_EQ_INT((int)(uint32_t)b.tile_order[k], want_order[k]);

    /* every (tile, triangle) pair once, clipped to its tile, in submission order per tile */
    static const struct {
        int tile;
        uint32_t tris[3];
        int n;
    } want[] = {{0, {0}, 1}, {1, {1, 2, 3}, 3}, {5, {1}, 1}, {11, {4}, 1}};
    CHECK_EQ_INT(atomic_load(&n_calls), 6);
    for (int k = 0; k < 4; k++) {
        int tx = want[k].tile % 4, ty = want[k].tile / 4, seen = 0;
        struct raster_rect r = {tx * 64, ty * 64, tx * 64 + 63, ty * 64 + 63};
        r.x1 = r.x1 < 199 ? r.x1 : 199;
        r.y1 = r.y1 < 129 ? r.y1 : 129;
        for (int c = 0; c < atomic_load(&n_calls) && c < MAX_CALLS; c++) {
            if (memcmp(&calls[c].r, &r, sizeof r))
                continue;
            if (seen < want[k].n)
                CHECK_EQ_INT((int)calls[c].tri, (int)want[k].tris[seen]);
            seen++;
        }
        CHECK_EQ_INT(seen, want[k].n);
    }
    batch_free(&b);
}
