/* lod_cache.c: the chain of a large mesh kept on disk (lod.h, "The cache"): a file per mesh
 * content, read instead of simplifying again. */
#include "lod_cache.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <meshoptimizer.h>

#include "file.h"

#define CACHE_MAGIC "rastty-lod-chain"
#define CACHE_VERSION 1u

/* the file: a header, then per level its error, shading error, triangle count and its
 * triangles as indices into the source mesh's vertices */
struct cache_head {
    char magic[16];
    uint32_t version, n_levels;
    uint64_t key;
    uint32_t n_verts, n_tris;
};
struct cache_level {
    double error, shade;
    uint32_t n_tris, pad;
};

/* 64-bit FNV-1a over 8-byte words (the tail byte by byte) */
static uint64_t mix(uint64_t h, const void *p, size_t n)
{
    const unsigned char *b = p;
    size_t i = 0;
    for (; i + 8 <= n; i += 8) {
        uint64_t w;
        memcpy(&w, b + i, 8);
        h = (h ^ w) * 0x100000001b3ull;
    }
    for (; i < n; i++)
        h = (h ^ b[i]) * 0x100000001b3ull;
    return h;
}

uint64_t lod_cache_key(const struct mesh *m, const double *rules, int n_rules)
{
    /* what makes the chain: the geometry, the materials' seams, the rules and the library */
    const uint32_t ours[] = {CACHE_VERSION, MESHOPTIMIZER_VERSION, m->n_verts, m->n_tris,
                             m->colors != NULL};
    uint64_t h = 0xcbf29ce484222325ull;
    h = mix(h, ours, sizeof ours);
    h = mix(h, rules, (size_t)n_rules * sizeof *rules);
    h = mix(h, m->verts, (size_t)m->n_verts * sizeof *m->verts);
    h = mix(h, m->vert_material, (size_t)m->n_verts * sizeof *m->vert_material);
    if (m->colors)
        h = mix(h, m->colors, (size_t)m->n_verts * sizeof *m->colors);
    return mix(h, m->tris, (size_t)m->n_tris * sizeof *m->tris);
}

/* the folder: $RASTTY_CACHE_DIR (empty: no cache), else $XDG_CACHE_HOME/rastty, else
 * $HOME/.cache/rastty; NULL when there is none */
static int cache_dir(char *out, size_t size)
{
    const char *d = getenv("RASTTY_CACHE_DIR"), *x, *home;
    int n;
    if (d)
        n = *d ? snprintf(out, size, "%s", d) : -1;
    else if ((x = getenv("XDG_CACHE_HOME")) && *x == '/')
        n = snprintf(out, size, "%s/rastty", x);
    else if ((home = getenv("HOME")) && *home == '/')
        n = snprintf(out, size, "%s/.cache/rastty", home);
    else
        n = -1;
    return n > 0 && (size_t)n < size ? 0 : -1;
}

/* the folder (dir: 4096 bytes) and, in it, the file of key */
static int cache_path(char *dir, uint64_t key, char *out, size_t size)
{
    if (cache_dir(dir, 4096))
        return -1;
    int n = snprintf(out, size, "%s/lod-%016llx.bin", dir, (unsigned long long)key);
    return n > 0 && (size_t)n < size ? 0 : -1;
}

bool lod_cache_enabled(void)
{
    char dir[4096];
    return cache_dir(dir, sizeof dir) == 0;
}

int lod_cache_read(const struct mesh *m, uint64_t key, struct lod_cached *out)
{
    memset(out, 0, sizeof *out);
    char dir[4096], path[4200];
    if (cache_path(dir, key, path, sizeof path))
        return -1;
    char *buf;
    size_t len;
    if (file_read(path, FILE_MAX_MODEL, &buf, &len))
        return -1;
    /* every field checked: a file from another version, cut short or damaged is ignored */
    struct cache_head h;
    int rc = -1;
    size_t at = sizeof h;
    if (len < sizeof h)
        goto done;
    memcpy(&h, buf, sizeof h);
    if (memcmp(h.magic, CACHE_MAGIC, sizeof h.magic) || h.version != CACHE_VERSION ||
        h.key != key || h.n_verts != m->n_verts || h.n_tris != m->n_tris ||
        h.n_levels < 1 || h.n_levels > LOD_CACHE_LEVELS)
        goto done;
    uint32_t prev = m->n_tris;
    double prev_error = 0;
    for (uint32_t k = 0; k < h.n_levels; k++) {
        struct cache_level lv;
        if (len - at < sizeof lv)
            goto done;
        memcpy(&lv, buf + at, sizeof lv);
        at += sizeof lv;
        if (!(lv.n_tris >= 1 && lv.n_tris < prev) || !isfinite(lv.error) ||
            !(lv.error >= prev_error) || !isfinite(lv.shade) || !(lv.shade >= 0) ||
            (len - at) / (3 * sizeof(uint32_t)) < lv.n_tris)
            goto done;
        size_t bytes = (size_t)lv.n_tris * 3 * sizeof(uint32_t);
        uint32_t *idx = malloc(bytes);
        if (!idx)
            goto done;
        memcpy(idx, buf + at, bytes);
        at += bytes;
        for (size_t i = 0; i < (size_t)lv.n_tris * 3; i++)
            if (idx[i] >= m->n_verts) {
                free(idx);
                goto done;
            }
        out->idx[k] = idx;
        out->n_tris[k] = lv.n_tris;
        out->error[k] = lv.error;
        out->shade[k] = lv.shade;
        out->n_levels = (int)k + 1;
        prev = lv.n_tris;
        prev_error = lv.error;
    }
    rc = at == len ? 0 : -1;
done:
    free(buf);
    if (rc)
        lod_cached_free(out);
    else
        utimensat(AT_FDCWD, path, NULL, 0); /* used now: the last to go (evict) */
    return rc;
}

void lod_cached_free(struct lod_cached *c)
{
    for (int k = 0; k < LOD_CACHE_LEVELS; k++)
        free(c->idx[k]);
    memset(c, 0, sizeof *c);
}

/* mkdir -p, each new folder private (0700) */
static int make_dirs(char *dir)
{
    for (char *p = dir + 1; *p; p++)
        if (*p == '/') {
            *p = 0;
            int bad = mkdir(dir, 0700) && errno != EEXIST;
            *p = '/';
            if (bad)
                return -1;
        }
    return mkdir(dir, 0700) && errno != EEXIST ? -1 : 0;
}

static bool put(FILE *f, const void *p, size_t n)
{
    return fwrite(p, 1, n, f) == n;
}

/* the folder's size limit in bytes: $RASTTY_CACHE_MAX_MB, else LOD_CACHE_MAX_MB */
static uint64_t cache_max(void)
{
    const char *v = getenv("RASTTY_CACHE_MAX_MB");
    char *end;
    unsigned long long mb = v && *v ? strtoull(v, &end, 10) : LOD_CACHE_MAX_MB;
    if (v && *v && *end)
        mb = LOD_CACHE_MAX_MB;
    return (uint64_t)mb << 20;
}

struct entry {
    struct timespec used;
    uint64_t size;
    char name[32];
};

static int older(const void *a, const void *b)
{
    const struct entry *x = a, *y = b;
    if (x->used.tv_sec != y->used.tv_sec)
        return x->used.tv_sec < y->used.tv_sec ? -1 : 1;
    return (x->used.tv_nsec > y->used.tv_nsec) - (x->used.tv_nsec < y->used.tv_nsec);
}

/* Past the limit, the files used least recently go (by their times: written, or last read),
 * keep's (the one just written) last of all. Only lod-*.bin files are touched. */
static void evict(const char *dir, const char *keep)
{
    DIR *d = opendir(dir);
    if (!d)
        return;
    struct entry *e = NULL;
    size_t n = 0, cap = 0;
    uint64_t total = 0;
    for (struct dirent *de; (de = readdir(d));) {
        size_t l = strlen(de->d_name);
        if (l >= sizeof e->name || l < 8 || strncmp(de->d_name, "lod-", 4) ||
            strcmp(de->d_name + l - 4, ".bin"))
            continue;
        struct stat st;
        if (fstatat(dirfd(d), de->d_name, &st, AT_SYMLINK_NOFOLLOW) || !S_ISREG(st.st_mode))
            continue;
        if (n == cap) {
            struct entry *g = realloc(e, (cap = cap ? 2 * cap : 64) * sizeof *e);
            if (!g)
                break;
            e = g;
        }
        e[n].used = st.st_mtim;
        e[n].size = (uint64_t)st.st_size;
        memcpy(e[n].name, de->d_name, l + 1);
        if (strcmp(e[n].name, keep) == 0)
            e[n].used.tv_sec = INT64_MAX; /* (never before the others) */
        total += e[n].size;
        n++;
    }
    const uint64_t max = cache_max();
    if (total > max && e) {
        qsort(e, n, sizeof *e, older);
        for (size_t i = 0; i < n && total > max; i++)
            if (strcmp(e[i].name, keep) && unlinkat(dirfd(d), e[i].name, 0) == 0)
                total -= e[i].size;
    }
    free(e);
    closedir(d);
}

int lod_cache_write(const struct mesh *m, uint64_t key, const struct lod_cached *c)
{
    char dir[4096], path[4200], tmp[4300];
    if (c->n_levels < 1 || cache_path(dir, key, path, sizeof path) || make_dirs(dir))
        return -1;
    /* beside the target and renamed over it when whole: a reader never sees half a file,
     * and two writers of the same mesh leave one of their (equal) files */
    int n = snprintf(tmp, sizeof tmp, "%s/.lod-%016llx.XXXXXX", dir, (unsigned long long)key);
    if (n < 0 || (size_t)n >= sizeof tmp)
        return -1;
    int fd = mkstemp(tmp);
    if (fd < 0)
        return -1;
    FILE *f = fdopen(fd, "wb");
    if (!f) {
        close(fd);
        unlink(tmp);
        return -1;
    }
    struct cache_head h = {.version = CACHE_VERSION, .n_levels = (uint32_t)c->n_levels,
                           .key = key, .n_verts = m->n_verts, .n_tris = m->n_tris};
    memcpy(h.magic, CACHE_MAGIC, sizeof h.magic);
    bool ok = put(f, &h, sizeof h);
    for (int k = 0; ok && k < c->n_levels; k++) {
        struct cache_level lv = {.error = c->error[k], .shade = c->shade[k],
                                 .n_tris = c->n_tris[k]};
        ok = put(f, &lv, sizeof lv) &&
             put(f, c->idx[k], (size_t)c->n_tris[k] * 3 * sizeof *c->idx[k]);
    }
    ok = fclose(f) == 0 && ok;
    if (!ok || rename(tmp, path)) {
        unlink(tmp);
        return -1;
    }
    evict(dir, path + strlen(dir) + 1);
    return 0;
}
