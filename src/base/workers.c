/* workers.c: the thread pool (see workers.h). */
#include "workers.h"

#include <pthread.h>
#include <signal.h>
#include <stdatomic.h>
#include <stdbool.h>
#include <stdlib.h>
#include <unistd.h>

#include "timing.h"

struct workers {
    int n;
    pthread_t *th;
    pthread_mutex_t mu;
    pthread_cond_t go, done;
    atomic_ulong gen; /* job number: a change starts the threads on the job */
    atomic_int busy;  /* threads still inside the current job */
    atomic_int quit;
    workers_fn fn;    /* the job: written before gen changes, read after */
    void *arg;
};

struct start {
    struct workers *w;
    int k;
};

/* A frame is several short jobs in a row (clear, vertices, tiles, sky), a fraction of a
 * millisecond each: a thread that went to sleep after one job takes tens of microseconds to
 * be woken for the next, and the caller does that share alone meanwhile. So both sides
 * first spin on the atomic for up to SPIN_US, then sleep on the condition variable. */
#define SPIN_US 200

static inline void cpu_relax(void)
{
#if defined(__x86_64__) || defined(__i386__)
    __builtin_ia32_pause();
#endif
}

/* spin until cond(w) holds or SPIN_US pass; whether it holds */
static bool spin_until(struct workers *w, bool (*cond)(struct workers *, unsigned long),
                       unsigned long v)
{
    double t0 = 0;
    for (unsigned i = 0;; i++) {
        if (cond(w, v))
            return true;
        if ((i & 255) == 255) {
            double t = timing_now_ms();
            if (t0 == 0)
                t0 = t;
            else if (t - t0 > SPIN_US * 1e-3)
                return false;
        }
        cpu_relax();
    }
}

static bool new_job(struct workers *w, unsigned long seen)
{
    return atomic_load_explicit(&w->gen, memory_order_acquire) != seen ||
           atomic_load_explicit(&w->quit, memory_order_relaxed);
}

static bool all_done(struct workers *w, unsigned long unused)
{
    (void)unused;
    return atomic_load_explicit(&w->busy, memory_order_acquire) == 0;
}

static void *thread_main(void *p)
{
    struct start *s = p;
    struct workers *w = s->w;
    int k = s->k;
    free(s);
    unsigned long seen = 0;
    for (;;) {
        if (!spin_until(w, new_job, seen)) {
            pthread_mutex_lock(&w->mu);
            while (!new_job(w, seen))
                pthread_cond_wait(&w->go, &w->mu);
            pthread_mutex_unlock(&w->mu);
        }
        if (atomic_load_explicit(&w->quit, memory_order_relaxed))
            break;
        seen = atomic_load_explicit(&w->gen, memory_order_acquire);
        w->fn(w->arg, k);
        if (atomic_fetch_sub_explicit(&w->busy, 1, memory_order_acq_rel) == 1) {
            /* the last one: wake the caller if it went to sleep (it checks busy under the
             * lock, so taking the lock here means it is either waiting or will see 0) */
            pthread_mutex_lock(&w->mu);
            pthread_cond_signal(&w->done);
            pthread_mutex_unlock(&w->mu);
        }
    }
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
    atomic_init(&w->gen, 0);
    atomic_init(&w->busy, 0);
    atomic_init(&w->quit, 0);
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
    atomic_store(&w->quit, 1);
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

void workers_start(struct workers *w, workers_fn fn, void *arg)
{
    if (!w || w->n == 0)
        return;
    w->fn = fn;
    w->arg = arg;
    atomic_store_explicit(&w->busy, w->n, memory_order_relaxed);
    pthread_mutex_lock(&w->mu); /* sleeping threads check gen under the lock */
    atomic_fetch_add_explicit(&w->gen, 1, memory_order_release);
    pthread_cond_broadcast(&w->go);
    pthread_mutex_unlock(&w->mu);
}

void workers_wait(struct workers *w)
{
    if (!w || w->n == 0)
        return;
    if (!spin_until(w, all_done, 0)) {
        pthread_mutex_lock(&w->mu);
        while (!all_done(w, 0))
            pthread_cond_wait(&w->done, &w->mu);
        pthread_mutex_unlock(&w->mu);
    }
}

void workers_run(struct workers *w, workers_fn fn, void *arg)
{
    workers_start(w, fn, arg);
    fn(arg, 0);
    workers_wait(w);
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

struct call {
    void (*fn)(void *);
    void *arg;
};

static void *call_main(void *p)
{
    struct call *c = p;
    c->fn(c->arg);
    return NULL;
}

void workers_call(void (*fn)(void *arg), void *arg)
{
    struct call c = {fn, arg};
    pthread_attr_t a;
    pthread_t th;
    bool started = false;
    if (pthread_attr_init(&a) == 0) {
        /* the thread takes no signals: the terminal's handlers belong to the main thread */
        sigset_t all, old;
        sigfillset(&all);
        pthread_sigmask(SIG_SETMASK, &all, &old);
        started = pthread_attr_setstacksize(&a, WORKERS_CALL_STACK) == 0 &&
                  pthread_create(&th, &a, call_main, &c) == 0;
        pthread_sigmask(SIG_SETMASK, &old, NULL);
        pthread_attr_destroy(&a);
    }
    if (started)
        pthread_join(th, NULL);
    else
        fn(arg);
}
