/* view_state.c: the viewer's model and what keys and the mouse do to it (see view_state.h). */
#include "view_state.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "light.h"
#include "options.h"

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

/* The next value of an enum with n values (a "cycle this render option" key). */
static int cycle(int v, int n)
{
    return (v + 1) % n;
}

void view_state_init(struct view_state *s, const struct camera *cam, const struct render_opts *ro,
                     bool spin, bool headlight, double spin_timeout, double now)
{
    memset(s, 0, sizeof *s);
    s->cam = s->home = *cam;
    s->ro = *ro;
    s->shade_i = SHADE_CYCLE_N - 1; /* textured */
    for (int i = 0; i < SHADE_CYCLE_N; i++)
        if (shade_cycle[i].shade == ro->shade && shade_cycle[i].textures == ro->textures)
            s->shade_i = i;
    s->orbit = true;
    s->spin = spin;
    s->headlight = headlight;
    s->speed = 1;
    s->extent = 1;
    s->cell_w = 0.5;
    s->spin_timeout = spin_timeout;
    s->last_input = now;
    s->dirty = s->hud_dirty = true;
}

void view_state_scene(struct view_state *s, const struct camera *cam,
                      const struct render_opts *scene_ro, double extent)
{
    struct render_opts keep = s->ro;
    s->cam = s->home = *cam;
    s->ro = *scene_ro;
    s->ro.shade = keep.shade;
    s->ro.textures = keep.textures;
    s->ro.filter = keep.filter;
    s->ro.cull = keep.cull;
    s->ro.view = keep.view;
    s->ro.raster = keep.raster;
    s->ro.persp = keep.persp;
    s->ro.depth = keep.depth;
    s->ro.lod = keep.lod;
    s->ro.lod_ratio = keep.lod_ratio;
    s->ro.lod_px = keep.lod_px;
    s->extent = extent > 0 ? extent : 1;
    s->dirty = s->hud_dirty = true;
}

const char *view_shade_name(const struct view_state *s)
{
    return shade_cycle[s->shade_i].name;
}

void view_message(struct view_state *s, const char *msg, double t)
{
    snprintf(s->message, sizeof s->message, "%s", msg);
    s->message_until = t + VIEW_MESSAGE_S;
    s->hud_dirty = true;
}

/* Cycle a method and say so: "rasterizer: scanline  (edge scanline tiled)". */
static int cycle_method(struct view_state *s, const char *axis, const struct render_enum *e,
                        int cur, double t)
{
    int next = cycle(cur, e->n);
    char msg[sizeof s->message];
    int n = snprintf(msg, sizeof msg, "%s: %s  (", axis, e->names[next]);
    for (int i = 0; i < e->n && n > 0 && (size_t)n < sizeof msg; i++)
        n += snprintf(msg + n, sizeof msg - (size_t)n, "%s%s", i ? " " : "", e->names[i]);
    if (n > 0 && (size_t)n < sizeof msg)
        snprintf(msg + n, sizeof msg - (size_t)n, ")");
    view_message(s, msg, t);
    return next;
}

/* A camera key or mouse move: the auto-rotation stops (Space starts it again). */
static void camera_touched(struct view_state *s)
{
    if (s->spin) {
        s->spin = false;
        s->hud_dirty = true;
    }
}

enum view_action view_key(struct view_state *s, enum input_cmd c, double t)
{
    s->last_input = t;
    if (c == IN_NONE)
        return VIEW_NONE;
    if (c < IN_HELD_COUNT) {
        bool repeat = t - s->last_press[c] < VIEW_REPEAT_GAP_S;
        s->last_press[c] = t;
        double until = t + (repeat ? VIEW_REPEAT_HOLD_S : VIEW_TAP_S);
        if (s->held_until[c] <= t) /* not moving yet: start now, not at the last frame */
            s->held_from[c] = t;
        s->held_until[c] = until > s->held_until[c] ? until : s->held_until[c];
        camera_touched(s);
        return VIEW_NONE;
    }
    s->dirty = s->hud_dirty = true;
    switch (c) {
    case IN_ORBIT: s->orbit = !s->orbit; break;
    case IN_FOV_IN:
        s->cam.fov_deg = s->cam.fov_deg > 15 ? s->cam.fov_deg - 5 : 10;
        camera_touched(s);
        break;
    case IN_FOV_OUT:
        s->cam.fov_deg = s->cam.fov_deg < 115 ? s->cam.fov_deg + 5 : 120;
        camera_touched(s);
        break;
    case IN_SLOWER: s->speed /= 1.5; break;
    case IN_FASTER: s->speed *= 1.5; break;
    case IN_RESET:
        s->cam = s->home;
        camera_touched(s);
        break;
    case IN_NEXT_SCENE: return VIEW_NEXT_SCENE;
    case IN_PREV_SCENE: return VIEW_PREV_SCENE;
    case IN_SHADE:
        s->shade_i = cycle(s->shade_i, SHADE_CYCLE_N);
        s->ro.shade = shade_cycle[s->shade_i].shade;
        s->ro.textures = shade_cycle[s->shade_i].textures;
        break;
    /* render options that cycle: one line each */
    case IN_FILTER: s->ro.filter = (enum tex_filter)cycle(s->ro.filter, TEX_FILTER_COUNT); break;
    case IN_CULL: s->ro.cull = (enum cull_mode)cycle(s->ro.cull, CULL_COUNT); break;
    case IN_VIEW: s->ro.view = (enum debug_view)cycle(s->ro.view, VIEW_COUNT); break;
    case IN_RASTER:
        s->ro.raster = (enum raster_method)cycle_method(s, "rasterizer", &render_raster_names,
                                                        (int)s->ro.raster, t);
        break;
    case IN_PERSPECTIVE:
        s->ro.persp = (enum persp_method)cycle_method(s, "interpolation", &render_persp_names,
                                                      (int)s->ro.persp, t);
        break;
    case IN_DEPTH:
        s->ro.depth = (enum depth_mode)cycle_method(s, "depth buffer", &render_depth_names,
                                                    (int)s->ro.depth, t);
        break;
    case IN_LOD: /* off -> auto -> clusters -> off (a --lod RATIO goes to auto) */
        s->ro.lod = s->ro.lod == LOD_AUTO ? LOD_CLUSTERS : s->ro.lod == LOD_CLUSTERS ? LOD_OFF
                                                                                  : LOD_AUTO;
        view_message(s, s->ro.lod == LOD_AUTO       ? "level of detail: auto  (L: clusters)"
                        : s->ro.lod == LOD_CLUSTERS ? "level of detail: clusters  (L: off)"
                                                    : "level of detail: off  (L: auto)", t);
        break;
    case IN_GLYPHS:
        s->glyphs = (enum cell_glyphs)cycle_method(s, "glyphs", &options_glyphs_names,
                                                   (int)s->glyphs, t);
        break;
    case IN_LIGHT:
        s->headlight = !s->headlight;
        view_message(s, s->headlight ? "light follows the camera (b: fixed in the world)"
                                     : "light fixed in the world (b: follows the camera)", t);
        break;
    case IN_PAUSE: /* pause and resume; after a camera key stopped it, start it again */
        if (s->spin) {
            s->paused = !s->paused;
        } else {
            s->spin = true;
            s->paused = false;
            s->hud_dirty = true;
            view_message(s, "auto-rotation on  (Space: pause)", t);
        }
        break;
    case IN_INFO: s->hud_camera = !s->hud_camera; break;
    case IN_HUD:
        s->hud_hidden = !s->hud_hidden;
        return VIEW_HUD_TOGGLED;
    case IN_HELP:
        s->help = !s->help;
        return s->help ? VIEW_HELP_OPENED : VIEW_HELP_CLOSED;
    case IN_QUIT:
        if (s->help) { /* q and Esc close the help first */
            s->help = false;
            return VIEW_HELP_CLOSED;
        }
        return VIEW_QUIT;
    case IN_SCREENSHOT: return VIEW_SCREENSHOT;
    case IN_TURN_UP:
        camera_touched(s);
        return VIEW_TURN_UP;
    case IN_NEXT_CAMERA:
        camera_touched(s);
        return VIEW_NEXT_CAMERA;
    default: break;
    }
    return VIEW_NONE;
}

void view_mouse(struct view_state *s, const struct tty_event *ev, double t)
{
    s->last_input = t;
    if (ev->button == 4 || ev->button == 5) {
        double d = camera_distance(&s->cam) * 0.1 * (ev->button == 4 ? 1 : -1);
        camera_move(&s->cam, d, 0, 0, 1);
        camera_touched(s);
        s->dirty = true;
        return;
    }
    if (ev->pressed && ev->button == 1) {
        s->dragging = true;
        s->drag_pan = ev->pan; /* shift-drag or the middle button: the whole drag pans */
        s->drag_x = ev->mx, s->drag_y = ev->my;
        return;
    }
    if (s->dragging && (ev->button == 0 || ev->released)) {
        int dx = ev->mx - s->drag_x, dy = ev->my - s->drag_y;
        if ((dx || dy) && (s->drag_pan || ev->pan)) {
            /* the point at the target's depth follows the mouse: the view's height there
             * over the picture's rows per cell */
            double rows = s->rows > 0 ? s->rows : 24;
            double cell = 2 * camera_distance(&s->cam) * tan(s->cam.fov_deg * M_PI / 360) / rows;
            if (s->cam.ortho_height > 0)
                cell = s->cam.ortho_height / rows;
            camera_pan(&s->cam, -dx * cell * s->cell_w, dy * cell);
            camera_touched(s);
            s->dirty = true;
        } else if (dx || dy) {
            /* a cell is 2 pixels tall: equal angle per pixel in both directions */
            camera_turn(&s->cam, -dx * 1.5, dy * 3.0, 1);
            camera_touched(s);
            s->dirty = true;
        }
        s->drag_x = ev->mx, s->drag_y = ev->my;
        if (ev->released)
            s->dragging = false;
    }
}

void view_advance(struct view_state *s, double from, double to)
{
    double speed = 0.4 * s->extent * s->speed;
    for (int c = 0; c < IN_HELD_COUNT; c++) {
        double start = s->held_from[c] > from ? s->held_from[c] : from;
        double end = s->held_until[c] < to ? s->held_until[c] : to;
        if (end <= start)
            continue;
        double dt = end - start;
        double d = speed * dt, a = VIEW_TURN_DEG_S * dt, zoom = 0.8 * dt * camera_distance(&s->cam);
        switch ((enum input_cmd)c) {
        case IN_FORWARD: camera_move(&s->cam, s->orbit ? zoom : d, 0, 0, s->orbit); break;
        case IN_BACK: camera_move(&s->cam, s->orbit ? -zoom : -d, 0, 0, s->orbit); break;
        case IN_LEFT: camera_move(&s->cam, 0, -d, 0, s->orbit); break;
        case IN_RIGHT: camera_move(&s->cam, 0, d, 0, s->orbit); break;
        case IN_DOWN: camera_move(&s->cam, 0, 0, -d, s->orbit); break;
        case IN_UP: camera_move(&s->cam, 0, 0, d, s->orbit); break;
        case IN_YAW_LEFT: camera_turn(&s->cam, a, 0, s->orbit); break;
        case IN_YAW_RIGHT: camera_turn(&s->cam, -a, 0, s->orbit); break;
        case IN_PITCH_UP: camera_turn(&s->cam, 0, a, s->orbit); break;
        case IN_PITCH_DOWN: camera_turn(&s->cam, 0, -a, s->orbit); break;
        case IN_PAN_LEFT: camera_pan(&s->cam, -d, 0); break;
        case IN_PAN_RIGHT: camera_pan(&s->cam, d, 0); break;
        case IN_PAN_UP: camera_pan(&s->cam, 0, d); break;
        case IN_PAN_DOWN: camera_pan(&s->cam, 0, -d); break;
        default: break;
        }
        s->dirty = true;
    }
    if (s->spin && !s->paused && to > from) {
        camera_turn(&s->cam, VIEW_SPIN_DEG_S * (to - from), 0, 1);
        s->dirty = true;
    }
}

bool view_animating(struct view_state *s, double t)
{
    if (s->spin && !s->paused && s->spin_timeout > 0 && t - s->last_input > s->spin_timeout) {
        s->paused = true;
        view_message(s, "auto-rotation paused: no input for a while (Space resumes)", t);
    }
    if (s->spin && !s->paused)
        return true;
    for (int c = 0; c < IN_HELD_COUNT; c++)
        if (s->held_until[c] > t)
            return true;
    return false;
}

void view_frame_opts(const struct view_state *s, struct render_opts *out)
{
    *out = s->ro;
    if (s->headlight)
        light_use_camera(out, &s->cam);
}
