/* config.c: RASTTY_COLORS and the config file (see config.h). */
#include "config.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "file.h"

/* A --colors value, or "auto" (= not set); else -1. */
static int set_colors(struct config *c, const char *v)
{
    static const char *const ok[] = {"truecolor", "256", "16", "none"};
    if (strcmp(v, "auto") == 0) {
        c->colors[0] = '\0';
        return 0;
    }
    for (unsigned i = 0; i < sizeof ok / sizeof ok[0]; i++)
        if (strcmp(v, ok[i]) == 0) {
            snprintf(c->colors, sizeof c->colors, "%s", ok[i]);
            return 0;
        }
    return -1;
}

static char *trim(char *s)
{
    while (*s == ' ' || *s == '\t')
        s++;
    char *e = s + strlen(s);
    while (e > s && (e[-1] == ' ' || e[-1] == '\t' || e[-1] == '\r'))
        *--e = '\0';
    return s;
}

static int line_err(struct err *e, const char *path, int line, const char *what, const char *v)
{
    char q[64];
    if (!v)
        return err_set(e, "%s:%d: %s", path, line, what);
    return err_set(e, "%s:%d: %s, got '%s'", path, line, what, err_quote(v, strlen(v), 40, q, sizeof q));
}

static int setting(struct config *c, const char *path, int line, const char *key, char *v,
                   struct err *e)
{
    if (strcmp(key, "colors") == 0) {
        if (set_colors(c, v))
            return line_err(e, path, line, "colors: expected auto, truecolor, 256, 16 or none", v);
    } else if (strcmp(key, "light") == 0) {
        double d[3];
        char tail;
        if (strcmp(v, "camera") == 0)
            c->light = CONFIG_LIGHT_CAMERA;
        else if (strcmp(v, "world") == 0)
            c->light = CONFIG_LIGHT_WORLD;
        else if (sscanf(v, "%lf,%lf,%lf%c", &d[0], &d[1], &d[2], &tail) == 3 &&
                 isfinite(d[0]) && isfinite(d[1]) && isfinite(d[2]) &&
                 (d[0] != 0 || d[1] != 0 || d[2] != 0)) {
            c->light = CONFIG_LIGHT_DIR;
            c->light_dir = v3(d[0], d[1], d[2]);
        } else {
            return line_err(e, path, line, "light: expected camera, world or X,Y,Z", v);
        }
    } else if (strcmp(key, "spin") == 0) {
        if (strcmp(v, "on") == 0 || strcmp(v, "yes") == 0 || strcmp(v, "true") == 0)
            c->spin = 1;
        else if (strcmp(v, "off") == 0 || strcmp(v, "no") == 0 || strcmp(v, "false") == 0)
            c->spin = 0;
        else
            return line_err(e, path, line, "spin: expected on or off", v);
    } else if (strcmp(key, "spin-timeout") == 0) {
        char *end;
        double s = strtod(v, &end);
        if (end == v || *end || !(s >= 0 && s <= 1e6))
            return line_err(e, path, line, "spin-timeout: expected seconds (0 = never)", v);
        c->spin_timeout = s;
    } else if (strcmp(key, "bandwidth") == 0) {
        if (options_parse_rate(v, &c->bandwidth))
            return line_err(e, path, line, "bandwidth: expected bytes/s like 128k or 1Mbit", v);
    } else if (strcmp(key, "glyphs") == 0) {
        int g = cell_glyphs_parse(v);
        if (g < 0)
            return line_err(e, path, line,
                            "glyphs: expected half, quadrant, sextant, braille or ascii", v);
        c->glyphs = g;
    } else {
        return line_err(e, path, line,
                        "unknown key (expected colors, light, spin, spin-timeout, bandwidth, glyphs)", key);
    }
    return 0;
}

int config_parse(const char *path, const char *text, struct config *c, struct err *e)
{
    char q[200];
    err_quote(path, strlen(path), 160, q, sizeof q);
    int line = 0;
    for (const char *p = text; *p;) {
        const char *eol = strchr(p, '\n');
        size_t len = eol ? (size_t)(eol - p) : strlen(p);
        line++;
        char buf[512];
        if (len >= sizeof buf)
            return line_err(e, q, line, "line too long", NULL);
        memcpy(buf, p, len);
        buf[len] = '\0';
        p += len + (eol ? 1 : 0);
        char *hash = strchr(buf, '#');
        if (hash)
            *hash = '\0';
        char *s = trim(buf);
        if (!*s)
            continue;
        char *eq = strchr(s, '=');
        if (!eq)
            return line_err(e, q, line, "expected key = value", s);
        *eq = '\0';
        if (setting(c, q, line, trim(s), trim(eq + 1), e))
            return -1;
    }
    return 0;
}

int config_load(const char *xdg, const char *home, const char *env, struct config *c,
                struct err *e)
{
    *c = (struct config){.spin = -1, .spin_timeout = -1, .glyphs = -1};
    char path[4200];
    if (xdg && *xdg)
        snprintf(path, sizeof path, "%s/rastty/config", xdg);
    else if (home && *home)
        snprintf(path, sizeof path, "%s/.config/rastty/config", home);
    else
        path[0] = '\0';
    char *text;
    size_t len;
    int err_no = path[0] ? file_read(path, FILE_MAX_TEXT, &text, &len) : ENOENT;
    if (err_no && err_no != ENOENT) {
        char q[200];
        return err_set(e, "%s: cannot read: %s", err_quote(path, strlen(path), 160, q, sizeof q),
                       file_strerror(err_no));
    }
    if (!err_no) {
        char q[200];
        err_quote(path, strlen(path), 160, q, sizeof q);
        int rc = memchr(text, '\0', len) ? err_set(e, "%s: binary data in the config file", q)
                                         : config_parse(path, text, c, e);
        free(text);
        if (rc)
            return -1;
    }
    if (env && *env && set_colors(c, env)) {
        char q[64];
        return err_set(e, "rastty: RASTTY_COLORS: expected auto, truecolor, 256, 16 or none, "
                          "got '%s'", err_quote(env, strlen(env), 40, q, sizeof q));
    }
    return 0;
}

void config_apply(const struct config *c, struct options *o)
{
    if (!o->colors && c->colors[0])
        o->colors = c->colors;
    if (!o->light_set && !o->light_camera) {
        if (c->light == CONFIG_LIGHT_CAMERA)
            o->light_camera = true;
        else if (c->light == CONFIG_LIGHT_WORLD)
            o->light_world = true;
        else if (c->light == CONFIG_LIGHT_DIR) {
            o->render.lights[0].dir = c->light_dir;
            o->light_set = true;
        }
    }
    if (o->spin < 0)
        o->spin = c->spin;
    if (o->spin_timeout < 0)
        o->spin_timeout = c->spin_timeout;
    if (o->bandwidth == 0)
        o->bandwidth = c->bandwidth;
    if (!o->glyphs_set && c->glyphs >= 0) {
        o->glyphs = (enum cell_glyphs)c->glyphs;
        o->glyphs_set = true;
    }
}
