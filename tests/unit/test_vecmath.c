/* test_vecmath.c: matrices against values worked out by hand. */
#include <string.h>

#include "test.h"
#include "vecmath.h"

static void check_mat(struct test *t, mat4 got, const double want[4][4], double tol, int line)
{
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++)
            if (!(got.m[i][j] - want[i][j] <= tol && want[i][j] - got.m[i][j] <= tol))
                test_fail(t, __FILE__, line, "m[%d][%d] = %.12g, want %.12g", i, j, got.m[i][j],
                          want[i][j]);
}

TEST(perspective_fov90_square_matches_glfrustum)
{
    /* fovy 90 -> f = 1/tan(45) = 1; n=1, f=3: (f+n)/(n-f) = -2, 2fn/(n-f) = -3 */
    const double want[4][4] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, -2, -3}, {0, 0, -1, 0}};
    check_mat(t, m4_perspective(90, 1, 1, 3), want, 1e-12, __LINE__);
    /* aspect 2 halves x */
    mat4 p = m4_perspective(90, 2, 1, 3);
    CHECK_NEAR(p.m[0][0], 0.5, 1e-12);
}

TEST(perspective_maps_near_to_minus1_far_to_plus1)
{
    mat4 p = m4_perspective(50, 16.0 / 9, 0.1, 100);
    vec4 n = m4_mul_v4(p, (vec4){0, 0, -0.1, 1}), f = m4_mul_v4(p, (vec4){0, 0, -100, 1});
    CHECK_NEAR(n.z / n.w, -1, 1e-12);
    CHECK_NEAR(f.z / f.w, 1, 1e-12);
    /* a point at the top edge of the fov maps to y_ndc = 1 */
    double y = 2 * tan(25 * M_PI / 180);
    vec4 top = m4_mul_v4(p, (vec4){0, y, -2, 1});
    CHECK_NEAR(top.y / top.w, 1, 1e-12);
}

TEST(ortho_maps_box_to_ndc_cube)
{
    mat4 o = m4_ortho(4, 2, 1, 11); /* height 4 -> y in [-2,2]; width 8 -> x in [-4,4] */
    vec4 a = m4_mul_v4(o, (vec4){4, 2, -1, 1}), b = m4_mul_v4(o, (vec4){-4, -2, -11, 1});
    CHECK_NEAR(a.x, 1, 1e-12);
    CHECK_NEAR(a.y, 1, 1e-12);
    CHECK_NEAR(a.z, -1, 1e-12);
    CHECK_NEAR(b.x, -1, 1e-12);
    CHECK_NEAR(b.y, -1, 1e-12);
    CHECK_NEAR(b.z, 1, 1e-12);
}

TEST(lookat_default_camera_is_translation)
{
    const double want[4][4] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, -3}, {0, 0, 0, 1}};
    check_mat(t, m4_lookat(v3(0, 0, 3), v3(0, 0, 0), v3(0, 1, 0)), want, 1e-12, __LINE__);
}

TEST(lookat_from_plus_x_rotates_world)
{
    /* eye on +X looking at the origin: world +X is toward the viewer (view +Z),
     * world -Z is to the right (view +X) */
    mat4 v = m4_lookat(v3(5, 0, 0), v3(0, 0, 0), v3(0, 1, 0));
    vec3 p = m4_mul_point(v, v3(0, 0, -1));
    CHECK_NEAR(p.x, 1, 1e-12);
    CHECK_NEAR(p.y, 0, 1e-12);
    CHECK_NEAR(p.z, -5, 1e-12);
}

TEST(normal_matrix_is_inverse_transpose)
{
    /* non-uniform scale (2,1,1): normals scale by (1/2,1,1) */
    mat4 n = m4_normal_matrix(m4_scale(v3(2, 1, 1)));
    const double want[4][4] = {{0.5, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}};
    check_mat(t, n, want, 1e-15, __LINE__);
    /* a sheared plane's normal stays perpendicular to its transformed tangents */
    mat4 m = m4_identity();
    m.m[0][1] = 0.7; /* x += 0.7 y */
    mat4 nm = m4_normal_matrix(m);
    vec3 normal = m4_mul_dir(nm, v3(1, 1, 0)); /* plane x + y = 0, tangent (1,-1,0), (0,0,1) */
    CHECK_NEAR(v3_dot(normal, m4_mul_dir(m, v3(1, -1, 0))), 0, 1e-12);
    CHECK_NEAR(v3_dot(normal, m4_mul_dir(m, v3(0, 0, 1))), 0, 1e-12);
}

TEST(rotate_is_counterclockwise_about_axis)
{
    vec3 p = m4_mul_point(m4_rotate(v3(0, 0, 1), 90), v3(1, 0, 0));
    CHECK_NEAR(p.x, 0, 1e-15);
    CHECK_NEAR(p.y, 1, 1e-15);
}

#include "camera.h"

TEST(camera_turn_yaw_left_pitch_up_and_clamped)
{
    struct camera c;
    camera_default(&c);
    c.eye = v3(0, 0, 0), c.target = v3(0, 0, -1);
    camera_turn(&c, 90, 0, 0); /* yaw left: now looking down -X */
    CHECK_NEAR(c.target.x, -1, 1e-12);
    CHECK_NEAR(c.target.z, 0, 1e-12);
    camera_turn(&c, 0, 200, 0); /* pitch far up: clamped 1 degree short of +Y */
    double ang = acos(v3_dot(v3_norm(v3_sub(c.target, c.eye)), v3(0, 1, 0))) * 180 / M_PI;
    CHECK_NEAR(ang, CAMERA_PITCH_LIMIT, 1e-9);
    camera_turn(&c, 0, -400, 0);
    ang = acos(v3_dot(v3_norm(v3_sub(c.target, c.eye)), v3(0, 1, 0))) * 180 / M_PI;
    CHECK_NEAR(ang, 180 - CAMERA_PITCH_LIMIT, 1e-9);
}

TEST(camera_orbit_keeps_target_and_distance)
{
    struct camera c;
    camera_default(&c);
    camera_turn(&c, 90, 30, 1);
    CHECK_NEAR(c.target.x, 0, 1e-12);
    CHECK_NEAR(camera_distance(&c), 3, 1e-12);
    CHECK(c.eye.y > 0); /* orbit "pitch up" raises the eye: we look down on the model */
    camera_move(&c, 2.5, 0, 0, 1); /* zoom in */
    CHECK_NEAR(camera_distance(&c), 0.5, 1e-12);
    camera_move(&c, 10, 0, 0, 1); /* never through the target */
    CHECK(camera_distance(&c) > 0);
}
