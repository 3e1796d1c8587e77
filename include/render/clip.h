/* clip.h: clip a triangle against frustum planes in homogeneous clip space.
 *
 * In:  3 vertex_out corners (clip-space x,y,z,w plus varyings), a mask of VERTEX_OUT_NEAR,
 *      VERTEX_OUT_FAR and VERTEX_GUARD_* bits naming the planes to clip against.
 * Out: 0..9 vertices of a convex polygon in the same winding, varyings interpolated linearly
 *      in clip space (exact for perspective-correct attributes).
 * Planes: near z >= -w, far z <= w (the real frustum), and the x/y guard band
 *      -g*w <= x,y <= g*w (g >= 1): clipping x/y at the guard band rather than the viewport
 *      puts every new edge outside the visible area, so clipping never moves a visible edge.
 *      Near is clipped first, so every later vertex has w > 0.
 * A vertex exactly on a plane is inside. A new vertex on an edge is always interpolated from
 * the edge's inside endpoint, so two triangles sharing that edge create bit-identical vertices
 * (no cracks along clipped shared edges). Should interpolation overflow (coordinates near
 * the double range) the polygon is dropped: 0 vertices. */
#ifndef RASTTY_CLIP_H
#define RASTTY_CLIP_H

#include <stdint.h>

#include "vertex.h"

#define CLIP_MAX_VERTS 9

/* n_var: the varyings var[0 .. n_var) are interpolated (with wpos); a negative n_var means
 * the features path's all[0 .. -n_var) (vertex.h, struct vary_rich). */
int clip_triangle(const struct vertex_out *const in[3], uint32_t planes, int n_var, double guard_x,
                  double guard_y, struct vertex_out out[CLIP_MAX_VERTS]);

#endif
