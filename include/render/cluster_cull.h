/* cluster_cull.h: which of a mesh's clusters (scene/cluster.h) a frame can drop whole,
 * before their vertices are transformed — and no pixel may change for it.
 *
 * The front end (frontend.c, walk_clusters) tests each cluster in the file's order, just
 * before it would walk its triangles; the clusters left have their vertices made and
 * their triangles walked one by one as without clusters. A cluster is dropped when every
 * one of its triangles would have been dropped by the front end one by one (frontend.h),
 * which draws nothing for them:
 *   frustum   its box lies outside one plane of the view volume (-w <= x, y, z <= w): every
 *             triangle is trivially rejected (all corners outside that plane);
 *   facing    --cull back (or front), or --cull auto with its triangles all of
 *             single-sided materials: seen from anywhere in its box every normal of its cone
 *             faces away (the box's bounding sphere seen from the eye, plus the cone's
 *             half-angle, stays more than CLUSTER_FACING_MARGIN radians short of 90
 *             degrees), so every triangle's facing (setup_front_facing: the sign of a
 *             determinant of clip coordinates) culls it;
 *   no centre the box is wholly in front of the eye (w > 0 at its eight corners) and its
 *             window-space rectangle (the corners projected), widened by
 *             CLUSTER_SCREEN_MARGIN px for rounding and the 1/256 px snap, holds no pixel
 *             centre of the framebuffer: every triangle's box (setup_box) is empty, and
 *             every piece clipping would make lies inside it;
 *   hidden    (the front end's, with --hidden-cull, from cluster_rect below) the box is
 *             wholly in front of the eye and the least window depth of its corners is at or
 *             behind the depth drawn so far at every pixel centre of its rectangle: every
 *             triangle is hidden (frontend.h, "Hidden": its box, and every piece clipping
 *             makes of it, lies in the rectangle, its corners no nearer).
 * The tests are exact bounds with margins: what they drop covers no pixel centre or loses
 * every depth test, so the picture is the same bytes with --cluster-cull on and off
 * (tests/unit/test_clusters.c, test_hidden.c: random views, partly off screen, sub-pixel,
 * every culling mode). Wireframe and the wireframe overlay draw every edge: no cluster is
 * dropped there. */
#ifndef RASTTY_CLUSTER_CULL_H
#define RASTTY_CLUSTER_CULL_H

#include <stdbool.h>

#include "mesh.h"
#include "render_opts.h"
#include "vecmath.h"

#define CLUSTER_SCREEN_MARGIN (1.0 / 64)
#define CLUSTER_FACING_MARGIN 1e-3

/* (CLUSTER_HIDDEN is the front end's verdict, from cluster_rect: cluster_test never
 * returns it) */
enum cluster_verdict {
    CLUSTER_DRAW,
    CLUSTER_FRUSTUM,
    CLUSTER_FACING,
    CLUSTER_NO_CENTRE,
    CLUSTER_HIDDEN,
    CLUSTER_VERDICTS
};

/* What a frame knows to test an item's clusters: its object-to-clip matrix, the eye in
 * object space (or the direction of view, orthographic), the framebuffer, and the culling
 * that applies. */
struct cluster_view {
    mat4 mvp;
    vec3 eye;          /* object space (perspective) */
    vec3 dir;          /* object space, eye toward the scene (orthographic) */
    bool ortho;
    int fb_w, fb_h;
    int facing;        /* which face is culled: +1 back, -1 front, 0 none */
    bool by_material;  /* cull the back of clusters that are all one-sided (--cull auto) */
    int det_sign;      /* the model matrix's determinant's sign (0: flat, nothing culled) */
};

/* The view for an item with model matrix `model`, mvp, camera eye (world) and, orthographic,
 * view_back (unit, toward the viewer); cull: the culling the mesh gets (CULL_AUTO already
 * resolved to BACK or NONE), by_material: per material (MESH_SIDES_SOME under auto). */
void cluster_view_init(struct cluster_view *v, mat4 model, mat4 mvp, vec3 eye, bool ortho,
                       vec3 view_back, int fb_w, int fb_h, enum cull_mode cull,
                       bool by_material);
/* Where a cluster that may draw lies on screen, for the hidden test (frontend.h): the pixel
 * centres any of its triangles' boxes can hold, and so any piece clipping makes of them
 * (x0 .. x1, y0 .. y1, within the framebuffer), and a window depth that none of their
 * corners is nearer than (z_lo). Valid when the whole box lies in front of the eye. */
struct cluster_rect {
    int x0, y0, x1, y1;
    float z_lo;
    bool valid;
};

/* The verdict on cluster c; with `r`, where it lies (when the verdict is CLUSTER_DRAW). */
enum cluster_verdict cluster_test(const struct cluster_view *v, const struct mesh_cluster *c,
                                  struct cluster_rect *r);

#endif
