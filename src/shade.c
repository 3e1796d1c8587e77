/* shade.c: the per-frame shading context (the per-pixel code is inline in shade.h). */
#include "shade.h"

#include "vecmath.h"

void shade_ctx_init(struct shade_ctx *c, const struct render_opts *o, const float eye[3],
                    int ortho, const float view_back[3])
{
    c->shade = o->shade;
    c->view = o->view;
    c->filter = o->filter;
    c->ortho = ortho;
    for (int k = 0; k < 3; k++) {
        c->eye[k] = eye[k];
        c->view_back[k] = view_back[k];
    }
    c->n_lights = o->n_lights;
    for (int i = 0; i < o->n_lights; i++) {
        vec3 l = v3_norm(o->lights[i].dir);
        c->light_dir[i][0] = (float)l.x;
        c->light_dir[i][1] = (float)l.y;
        c->light_dir[i][2] = (float)l.z;
        c->light_col[i][0] = (float)o->lights[i].color.x;
        c->light_col[i][1] = (float)o->lights[i].color.y;
        c->light_col[i][2] = (float)o->lights[i].color.z;
    }
}
