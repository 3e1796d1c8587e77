/* workers.h: a small pool of threads that run one job at a time, together with the caller.
 *
 * workers_run(pool, fn, arg) calls fn(arg, k) once on each of the pool's threads (k = 1..n)
 * and once on the calling thread (k = 0), and returns when all calls have returned. The
 * job divides its own work (the back end hands out screen tiles through an atomic counter),
 * so results never depend on which thread did what. Threads sleep between jobs. A pool of
 * zero threads is valid: the caller does everything. Not reentrant: one job at a time.
 *
 * workers_start + workers_wait split workers_run for the caller that has other work
 * meanwhile (the pipeline sets up the next batch of triangles while the pool draws this
 * one): start calls fn(arg, k) on the pool's threads only and returns at once; the caller
 * may join with fn(arg, 0) whenever it likes; wait returns when the pool's calls have
 * returned. Nothing else may be given to the pool between the two. */
#ifndef RASTTY_WORKERS_H
#define RASTTY_WORKERS_H

#include <stddef.h>

#include "err.h"

struct workers;

typedef void (*workers_fn)(void *arg, int k);

/* n extra threads (0 .. WORKERS_MAX); NULL and e set on failure */
struct workers *workers_new(int n, struct err *e);
void workers_destroy(struct workers *w);
int workers_count(const struct workers *w); /* extra threads, 0 for NULL */
void workers_run(struct workers *w, workers_fn fn, void *arg);
void workers_start(struct workers *w, workers_fn fn, void *arg);
void workers_wait(struct workers *w);

/* workers_for(pool, n, chunk, fn, arg) calls fn(arg, i0, i1) on ranges [i0, i1) that cover
 * 0 .. n-1 exactly once, chunk items each (the last may be shorter), handed out to every
 * thread through a shared counter; on the calling thread alone, in one call, when the pool
 * is empty or n < 2 * chunk (too little work to share). */
typedef void (*workers_range_fn)(void *arg, size_t i0, size_t i1);
void workers_for(struct workers *w, size_t n, size_t chunk, workers_range_fn fn, void *arg);

#define WORKERS_MAX 63

/* The number of online cores (1 .. WORKERS_MAX + 1): the default thread count. */
int workers_cores(void);

/* fn(arg) on a thread of its own with a stack of WORKERS_CALL_STACK bytes and no signals,
 * waited for; on the calling thread when no thread can be made. For library calls that need
 * more stack than a small `ulimit -s` gives the main thread (libtinfo reads a terminfo entry
 * into a 32 KiB buffer on its stack: the viewer died of SIGSEGV under ulimit -s 64). */
#define WORKERS_CALL_STACK ((size_t)1 << 20)
void workers_call(void (*fn)(void *arg), void *arg);

#endif
