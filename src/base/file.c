/* file.c: regular-file reads with size limits, atomic writes (see file.h). */
#include "file.h"

#include <errno.h>
#include <limits.h>
#include <signal.h>
#include <stdbool.h>
#include <stdio.h>
#include <fcntl.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "mem.h"

const char *file_quote(const char *path, char *buf, size_t size)
{
    return err_quote(path, strlen(path), 160, buf, size);
}

int file_inside_dir_of(const char *of, const char *path)
{
    const char *slash = strrchr(of, '/');
    size_t dl = slash ? (size_t)(slash - of) : 0;
    char *dir = malloc(dl + 2);
    if (!dir)
        return ENOMEM;
    if (slash == of)
        strcpy(dir, "/");
    else if (dl)
        memcpy(dir, of, dl), dir[dl] = '\0';
    else
        strcpy(dir, ".");
    char *rd = realpath(dir, NULL);
    int err = errno;
    free(dir);
    if (!rd)
        return err > 1 ? err : ENOENT;
    char *rp = realpath(path, NULL);
    err = errno;
    if (!rp) {
        free(rd);
        return err > 1 ? err : ENOENT;
    }
    size_t n = strlen(rd);
    int inside = strncmp(rp, rd, n) == 0 && (rp[n] == '/' || (n == 1 && rd[0] == '/'));
    free(rd);
    free(rp);
    return inside;
}

static int kind_error(mode_t m)
{
    if (S_ISDIR(m))
        return EISDIR;
    if (S_ISFIFO(m))
        return FILE_E_FIFO;
    if (S_ISCHR(m) || S_ISBLK(m))
        return FILE_E_DEVICE;
    if (S_ISSOCK(m))
        return FILE_E_SOCKET;
    return FILE_E_OTHER;
}

/* Read fd to its end into a malloc'd, NUL-terminated buffer; size: the expected length (a
 * first allocation), max: the limit (FILE_E_TOO_BIG past it). */
static int read_all(int fd, size_t size, size_t max, char **buf_out, size_t *len_out)
{
    size_t cap = size + 2; /* the NUL, and one byte to see EOF at once */
    char *buf = mem_big(malloc(cap), cap);
    if (!buf)
        return ENOMEM;
    size_t len = 0;
    int rc = 0;
    for (;;) {
        if (len + 1 >= cap) { /* the file grew since fstat (or a pipe: it goes on) */
            if (cap - 2 >= max) {
                rc = FILE_E_TOO_BIG;
                break;
            }
            size_t ncap = cap * 2 > max + 2 ? max + 2 : cap * 2;
            char *nb = realloc(buf, ncap);
            if (!nb) {
                rc = ENOMEM;
                break;
            }
            buf = mem_big(nb, ncap);
            cap = ncap;
        }
        ssize_t got = read(fd, buf + len, cap - 1 - len);
        if (got < 0) {
            if (errno == EINTR)
                continue;
            rc = errno ? errno : EIO;
            break;
        }
        if (got == 0)
            break;
        len += (size_t)got;
    }
    if (rc == 0 && len > max)
        rc = FILE_E_TOO_BIG;
    if (rc) {
        free(buf);
        return rc;
    }
    buf[len] = '\0';
    *buf_out = buf;
    *len_out = len;
    return 0;
}

int file_read(const char *path, size_t max, char **buf_out, size_t *len_out)
{
    *buf_out = NULL;
    *len_out = 0;
    /* O_NONBLOCK: opening a FIFO for reading would otherwise wait for a writer */
    int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
    if (fd < 0)
        return errno ? errno : EIO;
    struct stat st;
    if (fstat(fd, &st) != 0) {
        int rc = errno ? errno : EIO;
        close(fd);
        return rc;
    }
    if (!S_ISREG(st.st_mode)) {
        close(fd);
        return kind_error(st.st_mode);
    }
    if (st.st_size < 0 || (unsigned long long)st.st_size > max) {
        close(fd);
        return FILE_E_TOO_BIG;
    }
    /* regular files never return EAGAIN, but switch back to blocking reads anyway */
    int fl = fcntl(fd, F_GETFL);
    if (fl >= 0)
        fcntl(fd, F_SETFL, fl & ~O_NONBLOCK);
    int rc = read_all(fd, (size_t)st.st_size, max, buf_out, len_out);
    close(fd);
    return rc;
}

int file_read_stdin(size_t max, char **buf_out, size_t *len_out)
{
    *buf_out = NULL;
    *len_out = 0;
    if (isatty(STDIN_FILENO))
        return FILE_E_TTY; /* nothing piped in: reading would wait for the user's typing */
    struct stat st;
    size_t hint = 0;
    if (fstat(STDIN_FILENO, &st) == 0 && S_ISREG(st.st_mode) && st.st_size > 0) {
        if ((unsigned long long)st.st_size > max)
            return FILE_E_TOO_BIG;
        hint = (size_t)st.st_size;
    }
    return read_all(STDIN_FILENO, hint ? hint : 65536, max, buf_out, len_out);
}

const char *file_strerror(int code)
{
    switch (code) {
    case FILE_E_FIFO: return "a FIFO, not a regular file";
    case FILE_E_DEVICE: return "a device, not a regular file";
    case FILE_E_SOCKET: return "a socket, not a regular file";
    case FILE_E_OTHER: return "not a regular file";
    case FILE_E_TOO_BIG: return "file too large";
    case FILE_E_TTY: return "standard input is a terminal, nothing was piped in (rastty - < FILE)";
    case EISDIR: return "a directory, not a file";
    default: return strerror(code);
    }
}

/* ---- atomic writes ---- */

/* Temporary files being written, for the signal handler (file_out_cleanup_on_signals): a
 * quit signal removes them before the process dies. Besides tty.c's, the only mutable
 * globals in rastty; a slot is filled before it is marked used and unmarked before it is
 * reused, so the handler sees whole names. */
#define PENDING_MAX 8
static char pending[PENDING_MAX][4096];
static volatile sig_atomic_t pending_used[PENDING_MAX];

static void pending_add(const char *tmp)
{
    size_t n = strlen(tmp);
    for (int i = 0; i < PENDING_MAX; i++)
        if (!pending_used[i] && n < sizeof pending[i]) {
            memcpy(pending[i], tmp, n + 1);
            pending_used[i] = 1;
            return;
        }
}

static void pending_remove(const char *tmp)
{
    for (int i = 0; i < PENDING_MAX; i++)
        if (pending_used[i] && strcmp(pending[i], tmp) == 0)
            pending_used[i] = 0;
}

static void on_quit_signal(int sig)
{
    for (int i = 0; i < PENDING_MAX; i++)
        if (pending_used[i])
            unlink(pending[i]); /* async-signal-safe */
    signal(sig, SIG_DFL);
    raise(sig);
}

void file_out_cleanup_on_signals(void)
{
    struct sigaction sa, old;
    memset(&sa, 0, sizeof sa);
    sigemptyset(&sa.sa_mask);
    sa.sa_handler = on_quit_signal;
    static const int sigs[] = {SIGINT, SIGTERM, SIGHUP, SIGQUIT};
    for (unsigned i = 0; i < sizeof sigs / sizeof sigs[0]; i++) /* an ignored one (nohup, a */
        if (sigaction(sigs[i], NULL, &old) == 0 && old.sa_handler != SIG_IGN) /* background */
            sigaction(sigs[i], &sa, NULL);                                 /* job) stays so */
    /* past ulimit -f a write fails with EFBIG (a message, the temporary removed) instead of
     * the signal killing the process */
    signal(SIGXFSZ, SIG_IGN);
}

/* The file a symbolic link --out names (links followed, at most 40, a missing target
 * included): writing replaces the link's target and keeps the link. NULL when path is no
 * link (or the chain is too long to follow: then the link itself is replaced). */
static char *link_target(const char *path)
{
    char cur[4096], link[4096];
    if (strlen(path) >= sizeof cur)
        return NULL;
    snprintf(cur, sizeof cur, "%s", path);
    bool followed = false;
    for (int hops = 0;; hops++) {
        struct stat st;
        if (lstat(cur, &st) != 0 || !S_ISLNK(st.st_mode))
            break;
        ssize_t n = readlink(cur, link, sizeof link - 1);
        if (hops == 40 || n <= 0)
            return NULL;
        link[n] = '\0';
        if (link[0] == '/') {
            snprintf(cur, sizeof cur, "%s", link);
        } else { /* relative to the link's folder */
            char *slash = strrchr(cur, '/');
            size_t dir = slash ? (size_t)(slash - cur) + 1 : 0;
            if (dir + (size_t)n >= sizeof cur)
                return NULL;
            memcpy(cur + dir, link, (size_t)n + 1);
        }
        followed = true;
    }
    return followed ? strdup(cur) : NULL;
}

int file_out_open(struct file_out *o, const char *path, struct err *e)
{
    memset(o, 0, sizeof *o);
    char q[FILE_QUOTE_SIZE];
    char *target = link_target(path);
    o->path = target ? target : strdup(path);
    if (!o->path)
        return err_set(e, "%s: out of memory", file_quote(path, q, sizeof q));
    const char *slash = strrchr(o->path, '/');
    size_t dir = slash ? (size_t)(slash - o->path) + 1 : 0;
    size_t n = strlen(o->path);
    o->tmp = malloc(n + 24);
    if (!o->tmp) {
        file_out_abort(o);
        return err_set(e, "%s: out of memory", file_quote(path, q, sizeof q));
    }
    /* ".NAME.XXXXXX" in the target's directory: same file system, so rename is atomic; a name
     * too long for that (NAME_MAX 255 with the 8 added bytes) gets ".rastty.XXXXXX" */
    memcpy(o->tmp, o->path, dir);
    if (n - dir + 8 <= 255)
        snprintf(o->tmp + dir, n + 24 - dir, ".%s.XXXXXX", o->path + dir);
    else
        snprintf(o->tmp + dir, n + 24 - dir, ".rastty.XXXXXX");
    struct stat st;
    bool exists = stat(o->path, &st) == 0;
    if (exists && !S_ISREG(st.st_mode)) {
        /* /dev/null, a FIFO, a terminal: write to it directly, nothing to replace */
        free(o->tmp);
        o->tmp = NULL;
        if (S_ISDIR(st.st_mode)) {
            file_out_abort(o);
            return err_set(e, "%s: cannot create: %s", file_quote(path, q, sizeof q),
                           strerror(EISDIR));
        }
        o->f = fopen(o->path, "wb");
    } else {
        int fd = mkstemp(o->tmp);
        if (fd >= 0) {
            pending_add(o->tmp);
            /* mkstemp makes 0600; give the file the mode the old one had, or the mode open(2)
             * would (0666 & ~umask) */
            mode_t um = umask(0);
            umask(um);
            fchmod(fd, exists ? st.st_mode & 07777 : 0666 & ~um);
            o->f = fdopen(fd, "wb");
            if (!o->f) {
                close(fd);
                unlink(o->tmp);
                pending_remove(o->tmp);
            }
        }
    }
    if (!o->f) {
        int err_no = errno ? errno : EIO;
        file_out_abort(o);
        return err_set(e, "%s: cannot create: %s", file_quote(path, q, sizeof q),
                       strerror(err_no));
    }
    errno = 0; /* so commit can tell the errno of a failed write from an older one */
    return 0;
}

static void out_free(struct file_out *o)
{
    free(o->tmp);
    free(o->path);
    memset(o, 0, sizeof *o);
}

int file_out_commit(struct file_out *o, struct err *e)
{
    char q[FILE_QUOTE_SIZE];
    file_quote(o->path ? o->path : "", q, sizeof q);
    int err_no = errno; /* set by a failed fwrite since file_out_open, else 0 */
    int bad = ferror(o->f);
    if (fflush(o->f) != 0) {
        bad = 1;
        err_no = errno;
    }
    if (fclose(o->f) != 0 && !bad) {
        bad = 1;
        err_no = errno;
    }
    o->f = NULL;
    if (!bad && o->tmp && rename(o->tmp, o->path) != 0) {
        bad = 1;
        err_no = errno;
    }
    if (o->tmp && bad)
        unlink(o->tmp);
    if (o->tmp)
        pending_remove(o->tmp);
    if (bad) {
        out_free(o);
        return err_set(e, "%s: write failed: %s", q, strerror(err_no ? err_no : EIO));
    }
    out_free(o);
    return 0;
}

void file_out_abort(struct file_out *o)
{
    if (o->f)
        fclose(o->f);
    if (o->tmp && o->f)
        unlink(o->tmp);
    if (o->tmp)
        pending_remove(o->tmp);
    o->f = NULL;
    out_free(o);
}
