/* test.h: the unit-test harness (no dependencies).
 *
 *   TEST(shared_edge_drawn_once) { CHECK(x == 1); CHECK_EQ_INT(a, b); ... }
 *
 * Each TEST registers itself; tests/unit/runner.c runs them all (or those whose name contains
 * argv[1]) and ends with "N passed, N failed, N skipped". CHECK records a failure and goes
 * on; REQUIRE returns from the test. test_skip() marks a test skipped with a reason. */
#ifndef RASTTY_TEST_H
#define RASTTY_TEST_H

#include <stdio.h>

struct test {
    const char *name;
    int failures;
    int skipped;
};

typedef void (*test_fn)(struct test *t);
void test_register(const char *name, const char *file, test_fn fn);
void test_fail(struct test *t, const char *file, int line, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));
void test_skip(struct test *t, const char *reason);
/* Path to ../shared/models (env RASTTY_SHARED overrides ../shared), or NULL if absent. */
const char *test_models_dir(void);

#define TEST(name)                                                                         \
    static void name(struct test *t);                                                      \
    __attribute__((constructor)) static void reg_##name(void)                              \
    {                                                                                      \
        test_register(#name, __FILE__, name);                                              \
    }                                                                                      \
    static void name(struct test *t)

#define CHECK(c)                                                                           \
    do {                                                                                   \
        if (!(c))                                                                          \
            test_fail(t, __FILE__, __LINE__, "%s", #c);                                    \
    } while (0)
#define REQUIRE(c)                                                                         \
    do {                                                                                   \
        if (!(c)) {                                                                        \
            test_fail(t, __FILE__, __LINE__, "%s", #c);                                    \
            return;                                                                        \
        }                                                                                  \
    } while (0)
#define CHECK_EQ_INT(a, b)                                                                 \
    do {                                                                                   \
        long long a_ = (long long)(a), b_ = (long long)(b);                                \
        if (a_ != b_)                                                                      \
            test_fail(t, __FILE__, __LINE__, "%s == %s: %lld != %lld", #a, #b, a_, b_);    \
    } while (0)
#define CHECK_NEAR(a, b, tol)                                                              \
    do {                                                                                   \
        double a_ = (double)(a), b_ = (double)(b);                                         \
        if (!(a_ - b_ <= (tol) && b_ - a_ <= (tol)))                                       \
            test_fail(t, __FILE__, __LINE__, "%s ~ %s: %.9g vs %.9g (tol %g)", #a, #b, a_, \
                      b_, (double)(tol));                                                  \
    } while (0)
#define CHECK_STR_CONTAINS(hay, needle)                                                    \
    do {                                                                                   \
        const char *h_ = (hay), *n_ = (needle);                                            \
        if (!h_ || !strstr(h_, n_))                                                        \
            test_fail(t, __FILE__, __LINE__, "\"%s\" does not contain \"%s\"",             \
                      h_ ? h_ : "(null)", n_);                                             \
    } while (0)

#endif
