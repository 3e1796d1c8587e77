/* test_raster.c: coverage, the tie rule, snapping and attribute interpolation of setup +
 * the three rasterizers + the span shader. Coverage tests run once per rasterizer; failing
 * ones print the frame as a picture: '.' empty, digits = times written. */
#include <stdlib.h>
#include <string.h>

#include "kernel.h"
#include "raster.h"
#include "setup.h"
#include "span.h"
#include "test.h"
#include "viewport.h"

#define W 32
#define H 24

/* a projected vertex at window position (x, y) (pixels, y down), depth z, w = 1 */
static struct vertex_out win(double x, double y)
{
    struct vertex_out v;
    memset(&v, 0, sizeof v);
    v.clip[0] = 2.0 * x / W - 1;
    v.clip[1] = 1 - 2.0 * y / H;
    v.clip[2] = 0;
    v.clip[3] = 1;
    vertex_project(&v, W, H);
    return v;
}

struct rig {
    struct fb fb;
    struct shade_ctx sc;
    struct material mat;
    struct shade_tri st;
    struct span_ctx span;
    enum raster_method method;
};

static void rig_init(struct rig *r, enum raster_method method)
{
    struct render_opts o;
    render_opts_default(&o);
    o.shade = SHADE_UNLIT;
    o.filter = TEX_NEAREST; /* the tests read texels back */
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
    r->span.fb = &r->fb;
    r->span.shade = &r->sc;
    r->span.mode = SHADE_UNLIT;
    r->span.persp = PERSP_CORRECT;
    r->span.depth = DEPTH_Z;
    r->method = method;
}

/* one triangle through setup, the rig's rasterizer and the span shader; 1 if set up */
static int draw(struct rig *r, struct vertex_out a, struct vertex_out b, struct vertex_out c)
{
    struct setup_tri t;
    if (setup_triangle(&a, &b, &c, W, H, &t) != SETUP_DRAW)
        return 0;
    struct raster_rect all = {0, 0, W - 1, H - 1};
    const struct kernel_set *ks = kernel_set(KERNEL_AUTO); /* (for the rig's methods now) */
    kernel_choose_span(ks, &r->span);
    span_begin(&r->span, &t, &r->st, 0);
    ks->by_size[SPAN_SIZE_LARGE]->raster[r->method](&t, all, &r->span);
    span_end(&r->span);
    return 1;
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
static int check_exact_cover(struct test *t, const struct rig *r, int x0, int y0, int x1,
                             int y1, int line)
{
    const struct fb *fb = &r->fb;
    int bad = 0;
    for (int y = 0; y < fb->h; y++)
        for (int x = 0; x < fb->w; x++) {
            uint32_t want = (x >= x0 && x < x1 && y >= y0 && y < y1) ? 1 : 0;
            bad += fb->overdraw[y * fb->w + x] != want;
        }
    if (bad) {
        test_fail(t, __FILE__, line, "%s rasterizer: %d pixels not written exactly once",
                  render_raster_name(r->method), bad);
        print_overdraw(fb);
    }
    return bad;
}

#define EACH_RASTER(m) for (enum raster_method m = 0; m < RASTER_COUNT; m++)

TEST(shared_edge_drawn_once_square_split)
{
    EACH_RASTER(m) {
        /* square with corners ON pixel centres: its edges and diagonal pass through centres */
        struct rig r;
        rig_init(&r, m);
        draw(&r, win(4.5, 4.5), win(12.5, 4.5), win(12.5, 12.5));
        draw(&r, win(4.5, 4.5), win(12.5, 12.5), win(4.5, 12.5));
        /* tie rule: left edge x=4.5 in, right edge x=12.5 out; bottom y=12.5 in, top y=4.5 out */
        check_exact_cover(t, &r, 4, 5, 12, 13, __LINE__);
        fb_free(&r.fb);
    }
}

TEST(tie_rule_left_and_bottom_edges_own_centres)
{
    EACH_RASTER(m) {
        struct rig r;
        rig_init(&r, m);
        /* right triangle: vertical left edge x=2.5, horizontal bottom edge y=10.5 (image coords) */
        draw(&r, win(2.5, 2.5), win(2.5, 10.5), win(10.5, 10.5));
        const struct fb *fb = &r.fb;
        CHECK_EQ_INT(fb->overdraw[6 * W + 2], 1);  /* on the left edge: inside */
        CHECK_EQ_INT(fb->overdraw[10 * W + 6], 1); /* on the bottom edge: inside */
        CHECK_EQ_INT(fb->overdraw[6 * W + 6], 0);  /* on the hypotenuse (a right/top edge): out */
        CHECK_EQ_INT(fb->overdraw[7 * W + 6], 1);  /* just below the hypotenuse: inside */
        /* mirrored: vertical RIGHT edge and horizontal TOP edge do not own their centres */
        fb_free(&r.fb);
        rig_init(&r, m);
        draw(&r, win(20.5, 2.5), win(12.5, 2.5), win(20.5, 10.5));
        CHECK_EQ_INT(r.fb.overdraw[6 * W + 20], 0); /* right edge */
        CHECK_EQ_INT(r.fb.overdraw[2 * W + 16], 0); /* top edge */
        CHECK_EQ_INT(r.fb.overdraw[3 * W + 19], 1);
        fb_free(&r.fb);
    }
}

TEST(snapping_is_one_256th_of_a_pixel)
{
    /* a left edge one snap step right of a column of centres must miss them; one step left,
     * cover them. At 1/128 px both would snap onto the centres (and the tie rule would
     * cover them); with no snapping at all the test still holds, so the next check pins the
     * rounding itself. */
    const double step = 1.0 / 256;
    EACH_RASTER(m) {
        for (int side = 0; side < 2; side++) {
            struct rig r;
            rig_init(&r, m);
            double x = 10.5 + (side ? -step : step);
            draw(&r, win(x, 2), win(x, 20), win(20, 11));
            for (int y = 4; y <= 18; y++)
                CHECK_EQ_INT(r.fb.overdraw[y * W + 10], side ? 1 : 0);
            CHECK_EQ_INT(r.fb.overdraw[11 * W + 11], 1);
            fb_free(&r.fb);
        }
    }
    /* 3/1024 px rounds to the nearest 1/256 (3 units of 1/1024 = 0.75/256 -> 1/256), and
     * half a step rounds to even */
    CHECK_EQ_INT(viewport_snap(10.5 + 3.0 / 1024), 10 * 256 + 128 + 1);
    CHECK_EQ_INT(viewport_snap(5.5 + 1.0 / 512), 5 * 256 + 128); /* 128.5 -> 128 (even) */
    CHECK_EQ_INT(viewport_snap(0.5 + 3.0 / 512), 128 + 2);      /* 129.5 -> 130 (even) */
}

TEST(fan_around_centre_covers_disc_exactly_once)
{
    EACH_RASTER(m) {
        /* 16 triangles around a pixel centre: edges through centres in many directions */
        struct rig r;
        rig_init(&r, m);
        double cx = 15.5, cy = 11.5;
        double ring[][2] = {{10, 0},  {10, 5},   {10, 10},   {5, 10},  {0, 10},   {-5, 10},
                            {-10, 10}, {-10, 5}, {-10, 0},   {-10, -5}, {-10, -10}, {-5, -10},
                            {0, -10}, {5, -10},  {10, -10},  {10, -5}};
        for (int i = 0; i < 16; i++) {
            int j = (i + 1) % 16;
            draw(&r, win(cx, cy), win(cx + ring[i][0], cy + ring[i][1]),
                 win(cx + ring[j][0], cy + ring[j][1]));
        }
        /* the fan is the square [5.5,25.5] x [1.5,21.5]: left/bottom in, right/top out */
        check_exact_cover(t, &r, 5, 2, 25, 22, __LINE__);
        fb_free(&r.fb);
    }
}

TEST(random_triangulation_of_rectangle_no_cracks_no_overlaps)
{
    /* a grid with jittered interior vertices (arbitrary 1/256 positions), split into
     * triangles both ways: every centre of the rectangle covered exactly once */
    EACH_RASTER(m) {
        srand(12345);
        for (int trial = 0; trial < 20; trial++) {
            struct rig r;
            rig_init(&r, m);
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
                    struct vertex_out a = win(px[j][i], py[j][i]);
                    struct vertex_out b = win(px[j][i + 1], py[j][i + 1]);
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
            int bad = check_exact_cover(t, &r, 2, 1, 26, 22, __LINE__);
            fb_free(&r.fb);
            if (bad)
                break;
        }
    }
}

/* a random window coordinate: mostly on pixel centres, half pixels and pixel corners (where
 * ties happen), otherwise any 1/256 position; sometimes far outside the framebuffer */
static double rand_coord(int n)
{
    int k = rand() % 8;
    double base = rand() % (n + 8) - 4;
    if (k == 0)
        return base + 0.5;
    if (k == 1)
        return base;
    if (k == 2)
        return (rand() % 4000 - 2000) / 7.0;
    return base + (rand() % 256) / 256.0;
}

TEST(rasterizers_find_identical_pixels_on_random_triangles)
{
    /* 20000 random triangles (slivers, huge, on ties, off screen), each drawn alone by all
     * three rasterizers: the same pixels, and the same bytes */
    srand(777);
    uint8_t px[16 * 16 * 4];
    for (int i = 0; i < 16 * 16 * 4; i++)
        px[i] = (uint8_t)rand();
    struct texture tex;
    REQUIRE(texture_from_rgba(16, 16, px, &tex, NULL) == 0);
    struct rig r[RASTER_COUNT];
    EACH_RASTER(m) {
        rig_init(&r[m], m);
        r[m].st.tex = &tex;
    }
    int mismatches = 0, drawn = 0;
    for (int i = 0; i < 20000 && mismatches < 5; i++) {
        struct vertex_out v[3];
        for (int k = 0; k < 3; k++) {
            if (i % 4 == 3 && k > 0) { /* a sliver: near the previous corner's line */
                v[k] = win(v[0].win[0] + (rand() % 2000) / 100.0,
                           v[0].win[1] + (rand() % 2000) / 100.0 * 1e-3);
                continue;
            }
            v[k] = win(rand_coord(W), rand_coord(H));
            v[k].var[0] = (float)(rand() % 100) / 100, v[k].var[1] = (float)k;
        }
        EACH_RASTER(m) {
            uint8_t bg[3] = {0, 0, 0};
            fb_clear(&r[m].fb, bg);
            memset(r[m].fb.overdraw, 0, W * H * sizeof *r[m].fb.overdraw);
            drawn += draw(&r[m], v[0], v[1], v[2]) && m == 0;
        }
        for (int m = 1; m < RASTER_COUNT; m++)
            if (memcmp(r[0].fb.overdraw, r[m].fb.overdraw, W * H * sizeof(uint32_t)) ||
                memcmp(r[0].fb.rgb, r[m].fb.rgb, W * H * 3) ||
                memcmp(r[0].fb.depth, r[m].fb.depth, W * H * sizeof(float))) {
                test_fail(t, __FILE__, __LINE__, "triangle %d: %s differs from edge", i,
                          render_raster_name((enum raster_method)m));
                print_overdraw(&r[0].fb);
                print_overdraw(&r[m].fb);
                mismatches++;
            }
    }
    CHECK(drawn > 5000); /* the test really drew triangles */
    EACH_RASTER(m) fb_free(&r[m].fb);
    texture_free(&tex);
}

TEST(zero_area_and_subpixel_triangles_draw_nothing)
{
    struct setup_tri tri;
    struct vertex_out a = win(1, 1), b = win(10, 10), c = win(19, 19);
    CHECK_EQ_INT(setup_triangle(&a, &b, &c, W, H, &tri), SETUP_EMPTY);
    /* tiny triangle between centres */
    a = win(5.6, 5.6), b = win(5.9, 5.6), c = win(5.6, 5.9);
    CHECK_EQ_INT(setup_triangle(&a, &b, &c, W, H, &tri), SETUP_EMPTY);
    /* entirely off to the right */
    a = win(40, 1), b = win(50, 1), c = win(45, 9);
    CHECK_EQ_INT(setup_triangle(&a, &b, &c, W, H, &tri), SETUP_EMPTY);
}

TEST(cull_back_removes_clockwise_faces)
{
    /* top-left -> bottom-left -> bottom-right: counter-clockwise as displayed (and in GL's
     * y-up window coordinates, which display the same way up): the front face */
    struct vertex_out a = win(2, 2), b = win(2, 10), c = win(10, 10);
    CHECK_EQ_INT(setup_front_facing(&a, &b, &c), 1);
    CHECK_EQ_INT(setup_front_facing(&a, &c, &b), 0);
    CHECK(setup_culled(CULL_FRONT, 1));
    CHECK(!setup_culled(CULL_BACK, 1));
    CHECK(setup_culled(CULL_BACK, 0));
    CHECK(!setup_culled(CULL_NONE, 0) && !setup_culled(CULL_NONE, 1));
    /* valid behind the eye too: negating every clip coordinate keeps the window position
     * and the facing (w < 0 on all three corners) */
    struct vertex_out na = a, nb = b, nc = c;
    for (int k = 0; k < 4; k++)
        na.clip[k] = -a.clip[k], nb.clip[k] = -b.clip[k], nc.clip[k] = -c.clip[k];
    CHECK_EQ_INT(setup_front_facing(&na, &nb, &nc), 0); /* det flips sign with w */
}

TEST(depth_test_less_keeps_the_first_of_equal_depths)
{
    /* the same triangle twice, red then green: LESS (and GREATER for reversed z) keeps red;
     * a <= test would let green through */
    for (enum depth_mode d = 0; d < DEPTH_COUNT; d++) {
        struct rig r;
        rig_init(&r, RASTER_EDGE);
        r.span.depth = d;
        r.fb.depth_mode = d;
        r.fb.proj = (struct fb_depth_proj){1, 0.1, 100}; /* w = 1 everywhere: orthographic */
        uint8_t bg[3] = {0, 0, 0};
        fb_clear(&r.fb, bg);
        struct vertex_out a = win(2, 2), b = win(2, 20), c = win(28, 12);
        for (int k = 0; k < 2; k++) {
            float col[3] = {(float)(k == 0), (float)(k == 1), 0};
            memcpy(r.st.base, col, sizeof col);
            draw(&r, a, b, c);
        }
        int i = 11 * W + 8;
        CHECK_EQ_INT(r.fb.overdraw[i], 2);
        CHECK_EQ_INT(r.fb.rgb[3 * i], 255);
        CHECK_EQ_INT(r.fb.rgb[3 * i + 1], 0);
        CHECK(fb_covered(&r.fb, (size_t)i));
        CHECK(!fb_covered(&r.fb, 0));
        CHECK_NEAR(fb_depth_window(&r.fb, (size_t)i), 0.5, d == DEPTH_Z16 ? 1e-5 : 1e-6);
        fb_free(&r.fb);
    }
}

TEST(sliver_depth_stays_within_its_corners)
{
    /* a sliver whose unsnapped height (1e-4 px) is far below the snap error: its corners'
     * snapped positions cover a row of centres, where unsnapped barycentrics extrapolate
     * by thousands. Corners at depth 0.90 .. 0.95: no written depth may leave that range
     * (it once wrote 0.036, punching through nearer surfaces). */
    EACH_RASTER(m) {
        struct rig r;
        rig_init(&r, m);
        double zs[3] = {0.90, 0.95, 0.92};
        double xs[3] = {1.3, 30.7, 16.1}, ys[3] = {10.5 + 1.5 / 256, 10.5 + 1.5 / 256,
                                                     10.5 + 1.5 / 256 - 1e-4};
        struct vertex_out v[3];
        for (int k = 0; k < 3; k++) {
            v[k] = win(xs[k], ys[k]);
            v[k].clip[2] = 2 * zs[k] - 1; /* window depth zs[k] */
        }
        /* the snapped corners: two at 10.5+2/256 (1.5 rounds to even 2), one moved to 1/256
         * above the centre row (as a snap of a slightly different position would put it):
         * the snapped triangle covers centres of row 10, the unsnapped one (same
         * orientation, 1e-4 px tall) lies entirely below them */
        v[2].fy = 10 * 256 + 128 - 1;
        /* Gouraud terms D = 0.1, 0.3, 0.5 (red) at the corners, S = 0, albedo 1: the red
         * channel is D itself, and must stay inside the corners' hull too */
        r.span.mode = SHADE_GOURAUD;
        for (int k = 0; k < 3; k++)
            v[k].var[2] = 0.1f + 0.2f * (float)k;
        REQUIRE(draw(&r, v[0], v[1], v[2]));
        int covered = 0;
        for (int i = 0; i < W * H; i++) {
            if (!fb_covered(&r.fb, (size_t)i))
                continue;
            covered++;
            CHECK(r.fb.depth[i] >= 0.90f && r.fb.depth[i] <= 0.95f);
            CHECK(r.fb.rgb[3 * i] >= 25 && r.fb.rgb[3 * i] <= 128);
        }
        CHECK(covered > 0);
        fb_free(&r.fb);
    }
}

TEST(perspective_correct_varying_and_linear_depth)
{
    /* a quad receding in depth: u goes 0..1 along x; with w = 1 on the left and 4 on the
     * right, the screen midpoint sees u = 1/(1+4) * ... = 0.2 (perspective), not 0.5 */
    struct rig r;
    rig_init(&r, RASTER_EDGE);
    struct vertex_out v[3];
    double xs[3] = {0, 32, 0}, ys[3] = {0, 12, 24}, ws[3] = {1, 4, 1}, us[3] = {0, 1, 0};
    for (int i = 0; i < 3; i++) {
        v[i] = win(xs[i], ys[i]);
        for (int k = 0; k < 4; k++)
            v[i].clip[k] *= ws[i]; /* same window position, different w */
        v[i].clip[2] = ws[i] * (i == 1 ? 0.5 : -0.5); /* ndc z -0.5 left, 0.5 right */
        vertex_project(&v[i], W, H);
        v[i].var[0] = (float)us[i];
    }
    /* pixel (15, 11): centre (15.5, 11.5) */
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
    REQUIRE(draw(&r, v[0], v[1], v[2]));
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
    const enum persp_method methods[] = {PERSP_CORRECT, PERSP_AFFINE, PERSP_SPAN8};
    int red[3];
    for (int k = 0; k < 3; k++) {
        r.span.persp = methods[k];
        r.fb.depth[11 * W + 15] = 1;
        draw(&r, v[0], v[1], v[2]);
        red[k] = r.fb.rgb[3 * (11 * W + 15)];
    }
    CHECK_EQ_INT(red[0], (int)(want_u * 256));
    CHECK_EQ_INT(red[1], (int)((l1 * 1) * 256)); /* affine: u = l1 */
    /* span8: exact at columns 8 and 16 of row 11, affine between: within the two */
    CHECK(red[2] != red[0] && abs(red[2] - red[0]) < abs(red[1] - red[0]));
    texture_free(&tex);
    fb_free(&r.fb);
}
