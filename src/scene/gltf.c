/* gltf.c: glTF 2.0 -> struct mesh (see gltf.h for what is read). One pass over the default
 * scene's nodes: each placed primitive's vertices are read (accessors, or Draco), morphed,
 * skinned, moved into the model's space and appended; materials and their images after
 * that; then mesh_build. Every index and length in the file is checked before use. */
#include "gltf.h"

#include <ctype.h>
#include <math.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <meshoptimizer.h>

#include "draco.h"
#include "file.h"
#include "json.h"
#include "material.h"
#include "mtl.h"

#define GLTF_MAX_DEPTH 64         /* node nesting */
#define GLTF_MAX_PLACEMENTS 10000000 /* nodes x instances visited */

/* a 4x4 matrix, row-major, for column vectors: p' = m p */
typedef struct {
    double m[4][4];
} m4d;

static m4d mat_id(void)
{
    m4d r = {{{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}}};
    return r;
}

static m4d mat_mul(const m4d *a, const m4d *b)
{
    m4d r;
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++) {
            double s = 0;
            for (int k = 0; k < 4; k++)
                s += a->m[i][k] * b->m[k][j];
            r.m[i][j] = s;
        }
    return r;
}

/* T * R * S from a translation, a unit quaternion (x, y, z, w) and a scale */
static m4d mat_trs(const double t[3], const double q[4], const double s[3])
{
    double x = q[0], y = q[1], z = q[2], w = q[3];
    double n = sqrt(x * x + y * y + z * z + w * w);
    if (n > 0)
        x /= n, y /= n, z /= n, w /= n;
    else
        x = y = z = 0, w = 1;
    double r[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)},
                      {2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)},
                      {2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)}};
    m4d m = mat_id();
    for (int i = 0; i < 3; i++) {
        for (int j = 0; j < 3; j++)
            m.m[i][j] = r[i][j] * s[j];
        m.m[i][3] = t[i];
    }
    return m;
}

static double mat_det3(const m4d *a)
{
    const double(*m)[4] = a->m;
    return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
           m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

/* the normals' matrix: the cofactors of the upper 3x3 (det M^-T), turned by the sign of the
 * determinant so that a mirror keeps normals outward (the length is mesh_build's) */
static void mat_normal(const m4d *a, double n[3][3])
{
    const double(*m)[4] = a->m;
    double s = mat_det3(a) < 0 ? -1 : 1;
    n[0][0] = s * (m[1][1] * m[2][2] - m[1][2] * m[2][1]);
    n[0][1] = s * (m[1][2] * m[2][0] - m[1][0] * m[2][2]);
    n[0][2] = s * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    n[1][0] = s * (m[0][2] * m[2][1] - m[0][1] * m[2][2]);
    n[1][1] = s * (m[0][0] * m[2][2] - m[0][2] * m[2][0]);
    n[1][2] = s * (m[0][1] * m[2][0] - m[0][0] * m[2][1]);
    n[2][0] = s * (m[0][1] * m[1][2] - m[0][2] * m[1][1]);
    n[2][1] = s * (m[0][2] * m[1][0] - m[0][0] * m[1][2]);
    n[2][2] = s * (m[0][0] * m[1][1] - m[0][1] * m[1][0]);
}

/* ---- the reader's state ---- */

struct gbuf {
    const uint8_t *p;
    size_t n;
    uint8_t *owned;
    int state; /* 0 not read yet, 1 read, -1 failed */
};

/* a primitive's vertices as read (before placement) */
struct prim {
    uint32_t nv;
    size_t ni;
    float *pos, *nrm, *uv0, *uv1, *tan, *col; /* 3, 3, 2, 2, 4, 4 floats a vertex */
    float *weights;                           /* 4 x n_sets a vertex */
    uint32_t *joints;                         /* 4 x n_sets a vertex */
    int n_sets;                               /* JOINTS_n / WEIGHTS_n pairs */
    uint32_t *idx;
    int mode;
    int material; /* glTF material index, -1 none */
};

struct gl {
    const struct model_ctx *ctx;
    const char *where;
    struct err *e;
    size_t json_at; /* the JSON's offset in the file (GLB: 20) */
    const char *json; /* the JSON text, json_len bytes (for line and column in messages) */
    size_t json_len;
    struct json_doc doc;
    const struct json *root;
    const struct json *accessors, *views, *buffers, *meshes, *nodes, *materials, *textures,
        *images, *samplers, *cameras, *skins;
    const uint8_t *bin;
    size_t bin_len;
    bool has_bin;
    struct gbuf *buf;
    uint32_t n_buf;
    uint8_t **view_data; /* EXT_meshopt_compression: decoded views, per view (or NULL) */
    size_t *view_len;
    /* output, per vertex */
    float *pos, *nrm, *uv0, *uv1, *tan;
    uint8_t *rgba;
    uint32_t nv, cap_v;
    bool any_uv1, any_tan, any_col, any_nrm_missing, tan_missing;
    struct mesh_corner *corners;
    uint16_t *tri_mat;
    uint32_t nt, cap_t;
    /* materials: glTF material i is mesh material i + 1; which are used */
    bool *mat_used;
    uint32_t n_mats;
    /* nodes */
    m4d *world;        /* per node, once computed */
    uint8_t *world_st; /* 0 not yet, 1 computing, 2 done */
    int32_t *parent;
    unsigned long placements;
    /* cameras found */
    struct mesh_camera *cams;
    uint32_t n_cams;
    /* warnings said once */
    unsigned long skipped_points;
    bool warned_skin_sets, warned_cycle;
};

static int gfail(struct gl *G, const struct json *at, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));
/* "byte N" of the file for offset `at` of the JSON text; in a JSON of several lines also
 * "(line L, column C)", as an editor counts them (from 1, bytes) */
static const char *json_where(const struct gl *G, size_t at, char *buf, size_t n)
{
    size_t line = 1, col = 1;
    for (size_t i = 0; G->json && i < at && i < G->json_len; i++)
        if (G->json[i] == '\n')
            line++, col = 1;
        else
            col++;
    bool lines = G->json && memchr(G->json, '\n', G->json_len) != NULL;
    if (lines)
        snprintf(buf, n, "byte %zu (line %zu, column %zu)", G->json_at + at, line, col);
    else
        snprintf(buf, n, "byte %zu", G->json_at + at);
    return buf;
}

static int gfail(struct gl *G, const struct json *at, const char *fmt, ...)
{
    char msg[256], w[80];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    if (at)
        return err_set(G->e, "%s: %s: %s", G->where, json_where(G, at->at, w, sizeof w), msg);
    return err_set(G->e, "%s: %s", G->where, msg);
}

static void gwarn(struct gl *G, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void gwarn(struct gl *G, const char *fmt, ...)
{
    char msg[280];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    warn_add(G->ctx->warn, "%s: %s", G->where, msg);
}

/* a quoted string from the file, for messages */
static const char *q(const char *s, char *buf, size_t n)
{
    return err_quote(s ? s : "", s ? strlen(s) : 0, 60, buf, n);
}

static const struct json *arr_get(const struct json *arr, int64_t i)
{
    return i >= 0 && i < (int64_t)json_len(arr) ? json_at(arr, (uint32_t)i) : NULL;
}

/* member `key` of `obj` as an index into arr (required or not); -1 when absent */
static int64_t index_of(struct gl *G, const struct json *obj, const char *key,
                        const struct json *arr, const char *what, bool required, int *rc)
{
    const struct json *v = json_get(obj, key);
    if (!v) {
        if (required)
            *rc = gfail(G, obj, "%s: no \"%s\"", what, key);
        return -1;
    }
    if (!json_is_int(v) || v->num < 0 || v->num >= json_len(arr)) {
        *rc = gfail(G, v, "%s: \"%s\" must index one of the %u entries", what, key,
                    json_len(arr));
        return -1;
    }
    return (int64_t)v->num;
}

static float srgb_encode(float x)
{
    return material_srgb_encode(x);
}

/* ---- URIs and buffers ---- */

static int b64(int c)
{
    return c >= 'A' && c <= 'Z' ? c - 'A' : c >= 'a' && c <= 'z' ? c - 'a' + 26
           : c >= '0' && c <= '9' ? c - '0' + 52 : c == '+' || c == '-' ? 62
           : c == '/' || c == '_' ? 63 : -1;
}

/* data:[mime][;base64],payload -> bytes (malloc'd); -1 when it is no such URI or broken */
static int data_uri(const char *uri, uint8_t **out, size_t *n_out, bool *is_data)
{
    *is_data = strncmp(uri, "data:", 5) == 0;
    if (!*is_data)
        return -1;
    const char *comma = strchr(uri, ',');
    if (!comma)
        return -1;
    bool base64 = comma - uri >= 7 && memcmp(comma - 7, ";base64", 7) == 0;
    const char *p = comma + 1;
    size_t n = strlen(p);
    uint8_t *d = malloc(n + 1);
    if (!d)
        return -1;
    size_t k = 0;
    if (base64) {
        unsigned acc = 0;
        int bits = 0;
        for (size_t i = 0; i < n; i++) {
            if (p[i] == '=' || p[i] == ' ' || p[i] == '\n' || p[i] == '\r')
                continue;
            int v = b64((unsigned char)p[i]);
            if (v < 0) {
                free(d);
                return -1;
            }
            acc = acc << 6 | (unsigned)v;
            bits += 6;
            if (bits >= 8) {
                bits -= 8;
                d[k++] = (uint8_t)(acc >> bits);
            }
        }
    } else { /* percent-encoded bytes */
        for (size_t i = 0; i < n; i++) {
            if (p[i] == '%' && i + 2 < n + 0 && isxdigit((unsigned char)p[i + 1]) &&
                isxdigit((unsigned char)p[i + 2])) {
                char h[3] = {p[i + 1], p[i + 2], 0};
                d[k++] = (uint8_t)strtol(h, NULL, 16);
                i += 2;
            } else {
                d[k++] = (uint8_t)p[i];
            }
        }
    }
    *out = d;
    *n_out = k;
    return 0;
}

/* A file a URI names, relative to the model, percent-decoded; confined to the model's
 * folder tree unless --allow-outside. malloc'd path, or NULL with why (a static text or
 * an errno-based word) in *why. */
static char *uri_path(struct gl *G, const char *uri, const char **why)
{
    *why = NULL;
    if (!G->ctx->path) {
        *why = "a model read from memory may name no other file";
        return NULL;
    }
    if (strstr(uri, "://") || strncmp(uri, "file:", 5) == 0) {
        *why = strncmp(uri, "file:", 5) == 0 ? "file: URIs are not read (name the file "
                                               "relative to the model)"
                                             : "a URL: rastty reads no network";
        return NULL;
    }
    size_t n = strlen(uri);
    char *dec = malloc(n + 1), *d = dec;
    if (!dec) {
        *why = "out of memory";
        return NULL;
    }
    for (size_t i = 0; i < n; i++) {
        if (uri[i] == '%' && i + 2 < n && isxdigit((unsigned char)uri[i + 1]) &&
            isxdigit((unsigned char)uri[i + 2])) {
            char h[3] = {uri[i + 1], uri[i + 2], 0};
            *d++ = (char)strtol(h, NULL, 16);
            i += 2;
        } else {
            *d++ = uri[i];
        }
    }
    *d = '\0';
    if (memchr(dec, '\0', (size_t)(d - dec)) != NULL || strlen(dec) != (size_t)(d - dec)) {
        free(dec);
        *why = "a NUL byte in the name";
        return NULL;
    }
    char *path = material_path_beside(G->ctx->path, dec, strlen(dec));
    free(dec);
    if (!path) {
        *why = "out of memory";
        return NULL;
    }
    if (!model_opts_of(G->ctx)->any_path) {
        int in = file_inside_dir_of(G->ctx->path, path);
        if (in == 0) {
            free(path);
            *why = "outside the model's folder (--allow-outside reads it)";
            return NULL;
        }
        /* (a name that does not resolve: the read below says why) */
    }
    return path;
}

static const struct gbuf *buffer(struct gl *G, uint32_t i)
{
    struct gbuf *b = &G->buf[i];
    if (b->state)
        return b->state > 0 ? b : NULL;
    b->state = -1;
    const struct json *bj = json_at(G->buffers, i);
    const struct json *len_j = json_get(bj, "byteLength");
    if (!json_is_int(len_j) || len_j->num < 1) {
        gfail(G, bj, "buffer %u: byteLength must be a whole number of at least 1", i);
        return NULL;
    }
    size_t want = (size_t)len_j->num;
    const char *uri = json_str(json_get(bj, "uri"), NULL);
    char qb[80];
    if (!uri) {
        /* the GLB's binary chunk (buffer 0), or an EXT_meshopt_compression fallback */
        const struct json *mo = json_get(json_get(bj, "extensions"), "EXT_meshopt_compression");
        if (!mo)
            mo = json_get(json_get(bj, "extensions"), "KHR_meshopt_compression");
        if (i == 0 && G->has_bin) {
            if (G->bin_len < want) {
                gfail(G, len_j, "buffer 0: byteLength %zu, but the GLB's binary chunk has %zu",
                      want, G->bin_len);
                return NULL;
            }
            b->p = G->bin;
            b->n = want;
        } else if (mo && json_bool(json_get(mo, "fallback"), false)) {
            b->p = NULL; /* no data: only meshopt-decoded views may use it */
            b->n = want;
        } else {
            gfail(G, bj, "buffer %u has no uri and is not the GLB's binary chunk", i);
            return NULL;
        }
        b->state = 1;
        return b;
    }
    bool is_data;
    if (data_uri(uri, &b->owned, &b->n, &is_data) == 0) {
        b->p = b->owned;
    } else if (is_data) {
        gfail(G, bj, "buffer %u: a broken data: URI", i);
        return NULL;
    } else {
        const char *why;
        char *path = uri_path(G, uri, &why);
        if (!path) {
            gfail(G, bj, "buffer %u: '%s': %s", i, q(uri, qb, sizeof qb), why);
            return NULL;
        }
        char *data;
        size_t n;
        int rc = file_read(path, FILE_MAX_MODEL, &data, &n);
        free(path);
        if (rc) {
            gfail(G, bj, "buffer %u: cannot read '%s': %s", i, q(uri, qb, sizeof qb),
                  file_strerror(rc));
            return NULL;
        }
        b->owned = (uint8_t *)data;
        b->p = b->owned;
        b->n = n;
    }
    if (b->n < want) {
        gfail(G, bj, "buffer %u: byteLength %zu, but it holds %zu bytes", i, want, b->n);
        return NULL;
    }
    b->n = want;
    b->state = 1;
    return b;
}

/* ---- buffer views ---- */

struct view {
    const uint8_t *p;
    size_t n;
    size_t stride; /* 0: tightly packed */
};

/* EXT_meshopt_compression: the view's bytes decoded into view_data[i] */
static int meshopt_view(struct gl *G, uint32_t i, const struct json *vj, const struct json *mo)
{
    int rc = 0;
    int64_t bi = index_of(G, mo, "buffer", G->buffers, "EXT_meshopt_compression", true, &rc);
    if (rc)
        return -1;
    const struct gbuf *b = buffer(G, (uint32_t)bi);
    if (!b)
        return -1;
    int64_t off = json_int(json_get(mo, "byteOffset"), 0);
    int64_t len = json_int(json_get(mo, "byteLength"), -1);
    int64_t stride = json_int(json_get(mo, "byteStride"), -1);
    int64_t count = json_int(json_get(mo, "count"), -1);
    const char *mode = json_str(json_get(mo, "mode"), "");
    const char *filter = json_str(json_get(mo, "filter"), "NONE");
    if (off < 0 || len < 0 || !b->p || (uint64_t)off > b->n || (uint64_t)len > b->n - (size_t)off)
        return gfail(G, mo, "buffer view %u: EXT_meshopt_compression: its bytes are outside "
                            "buffer %lld",
                     i, (long long)bi);
    if (stride < 1 || stride > 256 || count < 1 || (uint64_t)count * (uint64_t)stride > (1ull << 31))
        return gfail(G, mo, "buffer view %u: EXT_meshopt_compression: bad count or byteStride",
                     i);
    size_t out_n = (size_t)count * (size_t)stride;
    uint8_t *out = malloc(out_n);
    if (!out)
        return gfail(G, NULL, "out of memory");
    const unsigned char *src = b->p + off;
    int r;
    if (strcmp(mode, "ATTRIBUTES") == 0) {
        if (stride % 4 != 0) {
            free(out);
            return gfail(G, mo, "buffer view %u: EXT_meshopt_compression: ATTRIBUTES need a "
                                "byteStride that is a multiple of 4",
                         i);
        }
        r = meshopt_decodeVertexBuffer(out, (size_t)count, (size_t)stride, src, (size_t)len);
    } else if (strcmp(mode, "TRIANGLES") == 0 || strcmp(mode, "INDICES") == 0) {
        if (stride != 2 && stride != 4) {
            free(out);
            return gfail(G, mo, "buffer view %u: EXT_meshopt_compression: indices are 2 or 4 "
                                "bytes",
                         i);
        }
        if (strcmp(mode, "TRIANGLES") == 0 && count % 3) {
            free(out);
            return gfail(G, mo, "buffer view %u: EXT_meshopt_compression: TRIANGLES count is "
                                "not a multiple of 3",
                         i);
        }
        r = mode[0] == 'T' ? meshopt_decodeIndexBuffer(out, (size_t)count, (size_t)stride, src,
                                                       (size_t)len)
                           : meshopt_decodeIndexSequence(out, (size_t)count, (size_t)stride,
                                                         src, (size_t)len);
    } else {
        free(out);
        char qb[80];
        return gfail(G, mo, "buffer view %u: EXT_meshopt_compression: unknown mode '%s'", i,
                     q(mode, qb, sizeof qb));
    }
    if (r != 0) {
        free(out);
        return gfail(G, mo, "buffer view %u: EXT_meshopt_compression: the compressed data is "
                            "corrupt (meshoptimizer: %d)",
                     i, r);
    }
    if (strcmp(filter, "OCTAHEDRAL") == 0 && (stride == 4 || stride == 8))
        meshopt_decodeFilterOct(out, (size_t)count, (size_t)stride);
    else if (strcmp(filter, "QUATERNION") == 0 && stride == 8)
        meshopt_decodeFilterQuat(out, (size_t)count, (size_t)stride);
    else if (strcmp(filter, "EXPONENTIAL") == 0 && stride % 4 == 0)
        meshopt_decodeFilterExp(out, (size_t)count, (size_t)stride);
    else if (strcmp(filter, "NONE") != 0) {
        free(out);
        char qb[80];
        return gfail(G, mo, "buffer view %u: EXT_meshopt_compression: filter '%s' does not fit "
                            "byteStride %lld",
                     i, q(filter, qb, sizeof qb), (long long)stride);
    }
    (void)vj;
    G->view_data[i] = out;
    G->view_len[i] = out_n;
    return 0;
}

static int view(struct gl *G, int64_t i, struct view *v)
{
    const struct json *vj = arr_get(G->views, i);
    if (!vj)
        return gfail(G, NULL, "buffer view %lld does not exist", (long long)i);
    int64_t stride = json_int(json_get(vj, "byteStride"), 0);
    const struct json *sj = json_get(vj, "byteStride");
    if (sj && (!json_is_int(sj) || stride < 4 || stride > 252 || stride % 4))
        return gfail(G, sj, "buffer view %lld: byteStride must be a multiple of 4 from 4 to "
                            "252",
                     (long long)i);
    v->stride = (size_t)stride;
    const struct json *mo = json_get(json_get(vj, "extensions"), "EXT_meshopt_compression");
    if (!mo)
        mo = json_get(json_get(vj, "extensions"), "KHR_meshopt_compression");
    if (mo) {
        if (!G->view_data[i] && meshopt_view(G, (uint32_t)i, vj, mo))
            return -1;
        v->p = G->view_data[i];
        v->n = G->view_len[i];
        return 0;
    }
    int rc = 0;
    int64_t bi = index_of(G, vj, "buffer", G->buffers, "buffer view", true, &rc);
    if (rc)
        return -1;
    const struct gbuf *b = buffer(G, (uint32_t)bi);
    if (!b)
        return -1;
    int64_t off = json_int(json_get(vj, "byteOffset"), 0);
    int64_t len = json_int(json_get(vj, "byteLength"), -1);
    if (off < 0 || len < 1 || !b->p || (uint64_t)off > b->n || (uint64_t)len > b->n - (size_t)off)
        return gfail(G, vj, "buffer view %lld: bytes %lld..%lld are outside buffer %lld (%zu "
                            "bytes)",
                     (long long)i, (long long)off, (long long)(off + len), (long long)bi,
                     b->n);
    v->p = b->p + off;
    v->n = (size_t)len;
    return 0;
}

/* ---- accessors ---- */

struct acc {
    uint32_t count;
    int comps, ctype, csize;
    bool normalized;
    const struct json *j;
};

static int comps_of(const char *type)
{
    static const struct {
        const char *name;
        int n;
    } t[] = {{"SCALAR", 1}, {"VEC2", 2}, {"VEC3", 3}, {"VEC4", 4},
             {"MAT2", 4},   {"MAT3", 9}, {"MAT4", 16}};
    for (size_t i = 0; i < sizeof t / sizeof *t; i++)
        if (strcmp(type, t[i].name) == 0)
            return t[i].n;
    return 0;
}

static int ctype_size(int64_t c)
{
    return c == 5120 || c == 5121 ? 1 : c == 5122 || c == 5123 ? 2 : c == 5125 || c == 5126 ? 4
                                                                                          : 0;
}

static double component(const uint8_t *p, int ctype, bool normalized)
{
    switch (ctype) {
    case 5120: {
        int8_t v = (int8_t)p[0];
        return normalized ? fmax(v / 127.0, -1.0) : v;
    }
    case 5121: return normalized ? p[0] / 255.0 : p[0];
    case 5122: {
        int16_t v = (int16_t)(p[0] | p[1] << 8);
        return normalized ? fmax(v / 32767.0, -1.0) : v;
    }
    case 5123: {
        uint16_t v = (uint16_t)(p[0] | p[1] << 8);
        return normalized ? v / 65535.0 : v;
    }
    case 5125: {
        uint32_t v = (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 |
                     (uint32_t)p[3] << 24;
        return normalized ? v / 4294967295.0 : v;
    }
    default: {
        uint32_t u = (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 |
                     (uint32_t)p[3] << 24;
        float f;
        memcpy(&f, &u, 4);
        return f;
    }
    }
}

static int accessor(struct gl *G, int64_t i, struct acc *a, const char *what)
{
    const struct json *aj = arr_get(G->accessors, i);
    if (!aj)
        return gfail(G, NULL, "%s: accessor %lld does not exist", what, (long long)i);
    a->j = aj;
    const struct json *cj = json_get(aj, "count");
    if (!json_is_int(cj) || cj->num < 1 || cj->num > GLTF_MAX_VERTS * 3.0)
        return gfail(G, cj ? cj : aj, "accessor %lld: count must be a whole number from 1 to "
                                      "%u",
                     (long long)i, GLTF_MAX_VERTS * 3);
    a->count = (uint32_t)cj->num;
    const char *type = json_str(json_get(aj, "type"), NULL);
    char qb[80];
    if (!type || !(a->comps = comps_of(type)))
        return gfail(G, json_get(aj, "type") ? json_get(aj, "type") : aj,
                     "accessor %lld: type '%s' is not a glTF accessor type (SCALAR, VEC2, VEC3, "
                     "VEC4, MAT2, MAT3, MAT4)",
                     (long long)i, q(type, qb, sizeof qb));
    int64_t ct = json_int(json_get(aj, "componentType"), -1);
    if (!(a->csize = ctype_size(ct)))
        return gfail(G, aj, "accessor %lld: componentType %lld is not a glTF component type",
                     (long long)i, (long long)ct);
    a->ctype = (int)ct;
    a->normalized = json_bool(json_get(aj, "normalized"), false);
    return 0;
}

/* The accessor's elements as doubles (count x comps), sparse values applied. The view's
 * layout is checked: every element inside the view and the buffer. */
static int acc_read(struct gl *G, int64_t i, const struct acc *a, double *out)
{
    const struct json *aj = a->j;
    size_t elem = (size_t)a->comps * (size_t)a->csize;
    if (a->comps >= 4 && a->csize < 4 && a->comps != 4) /* MATn of bytes: column padding */
        return gfail(G, aj, "accessor %lld: matrices of 1- or 2-byte components are not read",
                     (long long)i);
    const struct json *vj = json_get(aj, "bufferView");
    if (vj) {
        int rc = 0;
        int64_t vw = index_of(G, aj, "bufferView", G->views, "accessor", true, &rc);
        if (rc)
            return -1;
        struct view v;
        if (view(G, vw, &v))
            return -1;
        int64_t off = json_int(json_get(aj, "byteOffset"), 0);
        size_t stride = v.stride ? v.stride : elem;
        if (off < 0 || off % a->csize)
            return gfail(G, aj, "accessor %lld: byteOffset must be a multiple of its component "
                                "size",
                         (long long)i);
        if (stride < elem)
            return gfail(G, aj, "accessor %lld: byteStride %zu is shorter than an element (%zu "
                                "bytes)",
                         (long long)i, stride, elem);
        uint64_t need = (uint64_t)off + (uint64_t)stride * (a->count - 1) + elem;
        if (need > v.n)
            return gfail(G, aj, "accessor %lld: %u elements of %zu bytes every %zu from byte "
                                "%lld need %llu bytes; its buffer view has %zu",
                         (long long)i, a->count, elem, stride, (long long)off,
                         (unsigned long long)need, v.n);
        for (uint32_t k = 0; k < a->count; k++) {
            const uint8_t *p = v.p + (size_t)off + (size_t)k * stride;
            for (int c = 0; c < a->comps; c++)
                out[(size_t)k * a->comps + c] = component(p + (size_t)c * a->csize, a->ctype,
                                                          a->normalized);
        }
    } else {
        memset(out, 0, (size_t)a->count * a->comps * sizeof *out);
    }
    const struct json *sp = json_get(aj, "sparse");
    if (!sp)
        return 0;
    int64_t n = json_int(json_get(sp, "count"), -1);
    const struct json *ij = json_get(sp, "indices"), *vvj = json_get(sp, "values");
    if (n < 1 || n > a->count || !ij || !vvj)
        return gfail(G, sp, "accessor %lld: sparse needs a count from 1 to %u, indices and "
                            "values",
                     (long long)i, a->count);
    int rc = 0;
    int64_t iv = index_of(G, ij, "bufferView", G->views, "sparse indices", true, &rc);
    int64_t vv = rc ? -1 : index_of(G, vvj, "bufferView", G->views, "sparse values", true, &rc);
    if (rc)
        return -1;
    int64_t ict = json_int(json_get(ij, "componentType"), -1);
    int isz = ict == 5121 ? 1 : ict == 5123 ? 2 : ict == 5125 ? 4 : 0;
    if (!isz)
        return gfail(G, ij, "accessor %lld: sparse indices must be unsigned bytes, shorts or "
                            "ints",
                     (long long)i);
    struct view v1, v2;
    if (view(G, iv, &v1) || view(G, vv, &v2))
        return -1;
    int64_t o1 = json_int(json_get(ij, "byteOffset"), 0), o2 = json_int(json_get(vvj, "byteOffset"), 0);
    if (o1 < 0 || o2 < 0 || (uint64_t)o1 + (uint64_t)n * isz > v1.n ||
        (uint64_t)o2 + (uint64_t)n * elem > v2.n)
        return gfail(G, sp, "accessor %lld: sparse data outside its buffer views", (long long)i);
    for (int64_t k = 0; k < n; k++) {
        uint32_t at = (uint32_t)component(v1.p + o1 + k * isz, (int)ict, false);
        if (at >= a->count)
            return gfail(G, sp, "accessor %lld: sparse index %u past its %u elements",
                         (long long)i, at, a->count);
        for (int c = 0; c < a->comps; c++)
            out[(size_t)at * a->comps + c] = component(v2.p + o2 + (size_t)k * elem +
                                                           (size_t)c * a->csize,
                                                       a->ctype, a->normalized);
    }
    return 0;
}

/* An attribute accessor as floats, `want` components a vertex (the accessor must have
 * want, or want_alt, components: COLOR_0 is VEC3 or VEC4); malloc'd into *out. The
 * component types allowed are the specification's for the attribute (with
 * KHR_mesh_quantization's). Non-finite values become 0. */
static int attr_floats(struct gl *G, int64_t i, uint32_t count, int want, int want_alt,
                       const char *name, bool need_float_or_norm, float **out, int *comps_out)
{
    struct acc a;
    if (accessor(G, i, &a, name))
        return -1;
    if (a.comps != want && a.comps != want_alt)
        return gfail(G, a.j, "%s: accessor %lld has %d components a vertex, %d expected", name,
                     (long long)i, a.comps, want);
    if (count && a.count != count)
        return gfail(G, a.j, "%s: accessor %lld has %u elements, POSITION %u", name,
                     (long long)i, a.count, count);
    if (need_float_or_norm && a.ctype != 5126 && !a.normalized)
        return gfail(G, a.j, "%s: accessor %lld: integer components must be normalized", name,
                     (long long)i);
    double *d = malloc((size_t)a.count * a.comps * sizeof *d);
    float *f = malloc((size_t)a.count * a.comps * sizeof *f + 1);
    if (!d || !f) {
        free(d);
        free(f);
        return gfail(G, NULL, "out of memory");
    }
    if (acc_read(G, i, &a, d)) {
        free(d);
        free(f);
        return -1;
    }
    for (size_t k = 0; k < (size_t)a.count * a.comps; k++)
        f[k] = isfinite(d[k]) && fabs(d[k]) < 3e38 ? (float)d[k] : 0;
    free(d);
    *out = f;
    if (comps_out)
        *comps_out = a.comps;
    return 0;
}

/* ---- primitives ---- */

static void prim_free(struct prim *p)
{
    free(p->pos);
    free(p->nrm);
    free(p->uv0);
    free(p->uv1);
    free(p->tan);
    free(p->col);
    free(p->weights);
    free(p->joints);
    free(p->idx);
    memset(p, 0, sizeof *p);
}

static int64_t attr_index(struct gl *G, const struct json *attrs, const char *name, int *rc)
{
    return index_of(G, attrs, name, G->accessors, name, false, rc);
}

/* colours: COLOR_0 as rgba floats (alpha 1 for VEC3) */
static int read_colors(struct gl *G, int64_t ci, struct prim *p)
{
    int comps;
    float *c;
    if (attr_floats(G, ci, p->nv, 4, 3, "COLOR_0", true, &c, &comps))
        return -1;
    p->col = malloc((size_t)p->nv * 4 * sizeof *p->col);
    if (!p->col) {
        free(c);
        return gfail(G, NULL, "out of memory");
    }
    for (uint32_t v = 0; v < p->nv; v++)
        for (int k = 0; k < 4; k++)
            p->col[4 * (size_t)v + k] = k < comps ? c[(size_t)v * comps + k] : 1;
    free(c);
    return 0;
}

/* KHR_draco_mesh_compression: the primitive's vertices and indices from the Draco data */
static int read_draco(struct gl *G, const struct json *dj, struct prim *p)
{
    int rc = 0;
    int64_t vw = index_of(G, dj, "bufferView", G->views, "KHR_draco_mesh_compression", true, &rc);
    if (rc)
        return -1;
    struct view v;
    if (view(G, vw, &v))
        return -1;
    const struct json *attrs = json_get(dj, "attributes");
    static const char *const names[DRACO_ATTR_COUNT] = {"POSITION", "NORMAL", "TEXCOORD_0",
                                                        "TEXCOORD_1", "COLOR_0", "TANGENT",
                                                        "JOINTS_0", "WEIGHTS_0"};
    int ids[DRACO_ATTR_COUNT];
    for (int a = 0; a < DRACO_ATTR_COUNT; a++) {
        const struct json *id = json_get(attrs, names[a]);
        ids[a] = json_is_int(id) && id->num >= 0 && id->num < 1e6 ? (int)id->num : -1;
    }
    if (ids[DRACO_POSITION] < 0)
        return gfail(G, dj, "KHR_draco_mesh_compression: no POSITION attribute");
    struct draco_mesh dm;
    struct err de;
    if (draco_decode(v.p, v.n, ids, &dm, &de))
        return gfail(G, dj, "KHR_draco_mesh_compression: %s", de.msg);
    p->nv = dm.n_points;
    p->ni = (size_t)dm.n_faces * 3;
    p->idx = dm.faces;
    dm.faces = NULL;
    p->pos = dm.attr[DRACO_POSITION], dm.attr[DRACO_POSITION] = NULL;
    if (dm.attr[DRACO_NORMAL] && dm.comps[DRACO_NORMAL] == 3)
        p->nrm = dm.attr[DRACO_NORMAL], dm.attr[DRACO_NORMAL] = NULL;
    if (dm.attr[DRACO_UV0] && dm.comps[DRACO_UV0] == 2)
        p->uv0 = dm.attr[DRACO_UV0], dm.attr[DRACO_UV0] = NULL;
    if (dm.attr[DRACO_UV1] && dm.comps[DRACO_UV1] == 2)
        p->uv1 = dm.attr[DRACO_UV1], dm.attr[DRACO_UV1] = NULL;
    if (dm.attr[DRACO_TANGENT] && dm.comps[DRACO_TANGENT] == 4)
        p->tan = dm.attr[DRACO_TANGENT], dm.attr[DRACO_TANGENT] = NULL;
    int cc = dm.comps[DRACO_COLOR];
    if (dm.attr[DRACO_COLOR] && (cc == 3 || cc == 4)) {
        p->col = malloc((size_t)p->nv * 4 * sizeof *p->col);
        if (p->col)
            for (uint32_t k = 0; k < p->nv; k++)
                for (int c = 0; c < 4; c++)
                    p->col[4 * (size_t)k + c] = c < cc ? dm.attr[DRACO_COLOR][(size_t)k * cc + c]
                                                       : 1;
    }
    if (dm.attr[DRACO_JOINTS] && dm.attr[DRACO_WEIGHTS] && dm.comps[DRACO_JOINTS] == 4 &&
        dm.comps[DRACO_WEIGHTS] == 4) {
        p->n_sets = 1;
        p->weights = dm.attr[DRACO_WEIGHTS], dm.attr[DRACO_WEIGHTS] = NULL;
        p->joints = malloc((size_t)p->nv * 4 * sizeof *p->joints);
        if (p->joints)
            for (size_t k = 0; k < (size_t)p->nv * 4; k++) {
                float j = dm.attr[DRACO_JOINTS][k];
                p->joints[k] = j >= 0 && j < 65536 ? (uint32_t)j : 0;
            }
    }
    /* draco's attributes are glTF's, with one difference: the decoder gives colours of
     * normalized integers as their integers */
    if (p->col && cc && dm.attr[DRACO_COLOR]) {
        float mx = 0;
        for (size_t k = 0; k < (size_t)p->nv * 4; k++)
            mx = p->col[k] > mx ? p->col[k] : mx;
        if (mx > 1.0001f) {
            float s = mx > 255.5f ? 1.0f / 65535 : 1.0f / 255;
            for (size_t k = 0; k < (size_t)p->nv * 4; k++)
                if (k % 4 < (size_t)cc)
                    p->col[k] *= s;
        }
    }
    draco_mesh_free(&dm);
    for (size_t k = 0; k < p->ni; k++)
        if (p->idx[k] >= p->nv)
            return gfail(G, dj, "KHR_draco_mesh_compression: a face names point %u of %u",
                         p->idx[k], p->nv);
    return 0;
}

/* the primitive's vertices (morphed by `weights`, n_weights of them) and indices */
static int read_prim(struct gl *G, const struct json *pj, const double *weights, uint32_t n_w,
                     struct prim *p)
{
    memset(p, 0, sizeof *p);
    p->mode = (int)json_int(json_get(pj, "mode"), 4);
    int rc = 0;
    p->material = (int)index_of(G, pj, "material", G->materials, "primitive", false, &rc);
    if (rc)
        return -1;
    const struct json *attrs = json_get(pj, "attributes");
    if (!attrs || attrs->type != JSON_OBJECT)
        return gfail(G, pj, "primitive: no attributes");
    const struct json *draco =
        json_get(json_get(pj, "extensions"), "KHR_draco_mesh_compression");
    if (draco)
        return read_draco(G, draco, p);
    int64_t pi = attr_index(G, attrs, "POSITION", &rc);
    if (rc)
        return -1;
    if (pi < 0)
        return gfail(G, pj, "primitive: no POSITION");
    struct acc a;
    if (accessor(G, pi, &a, "POSITION"))
        return -1;
    p->nv = a.count;
    if (attr_floats(G, pi, p->nv, 3, 3, "POSITION", false, &p->pos, NULL))
        return -1;
    int64_t ni = attr_index(G, attrs, "NORMAL", &rc), ti = attr_index(G, attrs, "TANGENT", &rc),
            u0 = attr_index(G, attrs, "TEXCOORD_0", &rc), u1 = attr_index(G, attrs, "TEXCOORD_1", &rc),
            ci = attr_index(G, attrs, "COLOR_0", &rc);
    if (rc)
        return -1;
    if ((ni >= 0 && attr_floats(G, ni, p->nv, 3, 3, "NORMAL", true, &p->nrm, NULL)) ||
        (ti >= 0 && attr_floats(G, ti, p->nv, 4, 4, "TANGENT", true, &p->tan, NULL)) ||
        (u0 >= 0 && attr_floats(G, u0, p->nv, 2, 2, "TEXCOORD_0", false, &p->uv0, NULL)) ||
        (u1 >= 0 && attr_floats(G, u1, p->nv, 2, 2, "TEXCOORD_1", false, &p->uv1, NULL)) ||
        (ci >= 0 && read_colors(G, ci, p)))
        return -1;
    /* skins: JOINTS_n with WEIGHTS_n */
    for (int set = 0; set < 2; set++) {
        char jn[24], wn[24]; /* (room for any int: the sanitizer build checks it) */
        snprintf(jn, sizeof jn, "JOINTS_%d", set);
        snprintf(wn, sizeof wn, "WEIGHTS_%d", set);
        int64_t ji = attr_index(G, attrs, jn, &rc), wi = attr_index(G, attrs, wn, &rc);
        if (rc)
            return -1;
        if (ji < 0 || wi < 0)
            break;
        float *j, *w;
        if (attr_floats(G, ji, p->nv, 4, 4, jn, false, &j, NULL))
            return -1;
        if (attr_floats(G, wi, p->nv, 4, 4, wn, true, &w, NULL)) {
            free(j);
            return -1;
        }
        size_t n = (size_t)p->nv * 4 * (size_t)(set + 1);
        uint32_t *nj = realloc(p->joints, n * sizeof *nj);
        if (nj)
            p->joints = nj;
        float *nw = nj ? realloc(p->weights, n * sizeof *nw) : NULL;
        if (!nw) {
            free(j);
            free(w);
            return gfail(G, NULL, "out of memory");
        }
        p->weights = nw;
        /* interleave: vertex v's influences at [8 v .. 8 v + 4 n_sets) */
        if (set == 1) {
            for (size_t v = p->nv; v-- > 0;)
                for (int k = 3; k >= 0; k--) {
                    p->joints[8 * v + k] = p->joints[4 * v + k];
                    p->weights[8 * v + k] = p->weights[4 * v + k];
                }
        }
        size_t per = 4 * (size_t)(set + 1);
        for (size_t v = 0; v < p->nv; v++)
            for (int k = 0; k < 4; k++) {
                float jv = j[4 * v + k];
                p->joints[per * v + 4 * (size_t)set + k] = jv >= 0 && jv < 65536 ? (uint32_t)jv : 0;
                p->weights[per * v + 4 * (size_t)set + k] = w[4 * v + k];
            }
        free(j);
        free(w);
        p->n_sets = set + 1;
    }
    /* morph targets at their default weights */
    const struct json *targets = json_get(pj, "targets");
    for (uint32_t t = 0; t < json_len(targets) && t < n_w; t++) {
        if (weights[t] == 0)
            continue;
        const struct json *tj = json_at(targets, t);
        static const char *const names[3] = {"POSITION", "NORMAL", "TANGENT"};
        float *dst[3] = {p->pos, p->nrm, p->tan};
        for (int k = 0; k < 3; k++) {
            int64_t di = attr_index(G, tj, names[k], &rc);
            if (rc)
                return -1;
            if (di < 0 || !dst[k])
                continue;
            float *d;
            if (attr_floats(G, di, p->nv, 3, 3, names[k], false, &d, NULL))
                return -1;
            int stride = k == 2 ? 4 : 3;
            for (size_t v = 0; v < p->nv; v++)
                for (int c = 0; c < 3; c++)
                    dst[k][(size_t)v * stride + c] += (float)(weights[t] * d[3 * v + c]);
            free(d);
        }
    }
    /* indices */
    int64_t ii = index_of(G, pj, "indices", G->accessors, "primitive", false, &rc);
    if (rc)
        return -1;
    if (ii >= 0) {
        struct acc ia;
        if (accessor(G, ii, &ia, "indices"))
            return -1;
        if (ia.comps != 1 || (ia.ctype != 5121 && ia.ctype != 5123 && ia.ctype != 5125))
            return gfail(G, ia.j, "indices: accessor %lld must be SCALAR unsigned bytes, shorts "
                                  "or ints",
                         (long long)ii);
        double *d = malloc((size_t)ia.count * sizeof *d);
        p->idx = malloc((size_t)ia.count * sizeof *p->idx);
        if (!d || !p->idx) {
            free(d);
            return gfail(G, NULL, "out of memory");
        }
        if (acc_read(G, ii, &ia, d)) {
            free(d);
            return -1;
        }
        p->ni = ia.count;
        for (size_t k = 0; k < p->ni; k++) {
            if (!(d[k] >= 0 && d[k] < p->nv)) {
                uint32_t bad = (uint32_t)d[k];
                free(d);
                return gfail(G, ia.j, "indices: accessor %lld: index %u past the %u vertices",
                             (long long)ii, bad, p->nv);
            }
            p->idx[k] = (uint32_t)d[k];
        }
        free(d);
    } else {
        p->ni = p->nv;
        p->idx = malloc((size_t)p->nv * sizeof *p->idx);
        if (!p->idx)
            return gfail(G, NULL, "out of memory");
        for (uint32_t k = 0; k < p->nv; k++)
            p->idx[k] = k;
    }
    return 0;
}

/* ---- appending placed vertices and triangles ---- */

static int grow(struct gl *G, uint32_t add_v, size_t add_t)
{
    if ((uint64_t)G->nv + add_v > GLTF_MAX_VERTS || (uint64_t)G->nt + add_t > GLTF_MAX_TRIS)
        return gfail(G, NULL, "more than %u triangles or vertices after instancing (at %u and "
                              "%u with %zu more): too large to draw",
                     GLTF_MAX_TRIS, G->nt, G->nv, add_t);
    if (G->nv + add_v > G->cap_v) {
        uint32_t cap = G->cap_v ? G->cap_v : 1024;
        while (cap < G->nv + add_v)
            cap = cap > GLTF_MAX_VERTS / 2 ? GLTF_MAX_VERTS : cap * 2;
        float **fa[5] = {&G->pos, &G->nrm, &G->uv0, &G->uv1, &G->tan};
        const int fc[5] = {3, 3, 2, 2, 4};
        for (int k = 0; k < 5; k++) {
            float *n = realloc(*fa[k], (size_t)cap * fc[k] * sizeof *n);
            if (!n)
                return gfail(G, NULL, "out of memory");
            *fa[k] = n;
        }
        uint8_t *c = realloc(G->rgba, (size_t)cap * 4);
        if (!c)
            return gfail(G, NULL, "out of memory");
        G->rgba = c;
        G->cap_v = cap;
    }
    if (G->nt + add_t > G->cap_t) {
        size_t cap = G->cap_t ? G->cap_t : 1024;
        while (cap < G->nt + add_t)
            cap *= 2;
        struct mesh_corner *c = realloc(G->corners, cap * 3 * sizeof *c);
        if (c)
            G->corners = c;
        uint16_t *m = c ? realloc(G->tri_mat, cap * sizeof *m) : NULL;
        if (!m)
            return gfail(G, NULL, "out of memory");
        G->tri_mat = m;
        G->cap_t = (uint32_t)cap;
    }
    return 0;
}

/* vertex v of the primitive, skinned: sum w J p over its influences */
static void skin_point(const struct prim *p, uint32_t v, const m4d *joints, uint32_t n_joints,
                       const float *in, int n_in, bool point, float *out)
{
    double acc[3] = {0, 0, 0}, wsum = 0;
    int per = 4 * p->n_sets;
    for (int k = 0; k < per; k++) {
        float w = p->weights[(size_t)v * per + k];
        uint32_t j = p->joints[(size_t)v * per + k];
        if (!(w > 0) || j >= n_joints)
            continue;
        const m4d *m = &joints[j];
        for (int r = 0; r < 3; r++)
            acc[r] += w * (m->m[r][0] * in[0] + m->m[r][1] * in[1] + m->m[r][2] * in[2] +
                           (point ? m->m[r][3] : 0));
        wsum += w;
    }
    if (wsum > 0)
        for (int r = 0; r < 3; r++)
            out[r] = (float)(acc[r] / wsum);
    else
        for (int r = 0; r < 3; r++)
            out[r] = in[r];
    (void)n_in;
}

/* the primitive placed by xf (or by its skin's joints) appended to the mesh */
static int place(struct gl *G, const struct prim *p, const m4d *xf, const m4d *joints,
                 uint32_t n_joints)
{
    size_t nt = 0;
    if (p->mode == 4)
        nt = p->ni / 3;
    else if ((p->mode == 5 || p->mode == 6) && p->ni >= 3)
        nt = p->ni - 2;
    else {
        G->skipped_points++;
        return 0;
    }
    if (nt == 0)
        return 0;
    if (grow(G, p->nv, nt))
        return -1;
    bool skin = joints && p->weights && p->n_sets;
    double nm[3][3];
    mat_normal(xf, nm);
    bool mirrored = !skin && mat_det3(xf) < 0;
    uint32_t base = G->nv;
    for (uint32_t v = 0; v < p->nv; v++) {
        float *dp = &G->pos[3 * (size_t)(base + v)], *dn = &G->nrm[3 * (size_t)(base + v)];
        const float *sp = &p->pos[3 * (size_t)v];
        if (skin) {
            skin_point(p, v, joints, n_joints, sp, 3, true, dp);
        } else {
            for (int r = 0; r < 3; r++)
                dp[r] = (float)(xf->m[r][0] * sp[0] + xf->m[r][1] * sp[1] + xf->m[r][2] * sp[2] +
                                xf->m[r][3]);
        }
        if (p->nrm) {
            const float *sn = &p->nrm[3 * (size_t)v];
            if (skin) {
                skin_point(p, v, joints, n_joints, sn, 3, false, dn); /* (no scale: close) */
            } else {
                for (int r = 0; r < 3; r++)
                    dn[r] = (float)(nm[r][0] * sn[0] + nm[r][1] * sn[1] + nm[r][2] * sn[2]);
            }
        } else {
            dn[0] = dn[1] = dn[2] = 0;
        }
        float *du = &G->uv0[2 * (size_t)(base + v)], *du1 = &G->uv1[2 * (size_t)(base + v)];
        /* glTF's v runs down the image; rastty's (OBJ's) up */
        du[0] = p->uv0 ? p->uv0[2 * (size_t)v] : 0;
        du[1] = p->uv0 ? 1 - p->uv0[2 * (size_t)v + 1] : 0;
        du1[0] = p->uv1 ? p->uv1[2 * (size_t)v] : du[0];
        du1[1] = p->uv1 ? 1 - p->uv1[2 * (size_t)v + 1] : du[1];
        float *dt = &G->tan[4 * (size_t)(base + v)];
        if (p->tan) {
            const float *st = &p->tan[4 * (size_t)v];
            if (skin)
                skin_point(p, v, joints, n_joints, st, 3, false, dt);
            else
                for (int r = 0; r < 3; r++)
                    dt[r] = (float)(xf->m[r][0] * st[0] + xf->m[r][1] * st[1] + xf->m[r][2] * st[2]);
            float l = sqrtf(dt[0] * dt[0] + dt[1] * dt[1] + dt[2] * dt[2]);
            for (int r = 0; r < 3; r++)
                dt[r] = l > 0 ? dt[r] / l : (r == 0);
            /* the bitangent's sign (B = w N x T, the normal map's +Y: up the image, glTF's
             * -v and rastty's +v), turned by a mirror */
            dt[3] = (st[3] < 0 ? -1.0f : 1.0f) * (mirrored ? -1.0f : 1.0f);
        } else {
            dt[0] = 1, dt[1] = dt[2] = 0, dt[3] = 1;
        }
        uint8_t *dc = &G->rgba[4 * (size_t)(base + v)];
        for (int k = 0; k < 4; k++) {
            float c = p->col ? p->col[4 * (size_t)v + k] : 1;
            c = k < 3 ? srgb_encode(c) : (c > 0 ? (c < 1 ? c : 1) : 0);
            dc[k] = (uint8_t)(c * 255 + 0.5f);
        }
    }
    G->nv += p->nv;
    G->any_uv1 |= p->uv1 != NULL;
    G->any_col |= p->col != NULL;
    G->any_tan |= p->tan != NULL;
    G->tan_missing |= p->tan == NULL;
    uint16_t mi = p->material >= 0 && (uint32_t)p->material < G->n_mats
                      ? (uint16_t)(p->material + 1)
                      : 0;
    if (mi)
        G->mat_used[mi - 1] = true;
    for (size_t t = 0; t < nt; t++) {
        uint32_t c[3];
        if (p->mode == 4) {
            c[0] = p->idx[3 * t], c[1] = p->idx[3 * t + 1], c[2] = p->idx[3 * t + 2];
        } else if (p->mode == 5) { /* strips alternate their winding */
            c[0] = p->idx[t + (t & 1)], c[1] = p->idx[t + 1 - (t & 1)], c[2] = p->idx[t + 2];
        } else {
            c[0] = p->idx[t + 1], c[1] = p->idx[t + 2], c[2] = p->idx[0];
        }
        if (c[0] == c[1] || c[1] == c[2] || c[0] == c[2])
            continue; /* degenerate by index: strips' restarts */
        struct mesh_corner *mc = &G->corners[3 * (size_t)G->nt];
        for (int k = 0; k < 3; k++) {
            uint32_t vw = base + c[mirrored && k ? 3 - k : k];
            mc[k] = (struct mesh_corner){vw, p->uv0 ? vw : MESH_NONE, p->nrm ? vw : MESH_NONE};
        }
        G->any_nrm_missing |= p->nrm == NULL;
        G->tri_mat[G->nt++] = mi;
    }
    return 0;
}

/* ---- nodes ---- */

static m4d node_local(const struct json *nj)
{
    const struct json *m = json_get(nj, "matrix");
    if (json_len(m) == 16) {
        m4d r;
        for (int c = 0; c < 4; c++)
            for (int row = 0; row < 4; row++)
                r.m[row][c] = json_num(json_at(m, (uint32_t)(c * 4 + row)), row == c);
        return r;
    }
    double t[3] = {0, 0, 0}, qt[4] = {0, 0, 0, 1}, s[3] = {1, 1, 1};
    const struct json *tj = json_get(nj, "translation"), *rj = json_get(nj, "rotation"),
                      *sj = json_get(nj, "scale");
    for (uint32_t k = 0; k < 3; k++) {
        if (json_len(tj) == 3)
            t[k] = json_num(json_at(tj, k), 0);
        if (json_len(sj) == 3)
            s[k] = json_num(json_at(sj, k), 1);
    }
    if (json_len(rj) == 4)
        for (uint32_t k = 0; k < 4; k++)
            qt[k] = json_num(json_at(rj, k), k == 3);
    return mat_trs(t, qt, s);
}

/* node i's world matrix: its parents' chain (a cycle: identity, once warned) */
static m4d world_of(struct gl *G, uint32_t i, int depth)
{
    if (G->world_st[i] == 2)
        return G->world[i];
    if (G->world_st[i] == 1 || depth > GLTF_MAX_DEPTH) {
        G->warned_cycle = true;
        return mat_id();
    }
    G->world_st[i] = 1;
    m4d local = node_local(json_at(G->nodes, i)), w = local;
    if (G->parent[i] >= 0) {
        m4d pw = world_of(G, (uint32_t)G->parent[i], depth + 1);
        w = mat_mul(&pw, &local);
    }
    G->world[i] = w;
    G->world_st[i] = 2;
    return w;
}

/* EXT_mesh_gpu_instancing: the node's instance matrices (malloc'd), or NULL and *n 0 */
static int instances(struct gl *G, const struct json *nj, m4d **out, uint32_t *n)
{
    *out = NULL;
    *n = 0;
    const struct json *ext = json_get(json_get(nj, "extensions"), "EXT_mesh_gpu_instancing");
    const struct json *attrs = json_get(ext, "attributes");
    if (!attrs)
        return 0;
    static const char *const names[3] = {"TRANSLATION", "ROTATION", "SCALE"};
    float *d[3] = {NULL, NULL, NULL};
    uint32_t count = 0;
    int rc = 0;
    for (int k = 0; k < 3 && rc == 0; k++) {
        int64_t ai = index_of(G, attrs, names[k], G->accessors, names[k], false, &rc);
        if (rc || ai < 0)
            continue;
        struct acc a;
        if (accessor(G, ai, &a, names[k])) {
            rc = -1;
            break;
        }
        if (count && a.count != count) {
            rc = gfail(G, a.j, "EXT_mesh_gpu_instancing: %s has %u instances, another %u",
                       names[k], a.count, count);
            break;
        }
        count = a.count;
        rc = attr_floats(G, ai, count, k == 1 ? 4 : 3, k == 1 ? 4 : 3, names[k], k == 1, &d[k],
                         NULL);
    }
    if (rc == 0 && count) {
        *out = malloc((size_t)count * sizeof **out);
        if (!*out)
            rc = gfail(G, NULL, "out of memory");
        for (uint32_t i = 0; rc == 0 && i < count; i++) {
            double t[3] = {0, 0, 0}, r[4] = {0, 0, 0, 1}, s[3] = {1, 1, 1};
            for (int k = 0; k < 4; k++) {
                if (k < 3 && d[0])
                    t[k] = d[0][3 * (size_t)i + k];
                if (d[1])
                    r[k] = d[1][4 * (size_t)i + k];
                if (k < 3 && d[2])
                    s[k] = d[2][3 * (size_t)i + k];
            }
            (*out)[i] = mat_trs(t, r, s);
        }
        if (rc == 0)
            *n = count;
    }
    for (int k = 0; k < 3; k++)
        free(d[k]);
    if (rc) {
        free(*out);
        *out = NULL;
    }
    return rc;
}

/* the joint matrices of node nj's skin (world(joint) x inverse bind), malloc'd */
static int skin_joints(struct gl *G, const struct json *nj, m4d **out, uint32_t *n)
{
    *out = NULL;
    *n = 0;
    int rc = 0;
    int64_t si = index_of(G, nj, "skin", G->skins, "node", false, &rc);
    if (rc || si < 0)
        return rc;
    const struct json *sk = json_at(G->skins, (uint32_t)si), *jl = json_get(sk, "joints");
    uint32_t nj_ = json_len(jl);
    if (nj_ == 0)
        return 0;
    float *ibm = NULL;
    int64_t ai = index_of(G, sk, "inverseBindMatrices", G->accessors, "skin", false, &rc);
    if (rc)
        return -1;
    if (ai >= 0 && attr_floats(G, ai, nj_, 16, 16, "inverseBindMatrices", false, &ibm, NULL))
        return -1;
    m4d *m = malloc((size_t)nj_ * sizeof *m);
    if (!m) {
        free(ibm);
        return gfail(G, NULL, "out of memory");
    }
    for (uint32_t k = 0; k < nj_; k++) {
        const struct json *jj = json_at(jl, k);
        if (!json_is_int(jj) || jj->num < 0 || jj->num >= json_len(G->nodes)) {
            free(m);
            free(ibm);
            return gfail(G, jj, "skin %lld: joint %u is not a node", (long long)si, k);
        }
        m4d w = world_of(G, (uint32_t)jj->num, 0), b = mat_id();
        if (ibm)
            for (int c = 0; c < 4; c++)
                for (int r = 0; r < 4; r++)
                    b.m[r][c] = ibm[16 * (size_t)k + 4 * (size_t)c + r];
        m[k] = mat_mul(&w, &b);
    }
    free(ibm);
    *out = m;
    *n = nj_;
    return 0;
}

static void add_camera(struct gl *G, const struct json *nj, const m4d *w, int64_t ci)
{
    const struct json *cj = json_at(G->cameras, (uint32_t)ci);
    if (G->n_cams >= MESH_MAX_CAMERAS || !cj)
        return;
    struct mesh_camera c;
    memset(&c, 0, sizeof c);
    const char *name = json_str(json_get(cj, "name"), json_str(json_get(nj, "name"), ""));
    err_quote(name, strlen(name), MESH_NAME_MAX - 5, c.name, sizeof c.name);
    for (int r = 0; r < 3; r++) {
        c.eye[r] = (float)w->m[r][3];
        c.forward[r] = (float)-w->m[r][2];
        c.up[r] = (float)w->m[r][1];
    }
    float lf = sqrtf(c.forward[0] * c.forward[0] + c.forward[1] * c.forward[1] +
                     c.forward[2] * c.forward[2]),
          lu = sqrtf(c.up[0] * c.up[0] + c.up[1] * c.up[1] + c.up[2] * c.up[2]);
    if (!(lf > 0) || !(lu > 0))
        return;
    for (int r = 0; r < 3; r++)
        c.forward[r] /= lf, c.up[r] /= lu;
    const char *type = json_str(json_get(cj, "type"), "");
    if (strcmp(type, "orthographic") == 0) {
        const struct json *o = json_get(cj, "orthographic");
        c.ortho_height = (float)(2 * fabs(json_num(json_get(o, "ymag"), 1)) * lu);
        c.znear = (float)json_num(json_get(o, "znear"), 0.01);
        c.zfar = (float)json_num(json_get(o, "zfar"), 100);
    } else {
        const struct json *pp = json_get(cj, "perspective");
        double yfov = json_num(json_get(pp, "yfov"), 0.8);
        c.yfov_deg = (float)(yfov * 180 / M_PI);
        c.znear = (float)json_num(json_get(pp, "znear"), 0.01);
        c.zfar = (float)json_num(json_get(pp, "zfar"), 0);
        if (!(c.yfov_deg > 0.01f && c.yfov_deg < 179.99f))
            c.yfov_deg = 45;
    }
    if (!(c.znear > 0))
        c.znear = 0.01f;
    if (!(c.zfar > c.znear))
        c.zfar = 0;
    G->cams[G->n_cams++] = c;
}

/* node i and its children, depth first */
static int walk(struct gl *G, uint32_t i, int depth)
{
    if (depth > GLTF_MAX_DEPTH || ++G->placements > GLTF_MAX_PLACEMENTS) {
        G->warned_cycle = true;
        return 0;
    }
    const struct json *nj = json_at(G->nodes, i);
    m4d w = world_of(G, i, 0);
    int rc = 0;
    int64_t ci = index_of(G, nj, "camera", G->cameras, "node", false, &rc);
    if (rc)
        return -1;
    if (ci >= 0)
        add_camera(G, nj, &w, ci);
    int64_t mi = index_of(G, nj, "mesh", G->meshes, "node", false, &rc);
    if (rc)
        return -1;
    if (mi >= 0) {
        const struct json *mj = json_at(G->meshes, (uint32_t)mi);
        const struct json *prims = json_get(mj, "primitives");
        const struct json *wj = json_get(nj, "weights");
        if (!wj)
            wj = json_get(mj, "weights");
        double wts[64];
        uint32_t n_w = json_len(wj) < 64 ? json_len(wj) : 64;
        for (uint32_t k = 0; k < n_w; k++)
            wts[k] = json_num(json_at(wj, k), 0);
        m4d *inst = NULL, *joints = NULL;
        uint32_t n_inst = 0, n_joints = 0;
        if (instances(G, nj, &inst, &n_inst) || skin_joints(G, nj, &joints, &n_joints)) {
            free(inst);
            return -1;
        }
        for (uint32_t k = 0; rc == 0 && k < json_len(prims); k++) {
            struct prim p;
            if (read_prim(G, json_at(prims, k), wts, n_w, &p)) {
                prim_free(&p);
                rc = -1;
                break;
            }
            /* the instances' triangles at once: a file instanced past the limit fails
             * before it is built up to it (120 x 200k triangles took seconds and GBs) */
            uint64_t all_t = (uint64_t)n_inst * (p.ni / 3), all_v = (uint64_t)n_inst * p.nv;
            if (n_inst && (G->nt + all_t > GLTF_MAX_TRIS || G->nv + all_v > GLTF_MAX_VERTS)) {
                rc = gfail(G, NULL, "node %u: %u instances of %llu triangles make more than %u "
                                    "triangles or vertices: too large to draw",
                           i, n_inst, (unsigned long long)(p.ni / 3), GLTF_MAX_TRIS);
                prim_free(&p);
                break;
            }
            if (n_inst) {
                for (uint32_t t = 0; rc == 0 && t < n_inst; t++) {
                    m4d x = mat_mul(&w, &inst[t]);
                    rc = place(G, &p, &x, NULL, 0);
                }
            } else {
                rc = place(G, &p, &w, joints, n_joints);
            }
            prim_free(&p);
        }
        free(inst);
        free(joints);
        if (rc)
            return -1;
    }
    const struct json *kids = json_get(nj, "children");
    for (uint32_t k = 0; k < json_len(kids); k++) {
        const struct json *c = json_at(kids, k);
        if (!json_is_int(c) || c->num < 0 || c->num >= json_len(G->nodes))
            return gfail(G, c, "node %u: child %u is not a node", i, k);
        if (walk(G, (uint32_t)c->num, depth + 1))
            return -1;
    }
    return 0;
}

/* ---- extensions ---- */

enum ext_kind { EXT_DRAWN, EXT_HARMLESS, EXT_FALLBACK };
static const struct {
    const char *name;
    enum ext_kind kind;
    const char *fallback; /* what is drawn instead */
} exts[] = {
    {"KHR_materials_unlit", EXT_DRAWN, NULL},
    {"KHR_texture_transform", EXT_DRAWN, NULL},
    {"KHR_mesh_quantization", EXT_DRAWN, NULL},
    {"KHR_materials_emissive_strength", EXT_DRAWN, NULL},
    {"KHR_materials_pbrSpecularGlossiness", EXT_DRAWN, NULL},
    {"KHR_materials_ior", EXT_DRAWN, NULL},
    {"KHR_materials_specular", EXT_DRAWN, NULL},
    {"EXT_mesh_gpu_instancing", EXT_DRAWN, NULL},
    {"EXT_meshopt_compression", EXT_DRAWN, NULL},
    {"KHR_meshopt_compression", EXT_DRAWN, NULL},
    {"KHR_draco_mesh_compression", EXT_DRAWN, NULL},
    {"KHR_xmp_json_ld", EXT_HARMLESS, NULL},
    {"KHR_xmp", EXT_HARMLESS, NULL},
    {"KHR_materials_variants", EXT_FALLBACK, "the default materials are drawn"},
    {"KHR_lights_punctual", EXT_FALLBACK, "the file's lights are not used: rastty's light is"},
    {"KHR_materials_clearcoat", EXT_FALLBACK, "drawn without the clear coat layer"},
    {"KHR_materials_sheen", EXT_FALLBACK, "drawn without sheen"},
    {"KHR_materials_transmission", EXT_FALLBACK, "transmissive surfaces are drawn opaque"},
    {"KHR_materials_diffuse_transmission", EXT_FALLBACK, "drawn opaque"},
    {"KHR_materials_volume", EXT_FALLBACK, "drawn without volume attenuation"},
    {"KHR_materials_iridescence", EXT_FALLBACK, "drawn without iridescence"},
    {"KHR_materials_anisotropy", EXT_FALLBACK, "highlights drawn round (no anisotropy)"},
    {"KHR_materials_dispersion", EXT_FALLBACK, "drawn without dispersion"},
    {"KHR_texture_basisu", EXT_FALLBACK,
     "KTX2 images cannot be decoded: a texture's PNG/JPEG fallback is drawn, else none"},
    {"EXT_texture_webp", EXT_FALLBACK,
     "WebP images cannot be decoded: a texture's PNG/JPEG fallback is drawn, else none"},
    {"EXT_texture_avif", EXT_FALLBACK,
     "AVIF images cannot be decoded: a texture's PNG/JPEG fallback is drawn, else none"},
    {"MSFT_texture_dds", EXT_FALLBACK,
     "DDS images cannot be decoded: a texture's PNG/JPEG fallback is drawn, else none"},
    {"KHR_animation_pointer", EXT_FALLBACK, "animations are not played"},
    {"MSFT_lod", EXT_FALLBACK, "the finest level is drawn"},
    {"EXT_lights_image_based", EXT_FALLBACK, "the environment light is not used"},
};

static int check_extensions(struct gl *G)
{
    const struct json *req = json_get(G->root, "extensionsRequired");
    const struct json *used = json_get(G->root, "extensionsUsed");
    char qb[80];
    for (uint32_t i = 0; i < json_len(req); i++) {
        const char *n = json_str(json_at(req, i), "");
        bool ok = false;
        for (size_t k = 0; k < sizeof exts / sizeof *exts; k++)
            ok |= strcmp(n, exts[k].name) == 0 && exts[k].kind != EXT_FALLBACK;
        if (!ok)
            return gfail(G, json_at(req, i), "the file requires extension %s, which rastty "
                                             "cannot draw",
                         q(n, qb, sizeof qb));
    }
    for (uint32_t i = 0; i < json_len(used); i++) {
        const char *n = json_str(json_at(used, i), "");
        size_t k = 0;
        while (k < sizeof exts / sizeof *exts && strcmp(n, exts[k].name) != 0)
            k++;
        if (k == sizeof exts / sizeof *exts)
            gwarn(G, "extension %s is not supported; drawn without it",
                  q(n, qb, sizeof qb));
        else if (exts[k].kind == EXT_FALLBACK)
            gwarn(G, "extension %s is not drawn: %s", exts[k].name, exts[k].fallback);
    }
    return 0;
}

/* ---- materials and textures ---- */

struct images {
    int *tex; /* per glTF image: mesh texture index, -1 failed, -2 not loaded yet */
};

static const char *image_kind(const char *mime)
{
    if (!mime)
        return NULL;
    if (strcmp(mime, "image/webp") == 0)
        return "WebP";
    if (strcmp(mime, "image/ktx2") == 0)
        return "KTX2";
    if (strcmp(mime, "image/avif") == 0)
        return "AVIF";
    if (strcmp(mime, "image/vnd-ms.dds") == 0)
        return "DDS";
    return NULL;
}

static int image(struct gl *G, struct mesh *out, struct images *I, int64_t ii)
{
    if (ii < 0 || ii >= (int64_t)json_len(G->images))
        return -1;
    if (I->tex[ii] != -2)
        return I->tex[ii];
    I->tex[ii] = -1;
    const struct json *ij = json_at(G->images, (uint32_t)ii);
    const char *uri = json_str(json_get(ij, "uri"), NULL);
    const char *mime = json_str(json_get(ij, "mimeType"), NULL);
    char name[FILE_QUOTE_SIZE + 40], qb[80];
    snprintf(name, sizeof name, "%s: image %lld", G->where, (long long)ii);
    const char *kind = image_kind(mime);
    if (kind) {
        gwarn(G, "image %lld is %s, which rastty cannot decode; drawn without it",
              (long long)ii, kind);
        return -1;
    }
    if (uri) {
        uint8_t *d;
        size_t n;
        bool is_data;
        if (data_uri(uri, &d, &n, &is_data) == 0) {
            I->tex[ii] = material_image_bytes(out, d, n, name, G->ctx);
            free(d);
        } else if (is_data) {
            gwarn(G, "image %lld: a broken data: URI; drawn without it", (long long)ii);
        } else {
            const char *why;
            char *path = uri_path(G, uri, &why);
            if (!path)
                gwarn(G, "image %lld '%s': %s; drawn without it", (long long)ii,
                      q(uri, qb, sizeof qb), why);
            else
                I->tex[ii] = material_image_file(out, path, name, 0, G->ctx);
            free(path);
        }
        return I->tex[ii];
    }
    int rc = 0;
    int64_t vw = index_of(G, ij, "bufferView", G->views, "image", false, &rc);
    struct view v;
    struct err keep = *G->e;
    if (rc || vw < 0 || view(G, vw, &v)) {
        gwarn(G, "image %lld has no usable data (%s); drawn without it", (long long)ii,
              rc || vw >= 0 ? G->e->msg : "neither uri nor bufferView");
        *G->e = keep;
        return -1;
    }
    I->tex[ii] = material_image_bytes(out, v.p, v.n, name, G->ctx);
    return I->tex[ii];
}

static uint8_t wrap_of(int64_t w)
{
    return w == 33071 ? TEX_WRAP_CLAMP : w == 33648 ? TEX_WRAP_MIRROR : TEX_WRAP_REPEAT;
}

/* a textureInfo (the material's "baseColorTexture" and the like) into a slot */
static void slot(struct gl *G, struct mesh *out, struct images *I, const struct json *info,
                 struct tex_slot *s, const char *what, uint32_t mi)
{
    *s = (struct tex_slot){.tex = -1};
    if (!info)
        return;
    int rc = 0;
    struct err keep = *G->e;
    int64_t ti = index_of(G, info, "index", G->textures, what, true, &rc);
    if (rc) {
        gwarn(G, "material %u: %s: %s; drawn without it", mi, what, G->e->msg);
        *G->e = keep;
        return;
    }
    const struct json *tj = json_at(G->textures, (uint32_t)ti);
    int64_t src = json_int(json_get(tj, "source"), -1);
    if (src < 0) { /* only an extension's image (KTX2, WebP, AVIF): none decodable */
        gwarn(G, "material %u: %s: texture %lld has no PNG or JPEG image; drawn without it",
              mi, what, (long long)ti);
        return;
    }
    s->tex = image(G, out, I, src);
    if (s->tex < 0) {
        s->tex = -1;
        return;
    }
    s->uv = (uint8_t)(json_int(json_get(info, "texCoord"), 0) == 1);
    if (json_int(json_get(info, "texCoord"), 0) > 1)
        gwarn(G, "material %u: %s uses TEXCOORD_%lld: drawn with TEXCOORD_1", mi, what,
              (long long)json_int(json_get(info, "texCoord"), 0));
    int64_t si = json_int(json_get(tj, "sampler"), -1);
    const struct json *sj = arr_get(G->samplers, si);
    s->wrap[0] = wrap_of(json_int(json_get(sj, "wrapS"), 10497));
    s->wrap[1] = wrap_of(json_int(json_get(sj, "wrapT"), 10497));
    s->nearest = json_int(json_get(sj, "magFilter"), 9729) == 9728;
    const struct json *tt = json_get(json_get(info, "extensions"), "KHR_texture_transform");
    if (tt) {
        double o[2] = {0, 0}, sc[2] = {1, 1}, r = json_num(json_get(tt, "rotation"), 0);
        const struct json *oj = json_get(tt, "offset"), *scj = json_get(tt, "scale");
        for (uint32_t k = 0; k < 2; k++) {
            if (json_len(oj) == 2)
                o[k] = json_num(json_at(oj, k), 0);
            if (json_len(scj) == 2)
                sc[k] = json_num(json_at(scj, k), 1);
        }
        if (json_is_int(json_get(tt, "texCoord")))
            s->uv = (uint8_t)(json_int(json_get(tt, "texCoord"), 0) == 1);
        /* glTF's uv' = T(o) R(r) S(sc) uv, R = (cos sin; -sin cos), in glTF's space (v
         * down); in rastty's (v_r = 1 - v): F M F with F: v -> 1 - v */
        double c = cos(r), sn = sin(r);
        double a = c * sc[0], b = sn * sc[1], tx = o[0];
        double d = -sn * sc[0], e = c * sc[1], ty = o[1];
        /* u' = a u + b (1 - v_r) + tx;  v_r' = 1 - (d u + e (1 - v_r) + ty) */
        s->xf[0] = (float)a, s->xf[1] = (float)-b, s->xf[2] = (float)(b + tx);
        s->xf[3] = (float)-d, s->xf[4] = (float)e, s->xf[5] = (float)(1 - e - ty);
        s->xform = !(s->xf[0] == 1 && s->xf[1] == 0 && s->xf[2] == 0 && s->xf[3] == 0 &&
                     s->xf[4] == 1 && s->xf[5] == 0);
    }
}

static void factor3(const struct json *v, float out[3], float dflt)
{
    for (uint32_t k = 0; k < 3; k++) {
        double x = json_len(v) >= 3 ? json_num(json_at(v, k), dflt) : dflt;
        out[k] = isfinite(x) ? (float)(x < 0 ? 0 : x) : dflt;
    }
}

static bool slot_default(const struct tex_slot *s)
{
    return s->uv == 0 && s->wrap[0] == TEX_WRAP_REPEAT && s->wrap[1] == TEX_WRAP_REPEAT &&
           !s->nearest && !s->xform;
}

static void material(struct gl *G, struct mesh *out, struct images *I, uint32_t i)
{
    struct material *m = &out->materials[i + 1];
    const struct json *mj = json_at(G->materials, i);
    char name[MESH_NAME_MAX];
    const char *jn = json_str(json_get(mj, "name"), NULL);
    if (jn)
        snprintf(name, sizeof name, "%.40s", jn);
    else
        snprintf(name, sizeof name, "material%u", i);
    mtl_default(m, name);
    const struct json *ext = json_get(mj, "extensions");
    const struct json *pbr = json_get(mj, "pbrMetallicRoughness");
    const struct json *sg = json_get(ext, "KHR_materials_pbrSpecularGlossiness");
    float base[4] = {1, 1, 1, 1};
    const struct json *bcf = json_get(sg ? sg : pbr, sg ? "diffuseFactor" : "baseColorFactor");
    for (uint32_t k = 0; k < 4; k++) {
        double x = json_len(bcf) == 4 ? json_num(json_at(bcf, k), 1) : 1;
        base[k] = isfinite(x) ? (float)(x < 0 ? 0 : x > 1 ? 1 : x) : 1;
    }
    for (int k = 0; k < 3; k++) {
        m->base_lin[k] = base[k];
        m->kd[k] = srgb_encode(base[k]);
    }
    m->alpha = base[3];
    slot(G, out, I, json_get(sg ? sg : pbr, sg ? "diffuseTexture" : "baseColorTexture"),
         &m->base, "base colour texture", i);
    m->texture = m->base.tex;
    /* the highlight: Blinn-Phong's ks and ns (light.h's mapping) */
    float rough, metal = 0, f0[3] = {0.04f, 0.04f, 0.04f};
    if (sg) {
        factor3(json_get(sg, "specularFactor"), f0, 1);
        double g = json_num(json_get(sg, "glossinessFactor"), 1);
        rough = (float)(1 - (g < 0 ? 0 : g > 1 ? 1 : g));
        slot(G, out, I, json_get(sg, "specularGlossinessTexture"), &m->spec_map,
             "specular-glossiness texture", i);
        m->metallic = -1; /* (spec_map holds specular rgb and glossiness) */
    } else {
        double r = json_num(json_get(pbr, "roughnessFactor"), 1);
        double mt = json_num(json_get(pbr, "metallicFactor"), 1);
        rough = (float)(r < 0 ? 0 : r > 1 ? 1 : r);
        metal = (float)(mt < 0 ? 0 : mt > 1 ? 1 : mt);
        const struct json *ior = json_get(ext, "KHR_materials_ior");
        if (ior) {
            double n = json_num(json_get(ior, "ior"), 1.5), r0 = (n - 1) / (n + 1);
            f0[0] = f0[1] = f0[2] = (float)(r0 * r0);
        }
        const struct json *spec = json_get(ext, "KHR_materials_specular");
        if (spec) {
            float col[3];
            factor3(json_get(spec, "specularColorFactor"), col, 1);
            double sf = json_num(json_get(spec, "specularFactor"), 1);
            for (int k = 0; k < 3; k++)
                f0[k] = (float)fmin(f0[k] * col[k], 1) * (float)(sf < 0 ? 0 : sf > 1 ? 1 : sf);
            if (json_get(spec, "specularTexture") || json_get(spec, "specularColorTexture"))
                gwarn(G, "material %u: KHR_materials_specular's textures are not drawn (its "
                         "factors are)",
                      i);
        }
        slot(G, out, I, json_get(pbr, "metallicRoughnessTexture"), &m->spec_map,
             "metallic-roughness texture", i);
        m->metallic = metal;
    }
    m->pbr = true;
    m->roughness = rough;
    memcpy(m->spec_lin, f0, sizeof f0);
    material_pbr_highlight(m->base_lin, f0, metal, rough, m->ks, &m->ns);
    /* emission */
    float em[3];
    factor3(json_get(mj, "emissiveFactor"), em, 0);
    double strength = json_num(json_get(json_get(ext, "KHR_materials_emissive_strength"),
                                        "emissiveStrength"),
                               1);
    for (int k = 0; k < 3; k++)
        m->emissive[k] = srgb_encode((float)(em[k] * (strength > 0 ? strength : 0)));
    slot(G, out, I, json_get(mj, "emissiveTexture"), &m->emissive_map, "emissive texture", i);
    if (m->emissive_map.tex >= 0 && !(m->emissive[0] > 0 || m->emissive[1] > 0 ||
                                      m->emissive[2] > 0))
        m->emissive_map.tex = -1; /* a black factor: the texture adds nothing */
    /* normal and occlusion */
    const struct json *nt = json_get(mj, "normalTexture");
    slot(G, out, I, nt, &m->normal_map, "normal texture", i);
    m->normal_scale = (float)json_num(json_get(nt, "scale"), 1);
    const struct json *ot = json_get(mj, "occlusionTexture");
    slot(G, out, I, ot, &m->occlusion_map, "occlusion texture", i);
    double os = json_num(json_get(ot, "strength"), 1);
    m->occlusion_strength = (float)(os < 0 ? 0 : os > 1 ? 1 : os);
    /* alpha and sides */
    const char *am = json_str(json_get(mj, "alphaMode"), "OPAQUE");
    m->alpha_mode = strcmp(am, "MASK") == 0 ? MAT_MASK : strcmp(am, "BLEND") == 0 ? MAT_BLEND
                                                                                   : MAT_OPAQUE;
    double cut = json_num(json_get(mj, "alphaCutoff"), 0.5);
    m->alpha_cutoff = (float)(cut < 0 ? 0 : cut);
    m->sides = json_bool(json_get(mj, "doubleSided"), false) ? MAT_TWO_SIDED : MAT_ONE_SIDED;
    m->unlit = json_get(ext, "KHR_materials_unlit") != NULL;
    /* drawn by the features path: a metal has no diffuse and its highlight is weighted by
     * N.L (light.h), which the conventions' path has not; a dielectric without textures
     * draws as the conventions' Blinn-Phong (the Mesa oracle's globe.glb) */
    bool em_on = m->emissive[0] > 0 || m->emissive[1] > 0 || m->emissive[2] > 0;
    m->features = (m->pbr && m->metallic > 0) || m->unlit || em_on || m->normal_map.tex >= 0 || m->occlusion_map.tex >= 0 ||
                  m->spec_map.tex >= 0 || m->alpha_mode != MAT_OPAQUE ||
                  m->sides == MAT_TWO_SIDED || (m->base.tex >= 0 && !slot_default(&m->base));
}

/* ---- the container ---- */

static uint32_t le32(const uint8_t *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

static int container(struct gl *G, const uint8_t *d, size_t len, const char **json,
                     size_t *json_len_out)
{
    if (len >= 4 && memcmp(d, "glTF", 4) == 0) {
        if (len < 20)
            return err_set(G->e, "%s: byte 0: GLB too short for its header", G->where);
        if (le32(d + 4) != 2)
            return err_set(G->e, "%s: byte 4: GLB version %u (only glTF 2.0)", G->where,
                           le32(d + 4));
        if (le32(d + 8) != len)
            return err_set(G->e, "%s: byte 8: GLB says %u bytes, the file has %zu", G->where,
                           le32(d + 8), len);
        bool first = true;
        for (size_t off = 12; off < len;) {
            if (len - off < 8)
                return err_set(G->e, "%s: byte %zu: truncated GLB chunk header", G->where, off);
            uint32_t n = le32(d + off), type = le32(d + off + 4);
            if (n > len - off - 8)
                return err_set(G->e, "%s: byte %zu: GLB chunk of %u bytes, %zu left in the file",
                               G->where, off, n, len - off - 8);
            if (first) {
                if (type != 0x4e4f534a) /* "JSON" */
                    return err_set(G->e, "%s: byte %zu: the first GLB chunk must be JSON",
                                   G->where, off + 4);
                *json = (const char *)d + off + 8;
                *json_len_out = n;
                G->json_at = off + 8;
            } else if (type == 0x004e4942 && !G->has_bin) { /* "BIN\0" */
                G->bin = d + off + 8;
                G->bin_len = n;
                G->has_bin = true;
            }
            first = false;
            off += 8 + (size_t)n;
        }
        if (first)
            return err_set(G->e, "%s: byte 12: GLB without a JSON chunk", G->where);
        return 0;
    }
    *json = (const char *)d;
    *json_len_out = len;
    G->json_at = 0;
    return 0;
}

static void gl_free(struct gl *G)
{
    for (uint32_t i = 0; i < G->n_buf; i++)
        free(G->buf[i].owned);
    free(G->buf);
    uint32_t nv = json_len(G->views);
    for (uint32_t i = 0; G->view_data && i < nv; i++)
        free(G->view_data[i]);
    free(G->view_data);
    free(G->view_len);
    free(G->pos);
    free(G->nrm);
    free(G->uv0);
    free(G->uv1);
    free(G->tan);
    free(G->rgba);
    free(G->corners);
    free(G->tri_mat);
    free(G->mat_used);
    free(G->world);
    free(G->world_st);
    free(G->parent);
    free(G->cams);
    json_free(&G->doc);
}

static int read_all(struct gl *G, const char *data, size_t len, struct mesh *out)
{
    const char *json = NULL;
    size_t jlen = 0;
    if (container(G, (const uint8_t *)data, len, &json, &jlen))
        return -1;
    struct err je;
    G->json = json;
    G->json_len = jlen;
    if (json_parse(json, jlen, &G->doc, &je)) {
        /* "byte N: ..." of the JSON text, as an offset in the file */
        size_t at;
        const char *rest;
        char w[80];
        if (sscanf(je.msg, "byte %zu", &at) == 1 && (rest = strchr(je.msg, ':')))
            return err_set(G->e, "%s: %s: not valid JSON:%s", G->where,
                           json_where(G, at, w, sizeof w), rest + 1);
        return err_set(G->e, "%s: not valid JSON: %s", G->where, je.msg);
    }
    G->root = G->doc.root;
    if (G->root->type != JSON_OBJECT)
        return gfail(G, G->root, "a glTF file is a JSON object");
    const struct json *asset = json_get(G->root, "asset");
    const char *ver = json_str(json_get(asset, "version"), NULL);
    char qb[80];
    if (!ver)
        return gfail(G, asset ? asset : G->root, "no asset.version (not a glTF file)");
    if (ver[0] != '2' || ver[1] != '.')
        return gfail(G, json_get(asset, "version"), "glTF version '%s' (rastty reads 2.x)",
                     q(ver, qb, sizeof qb));
    if (check_extensions(G))
        return -1;
    G->accessors = json_get(G->root, "accessors");
    G->views = json_get(G->root, "bufferViews");
    G->buffers = json_get(G->root, "buffers");
    G->meshes = json_get(G->root, "meshes");
    G->nodes = json_get(G->root, "nodes");
    G->materials = json_get(G->root, "materials");
    G->textures = json_get(G->root, "textures");
    G->images = json_get(G->root, "images");
    G->samplers = json_get(G->root, "samplers");
    G->cameras = json_get(G->root, "cameras");
    G->skins = json_get(G->root, "skins");
    /* a top-level collection that is no array was read as none ("meshes": 7 said "no
     * triangles (the file has no meshes)"): named where it is */
    static const char *const lists[] = {"accessors", "bufferViews", "buffers", "meshes",
                                        "nodes",     "materials",   "textures", "images",
                                        "samplers",  "cameras",     "skins",    "scenes"};
    for (size_t i = 0; i < sizeof lists / sizeof *lists; i++) {
        const struct json *l = json_get(G->root, lists[i]);
        if (l && l->type != JSON_ARRAY)
            return gfail(G, l, "\"%s\" must be an array", lists[i]);
    }
    G->n_buf = json_len(G->buffers);
    uint32_t n_nodes = json_len(G->nodes), n_views = json_len(G->views);
    G->n_mats = json_len(G->materials);
    G->buf = calloc(G->n_buf + 1, sizeof *G->buf);
    G->view_data = calloc(n_views + 1, sizeof *G->view_data);
    G->view_len = calloc(n_views + 1, sizeof *G->view_len);
    G->mat_used = calloc(G->n_mats + 1, sizeof *G->mat_used);
    G->world = calloc(n_nodes + 1, sizeof *G->world);
    G->world_st = calloc(n_nodes + 1, 1);
    G->parent = malloc((n_nodes + 1) * sizeof *G->parent);
    G->cams = calloc(MESH_MAX_CAMERAS, sizeof *G->cams);
    if (!G->buf || !G->view_data || !G->view_len || !G->mat_used || !G->world ||
        !G->world_st || !G->parent || !G->cams)
        return gfail(G, NULL, "out of memory");
    for (uint32_t i = 0; i < n_nodes; i++)
        G->parent[i] = -1;
    for (uint32_t i = 0; i < n_nodes; i++) {
        const struct json *kids = json_get(json_at(G->nodes, i), "children");
        for (uint32_t k = 0; k < json_len(kids); k++) {
            int64_t c = json_int(json_at(kids, k), -1);
            if (c < 0 || c >= n_nodes)
                return gfail(G, json_at(kids, k), "node %u: child %u is not a node", i, k);
            if (G->parent[c] >= 0 || c == i)
                return gfail(G, json_at(kids, k), "node %lld has two parents (a glTF node tree "
                                                  "is a forest)",
                             (long long)c);
            G->parent[c] = (int32_t)i;
        }
    }
    /* the scene: "scene", else the first, else every root node */
    const struct json *scenes = json_get(G->root, "scenes");
    int64_t si = json_int(json_get(G->root, "scene"), json_len(scenes) ? 0 : -1);
    const struct json *sj = arr_get(scenes, si);
    if (si >= 0 && !sj)
        return gfail(G, json_get(G->root, "scene"), "scene %lld does not exist", (long long)si);
    if (sj) {
        const struct json *roots = json_get(sj, "nodes");
        for (uint32_t k = 0; k < json_len(roots); k++) {
            int64_t r = json_int(json_at(roots, k), -1);
            if (r < 0 || r >= n_nodes)
                return gfail(G, json_at(roots, k), "scene %lld: root %u is not a node",
                             (long long)si, k);
            if (walk(G, (uint32_t)r, 0))
                return -1;
        }
    } else {
        for (uint32_t i = 0; i < n_nodes; i++)
            if (G->parent[i] < 0 && walk(G, i, 0))
                return -1;
    }
    if (G->warned_cycle)
        gwarn(G, "the node tree is deeper than %d or holds a cycle; the rest is not drawn",
              GLTF_MAX_DEPTH);
    if (G->skipped_points)
        gwarn(G, "%lu point and line primitives are not drawn (rastty draws surfaces)",
              G->skipped_points);
    if (json_len(json_get(G->root, "animations")))
        gwarn(G, "%u animations are not played: drawn in the nodes' rest pose",
              json_len(json_get(G->root, "animations")));
    if (G->nt == 0) {
        if (G->skipped_points)
            return gfail(G, NULL, "no triangles (only points and lines, and rastty draws "
                                  "surfaces)");
        if (json_len(G->meshes) == 0)
            return gfail(G, NULL, "no triangles (the file has no meshes)");
        return gfail(G, NULL, "no triangles (no node of the scene places a mesh)");
    }
    /* materials: 0 is the default (a primitive without one), glTF's i is i + 1 */
    out->materials = calloc(G->n_mats + 1, sizeof *out->materials);
    if (!out->materials)
        return gfail(G, NULL, "out of memory");
    out->n_materials = G->n_mats + 1;
    mtl_default(&out->materials[0], "default");
    out->materials[0].implicit = true;
    struct images I = {calloc(json_len(G->images) + 1, sizeof *I.tex)};
    if (!I.tex || material_reserve_n(out, json_len(G->images) + 1, G->e)) {
        free(I.tex);
        return gfail(G, NULL, "out of memory");
    }
    for (uint32_t i = 0; i < json_len(G->images); i++)
        I.tex[i] = -2;
    for (uint32_t i = 0; i < G->n_mats; i++) {
        if (G->mat_used[i])
            material(G, out, &I, i);
        else
            mtl_default(&out->materials[i + 1], "unused");
    }
    free(I.tex);
    /* the mesh */
    struct mesh_source src = {
        .pos = G->pos, .nrm = G->nrm, .uv = G->uv0, .n_pos = G->nv, .n_nrm = G->nv,
        .n_uv = G->nv, .corners = G->corners, .tri_material = G->tri_mat, .n_tris = G->nt,
        .rgba = G->any_col ? G->rgba : NULL, .uv1 = G->any_uv1 ? G->uv1 : NULL,
        .tangent = G->any_tan && !G->tan_missing ? G->tan : NULL,
        .crease_set = true, /* glTF: flat normals when a primitive has none */
        .crease_deg = model_opts_of(G->ctx)->crease_set ? model_opts_of(G->ctx)->crease_deg : 0,
    };
    struct err be;
    if (mesh_build(&src, out, &be))
        return gfail(G, NULL, "%s", be.msg);
    out->file_up = 'y';
    if (G->n_cams) {
        out->cameras = malloc(G->n_cams * sizeof *out->cameras);
        if (out->cameras) {
            memcpy(out->cameras, G->cams, G->n_cams * sizeof *out->cameras);
            out->n_cameras = G->n_cams;
        }
    }
    return 0;
}

int gltf_read(const char *data, size_t len, const struct model_ctx *ctx, struct mesh *out,
              struct err *e)
{
    memset(out, 0, sizeof *out);
    char where[FILE_QUOTE_SIZE];
    file_quote(ctx->path ? ctx->path : "<memory>", where, sizeof where);
    struct err local;
    struct gl G = {.ctx = ctx, .where = where, .e = e ? e : &local};
    int rc = read_all(&G, data, len, out);
    gl_free(&G);
    if (rc)
        mesh_free(out);
    return rc;
}
