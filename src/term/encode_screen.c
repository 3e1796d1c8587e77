/* encode_screen.c: the encoder's screen model (see encode_screen.h). */
#include "encode_screen.h"

#include <stdlib.h>
#include <string.h>

void encode_screen_glyphs(struct encode_screen *s, enum cell_glyphs g)
{
    s->glyphs = g;
    s->geom = cell_geom(g);
    for (unsigned m = 0; m < 256; m++) {
        char u[4];
        int n = cell_utf8(cell_glyph_cp(g, m), u);
        memcpy(s->glyph[m].utf8, u, 4);
        s->glyph[m].len = (uint8_t)n;
    }
}

int encode_screen_init(struct encode_screen *s, int cols, int rows, struct err *e)
{
    memset(s, 0, sizeof *s);
    if (cols < 1 || cols > ENCODE_MAX_COLS || rows < 1 || rows > ENCODE_MAX_ROWS)
        return err_set(e, "encoder: %dx%d cells out of range (1..%d x 1..%d)", cols, rows,
                       ENCODE_MAX_COLS, ENCODE_MAX_ROWS);
    size_t n = (size_t)cols * (size_t)rows;
    s->cols = cols;
    s->rows = rows;
    s->cells = malloc(n * sizeof *s->cells);
    s->target = malloc(n * sizeof *s->target);
    s->memo = malloc(n * sizeof *s->memo);
    s->saved = malloc(n * sizeof *s->saved);
    s->out_cap = ENCODE_BOUND(cols, rows);
    s->out = malloc(s->out_cap);
    s->qcache = malloc(sizeof(uint32_t) * 2 << ENCODE_QCACHE_BITS);
    if (!s->cells || !s->target || !s->memo || !s->saved || !s->out || !s->qcache) {
        encode_screen_free(s);
        return err_set(e, "encoder: out of memory for %dx%d cells", cols, rows);
    }
    memset(s->qcache, 0xff, sizeof(uint32_t) * 2 << ENCODE_QCACHE_BITS); /* no valid key */
    encode_screen_glyphs(s, CELL_HALF);
    encode_screen_invalidate(s);
    return 0;
}

void encode_screen_free(struct encode_screen *s)
{
    free(s->cells);
    free(s->target);
    free(s->memo);
    free(s->saved);
    free(s->out);
    free(s->qcache);
    memset(s, 0, sizeof *s);
}

void encode_screen_invalidate(struct encode_screen *s)
{
    s->valid = false;
    encode_screen_damage(s, 0, 0, s->cols, s->rows);
}

void encode_screen_damage(struct encode_screen *s, int col, int row, int ncols, int nrows)
{
    int c0 = col < 0 ? 0 : col, r0 = row < 0 ? 0 : row;
    int c1 = col + ncols > s->cols ? s->cols : col + ncols;
    int r1 = row + nrows > s->rows ? s->rows : row + nrows;
    for (int r = r0; r < r1; r++)
        for (int c = c0; c < c1; c++)
            s->cells[(size_t)r * (size_t)s->cols + c] =
                (struct encode_cell){ENCODE_CELL_UNKNOWN, ENCODE_CELL_UNKNOWN, 0};
}

void encode_screen_keep(const struct encode_screen *s, struct encode_cell *keep,
                        struct encode_kept *kept)
{
    memcpy(keep, s->cells, (size_t)s->cols * (size_t)s->rows * sizeof *keep);
    *kept = (struct encode_kept){.valid = s->valid, .mode = s->mode, .lambda = s->lambda};
}

void encode_screen_restore(struct encode_screen *s, const struct encode_cell *keep,
                           const struct encode_kept *kept)
{
    memcpy(s->cells, keep, (size_t)s->cols * (size_t)s->rows * sizeof *keep);
    s->valid = kept->valid;
    s->mode = kept->mode;
    s->lambda = kept->lambda;
}
