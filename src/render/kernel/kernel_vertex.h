/* kernel_vertex.h: the vertex stage's bulk work (vertex.h) — positioning vertices and
 * shading many at once — compiled once per instruction set by kernel_*.c (kernel.h): with
 * AVX the clip position's four rows in one register instead of two, and SIMD_LANES vertices
 * lit at a time; the same doubles and floats as vertex.c's one-at-a-time functions. */
#ifndef RASTTY_KERNEL_VERTEX_H
#define RASTTY_KERNEL_VERTEX_H

#include "kernel_setup.h"
#include "vertex.h"
#include "viewport.h"

/* one vertex's record from its clip position (vertex_outcode's, vertex_project's) */
static inline void vertex_from_clip(struct vertex_out *o, const double clip[4], double gx,
                                    double gy, int w, int h)
{
    __builtin_memcpy(o->clip, clip, sizeof o->clip);
    o->outcode = vertex_outcode(o->clip, gx, gy);
    o->projected = 0;
    o->shaded = VERTEX_UNSHADED;
    if (!(o->outcode & VERTEX_NEEDS_CLIP))
        vertex_project(o, w, h);
}

static void vertex_run(const struct mesh *m, const struct vertex_uniforms *u,
                       struct vertex_out *out, uint32_t i0, uint32_t i1)
{
    /* the matrix in locals: the stores below may alias it otherwise (same sums, same order
     * as m4_mul_v4, so the same bits) */
    const mat4 a = u->mvp;
    const double gx = u->guard_x, gy = u->guard_y;
    const int w = u->fb_w, h = u->fb_h;
    /* four vertices at a time, a lane each: row r of the clip position is
     * ((m[r][0] x + m[r][1] y) + m[r][2] z) + m[r][3] 1 in every lane, as m4_mul_v4 sums
     * it, and the outcode's comparisons, the divide, viewport and snap are vertex.h's and
     * viewport.h's in their order: the same bits as one at a time */
    d4 mr[4][4];
    for (int r = 0; r < 4; r++)
        for (int c = 0; c < 4; c++)
            mr[r][c] = (d4){a.m[r][c], a.m[r][c], a.m[r][c], a.m[r][c]};
    const d4 one = {1, 1, 1, 1}, half = {0.5, 0.5, 0.5, 0.5};
    const d4 gxn = -(d4){gx, gx, gx, gx}, gxp = (d4){gx, gx, gx, gx};
    const d4 gyn = -(d4){gy, gy, gy, gy}, gyp = (d4){gy, gy, gy, gy};
    const d4 fw = {w, w, w, w}, fh = {h, h, h, h};
    const d4 sub = {VIEWPORT_SUBPIX_ONE, VIEWPORT_SUBPIX_ONE, VIEWPORT_SUBPIX_ONE,
                    VIEWPORT_SUBPIX_ONE};
    const double mg = 6755399441055744.0; /* viewport_snap's 1.5 * 2^52 */
    const d4 magic = {mg, mg, mg, mg};
    uint32_t i = i0;
    for (; i + 4 <= i1; i += 4) {
        /* (the positions a few steps on: a cluster's run is too short for the hardware's
         * prefetcher to find) */
        if (i + 19 < m->n_verts) {
            __builtin_prefetch(&m->verts[i + 16]);
            __builtin_prefetch(&m->verts[i + 18]);
        }
        d4 p[3];
        for (int l = 0; l < 4; l++)
            for (int c = 0; c < 3; c++)
                p[c][l] = m->verts[i + l].pos[c];
        d4 q[4];
        for (int r = 0; r < 4; r++)
            q[r] = mr[r][0] * p[0] + mr[r][1] * p[1] + mr[r][2] * p[2] + mr[r][3] * 1.0;
        const d4 x = q[0], y = q[1], z = q[2], wc = q[3];
        l4 oc = ((l4)(x < -wc) & VERTEX_OUT_LEFT) | ((l4)(x > wc) & VERTEX_OUT_RIGHT) |
                ((l4)(y < -wc) & VERTEX_OUT_BOTTOM) | ((l4)(y > wc) & VERTEX_OUT_TOP) |
                ((l4)(z < -wc) & VERTEX_OUT_NEAR) | ((l4)(z > wc) & VERTEX_OUT_FAR);
        const l4 guard = ((l4)(x < gxn * wc) & VERTEX_GUARD_LEFT) |
                         ((l4)(x > gxp * wc) & VERTEX_GUARD_RIGHT) |
                         ((l4)(y < gyn * wc) & VERTEX_GUARD_BOTTOM) |
                         ((l4)(y > gyp * wc) & VERTEX_GUARD_TOP);
        oc |= guard & (l4)((oc & 0xf) != 0);
        const l4 finite = (l4)((x - x) + (y - y) + (z - z) + (wc - wc) == 0);
        oc = (oc & finite) |
             (~finite & (VERTEX_OUT_FRUSTUM | VERTEX_NEEDS_CLIP | VERTEX_INVALID));
        const d4 rw = one / wc;
        const d4 wx = (x * rw + 1.0) * half * fw, wy = (1.0 - y * rw) * half * fh;
        const d4 sx = (wx * sub + magic) - magic, sy = (wy * sub + magic) - magic;
        for (int l = 0; l < 4; l++) {
            struct vertex_out *o = &out[i + l];
            o->clip[0] = x[l], o->clip[1] = y[l], o->clip[2] = z[l], o->clip[3] = wc[l];
            o->outcode = (uint32_t)oc[l];
            o->shaded = VERTEX_UNSHADED;
            o->projected = 0;
            if (!(oc[l] & VERTEX_NEEDS_CLIP)) {
                o->win[0] = wx[l], o->win[1] = wy[l];
                o->fx = (int32_t)(int64_t)sx[l];
                o->fy = (int32_t)(int64_t)sy[l];
                o->projected = 1;
            }
        }
    }
    for (; i < i1; i++) {
        const float *p = m->verts[i].pos;
        double cl[4];
        for (int r = 0; r < 4; r++)
            cl[r] = a.m[r][0] * p[0] + a.m[r][1] * p[1] + a.m[r][2] * p[2] + a.m[r][3] * 1.0;
        vertex_from_clip(&out[i], cl, gx, gy, w, h);
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
