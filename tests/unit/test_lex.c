/* test_lex.c: the text scanning OBJ and MTL share: whitespace and tokens, the comment rule
 * for names, and the number parser (bit-identical to glibc strtof). */
#include <errno.h>
#include <math.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "lex.h"
#include "test.h"

/* ---- whitespace, tokens, comments ---- */

TEST(whitespace_is_blank_and_cr_but_not_newline)
{
    static const char ws[] = " \t\r\v\f", not_ws[] = "\n\0a#/.-";
    for (size_t i = 0; i < sizeof ws - 1; i++)
        if (!lex_is_ws(ws[i]))
            test_fail(t, __FILE__, __LINE__, "byte 0x%02x should be whitespace", ws[i]);
    for (size_t i = 0; i < sizeof not_ws - 1; i++)
        if (lex_is_ws(not_ws[i]))
            test_fail(t, __FILE__, __LINE__, "byte 0x%02x should not be whitespace",
                      not_ws[i]);
}

TEST(tokens_are_bounded_by_whitespace_and_end)
{
    const char *s = " \t key  val#x \r\v";
    const char *end = s + strlen(s);
    const char *p = lex_skip_ws(s, end), *te = lex_tok_end(p, end);
    CHECK_EQ_INT(p - s, 3);
    CHECK_EQ_INT(te - s, 6);
    CHECK(lex_tok_is(p, te, "key"));
    CHECK(!lex_tok_is(p, te, "ke"));
    CHECK(!lex_tok_is(p, te, "keys"));
    p = lex_skip_ws(te, end);
    te = lex_tok_end(p, end);
    CHECK(lex_tok_is(p, te, "val#x")); /* '#' is an ordinary byte here */
    CHECK_EQ_INT(lex_rtrim(s, end) - s, 13);
    CHECK(lex_skip_ws(te, end) == end);
    /* all blank: skipping reaches end, trimming reaches the start */
    CHECK(lex_skip_ws(s, s + 3) == s + 3);
    CHECK(lex_rtrim(s, s + 3) == s);
    /* the range ends at end, not at a NUL */
    CHECK(lex_tok_end(s + 3, s + 5) == s + 5);
    CHECK(lex_tok_is(s + 3, s + 5, "ke"));
}

TEST(name_comment_starts_at_a_free_standing_hash)
{
    static const struct {
        const char *s;
        int at; /* -1: no comment (end) */
    } cases[] = {
        {"tex#1.png", -1},  {"tex#1.png # note", 10}, {"#x", 0},       {"a #b", 2},
        {"a\t#b", 2},       {"a#b#c", -1},            {"", -1},        {"a# #", 3},
        {"my file.png#", -1},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        const char *s = cases[i].s, *end = s + strlen(s);
        long got = (long)(lex_comment_start(s, end) - s);
        long want = cases[i].at < 0 ? (long)(end - s) : cases[i].at;
        if (got != want)
            test_fail(t, __FILE__, __LINE__, "\"%s\": comment at %ld, want %ld", s, got, want);
    }
    const char *s = "ab #c";
    CHECK(lex_comment_start(s, s + 3) == s + 3); /* a '#' past end does not count */
}

/* ---- numbers ---- */

TEST(number_edge_cases)
{
    static const struct {
        const char *s;
        int rc;
        float want;
    } cases[] = {
        {"0", LEX_NUM_OK, 0},          {"-0", LEX_NUM_OK, -0.0f},
        {"+1", LEX_NUM_OK, 1},          {".5", LEX_NUM_OK, 0.5f},
        {"5.", LEX_NUM_OK, 5},          {"-1.25e+2", LEX_NUM_OK, -125},
        {"1E-2", LEX_NUM_OK, 0.01f},    {"1e-50", LEX_NUM_OK, 0},
        {"1e-45", LEX_NUM_OK, 1e-45f},  {"3.4028235e38", LEX_NUM_OK, 3.4028235e38f},
        {"16777217", LEX_NUM_OK, 16777216.0f}, /* a tie: round to even */
        {"16777219", LEX_NUM_OK, 16777220.0f},
        {"16777217.0000000000000000000000001", LEX_NUM_OK, 16777218.0f}, /* just above */
        {"16777217.0000000000000000000000000", LEX_NUM_OK, 16777216.0f},
        {"0.70710678118654757", LEX_NUM_OK, 0.70710678f},
        {"1e39", LEX_NUM_RANGE, 0},     {"-1e99999999999", LEX_NUM_RANGE, 0},
        {"3.5e38", LEX_NUM_RANGE, 0},   {"", LEX_NUM_SYNTAX, 0},
        {"-", LEX_NUM_SYNTAX, 0},       {".", LEX_NUM_SYNTAX, 0},
        {"e5", LEX_NUM_SYNTAX, 0},      {"1e", LEX_NUM_SYNTAX, 0},
        {"1e+", LEX_NUM_SYNTAX, 0},     {"1.2.3", LEX_NUM_SYNTAX, 0},
        {"0x10", LEX_NUM_SYNTAX, 0},    {"inf", LEX_NUM_SYNTAX, 0},
        {"nan", LEX_NUM_SYNTAX, 0},     {"1,5", LEX_NUM_SYNTAX, 0},
        {"--1", LEX_NUM_SYNTAX, 0},     {" 1", LEX_NUM_SYNTAX, 0},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        float f = 12345;
        int rc = lex_float(cases[i].s, strlen(cases[i].s), &f);
        if (rc != cases[i].rc || (rc == LEX_NUM_OK && (f != cases[i].want ||
                                                       signbit(f) != signbit(cases[i].want))))
            test_fail(t, __FILE__, __LINE__, "\"%s\": rc %d value %.9g, want rc %d value %.9g",
                      cases[i].s, rc, f, cases[i].rc, cases[i].want);
    }
    /* the token is bounded by n, not by a NUL */
    float f;
    CHECK_EQ_INT(lex_float("12x", 2, &f), LEX_NUM_OK);
    CHECK_NEAR(f, 12, 0);
}

static char random_digit(uint64_t *state)
{
    *state = *state * 6364136223846793005ULL + 1442695040888963407ULL; /* Knuth's MMIX LCG */
    return (char)('0' + (*state >> 60) % 10);
}

TEST(number_parser_matches_strtof)
{
    /* Random decimal strings of every shape exporters write (and some they do not): the
     * result must be bit-identical to glibc's correctly rounded strtof (C locale). */
    uint64_t x = 0x9e3779b97f4a7c15ULL;
    int mismatches = 0;
    for (int i = 0; i < 300000; i++) {
        char s[64];
        size_t n = 0;
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        uint64_t r = x;
        if (r & 1)
            s[n++] = '-';
        int int_digits = (int)((r >> 1) % 12), frac_digits = (int)((r >> 5) % 22);
        if (int_digits + frac_digits == 0)
            int_digits = 1;
        uint64_t d = x * 0x2545f4914f6cdd1dULL;
        for (int k = 0; k < int_digits; k++)
            s[n++] = random_digit(&d);
        if (frac_digits || (r >> 10) & 1) {
            s[n++] = '.';
            for (int k = 0; k < frac_digits; k++)
                s[n++] = random_digit(&d);
        }
        if ((r >> 11) % 3 == 0)
            n += (size_t)snprintf(s + n, sizeof s - n, "e%d", (int)((r >> 16) % 90) - 50);
        s[n] = '\0';
        float got, want = strtof(s, NULL);
        int rc = lex_float(s, n, &got);
        bool same = isinf(want) ? rc == LEX_NUM_RANGE
                                : rc == LEX_NUM_OK && memcmp(&got, &want, sizeof got) == 0;
        if (!same && mismatches++ < 10)
            test_fail(t, __FILE__, __LINE__, "\"%s\": got %.9g (rc %d), strtof %.9g", s, got, rc,
                      want);
    }
    CHECK_EQ_INT(mismatches, 0);
}

TEST(number_ties_and_neighbours_match_strtof)
{
    /* exact float midpoints and their 1e-25 neighbours: the double-rounding trap */
    int mismatches = 0;
    /* in [2^24, 2^25) the floats are the even integers, so odd ones are exact ties */
    for (uint32_t k = 0; k < 2000; k++) {
        for (int shift = -30; shift <= 30; shift += 3) {
            double mid = ldexp((double)((1u << 24) + 2 * k + 1), shift);
            for (int v = 0; v < 3; v++) {
                char s[160];
                snprintf(s, sizeof s, "%.40g", mid); /* exact: no exponent at these scales */
                if (v > 0) {
                    if (!strchr(s, '.'))
                        strcat(s, ".");
                    strcat(s, v == 1 ? "0000000000000000000000001" /* a hair above */
                                     : "0000000000000000000000000");
                }
                float got, want = strtof(s, NULL);
                if (lex_float(s, strlen(s), &got) != LEX_NUM_OK ||
                    memcmp(&got, &want, sizeof got) != 0) {
                    if (mismatches++ < 10)
                        test_fail(t, __FILE__, __LINE__, "\"%s\": got %.9g, strtof %.9g", s,
                                  got, want);
                }
            }
        }
    }
    CHECK_EQ_INT(mismatches, 0);
}
