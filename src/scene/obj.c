/* obj.c: Wavefront OBJ text -> struct mesh (see obj.h).
 *
 * One pass over the text collects positions, uvs, normals and triangles of corner indices
 * (polygons through polygon.h: fans when convex, ear clipping otherwise), with a material
 * "slot" per distinct usemtl name. After the pass the slots are resolved against the loaded
 * MTL libraries (mtl_resolve, so mtllib may come late; textures via material.h), and
 * mesh_build (mesh.c) turns the corners into unique vertices. */
#include "obj.h"

#include <errno.h>
#include <math.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "file.h"
#include "lex.h"
#include "material.h"
#include "model.h"
#include "mtl.h"
#include "polygon.h"
#include "strmap.h"

#define OBJ_QUOTE_PATH 100
#define OBJ_QUOTE_TEXT 40
#define OBJ_MAX_INDEX 0x7fffffffLL     /* counts and |indices| stay within int32 */
#define OBJ_MAX_TRIS (UINT32_MAX / 3)   /* mesh_build's limit */
#define OBJ_MAX_MATERIALS 65535         /* tri_material is uint16_t; slot 0 is the default */
#define OBJ_MEMORY_NAME "<memory>"

/* ---- OBJ-only lexing (the rules shared with MTL are in lex.h) ------------------------- */

/* Numbers and indices: a token also ends at '#', which ends the line. */
static const char *num_end(const char *p, const char *end)
{
    /* every whitespace byte and '#' is below '$': one comparison for a digit or sign */
    while (p < end && ((unsigned char)*p > '#' || (!lex_is_ws(*p) && *p != '#')))
        p++;
    return p;
}

static const char *num_next(const char *p, const char *end)
{
    p = lex_skip_ws(p, end);
    return p < end && *p == '#' ? end : p;
}

/* Grow an array to hold `need` elements; returns the (maybe moved) array, or NULL with the
 * old one intact. */
static void *grow(void *p, size_t *cap, size_t need, size_t elem)
{
    if (need <= *cap)
        return p;
    size_t c = *cap ? *cap : 256;
    while (c < need) {
        if (c > SIZE_MAX / 2 / elem)
            return NULL;
        c *= 2;
    }
    void *np = realloc(p, c * elem);
    if (np)
        *cap = c;
    return np;
}

/* ---- the parser ----------------------------------------------------------------------- */

struct oparse {
    struct err *e;
    const struct model_ctx *ctx;
    const char *path; /* as given; NULL for in-memory text */
    char where[OBJ_QUOTE_PATH + 8];
    unsigned long line;

    float *pos, *uv, *nrm; /* 3, 2, 3 floats each */
    size_t n_pos, n_uv, n_nrm, cap_pos, cap_uv, cap_nrm;
    uint8_t *rgb;          /* per position, once a "v x y z r g b" line came; else NULL */
    size_t cap_rgb;

    struct mesh_corner *corners; /* 3 per triangle */
    uint16_t *tri_slot;          /* per triangle: slot, later material */
    size_t n_tris, cap_corners, cap_tri_slot;

    /* the face being read: its corners, position indices, triangulation scratch */
    struct mesh_corner *face;
    uint32_t *face_pos, *face_scratch, (*face_tris)[3];
    size_t cap_face;
    unsigned long n_lines, n_points; /* l and p statements: drawn by no one */

    /* slot 0 = default material; slot i > 0 = the i-th distinct usemtl name */
    struct strmap_key *slot_names; /* point into the text */
    bool *slot_used;
    size_t n_slots, cap_slot_names, cap_slot_used;
    struct strmap slot_map;
    uint16_t cur_slot;

    struct mtl_lib *libs;
    size_t n_libs, cap_libs;
};

static int fail(struct oparse *P, const char *msg)
{
    return err_set(P->e, "%s:%lu: %s", P->where, P->line, msg);
}

static int fail_text(struct oparse *P, const char *what, const char *t, const char *te)
{
    char q[OBJ_QUOTE_TEXT + 8];
    err_quote(t, (size_t)(te - t), OBJ_QUOTE_TEXT, q, sizeof q);
    return err_set(P->e, "%s:%lu: %s '%s'", P->where, P->line, what, q);
}

static int oom(struct oparse *P)
{
    return fail(P, "out of memory");
}

/* Up to `want` numbers after the keyword; fewer than `need` is an error; the rest of the
 * line (w, vertex colours, ...) is ignored. Returns how many were read, or -1. */
static int parse_floats(struct oparse *P, const char *kw, const char *p, const char *end,
                        float *out, int want, int need)
{
    int n = 0;
    while (n < want && (p = num_next(p, end)) < end) {
        const char *t = p;
        p = num_end(p, end);
        int rc = lex_float(t, (size_t)(p - t), &out[n]);
        if (rc)
            return fail_text(P, lex_num_problem(rc), t, p);
        n++;
    }
    if (n < need)
        return err_set(P->e, "%s:%lu: '%s' needs %d number%s, got %d", P->where, P->line, kw,
                       need, need > 1 ? "s" : "", n);
    return n;
}

/* A vertex attribute line (v, vt, vn): up to `want` numbers, at least `need` (the rest 0),
 * appended to the array *a of *n vectors of `want` floats, capacity *cap; `kind` names them
 * in the limit's message. */
static inline int add_vector(struct oparse *P, const char *kw, const char *p, const char *end,
                             int want, int need, float **a, size_t *n, size_t *cap,
                             const char *kind)
{
    float v[3] = {0, 0, 0};
    if (need && parse_floats(P, kw, p, end, v, want, need) < 0)
        return -1;
    if ((long long)*n >= OBJ_MAX_INDEX)
        return err_set(P->e, "%s:%lu: too many %s (limit 2^31-1)", P->where, P->line, kind);
    float *na = grow(*a, cap, *n + 1, (size_t)want * sizeof *na);
    if (!na)
        return oom(P);
    *a = na;
    memcpy(&na[*n * (size_t)want], v, (size_t)want * sizeof *v);
    ++*n;
    return 0;
}

/* A v line: x y z, and "x y z r g b" (the vertex colours MeshLab and ZBrush write, 0..1
 * display values, or 0..255 when a component passes 1); a fourth number alone is w,
 * ignored. Positions without a colour in a file that has some are white. */
static int add_position(struct oparse *P, const char *p, const char *end)
{
    float v[6];
    int n = parse_floats(P, "v", p, end, v, 6, 3);
    if (n < 0)
        return -1;
    size_t at = P->n_pos;
    if (add_vector(P, "v", "", "", 3, 0, &P->pos, &P->n_pos, &P->cap_pos, "positions"))
        return -1;
    memcpy(&P->pos[at * 3], v, sizeof(float) * 3);
    if (n < 6 && !P->rgb)
        return 0;
    uint8_t *c = grow(P->rgb, &P->cap_rgb, P->n_pos, 3);
    if (!c)
        return oom(P);
    if (!P->rgb)
        memset(c, 255, at * 3); /* the positions before the first colour */
    P->rgb = c;
    float top = n >= 6 ? fmaxf(v[3], fmaxf(v[4], v[5])) : 1, k = top > 1 ? 1 : 255;
    for (int i = 0; i < 3; i++) {
        float x = n >= 6 ? v[3 + i] * k : 255;
        c[at * 3 + (size_t)i] = (uint8_t)(x > 0 ? (x < 255 ? x + 0.5f : 255) : 0);
    }
    return 0;
}

enum { IDX_OK, IDX_SYNTAX, IDX_ZERO, IDX_RANGE };

/* One index field; resolves relative indices against count. */
static int parse_index(const char *p, const char *end, size_t count, uint32_t *out)
{
    bool neg = false;
    if (p < end && (*p == '-' || *p == '+'))
        neg = *p++ == '-';
    if (p == end)
        return IDX_SYNTAX;
    long long v = 0;
    for (; p < end; p++) {
        if (*p < '0' || *p > '9')
            return IDX_SYNTAX;
        if (v <= OBJ_MAX_INDEX) /* saturate just past the limit */
            v = v * 10 + (*p - '0');
    }
    if (v == 0)
        return IDX_ZERO;
    if (v > OBJ_MAX_INDEX)
        return IDX_RANGE;
    if (neg) {
        if ((size_t)v > count)
            return IDX_RANGE;
        *out = (uint32_t)(count - (size_t)v);
    } else {
        if ((size_t)v > count)
            return IDX_RANGE;
        *out = (uint32_t)(v - 1);
    }
    return IDX_OK;
}

static int parse_corner(struct oparse *P, const char *t, const char *te, struct mesh_corner *c)
{
    static const char *const kind[3] = {"v", "vt", "vn"};
    const size_t count[3] = {P->n_pos, P->n_uv, P->n_nrm};
    uint32_t idx[3] = {MESH_NONE, MESH_NONE, MESH_NONE};
    const char *q = t;
    for (int field = 0;; field++) {
        const char *fe = q;
        while (fe < te && *fe != '/')
            fe++;
        if (field == 2 && fe < te) /* a third slash */
            return fail_text(P, "bad face corner", t, te);
        if (fe > q || field == 0) {
            int rc = parse_index(q, fe, count[field], &idx[field]);
            if (rc == IDX_SYNTAX)
                return fail_text(P, "bad face corner", t, te);
            if (rc == IDX_RANGE && field > 0) {
                /* a uv or normal past the end: the corner goes without (as other readers do) */
                char qt[OBJ_QUOTE_TEXT + 8];
                err_quote(t, (size_t)(te - t), OBJ_QUOTE_TEXT, qt, sizeof qt);
                warn_add(P->ctx->warn,
                         "%s:%lu: face corner '%s': %s index out of range (%zu defined so "
                         "far); the corner has no %s",
                         P->where, P->line, qt, kind[field], count[field],
                         field == 1 ? "uv" : "normal");
                idx[field] = MESH_NONE;
            } else if (rc != IDX_OK) {
                char qt[OBJ_QUOTE_TEXT + 8];
                err_quote(t, (size_t)(te - t), OBJ_QUOTE_TEXT, qt, sizeof qt);
                if (rc == IDX_ZERO)
                    return err_set(P->e,
                                   "%s:%lu: face corner '%s': index 0 is invalid (OBJ counts "
                                   "from 1)",
                                   P->where, P->line, qt);
                return err_set(P->e, "%s:%lu: face corner '%s': %s index out of range (%zu "
                               "defined so far)",
                               P->where, P->line, qt, kind[field], count[field]);
            }
        }
        if (fe == te)
            break;
        q = fe + 1;
    }
    c->pos = idx[0];
    c->uv = idx[1];
    c->nrm = idx[2];
    return 0;
}

static int add_triangle(struct oparse *P, const struct mesh_corner *a,
                        const struct mesh_corner *b, const struct mesh_corner *c)
{
    if (P->n_tris >= OBJ_MAX_TRIS)
        return fail(P, "too many triangles");
    struct mesh_corner *nc = grow(P->corners, &P->cap_corners, (P->n_tris + 1) * 3, sizeof *nc);
    if (!nc)
        return oom(P);
    P->corners = nc;
    uint16_t *ns = grow(P->tri_slot, &P->cap_tri_slot, P->n_tris + 1, sizeof *ns);
    if (!ns)
        return oom(P);
    P->tri_slot = ns;
    nc += P->n_tris * 3;
    nc[0] = *a;
    nc[1] = *b;
    nc[2] = *c;
    ns[P->n_tris++] = P->cur_slot;
    P->slot_used[P->cur_slot] = true;
    return 0;
}

/* f c0 c1 c2 ...: the corners, then polygon.h's triangles (a fan when convex). */
static int parse_face(struct oparse *P, const char *p, const char *end)
{
    size_t n = 0;
    while ((p = num_next(p, end)) < end) {
        const char *t = p;
        p = num_end(p, end);
        if (n == P->cap_face) { /* every per-face array holds cap corners (scratch 2x) */
            size_t cap = P->cap_face;
            struct mesh_corner *nf = grow(P->face, &cap, n + 1, sizeof *nf);
            if (!nf)
                return oom(P);
            P->face = nf;
            uint32_t *np = realloc(P->face_pos, cap * sizeof *np);
            if (np)
                P->face_pos = np;
            uint32_t *ns = np ? realloc(P->face_scratch, 2 * cap * sizeof *ns) : NULL;
            if (ns)
                P->face_scratch = ns;
            uint32_t(*nt)[3] = ns ? realloc(P->face_tris, cap * sizeof *nt) : NULL;
            if (!nt)
                return oom(P);
            P->face_tris = nt;
            P->cap_face = cap;
        }
        if (parse_corner(P, t, p, &P->face[n]))
            return -1;
        P->face_pos[n] = P->face[n].pos;
        n++;
    }
    if (n < 3)
        return err_set(P->e, "%s:%lu: face needs at least 3 corners, got %zu", P->where,
                       P->line, n);
    if (n > UINT32_MAX / 4)
        return fail(P, "face has too many corners");
    enum polygon_how how =
        polygon_triangulate(P->pos, P->face_pos, (uint32_t)n, P->face_tris, P->face_scratch);
    if (how == POLYGON_FAN_TOO_BIG)
        warn_add(P->ctx->warn,
                 "%s:%lu: concave face of %zu corners fanned (ear clipping stops at %d)",
                 P->where, P->line, n, POLYGON_MAX_EAR);
    for (size_t i = 0; i + 2 < n; i++) {
        const uint32_t *tr = P->face_tris[i];
        if (add_triangle(P, &P->face[tr[0]], &P->face[tr[1]], &P->face[tr[2]]))
            return -1;
    }
    return 0;
}

static int use_material(struct oparse *P, const char *p, const char *end)
{
    if (p == end) {
        P->cur_slot = 0;
        return 0;
    }
    size_t n = (size_t)(end - p);
    uint64_t h = strmap_hash(p, n);
    long id = strmap_find(&P->slot_map, P->slot_names, p, n, h);
    if (id < 0) {
        if (P->n_slots >= OBJ_MAX_MATERIALS)
            return fail(P, "too many materials (limit 65535)");
        struct strmap_key *nk = grow(P->slot_names, &P->cap_slot_names, P->n_slots + 1, sizeof *nk);
        if (!nk)
            return oom(P);
        P->slot_names = nk;
        bool *nu = grow(P->slot_used, &P->cap_slot_used, P->n_slots + 1, sizeof *nu);
        if (!nu)
            return oom(P);
        P->slot_used = nu;
        id = (long)P->n_slots;
        if (strmap_add(&P->slot_map, h, (uint32_t)id))
            return oom(P);
        nk[id] = (struct strmap_key){p, n};
        nu[id] = false;
        P->n_slots++;
    }
    P->cur_slot = (uint16_t)id;
    return 0;
}

/* Does the file exist (as something stat can see)? */
static bool exists(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0;
}

/* mtllib NAME: read and parse it. A missing, unreadable or malformed library is a warning:
 * the faces then draw with the default material. 1 when name was found and read. */
static int load_library(struct oparse *P, const char *name, size_t n, bool quiet)
{
    if (memchr(name, '\0', n))
        return fail(P, "mtllib file name contains a NUL byte");
    char *full = material_path_beside(P->path, name, n);
    if (!full)
        return oom(P);
    if (quiet && !exists(full)) {
        free(full);
        return 0;
    }
    for (size_t i = 0; i < P->n_libs; i++)
        if (strcmp(P->libs[i].path, full) == 0) {
            free(full); /* listed twice: once is enough */
            return 1;
        }
    struct mtl_lib *nl = grow(P->libs, &P->cap_libs, P->n_libs + 1, sizeof *nl);
    if (!nl) {
        free(full);
        return oom(P);
    }
    P->libs = nl;
    char *text;
    size_t len;
    char q[OBJ_QUOTE_PATH + 8];
    err_quote(full, strlen(full), OBJ_QUOTE_PATH, q, sizeof q);
    int rc = file_read(full, FILE_MAX_TEXT, &text, &len);
    if (rc) {
        warn_add(P->ctx->warn, "%s:%lu: cannot open material library '%s': %s; default "
                 "materials used", P->where, P->line, q, file_strerror(rc));
        free(full);
        return 1;
    }
    struct err me;
    rc = mtl_parse(text, len, full, &P->libs[P->n_libs], P->ctx->warn, &me);
    free(text);
    free(full);
    if (rc) {
        warn_add(P->ctx->warn, "%s; material library ignored", me.msg);
        return 1;
    }
    P->n_libs++;
    return 1;
}

/* mtllib names: the whole rest of the line first ("my cube.mtl", as Blender writes names
 * with spaces), then with "\ " read as a space, then each word as its own file. */
static int parse_libraries(struct oparse *P, const char *p, const char *end)
{
    if (!P->path)
        return 0; /* in-memory text has no directory to look in */
    if (p == end)
        return 0;
    int rc = load_library(P, p, (size_t)(end - p), true);
    if (rc)
        return rc < 0 ? -1 : 0;
    if (memchr(p, '\\', (size_t)(end - p))) {
        char *un = malloc((size_t)(end - p) + 1);
        if (!un)
            return oom(P);
        size_t k = 0;
        for (const char *c = p; c < end; c++) {
            if (*c == '\\' && c + 1 < end && c[1] == ' ')
                c++;
            un[k++] = *c;
        }
        rc = load_library(P, un, k, true);
        free(un);
        if (rc)
            return rc < 0 ? -1 : 0;
    }
    while ((p = lex_skip_ws(p, end)) < end) {
        const char *t = p;
        p = lex_tok_end(p, end);
        if (load_library(P, t, (size_t)(p - t), false) < 0)
            return -1;
    }
    return 0;
}

static int parse_line(struct oparse *P, const char *p, const char *end)
{
    const char *kwe, *kw = lex_keyword(p, end, &kwe);
    if (!kw)
        return 0; /* blank or comment */
    p = kwe;
    size_t kn = (size_t)(kwe - kw);
    if (kn <= 2) {
        /* numbers and indices: '#' anywhere ends the line (see num_end) */
        if (lex_tok_is(kw, kwe, "v"))
            return add_position(P, p, end);
        if (lex_tok_is(kw, kwe, "vt"))
            return add_vector(P, "vt", p, end, 2, 1, &P->uv, &P->n_uv, &P->cap_uv, "uvs");
        if (lex_tok_is(kw, kwe, "vn"))
            return add_vector(P, "vn", p, end, 3, 3, &P->nrm, &P->n_nrm, &P->cap_nrm, "normals");
        if (lex_tok_is(kw, kwe, "f"))
            return parse_face(P, p, end);
        P->n_lines += lex_tok_is(kw, kwe, "l");
        P->n_points += lex_tok_is(kw, kwe, "p");
        return 0; /* o, g, s, vp, ... */
    }
    end = lex_rtrim(p, lex_comment_start(p, end));
    p = lex_skip_ws(p, end);
    if (lex_tok_is(kw, kwe, "usemtl"))
        return use_material(P, p, end);
    if (lex_tok_is(kw, kwe, "mtllib"))
        return parse_libraries(P, p, end);
    return 0;
}

/* ---- after the pass: materials, textures, the mesh ------------------------------------ */

static int finish(struct oparse *P, struct mesh *out)
{
    if (P->n_tris == 0) {
        if (P->n_lines || P->n_points)
            return err_set(P->e, "%s: no faces, only %lu line and %lu point elements (rastty "
                           "draws surfaces)", P->where, P->n_lines, P->n_points);
        return err_set(P->e, "%s: no faces", P->where);
    }
    uint16_t *slot_mat = malloc(P->n_slots * sizeof *slot_mat);
    if (!slot_mat)
        return err_set(P->e, "%s: out of memory", P->where);
    if (mtl_resolve(P->libs, P->n_libs, P->slot_names, P->slot_used, P->n_slots, P->ctx, out,
                    slot_mat, P->e)) {
        free(slot_mat);
        return -1;
    }
    for (size_t t = 0; t < P->n_tris; t++)
        P->tri_slot[t] = slot_mat[P->tri_slot[t]];
    free(slot_mat);

    struct mesh_source src = {
        .pos = P->pos, .uv = P->uv, .nrm = P->nrm,
        .n_pos = (uint32_t)P->n_pos, .n_uv = (uint32_t)P->n_uv, .n_nrm = (uint32_t)P->n_nrm,
        .corners = P->corners, .tri_material = P->tri_slot, .n_tris = (uint32_t)P->n_tris,
        .rgb = P->rgb,
    };
    /* OBJ keeps the conventions' smooth normals (the Mesa contract) unless --crease */
    src.crease_set = true;
    src.crease_deg = model_opts_of(P->ctx)->crease_set ? model_opts_of(P->ctx)->crease_deg : 180;
    struct err be;
    if (mesh_build(&src, out, &be))
        return err_set(P->e, "%s: %s", P->where, be.msg);
    return 0;
}

static void parser_free(struct oparse *P)
{
    free(P->pos);
    free(P->uv);
    free(P->nrm);
    free(P->rgb);
    free(P->corners);
    free(P->tri_slot);
    free(P->face);
    free(P->face_pos);
    free(P->face_scratch);
    free(P->face_tris);
    free(P->slot_names);
    free(P->slot_used);
    strmap_free(&P->slot_map);
    for (size_t i = 0; i < P->n_libs; i++)
        mtl_free(&P->libs[i]);
    free(P->libs);
}

int obj_read(const char *text, size_t len, const struct model_ctx *ctx, struct mesh *out,
             struct err *e)
{
    memset(out, 0, sizeof *out);
    struct oparse P = {.e = e, .ctx = ctx, .path = ctx->path};
    const char *shown = ctx->path ? ctx->path : OBJ_MEMORY_NAME;
    err_quote(shown, strlen(shown), OBJ_QUOTE_PATH, P.where, sizeof P.where);
    if (len >= 2 && (memcmp(text, "\xff\xfe", 2) == 0 || memcmp(text, "\xfe\xff", 2) == 0))
        return err_set(e, "%s: UTF-16 text (save the file as UTF-8 or ASCII)", P.where);
    int rc = -1;
    /* slot 0, the default material, exists before any usemtl */
    P.slot_names = grow(NULL, &P.cap_slot_names, 1, sizeof *P.slot_names);
    P.slot_used = grow(NULL, &P.cap_slot_used, 1, sizeof *P.slot_used);
    if (!P.slot_names || !P.slot_used) {
        err_set(e, "%s: out of memory", P.where);
        goto done;
    }
    P.slot_names[0] = (struct strmap_key){"", 0};
    P.slot_used[0] = false;
    P.n_slots = 1;

    const char *p = lex_skip_bom(text, text + len), *end = text + len;
    while (p < end) {
        const char *eol = lex_line_end(p, end);
        P.line++;
        if (parse_line(&P, p, eol))
            goto done;
        p = eol + 1;
    }
    rc = finish(&P, out);
done:
    parser_free(&P);
    if (rc)
        mesh_free(out);
    return rc;
}

int obj_parse(const char *text, size_t len, const char *path, struct mesh *out, struct err *e)
{
    struct model_ctx ctx = {.path = path};
    return model_parse_as(MODEL_OBJ, text, len, &ctx, out, e);
}

int obj_load(const char *path, struct mesh *out, struct err *e)
{
    char *text;
    size_t len;
    memset(out, 0, sizeof *out);
    int rc = file_read(path, FILE_MAX_MODEL, &text, &len);
    if (rc) {
        char q[OBJ_QUOTE_PATH + 8];
        err_quote(path, strlen(path), OBJ_QUOTE_PATH, q, sizeof q);
        return err_set(e, "%s: cannot read: %s", q, file_strerror(rc));
    }
    rc = obj_parse(text, len, path, out, e);
    free(text);
    return rc;
}
