/* config.h: the user's standing defaults — RASTTY_COLORS and a small config file,
 * ${XDG_CONFIG_HOME:-$HOME/.config}/rastty/config.
 *
 * Precedence: the command line, then RASTTY_COLORS (colours only), then the file, then
 * rastty's own defaults. They apply to the viewer; dump takes the colours only when it
 * writes to a terminal. render, and dump to a file, keep the conventions. A missing file is
 * no error; anything wrong in it is "PATH:LINE: what" (exit status 2).
 * The file: one "key = value" per line, # starts a comment, blank lines are fine.
 *   colors = auto | truecolor | 256 | 16 | none     (auto: detect, as without the line)
 *   light = camera | world | X,Y,Z                  (the viewer's light at start)
 *   spin = on | off                                 (auto-rotation at start)
 *   spin-timeout = SECONDS                          (an untouched spin pauses; 0 = never)
 *   bandwidth = RATE                                (as --bandwidth)
 *   glyphs = half | quadrant | sextant | braille | ascii   (how cells show pixels, cell.h) */
#ifndef RASTTY_CONFIG_H
#define RASTTY_CONFIG_H

#include <stdbool.h>

#include "err.h"
#include "options.h"
#include "vecmath.h"

enum config_light { CONFIG_UNSET, CONFIG_LIGHT_CAMERA, CONFIG_LIGHT_WORLD, CONFIG_LIGHT_DIR };

struct config {
    char colors[16];          /* "" = not set; else a --colors value */
    enum config_light light;
    vec3 light_dir;           /* CONFIG_LIGHT_DIR */
    int spin;                 /* -1 not set, 0 off, 1 on */
    double spin_timeout;      /* -1 not set */
    double bandwidth;         /* 0 not set */
    int glyphs;               /* -1 not set, else an enum cell_glyphs */
};

/* Read the file ($XDG_CONFIG_HOME/rastty/config, else $HOME/.config/rastty/config; NULL or
 * empty values count as unset), then RASTTY_COLORS (rastty_colors) over its colours. */
int config_load(const char *xdg_config_home, const char *home, const char *rastty_colors,
                struct config *c, struct err *e);
/* Parse one file's text (path for messages). */
int config_parse(const char *path, const char *text, struct config *c, struct err *e);
/* Fill what the command line left unset. */
void config_apply(const struct config *c, struct options *o);

#endif
