/* cmd_render.c: `rastty render` — one frame of one model or scene to an image file. */
#include "cmd.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "file.h"
#include "image.h"
#include "light.h"
#include "pipeline.h"
#include "scene.h"
#include "span.h"
#include "ssaa.h"
#include "texfind.h"
#include "timing.h"

#ifndef RASTTY_DATADIR
#define RASTTY_DATADIR "/usr/local/share/rastty"
#endif

int cmd_find_asset(const char *name, char *out, size_t n)
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

void cmd_view_setup(const struct options *o, const struct scene *s, double aspect, bool frame,
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

int cmd_load_scene(const struct options *o, const char *path, struct scene *s, char *found_out,
                   size_t n, struct err *e)
{
    if (found_out && n)
        found_out[0] = '\0';
    if (scene_load(path, s, e))
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
    return 0;
}

int cmd_sky(const struct options *o, const struct scene *s, const struct render_opts *ro,
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

void cmd_print_stats(const struct frame_stats *st)
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
    if (st->lod_max < 0)
        fprintf(stderr, "lod: no mesh drawn\n");
    else if (st->lod_min == st->lod_max)
        fprintf(stderr, "lod: level %d, %llu of %llu triangles\n", st->lod_max,
                (unsigned long long)st->tris_in, (unsigned long long)st->tris_full);
    else
        fprintf(stderr, "lod: levels %d-%d, %llu of %llu triangles\n", st->lod_min, st->lod_max,
                (unsigned long long)st->tris_in, (unsigned long long)st->tris_full);
}

int cmd_render(const struct options *o, struct err *e)
{
    char q[FILE_QUOTE_SIZE];
    if (!image_color_ext_ok(o->out))
        return err_set(e, "rastty render: --out %s: use a .ppm or .png file name",
                       file_quote(o->out, q, sizeof q)), 2;
    struct scene scene;
    double l0 = timing_now_ms();
    if (cmd_load_scene(o, o->inputs[0], &scene, NULL, 0, e))
        return 2;
    double load_ms = timing_now_ms() - l0;
    struct camera cam;
    struct render_opts ro;
    /* --glyphs: the pixels are that glyph set's (cell.h), as a terminal would show them */
    struct cell_geom geom = cell_geom(o->render.glyphs);
    double pixel_aspect = cell_pixel_aspect(&geom); /* 1: half blocks' pixels are square */
    cmd_view_setup(o, &scene, (double)o->width * pixel_aspect / o->height, o->frame, &cam, &ro);
    struct fb fb;
    struct ssaa ss = {0};
    struct pipeline *p = pipeline_new();
    struct frame_stats st;
    struct skybox tmp = {0};
    const struct skybox *sky;
    double *ms = NULL;
    int rc = 1;
    if (!p)
        err_set(e, "out of memory");
    else if (!(ms = malloc((size_t)o->repeat * sizeof *ms)))
        err_set(e, "out of memory");
    else if (cmd_sky(o, &scene, &ro, &tmp, &sky, e) == 0 &&
             fb_init(&fb, o->width, o->height, ro.view == VIEW_OVERDRAW, e) == 0) {
        fb.pixel_aspect = pixel_aspect;
        if (o->light_camera) /* after the sky: its sun stays toward the world light */
            light_use_camera(&ro, &cam);
        int drawn = 0;
        for (; drawn < o->repeat; drawn++) { /* --repeat: the same frame again, for timing */
            if (ssaa_draw(&ss, p, scene.items, scene.n_items, sky, &cam, &ro, &fb, &st, e))
                break;
            ms[drawn] = st.render_ms;
        }
        if (drawn == o->repeat && image_write_color(o->out, &fb, e) == 0 &&
            (!o->depth_out || image_write_pfm(o->depth_out, &fb, e) == 0))
            rc = 0;
        if (o->stats && drawn > 0) {
            cmd_print_stats(&st);
            fprintf(stderr, "camera: --eye %.9g,%.9g,%.9g --target %.9g,%.9g,%.9g --up %.9g,%.9g,%.9g "
                            "--fov %.9g --near %.9g --far %.9g\n",
                    cam.eye.x, cam.eye.y, cam.eye.z, cam.target.x, cam.target.y, cam.target.z,
                    cam.up.x, cam.up.y, cam.up.z, cam.fov_deg, cam.near, cam.far);
            double med = timing_median(ms, drawn); /* sorts ms: ms[0] is the fastest */
            fprintf(stderr,
                    "frames=%d median_ms=%.4f min_ms=%.4f load_ms=%.2f simd=%s threads=%d "
                    "split=%s\n",
                    drawn, med, ms[0], load_ms, span_isa_name(), st.threads,
                    st.threads < 2 ? "none" : st.slices ? "slices" : "tiles");
        }
        fb_free(&fb);
    }
    free(ms);
    ssaa_free(&ss);
    pipeline_destroy(p);
    skybox_free(&tmp);
    scene_free(&scene);
    return rc;
}
