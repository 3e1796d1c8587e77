/* test_line.c: Bresenham in all octants, line clipping. */
#include <string.h>

#include "line.h"
#include "test.h"

#define W 41
#define H 41

static int count_lit(const struct fb *fb)
{
    int n = 0;
    for (int i = 0; i < fb->w * fb->h; i++)
        n += fb->rgb[3 * i] != 0;
    return n;
}

static int lit(const struct fb *fb, int x, int y)
{
    return fb->rgb[3 * (y * fb->w + x)] != 0;
}

TEST(bresenham_endpoints_and_count_every_octant)
{
    static const int d[][2] = {{15, 4},  {4, 15},   {-4, 15}, {-15, 4}, {-15, -4}, {-4, -15},
                               {4, -15}, {15, -4},  {15, 0},  {0, 15},  {-15, 0},  {0, -15},
                               {15, 15}, {-15, 15}, {15, -15}, {-15, -15}, {7, 3}, {-3, -7}};
    const uint8_t white[3] = {255, 255, 255};
    struct fb fb, rev;
    REQUIRE(fb_init(&fb, W, H, false, NULL) == 0);
    REQUIRE(fb_init(&rev, W, H, false, NULL) == 0);
    const uint8_t black[3] = {0, 0, 0};
    for (unsigned k = 0; k < sizeof d / sizeof d[0]; k++) {
        int x0 = 20, y0 = 20, x1 = 20 + d[k][0], y1 = 20 + d[k][1];
        fb_clear(&fb, black);
        fb_clear(&rev, black);
        int n = line_draw_px(&fb, x0, y0, 0, x1, y1, 0, white, 0);
        line_draw_px(&rev, x1, y1, 0, x0, y0, 0, white, 0);
        int adx = d[k][0] < 0 ? -d[k][0] : d[k][0], ady = d[k][1] < 0 ? -d[k][1] : d[k][1];
        int major = adx > ady ? adx : ady;
        CHECK_EQ_INT(n, major + 1);
        CHECK_EQ_INT(count_lit(&fb), major + 1);
        CHECK(lit(&fb, x0, y0));
        CHECK(lit(&fb, x1, y1));
        CHECK(memcmp(fb.rgb, rev.rgb, (size_t)W * H * 3) == 0); /* direction-independent */
        /* one pixel per step of the major axis, and 8-connected */
        for (int s = 0; s <= major; s++) {
            int c = 0;
            for (int o = 0; o < (adx > ady ? H : W); o++)
                c += adx > ady ? lit(&fb, x0 + (d[k][0] > 0 ? s : -s), o)
                               : lit(&fb, o, y0 + (d[k][1] > 0 ? s : -s));
            CHECK_EQ_INT(c, 1);
        }
    }
    fb_free(&fb);
    fb_free(&rev);
}

TEST(line_clip_near_plane_and_viewport)
{
    struct fb fb;
    REQUIRE(fb_init(&fb, W, H, false, NULL) == 0);
    const uint8_t black[3] = {0, 0, 0}, white[3] = {255, 255, 255};
    fb_clear(&fb, black);
    /* entirely behind the eye (w < 0, outside near): nothing */
    double a[4] = {0, 0, 2, -1}, b[4] = {0.5, 0.5, 3, -2};
    CHECK_EQ_INT(line_draw_clip(&fb, a, b, white, 0), 0);
    CHECK_EQ_INT(count_lit(&fb), 0);
    /* from in front (centre of the screen) to behind the eye: only the visible part,
     * starting at the centre pixel, never wrapping to the far side */
    double c[4] = {0, 0, 0, 1}, d[4] = {-0.5, 0, 4, -3};
    int n = line_draw_clip(&fb, c, d, white, 0);
    CHECK(n > 0);
    CHECK(lit(&fb, 20, 20));
    for (int x = 21; x < W; x++)
        CHECK(!lit(&fb, x, 20));
    /* a long horizontal line far outside the viewport in x is clipped to it: W pixels */
    fb_clear(&fb, black);
    double e0[4] = {-1000, 0, 0, 1}, e1[4] = {1000, 0, 0, 1};
    CHECK_EQ_INT(line_draw_clip(&fb, e0, e1, white, 0), W);
    /* fully outside above the top: nothing */
    double f0[4] = {-0.5, 1.5, 0, 1}, f1[4] = {0.5, 1.2, 0, 1};
    CHECK_EQ_INT(line_draw_clip(&fb, f0, f1, white, 0), 0);
    fb_free(&fb);
}

TEST(line_depth_test_hides_lines_behind_surface)
{
    struct fb fb;
    REQUIRE(fb_init(&fb, W, H, false, NULL) == 0);
    const uint8_t black[3] = {0, 0, 0}, white[3] = {255, 255, 255};
    fb_clear(&fb, black);
    for (int i = 0; i < W * H; i++)
        fb.depth[i] = 0.5f;
    CHECK_EQ_INT(line_draw_px(&fb, 0, 5, 0.9f, 40, 5, 0.9f, white, 1), 0); /* behind */
    CHECK_EQ_INT(line_draw_px(&fb, 0, 6, 0.5f, 40, 6, 0.5f, white, 1), 41); /* on it */
    CHECK_EQ_INT(line_draw_px(&fb, 0, 7, 0.9f, 40, 7, 0.9f, white, 0), 41); /* no test */
    fb_free(&fb);
}
