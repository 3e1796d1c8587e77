/* stl.c: STL (binary and ASCII) -> struct mesh, the loader behind model.h.
 *
 * Binary: an 80-byte header (ignored, even when it starts with "solid"), a little-endian
 * uint32 triangle count, then 50 bytes per triangle: normal, three corners (float32 x3
 * each), a 16-bit attribute (ignored). The file must be exactly that long. ASCII:
 * "solid NAME" { "facet normal nx ny nz" "outer loop" "vertex x y z" x3 "endloop"
 * "endfacet" } "endsolid NAME", several solids allowed, words separated by any whitespace.
 *
 * STL stores every triangle's corners separately: equal positions (bit for bit) are welded
 * into one, so smooth normals (mesh.h: area-weighted per position) run across faces.
 * The facet normal decides the winding: a triangle whose corners turn against its given
 * (non-zero) normal is turned around, so flat shading, which takes the face normal from
 * the winding, uses the file's normal direction. No uvs, one default material.
 * Errors: ASCII "file:line: message"; binary "file: byte N: message". */
#include <math.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "file.h"
#include "lex.h"
#include "model.h"
#include "mtl.h"

#define STL_MAX_TRIS (UINT32_MAX / 3)

struct sparse {
    float *pos; /* welded positions, 3 floats each */
    uint8_t *rgb; /* their colours (3 bytes each) when the file has facet colours, else NULL */
    uint32_t n_pos;
    size_t cap_pos;
    struct mesh_corner *corners;
    uint32_t n_tris;
    size_t cap_tris;
    uint32_t *slot; /* weld hash: position index + 1, 0 = empty */
    size_t mask;
};

static uint64_t mix(uint64_t x)
{
    x ^= x >> 31;
    x *= 0x9e3779b97f4a7c15ULL;
    x ^= x >> 29;
    return x;
}

static uint64_t pos_hash(const float *p, uint32_t colour)
{
    uint32_t b[3];
    memcpy(b, p, sizeof b);
    return mix(((uint64_t)b[0] << 32 | b[1]) ^ mix(b[2] ^ (uint64_t)colour << 32));
}

static uint32_t colour_of(const struct sparse *S, uint32_t i)
{
    if (!S->rgb)
        return 0;
    const uint8_t *c = &S->rgb[3 * (size_t)i];
    return (uint32_t)c[0] | (uint32_t)c[1] << 8 | (uint32_t)c[2] << 16 | 1u << 24;
}

static int weld_grow(struct sparse *S)
{
    size_t cap = S->slot ? (S->mask + 1) * 2 : 1024;
    uint32_t *ns = calloc(cap, sizeof *ns);
    if (!ns)
        return -1;
    for (uint32_t i = 0; i < S->n_pos; i++) {
        size_t h = (size_t)pos_hash(&S->pos[3 * (size_t)i], colour_of(S, i)) & (cap - 1);
        while (ns[h])
            h = (h + 1) & (cap - 1);
        ns[h] = i + 1;
    }
    free(S->slot);
    S->slot = ns;
    S->mask = cap - 1;
    return 0;
}

/* index of position p (of colour `colour`: welded only with its own colour), added when new;
 * UINT32_MAX when out of memory */
static uint32_t weld(struct sparse *S, const float *p, uint32_t colour)
{
    if (!S->slot || ((size_t)S->n_pos + 1) * 2 > S->mask + 1)
        if (weld_grow(S))
            return UINT32_MAX;
    size_t h = (size_t)pos_hash(p, colour) & S->mask;
    for (uint32_t v; (v = S->slot[h]) != 0; h = (h + 1) & S->mask)
        if (memcmp(&S->pos[3 * (size_t)(v - 1)], p, 3 * sizeof *p) == 0 &&
            colour_of(S, v - 1) == colour)
            return v - 1;
    if (S->n_pos == S->cap_pos) {
        size_t cap = S->cap_pos ? S->cap_pos * 2 : 1024;
        float *np = realloc(S->pos, cap * 3 * sizeof *np);
        if (!np)
            return UINT32_MAX;
        S->pos = np;
        if (S->rgb) {
            uint8_t *nc = realloc(S->rgb, cap * 3);
            if (!nc)
                return UINT32_MAX;
            S->rgb = nc;
        }
        S->cap_pos = cap;
    }
    memcpy(&S->pos[3 * (size_t)S->n_pos], p, 3 * sizeof *p);
    if (S->rgb) {
        S->rgb[3 * (size_t)S->n_pos] = (uint8_t)colour;
        S->rgb[3 * (size_t)S->n_pos + 1] = (uint8_t)(colour >> 8);
        S->rgb[3 * (size_t)S->n_pos + 2] = (uint8_t)(colour >> 16);
    }
    S->slot[h] = ++S->n_pos;
    return S->n_pos - 1;
}

/* one triangle (of colour `colour`, 0: none): corners welded, winding turned to agree
 * with a non-zero normal. 0, or -1 out of memory */
static int add_tri(struct sparse *S, const float *nrm, float v[3][3], uint32_t colour)
{
    if (S->n_tris == S->cap_tris) {
        size_t cap = S->cap_tris ? S->cap_tris * 2 : 1024;
        struct mesh_corner *nc = realloc(S->corners, cap * 3 * sizeof *nc);
        if (!nc)
            return -1;
        S->corners = nc;
        S->cap_tris = cap;
    }
    double a[3], b[3];
    for (int k = 0; k < 3; k++) {
        a[k] = (double)v[1][k] - v[0][k];
        b[k] = (double)v[2][k] - v[0][k];
    }
    double c[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                   a[0] * b[1] - a[1] * b[0]};
    bool flip = nrm && c[0] * nrm[0] + c[1] * nrm[1] + c[2] * nrm[2] < 0;
    struct mesh_corner *t = &S->corners[(size_t)S->n_tris * 3];
    for (int k = 0; k < 3; k++) {
        uint32_t id = weld(S, v[flip && k ? 3 - k : k], colour);
        if (id == UINT32_MAX)
            return -1;
        t[k] = (struct mesh_corner){id, MESH_NONE, MESH_NONE};
    }
    S->n_tris++;
    return 0;
}

static float le_float(const uint8_t *p)
{
    uint32_t u = (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 |
                 (uint32_t)p[3] << 24;
    float f;
    memcpy(&f, &u, sizeof f);
    return f;
}

static int read_binary(struct sparse *S, const uint8_t *d, size_t len, const char *where,
                       struct err *e)
{
    uint32_t n = (uint32_t)d[80] | (uint32_t)d[81] << 8 | (uint32_t)d[82] << 16 |
                 (uint32_t)d[83] << 24;
    if ((len - 84) / 50 != n || (len - 84) % 50 != 0)
        return err_set(e, "%s: byte 80: binary STL says %u triangles, which take %llu bytes, "
                          "but the file has %zu",
                       where, n, 84ULL + 50ULL * n, len);
    if (n == 0)
        return err_set(e, "%s: no triangles", where);
    if (n > STL_MAX_TRIS)
        return err_set(e, "%s: %u triangles (limit %u)", where, n, STL_MAX_TRIS);
    /* facet colours: Materialise Magics ("COLOR=" r g b a in the header: the part's colour;
     * a facet's 15 bits, red lowest, its own when bit 15 is clear) or VisCAM/SolidView (no
     * such header: 15 bits, blue lowest, valid when bit 15 is set) */
    uint32_t part = 0;
    bool magics = false, any = false;
    for (size_t i = 0; i + 10 <= 80; i++)
        if (memcmp(d + i, "COLOR=", 6) == 0) {
            magics = true;
            part = (uint32_t)d[i + 6] | (uint32_t)d[i + 7] << 8 | (uint32_t)d[i + 8] << 16 |
                   1u << 24;
            break;
        }
    for (uint32_t i = 0; i < n && !any; i++) {
        uint16_t a = (uint16_t)(d[84 + 50 * (size_t)i + 48] | d[84 + 50 * (size_t)i + 49] << 8);
        any = magics ? !(a & 0x8000) || part : (a & 0x8000) != 0;
    }
    if (any && !(S->rgb = malloc(1)))
        return err_set(e, "%s: out of memory", where);
    for (uint32_t i = 0; i < n; i++) {
        const uint8_t *p = d + 84 + 50 * (size_t)i;
        float nrm[3], v[3][3];
        for (int k = 0; k < 3; k++)
            nrm[k] = le_float(p + 4 * k);
        for (int c = 0; c < 3; c++)
            for (int k = 0; k < 3; k++) {
                v[c][k] = le_float(p + 12 + 12 * c + 4 * k);
                if (!isfinite(v[c][k]))
                    return err_set(e, "%s: byte %zu: triangle %u: coordinate is not a finite "
                                      "number",
                                   where, (size_t)(p - d) + 12 + 12 * (size_t)c + 4 * (size_t)k,
                                   i);
            }
        bool use_n = isfinite(nrm[0]) && isfinite(nrm[1]) && isfinite(nrm[2]);
        uint32_t colour = 0;
        if (any) {
            uint16_t a = (uint16_t)(p[48] | p[49] << 8);
            uint32_t lo = a & 31, mid = (a >> 5) & 31, hi = (a >> 10) & 31;
            bool own = magics ? !(a & 0x8000) : (a & 0x8000) != 0;
            uint32_t r = magics ? lo : hi, b = magics ? hi : lo;
            colour = own ? (r * 255 + 15) / 31 | ((mid * 255 + 15) / 31) << 8 |
                               ((b * 255 + 15) / 31) << 16 | 1u << 24
                 : magics && part ? part
                                  : 204 | 204 << 8 | 204 << 16 | 1u << 24; /* the 0.8 grey */
        }
        if (add_tri(S, use_n ? nrm : NULL, v, colour))
            return err_set(e, "%s: out of memory", where);
    }
    return 0;
}

/* a keyword, in any case ("SOLID", "Facet": exporters write both) */
static bool kw_is(const char *t, const char *te, const char *w)
{
    size_t n = strlen(w);
    return (size_t)(te - t) == n && strncasecmp(t, w, n) == 0;
}

struct ascii {
    const char *p, *end;
    unsigned long line;
    const char *where;
    struct err *e;
};

/* next word (crossing lines, counting them); false at the end of the text */
static bool word(struct ascii *A, const char **t, const char **te)
{
    const char *we, *w = lex_word(A->p, A->end, &A->line, &we);
    A->p = we;
    if (!w)
        return false;
    *t = w, *te = we;
    return true;
}

static int expect(struct ascii *A, const char *w)
{
    const char *t, *te;
    if (!word(A, &t, &te))
        return err_set(A->e, "%s:%lu: unexpected end of file (expected '%s')", A->where,
                       A->line, w);
    if (!kw_is(t, te, w)) {
        char q[48];
        err_quote(t, (size_t)(te - t), 40, q, sizeof q);
        return err_set(A->e, "%s:%lu: expected '%s', got '%s'", A->where, A->line, w, q);
    }
    return 0;
}

static int numbers(struct ascii *A, float *out, int n)
{
    for (int k = 0; k < n; k++) {
        const char *t, *te;
        if (!word(A, &t, &te))
            return err_set(A->e, "%s:%lu: unexpected end of file (expected a number)",
                           A->where, A->line);
        int rc = lex_float(t, (size_t)(te - t), &out[k]);
        if (rc) {
            char q[48];
            err_quote(t, (size_t)(te - t), 40, q, sizeof q);
            return err_set(A->e, "%s:%lu: %s '%s'", A->where, A->line, lex_num_problem(rc), q);
        }
    }
    return 0;
}

/* the rest of the line (a solid's name) */
static void skip_line(struct ascii *A)
{
    while (A->p < A->end && *A->p != '\n')
        A->p++;
}

static int read_ascii(struct sparse *S, const char *text, size_t len, const char *where,
                      struct err *e)
{
    struct ascii A = {lex_skip_bom(text, text + len), text + len, 1, where, e};
    const char *t, *te;
    bool in_solid = false;
    while (word(&A, &t, &te)) {
        if (kw_is(t, te, "solid")) {
            skip_line(&A);
            in_solid = true;
        } else if (kw_is(t, te, "endsolid")) {
            skip_line(&A);
            in_solid = false;
        } else if (kw_is(t, te, "facet") && in_solid) {
            float nrm[3] = {0, 0, 0}, v[3][3];
            const char *save = A.p;
            unsigned long save_line = A.line;
            if (word(&A, &t, &te) && kw_is(t, te, "normal")) {
                if (numbers(&A, nrm, 3))
                    return -1;
            } else {
                A.p = save; /* "facet" alone: no normal */
                A.line = save_line;
            }
            if (expect(&A, "outer") || expect(&A, "loop"))
                return -1;
            for (int c = 0; c < 3; c++)
                if (expect(&A, "vertex") || numbers(&A, v[c], 3))
                    return -1;
            if (expect(&A, "endloop") || expect(&A, "endfacet"))
                return -1;
            if (S->n_tris >= STL_MAX_TRIS)
                return err_set(e, "%s:%lu: too many triangles", where, A.line);
            if (add_tri(S, nrm, v, 0))
                return err_set(e, "%s: out of memory", where);
        } else {
            char q[48];
            err_quote(t, (size_t)(te - t), 40, q, sizeof q);
            return err_set(e, "%s:%lu: expected '%s', got '%s'", where, A.line,
                           in_solid ? "facet" : "solid", q);
        }
    }
    if (S->n_tris == 0)
        return err_set(e, "%s: no triangles", where);
    return 0;
}

int stl_read(const char *data, size_t len, const struct model_ctx *ctx, struct mesh *out,
             struct err *e)
{
    memset(out, 0, sizeof *out);
    char where[FILE_QUOTE_SIZE];
    file_quote(ctx->path ? ctx->path : "<memory>", where, sizeof where);
    const uint8_t *d = (const uint8_t *)data;
    struct sparse S = {0};
    /* ASCII when it says "solid" and is not exactly a binary file's length */
    const char *t = lex_skip_bom(data, data + len);
    while (t < data + len && (lex_is_ws(*t) || *t == '\n'))
        t++;
    bool ascii = (size_t)(data + len - t) >= 5 && strncasecmp(t, "solid", 5) == 0;
    if (len >= 84) {
        uint32_t n = (uint32_t)d[80] | (uint32_t)d[81] << 8 | (uint32_t)d[82] << 16 |
                     (uint32_t)d[83] << 24;
        if ((len - 84) % 50 == 0 && (len - 84) / 50 == n)
            ascii = false;
    }
    int rc;
    if (ascii)
        rc = read_ascii(&S, data, len, where, e);
    else if (len < 84)
        rc = err_set(e, "%s: too short for a binary STL (%zu bytes, the header alone is 84)",
                     where, len);
    else
        rc = read_binary(&S, d, len, where, e);
    if (rc == 0) {
        out->materials = malloc(sizeof *out->materials);
        if (!out->materials) {
            rc = err_set(e, "%s: out of memory", where);
        } else {
            mtl_default(&out->materials[0], "default");
            out->materials[0].implicit = true; /* STL names no material: light.h's 0.8 */
            out->n_materials = 1;
            struct mesh_source src = {.pos = S.pos, .n_pos = S.n_pos, .corners = S.corners,
                                      .n_tris = S.n_tris, .rgb = S.rgb};
    src.crease_set = true;
    src.crease_deg = model_opts_of(ctx)->crease_set ? model_opts_of(ctx)->crease_deg : MESH_CREASE_DEFAULT;
            struct err be;
            if (mesh_build(&src, out, &be))
                rc = err_set(e, "%s: %s", where, be.msg);
            out->file_up = 'z'; /* the 3D-printing convention (slicers, the OS previews) */
        }
    }
    free(S.pos);
    free(S.rgb);
    free(S.corners);
    free(S.slot);
    if (rc)
        mesh_free(out);
    return rc;
}
