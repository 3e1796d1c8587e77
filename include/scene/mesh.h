/* mesh.h: an indexed triangle mesh with its materials, as loaded from disk.
 *
 * Loaded once (a loader of model.h fills it), never modified by rendering. Vertices are unique
 * (position, uv, normal, material) combinations, like a GPU vertex buffer, so the vertex stage
 * transforms each one once per frame and every triangle is three indices into them.
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

/* How a material lights up is light.h's business. A mesh always has a material 0: the
 * implicit one for faces that name no material (kd = (1,1,1), ks = 0.5, ns = 32, no texture;
 * `implicit` set, so an untextured face gets light.h's default albedo 0.8 instead). */
struct material {
    char name[MESH_NAME_MAX]; /* sanitised (printable ASCII) */
    float kd[3];              /* diffuse albedo, multiplies the texture */
    float ks[3];              /* specular colour; default 0.5 */
    float ns;                 /* Blinn-Phong exponent; default 32 */
    int texture;              /* index into mesh.textures, or -1 */
    bool implicit;            /* no material was named: see light_base_color() */
};

struct mesh_vertex {
    float pos[3];
    float uv[2];
    float nrm[3];
};

struct mesh {
    struct mesh_vertex *verts;
    uint32_t n_verts;
    uint32_t (*tris)[3];  /* triangle corners, indices into verts, in the file's winding */
    uint16_t *tri_material; /* per triangle, index into materials */
    uint16_t *vert_material; /* per vertex (vertices are unique per material), n_verts long */
    uint32_t n_tris;
    struct material *materials; /* at least one */
    uint32_t n_materials;
    struct texture *textures; /* map_Kd images, loaded (owned, or borrowed from a cache) */
    uint32_t n_textures;
    uint8_t (*colors)[3]; /* per vertex colour from the file (PLY), n_verts long; NULL when
                             the file has none. Not drawn yet: the pipeline would multiply
                             the albedo by it (interpolated like a uv). */
    bool has_uvs;     /* some corner had a vt */
    bool has_normals; /* some corner had a vn (others may have generated normals) */
    char file_up;     /* the file's up axis, 'x', 'y' or 'z' (its metadata, else its format's
                         convention; 0: y). model.c turns the mesh so that it is +Y */
    float bbox_min[3], bbox_max[3]; /* over the positions used by triangles */
    float center[3], radius;        /* bounding sphere: bbox centre, farthest used vertex */
    struct mesh_lod *lod; /* simplified levels (lod.h), or NULL; a level's own is NULL */
};

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

/* Fill out's geometry (verts, tris, tri_material, vert_material, n_verts, n_tris, has_uvs,
 * has_normals, bounds) from src: one vertex per distinct (pos, uv, nrm, material) corner
 * (chained per position, O(corners); a position with more than 32 distinct corners may get
 * duplicate vertices), in order of first use; triangles keep their winding;
 * missing normals and uvs as described at the top of this file; a zero-length given normal
 * also becomes (0,0,1). Leaves materials and textures alone (the caller sets them; every
 * tri_material value must index them). Errors: no triangles, an index out of range, out of
 * memory; on failure the geometry fields are NULL/0. */
int mesh_build(const struct mesh_source *src, struct mesh *out, struct err *e);
/* Turn the mesh's positions and normals (a rotation: windings keep their facing) so that
 * its axis `axis` ('x' or 'z'; anything else: nothing) points up (+Y): Z-up (x, y, z) ->
 * (x, z, -y), the front (-Y) toward the default camera; X-up (x, y, z) -> (-y, x, z). The
 * bounds follow. */
void mesh_turn_up(struct mesh *m, char axis);
/* Frees everything the mesh owns (its textures) and zeroes it; a zeroed mesh is fine. Its
 * levels of detail, if any were built, are lod_free's (scene_free calls both). */
void mesh_free(struct mesh *m);

#endif
