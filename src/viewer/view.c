/* view.c: the interactive viewer's loop (see view.h): terminal events in, frames out.
 *
 * One turn of the loop: wait for input (or the next frame's time), turn each event into a
 * view_state call (view_state.c) and act on what it returns, advance held keys and the
 * spin, and draw a frame when the picture changed and the pacing (pace.c) lets one go out.
 * Everything that touches the terminal, the scenes or the renderer is here; the model and
 * the status line's text are pure and tested without a terminal. */
#include "view.h"

#include <errno.h>
#include <math.h>
#include <pthread.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "prepare.h"
#include "encode.h"
#include "image.h"
#include "input.h"
#include "pace.h"
#include "pipeline.h"
#include "sandbox.h"
#include "scene.h"
#include "ssaa.h"
#include "termcaps.h"
#include "timing.h"
#include "tty.h"
#include "view_frames.h"
#include "view_hud.h"
#include "view_shot.h"
#include "view_state.h"

#ifndef RASTTY_DATADIR
#define RASTTY_DATADIR "/usr/local/share/rastty"
#endif

#define VIEW_MAX_SCENES OPTIONS_MAX_INPUTS
#define HUD_PERIOD_S 0.5 /* while animating, refresh the status line at most this often */
#define DRAIN_S 1.0      /* Ctrl-Z: wait this long (+ the transfer) for the answer in flight */
#define MAX_SHOTS 16
#define FPS_GAP_S 0.5    /* frames further apart than this are not counted in the frame rate */
#define LINK_SPIN_S 0.25 /* the demo's own spin pauses when a whole frame of it takes the link
                          * longer than this (fewer than 4 frames a second: view_frames.h) */

struct view {
    const struct options *o;
    struct scene *scenes[VIEW_MAX_SCENES];
    const char *paths[VIEW_MAX_SCENES];
    char texture[VIEW_MAX_SCENES][64]; /* for the status line: file used, "MTL" or "" */
    int n_scenes, cur;
    struct view_state s;
    /* output */
    struct tty tty;
    struct fb fb;
    struct encode_screen es;
    struct encode_opts eo;
    enum palette_mode mode; /* the terminal's colour mode (the pacing may draw in 256) */
    struct pace pace;
    struct view_frames vf;  /* the decoded screen: the quality floor, RASTTY_FRAME_LOG */
    bool link_paused;       /* the link paused the demo's spin once (Space spins it again) */
    size_t last_bytes;      /* the last frame's bytes, and the camera it was drawn with */
    struct camera last_cam;
    bool cam_drawn;
    struct pipeline *pipe;
    struct ssaa ssaa;       /* --ssaa's big framebuffer */
    struct skybox default_sky;
    /* the default sky made ahead, while the models load (sky_guess_start) */
    struct {
        pthread_t thread;
        bool running, joined;
        vec3 sun;
        struct skybox sky;
        int rc;
    } guess;
    int fb_cols, fb_rows;   /* cells used by the picture */
    enum cell_glyphs glyphs; /* the glyph set fb was sized for */
    bool help_drawn;        /* the help overlay is on the screen */
    bool drawn;             /* fb holds a frame (for screenshots) */
    bool lod_pending;       /* the scene's levels of detail are still being built */
    bool lod_started;       /* every scene's build has been started (start_levels) */
    bool written;           /* a frame has been written: the level builds may start */
    /* stats for the status line */
    struct frame_stats st;
    struct encode_stats est;
    double encode_ms, fps, last_frame_at, next_hud_at;
    unsigned long frames;   /* frames written in full: the status line's "#N" (view_hud.h) */
    double cell_r;          /* a cell's height / width (--cell-aspect, or the terminal's) */
    char hud_text[512];
    /* everything for one update (status line, overlay, frame, DSR) goes out in one write */
    char *out;
    size_t out_len, out_cap;
    char shots[MAX_SHOTS][VIEW_SHOT_MAX];
    int n_shots;
    int camera_k[VIEW_MAX_SCENES]; /* the C key's choice: the file's camera k, 0 rastty's
                                      framing, -1 as the command line says */
};

static int ms(double s)
{
    return s > 0 ? (int)(s * 1e3) + 1 : 0;
}

/* Append to the pending output; grows rarely (the frame bound is reserved on resize). */
static void out_add(struct view *v, const char *bytes, size_t n)
{
    if (v->out_len + n > v->out_cap) {
        size_t cap = (v->out_len + n) * 2;
        char *nb = realloc(v->out, cap);
        if (!nb)
            return; /* drop this piece; the next full frame repairs the screen */
        v->out = nb;
        v->out_cap = cap;
    }
    memcpy(v->out + v->out_len, bytes, n);
    v->out_len += n;
}

static int out_flush(struct view *v)
{
    int rc = v->out_len ? tty_write(v->out, v->out_len) : 0;
    v->out_len = 0;
    return rc;
}

/* ---- scenes ---- */

/* Does the viewer draw its procedural sky behind this scene? When the scene sets neither a
 * sky nor a background, and no --background was given (render and dump keep black). */
static bool default_sky_used(const struct view *v)
{
    const struct scene *s = v->scenes[v->cur];
    return !s->has_sky && !s->has_background && !v->o->background_set;
}

/* The default sky takes 0.1-0.15 s of CPU (skybox_procedural: 1.6M samples): made on a
 * thread of its own while the models load, toward the command line's first light (the sun
 * a model without lights of its own gets), it is ready for the first frame. A scene that
 * turns out to want another sun (its own lights) or none (its own sky or background) drops
 * it: the same bytes either way. */
static void *sky_guess_main(void *arg)
{
    struct view *v = arg;
    struct err ignored;
    v->guess.rc = skybox_procedural(&v->guess.sky, v->guess.sun, &ignored);
    return NULL;
}

/* The guess's thread ended (its sky kept for sky_guess_take). */
static void sky_guess_join(void *arg)
{
    struct view *v = arg;
    if (v->guess.running && !v->guess.joined)
        pthread_join(v->guess.thread, NULL);
    v->guess.joined = true;
}

static void sky_guess_start(struct view *v)
{
    if (v->o->background_set)
        return; /* no default sky anywhere */
    v->guess.sun = v->o->render.lights[0].dir;
    /* no signals on it (nor on the pool it starts): they are the terminal loop's */
    sigset_t all, old;
    sigfillset(&all);
    pthread_sigmask(SIG_SETMASK, &all, &old);
    v->guess.running = pthread_create(&v->guess.thread, NULL, sky_guess_main, v) == 0;
    pthread_sigmask(SIG_SETMASK, &old, NULL);
    if (v->guess.running) /* an importer's fork waits for it to end (sandbox.h) */
        sandbox_before_fork(sky_guess_join, v);
}

/* The guess, once finished: into v->default_sky when its sun is sun, else dropped. */
static void sky_guess_take(struct view *v, vec3 sun)
{
    if (!v->guess.running)
        return;
    sandbox_before_fork(NULL, NULL);
    sky_guess_join(v);
    v->guess.running = false;
    if (v->guess.rc == 0 && v->default_sky.n_levels == 0 && v->guess.sun.x == sun.x &&
        v->guess.sun.y == sun.y && v->guess.sun.z == sun.z) {
        v->default_sky = v->guess.sky;
        memset(&v->guess.sky, 0, sizeof v->guess.sky);
    } else if (v->guess.rc == 0) {
        skybox_free(&v->guess.sky);
    }
}

/* The sky for the current scene; the default one has its sun toward the first world light. */
static const struct skybox *scene_sky(struct view *v)
{
    const struct scene *s = v->scenes[v->cur];
    if (s->has_sky)
        return &s->sky;
    if (!default_sky_used(v))
        return NULL;
    if (v->default_sky.n_levels == 0)
        sky_guess_take(v, v->s.ro.lights[0].dir);
    if (v->default_sky.n_levels == 0) {
        struct err ignored;
        if (skybox_procedural(&v->default_sky, v->s.ro.lights[0].dir, &ignored))
            return NULL;
    }
    return &v->default_sky;
}

/* camera, lights and background for the current scene; the camera becomes "home" */
static void enter_scene(struct view *v)
{
    const struct scene *s = v->scenes[v->cur];
    double aspect = v->fb.w > 0 ? fb_aspect(&v->fb) : 2.0;
    struct camera cam;
    struct render_opts ro;
    /* a model alone is framed, unless the command line placed the camera (or the C key
     * chose a camera of the file, or rastty's framing) */
    prepare_camera(v->o, s, aspect, !v->o->camera_set, &cam, &ro);
    int k = v->camera_k[v->cur];
    if (k > 0)
        prepare_file_camera(s, k, &cam);
    else if (k == 0)
        camera_frame_box(&cam, s->bound_lo, s->bound_hi, aspect);
    view_state_scene(&v->s, &cam, &ro, v3_len(v3_sub(s->bound_hi, s->bound_lo)));
    v->lod_pending = v->lod_started && !scene_lod_done(s);
    skybox_free(&v->default_sky); /* its sun follows the scene's first light */
    /* the load's warnings went to stderr, which the alternate screen hides until the exit:
     * say the first on the status line (all of them are on the screen after q) */
    if (s->warnings.n > 0) {
        char msg[sizeof v->s.message];
        int more = s->warnings.n - 1 + s->warnings.dropped;
        char tail[48] = "";
        if (more > 0)
            snprintf(tail, sizeof tail, " (+%d more)", more);
        snprintf(msg, sizeof msg, "warning: %.*s%s", (int)(sizeof msg - 10 - strlen(tail)),
                 s->warnings.msg[0], tail);
        view_message(&v->s, msg, timing_now_s());
    }
}

/* ---- output ---- */

static int resize(struct view *v, struct err *e)
{
    tty_refresh_size(&v->tty);
    int rows = v->tty.rows - 1; /* the status line */
    if (v->s.hud_hidden)
        rows = v->tty.rows;
    int cols = v->tty.cols;
    cols = cols > ENCODE_MAX_COLS ? ENCODE_MAX_COLS : cols;
    rows = rows > ENCODE_MAX_ROWS ? ENCODE_MAX_ROWS : rows;
    if (cols < 1 || rows < 1) {
        v->fb_cols = v->fb_rows = 0;
        v->glyphs = v->s.glyphs;
        return 0;
    }
    struct cell_geom g = cell_geom(v->s.glyphs);
    if (cols != v->fb_cols || rows != v->fb_rows || g.glyphs != v->glyphs) {
        fb_free(&v->fb);
        encode_screen_free(&v->es);
        v->drawn = false;
        if (fb_init(&v->fb, cell_fb_w(&g, cols), cell_fb_h(&g, rows), true, e) ||
            encode_screen_init(&v->es, cols, rows, e))
            return -1;
        v->fb.pixel_aspect = cell_pixel_aspect_r(&g, v->cell_r);
        v->fb_cols = cols;
        v->fb_rows = rows;
        v->s.rows = rows; /* a pan drag: the model follows the mouse */
        v->s.cell_w = 1 / v->cell_r;
        v->glyphs = g.glyphs;
        v->eo.glyphs = g.glyphs;
    }
    encode_screen_invalidate(&v->es);
    view_frames_resize(&v->vf, cols, rows, g);
    out_add(v, "\033[0m\033[2J", 8);
    v->help_drawn = false;
    v->s.dirty = v->s.hud_dirty = true;
    return 0;
}

/* Are levels of detail still to come for the current scene: being built, or to be built
 * after the first frame (a mode that draws them, the build not started yet)? The status line
 * says so ("lod auto..."). */
static bool lod_coming(const struct view *v)
{
    return v->lod_pending || (!v->lod_started && v->s.ro.lod != LOD_OFF);
}

/* The frame log's word for it (view_frames.h): none, pending, building or ready. */
static const char *lod_state(const struct view *v)
{
    if (!v->lod_started)
        return v->s.ro.lod != LOD_OFF ? "pending" : "none";
    return v->lod_pending ? "building" : "ready";
}

/* Start building every scene's levels of detail on background threads (scene_build_lod),
 * once: after the first frame has been written, so the build does not share the cores with
 * it, and under --lod off only when L first asks for levels. A build that cannot start
 * (out of memory) leaves the meshes drawn in full, and says so. */
static void start_levels(struct view *v, double t)
{
    if (v->lod_started || !v->written || v->s.ro.lod == LOD_OFF)
        return;
    v->lod_started = true;
    for (int i = 0; i < v->n_scenes; i++) {
        struct err e = {""};
        if (scene_build_lod(v->scenes[i], false, v->o->render.lod == LOD_CLUSTERS, &e)) {
            char msg[sizeof v->s.message];
            snprintf(msg, sizeof msg, "no levels of detail: %.*s", (int)sizeof msg - 24, e.msg);
            view_message(&v->s, msg, t);
        }
    }
    v->lod_pending = !scene_lod_done(v->scenes[v->cur]);
    v->s.hud_dirty = true;
    view_frames_note(&v->vf, "levels", 0, timing_now_s());
}

/* Does the picture stand still at t: the last frame written in full, nothing moving (a held
 * key, the spin), no levels of detail still to come? Then the status line shows "#N". */
static bool still(struct view *v, double t)
{
    return !v->s.dirty && !lod_coming(v) && !view_animating(&v->s, t);
}

static void hud_draw(struct view *v, double t)
{
    if (v->s.hud_hidden || v->tty.rows < 1) {
        v->s.hud_dirty = false; /* nothing to draw: or the loop never waits (100% CPU idle) */
        return;
    }
    char text[512], pos[32];
    struct view_hud_info in = {
        .scene = v->scenes[v->cur]->name, .scene_i = v->cur, .n_scenes = v->n_scenes,
        .texture = v->texture[v->cur][0] ? v->texture[v->cur] : NULL, .mode = v->eo.mode,
        .fps = v->fps, .render_ms = v->st.render_ms, .encode_ms = v->encode_ms,
        .bytes = v->est.bytes, .st = &v->st, .lod_building = lod_coming(v),
        .frames = still(v, t) ? v->frames : 0};
    char pacing[96];
    pace_describe(&v->pace, v->est.max_err, pacing, sizeof pacing);
    if (v->link_paused && v->s.spin && v->s.paused) { /* link_spin: said for as long as it lasts */
        size_t k = strlen(pacing);
        snprintf(pacing + k, sizeof pacing - k, "%sspin paused", k ? " " : "slow link: ");
    }
    in.pacing = pacing;
    view_hud_compose(&v->s, &in, v->tty.cols, t, text, sizeof text);
    if (!v->s.hud_dirty && strcmp(text, v->hud_text) == 0)
        return;
    snprintf(v->hud_text, sizeof v->hud_text, "%s", text);
    /* exactly cols-1 characters: padded so a longer old text is erased, and the last cell of
     * the last row is never written (some terminals scroll when it is) */
    int width = v->tty.cols - 1, len = (int)strlen(text);
    len = len > width ? width : len;
    int k = snprintf(pos, sizeof pos, "\033[%d;1H", v->tty.rows);
    out_add(v, pos, (size_t)k);
    out_add(v, v->eo.mode == PALETTE_NONE ? "\033[0m" : "\033[0;30;47m",
            v->eo.mode == PALETTE_NONE ? 4 : 10);
    out_add(v, text, (size_t)(len > 0 ? len : 0));
    static const char spaces[64] = "                                                                ";
    for (int pad = width - len; pad > 0; pad -= 64)
        out_add(v, spaces, (size_t)(pad < 64 ? pad : 64));
    out_add(v, "\033[0m", 4);
    v->s.hud_dirty = false;
}

/* The help box, drawn once when it opens (and after the screen was cleared); frames leave
 * its cells alone (encode_opts' hold) until it closes. */
static void help_draw(struct view *v)
{
    struct view_hud_rect r = view_hud_help_rect(v->fb_cols, v->fb_rows);
    const char *sgr = v->eo.mode == PALETTE_NONE ? "" : "\033[0;97;44m";
    for (int i = 0; i < r.rows; i++) {
        char pos[32], line[512];
        int k = snprintf(pos, sizeof pos, "\033[%d;%dH", r.row + i + 1, r.col + 1);
        view_hud_help_text(&r, i, line, sizeof line);
        out_add(v, pos, (size_t)k);
        out_add(v, sgr, strlen(sgr));
        out_add(v, line, (size_t)r.cols); /* clipped to the picture: never wraps */
    }
    out_add(v, "\033[0m", 4);
    v->help_drawn = true;
}

/* The demo's own spin (not --spin) over a link too slow to carry it whole: when the last
 * frame took the link longer than LINK_SPIN_S, pause it and say so, once (Space spins it
 * again, in fewer but whole frames). The motion since that frame was never shown: the camera
 * goes back to where that frame saw the scene, so what follows only finishes it. */
static void link_spin(struct view *v, double t)
{
    double rate = pace_rate(&v->pace);
    if (v->o->spin >= 0 || !v->vf.floor || v->link_paused || !v->s.spin || v->s.paused ||
        !v->cam_drawn || rate <= 0 || (double)v->last_bytes <= rate * LINK_SPIN_S)
        return;
    v->link_paused = true;
    v->s.paused = true;
    v->s.cam = v->last_cam;
    view_message(&v->s, "auto-rotation paused: the link is too slow for it (Space resumes)", t);
}

static int draw_frame(struct view *v, double t, struct err *e)
{
    if (v->fb_cols == 0) { /* no room for a picture (one row and a HUD): only the HUD */
        v->s.dirty = false;
        v->last_frame_at = t;
        v->frames++;
        v->written = true;
        hud_draw(v, t);
        return out_flush(v) ? err_set(e, "rastty: cannot write to the terminal") : 0;
    }
    link_spin(v, t);
    const struct scene *s = v->scenes[v->cur];
    struct render_opts ro;
    view_frame_opts(&v->s, &ro);
    if (ssaa_draw(&v->ssaa, v->pipe, s->items, s->n_items, scene_sky(v), &v->s.cam, &ro, &v->fb,
                  &v->st, e))
        return -1;
    v->drawn = true;
    v->eo.mode = pace_mode(&v->pace, v->mode);
    v->eo.budget = pace_budget(&v->pace);
    v->eo.diff = true;
    struct view_hud_rect help = view_hud_help_rect(v->fb_cols, v->fb_rows);
    v->eo.hold_col = help.col, v->eo.hold_row = help.row;
    v->eo.hold_cols = v->s.help ? help.cols : 0, v->eo.hold_rows = v->s.help ? help.rows : 0;
    double t0 = timing_now_s();
    size_t n;
    int tries;
    const char *bytes = view_frames_encode(&v->vf, &v->es, &v->fb, &v->eo, !v->s.help, &n,
                                           &v->est, &tries);
    v->encode_ms = (timing_now_s() - t0) * 1e3;
    /* the frame rate of motion: a frame after an idle pause (a key after a still picture)
     * says nothing about it, and would make the rate decay toward 0 while nothing moves */
    if (v->last_frame_at > 0 && t - v->last_frame_at < FPS_GAP_S) {
        double inst = 1.0 / (t - v->last_frame_at > 1e-4 ? t - v->last_frame_at : 1e-4);
        v->fps = v->fps > 0 ? 0.8 * v->fps + 0.2 * inst : inst;
    }
    v->last_frame_at = t;
    /* a still picture the budget left unfinished is refined by the next frames */
    v->s.dirty = v->est.cells_pending > 0;
    if (!v->s.dirty)
        v->frames++;
    /* While the picture moves, the status line goes first: what a key changed shows before
     * the frame has arrived. The frame that leaves the picture standing still has it after
     * the picture, with the frame count: "#N" on the screen means all of frame N is. */
    bool rest = still(v, t);
    if (!rest && (t >= v->next_hud_at || v->s.hud_dirty)) {
        if (v->s.hud_dirty)
            view_frames_note(&v->vf, "hud", 0, t);
        hud_draw(v, t);
        v->next_hud_at = t + HUD_PERIOD_S;
    }
    if (v->s.help && !v->help_drawn)
        help_draw(v);
    out_add(v, bytes, n);
    if (rest)
        hud_draw(v, t); /* the count changed: always drawn */
    if (v->out_len == 0)
        return 0;
    char req[TTY_SYNC_REQUEST_MAX];
    out_add(v, req, tty_sync_request(&v->tty, req, sizeof req));
    size_t total = v->out_len;
    /* the link's time starts with the write: drawing and encoding the frame are not the
     * link's (counted in, a heavy model measured a local terminal as a slow link) */
    double sent_at = timing_now_s();
    if (out_flush(v))
        return err_set(e, "rastty: cannot write to the terminal");
    pace_sent(&v->pace, sent_at, total, v->est.demand + (total - n), v->fb_cols * v->fb_rows);
    if (n > 0)
        view_frames_written(&v->vf, &v->fb, &v->eo, n, v->eo.budget, tries, v->est.full,
                            lod_state(v), sent_at);
    v->written = true;
    v->last_bytes = n;
    v->last_cam = v->s.cam;
    v->cam_drawn = true;
    return 0;
}

/* A bare query: measures the round trip before the first frame (and after Ctrl-Z). */
static void probe(struct view *v)
{
    char req[TTY_SYNC_REQUEST_MAX];
    size_t n = tty_sync_request(&v->tty, req, sizeof req);
    if (n > 0 && tty_write(req, n) == 0)
        pace_sent(&v->pace, timing_now_s(), n, 0, v->fb_cols * v->fb_rows);
}

/* ---- screenshots ---- */

static void screenshot(struct view *v, double t)
{
    if (!v->drawn || v->n_shots == MAX_SHOTS) {
        view_message(&v->s, v->drawn ? "too many screenshots" : "nothing drawn yet", t);
        return;
    }
    char png[32], ans[32];
    int k = 1;
    for (; k < 1000; k++) {
        snprintf(png, sizeof png, "rastty-%03d.png", k);
        snprintf(ans, sizeof ans, "rastty-%03d.ans", k);
        if (access(png, F_OK) != 0 && access(ans, F_OK) != 0)
            break;
    }
    struct err e = {""};
    struct encode_screen es;
    int rc = image_write_png(png, &v->fb, &e);
    if (rc == 0 && (rc = encode_screen_init(&es, v->fb_cols, v->fb_rows, &e)) == 0) {
        struct encode_opts eo = {.mode = v->eo.mode, .mark_frames = true, .lf_newline = true,
                                 .glyphs = v->eo.glyphs};
        size_t n;
        const char *bytes = encode_fb(&es, &v->fb, &eo, &n, NULL);
        FILE *f = fopen(ans, "wb");
        if (!f || fwrite(bytes, 1, n, f) != n || fclose(f) != 0) {
            if (f)
                fclose(f);
            rc = err_set(&e, "%s: cannot write: %s", ans, strerror(errno));
        }
        encode_screen_free(&es);
    }
    if (rc) {
        view_message(&v->s, e.msg, t);
        return;
    }
    struct view_shot_info in = {.model = v->paths[v->cur], .texture = v->o->texture,
                                .width = v->fb.w, .height = v->fb.h, .out = png,
                                .background_set = v->o->background_set,
                                .background = v->o->render.background,
                                .sky = default_sky_used(v)};
    const struct scene *sc = v->scenes[v->cur];
    if (sc->load.up != MODEL_UP_AUTO || sc->up != (sc->n_meshes ? (sc->meshes[0].file_up
                                                                       ? sc->meshes[0].file_up
                                                                       : 'y')
                                                                 : 'y'))
        in.up_axis = sc->up;
    view_shot_command(&v->s, &in, v->shots[v->n_shots++], VIEW_SHOT_MAX);
    char msg[128];
    snprintf(msg, sizeof msg, "saved %s and %s (the render command is printed at exit)", png, ans);
    view_message(&v->s, msg, t);
}

/* ---- the loop ---- */

static int act(struct view *v, enum view_action a, double t, bool *quit, struct err *e)
{
    switch (a) {
    case VIEW_QUIT: *quit = true; break;
    case VIEW_NEXT_SCENE:
    case VIEW_PREV_SCENE:
        v->cur = (v->cur + (a == VIEW_NEXT_SCENE ? 1 : v->n_scenes - 1)) % v->n_scenes;
        enter_scene(v);
        break;
    case VIEW_HELP_OPENED: v->help_drawn = false; break;
    case VIEW_HELP_CLOSED: { /* uncover the picture: those cells must be drawn again */
        struct view_hud_rect r = view_hud_help_rect(v->fb_cols, v->fb_rows);
        encode_screen_damage(&v->es, r.col, r.row, r.cols, r.rows);
        break;
    }
    case VIEW_SCREENSHOT: screenshot(v, t); break;
    case VIEW_NEXT_CAMERA: {
        const struct scene *sc = v->scenes[v->cur];
        int n = prepare_camera_count(sc), *k = &v->camera_k[v->cur];
        char msg[128];
        if (n == 0) {
            view_message(&v->s, "the model has no cameras of its own", t);
            break;
        }
        int cur = *k >= 0 ? *k : v->o->file_camera >= 0 ? v->o->file_camera : 1;
        *k = (cur + 1) % (n + 1);
        enter_scene(v);
        if (*k)
            snprintf(msg, sizeof msg, "the model's camera %d of %d %.40s (C: next)", *k, n,
                     sc->items[0].mesh->cameras[*k - 1].name);
        else
            snprintf(msg, sizeof msg, "rastty's framing (C: the model's cameras)");
        view_message(&v->s, msg, t);
        break;
    }
    case VIEW_TURN_UP: {
        char up = scene_turn_up(v->scenes[v->cur]);
        enter_scene(v);
        char msg[80];
        snprintf(msg, sizeof msg, "the model's %c axis up  (u: next)", up);
        view_message(&v->s, msg, t);
        break;
    }
    case VIEW_HUD_TOGGLED: /* the picture gains or gives back the last row */
        if (resize(v, e))
            return -1;
        if (!v->s.hud_hidden)
            view_message(&v->s, "status line on  (H: off)", t);
        break;
    case VIEW_NONE: break;
    }
    return 0;
}

/* Ctrl-Z and q: collect the answer to the frame in flight first, or it reaches the shell's
 * prompt after the stop or the exit ("^[[0n", and `fg` typed after it becomes `nfg`). A
 * quit signal does not wait: the terminal may be gone or stalled. */
static void drain_answers(struct view *v)
{
    double r = v->pace.rate > 0 ? v->pace.rate : PACE_SLOWEST_RATE;
    /* a round trip measured: a few of them, not a second (Ctrl-Z took 1.1 s, and keys typed
     * meanwhile, a `fg`, were dropped with the typeahead) */
    double grace = v->pace.rtt >= 0 && 0.1 + 4 * v->pace.rtt < DRAIN_S ? 0.1 + 4 * v->pace.rtt
                                                                        : DRAIN_S;
    double end = timing_now_s() + grace + (double)v->pace.sent_bytes / r;
    struct tty_event ev;
    while (v->pace.inflight && !tty_signalled()) {
        double t = timing_now_s();
        if (t >= end)
            break;
        if (tty_next_event(&v->tty, ms(end - t), &ev) == TTY_SYNC_REPLY)
            pace_answer(&v->pace, timing_now_s());
    }
}

static int loop(struct view *v, struct err *e)
{
    bool quit = false;
    double last = timing_now_s();
    if (!v->pace.answers)
        probe(v);
    while (!quit && !tty_signalled()) {
        double t = timing_now_s();
        pace_tick(&v->pace, t);
        /* the motion since the last turn first: a tap that ended meanwhile (the loop was late)
         * still has its last stretch to draw, or it would wait for the next input */
        view_advance(&v->s, last, t);
        last = t;
        bool want = v->s.dirty || view_animating(&v->s, t);
        double wait = 0;
        bool ready = pace_ready(&v->pace, t, &wait);
        int timeout = -1;
        if (want)
            timeout = ready ? 0 : ms(wait);
        if (v->s.message_until > t) {
            int m = ms(v->s.message_until - t);
            timeout = timeout < 0 || m < timeout ? m : timeout;
        } else if (v->s.message[0]) {
            v->s.message[0] = '\0';
            v->s.hud_dirty = true;
        }
        start_levels(v, t); /* after the first frame; under --lod off, after L */
        for (int i = 0; v->lod_started && i < v->n_scenes; i++)
            scene_lod_settle(v->scenes[i]); /* (no frame in flight here) */
        if (v->lod_pending && scene_lod_done(v->scenes[v->cur])) {
            v->lod_pending = false; /* the levels are in: draw with them */
            view_frames_note(&v->vf, "levels-ready", 0, timing_now_s());
            v->s.dirty = v->s.hud_dirty = true;
            timeout = 0;
        } else if (v->lod_pending && (timeout < 0 || timeout > 50)) {
            timeout = 50; /* look again soon */
        }
        if (v->s.hud_dirty && !v->s.dirty) /* draw it before waiting (a message ended, say);
                                              * with a frame due it goes out with the frame */
            timeout = 0;
        struct tty_event ev;
        for (int n = 0; n < 256; n++) {
            enum tty_event_kind k = tty_next_event(&v->tty, n == 0 ? timeout : 0, &ev);
            if (k == TTY_NONE)
                break;
            double te = timing_now_s();
            if (k == TTY_KEY)
                view_frames_note(&v->vf, "key", 0, te);
            if (k == TTY_KEY && act(v, view_key(&v->s, input_command(ev.key), te), te, &quit, e))
                return -1;
            else if (k == TTY_MOUSE)
                view_mouse(&v->s, &ev, te);
            else if (k == TTY_RESIZE && resize(v, e))
                return -1;
            else if (k == TTY_SYNC_REPLY)
                pace_answer(&v->pace, te);
        }
        if (tty_stop_requested()) {
            drain_answers(v);
            if (tty_suspend(&v->tty)) { /* back from Ctrl-Z: repaint everything */
                if (tty_signalled())
                    break;
                pace_forget(&v->pace);
                if (resize(v, e))
                    return -1;
                probe(v);
            }
        }
        t = timing_now_s();
        view_advance(&v->s, last, t);
        last = t;
        if (quit)
            break;
        if (v->s.glyphs != v->glyphs && resize(v, e)) /* g: a new grid, a new screen */
            return -1;
        if (v->s.dirty && pace_ready(&v->pace, t, NULL)) {
            if (draw_frame(v, t, e))
                return tty_signalled() ? 0 : -1; /* a quit signal cut the write short */
        } else if (v->s.hud_dirty) {
            /* a still picture's status line; or, while a frame is on its way, what a key
             * changed: it goes out now, behind that frame, not after its answer (the next
             * frame may wait for the link a while; the status line is a hundred bytes) */
            size_t before = v->out_len;
            hud_draw(v, t);
            if (v->out_len > before)
                view_frames_note(&v->vf, "hud", v->out_len - before, timing_now_s());
            out_flush(v);
        }
    }
    return 0;
}

/* The status line's texture field for a loaded scene. */
static void texture_label(struct view *v, int i, const char *conv)
{
    const struct scene *s = v->scenes[i];
    const char *path = v->o->texture ? v->o->texture : conv;
    if (path) {
        const char *base = strrchr(path, '/');
        base = base ? base + 1 : path;
        err_quote(base, strlen(base), sizeof v->texture[i] - 4, v->texture[i],
                  sizeof v->texture[i]);
        return;
    }
    v->texture[i][0] = '\0';
    for (int m = 0; m < s->n_meshes; m++)
        if (s->meshes[m].n_textures)
            snprintf(v->texture[i], sizeof v->texture[i], "MTL");
    for (int k = 0; k < s->n_items; k++)
        if (s->items[k].texture_override)
            snprintf(v->texture[i], sizeof v->texture[i], "scene file");
}

static int load_scenes(struct view *v, struct err *e)
{
    static char demo[4200];
    if (v->o->n_inputs == 0) {
        if (prepare_find_asset("demo.rsc", demo, sizeof demo))
            return err_set(e, "rastty: cannot find the demo scene (looked in $RASTTY_ASSETS, "
                              "assets/ next to the binary, ./assets and %s); run 'make' first",
                           RASTTY_DATADIR);
        v->paths[0] = demo;
        v->n_scenes = 1;
    } else {
        for (int i = 0; i < v->o->n_inputs; i++)
            v->paths[i] = v->o->inputs[i];
        v->n_scenes = v->o->n_inputs;
    }
    for (int i = 0; i < v->n_scenes; i++) {
        v->scenes[i] = calloc(1, sizeof(struct scene));
        if (!v->scenes[i])
            return err_set(e, "out of memory");
        char found[4200];
        if (prepare_scene(v->o, v->paths[i], v->scenes[i], found, sizeof found, e))
            return -1;
        texture_label(v, i, found[0] ? found : NULL);
    }
    return 0;
}

#define QUERY_MS 1000 /* a terminal that answers no query within this is not asked again */

/* The colour mode: --colors (or RASTTY_COLORS, or the config file, which main put there),
 * else what the environment says (termcaps.h); *ask_out: 256 or 16 and nothing explicit,
 * so the terminal itself may know better. Inside tmux, tmux's record of its client. */
static enum palette_mode colour_mode(const struct options *o, bool *ask_out)
{
    enum palette_mode m;
    *ask_out = false;
    if (o->colors && palette_mode_parse(o->colors, &m, NULL) == 0)
        return m;
    m = termcaps_detect_env(NULL);
    if (m != PALETTE_256 && m != PALETTE_16)
        return m;
    char features[512];
    int rgb = termcaps_tmux_features(features, sizeof features) == 0 ? termcaps_tmux_rgb(features)
                                                                     : -1;
    if (rgb >= 0) /* a client is attached: tmux knows whether it passes 24-bit colour on */
        return rgb ? PALETTE_TRUECOLOR : m;
    *ask_out = true;
    return m;
}

/* Learn which query the terminal answers (tty_query: DSR, CPR or DA1, or none: then the
 * frames are paced by time and carry no query), and when ask, its colours (termcaps.h,
 * TERMCAPS_QUERY). The answer also measures the round trip for the pacing. */
static void ask_terminal(struct view *v, bool ask)
{
    char reply[1024], req[256];
    /* the cell's shape: --cell-aspect, else the window's pixels over its cells (TIOCGWINSZ),
     * else ESC[16t's answer (asked with the probe: no wait of its own), else 1:2 */
    double r = v->o->cell_aspect;
    if (r <= 0)
        r = cell_aspect_of(v->tty.px_w, v->tty.px_h, v->tty.cols, v->tty.rows);
    snprintf(req, sizeof req, "%s%s", ask ? TERMCAPS_QUERY : "", r > 0 ? "" : TERMCAPS_CELL_QUERY);
    v->cell_r = r > 0 ? r : 1 / CELL_ASPECT;
    double t0 = timing_now_s();
    if (tty_query(&v->tty, req, reply, sizeof reply, QUERY_MS) < 0) {
        pace_no_answers(&v->pace);
        return;
    }
    int ch, cw;
    if (r <= 0 && termcaps_cell_pixels(reply, &ch, &cw) == 0 && cell_aspect_of(cw, ch, 1, 1) > 0)
        v->cell_r = cell_aspect_of(cw, ch, 1, 1);
    pace_sent(&v->pace, t0, strlen(req) + sizeof TTY_PROBE - 1, 0, 1);
    pace_answer(&v->pace, timing_now_s());
    if (ask)
        v->mode = termcaps_from_reply(v->mode, reply, NULL);
}

int view_run(const struct options *o, struct err *e)
{
    double t_start = timing_now_s(); /* the frame log's times count from here */
    struct view *v = calloc(1, sizeof *v);
    if (!v)
        return err_set(e, "out of memory"), 1;
    v->o = o;
    for (int i = 0; i < VIEW_MAX_SCENES; i++)
        v->camera_k[i] = -1;
    int rc = 2;
    sky_guess_start(v);
    if (load_scenes(v, e))
        goto out;
    double t_loaded = timing_now_s();
    for (int i = 0; i < o->n_inputs; i++) /* the model came on stdin: keys from the terminal */
        if (strcmp(o->inputs[i], "-") == 0 && tty_keys_from_terminal(e))
            goto out;
    /* the demo spins unless told not to; a model given on the command line does not */
    bool spin = o->spin >= 0 ? o->spin : o->n_inputs == 0;
    bool headlight = o->light_camera || (!o->light_set && !o->light_world);
    struct camera cam;
    camera_default(&cam);
    struct render_opts ro = o->render;
    if (!o->lod_set) /* the viewer draws what the terminal can show */
        ro.lod = LOD_AUTO;
    view_state_init(&v->s, &cam, &ro, spin, headlight,
                    o->spin_timeout >= 0 ? o->spin_timeout : VIEW_SPIN_TIMEOUT_S, timing_now_s());
    v->s.glyphs = o->glyphs;
    v->s.hud_hidden = o->no_hud; /* the start state; H toggles it */
    bool ask;
    v->mode = colour_mode(o, &ask);
    /* over ssh, default to a small tolerance: far fewer bytes, invisible change */
    bool ssh = getenv("SSH_CONNECTION") || getenv("SSH_TTY") || getenv("SSH_CLIENT");
    v->eo.tolerance = o->tolerance >= 0 ? o->tolerance : ssh ? 3 : 0;
    v->eo.dither = o->dither;
    pace_init(&v->pace, o->fps, o->bandwidth, !ssh);
    view_frames_init(&v->vf, !v->pace.local, t_start);
    view_frames_note(&v->vf, "loaded", 0, t_loaded);
    rc = 1;
    if (!(v->pipe = pipeline_new())) {
        err_set(e, "out of memory");
        goto out;
    }
    if (tty_open(&v->tty, e)) {
        rc = 2;
        goto out_tty;
    }
    ask_terminal(v, ask);
    view_frames_note(&v->vf, "terminal", 0, timing_now_s());
    v->eo.mode = v->mode;
    if (resize(v, e) == 0) {
        enter_scene(v);
        rc = loop(v, e) ? 1 : 0;
        if (rc == 0 && tty_quit_signal()) /* the shell convention for "killed by" */
            rc = 128 + tty_quit_signal();
        else /* q: the answer in flight goes to us, not to the shell's prompt */
            drain_answers(v);
    }
out_tty:
    tty_close(&v->tty);
    for (int i = 0; i < v->n_shots; i++)
        printf("screenshot: %s\n", v->shots[i]);
out:
    sky_guess_take(v, v3(NAN, NAN, NAN)); /* (not taken: a NaN equals nothing) */
    for (int i = 0; i < v->n_scenes; i++)
        if (v->scenes[i]) {
            scene_free(v->scenes[i]);
            free(v->scenes[i]);
        }
    encode_screen_free(&v->es);
    view_frames_free(&v->vf);
    fb_free(&v->fb);
    ssaa_free(&v->ssaa);
    pipeline_destroy(v->pipe);
    skybox_free(&v->default_sky);
    free(v->out);
    free(v);
    return rc;
}
