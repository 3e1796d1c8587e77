/* dag.h: hierarchical level of detail by clusters (issue 24, Deliver 2) — a mesh's triangles
 * in clusters, groups of clusters simplified together with their common border locked, the
 * results split into clusters again, level after level: a DAG of clusters (Nanite's, and
 * meshoptimizer's cluster LOD), of which each frame draws a cut chosen per cluster by its
 * projected error (--lod clusters; auto's bound, lod_px pixels), so that the near side of a model
 * keeps its detail while the far side, and the sub-pixel detail everywhere, is coarse.
 *
 * Build (dag_build; with --lod clusters lod.c's job runs it first, the per-mesh chain only
 * for a mesh that gets none):
 *   level 0  meshopt_buildMeshlets over the mesh's triangles (at most DAG_CLUSTER_TRIS
 *            triangles, DAG_CLUSTER_VERTS vertices), each meshlet's triangles found again by
 *            their corners: level 0 clusters are the source's own triangles, numbered as
 *            in the file;
 *   level k+1  the clusters of level k sorted by the Morton code of their centres and taken
 *            grown greedily, DAG_GROUP at a time, each next one the cluster sharing the
 *            most vertices with the group (meshoptimizer 0.18 has no partitioner); each
 *            group's triangles simplified to half
 *            by meshopt_simplify with meshopt_SimplifyLockBorder (its border, the edges it
 *            shares with other groups and the mesh's own, stays as it is: a neighbour drawn
 *            at another level meets it without a crack); vertices with one position and
 *            other uvs, normals or materials are seams to the simplifier (positions alone
 *            are its input, in 0.18), so every triangle keeps one material and its uvs —
 *            but for atlas tiles (below); the result split by meshopt_buildMeshlets again. A group whose border moved
 *            all the same (a border vertex on a seam is a seam to 0.18, not a border: its
 *            open edges are compared before and after) or that cannot lose a sixth of its
 *            triangles (borders and seams everywhere: lost_empire's blocks) is left as it
 *            is: its clusters go on to the next level's grouping.
 *   Per cluster: the bounding sphere and error of the group that made it (level 0: its own
 *   sphere, error 0), and of the group it was simplified in ("parent"; none for a root).
 *   A group's error is its children's largest plus the simplifier's (object space, at
 *   least DAG_MIN_STEP of the mesh's extent), its sphere holds its children's: both grow up
 *   the DAG, so the rule below picks, over any part of the surface, exactly one level.
 *   Vertices: the simplifier collapses onto existing vertices, so every level's are the
 *   source's; the hierarchy's mesh (mesh_dag.mesh) holds the source's opaque triangles
 *   first, as they are, then every coarser cluster's: those of level DAG_COPY_LEVEL and
 *   coarser on copies of their vertices (laid out cluster by cluster: the cut reads them
 *   forward), level 1's on the source's own (half the coarser triangles; a tiled mesh
 *   copies level 1 too, for the tile uvs); it borrows the source's textures (and its
 *   materials, but for the tiles' below). A coarser cluster's triangles, and a copying
 *   one's copies, are consecutive there, so only level 0's clusters keep a list
 *   (mesh_dag.tris). Memory: once the build is done and nothing draws (dag_settle; the
 *   viewer's loop between frames, render after its build), the source frees its arrays and
 *   points to the first part of the hierarchy's mesh, the same bytes: the hierarchy then
 *   costs its coarser levels (about as many triangles as the source; 0.7-0.8 copies a
 *   triangle of theirs where they copy), level 0's list and its runs. render --stats: the
 *   car 1.00x its mesh's own geometry, the 1M sphere 1.21x, the bunny 1.20x, lost_empire
 *   0.37x (its positions shared too); with level 0 repeated and every coarser level
 *   copied, 2.98x, 3.28x, 3.25x, 1.49x (the README has the steps and the times).
 *   Atlas tiles (tiles.h; a mesh on the features path, as voxel exporters' block worlds
 *   are): the source's vertices welded per tile class for the grouping and the
 *   simplifier, the coarser clusters' copies given their tile uvs and derived materials.
 *   Measured: a 121k-triangle block world's (build/bench/genvoxels) framed cut is 22k
 *   triangles, the same bytes; lost_empire's 182k of 225k (its blocks' kinds change every
 *   few blocks, and three classes meet at most corners: 0.18 locks those).
 *
 * The cut (render/frontend.c, per frame and item): cluster c is drawn when its own group's
 * error, projected at the nearest point of its sphere (lod.h's lod_pixels_per_unit), is at
 * most lod_px, and its parent's is more. Drawn clusters are then culled as --cluster-cull's
 * (frustum, facing, no pixel centre: cluster_cull.h) and their triangles drawn in the order
 * of the hierarchy's mesh: the source's in the file's order first, by that mesh's runs of 64
 * (cluster.h; built with the hierarchy), a run hidden behind the depth drawn so far dropped
 * whole as --cluster-cull drops a hidden cluster. A mesh walked by position (frontend.c's
 * walks_by_position: lost_empire) has its cut walked so too, each run's marked triangles
 * filtered at once, or, when the runs the cut touches hold fewer vertices than the mesh
 * has positions (most of level 0 replaced: a far block world), by heads, made run by run.
 * With no level coarsened (every parent's error projects above lod_px), the frame is the
 * bytes of --lod off.
 *
 * Meshes get a hierarchy when they have at least DAG_MIN_TRIS triangles, all opaque, and no
 * second uv set or tangents (material features allowed: its mesh is drawn by the features
 * path, as the source); only --lod clusters draws it. */
#ifndef RASTTY_DAG_H
#define RASTTY_DAG_H

#include <stdatomic.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "mesh.h"

#define DAG_MIN_TRIS 16384
#define DAG_CLUSTER_TRIS 128
#define DAG_CLUSTER_VERTS 128
#define DAG_GROUP 8
#define DAG_MAX_LEVELS 24
#define DAG_MIN_STEP 1e-6 /* of the mesh's extent: a group's error exceeds its children's */
#define DAG_COPY_LEVEL 2  /* clusters this coarse or more draw copies of their vertices */

struct dag_cluster {
    float center[3], radius, error;       /* the group that made it (level 0: its own; 0) */
    float p_center[3], p_radius, p_error; /* the group it is simplified in; p_error < 0: none */
    uint32_t tri_first, n_tris;           /* its triangles (dag_tri): level 0,
                                             mesh_dag.tris[tri_first ..]; coarser (made
                                             consecutive), tri_first .. + n_tris - 1 */
    uint32_t vert_first, n_verts;         /* its vertex copies, vert_first .. + n_verts
                                             - 1; n_verts 0: none (level 0, and levels
                                             under DAG_COPY_LEVEL: the source's vertices,
                                             its triangles' corners) */
    uint32_t tri_lo, tri_hi;              /* its lowest and highest triangle */
    uint32_t level;                       /* 0: the source's triangles */
    struct mesh_cluster box;              /* culling bounds (cluster.h's cluster_bounds) */
};

struct mesh_dag {
    struct mesh mesh;       /* the source's opaque triangles, then the coarser clusters';
                               its vertices the source's, then each coarser cluster's own
                               copies (read forward when walked in order) */
    struct dag_cluster *c;  /* every level's clusters */
    uint32_t n;
    uint32_t *tris;         /* level 0's clusters' triangles (into mesh.tris), cluster by
                               cluster */
    int levels;             /* levels built (1: none coarser than the source) */
    uint32_t n_level0;      /* clusters of level 0 */
    double build_ms;
    size_t bytes;           /* what it holds: its mesh's geometry (mesh_geometry_bytes), runs
                               and materials, its clusters and level 0's list — less what its
                               source shares once settled (dag_settle) */
    uint8_t shared;         /* the arrays of mesh its source owns and shares (DAG_SHARES_*) */
};
enum { DAG_SHARES_VERTS = 1, DAG_SHARES_TRIS = 2, DAG_SHARES_COLORS = 4,
       DAG_SHARES_POSITIONS = 8, DAG_SETTLED = 128 };

/* Triangle q of cluster c (into d->mesh.tris). */
static inline uint32_t dag_tri(const struct mesh_dag *d, const struct dag_cluster *c, uint32_t q)
{
    return c->level ? c->tri_first + q : d->tris[c->tri_first + q];
}

/* Is cluster c in the cut for an error bound of max_px pixels, its own group's error
 * projecting to own_px and its parent's to parent_px (dag.h's rule; a root has no parent,
 * a level 0 cluster no error)? */
static inline bool dag_cut_takes(const struct dag_cluster *c, double own_px, double parent_px,
                                 double max_px)
{
    return (c->p_error < 0 || parent_px > max_px) && (c->error <= 0 || own_px <= max_px);
}

/* Does m get a hierarchy (the rule above)? */
bool dag_eligible(const struct mesh *m);
/* Build m's hierarchy (on this thread; cancel: stop early, NULL: never) and publish it in
 * m->dag when it has a coarser level. 0 (also when m gets none), or -1 out of memory. */
int dag_build(struct mesh *m, const atomic_bool *cancel);
/* m's hierarchy when complete, else NULL. */
const struct mesh_dag *dag_of(const struct mesh *m);
/* Is m a hierarchy's mesh (drawn by its cut)? */
bool dag_is_cut_mesh(const struct mesh *m);
/* Let m and its complete hierarchy share what they have in common: m's vertices, triangles,
 * their materials, colours and positions are the first of the hierarchy's mesh's (the same
 * bytes), so m frees its own and points to those (then owning them: dag_free leaves them).
 * Only while nothing else reads m (no frame drawn, no build running: scene.h's
 * scene_lod_settle). Does nothing when m has no hierarchy, or again. */
void dag_settle(struct mesh *m);
/* Free m's hierarchy (lod_free does it). */
void dag_free(struct mesh *m);

#endif
