/* vertex.c: per-vertex lighting (see vertex.h; positioning vertices in bulk is the kernels',
 * src/render/kernel/kernel_vertex.h). */
#include "vertex.h"

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
