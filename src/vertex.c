/* vertex.c: per-vertex transform and lighting (see vertex.h). */
#include "vertex.h"

#include "viewport.h"

int vertex_varying_count(enum shade_mode shade, enum debug_view view)
{
    if (view == VIEW_NORMALS || shade == SHADE_PHONG)
        return 8;
    if (shade == SHADE_GOURAUD)
        return 8;
    return 2;
}

void vertex_project(struct vertex_out *v, int fb_w, int fb_h)
{
    viewport_window(v->clip, fb_w, fb_h, v->win);
    v->fx = viewport_snap(v->win[0]);
    v->fy = viewport_snap(v->win[1]);
    v->projected = 1;
}

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

void vertex_run(const struct mesh *m, const struct vertex_uniforms *u, struct vertex_out *out,
                uint32_t i0, uint32_t i1)
{
    for (uint32_t i = i0; i < i1; i++) {
        const struct mesh_vertex *mv = &m->verts[i];
        struct vertex_out *o = &out[i];
        vec4 c = m4_mul_v4(u->mvp, (vec4){mv->pos[0], mv->pos[1], mv->pos[2], 1});
        o->clip[0] = c.x, o->clip[1] = c.y, o->clip[2] = c.z, o->clip[3] = c.w;
        o->outcode = vertex_outcode(o->clip, u->guard_x, u->guard_y);
        o->projected = 0;
        o->shaded = 0;
        if (!(o->outcode & VERTEX_NEEDS_CLIP))
            vertex_project(o, u->fb_w, u->fb_h);
    }
}

void vertex_shade(const struct mesh *m, const struct vertex_uniforms *u, uint32_t i,
                  struct vertex_out *o)
{
    const struct mesh_vertex *mv = &m->verts[i];
    int want_normals = u->view == VIEW_NORMALS || u->shade == SHADE_PHONG;
    int want_gouraud = !want_normals && u->shade == SHADE_GOURAUD;
    vec3 wp = m4_mul_point(u->model, (vec3){mv->pos[0], mv->pos[1], mv->pos[2]});
    o->wpos[0] = (float)wp.x, o->wpos[1] = (float)wp.y, o->wpos[2] = (float)wp.z;
    o->var[0] = mv->uv[0];
    o->var[1] = mv->uv[1];
    o->shaded = 1;
    if (!want_normals && !want_gouraud)
        return;
    vec3 nd = v3_norm(m4_mul_dir(u->normal_matrix, v3(mv->nrm[0], mv->nrm[1], mv->nrm[2])));
    float n[3] = {(float)nd.x, (float)nd.y, (float)nd.z};
    if (want_normals) {
        o->var[2] = o->wpos[0], o->var[3] = o->wpos[1], o->var[4] = o->wpos[2];
        o->var[5] = n[0], o->var[6] = n[1], o->var[7] = n[2];
    } else {
        float ns = m->materials[m->vert_material ? m->vert_material[i] : 0].ns;
        vertex_light(u, n, o->wpos, ns, &o->var[2], &o->var[5]);
    }
}
