/* model.c: which loader reads a file, and the one entry point for all of them (model.h). */
#include "model.h"

#include <stdbool.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "file.h"
#include "imgdec.h"

static bool starts(const char *d, size_t n, const char *s)
{
    size_t k = strlen(s);
    return n >= k && memcmp(d, s, k) == 0;
}

/* does the text's first KB hold s? (memmem on a bounded window) */
static bool early(const char *d, size_t n, const char *s)
{
    size_t k = strlen(s), w = n < 4096 ? n : 4096;
    for (size_t i = 0; i + k <= w; i++)
        if (memcmp(d + i, s, k) == 0)
            return true;
    return false;
}

static bool starts_nocase(const char *d, size_t n, const char *s)
{
    size_t k = strlen(s);
    return n >= k && strncasecmp(d, s, k) == 0;
}

static bool early_nocase(const char *d, size_t n, const char *s)
{
    size_t k = strlen(s), w = n < 4096 ? n : 4096;
    for (size_t i = 0; i + k <= w; i++)
        if (strncasecmp(d + i, s, k) == 0)
            return true;
    return false;
}

static const char *extension(const char *path)
{
    if (!path)
        return "";
    const char *slash = strrchr(path, '/'), *dot = strrchr(path, '.');
    return dot && (!slash || dot > slash) ? dot + 1 : "";
}

static bool ext_in(const char *ext, const char *const *list)
{
    for (; *list; list++)
        if (strcasecmp(ext, *list) == 0)
            return true;
    return false;
}

/* formats assimp reads that rastty hands to it (OBJ, STL and PLY stay on our own parsers) */
static const char *const import_exts[] = {
    "gltf", "glb", "fbx", "dae", "3ds", "x", "lwo", "lws", "ase", "ms3d", "off", "ac", "ac3d",
    "3mf", "amf", "md2", "md3", "md5mesh", "mdl", "smd", "irrmesh", "xgl", "zgl", "cob", "q3o",
    "q3s", "nff", "raw", "ter", "hmp", "ndo", "b3d", "csm", "bvh", "ogex", "x3d", "m3d", NULL};
static const char *const image_exts[] = {"png", "jpg", "jpeg", "tga", "bmp", "gif", "psd",
                                         "hdr", "ppm", "pgm", "pnm", "pic", NULL};

/* UTF-16 text (with a byte-order mark, or without one: every other byte zero in its first
 * 256): 1 little-endian, 2 big-endian, 0 not */
static int utf16(const uint8_t *d, size_t n)
{
    if (n >= 2 && d[0] == 0xff && d[1] == 0xfe)
        return 1;
    if (n >= 2 && d[0] == 0xfe && d[1] == 0xff)
        return 2;
    if (n < 8)
        return 0;
    size_t w = (n < 256 ? n : 256) & ~(size_t)1, zero_odd = 0, zero_even = 0;
    for (size_t i = 0; i < w; i += 2) {
        zero_even += d[i] == 0;
        zero_odd += d[i + 1] == 0;
    }
    /* (ASCII text has no NULs; UTF-16 of mostly ASCII has one in every other byte) */
    if (zero_even == 0 && zero_odd * 4 >= w / 2 * 3)
        return 1;
    if (zero_odd == 0 && zero_even * 4 >= w / 2 * 3)
        return 2;
    return 0;
}

int model_detect(const char *data, size_t len, const char *path, enum model_format *fmt,
                 struct err *e)
{
    char q[FILE_QUOTE_SIZE];
    file_quote(path ? path : "<memory>", q, sizeof q);
    const uint8_t *u = (const uint8_t *)data;
    const char *ext = extension(path);
    /* binary formats with magic */
    if (starts(data, len, "glTF")) {
        *fmt = MODEL_GLTF;
        return 0;
    }
    if (starts(data, len, "Kaydara FBX Binary")) {
        *fmt = MODEL_IMPORT;
        return 0;
    }
    if (starts(data, len, "DRACO")) {
        *fmt = MODEL_DRACO;
        return 0;
    }
    if (starts(data, len, "ply\n") || starts(data, len, "ply\r\n")) {
        *fmt = MODEL_PLY;
        return 0;
    }
    /* binary STL: an 80-byte header, a count, exactly 50 bytes per triangle */
    if (len >= 84) {
        uint32_t n = (uint32_t)u[80] | (uint32_t)u[81] << 8 | (uint32_t)u[82] << 16 |
                     (uint32_t)u[83] << 24;
        if ((len - 84) % 50 == 0 && (len - 84) / 50 == n) {
            *fmt = MODEL_STL;
            return 0;
        }
    }
    /* files that are no model at all */
    const char *kind = imgdec_kind(u, len);
    if (!kind && ext_in(ext, image_exts) && !starts(data, len, "solid"))
        kind = "an image, by its name";
    if (!kind) {
        static const struct {
            const char *magic, *what;
        } other[] = {
            {"\x1f\x8b", "gzip-compressed data: decompress it first"},
            {"PK\x03\x04", "ZIP archive: extract it first"},
            {"7z\xbc\xaf\x27\x1c", "7-Zip archive: extract it first"},
            {"Rar!", "RAR archive: extract it first"},
            {"%PDF", "PDF document"},
            {"\x7f" "ELF", "ELF executable"},
            {"BLENDER", "Blender file: export it as glTF, OBJ or STL"},
        };
        for (size_t i = 0; i < sizeof other / sizeof other[0]; i++)
            if (starts(data, len, other[i].magic))
                kind = other[i].what;
    }
    if (kind)
        return err_set(e, "%s: not a model (%s)", q, kind);
    if (utf16(u, len))
        return err_set(e, "%s: UTF-16 text (save the file as UTF-8 or ASCII)", q);
    /* text formats: skip a byte-order mark and blanks */
    const char *t = data, *end = data + len;
    if (starts(t, len, "\xef\xbb\xbf"))
        t += 3;
    while (t < end && (*t == ' ' || *t == '\t' || *t == '\r' || *t == '\n'))
        t++;
    size_t tn = (size_t)(end - t);
    if (starts(t, tn, "{") && early(t, tn, "\"asset\"")) {
        *fmt = MODEL_GLTF;
        return 0;
    }
    if (early(t, tn, "<COLLADA") || starts(t, tn, "; FBX")) {
        *fmt = MODEL_IMPORT;
        return 0;
    }
    if (starts_nocase(t, tn, "solid") &&
        (early_nocase(t, tn, "facet") || early_nocase(t, tn, "endsolid"))) {
        *fmt = MODEL_STL;
        return 0;
    }
    /* then the name */
    if (strcasecmp(ext, "stl") == 0)
        *fmt = MODEL_STL;
    else if (strcasecmp(ext, "ply") == 0)
        *fmt = MODEL_PLY;
    else if (strcasecmp(ext, "gltf") == 0 || strcasecmp(ext, "glb") == 0)
        *fmt = MODEL_GLTF;
    else if (strcasecmp(ext, "drc") == 0)
        *fmt = MODEL_DRACO;
    else if (ext_in(ext, import_exts))
        *fmt = MODEL_IMPORT;
    else
        *fmt = MODEL_OBJ; /* the text format without magic */
    return 0;
}

/* the blended triangles after the rest, each part in the file's order */
static int sort_blended(struct mesh *m)
{
    uint32_t n_blend = 0;
    for (uint32_t t = 0; t < m->n_tris; t++)
        n_blend += m->materials[m->tri_material[t]].alpha_mode == MAT_BLEND;
    m->n_opaque = m->n_tris - n_blend;
    if (n_blend == 0 || n_blend == m->n_tris)
        return 0;
    uint32_t(*tris)[3] = malloc((size_t)m->n_tris * sizeof *tris);
    uint16_t *mat = malloc((size_t)m->n_tris * sizeof *mat);
    if (!tris || !mat) {
        free(tris);
        free(mat);
        return -1;
    }
    uint32_t a = 0, b = m->n_opaque;
    for (uint32_t t = 0; t < m->n_tris; t++) {
        uint32_t d = m->materials[m->tri_material[t]].alpha_mode == MAT_BLEND ? b++ : a++;
        memcpy(tris[d], m->tris[t], sizeof tris[d]);
        mat[d] = m->tri_material[t];
    }
    free(m->tris);
    free(m->tri_material);
    m->tris = tris;
    m->tri_material = mat;
    return 0;
}

int model_finish(struct mesh *out, const struct model_ctx *ctx, struct err *e)
{
    /* the file's up axis (or --up-axis) turned to +Y */
    enum model_up up = model_opts_of(ctx)->up;
    char axis = up == MODEL_UP_X   ? 'x'
                : up == MODEL_UP_Y ? 'y'
                : up == MODEL_UP_Z ? 'z'
                : out->file_up ? out->file_up
                               : 'y';
    bool tangent_map = false;
    int uv_set = -1;
    out->features = false;
    for (uint32_t i = 0; i < out->n_materials; i++) {
        const struct material *m = &out->materials[i];
        out->features |= m->features;
        if (m->normal_map.tex >= 0 && m->normal_space == MAT_NORMAL_TANGENT) {
            tangent_map = true;
            uv_set = uv_set < 0 ? m->normal_map.uv : uv_set;
        }
    }
    uint32_t one = 0;
    for (uint32_t t = 0; t < out->n_tris; t++)
        one += out->materials[out->tri_material[t]].sides == MAT_ONE_SIDED;
    out->one_sided = one == 0 ? MESH_SIDES_NONE : one == out->n_tris ? MESH_SIDES_ALL
                                                                      : MESH_SIDES_SOME;
    char q[FILE_QUOTE_SIZE];
    file_quote(ctx->path ? ctx->path : "<memory>", q, sizeof q);
    if (sort_blended(out))
        return err_set(e, "%s: out of memory", q);
    if (tangent_map && !out->tangents && mesh_tangents(out, uv_set > 0 && out->uv1))
        return err_set(e, "%s: out of memory making tangents", q);
    mesh_turn_up(out, axis);
    return 0;
}

typedef int (*model_reader)(const char *, size_t, const struct model_ctx *, struct mesh *,
                            struct err *);
static const model_reader readers[MODEL_FORMAT_COUNT] = {obj_read,    stl_read,  ply_read,
                                                         import_read, gltf_read, draco_read};

int model_parse_as(enum model_format f, const char *data, size_t len,
                   const struct model_ctx *ctx, struct mesh *out, struct err *e)
{
    /* loaders always load textures through a cache (one decode per file, one budget);
     * without the caller's, a private one whose textures the mesh then owns */
    struct texture_cache local = {.solo = true};
    struct model_ctx c = *ctx;
    if (!c.cache)
        c.cache = &local;
    int rc = readers[f](data, len, &c, out, e);
    if (rc == 0)
        rc = model_finish(out, &c, e);
    if (!ctx->cache) {
        for (int i = 0; i < local.n; i++) {
            bool moved = false;
            for (uint32_t k = 0; rc == 0 && k < out->n_textures; k++)
                if (out->textures[k].rgba == local.entries[i]->tex.rgba) {
                    out->textures[k].borrowed = false; /* the mesh owns it now */
                    moved = true;
                }
            if (moved)
                local.entries[i]->tex.borrowed = true;
        }
        texture_cache_free(&local);
    }
    return rc;
}

/* Text the loaders can read from what the file holds: UTF-16 whose characters are all
 * ASCII becomes those bytes (Windows tools write OBJ and ASCII STL so); a file whose only
 * line ends are CRs (old Mac) gets LFs. NULL when the text needs neither (or when UTF-16
 * holds other characters: model_detect then says what it is). */
static char *readable_text(const char *data, size_t len, size_t *len_out)
{
    const uint8_t *d = (const uint8_t *)data;
    int u = utf16(d, len);
    if (u) {
        size_t start = (d[0] == 0xff && d[1] == 0xfe) || (d[0] == 0xfe && d[1] == 0xff) ? 2 : 0;
        char *t = malloc(len / 2 + 1);
        if (!t)
            return NULL;
        size_t k = 0;
        for (size_t i = start; i + 1 < len; i += 2) {
            unsigned c = u == 1 ? d[i] | d[i + 1] << 8 : d[i] << 8 | d[i + 1];
            if (c == 0 || c >= 0x80) {
                free(t);
                return NULL;
            }
            t[k++] = (char)c;
        }
        t[k] = '\0';
        *len_out = k;
        return t;
    }
    if (len && !memchr(data, '\n', len) && memchr(data, '\r', len) && !memchr(data, '\0', len)) {
        char *t = malloc(len + 1);
        if (!t)
            return NULL;
        for (size_t i = 0; i < len; i++)
            t[i] = data[i] == '\r' ? '\n' : data[i];
        t[len] = '\0';
        *len_out = len;
        return t;
    }
    return NULL;
}

int model_parse(const char *data, size_t len, const struct model_ctx *ctx, struct mesh *out,
                struct err *e)
{
    memset(out, 0, sizeof *out);
    size_t tn;
    char *text = readable_text(data, len, &tn);
    if (text)
        data = text, len = tn;
    enum model_format f;
    int rc = model_detect(data, len, ctx->path, &f, e);
    if (rc == 0)
        rc = model_parse_as(f, data, len, ctx, out, e);
    free(text);
    return rc;
}

const struct model_opts *model_opts_of(const struct model_ctx *ctx)
{
    static const struct model_opts defaults = {0};
    return ctx && ctx->opts ? ctx->opts : &defaults;
}

int model_load(const char *path, struct texture_cache *cache, struct warnings *w,
               struct mesh *out, struct err *e)
{
    return model_load_with(path, NULL, cache, w, out, e);
}

int model_load_with(const char *path, const struct model_opts *opts,
                    struct texture_cache *cache, struct warnings *w, struct mesh *out,
                    struct err *e)
{
    memset(out, 0, sizeof *out);
    char *data;
    size_t len;
    bool in = strcmp(path, "-") == 0; /* standard input: its name in messages is <stdin>,
                                          its MTL and textures are relative to . */
    int rc = in ? file_read_stdin(FILE_MAX_MODEL, &data, &len)
                : file_read(path, FILE_MAX_MODEL, &data, &len);
    if (rc) {
        char q[FILE_QUOTE_SIZE];
        return err_set(e, "%s: cannot read: %s",
                       in ? MODEL_STDIN_NAME : file_quote(path, q, sizeof q), file_strerror(rc));
    }
    struct model_ctx ctx = {.path = in ? MODEL_STDIN_NAME : path, .cache = cache, .warn = w,
                            .opts = opts};
    rc = model_parse(data, len, &ctx, out, e);
    free(data);
    return rc;
}
