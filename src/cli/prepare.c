/* prepare.c: what every subcommand does around its frames (see prepare.h). */
#include "prepare.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "texfind.h"

#ifndef RASTTY_DATADIR
#define RASTTY_DATADIR "/usr/local/share/rastty"
#endif

int prepare_find_asset(const char *name, char *out, size_t n)
{
    const char *env = getenv("RASTTY_ASSETS");
    if (env && *env) {
        snprintf(out, n, "%s/%s", env, name);
        return access(out, R_OK);
    }
    char exe[4096];
    ssize_t len = readlink("/proc/self/exe", exe, sizeof exe - 1);
    char *slash = len > 0 ? (exe[len] = '\0', strrchr(exe, '/')) : NULL;
    if (slash) {
        *slash = '\0';
        snprintf(out, n, "%s/assets/%s", exe, name);
        if (access(out, R_OK) == 0)
            return 0;
        snprintf(out, n, "%s/../share/rastty/%s", exe, name);
        if (access(out, R_OK) == 0)
            return 0;
    }
    snprintf(out, n, "assets/%s", name);
    if (access(out, R_OK) == 0)
        return 0;
    snprintf(out, n, "%s/%s", RASTTY_DATADIR, name);
    return access(out, R_OK);
}

void prepare_camera(const struct options *o, const struct scene *s, double aspect, bool frame,
                    struct camera *cam, struct render_opts *ro)
{
    *cam = o->camera;
    *ro = o->render;
    if (s->has_camera && !o->camera_set) {
        *cam = s->camera;
        cam->ortho_height = o->camera.ortho_height;
    } else if (frame) {
        camera_frame_box(cam, s->bound_lo, s->bound_hi, aspect);
    }
    if (o->near_far_set) { /* --near/--far win over the scene's and the framing's */
        cam->near = o->camera.near;
        cam->far = o->camera.far;
    }
    if (s->n_lights && !o->light_set) {
        ro->n_lights = s->n_lights;
        for (int i = 0; i < s->n_lights; i++)
            ro->lights[i] = s->lights[i];
    }
    if (s->has_background && !o->background_set)
        for (int k = 0; k < 3; k++)
            ro->background[k] = s->background[k];
}

/* A model as it came from a bare OBJ: one mesh, uvs, only the implicit material. */
static bool wants_a_texture(const struct scene *s)
{
    const struct mesh *m = &s->meshes[0];
    return s->n_meshes == 1 && s->n_items == 1 && m->has_uvs && m->n_textures == 0 &&
           m->n_materials == 1 && m->materials[0].implicit;
}

int prepare_scene(const struct options *o, const char *path, struct scene *s, char *found_out,
                   size_t n, struct err *e)
{
    if (found_out && n)
        found_out[0] = '\0';
    if (scene_load_with(path, &o->model, s, e))
        return -1;
    if (o->texture && scene_set_texture(s, o->texture, e)) {
        scene_free(s);
        return -1;
    }
    /* the model still draws: say what was wrong with it, and go on */
    for (int i = 0; i < s->warnings.n; i++)
        fprintf(stderr, "warning: %s\n", s->warnings.msg[i]);
    if (s->warnings.dropped)
        fprintf(stderr, "warning: ... and %d more warnings\n", s->warnings.dropped);
    size_t len = strlen(path);
    bool model = len < 4 || strcmp(path + len - 4, ".rsc") != 0;
    char found[4200];
    if (!o->texture && o->render.textures && model && wants_a_texture(s) &&
        texfind_beside(path, found, sizeof found) == 0) {
        /* like a model's own map_Kd, a texture nobody named is a warning, not an error */
        struct err why = {""};
        if (scene_set_texture(s, found, &why))
            fprintf(stderr, "warning: %s (found beside the model; drawn untextured)\n", why.msg);
        else if (found_out)
            snprintf(found_out, n, "%s", found);
    }
    /* levels of detail when they may be drawn: the viewer builds them in the background
     * (its first frames draw the meshes in full), the others before the first frame */
    bool view = o->cmd == CMD_VIEW;
    if ((view || o->render.lod != LOD_OFF) && scene_build_lod(s, !view, e)) {
        scene_free(s);
        return -1;
    }
    /* clusters only when they are used (--cluster-cull on): they do not pay yet (README) */
    if (o->render.cluster_cull == CLUSTER_CULL_ON && scene_build_clusters(s, e)) {
        scene_free(s);
        return -1;
    }
    return 0;
}

int prepare_sky(const struct options *o, const struct scene *s, const struct render_opts *ro,
            struct skybox *tmp, const struct skybox **sky_out, struct err *e)
{
    *sky_out = NULL;
    if (s->has_sky)
        *sky_out = &s->sky;
    else if (o->sky_procedural) {
        if (skybox_procedural(tmp, ro->lights[0].dir, e))
            return -1;
        *sky_out = tmp;
    }
    return 0;
}

void prepare_print_stats(const struct frame_stats *st)
{
    fprintf(stderr,
            "tris in %llu, rejected %llu, culled %llu, no pixel centre %llu, clipped %llu, "
            "drawn %llu (no pixel %llu); vertices lit %llu; pixels tested %llu, shaded %llu; "
            "%.3f ms\n",
            (unsigned long long)st->tris_in, (unsigned long long)st->tris_rejected,
            (unsigned long long)st->tris_culled, (unsigned long long)st->tris_no_centre,
            (unsigned long long)st->tris_clipped,
            (unsigned long long)st->tris_drawn, (unsigned long long)st->tris_empty,
            (unsigned long long)st->verts_lit,
            (unsigned long long)st->pixels_tested,
            (unsigned long long)st->pixels_shaded, st->render_ms);
    if (st->clusters_tested)
        fprintf(stderr, "clusters: tested %llu, culled %llu (frustum %llu, facing %llu, no "
                        "pixel centre %llu), drawn %llu\n",
                (unsigned long long)st->clusters_tested,
                (unsigned long long)(st->clusters_frustum + st->clusters_facing +
                                     st->clusters_no_centre),
                (unsigned long long)st->clusters_frustum, (unsigned long long)st->clusters_facing,
                (unsigned long long)st->clusters_no_centre, (unsigned long long)st->clusters_drawn);
    if (st->lod_max < 0)
        fprintf(stderr, "lod: no mesh drawn\n");
    else if (st->lod_min == st->lod_max)
        fprintf(stderr, "lod: level %d, %llu of %llu triangles\n", st->lod_max,
                (unsigned long long)st->tris_in, (unsigned long long)st->tris_full);
    else
        fprintf(stderr, "lod: levels %d-%d, %llu of %llu triangles\n", st->lod_min, st->lod_max,
                (unsigned long long)st->tris_in, (unsigned long long)st->tris_full);
}

