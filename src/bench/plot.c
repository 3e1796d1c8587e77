/* plot.c: SVG and terminal back ends of the chart drawing surface (see plot.h). */
#include "plot.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "encode.h"
#include "line.h"

#define SVG_CHAR_W 7.0
#define SVG_CHAR_H 14.0

static void xml_text(FILE *f, const char *s)
{
    for (; *s; s++) {
        if (*s == '&')
            fputs("&amp;", f);
        else if (*s == '<')
            fputs("&lt;", f);
        else if (*s == '>')
            fputs("&gt;", f);
        else if ((unsigned char)*s >= 0x20)
            fputc(*s, f);
    }
}

void plot_svg_begin(struct plot *p, FILE *f, int w, int h, const char *title)
{
    memset(p, 0, sizeof *p);
    p->w = w, p->h = h;
    p->char_w = SVG_CHAR_W, p->char_h = SVG_CHAR_H;
    p->svg = f;
    fprintf(f, "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%d\" height=\"%d\" "
               "viewBox=\"0 0 %d %d\" font-family=\"DejaVu Sans, Helvetica, Arial, sans-serif\" "
               "font-size=\"12\">\n<title>", w, h, w, h);
    xml_text(f, title);
    fprintf(f, "</title>\n<rect width=\"%d\" height=\"%d\" fill=\"#ffffff\"/>\n", w, h);
}

int plot_svg_end(struct plot *p, const char *path, struct err *e)
{
    fputs("</svg>\n", p->svg);
    if (fflush(p->svg) != 0 || ferror(p->svg))
        return err_set(e, "%s: write failed", path);
    return 0;
}

void plot_fb_begin(struct plot *p, struct fb *fb)
{
    memset(p, 0, sizeof *p);
    p->w = fb->w, p->h = fb->h;
    p->char_w = 1, p->char_h = 2;
    p->fb = fb;
    memset(fb->rgb, 0, (size_t)fb->w * fb->h * 3);
}

void plot_free(struct plot *p)
{
    free(p->labels);
    p->labels = NULL;
    p->n_labels = p->cap_labels = 0;
}

static void rgb3(uint32_t c, uint8_t out[3])
{
    out[0] = (uint8_t)(c >> 16), out[1] = (uint8_t)(c >> 8), out[2] = (uint8_t)c;
}

void plot_line(struct plot *p, double x0, double y0, double x1, double y1, uint32_t rgb,
               double width, bool dashed)
{
    if (p->svg) {
        fprintf(p->svg, "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"#%06x\" "
                        "stroke-width=\"%.1f\"%s/>\n", x0, y0, x1, y1, (unsigned)rgb, width,
                dashed ? " stroke-dasharray=\"6 4\"" : "");
        return;
    }
    if (!p->fb || !isfinite(x0 + y0 + x1 + y1))
        return;
    uint8_t c[3];
    rgb3(rgb, c);
    if (!dashed) {
        line_draw_px(p->fb, (int)floor(x0), (int)floor(y0), 0, (int)floor(x1), (int)floor(y1), 0,
                     c, 0);
        return;
    }
    double len = hypot(x1 - x0, y1 - y0);
    int n = (int)(len / 2);
    for (int i = 0; i <= n; i += 2) { /* 2 pixels on, 2 off */
        double a = n ? (double)i / n : 0, b = n ? fmin(1, (double)(i + 1) / n) : 0;
        line_draw_px(p->fb, (int)floor(x0 + a * (x1 - x0)), (int)floor(y0 + a * (y1 - y0)), 0,
                     (int)floor(x0 + b * (x1 - x0)), (int)floor(y0 + b * (y1 - y0)), 0, c, 0);
    }
}

static void fb_dot(struct fb *fb, int x, int y, const uint8_t c[3])
{
    if (x >= 0 && y >= 0 && x < fb->w && y < fb->h)
        memcpy(fb->rgb + 3 * ((size_t)y * fb->w + x), c, 3);
}

void plot_marker(struct plot *p, double x, double y, enum plot_shape shape, double r,
                 uint32_t rgb)
{
    if (p->svg) {
        const char *style = "stroke=\"#202020\" stroke-width=\"0.8\"";
        switch (shape) {
        case PLOT_CIRCLE:
            fprintf(p->svg, "<circle cx=\"%.1f\" cy=\"%.1f\" r=\"%.1f\" fill=\"#%06x\" %s/>\n",
                    x, y, r, (unsigned)rgb, style);
            break;
        case PLOT_SQUARE:
            fprintf(p->svg, "<rect x=\"%.1f\" y=\"%.1f\" width=\"%.1f\" height=\"%.1f\" "
                            "fill=\"#%06x\" %s/>\n", x - r, y - r, 2 * r, 2 * r, (unsigned)rgb,
                    style);
            break;
        case PLOT_DIAMOND:
            fprintf(p->svg, "<polygon points=\"%.1f,%.1f %.1f,%.1f %.1f,%.1f %.1f,%.1f\" "
                            "fill=\"#%06x\" %s/>\n", x, y - 1.3 * r, x + 1.3 * r, y, x,
                    y + 1.3 * r, x - 1.3 * r, y, (unsigned)rgb, style);
            break;
        case PLOT_TRIANGLE:
            fprintf(p->svg, "<polygon points=\"%.1f,%.1f %.1f,%.1f %.1f,%.1f\" fill=\"#%06x\" "
                            "%s/>\n", x, y - 1.3 * r, x + 1.2 * r, y + 0.9 * r, x - 1.2 * r,
                    y + 0.9 * r, (unsigned)rgb, style);
            break;
        }
        return;
    }
    if (!p->fb || !isfinite(x + y))
        return;
    uint8_t c[3];
    rgb3(rgb, c);
    int cx = (int)floor(x), cy = (int)floor(y), ri = r >= 1 ? (int)r : 1;
    for (int dy = -ri; dy <= ri; dy++)
        for (int dx = -ri; dx <= ri; dx++)
            if (shape != PLOT_DIAMOND || dx == 0 || dy == 0) /* a cross for diamonds */
                fb_dot(p->fb, cx + dx, cy + dy, c);
}

void plot_text(struct plot *p, double x, double y, const char *text, uint32_t rgb,
               enum plot_anchor anchor, double size, bool bold)
{
    if (p->svg) {
        static const char *const anchors[] = {"start", "middle", "end"};
        fprintf(p->svg, "<text x=\"%.1f\" y=\"%.1f\" dy=\"0.35em\" text-anchor=\"%s\" "
                        "font-size=\"%.1f\"%s fill=\"#%06x\">", x, y, anchors[anchor],
                12 * size, bold ? " font-weight=\"bold\"" : "", (unsigned)rgb);
        xml_text(p->svg, text);
        fputs("</text>\n", p->svg);
        return;
    }
    if (!p->fb || !isfinite(x + y))
        return;
    if (p->n_labels == p->cap_labels) {
        int cap = p->cap_labels ? 2 * p->cap_labels : 64;
        struct plot_label *nl = realloc(p->labels, (size_t)cap * sizeof *nl);
        if (!nl)
            return; /* a label less; plot_emit_terminal still draws the picture */
        p->labels = nl;
        p->cap_labels = cap;
    }
    struct plot_label *l = &p->labels[p->n_labels++];
    snprintf(l->text, sizeof l->text, "%s", text);
    int len = (int)strlen(l->text);
    int col = (int)lround(x) - (anchor == PLOT_MIDDLE ? len / 2 : anchor == PLOT_RIGHT ? len : 0);
    col = col + len > p->w ? p->w - len : col;
    l->col = col < 0 ? 0 : col;
    l->row = (int)floor(y / 2);
    l->row = l->row < 0 ? 0 : l->row >= (p->h + 1) / 2 ? (p->h + 1) / 2 - 1 : l->row;
    l->rgb = rgb;
}

int plot_emit_terminal(struct plot *p, FILE *out, enum palette_mode mode, struct err *e)
{
    struct cell_geom half = cell_geom(CELL_HALF);
    int rows = cell_rows(&half, p->h);
    struct encode_screen es;
    if (encode_screen_init(&es, p->w, rows, e))
        return -1;
    struct encode_opts eo = {.mode = mode};
    size_t n;
    const char *bytes = encode_frame(&es, p->fb->rgb, p->w, p->h, &eo, &n, NULL);
    fputs("\033[2J", out);
    fwrite(bytes, 1, n, out);
    encode_screen_free(&es);
    for (int i = 0; i < p->n_labels; i++) {
        const struct plot_label *l = &p->labels[i];
        fprintf(out, "\033[%d;%dH", l->row + 1, l->col + 1);
        if (mode == PALETTE_TRUECOLOR)
            fprintf(out, "\033[38;2;%u;%u;%u;48;2;0;0;0m", (unsigned)(l->rgb >> 16) & 255,
                    (unsigned)(l->rgb >> 8) & 255, (unsigned)l->rgb & 255);
        else if (mode != PALETTE_NONE)
            fputs("\033[97;40m", out);
        fputs(l->text, out);
    }
    fprintf(out, "\033[0m\033[%d;1H", rows + 1);
    if (fflush(out) != 0 || ferror(out))
        return err_set(e, "rastty bench: write failed");
    return 0;
}

double plot_map(const struct plot_axis *a, double v)
{
    double lo = a->lo, hi = a->hi;
    if (a->log) {
        lo = log10(lo), hi = log10(hi);
        v = v > 0 ? log10(v) : lo - 1;
    }
    return a->px0 + (v - lo) / (hi - lo) * (a->px1 - a->px0);
}

/* "1e+06" -> "1e6", "0.0001" -> "1e-4": short tick labels */
static void tick_label(double v, char *out, size_t n)
{
    double a = fabs(v);
    if (v == 0)
        snprintf(out, n, "0");
    else if (a >= 1e4 || a < 1e-3) {
        int ex = (int)floor(log10(a) + 1e-9);
        double m = v / pow(10, ex);
        if (fabs(m - round(m)) < 1e-9 && fabs(round(m)) == 1)
            snprintf(out, n, "%s1e%d", m < 0 ? "-" : "", ex);
        else
            snprintf(out, n, "%ge%d", m, ex);
    } else
        snprintf(out, n, "%g", v);
}

/* Tick values on the axis in a[], at most max of them; returns the count. Linear: multiples
 * of a 1-2-5 step giving about `want` ticks; log: 1-2-5 per decade, or decades only when
 * that would be too many. */
static int ticks(const struct plot_axis *ax, int want, double *a, int max)
{
    int n = 0;
    double lo = fmin(ax->lo, ax->hi), hi = fmax(ax->lo, ax->hi);
    if (ax->log) {
        int d0 = (int)floor(log10(lo) + 1e-9), d1 = (int)ceil(log10(hi) - 1e-9);
        bool fine = (d1 - d0) * 3 <= want;
        int step = (d1 - d0) > want ? (d1 - d0 + want - 1) / want : 1;
        for (int d = d0; d <= d1; d += step)
            for (int m = 1; m <= 5; m += (m == 1 ? 1 : 3)) {
                if (!fine && m > 1)
                    continue;
                double v = pow(10, d) * m;
                if (v >= lo * (1 - 1e-9) && v <= hi * (1 + 1e-9) && n < max)
                    a[n++] = v;
            }
        return n;
    }
    double span = fabs(ax->hi - ax->lo), raw = span / (want > 1 ? want : 1);
    double mag = pow(10, floor(log10(raw))), step = mag;
    if (raw / mag > 5)
        step = 10 * mag;
    else if (raw / mag > 2)
        step = 5 * mag;
    else if (raw / mag > 1)
        step = 2 * mag;
    for (double v = ceil(lo / step - 1e-9) * step; v <= hi + step * 1e-9 && n < max; v += step)
        a[n++] = fabs(v) < step * 1e-9 ? 0 : v;
    return n;
}

void plot_axes(struct plot *p, const struct plot_axis *x, const struct plot_axis *y,
               const char *xtitle, const char *ytitle, const char *title)
{
    const uint32_t grid = p->svg ? 0xe4e4e4 : 0x303030, frame = p->svg ? 0x808080 : 0x707070;
    const uint32_t ink = p->svg ? 0x303030 : 0xc0c0c0;
    double t[64];
    double xl = fmin(x->px0, x->px1), xr = fmax(x->px0, x->px1);
    double yt = fmin(y->px0, y->px1), yb = fmax(y->px0, y->px1);
    int nx = ticks(x, (int)((xr - xl) / (p->char_w * 9)), t, 64);
    for (int i = 0; i < nx; i++) {
        double px = plot_map(x, t[i]);
        char s[32];
        tick_label(t[i], s, sizeof s);
        plot_line(p, px, yt, px, yb, grid, 1, false);
        plot_text(p, px, yb + p->char_h * 0.9, s, ink, PLOT_MIDDLE, 0.9, false);
    }
    int ny = ticks(y, (int)((yb - yt) / (p->char_h * 2.5)), t, 64);
    for (int i = 0; i < ny; i++) {
        double py = plot_map(y, t[i]);
        char s[32];
        tick_label(t[i], s, sizeof s);
        plot_line(p, xl, py, xr, py, grid, 1, false);
        plot_text(p, xl - p->char_w * 0.6, py, s, ink, PLOT_RIGHT, 0.9, false);
    }
    plot_line(p, xl, yt, xr, yt, frame, 1, false);
    plot_line(p, xl, yb, xr, yb, frame, 1, false);
    plot_line(p, xl, yt, xl, yb, frame, 1, false);
    plot_line(p, xr, yt, xr, yb, frame, 1, false);
    if (xtitle)
        plot_text(p, (xl + xr) / 2, yb + p->char_h * 2.1, xtitle, ink, PLOT_MIDDLE, 1, false);
    if (ytitle)
        plot_text(p, xl, yt - p->char_h * 0.8, ytitle, ink, PLOT_LEFT, 1, false);
    if (title)
        plot_text(p, (xl + xr) / 2, yt - p->char_h * 2.2, title, ink, PLOT_MIDDLE, 1.15, true);
}

void plot_keep_clear(struct plot_clear *c, double x, double y, double r)
{
    if (c->n < (int)(sizeof c->boxes / sizeof c->boxes[0]))
        c->boxes[c->n++] = (struct plot_box){x - r, y - r, x + r, y + r};
}

static bool box_overlaps(const struct plot_box *a, const struct plot_box *b)
{
    return a->x0 < b->x1 && b->x0 < a->x1 && a->y0 < b->y1 && b->y0 < a->y1;
}

bool plot_text_clear(struct plot *p, struct plot_clear *c, double x, double y, double r,
                     const char *text, uint32_t rgb, double size, bool bold, bool optional)
{
    double tw = (double)strlen(text) * p->char_w * size * (p->svg ? 0.95 : 1);
    double th = p->char_h * size;
    static const double offs[][2] = {{1, 0},  {1, -1},  {1, 1},  {-1, 0}, {-1, -1},
                                     {-1, 1}, {1, -2},  {1, 2},  {-1, -2}, {-1, 2},
                                     {1, -3}, {1, 3},   {-1, -3}, {-1, 3}};
    for (size_t k = 0; k < sizeof offs / sizeof offs[0]; k++) {
        double lx = offs[k][0] > 0 ? x + r + p->char_w * 0.5 : x - r - p->char_w * 0.5 - tw;
        double ly = y + offs[k][1] * th;
        struct plot_box b = {lx, ly - th / 2, lx + tw, ly + th / 2};
        if (b.x0 < c->area.x0 || b.x1 > c->area.x1 || b.y0 < c->area.y0 || b.y1 > c->area.y1)
            continue;
        bool clash = false;
        for (int i = 0; i < c->n && !clash; i++)
            clash = box_overlaps(&b, &c->boxes[i]);
        if (clash)
            continue;
        if (c->n < (int)(sizeof c->boxes / sizeof c->boxes[0]))
            c->boxes[c->n++] = b;
        plot_text(p, lx, ly, text, rgb, PLOT_LEFT, size, bold);
        return true;
    }
    if (optional)
        return false;
    plot_text(p, x + r + p->char_w * 0.5, y, text, rgb, PLOT_LEFT, size, bold);
    return true;
}
