/* pattern.c: procedural textures (square, power-of-two, tile seamlessly with wrap = repeat)
 * Images are RGB8, row 0 = top (= OBJ v near 1).
 *   checker  2 x 2 cells per tile, light grey / dark slate: with the floor's 10 repeats over
 *            20 units every cell is 1 x 1 unit.
 *   brick    8 courses of 4 bricks (each 1/4 x 1/8 of the tile), every other course shifted
 *            half a brick, 6-pixel mortar at 512, each brick tinted by gen_rand01 of its number,
 *            plus per-pixel speckle; edges of bricks are darkened a little (bevel).
 *   uvgrid   8 x 8 coloured cells labelled A..H (u, left to right) and 1..8 (v, bottom to
 *            top), so a mirrored or rotated mapping is obvious ("A1" is at uv (0,0)).
 *   stripes  one rainbow across u with white diagonal stripes (a mirror flips their slant). */
#include "gen.h"

#include <math.h>

static unsigned char to8(double c)
{
    c = c < 0 ? 0 : c > 1 ? 1 : c;
    return (unsigned char)floor(c * 255.0 + 0.5);
}

static void put(unsigned char *rgb, int size, int x, int y, gen_vec3 c)
{
    unsigned char *p = rgb + ((size_t)y * size + x) * 3;
    p[0] = to8(c.x);
    p[1] = to8(c.y);
    p[2] = to8(c.z);
}

static gen_vec3 mix(gen_vec3 a, gen_vec3 b, double t)
{
    return gen_add(a, gen_scale(gen_sub(b, a), t));
}

/* h in [0,1) around the colour wheel, s and v in [0,1]. */
static gen_vec3 hsv(double h, double s, double v)
{
    h = (h - floor(h)) * 6.0;
    int i = (int)h;
    double f = h - i, p = v * (1 - s), q = v * (1 - s * f), t = v * (1 - s * (1 - f));
    switch (i % 6) {
    case 0: return gen_vec(v, t, p);
    case 1: return gen_vec(q, v, p);
    case 2: return gen_vec(p, v, t);
    case 3: return gen_vec(p, q, v);
    case 4: return gen_vec(t, p, v);
    default: return gen_vec(v, p, q);
    }
}

void pattern_checker(unsigned char *rgb_out, int size)
{
    const gen_vec3 light = gen_vec(0.82, 0.82, 0.79), dark = gen_vec(0.22, 0.24, 0.28);
    int half = size / 2;
    for (int y = 0; y < size; y++)
        for (int x = 0; x < size; x++)
            put(rgb_out, size, x, y, ((x / half + y / half) & 1) ? dark : light);
}

void pattern_brick(unsigned char *rgb_out, int size)
{
    const int courses = 8, per_course = 4;
    const double mortar = 3.0 * size / 512.0;   /* half the mortar joint, in pixels */
    const gen_vec3 base = gen_vec(0.58, 0.24, 0.16), mortar_c = gen_vec(0.70, 0.68, 0.63);
    int bh = size / courses, bw = size / per_course;
    for (int y = 0; y < size; y++) {
        int course = y / bh;
        int shift = (course & 1) ? bw / 2 : 0;
        for (int x = 0; x < size; x++) {
            int xs = (x + shift) % size;
            int col = xs / bw;
            double lx = xs % bw + 0.5, ly = y % bh + 0.5;
            /* distance to the nearest joint, in pixels */
            double edge = fmin(fmin(lx, bw - lx), fmin(ly, bh - ly));
            /* speckle: 5 levels on 2x2-pixel blocks (finer noise is invisible in a terminal
             * and only makes the PNG bigger) */
            double speck = floor(5.0 * gen_rand01((uint32_t)x / 2, (uint32_t)y / 2, 7)) / 4.0 - 0.5;
            gen_vec3 c;
            if (edge < mortar) {
                c = gen_scale(mortar_c, 1.0 + 0.12 * speck);
            } else {
                uint32_t id = (uint32_t)(course * per_course + col);
                double tone = 0.78 + 0.36 * gen_rand01(id, 1, 11);
                double warm = 0.90 + 0.22 * gen_rand01(id, 2, 11);
                c = gen_vec(base.x * tone * warm, base.y * tone, base.z * tone / warm);
                double bevel = fmin(1.0, (edge - mortar) / (4.0 * size / 512.0));
                c = gen_scale(c, (0.80 + 0.20 * bevel) * (1.0 + 0.16 * speck));
            }
            put(rgb_out, size, x, y, c);
        }
    }
}

/* 5 x 7 glyphs for the uvgrid labels, '#' = ink. */
static const char *const GLYPH_LETTER[8][7] = {
    { ".###.", "#...#", "#...#", "#####", "#...#", "#...#", "#...#" },  /* A */
    { "####.", "#...#", "#...#", "####.", "#...#", "#...#", "####." },  /* B */
    { ".###.", "#...#", "#....", "#....", "#....", "#...#", ".###." },  /* C */
    { "####.", "#...#", "#...#", "#...#", "#...#", "#...#", "####." },  /* D */
    { "#####", "#....", "#....", "####.", "#....", "#....", "#####" },  /* E */
    { "#####", "#....", "#....", "####.", "#....", "#....", "#...." },  /* F */
    { ".###.", "#...#", "#....", "#.###", "#...#", "#...#", ".###." },  /* G */
    { "#...#", "#...#", "#...#", "#####", "#...#", "#...#", "#...#" },  /* H */
};
static const char *const GLYPH_DIGIT[8][7] = {
    { "..#..", ".##..", "..#..", "..#..", "..#..", "..#..", ".###." },  /* 1 */
    { ".###.", "#...#", "....#", "...#.", "..#..", ".#...", "#####" },  /* 2 */
    { "#####", "...#.", "..#..", "...#.", "....#", "#...#", ".###." },  /* 3 */
    { "...#.", "..##.", ".#.#.", "#..#.", "#####", "...#.", "...#." },  /* 4 */
    { "#####", "#....", "####.", "....#", "....#", "#...#", ".###." },  /* 5 */
    { "..##.", ".#...", "#....", "####.", "#...#", "#...#", ".###." },  /* 6 */
    { "#####", "....#", "...#.", "..#..", ".#...", ".#...", ".#..." },  /* 7 */
    { ".###.", "#...#", "#...#", ".###.", "#...#", "#...#", ".###." },  /* 8 */
};

/* 1 if pixel (gx, gy) of a glyph drawn at scale sc is ink. */
static int glyph_ink(const char *const g[7], int gx, int gy, int sc)
{
    if (gx < 0 || gy < 0 || gx >= 5 * sc || gy >= 7 * sc)
        return 0;
    return g[gy / sc][gx / sc] == '#';
}

void pattern_uvgrid(unsigned char *rgb_out, int size)
{
    const int cells = 8;
    int cs = size / cells;             /* cell size, 64 at 512 */
    int sc = cs / 16 > 0 ? cs / 16 : 1; /* glyph scale, 4 at 512 */
    int label_w = 2 * 5 * sc + sc, label_h = 7 * sc;
    int line = cs / 32 > 0 ? cs / 32 : 1;
    for (int y = 0; y < size; y++) {
        int row = cells - 1 - y / cs;   /* counted from the bottom, like v */
        for (int x = 0; x < size; x++) {
            int col = x / cs, lx = x % cs, ly = y % cs;
            double val = ((col + row) & 1) ? 0.78 : 0.95;
            gen_vec3 c = hsv((double)col / cells + 0.06 * row, 0.35 + 0.06 * row, val);
            if (lx < line || ly < line || lx >= cs - line || ly >= cs - line)
                c = gen_vec(0.15, 0.15, 0.18);
            int ox = (cs - label_w) / 2, oy = (cs - label_h) / 2;
            if (glyph_ink(GLYPH_LETTER[col], lx - ox, ly - oy, sc) ||
                glyph_ink(GLYPH_DIGIT[row], lx - ox - 6 * sc, ly - oy, sc)) {
                /* ink contrasts with its cell: dark on light cells, white on dark ones */
                gen_vec3 cell = hsv((double)col / cells + 0.06 * row, 0.35 + 0.06 * row, val);
                double luma = 0.299 * cell.x + 0.587 * cell.y + 0.114 * cell.z;
                c = luma > 0.5 ? gen_vec(0.08, 0.08, 0.10) : gen_vec(1.0, 1.0, 1.0);
            }
            put(rgb_out, size, x, y, c);
        }
    }
}

void pattern_stripes(unsigned char *rgb_out, int size)
{
    int period = size / 8, width = period * 5 / 16;
    for (int y = 0; y < size; y++) {
        for (int x = 0; x < size; x++) {
            gen_vec3 c = hsv((double)x / size, 0.85, 0.95);
            if ((x + y) % period < width)
                c = mix(c, gen_vec(1, 1, 1), 0.7);
            put(rgb_out, size, x, y, c);
        }
    }
}
