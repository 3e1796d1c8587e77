/* test_raster.c: coverage, the tie rule and attribute interpolation of setup + raster.
 * Failing coverage tests print the frame as a picture: '.' empty, digits = times written. */
#include <stdlib.h>
#include <string.h>

#include "raster.h"
#include "setup.h"
#include "test.h"

#define W 32
#define H 24

/* a vertex at window position (x, y) (pixels, y down), depth z, w = 1 */
static struct vertex_out win(double x, double y)
{
    struct vertex_out v;
    memset(&v, 0, sizeof v);
    v.clip[0] = 2.0 * x / W - 1;
    v.clip[1] = 1 - 2.0 * y / H;
    v.clip[2] = 0;
    v.clip[3] = 1;
    return v;
}

struct rig {
    struct fb fb;
    struct shade_ctx sc;
    struct material mat;
    struct shade_tri st;
    struct frame_stats stats;
};

static void rig_init(struct rig *r)
{
    struct render_opts o;
    render_opts_default(&o);
    o.shade = SHADE_UNLIT;
    float eye[3] = {0, 0, 3}, back[3] = {0, 0, 1};
    memset(r, 0, sizeof *r);
    fb_init(&r->fb, W, H, true, NULL);
    uint8_t bg[3] = {0, 0, 0};
    fb_clear(&r->fb, bg);
    shade_ctx_init(&r->sc, &o, eye, 0, back);
    r->mat.kd[0] = r->mat.kd[1] = r->mat.kd[2] = 1;
    r->mat.ns = 32;
    r->mat.texture = -1;
    r->st.mat = &r->mat;
    memcpy(r->st.base, r->mat.kd, sizeof r->st.base);
}

/* draw without depth test interference: every triangle gets a fresh depth buffer slot
 * (overdraw counts coverage before the depth test anyway) */
static void draw(struct rig *r, struct vertex_out a, struct vertex_out b, struct vertex_out c)
{
    struct setup_tri t;
    if (setup_triangle(&a, &b, &c, W, H, CULL_NONE, 2, &t) == SETUP_DRAW)
        raster_triangle(&t, &r->sc, &r->st, &r->fb, &r->stats);
}

static void print_overdraw(const struct fb *fb)
{
    for (int y = 0; y < fb->h; y++) {
        fprintf(stderr, "      ");
        for (int x = 0; x < fb->w; x++) {
            uint32_t k = fb->overdraw[y * fb->w + x];
            fputc(k == 0 ? '.' : k > 9 ? '+' : (char)('0' + k), stderr);
        }
        fputc('\n', stderr);
    }
}

/* every pixel with centre in [x0,x1) x [y0,y1) written exactly once, none outside */
static int check_exact_cover(struct test *t, const struct fb *fb, int x0, int y0, int x1, int y1,
                             int line)
{
    int bad = 0;
    for (int y = 0; y < fb->h; y++)
        for (int x = 0; x < fb->w; x++) {
            uint32_t want = (x >= x0 && x < x1 && y >= y0 && y < y1) ? 1 : 0;
            bad += fb->overdraw[y * fb->w + x] != want;
        }
    if (bad) {
        test_fail(t, __FILE__, line, "%d pixels not written exactly once", bad);
        print_overdraw(fb);
    }
    return bad;
}

TEST(shared_edge_drawn_once_square_split)
{
    /* square with corners ON pixel centres: its edges and diagonal pass through centres */
    struct rig r;
    rig_init(&r);
    draw(&r, win(4.5, 4.5), win(12.5, 4.5), win(12.5, 12.5));
    draw(&r, win(4.5, 4.5), win(12.5, 12.5), win(4.5, 12.5));
    /* tie rule: left edge x=4.5 in, right edge x=12.5 out; bottom y=12.5 in, top y=4.5 out */
    check_exact_cover(t, &r.fb, 4, 5, 12, 13, __LINE__);
    fb_free(&r.fb);
}

TEST(tie_rule_left_and_bottom_edges_own_centres)
{
    struct rig r;
    rig_init(&r);
    /* right triangle: vertical left edge x=2.5, horizontal bottom edge y=10.5 (image coords) */
    draw(&r, win(2.5, 2.5), win(2.5, 10.5), win(10.5, 10.5));
    const struct fb *fb = &r.fb;
    CHECK_EQ_INT(fb->overdraw[6 * W + 2], 1);  /* on the left edge: inside */
    CHECK_EQ_INT(fb->overdraw[10 * W + 6], 1); /* on the bottom edge: inside */
    CHECK_EQ_INT(fb->overdraw[6 * W + 6], 0);  /* on the hypotenuse (a right/top edge): out */
    CHECK_EQ_INT(fb->overdraw[7 * W + 6], 1);  /* just below the hypotenuse: inside */
    /* mirrored: vertical RIGHT edge and horizontal TOP edge do not own their centres */
    fb_free(&r.fb);
    rig_init(&r);
    draw(&r, win(20.5, 2.5), win(12.5, 2.5), win(20.5, 10.5));
    CHECK_EQ_INT(r.fb.overdraw[6 * W + 20], 0);  /* right edge */
    CHECK_EQ_INT(r.fb.overdraw[2 * W + 16], 0);  /* top edge */
    CHECK_EQ_INT(r.fb.overdraw[3 * W + 19], 1);
    fb_free(&r.fb);
}

TEST(fan_around_centre_covers_disc_exactly_once)
{
    /* 16 triangles around a pixel centre: edges through centres in many directions */
    struct rig r;
    rig_init(&r);
    double cx = 15.5, cy = 11.5;
    double ring[][2] = {{10, 0}, {10, 5}, {10, 10}, {5, 10}, {0, 10}, {-5, 10}, {-10, 10},
                        {-10, 5}, {-10, 0}, {-10, -5}, {-10, -10}, {-5, -10}, {0, -10},
                        {5, -10}, {10, -10}, {10, -5}};
    for (int i = 0; i < 16; i++) {
        int j = (i + 1) % 16;
        draw(&r, win(cx, cy), win(cx + ring[i][0], cy + ring[i][1]),
             win(cx + ring[j][0], cy + ring[j][1]));
    }
    /* the fan is the square [5.5,25.5] x [1.5,21.5]: left/bottom in, right/top out */
    check_exact_cover(t, &r.fb, 5, 2, 25, 22, __LINE__);
    fb_free(&r.fb);
}

TEST(random_triangulation_of_rectangle_no_cracks_no_overlaps)
{
    /* a grid with jittered interior vertices (arbitrary 1/256 positions), split into
     * triangles both ways: every centre of the rectangle covered exactly once */
    srand(12345);
    for (int trial = 0; trial < 20; trial++) {
        struct rig r;
        rig_init(&r);
        enum { N = 6 };
        double px[N + 1][N + 1], py[N + 1][N + 1];
        for (int j = 0; j <= N; j++)
            for (int i = 0; i <= N; i++) {
                px[j][i] = 2 + 4.0 * i;
                py[j][i] = 1 + 3.5 * j;
                if (i > 0 && i < N && j > 0 && j < N) {
                    px[j][i] += (rand() % 512 - 256) / 256.0;
                    py[j][i] += (rand() % 512 - 256) / 256.0;
                }
            }
        for (int j = 0; j < N; j++)
            for (int i = 0; i < N; i++) {
                struct vertex_out a = win(px[j][i], py[j][i]), b = win(px[j][i + 1], py[j][i + 1]);
                struct vertex_out c = win(px[j + 1][i + 1], py[j + 1][i + 1]);
                struct vertex_out d = win(px[j + 1][i], py[j + 1][i]);
                if ((i + j + trial) % 2) {
                    draw(&r, a, b, c);
                    draw(&r, a, c, d);
                } else {
                    draw(&r, a, b, d);
                    draw(&r, b, c, d);
                }
            }
        /* rectangle x in [2, 26], y in [1, 22]: centres x 2..25, y 1..21 */
        int bad = check_exact_cover(t, &r.fb, 2, 1, 26, 22, __LINE__);
        fb_free(&r.fb);
        if (bad)
            break;
    }
}

TEST(zero_area_and_subpixel_triangles_draw_nothing)
{
    struct rig r;
    rig_init(&r);
    struct setup_tri tri;
    struct vertex_out a = win(1, 1), b = win(10, 10), c = win(19, 19);
    CHECK_EQ_INT(setup_triangle(&a, &b, &c, W, H, CULL_NONE, 2, &tri), SETUP_EMPTY);
    /* tiny triangle between centres */
    a = win(5.6, 5.6), b = win(5.9, 5.6), c = win(5.6, 5.9);
    CHECK_EQ_INT(setup_triangle(&a, &b, &c, W, H, CULL_NONE, 2, &tri), SETUP_EMPTY);
    /* entirely off to the right */
    a = win(40, 1), b = win(50, 1), c = win(45, 9);
    CHECK_EQ_INT(setup_triangle(&a, &b, &c, W, H, CULL_NONE, 2, &tri), SETUP_EMPTY);
    fb_free(&r.fb);
}

TEST(cull_back_removes_clockwise_faces)
{
    struct setup_tri tri;
    /* top-left -> bottom-left -> bottom-right: counter-clockwise as displayed (and in GL's
     * y-up window coordinates, which display the same way up): the front face */
    struct vertex_out a = win(2, 2), b = win(2, 10), c = win(10, 10);
    CHECK_EQ_INT(setup_triangle(&a, &b, &c, W, H, CULL_FRONT, 2, &tri), SETUP_CULLED);
    CHECK_EQ_INT(setup_triangle(&a, &b, &c, W, H, CULL_BACK, 2, &tri), SETUP_DRAW);
    CHECK_EQ_INT(tri.front, 1);
    CHECK_EQ_INT(setup_triangle(&a, &c, &b, W, H, CULL_BACK, 2, &tri), SETUP_CULLED);
    CHECK_EQ_INT(setup_triangle(&a, &c, &b, W, H, CULL_NONE, 2, &tri), SETUP_DRAW);
    CHECK_EQ_INT(tri.front, 0);
}

TEST(perspective_correct_varying_and_linear_depth)
{
    /* a quad receding in depth: u goes 0..1 along x; with w = 1 on the left and 4 on the
     * right, the screen midpoint sees u = 1/(1+4) * ... = 0.2 (perspective), not 0.5 */
    struct rig r;
    rig_init(&r);
    struct vertex_out v[3];
    double xs[3] = {0, 32, 0}, ys[3] = {0, 12, 24}, ws[3] = {1, 4, 1}, us[3] = {0, 1, 0};
    for (int i = 0; i < 3; i++) {
        v[i] = win(xs[i], ys[i]);
        for (int k = 0; k < 4; k++)
            v[i].clip[k] *= ws[i]; /* same window position, different w */
        v[i].clip[2] = ws[i] * (i == 1 ? 0.5 : -0.5); /* ndc z -0.5 left, 0.5 right */
        v[i].var[0] = (float)us[i];
    }
    struct setup_tri tri;
    REQUIRE(setup_triangle(&v[0], &v[1], &v[2], W, H, CULL_NONE, 2, &tri) == SETUP_DRAW);
    /* pixel (15, 11): centre (15.5, 11.5); screen fraction s = 15.5/32 along x at that row
     * is not exactly the edge param, so compute barycentrics directly */
    double sx = 15.5, sy = 11.5;
    double l1 = 0, l2;
    {
        double ax = xs[0], ay = ys[0], bx = xs[1], by = ys[1], cx = xs[2], cy = ys[2];
        double area = (bx - ax) * (cy - ay) - (by - ay) * (cx - ax);
        l1 = ((sx - ax) * (cy - ay) - (sy - ay) * (cx - ax)) / area;
        l2 = ((bx - ax) * (sy - ay) - (by - ay) * (sx - ax)) / area;
    }
    double l0 = 1 - l1 - l2;
    double want_u = (l1 * 1 / 4.0) / (l0 / 1 + l1 / 4.0 + l2 / 1);
    double want_z = 0.5 * (l0 * -0.5 + l1 * 0.5 + l2 * -0.5) + 0.5;
    r.sc.shade = SHADE_UNLIT;
    raster_triangle(&tri, &r.sc, &r.st, &r.fb, &r.stats);
    CHECK_NEAR(r.fb.depth[11 * W + 15], want_z, 1e-6);
    /* u comes back through the shading: unlit albedo = kd * texel of a 256-wide gradient
     * texture whose texel i is i (red), so the red channel is floor(u*256) */
    CHECK(want_u < 0.3); /* and it really is not the affine 0.48 */
    uint8_t px[256 * 4];
    for (int i = 0; i < 256; i++)
        px[4 * i] = (uint8_t)i, px[4 * i + 1] = px[4 * i + 2] = 0, px[4 * i + 3] = 255;
    struct texture tex;
    REQUIRE(texture_from_rgba(256, 1, px, &tex, NULL) == 0);
    r.st.tex = &tex;
    r.fb.depth[11 * W + 15] = 1;
    raster_triangle(&tri, &r.sc, &r.st, &r.fb, &r.stats);
    CHECK_EQ_INT(r.fb.rgb[3 * (11 * W + 15)], (int)(want_u * 256));
    texture_free(&tex);
    fb_free(&r.fb);
}
