/* render.c: default render options and the names of every method (see render.h). */
#include "render.h"

#include <string.h>

static const char *const shade_names[] = {"unlit", "flat", "gouraud", "phong", "wire"};
static const char *const cull_names[] = {"none", "back", "front"};
static const char *const filter_names[] = {"nearest", "bilinear"};
static const char *const view_names[] = {"color", "depth", "normals", "overdraw", "wire-overlay"};
_Static_assert(sizeof shade_names / sizeof *shade_names == SHADE_COUNT, "shade names");
_Static_assert(sizeof cull_names / sizeof *cull_names == CULL_COUNT, "cull names");
_Static_assert(sizeof filter_names / sizeof *filter_names == TEX_FILTER_COUNT, "filter names");
_Static_assert(sizeof view_names / sizeof *view_names == VIEW_COUNT, "view names");

void render_opts_default(struct render_opts *o)
{
    memset(o, 0, sizeof *o);
    o->shade = SHADE_PHONG;
    o->filter = TEX_NEAREST;
    o->cull = CULL_NONE;
    o->view = VIEW_COLOR;
    o->textures = true;
    o->wire_color[0] = o->wire_color[1] = o->wire_color[2] = 255;
    o->n_lights = 1;
    o->lights[0].dir = v3(1, 1, 1);
    o->lights[0].color = v3(1, 1, 1);
}

const char *render_shade_name(enum shade_mode m) { return shade_names[m]; }
const char *render_cull_name(enum cull_mode m) { return cull_names[m]; }
const char *render_filter_name(enum tex_filter f) { return filter_names[f]; }
const char *render_view_name(enum debug_view v) { return view_names[v]; }

static int lookup(const char *const *names, int n, const char *s)
{
    for (int i = 0; i < n; i++)
        if (strcmp(names[i], s) == 0)
            return i;
    return -1;
}

int render_shade_parse(const char *s) { return lookup(shade_names, SHADE_COUNT, s); }
int render_cull_parse(const char *s) { return lookup(cull_names, CULL_COUNT, s); }
int render_filter_parse(const char *s) { return lookup(filter_names, TEX_FILTER_COUNT, s); }
