/* scene.h: what is drawn — meshes placed in the world, plus lights, camera start, sky and
 * background. Holds only what a scene uses; owns its meshes, textures and sky; the pipeline
 * borrows meshes through the draw items.
 *
 * Sources: one model (scene_load_model: any format model.h reads, as given, identity
 * transform) or a scene file (scene_load_file, format below; every error is
 * "file:line: message"). Textures load through the scene's texture cache: each file once,
 * within one budget (texture.h). Things wrong with a model that still draws (a material's
 * missing texture, ...) are collected in `warnings` for the caller to print.
 *
 * Scene file (.rsc), one statement per line, '#' starts a comment, paths relative to the
 * scene file, a path with spaces in double quotes:
 *   model PATH [at X Y Z] [rotate X Y Z] [scale S | scale X Y Z] [texture PATH] [kd R G B]
 *         PATH: any model format (model.h)
 *         rotate = degrees about X, then Y, then Z; model matrix = translate * rotate * scale;
 *         texture replaces the OBJ's map_Kd, kd (0..1) replaces its diffuse colour
 *   light X Y Z [R G B]           direction toward the light, colour 0..1 (default white);
 *                                 up to 4; no light line = one white light toward (1,1,1)
 *   camera X Y Z [target X Y Z] [fov DEG]
 *   sky procedural | sky POSX NEGX POSY NEGY POSZ NEGZ
 *   background R G B              0..255, shown where there is no sky
 */
#ifndef RASTTY_SCENE_H
#define RASTTY_SCENE_H

#include <stdbool.h>

#include "camera.h"
#include "err.h"
#include "mesh.h"
#include "model.h"
#include "skybox.h"

#define SCENE_MAX_ITEMS 64
#define SCENE_MAX_LIGHTS 4

/* A directional light (render/light.h says how it lights a point). */
struct light {
    vec3 dir;   /* toward the light, world space, need not be unit length */
    vec3 color; /* linear, 1 = white */
};

/* One mesh placed in the world: what the pipeline draws (render/pipeline.h). */
struct draw_item {
    const struct mesh *mesh;
    mat4 model;                              /* object -> world */
    const struct texture *texture_override;  /* --texture: replaces every map_Kd; or NULL */
    const float *kd_override;                /* replaces every material's kd; or NULL */
};

struct lod_job;

struct scene {
    char name[64];                      /* for the HUD: file name, printable ASCII only */
    struct mesh meshes[SCENE_MAX_ITEMS]; /* distinct model files, n_meshes of them */
    int n_meshes;
    struct texture_cache textures;      /* every texture of the scene, once per file */
    struct warnings warnings;           /* from loading: the caller prints them */
    float kd_override[SCENE_MAX_ITEMS][3];     /* per item, for `kd` */
    struct draw_item items[SCENE_MAX_ITEMS];
    int n_items;
    int n_lights;                       /* 0 = use the caller's default light */
    struct light lights[SCENE_MAX_LIGHTS];
    bool has_camera;
    struct camera camera;               /* valid when has_camera */
    bool has_background;
    uint8_t background[3];
    bool has_sky;
    struct skybox sky;
    vec3 bound_lo, bound_hi;            /* world-space box around every item */
    struct lod_job *lod_job;            /* levels of detail being built (lod.h), or NULL */
    struct model_opts load;             /* how its models were read (model.h) */
    char up;                            /* the models' axis drawn up: 'x', 'y' or 'z' (as
                                           loaded: the file's or --up-axis; scene_turn_up) */
};

/* One model drawn as given (identity model matrix). */
int scene_load_model(const char *obj_path, struct scene *out, struct err *e);
/* A scene file (format above). */
int scene_load_file(const char *path, struct scene *out, struct err *e);
/* By extension: .rsc -> scene file, anything else -> model. */
int scene_load(const char *path, struct scene *out, struct err *e);
/* The same, every model read with these options (model.h; NULL: the defaults). */
int scene_load_with(const char *path, const struct model_opts *opts, struct scene *out,
                    struct err *e);
/* Give every material of every mesh without one this normal map (--normal-map, or one found
 * by name beside the model): tangent or object space or a bump map, told apart by its
 * texels (material.h); the meshes then draw by the features path. Errors: the file cannot
 * be read or decoded ("path: ..."), out of memory. */
int scene_set_normal_map(struct scene *s, const char *path, struct err *e);
/* Turn every item so that the next axis of its model file is up (y -> z -> x -> y, about
 * the scene's centre; the viewer's u key); the new axis. */
char scene_turn_up(struct scene *s);
/* Draw every item with this texture instead of its own (--texture). */
int scene_set_texture(struct scene *s, const char *path, struct err *e);
/* Build every mesh's levels of detail (lod.h; clusters: first the cluster hierarchies,
 * dag.h): wait = before returning; else on a background thread (the viewer: the first
 * frames draw the meshes in full, then the levels arrive). Again: nothing. -1 only when out
 * of memory. */
int scene_build_lod(struct scene *s, bool wait, bool clusters, struct err *e);
/* Every mesh's clusters (cluster.h; --cluster-cull on), now: -1 out of memory. */
int scene_build_clusters(struct scene *s, struct err *e);
/* Are the levels built (or none asked for)? */
bool scene_lod_done(const struct scene *s);
/* Once the levels are built, let every mesh share its hierarchy's copy of its own arrays
 * (dag_settle: its memory freed); call it where no frame is being drawn. With wait,
 * scene_build_lod does it. */
void scene_lod_settle(struct scene *s);
/* Stops a background build first. */
void scene_free(struct scene *s);

#endif
