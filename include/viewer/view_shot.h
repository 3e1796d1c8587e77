/* view_shot.h: the `rastty render` command line that reproduces what the viewer shows.
 *
 * The screenshot key (S) writes the framebuffer as PNG and ANSI (view.c) and prints this
 * command at exit: same scene file, framebuffer size, camera (every number with 17
 * significant digits, so it round-trips exactly), light (--light camera for the headlight),
 * shading, texture, filter, culling, methods (--raster, --persp, --depth, --ssaa, --lod:
 * render builds every level before drawing, the viewer in the background), debug view,
 * background and the viewer's default sky
 * (--sky procedural). Rendering it gives the same pixels as the PNG. Pure. */
#ifndef RASTTY_VIEW_SHOT_H
#define RASTTY_VIEW_SHOT_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "view_state.h"

#define VIEW_SHOT_MAX 1200

struct view_shot_info {
    const char *model;        /* the scene or model file, as given */
    const char *texture;      /* --texture, or NULL */
    int width, height;        /* framebuffer pixels */
    const char *out;          /* the PNG the command writes */
    bool light_set;           /* --light X,Y,Z was given: repeat it in world-light mode */
    bool background_set;      /* --background was given */
    const uint8_t *background;
    bool sky;                 /* the viewer's default procedural sky is behind the scene */
    char up_axis;             /* 'x', 'y' or 'z': the model's axis drawn up, when the u key
                                 changed it (or --up-axis gave it); 0: the file's own */
};

void view_shot_command(const struct view_state *s, const struct view_shot_info *in, char *out,
                       size_t n);

#endif
