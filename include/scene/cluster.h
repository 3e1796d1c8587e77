/* cluster.h: a mesh's triangles in clusters with a tree over them, so that a frame can
 * drop whole clusters that cannot reach a pixel before their vertices are transformed
 * (render/cluster_cull.h; --cluster-cull on).
 *
 * Drawing order. The order triangles are drawn in decides a pixel where two surfaces meet
 * at the same depth (the depth test is LESS: the first one stays), and culling must never
 * change a pixel, so it must not change that order. meshopt_buildMeshlets regroups the
 * index buffer into compact meshlets (and returns their corners, not which triangles they
 * were); here a cluster is a run of CLUSTER_MAX_TRIS consecutive opaque triangles of the
 * file (mesh.n_opaque: the blended ones are drawn apart, sorted), and the drawn clusters are
 * walked in the file's order. Exporters write triangles in spatially coherent order and
 * mesh_build numbers vertices in order of first use, so a run is a small patch (on a
 * scanned grid, a strip) whose vertices lie in a few short ranges. Tried and dropped
 * (README): sets of 32 or 128 triangles by the Morton order of their centroids (compact,
 * but each drawn one reads its triangles and vertices from all over memory: slower).
 *
 * Per cluster:
 *   - its oriented box (object space): the mean face normal, and in its plane the
 *     direction its corners spread most along and the one across it; centre and half
 *     sizes widened so that every corner is inside in exact arithmetic on the float axes;
 *     no_bounds when a corner is not finite (never culled: the vertex stage rejects such
 *     triangles one by one);
 *   - its normal cone: the unit face normals (file's winding, cross(p1-p0, p2-p0)) all lie
 *     within acos(cone_cos) of cone_axis; no_cone when a triangle is degenerate (its facing
 *     on screen is decided by rounding) or the cone is wider than acos(CLUSTER_MIN_CONE_COS);
 *   - one_sided: every triangle's material is MAT_ONE_SIDED (culled under --cull auto);
 *   - its vertices as ranges of consecutive indices: the vertex stage runs on exactly those.
 * The tree: the clusters sorted by the Morton code of their box centre (10 bits an axis
 * over the mesh's box), split where the codes' highest differing bit changes, depth first
 * in one array (mesh_clusters.c[]: a node's subtree ends at its skip); a node's box is the
 * axis-aligned box of its children's, so it holds them, and it has no cone.
 * Memory: 7.4 bytes a triangle (the 1M-triangle sphere: 7.4 MB, 24% of its mesh; lost_empire
 * 9%, the sports car 29%); build 0.4 s a million triangles (README). */
#ifndef RASTTY_CLUSTER_H
#define RASTTY_CLUSTER_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "mesh.h"

#define CLUSTER_MAX_TRIS 32
#define CLUSTER_MIN_CONE_COS 0.05f

/* Build m's clusters over its opaque triangles (replacing any): 0, or -1 out of memory (m
 * then has none, and is drawn triangle by triangle as before). */
int cluster_build(struct mesh *m);
/* The box, cone and flags (mesh_cluster's center, axis, half, cone_axis, cone_cos, flags;
 * the rest untouched) of the triangles tri[0 .. n) of m, n > 0 (scene/dag.h uses it for its
 * clusters of every level). */
void cluster_bounds(const struct mesh *m, const uint32_t *tri, uint32_t n, struct mesh_cluster *c);
/* The 30-bit Morton code of a point quantised to q[a] in 0 .. 1023 on each axis (the order
 * cluster_build's tree and scene/dag.h's groups sort by). */
uint32_t cluster_morton3(const uint32_t q[3]);
/* Bytes the clusters take. */
size_t cluster_bytes(const struct mesh *m);

#endif
