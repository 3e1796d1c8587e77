/* view_state.h: the viewer's model and how input changes it.
 *
 * Pure functions from (state, event, time) to state: no terminal, no rendering, no files, so
 * tests drive them directly. The loop (view.c) turns terminal events into calls here, acts
 * on the returned action (quit, scene change, screenshot, help closed) and draws when
 * `dirty` says the picture changed or `hud_dirty` the status line.
 *
 *   view_key      a command (input.h) at time t
 *   view_mouse    a mouse event: the wheel zooms, a left drag orbits, a shift- or
 *                 middle-drag pans (eye and target together, the model following the mouse)
 *   view_advance  held keys and auto-rotation over [from, to]
 *   view_frame_opts  the render options a frame is drawn with (the headlight applied)
 *
 * Motion follows elapsed time: a key press moves for TAP_S, auto-repeat keeps it moving.
 * Auto-rotation ("spin"): on for the demo and with --spin; the first camera key (movement,
 * turning, field of view, reset, mouse) stops it. Space pauses and resumes it, and starts
 * it again after a camera key stopped it. Without input for spin_timeout seconds it
 * pauses by itself, so a viewer left open does not stream forever.
 * Cycling a render option is one line in view_key's switch (cycle(), or cycle_method() for
 * the methods R, p and Z, which also say which one is on). */
#ifndef RASTTY_VIEW_STATE_H
#define RASTTY_VIEW_STATE_H

#include <stdbool.h>

#include "camera.h"
#include "cell.h"
#include "input.h"
#include "render_opts.h"
#include "tty.h"

#define VIEW_TAP_S 0.15         /* a single key press moves for this long */
#define VIEW_REPEAT_GAP_S 0.5   /* a press this soon after the last one is auto-repeat */
#define VIEW_REPEAT_HOLD_S 0.11 /* while repeating, each repeat keeps moving this long */
#define VIEW_TURN_DEG_S 90.0
#define VIEW_SPIN_DEG_S 20.0
#define VIEW_MESSAGE_S 2.5
#define VIEW_SPIN_TIMEOUT_S 120.0 /* default: an untouched spin pauses after two minutes */

enum view_action {
    VIEW_NONE,
    VIEW_QUIT,
    VIEW_NEXT_SCENE,
    VIEW_PREV_SCENE,
    VIEW_HELP_OPENED,
    VIEW_HELP_CLOSED,  /* the cells under the overlay must be drawn again */
    VIEW_SCREENSHOT,
    VIEW_TURN_UP,      /* the model's next axis up (scene_turn_up), framed again */
    VIEW_NEXT_CAMERA,  /* the model file's next camera (then rastty's framing) */
    VIEW_HUD_TOGGLED,  /* H: the status line hidden or shown (the picture's rows change) */
};

struct view_state {
    struct camera cam, home;  /* home: where `r` goes back to */
    struct render_opts ro;    /* methods chosen with keys; world lights */
    enum cell_glyphs glyphs;  /* how cells show pixels (the g key) */
    int shade_i;              /* position in the m key's cycle */
    bool orbit;               /* orbit the target (else fly) */
    bool spin;                /* auto-rotation wanted (off after a camera key, Space: on) */
    bool paused;              /* Space, or the idle timeout */
    bool headlight;           /* the light follows the camera (else the world lights) */
    bool help;                /* the key help overlay is shown */
    bool hud_camera;          /* the status line shows the camera position */
    bool hud_hidden;          /* no status line (--no-hud at start, then the H key) */
    int rows;                 /* the picture's rows of cells (a pan drag follows the mouse) */
    double cell_w;            /* a cell's width over its height (0.5 for 1:2 cells) */
    double extent;            /* the scene's size: movement speed scales with it */
    double speed;             /* [ and ] */
    double spin_timeout;      /* seconds without input before the spin pauses; 0 = never */
    double last_input;        /* time of the last key or mouse event */
    /* held keys: each command moves from held_from until held_until */
    double held_from[IN_HELD_COUNT], held_until[IN_HELD_COUNT], last_press[IN_HELD_COUNT];
    bool dragging;
    bool drag_pan;            /* this drag pans (shift held, or the middle button) */
    int drag_x, drag_y;
    /* for the loop */
    bool dirty;               /* the picture must be drawn again */
    bool hud_dirty;           /* the status line must be drawn again */
    char message[96];         /* shown instead of the status line until message_until */
    double message_until;
};

/* Start state: camera and home, render options (world lights) as given; textured phong
 * unless ro says otherwise; orbit mode. */
void view_state_init(struct view_state *s, const struct camera *cam, const struct render_opts *ro,
                     bool spin, bool headlight, double spin_timeout, double now);
/* A new scene: its camera becomes home and its lights the world lights; modes chosen with
 * keys (shading, filter, culling, debug view, methods, level of detail, light mode) are
 * kept. */
void view_state_scene(struct view_state *s, const struct camera *cam,
                      const struct render_opts *scene_ro, double extent);
enum view_action view_key(struct view_state *s, enum input_cmd c, double t);
void view_mouse(struct view_state *s, const struct tty_event *ev, double t);
void view_advance(struct view_state *s, double from, double to);
/* Is the picture moving at t (spin or a held key)? Pauses an idle spin (spin_timeout). */
bool view_animating(struct view_state *s, double t);
/* The options a frame is drawn with: s->ro, with the headlight (light.h) when it is on. */
void view_frame_opts(const struct view_state *s, struct render_opts *out);
/* "wire", "flat", "gouraud", "phong", "textured" */
const char *view_shade_name(const struct view_state *s);
void view_message(struct view_state *s, const char *msg, double t);

#endif
