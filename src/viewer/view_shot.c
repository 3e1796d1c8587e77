/* view_shot.c: the render command line for a screenshot (see view_shot.h). */
#include "view_shot.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

struct buf {
    char *p;
    size_t n, len;
};

static void put(struct buf *b, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void put(struct buf *b, const char *fmt, ...)
{
    if (b->len >= b->n)
        return;
    va_list ap;
    va_start(ap, fmt);
    int k = vsnprintf(b->p + b->len, b->n - b->len, fmt, ap);
    va_end(ap);
    b->len += k > 0 ? (size_t)k : 0;
}

/* A word for sh: as it is when it is plain, else in single quotes. */
static void put_word(struct buf *b, const char *w)
{
    if (*w && strspn(w, "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789"
                        "_-./,:=+@%") == strlen(w)) {
        put(b, " %s", w);
        return;
    }
    put(b, " '");
    for (; *w; w++) {
        if (*w == '\'')
            put(b, "'\\''");
        else
            put(b, "%c", *w);
    }
    put(b, "'");
}

static void put_vec(struct buf *b, const char *flag, vec3 v)
{
    put(b, " %s %.17g,%.17g,%.17g", flag, v.x, v.y, v.z);
}

void view_shot_command(const struct view_state *s, const struct view_shot_info *in, char *out,
                       size_t n)
{
    struct buf b = {out, n, 0};
    out[0] = '\0';
    put(&b, "rastty render");
    put_word(&b, in->model);
    if (in->texture) {
        put(&b, " --texture");
        put_word(&b, in->texture);
    }
    put(&b, " --size %dx%d", in->width, in->height);
    if (in->up_axis)
        put(&b, " --up-axis %c", in->up_axis);
    const struct camera *c = &s->cam;
    put_vec(&b, "--eye", c->eye);
    put_vec(&b, "--target", c->target);
    put_vec(&b, "--up", c->up);
    put(&b, " --fov %.17g --near %.17g --far %.17g", c->fov_deg, c->near, c->far);
    if (c->ortho_height > 0)
        put(&b, " --ortho %.17g", c->ortho_height);
    if (s->headlight)
        put(&b, " --light camera");
    else if (in->light_set)
        put_vec(&b, "--light", s->ro.lights[0].dir);
    const char *shade = view_shade_name(s);
    bool textured = strcmp(shade, "textured") == 0;
    put(&b, " --shade %s%s", textured ? "phong" : render_shade_name(s->ro.shade),
        textured ? "" : " --no-texture");
    put(&b, " --filter %s --cull %s", render_filter_name(s->ro.filter),
        render_cull_name(s->ro.cull));
    put(&b, " --raster %s --persp %s --depth %s", render_raster_name(s->ro.raster),
        render_persp_name(s->ro.persp), render_depth_name(s->ro.depth));
    if (s->ro.ssaa != SSAA_1)
        put(&b, " --ssaa %s", render_ssaa_names.names[s->ro.ssaa]);
    if (s->ro.lod == LOD_RATIO)
        put(&b, " --lod %.9g", s->ro.lod_ratio);
    else if (s->ro.lod == LOD_AUTO && s->ro.lod_px == LOD_DEFAULT_PX)
        put(&b, " --lod auto");
    else if (s->ro.lod == LOD_AUTO)
        put(&b, " --lod auto:%.9g", s->ro.lod_px);
    else if (s->ro.lod == LOD_CLUSTERS && s->ro.lod_px == LOD_DEFAULT_PX)
        put(&b, " --lod clusters");
    else if (s->ro.lod == LOD_CLUSTERS)
        put(&b, " --lod clusters:%.9g", s->ro.lod_px);
    if (s->glyphs != CELL_HALF) /* the framebuffer's pixels are that glyph set's shape */
        put(&b, " --glyphs %s", cell_glyphs_name(s->glyphs));
    if (s->ro.view != VIEW_COLOR)
        put(&b, " --view %s", render_view_name(s->ro.view));
    if (s->ro.hidden_lines)
        put(&b, " --hidden-lines");
    if (s->ro.wire != WIRE_AUTO)
        put(&b, " --wire %s", render_wire_names.names[s->ro.wire]);
    if (in->background_set)
        put(&b, " --background %d,%d,%d", in->background[0], in->background[1],
            in->background[2]);
    if (in->sky)
        put(&b, " --sky procedural");
    put(&b, " --out");
    put_word(&b, in->out);
}
