/* test_gltf.c: glTF as its specification defines it — every rule on a tiny file written here
 * (gltf_build.h): colour spaces, vertex colours, emission, alpha, samplers, texture
 * transforms, the second uv set, quantized and instanced geometry, mirrored nodes, sides,
 * materials, extensions, and what the reader refuses. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "gltf_build.h"
#include "meshoptimizer.h"
#include "test.h"

static const uint8_t black[3] = {0, 0, 0};

/* a quad (z = 0, facing +z, uvs 0..us) with this material JSON, as a glTF in memory */
static char *quad_gltf(struct gb *g, const char *material, float us, const char *extra_attrs,
                       const char *rest)
{
    static struct gb_quad q;
    gb_quad(&q, 0, us, 1);
    int a[4];
    gb_quad_accs(g, &q, a);
    char body[16384];
    snprintf(body, sizeof body,
             "\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0}],\"meshes\":[{\"primitives\":"
             "[{\"attributes\":{\"POSITION\":%d,\"NORMAL\":%d,\"TEXCOORD_0\":%d%s},\"indices\":%d,"
             "\"material\":0}]}],\"materials\":[%s]%s%s",
             a[0], a[1], a[2], extra_attrs, a[3], material, *rest ? "," : "", rest);
    return gb_json(g, body);
}

static int load(const char *json, struct mesh *m, struct warnings *w)
{
    struct err e;
    if (gb_load(json, strlen(json), NULL, m, w, &e)) {
        fprintf(stderr, "      load: %s\n", e.msg);
        return -1;
    }
    return 0;
}

/* the centre pixel of the quad drawn at 16x16 */
static int centre(const struct mesh *m, enum shade_mode shade, uint8_t out[3])
{
    struct fb fb;
    if (fb_init(&fb, 16, 16, false, NULL))
        return -1;
    int rc = gb_draw(m, &fb, shade, CULL_AUTO, black);
    memcpy(out, gb_px(&fb, 8, 8), 3);
    fb_free(&fb);
    return rc;
}

#define CHECK_RGB(c, r, g, b)                                                              \
    do {                                                                                   \
        if (!((c)[0] == (r) && (c)[1] == (g) && (c)[2] == (b)))                            \
            test_fail(t, __FILE__, __LINE__, "(%d, %d, %d) != (%d, %d, %d)", (c)[0], (c)[1], \
                      (c)[2], r, g, b);                                                    \
    } while (0)

TEST(gltf_base_colour_factors_are_linear)
{
    /* glTF's baseColorFactor is linear: 0.8 is drawn as its display value 231 (not 204);
     * an unlit orange (1, 0.218, 0) as (255, 129, 0), the sRGB transfer function's */
    struct gb g = {0};
    char *j = quad_gltf(&g, "{\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.8,0.8,0.8,1]}}",
                        1, "", "");
    struct mesh m;
    REQUIRE(load(j, &m, NULL) == 0);
    uint8_t c[3];
    REQUIRE(centre(&m, SHADE_UNLIT, c) == 0);
    CHECK_RGB(c, 231, 231, 231);
    mesh_free(&m);
    free(j);
    struct gb g2 = {0};
    j = quad_gltf(&g2, "{\"pbrMetallicRoughness\":{\"baseColorFactor\":[1,0.218,0,1]},"
                       "\"extensions\":{\"KHR_materials_unlit\":{}}}",
                  1, "", "\"extensionsUsed\":[\"KHR_materials_unlit\"]");
    REQUIRE(load(j, &m, NULL) == 0);
    REQUIRE(centre(&m, SHADE_PHONG, c) == 0); /* unlit whatever the shading */
    CHECK_RGB(c, 255, 129, 0);
    mesh_free(&m);
    free(j);
}

TEST(gltf_color_0_is_drawn)
{
    /* COLOR_0 (linear, float VEC3 and normalized ubyte VEC4) multiplies the base colour:
     * 0.2 grey is drawn 124; a flamingo whose only colour is its vertex colours is not
     * white */
    struct gb g = {0};
    float col[12];
    for (int i = 0; i < 12; i++)
        col[i] = i % 3 == 0 ? 0.2f : i % 3 == 1 ? 0.5f : 0;
    int ca = gb_acc(&g, col, sizeof col, 5126, 4, "VEC3", "");
    char attr[64];
    snprintf(attr, sizeof attr, ",\"COLOR_0\":%d", ca);
    char *j = quad_gltf(&g, "{}", 1, attr, "");
    struct mesh m;
    REQUIRE(load(j, &m, NULL) == 0);
    REQUIRE(m.colors);
    uint8_t c[3];
    REQUIRE(centre(&m, SHADE_UNLIT, c) == 0);
    CHECK_RGB(c, 124, 188, 0);
    mesh_free(&m);
    free(j);
    struct gb g2 = {0};
    uint8_t c8[16];
    for (int i = 0; i < 16; i++)
        c8[i] = i % 4 == 3 ? 255 : i % 4 == 0 ? 51 : 0; /* 0.2 red */
    ca = gb_acc(&g2, c8, sizeof c8, 5121, 4, "VEC4", ",\"normalized\":true");
    snprintf(attr, sizeof attr, ",\"COLOR_0\":%d", ca);
    j = quad_gltf(&g2, "{}", 1, attr, "");
    REQUIRE(load(j, &m, NULL) == 0);
    REQUIRE(centre(&m, SHADE_UNLIT, c) == 0);
    CHECK_RGB(c, 124, 0, 0);
    mesh_free(&m);
    free(j);
}

TEST(gltf_emission_is_drawn)
{
    /* a black material glowing (1, 0.5, 0): the emission added to the lighting, as display
     * values; KHR_materials_emissive_strength scales the linear factor */
    struct gb g = {0};
    char *j = quad_gltf(&g,
                        "{\"pbrMetallicRoughness\":{\"baseColorFactor\":[0,0,0,1]},"
                        "\"emissiveFactor\":[1,0.5,0]}",
                        1, "", "");
    struct mesh m;
    REQUIRE(load(j, &m, NULL) == 0);
    uint8_t c[3];
    REQUIRE(centre(&m, SHADE_PHONG, c) == 0);
    CHECK_RGB(c, 255, 188, 0);
    mesh_free(&m);
    free(j);
    struct gb g2 = {0};
    j = quad_gltf(&g2,
                  "{\"pbrMetallicRoughness\":{\"baseColorFactor\":[0,0,0,1]},"
                  "\"emissiveFactor\":[1,1,1],\"extensions\":{\"KHR_materials_emissive_strength\":"
                  "{\"emissiveStrength\":0.5}}}",
                  1, "", "\"extensionsUsed\":[\"KHR_materials_emissive_strength\"]");
    REQUIRE(load(j, &m, NULL) == 0);
    REQUIRE(centre(&m, SHADE_GOURAUD, c) == 0);
    CHECK_RGB(c, 188, 188, 188);
    mesh_free(&m);
    free(j);
}

TEST(gltf_emissive_texture_reads_its_own_uv_set)
{
    /* an emissive texture, red on the left and blue on the right, read with TEXCOORD_1,
     * which points at the red half while TEXCOORD_0 points at the blue one */
    const uint8_t px[8] = {255, 0, 0, 255, 0, 0, 255, 255};
    char *uri = gb_png_uri(2, 1, px);
    struct gb g = {0};
    float uv1[8] = {0.25f, 0.5f, 0.25f, 0.5f, 0.25f, 0.5f, 0.25f, 0.5f};
    int u1 = gb_acc(&g, uv1, sizeof uv1, 5126, 4, "VEC2", "");
    char attr[64], rest[4096];
    snprintf(attr, sizeof attr, ",\"TEXCOORD_1\":%d", u1);
    snprintf(rest, sizeof rest,
             "\"textures\":[{\"source\":0,\"sampler\":0}],\"samplers\":[{\"magFilter\":9728}],"
             "\"images\":[{\"uri\":\"%s\"}]",
             uri);
    free(uri);
    /* TEXCOORD_0 at u = 0.75: the quad's uvs all 0.75 (us 0: every u 0; moved by the
     * transform below would be another rule, so the uvs are set here) */
    char *j = quad_gltf(&g,
                        "{\"pbrMetallicRoughness\":{\"baseColorFactor\":[0,0,0,1]},"
                        "\"emissiveFactor\":[1,1,1],"
                        "\"emissiveTexture\":{\"index\":0,\"texCoord\":1}}",
                        0, attr, rest);
    struct mesh m;
    REQUIRE(load(j, &m, NULL) == 0);
    REQUIRE(m.uv1);
    uint8_t c[3];
    REQUIRE(centre(&m, SHADE_PHONG, c) == 0);
    CHECK_RGB(c, 255, 0, 0);
    mesh_free(&m);
    free(j);
}

TEST(gltf_alpha_mask_cuts_out)
{
    /* MASK: alpha 0.3 under the cutoff 0.5 is not drawn at all (the background shows);
     * 0.6 is drawn opaque */
    const char *mats[2] = {"{\"pbrMetallicRoughness\":{\"baseColorFactor\":[1,1,1,0.3]},"
                           "\"alphaMode\":\"MASK\",\"alphaCutoff\":0.5}",
                           "{\"pbrMetallicRoughness\":{\"baseColorFactor\":[1,1,1,0.6]},"
                           "\"alphaMode\":\"MASK\"}"};
    for (int i = 0; i < 2; i++) {
        struct gb g = {0};
        char *j = quad_gltf(&g, mats[i], 1, "", "");
        struct mesh m;
        REQUIRE(load(j, &m, NULL) == 0);
        uint8_t c[3];
        REQUIRE(centre(&m, SHADE_UNLIT, c) == 0);
        if (i == 0)
            CHECK_RGB(c, 0, 0, 0);
        else
            CHECK_RGB(c, 255, 255, 255);
        mesh_free(&m);
        free(j);
    }
}

/* two quads: the first primitive's material `m0` at z0, the second's `m1` at z1 */
static char *two_quads(struct gb *g, float z0, float z1, const char *m0, const char *m1)
{
    static struct gb_quad q0, q1;
    gb_quad(&q0, z0, 1, 1);
    gb_quad(&q1, z1, 1, 1);
    int a[4], b[4];
    gb_quad_accs(g, &q0, a);
    gb_quad_accs(g, &q1, b);
    char body[8192];
    snprintf(body, sizeof body,
             "\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0}],\"meshes\":[{\"primitives\":["
             "{\"attributes\":{\"POSITION\":%d,\"NORMAL\":%d},\"indices\":%d,\"material\":0},"
             "{\"attributes\":{\"POSITION\":%d,\"NORMAL\":%d},\"indices\":%d,\"material\":1}]}],"
             "\"materials\":[%s,%s]",
             a[0], a[1], a[3], b[0], b[1], b[3], m0, m1);
    return gb_json(g, body);
}

TEST(gltf_alpha_blend_mixes_back_to_front)
{
    /* BLEND: half-transparent red in front of opaque blue: (128, 0, 128) whichever comes
     * first in the file (the blended pass runs after the opaque one) */
    const char *red = "{\"pbrMetallicRoughness\":{\"baseColorFactor\":[1,0,0,0.5]},"
                      "\"alphaMode\":\"BLEND\"}";
    const char *green = "{\"pbrMetallicRoughness\":{\"baseColorFactor\":[0,1,0,0.5]},"
                        "\"alphaMode\":\"BLEND\"}";
    const char *blue = "{\"pbrMetallicRoughness\":{\"baseColorFactor\":[0,0,1,1]}}";
    for (int order = 0; order < 2; order++) {
        struct gb g = {0};
        char *j = order ? two_quads(&g, 0.5f, -0.5f, red, blue) : two_quads(&g, -0.5f, 0.5f, blue, red);
        struct mesh m;
        REQUIRE(load(j, &m, NULL) == 0);
        CHECK_EQ_INT(m.n_opaque, 2);
        uint8_t c[3];
        REQUIRE(centre(&m, SHADE_UNLIT, c) == 0);
        CHECK_RGB(c, 128, 0, 128);
        mesh_free(&m);
        free(j);
    }
    /* two blended quads, the nearer (red) first in the file: drawn farthest first, so red
     * is mixed over green over black: (128, 64, 0); nearest first would give (64, 128, 0) */
    struct gb g = {0};
    char *j = two_quads(&g, 0.5f, -0.5f, red, green);
    struct mesh m;
    REQUIRE(load(j, &m, NULL) == 0);
    CHECK_EQ_INT(m.n_opaque, 0);
    uint8_t c[3];
    REQUIRE(centre(&m, SHADE_UNLIT, c) == 0);
    CHECK_RGB(c, 128, 64, 0);
    mesh_free(&m);
    free(j);
}

/* a quad with uvs u 0..2 and a 2x1 texture (black, white) through a sampler; the colours
 * at u = 0.3, 0.7, 1.3, 1.7 (nearest) */
static int wrap_row(struct test *t, const char *sampler, const char *slot_extra, uint8_t out[4])
{
    const uint8_t px[8] = {0, 0, 0, 255, 255, 255, 255, 255};
    char *uri = gb_png_uri(2, 1, px);
    char rest[4096], mat[512];
    snprintf(rest, sizeof rest,
             "\"textures\":[{\"source\":0,\"sampler\":0}],\"samplers\":[%s],"
             "\"images\":[{\"uri\":\"%s\"}]",
             sampler, uri);
    free(uri);
    snprintf(mat, sizeof mat,
             "{\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":0%s}}}", slot_extra);
    struct gb g = {0};
    char *j = quad_gltf(&g, mat, 2, "", rest);
    struct mesh m;
    int rc = load(j, &m, NULL);
    free(j);
    if (rc)
        return -1;
    struct fb fb;
    if (fb_init(&fb, 90, 20, false, NULL)) {
        mesh_free(&m);
        return -1;
    }
    /* ortho, 2 units tall at 90x20: x = (px + 0.5) / 90 * 9 - 4.5; the quad spans
     * [-0.9, 0.9], u = (x + 0.9) / 1.8 * 2 */
    rc = gb_draw_f(&m, &fb, SHADE_UNLIT, CULL_AUTO, black, TEX_NEAREST);
    const double us[4] = {0.3, 0.7, 1.3, 1.7};
    for (int i = 0; i < 4; i++) {
        double x = us[i] / 2 * 1.8 - 0.9;
        int pxl = (int)((x + 4.5) / 9 * 90);
        out[i] = gb_px(&fb, pxl, 10)[0];
    }
    (void)t;
    fb_free(&fb);
    mesh_free(&m);
    return rc;
}

TEST(gltf_sampler_wrap_modes)
{
    uint8_t c[4];
    REQUIRE(wrap_row(t, "{}", "", c) == 0); /* REPEAT: b w b w */
    CHECK(c[0] == 0 && c[1] == 255 && c[2] == 0 && c[3] == 255);
    REQUIRE(wrap_row(t, "{\"wrapS\":33071}", "", c) == 0); /* CLAMP_TO_EDGE: b w w w */
    CHECK(c[0] == 0 && c[1] == 255 && c[2] == 255 && c[3] == 255);
    REQUIRE(wrap_row(t, "{\"wrapS\":33648}", "", c) == 0); /* MIRRORED_REPEAT: b w w b */
    CHECK(c[0] == 0 && c[1] == 255 && c[2] == 255 && c[3] == 0);
}

TEST(gltf_texture_transform)
{
    /* KHR_texture_transform: offset 0.5 moves the texture half a copy (w b w b); scale 0.5
     * shows half a copy over the quad's two (b b w w) */
    uint8_t c[4];
    REQUIRE(wrap_row(t, "{}", ",\"extensions\":{\"KHR_texture_transform\":{\"offset\":[0.5,0]}}",
                     c) == 0);
    CHECK(c[0] == 255 && c[1] == 0 && c[2] == 255 && c[3] == 0);
    REQUIRE(wrap_row(t, "{}", ",\"extensions\":{\"KHR_texture_transform\":{\"scale\":[0.5,1]}}",
                     c) == 0);
    CHECK(c[0] == 0 && c[1] == 0 && c[2] == 255 && c[3] == 255);
    /* rotation by a half turn about the origin: u' = -u, v' = -v: (b w b w) becomes
     * (w b w b) */
    REQUIRE(wrap_row(t, "{}", ",\"extensions\":{\"KHR_texture_transform\":{\"rotation\":3.14159265}}",
                     c) == 0);
    CHECK(c[0] == 255 && c[1] == 0 && c[2] == 255 && c[3] == 0);
}

TEST(gltf_quantized_positions_draw)
{
    /* KHR_mesh_quantization: positions as shorts (not normalized) scaled by the node, normals
     * as normalized bytes: the quad at its place (it was a blank picture, exit 0) */
    struct gb g = {0};
    int16_t pos[12] = {-90, -90, 0, 90, -90, 0, 90, 90, 0, -90, 90, 0};
    int8_t nrm[16] = {0, 0, 127, 0, 0, 0, 127, 0, 0, 0, 127, 0, 0, 0, 127, 0};
    uint16_t idx[6] = {0, 1, 2, 0, 2, 3};
    int p = gb_acc(&g, pos, sizeof pos, 5122, 4, "VEC3", ",\"min\":[-90,-90,0],\"max\":[90,90,0]");
    int v = gb_view(&g, nrm, sizeof nrm, ",\"byteStride\":4");
    char acc[128];
    snprintf(acc, sizeof acc, ",{\"bufferView\":%d,\"componentType\":5120,\"count\":4,"
                              "\"type\":\"VEC3\",\"normalized\":true}",
             v);
    strcat(g.accs, acc);
    int n = g.n_accs++;
    int i = gb_acc(&g, idx, sizeof idx, 5123, 6, "SCALAR", "");
    char body[1024];
    snprintf(body, sizeof body,
             "\"extensionsUsed\":[\"KHR_mesh_quantization\"],\"extensionsRequired\":"
             "[\"KHR_mesh_quantization\"],\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0,"
             "\"scale\":[0.01,0.01,0.01]}],\"meshes\":[{\"primitives\":[{\"attributes\":"
             "{\"POSITION\":%d,\"NORMAL\":%d},\"indices\":%d}]}]",
             p, n, i);
    char *j = gb_json(&g, body);
    struct mesh m;
    REQUIRE(load(j, &m, NULL) == 0);
    CHECK_NEAR(m.bbox_min[0], -0.9, 1e-6);
    CHECK_NEAR(m.bbox_max[1], 0.9, 1e-6);
    CHECK_NEAR(m.verts[0].nrm[2], 1, 1e-6);
    uint8_t c[3];
    REQUIRE(centre(&m, SHADE_UNLIT, c) == 0);
    CHECK(c[0] > 100);
    mesh_free(&m);
    free(j);
}

TEST(gltf_gpu_instancing_draws_every_instance)
{
    /* EXT_mesh_gpu_instancing: three translations, three quads (it drew one) */
    struct gb g = {0};
    static struct gb_quad q;
    gb_quad(&q, 0, 1, 1);
    int a[4];
    gb_quad_accs(&g, &q, a);
    float tr[9] = {-3, 0, 0, 0, 0, 0, 3, 0, 0};
    int ti = gb_acc(&g, tr, sizeof tr, 5126, 3, "VEC3", "");
    char body[1024];
    snprintf(body, sizeof body,
             "\"extensionsUsed\":[\"EXT_mesh_gpu_instancing\"],\"scenes\":[{\"nodes\":[0]}],"
             "\"nodes\":[{\"mesh\":0,\"extensions\":{\"EXT_mesh_gpu_instancing\":{\"attributes\":"
             "{\"TRANSLATION\":%d}}}}],\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":"
             "%d},\"indices\":%d}]}]",
             ti, a[0], a[3]);
    char *j = gb_json(&g, body);
    struct mesh m;
    REQUIRE(load(j, &m, NULL) == 0);
    CHECK_EQ_INT(m.n_tris, 6);
    CHECK_NEAR(m.bbox_min[0], -3.9, 1e-6);
    CHECK_NEAR(m.bbox_max[0], 3.9, 1e-6);
    mesh_free(&m);
    free(j);
}

TEST(gltf_mirrored_node_keeps_normals_out_and_faces_front)
{
    /* a node scaled by (-1, 1, 1): normals still toward +z, the winding turned back, so
     * --cull back keeps it and the light falls on its front */
    struct gb g = {0};
    static struct gb_quad q;
    gb_quad(&q, 0, 1, 1);
    int a[4];
    gb_quad_accs(&g, &q, a);
    char body[1024];
    snprintf(body, sizeof body,
             "\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0,\"scale\":[-1,1,1]}],"
             "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":%d,\"NORMAL\":%d},"
             "\"indices\":%d}]}],\"materials\":[]",
             a[0], a[1], a[3]);
    char *j = gb_json(&g, body);
    struct mesh m;
    REQUIRE(load(j, &m, NULL) == 0);
    for (uint32_t i = 0; i < m.n_tris; i++) {
        const float *p0 = m.verts[m.tris[i][0]].pos, *p1 = m.verts[m.tris[i][1]].pos,
                    *p2 = m.verts[m.tris[i][2]].pos;
        double z = (double)(p1[0] - p0[0]) * (p2[1] - p0[1]) - (double)(p1[1] - p0[1]) * (p2[0] - p0[0]);
        CHECK(z > 0);
        CHECK_NEAR(m.verts[m.tris[i][0]].nrm[2], 1, 1e-6);
    }
    struct fb fb;
    REQUIRE(fb_init(&fb, 16, 16, false, NULL) == 0);
    REQUIRE(gb_draw(&m, &fb, SHADE_PHONG, CULL_BACK, black) == 0);
    CHECK(gb_px(&fb, 8, 8)[0] > 100);
    fb_free(&fb);
    mesh_free(&m);
    free(j);
}

TEST(gltf_double_sided_rules)
{
    /* a quad facing away from the camera: single-sided (the default) it is culled under
     * --cull auto; two-sided it is drawn, lit with its normal turned toward the camera —
     * the same colour as the quad facing the camera */
    static struct gb_quad q;
    gb_quad(&q, 0, 1, 1);
    for (int i = 0; i < 4; i++) { /* mirror it in x by hand: clockwise, normals -z */
        q.pos[3 * i] = -q.pos[3 * i];
        q.nrm[3 * i + 2] = -1;
    }
    uint8_t front[3];
    {
        struct gb g = {0};
        char *j = quad_gltf(&g, "{\"doubleSided\":true}", 1, "", "");
        struct mesh m;
        REQUIRE(load(j, &m, NULL) == 0);
        REQUIRE(centre(&m, SHADE_PHONG, front) == 0);
        mesh_free(&m);
        free(j);
    }
    for (int two = 0; two < 2; two++) {
        struct gb g = {0};
        int a[4];
        gb_quad_accs(&g, &q, a);
        char body[1024];
        snprintf(body, sizeof body,
                 "\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0}],\"meshes\":[{"
                 "\"primitives\":[{\"attributes\":{\"POSITION\":%d,\"NORMAL\":%d},\"indices\":"
                 "%d,\"material\":0}]}],\"materials\":[{\"doubleSided\":%s}]",
                 a[0], a[1], a[3], two ? "true" : "false");
        char *j = gb_json(&g, body);
        struct mesh m;
        REQUIRE(load(j, &m, NULL) == 0);
        uint8_t c[3];
        REQUIRE(centre(&m, SHADE_PHONG, c) == 0);
        if (two)
            CHECK_RGB(c, front[0], front[1], front[2]);
        else
            CHECK_RGB(c, 0, 0, 0);
        mesh_free(&m);
        free(j);
    }
}

TEST(gltf_spec_gloss_and_unlit_materials)
{
    /* KHR_materials_pbrSpecularGlossiness: its diffuse factor is the base colour (it drew
     * black); unlit: the colour alone */
    struct gb g = {0};
    char *j = quad_gltf(&g,
                        "{\"extensions\":{\"KHR_materials_pbrSpecularGlossiness\":{"
                        "\"diffuseFactor\":[0.2,0.2,0.2,1],\"specularFactor\":[0,0,0],"
                        "\"glossinessFactor\":0.5}}}",
                        1, "", "\"extensionsUsed\":[\"KHR_materials_pbrSpecularGlossiness\"]");
    struct mesh m;
    REQUIRE(load(j, &m, NULL) == 0);
    uint8_t c[3];
    REQUIRE(centre(&m, SHADE_UNLIT, c) == 0);
    CHECK_RGB(c, 124, 124, 124);
    const struct material *mat = &m.materials[m.tri_material[0]];
    CHECK(mat->ks[0] == 0); /* no specular colour: no highlight */
    CHECK(mat->ns > 1 && mat->ns < 64);
    mesh_free(&m);
    free(j);
}

TEST(gltf_metallic_roughness_sets_the_highlight)
{
    /* the Blinn-Phong exponent from the roughness (n = 2 / r^4 - 2: 0.5 -> 30, 1 -> 1) and
     * a metal's highlight in its own colour (light.h's mapping) */
    struct gb g = {0};
    char *j = quad_gltf(&g,
                        "{\"pbrMetallicRoughness\":{\"baseColorFactor\":[1,0.5,0.1,1],"
                        "\"metallicFactor\":1,\"roughnessFactor\":0.5}}",
                        1, "", "");
    struct mesh m;
    REQUIRE(load(j, &m, NULL) == 0);
    const struct material *mat = &m.materials[m.tri_material[0]];
    CHECK_NEAR(mat->ns, 30, 0);
    CHECK(mat->ks[0] > mat->ks[1] && mat->ks[1] > mat->ks[2]); /* the metal's hue */
    CHECK_NEAR(mat->ks[0], 1, 1e-6);
    mesh_free(&m);
    free(j);
    struct gb g2 = {0};
    j = quad_gltf(&g2, "{\"pbrMetallicRoughness\":{\"metallicFactor\":0,\"roughnessFactor\":1}}",
                  1, "", "");
    REQUIRE(load(j, &m, NULL) == 0);
    mat = &m.materials[m.tri_material[0]];
    CHECK_NEAR(mat->ns, 1, 0);
    CHECK(mat->ks[0] < 0.3f && mat->ks[0] == mat->ks[2]); /* a dull grey highlight */
    mesh_free(&m);
    free(j);
}

/* a 1x1 texture image's data URI */
static char *texel_uri(uint8_t r, uint8_t g, uint8_t b)
{
    const uint8_t px[4] = {r, g, b, 255};
    return gb_png_uri(1, 1, px);
}

TEST(gltf_normal_and_occlusion_maps)
{
    /* a normal map tilting the quad's normal toward the light (+x: tangent space, the
     * tangents generated from the uvs) brightens it; an occlusion texture of 0 takes the
     * ambient away */
    uint8_t plain[3], bent[3], dark[3];
    struct mesh m;
    struct gb g = {0};
    char *j = quad_gltf(&g, "{\"pbrMetallicRoughness\":{\"metallicFactor\":0}}", 1, "", "");
    REQUIRE(load(j, &m, NULL) == 0);
    REQUIRE(centre(&m, SHADE_PHONG, plain) == 0);
    mesh_free(&m);
    free(j);
    char *uri = texel_uri(218, 128, 218); /* (0.71, 0, 0.71) */
    char rest[1024];
    snprintf(rest, sizeof rest, "\"textures\":[{\"source\":0}],\"images\":[{\"uri\":\"%s\"}]", uri);
    free(uri);
    struct gb g2 = {0};
    j = quad_gltf(&g2, "{\"pbrMetallicRoughness\":{\"metallicFactor\":0},\"normalTexture\":"
                       "{\"index\":0}}",
                  1, "", rest);
    REQUIRE(load(j, &m, NULL) == 0);
    REQUIRE(m.tangents);
    CHECK_NEAR(m.tangents[0][0], 1, 1e-6); /* dP/du is +x */
    REQUIRE(centre(&m, SHADE_PHONG, bent) == 0);
    mesh_free(&m);
    free(j);
    CHECK(bent[0] > plain[0] + 20);
    uri = texel_uri(0, 0, 0);
    snprintf(rest, sizeof rest, "\"textures\":[{\"source\":0}],\"images\":[{\"uri\":\"%s\"}]", uri);
    free(uri);
    struct gb g3 = {0};
    j = quad_gltf(&g3, "{\"pbrMetallicRoughness\":{\"metallicFactor\":0},\"occlusionTexture\":"
                       "{\"index\":0}}",
                  1, "", rest);
    REQUIRE(load(j, &m, NULL) == 0);
    REQUIRE(centre(&m, SHADE_PHONG, dark) == 0);
    mesh_free(&m);
    free(j);
    /* ambient 0.1 of albedo 1: 25 or 26 levels lower */
    CHECK(plain[0] - dark[0] >= 25 && plain[0] - dark[0] <= 26);
}

TEST(gltf_extensions_required_and_used)
{
    /* a required extension rastty cannot draw: an error naming it; a used one: a warning */
    struct gb g = {0};
    char *j = quad_gltf(&g, "{}", 1, "",
                        "\"extensionsUsed\":[\"KHR_future_thing\"],\"extensionsRequired\":"
                        "[\"KHR_future_thing\"]");
    struct mesh m;
    struct err e;
    CHECK_EQ_INT(gb_load(j, strlen(j), NULL, &m, NULL, &e), -1);
    CHECK_STR_CONTAINS(e.msg, "requires extension KHR_future_thing");
    free(j);
    struct gb g2 = {0};
    j = quad_gltf(&g2, "{}", 1, "", "\"extensionsUsed\":[\"KHR_future_thing\","
                                    "\"KHR_materials_clearcoat\"]");
    struct warnings w;
    REQUIRE(gb_load(j, strlen(j), NULL, &m, &w, &e) == 0);
    REQUIRE(w.n == 2);
    CHECK_STR_CONTAINS(w.msg[0], "extension KHR_future_thing is not supported");
    CHECK_STR_CONTAINS(w.msg[1], "KHR_materials_clearcoat is not drawn");
    mesh_free(&m);
    free(j);
}

TEST(gltf_meshopt_compression_is_decoded)
{
    /* EXT_meshopt_compression: the quad's positions and indices compressed by
     * meshoptimizer's encoders, the fallback buffer without data: the same quad */
    static struct gb_quad q;
    gb_quad(&q, 0, 1, 1);
    float pos4[16]; /* ATTRIBUTES want strides of 4n: xyz + padding */
    for (int i = 0; i < 4; i++)
        for (int k = 0; k < 4; k++)
            pos4[4 * i + k] = k < 3 ? q.pos[3 * i + k] : 0;
    uint32_t idx[6] = {0, 1, 2, 0, 2, 3};
    uint8_t vbuf[256], ibuf[256];
    size_t vn = meshopt_encodeVertexBuffer(vbuf, sizeof vbuf, pos4, 4, 16);
    size_t in = meshopt_encodeIndexBuffer(ibuf, sizeof ibuf, idx, 6);
    REQUIRE(vn > 0 && in > 0);
    struct gb g = {0};
    int v0 = gb_view(&g, vbuf, vn, ""), v1 = gb_view(&g, ibuf, in, "");
    (void)v0, (void)v1;
    char *b64 = gb_base64(g.bin, g.n);
    char *j = malloc(8192);
    snprintf(j, 8192,
             "{\"asset\":{\"version\":\"2.0\"},\"extensionsUsed\":[\"EXT_meshopt_compression\"],"
             "\"extensionsRequired\":[\"EXT_meshopt_compression\"],"
             "\"buffers\":[{\"byteLength\":%zu,\"uri\":\"data:application/octet-stream;base64,%s\"},"
             "{\"byteLength\":88,\"extensions\":{\"EXT_meshopt_compression\":{\"fallback\":true}}}],"
             "\"bufferViews\":[{\"buffer\":1,\"byteLength\":64,\"byteStride\":16,\"extensions\":"
             "{\"EXT_meshopt_compression\":{\"buffer\":0,\"byteOffset\":0,\"byteLength\":%zu,"
             "\"byteStride\":16,\"count\":4,\"mode\":\"ATTRIBUTES\"}}},"
             "{\"buffer\":1,\"byteOffset\":64,\"byteLength\":24,\"extensions\":"
             "{\"EXT_meshopt_compression\":{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu,"
             "\"byteStride\":4,\"count\":6,\"mode\":\"TRIANGLES\"}}}],"
             "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":4,\"type\":\"VEC3\","
             "\"min\":[-0.9,-0.9,0],\"max\":[0.9,0.9,0]},{\"bufferView\":1,\"componentType\":5125,"
             "\"count\":6,\"type\":\"SCALAR\"}],"
             "\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0}],\"meshes\":[{\"primitives\":"
             "[{\"attributes\":{\"POSITION\":0},\"indices\":1}]}]}",
             g.n, b64, vn, (vn + 3) & ~(size_t)3, in);
    free(b64);
    struct mesh m;
    REQUIRE(load(j, &m, NULL) == 0);
    CHECK_EQ_INT(m.n_tris, 2);
    CHECK_NEAR(m.bbox_min[0], -0.9, 1e-6);
    CHECK_NEAR(m.bbox_max[1], 0.9, 1e-6);
    mesh_free(&m);
    free(j);
}

/* ---- what is refused, and how it says so ---- */

TEST(gltf_refuses_broken_accessors_with_the_reason)
{
    /* a VEC7 accessor and a byteStride of 3 were a blank picture with exit 0 */
    struct gb g = {0};
    static struct gb_quad q;
    gb_quad(&q, 0, 1, 1);
    int a[4];
    gb_quad_accs(&g, &q, a);
    char *j = gb_json(&g, "\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0}],\"meshes\":[{"
                          "\"primitives\":[{\"attributes\":{\"POSITION\":0}}]}]");
    char *k = strstr(j, "\"VEC3\"");
    REQUIRE(k);
    memcpy(k, "\"VEC7\"", 6);
    struct mesh m;
    struct err e;
    CHECK_EQ_INT(gb_load(j, strlen(j), NULL, &m, NULL, &e), -1);
    CHECK_STR_CONTAINS(e.msg, "accessor 0: type 'VEC7' is not a glTF accessor type");
    CHECK_STR_CONTAINS(e.msg, "<memory>: byte ");
    free(j);
    struct gb g2 = {0};
    gb_quad_accs(&g2, &q, a);
    char *s = strstr(g2.views, "}");
    REQUIRE(s);
    memmove(s + 15, s, strlen(s) + 1);
    memcpy(s, ",\"byteStride\":3", 15);
    j = gb_json(&g2, "\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0}],\"meshes\":[{"
                     "\"primitives\":[{\"attributes\":{\"POSITION\":0}}]}]");
    CHECK_EQ_INT(gb_load(j, strlen(j), NULL, &m, NULL, &e), -1);
    CHECK_STR_CONTAINS(e.msg, "byteStride must be a multiple of 4");
    free(j);
}

TEST(gltf_json_errors_name_the_byte)
{
    static const char bad[] = "{\"asset\":{\"version\":\"2.0\"},\n\"meshes\":[ }";
    struct mesh m;
    struct err e;
    CHECK_EQ_INT(gb_load(bad, strlen(bad), NULL, &m, NULL, &e), -1);
    /* issue 25: a JSON of several lines is named by line and column too */
    CHECK(strcmp(e.msg, "<memory>: byte 39 (line 2, column 12): not valid JSON: a value "
                        "(object, array, string, number, true, false or null), got '}'") == 0);
    /* a glTF error after parsing, in a file of several lines: the member's line */
    static const char wrong[] = "{\n  \"asset\": {\"version\": \"3.0\"}\n}\n";
    CHECK_EQ_INT(gb_load(wrong, strlen(wrong), NULL, &m, NULL, &e), -1);
    CHECK(strcmp(e.msg, "<memory>: byte 25 (line 2, column 24): glTF version '3.0' (rastty "
                        "reads 2.x)") == 0);
    /* a collection that is no array was taken for none: "no triangles" */
    static const char notarr[] = "{\n  \"asset\": {\"version\": \"2.0\"},\n  \"meshes\": 7\n}\n";
    CHECK_EQ_INT(gb_load(notarr, strlen(notarr), NULL, &m, NULL, &e), -1);
    CHECK(strcmp(e.msg, "<memory>: byte 45 (line 3, column 13): \"meshes\" must be an array") ==
          0);
    static const char none[] = "{\"asset\":{\"version\":\"2.0\"},\"meshes\":[]}";
    CHECK_EQ_INT(gb_load(none, strlen(none), NULL, &m, NULL, &e), -1);
    CHECK_STR_CONTAINS(e.msg, "no triangles (the file has no meshes)");
}

/* issue 25: a model's references stay in its folder tree unless --allow-outside */
TEST(gltf_references_stay_in_the_models_folder)
{
    char dir[96], sub[128], path[160], out[160];
    snprintf(dir, sizeof dir, "/tmp/rastty-confine-%d", (int)getpid());
    snprintf(sub, sizeof sub, "%s/model", dir);
    mkdir(dir, 0700);
    mkdir(sub, 0700);
    /* the buffer beside the folder: ../quad.bin */
    static struct gb_quad q;
    gb_quad(&q, 0, 1, 1);
    struct gb g = {0};
    int a[4];
    gb_quad_accs(&g, &q, a);
    snprintf(out, sizeof out, "%s/quad.bin", dir);
    FILE *f = fopen(out, "wb");
    REQUIRE(f);
    fwrite(g.bin, 1, g.n, f);
    fclose(f);
    const char *uris[3] = {"../quad.bin", "%2e%2e/quad.bin", out};
    for (int i = 0; i < 3; i++) {
        char *j = malloc(40000);
        snprintf(j, 40000,
                 "{\"asset\":{\"version\":\"2.0\"},\"buffers\":[{\"byteLength\":%zu,\"uri\":"
                 "\"%s\"}],\"bufferViews\":[%s],\"accessors\":[%s],\"scenes\":[{\"nodes\":[0]}],"
                 "\"nodes\":[{\"mesh\":0}],\"meshes\":[{\"primitives\":[{\"attributes\":"
                 "{\"POSITION\":0},\"indices\":3}]}]}",
                 g.n, uris[i], g.views, g.accs);
        snprintf(path, sizeof path, "%s/m.gltf", sub);
        f = fopen(path, "w");
        REQUIRE(f);
        fputs(j, f);
        fclose(f);
        free(j);
        struct mesh m;
        struct err e;
        CHECK_EQ_INT(model_load(path, NULL, NULL, &m, &e), -1);
        CHECK_STR_CONTAINS(e.msg, "outside the model's folder (--allow-outside reads it)");
        struct model_opts any = {.any_path = true};
        CHECK_EQ_INT(model_load_with(path, &any, NULL, NULL, &m, &e), 0);
        if (m.n_tris)
            CHECK_EQ_INT(m.n_tris, 2);
        mesh_free(&m);
    }
    /* inside the folder: read */
    snprintf(out, sizeof out, "%s/quad.bin", sub);
    rename((snprintf(path, sizeof path, "%s/quad.bin", dir), path), out);
    char *j = malloc(40000);
    snprintf(j, 40000,
             "{\"asset\":{\"version\":\"2.0\"},\"buffers\":[{\"byteLength\":%zu,\"uri\":"
             "\"quad.bin\"}],\"bufferViews\":[%s],\"accessors\":[%s],\"scenes\":[{\"nodes\":[0]}],"
             "\"nodes\":[{\"mesh\":0}],\"meshes\":[{\"primitives\":[{\"attributes\":"
             "{\"POSITION\":0},\"indices\":3}]}]}",
             g.n, g.views, g.accs);
    snprintf(path, sizeof path, "%s/m.gltf", sub);
    f = fopen(path, "w");
    REQUIRE(f);
    fputs(j, f);
    fclose(f);
    free(j);
    struct mesh m;
    struct err e;
    CHECK_EQ_INT(model_load(path, NULL, NULL, &m, &e), 0);
    mesh_free(&m);
    unlink(path);
    unlink(out);
    rmdir(sub);
    rmdir(dir);
}

TEST(gltf_glb_and_cameras)
{
    /* the same quad as a GLB, with two cameras the nodes carry: perspective and
     * orthographic, placed by their nodes */
    struct gb g = {0};
    static struct gb_quad q;
    gb_quad(&q, 0, 1, 1);
    int a[4];
    gb_quad_accs(&g, &q, a);
    char body[2048];
    snprintf(body, sizeof body,
             "\"scenes\":[{\"nodes\":[0,1,2]}],\"nodes\":[{\"mesh\":0},{\"camera\":0,"
             "\"translation\":[0,0,5]},{\"camera\":1,\"translation\":[1,2,3],\"rotation\":"
             "[0,0.7071068,0,0.7071068]}],\"cameras\":[{\"type\":\"perspective\",\"perspective\":"
             "{\"yfov\":0.5,\"znear\":0.1}},{\"type\":\"orthographic\",\"orthographic\":{\"xmag\":2,"
             "\"ymag\":1.5,\"znear\":0.1,\"zfar\":10}}],\"meshes\":[{\"primitives\":[{\"attributes\":"
             "{\"POSITION\":%d},\"indices\":%d}]}]",
             a[0], a[3]);
    size_t len;
    char *glb = gb_glb(&g, body, &len);
    struct mesh m;
    struct err e;
    REQUIRE(gb_load(glb, len, NULL, &m, NULL, &e) == 0);
    CHECK_EQ_INT(m.n_tris, 2);
    REQUIRE(m.n_cameras == 2);
    CHECK_NEAR(m.cameras[0].eye[2], 5, 1e-6);
    CHECK_NEAR(m.cameras[0].forward[2], -1, 1e-6);
    CHECK_NEAR(m.cameras[0].yfov_deg, 0.5 * 180 / M_PI, 1e-4);
    CHECK_NEAR(m.cameras[1].ortho_height, 3, 1e-6);
    CHECK_NEAR(m.cameras[1].eye[0], 1, 1e-6);
    CHECK_NEAR(m.cameras[1].forward[0], -1, 1e-6); /* turned a quarter about +y: -z -> -x */
    mesh_free(&m);
    free(glb);
}

TEST(gltf_rough_metal_highlight_is_weighted_by_n_dot_l)
{
    /* glTF's default material (metallic 1, roughness 1: Blinn-Phong ns 1) in red, facing
     * the camera (+z, orthographic), light toward (1,1,1): no diffuse (a metal), the ambient
     * 0.1, and the highlight ks N.H = 0.888 weighted by N.L = 0.577 as a BRDF's radiance
     * is: 0.1 + 0.512 -> 156. Without the weight it was 252 (and 255 on every face of a
     * box, where the sample viewer shows 147, 123, 70). */
    struct gb g = {0};
    char *j = quad_gltf(&g, "{\"pbrMetallicRoughness\":{\"baseColorFactor\":[1,0,0,1]}}", 1,
                        "", "");
    struct mesh m;
    REQUIRE(load(j, &m, NULL) == 0);
    CHECK(m.features); /* a metal: the features path */
    uint8_t c[3];
    REQUIRE(centre(&m, SHADE_PHONG, c) == 0);
    CHECK(c[0] >= 155 && c[0] <= 157 && c[1] == 0 && c[2] == 0);
    mesh_free(&m);
    free(j);
}

TEST(gltf_instanced_past_the_limit_fails_with_a_reason_at_once)
{
    /* a mesh of 1M triangles (indices without a buffer view: zeros) instanced 20 times by
     * EXT_mesh_gpu_instancing: 20M triangles, past GLTF_MAX_TRIS; the reason is given
     * before anything is built (assimp said 'glb_instanced_120.glb: ' and nothing more) */
    struct gb g = {0};
    static struct gb_quad q;
    gb_quad(&q, 0, 1, 1);
    int a[4];
    gb_quad_accs(&g, &q, a);
    size_t l = strlen(g.accs);
    snprintf(g.accs + l, sizeof g.accs - l,
             ",{\"componentType\":5125,\"count\":3000000,\"type\":\"SCALAR\"},"
             "{\"componentType\":5126,\"count\":20,\"type\":\"VEC3\"}");
    int ii = g.n_accs++, ti = g.n_accs++;
    char body[1024];
    snprintf(body, sizeof body,
             "\"extensionsUsed\":[\"EXT_mesh_gpu_instancing\"],\"scenes\":[{\"nodes\":[0]}],"
             "\"nodes\":[{\"mesh\":0,\"extensions\":{\"EXT_mesh_gpu_instancing\":{\"attributes\":"
             "{\"TRANSLATION\":%d}}}}],\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":"
             "%d},\"indices\":%d}]}]",
             ti, a[0], ii);
    char *j = gb_json(&g, body);
    struct mesh m;
    struct err e;
    CHECK_EQ_INT(gb_load(j, strlen(j), NULL, &m, NULL, &e), -1);
    CHECK_STR_CONTAINS(e.msg, "20 instances of 1000000 triangles make more than 16777216");
    free(j);
}
