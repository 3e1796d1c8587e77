/* test_methods.c: every method where it must hold and where theory says it must fail —
 * the batch size never changes a picture; affine interpolation swims more the flatter a
 * textured ground is seen, piecewise-affine spans stay between affine and correct; 16-bit
 * depth z-fights two near-coplanar quads far away where float z, w and reversed z do not. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "kernel.h"
#include "model.h"
#include "mtl.h"
#include "obj.h"
#include "pipeline.h"
#include "skybox.h"
#include "span.h"
#include "test.h"

/* an n x n grid over [-s,s]^2 in the plane y = 0 (two triangles a cell), uv = (x, z) / 2 */
static char *grid_obj(int n, double s)
{
    size_t cap = (size_t)(n + 1) * (n + 1) * 96 + (size_t)n * n * 64 + 64, len = 0;
    char *o = malloc(cap);
    if (!o)
        return NULL;
    for (int j = 0; j <= n; j++)
        for (int i = 0; i <= n; i++) {
            double x = -s + 2 * s * i / n, z = -s + 2 * s * j / n;
            len += (size_t)snprintf(o + len, cap - len, "v %g 0 %g\nvt %g %g\n", x, z, x / 2,
                                    z / 2);
        }
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            int a = j * (n + 1) + i + 1, b = a + 1, c = a + n + 2, d = a + n + 1;
            len += (size_t)snprintf(o + len, cap - len, "f %d/%d %d/%d %d/%d\nf %d/%d %d/%d %d/%d\n",
                                    a, a, c, c, b, b, a, a, d, d, c, c);
        }
    return o;
}

/* an 8x8 two-colour checker with a gradient, so that a shifted uv changes the colour */
static int checker(struct texture *tex)
{
    uint8_t px[8 * 8 * 4];
    for (int y = 0; y < 8; y++)
        for (int x = 0; x < 8; x++) {
            uint8_t *p = px + 4 * (y * 8 + x);
            int on = (x + y) % 2;
            p[0] = (uint8_t)(on ? 230 : 30 + 20 * x);
            p[1] = (uint8_t)(on ? 200 : 40 + 20 * y);
            p[2] = (uint8_t)(on ? 60 : 180);
            p[3] = 255;
        }
    return texture_from_rgba(8, 8, px, tex, NULL);
}

/* a smooth 16x16 ramp (red along u, green along v): colour error is proportional to uv error */
static int ramp(struct texture *tex)
{
    uint8_t px[16 * 16 * 4];
    for (int y = 0; y < 16; y++)
        for (int x = 0; x < 16; x++) {
            uint8_t *p = px + 4 * (y * 16 + x);
            p[0] = (uint8_t)(8 + 16 * x), p[1] = (uint8_t)(8 + 16 * y), p[2] = 128, p[3] = 255;
        }
    return texture_from_rgba(16, 16, px, tex, NULL);
}

struct scene1 {
    struct mesh m;
    struct texture tex;
    struct draw_item item;
    struct pipeline *p;
    struct fb fb;
};

static int scene1_init(struct scene1 *s, const char *obj, int w, int h, uint32_t batch)
{
    memset(s, 0, sizeof *s);
    if (!obj || obj_parse(obj, strlen(obj), NULL, &s->m, NULL) || checker(&s->tex) ||
        fb_init(&s->fb, w, h, false, NULL))
        return -1;
    s->item.mesh = &s->m;
    s->item.model = m4_identity();
    s->item.texture_override = &s->tex;
    s->p = batch ? pipeline_new_batch(batch) : pipeline_new();
    return s->p ? 0 : -1;
}

/* a camera low over the grid, looking into it through the near plane (fov 100): the near
 * triangles are clipped and large, the far ones small */
static struct camera grid_camera(double eye_y)
{
    struct camera c;
    camera_default(&c);
    c.eye = v3(0.3, eye_y, 2);
    c.target = v3(0, 0, -2);
    c.fov_deg = 100;
    return c;
}

static void scene1_free(struct scene1 *s)
{
    pipeline_destroy(s->p);
    fb_free(&s->fb);
    texture_free(&s->tex);
    mesh_free(&s->m);
}

TEST(batch_capacity_never_changes_the_picture)
{
    /* a 24x24 grid through the near plane (clipping), drawn through a batch that holds one
     * clipped triangle at a time and through the default one: the same bytes */
    char *obj = grid_obj(24, 6);
    struct scene1 a, b;
    REQUIRE(scene1_init(&a, obj, 96, 64, 9) == 0);
    REQUIRE(scene1_init(&b, obj, 96, 64, 0) == 0);
    free(obj);
    struct camera cam = grid_camera(0.2); /* the grid passes under the eye, through near */
    struct render_opts o;
    render_opts_default(&o);
    for (enum raster_method r = 0; r < RASTER_COUNT; r++) {
        o.raster = r;
        struct frame_stats sa, sb;
        REQUIRE(pipeline_draw(a.p, &a.item, 1, NULL, &cam, &o, &a.fb, &sa, NULL) == 0);
        REQUIRE(pipeline_draw(b.p, &b.item, 1, NULL, &cam, &o, &b.fb, &sb, NULL) == 0);
        CHECK(sa.tris_clipped > 0);
        CHECK(memcmp(a.fb.rgb, b.fb.rgb, 96 * 64 * 3) == 0);
        CHECK(memcmp(a.fb.depth, b.fb.depth, 96 * 64 * sizeof(float)) == 0);
        CHECK_EQ_INT(sa.pixels_shaded, sb.pixels_shaded);
    }
    scene1_free(&a);
    scene1_free(&b);
}

/* mean absolute channel difference over pixels both frames covered */
static double mean_abs_diff(const struct fb *a, const uint8_t *ref_rgb, const float *ref_depth)
{
    double sum = 0;
    long n = 0;
    for (int i = 0; i < a->w * a->h; i++) {
        if (!fb_covered(a, (size_t)i) || ref_depth[i] == 1.0f)
            continue;
        for (int k = 0; k < 3; k++)
            sum += abs((int)a->rgb[3 * i + k] - (int)ref_rgb[3 * i + k]);
        n += 3;
    }
    return n ? sum / n : 0;
}

TEST(affine_swims_more_the_flatter_the_ground_spans_stay_between)
{
    /* a 2x2 ground quad (two triangles) with a smooth ramp texture (bilinear, so colour
     * error is proportional to uv error) seen from 1.5 units at elevations 80 .. 10 degrees:
     * per-pixel perspective is the reference. The flatter the view, the more w varies
     * across each triangle, so affine's error must grow; 16-pixel spans must stay between
     * it and the reference, and shorter spans closer */
    const char *obj = "v -1 0 1\nv 1 0 1\nv 1 0 -1\nv -1 0 -1\n"
                      "vt 0.02 0.02\nvt 0.98 0.02\nvt 0.98 0.98\nvt 0.02 0.98\n"
                      "f 1/1 2/2 3/3\nf 1/1 3/3 4/4\n";
    struct scene1 s;
    REQUIRE(scene1_init(&s, obj, 160, 96, 0) == 0);
    texture_free(&s.tex);
    REQUIRE(ramp(&s.tex) == 0);
    size_t n = 160 * 96;
    uint8_t *ref = malloc(n * 3);
    float *ref_depth = malloc(n * sizeof(float));
    REQUIRE(ref && ref_depth);
    const double angles[] = {80, 60, 40, 20, 10};
    double prev_affine = -1, prev_span16 = -1;
    for (int a = 0; a < 5; a++) {
        struct camera cam;
        camera_default(&cam);
        double th = angles[a] * M_PI / 180;
        cam.eye = v3(0, 1.5 * sin(th), 1.5 * cos(th));
        cam.target = v3(0, 0, 0);
        cam.up = v3(0.5, 0.866, 0); /* rolled 30 degrees: rows are not lines of equal depth */
        struct render_opts o;
        render_opts_default(&o);
        o.shade = SHADE_UNLIT;
        o.filter = TEX_BILINEAR;
        struct frame_stats st;
        REQUIRE(pipeline_draw(s.p, &s.item, 1, NULL, &cam, &o, &s.fb, &st, NULL) == 0);
        memcpy(ref, s.fb.rgb, n * 3);
        memcpy(ref_depth, s.fb.depth, n * sizeof(float));
        double err[PERSP_COUNT];
        for (enum persp_method p = 0; p < PERSP_COUNT; p++) {
            o.persp = p;
            REQUIRE(pipeline_draw(s.p, &s.item, 1, NULL, &cam, &o, &s.fb, &st, NULL) == 0);
            err[p] = mean_abs_diff(&s.fb, ref, ref_depth);
        }
        fprintf(stderr, "      %4.0f deg: affine %.2f span32 %.2f span16 %.2f span8 %.2f\n",
                angles[a], err[PERSP_AFFINE], err[PERSP_SPAN32], err[PERSP_SPAN16],
                err[PERSP_SPAN8]);
        CHECK(err[PERSP_CORRECT] == 0);
        CHECK(err[PERSP_AFFINE] > prev_affine);          /* grows as the angle flattens */
        CHECK(err[PERSP_SPAN16] < err[PERSP_AFFINE]);    /* spans: between affine ... */
        CHECK(err[PERSP_SPAN8] <= err[PERSP_SPAN16]);    /* ... shorter spans closer ... */
        CHECK(err[PERSP_SPAN16] <= err[PERSP_SPAN32]);
        CHECK(err[PERSP_SPAN16] > prev_span16);          /* spans fail too, more slowly */
        prev_affine = err[PERSP_AFFINE];
        prev_span16 = err[PERSP_SPAN16];
    }
    CHECK(prev_affine > 10); /* at 10 degrees affine is far off: the swim is real */
    free(ref);
    free(ref_depth);
    scene1_free(&s);
}

TEST(z16_z_fights_far_away_z_w_and_reversed_z_do_not)
{
    /* two quads facing the camera 20 units away, 0.01 apart (near 0.1, far 100), the far
     * one (green) drawn first, slightly tilted so its depth sweeps across many steps. A
     * 16-bit depth step there spans ~0.06 units: the near red quad ties with the green one
     * and loses (LESS) in many pixels. Float z steps 2.4e-4 units there; w and reversed z
     * are finer still: red everywhere. */
    const char *quad = "v -1 -1 0\nv 1 -1 0\nv 1 1 0.2\nv -1 1 0.2\nf 1 2 3 4\n";
    struct mesh m;
    REQUIRE(obj_parse(quad, strlen(quad), NULL, &m, NULL) == 0);
    float green[3] = {0, 1, 0}, red[3] = {1, 0, 0};
    struct draw_item items[2] = {
        {.mesh = &m, .model = m4_mul(m4_translate(v3(0, 0, -20)), m4_scale(v3(8, 8, 1))),
         .kd_override = green},
        {.mesh = &m, .model = m4_mul(m4_translate(v3(0, 0, -19.99)), m4_scale(v3(8, 8, 1))),
         .kd_override = red},
    };
    struct fb fb;
    REQUIRE(fb_init(&fb, 64, 64, false, NULL) == 0);
    struct pipeline *p = pipeline_new();
    REQUIRE(p);
    struct camera cam;
    camera_default(&cam);
    struct render_opts o;
    render_opts_default(&o);
    o.shade = SHADE_UNLIT;
    int fights[DEPTH_COUNT];
    for (enum depth_mode d = 0; d < DEPTH_COUNT; d++) {
        o.depth = d;
        struct frame_stats st;
        REQUIRE(pipeline_draw(p, items, 2, NULL, &cam, &o, &fb, &st, NULL) == 0);
        fights[d] = 0;
        int red_px = 0;
        for (int y = 20; y < 44; y++) /* inside both quads */
            for (int x = 20; x < 44; x++) {
                const uint8_t *c = fb.rgb + 3 * (y * 64 + x);
                fights[d] += c[1] > 0;
                red_px += c[0] > 0;
            }
        CHECK_EQ_INT(fights[d] + red_px, 24 * 24); /* every pixel is one of the two */
    }
    fprintf(stderr, "      far quad wins: z %d, w %d, z16 %d, rz %d of 576 px\n", fights[DEPTH_Z],
            fights[DEPTH_W], fights[DEPTH_Z16], fights[DEPTH_RZ]);
    CHECK(fights[DEPTH_Z16] > 50);
    CHECK_EQ_INT(fights[DEPTH_Z], 0);
    CHECK_EQ_INT(fights[DEPTH_W], 0);
    CHECK_EQ_INT(fights[DEPTH_RZ], 0);
    pipeline_destroy(p);
    fb_free(&fb);
    mesh_free(&m);
}

TEST(depth_methods_store_the_same_window_depth)
{
    /* a ground quad receding at 40 degrees: every method's stored measure, mapped back to
     * window depth, agrees with float z (w: interpolated perspective-correctly, so a
     * screen-linear w would be off by up to ~1e-2 here; z16: within a step) */
    const char *obj = "v -1 0 1\nv 1 0 1\nv 1 0 -1\nv -1 0 -1\nf 1 2 3 4\n";
    struct scene1 s;
    REQUIRE(scene1_init(&s, obj, 160, 96, 0) == 0);
    struct camera cam;
    camera_default(&cam);
    cam.eye = v3(0, 1.5 * sin(0.7), 1.5 * cos(0.7));
    struct render_opts o;
    render_opts_default(&o);
    struct frame_stats st;
    size_t n = 160 * 96;
    double *ref = malloc(n * sizeof *ref);
    REQUIRE(ref);
    REQUIRE(pipeline_draw(s.p, &s.item, 1, NULL, &cam, &o, &s.fb, &st, NULL) == 0);
    int covered = 0;
    for (size_t i = 0; i < n; i++) {
        ref[i] = fb_depth_window(&s.fb, i);
        covered += fb_covered(&s.fb, i);
    }
    CHECK(covered > 2000);
    for (enum depth_mode d = DEPTH_W; d < DEPTH_COUNT; d++) {
        o.depth = d;
        REQUIRE(pipeline_draw(s.p, &s.item, 1, NULL, &cam, &o, &s.fb, &st, NULL) == 0);
        double worst = 0;
        int cov = 0;
        for (size_t i = 0; i < n; i++) {
            cov += fb_covered(&s.fb, i);
            double dd = fabs(fb_depth_window(&s.fb, i) - ref[i]);
            worst = dd > worst ? dd : worst;
        }
        CHECK_EQ_INT(cov, covered);
        CHECK(worst < (d == DEPTH_Z16 ? 0.6 / 65535 : 1e-6));
        if (!(worst < (d == DEPTH_Z16 ? 0.6 / 65535 : 1e-6)))
            fprintf(stderr, "      %s: worst window-depth difference %g\n",
                    render_depth_name(d), worst);
    }
    free(ref);
    scene1_free(&s);
}

TEST(thread_count_never_changes_the_picture)
{
    /* a textured grid through the near plane (clipped, many tiles, triangles across tile
     * edges), drawn with 1, 2, 3 and 5 threads, every rasterizer and two interpolation
     * methods, overdraw counted, the sky behind it (drawn in bands of rows): the same
     * bytes, depths, counts and statistics */
    char *obj = grid_obj(30, 6);
    struct skybox sky;
    REQUIRE(skybox_procedural(&sky, v3(1, 1, 1), NULL) == 0);
    struct scene1 s;
    REQUIRE(scene1_init(&s, obj, 203, 117, 0) == 0);
    free(obj);
    fb_free(&s.fb);
    REQUIRE(fb_init(&s.fb, 203, 117, true, NULL) == 0);
    struct camera cam = grid_camera(0.2);
    size_t n = 203 * 117;
    uint8_t *rgb = malloc(n * 3);
    float *depth = malloc(n * sizeof *depth);
    uint32_t *od = malloc(n * sizeof *od);
    REQUIRE(rgb && depth && od);
    const int threads[] = {1, 2, 3, 5};
    const enum persp_method persps[] = {PERSP_CORRECT, PERSP_SPAN8};
    for (enum raster_method r = 0; r < RASTER_COUNT; r++)
        for (int pi = 0; pi < 2; pi++) {
            struct frame_stats ref = {0};
            for (int ti = 0; ti < 4; ti++) {
                struct render_opts o;
                render_opts_default(&o);
                o.raster = r;
                o.persp = persps[pi];
                o.threads = threads[ti];
                struct frame_stats st;
                REQUIRE(pipeline_draw(s.p, &s.item, 1, &sky, &cam, &o, &s.fb, &st, NULL) == 0);
                if (ti == 0) {
                    size_t sky_px = 0;
                    for (size_t i = 0; i < n; i++)
                        sky_px += !fb_covered(&s.fb, i) && s.fb.rgb[3 * i + 2] > 0;
                    CHECK(sky_px > n / 10); /* the sky shows, not only the grid */
                    memcpy(rgb, s.fb.rgb, n * 3);
                    memcpy(depth, s.fb.depth, n * sizeof *depth);
                    memcpy(od, s.fb.overdraw, n * sizeof *od);
                    ref = st;
                    CHECK(st.tris_clipped > 0 && st.pixels_shaded > 1000);
                    continue;
                }
                CHECK(memcmp(rgb, s.fb.rgb, n * 3) == 0);
                CHECK(memcmp(depth, s.fb.depth, n * sizeof *depth) == 0);
                CHECK(memcmp(od, s.fb.overdraw, n * sizeof *od) == 0);
                CHECK_EQ_INT(st.pixels_tested, ref.pixels_tested);
                CHECK_EQ_INT(st.pixels_shaded, ref.pixels_shaded);
                CHECK_EQ_INT(st.tris_drawn, ref.tris_drawn);
                CHECK_EQ_INT(st.tris_empty, ref.tris_empty);
            }
        }
    free(rgb);
    free(depth);
    free(od);
    skybox_free(&sky);
    scene1_free(&s);
}

/* The fast kernels (kernel.h) this build and CPU can run. */
static const enum kernel_isa fast_kernels[] = {KERNEL_SSE2, KERNEL_AVX2, KERNEL_AVX2_4,
                                               KERNEL_AVX2_8};
#define N_FAST (int)(sizeof fast_kernels / sizeof fast_kernels[0])

/* s drawn with options o (and the sky, when given) by the reference kernel, then by each
 * fast kernel this build and CPU has: how many of those frames differ from the reference's
 * (colours, depths, overdraw counts, or the pixel and triangle counts); *compared_out: how
 * many were drawn; *st: the reference frame's counts. -1 if a draw failed. */
static int frames_differ_from_ref(struct scene1 *s, const struct skybox *sky,
                                  const struct camera *cam, const struct render_opts *o,
                                  struct frame_stats *st, int *compared_out)
{
    size_t n = (size_t)s->fb.w * (size_t)s->fb.h;
    uint8_t *rgb = malloc(n * 3);
    float *depth = malloc(n * sizeof *depth);
    uint32_t *od = s->fb.overdraw ? malloc(n * sizeof *od) : NULL;
    int differ = -1;
    struct render_opts ro = *o;
    ro.kernel = KERNEL_REF;
    *compared_out = 0;
    if (rgb && depth && (od || !s->fb.overdraw) &&
        pipeline_draw(s->p, &s->item, 1, sky, cam, &ro, &s->fb, st, NULL) == 0) {
        memcpy(rgb, s->fb.rgb, n * 3);
        memcpy(depth, s->fb.depth, n * sizeof *depth);
        if (od)
            memcpy(od, s->fb.overdraw, n * sizeof *od);
        differ = 0;
        for (int c = 0; c < N_FAST && differ >= 0; c++) {
            struct frame_stats other;
            ro.kernel = fast_kernels[c];
            if (!kernel_set(ro.kernel))
                continue;
            if (pipeline_draw(s->p, &s->item, 1, sky, cam, &ro, &s->fb, &other, NULL) != 0) {
                differ = -1;
                break;
            }
            ++*compared_out;
            differ += memcmp(rgb, s->fb.rgb, n * 3) != 0 ||
                      memcmp(depth, s->fb.depth, n * sizeof *depth) != 0 ||
                      (od && memcmp(od, s->fb.overdraw, n * sizeof *od) != 0) ||
                      other.pixels_tested != st->pixels_tested ||
                      other.pixels_shaded != st->pixels_shaded ||
                      other.tris_drawn != st->tris_drawn || other.tris_empty != st->tris_empty;
        }
    }
    free(rgb);
    free(depth);
    free(od);
    return differ;
}

TEST(one_pixel_triangles_draw_the_reference_bytes)
{
    /* a dense grid to the horizon (most triangles a pixel or less): the AVX2 set draws the
     * triangles of one pixel without lanes (kernel.h), the others in lanes; every shading
     * mode and filter of the default methods, every fast kernel against the reference: the
     * same bytes, depths and counts */
    char *obj = grid_obj(240, 6);
    struct scene1 s;
    REQUIRE(scene1_init(&s, obj, 160, 96, 0) == 0);
    free(obj);
    REQUIRE(texture_build_mips(&s.tex, NULL) >= 0);
    struct camera cam = grid_camera(0.5);
    int runs = 0, compared = 0, differ = 0;
    for (enum shade_mode m = SHADE_UNLIT; m <= SHADE_PHONG; m++)
        for (enum tex_filter f = 0; f < TEX_FILTER_COUNT; f++) {
            struct render_opts o;
            render_opts_default(&o);
            o.shade = m, o.filter = f, o.threads = 1;
            struct frame_stats st = {0};
            int c, d = frames_differ_from_ref(&s, NULL, &cam, &o, &st, &c);
            /* tiny triangles: about two pixels a triangle drawn */
            CHECK(st.tris_drawn > 3000 && st.pixels_tested < 3 * st.tris_drawn);
            runs += d >= 0 && c >= 1;
            compared += c;
            differ += d != 0;
        }
    CHECK_EQ_INT(runs, 4 * 3);
    CHECK_EQ_INT(differ, 0);
    fprintf(stderr, "      %d frames compared with the reference's%s\n", compared,
            kernel_set(KERNEL_AVX2) ? "" : " (no AVX2 kernel here: the baseline's only)");
    scene1_free(&s);
}

TEST(every_kernel_draws_the_reference_bytes)
{
    /* every fast kernel (kernel.h) against the reference: a textured grid through the near
     * plane with a 6x5 texture (no power of two: the modulo wrap) and its mips, the sky
     * behind it, in every shading mode, filter, depth and interpolation method; then every
     * rasterizer, the overdraw count and the normals and depth views: the same bytes,
     * depths and counts */
    char *obj = grid_obj(20, 6);
    struct scene1 s;
    REQUIRE(scene1_init(&s, obj, 203, 117, 0) == 0);
    free(obj);
    texture_free(&s.tex);
    uint8_t px[6 * 5 * 4];
    for (int i = 0; i < 6 * 5 * 4; i++)
        px[i] = (uint8_t)(i * 37 + (i / 4) * 11);
    REQUIRE(texture_from_rgba(6, 5, px, &s.tex, NULL) == 0);
    REQUIRE(texture_build_mips(&s.tex, NULL) >= 0);
    struct skybox sky;
    REQUIRE(skybox_procedural(&sky, v3(1, 2, 1), NULL) == 0);
    struct camera cam = grid_camera(0.4);
    const enum depth_mode depths[] = {DEPTH_Z, DEPTH_W, DEPTH_Z16, DEPTH_RZ};
    const enum persp_method persps[] = {PERSP_CORRECT, PERSP_AFFINE, PERSP_SPAN8};
    int runs = 0, compared = 0, differ = 0;
    for (enum shade_mode m = SHADE_UNLIT; m <= SHADE_WIRE; m++)
        for (enum tex_filter f = 0; f < TEX_FILTER_COUNT; f++)
            for (int di = 0; di < 4; di++)
                for (int pi = 0; pi < 3; pi++) {
                    struct render_opts o;
                    render_opts_default(&o);
                    o.shade = m, o.filter = f, o.depth = depths[di], o.persp = persps[pi];
                    o.threads = 1;
                    o.hidden_lines = true;
                    struct frame_stats st = {0};
                    int c, d = frames_differ_from_ref(&s, &sky, &cam, &o, &st, &c);
                    CHECK(m == SHADE_WIRE || st.pixels_shaded > 1000);
                    runs += d >= 0 && c >= 1;
                    compared += c;
                    differ += d != 0;
                }
    CHECK_EQ_INT(runs, 5 * 3 * 4 * 3);
    /* the other rasterizers, the views, the overdraw count (and its runs), two threads */
    fb_free(&s.fb);
    REQUIRE(fb_init(&s.fb, 203, 117, true, NULL) == 0);
    for (int v = 0; v < 6; v++) {
        struct render_opts o;
        render_opts_default(&o);
        o.threads = v == 5 ? 2 : 1;
        o.raster = v == 0 ? RASTER_SCANLINE : v == 1 ? RASTER_TILED : RASTER_EDGE;
        o.view = v == 2 ? VIEW_NORMALS : v == 3 ? VIEW_DEPTH : v == 4 ? VIEW_OVERDRAW : VIEW_COLOR;
        struct frame_stats st = {0};
        int c, d = frames_differ_from_ref(&s, &sky, &cam, &o, &st, &c);
        runs += d >= 0 && c >= 1;
        compared += c;
        differ += d != 0;
    }
    CHECK_EQ_INT(runs, 5 * 3 * 4 * 3 + 6);
    CHECK_EQ_INT(differ, 0);
    fprintf(stderr, "      %d frames compared with the reference's%s\n", compared,
            kernel_set(KERNEL_AVX2) ? "" : " (no AVX2 kernel here: the baseline's only)");
    skybox_free(&sky);
    scene1_free(&s);
}

/* the grid's mesh made a mesh of the features path (mesh.h): material 1 for half its
 * triangles (alpha MASK through an alpha map, emission with its map on the second uv set,
 * a mirrored and transformed base slot, a tangent-space normal map, occlusion, a
 * metallic-roughness texture, two sides), material 2 for every fifth (BLEND), vertex colours
 * with alpha and a second uv set; textures of 6x5 texels (no power of two) with mips */
static int make_features(struct scene1 *s)
{
    struct mesh *m = &s->m;
    struct material *mats = realloc(m->materials, 3 * sizeof *mats);
    if (!mats)
        return -1;
    m->materials = mats;
    m->n_materials = 3;
    mtl_default(&mats[1], "cutout");
    mtl_default(&mats[2], "glass");
    for (uint32_t k = 0; k < m->n_textures; k++) /* (the OBJ's own: none, but its array) */
        texture_free(&m->textures[k]);
    free(m->textures);
    m->textures = calloc(2, sizeof *m->textures);
    if (!m->textures)
        return -1;
    m->n_textures = 2;
    for (int k = 0; k < 2; k++) {
        uint8_t px[6 * 5 * 4];
        for (int i = 0; i < 6 * 5 * 4; i++)
            px[i] = (uint8_t)(i * (29 + 8 * k) + (i / 4) * 13);
        if (texture_from_rgba(6, 5, px, &m->textures[k], NULL) ||
            texture_build_mips(&m->textures[k], NULL) < 0)
            return -1;
    }
    struct material *a = &mats[1], *b = &mats[2];
    a->features = b->features = true;
    a->alpha_mode = MAT_MASK, a->alpha_cutoff = 0.3f;
    a->alpha_map = (struct tex_slot){.tex = 1, .uv = 1, .wrap = {TEX_WRAP_CLAMP, TEX_WRAP_MIRROR}};
    a->emissive[0] = 0.3f, a->emissive[2] = 0.2f;
    a->emissive_map = (struct tex_slot){.tex = 0, .uv = 1};
    a->base = (struct tex_slot){.tex = -1, .wrap = {TEX_WRAP_MIRROR, TEX_WRAP_CLAMP},
                                .xform = true, .xf = {0.8f, 0.3f, 0.1f, -0.2f, 1.1f, 0.05f}};
    a->normal_map = (struct tex_slot){.tex = 1, .nearest = true};
    a->normal_scale = 0.7f;
    a->occlusion_map = (struct tex_slot){.tex = 0, .wrap = {TEX_WRAP_CLAMP, TEX_WRAP_CLAMP}};
    a->occlusion_strength = 0.8f;
    a->spec_map = (struct tex_slot){.tex = 1};
    a->pbr = true, a->metallic = 0.6f, a->roughness = 0.7f;
    a->sides = MAT_TWO_SIDED;
    b->alpha_mode = MAT_BLEND, b->alpha = 0.6f;
    b->kd[1] = 0.3f;
    b->base = (struct tex_slot){.tex = -1, .uv = 1};
    b->sides = MAT_TWO_SIDED;
    for (uint32_t t = 0; t < m->n_tris; t++)
        m->tri_material[t] = t % 5 == 4 ? 2 : t % 2 ? 1 : 0;
    /* vertices are unique per material: the grid's are shared, which the features path
     * does not mind (it reads the triangle's material) */
    m->colors = malloc(m->n_verts * sizeof *m->colors);
    m->uv1 = malloc(m->n_verts * sizeof *m->uv1);
    if (!m->colors || !m->uv1)
        return -1;
    for (uint32_t v = 0; v < m->n_verts; v++) {
        for (int k = 0; k < 4; k++)
            m->colors[v][k] = (uint8_t)(120 + (v * 37 + (uint32_t)k * 51) % 136);
        m->uv1[v][0] = m->verts[v].uv[1] * 1.3f, m->uv1[v][1] = -m->verts[v].uv[0];
    }
    if (mesh_tangents(m, false))
        return -1;
    struct model_ctx ctx = {0};
    return model_finish(m, &ctx, NULL);
}

TEST(every_kernel_draws_the_features_path_as_the_reference)
{
    /* the features path (shade.h: alpha cut-outs and blending, emission, wrap modes,
     * transforms, the second uv set, normal and occlusion maps, per-pixel highlights, two
     * sides, vertex colours) through every kernel, every shading mode and filter, depth and
     * interpolation method, the views, the rasterizers and two threads both ways: the
     * reference's bytes, depths and counts */
    char *obj = grid_obj(20, 6);
    struct scene1 s;
    REQUIRE(scene1_init(&s, obj, 203, 117, 0) == 0);
    free(obj);
    REQUIRE(make_features(&s) == 0);
    REQUIRE(s.m.features && s.m.n_opaque < s.m.n_tris && s.m.tangents);
    struct skybox sky;
    REQUIRE(skybox_procedural(&sky, v3(1, 2, 1), NULL) == 0);
    struct camera cam = grid_camera(0.4);
    const enum depth_mode depths[] = {DEPTH_Z, DEPTH_W, DEPTH_Z16, DEPTH_RZ};
    const enum persp_method persps[] = {PERSP_CORRECT, PERSP_AFFINE, PERSP_SPAN8};
    int runs = 0, compared = 0, differ = 0;
    for (enum shade_mode m = SHADE_UNLIT; m <= SHADE_PHONG; m++)
        for (enum tex_filter f = 0; f < TEX_FILTER_COUNT; f++)
            for (int di = 0; di < 4; di++)
                for (int pi = 0; pi < 3; pi++) {
                    struct render_opts o;
                    render_opts_default(&o);
                    o.shade = m, o.filter = f, o.depth = depths[di], o.persp = persps[pi];
                    o.threads = 1;
                    struct frame_stats st = {0};
                    int c, d = frames_differ_from_ref(&s, &sky, &cam, &o, &st, &c);
                    CHECK(st.pixels_shaded > 1000);
                    runs += d >= 0 && c >= 1;
                    compared += c;
                    differ += d != 0;
                }
    CHECK_EQ_INT(runs, 4 * 3 * 4 * 3);
    fb_free(&s.fb);
    REQUIRE(fb_init(&s.fb, 203, 117, true, NULL) == 0);
    for (int v = 0; v < 7; v++) {
        struct render_opts o;
        render_opts_default(&o);
        o.threads = v >= 5 ? 2 : 1;
        o.split = v == 6 ? SPLIT_SLICES : SPLIT_TILES;
        o.raster = v == 0 ? RASTER_SCANLINE : v == 1 ? RASTER_TILED : RASTER_EDGE;
        o.view = v == 2 ? VIEW_NORMALS : v == 3 ? VIEW_DEPTH : v == 4 ? VIEW_OVERDRAW : VIEW_COLOR;
        struct frame_stats st = {0};
        int c, d = frames_differ_from_ref(&s, &sky, &cam, &o, &st, &c);
        runs += d >= 0 && c >= 1;
        compared += c;
        differ += d != 0;
    }
    CHECK_EQ_INT(runs, 4 * 3 * 4 * 3 + 7);
    CHECK_EQ_INT(differ, 0);
    fprintf(stderr, "      %d frames of the features path compared with the reference's\n",
            compared);
    skybox_free(&sky);
    s.item.texture_override = NULL; /* (the mesh's textures: freed with it) */
    scene1_free(&s);
}

TEST(features_path_is_the_same_at_any_thread_count)
{
    /* the blended pass after the opaque one, on one thread: the picture of 1, 2, 3 and 5
     * threads, by tiles and by slices, is one thread's */
    char *obj = grid_obj(24, 6);
    struct scene1 s;
    REQUIRE(scene1_init(&s, obj, 160, 96, 0) == 0);
    free(obj);
    REQUIRE(make_features(&s) == 0);
    struct camera cam = grid_camera(0.3);
    size_t n = (size_t)s.fb.w * s.fb.h * 3;
    uint8_t *one = malloc(n);
    REQUIRE(one);
    struct render_opts o;
    render_opts_default(&o);
    o.threads = 1;
    struct frame_stats st;
    REQUIRE(pipeline_draw(s.p, &s.item, 1, NULL, &cam, &o, &s.fb, &st, NULL) == 0);
    memcpy(one, s.fb.rgb, n);
    int differ = 0;
    const int threads[] = {2, 3, 5};
    for (int split = 0; split < 2; split++)
        for (int k = 0; k < 3; k++) {
            o.threads = threads[k];
            o.split = split ? SPLIT_SLICES : SPLIT_TILES;
            REQUIRE(pipeline_draw(s.p, &s.item, 1, NULL, &cam, &o, &s.fb, &st, NULL) == 0);
            differ += memcmp(one, s.fb.rgb, n) != 0;
        }
    CHECK_EQ_INT(differ, 0);
    free(one);
    s.item.texture_override = NULL;
    scene1_free(&s);
}

TEST(slices_draw_what_one_thread_draws)
{
    /* SPLIT_SLICES (render.h): the textured grid through the near plane twice, as two items
     * in the same place (every fragment of the second ties with the first's, which must
     * win: the merge keeps the earlier slice), the second one green; 2, 3 and 5 threads
     * (slice ends inside an item), every depth method (reversed z's test is GREATER), every
     * rasterizer, three interpolation methods, the sky after the merge, the depth and
     * normals views: the bytes and depths of one thread, and the counts that do not depend
     * on what hides what */
    char *obj = grid_obj(30, 6);
    struct skybox sky;
    REQUIRE(skybox_procedural(&sky, v3(1, 1, 1), NULL) == 0);
    struct scene1 s, r;
    REQUIRE(scene1_init(&s, obj, 160, 96, 0) == 0);
    REQUIRE(scene1_init(&r, obj, 160, 96, 0) == 0);
    free(obj);
    static const float green[3] = {0.1f, 0.9f, 0.2f};
    struct draw_item items[2] = {s.item, s.item};
    items[1].texture_override = NULL;
    items[1].kd_override = green;
    struct camera cam = grid_camera(0.2);
    const size_t n = 160 * 96;
    const int threads[] = {2, 3, 5};
    int compared = 0, differ = 0, green_px = 0;
    for (int c = 0; c < DEPTH_COUNT * RASTER_COUNT * 3 + 2; c++) {
        struct render_opts o;
        render_opts_default(&o);
        o.shade = SHADE_GOURAUD;
        if (c < DEPTH_COUNT * RASTER_COUNT * 3) {
            o.depth = (enum depth_mode)(c % DEPTH_COUNT);
            o.raster = (enum raster_method)(c / DEPTH_COUNT % RASTER_COUNT);
            const enum persp_method persps[] = {PERSP_CORRECT, PERSP_SPAN8, PERSP_AFFINE};
            o.persp = persps[c / DEPTH_COUNT / RASTER_COUNT];
        } else {
            o.view = c % 2 ? VIEW_DEPTH : VIEW_NORMALS;
        }
        o.threads = 1;
        struct frame_stats ref, st;
        REQUIRE(pipeline_draw(r.p, items, 2, &sky, &cam, &o, &r.fb, &ref, NULL) == 0);
        CHECK(ref.tris_clipped > 0 && ref.pixels_shaded > 3000);
        for (size_t i = 0; i < n && c == 0; i++) /* the second item never shows */
            green_px += r.fb.rgb[3 * i + 1] > 2 * r.fb.rgb[3 * i] + 40;
        for (int ti = 0; ti < 3; ti++) {
            o.threads = threads[ti];
            o.split = SPLIT_SLICES;
            REQUIRE(pipeline_draw(s.p, items, 2, &sky, &cam, &o, &s.fb, &st, NULL) == 0);
            compared++;
            differ += memcmp(s.fb.rgb, r.fb.rgb, n * 3) != 0 ||
                      memcmp(s.fb.depth, r.fb.depth, n * sizeof *s.fb.depth) != 0;
            CHECK_EQ_INT(st.tris_in, ref.tris_in);
            CHECK_EQ_INT(st.tris_drawn, ref.tris_drawn);
            CHECK_EQ_INT(st.tris_clipped, ref.tris_clipped);
            CHECK_EQ_INT(st.tris_no_centre, ref.tris_no_centre);
            CHECK_EQ_INT(st.tris_empty, ref.tris_empty);
            CHECK_EQ_INT(st.pixels_tested, ref.pixels_tested);
            CHECK(st.pixels_shaded >= ref.pixels_shaded); /* a slice sees less that hides */
        }
    }
    CHECK_EQ_INT(compared, 3 * (DEPTH_COUNT * RASTER_COUNT * 3 + 2));
    CHECK_EQ_INT(differ, 0);
    CHECK_EQ_INT(green_px, 0);
    skybox_free(&sky);
    scene1_free(&s);
    scene1_free(&r);
}

TEST(split_auto_takes_slices_for_dense_meshes_in_small_frames)
{
    /* render.h: a 30x30 grid (1800 triangles) at 160x96 holds a triangle for every 8.5
     * pixels: slices (the frame is under 320x200 and has one for every 64); at 640x480, one
     * for every 171: tiles; one thread: neither; wireframe: tiles; asked for: as asked */
    char *obj = grid_obj(30, 6);
    struct scene1 s, b;
    REQUIRE(scene1_init(&s, obj, 160, 96, 0) == 0);
    REQUIRE(scene1_init(&b, obj, 640, 480, 0) == 0);
    free(obj);
    struct camera cam = grid_camera(0.4);
    struct render_opts o;
    render_opts_default(&o);
    struct frame_stats st;
    o.threads = 2;
    REQUIRE(pipeline_draw(s.p, &s.item, 1, NULL, &cam, &o, &s.fb, &st, NULL) == 0);
    CHECK(st.slices && st.threads == 2);
    REQUIRE(pipeline_draw(b.p, &b.item, 1, NULL, &cam, &o, &b.fb, &st, NULL) == 0);
    CHECK(!st.slices && st.threads == 2);
    o.split = SPLIT_SLICES;
    REQUIRE(pipeline_draw(b.p, &b.item, 1, NULL, &cam, &o, &b.fb, &st, NULL) == 0);
    CHECK(st.slices);
    o.split = SPLIT_TILES;
    REQUIRE(pipeline_draw(s.p, &s.item, 1, NULL, &cam, &o, &s.fb, &st, NULL) == 0);
    CHECK(!st.slices);
    o.split = SPLIT_AUTO;
    o.shade = SHADE_WIRE;
    REQUIRE(pipeline_draw(s.p, &s.item, 1, NULL, &cam, &o, &s.fb, &st, NULL) == 0);
    CHECK(!st.slices);
    o.shade = SHADE_GOURAUD;
    o.threads = 1;
    REQUIRE(pipeline_draw(s.p, &s.item, 1, NULL, &cam, &o, &s.fb, &st, NULL) == 0);
    CHECK(!st.slices && st.threads == 1);
    scene1_free(&s);
    scene1_free(&b);
}

TEST(packed_groups_draw_what_runs_draw)
{
    /* perspective-correct and affine interpolation draw a triangle's pixels in packs
     * gathered from several runs (span.h); counting overdraw sends the same frame run by
     * run. A grid of small triangles (most runs one to three pixels) and a large one
     * through the near plane, in every shading mode, filter and depth method, correct and
     * affine, on one and three threads (triangles cut by tiles): the same bytes and depths
     * either way */
    const int sizes[] = {60, 6};
    int compared = 0, differ = 0;
    for (int gi = 0; gi < 2; gi++) {
        char *obj = grid_obj(sizes[gi], 6);
        struct scene1 s, r;
        REQUIRE(scene1_init(&s, obj, 203, 117, 0) == 0);
        REQUIRE(scene1_init(&r, obj, 203, 117, 0) == 0);
        free(obj);
        REQUIRE(texture_build_mips(&s.tex, NULL) >= 0);
        REQUIRE(texture_build_mips(&r.tex, NULL) >= 0);
        fb_free(&r.fb);
        REQUIRE(fb_init(&r.fb, 203, 117, true, NULL) == 0); /* overdraw: run by run */
        struct camera cam = grid_camera(0.4);
        size_t n = 203 * 117;
        for (int c = 0; c < 4 * 3 * 2 * 2 + 2 * 4; c++) {
            /* every mode x filter x thread count x {correct, affine} in depth z, then every
             * depth method with Gouraud and Phong */
            struct render_opts o;
            render_opts_default(&o);
            if (c < 48) {
                o.shade = (enum shade_mode)(SHADE_UNLIT + c % 4);
                o.filter = (enum tex_filter)(c / 4 % 3);
                o.threads = c / 12 % 2 ? 3 : 1;
                o.persp = c / 24 ? PERSP_AFFINE : PERSP_CORRECT;
            } else {
                o.shade = c % 2 ? SHADE_PHONG : SHADE_GOURAUD;
                o.depth = (enum depth_mode)((c - 48) / 2);
                o.threads = 2;
            }
            struct frame_stats a, b;
            REQUIRE(pipeline_draw(s.p, &s.item, 1, NULL, &cam, &o, &s.fb, &a, NULL) == 0);
            REQUIRE(pipeline_draw(r.p, &r.item, 1, NULL, &cam, &o, &r.fb, &b, NULL) == 0);
            CHECK(a.pixels_shaded > 5000);
            CHECK_EQ_INT(a.pixels_tested, b.pixels_tested);
            CHECK_EQ_INT(a.pixels_shaded, b.pixels_shaded);
            compared++;
            differ += memcmp(s.fb.rgb, r.fb.rgb, n * 3) != 0 ||
                      memcmp(s.fb.depth, r.fb.depth, n * sizeof *s.fb.depth) != 0;
        }
        scene1_free(&s);
        scene1_free(&r);
    }
    CHECK_EQ_INT(compared, 2 * (48 + 8));
    CHECK_EQ_INT(differ, 0);
}

TEST(vertex_order_never_changes_the_picture)
{
    /* one thread runs the vertex stage in chunks just ahead of the triangles that use them
     * (pipeline.c): a grid whose vertices are reversed (the first triangle uses the last
     * vertex) or shuffled draws the same bytes as the grid in order, on one thread and on
     * two; the camera above it sees every triangle */
    char *obj = grid_obj(60, 6);
    struct scene1 a, b;
    REQUIRE(scene1_init(&a, obj, 160, 96, 0) == 0);
    free(obj);
    struct camera cam;
    camera_default(&cam);
    cam.eye = v3(0, 9, 0.01);
    cam.target = v3(0, 0, 0);
    cam.fov_deg = 90;
    struct render_opts o;
    render_opts_default(&o);
    o.shade = SHADE_GOURAUD;
    o.threads = 1;
    struct frame_stats sa, sb;
    REQUIRE(pipeline_draw(a.p, &a.item, 1, NULL, &cam, &o, &a.fb, &sa, NULL) == 0);
    CHECK(sa.pixels_shaded > 3000);
    CHECK_EQ_INT(sa.tris_rejected, 0);
    for (int order = 0; order < 2; order++) {
        obj = grid_obj(60, 6);
        REQUIRE(scene1_init(&b, obj, 160, 96, 0) == 0);
        free(obj);
        uint32_t n = b.m.n_verts, *perm = malloc(n * sizeof *perm);
        struct mesh_vertex *v = malloc(n * sizeof *v);
        REQUIRE(perm && v);
        for (uint32_t i = 0; i < n; i++)
            perm[i] = order == 0 ? n - 1 - i : i;
        uint32_t r = 12345;
        for (uint32_t i = n - 1; order == 1 && i > 0; i--) { /* vertex i goes to perm[i] */
            r = r * 1103515245u + 12345u;
            uint32_t j = (r >> 8) % (i + 1), tmp = perm[i];
            perm[i] = perm[j], perm[j] = tmp;
        }
        for (uint32_t i = 0; i < n; i++)
            v[perm[i]] = b.m.verts[i];
        memcpy(b.m.verts, v, n * sizeof *v);
        for (uint32_t ti = 0; ti < b.m.n_tris; ti++)
            for (int k = 0; k < 3; k++)
                b.m.tris[ti][k] = perm[b.m.tris[ti][k]];
        REQUIRE(mesh_share_positions(&b.m) == 0); /* (mesh.h: after moving vertices) */
        for (int run = 0; run < 3; run++) { /* one thread; two by tiles; two by slices */
            o.threads = run ? 2 : 1;
            o.split = run == 2 ? SPLIT_SLICES : SPLIT_TILES;
            REQUIRE(pipeline_draw(b.p, &b.item, 1, NULL, &cam, &o, &b.fb, &sb, NULL) == 0);
            CHECK(memcmp(a.fb.rgb, b.fb.rgb, (size_t)160 * 96 * 3) == 0);
            CHECK(memcmp(a.fb.depth, b.fb.depth, (size_t)160 * 96 * sizeof *a.fb.depth) == 0);
            if (run == 2) /* each slice lights the vertices it uses (render.h) */
                continue;
            CHECK_EQ_INT(sb.pixels_shaded, sa.pixels_shaded);
            CHECK_EQ_INT(sb.verts_lit, sa.verts_lit);
        }
        free(perm);
        free(v);
        scene1_free(&b);
    }
    scene1_free(&a);
}

/* an n x n grid over [-s,s]^2 at y = 0 whose every cell has its own four uvs (a seam along
 * every edge: each inner position is the corner of four vertices, lost_empire's shape), the
 * heights a little bumpy */
static char *seam_grid_obj(int n, double s)
{
    size_t cap = (size_t)(n + 1) * (n + 1) * 64 + (size_t)n * n * 200 + 64, len = 0;
    char *o = malloc(cap);
    if (!o)
        return NULL;
    for (int j = 0; j <= n; j++)
        for (int i = 0; i <= n; i++)
            len += (size_t)snprintf(o + len, cap - len, "v %g %g %g\n", -s + 2 * s * i / n,
                                    0.01 * ((i * 7 + j * 3) % 5), -s + 2 * s * j / n);
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++)
            len += (size_t)snprintf(o + len, cap - len, "vt %g %g\nvt %g %g\nvt %g %g\nvt %g %g\n",
                                    0.1 * (i % 3), 0.2, 0.9, 0.1 * (j % 4), 0.5, 1.0, 0.0,
                                    0.3 + 0.1 * (i % 2));
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            int a = j * (n + 1) + i + 1, b = a + 1, c = a + n + 2, d = a + n + 1;
            int t = 4 * (j * n + i) + 1;
            len += (size_t)snprintf(o + len, cap - len,
                                    "f %d/%d %d/%d %d/%d\nf %d/%d %d/%d %d/%d\n", a, t, c,
                                    t + 2, b, t + 1, a, t, d, t + 3, c, t + 2);
        }
    return o;
}

TEST(walking_by_position_draws_the_vertex_stage_bytes)
{
    /* the front end tests triangles against their corners' positions, each projected once
     * (mesh.h's pos_id, frontend.c's walk by position), and makes only the vertices of the
     * triangles that pass: on a grid with a uv seam along every edge, low over it through
     * the near plane (clipped triangles near, most far ones holding no pixel centre), every
     * shading mode on one and two threads draws the same colour and depth bytes as with
     * every vertex positioned by the vertex stage (pos_id NULL), and as walking that one by
     * its vertices' heads (render_opts.heads_ratio 0) */
    enum { N = 90 };
    char *obj = seam_grid_obj(N, 6);
    struct scene1 a, b;
    REQUIRE(scene1_init(&a, obj, 160, 96, 0) == 0);
    REQUIRE(scene1_init(&b, obj, 160, 96, 0) == 0);
    free(obj);
    /* the positions: one per grid point, each vertex's its own bits */
    CHECK_EQ_INT(a.m.n_verts, 4 * N * N);
    CHECK_EQ_INT(a.m.n_pos, (N + 1) * (N + 1));
    REQUIRE(a.m.pos_id && a.m.pos_xyz);
    int wrong = 0;
    for (uint32_t i = 0; i < a.m.n_verts; i++)
        wrong += a.m.pos_id[i] >= a.m.n_pos ||
                 memcmp(a.m.pos_xyz[a.m.pos_id[i]], a.m.verts[i].pos, sizeof a.m.verts[i].pos);
    CHECK_EQ_INT(wrong, 0);
    free(b.m.pos_id);
    free(b.m.pos_xyz);
    b.m.pos_id = NULL, b.m.pos_xyz = NULL, b.m.n_pos = 0;
    struct camera cam = grid_camera(0.03);
    struct render_opts o;
    render_opts_default(&o);
    o.occluders = OCCLUDERS_OFF; /* (the counts compared below would follow each pipeline's
                                    last frame) */
    static const enum shade_mode modes[] = {SHADE_PHONG, SHADE_GOURAUD, SHADE_FLAT, SHADE_UNLIT};
    const size_t np = (size_t)160 * 96;
    for (int mi = 0; mi < 4; mi++)
        for (int run = 0; run < 3; run++) { /* one thread; two by tiles; two by slices */
            o.shade = modes[mi];
            o.threads = run ? 2 : 1;
            o.split = run == 2 ? SPLIT_SLICES : SPLIT_TILES;
            struct frame_stats sa, sb;
            REQUIRE(pipeline_draw(a.p, &a.item, 1, NULL, &cam, &o, &a.fb, &sa, NULL) == 0);
            REQUIRE(pipeline_draw(b.p, &b.item, 1, NULL, &cam, &o, &b.fb, &sb, NULL) == 0);
            CHECK(sa.tris_clipped > 5 && sa.tris_no_centre > 5000 && sa.pixels_shaded > 3000);
            CHECK_EQ_INT(sa.tris_drawn, sb.tris_drawn);
            /* (walked by position: all of it on one thread, the first slice's share on
             * two; never without positions) */
            CHECK(run == 0 ? sa.tris_by_position == a.m.n_tris : sa.tris_by_position > 0);
            CHECK_EQ_INT(sb.tris_by_position, 0);
            if (run < 2) /* (slices follow the last frame's times: their vertices too) */
                CHECK_EQ_INT(sa.verts_lit, sb.verts_lit);
            CHECK(memcmp(a.fb.rgb, b.fb.rgb, np * 3) == 0);
            CHECK(memcmp(a.fb.depth, b.fb.depth, np * sizeof *a.fb.depth) == 0);
            /* without positions, by heads (render_opts.h: each vertex's head made alone,
             * the records of the triangles that draw): the same bytes again */
            o.heads_ratio = 0;
            struct frame_stats sh;
            REQUIRE(pipeline_draw(b.p, &b.item, 1, NULL, &cam, &o, &a.fb, &sh, NULL) == 0);
            o.heads_ratio = RENDER_HEADS_RATIO;
            CHECK(run == 0 ? sh.tris_by_position == b.m.n_tris : sh.tris_by_position > 0);
            CHECK_EQ_INT(sh.tris_drawn, sb.tris_drawn);
            if (run < 2)
                CHECK_EQ_INT(sh.verts_lit, sb.verts_lit);
            CHECK(memcmp(a.fb.rgb, b.fb.rgb, np * 3) == 0);
            CHECK(memcmp(a.fb.depth, b.fb.depth, np * sizeof *a.fb.depth) == 0);
        }
    /* a framebuffer with more pixels than the grid has triangles: the vertex stage (most
     * triangles then hold a pixel centre, and walking by position does not pay) */
    struct scene1 c;
    obj = seam_grid_obj(N, 6);
    REQUIRE(scene1_init(&c, obj, 200, 100, 0) == 0);
    free(obj);
    struct frame_stats sc;
    o.threads = 1;
    REQUIRE(pipeline_draw(c.p, &c.item, 1, NULL, &cam, &o, &c.fb, &sc, NULL) == 0);
    CHECK(c.m.n_tris < 200 * 100 && sc.tris_in == c.m.n_tris);
    CHECK_EQ_INT(sc.tris_by_position, 0);
    scene1_free(&a);
    scene1_free(&b);
    scene1_free(&c);
}
