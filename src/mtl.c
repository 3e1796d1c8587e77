/* mtl.c: MTL material libraries (see mtl.h); lexing rules come from lex.h. */
#include "mtl.h"

#include <errno.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lex.h"
#include "texture.h"

#define MTL_QUOTE_PATH 100 /* bytes of a path shown in a message */
#define MTL_QUOTE_TEXT 40  /* bytes of file text shown in a message */

/* ---- MTL parsing -------------------------------------------------------------------- */

struct mparse {
    struct mtl_lib *lib;
    size_t cap;
    const char *path;
    char where[MTL_QUOTE_PATH + 8];
    unsigned long line;
    struct err *e;
};

static int fail_text(struct mparse *P, const char *what, const char *t, const char *te)
{
    char q[MTL_QUOTE_TEXT + 8];
    err_quote(t, (size_t)(te - t), MTL_QUOTE_TEXT, q, sizeof q);
    return err_set(P->e, "%s:%lu: %s '%s'", P->where, P->line, what, q);
}

static int oom(struct mparse *P)
{
    return err_set(P->e, "%s:%lu: out of memory", P->where, P->line);
}

void mtl_default(struct material *m, const char *name)
{
    memset(m, 0, sizeof *m);
    err_quote(name, strlen(name), MESH_NAME_MAX - 5, m->name, sizeof m->name);
    m->kd[0] = m->kd[1] = m->kd[2] = 1;
    m->ks[0] = m->ks[1] = m->ks[2] = 0.5f;
    m->ns = 32;
    m->texture = -1;
}

static char *dup_bytes(const char *s, size_t n)
{
    char *d = malloc(n + 1);
    if (d) {
        memcpy(d, s, n);
        d[n] = '\0';
    }
    return d;
}

static int add_material(struct mparse *P, const char *name, size_t len)
{
    struct mtl_lib *L = P->lib;
    if (L->n == P->cap) {
        if (P->cap >= UINT32_MAX / 2)
            return err_set(P->e, "%s:%lu: too many materials", P->where, P->line);
        size_t cap = P->cap ? P->cap * 2 : 8;
        struct material *m = realloc(L->materials, cap * sizeof *m);
        if (m)
            L->materials = m;
        char **tp = realloc(L->texture_paths, cap * sizeof *tp);
        if (tp)
            L->texture_paths = tp;
        char **nm = realloc(L->names, cap * sizeof *nm);
        if (nm)
            L->names = nm;
        unsigned long *tl = realloc(L->texture_lines, cap * sizeof *tl);
        if (tl)
            L->texture_lines = tl;
        if (!m || !tp || !nm || !tl)
            return oom(P);
        P->cap = cap;
    }
    char *copy = dup_bytes(name, len);
    if (!copy)
        return oom(P);
    struct material *m = &L->materials[L->n];
    mtl_default(m, "");
    err_quote(name, len, MESH_NAME_MAX - 5, m->name, sizeof m->name);
    L->names[L->n] = copy;
    L->texture_paths[L->n] = NULL;
    L->texture_lines[L->n] = 0;
    L->n++;
    return 0;
}

/* Colour statements: "r", "r g b" (extra values ignored); "spectral ..." and "xyz ..."
 * forms are accepted and leave the colour alone. */
static int parse_colour(struct mparse *P, const char *kw, const char *p, const char *end,
                        float *out)
{
    float v[3];
    int n = 0;
    p = lex_skip_ws(p, end);
    const char *t = p, *te = lex_tok_end(p, end);
    if (lex_tok_is(t, te, "spectral") || lex_tok_is(t, te, "xyz"))
        return 0;
    while (n < 3 && (p = lex_skip_ws(p, end)) < end) {
        t = p;
        p = lex_tok_end(p, end);
        int rc = lex_float(t, (size_t)(p - t), &v[n]);
        if (rc)
            return fail_text(P, lex_num_problem(rc), t, p);
        n++;
    }
    if (n == 2 || n == 0)
        return err_set(P->e, "%s:%lu: '%s' needs 3 numbers, got %d", P->where, P->line, kw, n);
    if (n == 1)
        v[1] = v[2] = v[0];
    memcpy(out, v, sizeof v);
    return 0;
}

/* map_Kd options and how many values each takes (min fixed, up to max if numbers). */
static const struct {
    const char *name;
    int min, max;
} map_options[] = {
    {"-blendu", 1, 1}, {"-blendv", 1, 1}, {"-cc", 1, 1},      {"-clamp", 1, 1},
    {"-bm", 1, 1},     {"-boost", 1, 1},  {"-mm", 2, 2},      {"-o", 1, 3},
    {"-s", 1, 3},      {"-t", 1, 3},      {"-texres", 1, 1},  {"-imfchan", 1, 1},
    {"-type", 1, 1},
};

static bool is_number(const char *t, const char *te)
{
    float f;
    return lex_float(t, (size_t)(te - t), &f) == LEX_NUM_OK;
}

static int parse_map(struct mparse *P, const char *p, const char *end)
{
    for (;;) {
        p = lex_skip_ws(p, end);
        const char *t = p, *te = lex_tok_end(p, end);
        size_t k, n_opt = sizeof map_options / sizeof map_options[0];
        for (k = 0; k < n_opt; k++)
            if (lex_tok_is(t, te, map_options[k].name))
                break;
        if (k == n_opt)
            break; /* not an option: the file name starts here */
        p = te;
        for (int a = 0; a < map_options[k].max; a++) {
            const char *q = lex_skip_ws(p, end), *qe = lex_tok_end(q, end);
            if (q == end) {
                if (a < map_options[k].min)
                    return err_set(P->e, "%s:%lu: map_Kd option '%s' needs a value", P->where,
                                   P->line, map_options[k].name);
                break;
            }
            if (a >= map_options[k].min && !is_number(q, qe))
                break;
            p = qe;
        }
    }
    p = lex_skip_ws(p, end);
    if (p == end)
        return err_set(P->e, "%s:%lu: map_Kd needs a file name", P->where, P->line);
    if (memchr(p, '\0', (size_t)(end - p)))
        return err_set(P->e, "%s:%lu: map_Kd file name contains a NUL byte", P->where, P->line);
    struct mtl_lib *L = P->lib;
    /* relative names are relative to the MTL file's directory */
    size_t dir = 0;
    if (P->path && *p != '/') {
        const char *slash = strrchr(P->path, '/');
        dir = slash ? (size_t)(slash - P->path) + 1 : 0;
    }
    size_t nlen = (size_t)(end - p);
    char *full = malloc(dir + nlen + 1);
    if (!full)
        return oom(P);
    if (dir)
        memcpy(full, P->path, dir);
    memcpy(full + dir, p, nlen);
    full[dir + nlen] = '\0';
    free(L->texture_paths[L->n - 1]);
    L->texture_paths[L->n - 1] = full;
    L->texture_lines[L->n - 1] = P->line;
    return 0;
}

static int parse_line(struct mparse *P, const char *p, const char *end)
{
    const char *kwe, *kw = lex_keyword(p, end, &kwe);
    if (!kw)
        return 0; /* blank or comment */
    p = kwe;
    bool named = lex_tok_is(kw, kwe, "newmtl") || lex_tok_is(kw, kwe, "map_Kd");
    /* names keep a '#' inside a word; lines of numbers end at any '#' */
    if (named) {
        end = lex_comment_start(p, end);
    } else {
        const char *hash = memchr(p, '#', (size_t)(end - p));
        end = hash ? hash : end;
    }
    end = lex_rtrim(p, end);
    p = lex_skip_ws(p, end);
    if (lex_tok_is(kw, kwe, "newmtl")) {
        if (p == end)
            return err_set(P->e, "%s:%lu: newmtl needs a name", P->where, P->line);
        return add_material(P, p, (size_t)(end - p));
    }
    struct mtl_lib *L = P->lib;
    struct material *m = L->n ? &L->materials[L->n - 1] : NULL;
    if (!m)
        return 0; /* statements before the first newmtl belong to nothing */
    if (lex_tok_is(kw, kwe, "Kd"))
        return parse_colour(P, "Kd", p, end, m->kd);
    if (lex_tok_is(kw, kwe, "Ks"))
        return parse_colour(P, "Ks", p, end, m->ks);
    if (lex_tok_is(kw, kwe, "Ns")) {
        const char *te = lex_tok_end(p, end);
        if (p == end)
            return err_set(P->e, "%s:%lu: 'Ns' needs a number", P->where, P->line);
        int rc = lex_float(p, (size_t)(te - p), &m->ns);
        if (rc)
            return fail_text(P, lex_num_problem(rc), p, te);
        if (m->ns < 0)
            m->ns = 0; /* pow(x, negative) would blow up at grazing angles */
        return 0;
    }
    if (lex_tok_is(kw, kwe, "map_Kd"))
        return parse_map(P, p, end);
    return 0;
}

int mtl_parse(const char *text, size_t len, const char *path, struct mtl_lib *out, struct err *e)
{
    memset(out, 0, sizeof *out);
    struct mparse P = {.lib = out, .path = path, .e = e};
    const char *shown = path ? path : "<memory>";
    err_quote(shown, strlen(shown), MTL_QUOTE_PATH, P.where, sizeof P.where);
    if (path && !(out->path = dup_bytes(path, strlen(path))))
        return err_set(e, "%s: out of memory", P.where);
    const char *p = text, *end = text + len;
    while (p < end) {
        const char *eol = lex_line_end(p, end);
        P.line++;
        if (parse_line(&P, p, eol)) {
            mtl_free(out);
            return -1;
        }
        p = eol + 1;
    }
    return 0;
}

int mtl_load(const char *path, struct mtl_lib *out, struct err *e)
{
    char *text;
    size_t len;
    memset(out, 0, sizeof *out);
    int rc = lex_read_file(path, &text, &len);
    if (rc) {
        char q[MTL_QUOTE_PATH + 8];
        err_quote(path, strlen(path), MTL_QUOTE_PATH, q, sizeof q);
        return err_set(e, "%s: cannot open material library: %s", q, strerror(rc));
    }
    rc = mtl_parse(text, len, path, out, e);
    free(text);
    return rc;
}

void mtl_free(struct mtl_lib *lib)
{
    for (uint32_t i = 0; i < lib->n; i++) {
        free(lib->texture_paths[i]);
        free(lib->names[i]);
    }
    free(lib->materials);
    free(lib->texture_paths);
    free(lib->names);
    free(lib->texture_lines);
    free(lib->path);
    memset(lib, 0, sizeof *lib);
}

int mtl_load_texture(const struct mtl_lib *lib, uint32_t i, struct texture *out, struct err *e)
{
    const char *tp = lib->texture_paths[i];
    const char *shown = lib->path ? lib->path : "<memory>";
    char where[MTL_QUOTE_PATH + 8], q[MTL_QUOTE_PATH + 8];
    err_quote(shown, strlen(shown), MTL_QUOTE_PATH, where, sizeof where);
    err_quote(tp, strlen(tp), MTL_QUOTE_PATH, q, sizeof q);
    /* open it here first so the common failure reads as one clean sentence */
    FILE *f = fopen(tp, "rb");
    if (!f)
        return err_set(e, "%s:%lu: cannot open texture '%s': %s", where, lib->texture_lines[i],
                       q, strerror(errno));
    fclose(f);
    struct err te;
    if (texture_load(tp, out, &te))
        return err_set(e, "%s:%lu: bad texture (%s)", where, lib->texture_lines[i], te.msg);
    return 0;
}
