/* kernel_vertex.h: the vertex stage's bulk work (vertex.h) — positioning vertices (or
 * positions alone) four at a time and shading many at once — compiled once per
 * instruction set by kernel_*.c (kernel.h): four doubles in one register with AVX, two with
 * SSE2, and SIMD_LANES vertices lit at a time; the same doubles and floats as vertex.c's
 * one-at-a-time functions. */
#ifndef RASTTY_KERNEL_VERTEX_H
#define RASTTY_KERNEL_VERTEX_H

#include "kernel_setup.h"
#include "vertex.h"
#include "viewport.h"

/* Four vertices at a time, a lane each: row r of the clip position is
 * ((m[r][0] x + m[r][1] y) + m[r][2] z) + m[r][3] 1 in every lane, as m4_mul_v4 sums it,
 * and the outcode's comparisons, the divide, viewport and snap are vertex.h's and
 * viewport.h's in their order: the same bits as one at a time (tests/unit/test_vertex.c) */
struct lanes_view { /* a frame's constants, broadcast */
    d4 m[4][4], gxn, gxp, gyn, gyp, fw, fh;
};
struct lanes { /* four vertices positioned */
    d4 clip[4], wx, wy, sx, sy; /* window x, y; snapped x, y (whole numbers of 1/256 px) */
    d4 rw;                      /* 1 / w */
    l4 oc;
};

static inline void lanes_view_init(struct lanes_view *L, const struct vertex_uniforms *u)
{
    for (int r = 0; r < 4; r++)
        for (int c = 0; c < 4; c++)
            L->m[r][c] = (d4){u->mvp.m[r][c], u->mvp.m[r][c], u->mvp.m[r][c], u->mvp.m[r][c]};
    const double gx = u->guard_x, gy = u->guard_y;
    L->gxp = (d4){gx, gx, gx, gx}, L->gxn = -L->gxp;
    L->gyp = (d4){gy, gy, gy, gy}, L->gyn = -L->gyp;
    L->fw = (d4){u->fb_w, u->fb_w, u->fb_w, u->fb_w};
    L->fh = (d4){u->fb_h, u->fb_h, u->fb_h, u->fb_h};
}

/* (by pointer: a function returning vectors would have an AVX-only calling convention in
 * the baseline build) */
static inline void lanes_position(const struct lanes_view *L, const float *const pt[4],
                                  struct lanes *o)
{
    const d4 p[3] = {{pt[0][0], pt[1][0], pt[2][0], pt[3][0]},
                     {pt[0][1], pt[1][1], pt[2][1], pt[3][1]},
                     {pt[0][2], pt[1][2], pt[2][2], pt[3][2]}};
    for (int r = 0; r < 4; r++)
        o->clip[r] = L->m[r][0] * p[0] + L->m[r][1] * p[1] + L->m[r][2] * p[2] + L->m[r][3] * 1.0;
    const d4 x = o->clip[0], y = o->clip[1], z = o->clip[2], w = o->clip[3];
    l4 oc = ((l4)(x < -w) & VERTEX_OUT_LEFT) | ((l4)(x > w) & VERTEX_OUT_RIGHT) |
            ((l4)(y < -w) & VERTEX_OUT_BOTTOM) | ((l4)(y > w) & VERTEX_OUT_TOP) |
            ((l4)(z < -w) & VERTEX_OUT_NEAR) | ((l4)(z > w) & VERTEX_OUT_FAR);
    const l4 guard = ((l4)(x < L->gxn * w) & VERTEX_GUARD_LEFT) |
                     ((l4)(x > L->gxp * w) & VERTEX_GUARD_RIGHT) |
                     ((l4)(y < L->gyn * w) & VERTEX_GUARD_BOTTOM) |
                     ((l4)(y > L->gyp * w) & VERTEX_GUARD_TOP);
    oc |= guard & (l4)((oc & 0xf) != 0); /* (the guard band only outside x or y) */
    const l4 finite = (l4)((x - x) + (y - y) + (z - z) + (w - w) == 0);
    o->oc = (oc & finite) | (~finite & (VERTEX_OUT_FRUSTUM | VERTEX_NEEDS_CLIP | VERTEX_INVALID));
    const d4 one = {1, 1, 1, 1}, half = {0.5, 0.5, 0.5, 0.5};
    const double mg = 6755399441055744.0, s = VIEWPORT_SUBPIX_ONE; /* viewport_snap's */
    const d4 magic = {mg, mg, mg, mg}, sub = {s, s, s, s};
    const d4 rw = one / w;
    o->rw = rw;
    o->wx = (x * rw + 1.0) * half * L->fw;
    o->wy = (1.0 - y * rw) * half * L->fh;
    o->sx = (o->wx * sub + magic) - magic;
    o->sy = (o->wy * sub + magic) - magic;
}

/* the lanes' window depths, as viewport_window makes them (1 / w the same correctly
 * rounded quotient in a lane as alone; meaningful only where a lane projects) */
static inline void lanes_depth(const struct lanes *o, d4 *z)
{
    const d4 half = {0.5, 0.5, 0.5, 0.5};
    *z = half * o->clip[2] * o->rw + half;
}

/* (the last run of fewer than four fills its empty lanes with its last vertex again, and
 * stores only its own) */
static void vertex_run(const struct mesh *m, const struct vertex_uniforms *u,
                       struct vertex_out *out, uint32_t i0, uint32_t i1)
{
    struct lanes_view L;
    lanes_view_init(&L, u);
    for (uint32_t i = i0; i < i1; i += 4) {
        const int n = i1 - i < 4 ? (int)(i1 - i) : 4;
        /* (the positions a few steps on: a cluster's run is too short for the hardware's
         * prefetcher to find) */
        if (i + 19 < m->n_verts) {
            __builtin_prefetch(&m->verts[i + 16]);
            __builtin_prefetch(&m->verts[i + 18]);
        }
        const float *pt[4];
        for (int l = 0; l < 4; l++)
            pt[l] = m->verts[i + (l < n ? l : n - 1)].pos;
        struct lanes q;
        lanes_position(&L, pt, &q);
        for (int l = 0; l < n; l++) {
            struct vertex_out *o = &out[i + l];
            for (int r = 0; r < 4; r++)
                o->clip[r] = q.clip[r][l];
            o->outcode = (uint32_t)q.oc[l];
            o->shaded = VERTEX_UNSHADED;
            o->projected = 0;
            if (!(q.oc[l] & VERTEX_NEEDS_CLIP)) {
                o->win[0] = q.wx[l], o->win[1] = q.wy[l];
                o->fx = (int32_t)(int64_t)q.sx[l];
                o->fy = (int32_t)(int64_t)q.sy[l];
                o->projected = 1;
            }
        }
    }
}

static void position_run(const float *xyz, size_t stride, const struct vertex_uniforms *u,
                         struct vertex_pos *out, uint32_t p0, uint32_t p1)
{
    struct lanes_view L;
    lanes_view_init(&L, u);
    for (uint32_t i = p0; i < p1; i += 4) {
        const int n = p1 - i < 4 ? (int)(p1 - i) : 4;
        const float *pt[4];
        for (int l = 0; l < 4; l++)
            pt[l] = (const float *)((const char *)xyz + (size_t)(i + (l < n ? l : n - 1)) * stride);
        struct lanes q;
        lanes_position(&L, pt, &q);
        d4 z;
        lanes_depth(&q, &z);
        for (int l = 0; l < n; l++) {
            struct vertex_pos *o = &out[i + l];
            o->outcode = (uint32_t)q.oc[l];
            o->fx = o->fy = 0;
            o->z = 0;
            if (!(q.oc[l] & VERTEX_NEEDS_CLIP)) {
                o->fx = (int32_t)(int64_t)q.sx[l];
                o->fy = (int32_t)(int64_t)q.sy[l];
                o->z = (float)z[l];
            }
        }
    }
}

/* Gouraud and the modes with normals, SIMD_LANES vertices at a time (vertex_shade_batched):
 * vertex_shade's operations in its order, a vertex per lane, so the same floats; a Gouraud
 * group whose vertices have materials of different Ns (the power is the same in every lane),
 * and the last few, one at a time. */
static void vertex_shade_lanes(const struct mesh *m, const struct vertex_uniforms *u,
                               const uint32_t *idx, struct vertex_out *const *out, uint32_t n)
{
    const float(*a)[4] = u->model_f, (*b)[3] = u->normal_f;
    const bool grey = u->lights.grey;
    const bool normals = u->view == VIEW_NORMALS || u->shade == SHADE_PHONG;
    uint32_t k = 0;
    for (; k + SIMD_LANES <= n; k += SIMD_LANES) {
        float ns = m->materials[m->vert_material ? m->vert_material[idx[k]] : 0].ns;
        bool same = true; /* (the modes with normals light per pixel: Ns does not matter) */
        for (int l = 1; l < SIMD_LANES && m->vert_material && !normals; l++)
            same &= m->materials[m->vert_material[idx[k + l]]].ns == ns;
        if (!same) {
            for (int l = 0; l < SIMD_LANES; l++)
                vertex_shade(m, u, idx[k + l], out[k + l]);
            continue;
        }
        float pl[3][SIMD_LANES], nl[3][SIMD_LANES]; /* lanes gathered, then loaded */
        for (int l = 0; l < SIMD_LANES; l++) {
            const struct mesh_vertex *mv = &m->verts[idx[k + l]];
            for (int c = 0; c < 3; c++)
                pl[c][l] = mv->pos[c], nl[c][l] = mv->nrm[c];
        }
        vf p[3], nn[3];
        __builtin_memcpy(p, pl, sizeof p);
        __builtin_memcpy(nn, nl, sizeof nn);
        vf w[3], nv[3], v[3];
        for (int r = 0; r < 3; r++) {
            w[r] = vf_set(a[r][0]) * p[0] + vf_set(a[r][1]) * p[1] + vf_set(a[r][2]) * p[2] +
                   vf_set(a[r][3]);
            nv[r] = vf_set(b[r][0]) * nn[0] + vf_set(b[r][1]) * nn[1] + vf_set(b[r][2]) * nn[2];
        }
        light_normalize_v(nv);
        if (normals) {
            for (int l = 0; l < SIMD_LANES; l++) {
                struct vertex_out *o = out[k + l];
                const struct mesh_vertex *mv = &m->verts[idx[k + l]];
                o->wpos[0] = w[0][l], o->wpos[1] = w[1][l], o->wpos[2] = w[2][l];
                o->var[0] = mv->uv[0], o->var[1] = mv->uv[1];
                o->var[2] = w[0][l], o->var[3] = w[1][l], o->var[4] = w[2][l];
                o->var[5] = nv[0][l], o->var[6] = nv[1][l], o->var[7] = nv[2][l];
                o->shaded = VERTEX_SHADED;
            }
            continue;
        }
        if (u->ortho) {
            v[0] = vf_set((float)u->view_back.x), v[1] = vf_set((float)u->view_back.y);
            v[2] = vf_set((float)u->view_back.z);
        } else {
            v[0] = vf_set((float)u->eye.x) - w[0], v[1] = vf_set((float)u->eye.y) - w[1];
            v[2] = vf_set((float)u->eye.z) - w[2];
            light_normalize_v(v);
        }
        vf d[3], s[3];
        light_terms_k_v(&u->lights, nv, v, ns, light_pow_int(ns), d, s);
        for (int l = 0; l < SIMD_LANES; l++) {
            struct vertex_out *o = out[k + l];
            const struct mesh_vertex *mv = &m->verts[idx[k + l]];
            o->wpos[0] = w[0][l], o->wpos[1] = w[1][l], o->wpos[2] = w[2][l];
            o->var[0] = mv->uv[0], o->var[1] = mv->uv[1];
            o->shaded = VERTEX_SHADED;
            if (grey) {
                o->var[VARY_GOURAUD_D] = d[0][l], o->var[VARY_GOURAUD_S(true)] = s[0][l];
            } else {
                for (int c = 0; c < 3; c++)
                    o->var[VARY_GOURAUD_D + c] = d[c][l], o->var[VARY_GOURAUD_S(false) + c] = s[c][l];
            }
        }
    }
    for (; k < n; k++)
        vertex_shade(m, u, idx[k], out[k]);
}

/* vertex.h's vertex_shade_many: in lanes when that gains (vertex_shade_batched) */
static void vertex_shade_many(const struct mesh *m, const struct vertex_uniforms *u,
                              const uint32_t *idx, struct vertex_out *const *out, uint32_t n)
{
    if (!vertex_shade_batched(m, u)) {
        for (uint32_t k = 0; k < n; k++)
            vertex_shade(m, u, idx[k], out[k]);
        return;
    }
    vertex_shade_lanes(m, u, idx, out, n);
}

#endif
