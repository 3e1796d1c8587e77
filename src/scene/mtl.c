/* mtl.c: MTL material libraries (see mtl.h); lexing rules come from lex.h. */
#include "mtl.h"

#include <errno.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "file.h"
#include "lex.h"
#include "material.h"
#include "strmap.h"

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
    struct warnings *w;
    bool has_d;        /* the material being read said d (Tr then does not count) */
    bool warned_ke;    /* a non-zero Ke was warned about */
    unsigned warned_maps; /* the maps not drawn that were warned about (bits) */
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
    m->alpha = 1;
    m->alpha_cutoff = 0.5f;
    m->base = m->alpha_map = m->emissive_map = m->normal_map = m->occlusion_map = m->spec_map =
        (struct tex_slot){.tex = -1};
    m->normal_scale = 1;
    m->occlusion_strength = 1;
    m->base_lin[0] = m->base_lin[1] = m->base_lin[2] = 1;
    m->spec_lin[0] = m->spec_lin[1] = m->spec_lin[2] = 0.04f;
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
        struct mtl_maps *mp = realloc(L->maps, cap * sizeof *mp);
        if (mp)
            L->maps = mp;
        if (!m || !tp || !nm || !tl || !mp)
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
    memset(&L->maps[L->n], 0, sizeof L->maps[L->n]);
    L->maps[L->n].bm = 1;
    L->n++;
    P->has_d = false;
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

/* Every map_Kd option of the MTL format and how many values each takes (min fixed, up to
 * max if numbers): -blendu/-blendv/-cc/-clamp on|off, -bm/-boost/-texres one value, -mm base
 * gain, -o/-s/-t u [v [w]], -imfchan r|g|b|m|l|z, -type (reflection maps). */
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

/* a map statement (map_Kd; or `which` of MTL_MAP_*, -1 for map_Kd): its options, then the
 * file name; -bm's value kept for a bump map */
static int parse_map(struct mparse *P, const char *p, const char *end, int which)
{
    const char *kwname = which < 0 ? "map_Kd" : which == MTL_MAP_D ? "map_d"
                         : which == MTL_MAP_BUMP ? "map_Bump" : "norm";
    for (;;) {
        p = lex_skip_ws(p, end);
        const char *t = p, *te = lex_tok_end(p, end);
        if (te - t < 2 || *t != '-' || is_number(t, te))
            break; /* not an option: the file name starts here */
        size_t k, n_opt = sizeof map_options / sizeof map_options[0];
        for (k = 0; k < n_opt; k++)
            if (lex_tok_is(t, te, map_options[k].name))
                break;
        p = te;
        if (k == n_opt) {
            /* an option the format does not define (exporters invent them: -colorspace
             * sRGB): skip it and one value, keeping at least one word for the name */
            const char *v = lex_skip_ws(p, end), *ve = lex_tok_end(v, end);
            char q[MTL_QUOTE_TEXT + 8];
            err_quote(t, (size_t)(te - t), MTL_QUOTE_TEXT, q, sizeof q);
            if (v == end) { /* nothing follows: "-name.png" is the file name */
                p = t;
                break;
            }
            if (lex_skip_ws(ve, end) < end) {
                warn_add(P->w, "%s:%lu: unknown %s option '%s' skipped with its value",
                         P->where, P->line, kwname, q);
                p = ve;
            } else {
                warn_add(P->w, "%s:%lu: unknown %s option '%s' skipped", P->where, P->line,
                         kwname, q);
            }
            continue;
        }
        for (int a = 0; a < map_options[k].max; a++) {
            const char *q = lex_skip_ws(p, end), *qe = lex_tok_end(q, end);
            if (q == end) {
                if (a < map_options[k].min)
                    return err_set(P->e, "%s:%lu: %s option '%s' needs a value", P->where,
                                   P->line, kwname, map_options[k].name);
                break;
            }
            if (a >= map_options[k].min && !is_number(q, qe))
                break;
            float bm;
            if (which >= 0 && a == 0 && lex_tok_is(t, te, "-bm") &&
                lex_float(q, (size_t)(qe - q), &bm) == LEX_NUM_OK && bm == bm)
                P->lib->maps[P->lib->n - 1].bm = bm;
            p = qe;
        }
    }
    p = lex_skip_ws(p, end);
    if (p == end)
        return err_set(P->e, "%s:%lu: %s needs a file name", P->where, P->line, kwname);
    if (memchr(p, '\0', (size_t)(end - p)))
        return err_set(P->e, "%s:%lu: %s file name contains a NUL byte", P->where, P->line,
                       kwname);
    struct mtl_lib *L = P->lib;
    /* relative names are relative to the MTL file's directory */
    char *full = material_path_beside(P->path, p, (size_t)(end - p));
    if (!full)
        return oom(P);
    if (which >= 0) {
        struct mtl_maps *mp = &L->maps[L->n - 1];
        free(mp->path[which]);
        mp->path[which] = full;
        mp->line[which] = P->line;
        return 0;
    }
    free(L->texture_paths[L->n - 1]);
    L->texture_paths[L->n - 1] = full;
    L->texture_lines[L->n - 1] = P->line;
    return 0;
}

/* one number (d, Tr) */
static int parse_number(struct mparse *P, const char *kw, const char *p, const char *end,
                        float *out)
{
    p = lex_skip_ws(p, end);
    const char *te = lex_tok_end(p, end);
    if (lex_tok_is(p, te, "-halo")) /* "d -halo 0.5": the halo form, read as d */
        p = lex_skip_ws(te, end), te = lex_tok_end(p, end);
    if (p == end)
        return err_set(P->e, "%s:%lu: '%s' needs a number", P->where, P->line, kw);
    int rc = lex_float(p, (size_t)(te - p), out);
    if (rc)
        return fail_text(P, lex_num_problem(rc), p, te);
    return 0;
}

static int parse_line(struct mparse *P, const char *p, const char *end)
{
    const char *kwe, *kw = lex_keyword(p, end, &kwe);
    if (!kw)
        return 0; /* blank or comment */
    p = kwe;
    bool named = lex_tok_is(kw, kwe, "newmtl") || lex_tok_is(kw, kwe, "map_Kd") ||
                 lex_tok_is(kw, kwe, "map_d") || lex_tok_is(kw, kwe, "map_Bump") ||
                 lex_tok_is(kw, kwe, "map_bump") || lex_tok_is(kw, kwe, "bump") ||
                 lex_tok_is(kw, kwe, "norm");
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
        if (p == end) /* its statements still belong to it, not to the one before */
            warn_add(P->w, "%s:%lu: newmtl without a name (no usemtl can use it)", P->where,
                     P->line);
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
        return parse_map(P, p, end, -1);
    if (lex_tok_is(kw, kwe, "map_d"))
        return parse_map(P, p, end, MTL_MAP_D);
    if (lex_tok_is(kw, kwe, "map_Bump") || lex_tok_is(kw, kwe, "map_bump") ||
        lex_tok_is(kw, kwe, "bump"))
        return parse_map(P, p, end, MTL_MAP_BUMP);
    if (lex_tok_is(kw, kwe, "norm"))
        return parse_map(P, p, end, MTL_MAP_NORM);
    if (lex_tok_is(kw, kwe, "d") || (lex_tok_is(kw, kwe, "Tr") && !P->has_d)) {
        float v;
        if (parse_number(P, lex_tok_is(kw, kwe, "d") ? "d" : "Tr", p, end, &v))
            return -1;
        bool tr = !lex_tok_is(kw, kwe, "d");
        v = tr ? 1 - v : v;
        if (tr && !(v > 0)) { /* "Tr 1": exporters that write it mean opaque */
            warn_add(P->w, "%s:%lu: Tr 1 (fully transparent) read as opaque, as the exporters "
                           "that write it mean",
                     P->where, P->line);
            v = 1;
        }
        m->alpha = v == v ? (v < 0 ? 0 : v > 1 ? 1 : v) : 1;
        P->has_d |= lex_tok_is(kw, kwe, "d");
        return 0;
    }
    static const char *const unseen[] = {"map_Ks", "map_Ns", "map_Ke", "refl",
                                         "disp", "decal"};
    for (int k = 0; k < (int)(sizeof unseen / sizeof unseen[0]); k++)
        if (lex_tok_is(kw, kwe, unseen[k]) && !(P->warned_maps & 1u << k)) {
            warn_add(P->w, "%s:%lu: %s is not drawn (rastty draws map_Kd, map_d and the bump "
                           "and normal maps); drawn without it",
                     P->where, P->line, unseen[k]);
            P->warned_maps |= 1u << k;
        }
    if (lex_tok_is(kw, kwe, "Ke") && !P->warned_ke) {
        float ke[3] = {0, 0, 0};
        if (parse_colour(P, "Ke", p, end, ke) == 0 && (ke[0] > 0 || ke[1] > 0 || ke[2] > 0)) {
            warn_add(P->w, "%s:%lu: Ke (emission) is not drawn: OBJ follows the conventions' "
                           "Blinn-Phong, which has none",
                     P->where, P->line);
            P->warned_ke = true;
        }
        return 0;
    }
    return 0;
}

int mtl_parse(const char *text, size_t len, const char *path, struct mtl_lib *out,
              struct warnings *w, struct err *e)
{
    memset(out, 0, sizeof *out);
    struct mparse P = {.lib = out, .path = path, .e = e, .w = w};
    const char *shown = path ? path : "<memory>";
    err_quote(shown, strlen(shown), MTL_QUOTE_PATH, P.where, sizeof P.where);
    if (path && !(out->path = dup_bytes(path, strlen(path))))
        return err_set(e, "%s: out of memory", P.where);
    const char *p = lex_skip_bom(text, text + len), *end = text + len;
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

int mtl_load(const char *path, struct mtl_lib *out, struct warnings *w, struct err *e)
{
    char *text;
    size_t len;
    memset(out, 0, sizeof *out);
    int rc = file_read(path, FILE_MAX_TEXT, &text, &len);
    if (rc) {
        char q[MTL_QUOTE_PATH + 8];
        err_quote(path, strlen(path), MTL_QUOTE_PATH, q, sizeof q);
        return err_set(e, "%s: cannot open material library: %s", q, file_strerror(rc));
    }
    rc = mtl_parse(text, len, path, out, w, e);
    free(text);
    return rc;
}

void mtl_free(struct mtl_lib *lib)
{
    for (uint32_t i = 0; i < lib->n; i++) {
        free(lib->texture_paths[i]);
        free(lib->names[i]);
        for (int k = 0; k < MTL_MAP_COUNT; k++)
            free(lib->maps[i].path[k]);
    }
    free(lib->maps);
    free(lib->materials);
    free(lib->texture_paths);
    free(lib->names);
    free(lib->texture_lines);
    free(lib->path);
    memset(lib, 0, sizeof *lib);
}

/* ---- resolving a model's material names against its libraries ------------------------- */

struct libref {
    uint32_t lib, idx;
};

int mtl_resolve(const struct mtl_lib *libs, size_t n_libs, const struct strmap_key *slots,
                const bool *used, size_t n_slots, const struct model_ctx *ctx,
                struct mesh *out, uint16_t *slot_mat, struct err *e)
{
    char where[MTL_QUOTE_PATH + 8];
    const char *shown = ctx->path ? ctx->path : "<memory>";
    err_quote(shown, strlen(shown), MTL_QUOTE_PATH, where, sizeof where);
    size_t n_lib_mats = 0;
    for (size_t i = 0; i < n_libs; i++)
        n_lib_mats += libs[i].n;
    struct strmap_key *keys = malloc((n_lib_mats + 1) * sizeof *keys);
    struct libref *refs = malloc((n_lib_mats + 1) * sizeof *refs);
    struct libref *chosen = malloc(n_slots * sizeof *chosen);
    out->materials = malloc(n_slots * sizeof *out->materials);
    struct strmap names = {0};
    int rc = -1;
    if (!keys || !refs || !chosen || !out->materials) {
        err_set(e, "%s: out of memory", where);
        goto done;
    }
    /* every library name, first definition wins */
    size_t nk = 0;
    for (uint32_t l = 0; l < n_libs; l++)
        for (uint32_t i = 0; i < libs[l].n; i++) {
            const char *s = libs[l].names[i];
            size_t n = strlen(s);
            uint64_t h = strmap_hash(s, n);
            if (strmap_find(&names, keys, s, n, h) >= 0)
                continue;
            keys[nk] = (struct strmap_key){s, n};
            refs[nk] = (struct libref){l, i};
            if (strmap_add(&names, h, (uint32_t)nk++)) {
                err_set(e, "%s: out of memory", where);
                goto done;
            }
        }
    mtl_default(&out->materials[0], "default");
    out->materials[0].implicit = true; /* faces naming no (known) material: light.h */
    out->n_materials = 1;
    slot_mat[0] = 0;
    for (size_t s = 1; s < n_slots; s++) {
        const struct strmap_key *k = &slots[s];
        long id = used[s] ? strmap_find(&names, keys, k->s, k->n, strmap_hash(k->s, k->n)) : -1;
        if (id < 0) {
            slot_mat[s] = 0; /* unknown or unused name: the default material */
            continue;
        }
        chosen[out->n_materials] = refs[id];
        out->materials[out->n_materials] = libs[refs[id].lib].materials[refs[id].idx];
        slot_mat[s] = (uint16_t)out->n_materials++;
    }
    if (material_reserve_n(out, (MTL_MAP_COUNT + 1) * out->n_materials, e))
        goto done;
    for (uint32_t m = 1; m < out->n_materials; m++) {
        const struct mtl_lib *L = &libs[chosen[m].lib];
        const struct mtl_maps *mp = &L->maps[chosen[m].idx];
        const char *tp = L->texture_paths[chosen[m].idx];
        char lw[MTL_QUOTE_PATH + 8];
        err_quote(L->path ? L->path : "<memory>", strlen(L->path ? L->path : "<memory>"),
                  MTL_QUOTE_PATH, lw, sizeof lw);
        if (tp && material_texture_file(out, m, tp, lw, L->texture_lines[chosen[m].idx], ctx, e))
            goto done;
        struct material *mat = &out->materials[m];
        if (mp->path[MTL_MAP_D]) {
            mat->alpha_map.tex = material_image_file(out, mp->path[MTL_MAP_D], lw,
                                                     mp->line[MTL_MAP_D], ctx);
            mat->alpha_map.uv = 0;
        }
        for (int k = MTL_MAP_BUMP; k <= MTL_MAP_NORM; k++) /* norm wins over bump */
            if (mp->path[k] && material_normal_map(out, m, mp->path[k], lw, mp->line[k],
                                                   k == MTL_MAP_BUMP ? mp->bm : 1, ctx, e))
                goto done;
        /* opacity below 1: blended; an opacity map alone: cut out below 0.5 */
        if (mat->alpha < 1)
            mat->alpha_mode = MAT_BLEND;
        else if (mat->alpha_map.tex >= 0)
            mat->alpha_mode = MAT_MASK;
        mat->features = mat->alpha_mode != MAT_OPAQUE || mat->normal_map.tex >= 0;
    }
    rc = 0;
done:
    free(keys);
    free(refs);
    free(chosen);
    strmap_free(&names);
    return rc;
}
