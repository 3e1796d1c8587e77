/* stats.h: what a frame reports back — counts of triangles, vertices and pixels at each
 * stage, the levels of detail drawn, how the threads shared it, its time (the HUD, --stats,
 * the benchmarks). pipeline_draw fills it. */
#ifndef RASTTY_STATS_H
#define RASTTY_STATS_H

#include <stdbool.h>
#include <stdint.h>

struct frame_stats {
    uint64_t tris_in;       /* triangles submitted */
    uint64_t tris_culled;   /* back/front-face culled, zero-area, or mesh outside frustum */
    uint64_t tris_rejected; /* trivially outside one frustum plane */
    uint64_t tris_clipped;  /* needed polygon clipping */
    uint64_t tris_drawn;    /* reached the rasterizer (after clipping, fan pieces counted) */
    uint64_t tris_empty;    /* reached the rasterizer but covered no pixel centre */
    uint64_t tris_no_centre; /* dropped by setup: zero area, no pixel centre in the box, or a
                              * box of at most 4 pixels whose centres it misses (not
                              * lit, no shading record); unclipped, in = rejected + culled +
                              * no_centre + drawn */
    uint64_t tris_hidden;   /* dropped by the front end: behind the depth buffer over its
                               whole pixel box (--hidden-cull; frontend.h, "Hidden"); in
                               the sum above beside no_centre */
    uint64_t verts_lit;     /* vertices lit (vertex_shade): only those of triangles drawn */
    uint64_t tris_by_position; /* of tris_in, walked by position (frontend.c: a mesh whose
                                  vertices share positions, denser than the framebuffer) */
    uint64_t pixels_tested; /* fragments inside a triangle */
    uint64_t pixels_shaded; /* fragments that passed the depth test */
    uint64_t meshes_culled; /* whole meshes outside the frustum (bounding sphere) */
    uint64_t tris_full;     /* what tris_in would be at full detail (--lod off) */
    /* clusters (cluster_cull.h): tested, dropped whole (outside a frustum plane, facing away
     * under culling, no pixel centre in their screen box, hidden behind the depth drawn so
     * far: frontend.h), and drawn triangle by triangle; tested = frustum + facing +
     * no_centre + hidden + drawn. With slices, a cluster two slices hold triangles of is
     * counted by the one with its first. Their triangles count as tris_culled,
     * tris_rejected, tris_no_centre and tris_hidden. */
    uint64_t clusters_tested, clusters_frustum, clusters_facing, clusters_no_centre,
        clusters_hidden, clusters_drawn;
    /* occluders (--occluders; frontend.h, "Occluders"): last frame's triangles drawn into
     * the occluder depth, and of tris_hidden and clusters_hidden those found behind it */
    uint64_t occluders, tris_occluded, clusters_occluded;
    /* the cluster hierarchy (scene/dag.h, --lod auto): clusters in the cut (drawn or culled),
     * their triangles, and a bit per level they come from */
    uint64_t dag_cut, dag_tris;
    uint32_t dag_levels;
    int lod_min, lod_max;   /* levels of detail drawn (0 = full), over the drawn items; -1 none */
    const char *kernel;     /* the kernels that drew it (kernel.h: "avx2", "sse2", "ref", ...) */
    int threads;            /* threads that drew the frame */
    bool slices;            /* they split the triangles (SPLIT_SLICES), not the screen */
    double render_ms;
};

#endif
