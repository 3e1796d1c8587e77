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

int prepare_camera_count(const struct scene *s)
{
    return s->n_items == 1 && s->items[0].mesh ? (int)s->items[0].mesh->n_cameras : 0;
}

int prepare_file_camera(const struct scene *s, int k, struct camera *out)
{
    if (k < 1 || k > prepare_camera_count(s))
        return -1;
    const struct mesh_camera *c = &s->items[0].mesh->cameras[k - 1];
    mat4 m = s->items[0].model; /* (the u key turns the scene: its cameras turn with it) */
    vec3 eye = m4_mul_point(m, v3(c->eye[0], c->eye[1], c->eye[2]));
    vec3 fwd = v3_norm(m4_mul_dir(m, v3(c->forward[0], c->forward[1], c->forward[2])));
    vec3 up = v3_norm(m4_mul_dir(m, v3(c->up[0], c->up[1], c->up[2])));
    /* the target: where the view passes the scene's centre (orbiting turns about it) */
    vec3 centre = v3_scale(v3_add(s->bound_lo, s->bound_hi), 0.5);
    double ext = v3_len(v3_sub(s->bound_hi, s->bound_lo));
    double d = v3_dot(v3_sub(centre, eye), fwd);
    d = d > 1e-3 * ext ? d : ext > 0 ? ext : 1;
    camera_default(out);
    out->eye = eye;
    out->target = v3_add(eye, v3_scale(fwd, d));
    out->up = up;
    if (c->yfov_deg > 0)
        out->fov_deg = c->yfov_deg;
    else
        out->ortho_height = c->ortho_height;
    out->near = c->znear;
    /* no far plane (glTF's infinite projection): past the scene's farthest corner */
    double far = c->zfar > c->znear ? c->zfar : 0;
    if (!(far > 0))
        far = 2 * (v3_len(v3_sub(centre, eye)) + ext) + out->near;
    out->far = far;
    if (v3_len(v3_cross(fwd, up)) < 1e-9) /* (a degenerate camera: rastty's framing instead) */
        return -1;
    return 0;
}

void prepare_camera(const struct options *o, const struct scene *s, double aspect, bool frame,
                    struct camera *cam, struct render_opts *ro)
{
    *cam = o->camera;
    *ro = o->render;
    if (s->has_camera && !o->camera_set) {
        *cam = s->camera;
        cam->ortho_height = o->camera.ortho_height;
    } else if (!o->camera_set && o->file_camera != 0 &&
               prepare_file_camera(s, o->file_camera < 0 ? 1 : o->file_camera, cam) == 0) {
        /* the model's own camera: the author's view */
    } else if (frame || (!o->camera_set && o->file_camera == 0)) {
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
    if (o->normal_map && scene_set_normal_map(s, o->normal_map, e)) {
        scene_free(s);
        return -1;
    }
    if (o->file_camera > 0 && o->file_camera > prepare_camera_count(s)) {
        char q[200];
        err_quote(path, strlen(path), 160, q, sizeof q);
        err_set(e, "%s: --camera %d: the model has %d camera%s", q, o->file_camera,
                prepare_camera_count(s), prepare_camera_count(s) == 1 ? "" : "s");
        scene_free(s);
        return -1;
    }
    /* the model still draws: say what was wrong with it, and go on */
    for (int i = 0; i < s->warnings.n; i++)
        fprintf(stderr, "warning: %s\n", s->warnings.msg[i]);
    if (s->warnings.dropped)
        fprintf(stderr, "warning: ... and %d more warnings\n", s->warnings.dropped);
    size_t len = strlen(path);
    /* (standard input has no name to find a texture beside) */
    bool model = (len < 4 || strcmp(path + len - 4, ".rsc") != 0) && strcmp(path, "-") != 0;
    char found[4200];
    if (!o->texture && o->render.textures && model && wants_a_texture(s) &&
        texfind_beside(path, found, sizeof found) == 0) {
        /* like a model's own map_Kd, a texture nobody named is a warning, not an error */
        struct err why = {""};
        if (scene_set_texture(s, found, &why))
            fprintf(stderr, "warning: %s (found beside the model; drawn untextured)\n", why.msg);
        else if (found_out)
            snprintf(found_out, n, "%s", found);
        /* and its normal map, by the same habit (tinyrenderer's head: african_head_nm.tga) */
        if (!o->normal_map && texfind_normal_beside(path, found, sizeof found) == 0 &&
            scene_set_normal_map(s, found, &why))
            fprintf(stderr, "warning: %s (found beside the model; drawn without it)\n", why.msg);
    }
    /* levels of detail when they may be drawn, before the first frame; the viewer starts
     * them itself, in the background after its first frame (view.c start_levels) */
    if (o->cmd != CMD_VIEW && o->render.lod != LOD_OFF &&
        scene_build_lod(s, true, o->render.lod == LOD_CLUSTERS, e)) {
        scene_free(s);
        return -1;
    }
    /* clusters when they are used (--cluster-cull on, the default; 0.07 s a million
     * triangles) */
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
            "tris in %llu, rejected %llu, culled %llu, no pixel centre %llu, hidden %llu, "
            "clipped %llu, drawn %llu (no pixel %llu); vertices lit %llu; pixels tested %llu, "
            "shaded %llu; %.3f ms\n",
            (unsigned long long)st->tris_in, (unsigned long long)st->tris_rejected,
            (unsigned long long)st->tris_culled, (unsigned long long)st->tris_no_centre,
            (unsigned long long)st->tris_hidden,
            (unsigned long long)st->tris_clipped,
            (unsigned long long)st->tris_drawn, (unsigned long long)st->tris_empty,
            (unsigned long long)st->verts_lit,
            (unsigned long long)st->pixels_tested,
            (unsigned long long)st->pixels_shaded, st->render_ms);
    if (st->clusters_tested)
        fprintf(stderr, "clusters: tested %llu, culled %llu (frustum %llu, facing %llu, no "
                        "pixel centre %llu, hidden %llu), drawn %llu\n",
                (unsigned long long)st->clusters_tested,
                (unsigned long long)(st->clusters_frustum + st->clusters_facing +
                                     st->clusters_no_centre + st->clusters_hidden),
                (unsigned long long)st->clusters_frustum, (unsigned long long)st->clusters_facing,
                (unsigned long long)st->clusters_no_centre,
                (unsigned long long)st->clusters_hidden, (unsigned long long)st->clusters_drawn);
    if (st->occluders)
        fprintf(stderr, "occluders: %llu triangles of the last frame; behind them %llu "
                        "clusters and %llu triangles (of those hidden)\n",
                (unsigned long long)st->occluders, (unsigned long long)st->clusters_occluded,
                (unsigned long long)st->tris_occluded);
    if (st->dag_cut) {
        int lo = __builtin_ctz(st->dag_levels), hi = 31 - __builtin_clz(st->dag_levels);
        fprintf(stderr, "lod: cluster hierarchy, a cut of %llu clusters of levels %d-%d, %llu "
                        "triangles\n",
                (unsigned long long)st->dag_cut, lo, hi, (unsigned long long)st->dag_tris);
    }
    if (st->lod_max < 0) {
        if (!st->dag_cut)
            fprintf(stderr, "lod: no mesh drawn\n");
    } else if (st->dag_cut)
        fprintf(stderr, "lod: other meshes at levels %d-%d\n", st->lod_min, st->lod_max);
    else if (st->lod_min == st->lod_max)
        fprintf(stderr, "lod: level %d, %llu of %llu triangles\n", st->lod_max,
                (unsigned long long)st->tris_in, (unsigned long long)st->tris_full);
    else
        fprintf(stderr, "lod: levels %d-%d, %llu of %llu triangles\n", st->lod_min, st->lod_max,
                (unsigned long long)st->tris_in, (unsigned long long)st->tris_full);
}

