/* kernel.h: the per-pixel and per-vertex kernels, one set of them per instruction set, and
 * the table that says which kernel draws what.
 *
 * The hot loops of the pipeline — the vertex stage (vertex.h), the edge rasterizer
 * (raster.h), interpolation setup (setup.h), the per-pixel work (span.h) and the sky — are
 * written once, in the bodies in src/render/kernel/kernel_*.h, and compiled once per
 * instruction set, each copy in a file of its own (as Intel's Masked Occlusion Culling
 * keeps one .cpp per ISA around one common body):
 *   kernel_sse2.c    the x86-64 baseline: SSE2, four lanes (simd.h)
 *   kernel_avx2.c    AVX2, eight lanes (-mavx2 -mno-fma: the same IEEE operations in the
 *                    same order, so the same bytes, with blends, gathers and three-operand
 *                    forms)
 *   kernel_avx2_4.c  AVX2, four lanes: a triangle of up to four pixels fills one group of
 *                    four with half the per-lane loads and stores of a group of eight
 *   kernel_ref.c     the REFERENCE: scalar, plain C, one pixel at a time — the project's
 *                    tinyrenderer-sized rasterize. Every fast kernel must write exactly its
 *                    bytes; the tests compare each of them with it (test_methods.c,
 *                    test_vertex.c, test_skybox.c).
 * Each file defines one table, struct kernel, of its copies. Which table draws is decided
 * once, here (kernel_set), from render_opts.kernel (--kernel; $RASTTY_SIMD sets its
 * default), and the frame picks its functions from the tables once (kernel_choose_span: the
 * per-pixel function by method, and by the triangle's size class) — no hot function asks
 * which instruction set it runs on.
 *
 * Names inside the bodies: a function with the suffix _v works on SIMD_LANES pixels (or
 * vertices) at once, a vector per quantity, and gives in every lane exactly what the scalar
 * function of the same name without _v gives (the reference kernel is built from the scalar
 * ones); see simd.h. */
#ifndef RASTTY_KERNEL_H
#define RASTTY_KERNEL_H

#include <stdbool.h>
#include <stdint.h>

#include "camera.h"
#include "fb.h"
#include "mesh.h"
#include "raster.h"
#include "render_opts.h"
#include "skybox.h"
#include "span.h"
#include "vertex.h"

struct kernel {
    const char *name;
    int lanes; /* pixels (vertices) a vector holds; 1 for the reference */
    /* The span stage (span.h), one function per shading mode (wire: depth only):
     *   span_one_pixel   the default methods (depth z, perspective-correct), a pixel at a
     *                    time: for triangles of one pixel, which a group of lanes would
     *                    cost its setting up whatever it holds
     *   span_packs_z     the default methods in packs of SIMD_LANES pixels (span.h), with a
     *                    copy per texture filter: every test folds away
     *   span_packs       any depth method, perspective-correct or affine, in packs
     *   span_runs        run by run: the span methods, the overdraw count, the normals view */
    span_fn span_one_pixel[SHADE_COUNT];
    span_fn span_packs_z[SHADE_COUNT][TEX_FILTER_COUNT];
    span_fn span_packs[SHADE_COUNT];
    span_fn span_runs[SHADE_COUNT];
    /* the features path (materials with features, shade.h): every method, a pixel at a time
     * through kernel_rich_pixel, the same scalar function in every kernel */
    span_fn span_rich[SHADE_COUNT];
    /* by enum raster_method: the edge rasterizer is the kernel's own, scanline and tiled
     * are shared (raster_scan.c, raster_tile.c); the reference has one plain loop for all */
    raster_fn raster[RASTER_COUNT];
    /* vertex.h's vertex_run and vertex_shade_many */
    void (*vertex_run)(const struct mesh *m, const struct vertex_uniforms *u,
                       struct vertex_out *out, uint32_t i0, uint32_t i1);
    /* points p0 .. p1 (point i: three floats `stride` bytes on from xyz, i strides in: a
     * mesh's positions, or its vertices' positions in place) as vertex_run positions a
     * vertex, kept as struct vertex_pos in out[i]: outcode, snapped window position and
     * depth (the front end's walk by position) */
    void (*position_run)(const float *xyz, size_t stride, const struct vertex_uniforms *u,
                         struct vertex_pos *out, uint32_t p0, uint32_t p1);
    void (*vertex_shade_many)(const struct mesh *m, const struct vertex_uniforms *u,
                              const uint32_t *idx, struct vertex_out *const *out, uint32_t n);
    /* The sky (scene/skybox.h) in rows y0 .. y1-1 of fb: every pixel nothing covered (its
     * depth still the clear value) gets the sky seen through cam (orthographic cameras see
     * it as a perspective camera with the same fov would); bands of rows may be drawn on
     * different threads (a pixel depends on its position alone). Trilinear between the two
     * face levels around the one whose texel matches a pixel. */
    void (*sky_rows)(const struct skybox *s, const struct camera *cam, struct fb *fb, int y0,
                     int y1);
};

/* The kernels an instruction set draws with: by the size class of a triangle (span.h:
 * one pixel, two to four, more), and whether one-pixel triangles take span_one_pixel.
 * The vertex stage, the rasterizers and the sky use by_size[SPAN_SIZE_LARGE]. */
struct kernel_set {
    const char *name;
    const struct kernel *by_size[SPAN_SIZES];
    bool one_pixel;
};

/* The set for a --kernel choice: KERNEL_AUTO is "avx2" on a CPU that has AVX2 (x86-64
 * builds), else "sse2"; NULL when this build or CPU cannot run the one asked for. */
const struct kernel_set *kernel_set(enum kernel_isa isa);

/* The frame's per-pixel functions (s->flush, by size class), from the set's tables and s's
 * methods: once a frame, before any triangle (the pipeline calls it on the template every
 * thread's span_ctx starts from). The same methods the function has in its name: the
 * default methods (depth z, perspective-correct) in packs by shading mode and filter, or a
 * pixel at a time for one-pixel triangles when ks->one_pixel; any other depth method,
 * perspective-correct or affine, in packs; the span methods, the overdraw count and the
 * normals view run by run. */
void kernel_choose_span(const struct kernel_set *ks, struct span_ctx *s);

/* The tables (kernel_*.c); the AVX2 ones only in x86-64 builds with RASTTY_KERNEL_AVX2. */
extern const struct kernel kernel_ref, kernel_sse2, kernel_avx2, kernel_avx2_4;

#endif
