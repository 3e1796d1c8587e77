/* chart.c: speed against accuracy for every method (see chart.h). */
#include "chart.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "cell.h"
#include "decode.h"
#include "encode.h"
#include "pipeline.h"
#include "psnr.h"
#include "scene.h"
#include "ssaa.h"
#include "timing.h"

const struct chart_axis chart_axes[CHART_AXES] = {
    {"raster", &render_raster_names, offsetof(struct render_opts, raster), false},
    {"persp", &render_persp_names, offsetof(struct render_opts, persp), false},
    {"depth", &render_depth_names, offsetof(struct render_opts, depth), false},
    {"filter", &render_filter_names, offsetof(struct render_opts, filter), false},
    {"ssaa", &render_ssaa_names, offsetof(struct render_opts, ssaa), false},
    {"lod", &render_lod_names, offsetof(struct render_opts, lod), true},
};
_Static_assert(CHART_CSV_AXES <= CHART_AXES, "CSV axes are a prefix of the axes");

#define CHART_PILOT 4 /* pilot frames per row: one warm-up (errors, bytes), three timed */
#define CHART_MAX_ROWS 48 /* per scene and size */

/* ---- the scene set ---- */

enum chart_camera {
    CAM_SCENE, /* the scene file's camera, else the default one */
    CAM_GIVEN, /* eye, target, up below */
    CAM_FRAME, /* from eye's direction, backed off to fit the model's box */
};

struct chart_scene_def {
    const char *name;
    bool shared;                /* under models_dir, else under assets_dir */
    const char *file, *texture; /* texture: replaces the model's own (--texture), or NULL */
    enum chart_camera camera;
    double eye[3], target[3], up[3];
    bool magenta;               /* background 255,0,255: cracks show */
};

static const struct chart_scene_def scene_defs[] = {
    {"demo", false, "demo.rsc", NULL, CAM_SCENE, {0}, {0}, {0}, false},
    /* 20x20 checker floor from 0.5 above, looking 19 units along it, rolled 20 degrees:
     * rows are not lines of equal depth, so spans are not exact by luck */
    {"ground", false, "floor.obj", NULL, CAM_GIVEN, {0, 0.5, 9.5}, {0, 0.2, -1},
     {0.34, 0.94, 0}, false},
    {"sphere", false, "sphere.obj", NULL, CAM_FRAME, {0.3, 0.4, 2}, {0, 0, 0}, {0, 1, 0}, true},
    {"head", true, "african_head/african_head.obj", "african_head/african_head_diffuse.tga",
     CAM_SCENE, {0}, {0}, {0}, false},
    {"car", true, "sports_car/sportsCar.obj", NULL, CAM_FRAME, {2, 1, 3}, {0, 0, 0}, {0, 1, 0},
     false},
    /* the other dense shared models, for the level of detail */
    {"empire", true, "lost_empire/lost_empire.obj", NULL, CAM_FRAME, {2, 1, 3}, {0, 0, 0},
     {0, 1, 0}, false},
    {"bunny", true, "bunny/bunny.obj", NULL, CAM_FRAME, {2, 1, 3}, {0, 0, 0}, {0, 1, 0}, false},
};
enum { N_SCENE_DEFS = sizeof scene_defs / sizeof scene_defs[0] };

struct loaded {
    const struct chart_scene_def *def;
    struct scene *s;
};

/* One scene at one size: its camera and options, the ideal picture, its rows. */
struct group {
    struct loaded *sc;
    int w, h;
    struct camera cam;
    struct render_opts base; /* default methods, the scene's lights and background */
    uint8_t *ideal;          /* w*h*3 */
    int rows[CHART_MAX_ROWS];
    int n_rows;
    double *times;           /* per row, per timed frame */
};

struct run {
    const struct chart_config *c;
    struct chart *out;
    int cap_rows;
    struct pipeline *p;
};

static int axis_get(const struct render_opts *o, int a)
{
    return render_opts_get(o, chart_axes[a].field);
}

static void axis_set(struct render_opts *o, int a, int v)
{
    render_opts_set(o, chart_axes[a].field, v);
}

static void row_opts(const struct group *g, const struct chart_row *r, struct render_opts *o)
{
    *o = g->base;
    for (int a = 0; a < CHART_AXES; a++)
        axis_set(o, a, r->value[a]);
}

static int load_scenes(const struct chart_config *c, struct loaded *ls, int *n_out,
                       struct chart *out, struct err *e)
{
    int n = 0;
    for (int i = 0; i < N_SCENE_DEFS; i++) {
        const struct chart_scene_def *d = &scene_defs[i];
        if (c->only && !strstr(d->name, c->only))
            continue;
        const char *dir = d->shared ? c->models_dir : c->assets_dir;
        if (!dir) {
            size_t len = strlen(out->note);
            snprintf(out->note + len, sizeof out->note - len, "%s%s", len ? ", " : "", d->name);
            continue;
        }
        char path[4200];
        snprintf(path, sizeof path, "%s/%s", dir, d->file);
        struct scene *s = calloc(1, sizeof *s);
        if (!s)
            return err_set(e, "out of memory");
        ls[n].def = d;
        ls[n].s = s;
        n++;
        *n_out = n;
        if (scene_load(path, s, e) || scene_build_lod(s, true, false, e))
            return -1;
        if (d->texture) {
            snprintf(path, sizeof path, "%s/%s", dir, d->texture);
            if (scene_set_texture(s, path, e))
                return -1;
        }
    }
    if (out->note[0]) {
        char tmp[sizeof out->note];
        memcpy(tmp, out->note, sizeof tmp);
        snprintf(out->note, sizeof out->note, "no shared models: %.200s skipped", tmp);
    }
    return 0;
}

static void group_setup(struct group *g, struct loaded *l, int w, int h)
{
    memset(g, 0, sizeof *g);
    g->sc = l;
    g->w = w, g->h = h;
    const struct chart_scene_def *d = l->def;
    const struct scene *s = l->s;
    camera_default(&g->cam);
    if (d->camera == CAM_SCENE && s->has_camera) {
        g->cam = s->camera;
    } else if (d->camera != CAM_SCENE) {
        g->cam.eye = v3(d->eye[0], d->eye[1], d->eye[2]);
        g->cam.target = v3(d->target[0], d->target[1], d->target[2]);
        g->cam.up = v3(d->up[0], d->up[1], d->up[2]);
        if (d->camera == CAM_FRAME)
            camera_frame_box(&g->cam, s->bound_lo, s->bound_hi, (double)w / h);
    }
    render_opts_default(&g->base);
    g->base.threads = 1; /* one thread: the methods' own cost, not the machine's cores */
    if (s->n_lights) {
        g->base.n_lights = s->n_lights;
        for (int i = 0; i < s->n_lights; i++)
            g->base.lights[i] = s->lights[i];
    }
    if (d->magenta) {
        g->base.background[0] = g->base.background[2] = 255;
    } else if (s->has_background) {
        memcpy(g->base.background, s->background, 3);
    }
}

/* a new row of the chart for g's scene and size (not yet one of g's rows), or NULL */
static struct chart_row *push_row(struct run *x, struct group *g, const struct chart_row *r,
                                  struct err *e)
{
    struct chart *out = x->out;
    if (out->n_rows == x->cap_rows) {
        int cap = x->cap_rows ? 2 * x->cap_rows : 64;
        struct chart_row *nr = realloc(out->rows, (size_t)cap * sizeof *nr);
        if (!nr)
            return err_set(e, "out of memory"), NULL;
        out->rows = nr;
        x->cap_rows = cap;
    }
    struct chart_row *d = &out->rows[out->n_rows++];
    *d = *r;
    snprintf(d->scene, sizeof d->scene, "%s", g->sc->def->name);
    d->w = g->w, d->h = g->h;
    d->psnr_db = NAN;
    d->shimmer = NAN;
    d->encode_ms = NAN;
    return d;
}

static int add_row(struct run *x, struct group *g, const struct chart_row *r, struct err *e)
{
    if (g->n_rows == CHART_MAX_ROWS)
        return err_set(e, "chart: too many rows for one scene");
    if (!push_row(x, g, r, e))
        return -1;
    g->rows[g->n_rows++] = x->out->n_rows - 1;
    return 0;
}

/* default, then every other value of every axis alone */
static int add_base_rows(struct run *x, struct group *g, struct err *e)
{
    struct render_opts d;
    render_opts_default(&d);
    struct chart_row r = {.kind = CHART_DEFAULT};
    for (int a = 0; a < CHART_AXES; a++)
        r.value[a] = axis_get(&d, a);
    if (add_row(x, g, &r, e))
        return -1;
    for (int a = 0; a < CHART_AXES; a++)
        for (int v = 0; v < chart_axes[a].values->n; v++) {
            if (v == axis_get(&d, a))
                continue;
            struct chart_row rv = r;
            rv.kind = CHART_VARIED;
            rv.axis = a;
            rv.value[a] = v;
            if (add_row(x, g, &rv, e))
                return -1;
        }
    return 0;
}

/* PSNR over all channels, and the fraction of pixels with a channel off by more than 8 */
static void compare(const uint8_t *a, const uint8_t *b, size_t n_px, double *psnr_out,
                    double *frac_out)
{
    size_t off = 0;
    for (size_t i = 0; i < n_px; i++) {
        int worst = 0;
        for (int k = 0; k < 3; k++) {
            int d = abs((int)a[3 * i + k] - (int)b[3 * i + k]);
            worst = d > worst ? d : worst;
        }
        off += worst > 8;
    }
    *psnr_out = psnr_db(psnr_sse(a, b, 3 * n_px) / (3.0 * (double)n_px));
    *frac_out = (double)off / (double)n_px;
}

/* Draw every row of g `frames` times, taking turns in a new random order each round; frame 0
 * is a warm-up that also measures error and bytes (where not known yet); in the others each
 * row is drawn twice and the second frame is timed into g->times. */
static int run_group(struct run *x, struct group *g, int frames, struct err *e)
{
    struct fb fb = {0};
    struct ssaa ss[SSAA_COUNT];
    memset(ss, 0, sizeof ss);
    struct encode_screen es = {0};
    int rc = -1;
    int timed = frames - 1;
    free(g->times);
    g->times = calloc((size_t)g->n_rows * (size_t)(timed > 0 ? timed : 1), sizeof *g->times);
    if (!g->times || fb_init(&fb, g->w, g->h, false, e) ||
        encode_screen_init(&es, g->w, (g->h + 1) / 2, e))
        goto done;
    const struct scene *s = g->sc->s;
    const struct skybox *sky = s->has_sky ? &s->sky : NULL;
    if (!g->ideal) {
        if (!(g->ideal = malloc((size_t)g->w * g->h * 3))) {
            err_set(e, "out of memory");
            goto done;
        }
        struct render_opts o = g->base;
        render_opts_ideal(&o);
        struct frame_stats st;
        if (ssaa_draw(&ss[o.ssaa], x->p, s->items, s->n_items, sky, &g->cam, &o, &fb, &st, e))
            goto done;
        memcpy(g->ideal, fb.rgb, (size_t)g->w * g->h * 3);
    }
    int order[CHART_MAX_ROWS];
    for (int k = 0; k < g->n_rows; k++)
        order[k] = k;
    uint32_t seed = 2463534242u;
    for (int f = 0; f < frames; f++) {
        for (int k = g->n_rows - 1; k > 0; k--) { /* a new order each round (xorshift) */
            seed ^= seed << 13, seed ^= seed >> 17, seed ^= seed << 5;
            int j = (int)(seed % (uint32_t)(k + 1)), tmp = order[k];
            order[k] = order[j], order[j] = tmp;
        }
        for (int k = 0; k < g->n_rows; k++) {
            int i = order[k];
            struct chart_row *r = &x->out->rows[g->rows[i]];
            struct render_opts o;
            row_opts(g, r, &o);
            struct frame_stats st;
            /* frame 0 warms up and measures the error; later rounds draw the row twice and
             * time the second frame, so each method is timed with its own data in the caches
             * (as a viewer draws it frame after frame), not the previous row's */
            double dt = 0;
            for (int rep = f > 0 ? 2 : 1; rep > 0; rep--) {
                double t0 = timing_now_ms();
                if (ssaa_draw(&ss[o.ssaa], x->p, s->items, s->n_items, sky, &g->cam, &o, &fb,
                              &st, e))
                    goto done;
                dt = timing_now_ms() - t0;
            }
            if (f > 0)
                g->times[(size_t)i * timed + (size_t)(f - 1)] = dt;
            else if (isnan(r->psnr_db)) {
                compare(fb.rgb, g->ideal, (size_t)g->w * g->h, &r->psnr_db, &r->frac_gt8);
                struct encode_opts eo = {.mode = PALETTE_TRUECOLOR};
                encode_screen_invalidate(&es);
                encode_fb(&es, &fb, &eo, &r->bytes, NULL);
            }
        }
    }
    rc = 0;
done:
    for (int k = 0; k < SSAA_COUNT; k++)
        ssaa_free(&ss[k]);
    encode_screen_free(&es);
    fb_free(&fb);
    return rc;
}

/* chart_row.shimmer for every row of g (the head only): the ideal's orbit frames once, then
 * each row's, the change from frame to frame compared with the ideal's */
static int measure_shimmer(struct run *x, struct group *g, struct err *e)
{
    if (strcmp(g->sc->def->name, "head") != 0)
        return 0;
    const size_t n = (size_t)g->w * g->h * 3;
    const int nf = CHART_SHIMMER_FRAMES;
    const struct scene *s = g->sc->s;
    const struct skybox *sky = s->has_sky ? &s->sky : NULL;
    struct fb fb = {0};
    struct ssaa ss[SSAA_COUNT];
    memset(ss, 0, sizeof ss);
    uint8_t *ideal = malloc(n * nf), *prev = malloc(n);
    int rc = -1;
    if (!ideal || !prev || fb_init(&fb, g->w, g->h, false, e)) {
        err_set(e, "out of memory");
        goto done;
    }
    for (int r = -1; r < g->n_rows; r++) { /* r = -1: the ideal */
        struct render_opts o;
        if (r < 0) {
            o = g->base;
            render_opts_ideal(&o);
        } else {
            row_opts(g, &x->out->rows[g->rows[r]], &o);
        }
        double sum = 0;
        for (int f = 0; f < nf; f++) {
            struct camera cam = g->cam;
            camera_turn(&cam, CHART_SHIMMER_DEG * f, 0, 1);
            struct frame_stats st;
            if (ssaa_draw(&ss[o.ssaa], x->p, s->items, s->n_items, sky, &cam, &o, &fb, &st, e))
                goto done;
            if (r < 0) {
                memcpy(ideal + n * (size_t)f, fb.rgb, n);
                continue;
            }
            if (f > 0) {
                const uint8_t *i1 = ideal + n * (size_t)f, *i0 = i1 - n;
                for (size_t k = 0; k < n; k++)
                    sum += abs(((int)fb.rgb[k] - prev[k]) - ((int)i1[k] - i0[k]));
            }
            memcpy(prev, fb.rgb, n);
        }
        if (r >= 0)
            x->out->rows[g->rows[r]].shimmer = sum / ((double)n * (nf - 1));
    }
    rc = 0;
done:
    for (int k = 0; k < SSAA_COUNT; k++)
        ssaa_free(&ss[k]);
    fb_free(&fb);
    free(ideal);
    free(prev);
    return rc;
}

/* The glyph rows (chart.h): g's scene with the default methods on a terminal of g->w x
 * g->h / 2 cells in each glyph set — the framebuffer at the set's sub-cell grid, the ideal
 * image at that grid, the frame encoded whole in truecolor and decoded back. */
static int measure_glyphs(struct run *x, struct group *g, struct err *e)
{
    const int cols = g->w, rows = g->h / 2, reps = x->c->repeat;
    const struct scene *s = g->sc->s;
    const struct skybox *sky = s->has_sky ? &s->sky : NULL;
    double *enc = calloc((size_t)reps, sizeof *enc), *ren = calloc((size_t)reps, sizeof *ren);
    int rc = enc && ren ? 0 : err_set(e, "out of memory");
    for (int gl = 0; gl < CELL_GLYPHS_COUNT && rc == 0; gl++) {
        const struct cell_geom geom = cell_geom((enum cell_glyphs)gl);
        struct fb fb = {0};
        struct ssaa ss[SSAA_COUNT];
        memset(ss, 0, sizeof ss);
        struct encode_screen es = {0};
        struct decode_state d = {0};
        uint8_t *ideal = NULL;
        struct chart_row r = {.kind = CHART_GLYPHS, .glyphs = gl};
        struct render_opts o = g->base;
        for (int a = 0; a < CHART_AXES; a++)
            r.value[a] = axis_get(&o, a);
        struct err too_big;
        if (ssaa_check(SSAA_8, cell_fb_w(&geom, cols), cell_fb_h(&geom, rows), &too_big))
            continue; /* no ideal image at that grid: no row (a huge --size) */
        rc = -1;
        if (fb_init(&fb, cell_fb_w(&geom, cols), cell_fb_h(&geom, rows), false, e) ||
            encode_screen_init(&es, cols, rows, e) || decode_init(&d, cols, rows, geom, e))
            goto next;
        fb.pixel_aspect = cell_pixel_aspect(&geom);
        const size_t n = (size_t)fb.w * fb.h * 3;
        if (!(ideal = malloc(n))) {
            err_set(e, "out of memory");
            goto next;
        }
        struct render_opts io = o;
        render_opts_ideal(&io);
        struct frame_stats st;
        if (ssaa_draw(&ss[io.ssaa], x->p, s->items, s->n_items, sky, &g->cam, &io, &fb, &st, e))
            goto next;
        memcpy(ideal, fb.rgb, n);
        struct encode_opts eo = {.mode = PALETTE_TRUECOLOR, .glyphs = geom.glyphs};
        size_t len = 0;
        const char *bytes = NULL;
        for (int k = 0; k < reps; k++) {
            double t0 = timing_now_ms();
            if (ssaa_draw(&ss[o.ssaa], x->p, s->items, s->n_items, sky, &g->cam, &o, &fb, &st, e))
                goto next;
            double t1 = timing_now_ms();
            encode_screen_invalidate(&es);
            bytes = encode_fb(&es, &fb, &eo, &len, NULL);
            ren[k] = t1 - t0, enc[k] = timing_now_ms() - t1;
        }
        if (decode_frame(&d, bytes, len, 0, e))
            goto next;
        struct chart_row *out = push_row(x, g, &r, e);
        if (!out)
            goto next;
        compare(d.rgb, ideal, (size_t)fb.w * fb.h, &out->psnr_db, &out->frac_gt8);
        out->bytes = len;
        out->ms = out->pilot_ms = timing_median(ren, reps);
        out->encode_ms = timing_median(enc, reps);
        rc = 0;
next:
        for (int k = 0; k < SSAA_COUNT; k++)
            ssaa_free(&ss[k]);
        encode_screen_free(&es);
        decode_free(&d);
        fb_free(&fb);
        free(ideal);
    }
    free(enc);
    free(ren);
    return rc;
}

/* geometric mean over the scenes of `size`'s groups of rows with these methods */
struct agg {
    double ms, mse, frac;
    int n;
};

static bool same_values(const int a[CHART_AXES], const int b[CHART_AXES])
{
    return memcmp(a, b, CHART_AXES * sizeof *a) == 0;
}

static struct agg aggregate(const struct chart *c, int w, int h, const int values[CHART_AXES],
                            bool pilot)
{
    struct agg g = {0, 0, 0, 0};
    double log_ms = 0;
    for (int i = 0; i < c->n_rows; i++) {
        const struct chart_row *r = &c->rows[i];
        if (r->w != w || r->h != h || r->kind == CHART_GLYPHS || !same_values(r->value, values))
            continue;
        double ms = pilot ? r->pilot_ms : r->ms;
        log_ms += log(ms > 1e-6 ? ms : 1e-6);
        g.mse += psnr_mse(r->psnr_db);
        g.frac += r->frac_gt8;
        g.n++;
        /* a scene's rows are unique by methods: the next match is another scene */
    }
    if (g.n) {
        g.ms = exp(log_ms / g.n);
        g.mse /= g.n;
        g.frac /= g.n;
    }
    return g;
}

/* Per axis, from the default: the fastest value (pilot medians, geometric mean over the
 * scenes), and the most accurate (pooled PSNR, then fewer pixels off by more than 8). A value
 * other than the default needs a clear margin — 5% faster, 0.1 dB more accurate — so that
 * noise and identical pictures keep the default. */
#define CHART_FASTER 0.95
#define CHART_BETTER_DB 0.1

static void choose_combos(const struct chart *c, int w, int h, int fast[CHART_AXES],
                          int best[CHART_AXES])
{
    struct render_opts d;
    render_opts_default(&d);
    int def[CHART_AXES];
    for (int a = 0; a < CHART_AXES; a++)
        def[a] = axis_get(&d, a);
    struct agg g0 = aggregate(c, w, h, def, true);
    double db0 = psnr_db(g0.mse);
    for (int a = 0; a < CHART_AXES; a++) {
        double fast_ms = g0.ms * CHART_FASTER, best_db = db0 + CHART_BETTER_DB;
        double best_frac = g0.frac;
        fast[a] = best[a] = def[a];
        for (int v = 0; v < chart_axes[a].values->n; v++) {
            int vals[CHART_AXES];
            memcpy(vals, def, sizeof vals);
            vals[a] = v;
            struct agg g = aggregate(c, w, h, vals, true);
            if (!g.n || v == def[a])
                continue;
            double db = psnr_db(g.mse);
            if (g.ms < fast_ms)
                fast_ms = g.ms, fast[a] = v;
            if (chart_axes[a].ideal_is_default)
                continue;
            if (db > best_db || (db == best_db && isinf(db) && g.frac < best_frac))
                best_db = db, best_frac = g.frac, best[a] = v;
        }
    }
}

static int add_combo(struct run *x, struct group *g, enum chart_kind kind,
                     const int values[CHART_AXES], struct err *e)
{
    for (int i = 0; i < g->n_rows; i++)
        if (same_values(x->out->rows[g->rows[i]].value, values)) {
            x->out->rows[g->rows[i]].also |= 1u << kind; /* already a row: say so there */
            return 0;
        }
    struct chart_row r = {.kind = kind};
    memcpy(r.value, values, sizeof r.value);
    return add_row(x, g, &r, e);
}

static void progress(const struct chart_config *c, const char *what, const struct group *g)
{
    if (c->progress) {
        fprintf(c->progress, "chart: %s %s %dx%d (%d rows)\n", what, g->sc->def->name, g->w,
                g->h, g->n_rows);
        fflush(c->progress);
    }
}

int chart_run(const struct chart_config *c, struct chart *out, struct err *e)
{
    memset(out, 0, sizeof *out);
    struct loaded ls[N_SCENE_DEFS];
    memset(ls, 0, sizeof ls);
    int n_sc = 0, rc = -1;
    struct run x = {c, out, 0, pipeline_new()};
    struct group *gs = calloc((size_t)N_SCENE_DEFS, sizeof *gs);
    if (!x.p || !gs) {
        err_set(e, "out of memory");
        goto done;
    }
    if (load_scenes(c, ls, &n_sc, out, e))
        goto done;
    int glyph_scene = 0; /* the head, else the first scene */
    for (int i = 0; i < n_sc; i++)
        if (strcmp(ls[i].def->name, "head") == 0)
            glyph_scene = i;
    for (int si = 0; si < c->n_sizes; si++) {
        int w = c->sizes[si][0], h = c->sizes[si][1];
        if (ssaa_check(SSAA_8, w, h, e)) /* the ideal image needs --ssaa 8 */
            goto done;
        for (int i = 0; i < n_sc; i++) {
            group_setup(&gs[i], &ls[i], w, h);
            if (add_base_rows(&x, &gs[i], e))
                goto done;
            progress(c, "pilot", &gs[i]);
            if (run_group(&x, &gs[i], CHART_PILOT, e))
                goto done;
            for (int k = 0; k < gs[i].n_rows; k++)
                out->rows[gs[i].rows[k]].pilot_ms =
                    timing_median(gs[i].times + k * (CHART_PILOT - 1), CHART_PILOT - 1);
        }
        int fast[CHART_AXES], best[CHART_AXES];
        choose_combos(out, w, h, fast, best);
        for (int i = 0; i < n_sc; i++) {
            if (add_combo(&x, &gs[i], CHART_FASTEST, fast, e) ||
                add_combo(&x, &gs[i], CHART_ACCURATE, best, e))
                goto done;
            progress(c, "timing", &gs[i]);
            if (run_group(&x, &gs[i], 1 + c->repeat, e))
                goto done;
            for (int k = 0; k < gs[i].n_rows; k++)
                out->rows[gs[i].rows[k]].ms =
                    timing_median(gs[i].times + (size_t)k * c->repeat, c->repeat);
            if (measure_shimmer(&x, &gs[i], e))
                goto done;
            if (si == 0 && i == glyph_scene) {
                progress(c, "glyphs", &gs[i]);
                if (measure_glyphs(&x, &gs[i], e))
                    goto done;
            }
            free(gs[i].ideal);
            free(gs[i].times);
            gs[i].ideal = NULL;
            gs[i].times = NULL;
        }
    }
    rc = 0;
done:
    if (gs)
        for (int i = 0; i < N_SCENE_DEFS; i++) {
            free(gs[i].ideal);
            free(gs[i].times);
        }
    free(gs);
    for (int i = 0; i < n_sc; i++) {
        scene_free(ls[i].s);
        free(ls[i].s);
    }
    pipeline_destroy(x.p);
    if (rc)
        chart_free(out);
    return rc;
}

void chart_free(struct chart *c)
{
    free(c->rows);
    c->rows = NULL;
    c->n_rows = 0;
}

void chart_row_label(const struct chart_row *r, char *out, size_t n)
{
    if (r->also) {
        struct chart_row plain = *r;
        plain.also = 0;
        char base[48];
        chart_row_label(&plain, base, sizeof base);
        snprintf(out, n, "%s = %s%s", base,
                 r->also & (1u << CHART_FASTEST) ? "fastest" : "most accurate",
                 r->also == ((1u << CHART_FASTEST) | (1u << CHART_ACCURATE)) ? ", most accurate"
                                                                             : "");
        return;
    }
    if (r->kind == CHART_GLYPHS) {
        snprintf(out, n, "glyphs %s", cell_glyphs_name((enum cell_glyphs)r->glyphs));
    } else if (r->kind == CHART_DEFAULT) {
        snprintf(out, n, "default");
    } else if (r->kind == CHART_FASTEST) {
        snprintf(out, n, "fastest");
    } else if (r->kind == CHART_ACCURATE) {
        snprintf(out, n, "most accurate");
    } else {
        const char *v = chart_axes[r->axis].values->names[r->value[r->axis]];
        if (strlen(v) <= 4) /* "w", "z16", "4", "auto": say which axis */
            snprintf(out, n, "%s %s", chart_axes[r->axis].name, v);
        else
            snprintf(out, n, "%s", v);
    }
}

static void write_psnr(FILE *f, double v)
{
    if (isinf(v))
        fputs("inf", f);
    else
        fprintf(f, "%.2f", v);
}

int chart_write_csv(const struct chart *c, FILE *f)
{
    fputs("scene,size", f);
    for (int a = 0; a < CHART_CSV_AXES; a++)
        fprintf(f, ",%s", chart_axes[a].name);
    fputs(",ms,psnr_db,frac_gt8,bytes", f);
    for (int a = CHART_CSV_AXES; a < CHART_AXES; a++)
        fprintf(f, ",%s", chart_axes[a].name);
    fputs(",shimmer,glyphs,encode_ms\n", f);
    for (int i = 0; i < c->n_rows; i++) {
        const struct chart_row *r = &c->rows[i];
        fprintf(f, "%s,%dx%d", r->scene, r->w, r->h);
        for (int a = 0; a < CHART_CSV_AXES; a++)
            fprintf(f, ",%s", chart_axes[a].values->names[r->value[a]]);
        fprintf(f, ",%.4f,", r->ms);
        write_psnr(f, r->psnr_db);
        fprintf(f, ",%.6f,%zu", r->frac_gt8, r->bytes);
        for (int a = CHART_CSV_AXES; a < CHART_AXES; a++)
            fprintf(f, ",%s", chart_axes[a].values->names[r->value[a]]);
        if (isnan(r->shimmer))
            fputs(",", f);
        else
            fprintf(f, ",%.3f", r->shimmer);
        fprintf(f, ",%s", cell_glyphs_name((enum cell_glyphs)r->glyphs));
        if (isnan(r->encode_ms))
            fputs(",\n", f);
        else
            fprintf(f, ",%.4f\n", r->encode_ms);
    }
    return ferror(f) ? -1 : 0;
}

void chart_write_table(const struct chart *c, FILE *f)
{
    fprintf(f, "%-7s %-8s", "scene", "size");
    for (int a = 0; a < CHART_AXES; a++)
        fprintf(f, " %-8s", chart_axes[a].name);
    fprintf(f, " %9s %8s %8s %8s %8s %8s  %s\n", "ms/frame", "PSNR dB", ">8 px %", "KB",
            "shimmer", "enc ms", "method");
    for (int i = 0; i < c->n_rows; i++) {
        const struct chart_row *r = &c->rows[i];
        char size[16], label[48];
        snprintf(size, sizeof size, "%dx%d", r->w, r->h);
        chart_row_label(r, label, sizeof label);
        fprintf(f, "%-7s %-8s", r->scene, size);
        for (int a = 0; a < CHART_AXES; a++)
            fprintf(f, " %-8s", chart_axes[a].values->names[r->value[a]]);
        fprintf(f, " %9.3f", r->ms);
        if (isinf(r->psnr_db))
            fprintf(f, " %8s", "ideal");
        else
            fprintf(f, " %8.2f", r->psnr_db);
        fprintf(f, " %8.3f %8.1f", 100 * r->frac_gt8, r->bytes / 1024.0);
        if (isnan(r->shimmer))
            fprintf(f, " %8s", "-");
        else
            fprintf(f, " %8.3f", r->shimmer);
        if (isnan(r->encode_ms))
            fprintf(f, " %8s  %s\n", "-", label);
        else
            fprintf(f, " %8.3f  %s\n", r->encode_ms, label);
    }
}

/* ---- the picture ---- */

struct point {
    double ms, psnr; /* psnr INFINITY: identical to the ideal */
    const struct chart_row *row;
    bool front;
};

static uint32_t row_color(const struct chart_row *r, bool svg)
{
    static const uint32_t axis_col[CHART_AXES] = {0x1f77b4, 0xff7f0e, 0x2ca02c, 0x9467bd,
                                                  0xd62728, 0x8c564b};
    if (r->kind == CHART_DEFAULT)
        return svg ? 0x000000 : 0xffffff;
    if (r->kind == CHART_FASTEST)
        return 0x17becf;
    if (r->kind == CHART_ACCURATE)
        return 0xbcbd22;
    return axis_col[r->axis % CHART_AXES];
}

static enum plot_shape row_shape(const struct chart_row *r)
{
    if (r->kind != CHART_VARIED)
        return PLOT_DIAMOND;
    static const enum plot_shape s[4] = {PLOT_SQUARE, PLOT_CIRCLE, PLOT_TRIANGLE, PLOT_SQUARE};
    return s[r->axis % 4];
}

static void draw_panel(const struct chart *c, struct plot *p, int w, int h, double x0,
                       double y0, double pw, double ph)
{
    struct point pts[CHART_MAX_ROWS];
    int n = 0;
    int n_scenes = 0;
    char scenes[128] = "";
    for (int i = 0; i < c->n_rows && n < CHART_MAX_ROWS; i++) {
        const struct chart_row *r = &c->rows[i];
        if (r->w != w || r->h != h || r->kind == CHART_GLYPHS) /* not a rendering method */
            continue;
        if (!strstr(scenes, r->scene)) {
            size_t len = strlen(scenes);
            snprintf(scenes + len, sizeof scenes - len, "%s%s", len ? ", " : "", r->scene);
            n_scenes++;
        }
        bool seen = false;
        for (int k = 0; k < n && !seen; k++)
            seen = same_values(pts[k].row->value, r->value);
        if (seen)
            continue;
        struct agg g = aggregate(c, w, h, r->value, false);
        pts[n].ms = g.ms;
        pts[n].psnr = psnr_db(g.mse);
        pts[n].row = r;
        n++;
    }
    if (!n)
        return;
    /* the Pareto front: no other point both faster (or as fast) and more accurate */
    for (int i = 0; i < n; i++) {
        pts[i].front = true;
        for (int k = 0; k < n && pts[i].front; k++)
            if (k != i && pts[k].ms <= pts[i].ms && pts[k].psnr >= pts[i].psnr &&
                (pts[k].ms < pts[i].ms || pts[k].psnr > pts[i].psnr))
                pts[i].front = false;
    }
    double ms_lo = INFINITY, ms_hi = 0, db_lo = INFINITY, db_hi = -INFINITY;
    bool any_inf = false;
    for (int i = 0; i < n; i++) {
        ms_lo = fmin(ms_lo, pts[i].ms), ms_hi = fmax(ms_hi, pts[i].ms);
        if (isinf(pts[i].psnr))
            any_inf = true;
        else
            db_lo = fmin(db_lo, pts[i].psnr), db_hi = fmax(db_hi, pts[i].psnr);
    }
    if (!isfinite(db_lo))
        db_lo = 30, db_hi = 40;
    db_lo = 5 * floor(db_lo / 5 - 0.2);
    double top = 5 * ceil(db_hi / 5 + 0.2) + (any_inf ? 5 : 0);
    struct plot_axis ax = {ms_lo / 1.6, ms_hi * 1.6, true, x0, x0 + pw};
    struct plot_axis ay = {db_lo, top, false, y0 + ph, y0};
    char title[160];
    snprintf(title, sizeof title, "%dx%d: %s", w, h, scenes);
    plot_axes(p, &ax, &ay, "ms per frame (log; geometric mean over the scenes)",
              "PSNR against the ideal image, dB (up = more accurate)", title);
    double inf_y = plot_map(&ay, top);
    if (any_inf)
        plot_text(p, x0 + pw - p->char_w, inf_y + p->char_h * 0.6, "= the ideal", 0x808080,
                  PLOT_RIGHT, 0.9, false);
    /* the front, joined in order of speed */
    int order[CHART_MAX_ROWS], nf = 0;
    for (int i = 0; i < n; i++)
        if (pts[i].front)
            order[nf++] = i;
    for (int i = 1; i < nf; i++)
        for (int k = i; k > 0 && pts[order[k]].ms < pts[order[k - 1]].ms; k--) {
            int t = order[k];
            order[k] = order[k - 1];
            order[k - 1] = t;
        }
    const uint32_t front_col = p->svg ? 0xd62728 : 0xff5050;
    for (int i = 1; i < nf; i++) {
        const struct point *a = &pts[order[i - 1]], *b = &pts[order[i]];
        double ya = isinf(a->psnr) ? inf_y : plot_map(&ay, a->psnr);
        double yb = isinf(b->psnr) ? inf_y : plot_map(&ay, b->psnr);
        plot_line(p, plot_map(&ax, a->ms), ya, plot_map(&ax, b->ms), yb, front_col,
                  p->svg ? 2.5 : 1, false);
    }
    double r = p->svg ? 5 : 1;
    struct plot_clear clear = {.area = {x0, y0, x0 + pw, y0 + ph}};
    for (int i = 0; i < n; i++) { /* markers first: labels avoid them */
        double px = plot_map(&ax, pts[i].ms);
        double py = isinf(pts[i].psnr) ? inf_y : plot_map(&ay, pts[i].psnr);
        plot_marker(p, px, py, row_shape(pts[i].row), r, row_color(pts[i].row, p->svg != NULL));
        plot_keep_clear(&clear, px, py, r);
    }
    /* Labels: methods that land on the same spot (the same picture within 0.05 dB, times
     * within 25%: the rasterizers, w and rz draw the default's bytes) share one label, which
     * is bold when one of them is on the front; the front's labels are placed first. */
    int group[CHART_MAX_ROWS];
    for (int i = 0; i < n; i++) {
        group[i] = i;
        for (int k = 0; k < i && group[i] == i; k++) {
            const struct point *a = &pts[group[k]], *b = &pts[i];
            bool same_db = (isinf(a->psnr) && isinf(b->psnr)) || fabs(a->psnr - b->psnr) < 0.05;
            if (group[k] == k && same_db && b->ms < a->ms * 1.25 && b->ms > a->ms / 1.25)
                group[i] = k;
        }
    }
    for (int pass = 0; pass < 2; pass++)
        for (int i = 0; i < n; i++) {
            if (group[i] != i)
                continue;
            bool front = false;
            char label[160] = "";
            for (int k = i; k < n; k++) {
                if (group[k] != i)
                    continue;
                front |= pts[k].front;
                char one[48];
                chart_row_label(pts[k].row, one, sizeof one);
                size_t len = strlen(label);
                snprintf(label + len, sizeof label - len, "%s%s", len ? ", " : "", one);
            }
            if (front != (pass == 0))
                continue;
            double px = plot_map(&ax, pts[i].ms);
            double py = isinf(pts[i].psnr) ? inf_y : plot_map(&ay, pts[i].psnr);
            uint32_t col = front ? (p->svg ? 0x000000 : 0xffffff) : 0x808080;
            plot_text_clear(p, &clear, px, py, r, label, col, 1, front, !front);
        }
}

void chart_draw(const struct chart *c, struct plot *p)
{
    int sizes[8][2], n_sizes = 0;
    for (int i = 0; i < c->n_rows && n_sizes < 8; i++) {
        bool seen = false;
        for (int k = 0; k < n_sizes; k++)
            seen |= sizes[k][0] == c->rows[i].w && sizes[k][1] == c->rows[i].h;
        if (!seen)
            sizes[n_sizes][0] = c->rows[i].w, sizes[n_sizes++][1] = c->rows[i].h;
    }
    if (!n_sizes)
        return;
    double cw = p->char_w, ch = p->char_h;
    double left = 7 * cw, right = 2 * cw, top = 4.5 * ch, bottom = 5.5 * ch, gap = 9 * cw;
    double pw = (p->w - left - right - gap * (n_sizes - 1)) / n_sizes;
    double ph = p->h - top - bottom;
    for (int s = 0; s < n_sizes; s++)
        draw_panel(c, p, sizes[s][0], sizes[s][1], left + s * (pw + gap), top, pw, ph);
    /* legend: colour and shape per axis */
    double lx = left, ly = p->h - 1.2 * ch;
    struct chart_row key = {.kind = CHART_DEFAULT};
    const char *names[CHART_AXES + 3];
    struct chart_row keys[CHART_AXES + 3];
    int nk = 0;
    keys[nk] = key, names[nk++] = "default";
    for (int a = 0; a < CHART_AXES; a++) {
        keys[nk] = (struct chart_row){.kind = CHART_VARIED, .axis = a};
        names[nk++] = chart_axes[a].name;
    }
    keys[nk] = (struct chart_row){.kind = CHART_FASTEST}, names[nk++] = "fastest combination";
    keys[nk] = (struct chart_row){.kind = CHART_ACCURATE}, names[nk++] = "most accurate";
    uint32_t ink = p->svg ? 0x303030 : 0xc0c0c0;
    plot_text(p, lx, ly, "varied:", ink, PLOT_LEFT, 1, false);
    lx += 8 * cw;
    for (int k = 0; k < nk; k++) {
        plot_marker(p, lx, ly, row_shape(&keys[k]), p->svg ? 5 : 0.5,
                    row_color(&keys[k], p->svg != NULL));
        plot_text(p, lx + 1.5 * cw, ly, names[k], ink, PLOT_LEFT, 1, false);
        lx += (strlen(names[k]) + 4) * cw;
    }
    plot_line(p, lx, ly, lx + 3 * cw, ly, p->svg ? 0xd62728 : 0xff5050, p->svg ? 2.5 : 1, false);
    plot_text(p, lx + 4 * cw, ly, "Pareto front (bold labels)", ink, PLOT_LEFT, 1, false);
}
