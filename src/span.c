/* span.c: depth test, interpolation, shading and the write for a run of pixels (see span.h). */
#include "span.h"

#include <math.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

#include "simd.h"

/* This file is compiled three times on x86-64 (Makefile): once for the baseline (SSE2, four
 * lanes), and twice with -mavx2 -DSPAN_AVX2_COPY, which makes only span_flush_avx2 (eight
 * lanes, -DSIMD_LANES=8) or span_flush_avx2_4 (four) — the same C, so the same IEEE
 * operations in the same order (no fused multiply-add: -mno-fma, -ffp-contract=off) and the
 * same bytes, in VEX encoding with blends, rounding and 32-bit multiplies (simd.h). A
 * triangle of at most four pixels fills one group of four: the four-lane copy draws it with
 * half the per-lane loads and stores of a group of eight (span_flush). */
void span_flush_avx2(struct span_ctx *s, bool pixelwise);
void span_flush_avx2_4(struct span_ctx *s, bool pixelwise);
/* triangles of at most this many pixels are drawn a pixel at a time (pixels()): one pixel
 * 7.46M -> 7.13M instructions a frame on the demo at 160x96, two 7.21M (Phong slower) */
#define SPAN_PIXELS_MAX 1
#if defined(SPAN_AVX2_COPY) && SIMD_LANES == 8
#define SPAN_FLUSH span_flush_avx2
#elif defined(SPAN_AVX2_COPY)
#define SPAN_FLUSH span_flush_avx2_4
#else
#define SPAN_FLUSH span_flush_base
static void span_flush_base(struct span_ctx *s, bool pixelwise);

void span_begin(struct span_ctx *s, const struct setup_tri *t, const struct shade_tri *st,
                uint32_t tri_index)
{
    s->tri = t;
    s->st = st;
    s->tri_index = tri_index;
    s->in_ready = false;
    s->n_runs = 0;
    s->n_pixels = 0;
}

#ifdef RASTTY_SPAN_AVX2
static bool cpu_has_avx2(void)
{
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx2");
}
#else
static bool cpu_has_avx2(void)
{
    return false;
}
#endif

static atomic_int isa_now = -1; /* enum span_isa, -1 until first asked */

int span_isa_set(const char *name)
{
    int isa;
    if (!strcmp(name, "auto"))
        isa = cpu_has_avx2() ? SPAN_ISA_AVX2 : SPAN_ISA_SSE2;
    else if (!strcmp(name, "sse2"))
        isa = SPAN_ISA_SSE2;
    else if (!strcmp(name, "avx2") && cpu_has_avx2())
        isa = SPAN_ISA_AVX2;
    else if (!strcmp(name, "avx2-4") && cpu_has_avx2())
        isa = SPAN_ISA_AVX2_4;
    else if (!strcmp(name, "avx2-8") && cpu_has_avx2())
        isa = SPAN_ISA_AVX2_8;
    else
        return -1;
    atomic_store_explicit(&isa_now, isa, memory_order_relaxed);
    return 0;
}

int span_isa_get(void)
{
    int isa = atomic_load_explicit(&isa_now, memory_order_relaxed);
    if (isa >= 0)
        return isa;
    const char *env = getenv("RASTTY_SIMD");
    if (!env || span_isa_set(env))
        span_isa_set("auto");
    return atomic_load_explicit(&isa_now, memory_order_relaxed);
}

const char *span_isa_name(void)
{
    static const char *const names[] = {"sse2", "avx2", "avx2-4", "avx2-8"};
    return names[span_isa_get()];
}

void span_flush(struct span_ctx *s)
{
    switch (span_isa_get()) {
#ifdef RASTTY_SPAN_AVX2 /* (span_isa_set refuses AVX2 in builds without the copies) */
    case SPAN_ISA_AVX2_4: span_flush_avx2_4(s, false); break;
    case SPAN_ISA_AVX2_8: span_flush_avx2(s, false); break;
    case SPAN_ISA_AVX2: /* a triangle of up to four pixels fills one group of four */
        if (s->n_pixels <= 4)
            span_flush_avx2_4(s, s->n_pixels <= SPAN_PIXELS_MAX);
        else
            span_flush_avx2(s, false);
        break;
#endif
    default: span_flush_base(s, false); break;
    }
}
#endif

/* floor(a / b), b > 0 */
static inline int64_t floor_div(int64_t a, int64_t b)
{
    int64_t q = a / b;
    return q - (a % b < 0);
}

/* The first and last covered column of row y, from the edge functions (the same integers
 * every rasterizer tests): the ends that span methods clamp their spans to. */
static void row_extent(const struct setup_tri *t, int y, int *lo_out, int *hi_out)
{
    int64_t lo = t->x0, hi = t->x1;
    for (int k = 0; k < 3; k++) {
        int64_t a = t->e_dx[k], e = t->e[k] + (int64_t)(y - t->y0) * t->e_dy[k];
        if (a > 0) { /* e + (x - x0) a >= 0  <=>  x >= x0 - floor(e / a) */
            int64_t b = t->x0 - floor_div(e, a);
            lo = b > lo ? b : lo;
        } else if (a < 0) { /* x <= x0 + floor(e / -a) */
            int64_t b = t->x0 + floor_div(e, -a);
            hi = b < hi ? b : hi;
        }
    }
    *lo_out = (int)lo, *hi_out = (int)hi;
}

/* a plane's value on row y (its row base), then at column offset X: the fixed order */
static inline float row_of(const struct setup_plane *p, float Y)
{
    return p->c + p->dy * Y;
}

/* The varyings exactly (one division) at column offset X of the row whose denominator and
 * numerator bases are qr, ar; qdx, adx their steps per column. */
static inline void exact_at(float qr, float qdx, const float *ar, const float *adx, float X,
                            int n_var, float *var_out)
{
    float rq = 1.0f / (qr + qdx * X);
    for (int k = 0; k < n_var; k++)
        var_out[k] = (ar[k] + adx[k] * X) * rq;
}

/* varyings a triangle's pixels interpolate in a shading mode */
static inline int span_n_var(const struct span_ctx *s, enum shade_mode mode)
{
    /* (the depth-only pass has no shading record: never look at s->st there) */
    return mode == SHADE_WIRE        ? 0
           : s->st->vcolor           ? VARY_COLOR + 3
           : vertex_varying_count(mode, VIEW_COLOR, s->shade->lights.grey);
}

/* What the texture's level of detail needs (trilinear): the planes of u, v and q per pixel
 * step, in every lane. */
struct lod_planes {
    vf udx, vdx, qdx, udy, vdy, qdy;
};

static inline struct lod_planes lod_planes_of(const struct setup_interp *in)
{
    return (struct lod_planes){vf_set(in->a_dx[0]), vf_set(in->a_dx[1]), vf_set(in->q.dx),
                               vf_set(in->a_dy[0]), vf_set(in->a_dy[1]), vf_set(in->q.dy)};
}

/* The rest of a group of pixels once its depth test is done: the colour of the lanes in
 * `pass` from their varyings, quantised and written. rq: 1 / q at the group's pixels (the
 * level of detail's d(a/q) = (da - (a/q) dq) / q, exactly, from the planes). The pixels'
 * colours are at rgb + off[l]; `contig`: at rgb + off[0] + 3 l instead (side by side; when
 * every lane passed, one wide store). */
static inline __attribute__((always_inline)) void
shade_write_v(const struct span_ctx *s, const enum shade_mode mode, const enum tex_filter filter,
              const bool lod, const struct lod_planes *lp, int pow_k, const vf *var, vf rq,
              vi pass, uint8_t *restrict rgb, const bool contig, const size_t off[SIMD_LANES])
{
    const struct shade_tri *st = s->st;
    vf lambda = vf_set(0);
    if (lod)
        lambda = texture_lod_v(st->tex, (lp->udx - var[0] * lp->qdx) * rq,
                               (lp->vdx - var[1] * lp->qdx) * rq,
                               (lp->udy - var[0] * lp->qdy) * rq,
                               (lp->vdy - var[1] * lp->qdy) * rq);
    vf c[3];
    shade_fragment_v(s->shade, mode, filter, st, pow_k, var, lambda, c);
    vi r8 = fb_quantize_v(c[0]), g8 = fb_quantize_v(c[1]), b8 = fb_quantize_v(c[2]);
    const vi px = r8 | (g8 << 8) | (b8 << 16);
    if (contig && vi_all(pass)) {
        fb_store_rgb_v(rgb + off[0], px);
        return;
    }
    for (int l = 0; l < SIMD_LANES; l++) /* lane by lane */
        if (pass[l])
            fb_store_rgb(rgb + (contig ? off[0] + 3 * (size_t)l : off[l]), (uint32_t)px[l]);
}

/* One run in any method, instantiated per shading mode by span_flush's switch: `mode` is a
 * compile-time constant in each copy, so the shading's switches fold away. Pixels go
 * SIMD_LANES at a time (simd.h): depth, the test and the varyings of a group in a few vector
 * operations, then the shading a group at a time too (shade_write_v; the normals view lane by
 * lane). A lane's arithmetic is the scalar formula, so a pixel's bytes never depend on
 * where its group started. Every plane coefficient is copied into a local first:
 * the framebuffer's byte stores may alias anything and would otherwise force reloads. */
static inline __attribute__((always_inline)) void run(struct span_ctx *s, int y, int xa, int xb,
                                                      const enum shade_mode mode,
                                                      const enum depth_mode depth,
                                                      const enum persp_method persp,
                                                      const enum tex_filter filter)
{
    const struct setup_interp *in = &s->in;
    const struct setup_tri *t = s->tri;
    const int n_var = span_n_var(s, mode);
    const int span_n = persp == PERSP_SPAN8 ? 8 : persp == PERSP_SPAN16 ? 16 : 32;
    const float Y = (float)(y - t->y0);
    /* depth: the plane's value as c + (small part), rounded once (setup.h) */
    const vf zc = vf_set(in->z.c);
    const float zr = in->z_c_lo + in->z.dy * Y, zqr = row_of(&in->zq, Y), qr = row_of(&in->q, Y);
    const vf zdx = vf_set(in->z.dx), zqdx = vf_set(in->zq.dx), qdx = vf_set(in->q.dx);
    const vf z_lo = vf_set(in->z_lo), z_hi = vf_set(in->z_hi);
    float ar[VARY_MAX], adx[VARY_MAX];
    vf ar4[VARY_MAX]; /* the row bases in every lane: row_of, a group at a time */
    vf adx4[VARY_MAX];
    const vf Y4 = vf_set(Y);
    for (int k = 0; k < n_var; k++) {
        ar4[k] = vf_set(in->a_c[k]) + vf_set(in->a_dy[k]) * Y4;
        ar[k] = ar4[k][0];
        adx[k] = in->a_dx[k];
        adx4[k] = vf_set(adx[k]);
    }
    const bool lod = mode != SHADE_WIRE && filter == TEX_TRILINEAR && s->st->tex;
    const struct lod_planes lp = lod_planes_of(in);
    const int x_org = t->x0, fb_w = s->fb->w;
    const size_t row = (size_t)y * (size_t)fb_w;
    float *restrict depth_buf = s->fb->depth + row;
    uint8_t *restrict rgb_buf = s->fb->rgb + 3 * row;
    uint32_t *restrict overdraw = s->fb->overdraw ? s->fb->overdraw + row : NULL;
    const struct shade_ctx *sc = s->shade;
    const int pow_k = mode == SHADE_PHONG ? light_pow_int(s->st->mat->ns) : 0;
    /* span methods: the current span's absolute start column, its clamped ends, the
     * varyings there and their change per pixel; the row's covered extent */
    int anchor = -1, a0 = 0, row_lo = -1, row_hi = -1;
    float va[VARY_MAX] = {0}, vd[VARY_MAX] = {0};
    uint64_t shaded = 0;
    const vf lane = vf_lanes();
    for (int x = xa; x <= xb; x += SIMD_LANES) {
        const int n = xb - x + 1 < SIMD_LANES ? xb - x + 1 : SIMD_LANES;
        const vf X = vf_set((float)(x - x_org)) + lane;
        vf z = zc + (vf_set(zr) + zdx * X);
        if (depth == DEPTH_W)
            z = z / (vf_set(zqr) + zqdx * X);
        z = vf_max(z_lo, z); /* never past the corners: z < z_lo ? z_lo : z */
        z = vf_min(z_hi, z); /* z > z_hi ? z_hi : z */
        if (depth == DEPTH_Z16) { /* floor(z * 65535 + 0.5); z is in [0, 1] */
            vf q = z * vf_set(65535.0f) + vf_set(0.5f);
            vi qi = vi_trunc(q);
            z = vf_from_vi(qi);
        }
        vf old;
        if (n == SIMD_LANES) /* a whole group inside the run: one load */
            __builtin_memcpy(&old, depth_buf + x, sizeof old);
        else /* never past the run: the pixels after it may be another thread's tile */
            for (int l = 0; l < SIMD_LANES; l++)
                old[l] = l < n ? depth_buf[x + l] : 0;
        vi pass = (depth == DEPTH_RZ ? z > old : z < old) & (vf_set((float)n) > lane);
        if (overdraw)
            for (int l = 0; l < n; l++)
                overdraw[x + l]++;
        if (!vi_any(pass))
            continue;
        if (n == SIMD_LANES) { /* a whole group inside the run: one store */
            vf kept = vf_select(pass, z, old);
            __builtin_memcpy(depth_buf + x, &kept, sizeof kept);
            shaded += (uint64_t)vi_count(pass);
        } else {
            for (int l = 0; l < n; l++)
                if (pass[l]) {
                    depth_buf[x + l] = z[l];
                    shaded++;
                }
        }
        if (mode == SHADE_WIRE)
            continue;
        vf var[VARY_MAX];
        const vf rq = vf_set(1.0f) / (vf_set(qr) + qdx * X);
        if (persp == PERSP_CORRECT || persp == PERSP_AFFINE) {
            for (int k = 0; k < n_var; k++)
                var[k] = (ar4[k] + adx4[k] * X) * rq;
        } else {
            for (int k = 0; k < n_var; k++)
                var[k] = vf_set(0);
            for (int l = 0; l < n; l++) {
                int xl = x + l, a = xl - xl % span_n; /* x >= 0 */
                if (a != anchor) { /* a new span: exact varyings at both (clamped) ends */
                    if (row_lo < 0)
                        row_extent(t, y, &row_lo, &row_hi);
                    anchor = a;
                    a0 = a > row_lo ? a : row_lo;
                    int a1 = a + span_n < row_hi ? a + span_n : row_hi;
                    float vb[VARY_MAX];
                    exact_at(qr, in->q.dx, ar, adx, (float)(a0 - x_org), n_var, va);
                    exact_at(qr, in->q.dx, ar, adx, (float)(a1 - x_org), n_var, vb);
                    float inv_len = a1 > a0 ? 1.0f / (float)(a1 - a0) : 0;
                    for (int k = 0; k < n_var; k++)
                        vd[k] = (vb[k] - va[k]) * inv_len;
                }
                float f = (float)(xl - a0);
                for (int k = 0; k < n_var; k++)
                    var[k][l] = va[k] + f * vd[k];
            }
        }
        if (sc->view == VIEW_NORMALS) { /* lane by lane */
            for (int l = 0; l < n; l++) {
                if (!pass[l])
                    continue;
                float v1[VARY_MAX] = {0}, rgb[3];
                for (int k = 0; k < n_var; k++)
                    v1[k] = var[k][l];
                shade_fragment(sc, mode, s->st, v1, rgb);
                uint8_t *p = rgb_buf + 3 * (x + l);
                p[0] = fb_quantize(rgb[0]), p[1] = fb_quantize(rgb[1]), p[2] = fb_quantize(rgb[2]);
            }
            continue;
        }
        const size_t off[SIMD_LANES] = {3 * (size_t)x}; /* side by side: lanes past the run
                                                           are never in pass */
        shade_write_v(s, mode, filter, lod, &lp, pow_k, var, rq, pass, rgb_buf, true, off);
    }
    s->tested += (uint64_t)(xb - xa + 1);
    s->shaded += shaded;
}

/* The triangle's constants a group of the default methods reads, in every lane. */
struct pack_ctx {
    vf zc, z_c_lo, zdy, zdx, z_lo, z_hi; /* depth: c + ((c_lo + dy Y) + dx X) */
    vf zqc, zqdy, zqdx;                  /* DEPTH_W: its denominator */
    vf qc, qdy, qdx;
    const float *a_c, *a_dy, *a_dx; /* the varyings' planes (setup_interp's), broadcast where
                                       used: one load each with AVX, and no copies to keep */
    int n_var, pow_k;
    bool lod;
    struct lod_planes lp;
    float *restrict depth;
    uint8_t *restrict rgb;
};

/* One group of the methods that go in packs (any depth method, perspective-correct or
 * affine; no overdraw count, no normals view): pixels at columns x_org + X, rows y_org + Y.
 * `contig`: SIMD_LANES pixels of a run side by side, the first at index `first` of the
 * framebuffer; else the first n lanes are pixels (leftovers of several runs) at indices
 * idx. The same operations, in the
 * same order, as run() gives these pixels. Returns how many passed the depth test. */
static inline __attribute__((always_inline)) uint64_t
pack_group(const struct span_ctx *s, const struct pack_ctx *k, const enum shade_mode mode,
           const enum tex_filter filter, const enum depth_mode depth, const bool contig, vf X,
           vf Y, size_t first, vi idx, int n)
{
    vf z = k->zc + ((k->z_c_lo + k->zdy * Y) + k->zdx * X);
    if (depth == DEPTH_W)
        z = z / ((k->zqc + k->zqdy * Y) + k->zqdx * X);
    z = vf_max(k->z_lo, z);
    z = vf_min(k->z_hi, z);
    if (depth == DEPTH_Z16) /* floor(z * 65535 + 0.5); z is in [0, 1] */
        z = vf_from_vi(vi_trunc(z * vf_set(65535.0f) + vf_set(0.5f)));
    vf old;
    vi pass;
    int32_t at[SIMD_LANES]; /* leftovers: each lane's pixel (one vector store, lane loads) */
    if (contig) {
        __builtin_memcpy(&old, k->depth + first, sizeof old);
        pass = depth == DEPTH_RZ ? z > old : z < old;
    } else {
        __builtin_memcpy(at, &idx, sizeof at);
        old = vf_gather_first(k->depth, idx, n);
        pass = (depth == DEPTH_RZ ? z > old : z < old) & (vf_set((float)n) > vf_lanes());
    }
    if (!vi_any(pass))
        return 0;
    if (contig) {
        vf kept = vf_select(pass, z, old);
        __builtin_memcpy(k->depth + first, &kept, sizeof kept);
    } else {
        for (int l = 0; l < SIMD_LANES; l++)
            if (pass[l])
                k->depth[at[l]] = z[l];
    }
    uint64_t shaded = (uint64_t)vi_count(pass);
    if (mode == SHADE_WIRE)
        return shaded;
    const vf rq = vf_set(1.0f) / ((k->qc + k->qdy * Y) + k->qdx * X);
    vf var[VARY_MAX];
    for (int v = 0; v < k->n_var; v++)
        var[v] = ((vf_set(k->a_c[v]) + vf_set(k->a_dy[v]) * Y) + vf_set(k->a_dx[v]) * X) * rq;
    size_t off[SIMD_LANES];
    for (int l = 0; l < SIMD_LANES; l++)
        off[l] = contig ? 3 * first : 3 * (size_t)at[l];
    shade_write_v(s, mode, filter, k->lod, &k->lp, k->pow_k, var, rq, pass, k->rgb, contig, off);
    return shaded;
}

/* The queued runs in packs: SIMD_LANES pixels side by side of one run are a group; the
 * pixels left at a run's end wait, in lanes, for the leftovers of the next runs (span.h).
 * Lanes are filled by selects, never one by one through memory. */
static inline __attribute__((always_inline)) void packs(struct span_ctx *s,
                                                        const enum shade_mode mode,
                                                        const enum tex_filter filter,
                                                        const enum depth_mode depth)
{
    const struct setup_interp *in = &s->in;
    const struct setup_tri *t = s->tri;
    struct pack_ctx k; /* field by field: an initialiser would zero the unused planes */
    k.zc = vf_set(in->z.c), k.z_c_lo = vf_set(in->z_c_lo), k.zdy = vf_set(in->z.dy);
    k.zdx = vf_set(in->z.dx), k.z_lo = vf_set(in->z_lo), k.z_hi = vf_set(in->z_hi);
    k.zqc = vf_set(in->zq.c), k.zqdy = vf_set(in->zq.dy), k.zqdx = vf_set(in->zq.dx);
    k.qc = vf_set(in->q.c), k.qdy = vf_set(in->q.dy), k.qdx = vf_set(in->q.dx);
    k.n_var = span_n_var(s, mode);
    k.pow_k = mode == SHADE_PHONG ? light_pow_int(s->st->mat->ns) : 0;
    k.lod = mode != SHADE_WIRE && filter == TEX_TRILINEAR && s->st->tex;
    k.lp = lod_planes_of(in);
    k.depth = s->fb->depth, k.rgb = s->fb->rgb;
    k.a_c = in->a_c, k.a_dy = in->a_dy, k.a_dx = in->a_dx;
    const int x_org = t->x0, y_org = t->y0;
    const size_t fb_w = (size_t)s->fb->w;
    const vf lane = vf_lanes();
    const vi lane_i = vi_lanes();
    vf lx = vf_set(0), ly = vf_set(0); /* the leftovers waiting: columns, rows, pixels */
    vi li = vi_set(0);
    int nl = 0;
    uint64_t tested = 0, shaded = 0;
    for (int r = 0; r < s->n_runs; r++) {
        const int y = s->runs[r].y, x1 = s->runs[r].x1;
        int x = s->runs[r].x0;
        tested += (uint64_t)(x1 - x + 1);
        const size_t row = (size_t)y * fb_w;
        const vf Y = vf_set((float)(y - y_org));
        for (; x + SIMD_LANES - 1 <= x1; x += SIMD_LANES)
            shaded += pack_group(s, &k, mode, filter, depth, true,
                                 vf_set((float)(x - x_org)) + lane, Y, row + (size_t)x, li,
                                 SIMD_LANES);
        while (x <= x1) { /* lanes nl .. nl + take - 1 get pixels x .. x + take - 1 */
            int take = x1 - x + 1 < SIMD_LANES - nl ? x1 - x + 1 : SIMD_LANES - nl;
            vi m = (lane_i >= vi_set(nl)) & (lane_i < vi_set(nl + take));
            lx = vf_select(m, vf_set((float)(x - nl - x_org)) + lane, lx);
            ly = vf_select(m, Y, ly);
            li = vi_select(m, vi_set((int32_t)(row + (size_t)x) - nl) + lane_i, li);
            x += take;
            if ((nl += take) == SIMD_LANES) {
                shaded += pack_group(s, &k, mode, filter, depth, false, lx, ly, 0, li,
                                     SIMD_LANES);
                nl = 0;
            }
        }
    }
    if (nl)
        shaded += pack_group(s, &k, mode, filter, depth, false, lx, ly, 0, li, nl);
    s->tested += tested;
    s->shaded += shaded;
}

/* The default methods (depth z, perspective-correct) one pixel at a time, for the triangles
 * of one pixel (SPAN_PIXELS_MAX; a third of the head's drawn triangles at 160x96, three
 * quarters of the demo's with --lod auto): a group of lanes
 * costs its setting up (the triangle's planes in every lane, the lanes filled run by run,
 * stored back lane by lane) whatever it holds. Each pixel takes the operations a lane of
 * pack_group would, in the same order, so the bytes are the same (shade.h, texture.h,
 * light.h: every vector function is its scalar one in each lane). */
static inline __attribute__((always_inline)) void pixels(struct span_ctx *s,
                                                         const enum shade_mode mode)
{
    const struct setup_interp *in = &s->in;
    const struct setup_tri *t = s->tri;
    const int n_var = span_n_var(s, mode);
    const struct shade_ctx *sc = s->shade;
    const struct texture *tex = mode != SHADE_WIRE ? s->st->tex : NULL;
    const bool lod = tex && sc->filter == TEX_TRILINEAR;
    float *restrict depth = s->fb->depth;
    uint8_t *restrict rgb = s->fb->rgb;
    const size_t fb_w = (size_t)s->fb->w;
    uint64_t tested = 0, shaded = 0;
    for (int r = 0; r < s->n_runs; r++) {
        const int y = s->runs[r].y, x1 = s->runs[r].x1;
        tested += (uint64_t)(x1 - s->runs[r].x0 + 1);
        const float Y = (float)(y - t->y0);
        for (int x = s->runs[r].x0; x <= x1; x++) {
            const float X = (float)(x - t->x0);
            const size_t i = (size_t)y * fb_w + (size_t)x;
            float z = in->z.c + ((in->z_c_lo + in->z.dy * Y) + in->z.dx * X);
            z = in->z_lo > z ? in->z_lo : z; /* vf_max(z_lo, z) */
            z = in->z_hi < z ? in->z_hi : z; /* vf_min(z_hi, z) */
            if (!(z < depth[i]))
                continue;
            depth[i] = z;
            shaded++;
            if (mode == SHADE_WIRE)
                continue;
            const float rq = 1.0f / ((in->q.c + in->q.dy * Y) + in->q.dx * X);
            float var[VARY_MAX];
            for (int v = 0; v < n_var; v++)
                var[v] = ((in->a_c[v] + in->a_dy[v] * Y) + in->a_dx[v] * X) * rq;
            float lambda = 0, c[3];
            if (lod)
                lambda = texture_lod(tex, (in->a_dx[0] - var[0] * in->q.dx) * rq,
                                     (in->a_dx[1] - var[1] * in->q.dx) * rq,
                                     (in->a_dy[0] - var[0] * in->q.dy) * rq,
                                     (in->a_dy[1] - var[1] * in->q.dy) * rq);
            shade_fragment_l(sc, mode, s->st, var, lambda, c);
            uint8_t *p = rgb + 3 * i;
            p[0] = fb_quantize(c[0]), p[1] = fb_quantize(c[1]), p[2] = fb_quantize(c[2]);
        }
    }
    s->tested += tested;
    s->shaded += shaded;
}

#define PIXELS(MODE)                                                                           \
    static __attribute__((noinline)) void pixels_##MODE(struct span_ctx *s)                   \
    {                                                                                          \
        pixels(s, MODE);                                                                       \
    }
PIXELS(SHADE_UNLIT)
PIXELS(SHADE_FLAT)
PIXELS(SHADE_GOURAUD)
PIXELS(SHADE_PHONG)
PIXELS(SHADE_WIRE)
#undef PIXELS
static void (*const pixels_copy[SHADE_COUNT])(struct span_ctx *) = {
    pixels_SHADE_UNLIT, pixels_SHADE_FLAT, pixels_SHADE_GOURAUD, pixels_SHADE_PHONG,
    pixels_SHADE_WIRE};

/* The default methods' copies (depth z, perspective-correct), one function each: compiled
 * apart, each copy's registers and code layout are its own, not whatever the others left
 * in one huge function (a change in one mode's code moved another's time by 5-10%). */
#define PACKS_Z(MODE, FILTER)                                                                  \
    static __attribute__((noinline)) void packs_z_##MODE##_##FILTER(struct span_ctx *s)       \
    {                                                                                          \
        packs(s, MODE, FILTER, DEPTH_Z);                                                       \
    }
#define PACKS_Z_FILTERS(MODE)                                                                  \
    PACKS_Z(MODE, TEX_NEAREST)                                                                 \
    PACKS_Z(MODE, TEX_BILINEAR)                                                                \
    PACKS_Z(MODE, TEX_TRILINEAR)
PACKS_Z_FILTERS(SHADE_UNLIT)
PACKS_Z_FILTERS(SHADE_FLAT)
PACKS_Z_FILTERS(SHADE_GOURAUD)
PACKS_Z_FILTERS(SHADE_PHONG)
PACKS_Z(SHADE_WIRE, TEX_NEAREST)
#undef PACKS_Z_FILTERS
#undef PACKS_Z
#define PACKS_Z_ROW(MODE)                                                                      \
    [MODE] = {packs_z_##MODE##_TEX_NEAREST, packs_z_##MODE##_TEX_BILINEAR,                     \
              packs_z_##MODE##_TEX_TRILINEAR}
/* by shading mode and filter (wire draws depth only: one copy for every filter) */
static void (*const packs_z_copy[SHADE_COUNT][TEX_FILTER_COUNT])(struct span_ctx *) = {
    PACKS_Z_ROW(SHADE_UNLIT), PACKS_Z_ROW(SHADE_FLAT), PACKS_Z_ROW(SHADE_GOURAUD),
    PACKS_Z_ROW(SHADE_PHONG),
    [SHADE_WIRE] = {packs_z_SHADE_WIRE_TEX_NEAREST, packs_z_SHADE_WIRE_TEX_NEAREST,
                    packs_z_SHADE_WIRE_TEX_NEAREST}};
#undef PACKS_Z_ROW
/* the other methods: one function per shading mode, in packs or run by run */
#define OTHER_METHODS(MODE)                                                                    \
    static __attribute__((noinline)) void packs_##MODE(struct span_ctx *s, enum tex_filter f)  \
    {                                                                                          \
        packs(s, MODE, f, s->depth);                                                           \
    }                                                                                          \
    static __attribute__((noinline)) void runs_##MODE(struct span_ctx *s, enum tex_filter f)   \
    {                                                                                          \
        for (int r = 0; r < s->n_runs; r++)                                                    \
            run(s, s->runs[r].y, s->runs[r].x0, s->runs[r].x1, MODE, s->depth, s->persp, f);   \
    }
OTHER_METHODS(SHADE_UNLIT)
OTHER_METHODS(SHADE_FLAT)
OTHER_METHODS(SHADE_GOURAUD)
OTHER_METHODS(SHADE_PHONG)
OTHER_METHODS(SHADE_WIRE)
#undef OTHER_METHODS
static void (*const packs_copy[SHADE_COUNT])(struct span_ctx *, enum tex_filter) = {
    packs_SHADE_UNLIT, packs_SHADE_FLAT, packs_SHADE_GOURAUD, packs_SHADE_PHONG,
    packs_SHADE_WIRE};
static void (*const runs_copy[SHADE_COUNT])(struct span_ctx *, enum tex_filter) = {
    runs_SHADE_UNLIT, runs_SHADE_FLAT, runs_SHADE_GOURAUD, runs_SHADE_PHONG, runs_SHADE_WIRE};

#ifdef SPAN_AVX2_COPY
void SPAN_FLUSH(struct span_ctx *s, bool pixelwise)
#else
static void SPAN_FLUSH(struct span_ctx *s, bool pixelwise)
#endif
{
    if (!s->in_ready) {
        int n_var = span_n_var(s, s->mode);
#ifdef RASTTY_FLOOR_SETUP_TWICE /* measuring only (as RASTTY_FLOOR_TEXELS, texture.h): the
                                  frame with interpolation setup paid twice, the same bytes */
        for (int twice = 0; twice < 2; twice++)
#endif
#ifdef SPAN_AVX2_COPY
        setup_interp_avx2(s->tri, s->depth, &s->fb->proj, s->persp == PERSP_AFFINE, n_var,
                          &s->in);
#else
        setup_interp(s->tri, s->depth, &s->fb->proj, s->persp == PERSP_AFFINE, n_var, &s->in);
#endif
        s->in_ready = true;
        if (s->hit)
            s->hit[s->tri_index] = 1;
    }
    /* perspective-correct or affine, without the overdraw count or the normals view, in
     * packs: the default methods (depth z, perspective-correct) with copies of their own
     * per filter (every test folds away), the others one copy per shading mode; the span
     * methods, the overdraw count and the normals view run by run */
    const enum tex_filter f = s->shade ? s->shade->filter : TEX_NEAREST;
    if ((s->persp == PERSP_CORRECT || s->persp == PERSP_AFFINE) && !s->fb->overdraw &&
        (!s->shade || s->shade->view != VIEW_NORMALS)) {
        if (s->depth == DEPTH_Z && s->persp == PERSP_CORRECT && pixelwise)
            pixels_copy[s->mode](s);
        else if (s->depth == DEPTH_Z && s->persp == PERSP_CORRECT)
            packs_z_copy[s->mode][f](s);
        else
            packs_copy[s->mode](s, f);
        s->n_runs = s->n_pixels = 0;
        return;
    }
    runs_copy[s->mode](s, f);
    s->n_runs = s->n_pixels = 0;
}
