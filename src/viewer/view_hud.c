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
    add(&f, 0, "%s %s", view_shade_name(s), render_filter_name(s->ro.filter));
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
        else
            snprintf(mode, sizeof mode, "%s", render_lod_names.names[s->ro.lod]);
        if (st->lod_min >= 0 && st->lod_min != st->lod_max)
            snprintf(level, sizeof level, " L%d-%d", st->lod_min, st->lod_max);
        else if (st->lod_max >= 0)
            snprintf(level, sizeof level, " L%d", st->lod_max);
        add(&f, 2, "lod %s%s%s %.1fk/%.1fk", mode, in->lod_building ? "..." : "", level,
            (double)st->tris_in / 1e3, (double)st->tris_full / 1e3);
    }
    if (s->spin)
        add(&f, 3, "%s", s->paused ? "spin paused" : "spin");
    if (s->ro.cull != CULL_AUTO)
        add(&f, 3, "cull:%s", render_cull_name(s->ro.cull));
    add(&f, 3, "%.1f KB", (double)in->bytes / 1024.0);
    add(&f, 3, "h: help");
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
    r.cols = r.text_w + 4;
    r.rows = lines + 2;
    r.col = (cols - r.cols) / 2;
    r.row = (rows - r.rows) / 2;
    r.col = r.col < 0 ? 0 : r.col;
    r.row = r.row < 0 ? 0 : r.row;
    r.cols = r.col + r.cols > cols ? cols - r.col : r.cols;
    r.rows = r.row + r.rows > rows ? rows - r.row : r.rows;
    return r;
}
