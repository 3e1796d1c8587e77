/* material.c: textures for materials, through the texture cache (see material.h). */
#include "material.h"

#include <errno.h>
#include <math.h>
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
