/* sandbox.c: a job in a child process with limits (see sandbox.h). */
#include "sandbox.h"

#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include "timing.h"

#if defined(__SANITIZE_ADDRESS__)
#define SANDBOX_UNDER_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define SANDBOX_UNDER_ASAN 1
#endif
#endif

/* the child's exit status when an allocation of its reply failed */
#define SANDBOX_EXIT_NO_MEMORY 4

void sandbox_put(struct sandbox_blob *b, const void *p, size_t n)
{
    if (b->failed || n == 0)
        return;
    if (n > b->cap - b->n) {
        size_t cap = b->cap ? b->cap : 1 << 16;
        while (cap - b->n < n) {
            if (cap > SANDBOX_MAX_REPLY) {
                b->failed = true;
                return;
            }
            cap *= 2;
        }
        uint8_t *np = realloc(b->p, cap);
        if (!np) {
            b->failed = true;
            return;
        }
        b->p = np;
        b->cap = cap;
    }
    memcpy(b->p + b->n, p, n);
    b->n += n;
}

void sandbox_put_u32(struct sandbox_blob *b, uint32_t v)
{
    sandbox_put(b, &v, sizeof v);
}

static void child(sandbox_job job, void *arg, int fd)
{
    int null = open("/dev/null", O_RDWR);
    if (null >= 0) {
        dup2(null, 0);
        dup2(null, 1);
        dup2(null, 2);
    }
    struct rlimit cpu = {SANDBOX_MAX_SECONDS, SANDBOX_MAX_SECONDS + 1};
    setrlimit(RLIMIT_CPU, &cpu);
#ifndef SANDBOX_UNDER_ASAN /* ASan reserves terabytes of address space: no RLIMIT_AS there */
    struct rlimit as = {SANDBOX_MAX_MEMORY, SANDBOX_MAX_MEMORY};
    setrlimit(RLIMIT_AS, &as);
#endif
    struct sandbox_blob r = {0};
    char msg[220] = "";
    uint8_t status = 0;
    if (job(arg, &r, msg) != 0) {
        status = 1;
        r.n = 0;
        r.failed = false;
        msg[sizeof msg - 1] = '\0';
        sandbox_put(&r, msg, strlen(msg));
    }
    if (r.failed)
        _exit(SANDBOX_EXIT_NO_MEMORY);
    if (write(fd, &status, 1) != 1)
        _exit(3);
    for (size_t off = 0; off < r.n;) {
        ssize_t w = write(fd, r.p + off, r.n - off);
        if (w < 0 && errno == EINTR)
            continue;
        if (w <= 0)
            _exit(3);
        off += (size_t)w;
    }
    _exit(0);
}

static void (*before_fork)(void *);
static void *before_fork_arg;

void sandbox_before_fork(void (*fn)(void *), void *arg)
{
    before_fork = fn;
    before_fork_arg = arg;
}

int sandbox_run(sandbox_job job, void *arg, const char *where, const char *who,
                uint8_t **reply_out, size_t *n_out, struct err *e)
{
    *reply_out = NULL;
    *n_out = 0;
    int fds[2];
    if (pipe(fds) != 0)
        return err_set(e, "%s: cannot start the %s: %s", where, who, strerror(errno));
    fflush(NULL);
    if (before_fork)
        before_fork(before_fork_arg);
    pid_t pid = fork();
    if (pid < 0) {
        close(fds[0]);
        close(fds[1]);
        return err_set(e, "%s: cannot start the %s: %s", where, who, strerror(errno));
    }
    if (pid == 0) {
        close(fds[0]);
        child(job, arg, fds[1]);
    }
    close(fds[1]);
    struct sandbox_blob in = {0};
    uint8_t *buf = malloc(1 << 16);
    double deadline = timing_now_s() + SANDBOX_MAX_SECONDS + 5;
    bool timed_out = false;
    while (buf) {
        double left = deadline - timing_now_s();
        if (left <= 0) {
            timed_out = true;
            break;
        }
        struct pollfd pf = {fds[0], POLLIN, 0};
        int pr = poll(&pf, 1, (int)(left * 1000) + 1);
        if (pr <= 0)
            continue; /* (EINTR, or the deadline: looked at above) */
        ssize_t got = read(fds[0], buf, 1 << 16);
        if (got < 0 && errno == EINTR)
            continue;
        if (got <= 0)
            break;
        sandbox_put(&in, buf, (size_t)got);
        if (in.failed)
            break;
    }
    close(fds[0]);
    if (timed_out || in.failed || !buf)
        kill(pid, SIGKILL);
    int status = 0;
    while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    int rc = -1;
    if (!buf) {
        err_set(e, "%s: out of memory", where);
    } else if (timed_out) {
        err_set(e, "%s: the %s took longer than %d s; stopped", where, who,
                SANDBOX_MAX_SECONDS + 5);
    } else if (in.failed) {
        err_set(e, "%s: the %s's result is too large for this machine's memory", where, who);
    } else if (WIFSIGNALED(status)) {
        int sig = WTERMSIG(status);
        if (sig == SIGXCPU)
            err_set(e, "%s: the %s used its %d s of CPU time; stopped", where, who,
                    SANDBOX_MAX_SECONDS);
        else
            err_set(e, "%s: the %s crashed on this file (killed by signal %d)", where, who,
                    sig);
    } else if (WIFEXITED(status) && WEXITSTATUS(status) == SANDBOX_EXIT_NO_MEMORY) {
        err_set(e, "%s: the %s ran out of memory (%zu MiB) on this file", where, who,
                SANDBOX_MAX_MEMORY >> 20);
    } else if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || in.n < 1) {
        /* a C++ library dies by std::terminate (SIGABRT above) or exit: no reply */
        err_set(e, "%s: the %s stopped without a result (exit status %d): the file is "
                   "likely too large for %zu MiB, or broken",
                where, who, WIFEXITED(status) ? WEXITSTATUS(status) : -1,
                SANDBOX_MAX_MEMORY >> 20);
    } else if (in.p[0] != 0) {
        char msg[220];
        err_quote((const char *)in.p + 1, in.n - 1, 200, msg, sizeof msg);
        err_set(e, "%s: %s", where, msg);
    } else {
        memmove(in.p, in.p + 1, in.n - 1);
        *reply_out = in.p;
        *n_out = in.n - 1;
        in.p = NULL;
        rc = 0;
    }
    free(buf);
    free(in.p);
    return rc;
}
