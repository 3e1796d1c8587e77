/* lex.c: the decimal number parser and the comment rule for names (see lex.h). */
#include "lex.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

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

int lex_float(const char *s, size_t n, float *out)
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
        return LEX_NUM_SYNTAX;
    if (i < n && (s[i] == 'e' || s[i] == 'E')) {
        bool eneg = false;
        long ev = 0;
        i++;
        if (i < n && (s[i] == '+' || s[i] == '-'))
            eneg = s[i++] == '-';
        if (i >= n || !is_digit(s[i]))
            return LEX_NUM_SYNTAX;
        for (; i < n && is_digit(s[i]); i++)
            if (ev < 100000) /* saturate: the result is 0 or inf long before */
                ev = ev * 10 + (s[i] - '0');
        e10 += eneg ? -ev : ev;
    }
    if (i != n)
        return LEX_NUM_SYNTAX;

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
        return LEX_NUM_RANGE;
    *out = neg ? -f : f;
    return LEX_NUM_OK;
}

const char *lex_comment_start(const char *p, const char *end)
{
    for (const char *q = p; q < end; q++) {
        q = memchr(q, '#', (size_t)(end - q));
        if (!q)
            break;
        if (q == p || lex_is_ws(q[-1]))
            return q;
    }
    return end;
}
