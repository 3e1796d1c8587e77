/* test_clip.c: polygon clipping against each plane with 0..3 corners inside. */
#include <string.h>

#include "clip.h"
#include "test.h"

/* varyings are affine functions of the clip position, so after clipping each one must still
 * equal that function of the new vertex's position */
static struct vertex_out vert(double x, double y, double z, double w)
{
    struct vertex_out v;
    memset(&v, 0, sizeof v);
    v.clip[0] = x, v.clip[1] = y, v.clip[2] = z, v.clip[3] = w;
    v.var[0] = (float)(x + 2 * y);
    v.var[1] = (float)(3 * z - w);
    v.wpos[0] = (float)w;
    v.outcode = vertex_outcode(v.clip, 2, 2);
    return v;
}

static double plane_dist(uint32_t plane, const double *c, double g)
{
    switch (plane) {
    case VERTEX_OUT_NEAR: return c[2] + c[3];
    case VERTEX_OUT_FAR: return c[3] - c[2];
    case VERTEX_GUARD_LEFT: return c[0] + g * c[3];
    case VERTEX_GUARD_RIGHT: return g * c[3] - c[0];
    case VERTEX_GUARD_BOTTOM: return c[1] + g * c[3];
    default: return g * c[3] - c[1];
    }
}

/* a vertex at "distance" d from a plane along its normal, other coordinates benign */
static struct vertex_out at(uint32_t plane, double d, double s)
{
    double w = 1;
    switch (plane) {
    case VERTEX_OUT_NEAR: return vert(s * 0.1, 0.2, d - w, w);
    case VERTEX_OUT_FAR: return vert(s * 0.1, -0.2, w - d, w);
    case VERTEX_GUARD_LEFT: return vert(d - 2 * w, s * 0.1, 0.3, w);
    case VERTEX_GUARD_RIGHT: return vert(2 * w - d, s * 0.1, -0.3, w);
    case VERTEX_GUARD_BOTTOM: return vert(s * 0.1, d - 2 * w, 0.1, w);
    default: return vert(0.3 * s, 2 * w - d, 0.2, w);
    }
}

TEST(clip_each_plane_0_1_2_3_inside)
{
    static const uint32_t planes[] = {VERTEX_OUT_NEAR,    VERTEX_OUT_FAR,      VERTEX_GUARD_LEFT,
                                      VERTEX_GUARD_RIGHT, VERTEX_GUARD_BOTTOM, VERTEX_GUARD_TOP};
    static const int want_count[4] = {0, 3, 4, 3}; /* by number of corners inside */
    for (unsigned p = 0; p < 6; p++)
        for (int inside = 0; inside <= 3; inside++) {
            struct vertex_out v[3];
            for (int i = 0; i < 3; i++)
                v[i] = at(planes[p], i < inside ? 0.5 + 0.25 * i : -0.5 - 0.25 * i,
                          (double)(i - 1));
            const struct vertex_out *in[3] = {&v[0], &v[1], &v[2]};
            struct vertex_out out[CLIP_MAX_VERTS];
            int n = clip_triangle(in, planes[p], 2, 2, 2, out);
            if (n != want_count[inside])
                test_fail(t, __FILE__, __LINE__, "plane %u, %d inside: %d vertices, want %d",
                          planes[p], inside, n, want_count[inside]);
            for (int i = 0; i < n; i++) {
                const double *c = out[i].clip;
                CHECK(plane_dist(planes[p], c, 2) >= -1e-12);
                CHECK_NEAR(out[i].var[0], c[0] + 2 * c[1], 1e-5);
                CHECK_NEAR(out[i].var[1], 3 * c[2] - c[3], 1e-5);
            }
        }
}

TEST(clip_near_then_far_keeps_slab)
{
    /* a long triangle through both near and far planes: all output within both */
    struct vertex_out v[3] = {vert(0, 0, -3, 1), vert(0.5, 0, 3, 1), vert(-0.5, 0.5, 0, 1)};
    const struct vertex_out *in[3] = {&v[0], &v[1], &v[2]};
    struct vertex_out out[CLIP_MAX_VERTS];
    int n = clip_triangle(in, VERTEX_OUT_NEAR | VERTEX_OUT_FAR, 2, 2, 2, out);
    CHECK_EQ_INT(n, 5);
    for (int i = 0; i < n; i++) {
        CHECK(out[i].clip[2] >= -out[i].clip[3] - 1e-12);
        CHECK(out[i].clip[2] <= out[i].clip[3] + 1e-12);
    }
}

TEST(clip_shared_edge_gives_identical_vertices)
{
    /* the edge a-b crosses the near plane; two triangles use it in opposite directions */
    struct vertex_out a = vert(0.1, 0.2, -5, 1), b = vert(-0.3, 0.4, 0.5, 1);
    struct vertex_out c = vert(0.5, -0.5, 0, 1), d = vert(-0.5, -0.7, 0.2, 1);
    const struct vertex_out *t1[3] = {&a, &b, &c}, *t2[3] = {&b, &a, &d};
    struct vertex_out o1[CLIP_MAX_VERTS], o2[CLIP_MAX_VERTS];
    int n1 = clip_triangle(t1, VERTEX_OUT_NEAR, 2, 2, 2, o1);
    int n2 = clip_triangle(t2, VERTEX_OUT_NEAR, 2, 2, 2, o2);
    int matches = 0;
    for (int i = 0; i < n1; i++)
        for (int j = 0; j < n2; j++)
            matches += memcmp(o1[i].clip, o2[j].clip, sizeof o1[i].clip) == 0;
    /* b is shared as is, plus the new vertex on a-b: bit-identical in both */
    CHECK_EQ_INT(matches, 2);
}

TEST(clip_behind_eye_everything_removed)
{
    /* real perspective: points behind the eye (z_eye > 0) have w < 0 and are outside near;
     * a triangle with one corner behind keeps only w >= near after clipping */
    mat4 p = m4_perspective(50, 1.5, 0.1, 100);
    vec4 pts[4] = {{0, 0, 1, 1}, {1, 0, 2, 1}, {0, 1, 0.5, 1}, {0.2, 0.3, -2, 1}};
    struct vertex_out v[4];
    for (int i = 0; i < 4; i++) {
        vec4 c = m4_mul_v4(p, pts[i]);
        v[i] = vert(c.x, c.y, c.z, c.w);
    }
    const struct vertex_out *behind[3] = {&v[0], &v[1], &v[2]};
    struct vertex_out out[CLIP_MAX_VERTS];
    CHECK_EQ_INT(clip_triangle(behind, VERTEX_OUT_NEAR, 2, 2, 2, out), 0);
    const struct vertex_out *mixed[3] = {&v[0], &v[3], &v[2]};
    int n = clip_triangle(mixed, VERTEX_OUT_NEAR, 2, 2, 2, out);
    CHECK_EQ_INT(n, 3);
    for (int i = 0; i < n; i++)
        CHECK(out[i].clip[3] >= 0.1 - 1e-12);
}
