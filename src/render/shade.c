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
    light_env_init(&c->lights, o);
}
