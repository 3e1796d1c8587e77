/* kernel.c: which kernels draw (see kernel.h) — the one place that knows the instruction
 * sets. */
#include "kernel.h"

/* the sets --kernel names (render_kernel_names), by enum kernel_isa */
static const struct kernel_set sets[KERNEL_ISA_COUNT] = {
    [KERNEL_REF] = {"ref", {&kernel_ref, &kernel_ref, &kernel_ref}, false},
    [KERNEL_SSE2] = {"sse2", {&kernel_sse2, &kernel_sse2, &kernel_sse2}, false},
#ifdef RASTTY_KERNEL_AVX2
    /* one-pixel triangles a pixel at a time, up to four pixels in one group of four, the
     * rest eight at a time: demo 160x96 7.46M -> 7.13M instructions a frame with the
     * one-pixel path (two pixels a triangle: Phong slower, not kept) */
    [KERNEL_AVX2] = {"avx2", {&kernel_avx2_4, &kernel_avx2_4, &kernel_avx2}, true},
    [KERNEL_AVX2_4] = {"avx2-4", {&kernel_avx2_4, &kernel_avx2_4, &kernel_avx2_4}, false},
    [KERNEL_AVX2_8] = {"avx2-8", {&kernel_avx2, &kernel_avx2, &kernel_avx2}, false},
#endif
};

static bool cpu_has_avx2(void)
{
#ifdef RASTTY_KERNEL_AVX2
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx2");
#else
    return false;
#endif
}

const struct kernel_set *kernel_set(enum kernel_isa isa)
{
    if (isa == KERNEL_AUTO)
        isa = cpu_has_avx2() ? KERNEL_AVX2 : KERNEL_SSE2;
    if ((unsigned)isa >= KERNEL_ISA_COUNT || !sets[isa].name)
        return NULL;
    if (sets[isa].by_size[SPAN_SIZE_LARGE]->lanes == 8 || isa == KERNEL_AVX2_4)
        if (!cpu_has_avx2())
            return NULL;
    return &sets[isa];
}

/* the function of kernel k for s's methods */
static span_fn choose(const struct kernel *k, const struct span_ctx *s, bool one_pixel)
{
    const enum tex_filter f = s->shade ? s->shade->filter : TEX_NEAREST;
    const bool in_packs = (s->persp == PERSP_CORRECT || s->persp == PERSP_AFFINE) &&
                          !s->fb->overdraw && (!s->shade || s->shade->view != VIEW_NORMALS);
    if (!in_packs)
        return k->span_runs[s->mode];
    if (s->depth == DEPTH_Z && s->persp == PERSP_CORRECT)
        return one_pixel ? k->span_one_pixel[s->mode] : k->span_packs_z[s->mode][f];
    return k->span_packs[s->mode];
}

void kernel_choose_span(const struct kernel_set *ks, struct span_ctx *s)
{
    for (int c = 0; c < SPAN_SIZES; c++) {
        s->flush_path[0][c] = choose(ks->by_size[c], s, c == SPAN_SIZE_ONE && ks->one_pixel);
        s->flush_path[1][c] = ks->by_size[c]->span_rich[s->mode];
        s->flush[c] = s->flush_path[0][c];
    }
    s->path = 0;
}
