/* cell.c: cell geometry and the glyph tables the encoder and decoder share (see cell.h). */
#include "cell.h"

#include <string.h>

const char *const cell_glyphs_names[CELL_GLYPHS_COUNT] = {"half", "quadrant", "sextant",
                                                           "braille", "ascii"};

static const struct cell_geom GEOMS[CELL_GLYPHS_COUNT] = {
    [CELL_HALF] = {CELL_HALF, 1, 2, false},
    [CELL_QUADRANT] = {CELL_QUADRANT, 2, 2, false},
    [CELL_SEXTANT] = {CELL_SEXTANT, 2, 3, false},
    [CELL_BRAILLE] = {CELL_BRAILLE, 2, 4, true},
    [CELL_ASCII] = {CELL_ASCII, 1, 1, false},
};

/* mask (bit 0 top left, 1 top right, 2 bottom left, 3 bottom right) -> block element */
static const uint16_t QUADRANT_CP[16] = {
    ' ',    0x2598, 0x259D, 0x2580, 0x2596, 0x258C, 0x259E, 0x259B,
    0x2597, 0x259A, 0x2590, 0x259C, 0x2584, 0x2599, 0x259F, 0x2588,
};

/* pixel i of a 2x4 cell (column i % 2, row i / 2) -> its braille dot's bit */
static const uint8_t BRAILLE_DOT[8] = {0x01, 0x08, 0x02, 0x10, 0x04, 0x20, 0x40, 0x80};

struct cell_geom cell_geom(enum cell_glyphs g)
{
    return GEOMS[(unsigned)g < CELL_GLYPHS_COUNT ? g : CELL_HALF];
}

const char *cell_glyphs_name(enum cell_glyphs g)
{
    return cell_glyphs_names[(unsigned)g < CELL_GLYPHS_COUNT ? g : CELL_HALF];
}

int cell_glyphs_parse(const char *s)
{
    for (int i = 0; i < CELL_GLYPHS_COUNT; i++)
        if (strcmp(s, cell_glyphs_names[i]) == 0)
            return i;
    return -1;
}

uint32_t cell_glyph_cp(enum cell_glyphs g, unsigned mask)
{
    switch (g) {
    case CELL_HALF:
        return mask == 0 ? ' ' : mask == 1 ? 0x2580 : mask == 2 ? 0x2584 : 0x2588;
    case CELL_QUADRANT:
        return QUADRANT_CP[mask & 15];
    case CELL_SEXTANT:
        mask &= 63;
        if (mask == 0 || mask == 63)
            return mask ? 0x2588 : ' ';
        if (mask == 21 || mask == 42) /* a whole column: the half blocks */
            return mask == 21 ? 0x258C : 0x2590;
        /* U+1FB00.. count the other 60 patterns up, sextant k being bit k-1 */
        return 0x1FB00 + mask - 1 - (mask > 21) - (mask > 42);
    case CELL_BRAILLE: {
        unsigned dots = 0;
        for (int i = 0; i < 8; i++)
            dots |= (mask >> i & 1) ? BRAILLE_DOT[i] : 0;
        return dots ? 0x2800 + dots : ' ';
    }
    case CELL_ASCII:
    case CELL_GLYPHS_COUNT:
        break;
    }
    return ' ';
}

int cell_utf8(uint32_t cp, char out[4])
{
    if (cp < 0x80) {
        out[0] = (char)cp;
        return 1;
    }
    if (cp < 0x800) {
        out[0] = (char)(0xC0 | cp >> 6);
        out[1] = (char)(0x80 | (cp & 63));
        return 2;
    }
    if (cp < 0x10000) {
        out[0] = (char)(0xE0 | cp >> 12);
        out[1] = (char)(0x80 | (cp >> 6 & 63));
        out[2] = (char)(0x80 | (cp & 63));
        return 3;
    }
    out[0] = (char)(0xF0 | cp >> 18);
    out[1] = (char)(0x80 | (cp >> 12 & 63));
    out[2] = (char)(0x80 | (cp >> 6 & 63));
    out[3] = (char)(0x80 | (cp & 63));
    return 4;
}

/* A pattern of a px_w x px_h cell on the master grid. */
static uint32_t master_shape(unsigned mask, int px_w, int px_h)
{
    uint32_t s = 0;
    for (int y = 0; y < CELL_MASTER_H; y++)
        for (int x = 0; x < CELL_MASTER_W; x++) {
            int i = (y * px_h / CELL_MASTER_H) * px_w + x * px_w / CELL_MASTER_W;
            if (mask >> i & 1)
                s |= 1u << (y * CELL_MASTER_W + x);
        }
    return s;
}

int cell_shape(uint32_t cp, uint32_t *shape_out)
{
    if (cp == ' ') {
        *shape_out = 0;
        return 0;
    }
    for (unsigned m = 1; m < 16; m++)
        if (QUADRANT_CP[m] == cp) {
            *shape_out = master_shape(m, 2, 2);
            return 0;
        }
    if (cp >= 0x1FB00 && cp <= 0x1FB3B) {
        unsigned m = cp - 0x1FB00 + 1;
        m += m >= 21;
        m += m >= 42;
        *shape_out = master_shape(m, 2, 3);
        return 0;
    }
    if (cp >= 0x2800 && cp <= 0x28FF) {
        unsigned mask = 0;
        for (int i = 0; i < 8; i++)
            mask |= ((cp - 0x2800) & BRAILLE_DOT[i]) ? 1u << i : 0;
        *shape_out = master_shape(mask, 2, 4);
        return 0;
    }
    return -1;
}

/* The two bits of master row y. */
static inline unsigned master_row(uint32_t shape, int y)
{
    return shape >> (y * CELL_MASTER_W) & ((1u << CELL_MASTER_W) - 1);
}

void cell_shape_grid(uint32_t shape, int *px_w_out, int *px_h_out)
{
    /* two columns when the left and right differ; rows: the fewest bands of equal master
     * rows (the exact row counts are closed under gcd, so the smallest divides the rest) */
    *px_w_out = ((shape & 0x555555u) << 1) == (shape & 0xAAAAAAu) ? 1 : 2;
    static const int heights[] = {1, 2, 3, 4, 6, 12};
    for (unsigned k = 0; k < sizeof heights / sizeof heights[0]; k++) {
        int band = CELL_MASTER_H / heights[k], y = 0;
        while (y < CELL_MASTER_H && master_row(shape, y) == master_row(shape, y - y % band))
            y++;
        if (y == CELL_MASTER_H) {
            *px_h_out = heights[k];
            return;
        }
    }
    *px_h_out = CELL_MASTER_H;
}
