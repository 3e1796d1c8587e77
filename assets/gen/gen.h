/* gen.h: shared contract of rastty's asset generator (build/generate-assets).
 * A build tool, not part of rastty: it links nothing from src/, only libc, libm and stb.
 * It writes every built-in asset (OBJ, MTL, PNG) into one output directory.
 *
 * Modules: gen.c (errors, paths, hashing, vectors, PNG writer), trimesh.c (triangle meshes,
 * OBJ/MTL writers), teapot.c (Bezier patches -> mesh), shapes.c (cube, sphere, torus, floor),
 * pattern.c (procedural textures), sky.c (procedural sky cubemap faces). The names avoid
 * rastty's own modules (src/mesh.c, src/texture.c) so that a grep finds one definition.
 *
 * Conventions (the same as rastty's):
 *   - Right-handed, Y up. Meshes wind counter-clockwise seen from outside; every vn points
 *     outward; a texture looks unmirrored from outside (du x dv points outward).
 *   - OBJ vt v = 1 is the top row of the image; texture images are stored top row first.
 *   - Deterministic: no clocks, no rand(); pseudo-random values come from gen_hash32().
 *     Numbers are printed with fixed "%.6f"; -0 is printed as 0.
 * Errors: fallible functions return 0 or -1 and fill struct gen_err; only main prints. */
#ifndef ASSETS_GEN_H
#define ASSETS_GEN_H

#include <stddef.h>
#include <stdint.h>

struct gen_err { char msg[256]; };

/* Formats msg into e (one line) and returns -1. */
int gen_err_set(struct gen_err *e, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
/* Joins dir and name into path_out (size cap); -1 if it does not fit. */
int gen_path(char *path_out, size_t cap, const char *dir, const char *name, struct gen_err *e);
/* A well-mixed 32-bit integer hash: the generator's only source of "randomness". */
uint32_t gen_hash32(uint32_t x);
/* gen_hash32 of (a, b, c) mapped to [0, 1). */
double gen_rand01(uint32_t a, uint32_t b, uint32_t c);
/* Writes dir/name as an 8-bit RGB PNG (rgb: w*h*3 bytes, row 0 = top). */
int gen_write_png(const char *dir, const char *name, int w, int h,
                  const unsigned char *rgb, struct gen_err *e);

/* ---- vectors: a small value type; gen_len and gen_norm are in gen.c ---- */
typedef struct { double x, y, z; } gen_vec3;

static inline gen_vec3 gen_vec(double x, double y, double z)
{
    gen_vec3 r = { x, y, z };
    return r;
}
static inline gen_vec3 gen_add(gen_vec3 a, gen_vec3 b)
{
    return gen_vec(a.x + b.x, a.y + b.y, a.z + b.z);
}
static inline gen_vec3 gen_sub(gen_vec3 a, gen_vec3 b)
{
    return gen_vec(a.x - b.x, a.y - b.y, a.z - b.z);
}
static inline gen_vec3 gen_scale(gen_vec3 a, double s)
{
    return gen_vec(a.x * s, a.y * s, a.z * s);
}
static inline double gen_dot(gen_vec3 a, gen_vec3 b)
{
    return a.x * b.x + a.y * b.y + a.z * b.z;
}
static inline gen_vec3 gen_cross(gen_vec3 a, gen_vec3 b)
{
    return gen_vec(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}
double gen_len(gen_vec3 a);
gen_vec3 gen_norm(gen_vec3 a);   /* (0,0,0) stays (0,0,0) */

/* ---- trimesh.c ---- */
struct trimesh_tri { int v[3], vt[3], vn[3]; };   /* 0-based indices into the arrays below */

/* A triangle mesh with OBJ-style separate index spaces for v, vt and vn. Adding grows the
 * arrays; an allocation failure sets failed, makes later adds no-ops and makes
 * trimesh_write_obj fail. */
struct trimesh {
    gen_vec3 *v;  int nv,  cap_v;
    gen_vec3 *vn; int nvn, cap_vn;
    double (*vt)[2]; int nvt, cap_vt;
    struct trimesh_tri *tri; int ntri, cap_tri;
    int failed;
};

/* One MTL material. map_kd may be NULL (colour only). */
struct trimesh_material {
    const char *name;
    double kd[3];
    double ks;          /* specular strength, written as "Ks ks ks ks" */
    double ns;          /* specular exponent */
    const char *map_kd; /* file name relative to the MTL file */
};

void trimesh_init(struct trimesh *m);
void trimesh_free(struct trimesh *m);
/* The adders return the new element's 0-based index (-1 after an allocation failure). */
int trimesh_add_v(struct trimesh *m, gen_vec3 p);
int trimesh_add_vn(struct trimesh *m, gen_vec3 n);
int trimesh_add_vt(struct trimesh *m, double u, double v);
void trimesh_add_tri(struct trimesh *m, const int v[3], const int vt[3], const int vn[3]);
/* Writes dir/name.obj referencing name.mtl and material mtl_name. comment: lines of text
 * written as "# ..." at the top (may contain '\n'). */
int trimesh_write_obj(const struct trimesh *m, const char *dir, const char *name,
                      const char *mtl_name, const char *comment, struct gen_err *e);
int trimesh_write_mtl(const struct trimesh_material *mat, const char *dir, const char *name,
                      struct gen_err *e);

/* ---- teapot.c ---- */
/* Tessellates the 32 Newell patches, steps x steps quads each, into m (see teapot.c for the
 * placement: Y up, 2 units wide along X, bottom at y = 0, centred in X and Z). */
void teapot_build(struct trimesh *m, int steps);

/* ---- shapes.c ---- (sizes in shapes.c's header comment) */
void shapes_cube(struct trimesh *m);
void shapes_sphere(struct trimesh *m, int stacks, int slices);
void shapes_torus(struct trimesh *m, int rings, int sides);
void shapes_floor(struct trimesh *m);

/* ---- texture.c ---- RGB8 images, row 0 = top, w*h*3 bytes, caller-allocated. */
void pattern_checker(unsigned char *rgb_out, int size);
void pattern_brick(unsigned char *rgb_out, int size);
void pattern_uvgrid(unsigned char *rgb_out, int size);
void pattern_stripes(unsigned char *rgb_out, int size);

/* ---- sky.c ---- */
enum sky_face { SKY_POSX, SKY_NEGX, SKY_POSY, SKY_NEGY, SKY_POSZ, SKY_NEGZ, SKY_FACE_COUNT };
extern const char *const SKY_FACE_NAME[SKY_FACE_COUNT];   /* "posx", ... */
/* Direction (not normalised) of face point (sc, tc), both in [-1, 1]; see sky.c. */
gen_vec3 sky_face_dir(enum sky_face f, double sc, double tc);
/* Sky colour, each channel in [0, 1], seen along unit direction d. */
gen_vec3 sky_colour(gen_vec3 d);
void sky_face_image(enum sky_face f, int size, unsigned char *rgb_out);

#endif
