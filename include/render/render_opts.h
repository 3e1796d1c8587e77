/* render_opts.h: everything that chooses HOW a frame is drawn, in one value.
 *
 * The same struct render_opts reaches the pipeline from `rastty render`, `dump`, the viewer
 * and the benchmarks, so every method is selectable everywhere (what a frame reports back,
 * struct frame_stats, is pipeline.h's).
 *
 * Lighting model (conventions): directional lights (direction TOWARD the light, colour),
 * default one white light toward (1,1,1). With V toward the eye and H = normalize(L+V):
 *   c = albedo * (0.1 + 0.9 * sum_l max(0,N.L)*col_l) + ks * sum_l max(0,N.H)^ns * col_l
 * clamped to [0,1]; albedo = material kd * texture texel (texel = 1 without texture);
 * ks = 0.5 and ns = 32 unless the MTL says otherwise.
 *   unlit   : c = albedo
 *   flat    : N = face normal (file winding, world space); diffuse and specular evaluated once
 *             per triangle with V from the triangle's centroid; albedo still per pixel.
 *   gouraud : diffuse and specular sums evaluated per vertex (V per vertex), interpolated
 *             (perspective-correct), combined per pixel with the per-pixel albedo.
 *   phong   : N (interpolated, renormalised) and V (from interpolated world position) per
 *             pixel.
 *   wire    : triangle edges as Bresenham lines (line.h), in the wire colour.
 * Orthographic cameras use a constant V = camera_back(). Normals are not flipped for back
 * faces. */
#ifndef RASTTY_RENDER_OPTS_H
#define RASTTY_RENDER_OPTS_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "fb.h"
#include "lod.h"
#include "scene.h"
#include "texture.h"
#include "vecmath.h"

#define RENDER_MAX_LIGHTS SCENE_MAX_LIGHTS

enum shade_mode { SHADE_UNLIT, SHADE_FLAT, SHADE_GOURAUD, SHADE_PHONG, SHADE_WIRE, SHADE_COUNT };
/* --wire: which edges wireframe draws (frontend_edges, edges.h).
 *   all     every triangle's three edges.
 *   outline the edges a terminal can show: silhouettes (the faces on either side face
 *           different ways from the eye), creases (they turn by more than EDGE_CREASE_DEG)
 *           and the mesh's borders.
 *   auto    all while they are readable: outline when the edges' projected length exceeds
 *           WIRE_DENSITY_MAX pixels per pixel of the model's projected area (1-pixel lines
 *           would light more than that fraction of it: a white blob). */
enum wire_mode { WIRE_AUTO, WIRE_ALL, WIRE_OUTLINE, WIRE_COUNT };
#define WIRE_DENSITY_MAX 0.5
/* CULL_AUTO (the default): as the model's materials say — glTF's single-sided materials
 * (doubleSided false) drop their back faces, every other face is drawn (the conventions'
 * "no culling" for OBJ and the formats without a rule) */
enum cull_mode { CULL_NONE, CULL_BACK, CULL_FRONT, CULL_AUTO, CULL_COUNT };
/* Methods: each axis picks one way to do a stage; every combination draws the same scene.
 * What each costs and where it fails is documented beside its code: rasterizers in raster.h,
 * perspective methods in span.h, depth buffers in fb.h (enum depth_mode). */
enum raster_method { RASTER_EDGE, RASTER_SCANLINE, RASTER_TILED, RASTER_COUNT };
enum persp_method { PERSP_CORRECT, PERSP_AFFINE, PERSP_SPAN8, PERSP_SPAN16, PERSP_SPAN32,
                    PERSP_COUNT };
/* Supersampling (--ssaa N; ssaa.h does it around pipeline_draw, which ignores the field):
 * k x k samples per pixel with k = render_ssaa_factor(), averaged with a box filter. */
enum ssaa_method { SSAA_1, SSAA_2, SSAA_4, SSAA_8, SSAA_COUNT };

/* What the framebuffer's colour shows after the frame (the viewer's `v` key). */
enum debug_view { VIEW_COLOR, VIEW_DEPTH, VIEW_NORMALS, VIEW_OVERDRAW, VIEW_WIRE_OVERLAY,
                  VIEW_COUNT };

/* How several threads share a frame (--split; the picture never depends on it, a test
 * checks every method at 1, 2, 3 and 5 threads both ways):
 *   SPLIT_TILES   the calling thread runs the front end (vertices, culling, setup) while the
 *                 pool draws the set-up triangles by 64x64 screen tile (llvmpipe's way).
 *                 Fails: at terminal sizes a dense mesh is mostly front end, which stays on
 *                 one thread — two threads draw the head at 160x96 no faster than one.
 *   SPLIT_SLICES  thread k takes the k-th slice of the frame's triangles (in submission
 *                 order) through the whole pipeline into a framebuffer of its own; the
 *                 framebuffers are then merged pixel by pixel, the nearer fragment winning
 *                 and on a tie the earlier slice — which is what one thread drawing every
 *                 slice in turn keeps, since the depth test is strict. Costs: a framebuffer
 *                 per thread to clear and merge, and the vertices two slices share done in
 *                 both. Fails: large frames, where the clear and the merge grow with the
 *                 pixels while a dense mesh's front end does not. The counts of lit
 *                 vertices and shaded pixels are then summed over the slices (a fragment a
 *                 later slice hides is still counted), so they can exceed one thread's.
 *   SPLIT_AUTO    slices when the frame holds at least one triangle (after culling of
 *                 whole meshes) for every PIPELINE_SLICE_PIXELS pixels, else tiles; tiles
 *                 always for wireframe, the wireframe overlay and the overdraw count. */
/* Cluster culling (--cluster-cull; cluster_cull.h): whole clusters of a mesh's triangles
 * dropped before the vertex stage when they cannot reach a pixel, or (with --hidden-cull)
 * lie behind the depth drawn so far. Never changes a picture. On by default (README, "Cost
 * against triangles": at 160x96 the sports car 26% faster, the 1M sphere 39%, the bunny
 * and the head 2%). */
enum cluster_cull { CLUSTER_CULL_OFF, CLUSTER_CULL_ON, CLUSTER_CULL_COUNT };
/* Hidden triangles (--hidden-cull; frontend.h, "Hidden"): a triangle whose nearest corner
 * lies at or behind what the depth buffer already holds over its whole pixel box is dropped
 * before its vertices are lit or it is set up. Never changes a picture. On by default. */
enum hidden_cull { HIDDEN_CULL_OFF, HIDDEN_CULL_ON, HIDDEN_CULL_COUNT };
/* Occluders (--occluders; frontend.h, "Occluders"): the triangles each draw item drew in
 * the last frame, drawn first at this frame's view into a depth of their own; a cluster or
 * triangle strictly behind them over its whole box is dropped as hidden. Never changes a
 * picture. on: an item's occluders sit out a few frames when they hid too little for their
 * cost (frontend.h's FRONTEND_OCC_PAYS); always: never (tests). On by default (README, "Occluders": at 160x96 the sports car 3.54 -> 3.01 ms,
 * lost_empire 6.72 -> 4.85, from the second frame on). */
enum occluders { OCCLUDERS_OFF, OCCLUDERS_ON, OCCLUDERS_ALWAYS, OCCLUDERS_COUNT };

enum thread_split { SPLIT_AUTO, SPLIT_TILES, SPLIT_SLICES, SPLIT_COUNT };

/* Which instruction set's kernels draw (--kernel; kernel.h): auto is AVX2 where the CPU has
 * it (x86-64), else SSE2; ref is the scalar reference every other kernel must match byte for
 * byte; avx2-4 and avx2-8 draw every triangle with one AVX2 width (avx2 picks the width by
 * the triangle's size). The picture never depends on it. */
enum kernel_isa { KERNEL_AUTO, KERNEL_REF, KERNEL_SSE2, KERNEL_AVX2, KERNEL_AVX2_4, KERNEL_AVX2_8,
                  KERNEL_ISA_COUNT };

/* By heads (render_opts.heads_ratio, default this; render/frontend.c): a mesh with more
 * vertices than this many times the framebuffer's pixels, and no pos_id (walked by
 * position instead), is walked as by position with every vertex its own position — the
 * vertex stage makes each vertex's head alone (outcode, snapped window position, depth: 16
 * bytes, position_run reading the vertices in place) and the records only of the
 * triangles that draw. Where the vertex records are the
 * frame's cost it pays (160x96, one thread: the 1M sphere 10.3 -> 8.2 ms, 4M 37.4 -> 28.4;
 * at 640x480 the 4M sphere 54.1 -> 47.3, the 1M 22.0 -> 21.2); where many triangles draw
 * for the vertices staged it does not (the car at 160x96, 11 vertices a pixel: 4.59 ->
 * 4.81; at 320x192 8.73 -> 8.86; the 100k sphere 1.35 -> 1.36). */
#define RENDER_HEADS_RATIO 16

struct render_opts {
    enum shade_mode shade;
    enum tex_filter filter;
    enum raster_method raster;  /* --raster: which pixels a triangle covers */
    enum persp_method persp;    /* --persp: how varyings are interpolated */
    enum depth_mode depth;      /* --depth: what the depth buffer stores */
    int threads;                /* --threads: 0 = one per core; the picture never depends on it */
    enum thread_split split;    /* --split: how the threads share the frame */
    enum kernel_isa kernel;     /* --kernel: whose kernels draw; the picture never depends on it */
    enum ssaa_method ssaa;      /* --ssaa: samples per pixel (ssaa.h) */
    enum lod_mode lod;          /* --lod: which simplified level of each mesh is drawn */
    float lod_ratio;            /* LOD_RATIO: fraction of the triangles kept, (0, 1] */
    float lod_px;               /* LOD_AUTO: largest error on screen, in pixels (> 0) */
    enum cull_mode cull;
    enum cluster_cull cluster_cull; /* --cluster-cull: the picture never depends on it */
    enum hidden_cull hidden_cull;   /* --hidden-cull: nor on it */
    enum occluders occluders;       /* --occluders: nor on it */
    int heads_ratio; /* walk a mesh by its vertices' heads when it has more vertices than
                        this many times the framebuffer's pixels (default
                        RENDER_HEADS_RATIO, 0 always, negative never): nor on it */
    enum debug_view view;
    bool textures;       /* sample material / override textures (else albedo = kd) */
    bool hidden_lines;   /* wire: hide edges behind the model's surfaces (depth pre-pass) */
    enum wire_mode wire; /* wire: which edges (auto: all while readable, else the outline) */
    uint8_t background[3];
    uint8_t wire_color[3];
    int n_lights;
    struct light lights[RENDER_MAX_LIGHTS];
    vec3 ambient_sky, ambient_ground; /* hemisphere ambient (light.h): from straight above
                                       * (+Y) and below; both 0.1 = the constant 0.1 */
};

/* Defaults from the conventions: phong, trilinear, edge rasterizer, perspective-correct, float
 * window depth, no supersampling, every mesh in full (lod off; auto's bound LOD_DEFAULT_PX),
 * culling as the model says (auto: none but glTF's single-sided materials), textures on, black background, white wire colour, one white light toward
 * (1,1,1), ambient 0.1. */
void render_opts_default(struct render_opts *o);
/* The ideal image's methods — rastty's most accurate setting, the reference every method is
 * measured against (bench --chart): perspective-correct, trilinear, --ssaa 8, meshes in full
 * (lod off). Everything else (shading, lights, depth method, rasterizer, ...) is left as it
 * is. */
void render_opts_ideal(struct render_opts *o);

/* --ssaa's k: 1, 2, 4 or 8 samples per axis */
static inline int render_ssaa_factor(enum ssaa_method m)
{
    return 1 << (int)m;
}

/* Every enum-valued option by name: the flag parser, --help, the HUD and the viewer's cycle
 * keys all read these tables. names[v] is the spelling of value v; n is the count. */
struct render_enum {
    const char *const *names;
    int n;
};
extern const struct render_enum render_shade_names, render_cull_names, render_filter_names,
    render_view_names, render_raster_names, render_persp_names, render_depth_names,
    render_ssaa_names, render_lod_names, render_split_names, render_kernel_names,
    render_cluster_cull_names, render_hidden_cull_names, render_occluders_names,
    render_wire_names;

const char *render_shade_name(enum shade_mode m);
const char *render_cull_name(enum cull_mode m);
const char *render_filter_name(enum tex_filter f);
const char *render_view_name(enum debug_view v);
const char *render_raster_name(enum raster_method m);
const char *render_persp_name(enum persp_method m);
const char *render_depth_name(enum depth_mode m);
/* Parse a name back; -1 if unknown. */
int render_enum_parse(const struct render_enum *t, const char *s);
/* A method axis as data (the chart's and the sweeps'): the int-sized enum field of o at
 * offset `field` (offsetof(struct render_opts, raster) and the like). */
int render_opts_get(const struct render_opts *o, size_t field);
void render_opts_set(struct render_opts *o, size_t field, int v);

#endif
