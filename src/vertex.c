/* vertex.c: per-vertex transform and lighting (see vertex.h). */
#include "vertex.h"

#include "span.h"
#include "viewport.h"

/* vertex_run is compiled a second time on x86-64 (Makefile), as span.c is: the copy with
 * -mavx2 -DVERTEX_AVX2_COPY makes only vertex_run_avx2 (the clip position's four rows in
 * one AVX register instead of two), used when the span stage runs on AVX2 — the same C,
 * the same doubles. */
void vertex_run_avx2(const struct mesh *m, const struct vertex_uniforms *u,
                     struct vertex_out *out, uint32_t i0, uint32_t i1);
void vertex_shade_many_avx2(const struct mesh *m, const struct vertex_uniforms *u,
                            const uint32_t *idx, struct vertex_out *const *out, uint32_t n);
#ifdef VERTEX_AVX2_COPY
#define VERTEX_RUN vertex_run_avx2
#define VERTEX_SHADE_MANY vertex_shade_many_avx2
#else
#define VERTEX_RUN vertex_run_base
#define VERTEX_SHADE_MANY vertex_shade_many_base
static void vertex_run_base(const struct mesh *m, const struct vertex_uniforms *u,
                            struct vertex_out *out, uint32_t i0, uint32_t i1);
static void vertex_shade_many_base(const struct mesh *m, const struct vertex_uniforms *u,
                                   const uint32_t *idx, struct vertex_out *const *out,
                                   uint32_t n);

void vertex_light(const struct vertex_uniforms *u, const float n[3], const float p[3], float ns,
                  float d_out[3], float s_out[3])
{
    float v[3] = {(float)u->view_back.x, (float)u->view_back.y, (float)u->view_back.z};
    if (!u->ortho) {
        v[0] = (float)u->eye.x - p[0], v[1] = (float)u->eye.y - p[1], v[2] = (float)u->eye.z - p[2];
        light_normalize(v);
    }
    light_terms(&u->lights, n, v, ns, d_out, s_out);
}

void vertex_shade(const struct mesh *m, const struct vertex_uniforms *u, uint32_t i,
                  struct vertex_out *o)
{
    const struct mesh_vertex *mv = &m->verts[i];
    int want_normals = u->view == VIEW_NORMALS || u->shade == SHADE_PHONG;
    int want_gouraud = !want_normals && u->shade == SHADE_GOURAUD;
    const float *p = mv->pos, (*a)[4] = u->model_f;
    for (int r = 0; r < 3; r++) /* float, as a GPU's vertex shader would */
        o->wpos[r] = a[r][0] * p[0] + a[r][1] * p[1] + a[r][2] * p[2] + a[r][3];
    o->var[0] = mv->uv[0];
    o->var[1] = mv->uv[1];
    o->shaded = 1;
    if (m->colors) { /* every varying up to the colour is defined: clipping and setup read them */
        for (int k = 2; k < VARY_COLOR; k++)
            o->var[k] = 0;
        for (int k = 0; k < 3; k++)
            o->var[VARY_COLOR + k] = m->colors[i][k] * (1.0f / 255.0f);
    }
    if (!want_normals && !want_gouraud)
        return;
    const float *nn = mv->nrm, (*b)[3] = u->normal_f;
    float n[3];
    for (int r = 0; r < 3; r++)
        n[r] = b[r][0] * nn[0] + b[r][1] * nn[1] + b[r][2] * nn[2];
    light_normalize(n);
    if (want_normals) {
        o->var[2] = o->wpos[0], o->var[3] = o->wpos[1], o->var[4] = o->wpos[2];
        o->var[5] = n[0], o->var[6] = n[1], o->var[7] = n[2];
    } else {
        float ns = m->materials[m->vert_material ? m->vert_material[i] : 0].ns, d[3], s[3];
        vertex_light(u, n, o->wpos, ns, d, s);
        if (u->lights.grey) {
            o->var[VARY_GOURAUD_D] = d[0], o->var[VARY_GOURAUD_S(true)] = s[0];
        } else {
            for (int k = 0; k < 3; k++)
                o->var[VARY_GOURAUD_D + k] = d[k], o->var[VARY_GOURAUD_S(false) + k] = s[k];
        }
    }
}

void vertex_run(const struct mesh *m, const struct vertex_uniforms *u, struct vertex_out *out,
                uint32_t i0, uint32_t i1)
{
#ifdef RASTTY_SPAN_AVX2
    if (span_isa_get() != SPAN_ISA_SSE2) {
        vertex_run_avx2(m, u, out, i0, i1);
        return;
    }
#endif
    vertex_run_base(m, u, out, i0, i1);
}

void vertex_shade_many(const struct mesh *m, const struct vertex_uniforms *u,
                       const uint32_t *idx, struct vertex_out *const *out, uint32_t n)
{
    if (!vertex_shade_batched(m, u)) {
        for (uint32_t k = 0; k < n; k++)
            vertex_shade(m, u, idx[k], out[k]);
        return;
    }
#ifdef RASTTY_SPAN_AVX2
    if (span_isa_get() != SPAN_ISA_SSE2) {
        vertex_shade_many_avx2(m, u, idx, out, n);
        return;
    }
#endif
    vertex_shade_many_base(m, u, idx, out, n);
}
#endif /* !VERTEX_AVX2_COPY */

#ifdef VERTEX_AVX2_COPY
void VERTEX_RUN(const struct mesh *m, const struct vertex_uniforms *u, struct vertex_out *out,
                uint32_t i0, uint32_t i1)
#else
static void VERTEX_RUN(const struct mesh *m, const struct vertex_uniforms *u,
                       struct vertex_out *out, uint32_t i0, uint32_t i1)
#endif
{
    /* the matrix in locals: the stores below may alias it otherwise (same sums, same order
     * as m4_mul_v4, so the same bits) */
    const mat4 a = u->mvp;
    const double gx = u->guard_x, gy = u->guard_y;
    const int w = u->fb_w, h = u->fb_h;
    /* the matrix by columns, four rows at once (two SSE2 or one AVX operation per column):
     * each row's sum in the same order as m4_mul_v4, so the same bits */
    typedef double d4 __attribute__((vector_size(32)));
    d4 col[4];
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
        o->shaded = 0;
        if (!(o->outcode & VERTEX_NEEDS_CLIP))
            vertex_project(o, w, h);
    }
}

/* Gouraud and the modes with normals, SIMD_LANES vertices at a time (vertex_shade_batched):
 * vertex_shade's operations in its order, a vertex per lane, so the same floats; a Gouraud
 * group whose vertices have materials of different Ns (the power is the same in every lane),
 * and the last few, one at a time. */
#ifdef VERTEX_AVX2_COPY
void VERTEX_SHADE_MANY(const struct mesh *m, const struct vertex_uniforms *u,
                       const uint32_t *idx, struct vertex_out *const *out, uint32_t n)
#else
static void VERTEX_SHADE_MANY(const struct mesh *m, const struct vertex_uniforms *u,
                              const uint32_t *idx, struct vertex_out *const *out, uint32_t n)
#endif
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
                o->shaded = 1;
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
        light_terms_v_k(&u->lights, nv, v, ns, light_pow_int(ns), d, s);
        for (int l = 0; l < SIMD_LANES; l++) {
            struct vertex_out *o = out[k + l];
            const struct mesh_vertex *mv = &m->verts[idx[k + l]];
            o->wpos[0] = w[0][l], o->wpos[1] = w[1][l], o->wpos[2] = w[2][l];
            o->var[0] = mv->uv[0], o->var[1] = mv->uv[1];
            o->shaded = 1;
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
