/* vertex.h: the vertex stage — each unique mesh vertex transformed once per frame (or, when
 * the front end walks a mesh by position (frontend.h), each distinct position projected
 * once and the records of the vertices of triangles that reach a pixel centre made from
 * it: the same bytes).
 *
 * In:  a mesh, the frame's uniforms (matrices, eye, lights, shading mode).
 * Out: one struct vertex_out per mesh vertex: clip-space position (double), frustum/guard-band
 *      outcode, snapped window position (vertex_run, every vertex); world position and the
 *      varyings the shading mode needs (vertex_shade, on demand):
 *        unlit, flat, wire : u v
 *        gouraud           : u v, light.h's D rgb, S rgb (per-vertex lighting); with grey
 *                            lights (light_env.grey) u v D S: the channels are equal
 *                            (VARY_GOURAUD_D, VARY_GOURAUD_S say where they are)
 *        phong, normals    : u v, world position xyz, world normal xyz
 *        + for a mesh with vertex colours (PLY, OBJ, STL): rgb in var[VARY_COLOR..+2] (2..7
 *          zero where the mode leaves them unused), which multiplies the albedo
 *      A mesh with material features (mesh.h: mesh.features) is drawn by the features path
 *      (shade.h) with its own varyings, laid out by struct vary_rich over all[] (the
 *      world position and the varyings together, VARY_ALL floats): see vertex_rich_layout.
 * Varyings are interpolated perspective-correctly downstream; clip.c interpolates all of them
 * linearly in clip space, which is exact for perspective-correct attributes.
 *
 * Outcodes: bits VERTEX_OUT_* say which real frustum plane (-w <= x,y,z <= w) a vertex is
 * outside (used for trivial rejection); VERTEX_GUARD_* say it is outside the x/y guard band
 * (used to decide whether clipping is needed: triangles inside the guard band are rasterised
 * directly and their bounding box is clipped to the framebuffer instead, which is cheaper and
 * creates no new vertices). */
#ifndef RASTTY_VERTEX_H
#define RASTTY_VERTEX_H

#include <stddef.h>
#include <stdint.h>

#include "light.h"
#include "mesh.h"
#include "render_opts.h"
#include "vecmath.h"
#include "viewport.h"

#define VARY_MAX 12
#define VARY_COLOR 8 /* var[8..10]: the vertex colour (0..1), for meshes that have one */
#define VARY_ALL 16  /* all[]: wpos, var and the record's last 4 bytes, as one array */
#define VARY_BASE 3  /* var == all + VARY_BASE: where the default path's varyings start */
/* where Gouraud's D and S start: rgb at 2 and 5, or with grey lights one float each at 2, 3 */
#define VARY_GOURAUD_D 2
#define VARY_GOURAUD_S(grey) ((grey) ? 3 : 5)

enum {
    VERTEX_OUT_LEFT = 1 << 0,
    VERTEX_OUT_RIGHT = 1 << 1,
    VERTEX_OUT_BOTTOM = 1 << 2,
    VERTEX_OUT_TOP = 1 << 3,
    VERTEX_OUT_NEAR = 1 << 4,
    VERTEX_OUT_FAR = 1 << 5,
    VERTEX_GUARD_LEFT = 1 << 6,
    VERTEX_GUARD_RIGHT = 1 << 7,
    VERTEX_GUARD_BOTTOM = 1 << 8,
    VERTEX_GUARD_TOP = 1 << 9,
    VERTEX_INVALID = 1 << 10, /* a non-finite coordinate: its triangles are dropped */
    VERTEX_OUT_FRUSTUM = 0x3f,
    VERTEX_NEEDS_CLIP = VERTEX_OUT_NEAR | VERTEX_OUT_FAR | 0x3c0,
};

/* The guard band: how far beyond the viewport (in pixels) a triangle may reach and still be
 * rasterised without clipping. 2^14 px at 1/256 px is 2^22 fixed-point units, so edge
 * functions (products of two coordinates) stay below 2^46: int64 with room to spare. */
#define VERTEX_GUARD_PX 16384.0

/* Where a vertex's world position and varyings are (struct vertex_out.shaded). */
enum vertex_shaded {
    VERTEX_UNSHADED, /* not yet: the vertex stage positioned it only */
    VERTEX_SHADED,   /* wpos and var are valid (vertex_shade) */
    VERTEX_QUEUED,   /* waiting for vertex_shade_many with others (the pipeline's queue):
                      * valid once the queue is shaded, before the back end reads it */
};

/* 128 bytes in two halves of one cache line each (when the array is 64-byte aligned, as the
 * pipeline allocates it): the first is all the vertex stage writes for every vertex and all
 * the front end reads to reject, cull and box a triangle; the second is written only for
 * vertices of drawn triangles (vertex_shade). On a dense mesh the vertex array is larger
 * than the caches, so the untouched half is memory traffic saved. Window depth is not kept:
 * setup_interp computes it from clip as viewport_window does (the same bits). */
struct vertex_out {
    int32_t fx, fy;    /* win x, y snapped to 1/256 pixel (viewport.h; the guard band keeps
                          them below 2^23); valid when `projected` */
    uint32_t outcode;
    uint8_t projected; /* set by vertex_project (the vertex stage does it for every w > 0) */
    uint8_t shaded;    /* enum vertex_shaded: are wpos and var valid? */
    double clip[4];    /* x, y, z, w in clip space */
    double win[2];     /* window x, y (pixels, y down); valid when `projected` */
    union {
        struct {
            float wpos[3]; /* world position (flat shading, centroid and face normal) */
            float var[VARY_MAX];
        };
        float all[VARY_ALL]; /* the features path's varyings (struct vary_rich), from 0 */
    };
};
_Static_assert(sizeof(struct vertex_out) == 128, "struct vertex_out: two cache lines");
_Static_assert(offsetof(struct vertex_out, var) == offsetof(struct vertex_out, all) + VARY_BASE * 4,
               "var is all[] from VARY_BASE on");

/* The features path's varyings in all[] (offsets; -1: absent), for a mesh and mode
 * (vertex_rich_layout): all[0..2] the world position always (flat shading's centroid, the
 * view vector); interpolated are all[0 .. n) — phong and the normals view: world position,
 * normal, uv, then tangent (xyz w), colour (rgba), second uv as the mesh has them;
 * Gouraud: D and S (rgb each, or one each with grey lights) instead of the normal and no
 * tangent; flat and unlit: position and uv, colour, second uv. What does not fit in
 * VARY_ALL is dropped, last first: the second uv (its textures read the first), the colour's
 * alpha (the file's 16 varyings: a normal-mapped, vertex-coloured, two-uv mesh). */
struct vary_rich {
    int8_t n;              /* varyings interpolated: all[0 .. n) */
    int8_t nrm, d, s, uv0, uv1, tan, col;
    int8_t col_n;          /* colour channels kept (3 or 4; 0 none) */
    bool dropped_uv1, dropped_alpha;
};

/* A position's share of a vertex record (struct vertex_out): what rejection, the pixel box
 * and the hidden test read — the front end's walk by position keeps one per distinct
 * position (mesh.h's pos_id; kernel.h's position_run makes them) */
struct vertex_pos {
    int32_t fx, fy; /* valid when outcode has no VERTEX_NEEDS_CLIP bit */
    uint32_t outcode;
    float z;        /* window depth (viewport_window's, rounded to float), the same */
};

struct vertex_uniforms {
    int fb_w, fb_h;
    mat4 model, normal_matrix, mvp;
    float model_f[3][4], normal_f[3][3]; /* the same in float, for vertex_shade */
    vec3 eye;          /* world space */
    int ortho;         /* V = view_back everywhere */
    vec3 view_back;    /* unit vector toward the viewer (orthographic) */
    double guard_x, guard_y; /* guard band as multiples of w (>= 1) */
    enum shade_mode shade;
    enum debug_view view;
    struct light_env lights;
    const struct vary_rich *rich; /* the current item's mesh has features (frame.h): its
                                     varyings' layout; NULL for every other mesh */
    float model_det;               /* sign of the model matrix's determinant (tangents' w) */
};

/* The layout of the features path's varyings for mesh m drawn in mode (view: the debug
 * view; grey: light_env.grey). */
void vertex_rich_layout(const struct mesh *m, enum shade_mode mode, enum debug_view view,
                        bool grey, struct vary_rich *out);

/* Number of varyings written for a shading mode / debug view (grey: light_env.grey). Inline:
 * the span stage asks for every triangle. */
static inline int vertex_varying_count(enum shade_mode shade, enum debug_view view, bool grey)
{
    if (view == VIEW_NORMALS || shade == SHADE_PHONG)
        return 8;
    if (shade == SHADE_GOURAUD)
        return grey ? 4 : 8;
    return 2;
}
/* The bulk of the stage is each kernel's (kernel.h):
 *   vertex_run(m, u, out, i0, i1)  positions vertices i0 .. i1-1 of m into out[i0 .. i1):
 *                                  clip position, outcode, window position and snap; wpos
 *                                  and var wait for vertex_shade. Ranges may run on
 *                                  different threads.
 *   vertex_shade_many(m, u, idx, out, n)  vertex_shade for n vertices (vertex idx[k] of m
 *                                  into out[k]), several at a time when the mode is Gouraud
 *                                  or per-pixel (SIMD lanes: the square roots and divisions
 *                                  of eight vertices' normals and lighting in one
 *                                  instruction; every lane the same floats as vertex_shade). */
/* World position and varyings of vertex i (lighting for Gouraud): done only for vertices of
 * triangles that survive rejection and culling — on a closed mesh half the vertices are
 * used by back faces alone. */
void vertex_shade(const struct mesh *m, const struct vertex_uniforms *u, uint32_t i,
                  struct vertex_out *o);
/* Does vertex_shade_many gain over vertex_shade for this mesh and these uniforms? */
static inline bool vertex_shade_batched(const struct mesh *m, const struct vertex_uniforms *u)
{
    return (u->shade == SHADE_GOURAUD || u->shade == SHADE_PHONG || u->view == VIEW_NORMALS) &&
           !m->colors && !u->rich;
}
/* Outcode of a clip-space position (also used by clip.c for new vertices); the guard band
 * gx, gy >= 1 (as multiples of w: never inside the frustum). */
static inline uint32_t vertex_outcode(const double c[4], double gx, double gy)
{
    double x = c[0], y = c[1], z = c[2], w = c[3];
    uint32_t oc = 0;
    oc |= (x < -w) ? VERTEX_OUT_LEFT : 0;
    oc |= (x > w) ? VERTEX_OUT_RIGHT : 0;
    oc |= (y < -w) ? VERTEX_OUT_BOTTOM : 0;
    oc |= (y > w) ? VERTEX_OUT_TOP : 0;
    oc |= (z < -w) ? VERTEX_OUT_NEAR : 0;
    oc |= (z > w) ? VERTEX_OUT_FAR : 0;
    if (oc & 0xf) { /* inside x and y (|x|, |y| <= w): inside the wider guard band too */
        oc |= (x < -gx * w) ? VERTEX_GUARD_LEFT : 0;
        oc |= (x > gx * w) ? VERTEX_GUARD_RIGHT : 0;
        oc |= (y < -gy * w) ? VERTEX_GUARD_BOTTOM : 0;
        oc |= (y > gy * w) ? VERTEX_GUARD_TOP : 0;
    }
    /* inf or NaN (a model scaled by 1e300, say): no clipping or snapping can use it, so
     * every triangle touching it is dropped (x - x is 0 only for finite x, NaN otherwise,
     * and a NaN anywhere makes the sum NaN: one test for the four) */
    if (!((x - x) + (y - y) + (z - z) + (w - w) == 0))
        oc = VERTEX_OUT_FRUSTUM | VERTEX_NEEDS_CLIP | VERTEX_INVALID;
    return oc;
}
/* Perspective divide, viewport and the 1/256-pixel snap (viewport.h) of a vertex inside the
 * guard band with w > 0. Sets win, fx, fy, projected (depth: see struct vertex_out). */
static inline void vertex_project(struct vertex_out *v, int fb_w, int fb_h)
{
    double win[3];
    viewport_window(v->clip, fb_w, fb_h, win);
    v->win[0] = win[0], v->win[1] = win[1];
    v->fx = (int32_t)viewport_snap(win[0]);
    v->fy = (int32_t)viewport_snap(win[1]);
    v->projected = 1;
}
/* light.h's D and S at a world-space point with unit normal n (Gouraud per vertex, flat per
 * face): V toward the eye from p, or view_back for orthographic cameras. */
void vertex_light(const struct vertex_uniforms *u, const float n[3], const float p[3], float ns,
                  float d_out[3], float s_out[3]);

#endif
