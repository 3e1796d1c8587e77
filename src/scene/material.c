/* material.c: textures for materials, through the texture cache (see material.h). */
#include "material.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "file.h"

float material_srgb_encode(float x)
{
    if (!(x < 1))
        return x > 0 ? 1 : 0; /* (1 exactly: powf's 0.99999994 would be 254.99998) */
    x = x > 0 ? x : 0;
    return x <= 0.0031308f ? 12.92f * x : 1.055f * powf(x, 1 / 2.4f) - 0.055f;
}

float material_srgb_decode(float x)
{
    x = x > 0 ? (x < 1 ? x : 1) : 0;
    return x <= 0.04045f ? x / 12.92f : powf((x + 0.055f) / 1.055f, 2.4f);
}

void material_pbr_highlight(const float base_lin[3], const float f0[3], float metallic,
                            float roughness, float ks_out[3], float *ns_out)
{
    float a = roughness * roughness; /* GGX's alpha; Blinn-Phong's n = 2 / alpha^2 - 2 */
    float a2 = a * a;
    float ns = a2 > 2.0f / 1026 ? 2 / a2 - 2 : 1024;
    ns = ns < 1 ? 1 : ns > 1024 ? 1024 : floorf(ns + 0.5f);
    float k = (ns + 8) / 8, f[3], top = 0;
    for (int c = 0; c < 3; c++) {
        f[c] = (f0[c] + metallic * (base_lin[c] - f0[c])) * k;
        top = f[c] > top ? f[c] : top;
    }
    for (int c = 0; c < 3; c++)
        ks_out[c] = material_srgb_encode(top > 1 ? f[c] / top : f[c]);
    *ns_out = ns;
}

char *material_path_beside(const char *from, const char *name, size_t name_len)
{
    size_t dir = 0;
    if (from && !(name_len > 0 && name[0] == '/')) {
        const char *slash = strrchr(from, '/');
        dir = slash ? (size_t)(slash - from) + 1 : 0;
    }
    char *full = malloc(dir + name_len + 1);
    if (!full)
        return NULL;
    if (dir)
        memcpy(full, from, dir);
    memcpy(full + dir, name, name_len);
    full[dir + name_len] = '\0';
    return full;
}

int material_reserve_n(struct mesh *m, uint32_t n, struct err *e)
{
    free(m->textures);
    m->n_textures = 0;
    m->textures = calloc(n ? n : 1, sizeof *m->textures);
    return m->textures ? 0 : err_set(e, "out of memory");
}

int material_reserve_textures(struct mesh *m, struct err *e)
{
    return material_reserve_n(m, m->n_materials, e);
}

/* the mesh's entry for t (borrowed from the cache), shared by every material using it */
static int attach_image(struct mesh *m, const struct texture *t)
{
    for (uint32_t i = 0; i < m->n_textures; i++)
        if (m->textures[i].rgba == t->rgba)
            return (int)i;
    m->textures[m->n_textures] = *t;
    m->textures[m->n_textures].borrowed = true;
    return (int)m->n_textures++;
}

static void attach(struct mesh *m, uint32_t mat, const struct texture *t)
{
    int i = attach_image(m, t);
    m->materials[mat].texture = i;
    m->materials[mat].base.tex = i;
}

static void warn_texture(const struct model_ctx *ctx, const char *where, unsigned long line,
                         const char *msg)
{
    if (line)
        warn_add(ctx->warn, "%s:%lu: %s; drawn without it", where, line, msg);
    else
        warn_add(ctx->warn, "%s: %s; drawn without it", where, msg);
}

/* the texture in the file path, through the cache; NULL after a warning */
static const struct texture *load_file(const char *path, const char *where, unsigned long line,
                                       const struct model_ctx *ctx)
{
    struct stat st;
    char *alt = NULL;
    if (stat(path, &st) != 0 && errno == ENOENT && strchr(path, '\\')) {
        /* "map_Kd .\tex\a.jpg" from a Windows machine: try '\' as the separator */
        if ((alt = strdup(path)))
            for (char *c = alt; *c; c++)
                if (*c == '\\')
                    *c = '/';
        if (alt && stat(alt, &st) == 0)
            path = alt;
    }
    if (path != alt && stat(path, &st) != 0 && errno == ENOENT) {
        /* DIR/x.jpg missing: DIR/textures/x.jpg (3DS and FBX exports keep their images in
         * a textures folder beside the model); a name carrying the exporter's own folders
         * (C:\art\x.jpg) is tried by its last part there and beside the model */
        const char *s = strrchr(path, '/');
        size_t dir_len = s ? (size_t)(s + 1 - path) : 0;
        const char *base = path + dir_len;
        for (const char *c = base; *c; c++)
            if (*c == '\\')
                base = c + 1;
        static const char *const folders[] = {"", "textures/", "Textures/"};
        for (int k = base > path + dir_len ? 0 : 1; k < 3 && *base; k++) {
            free(alt);
            size_t n = dir_len + strlen(folders[k]) + strlen(base) + 1;
            if (!(alt = malloc(n)))
                break;
            snprintf(alt, n, "%.*s%s%s", (int)dir_len, path, folders[k], base);
            if (stat(alt, &st) == 0) {
                path = alt;
                break;
            }
        }
    }
    const struct texture *t;
    struct err te;
    if (texture_cache_load(ctx->cache, path, &t, ctx->warn, &te)) {
        char msg[sizeof te.msg + 40];
        char q[FILE_QUOTE_SIZE];
        /* "cannot open texture" reads better with the path in quotes */
        const char *reason = strstr(te.msg, ": cannot open texture: ");
        if (reason)
            snprintf(msg, sizeof msg, "cannot open texture '%s': %s", file_quote(path, q, sizeof q),
                     reason + strlen(": cannot open texture: "));
        else
            snprintf(msg, sizeof msg, "bad texture (%s)", te.msg);
        warn_texture(ctx, where, line, msg);
        free(alt);
        return NULL;
    }
    free(alt);
    return t;
}

int material_texture_file(struct mesh *m, uint32_t mat, const char *path, const char *where,
                          unsigned long line, const struct model_ctx *ctx, struct err *e)
{
    (void)e;
    const struct texture *t = load_file(path, where, line, ctx);
    if (t)
        attach(m, mat, t);
    return 0;
}

enum material_map_kind material_normal_kind(const struct texture *t)
{
    size_t n = (size_t)t->w * (size_t)t->h, low = 0, grey = 0;
    double blue = 0;
    for (size_t i = 0; i < n; i++) {
        const uint8_t *p = t->rgba + 4 * i;
        low += p[2] < 100;
        blue += p[2];
        int d1 = p[0] - p[1], d2 = p[1] - p[2];
        grey += d1 > -4 && d1 < 4 && d2 > -4 && d2 < 4;
    }
    if (n && grey * 10 >= n * 9)
        return MATERIAL_MAP_HEIGHT;
    if (n && low * 100 <= n && blue / (double)n > 200)
        return MATERIAL_MAP_TANGENT;
    return low * 100 > n ? MATERIAL_MAP_OBJECT : MATERIAL_MAP_TANGENT;
}

/* a tangent-space normal map from a height map: central differences of the height (red,
 * 0..1, wrapping) per texel, times strength */
static int height_to_normal(const struct texture *h, float strength, struct texture *out,
                            struct err *e)
{
    int w = h->w, hh = h->h;
    uint8_t *px = malloc((size_t)w * (size_t)hh * 4);
    if (!px)
        return err_set(e, "out of memory");
    for (int y = 0; y < hh; y++)
        for (int x = 0; x < w; x++) {
            const uint8_t *l = texture_texel(&(struct texture_level){w, hh, h->rgba}, (x + w - 1) % w, y);
            const uint8_t *r = texture_texel(&(struct texture_level){w, hh, h->rgba}, (x + 1) % w, y);
            const uint8_t *d = texture_texel(&(struct texture_level){w, hh, h->rgba}, x, (y + hh - 1) % hh);
            const uint8_t *u = texture_texel(&(struct texture_level){w, hh, h->rgba}, x, (y + 1) % hh);
            /* heights 0..1 over a texel: the slopes in texels, scaled */
            float dx = (r[0] - l[0]) / 255.0f * 0.5f * strength * 8;
            float dy = (u[0] - d[0]) / 255.0f * 0.5f * strength * 8;
            float nx = -dx, ny = -dy, nz = 1, len = sqrtf(nx * nx + ny * ny + nz * nz);
            uint8_t *o = px + 4 * ((size_t)(hh - 1 - y) * (size_t)w + (size_t)x);
            o[0] = (uint8_t)((nx / len * 0.5f + 0.5f) * 255 + 0.5f);
            o[1] = (uint8_t)((ny / len * 0.5f + 0.5f) * 255 + 0.5f);
            o[2] = (uint8_t)((nz / len * 0.5f + 0.5f) * 255 + 0.5f);
            o[3] = 255;
        }
    int rc = texture_from_rgba(w, hh, px, out, e);
    free(px);
    if (rc == 0 && texture_build_mips(out, e) < 0) {
        texture_free(out);
        return -1;
    }
    return rc;
}

int material_normal_map(struct mesh *m, uint32_t mat, const char *path, const char *where,
                        unsigned long line, float strength, const struct model_ctx *ctx,
                        struct err *e)
{
    const struct texture *t = load_file(path, where, line, ctx);
    if (!t)
        return 0;
    struct material *mt = &m->materials[mat];
    enum material_map_kind kind = material_normal_kind(t);
    if (kind == MATERIAL_MAP_HEIGHT) {
        struct texture nt;
        if (height_to_normal(t, strength, &nt, e))
            return -1;
        m->textures[m->n_textures] = nt; /* (owned: not the cache's) */
        mt->normal_map = (struct tex_slot){.tex = (int)m->n_textures++};
        mt->normal_space = MAT_NORMAL_TANGENT;
        mt->normal_scale = 1;
    } else {
        mt->normal_map = (struct tex_slot){.tex = attach_image(m, t)};
        mt->normal_space = kind == MATERIAL_MAP_OBJECT ? MAT_NORMAL_OBJECT : MAT_NORMAL_TANGENT;
        mt->normal_scale = strength;
    }
    mt->features = true;
    return 0;
}

int material_image_file(struct mesh *m, const char *path, const char *where, unsigned long line,
                        const struct model_ctx *ctx)
{
    const struct texture *t = load_file(path, where, line, ctx);
    return t ? attach_image(m, t) : -1;
}

int material_image_bytes(struct mesh *m, const uint8_t *data, size_t len, const char *name,
                         const struct model_ctx *ctx)
{
    struct texture t;
    struct err te;
    if (texture_cache_decode(ctx->cache, data, len, name, &t, ctx->warn, &te)) {
        warn_add(ctx->warn, "bad texture (%s); drawn without it", te.msg);
        return -1;
    }
    return attach_image(m, &t);
}

int material_texture_bytes(struct mesh *m, uint32_t mat, const uint8_t *data, size_t len,
                           const char *name, const struct model_ctx *ctx, struct err *e)
{
    (void)e;
    struct texture t;
    struct err te;
    if (texture_cache_decode(ctx->cache, data, len, name, &t, ctx->warn, &te)) {
        warn_add(ctx->warn, "bad texture (%s); drawn without it", te.msg);
        return 0;
    }
    attach(m, mat, &t);
    return 0;
}
