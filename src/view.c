/* view.c: the interactive viewer loop (see view.h). */
#include "view.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "cmd.h"
#include "encode.h"
#include "input.h"
#include "pipeline.h"
#include "scene.h"
#include "ssaa.h"
#include "termcaps.h"
#include "tty.h"

#ifndef RASTTY_DATADIR
#define RASTTY_DATADIR "/usr/local/share/rastty"
#endif

#define VIEW_MAX_SCENES OPTIONS_MAX_INPUTS
#define TAP_S 0.15         /* a single key press moves for this long */
#define REPEAT_GAP_S 0.5   /* a press this soon after the last one is auto-repeat */
#define REPEAT_HOLD_S 0.11 /* while repeating, each repeat keeps moving this long */
#define TURN_DEG_S 90.0
#define SPIN_DEG_S 20.0
#define SYNC_TIMEOUT_S 1.0 /* no DSR answer this long: the terminal does not answer */
#define HUD_PERIOD_S 0.5   /* while animating, refresh the status line at most this often */
#define MESSAGE_S 2.5

/* The m key cycles these; "textured" is phong with textures. */
static const struct {
    enum shade_mode shade;
    bool textures;
    const char *name;
} shade_cycle[] = {
    {SHADE_WIRE, false, "wire"},   {SHADE_FLAT, false, "flat"},
    {SHADE_GOURAUD, false, "gouraud"}, {SHADE_PHONG, false, "phong"},
    {SHADE_PHONG, true, "textured"},
};
enum { SHADE_CYCLE_N = sizeof shade_cycle / sizeof shade_cycle[0] };

struct view {
    const struct options *o;
    struct scene *scenes[VIEW_MAX_SCENES];
    const char *paths[VIEW_MAX_SCENES];
    int n_scenes, cur;
    struct camera cam, home;
    struct render_opts ro;
    int shade_i;
    bool orbit, spinning, help, hud;
    double speed_scale;
    /* held keys: each command moves from held_from until held_until */
    double held_from[IN_HELD_COUNT], held_until[IN_HELD_COUNT], last_press[IN_HELD_COUNT];
    bool dragging;
    int drag_x, drag_y;
    /* output */
    struct tty tty;
    struct fb fb;
    struct encode_screen es;
    struct encode_opts eo;
    struct pipeline *pipe;
    struct ssaa ssaa;     /* --ssaa's big framebuffer */
    struct skybox default_sky;
    int fb_cols, fb_rows; /* cells used by the picture */
    bool dirty, hud_dirty;
    bool sync_ok;         /* the terminal answers DSR */
    int inflight;
    double sync_sent_at;
    /* stats for the HUD */
    struct frame_stats st;
    double encode_ms, fps, last_frame_at, next_hud_at;
    size_t last_bytes;
    char message[96];
    double message_until;
    char hud_text[512];
    /* everything for one update (frame, overlays, status line, DSR) goes out in one write */
    char *out;
    size_t out_len, out_cap;
};

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + ts.tv_nsec * 1e-9;
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

static void set_message(struct view *v, const char *msg)
{
    snprintf(v->message, sizeof v->message, "%s", msg);
    v->message_until = now_s() + MESSAGE_S;
    v->hud_dirty = true;
}

/* "rasterizer: scanline  (edge scanline tiled)" */
static void method_message(struct view *v, const char *axis, const struct render_enum *t, int cur)
{
    char msg[sizeof v->message];
    int n = snprintf(msg, sizeof msg, "%s: %s  (", axis, t->names[cur]);
    for (int i = 0; i < t->n && n > 0 && (size_t)n < sizeof msg; i++)
        n += snprintf(msg + n, sizeof msg - (size_t)n, "%s%s", i ? " " : "", t->names[i]);
    if (n > 0 && (size_t)n < sizeof msg)
        snprintf(msg + n, sizeof msg - (size_t)n, ")");
    set_message(v, msg);
}

/* ---- scenes ---- */


/* The viewer's default sky for scenes that set neither a sky nor a background (and no
 * --background): the procedural one, sun toward the first light. render and dump keep the
 * conventions' black background. */
static const struct skybox *scene_sky(struct view *v)
{
    const struct scene *s = v->scenes[v->cur];
    if (s->has_sky)
        return &s->sky;
    if (s->has_background || v->o->background_set)
        return NULL;
    if (v->default_sky.n_levels == 0) {
        struct err ignored;
        if (skybox_procedural(&v->default_sky, v->ro.lights[0].dir, &ignored))
            return NULL;
    }
    return &v->default_sky;
}

static double scene_extent(const struct scene *s)
{
    return v3_len(v3_sub(s->bound_hi, s->bound_lo));
}

/* camera, lights and background for the current scene; the camera becomes "home" */
static void enter_scene(struct view *v)
{
    const struct scene *s = v->scenes[v->cur];
    struct render_opts keep = v->ro;
    double aspect = v->fb.w > 0 ? (double)v->fb.w / v->fb.h : 2.0;
    /* a model alone is framed, unless the command line placed the camera */
    cmd_view_setup(v->o, s, aspect, !v->o->camera_set, &v->home, &v->ro);
    /* modes chosen with keys survive a scene change */
    v->ro.shade = keep.shade;
    v->ro.textures = keep.textures;
    v->ro.filter = keep.filter;
    v->ro.cull = keep.cull;
    v->ro.view = keep.view;
    v->ro.raster = keep.raster;
    v->ro.persp = keep.persp;
    v->ro.depth = keep.depth;
    v->cam = v->home;
    v->dirty = v->hud_dirty = true;
}

/* ---- output ---- */

static int resize(struct view *v, struct err *e)
{
    tty_refresh_size(&v->tty);
    int rows = v->tty.rows - (v->hud ? 1 : 0);
    int cols = v->tty.cols;
    cols = cols > ENCODE_MAX_COLS ? ENCODE_MAX_COLS : cols;
    rows = rows > ENCODE_MAX_ROWS ? ENCODE_MAX_ROWS : rows;
    if (cols < 1 || rows < 1) {
        v->fb_cols = v->fb_rows = 0;
        return 0;
    }
    if (cols != v->fb_cols || rows != v->fb_rows) {
        fb_free(&v->fb);
        encode_screen_free(&v->es);
        if (fb_init(&v->fb, cols, 2 * rows, true, e) || encode_screen_init(&v->es, cols, rows, e))
            return -1;
        v->fb_cols = cols;
        v->fb_rows = rows;
    }
    encode_screen_invalidate(&v->es);
    out_add(v, "\033[0m\033[2J", 8);
    v->dirty = v->hud_dirty = true;
    return 0;
}

static void hud_compose(struct view *v, char *out, size_t n)
{
    const struct scene *s = v->scenes[v->cur];
    const char *shade = shade_cycle[v->shade_i].name;
    char extra[128] = "";
    if (v->ro.view != VIEW_COLOR)
        snprintf(extra, sizeof extra, " view:%s", render_view_name(v->ro.view));
    if (v->message_until > now_s()) {
        snprintf(out, n, " %s ", v->message);
        return;
    }
    char ssaa[16] = "";
    if (v->ro.ssaa != SSAA_1)
        snprintf(ssaa, sizeof ssaa, " ssaa%d", render_ssaa_factor(v->ro.ssaa));
    snprintf(out, n,
             " %s [%d/%d] | %s %s cull:%s%s | %s | %.0f fps | %s %s %s%s | render %.1f ms "
             "enc %.2f ms | %.1f KB | tris %llu clip %llu cull %llu | %s | h: help",
             s->name, v->cur + 1, v->n_scenes, shade, render_filter_name(v->ro.filter),
             render_cull_name(v->ro.cull), extra, v->orbit ? "orbit" : "fly", v->fps,
             render_raster_name(v->ro.raster), render_persp_name(v->ro.persp),
             render_depth_name(v->ro.depth), ssaa,
             v->st.render_ms, v->encode_ms, v->last_bytes / 1024.0,
             (unsigned long long)v->st.tris_drawn, (unsigned long long)v->st.tris_clipped,
             (unsigned long long)(v->st.tris_culled + v->st.tris_rejected),
             palette_mode_name(v->eo.mode));
}

static void hud_draw(struct view *v)
{
    if (!v->hud || v->tty.rows < 1)
        return;
    char text[512], pos[32];
    hud_compose(v, text, sizeof text);
    if (!v->hud_dirty && strcmp(text, v->hud_text) == 0)
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
    v->hud_dirty = false;
}

/* Where the help box goes: centred on the picture, clipped to it. */
static void help_rect(const struct view *v, int *x0, int *y0, int *w, int *h, int *text_w)
{
    int lines = 0, width = 0;
    while (input_help_line(lines)) {
        int l = (int)strlen(input_help_line(lines++));
        width = l > width ? l : width;
    }
    *text_w = width;
    *w = width + 4;
    *h = lines + 2;
    *x0 = (v->fb_cols - *w) / 2;
    *y0 = (v->fb_rows - *h) / 2;
    *x0 = *x0 < 0 ? 0 : *x0;
    *y0 = *y0 < 0 ? 0 : *y0;
}

static void help_draw(struct view *v)
{
    int x0, y0, w, h, width;
    help_rect(v, &x0, &y0, &w, &h, &width);
    int visible = v->fb_cols - x0 < w ? v->fb_cols - x0 : w; /* never wrap a line */
    const char *sgr = v->eo.mode == PALETTE_NONE ? "" : "\033[0;97;44m";
    for (int i = 0; i < h && y0 + i < v->fb_rows; i++) {
        const char *text = i == 0 || i == h - 1 ? "" : input_help_line(i - 1);
        char pos[32], line[256];
        int k = snprintf(pos, sizeof pos, "\033[%d;%dH", y0 + i + 1, x0 + 1);
        snprintf(line, sizeof line, "  %-*.*s  ", width, width, text);
        out_add(v, pos, (size_t)k);
        out_add(v, sgr, strlen(sgr));
        out_add(v, line, (size_t)visible);
    }
    out_add(v, "\033[0m", 4);
}

static int draw_frame(struct view *v, struct err *e)
{
    if (v->fb_cols == 0) { /* no room for a picture (one row and a HUD): only the HUD */
        v->dirty = false;
        v->last_frame_at = now_s();
        hud_draw(v);
        return out_flush(v) ? err_set(e, "rastty: cannot write to the terminal") : 0;
    }
    const struct scene *s = v->scenes[v->cur];
    if (ssaa_draw(&v->ssaa, v->pipe, s->items, s->n_items, scene_sky(v), &v->cam, &v->ro,
                  &v->fb, &v->st, e))
        return -1;
    double t0 = now_s();
    size_t n;
    v->eo.diff = true;
    const char *bytes = encode_fb(&v->es, &v->fb, &v->eo, &n, NULL);
    v->encode_ms = (now_s() - t0) * 1e3;
    v->last_bytes = n;
    out_add(v, bytes, n);
    if (v->help)
        help_draw(v);
    double t = now_s();
    if (v->last_frame_at > 0) {
        double inst = 1.0 / (t - v->last_frame_at > 1e-4 ? t - v->last_frame_at : 1e-4);
        v->fps = v->fps > 0 ? 0.8 * v->fps + 0.2 * inst : inst;
    }
    v->last_frame_at = t;
    if (t >= v->next_hud_at || v->hud_dirty) {
        hud_draw(v);
        v->next_hud_at = t + HUD_PERIOD_S;
    }
    if (v->sync_ok && n) {
        out_add(v, TTY_SYNC_REQUEST, sizeof TTY_SYNC_REQUEST - 1);
        if (v->inflight++ == 0)
            v->sync_sent_at = t;
    }
    v->dirty = false;
    if (out_flush(v))
        return err_set(e, "rastty: cannot write to the terminal");
    return 0;
}

/* ---- input ---- */

static void stop_spin(struct view *v)
{
    if (v->spinning) {
        v->spinning = false;
        v->hud_dirty = true;
    }
}

static void command(struct view *v, enum input_cmd c, double t, bool *quit)
{
    if (c < IN_HELD_COUNT) {
        bool repeat = t - v->last_press[c] < REPEAT_GAP_S;
        v->last_press[c] = t;
        double until = t + (repeat ? REPEAT_HOLD_S : TAP_S);
        if (v->held_until[c] <= t) /* not moving yet: start now, not at the last frame */
            v->held_from[c] = t;
        v->held_until[c] = until > v->held_until[c] ? until : v->held_until[c];
        stop_spin(v);
        return;
    }
    v->dirty = v->hud_dirty = true;
    switch (c) {
    case IN_ORBIT: v->orbit = !v->orbit; break;
    case IN_FOV_IN: v->cam.fov_deg = v->cam.fov_deg > 15 ? v->cam.fov_deg - 5 : 10; break;
    case IN_FOV_OUT: v->cam.fov_deg = v->cam.fov_deg < 115 ? v->cam.fov_deg + 5 : 120; break;
    case IN_SLOWER: v->speed_scale /= 1.5; break;
    case IN_FASTER: v->speed_scale *= 1.5; break;
    case IN_RESET: v->cam = v->home; break;
    case IN_NEXT_SCENE:
    case IN_PREV_SCENE:
        v->cur = (v->cur + (c == IN_NEXT_SCENE ? 1 : v->n_scenes - 1)) % v->n_scenes;
        enter_scene(v);
        break;
    case IN_SHADE:
        v->shade_i = (v->shade_i + 1) % SHADE_CYCLE_N;
        v->ro.shade = shade_cycle[v->shade_i].shade;
        v->ro.textures = shade_cycle[v->shade_i].textures;
        break;
    case IN_FILTER: v->ro.filter = (enum tex_filter)((v->ro.filter + 1) % TEX_FILTER_COUNT); break;
    case IN_CULL: v->ro.cull = (enum cull_mode)((v->ro.cull + 1) % CULL_COUNT); break;
    case IN_LIGHT:
        for (int i = 0; i < v->ro.n_lights; i++)
            v->ro.lights[i].dir = m4_mul_dir(m4_rotate(v3(0, 1, 0), 30), v->ro.lights[i].dir);
        break;
    case IN_VIEW: v->ro.view = (enum debug_view)((v->ro.view + 1) % VIEW_COUNT); break;
    case IN_RASTER:
        v->ro.raster = (enum raster_method)((v->ro.raster + 1) % RASTER_COUNT);
        method_message(v, "rasterizer", &render_raster_names, (int)v->ro.raster);
        break;
    case IN_PERSPECTIVE:
        v->ro.persp = (enum persp_method)((v->ro.persp + 1) % PERSP_COUNT);
        method_message(v, "interpolation", &render_persp_names, (int)v->ro.persp);
        break;
    case IN_DEPTH:
        v->ro.depth = (enum depth_mode)((v->ro.depth + 1) % DEPTH_COUNT);
        method_message(v, "depth buffer", &render_depth_names, (int)v->ro.depth);
        break;
    case IN_PAUSE: v->spinning = !v->spinning; break;
    case IN_HELP:
        v->help = !v->help;
        if (!v->help) { /* uncover the picture: those cells must be drawn again */
            int x, y, w, h, width;
            help_rect(v, &x, &y, &w, &h, &width);
            encode_screen_damage(&v->es, x, y, w, h);
        }
        break;
    case IN_QUIT: *quit = true; break;
    default: break;
    }
}

static void mouse(struct view *v, const struct tty_event *ev)
{
    if (ev->button == 4 || ev->button == 5) {
        double d = camera_distance(&v->cam) * 0.1 * (ev->button == 4 ? 1 : -1);
        camera_move(&v->cam, d, 0, 0, 1);
        stop_spin(v);
        v->dirty = true;
        return;
    }
    if (ev->pressed && ev->button == 1) {
        v->dragging = true;
        v->drag_x = ev->mx, v->drag_y = ev->my;
        return;
    }
    if (v->dragging && (ev->button == 0 || ev->released)) {
        int dx = ev->mx - v->drag_x, dy = ev->my - v->drag_y;
        if (dx || dy) {
            /* a cell is 2 pixels tall: equal angle per pixel in both directions */
            camera_turn(&v->cam, -dx * 1.5, dy * 3.0, 1);
            stop_spin(v);
            v->dirty = true;
        }
        v->drag_x = ev->mx, v->drag_y = ev->my;
        if (ev->released)
            v->dragging = false;
    }
}

/* apply held keys and auto-rotation over [from, to] */
static void advance(struct view *v, double from, double to)
{
    double speed = 0.4 * scene_extent(v->scenes[v->cur]) * v->speed_scale;
    for (int c = 0; c < IN_HELD_COUNT; c++) {
        double start = v->held_from[c] > from ? v->held_from[c] : from;
        double end = v->held_until[c] < to ? v->held_until[c] : to;
        if (end <= start)
            continue;
        double dt = end - start;
        double d = speed * dt, a = TURN_DEG_S * dt;
        switch ((enum input_cmd)c) {
        case IN_FORWARD: camera_move(&v->cam, v->orbit ? 0.8 * dt * camera_distance(&v->cam) : d, 0, 0, v->orbit); break;
        case IN_BACK: camera_move(&v->cam, v->orbit ? -0.8 * dt * camera_distance(&v->cam) : -d, 0, 0, v->orbit); break;
        case IN_LEFT: camera_move(&v->cam, 0, -d, 0, v->orbit); break;
        case IN_RIGHT: camera_move(&v->cam, 0, d, 0, v->orbit); break;
        case IN_DOWN: camera_move(&v->cam, 0, 0, -d, v->orbit); break;
        case IN_UP: camera_move(&v->cam, 0, 0, d, v->orbit); break;
        case IN_YAW_LEFT: camera_turn(&v->cam, a, 0, v->orbit); break;
        case IN_YAW_RIGHT: camera_turn(&v->cam, -a, 0, v->orbit); break;
        case IN_PITCH_UP: camera_turn(&v->cam, 0, a, v->orbit); break;
        case IN_PITCH_DOWN: camera_turn(&v->cam, 0, -a, v->orbit); break;
        default: break;
        }
        v->dirty = true;
    }
    if (v->spinning && to > from) {
        camera_turn(&v->cam, SPIN_DEG_S * (to - from), 0, 1);
        v->dirty = true;
    }
}

static bool animating(const struct view *v, double t)
{
    if (v->spinning)
        return true;
    for (int c = 0; c < IN_HELD_COUNT; c++)
        if (v->held_until[c] > t)
            return true;
    return false;
}

static int loop(struct view *v, struct err *e)
{
    bool quit = false;
    double last = now_s(), frame_gap = 1.0 / v->o->fps;
    while (!quit && !tty_signalled()) {
        double t = now_s();
        if (v->inflight && t - v->sync_sent_at > SYNC_TIMEOUT_S) {
            v->sync_ok = false; /* no answer: stop waiting for them */
            v->inflight = 0;
        }
        bool want = v->dirty || animating(v, t);
        bool blocked = v->sync_ok && v->inflight >= 2;
        int timeout = -1;
        if (want) {
            double wait = blocked ? SYNC_TIMEOUT_S : v->last_frame_at + frame_gap - t;
            timeout = wait > 0 ? (int)(wait * 1e3) + 1 : 0;
        }
        if (v->message_until > t) {
            int m = (int)((v->message_until - t) * 1e3) + 1;
            timeout = timeout < 0 || m < timeout ? m : timeout;
        } else if (v->message[0]) {
            v->message[0] = '\0';
            v->hud_dirty = true;
            v->dirty = true; /* redraw the status line */
        }
        struct tty_event ev;
        for (int n = 0; n < 256; n++) {
            enum tty_event_kind k = tty_next_event(&v->tty, n == 0 ? timeout : 0, &ev);
            if (k == TTY_NONE)
                break;
            double te = now_s();
            if (k == TTY_KEY)
                command(v, input_command(ev.key), te, &quit);
            else if (k == TTY_MOUSE)
                mouse(v, &ev);
            else if (k == TTY_RESIZE && resize(v, e))
                return -1;
            else if (k == TTY_SYNC_REPLY && v->inflight > 0)
                v->inflight--;
        }
        if (tty_suspend(&v->tty) && resize(v, e)) /* back from Ctrl-Z: repaint everything */
            return -1;
        t = now_s();
        advance(v, last, t);
        last = t;
        if (quit)
            break;
        if (v->dirty && t >= v->last_frame_at + frame_gap && !(v->sync_ok && v->inflight >= 2)) {
            if (draw_frame(v, e))
                return tty_signalled() ? 0 : -1; /* a quit signal cut the write short */
        } else if (v->hud_dirty && !v->dirty) {
            hud_draw(v);
            out_flush(v);
        }
    }
    return 0;
}

static int load_scenes(struct view *v, struct err *e)
{
    static char demo[4200];
    if (v->o->n_inputs == 0) {
        if (cmd_find_asset("demo.rsc", demo, sizeof demo))
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
        if (cmd_load_scene(v->o, v->paths[i], v->scenes[i], e))
            return -1;
    }
    return 0;
}

int view_run(const struct options *o, struct err *e)
{
    struct view *v = calloc(1, sizeof *v);
    if (!v)
        return err_set(e, "out of memory"), 1;
    v->o = o;
    v->ro = o->render;
    v->shade_i = SHADE_CYCLE_N - 1; /* textured */
    for (int i = 0; i < SHADE_CYCLE_N; i++)
        if (shade_cycle[i].shade == o->render.shade && shade_cycle[i].textures == o->render.textures)
            v->shade_i = i;
    v->orbit = true;
    v->spinning = true;
    v->hud = !o->no_hud;
    v->speed_scale = 1;
    v->sync_ok = true;
    int rc = 2;
    if (load_scenes(v, e))
        goto out;
    v->eo.mode = termcaps_detect_env(NULL);
    if (o->colors)
        palette_mode_parse(o->colors, &v->eo.mode, NULL);
    /* over ssh, default to a small tolerance: far fewer bytes, invisible change */
    bool ssh = getenv("SSH_CONNECTION") || getenv("SSH_TTY");
    v->eo.tolerance = o->tolerance >= 0 ? o->tolerance : ssh ? 3 : 0;
    v->eo.dither = o->dither;
    rc = 1;
    if (!(v->pipe = pipeline_new())) {
        err_set(e, "out of memory");
        goto out;
    }
    if (tty_open(&v->tty, e)) {
        rc = 2;
        goto out_tty;
    }
    if (resize(v, e) == 0) {
        enter_scene(v);
        rc = loop(v, e) ? 1 : 0;
        if (rc == 0 && tty_quit_signal()) /* the shell convention for "killed by" */
            rc = 128 + tty_quit_signal();
    }
out_tty:
    tty_close(&v->tty);
out:
    for (int i = 0; i < v->n_scenes; i++)
        if (v->scenes[i]) {
            scene_free(v->scenes[i]);
            free(v->scenes[i]);
        }
    encode_screen_free(&v->es);
    fb_free(&v->fb);
    ssaa_free(&v->ssaa);
    pipeline_destroy(v->pipe);
    skybox_free(&v->default_sky);
    free(v->out);
    free(v);
    return rc;
}
