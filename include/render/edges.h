/* edges.h: a mesh's edges with the triangles on either side, for wireframe's outline
 * (render_opts.h, --wire).
 *
 * Positions are welded: corners at the same position are one vertex whatever their uv or
 * normal, so a texture seam or a split normal is no boundary. An edge shared by exactly two
 * triangles knows both; an edge of one triangle (the mesh's border), or of three or more
 * (non-manifold), is listed once per triangle, as a boundary. `crease`: the two faces turn
 * by more than EDGE_CREASE_DEG (their geometric normals, from the positions). Built once
 * per mesh (level) and kept by the front end: ~0.1 s per million triangles. */
#ifndef RASTTY_EDGES_H
#define RASTTY_EDGES_H

#include <stdbool.h>
#include <stdint.h>

#include "err.h"
#include "mesh.h"

#define EDGE_NONE UINT32_MAX
#define EDGE_CREASE_DEG 40.0

struct edge {
    uint32_t v0, v1; /* the edge's corners, as vertex indices of triangle t0 */
    uint32_t t0, t1; /* the triangles on either side; t1 = EDGE_NONE: a boundary */
    bool crease;
};

struct edge_table {
    const struct mesh *mesh; /* what it was built for (with n_tris): rebuilt when it changes */
    uint32_t n_tris;
    struct edge *e;
    uint32_t n;
};

/* 0, or -1 (out of memory: et left empty). */
int edge_table_build(struct edge_table *et, const struct mesh *m, struct err *e);
void edge_table_free(struct edge_table *et);

#endif
