/* generate.c: writes rastty's built-in assets into the directory given as argv[1].
 *
 *   build/generate-assets assets
 *
 * Everything is made here from formulas and public-domain data (Newell's teapot patches);
 * nothing is copied from elsewhere. Output is deterministic: two runs write identical bytes.
 * Files (see assets/assets.mk, ASSET_FILES):
 *   teapot.obj/.mtl   Utah teapot, TEAPOT_STEPS^2 quads per patch, colour only
 *   cube, sphere, torus .obj/.mtl   textured primitives (uvgrid.png, uvgrid.png, stripes.png)
 *   floor.obj/.mtl    20 x 20 units at y = 0, checker.png repeated 10 times
 *   checker.png brick.png uvgrid.png stripes.png   textures (brick is for scene overrides)
 *   sky_{posx,negx,posy,negy,posz,negz}.png        procedural sky cubemap (sky.c)
 * Module contracts are in gen/gen.h; sizes and orientations in each module's header comment. */
#include "gen/gen.h"

#include <stdio.h>
#include <stdlib.h>

#define STR_(x) #x
#define STR(x) STR_(x)

#define TEAPOT_STEPS 10
#define SPHERE_STACKS 24
#define SPHERE_SLICES 48
#define TORUS_RINGS 48
#define TORUS_SIDES 24
#define TEXTURE_SIZE 512
#define CHECKER_SIZE 256
#define SKY_SIZE 256

struct model {
    const char *name;
    const char *comment;
    struct trimesh_material mat;
};

static int write_model(const char *dir, const struct model *md, struct trimesh *m,
                       struct gen_err *e)
{
    int rc = trimesh_write_obj(m, dir, md->name, md->mat.name, md->comment, e);
    if (rc == 0)
        rc = trimesh_write_mtl(&md->mat, dir, md->name, e);
    trimesh_free(m);
    return rc;
}

static int write_models(const char *dir, struct gen_err *e)
{
    static const struct model TEAPOT = {
        "teapot",
        "Utah teapot (Martin Newell, 1975; public-domain Bezier patch data), made by rastty's\n"
        "assets/generate.c. Y up; 2 units wide along X (spout +X, handle -X); bottom at y = 0;\n"
        "centred in X and Z. 32 patches, patch resolution "
        STR(TEAPOT_STEPS) " x " STR(TEAPOT_STEPS) "; open edges only at the\n"
        "lid rim, body rim, spout ends and handle ends.",
        { "teapot", { 0.85, 0.42, 0.26 }, 0.5, 32.0, NULL },
    };
    static const struct model CUBE = {
        "cube",
        "Cube made by rastty's assets/generate.c: edge 1, centred at the origin, each face\n"
        "maps the whole texture upright, watertight.",
        { "cube", { 1, 1, 1 }, 0.5, 32.0, "uvgrid.png" },
    };
    static const struct model SPHERE = {
        "sphere",
        "UV sphere made by rastty's assets/generate.c: radius 0.5, "
        STR(SPHERE_STACKS) " stacks x " STR(SPHERE_SLICES) " slices,\n"
        "one vertex per pole, texture seam at -Z (u = 0.5 faces +Z), watertight.",
        { "sphere", { 1, 1, 1 }, 0.5, 32.0, "uvgrid.png" },
    };
    static const struct model TORUS = {
        "torus",
        "Torus made by rastty's assets/generate.c: axis Y, major radius 0.35, tube radius\n"
        "0.15, " STR(TORUS_RINGS) " x " STR(TORUS_SIDES)
        " segments, u in [0,2] around the axis, watertight.",
        { "torus", { 1, 1, 1 }, 0.5, 32.0, "stripes.png" },
    };
    static const struct model FLOOR = {
        "floor",
        "Floor made by rastty's assets/generate.c: 20 x 20 units at y = 0, normal +Y,\n"
        "texture repeated 10 times each way (1 unit checker squares).",
        { "floor", { 1, 1, 1 }, 0.15, 16.0, "checker.png" },
    };
    struct trimesh m;
    trimesh_init(&m);
    teapot_build(&m, TEAPOT_STEPS);
    if (write_model(dir, &TEAPOT, &m, e))
        return -1;
    shapes_cube(&m);
    if (write_model(dir, &CUBE, &m, e))
        return -1;
    shapes_sphere(&m, SPHERE_STACKS, SPHERE_SLICES);
    if (write_model(dir, &SPHERE, &m, e))
        return -1;
    shapes_torus(&m, TORUS_RINGS, TORUS_SIDES);
    if (write_model(dir, &TORUS, &m, e))
        return -1;
    shapes_floor(&m);
    return write_model(dir, &FLOOR, &m, e);
}

static int write_textures(const char *dir, struct gen_err *e)
{
    static const struct {
        const char *name;
        int size;
        void (*make)(unsigned char *rgb_out, int size);
    } TEX[] = {
        { "checker.png", CHECKER_SIZE, pattern_checker },
        { "brick.png", TEXTURE_SIZE, pattern_brick },
        { "uvgrid.png", TEXTURE_SIZE, pattern_uvgrid },
        { "stripes.png", TEXTURE_SIZE, pattern_stripes },
    };
    unsigned char *rgb = malloc((size_t)TEXTURE_SIZE * TEXTURE_SIZE * 3);
    if (!rgb)
        return gen_err_set(e, "out of memory");
    int rc = 0;
    for (size_t i = 0; i < sizeof TEX / sizeof TEX[0] && rc == 0; i++) {
        TEX[i].make(rgb, TEX[i].size);
        rc = gen_write_png(dir, TEX[i].name, TEX[i].size, TEX[i].size, rgb, e);
    }
    for (int f = 0; f < SKY_FACE_COUNT && rc == 0; f++) {
        char name[32];
        snprintf(name, sizeof name, "sky_%s.png", SKY_FACE_NAME[f]);
        sky_face_image((enum sky_face)f, SKY_SIZE, rgb);
        rc = gen_write_png(dir, name, SKY_SIZE, SKY_SIZE, rgb, e);
    }
    free(rgb);
    return rc;
}

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: %s OUTPUT_DIR\n", argc > 0 ? argv[0] : "generate-assets");
        return 2;
    }
    struct gen_err e = { { 0 } };
    if (write_textures(argv[1], &e) || write_models(argv[1], &e)) {
        fprintf(stderr, "generate-assets: %s\n", e.msg);
        return 1;
    }
    return 0;
}
