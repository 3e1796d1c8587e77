/* raster_tile.c: the 8x8-block rasterizer (see raster.h).
 *
 * Blocks sit on absolute multiples of RASTER_BLOCK pixels. Edge values are linear, so over a
 * block (clipped to the triangle's box) each edge's smallest and largest value are at
 * corners: if some edge is negative at every corner the block is empty; if every edge is
 * >= 0 at every corner the whole block is covered and its rows go out as runs without a
 * single per-pixel test; otherwise the block's pixels are tested one by one. */
#include "raster.h"

#define RASTER_BLOCK 8

void raster_tiled(const struct setup_tri *t, struct raster_rect r, struct span_ctx *s)
{
    struct raster_rect b;
    if (!raster_clip_box(t, r, &b))
        return;
    for (int by = b.y0 - b.y0 % RASTER_BLOCK; by <= b.y1; by += RASTER_BLOCK) {
        int y0 = by > b.y0 ? by : b.y0;
        int y1 = by + RASTER_BLOCK - 1 < b.y1 ? by + RASTER_BLOCK - 1 : b.y1;
        for (int bx = b.x0 - b.x0 % RASTER_BLOCK; bx <= b.x1; bx += RASTER_BLOCK) {
            int x0 = bx > b.x0 ? bx : b.x0;
            int x1 = bx + RASTER_BLOCK - 1 < b.x1 ? bx + RASTER_BLOCK - 1 : b.x1;
            int64_t e[3];
            int full = 1, empty = 0;
            for (int k = 0; k < 3; k++) {
                int64_t a = t->e_dx[k] * (x1 - x0), c = t->e_dy[k] * (y1 - y0);
                e[k] = raster_edge_at(t, k, x0, y0);
                int64_t lo = e[k] + (a < 0 ? a : 0) + (c < 0 ? c : 0);
                int64_t hi = e[k] + (a > 0 ? a : 0) + (c > 0 ? c : 0);
                full &= lo >= 0;
                empty |= hi < 0;
            }
            if (empty)
                continue;
            if (full) {
                for (int y = y0; y <= y1; y++)
                    span_draw(s, y, x0, x1);
                continue;
            }
            for (int y = y0; y <= y1; y++) { /* partial: pixel by pixel */
                int64_t e0 = e[0], e1 = e[1], e2 = e[2];
                int start = -1, end = -1;
                for (int x = x0; x <= x1; x++) {
                    if ((e0 | e1 | e2) >= 0) {
                        start = start < 0 ? x : start;
                        end = x;
                    } else if (start >= 0) { /* convex: nothing more on this row */
                        break;
                    }
                    e0 += t->e_dx[0], e1 += t->e_dx[1], e2 += t->e_dx[2];
                }
                if (start >= 0)
                    span_draw(s, y, start, end);
                e[0] += t->e_dy[0], e[1] += t->e_dy[1], e[2] += t->e_dy[2];
            }
        }
    }
}
