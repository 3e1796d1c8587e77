/* test_formats.c: OBJ, STL and PLY as the files people have write them — vertex and facet
 * colours, upper-case STL, old Mac line ends, UTF-16 text, PLY faces with extra values. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <math.h>

#include "gltf_build.h"
#include "material.h"
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
    struct render_opts o; /* (the default culling: gb_draw names it) */
    render_opts_default(&o);
    if (gb_draw(m, &fb, SHADE_UNLIT, o.cull, NULL) == 0)
        memcpy(out, gb_px(&fb, 8, 8), 3);
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

/* ---- MTL's opacity and bump maps, --normal-map, file cameras ---- */

#include <sys/stat.h>
#include <unistd.h>

#include "prepare.h"
#include "scene.h"

static void write_file(const char *path, const void *data, size_t n)
{
    FILE *f = fopen(path, "wb");
    if (f) {
        fwrite(data, 1, n, f);
        fclose(f);
    }
}

static void write_png(const char *path, int w, int h, const uint8_t *rgba)
{
    size_t n;
    uint8_t *png = gb_png(w, h, rgba, &n);
    write_file(path, png, n);
    free(png);
}

TEST(mtl_opacity_and_normal_maps)
{
    /* d 0.5: blended over the black background (half the lit colour); map_d: cut out below
     * 0.5 (an opacity map black on the left half); Tr 1 read as opaque, with a warning;
     * map_Bump naming a normal map: a tangent-space normal map (features); Ke: a warning */
    char dir[64], path[128];
    snprintf(dir, sizeof dir, "/tmp/rastty-mtl-%d", (int)getpid());
    mkdir(dir, 0700);
    const uint8_t half[16] = {0, 0, 0, 255, 255, 255, 255, 255, 0, 0, 0, 255, 255, 255, 255, 255};
    snprintf(path, sizeof path, "%s/alpha.png", dir);
    write_png(path, 2, 2, half);
    uint8_t nrm[4] = {128, 128, 255, 255};
    snprintf(path, sizeof path, "%s/nm.png", dir);
    write_png(path, 1, 1, nrm);
    const char *mtl = "newmtl glass\nKd 1 1 1\nd 0.5\nnewmtl leaf\nKd 1 1 1\nmap_d alpha.png\n"
                      "newmtl tr\nKd 1 1 1\nTr 1\nnewmtl bumpy\nKd 1 1 1\nmap_Bump -bm 0.5 nm.png\n"
                      "newmtl lamp\nKd 1 1 1\nKe 2 2 2\n";
    snprintf(path, sizeof path, "%s/m.mtl", dir);
    write_file(path, mtl, strlen(mtl));
    const char *names[5] = {"glass", "leaf", "tr", "bumpy", "lamp"};
    for (int i = 0; i < 5; i++) {
        char obj[512];
        snprintf(obj, sizeof obj,
                 "mtllib m.mtl\nv -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nvt 0 0\nvt 1 0\nvt 1 1\n"
                 "vt 0 1\nusemtl %s\nf 1/1 2/2 3/3\nf 1/1 3/3 4/4\n",
                 names[i]);
        snprintf(path, sizeof path, "%s/q%d.obj", dir, i);
        write_file(path, obj, strlen(obj));
        struct mesh m;
        struct err e;
        struct warnings w = {0};
        REQUIRE(model_load(path, NULL, &w, &m, &e) == 0);
        const struct material *mt = &m.materials[m.tri_material[0]];
        uint8_t c[3];
        centre(&m, c);
        switch (i) {
        case 0:
            CHECK(mt->alpha_mode == MAT_BLEND && m.n_opaque == 0);
            CHECK(c[0] == 128); /* unlit white at alpha 0.5 over black */
            break;
        case 1: {
            CHECK(mt->alpha_mode == MAT_MASK && mt->alpha_map.tex >= 0);
            struct fb fb;
            REQUIRE(fb_init(&fb, 16, 16, false, NULL) == 0);
            struct pipeline *p = pipeline_new();
            struct draw_item item = {.mesh = &m, .model = m4_identity()};
            struct camera cam;
            camera_default(&cam);
            cam.ortho_height = 2;
            struct render_opts o;
            render_opts_default(&o);
            o.shade = SHADE_UNLIT;
            o.filter = TEX_NEAREST;
            struct frame_stats st;
            REQUIRE(pipeline_draw(p, &item, 1, NULL, &cam, &o, &fb, &st, NULL) == 0);
            CHECK(fb.rgb[3 * (8 * 16 + 3)] == 0 && fb.rgb[3 * (8 * 16 + 12)] == 255);
            pipeline_destroy(p);
            fb_free(&fb);
            break;
        }
        case 2:
            CHECK(mt->alpha == 1 && mt->alpha_mode == MAT_OPAQUE);
            CHECK(w.n >= 1 && strstr(w.msg[0], "m.mtl:9: Tr 1 (fully transparent) read as opaque"));
            break;
        case 3:
            CHECK(mt->normal_map.tex >= 0 && mt->normal_space == MAT_NORMAL_TANGENT);
            CHECK_NEAR(mt->normal_scale, 0.5, 0);
            CHECK(m.features && m.tangents);
            break;
        case 4:
            CHECK(w.n == 2 && strstr(w.msg[1], "m.mtl:15: Ke (emission) is not drawn"));
            CHECK(!m.features);
            break;
        }
        mesh_free(&m);
        unlink(path);
    }
    const char *files[3] = {"alpha.png", "nm.png", "m.mtl"};
    for (int i = 0; i < 3; i++) {
        snprintf(path, sizeof path, "%s/%s", dir, files[i]);
        unlink(path);
    }
    rmdir(dir);
}

TEST(normal_maps_are_told_apart_by_their_texels)
{
    struct texture tx;
    uint8_t px[4 * 4 * 4];
    for (int i = 0; i < 16; i++) { /* blue, near +z: tangent space */
        px[4 * i] = (uint8_t)(120 + i), px[4 * i + 1] = 128, px[4 * i + 2] = 250, px[4 * i + 3] = 255;
    }
    REQUIRE(texture_from_rgba(4, 4, px, &tx, NULL) == 0);
    CHECK_EQ_INT(material_normal_kind(&tx), MATERIAL_MAP_TANGENT);
    texture_free(&tx);
    for (int i = 0; i < 16; i++) /* every direction: object space */
        px[4 * i] = (uint8_t)(i * 16), px[4 * i + 1] = (uint8_t)(255 - i * 16),
        px[4 * i + 2] = (uint8_t)(i * 37 % 256);
    REQUIRE(texture_from_rgba(4, 4, px, &tx, NULL) == 0);
    CHECK_EQ_INT(material_normal_kind(&tx), MATERIAL_MAP_OBJECT);
    texture_free(&tx);
    for (int i = 0; i < 16; i++) /* grey: heights */
        px[4 * i] = px[4 * i + 1] = px[4 * i + 2] = (uint8_t)(i * 16);
    REQUIRE(texture_from_rgba(4, 4, px, &tx, NULL) == 0);
    CHECK_EQ_INT(material_normal_kind(&tx), MATERIAL_MAP_HEIGHT);
    texture_free(&tx);
}

TEST(object_space_normal_map_lights_the_model)
{
    /* tinyrenderer's habit: the head's object-space normal map turns a flat quad's normals:
     * a map of (+x) lights a quad facing +z as a face facing +x would be */
    char dir[64], path[128];
    snprintf(dir, sizeof dir, "/tmp/rastty-nm-%d", (int)getpid());
    mkdir(dir, 0700);
    uint8_t px[4 * 4 * 4];
    for (int i = 0; i < 16; i++) /* +x everywhere, and a few texels down (object space) */
        px[4 * i] = 255, px[4 * i + 1] = 128, px[4 * i + 2] = i == 0 ? 0 : 128, px[4 * i + 3] = 255;
    snprintf(path, sizeof path, "%s/x_nm.png", dir);
    write_png(path, 4, 4, px);
    char obj[256];
    snprintf(obj, sizeof obj, "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nvt 0 0\nvt 1 0\nvt 1 1\n"
                              "vt 0 1\nvn 0 0 1\nf 1/1/1 2/2/1 3/3/1\nf 1/1/1 3/3/1 4/4/1\n");
    char op[128];
    snprintf(op, sizeof op, "%s/x.obj", dir);
    write_file(op, obj, strlen(obj));
    struct scene s;
    struct err e;
    REQUIRE(scene_load(op, &s, &e) == 0);
    REQUIRE(scene_set_normal_map(&s, path, &e) == 0);
    const struct material *mt = &s.meshes[0].materials[0];
    CHECK(mt->normal_space == MAT_NORMAL_OBJECT && s.meshes[0].features);
    struct fb fb;
    REQUIRE(fb_init(&fb, 16, 16, false, NULL) == 0);
    struct pipeline *p = pipeline_new();
    struct camera cam;
    camera_default(&cam);
    cam.ortho_height = 2;
    struct render_opts o;
    render_opts_default(&o);
    o.filter = TEX_NEAREST;
    struct frame_stats st;
    REQUIRE(pipeline_draw(p, s.items, 1, NULL, &cam, &o, &fb, &st, NULL) == 0);
    /* N = +x, L = (1,1,1)/sqrt 3: diffuse 0.9 * 0.577 + 0.1 on albedo 0.8 = 0.5; V = +z, so
     * N.H = 0.46 and the highlight is 0.5 * 0.46^32: nothing; 0.5 * 255 = 127.5 */
    const uint8_t *c = fb.rgb + 3 * (8 * 16 + 8);
    CHECK(c[0] >= 126 && c[0] <= 129);
    pipeline_destroy(p);
    fb_free(&fb);
    scene_free(&s);
    unlink(path);
    unlink(op);
    rmdir(dir);
}

TEST(file_cameras_are_the_default_view)
{
    /* a glTF with two cameras: the first is the default view; --camera 2 the second; 0
     * rastty's framing; --eye wins over them */
    char dir[64], path[128];
    snprintf(dir, sizeof dir, "/tmp/rastty-cam-%d", (int)getpid());
    mkdir(dir, 0700);
    struct gb g = {0};
    static struct gb_quad q;
    gb_quad(&q, 0, 1, 1);
    int a[4];
    gb_quad_accs(&g, &q, a);
    char body[2048];
    snprintf(body, sizeof body,
             "\"scenes\":[{\"nodes\":[0,1,2]}],\"nodes\":[{\"mesh\":0},{\"camera\":0,"
             "\"translation\":[0,0,5]},{\"camera\":1,\"translation\":[0,4,0],\"rotation\":"
             "[-0.7071068,0,0,0.7071068]}],\"cameras\":[{\"type\":\"perspective\",\"perspective\":"
             "{\"yfov\":0.5,\"znear\":0.1}},{\"type\":\"orthographic\",\"orthographic\":{\"xmag\":2,"
             "\"ymag\":1.5,\"znear\":0.1,\"zfar\":10}}],\"meshes\":[{\"primitives\":[{\"attributes\":"
             "{\"POSITION\":%d},\"indices\":%d}]}]",
             a[0], a[3]);
    char *j = gb_json(&g, body);
    snprintf(path, sizeof path, "%s/c.gltf", dir);
    write_file(path, j, strlen(j));
    free(j);
    struct options o;
    struct err e;
    char *argv[] = {"rastty", "render", path, "--out", "x.png"};
    REQUIRE(options_parse(5, argv, &o, &e) == 0);
    struct scene s;
    REQUIRE(prepare_scene(&o, path, &s, NULL, 0, &e) == 0);
    CHECK_EQ_INT(prepare_camera_count(&s), 2);
    struct camera cam;
    struct render_opts ro;
    prepare_camera(&o, &s, 1.6, false, &cam, &ro);
    CHECK_NEAR(cam.eye.z, 5, 1e-6);
    CHECK_NEAR(cam.fov_deg, 0.5 * 180 / M_PI, 1e-4);
    o.file_camera = 2;
    prepare_camera(&o, &s, 1.6, false, &cam, &ro);
    CHECK_NEAR(cam.eye.y, 4, 1e-6);
    CHECK(cam.target.y < cam.eye.y); /* looking down */
    CHECK_NEAR(cam.ortho_height, 3, 1e-6);
    o.file_camera = 0;
    prepare_camera(&o, &s, 1.6, false, &cam, &ro); /* rastty's framing: the quad fills it */
    CHECK(cam.eye.z > 0 && cam.eye.z < 5);
    o.file_camera = -1;
    o.camera_set = true;
    o.camera.eye = v3(7, 0, 0);
    prepare_camera(&o, &s, 1.6, false, &cam, &ro);
    CHECK_NEAR(cam.eye.x, 7, 0);
    /* past the file's cameras: an error */
    o.file_camera = 3;
    o.camera_set = false;
    scene_free(&s);
    CHECK_EQ_INT(prepare_scene(&o, path, &s, NULL, 0, &e), -1);
    CHECK_STR_CONTAINS(e.msg, "--camera 3: the model has 2 cameras");
    unlink(path);
    rmdir(dir);
}

TEST(a_texture_in_a_textures_folder_is_found)
{
    /* map_Kd wood.png (and an exporter's C:\art\wood.png) with the image in textures/ beside
     * the model, as 3DS and FBX exports keep them: drawn with it, no warning */
    char dir[64], sub[96], path[160];
    snprintf(dir, sizeof dir, "/tmp/rastty-texdir-%d", (int)getpid());
    snprintf(sub, sizeof sub, "%s/textures", dir);
    mkdir(dir, 0700);
    mkdir(sub, 0700);
    const uint8_t red[4] = {200, 30, 10, 255};
    snprintf(path, sizeof path, "%s/wood.png", sub);
    write_png(path, 1, 1, red);
    const char *maps[2] = {"wood.png", "C:\\art\\wood.png"};
    for (int i = 0; i < 2; i++) {
        char mtl[128];
        snprintf(mtl, sizeof mtl, "newmtl w\nKd 1 1 1\nmap_Kd %s\n", maps[i]);
        snprintf(path, sizeof path, "%s/m.mtl", dir);
        write_file(path, mtl, strlen(mtl));
        const char *obj = "mtllib m.mtl\nv -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nvt 0 0\nvt 1 0\n"
                          "vt 1 1\nvt 0 1\nusemtl w\nf 1/1 2/2 3/3\nf 1/1 3/3 4/4\n";
        snprintf(path, sizeof path, "%s/q.obj", dir);
        write_file(path, obj, strlen(obj));
        struct mesh m;
        struct err e;
        struct warnings w = {0};
        REQUIRE(model_load(path, NULL, &w, &m, &e) == 0);
        CHECK_EQ_INT(w.n, 0);
        uint8_t c[3];
        centre(&m, c);
        CHECK(c[0] == 200 && c[1] == 30 && c[2] == 10);
        mesh_free(&m);
    }
    snprintf(path, sizeof path, "%s/q.obj", dir);
    unlink(path);
    snprintf(path, sizeof path, "%s/m.mtl", dir);
    unlink(path);
    snprintf(path, sizeof path, "%s/wood.png", sub);
    unlink(path);
    rmdir(sub);
    rmdir(dir);
}

TEST(allow_outside_and_normal_map_flags_reach_the_loader)
{
    struct options o;
    struct err e;
    char *argv[] = {"rastty", "render", "m.gltf", "--allow-outside", "--normal-map", "n.png",
                    "--camera", "2", "--out", "x.png"};
    REQUIRE(options_parse(10, argv, &o, &e) == 0);
    CHECK(o.model.any_path);
    CHECK(o.normal_map && strcmp(o.normal_map, "n.png") == 0);
    CHECK_EQ_INT(o.file_camera, 2);
    char *bad[] = {"rastty", "render", "m.gltf", "--camera", "65", "--out", "x.png"};
    CHECK_EQ_INT(options_parse(7, bad, &o, &e), -1);
    CHECK_STR_CONTAINS(e.msg, "camera number");
}
