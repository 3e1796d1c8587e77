/* test_ssaa.c: supersampling — the box filter by hand, an edge through a pixel's middle
 * mixes half and half, k = 1 is pipeline_draw itself, lines stay what they were without it,
 * and the framebuffer limit is a clear error. */
#include <string.h>

#include "obj.h"
#include "ssaa.h"
#include "test.h"

TEST(resolve_averages_colour_rounding_half_up_and_keeps_the_nearest_depth)
{
    struct fb big, out;
    REQUIRE(fb_init(&big, 4, 2, true, NULL) == 0);
    REQUIRE(fb_init(&out, 2, 1, true, NULL) == 0);
    big.depth_mode = DEPTH_Z;
    /* 4 x 2 samples, k = 2: pixel 0 is columns 0-1 of both rows, pixel 1 columns 2-3 */
    const uint8_t v[2][4] = {{0, 1, 2, 255}, {254, 3, 254, 254}};
    const float d[2][4] = {{0.5f, 0.25f, 1, 1}, {0.75f, 1, 0.6f, 1}};
    for (int y = 0; y < 2; y++)
        for (int x = 0; x < 4; x++) {
            memset(big.rgb + 3 * (y * 4 + x), v[y][x], 3);
            big.depth[y * 4 + x] = d[y][x];
            big.overdraw[y * 4 + x] = (uint32_t)(x + y);
        }
    ssaa_resolve(&big, 2, &out);
    CHECK_EQ_INT(out.rgb[0], 65);  /* (0 + 1 + 254 + 3) / 4 = 64.5: half rounds up */
    CHECK_EQ_INT(out.rgb[3], 191); /* (2 + 255 + 254 + 254) / 4 = 191.25 */
    CHECK(out.depth[0] == 0.25f);  /* the nearest sample wins (LESS) */
    CHECK(out.depth[1] == 0.6f);
    CHECK_EQ_INT(out.overdraw[0], 1); /* (0 + 1 + 1 + 2) / 4 */
    CHECK_EQ_INT(out.overdraw[1], 3); /* (2 + 3 + 3 + 4) / 4 */
    big.depth_mode = DEPTH_RZ; /* reversed z: GREATER, the nearest is the largest */
    ssaa_resolve(&big, 2, &out);
    CHECK(out.depth[0] == 1.0f);
    CHECK(out.depth[1] == 1.0f);
    CHECK(out.depth_mode == DEPTH_RZ);
    fb_free(&big);
    fb_free(&out);
}

struct quad_scene {
    struct mesh m;
    struct draw_item item;
    struct camera cam;
    struct render_opts o;
    struct pipeline *p;
};

/* a white unlit quad x in [-8, 0.5], y in [-8, 8] seen orthographically by a 16 x 16 view
 * of height 16 centred on the origin: its right edge runs down the middle of column 8 */
static int quad_init(struct quad_scene *q)
{
    memset(q, 0, sizeof *q);
    const char *obj = "v -8 -8 0\nv 0.5 -8 0\nv 0.5 8 0\nv -8 8 0\nf 1 2 3 4\n";
    if (obj_parse(obj, strlen(obj), NULL, &q->m, NULL))
        return -1;
    q->item.mesh = &q->m;
    q->item.model = m4_identity();
    camera_default(&q->cam);
    q->cam.ortho_height = 16;
    render_opts_default(&q->o);
    q->o.shade = SHADE_UNLIT;
    q->p = pipeline_new();
    return q->p ? 0 : -1;
}

static void quad_free(struct quad_scene *q)
{
    pipeline_destroy(q->p);
    mesh_free(&q->m);
}

TEST(an_edge_through_a_pixels_middle_mixes_it_half_and_half)
{
    struct quad_scene q;
    REQUIRE(quad_init(&q) == 0);
    struct fb fb;
    REQUIRE(fb_init(&fb, 16, 16, false, NULL) == 0);
    struct ssaa ss = {0};
    struct frame_stats st;
    /* default material: albedo 0.8 -> 204; column 8 holds half the samples of each row
     * (without ssaa its centre lies on the quad's right edge: outside, by the tie rule) */
    const int want[SSAA_COUNT] = {0, 102, 102, 102};
    for (enum ssaa_method m = SSAA_1; m < SSAA_COUNT; m++) {
        q.o.ssaa = m;
        REQUIRE(ssaa_draw(&ss, q.p, &q.item, 1, NULL, &q.cam, &q.o, &fb, &st, NULL) == 0);
        CHECK_EQ_INT(fb.rgb[3 * (5 * 16 + 7)], 204); /* inside */
        CHECK_EQ_INT(fb.rgb[3 * (5 * 16 + 8)], want[m]);
        CHECK_EQ_INT(fb.rgb[3 * (5 * 16 + 9)], 0);   /* outside */
        CHECK(fb_covered(&fb, 5 * 16 + 8) == (m != SSAA_1)); /* some sample is covered */
        CHECK(!fb_covered(&fb, 5 * 16 + 9));
    }
    ssaa_free(&ss);
    fb_free(&fb);
    quad_free(&q);
}

TEST(ssaa_1_is_pipeline_draw_byte_for_byte)
{
    struct quad_scene q;
    REQUIRE(quad_init(&q) == 0);
    q.cam.ortho_height = 0; /* perspective, a rotated view: slanted edges */
    q.cam.eye = v3(3, 2, 12);
    struct fb a, b;
    REQUIRE(fb_init(&a, 40, 30, false, NULL) == 0);
    REQUIRE(fb_init(&b, 40, 30, false, NULL) == 0);
    struct ssaa ss = {0};
    struct frame_stats st;
    REQUIRE(ssaa_draw(&ss, q.p, &q.item, 1, NULL, &q.cam, &q.o, &a, &st, NULL) == 0);
    REQUIRE(pipeline_draw(q.p, &q.item, 1, NULL, &q.cam, &q.o, &b, &st, NULL) == 0);
    CHECK(memcmp(a.rgb, b.rgb, 40 * 30 * 3) == 0);
    CHECK(memcmp(a.depth, b.depth, 40 * 30 * sizeof(float)) == 0);
    CHECK(ss.big.rgb == NULL); /* nothing allocated */
    ssaa_free(&ss);
    fb_free(&a);
    fb_free(&b);
    quad_free(&q);
}

TEST(lines_are_drawn_after_the_resolve_as_without_ssaa)
{
    /* a wire frame, hidden lines and the wire-overlay view: with --ssaa 4 every line pixel
     * is where it is without supersampling, in the full wire colour; under the overlay, the
     * other pixels are the supersampled surfaces */
    struct quad_scene q;
    REQUIRE(quad_init(&q) == 0);
    q.cam.ortho_height = 0;
    q.cam.eye = v3(3, 2, 12);
    struct fb a, b, c;
    REQUIRE(fb_init(&a, 40, 30, false, NULL) == 0);
    REQUIRE(fb_init(&b, 40, 30, false, NULL) == 0);
    REQUIRE(fb_init(&c, 40, 30, false, NULL) == 0);
    struct ssaa ss = {0};
    struct frame_stats st;
    q.o.wire_color[0] = 255, q.o.wire_color[1] = 0, q.o.wire_color[2] = 0;
    for (int mode = 0; mode < 3; mode++) {
        q.o.shade = mode < 2 ? SHADE_WIRE : SHADE_UNLIT;
        q.o.hidden_lines = mode == 1;
        q.o.view = mode == 2 ? VIEW_WIRE_OVERLAY : VIEW_COLOR;
        q.o.ssaa = SSAA_1;
        REQUIRE(ssaa_draw(&ss, q.p, &q.item, 1, NULL, &q.cam, &q.o, &a, &st, NULL) == 0);
        q.o.ssaa = SSAA_4;
        REQUIRE(ssaa_draw(&ss, q.p, &q.item, 1, NULL, &q.cam, &q.o, &b, &st, NULL) == 0);
        q.o.view = VIEW_COLOR; /* the surfaces alone */
        REQUIRE(ssaa_draw(&ss, q.p, &q.item, 1, NULL, &q.cam, &q.o, &c, &st, NULL) == 0);
        int lines = 0, moved = 0, other = 0;
        for (int i = 0; i < 40 * 30; i++) {
            const uint8_t *x = a.rgb + 3 * i, *y = b.rgb + 3 * i;
            bool la = x[0] == 255 && x[1] == 0, lb = y[0] == 255 && y[1] == 0;
            lines += la;
            moved += la != lb;
            other += !lb && memcmp(y, c.rgb + 3 * i, 3) != 0;
        }
        CHECK(lines > 40);
        CHECK_EQ_INT(moved, 0);
        if (mode < 2)
            CHECK(memcmp(a.rgb, b.rgb, 40 * 30 * 3) == 0);
        else
            CHECK_EQ_INT(other, 0);
    }
    ssaa_free(&ss);
    fb_free(&a);
    fb_free(&b);
    fb_free(&c);
    quad_free(&q);
}

TEST(the_big_framebuffer_limit_is_a_clear_error)
{
    struct err e = {""};
    CHECK(ssaa_check(SSAA_8, 1024, 1024, &e) == 0);
    CHECK(ssaa_check(SSAA_8, 1025, 96, &e) == -1);
    CHECK_STR_CONTAINS(e.msg, "--ssaa 8 at 1025x96 needs a 8200x768 framebuffer");
    CHECK(ssaa_check(SSAA_2, 4097, 10, &e) == -1);
}
