/* cmd_bench.c: `rastty bench` — what a frame costs: render time, encode time, terminal bytes,
 * and how close the decoded terminal picture stays to the exact frame.
 *
 * For every scene given, the camera orbits the target (--orbit degrees a frame, --frames
 * frames, --cols x --rows cells) twice: first as the viewer draws (viewer_pass: the frame's
 * whole cost), then each frame is rendered once and fed through every encoder
 * configuration below, each with its own screen model, as a viewer would send it. Every
 * configuration's output is decoded back (decode.c) and compared with the exact frame.
 * Numbers, not verdicts: `make bench` prints them; tests never assert times. */
#include "bench.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "decode.h"
#include "encode.h"
#include "light.h"
#include "pipeline.h"
#include "prepare.h"
#include "psnr.h"
#include "ssaa.h"
#include "timing.h"

struct config {
    const char *name;
    enum palette_mode mode;
    bool diff;
    int tolerance;
    size_t budget; /* bytes per frame, 0 = none (encode.h, "Budget") */
};

/* Fixed tolerances against byte budgets: the PSNR-vs-bytes curve of the rate-distortion
 * choice, in truecolor and in 256 colours. */
static const struct config configs[] = {
    {"full truecolor", PALETTE_TRUECOLOR, false, 0, 0},
    {"diff truecolor", PALETTE_TRUECOLOR, true, 0, 0},
    {"diff tol 2", PALETTE_TRUECOLOR, true, 2, 0},
    {"diff tol 4", PALETTE_TRUECOLOR, true, 4, 0},
    {"diff 256", PALETTE_256, true, 0, 0},
    {"diff 256 tol 4", PALETTE_256, true, 4, 0},
    {"budget 2K", PALETTE_TRUECOLOR, true, 0, 2000},
    {"budget 4K", PALETTE_TRUECOLOR, true, 0, 4000},
    {"budget 8K", PALETTE_TRUECOLOR, true, 0, 8000},
    {"budget 12K", PALETTE_TRUECOLOR, true, 0, 12000},
    {"budget 16K", PALETTE_TRUECOLOR, true, 0, 16000},
    {"budget 20K", PALETTE_TRUECOLOR, true, 0, 20000},
    {"budget 25K", PALETTE_TRUECOLOR, true, 0, 25000},
    {"budget 32K", PALETTE_TRUECOLOR, true, 0, 32000},
    {"budget 48K", PALETTE_TRUECOLOR, true, 0, 48000},
    {"budget 64K", PALETTE_TRUECOLOR, true, 0, 64000},
    {"budget 80K", PALETTE_TRUECOLOR, true, 0, 80000},
    {"256 budget 2K", PALETTE_256, true, 0, 2000},
    {"256 budget 4K", PALETTE_256, true, 0, 4000},
    {"256 budget 8K", PALETTE_256, true, 0, 8000},
    {"256 budget 12K", PALETTE_256, true, 0, 12000},
    {"256 budget 16K", PALETTE_256, true, 0, 16000},
    {"256 budget 25K", PALETTE_256, true, 0, 25000},
};
enum { N_CONFIGS = sizeof configs / sizeof configs[0] };

struct track {
    struct encode_screen es;
    struct decode_state dec;
    double *bytes, *enc_ms;
    double sq;      /* accumulated squared error, all frames */
    double worst_psnr;
    int max_dev;    /* largest channel deviation seen */
};

/* frame k's camera on the orbit; the headlight, when asked, follows it as in the viewer */
static struct camera orbit_frame(const struct options *o, const struct camera *cam, int k,
                                 struct render_opts *ro)
{
    struct camera c = *cam;
    camera_turn(&c, o->orbit_deg * k, 0, 1);
    if (o->light_camera)
        light_use_camera(ro, &c);
    return c;
}

/* The viewer's frame as the viewer draws it (view.c, draw_frame): render, then the one
 * encoding it sends (truecolor, only the changed cells), nothing else between frames — the
 * comparison below runs every configuration after each render, and their screens and
 * decoders push the scene out of the caches (the render alone measured 0.93 instead of
 * 0.77 ms on the demo). Not timed: the terminal write and the status line (twice a second). */
static int viewer_pass(const struct options *o, struct pipeline *p, const struct scene *scene,
                       const struct camera *cam, struct render_opts *ro, struct fb *fb,
                       struct ssaa *ss, int cols, int rows, int frames, struct err *e)
{
    struct encode_screen es;
    double *ms = calloc(3 * (size_t)frames, sizeof *ms);
    if (!ms || encode_screen_init(&es, cols, rows, e)) {
        free(ms);
        return ms ? -1 : err_set(e, "rastty bench: out of memory");
    }
    double *render = ms + frames, *enc = ms + 2 * frames;
    struct encode_opts eo = {.mode = PALETTE_TRUECOLOR, .glyphs = cell_geom(o->glyphs).glyphs};
    int rc = 0;
    for (int k = 0; k < frames && !rc; k++) {
        struct camera c = orbit_frame(o, cam, k, ro);
        struct frame_stats st;
        double t0 = timing_now_ms();
        rc = ssaa_draw(ss, p, scene->items, scene->n_items, scene->has_sky ? &scene->sky : NULL,
                       &c, ro, fb, &st, e);
        double t1 = timing_now_ms();
        eo.diff = k > 0;
        size_t n;
        (void)encode_fb(&es, fb, &eo, &n, NULL);
        double t2 = timing_now_ms();
        ms[k] = t2 - t0, render[k] = t1 - t0, enc[k] = t2 - t1;
    }
    if (!rc)
        printf("\n%s: viewer frame (render + diff truecolor encode, nothing else between frames): "
               "median %.3f ms (render %.3f + encode %.3f), p95 %.3f ms\n",
               scene->name, timing_median(ms, frames), timing_median(render, frames),
               timing_median(enc, frames), timing_percentile(ms, frames, 0.95));
    encode_screen_free(&es);
    free(ms);
    return rc ? -1 : 0;
}

static int bench_scene(const struct options *o, const char *path, int cols, int rows, int frames,
                       struct err *e)
{
    struct scene scene;
    if (scene_load_with(path, &o->model, &scene, e))
        return 2;
    if (o->render.lod != LOD_OFF && scene_build_lod(&scene, true, o->render.lod == LOD_CLUSTERS, e)) {
        scene_free(&scene);
        return 1;
    }
    struct camera cam;
    struct render_opts ro;
    struct cell_geom geom = cell_geom(o->glyphs);
    prepare_camera(o, &scene, cols * CELL_ASPECT / rows, !scene.has_camera, &cam, &ro);
    struct fb fb = {0};
    struct ssaa ss = {0};
    struct pipeline *p = pipeline_new();
    struct track t[N_CONFIGS];
    memset(t, 0, sizeof t);
    double *render_ms = calloc((size_t)frames, sizeof *render_ms);
    int rc = 1;
    if (!p || !render_ms || fb_init(&fb, cell_fb_w(&geom, cols), cell_fb_h(&geom, rows), false, e))
        goto done;
    fb.pixel_aspect = cell_pixel_aspect(&geom);
    for (int c = 0; c < N_CONFIGS; c++) {
        t[c].bytes = calloc((size_t)frames, sizeof(double));
        t[c].enc_ms = calloc((size_t)frames, sizeof(double));
        t[c].worst_psnr = INFINITY;
        if (!t[c].bytes || !t[c].enc_ms || encode_screen_init(&t[c].es, cols, rows, e) ||
            decode_init(&t[c].dec, cols, rows, geom, e))
            goto done;
    }
    size_t npx = (size_t)fb.w * (size_t)fb.h * 3;
    if (viewer_pass(o, p, &scene, &cam, &ro, &fb, &ss, cols, rows, frames, e))
        goto done;
    uint64_t static_bytes = 0;
    for (int k = 0; k <= frames; k++) {
        struct camera c = orbit_frame(o, &cam, k < frames ? k : frames - 1, &ro);
        struct frame_stats st;
        if (ssaa_draw(&ss, p, scene.items, scene.n_items, scene.has_sky ? &scene.sky : NULL, &c,
                      &ro, &fb, &st, e))
            goto done;
        if (k < frames)
            render_ms[k] = st.render_ms;
        for (int i = 0; i < N_CONFIGS; i++) {
            struct encode_opts eo = {.mode = configs[i].mode,
                                     .diff = configs[i].diff && k > 0,
                                     .tolerance = configs[i].tolerance,
                                     .budget = configs[i].budget,
                                     .glyphs = geom.glyphs};
            size_t n;
            double t0 = timing_now_ms();
            const char *bytes = encode_fb(&t[i].es, &fb, &eo, &n, NULL);
            double dt = timing_now_ms() - t0;
            if (k == frames) { /* the same frame again: a static scene */
                if (configs[i].diff && !configs[i].budget) /* budgets may still refine */
                    static_bytes += n;
                continue;
            }
            t[i].bytes[k] = (double)n;
            t[i].enc_ms[k] = dt;
            if (decode_apply(&t[i].dec, bytes, n, e))
                goto done;
            double sq = psnr_sse(t[i].dec.rgb, fb.rgb, npx);
            t[i].sq += sq;
            double psnr = psnr_db(sq / (double)npx);
            t[i].worst_psnr = psnr < t[i].worst_psnr ? psnr : t[i].worst_psnr;
            for (size_t j = 0; j < npx; j++) {
                int d = abs((int)t[i].dec.rgb[j] - (int)fb.rgb[j]);
                t[i].max_dev = d > t[i].max_dev ? d : t[i].max_dev;
            }
        }
    }
    printf("\n%s: %d frames, %dx%d cells (%dx%d px, %s), orbit %g deg/frame, render median "
           "%.2f ms, p95 %.2f ms\n",
           scene.name, frames, cols, rows, fb.w, fb.h, cell_glyphs_name(geom.glyphs), o->orbit_deg,
           timing_median(render_ms, frames), timing_percentile(render_ms, frames, 0.95));
    printf("  %-16s %10s %10s %10s %10s %10s %8s %11s\n", "encoding", "median B", "mean B",
           "p95 B", "enc med ms", "PSNR dB", "min dB", "max |err|");
    for (int i = 0; i < N_CONFIGS; i++) {
        double sum = 0;
        for (int k = 0; k < frames; k++)
            sum += t[i].bytes[k];
        double psnr = psnr_db(t[i].sq / ((double)npx * frames));
        printf("  %-16s %10.0f %10.0f %10.0f %10.4f %10.2f %8.2f %11d\n", configs[i].name,
               timing_median(t[i].bytes, frames), sum / frames, timing_percentile(t[i].bytes, frames, 0.95),
               timing_median(t[i].enc_ms, frames), psnr, t[i].worst_psnr, t[i].max_dev);
    }
    printf("  static scene (same frame again, all unbudgeted diff encodings): %llu bytes\n",
           (unsigned long long)static_bytes);
    rc = 0;
done:
    for (int i = 0; i < N_CONFIGS; i++) {
        encode_screen_free(&t[i].es);
        decode_free(&t[i].dec);
        free(t[i].bytes);
        free(t[i].enc_ms);
    }
    free(render_ms);
    fb_free(&fb);
    ssaa_free(&ss);
    pipeline_destroy(p);
    scene_free(&scene);
    return rc;
}

int cmd_bench(const struct options *o, struct err *e)
{
    if (o->chart)
        return cmd_bench_chart(o, e);
    if (o->sweep)
        return cmd_bench_sweep(o, e);
    int cols = o->cols ? o->cols : 160, rows = o->rows ? o->rows : 48;
    int frames = o->frames ? o->frames : 180;
    if (o->n_inputs == 0)
        return err_set(e, "rastty bench: give one or more MODEL.obj or SCENE.rsc "
                          "(make bench supplies the standard set)"), 2;
    struct options oo = *o;
    if (oo.orbit_deg == 0)
        oo.orbit_deg = 2;
    for (int i = 0; i < o->n_inputs; i++) {
        int rc = bench_scene(&oo, o->inputs[i], cols, rows, frames, e);
        if (rc)
            return rc;
    }
    return 0;
}
