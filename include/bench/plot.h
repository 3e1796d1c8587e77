/* plot.h: a small drawing surface for charts, with two back ends — SVG text, and a
 * framebuffer shown in the terminal by rastty's own half-block encoder — so the methods chart
 * and the sweeps draw their pictures with one piece of code (bench_chart.c, bench_sweep.c).
 *
 * Coordinates are pixels from the top-left corner, as doubles. Text is measured in the back
 * end's character cell (char_w x char_h pixels: 7 x 14 for SVG's 12 px font, 1 x 2 in the
 * terminal, where a cell shows two framebuffer pixels), so a layout written in characters
 * fits both. In the terminal, lines are Bresenham (line.h), markers are filled squares, and
 * text is collected and written over the encoded picture at its cell (plot_emit_terminal).
 * Colours are 0xRRGGBB. Callers own the FILE and the framebuffer. */
#ifndef RASTTY_PLOT_H
#define RASTTY_PLOT_H

#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>

#include "err.h"
#include "fb.h"
#include "palette.h"

struct plot_label {
    int col, row; /* terminal cell, 0-based */
    uint32_t rgb;
    char text[96];
};

struct plot {
    int w, h;              /* pixels */
    double char_w, char_h; /* pixels per character of text */
    FILE *svg;             /* SVG back end, or NULL */
    struct fb *fb;         /* terminal back end, or NULL */
    struct plot_label *labels; /* terminal back end: text over the picture */
    int n_labels, cap_labels;
};

enum plot_anchor { PLOT_LEFT, PLOT_MIDDLE, PLOT_RIGHT };
enum plot_shape { PLOT_CIRCLE, PLOT_SQUARE, PLOT_DIAMOND, PLOT_TRIANGLE };

/* An SVG document of w x h pixels on a white page, its <title> `title`. */
void plot_svg_begin(struct plot *p, FILE *f, int w, int h, const char *title);
/* Close the document; -1 with e set if writing failed. */
int plot_svg_end(struct plot *p, const char *path, struct err *e);
/* Draw into fb (cleared to black); text goes to p->labels. */
void plot_fb_begin(struct plot *p, struct fb *fb);
/* Encode the framebuffer (full frame, `mode` colours) from the terminal's home position,
 * then the labels at their cells, then move the cursor below the picture. -1 on a write
 * error or out of memory. */
int plot_emit_terminal(struct plot *p, FILE *out, enum palette_mode mode, struct err *e);
void plot_free(struct plot *p);

void plot_line(struct plot *p, double x0, double y0, double x1, double y1, uint32_t rgb,
               double width, bool dashed);
void plot_marker(struct plot *p, double x, double y, enum plot_shape shape, double r,
                 uint32_t rgb);
/* One line of text whose vertical middle is y; size in characters (1 = normal). */
void plot_text(struct plot *p, double x, double y, const char *text, uint32_t rgb,
               enum plot_anchor anchor, double size, bool bold);

/* Labels that keep out of each other's way: each placed label (and each marker registered
 * with plot_keep_clear) reserves its box; plot_text_clear tries spots around (x, y) — right,
 * left, above, below — and takes the first free one inside `area`. */
struct plot_box {
    double x0, y0, x1, y1;
};
struct plot_clear {
    struct plot_box area;
    struct plot_box boxes[256];
    int n;
};
void plot_keep_clear(struct plot_clear *c, double x, double y, double r);
/* Returns false (and draws nothing) when no spot is free and `optional`; otherwise draws at
 * the first free spot, or to the right of (x, y) when none is. */
bool plot_text_clear(struct plot *p, struct plot_clear *c, double x, double y, double r,
                     const char *text, uint32_t rgb, double size, bool bold, bool optional);

/* An axis maps values lo..hi (log10 when `log`) onto pixels px0..px1 (px1 < px0 for y). */
struct plot_axis {
    double lo, hi;
    bool log;
    double px0, px1;
};
double plot_map(const struct plot_axis *a, double v);
/* A frame around the plot area, grid lines and tick labels at round values (1-2-5 per decade
 * on log axes), the axis titles, and a title above. */
void plot_axes(struct plot *p, const struct plot_axis *x, const struct plot_axis *y,
               const char *xtitle, const char *ytitle, const char *title);

#endif
