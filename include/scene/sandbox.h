/* sandbox.h: running a large C++ library on untrusted bytes (assimp, Draco) in a child
 * process, with limits, so that its crash, hang or allocation storm is one error line.
 *
 * The child: stdin, stdout and stderr on /dev/null (it may not write to the terminal), at
 * most SANDBOX_MAX_SECONDS of CPU and SANDBOX_MAX_MEMORY of address space (not under
 * AddressSanitizer, which reserves terabytes), then the job, whose result goes back
 * through a pipe as one reply. The parent waits at most SANDBOX_MAX_SECONDS + 5 of wall
 * time, reading into the heap (never a large stack buffer: rastty runs under `ulimit -s
 * 64`), and reports what happened in words: the job's own message, "killed by signal 11",
 * "CPU time limit", "took longer than 60 s", "ran out of memory" (the child's allocation
 * failed, or it died without a reply). */
#ifndef RASTTY_SANDBOX_H
#define RASTTY_SANDBOX_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "err.h"

#define SANDBOX_MAX_SECONDS 60
#define SANDBOX_MAX_MEMORY ((size_t)2 << 30)
#define SANDBOX_MAX_REPLY ((size_t)3 << 30)

/* A growing byte array (the reply). Appending zero bytes (from NULL or not) is nothing;
 * once an append fails (out of memory, past SANDBOX_MAX_REPLY) `failed` stays set. */
struct sandbox_blob {
    uint8_t *p;
    size_t n, cap;
    bool failed;
};
void sandbox_put(struct sandbox_blob *b, const void *p, size_t n);
void sandbox_put_u32(struct sandbox_blob *b, uint32_t v);

/* The job, in the child: fill `reply` and return 0, or return -1 with msg (a NUL-terminated
 * text of at most 219 bytes, what went wrong: it is quoted, never printed raw). */
typedef int (*sandbox_job)(void *arg, struct sandbox_blob *reply, char msg[220]);

/* Run job(arg) in a child. 0 with the reply (malloc'd, *reply_out, *n_out), or -1 with e =
 * "where: why" (who: "importer", "Draco decoder": what the messages call the job). */
int sandbox_run(sandbox_job job, void *arg, const char *where, const char *who,
                uint8_t **reply_out, size_t *n_out, struct err *e);

/* Before each fork, sandbox_run calls fn(arg) (NULL: nothing), on its own thread. The child
 * starts with one thread and every lock as the parent's threads held it at fork(): a lock
 * another thread held then — in its allocator, or its exit's clean-up (not glibc's malloc,
 * which fork keeps whole, but AddressSanitizer's) — is never released in the child, and the
 * job waits on it for ever. A program that runs a thread beside a load (the viewer's sky
 * made while the models load) ends it there. */
void sandbox_before_fork(void (*fn)(void *), void *arg);

#endif
