/* file.h: every file rastty reads or writes goes through here.
 *
 * Reading: only regular files. The file is opened with O_NONBLOCK (so even opening a FIFO
 * cannot block), checked with fstat, and a FIFO, device, socket or directory is refused
 * before a byte is read: `mtllib /dev/zero` or a FIFO named by `map_Kd` is an error, not an
 * endless read. The size is checked against the caller's limit before anything is
 * allocated, and the read stops one byte past the limit should the file grow meanwhile.
 * The limits (FILE_MAX_*) are documented in rastty(1) under LIMITS.
 *
 * Writing: output goes to a temporary file beside the target (".NAME.XXXXXX" in the same
 * directory, so rename(2) is atomic) and is renamed over the target only when every byte
 * was written, flushed and closed without error. On failure (a full disk, a closed pipe is
 * not possible for files) the old target is untouched and the temporary file removed.
 *
 * Errors: file_read returns 0 or an error code (an errno value, or one of FILE_E_*);
 * file_strerror turns either into words. Writers fill a struct err naming the path
 * (quoted: never raw bytes). */
#ifndef RASTTY_FILE_H
#define RASTTY_FILE_H

#include <stddef.h>
#include <stdio.h>

#include "err.h"

/* size limits for inputs (bytes) */
#define FILE_MAX_MODEL ((size_t)2 << 30)   /* OBJ, STL, PLY, glTF, ...: 2 GiB */
#define FILE_MAX_TEXT ((size_t)64 << 20)   /* MTL libraries, scene files, camera paths */
#define FILE_MAX_IMAGE ((size_t)256 << 20) /* texture files */
#define FILE_MAX_ANSI ((size_t)1 << 30)    /* ansi2ppm input */

enum {
    FILE_E_FIFO = -1001,  /* a FIFO (named pipe) */
    FILE_E_DEVICE = -1002, /* a character or block device */
    FILE_E_SOCKET = -1003,
    FILE_E_OTHER = -1004, /* some other kind of file that is not a regular file */
    FILE_E_TOO_BIG = -1005,
    FILE_E_TTY = -1006,   /* file_read_stdin: standard input is a terminal, nothing piped */
};

/* Read the whole regular file into a malloc'd buffer (NUL-terminated; *len_out excludes
 * the NUL). Returns 0, or an error code with *buf_out = NULL: errno values (ENOENT,
 * EISDIR, ENOMEM, ...) or FILE_E_* above (FILE_E_TOO_BIG beyond max bytes). */
int file_read(const char *path, size_t max, char **buf_out, size_t *len_out);
/* Standard input to its end (a pipe or a redirected file; `-` as a model name), the same
 * contract; FILE_E_TTY when it is a terminal (nothing piped in: never wait for typing). */
int file_read_stdin(size_t max, char **buf_out, size_t *len_out);
/* Words for a file_read code: strerror, or "a FIFO, not a regular file" and the like. */
const char *file_strerror(int code);

/* An output file being written atomically. */
struct file_out {
    FILE *f;         /* write here */
    char *tmp;       /* the temporary file's path */
    char *path;      /* the target */
};
/* Create the temporary file beside path. */
int file_out_open(struct file_out *o, const char *path, struct err *e);
/* Flush, fsync-free close and rename over the target; on any error the temporary file is
 * removed, the target untouched, and e says "PATH: write failed: reason". Always frees o. */
int file_out_commit(struct file_out *o, struct err *e);
/* Give up: remove the temporary file, free o. Harmless on a zeroed or finished o. */
void file_out_abort(struct file_out *o);
/* For commands that write files (not the viewer, whose handlers only set flags): SIGINT,
 * SIGTERM, SIGHUP and SIGQUIT remove the temporary files being written, then end the process
 * as the signal would; SIGXFSZ is ignored, so a write past `ulimit -f` fails with a message.
 * A symbolic link given as the target is written through (the link stays), an existing
 * target keeps its mode, and a name too long for ".NAME.XXXXXX" gets ".rastty.XXXXXX". */
void file_out_cleanup_on_signals(void);

/* Does path lie in the folder tree of the file `of` (its directory or below)? Both are
 * resolved first (realpath: symbolic links followed, so a link inside that points out is
 * outside). 1 inside, 0 outside, or an errno value > 1 when path cannot be resolved (it
 * does not exist). How a model's references are confined (a glTF's buffers and images). */
int file_inside_dir_of(const char *of, const char *path);

/* A path for messages: printable ASCII, at most 160 bytes ("..." after). */
const char *file_quote(const char *path, char *buf, size_t size);
#define FILE_QUOTE_SIZE 170

#endif
