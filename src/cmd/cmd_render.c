/* cmd_render.c: `rastty render` — one frame of one model or scene to an image file. */
#include "cmd.h"

#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "dag.h"
#include "file.h"
#include "image.h"
#include "light.h"
#include "lod.h"
#include "pipeline.h"
#include "prepare.h"
#include "scene.h"
#include "span.h"
#include "ssaa.h"
#include "texfind.h"
#include "timing.h"

int cmd_render(const struct options *o, struct err *e)
{
    char q[FILE_QUOTE_SIZE];
    bool to_stdout = strcmp(o->out, "-") == 0;
    if (!to_stdout && !image_color_ext_ok(o->out))
        return err_set(e, "rastty render: --out %s: use a .ppm or .png file name (or - for "
                          "standard output)",
                       file_quote(o->out, q, sizeof q)), 2;
    if (to_stdout && isatty(STDOUT_FILENO)) /* as chafa and convert do: no binary on a screen */
        return err_set(e, "rastty render: --out -: standard output is a terminal; refusing to "
                          "write a %s image to it (redirect it: > x.png, or | a viewer)",
                       o->format && strcmp(o->format, "ppm") == 0 ? "PPM" : "PNG"), 2;
    /* a scene is ~28 KB: on the heap, so a 64 KiB stack (ulimit -s 64) holds the frame */
    struct scene *scene = malloc(sizeof *scene);
    if (!scene)
        return err_set(e, "out of memory"), 2;
    double l0 = timing_now_ms();
    if (prepare_scene(o, o->inputs[0], scene, NULL, 0, e)) {
        free(scene);
        return 2;
    }
    double load_ms = timing_now_ms() - l0;
    struct camera cam;
    struct render_opts ro;
    /* --glyphs: the pixels are that glyph set's (cell.h), as a terminal would show them */
    struct cell_geom geom = cell_geom(o->glyphs);
    /* 1: half blocks' pixels are square (on 1:2 cells; --cell-aspect another shape) */
    double pixel_aspect = cell_pixel_aspect_r(&geom, o->cell_aspect > 0 ? o->cell_aspect : 2);
    prepare_camera(o, scene, (double)o->width * pixel_aspect / o->height, o->frame, &cam, &ro);
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
    else if (prepare_sky(o, scene, &ro, &tmp, &sky, e) == 0 &&
             fb_init(&fb, o->width, o->height, ro.view == VIEW_OVERDRAW, e) == 0) {
        fb.pixel_aspect = pixel_aspect;
        if (o->light_camera) /* after the sky: its sun stays toward the world light */
            light_use_camera(&ro, &cam);
        int drawn = 0;
        for (; drawn < o->repeat; drawn++) { /* --repeat: the same frame again, for timing */
            if (ssaa_draw(&ss, p, scene->items, scene->n_items, sky, &cam, &ro, &fb, &st, e))
                break;
            ms[drawn] = st.render_ms;
        }
        if (drawn == o->repeat &&
            (to_stdout ? image_write_stdout(&fb, o->format && strcmp(o->format, "ppm") == 0, e)
                       : image_write_color(o->out, &fb, e)) == 0 &&
            (!o->depth_out || image_write_pfm(o->depth_out, &fb, e) == 0))
            rc = 0;
        if (o->stats && drawn > 0) {
            prepare_print_stats(&st);
            fprintf(stderr, "camera: --eye %.9g,%.9g,%.9g --target %.9g,%.9g,%.9g --up %.9g,%.9g,%.9g "
                            "--fov %.9g --near %.9g --far %.9g\n",
                    cam.eye.x, cam.eye.y, cam.eye.z, cam.target.x, cam.target.y, cam.target.z,
                    cam.up.x, cam.up.y, cam.up.z, cam.fov_deg, cam.near, cam.far);
            int read = 0, written = 0;
            for (int i = 0; i < scene->n_meshes; i++) {
                read += lod_cache_use(&scene->meshes[i]) == LOD_CACHE_READ;
                written += lod_cache_use(&scene->meshes[i]) == LOD_CACHE_WRITTEN;
            }
            if (read || written)
                fprintf(stderr, "lod cache: %d chains read, %d written\n", read, written);
            /* the hierarchies and the chains (issue 24: at most 1.5x their meshes' own
             * memory): [0] hierarchies, [1] chains */
            int n_with[2] = {0, 0};
            size_t held[2] = {0, 0}, own[2] = {0, 0};
            double dag_ms = 0;
            for (int i = 0; i < scene->n_meshes; i++) {
                const struct mesh *m = &scene->meshes[i];
                const struct mesh_dag *d = dag_of(m);
                const size_t b[2] = {d ? d->bytes : 0, lod_bytes(m)};
                for (int k = 0; k < 2; k++)
                    if (k ? lod_level_count(m) > 1 : d != NULL) {
                        n_with[k]++;
                        held[k] += b[k];
                        own[k] += mesh_geometry_bytes(m);
                    }
                dag_ms += d ? d->build_ms : 0;
            }
            for (int k = 0; k < 2; k++)
                if (n_with[k]) {
                    fprintf(stderr, "%s: %d meshes, %.1f MB, %.2fx their own geometry's %.1f MB",
                            k ? "levels" : "hierarchy", n_with[k], held[k] / 1048576.0,
                            (double)held[k] / (double)own[k], own[k] / 1048576.0);
                    if (!k)
                        fprintf(stderr, "; built in %.0f ms", dag_ms);
                    fputc('\n', stderr);
                }
            double med = timing_median(ms, drawn); /* sorts ms: ms[0] is the fastest */
            fprintf(stderr,
                    "frames=%d median_ms=%.4f min_ms=%.4f load_ms=%.2f simd=%s threads=%d "
                    "split=%s\n",
                    drawn, med, ms[0], load_ms, st.kernel, st.threads,
                    st.threads < 2 ? "none" : st.slices ? "slices" : "tiles");
        }
        fb_free(&fb);
    }
    free(ms);
    ssaa_free(&ss);
    pipeline_destroy(p);
    skybox_free(&tmp);
    scene_free(scene);
    free(scene);
    return rc;
}
