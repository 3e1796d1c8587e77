/* test_formats.c: OBJ, STL and PLY as the files people have write them — vertex and facet
 * colours, upper-case STL, old Mac line ends, UTF-16 text, PLY faces with extra values. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "model.h"
#include "pipeline.h"
#include "test.h"

static int parse(const char *text, size_t len, const char *path, struct mesh *m,
                 struct warnings *w, struct err *e)
{
    struct model_ctx ctx = {.path = path, .warn = w};
    if (w)
        memset(w, 0, sizeof *w);
    return model_parse(text, len, &ctx, m, e);
}

/* the colour drawn unlit at the centre of a 16x16 frame, the model framed by an orthographic
 * camera looking down -z */
static void centre(const struct mesh *m, uint8_t out[3])
{
    struct fb fb;
    memset(out, 0, 3);
    if (fb_init(&fb, 16, 16, false, NULL))
        return;
    struct pipeline *p = pipeline_new();
    struct draw_item item = {.mesh = m, .model = m4_identity()};
    struct camera cam;
    camera_default(&cam);
    cam.ortho_height = 2;
    struct render_opts o;
    render_opts_default(&o);
    o.shade = SHADE_UNLIT;
    struct frame_stats st;
    if (p && pipeline_draw(p, &item, 1, NULL, &cam, &o, &fb, &st, NULL) == 0)
        memcpy(out, fb.rgb + 3 * (8 * 16 + 8), 3);
    pipeline_destroy(p);
    fb_free(&fb);
}

TEST(obj_vertex_colours_are_drawn)
{
    /* "v x y z r g b" (MeshLab, ZBrush): 0..1 display values, or 0..255 */
    const char *obj[2] = {"v -1 -1 0 0.2 0.4 1\nv 1 -1 0 0.2 0.4 1\nv 0 1 0 0.2 0.4 1\nf 1 2 3\n",
                          "v -1 -1 0 51 102 255\nv 1 -1 0 51 102 255\nv 0 1 0 51 102 255\n"
                          "f 1 2 3\n"};
    for (int i = 0; i < 2; i++) {
        struct mesh m;
        struct err e;
        REQUIRE(parse(obj[i], strlen(obj[i]), "c.obj", &m, NULL, &e) == 0);
        REQUIRE(m.colors);
        uint8_t c[3];
        centre(&m, c);
        CHECK(c[0] == 51 && c[1] == 102 && c[2] == 255);
        mesh_free(&m);
    }
    /* a w alone is no colour; a file without colours has none */
    const char *w = "v -1 -1 0 1\nv 1 -1 0 1\nv 0 1 0 1\nf 1 2 3\n";
    struct mesh m;
    struct err e;
    REQUIRE(parse(w, strlen(w), "w.obj", &m, NULL, &e) == 0);
    CHECK(m.colors == NULL);
    mesh_free(&m);
}

/* a binary STL of one triangle facing +z (the file's: Z-up, drawn facing the viewer's +y:
 * seen from above here) with a header and the attribute bytes */
static void stl_one(unsigned char out[134], const char *header, uint16_t attr)
{
    memset(out, 0, 134);
    memcpy(out, header, strlen(header));
    out[80] = 1;
    const float v[12] = {0, 0, 1, -1, -1, 0, 1, -1, 0, 0, 1, 0};
    memcpy(out + 84, v, sizeof v);
    out[132] = (uint8_t)attr, out[133] = (uint8_t)(attr >> 8);
}

static void stl_colour(struct test *t, const unsigned char *bin, int r, int g, int b, int line)
{
    struct mesh m;
    struct err e;
    struct model_opts o = {.up = MODEL_UP_Y}; /* as written: facing +z, toward the camera */
    struct model_ctx ctx = {.path = "c.stl", .opts = &o};
    if (model_parse((const char *)bin, 134, &ctx, &m, &e)) {
        test_fail(t, __FILE__, line, "%s", e.msg);
        return;
    }
    uint8_t c[3];
    centre(&m, c);
    if (!(c[0] == r && c[1] == g && c[2] == b))
        test_fail(t, __FILE__, line, "(%d, %d, %d) != (%d, %d, %d)", c[0], c[1], c[2], r, g, b);
    mesh_free(&m);
}

TEST(stl_facet_colours_both_conventions)
{
    unsigned char bin[134];
    /* VisCAM/SolidView: bit 15 set, blue in the low bits: red 31, green 0, blue 10 */
    stl_one(bin, "solid part", 0x8000 | 31 << 10 | 10);
    stl_colour(t, bin, 255, 0, 82, __LINE__);
    /* without bit 15: no colour (the default albedo 0.8: 204) */
    stl_one(bin, "solid part", 31 << 10);
    stl_colour(t, bin, 204, 204, 204, __LINE__);
    /* Materialise Magics: red in the low bits, bit 15 clear = the facet's own */
    stl_one(bin, "COLOR=\x10\x20\x30\xff", 31 | 10 << 10);
    stl_colour(t, bin, 255, 0, 82, __LINE__);
    /* bit 15 set: the part's colour from the header */
    stl_one(bin, "COLOR=\x10\x20\x30\xff", 0x8000);
    stl_colour(t, bin, 0x10, 0x20, 0x30, __LINE__);
}

TEST(stl_upper_case_ascii_is_ascii)
{
    /* "SOLID ... FACET NORMAL": it was read as binary ("binary STL says 1347374924 ...") */
    const char *stl = "SOLID X\nFACET NORMAL 0 0 1\nOUTER LOOP\nVERTEX 0 0 0\nVERTEX 1 0 0\n"
                      "VERTEX 0 1 0\nENDLOOP\nENDFACET\nENDSOLID X\n";
    struct mesh m;
    struct err e;
    enum model_format f;
    REQUIRE(model_detect(stl, strlen(stl), "x.dat", &f, &e) == 0);
    CHECK_EQ_INT(f, MODEL_STL);
    REQUIRE(parse(stl, strlen(stl), "x.stl", &m, NULL, &e) == 0);
    CHECK_EQ_INT(m.n_tris, 1);
    mesh_free(&m);
}

TEST(obj_old_mac_line_ends_and_utf16_are_read)
{
    /* CR-only lines and UTF-16 without a byte-order mark said "no faces" */
    const char cr[] = "v 0 0 0\rv 1 0 0\rv 0 1 0\rf 1 2 3\r";
    struct mesh m;
    struct err e;
    REQUIRE(parse(cr, strlen(cr), "cr.obj", &m, NULL, &e) == 0);
    CHECK_EQ_INT(m.n_tris, 1);
    mesh_free(&m);
    const char text[] = "v 0 0 0\r\nv 1 0 0\r\nv 0 1 0\r\nf 1 2 3\r\n";
    char u16[2 * sizeof text];
    for (int be = 0; be < 2; be++) {
        for (size_t i = 0; i < sizeof text - 1; i++)
            u16[2 * i + be] = text[i], u16[2 * i + !be] = 0;
        REQUIRE(parse(u16, 2 * (sizeof text - 1), "u.obj", &m, NULL, &e) == 0);
        CHECK_EQ_INT(m.n_tris, 1);
        mesh_free(&m);
    }
    /* UTF-16 holding other characters: still named */
    const char odd[8] = {'v', 0, ' ', 0, (char)0xe9, 0x30, '\n', 0};
    CHECK_EQ_INT(parse(odd, 8, "u.obj", &m, NULL, &e), -1);
    CHECK_STR_CONTAINS(e.msg, "UTF-16");
}

TEST(ply_face_lines_with_more_values_are_read)
{
    /* face lines carrying values the header does not declare (an exporter's): read, as
     * assimp reads them, with a warning naming the first line (it stopped at "bad integer") */
    const char *ply = "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\n"
                      "property float y\nproperty float z\nelement face 2\n"
                      "property list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n1 1 0\n"
                      "0 1 0\n3 0 1 2 0.5 0.5\n3 0 2 3 0.5 0.5\n";
    struct mesh m;
    struct err e;
    struct warnings w;
    REQUIRE(parse(ply, strlen(ply), "x.ply", &m, &w, &e) == 0);
    CHECK_EQ_INT(m.n_tris, 2);
    REQUIRE(w.n == 1);
    CHECK(strcmp(w.msg[0], "x.ply:14: a 'face' line holds more values than the header declares; "
                           "the extra values are skipped") == 0);
    mesh_free(&m);
}
