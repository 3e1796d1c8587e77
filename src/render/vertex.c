/* vertex.c: per-vertex lighting (see vertex.h; positioning vertices in bulk is the kernels',
 * src/render/kernel/kernel_vertex.h). */
#include "vertex.h"

#include <string.h>

#include "viewport.h"

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

void vertex_rich_layout(const struct mesh *m, enum shade_mode mode, enum debug_view view,
                        bool grey, struct vary_rich *L)
{
    memset(L, -1, sizeof *L);
    L->col_n = 0;
    L->dropped_uv1 = L->dropped_alpha = false;
    bool normals = view == VIEW_NORMALS || mode == SHADE_PHONG;
    int n = 3; /* the world position */
    if (normals) {
        L->nrm = (int8_t)n, n += 3;
    } else if (mode == SHADE_GOURAUD) {
        L->d = (int8_t)n, n += grey ? 1 : 3;
        L->s = (int8_t)n, n += grey ? 1 : 3;
    }
    L->uv0 = (int8_t)n, n += 2;
    if (normals && m->tangents)
        L->tan = (int8_t)n, n += 4;
    int want_col = m->colors ? 4 : 0, want_uv1 = m->uv1 ? 2 : 0;
    if (n + want_col + want_uv1 > VARY_ALL && want_uv1)
        L->dropped_uv1 = true, want_uv1 = 0;
    if (n + want_col + want_uv1 > VARY_ALL && want_col)
        L->dropped_alpha = true, want_col = 3;
    if (want_col)
        L->col = (int8_t)n, L->col_n = (int8_t)want_col, n += want_col;
    if (want_uv1)
        L->uv1 = (int8_t)n, n += 2;
    L->n = (int8_t)n;
}

/* vertex_shade for a mesh drawn by the features path: its varyings in u->rich's layout */
static void vertex_shade_rich(const struct mesh *m, const struct vertex_uniforms *u, uint32_t i,
                              struct vertex_out *o)
{
    const struct vary_rich *L = u->rich;
    const struct mesh_vertex *mv = &m->verts[i];
    const float *p = mv->pos, (*a)[4] = u->model_f;
    for (int r = 0; r < 3; r++)
        o->all[r] = a[r][0] * p[0] + a[r][1] * p[1] + a[r][2] * p[2] + a[r][3];
    for (int k = 3; k < VARY_ALL; k++) /* every varying defined: clipping reads them */
        o->all[k] = 0;
    o->shaded = VERTEX_SHADED;
    o->all[L->uv0] = mv->uv[0];
    o->all[L->uv0 + 1] = mv->uv[1];
    if (L->uv1 >= 0)
        o->all[L->uv1] = m->uv1[i][0], o->all[L->uv1 + 1] = m->uv1[i][1];
    for (int k = 0; k < L->col_n; k++)
        o->all[L->col + k] = m->colors[i][k] * (1.0f / 255.0f);
    if (L->nrm < 0 && L->d < 0)
        return;
    const float *nn = mv->nrm, (*b)[3] = u->normal_f;
    float n[3];
    for (int r = 0; r < 3; r++)
        n[r] = b[r][0] * nn[0] + b[r][1] * nn[1] + b[r][2] * nn[2];
    light_normalize(n);
    if (L->nrm >= 0) {
        for (int k = 0; k < 3; k++)
            o->all[L->nrm + k] = n[k];
        if (L->tan >= 0) { /* tangents move with the model (a mirror turns w) */
            const float *t = m->tangents[i];
            float tw[3];
            for (int r = 0; r < 3; r++)
                tw[r] = a[r][0] * t[0] + a[r][1] * t[1] + a[r][2] * t[2];
            light_normalize(tw);
            for (int k = 0; k < 3; k++)
                o->all[L->tan + k] = tw[k];
            o->all[L->tan + 3] = t[3] * u->model_det;
        }
        return;
    }
    float ns = m->materials[m->vert_material ? m->vert_material[i] : 0].ns, d[3], s[3];
    vertex_light(u, n, o->wpos, ns, d, s);
    int nc = u->lights.grey ? 1 : 3;
    for (int k = 0; k < nc; k++)
        o->all[L->d + k] = d[k], o->all[L->s + k] = s[k];
}

void vertex_shade(const struct mesh *m, const struct vertex_uniforms *u, uint32_t i,
                  struct vertex_out *o)
{
    if (u->rich) {
        vertex_shade_rich(m, u, i, o);
        return;
    }
    const struct mesh_vertex *mv = &m->verts[i];
    int want_normals = u->view == VIEW_NORMALS || u->shade == SHADE_PHONG;
    int want_gouraud = !want_normals && u->shade == SHADE_GOURAUD;
    const float *p = mv->pos, (*a)[4] = u->model_f;
    for (int r = 0; r < 3; r++) /* float, as a GPU's vertex shader would */
        o->wpos[r] = a[r][0] * p[0] + a[r][1] * p[1] + a[r][2] * p[2] + a[r][3];
    o->var[0] = mv->uv[0];
    o->var[1] = mv->uv[1];
    o->shaded = VERTEX_SHADED;
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
