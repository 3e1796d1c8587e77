/* kernel_span.h: the span stage's body (span.h) — depth test, interpolation, shading and the
 * write of a triangle's queued runs — compiled once per instruction set by kernel_*.c
 * (kernel.h). Every function here is static: each instruction set's file makes its own copy,
 * and its table (kernel_table.h) is the only way in. Each pixel's weights come from its
 * absolute position in one fixed order of operations (span.h), so every copy, and the
 * reference kernel, write the same bytes. */
#ifndef RASTTY_KERNEL_SPAN_H
#define RASTTY_KERNEL_SPAN_H

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "kernel_common.h"
#include "kernel_setup.h"

/* a plane's value on row y (its row base), then at column offset X: the fixed order */
static inline float row_of(const struct setup_plane *p, float Y)
{
    return p->c + p->dy * Y;
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
    vi r8 = kernel_quantize_v(c[0]), g8 = kernel_quantize_v(c[1]), b8 = kernel_quantize_v(c[2]);
    const vi px = r8 | (g8 << 8) | (b8 << 16);
    if (contig && vi_all(pass)) {
        kernel_store_rgb_v(rgb + off[0], px);
        return;
    }
    for (int l = 0; l < SIMD_LANES; l++) /* lane by lane */
        if (pass[l])
            kernel_store_rgb(rgb + (contig ? off[0] + 3 * (size_t)l : off[l]), (uint32_t)px[l]);
}

/* One run in any method, instantiated per shading mode below (span_runs_*): `mode` is a
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
    const int n_var = kernel_n_var(s, mode);
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
                        kernel_row_extent(t, y, &row_lo, &row_hi);
                    anchor = a;
                    a0 = a > row_lo ? a : row_lo;
                    int a1 = a + span_n < row_hi ? a + span_n : row_hi;
                    float vb[VARY_MAX];
                    kernel_exact_at(qr, in->q.dx, ar, adx, (float)(a0 - x_org), n_var, va);
                    kernel_exact_at(qr, in->q.dx, ar, adx, (float)(a1 - x_org), n_var, vb);
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
                p[0] = pixel_quantize(rgb[0]), p[1] = pixel_quantize(rgb[1]), p[2] = pixel_quantize(rgb[2]);
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
    k.n_var = kernel_n_var(s, mode);
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
    const int n_var = kernel_n_var(s, mode);
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
            shade_fragment_lod(sc, mode, s->st, var, lambda, c);
            uint8_t *p = rgb + 3 * i;
            p[0] = pixel_quantize(c[0]), p[1] = pixel_quantize(c[1]), p[2] = pixel_quantize(c[2]);
        }
    }
    s->tested += tested;
    s->shaded += shaded;
}

/* A triangle's first flush: its interpolation setup (setup.h), which the triangles that
 * cover no pixel never pay for. */
static inline __attribute__((always_inline)) void begin_pixels(struct span_ctx *s)
{
    if (s->in_ready)
        return;
    int n_var = kernel_n_var(s, s->mode);
    const int base = s->mode == SHADE_WIRE ? VARY_BASE : kernel_vary_base(s);
#ifdef RASTTY_FLOOR_SETUP_TWICE /* measuring only (as RASTTY_FLOOR_TEXELS, texture.h): the
                                   frame with interpolation setup paid twice, the same bytes */
    for (int twice = 0; twice < 2; twice++)
#endif
        setup_interp(s->tri, s->depth, &s->fb->proj, s->persp == PERSP_AFFINE, base, n_var,
                     &s->in);
    s->in_ready = true;
    if (s->hit)
        s->hit[s->tri_index] = 1;
}

/* The filter a triangle's texels are fetched with (the depth-only pass has no shading) */
static inline enum tex_filter span_filter(const struct span_ctx *s)
{
    return s->shade ? s->shade->filter : TEX_NEAREST;
}

/* The table's entries, one function per method (kernel.h), each compiled apart: each copy's
 * registers and code layout are its own, not whatever the others left in one huge function
 * (a change in one mode's code moved another's time by 5-10%). `mode` (and for the default
 * methods the filter) are constants in each, so the shading's switches fold away. */

/* the default methods, a pixel at a time (one-pixel triangles) */
static __attribute__((noinline)) void span_one_pixel_unlit(struct span_ctx *s)
{
    begin_pixels(s);
    pixels(s, SHADE_UNLIT);
}
static __attribute__((noinline)) void span_one_pixel_flat(struct span_ctx *s)
{
    begin_pixels(s);
    pixels(s, SHADE_FLAT);
}
static __attribute__((noinline)) void span_one_pixel_gouraud(struct span_ctx *s)
{
    begin_pixels(s);
    pixels(s, SHADE_GOURAUD);
}
static __attribute__((noinline)) void span_one_pixel_phong(struct span_ctx *s)
{
    begin_pixels(s);
    pixels(s, SHADE_PHONG);
}
static __attribute__((noinline)) void span_one_pixel_wire(struct span_ctx *s)
{
    begin_pixels(s);
    pixels(s, SHADE_WIRE);
}

/* the default methods in packs, a copy per shading mode and filter (wire: depth only, one) */
static __attribute__((noinline)) void span_packs_z_unlit_nearest(struct span_ctx *s)
{
    begin_pixels(s);
    packs(s, SHADE_UNLIT, TEX_NEAREST, DEPTH_Z);
}
static __attribute__((noinline)) void span_packs_z_unlit_bilinear(struct span_ctx *s)
{
    begin_pixels(s);
    packs(s, SHADE_UNLIT, TEX_BILINEAR, DEPTH_Z);
}
static __attribute__((noinline)) void span_packs_z_unlit_trilinear(struct span_ctx *s)
{
    begin_pixels(s);
    packs(s, SHADE_UNLIT, TEX_TRILINEAR, DEPTH_Z);
}
static __attribute__((noinline)) void span_packs_z_flat_nearest(struct span_ctx *s)
{
    begin_pixels(s);
    packs(s, SHADE_FLAT, TEX_NEAREST, DEPTH_Z);
}
static __attribute__((noinline)) void span_packs_z_flat_bilinear(struct span_ctx *s)
{
    begin_pixels(s);
    packs(s, SHADE_FLAT, TEX_BILINEAR, DEPTH_Z);
}
static __attribute__((noinline)) void span_packs_z_flat_trilinear(struct span_ctx *s)
{
    begin_pixels(s);
    packs(s, SHADE_FLAT, TEX_TRILINEAR, DEPTH_Z);
}
static __attribute__((noinline)) void span_packs_z_gouraud_nearest(struct span_ctx *s)
{
    begin_pixels(s);
    packs(s, SHADE_GOURAUD, TEX_NEAREST, DEPTH_Z);
}
static __attribute__((noinline)) void span_packs_z_gouraud_bilinear(struct span_ctx *s)
{
    begin_pixels(s);
    packs(s, SHADE_GOURAUD, TEX_BILINEAR, DEPTH_Z);
}
static __attribute__((noinline)) void span_packs_z_gouraud_trilinear(struct span_ctx *s)
{
    begin_pixels(s);
    packs(s, SHADE_GOURAUD, TEX_TRILINEAR, DEPTH_Z);
}
static __attribute__((noinline)) void span_packs_z_phong_nearest(struct span_ctx *s)
{
    begin_pixels(s);
    packs(s, SHADE_PHONG, TEX_NEAREST, DEPTH_Z);
}
static __attribute__((noinline)) void span_packs_z_phong_bilinear(struct span_ctx *s)
{
    begin_pixels(s);
    packs(s, SHADE_PHONG, TEX_BILINEAR, DEPTH_Z);
}
static __attribute__((noinline)) void span_packs_z_phong_trilinear(struct span_ctx *s)
{
    begin_pixels(s);
    packs(s, SHADE_PHONG, TEX_TRILINEAR, DEPTH_Z);
}
static __attribute__((noinline)) void span_packs_z_wire(struct span_ctx *s)
{
    begin_pixels(s);
    packs(s, SHADE_WIRE, TEX_NEAREST, DEPTH_Z);
}

/* any depth method, perspective-correct or affine, in packs */
static __attribute__((noinline)) void span_packs_unlit(struct span_ctx *s)
{
    begin_pixels(s);
    packs(s, SHADE_UNLIT, span_filter(s), s->depth);
}
static __attribute__((noinline)) void span_packs_flat(struct span_ctx *s)
{
    begin_pixels(s);
    packs(s, SHADE_FLAT, span_filter(s), s->depth);
}
static __attribute__((noinline)) void span_packs_gouraud(struct span_ctx *s)
{
    begin_pixels(s);
    packs(s, SHADE_GOURAUD, span_filter(s), s->depth);
}
static __attribute__((noinline)) void span_packs_phong(struct span_ctx *s)
{
    begin_pixels(s);
    packs(s, SHADE_PHONG, span_filter(s), s->depth);
}
static __attribute__((noinline)) void span_packs_wire(struct span_ctx *s)
{
    begin_pixels(s);
    packs(s, SHADE_WIRE, TEX_NEAREST, s->depth);
}

/* the features path (materials with features): every method, pixel by pixel, through the
 * scalar kernel_rich_pixel every kernel shares (kernel_common.h) */
static inline __attribute__((always_inline)) void rich(struct span_ctx *s)
{
    begin_pixels(s);
    for (int r = 0; r < s->n_runs; r++)
        for (int x = s->runs[r].x0; x <= s->runs[r].x1; x++)
            kernel_rich_pixel(s, x, s->runs[r].y);
}
static __attribute__((noinline)) void span_rich_unlit(struct span_ctx *s)
{
    rich(s);
}
static __attribute__((noinline)) void span_rich_flat(struct span_ctx *s)
{
    rich(s);
}
static __attribute__((noinline)) void span_rich_gouraud(struct span_ctx *s)
{
    rich(s);
}
static __attribute__((noinline)) void span_rich_phong(struct span_ctx *s)
{
    rich(s);
}

/* run by run: the span methods, the overdraw count, the normals view */
static __attribute__((noinline)) void span_runs_unlit(struct span_ctx *s)
{
    begin_pixels(s);
    for (int r = 0; r < s->n_runs; r++)
        run(s, s->runs[r].y, s->runs[r].x0, s->runs[r].x1, SHADE_UNLIT, s->depth, s->persp,
            span_filter(s));
}
static __attribute__((noinline)) void span_runs_flat(struct span_ctx *s)
{
    begin_pixels(s);
    for (int r = 0; r < s->n_runs; r++)
        run(s, s->runs[r].y, s->runs[r].x0, s->runs[r].x1, SHADE_FLAT, s->depth, s->persp,
            span_filter(s));
}
static __attribute__((noinline)) void span_runs_gouraud(struct span_ctx *s)
{
    begin_pixels(s);
    for (int r = 0; r < s->n_runs; r++)
        run(s, s->runs[r].y, s->runs[r].x0, s->runs[r].x1, SHADE_GOURAUD, s->depth, s->persp,
            span_filter(s));
}
static __attribute__((noinline)) void span_runs_phong(struct span_ctx *s)
{
    begin_pixels(s);
    for (int r = 0; r < s->n_runs; r++)
        run(s, s->runs[r].y, s->runs[r].x0, s->runs[r].x1, SHADE_PHONG, s->depth, s->persp,
            span_filter(s));
}
static __attribute__((noinline)) void span_runs_wire(struct span_ctx *s)
{
    begin_pixels(s);
    for (int r = 0; r < s->n_runs; r++)
        run(s, s->runs[r].y, s->runs[r].x0, s->runs[r].x1, SHADE_WIRE, s->depth, s->persp,
            TEX_NEAREST);
}

#endif
