/* test_mip.c: mipmaps — the box-filtered chain, the level a footprint picks, trilinear
 * blending, the four-lane sampler against the scalar one, and the level of detail a frame
 * takes from its planes (a texture minified 4x draws its 4x4 averages). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "obj.h"
#include "pipeline.h"
#include "test.h"
#include "texture.h"

TEST(mip_chain_is_an_area_weighted_box_filter)
{
    /* 4x2: level 1 is 2x1, each texel the mean of a 2x2 block; level 2 is 1x1 */
    uint8_t px[4 * 2 * 4];
    for (int i = 0; i < 8; i++)
        px[4 * i] = (uint8_t)(i * 30), px[4 * i + 1] = (uint8_t)(200 - i * 20),
        px[4 * i + 2] = 7, px[4 * i + 3] = 255;
    struct texture tx;
    REQUIRE(texture_from_rgba(4, 2, px, &tx, NULL) == 0);
    CHECK_EQ_INT(tx.n_levels, 3);
    CHECK_EQ_INT(tx.level[1].w, 2);
    CHECK_EQ_INT(tx.level[1].h, 1);
    CHECK_EQ_INT(tx.level[2].w, 1);
    CHECK_EQ_INT(tx.level[2].h, 1);
    /* left block: texels 0, 1 (row 0) and 4, 5 (row 1): red (0+30+120+150)/4 = 75 */
    CHECK_EQ_INT(tx.level[1].rgba[0], 75);
    CHECK_EQ_INT(tx.level[1].rgba[1], (200 + 180 + 120 + 100) / 4);
    CHECK_EQ_INT(tx.level[1].rgba[4], (60 + 90 + 180 + 210) / 4);
    CHECK_EQ_INT(tx.level[2].rgba[0], (75 + 135) / 2);
    texture_free(&tx);
    /* odd sizes: 5x1 -> 2x1, each output texel covers 2.5 input texels */
    uint8_t odd[5 * 4];
    for (int i = 0; i < 5; i++)
        odd[4 * i] = (uint8_t)(i * 50), odd[4 * i + 1] = odd[4 * i + 2] = 0, odd[4 * i + 3] = 255;
    REQUIRE(texture_from_rgba(5, 1, odd, &tx, NULL) == 0);
    CHECK_EQ_INT(tx.level[1].w, 2);
    CHECK_EQ_INT(tx.level[1].rgba[0], (int)((0 + 50 + 0.5 * 100) / 2.5 + 0.5)); /* 40 */
    CHECK_EQ_INT(tx.level[1].rgba[4], (int)((0.5 * 100 + 150 + 200) / 2.5 + 0.5)); /* 160 */
    texture_free(&tx);
}

/* every level of an even-sized texture: each texel the mean of its 2x2 block, rounded
 * (floor(sum / 4 + 1/2): a sum of 4k + 2 rounds up), whatever the bytes */
TEST(mip_levels_of_even_sizes_are_rounded_block_means)
{
    enum { W = 32, H = 16 };
    uint8_t px[W * H * 4];
    unsigned seed = 12345;
    for (size_t i = 0; i < sizeof px; i++)
        px[i] = (uint8_t)((seed = seed * 1103515245u + 12345u) >> 16);
    struct texture tx;
    REQUIRE(texture_from_rgba(W, H, px, &tx, NULL) == 0);
    CHECK_EQ_INT(tx.n_levels, 6);
    int bad = 0, ups = 0;
    for (int l = 1; l < tx.n_levels; l++) {
        const struct texture_level *up = &tx.level[l - 1], *lv = &tx.level[l];
        if (up->w != 2 * lv->w || up->h != 2 * lv->h)
            continue; /* 2x1 -> 1x1: not a 2x2 block */
        for (int y = 0; y < lv->h; y++)
            for (int x = 0; x < lv->w * 4; x++) {
                const uint8_t *a = up->rgba + ((size_t)(2 * y) * (size_t)up->w) * 4 +
                                   (size_t)(x / 4) * 8 + (size_t)(x % 4);
                const uint8_t *b = a + (size_t)up->w * 4;
                int sum = a[0] + a[4] + b[0] + b[4];
                ups += sum % 4 == 2;
                bad += lv->rgba[(size_t)y * (size_t)lv->w * 4 + (size_t)x] != (sum + 2) / 4;
            }
    }
    CHECK_EQ_INT(bad, 0);
    CHECK(ups > 0); /* the data has halves to round */
    texture_free(&tx);
}

TEST(footprint_picks_levels_and_blends)
{
    uint8_t px[8 * 8 * 4];
    memset(px, 255, sizeof px);
    struct texture tx;
    REQUIRE(texture_from_rgba(8, 8, px, &tx, NULL) == 0);
    CHECK_EQ_INT(tx.n_levels, 4);
    float frac;
    CHECK_EQ_INT(texture_levels(&tx, -3, &frac), 0); /* magnification: level 0 */
    CHECK_EQ_INT(frac == 0, 1);
    CHECK_EQ_INT(texture_levels(&tx, 1.25f, &frac), 1);
    CHECK_NEAR(frac, 0.25, 1e-6);
    CHECK_EQ_INT(texture_levels(&tx, 9, &frac), 3); /* past the last level: the last */
    CHECK_EQ_INT(frac == 0, 1);
    texture_free(&tx);
}

/* 64x64: red a checker of 2x2-texel cells (gone by level 2), green one of 16x16-texel cells
 * (still sharp at level 2, blurred from level 4) */
static int checker64(struct texture *t)
{
    uint8_t *px = malloc(64 * 64 * 4);
    if (!px)
        return -1;
    for (int y = 0; y < 64; y++)
        for (int x = 0; x < 64; x++) {
            uint8_t *p = px + 4 * (y * 64 + x);
            p[0] = (x / 2 + y / 2) % 2 ? 255 : 0;
            p[1] = (x / 16 + y / 16) % 2 ? 255 : 0;
            p[2] = 0, p[3] = 255;
        }
    int rc = texture_from_rgba(64, 64, px, t, NULL);
    free(px);
    return rc;
}

TEST(four_lanes_sample_exactly_as_one)
{
    /* lanes in different levels (the pixel-by-pixel path) and in the same level (the vector
     * path): every lane equals the scalar sampler, bit for bit */
    struct texture tx;
    REQUIRE(checker64(&tx) == 0);
    srand(5);
    for (int n = 0; n < 2000; n++) {
        vf u, v, lam;
        int same = n % 2;
        for (int l = 0; l < SIMD_LANES; l++) {
            u[l] = (float)(rand() % 10000) / 3333.0f - 1;
            v[l] = (float)(rand() % 10000) / 4444.0f;
            lam[l] = same ? 2.3f + 0.001f * (float)l : (float)(rand() % 900) / 100.0f - 1;
        }
        vf c4[3];
        texture_sample_v(&tx, TEX_TRILINEAR, u, v, lam, c4);
        for (int l = 0; l < SIMD_LANES; l++) {
            float c[3];
            texture_sample(&tx, TEX_TRILINEAR, u[l], v[l], lam[l], c);
            for (int k = 0; k < 3; k++)
                if (c[k] != c4[k][l]) {
                    test_fail(t, __FILE__, __LINE__, "lane %d: %g != %g", l, c4[k][l], c[k]);
                    n = 2000;
                }
        }
    }
    texture_free(&tx);
}

/* one unlit quad filling a 16x16 framebuffer from the front, the checker over it `repeats`
 * times (64 * repeats / 16 texels per pixel), shifted by 1/64: then pixel centres fall on
 * texel centres of level 1, where a 2x2-texel checker of level 0 is still black and white */
static void draw_quad(struct test *t, enum tex_filter f, float repeats, uint8_t *rgb_out)
{
    char obj[256];
    const float d = 1.0f / 64;
    snprintf(obj, sizeof obj,
             "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nvt %g %g\nvt %g %g\nvt %g %g\nvt %g %g\n"
             "f 1/1 2/2 3/3 4/4\n", d, d, repeats + d, d, repeats + d, repeats + d, d,
             repeats + d);
    struct mesh m;
    struct texture tex;
    struct fb fb;
    REQUIRE(obj_parse(obj, strlen(obj), NULL, &m, NULL) == 0);
    REQUIRE(checker64(&tex) == 0);
    REQUIRE(fb_init(&fb, 16, 16, false, NULL) == 0);
    struct pipeline *p = pipeline_new();
    struct draw_item item = {.mesh = &m, .model = m4_identity(), .texture_override = &tex};
    struct camera cam;
    camera_default(&cam);
    cam.ortho_height = 2;
    struct render_opts o;
    render_opts_default(&o);
    o.shade = SHADE_UNLIT;
    o.filter = f;
    struct frame_stats st;
    REQUIRE(p && pipeline_draw(p, &item, 1, NULL, &cam, &o, &fb, &st, NULL) == 0);
    memcpy(rgb_out, fb.rgb, 16 * 16 * 3);
    pipeline_destroy(p);
    fb_free(&fb);
    texture_free(&tex);
    mesh_free(&m);
}

TEST(minified_checker_draws_its_average)
{
    /* 64 texels over 16 pixels: 4 texels per pixel, lambda = 2, and level 2 is what a pixel
     * covers: the fine red checker averages to grey 128, the coarse green one stays sharp
     * (level 1 would leave red black and white; level 3 or more would blur more of green).
     * Nearest keeps the fine checker: black and white. */
    uint8_t rgb[16 * 16 * 3];
    draw_quad(t, TEX_TRILINEAR, 1, rgb);
    int red_lo = 255, red_hi = 0, green_sharp = 0;
    for (int i = 0; i < 16 * 16; i++) {
        red_lo = rgb[3 * i] < red_lo ? rgb[3 * i] : red_lo;
        red_hi = rgb[3 * i] > red_hi ? rgb[3 * i] : red_hi;
        green_sharp += rgb[3 * i + 1] <= 1 || rgb[3 * i + 1] >= 254;
    }
    CHECK(red_lo >= 126 && red_hi <= 130);
    /* level 2 is sampled a quarter texel off its centres: pixels next to a green cell's
     * far edges blend a quarter of the next cell, the other 12 of every 16 in each
     * direction are exact: 144 of 256 */
    CHECK_EQ_INT(green_sharp, 144);
    draw_quad(t, TEX_NEAREST, 1, rgb);
    int extremes = 0;
    for (int i = 0; i < 16 * 16; i++)
        extremes += rgb[3 * i] == 0 || rgb[3 * i] == 255;
    CHECK_EQ_INT(extremes, 256);
}
