/* options.h: the command line, parsed once into one struct for every subcommand.
 *
 * rastty [view] [MODEL|SCENE.rsc ...]      interactive viewer (default)
 * rastty render MODEL --out FILE            one frame to PPM/PNG (+ PFM depth)
 * rastty dump MODEL                         frames as ANSI text
 * rastty ansi2ppm FILE.ans --out FILE.ppm   decode our ANSI output back to pixels
 * rastty bench [--chart | --sweep NAME]      benchmarks, the methods chart, stress sweeps
 * Flags are defined in one table (options.c) that also prints --help, so the two cannot
 * drift apart. Bad flags or values: err "rastty: --flag: problem", exit status 2. */
#ifndef RASTTY_OPTIONS_H
#define RASTTY_OPTIONS_H

#include <stdbool.h>
#include <stdio.h>

#include "camera.h"
#include "cell.h"
#include "err.h"
#include "model.h"
#include "render_opts.h"

#define OPTIONS_MAX_INPUTS 64

enum options_cmd { CMD_VIEW, CMD_RENDER, CMD_DUMP, CMD_ANSI2PPM, CMD_BENCH, CMD_HELP,
                   CMD_VERSION, CMD_COUNT };

struct options {
    enum options_cmd cmd;
    const char *inputs[OPTIONS_MAX_INPUTS];
    int n_inputs;
    int width, height;        /* --size; 0 = subcommand default */
    struct camera camera;
    bool camera_set;          /* any of --eye/--target/--up/--fov given */
    bool near_far_set;        /* --near or --far given */
    bool light_set, background_set;
    bool light_camera;        /* --light camera: the headlight (light.h) */
    bool light_world;         /* config light = world: the viewer starts with the world lights */
    bool sky_procedural;      /* --sky procedural */
    bool frame;               /* --frame: fit the camera to the model's bounding sphere */
    struct render_opts render;
    bool lod_set;             /* --lod given (the viewer's default is auto, the others' off) */
    const char *texture;      /* --texture */
    struct model_opts model;  /* how models are read: --crease, --up-axis, --allow-outside */
    const char *normal_map;   /* --normal-map */
    int file_camera;          /* --camera N: the file's camera N (1-based), 0 rastty's framing,
                                 -1 not given (the file's first, if any) */
    const char *out;          /* --out */
    const char *depth_out;    /* --depth-out */
    const char *format;       /* --format png|ppm: what --out - writes; NULL = png */
    bool stats;               /* --stats: print frame statistics to stderr */
    int repeat;               /* --repeat: render this many times (timing); 0 = not given */
    /* bench */
    bool chart;               /* --chart: speed against accuracy of every method */
    const char *sweep;        /* --sweep NAME: where each method fails */
    const char *csv, *svg;    /* --csv FILE, --svg FILE */
    const char *models;       /* --models DIR: the shared models (default ../shared/models) */
    /* dump / view */
    int cols, rows;           /* 0 = terminal size or 80x24 */
    int frames;
    double orbit_deg;
    const char *camera_path;
    const char *colors;       /* NULL = auto */
    int tolerance;            /* -1 = not given */
    bool dither;              /* ordered dithering in 256/16 colours */
    enum cell_glyphs glyphs;  /* --glyphs: how terminal cells show pixels (cell.h); it picks
                               * the framebuffer's grid and pixel shape and the encoder's
                               * glyphs */
    bool glyphs_set;          /* --glyphs given */
    bool diff;
    int budget;               /* dump --budget: bytes per frame, 0 = none */
    const char *ppm_dir;
    int frame_index;          /* ansi2ppm --frame K; -1 = the last */
    double fps;
    bool no_hud;
    double cell_aspect;       /* --cell-aspect: a cell's height / width; 0 = not given */
    int spin;                 /* --spin 1, --no-spin 0, not given -1 */
    double spin_timeout;      /* config spin-timeout; -1 = the default */
    double bandwidth;         /* --bandwidth in bytes/s, 0 = none */
};

/* "128000", "128k", "2M", "1Mbit", "500kB/s"... (k, M, G = 1000^n; bit/bps = 1/8 byte) ->
 * bytes per second, 1000 .. 1e12; -1 otherwise. */
int options_parse_rate(const char *s, double *bytes_s_out);
/* --glyphs's names, for the viewer's g key as for the flag */
extern const struct render_enum options_glyphs_names;
/* Fill defaults, then parse argv. Returns 0, or -1 with e set (a usage error). */
int options_parse(int argc, char **argv, struct options *out, struct err *e);
/* The --help text, generated from the flag table. */
void options_usage(FILE *f);

#endif
