/* test_normals.c: generated normals keep sharp edges sharp (mesh.h's creases), for every
 * format, and never change a smooth surface. */
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "model.h"
#include "test.h"

static int load_text(const char *text, const char *path, const struct model_opts *o,
                     struct mesh *m, struct err *e)
{
    struct model_ctx ctx = {.path = path, .opts = o};
    return model_parse(text, strlen(text), &ctx, m, e);
}

/* the unit cube's 12 triangles, outward, as corner positions */
static const float cube_tri[12][3][3] = {
    {{0, 0, 0}, {0, 1, 0}, {1, 1, 0}}, {{0, 0, 0}, {1, 1, 0}, {1, 0, 0}}, /* z = 0 */
    {{0, 0, 1}, {1, 0, 1}, {1, 1, 1}}, {{0, 0, 1}, {1, 1, 1}, {0, 1, 1}}, /* z = 1 */
    {{0, 0, 0}, {1, 0, 0}, {1, 0, 1}}, {{0, 0, 0}, {1, 0, 1}, {0, 0, 1}}, /* y = 0 */
    {{0, 1, 0}, {0, 1, 1}, {1, 1, 1}}, {{0, 1, 0}, {1, 1, 1}, {1, 1, 0}}, /* y = 1 */
    {{0, 0, 0}, {0, 0, 1}, {0, 1, 1}}, {{0, 0, 0}, {0, 1, 1}, {0, 1, 0}}, /* x = 0 */
    {{1, 0, 0}, {1, 1, 0}, {1, 1, 1}}, {{1, 0, 0}, {1, 1, 1}, {1, 0, 1}}, /* x = 1 */
};

/* the cube as ASCII STL (facet normals zero: the winding decides) */
static char *cube_stl(void)
{
    size_t cap = 8192, n = 0;
    char *s = malloc(cap);
    n += (size_t)snprintf(s + n, cap - n, "solid cube\n");
    for (int t = 0; t < 12; t++) {
        n += (size_t)snprintf(s + n, cap - n, "facet normal 0 0 0\nouter loop\n");
        for (int k = 0; k < 3; k++)
            n += (size_t)snprintf(s + n, cap - n, "vertex %g %g %g\n", cube_tri[t][k][0],
                                  cube_tri[t][k][1], cube_tri[t][k][2]);
        n += (size_t)snprintf(s + n, cap - n, "endloop\nendfacet\n");
    }
    snprintf(s + n, cap - n, "endsolid cube\n");
    return s;
}

/* the cube as OBJ without normals: 8 shared positions */
static char *cube_obj(void)
{
    size_t cap = 4096, n = 0;
    char *s = malloc(cap);
    for (int i = 0; i < 8; i++)
        n += (size_t)snprintf(s + n, cap - n, "v %d %d %d\n", i & 1, (i >> 1) & 1, (i >> 2) & 1);
    for (int t = 0; t < 12; t++) {
        n += (size_t)snprintf(s + n, cap - n, "f");
        for (int k = 0; k < 3; k++) {
            const float *p = cube_tri[t][k];
            n += (size_t)snprintf(s + n, cap - n, " %d",
                                  1 + (int)p[0] + 2 * (int)p[1] + 4 * (int)p[2]);
        }
        n += (size_t)snprintf(s + n, cap - n, "\n");
    }
    return s;
}

/* every corner's normal is its face's: flat faces, sharp edges */
static int corners_flat(const struct mesh *m)
{
    int bad = 0;
    for (uint32_t t = 0; t < m->n_tris; t++) {
        const float *a = m->verts[m->tris[t][0]].pos, *b = m->verts[m->tris[t][1]].pos,
                    *c = m->verts[m->tris[t][2]].pos;
        double u[3], v[3], f[3];
        for (int k = 0; k < 3; k++)
            u[k] = b[k] - a[k], v[k] = c[k] - a[k];
        f[0] = u[1] * v[2] - u[2] * v[1], f[1] = u[2] * v[0] - u[0] * v[2],
        f[2] = u[0] * v[1] - u[1] * v[0];
        double l = sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
        for (int k = 0; k < 3; k++) {
            const float *n = m->verts[m->tris[t][k]].nrm;
            double d = (n[0] * f[0] + n[1] * f[1] + n[2] * f[2]) / l;
            bad += !(d > 0.99999);
        }
    }
    return bad;
}

TEST(stl_facets_stay_flat)
{
    /* a cube as STL: welded positions, but every corner keeps its face's normal (the old
     * smooth normals turned every face into a pillow) */
    char *stl = cube_stl();
    struct mesh m;
    struct err e;
    REQUIRE(load_text(stl, "cube.stl", NULL, &m, &e) == 0);
    CHECK_EQ_INT(m.n_tris, 12);
    CHECK_EQ_INT(m.n_verts, 24); /* each corner of the cube: three faces, three vertices */
    CHECK_EQ_INT(corners_flat(&m), 0);
    mesh_free(&m);
    /* --crease 180: one smooth normal per position again */
    struct model_opts smooth = {.crease_set = true, .crease_deg = 180};
    REQUIRE(load_text(stl, "cube.stl", &smooth, &m, &e) == 0);
    CHECK_EQ_INT(m.n_verts, 8);
    CHECK(corners_flat(&m) > 0);
    mesh_free(&m);
    free(stl);
}

TEST(obj_keeps_smooth_normals_unless_creased)
{
    /* OBJ without normals: the conventions' smooth normal per position by default (the Mesa
     * oracle's contract); --crease splits it like any other format */
    char *obj = cube_obj();
    struct mesh m;
    struct err e;
    REQUIRE(load_text(obj, "cube.obj", NULL, &m, &e) == 0);
    CHECK_EQ_INT(m.n_verts, 8);
    mesh_free(&m);
    struct model_opts o = {.crease_set = true, .crease_deg = 30};
    REQUIRE(load_text(obj, "cube.obj", &o, &m, &e) == 0);
    CHECK_EQ_INT(m.n_verts, 24);
    CHECK_EQ_INT(corners_flat(&m), 0);
    mesh_free(&m);
    /* a 90-degree edge is smooth under a crease angle above 90 */
    o.crease_deg = 91;
    REQUIRE(load_text(obj, "cube.obj", &o, &m, &e) == 0);
    CHECK_EQ_INT(m.n_verts, 8);
    mesh_free(&m);
    free(obj);
}

/* an n-sided prism of height 2 as OBJ without normals: positions on three rings (y = 0, 1,
 * 2), the side's quads as two triangles each, and with caps a fan on each end ring;
 * neighbouring side faces turn by 360/n degrees, a cap meets the side at 90 */
static char *prism_obj(int n, bool caps)
{
    size_t cap = 200 * (size_t)n + 256, len = 0;
    char *s = malloc(cap);
    for (int r = 0; r < 3; r++)
        for (int i = 0; i < n; i++) {
            double a = 2 * M_PI * i / n;
            len += (size_t)snprintf(s + len, cap - len, "v %.9f %d %.9f\n", cos(a), r, sin(a));
        }
    for (int r = 0; r < 2; r++)
        for (int i = 0; i < n; i++) {
            int a = r * n + i + 1, b = r * n + (i + 1) % n + 1;
            len += (size_t)snprintf(s + len, cap - len, "f %d %d %d\nf %d %d %d\n", a, a + n,
                                    b + n, a, b + n, b);
        }
    for (int i = 1; caps && i + 1 < n; i++)
        len += (size_t)snprintf(s + len, cap - len, "f 1 %d %d\nf %d %d %d\n", i + 1, i + 2,
                                2 * n + 1, 2 * n + i + 2, 2 * n + i + 1);
    return s;
}

TEST(crease_angle_decides_which_edges_stay_sharp)
{
    char *obj = prism_obj(8, false); /* 45 degrees between neighbouring faces */
    struct mesh m;
    struct err e;
    struct model_opts o = {.crease_set = true, .crease_deg = 40};
    REQUIRE(load_text(obj, "p.obj", &o, &m, &e) == 0);
    CHECK_EQ_INT(m.n_verts, 48); /* every position split in two */
    CHECK_EQ_INT(corners_flat(&m), 0);
    mesh_free(&m);
    o.crease_deg = 50;
    REQUIRE(load_text(obj, "p.obj", &o, &m, &e) == 0);
    CHECK_EQ_INT(m.n_verts, 24);
    /* smooth: the normals of one smooth sum per position */
    struct mesh s;
    o.crease_deg = 180;
    REQUIRE(load_text(obj, "p.obj", &o, &s, &e) == 0);
    REQUIRE(s.n_verts == m.n_verts);
    CHECK(memcmp(s.verts, m.verts, m.n_verts * sizeof *m.verts) == 0);
    mesh_free(&s);
    mesh_free(&m);
    free(obj);
}

TEST(uncreased_positions_keep_the_smooth_normals_bits)
{
    /* without caps nothing is creased: the same vertices, in the same order, to the bit, as
     * one smooth sum per position */
    char *obj = prism_obj(64, false);
    struct mesh a, b;
    struct err e;
    struct model_opts smooth = {.crease_set = true, .crease_deg = 180};
    struct model_opts creased = {.crease_set = true, .crease_deg = 30};
    REQUIRE(load_text(obj, "p.obj", &smooth, &a, &e) == 0);
    REQUIRE(load_text(obj, "p.obj", &creased, &b, &e) == 0);
    REQUIRE(a.n_verts == b.n_verts);
    CHECK(memcmp(a.verts, b.verts, a.n_verts * sizeof *a.verts) == 0);
    mesh_free(&a);
    mesh_free(&b);
    free(obj);
    /* with caps the end rings split (side and cap apart); the middle ring sees no crease and
     * keeps the smooth sum's bits */
    obj = prism_obj(64, true);
    REQUIRE(load_text(obj, "p.obj", &smooth, &a, &e) == 0);
    REQUIRE(load_text(obj, "p.obj", &creased, &b, &e) == 0);
    CHECK_EQ_INT(a.n_verts, 3 * 64);
    CHECK_EQ_INT(b.n_verts, 5 * 64);
    int middle = 0;
    for (uint32_t i = 0; i < a.n_verts; i++) {
        if (a.verts[i].pos[1] != 1)
            continue;
        for (uint32_t j = 0; j < b.n_verts; j++)
            if (memcmp(b.verts[j].pos, a.verts[i].pos, sizeof a.verts[i].pos) == 0) {
                CHECK(memcmp(b.verts[j].nrm, a.verts[i].nrm, sizeof a.verts[i].nrm) == 0);
                middle++;
            }
    }
    CHECK_EQ_INT(middle, 64);
    mesh_free(&a);
    mesh_free(&b);
    free(obj);
}
