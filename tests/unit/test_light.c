/* test_light.c: the lighting model against hand-computed values — ambient, the diffuse
 * factor, the specular exponent, Phong's renormalised normal, flat shading's face normal and
 * the base colour rule — so no shading detail depends on the Mesa oracle alone. */
#include <math.h>
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
