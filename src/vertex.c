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
#ifdef VERTEX_AVX2_COPY
#define VERTEX_RUN vertex_run_avx2
#else
#define VERTEX_RUN vertex_run_base
static void vertex_run_base(const struct mesh *m, const struct vertex_uniforms *u,
                            struct vertex_out *out, uint32_t i0, uint32_t i1);

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

