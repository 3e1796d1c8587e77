/* material.c: textures for materials, through the texture cache (see material.h). */
#include "material.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "file.h"

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

int material_reserve_textures(struct mesh *m, struct err *e)
{
    free(m->textures);
    m->n_textures = 0;
    m->textures = calloc(m->n_materials ? m->n_materials : 1, sizeof *m->textures);
    return m->textures ? 0 : err_set(e, "out of memory");
}

/* the mesh's entry for t (borrowed from the cache), shared by every material using it */
static void attach(struct mesh *m, uint32_t mat, const struct texture *t)
{
    for (uint32_t i = 0; i < m->n_textures; i++)
        if (m->textures[i].rgba == t->rgba) {
            m->materials[mat].texture = (int)i;
            return;
        }
    m->textures[m->n_textures] = *t;
    m->textures[m->n_textures].borrowed = true;
    m->materials[mat].texture = (int)m->n_textures++;
}

static void warn_texture(const struct model_ctx *ctx, const char *where, unsigned long line,
                         const char *msg)
{
    if (line)
        warn_add(ctx->warn, "%s:%lu: %s; drawn without it", where, line, msg);
    else
        warn_add(ctx->warn, "%s: %s; drawn without it", where, msg);
}

int material_texture_file(struct mesh *m, uint32_t mat, const char *path, const char *where,
                          unsigned long line, const struct model_ctx *ctx, struct err *e)
{
    (void)e;
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
        return 0;
    }
    free(alt);
    attach(m, mat, t);
    return 0;
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
