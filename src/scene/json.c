/* json.c: the JSON reader (see json.h). A recursive descent over the bytes; each array or
 * object collects its members on a scratch stack, then copies them into the arena. */
#include "json.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* ---- the arena: blocks of bytes, never moved ---- */

struct json_block {
    struct json_block *next;
    size_t used, cap;
    _Alignas(16) unsigned char data[];
};

struct json_arena {
    struct json_block *head;
};

static void *arena_alloc(struct json_arena *a, size_t n)
{
    n = (n + 15) & ~(size_t)15;
    struct json_block *b = a->head;
    if (!b || b->cap - b->used < n) {
        size_t cap = n > ((size_t)1 << 16) ? n : ((size_t)1 << 16);
        b = malloc(sizeof *b + cap);
        if (!b)
            return NULL;
        b->used = 0;
        b->cap = cap;
        b->next = a->head;
        a->head = b;
    }
    void *p = b->data + b->used;
    b->used += n;
    return p;
}

/* ---- the parser ---- */

struct scratch { /* members of the arrays and objects being parsed, innermost last */
    struct json *v;
    const char **k;
    size_t n, cap;
};

struct parser {
    const char *s, *end, *text;
    struct json_arena *arena;
    struct scratch st;
    size_t values;
    struct err *e;
};

static size_t off(const struct parser *P, const char *at)
{
    return (size_t)(at - P->text);
}

/* "byte N: what, got 'x'" (or "the end of the text") */
static int fail(struct parser *P, const char *at, const char *what)
{
    if (at >= P->end)
        return err_set(P->e, "byte %zu: %s, got the end of the text", off(P, at), what);
    char q[24];
    err_quote(at, 1, 8, q, sizeof q);
    return err_set(P->e, "byte %zu: %s, got '%s'", off(P, at), what, q);
}

static void blanks(struct parser *P)
{
    while (P->s < P->end && (*P->s == ' ' || *P->s == '\t' || *P->s == '\n' || *P->s == '\r'))
        P->s++;
}

static int hex4(const char *p, unsigned *out)
{
    unsigned v = 0;
    for (int i = 0; i < 4; i++) {
        char c = p[i];
        int d = c >= '0' && c <= '9' ? c - '0' : c >= 'a' && c <= 'f' ? c - 'a' + 10
                : c >= 'A' && c <= 'F' ? c - 'A' + 10 : -1;
        if (d < 0)
            return -1;
        v = v * 16 + (unsigned)d;
    }
    *out = v;
    return 0;
}

static char *put_utf8(char *d, unsigned c)
{
    if (c < 0x80) {
        *d++ = (char)c;
    } else if (c < 0x800) {
        *d++ = (char)(0xc0 | c >> 6);
        *d++ = (char)(0x80 | (c & 0x3f));
    } else if (c < 0x10000) {
        *d++ = (char)(0xe0 | c >> 12);
        *d++ = (char)(0x80 | ((c >> 6) & 0x3f));
        *d++ = (char)(0x80 | (c & 0x3f));
    } else {
        *d++ = (char)(0xf0 | c >> 18);
        *d++ = (char)(0x80 | ((c >> 12) & 0x3f));
        *d++ = (char)(0x80 | ((c >> 6) & 0x3f));
        *d++ = (char)(0x80 | (c & 0x3f));
    }
    return d;
}

/* a string at P->s (its opening quote): decoded into the arena */
static int string(struct parser *P, const char **out, uint32_t *len_out)
{
    const char *start = P->s++, *p = P->s;
    size_t n = 0; /* first pass: the end, and an upper bound of the decoded length */
    for (; p < P->end && *p != '"'; p++, n++) {
        if ((unsigned char)*p < 0x20)
            return fail(P, p, "a control character inside a string (escape it)");
        if (*p == '\\')
            p++, n++;
    }
    if (p >= P->end)
        return fail(P, p, "the end of a string");
    if (n > UINT32_MAX - 1)
        return err_set(P->e, "byte %zu: string too long", off(P, start));
    char *d = arena_alloc(P->arena, n + 1), *d0 = d;
    if (!d)
        return err_set(P->e, "out of memory");
    for (const char *q = P->s; q < p; q++) {
        if (*q != '\\') {
            *d++ = *q;
            continue;
        }
        q++;
        switch (*q) {
        case '"': *d++ = '"'; break;
        case '\\': *d++ = '\\'; break;
        case '/': *d++ = '/'; break;
        case 'b': *d++ = '\b'; break;
        case 'f': *d++ = '\f'; break;
        case 'n': *d++ = '\n'; break;
        case 'r': *d++ = '\r'; break;
        case 't': *d++ = '\t'; break;
        case 'u': {
            unsigned c, c2;
            if (p - q < 5 || hex4(q + 1, &c))
                return fail(P, q, "four hex digits after \\u");
            q += 4;
            if (c >= 0xd800 && c < 0xdc00 && p - q >= 7 && q[1] == '\\' && q[2] == 'u' &&
                !hex4(q + 3, &c2) && c2 >= 0xdc00 && c2 < 0xe000) {
                c = 0x10000 + ((c - 0xd800) << 10) + (c2 - 0xdc00);
                q += 6;
            } else if (c >= 0xd800 && c < 0xe000) {
                c = 0xfffd; /* a lone surrogate: the replacement character */
            }
            d = put_utf8(d, c); /* (at most 4 bytes for the 6 or 12 read) */
            break;
        }
        default: return fail(P, q, "an escape (\\\" \\\\ \\/ \\b \\f \\n \\r \\t \\u)");
        }
    }
    *d = '\0';
    *out = d0;
    *len_out = (uint32_t)(d - d0);
    P->s = p + 1;
    return 0;
}

static int number(struct parser *P, double *out)
{
    const char *p = P->s, *start = p;
    if (p < P->end && *p == '-')
        p++;
    if (p >= P->end || !(*p >= '0' && *p <= '9'))
        return fail(P, p, "a digit");
    if (*p == '0')
        p++;
    else
        while (p < P->end && *p >= '0' && *p <= '9')
            p++;
    if (p < P->end && *p == '.') {
        p++;
        if (p >= P->end || !(*p >= '0' && *p <= '9'))
            return fail(P, p, "a digit after the decimal point");
        while (p < P->end && *p >= '0' && *p <= '9')
            p++;
    }
    if (p < P->end && (*p == 'e' || *p == 'E')) {
        p++;
        if (p < P->end && (*p == '+' || *p == '-'))
            p++;
        if (p >= P->end || !(*p >= '0' && *p <= '9'))
            return fail(P, p, "a digit in the exponent");
        while (p < P->end && *p >= '0' && *p <= '9')
            p++;
    }
    char buf[64];
    size_t n = (size_t)(p - start);
    if (n >= sizeof buf) { /* long digit strings: strtod on a heap copy */
        char *h = malloc(n + 1);
        if (!h)
            return err_set(P->e, "out of memory");
        memcpy(h, start, n);
        h[n] = '\0';
        *out = strtod(h, NULL);
        free(h);
    } else {
        memcpy(buf, start, n);
        buf[n] = '\0';
        *out = strtod(buf, NULL);
    }
    if (!isfinite(*out))
        return err_set(P->e, "byte %zu: number out of range", off(P, start));
    P->s = p;
    return 0;
}

static int literal(struct parser *P, const char *word)
{
    size_t n = strlen(word);
    if ((size_t)(P->end - P->s) < n || memcmp(P->s, word, n) != 0)
        return fail(P, P->s, "a value (object, array, string, number, true, false or null)");
    P->s += n;
    return 0;
}

static int push(struct parser *P, const struct json *v, const char *key)
{
    struct scratch *S = &P->st;
    if (S->n == S->cap) {
        size_t cap = S->cap ? S->cap * 2 : 256;
        struct json *nv = realloc(S->v, cap * sizeof *nv);
        if (nv)
            S->v = nv;
        const char **nk = nv ? realloc(S->k, cap * sizeof *nk) : NULL;
        if (!nk)
            return err_set(P->e, "out of memory");
        S->k = nk;
        S->cap = cap;
    }
    S->v[S->n] = *v;
    S->k[S->n++] = key;
    return 0;
}

static int value(struct parser *P, struct json *v, int depth);

/* an array or object's members from scratch entry `from` on, moved into the arena */
static int collect(struct parser *P, struct json *v, size_t from, bool keys)
{
    size_t n = P->st.n - from;
    if (n > UINT32_MAX)
        return err_set(P->e, "byte %zu: too many members", v->at);
    v->n = (uint32_t)n;
    if (n) {
        struct json *kids = arena_alloc(P->arena, n * sizeof *kids);
        const char **k = keys ? arena_alloc(P->arena, n * sizeof *k) : NULL;
        if (!kids || (keys && !k))
            return err_set(P->e, "out of memory");
        memcpy(kids, P->st.v + from, n * sizeof *kids);
        if (keys)
            memcpy(k, P->st.k + from, n * sizeof *k);
        v->kids = kids;
        v->keys = k;
    }
    P->st.n = from;
    return 0;
}

static int value(struct parser *P, struct json *v, int depth)
{
    blanks(P);
    memset(v, 0, sizeof *v);
    v->at = off(P, P->s);
    if (++P->values > JSON_MAX_VALUES)
        return err_set(P->e, "byte %zu: more than %u values", v->at, JSON_MAX_VALUES);
    if (P->s >= P->end)
        return fail(P, P->s, "a value");
    char c = *P->s;
    if (c == '{' || c == '[') {
        if (depth >= JSON_MAX_DEPTH)
            return err_set(P->e, "byte %zu: nested more than %d deep", v->at, JSON_MAX_DEPTH);
        bool obj = c == '{';
        v->type = obj ? JSON_OBJECT : JSON_ARRAY;
        size_t from = P->st.n;
        P->s++;
        blanks(P);
        if (P->s < P->end && *P->s == (obj ? '}' : ']')) {
            P->s++;
            return 0;
        }
        for (;;) {
            const char *key = NULL;
            uint32_t klen;
            if (obj) {
                blanks(P);
                if (P->s >= P->end || *P->s != '"')
                    return fail(P, P->s, "a member name in double quotes");
                if (string(P, &key, &klen))
                    return -1;
                blanks(P);
                if (P->s >= P->end || *P->s != ':')
                    return fail(P, P->s, "':' after a member name");
                P->s++;
            }
            struct json kid;
            if (value(P, &kid, depth + 1) || push(P, &kid, key))
                return -1;
            blanks(P);
            if (P->s < P->end && *P->s == ',') {
                P->s++;
                continue;
            }
            if (P->s < P->end && *P->s == (obj ? '}' : ']')) {
                P->s++;
                return collect(P, v, from, obj);
            }
            return fail(P, P->s, obj ? "',' or '}' after an object member"
                                     : "',' or ']' after an array element");
        }
    }
    if (c == '"') {
        v->type = JSON_STRING;
        return string(P, &v->str, &v->n);
    }
    if (c == '-' || (c >= '0' && c <= '9')) {
        v->type = JSON_NUMBER;
        return number(P, &v->num);
    }
    if (c == 't' || c == 'f') {
        v->type = JSON_BOOL;
        v->num = c == 't';
        return literal(P, c == 't' ? "true" : "false");
    }
    v->type = JSON_NULL;
    return literal(P, "null");
}

int json_parse(const char *text, size_t len, struct json_doc *doc, struct err *e)
{
    memset(doc, 0, sizeof *doc);
    struct json_arena *a = calloc(1, sizeof *a);
    if (!a)
        return err_set(e, "out of memory");
    struct parser P = {.s = text, .end = text + len, .text = text, .arena = a, .e = e};
    if (len >= 3 && memcmp(text, "\xef\xbb\xbf", 3) == 0)
        P.s += 3;
    struct json *root = arena_alloc(a, sizeof *root);
    int rc = root ? value(&P, root, 0) : err_set(e, "out of memory");
    if (rc == 0) {
        blanks(&P);
        if (P.s < P.end)
            rc = fail(&P, P.s, "the end of the text after the top-level value");
    }
    free(P.st.v);
    free(P.st.k);
    doc->arena = a;
    if (rc) {
        json_free(doc);
        return -1;
    }
    doc->root = root;
    return 0;
}

void json_free(struct json_doc *doc)
{
    if (doc->arena) {
        for (struct json_block *b = doc->arena->head, *n; b; b = n) {
            n = b->next;
            free(b);
        }
        free(doc->arena);
    }
    memset(doc, 0, sizeof *doc);
}

const struct json *json_get(const struct json *v, const char *key)
{
    if (!v || v->type != JSON_OBJECT)
        return NULL;
    for (uint32_t i = v->n; i-- > 0;)
        if (strcmp(v->keys[i], key) == 0)
            return &v->kids[i];
    return NULL;
}

const struct json *json_at(const struct json *v, uint32_t i)
{
    return v && v->type == JSON_ARRAY && i < v->n ? &v->kids[i] : NULL;
}

double json_num(const struct json *v, double dflt)
{
    return v && v->type == JSON_NUMBER ? v->num : dflt;
}

bool json_is_int(const struct json *v)
{
    return v && v->type == JSON_NUMBER && v->num == floor(v->num) && fabs(v->num) < 4.6e18;
}

int64_t json_int(const struct json *v, int64_t dflt)
{
    return json_is_int(v) ? (int64_t)v->num : dflt;
}

const char *json_str(const struct json *v, const char *dflt)
{
    return v && v->type == JSON_STRING ? v->str : dflt;
}

bool json_bool(const struct json *v, bool dflt)
{
    return v && v->type == JSON_BOOL ? v->num != 0 : dflt;
}

uint32_t json_len(const struct json *v)
{
    return v && v->type == JSON_ARRAY ? v->n : 0;
}
