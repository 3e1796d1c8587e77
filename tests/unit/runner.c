/* runner.c: runs every registered TEST and prints one summary line. */
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "test.h"

#define MAX_TESTS 1024

struct entry {
    const char *name, *file;
    test_fn fn;
    int order;
};
static struct entry tests[MAX_TESTS];
static int n_tests;

void test_register(const char *name, const char *file, test_fn fn)
{
    if (n_tests < MAX_TESTS) {
        tests[n_tests] = (struct entry){name, file, fn, n_tests};
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

int main(int argc, char **argv)
{
    int passed = 0, failed = 0, skipped = 0;
    qsort(tests, (size_t)n_tests, sizeof tests[0], by_file_then_order);
    for (int i = 0; i < n_tests; i++) {
        if (argc > 1 && !strstr(tests[i].name, argv[1]))
            continue;
        struct test t = {tests[i].name, 0, 0};
        tests[i].fn(&t);
        const char *verdict = t.failures ? "FAIL" : t.skipped ? "skip" : "ok  ";
        printf("%s %s (%s)\n", verdict, tests[i].name, tests[i].file);
        fflush(stdout);
        if (t.failures)
            failed++;
        else if (t.skipped)
            skipped++;
        else
            passed++;
    }
    printf("%d passed, %d failed, %d skipped\n", passed, failed, skipped);
    return failed ? 1 : 0;
}
