/* test_obj.c: OBJ parsing and mesh building, from in-memory text, the fixtures in
 * tests/data/obj/ (run from the repository root) and the shared models. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include <stdio.h>
#include <unistd.h>

#include "model.h"
#include "mtl.h"
#include "obj.h"
#include "test.h"

#define DATA "tests/data/obj/"

static int parse(const char *text, struct mesh *m, struct err *e)
{
    return obj_parse(text, strlen(text), "t.obj", m, e);
}

static const struct mesh_vertex *corner(const struct mesh *m, uint32_t tri, int k)
{
    return &m->verts[m->tris[tri][k]];
}

static void check_vec3(struct test *t, const float *got, double x, double y, double z,
                       double tol, int line)
{
    if (!(fabs(got[0] - x) <= tol && fabs(got[1] - y) <= tol && fabs(got[2] - z) <= tol))
        test_fail(t, __FILE__, line, "(%.9g, %.9g, %.9g) != (%.9g, %.9g, %.9g)", got[0], got[1],
                  got[2], x, y, z);
}
#define CHECK_VEC3(got, x, y, z) check_vec3(t, (got), (x), (y), (z), 1e-6, __LINE__)

static bool have_fixtures(struct test *t)
{
    struct stat st;
    if (stat(DATA "materials.obj", &st) != 0) {
        test_fail(t, __FILE__, __LINE__, "fixtures missing: run from the repository root");
        return false;
    }
    return true;
}

TEST(all_four_corner_forms_parse)
{
    struct mesh m;
    struct err e;
    REQUIRE(parse("v 0 0 0\nv 1 0 0\nv 0 1 0\n"
                  "vt 0.25 0.75\nvt 0.5 0.5\n"
                  "vn 0 0 2\nvn 1 0 0\n"
                  "f 1 2 3\n"
                  "f 1/1 2/2 3/1\n"
                  "f 1//2 2//2 3//2\n"
                  "f 1/2/1 2/1/1 3/2/2\n",
                  &m, &e) == 0);
    CHECK_EQ_INT(m.n_tris, 4);
    CHECK_EQ_INT(m.n_verts, 12);
    CHECK(m.has_uvs);
    CHECK(m.has_normals);
    /* v: uv (0,0), generated normal of the plane */
    CHECK_VEC3(corner(&m, 0, 1)->pos, 1, 0, 0);
    CHECK_NEAR(corner(&m, 0, 1)->uv[0], 0, 0);
    CHECK_VEC3(corner(&m, 0, 1)->nrm, 0, 0, 1);
    /* v/vt */
    CHECK_NEAR(corner(&m, 1, 0)->uv[0], 0.25, 1e-7);
    CHECK_NEAR(corner(&m, 1, 0)->uv[1], 0.75, 1e-7);
    CHECK_NEAR(corner(&m, 1, 1)->uv[0], 0.5, 1e-7);
    CHECK_NEAR(corner(&m, 1, 2)->uv[1], 0.75, 1e-7);
    /* v//vn */
    CHECK_VEC3(corner(&m, 2, 2)->nrm, 1, 0, 0);
    CHECK_NEAR(corner(&m, 2, 2)->uv[1], 0, 0);
    /* v/vt/vn; the file's (0,0,2) comes back unit length */
    CHECK_VEC3(corner(&m, 3, 0)->nrm, 0, 0, 1);
    CHECK_NEAR(corner(&m, 3, 0)->uv[0], 0.5, 1e-7);
    CHECK_VEC3(corner(&m, 3, 2)->nrm, 1, 0, 0);
    CHECK_NEAR(corner(&m, 3, 1)->uv[1], 0.75, 1e-7);
    mesh_free(&m);
}

TEST(mixed_corners_in_one_face_fill_missing_parts)
{
    struct mesh m;
    struct err e;
    /* corner 1 has all three, corner 2 lacks vt, corner 3 lacks vn */
    REQUIRE(parse("v 0 0 0\nv 2 0 0\nv 0 2 0\nvt 0.5 0.25\nvn 1 0 0\n"
                  "f 1/1/1 2//1 3/1\n",
                  &m, &e) == 0);
    CHECK_NEAR(corner(&m, 0, 1)->uv[0], 0, 0);
    CHECK_NEAR(corner(&m, 0, 1)->uv[1], 0, 0);
    CHECK_VEC3(corner(&m, 0, 1)->nrm, 1, 0, 0);
    CHECK_NEAR(corner(&m, 0, 2)->uv[0], 0.5, 1e-7);
    CHECK_VEC3(corner(&m, 0, 2)->nrm, 0, 0, 1); /* generated from the face */
    mesh_free(&m);
}

TEST(negative_indices_are_relative)
{
    struct mesh m;
    struct err e;
    REQUIRE(parse("v 0 0 0\nv 1 0 0\nv 0 1 0\n"
                  "f -3 -2 -1\n"
                  "v 5 5 5\nvt 0 1\nvn 0 1 0\n"
                  "f -4/-1/-1 -2/-1/-1 -1/-1/-1\n",
                  &m, &e) == 0);
    REQUIRE(m.n_tris == 2);
    CHECK_VEC3(corner(&m, 0, 0)->pos, 0, 0, 0);
    CHECK_VEC3(corner(&m, 0, 2)->pos, 0, 1, 0);
    CHECK_VEC3(corner(&m, 1, 0)->pos, 0, 0, 0);
    CHECK_VEC3(corner(&m, 1, 1)->pos, 0, 1, 0);
    CHECK_VEC3(corner(&m, 1, 2)->pos, 5, 5, 5);
    CHECK_NEAR(corner(&m, 1, 2)->uv[1], 1, 0);
    CHECK_VEC3(corner(&m, 1, 2)->nrm, 0, 1, 0);
    mesh_free(&m);
}

TEST(quad_is_fanned_0_i_i1)
{
    struct mesh m;
    struct err e;
    /* position k is (k, k*k, 0), so x names the index; winding is kept, also reversed */
    REQUIRE(parse("v 1 1 0\nv 2 4 0\nv 3 9 0\nv 4 16 0\nv 5 25 0\n"
                  "f 1 2 3 4 5\nf 3 2 1\n",
                  &m, &e) == 0);
    REQUIRE(m.n_tris == 4);
    const int want[4][3] = {{1, 2, 3}, {1, 3, 4}, {1, 4, 5}, {3, 2, 1}};
    for (uint32_t i = 0; i < 4; i++)
        for (int k = 0; k < 3; k++)
            CHECK_NEAR(corner(&m, i, k)->pos[0], want[i][k], 0);
    mesh_free(&m);
}

TEST(crlf_and_tabs_accepted)
{
    struct mesh a, b;
    struct err e;
    REQUIRE(parse("# header\r\n"
                  "v\t0 0 0\r\n"
                  "\r\n"
                  "  v 1\t0 0  \r\n"
                  "\tv 0 1 0\t\r\n"
                  "   \r\n"
                  "vt 0.5 0.5 \r\n"
                  "f\t1/1 2/1\t3/1 \r\n"
                  "f 3/1 2/1 1/1", /* no newline at the end */
                  &a, &e) == 0);
    REQUIRE(parse("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0.5 0.5\nf 1/1 2/1 3/1\nf 3/1 2/1 1/1\n", &b,
                  &e) == 0);
    REQUIRE(a.n_verts == b.n_verts);
    CHECK_EQ_INT(a.n_tris, 2);
    CHECK(memcmp(a.verts, b.verts, a.n_verts * sizeof *a.verts) == 0);
    CHECK(memcmp(a.tris, b.tris, a.n_tris * sizeof *a.tris) == 0);
    mesh_free(&a);
    mesh_free(&b);
}

TEST(comments_end_number_lines_anywhere)
{
    struct mesh m;
    struct err e;
    REQUIRE(parse("v 1 2 3# glued\nv 4 5 6 # spaced\n# whole line\nv 7 8 9\nf 1 2 3#tri\n", &m,
                  &e) == 0);
    CHECK_EQ_INT(m.n_tris, 1);
    CHECK_VEC3(corner(&m, 0, 0)->pos, 1, 2, 3);
    CHECK_VEC3(corner(&m, 0, 2)->pos, 7, 8, 9);
    mesh_free(&m);
}

TEST(extra_vertex_values_ignored)
{
    struct mesh m;
    struct err e;
    /* w, vertex colours, a 1-value and a 3-value vt */
    REQUIRE(parse("v 1 2 3 1.0 0.5 0.25 0.125\nv 4 5 6 1\nv 7 8 9\nvt 0.5\nvt 0.25 0.75 0.0\n"
                  "f 1/1 2/2 3/1\n",
                  &m, &e) == 0);
    CHECK_VEC3(corner(&m, 0, 0)->pos, 1, 2, 3);
    CHECK_VEC3(corner(&m, 0, 1)->pos, 4, 5, 6);
    CHECK_NEAR(corner(&m, 0, 0)->uv[0], 0.5, 0);
    CHECK_NEAR(corner(&m, 0, 0)->uv[1], 0, 0);
    CHECK_NEAR(corner(&m, 0, 1)->uv[0], 0.25, 0);
    CHECK_NEAR(corner(&m, 0, 1)->uv[1], 0.75, 0);
    mesh_free(&m);
}

TEST(unknown_statements_ignored)
{
    struct mesh m;
    struct err e;
    REQUIRE(parse("o thing\ng group one\ns 1\ns off\nl 1 2\np 1\nvp 0.5\ncstype bezier\n"
                  "deg 3\nfoo bar baz\nusemtl\nmtllib\n"
                  "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
                  &m, &e) == 0);
    CHECK_EQ_INT(m.n_tris, 1);
    mesh_free(&m);
}

TEST(missing_normals_area_weighted)
{
    struct mesh m;
    struct err e;
    /* Position 1 is shared by three triangles:
     *   A (1,2,3): cross((2,0,0),(0,2,0)) = (0,0,4)
     *   B (1,4,5): cross((0,0,1),(1,0,0)) = (0,1,0)
     *   C (1,6,7): cross((0,3,0),(0,0,3)) = (9,0,0), its corners carry vn (0,-1,0)
     * Corners without vn at position 1 get normalize(9,1,4) (C counts: per position, every
     * triangle); corners only on A or B get that face's direction; C keeps its vn. */
    REQUIRE(parse("v 0 0 0\nv 2 0 0\nv 0 2 0\nv 0 0 1\nv 1 0 0\nv 0 3 0\nv 0 0 3\n"
                  "vn 0 -1 0\n"
                  "f 1 2 3\nf 1 4 5\nf 1//1 6//1 7//1\n",
                  &m, &e) == 0);
    double l = sqrt(81 + 1 + 16);
    CHECK_VEC3(corner(&m, 0, 0)->nrm, 9 / l, 1 / l, 4 / l);
    CHECK_VEC3(corner(&m, 1, 0)->nrm, 9 / l, 1 / l, 4 / l);
    CHECK_EQ_INT(m.tris[0][0], m.tris[1][0]); /* same (pos, -, -) corner: one vertex */
    CHECK_VEC3(corner(&m, 0, 1)->nrm, 0, 0, 1);
    CHECK_VEC3(corner(&m, 1, 2)->nrm, 0, 1, 0);
    CHECK_VEC3(corner(&m, 2, 0)->nrm, 0, -1, 0);
    CHECK(m.has_normals);
    mesh_free(&m);
}

TEST(missing_normals_quads_weighted_after_fanning)
{
    struct mesh m;
    struct err e;
    /* a 2x1 quad in z=0 fanned into two triangles of area 1 each; its corner 1 is on both,
     * corner 2 only on the first: every normal is +z either way, and the sum is not
     * renormalised per triangle (a tilted second face would show it) */
    REQUIRE(parse("v 0 0 0\nv 2 0 0\nv 2 1 0\nv 0 1 1\nf 1 2 3 4\n", &m, &e) == 0);
    REQUIRE(m.n_tris == 2);
    /* tri0 (1,2,3): cross((2,0,0),(2,1,0)) = (0,0,2); tri1 (1,3,4): cross((2,1,0),(0,1,1))
     * = (1,-2,2). Position 1: (1,-2,4)/sqrt(21); position 2: (0,0,1); 4: (1,-2,2)/3 */
    double l = sqrt(21);
    CHECK_VEC3(corner(&m, 0, 0)->nrm, 1 / l, -2 / l, 4 / l);
    CHECK_VEC3(corner(&m, 0, 1)->nrm, 0, 0, 1);
    CHECK_VEC3(corner(&m, 1, 2)->nrm, 1 / 3.0, -2 / 3.0, 2 / 3.0);
    mesh_free(&m);
}

TEST(missing_normals_zero_sum_is_plus_z)
{
    struct mesh m;
    struct err e;
    /* the same triangle in both windings cancels; a collinear one has no area */
    REQUIRE(parse("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 5 0 0\nv 6 0 0\nv 7 0 0\n"
                  "f 1 2 3\nf 1 3 2\nf 4 5 6\n",
                  &m, &e) == 0);
    CHECK(!m.has_normals);
    for (uint32_t i = 0; i < m.n_verts; i++)
        CHECK_VEC3(m.verts[i].nrm, 0, 0, 1);
    mesh_free(&m);
}

TEST(vertex_dedup_counts)
{
    static const char *cube_v = "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\n"
                                "v -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n";
    char text[1024];
    struct mesh m;
    struct err e;
    /* positions only: 8 corners shared by 12 triangles */
    snprintf(text, sizeof text,
             "%sf 1 2 3 4\nf 5 8 7 6\nf 1 5 6 2\nf 2 6 7 3\nf 3 7 8 4\nf 4 8 5 1\n", cube_v);
    REQUIRE(parse(text, &m, &e) == 0);
    CHECK_EQ_INT(m.n_tris, 12);
    CHECK_EQ_INT(m.n_verts, 8);
    mesh_free(&m);
    /* one normal per face: every position splits into 3 vertices */
    snprintf(text, sizeof text,
             "%svn 0 0 -1\nvn 0 0 1\nvn 0 -1 0\nvn 1 0 0\nvn 0 1 0\nvn -1 0 0\n"
             "f 1//1 2//1 3//1 4//1\nf 5//2 8//2 7//2 6//2\nf 1//3 5//3 6//3 2//3\n"
             "f 2//4 6//4 7//4 3//4\nf 3//5 7//5 8//5 4//5\nf 4//6 8//6 5//6 1//6\n",
             cube_v);
    REQUIRE(parse(text, &m, &e) == 0);
    CHECK_EQ_INT(m.n_verts, 24);
    /* every triangle's corners carry their face's normal */
    for (uint32_t i = 0; i < m.n_tris; i++)
        for (int k = 1; k < 3; k++)
            CHECK(memcmp(corner(&m, i, k)->nrm, corner(&m, i, 0)->nrm, 12) == 0);
    mesh_free(&m);
    /* the same corner repeated in one face is one vertex; tris index it twice */
    REQUIRE(parse("v 0 0 0\nv 1 0 0\nf 1 2 1\n", &m, &e) == 0);
    CHECK_EQ_INT(m.n_verts, 2);
    CHECK_EQ_INT(m.tris[0][0], m.tris[0][2]);
    mesh_free(&m);
}

TEST(bounds_cover_used_positions_only)
{
    struct mesh m;
    struct err e;
    REQUIRE(parse("v 100 100 100\nv 0 0 0\nv 2 0 0\nv 0 4 0\nv 2 4 -6\nf 2 3 4\nf 3 5 4\n",
                  &m, &e) == 0);
    CHECK_VEC3(m.bbox_min, 0, 0, -6);
    CHECK_VEC3(m.bbox_max, 2, 4, 0);
    CHECK_VEC3(m.center, 1, 2, -3);
    CHECK_NEAR(m.radius, sqrt(1 + 4 + 9), 1e-6);
    for (uint32_t i = 0; i < m.n_verts; i++) {
        double d2 = 0;
        for (int k = 0; k < 3; k++)
            d2 += pow(m.verts[i].pos[k] - m.center[k], 2);
        CHECK(sqrt(d2) <= m.radius);
    }
    mesh_free(&m);
}

struct bad_case {
    const char *text, *msg;
};

TEST(error_names_file_and_line)
{
    static const struct bad_case cases[] = {
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n",
         "t.obj:4: face corner '4': v index out of range (3 defined so far)"},
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf -4 2 3\n",
         "t.obj:4: face corner '-4': v index out of range (3 defined so far)"},
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 1 2 99999999999\n",
         "t.obj:5: face corner '99999999999': v index out of range (3 defined so far)"},
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n",
         "t.obj:4: face corner '0': index 0 is invalid (OBJ counts from 1)"},
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/0 2 3\n",
         "t.obj:4: face corner '1/0': index 0 is invalid (OBJ counts from 1)"},
        {"v 0 0 0\nv 1 0 0\nf 1 2\n", "t.obj:3: face needs at least 3 corners, got 2"},
        {"f\n", "t.obj:1: face needs at least 3 corners, got 0"},
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/1/1/1 2 3\n", "t.obj:4: bad face corner '1/1/1/1'"},
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3x\n", "t.obj:4: bad face corner '3x'"},
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 /3\n", "t.obj:4: bad face corner '/3'"},
        {"v 0 0 0\r\nv 1 0 abc\r\n", "t.obj:2: bad number 'abc'"},
        {"v 1.5.2 0 0\n", "t.obj:1: bad number '1.5.2'"},
        {"vn 0 0 1e\n", "t.obj:1: bad number '1e'"},
        {"v nan 0 0\n", "t.obj:1: bad number 'nan'"},
        {"v 0 0\n", "t.obj:1: 'v' needs 3 numbers, got 2"},
        {"vt\n", "t.obj:1: 'vt' needs 1 number, got 0"},
        {"vn 1 0 # z missing\n", "t.obj:1: 'vn' needs 3 numbers, got 2"},
        {"v 1e39 0 0\n", "t.obj:1: number out of range '1e39'"},
        {"", "t.obj: no faces"},
        {"v 0 0 0\n# nothing else\n", "t.obj: no faces"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        struct mesh m;
        struct err e = {{0}};
        CHECK_EQ_INT(parse(cases[i].text, &m, &e), -1);
        if (strcmp(e.msg, cases[i].msg) != 0)
            test_fail(t, __FILE__, __LINE__, "case %zu: got \"%s\", want \"%s\"", i, e.msg,
                      cases[i].msg);
    }
}

TEST(error_names_referring_file_and_line_on_disk)
{
    struct mesh m;
    struct err e = {{0}};
    CHECK_EQ_INT(obj_load(DATA "no_such_file.obj", &m, &e), -1);
    CHECK(strcmp(e.msg, DATA "no_such_file.obj: cannot read: No such file or directory") == 0);
}

/* load a fixture the way rastty does (model.h), keeping the warnings */
static int load_warn(const char *path, struct mesh *m, struct warnings *w, struct err *e)
{
    memset(w, 0, sizeof *w);
    return model_load(path, NULL, w, m, e);
}

#define CHECK_WARNING(w, i, text)                                                          \
    do {                                                                                   \
        if ((w).n <= (i) || strcmp((w).msg[i], (text)) != 0)                               \
            test_fail(t, __FILE__, __LINE__, "warning %d: got \"%s\", want \"%s\"", (i),     \
                      (w).n > (i) ? (w).msg[i] : "(none)", (text));                        \
    } while (0)

/* issue 12: a material's missing or broken file is a warning; the model still draws */
TEST(missing_material_files_are_warnings)
{
    if (!have_fixtures(t))
        return;
    static const struct bad_case cases[] = {
        {DATA "missing_mtl.obj", DATA "missing_mtl.obj:4: cannot open material library '" DATA
                                      "nope.mtl': No such file or directory; default materials "
                                      "used"},
        {DATA "missing_tex.obj",
         DATA "missing_tex.mtl:3: cannot open texture '" DATA "nope.png': No such file or "
              "directory; drawn without it"},
        {DATA "bad_mtl.obj", DATA "bad.mtl:2: bad number 'x'; material library ignored"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        struct mesh m;
        struct err e = {{0}};
        struct warnings w;
        if (load_warn(cases[i].text, &m, &w, &e)) {
            test_fail(t, __FILE__, __LINE__, "case %zu: %s", i, e.msg);
            continue;
        }
        CHECK_EQ_INT(m.n_tris, 1);
        CHECK_EQ_INT(m.n_textures, 0);
        CHECK_EQ_INT(w.n, 1);
        CHECK_WARNING(w, 0, cases[i].msg);
        mesh_free(&m);
    }
    /* a file that is not an image: the MTL line, then the decoder's reason */
    struct mesh m;
    struct err e;
    struct warnings w;
    REQUIRE(load_warn(DATA "corrupt_tex.obj", &m, &w, &e) == 0);
    CHECK_EQ_INT(m.materials[1].texture, -1);
    REQUIRE(w.n == 1);
    CHECK_STR_CONTAINS(w.msg[0], DATA "corrupt_tex.mtl:2: bad texture (" DATA "corrupt.png: ");
    mesh_free(&m);
}

/* issue 12: a FIFO or device named by mtllib is refused at once, never read */
TEST(special_files_named_by_a_model_are_refused)
{
    char dir[64], obj[96], fifo[96], text[300];
    snprintf(dir, sizeof dir, "/tmp/rastty-special-%d", (int)getpid());
    mkdir(dir, 0700);
    snprintf(obj, sizeof obj, "%s/m.obj", dir);
    snprintf(fifo, sizeof fifo, "%s/fifo.mtl", dir);
    REQUIRE(mkfifo(fifo, 0600) == 0);
    snprintf(text, sizeof text,
             "v 0 0 0\nv 1 0 0\nv 0 1 0\nmtllib /dev/zero\nmtllib fifo.mtl\nf 1 2 3\n");
    FILE *f = fopen(obj, "w");
    REQUIRE(f);
    fputs(text, f);
    fclose(f);
    struct mesh m;
    struct err e;
    struct warnings w;
    REQUIRE(load_warn(obj, &m, &w, &e) == 0);
    CHECK_EQ_INT(w.n, 2);
    CHECK_STR_CONTAINS(w.msg[0], "m.obj:4: cannot open material library '/dev/zero': a device, "
                                 "not a regular file");
    CHECK_STR_CONTAINS(w.msg[1], "m.obj:5: cannot open material library '");
    CHECK_STR_CONTAINS(w.msg[1], "fifo.mtl': a FIFO, not a regular file");
    mesh_free(&m);
    unlink(fifo);
    unlink(obj);
    rmdir(dir);
}

/* issue 12: OBJ as exporters write it */
TEST(mtllib_names_with_spaces)
{
    if (!have_fixtures(t))
        return;
    const char *files[] = {DATA "spaced_mtllib.obj", DATA "escaped_mtllib.obj"};
    for (int i = 0; i < 2; i++) {
        struct mesh m;
        struct err e;
        struct warnings w;
        if (load_warn(files[i], &m, &w, &e)) {
            test_fail(t, __FILE__, __LINE__, "%s", e.msg);
            continue;
        }
        CHECK_EQ_INT(w.n, 0);
        REQUIRE(m.n_materials == 2);
        CHECK(strcmp(m.materials[1].name, "green") == 0);
        CHECK_VEC3(m.materials[1].kd, 0, 1, 0);
        mesh_free(&m);
    }
}

TEST(windows_texture_path_and_unknown_option)
{
    if (!have_fixtures(t))
        return;
    struct mesh m;
    struct err e;
    struct warnings w;
    /* map_Kd -colorspace sRGB .\sub\check.png */
    REQUIRE(load_warn(DATA "windows.obj", &m, &w, &e) == 0);
    REQUIRE(m.n_materials == 2);
    CHECK_EQ_INT(m.n_textures, 1);
    CHECK_EQ_INT(m.materials[1].texture, 0);
    CHECK_EQ_INT(m.textures[0].w, 2);
    CHECK_EQ_INT(w.n, 1);
    CHECK_WARNING(w, 0, DATA "windows.mtl:3: unknown map_Kd option '-colorspace' skipped with "
                             "its value");
    mesh_free(&m);
}

TEST(uv_and_normal_indices_past_the_end_are_warnings)
{
    struct mesh m;
    struct err e;
    struct warnings w = {0};
    struct model_ctx ctx = {.path = "t.obj", .warn = &w};
    static const char text[] = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0.5 0.5\nvn 1 0 0\n"
                               "f 1/2 2/1 3\nf 1//1 2//1 3//2\n";
    REQUIRE(model_parse_as(MODEL_OBJ, text, sizeof text - 1, &ctx, &m, &e) == 0);
    CHECK_EQ_INT(m.n_tris, 2);
    CHECK_NEAR(corner(&m, 0, 0)->uv[0], 0, 0);   /* lost its uv */
    CHECK_NEAR(corner(&m, 0, 1)->uv[0], 0.5, 0); /* kept */
    CHECK_VEC3(corner(&m, 1, 0)->nrm, 1, 0, 0);
    CHECK_VEC3(corner(&m, 1, 2)->nrm, 0, 0, 1); /* generated from the face */
    CHECK_EQ_INT(w.n, 2);
    CHECK_WARNING(w, 0, "t.obj:6: face corner '1/2': vt index out of range (1 defined so far); "
                        "the corner has no uv");
    CHECK_WARNING(w, 1, "t.obj:7: face corner '3//2': vn index out of range (1 defined so far); "
                        "the corner has no normal");
    mesh_free(&m);
}

TEST(byte_order_mark_keeps_the_first_vertex)
{
    struct mesh m;
    struct err e;
    REQUIRE(parse("\xef\xbb\xbfv 5 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", &m, &e) == 0);
    CHECK_VEC3(corner(&m, 0, 0)->pos, 5, 0, 0);
    mesh_free(&m);
}

TEST(lines_points_and_utf16_say_so)
{
    struct mesh m;
    struct err e;
    CHECK_EQ_INT(parse("v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2 3\nl 1 2\np 1\n", &m, &e), -1);
    CHECK(strcmp(e.msg, "t.obj: no faces, only 2 line and 1 point elements (rastty draws "
                        "surfaces)") == 0);
    static const char u16[] = "\xff\xfev\0 \0""0\0 \0""0\0";
    CHECK_EQ_INT(obj_parse(u16, sizeof u16 - 1, "t.obj", &m, &e), -1);
    CHECK(strcmp(e.msg, "t.obj: UTF-16 text (save the file as UTF-8 or ASCII)") == 0);
}

/* twice the area of triangle i, in the xy plane */
static double area2(const struct mesh *m, uint32_t i)
{
    const float *a = corner(m, i, 0)->pos, *b = corner(m, i, 1)->pos, *c = corner(m, i, 2)->pos;
    return (double)(b[0] - a[0]) * (c[1] - a[1]) - (double)(b[1] - a[1]) * (c[0] - a[0]);
}

/* issue 12: a 66-corner face outlining a ring drew as a filled disc (fanned) */
TEST(concave_ring_face_is_ear_clipped)
{
    /* outer circle r=1 counter-clockwise (33 corners, the first repeated), a bridge to the
     * inner circle r=0.5 walked clockwise (33 corners): one polygon with a hole */
    char text[8192];
    size_t n = 0;
    const int k = 32;
    for (int i = 0; i <= k; i++)
        n += (size_t)snprintf(text + n, sizeof text - n, "v %.9f %.9f 0\n",
                              cos(2 * M_PI * i / k), sin(2 * M_PI * i / k));
    for (int i = 0; i <= k; i++)
        n += (size_t)snprintf(text + n, sizeof text - n, "v %.9f %.9f 0\n",
                              0.5 * cos(-2 * M_PI * i / k), 0.5 * sin(-2 * M_PI * i / k));
    n += (size_t)snprintf(text + n, sizeof text - n, "f");
    for (int i = 1; i <= 2 * (k + 1); i++)
        n += (size_t)snprintf(text + n, sizeof text - n, " %d", i);
    n += (size_t)snprintf(text + n, sizeof text - n, "\n");
    struct mesh m;
    struct err e;
    REQUIRE(obj_parse(text, n, "ring.obj", &m, &e) == 0);
    CHECK_EQ_INT(m.n_tris, 2 * (k + 1) - 2);
    /* the triangles cover the ring exactly once: total area = outer - inner polygon, every
     * triangle wound counter-clockwise, and none covers the centre */
    double sum = 0, want = 0.75 * 0.5 * k * sin(2 * M_PI / k); /* (1 - 1/4) * k-gon area */
    for (uint32_t i = 0; i < m.n_tris; i++) {
        double a = area2(&m, i);
        CHECK(a >= -1e-9);
        sum += a / 2;
        /* centre (0,0) strictly inside? */
        const float *p[3] = {corner(&m, i, 0)->pos, corner(&m, i, 1)->pos, corner(&m, i, 2)->pos};
        int inside = 1;
        for (int j = 0; j < 3; j++) {
            const float *u = p[j], *v = p[(j + 1) % 3];
            inside &= (double)(v[0] - u[0]) * (0 - u[1]) - (double)(v[1] - u[1]) * (0 - u[0]) > 0;
        }
        CHECK(!inside);
    }
    CHECK_NEAR(sum, want, 1e-5);
    mesh_free(&m);
    /* convex polygons keep their fan (0, i, i+1): quad_is_fanned_0_i_i1 */
}

TEST(in_memory_errors_say_memory)
{
    struct mesh m;
    struct err e;
    CHECK_EQ_INT(obj_parse("v x 0 0\n", 8, NULL, &m, &e), -1);
    CHECK(strcmp(e.msg, "<memory>:1: bad number 'x'") == 0);
}

TEST(control_bytes_not_echoed)
{
    struct mesh m;
    struct err e;
    CHECK_EQ_INT(parse("v 1 \x1b[31mred\x07 0\n", &m, &e), -1);
    CHECK(strcmp(e.msg, "t.obj:1: bad number '?[31mred?'") == 0);
    /* long junk is cut after 40 bytes, and a hostile path is sanitised too */
    char text[400] = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 ";
    size_t n = strlen(text);
    memset(text + n, 'z', 300);
    text[n + 300] = '\0';
    CHECK_EQ_INT(obj_parse(text, strlen(text), "dir/\x1b]0;x\x07.obj", &m, &e), -1);
    char want[200];
    snprintf(want, sizeof want, "dir/?]0;x?.obj:4: bad face corner '%.40s...'", text + n);
    if (strcmp(e.msg, want) != 0)
        test_fail(t, __FILE__, __LINE__, "got \"%s\", want \"%s\"", e.msg, want);
    for (const char *c = e.msg; *c; c++)
        CHECK(*c >= 0x20 && *c < 0x7f);
    CHECK(strlen(e.msg) < 200);
}

TEST(long_lines_are_not_truncated)
{
    /* a 1 MB comment, a number padded by 100k spaces, a 300-digit number, and one face
     * of 100000 corners (fanned into 99998 triangles) */
    size_t cap = 3u << 20, n = 0;
    char *s = malloc(cap);
    REQUIRE(s);
    s[n++] = '#';
    memset(s + n, 'x', 1u << 20);
    n += 1u << 20;
    n += (size_t)sprintf(s + n, "\nv 0 0");
    memset(s + n, ' ', 100000);
    n += 100000;
    n += (size_t)sprintf(s + n, "0\nv 1");
    memset(s + n, '0', 300);
    n += 300;
    n += (size_t)sprintf(s + n, "e-300 0 0\nv 0 1 0\nf");
    for (int i = 0; i < 100000; i++)
        n += (size_t)sprintf(s + n, " %d", 1 + i % 3);
    s[n++] = '\n';
    struct mesh m;
    struct err e;
    int rc = obj_parse(s, n, "t.obj", &m, &e);
    free(s);
    REQUIRE(rc == 0);
    CHECK_EQ_INT(m.n_tris, 99998);
    CHECK_EQ_INT(m.n_verts, 3);
    CHECK_VEC3(m.verts[m.tris[0][1]].pos, 1, 0, 0);
    mesh_free(&m);
}

TEST(binary_garbage_does_not_crash)
{
    /* junk lines behind an unknown keyword are skipped ... */
    static const char ok[] = "v 0 0 0\nv 1 0 0\nv 0 1 0\n"
                             "X\x00\xff\xfe\x80 \x01\x02\r\r\n"
                             "\x7f\x80\x81 v 1 2 3\n"
                             "\xef\xbb\xbf\n"
                             "f 1 2 3\n";
    struct mesh m;
    struct err e;
    REQUIRE(obj_parse(ok, sizeof ok - 1, "t.obj", &m, &e) == 0);
    CHECK_EQ_INT(m.n_tris, 1);
    mesh_free(&m);
    /* ... and random bytes either parse or fail with a clean one-line message */
    uint32_t x = 12345;
    for (int round = 0; round < 200; round++) {
        char buf[512];
        size_t len = 0;
        len += (size_t)sprintf(buf, "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
        for (; len < sizeof buf; len++) {
            x = x * 1664525u + 1013904223u;
            const char alphabet[] = "vtnf/ -0123#\n\r\t.e";
            buf[len] = (x >> 24) & 1 ? (char)(x >> 16) : alphabet[(x >> 8) % 18];
        }
        if (obj_parse(buf, len, "t.obj", &m, &e) == 0) {
            for (uint32_t i = 0; i < m.n_tris; i++)
                for (int k = 0; k < 3; k++)
                    CHECK(m.tris[i][k] < m.n_verts);
            mesh_free(&m);
        } else {
            CHECK(strncmp(e.msg, "t.obj", 5) == 0);
            for (const char *c = e.msg; *c; c++)
                CHECK(*c >= 0x20 && *c < 0x7f);
        }
    }
}

TEST(failure_leaves_mesh_zeroed)
{
    struct mesh m, zero;
    struct err e;
    memset(&m, 0xab, sizeof m);
    memset(&zero, 0, sizeof zero);
    CHECK_EQ_INT(parse("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 9\n", &m, &e), -1);
    CHECK(memcmp(&m, &zero, sizeof m) == 0);
    mesh_free(&m); /* harmless */
}

TEST(in_memory_usemtl_uses_default_material)
{
    struct mesh m;
    struct err e;
    static const char text[] = "mtllib x.mtl\nusemtl shiny\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    REQUIRE(obj_parse(text, sizeof text - 1, NULL, &m, &e) == 0);
    CHECK_EQ_INT(m.n_materials, 1);
    CHECK_EQ_INT(m.n_textures, 0);
    CHECK_EQ_INT(m.tri_material[0], 0);
    CHECK(strcmp(m.materials[0].name, "default") == 0);
    CHECK_VEC3(m.materials[0].kd, 1, 1, 1);
    CHECK_VEC3(m.materials[0].ks, 0.5, 0.5, 0.5);
    CHECK_NEAR(m.materials[0].ns, 32, 0);
    CHECK_EQ_INT(m.materials[0].texture, -1);
    mesh_free(&m);
}

TEST(materials_resolved_from_libraries)
{
    if (!have_fixtures(t))
        return;
    struct mesh m;
    struct err e;
    if (obj_load(DATA "materials.obj", &m, &e)) {
        test_fail(t, __FILE__, __LINE__, "%s", e.msg);
        return;
    }
    /* default, then used materials in first-use order; no_such_material -> default;
     * unused_missing's missing texture is never opened */
    static const char *names[] = {"default", "red", "checker", "checker_again", "grey",
                                  "blue"};
    REQUIRE(m.n_materials == 6);
    for (int i = 0; i < 6; i++)
        CHECK(strcmp(m.materials[i].name, names[i]) == 0);
    static const int tri_mat[7] = {0, 1, 2, 3, 4, 0, 5};
    REQUIRE(m.n_tris == 7);
    for (int i = 0; i < 7; i++)
        CHECK_EQ_INT(m.tri_material[i], tri_mat[i]);
    /* vertices split by material: 3+3+3+3+3, then tri 5 reuses two default corners, +3 */
    CHECK_EQ_INT(m.n_verts, 19);
    /* "red" is defined twice: the first definition wins */
    CHECK_VEC3(m.materials[1].kd, 1, 0, 0);
    CHECK_VEC3(m.materials[1].ks, 0.25, 0.25, 0.25);
    CHECK_NEAR(m.materials[1].ns, 10, 0);
    CHECK_EQ_INT(m.materials[1].texture, -1);
    CHECK_VEC3(m.materials[3].kd, 0.5, 1, 1);
    CHECK_VEC3(m.materials[5].kd, 0, 0, 1); /* from extra.mtl (CRLF) */
    /* one image shared by two materials, loaded once; the spaced name after options */
    CHECK_EQ_INT(m.n_textures, 2);
    CHECK_EQ_INT(m.materials[2].texture, m.materials[3].texture);
    REQUIRE(m.materials[2].texture >= 0 && m.materials[4].texture >= 0);
    const struct texture *ck = &m.textures[m.materials[2].texture];
    const struct texture *gr = &m.textures[m.materials[4].texture];
    CHECK(ck != gr);
    CHECK_EQ_INT(ck->w, 2);
    CHECK_EQ_INT(ck->h, 2);
    CHECK_EQ_INT(ck->rgba[0], 255); /* top-left red */
    CHECK_EQ_INT(ck->rgba[1], 0);
    CHECK_EQ_INT(ck->rgba[4 * 2 + 2], 255); /* bottom-left blue */
    CHECK_EQ_INT(gr->w, 1);
    CHECK_EQ_INT(gr->rgba[0], 128);
    mesh_free(&m);
}

TEST(vertices_carry_their_material)
{
    if (!have_fixtures(t))
        return;
    struct mesh m;
    struct err e;
    REQUIRE(obj_load(DATA "materials.obj", &m, &e) == 0);
    for (uint32_t i = 0; i < m.n_tris; i++)
        for (int k = 0; k < 3; k++)
            CHECK_EQ_INT(m.vert_material[m.tris[i][k]], m.tri_material[i]);
    mesh_free(&m);
}

/* ---- shared models ---- */

static bool load_model(struct test *t, const char *rel, struct mesh *m)
{
    const char *dir = test_models_dir();
    if (!dir) {
        test_skip(t, "no shared models");
        return false;
    }
    char path[4200];
    struct err e;
    snprintf(path, sizeof path, "%s/%s", dir, rel);
    if (obj_load(path, m, &e)) {
        test_fail(t, __FILE__, __LINE__, "%s", e.msg);
        return false;
    }
    return true;
}

static int find_material(const struct mesh *m, const char *name)
{
    for (uint32_t i = 0; i < m->n_materials; i++)
        if (strcmp(m->materials[i].name, name) == 0)
            return (int)i;
    return -1;
}

/* counts cross-checked against an independent Python reading of the files */
TEST(cornell_box_loads)
{
    struct mesh m;
    if (!load_model(t, "cornell_box/CornellBox-Original.obj", &m))
        return;
    CHECK_EQ_INT(m.n_tris, 36);
    CHECK_EQ_INT(m.n_verts, 64);
    CHECK_EQ_INT(m.n_materials, 9); /* default + 8 */
    CHECK(!m.has_uvs && !m.has_normals);
    int lw = find_material(&m, "leftWall");
    REQUIRE(lw > 0);
    CHECK_VEC3(m.materials[lw].kd, 0.63, 0.065, 0.05); /* "Ka ... # Red" before it */
    CHECK_VEC3(m.materials[lw].ks, 0, 0, 0);
    CHECK_NEAR(m.materials[lw].ns, 10, 0);
    CHECK_VEC3(m.bbox_min, -1.02, 0, -1.04);
    CHECK_VEC3(m.bbox_max, 1, 1.99, 0.99);
    mesh_free(&m);
    if (!load_model(t, "cornell_box/CornellBox-Sphere.obj", &m))
        return;
    CHECK_EQ_INT(m.n_tris, 2188);
    CHECK_EQ_INT(m.n_verts, 1280);
    CHECK(m.has_uvs && m.has_normals);
    mesh_free(&m);
}

TEST(sports_car_loads)
{
    struct mesh m;
    if (!load_model(t, "sports_car/sportsCar.obj", &m))
        return;
    CHECK_EQ_INT(m.n_tris, 300603);
    CHECK_EQ_INT(m.n_verts, 163634);
    CHECK_EQ_INT(m.n_materials, 39);
    CHECK_EQ_INT(m.n_textures, 0);
    CHECK(!m.has_uvs && m.has_normals);
    int rl = find_material(&m, "RearLights"); /* "newmtl  RearLights" in the file */
    REQUIRE(rl > 0);
    CHECK_VEC3(m.materials[rl].kd, 0.7961, 0.0941, 0);
    CHECK_NEAR(m.materials[rl].ns, 100, 0);
    CHECK_NEAR(m.bbox_min[0], -1.14, 0.01);
    CHECK_NEAR(m.bbox_max[2], 2.24, 0.01);
    mesh_free(&m);
}

TEST(holodeck_loads)
{
    struct mesh m;
    if (!load_model(t, "holodeck/holodeck.obj", &m))
        return;
    CHECK_EQ_INT(m.n_tris, 4015);
    CHECK_EQ_INT(m.n_verts, 4269);
    CHECK_EQ_INT(m.n_materials, 8);
    CHECK_EQ_INT(m.n_textures, 1); /* wall.png; screen.png is map_Ke */
    REQUIRE(m.n_textures == 1);
    CHECK_EQ_INT(m.textures[0].w, 512);
    float lo = 0, hi = 0;
    for (uint32_t i = 0; i < m.n_verts; i++) {
        lo = fminf(lo, m.verts[i].uv[0]);
        hi = fmaxf(hi, m.verts[i].uv[0]);
    }
    CHECK(lo < -1 && hi > 2); /* UVs far outside [0,1] survive untouched */
    mesh_free(&m);
}

TEST(lost_empire_loads)
{
    struct mesh m;
    if (!load_model(t, "lost_empire/lost_empire.obj", &m))
        return;
    CHECK_EQ_INT(m.n_tris, 224998);
    CHECK_EQ_INT(m.n_verts, 449992);
    CHECK_EQ_INT(m.n_materials, 46);
    CHECK_EQ_INT(m.n_textures, 3); /* RGB, RGBA and the map_d cut-outs' Alpha */
    CHECK(m.features); /* 14 materials cut out by their map_d */
    CHECK_VEC3(m.bbox_min, -37, 0, -82);
    CHECK_VEC3(m.bbox_max, 38, 49, 83);
    mesh_free(&m);
}

TEST(models_without_normals_get_unit_normals)
{
    struct mesh m;
    if (!load_model(t, "bunny/bunny_res4.obj", &m))
        return;
    CHECK(!m.has_normals);
    CHECK_EQ_INT(m.n_tris, 948);
    for (uint32_t i = 0; i < m.n_verts; i++) {
        const float *n = m.verts[i].nrm;
        CHECK_NEAR(n[0] * n[0] + n[1] * n[1] + n[2] * n[2], 1, 1e-5);
    }
    mesh_free(&m);
}

/* a concave face of 200 corners after smaller faces: the per-face scratch must grow with the
 * face (fuzz_obj found a heap overflow in polygon.c here) */
TEST(large_concave_face_after_small_ones)
{
    size_t cap = 1 << 16, n = 0;
    char *text = malloc(cap);
    REQUIRE(text);
    const int k = 200; /* a star: every other corner pulled in, so the face is concave */
    for (int i = 0; i < k; i++) {
        double r = i % 2 ? 0.5 : 1.0, a = 2 * M_PI * i / k;
        n += (size_t)snprintf(text + n, cap - n, "v %.9f %.9f 0\n", r * cos(a), r * sin(a));
    }
    n += (size_t)snprintf(text + n, cap - n, "f 1 2 3\nf");
    for (int i = 1; i <= k; i++)
        n += (size_t)snprintf(text + n, cap - n, " %d", i);
    n += (size_t)snprintf(text + n, cap - n, "\n");
    struct mesh m;
    struct err e;
    int rc = obj_parse(text, n, "star.obj", &m, &e);
    free(text);
    REQUIRE(rc == 0);
    CHECK_EQ_INT(m.n_tris, 1 + k - 2);
    double sum = 0;
    for (uint32_t i = 1; i < m.n_tris; i++) {
        CHECK(area2(&m, i) >= -1e-9); /* ears keep the winding */
        sum += area2(&m, i) / 2;
    }
    /* star area: k triangles (centre, outer i, inner i+1) of 1 * 0.5 * sin(2 pi / k) / 2 */
    CHECK_NEAR(sum, k * 0.25 * sin(2 * M_PI / k), 1e-5);
    mesh_free(&m);
}

TEST(a_position_with_many_uvs_stays_linear_and_correct)
{
    /* position 1 gets 300 different uvs, then 300 faces that all use its first uv again:
     * vertex sharing may give up after a few comparisons (no quadratic time on such files),
     * but every triangle corner must still carry its own position and uv */
    size_t cap = 64 * 1024, len = 0;
    char *text = malloc(cap);
    REQUIRE(text);
    len += (size_t)snprintf(text + len, cap - len, "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
    for (int i = 0; i < 300; i++)
        len += (size_t)snprintf(text + len, cap - len, "vt %d 0\n", i);
    for (int i = 0; i < 600; i++)
        len += (size_t)snprintf(text + len, cap - len, "f 1/%d 2/1 3/1\n", i < 300 ? i + 1 : 1);
    struct mesh m;
    struct err e = {""};
    REQUIRE(parse(text, &m, &e) == 0);
    free(text);
    CHECK_EQ_INT(m.n_tris, 600);
    CHECK(m.n_verts >= 302 && m.n_verts <= 310); /* 300 + two shared, a few duplicates */
    for (uint32_t tri = 0; tri < m.n_tris; tri++) {
        const struct mesh_vertex *a = corner(&m, tri, 0);
        CHECK(a->pos[0] == 0 && a->pos[1] == 0);
        CHECK_NEAR(a->uv[0], tri < 300 ? (double)tri : 0.0, 0);
    }
    mesh_free(&m);
}
