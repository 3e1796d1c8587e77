/* test_normals.c: generated normals keep sharp edges sharp (mesh.h's creases), for every
 * format, and never change a smooth surface. */
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <unistd.h>

#include "camera.h"
#include "model.h"
#include "scene.h"
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

/* ---- which way is up ---- */

static void bbox_is(struct test *t, const struct mesh *m, const float lo[3], const float hi[3],
                    int line)
{
    for (int k = 0; k < 3; k++)
        if (!(fabsf(m->bbox_min[k] - lo[k]) < 1e-6f && fabsf(m->bbox_max[k] - hi[k]) < 1e-6f))
            test_fail(t, __FILE__, line, "axis %d: [%g, %g], expected [%g, %g]", k,
                      m->bbox_min[k], m->bbox_max[k], lo[k], hi[k]);
}
#define BBOX_IS(m, x0, y0, z0, x1, y1, z1)                                                 \
    bbox_is(t, (m), (const float[3]){x0, y0, z0}, (const float[3]){x1, y1, z1}, __LINE__)

/* one triangle 1 wide (x), 2 deep (y) and 3 tall (z), in each format */
static const char tall_stl[] = "solid t\nfacet normal 0 -1 0\nouter loop\nvertex 0 0 0\n"
                               "vertex 1 0 0\nvertex 0 2 3\nendloop\nendfacet\nendsolid t\n";
static const char tall_obj[] = "v 0 0 0\nv 1 0 0\nv 0 2 3\nf 1 2 3\n";
static const char tall_ply[] = "ply\nformat ascii 1.0\n%s\nelement vertex 3\nproperty float x\n"
                               "property float y\nproperty float z\nelement face 1\n"
                               "property list uchar int vertex_indices\nend_header\n"
                               "0 0 0\n1 0 0\n0 2 3\n3 0 1 2\n";

TEST(stl_is_z_up)
{
    /* the 3D-printing convention: the file's z is drawn up (+Y), its -y toward the viewer */
    struct mesh m;
    struct err e;
    REQUIRE(load_text(tall_stl, "t.stl", NULL, &m, &e) == 0);
    BBOX_IS(&m, 0, 0, -2, 1, 3, 0);
    CHECK(m.file_up == 'z');
    /* its face normal (0, -3, 2) / sqrt 13, toward the viewer and up, is drawn as (0, 2, 3) */
    CHECK_NEAR(m.verts[0].nrm[0], 0, 1e-6);
    CHECK_NEAR(m.verts[0].nrm[1], 2 / sqrt(13), 1e-6);
    CHECK_NEAR(m.verts[0].nrm[2], 3 / sqrt(13), 1e-6);
    mesh_free(&m);
    /* --up-axis y: as written */
    struct model_opts o = {.up = MODEL_UP_Y};
    REQUIRE(load_text(tall_stl, "t.stl", &o, &m, &e) == 0);
    BBOX_IS(&m, 0, 0, 0, 1, 2, 3);
    mesh_free(&m);
}

TEST(obj_and_ply_are_y_up_unless_told)
{
    struct mesh m;
    struct err e;
    REQUIRE(load_text(tall_obj, "t.obj", NULL, &m, &e) == 0);
    BBOX_IS(&m, 0, 0, 0, 1, 2, 3);
    mesh_free(&m);
    struct model_opts z = {.up = MODEL_UP_Z}, x = {.up = MODEL_UP_X};
    REQUIRE(load_text(tall_obj, "t.obj", &z, &m, &e) == 0);
    BBOX_IS(&m, 0, 0, -2, 1, 3, 0);
    mesh_free(&m);
    REQUIRE(load_text(tall_obj, "t.obj", &x, &m, &e) == 0); /* (x, y, z) -> (-y, x, z) */
    BBOX_IS(&m, -2, 0, 0, 0, 1, 3);
    mesh_free(&m);
    /* PLY: Y-up, unless a header comment or obj_info names the up axis */
    static const char *const says_z[] = {"comment up_axis Z", "comment Z-up scan",
                                         "obj_info UpAxis=Z", "comment +z up",
                                         "comment zup", "comment Up axis: z"};
    static const char *const says_nothing[] = {"comment made by hand", "comment zebra up",
                                               "comment up to you", "obj_info x y z"};
    char text[512];
    for (size_t i = 0; i < sizeof says_z / sizeof *says_z; i++) {
        snprintf(text, sizeof text, tall_ply, says_z[i]);
        REQUIRE(load_text(text, "t.ply", NULL, &m, &e) == 0);
        BBOX_IS(&m, 0, 0, -2, 1, 3, 0);
        mesh_free(&m);
    }
    for (size_t i = 0; i < sizeof says_nothing / sizeof *says_nothing; i++) {
        snprintf(text, sizeof text, tall_ply, says_nothing[i]);
        REQUIRE(load_text(text, "t.ply", NULL, &m, &e) == 0);
        BBOX_IS(&m, 0, 0, 0, 1, 2, 3);
        mesh_free(&m);
    }
    /* --up-axis wins over the header */
    struct model_opts y = {.up = MODEL_UP_Y};
    snprintf(text, sizeof text, tall_ply, says_z[0]);
    REQUIRE(load_text(text, "t.ply", &y, &m, &e) == 0);
    BBOX_IS(&m, 0, 0, 0, 1, 2, 3);
    mesh_free(&m);
}

TEST(collada_and_fbx_follow_their_axis_metadata)
{
    /* COLLADA's up_axis (assimp applies it) and FBX's axis settings (rastty applies them):
     * a Z-up file's z drawn up */
    static const char dae[] =
        "<?xml version=\"1.0\"?>\n<COLLADA xmlns=\"http://www.collada.org/2005/11/"
        "COLLADASchema\" version=\"1.4.1\"><asset><up_axis>Z_UP</up_axis></asset>"
        "<library_geometries><geometry id=\"g\"><mesh><source id=\"p\"><float_array id=\"pa\" "
        "count=\"9\">0 0 0 1 0 0 0 2 3</float_array><technique_common><accessor source=\"#pa\" "
        "count=\"3\" stride=\"3\"><param name=\"X\" type=\"float\"/><param name=\"Y\" "
        "type=\"float\"/><param name=\"Z\" type=\"float\"/></accessor></technique_common>"
        "</source><vertices id=\"v\"><input semantic=\"POSITION\" source=\"#p\"/></vertices>"
        "<triangles count=\"1\"><input semantic=\"VERTEX\" source=\"#v\" offset=\"0\"/><p>0 1 2"
        "</p></triangles></mesh></geometry></library_geometries><library_visual_scenes>"
        "<visual_scene id=\"s\"><node id=\"n\"><instance_geometry url=\"#g\"/></node>"
        "</visual_scene></library_visual_scenes><scene><instance_visual_scene url=\"#s\"/>"
        "</scene></COLLADA>\n";
    static const char fbx[] =
        "; FBX 7.4.0 project file\nFBXHeaderExtension:  {\n\tFBXHeaderVersion: 1003\n"
        "\tFBXVersion: 7400\n}\nGlobalSettings:  {\n\tVersion: 1000\n\tProperties70:  {\n"
        "\t\tP: \"UpAxis\", \"int\", \"Integer\", \"\",2\n"
        "\t\tP: \"UpAxisSign\", \"int\", \"Integer\", \"\",1\n"
        "\t\tP: \"FrontAxis\", \"int\", \"Integer\", \"\",1\n"
        "\t\tP: \"FrontAxisSign\", \"int\", \"Integer\", \"\",-1\n"
        "\t\tP: \"CoordAxis\", \"int\", \"Integer\", \"\",0\n"
        "\t\tP: \"CoordAxisSign\", \"int\", \"Integer\", \"\",1\n\t}\n}\nObjects:  {\n"
        "\tGeometry: 100, \"Geometry::tri\", \"Mesh\" {\n\t\tVertices: *9 {\n"
        "\t\t\ta: 0,0,0,1,0,0,0,2,3\n\t\t}\n\t\tPolygonVertexIndex: *3 {\n\t\t\ta: 0,1,-3\n"
        "\t\t}\n\t}\n\tModel: 200, \"Model::tri\", \"Mesh\" {\n\t\tVersion: 232\n\t}\n}\n"
        "Connections:  {\n\tC: \"OO\",100,200\n\tC: \"OO\",200,0\n}\n";
    struct mesh m;
    struct err e;
    REQUIRE(load_text(dae, NULL, NULL, &m, &e) == 0);
    BBOX_IS(&m, 0, 0, -2, 1, 3, 0);
    mesh_free(&m);
    if (load_text(fbx, NULL, NULL, &m, &e)) {
        test_fail(t, __FILE__, __LINE__, "%s", e.msg);
        return;
    }
    BBOX_IS(&m, 0, 0, -2, 1, 3, 0);
    mesh_free(&m);
}

TEST(scene_turn_up_cycles_the_axes_about_the_centre)
{
    /* the tall triangle as OBJ (Y-up as read): u draws its z up, then its x, then its y again */
    char path[64];
    snprintf(path, sizeof path, "/tmp/rastty-up-%d.obj", (int)getpid());
    FILE *f = fopen(path, "w");
    REQUIRE(f);
    fputs(tall_obj, f);
    fclose(f);
    struct scene s;
    struct err e;
    REQUIRE(scene_load(path, &s, &e) == 0);
    unlink(path);
    CHECK(s.up == 'y');
    vec3 c0 = v3_scale(v3_add(s.bound_lo, s.bound_hi), 0.5);
    const char want[3] = {'z', 'x', 'y'};
    /* extents (x, y, z) after each turn: z up is (1, 3, 2), x up (2, 1, 3), y up (1, 2, 3) */
    const double ext[3][3] = {{1, 3, 2}, {2, 1, 3}, {1, 2, 3}};
    for (int i = 0; i < 3; i++) {
        CHECK_EQ_INT(scene_turn_up(&s), want[i]);
        vec3 d = v3_sub(s.bound_hi, s.bound_lo), c = v3_scale(v3_add(s.bound_lo, s.bound_hi), 0.5);
        CHECK_NEAR(d.x, ext[i][0], 1e-9);
        CHECK_NEAR(d.y, ext[i][1], 1e-9);
        CHECK_NEAR(d.z, ext[i][2], 1e-9);
        CHECK_NEAR(v3_len(v3_sub(c, c0)), 0, 1e-9); /* about the centre: still framed */
    }
    scene_free(&s);
}

TEST(a_flat_model_is_never_framed_edge_on)
{
    /* a floor (thin in y) seen from the default direction (+z): a 3/4 view from above */
    vec3 back = camera_flat_view(v3(0, 0, 1), v3(-1, -0.01, -1), v3(1, 0.01, 1));
    CHECK_NEAR(back.x, 0, 1e-12);
    CHECK_NEAR(back.y, sqrt(0.5), 1e-12);
    CHECK_NEAR(back.z, sqrt(0.5), 1e-12);
    /* a wall facing the camera, and a box: the view direction kept */
    vec3 same = camera_flat_view(v3(0, 0, 1), v3(-1, -1, 0), v3(1, 1, 0));
    CHECK(same.x == 0 && same.y == 0 && same.z == 1);
    same = camera_flat_view(v3(0.6, 0, 0.8), v3(-1, -1, -1), v3(1, 1, 1));
    CHECK(same.x == 0.6 && same.z == 0.8);
    /* the STL square (the file's xy plane, drawn as a floor) framed: it shows */
    struct camera cam;
    camera_default(&cam);
    camera_frame_box(&cam, v3(0, 0, -1), v3(1, 0, 0), 160.0 / 96);
    vec3 dir = v3_norm(v3_sub(cam.eye, cam.target));
    CHECK(dir.y > 0.7);
}
TEST(gltf_without_normals_is_flat)
{
    /* glTF 2.0: "When normals are not specified, client implementations MUST calculate flat
     * normals": two triangles folded by 20 degrees, sharing an edge */
    static const char gltf[] =
        "{\"asset\":{\"version\":\"2.0\"},\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0}],"
        "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1}]}],"
        "\"buffers\":[{\"byteLength\":60,\"uri\":\"data:application/octet-stream;base64,"
        /* (0,0,0) (1,0,0) (0,1,0) (1,1,0.36397) ; indices 0 1 2, 2 1 3 */
        "AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAACAPwAAgD9HWro+AAABAAIAAgABAAMA\"}],"
        "\"bufferViews\":[{\"buffer\":0,\"byteLength\":48},{\"buffer\":0,\"byteOffset\":48,"
        "\"byteLength\":12}],"
        "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":4,\"type\":\"VEC3\","
        "\"min\":[0,0,0],\"max\":[1,1,0.36397]},{\"bufferView\":1,\"componentType\":5123,"
        "\"count\":6,\"type\":\"SCALAR\"}]}";
    struct mesh m;
    struct err e;
    REQUIRE(load_text(gltf, NULL, NULL, &m, &e) == 0);
    CHECK_EQ_INT(m.n_tris, 2);
    CHECK_EQ_INT(corners_flat(&m), 0);
    mesh_free(&m);
}

TEST(assimp_formats_name_what_they_do_not_draw)
{
    /* a COLLADA file with a camera and a light beside its triangle: drawn, and each thing
     * rastty does not draw is a warning naming it (they were dropped silently) */
    static const char dae[] =
        "<?xml version=\"1.0\"?>\n<COLLADA xmlns=\"http://www.collada.org/2005/11/"
        "COLLADASchema\" version=\"1.4.1\"><asset><up_axis>Y_UP</up_axis></asset>"
        "<library_cameras><camera id=\"c\"><optics><technique_common><perspective><yfov>45"
        "</yfov><znear>0.1</znear><zfar>100</zfar></perspective></technique_common></optics>"
        "</camera></library_cameras><library_lights><light id=\"l\"><technique_common>"
        "<point><color>1 1 1</color></point></technique_common></light></library_lights>"
        "<library_geometries><geometry id=\"g\"><mesh><source id=\"p\"><float_array id=\"pa\" "
        "count=\"9\">0 0 0 1 0 0 0 2 3</float_array><technique_common><accessor source=\"#pa\" "
        "count=\"3\" stride=\"3\"><param name=\"X\" type=\"float\"/><param name=\"Y\" "
        "type=\"float\"/><param name=\"Z\" type=\"float\"/></accessor></technique_common>"
        "</source><vertices id=\"v\"><input semantic=\"POSITION\" source=\"#p\"/></vertices>"
        "<triangles count=\"1\"><input semantic=\"VERTEX\" source=\"#v\" offset=\"0\"/><p>0 1 2"
        "</p></triangles></mesh></geometry></library_geometries><library_visual_scenes>"
        "<visual_scene id=\"s\"><node id=\"n\"><instance_geometry url=\"#g\"/></node>"
        "<node id=\"cn\"><instance_camera url=\"#c\"/></node><node id=\"ln\">"
        "<instance_light url=\"#l\"/></node></visual_scene></library_visual_scenes><scene>"
        "<instance_visual_scene url=\"#s\"/></scene></COLLADA>\n";
    struct mesh m;
    struct err e;
    struct warnings w = {0};
    struct model_ctx ctx = {.path = "cam.dae", .warn = &w};
    REQUIRE(model_parse(dae, strlen(dae), &ctx, &m, &e) == 0);
    CHECK_EQ_INT(m.n_tris, 1);
    bool cam = false, light = false;
    for (int i = 0; i < w.n; i++) {
        cam |= strstr(w.msg[i], "cam.dae: 1 cameras are ignored") != NULL;
        light |= strstr(w.msg[i], "cam.dae: 1 lights are ignored") != NULL;
    }
    CHECK(cam && light);
    mesh_free(&m);
}

TEST(random_bytes_named_ase_are_an_error_naming_the_file)
{
    /* assimp's ASE reader takes any bytes and gives 8 triangles at the origin: a blank
     * picture with exit 0 before; now an error naming the file */
    static char junk[3000];
    uint32_t x = 12345;
    for (size_t i = 0; i < sizeof junk; i++) {
        x = x * 1103515245u + 12345u;
        junk[i] = (char)(x >> 24);
    }
    struct mesh m;
    struct err e;
    struct model_ctx ctx = {.path = "r.ase"};
    CHECK_EQ_INT(model_parse(junk, sizeof junk, &ctx, &m, &e), -1);
    CHECK_STR_CONTAINS(e.msg, "r.ase");
    CHECK_STR_CONTAINS(e.msg, "no triangles");
}

/* A COLLADA file with a node and no geometry: assimp built 8 triangles of a stand-in
 * skeleton and the message spoke of them ('none of its 8 triangles has an area'); it has
 * no triangles, and says so */
TEST(a_model_without_surfaces_says_no_triangles)
{
    static const char dae[] =
        "<?xml version=\"1.0\"?>\n<COLLADA xmlns=\"http://www.collada.org/2005/11/"
        "COLLADASchema\" version=\"1.4.1\"><asset><up_axis>Y_UP</up_axis></asset>"
        "<library_visual_scenes><visual_scene id=\"s\"><node id=\"n\"/></visual_scene>"
        "</library_visual_scenes><scene><instance_visual_scene url=\"#s\"/></scene>"
        "</COLLADA>\n";
    struct mesh m;
    struct err e;
    struct model_ctx ctx = {.path = "empty.dae"};
    CHECK_EQ_INT(model_parse(dae, sizeof dae - 1, &ctx, &m, &e), -1);
    CHECK(strcmp(e.msg, "empty.dae: no triangles (the file has no surfaces rastty can draw)") ==
          0);
}
