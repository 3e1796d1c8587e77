/* raster.c: the edge-function rasterizer and the method table (see raster.h). */
#include "raster.h"

const raster_fn raster_methods[RASTER_COUNT] = {raster_edge, raster_scanline, raster_tiled};

void raster_edge(const struct setup_tri *t, struct raster_rect r, struct span_ctx *s)
{
    struct raster_rect b;
    if (!raster_clip_box(t, r, &b))
        return;
    int64_t r0 = raster_edge_at(t, 0, b.x0, b.y0), r1 = raster_edge_at(t, 1, b.x0, b.y0),
            r2 = raster_edge_at(t, 2, b.x0, b.y0);
    const int64_t dx0 = t->e_dx[0], dx1 = t->e_dx[1], dx2 = t->e_dx[2];
    for (int y = b.y0; y <= b.y1; y++) {
        int64_t e0 = r0, e1 = r1, e2 = r2;
        int start = -1;
        for (int x = b.x0; x <= b.x1; x++) {
            if ((e0 | e1 | e2) >= 0) {
                if (start < 0)
                    start = x;
            } else if (start >= 0) { /* convex: nothing more on this row */
                span_draw(s, y, start, x - 1);
                start = -1;
                break;
            }
            e0 += dx0, e1 += dx1, e2 += dx2;
        }
        if (start >= 0)
            span_draw(s, y, start, b.x1);
        r0 += t->e_dy[0], r1 += t->e_dy[1], r2 += t->e_dy[2];
    }
}
