/* test_scene.c: scene files — every statement, and every error naming file:line. */
#include <string.h>

#include "scene.h"
#include "test.h"

#define DIR "tests/data/scene/"

TEST(scene_file_reads_every_statement)
{
    struct scene s;
    struct err e = {""};
    int rc = scene_load_file(DIR "ok.rsc", &s, &e);
    if (rc)
        fprintf(stderr, "    %s\n", e.msg);
    REQUIRE(rc == 0);
    CHECK_EQ_INT(s.n_items, 2);
    CHECK_EQ_INT(s.n_meshes, 1); /* the same OBJ twice is loaded once */
    CHECK(s.items[0].mesh == s.items[1].mesh);
    /* model 0: translate(1,2,3) * rotY(90) * scale(2): vertex (1,-1,0) -> (1, 0, -2) + t */
    vec3 p = m4_mul_point(s.items[0].model, v3(1, -1, 0));
    CHECK_NEAR(p.x, 1, 1e-12);
    CHECK_NEAR(p.y, 0, 1e-12);
    CHECK_NEAR(p.z, 1, 1e-12);
    vec3 q = m4_mul_point(s.items[1].model, v3(1, 1, 1));
    CHECK_NEAR(q.x, 1, 1e-12);
    CHECK_NEAR(q.y, 2, 1e-12);
    CHECK_NEAR(q.z, 3, 1e-12);
    REQUIRE(s.items[1].kd_override != NULL);
    CHECK_NEAR(s.items[1].kd_override[1], 0.25, 1e-7);
    CHECK(s.items[0].kd_override == NULL);
    CHECK_EQ_INT(s.n_lights, 2);
    CHECK_NEAR(s.lights[1].color.x, 0.5, 1e-12);
    CHECK_NEAR(s.lights[0].color.y, 1, 1e-12);
    CHECK(s.has_camera);
    CHECK_NEAR(s.camera.eye.z, 5, 0);
    CHECK_NEAR(s.camera.fov_deg, 40, 0);
    CHECK(s.has_background);
    CHECK_EQ_INT(s.background[2], 30);
    CHECK(!s.has_sky);
    /* world box covers both placed triangles */
    CHECK(s.bound_lo.y <= -2 + 1e-9 && s.bound_hi.y >= 2 + 2 - 1e-9);
    scene_free(&s);
}

static void expect_error(struct test *t, const char *file, const char *want, int line)
{
    struct scene s;
    struct err e = {""};
    if (scene_load_file(file, &s, &e) == 0) {
        test_fail(t, __FILE__, line, "%s loaded, expected an error", file);
        scene_free(&s);
        return;
    }
    if (!strstr(e.msg, want))
        test_fail(t, __FILE__, line, "message \"%s\" lacks \"%s\"", e.msg, want);
    for (const char *c = e.msg; *c; c++)
        if ((unsigned char)*c < 0x20 || (unsigned char)*c >= 0x7f) {
            test_fail(t, __FILE__, line, "control byte in message \"%s\"", e.msg);
            break;
        }
}

TEST(scene_errors_name_file_and_line)
{
    expect_error(t, DIR "bad_option.rsc", DIR "bad_option.rsc:3: unknown model option 'bogus'",
                 __LINE__);
    expect_error(t, DIR "bad_camera.rsc", DIR "bad_camera.rsc:3: camera must not", __LINE__);
    expect_error(t, DIR "missing_model.rsc", DIR "missing_model.rsc:1: ", __LINE__);
    expect_error(t, DIR "missing_model.rsc", "missing.obj", __LINE__);
    expect_error(t, DIR "bad_sky.rsc", DIR "bad_sky.rsc:2: sky needs", __LINE__);
    expect_error(t, DIR "control.rsc", DIR "control.rsc:2: unknown statement", __LINE__);
    expect_error(t, DIR "empty.rsc", "no model statements", __LINE__);
    expect_error(t, DIR "bad_bg.rsc", DIR "bad_bg.rsc:2: background components", __LINE__);
    expect_error(t, DIR "nonexistent.rsc", "cannot open scene", __LINE__);
    expect_error(t, DIR "nul.rsc", DIR "nul.rsc:1: binary data", __LINE__);
    /* one prefix, not "longpath.rsc:1: longpath.rsc:1: ..." */
    expect_error(t, DIR "longpath.rsc", DIR "longpath.rsc:1: path too long", __LINE__);
}

TEST(scene_load_picks_format_by_extension)
{
    struct scene s;
    struct err e;
    REQUIRE(scene_load(DIR "tri.obj", &s, &e) == 0);
    CHECK_EQ_INT(s.n_items, 1);
    CHECK_EQ_INT(s.items[0].mesh->n_tris, 1);
    CHECK(strcmp(s.name, "tri.obj") == 0);
    scene_free(&s);
}

TEST(procedural_sky_follows_a_light_declared_after_it)
{
    /* the sun sits toward the first light, wherever the light line is: toward -X here */
    struct scene s;
    struct err e;
    REQUIRE(scene_load_file(DIR "late_light.rsc", &s, &e) == 0);
    REQUIRE(s.has_sky && s.sky.n_levels > 0);
    float toward[3], away[3];
    skybox_sample(&s.sky, 0, v3(-1, 0.2, 0), toward);
    skybox_sample(&s.sky, 0, v3(1, 0.2, 0), away);
    CHECK(toward[0] + toward[1] + toward[2] > away[0] + away[1] + away[2] + 0.5);
    scene_free(&s);
}
