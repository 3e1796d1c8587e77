/* view_hud.h: the status line's text and the help overlay's place — pure, from the viewer's
 * state and the numbers of the last frame; view.c writes them to the terminal.
 *
 * The status line is a list of fields, most important first: the scene, shading and texture
 * filter, colour mode, frame rate, and "#N" once the picture stands still (N: frames written
 * in full so far; see view_hud_info.frames); then what the pacing did to the picture (pace.h), a
 * debug view, fly mode, the camera (`i`), the texture file ("untextured" when none), the
 * light and the methods (rasterizer, interpolation, depth buffer), the level of detail (mode,
 * level drawn, triangles submitted of the full count: "lod auto L1 149.6k/300.6k", "..."
 * while the levels are being built); then culling, bytes,
 * timings, triangle counts and the help key. A line too narrow
 * for all of them drops whole fields, least important first (and the rightmost of equals),
 * never cutting one: at 80 columns the first five always fit. A new field is one line in
 * view_hud_compose. */
#ifndef RASTTY_VIEW_HUD_H
#define RASTTY_VIEW_HUD_H

#include <stddef.h>

#include "palette.h"
#include "pipeline.h"
#include "render_opts.h"
#include "view_state.h"

struct view_hud_info {
    const char *scene;          /* the scene's name */
    int scene_i, n_scenes;
    const char *texture;        /* texture file name, "MTL" or NULL (untextured) */
    enum palette_mode mode;     /* the colour mode frames are drawn in */
    double fps, render_ms, encode_ms;
    size_t bytes;               /* the last frame's */
    const struct frame_stats *st;
    const char *pacing;         /* pace_describe(): "" when the link keeps up */
    bool lod_building;          /* the scene's levels of detail are still being built */
    /* Frames written to the terminal in full, shown as "#N" (also after a message) when the
     * picture stands still: nothing moving, nothing left to draw or refine. The viewer writes
     * that status line after the frame, so once "#N" is on the screen the whole frame is:
     * the end-to-end tests wait for it. 0 = not shown (the picture is moving). */
    unsigned long frames;
};

/* The status line for a terminal `width` columns wide (at most width - 1 characters: the
 * last cell of the screen is never written), or the current message while there is one
 * (" message | #N " when the frame count is shown). */
void view_hud_compose(const struct view_state *s, const struct view_hud_info *in, int width,
                      double now, char *out, size_t n);

/* The help overlay: centred on a cols x rows picture and clipped to it; text_w is the width
 * of the widest help line (input.h). */
struct view_hud_rect {
    int col, row, cols, rows, text_w;
};
struct view_hud_rect view_hud_help_rect(int cols, int rows);

#endif
