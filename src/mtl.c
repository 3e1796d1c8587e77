/* mtl.c: MTL material libraries, and the file/number lexing OBJ shares (see mtl.h). */
#include "mtl.h"

#include <errno.h>
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "texture.h"

#define MTL_QUOTE_PATH 100 /* bytes of a path shown in a message */
#define MTL_QUOTE_TEXT 40  /* bytes of file text shown in a message */
#define MTL_MAX_FILE ((size_t)1 << 34) /* 16 GiB: refuse before trying to allocate */

/* ---- lexing shared with obj.c ------------------------------------------------------- */

int mtl_read_file(const char *path, char **text_out, size_t *len_out)
{
    *text_out = NULL;
    *len_out = 0;
    FILE *f = fopen(path, "rb");
    if (!f)
        return errno ? errno : EIO;
    struct stat st;
    int rc = 0;
    if (fstat(fileno(f), &st) != 0) {
        rc = errno ? errno : EIO;
        fclose(f);
        return rc;
    }
    if (S_ISDIR(st.st_mode)) {
        fclose(f);
        return EISDIR;
    }
    /* regular files: one read of the known size; pipes and the like: grow as data comes */
    /* +2: room for the NUL and one byte more, so the first read comes back short at EOF */
    size_t cap = S_ISREG(st.st_mode) && st.st_size >= 0 ? (size_t)st.st_size + 2 : 65536;
    if (cap > MTL_MAX_FILE) {
        fclose(f);
        return EFBIG;
    }
    char *buf = malloc(cap);
    size_t len = 0;
    if (!buf) {
        fclose(f);
        return ENOMEM;
    }
    for (;;) {
        if (len + 1 >= cap) {
            if (cap >= MTL_MAX_FILE) {
                rc = EFBIG;
                break;
            }
            char *nb = realloc(buf, cap * 2);
            if (!nb) {
                rc = ENOMEM;
                break;
            }
            buf = nb;
            cap *= 2;
        }
        size_t want = cap - 1 - len, got = fread(buf + len, 1, want, f);
        len += got;
        if (got < want) {
            if (ferror(f))
                rc = errno ? errno : EIO;
            break;
        }
    }
    fclose(f);
    if (rc) {
        free(buf);
        return rc;
    }
    buf[len] = '\0';
    *text_out = buf;
    *len_out = len;
    return 0;
}

static const double pow10_exact[23] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                       1e8,  1e9,  1e10, 1e11, 1e12, 1e13, 1e14, 1e15,
                                       1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};

static bool is_digit(char c)
{
    return c >= '0' && c <= '9';
}

/* The exact answer for everything the fast path declines: rewrite the (already validated)
 * token, without its sign, as "DIGITSe<exp>" with no decimal point, so strtof reads it the
 * same in every locale, and let strtof round it (glibc rounds correctly). Keeping 120
 * significant digits plus a sticky '1' for any nonzero digits dropped after them is exact
 * for rounding: a float rounding boundary (odd * 2^k, k >= -150) has at most 113
 * significant digits, so the kept digits either differ from it or equal it, and the
 * sticky digit then says "above". */
static float slow_strtof(const char *s, size_t n)
{
    char buf[160];
    size_t k = 0, i = 0;
    long e10 = 0;
    int kept = 0;
    bool sticky = false, frac = false;
    if (s[i] == '+' || s[i] == '-')
        i++; /* the caller applies the sign */
    for (; i < n && s[i] != 'e' && s[i] != 'E'; i++) {
        if (s[i] == '.') {
            frac = true;
            continue;
        }
        if (kept == 0 && s[i] == '0') { /* leading zero */
            e10 -= frac;
            continue;
        }
        if (kept < 120) {
            buf[k++] = s[i];
            kept++;
            e10 -= frac;
        } else {
            sticky |= s[i] != '0';
            e10 += !frac;
        }
    }
    if (kept == 0)
        return 0;
    if (sticky) {
        buf[k++] = '1';
        e10--;
    }
    if (i < n) { /* exponent: validated by the caller, saturated like there */
        bool eneg = false;
        long ev = 0;
        i++;
        if (s[i] == '+' || s[i] == '-')
            eneg = s[i++] == '-';
        for (; i < n; i++)
            if (ev < 100000)
                ev = ev * 10 + (s[i] - '0');
        e10 += eneg ? -ev : ev;
    }
    snprintf(buf + k, sizeof buf - k, "e%ld", e10);
    return strtof(buf, NULL);
}

int mtl_lex_float(const char *s, size_t n, float *out)
{
    size_t i = 0;
    bool neg = false;
    if (i < n && (s[i] == '+' || s[i] == '-'))
        neg = s[i++] == '-';
    /* 18 significant digits cannot overflow 64 bits, and are more than the fast path
     * takes (2^53); `dropped` says whether any nonzero digit did not fit */
    uint64_t mant = 0;
    int sig = 0;
    long e10 = 0;
    bool any = false, dropped = false;
    for (; i < n && is_digit(s[i]); i++) {
        any = true;
        if (sig < 18) {
            mant = mant * 10 + (uint64_t)(s[i] - '0');
            sig += mant != 0;
        } else {
            e10++;
            dropped |= s[i] != '0';
        }
    }
    if (i < n && s[i] == '.') {
        for (i++; i < n && is_digit(s[i]); i++) {
            any = true;
            if (sig < 18) {
                mant = mant * 10 + (uint64_t)(s[i] - '0');
                sig += mant != 0;
                e10--;
            } else {
                dropped |= s[i] != '0';
            }
        }
    }
    if (!any)
        return MTL_NUM_SYNTAX;
    if (i < n && (s[i] == 'e' || s[i] == 'E')) {
        bool eneg = false;
        long ev = 0;
        i++;
        if (i < n && (s[i] == '+' || s[i] == '-'))
            eneg = s[i++] == '-';
        if (i >= n || !is_digit(s[i]))
            return MTL_NUM_SYNTAX;
        for (; i < n && is_digit(s[i]); i++)
            if (ev < 100000) /* saturate: the result is 0 or inf long before */
                ev = ev * 10 + (s[i] - '0');
        e10 += eneg ? -ev : ev;
    }
    if (i != n)
        return MTL_NUM_SYNTAX;

    float f;
    if (mant == 0) {
        f = 0;
    } else if (!dropped && mant <= (1ULL << 53) && e10 >= -22 && e10 <= 22) {
        /* Clinger's fast path: mant and 10^|e10| are exact doubles, so one IEEE operation
         * gives the correctly rounded double d. Rounding d to float is then correct unless
         * d is exactly halfway between two floats (a double rounding hazard): those go to
         * the slow path, which decides with more precision. */
        double d = (double)mant;
        d = e10 < 0 ? d / pow10_exact[-e10] : d * pow10_exact[e10];
        /* a normal float keeps the top 24 of the double's 53 significand bits, so d is a
         * tie exactly when the 29 dropped bits are 1000...0 */
        uint64_t bits;
        memcpy(&bits, &d, sizeof bits);
        if ((bits & 0x1fffffffULL) == 0x10000000ULL || d < 0x1p-126)
            f = slow_strtof(s, n);
        else
            f = (float)d;
    } else {
        f = slow_strtof(s, n);
    }
    if (!isfinite(f))
        return MTL_NUM_RANGE;
    *out = neg ? -f : f;
    return MTL_NUM_OK;
}

/* ---- MTL parsing -------------------------------------------------------------------- */

static bool is_ws(char c)
{
    return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

static const char *skip_ws(const char *p, const char *end)
{
    while (p < end && is_ws(*p))
        p++;
    return p;
}

static const char *tok_end(const char *p, const char *end)
{
    while (p < end && !is_ws(*p))
        p++;
    return p;
}

static bool tok_is(const char *t, const char *te, const char *word)
{
    size_t n = strlen(word);
    return (size_t)(te - t) == n && memcmp(t, word, n) == 0;
}

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
    p = skip_ws(p, end);
    const char *t = p, *te = tok_end(p, end);
    if (tok_is(t, te, "spectral") || tok_is(t, te, "xyz"))
        return 0;
    while (n < 3 && (p = skip_ws(p, end)) < end) {
        t = p;
        p = tok_end(p, end);
        int rc = mtl_lex_float(t, (size_t)(p - t), &v[n]);
        if (rc == MTL_NUM_RANGE)
            return fail_text(P, "number out of range", t, p);
        if (rc)
            return fail_text(P, "bad number", t, p);
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
    return mtl_lex_float(t, (size_t)(te - t), &f) == MTL_NUM_OK;
}

static int parse_map(struct mparse *P, const char *p, const char *end)
{
    for (;;) {
        p = skip_ws(p, end);
        const char *t = p, *te = tok_end(p, end);
        size_t k, n_opt = sizeof map_options / sizeof map_options[0];
        for (k = 0; k < n_opt; k++)
            if (tok_is(t, te, map_options[k].name))
                break;
        if (k == n_opt)
            break; /* not an option: the file name starts here */
        p = te;
        for (int a = 0; a < map_options[k].max; a++) {
            const char *q = skip_ws(p, end), *qe = tok_end(q, end);
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
    p = skip_ws(p, end);
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

/* The comment starts at a '#' that begins the line or follows whitespace. */
static const char *comment_cut(const char *p, const char *end)
{
    for (const char *q = p; q < end; q++) {
        q = memchr(q, '#', (size_t)(end - q));
        if (!q)
            break;
        if (q == p || is_ws(q[-1]))
            return q;
    }
    return end;
}

static int parse_line(struct mparse *P, const char *p, const char *end)
{
    p = skip_ws(p, end);
    if (p == end || *p == '#')
        return 0;
    const char *kw = p;
    while (p < end && !is_ws(*p) && *p != '#')
        p++;
    const char *kwe = p;
    bool named = tok_is(kw, kwe, "newmtl") || tok_is(kw, kwe, "map_Kd");
    /* names keep a '#' inside a word; lines of numbers end at any '#' */
    if (named) {
        end = comment_cut(p, end);
    } else {
        const char *hash = memchr(p, '#', (size_t)(end - p));
        end = hash ? hash : end;
    }
    while (end > p && is_ws(end[-1]))
        end--;
    p = skip_ws(p, end);
    if (tok_is(kw, kwe, "newmtl")) {
        if (p == end)
            return err_set(P->e, "%s:%lu: newmtl needs a name", P->where, P->line);
        return add_material(P, p, (size_t)(end - p));
    }
    struct mtl_lib *L = P->lib;
    struct material *m = L->n ? &L->materials[L->n - 1] : NULL;
    if (!m)
        return 0; /* statements before the first newmtl belong to nothing */
    if (tok_is(kw, kwe, "Kd"))
        return parse_colour(P, "Kd", p, end, m->kd);
    if (tok_is(kw, kwe, "Ks"))
        return parse_colour(P, "Ks", p, end, m->ks);
    if (tok_is(kw, kwe, "Ns")) {
        const char *te = tok_end(p, end);
        if (p == end)
            return err_set(P->e, "%s:%lu: 'Ns' needs a number", P->where, P->line);
        int rc = mtl_lex_float(p, (size_t)(te - p), &m->ns);
        if (rc == MTL_NUM_RANGE)
            return fail_text(P, "number out of range", p, te);
        if (rc)
            return fail_text(P, "bad number", p, te);
        if (m->ns < 0)
            m->ns = 0; /* pow(x, negative) would blow up at grazing angles */
        return 0;
    }
    if (tok_is(kw, kwe, "map_Kd"))
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
        const char *eol = memchr(p, '\n', (size_t)(end - p));
        if (!eol)
            eol = end;
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
    int rc = mtl_read_file(path, &text, &len);
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
