/* mesh.h: an indexed triangle mesh with its materials, as loaded from disk.
 *
 * Loaded once (a loader of model.h fills it), never modified by rendering. Vertices are unique
 * (position, uv, normal, material) combinations, like a GPU vertex buffer, so the vertex stage
 * transforms each one once per frame and every triangle is three indices into them; the
 * positions they share (pos_id) let the front end project each position once instead.
 *
 * Spaces and units: object space, whatever units the file uses. Normals are unit length.
 * Missing normals (a corner without `vn`) are the area-weighted average of the face normals
 * (cross(p1-p0, p2-p0), unnormalised, from the file's winding) of the triangles around the
 * same position index that lie on the corner's side of every crease, normalised; a position
 * whose faces sum to zero gets (0,0,1). A crease is an edge (two positions two triangles
 * share) across which the face normals turn by more than the crease angle
 * (mesh_source.crease_deg, MESH_CREASE_DEFAULT: auto-smooth, as Blender's and f3d's): at a
 * position with no crease every triangle around it counts (the smooth normal of the
 * conventions, the same bits as without creases); at one with creases the triangles around
 * it fall into fans joined by their uncreased shared edges, and each fan has its own
 * normal, so a cube keeps flat faces and sharp edges while a sphere stays smooth. Crease
 * angle 0: flat faces everywhere (glTF's rule for primitives without normals); 180 or
 * more: one smooth normal per position.
 * Missing uvs are (0,0). */
#ifndef RASTTY_MESH_H
#define RASTTY_MESH_H

#include <stdbool.h>
#include <stdint.h>

#include "err.h"
#include "texture.h"

#define MESH_NAME_MAX 64

/* How a texture is read by a material (glTF's textureInfo with its sampler and
 * KHR_texture_transform): which image, on which uv set, wrapped how, moved how. */
enum tex_wrap { TEX_WRAP_REPEAT, TEX_WRAP_CLAMP, TEX_WRAP_MIRROR };
struct tex_slot {
    int tex;          /* index into mesh.textures, or -1: none */
    uint8_t uv;       /* the uv set: 0 (OBJ vt, glTF TEXCOORD_0) or 1 (TEXCOORD_1) */
    uint8_t wrap[2];  /* u and v: enum tex_wrap */
    bool nearest;     /* the sampler magnifies NEAREST (pixel art): nearest whatever --filter */
    bool xform;       /* xf applies (else the identity) */
    float xf[6];      /* uv' = (xf0 u + xf1 v + xf2, xf3 u + xf4 v + xf5), in rastty's uv space
                         (v up: glTF's transform conjugated by its v flip) */
    bool tile;        /* uv (after xf) wraps inside rect, not the image: u' = rect0 + (u -
                         floor u) rect2, v' likewise (dag.h: an atlas tile's faces merged) */
    float rect[4];    /* u0, v0, du, dv */
};

enum mat_alpha { MAT_OPAQUE, MAT_MASK, MAT_BLEND };
/* MAT_SIDES_ANY: the conventions' (OBJ and the formats without a rule): both sides drawn,
 * lit with the file's normal (--cull decides). MAT_ONE_SIDED: glTF doubleSided false: the
 * back faces culled under --cull auto. MAT_TWO_SIDED: glTF doubleSided true: both sides
 * drawn, a back face lit with its normal turned around. */
enum mat_sides { MAT_SIDES_ANY, MAT_ONE_SIDED, MAT_TWO_SIDED };
enum mat_normal_space { MAT_NORMAL_TANGENT, MAT_NORMAL_OBJECT };

/* How a material lights up is light.h's business. A mesh always has a material 0: the
 * implicit one for faces that name no material (kd = (1,1,1), ks = 0.5, ns = 32, no texture;
 * `implicit` set, so an untextured face gets light.h's default albedo 0.8 instead).
 * Colours are display values (light.h says how glTF's linear factors become them). The
 * fields after `implicit` are the material features beyond the conventions' Blinn-Phong
 * (glTF's, MTL's d, map_d and bump maps): a material whose `features` is set is drawn by
 * the features path (shade.h), every other one exactly as before they existed. */
struct material {
    char name[MESH_NAME_MAX]; /* sanitised (printable ASCII) */
    float kd[3];              /* diffuse albedo, multiplies the texture */
    float ks[3];              /* specular colour; default 0.5 */
    float ns;                 /* Blinn-Phong exponent; default 32 */
    int texture;              /* index into mesh.textures, or -1 */
    bool implicit;            /* no material was named: see light_base_color() */
    /* ---- features (shade.h's features path; mtl_default: none) ---- */
    bool features;            /* any of the below differs from its default */
    float alpha;              /* opacity: baseColorFactor's alpha, MTL d (1 - Tr); 1 */
    uint8_t alpha_mode;       /* enum mat_alpha (MASK: cut below alpha_cutoff) */
    uint8_t sides;            /* enum mat_sides */
    bool unlit;               /* KHR_materials_unlit: the colour is the albedo */
    float alpha_cutoff;       /* 0.5 */
    float emissive[3];        /* added light, display values; 0 */
    struct tex_slot base;     /* the base colour texture's slot (base.tex == texture) */
    struct tex_slot alpha_map;     /* MTL map_d: the opacity in its red channel */
    struct tex_slot emissive_map;  /* multiplies emissive */
    struct tex_slot normal_map;    /* normalTexture, MTL norm / bump / map_Bump */
    struct tex_slot occlusion_map; /* its red channel scales the ambient term */
    struct tex_slot spec_map;      /* metallic-roughness (G roughness, B metallic) */
    uint8_t normal_space;     /* enum mat_normal_space */
    float normal_scale;       /* the tangent-space normal's x and y scaled by it; 1 */
    float occlusion_strength; /* 1 */
    bool pbr;                 /* metallic-roughness: ks and ns follow spec_map per pixel */
    float metallic, roughness;     /* the factors (pbr) */
    float base_lin[3];        /* the base colour, linear (the metals' highlight colour) */
    float spec_lin[3];        /* dielectric specular colour, linear (KHR_materials_specular) */
};

struct mesh_vertex {
    float pos[3];
    float uv[2];
    float nrm[3];
};

/* A camera the file defines (glTF), placed in the model's space. */
struct mesh_camera {
    char name[MESH_NAME_MAX];
    float eye[3], forward[3], up[3]; /* forward, up: unit */
    float yfov_deg;                  /* perspective; 0 = orthographic */
    float ortho_height;              /* orthographic: the view's height (2 ymag) */
    float znear, zfar;               /* zfar 0: infinite */
};
#define MESH_MAX_CAMERAS 64

/* A cluster: a run of a mesh's triangles with its bounds (cluster.h builds them and says
 * what they hold). */
struct mesh_cluster {
    float center[3];     /* box, object space: center + sum of s_i half[i] axis[i], |s_i| <= 1 */
    float axis[3][3];    /* its axes: unit, orthogonal (to rounding; half[] allows for it) */
    float half[3];
    float cone_axis[3];  /* unit */
    float cone_cos;      /* every face normal n: dot(n, cone_axis) >= cone_cos */
    uint32_t tri_first;  /* its triangles: tri_first .. + n_tris - 1 (the file's order) */
    uint32_t v_end;      /* its highest vertex + 1 */
    uint32_t v_need;     /* the lowest vertex of it and of every later cluster */
    uint8_t n_tris;      /* 1 .. CLUSTER_MAX_TRIS */
    uint8_t flags;       /* CLUSTER_NO_BOUNDS, CLUSTER_NO_CONE, CLUSTER_ONE_SIDED */
};
enum { CLUSTER_NO_BOUNDS = 1, CLUSTER_NO_CONE = 2, CLUSTER_ONE_SIDED = 4 };

struct mesh_clusters {
    struct mesh_cluster *c; /* in the file's order: c[k] holds triangles k * CLUSTER_MAX_TRIS on */
    uint32_t n;
};

struct mesh {
    struct mesh_vertex *verts;
    uint32_t n_verts;
    uint32_t (*tris)[3];  /* triangle corners, indices into verts, in the file's winding */
    uint16_t *tri_material; /* per triangle, index into materials */
    uint16_t *vert_material; /* per vertex (vertices are unique per material), n_verts long */
    uint32_t n_tris;
    /* Positions: vertices whose position has the same bits (a uv or material seam makes
     * several) are one position, numbered in order of their first vertex: the front end
     * tests a triangle against its corners' positions, each projected once a frame
     * (frontend.c), before it makes any of its vertices. Whoever reorders or edits verts
     * calls mesh_share_positions again (or frees both and sets them NULL). */
    uint32_t *pos_id;   /* per vertex, its position (n_verts long), or NULL: none kept (a
                           mesh with more than one position for every two vertices) */
    float (*pos_xyz)[3]; /* per position, its coordinates (n_pos long): read together */
    uint32_t n_pos;
    struct material *materials; /* at least one */
    uint32_t n_materials;
    struct texture *textures; /* map_Kd images, loaded (owned, or borrowed from a cache) */
    uint32_t n_textures;
    uint8_t (*colors)[4]; /* per vertex colour (PLY, OBJ v x y z r g b, STL facet colours, glTF
                             COLOR_0; display values, alpha 255 unless the file has one),
                             n_verts long; NULL when the file has none. It multiplies the
                             albedo (and the alpha), interpolated like a uv. */
    float (*uv1)[2];      /* per vertex second uv set (glTF TEXCOORD_1), or NULL */
    float (*tangents)[4]; /* per vertex tangent (xyz unit, w the bitangent's sign: B = w N x T)
                             for tangent-space normal maps; NULL when no material has one */
    bool features;        /* some material has features (struct material): the features path */
    uint8_t one_sided;    /* triangles of MAT_ONE_SIDED materials (culled by --cull auto):
                             MESH_SIDES_NONE, _ALL or _SOME (model_finish) */
    uint32_t n_opaque;    /* triangles [0, n_opaque) are opaque or cut out; the rest blend
                             (MAT_BLEND), drawn after them back to front (mesh_build keeps
                             the file's order within each part) */
    struct mesh_camera *cameras; /* the file's cameras, or NULL */
    uint32_t n_cameras;
    bool has_uvs;     /* some corner had a vt */
    bool has_normals; /* some corner had a vn (others may have generated normals) */
    char file_up;     /* the file's up axis, 'x', 'y' or 'z' (its metadata, else its format's
                         convention; 0: y). model.c turns the mesh so that it is +Y */
    float bbox_min[3], bbox_max[3]; /* over the positions used by triangles */
    float center[3], radius;        /* bounding sphere: bbox centre, farthest used vertex */
    struct mesh_lod *lod; /* simplified levels (lod.h), or NULL; a level's own is NULL */
    struct mesh_dag *dag; /* the cluster hierarchy (dag.h), set (atomically) once complete,
                             or NULL; the hierarchy's own mesh points to it too */
    struct mesh_clusters *clusters; /* its opaque triangles in runs with bounds (cluster.h),
                                       or NULL: drawn triangle by triangle; whoever edits
                                       tris or verts frees them (mesh_free_clusters) */
};

enum { MESH_SIDES_NONE, MESH_SIDES_ALL, MESH_SIDES_SOME };

/* Building a mesh from corner-indexed data (what an OBJ file or a generator describes).
 * Each triangle corner names a position, a uv (or MESH_NONE) and a normal (or MESH_NONE),
 * all 0-based into the arrays below. */
#define MESH_NONE UINT32_MAX
struct mesh_corner {
    uint32_t pos, uv, nrm;
};
struct mesh_source {
    const float *pos; /* n_pos * 3 */
    const float *uv;  /* n_uv * 2, may be NULL when n_uv == 0 */
    const float *nrm; /* n_nrm * 3, need not be unit length (mesh_build normalises) */
    uint32_t n_pos, n_uv, n_nrm;
    const uint8_t *rgb; /* n_pos * 3 vertex colours (per position), or NULL */
    const uint8_t *rgba; /* n_pos * 4: the same with alpha (instead of rgb), or NULL */
    const float *uv1;   /* n_pos * 2 second uv set (per position), or NULL */
    const float *tangent; /* n_pos * 4 tangents (per position, model.h's form), or NULL */
    const struct mesh_corner *corners; /* n_tris * 3, triangle by triangle */
    const uint16_t *tri_material; /* per triangle; NULL: all 0 */
    uint32_t n_tris;
    bool crease_set;  /* crease_deg given; else MESH_CREASE_DEFAULT */
    float crease_deg; /* generated normals split where faces turn by more (see the top) */
};

/* The crease angle of generated normals when nothing else is asked for (--crease) and the
 * format has no rule of its own: faces meeting at more than this keep their edge sharp.
 * 30 degrees is Blender's auto-smooth default and VTK's (f3d's) feature angle: CAD parts and
 * boxes get their edges, a dense scan stays smooth but for a few spikes (the full-resolution
 * bunny: 3% of its positions). The loaders' defaults: STL, PLY and assimp's formats this;
 * OBJ 180, one smooth normal per position (the conventions' contract, which the Mesa oracle
 * holds rastty to: its decimated bunny has faces folded onto each other, split at any
 * angle); glTF 0, flat faces (its specification's rule). */
#define MESH_CREASE_DEFAULT 30.0f

/* Fill out's geometry (verts, tris, tri_material, vert_material, positions, n_verts, n_tris,
 * has_uvs, has_normals, bounds) from src: one vertex per distinct (pos, uv, nrm, material) corner
 * (chained per position, O(corners); a position with more than 32 distinct corners may get
 * duplicate vertices), in order of first use; triangles keep their winding;
 * missing normals and uvs as described at the top of this file; a zero-length given normal
 * also becomes (0,0,1). Leaves materials and textures alone (the caller sets them; every
 * tri_material value must index them). Errors: no triangles, an index out of range, out of
 * memory; on failure the geometry fields are NULL/0. */
int mesh_build(const struct mesh_source *src, struct mesh *out, struct err *e);
/* Fill m's positions (pos_id, pos_xyz, n_pos above) for its vertices as they are now,
 * replacing any it had: a hash of the positions' bits, O(n_verts); 4 bytes a vertex and 12 a
 * position, kept only when they are at most half as many as the vertices (where walking by
 * position pays, frontend.h; else pos_id is NULL). mesh_build, mesh_tangents and the
 * levels of lod.h and dag.h call it. -1 when out of memory (pos_id and pos_xyz are then
 * NULL). */
int mesh_share_positions(struct mesh *m);
/* Tangents for tangent-space normal maps (mesh.tangents), from uv set 0 (or uv1 when
 * `second`): as MikkTSpace makes them — per triangle corner dP/du projected onto the
 * corner's normal plane, weighted by the corner's angle, summed per vertex and
 * orthonormalised; the bitangent's sign w is the triangle's handedness (w N x T along dP/dv,
 * v up), and a vertex whose triangles disagree (a mirrored uv seam) is split in two, as
 * MikkTSpace splits it. -1 when out of memory. */
int mesh_tangents(struct mesh *m, bool second);
/* Turn the mesh's positions and normals (a rotation: windings keep their facing) so that
 * its axis `axis` ('x' or 'z'; anything else: nothing) points up (+Y): Z-up (x, y, z) ->
 * (x, z, -y), the front (-Y) toward the default camera; X-up (x, y, z) -> (-y, x, z). The
 * bounds, tangents and the file's cameras follow. */
void mesh_turn_up(struct mesh *m, char axis);
/* Whether every vertex position is finite (the simplifiers of lod.h and dag.h need it). */
bool mesh_positions_finite(const struct mesh *m);
/* The bytes of m's own geometry: vertices, triangles, their materials, positions, colours,
 * second uvs, tangents (not textures, materials, clusters or levels). */
size_t mesh_geometry_bytes(const struct mesh *m);
/* Frees everything the mesh owns (its textures) and zeroes it; a zeroed mesh is fine. Its
 * levels of detail, if any were built, are lod_free's (scene_free calls both). */
void mesh_free(struct mesh *m);
/* Frees the mesh's clusters (cluster.h) alone; mesh_free does it too. */
void mesh_free_clusters(struct mesh *m);

#endif
