/* palette.c: colour tables and nearest-colour search (see palette.h). */
#include "palette.h"

#include <stddef.h>
#include <string.h>
#include <strings.h>

static const uint8_t CUBE_LEVEL[6] = {0, 95, 135, 175, 215, 255};

/* xterm's defaults (XTerm-col.ad / 256colres.h). */
static const uint8_t ANSI16[16][3] = {
    {0, 0, 0},       {205, 0, 0},     {0, 205, 0},     {205, 205, 0},
    {0, 0, 238},     {205, 0, 205},   {0, 205, 205},   {229, 229, 229},
    {127, 127, 127}, {255, 0, 0},     {0, 255, 0},     {255, 255, 0},
    {92, 92, 255},   {255, 0, 255},   {0, 255, 255},   {255, 255, 255},
};

/* Classic 4x4 Bayer matrix, values 0..15. */
static const uint8_t BAYER4[4][4] = {
    {0, 8, 2, 10}, {12, 4, 14, 6}, {3, 11, 1, 9}, {15, 7, 13, 5}};

static const char *const MODE_NAME[] = {"none", "16", "256", "truecolor"};
_Static_assert(sizeof MODE_NAME / sizeof MODE_NAME[0] == PALETTE_MODE_COUNT,
               "one name per palette mode");

const char *palette_mode_name(enum palette_mode mode)
{
    return (unsigned)mode < PALETTE_MODE_COUNT ? MODE_NAME[mode] : "?";
}

int palette_mode_parse(const char *s, enum palette_mode *mode_out, struct err *e)
{
    for (int m = 0; m < PALETTE_MODE_COUNT; m++)
        if (strcasecmp(s, MODE_NAME[m]) == 0) {
            *mode_out = (enum palette_mode)m;
            return 0;
        }
    if (strcasecmp(s, "24bit") == 0) {
        *mode_out = PALETTE_TRUECOLOR;
        return 0;
    }
    char q[40];
    return err_set(e, "colour mode '%s' unknown (expected truecolor, 256, 16 or none)",
                   err_quote(s, strlen(s), 24, q, sizeof q));
}

void palette_rgb(int index, uint8_t rgb_out[3])
{
    index &= 255;
    if (index < 16) {
        for (int k = 0; k < 3; k++)
            rgb_out[k] = ANSI16[index][k];
    } else if (index < 232) {
        int i = index - 16;
        rgb_out[0] = CUBE_LEVEL[i / 36];
        rgb_out[1] = CUBE_LEVEL[i / 6 % 6];
        rgb_out[2] = CUBE_LEVEL[i % 6];
    } else {
        uint8_t v = (uint8_t)(8 + 10 * (index - 232));
        rgb_out[0] = rgb_out[1] = rgb_out[2] = v;
    }
}

/* Integer redmean: (2 + rbar/256) dR^2 + 4 dG^2 + (2 + (255-rbar)/256) dB^2, scaled by 256.
 * Largest value 767*255^2 + 1024*255^2 + 767*255^2 < 2^28: fits uint32. */
static inline uint32_t dist3(int r1, int g1, int b1, int r2, int g2, int b2)
{
    int rbar = (r1 + r2) >> 1, dr = r1 - r2, dg = g1 - g2, db = b1 - b2;
    return (uint32_t)((512 + rbar) * dr * dr + 1024 * dg * dg + (767 - rbar) * db * db);
}

uint32_t palette_dist(const uint8_t a[3], const uint8_t b[3])
{
    return dist3(a[0], a[1], a[2], b[0], b[1], b[2]);
}

int palette_nearest_256_ref(const uint8_t rgb[3])
{
    uint32_t best = UINT32_MAX;
    int best_i = 16;
    for (int i = 16; i < 256; i++) {
        uint8_t p[3];
        palette_rgb(i, p);
        uint32_t d = palette_dist(rgb, p);
        if (d < best) {
            best = d;
            best_i = i;
        }
    }
    return best_i;
}

/* Index of the nearest cube level to v, ties to the lower level (as the reference's
 * lowest-index rule does): boundaries at 47.5, 115, 155, 195, 235. */
static inline int cube_nearest(int v)
{
    return v < 48 ? 0 : v <= 115 ? 1 : (v - 36) / 40;
}

/* Keep the smaller distance; written as selects so the compiler emits conditional moves:
 * with image data the comparisons are unpredictable and branches cost more than the maths. */
#define KEEP_NEAREST(d, i, best, best_i)                                                     \
    do {                                                                                   \
        uint32_t d_ = (d);                                                                 \
        int i_ = (i);                                                                      \
        best_i = d_ < best ? i_ : best_i;                                                  \
        best = d_ < best ? d_ : best;                                                      \
    } while (0)

int palette_nearest_256(const uint8_t rgb[3])
{
    int r = rgb[0], g = rgb[1], b = rgb[2];
    /* Cube. For a fixed red level R the metric's weights are fixed (rbar = (r + R) / 2), and
     * a weighted Euclidean distance over a product grid separates per channel: the best green
     * and blue levels are simply the nearest ones. Red is tried at the two levels around r;
     * lower index first so that `<` keeps the lowest index on ties, like the reference. */
    int ig = cube_nearest(g), ib = cube_nearest(b);
    int r_lo = r < 95 ? 0 : (r - 55) / 40, r_hi = r_lo < 5 ? r_lo + 1 : r_lo;
    int lg = CUBE_LEVEL[ig], lb = CUBE_LEVEL[ib];
    int best_i = 16 + 36 * r_lo + 6 * ig + ib;
    uint32_t best = dist3(r, g, b, CUBE_LEVEL[r_lo], lg, lb);
    KEEP_NEAREST(dist3(r, g, b, CUBE_LEVEL[r_hi], lg, lb), 16 + 36 * r_hi + 6 * ig + ib, best,
                 best_i);
    /* Greys: the weighted mean (weights taken at rbar = r; they sum to 2303) is the best grey
     * for a fixed weighting; its neighbours absorb the small weight change. k is clamped so
     * the three candidates exist (at the ends that adds a harmless extra one). Grey indices
     * are all above the cube's, so ties already favour the cube. */
    int mean = ((512 + r) * r + 1024 * g + (767 - r) * b) / 2303;
    int k = (mean - 3) / 10;
    k = k < 1 ? 1 : k > 22 ? 22 : k;
    for (int j = k - 1; j <= k + 1; j++) {
        int v = 8 + 10 * j;
        KEEP_NEAREST(dist3(r, g, b, v, v, v), 232 + j, best, best_i);
    }
    return best_i;
}

int palette_nearest_16(const uint8_t rgb[3])
{
    uint32_t best = UINT32_MAX;
    int best_i = 0;
    for (int i = 0; i < 16; i++)
        KEEP_NEAREST(palette_dist(rgb, ANSI16[i]), i, best, best_i);
    return best_i;
}

int palette_dither(int x, int y)
{
    /* Centre the matrix on zero and scale to about half the cube's 40-level step. */
    return (2 * BAYER4[y & 3][x & 3] - 15) * 5 / 4;
}
