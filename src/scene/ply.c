/* ply.c: PLY (ASCII, binary little and big endian) -> struct mesh, the loader behind
 * model.h.
 *
 * Header: "ply", "format ascii|binary_little_endian|binary_big_endian 1.0", "element NAME
 * COUNT", "property TYPE NAME", "property list COUNT_TYPE ITEM_TYPE NAME", "comment" and
 * "obj_info" lines, "end_header". Types char/int8 uchar/uint8 short/int16 ushort/uint16
 * int/int32 uint/uint32 float/float32 double/float64.
 * Used: element "vertex" (x y z; nx ny nz; u v, s t or texture_u texture_v; red green blue,
 * as uchar 0..255 or float 0..1) and element "face" (vertex_indices or vertex_index; an
 * optional per-corner "texcoord" list of 2n values, as MeshLab writes). Every other
 * element and property is read and skipped. Faces of more than 3 corners go through
 * polygon.h. "comment TextureFile NAME" (MeshLab) names a texture beside the file.
 * Vertex colours are kept in mesh.colors; the pipeline multiplies the albedo by them.
 * Limits: element counts are checked against the bytes left before anything is allocated
 * (each instance takes at least one byte in ASCII, its fixed size in binary).
 * Errors: "file:line: message" in the header and ASCII data, "file: byte N: message" in
 * binary data. */
#include <math.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "file.h"
#include "lex.h"
#include "material.h"
#include "mem.h"
#include "model.h"
#include "mtl.h"
#include "polygon.h"

#define PLY_MAX_ELEMENTS 32
#define PLY_MAX_PROPS 64
#define PLY_MAX_COUNT 0x7fffffffL
#define PLY_MAX_FACE 65536 /* corners in one face */

enum ptype { T_NONE, T_I8, T_U8, T_I16, T_U16, T_I32, T_U32, T_F32, T_F64 };
static const int type_size[] = {0, 1, 1, 2, 2, 4, 4, 4, 8};

enum role { R_NONE, R_X, R_Y, R_Z, R_NX, R_NY, R_NZ, R_U, R_V, R_R, R_G, R_B, R_INDICES,
            R_TEXCOORD };

struct prop {
    enum ptype type;       /* value type, or list item type */
    enum ptype count_type; /* T_NONE: not a list */
    enum role role;
};

struct element {
    char name[32];
    long count;
    struct prop props[PLY_MAX_PROPS];
    int n_props;
};

struct pparse {
    const char *where;
    struct err *e;
    const struct model_ctx *ctx;
    enum { F_ASCII, F_LE, F_BE } format;
    struct element el[PLY_MAX_ELEMENTS];
    int n_el;
    char *texture; /* comment TextureFile */
    char up;       /* 'x', 'y' or 'z' from a comment or obj_info naming the up axis; 0 */
    bool warned_extra; /* an ASCII line with more values than declared was met */
    /* data cursor */
    const uint8_t *d, *end, *start;
    unsigned long line;
    /* results */
    float *pos, *nrm, *uv; /* per vertex */
    uint8_t *rgb;
    long n_verts;
    bool has_nrm, has_uv, has_rgb;
    float *corner_uv; /* per-face texcoords, 2 per entry */
    size_t n_corner_uv, cap_corner_uv;
    struct mesh_corner *corners;
    size_t n_tris, cap_tris;
    struct mesh_corner *face;
    uint32_t *face_pos, *scratch, (*tris)[3];
    float *face_tc;
};

static enum ptype parse_type(const char *t, const char *te)
{
    static const struct {
        const char *name;
        enum ptype t;
    } names[] = {{"char", T_I8},    {"int8", T_I8},      {"uchar", T_U8},    {"uint8", T_U8},
                 {"short", T_I16},  {"int16", T_I16},    {"ushort", T_U16},  {"uint16", T_U16},
                 {"int", T_I32},    {"int32", T_I32},    {"uint", T_U32},    {"uint32", T_U32},
                 {"float", T_F32},  {"float32", T_F32},  {"double", T_F64},  {"float64", T_F64}};
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++)
        if (lex_tok_is(t, te, names[i].name))
            return names[i].t;
    return T_NONE;
}

static enum role vertex_role(const char *t, const char *te)
{
    static const struct {
        const char *name;
        enum role r;
    } names[] = {{"x", R_X},          {"y", R_Y},          {"z", R_Z},
                 {"nx", R_NX},        {"ny", R_NY},        {"nz", R_NZ},
                 {"u", R_U},          {"v", R_V},          {"s", R_U},
                 {"t", R_V},          {"texture_u", R_U},  {"texture_v", R_V},
                 {"texture_s", R_U},  {"texture_t", R_V},  {"red", R_R},
                 {"green", R_G},      {"blue", R_B},       {"diffuse_red", R_R},
                 {"diffuse_green", R_G}, {"diffuse_blue", R_B}};
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++)
        if (lex_tok_is(t, te, names[i].name))
            return names[i].r;
    return R_NONE;
}

static int herr(struct pparse *P, unsigned long line, const char *msg)
{
    return err_set(P->e, "%s:%lu: %s", P->where, line, msg);
}

/* The up axis a header line's text names, or 0. PLY has no convention (scanning
 * repositories write Y-up, CAD programs Z-up); exporters that say write it in a comment or
 * obj_info: "up_axis Z", "up: z", "UpAxis=Z", "Z-up", "z up", "+Z up". */
static char header_up(const char *p, const char *end)
{
    char t[160], *w[24];
    size_t n = 0;
    int nw = 0;
    for (; p < end && n + 1 < sizeof t; p++) /* lower case, punctuation as blanks */
        t[n++] = *p >= 'A' && *p <= 'Z' ? (char)(*p - 'A' + 'a')
                 : (*p >= 'a' && *p <= 'z') || (*p >= '0' && *p <= '9') ? *p
                                                                        : ' ';
    t[n] = '\0';
    for (char *sv, *c = strtok_r(t, " ", &sv); c && nw < 24; c = strtok_r(NULL, " ", &sv))
        w[nw++] = c;
    for (int i = 0; i < nw; i++) {
        bool axis = w[i][0] >= 'x' && w[i][0] <= 'z';
        if (axis && w[i][1] == '\0' && i + 1 < nw && strcmp(w[i + 1], "up") == 0)
            return w[i][0]; /* "z up", "Z-up" */
        if (axis && strcmp(w[i] + 1, "up") == 0)
            return w[i][0]; /* "zup" */
        if (strcmp(w[i], "up") == 0 || strcmp(w[i], "upaxis") == 0) {
            int k = i + 1 + (i + 1 < nw && strcmp(w[i + 1], "axis") == 0);
            if (k < nw && w[k][0] >= 'x' && w[k][0] <= 'z' && w[k][1] == '\0')
                return w[k][0]; /* "up_axis Z", "UpAxis=Z", "up: z" */
        }
    }
    return 0;
}

/* the header; on success P->d points at the first data byte */
static int parse_header(struct pparse *P, const char *text, size_t len)
{
    const char *p = text, *end = text + len;
    unsigned long line = 0;
    bool have_format = false;
    for (;;) {
        if (p >= end)
            return err_set(P->e, "%s: header has no end_header", P->where);
        const char *eol = lex_line_end(p, end);
        line++;
        const char *kwe, *kw = lex_keyword(p, eol, &kwe);
        const char *rest = kw ? lex_skip_ws(kwe, eol) : eol;
        const char *next = eol < end ? eol + 1 : end;
        if (line == 1) {
            if (!kw || !lex_tok_is(kw, kwe, "ply"))
                return herr(P, line, "not a PLY file (first line must be 'ply')");
        } else if (!kw) {
            /* blank line */
        } else if (lex_tok_is(kw, kwe, "end_header")) {
            P->d = (const uint8_t *)next;
            P->line = line + 1;
            break;
        } else if (lex_tok_is(kw, kwe, "format")) {
            const char *t = rest, *te = lex_tok_end(t, eol);
            if (lex_tok_is(t, te, "ascii"))
                P->format = F_ASCII;
            else if (lex_tok_is(t, te, "binary_little_endian"))
                P->format = F_LE;
            else if (lex_tok_is(t, te, "binary_big_endian"))
                P->format = F_BE;
            else
                return herr(P, line, "unknown format (ascii, binary_little_endian or "
                                     "binary_big_endian)");
            have_format = true;
        } else if (lex_tok_is(kw, kwe, "comment") || lex_tok_is(kw, kwe, "obj_info")) {
            char up = header_up(rest, eol);
            P->up = up ? up : P->up;
            const char *t = rest, *te = lex_tok_end(t, eol);
            if (lex_tok_is(t, te, "TextureFile")) {
                const char *n = lex_skip_ws(te, eol), *ne = lex_rtrim(n, eol);
                free(P->texture);
                P->texture = ne > n && !memchr(n, '\0', (size_t)(ne - n))
                                 ? material_path_beside(P->ctx->path, n, (size_t)(ne - n))
                                 : NULL;
            }
        } else if (lex_tok_is(kw, kwe, "element")) {
            if (P->n_el == PLY_MAX_ELEMENTS)
                return herr(P, line, "too many elements (limit 32)");
            struct element *el = &P->el[P->n_el];
            memset(el, 0, sizeof *el);
            const char *t = rest, *te = lex_tok_end(t, eol);
            err_quote(t, (size_t)(te - t), sizeof el->name - 5, el->name, sizeof el->name);
            const char *c = lex_skip_ws(te, eol), *ce = lex_tok_end(c, eol);
            long v = 0;
            if (c == ce || te == t)
                return herr(P, line, "element needs a name and a count");
            for (const char *q = c; q < ce; q++) {
                if (*q < '0' || *q > '9' || v > PLY_MAX_COUNT / 10)
                    return herr(P, line, "bad element count");
                v = v * 10 + (*q - '0');
            }
            el->count = v;
            P->n_el++;
        } else if (lex_tok_is(kw, kwe, "property")) {
            if (P->n_el == 0)
                return herr(P, line, "property before any element");
            struct element *el = &P->el[P->n_el - 1];
            if (el->n_props == PLY_MAX_PROPS)
                return herr(P, line, "too many properties (limit 64)");
            struct prop *pr = &el->props[el->n_props];
            memset(pr, 0, sizeof *pr);
            const char *t = rest, *te = lex_tok_end(t, eol);
            if (lex_tok_is(t, te, "list")) {
                const char *a = lex_skip_ws(te, eol), *ae = lex_tok_end(a, eol);
                const char *b = lex_skip_ws(ae, eol), *be = lex_tok_end(b, eol);
                pr->count_type = parse_type(a, ae);
                pr->type = parse_type(b, be);
                if (!pr->count_type || !pr->type || pr->count_type >= T_F32)
                    return herr(P, line, "bad list property types");
                t = lex_skip_ws(be, eol);
            } else {
                pr->type = parse_type(t, te);
                if (!pr->type)
                    return herr(P, line, "unknown property type");
                t = lex_skip_ws(te, eol);
            }
            te = lex_tok_end(t, eol);
            if (t == te)
                return herr(P, line, "property needs a name");
            if (strcmp(el->name, "vertex") == 0 && !pr->count_type)
                pr->role = vertex_role(t, te);
            else if (strcmp(el->name, "face") == 0 && pr->count_type &&
                     (lex_tok_is(t, te, "vertex_indices") || lex_tok_is(t, te, "vertex_index")))
                pr->role = R_INDICES;
            else if (strcmp(el->name, "face") == 0 && pr->count_type &&
                     lex_tok_is(t, te, "texcoord"))
                pr->role = R_TEXCOORD;
            el->n_props++;
        } else {
            char q[48];
            err_quote(kw, (size_t)(kwe - kw), 40, q, sizeof q);
            return err_set(P->e, "%s:%lu: unknown header line '%s'", P->where, line, q);
        }
        p = next;
    }
    if (!have_format)
        return err_set(P->e, "%s: header has no format line", P->where);
    return 0;
}

/* ---- values ---- */

static int data_err(struct pparse *P, const char *msg)
{
    if (P->format == F_ASCII)
        return err_set(P->e, "%s:%lu: %s", P->where, P->line, msg);
    return err_set(P->e, "%s: byte %zu: %s", P->where, (size_t)(P->d - P->start), msg);
}

/* next ASCII token, crossing lines */
static int ascii_token(struct pparse *P, const char **t, const char **te)
{
    const char *we, *w = lex_word((const char *)P->d, (const char *)P->end, &P->line, &we);
    P->d = (const uint8_t *)we;
    if (!w)
        return data_err(P, "unexpected end of file");
    *t = w, *te = we;
    return 0;
}

static int read_value(struct pparse *P, enum ptype type, double *out)
{
    if (P->format == F_ASCII) {
        const char *t = NULL, *te = NULL;
        if (ascii_token(P, &t, &te))
            return -1;
        if (type >= T_F32) {
            float f;
            int rc = lex_float(t, (size_t)(te - t), &f);
            if (rc) {
                char q[48];
                err_quote(t, (size_t)(te - t), 40, q, sizeof q);
                return err_set(P->e, "%s:%lu: %s '%s'", P->where, P->line, lex_num_problem(rc),
                               q);
            }
            *out = f;
            return 0;
        }
        const char *q = t;
        bool neg = q < te && *q == '-';
        if (q < te && (*q == '-' || *q == '+'))
            q++;
        if (q == te)
            return data_err(P, "bad integer");
        double v = 0;
        for (; q < te; q++) {
            if (*q < '0' || *q > '9' || v > 1e12)
                return data_err(P, "bad integer");
            v = v * 10 + (*q - '0');
        }
        *out = neg ? -v : v;
        return 0;
    }
    int n = type_size[type];
    if (P->end - P->d < n)
        return data_err(P, "unexpected end of file");
    /* the value's bytes, least significant first: one load for each size (a loop over n
     * bytes was a third of read_value's time on a 1M-triangle file) */
    const uint8_t *d = P->d;
    uint64_t u = 0;
    if (P->format == F_LE) {
        switch (n) {
        case 1: u = d[0]; break;
        case 2: u = (uint64_t)d[0] | (uint64_t)d[1] << 8; break;
        case 4: u = (uint64_t)d[0] | (uint64_t)d[1] << 8 | (uint64_t)d[2] << 16 |
                    (uint64_t)d[3] << 24; break;
        default:
            for (int i = n - 1; i >= 0; i--)
                u = u << 8 | d[i];
        }
    } else {
        for (int i = 0; i < n; i++)
            u = u << 8 | d[i];
    }
    P->d += n;
    switch (type) {
    case T_I8: *out = (int8_t)u; break;
    case T_U8: *out = (uint8_t)u; break;
    case T_I16: *out = (int16_t)u; break;
    case T_U16: *out = (uint16_t)u; break;
    case T_I32: *out = (int32_t)u; break;
    case T_U32: *out = (uint32_t)u; break;
    case T_F32: {
        uint32_t w = (uint32_t)u;
        float f;
        memcpy(&f, &w, sizeof f);
        *out = f;
        break;
    }
    default: {
        double f;
        memcpy(&f, &u, sizeof f);
        *out = f;
        break;
    }
    }
    return 0;
}

/* a list's length: a non-negative integer below limit */
static int read_count(struct pparse *P, enum ptype type, long limit, long *out)
{
    double v;
    if (read_value(P, type, &v))
        return -1;
    if (!(v >= 0 && v <= (double)limit) || v != floor(v))
        return data_err(P, "bad list length");
    *out = (long)v;
    return 0;
}

/* ---- elements ---- */

/* ASCII: an element's values read, the rest of its line is more than the header declares
 * (exporters append values to face lines; assimp reads such files): skipped, with one
 * warning naming the first such line. A value on the next line is the next element's. */
static void ascii_line_end(struct pparse *P, const struct element *el)
{
    if (P->format != F_ASCII)
        return;
    const char *p = (const char *)P->d, *end = (const char *)P->end;
    while (p < end && *p != '\n' && lex_is_ws(*p))
        p++;
    if (p >= end || *p == '\n')
        return;
    if (!P->warned_extra)
        warn_add(P->ctx->warn, "%s:%lu: a '%s' line holds more values than the header "
                               "declares; the extra values are skipped",
                 P->where, P->line, el->name);
    P->warned_extra = true;
    while (p < end && *p != '\n')
        p++;
    P->d = (const uint8_t *)p;
}

static int check_room(struct pparse *P, const struct element *el)
{
    size_t left = (size_t)(P->end - P->d), min = 0;
    if (P->format == F_ASCII) {
        min = 1;
    } else {
        for (int k = 0; k < el->n_props; k++)
            min += (size_t)type_size[el->props[k].count_type ? el->props[k].count_type
                                                             : el->props[k].type];
    }
    if (min && (size_t)el->count > left / min) {
        char msg[160];
        snprintf(msg, sizeof msg, "the file is too short for %ld '%s' elements", el->count,
                 el->name);
        return data_err(P, msg);
    }
    return 0;
}

static int read_vertices(struct pparse *P, const struct element *el)
{
    if (P->pos)
        return data_err(P, "a second vertex element");
    size_t n = (size_t)el->count;
    P->n_verts = el->count;
    P->pos = calloc(n ? n * 3 : 1, sizeof *P->pos);
    P->nrm = calloc(n ? n * 3 : 1, sizeof *P->nrm);
    P->uv = calloc(n ? n * 2 : 1, sizeof *P->uv);
    P->rgb = calloc(n ? n * 3 : 1, 1);
    if (!P->pos || !P->nrm || !P->uv || !P->rgb)
        return err_set(P->e, "%s: out of memory for %zu vertices", P->where, n);
    mem_big(P->pos, n * 3 * sizeof *P->pos);
    bool has[R_TEXCOORD + 1] = {false};
    for (int k = 0; k < el->n_props; k++)
        has[el->props[k].role] = true;
    if (!has[R_X] || !has[R_Y] || !has[R_Z])
        return err_set(P->e, "%s: vertex element has no x, y and z", P->where);
    P->has_nrm = has[R_NX] && has[R_NY] && has[R_NZ];
    P->has_uv = has[R_U] && has[R_V];
    P->has_rgb = has[R_R] && has[R_G] && has[R_B];
    for (size_t i = 0; i < n; i++) {
        for (int k = 0; k < el->n_props; k++) {
            const struct prop *pr = &el->props[k];
            double v;
            if (pr->count_type) { /* a list on a vertex: skip it */
                long cnt = 0;
                if (read_count(P, pr->count_type, PLY_MAX_FACE, &cnt))
                    return -1;
                for (long j = 0; j < cnt; j++)
                    if (read_value(P, pr->type, &v))
                        return -1;
                continue;
            }
            if (read_value(P, pr->type, &v))
                return -1;
            float f = (float)v;
            if (pr->role != R_NONE && pr->role <= R_V && !isfinite(f))
                return data_err(P, "vertex value is not a finite number");
            switch (pr->role) {
            case R_X: case R_Y: case R_Z: P->pos[3 * i + (size_t)(pr->role - R_X)] = f; break;
            case R_NX: case R_NY: case R_NZ: P->nrm[3 * i + (size_t)(pr->role - R_NX)] = f; break;
            case R_U: case R_V: P->uv[2 * i + (size_t)(pr->role - R_U)] = f; break;
            case R_R: case R_G: case R_B: {
                double c = pr->type >= T_F32 ? v * 255.0 : v; /* float colours are 0..1 */
                c = c != c ? 0 : c < 0 ? 0 : c > 255 ? 255 : c;
                P->rgb[3 * i + (size_t)(pr->role - R_R)] = (uint8_t)(c + 0.5);
                break;
            }
            default: break;
            }
        }
        ascii_line_end(P, el);
    }
    return 0;
}

/* room for cap triangles' corners */
static int reserve_tris(struct pparse *P, size_t cap)
{
    struct mesh_corner *nc = realloc(P->corners, cap * 3 * sizeof *nc);
    if (!nc)
        return err_set(P->e, "%s: out of memory", P->where);
    P->corners = mem_big(nc, cap * 3 * sizeof *nc);
    P->cap_tris = cap;
    return 0;
}

static int add_tri(struct pparse *P, const struct mesh_corner *a, const struct mesh_corner *b,
                   const struct mesh_corner *c)
{
    if (P->n_tris >= UINT32_MAX / 3)
        return data_err(P, "too many triangles");
    if (P->n_tris == P->cap_tris && reserve_tris(P, P->cap_tris ? P->cap_tris * 2 : 1024))
        return -1;
    struct mesh_corner *t = &P->corners[P->n_tris++ * 3];
    t[0] = *a;
    t[1] = *b;
    t[2] = *c;
    return 0;
}

static int read_faces(struct pparse *P, const struct element *el, long index)
{
    if (!P->pos)
        return data_err(P, "faces before the vertex element");
    if (!P->face) {
        P->face = malloc(PLY_MAX_FACE * sizeof *P->face);
        P->face_pos = malloc(PLY_MAX_FACE * sizeof *P->face_pos);
        P->scratch = malloc(2 * PLY_MAX_FACE * sizeof *P->scratch);
        P->tris = malloc(PLY_MAX_FACE * sizeof *P->tris);
        P->face_tc = malloc(2 * PLY_MAX_FACE * sizeof *P->face_tc);
        if (!P->face || !P->face_pos || !P->scratch || !P->tris || !P->face_tc)
            return err_set(P->e, "%s: out of memory", P->where);
    }
    /* a triangle per face at least (check_room bounded the count by the file's size): a
     * file of triangles fills one allocation, never copied by a growing realloc */
    size_t want = P->n_tris + (size_t)el->count;
    want = want < UINT32_MAX / 3 ? want : UINT32_MAX / 3;
    if (want > P->cap_tris && reserve_tris(P, want))
        return -1;
    (void)index;
    for (long i = 0; i < el->count; i++) {
        long n = -1, n_tc = -1;
        for (int k = 0; k < el->n_props; k++) {
            const struct prop *pr = &el->props[k];
            double v;
            if (!pr->count_type) {
                if (read_value(P, pr->type, &v))
                    return -1;
                continue;
            }
            long cnt = 0;
            if (read_count(P, pr->count_type, pr->role == R_TEXCOORD ? 2 * PLY_MAX_FACE
                                                                      : PLY_MAX_FACE, &cnt))
                return -1;
            for (long j = 0; j < cnt; j++) {
                if (read_value(P, pr->type, &v))
                    return -1;
                if (pr->role == R_INDICES && n < 0) {
                    if (!(v >= 0 && v < (double)P->n_verts) || v != floor(v)) {
                        char msg[160];
                        snprintf(msg, sizeof msg, "face %ld: vertex index %.0f out of range (%ld "
                                                  "vertices)", i, v, P->n_verts);
                        return data_err(P, msg);
                    }
                    P->face_pos[j] = (uint32_t)v;
                } else if (pr->role == R_TEXCOORD && n_tc < 0) {
                    P->face_tc[j] = isfinite(v) ? (float)v : 0;
                }
            }
            if (pr->role == R_INDICES && n < 0)
                n = cnt;
            else if (pr->role == R_TEXCOORD && n_tc < 0)
                n_tc = cnt;
        }
        ascii_line_end(P, el);
        if (n < 0)
            return data_err(P, "face element has no vertex_indices");
        if (n < 3)
            continue; /* points and lines: nothing to draw */
        bool tc = n_tc == 2 * n;
        if (tc && P->n_corner_uv + (size_t)n > P->cap_corner_uv) {
            size_t cap = P->cap_corner_uv ? P->cap_corner_uv * 2 : 4096;
            while (cap < P->n_corner_uv + (size_t)n)
                cap *= 2;
            float *nu = realloc(P->corner_uv, cap * 2 * sizeof *nu);
            if (!nu)
                return err_set(P->e, "%s: out of memory", P->where);
            P->corner_uv = nu;
            P->cap_corner_uv = cap;
        }
        for (long j = 0; j < n; j++) {
            uint32_t v = P->face_pos[j];
            P->face[j] = (struct mesh_corner){v, P->has_uv ? v : MESH_NONE,
                                              P->has_nrm ? v : MESH_NONE};
            if (tc) {
                P->corner_uv[2 * P->n_corner_uv] = P->face_tc[2 * j];
                P->corner_uv[2 * P->n_corner_uv + 1] = P->face_tc[2 * j + 1];
                P->face[j].uv = (uint32_t)(P->n_verts + (long)P->n_corner_uv++);
            }
        }
        polygon_triangulate(P->pos, P->face_pos, (uint32_t)n, P->tris, P->scratch);
        for (long j = 0; j + 2 < n; j++)
            if (add_tri(P, &P->face[P->tris[j][0]], &P->face[P->tris[j][1]],
                        &P->face[P->tris[j][2]]))
                return -1;
    }
    return 0;
}

static int skip_element(struct pparse *P, const struct element *el)
{
    for (long i = 0; i < el->count; i++) {
        for (int k = 0; k < el->n_props; k++) {
            const struct prop *pr = &el->props[k];
            double v;
            long cnt = 1;
            if (pr->count_type && read_count(P, pr->count_type, PLY_MAX_COUNT, &cnt))
                return -1;
            for (long j = 0; j < cnt; j++)
                if (read_value(P, pr->type, &v))
                    return -1;
        }
        ascii_line_end(P, el);
    }
    return 0;
}

static void pparse_free(struct pparse *P)
{
    free(P->texture);
    free(P->pos);
    free(P->nrm);
    free(P->uv);
    free(P->rgb);
    free(P->corner_uv);
    free(P->corners);
    free(P->face);
    free(P->face_pos);
    free(P->scratch);
    free(P->tris);
    free(P->face_tc);
}

static int finish(struct pparse *P, struct mesh *out)
{
    if (P->n_tris == 0)
        return err_set(P->e, "%s: no faces", P->where);
    /* uvs: the per-vertex ones, then the per-corner texcoords after them */
    size_t n_uv = (size_t)P->n_verts + P->n_corner_uv;
    float *uv = NULL; /* without per-corner texcoords: the vertices' own, not copied */
    if (P->n_corner_uv && (uv = malloc(n_uv * 2 * sizeof *uv))) {
        memcpy(uv, P->uv, (size_t)P->n_verts * 2 * sizeof *uv);
        memcpy(uv + 2 * (size_t)P->n_verts, P->corner_uv, P->n_corner_uv * 2 * sizeof *uv);
    }
    out->materials = malloc(sizeof *out->materials);
    if ((P->n_corner_uv && !uv) || !out->materials) {
        free(uv);
        return err_set(P->e, "%s: out of memory", P->where);
    }
    mtl_default(&out->materials[0], "default");
    out->materials[0].implicit = true; /* PLY names no material: light.h's 0.8 */
    out->n_materials = 1;
    struct mesh_source src = {
        .pos = P->pos, .uv = uv ? uv : P->uv, .nrm = P->nrm, .n_pos = (uint32_t)P->n_verts,
        .n_uv = (uint32_t)n_uv, .n_nrm = (uint32_t)P->n_verts,
        .rgb = P->has_rgb ? P->rgb : NULL, .corners = P->corners, .n_tris = (uint32_t)P->n_tris,
    };
    src.crease_set = true;
    out->file_up = P->up;
    src.crease_deg = model_opts_of(P->ctx)->crease_set ? model_opts_of(P->ctx)->crease_deg : MESH_CREASE_DEFAULT;
    struct err be;
    int rc = mesh_build(&src, out, &be);
    free(uv);
    if (rc)
        return err_set(P->e, "%s: %s", P->where, be.msg);
    if (material_reserve_textures(out, P->e))
        return -1;
    if (P->texture && (P->has_uv || P->n_corner_uv))
        return material_texture_file(out, 0, P->texture, P->where, 0, P->ctx, P->e);
    return 0;
}

int ply_read(const char *data, size_t len, const struct model_ctx *ctx, struct mesh *out,
             struct err *e)
{
    memset(out, 0, sizeof *out);
    char where[FILE_QUOTE_SIZE];
    file_quote(ctx->path ? ctx->path : "<memory>", where, sizeof where);
    struct pparse *P = calloc(1, sizeof *P);
    if (!P)
        return err_set(e, "%s: out of memory", where);
    P->where = where;
    P->e = e;
    P->ctx = ctx;
    int rc = parse_header(P, data, len);
    P->start = (const uint8_t *)data;
    P->end = (const uint8_t *)data + len;
    for (int i = 0; rc == 0 && i < P->n_el; i++) {
        const struct element *el = &P->el[i];
        rc = check_room(P, el);
        if (rc == 0) {
            if (strcmp(el->name, "vertex") == 0)
                rc = read_vertices(P, el);
            else if (strcmp(el->name, "face") == 0)
                rc = read_faces(P, el, i);
            else
                rc = skip_element(P, el);
        }
    }
    if (rc == 0)
        rc = finish(P, out);
    pparse_free(P);
    free(P);
    if (rc)
        mesh_free(out);
    return rc;
}
