/* test_light.c: the lighting model against hand-computed values — ambient, the diffuse
 * factor, the specular exponent, Phong's renormalised normal, flat shading's face normal and
 * the base colour rule — so no shading detail depends on the Mesa oracle alone; and the
 * ambient term (exact by default, a hemisphere for the headlight) and the headlight. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "light.h"
#include "obj.h"
#include "pipeline.h"
#include "shade.h"
#include "test.h"

static struct light_env one_light(float x, float y, float z)
{
    struct render_opts o;
    render_opts_default(&o);
    o.lights[0].dir = v3(x, y, z);
    struct light_env env;
    light_env_init(&env, &o);
    return env;
}

TEST(light_ambient_alone_when_facing_away)
{
    /* N opposite L: D = ambient 0.1, S = 0 (N.H < 0) */
    struct light_env env = one_light(0, 0, -1);
    float n[3] = {0, 0, 1}, v[3] = {0, 0.6f, 0.8f}, d[3], s[3];
    light_terms(&env, n, v, 32, d, s);
    for (int k = 0; k < 3; k++) {
        CHECK_NEAR(d[k], 0.1, 1e-7);
        CHECK_NEAR(s[k], 0.0, 1e-7);
    }
    float albedo[3] = {0.5f, 1, 0}, ks[3] = {0.5f, 0.5f, 0.5f}, c[3];
    light_combine(albedo, d, s, ks, c);
    CHECK_NEAR(c[0], 0.05, 1e-7);
    CHECK_NEAR(c[1], 0.1, 1e-7);
    CHECK_NEAR(c[2], 0.0, 1e-7);
}

TEST(light_diffuse_and_specular_exponent)
{
    /* L = V = +z, N tilted so that N.L = N.H = 0.95:
     * D = 0.1 + 0.9 * 0.95 = 0.955, S = 0.95^32 = 0.19371 (ns 32, five squarings),
     * S = 0.95^10 = 0.59874 (ns 10, powf); exponent 16 would give 0.44013 */
    struct light_env env = one_light(0, 0, 5); /* not unit: normalised by light_env_init */
    float c = 0.95f, sn = sqrtf(1 - c * c);
    float n[3] = {sn, 0, c}, v[3] = {0, 0, 1}, d[3], s[3];
    light_terms(&env, n, v, 32, d, s);
    CHECK_NEAR(d[0], 0.955, 1e-6);
    CHECK_NEAR(s[0], 0.193711, 1e-5);
    light_terms(&env, n, v, 10, d, s);
    CHECK_NEAR(s[1], 0.598737, 1e-5);
    /* two lights add (white + red) */
    struct render_opts o;
    render_opts_default(&o);
    o.n_lights = 2;
    o.lights[1].dir = v3(0, 0, 1);
    o.lights[1].color = v3(1, 0, 0);
    light_env_init(&env, &o);
    float n2[3] = {0, 0, 1};
    light_terms(&env, n2, v, 32, d, s);
    /* light 0 toward (1,1,1)/sqrt3: N.L = 0.57735; light 1: N.L = 1 */
    CHECK_NEAR(d[0], 0.1 + 0.9 * (0.577350 + 1), 1e-5);
    CHECK_NEAR(d[1], 0.1 + 0.9 * 0.577350, 1e-5);
}

TEST(phong_renormalises_the_interpolated_normal)
{
    /* an interpolated normal half as long (what the middle of a curved triangle gets) must
     * light exactly like the unit one: c = albedo * D + 0.5 * S with N.L = 1 */
    struct render_opts o;
    render_opts_default(&o);
    o.lights[0].dir = v3(0, 0, 1);
    struct shade_ctx sc;
    float eye[3] = {0, 0, 3}, back[3] = {0, 0, 1};
    shade_ctx_init(&sc, &o, eye, 0, back);
    struct material mat;
    memset(&mat, 0, sizeof mat);
    mat.ks[0] = mat.ks[1] = mat.ks[2] = 0.5f;
    mat.ns = 32;
    mat.texture = -1;
    struct shade_tri st = {.mat = &mat, .base = {0.4f, 0.4f, 0.4f}, .tex = NULL};
    /* var: u v | world position | normal; the point is on the axis, V = +z */
    float unit[8] = {0, 0, 0, 0, 0, 0, 0, 1}, half[8] = {0, 0, 0, 0, 0, 0, 0, 0.5f};
    float c1[3], c2[3];
    shade_fragment(&sc, SHADE_PHONG, &st, unit, c1);
    shade_fragment(&sc, SHADE_PHONG, &st, half, c2);
    /* D = 1, S = 1: 0.4 + 0.5 */
    CHECK_NEAR(c1[0], 0.9, 1e-6);
    CHECK_NEAR(c2[0], 0.9, 1e-6);
    /* tilted 60 degrees: N.L = N.H = 0.5 -> D = 0.55, S = 0.5^32 */
    float tilt[8] = {0, 0, 0, 0, 0, 0.866025f * 0.3f, 0, 0.5f * 0.3f};
    shade_fragment(&sc, SHADE_PHONG, &st, tilt, c1);
    CHECK_NEAR(c1[0], 0.4 * 0.55 + 0.5 * pow(0.5, 32), 1e-5);
}

TEST(base_colour_default_albedo_rule)
{
    struct material implicit, named;
    memset(&implicit, 0, sizeof implicit);
    implicit.kd[0] = implicit.kd[1] = implicit.kd[2] = 1;
    implicit.implicit = true;
    named = implicit;
    named.implicit = false; /* a material without Kd: Kd = 1 */
    float b[3], over[3] = {0.2f, 0.3f, 0.4f};
    light_base_color(&implicit, NULL, 0, b);
    CHECK_NEAR(b[0], 0.8, 1e-7); /* no material, no texture: GL's default diffuse */
    light_base_color(&implicit, NULL, 1, b);
    CHECK_NEAR(b[1], 1.0, 1e-7); /* textured: the texture keeps its colours */
    light_base_color(&named, NULL, 0, b);
    CHECK_NEAR(b[2], 1.0, 1e-7);
    light_base_color(&implicit, over, 0, b);
    CHECK_NEAR(b[2], 0.4, 1e-7); /* a scene's kd wins */
}

/* the colour of pixel (16,16) of one triangle covering the middle, lit from normalize(0,1,1) */
static int flat_pixel(const char *obj, enum shade_mode mode)
{
    struct mesh m;
    struct fb fb;
    if (obj_parse(obj, strlen(obj), NULL, &m, NULL) || fb_init(&fb, 32, 32, false, NULL))
        return -1;
    struct pipeline *p = pipeline_new();
    struct draw_item item = {.mesh = &m, .model = m4_identity()};
    struct camera cam;
    camera_default(&cam);
    struct render_opts o;
    render_opts_default(&o);
    o.shade = mode;
    o.lights[0].dir = v3(0, 1, 1);
    struct frame_stats st;
    int r = -1;
    if (p && pipeline_draw(p, &item, 1, NULL, &cam, &o, &fb, &st, NULL) == 0)
        r = fb.rgb[3 * (16 * 32 + 16)];
    pipeline_destroy(p);
    fb_free(&fb);
    mesh_free(&m);
    return r;
}

TEST(flat_uses_the_face_normal_from_the_winding)
{
    /* a triangle in z = 0, counter-clockwise seen from the eye at +z, whose vertex normals
     * point along +x. Flat: N = (0,0,1) from the winding, L = (0,1,1)/sqrt2, V from the
     * centroid (0,-1/3,0) to the eye (0,0,3): N.L = 0.70711, N.H = 0.90130,
     * c = 0.8 * (0.1 + 0.9 * 0.70711) + 0.5 * 0.90130^32 = 0.60710 -> 155
     * (V = +z instead of from the centroid would give 160).
     * Gouraud uses the vertex normals instead: N.L = 0, N.H = 0 -> c = 0.08 -> 20.
     * Wound the other way the face normal is -z: ambient only (no flipping) -> 20. */
    const char *ccw = "v -1 -1 0\nv 1 -1 0\nv 0 1 0\nvn 1 0 0\nf 1//1 2//1 3//1\n";
    const char *cw = "v -1 -1 0\nv 1 -1 0\nv 0 1 0\nvn 1 0 0\nf 1//1 3//1 2//1\n";
    CHECK_EQ_INT(flat_pixel(ccw, SHADE_FLAT), 155);
    CHECK_EQ_INT(flat_pixel(ccw, SHADE_GOURAUD), 20);
    CHECK_EQ_INT(flat_pixel(cw, SHADE_FLAT), 20);
}

static void unit(float v[3], uint32_t *seed)
{
    for (int k = 0; k < 3; k++) {
        *seed = *seed * 1664525u + 1013904223u;
        v[k] = (float)((*seed >> 8) / 16777216.0 * 2 - 1);
    }
    light_normalize(v);
}

TEST(default_ambient_is_exactly_the_constant)
{
    /* render and dump keep the conventions bit for bit (the Mesa oracle checks them too) */
    struct render_opts ro;
    render_opts_default(&ro);
    struct light_env env;
    light_env_init(&env, &ro);
    uint32_t seed = 11;
    for (int i = 0; i < 2000; i++) {
        float n[3], v[3], d[3], s[3];
        unit(n, &seed);
        unit(v, &seed);
        light_terms(&env, n, v, 32, d, s);
        float ndl = n[0] * env.dir[0][0] + n[1] * env.dir[0][1] + n[2] * env.dir[0][2];
        float want = 0.1f + 0.9f * (ndl > 0 ? ndl : 0);
        for (int k = 0; k < 3; k++)
            if (d[k] != want) {
                test_fail(t, __FILE__, __LINE__, "D %.9g != %.9g", d[k], want);
                return;
            }
    }
}

TEST(hemisphere_ambient_blends_sky_and_ground_by_the_normal)
{
    struct render_opts ro;
    render_opts_default(&ro);
    ro.n_lights = 0;
    ro.ambient_sky = v3(0.3, 0.3, 0.3);
    ro.ambient_ground = v3(0.1, 0.1, 0.1);
    struct light_env env;
    light_env_init(&env, &ro);
    static const float normals[][3] = {{0, 1, 0}, {0, -1, 0}, {1, 0, 0}, {0, 0.6f, 0.8f}};
    static const float want[] = {0.3f, 0.1f, 0.2f, 0.26f};
    const float v[3] = {0, 0, 1};
    for (int i = 0; i < 4; i++) {
        float d[3], s[3];
        light_terms(&env, normals[i], v, 32, d, s);
        CHECK_NEAR(d[0], want[i], 1e-6);
    }
}

TEST(headlight_comes_from_over_the_viewers_shoulder)
{
    struct camera c;
    camera_default(&c); /* eye (0,0,3) looking at the origin */
    struct render_opts ro;
    render_opts_default(&ro);
    light_use_camera(&ro, &c);
    CHECK_EQ_INT(ro.n_lights, 2);
    CHECK_NEAR(ro.lights[1].dir.x, LIGHT_FILL_RIGHT, 1e-12); /* the fill: the other side, low */
    CHECK_NEAR(ro.lights[1].dir.y, LIGHT_FILL_UP, 1e-12);
    CHECK(ro.lights[1].color.x < ro.lights[0].color.x);
    CHECK_NEAR(ro.lights[0].dir.x, LIGHT_HEAD_RIGHT, 1e-12);
    CHECK_NEAR(ro.lights[0].dir.y, LIGHT_HEAD_UP, 1e-12);
    CHECK_NEAR(ro.lights[0].dir.z, LIGHT_HEAD_BACK, 1e-12);
    c.eye = v3(3, 0, 0); /* from +X: right is -Z */
    light_use_camera(&ro, &c);
    CHECK_NEAR(ro.lights[0].dir.x, LIGHT_HEAD_BACK, 1e-12);
    CHECK_NEAR(ro.lights[0].dir.y, LIGHT_HEAD_UP, 1e-12);
    CHECK_NEAR(ro.lights[0].dir.z, -LIGHT_HEAD_RIGHT, 1e-12);
    CHECK(ro.ambient_sky.x > ro.ambient_ground.x);
}

/* A UV sphere of radius 1: 16 rings of 32 quads. */
static int sphere(struct mesh *m)
{
    enum { RINGS = 16, SEGS = 32, NV = (RINGS + 1) * (SEGS + 1), NT = RINGS * SEGS * 2 };
    static float pos[NV * 3];
    static struct mesh_corner corners[NT * 3];
    for (int r = 0; r <= RINGS; r++)
        for (int s = 0; s <= SEGS; s++) {
            double th = M_PI * r / RINGS, ph = 2 * M_PI * s / SEGS;
            float *p = pos + 3 * (r * (SEGS + 1) + s);
            p[0] = (float)(sin(th) * cos(ph));
            p[1] = (float)cos(th);
            p[2] = (float)(-sin(th) * sin(ph));
        }
    int k = 0;
    for (int r = 0; r < RINGS; r++)
        for (int s = 0; s < SEGS; s++) {
            uint32_t a = (uint32_t)(r * (SEGS + 1) + s), b = a + SEGS + 1;
            uint32_t q[6] = {a, b, a + 1, a + 1, b, b + 1};
            for (int i = 0; i < 6; i++)
                corners[k++] = (struct mesh_corner){q[i], MESH_NONE, MESH_NONE};
        }
    struct mesh_source src = {.pos = pos, .n_pos = NV, .corners = corners, .n_tris = NT};
    memset(m, 0, sizeof *m);
    m->materials = calloc(1, sizeof *m->materials);
    if (!m->materials)
        return -1;
    m->n_materials = 1;
    m->materials[0] = (struct material){.kd = {1, 1, 1}, .ns = 32, .texture = -1,
                                        .implicit = true};
    return mesh_build(&src, m, NULL);
}

static int cmp_u8(const void *a, const void *b)
{
    return *(const uint8_t *)a - *(const uint8_t *)b;
}

/* The mean brightness (0..1, green channel) of the sphere's pixels seen from angle deg
 * around it, at height y; *dim_out: the tenth-darkest percentile (the side turned away). */
static double seen(struct pipeline *p, const struct draw_item *it, struct fb *fb, double deg,
                   double y, bool headlight, double *dim_out)
{
    struct camera c;
    camera_default(&c);
    double a = deg * M_PI / 180;
    c.eye = v3(3 * sin(a), y, 3 * cos(a));
    struct render_opts ro;
    render_opts_default(&ro);
    if (headlight)
        light_use_camera(&ro, &c);
    struct frame_stats st;
    if (pipeline_draw(p, it, 1, NULL, &c, &ro, fb, &st, NULL))
        return -1;
    double sum = 0;
    int n = 0;
    static uint8_t g[64 * 64];
    for (int i = 0; i < fb->w * fb->h; i++)
        if (fb->depth[i] < 1) {
            sum += fb->rgb[3 * i + 1] / 255.0;
            g[n++] = fb->rgb[3 * i + 1];
        }
    qsort(g, (size_t)n, 1, cmp_u8);
    *dim_out = n ? g[n / 10] / 255.0 : -1;
    return n ? sum / n : -1;
}

TEST(the_headlight_lights_a_model_from_every_side)
{
    /* The fixed world light toward (1,1,1) leaves the sphere dark seen from the far side;
     * the headlight lights every side the camera looks at. */
    struct mesh m;
    REQUIRE(sphere(&m) == 0);
    struct fb fb;
    REQUIRE(fb_init(&fb, 64, 64, false, NULL) == 0);
    struct pipeline *p = pipeline_new();
    REQUIRE(p);
    struct draw_item it = {&m, m4_identity(), NULL, NULL};
    double world_min = 1, head_min = 1, head_dim = 1, dim;
    for (int deg = 0; deg < 360; deg += 45)
        for (double y = -2; y <= 2; y += 2) {
            double w = seen(p, &it, &fb, deg, y, false, &dim);
            double h = seen(p, &it, &fb, deg, y, true, &dim);
            world_min = w < world_min ? w : world_min;
            head_min = h < head_min ? h : head_min;
            head_dim = dim < head_dim ? dim : head_dim;
        }
    CHECK(world_min < 0.2);  /* today's convention: a dark side */
    CHECK(head_min > 0.55);  /* the headlight: every view lit */
    CHECK(head_dim > 0.4);   /* and within a view the side turned from the key (the fill):
                              * 0.32 with the key light alone */
    if (t->failures)
        fprintf(stderr, "    darkest view: world light %.3f, headlight %.3f; darkest rim %.3f\n",
                world_min, head_min, head_dim);
    pipeline_destroy(p);
    fb_free(&fb);
    mesh_free(&m);
}

TEST(four_lane_terms_equal_one_lane_terms_with_a_hemisphere)
{
    /* the span shader's light_terms_v gives, lane by lane, exactly light_terms: with the
     * default single light (its own code path) and with the headlight's two lights and
     * hemisphere ambient, for exponents by squaring (a power of two or not) and by powf */
    struct camera c;
    camera_default(&c);
    const float exps[3] = {32, 10, 7.5f};
    for (int e = 0; e < 2; e++) {
        struct render_opts ro;
        render_opts_default(&ro);
        if (e == 1)
            light_use_camera(&ro, &c);
        struct light_env env;
        light_env_init(&env, &ro);
        CHECK_EQ_INT(env.n, e == 0 ? 1 : 2);
        uint32_t seed = 5;
        for (int i = 0; i < 600; i++) {
            float n[4][3], v[4][3], ns = exps[i % 3];
            vf n4[3], v4[3], d4[3], s4[3];
            for (int l = 0; l < 4; l++) {
                unit(n[l], &seed);
                unit(v[l], &seed);
                for (int k = 0; k < 3; k++)
                    n4[k][l] = n[l][k], v4[k][l] = v[l][k];
            }
            light_terms_v(&env, n4, v4, ns, d4, s4);
            for (int l = 0; l < 4; l++) {
                float d[3], s[3];
                light_terms(&env, n[l], v[l], ns, d, s);
                for (int k = 0; k < 3; k++)
                    if (d[k] != d4[k][l] || s[k] != s4[k][l]) {
                        test_fail(t, __FILE__, __LINE__, "%d lights, ns %g, lane %d: D %.9g vs %.9g, S %.9g vs %.9g",
                                  env.n, ns, l, d4[k][l], d[k], s4[k][l], s[k]);
                        return;
                    }
            }
        }
    }
}

TEST(specular_power_by_squaring_for_whole_exponents)
{
    /* whole exponents (every shared model's Ns) multiply, others call powf; all agree with
     * powf to n ulps (each squaring doubles the relative error: at n = 1024 that is 1e-4,
     * a 40th of an 8-bit step), 0^n = 0, x^1 = x exactly, and the four lanes equal one lane */
    const float ns[] = {1, 2, 5, 16, 32, 77, 1024, 2.5f, 0.5f, 1025};
    const float xs[] = {0, 0.25f, 0.5f, 0.9f, 0.999f, 1};
    for (size_t a = 0; a < sizeof ns / sizeof *ns; a++) {
        vf x4 = {xs[1], xs[2], xs[3], xs[4]};
        vf p4 = light_pow_v(x4, ns[a]);
        for (size_t b = 0; b < sizeof xs / sizeof *xs; b++) {
            float got = light_pow(xs[b], ns[a]), want = powf(xs[b], ns[a]);
            CHECK(fabsf(got - want) <= ldexpf(ns[a] < 1 ? 1 : ns[a], -23) * want + 1e-38f);
        }
        for (int l = 0; l < SIMD_LANES; l++)
            CHECK(p4[l] == light_pow(x4[l], ns[a]));
    }
    CHECK(light_pow(0.3f, 1) == 0.3f);
    CHECK(light_pow(0, 16) == 0);
    float x = 0.9f, x2 = x * x, x4 = x2 * x2, x8 = x4 * x4, x16 = x8 * x8;
    CHECK(light_pow(x, 16) == x16); /* squarings, not powf */
    CHECK(light_pow(x, 5) == x * x4);
}
