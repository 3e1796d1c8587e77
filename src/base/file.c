/* file.c: regular-file reads with size limits, atomic writes (see file.h). */
#include "file.h"

#include <errno.h>
#include <fcntl.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

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
    size_t cap = (size_t)st.st_size + 2; /* the NUL, and one byte to see EOF at once */
    char *buf = malloc(cap);
    if (!buf) {
        close(fd);
        return ENOMEM;
    }
    size_t len = 0;
    int rc = 0;
    for (;;) {
        if (len + 1 >= cap) { /* the file grew since fstat */
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
            buf = nb;
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
    close(fd);
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

const char *file_strerror(int code)
{
    switch (code) {
    case FILE_E_FIFO: return "a FIFO, not a regular file";
    case FILE_E_DEVICE: return "a device, not a regular file";
    case FILE_E_SOCKET: return "a socket, not a regular file";
    case FILE_E_OTHER: return "not a regular file";
    case FILE_E_TOO_BIG: return "file too large";
    case EISDIR: return "a directory, not a file";
    default: return strerror(code);
    }
}

/* ---- atomic writes ---- */

int file_out_open(struct file_out *o, const char *path, struct err *e)
{
    memset(o, 0, sizeof *o);
    char q[FILE_QUOTE_SIZE];
    const char *slash = strrchr(path, '/');
    size_t dir = slash ? (size_t)(slash - path) + 1 : 0;
    size_t n = strlen(path);
    o->path = strdup(path);
    o->tmp = malloc(n + 16);
    if (!o->path || !o->tmp) {
        file_out_abort(o);
        return err_set(e, "%s: out of memory", file_quote(path, q, sizeof q));
    }
    /* ".NAME.XXXXXX" in the target's directory: same file system, so rename is atomic */
    memcpy(o->tmp, path, dir);
    o->tmp[dir] = '.';
    memcpy(o->tmp + dir + 1, path + dir, n - dir);
    memcpy(o->tmp + n + 1, ".XXXXXX", 8);
    struct stat st;
    if (stat(path, &st) == 0 && !S_ISREG(st.st_mode)) {
        /* /dev/null, a FIFO, a terminal: write to it directly, nothing to replace */
        free(o->tmp);
        o->tmp = NULL;
        if (S_ISDIR(st.st_mode)) {
            file_out_abort(o);
            return err_set(e, "%s: cannot create: %s", file_quote(path, q, sizeof q),
                           strerror(EISDIR));
        }
        o->f = fopen(path, "wb");
    } else {
        int fd = mkstemp(o->tmp);
        if (fd >= 0) {
            /* mkstemp makes 0600; give the file the mode open(2) would (0666 & ~umask) */
            mode_t um = umask(0);
            umask(um);
            fchmod(fd, 0666 & ~um);
            o->f = fdopen(fd, "wb");
            if (!o->f) {
                close(fd);
                unlink(o->tmp);
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
    if (bad) {
        if (o->tmp)
            unlink(o->tmp);
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
    o->f = NULL;
    out_free(o);
}
