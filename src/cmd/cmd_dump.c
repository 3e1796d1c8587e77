/* cmd_dump.c: `rastty dump` — frames as ANSI text that replays with `cat`, and `rastty
 * ansi2ppm`, which decodes such text back to pixels.
 *
 * Output never assumes a terminal: no initialisation codes, no alternate screen; every frame
 * starts at the home position (ESC[H), so `cat frames.ans` plays them back in place. With
 * --diff, frames after the first carry only the cells that changed.
 * Colours: --colors, else on a terminal what it supports (termcaps.h; RASTTY_COLORS and the
 * config file's colors count there), else — a file or a pipe — truecolor, whatever TERM
 * says. Files and pipes get plain LF line ends (a tty playing them adds the CR).
 * --out FILE.cast writes an asciicast v2 recording instead (cast.h): frame k at k / --fps
 * seconds, the cursor hidden while it plays. */
#include "cmd.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/ioctl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cast.h"
#include "decode.h"
#include "encode.h"
#include "file.h"
#include "image.h"
#include "light.h"
#include "pipeline.h"
#include "prepare.h"
#include "ssaa.h"
#include "termcaps.h"
#include "timing.h"

/* Camera for frame k: from the path file, or the start camera orbited k * orbit degrees. */
struct camera_path {
    vec3 *eye, *target;
    int n;
};

static int path_load(const char *path, struct camera_path *cp, struct err *e)
{
    memset(cp, 0, sizeof *cp);
    char q[FILE_QUOTE_SIZE];
    file_quote(path, q, sizeof q);
    char *text;
    size_t len;
    int rc = file_read(path, FILE_MAX_TEXT, &text, &len);
    if (rc)
        return err_set(e, "%s: cannot open camera path: %s", q, file_strerror(rc));
    int lineno = 0, cap = 0;
    for (char *s = text, *end = text + len; rc == 0 && s < end;) {
        char *eol = memchr(s, '\n', (size_t)(end - s));
        eol = eol ? eol : end;
        *eol = '\0'; /* our buffer: each line becomes a C string */
        char *line = s;
        s = eol + 1;
        lineno++;
        if (strlen(line) != (size_t)(eol - line)) {
            rc = err_set(e, "%s:%d: binary data in camera path", q, lineno);
            break;
        }
        while (*line == ' ' || *line == '\t')
            line++;
        if (*line == '#' || *line == '\r' || *line == '\0')
            continue;
        double v[6];
        int used = 0;
        if (sscanf(line, "%lf %lf %lf %lf %lf %lf %n", &v[0], &v[1], &v[2], &v[3], &v[4], &v[5],
                   &used) != 6 || (line[used] != '\0' && line[used] != '#')) {
            rc = err_set(e, "%s:%d: expected 'ex ey ez tx ty tz'", q, lineno);
            break;
        }
        int finite = 1;
        for (int k = 0; k < 6; k++)
            finite &= isfinite(v[k]) != 0;
        if (!finite) {
            rc = err_set(e, "%s:%d: coordinates must be finite numbers", q, lineno);
            break;
        }
        if (v[0] == v[3] && v[1] == v[4] && v[2] == v[5]) {
            rc = err_set(e, "%s:%d: eye and target are the same point", q, lineno);
            break;
        }
        if (v[0] == v[3] && v[2] == v[5]) { /* straight up or down: the up vector is +Y */
            rc = err_set(e, "%s:%d: the camera must not look straight up or down", q, lineno);
            break;
        }
        if (cp->n == cap) {
            cap = cap ? cap * 2 : 64;
            vec3 *ne = realloc(cp->eye, (size_t)cap * sizeof *ne);
            vec3 *nt = ne ? realloc(cp->target, (size_t)cap * sizeof *nt) : NULL;
            if (ne)
                cp->eye = ne;
            if (!nt) {
                rc = err_set(e, "%s: out of memory", q);
                break;
            }
            cp->target = nt;
        }
        cp->eye[cp->n] = v3(v[0], v[1], v[2]);
        cp->target[cp->n] = v3(v[3], v[4], v[5]);
        cp->n++;
    }
    free(text);
    if (rc == 0 && cp->n == 0)
        rc = err_set(e, "%s: no camera positions", q);
    return rc;
}

static void path_free(struct camera_path *cp)
{
    free(cp->eye);
    free(cp->target);
}

static enum palette_mode color_mode(const struct options *o, bool to_tty)
{
    enum palette_mode m;
    if (o->colors && palette_mode_parse(o->colors, &m, NULL) == 0)
        return m;
    return to_tty ? termcaps_detect_env(NULL) : PALETTE_TRUECOLOR;
}

static bool ends_with(const char *s, const char *suffix)
{
    size_t n = strlen(s), k = strlen(suffix);
    return n >= k && strcmp(s + n - k, suffix) == 0;
}

int cmd_dump(const struct options *o, struct err *e)
{
    int cols = o->cols, rows = o->rows;
    if (!cols || !rows) {
        struct winsize ws;
        int tty = isatty(STDOUT_FILENO) && !o->out && ioctl(STDOUT_FILENO, TIOCGWINSZ, &ws) == 0 &&
                  ws.ws_col > 0 && ws.ws_row > 0;
        if (!cols)
            cols = tty ? ws.ws_col : 80;
        if (!rows)
            rows = tty ? ws.ws_row : 24;
    }
    char q[FILE_QUOTE_SIZE];
    if (o->ppm_dir) {
        struct stat st;
        if (stat(o->ppm_dir, &st) != 0 || !S_ISDIR(st.st_mode))
            return err_set(e, "rastty dump: --ppm-dir %s: not a directory",
                           file_quote(o->ppm_dir, q, sizeof q)), 2;
    }
    struct camera_path cp = {0};
    if (o->camera_path && path_load(o->camera_path, &cp, e)) {
        path_free(&cp);
        return 2;
    }
    struct scene *scene = malloc(sizeof *scene); /* ~28 KB: off the stack, as render's */
    if (!scene || prepare_scene(o, o->inputs[0], scene, NULL, 0, e)) {
        if (!scene)
            err_set(e, "out of memory");
        free(scene);
        path_free(&cp);
        return 2;
    }
    /* default: one frame, or one per camera-path line */
    int frames = o->frames ? o->frames : o->camera_path ? cp.n : 1;

    struct camera cam;
    struct render_opts ro;
    struct cell_geom geom = cell_geom(o->glyphs);
    double cell_r = o->cell_aspect > 0 ? o->cell_aspect : 1 / CELL_ASPECT; /* height/width */
    prepare_camera(o, scene, cols / (cell_r * rows), o->frame, &cam, &ro);
    /* a dump is what the viewer shows: its light, the headlight, unless --light X,Y,Z (or the
     * config file's light = world); render keeps the conventions' fixed light */
    bool headlight = o->light_camera || (!o->light_set && !o->light_world);
    bool to_tty = !o->out && isatty(STDOUT_FILENO);
    bool cast = o->out && ends_with(o->out, ".cast");
    struct encode_opts eo = {.mode = color_mode(o, to_tty),
                             .lf_newline = !to_tty && !cast,
                             .tolerance = o->tolerance > 0 ? o->tolerance : 0,
                             .dither = o->dither,
                             .mark_frames = true,
                             .glyphs = geom.glyphs,
                             .budget = o->budget};
    FILE *out = stdout;
    struct file_out fo = {0}; /* --out: written atomically, renamed at the end */
    int rc = 1;
    struct fb fb = {0};
    struct encode_screen es = {0};
    struct ssaa ss = {0};
    struct skybox tmp = {0};
    const struct skybox *sky;
    struct pipeline *p = pipeline_new();
    if (prepare_sky(o, scene, &ro, &tmp, &sky, e))
        goto done;
    if (!p) {
        err_set(e, "out of memory");
        goto done;
    }
    if (o->out) {
        if (file_out_open(&fo, o->out, e))
            goto done;
        out = fo.f;
    }
    if (fb_init(&fb, cell_fb_w(&geom, cols), cell_fb_h(&geom, rows), ro.view == VIEW_OVERDRAW, e) ||
        encode_screen_init(&es, cols, rows, e))
        goto done;
    fb.pixel_aspect = cell_pixel_aspect_r(&geom, cell_r);
    for (int k = 0; k < frames; k++) {
        struct camera c = cam;
        if (o->camera_path) {
            c.eye = cp.eye[k % cp.n];
            c.target = cp.target[k % cp.n];
        } else if (o->orbit_deg != 0) {
            camera_turn(&c, o->orbit_deg * k, 0, 1);
        }
        if (headlight) /* the headlight follows the camera */
            light_use_camera(&ro, &c);
        struct frame_stats st;
        if (ssaa_draw(&ss, p, scene->items, scene->n_items, sky, &c, &ro, &fb, &st, e))
            goto done;
        eo.diff = o->diff && k > 0;
        size_t n;
        struct encode_stats es_stats;
        double t0 = timing_now_ms();
        const char *bytes = encode_fb(&es, &fb, &eo, &n, &es_stats);
        double encode_ms = timing_now_ms() - t0;
        const char *name = strrchr(o->inputs[0], '/') ? strrchr(o->inputs[0], '/') + 1 : o->inputs[0];
        if (cast && ((k == 0 && (cast_header(out, cols, rows, timing_wall_s(), name) ||
                                 cast_event(out, 0, "\033[?25l", 6))) ||
                     cast_event(out, k / o->fps, bytes, n) ||
                     (k == frames - 1 && cast_event(out, (k + 1) / o->fps, "\033[?25h", 6)))) {
            err_set(e, "rastty dump: %s: write failed: %s", file_quote(o->out, q, sizeof q),
                    strerror(errno));
            goto done;
        }
        if (!cast && fwrite(bytes, 1, n, out) != n) {
            err_set(e, "rastty dump: %s: write failed: %s",
                    o->out ? file_quote(o->out, q, sizeof q) : "standard output", strerror(errno));
            goto done;
        }
        if (o->ppm_dir) {
            char path[4200];
            snprintf(path, sizeof path, "%s/frame-%04d.ppm", o->ppm_dir, k);
            if (image_write_ppm(path, &fb, e))
                goto done;
        }
        if (o->stats)
            fprintf(stderr, "frame %d: %zu bytes, %d cells, %.3f ms render, %.3f ms encode\n", k,
                    n, es_stats.cells_drawn, st.render_ms, encode_ms);
    }
    if (o->out) {
        out = NULL;
        if (file_out_commit(&fo, e))
            goto done;
    } else if (fflush(out) != 0) {
        err_set(e, "rastty dump: standard output: write failed: %s", strerror(errno));
        goto done;
    }
    rc = 0;
done:
    if (rc)
        file_out_abort(&fo); /* the old --out file stays as it was */
    encode_screen_free(&es);
    fb_free(&fb);
    ssaa_free(&ss);
    pipeline_destroy(p);
    skybox_free(&tmp);
    scene_free(scene);
    free(scene);
    path_free(&cp);
    return rc;
}

int cmd_ansi2ppm(const struct options *o, struct err *e)
{
    char q_out[FILE_QUOTE_SIZE];
    bool to_stdout = strcmp(o->out, "-") == 0;
    bool ppm = o->format && strcmp(o->format, "ppm") == 0;
    if (!to_stdout && !image_color_ext_ok(o->out))
        return err_set(e, "rastty ansi2ppm: --out %s: use a .ppm or .png file name (or - for "
                          "standard output)",
                       file_quote(o->out, q_out, sizeof q_out)), 2;
    if (to_stdout && isatty(STDOUT_FILENO))
        return err_set(e, "rastty ansi2ppm: --out -: standard output is a terminal; refusing to "
                          "write a %s image to it (redirect it: > x.png, or | a viewer)",
                       ppm ? "PPM" : "PNG"), 2;
    const char *path = o->inputs[0];
    bool in = strcmp(path, "-") == 0; /* `tmux capture-pane -e -p | rastty ansi2ppm - ...` */
    char q[FILE_QUOTE_SIZE];
    if (in)
        snprintf(q, sizeof q, "<stdin>");
    else
        file_quote(path, q, sizeof q);
    char *buf;
    size_t len;
    int read_rc = in ? file_read_stdin(FILE_MAX_ANSI, &buf, &len)
                     : file_read(path, FILE_MAX_ANSI, &buf, &len);
    if (read_rc)
        return err_set(e, "%s: cannot read: %s", q, file_strerror(read_rc)), 2;
    int cols, rows, frames, rc = 2;
    struct decode_state d = {0};
    struct cell_geom grid; /* the grid the glyphs need, unless --glyphs names one */
    if (decode_measure(buf, len, q, true, &cols, &rows, &frames, &grid, e) == 0) {
        if (o->glyphs_set)
            grid = cell_geom(o->glyphs);
        int k = o->frame_index >= 0 ? o->frame_index : frames - 1;
        if (k >= frames) {
            err_set(e, "%s: has %d frame%s, no frame %d", q, frames, frames == 1 ? "" : "s", k);
        } else if (decode_init(&d, cols, rows, grid, e) == 0) {
            d.name = q;
            d.text = true; /* a capture's status line and help box: their background */
            if (decode_frame(&d, buf, len, k, e) == 0) {
                if (d.text_cells)
                    fprintf(stderr, "%s: %d text cell%s (a status line, a help box) drawn as "
                                    "their background colour\n",
                            q, d.text_cells, d.text_cells == 1 ? "" : "s");
                struct fb fb = {.w = cell_fb_w(&grid, cols), .h = cell_fb_h(&grid, rows),
                                .rgb = d.rgb};
                rc = (to_stdout ? image_write_stdout(&fb, ppm, e)
                                : image_write_color(o->out, &fb, e)) ? 1 : 0;
            }
            decode_free(&d);
        }
    }
    free(buf);
    return rc;
}
