/* kernel_vertex.h: the vertex stage's bulk work (vertex.h) — positioning vertices and
 * shading many at once — compiled once per instruction set by kernel_*.c (kernel.h): with
 * AVX the clip position's four rows in one register instead of two, and SIMD_LANES vertices
 * lit at a time; the same doubles and floats as vertex.c's one-at-a-time functions. */
#ifndef RASTTY_KERNEL_VERTEX_H
#define RASTTY_KERNEL_VERTEX_H

#include "kernel_setup.h"
#include "vertex.h"
#include "viewport.h"

static void vertex_run(const struct mesh *m, const struct vertex_uniforms *u,
                       struct vertex_out *out, uint32_t i0, uint32_t i1)
{
    /* the matrix in locals: the stores below may alias it otherwise (same sums, same order
     * as m4_mul_v4, so the same bits) */
    const mat4 a = u->mvp;
    const double gx = u->guard_x, gy = u->guard_y;
    const int w = u->fb_w, h = u->fb_h;
    /* the matrix by columns, four rows at once (two SSE2 or one AVX operation per column):
     * each row's sum in the same order as m4_mul_v4, so the same bits */
    d4 col[4]; /* (kernel_setup.h's four doubles) */
    for (int c = 0; c < 4; c++)
        col[c] = (d4){a.m[0][c], a.m[1][c], a.m[2][c], a.m[3][c]};
    for (uint32_t i = i0; i < i1; i++) {
        const float *p = m->verts[i].pos;
        const double x = p[0], y = p[1], z = p[2];
        struct vertex_out *o = &out[i];
        d4 cl = col[0] * x + col[1] * y + col[2] * z + col[3] * 1.0;
        __builtin_memcpy(o->clip, &cl, sizeof cl);
        o->outcode = vertex_outcode(o->clip, gx, gy);
        o->projected = 0;
        o->shaded = VERTEX_UNSHADED;
        if (!(o->outcode & VERTEX_NEEDS_CLIP))
            vertex_project(o, w, h);
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
