/* view_hud.c: the status line and the help overlay's place (see view_hud.h). */
#include "view_hud.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#define MAX_FIELDS 20

struct fields {
    int n;
    int prio[MAX_FIELDS]; /* 0 = always shown; larger = dropped sooner */
    char text[MAX_FIELDS][96];
};

static void add(struct fields *f, int prio, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));
static void add(struct fields *f, int prio, const char *fmt, ...)
{
    if (f->n == MAX_FIELDS)
        return;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(f->text[f->n], sizeof f->text[0], fmt, ap);
    va_end(ap);
    f->prio[f->n++] = prio;
}

/* a triangle count: as it is below 1000, else in thousands ("149.6k") */
static void tri_count(unsigned long long n, char *out, size_t cap)
{
    if (n < 1000)
        snprintf(out, cap, "%llu", n);
    else
        snprintf(out, cap, "%.1fk", (double)n / 1e3);
}

/* length of " a | b | c" */
static size_t line_len(const struct fields *f, const bool *drop)
{
    size_t len = 0;
    for (int i = 0; i < f->n; i++)
        if (!drop[i])
            len += strlen(f->text[i]) + (len ? 3 : 1);
    return len;
}

void view_hud_compose(const struct view_state *s, const struct view_hud_info *in, int width,
                      double now, char *out, size_t n)
{
    if (s->message_until > now) {
        char count[32] = "";
        if (in->frames)
            snprintf(count, sizeof count, " | #%lu", in->frames);
        /* a message too long for the line is cut, not the count after it */
        int room = width - 3 - (int)strlen(count);
        snprintf(out, n, " %.*s%s ", room > 0 ? room : 0, s->message, count);
        return;
    }
    struct fields f = {0};
    const struct frame_stats *st = in->st;
    add(&f, 0, "%s [%d/%d]", in->scene, in->scene_i + 1, in->n_scenes);
    /* the filter only where there is a texture to filter; "textured" without one draws phong */
    bool textured = in->texture && s->ro.textures;
    const char *shade = view_shade_name(s);
    if (textured && strcmp(shade, "textured") == 0)
        add(&f, 0, "%s %s", shade, render_filter_name(s->ro.filter));
    else
        add(&f, 0, "%s", strcmp(shade, "textured") == 0 ? "phong" : shade);
    if (s->glyphs != CELL_HALF)
        add(&f, 0, "%s %s", palette_mode_name(in->mode), cell_glyphs_name(s->glyphs));
    else
        add(&f, 0, "%s", palette_mode_name(in->mode));
    add(&f, 0, "%.0f fps", in->fps);
    if (in->frames)
        add(&f, 0, "#%lu", in->frames);
    if (in->pacing && in->pacing[0])
        add(&f, 1, "%s", in->pacing);
    if (s->ro.view != VIEW_COLOR)
        add(&f, 1, "view:%s", render_view_name(s->ro.view));
    if (!s->orbit)
        add(&f, 1, "fly");
    if (s->hud_camera)
        add(&f, 1, "eye %.2f,%.2f,%.2f target %.2f,%.2f,%.2f fov %.0f", s->cam.eye.x,
            s->cam.eye.y, s->cam.eye.z, s->cam.target.x, s->cam.target.y, s->cam.target.z,
            s->cam.fov_deg);
    add(&f, 1, "?: help"); /* the key a new user needs: goes only after every field below */
    if (in->texture && s->ro.textures)
        add(&f, 2, "tex:%s", in->texture);
    else
        add(&f, 2, "untextured");
    add(&f, 2, "light:%s", s->headlight ? "camera" : "world");
    if (s->ro.ssaa != SSAA_1)
        add(&f, 2, "%s %s %s ssaa%d", render_raster_name(s->ro.raster),
            render_persp_name(s->ro.persp), render_depth_name(s->ro.depth),
            render_ssaa_factor(s->ro.ssaa));
    else
        add(&f, 2, "%s %s %s", render_raster_name(s->ro.raster), render_persp_name(s->ro.persp),
            render_depth_name(s->ro.depth));
    if (st) {
        char level[24] = "", mode[24];
        if (s->ro.lod == LOD_RATIO)
            snprintf(mode, sizeof mode, "%g", s->ro.lod_ratio);
        else if (s->ro.lod == LOD_CLUSTERS)
            snprintf(mode, sizeof mode, "clusters");
        else
            snprintf(mode, sizeof mode, "%s", render_lod_names.names[s->ro.lod]);
        if (st->dag_cut) /* the cluster hierarchy: the levels its cut takes */
            snprintf(level, sizeof level, " C%d-%d", __builtin_ctz(st->dag_levels),
                     31 - __builtin_clz(st->dag_levels));
        else if (st->lod_min >= 0 && st->lod_min != st->lod_max)
            snprintf(level, sizeof level, " L%d-%d", st->lod_min, st->lod_max);
        else if (st->lod_max >= 0)
            snprintf(level, sizeof level, " L%d", st->lod_max);
        char in_k[24], full_k[24]; /* 36, not 0.0k */
        tri_count(st->tris_in, in_k, sizeof in_k);
        tri_count(st->tris_full, full_k, sizeof full_k);
        add(&f, 2, "lod %s%s%s %s/%s", mode, in->lod_building ? "..." : "", level, in_k, full_k);
    }
    if (s->spin)
        add(&f, 3, "%s", s->paused ? "spin paused" : "spin");
    if (s->ro.cull != CULL_AUTO)
        add(&f, 3, "cull:%s", render_cull_name(s->ro.cull));
    add(&f, 3, "%.1f KB", (double)in->bytes / 1024.0);
    add(&f, 4, "render %.1f ms enc %.2f ms", in->render_ms, in->encode_ms);
    if (st)
        add(&f, 5, "tris %llu clip %llu cull %llu", (unsigned long long)st->tris_drawn,
            (unsigned long long)st->tris_clipped,
            (unsigned long long)(st->tris_culled + st->tris_rejected));

    /* drop whole fields, least important (then rightmost) first, until the line fits */
    bool drop[MAX_FIELDS] = {false};
    size_t room = width > 1 ? (size_t)(width - 1) : 0;
    while (line_len(&f, drop) > room) {
        int worst = -1;
        for (int i = 0; i < f.n; i++)
            if (!drop[i] && f.prio[i] > 0 && (worst < 0 || f.prio[i] >= f.prio[worst]))
                worst = i;
        if (worst < 0)
            break; /* only the essentials left: the caller cuts the line at the edge */
        drop[worst] = true;
    }
    size_t k = 0;
    out[0] = '\0';
    for (int i = 0; i < f.n && k < n; i++)
        if (!drop[i]) {
            int w = snprintf(out + k, n - k, "%s%s", k ? " | " : " ", f.text[i]);
            k += w > 0 ? (size_t)w : 0;
        }
}

struct view_hud_rect view_hud_help_rect(int cols, int rows)
{
    struct view_hud_rect r = {0};
    int lines = 0;
    while (input_help_line(lines)) {
        int l = (int)strlen(input_help_line(lines++));
        r.text_w = l > r.text_w ? l : r.text_w;
    }
    r.columns = 1;
    r.per_col = lines;
    if (lines + 2 > rows) { /* too tall: two columns, cut to the width if they must be */
        r.columns = 2;
        r.per_col = (lines + 1) / 2;
        int w = (cols - 6) / 2;
        r.text_w = r.text_w > w ? (w > 1 ? w : 1) : r.text_w;
    }
    r.cols = r.columns * r.text_w + (r.columns - 1) * 2 + 4;
    r.rows = r.per_col + 2;
    r.col = (cols - r.cols) / 2;
    r.row = (rows - r.rows) / 2;
    r.col = r.col < 0 ? 0 : r.col;
    r.row = r.row < 0 ? 0 : r.row;
    r.cols = r.col + r.cols > cols ? cols - r.col : r.cols;
    r.rows = r.row + r.rows > rows ? rows - r.row : r.rows;
    return r;
}

void view_hud_help_text(const struct view_hud_rect *r, int i, char *out, size_t n)
{
    /* a blank margin above and below the lines (input_help_line is NULL past the last) */
    const char *left = i > 0 && i <= r->per_col ? input_help_line(i - 1) : NULL;
    const char *right = r->columns == 2 && i > 0 && i <= r->per_col
                            ? input_help_line(i - 1 + r->per_col) : NULL;
    int k = snprintf(out, n, "  %-*.*s", r->text_w, r->text_w, left ? left : "");
    if (r->columns == 2 && k >= 0 && (size_t)k < n)
        k += snprintf(out + k, n - (size_t)k, "  %-*.*s", r->text_w, r->text_w, right ? right : "");
    if (k >= 0 && (size_t)k < n)
        snprintf(out + k, n - (size_t)k, "  ");
}
