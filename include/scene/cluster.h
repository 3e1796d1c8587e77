/* cluster.h: a mesh's triangles in clusters, so that a frame can drop whole clusters that
 * cannot reach a pixel before their vertices are transformed (render/cluster_cull.h;
 * --cluster-cull, on by default).
 *
 * Drawing order. The order triangles are drawn in decides a pixel where two surfaces meet
 * at the same depth (the depth test is LESS: the first one stays), and culling must never
 * change a pixel, so it must not change that order. meshopt_buildMeshlets regroups the
 * index buffer into compact meshlets (and returns their corners, not which triangles they
 * were); here a cluster is a run of CLUSTER_MAX_TRIS consecutive opaque triangles of the
 * file (mesh.n_opaque: the blended ones are drawn apart, sorted), kept in the file's order
 * and walked in it. Exporters write triangles in spatially coherent order and mesh_build
 * numbers vertices in order of first use, so a run is a small patch (on a scanned grid, a
 * strip) whose vertices lie close together. Tried and dropped (README): sets of triangles
 * by the Morton order of their centroids (compact, but each drawn one reads its triangles
 * and vertices from all over memory: slower); a tree over the clusters (its nodes cost a
 * test each and seldom drop anything in a framed view; each cluster read out of the file's
 * order missed the cache); runs of 16 and 32 triangles (more tests than they save: the car
 * 5.6 and 4.8 ms against 4.4 at 64; 128 the same as 64).
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
 *   - its vertices' reach: v_end, its highest vertex + 1, and v_need, the lowest vertex it
 *     or any later cluster uses. The front end makes vertices in order, up to each drawn
 *     cluster's v_end, and jumps to its v_need first: the vertices it skips are read by
 *     dropped clusters alone.
 * Memory: 92 bytes a cluster, 1.4 a triangle (the 1M-triangle sphere: 1.4 MB, 5% of its
 * mesh); build 0.07 s a million triangles (README). */
#ifndef RASTTY_CLUSTER_H
#define RASTTY_CLUSTER_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "mesh.h"

#define CLUSTER_MAX_TRIS 64
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
