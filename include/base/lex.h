/* lex.h: text scanning shared by the OBJ and MTL parsers (and anything else that reads our
 * line-based text formats).
 *
 * Owns: the one decimal number syntax (lex_float), and the rules for lines, whitespace,
 * tokens, statement keywords and comments on names (the small lex_* helpers, inline because
 * the OBJ loop runs them per byte), so both formats agree on them and there is one place to
 * get them right. No state, no allocation. Files are read by file.h (regular files only,
 * with size limits).
 * Called by obj.c and mtl.c: each splits its text with lex_line_end, takes the keyword with
 * lex_keyword and keeps its own statement rules (which '#' ends a line of numbers, what a
 * name may contain); ply.c and stl.c read their ASCII bodies word by word (lex_word).
 *
 * Conventions:
 *   - Text is a byte range [p, end): never read past end, never rely on a NUL (a NUL byte is
 *     just another token byte). Scanners return a pointer in [p, end].
 *   - Whitespace is ' ', '\t', '\r', '\v', '\f' ('\r' so CRLF files need nothing special;
 *     '\n' never occurs inside a line). A token is a maximal run of non-whitespace bytes.
 *   - lex_float is bit-identical to glibc strtof on every token it accepts and ignores the
 *     locale (a "de_DE" user still reads "0.5").
 *   - Where a '#' comment starts differs by statement (any '#' on a line of numbers, only a
 *     free-standing one on a line holding a name); that choice stays with each parser, and
 *     lex_comment_start is the rule for names. */
#ifndef RASTTY_LEX_H
#define RASTTY_LEX_H

#include <stdbool.h>
#include <stddef.h>
#include <string.h>

enum { LEX_NUM_OK = 0, LEX_NUM_SYNTAX = -1, LEX_NUM_RANGE = -2 };
/* Parse the whole token s[0..n) as a decimal float: [+-] digits [. digits] [e [+-] digits]
 * (".5" and "5." too). No hex, inf or nan, no surrounding whitespace; a result that
 * overflows float is LEX_NUM_RANGE, underflow gives 0 or a subnormal. On LEX_NUM_OK *out is
 * the correctly rounded value (bit-identical to glibc strtof, sign of -0 kept); otherwise
 * *out is untouched. Locale-independent: up to 15-16 significant digits with a small
 * exponent go through an exact double computation (Clinger's fast path); the rest through
 * strtof on a rewritten token without a decimal point. */
int lex_float(const char *s, size_t n, float *out);

/* "bad number" or "number out of range": how both formats word a token lex_float refused
 * (rc != LEX_NUM_OK), before quoting it. */
static inline const char *lex_num_problem(int rc)
{
    return rc == LEX_NUM_RANGE ? "number out of range" : "bad number";
}

/* ---- lines and tokens ---- */

/* Past a UTF-8 byte-order mark at p, if there is one (Windows editors write it; read as
 * text it would glue itself to the first keyword). */
static inline const char *lex_skip_bom(const char *p, const char *end)
{
    return end - p >= 3 && memcmp(p, "\xef\xbb\xbf", 3) == 0 ? p + 3 : p;
}

/* End of the line starting at p: its '\n' (which the line does not include) or end. */
static inline const char *lex_line_end(const char *p, const char *end)
{
    const char *eol = memchr(p, '\n', (size_t)(end - p));
    return eol ? eol : end;
}

static inline bool lex_is_ws(char c)
{
    return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

/* First non-whitespace byte at or after p (or end). */
static inline const char *lex_skip_ws(const char *p, const char *end)
{
    while (p < end && lex_is_ws(*p))
        p++;
    return p;
}

/* End of the token starting at p: the first whitespace byte (or end). */
static inline const char *lex_tok_end(const char *p, const char *end)
{
    while (p < end && !lex_is_ws(*p))
        p++;
    return p;
}

/* [p, end) without its trailing whitespace: the new end. */
static inline const char *lex_rtrim(const char *p, const char *end)
{
    while (end > p && lex_is_ws(end[-1]))
        end--;
    return end;
}

/* The next token at or after p in [p, end), crossing lines: whitespace and '\n' are skipped,
 * each '\n' counted in *line, and the token ends at whitespace or '\n'. Returns its start
 * and sets *te_out to its end; NULL at the end of the text (*te_out = end). For formats
 * whose numbers may wrap across lines (ASCII PLY and STL). */
static inline const char *lex_word(const char *p, const char *end, unsigned long *line,
                                   const char **te_out)
{
    for (;;) {
        p = lex_skip_ws(p, end);
        if (p < end && *p == '\n') {
            ++*line;
            p++;
            continue;
        }
        break;
    }
    if (p >= end) {
        *te_out = end;
        return NULL;
    }
    const char *t = p;
    while (p < end && !lex_is_ws(*p) && *p != '\n')
        p++;
    *te_out = p;
    return t;
}

/* Is the token [t, te) exactly word? (strlen of a literal folds away when inlined.) */
static inline bool lex_tok_is(const char *t, const char *te, const char *word)
{
    size_t n = strlen(word);
    return (size_t)(te - t) == n && memcmp(t, word, n) == 0;
}

/* The statement keyword of a line [p, end): its first token, which a '#' also ends ("v#c"
 * is "v", as "v #c" would be). Returns its start and sets *kw_end_out, or returns NULL for
 * a blank line or a comment line. */
static inline const char *lex_keyword(const char *p, const char *end, const char **kw_end_out)
{
    p = lex_skip_ws(p, end);
    if (p == end || *p == '#')
        return NULL;
    const char *kw = p;
    while (p < end && !lex_is_ws(*p) && *p != '#')
        p++;
    *kw_end_out = p;
    return kw;
}

/* Where the comment starts on a line holding a name (newmtl, map_Kd, usemtl, mtllib): at a
 * '#' that begins [p, end) or follows whitespace, so "tex#1.png" keeps its '#'. Returns
 * end when there is none. */
const char *lex_comment_start(const char *p, const char *end);

#endif
