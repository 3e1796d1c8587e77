/* workers.c: the thread pool (see workers.h). */
#include "workers.h"

#include <pthread.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <unistd.h>

struct workers {
    int n;
    pthread_t *th;
    pthread_mutex_t mu;
    pthread_cond_t go, done;
    unsigned long gen; /* job number: a change wakes the threads */
    int busy;          /* threads still inside the current job */
    int quit;
    workers_fn fn;
    void *arg;
};

struct start {
    struct workers *w;
    int k;
};

static void *thread_main(void *p)
{
    struct start *s = p;
    struct workers *w = s->w;
    int k = s->k;
    free(s);
    unsigned long seen = 0;
    pthread_mutex_lock(&w->mu);
    for (;;) {
        while (w->gen == seen && !w->quit)
            pthread_cond_wait(&w->go, &w->mu);
        if (w->quit)
            break;
        seen = w->gen;
        workers_fn fn = w->fn;
        void *arg = w->arg;
        pthread_mutex_unlock(&w->mu);
        fn(arg, k);
        pthread_mutex_lock(&w->mu);
        if (--w->busy == 0)
            pthread_cond_signal(&w->done);
    }
    pthread_mutex_unlock(&w->mu);
    return NULL;
}

struct workers *workers_new(int n, struct err *e)
{
    if (n < 0 || n > WORKERS_MAX)
        return err_set(e, "thread count %d out of range", n + 1), NULL;
    struct workers *w = calloc(1, sizeof *w);
    if (!w || (n && !(w->th = calloc((size_t)n, sizeof *w->th)))) {
        free(w);
        return err_set(e, "out of memory for %d threads", n), NULL;
    }
    pthread_mutex_init(&w->mu, NULL);
    pthread_cond_init(&w->go, NULL);
    pthread_cond_init(&w->done, NULL);
    for (int i = 0; i < n; i++) {
        struct start *s = malloc(sizeof *s);
        if (!s || (s->w = w, s->k = i + 1, pthread_create(&w->th[i], NULL, thread_main, s))) {
            free(s);
            w->n = i; /* the ones that started are joined */
            workers_destroy(w);
            return err_set(e, "cannot start thread %d of %d", i + 2, n + 1), NULL;
        }
    }
    w->n = n;
    return w;
}

void workers_destroy(struct workers *w)
{
    if (!w)
        return;
    pthread_mutex_lock(&w->mu);
    w->quit = 1;
    pthread_cond_broadcast(&w->go);
    pthread_mutex_unlock(&w->mu);
    for (int i = 0; i < w->n; i++)
        pthread_join(w->th[i], NULL);
    pthread_mutex_destroy(&w->mu);
    pthread_cond_destroy(&w->go);
    pthread_cond_destroy(&w->done);
    free(w->th);
    free(w);
}

int workers_count(const struct workers *w)
{
    return w ? w->n : 0;
}

void workers_run(struct workers *w, workers_fn fn, void *arg)
{
    if (!w || w->n == 0) {
        fn(arg, 0);
        return;
    }
    pthread_mutex_lock(&w->mu);
    w->fn = fn;
    w->arg = arg;
    w->busy = w->n;
    w->gen++;
    pthread_cond_broadcast(&w->go);
    pthread_mutex_unlock(&w->mu);
    fn(arg, 0);
    pthread_mutex_lock(&w->mu);
    while (w->busy > 0)
        pthread_cond_wait(&w->done, &w->mu);
    pthread_mutex_unlock(&w->mu);
}

int workers_cores(void)
{
    long n = sysconf(_SC_NPROCESSORS_ONLN);
    return n < 1 ? 1 : n > WORKERS_MAX + 1 ? WORKERS_MAX + 1 : (int)n;
}

struct range_job {
    size_t n, chunk;
    workers_range_fn fn;
    void *arg;
    atomic_size_t next; /* the next chunk to hand out */
};

static void range_chunks(void *arg, int k)
{
    struct range_job *j = arg;
    (void)k;
    for (;;) {
        size_t i0 = atomic_fetch_add_explicit(&j->next, 1, memory_order_relaxed) * j->chunk;
        if (i0 >= j->n)
            return;
        j->fn(j->arg, i0, j->n - i0 > j->chunk ? i0 + j->chunk : j->n);
    }
}

void workers_for(struct workers *w, size_t n, size_t chunk, workers_range_fn fn, void *arg)
{
    if (!w || w->n == 0 || n < 2 * chunk) {
        if (n > 0)
            fn(arg, 0, n);
        return;
    }
    struct range_job j = {.n = n, .chunk = chunk, .fn = fn, .arg = arg};
    atomic_init(&j.next, 0);
    workers_run(w, range_chunks, &j);
}
