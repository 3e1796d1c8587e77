/* test_pipeline.c: whole frames — culling a mesh by its bounding sphere, hidden lines,
 * near-plane crossing, and that a failed depth test changes nothing. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "light.h"
#include "obj.h"
#include "pipeline.h"
#include "test.h"

static const char quad[] = "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nf 1 2 3 4\n";

struct frame {
    struct mesh m;
    struct fb fb;
    struct pipeline *p;
    struct draw_item item;
    struct camera cam;
    struct render_opts ro;
    struct frame_stats st;
};

static int frame_init(struct frame *f, const char *obj, int w, int h)
{
    memset(f, 0, sizeof *f);
    if (obj_parse(obj, strlen(obj), NULL, &f->m, NULL) || fb_init(&f->fb, w, h, true, NULL))
        return -1;
    f->p = pipeline_new();
    f->item.mesh = &f->m;
    f->item.model = m4_identity();
    camera_default(&f->cam);
    render_opts_default(&f->ro);
    f->ro.shade = SHADE_UNLIT;
    return f->p ? 0 : -1;
}

static void frame_free(struct frame *f)
{
    pipeline_destroy(f->p);
    fb_free(&f->fb);
    mesh_free(&f->m);
}

static int draw(struct frame *f)
{
    return pipeline_draw(f->p, &f->item, 1, NULL, &f->cam, &f->ro, &f->fb, &f->st, NULL);
}

static int covered(const struct fb *fb)
{
    int n = 0;
    for (int i = 0; i < fb->w * fb->h; i++)
        n += fb_covered(fb, (size_t)i);
    return n;
}

TEST(mesh_outside_frustum_is_culled_whole)
{
    struct frame f;
    REQUIRE(frame_init(&f, quad, 32, 32) == 0);
    REQUIRE(draw(&f) == 0);
    CHECK_EQ_INT(f.st.meshes_culled, 0);
    CHECK(covered(&f.fb) > 0);
    f.item.model = m4_translate(v3(0, 0, 10)); /* behind the camera */
    REQUIRE(draw(&f) == 0);
    CHECK_EQ_INT(f.st.meshes_culled, 1);
    CHECK_EQ_INT(f.st.tris_drawn, 0);
    CHECK_EQ_INT(covered(&f.fb), 0);
    f.item.model = m4_translate(v3(30, 0, 0)); /* far off to the right */
    REQUIRE(draw(&f) == 0);
    CHECK_EQ_INT(f.st.meshes_culled, 1);
    frame_free(&f);
}

TEST(near_plane_crossing_keeps_visible_part)
{
    /* a floor quad from behind the eye to far in front: clipped, and it covers the lower
     * half of the picture right up to the bottom edge */
    struct frame f;
    REQUIRE(frame_init(&f, "v -50 -1 50\nv 50 -1 50\nv 50 -1 -50\nv -50 -1 -50\nf 1 2 3 4\n",
                       40, 30) == 0);
    REQUIRE(draw(&f) == 0);
    CHECK(f.st.tris_clipped > 0);
    for (int x = 0; x < 40; x++) {
        CHECK(fb_covered(&f.fb, 29 * 40 + (size_t)x)); /* bottom row covered */
        CHECK(!fb_covered(&f.fb, (size_t)x));            /* top row (sky) empty */
    }
    frame_free(&f);
}

TEST(hidden_lines_removes_back_edges)
{
    /* a cube seen along a diagonal: without hidden-line removal its 3 back faces' edges show,
     * with it fewer pixels are lit */
    const char *cube = "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\n"
                       "v 1 1 1\nv -1 1 1\nf 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 4 8 7 3\n"
                       "f 1 5 8 4\nf 2 3 7 6\n";
    struct frame f;
    REQUIRE(frame_init(&f, cube, 64, 64) == 0);
    f.cam.eye = v3(3, 2.5, 4);
    f.ro.shade = SHADE_WIRE;
    REQUIRE(draw(&f) == 0);
    int all = 0, visible = 0;
    for (int i = 0; i < 64 * 64; i++)
        all += f.fb.rgb[3 * i] != 0;
    f.ro.hidden_lines = true;
    REQUIRE(draw(&f) == 0);
    for (int i = 0; i < 64 * 64; i++)
        visible += f.fb.rgb[3 * i] != 0;
    CHECK(all > 0);
    CHECK(visible > all / 2);
    CHECK(visible < all);
    frame_free(&f);
}

TEST(failed_depth_test_changes_nothing)
{
    /* draw a near red quad, then a far green one behind it: the red pixels and their depth
     * stay exactly as they were */
    const char *two = "mtllib none.mtl\nv -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\n"
                      "v -2 -2 -1\nv 2 -2 -1\nv 2 2 -1\nv -2 2 -1\nf 1 2 3 4\nf 5 6 7 8\n";
    struct frame f;
    REQUIRE(frame_init(&f, two, 32, 32) == 0);
    float kd_red[3] = {1, 0, 0};
    f.item.kd_override = kd_red;
    REQUIRE(draw(&f) == 0);
    /* same frame, but count: every covered centre pixel was tested twice, shaded once */
    int centre = 16 * 32 + 16;
    CHECK_EQ_INT(f.fb.overdraw[centre], 2);
    CHECK_EQ_INT(f.fb.rgb[3 * centre], 255);
    CHECK_EQ_INT(f.fb.rgb[3 * centre + 1], 0);
    CHECK(f.st.pixels_shaded < f.st.pixels_tested);
    frame_free(&f);
}

TEST(non_finite_vertices_drop_their_triangles)
{
    /* 1e10 * a scale of 1e300 overflows to inf in clip space: such triangles can be neither
     * clipped nor snapped, so they are dropped, in every mode, without undefined behaviour
     * (the sanitizer build checks float-to-int conversions); the finite triangle beside them
     * (x 0 .. 0.5 once scaled) is drawn and covers pixels */
    struct frame f;
    REQUIRE(frame_init(&f, "v 0 0 0\nv 1e10 0 0\nv 0 1 0\nv -1 -1 0\nv 5e-301 0.5 0\n"
                           "f 1 2 3\nf 1 3 4\nf 1 5 3\n", 32, 32) == 0);
    f.item.model = m4_scale(v3(1e300, 1, 1));
    const enum shade_mode modes[] = {SHADE_PHONG, SHADE_WIRE};
    for (int i = 0; i < 2; i++) {
        f.ro.shade = modes[i];
        REQUIRE(draw(&f) == 0);
        CHECK(f.st.tris_rejected >= 1);
        CHECK(f.st.tris_drawn >= 1);
        if (modes[i] == SHADE_PHONG)
            CHECK(covered(&f.fb) > 0);
    }
    f.ro.shade = SHADE_FLAT;
    f.ro.view = VIEW_WIRE_OVERLAY;
    REQUIRE(draw(&f) == 0);
    frame_free(&f);
}

TEST(culling_is_decided_once_per_source_triangle)
{
    /* a triangle through the near plane (found by a random search): clipping makes a quad,
     * fanned into two pieces, and snapping flips one piece's orientation. Culled piece by
     * piece, that piece would be judged the other way round from its source triangle;
     * culled as a whole (the rule), the triangle is kept or dropped entirely. */
    const char *obj = "v 2.837 -5.794 -2.8095\nv -2.884 9.511 2.898\nv -1.156 -0.023 9.29\n"
                      "f 1 2 3\n";
    struct frame f;
    REQUIRE(frame_init(&f, obj, 64, 48) == 0);
    f.ro.cull = CULL_FRONT; /* it faces the camera */
    REQUIRE(draw(&f) == 0);
    CHECK_EQ_INT(f.st.tris_culled, 1);
    CHECK_EQ_INT(f.st.tris_drawn, 0);
    CHECK_EQ_INT(covered(&f.fb), 0);
    /* culling back faces keeps all of it: the same pixels as no culling */
    f.ro.cull = CULL_BACK;
    REQUIRE(draw(&f) == 0);
    CHECK_EQ_INT(f.st.tris_culled, 0);
    CHECK_EQ_INT(f.st.tris_clipped, 1);
    int back_cull = covered(&f.fb);
    f.ro.cull = CULL_NONE;
    REQUIRE(draw(&f) == 0);
    CHECK_EQ_INT(covered(&f.fb), back_cull);
    CHECK(back_cull > 0);
    frame_free(&f);
}

TEST(triangles_that_cover_no_pixel_are_counted)
{
    /* orthographic, 32 px for 32 units: window = (x + 16, 16 - y). A sliver from (0.6,1.0)
     * to (9.4,2.0)/(9.4,2.05) in window coordinates has 8 pixel centres in its box (too many
     * for setup to test) but none inside it; a 4x4 square covers 16. Drawn alone or
     * together, on any thread count. */
    const char *obj = "v -15.4 15 0\nv -6.6 14 0\nv -6.6 13.95 0\n"
                      "v 0 0 0\nv 4 0 0\nv 4 4 0\nv 0 4 0\nf 1 2 3\nf 4 5 6 7\n";
    struct frame f;
    REQUIRE(frame_init(&f, obj, 32, 32) == 0);
    f.cam.ortho_height = 32;
    for (int threads = 1; threads <= 2; threads++) {
        f.ro.threads = threads;
        REQUIRE(draw(&f) == 0);
        CHECK_EQ_INT(f.st.tris_in, 3);
        CHECK_EQ_INT(f.st.tris_drawn, 3);
        CHECK_EQ_INT(f.st.tris_empty, 1);
        CHECK_EQ_INT(f.st.pixels_tested, 16);
        CHECK_EQ_INT(covered(&f.fb), 16);
    }
    frame_free(&f);
}

TEST(triangles_without_a_pixel_centre_are_not_lit)
{
    /* the window mapping of the test above: a triangle inside one pixel, away from its centre
     * (8.1..8.4, 8.1..8.4), a zero-area one, and one whose box holds the centre (7.5, 7.5)
     * that it misses ((7.2,7.2), (7.7,7.2), (7.2,7.7)), beside the 4x4 square. Setup drops
     * all three before any lighting: only the square's four vertices are lit, and the
     * counters add up (in = rejected + culled + no centre + drawn). With back faces culled
     * too (the three face away or have no area): the first, with no centre in its box, is
     * dropped for that before its facing is computed and counts as no centre; the other two
     * have centres in their boxes and are culled. */
    const char *obj = "v -7.9 7.9 0\nv -7.6 7.9 0\nv -7.9 7.6 0\n"
                      "v -10 -10 0\nv -9 -9 0\nv -8 -8 0\n"
                      "v 0 0 0\nv 4 0 0\nv 4 4 0\nv 0 4 0\n"
                      "v -8.8 8.8 0\nv -8.3 8.8 0\nv -8.8 8.3 0\n"
                      "f 1 2 3\nf 4 5 6\nf 7 8 9 10\nf 11 12 13\n";
    struct frame f;
    REQUIRE(frame_init(&f, obj, 32, 32) == 0);
    f.cam.ortho_height = 32;
    for (int run = 0; run < 4; run++) {
        f.ro.threads = 1 + run % 2;
        f.ro.cull = run < 2 ? CULL_NONE : CULL_BACK;
        REQUIRE(draw(&f) == 0);
        CHECK_EQ_INT(f.st.tris_in, 5);
        CHECK_EQ_INT(f.st.tris_culled, run < 2 ? 0 : 2);
        CHECK_EQ_INT(f.st.tris_no_centre, run < 2 ? 3 : 1);
        CHECK_EQ_INT(f.st.tris_drawn, 2);
        CHECK_EQ_INT(f.st.tris_in, f.st.tris_rejected + f.st.tris_culled +
                                       f.st.tris_no_centre + f.st.tris_drawn);
        CHECK_EQ_INT(f.st.verts_lit, 4);
        CHECK_EQ_INT(covered(&f.fb), 16);
    }
    frame_free(&f);
}

TEST(grey_lights_carry_one_channel_and_draw_the_same)
{
    /* Grey lights (r = g = b: the default light, the headlight) make light.h's D and S the
     * same in every channel, so Gouraud carries one D and one S instead of two rgb triples.
     * A second light of colour (0, 0, 1e-30) makes the same lighting non-grey without
     * changing a float that reaches a pixel: both frames must be the same bytes, drawn
     * once through the four-varying path and once through the eight-varying one — also with
     * the eye close enough that the near plane cuts triangles (clipping carries varyings). */
    const char *obj = "v 0 0 0.6\nv -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\n"
                      "f 1 2 3\nf 1 3 4\nf 1 4 5\nf 1 5 2\n";
    struct frame f;
    REQUIRE(frame_init(&f, obj, 48, 40) == 0);
    f.ro.shade = SHADE_GOURAUD;
    struct fb grey = {0};
    REQUIRE(fb_init(&grey, 48, 40, true, NULL) == 0);
    const vec3 eyes[2] = {{0.2, 0.1, 3}, {0.05, 0.02, 0.68}}; /* the second: apex too near */
    for (int e = 0; e < 2; e++) {
        f.cam.eye = eyes[e];
        f.ro.n_lights = 1;
        struct light_env env;
        light_env_init(&env, &f.ro);
        CHECK(env.grey);
        REQUIRE(draw(&f) == 0);
        CHECK(covered(&f.fb) > 200);
        if (e == 1)
            CHECK(f.st.tris_clipped > 0);
        memcpy(grey.rgb, f.fb.rgb, (size_t)48 * 40 * 3);
        f.ro.n_lights = 2;
        f.ro.lights[1].dir = v3(-1, 0.5, 1);
        f.ro.lights[1].color = v3(0, 0, 1e-30);
        light_env_init(&env, &f.ro);
        CHECK(!env.grey);
        REQUIRE(draw(&f) == 0);
        CHECK(memcmp(grey.rgb, f.fb.rgb, (size_t)48 * 40 * 3) == 0);
        /* and from afar the highlight is in the picture (S reaches the pixels) */
        int bright = 0;
        for (int i = 0; i < 48 * 40 * 3; i++)
            bright += f.fb.rgb[i] > 230;
        CHECK(e == 1 || bright > 0);
    }
    fb_free(&grey);
    frame_free(&f);
}

static int lit(const struct fb *fb)
{
    int n = 0;
    for (int i = 0; i < fb->w * fb->h; i++)
        n += fb->rgb[3 * i] != 0;
    return n;
}

/* A UV sphere of `st` stacks and 2*st slices as OBJ text (a seam of split vertices where the
 * slices close: welding must join it). */
static char *sphere_obj(int st)
{
    size_t cap = 64 * (size_t)(st + 1) * (2 * st + 1) * 3, k = 0;
    char *s = malloc(cap);
    if (!s)
        return NULL;
    for (int i = 0; i <= st; i++)
        for (int j = 0; j <= 2 * st; j++) { /* j = 2*st repeats j = 0's positions */
            double th = 3.14159265358979 * i / st, ph = 3.14159265358979 * j / st;
            k += (size_t)snprintf(s + k, cap - k, "v %.9f %.9f %.9f\n", sin(th) * cos(ph),
                                  cos(th), sin(th) * sin(ph));
        }
    for (int i = 0; i < st; i++)
        for (int j = 0; j < 2 * st; j++) {
            int a = i * (2 * st + 1) + j + 1, b = a + 2 * st + 1;
            k += (size_t)snprintf(s + k, cap - k, "f %d %d %d %d\n", a, a + 1, b + 1, b);
        }
    return s;
}

TEST(wire_auto_draws_the_outline_of_a_dense_mesh_and_every_edge_of_a_cube)
{
    /* 1. a sphere of 3200 triangles at 160x96: every edge is a white disc; auto draws what
     *    outline draws (its silhouette: the UV seam and the poles' fans are no edges of it),
     *    a small fraction of the pixels */
    char *obj = sphere_obj(40);
    REQUIRE(obj);
    struct frame f;
    REQUIRE(frame_init(&f, obj, 160, 96) == 0);
    free(obj);
    f.ro.shade = SHADE_WIRE;
    f.ro.wire = WIRE_ALL;
    REQUIRE(draw(&f) == 0);
    int all = lit(&f.fb);
    f.ro.wire = WIRE_OUTLINE;
    REQUIRE(draw(&f) == 0);
    int outline = lit(&f.fb);
    uint8_t *keep = malloc((size_t)160 * 96 * 3);
    REQUIRE(keep);
    memcpy(keep, f.fb.rgb, (size_t)160 * 96 * 3);
    f.ro.wire = WIRE_AUTO;
    REQUIRE(draw(&f) == 0);
    CHECK(memcmp(keep, f.fb.rgb, (size_t)160 * 96 * 3) == 0);
    CHECK(outline > 50);       /* a circle around it */
    CHECK(outline * 4 < all);  /* not the disc */
    printf("    sphere 3200 triangles, 160x96: all %d px, auto = outline %d px\n", all, outline);
    free(keep);
    frame_free(&f);

    /* 2. a cube at 64x64: auto keeps every edge (the same bytes as all, diagonals too);
     *    outline drops the six face diagonals and keeps its 12 edges */
    const char *cube = "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\n"
                       "v 1 1 1\nv -1 1 1\nf 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 4 8 7 3\n"
                       "f 1 5 8 4\nf 2 3 7 6\n";
    REQUIRE(frame_init(&f, cube, 64, 64) == 0);
    f.cam.eye = v3(3, 2.5, 4);
    f.ro.shade = SHADE_WIRE;
    f.ro.wire = WIRE_ALL;
    REQUIRE(draw(&f) == 0);
    keep = malloc((size_t)64 * 64 * 3);
    REQUIRE(keep);
    memcpy(keep, f.fb.rgb, (size_t)64 * 64 * 3);
    all = lit(&f.fb);
    f.ro.wire = WIRE_AUTO;
    REQUIRE(draw(&f) == 0);
    CHECK(memcmp(keep, f.fb.rgb, (size_t)64 * 64 * 3) == 0);
    f.ro.wire = WIRE_OUTLINE;
    REQUIRE(draw(&f) == 0);
    outline = lit(&f.fb);
    CHECK(outline < all);
    CHECK(outline > all / 2);
    /* every pixel outline lights, all lights too (the same edges, fewer of them) */
    for (int i = 0; i < 64 * 64; i++)
        CHECK(!f.fb.rgb[3 * i] || keep[3 * i]);
    /* hidden lines still work on the outline: fewer pixels */
    f.ro.hidden_lines = true;
    REQUIRE(draw(&f) == 0);
    CHECK(lit(&f.fb) < outline);
    free(keep);
    frame_free(&f);
}
