/* test_workers.c: the thread pool — every thread runs a job once, and workers_for covers a
 * range exactly once, in chunks, whatever the pool's size (the back end's, the vertex stage's
 * and the sky's work is split this way, so a gap or an overlap would be a wrong picture). */
#include <stdatomic.h>
#include <stdlib.h>

#include "test.h"
#include "workers.h"

struct cover {
    atomic_int *hits;
    size_t chunk;
    atomic_int calls, bad; /* bad: empty ranges */
};

static void count_range(void *arg, size_t i0, size_t i1)
{
    struct cover *c = arg;
    atomic_fetch_add(&c->calls, 1);
    if (i1 <= i0)
        atomic_fetch_add(&c->bad, 1);
    for (size_t i = i0; i < i1; i++)
        atomic_fetch_add(&c->hits[i], 1);
}

TEST(workers_for_covers_a_range_exactly_once)
{
    const int pools[] = {0, 1, 3};
    const size_t ns[] = {0, 1, 6, 7, 14, 15, 1000};
    for (int pi = 0; pi < 3; pi++) {
        struct workers *w = workers_new(pools[pi], NULL);
        REQUIRE(w != NULL);
        CHECK_EQ_INT(workers_count(w), pools[pi]);
        for (size_t ni = 0; ni < sizeof ns / sizeof *ns; ni++) {
            size_t n = ns[ni];
            struct cover c = {.hits = calloc(n + 1, sizeof *c.hits), .chunk = 7};
            REQUIRE(c.hits != NULL);
            atomic_init(&c.calls, 0);
            atomic_init(&c.bad, 0);
            workers_for(w, n, c.chunk, count_range, &c);
            int once = 0;
            for (size_t i = 0; i < n; i++)
                once += atomic_load(&c.hits[i]) == 1;
            CHECK_EQ_INT(once, (int)n);
            CHECK_EQ_INT(atomic_load(&c.bad), 0);
            /* one call when there is too little to share (or no one to share with), else
             * one call a chunk */
            int calls = n == 0 ? 0 : pools[pi] == 0 || n < 2 * c.chunk ? 1
                                                                       : (int)((n + 6) / 7);
            CHECK_EQ_INT(atomic_load(&c.calls), calls);
            free(c.hits);
        }
        workers_destroy(w);
    }
}

static void mark_thread(void *arg, int k)
{
    atomic_fetch_add(&((atomic_int *)arg)[k], 1);
}

TEST(workers_run_calls_each_thread_once_per_job)
{
    struct workers *w = workers_new(3, NULL);
    REQUIRE(w != NULL);
    atomic_int seen[4];
    for (int k = 0; k < 4; k++)
        atomic_init(&seen[k], 0);
    for (int job = 0; job < 50; job++)
        workers_run(w, mark_thread, seen);
    for (int k = 0; k < 4; k++)
        CHECK_EQ_INT(atomic_load(&seen[k]), 50);
    workers_destroy(w);
}
