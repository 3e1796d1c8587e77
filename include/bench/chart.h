/* chart.h: speed against accuracy for every rendering method — `rastty bench --chart`.
 *
 * A fixed scene set (built-in assets: the demo scene, a grazing textured ground seen with a
 * 20-degree roll, a textured sphere on magenta — the crack test; shared models when their
 * folder is there: the textured african_head, and the dense meshes — the 300k-triangle sports
 * car, the 225k-triangle lost_empire and the 69k-triangle bunny) is drawn at each size
 * (160x96, a terminal's worth, and 640x480) with
 *   - the default methods, and every other value of every axis varied alone from them;
 *   - the fastest combination (per axis the value fastest in a pilot run, over all scenes of
 *     that size) and the most accurate (per axis the value with the best pooled PSNR, ties to
 *     the faster; an axis whose default is the ideal's, lod off, keeps it: a coarser mesh at
 *     one sample a pixel may score higher by the luck of its aliasing, never under the
 *     ideal's supersampling), unless another row already has those methods.
 * Per row: ms/frame (median of `repeat` frames, wall clock around ssaa_draw, one thread;
 * the rows of a scene take turns, in a new random order each round, so load from other
 * processes falls on every method alike; each turn draws the row twice and times the second
 * frame, so a method is timed with its own data in the caches, as a viewer draws it, not
 * with the previous row's — without this the row after a --ssaa 8 row, whose framebuffer
 * is 140 MB at 640x480, came out 15% slower than the same work elsewhere); error against the
 * scene's ideal image (render_opts_ideal: perspective-correct, trilinear, --ssaa 8, lod off;
 * every scene's levels of detail are built before it is drawn): PSNR over
 * all pixels and channels, and the fraction of pixels with a channel off by more than 8;
 * terminal bytes of the frame encoded as one full truecolor frame (encode.h).
 *
 * On the textured head, also the temporal shimmer (chart_row.shimmer): each method and the
 * ideal draw CHART_SHIMMER_FRAMES frames of an orbit turning CHART_SHIMMER_DEG degrees a
 * frame; a minified texture that aliases flickers from frame to frame where the ideal's
 * picture changes smoothly.
 *
 * Axes are data: chart_axes[] lists each method axis once (its CSV column, its names, its
 * render_opts field), so a new axis is one entry there. The CSV starts with
 *   scene,size,raster,persp,depth,filter,ssaa,ms,psnr_db,frac_gt8,bytes
 * and axes after the first CHART_CSV_AXES follow `bytes` (part 3: lod), then `shimmer` (empty
 * where not measured), then `glyphs` and `encode_ms`, so the header only grows.
 *
 * Glyph rows (CHART_GLYPHS): on the head (else the first scene), at the first size only, one
 * row per glyph set (cell.h): the terminal has w x h/2 cells (as half blocks show w x h
 * pixels) and the framebuffer the set's sub-cell grid (quadrant 2w x h, braille 2w x 2h, ascii
 * w x h/2). Per row: ms = render at that grid, psnr_db and frac_gt8 = the frame as the
 * terminal shows it (encoded whole in truecolor, decoded) against the ideal image at that
 * grid, bytes = that frame, encode_ms = its encode time. Half blocks in truecolor are lossless,
 * so every other row is its `glyphs = half` row. Glyph rows take no part in the fastest and
 * most accurate combinations or the picture. */
#ifndef RASTTY_CHART_H
#define RASTTY_CHART_H

#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

#include "err.h"
#include "plot.h"
#include "render_opts.h"

struct chart_axis {
    const char *name;                 /* CSV column; the flag is --name */
    const struct render_enum *values; /* value names; the default is render_opts_default's */
    size_t field;                     /* offsetof(struct render_opts, ...), an int-sized enum */
    bool ideal_is_default;            /* the ideal image uses this axis's default (lod off):
                                       * the most accurate combination keeps it */
};
#define CHART_AXES 6     /* entries of chart_axes */
#define CHART_CSV_AXES 5 /* of them, the columns before ms */
#define CHART_SHIMMER_FRAMES 9
#define CHART_SHIMMER_DEG 0.5
extern const struct chart_axis chart_axes[CHART_AXES];

enum chart_kind { CHART_DEFAULT, CHART_VARIED, CHART_FASTEST, CHART_ACCURATE, CHART_GLYPHS };

struct chart_row {
    char scene[16];
    int w, h;
    int value[CHART_AXES]; /* each axis's method */
    enum chart_kind kind;
    int axis;              /* CHART_VARIED: which axis differs from the default */
    unsigned also;         /* 1 << CHART_FASTEST, 1 << CHART_ACCURATE: this row's methods are
                            * also that combination (which then has no row of its own) */
    double ms;             /* median ms/frame */
    double pilot_ms;       /* the pilot run's median (chooses the fastest combination) */
    double psnr_db;        /* against the ideal; INFINITY when identical */
    double frac_gt8;       /* pixels with a channel off by more than 8, 0..1 */
    size_t bytes;          /* one full truecolor frame */
    double shimmer;        /* head only (else NaN): temporal shimmer over a slow orbit —
                            * the mean absolute difference, per channel in 8-bit levels,
                            * between this method's frame-to-frame change and the ideal
                            * image's (0 = it changes exactly as the ideal does) */
    int glyphs;            /* enum cell_glyphs: how the terminal shows the frame (half blocks
                            * for every row but CHART_GLYPHS's) */
    double encode_ms;      /* CHART_GLYPHS only (else NaN): median ms to encode the frame */
};

struct chart_config {
    const char *assets_dir; /* where demo.rsc, floor.obj, sphere.obj are */
    const char *models_dir; /* the shared models, or NULL (those scenes are skipped) */
    const int (*sizes)[2];  /* w, h */
    int n_sizes;
    int repeat;             /* timed frames per row (>= 1) */
    const char *only;       /* NULL, or only scenes whose name contains it */
    FILE *progress;         /* one line per step (stderr), or NULL */
};

struct chart {
    struct chart_row *rows;
    int n_rows;
    char note[256];         /* scenes skipped and why, or "" */
};

int chart_run(const struct chart_config *c, struct chart *out, struct err *e);
void chart_free(struct chart *c);
/* "default", "scanline", "depth z16", "ssaa 4", "fastest", "most accurate"; a row that is
 * also a combination says so: "default = fastest" */
void chart_row_label(const struct chart_row *r, char *out, size_t n);
int chart_write_csv(const struct chart *c, FILE *f);
void chart_write_table(const struct chart *c, FILE *f);
/* One panel per size: each method's ms (geometric mean over the scenes) on a log x axis,
 * its pooled PSNR on y, the Pareto front (no other method both faster and more accurate)
 * joined and labelled. Fits any plot size from a terminal's 120x70 pixels up. */
void chart_draw(const struct chart *c, struct plot *p);

#endif
