/* cmd_chart.c: `rastty bench --chart` and `rastty bench --sweep NAME` — the options, the files
 * and the terminal around chart.c and sweep.c. */
#include "bench.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/ioctl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "chart.h"
#include "plot.h"
#include "prepare.h"
#include "sweep.h"
#include "termcaps.h"

static FILE *create(const char *path, struct err *e)
{
    FILE *f = fopen(path, "w");
    if (!f)
        err_set(e, "rastty bench: %s: cannot create: %s", path, strerror(errno));
    return f;
}

static int close_file(FILE *f, const char *path, int rc, struct err *e)
{
    if (fclose(f) != 0 && rc == 0)
        return err_set(e, "rastty bench: %s: write failed", path), 1;
    return rc;
}

/* A picture in the terminal: as wide as it is (at most 200 columns), 40 rows when stdout is
 * not a terminal. */
static int draw_in_terminal(void (*draw)(const void *, struct plot *), const void *what,
                            struct err *e)
{
    int cols = 140, rows = 40;
    enum palette_mode mode = PALETTE_TRUECOLOR;
    struct winsize ws;
    if (isatty(STDOUT_FILENO)) {
        mode = termcaps_detect_env(NULL);
        if (ioctl(STDOUT_FILENO, TIOCGWINSZ, &ws) == 0 && ws.ws_col > 0 && ws.ws_row > 0) {
            cols = ws.ws_col > 200 ? 200 : ws.ws_col;
            rows = ws.ws_row - 2 > 60 ? 60 : ws.ws_row - 2;
        }
    }
    if (cols < 60 || rows < 16)
        return err_set(e, "rastty bench: the terminal is too small for the chart (%dx%d, "
                          "need 60x18): use --svg FILE", cols, rows + 2), 1;
    struct fb fb;
    struct cell_geom half = cell_geom(CELL_HALF); /* plot.c places its labels on half blocks */
    if (fb_init(&fb, cell_fb_w(&half, cols), cell_fb_h(&half, rows), false, e))
        return 1;
    struct plot p;
    plot_fb_begin(&p, &fb);
    draw(what, &p);
    int rc = plot_emit_terminal(&p, stdout, mode, e) ? 1 : 0;
    plot_free(&p);
    fb_free(&fb);
    return rc;
}

static void draw_chart(const void *c, struct plot *p)
{
    chart_draw(c, p);
}

static void draw_sweep(const void *r, struct plot *p)
{
    sweep_draw(r, p);
}

static int write_svg(void (*draw)(const void *, struct plot *), const void *what, int w, int h,
                     const char *title, const char *path, struct err *e)
{
    FILE *f = create(path, e);
    if (!f)
        return 1;
    struct plot p;
    plot_svg_begin(&p, f, w, h, title);
    draw(what, &p);
    int rc = plot_svg_end(&p, path, e) ? 1 : 0;
    return close_file(f, path, rc, e);
}

/* --models, else $RASTTY_SHARED/models, else ../shared/models; NULL when not a folder */
static const char *models_dir(const struct options *o, char *buf, size_t n)
{
    const char *shared = getenv("RASTTY_SHARED");
    if (o->models)
        snprintf(buf, n, "%s", o->models);
    else
        snprintf(buf, n, "%s/models", shared && *shared ? shared : "../shared");
    struct stat st;
    return stat(buf, &st) == 0 && S_ISDIR(st.st_mode) ? buf : NULL;
}

int cmd_bench_chart(const struct options *o, struct err *e)
{
    static const int sizes[2][2] = {{160, 96}, {640, 480}};
    int one[1][2] = {{o->width, o->height}};
    char assets[4200], models[4200];
    if (prepare_find_asset("demo.rsc", assets, sizeof assets))
        return err_set(e, "rastty bench --chart: cannot find the built-in assets (%s); run "
                          "'make' first", assets), 2;
    *strrchr(assets, '/') = '\0';
    struct chart_config c = {
        .assets_dir = assets,
        .models_dir = models_dir(o, models, sizeof models),
        .sizes = o->width ? (const int(*)[2])one : sizes,
        .n_sizes = o->width ? 1 : 2,
        .repeat = o->repeat ? o->repeat : 9,
        .progress = stderr,
    };
    if (o->models && !c.models_dir)
        return err_set(e, "rastty bench --chart: --models %s: not a folder", o->models), 2;
    struct chart ch;
    if (chart_run(&c, &ch, e))
        return 1;
    if (ch.note[0])
        fprintf(stderr, "chart: %s (looked in %s)\n", ch.note, models);
    int rc = 0;
    if (o->csv) {
        FILE *f = create(o->csv, e);
        rc = !f ? 1 : close_file(f, o->csv, chart_write_csv(&ch, f) ? 1 : 0, e);
    }
    if (rc == 0 && o->svg)
        rc = write_svg(draw_chart, &ch, 1200, 600, "rastty: speed against accuracy of every "
                                                   "method", o->svg, e);
    else if (rc == 0)
        rc = draw_in_terminal(draw_chart, &ch, e);
    if (rc == 0)
        chart_write_table(&ch, stdout);
    chart_free(&ch);
    return rc;
}

int cmd_bench_sweep(const struct options *o, struct err *e)
{
    int k = sweep_parse(o->sweep);
    if (k < 0) {
        char q[80], names[128] = ""; /* "grazing, ... or minification" */
        for (int i = 0; i < SWEEP_COUNT; i++) {
            size_t n = strlen(names);
            snprintf(names + n, sizeof names - n, "%s%s",
                     i == 0 ? "" : i == SWEEP_COUNT - 1 ? " or " : ", ",
                     sweep_name((enum sweep_kind)i));
        }
        return err_set(e, "rastty: --sweep: expected %s, got '%s'", names,
                       err_quote(o->sweep, strlen(o->sweep), 60, q, sizeof q)), 2;
    }
    int w = o->width ? o->width : 160, h = o->width ? o->height : 96;
    struct sweep_result *r = malloc(sizeof *r);
    if (!r)
        return err_set(e, "out of memory"), 1;
    int rc = sweep_run((enum sweep_kind)k, w, h, r, e) ? 1 : 0;
    if (rc == 0) {
        sweep_write_table(r, stdout);
        fflush(stdout);
    }
    if (rc == 0 && o->csv) {
        FILE *f = create(o->csv, e);
        rc = !f ? 1 : close_file(f, o->csv, sweep_write_csv(r, f) ? 1 : 0, e);
    }
    if (rc == 0 && o->svg) {
        char title[64];
        snprintf(title, sizeof title, "rastty sweep %s", r->name);
        rc = write_svg(draw_sweep, r, 900, 520, title, o->svg, e);
    }
    free(r);
    return rc;
}
