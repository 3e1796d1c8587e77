/* options.c: the flag table, parsing and --help (see options.h). */
#include "options.h"

#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "fb.h"
#include "kernel.h"
#include "ssaa.h"

/* ARG_ENUM: the value is one of a render_enum's names, stored as an int at `field` (offset
 * into struct options); its --help line lists the names and the default from the table. */
enum arg { ARG_NONE, ARG_VALUE, ARG_ENUM };

/* which subcommands accept a flag */
#define C_VIEW (1u << CMD_VIEW)
#define C_RENDER (1u << CMD_RENDER)
#define C_DUMP (1u << CMD_DUMP)
#define C_A2P (1u << CMD_ANSI2PPM)
#define C_BENCH (1u << CMD_BENCH)
#define C_DRAW (C_VIEW | C_RENDER | C_DUMP) /* everything that renders a scene */

enum flag_id {
    F_SIZE, F_EYE, F_TARGET, F_UP, F_FOV, F_NEAR, F_FAR, F_ORTHO, F_FRAME, F_LIGHT, F_ENUM,
    F_TEXTURE, F_NO_TEXTURE, F_BACKGROUND, F_HIDDEN_LINES, F_OUT,
    F_DEPTH_OUT, F_STATS, F_REPEAT, F_THREADS, F_COLS, F_ROWS, F_FRAMES, F_ORBIT, F_CAMERA_PATH,
    F_COLORS, F_TOLERANCE, F_DITHER, F_DIFF, F_PPM_DIR, F_FRAME_INDEX, F_FPS, F_NO_HUD, F_CHART,
    F_SWEEP, F_CSV, F_SVG, F_MODELS, F_HELP, F_VERSION, F_SPIN, F_NO_SPIN, F_BANDWIDTH, F_SKY,
    F_LOD,
    F_GLYPHS, F_BUDGET, F_CREASE, F_UP_AXIS, F_NORMAL_MAP, F_CAMERA, F_ALLOW_OUTSIDE, F_FORMAT, F_CELL_ASPECT,
};

struct flag {
    const char *name;
    enum flag_id id;
    enum arg arg;
    unsigned cmds;
    const char *metavar, *help;
    const struct render_enum *values; /* ARG_ENUM */
    size_t field;                     /* ARG_ENUM: offsetof(struct options, ...) */
};

/* every enum field is an int underneath (the flag table writes them as ints) */
_Static_assert(sizeof(enum shade_mode) == sizeof(int) && sizeof(enum raster_method) == sizeof(int) &&
                   sizeof(enum thread_split) == sizeof(int),
               "enums are ints");
#define ENUM_FLAG(flag, cmds, what, table, member)                                         \
    {flag, F_ENUM, ARG_ENUM, cmds, "M", what, &table, offsetof(struct options, member)}

static const struct flag flags[] = {
    {"--size", F_SIZE, ARG_VALUE, C_RENDER | C_BENCH, "WxH", "framebuffer size in pixels (default 160x96; bench --chart: 160x96 and 640x480)", NULL, 0},
    {"--eye", F_EYE, ARG_VALUE, C_DRAW, "X,Y,Z", "camera position (default 0,0,3)", NULL, 0},
    {"--target", F_TARGET, ARG_VALUE, C_DRAW, "X,Y,Z", "point looked at (default 0,0,0)", NULL, 0},
    {"--up", F_UP, ARG_VALUE, C_DRAW, "X,Y,Z", "up direction (default 0,1,0)", NULL, 0},
    {"--fov", F_FOV, ARG_VALUE, C_DRAW, "DEG", "vertical field of view, 0.01..179.99 (default 50)", NULL, 0},
    {"--near", F_NEAR, ARG_VALUE, C_DRAW, "N", "near plane distance > 0 (default 0.1)", NULL, 0},
    {"--far", F_FAR, ARG_VALUE, C_DRAW, "F", "far plane distance > near (default 100)", NULL, 0},
    {"--ortho", F_ORTHO, ARG_VALUE, C_DRAW, "H", "orthographic projection, view height H", NULL, 0},
    {"--frame", F_FRAME, ARG_NONE, C_RENDER | C_DUMP, NULL, "move the camera to fit the model (keeps the view direction)", NULL, 0},
    {"--light", F_LIGHT, ARG_VALUE, C_DRAW | C_BENCH, "X,Y,Z|camera", "fixed light toward X,Y,Z (default 1,1,1), or the headlight (viewer default)", NULL, 0},
    ENUM_FLAG("--shade", C_DRAW | C_BENCH, "shading", render_shade_names, render.shade),
    {"--texture", F_TEXTURE, ARG_VALUE, C_DRAW, "FILE", "diffuse texture replacing the materials' (PNG, JPEG, TGA, BMP, GIF, PSD, PNM, HDR)", NULL, 0},
    {"--crease", F_CREASE, ARG_VALUE, C_DRAW | C_BENCH, "DEG", "a model without normals keeps edges where its faces turn by more than DEG sharp, 0..180 (default: 30; OBJ 180, one smooth normal per position; glTF 0, flat)", NULL, 0},
    {"--up-axis", F_UP_AXIS, ARG_VALUE, C_DRAW | C_BENCH, "x|y|z", "the model's axis that points up, turned to +Y (default: the file's metadata, else its format's convention: STL z, the others y)", NULL, 0},
    {"--normal-map", F_NORMAL_MAP, ARG_VALUE, C_DRAW, "FILE", "a normal map for every material without one: tangent or object space, or a bump map (told apart by its texels)", NULL, 0},
    {"--camera", F_CAMERA, ARG_VALUE, C_DRAW, "N", "view through the model file's camera N (1, 2, ...; 0: rastty's own framing); default: the file's first camera, if it has one", NULL, 0},
    {"--allow-outside", F_ALLOW_OUTSIDE, ARG_NONE, C_DRAW | C_BENCH, NULL, "let a glTF read buffers and images outside its folder (refused by default: a downloaded model must not draw another file of the machine)", NULL, 0},
    {"--no-texture", F_NO_TEXTURE, ARG_NONE, C_DRAW, NULL, "ignore all textures (albedo = Kd)", NULL, 0},
    ENUM_FLAG("--filter", C_DRAW | C_BENCH, "texture filter", render_filter_names, render.filter),
    ENUM_FLAG("--raster", C_DRAW | C_BENCH, "rasterizer", render_raster_names, render.raster),
    ENUM_FLAG("--persp", C_DRAW | C_BENCH, "varying interpolation", render_persp_names, render.persp),
    ENUM_FLAG("--depth", C_DRAW | C_BENCH, "depth buffer", render_depth_names, render.depth),
    {"--threads", F_THREADS, ARG_VALUE, C_DRAW | C_BENCH, "N", "rendering threads, 1..64 (default: $RASTTY_THREADS, else one per core)", NULL, 0},
    ENUM_FLAG("--split", C_DRAW | C_BENCH, "how threads share a frame: triangle slices merged by depth, screen tiles, or auto (slices for dense meshes at small sizes)", render_split_names, render.split),
    ENUM_FLAG("--kernel", C_DRAW | C_BENCH, "whose kernels draw ($RASTTY_SIMD sets the default): auto is avx2 where the CPU has it; ref is the scalar reference the others match byte for byte", render_kernel_names, render.kernel),
    ENUM_FLAG("--ssaa", C_DRAW | C_BENCH, "supersampling: M x M samples a pixel, box filter", render_ssaa_names, render.ssaa),
    {"--lod", F_LOD, ARG_VALUE, C_DRAW | C_BENCH, "M", "mesh level of detail: off, auto (the coarsest level whose error is under 0.15 px on screen and whose shading error, weighted by each material's liveliness, fits the mesh's share of the screen; auto:PX another bound), clusters (per cluster of a hierarchy for meshes of 16384 triangles or more, the same bound; clusters:PX) or RATIO (the level nearest that fraction of the triangles, 0..1) (default: auto in the viewer, else off)", NULL, 0},
    {"--background", F_BACKGROUND, ARG_VALUE, C_DRAW, "R,G,B", "background colour, 0..255 each (default 0,0,0)", NULL, 0},
    {"--sky", F_SKY, ARG_VALUE, C_DRAW, "procedural", "the generated sky behind the scene (the viewer's default)", NULL, 0},
    ENUM_FLAG("--cull", C_DRAW | C_BENCH, "face culling", render_cull_names, render.cull),
    ENUM_FLAG("--cluster-cull", C_DRAW | C_BENCH, "drop whole clusters of 64 triangles that cannot reach a pixel (outside the view, facing away when culled, between pixel centres, or with --hidden-cull behind the depth drawn so far) before their vertices are transformed; never changes a picture", render_cluster_cull_names, render.cluster_cull),
    ENUM_FLAG("--hidden-cull", C_DRAW | C_BENCH, "drop a triangle whose nearest corner is at or behind what the depth buffer already holds over its whole pixel box (the batches drawn so far, one thread at a time), before its vertices are lit or it is set up; never changes a picture", render_hidden_cull_names, render.hidden_cull),
    ENUM_FLAG("--occluders", C_DRAW | C_BENCH, "with --hidden-cull: draw each item's triangles of the last frame first, at this frame's view, into a depth of their own, and drop a cluster or triangle strictly behind them over its whole box before its vertices are made (on: an item whose occluders hide too little rests them a few frames; always: every frame); never changes a picture", render_occluders_names, render.occluders),
    {"--hidden-lines", F_HIDDEN_LINES, ARG_NONE, C_DRAW, NULL, "wire: hide edges behind the model's surfaces", NULL, 0},
    ENUM_FLAG("--wire", C_DRAW | C_BENCH, "wire: which edges: all, outline (silhouettes, creases and borders) or auto (all while readable: outline when they would light over half of the model's area)", render_wire_names, render.wire),
    ENUM_FLAG("--view", C_DRAW, "what the picture shows", render_view_names, render.view),
    {"--out", F_OUT, ARG_VALUE, C_RENDER | C_DUMP | C_A2P, "FILE", "output file (.ppm/.png; dump: .ans or .cast); - is standard output (render, ansi2ppm: never a terminal)", NULL, 0},
    {"--format", F_FORMAT, ARG_VALUE, C_RENDER | C_A2P, "png|ppm", "the image format of --out - (default png); a file's is its extension", NULL, 0},
    {"--depth-out", F_DEPTH_OUT, ARG_VALUE, C_RENDER, "FILE.pfm", "also write the depth buffer as PFM", NULL, 0},
    {"--stats", F_STATS, ARG_NONE, C_RENDER | C_DUMP, NULL, "print triangle/pixel counts and timings to stderr", NULL, 0},
    {"--repeat", F_REPEAT, ARG_VALUE, C_RENDER | C_BENCH, "N", "render the frame N times (timing; --stats prints median_ms=; bench --chart: frames timed per method, default 9)", NULL, 0},
    {"--cols", F_COLS, ARG_VALUE, C_DUMP | C_BENCH, "C", "terminal columns (dump: 80 or the terminal's; bench: 160)", NULL, 0},
    {"--rows", F_ROWS, ARG_VALUE, C_DUMP | C_BENCH, "R", "terminal rows (dump: 24 or the terminal's; bench: 48)", NULL, 0},
    {"--frames", F_FRAMES, ARG_VALUE, C_DUMP | C_BENCH, "N", "number of frames (dump: 1 or the camera path's length; bench: 180)", NULL, 0},
    {"--orbit", F_ORBIT, ARG_VALUE, C_DUMP | C_BENCH, "DEG", "orbit the camera around the target DEG per frame", NULL, 0},
    {"--camera-path", F_CAMERA_PATH, ARG_VALUE, C_DUMP, "FILE", "camera per frame: lines 'ex ey ez tx ty tz'", NULL, 0},
    {"--colors", F_COLORS, ARG_VALUE, C_VIEW | C_DUMP, "MODE", "truecolor|256|16|none (default: detect)", NULL, 0},
    {"--tolerance", F_TOLERANCE, ARG_VALUE, C_VIEW | C_DUMP, "N", "treat colour changes <= N per channel as unchanged", NULL, 0},
    {"--dither", F_DITHER, ARG_NONE, C_VIEW | C_DUMP, NULL, "256/16 colours: 4x4 ordered dithering (default off)", NULL, 0},
    {"--glyphs", F_GLYPHS, ARG_VALUE, C_VIEW | C_RENDER | C_DUMP | C_A2P | C_BENCH, "G", "how cells show pixels: half|quadrant|sextant|braille|ascii (default half; render: that grid's pixel shape; ansi2ppm: the grid the file's glyphs need)", NULL, 0},
    {"--diff", F_DIFF, ARG_NONE, C_DUMP, NULL, "frames after the first are diffs", NULL, 0},
    {"--budget", F_BUDGET, ARG_VALUE, C_DUMP, "BYTES", "at most BYTES a frame (colour modes): the cells whose error drops most per byte first", NULL, 0},
    {"--ppm-dir", F_PPM_DIR, ARG_VALUE, C_DUMP, "DIR", "also write each framebuffer as DIR/frame-NNNN.ppm", NULL, 0},
    {"--frame", F_FRAME_INDEX, ARG_VALUE, C_A2P, "K", "which frame to decode, 0-based (default: the last)", NULL, 0},
    {"--fps", F_FPS, ARG_VALUE, C_VIEW | C_DUMP, "N", "frame rate cap (view, default 60); dump: .cast timing (default 30)", NULL, 0},
    {"--bandwidth", F_BANDWIDTH, ARG_VALUE, C_VIEW, "RATE", "cap the bytes/s sent (128k, 1Mbit, 2M; default: what the link takes)", NULL, 0},
    {"--spin", F_SPIN, ARG_NONE, C_VIEW, NULL, "auto-rotate (the default for the demo only)", NULL, 0},
    {"--no-spin", F_NO_SPIN, ARG_NONE, C_VIEW, NULL, "do not auto-rotate", NULL, 0},
    {"--cell-aspect", F_CELL_ASPECT, ARG_VALUE, C_DRAW, "R", "a terminal cell's height / width, 0.5..4 (view: default the terminal's, from its pixel size or ESC[16t, else 2; render, dump: 2), so circles stay round", NULL, 0},
    {"--no-hud", F_NO_HUD, ARG_NONE, C_VIEW, NULL, "start with the status line hidden (H shows it)", NULL, 0},
    {"--chart", F_CHART, ARG_NONE, C_BENCH, NULL, "speed against accuracy of every method on the scene set", NULL, 0},
    {"--sweep", F_SWEEP, ARG_VALUE, C_BENCH, "NAME", "where methods fail: grazing|depthrange|magnitude|sliver|nearplane|minification", NULL, 0},
    {"--csv", F_CSV, ARG_VALUE, C_BENCH, "FILE", "--chart/--sweep: also write the numbers as CSV", NULL, 0},
    {"--svg", F_SVG, ARG_VALUE, C_BENCH, "FILE", "--chart/--sweep: draw the chart as SVG (chart: else in the terminal)", NULL, 0},
    {"--models", F_MODELS, ARG_VALUE, C_BENCH, "DIR", "--chart: the shared models (default $RASTTY_SHARED/models or ../shared/models)", NULL, 0},
    {"--help", F_HELP, ARG_NONE, ~0u, NULL, "show this help", NULL, 0},
    {"--version", F_VERSION, ARG_NONE, ~0u, NULL, "show the version", NULL, 0},
};

const struct render_enum options_glyphs_names = {cell_glyphs_names, CELL_GLYPHS_COUNT};

static const char *const cmd_names[CMD_COUNT] = {"view", "render", "dump", "ansi2ppm", "bench",
                                                 "help", "version"};

/* "a, b or c" (sep = ", ", last = " or ") or "a|b|c" (both "|") */
static void enum_list(const struct render_enum *t, const char *sep, const char *last, char *out,
                      size_t n)
{
    size_t len = 0;
    out[0] = '\0';
    for (int i = 0; i < t->n && len < n; i++) {
        const char *s = i == 0 ? "" : i == t->n - 1 ? last : sep;
        int w = snprintf(out + len, n - len, "%s%s", s, t->names[i]);
        len += w > 0 ? (size_t)w : 0;
    }
}

static int bad(struct err *e, const char *flag, const char *why, const char *val)
{
    char q[80];
    if (!val)
        return err_set(e, "rastty: %s: %s", flag, why);
    return err_set(e, "rastty: %s: %s, got '%s'", flag, why,
                   err_quote(val, strlen(val), 60, q, sizeof q));
}

static int parse_double(const char *s, double *out)
{
    char *end;
    double v = strtod(s, &end);
    if (end == s || *end || !isfinite(v))
        return -1;
    *out = v;
    return 0;
}

static int parse_int(const char *s, long lo, long hi, int *out)
{
    char *end;
    long v = strtol(s, &end, 10);
    if (end == s || *end || v < lo || v > hi)
        return -1;
    *out = (int)v;
    return 0;
}

/* "x,y,z" -> n doubles */
static int parse_list(const char *s, double *v, int n)
{
    char buf[256];
    if (strlen(s) >= sizeof buf)
        return -1;
    strcpy(buf, s);
    char *p = buf;
    for (int i = 0; i < n; i++) {
        char *comma = strchr(p, ',');
        if ((comma == NULL) != (i == n - 1))
            return -1;
        if (comma)
            *comma = '\0';
        if (parse_double(p, &v[i]))
            return -1;
        p = comma ? comma + 1 : p;
    }
    return 0;
}

static bool is_zero(vec3 a)
{
    return a.x == 0 && a.y == 0 && a.z == 0;
}

/* a / max|component|: same direction, length in [1, sqrt 3], so products cannot overflow
 * or underflow (1e200 and 1e-300 are valid coordinates) */
static vec3 unit_scale(vec3 a)
{
    double m = fmax(fabs(a.x), fmax(fabs(a.y), fabs(a.z)));
    return m > 0 ? v3_scale(a, 1.0 / m) : a;
}

static int parse_vec3(const char *s, vec3 *out)
{
    double v[3];
    if (parse_list(s, v, 3))
        return -1;
    *out = v3(v[0], v[1], v[2]);
    return 0;
}

static int parse_size(const char *s, int *w, int *h)
{
    char buf[64], *x;
    if (strlen(s) >= sizeof buf)
        return -1;
    strcpy(buf, s);
    if (!(x = strchr(buf, 'x')))
        return -1;
    *x = '\0';
    return parse_int(buf, 1, FB_MAX_DIM, w) || parse_int(x + 1, 1, FB_MAX_DIM, h) ? -1 : 0;
}

/* --lod: off | auto | auto:PX | clusters | clusters:PX | RATIO */
static int parse_lod(const char *s, struct render_opts *r)
{
    double d;
    if (strcmp(s, "clusters") == 0 || strncmp(s, "clusters:", 9) == 0) {
        d = LOD_DEFAULT_PX;
        if (s[8] == ':' && (parse_double(s + 9, &d) || !(d > 0 && d <= 1e6)))
            return -1;
        r->lod = LOD_CLUSTERS;
        r->lod_px = (float)d;
        return 0;
    }
    if (strcmp(s, "off") == 0 || strcmp(s, "auto") == 0) {
        r->lod = s[0] == 'o' ? LOD_OFF : LOD_AUTO;
        r->lod_px = LOD_DEFAULT_PX;
        return 0;
    }
    if (strncmp(s, "auto:", 5) == 0) {
        if (parse_double(s + 5, &d) || !(d > 0 && d <= 1e6))
            return -1;
        r->lod = LOD_AUTO;
        r->lod_px = (float)d;
        return 0;
    }
    if (parse_double(s, &d) || !(d > 0 && d <= 1))
        return -1;
    r->lod = LOD_RATIO;
    r->lod_ratio = (float)d;
    return 0;
}

static void defaults(struct options *o)
{
    memset(o, 0, sizeof *o);
    camera_default(&o->camera);
    render_opts_default(&o->render);
    o->frames = 0; /* not given: each subcommand picks its default */
    o->frame_index = -1;
    o->tolerance = -1; /* not given: each subcommand picks its default */
    o->fps = 0;        /* not given: view 60, dump 30 */
    o->spin = -1;
    o->file_camera = -1;
    o->spin_timeout = -1;
}

static int apply(struct options *o, const struct flag *f, const char *v, struct err *e)
{
    double d;
    double rgb[3];
    int k;
    switch (f->id) {
    case F_SIZE:
        if (parse_size(v, &o->width, &o->height))
            return bad(e, f->name, "expected WxH, each 1..8192", v);
        return 0;
    case F_EYE:
    case F_TARGET:
    case F_UP: {
        vec3 *dst = f->id == F_EYE ? &o->camera.eye : f->id == F_TARGET ? &o->camera.target
                                                                         : &o->camera.up;
        if (parse_vec3(v, dst))
            return bad(e, f->name, "expected three numbers X,Y,Z", v);
        o->camera_set = true;
        return 0;
    }
    case F_FOV:
        /* 0.01 .. 179.99: beyond that the projection overflows double precision */
        if (parse_double(v, &d) || !(d >= 0.01 && d <= 179.99))
            return bad(e, f->name, "expected degrees between 0.01 and 179.99", v);
        o->camera.fov_deg = d;
        o->camera_set = true;
        return 0;
    case F_NEAR:
    case F_FAR:
        if (parse_double(v, &d) || !(d > 0))
            return bad(e, f->name, "expected a positive distance", v);
        *(f->id == F_NEAR ? &o->camera.near : &o->camera.far) = d;
        o->near_far_set = true;
        return 0;
    case F_ORTHO:
        if (parse_double(v, &d) || !(d > 0))
            return bad(e, f->name, "expected a positive view height", v);
        o->camera.ortho_height = d;
        return 0;
    case F_FRAME: o->frame = true; return 0;
    case F_LIGHT:
        if (strcmp(v, "camera") == 0) {
            o->light_camera = true;
            return 0;
        }
        if (parse_vec3(v, &o->render.lights[0].dir) || is_zero(o->render.lights[0].dir))
            return bad(e, f->name, "expected a non-zero direction X,Y,Z or camera", v);
        o->light_set = true;
        o->light_camera = false;
        return 0;
    case F_SKY:
        if (strcmp(v, "procedural") != 0)
            return bad(e, f->name, "expected procedural", v);
        o->sky_procedural = true;
        return 0;
    case F_SPIN: o->spin = 1; return 0;
    case F_NO_SPIN: o->spin = 0; return 0;
    case F_BANDWIDTH:
        if (options_parse_rate(v, &o->bandwidth))
            return bad(e, f->name, "expected bytes per second >= 1000, like 128000, 128k, "
                                   "1Mbit or 2M", v);
        return 0;
    case F_ENUM:
        if ((k = render_enum_parse(f->values, v)) < 0) {
            char want[160];
            enum_list(f->values, ", ", " or ", want, sizeof want);
            char why[192];
            snprintf(why, sizeof why, "expected %s", want);
            return bad(e, f->name, why, v);
        }
        memcpy((char *)o + f->field, &k, sizeof k);
        return 0;
    case F_TEXTURE: o->texture = v; return 0;
    case F_NO_TEXTURE: o->render.textures = false; return 0;
    case F_BACKGROUND:
        if (parse_list(v, rgb, 3))
            return bad(e, f->name, "expected R,G,B in 0..255", v);
        for (int i = 0; i < 3; i++) {
            if (!(rgb[i] >= 0 && rgb[i] <= 255) || rgb[i] != floor(rgb[i]))
                return bad(e, f->name, "expected R,G,B in 0..255", v);
            o->render.background[i] = (uint8_t)rgb[i];
        }
        o->background_set = true;
        return 0;
    case F_HIDDEN_LINES: o->render.hidden_lines = true; return 0;
    case F_OUT: o->out = v; return 0;
    case F_DEPTH_OUT: o->depth_out = v; return 0;
    case F_STATS: o->stats = true; return 0;
    case F_THREADS:
        if (parse_int(v, 1, 64, &o->render.threads))
            return bad(e, f->name, "expected a thread count 1..64", v);
        return 0;
    case F_REPEAT:
        if (parse_int(v, 1, 100000, &o->repeat))
            return bad(e, f->name, "expected a count 1..100000", v);
        return 0;
    case F_COLS:
    case F_ROWS:
        if (parse_int(v, 1, FB_MAX_DIM / 2, f->id == F_COLS ? &o->cols : &o->rows))
            return bad(e, f->name, "expected a count 1..4096", v);
        return 0;
    case F_FRAMES:
        if (parse_int(v, 1, 1000000, &o->frames))
            return bad(e, f->name, "expected a frame count 1..1000000", v);
        return 0;
    case F_ORBIT:
        if (parse_double(v, &o->orbit_deg))
            return bad(e, f->name, "expected degrees per frame", v);
        return 0;
    case F_CAMERA_PATH: o->camera_path = v; return 0;
    case F_COLORS:
        if (strcmp(v, "truecolor") && strcmp(v, "256") && strcmp(v, "16") && strcmp(v, "none"))
            return bad(e, f->name, "expected truecolor, 256, 16 or none", v);
        o->colors = v;
        return 0;
    case F_TOLERANCE:
        if (parse_int(v, 0, 255, &o->tolerance))
            return bad(e, f->name, "expected 0..255", v);
        return 0;
    case F_DITHER: o->dither = true; return 0;
    case F_GLYPHS:
        if ((k = cell_glyphs_parse(v)) < 0)
            return bad(e, f->name, "expected half, quadrant, sextant, braille or ascii", v);
        o->glyphs = (enum cell_glyphs)k;
        o->glyphs_set = true;
        return 0;
    case F_DIFF: o->diff = true; return 0;
    case F_BUDGET:
        if (parse_int(v, 64, 1000000000, &o->budget))
            return bad(e, f->name, "expected bytes per frame, 64..1000000000", v);
        return 0;
    case F_PPM_DIR: o->ppm_dir = v; return 0;
    case F_FRAME_INDEX:
        if (parse_int(v, 0, 100000000, &o->frame_index))
            return bad(e, f->name, "expected a frame number >= 0", v);
        return 0;
    case F_FPS:
        if (parse_double(v, &o->fps) || !(o->fps >= 1 && o->fps <= 1000))
            return bad(e, f->name, "expected 1..1000 frames per second", v);
        return 0;
    case F_NO_HUD: o->no_hud = true; return 0;
    case F_CHART: o->chart = true; return 0;
    case F_SWEEP: o->sweep = v; return 0; /* (its name: cmd_bench_sweep checks it) */
    case F_CSV: o->csv = v; return 0;
    case F_SVG: o->svg = v; return 0;
    case F_MODELS: o->models = v; return 0;
    case F_LOD:
        if (parse_lod(v, &o->render))
            return bad(e, f->name, "expected off, auto, auto:PX (pixels > 0), clusters, clusters:PX or RATIO (a fraction "
                                   "of the triangles, 0 < RATIO <= 1)", v);
        o->lod_set = true;
        return 0;
    case F_CREASE: {
        double deg;
        if (parse_double(v, &deg) || !(deg >= 0 && deg <= 180))
            return bad(e, f->name, "expected an angle in degrees, 0..180", v);
        o->model.crease_set = true;
        o->model.crease_deg = (float)deg;
        return 0;
    }
    case F_UP_AXIS:
        if (strlen(v) != 1 || !strchr("xyzXYZ", v[0]))
            return bad(e, f->name, "expected x, y or z", v);
        o->model.up = (v[0] | 0x20) == 'x' ? MODEL_UP_X : (v[0] | 0x20) == 'y' ? MODEL_UP_Y
                                                                                : MODEL_UP_Z;
        return 0;
    case F_NORMAL_MAP: o->normal_map = v; return 0;
    case F_CAMERA:
        if (parse_int(v, 0, MESH_MAX_CAMERAS, &o->file_camera))
            return bad(e, f->name, "expected a camera number 0..64", v);
        return 0;
    case F_ALLOW_OUTSIDE: o->model.any_path = true; return 0;
    case F_CELL_ASPECT:
        if (parse_double(v, &o->cell_aspect) ||
            !(o->cell_aspect >= CELL_ASPECT_MIN && o->cell_aspect <= CELL_ASPECT_MAX))
            return bad(e, f->name, "expected a cell's height / width, 0.5..4", v);
        return 0;
    case F_FORMAT:
        if (strcmp(v, "png") != 0 && strcmp(v, "ppm") != 0)
            return bad(e, f->name, "expected png or ppm", v);
        o->format = v;
        return 0;
    case F_HELP: o->cmd = CMD_HELP; return 0;
    case F_VERSION: o->cmd = CMD_VERSION; return 0;
    }
    return 0;
}

static int validate(struct options *o, struct err *e)
{
    struct camera *c = &o->camera;
    if (!(c->far > c->near))
        return err_set(e, "rastty: --far (%g) must be greater than --near (%g)", c->far, c->near);
    vec3 dir = v3_sub(c->target, c->eye);
    if (is_zero(dir) || !isfinite(dir.x) || !isfinite(dir.y) || !isfinite(dir.z))
        return err_set(e, "rastty: --eye and --target must differ (by a finite distance)");
    if (is_zero(c->up) || v3_len(v3_cross(unit_scale(dir), unit_scale(c->up))) <= 1e-9)
        return err_set(e, "rastty: --up must not be parallel to the view direction (or zero)");
    if (!kernel_set(o->render.kernel))
        return err_set(e, "rastty: --kernel %s: not available on this CPU or in this build",
                       render_kernel_names.names[o->render.kernel]);
    int stdin_inputs = 0;
    for (int i = 0; i < o->n_inputs; i++)
        stdin_inputs += strcmp(o->inputs[i], "-") == 0;
    if (stdin_inputs > 1)
        return err_set(e, "rastty: - (standard input) may be given once");
    if (o->format && o->out && strcmp(o->out, "-") != 0)
        return err_set(e, "rastty: --format %s is for --out - (standard output); a file's format "
                          "is its extension", o->format);
    if (o->depth_out && strcmp(o->depth_out, "-") == 0)
        return err_set(e, "rastty render: --depth-out -: the depth goes to a file (FILE.pfm)");
    switch (o->cmd) {
    case CMD_RENDER:
        if (o->n_inputs != 1)
            return err_set(e, "rastty render: expected one MODEL or SCENE.rsc (see rastty --help)");
        if (!o->out)
            return err_set(e, "rastty render: --out FILE.ppm|FILE.png is required");
        if (o->width == 0)
            o->width = 160, o->height = 96;
        if (o->repeat == 0)
            o->repeat = 1;
        if (ssaa_check(o->render.ssaa, o->width, o->height, e))
            return -1;
        break;
    case CMD_DUMP:
        if (o->out && strcmp(o->out, "-") == 0) /* standard output, as without --out */
            o->out = NULL;
        if (o->n_inputs != 1)
            return err_set(e, "rastty dump: expected one MODEL or SCENE.rsc (see rastty --help)");
        if (o->cols && o->rows) {
            struct cell_geom g = cell_geom(o->glyphs);
            if (ssaa_check(o->render.ssaa, cell_fb_w(&g, o->cols), cell_fb_h(&g, o->rows), e))
                return -1;
        }
        break;
    case CMD_ANSI2PPM:
        if (o->n_inputs != 1 || !o->out)
            return err_set(e, "rastty ansi2ppm: expected FILE.ans and --out FILE.ppm");
        break;
    case CMD_BENCH:
        if (o->chart && o->sweep)
            return err_set(e, "rastty bench: --chart and --sweep are separate runs");
        if (!o->chart && !o->sweep && (o->csv || o->svg || o->models || o->width || o->repeat))
            return err_set(e, "rastty bench: --csv, --svg, --models, --size and --repeat go with "
                              "--chart or --sweep");
        if (o->sweep && (o->models || o->repeat))
            return err_set(e, "rastty bench --sweep: --models and --repeat are --chart's");
        if (o->chart && o->n_inputs)
            return err_set(e, "rastty bench --chart: draws its own scene set (no MODEL "
                              "arguments; --models DIR for the shared models)");
        if (o->width && ssaa_check(SSAA_8, o->width, o->height, e)) /* the ideal image */
            return -1;
        break;
    default:
        break;
    }
    return 0;
}

int options_parse_rate(const char *s, double *bytes_s_out)
{
    char *end;
    double v = strtod(s, &end);
    if (end == s || !isfinite(v))
        return -1;
    switch (*end) {
    case 'k': case 'K': v *= 1e3, end++; break;
    case 'M': v *= 1e6, end++; break;
    case 'G': v *= 1e9, end++; break;
    default: break;
    }
    if (strcmp(end, "bit") == 0 || strcmp(end, "bit/s") == 0 || strcmp(end, "bps") == 0)
        v /= 8;
    else if (*end && strcmp(end, "B") != 0 && strcmp(end, "B/s") != 0)
        return -1;
    if (!(v >= 1000 && v <= 1e12))
        return -1;
    *bytes_s_out = v;
    return 0;
}

/* Edit distance (insertions, deletions, substitutions, adjacent swaps) between a[0..la)
 * and b; saturates at 9 (only small distances matter). */
static int distance(const char *a, size_t la, const char *b)
{
    size_t lb = strlen(b);
    if (la > 40 || lb > 40)
        return 9;
    int d[41][41];
    for (size_t i = 0; i <= la; i++)
        for (size_t j = 0; j <= lb; j++) {
            if (i == 0 || j == 0) {
                d[i][j] = (int)(i + j);
                continue;
            }
            int best = d[i - 1][j - 1] + (a[i - 1] != b[j - 1]);
            best = d[i - 1][j] + 1 < best ? d[i - 1][j] + 1 : best;
            best = d[i][j - 1] + 1 < best ? d[i][j - 1] + 1 : best;
            if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] &&
                d[i - 2][j - 2] + 1 < best)
                best = d[i - 2][j - 2] + 1;
            d[i][j] = best;
        }
    return d[la][lb] < 9 ? d[la][lb] : 9;
}

/* The name closest to word among n names (stride bytes apart), if close enough to be a typo:
 * at most 2 edits, and fewer than half the word. */
static const char *nearest(const char *word, size_t len, const char *const *names, size_t n,
                           size_t stride)
{
    const char *best = NULL;
    int best_d = 3;
    for (size_t i = 0; i < n; i++) {
        const char *name = *(const char *const *)((const char *)names + i * stride);
        int d = distance(word, len, name);
        if (d < best_d && 2 * (size_t)d < len) {
            best_d = d;
            best = name;
        }
    }
    return best;
}

int options_parse(int argc, char **argv, struct options *o, struct err *e)
{
    defaults(o);
    const char *env = getenv("RASTTY_THREADS"); /* --threads overrides it */
    if (env && *env && parse_int(env, 1, 64, &o->render.threads))
        return bad(e, "RASTTY_THREADS", "expected a thread count 1..64", env);
    env = getenv("RASTTY_SIMD"); /* the kernels' instruction set (kernel.h); --kernel overrides */
    if (env && *env) {
        int k = render_enum_parse(&render_kernel_names, env);
        if (k < 0)
            return bad(e, "RASTTY_SIMD", "expected auto, ref, sse2, avx2, avx2-4 or avx2-8", env);
        if (!kernel_set((enum kernel_isa)k))
            return bad(e, "RASTTY_SIMD", "avx2 is not available on this CPU or build", env);
        o->render.kernel = (enum kernel_isa)k;
    }
    int i = 1;
    if (argc > 1 && argv[1][0] != '-') {
        for (int c = 0; c < CMD_COUNT; c++)
            if (strcmp(argv[1], cmd_names[c]) == 0) {
                o->cmd = (enum options_cmd)c;
                i = 2;
            }
        /* not a subcommand, not a file, no dot or slash, but close to a subcommand: a typo */
        const char *near = nearest(argv[1], strlen(argv[1]), cmd_names, CMD_COUNT,
                                   sizeof cmd_names[0]);
        if (i == 1 && near && !strpbrk(argv[1], "./") && access(argv[1], F_OK) != 0) {
            char q[80];
            return err_set(e, "rastty: unknown subcommand '%s' (did you mean %s? see rastty --help)",
                           err_quote(argv[1], strlen(argv[1]), 60, q, sizeof q), near);
        }
    }
    enum options_cmd cmd = o->cmd;
    bool only_inputs = false;
    for (; i < argc; i++) {
        const char *a = argv[i];
        if (only_inputs || a[0] != '-' || a[1] == '\0') {
            if (o->n_inputs == OPTIONS_MAX_INPUTS)
                return err_set(e, "rastty: too many input files (limit %d)", OPTIONS_MAX_INPUTS);
            o->inputs[o->n_inputs++] = a;
            continue;
        }
        if (strcmp(a, "--") == 0) {
            only_inputs = true;
            continue;
        }
        if (strcmp(a, "-h") == 0)
            a = "--help";
        const char *eq = strchr(a, '=');
        size_t len = eq ? (size_t)(eq - a) : strlen(a);
        /* a name may mean different things to different subcommands (--frame): take the
         * entry for this subcommand, else report the name as not applying here */
        const struct flag *f = NULL, *named = NULL;
        for (size_t k = 0; k < sizeof flags / sizeof flags[0]; k++)
            if (strlen(flags[k].name) == len && strncmp(flags[k].name, a, len) == 0) {
                named = &flags[k];
                if (flags[k].cmds & (1u << cmd))
                    f = &flags[k];
            }
        char q[80];
        if (!named) {
            /* the nearest flag of this subcommand, else of any */
            const char *mine[sizeof flags / sizeof flags[0]];
            size_t n_mine = 0;
            for (size_t k = 0; k < sizeof flags / sizeof flags[0]; k++)
                if (flags[k].cmds & (1u << cmd))
                    mine[n_mine++] = flags[k].name;
            const char *near = nearest(a, len, mine, n_mine, sizeof mine[0]);
            if (!near)
                near = nearest(a, len, &flags[0].name, sizeof flags / sizeof flags[0],
                               sizeof flags[0]);
            if (near)
                return err_set(e, "rastty: unknown option '%s' (did you mean %s? see rastty --help)",
                               err_quote(a, len, 60, q, sizeof q), near);
            return err_set(e, "rastty: unknown option '%s' (see rastty --help)",
                           err_quote(a, len, 60, q, sizeof q));
        }
        if (!f)
            return err_set(e, "rastty %s: %s does not apply here (see rastty --help)",
                           cmd_names[cmd], named->name);
        const char *v = NULL;
        if (f->arg != ARG_NONE) {
            if (eq)
                v = eq + 1;
            else if (i + 1 < argc)
                v = argv[++i];
            else
                return bad(e, f->name, "needs a value", NULL);
        } else if (eq) {
            return bad(e, f->name, "takes no value", NULL);
        }
        if (apply(o, f, v, e))
            return -1;
    }
    if (o->cmd == CMD_HELP || o->cmd == CMD_VERSION)
        return 0;
    if (o->fps == 0)
        o->fps = o->cmd == CMD_DUMP ? 30 : 60;
    return validate(o, e);
}

void options_usage(FILE *out)
{
    struct options dflt;
    defaults(&dflt);
    fprintf(out,
            "usage: rastty [view] [MODEL|SCENE.rsc ...]   interactive viewer (no file: demo)\n"
            "       rastty render MODEL --out FILE.ppm|FILE.png|- [options]\n"
            "       rastty dump MODEL [--out FILE.ans|-] [options]\n"
            "       rastty ansi2ppm FILE.ans --out FILE.ppm|FILE.png|- [--frame K]\n"
            "       rastty bench [options]\n\noptions:\n");
    for (size_t k = 0; k < sizeof flags / sizeof flags[0]; k++) {
        const struct flag *f = &flags[k];
        char left[48];
        snprintf(left, sizeof left, "%s%s%s%s", f->name, f->id == F_HELP ? ", -h" : "",
                 f->metavar ? " " : "", f->metavar ? f->metavar : "");
        if (f->arg == ARG_ENUM) {
            char names[160];
            int def;
            memcpy(&def, (const char *)&dflt + f->field, sizeof def);
            enum_list(f->values, "|", "|", names, sizeof names);
            fprintf(out, "  %-24s %s: %s (default %s) [", left, f->help, names,
                    f->values->names[def]);
        } else {
            fprintf(out, "  %-24s %s [", left, f->help);
        }
        const char *sep = "";
        for (int c = 0; c < CMD_HELP; c++)
            if (f->cmds & (1u << c) && f->cmds != ~0u) {
                fprintf(out, "%s%s", sep, cmd_names[c]);
                sep = ",";
            }
        fprintf(out, "%s]\n", f->cmds == ~0u ? "all" : "");
    }
    fprintf(out, "\nMODEL: OBJ, STL, PLY, glTF/GLB, FBX, COLLADA, 3DS, ... (format by content); - reads it\n"
                 "from standard input (its MTL and textures relative to the current folder).\n"
                 "Exit status: 0 success (a material's missing texture or library is only a\n"
                 "warning), 1 runtime failure, 2 bad usage or a bad file named on the command line.\n"
                 "See rastty(1) for keys, the scene format and examples.\n");
}
