/* cell.h: the terminal cell's geometry — how many framebuffer pixels one character cell
 * shows, and with which glyphs. The one home of "pixels per cell": the framebuffer's size
 * (viewer, dump, bench, chart), the encoder's fitting and glyphs, and the decoder's grid all
 * come from here.
 *
 * Glyph sets (--glyphs), pixels per cell (columns x rows), and what a cell can show:
 *   half      1x2  U+2580/U+2584 half blocks: fg on one pixel, bg on the other (the default)
 *   quadrant  2x2  U+2596..U+259F quadrants, U+2580/2584/258C/2590 halves: any 2 colours
 *   sextant   2x3  U+1FB00..U+1FB3B sextants (Symbols for Legacy Computing), U+258C/2590
 *                  halves: any 2 colours
 *   braille   2x4  U+2800..U+28FF braille: ONE colour (the dots, fg) on the terminal's own
 *                  background, never set (assumed black, as a dark terminal shows it); every
 *                  dot is taken to fill its eighth of the cell
 *   ascii     1x1  a space on the cell's colour (colour modes), or a character of the
 *                  monochrome ramp: nothing outside ASCII, for any terminal and font
 * Pixel i of a cell is (i % px_w, i / px_w): row-major from the top left; a pattern (mask)
 * has bit i set where pixel i shows the glyph's foreground. Uniform cells are always a
 * space on their background (never U+2588: see encode.h).
 *
 * Aspect: a cell is CELL_ASPECT (1/2) as wide as it is tall, as in common terminal fonts, so
 * a pixel of a px_w x px_h cell is CELL_ASPECT * px_h / px_w as wide as tall (half and
 * braille: square; quadrant 1/2; sextant 3/4; ascii 1/2). The projection uses the picture's
 * physical aspect, fb_aspect() = w * pixel_aspect / h = cols / (2 rows) whatever the glyphs,
 * so a sphere stays round in every mode.
 *
 * Decoding: every glyph above has a shape on a 2x12 "master" grid (12 = the least common
 * multiple of 1, 2, 3 and 4 rows), so the decoder can show any glyph on any of the grids by
 * area: a pixel of a coarser grid gets the fg/bg mix of the master cells it covers. */
#ifndef RASTTY_CELL_H
#define RASTTY_CELL_H

#include <stdbool.h>
#include <stdint.h>

#include "err.h"

enum cell_glyphs { CELL_HALF, CELL_QUADRANT, CELL_SEXTANT, CELL_BRAILLE, CELL_ASCII,
                   CELL_GLYPHS_COUNT };

#define CELL_ASPECT 0.5   /* cell width / height */
#define CELL_MAX_PX 8     /* pixels in a cell, at most (braille) */
#define CELL_MASTER_W 2   /* the decoder's master grid per cell */
#define CELL_MASTER_H 12
#define CELL_MASTER_PX (CELL_MASTER_W * CELL_MASTER_H)

struct cell_geom {
    enum cell_glyphs glyphs;
    int px_w, px_h; /* pixels per cell: columns, rows */
    bool fg_only;   /* one colour per cell on the terminal's background (braille) */
};

extern const char *const cell_glyphs_names[CELL_GLYPHS_COUNT];

/* The geometry of a glyph set. */
struct cell_geom cell_geom(enum cell_glyphs g);
/* "half", "quadrant", ... */
const char *cell_glyphs_name(enum cell_glyphs g);
/* the name back, or -1 */
int cell_glyphs_parse(const char *s);

static inline int cell_px(const struct cell_geom *g) { return g->px_w * g->px_h; }
/* framebuffer size for cols x rows cells, and the cells a w x h framebuffer needs (a
 * partial last row is padded) */
static inline int cell_fb_w(const struct cell_geom *g, int cols) { return cols * g->px_w; }
static inline int cell_fb_h(const struct cell_geom *g, int rows) { return rows * g->px_h; }
static inline int cell_rows(const struct cell_geom *g, int h) { return (h + g->px_h - 1) / g->px_h; }
/* a pixel's width / height on the screen, for cells `r` times as tall as wide (--cell-aspect,
 * or the terminal's: cell_aspect_of) */
static inline double cell_pixel_aspect_r(const struct cell_geom *g, double r)
{
    return (double)g->px_h / (r * g->px_w);
}
/* ... for the usual 1:2 cells (CELL_ASPECT) */
static inline double cell_pixel_aspect(const struct cell_geom *g)
{
    return cell_pixel_aspect_r(g, 1 / CELL_ASPECT);
}
#define CELL_ASPECT_MIN 0.5 /* --cell-aspect's range (height / width) */
#define CELL_ASPECT_MAX 4.0
/* A cell's height / width from a window of cols x rows cells and px_w x px_h pixels
 * (TIOCGWINSZ), or from one cell's pixels (rows = cols = 1: ESC[16t's answer): 0 when
 * unknown (a zero) or outside CELL_ASPECT_MIN..MAX (a terminal telling nonsense). */
static inline double cell_aspect_of(int px_w, int px_h, int cols, int rows)
{
    if (px_w <= 0 || px_h <= 0 || cols <= 0 || rows <= 0)
        return 0;
    double r = ((double)px_h / rows) / ((double)px_w / cols);
    return r >= CELL_ASPECT_MIN && r <= CELL_ASPECT_MAX ? r : 0;
}

/* The code point showing `mask` (fg where set) in glyph set g: ' ' for 0; U+2588 for every
 * pixel set (the monochrome modes' full cell); ascii: ' ' only. */
uint32_t cell_glyph_cp(enum cell_glyphs g, unsigned mask);
/* UTF-8 of a code point (<= U+10FFFF) into out (4 bytes of room); returns its length. */
int cell_utf8(uint32_t cp, char out[4]);

/* The shape of a code point on the master grid, bit (row * 2 + col) = fg, for ' ' (0),
 * the block elements listed above and U+2588, sextants and braille; -1 for anything else. */
int cell_shape(uint32_t cp, uint32_t *shape_out);
/* The smallest grid (columns, rows per cell) that shows a shape exactly. */
void cell_shape_grid(uint32_t shape, int *px_w_out, int *px_h_out);

#endif
