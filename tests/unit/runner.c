/* runner.c: runs every registered TEST and prints one summary line.
 *   unit-tests [--times] [FILTER]   only tests whose name contains FILTER; --times adds each
 *                                    test's wall time (ms) to its line and lists the slowest */
#include <stdarg.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#include "test.h"

#define MAX_TESTS 1024

struct entry {
    const char *name, *file;
    test_fn fn;
    int order;
    double ms;
};
static struct entry tests[MAX_TESTS];
static int n_tests;

void test_register(const char *name, const char *file, test_fn fn)
{
    if (n_tests < MAX_TESTS) {
        tests[n_tests] = (struct entry){name, file, fn, n_tests, 0};
        n_tests++;
    }
}

void test_fail(struct test *t, const char *file, int line, const char *fmt, ...)
{
    va_list ap;
    fprintf(stderr, "    %s:%d: ", file, line);
    va_start(ap, fmt);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fputc('\n', stderr);
    t->failures++;
}

void test_skip(struct test *t, const char *reason)
{
    fprintf(stderr, "    skipped: %s\n", reason);
    t->skipped = 1;
}

const char *test_models_dir(void)
{
    static char path[4096];
    const char *shared = getenv("RASTTY_SHARED");
    struct stat st;
    snprintf(path, sizeof path, "%s/models", shared && *shared ? shared : "../shared");
    return stat(path, &st) == 0 && S_ISDIR(st.st_mode) ? path : NULL;
}

static int by_file_then_order(const void *a, const void *b)
{
    const struct entry *x = a, *y = b;
    int c = strcmp(x->file, y->file);
    return c ? c : x->order - y->order;
}

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec / 1e6;
}

static int by_time(const void *a, const void *b)
{
    const struct entry *x = *(const struct entry *const *)a, *y = *(const struct entry *const *)b;
    return (x->ms < y->ms) - (x->ms > y->ms);
}

int main(int argc, char **argv)
{
    int passed = 0, failed = 0, skipped = 0;
    bool times = argc > 1 && strcmp(argv[1], "--times") == 0;
    const char *filter = argc > 1 + times ? argv[1 + times] : NULL;
    qsort(tests, (size_t)n_tests, sizeof tests[0], by_file_then_order);
    double total = 0;
    static struct entry *ran[MAX_TESTS];
    int n_ran = 0;
    for (int i = 0; i < n_tests; i++) {
        if (filter && !strstr(tests[i].name, filter))
            continue;
        struct test t = {tests[i].name, 0, 0};
        double t0 = now_ms();
        tests[i].fn(&t);
        tests[i].ms = now_ms() - t0;
        total += tests[i].ms;
        ran[n_ran++] = &tests[i];
        const char *verdict = t.failures ? "FAIL" : t.skipped ? "skip" : "ok  ";
        if (times)
            printf("%s %s (%s) %.1f ms\n", verdict, tests[i].name, tests[i].file, tests[i].ms);
        else
            printf("%s %s (%s)\n", verdict, tests[i].name, tests[i].file);
        fflush(stdout);
        if (t.failures)
            failed++;
        else if (t.skipped)
            skipped++;
        else
            passed++;
    }
    if (times) {
        qsort(ran, (size_t)n_ran, sizeof ran[0], by_time);
        printf("slowest of %.0f ms:\n", total);
        for (int i = 0; i < n_ran && i < 10; i++)
            printf("  %8.1f ms %4.1f %%  %s (%s)\n", ran[i]->ms,
                   total > 0 ? 100 * ran[i]->ms / total : 0, ran[i]->name, ran[i]->file);
    }
    printf("%d passed, %d failed, %d skipped\n", passed, failed, skipped);
    return failed ? 1 : 0;
}
