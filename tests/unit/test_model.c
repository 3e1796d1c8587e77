/* test_model.c: format detection and the STL, PLY and assimp (glTF) loaders. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "model.h"
#include "pipeline.h"
#include "test.h"

static int parse_as(const char *text, size_t len, const char *path, struct mesh *m,
                    struct warnings *w, struct err *e)
{
    struct model_ctx ctx = {.path = path, .warn = w};
    if (w)
        memset(w, 0, sizeof *w);
    return model_parse(text, len, &ctx, m, e);
}

static int parse(const char *text, const char *path, struct mesh *m, struct err *e)
{
    return parse_as(text, strlen(text), path, m, NULL, e);
}

static void check_vec3(struct test *t, const float *got, double x, double y, double z,
                       double tol, int line)
{
    if (!(fabs(got[0] - x) <= tol && fabs(got[1] - y) <= tol && fabs(got[2] - z) <= tol))
        test_fail(t, __FILE__, line, "(%.9g, %.9g, %.9g) != (%.9g, %.9g, %.9g)", got[0], got[1],
                  got[2], x, y, z);
}
#define CHECK_VEC3(got, x, y, z) check_vec3(t, (got), (x), (y), (z), 1e-5, __LINE__)
#define CORNER(m, i, k) (&(m).verts[(m).tris[i][k]])

TEST(detect_by_content_then_name)
{
    static const struct {
        const char *bytes;
        size_t n;
        const char *path;
        int fmt; /* -1: error */
        const char *msg;
    } cases[] = {
        {"\x89PNG\r\n\x1a\n....", 12, "posx.obj", -1, "posx.obj: not a model (PNG image)"},
        {"\xff\xd8\xff\xe0....", 8, "posx.jpg", -1, "posx.jpg: not a model (JPEG image)"},
        {"\x1f\x8b\x08\x00", 4, "m.obj", -1,
         "m.obj: not a model (gzip-compressed data: decompress it first)"},
        {"PK\x03\x04", 4, "m.zip", -1, "m.zip: not a model (ZIP archive: extract it first)"},
        {"\xff\xfev\0", 4, "m.obj", -1, "m.obj: UTF-16 text (save the file as UTF-8 or ASCII)"},
        {"ply\nformat ascii 1.0\n", 20, "m.obj", MODEL_PLY, NULL},
        {"glTF\x02\0\0\0", 8, "m.bin", MODEL_GLTF, NULL},
        {" {\"asset\": {\"version\": \"2.0\"}}", 31, "m.json", MODEL_GLTF, NULL},
        {"solid x\n facet normal 0 0 1\n", 28, "m.txt", MODEL_STL, NULL},
        {"solid cube\nv 0 0 0\n", 19, "solid.obj", MODEL_OBJ, NULL}, /* "solid" alone */
        {"v 0 0 0\n", 8, "m.stl", MODEL_STL, NULL},
        {"v 0 0 0\n", 8, "m.gltf", MODEL_GLTF, NULL},
        {"v 0 0 0\n", 8, "m.dat", MODEL_OBJ, NULL},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        enum model_format f = MODEL_FORMAT_COUNT;
        struct err e = {{0}};
        int rc = model_detect(cases[i].bytes, cases[i].n, cases[i].path, &f, &e);
        if (cases[i].fmt < 0) {
            CHECK_EQ_INT(rc, -1);
            if (strcmp(e.msg, cases[i].msg) != 0)
                test_fail(t, __FILE__, __LINE__, "case %zu: \"%s\"", i, e.msg);
        } else if (rc != 0 || (int)f != cases[i].fmt) {
            test_fail(t, __FILE__, __LINE__, "case %zu: rc %d format %d, want %d", i, rc,
                      (int)f, cases[i].fmt);
        }
    }
    /* a binary STL whose header starts with "solid" (many exporters write that) */
    char bin[84 + 50] = "solid exported by a CAD program";
    bin[80] = 1;
    enum model_format f;
    struct err e;
    CHECK(model_detect(bin, sizeof bin, "part.stl", &f, &e) == 0 && f == MODEL_STL);
}

/* ---- STL ---- */

static const char ascii_square[] =
    "solid square\n"
    "  facet normal 0 0 1\n    outer loop\n"
    "      vertex 0 0 0\n      vertex 1 0 0\n      vertex 1 1 0\n"
    "    endloop\n  endfacet\n"
    /* wound clockwise, but its normal says +z: turned around */
    "  facet normal 0 0 1\n    outer loop\n"
    "      vertex 0 0 0\n      vertex 0 1 0\n      vertex 1 1 0\n"
    "    endloop\n  endfacet\n"
    "endsolid square\n";

TEST(stl_ascii_welds_and_follows_facet_normals)
{
    struct mesh m;
    struct err e;
    REQUIRE(parse(ascii_square, "sq.stl", &m, &e) == 0);
    CHECK_EQ_INT(m.n_tris, 2);
    CHECK_EQ_INT(m.n_verts, 4); /* (0,0,0) and (1,1,0) shared */
    CHECK(!m.has_uvs && !m.has_normals);
    for (uint32_t i = 0; i < 2; i++) { /* STL is Z-up: the file's +z is drawn as +y */
        const float *a = CORNER(m, i, 0)->pos, *b = CORNER(m, i, 1)->pos, *c = CORNER(m, i, 2)->pos;
        double y = (double)(b[2] - a[2]) * (c[0] - a[0]) - (double)(b[0] - a[0]) * (c[2] - a[2]);
        CHECK(y > 0); /* counter-clockwise seen from the file's +z, as the normals say */
        CHECK_VEC3(CORNER(m, i, 0)->nrm, 0, 1, 0);
        CHECK(a[1] == 0 && b[1] == 0 && c[1] == 0);
    }
    CHECK_EQ_INT(m.n_materials, 1);
    mesh_free(&m);
}

static void put_f32(unsigned char *p, float f)
{
    uint32_t u;
    memcpy(&u, &f, 4);
    for (int k = 0; k < 4; k++)
        p[k] = (unsigned char)(u >> (8 * k));
}

TEST(stl_binary_and_its_errors)
{
    unsigned char bin[84 + 100] = {0};
    bin[80] = 2;
    const float v[2][3][3] = {{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}}, {{0, 0, 0}, {1, 1, 0}, {0, 1, 0}}};
    for (int i = 0; i < 2; i++)
        for (int c = 0; c < 3; c++)
            for (int k = 0; k < 3; k++)
                put_f32(bin + 84 + 50 * i + 12 + 12 * c + 4 * k, v[i][c][k]);
    struct mesh m;
    struct err e;
    REQUIRE(parse_as((const char *)bin, sizeof bin, "b.stl", &m, NULL, &e) == 0);
    CHECK_EQ_INT(m.n_tris, 2);
    CHECK_EQ_INT(m.n_verts, 4);
    mesh_free(&m);
    /* truncated: the count says 2, the file holds one and a half */
    CHECK_EQ_INT(parse_as((const char *)bin, sizeof bin - 25, "b.stl", &m, NULL, &e), -1);
    CHECK(strcmp(e.msg, "b.stl: byte 80: binary STL says 2 triangles, which take 184 bytes, "
                        "but the file has 159") == 0);
    /* a coordinate that is not a number */
    put_f32(bin + 84 + 50 + 12 + 12 + 4, NAN);
    CHECK_EQ_INT(parse_as((const char *)bin, sizeof bin, "b.stl", &m, NULL, &e), -1);
    CHECK(strcmp(e.msg, "b.stl: byte 162: triangle 1: coordinate is not a finite number") == 0);
    /* ASCII errors name the line */
    CHECK_EQ_INT(parse("solid a\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 x 0\n",
                       "a.stl", &m, &e), -1);
    CHECK(strcmp(e.msg, "a.stl:5: bad number 'x'") == 0);
    CHECK_EQ_INT(parse("solid a\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nendloop\n", "a.stl",
                       &m, &e), -1);
    CHECK(strcmp(e.msg, "a.stl:5: expected 'vertex', got 'endloop'") == 0);
    CHECK_EQ_INT(parse("solid a\nendsolid a\n", "a.stl", &m, &e), -1);
    CHECK(strcmp(e.msg, "a.stl: no triangles") == 0);
}

/* ---- PLY ---- */

static const char ply_ascii[] =
    "ply\nformat ascii 1.0\ncomment a quad and a triangle\n"
    "element vertex 5\nproperty float x\nproperty float y\nproperty float z\n"
    "property float u\nproperty float v\n"
    "property uchar red\nproperty uchar green\nproperty uchar blue\n"
    "element face 2\nproperty list uchar int vertex_indices\n"
    "element edge 1\nproperty int vertex1\nproperty int vertex2\n"
    "end_header\n"
    "0 0 0 0 0 255 0 0\n1 0 0 1 0 0 255 0\n1 1 0 1 1 0 0 255\n0 1 0 0 1 10 20 30\n"
    "2 2 0 0.5 0.5 1 2 3\n"
    "4 0 1 2 3\n3 1 4 2\n"
    "0 1\n";

TEST(ply_ascii_with_colours_uvs_and_quads)
{
    struct mesh m;
    struct err e;
    REQUIRE(parse(ply_ascii, "q.ply", &m, &e) == 0);
    CHECK_EQ_INT(m.n_tris, 3);
    CHECK_EQ_INT(m.n_verts, 5);
    CHECK(m.has_uvs);
    REQUIRE(m.colors != NULL);
    /* corner 0 of the quad's fan is vertex 0: red, uv (0,0) */
    CHECK_VEC3(CORNER(m, 0, 0)->pos, 0, 0, 0);
    CHECK_EQ_INT(m.colors[m.tris[0][0]][0], 255);
    CHECK_EQ_INT(m.colors[m.tris[0][1]][1], 255);
    CHECK_EQ_INT(m.colors[m.tris[0][2]][2], 255);
    CHECK_VEC3(CORNER(m, 1, 2)->pos, 0, 1, 0);
    CHECK_EQ_INT(m.colors[m.tris[1][2]][2], 30);
    CHECK_VEC3(CORNER(m, 2, 1)->pos, 2, 2, 0);
    CHECK_NEAR(CORNER(m, 2, 1)->uv[0], 0.5, 0);
    mesh_free(&m);
}

/* the same mesh in binary, both byte orders, equals the ASCII one */
static size_t ply_binary(char *out, int big)
{
    size_t n = (size_t)sprintf(out, "ply\nformat binary_%s_endian 1.0\n"
                                    "element vertex 4\nproperty float x\nproperty float y\n"
                                    "property float z\nproperty float nx\nproperty float ny\n"
                                    "property float nz\n"
                                    "element face 1\nproperty list uchar uint vertex_index\n"
                                    "end_header\n",
                               big ? "big" : "little");
    const float vals[4][6] = {{0, 0, 0, 0, 0, 1}, {1, 0, 0, 0, 0, 1}, {1, 1, 0, 0, 0, 1},
                              {0, 1, 0, 0, 0, 1}};
    for (int i = 0; i < 4; i++)
        for (int k = 0; k < 6; k++) {
            uint32_t u;
            memcpy(&u, &vals[i][k], 4);
            for (int b = 0; b < 4; b++)
                out[n++] = (char)(u >> (8 * (big ? 3 - b : b)));
        }
    out[n++] = 4;
    for (uint32_t i = 0; i < 4; i++)
        for (int b = 0; b < 4; b++)
            out[n++] = (char)(i >> (8 * (big ? 3 - b : b)));
    return n;
}

TEST(ply_binary_both_endians)
{
    for (int big = 0; big < 2; big++) {
        char buf[1024];
        size_t n = ply_binary(buf, big);
        struct mesh m;
        struct err e;
        if (parse_as(buf, n, "b.ply", &m, NULL, &e)) {
            test_fail(t, __FILE__, __LINE__, "%s", e.msg);
            continue;
        }
        CHECK_EQ_INT(m.n_tris, 2);
        CHECK(m.has_normals);
        CHECK(m.colors == NULL);
        CHECK_VEC3(CORNER(m, 0, 1)->pos, 1, 0, 0);
        CHECK_VEC3(CORNER(m, 1, 2)->pos, 0, 1, 0);
        CHECK_VEC3(CORNER(m, 1, 2)->nrm, 0, 0, 1);
        mesh_free(&m);
        /* cut inside the faces: the byte offset is named */
        CHECK_EQ_INT(parse_as(buf, n - 3, "b.ply", &m, NULL, &e), -1);
        CHECK_STR_CONTAINS(e.msg, "b.ply: byte ");
    }
}

TEST(ply_errors)
{
    static const struct {
        const char *text, *msg;
    } cases[] = {
        {"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
         "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
         "0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n",
         "p.ply:13: face 0: vertex index 7 out of range (3 vertices)"},
        {"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
         "property float z\nend_header\n0 0 0\n1 x 0\n",
         "p.ply:9: bad number 'x'"},
        {"ply\nformat binary_little_endian 1.0\nelement vertex 1000000000\nproperty float x\n"
         "property float y\nproperty float z\nend_header\n\x01\x02",
         "p.ply: byte 124: the file is too short for 1000000000 'vertex' elements"},
        {"ply\nformat ascii 2.0x\nend_header\n", NULL},
        {"ply\nformat ascii 1.0\nelement vertex 1\nproperty float128 x\nend_header\n",
         "p.ply:4: unknown property type"},
        {"ply\nformat ascii 1.0\nelement vertex 0\n", "p.ply: header has no end_header"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        struct mesh m;
        struct err e = {{0}};
        CHECK_EQ_INT(parse(cases[i].text, "p.ply", &m, &e), -1);
        if (cases[i].msg && strcmp(e.msg, cases[i].msg) != 0)
            test_fail(t, __FILE__, __LINE__, "case %zu: got \"%s\", want \"%s\"", i, e.msg,
                      cases[i].msg);
        for (const char *c = e.msg; *c; c++)
            CHECK(*c >= 0x20 && *c < 0x7f);
    }
}

/* ---- glTF through assimp (in a child process) ---- */

/* one triangle, base64 buffer: positions (0,0,0) (1,0,0) (0,1,0), under a node that moves
 * it by (0, 0, -2) and scales by 2; base colour (1, 0.5, 0.25) */
static const char gltf_tri[] =
    "{\"asset\":{\"version\":\"2.0\"},\"scene\":0,\"scenes\":[{\"nodes\":[0]}],"
    "\"nodes\":[{\"mesh\":0,\"translation\":[0,0,-2],\"scale\":[2,2,2]}],"
    "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"material\":0}]}],"
    "\"materials\":[{\"pbrMetallicRoughness\":{\"baseColorFactor\":[1,0.5,0.25,1]}}],"
    "\"buffers\":[{\"byteLength\":36,\"uri\":\"data:application/octet-stream;base64,"
    "AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA\"}],"
    "\"bufferViews\":[{\"buffer\":0,\"byteLength\":36}],"
    "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\","
    "\"min\":[0,0,0],\"max\":[1,1,0]}]}";

TEST(gltf_node_transform_and_base_colour)
{
    struct mesh m;
    struct err e;
    struct warnings w;
    if (parse_as(gltf_tri, sizeof gltf_tri - 1, NULL, &m, &w, &e)) {
        test_fail(t, __FILE__, __LINE__, "%s", e.msg);
        return;
    }
    CHECK_EQ_INT(m.n_tris, 1);
    CHECK_VEC3(CORNER(m, 0, 0)->pos, 0, 0, -2);
    CHECK_VEC3(CORNER(m, 0, 1)->pos, 2, 0, -2);
    CHECK_VEC3(CORNER(m, 0, 2)->pos, 0, 2, -2);
    CHECK_VEC3(CORNER(m, 0, 0)->nrm, 0, 0, 1); /* generated */
    REQUIRE(m.tri_material[0] < m.n_materials);
    /* glTF's factors are linear: drawn as their display values (sRGB), 0.5 -> 0.7354 */
    CHECK_VEC3(m.materials[m.tri_material[0]].kd, 1, 0.735357, 0.537099);
    mesh_free(&m);
}

TEST(gltf_external_files_follow_the_file_rules)
{
    char dir[64], path[96];
    snprintf(dir, sizeof dir, "/tmp/rastty-gltf-%d", (int)getpid());
    mkdir(dir, 0700);
    snprintf(path, sizeof path, "%s/m.gltf", dir);
    /* a buffer at /dev/zero: refused by file_read, not read forever */
    char *text = malloc(sizeof gltf_tri + 64);
    REQUIRE(text);
    strcpy(text, gltf_tri);
    char *uri = strstr(text, "data:application");
    char *end = strchr(uri, '"');
    memmove(uri + 9, end, strlen(end) + 1);
    memcpy(uri, "/dev/zero", 9);
    FILE *f = fopen(path, "w");
    REQUIRE(f);
    fputs(text, f);
    fclose(f);
    free(text);
    struct mesh m;
    struct err e;
    struct warnings w = {0};
    CHECK_EQ_INT(model_load(path, NULL, &w, &m, &e), -1);
    CHECK_STR_CONTAINS(e.msg, "m.gltf: ");
    for (const char *c = e.msg; *c; c++)
        CHECK(*c >= 0x20 && *c < 0x7f);
    unlink(path);
    rmdir(dir);
    /* from memory: no file may be named at all */
    static const char abs_uri[] = "{\"asset\":{\"version\":\"2.0\"},\"buffers\":[{\"byteLength\":4,"
                                  "\"uri\":\"/etc/passwd\"}]}";
    CHECK_EQ_INT(parse_as(abs_uri, strlen(abs_uri), NULL, &m, NULL, &e), -1);
}

/* a 20-byte GLB whose JSON chunk claims 2 GB: assimp allocated it (2.1 GB, 7 s) */
TEST(glb_lengths_checked_before_assimp)
{
    static const char bomb[] = "glTF\x02\0\0\0\x14\0\0\0\xf0\xff\xff\x7fJSON";
    struct mesh m;
    struct err e;
    CHECK_EQ_INT(parse_as(bomb, 20, NULL, &m, NULL, &e), -1);
    CHECK(strcmp(e.msg, "<memory>: byte 12: GLB chunk of 2147483632 bytes, 0 left in the "
                        "file") == 0);
    static const char wrong_total[] = "glTF\x02\0\0\0\xff\xff\xff\x7f\0\0\0\0JSON";
    CHECK_EQ_INT(parse_as(wrong_total, 20, NULL, &m, NULL, &e), -1);
    CHECK(strcmp(e.msg, "<memory>: byte 8: GLB says 2147483647 bytes, the file has 20") == 0);
}

TEST(gltf_garbage_is_an_error_not_a_crash)
{
    static const char *junk[] = {
        "glTF\x02\0\0\0\xff\xff\xff\xff",
        "{\"asset\":{\"version\":\"2.0\"},\"meshes\":[{\"primitives\":[{\"attributes\":"
        "{\"POSITION\":7}}]}]}",
        "{\"asset\":",
    };
    for (size_t i = 0; i < sizeof junk / sizeof junk[0]; i++) {
        struct mesh m;
        struct err e = {{0}};
        size_t n = i == 0 ? 12 : strlen(junk[i]);
        CHECK_EQ_INT(parse_as(junk[i], n, NULL, &m, NULL, &e), -1);
        CHECK_STR_CONTAINS(e.msg, "<memory>: ");
        for (const char *c = e.msg; *c; c++)
            CHECK(*c >= 0x20 && *c < 0x7f);
    }
}

TEST(ply_vertex_colours_are_drawn)
{
    /* a triangle whose corners are red, green and blue, drawn unlit and untextured from the
     * front (orthographic, one unit = 16 pixels): near each corner its own colour; at the
     * centroid a third of each. A vertex colour replaces the 0.8 default albedo, as GL's
     * glColorMaterial does; textures would multiply it */
    const char *ply = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                      "property float y\nproperty float z\nproperty uchar red\n"
                      "property uchar green\nproperty uchar blue\nelement face 1\n"
                      "property list uchar int vertex_indices\nend_header\n"
                      "-0.9 -0.9 0 255 0 0\n0.9 -0.9 0 0 255 0\n0 0.9 0 0 0 255\n3 0 1 2\n";
    struct mesh m;
    struct err e;
    REQUIRE(parse(ply, "rgb.ply", &m, &e) == 0);
    struct fb fb;
    REQUIRE(fb_init(&fb, 32, 32, false, NULL) == 0);
    struct pipeline *p = pipeline_new();
    REQUIRE(p);
    struct draw_item item = {.mesh = &m, .model = m4_identity()};
    struct camera cam;
    camera_default(&cam);
    cam.ortho_height = 2;
    for (int shade = SHADE_UNLIT; shade <= SHADE_PHONG; shade++) {
        struct render_opts o;
        render_opts_default(&o);
        o.shade = (enum shade_mode)shade;
        struct frame_stats st;
        REQUIRE(pipeline_draw(p, &item, 1, NULL, &cam, &o, &fb, &st, NULL) == 0);
        const uint8_t *near_red = fb.rgb + 3 * (29 * 32 + 3), *near_green = fb.rgb + 3 * (29 * 32 + 28);
        const uint8_t *near_blue = fb.rgb + 3 * (4 * 32 + 16);
        CHECK(near_red[0] > 3 * near_red[1] && near_red[0] > 3 * near_red[2]);
        CHECK(near_green[1] > 3 * near_green[0] && near_green[1] > 3 * near_green[2]);
        CHECK(near_blue[2] > 3 * near_blue[0] && near_blue[2] > 3 * near_blue[1]);
        if (shade == SHADE_UNLIT) { /* exactly the colour: albedo = vertex colour */
            /* pixel (16,19): centre (0.03125, -0.21875) in world units, barycentrics
             * red 0.29340, green 0.32813, blue 0.37847 -> 74.8, 83.7, 96.5 */
            const uint8_t *c = fb.rgb + 3 * (19 * 32 + 16);
            CHECK_EQ_INT(c[0], 75);
            CHECK_EQ_INT(c[1], 84);
            CHECK_EQ_INT(c[2], 97);
        }
    }
    pipeline_destroy(p);
    fb_free(&fb);
    mesh_free(&m);
}
