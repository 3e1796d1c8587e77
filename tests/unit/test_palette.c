/* test_palette.c: colour tables, nearest-colour search against brute force, the documented
 * quantisation bounds, mode names, the none-mode ramp and the dither matrix. */
#include <stdlib.h>
#include <string.h>

#include "palette.h"
#include "test.h"

static int max_chan_err(const uint8_t a[3], const uint8_t b[3])
{
    int m = 0;
    for (int k = 0; k < 3; k++) {
        int d = abs((int)a[k] - b[k]);
        m = d > m ? d : m;
    }
    return m;
}

TEST(xterm_256_table_entries)
{
    /* rule: 16 + 36r + 6g + b with levels 0,95,135,175,215,255; greys 8 + 10i */
    static const struct {
        int index, r, g, b;
    } rows[] = {
        {0, 0, 0, 0},       {1, 205, 0, 0},     {7, 229, 229, 229}, {8, 127, 127, 127},
        {12, 92, 92, 255},  {15, 255, 255, 255}, {16, 0, 0, 0},     {17, 0, 0, 95},
        {21, 0, 0, 255},    {52, 95, 0, 0},     {196, 255, 0, 0},   {145, 175, 175, 175},
        {231, 255, 255, 255}, {232, 8, 8, 8},   {244, 128, 128, 128}, {255, 238, 238, 238},
    };
    for (size_t i = 0; i < sizeof rows / sizeof rows[0]; i++) {
        uint8_t c[3];
        palette_rgb(rows[i].index, c);
        CHECK_EQ_INT(c[0], rows[i].r);
        CHECK_EQ_INT(c[1], rows[i].g);
        CHECK_EQ_INT(c[2], rows[i].b);
    }
}

TEST(palette_colours_map_to_themselves)
{
    for (int i = 16; i < 256; i++) {
        uint8_t c[3];
        palette_rgb(i, c);
        CHECK_EQ_INT(palette_nearest_256(c), i);
        CHECK_EQ_INT(palette_dist(c, c), 0);
    }
    for (int i = 0; i < 16; i++) {
        uint8_t c[3];
        palette_rgb(i, c);
        CHECK_EQ_INT(palette_nearest_16(c), i);
    }
}

TEST(fast_256_search_equals_brute_force)
{
    /* A 52^3 lattice (every 5th value, including 0 and 255) plus 200k random colours. The
     * full 2^24 comparison was run once while writing palette.c (no mismatch, 20 s). */
    int mismatches = 0;
    for (int r = 0; r < 256; r += 5)
        for (int g = 0; g < 256; g += 5)
            for (int b = 0; b < 256; b += 5) {
                uint8_t c[3] = {(uint8_t)r, (uint8_t)g, (uint8_t)b};
                mismatches += palette_nearest_256(c) != palette_nearest_256_ref(c);
            }
    uint32_t s = 2463534242u;
    for (int i = 0; i < 200000; i++) {
        s ^= s << 13;
        s ^= s >> 17;
        s ^= s << 5;
        uint8_t c[3] = {(uint8_t)(s >> 16), (uint8_t)(s >> 8), (uint8_t)s};
        mismatches += palette_nearest_256(c) != palette_nearest_256_ref(c);
    }
    CHECK_EQ_INT(mismatches, 0);
}

TEST(quantisation_error_bounds_hold_over_every_colour)
{
    /* The constants the encoder tests rely on: exact maxima over all 2^24 colours. */
    int worst256 = 0, worst16 = 0;
    uint8_t c[3], q[3];
    for (int r = 0; r < 256; r++)
        for (int g = 0; g < 256; g++)
            for (int b = 0; b < 256; b++) {
                c[0] = (uint8_t)r;
                c[1] = (uint8_t)g;
                c[2] = (uint8_t)b;
                palette_rgb(palette_nearest_256(c), q);
                int e = max_chan_err(c, q);
                worst256 = e > worst256 ? e : worst256;
                palette_rgb(palette_nearest_16(c), q);
                e = max_chan_err(c, q);
                worst16 = e > worst16 ? e : worst16;
            }
    CHECK_EQ_INT(worst256, PALETTE_256_MAX_ERR);
    CHECK_EQ_INT(worst16, PALETTE_16_MAX_ERR);
}

TEST(redmean_prefers_perceptual_neighbours)
{
    /* Green differences weigh 4, red 2..3, blue 2..3: a green step costs more than a blue one. */
    uint8_t a[3] = {100, 100, 100}, g[3] = {100, 110, 100}, b[3] = {100, 100, 110};
    CHECK(palette_dist(a, g) > palette_dist(a, b));
    CHECK_EQ_INT(palette_dist(a, g), palette_dist(g, a));
    /* a mid grey maps to the grey ramp, not the cube's coarse 95/135 */
    uint8_t grey[3] = {118, 118, 118};
    CHECK_EQ_INT(palette_nearest_256(grey), 243); /* 8 + 10*11 = 118 */
}

TEST(mode_names_parse_and_print)
{
    static const struct {
        const char *s;
        enum palette_mode m;
    } ok[] = {{"truecolor", PALETTE_TRUECOLOR}, {"24bit", PALETTE_TRUECOLOR},
              {"TrueColor", PALETTE_TRUECOLOR}, {"256", PALETTE_256},
              {"16", PALETTE_16},               {"none", PALETTE_NONE}};
    for (size_t i = 0; i < sizeof ok / sizeof ok[0]; i++) {
        enum palette_mode m = PALETTE_MODE_COUNT;
        CHECK(palette_mode_parse(ok[i].s, &m, NULL) == 0);
        CHECK_EQ_INT(m, ok[i].m);
    }
    CHECK(strcmp(palette_mode_name(PALETTE_256), "256") == 0);
    CHECK(strcmp(palette_mode_name(PALETTE_TRUECOLOR), "truecolor") == 0);
    enum palette_mode m;
    struct err e;
    CHECK(palette_mode_parse("8\x1b[31m", &m, &e) == -1);
    CHECK_STR_CONTAINS(e.msg, "'8?[31m' unknown");
}

TEST(ramp_levels_cover_black_to_white)
{
    static const uint8_t white[3] = {255, 255, 255}, black[3] = {0, 0, 0};
    CHECK_EQ_INT(palette_luma(white), 255);
    CHECK_EQ_INT(palette_luma(black), 0);
    CHECK_EQ_INT(palette_ramp_level(0), 0);
    CHECK_EQ_INT(palette_ramp_level(255), PALETTE_RAMP_LEVELS - 1);
    CHECK_EQ_INT(palette_ramp_level(14), 0);  /* rounds: 14*9/255 = 0.49 */
    CHECK_EQ_INT(palette_ramp_level(15), 1);  /* 0.53 */
    CHECK_EQ_INT(palette_ramp_grey(0), 0);
    CHECK_EQ_INT(palette_ramp_grey(PALETTE_RAMP_LEVELS - 1), 255);
    CHECK_EQ_INT((int)strlen(PALETTE_RAMP), PALETTE_RAMP_LEVELS);
    for (int l = 0; l < PALETTE_RAMP_LEVELS; l++) /* grey(level) maps back to the level */
        CHECK_EQ_INT(palette_ramp_level(palette_ramp_grey(l)), l);
}

TEST(dither_offsets_are_centred_and_bounded)
{
    int sum = 0, seen[64] = {0};
    for (int y = 0; y < 4; y++)
        for (int x = 0; x < 4; x++) {
            int d = palette_dither(x, y);
            CHECK(d >= -PALETTE_DITHER_AMP && d <= PALETTE_DITHER_AMP);
            CHECK_EQ_INT(d, palette_dither(x + 4, y + 8)); /* period 4 */
            sum += d;
            seen[d + 32]++;
        }
    CHECK_EQ_INT(sum, 0);
    for (int i = 0; i < 64; i++)
        CHECK(seen[i] <= 1); /* 16 distinct thresholds */
}
