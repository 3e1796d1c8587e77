/* outputs.c: outputs that are inputs or each other are refused (see outputs.h). */
#include "outputs.h"

#include <stdbool.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

#include "file.h"

struct ident {
    bool known, exists;
    dev_t dev;
    ino_t ino;
    char base[256]; /* a file not there yet: its name in the folder dev/ino */
};

static struct ident ident_of(const char *path)
{
    struct ident id = {0};
    struct stat st;
    if (stat(path, &st) == 0) {
        id.known = id.exists = true;
        id.dev = st.st_dev;
        id.ino = st.st_ino;
        return id;
    }
    char dir[4096];
    const char *slash = strrchr(path, '/');
    const char *base = slash ? slash + 1 : path;
    if (strlen(base) >= sizeof id.base || (slash && (size_t)(slash - path) >= sizeof dir))
        return id;
    if (!slash)
        snprintf(dir, sizeof dir, ".");
    else if (slash == path)
        snprintf(dir, sizeof dir, "/");
    else
        snprintf(dir, sizeof dir, "%.*s", (int)(slash - path), path);
    if (stat(dir, &st) != 0)
        return id; /* the write fails later, with its own message */
    id.known = true;
    id.dev = st.st_dev;
    id.ino = st.st_ino;
    snprintf(id.base, sizeof id.base, "%s", base);
    return id;
}

static bool same(const struct ident *a, const struct ident *b)
{
    return a->known && b->known && a->exists == b->exists && a->dev == b->dev &&
           a->ino == b->ino && strcmp(a->base, b->base) == 0;
}

struct named {
    const char *what, *path;
};

/* The first of list[0 .. n) that names the file a does (standard output, "-", names none):
 * its index, or -1. */
static int first_same(const struct ident *a, const struct named *list, int n)
{
    for (int k = 0; k < n; k++) {
        if (!list[k].path || strcmp(list[k].path, "-") == 0)
            continue;
        struct ident b = ident_of(list[k].path);
        if (same(a, &b))
            return k;
    }
    return -1;
}

int outputs_check(const struct options *o, struct err *e)
{
    struct named out[] = {{"--out", o->out}, {"--depth-out", o->depth_out},
                          {"--csv", o->csv}, {"--svg", o->svg}};
    struct named in[OPTIONS_MAX_INPUTS + 2];
    int n_in = 0;
    for (int i = 0; i < o->n_inputs; i++)
        in[n_in++] = (struct named){o->cmd == CMD_ANSI2PPM ? "the input" : "the model",
                                    o->inputs[i]};
    in[n_in++] = (struct named){"the --texture", o->texture};
    in[n_in++] = (struct named){"the --camera-path", o->camera_path};
    int n_out = (int)(sizeof out / sizeof out[0]);
    for (int i = 0; i < n_out; i++) {
        if (!out[i].path || strcmp(out[i].path, "-") == 0)
            continue;
        struct ident a = ident_of(out[i].path);
        char q1[FILE_QUOTE_SIZE], q2[FILE_QUOTE_SIZE];
        int k = first_same(&a, in, n_in);
        if (k >= 0)
            return err_set(e, "rastty: %s %s is the same file as %s %s: refusing to write "
                              "over an input",
                           out[i].what, file_quote(out[i].path, q1, sizeof q1), in[k].what,
                           file_quote(in[k].path, q2, sizeof q2));
        k = first_same(&a, out, i);
        if (k >= 0)
            return err_set(e, "rastty: %s %s and %s %s are the same file: each output "
                              "needs its own",
                           out[k].what, file_quote(out[k].path, q2, sizeof q2), out[i].what,
                           file_quote(out[i].path, q1, sizeof q1));
    }
    return 0;
}
