/* lod_cache.h: the chain of levels of detail kept on disk between runs (lod.h, "The
 * cache"), so that opening a large model again does not simplify it again.
 *
 * One file per mesh content: $RASTTY_CACHE_DIR (set and empty: no cache), else
 * $XDG_CACHE_HOME/rastty, else $HOME/.cache/rastty; named lod-KEY.bin, KEY a 64-bit hash
 * of what makes the chain (the vertices, their materials and colours, the triangles, the
 * chain's rules and the meshoptimizer version). It holds each level's error, shading error
 * and triangles as indices into the mesh's own vertices: lod.c makes each level from them
 * as it made it from the simplifier's output (the same vertices in the same order, the same
 * bytes drawn). Written whole beside its name and renamed over it; read with every field
 * checked (version, key, counts, errors in order, every index inside the mesh), and
 * ignored when any is wrong: the chain is then built and the file written again. */
#ifndef RASTTY_LOD_CACHE_H
#define RASTTY_LOD_CACHE_H

#include <stdbool.h>
#include <stdint.h>

#include "mesh.h"

/* The folder's limit: past it, writing a file removes the files used least recently (by
 * their times: a read marks a file used). $RASTTY_CACHE_MAX_MB sets another. */
#define LOD_CACHE_MAX_MB 1024

/* the most levels a file holds (lod.h's LOD_MAX_LEVELS: lod.c checks) */
#define LOD_CACHE_LEVELS 8

/* the levels, as the file holds them */
struct lod_cached {
    int n_levels;
    uint32_t *idx[LOD_CACHE_LEVELS]; /* level k's triangles, 3 * n_tris[k] source vertices */
    uint32_t n_tris[LOD_CACHE_LEVELS];
    double error[LOD_CACHE_LEVELS], shade[LOD_CACHE_LEVELS];
};

/* Is there a cache folder to use? */
bool lod_cache_enabled(void);
/* The key of m's chain made by rules (the caller's numbers that shape the chain: they go
 * into the key; O(size of the mesh)). */
uint64_t lod_cache_key(const struct mesh *m, const double *rules, int n_rules);
/* 0 and out filled (free it with lod_cached_free), or -1: no usable file. */
int lod_cache_read(const struct mesh *m, uint64_t key, struct lod_cached *out);
/* 0 written, -1 not (no folder, a full disk: the cache is only ever a shortcut). */
int lod_cache_write(const struct mesh *m, uint64_t key, const struct lod_cached *c);
void lod_cached_free(struct lod_cached *c);

#endif
