/* render_opts.c: the methods and their names (see render_opts.h). */
#include "render_opts.h"

#include <string.h>

static const char *const shade_names[] = {"unlit", "flat", "gouraud", "phong", "wire"};
static const char *const cull_names[] = {"none", "back", "front", "auto"};
static const char *const filter_names[] = {"nearest", "bilinear", "trilinear"};
static const char *const view_names[] = {"color", "depth", "normals", "overdraw", "wire-overlay"};
static const char *const raster_names[] = {"edge", "scanline", "tiled"};
static const char *const persp_names[] = {"correct", "affine", "span8", "span16", "span32"};
static const char *const depth_names[] = {"z", "w", "z16", "rz"};
static const char *const ssaa_names[] = {"1", "2", "4", "8"};
static const char *const lod_names[] = {"off", "auto"}; /* LOD_RATIO is a number */
static const char *const split_names[] = {"auto", "tiles", "slices"};
static const char *const cluster_cull_names[] = {"off", "on"};
static const char *const hidden_cull_names[] = {"off", "on"};
static const char *const occluders_names[] = {"off", "on", "always"};
static const char *const wire_names[] = {"auto", "all", "outline"};
static const char *const kernel_names[] = {"auto", "ref", "sse2", "avx2", "avx2-4", "avx2-8"};
#define COUNT(a) ((int)(sizeof a / sizeof *a))
_Static_assert(COUNT(shade_names) == SHADE_COUNT, "shade names");
_Static_assert(COUNT(cull_names) == CULL_COUNT, "cull names");
_Static_assert(COUNT(filter_names) == TEX_FILTER_COUNT, "filter names");
_Static_assert(COUNT(view_names) == VIEW_COUNT, "view names");
_Static_assert(COUNT(raster_names) == RASTER_COUNT, "raster names");
_Static_assert(COUNT(persp_names) == PERSP_COUNT, "persp names");
_Static_assert(COUNT(depth_names) == DEPTH_COUNT, "depth names");
_Static_assert(COUNT(ssaa_names) == SSAA_COUNT, "ssaa names");
_Static_assert(COUNT(lod_names) == LOD_NAMED && LOD_AUTO == 1, "lod names");
_Static_assert(COUNT(split_names) == SPLIT_COUNT, "split names");
_Static_assert(COUNT(kernel_names) == KERNEL_ISA_COUNT, "kernel names");
_Static_assert(COUNT(cluster_cull_names) == CLUSTER_CULL_COUNT, "cluster cull names");
_Static_assert(COUNT(hidden_cull_names) == HIDDEN_CULL_COUNT, "hidden cull names");
_Static_assert(COUNT(occluders_names) == OCCLUDERS_COUNT, "occluders names");
_Static_assert(COUNT(wire_names) == WIRE_COUNT && WIRE_AUTO == 0, "wire names");

const struct render_enum render_shade_names = {shade_names, SHADE_COUNT};
const struct render_enum render_cull_names = {cull_names, CULL_COUNT};
const struct render_enum render_filter_names = {filter_names, TEX_FILTER_COUNT};
const struct render_enum render_view_names = {view_names, VIEW_COUNT};
const struct render_enum render_raster_names = {raster_names, RASTER_COUNT};
const struct render_enum render_persp_names = {persp_names, PERSP_COUNT};
const struct render_enum render_depth_names = {depth_names, DEPTH_COUNT};
const struct render_enum render_ssaa_names = {ssaa_names, SSAA_COUNT};
const struct render_enum render_lod_names = {lod_names, LOD_NAMED};
const struct render_enum render_split_names = {split_names, SPLIT_COUNT};
const struct render_enum render_kernel_names = {kernel_names, KERNEL_ISA_COUNT};
const struct render_enum render_cluster_cull_names = {cluster_cull_names, CLUSTER_CULL_COUNT};
const struct render_enum render_hidden_cull_names = {hidden_cull_names, HIDDEN_CULL_COUNT};
const struct render_enum render_occluders_names = {occluders_names, OCCLUDERS_COUNT};
const struct render_enum render_wire_names = {wire_names, WIRE_COUNT};

void render_opts_default(struct render_opts *o)
{
    memset(o, 0, sizeof *o);
    o->shade = SHADE_PHONG;
    o->filter = TEX_TRILINEAR;
    o->raster = RASTER_EDGE;
    o->persp = PERSP_CORRECT;
    o->depth = DEPTH_Z;
    o->ssaa = SSAA_1;
    o->lod = LOD_OFF;
    o->lod_ratio = 1;
    o->lod_px = LOD_DEFAULT_PX;
    o->cull = CULL_AUTO;
    o->cluster_cull = CLUSTER_CULL_ON;
    o->hidden_cull = HIDDEN_CULL_ON;
    o->occluders = OCCLUDERS_ON;
    o->heads_ratio = RENDER_HEADS_RATIO;
    o->view = VIEW_COLOR;
    o->textures = true;
    o->wire_color[0] = o->wire_color[1] = o->wire_color[2] = 255;
    o->n_lights = 1;
    o->lights[0].dir = v3(1, 1, 1);
    o->lights[0].color = v3(1, 1, 1);
    o->ambient_sky = o->ambient_ground = v3(0.1, 0.1, 0.1);
}

void render_opts_ideal(struct render_opts *o)
{
    o->persp = PERSP_CORRECT;
    o->filter = TEX_TRILINEAR;
    o->ssaa = SSAA_8;
    o->lod = LOD_OFF;
}

const char *render_shade_name(enum shade_mode m) { return shade_names[m]; }
const char *render_cull_name(enum cull_mode m) { return cull_names[m]; }
const char *render_filter_name(enum tex_filter f) { return filter_names[f]; }
const char *render_view_name(enum debug_view v) { return view_names[v]; }
const char *render_raster_name(enum raster_method m) { return raster_names[m]; }
const char *render_persp_name(enum persp_method m) { return persp_names[m]; }
const char *render_depth_name(enum depth_mode m) { return depth_names[m]; }

int render_enum_parse(const struct render_enum *t, const char *s)
{
    for (int i = 0; i < t->n; i++)
        if (strcmp(t->names[i], s) == 0)
            return i;
    return -1;
}

int render_opts_get(const struct render_opts *o, size_t field)
{
    int v;
    memcpy(&v, (const char *)o + field, sizeof v);
    return v;
}

void render_opts_set(struct render_opts *o, size_t field, int v)
{
    memcpy((char *)o + field, &v, sizeof v);
}
