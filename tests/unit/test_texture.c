/* test_texture.c: texel conventions (v = 1 is the top row, centres at half texels, repeat),
 * both filters, and loading (LDR formats, HDR tone mapping, corrupt files). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "test.h"
#include "texture.h"

/* 2x2: top row red, green; bottom row blue, white (as a file stores it: row 0 = top) */
static int tex2(struct texture *t)
{
    static const uint8_t px[16] = {255, 0, 0, 255, 0, 255, 0, 255,
                                   0, 0, 255, 255, 255, 255, 255, 255};
    return texture_from_rgba(2, 2, px, t, NULL);
}

static void expect(struct test *t, const struct texture *tx, enum tex_filter f, float u, float v,
                   float r, float g, float b, int line)
{
    float c[3];
    texture_sample(tx, f, u, v, c);
    if (fabsf(c[0] - r) > 1e-5f || fabsf(c[1] - g) > 1e-5f || fabsf(c[2] - b) > 1e-5f)
        test_fail(t, __FILE__, line, "sample(%g, %g) = (%g %g %g), want (%g %g %g)", u, v, c[0],
                  c[1], c[2], r, g, b);
}

TEST(texture_v1_is_top_row_and_nearest_picks_floor)
{
    struct texture tx;
    REQUIRE(tex2(&tx) == 0);
    expect(t, &tx, TEX_NEAREST, 0.25f, 0.75f, 1, 0, 0, __LINE__); /* top-left: red */
    expect(t, &tx, TEX_NEAREST, 0.75f, 0.75f, 0, 1, 0, __LINE__); /* top-right: green */
    expect(t, &tx, TEX_NEAREST, 0.25f, 0.25f, 0, 0, 1, __LINE__); /* bottom-left: blue */
    expect(t, &tx, TEX_NEAREST, 0.5f, 0.5f, 0, 1, 0, __LINE__);   /* floor(1): texel 1, row 1 */
    expect(t, &tx, TEX_NEAREST, 1.25f, -0.25f, 1, 0, 0, __LINE__); /* repeat: -0.25 = 0.75 */
    expect(t, &tx, TEX_NEAREST, -0.75f, 2.75f, 1, 0, 0, __LINE__);
    texture_free(&tx);
}

TEST(texture_bilinear_centres_and_wrap)
{
    struct texture tx;
    REQUIRE(tex2(&tx) == 0);
    /* at a texel centre: exactly that texel */
    expect(t, &tx, TEX_BILINEAR, 0.25f, 0.75f, 1, 0, 0, __LINE__);
    /* halfway between the two top texels */
    expect(t, &tx, TEX_BILINEAR, 0.5f, 0.75f, 0.5f, 0.5f, 0, __LINE__);
    /* at u = 0 (an edge) repeat blends the left and right columns equally */
    expect(t, &tx, TEX_BILINEAR, 0.0f, 0.75f, 0.5f, 0.5f, 0, __LINE__);
    /* centre of the texture: the mean of all four */
    expect(t, &tx, TEX_BILINEAR, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f, __LINE__);
    texture_free(&tx);
}

/* NaN cannot come from a file (the parser rejects it), but a finite 1e38 times the width
 * overflows to inf, and inf - floor(inf) is NaN: samples must stay in [0,1] regardless */
TEST(texture_huge_and_nonfinite_coordinates_stay_in_range)
{
    struct texture tx;
    REQUIRE(tex2(&tx) == 0);
    float c[3];
    const float bad[] = {1e30f, -1e30f, INFINITY, -INFINITY, NAN};
    for (unsigned i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        texture_sample(&tx, TEX_NEAREST, bad[i], bad[i], c);
        CHECK(c[0] >= 0 && c[0] <= 1);
        texture_sample(&tx, TEX_BILINEAR, bad[i], 0.3f, c);
        CHECK(c[1] >= 0 && c[1] <= 1);
    }
    texture_free(&tx);
}

TEST(texture_load_formats_and_errors)
{
    struct texture tx;
    struct err e;
    REQUIRE(texture_load("tests/data/obj/checker2x2.png", &tx, &e) == 0);
    CHECK_EQ_INT(tx.w, 2);
    CHECK_EQ_INT(tx.h, 2);
    texture_free(&tx);
    CHECK(texture_load("tests/data/obj/corrupt.png", &tx, &e) == -1);
    CHECK_STR_CONTAINS(e.msg, "corrupt.png");
    CHECK(texture_load("tests/data/obj/no-such-file.png", &tx, &e) == -1);
    CHECK_STR_CONTAINS(e.msg, "no-such-file.png");
}

TEST(texture_hdr_is_tone_mapped_not_clipped)
{
    const char *dir = test_models_dir();
    if (!dir) {
        test_skip(t, "no ../shared/models");
        return;
    }
    char path[512];
    snprintf(path, sizeof path, "%s/sky_hdr/venice_sunset_1k.hdr", dir);
    struct texture tx;
    struct err e;
    REQUIRE(texture_load(path, &tx, &e) == 0);
    CHECK_EQ_INT(tx.w, 1024);
    CHECK_EQ_INT(tx.h, 512);
    /* radiance up to 6496 (the sun): Reinhard keeps everything below white except the
     * brightest texels, and the picture is neither black nor blown out */
    long sum = 0, white = 0, n = (long)tx.w * tx.h;
    for (long i = 0; i < n; i++) {
        const uint8_t *p = tx.rgba + 4 * i;
        sum += p[0] + p[1] + p[2];
        white += p[0] == 255 && p[1] == 255 && p[2] == 255;
    }
    double mean = sum / (3.0 * n);
    CHECK(mean > 60 && mean < 200);
    CHECK(white < n / 1000);
    texture_free(&tx);
}
